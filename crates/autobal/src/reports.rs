//! The result of each front-end command as one JSON value: what `autobal <command> --format
//! json` prints and what the Python package's `autobal.run(command, ...)` returns, built here
//! once so that the two cannot differ.
//!
//! ```
//! use autobal::{config, reports};
//! let c = config::spatial(&config::parse(config::DEFAULT_SPATIAL, "default").unwrap()).unwrap();
//! let v = reports::critical(&c, "default");
//! assert_eq!(v["rotor_type"], "long");
//! assert_eq!(v["critical_speeds"].as_array().unwrap().len(), 4);
//! ```

use crate::config::SpatialConfig;
use crate::error::Result;
use crate::limits::check_finite;
use crate::planar::problem::PlanarProblem;
use crate::planar::stationary::capacity_ratio;
use crate::planar::Summary;
use crate::spatial::comparison::Comparison;
use crate::spatial::critical_speeds::{critical_speeds, critical_speeds_at};
use crate::spatial::inertia::composite_inertia;
use crate::spatial::linear_model::Balls;
use crate::spatial::params::SpatialModel;
use crate::spatial::ranges::{antiresonance_speed, autobalancing_ranges, SpeedRange};
use crate::spatial::sensitivity::sensitivity;
use crate::spatial::stability::Campbell;
use serde_json::{json, Value};

/// `[lo, hi]` pairs with `null` for an unbounded end.
pub fn ranges_value(r: &[SpeedRange]) -> Value {
    Value::Array(r.iter().map(|x| json!([x.lo, x.hi])).collect())
}

/// Whether the last of ranges computed over a span reaches the span's end (`hi = None` there).
fn open_at(r: &[SpeedRange]) -> bool {
    r.last().is_some_and(|x| x.hi.is_none())
}

/// Ranges scaled by `k` (e.g. to rpm).
pub fn scale_ranges(r: &[SpeedRange], k: f64) -> Vec<SpeedRange> {
    r.iter().map(|x| SpeedRange { lo: x.lo * k, hi: x.hi.map(|h| h * k) }).collect()
}

/// rad/s and rpm per unit of dimensionless speed Ω (`ω0` and `30 ω0 / π`), for a dimensional
/// config; `None` for a dimensionless one, whose SI keys are then `null`.
fn si_units(m: &SpatialModel) -> Option<(f64, f64)> {
    m.scale.map(|s| (s.omega0, s.omega0 * 30.0 / std::f64::consts::PI))
}

/// A speed (or speeds) Ω in rad/s and rpm: `(rad_s, rpm)`, `null`s without a scale.
fn speed_si(m: &SpatialModel, w: &[f64]) -> (Value, Value) {
    match si_units(m) {
        Some((rad, rpm)) => (json!(w.iter().map(|x| x * rad).collect::<Vec<_>>()), json!(w.iter().map(|x| x * rpm).collect::<Vec<_>>())),
        None => (Value::Null, Value::Null),
    }
}

/// Ranges of Ω in rpm, `null` without a scale.
fn ranges_rpm(m: &SpatialModel, r: &[SpeedRange]) -> Value {
    si_units(m).map_or(Value::Null, |(_, rpm)| ranges_value(&scale_ranges(r, rpm)))
}

/// The upper end of the speed axis when none is given: 1.3 times the highest critical,
/// antiresonance or split-pair speed (at least 1), at most 50.
pub fn default_omega_max(m: &SpatialModel) -> f64 {
    let top = critical_speeds_at(m, m.anisotropy.used)
        .iter()
        .map(|r| r.0)
        .chain(antiresonance_speed(m))
        .chain(autobalancing_ranges(m).critical_speeds)
        .fold(1.0, f64::max);
    (1.3 * top).min(50.0)
}

