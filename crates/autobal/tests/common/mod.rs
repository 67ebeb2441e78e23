//! Helpers shared by the integration tests.

// Each test file compiles this module on its own and uses only some of it.
#![allow(dead_code)]

use autobal::balls::BallPhysics;
use autobal::planar::PlanarRotor;
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};

/// SplitMix64: a tiny seeded generator, so failures reproduce.
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

/// A Python interpreter that can import `modules`: `$AUTOBAL_PYTHON`, the repository's `.venv`
/// (made by scripts/test.sh), or `python3`. Without one the cross-check is skipped with a
/// message, unless `AUTOBAL_REQUIRE_PYTHON` is set (scripts/test.sh sets it), where it fails.
pub fn python_with(modules: &[&str]) -> Option<String> {
    let venv = format!("{}/../../.venv/bin/python", env!("CARGO_MANIFEST_DIR"));
    let candidates = std::env::var("AUTOBAL_PYTHON").into_iter().chain([venv, "python3".to_string()]);
    let import = format!("import {}", modules.join(", "));
    for py in candidates {
        if std::process::Command::new(&py).args(["-c", &import]).output().is_ok_and(|o| o.status.success()) {
            return Some(py);
        }
    }
    let msg = format!(
        "this cross-check needs Python with {}: run scripts/test.sh (it creates .venv with them), or set AUTOBAL_PYTHON to a python that has them",
        modules.join(", ")
    );
    assert!(std::env::var_os("AUTOBAL_REQUIRE_PYTHON").is_none(), "{msg}");
    eprintln!("skipped: {msg}");
    None
}

/// Paper 004's planar rotor `p` (balancer centred: `s2 = 0`, no housing mass `m2`) as the spatial
/// rotor with its tilt locked on one support, its two balls given `physics`: the disk (mass
/// `m1`, eccentricity `s1`) becomes a rotor mass `m1 − m_u` on the axis plus an unbalance mass
/// `m_u` at radius `s1 m1/m_u` (the same mass and first moment), with the same polar moment about
/// the axis (`I_G + m1 s1² = C_r + m_u R_u²`).
pub fn planar_as_spatial(p: &PlanarRotor, physics: BallPhysics) -> SpatialRotor {
    assert!(p.s2 == 0.0 && p.m2 == 0.0, "the spatial rotor's balancer is centred and has no housing of its own");
    let mu = 0.1;
    let ru = p.s1 * p.m1 / mu;
    let rotor = SpatialRotor {
        rotor: RigidRotor {
            mass: p.m1 - mu,
            equatorial_moment: 0.01,
            polar_moment: p.i_g + p.m1 * p.s1 * p.s1 - mu * ru * ru,
            z: 0.0,
            axis_tilt: 0.0,
            axis_tilt_angle: 0.0,
        },
        supports: vec![Support { z: 0.0, stiffness: [p.k; 2], damping: [p.c; 2] }],
        unbalances: vec![PointMass { mass: mu, radius: ru, angle: 0.0, z: 0.0 }],
        planes: vec![BallPlane { z: 0.0, n: 2, ball_mass: p.m3, race_radius: p.r, drag: p.c_psi / (p.r * p.r), physics }],
        gravity: [0.0; 3],
        spin_drag: 0.0,
        lock_tilt: true,
    };
    assert!(rotor.rotor.polar_moment > 0.0);
    rotor
}

/// A random one-plane spatial rotor of papers 000/003 with two balls (the model and its
/// nonlinear equations), rejected and redrawn until both build: unbalance `m0` 0.005-0.04 at
/// `r0` 0.5-2.5, capacity `E = n m r / (m0 r0)` in `capacity`, `C̄Σ` 0.3-1.6, `ρ̄s` 0.25-0.6,
/// `l̄_L` 0.2-1.3, `z̄_A` ±1, support damping `h_x` and ball drag `h_s` in the given ranges.
pub fn random_spatial_model(
    rng: &mut Rng,
    method: autobal::spatial::inertia::AnisotropyMethod,
    capacity: (f64, f64),
    h_x: (f64, f64),
    h_s: (f64, f64),
) -> (autobal::spatial::params::SpatialModel, SpatialRotor) {
    use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
    loop {
        let m0 = rng.range(0.005, 0.04);
        let r0 = rng.range(0.5, 2.5);
        let e = rng.range(capacity.0, capacity.1);
        let r = rng.range(0.5, 2.5);
        let m = e * m0 * r0 / r;
        let inp = DimensionlessInput {
            c_sigma: rng.range(0.3, 1.6),
            rho_s: rng.range(0.25, 0.6),
            l_left: rng.range(0.2, 1.3),
            z_a: rng.range(-1.0, 1.0),
            anisotropy: AnisotropyInput::Masses { masses: MassSet { m0, r0, m, r, n: 2 }, d_a: None },
            h_x: rng.range(h_x.0, h_x.1),
            h_s: rng.range(h_s.0, h_s.1),
            method,
            direct_balls: None,
        };
        let Ok(model) = SpatialModel::from_dimensionless(&inp) else { continue };
        if let Ok(rotor) = SpatialRotor::from_dimensionless(&model) {
            return (model, rotor);
        }
    }
}

