//! Nonlinear spatial dynamics (papers 000/003 in time): the equations against an independent
//! symbolic Lagrangian derivation, their linearisation against the 12-state linear model,
//! energy and power balance, the planar limit, and what the time simulation shows about the
//! stability verdicts of the linear analysis.

use autobal::drive::Drive;
use autobal::ode::System;
use autobal::spatial::dynamics::{BallPlane, Equations, PointMass, RigidRotor, SpatialRotor, Support};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, Pencil};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
use serde_json::json;

mod common;
use common::{general_rotor, planar_as_spatial, python_with, random_state, Rng};

/// The case as the SymPy script reads it (axial positions relative to the reference point).
fn case_json(r: &SpatialRotor, eq: &Equations, y: &[f64], t: f64) -> serde_json::Value {
    let zr = eq.z_reference();
    let nc = eq.coords();
    let mut qd = y[nc..].to_vec();
    qd[4] = eq.spin_rate(t, y);
    let balls: Vec<_> =
        r.planes.iter().flat_map(|p| (0..p.n).map(move |_| json!({"mass": p.ball_mass, "radius": p.race_radius, "zeta": p.z - zr, "drag": p.drag}))).collect();
    json!({
        "rotor": {"mass": r.rotor.mass, "a": r.rotor.equatorial_moment, "c": r.rotor.polar_moment, "zeta": r.rotor.z - zr,
                  "kappa": r.rotor.axis_tilt, "beta": r.rotor.axis_tilt_angle},
        "gravity": r.gravity, "spin_drag": r.spin_drag,
        "unbalances": r.unbalances.iter().map(|u| json!({"mass": u.mass, "radius": u.radius, "angle": u.angle, "zeta": u.z - zr})).collect::<Vec<_>>(),
        "balls": balls,
        "supports": r.supports.iter().map(|s| json!({"zeta": s.z - zr, "kx": s.stiffness[0], "ky": s.stiffness[1], "cx": s.damping[0], "cy": s.damping[1]})).collect::<Vec<_>>(),
        "q": y[..nc].to_vec(), "qd": qd,
        "lock_tilt": r.lock_tilt, "prescribed": eq.drive.prescribed(),
        "torque": eq.drive.torque(t, qd[4]) , "phi_dd": eq.drive.kinematics(t).1,
    })
}

#[test]
fn equations_equal_an_independent_symbolic_lagrangian_derivation() {
    // SymPy derives Lagrange's equations from positions in fixed axes and the rotor's angular
    // velocity from Qᵀ Q̇ (tests/spatial_lagrange.py); we derive ours by d'Alembert's principle
    // in the turning frame. Random rotors with every feature, random states far from balance
    // (tilts up to 0.4 rad, balls anywhere), free spin under torque, prescribed spin, tilt
    // locked. Agreement to 1e-9 relative: both are exact, only round-off separates them.
    let Some(python) = python_with(&["sympy", "numpy"]) else { return };
    let mut rng = Rng(7);
    let mut cases = vec![];
    let mut ours = vec![];
    for i in 0..24 {
        let mut r = general_rotor(&mut rng, [2, 1]);
        let kind = i % 3;
        r.lock_tilt = kind == 2;
        let drive = if kind == 0 {
            Drive::Torque { omega0: 0.0, torque: rng.range(-5.0, 5.0), t_off: None }
        } else {
            Drive::Acceleration { omega0: rng.range(-20.0, 20.0), b: rng.range(-10.0, 10.0) }
        };
        let eq = Equations::new(&r, &drive);
        let y = random_state(&mut rng, eq.coords(), r.lock_tilt);
        let t = rng.range(0.0, 1.0);
        let mut dy = vec![0.0; eq.dim()];
        eq.rhs(t, &y, &mut dy);
        cases.push(case_json(&r, &eq, &y, t));
        ours.push(dy[eq.coords()..].to_vec());
    }
    let script = format!("{}/tests/spatial_lagrange.py", env!("CARGO_MANIFEST_DIR"));
    let mut child =
        std::process::Command::new(python).arg(script).stdin(std::process::Stdio::piped()).stdout(std::process::Stdio::piped()).spawn().expect("python runs");
    use std::io::Write;
    child.stdin.take().unwrap().write_all(serde_json::to_string(&cases).unwrap().as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let theirs: Vec<Vec<f64>> = serde_json::from_slice(&out.stdout).unwrap();
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        let scale = b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!((x - y).abs() <= 1e-9 * scale, "case {k}, q̈[{i}]: ours {x}, SymPy {y} (scale {scale})");
        }
    }
}

/// A random dimensionless model with masses (two balls) and the speed, retried until the
/// rotor exists (positive A_r, C_r).
fn random_model(rng: &mut Rng, method: AnisotropyMethod, capacity: (f64, f64)) -> (SpatialModel, SpatialRotor) {
    common::random_spatial_model(rng, method, capacity, (0.0, 0.2), (0.01, 0.5))
}

/// Put unbalance and balls at balance in the composite's principal frame (the linear model's
/// frame): the unbalance at `−ψ`, `ψ = ½ arg(Ā_m0 + Ā_m D)`, the balls at `−ψ + π ± acos(1/E)`.
fn at_balance(model: &SpatialModel, rotor: &mut SpatialRotor) -> Vec<f64> {
    let ms = model.masses.unwrap();
    let e = ms.capacity();
    let d = 2.0 / (e * e) - 1.0; // D = cos 2β for two balls at π ± β
    let z = ms.a_m0() + ms.a_m() * d;
    let psi = if z < 0.0 { std::f64::consts::FRAC_PI_2 } else { 0.0 };
    rotor.unbalances[0].angle = -psi;
    let beta = (1.0 / e).acos();
    vec![-psi + std::f64::consts::PI - beta, -psi + std::f64::consts::PI + beta]
}

