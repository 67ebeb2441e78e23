//! One way to stop long work ([`autobal::control`]): for each kind of long computation, a
//! cancel flag set before it starts (or during it) returns the stopped outcome with what was
//! computed so far, never a panic and never a plain success, and a zero wall-time budget stops
//! it with [`StopReason::Budget`]. The boundary tracer, the general map and the sweep have theirs
//! next to their other tests (`stability.rs`, `rotor_map.rs`, `sweep.rs`).

use autobal::control::{Control, StopReason};
use autobal::drive::Drive;
use autobal::error::Error;
use autobal::ode::Status;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::ranges::SpeedRange;
use autobal::spatial::stability::{stability_grid, stability_ranges, stability_ranges_with, StabilityRanges};
use std::time::Duration;

fn zero_budget() -> Control {
    Control::new().with_budget(Duration::ZERO)
}

fn cancelled() -> Control {
    let c = Control::new();
    c.cancel();
    c
}

#[test]
fn planar_simulation_stops_with_its_partial_summary() {
    use autobal::planar::{simulate_summary, simulate_with, PlanarRotor, Settings};
    let rotor = PlanarRotor::paper();
    let drive = autobal::planar::Drive::Acceleration { omega0: 200.0, b: 20.0 };
    let settings = Settings::new(&rotor, 15.0);
    // cancelled from the sink at the tenth sample (as Ctrl-C from another thread would): the
    // samples up to then were delivered, the summary ends there and says why
    let control = Control::new();
    let mut seen = 0;
    let s = simulate_with(&rotor, &drive, &settings, &control, |_| {
        seen += 1;
        if seen == 10 {
            control.cancel();
        }
        true
    })
    .unwrap();
    assert_eq!(s.status, Status::Stopped(StopReason::Interrupted));
    assert!(s.t_end >= 9.0 * settings.dt && s.t_end < 10.0 * settings.dt, "{}", s.t_end);
    assert!(s.steps > 0 && s.peak_amplitude.is_finite(), "the partial run's summary is kept");
    assert!(s.stopped.as_deref().is_some_and(|t| t.starts_with("interrupted at t = ")), "{:?}", s.stopped);
    assert!(matches!(s.into_result(), Err(Error::Interrupted { .. })));
    // cancelled before the start: no step, the initial state's summary
    let s = simulate_summary(&rotor, &drive, &settings, &cancelled()).unwrap();
    assert_eq!((s.status, s.t_end, s.steps), (Status::Stopped(StopReason::Interrupted), 0.0, 0));
    // a zero budget
    let s = simulate_summary(&rotor, &drive, &settings, &zero_budget()).unwrap();
    assert_eq!(s.status, Status::Stopped(StopReason::Budget { seconds: 0.0 }));
    assert!(s.stopped.as_deref().is_some_and(|t| t.starts_with("time budget of 0 s spent")), "{:?}", s.stopped);
}

#[test]
fn spatial_simulation_stops_between_samples() {
    use autobal::spatial::dynamics::{simulate_summary, simulate_with, Initial, Settings, SpatialRotor};
    let rotor = SpatialRotor::default();
    let drive = Drive::Speed { omega0: 1.6 };
    let init = Initial::at_rest(&rotor);
    // one sample at the start and one at the end: only the control can stop it in between
    let settings = Settings { t_end: 200.0, dt: 200.0, ..Settings::default() };
    let s = simulate_with(&rotor, &drive, &init, &settings, &cancelled(), |_| true).unwrap();
    assert_eq!((s.status, s.t_end), (Status::Stopped(StopReason::Interrupted), 0.0));
    let s = simulate_summary(&rotor, &drive, &init, &settings, &zero_budget()).unwrap();
    assert_eq!(s.status, Status::Stopped(StopReason::Budget { seconds: 0.0 }));
    assert!(s.into_result().is_err());
    // the same run to its end under no control
    assert!(simulate_summary(&rotor, &drive, &init, &settings, &Control::none()).unwrap().status.is_completed());
}

