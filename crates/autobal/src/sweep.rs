//! Simulation sweeps: many runs of one [`PlanarProblem`] with parameters changed by path
//! ([`crate::paths`]), in parallel, delivered in order, stoppable.
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
//! - **Stopping**: `on_row` returns `false`, or `cancel` (polled by the workers between runs and
//!   during them) returns `true`. The outcome then says how many points were delivered
//!   ([`SweepOutcome::complete`] is `false`); [`SweepOutcome::into_result`] turns that into
//!   [`Error::Interrupted`]. A sweep never ends early with a plain success.
//! - A run that fails on its own (step size underflow, non-finite state) is a result, not an
//!   error: its summary says why it stopped ([`SUMMARY_COLUMNS`]' `completed` is 0).
//!
//! ```
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
//! }, &|| false).unwrap();
//! assert!(out.complete && rows.len() == 6);
//! assert_eq!(rows[1].1, vec![0.1, 100.0]); // the first axis varies fastest
//! let completed = SUMMARY_COLUMNS.iter().position(|c| *c == "completed").unwrap();
//! assert!(rows.iter().all(|r| r.2[completed] == 1.0));
//! ```

use crate::error::{fmt_num, Error, Result};
use crate::paths::Parameters;
use crate::planar::problem::PlanarProblem;
use crate::planar::{simulate_summary, Summary};
use rayon::prelude::*;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

/// Most points of one grid (a bound on what a mistyped axis can ask for, not on what a cluster
/// can run: 1e9 passages of 10 ms are 115 CPU-days).
pub const MAX_POINTS: usize = 1_000_000_000;

/// One axis of a sweep or map: a parameter path and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Parameter path (`planar.c_psi`, `drive.b`, `dimensionless.z_a`, ...).
    pub path: String,
    /// The values, in order.
    pub values: Vec<f64>,
}

impl Axis {
    /// An axis with the given values.
    pub fn new(path: impl Into<String>, values: Vec<f64>) -> Self {
        Axis { path: path.into(), values }
    }

    /// `n` equally spaced values from `lo` to `hi` (both included; `n = 1` gives `lo`). Inner
    /// values are rounded to 12 significant digits so that they read as typed (`0.4`, not
    /// `0.39999999999999997`): a grid value is the same number whichever process computes it.
    pub fn linspace(path: impl Into<String>, lo: f64, hi: f64, n: usize) -> Self {
        let values = (0..n)
            .map(|i| {
                if i == 0 {
                    return lo;
                }
                if i + 1 == n {
                    return hi;
                }
                let v = lo + (hi - lo) * i as f64 / (n - 1) as f64;
                round12(v)
            })
            .collect();
        Axis { path: path.into(), values }
    }

    /// An axis from its text form: `PATH=LO:HI:N` (`N ≥ 2` equally spaced values, see
    /// [`Axis::linspace`]), `PATH=V1,V2,…` (a list) or `PATH=V` (one value). Errors quote the
    /// spec (the caller puts the option in front).
    ///
    /// ```
    /// use autobal::sweep::Axis;
    /// assert_eq!(Axis::parse("drive.b=0.5:2.5:3").unwrap().values, vec![0.5, 1.5, 2.5]);
    /// assert_eq!(Axis::parse("planar.m3=0.01,0.03").unwrap().values, vec![0.01, 0.03]);
    /// assert!(Axis::parse("drive.b=2:1:3").unwrap_err().to_string().contains("HI must exceed LO"));
    /// ```
    pub fn parse(spec: &str) -> Result<Self> {
        let bad = |why: String| Error::invalid(spec, why);
        let (path, range) = spec.split_once('=').ok_or_else(|| bad("expected PATH=LO:HI:N, PATH=V1,V2,… or PATH=V, e.g. drive.b=0.5:12.5:5".into()))?;
        let path = path.trim();
        if path.is_empty() {
            return Err(bad("the parameter path is empty".into()));
        }
        let num = |s: &str, what: &str| -> Result<f64> {
            match s.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(bad(format!("{what} must be finite"))),
                Err(_) => Err(bad(format!("{what} `{}` is not a number", s.trim()))),
            }
        };
        let parts: Vec<&str> = range.split(':').collect();
        match parts.len() {
            3 => {
                let (lo, hi) = (num(parts[0], "LO")?, num(parts[1], "HI")?);
                let n: usize = parts[2].trim().parse().map_err(|_| bad(format!("N `{}` is not a whole number", parts[2].trim())))?;
                if !(2..=1_000_000).contains(&n) {
                    return Err(bad(format!("N must lie between 2 and 1000000, got {n}")));
                }
                if !(hi > lo) {
                    return Err(bad("HI must exceed LO".into()));
                }
                Ok(Axis::linspace(path, lo, hi, n))
            }
            1 => {
                let values = range.split(',').map(|s| num(s, "value")).collect::<Result<Vec<_>>>()?;
                Ok(Axis::new(path, values))
            }
            _ => Err(bad("expected PATH=LO:HI:N".into())),
        }
    }
}