fn model_json(c: &SpatialConfig, source: &str) -> Value {
    let m = &c.model;
    json!({
        "c_sigma": m.c_sigma,
        "rho_s": m.rho_s,
        "l_left": m.l_left,
        "z_a": m.z_a,
        "p_alpha": m.p_alpha_sq.sqrt(),
        "p_alpha_sq": m.p_alpha_sq,
        "c_y_alpha": m.c_y_alpha,
        "delta_a0": m.delta_a0,
        "damping": m.damping,
        "masses": m.masses,
        "scale": m.scale,
        "source": source,
    })
}

fn anisotropy_json(m: &SpatialModel) -> Value {
    let a = &m.anisotropy;
    json!({
        "paper": a.paper,
        "exact": a.exact[1],
        "used": a.used,
        "method": a.method,
        "exact_interval": a.exact,
        "paper_interval": a.paper_interval,
        "used_interval": a.used_interval,
        "d_a": a.d_a,
        "ball_angles_rad": a.ball_angles,
        "can_balance": a.can_balance,
        "warnings": a.warnings,
    })
}

/// Every number the analytic commands report is finite (else the error names the quantity);
/// the input ranges ([`crate::limits`]) are chosen so that this holds, this is the last guard.
pub fn check_results(c: &SpatialConfig) -> Result<()> {
    check_finite("the model", &c.model)?;
    check_finite("inertia", &composite_inertia(&c.model))?;
    check_finite("critical_speeds", &critical_speeds(&c.model))?;
    check_finite("autobalancing_ranges", &autobalancing_ranges(&c.model))?;
    check_finite("sensitivity", &sensitivity(&c.model, c.analysis.sensitivity_limit))?;
    Ok(())
}

/// `autobal inertia`: composite inertia and anisotropy.
pub fn inertia(c: &SpatialConfig, source: &str) -> Value {
    json!({
        "model": model_json(c, source),
        "inertia": composite_inertia(&c.model),
        "anisotropy": anisotropy_json(&c.model),
    })
}

/// `autobal critical`: critical speeds, sensitivity and autobalancing ranges.
pub fn critical(c: &SpatialConfig, source: &str) -> Value {
    let cs = critical_speeds(&c.model);
    let ar = autobalancing_ranges(&c.model);
    let s = sensitivity(&c.model, c.analysis.sensitivity_limit);
    let (a_rad, a_rpm) = speed_si(&c.model, &ar.antiresonance_speed.into_iter().collect::<Vec<_>>());
    json!({
        "critical_speeds": cs.speeds,
        "distinct_count": cs.distinct_count,
        "table1_count": cs.table1_count,
        "rotor_type": cs.rotor_class,
        "antiresonance_speed": ar.antiresonance_speed,
        "antiresonance_speed_rad_s": a_rad[0],
        "antiresonance_speed_rpm": a_rpm[0],
        "autobalancing_ranges": ranges_value(&ar.ranges),
        "autobalancing_ranges_rpm": ranges_rpm(&c.model, &ar.ranges),
        "balancing_class": ar.class,
        "sensitivity": s,
        "anisotropy": anisotropy_json(&c.model),
        "model": model_json(c, source),
    })
}

/// `autobal ranges`: the speed ranges where autobalancing is possible (003).
pub fn ranges(c: &SpatialConfig, source: &str) -> Value {
    let ar = autobalancing_ranges(&c.model);
    let (a_rad, a_rpm) = speed_si(&c.model, &ar.antiresonance_speed.into_iter().collect::<Vec<_>>());
    let (cs_rad, cs_rpm) = speed_si(&c.model, &ar.critical_speeds);
    json!({
        "antiresonance_speed": ar.antiresonance_speed,
        "antiresonance_speed_rad_s": a_rad[0],
        "antiresonance_speed_rpm": a_rpm[0],
        "autobalancing_ranges": ranges_value(&ar.ranges),
        "autobalancing_ranges_rpm": ranges_rpm(&c.model, &ar.ranges),
        "phase_condition_ranges": ranges_value(&ar.phase_condition),
        "instability_ranges": ranges_value(&ar.instability),
        "critical_speeds_unbalanced_rotor": ar.critical_speeds,
        "critical_speeds_unbalanced_rotor_rad_s": cs_rad,
        "critical_speeds_unbalanced_rotor_rpm": cs_rpm,
        "balancing_class": ar.class,
        "delta_a0": c.model.delta_a0,
        "model": model_json(c, source),
    })
}