#[test]
fn basins_keep_no_run_the_control_stopped() {
    use autobal::spatial::dynamics::basins::{angle_grid, basins};
    use autobal::spatial::dynamics::{Initial, Settings, SpatialRotor};
    let rotor = SpatialRotor::default();
    let cases = angle_grid(&Initial::at_rest(&rotor), &Drive::Speed { omega0: 1.6 }, 2, 2);
    let settings = Settings { t_end: 20.0, ..Settings::default() };
    for (control, why) in [(cancelled(), StopReason::Interrupted), (zero_budget(), StopReason::Budget { seconds: 0.0 })] {
        let out = basins(&rotor, &cases, &settings, &control).unwrap();
        assert_eq!(out.stopped, Some(why));
        assert_eq!(out.value.len(), cases.len());
        assert!(out.value.iter().all(Option::is_none));
    }
    // progress: one report per run, the last one all of them
    let seen = std::sync::Arc::new(std::sync::Mutex::new(vec![]));
    let s = seen.clone();
    let out = basins(&rotor, &cases, &settings, &Control::new().with_progress(move |p| s.lock().unwrap().push(p))).unwrap();
    assert!(out.is_complete());
    let mut done: Vec<u64> = seen.lock().unwrap().iter().map(|p| p.done).collect();
    done.sort();
    assert_eq!(done, vec![1, 2, 3, 4]);
}

#[test]
fn spatial_sweep_stops_as_the_planar_one() {
    use autobal::sweep::{simulate_batch, SpatialSweep};
    let mut root = autobal::config::parse(include_str!("../../../examples/spatial.toml"), "spatial.toml").unwrap();
    autobal::config::set_number(&mut root, "drive.t_end", 20.0).unwrap();
    let base = SpatialSweep::new(root).unwrap();
    for (control, why) in [(cancelled(), StopReason::Interrupted), (zero_budget(), StopReason::Budget { seconds: 0.0 })] {
        let out = simulate_batch(&base, &["drive.omega0"], &[1.5, 1.6], &mut |_, _, _| panic!("no point is delivered"), &control).unwrap();
        assert_eq!((out.delivered, out.stopped), (0, Some(why)));
        assert!(matches!(out.into_result(), Err(Error::Interrupted { .. })));
    }
}

#[test]
fn torque_outcomes_stop_with_a_typed_error() {
    use autobal::planar::paper004::{torque_outcomes, TORQUE_C_THETA, TORQUE_I_G};
    assert!(matches!(torque_outcomes(TORQUE_I_G, TORQUE_C_THETA, &cancelled()), Err(Error::Interrupted { .. })));
    assert!(matches!(torque_outcomes(TORQUE_I_G, TORQUE_C_THETA, &zero_budget()), Err(Error::Interrupted { .. })));
}

#[test]
fn spatial_stability_map_keeps_whole_rows() {
    use autobal::spatial::map::stability_map_units;
    use autobal::spatial::map::{stability_map, Axis, MapSettings};
    let root = autobal::config::parse(include_str!("../../../examples/washing_machine.toml"), "w").unwrap();
    let c = autobal::config::spatial(&root).unwrap();
    let x = Axis::linspace("balancer.z", 0.05, 0.15, 3);
    let omega = Axis::linspace("omega", 0.1, 3.0, 40);
    let rpm = Axis::linspace("speed_rpm", 300.0, 1500.0, 40);
    for (control, why) in [(cancelled(), StopReason::Interrupted), (zero_budget(), StopReason::Budget { seconds: 0.0 })] {
        let out = stability_map(&c.spec, &x, &omega, &MapSettings::default(), &control, &mut |_, _| panic!("no row")).unwrap();
        assert_eq!((out.rows, out.complete, out.stopped), (0, false, Some(why)));
        let out = stability_map_units(&c.spec, &x, &rpm, &MapSettings::default(), &control, &mut |_, _| panic!("no row")).unwrap();
        assert_eq!((out.rows, out.complete, out.stopped), (0, false, Some(why)));
    }
    // cancelled while the rows arrive (from the receiver of the third row, as Ctrl-C would be):
    // the rows handed over are whole, and the map stops after the third
    let control = Control::new();
    let mut rows = vec![];
    let out = stability_map(&c.spec, &x, &omega, &MapSettings::default(), &control, &mut |_, r| {
        rows.push(r.to_vec());
        if rows.len() == 3 {
            control.cancel();
        }
        true
    })
    .unwrap();
    assert_eq!((out.rows, out.stopped), (3, Some(StopReason::Interrupted)));
    assert!(rows.iter().all(|r| r.len() == 3));
    // a complete map under no control says so
    let out = stability_map(&c.spec, &x, &omega, &MapSettings::default(), &Control::none(), &mut |_, _| true).unwrap();
    assert!(out.complete && out.stopped.is_none() && out.rows == 40);
}

