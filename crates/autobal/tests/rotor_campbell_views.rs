//! The general route's Campbell views (`autobal::rotor_campbell::{campbell_locked, fixed_view}`)
//! against independent routes: paper 000's 8-state locked pencil and 12-state fixed-axes view on
//! one-plane rotors, the critical speeds of eq (16) for the crossings of `1×`, and a NumPy
//! eigenvalue computation in fixed axes for a rotor on supports that differ by direction.

use autobal::analysis::Kind;
use autobal::rotor_campbell::{campbell_locked, campbell_over_speed, fixed_view, Balls, Group};
use autobal::rotor_stability::Rotor;
use autobal::spatial::campbell::fixed_axes;
use autobal::spatial::critical_speeds::critical_speeds;
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::stability::{campbell, eigenvalues_at, Whirl};
use num_complex::Complex64;

mod common;
use common::{python_with, random_spatial_model, Rng};

#[test]
fn the_locked_diagram_has_the_eigenvalues_of_paper_000s_8_state_model() {
    // Balls locked at balance, damping kept: at every speed each eigenvalue of the general
    // route (the exact AD Jacobian of the locked rotor's nonlinear equations, its balls point
    // masses of the rotor) has a partner among the 8-state pencil's (000 eq (6) without the
    // ball rows, exact inertia tensor) within 1e-10 relative to max(1, |λ|), one to one: both
    // are balanced QR on 8 x 8 matrices equal to round-off, with simple eigenvalues here.
    let mut rng = Rng(31);
    let mut worst = 0.0f64;
    for case in 0..6 {
        let (model, rotor) = random_spatial_model(&mut rng, AnisotropyMethod::Exact, (1.05, 3.0), (0.02, 0.2), (0.02, 0.5));
        let speeds: Vec<f64> = (1..=40).map(|i| 0.1 * i as f64).collect();
        let c = campbell_locked(&Rotor::Spatial(rotor), &speeds).unwrap();
        assert_eq!(c.kind, Kind::Equilibrium);
        assert_eq!(c.lines.len(), 8, "case {case}: 8 states");
        for (k, &w) in speeds.iter().enumerate() {
            assert!(c.failures[k].is_none(), "case {case}, Ω = {w}: {:?}", c.failures[k]);
            let (_, theirs) = eigenvalues_at(&model, w, Balls::Locked).unwrap();
            let mut used = vec![false; theirs.len()];
            for l in &c.lines {
                let p = l.points[k].unwrap();
                assert_ne!(p.group, Group::Balls, "no balls left to move");
                let z = Complex64::new(p.re, p.im);
                let (j, d) = theirs.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, t)| (j, (t - z).norm())).min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
                used[j] = true;
                worst = worst.max(d / z.norm().max(1.0));
                assert!(d < 1e-10 * z.norm().max(1.0), "case {case}, Ω = {w}: λ = {z} has no 8-state partner (nearest {d} off)");
            }
        }
    }
    eprintln!("worst relative difference: {worst:e}");
}

#[test]
fn the_fixed_axes_curves_are_the_12_state_routes() {
    // One plane, two balls free: the fixed-axes view keeps one line of each conjugate pair (and
    // each line that is never complex), so both routes have as many curves, and at each speed the curves' (σ, |ν|) are the same multiset
    // (to 1e-9 relative to max(1, |λ|): the eigenvalues agree to ~1e-14, see
    // tests/rotor_campbell.rs). Each curve's components Ω ± ν are then the same numbers. Where
    // both routes call the same component dominant by a clear margin (share ≥ 0.6 in both; the
    // general route's share counts the rotor's motion, the 12-state route's also the balls'
    // unbalance s) the followed frequency |f| is the same.
    let mut rng = Rng(37);
    let (mut compared, mut followed) = (0, 0);
    for case in 0..5 {
        let (model, rotor) = random_spatial_model(&mut rng, AnisotropyMethod::Exact, (1.05, 3.0), (0.02, 0.2), (0.02, 0.5));
        let rotor = Rotor::Spatial(rotor);
        let speeds: Vec<f64> = (0..120).map(|i| 4.0 * (i as f64 + 0.5) / 120.0).collect();
        let ours = fixed_view(&rotor, Balls::Free, &campbell_over_speed(&rotor, &speeds).unwrap(), &[1]).unwrap();
        let c12 = campbell(&model, &speeds, Balls::Free).unwrap();
        let theirs = fixed_axes(&model, &c12, Balls::Free, &[1]).unwrap();
        assert_eq!(ours.curves.len(), theirs.curves.len(), "case {case}");
        assert!(ours.curves.len() >= 6, "case {case}: at least one curve per conjugate pair");
        for k in 0..speeds.len() {
            let mut used = vec![false; theirs.curves.len()];
            for cv in &ours.curves {
                let p = cv.points[k];
                assert_eq!(p.omega, speeds[k]);
                // the 12-state route's real point carries the largest real eigenvalue left out of
                // its component; the general route's its own, that one beside it (session 29)
                let p = autobal::spatial::campbell::FixedPoint { re: p.paired_re.map_or(p.re, |r| r.max(p.re)), ..p };
                let scale = p.re.hypot(p.nu).max(1.0);
                let (j, d) = theirs
                    .curves
                    .iter()
                    .enumerate()
                    .filter(|(j, _)| !used[*j])
                    .map(|(j, t)| (j, (t.points[k].re - p.re).abs() + (t.points[k].nu.abs() - p.nu.abs()).abs()))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap();
                used[j] = true;
                assert!(d < 1e-9 * scale, "case {case}, Ω = {}: σ {} ν {} has no 12-state curve (nearest {d} off)", speeds[k], p.re, p.nu);
                let q = theirs.curves[j].points[k];
                compared += 1;
                let side = |f: f64, w: f64, nu: f64| (f - (w + nu)).abs() < (f - (w - nu)).abs();
                if p.share >= 0.6 && q.share >= 0.6 && side(p.fixed_frequency, p.omega, p.nu) == side(q.fixed_frequency, q.omega, q.nu) {
                    followed += 1;
                    assert!((p.frequency - q.frequency).abs() < 1e-9 * scale, "case {case}, Ω = {}: |f| {} vs {}", speeds[k], p.frequency, q.frequency);
                }
            }
        }
    }
    eprintln!("{compared} curve points compared, {followed} followed frequencies");
    assert!(followed > compared / 2, "too few clearly dominant components: {followed} of {compared}");
}