/// `v` rounded to 12 significant digits (0 stays 0).
fn round12(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let mag = 10f64.powi(11 - v.abs().log10().floor() as i32);
    let r = (v * mag).round() / mag;
    if r.is_finite() {
        r
    } else {
        v
    }
}

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
            if axes[..i].iter().any(|b| b.path == a.path) {
                return Err(Error::invalid(a.path.clone(), "the same path on two axes (one would silently win)"));
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
/// real balls' events ([`crate::balls`]; 0 for point masses).
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
];

/// The summary's numbers in the order of [`SUMMARY_COLUMNS`] (counts are exact in `f64` up
/// to 2⁵³).
pub fn summary_values(s: &Summary) -> [f64; 13] {
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
    ]
}

/// One run of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct PointResult {
    /// Its summary.
    pub summary: Summary,
    /// Wall-clock time of the run (s); the one column that differs between repetitions.
    pub wall_s: f64,
}

/// How a sweep ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SweepOutcome {
    /// Points asked for.
    pub points: usize,
    /// Points delivered to `on_row` (a prefix of them, in order).
    pub delivered: usize,
    /// Whether every point was delivered (`false`: stopped by `on_row` or `cancel`).
    pub complete: bool,
}

impl SweepOutcome {
    /// `Ok` when complete, else [`Error::Interrupted`] with the fraction delivered as `t`.
    pub fn into_result(self) -> Result<Self> {
        if self.complete {
            Ok(self)
        } else {
            Err(Error::Interrupted { t: self.delivered as f64 / self.points.max(1) as f64 })
        }
    }
}