/// Greatest distance from a member of `a` to the member of `b` paired with it (closest first).
pub fn match_distance(a: &[num_complex::Complex64], b: &[num_complex::Complex64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut used = vec![false; b.len()];
    let mut worst: f64 = 0.0;
    for x in a {
        let (k, d) = b.iter().enumerate().filter(|(k, _)| !used[*k]).map(|(k, y)| (k, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
        used[k] = true;
        worst = worst.max(d);
    }
    worst
}

/// Every eigenvalue (or Floquet multiplier) of `st`, the structural ones included.
pub fn all_eigenvalues(st: &autobal::analysis::Stability) -> Vec<num_complex::Complex64> {
    st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).collect()
}

/// The multipliers over one revolution `T = 2π/Ω`: `exp(λ T)` of an equilibrium's eigenvalues,
/// `μ^(T/τ)` of an orbit of period `τ` (the native spatial model's unequal supports have
/// `2π/Ω`, the linear rotor's `π/Ω`).
pub fn per_revolution(st: &autobal::analysis::Stability, t: f64) -> Vec<num_complex::Complex64> {
    match st.period {
        None => all_eigenvalues(st).iter().map(|l| (l * t).exp()).collect(),
        Some(p) => all_eigenvalues(st).iter().map(|m| m.powi((t / p).round() as i32)).collect(),
    }
}

/// One case for tests/planar_linearisation.py: the planar rotor `p` at speed `omega` in state `x`.
pub fn planar_case(p: &PlanarRotor, omega: f64, x: &[f64]) -> serde_json::Value {
    serde_json::json!({
        "p": {"m1": p.m1, "m2": p.m2, "m3": p.m3, "n": p.n, "s1": p.s1, "s2": p.s2, "gamma": p.gamma, "r": p.r, "k": p.k, "c": p.c, "c_psi": p.c_psi},
        "omega": omega,
        "x": x,
    })
}

/// The independent SymPy/numpy linearisation of each case ([`planar_case`],
/// tests/planar_linearisation.py): (eigenvalues, right-hand side).
pub fn sympy_linearisation(python: &str, cases: &[serde_json::Value]) -> Vec<(Vec<num_complex::Complex64>, Vec<f64>)> {
    let script = format!("{}/tests/planar_linearisation.py", env!("CARGO_MANIFEST_DIR"));
    let mut child =
        std::process::Command::new(python).arg(script).stdin(std::process::Stdio::piped()).stdout(std::process::Stdio::piped()).spawn().expect("python runs");
    use std::io::Write;
    child.stdin.take().unwrap().write_all(serde_json::to_string(cases).unwrap().as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    v.iter()
        .map(|c| {
            let l = c["eigenvalues"].as_array().unwrap().iter().map(|e| num_complex::Complex64::new(e[0].as_f64().unwrap(), e[1].as_f64().unwrap())).collect();
            let f = c["rhs"].as_array().unwrap().iter().map(|e| e.as_f64().unwrap()).collect();
            (l, f)
        })
        .collect()
}

/// A random rotor with everything the spatial model has: tilted principal axis, static and
/// couple unbalance, two ball planes (`balls[0]` and `balls[1]` balls), anisotropic supports,
/// gravity off the axes.
pub fn general_rotor(rng: &mut Rng, balls: [usize; 2]) -> SpatialRotor {
    SpatialRotor {
        rotor: RigidRotor {
            mass: rng.range(1.0, 5.0),
            equatorial_moment: rng.range(0.1, 0.5),
            polar_moment: rng.range(0.05, 0.4),
            z: rng.range(-0.2, 0.2),
            axis_tilt: rng.range(-0.2, 0.2),
            axis_tilt_angle: rng.range(-3.0, 3.0),
        },
        supports: vec![
            Support {
                z: rng.range(-0.8, -0.4),
                stiffness: [rng.range(50.0, 200.0), rng.range(50.0, 200.0)],
                damping: [rng.range(0.0, 3.0), rng.range(0.0, 3.0)],
            },
            Support {
                z: rng.range(0.4, 0.8),
                stiffness: [rng.range(50.0, 200.0), rng.range(50.0, 200.0)],
                damping: [rng.range(0.0, 3.0), rng.range(0.0, 3.0)],
            },
        ],
        unbalances: vec![
            PointMass { mass: rng.range(0.01, 0.2), radius: rng.range(0.05, 0.3), angle: rng.range(-3.0, 3.0), z: rng.range(-0.5, 0.5) },
            PointMass { mass: rng.range(0.01, 0.2), radius: rng.range(0.05, 0.3), angle: rng.range(-3.0, 3.0), z: rng.range(-0.5, 0.5) },
        ],
        planes: vec![
            BallPlane {
                z: rng.range(0.1, 0.5),
                n: balls[0],
                ball_mass: rng.range(0.01, 0.1),
                race_radius: rng.range(0.1, 0.3),
                drag: rng.range(0.0, 0.5),
                physics: Default::default(),
            },
            BallPlane {
                z: rng.range(-0.5, -0.1),
                n: balls[1],
                ball_mass: rng.range(0.01, 0.1),
                race_radius: rng.range(0.1, 0.3),
                drag: rng.range(0.0, 0.5),
                physics: Default::default(),
            },
        ],
        gravity: [rng.range(-3.0, 3.0), rng.range(-10.0, 10.0), rng.range(-3.0, 3.0)],
        spin_drag: rng.range(0.0, 0.05),
        lock_tilt: false,
    }
}

/// A random full state of a spatial rotor with `nc` coordinates, far from balance (tilts up to
/// 0.4 rad, none with `lock_tilt`; balls anywhere).
pub fn random_state(rng: &mut Rng, nc: usize, lock_tilt: bool) -> Vec<f64> {
    let mut y: Vec<f64> = (0..2 * nc).map(|_| rng.range(-1.0, 1.0)).collect();
    for i in [0, 1, nc, nc + 1] {
        y[i] *= 0.05;
    }
    for i in [2, 3] {
        y[i] *= if lock_tilt { 0.0 } else { 0.4 };
        y[nc + i] *= if lock_tilt { 0.0 } else { 3.0 };
    }
    y[4] = rng.range(-3.0, 3.0);
    y[nc + 4] = rng.range(-30.0, 30.0);
    for i in 5..nc {
        y[i] *= 3.0;
        y[nc + i] *= 5.0;
    }
    y
}

/// Paper 000's dimensionless model with the anisotropy `ΔĀ` given directly (exact method) and,
/// optionally, the balls' `(m̄, d_A)`.
#[allow(clippy::too_many_arguments)]
pub fn direct_model(
    c_sigma: f64,
    rho: f64,
    l: f64,
    z: f64,
    delta_a: f64,
    h_x: f64,
    h_s: f64,
    balls: Option<(f64, f64)>,
) -> autobal::spatial::params::SpatialModel {
    use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
    SpatialModel::from_dimensionless(&DimensionlessInput {
        c_sigma,
        rho_s: rho,
        l_left: l,
        z_a: z,
        anisotropy: AnisotropyInput::Direct(delta_a),
        h_x,
        h_s,
        method: autobal::spatial::inertia::AnisotropyMethod::Exact,
        direct_balls: balls,
    })
    .unwrap()
}

/// `x(t)` and the monodromy `Φ(t)` from `x0` by the full variational equations `n + n²`
/// (DOP853 at rtol 1e-13, absolute tolerances `1e-13` of each component's scale and
/// `1e-13 S_a / S_b` for `Φ_ab`): the reference of the Floquet tests, no symmetry or
/// interpolation used. Returns the state `n + n²` at `t` (`[..n]` the orbit, `[n..]` `Φ`).
pub fn full_variational_flow<F: autobal::analysis::VectorField>(f: &F, x0: &[f64], t: f64) -> Vec<f64> {
    use autobal::ode::{Control, Method, Options, Solver};
    let n = f.dim();
    let sys = autobal::analysis::VariationalSystem::new(f);
    let mut y = vec![0.0; n + n * n];
    y[..n].copy_from_slice(x0);
    for a in 0..n {
        y[n + a * n + a] = 1.0;
    }
    let sc = f.scales();
    let mut atol: Vec<f64> = sc.iter().map(|v| 1e-13 * v).collect();
    for a in 0..n {
        for b in 0..n {
            atol.push(1e-13 * sc[a] / sc[b]);
        }
    }
    let mut solver = Solver::new(&sys, Options::new(1e-13, 1e-13).method(Method::Dop853).atol_per_component(atol)).unwrap();
    assert!(solver.integrate(0.0, &mut y, t, |_| Control::Continue).status.is_completed());
    y
}

/// The spatial rotor with its tilt locked on one support (a Jeffcott rotor in turning axes):
/// mass `M_r` = 10 kg plus an unbalance mass 0.01 kg at radius 0.1 m, supports `k_x, k_y`,
/// damping 40 N s/m, two balls of 0.02 kg on a race of radius 0.1 m with drag `h_A` = 0.5
/// (force `h_A R ψ̇`), gravity `(g_x, g_y)` across the axis (tests/linear_rotor_gravity.rs,
/// tests/state_kind_orbits.rs).
pub fn locked_tilt_jeffcott(k: [f64; 2], g: [f64; 2]) -> SpatialRotor {
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.0, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
        supports: vec![Support { z: 0.0, stiffness: k, damping: [40.0, 40.0] }],
        unbalances: vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.3, z: 0.0 }],
        planes: vec![BallPlane { z: 0.0, n: 2, ball_mass: 0.02, race_radius: 0.1, drag: 0.5, physics: Default::default() }],
        gravity: [g[0], g[1], 0.0],
        spin_drag: 0.0,
        lock_tilt: true,
    }
}

