//! `autobal sweep`: simulations over a grid of parameter paths, as one command ([`Args`] ->
//! [`Args::prepare`] -> [`Plan::run`] -> [`Output`]): the library's [`autobal::sweep`] runs them
//! in parallel and hands the runs over in order; the CLI streams them to its CSV (and Parquet)
//! as they arrive and spills each run's JSON to a scratch file ([`Spill`]), so that its memory
//! does not grow with the number of points; Python takes the JSON. Sharded for batch systems
//! (`shard`), merged back by [`crate::merge`].

use crate::command::{self, ConfigSource};
use crate::config;
use anyhow::{anyhow, bail, Result};
use autobal::control::Control;
use autobal::planar::problem::PlanarProblem;
use autobal::sweep::{definition_checksum, shard, simulate_grid, Axis, Grid, SpatialSweep, SweepModel, SweepSummary};
pub use autobal::sweep::{SPATIAL_SUMMARY_COLUMNS, SUMMARY_COLUMNS};
use serde_json::{json, Value};
use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Seek, Write};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// `autobal sweep`'s arguments (`Default`: the CLI's defaults; `x` has none and is required).
#[derive(Debug, Clone)]
pub struct Args {
    /// The config: the planar rotor of paper 004 or the spatial rotor of papers 000/003 with
    /// `[drive]`; [`ConfigSource::File`] without a path is the embedded examples/planar.toml.
    pub config: ConfigSource,
    /// The first axis (varies fastest).
    pub x: Axis,
    /// The second axis.
    pub y: Option<Axis>,
    /// More axes after `x` and `y` (`--axis`).
    pub more: Vec<Axis>,
    /// Shard `K` of `N`, 1-based: a contiguous part of the grid's points.
    pub shard: Option<(usize, usize)>,
}

impl Default for Args {
    fn default() -> Self {
        Args { config: ConfigSource::default(), x: Axis::new("", vec![]), y: None, more: vec![], shard: None }
    }
}

/// An axis from its text form (`PATH=LO:HI:N`, `PATH=V1,V2,…`, `PATH=V`; `flag` names it in
/// errors): the library's [`Axis::parse`], a parameter path (not `omega`).
pub fn parse_axis(flag: &str, spec: &str) -> Result<Axis> {
    let ax = Axis::parse(spec).map_err(|e| anyhow!("{flag} {e}"))?;
    if ax.path == "omega" {
        bail!("{flag} {spec}: a sweep varies parameter paths (e.g. drive.b, planar.c_psi, drive.omega0), not omega");
    }
    Ok(ax)
}

