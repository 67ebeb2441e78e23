//! The spatial and linear runs' summaries must not depend on where in the last revolution the
//! run stops (issue 18 item 4; the planar run's: tests/planar_phase_19.rs): under gravity
//! across the axis or on supports that differ by direction the stationary motion is periodic,
//! not constant, in the rotor's axes, and the summary's means over a revolution (residual,
//! whirl about the mean position, the balls' drift) must be those of that periodic motion,
//! wherever the run ends. They come from the one window of every model
//! (`autobal::simulation::RevolutionWindow`): records at 32 rotor angles a revolution on the
//! integrator's dense output. Main's spatial and linear windows took the trapezoidal rule over
//! DOP853's step ends (4-5 a revolution here), second order in the step.

use autobal::control::Control;
use autobal::drive::Drive;
use autobal::linear_rotor::runup::{simulate as linear_simulate, RunSettings};
use autobal::linear_rotor::LinearRotor;
use autobal::ode::Method;
use autobal::planar::PlanarRotor;
use autobal::spatial::dynamics::{simulate, RunOutcome, Sample, Summary};
use std::f64::consts::TAU;

/// A spatial example at the constant speed `omega` (rad/s) from its start to `t_end`, with
/// `edit` applied to the config; every sample to `samples`, taken every `dt` (None: the
/// config's).
fn spatial_run(text: &str, edit: &[(&str, &str)], omega: f64, t_end: f64, dt: Option<f64>, samples: &mut Vec<Sample>) -> Summary {
    let mut root = autobal::config::parse(text, "example").unwrap();
    for (k, v) in edit {
        autobal::config::set(&mut root, k, autobal::config::parse_value(v)).unwrap();
    }
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    let settings = autobal::spatial::dynamics::Settings { t_end, dt: dt.unwrap_or(sim.settings.dt), ..sim.settings.clone() };
    let s = simulate(&sim.rotor, &Drive::Speed { omega0: omega }, &sim.initial, &settings, |smp| {
        samples.push(smp.clone());
        true
    })
    .unwrap();
    assert!(s.status.is_completed(), "{s:?}");
    s
}

fn spread(v: &[f64]) -> f64 {
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &r| (a.min(r), b.max(r)));
    hi - lo
}

/// examples/spatial_two_plane.toml (gravity across the axis, bearings stiffer vertically) held
/// at 1400 rad/s, where `stability` finds its balanced orbit stable (from 1201 rad/s), from
/// the balls spread evenly: balanced after 12 s (its comments). Ten ends across one
/// revolution (4.49 ms).
///
/// The runs share every step but their last (the drive has no breakpoint before the ends, and
/// the step sizes do not depend on `t_end`), so their windows are the same trajectory's last
/// revolution shifted by a fraction of one. For a periodic motion the means over any
/// revolution agree; what is left is the dense output's error at the records, of the order of
/// the local error tolerance, `rtol |ψ| ≈ 1e-8 · 2π` in a ball angle (6e-8 rad), and the
/// transient's change over a revolution, which `ball_drift` bounds (below 1.1e-10 rad in all
/// ten runs). A ball angle moves the static residual by at most `m R / |U_s|` = 0.0024 /
/// 6.3e-4 = 3.8 per radian (four balls: 15), so the residuals agree to 15 · (6e-8 + 1.1e-10)
/// ≈ 1e-6. Measured: a spread of 1.2e-9 (8.57e-8 to 8.69e-8). Main's code: 5.1e-6 (5.8e-7 to
/// 5.7e-6), its `ball_drift` 8e-8 to 7.5e-7.
#[test]
fn the_spatial_residual_does_not_depend_on_where_in_the_last_revolution_the_run_ends() {
    let text = include_str!("../../../examples/spatial_two_plane.toml");
    let edit = [("drive.schedule", "[[0.0, 1400.0], [20.0, 1400.0]]")];
    let omega = 1400.0;
    let (mut residuals, mut couples, mut drifts) = (vec![], vec![], vec![]);
    for k in 0..10 {
        let t_end = 12.0 + TAU / omega * k as f64 / 10.0;
        let s = spatial_run(text, &edit, omega, t_end, None, &mut vec![]);
        eprintln!("{t_end}: {:?} {:e} {:?} {:e} {:?}", s.outcome, s.residual_unbalance, s.residual_couple, s.final_amplitude, s.ball_drift);
        assert_eq!(s.outcome, RunOutcome::Balanced, "t_end {t_end}: {s:?}");
        assert!(s.averaged, "t_end {t_end}: {s:?}");
        residuals.push(s.residual_unbalance);
        couples.push(s.residual_couple.unwrap());
        drifts.push(s.ball_drift.unwrap());
    }
    // (the couple's sensitivity to a ball angle is m R ζ / |U_c|, of the same order)
    assert!(spread(&residuals) <= 1e-6, "residuals {residuals:?}: spread {:e}", spread(&residuals));
    assert!(spread(&couples) <= 1e-6, "couples {couples:?}: spread {:e}", spread(&couples));
    // the tolerance's premise, checked after the spreads so that main's code fails on them
    // rather than on it: the transient is over (main's code read 8e-8 to 7.5e-7)
    assert!(drifts.iter().all(|&d| d < 1e-9), "ball drifts {drifts:?}");
}