/// A control whose progress observer cancels it once `after` items are done (as Ctrl-C from
/// another thread would, between two speeds).
fn cancelled_after(after: u64) -> Control {
    let c = Control::new();
    let flag = c.flag().clone();
    c.with_progress(move |p| {
        if p.done >= after {
            flag.store(true, std::sync::atomic::Ordering::Relaxed);
        }
    })
}

#[test]
fn speed_scans_stop_between_speeds_with_the_speeds_done() {
    use autobal::analysis::{speed_scan, speed_scan_with, ScanOptions};
    use autobal::planar::field::PlanarField;
    use autobal::planar::PlanarRotor;
    use autobal::rotor_campbell::{campbell_over_speed, campbell_over_speed_with};
    use autobal::rotor_stability::{stability_over_speed, stability_over_speed_with, Rotor};
    // the Jeffcott rotor of paper 004 (race centred): stable above ~1.05 ω_n, so the full grid
    // has a range end to locate
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    let wn = p.natural_frequency();
    let speeds: Vec<f64> = (1..=12).map(|i| 0.25 * wn * i as f64).collect();
    let field = |w| PlanarField::new(&p, w);
    let guess = |f: &PlanarField, _| f.semi_balanced_guess();
    let full = speed_scan(field, guess, &speeds, &ScanOptions::default()).unwrap();
    assert_eq!(full.points.len(), speeds.len());
    assert!(full.stable_ranges.iter().any(|r| r.from_is_boundary), "{:?}", full.stable_ranges);
    // cancelled before the start, or a zero budget: no speed done, and it says why
    for (control, why) in [(cancelled(), StopReason::Interrupted), (zero_budget(), StopReason::Budget { seconds: 0.0 })] {
        let out = speed_scan_with(field, guess, &speeds, &ScanOptions::default(), &control).unwrap();
        assert_eq!((out.value.points.len(), out.stopped), (0, Some(why)));
        assert!(out.into_result().is_err());
        let out = stability_over_speed_with(&Rotor::Planar(p.clone()), &speeds, &control).unwrap();
        assert_eq!((out.value.points.len(), out.stopped), (0, Some(why)));
        let out = campbell_over_speed_with(&Rotor::Planar(p.clone()), &speeds, &control).unwrap();
        assert_eq!((out.value.omega.len(), out.stopped), (0, Some(why)));
    }
    // cancelled after the fifth speed: those five, equal to the full scan's, and the stable
    // range among them ends at the grid (its end is not located)
    let out = speed_scan_with(field, guess, &speeds, &ScanOptions::default(), &cancelled_after(5)).unwrap();
    assert_eq!((out.value.points.len(), out.stopped), (5, Some(StopReason::Interrupted)));
    assert_eq!(out.value.points[..], full.points[..5]);
    let rotor = Rotor::Planar(p.clone());
    let out = stability_over_speed_with(&rotor, &speeds, &cancelled_after(5)).unwrap();
    let whole = stability_over_speed(&rotor, &speeds).unwrap();
    assert_eq!((out.value.points.len(), out.stopped), (5, Some(StopReason::Interrupted)));
    assert_eq!(out.value.points[..], whole.points[..5]);
    assert!(out.value.stable_ranges.iter().all(|r| !r.to_is_boundary), "{:?}", out.value.stable_ranges);
    let out = campbell_over_speed_with(&rotor, &speeds, &cancelled_after(5)).unwrap();
    let whole = campbell_over_speed(&rotor, &speeds).unwrap();
    assert_eq!((out.value.omega.len(), out.stopped), (5, Some(StopReason::Interrupted)));
    assert_eq!(out.value.omega[..], whole.omega[..5]);
    assert!(out.value.lines.iter().all(|l| l.points.len() == 5));
    // under no control, complete
    assert!(speed_scan_with(field, guess, &speeds, &ScanOptions::default(), &Control::none()).unwrap().is_complete());
}

