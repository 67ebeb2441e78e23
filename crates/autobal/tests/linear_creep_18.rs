//! The linear rotor's run does not call a slow creep away from an unstable stationary state
//! settled (issue 18 item 4, "verdicts that mean what they say"; item 6(e): the verdict against
//! a time simulation, growth at the computed rate).
//!
//! The model is paper 004's rotor with a centred race as a linear rotor (one node, the
//! unbalance in the balancer plane: `LinearRotor::from_planar`), ω_n = 288 rad/s, two balls of
//! 0.03 kg: below the critical speed its balanced state exists (capacity 3.6e-3 kg m against
//! 3e-3) and is unstable, by its exact linear stability; so is the state with the two balls
//! opposite each other on the line of the race's whirl.

use autobal::analysis::{stability, stationary, NewtonOptions, VectorField, Verdict};
use autobal::control::Control;
use autobal::drive::Drive;
use autobal::linear_rotor::runup::{simulate_from, RunSettings, RunSummary};
use autobal::linear_rotor::{Frame, LinearRotor, LinearRotorField};
use autobal::ode::Method;
use autobal::planar::PlanarRotor;
use autobal::rotor_stability::{unstable_isolated_state, Rotor, StateKind};
use autobal::spatial::dynamics::simulate::{drift_tolerance, BALANCE_TOLERANCE};
use autobal::spatial::dynamics::RunOutcome;

fn jeffcott() -> (PlanarRotor, LinearRotor) {
    let p = PlanarRotor { s2: 0.0, m3: 0.03, ..PlanarRotor::paper() };
    let r = LinearRotor::from_planar(&p).unwrap();
    (p, r)
}

/// A run at the constant speed `w` for `t_end` s from the balls at `psi0`, with its samples'
/// `(t, ψ)` every `dt`.
fn run(rotor: &LinearRotor, w: f64, psi0: &[f64], t_end: f64, dt: f64) -> (RunSummary, Vec<(f64, Vec<f64>)>) {
    let settings = RunSettings { t_end, dt, rtol: 1e-10, atol: 1e-12, method: Method::Auto, max_steps: 10_000_000, max_wall_s: None, physical_nodes: None };
    let mut samples = vec![];
    let s = simulate_from(rotor, &Drive::Speed { omega0: w }, &settings, Some(psi0), &Control::none(), |x| {
        samples.push((x.t, x.psi.clone()));
        true
    })
    .unwrap();
    (s, samples)
}

/// The least-squares slope of `ln δ` against `t` over the samples with `t` in `[a, b]`.
fn slope(points: &[(f64, f64)], a: f64, b: f64) -> f64 {
    let p: Vec<(f64, f64)> = points.iter().filter(|(t, _)| (a..=b).contains(t)).map(|(t, d)| (*t, d.ln())).collect();
    let n = p.len() as f64;
    let (mt, ml) = (p.iter().map(|q| q.0).sum::<f64>() / n, p.iter().map(|q| q.1).sum::<f64>() / n);
    p.iter().map(|q| (q.0 - mt) * (q.1 - ml)).sum::<f64>() / p.iter().map(|q| (q.0 - mt).powi(2)).sum::<f64>()
}

/// At 0.5 ω_n the balanced state is unstable (growth rate 0.2425/s, the next ball mode
/// 0.1094/s, the structure's modes decaying at ~20/s). A run from the balls 1e-7 rad off it
/// for 40 s ends with them ~2e-3 rad away, the race whirl and the balls' drift far below the
/// run's tolerances: the rule alone (main before this check) says balanced, settled. Now it
/// is not settled, with a warning giving the growth rate, and the deviation does grow at that
/// rate: the slope of `ln |ψ − ψ*|` over `[25, 40]` s equals the largest eigenvalue's real part
/// to 1 % (measured 2.3e-4). Why 1 %: the second unstable mode's share `r` of the deviation
/// falls as `e^{−(0.2425 − 0.1094) t}` and biases the local slope by `0.133 r/(1 + r)`; the
/// slope over `[10, 20]` s (0.2430, printed) puts `r` at 0.0036 at 15 s, so 1.3e-4 at 25 s,
/// 5e-4 of the rate; the nonlinearity adds a share of the order of the deviation (below 3e-3
/// at the end); the integration's error (rtol 1e-10 on angles of ~3 rad, 3e-10) is 100x below
/// the smallest deviation fitted (1e-7 e^{0.2425 · 25} = 4e-5).
/// Checked to fail: without the creep check in `simulate_from` the outcome is balanced; with
/// the rate off by 2 % the slope test fails.
#[test]
fn a_creep_away_from_the_unstable_balanced_state_is_not_settled() {
    let (p, r) = jeffcott();
    let w = 0.5 * p.natural_frequency();
    let rate = unstable_isolated_state(&Rotor::Linear(r.clone()), w).expect("the balanced state is unstable at 0.5 ω_n");
    assert!((rate - 0.2425).abs() < 1e-3, "growth rate {rate}");
    let (_, state) = autobal::rotor_campbell::stationary_at(&Rotor::Linear(r.clone()), w).unwrap();
    let nd = r.dofs();
    let star = state.x[nd..nd + 2].to_vec();
    let start: Vec<f64> = star.iter().map(|a| a + 1e-7).collect();
    let (s, samples) = run(&r, w, &start, 40.0, 0.05);
    // what the rule alone decides on: the race whirl and the drift, both far inside the
    // tolerances (balanced, settled, as main said)
    let wn = r.natural_frequencies(&[], true).unwrap()[0];
    assert!(s.race_whirl.unwrap() < 0.1 * BALANCE_TOLERANCE, "{s:?}");
    assert!(s.ball_drift.unwrap() < 1e-2 * drift_tolerance(w, wn), "{s:?}");
    // now: not settled, the warning with the growth rate
    assert_eq!(s.outcome, RunOutcome::NotSettled, "{s:?}");
    assert!(!s.balanced && !s.settled);
    assert_eq!(s.creep_rate, Some(rate));
    assert!(s.warnings.iter().any(|m| m.contains("unstable") && m.contains(&format!("{rate:.4e}"))), "{:?}", s.warnings);
    // the deviation grows at the computed rate
    let dev: Vec<(f64, f64)> = samples.iter().map(|(t, psi)| (*t, psi.iter().zip(&star).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt())).collect();
    let last = dev.last().unwrap().1;
    assert!(last < 1e-2 && last > 1e-4, "still a small deviation at the end: {last}");
    let fitted = slope(&dev, 25.0, 40.0);
    eprintln!("deviation at the end {last}, fitted slope {fitted}, computed {rate}, over [10, 20] {}", slope(&dev, 10.0, 20.0));
    assert!((fitted / rate - 1.0).abs() < 0.01, "fitted {fitted} vs computed {rate}");
}