/// Finite-difference Jacobian of the nonlinear equations at the balanced state, in the linear
/// model's 12 states `(ξ, η, δ, θ, s_ξ, s_η)` and rates: ball angles mapped to the total unbalance
/// `s = m0 R0 e^{iβ0} + m R Σ e^{iψ_j}` by `δs = T δψ`, `T = m R [−sin ψ_j; cos ψ_j]`.
fn jacobian_in_linear_coordinates(rotor: &SpatialRotor, psi: &[f64], omega: f64) -> [[f64; 12]; 12] {
    let drive = Drive::Speed { omega0: omega };
    let eq = Equations::new(rotor, &drive);
    let nc = eq.coords();
    let mut y = vec![0.0; 2 * nc];
    y[5] = psi[0];
    y[6] = psi[1];
    y[nc + 4] = omega;
    let idx = [0, 1, 2, 3, 5, 6, nc, nc + 1, nc + 2, nc + 3, nc + 5, nc + 6];
    let mut jac = [[0.0; 12]; 12];
    let h = 1e-6;
    for (c, &ic) in idx.iter().enumerate() {
        let (mut yp, mut ym) = (y.clone(), y.clone());
        yp[ic] += h;
        ym[ic] -= h;
        let (mut fp, mut fm) = (vec![0.0; 2 * nc], vec![0.0; 2 * nc]);
        eq.rhs(0.0, &yp, &mut fp);
        eq.rhs(0.0, &ym, &mut fm);
        for (r, &ir) in idx.iter().enumerate() {
            jac[r][c] = (fp[ir] - fm[ir]) / (2.0 * h);
        }
    }
    // similarity with P = diag(I4, T, I4, T)
    let b = &rotor.planes[0];
    let mr = b.ball_mass * b.race_radius;
    let t = [[-mr * psi[0].sin(), -mr * psi[1].sin()], [mr * psi[0].cos(), mr * psi[1].cos()]];
    let det = t[0][0] * t[1][1] - t[0][1] * t[1][0];
    let ti = [[t[1][1] / det, -t[0][1] / det], [-t[1][0] / det, t[0][0] / det]];
    let mut p = [[0.0; 12]; 12];
    let mut pi = [[0.0; 12]; 12];
    for blk in [0, 6] {
        for i in 0..4 {
            p[blk + i][blk + i] = 1.0;
            pi[blk + i][blk + i] = 1.0;
        }
        for i in 0..2 {
            for j in 0..2 {
                p[blk + 4 + i][blk + 4 + j] = t[i][j];
                pi[blk + 4 + i][blk + 4 + j] = ti[i][j];
            }
        }
    }
    let mul = |a: &[[f64; 12]; 12], b: &[[f64; 12]; 12]| {
        let mut r = [[0.0; 12]; 12];
        for i in 0..12 {
            for j in 0..12 {
                r[i][j] = (0..12).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        r
    };
    mul(&mul(&p, &jac), &pi)
}

fn max_difference(a: &[[f64; 12]; 12], model: &SpatialModel, omega: f64) -> (f64, f64) {
    let lin = Pencil::new(model, omega, Balls::Free).unwrap().state_matrix();
    let (mut diff, mut scale) = (0.0f64, 0.0f64);
    for i in 0..12 {
        for j in 0..12 {
            diff = diff.max((a[i][j] - lin[i][j]).abs());
            scale = scale.max(lin[i][j].abs());
        }
    }
    (diff, scale)
}

#[test]
fn jacobian_at_balance_equals_the_linear_model_exact_anisotropy() {
    // (a) of issue 7 §3: random rotors, capacities on both sides of √2 (where eq (17) and the
    // exact tensor part), both signs of z̄_A and c̄yα. Central differences with h = 1e-6 are
    // exact to ~1e-9 here (third derivatives O(1), round-off 1e-16/1e-6).
    let mut rng = Rng(3);
    for _ in 0..20 {
        let (model, mut rotor) = random_model(&mut rng, AnisotropyMethod::Exact, (1.02, 3.0));
        let psi = at_balance(&model, &mut rotor);
        let omega = rng.range(0.1, 4.0);
        let jac = jacobian_in_linear_coordinates(&rotor, &psi, omega);
        let (d, s) = max_difference(&jac, &model, omega);
        assert!(d <= 1e-7 * s, "Ω = {omega}: max |J − A| = {d:e} (scale {s}), model {model:?}");
    }
}

#[test]
fn jacobian_at_balance_equals_the_linear_model_paper_anisotropy_where_it_holds() {
    // With anisotropy = "paper" (eq (17), d_A = diag(1 ∓ D_A)) the linear model is the
    // linearisation of the physics only while the balls' principal axes line up with the
    // unbalance's (two balls: E ≤ √2); beyond, eq (17) adds anisotropies that cancel and the
    // Jacobian departs from it (docs/notes/papers.md), which this test also pins.
    let mut rng = Rng(5);
    for _ in 0..12 {
        let (model, mut rotor) = random_model(&mut rng, AnisotropyMethod::Paper, (1.02, 1.40));
        let psi = at_balance(&model, &mut rotor);
        let omega = rng.range(0.1, 4.0);
        let (d, s) = max_difference(&jacobian_in_linear_coordinates(&rotor, &psi, omega), &model, omega);
        assert!(d <= 1e-7 * s, "Ω = {omega}: max |J − A| = {d:e} (scale {s})");
    }
    for _ in 0..6 {
        let (model, mut rotor) = random_model(&mut rng, AnisotropyMethod::Paper, (1.6, 3.0));
        let psi = at_balance(&model, &mut rotor);
        let omega = rng.range(1.0, 4.0);
        let (d, s) = max_difference(&jacobian_in_linear_coordinates(&rotor, &psi, omega), &model, omega);
        assert!(d > 1e-4 * s, "eq (17) should not be the linearisation at E > √2: {d:e}");
    }
}

#[test]
fn dimensional_jacobian_scales_to_the_dimensionless_linear_model() {
    // An SI rotor: the Jacobian in SI, scaled by w̄ = w/ρ_s, χ̄ = χ, s̄ = s/(M_s ρ_s), τ = ω0 t,
    // equals the dimensionless linear model of the same rotor (000, eqs (8)-(10)): the
    // dimensionless config is this model in the units M_s = 1, ω0 = 1, ρ_s = 1.
    let mut rng = Rng(11);
    for _ in 0..6 {
        // drawn in this order: mass, A_r, C_r, z_G, z_A, c_L, c_R, h_L, h_R, m0, R0, m, R, h_A
        let rigid = RigidRotor::aligned(rng.range(5.0, 40.0), rng.range(0.2, 1.0), rng.range(0.05, 0.6), rng.range(0.15, 0.35));
        let z_balancer = rng.range(0.0, 0.6);
        let (stiffness_left, stiffness_right) = (rng.range(1e6, 4e6), rng.range(1e6, 4e6));
        let (damping_left, damping_right) = (rng.range(0.0, 800.0), rng.range(0.0, 800.0));
        let unbalance = PointMass { mass: rng.range(0.005, 0.05), radius: rng.range(0.05, 0.15), angle: 0.0, z: z_balancer };
        let plane = BallPlane::point_masses(z_balancer, 2, rng.range(0.01, 0.05), rng.range(0.08, 0.15), rng.range(0.1, 2.0));
        let supports = vec![Support::isotropic(0.0, stiffness_left, damping_left), Support::isotropic(0.5, stiffness_right, damping_right)];
        let mut rotor = SpatialRotor::new(rigid, supports, vec![unbalance], vec![plane]);
        let model = rotor.to_dimensionless(AnisotropyMethod::Exact).unwrap();
        let Some(ms) = model.masses else { unreachable!() };
        if ms.capacity() < 1.0 {
            continue;
        }
        let psi = at_balance(&model, &mut rotor);
        let sc = model.scale.unwrap();
        let omega = rng.range(0.2, 4.0);
        let jac = jacobian_in_linear_coordinates(&rotor, &psi, omega * sc.omega0);
        let dq = [1.0 / sc.rho_s, 1.0 / sc.rho_s, 1.0, 1.0, 1.0 / (sc.total_mass * sc.rho_s), 1.0 / (sc.total_mass * sc.rho_s)];
        let s: Vec<f64> = (0..12).map(|i| if i < 6 { dq[i] } else { dq[i - 6] / sc.omega0 }).collect();
        let mut a = [[0.0; 12]; 12];
        for i in 0..12 {
            for j in 0..12 {
                a[i][j] = s[i] * jac[i][j] / s[j] / sc.omega0;
            }
        }
        let (d, scale) = max_difference(&a, &model, omega);
        assert!(d <= 1e-6 * scale, "max |J − A| = {d:e} (scale {scale})");
    }
}

#[test]
fn power_balance_at_random_states() {
    // dE/dt along the equations = drive power − dissipated power, at random states of rotors
    // with every feature (free spin under torque). E is differentiated along the flow by
    // central differences: E(y + h f) − E(y − h f) over 2h, exact to O(h²).
    let mut rng = Rng(17);
    for _ in 0..50 {
        let r = general_rotor(&mut rng, [2, 1]);
        let torque = rng.range(-5.0, 5.0);
        let drive = Drive::Torque { omega0: 0.0, torque, t_off: None };
        let eq = Equations::new(&r, &drive);
        let y = random_state(&mut rng, eq.coords(), false);
        let mut f = vec![0.0; eq.dim()];
        eq.rhs(0.0, &y, &mut f);
        let h = 1e-6;
        let yp: Vec<f64> = y.iter().zip(&f).map(|(a, b)| a + h * b).collect();
        let ym: Vec<f64> = y.iter().zip(&f).map(|(a, b)| a - h * b).collect();
        let de = (eq.energy(0.0, &yp) - eq.energy(0.0, &ym)) / (2.0 * h);
        let phi_d = y[eq.coords() + 4];
        let expected = torque * phi_d - eq.dissipated_power(0.0, &y);
        let scale = eq.dissipated_power(0.0, &y) + (torque * phi_d).abs() + 1.0;
        assert!((de - expected).abs() <= 1e-6 * scale, "dE/dt = {de}, expected {expected}");
    }
}

// ---------------------------------------------------------------------------------------------
// In time

use autobal::spatial::dynamics::{simulate, Initial, Settings};
use autobal::spatial::stability::margin;

/// Paper 000's base case (examples/default.toml) at a given l̄_L.
fn base_case(l_left: f64) -> (SpatialModel, SpatialRotor) {
    let model = SpatialModel::from_dimensionless(&DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left,
        z_a: 0.8,
        anisotropy: AnisotropyInput::Masses { masses: MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 }, d_a: None },
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: None,
    })
    .unwrap();
    let rotor = SpatialRotor::from_dimensionless(&model).unwrap();
    (model, rotor)
}

