//! Simulation sweeps: many runs of one rotor with parameters changed by path, in parallel,
//! delivered in order, stoppable. The rotor is a [`SweepModel`]: paper 004's planar rotor, a
//! [`PlanarProblem`] (paths of [`crate::paths`]: `planar.c_psi`, `drive.b`, `drive.psi0[1]`),
//! or the spatial rotor of papers 000/003, a [`SpatialSweep`] (the config's own keys,
//! `balancer.ball_mass`, `drive.omega0`, `dimensionless.z_a`, …, set in its tables and the
//! rotor converted again per point), or a linear rotor config ([`LinearRotorSpec`], issue 19:
//! the paths of [`crate::linear_rotor::spec`], `linear_rotor.ball_mass`, `drive.b`, …, each
//! point the config with those values set, run as `simulate` runs it). Their rows are
//! [`SUMMARY_COLUMNS`], [`SPATIAL_SUMMARY_COLUMNS`] and [`LINEAR_SUMMARY_COLUMNS`].
//!
//! - A [`Grid`] is the product of [`Axis`] values (the first axis varies fastest); its points
//!   are numbered `0..len`, and a [`shard`] is a contiguous range of them, so that shards run
//!   anywhere (another process, another machine) and concatenate to the whole sweep.
//! - [`simulate_batch`] runs a list of points (an `n × k` array of values for `k` paths);
//!   [`simulate_grid`] runs a range of a grid's points. Both check every point first (an
//!   invalid value is an error naming the path and the point), then run blocks of points in
//!   parallel (rayon, in the caller's thread pool) and hand each result to `on_row` in the order
//!   of the points, whatever the number of threads: a sweep's output is the same on 1 thread,
//!   64 threads or 64 shards.
//! - **Stopping**: `on_row` returns `false`, or the [`Control`] stops (its cancel flag or its
//!   wall-time budget, asked by the workers between runs and during them). The outcome then
//!   says how many points were delivered and why it stopped ([`SweepOutcome::stopped`]);
//!   [`SweepOutcome::into_result`] turns that into [`Error::Interrupted`]. A sweep never ends
//!   early with a plain success. The control's progress observer hears `(points delivered,
//!   points asked for)`.
//! - A run that fails on its own (step size underflow, non-finite state) is a result, not an
//!   error: its summary says why it stopped ([`SUMMARY_COLUMNS`]' `completed` is 0).
//!
//! ```
//! use autobal::control::Control;
//! use autobal::planar::problem::PlanarProblem;
//! use autobal::sweep::{simulate_grid, summary_values, Axis, Grid, SUMMARY_COLUMNS};
//!
//! let mut base = PlanarProblem::default();
//! base.settings.t_end = 2.0; // two seconds of paper 004's run-up
//! let grid = Grid::new(vec![Axis::new("planar.c_psi", vec![0.05, 0.1]), Axis::linspace("drive.b", 100.0, 200.0, 3)]).unwrap();
//! let mut rows = vec![];
//! let out = simulate_grid(&base, &grid, 0..grid.len(), &mut |i, point, r| {
//!     rows.push((i, point.to_vec(), summary_values(&r.summary)));
//!     true
//! }, &Control::none()).unwrap();
//! assert!(out.complete() && rows.len() == 6);
//! assert_eq!(rows[1].1, vec![0.1, 100.0]); // the first axis varies fastest
//! let completed = SUMMARY_COLUMNS.iter().position(|c| *c == "completed").unwrap();
//! assert!(rows.iter().all(|r| r.2[completed] == 1.0));
//! ```

use crate::config::Table;
use crate::control::{Control, StopReason};
use crate::error::{fmt_num, Error, Result};
use crate::linear_rotor::spec::{LinearRotorSpec, LinearRun};
pub use crate::paths::Axis;
use crate::paths::Parameters;
use crate::planar::problem::PlanarProblem;
use crate::planar::{simulate_summary, Summary};
use crate::spatial::dynamics::RunOutcome;
use rayon::prelude::*;
use std::ops::Range;

/// Most points of one grid (a bound on what a mistyped axis can ask for, not on what a cluster
/// can run: 1e9 passages of 10 ms are 115 CPU-days).
pub const MAX_POINTS: usize = 1_000_000_000;

/// The product of axes; point `i` takes value `i mod n_0` of the first axis, and so on (the
/// first axis varies fastest).
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The axes.
    pub axes: Vec<Axis>,
}