/// A vector field ([`autobal::analysis::VectorField`]: a planar, spatial or linear rotor's
/// field) as an [`autobal::ode::System`], to integrate it in time with the crate's integrators:
/// its `dim` and `rhs`, the Jacobian the integrator's default.
pub struct Sys<'a, F: ?Sized>(pub &'a F);

impl<F: autobal::analysis::VectorField + ?Sized> autobal::ode::System for Sys<'_, F> {
    fn dim(&self) -> usize {
        autobal::analysis::VectorField::dim(self.0)
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        autobal::analysis::VectorField::rhs(self.0, t, y, dy)
    }
}

/// The model of examples/dimensional.toml (an anisotropic rotor: two balls at their balanced
/// positions, supports that differ left and right), without its run's tables.
pub fn dimensional_model() -> autobal::spatial::params::SpatialModel {
    let mut root = autobal::config::parse(include_str!("../../../../examples/dimensional.toml"), "test").unwrap();
    for t in ["drive", "initial"] {
        root.remove(t);
    }
    autobal::config::spatial_simulation(&root).unwrap().config.model
}

/// `n` speeds `w (k + ½)/n`: the grid of `autobal campbell --omega-max w --points n`.
pub fn campbell_grid(w: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| w * (k as f64 + 0.5) / n as f64).collect()
}