fn settings(t_end: f64, dt: f64) -> Settings {
    Settings { method: Default::default(), t_end, dt, rtol: 1e-10, atol: 1e-12 }
}

/// Samples `(t, |s|)` of the residual static unbalance of a run.
fn residual_history(rotor: &SpatialRotor, drive: &Drive, init: &Initial, t_end: f64, dt: f64) -> (Vec<(f64, f64)>, autobal::spatial::dynamics::Summary) {
    let eqs = Equations::new(rotor, drive);
    let mut out = vec![];
    let s = simulate(rotor, drive, init, &settings(t_end, dt), |x| {
        let mut y = vec![0.0; eqs.dim()];
        y[5..5 + x.psi.len()].copy_from_slice(&x.psi);
        let (st, _) = eqs.residual_unbalance(&y);
        out.push((x.t, st[0].hypot(st[1])));
        true
    })
    .unwrap();
    assert!(s.stopped.is_none(), "{:?}", s.stopped);
    (out, s)
}

/// Least-squares slope of ln v over the samples with `lo < v < hi`, taking the largest value
/// in each window of `window` time units (the envelope of an oscillating decay).
fn envelope_rate(h: &[(f64, f64)], lo: f64, hi: f64, window: f64) -> f64 {
    let mut pts = vec![];
    let mut i = 0;
    while i < h.len() {
        let t0 = h[i].0;
        let mut best = h[i];
        while i < h.len() && h[i].0 < t0 + window {
            if h[i].1 > best.1 {
                best = h[i];
            }
            i += 1;
        }
        if best.1 > lo && best.1 < hi {
            pts.push((best.0, best.1.ln()));
        }
    }
    assert!(pts.len() >= 8, "too few points in the fit window: {}", pts.len());
    let n = pts.len() as f64;
    let (st, sv) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mt, mv) = (st / n, sv / n);
    let num: f64 = pts.iter().map(|p| (p.0 - mt) * (p.1 - mv)).sum();
    let den: f64 = pts.iter().map(|p| (p.0 - mt).powi(2)).sum();
    num / den
}