impl Grid {
    /// A grid over `axes`: at least one, each with values, all finite, paths distinct, at most
    /// [`MAX_POINTS`] points.
    pub fn new(axes: Vec<Axis>) -> Result<Self> {
        if axes.is_empty() {
            return Err(Error::invalid("axes", "a sweep needs at least one axis"));
        }
        let mut len: usize = 1;
        for (i, a) in axes.iter().enumerate() {
            if a.values.is_empty() {
                return Err(Error::invalid(a.path.clone(), "the axis has no values"));
            }
            if let Some(v) = a.values.iter().find(|v| !v.is_finite()) {
                return Err(Error::invalid(a.path.clone(), format!("axis values must be finite, got {}", fmt_num(*v))));
            }
            // here, where every route passes (the text `--x` and Python's dict of lists alike:
            // `{"drive.b": [1, 1, 1]}` ran one point three times)
            if let Some(v) = crate::paths::repeated(&a.values) {
                return Err(Error::invalid(a.path.clone(), format!("the value {} is given more than once: each value is one point of the grid", fmt_num(v))));
            }
            // compared as `paths::canonical` spells them: `drive.psi0[01]` and `drive.psi0[1]`
            // are one number (the one axis was silently ignored)
            if let Some(b) = axes[..i].iter().find(|b| crate::paths::canonical(&b.path) == crate::paths::canonical(&a.path)) {
                return Err(if b.path == a.path {
                    Error::invalid(a.path.clone(), "the same path on two axes (one would silently win)")
                } else {
                    Error::invalid(a.path.clone(), format!("the same number as the axis {} (one would silently win)", b.path))
                });
            }
            len = len.checked_mul(a.values.len()).filter(|l| *l <= MAX_POINTS).ok_or_else(|| Error::TooLarge {
                what: "grid".into(),
                size: axes.iter().map(|a| a.values.len() as u64).fold(1u64, |p, n| p.saturating_mul(n)),
                limit: MAX_POINTS as u64,
                reason: "points".into(),
            })?;
        }
        Ok(Grid { axes })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// Whether the grid has no points (never, for a grid from [`Grid::new`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axes' paths.
    pub fn paths(&self) -> Vec<&str> {
        self.axes.iter().map(|a| a.path.as_str()).collect()
    }

    /// The values of point `i` into `out` (one per axis).
    pub fn point(&self, mut i: usize, out: &mut [f64]) {
        for (a, o) in self.axes.iter().zip(out.iter_mut()) {
            let n = a.values.len();
            *o = a.values[i % n];
            i /= n;
        }
    }

    /// The points of `range`, row after row (`range.len() × axes` values).
    pub fn points(&self, range: Range<usize>) -> Vec<f64> {
        let k = self.axes.len();
        let mut out = vec![0.0; range.len() * k];
        for (row, i) in out.chunks_mut(k).zip(range) {
            self.point(i, row);
        }
        out
    }
}

/// Points of shard `k` of `n` (0-based `k`) of a sweep of `total` points: contiguous ranges,
/// sizes differing by at most one, in order, so that the shards' outputs concatenate to the
/// whole sweep's.
pub fn shard(total: usize, k: usize, n: usize) -> Result<Range<usize>> {
    if n == 0 || k >= n {
        return Err(Error::invalid("--shard", format!("shard {} of {n} does not exist (k from 1 to N)", k + 1)));
    }
    let lo = total / n * k + k.min(total % n);
    let len = total / n + usize::from(k < total % n);
    Ok(lo..lo + len)
}

/// Columns of a run's summary as numbers ([`summary_values`]), in this order. `balanced` and
/// `completed` are 0 or 1; `completed` is 0 for a run that stopped on its own before `t_end`
/// (its reason is in the summary's `stopped`); `contacts` and `stick_slip_transitions` count
/// real balls' events ([`crate::balls`]; 0 for point masses); `outcome` is
/// [`Summary::outcome`] as a number ([`outcome_code`]: 0 not settled, 1 not balanced,
/// 2 partially balanced, 3 balanced, with an eccentric race the semi-balanced state) and
/// `residual_unbalance` [`Summary::residual_unbalance`], the words and number `simulate`
/// reports.
pub const SUMMARY_COLUMNS: &[&str] = &[
    "peak_amplitude",
    "omega_at_peak",
    "t_at_peak",
    "final_amplitude",
    "final_omega",
    "balanced",
    "completed",
    "t_reached",
    "steps",
    "rejected_steps",
    "rhs_evaluations",
    "contacts",
    "stick_slip_transitions",
    "outcome",
    "residual_unbalance",
];

/// The summary's numbers in the order of [`SUMMARY_COLUMNS`] (counts are exact in `f64` up
/// to 2⁵³).
pub fn summary_values(s: &Summary) -> [f64; 15] {
    [
        s.peak_amplitude,
        s.omega_at_peak,
        s.t_at_peak,
        s.final_amplitude,
        s.final_omega,
        f64::from(u8::from(s.balanced)),
        f64::from(u8::from(s.stopped.is_none())),
        s.t_end,
        s.steps as f64,
        s.rejected_steps as f64,
        s.rhs_evaluations as f64,
        s.contacts as f64,
        s.stick_slip_transitions as f64,
        outcome_code(s.outcome),
        s.residual_unbalance,
    ]
}

/// Columns of a spatial run's summary ([`spatial_summary_values`]), in this order: those of
/// [`SUMMARY_COLUMNS`], meaning the same for the spatial rotor ([`crate::spatial::dynamics::Summary`]:
/// amplitudes are the whirl radius at the first balancer plane, `balanced` and `outcome` its
/// verdict, `residual_unbalance` the static residual relative to the unbalance's own), then
/// `residual_couple` (relative to the unbalance's own couple; NaN when the unbalance has none)
/// and `static_sag` (distance of the mean position from the axis; NaN where the summary has
/// none: [`crate::spatial::dynamics::Summary::static_sag`]).
pub const SPATIAL_SUMMARY_COLUMNS: &[&str] = &[
    "peak_amplitude",
    "omega_at_peak",
    "t_at_peak",
    "final_amplitude",
    "final_omega",
    "balanced",
    "completed",
    "t_reached",
    "steps",
    "rejected_steps",
    "rhs_evaluations",
    "contacts",
    "stick_slip_transitions",
    "outcome",
    "residual_unbalance",
    "residual_couple",
    "static_sag",
];

/// [`RunOutcome`] as the number of the `outcome` column: 0 not settled, 1 not balanced,
/// 2 partially balanced, 3 balanced (the better, the larger).
pub fn outcome_code(o: RunOutcome) -> f64 {
    match o {
        RunOutcome::NotSettled => 0.0,
        RunOutcome::NotBalanced => 1.0,
        RunOutcome::PartiallyBalanced => 2.0,
        RunOutcome::Balanced => 3.0,
    }
}

/// A spatial run's summary in the order of [`SPATIAL_SUMMARY_COLUMNS`] (counts exact in `f64`
/// up to 2⁵³; `residual_couple` NaN when the unbalance has no couple, `static_sag` NaN where
/// the run measured no sag).
pub fn spatial_summary_values(s: &crate::spatial::dynamics::Summary) -> [f64; 17] {
    [
        s.peak_amplitude,
        s.omega_at_peak,
        s.t_at_peak,
        s.final_amplitude,
        s.final_omega,
        f64::from(u8::from(s.balanced)),
        f64::from(u8::from(s.stopped.is_none())),
        s.t_end,
        s.steps as f64,
        s.rejected_steps as f64,
        s.rhs_evaluations as f64,
        s.contacts as f64,
        s.stick_slip_transitions as f64,
        outcome_code(s.outcome),
        s.residual_unbalance,
        s.residual_couple.unwrap_or(f64::NAN),
        s.static_sag.unwrap_or(f64::NAN),
    ]
}

/// Columns of a linear rotor's run ([`crate::linear_rotor::runup::RunSummary`]), in this order:
/// `peak_amplitude`, `omega_at_peak`, `t_at_peak` (the first balancer plane's radius, m; NaN
/// without a plane), `peak_any_node`, `omega_at_peak_any_node` (the largest translation of any
/// physical node), `final_amplitude` (the first plane's radius at the end), `completed` (0 or
/// 1), `t_reached`, `steps`.
pub const LINEAR_SUMMARY_COLUMNS: &[&str] =
    &["peak_amplitude", "omega_at_peak", "t_at_peak", "peak_any_node", "omega_at_peak_any_node", "final_amplitude", "completed", "t_reached", "steps"];

/// A linear rotor's run summary in the order of [`LINEAR_SUMMARY_COLUMNS`] (a peak never
/// observed, −∞, is NaN).
pub fn linear_summary_values(s: &crate::linear_rotor::runup::RunSummary) -> [f64; 9] {
    let seen = |v: f64| if v.is_finite() { v } else { f64::NAN };
    let has_plane = s.peak.value.is_finite();
    [
        seen(s.peak.value),
        if has_plane { s.peak.with } else { f64::NAN },
        if has_plane { s.peak.t } else { f64::NAN },
        seen(s.peak_any_node.value),
        if s.peak_any_node.value.is_finite() { s.peak_any_node.with } else { f64::NAN },
        if has_plane { s.final_radius } else { f64::NAN },
        f64::from(u8::from(s.stopped.is_none())),
        s.t,
        s.steps as f64,
    ]
}

impl SweepSummary for crate::linear_rotor::runup::RunSummary {
    const COLUMNS: &'static [&'static str] = LINEAR_SUMMARY_COLUMNS;
    fn values(&self) -> Vec<f64> {
        linear_summary_values(self).to_vec()
    }
    fn stopped(&self) -> Option<&str> {
        self.stopped.as_deref()
    }
}

