//! The branch of the Floquet exponents in the general route's Campbell diagram (audit20 F9):
//! a periodic orbit's `Im ρ` is defined modulo `2π/T`, and the diagram puts each mode at the
//! harmonic of its motion that a fixed observer sees largest (`rotor_campbell::FLOQUET_BRANCH`).
//! Checked against a closed form (a rigid rotor on supports that differ by direction, which in
//! fixed axes is time-invariant), against the same rotor under a negligible gravity (which makes
//! the period a whole revolution but moves nothing a fixed observer sees), and for continuity
//! over speed.

use autobal::rotor_campbell::{campbell_locked, campbell_over_speed, CampbellPoint, Whirl};
use autobal::rotor_stability::Rotor;
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
use autobal::spatial::stability::Group;

mod common;

/// examples/spatial_two_plane.toml (two ball planes, supports 30 % / 20 % stiffer in y) with
/// the gravity `gravity`.
fn two_plane(gravity: &str) -> Rotor {
    let mut root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value(gravity)).unwrap();
    Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor)
}

/// The rotor's modes (not the balls', not structural) at speed index `k`.
fn rotor_modes(c: &autobal::rotor_campbell::RotorCampbell, k: usize) -> Vec<CampbellPoint> {
    c.lines.iter().filter_map(|l| l.points[k]).filter(|p| !p.structural && p.group != Group::Balls).collect()
}

#[test]
fn a_negligible_gravity_leaves_the_fixed_axes_frequencies_where_they_were() {
    // audit20 F9: at 1400 rad/s the translation mode with Re ρ = −15.9665 read 536.813 rad/s
    // forward without gravity and 1936.813 (= 536.813 + Ω) with g = 0.001 m/s² or 9.81 m/s²
    // (Rayleigh quotient's branch); a run's FFT shows it at ~534-537 rad/s (resolution 15.7
    // rad/s). Gravity makes the period 2π/Ω instead of π/Ω and moves the state by its sag, which
    // moves the exponents by ~1e-9 relative here (the rotor's supports are linear): the fixed-axes
    // frequencies must agree to 1e-6 relative (the exponents' Floquet accuracy is ~1e-9 / T,
    // and the sag's effect is below 1e-7 of |f| on every mode measured), far below a branch's Ω.
    let omega = 1400.0;
    let base = campbell_over_speed(&two_plane("[0.0, 0.0, 0.0]"), &[omega]).unwrap();
    let reference = rotor_modes(&base, 0);
    assert!(reference.len() >= 8, "{reference:?}");
    let target = reference.iter().find(|p| (p.re + 15.9665).abs() < 1e-3 && p.group == Group::Translation).expect("the translation mode at Re −15.9665");
    assert!((target.fixed_frequency - 536.8133).abs() < 1e-3, "{target:?}");
    assert_eq!(target.whirl, Whirl::Forward);
    for g in ["[0.0, -0.001, 0.0]", "[0.0, -9.81, 0.0]"] {
        let c = campbell_over_speed(&two_plane(g), &[omega]).unwrap();
        let got = rotor_modes(&c, 0);
        assert_eq!(got.len(), reference.len(), "g = {g}");
        for p in &got {
            let q =
                reference.iter().min_by(|a, b| ((a.re - p.re).abs() + (a.im - p.im).abs()).total_cmp(&((b.re - p.re).abs() + (b.im - p.im).abs()))).unwrap();
            assert!((p.fixed_frequency - q.fixed_frequency).abs() <= 1e-6 * q.fixed_frequency.abs(), "g = {g}: {p:?} vs without gravity {q:?}");
            assert!((p.im - q.im).abs() <= 1e-6 * omega, "g = {g}: the branch {p:?} vs {q:?}");
            assert_eq!(p.whirl, q.whirl, "g = {g}: {p:?} vs {q:?}");
        }
    }
}