#[test]
fn a_family_scan_stops_with_the_families_followed() {
    use autobal::planar::PlanarRotor;
    use autobal::rotor_stability::{stability_over_speed_with, Rotor};
    // three balls: a one-parameter family at each speed
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    p.n = 3;
    let wn = p.natural_frequency();
    let rotor = Rotor::Planar(p);
    let speeds = [1.2 * wn, 1.5 * wn, 2.0 * wn];
    for (control, why) in [(cancelled(), StopReason::Interrupted), (zero_budget(), StopReason::Budget { seconds: 0.0 })] {
        let out = stability_over_speed_with(&rotor, &speeds, &control).unwrap();
        assert_eq!((out.value.points.len(), out.stopped), (0, Some(why)));
    }
    // stopped after the scan's speeds (the observer cancels at the last): the points are all
    // there, no family is followed, and it says so
    let out = stability_over_speed_with(&rotor, &speeds, &cancelled_after(3)).unwrap();
    assert_eq!((out.value.points.len(), out.stopped), (3, Some(StopReason::Interrupted)));
    assert!(out.value.points.iter().all(|p| p.family.is_none()));
}

// Session 23: the closed-form stability scan (`stability_ranges_with`) stopped keeps the grid
// speeds it analysed and the ranges among them, checked against the same scan run to its end
// (the margins are the same computation, so bit for bit; the located ends the same bisections).

fn base_000() -> autobal::spatial::params::SpatialModel {
    use autobal::spatial::params::{DimensionlessInput, SpatialModel};
    SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap()
}

// paper 000's base case over (0, 5], 400 speeds, ends to 1e-9
const W: f64 = 5.0;
const SAMPLES: usize = 400;
const TOL: f64 = 1e-9;

/// Each range of `kept` (a scan stopped before its bisections: every end not located) against
/// the complete run's `whole` over the same speeds: the start of the axis and an end open to
/// `Ω_max` as there; every other end a grid speed where the state is stable (`margin` < 0) and
/// within one grid step of the located end.
fn ends_at_stable_grid_speeds(kept: &[SpeedRange], whole: &[SpeedRange], grid: &[f64], margin: impl Fn(f64) -> Option<f64>) {
    assert_eq!(kept.len(), whole.len(), "{kept:?} vs {whole:?}");
    let step = grid.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    for (a, b) in kept.iter().zip(whole) {
        for (cut, located) in [(Some(a.lo), Some(b.lo)), (a.hi, b.hi)] {
            match (cut, located) {
                (Some(c), Some(l)) if l > 0.0 => {
                    assert!(margin(c).is_some_and(|x| x < 0.0), "{c} is no stable grid speed");
                    assert!((c - l).abs() <= step, "{c} vs {l}");
                }
                (c, l) => assert_eq!(c, l),
            }
        }
    }
}