/// A linear rotor config as a sweep's base ([`crate::linear_rotor::spec`]): a point is the
/// config with its values set at paths, read again, and run as `autobal simulate` runs it
/// ([`crate::linear_rotor::spec::run_of`]: the reduction, the default run-up where the config
/// has no `[drive]`), sampled at every `dt` as `simulate` samples it.
impl SweepModel for LinearRotorSpec {
    type Point = LinearRun;
    type Summary = crate::linear_rotor::runup::RunSummary;
    fn at(&self, paths: &[&str], values: &[f64]) -> Result<LinearRun> {
        let at = || point_text(paths, values);
        let set: Vec<(&str, f64)> = paths.iter().copied().zip(values.iter().copied()).collect();
        let cfg = self.config_at(&set).map_err(|e| with_point(e, &at()))?;
        crate::linear_rotor::spec::run_of(&cfg).map_err(|e| with_point(e, &at()))
    }
    fn run(&self, p: &LinearRun, control: &Control) -> Result<Self::Summary> {
        crate::linear_rotor::runup::simulate(&p.rotor, &p.drive, &p.settings, control, |_| true)
    }
}

/// A run's summary as a sweep's row: its columns' names and numbers (and as JSON, its
/// run's `summary`).
pub trait SweepSummary: Send + Sync + serde::Serialize {
    /// The columns' names ([`SUMMARY_COLUMNS`], [`SPATIAL_SUMMARY_COLUMNS`]).
    const COLUMNS: &'static [&'static str];
    /// The numbers, one per column, in their order.
    fn values(&self) -> Vec<f64>;
    /// Why the run stopped before its end, if it did.
    fn stopped(&self) -> Option<&str>;
}

impl SweepSummary for Summary {
    const COLUMNS: &'static [&'static str] = SUMMARY_COLUMNS;
    fn values(&self) -> Vec<f64> {
        summary_values(self).to_vec()
    }
    fn stopped(&self) -> Option<&str> {
        self.stopped.as_deref()
    }
}

impl SweepSummary for crate::spatial::dynamics::Summary {
    const COLUMNS: &'static [&'static str] = SPATIAL_SUMMARY_COLUMNS;
    fn values(&self) -> Vec<f64> {
        spatial_summary_values(self).to_vec()
    }
    fn stopped(&self) -> Option<&str> {
        self.stopped.as_deref()
    }
}

/// What a sweep runs: a base description, the description of one point (the base with
/// numbers set at paths), and the run of that point.
pub trait SweepModel: Sync {
    /// One point's description.
    type Point: Send;
    /// One run's summary.
    type Summary: SweepSummary;
    /// The base with `values` set at `paths`, checked; errors name the path and the point.
    fn at(&self, paths: &[&str], values: &[f64]) -> Result<Self::Point>;
    /// Run a point under `control`, keeping its summary (a run the control stops is discarded
    /// by the sweep).
    fn run(&self, point: &Self::Point, control: &Control) -> Result<Self::Summary>;
}