/// A rigid rotor (tilt locked) on supports stiffer along x by `ratio`, no unbalance, its two
/// balls locked opposite each other (point masses of the rotor: its mass is the same in every
/// direction): in fixed axes `M ẍ + c ẋ + k_x x = 0`, `M ÿ + c ẏ + k_y y = 0`.
fn bare_rotor(ratio: f64) -> (SpatialRotor, f64, f64, f64, f64) {
    let mut r = SpatialRotor::new(
        RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
        vec![Support::isotropic(-0.3, 1e5, 40.0), Support::isotropic(0.3, 1.5e5, 60.0)],
        vec![PointMass { mass: 0.0, radius: 0.1, angle: 0.0, z: 0.1 }],
        vec![BallPlane::point_masses(0.1, 2, 0.02, 0.08, 0.02)],
    );
    r.lock_tilt = true;
    for s in &mut r.supports {
        s.stiffness[0] *= ratio;
    }
    let m = r.total_mass();
    let kx: f64 = r.supports.iter().map(|s| s.stiffness[0]).sum();
    let ky: f64 = r.supports.iter().map(|s| s.stiffness[1]).sum();
    let c: f64 = r.supports.iter().map(|s| s.damping[0]).sum();
    (r, m, kx, ky, c)
}

#[test]
fn a_rigid_rotor_on_unequal_supports_whirls_at_its_fixed_axes_frequencies() {
    // Closed form: the rotor is the same in every direction, so in fixed axes its equations are
    // constant: x and y oscillate apart at the damped frequencies ω_x,y = sqrt(k/M − (c/2M)²)
    // with decay c/2M, whatever the speed. In turning axes the field is periodic (T = π/Ω) and
    // the exponents are defined modulo 2Ω: the branch rule must find ±ω_x and ±ω_y at every
    // speed (each mode whirls on a line: equal forward and backward components, the pick goes
    // to the forward one). Tolerance 1e-7 relative: the multipliers are good to ~1e-9 (shooting
    // and monodromy at rtol 1e-10), a wrong branch is off by 2Ω ≥ 100 rad/s.
    let (r, m, kx, ky, c) = bare_rotor(1.3);
    let decay = c / (2.0 * m);
    let want = [(kx / m - decay * decay).sqrt(), (ky / m - decay * decay).sqrt()];
    let speeds = [50.0, 137.0, 300.0, 700.0, 1500.0];
    let diagram = campbell_locked(&Rotor::Spatial(r), &speeds).unwrap();
    assert_eq!(diagram.kind, autobal::analysis::Kind::PeriodicOrbit);
    for (k, &omega) in speeds.iter().enumerate() {
        let pts = rotor_modes(&diagram, k);
        assert_eq!(pts.len(), 4, "Ω = {omega}: {pts:?} {:?} {:?}", diagram.failures, diagram.lines);
        for p in &pts {
            let d = want.iter().map(|w| (p.fixed_frequency - w).abs()).fold(f64::INFINITY, f64::min);
            assert!(d <= 1e-7 * want[0], "Ω = {omega}: f = {} vs ω_x,y = {want:?} ({p:?})", p.fixed_frequency);
            assert!((p.re + decay).abs() <= 1e-7 * want[0], "Ω = {omega}: Re ρ = {} vs −c/2M = {}", p.re, -decay);
            assert_eq!(p.whirl, Whirl::Forward, "Ω = {omega}: {p:?}");
        }
        for w in want {
            assert_eq!(pts.iter().filter(|p| (p.fixed_frequency - w).abs() <= 1e-7 * w).count(), 2, "Ω = {omega}: {pts:?}");
        }
    }
}

