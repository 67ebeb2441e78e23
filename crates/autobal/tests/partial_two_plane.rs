//! The two-plane partially balanced state (issue 18 items 1 and 4): a two-plane rotor whose
//! plane nearer the unbalance cannot carry its share, solved as a stationary state with its
//! stability (autobal::rotor_partial), against the end of a time simulation of the full
//! equations (ball angles, residual unbalance, whirl radius) and against the balls'
//! equilibrium condition (each ball of a bunched plane along the rotor's displacement there).

use autobal::analysis::Verdict;
use autobal::drive::Drive;
use autobal::rotor_partial::partially_balanced;
use autobal::rotor_stability::{Rotor, StateKind};
use autobal::spatial::dynamics::field::SpatialField;
use autobal::spatial::dynamics::{simulate, BallPlane, Equations, Initial, PointMass, RigidRotor, Settings, SpatialRotor, Support};
use std::f64::consts::PI;

/// tests/two_plane.rs's long rotor (10 kg, supports ±0.3 m, planes ±0.15 m with two balls on a
/// race of 0.08 m), its unbalance 0.01 kg at 0.1 m moved to z = 0.075 m: the plane at +0.15
/// must carry 3/4 of it (`b_2 = −(ζ_1 − ζ_u)/(ζ_1 − ζ_2) s0`, 0.75e-3 kg·m) and the one at −0.15 a
/// quarter. Balls of 3.75 g: each plane's capacity `2 m R` = 0.6e-3 kg·m, **0.8 of the share of
/// the plane at +0.15** (a shortfall of 0.15e-3 kg·m, 15 % of the unbalance), 2.4 times that of
/// the other; together 1.2 times the static unbalance, so the shortfall is in the couple.
fn short_rotor() -> SpatialRotor {
    let support = |z: f64| Support { z, stiffness: [1e5, 1e5], damping: [40.0, 40.0] };
    let plane = |z: f64| BallPlane { z, n: 2, ball_mass: 3.75e-3, race_radius: 0.08, drag: 0.05, physics: Default::default() };
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.0, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
        supports: vec![support(-0.3), support(0.3)],
        unbalances: vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.0, z: 0.075 }],
        planes: vec![plane(-0.15), plane(0.15)],
        gravity: [0.0; 3],
        spin_drag: 0.0,
        lock_tilt: false,
    }
}

/// Above both rigid-body critical speeds (translation ~140 rad/s, conical ~250: tests/two_plane.rs).
const SPEED: f64 = 400.0;

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(2.0 * PI) - PI
}