/// The problem of one point: `base` with `values` set at `paths`, for a summary only; errors
/// name the path and the point.
pub fn problem_at(base: &PlanarProblem, paths: &[&str], values: &[f64]) -> Result<PlanarProblem> {
    let at = || paths.iter().zip(values).map(|(p, v)| format!("{p} = {}", fmt_num(*v))).collect::<Vec<_>>().join(", ");
    let mut p = base.clone();
    for (path, v) in paths.iter().zip(values) {
        p.set(path, *v).map_err(|e| with_point(e, &at()))?;
    }
    p.validate().map_err(|e| with_point(e, &at()))?;
    Ok(p)
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
fn run_points(
    base: &PlanarProblem,
    paths: &[&str],
    range: Range<usize>,
    point: &(dyn Fn(usize, &mut [f64]) + Sync),
    on_row: &mut dyn FnMut(usize, &[f64], &PointResult) -> bool,
    cancel: &(dyn Fn() -> bool + Sync),
) -> Result<SweepOutcome> {
    let k = paths.len();
    check_points(base, paths, range.clone(), point)?;
    let total = range.len();
    let stopping = AtomicBool::new(false);
    let stop_now = || {
        stopping.load(Ordering::Relaxed) || {
            let c = cancel();
            if c {
                stopping.store(true, Ordering::Relaxed);
            }
            c
        }
    };
    let mut out = SweepOutcome { points: total, delivered: 0, complete: true };
    let mut start = range.start;
    let block = block_len();
    while start < range.end {
        let end = (start + block).min(range.end);
        let results: Vec<Option<(Vec<f64>, PointResult)>> = (start..end)
            .into_par_iter()
            .map(|i| -> Result<Option<(Vec<f64>, PointResult)>> {
                if stop_now() {
                    return Ok(None);
                }
                let mut v = vec![0.0; k];
                point(i, &mut v);
                let p = problem_at(base, paths, &v)?;
                let t0 = std::time::Instant::now();
                // the run of `simulate` with the same settings (dt included: it is also the automatic
                // method's time resolution), sampled only at its ends; the stop is checked at every step
                let summary = simulate_summary(&p.rotor, &p.drive, &p.settings, Some(&stop_now))?;
                let wall_s = t0.elapsed().as_secs_f64();
                // a run cut short by the stop is no result
                Ok((!stopping.load(Ordering::Relaxed)).then_some((v, PointResult { summary, wall_s })))
            })
            .collect::<Result<_>>()?;
        for (i, r) in (start..end).zip(&results) {
            let Some((v, r)) = r else {
                out.complete = false;
                return Ok(out);
            };
            if !on_row(i, v, r) {
                out.delivered += 1;
                out.complete = out.delivered == total;
                return Ok(out);
            }
            out.delivered += 1;
        }
        start = end;
    }
    Ok(out)
}

/// Every point first: an invalid value must not surface after hours of runs.
fn check_points(base: &PlanarProblem, paths: &[&str], range: Range<usize>, point: &(dyn Fn(usize, &mut [f64]) + Sync)) -> Result<()> {
    let mut buf = vec![0.0; paths.len()];
    for i in range {
        point(i, &mut buf);
        problem_at(base, paths, &buf)?;
    }
    Ok(())
}

/// Check points `range` of `grid` on `base` as [`simulate_grid`] does before it runs anything
/// (for a caller that must know before it creates its output files); errors name the path and
/// the point.
pub fn check_grid(base: &PlanarProblem, grid: &Grid, range: Range<usize>) -> Result<()> {
    check_points(base, &grid.paths(), range, &|i, out| grid.point(i, out))
}

/// Check the points of a batch (`params` row after row, one value per path) as
/// [`simulate_batch`] does before it runs anything.
pub fn check_batch(base: &PlanarProblem, paths: &[&str], params: &[f64]) -> Result<()> {
    let k = paths.len().max(1);
    check_points(base, paths, 0..params.len() / k, &|i, out| out.copy_from_slice(&params[i * k..(i + 1) * k]))
}

/// Run points `range` of `grid` on `base` (see the module docs); `on_row(i, values, result)`
/// receives point `i` in order.
pub fn simulate_grid(
    base: &PlanarProblem,
    grid: &Grid,
    range: Range<usize>,
    on_row: &mut dyn FnMut(usize, &[f64], &PointResult) -> bool,
    cancel: &(dyn Fn() -> bool + Sync),
) -> Result<SweepOutcome> {
    if range.end > grid.len() {
        return Err(Error::invalid("range", format!("points {}..{} beyond the grid's {}", range.start, range.end, grid.len())));
    }
    let paths = grid.paths();
    run_points(base, &paths, range, &|i, out| grid.point(i, out), on_row, cancel)
}

/// Run `params.len() / paths.len()` points given row after row (`params[i k + j]` is the value
/// of `paths[j]` at point `i`); `on_row(i, values, result)` receives point `i` in order.
pub fn simulate_batch(
    base: &PlanarProblem,
    paths: &[&str],
    params: &[f64],
    on_row: &mut dyn FnMut(usize, &[f64], &PointResult) -> bool,
    cancel: &(dyn Fn() -> bool + Sync),
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
    run_points(base, paths, 0..n, &|i, out| out.copy_from_slice(&params[i * k..(i + 1) * k]), on_row, cancel)
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
        assert!(Grid::new(vec![Axis::new("a", vec![0.0; 100_000]), Axis::new("b", vec![0.0; 100_000])]).is_err());
        assert_eq!(Axis::linspace("c", 0.01, 0.4, 4).values, vec![0.01, 0.14, 0.27, 0.4]);
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
            &|| false,
        )
        .unwrap();
        assert_eq!((out.delivered, out.complete), (3, false));
        assert_eq!(seen, vec![0, 1, 2]);
        assert!(matches!(out.into_result(), Err(Error::Interrupted { .. })));
        // cancel from the start: nothing delivered, not complete
        let out = simulate_grid(&base, &g, 0..g.len(), &mut |_, _, _| true, &|| true).unwrap();
        assert_eq!((out.delivered, out.complete), (0, false));
    }

    #[test]
    fn invalid_points_name_the_path_and_the_point() {
        let base = short();
        let e = simulate_batch(&base, &["planar.m3", "drive.b"], &[0.03, 1.0, -0.01, 2.0], &mut |_, _, _| true, &|| false).unwrap_err().to_string();
        assert!(e.starts_with("planar.m3:") && e.contains("(at the point planar.m3 = -0.01, drive.b = 2)"), "{e}");
        let e = simulate_batch(&base, &["planar.m3"], &[], &mut |_, _, _| true, &|| false).unwrap();
        assert!(e.complete && e.points == 0);
        assert!(simulate_batch(&base, &["planar.m3", "drive.b"], &[1.0], &mut |_, _, _| true, &|| false).is_err());
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
                    &|| false,
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
            &|| false,
        )
        .unwrap();
        assert_eq!(whole, batch);
    }
}