#[test]
fn the_fixed_axes_frequencies_are_continuous_over_speed() {
    // audit20 F9: with g = 0.001 m/s² the Rayleigh branch put translation modes Ω or 2Ω off at 7
    // of 10 speeds (1300 rad/s: −475.0 backward → 825.0 forward). Away from crossings each rotor
    // mode's fixed-axes frequency moves by a few rad/s per 200 rad/s of speed (the supports are
    // linear, the balls light: 542 → 531 rad/s over 100-1900 rad/s); a branch jump moves it by
    // a multiple of Ω ≥ 100. Each translation mode's |f| must lie within 0.15 × ΔΩ = 30 rad/s
    // of a mode's |f| at the previous speed.
    let speeds: Vec<f64> = (0..10).map(|k| 100.0 + 200.0 * k as f64).collect();
    let c = campbell_over_speed(&two_plane("[0.0, -0.001, 0.0]"), &speeds).unwrap();
    let mut compared = 0;
    for k in 1..speeds.len() {
        // the previous speed's modes of any group: near the balls' own frequencies a rotor mode
        // mixes with theirs (at 500 rad/s the translation is labelled balls)
        let prev: Vec<CampbellPoint> = c.lines.iter().filter_map(|l| l.points[k - 1]).filter(|p| !p.structural).collect();
        let now = rotor_modes(&c, k);
        for p in now.iter().filter(|p| p.group == Group::Translation) {
            let d = prev.iter().map(|q| (q.fixed_frequency.abs() - p.fixed_frequency.abs()).abs()).fold(f64::INFINITY, f64::min);
            assert!(
                d <= 30.0,
                "Ω = {}: translation at f = {} is {d} from every rotor mode at Ω = {} ({:?})",
                speeds[k],
                p.fixed_frequency,
                speeds[k - 1],
                prev.iter().map(|q| q.fixed_frequency).collect::<Vec<_>>()
            );
            compared += 1;
        }
    }
    assert!(compared >= 10, "{compared}");
}

#[test]
fn every_mode_of_a_gyroscopic_rotor_on_unequal_supports_reads_its_fixed_axes_frequency() {
    // The tilt free (gyroscopic coupling: the modes whirl on ellipses, neither circular nor on
    // a line), no balls, no unbalance, supports 1.3× stiffer along x, the right one's damping
    // 1.5× along y: constant in fixed axes, where M q'' + (C + Ω G) q' + K q = 0 gives the
    // eigenvalues λ_f by NumPy (tests/rotor_campbell_fixed_axes.py, written from the rotor's
    // mass, moments and supports). Every rotor mode's point must read a signed f with
    // |f| = |Im λ_f| for a λ_f of the same decay: the largest component of an elliptical whirl
    // at frequency ω is at +ω or −ω, and any other branch is 2Ω away. Tolerance as
    // tests/rotor_campbell_views.rs: 1e-6 of max(|λ|, Ω) (exponents good to ~1e-9/T).
    let mut rotor = SpatialRotor::new(
        RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
        vec![Support::isotropic(-0.3, 1e5, 40.0), Support::isotropic(0.2, 1.5e5, 60.0)],
        vec![PointMass { mass: 0.0, radius: 0.1, angle: 0.0, z: 0.1 }],
        vec![BallPlane::point_masses(0.1, 0, 0.02, 0.08, 0.02)],
    );
    rotor.supports[0].stiffness[0] *= 1.3;
    rotor.supports[1].stiffness[0] *= 1.3;
    rotor.supports[1].damping[1] *= 1.5;
    let speeds = [50.0, 137.0, 300.0, 700.0, 1500.0];
    let c = campbell_locked(&Rotor::Spatial(rotor.clone()), &speeds).unwrap();
    assert_eq!(c.kind, autobal::analysis::Kind::PeriodicOrbit);
    assert!(c.failures.iter().all(|f| f.is_none()), "{:?}", c.failures);
    let Some(python) = common::python_with(&["numpy"]) else { return };
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
    let mut compared = 0;
    for (k, &w) in speeds.iter().enumerate() {
        let lam: Vec<(f64, f64)> = v["eigenvalues"][k].as_array().unwrap().iter().map(|z| (z[0].as_f64().unwrap(), z[1].as_f64().unwrap())).collect();
        let pts = rotor_modes(&c, k);
        assert_eq!(pts.len(), 8, "Ω = {w}: 8 states, 8 exponents: {pts:?}");
        for p in &pts {
            let tol = 1e-6 * p.re.hypot(p.im).max(w);
            let d = lam.iter().filter(|l| (l.0 - p.re).abs() < tol).map(|l| (l.1.abs() - p.fixed_frequency.abs()).abs()).fold(f64::INFINITY, f64::min);
            assert!(d < tol, "Ω = {w}: f = {} (σ {}) is no |Im λ_f| of {lam:?}", p.fixed_frequency, p.re);
            compared += 1;
        }
    }
    assert_eq!(compared, 40);
}