/// A run stopped long before its last revolutions (here by its observer at 1 s of 12: as
/// Ctrl-C stops it) records no revolution: its summary says its residuals are the end state's
/// (`averaged` false, no mean displacement, no drift), where main's code gave means over
/// step ends it had recorded from the start.
#[test]
fn a_spatial_run_stopped_early_says_its_numbers_are_the_end_state_s() {
    let text = include_str!("../../../examples/spatial_two_plane.toml");
    let mut root = autobal::config::parse(text, "example").unwrap();
    autobal::config::set(&mut root, "drive.schedule", autobal::config::parse_value("[[0.0, 1400.0], [20.0, 1400.0]]")).unwrap();
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    let settings = autobal::spatial::dynamics::Settings { t_end: 12.0, ..sim.settings.clone() };
    let s = simulate(&sim.rotor, &Drive::Speed { omega0: 1400.0 }, &sim.initial, &settings, |smp| smp.t < 1.0).unwrap();
    assert!(!s.status.is_completed() && s.t_end < 1.1, "{s:?}");
    assert!(!s.averaged && s.mean_displacement.is_none() && s.ball_drift.is_none(), "{s:?}");
    assert_eq!(s.outcome, RunOutcome::NotSettled);
}

/// The washer of examples/washing_machine.toml under gravity (its comments) held at its
/// 1400 rpm (146.61 rad/s; `stability`: stable from 301 rpm) for 60 s from the balls spread
/// evenly: balanced, the drum sagging 11.4 mm and whirling about that by ~0.9 µm. The whirl
/// (`final_amplitude`, the RMS of `|r − r̄|` over the last revolution, `r` the displacement at
/// the balancer plane in fixed axes) against an independent route: the run's own samples at
/// 47 equal times over its last revolution (`dt = T/47`, `t_end` a whole number of periods),
/// `r` from the samples' C and tilt (checked against the samples' own `|r|`), the mean and the
/// RMS by the trapezoidal rule in time:
/// exact for the periodic motion too, on another grid: 47 times a period, at `φ = 2π k/47`,
/// none but `φ = 0` among the window's `2π k/32` (at a constant speed from `φ = 0` a grid of
/// times `T/64` would be the window's own angles). What the routes
/// share is the trajectory; the samples and the records are both read from the dense output,
/// each to the local error, `rtol |r| + atol` = 1e-8 · 0.0114 + 1e-9 ≈ 1.1e-9 m, which bounds
/// the whirl's difference (0.12 % of it); the transient's change over one revolution is
/// smaller (`ball_drift` 1.6e-6 rad a revolution moves `r` by about the whirl times that).
/// Measured: the whirl 9.0441e-7 m to 9.0448e-7 at the ten ends (spread 6.6e-11), the
/// independent route's 1.6e-11 from the run's, the mean positions 4.7e-11 apart. Main's code:
/// 8.608e-7 to 8.626e-7 m (spread 1.8e-9; 5 % low against the samples: the step ends'
/// chords in the rotor frame, 4.6 steps a revolution, cut the part of the whirl that is not
/// constant in the rotor's axes).
#[test]
fn the_spatial_whirl_about_the_sag_is_the_motion_s_wherever_the_run_ends() {
    let text = include_str!("../../../examples/washing_machine.toml");
    let edit = [("spatial.gravity", "[0.0, -9.81, 0.0]")];
    let omega = 146.61;
    let period = TAU / omega;
    let root = autobal::config::parse(text, "washer").unwrap();
    let mut g = root.clone();
    autobal::config::set(&mut g, "spatial.gravity", autobal::config::parse_value(edit[0].1)).unwrap();
    let rotor = autobal::config::spatial_simulation(&g).unwrap().rotor;
    let zeta = rotor.planes[0].z - rotor.z_reference();
    let (rtol, atol) = {
        let s = autobal::config::spatial_simulation(&g).unwrap().settings;
        (s.rtol, s.atol)
    };
    let mut whirls = vec![];
    for k in 0..10 {
        let t_end = 60.0 + period * k as f64 / 10.0;
        let s = spatial_run(text, &edit, omega, t_end, None, &mut vec![]);
        eprintln!("{t_end}: {:?} {:e} {:e} {:?} {:?}", s.outcome, s.residual_unbalance, s.final_amplitude, s.ball_drift, s.static_sag);
        assert_eq!(s.outcome, RunOutcome::Balanced, "t_end {t_end}: {s:?}");
        whirls.push(s.final_amplitude);
    }
    let sag = 0.0114; // the drum's, 11.4 mm (the runs' static_sag)
    let tol = rtol * sag + atol;
    assert!(spread(&whirls) <= tol, "whirls {whirls:?}: spread {:e} over {tol:e}", spread(&whirls));
    // the independent route: 1401 whole periods (60.04 s), sampled 47 times a period
    let periods = (60.0 / period).ceil();
    let mut samples = vec![];
    let s = spatial_run(text, &edit, omega, periods * period, Some(period / 47.0), &mut samples);
    let last = &samples[samples.len() - 48..];
    assert!((last[47].t - last[0].t - period).abs() < 1e-9 * period, "{} {}", last[0].t, last[47].t);
    // the plane's point: C plus ζ times the tilted axis, `ζ (sin θ, −sin δ cos θ)` in axes
    // turning with the rotor (tilt `R_x(δ) R_y(θ)`, docs/notes/model.md), turned by `φ = ω t`
    // into fixed axes, `(δ, θ)` the samples' fixed-axes tilt turned back
    let r: Vec<[f64; 2]> = last
        .iter()
        .map(|p| {
            let (sn, cs) = (omega * p.t).sin_cos();
            let (d, th) = (cs * p.tilt_x + sn * p.tilt_y, -sn * p.tilt_x + cs * p.tilt_y);
            let rho = [zeta * th.sin(), -zeta * d.sin() * th.cos()];
            [p.x + cs * rho[0] - sn * rho[1], p.y + sn * rho[0] + cs * rho[1]]
        })
        .collect();
    // checked against the samples' own distance from the axis, to round-off of the sag
    for (p, q) in last.iter().zip(&r) {
        assert!((q[0].hypot(q[1]) - p.amplitude_planes[0]).abs() < 1e-15, "{q:?} vs {}", p.amplitude_planes[0]);
    }
    // trapezoid over one period: the end points' half weights make the periodic sum
    let mean = |f: &dyn Fn(usize) -> f64| (0..47).map(f).sum::<f64>() / 47.0;
    let m = [mean(&|i| r[i][0]), mean(&|i| r[i][1])];
    let rms = mean(&|i| (r[i][0] - m[0]).powi(2) + (r[i][1] - m[1]).powi(2)).sqrt();
    eprintln!("run {:e}, samples {rms:e}; mean {:?} vs {m:?}", s.final_amplitude, s.mean_displacement);
    assert!((s.final_amplitude - rms).abs() <= tol, "whirl {:e} vs the samples' {rms:e} (tolerance {tol:e})", s.final_amplitude);
    let md = s.mean_displacement.unwrap();
    assert!((md[0] - m[0]).hypot(md[1] - m[1]) <= tol, "mean {md:?} vs the samples' {m:?}");
}