#[test]
fn inside_the_exactly_stable_range_the_balls_balance_at_the_least_damped_rate() {
    // (b) of issue 7 §3: 000's base case, l̄_L = 0.8, Ω = 1.6 (exactly stable 1.4122-1.7071).
    // Balls started 1 rad (57°) off their balancing positions converge; the residual unbalance decays
    // at the rate of the least-damped eigenvalue of the 12-state model, measured on the
    // envelope over 1e-3..1e-8 of the initial unbalance (the linear regime): within 1 % (measured: 0.014 %).
    let (model, rotor) = base_case(0.8);
    let omega = 1.6;
    let rate = margin(&model, omega, Balls::Free).unwrap();
    assert!(rate < 0.0);
    let drive = Drive::Speed { omega0: omega };
    let mut init = Initial::at_rest(&rotor);
    let beta = (1.0f64 / 2.0).acos();
    init.psi = vec![std::f64::consts::PI - beta + 1.0, std::f64::consts::PI + beta + 1.0];
    let t_end = 25.0 / -rate;
    let (h, s) = residual_history(&rotor, &drive, &init, t_end, 0.25);
    assert!(s.balanced, "{s:?}");
    let s0 = 0.025 * 2.0;
    let measured = envelope_rate(&h, 1e-8 * s0, 1e-3 * s0, 4.0 * std::f64::consts::PI);
    assert!((measured - rate).abs() <= 0.01 * rate.abs(), "measured decay {measured}, least-damped eigenvalue {rate}");
}

#[test]
fn in_the_upper_range_of_003_the_balanced_state_is_left() {
    // (c) of issue 7 §3: l̄_L = 0.8, Ω = 4.0 lies in 003's upper range (Ω > Ω_K4 = 3.80), where
    // the exact analysis finds the balanced state unstable. Balls started 1e-7 rad from balance
    // drift away at the rate of the unstable eigenvalue (within 1 %; measured 0.15 %) and the
    // run does not end balanced.
    let (model, rotor) = base_case(0.8);
    let omega = 4.0;
    let rate = margin(&model, omega, Balls::Free).unwrap();
    assert!(rate > 0.0, "the exact analysis calls Ω = 4 unstable");
    let drive = Drive::Speed { omega0: omega };
    let mut init = Initial::at_rest(&rotor);
    let beta = (1.0f64 / 2.0).acos();
    init.psi = vec![std::f64::consts::PI - beta + 1e-7, std::f64::consts::PI + beta];
    let t_end = 30.0 / rate;
    let (h, s) = residual_history(&rotor, &drive, &init, t_end, 0.02);
    let s0 = 0.025 * 2.0;
    let measured = envelope_rate(&h, 1e-5 * s0, 1e-2 * s0, std::f64::consts::PI / omega);
    assert!((measured - rate).abs() <= 0.01 * rate, "measured growth {measured}, unstable eigenvalue {rate}");
    assert!(!s.balanced && s.residual_unbalance > 0.05, "{s:?}");
}