impl SweepModel for PlanarProblem {
    type Point = PlanarProblem;
    type Summary = Summary;
    fn at(&self, paths: &[&str], values: &[f64]) -> Result<PlanarProblem> {
        problem_at(self, paths, values)
    }
    fn run(&self, p: &PlanarProblem, control: &Control) -> Result<Summary> {
        // the run of `simulate` with the same settings (dt included: it is also the automatic
        // method's time resolution), sampled only at its ends; the stop is checked at every step
        simulate_summary(&p.rotor, &p.drive, &p.settings, control)
    }
}

/// A sweep of the spatial rotor of papers 000/003 ([`crate::config::spatial_simulation`]):
/// the config's tables, a point setting its keys (`balancer.ball_mass`, `drive.omega0`,
/// `dimensionless.z_a`, `supports.stiffness_left`, …, and an element of an array key,
/// `drive.psi0[2]`, 1-based) in the tables and converting them again, so that every key the
/// config accepts is a path and a point is exactly the config with that value set (as
/// `autobal simulate --set KEY=VALUE` runs it).
///
/// ```
/// use autobal::control::Control;
/// use autobal::sweep::{simulate_batch, SpatialSweep, SweepModel};
/// let mut root = autobal::config::parse(include_str!("../../../examples/spatial.toml"), "spatial.toml").unwrap();
/// autobal::config::set_number(&mut root, "drive.t_end", 50.0).unwrap();
/// let base = SpatialSweep::new(root.clone()).unwrap();
/// let mut rows = vec![];
/// simulate_batch(&base, &["drive.omega0"], &[1.5, 1.6], &mut |_, _, r| { rows.push(r.summary.clone()); true }, &Control::none()).unwrap();
/// // point 1 is the config with drive.omega0 = 1.6, run as `simulate` runs it
/// autobal::config::set_number(&mut root, "drive.omega0", 1.6).unwrap();
/// let sim = autobal::config::spatial_simulation(&root).unwrap();
/// let direct = autobal::spatial::dynamics::simulate(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, |_| true).unwrap();
/// assert_eq!(rows[1], direct);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialSweep {
    root: Table,
}

impl SpatialSweep {
    /// A sweep over the config `root` (the analytic commands' tables plus `[drive]`,
    /// `[integration]`, …), which must convert as it is.
    pub fn new(root: Table) -> Result<Self> {
        crate::config::spatial_simulation(&root)?;
        Ok(SpatialSweep { root })
    }

    /// The config's tables.
    pub fn root(&self) -> &Table {
        &self.root
    }

    /// The config with `value` set at `path` (`table.key`, or `table.key[j]` for element `j`,
    /// 1-based, of an array key); errors name the path.
    pub fn set(root: &mut Table, path: &str, value: f64) -> Result<()> {
        let (key, index) = match crate::paths::indexed(path) {
            Some((name, j)) => (name, Some(j.map_err(|r| Error::invalid(path, r))?)),
            None => (path, None),
        };
        if key.split('.').next() == Some("planar") {
            return Err(Error::invalid(path, "a key of the planar rotor of paper 004; this config is the spatial rotor's"));
        }
        let Some(j) = index else {
            return crate::config::set_number(root, key, value);
        };
        crate::config::set_element(root, path, key, j, value)
    }
}

impl SpatialSweep {
    /// The sweep's base problem as a sweep's JSON gives it (`problem`): `model: "spatial"`,
    /// the config's tables (`config`) and what they convert to (`rotor`, `drive`,
    /// `drive_is_default`, `initial`, `integration`).
    pub fn to_json(&self) -> Result<serde_json::Value> {
        let sim = crate::config::spatial_simulation(&self.root)?;
        Ok(serde_json::json!({
            "model": "spatial",
            "config": self.root,
            "rotor": sim.rotor,
            "drive": sim.drive,
            "drive_is_default": sim.default_drive,
            "initial": sim.initial,
            "integration": sim.settings,
        }))
    }
}

/// One run as a sweep's JSON lists it: the point's index and values (`x`, `y`: the first
/// two), the summary and the wall time, for either rotor.
pub fn run_json<S: serde::Serialize>(point: usize, values: &[f64], r: &PointResult<S>) -> serde_json::Value {
    serde_json::json!({
        "point": point,
        "values": values,
        "x": values.first(),
        "y": values.get(1),
        "summary": r.summary,
        "wall_time_s": r.wall_s,
    })
}

/// A sweep's JSON, for either rotor: the paths, the grid, which
/// part (`shard`, 1-based `(k, n)`, and `range`), whether it is complete, the base `problem`
/// ([`SpatialSweep::to_json`], or the [`PlanarProblem`] as JSON) and the runs in order
/// ([`run_json`]).
pub fn report(
    grid: &Grid,
    shard: Option<(usize, usize)>,
    range: &Range<usize>,
    complete: bool,
    problem: serde_json::Value,
    runs: Vec<serde_json::Value>,
) -> serde_json::Value {
    let keys = grid.paths();
    serde_json::json!({
        "paths": keys,
        "x_key": keys[0],
        "y_key": keys.get(1),
        "grid": grid.axes.iter().map(|a| serde_json::json!({ "path": a.path, "values": a.values })).collect::<Vec<_>>(),
        "points": grid.len(),
        "shard": shard.map(|(k, n)| [k, n]),
        "range": [range.start, range.end],
        "complete": complete,
        "problem": problem,
        "runs": runs,
    })
}