#[test]
fn the_short_plane_is_bunched_and_the_state_is_where_a_run_ends() {
    let r = short_rotor();
    // no balanced state: the closed form refuses it
    assert!(SpatialField::new(&r, SPEED).unwrap().balanced_guess().is_none());
    let states = partially_balanced(&Rotor::Spatial(r.clone()), SPEED).unwrap();
    for s in &states {
        eprintln!(
            "{:?} {:?} psi {:?} planes {:?} static {} couple {:?} whirl {:?} α {} {:?}",
            s.start, s.kind, s.psi, s.planes, s.residual_static_fraction, s.residual_couple_fraction, s.whirl, s.stability.abscissa, s.stability.verdict
        );
    }
    // the stable state (seen: α = −3.99 1/s; static residual 0.154 of the unbalance, couple
    // 0.294 of its own): the short plane at +0.15 bunched, the other plane's balls apart
    let s = &states[0];
    assert_eq!(s.kind, StateKind::PartiallyBalanced);
    assert_eq!(s.stability.verdict, Verdict::Stable, "{s:?}");
    let cap = 2.0 * 3.75e-3 * 0.08;
    assert!((s.planes[1].share - 0.75e-3).abs() < 1e-12 && (s.planes[1].capacity - cap).abs() < 1e-15, "{:?}", s.planes);
    assert!(s.planes[1].bunched && !s.planes[0].bunched, "{:?}", s.planes);
    // the residual cannot vanish: the static and the couple cannot both be cancelled
    assert!(s.residual_static_fraction > 0.01 && s.residual_couple_fraction.unwrap() > 0.01, "{s:?}");
    // the bunched placement of both planes (the closed form's guess for a short plane) is a
    // stationary state too, but unstable: a run does not end there
    assert!(states[1..].iter().all(|o| o.stability.verdict != Verdict::Stable), "one stable state: {states:?}");

    // second route, the balls' equilibrium in turning axes (rotor_partial's module docs): the
    // bunched plane's balls lie along the rotor's displacement d there (ψ = arg d, the far
    // side), and where the balls sit apart the displacement nearly vanishes (seen: 1.3e-5 of
    // the other plane's; not exactly 0: the race's tilt adds a small force along the race)
    let f = SpatialField::new(&r, SPEED).unwrap();
    let drive = Drive::Speed { omega0: SPEED };
    let eq = Equations::new(&r, &drive);
    let y = f.full_state(0.0, &s.x);
    let d: Vec<[f64; 2]> = r.planes.iter().map(|p| eq.displacement_at(&y, p.z)).collect();
    let size = |d: [f64; 2]| d[0].hypot(d[1]);
    assert!(size(d[0]) < 1e-4 * size(d[1]), "plane 1 (balls apart): |d| = {}, plane 2: {}", size(d[0]), size(d[1]));
    for psi in &s.psi[2..] {
        assert!(wrap(psi - d[1][1].atan2(d[1][0])).abs() < 1e-6, "ψ = {psi} against arg d = {}", d[1][1].atan2(d[1][0]));
    }

    // third route, the full equations in time: constant speed from rest with the balls spread
    // (the simulator's default start), 30 s. The state decays at α = −3.99 1/s: e^{−120} after
    // 30 s, so the end state is the stationary one to the integration's tolerance (rtol 1e-10,
    // atol 1e-13 m); 1e-6 (rad, or of the scale) leaves room for its accumulated error (seen:
    // ball angles 1e-13 apart, residuals 5e-14)
    let t_end = 30.0;
    let set = Settings { method: Default::default(), t_end, dt: 1e-2, rtol: 1e-10, atol: 1e-13 };
    let mut last = None;
    let sum = simulate(&r, &drive, &Initial::at_rest(&r), &set, |x| {
        last = Some(x.clone());
        true
    })
    .unwrap();
    let last = last.unwrap();
    eprintln!(
        "run: psi {:?} whirl {:?} residual {} couple {:?} drift {:?}",
        last.psi, last.amplitude_planes, sum.residual_unbalance, sum.residual_couple, sum.ball_drift
    );
    for (a, b) in last.psi.iter().zip(&s.psi) {
        assert!(wrap(a - b).abs() < 1e-6, "ball angles: run {:?}, state {:?}", last.psi, s.psi);
    }
    let scale = s.whirl.iter().fold(0.0f64, |m, v| m.max(*v));
    for (a, b) in last.amplitude_planes.iter().zip(&s.whirl) {
        assert!((a - b).abs() < 1e-6 * scale, "whirl at the planes: run {:?}, state {:?}", last.amplitude_planes, s.whirl);
    }
    assert!(
        (sum.residual_unbalance - s.residual_static_fraction).abs() < 1e-6,
        "residual: run {}, state {}",
        sum.residual_unbalance,
        s.residual_static_fraction
    );
    let (rc, sc) = (sum.residual_couple.unwrap(), s.residual_couple_fraction.unwrap());
    assert!((rc - sc).abs() < 1e-6, "couple: run {rc}, state {sc}");
}

#[test]
fn one_plane_short_of_capacity_leaves_at_least_the_shortfall() {
    // the Jeffcott rotor with two 20 g balls: capacity 2 m3 r = 2.4e-3 kg·m against m1 s1 =
    // 3e-3, so |m1 s1 + m3 r Σ e^{iψ}| ≥ 0.6e-3 whatever the angles: a residual of at least 0.2,
    // reached with the balls together exactly opposite; at 2 ω_n (damping ratio 0.069) the
    // whirl lags that by ~5°, a residual of ~0.216
    let p = autobal::planar::PlanarRotor { s2: 0.0, m3: 0.02, ..autobal::planar::PlanarRotor::paper() };
    let w = 2.0 * p.natural_frequency();
    let states = partially_balanced(&Rotor::Planar(p), w).unwrap();
    let s = &states[0];
    assert_eq!((s.kind, s.stability.verdict), (StateKind::PartiallyBalanced, Verdict::Stable), "{s:?}");
    assert!(s.planes[0].bunched, "{:?}", s.planes);
    assert!(s.residual_static_fraction > 0.2 - 1e-9 && s.residual_static_fraction < 0.25, "{}", s.residual_static_fraction);
}

/// The speed scan (`stability` of the general route) follows the stable partially balanced
/// state, not the unstable one with both planes bunched: its point at 400 rad/s equals
/// `partially_balanced`'s stable state (the growth rate to 1e-6 1/s, the same Newton on the same
/// equations from a start in the same basin), and says `partially_balanced`.
#[test]
fn the_speed_scan_follows_the_stable_partial_state() {
    let r = Rotor::Spatial(short_rotor());
    let states = partially_balanced(&r, SPEED).unwrap();
    let stable = &states[0];
    assert_eq!(stable.stability.verdict, Verdict::Stable);
    let scan = autobal::rotor_stability::stability_over_speed(&r, &[SPEED]).unwrap();
    let p = &scan.points[0];
    assert_eq!(p.verdict, Some(Verdict::Stable), "{p:?}");
    let a = p.abscissa.unwrap();
    assert!((a - stable.stability.abscissa).abs() < 1e-6, "scan {a} against rotor_partial {}", stable.stability.abscissa);
}