#[test]
fn with_the_tilt_locked_it_is_the_planar_rotor_of_paper_004() {
    // (d) of issue 7 §3: tilt locked, one support: the planar Jeffcott rotor with balls. Paper
    // 004's rotor with the balancer centred (s2 = 0) as the spatial rotor (`planar_as_spatial`).
    // Run-up through resonance and a torque-driven run: both models agree to the integration
    // tolerance.
    use autobal::planar::{self, PlanarRotor};
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    p.m2 = 0.0;
    let rotor = planar_as_spatial(&p, Default::default());
    for drive in [Drive::Acceleration { omega0: 200.0, b: 100.0 }, Drive::Torque { omega0: 200.0, torque: 5.0, t_off: None }] {
        let t_end = 2.0;
        let dt = 0.01;
        let mut ours = vec![];
        let init = Initial::at_rest(&rotor);
        simulate(&rotor, &drive, &init, &settings(t_end, dt), |s| {
            ours.push((s.omega, s.x, s.y, s.psi.clone()));
            true
        })
        .unwrap();
        let ps = planar::Settings {
            method: planar::Method::Dop853,
            t_end,
            dt,
            rtol: 1e-10,
            atol: 1e-12,
            psi0: init.psi.clone(),
            psi_rate0: vec![0.0; 2],
            ..planar::Settings::new(&p, t_end)
        };
        let mut theirs = vec![];
        planar::simulate(&p, &drive, &ps, |s| {
            theirs.push((s.omega, s.x, s.y, s.psi.clone()));
            true
        })
        .unwrap();
        assert_eq!(ours.len(), theirs.len());
        let peak = theirs.iter().map(|s| s.1.hypot(s.2)).fold(0.0, f64::max);
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((a.0 - b.0).abs() <= 1e-7 * b.0.abs(), "speed {} vs {}", a.0, b.0);
            assert!((a.1 - b.1).abs() <= 1e-6 * peak && (a.2 - b.2).abs() <= 1e-6 * peak, "x, y: {a:?} vs {b:?}");
            for j in 0..2 {
                assert!((a.3[j] - b.3[j]).abs() <= 1e-6, "ψ: {a:?} vs {b:?}");
            }
        }
    }
}

#[test]
fn energy_is_conserved_without_damping_or_drive() {
    // (e) of issue 7 §3: free spin, no damping, no torque, every feature on (tilted axis,
    // couple unbalance, two planes, anisotropic supports, gravity): T + V stays constant along
    // a run of many whirl periods to the integration tolerance (1e-8 relative to T at rtol
    // 1e-11).
    let mut rng = Rng(23);
    for _ in 0..3 {
        let mut r = general_rotor(&mut rng, [2, 1]);
        for s in r.supports.iter_mut() {
            s.damping = [0.0; 2];
        }
        for p in r.planes.iter_mut() {
            p.drag = 0.0;
        }
        r.spin_drag = 0.0;
        let drive = Drive::Torque { omega0: 30.0, torque: 0.0, t_off: None };
        let eq = Equations::new(&r, &drive);
        let mut init = Initial::at_rest(&r);
        init.position = [0.01, -0.02];
        init.tilt = [0.05, -0.03];
        init.psi_rate = vec![3.0, -2.0, 1.0];
        let y0 = autobal::spatial::dynamics::simulate::initial_state(&eq, &init).unwrap();
        let e0 = eq.energy(0.0, &y0[..eq.dim()]);
        let st = Settings { method: Default::default(), t_end: 20.0, dt: 20.0, rtol: 1e-11, atol: 1e-13 };
        let mut worst = 0.0f64;
        let opts = autobal::spatial::dynamics::simulate::tolerances(&eq, &st).method(autobal::ode::Method::Dop853);
        let mut solver = autobal::ode::Solver::new(&eq, opts).unwrap();
        let mut y1 = y0.clone();
        let out = solver.integrate(0.0, &mut y1, 20.0, |s| {
            worst = worst.max((eq.energy(s.t_new, s.y_new) - e0).abs());
            autobal::ode::Control::Continue
        });
        assert!(out.status.is_completed() && out.t == 20.0);
        assert!(y1[eq.coords() + 4].abs() > 1.0);
        assert!(worst <= 1e-8 * e0.abs(), "energy drift {worst:e} of {e0}");
    }
}

#[test]
fn stationary_whirl_of_the_symmetric_rotor_is_the_jeffcott_closed_form() {
    // Symmetric layout (l̄_L = 0.5) with plane A through C (z̄_A = 0): translation decouples from
    // tilt and the locked rotor with its balls at the unbalance side is a Jeffcott rotor with
    // unbalance U = m0 R0 + m R Σ cos ψ_j: |w| = U Ω² / sqrt((1 − Ω²)² + (h̄x Ω)²) (units
    // M_s = ω0 = 1). Newton on the nonlinear equations, continued across the critical speed.
    use autobal::spatial::dynamics::stationary::response_curve;
    let model = SpatialModel::from_dimensionless(&DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left: 0.5,
        z_a: 0.0,
        anisotropy: AnisotropyInput::Masses { masses: MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 }, d_a: None },
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: None,
    })
    .unwrap();
    let rotor = SpatialRotor::from_dimensionless(&model).unwrap();
    let psi = [0.3f64, -0.5];
    let u = 0.025 * 2.0 + 0.025 * 2.0 * (psi[0].cos() + psi[1].cos());
    let v = 0.025 * 2.0 * (psi[0].sin() + psi[1].sin());
    let omegas: Vec<f64> = (1..=80).map(|i| 0.05 * i as f64).collect();
    for (w, s) in omegas.iter().zip(response_curve(&rotor, &psi, &omegas)) {
        let s = s.expect("converges");
        let exact = u.hypot(v) * w * w / ((1.0 - w * w).powi(2) + (0.05 * w).powi(2)).sqrt();
        assert!((s.amplitude_planes[0] - exact).abs() <= 1e-6 * exact, "Ω = {w}: {} vs {exact}", s.amplitude_planes[0]);
    }
}

// Analyses only a time simulation gives (issue 7 §4)