impl SweepModel for SpatialSweep {
    type Point = crate::config::SpatialSimulation;
    type Summary = crate::spatial::dynamics::Summary;
    fn at(&self, paths: &[&str], values: &[f64]) -> Result<Self::Point> {
        let at = || point_text(paths, values);
        let mut root = self.root.clone();
        for (path, v) in paths.iter().zip(values) {
            SpatialSweep::set(&mut root, path, *v).map_err(|e| with_point(e, &at()))?;
        }
        crate::config::spatial_simulation(&root).map_err(|e| with_point(e, &at()))
    }
    fn run(&self, p: &Self::Point, control: &Control) -> Result<Self::Summary> {
        // the run of `autobal simulate` itself, samples every `dt` included: the peak is tracked
        // at step ends and samples, and the samples' dense output costs right-hand sides, so a
        // run sampled only at its ends would differ in those columns; the control is asked at
        // every step
        crate::spatial::dynamics::simulate_with(&p.rotor, &p.drive, &p.initial, &p.settings, control, |_| true)
    }
}

/// One run of a sweep of the planar rotor's run ([`Summary`], the default) or of
/// the spatial rotor's ([`crate::spatial::dynamics::Summary`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PointResult<S = Summary> {
    /// Its summary.
    pub summary: S,
    /// Wall-clock time of the run (s); the one column that differs between repetitions.
    pub wall_s: f64,
}

/// How a sweep ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepOutcome {
    /// Points asked for.
    pub points: usize,
    /// Points delivered to `on_row` (a prefix of them, in order).
    pub delivered: usize,
    /// Why it stopped before every point was delivered ([`StopReason::Observer`]: `on_row`
    /// returned `false`; else the control's reason); `None`: complete.
    pub stopped: Option<StopReason>,
}

impl SweepOutcome {
    /// Whether every point was delivered.
    pub fn complete(&self) -> bool {
        self.stopped.is_none()
    }

    /// `Ok` when complete, else [`Error::Interrupted`] with the fraction delivered as `t`.
    pub fn into_result(self) -> Result<Self> {
        if self.complete() {
            Ok(self)
        } else {
            Err(Error::Interrupted { t: self.delivered as f64 / self.points.max(1) as f64 })
        }
    }
}

/// The problem of one point: `base` with `values` set at `paths`, for a summary only; errors
/// name the path and the point.
pub fn problem_at(base: &PlanarProblem, paths: &[&str], values: &[f64]) -> Result<PlanarProblem> {
    let at = || point_text(paths, values);
    let mut p = base.clone();
    for (path, v) in paths.iter().zip(values) {
        p.set(path, *v).map_err(|e| with_point(e, &at()))?;
    }
    p.validate().map_err(|e| with_point(e, &at()))?;
    Ok(p)
}

/// `path = value, …` of a point, for errors.
fn point_text(paths: &[&str], values: &[f64]) -> String {
    paths.iter().zip(values).map(|(p, v)| format!("{p} = {}", fmt_num(*v))).collect::<Vec<_>>().join(", ")
}

fn with_point(e: Error, at: &str) -> Error {
    match e {
        Error::InvalidParameter { field, reason } => Error::InvalidParameter { field, reason: format!("{reason} (at the point {at})") },
        other => other,
    }
}

/// Points run in parallel between two deliveries: enough to keep every thread busy with runs of
/// uneven length, few enough that a stop is prompt and memory stays small.
fn block_len() -> usize {
    (16 * rayon::current_num_threads()).max(64)
}

/// The shared loop: points `range` (numbered as the caller numbers them), point values from
/// `point(i, out)`.
fn run_points<M: SweepModel>(
    base: &M,
    paths: &[&str],
    range: Range<usize>,
    point: &(dyn Fn(usize, &mut [f64]) + Sync),
    on_row: &mut dyn FnMut(usize, &[f64], &PointResult<M::Summary>) -> bool,
    control: &Control,
) -> Result<SweepOutcome> {
    let k = paths.len();
    check_points(base, paths, range.clone(), point)?;
    let total = range.len();
    let mut out = SweepOutcome { points: total, delivered: 0, stopped: None };
    let mut start = range.start;
    let block = block_len();
    while start < range.end {
        let end = (start + block).min(range.end);
        let results: Vec<Option<(Vec<f64>, PointResult<M::Summary>)>> = (start..end)
            .into_par_iter()
            .map(|i| -> Result<Option<(Vec<f64>, PointResult<M::Summary>)>> {
                if control.should_stop().is_some() {
                    return Ok(None);
                }
                let mut v = vec![0.0; k];
                point(i, &mut v);
                let p = base.at(paths, &v)?;
                let t0 = std::time::Instant::now();
                let summary = base.run(&p, control)?;
                let wall_s = t0.elapsed().as_secs_f64();
                // a run cut short by the stop is no result (the flag and a spent budget stay set)
                Ok(control.should_stop().is_none().then_some((v, PointResult { summary, wall_s })))
            })
            .collect::<Result<_>>()?;
        for (i, r) in (start..end).zip(&results) {
            let Some((v, r)) = r else {
                out.stopped = Some(control.should_stop().unwrap_or(StopReason::Interrupted));
                return Ok(out);
            };
            let go_on = on_row(i, v, r);
            out.delivered += 1;
            control.report(out.delivered as u64, total as u64);
            if !go_on {
                if out.delivered < total {
                    out.stopped = Some(StopReason::Observer);
                }
                return Ok(out);
            }
        }
        start = end;
    }
    Ok(out)
}

