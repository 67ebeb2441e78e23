//! The planar rotor on supports that differ by direction (`planar.k_x ≠ planar.k_y`,
//! `c_x ≠ c_y`) and with balls of their own mass and drag (`planar.ball_masses`,
//! `planar.ball_drags`): each piece against something independent.

mod common;

use autobal::analysis::{mode, stability, stationary, Kind, NewtonOptions, StationaryState, VectorField, Verdict};
use autobal::planar::field::{two_ball_angles, PlanarField};
use autobal::planar::{Drive, Equations, PlanarRotor};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use common::python_with;
use num_complex::Complex64 as C;

/// Paper 004's rotor with the race centred (`s2 = 0`): the Jeffcott rotor with two balls.
fn jeffcott() -> PlanarRotor {
    PlanarRotor { s2: 0.0, ..PlanarRotor::paper() }
}

/// `jeffcott()` on supports 15 % softer along x and 15 % stiffer along y than its `k`, with
/// damping 40 / 60 kg/s, and two balls of 0.025 and 0.035 kg with drags 0.08 and 0.12 N·m·s.
fn anisotropic() -> PlanarRotor {
    let p = jeffcott();
    PlanarRotor {
        k: 0.85 * p.k,
        k_y: Some(1.15 * p.k),
        c: 40.0,
        c_y: Some(60.0),
        ball_masses: Some(vec![0.025, 0.035]),
        ball_drags: Some(vec![0.08, 0.12]),
        ..p
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// A state away from every stationary one (for comparing right-hand sides and Jacobians).
fn some_state(n: usize, scale: f64) -> Vec<f64> {
    let nr = 2 + n;
    (0..2 * nr).map(|i| if i % nr < 2 { scale * (0.3 + 0.17 * i as f64) } else { 0.4 + 0.9 * i as f64 } * if i >= nr { 50.0 } else { 1.0 }).collect()
}

#[test]
fn equal_directions_and_equal_per_ball_values_reproduce_the_model() {
    // (a) the same rotor described per direction (k_x = k_y, c_x = c_y) and per ball (equal
    // masses and drags) takes other code: the support force's general form is skipped only when
    // the values are equal (so here it is the isotropic one), and the balls go through the
    // weighted elimination (moments weighted by m_j, drags by c_ψj) instead of the equal-ball
    // one. Right-hand sides (field, and the free-rotor simulation's), Jacobians, the stationary
    // state and its eigenvalues agree to round-off (1e-12 relative to the largest entry: the
    // two eliminations sum the same terms in a different order).
    for base in [PlanarRotor::paper(), PlanarRotor { n: 3, m3: 0.02, gamma: 0.7, ..PlanarRotor::paper() }] {
        let n = base.n;
        let twin =
            PlanarRotor { k_y: Some(base.k), c_y: Some(base.c), ball_masses: Some(vec![base.m3; n]), ball_drags: Some(vec![base.c_psi; n]), ..base.clone() };
        assert!(!twin.anisotropic() && !twin.equal_balls());
        let w = 400.0;
        let (f0, f1) = (PlanarField::new(&base, w).unwrap(), PlanarField::new(&twin, w).unwrap());
        assert_eq!(f1.period(), None, "equal supports: autonomous");
        let x = some_state(n, 1e-4);
        let dim = f0.dim();
        let (mut a, mut b) = (vec![0.0; dim], vec![0.0; dim]);
        f0.rhs(0.0, &x, &mut a);
        f1.rhs(0.0, &x, &mut b);
        let big = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..dim {
            assert!((a[i] - b[i]).abs() <= 1e-12 * big, "rhs[{i}]: {} vs {}", a[i], b[i]);
        }
        let (mut ja, mut jb) = (vec![0.0; dim * dim], vec![0.0; dim * dim]);
        f0.jacobian(0.0, &x, &mut ja);
        f1.jacobian(0.0, &x, &mut jb);
        let big = ja.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..dim * dim {
            assert!((ja[i] - jb[i]).abs() <= 1e-12 * big, "J[{i}]: {} vs {}", ja[i], jb[i]);
        }
        // the free rotor (torque drive): the 3×3 elimination with the rotation row
        let drive = Drive::Torque { omega0: 300.0, torque: 5.0, t_off: None };
        let (e0, e1) = (Equations::new(&base, &drive), Equations::new(&twin, &drive));
        let y = f0.full_state(&x);
        let (mut da, mut db) = (vec![0.0; y.len()], vec![0.0; y.len()]);
        autobal::ode::System::rhs(&e0, 0.0, &y, &mut da);
        autobal::ode::System::rhs(&e1, 0.0, &y, &mut db);
        let big = da.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..y.len() {
            assert!((da[i] - db[i]).abs() <= 1e-12 * big, "free rhs[{i}]: {} vs {}", da[i], db[i]);
        }
        // stationary state and eigenvalues, from the same start (for n = 3 the two closed forms
        // pick different members of the family: the unequal-ball one places ball 3 first)
        let g0 = f0.semi_balanced_guess().unwrap();
        let g1 = f1.semi_balanced_guess().unwrap();
        let residual = |f: &PlanarField, g: &[f64]| {
            let mut d = vec![0.0; dim];
            f.rhs(0.0, g, &mut d);
            d.iter().fold(0.0f64, |m, v| m.max(v.abs()))
        };
        assert!(residual(&f1, &g1) < 1e-9, "the unequal-ball closed form is stationary too");
        let s0 = stationary(&f0, &g0, &NewtonOptions::default()).unwrap();
        let s1 = stationary(&f1, &g0, &NewtonOptions::default()).unwrap();
        for i in 0..dim {
            let scale = if i % (2 + n) < 2 { 1e-4 } else { 1.0 };
            assert!((s0.x[i] - s1.x[i]).abs() <= 1e-12 * scale * if i >= 2 + n { w } else { 1.0 }, "x[{i}]: {} vs {}", s0.x[i], s1.x[i]);
        }
        let (st0, st1) = (stability(&f0, &s0).unwrap(), stability(&f1, &s1).unwrap());
        assert_eq!(st0.verdict, st1.verdict);
        for (l0, l1) in st0.spectrum.iter().zip(&st1.spectrum) {
            assert!((l0.complex() - l1.complex()).norm() <= 1e-12 * st0.rate, "{l0:?} vs {l1:?}");
        }
    }
}

#[test]
fn the_weighted_elimination_equals_the_mass_matrix_solve_for_unequal_balls_on_unequal_supports() {
    // The right-hand side (balls eliminated, moments weighted by m_j) against M⁻¹ F of the mass
    // matrix assembled body by body (no elimination), at a state with every term awake (θ ≠ 0
    // so the supports' e^{−2iθ} term acts, rotor turning freely), to 1e-11 relative (the
    // elimination's round-off in a 6×6 solve).
    let p = PlanarRotor { s2: 0.0005, n: 3, ball_masses: Some(vec![0.02, 0.03, 0.045]), ball_drags: Some(vec![0.05, 0.1, 0.2]), ..anisotropic() };
    p.validate().unwrap();
    for drive in [Drive::Torque { omega0: 300.0, torque: 5.0, t_off: None }, Drive::Speed { omega0: 300.0 }] {
        let eq = Equations::new(&p, &drive);
        let nc = 3 + p.n;
        let mut y: Vec<f64> = (0..2 * nc).map(|i| 0.1 + 0.37 * i as f64).collect();
        y[0] = 2e-4;
        y[1] = -1e-4;
        y[nc] = 0.03;
        y[nc + 1] = 0.05;
        y[nc + 2] = 300.0;
        let mut dy = vec![0.0; 2 * nc];
        autobal::ode::System::rhs(&eq, 0.0, &y, &mut dy);
        let (m, f) = eq.mass_matrix(0.0, &y);
        let res = eq.residuals(0.0, &y, &dy[nc..]);
        let scale = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for (i, r) in res.iter().enumerate() {
            assert!(r.abs() <= 1e-11 * scale, "{drive:?}: residual[{i}] = {r:e} (forces up to {scale:e})");
        }
        // and M q̈ = F directly
        for i in 0..nc {
            let lhs: f64 = (0..nc).map(|j| m[i * nc + j] * dy[nc + j]).sum();
            assert!((lhs - f[i]).abs() <= 1e-11 * scale, "{drive:?}: row {i}: {lhs:e} vs {:e}", f[i]);
        }
    }
}

#[test]
fn supports_that_differ_by_direction_conserve_energy_without_damping() {
    // No damping anywhere and a free rotor: T + V with V = ½(k_x X² + k_y Y²) is conserved.
    // The rotor angle enters the support force through e^{−2iθ}: a wrong sign or factor there
    // shows as energy drift. DOP853 at rtol 1e-11 over 0.2 s (~10 revolutions): relative drift
    // below 1e-8.
    let p = PlanarRotor { c: 0.0, c_y: Some(0.0), c_psi: 0.0, ball_drags: Some(vec![0.0, 0.0]), ..anisotropic() };
    let drive = Drive::Torque { omega0: 300.0, torque: 0.0, t_off: None };
    let eq = Equations::new(&p, &drive);
    let nc = 3 + p.n;
    let mut y = vec![0.0; 2 * nc];
    y[0] = 3e-4;
    y[1] = -2e-4;
    y[3] = 1.0;
    y[4] = 2.5;
    y[nc + 2] = 300.0;
    let e0 = autobal::planar::energy(&p, &y);
    let opts = autobal::ode::Options::new(1e-11, 1e-14).method(autobal::ode::Method::Dop853);
    let mut solver = autobal::ode::Solver::new(&eq, opts).unwrap();
    let out = solver.integrate(0.0, &mut y, 0.2, |_| autobal::ode::Control::Continue);
    assert!(out.status.is_completed());
    let e1 = autobal::planar::energy(&p, &y);
    assert!(rel(e1, e0) < 1e-8, "energy {e0} → {e1}");
}

/// The bare rotor (no balls) on supports `k_x`, `k_y`, `c_x`, `c_y`, mass `m0 = m1 + m2`.
fn bare() -> PlanarRotor {
    PlanarRotor { n: 0, m3: 0.0, ball_masses: None, ball_drags: None, ..anisotropic() }
}

#[test]
fn the_bare_rotor_has_the_natural_frequencies_and_forced_response_of_each_direction() {
    // (b) Without balls the planar rotor is a point mass m0 on two independent springs. At rest
    // (Ω = 0, nothing turns: an equilibrium) the Jacobian's eigenvalues are those of
    // m0 s² + c_d s + k_d = 0 for d = x, y (undamped: ±i sqrt(k_d/m0)), to 1e-12. Spinning at Ω
    // the field is periodic with T = π/Ω and the stationary motion is the unbalance response
    // z(t) = X + iY with X = Re(U Ω² e^{iΩt} / D_x), Y = Re(−i U Ω² e^{iΩt} / D_y),
    // D_d = k_d − m0 Ω² + i c_d Ω, U = m1 s1: shooting must find u(0) = z(0), u̇(0) = ż(0) − iΩz(0)
    // (to 1e-9 relative: the shooting's tolerance). The turning axes' free motion is the fixed
    // one turned by e^{−iΩt}, and e^{−iΩT} = −1: the Floquet multipliers are −e^{λ T} for the four
    // fixed-axes roots λ (to 1e-9: the variational integration at rtol 1e-12 over T).
    let p = bare();
    let m0 = p.total_mass();
    let (kx, ky) = p.stiffness_xy();
    let (cx, cy) = p.damping_xy();
    assert_eq!(m0, p.m1 + p.m2);
    let undamped = PlanarRotor { c: 0.0, c_y: Some(0.0), ..p.clone() };
    let f = PlanarField::new(&undamped, 0.0).unwrap();
    assert_eq!(f.period(), None);
    let mut j = vec![0.0; 16];
    f.jacobian(0.0, &[0.0; 4], &mut j);
    let l = autobal::linalg::eigen_dyn::eigenvalues(&j, 4).unwrap();
    let (wx, wy) = undamped.natural_frequencies_xy();
    assert!(rel(wx, (kx / m0).sqrt()) < 1e-15 && rel(wy, (ky / m0).sqrt()) < 1e-15);
    for target in [wx, wy] {
        for s in [-1.0, 1.0] {
            let d = l.iter().map(|z| (z - C::new(0.0, s * target)).norm()).fold(f64::INFINITY, f64::min);
            assert!(d < 1e-12 * target, "±i {target}: {l:?}");
        }
    }
    // fixed-axes roots with damping
    let roots = |k: f64, c: f64| {
        let disc = C::new(c * c - 4.0 * m0 * k, 0.0).sqrt();
        [(-c + disc) / (2.0 * m0), (-c - disc) / (2.0 * m0)]
    };
    let lambdas: Vec<C> = roots(kx, cx).into_iter().chain(roots(ky, cy)).collect();
    for w in [150.0, 290.0, 600.0] {
        let f = PlanarField::new(&p, w).unwrap();
        let t = f.period().unwrap();
        assert!(rel(t, std::f64::consts::PI / w) < 1e-15);
        let u0 = C::new(p.m1 * p.s1, 0.0);
        let dx = C::new(kx - m0 * w * w, cx * w);
        let dy = C::new(ky - m0 * w * w, cy * w);
        let z = |tt: f64| {
            let e = C::from_polar(1.0, w * tt) * u0 * (w * w);
            (e / dx).re + C::new(0.0, 1.0) * (C::new(0.0, -1.0) * e / dy).re
        };
        let zd = |tt: f64| {
            let e = C::from_polar(1.0, w * tt) * u0 * (w * w) * C::new(0.0, w);
            (e / dx).re + C::new(0.0, 1.0) * (C::new(0.0, -1.0) * e / dy).re
        };
        let (z0, zd0) = (z(0.0), zd(0.0));
        let ud0 = zd0 - C::new(0.0, w) * z0;
        let s = stationary(&f, &[0.0; 4], &NewtonOptions::default()).unwrap();
        assert_eq!(s.period, Some(t));
        let amp = z0.norm();
        for (got, want, scale) in [(s.x[0], z0.re, amp), (s.x[1], z0.im, amp), (s.x[2], ud0.re, amp * w), (s.x[3], ud0.im, amp * w)] {
            assert!((got - want).abs() < 1e-9 * scale, "Ω = {w}: {got} vs {want}");
        }
        let st = stability(&f, &s).unwrap();
        assert_eq!((st.kind, st.verdict), (Kind::PeriodicOrbit, Verdict::Stable));
        for m in &st.spectrum {
            let d = lambdas.iter().map(|l| (m.complex() + (l * t).exp()).norm()).fold(f64::INFINITY, f64::min);
            assert!(d < 1e-9, "Ω = {w}: multiplier {m:?} is no −e^(λT) of {lambdas:?}");
        }
    }
}

#[test]
fn two_unequal_balls_balance_at_the_closed_form_angles() {
    // (c) With the race centred the balanced state (C at rest on the axis, the balls cancelling
    // m1 s1) does not depend on the supports: no support force acts there, so it is an
    // equilibrium of the periodic field at every instant. The balls' angles are the triangle's
    // (two_ball_angles: sides m_a r, m_b r, m1 s1), unique up to the mirror image in the
    // unbalance's direction. Shooting from a start 0.1 rad and 5 µm off lands on it: the
    // angles to 1e-9 rad, C within 1e-12 m of the axis, r Σ m_j e^{iψ_j} = −m1 s1 to 1e-12
    // relative. Independent of the closed form's code: the angles are checked by the sum.
    let p = anisotropic();
    let (a, b) = (0.025 * p.r, 0.035 * p.r);
    let d = C::new(-p.m1 * p.s1, 0.0);
    let (pa, pb) = two_ball_angles(a, b, d).unwrap();
    let sum = C::from_polar(a, pa) + C::from_polar(b, pb);
    assert!((sum - d).norm() < 1e-15 * d.norm() * 10.0, "{sum} vs {d}");
    // the mirror image balances too; nothing else does (|D| < |a − b| has no solution)
    let (ma, mb) = (2.0 * std::f64::consts::PI - pa, 2.0 * std::f64::consts::PI - pb);
    assert!((C::from_polar(a, ma) + C::from_polar(b, mb) - d).norm() < 1e-14 * d.norm());
    assert!(two_ball_angles(a, b, C::new(0.5 * (b - a), 0.0)).is_none());
    for w in [400.0, 900.0] {
        let f = PlanarField::new(&p, w).unwrap();
        assert_eq!(f.period(), Some(std::f64::consts::PI / w));
        let g = f.semi_balanced_guess().unwrap();
        assert!((g[2] - pa).abs() < 1e-15 && (g[3] - pb).abs() < 1e-15 && g[0] == 0.0 && g[1] == 0.0);
        // an equilibrium of the periodic field at every instant
        let mut dx = vec![0.0; 8];
        for k in 0..8 {
            f.rhs(k as f64 * 0.1 / w, &g, &mut dx);
            assert!(dx.iter().all(|v| v.abs() < 1e-9), "t = {}: {dx:?}", k as f64 * 0.1 / w);
        }
        let mut start = g.clone();
        start[0] += 5e-6;
        start[1] -= 3e-6;
        start[2] += 0.1;
        start[3] -= 0.1;
        let s = stationary(&f, &start, &NewtonOptions::default()).unwrap();
        assert!(s.x[0].hypot(s.x[1]) < 1e-12, "Ω = {w}: C at {:?}", &s.x[..2]);
        let dpsi = |x: f64, y: f64| ((x - y + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI).abs();
        assert!(dpsi(s.x[2], pa) < 1e-9 && dpsi(s.x[3], pb) < 1e-9, "Ω = {w}: {:?} vs ({pa}, {pb})", &s.x[2..4]);
        let sum = C::from_polar(a, s.x[2]) + C::from_polar(b, s.x[3]);
        assert!((sum - d).norm() < 1e-12 * d.norm() * 1e3, "Ω = {w}: {sum}");
        // the mirror image is a balanced state too (stationary at every instant), a distinct one
        let mut m = g.clone();
        m[2] = -pa;
        m[3] = -pb;
        for k in 0..8 {
            f.rhs(k as f64 * 0.1 / w, &m, &mut dx);
            assert!(dx.iter().all(|v| v.abs() < 1e-9), "mirror, t = {}: {dx:?}", k as f64 * 0.1 / w);
        }
        let (a1, a2) = (stability(&f, &s).unwrap().abscissa, stability(&f, &stationary(&f, &m, &NewtonOptions::default()).unwrap()).unwrap().abscissa);
        eprintln!("Ω = {w}: Floquet abscissa {a1:.6} 1/s (closed form's branch), {a2:.6} 1/s (mirror image)");
    }
}

/// `δ(kT) = x(kT) − x*` for k = 0..=periods, by DOP853 from `x* + δ0`: the field's own
/// nonlinear equations written for the deviation, `δ' = f(t, x* + δ)` (`x*` is stationary at
/// every instant), so that the relative tolerance applies to `δ` and not to `x*`.
fn simulate_deviation(f: &PlanarField, s: &StationaryState, d0: &[f64], periods: usize) -> Vec<Vec<f64>> {
    struct Ode<'a>(&'a PlanarField, &'a [f64]);
    impl autobal::ode::System for Ode<'_> {
        fn dim(&self) -> usize {
            self.0.dim()
        }
        fn rhs(&self, t: f64, d: &[f64], dd: &mut [f64]) {
            let y: Vec<f64> = self.1.iter().zip(d).map(|(a, b)| a + b).collect();
            self.0.rhs(t, &y, dd)
        }
    }
    let t = s.period.unwrap();
    let sys = Ode(f, &s.x);
    let atol: Vec<f64> = f.scales().iter().map(|v| 1e-20 * v).collect();
    let opts = autobal::ode::Options::new(1e-12, 1e-20).method(autobal::ode::Method::Dop853).atol_per_component(atol);
    let mut solver = autobal::ode::Solver::new(&sys, opts).unwrap();
    let mut d = d0.to_vec();
    let mut out = vec![d0.to_vec()];
    for k in 1..=periods {
        let o = solver.integrate((k - 1) as f64 * t, &mut d, k as f64 * t, |_| autobal::ode::Control::Continue);
        assert!(o.status.is_completed());
        out.push(d.clone());
    }
    out
}

/// Least-squares coordinates of `d` in the basis `basis` (columns), in the metric scaled by `w`.
fn coordinates(basis: &[Vec<f64>], d: &[f64], w: &[f64]) -> Vec<f64> {
    let k = basis.len();
    let mut g = vec![0.0; k * k];
    let mut r = vec![0.0; k];
    for a in 0..k {
        for b in 0..k {
            g[a * k + b] = (0..d.len()).map(|i| basis[a][i] * basis[b][i] / (w[i] * w[i])).sum();
        }
        r[a] = (0..d.len()).map(|i| basis[a][i] * d[i] / (w[i] * w[i])).sum();
    }
    if k == 1 {
        return vec![r[0] / g[0]];
    }
    let det = g[0] * g[3] - g[1] * g[2];
    vec![(g[3] * r[0] - g[1] * r[1]) / det, (g[0] * r[1] - g[2] * r[0]) / det]
}

#[test]
fn the_floquet_rate_of_the_anisotropic_balanced_state_is_the_simulations() {
    // (d) The balanced state of the anisotropic rotor with unequal balls at a speed where it is
    // stable and at one where it is not: a simulation of the nonlinear equations started at
    // x* + δ0, δ0 = ε Re v (v the least stable multiplier's eigenvector, ε = 1e-7 of the
    // scales) for K periods, its deviation projected on span{Re v, Im v} at each period (least
    // squares, in the scaled metric): |coordinates| shrink or grow by |μ| per period, so the
    // measured rate ln(|c_K| / |c_K0|)/((K − K0) T), K0 = K/3, must equal the Floquet
    // abscissa. K is chosen so the deviation changes by e³ (capped at 600 periods); the first
    // third lets the other modes, excited at the eigenvector's accuracy (inverse iteration:
    // ~1e-3 where another multiplier is near), decay relative to this one. Tolerance 1e-4
    // relative: the nonlinear terms are ε = 1e-7 of the deviation, the integration of the
    // deviation itself is at rtol 1e-12, x* is exact (closed form), so the rate is good to
    // ~1e-6 over a change of e² where the other modes have died out; 1e-4 leaves room for the
    // slower of them.
    let p = anisotropic();
    let mut seen = [false; 2];
    // 250 rad/s: unstable, a complex pair; 400 rad/s: stable, a real multiplier 0.957 beside
    // another at 0.914 (measured: 3.450973 and −5.644365 1/s both ways, agreement ~1e-7)
    for w in [250.0, 400.0] {
        let f = PlanarField::new(&p, w).unwrap();
        let s = stationary(&f, &f.semi_balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
        let st = stability(&f, &s).unwrap();
        assert_eq!(st.kind, Kind::PeriodicOrbit);
        let t = s.period.unwrap();
        let i = st.least_stable.unwrap();
        let mu = st.spectrum[i].complex();
        let v = mode(&st.matrix, f.dim(), mu);
        let sc = f.scales();
        let big = v.iter().zip(&sc).map(|(z, s)| z.norm() / s).fold(0.0, f64::max);
        let basis: Vec<Vec<f64>> = if mu.im.abs() > 1e-12 {
            vec![v.iter().map(|z| z.re / big).collect(), v.iter().map(|z| z.im / big).collect()]
        } else {
            vec![v.iter().map(|z| z.re / big).collect()]
        };
        let eps = 1e-7;
        let d0: Vec<f64> = basis[0].iter().map(|b| eps * b).collect();
        let k = ((3.0 / (st.abscissa.abs() * t)).ceil() as usize).clamp(6, 600);
        let k0 = k / 3;
        let devs = simulate_deviation(&f, &s, &d0, k);
        let size = |d: &[f64]| coordinates(&basis, d, &sc).iter().map(|c| c * c).sum::<f64>().sqrt();
        let measured = (size(&devs[k]) / size(&devs[k0])).ln() / ((k - k0) as f64 * t);
        eprintln!("Ω = {w}: {:?}, Floquet abscissa {:.6e} 1/s (|μ| = {:.9}), measured {measured:.6e} over {k} periods", st.verdict, st.abscissa, mu.norm());
        assert!(rel(measured, st.abscissa) < 1e-4, "Ω = {w}: measured {measured}, Floquet {}", st.abscissa);
        seen[usize::from(st.verdict == Verdict::Stable)] = true;
    }
    assert!(seen[0] && seen[1], "the speeds must include a stable and an unstable balanced state");
}

/// The lowest end of the stable ranges over `speeds`.
fn lowest_stable(p: &PlanarRotor, speeds: &[f64]) -> f64 {
    let r = stability_over_speed(&Rotor::Planar(p.clone()), speeds).unwrap();
    let first = r.stable_ranges.iter().find(|s| s.from_is_boundary).unwrap_or_else(|| panic!("{:?}", r.stable_ranges));
    first.from
}

#[test]
fn support_anisotropy_moves_the_lowest_stable_speed_as_an_independent_floquet_analysis_finds() {
    // (e) The classic result: the balanced state of a Jeffcott rotor with balls is stable only
    // above its critical speed (isotropic: above ω_n = sqrt(k/m0), here at 1.048 ω_n); with
    // supports that differ by direction there are two critical speeds
    // sqrt(k_x/m0) < sqrt(k_y/m0), and the lowest stable speed moves. Here k_x, k_y =
    // (1 ∓ 0.15) k (same mean), equal balls: the general route's lowest stable speed (Floquet,
    // located to 1e-9) comes out at 0.991 ω_n, 5.4 % below the isotropic rotor's and between
    // the two critical speeds. Checked against tests/planar_floquet.py: Lagrange's equations
    // by SymPy with the supports in fixed axes, its own balanced state (scipy.optimize.root),
    // monodromy by solve_ivp, bisection to 1e-7 — agreement to 1e-6 relative.
    let iso = PlanarRotor { c: 50.0, ..jeffcott() };
    let aniso = PlanarRotor { k: 0.85 * iso.k, k_y: Some(1.15 * iso.k), ..iso.clone() };
    let wn = iso.natural_frequency();
    let speeds: Vec<f64> = (1..=60).map(|i| 0.05 * wn * i as f64).collect();
    let w_iso = lowest_stable(&iso, &speeds);
    let w_aniso = lowest_stable(&aniso, &speeds);
    let (wx, wy) = aniso.natural_frequencies_xy();
    eprintln!(
        "lowest stable speed: isotropic {w_iso:.6} rad/s ({:.4} ω_n), anisotropic {w_aniso:.6} rad/s ({:.4} ω_n; ω_x = {wx:.3}, ω_y = {wy:.3})",
        w_iso / wn,
        w_aniso / wn
    );
    assert!(w_iso > wn, "isotropic: stable only above the critical speed");
    assert!(w_aniso > wx && (w_aniso - w_iso).abs() > 0.01 * w_iso, "the anisotropy moves the lowest stable speed");
    let Some(python) = python_with(&["sympy", "numpy", "scipy"]) else { return };
    let pj = |p: &PlanarRotor| {
        let (kx, ky) = p.stiffness_xy();
        let (cx, cy) = p.damping_xy();
        serde_json::json!({"m1": p.m1, "m2": p.m2, "s1": p.s1, "r": p.r, "n": p.n, "k_x": kx, "k_y": ky, "c_x": cx, "c_y": cy,
            "masses": (0..p.n).map(|j| p.ball_mass(j)).collect::<Vec<_>>(), "drags": (0..p.n).map(|j| p.ball_drag(j)).collect::<Vec<_>>()})
    };
    // also the multipliers of one state of the unequal-ball rotor, against the SymPy monodromy
    let q = anisotropic();
    let wq = 800.0;
    let f = PlanarField::new(&q, wq).unwrap();
    let s = stationary(&f, &f.semi_balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    let st = stability(&f, &s).unwrap();
    let req = serde_json::json!({
        "cases": [{"p": pj(&q), "omega": wq, "x": s.x, "period": s.period.unwrap()}],
        "lowest": [{"p": pj(&aniso), "lo": 0.97 * w_aniso, "hi": 1.03 * w_aniso}],
    });
    let script = format!("{}/tests/planar_floquet.py", env!("CARGO_MANIFEST_DIR"));
    let mut child =
        std::process::Command::new(python).arg(script).stdin(std::process::Stdio::piped()).stdout(std::process::Stdio::piped()).spawn().expect("python runs");
    use std::io::Write;
    child.stdin.take().unwrap().write_all(req.to_string().as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let case = &v["cases"][0];
    assert!(case["rhs"].as_f64().unwrap() < 1e-9, "not stationary in the SymPy equations: {}", case["rhs"]);
    let theirs: Vec<C> = case["multipliers"].as_array().unwrap().iter().map(|m| C::new(m[0].as_f64().unwrap(), m[1].as_f64().unwrap())).collect();
    for m in &st.spectrum {
        let d = theirs.iter().map(|z| (z - m.complex()).norm()).fold(f64::INFINITY, f64::min);
        assert!(d < 1e-8, "multiplier {m:?} not among SymPy's {theirs:?}");
    }
    let python_lowest = v["lowest"][0].as_f64().unwrap();
    eprintln!("SymPy/SciPy lowest stable speed {python_lowest:.6} rad/s, autobal {w_aniso:.6}");
    assert!(rel(w_aniso, python_lowest) < 1e-6, "autobal {w_aniso}, SymPy/SciPy {python_lowest}");
}

#[test]
fn config_keys_per_direction_and_per_ball_are_read_and_checked() {
    use autobal::config::{parse, planar};
    use autobal::paths::Parameters;
    let base = "[planar]\nm1 = 1.0\nm2 = 0.2\ns1 = 0.003\nr = 0.06\ni_g = 0.0025\n";
    let read = |extra: &str| planar(&parse(&format!("{base}{extra}[drive]\nkind = \"speed\"\nomega0 = 300.0\n"), "t.toml").unwrap());
    let err = |extra: &str| read(extra).unwrap_err().to_string();
    // per direction
    let p = read("k_x = 9e4\nk_y = 1.2e5\nc_x = 40.0\nc_y = 60.0\nm3 = 0.03\n").unwrap();
    assert_eq!((p.rotor.stiffness_xy(), p.rotor.damping_xy()), ((9e4, 1.2e5), (40.0, 60.0)));
    assert!(p.rotor.anisotropic());
    // isotropic keys: the same in both directions
    let p = read("k = 1e5\nc = 50.0\nm3 = 0.03\n").unwrap();
    assert_eq!((p.rotor.stiffness_xy(), p.rotor.damping_xy()), ((1e5, 1e5), (50.0, 50.0)));
    assert!(!p.rotor.anisotropic());
    // both kinds, or half a pair: errors naming both keys
    let e = err("k = 1e5\nk_y = 1.2e5\nm3 = 0.03\n");
    assert!(e.starts_with("planar.k_y: conflicts with planar.k"), "{e}");
    let e = err("k = 1e5\nc = 5.0\nc_x = 4.0\nm3 = 0.03\n");
    assert!(e.starts_with("planar.c_x: conflicts with planar.c"), "{e}");
    let e = err("k_x = 1e5\nm3 = 0.03\n");
    assert!(e.starts_with("planar.k_y: missing") && e.contains("planar.k_x"), "{e}");
    let e = err("m3 = 0.03\n");
    assert!(e.starts_with("planar.k: missing"), "{e}");
    let e = err("k_x = 1e5\nk_y = -1.0\nm3 = 0.03\n");
    assert!(e.starts_with("planar.k_y:"), "{e}");
    // per ball
    let p = read("k = 1e5\nball_masses = [0.025, 0.035]\nball_drags = [0.08, 0.12]\n").unwrap();
    assert_eq!((p.rotor.ball_mass(1), p.rotor.ball_drag(0)), (0.035, 0.08));
    assert!((p.rotor.total_mass() - 1.26).abs() < 1e-15);
    let e = err("k = 1e5\nn = 3\nball_masses = [0.025, 0.035]\nm3 = 0.03\n");
    assert!(e.starts_with("planar.ball_masses: conflicts with planar.m3"), "{e}");
    let e = err("k = 1e5\nn = 3\nball_masses = [0.025, 0.035]\n");
    assert!(e.starts_with("planar.ball_masses: needs one mass per ball (planar.n = 3), got 2"), "{e}");
    let e = err("k = 1e5\nm3 = 0.03\nball_drags = [0.1, -0.1]\n");
    assert!(e.starts_with("planar.ball_drags") && e.contains("-0.1"), "{e}");
    let e = err("k = 1e5\nball_masses = [0.03, 0.03]\ncontact = true\n");
    assert!(e.starts_with("planar.ball_masses: real balls"), "{e}");
    // parameter paths: maps and sweeps vary them
    let mut p = read("k = 1e5\nm3 = 0.03\nn = 2\n").unwrap();
    p.set("planar.k_y", 1.3e5).unwrap();
    assert_eq!(p.rotor.stiffness_xy(), (1e5, 1.3e5));
    assert!(p.get("planar.k").unwrap_err().to_string().starts_with("planar.k: the supports differ by direction"));
    assert!(p.set("planar.k", 2e5).unwrap_err().to_string().starts_with("planar.k: the supports are given per direction"));
    p.set("planar.k_x", 1.1e5).unwrap();
    p.set("planar.c_y", 70.0).unwrap();
    assert_eq!((p.rotor.stiffness_xy(), p.rotor.damping_xy()), ((1.1e5, 1.3e5), (0.0, 70.0)));
    p.set("planar.ball_masses[2]", 0.04).unwrap();
    assert_eq!(p.rotor.ball_masses, Some(vec![0.03, 0.04]));
    assert!((p.rotor.m3 - 0.035).abs() < 1e-15 && p.get("planar.ball_masses[2]").unwrap() == 0.04);
    assert!(p.set("planar.m3", 0.02).unwrap_err().to_string().starts_with("planar.m3: the balls have their own masses"));
    assert!(p.set("planar.ball_drags[3]", 0.1).unwrap_err().to_string().starts_with("planar.ball_drags[3]: ball 3 does not exist"));
    p.validate().unwrap();
    p.set("planar.k_y", 0.0).unwrap();
    assert!(p.validate().unwrap_err().to_string().starts_with("planar.k_y"));
}

#[test]
fn the_simulation_runs_the_anisotropic_rotor_with_unequal_balls_to_its_balanced_state() {
    // A run at constant speed above the lowest stable speed (800 rad/s, where (d) finds the
    // balanced state stable, multiplier 0.955 per half revolution) from balls spread across the
    // unbalance: C ends on the axis (whirl below 1 % of m1 s1/m0, the unbalanced whirl's scale)
    // with the balls at the closed-form angles (or their mirror image) to 1e-3 rad; by DOP853
    // and by RODAS (whose Jacobian has the rotor angle's column, the supports' ∂F/∂θ).
    use autobal::planar::{simulate, Method, Settings};
    let p = anisotropic();
    let drive = Drive::Speed { omega0: 800.0 };
    for method in [Method::Dop853, Method::Rodas] {
        let settings = Settings { method, rtol: 1e-9, atol: 1e-12, ..Settings::new(&p, 6.0) };
        let mut last = None;
        let s = simulate(&p, &drive, &settings, |x| {
            last = Some(x.clone());
            true
        })
        .unwrap();
        assert!(s.status.is_completed());
        let last = last.unwrap();
        assert!(s.final_amplitude < 0.01 * p.m1 * p.s1 / p.total_mass(), "{s:?}");
        let (pa, pb) = two_ball_angles(0.025 * p.r, 0.035 * p.r, C::new(-p.m1 * p.s1, 0.0)).unwrap();
        let d = |x: f64, y: f64| ((x - y + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI).abs();
        let direct = d(last.psi[0], pa).max(d(last.psi[1], pb));
        let mirror = d(last.psi[0], -pa).max(d(last.psi[1], -pb));
        assert!(direct.min(mirror) < 1e-3, "{method:?}: balls at {:?}, closed form ({pa}, {pb}) or mirrored", last.psi);
    }
}

#[test]
fn the_jacobian_at_the_balanced_state_is_a_fixed_trigonometric_combination() {
    // At a state held fixed the rotor angle enters only through cos 2θ, sin 2θ of the support
    // force, so the field caches J(t) = J_a + cos 2Ωt J_c + sin 2Ωt J_s at the balanced state
    // (two calls there build it). Its values at other instants equal a fresh field's direct
    // Jacobian (each call on a new field is computed, not cached) to 1e-12 of the largest
    // entry; at a state off balance too (the accelerations are affine in cos 2θ, sin 2θ as
    // well, so the formula is exact at any fixed x).
    let p = anisotropic();
    let w = 500.0;
    let f = PlanarField::new(&p, w).unwrap();
    let g = f.semi_balanced_guess().unwrap();
    let mut off = g.clone();
    off[0] += 3e-5;
    off[5] = 2.0;
    for x in [g, off] {
        let n = f.dim();
        let mut j = vec![0.0; n * n];
        f.jacobian(0.0, &x, &mut j);
        f.jacobian(0.0, &x, &mut j); // builds the decomposition
        for k in 0..7 {
            let t = 0.37 * k as f64 / w;
            f.jacobian(t, &x, &mut j);
            let mut direct = vec![0.0; n * n];
            PlanarField::new(&p, w).unwrap().jacobian(t, &x, &mut direct);
            let big = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for i in 0..n * n {
                assert!((j[i] - direct[i]).abs() <= 1e-12 * big, "t = {t}: J[{i}] {} vs {}", j[i], direct[i]);
            }
        }
    }
}

#[test]
fn the_eccentric_race_on_unequal_supports_settles_on_the_shot_orbit() {
    // Paper 004's eccentric race (s2 = 0.5 mm) on the supports and balls of `anisotropic()`:
    // the stationary motion is a periodic orbit of half a revolution (the race centre cannot
    // stay on the axis: the support force on it turns), found by shooting from the
    // semi-balanced state of the mean supports. A constant-speed run of the simulator from
    // balls spread across the unbalance, ended at t = K π/Ω (θ = Kπ, so u = (−1)^K z), is on
    // one of them: C and the balls' angles to 1e-6 of their scales (the run's tolerance is
    // 1e-10; K is long enough for the slowest transient to fall by e^{-25}). Two orbits: the
    // unequal balls balance in a pair of mirror-image arrangements, which the supports'
    // anisotropy (and the Coriolis terms) make distinct states: C differs by 6e-5 of its whirl
    // between them. The closed form's guess and its mirror image (ψ → −ψ) start the shooting of
    // each; both are stable here, and the run from this start ends on the mirrored one.
    use autobal::planar::{simulate, Method, Settings};
    let p = PlanarRotor { s2: 0.0005, ..anisotropic() };
    let w = 600.0;
    let f = PlanarField::new(&p, w).unwrap();
    let g = f.semi_balanced_guess().unwrap();
    let mut mirrored = g.clone();
    mirrored[2] = -g[2];
    mirrored[3] = -g[3];
    let orbits: Vec<StationaryState> = [g, mirrored].iter().map(|x| stationary(&f, x, &NewtonOptions::default()).unwrap()).collect();
    assert!((orbits[0].x[0] - orbits[1].x[0]).abs() > 1e-9, "two distinct orbits");
    let mut slowest = f64::NEG_INFINITY;
    for o in &orbits {
        let st = stability(&f, o).unwrap();
        assert_eq!((st.kind, st.verdict), (Kind::PeriodicOrbit, Verdict::Stable), "{:?}", st.abscissa);
        slowest = slowest.max(st.abscissa);
    }
    let t = orbits[0].period.unwrap();
    // the race centre is off the axis on both: no semi-balanced state
    assert!(orbits.iter().all(|s| (s.x[0] + p.s2).hypot(s.x[1]) > 1e-3 * p.s2));
    let k = (25.0 / (-slowest) / t).round();
    let drive = Drive::Speed { omega0: w };
    let settings = Settings { method: Method::Dop853, rtol: 1e-10, atol: 1e-14, dt: t, ..Settings::new(&p, k * t) };
    let mut samples = vec![];
    let out = simulate(&p, &drive, &settings, |x| {
        samples.push(x.clone());
        true
    })
    .unwrap();
    assert!(out.status.is_completed());
    let last = samples.last().unwrap().clone();
    assert!((last.t - k * t).abs() < 1e-9 * k * t, "{} vs {}", last.t, k * t);
    let sign = if (k as u64).is_multiple_of(2) { 1.0 } else { -1.0 };
    let (ux, uy) = (sign * last.x, sign * last.y);
    let len = p.s1;
    let angle = |a: f64, b: f64| ((a - b + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI).abs();
    let on =
        |s: &StationaryState| (ux - s.x[0]).abs() < 1e-6 * len && (uy - s.x[1]).abs() < 1e-6 * len && (0..2).all(|j| angle(last.psi[j], s.x[2 + j]) < 1e-6);
    assert!(orbits.iter().any(on), "run ends at C ({ux}, {uy}), balls {:?}; orbits {:?}, {:?}", last.psi, &orbits[0].x[..4], &orbits[1].x[..4]);
}

#[test]
fn unequal_balls_reach_every_unbalance_of_their_annulus_in_any_order() {
    // Review 25a's F2: with three or more unequal balls the placement tried only three layouts
    // of balls 3.. and missed reachable unbalances (its 4-ball rotor: "no balanced state" where
    // the same balls listed largest first balance). The polygon-closure bound, independent of
    // the placement: lengths l_j = m_j r sum to a vector of any magnitude in
    // [max(0, 2 max l − Σ l), Σ l] and no other. Checked on a grid of magnitudes and
    // directions, for every order of the balls: inside the annulus a placement whose sum
    // equals b to 1e-12 of Σ l (round-off of a few trigonometric steps), outside none.
    use autobal::planar::field::unequal_balls_balancing;
    let r = 0.06;
    for masses in [vec![0.0763, 0.0120, 0.1015, 0.0553], vec![0.2, 0.01, 0.02, 0.03, 0.015], vec![0.05, 0.02, 0.02]] {
        let l: Vec<f64> = masses.iter().map(|m| m * r).collect();
        let sum: f64 = l.iter().sum();
        let lo = (2.0 * l.iter().copied().fold(0.0, f64::max) - sum).max(0.0);
        let mut orders = vec![masses.clone()];
        let mut rev = masses.clone();
        rev.reverse();
        orders.push(rev);
        let mut sorted = masses.clone();
        sorted.sort_by(f64::total_cmp);
        orders.push(sorted);
        for m in &orders {
            for k in 0..=40 {
                let mag = 1.1 * sum * k as f64 / 40.0;
                let b = C::from_polar(mag, 0.3 + 0.7 * k as f64);
                let inside = mag >= lo * (1.0 + 1e-9) && mag <= sum * (1.0 - 1e-9);
                let outside = mag < lo * (1.0 - 1e-9) || mag > sum * (1.0 + 1e-9);
                match unequal_balls_balancing(m, r, b) {
                    Some(psi) => {
                        assert!(!outside, "{m:?}: |b| = {mag} outside [{lo}, {sum}] placed {psi:?}");
                        let got: C = psi.iter().zip(m).map(|(a, mj)| C::from_polar(mj * r, *a)).sum();
                        assert!((got - b).norm() <= 1e-12 * sum, "{m:?}: |b| = {mag}: sum {got} vs {b}");
                    }
                    None => assert!(!inside, "{m:?}: |b| = {mag} inside [{lo}, {sum}] but no placement"),
                }
            }
        }
    }
}
