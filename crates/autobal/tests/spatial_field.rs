//! The spatial rotor at constant speed as an analysis vector field: its exact (forward-mode)
//! Jacobian against central differences of its right-hand side and against the 12-state
//! linear model of paper 000, its period, the family of balanced states, the refusal of real
//! balls; and the spatial simulation with up to the documented 100 balls per plane.

use autobal::analysis::VectorField;
use autobal::drive::Drive;
use autobal::error::Error;
use autobal::ode::System;
use autobal::spatial::dynamics::field::{arc_angles, SpatialField};
use autobal::spatial::dynamics::{simulate, BallPlane, Equations, Initial, PointMass, RigidRotor, Settings, SpatialRotor, Support};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, Pencil};
use autobal::spatial::params::SpatialModel;
use num_complex::Complex64;

mod common;
use common::{general_rotor, random_state, Rng};

/// Central differences of `f` at `x`, step `h_i = 1e-6 max(|x_i|, 0.1)`, row-major.
fn central_differences(dim: usize, x: &[f64], f: impl Fn(&[f64], &mut [f64])) -> Vec<f64> {
    let mut jac = vec![0.0; dim * dim];
    let (mut fp, mut fm) = (vec![0.0; dim], vec![0.0; dim]);
    for c in 0..dim {
        let h = 1e-6 * x[c].abs().max(0.1);
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[c] += h;
        xm[c] -= h;
        f(&xp, &mut fp);
        f(&xm, &mut fm);
        for r in 0..dim {
            jac[r * dim + c] = (fp[r] - fm[r]) / (xp[c] - xm[c]);
        }
    }
    jac
}

/// Largest `|a − b|` of each row over that row's largest `|b|` (floor 1: rows of order one
/// or below compare absolutely), the worst row.
fn worst_row_difference(a: &[f64], b: &[f64], dim: usize) -> f64 {
    (0..dim)
        .map(|r| {
            let row = r * dim..(r + 1) * dim;
            let scale = b[row.clone()].iter().fold(1.0f64, |m, v| m.max(v.abs()));
            a[row.clone()].iter().zip(&b[row]).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
        })
        .fold(0.0, f64::max)
}

#[test]
fn exact_jacobian_equals_central_differences_on_random_rotors_far_from_balance() {
    // (a) 24 random rotors with every feature (two planes, couple unbalance, tilted axis,
    // anisotropic supports, gravity across the axis), every third with the tilt locked, random
    // states far from balance (tilts to 0.4 rad, balls anywhere, fast ball rates), random times
    // (the field is periodic there). Central differences with h ~ 1e-6 of the coordinate are
    // good to ~1e-9 of a row's scale here (truncation h² f''' ~ 1e-12, round-off
    // eps |f|/h ~ 1e-10 with |f| up to ~1e3); 1e-6 leaves room and still catches any wrong
    // term (a missing derivative is of order one of the row).
    let mut rng = Rng(11);
    for i in 0..24 {
        let mut r = general_rotor(&mut rng, [3, 2]);
        r.lock_tilt = i % 3 == 2;
        let omega = rng.range(-30.0, 30.0);
        let field = SpatialField::new(&r, omega).unwrap();
        assert!(field.period().is_some());
        let drive = Drive::Speed { omega0: omega };
        let eq = Equations::new(&r, &drive);
        let y = random_state(&mut rng, eq.coords(), r.lock_tilt);
        let x = field.reduced_state(&y);
        let t = rng.range(0.0, 1.0);
        let dim = field.dim();
        assert_eq!(dim, 2 * (if r.lock_tilt { 2 } else { 4 } + 5));
        let mut jac = vec![0.0; dim * dim];
        field.jacobian(t, &x, &mut jac);
        let fd = central_differences(dim, &x, |x, f| field.rhs(t, x, f));
        let d = worst_row_difference(&jac, &fd, dim);
        assert!(d <= 1e-6, "rotor {i}: worst row difference {d:e}");
        // the reduced field is the full equations' under Drive::Speed at φ = Ω t
        let mut f = vec![0.0; dim];
        field.rhs(t, &x, &mut f);
        let mut dy = vec![0.0; eq.dim()];
        eq.rhs(t, &field.full_state(t, &x), &mut dy);
        assert_eq!(f, field.reduced_state(&dy));
    }
}