/// Every point first: an invalid value must not surface after hours of runs.
fn check_points<M: SweepModel>(base: &M, paths: &[&str], range: Range<usize>, point: &(dyn Fn(usize, &mut [f64]) + Sync)) -> Result<()> {
    let mut buf = vec![0.0; paths.len()];
    for i in range {
        point(i, &mut buf);
        base.at(paths, &buf)?;
    }
    Ok(())
}

/// Check points `range` of `grid` on `base` as [`simulate_grid`] does before it runs anything
/// (for a caller that must know before it creates its output files); errors name the path and
/// the point.
pub fn check_grid<M: SweepModel>(base: &M, grid: &Grid, range: Range<usize>) -> Result<()> {
    check_points(base, &grid.paths(), range, &|i, out| grid.point(i, out))
}

/// Check the points of a batch (`params` row after row, one value per path) as
/// [`simulate_batch`] does before it runs anything.
pub fn check_batch<M: SweepModel>(base: &M, paths: &[&str], params: &[f64]) -> Result<()> {
    let k = paths.len().max(1);
    check_points(base, paths, 0..params.len() / k, &|i, out| out.copy_from_slice(&params[i * k..(i + 1) * k]))
}

/// Run points `range` of `grid` on `base` (see the module docs); `on_row(i, values, result)`
/// receives point `i` in order.
pub fn simulate_grid<M: SweepModel>(
    base: &M,
    grid: &Grid,
    range: Range<usize>,
    on_row: &mut dyn FnMut(usize, &[f64], &PointResult<M::Summary>) -> bool,
    control: &Control,
) -> Result<SweepOutcome> {
    if range.end > grid.len() {
        return Err(Error::invalid("range", format!("points {}..{} beyond the grid's {}", range.start, range.end, grid.len())));
    }
    let paths = grid.paths();
    run_points(base, &paths, range, &|i, out| grid.point(i, out), on_row, control)
}

/// Run `params.len() / paths.len()` points given row after row (`params[i k + j]` is the value
/// of `paths[j]` at point `i`); `on_row(i, values, result)` receives point `i` in order.
pub fn simulate_batch<M: SweepModel>(
    base: &M,
    paths: &[&str],
    params: &[f64],
    on_row: &mut dyn FnMut(usize, &[f64], &PointResult<M::Summary>) -> bool,
    control: &Control,
) -> Result<SweepOutcome> {
    let k = paths.len();
    if k == 0 {
        if !params.is_empty() {
            return Err(Error::invalid("params", "values given but no paths"));
        }
    } else if !params.len().is_multiple_of(k) {
        return Err(Error::invalid("params", format!("{} values are not whole rows of {k} (one per path)", params.len())));
    }
    let n = params.len().checked_div(k).unwrap_or(0);
    run_points(base, paths, 0..n, &|i, out| out.copy_from_slice(&params[i * k..(i + 1) * k]), on_row, control)
}

/// A 64-bit FNV-1a hash of the sweep's definition: the config after the `--set` overrides
/// (as TOML text) and every axis's path and values (bit patterns), written in each shard's JSON
/// as `definition_checksum` so that `autobal merge` refuses shards of different sweeps. FNV-1a
/// (`h = (h ⊕ byte) · 0x100000001b3` from `0xcbf29ce484222325`) guards against mistakes, not
/// forgery: two different definitions collide with probability ~2⁻⁶⁴.
pub fn definition_checksum(root: &Table, grid: &Grid) -> String {
    let mut text = toml::to_string(root).unwrap_or_default();
    for a in &grid.axes {
        text.push_str(&format!("\naxis {}=", a.path));
        for v in &a.values {
            text.push_str(&format!("{:016x},", v.to_bits()));
        }
    }
    format!("fnv1a64:{:016x}", fnv1a64(text.as_bytes()))
}