use autobal::spatial::critical_speeds::critical_speeds_at;
use autobal::spatial::dynamics::stationary::{locked_rotor, response_curve};
use autobal::spatial::inertia::{exact_anisotropy_of, BallSet};

/// Samples `(Ω, whirl radius at the balancer plane)` of a run.
fn radius_vs_speed(rotor: &SpatialRotor, drive: &Drive, init: &Initial, set: &Settings) -> (Vec<(f64, f64)>, autobal::spatial::dynamics::Summary) {
    let mut out = vec![];
    let s = simulate(rotor, drive, init, set, |x| {
        out.push((x.omega, x.amplitude_planes[0]));
        true
    })
    .unwrap();
    assert!(s.stopped.is_none(), "{:?}", s.stopped);
    (out, s)
}

#[test]
fn run_up_through_the_split_critical_speeds_follows_the_locked_ball_curve() {
    // §4(b). 000's base case with its two balls held 57° off balance (turned into fixed
    // masses): together with the unbalance they make the rotor's inertia anisotropic,
    // ΔĀ = |½Ā_m0 + ½Ā_m (1/n) Σ e^{2iψ}| = 0.084, and the angular critical speed 2.965 of the
    // balanced rotor splits in two (eq (16) at that ΔĀ). Three routes meet:
    // - the stationary response curve (Newton on the nonlinear equations, no integration) has
    //   its two maxima at the split transverse critical speeds of the linear analysis
    //   (0.838, 0.848; within 1 %); the split angular ones (2.580, 3.618), damped more
    //   strongly, merge into one maximum between them;
    // - a run-up at constant acceleration (1000 revolutions from rest to Ω = 4.2) follows that
    //   curve below the first critical speed and between the transverse and the angular ones
    //   (Ω in 0.4-0.7 and 1.3-1.9: within 5 %, the rest of the passage's free vibration;
    //   measured 3.9 %);
    // - at the transverse critical speeds it peaks later and lower than the stationary curve
    //   (the classic passage result). Near the angular ones the run-up rises far above this
    //   curve (docs/notes/spatial.md): not asserted;
    // - under constant torques: captured below the pair (small torques) or through it so fast
    //   that the whirl stays far below the curve (below).
    let (model, rotor) = base_case(0.8);
    let psi = [3.0944, 5.1888];
    let locked = locked_rotor(&rotor, &psi);
    let set = BallSet { n: 2, a_m0: 0.025 * 4.0, a_m: 0.05 * 4.0, capacity: 2.0 };
    let da = exact_anisotropy_of(&set, &psi);
    let closed = 0.5
        * (num_complex::Complex64::new(set.a_m0, 0.0)
            + set.a_m / 2.0 * psi.iter().map(|a| num_complex::Complex64::from_polar(1.0, 2.0 * a)).sum::<num_complex::Complex64>())
        .norm();
    assert!((da - closed).abs() < 1e-12 && (da * 1e3).round() == 84.0, "ΔĀ of the held balls {da} vs {closed}");
    let crit: Vec<f64> = critical_speeds_at(&model, da).into_iter().map(|c| c.0).collect();
    let angular: Vec<f64> = crit.iter().copied().filter(|w| *w > 1.5).collect();
    assert_eq!(angular.len(), 2, "split angular critical speeds {crit:?}");
    assert!(angular[1] - angular[0] > 0.5 && crit[1] - crit[0] > 0.005, "{crit:?}");
    // damped (h̄x = 0.05), the stationary curve keeps a maximum at each split transverse
    // critical speed (within 1 %); the angular ones, damped more strongly, merge into one
    let ws: Vec<f64> = (0..=1400).map(|i| 0.3 + 3.9 * i as f64 / 1400.0).collect();
    let curve: Vec<f64> = response_curve(&rotor, &psi, &ws).into_iter().map(|w| w.expect("steady whirl").amplitude_planes[0]).collect();
    let maxima: Vec<(f64, f64)> = (1..ws.len() - 1).filter(|&i| curve[i] > curve[i - 1] && curve[i] >= curve[i + 1]).map(|i| (ws[i], curve[i])).collect();
    for w in &crit[..2] {
        assert!(maxima.iter().any(|m| (m.0 - w).abs() <= 0.01 * w), "no stationary maximum near the critical speed {w}: {maxima:?}");
    }
    let angular_peak = maxima.iter().filter(|m| m.0 > 1.5).fold((0.0, 0.0), |a, m| if m.1 > a.1 { *m } else { a });
    assert!(angular_peak.0 > angular[0] && angular_peak.0 < angular[1], "{maxima:?}");
    let stationary_at = |w: f64| -> f64 {
        let i = ((w - 0.3) / 3.9 * 1400.0).clamp(0.0, 1399.0) as usize;
        let f = (w - ws[i]) / (ws[i + 1] - ws[i]);
        curve[i] + f * (curve[i + 1] - curve[i])
    };
    // relative to the whirl, or to a tenth of the curve's peak near the antiresonance
    let scale = curve.iter().fold(0.0f64, |m, v| m.max(*v));
    let away = |w: f64| (0.4..0.7).contains(&w) || (1.3..1.9).contains(&w);
    let omega_end = 4.2;
    let b = omega_end * omega_end / (4.0 * std::f64::consts::PI * 1000.0);
    let t_end = omega_end / b;
    let init = Initial::at_rest(&locked);
    let polar = {
        // the rotor's polar moment about the axis, with the held balls and the unbalance
        let r = &locked;
        r.rotor.polar_moment + r.unbalances.iter().map(|u| u.mass * u.radius * u.radius).sum::<f64>()
    };
    // under the torque that would give the same acceleration without whirl, T = C b, and
    // under ten times that, the resonance captures the drive below the first critical speed
    // (the Sommerfeld effect: the support dampers take c Ω² a² ≈ 0.03 of power at a whirl of
    // 1 ρ_s, more than T Ω); T = 0.1 passes the transverse pair (below)
    let captured = Drive::Torque { omega0: 0.0, torque: polar * b, t_off: None };
    let set = Settings { method: Default::default(), t_end, dt: 0.5, rtol: 1e-8, atol: 1e-10 };
    let (_, s) = radius_vs_speed(&locked, &captured, &init, &set);
    assert!(s.final_omega < crit[0], "T = C b: captured below Ω_K1, ends at Ω = {}", s.final_omega);
    let captured = Drive::Torque { omega0: 0.0, torque: 10.0 * polar * b, t_off: None };
    let (_, s) = radius_vs_speed(&locked, &captured, &init, &set);
    assert!(s.final_omega < crit[1], "T = 10 C b: captured below Ω_K2, ends at Ω = {}", s.final_omega);
    let w = crit[0];
    let near = |p: &(f64, f64)| (p.0 - w).abs() <= 0.12 * w;
    let peak_of = |v: &mut dyn Iterator<Item = (f64, f64)>| v.fold((0.0, 0.0), |m, p| if p.1 > m.1 { p } else { m });
    let st_peak = peak_of(&mut maxima.iter().copied().filter(near));
    // the run-up at constant acceleration (speed monotonic): within 5 % of the curve away from
    // the critical speeds (measured 3.9 %), and its peak at the transverse pair later and lower
    // (measured 1.45 at Ω = 0.90 against 2.09 at 0.835)
    let (run, s) = radius_vs_speed(&locked, &Drive::Acceleration { omega0: 0.0, b }, &init, &set);
    assert!(s.final_omega > 4.0, "the run-up reaches Ω = {}", s.final_omega);
    let worst = run.iter().filter(|p| away(p.0)).map(|&(w, a)| (a - stationary_at(w)).abs() / stationary_at(w).max(0.1 * scale)).fold(0.0, f64::max);
    assert!(worst <= 0.05, "away from the critical speeds the run-up departs {worst} from the stationary curve");
    let run_peak = peak_of(&mut run.iter().copied().filter(near));
    assert!(run_peak.0 > st_peak.0 && run_peak.1 < st_peak.1, "run-up at Ω_K = {w}: run peak {run_peak:?}, stationary {st_peak:?}");
    // T = 0.1 crosses the transverse pair in about one τ (Ω 0.80 → 0.93): the whirl has no time
    // to build and peaks after the pair, far lower than the curve (measured 0.274 at Ω = 1.49,
    // 0.13 of the stationary peak, the same to 1e-9 at rtol 1e-8 to 1e-11). It does not follow
    // the curve below the pair either (0.045 against 0.135 at Ω = 0.67: the speed rises too
    // fast). Then the spin and the whirl trade energy: the speed swings over the whole range,
    // forward and back through every critical speed, without settling (second half of the run:
    // Ω from −0.23 to 5.4; from −0.09 to 8.6 and −0.24 to 7.3 at rtol 1e-10 and 1e-11, whose
    // final speeds 3.15, 2.91, 1.47 differ: a chaotic response, so only the span is asserted).
    let (run, _) = radius_vs_speed(&locked, &Drive::Torque { omega0: 0.0, torque: 0.1, t_off: None }, &init, &set);
    let upto = run.iter().position(|p| p.0 > 1.9).expect("T = 0.1 passes the transverse pair");
    let pass = peak_of(&mut run[..upto].iter().copied());
    assert!(pass.0 > crit[1] && pass.1 < 0.2 * st_peak.1, "T = 0.1: passage peak {pass:?}, stationary {st_peak:?}");
    let (lo, hi) = run[run.len() / 2..].iter().fold((f64::INFINITY, 0.0f64), |(l, h), p| (l.min(p.0), h.max(p.0)));
    assert!(lo < crit[0] && hi > angular[1], "T = 0.1: second half of the run only in Ω {lo}-{hi}");
}