fn balls_name(balls: Balls) -> &'static str {
    if balls == Balls::Free {
        "free"
    } else {
        "locked"
    }
}

/// `autobal stability`: exact stability ranges against 003's necessary ranges.
pub fn stability(model: &SpatialModel, c: &Comparison, balls: Balls) -> Value {
    json!({
        "balls": balls_name(balls),
        "omega_max": c.omega_max,
        "stable_ranges": ranges_value(&c.exact.stable_ranges),
        "necessary_ranges": ranges_value(&c.necessary),
        "stable_ranges_rpm": ranges_rpm(model, &c.exact.stable_ranges),
        "necessary_ranges_rpm": ranges_rpm(model, &c.necessary),
        "necessary_not_stable": ranges_value(&c.necessary_not_stable),
        "stable_not_necessary": ranges_value(&c.stable_not_necessary),
        // the ranges are computed over (0, omega_max] only: a null upper end means "reaches
        // omega_max", not "unbounded"; true for the lists whose last range reaches it
        "open_at_span_end": {
            "stable_ranges": open_at(&c.exact.stable_ranges),
            "necessary_ranges": open_at(&c.necessary),
            "necessary_not_stable": open_at(&c.necessary_not_stable),
            "stable_not_necessary": open_at(&c.stable_not_necessary),
        },
        "difference": c.difference(),
        "max_real_part": c.exact.max_real_part.iter().map(|(w, a)| json!([w, a])).collect::<Vec<_>>(),
        "tolerance": c.exact.tolerance,
        "stability_threshold": crate::spatial::stability::STABILITY_TOLERANCE,
        "anisotropy_used": model.anisotropy.used,
        "ball_coupling": model.balls,
    })
}

/// `autobal campbell` of a complete run: the speeds, the tracked lines and `complete: true`
/// (the CLI streams the same JSON, with `complete: false` after Ctrl-C).
pub fn campbell(c: &Campbell) -> Value {
    json!({ "omega": c.omega, "lines": c.lines, "complete": true })
}

/// `autobal simulate`: the run's summary, with the rotor, drive and tolerances it ran with.
pub fn simulation(p: &PlanarProblem, s: &Summary, wall_time_s: f64) -> Value {
    json!({
        "model": "planar",
        "peak_amplitude": s.peak_amplitude,
        "omega_at_peak": s.omega_at_peak,
        "t_at_peak": s.t_at_peak,
        "final_amplitude": s.final_amplitude,
        "final_omega": s.final_omega,
        "balanced": s.balanced,
        "settled": s.settled,
        "steps": s.steps,
        "implicit_steps": s.implicit_steps,
        "switches": s.switches,
        "rejected_steps": s.rejected_steps,
        "rhs_evaluations": s.rhs_evaluations,
        "contacts": s.contacts,
        "stick_slip_transitions": s.stick_slip_transitions,
        "t_end": s.t_end,
        "stopped": s.stopped,
        "warnings": s.warnings,
        "wall_time_s": wall_time_s,
        "natural_frequency": p.rotor.natural_frequency(),
        "capacity_ratio": capacity_ratio(&p.rotor),
        "s2": p.rotor.s2,
        "rotor": p.rotor,
        "drive": p.drive,
        "integration": {
            "method": p.settings.method,
            "rtol": p.settings.rtol,
            "atol": p.settings.atol,
            "dt": p.settings.dt,
            "max_steps": p.settings.max_steps,
            "max_wall_s": p.settings.max_wall_s,
        },
    })
}

