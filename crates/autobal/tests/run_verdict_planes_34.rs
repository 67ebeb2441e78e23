//! A spatial run's verdict where no balanced state exists although the balls' total capacity
//! exceeds the static unbalance (walk 34, D1): two balancer planes against a pure couple, each
//! plane short of its share, and one plane against a couple. `simulate` compared the total
//! capacity `Σ n m R` with the static unbalance `|s0|` alone and called such runs "balanced"
//! with a residual couple of 1.6 %; `stability` (each plane's capacity against its share,
//! Rodrigues et al. 2008 eq (21): `b_1 + b_2 = −s0`, `ζ_1 b_1 + ζ_2 b_2 = −c0`) called the same
//! state partially balanced.
//!
//! The rotor (walk 34's cp.toml): 20 kg, supports 2e6/3e6 N/m at z = 0 and 0.5 m; a couple of
//! two 0.001 kg m unbalances in opposite directions, at the two balancer planes (z = 0.45 and
//! 0.05 m); two balls of mass `m` on races of R = 0.12 m in each plane. Each plane must supply
//! 0.001 kg m, so a balanced state exists for `2 m R >= 0.001`, `m >= 0.0041667` kg; below it
//! each plane's two balls sit together and leave a residual couple of `1 − 2 m R / 0.001` of the
//! couple (0.016 at m = 0.0041), above it the run balances.

use autobal::spatial::dynamics::simulate::{simulate_summary, RunOutcome};

const CP: &str = r#"
[rotor]
mass = 20.0
equatorial_moment = 0.60
polar_moment = 0.15
z = 0.25
[supports]
z_left = 0.0
z_right = 0.50
stiffness_left = 2.0e6
stiffness_right = 3.0e6
damping_left = 300.0
damping_right = 300.0
[unbalance]
mass = 0.010
radius = 0.10
angle = 0.0
[couple]
mass = 0.010
radius = 0.10
angle = 3.141592653589793
z = 0.05
[balancer]
z = 0.45
balls = 2
ball_mass = 0.0045
race_radius = 0.12
drag = 0.5
[balancer2]
z = 0.05
balls = 2
ball_mass = 0.0045
race_radius = 0.12
drag = 0.5
[drive]
kind = "schedule"
schedule_of = "speed"
schedule = [[0.0, 1400.0], [5.0, 1400.0]]
t_end = 5.0
[integration]
method = "dop853"
rtol = 1e-9
atol = 1e-11
dt = 0.001
"#;

/// The run's summary with the given entries set.
fn run(sets: &[(&str, &str)]) -> autobal::spatial::dynamics::simulate::Summary {
    let mut root = autobal::config::parse(CP, "cp").unwrap();
    for (k, v) in sets {
        autobal::config::set(&mut root, k, autobal::config::parse_value(v)).unwrap();
    }
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    simulate_summary(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, &autobal::control::Control::none()).unwrap()
}

/// Each plane 1.6 % short of the couple's share: partially balanced, with the residual couple
/// of the closed form `1 − 2 m R / 0.001` = 0.016 within 5e-4 (the 5 s run has settled to
/// within its drift tolerance; measured 0.01611 at 5 s, 0.01607 at 20 s, `stability`'s state
/// 0.0160667); the static residual stays small (the couple's two halves cancel statically).
/// Fails on main at d4c2c0d ("balanced").
#[test]
fn two_planes_short_of_a_couples_share_are_partially_balanced() {
    let s = run(&[("balancer.ball_mass", "0.0041"), ("balancer2.ball_mass", "0.0041")]);
    assert_eq!(s.outcome, RunOutcome::PartiallyBalanced, "{s:?}");
    assert!(!s.balanced);
    let closed = 1.0 - 2.0 * 0.0041 * 0.12 / 0.001;
    let couple = s.residual_couple.expect("the rotor has a couple");
    assert!((couple - closed).abs() <= 5e-4, "residual couple {couple} against the closed form {closed}");
}

/// Plane 1 alone short of its share (a static unbalance in plane 1 only: its share is the
/// whole 0.001 kg m, plane 2's none), while the total capacity 4 m R = 0.00197 kg m is twice
/// the static unbalance: partially balanced. Fails on main ("balanced").
#[test]
fn one_plane_short_of_its_share_is_partially_balanced() {
    let s = run(&[("balancer.ball_mass", "0.0041"), ("balancer2.ball_mass", "0.0041"), ("couple.mass", "0.0")]);
    assert_eq!(s.outcome, RunOutcome::PartiallyBalanced, "{s:?}");
}

/// The control: above the threshold (m = 0.0045 kg, each plane 8 % above its share) the same
/// run balances, residuals within the run's tolerance.
#[test]
fn planes_above_their_shares_balance() {
    let s = run(&[]);
    assert_eq!(s.outcome, RunOutcome::Balanced, "{s:?}");
    assert!(s.residual_couple.unwrap() < 1e-3, "{s:?}");
}