#[test]
fn the_locked_undamped_rotors_crossings_of_1x_are_paper_000s_eq_16() {
    // Balls locked, no damping: a forward curve meets 1× where the turning-axes eigenvalue
    // vanishes, det K(Ω) = Δ1 Δ2 = 0 (000 eq (15)-(16)). The crossings are bisected on the
    // spectrum to 1e-13; at an isotropic critical speed the double zero is semisimple (two
    // static deflections), so ν is accurate to round-off there, and at the ends of a divergence
    // range g ~ sqrt(Ω − Ω_K) puts the round-off squared on the speed: 1e-9 relative holds. The
    // 12-state route's crossings of the same diagram are compared too.
    let mut rng = Rng(41);
    let (mut compared, mut worst, mut worst12) = (0, 0.0f64, 0.0f64);
    for case in 0..6 {
        let (model, rotor) = random_spatial_model(&mut rng, AnisotropyMethod::Exact, (1.05, 3.0), (0.0, 0.0), (0.02, 0.5));
        let mut want: Vec<f64> = critical_speeds(&model).speeds.iter().map(|s| s.omega).collect();
        want.dedup_by(|a, b| (*a - *b).abs() < 1e-12 * b.abs());
        let wmax = want.last().copied().unwrap_or(2.0) * 1.3;
        let speeds: Vec<f64> = (0..800).map(|i| wmax * (i as f64 + 0.5) / 800.0).collect();
        let rotor = Rotor::Spatial(rotor);
        let c = campbell_locked(&rotor, &speeds).unwrap();
        let f = fixed_view(&rotor, Balls::Locked, &c, &[1]).unwrap();
        assert_eq!(f.curves.len(), 4, "case {case}: 8 states, 4 modes");
        let forward = |cs: &[autobal::spatial::campbell::CriticalSpeed]| {
            let mut v: Vec<f64> = cs.iter().filter(|k| k.whirl == Whirl::Forward).map(|k| k.omega).collect();
            v.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * b.abs());
            v
        };
        let ours = forward(&f.critical_speeds);
        assert_eq!(ours.len(), want.len(), "case {case}: ours {ours:?}, eq (16) {want:?}");
        for (a, b) in ours.iter().zip(&want) {
            worst = worst.max((a - b).abs() / b);
            assert!((a - b).abs() <= 1e-9 * b, "case {case}: {a} vs eq (16) {b}");
            compared += 1;
        }
        let c12 = campbell(&model, &speeds, Balls::Locked).unwrap();
        let theirs = forward(&fixed_axes(&model, &c12, Balls::Locked, &[1]).unwrap().critical_speeds);
        assert_eq!(theirs.len(), ours.len(), "case {case}: 12-state {theirs:?}, general {ours:?}");
        for (a, b) in ours.iter().zip(&theirs) {
            worst12 = worst12.max((a - b).abs() / b);
        }
    }
    eprintln!("{compared} critical speeds; worst relative difference from eq (16) {worst:e}, from the 12-state route's crossings {worst12:e}");
    assert!(compared >= 10, "only {compared} critical speeds compared");
    assert!(worst12 <= 1e-9, "the 12-state route's crossings differ by {worst12:e}");
}

