//! Basins of a linear rotor (issue 19 item 4): the Jeffcott preset's runs from a grid of ball
//! start angles against the native planar model's runs from the same angles.

use autobal::control::Control;
use autobal::drive::Drive;
use autobal::linear_rotor::basins::{angle_grid, basins, residual_unbalance};
use autobal::linear_rotor::partial::length_scale;
use autobal::linear_rotor::runup::RunSettings;
use autobal::linear_rotor::spec::LinearRun;
use autobal::linear_rotor::LinearRotor;
use autobal::ode::Method;
use autobal::planar::{PlanarRotor, Settings};
use autobal::spatial::dynamics::simulate::BALANCE_TOLERANCE;
use autobal::spatial::dynamics::RunOutcome;

/// Each end of the preset's 3 × 3 grid at constant speed above the critical one equals the
/// planar model's run from the same start: the balls' final angles to 1e-7 rad and the whirl
/// radius to 1e-7 of the unbalanced eccentricity (both integrate at rtol 1e-10; run-ups agree
/// to 1e-8 of the peak, tests/linear_rotor_config.rs; 3 s at constant speed lets the angles'
/// error grow at most tenfold while the motion settles). One rule for "balanced": each end is
/// balanced exactly where its own run's outcome is (`simulate`'s word), and that word agrees
/// with the native planar run's (the same rule on the planar model's own measures, a second
/// route). The run's race whirl, on which the word is decided, is the end's radius over its
/// whirl with the balls spread, `|me Ω² / (k − m_t Ω² + i c Ω)|` (`m_t = m1 + m2 + n m3`, the
/// balls riding with the node) in closed form; a balanced end's race whirls at most 0.05
/// (`BALANCE_TOLERANCE`) of that, so its radius is at most 0.05 of the closed form (plus 1e-7 s1
/// for the integration). Balanced ends have a small static residual: with the node whirling at `r`, the
/// force balance far above the critical speed leaves `|me + Σ m_b R e^{iψ}| ≈ m_t r`, so the
/// residual is at most ~0.05 · 1.19 (the free whirl over `me/m_t` at 2.5 ω_n) plus the
/// damping's and the stiffness's share `(c/Ω + k/Ω²) r`: 0.1 allows them.
#[test]
fn the_presets_basins_end_where_the_planar_runs_end() {
    let p = PlanarRotor { s2: 0.0, ..PlanarRotor::paper() };
    let rotor = LinearRotor::from_planar(&p).unwrap();
    let wn = p.natural_frequency();
    let (t_end, dt) = (3.0, 0.01);
    let drive_speed = 2.5 * wn;
    let drive = Drive::Speed { omega0: drive_speed };
    let settings = RunSettings { t_end, dt, rtol: 1e-10, atol: 1e-12, method: Method::Auto, max_steps: 10_000_000, max_wall_s: None, physical_nodes: None };
    let run = LinearRun { rotor: rotor.clone(), drive: drive.clone(), settings, default_drive: false };
    let starts = angle_grid(&rotor, 3, "n").unwrap();
    let ends = basins(&run, &starts, &Control::none()).unwrap();
    assert!(ends.is_complete());
    let mut balanced = 0;
    for (start, end) in starts.iter().zip(&ends.value) {
        let end = end.as_ref().unwrap();
        assert_eq!(&end.psi0, start);
        let mut s = Settings::new(&p, t_end);
        s.dt = dt;
        s.rtol = 1e-10;
        s.atol = 1e-12;
        s.psi0 = start.clone();
        let mut last = None;
        let planar = autobal::planar::simulate(&p, &drive, &s, |x| {
            last = Some((x.x.hypot(x.y), x.psi.clone()));
            true
        })
        .unwrap();
        let (r, psi) = last.unwrap();
        for (a, b) in end.psi.iter().zip(&psi) {
            let mut d = a - b;
            d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            assert!(d.abs() < 1e-7, "start {start:?}: ψ {a} vs {b}");
        }
        assert!((end.final_amplitude - r).abs() < 1e-7 * p.s1, "start {start:?}: r {} vs {r}", end.final_amplitude);
        // from the wrapped angles: the same to round-off (the residual is relative to m e)
        assert!((end.residual_unbalance - residual_unbalance(&rotor, &end.psi)).abs() < 1e-12);
        // one rule: the run's own word, and the planar run's
        assert_eq!(end.balanced, end.summary.outcome == RunOutcome::Balanced, "start {start:?}: {end:?}");
        assert_eq!(end.balanced, planar.outcome == RunOutcome::Balanced, "start {start:?}: {end:?} vs planar {:?}", planar.outcome);
        // the run's race whirl, the measure its word is decided on (the race centre's mean over
        // the last revolution over its whirl with the balls spread, by the linear route's own
        // stationary solve), against the closed form: the end's radius over the free whirl. The
        // centre stands still in turning axes at a constant speed (the balls drift < 1e-10 rad a
        // revolution here), so they agree to the integration's 1e-7 s1 (above) plus the run's
        // floor, a whirl below 1e-6 ℓ reading 0 (ℓ = `partial::length_scale`)
        let w = drive_speed;
        let mt = p.m1 + p.m2 + p.n as f64 * p.m3;
        let free = p.m1 * p.s1 * w * w / (p.k - mt * w * w).hypot(p.c * w);
        let floor = (1e-6 * length_scale(&rotor) + 1e-7 * p.s1) / free;
        let race = end.summary.race_whirl.unwrap();
        assert!((race - end.final_amplitude / free).abs() <= floor, "start {start:?}: race whirl {race} vs r/free {}", end.final_amplitude / free);
        if end.balanced {
            balanced += 1;
            assert!(end.final_amplitude <= BALANCE_TOLERANCE * free + 1e-7 * p.s1, "start {start:?}: r {} vs free whirl {free}", end.final_amplitude);
            assert!(end.residual_unbalance < 0.1, "start {start:?}: {end:?}");
        }
    }
    assert!(balanced > 0, "no run balanced: {:?}", ends.value);
    // fewer than two balls, or a grid outside 2..=1000, are refused naming the field
    assert_eq!(angle_grid(&rotor, 1, "--n").unwrap_err().field(), Some("--n"));
    let mut one = rotor.clone();
    one.balancers[0].balls = 1;
    assert_eq!(angle_grid(&one, 3, "--n").unwrap_err().field(), Some("linear_rotor.balancer"));
    // cancelled: no run is reported as if it had ended
    let c = Control::new();
    c.cancel();
    let out = basins(&run, &starts, &c).unwrap();
    assert!(!out.is_complete() && out.value.iter().all(Option::is_none));
}
