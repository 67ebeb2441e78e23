//! A run on a rotor whose unbalance is at round-off level (far below
//! `rotor_stability::NO_UNBALANCE` = 1e-6 of the balls' capacity `Σ m_b R`) reads as the same
//! run without unbalance: the same verdict, the residual over the capacity, no couple to judge.
//! `stability` calls such a rotor one without unbalance (`Rotor::has_unbalance` false, its
//! residuals over the capacity: `ResidualScale::Capacity`), and a run must mean the same by
//! it: both use `rotor_stability`'s one rule (`unbalance_scale`).
//!
//! The second route is the rotor with the unbalance exactly zero, whose residual every version
//! measures over the capacity. Main at 04de1c6 divided the spatial run's static residual by
//! `|s0|` wherever `s0 ≠ 0`, however small, and judged any couple beside it: on
//! examples/spatial_two_plane.toml with a 1e-18 kg m unbalance (1e-16 of the capacity) it read
//! "not balanced" with a residual of 4.6e9 and a couple of 5.0e5 "of the unbalance's", where
//! the run without unbalance reads balanced, 4.8e-7. The linear run had the rule already
//! (its test guards it: checked to fail with its scale set to `|s0|` wherever `s0 ≠ 0`).
//! The planar run measures its residual as `stability`'s planar route does, the race centre's
//! distance over the whirl without balls (`planar::stationary::race_offset_scale`), which a
//! round-off unbalance leaves small (a ratio of whirls that scale alike): not this rule.

use autobal::rotor_stability::{ResidualScale, Rotor};
use autobal::spatial::dynamics::RunOutcome;

/// examples/spatial_two_plane.toml at a constant 1400 rad/s for 4 s from the balls spread
/// evenly, without its couple mass and with its first unbalance mass `m` kg (at 0.1 m, in the
/// first balancer plane at z = 0.45 m, off the reference point: a static and a couple
/// unbalance alike): its rotor and run summary.
fn two_plane_run(m: f64) -> (Rotor, autobal::spatial::dynamics::Summary) {
    let mut root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two_plane").unwrap();
    autobal::config::set_number(&mut root, "unbalance.mass", m).unwrap();
    autobal::config::set_number(&mut root, "couple.mass", 0.0).unwrap();
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    let settings = autobal::spatial::dynamics::Settings { t_end: 4.0, ..sim.settings.clone() };
    let s = autobal::spatial::dynamics::simulate(&sim.rotor, &autobal::drive::Drive::Speed { omega0: 1400.0 }, &sim.initial, &settings, |_| true).unwrap();
    assert!(s.status.is_completed(), "{s:?}");
    (Rotor::Spatial(sim.rotor), s)
}

/// The spatial run with a 1e-18 kg m unbalance (1e-17 kg at 0.1 m; the capacity 4 × 0.02 kg ×
/// 0.12 m = 9.6e-3 kg m) against the run with none: `stability` says no unbalance for both;
/// both read balanced (the balls' swing under gravity, ~5e-7 of their capacity), no couple
/// judged, the residuals equal to 1e-3 of themselves. (The unbalance changes the balls'
/// resultant by 1e-16 of the capacity; the integrations' paths (rtol 1e-8) differ by their
/// step choices: measured 1.0e-7 relative; the bound leaves a factor 1e4 and lies ~1e16 below
/// main's 4.6e9.)
#[test]
fn a_spatial_run_with_a_round_off_unbalance_reads_as_one_without() {
    let (rotor, tiny) = two_plane_run(1e-17);
    let (zero_rotor, zero) = two_plane_run(0.0);
    // stability's word: no unbalance, residuals over the capacity
    assert!(!rotor.has_unbalance() && !zero_rotor.has_unbalance());
    assert_eq!(rotor.residual_scale(), ResidualScale::Capacity);
    assert_eq!(zero.outcome, RunOutcome::Balanced, "{zero:?}");
    assert_eq!(tiny.outcome, RunOutcome::Balanced, "{tiny:?}");
    assert!(tiny.balanced);
    assert_eq!((tiny.residual_couple, zero.residual_couple), (None, None), "{tiny:?}");
    assert!(zero.residual_unbalance > 0.0 && zero.residual_unbalance < 1e-5, "{zero:?}");
    assert!(
        (tiny.residual_unbalance - zero.residual_unbalance).abs() <= 1e-3 * zero.residual_unbalance,
        "{} against {}",
        tiny.residual_unbalance,
        zero.residual_unbalance
    );
}

/// The linear run on paper 004's rotor (race centred, two 30 g balls on a 0.06 m race: the
/// capacity 3.6e-3 kg m) as a linear rotor, at 2 ω_n for 10 s, with its unbalance `m e` set to
/// 1e-18 kg m against 0: the same verdict (balanced) and the same residual, over the capacity,
/// to 1e-9 absolute: each run's balls end at their integration's noise (rtol 1e-9 on the
/// angles: a resultant of at most ~1e-9 of the capacity; measured 5.6e-11 and 4.5e-11), the
/// unbalance is 2.8e-16 of the capacity. Checked to fail: with `ending`'s scale `|s0|`
/// wherever `s0 ≠ 0` (the spatial run's old rule) the residual reads ~2e5 "of the unbalance".
#[test]
fn a_linear_run_with_a_round_off_unbalance_reads_as_one_without() {
    use autobal::linear_rotor::runup::{simulate, RunSettings};
    let p = autobal::planar::PlanarRotor { s2: 0.0, m3: 0.03, ..autobal::planar::PlanarRotor::paper() };
    let w = 2.0 * p.natural_frequency();
    let run = |me: f64| {
        let mut r = autobal::linear_rotor::LinearRotor::from_planar(&p).unwrap();
        r.unbalances[0].me = me;
        let settings = RunSettings {
            t_end: 10.0,
            dt: 0.05,
            rtol: 1e-9,
            atol: 1e-12,
            method: autobal::ode::Method::Auto,
            max_steps: 10_000_000,
            max_wall_s: None,
            physical_nodes: None,
        };
        let s = simulate(&r, &autobal::drive::Drive::Speed { omega0: w }, &settings, &autobal::control::Control::none(), |_| true).unwrap();
        (Rotor::Linear(r), s)
    };
    let (rotor, tiny) = run(1e-18);
    let (_, zero) = run(0.0);
    assert!(!rotor.has_unbalance());
    assert_eq!(rotor.residual_scale(), ResidualScale::Capacity);
    assert_eq!(zero.outcome, RunOutcome::Balanced, "{zero:?}");
    assert_eq!(tiny.outcome, RunOutcome::Balanced, "{tiny:?}");
    assert!(zero.residual_unbalance < 1e-9, "{zero:?}");
    assert!((tiny.residual_unbalance - zero.residual_unbalance).abs() <= 1e-9, "{} against {}", tiny.residual_unbalance, zero.residual_unbalance);
}
