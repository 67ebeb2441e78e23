//! The planar run's outcome in the words of the spatial run and of `stability` (issue 18, item
//! 4, session 16): a balancer whose capacity falls short is "partially balanced" with its
//! residual, never "balanced" nor merely "not balanced"; a balanced run reads balanced; balls
//! bunched on the unbalance's side read not balanced; each word equals `stability`'s state word
//! at the same constant speed.

use autobal::planar::{simulate, Drive, PlanarRotor, Settings, Summary};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::dynamics::RunOutcome;

/// Paper 004's rotor with its race centred (`s2 = 0`) and ball mass `m3`.
fn centred(m3: f64) -> PlanarRotor {
    PlanarRotor { s2: 0.0, m3, ..PlanarRotor::paper() }
}

/// A run at the constant speed `omega` for `t_end` seconds from the default start (the balls
/// across the unbalance, C on the axis).
fn run(p: &PlanarRotor, omega: f64, t_end: f64) -> Summary {
    let s = simulate(p, &Drive::Speed { omega0: omega }, &Settings::new(p, t_end), |_| true).unwrap();
    assert!(s.status.is_completed(), "{s:?}");
    s
}

/// `stability`'s state word at the constant speed `omega`.
fn stability_word(p: &PlanarRotor, omega: f64) -> &'static str {
    let r = stability_over_speed(&Rotor::Planar(p.clone()), &[omega]).unwrap();
    r.points[0].state.expect("a stationary state").name()
}

#[test]
fn too_little_ball_mass_reads_partially_balanced_with_its_residual() {
    let p = centred(0.01);
    // the capacity ratio, from the parameters: two balls of 10 g at 60 mm against 1 kg at 3 mm
    let alpha: f64 = 2.0 * 0.01 * 0.06 / (1.0 * 0.003);
    assert!((alpha - 0.4).abs() < 1e-12);
    let omega = 2.0 * p.natural_frequency();
    let s = run(&p, omega, 30.0);
    eprintln!("{s:?}");
    assert_eq!(s.outcome, RunOutcome::PartiallyBalanced, "{s:?}");
    assert!(!s.balanced);
    // the balls bunched opposite the unbalance cancel n m3 r of m1 s1: 1 − α = 0.6 left. With
    // damping they sit on the whirl's line, lagging the unbalance's opposite by the whirl's
    // phase δ (tan δ = 2ζr/(r² − 1) = 0.093 here, ζ = c/(2 sqrt(k m0)) = 0.070, r = 2), which
    // raises |1 + α e^{i(π+δ)}| by ≈ α δ²/(2(1 − α)) = 0.0029: 0.01 holds that and the
    // average's own error (the balls' drift over the last revolution, below 1e-4 here)
    assert!((s.residual_unbalance - (1.0 - alpha)).abs() < 0.01, "{}", s.residual_unbalance);
    assert_eq!(s.outcome.name(), stability_word(&p, omega));
}

#[test]
fn enough_ball_mass_reads_balanced() {
    let p = centred(0.03); // α = 1.2
    let omega = 2.0 * p.natural_frequency();
    let s = run(&p, omega, 30.0);
    eprintln!("{s:?}");
    assert_eq!(s.outcome, RunOutcome::Balanced, "{s:?}");
    assert!(s.balanced);
    assert!(s.residual_unbalance < 1e-3, "{}", s.residual_unbalance);
    assert_eq!(s.outcome.name(), stability_word(&p, omega));
}

#[test]
fn balls_bunched_on_the_unbalances_side_read_not_balanced() {
    let p = centred(0.01);
    let alpha: f64 = 2.0 * 0.01 * 0.06 / (1.0 * 0.003);
    // below the critical speed the balls join the unbalance: 1 + α = 1.4 of it (lagging it by
    // the whirl's phase, tan δ = 2ζr/(1 − r²) = 0.093 at r = 1/2, which lowers |1 + α e^{iδ}|
    // by ≈ α δ²/(2(1 + α)) = 0.0012: 0.01 holds that)
    let omega = 0.5 * p.natural_frequency();
    let s = run(&p, omega, 30.0);
    eprintln!("{s:?}");
    assert_eq!(s.outcome, RunOutcome::NotBalanced, "{s:?}");
    assert!(!s.balanced);
    assert!((s.residual_unbalance - (1.0 + alpha)).abs() < 0.01, "{}", s.residual_unbalance);
    assert_eq!(s.outcome.name(), stability_word(&p, omega));
}
