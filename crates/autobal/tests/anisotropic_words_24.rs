//! The planar rotor's state words on supports that differ by direction (audit 23, F1): a
//! periodic orbit with the balls at their capacity limit is "partially balanced", not
//! "semi-balanced", where the race centre E sits a millimetre off the axis, even though that
//! is under 5 % of E's offset without the balls' resultant by the supports' means (which
//! resonates between the split critical speeds). The independent measure is the run's own
//! radius test (`Summary::balanced`: C's mean position in rotor axes over the last revolution
//! within 5 % of `s2`), computed from the trajectory and not from the residual's reference;
//! `stability` at the same constant speed must use the same word (session 15: one state, one
//! word).

use autobal::planar::{simulate, stationary, Drive, PlanarRotor, Settings, Summary};
use autobal::rotor_stability::{stability_over_speed, Rotor, StateKind};
use autobal::spatial::dynamics::RunOutcome;

/// Audit 23's random rotor (config q1): capacity ratio 0.92, `s2` = 1.32 mm, the supports' x
/// and y natural frequencies 223 and 283 rad/s, two balls of their own masses and drags.
fn q1() -> PlanarRotor {
    PlanarRotor {
        m1: 1.9672,
        m2: 0.31215,
        n: 2,
        s1: 0.0014826,
        s2: 0.0013178,
        gamma: -2.12437,
        r: 0.053575,
        k: 117979.37,
        k_y: Some(188878.85),
        c: 5.26987,
        c_y: Some(48.854),
        ball_masses: Some(vec![0.04068, 0.04201]),
        ball_drags: Some(vec![0.12481, 0.19365]),
        c_theta: 0.0,
        i_g: 0.0025,
        ..PlanarRotor::paper()
    }
}

/// A 60 s run at the constant speed `omega` from the default start.
fn run(p: &PlanarRotor, omega: f64) -> Summary {
    let settings = Settings { rtol: 1e-9, atol: 1e-10, ..Settings::new(p, 60.0) };
    let s = simulate(p, &Drive::Speed { omega0: omega }, &settings, |_| true).unwrap();
    assert!(s.status.is_completed(), "{s:?}");
    s
}

/// `stability`'s state at the constant speed `omega`.
fn stability_state(p: &PlanarRotor, omega: f64) -> (StateKind, f64) {
    let r = stability_over_speed(&Rotor::Planar(p.clone()), &[omega]).unwrap();
    (r.points[0].state.expect("a stationary state"), r.points[0].residual.unwrap())
}

#[test]
fn balls_at_their_capacity_limit_on_anisotropic_supports_read_partially_balanced() {
    let p = q1();
    assert!(p.anisotropic());
    let omega = 255.0;
    let s = run(&p, omega);
    eprintln!("{s:?}");
    assert!(s.settled, "{s:?}");
    // C's mean radius is far from s2 (3.6 mm instantaneous, E 1.2 mm off the axis): the run's
    // own radius test fails, so the outcome cannot be balanced (semi-balanced); the balls end
    // together at their capacity nearer the axis than without them (residual below 1)
    assert!(!s.balanced);
    assert_eq!(s.outcome, RunOutcome::PartiallyBalanced, "{s:?}");
    // the residual's reference resonates here: the 5 % of it the old rule allowed is 1.2 mm,
    // more than s2 itself; the allowance now is 5 % of s2
    let scale = stationary::race_offset_scale(&p, omega);
    assert!(0.05 * scale > 0.9 * p.s2, "{scale}");
    assert!(s.residual_unbalance < 0.05 && s.residual_unbalance > stationary::balance_allowance(&p, omega));
    let (state, residual) = stability_state(&p, omega);
    assert_eq!(state.name(), s.outcome.name(), "stability: {state:?}, residual {residual}");
}

#[test]
fn the_semi_balanced_orbit_on_anisotropic_supports_still_reads_semi_balanced() {
    let p = q1();
    // above both critical speeds the run reaches the semi-balanced orbit: its own radius test
    // passes, and both words say so
    let omega = 288.0;
    let s = run(&p, omega);
    eprintln!("{s:?}");
    assert!(s.settled && s.balanced, "{s:?}");
    assert_eq!(s.outcome, RunOutcome::Balanced);
    let (state, residual) = stability_state(&p, omega);
    assert_eq!(state, StateKind::SemiBalanced, "residual {residual}");
    // E's mean offset (the swing's second order) is far inside the allowance: 1.5 µm of the
    // allowance's 66 µm
    let off = residual * stationary::race_offset_scale(&p, omega);
    assert!(off < 0.1 * 0.05 * p.s2, "{off}");
}

#[test]
fn equal_balls_bunched_on_an_anisotropic_orbit_stay_partially_balanced() {
    // review 24a's F3: examples/planar.toml on supports 8e4/1.3e5 N/m, 20/30 kg/s, s2 = 0.1 mm,
    // γ = 1.5, c_psi = 0.01. At 70 rad/s the balls' capacity falls short of the semi-balanced
    // demand by the supports' means (1.033 of it; that state begins at 73.6 rad/s), and the
    // orbit found has its two equal balls bunched at their capacity limit with E 2.3 µm off the
    // axis (2.3 % of s2, inside the allowance): bunched balls are the capacity limit whatever
    // E's offset, as on equal supports (3f95976 called it semi-balanced)
    let p = PlanarRotor { k: 8.0e4, k_y: Some(1.3e5), c: 20.0, c_y: Some(30.0), s2: 1e-4, gamma: 1.5, c_psi: 0.01, ..PlanarRotor::paper() };
    let (state, residual) = stability_state(&p, 70.0);
    assert_eq!(state, StateKind::PartiallyBalanced, "residual {residual}");
    // the semi-balanced orbit above that speed keeps its word
    assert_eq!(stability_state(&p, 84.0).0, StateKind::SemiBalanced);
}

#[test]
fn equal_supports_keep_the_five_percent_allowance() {
    // review 24a's F1: on equal supports the closed forms catch a capacity-limited end, and the
    // allowance stays 5 % of the residual's reference: a fast ramp on examples/planar.toml
    // (350 rad/s at 100 1/s² for 2 s) ends with its balls lagging, E 0.95 % of the reference
    // off the axis (5.5 % of s2): balanced, as sessions 15-23 read it (a 5 %-of-s2 rule read
    // it not balanced)
    let p = PlanarRotor::paper();
    assert!(!p.anisotropic());
    for omega in [100.0, 288.0, 550.0] {
        assert_eq!(stationary::balance_allowance(&p, omega), 0.05);
    }
    let settings = Settings::new(&p, 2.0);
    let s = simulate(&p, &Drive::Acceleration { omega0: 350.0, b: 100.0 }, &settings, |_| true).unwrap();
    eprintln!("{s:?}");
    assert!(s.residual_unbalance > 0.009 && s.residual_unbalance < 0.0125, "{}", s.residual_unbalance);
    assert_eq!(s.outcome, RunOutcome::Balanced, "{s:?}");
    assert!(s.balanced);
}