/// Where the balanced state is stable a run that settles on it reads balanced, with no
/// warning: the check leaves a true end alone (2 ω_n, from the balls 0.05 rad off it: the
/// transient decays at 7.1/s, 10 s is e^{-71}).
#[test]
fn a_run_on_the_stable_balanced_state_stays_balanced() {
    let (p, r) = jeffcott();
    let w = 2.0 * p.natural_frequency();
    assert_eq!(unstable_isolated_state(&Rotor::Linear(r.clone()), w), None);
    let (_, state) = autobal::rotor_campbell::stationary_at(&Rotor::Linear(r.clone()), w).unwrap();
    let nd = r.dofs();
    let start: Vec<f64> = state.x[nd..nd + 2].iter().map(|a| a + 0.05).collect();
    let (s, _) = run(&r, w, &start, 10.0, 0.05);
    assert_eq!(s.outcome, RunOutcome::Balanced, "{s:?}");
    assert!(s.warnings.is_empty() && s.creep_rate.is_none(), "{s:?}");
}

/// The second creep (issue item 4's last sentence: where the end depends on the start, the
/// warning says so): two balls spread evenly start opposite each other, next to the state with
/// the balls on the line of the race's whirl, which is not balanced and unstable. At 0.3 ω_n it
/// leaves that state at 0.0558/s (its next mode decaying at 0.018/s), slowly enough that a
/// 10 s run passes the drift test with the race whirling as without the balls (the rule alone:
/// "not balanced", settled, as main said). Now not settled, with the state's growth rate
/// (Newton from the end state, its exact linear stability: the rate to 1e-9, round-off of
/// one eigenvalue solve at a state found to 1e-12) and a warning that the end depends on the
/// start. Checked to fail: without the check the outcome is not balanced.
#[test]
fn a_creep_away_from_opposite_balls_is_not_settled_and_says_it_depends_on_the_start() {
    let (p, r) = jeffcott();
    let w = 0.3 * p.natural_frequency();
    let (s, _) = run(&r, w, &[0.0, std::f64::consts::PI], 10.0, 0.05);
    let wn = r.natural_frequencies(&[], true).unwrap()[0];
    assert!((s.race_whirl.unwrap() - 1.0).abs() < 0.05, "{s:?}");
    assert!(s.ball_drift.unwrap() < drift_tolerance(w, wn), "{s:?}");
    assert_eq!(s.outcome, RunOutcome::NotSettled, "{s:?}");
    // the state the balls sit next to, from the balls opposite: Newton, exact linear stability
    let f = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
    let nd = r.dofs();
    let mut x = vec![0.0; f.dim()];
    x[nd + 1] = std::f64::consts::PI;
    let opposite = stationary(&f, &x, &NewtonOptions::default()).unwrap();
    assert_eq!(autobal::linear_rotor::partial::state_kind(&f, &opposite.x), StateKind::NotBalanced);
    let lin = stability(&f, &opposite).unwrap();
    assert_eq!(lin.verdict, Verdict::Unstable);
    let rate = s.creep_rate.unwrap();
    assert!((rate / lin.abscissa - 1.0).abs() < 1e-9 && (rate - 0.0558).abs() < 1e-3, "{rate} vs {}", lin.abscissa);
    assert!(s.warnings.iter().any(|m| m.contains("not balanced") && m.contains("depends on the start")), "{:?}", s.warnings);
}

/// A torque drive with a polar moment below the balls' own `Σ n m_b R²` is refused naming
/// `linear_rotor.polar_inertia`, with the reason (1e-9 kg m² ran for minutes, stiff beyond use:
/// the spin against the balls' drag relaxes at drag / I_p); the balls' moment itself is taken.
/// Checked to fail: without the check `RunUpSystem::new` accepts 1e-9.
#[test]
fn a_torque_drive_lighter_than_its_balls_is_refused() {
    let (p, mut r) = jeffcott();
    let balls = p.n as f64 * p.m3 * p.r * p.r;
    let drive = Drive::Torque { omega0: 100.0, torque: 0.5, t_off: None };
    r.polar_inertia = 1e-9;
    let e = autobal::linear_rotor::runup::RunUpSystem::new(&r, &drive).err().expect("refused").to_string();
    assert!(e.starts_with("linear_rotor.polar_inertia:") && e.contains("below the balls' own moment"), "{e}");
    // a prescribed speed needs no polar moment
    assert!(autobal::linear_rotor::runup::RunUpSystem::new(&r, &Drive::Speed { omega0: 100.0 }).is_ok());
    r.polar_inertia = balls;
    assert!(autobal::linear_rotor::runup::RunUpSystem::new(&r, &drive).is_ok());
}