/// FNV-1a, 64 bits.
fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_points_in_order() {
        for total in [0, 1, 5, 17, 100] {
            for n in 1..=7 {
                let mut next = 0;
                for k in 0..n {
                    let r = shard(total, k, n).unwrap();
                    assert_eq!(r.start, next);
                    assert!(r.len() == total / n || r.len() == total / n + 1);
                    next = r.end;
                }
                assert_eq!(next, total);
            }
        }
        assert!(shard(10, 3, 3).is_err() && shard(10, 0, 0).is_err());
    }

    #[test]
    fn grid_points_first_axis_fastest() {
        let g = Grid::new(vec![Axis::new("a", vec![1.0, 2.0]), Axis::new("b", vec![10.0, 20.0, 30.0])]).unwrap();
        assert_eq!(g.len(), 6);
        assert_eq!(g.points(0..6), vec![1.0, 10.0, 2.0, 10.0, 1.0, 20.0, 2.0, 20.0, 1.0, 30.0, 2.0, 30.0]);
        assert!(Grid::new(vec![Axis::new("a", vec![1.0]), Axis::new("a", vec![2.0])]).is_err());
        assert!(Grid::new(vec![Axis::new("a", vec![f64::NAN])]).is_err());
        let many = || (0..100_000).map(f64::from).collect::<Vec<_>>();
        assert!(matches!(Grid::new(vec![Axis::new("a", many()), Axis::new("b", many())]), Err(Error::TooLarge { .. })));
        assert_eq!(Axis::linspace("c", 0.01, 0.4, 4).values, vec![0.01, 0.14, 0.27, 0.4]);
    }

    /// Two spellings of one index are one number: refused naming both axes (`drive.psi0[01]`
    /// was set as `drive.psi0[1]`, the other axis's value silently lost).
    #[test]
    fn one_number_on_two_axes_is_refused_however_spelled() {
        let e = Grid::new(vec![Axis::new("drive.psi0[01]", vec![1.0, 2.0]), Axis::new("drive.psi0[1]", vec![0.0, 1.0])]).unwrap_err().to_string();
        assert_eq!(e, "drive.psi0[1]: the same number as the axis drive.psi0[01] (one would silently win)");
        let e = Grid::new(vec![Axis::new("drive.b", vec![1.0]), Axis::new("drive.b", vec![2.0])]).unwrap_err().to_string();
        assert_eq!(e, "drive.b: the same path on two axes (one would silently win)");
        assert!(Grid::new(vec![Axis::new("drive.psi0[1]", vec![1.0]), Axis::new("drive.psi0[10]", vec![2.0])]).is_ok());
    }

    /// A repeated value is refused by the grid itself, whatever made the axis (`Axis::new` from
    /// Python's dict of lists, not only `Axis::parse`'s text); distinct values are kept.
    #[test]
    fn repeated_axis_values_are_refused_on_every_route() {
        let e = Grid::new(vec![Axis::new("drive.b", vec![1.0, 1.0, 1.0])]).unwrap_err().to_string();
        assert_eq!(e, "drive.b: the value 1 is given more than once: each value is one point of the grid");
        let e = Grid::new(vec![Axis::new("drive.b", vec![2.0]), Axis::new("planar.c_psi", vec![0.1, 0.2, -0.0, 0.0])]).unwrap_err().to_string();
        assert!(e.starts_with("planar.c_psi: the value 0 is given more than once"), "{e}");
        assert_eq!(Grid::new(vec![Axis::new("drive.b", vec![3.0, 1.0, 2.0])]).unwrap().len(), 3);
    }

    fn short() -> PlanarProblem {
        let mut p = PlanarProblem { drive: crate::planar::Drive::Acceleration { omega0: 250.0, b: 100.0 }, ..Default::default() };
        p.settings.t_end = 0.5;
        p
    }

    #[test]
    fn a_stop_is_an_outcome_never_a_silent_success() {
        let base = short();
        let g = Grid::new(vec![Axis::linspace("planar.c_psi", 0.05, 0.2, 200)]).unwrap();
        // on_row stops after 3 rows
        let mut seen = vec![];
        let out = simulate_grid(
            &base,
            &g,
            0..g.len(),
            &mut |i, _, _| {
                seen.push(i);
                seen.len() < 3
            },
            &Control::none(),
        )
        .unwrap();
        assert_eq!((out.delivered, out.stopped), (3, Some(StopReason::Observer)));
        assert_eq!(seen, vec![0, 1, 2]);
        assert!(matches!(out.into_result(), Err(Error::Interrupted { .. })));
        // cancel from the start: nothing delivered, interrupted
        let cancelled = Control::new();
        cancelled.cancel();
        let out = simulate_grid(&base, &g, 0..g.len(), &mut |_, _, _| true, &cancelled).unwrap();
        assert_eq!((out.delivered, out.stopped), (0, Some(StopReason::Interrupted)));
        // a zero budget: nothing delivered, the budget named
        let out = simulate_grid(&base, &g, 0..g.len(), &mut |_, _, _| true, &Control::new().with_budget(std::time::Duration::ZERO)).unwrap();
        assert_eq!((out.delivered, out.stopped), (0, Some(StopReason::Budget { seconds: 0.0 })));
    }

    #[test]
    fn invalid_points_name_the_path_and_the_point() {
        let base = short();
        let e = simulate_batch(&base, &["planar.m3", "drive.b"], &[0.03, 1.0, -0.01, 2.0], &mut |_, _, _| true, &Control::none()).unwrap_err().to_string();
        assert!(e.starts_with("planar.m3:") && e.contains("(at the point planar.m3 = -0.01, drive.b = 2)"), "{e}");
        let e = simulate_batch(&base, &["planar.m3"], &[], &mut |_, _, _| true, &Control::none()).unwrap();
        assert!(e.complete() && e.points == 0);
        assert!(simulate_batch(&base, &["planar.m3", "drive.b"], &[1.0], &mut |_, _, _| true, &Control::none()).is_err());
    }

    #[test]
    fn results_do_not_depend_on_threads_or_shards() {
        let base = short();
        let g = Grid::new(vec![Axis::linspace("planar.c_psi", 0.05, 0.2, 5), Axis::new("drive.b", vec![80.0, 120.0])]).unwrap();
        let collect = |range: Range<usize>, threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut rows = vec![];
            pool.install(|| {
                simulate_grid(
                    &base,
                    &g,
                    range,
                    &mut |i, v, r| {
                        rows.push((i, v.to_vec(), summary_values(&r.summary).map(f64::to_bits)));
                        true
                    },
                    &Control::none(),
                )
            })
            .unwrap();
            rows
        };
        let whole = collect(0..g.len(), 1);
        let mut sharded = vec![];
        for k in 0..3 {
            sharded.extend(collect(shard(g.len(), k, 3).unwrap(), 2));
        }
        assert_eq!(whole, sharded);
        // and a batch of the same points gives the same bits
        let params = g.points(0..g.len());
        let mut batch = vec![];
        simulate_batch(
            &base,
            &g.paths(),
            &params,
            &mut |i, v, r| {
                batch.push((i, v.to_vec(), summary_values(&r.summary).map(f64::to_bits)));
                true
            },
            &Control::none(),
        )
        .unwrap();
        assert_eq!(whole, batch);
    }

    /// examples/spatial.toml (paper 000's base case, dimensionless) cut to `t_end` τ.
    fn spatial_root(t_end: f64) -> Table {
        let mut root = crate::config::parse(include_str!("../../../examples/spatial.toml"), "spatial.toml").unwrap();
        crate::config::set_number(&mut root, "drive.t_end", t_end).unwrap();
        root
    }

    #[test]
    fn a_spatial_point_is_the_config_with_that_value_run_as_simulate_runs_it() {
        let root = spatial_root(60.0);
        let base = SpatialSweep::new(root.clone()).unwrap();
        let paths = ["drive.omega0", "dimensionless.z_a", "drive.psi0[2]"];
        let params = [1.5, 0.7, 4.5, 1.7, 0.9, 5.0];
        let mut rows = vec![];
        simulate_batch(
            &base,
            &paths,
            &params,
            &mut |i, v, r| {
                rows.push((i, v.to_vec(), r.summary.clone()));
                true
            },
            &Control::none(),
        )
        .unwrap();
        assert_eq!(rows.len(), 2);
        for (i, v, s) in &rows {
            // the second route: the config text edited by hand, converted and run with samples
            let mut r = root.clone();
            crate::config::set(&mut r, "drive.omega0", toml::Value::Float(v[0])).unwrap();
            crate::config::set(&mut r, "dimensionless.z_a", toml::Value::Float(v[1])).unwrap();
            crate::config::set(&mut r, "drive.psi0", toml::Value::Array(vec![toml::Value::Float(3.0944), toml::Value::Float(v[2])])).unwrap();
            let sim = crate::config::spatial_simulation(&r).unwrap();
            assert_eq!(sim.initial.psi, vec![3.0944, v[2]], "point {i}");
            let mut samples = 0;
            let direct = crate::spatial::dynamics::simulate(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, |_| {
                samples += 1;
                true
            })
            .unwrap();
            assert!(samples > 50, "the direct run was sampled every dt");
            assert_eq!(*s, direct, "point {i}");
            assert_eq!(spatial_summary_values(s).map(f64::to_bits), spatial_summary_values(&direct).map(f64::to_bits));
        }
        // the points differ (the paths reached the rotor), and a run that completed says so
        assert_ne!(rows[0].2.final_amplitude, rows[1].2.final_amplitude);
        let v = spatial_summary_values(&rows[0].2);
        let col = |c: &str| SPATIAL_SUMMARY_COLUMNS.iter().position(|x| *x == c).unwrap();
        assert_eq!((v[col("completed")], v[col("t_reached")]), (1.0, 60.0));
        assert_eq!(v[col("outcome")], outcome_code(rows[0].2.outcome));
        // the unbalance sits in plane A, off C: it has a couple
        assert_eq!(Some(v[col("residual_couple")]), rows[0].2.residual_couple);
        assert_eq!(SPATIAL_SUMMARY_COLUMNS[..SUMMARY_COLUMNS.len()], *SUMMARY_COLUMNS);
    }

    #[test]
    fn spatial_results_do_not_depend_on_threads_or_shards() {
        let base = SpatialSweep::new(spatial_root(40.0)).unwrap();
        let g = Grid::new(vec![Axis::linspace("drive.omega0", 1.5, 1.7, 3), Axis::new("dimensionless.h_s", vec![0.05, 0.1])]).unwrap();
        let collect = |range: Range<usize>, threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut rows = vec![];
            pool.install(|| {
                simulate_grid(
                    &base,
                    &g,
                    range,
                    &mut |i, v, r| {
                        rows.push((i, v.to_vec(), spatial_summary_values(&r.summary).map(f64::to_bits)));
                        true
                    },
                    &Control::none(),
                )
            })
            .unwrap();
            rows
        };
        let whole = collect(0..g.len(), 1);
        let mut sharded = vec![];
        for k in 0..4 {
            sharded.extend(collect(shard(g.len(), k, 4).unwrap(), 2));
        }
        assert_eq!(whole, sharded);
        assert_eq!(whole.len(), 6);
    }

    #[test]
    fn spatial_paths_are_the_configs_keys_and_errors_name_them() {
        let base = SpatialSweep::new(spatial_root(10.0)).unwrap();
        let err = |paths: &[&str], params: &[f64]| check_batch(&base, paths, params).unwrap_err().to_string();
        let e = err(&["dimensionless.m0"], &[0.01, -0.01]);
        assert!(e.starts_with("dimensionless.m0:") && e.ends_with("(at the point dimensionless.m0 = -0.01)"), "{e}");
        let e = err(&["dimensionless.z_b"], &[0.1]);
        assert!(e.starts_with("dimensionless.z_b:"), "{e}");
        let e = err(&["planar.c_psi"], &[0.1]);
        assert!(e.starts_with("planar.c_psi:") && e.contains("spatial rotor's"), "{e}");
        let e = err(&["drive.psi0[3]"], &[1.0]);
        assert!(e.starts_with("drive.psi0[3]:") && e.contains("has 2 elements"), "{e}");
        let e = err(&["drive.psi_rate0[1]"], &[1.0]);
        assert!(e.starts_with("drive.psi_rate0[1]:") && e.contains("not an array"), "{e}");
        let e = err(&["drive.psi0[0]"], &[1.0]);
        assert!(e.starts_with("drive.psi0[0]:"), "{e}");
        // the number of balls is a whole number in the config, and a path like any other
        check_batch(&base, &["dimensionless.n"], &[3.0]).unwrap_err(); // psi0 gives 2 angles
        assert!(err(&["dimensionless.n"], &[2.5]).starts_with("dimensionless.n:"));
        // a base that does not convert is refused up front
        let mut bad = spatial_root(10.0);
        crate::config::set_number(&mut bad, "dimensionless.m0", -1.0).unwrap();
        assert!(SpatialSweep::new(bad).is_err());
    }
}