#[test]
fn full_state_jacobian_equals_central_differences_under_every_drive() {
    // The full equations' exact Jacobian (spin angle and rate included) under a motor (torque
    // with a slope in φ̇), a constant torque and a speed ramp (prescribed φ̈): same tolerance
    // and reason as above.
    let mut rng = Rng(12);
    for i in 0..12 {
        let mut r = general_rotor(&mut rng, [3, 2]);
        r.lock_tilt = i % 4 == 3;
        let drive = match i % 3 {
            0 => Drive::Motor { omega0: 0.0, torque: rng.range(0.5, 5.0), omega_idle: rng.range(20.0, 40.0), t_off: None },
            1 => Drive::Torque { omega0: 0.0, torque: rng.range(-5.0, 5.0), t_off: None },
            _ => Drive::Acceleration { omega0: rng.range(-20.0, 20.0), b: rng.range(-10.0, 10.0) },
        };
        let eq = Equations::new(&r, &drive);
        let y = random_state(&mut rng, eq.coords(), r.lock_tilt);
        let t = rng.range(0.0, 1.0);
        let dim = eq.dim();
        let mut jac = vec![0.0; dim * dim];
        eq.exact_jacobian(t, &y, &mut jac).unwrap();
        let fd = central_differences(dim, &y, |y, f| eq.rhs(t, y, f));
        let d = worst_row_difference(&jac, &fd, dim);
        assert!(d <= 1e-6, "case {i}: worst row difference {d:e}");
    }
}

/// A random dimensionless model with masses (two balls), retried until the rotor exists
/// (tests/spatial_dynamics.rs).
fn random_model(rng: &mut Rng, capacity: (f64, f64)) -> (SpatialModel, SpatialRotor) {
    common::random_spatial_model(rng, AnisotropyMethod::Exact, capacity, (0.0, 0.2), (0.01, 0.5))
}

/// Unbalance and balls at balance in the composite's principal frame (the linear model's
/// frame), as tests/spatial_dynamics.rs: the unbalance at `−ψ`, the balls at `−ψ + π ± acos(1/E)`.
fn at_balance(model: &SpatialModel, rotor: &mut SpatialRotor) -> Vec<f64> {
    let ms = model.masses.unwrap();
    let e = ms.capacity();
    let d = 2.0 / (e * e) - 1.0;
    let z = ms.a_m0() + ms.a_m() * d;
    let psi = if z < 0.0 { std::f64::consts::FRAC_PI_2 } else { 0.0 };
    rotor.unbalances[0].angle = -psi;
    let beta = (1.0 / e).acos();
    vec![-psi + std::f64::consts::PI - beta, -psi + std::f64::consts::PI + beta]
}