/// The two-plane rotor of examples/spatial_two_plane.toml with isotropic supports and no
/// gravity, the couple unbalance mass moved to mid-span (so that neither ball set sits in the
/// plane of an unbalance mass alone).
fn two_plane_rotor() -> SpatialRotor {
    // the rotor of examples/dimensional.toml, whose [balancer] is the first plane
    let mut r = SpatialRotor::dimensional_example();
    r.unbalances.push(PointMass { mass: 0.01, radius: 0.1, angle: 2.5, z: 0.25 });
    r.planes.push(BallPlane { z: 0.05, n: 2, ball_mass: 0.02, race_radius: 0.12, drag: 0.5, physics: Default::default() });
    r
}

#[test]
fn two_ball_sets_cancel_static_plus_couple_unbalance_above_both_critical_speeds() {
    // §4(c). Static plus couple unbalance (10 g at 100 mm in the first balancer's plane, 10 g
    // at 100 mm, 143° round, at mid-span), two ball sets (2 × 20 g at 120 mm each) near the
    // ends. Linear critical speeds of the rotor: 484 rad/s (transverse) and 840 rad/s
    // (conical). At constant speed, balls started spread evenly:
    // - below the first and between the two critical speeds the balls do not balance, nor at
    //   1100 rad/s (1.31 times the conical critical speed; residuals 1.3 and 9.3 times the
    //   unbalance's);
    // - above both (1.4 to 3.6 times the conical one) they do, static and couple residuals
    //   below 1e-6 of the unbalance's, and each set sits where two-plane balancing in closed
    //   form puts it: the resultants B_A, B_B of the sets solve B_A + B_B = −ΣU and
    //   z_A B_A + z_B B_B = −Σ z U (rotor frame), each pair at arg B ± acos(|B|/(2 m R)),
    //   also on anisotropic supports (residuals 1e-13 at 1400 rad/s).
    let r = two_plane_rotor();
    let (u1, u2) = (&r.unbalances[0], &r.unbalances[1]);
    let cplx = |m: f64, rad: f64, a: f64| [m * rad * a.cos(), m * rad * a.sin()];
    let (c1, c2) = (cplx(u1.mass, u1.radius, u1.angle), cplx(u2.mass, u2.radius, u2.angle));
    let (za, zb) = (r.planes[0].z, r.planes[1].z);
    let ba: Vec<f64> = (0..2).map(|k| -((u1.z - zb) * c1[k] + (u2.z - zb) * c2[k]) / (za - zb)).collect();
    let bb: Vec<f64> = (0..2).map(|k| -(c1[k] + c2[k]) - ba[k]).collect();
    let expected = |b: &[f64], p: &BallPlane| -> [f64; 2] {
        let half = (b[0].hypot(b[1]) / (2.0 * p.ball_mass * p.race_radius)).acos();
        let arg = b[1].atan2(b[0]);
        [arg - half, arg + half]
    };
    let want = [expected(&ba, &r.planes[0]), expected(&bb, &r.planes[1])];
    let wrap = |a: f64| (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI;
    // anisotropic supports (k_y 1.3 and 1.2 times k_x) do not spoil it at 1400 rad/s
    let mut aniso = r.clone();
    aniso.supports[0].stiffness[1] *= 1.3;
    aniso.supports[1].stiffness[1] *= 1.2;
    for (omega, balances, r) in
        [(300.0, false, &r), (700.0, false, &r), (1100.0, false, &r), (1200.0, true, &r), (2000.0, true, &r), (3000.0, true, &r), (1400.0, true, &aniso)]
    {
        let drive = Drive::Speed { omega0: omega };
        let init = Initial::at_rest(r);
        let set = Settings { method: Default::default(), t_end: 10.0, dt: 0.05, rtol: 1e-10, atol: 1e-12 };
        let mut last = vec![];
        let s = simulate(r, &drive, &init, &set, |x| {
            last = x.psi.clone();
            true
        })
        .unwrap();
        if !balances {
            assert!(!s.balanced && s.residual_unbalance.max(s.residual_couple.unwrap()) > 0.05, "Ω = {omega}: {s:?}");
            continue;
        }
        assert!(s.balanced && s.residual_unbalance < 1e-6 && s.residual_couple.unwrap() < 1e-6, "Ω = {omega}: {s:?}");
        for (p, w) in want.iter().enumerate() {
            let mut got = [wrap(last[2 * p]), wrap(last[2 * p + 1])];
            let mut w = [wrap(w[0]), wrap(w[1])];
            got.sort_by(f64::total_cmp);
            w.sort_by(f64::total_cmp);
            for k in 0..2 {
                assert!(wrap(got[k] - w[k]).abs() < 1e-5, "Ω = {omega}, plane {p}: balls at {got:?}, closed form {w:?}");
            }
        }
    }
    // The example's layout (couple mass in the second ball plane) under gravity across the axis
    // (−9.81 m/s² along y) at 1400 rad/s: balanced on average over a revolution; the weight
    // seen by the turning balls makes them swing, a residual of 3.9e-4 static and 5.8e-5
    // couple at the run's end that averages out (docs/notes/spatial.md; measured 1.5e-6 and 2.9e-7
    // averaged over the last revolution): asserted below 1e-5.
    let mut heavy = two_plane_rotor();
    heavy.unbalances[1].z = 0.05;
    heavy.gravity = [0.0, -9.81, 0.0];
    let set = Settings { method: Default::default(), t_end: 10.0, dt: 0.05, rtol: 1e-9, atol: 1e-11 };
    let s = simulate(&heavy, &Drive::Speed { omega0: 1400.0 }, &Initial::at_rest(&heavy), &set, |_| true).unwrap();
    let couple = s.residual_couple.unwrap();
    assert!(s.balanced && s.residual_unbalance < 1e-5 && couple < 1e-5, "gravity: {s:?}");
}

/// A config's `[balancer]` without balls leaves `[balancer2]` as the simulation's only plane,
/// with its own ball physics (before, the first plane took `[balancer]`'s, silently dropping
/// `[balancer2]`'s contact).
#[test]
fn the_second_plane_keeps_its_ball_physics_when_the_first_has_no_balls() {
    let text = include_str!("../../../examples/spatial_two_plane.toml")
        .replace("balls = 2                   # n", "balls = 0")
        .replace("ball_mass = 0.020           # m (kg), each ball", "ball_mass = 0.0")
        .replace("[balancer2]                 # second ball set", "[balancer2]\ncontact = true\nrolling_resistance = 1e-3");
    let root = autobal::config::parse(&text, "two_plane.toml").unwrap();
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    assert_eq!(sim.rotor.planes.len(), 1);
    let p = &sim.rotor.planes[0];
    assert_eq!((p.z, p.n), (0.05, 2));
    assert!(p.physics.contact && p.physics.rolling_resistance == 1e-3, "{:?}", p.physics);
    // and the example as given: each plane its own (default) physics
    let root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two_plane.toml").unwrap();
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    assert_eq!(sim.rotor.planes.iter().map(|p| (p.z, p.n)).collect::<Vec<_>>(), [(0.45, 2), (0.05, 2)]);
}