// The Campbell crossing comparisons of campbell_grid_14.rs and campbell_modes_15.rs.

/// A crossing as compared: speed, kind (forward/backward), harmonic, mode number.
pub type Key = (f64, char, u32, usize);

pub fn keys(ks: &[autobal::spatial::campbell::CriticalSpeed]) -> Vec<Key> {
    ks.iter().map(|k| (k.omega, if k.whirl == autobal::spatial::stability::Whirl::Forward { 'f' } else { 'b' }, k.harmonic, k.mode)).collect()
}

pub fn show(v: &[Key]) -> String {
    v.iter().map(|k| format!("{:.6}{}{}m{}", k.0, k.1, k.2, k.3)).collect::<Vec<_>>().join(" ")
}

/// The crossings of `got` and `reference` in `[lo, hi]` the same: speeds to 1e-6 relative (both
/// are bisected to 1e-13 on the same spectrum; 1e-6 is the refinement's resolution, far above
/// that and far below the 4e-5 of the narrowest pair), the same kind, harmonic and mode number.
pub fn same(got: &[Key], reference: &[Key], lo: f64, hi: f64, what: &str) {
    let within = |v: &[Key]| -> Vec<Key> { v.iter().copied().filter(|k| k.0 >= lo && k.0 <= hi).collect() };
    let (a, b) = (within(got), within(reference));
    let ok = a.len() == b.len() && a.iter().zip(&b).all(|(x, y)| (x.0 - y.0).abs() <= 1e-6 * y.0.max(1.0) && (x.1, x.2, x.3) == (y.1, y.2, y.3));
    assert!(ok, "{what} over [{lo}, {hi}]:\n got {}\n ref {}", show(&a), show(&b));
}

/// Rodrigues et al.'s two-plane rotor of the independent check
/// (bench/independent/check_spatial_two_plane.py): a symmetric rotor, the static unbalance split between the two ball
/// planes, a couple, two balls of 0.97 m_c per plane (m_c = m_u e / (4 R) = 6.25 g).
pub const RODRIGUES_097: &str = r#"
[rotor]
mass = 10.0
equatorial_moment = 0.16
polar_moment = 0.08
z = 0.2
[supports]
z_left = 0.0
z_right = 0.4
stiffness_left = 500000.0
stiffness_right = 500000.0
damping_left = 100.0
damping_right = 100.0
[unbalance]
mass = 0.01
radius = 0.1
angle = 0.0
[couple]
mass = 0.01
radius = 0.1
angle = 0.0
z = 0.08
[balancer]
z = 0.32
balls = 2
ball_mass = 0.0060625
race_radius = 0.08
drag = 0.3
[balancer2]
z = 0.08
balls = 2
ball_mass = 0.0060625
race_radius = 0.08
drag = 0.3
"#;