/// A rigid rotor without balls or unbalance on two supports, stiffer along x by `ratio`.
fn bare_rotor(ratio: f64) -> SpatialRotor {
    let mut r = SpatialRotor::new(
        RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
        vec![Support::isotropic(-0.3, 1e5, 40.0), Support::isotropic(0.2, 1.5e5, 60.0)],
        vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.0, z: 0.1 }],
        vec![BallPlane::point_masses(0.1, 2, 0.02, 0.08, 0.02)],
    );
    r.planes.iter_mut().for_each(|p| p.n = 0);
    r.unbalances.iter_mut().for_each(|u| u.mass = 0.0);
    for s in &mut r.supports {
        s.stiffness[0] *= ratio;
        s.damping[1] *= 1.5;
    }
    r
}

#[test]
fn supports_that_differ_by_direction_against_numpys_fixed_axes_eigenvalues() {
    // The rigid rotor on supports that differ by direction (k_x = 1.1 k_y, c_y = 1.5 c_x) is
    // periodic in turning axes (Floquet exponents) but constant in fixed axes, where
    // M q'' + (C + Ω G) q' + K q = 0 gives the eigenvalues λ_f by NumPy (tests/
    // rotor_campbell_fixed_axes.py, written from the rotor's mass, moments and supports). The
    // multipliers are exp(λ_f T), so each curve's σ is a Re λ_f, and Ω ± ν ≡ ±Im λ_f modulo Ω.
    // Where a mode's whirl is clearly circular (share of the followed component ≥ 0.8), its
    // fixed-axes frequency |f| on the branch of FLOQUET_BRANCH is |Im λ_f| itself. Tolerance:
    // the exponents are good to ~1e-9/T (shooting at rtol 1e-10 over one period), 1e-6 relative
    // to max(|λ|, Ω) is room. No crossing speeds: undefined for Floquet exponents.
    let rotor = bare_rotor(1.1);
    let speeds = [60.0, 150.0, 320.0];
    // no balls to balance: the "locked" diagram, whose stationary state is the centred rotor
    let r = Rotor::Spatial(rotor.clone());
    let c = campbell_locked(&r, &speeds).unwrap();
    assert_eq!(c.kind, Kind::PeriodicOrbit);
    assert!(c.failures.iter().all(|f| f.is_none()), "{:?}", c.failures);
    let f = fixed_view(&r, Balls::Locked, &c, &[1, 2]).unwrap();
    assert!(f.critical_speeds.is_empty());
    assert_eq!(f.curves.len(), 4, "4 coordinates: 4 modes");
    let Some(python) = python_with(&["numpy"]) else { return };
    let supports: Vec<_> = rotor
        .supports
        .iter()
        .map(|s| serde_json::json!({"z": s.z - rotor.z_reference(), "kx": s.stiffness[0], "ky": s.stiffness[1], "cx": s.damping[0], "cy": s.damping[1]}))
        .collect();
    let req =
        serde_json::json!({"m": rotor.total_mass(), "a": rotor.rotor.equatorial_moment, "c": rotor.rotor.polar_moment, "supports": supports, "omegas": speeds});
    let script = format!("{}/tests/rotor_campbell_fixed_axes.py", env!("CARGO_MANIFEST_DIR"));
    let mut child =
        std::process::Command::new(python).arg(script).stdin(std::process::Stdio::piped()).stdout(std::process::Stdio::piped()).spawn().expect("python runs");
    use std::io::Write;
    child.stdin.take().unwrap().write_all(req.to_string().as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (mut circular, mut worst) = (0, 0.0f64);
    for (k, &w) in speeds.iter().enumerate() {
        let lam: Vec<Complex64> =
            v["eigenvalues"][k].as_array().unwrap().iter().map(|z| Complex64::new(z[0].as_f64().unwrap(), z[1].as_f64().unwrap())).collect();
        for cv in &f.curves {
            let p = cv.points[k];
            let tol = 1e-6 * p.re.hypot(p.nu).max(w);
            // a λ_f with the same decay and Im λ_f ≡ Ω + ν (mod Ω)
            let modulo = |x: f64| x - w * (x / w).round();
            let ok = lam.iter().any(|l| (l.re - p.re).abs() < tol && modulo(l.im - (w + p.nu)).abs() < tol);
            assert!(ok, "Ω = {w}: σ {} ν {} matches no fixed-axes eigenvalue of {lam:?}", p.re, p.nu);
            if p.share >= 0.8 {
                circular += 1;
                let d = lam.iter().filter(|l| (l.re - p.re).abs() < tol).map(|l| (l.im.abs() - p.frequency).abs()).fold(f64::INFINITY, f64::min);
                worst = worst.max(d / w);
                assert!(d < tol, "Ω = {w}: |f| = {} (share {}) is no |Im λ_f| of {lam:?}", p.frequency, p.share);
            }
        }
    }
    eprintln!("{circular} nearly circular whirls compared, worst |f| difference {worst:e} Ω");
    assert!(circular >= 4, "only {circular} nearly circular whirls");
}