/// The eigenvalues of the `n x n` row-major `a` by nalgebra's Schur iteration, after a balancing
/// step (Parlett-Reinsch: diagonal similarity by powers of two until each row and column have
/// comparable norms; exact in floating point), which ../shared/DEPENDENCIES.md records that
/// nalgebra needs on matrices in physical units: without it the iteration on this test's
/// Jacobian did not converge once the right-hand side's rounding changed (a fast sin_cos).
fn eigenvalues(a: &[f64], n: usize) -> Vec<Complex64> {
    let mut m = nalgebra::DMatrix::from_row_slice(n, n, a);
    loop {
        let mut changed = false;
        for i in 0..n {
            let c: f64 = (0..n).filter(|&k| k != i).map(|k| m[(k, i)].abs()).sum();
            let r: f64 = (0..n).filter(|&k| k != i).map(|k| m[(i, k)].abs()).sum();
            if c == 0.0 || r == 0.0 {
                continue;
            }
            // Numerical Recipes' balanc (radix 2): f with c f ≈ r / f
            let (mut c, s, mut f) = (c, c + r, 1.0);
            while c < r / 2.0 {
                f *= 2.0;
                c *= 4.0;
            }
            while c > r * 2.0 {
                f /= 2.0;
                c /= 4.0;
            }
            if (c + r) / f < 0.95 * s {
                changed = true;
                for k in 0..n {
                    m[(i, k)] /= f;
                    m[(k, i)] *= f;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let s = nalgebra::linalg::Schur::try_new(m, f64::EPSILON, 100_000).expect("nalgebra converges");
    s.complex_eigenvalues().iter().map(|z| Complex64::new(z.re, z.im)).collect()
}

/// Largest distance from an eigenvalue of `a` to its partner in `b` (greedy nearest matching).
fn spectrum_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut used = vec![false; b.len()];
    let mut worst = 0.0f64;
    for x in a {
        let (k, d) = b.iter().enumerate().filter(|(k, _)| !used[*k]).map(|(k, y)| (k, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
        used[k] = true;
        worst = worst.max(d);
    }
    worst
}

#[test]
fn at_balance_the_eigenvalues_are_those_of_the_linear_model_of_paper_000() {
    // (b) one plane, two balls, isotropic supports, no gravity: at the balanced state the
    // exact Jacobian (12 states: ξ, η, δ, θ, ψ1, ψ2 and rates) is similar to the 12-state
    // matrix of paper 000 eq (6) with the exact anisotropy (tests/spatial_dynamics.rs checks
    // the matrices to 1e-7 by differences). Both are exact, so only round-off separates the
    // spectra: 1e-10 of the largest |λ| (the eigenvalues are simple and well separated here).
    let mut rng = Rng(3);
    for _ in 0..20 {
        let (model, mut rotor) = random_model(&mut rng, (1.02, 3.0));
        let psi = at_balance(&model, &mut rotor);
        let omega = rng.range(0.1, 4.0);
        let field = SpatialField::new(&rotor, omega).unwrap();
        assert_eq!(field.period(), None);
        let mut x = vec![0.0; 12];
        x[4..6].copy_from_slice(&psi);
        let mut jac = vec![0.0; 144];
        field.jacobian(0.0, &x, &mut jac);
        let lin = Pencil::new(&model, omega, Balls::Free).unwrap().state_matrix();
        let lin: Vec<f64> = (0..12).flat_map(|i| (0..12).map(move |j| lin[i][j])).collect();
        let (ours, theirs) = (eigenvalues(&jac, 12), eigenvalues(&lin, 12));
        let scale = theirs.iter().fold(0.0f64, |m, z| m.max(z.norm()));
        let d = spectrum_distance(&ours, &theirs);
        assert!(d <= 1e-10 * scale, "Ω = {omega}: spectra differ by {d:e} (scale {scale}), model {model:?}");
        assert_eq!(field.structural_zeros(&x), 0, "two balls balancing one plane: no family");
    }
}

#[test]
fn the_field_is_periodic_exactly_when_something_turns_against_the_rotor() {
    // (c) isotropic supports and gravity along the axis: autonomous; gravity across the axis:
    // period 2π/|Ω|; a support differing in stiffness or damping between x and y alone: π/|Ω|
    // (the support force repeats after half a revolution, tests/half_period.rs).
    let mut rng = Rng(4);
    let (_, base) = random_model(&mut rng, (1.2, 2.0));
    let omega = -1.7;
    let period = |r: &SpatialRotor| SpatialField::new(r, omega).unwrap().period();
    assert_eq!(period(&base), None);
    let mut r = base.clone();
    r.gravity = [0.0, 0.0, -9.81];
    assert_eq!(period(&r), None);
    let t = Some(2.0 * std::f64::consts::PI / 1.7);
    r.gravity = [0.0, -9.81, 0.0];
    assert_eq!(period(&r), t);
    let mut with_gravity = r.clone();
    with_gravity.supports[1].stiffness[1] *= 1.1;
    assert_eq!(period(&with_gravity), t, "gravity across the axis with unequal supports: a revolution");
    let half = Some(std::f64::consts::PI / 1.7);
    let mut r = base.clone();
    r.supports[1].stiffness[1] *= 1.1;
    assert_eq!(period(&r), half);
    let mut r = base.clone();
    r.supports[0].damping[0] += 0.01;
    assert_eq!(period(&r), half);
    r.lock_tilt = true;
    assert_eq!(period(&r), half);
    // at rest nothing turns
    assert_eq!(SpatialField::new(&r, 0.0).unwrap().period(), None);
}

/// An SI rotor with `n` balls in the unbalance's plane, isotropic supports, no gravity.
fn si_rotor(n: u32) -> SpatialRotor {
    SpatialRotor::new(
        RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
        vec![Support::isotropic(-0.3, 1e5, 20.0), Support::isotropic(0.3, 1.5e5, 30.0)],
        vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.0, z: 0.1 }],
        vec![BallPlane::point_masses(0.1, n as usize, 0.02 / n as f64 * 2.0, 0.08, 0.01)],
    )
}

/// The eigenvalues of the field's Jacobian at `x`, their largest modulus, and how many lie
/// within `1e-9` of it, and the smallest modulus of the others.
fn zero_eigenvalues(field: &SpatialField, x: &[f64]) -> (usize, f64, f64) {
    let n = field.dim();
    let mut jac = vec![0.0; n * n];
    field.jacobian(0.0, x, &mut jac);
    // the QR iteration's deflation test is relative to the diagonal, which a multiple zero
    // eigenvalue leaves at zero: shift by σ (the spectrum of J + σ I is J's plus σ)
    // and scale the rates by a typical frequency w (similarity diag(1, 1/w)): the SI matrix's
    // entries span 1 to 1e5, and unscaled the iteration does not converge
    let w = jac.iter().fold(0.0f64, |m, v| m.max(v.abs())).sqrt();
    let sigma = 0.37 * w;
    for i in 0..n {
        for j in 0..n {
            let (ri, rj) = (i >= n / 2, j >= n / 2);
            jac[i * n + j] *= match (ri, rj) {
                (false, true) => w,
                (true, false) => 1.0 / w,
                _ => 1.0,
            };
        }
        jac[i * n + i] += sigma;
    }
    let ev: Vec<Complex64> = eigenvalues(&jac, n).into_iter().map(|z| z - sigma).collect();
    let scale = ev.iter().fold(0.0f64, |m, z| m.max(z.norm()));
    let zeros = ev.iter().filter(|z| z.norm() <= 1e-9 * scale).count();
    let others = ev.iter().map(|z| z.norm()).filter(|&a| a > 1e-9 * scale).fold(f64::INFINITY, f64::min);
    (zeros, scale, others)
}

#[test]
fn with_three_or_more_balls_in_one_plane_the_balanced_states_form_a_family() {
    // (d) n balls cancelling the unbalance in its own plane: every ball is in equilibrium
    // wherever it sits and the rotor needs only Σ m R e^{iψ} = −m0 R0, so the balanced states
    // form an (n − 2)-dimensional family and the Jacobian has n − 2 zero eigenvalues (along
    // the family; the rates' partners are the drag's −h/m). Zero means below 1e-9 of the
    // largest |λ| (round-off is ~1e-14 of it), and the gap to the others is wide (> 1e-6).
    for n in [3usize, 4, 5, 8] {
        let rotor = si_rotor(n as u32);
        let field = SpatialField::new(&rotor, 250.0).unwrap();
        let x = field.balanced_guess().unwrap();
        let mut f = vec![0.0; field.dim()];
        field.rhs(0.0, &x, &mut f);
        let fmax = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // accelerations ~ Ω² × (residual unbalance / mass) with a residual of round-off
        assert!(fmax <= 1e-9, "n = {n}: the guess is not stationary, |f| = {fmax:e}");
        assert_eq!(field.structural_zeros(&x), n - 2, "n = {n}");
        let (zeros, scale, others) = zero_eigenvalues(&field, &x);
        assert_eq!(zeros, n - 2, "n = {n}: zero eigenvalues");
        assert!(others > 1e-6 * scale, "n = {n}: no clear gap ({others:e} vs scale {scale:e})");
        // off balance: no family
        let mut off = x.clone();
        off[0] = 1e-3;
        assert_eq!(field.structural_zeros(&off), 0);
        let mut moved = x.clone();
        moved[4] += 0.1; // a ball moved alone: the unbalance is no longer cancelled
        assert_eq!(field.structural_zeros(&moved), 0);
    }
}

#[test]
fn two_planes_cancel_static_and_couple_unbalance_with_a_family_of_dimension_n_minus_4() {
    // Two planes (3 + 3 balls) against a static plus couple unbalance and a tilted principal
    // axis (Rodrigues et al. 2008): the closed-form guess is stationary, and the balanced
    // states form a family of dimension 6 − 4 = 2 (4 conditions: static and couple).
    let mut rng = Rng(21);
    let mut r = general_rotor(&mut rng, [3, 2]);
    r.gravity = [0.0; 3];
    for s in &mut r.supports {
        s.stiffness[1] = s.stiffness[0];
        s.damping[1] = s.damping[0];
    }
    r.planes[0].n = 3;
    r.planes[1].n = 3;
    for p in &mut r.planes {
        p.ball_mass = 0.2;
    }
    let field = SpatialField::new(&r, 40.0).unwrap();
    assert_eq!(field.period(), None);
    let x = field.balanced_guess().expect("capacity suffices");
    let mut f = vec![0.0; field.dim()];
    field.rhs(0.0, &x, &mut f);
    let fmax = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(fmax <= 1e-10, "the two-plane guess is not stationary, |f| = {fmax:e}");
    assert_eq!(field.structural_zeros(&x), 2);
    let (zeros, scale, others) = zero_eigenvalues(&field, &x);
    assert_eq!(zeros, 2);
    assert!(others > 1e-6 * scale);
    // too little capacity: no guess
    let mut small = r.clone();
    small.planes[0].ball_mass = 1e-5;
    assert!(SpatialField::new(&small, 40.0).unwrap().balanced_guess().is_none());
}

#[test]
fn arc_angles_sum_to_the_target_and_refuse_too_little_capacity() {
    // The arc's first moment equals the target to round-off, for any n, any direction, and
    // at the extremes (zero target: evenly spread; full capacity: all balls together).
    let mut rng = Rng(5);
    for n in 1..=12usize {
        for _ in 0..20 {
            let mr = rng.range(0.1, 2.0);
            let frac = if n == 1 { 1.0 } else { rng.range(0.0, 1.0) };
            let dir = rng.range(-3.0, 3.0);
            let target = [n as f64 * mr * frac * dir.cos(), n as f64 * mr * frac * dir.sin()];
            let psi = arc_angles(n, mr, target).unwrap();
            let sum = psi.iter().fold([0.0, 0.0], |s, p| [s[0] + mr * p.cos(), s[1] + mr * p.sin()]);
            let err = (sum[0] - target[0]).hypot(sum[1] - target[1]);
            assert!(err <= 1e-13 * n as f64 * mr, "n = {n}: {err:e}");
        }
        assert!(arc_angles(n, 1.0, [n as f64 * 1.001, 0.0]).is_none());
    }
    let even = arc_angles(4, 1.0, [0.0, 0.0]).unwrap();
    let s = even.iter().fold([0.0, 0.0], |s, p| [s[0] + p.cos(), s[1] + p.sin()]);
    assert!(s[0].hypot(s[1]) < 1e-14);
    assert!(arc_angles(1, 1.0, [0.5, 0.0]).is_none());
}

#[test]
fn real_balls_have_no_linearisation() {
    // (e) contact or rolling resistance: a dead zone and resting contacts, no derivative.
    let mut r = si_rotor(3);
    r.planes[0].physics.contact = true;
    let e = SpatialField::new(&r, 100.0).unwrap_err();
    assert!(matches!(e, Error::NoLinearisation { .. }), "{e}");
    assert!(!e.to_string().contains('\n'));
    let drive = Drive::Speed { omega0: 100.0 };
    let eq = Equations::new(&r, &drive);
    let mut jac = vec![0.0; eq.dim() * eq.dim()];
    let y = vec![0.0; eq.dim()];
    assert!(matches!(eq.exact_jacobian(0.0, &y, &mut jac), Err(Error::NoLinearisation { .. })));
    let mut r = si_rotor(3);
    r.planes[0].physics.rolling_resistance = 1e-3;
    assert!(matches!(SpatialField::new(&r, 100.0), Err(Error::NoLinearisation { .. })));
}

#[test]
fn the_simulation_takes_up_to_the_documented_100_balls_per_plane() {
    // The spatial limits table (docs/reference/robustness.md, limits.rs) gives 100 balls per plane; the
    // simulation refused more than 7 in all planes. 8 and 100 run; 101 is refused with the
    // limit's own message.
    let settings = Settings { method: Default::default(), t_end: 0.05, dt: 0.01, rtol: 1e-6, atol: 1e-9 };
    let drive = Drive::Speed { omega0: 300.0 };
    for n in [8u32, 100] {
        let r = si_rotor(n);
        let s = simulate(&r, &drive, &Initial::at_rest(&r), &settings, |_| true).unwrap();
        assert!(s.final_amplitude.is_finite() && s.t_end == 0.05, "n = {n}");
    }
    let r = si_rotor(101);
    let e = simulate(&r, &drive, &Initial::at_rest(&r), &settings, |_| true).unwrap_err();
    assert_eq!(e, autobal::limits::check_count("balancer.balls", 101).unwrap_err());
    assert!(e.to_string().starts_with("balancer.balls: 101 exceeds the limit of 100"), "{e}");
    // the second plane is named as such, and the same limit holds per plane
    let mut two = si_rotor(100);
    let mut p2 = two.planes[0];
    p2.z = -0.1;
    two.planes.push(p2);
    two.validate().unwrap();
    two.planes[1].n = 101;
    assert!(two.validate().unwrap_err().to_string().starts_with("balancer2.balls: 101 exceeds the limit of 100"));
}