/// Stopped inside a stable range (Ctrl-C after `k` grid speeds): the margins are the complete
/// run's first `k`; no bisection runs after the stop, so the ranges over `(0, Ω_k]` are the
/// complete run's with each end at its stable grid speed, and the range holding `Ω_k` ends
/// there (`hi = Some(Ω_k)`, never open to `Ω_max`); the progress counts the grid's speeds,
/// seeded split pairs included.
#[test]
fn a_stopped_scan_keeps_the_ranges_over_the_speeds_it_analysed() {
    let m = base_000();
    let whole = stability_ranges(&m, W, SAMPLES, Balls::Free, TOL).unwrap();
    let grid = stability_grid(&m, W, SAMPLES);
    assert_eq!(whole.max_real_part.iter().map(|p| p.0).collect::<Vec<_>>(), grid);
    // a grid speed in the middle of a stable range, past the first range
    let inside = |w: f64| whole.stable_ranges.iter().any(|r| r.lo < w && r.hi.is_none_or(|h| w < h));
    let k = (3..grid.len() - 1)
        .find(|&i| inside(grid[i - 1]) && inside(grid[i - 2]) && inside(grid[i]) && grid[i] > whole.stable_ranges[0].hi.unwrap_or(W))
        .expect("a second stable range");
    let out = stability_ranges_with(&m, W, SAMPLES, Balls::Free, TOL, &cancelled_after(k as u64)).unwrap();
    assert_eq!(out.stopped, Some(StopReason::Interrupted));
    let kept = &out.value;
    assert_eq!(kept.max_real_part, whole.max_real_part[..k]);
    let last = grid[k - 1];
    assert_eq!(kept.stable_ranges.last().unwrap().hi, Some(last));
    // the complete run's ranges over (0, Ω_k], the last end (Ω_k, compared above) left open in both
    let mut want: Vec<SpeedRange> = whole.stable_ranges.iter().filter(|r| r.lo < last).cloned().collect();
    want.last_mut().unwrap().hi = None;
    let mut got = kept.stable_ranges.clone();
    got.last_mut().unwrap().hi = None;
    let margin = |w: f64| whole.max_real_part.iter().find(|p| p.0 == w).map(|p| p.1);
    ends_at_stable_grid_speeds(&got, &want, &grid, margin);
}

/// Stopped after every grid speed, during the bisections of the ranges' ends: each end not
/// located is the grid speed on its stable side; a range reaching `Ω_max` stays open, the grid
/// having reached it.
#[test]
fn a_scan_stopped_in_its_bisections_ends_its_ranges_at_stable_grid_speeds() {
    let m = base_000();
    let whole = stability_ranges(&m, W, SAMPLES, Balls::Free, TOL).unwrap();
    let grid = stability_grid(&m, W, SAMPLES);
    let out = stability_ranges_with(&m, W, SAMPLES, Balls::Free, TOL, &cancelled_after(grid.len() as u64)).unwrap();
    assert_eq!(out.stopped, Some(StopReason::Interrupted));
    let kept: &StabilityRanges = &out.value;
    assert_eq!(kept.max_real_part, whole.max_real_part);
    let margin = |w: f64| whole.max_real_part.iter().find(|p| p.0 == w).map(|p| p.1);
    ends_at_stable_grid_speeds(&kept.stable_ranges, &whole.stable_ranges, &grid, margin);
    assert!(kept.stable_ranges.iter().zip(&whole.stable_ranges).any(|(a, b)| a.lo != b.lo), "no end was cut");
}

/// A budget spent before the first speed: nothing analysed, no range, the budget named (the
/// scan indexed its first margin and panicked on an empty grid before the stop was possible).
#[test]
fn a_scan_stopped_before_its_first_speed_keeps_nothing() {
    let out = stability_ranges_with(&base_000(), W, SAMPLES, Balls::Free, TOL, &Control::new().with_budget(Duration::ZERO)).unwrap();
    assert!(matches!(out.stopped, Some(StopReason::Budget { .. })));
    assert!(out.value.max_real_part.is_empty() && out.value.stable_ranges.is_empty());
}