/// The Jeffcott rotor of paper 004 as a linear rotor (race centred, two balls of 0.03 kg)
/// under gravity across the axis: its stationary motion a periodic orbit (the shaft sagging,
/// the balls swinging once a revolution).
fn jeffcott_under_gravity() -> (PlanarRotor, LinearRotor) {
    let p = PlanarRotor { s2: 0.0, m3: 0.03, ..PlanarRotor::paper() };
    let mut r = LinearRotor::from_planar(&p).unwrap();
    r.set_gravity([0.0, -9.81]);
    (p, r)
}

/// The linear run at 2 `ω_n` (576 rad/s; `stability`: balanced, stable) under gravity, ten
/// ends across one revolution after the transient has decayed by `e^{-25}`: the same residual,
/// race whirl and verdict at every end. As for the spatial run, the runs share their steps
/// but the last, and what is left is the dense output's error at the records, `rtol |ψ|` ≈
/// 6e-8 rad in a ball angle (`rtol` 1e-8), and the transient's change over a revolution
/// (`ball_drift` below 1e-10 rad). A ball angle moves the residual by at most `m_b R / (m1 s1)`
/// = 0.0018/0.003 = 0.6 per radian (two balls: 1.2): 7e-8. The race whirl is the race centre's
/// mean position in turning axes over its whirl with the balls spread (≈ 3.2e-3 m here); the
/// records' position error, `rtol |d| + atol` ≈ 1e-8 · 1.2e-4 m (the sag `g/ω_n²`) + 1e-10 m,
/// is 3e-8 of it. So both agree to 1e-7. Measured: residual spread 5e-11, the race whirl 0 at
/// every end (the sag, constant in fixed axes, turns through a whole revolution in the rotor's
/// axes: its mean there vanishes, below the 1e-6 ℓ that counts as centred). Main's code:
/// residual 7.8e-7 to 1.78e-6 (spread 1.0e-6), race whirl 2.9e-5 to 1.05e-4 (the step ends'
/// chords of the turning sag, 4.3 steps a revolution), `ball_drift` 2e-7 to 8.8e-7.
#[test]
fn the_linear_summary_does_not_depend_on_where_in_the_last_revolution_the_run_ends() {
    let (p, r) = jeffcott_under_gravity();
    let w = 2.0 * p.natural_frequency();
    let st = autobal::linear_rotor::stability::stability_over_speed(&r, &[w]).unwrap();
    let pt = &st.points[0];
    assert_eq!(pt.verdict, Some(autobal::analysis::Verdict::Stable), "{pt:?}");
    let t0 = 25.0 / -pt.abscissa.unwrap();
    let (rtol, atol) = (1e-8, 1e-10);
    let (mut residuals, mut whirls, mut drifts) = (vec![], vec![], vec![]);
    for k in 0..10 {
        let t_end = t0 + TAU / w * k as f64 / 10.0;
        let settings =
            RunSettings { t_end, dt: t_end / 100.0, rtol, atol, method: Method::Dop853, max_steps: 10_000_000, max_wall_s: None, physical_nodes: None };
        let s = linear_simulate(&r, &Drive::Speed { omega0: w }, &settings, &Control::none(), |_| true).unwrap();
        eprintln!("{t_end}: {:?} {:e} {:?} {:?} {}", s.outcome, s.residual_unbalance, s.race_whirl, s.ball_drift, s.steps);
        assert_eq!(s.outcome, RunOutcome::Balanced, "t_end {t_end}: {s:?}");
        assert!(s.averaged, "t_end {t_end}: {s:?}");
        residuals.push(s.residual_unbalance);
        whirls.push(s.race_whirl.unwrap());
        drifts.push(s.ball_drift.unwrap());
    }
    eprintln!("spreads {:e} {:e}", spread(&residuals), spread(&whirls));
    let tol = 1e-7;
    assert!(spread(&residuals) <= tol, "residuals {residuals:?}");
    assert!(spread(&whirls) <= tol, "race whirls {whirls:?}");
    // the tolerance's premise, checked after the spreads so that main's code fails on them
    // rather than on it: the transient is over (main's code read 2e-7 to 8.8e-7)
    assert!(drifts.iter().all(|&d| d < 1e-9), "ball drifts {drifts:?}");
}