/// `K/N` (1-based) as given: `1 ≤ K ≤ N`.
pub fn parse_shard(spec: &str) -> Result<(usize, usize)> {
    let bad = || anyhow!("--shard {spec}: expected K/N with 1 ≤ K ≤ N, e.g. --shard 3/8");
    let (k, n) = spec.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

/// The columns: point index, the axes' paths, the summary's columns (`summary`:
/// [`SUMMARY_COLUMNS`] or [`SPATIAL_SUMMARY_COLUMNS`]), the wall time.
pub fn columns(paths: &[&str], summary: &[&str]) -> Vec<String> {
    let mut cols = vec!["point"];
    cols.extend(paths);
    cols.extend(summary);
    cols.push("wall_s");
    cols.into_iter().map(String::from).collect()
}

/// Points whose warnings the notes list one by one; the others are counted.
const PRINTED_WARNINGS: usize = 10;

/// Rows the table shows (the first ones, in order); the others are counted in its last line
/// (`... N more rows in STEM.csv`), so that the table's memory does not grow with the grid.
pub const TABLE_ROWS: usize = 100;

/// Runs whose points a figure keeps when the runs are spilled to a file (the CLI's sweep):
/// past this many the CLI draws no figure and says so, so that its memory stays flat in the
/// points (a figure of more points is no longer read curve by curve anyway).
pub const FIGURE_POINTS: usize = 100_000;

/// The figures the CLI writes beside `STEM.csv`: `(figure id, file suffix)`, the file
/// `STEM_SUFFIX.svg` ([`figure_paths`]).
pub const FIGURES: [(&str, &str); 2] = [("sweep_peak", "peak"), ("sweep_final", "final")];

/// The figures' files of the stem `stem` with their ids: `STEM_peak.svg` (`sweep_peak`),
/// `STEM_final.svg` (`sweep_final`).
pub fn figure_paths(stem: &Path) -> Vec<(PathBuf, &'static str)> {
    FIGURES.iter().map(|(id, suffix)| (crate::sim::plot_path(stem, suffix), *id)).collect()
}

/// A run's summary as the sweep's table shows it.
pub(crate) trait Row: SweepSummary {
    /// The table's header after the axes (`lu`: the unit of lengths).
    fn header(lu: &str) -> String;
    /// The row after the axes (`ls`: lengths in that unit per config unit).
    fn cells(&self, ls: f64) -> String;
    /// The run's warnings (its early stop first).
    fn warnings(&self) -> Vec<String>;
    /// The run's peak and final whirl radius (config units: `peak_amplitude` and
    /// `final_amplitude` of its summary's values), the points of [`Output`]'s figures.
    fn peak_final(&self) -> [f64; 2];
}

impl Row for autobal::planar::Summary {
    fn header(lu: &str) -> String {
        format!(
            "{:>12} {:>12} {:>12} {:>9} {:>12} {:>19} {:>10}\n",
            format!("peak ({lu})"),
            "ω at peak",
            format!("final ({lu})"),
            "balanced",
            "residual",
            "outcome",
            "steps"
        )
    }
    fn cells(&self, ls: f64) -> String {
        // the outcome as the CSV's `outcome` and `simulate`'s JSON name it
        let outcome = serde_json::to_value(self.outcome).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default();
        format!(
            "{:>12.4} {:>12.2} {:>12.4} {:>9} {:>12.3e} {:>19} {:>10}",
            ls * self.peak_amplitude,
            self.omega_at_peak,
            ls * self.final_amplitude,
            self.balanced,
            self.residual_unbalance,
            outcome,
            self.steps
        )
    }
    fn warnings(&self) -> Vec<String> {
        self.stopped.iter().chain(&self.warnings).cloned().collect()
    }
    fn peak_final(&self) -> [f64; 2] {
        let v = autobal::sweep::summary_values(self);
        [v[0], v[3]]
    }
}

/// A linear rotor's run ([`crate::linear_rotor`] sweeps).
impl Row for autobal::linear_rotor::runup::RunSummary {
    fn header(lu: &str) -> String {
        format!("{:>12} {:>12} {:>15} {:>12} {:>10}\n", format!("peak ({lu})"), "ω at peak", format!("any node ({lu})"), format!("final ({lu})"), "steps")
    }
    fn cells(&self, ls: f64) -> String {
        let v = autobal::sweep::linear_summary_values(self);
        format!("{:>12.4} {:>12.2} {:>15.4} {:>12.4} {:>10}", ls * v[0], v[1], ls * v[3], ls * v[5], self.steps)
    }
    fn warnings(&self) -> Vec<String> {
        self.stopped.iter().chain(&self.warnings).cloned().collect()
    }
    fn peak_final(&self) -> [f64; 2] {
        let v = autobal::sweep::linear_summary_values(self);
        [v[0], v[5]]
    }
}

impl Row for autobal::spatial::dynamics::Summary {
    fn header(lu: &str) -> String {
        format!("{:>12} {:>12} {:>12} {:>12} {:>19} {:>10}\n", format!("peak ({lu})"), "ω at peak", format!("final ({lu})"), "residual", "outcome", "steps")
    }
    fn cells(&self, ls: f64) -> String {
        let outcome = serde_json::to_value(self.outcome).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default();
        format!(
            "{:>12.4} {:>12.4} {:>12.4} {:>12.3e} {:>19} {:>10}",
            ls * self.peak_amplitude,
            self.omega_at_peak,
            ls * self.final_amplitude,
            self.residual_unbalance,
            outcome,
            self.steps
        )
    }
    fn warnings(&self) -> Vec<String> {
        self.stopped.iter().chain(&self.warnings).cloned().collect()
    }
    fn peak_final(&self) -> [f64; 2] {
        let v = autobal::sweep::spatial_summary_values(self);
        [v[0], v[3]]
    }
}

/// Where a sweep's runs go as they arrive, besides the JSON.
pub enum Rows<'a> {
    /// The CSV (header first) and, where given, the Parquet table; with `runs`, each run's JSON
    /// (compact, one line each: [`autobal::sweep::run_json`]) goes there instead of memory,
    /// and [`Output::write_report`] reads it back.
    Files { csv: &'a mut dyn Write, parquet: Option<&'a mut crate::parquet::Table>, runs: Option<&'a mut dyn Write> },
    /// Nowhere else (Python's JSON: the runs are kept in the [`Output`], one compact JSON
    /// line each).
    None,
}

/// A scratch file for the runs' JSON lines ([`Rows::Files`]' `runs`), beside the outputs
/// (`NAME.runs.PID.part`): removed when dropped (on Unix at once, so that not even a killed
/// process leaves it behind: the open handle keeps it).
pub struct Spill {
    path: PathBuf,
    file: BufWriter<File>,
}

impl Spill {
    /// Create the scratch file beside `beside` (the JSON it is for).
    pub fn create(beside: &Path) -> Result<Self> {
        let mut name = beside.file_name().map(|n| n.to_os_string()).unwrap_or_default();
        name.push(format!(".runs.{}.part", std::process::id()));
        let path = beside.with_file_name(name);
        let f = File::options()
            .read(true)
            .write(true)
            .create(true)
            .truncate(true)
            .open(&path)
            .map_err(|e| anyhow!("--out: cannot create {}: {e}", path.display()))?;
        #[cfg(unix)]
        let _ = std::fs::remove_file(&path);
        Ok(Spill { path, file: BufWriter::with_capacity(1 << 16, f) })
    }

    /// The lines written, from the start.
    pub fn reader(&mut self) -> Result<BufReader<&File>> {
        self.file.flush().map_err(|e| anyhow!("--out: cannot write {}: {e}", self.path.display()))?;
        let mut f = self.file.get_ref();
        f.rewind()?;
        Ok(BufReader::with_capacity(1 << 16, f))
    }
}

impl Write for Spill {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.write(buf)
    }
    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.file.write_all(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl Drop for Spill {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// A sweep whose arguments, config and grid are checked ([`Args::prepare`]): a front end
/// checks its output files between the two.
pub struct Plan {
    base: Base,
    root: toml::Table,
    grid: Grid,
    shard: Option<(usize, usize)>,
    range: Range<usize>,
    problem: Value,
    /// The table's unit of lengths and its factor.
    units: (&'static str, f64),
    /// The most runs whose points the figures keep when the runs are spilled
    /// ([`FIGURE_POINTS`]); 0: none, whether spilled or not ([`Plan::without_figures`]).
    figure_points: usize,
}

enum Base {
    Planar(Box<PlanarProblem>),
    Spatial(Box<SpatialSweep>),
    Linear(Box<autobal::linear_rotor::spec::LinearRotorSpec>),
}

impl command::Command for Args {
    const NAME: &'static str = "sweep";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        self.prepare()?.run(control, Rows::None)
    }
}

/// The keys the spatial simulation reads without using them on `c` ([`config::check_axes`]):
/// `spatial.spin_drag` where the drive prescribes the speed; the parameters of another drive
/// kind ([`config::drive_key_unused`]); of `[analysis]`, the sensitivity's limit always, the
/// speeds but for the default run-up of a config without `[drive]` (its end:
/// `operating_speed`, else `omega_max`).
fn simulation_unused(c: &toml::Table, path: &str) -> Option<String> {
    // the drag on the spin acts only where a torque drives the spin, not where the speed is given
    let d = c.get("drive").and_then(toml::Value::as_table);
    let kind = d.and_then(|d| d.get("kind")).and_then(toml::Value::as_str).unwrap_or("acceleration");
    let of = d.and_then(|d| d.get("schedule_of")).and_then(toml::Value::as_str).unwrap_or("speed");
    if path == "spatial.spin_drag" && (matches!(kind, "speed" | "acceleration") || (kind == "schedule" && of == "speed")) {
        let of = if kind == "schedule" { format!(", schedule_of = \"{of}\"") } else { String::new() };
        return Some(format!("no effect on `sweep` with the rest of this config (with drive.kind = \"{kind}\"{of}: the speed is prescribed, the drag acts on a spin a torque drives)"));
    }
    if let Some(why) = config::drive_key_unused(c, path) {
        return Some(format!("no effect on `sweep` with the rest of this config ({why})"));
    }
    let has = |k: &str| c.get("analysis").and_then(|a| a.get(k)).is_some();
    let why = match path {
        "analysis.sensitivity_limit" => "an analytic commands' setting (the sensitivity's limit), which the simulation does not use",
        "analysis.omega_max" | "analysis.operating_speed" if c.contains_key("drive") => "it sets only the default run-up's end, and this config gives [drive]",
        "analysis.omega_max" if has("operating_speed") => "the default run-up ends at analysis.operating_speed",
        _ => return None,
    };
    Some(format!("no effect on `sweep` with the rest of this config ({why})"))
}

impl Args {
    /// The axes with their options, checked: parameter paths, distinct.
    fn axes(&self) -> Result<Vec<(&'static str, &Axis)>> {
        if self.x.path.is_empty() {
            return Err(autobal::Error::invalid("--x", "required: the first axis, e.g. --x drive.b=0.5:12.5:5").into());
        }
        let mut axes = vec![("--x", &self.x)];
        axes.extend(self.y.iter().map(|y| ("--y", y)));
        axes.extend(self.more.iter().map(|a| ("--axis", a)));
        for (i, (flag, ax)) in axes.iter().enumerate() {
            if ax.path == "omega" {
                bail!("{flag} {}: a sweep varies parameter paths (e.g. drive.b, planar.c_psi, drive.omega0), not omega", ax.path);
            }
            if let Some((first, _)) = axes[..i].iter().find(|(_, b)| b.path == ax.path) {
                bail!("{flag} {}: the same key as {first}; give this axis another field", ax.path);
            }
        }
        Ok(axes)
    }

    /// Read the config once, build the rotor `simulate` runs on it, check every axis against it
    /// (an unknown path, or a value it cannot take) and the grid, before anything runs or is
    /// written.
    pub fn prepare(&self) -> Result<Plan> {
        // a linear rotor config ([linear_rotor]): its parameter paths (crate::linear_rotor::sweep_base)
        if let ConfigSource::File { path, sets } = &self.config {
            if let Some((root, base, problem)) = crate::linear_rotor::sweep_base(path.as_deref(), sets)? {
                let axes = self.axes()?;
                Self::check_linear_axes(&base, &axes)?;
                return self.plan(Base::Linear(Box::new(base)), root, axes, problem, ("mm", 1e3));
            }
        }
        if let ConfigSource::Tables { root, dir, .. } = &self.config {
            if crate::linear_rotor::is_linear(root) {
                let (root, base, problem) = crate::linear_rotor::sweep_base_of(root.clone(), dir)?;
                let axes = self.axes()?;
                Self::check_linear_axes(&base, &axes)?;
                return self.plan(Base::Linear(Box::new(base)), root, axes, problem, ("mm", 1e3));
            }
        }
        let (root, source) = match &self.config {
            ConfigSource::File { path, sets } => config::read_planar_set(path.as_deref(), sets)?,
            c => c.read()?,
        };
        let axes = self.axes()?;
        // the same rotor `simulate` runs on this config; another rotor's tables are refused by
        // config::check_entries
        let (base, problem, units) = if autobal::config::is_spatial(&root) {
            // the spatial rotor of papers 000/003: the config's keys are the paths
            let sim = crate::spatial_sim::build(&root, &source)?;
            config::check_entries_with(&root, "sweep", &[config::Model::Spatial], config::FromLinear::RunUp)?;
            let base = SpatialSweep::new(root.clone())?;
            for (flag, ax) in &axes {
                SpatialSweep::set(&mut root.clone(), &ax.path, ax.values[0]).map_err(|e| anyhow!("{flag} {e}"))?;
            }
            // (after the paths' own checks, which name another rotor's key and a bad element)
            config::check_axes(&root, "sweep", &[config::Model::Spatial], &axes, &simulation_unused)?;
            let problem = base.to_json()?;
            let units = if sim.config.dimensional { ("mm", 1e3) } else { ("ρ_s", 1.0) };
            (Base::Spatial(Box::new(base)), problem, units)
        } else {
            let cfg = config::build_planar(&root, &source)?;
            config::check_entries(&root, "sweep", &[config::Model::Planar])?;
            let base = PlanarProblem { rotor: cfg.rotor, drive: cfg.drive, settings: cfg.settings };
            for (flag, ax) in &axes {
                let mut p = base.clone();
                autobal::paths::Parameters::set(&mut p, &ax.path, ax.values[0]).map_err(|e| anyhow!("{flag} {e}"))?;
            }
            config::check_axes(&root, "sweep", &[config::Model::Planar], &axes, &|_, _| None)?;
            let problem = serde_json::to_value(&base)?;
            (Base::Planar(Box::new(base)), problem, ("mm", 1e3))
        };
        self.plan(base, root, axes, problem, units)
    }

    /// A linear rotor's axes: `linear_rotor.omega_max` sets only the default run-up of a
    /// config without `[drive]` ([`crate::linear_rotor::drive_of`]).
    fn check_linear_axes(base: &autobal::linear_rotor::spec::LinearRotorSpec, axes: &[(&'static str, &Axis)]) -> Result<()> {
        for (flag, ax) in axes {
            if ax.path == "linear_rotor.omega_max" && base.config_at(&[])?.drive.is_some() {
                bail!("{flag} {}: no effect on `sweep` with the rest of this config (it sets only the default run-up's end, and this config gives [drive]); every point would be the same", ax.path);
            }
        }
        Ok(())
    }

    /// The grid and the shard's points, checked on `base`.
    fn plan(&self, base: Base, root: toml::Table, axes: Vec<(&'static str, &Axis)>, problem: Value, units: (&'static str, f64)) -> Result<Plan> {
        let grid = Grid::new(axes.into_iter().map(|(_, a)| a.clone()).collect())?;
        let range = match self.shard {
            // (--shard 1/1000000000000 on a one-point grid was taken: shards past the points run
            // nothing, and `merge` needs every one of the N outputs)
            Some((k, n)) if n > grid.len() => bail!(
                "--shard {k}/{n}: {n} shards of a grid of {} point{}: give N ≤ {} (every shard runs a point at least)",
                grid.len(),
                if grid.len() == 1 { "" } else { "s" },
                grid.len()
            ),
            Some((k, n)) if k >= 1 && k <= n => shard(grid.len(), k - 1, n)?,
            Some((k, n)) => bail!("--shard {k}/{n}: expected K/N with 1 ≤ K ≤ N, e.g. --shard 3/8"),
            None => 0..grid.len(),
        };
        match &base {
            Base::Planar(b) => autobal::sweep::check_grid(&**b, &grid, range.clone())?,
            Base::Spatial(b) => autobal::sweep::check_grid(&**b, &grid, range.clone())?,
            Base::Linear(b) => autobal::sweep::check_grid(&**b, &grid, range.clone())?,
        }
        Ok(Plan { base, root, grid, shard: self.shard, range, problem, units, figure_points: FIGURE_POINTS })
    }
}

impl Plan {
    /// The plan keeping no point for the figures (`--no-plots`): its output's figures
    /// ([`command::Output::figures`]) are none.
    pub fn without_figures(mut self) -> Self {
        self.figure_points = 0;
        self
    }

    /// The CSV's (and Parquet table's) columns.
    pub fn columns(&self) -> Vec<String> {
        let summary = match &self.base {
            Base::Planar(_) => SUMMARY_COLUMNS,
            Base::Spatial(_) => SPATIAL_SUMMARY_COLUMNS,
            Base::Linear(_) => autobal::sweep::LINEAR_SUMMARY_COLUMNS,
        };
        columns(&self.grid.paths(), summary)
    }

    /// Run the sweep's points under `control` (Ctrl-C keeps the runs finished, in order;
    /// progress in runs), the rows going to `rows` as they arrive.
    pub fn run(&self, control: &Control, rows: Rows<'_>) -> Result<Output> {
        match &self.base {
            Base::Planar(b) => self.run_on(&**b, control, rows),
            Base::Spatial(b) => self.run_on(&**b, control, rows),
            Base::Linear(b) => self.run_on(&**b, control, rows),
        }
    }

    fn run_on<M>(&self, base: &M, control: &Control, rows: Rows<'_>) -> Result<Output>
    where
        M: SweepModel,
        M::Summary: Row,
    {
        let (lu, ls) = self.units;
        let (mut csv, mut pq, mut spill) = match rows {
            Rows::Files { csv, parquet, runs } => (Some(csv), parquet, runs),
            Rows::None => (None, None, None),
        };
        let cols = self.columns();
        if let Some(w) = csv.as_mut() {
            writeln!(w, "{}", cols.join(","))?;
        }
        let paths = self.grid.paths();
        let mut table = String::new();
        for k in paths.iter().take(2) {
            table.push_str(&format!("{k:>14} "));
        }
        table.push_str(&<M::Summary as Row>::header(lu));
        // the runs' JSON, one compact line each: kept here, or spilled (then only counted)
        let (mut runs, mut spilled) = (vec![], 0usize);
        // the figures' points: every run's where the runs are kept, at most FIGURE_POINTS
        // where they are spilled (past them none: `unplotted`)
        let mut peaks = vec![];
        let mut unplotted = false;
        let mut more_rows = 0usize;
        // points whose runs have warnings: the first few listed, the rest counted (every run's
        // warnings are in the JSON)
        let (mut warned, mut warnings) = (0usize, vec![]);
        let mut io_error = None;
        let total = self.range.len() as u64;
        let mut done = 0u64;
        let outcome = simulate_grid(
            base,
            &self.grid,
            self.range.clone(),
            &mut |i, values, r| {
                let summary = r.summary.values();
                if let Some(w) = csv.as_mut() {
                    let mut line = format!("{i}");
                    for v in values.iter().chain(&summary) {
                        line.push(',');
                        line.push_str(&crate::num::Csv(*v).to_string());
                    }
                    line.push_str(&format!(",{}\n", crate::num::Csv(r.wall_s)));
                    if let Err(e) = w.write_all(line.as_bytes()) {
                        io_error = Some(anyhow!("--out: cannot write the CSV: {e}"));
                        return false;
                    }
                }
                if let Some(t) = pq.as_mut() {
                    let row: Vec<f64> = std::iter::once(i as f64).chain(values.iter().copied()).chain(summary.iter().copied()).chain([r.wall_s]).collect();
                    if let Err(e) = t.push(&row) {
                        io_error = Some(e);
                        return false;
                    }
                }
                let s = &r.summary;
                let ws = s.warnings();
                if done < TABLE_ROWS as u64 {
                    for v in values.iter().take(2) {
                        // 6 significant digits (Rust's `{v}` of 1e-300 is 300 digits wide)
                        table.push_str(&format!("{:>14} ", autobal::error::fmt_num(*v)));
                    }
                    table.push_str(&format!("{}{}\n", s.cells(ls), ws.first().map_or(String::new(), |w| format!("  ({w})"))));
                } else {
                    more_rows += 1;
                }
                if !ws.is_empty() {
                    warned += 1;
                    if warned <= PRINTED_WARNINGS {
                        for w in &ws {
                            warnings.push(format!(
                                "warning: point {i} ({}): {w}",
                                values.iter().map(|v| autobal::error::fmt_num(*v)).collect::<Vec<_>>().join(", ")
                            ));
                        }
                    }
                }
                let line = autobal::sweep::run_json(i, values, r).to_string();
                match spill.as_mut() {
                    Some(w) => {
                        if let Err(e) = w.write_all(line.as_bytes()).and_then(|()| w.write_all(b"\n")) {
                            io_error = Some(anyhow!("--out: cannot write the runs' JSON: {e}"));
                            return false;
                        }
                        spilled += 1;
                    }
                    None => runs.push(line.into_boxed_str()),
                }
                if self.figure_points > 0 && !unplotted {
                    if spill.is_some() && peaks.len() >= self.figure_points {
                        unplotted = true;
                        peaks = vec![];
                    } else {
                        peaks.push((values.to_vec(), s.peak_final()));
                    }
                }
                done += 1;
                control.report(done, total);
                true
            },
            control,
        )?;
        if let Some(e) = io_error {
            return Err(e);
        }
        let mut header = autobal::sweep::report(&self.grid, self.shard, &self.range, outcome.complete(), self.problem.clone(), vec![]);
        header["definition_checksum"] = json!(definition_checksum(&self.root, &self.grid));
        // a linear rotor's runs have no tolerance check (as `simulate`'s: review 26a)
        if !matches!(self.base, Base::Linear(_)) {
            header["tolerance_check"] = crate::tolerance::unchecked_runs(None).0;
        }
        let model = match &self.base {
            Base::Planar(_) => ("Planar rotor", "rotor"),
            Base::Spatial(_) => ("Spatial rotor", "first balancer plane"),
            Base::Linear(_) => ("Linear rotor", "first balancer plane"),
        };
        Ok(Output {
            header,
            runs: if spill.is_some() { Runs::Spilled(spilled) } else { Runs::Kept(runs) },
            table,
            more_rows,
            warnings,
            more_warned: warned.saturating_sub(PRINTED_WARNINGS),
            delivered: outcome.delivered,
            points: outcome.points,
            written: None,
            peaks,
            unplotted: unplotted.then_some(self.figure_points),
            paths: paths.iter().map(|p| p.to_string()).collect(),
            units: self.units,
            model,
        })
    }
}

/// The runs' JSON ([`autobal::sweep::run_json`], compact, one line each, in order).
enum Runs {
    /// Kept in memory.
    Kept(Vec<Box<str>>),
    /// Written to [`Rows::Files`]' `runs` (this many lines).
    Spilled(usize),
}

/// `sweep`'s result: its JSON (every run, in order), its table, its runs' warnings.
pub struct Output {
    /// The JSON but its runs (`runs` empty): the grid, the part, the problem, the checksum.
    header: Value,
    runs: Runs,
    /// The table's header and its first [`TABLE_ROWS`] rows.
    table: String,
    /// Rows beyond those in the table.
    more_rows: usize,
    /// The first runs' warnings, one line each.
    pub warnings: Vec<String>,
    /// Points with warnings beyond those listed.
    pub more_warned: usize,
    /// Runs finished, of `points`.
    pub delivered: usize,
    pub points: usize,
    /// The stem the front end wrote (`STEM.csv`, `STEM.json`), named in the messages.
    pub written: Option<PathBuf>,
    /// Each run's values and `[peak, final]` whirl radius ([`Row::peak_final`]), the figures'
    /// points (none with [`Plan::without_figures`], or past [`FIGURE_POINTS`] spilled runs).
    peaks: Vec<(Vec<f64>, [f64; 2])>,
    /// Where the runs were too many for the figures: the most they draw ([`FIGURE_POINTS`]).
    unplotted: Option<usize>,
    /// The axes' paths.
    paths: Vec<String>,
    /// The unit of lengths and its factor.
    units: (&'static str, f64),
    /// The rotor (the titles) and where its radii are taken (the curves).
    model: (&'static str, &'static str),
}

impl Output {
    /// Write the JSON (`STEM.json`, `--format json`), pretty-printed as
    /// `serde_json::to_string_pretty` would (keys in its order) but each run on one line, with
    /// a final newline, streamed: the runs from `spilled` (the lines written to
    /// [`Rows::Files`]' `runs`), or those kept. The whole JSON is never held in memory.
    pub fn write_report(&self, w: &mut dyn Write, spilled: Option<&mut dyn BufRead>) -> Result<()> {
        let mut lines: Box<dyn Iterator<Item = Result<String>> + '_> = match (&self.runs, spilled) {
            (Runs::Kept(runs), _) => Box::new(runs.iter().map(|l| Ok(l.to_string()))),
            (Runs::Spilled(n), Some(r)) => {
                let n = *n;
                Box::new(r.lines().take(n).map(|l| l.map_err(|e| anyhow!("cannot read the runs back: {e}"))))
            }
            (Runs::Spilled(_), None) => bail!("the runs were written to a file: give it to write the JSON"),
        };
        let header = self.header.as_object().ok_or_else(|| anyhow!("a sweep's JSON is an object"))?;
        w.write_all(b"{")?;
        for (i, (k, v)) in header.iter().enumerate() {
            w.write_all(if i == 0 { b"\n  " } else { b",\n  " })?;
            serde_json::to_writer(&mut *w, k)?;
            w.write_all(b": ")?;
            if k != "runs" {
                w.write_all(serde_json::to_string_pretty(v)?.replace('\n', "\n  ").as_bytes())?;
                continue;
            }
            let mut n = 0usize;
            for line in lines.by_ref() {
                w.write_all(if n == 0 { b"[\n    " } else { b",\n    " })?;
                w.write_all(line?.trim_end().as_bytes())?;
                n += 1;
            }
            w.write_all(if n == 0 { b"[]" } else { b"\n  ]" })?;
            let want = match &self.runs {
                Runs::Kept(r) => r.len(),
                Runs::Spilled(s) => *s,
            };
            if n != want {
                bail!("the runs' JSON: {n} of {want} runs read back");
            }
        }
        w.write_all(b"\n}\n")?;
        Ok(())
    }

    /// Lines for standard error: the first runs' warnings, the count of the others, and that no
    /// run's end was checked against a tighter tolerance (issue 18 item 4; audit 25: the
    /// outcomes read as answers).
    pub fn notes(&self) -> Vec<String> {
        let mut out = self.warnings.clone();
        if self.delivered > 0 && self.header.get("tolerance_check").is_some() {
            out.push(format!("note: {}", crate::tolerance::UNCHECKED_RUNS));
        }
        if self.more_warned > 0 {
            let json = self.written.as_ref().map_or("the JSON".to_string(), |s| crate::term::with_suffix(s, "json").display().to_string());
            out.push(format!("warning: {} more points have warnings (each run's warnings and stop reason are in {json})", self.more_warned));
        }
        if let Some(most) = self.unplotted {
            let csv = self.written.as_ref().map_or("the CSV".to_string(), |s| crate::term::with_suffix(s, "csv").display().to_string());
            out.push(format!("note: no figures: {} runs, more than the {most} a figure draws (plot the columns of {csv})", self.delivered));
        }
        out
    }
}

impl command::Output for Output {
    /// The JSON, every run parsed back from its line (exactly: `float_roundtrip`); an output
    /// whose runs were spilled to a file has none to give (the CLI streams its `STEM.json`).
    fn json(&self) -> Result<Value> {
        let Runs::Kept(runs) = &self.runs else { bail!("the runs were written to a file, not kept: read STEM.json") };
        let mut json = self.header.clone();
        json["runs"] = Value::Array(runs.iter().map(|l| serde_json::from_str(l)).collect::<serde_json::Result<_>>()?);
        Ok(json)
    }
    fn write_json(&self, out: &mut dyn Write) -> Result<()> {
        self.write_report(out, None)
    }
    fn table(&self) -> Result<String> {
        let mut t = self.table.clone();
        if self.more_rows > 0 {
            let whole = self.written.as_ref().map_or("the JSON".to_string(), |s| crate::term::with_suffix(s, "csv").display().to_string());
            t.push_str(&format!("... {} more rows in {whole}\n", self.more_rows));
        }
        Ok(t)
    }
    /// `sweep_peak` and `sweep_final`: each run's peak and final whirl radius against the first
    /// axis' value, a curve per value of the other axes
    /// ([`crate::linear_rotor::sweep_plots_of`]), of the runs finished; none without runs, with
    /// [`Plan::without_figures`], or past [`FIGURE_POINTS`] runs spilled to a file.
    fn figures(&self) -> Result<Vec<command::Figure>> {
        if self.peaks.is_empty() {
            return Ok(vec![]);
        }
        let (model, of) = self.model;
        Ok(crate::linear_rotor::sweep_plots_of(model, of, &self.paths, &self.peaks, self.units)
            .into_iter()
            .map(|(id, plot)| command::Figure { id, plot })
            .collect())
    }
    fn stopped(&self) -> Option<String> {
        (self.delivered < self.points).then(|| {
            format!(
                "interrupted: {} of {} runs complete{}",
                self.delivered,
                self.points,
                self.written.as_ref().map_or(String::new(), |s| format!(", kept in {}", crate::term::with_suffix(s, "csv").display()))
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::{Command as _, Output as _};

    #[test]
    fn shard_specs() {
        assert_eq!(parse_shard("1/4").unwrap(), (1, 4));
        assert_eq!(parse_shard("4/4").unwrap(), (4, 4));
        for bad in ["0/4", "5/4", "x/4", "1", "1/0", "-1/3"] {
            assert!(parse_shard(bad).unwrap_err().to_string().starts_with("--shard"), "{bad}");
        }
    }

    /// More shards than points is refused naming both (each of N shards runs a point at
    /// least, so that `merge` needs no output of a shard that ran nothing); N equal to the
    /// points is taken, one point each.
    #[test]
    fn shards_past_the_points_are_refused() {
        let args = |x: &str, shard| Args { config: short(), x: parse_axis("--x", x).unwrap(), shard: Some(shard), ..Default::default() };
        let e = args("drive.b=100", (1, 1_000_000_000_000)).prepare().err().unwrap().to_string();
        assert_eq!(e, "--shard 1/1000000000000: 1000000000000 shards of a grid of 1 point: give N ≤ 1 (every shard runs a point at least)");
        let e = args("drive.b=80,120", (3, 3)).prepare().err().unwrap().to_string();
        assert!(e.starts_with("--shard 3/3: 3 shards of a grid of 2 points: give N ≤ 2"), "{e}");
        let p = args("drive.b=80,120", (2, 2)).prepare().unwrap();
        assert_eq!(p.range, 1..2);
    }

    fn short() -> ConfigSource {
        let mut root = crate::config::parse_text(crate::config::DEFAULT_PLANAR, "test").unwrap();
        for s in ["drive.t_end=1.0", "drive.omega0=250.0", "drive.b=100.0"] {
            crate::config::apply_set(&mut root, s).unwrap();
        }
        ConfigSource::tables(root, "test")
    }

    /// The CSV the CLI streams is the JSON's runs, row by row (the axis values and the wall
    /// time bit for bit), and two shards are the whole sweep's runs, in order.
    #[test]
    fn csv_json_and_shards_are_one_sweep() {
        let args = Args {
            config: short(),
            x: parse_axis("--x", "planar.c_psi=0.05:0.15:3").unwrap(),
            y: Some(parse_axis("--y", "drive.b=80,120").unwrap()),
            ..Default::default()
        };
        let plan = args.prepare().unwrap();
        let mut csv = vec![];
        let out = plan.run(&Control::none(), Rows::Files { csv: &mut csv, parquet: None, runs: None }).unwrap();
        assert_eq!(out.stopped(), None);
        let text = String::from_utf8(csv).unwrap();
        let json = out.json().unwrap();
        let runs = json["runs"].as_array().unwrap();
        assert_eq!(text.lines().count(), 1 + 6);
        assert_eq!(text.lines().next().unwrap(), plan.columns().join(","));
        for (l, r) in text.lines().skip(1).zip(runs) {
            let f: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            assert_eq!(f[0] as u64, r["point"].as_u64().unwrap());
            let values: Vec<f64> = r["values"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
            assert_eq!(&f[1..3], &values[..]);
            assert_eq!(f.last().unwrap().to_bits(), r["wall_time_s"].as_f64().unwrap().to_bits());
        }
        let shard = |k| Args { shard: Some((k, 2)), ..args.clone() }.run(&Control::none()).unwrap().json().unwrap();
        let (a, b) = (shard(1), shard(2));
        // the runs but for their wall times (they differ between runs)
        let summary =
            |s: &Value| s.as_object().unwrap().iter().filter(|(k, _)| !k.starts_with("wall")).map(|(k, v)| (k.clone(), v.clone())).collect::<Vec<_>>();
        let strip =
            |v: &Value| v["runs"].as_array().unwrap().iter().map(|r| (r["point"].clone(), r["values"].clone(), summary(&r["summary"]))).collect::<Vec<_>>();
        let mut joined = strip(&a);
        joined.extend(strip(&b));
        assert_eq!(joined, strip(&json));
        assert_eq!(a["definition_checksum"], json["definition_checksum"]);
    }

    /// The figures of a sweep whose runs are spilled to a file (the CLI's): a vertex per run,
    /// at the run's first axis value and its peak and final radius (mm) as its JSON gives them;
    /// none with `without_figures`; none, and a note saying so, past the most a figure keeps.
    #[test]
    fn spilled_runs_keep_their_figures_points() {
        let args = Args {
            config: short(),
            x: parse_axis("--x", "planar.c_psi=0.05:0.15:3").unwrap(),
            y: Some(parse_axis("--y", "drive.b=80,120").unwrap()),
            ..Default::default()
        };
        let run = |plan: &Plan| {
            let (mut csv, mut spill) = (vec![], vec![]);
            let out = plan.run(&Control::none(), Rows::Files { csv: &mut csv, parquet: None, runs: Some(&mut spill) }).unwrap();
            (out, spill)
        };
        let plan = args.prepare().unwrap();
        let (out, spill) = run(&plan);
        let runs: Vec<Value> = String::from_utf8(spill).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        let figures = out.figures().unwrap();
        assert_eq!(figures.iter().map(|f| f.id.as_str()).collect::<Vec<_>>(), ["sweep_peak", "sweep_final"]);
        for (f, key) in figures.iter().zip(["peak_amplitude", "final_amplitude"]) {
            assert_eq!(f.plot.series.len(), 2, "a curve per drive.b");
            let got: Vec<(f64, f64)> = f.plot.series.iter().flat_map(|s| s.points.clone()).collect();
            // mm: the config's metres times 1e3, as the table shows them
            let want: Vec<(f64, f64)> = runs.iter().map(|r| (r["values"][0].as_f64().unwrap(), 1e3 * r["summary"][key].as_f64().unwrap())).collect();
            assert_eq!(got, want, "{key}");
        }
        assert!(out.notes().iter().all(|n| !n.contains("no figures")));
        let (none, _) = run(&args.prepare().unwrap().without_figures());
        assert!(none.figures().unwrap().is_empty());
        let mut capped = args.prepare().unwrap();
        capped.figure_points = 5;
        let (mut capped, _) = run(&capped);
        assert!(capped.figures().unwrap().is_empty(), "6 runs, at most 5 drawn");
        capped.written = Some("sw".into());
        assert!(
            capped.notes().contains(&"note: no figures: 6 runs, more than the 5 a figure draws (plot the columns of sw.csv)".to_string()),
            "{:?}",
            capped.notes()
        );
    }

    /// Bad axes and shards name their option, before anything runs.
    #[test]
    fn bad_axes_name_their_option() {
        let x = parse_axis("--x", "planar.c_psi=0.05:0.15:3").unwrap();
        for (args, start) in [
            (Args { config: short(), ..Default::default() }, "--x: required"),
            (Args { config: short(), x: x.clone(), y: Some(x.clone()), ..Default::default() }, "--y planar.c_psi: the same key as --x"),
            (Args { config: short(), x: x.clone(), more: vec![Axis::new("planar.nope", vec![1.0])], ..Default::default() }, "--axis planar.nope"),
            (Args { config: short(), x: x.clone(), shard: Some((3, 2)), ..Default::default() }, "--shard 3/2"),
        ] {
            let e = format!("{:#}", args.prepare().err().expect("refused"));
            assert!(e.starts_with(start), "{e}");
        }
        assert!(parse_axis("--y", "omega=1:2:3").unwrap_err().to_string().starts_with("--y omega=1:2:3: a sweep varies parameter paths"));
    }

    /// A sweep stopped before its first run keeps nothing and says so.
    #[test]
    fn a_stopped_sweep_says_what_it_kept() {
        let control = Control::new();
        control.cancel();
        let args = Args { config: short(), x: parse_axis("--x", "planar.c_psi=0.05:0.15:3").unwrap(), ..Default::default() };
        let mut out = args.run(&control).unwrap();
        assert_eq!(out.json().unwrap()["complete"], json!(false));
        assert_eq!(out.stopped().unwrap(), format!("interrupted: {} of 3 runs complete", out.delivered));
        out.written = Some("sw".into());
        assert!(out.stopped().unwrap().ends_with(", kept in sw.csv"));
    }

    /// The JSON streamed from the spilled runs ([`Output::write_report`], the CLI's
    /// `STEM.json`) is, as parsed JSON, the one built in memory the way it was before the
    /// spill (`report` with every run's `run_json` value, pretty-printed by serde_json):
    /// every key and value, the same runs in order, exactly (the spill's numbers are read back
    /// with `float_roundtrip`); a sweep kept in memory (Python's) writes the same text as
    /// its `json()`. Past [`TABLE_ROWS`] rows, the table counts the others.
    #[test]
    fn streamed_json_equals_the_json_built_in_memory() {
        let mut root = crate::config::parse_text(crate::config::DEFAULT_PLANAR, "test").unwrap();
        // short runs: the test is about the files, not the physics
        for s in ["drive.t_end=0.05", "drive.omega0=250.0", "drive.b=100.0"] {
            crate::config::apply_set(&mut root, s).unwrap();
        }
        let args = Args {
            config: ConfigSource::tables(root, "test"),
            x: parse_axis("--x", "planar.c_psi=0.05:0.15:3").unwrap(),
            y: Some(parse_axis("--y", &format!("drive.b=80:120:{}", TABLE_ROWS / 3 + 2)).unwrap()),
            shard: Some((1, 1)),
            ..Default::default()
        };
        let plan = args.prepare().unwrap();
        let (mut csv, mut spill) = (vec![], vec![]);
        let mut out = plan.run(&Control::none(), Rows::Files { csv: &mut csv, parquet: None, runs: Some(&mut spill) }).unwrap();
        let points = plan.grid.len();
        assert!(points > TABLE_ROWS);
        // one compact run per line
        let spilled = String::from_utf8(spill.clone()).unwrap();
        assert_eq!(spilled.lines().count(), points);
        assert!(out.json().is_err(), "the runs were not kept");
        let mut text = vec![];
        out.write_report(&mut text, Some(&mut &spill[..])).unwrap();
        let text = String::from_utf8(text).unwrap();
        let streamed: Value = serde_json::from_str(&text).unwrap();
        // built in memory, as before: every run a Value, the report pretty-printed
        let runs: Vec<Value> = spilled.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        let mut built = autobal::sweep::report(&plan.grid, plan.shard, &plan.range, true, plan.problem.clone(), runs);
        built["definition_checksum"] = json!(definition_checksum(&plan.root, &plan.grid));
        built["tolerance_check"] = crate::tolerance::unchecked_runs(None).0;
        let built: Value = serde_json::from_str(&serde_json::to_string_pretty(&built).unwrap()).unwrap();
        assert_eq!(streamed, built);
        assert_eq!(streamed["runs"].as_array().unwrap().len(), points);
        assert_eq!(streamed["shard"], json!([1, 1]));
        // the keys in serde_json's order, each run on one line, a final newline
        let keys: Vec<&str> = text.lines().filter(|l| l.starts_with("  \"")).map(|l| &l[3..l[3..].find('"').unwrap() + 3]).collect();
        assert_eq!(keys, built.as_object().unwrap().keys().map(String::as_str).collect::<Vec<_>>());
        assert_eq!(text.lines().filter(|l| l.starts_with("    {\"point\":")).count(), points);
        assert!(text.ends_with("\n}\n"));
        // a spill cut short is an error, not a JSON with runs missing
        let cut = &spill[..spill.len() / 2];
        assert!(out.write_report(&mut vec![], Some(&mut &cut[..])).is_err());
        // the table: the first TABLE_ROWS rows, then the count of the others
        let table = out.table().unwrap();
        assert_eq!(table.lines().count(), 1 + TABLE_ROWS + 1);
        assert!(table.ends_with(&format!("... {} more rows in the JSON\n", points - TABLE_ROWS)), "{table}");
        out.written = Some("sw".into());
        assert!(out.table().unwrap().ends_with(&format!("... {} more rows in sw.csv\n", points - TABLE_ROWS)));
        // kept in memory (Python's route): write_json is json(), pretty-printed
        let kept = plan.run(&Control::none(), Rows::None).unwrap();
        let mut text = vec![];
        kept.write_json(&mut text).unwrap();
        assert_eq!(serde_json::from_slice::<Value>(&text).unwrap(), kept.json().unwrap());
    }
}