/// `autobal simulate` on the spatial rotor (papers 000/003): the run's summary, with the rotor,
/// drive, initial state and tolerances it ran with; lengths and speeds in SI for an SI config,
/// in `ρ_s` and `ω0` for a dimensionless one (`units` says which).
pub fn spatial_simulation(sim: &crate::config::SpatialSimulation, s: &crate::spatial::dynamics::Summary, wall_time_s: f64) -> Value {
    json!({
        "model": "spatial",
        "units": if sim.config.dimensional { "SI" } else { "dimensionless (M_s = ω0 = ρ_s = 1)" },
        "outcome": s.outcome,
        "balanced": s.balanced,
        "residual_unbalance": s.residual_unbalance,
        "residual_couple": s.residual_couple,
        "balance_tolerance": crate::spatial::dynamics::simulate::BALANCE_TOLERANCE,
        "ball_drift": s.ball_drift,
        "peak_amplitude": s.peak_amplitude,
        "omega_at_peak": s.omega_at_peak,
        "t_at_peak": s.t_at_peak,
        "final_amplitude": s.final_amplitude,
        "static_sag": s.static_sag,
        "mean_displacement": s.mean_displacement,
        "final_omega": s.final_omega,
        "steps": s.steps,
        "rejected_steps": s.rejected_steps,
        "rhs_evaluations": s.rhs_evaluations,
        "contacts": s.contacts,
        "stick_slip_transitions": s.stick_slip_transitions,
        "wall_time_s": wall_time_s,
        "t_end": s.t_end,
        "stopped": s.stopped,
        "natural_frequency": sim.rotor.natural_frequency(),
        "rotor": sim.rotor,
        "drive": sim.drive,
        "drive_is_default": sim.default_drive,
        "initial": sim.initial,
        "integration": sim.settings,
    })
}

/// `autobal basins`: how many of the runs over the first two balls' initial angles completed
/// and ended balanced.
pub fn basins(results: &[Option<crate::spatial::dynamics::Summary>], wall_time_s: f64) -> Value {
    let done = results.iter().flatten().count();
    let balanced = results.iter().flatten().filter(|s| s.balanced).count();
    json!({
        "runs": results.len(),
        "completed": done,
        "balanced": balanced,
        "fraction_balanced": balanced as f64 / done.max(1) as f64,
        "wall_time_s": wall_time_s,
    })
}

/// One run of `autobal sweep` as its JSON lists it: the point's index and values (`x`, `y`:
/// the first two), the summary and the wall time.
pub fn sweep_run(point: usize, values: &[f64], r: &crate::sweep::PointResult) -> Value {
    json!({
        "point": point,
        "values": values,
        "x": values.first(),
        "y": values.get(1),
        "summary": r.summary,
        "wall_time_s": r.wall_s,
    })
}

/// Where a sweep's runs came from: the grid, the problem and (for a shard) which part.
pub struct SweepInfo<'a> {
    /// The problem every point changes.
    pub problem: &'a PlanarProblem,
    /// The grid.
    pub grid: &'a crate::sweep::Grid,
    /// `(k, n)`, 1-based, for shard `k` of `n`.
    pub shard: Option<(usize, usize)>,
    /// The points run.
    pub range: std::ops::Range<usize>,
    /// Whether every point of `range` was run.
    pub complete: bool,
}

/// `autobal sweep`: the grid, the problem, and the runs ([`sweep_run`]) in order.
pub fn sweep(info: &SweepInfo, runs: Vec<Value>) -> Value {
    let keys = info.grid.paths();
    json!({
        "paths": keys,
        "x_key": keys[0],
        "y_key": keys.get(1),
        "grid": info.grid.axes.iter().map(|a| json!({ "path": a.path, "values": a.values })).collect::<Vec<_>>(),
        "points": info.grid.len(),
        "shard": info.shard.map(|(k, n)| [k, n]),
        "range": [info.range.start, info.range.end],
        "complete": info.complete,
        "problem": info.problem,
        "runs": runs,
    })
}

/// The speeds of `autobal campbell`: `points` cell centres over `(0, omega_max)`.
pub fn campbell_speeds(omega_max: f64, points: usize) -> Vec<f64> {
    let n = points.max(3);
    (0..n).map(|i| omega_max * (i as f64 + 0.5) / n as f64).collect()
}
