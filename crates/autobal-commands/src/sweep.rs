//! `autobal sweep` and `autobal merge`: simulation sweeps over a grid of parameter paths (the
//! library's [`autobal::sweep`] runs them; this module reads the config, writes CSV/JSON rows as
//! they arrive and prints the table), sharded for batch systems and merged back.

use crate::config;
use crate::term::{emit, Format};
use anyhow::{anyhow, bail, Context, Result};
use autobal::control::Control;
use autobal::planar::problem::PlanarProblem;
use autobal::sweep::{definition_checksum, shard, simulate_grid, Axis, Grid, SpatialSweep, SweepModel, SweepSummary, SPATIAL_SUMMARY_COLUMNS, SUMMARY_COLUMNS};
use clap::Args;
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct SweepArgs {
    /// Config file: the planar rotor of paper 004 ([planar], [drive], [integration]) or the
    /// spatial rotor of papers 000/003 (the analytic commands' tables plus [drive],
    /// [integration]); default: the embedded examples/planar.toml
    #[arg(long, short)]
    config: Option<PathBuf>,
    /// Override a config field for every run, e.g. --set planar.c_psi=0.1 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// First axis (varies fastest): PATH=LO:HI:N, PATH=V1,V2,… or PATH=V (e.g. drive.b=0.5:12.5:5;
    /// for a spatial config any of its keys, e.g. balancer.ball_mass=0.01:0.05:5, drive.psi0[2]=3:4:3)
    #[arg(long, value_name = "PATH=LO:HI:N")]
    x: String,
    /// Second axis (e.g. planar.c_psi=0.01:0.4:4)
    #[arg(long, value_name = "PATH=LO:HI:N")]
    y: Option<String>,
    /// More axes after x and y (repeatable), e.g. --axis 'drive.psi0[1]=0:3:4'
    #[arg(long = "axis", value_name = "PATH=LO:HI:N")]
    axes: Vec<String>,
    /// Run only shard K of N (1 ≤ K ≤ N): a contiguous part of the grid's points; merge the
    /// shards' outputs with `autobal merge`
    #[arg(long, value_name = "K/N")]
    shard: Option<String>,
    /// Output stem: STEM.csv (one row per run, written as runs finish, to a temporary name
    /// renamed when done or stopped) and STEM.json; a folder (`DIR/`): DIR/sweep.*
    #[arg(long, short, default_value = "sweep")]
    out: PathBuf,
    /// Also write the rows as Parquet, STEM.parquet (row groups written as runs finish)
    #[arg(long)]
    parquet: bool,
    /// Output on standard output: a table to read or JSON
    #[arg(long, value_enum, default_value = "table")]
    format: Format,
    /// Worker threads (default: all cores)
    #[arg(long)]
    threads: Option<usize>,
}

#[derive(Args)]
pub struct MergeArgs {
    /// The shards' CSV files (each with its STEM.json beside it), in any order
    #[arg(required = true, value_name = "SHARD.csv")]
    shards: Vec<PathBuf>,
    /// Output stem: STEM.csv and STEM.json, as the unsharded sweep writes them (a folder,
    /// `DIR/`: DIR/sweep.*); written only when every shard checks out
    #[arg(long, short)]
    out: PathBuf,
    /// Also write STEM.parquet, as `autobal sweep --parquet` does
    #[arg(long)]
    parquet: bool,
}

/// `K/N` (1-based) as a 0-based `(k, n)`.
fn parse_shard(spec: &str) -> Result<(usize, usize)> {
    let bad = || anyhow!("--shard {spec}: expected K/N with 1 ≤ K ≤ N, e.g. --shard 3/8");
    let (k, n) = spec.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k - 1, n))
}

/// The columns: point index, the axes' paths, the summary's columns (`summary`:
/// [`SUMMARY_COLUMNS`] or [`SPATIAL_SUMMARY_COLUMNS`]), the wall time.
fn columns(paths: &[&str], summary: &[&str]) -> Vec<String> {
    let mut cols = vec!["point"];
    cols.extend(paths);
    cols.extend(summary);
    cols.push("wall_s");
    cols.into_iter().map(String::from).collect()
}

/// Points whose warnings a sweep prints on standard error; the others are counted.
const PRINTED_WARNINGS: usize = 10;

/// A run's summary as the sweep's table shows it.
pub(crate) trait Row: SweepSummary {
    /// The table's header after the axes (`lu`: the unit of lengths).
    fn header(lu: &str) -> String;
    /// The row after the axes (`ls`: lengths in that unit per config unit).
    fn cells(&self, ls: f64) -> String;
    /// The run's warnings (its early stop first).
    fn warnings(&self) -> Vec<String>;
}

impl Row for autobal::planar::Summary {
    fn header(lu: &str) -> String {
        format!("{:>12} {:>12} {:>12} {:>9} {:>10}\n", format!("peak ({lu})"), "ω at peak", format!("final ({lu})"), "balanced", "steps")
    }
    fn cells(&self, ls: f64) -> String {
        format!("{:>12.4} {:>12.2} {:>12.4} {:>9} {:>10}", ls * self.peak_amplitude, self.omega_at_peak, ls * self.final_amplitude, self.balanced, self.steps)
    }
    fn warnings(&self) -> Vec<String> {
        self.stopped.iter().chain(&self.warnings).cloned().collect()
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
        self.stopped.iter().cloned().collect()
    }
}

/// The axes of `--x`, `--y` and `--axis`, each with its option, distinct.
fn parse_axes(a: &SweepArgs) -> Result<Vec<(&'static str, Axis)>> {
    let mut axes = vec![("--x", a.x.as_str())];
    axes.extend(a.y.as_deref().map(|y| ("--y", y)));
    axes.extend(a.axes.iter().map(|s| ("--axis", s.as_str())));
    let axes = axes
        .into_iter()
        .map(|(flag, spec)| {
            let ax = Axis::parse(spec).map_err(|e| anyhow!("{flag} {e}"))?;
            if ax.path == "omega" {
                bail!("{flag} {spec}: a sweep varies parameter paths (e.g. drive.b, planar.c_psi, drive.omega0), not omega");
            }
            Ok((flag, ax))
        })
        .collect::<Result<Vec<_>>>()?;
    for (i, (flag, ax)) in axes.iter().enumerate() {
        if let Some((first, _)) = axes[..i].iter().find(|(_, b)| b.path == ax.path) {
            bail!("{flag} {}: the same key as {first}; give this axis another field", ax.path);
        }
    }
    Ok(axes)
}

pub fn run(a: SweepArgs, control: &Control) -> Result<()> {
    // a linear rotor config ([linear_rotor]): its parameter paths (crate::linear_rotor::sweep_base)
    if let Some((root, base, problem)) = crate::linear_rotor::sweep_base(a.config.as_deref(), &a.set)? {
        return sweep_on(&a, &root, &base, parse_axes(&a)?, problem, ("mm", 1e3), control);
    }
    let (root, source) = config::read_planar_set(a.config.as_deref(), &a.set)?;
    let axes = parse_axes(&a)?;
    // the same rotor `simulate` runs on this config; another rotor's tables are refused by
    // config::check_entries
    if autobal::config::is_spatial(&root) {
        // the spatial rotor of papers 000/003: the config's keys are the paths
        let sim = crate::spatial_sim::build(&root, &source)?;
        config::check_entries(&root, "sweep", &[config::Model::Spatial])?;
        let base = SpatialSweep::new(root.clone())?;
        for (flag, ax) in &axes {
            // an unknown key, or one the config cannot take, before anything runs
            SpatialSweep::set(&mut root.clone(), &ax.path, ax.values[0]).map_err(|e| anyhow!("{flag} {e}"))?;
        }
        let problem = base.to_json()?;
        let units = if sim.config.dimensional { ("mm", 1e3) } else { ("ρ_s", 1.0) };
        return sweep_on(&a, &root, &base, axes, problem, units, control);
    }
    let cfg = config::build_planar(&root, &source)?;
    config::check_entries(&root, "sweep", &[config::Model::Planar])?;
    let base = PlanarProblem { rotor: cfg.rotor, drive: cfg.drive, settings: cfg.settings };
    for (flag, ax) in &axes {
        // an unknown path, or one the drive does not have, before anything runs
        let mut p = base.clone();
        autobal::paths::Parameters::set(&mut p, &ax.path, ax.values[0]).map_err(|e| anyhow!("{flag} {e}"))?;
    }
    let problem = serde_json::to_value(&base)?;
    sweep_on(&a, &root, &base, axes, problem, ("mm", 1e3), control)
}

/// Run the sweep of `base` over `axes` and write its outputs (`units`: the table's unit of
/// lengths and its factor).
#[allow(clippy::too_many_arguments)]
fn sweep_on<M>(a: &SweepArgs, root: &toml::Table, base: &M, axes: Vec<(&str, Axis)>, problem: Value, (lu, ls): (&str, f64), control: &Control) -> Result<()>
where
    M: SweepModel,
    M::Summary: Row,
{
    let grid = Grid::new(axes.into_iter().map(|(_, a)| a).collect())?;
    let (shard_kn, range) = match a.shard.as_deref() {
        Some(s) => {
            let (k, n) = parse_shard(s)?;
            ((Some((k + 1, n))), shard(grid.len(), k, n)?)
        }
        None => (None, 0..grid.len()),
    };
    if let Some(t) = a.threads {
        if t == 0 {
            bail!("--threads: must be at least 1");
        }
        rayon::ThreadPoolBuilder::new().num_threads(t).build_global().ok();
    }
    autobal::sweep::check_grid(base, &grid, range.clone())?;
    let checksum = definition_checksum(root, &grid);
    let out = &crate::term::out_stem(&crate::outfile::resolve(&a.out, "sweep"), &["csv", "json", "parquet"]);
    let csv_path = crate::term::with_suffix(out, "csv");
    let json_path = crate::term::with_suffix(out, "json");
    let mut outputs = crate::outfile::Outputs::new();
    outputs.inputs(a.config.as_deref()).output("--out", &csv_path).output("--out", &json_path);
    if a.parquet {
        outputs.output("--parquet", &crate::term::with_suffix(out, "parquet"));
    }
    outputs.check()?;
    // rows go to a temporary file, renamed into place when the sweep ends or is interrupted
    // (complete rows, with its JSON); an error removes it
    let mut csv = crate::outfile::Staged::create("--out", &csv_path)?;
    let paths = grid.paths();
    let cols = columns(&paths, <M::Summary as SweepSummary>::COLUMNS);
    writeln!(csv, "{}", cols.join(","))?;
    let mut pq = match a.parquet {
        true => Some(crate::parquet::Table::create(&crate::term::with_suffix(out, "parquet"), &cols, true)?),
        false => None,
    };
    let mut table = String::new();
    for k in paths.iter().take(2) {
        table.push_str(&format!("{k:>14} "));
    }
    table.push_str(&<M::Summary as Row>::header(lu));
    let bar = std::io::IsTerminal::is_terminal(&std::io::stderr()).then(|| indicatif::ProgressBar::new(range.len() as u64));
    let mut runs = vec![];
    // points whose runs have warnings: the first few are printed, the rest counted (every run's
    // warnings are in STEM.json)
    let mut warned = 0usize;
    let mut io_error = None;
    let outcome = simulate_grid(
        base,
        &grid,
        range.clone(),
        &mut |i, values, r| {
            let summary = r.summary.values();
            let mut line = format!("{i}");
            for v in values.iter().chain(&summary) {
                line.push(',');
                line.push_str(&crate::num::Csv(*v).to_string());
            }
            line.push_str(&format!(",{}\n", crate::num::Csv(r.wall_s)));
            if let Err(e) = csv.write_all(line.as_bytes()) {
                io_error = Some(anyhow!("--out: cannot write {}: {e}", csv_path.display()));
                return false;
            }
            if let Some(t) = pq.as_mut() {
                let row: Vec<f64> = std::iter::once(i as f64).chain(values.iter().copied()).chain(summary.iter().copied()).chain([r.wall_s]).collect();
                if let Err(e) = t.push(&row) {
                    io_error = Some(e);
                    return false;
                }
            }
            let s = &r.summary;
            for v in values.iter().take(2) {
                table.push_str(&format!("{v:>14} "));
            }
            let warnings = s.warnings();
            table.push_str(&format!("{}{}\n", s.cells(ls), warnings.first().map_or(String::new(), |w| format!("  ({w})"))));
            if !warnings.is_empty() {
                warned += 1;
                if warned <= PRINTED_WARNINGS {
                    for w in &warnings {
                        crate::term::note(&format!("warning: point {i} ({}): {w}", values.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", ")));
                    }
                }
            }
            runs.push(autobal::sweep::run_json(i, values, r));
            if let Some(b) = &bar {
                b.inc(1);
            }
            true
        },
        control,
    )?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if warned > PRINTED_WARNINGS {
        crate::term::note(&format!(
            "warning: {} more points have warnings (each run's warnings and stop reason are in {})",
            warned - PRINTED_WARNINGS,
            crate::term::with_suffix(out, "json").display()
        ));
    }
    if let Some(e) = io_error {
        return Err(e);
    }
    let mut json = autobal::sweep::report(&grid, shard_kn, &range, outcome.complete(), problem, runs);
    json["definition_checksum"] = json!(checksum);
    let csv_path = csv.commit()?;
    if let Some(t) = pq {
        crate::term::note(&format!("wrote {}", t.finish()?.display()));
    }
    crate::outfile::write_atomic("--out", &json_path, serde_json::to_string_pretty(&json)?)?;
    emit(a.format, json, table)?;
    if !outcome.complete() {
        bail!("interrupted: {} of {} runs complete, kept in {}", outcome.delivered, outcome.points, csv_path.display());
    }
    Ok(())
}

/// Largest shard file `merge` reads (CSV or JSON), bytes: a row is well under 1 kB, so 1 GiB
/// holds over a million points per shard; a wrong path (`/dev/zero`, a disk image) is refused
/// from its size before anything is read.
pub const MAX_SHARD_BYTES: u64 = 1 << 30;

/// Read a shard's file: a regular file of at most [`MAX_SHARD_BYTES`], as UTF-8.
fn read_bounded(p: &Path, what: &str) -> Result<String> {
    use std::io::Read;
    let meta = std::fs::metadata(p).with_context(|| format!("{}: cannot read {what}", p.display()))?;
    if !meta.is_file() {
        bail!("{}: {what} is not a regular file (a folder, device or pipe)", p.display());
    }
    if meta.len() > MAX_SHARD_BYTES {
        return Err(autobal::Error::TooLarge {
            what: format!("{} ({what})", p.display()),
            size: meta.len(),
            limit: MAX_SHARD_BYTES,
            reason: "bytes per shard file".into(),
        }
        .into());
    }
    let mut bytes = vec![];
    std::fs::File::open(p).and_then(|f| f.take(MAX_SHARD_BYTES + 1).read_to_end(&mut bytes)).with_context(|| format!("{}: cannot read {what}", p.display()))?;
    if bytes.len() as u64 > MAX_SHARD_BYTES {
        bail!("{}: {what} grew past {MAX_SHARD_BYTES} bytes while being read", p.display());
    }
    String::from_utf8(bytes).map_err(|e| anyhow!("{}: {what} is not UTF-8 text (byte {})", p.display(), e.utf8_error().valid_up_to()))
}

/// A shard's outputs: its JSON sidecar and its CSV text.
struct Shard {
    path: PathBuf,
    json: Value,
    csv: String,
}

/// The JSON beside a shard's CSV: `STEM.json` for `STEM.csv`.
fn json_of(p: &Path) -> PathBuf {
    p.with_extension("json")
}

fn read_shard(p: &Path) -> Result<Shard> {
    let csv = read_bounded(p, "the shard's CSV")?;
    let jp = json_of(p);
    let text = read_bounded(&jp, "the shard's JSON beside its CSV")?;
    let json: Value = serde_json::from_str(&text).map_err(|e| anyhow!("{}: not a sweep's JSON: {e}", jp.display()))?;
    if !json.is_object() {
        bail!("{}: not a sweep's JSON (not an object)", jp.display());
    }
    Ok(Shard { path: p.to_path_buf(), json, csv })
}

/// The grid's values at `point` from a sweep's JSON (`grid`: the axes, first varying fastest).
fn grid_values(json: &Value, point: u64) -> Option<Vec<f64>> {
    let mut idx = point;
    let mut out = vec![];
    for a in json["grid"].as_array()? {
        let vals = a["values"].as_array()?;
        let n = vals.len() as u64;
        if n == 0 {
            return None;
        }
        out.push(vals[(idx % n) as usize].as_f64()?);
        idx /= n;
    }
    Some(out)
}

/// Check every row of a shard: complete (ends with a line end, as many fields as the header),
/// every field a number, the points its JSON's `range` in order, the axis values those of the
/// grid at that point, and each row's point, values and wall time those of its JSON's run.
/// Errors name the shard and the line.
fn verify_rows(s: &Shard, head: &str, control: &Control) -> Result<Vec<String>> {
    let name = s.path.display();
    let width = head.split(',').count();
    let paths = s.json["paths"].as_array().map_or(0, |p| p.len());
    let range = (s.json["range"][0].as_u64(), s.json["range"][1].as_u64());
    let (Some(start), Some(end)) = range else { bail!("{}: no range [start, end] of points", json_of(&s.path).display()) };
    let runs = s.json["runs"].as_array().ok_or_else(|| anyhow!("{}: no runs", json_of(&s.path).display()))?;
    if !s.csv.is_empty() && !s.csv.ends_with('\n') {
        let last = s.csv.lines().count();
        bail!("{name}: line {last} is cut short (no line end): the shard was truncated mid-row; run this shard again");
    }
    let mut rows = vec![];
    let mut expected = start;
    for (i, l) in s.csv.lines().enumerate().skip(1) {
        let line = i + 1;
        if control.should_stop().is_some() {
            bail!("interrupted while reading {name}: nothing written");
        }
        let fields: Vec<&str> = l.split(',').collect();
        if fields.len() != width {
            bail!("{name}: line {line} has {} fields where the header has {width} (a row cut short or edited)", fields.len());
        }
        let point: u64 = fields[0].parse().map_err(|_| anyhow!("{name}: line {line}: the point index `{}` is not a whole number", fields[0]))?;
        let mut values = Vec::with_capacity(width);
        for (k, f) in fields.iter().enumerate().skip(1) {
            let v: f64 = f.parse().map_err(|_| anyhow!("{name}: line {line}, column {}: `{f}` is not a number", k + 1))?;
            values.push(v);
        }
        if point != expected {
            bail!("{name}: line {line}: point {point} where {expected} was expected (edited or truncated shard?)");
        }
        let grid = grid_values(&s.json, point).ok_or_else(|| anyhow!("{}: its grid does not give point {point}", json_of(&s.path).display()))?;
        if grid.len() != paths || values[..paths].iter().zip(&grid).any(|(a, b)| a.to_bits() != b.to_bits()) {
            bail!("{name}: line {line}: the axis values of point {point} are not the sweep's grid values {grid:?}");
        }
        let run =
            runs.get((point - start) as usize).ok_or_else(|| anyhow!("{name}: line {line}: point {point} has no run in {}", json_of(&s.path).display()))?;
        let json_values: Option<Vec<f64>> = run["values"].as_array().map(|v| v.iter().filter_map(Value::as_f64).collect());
        let wall = values.last().copied().unwrap_or(f64::NAN);
        if run["point"].as_u64() != Some(point)
            || json_values.as_deref() != Some(&grid[..])
            || run["wall_time_s"].as_f64().map(f64::to_bits) != Some(wall.to_bits())
        {
            bail!("{name}: line {line}: point {point} differs from its run in {} (CSV and JSON of different runs?)", json_of(&s.path).display());
        }
        rows.push(l.to_string());
        expected += 1;
    }
    if expected != end || runs.len() as u64 != end - start {
        bail!("{name}: holds points {start}..{expected} but its JSON says {start}..{end} with {} runs (truncated shard?)", runs.len());
    }
    Ok(rows)
}

pub fn merge(a: MergeArgs, control: &Control) -> Result<()> {
    // the outputs, checked against each other and the shards before anything is read
    let out = crate::term::out_stem(&crate::outfile::resolve(&a.out, "sweep"), &["csv", "json", "parquet"]);
    let (cp, jp, pp) = (crate::term::with_suffix(&out, "csv"), crate::term::with_suffix(&out, "json"), crate::term::with_suffix(&out, "parquet"));
    let mut outputs = crate::outfile::Outputs::new();
    for s in &a.shards {
        outputs.input("shard", s).input("shard JSON", &json_of(s));
    }
    outputs.output("--out", &cp).output("--out", &jp);
    if a.parquet {
        outputs.output("--parquet", &pp);
    }
    outputs.check()?;
    let mut shards = vec![];
    for p in &a.shards {
        if control.should_stop().is_some() {
            bail!("interrupted while reading the shards: nothing written");
        }
        shards.push(read_shard(p)?);
    }
    let name = |s: &Shard| s.path.display().to_string();
    let kn = |s: &Shard| -> Result<(u64, u64)> {
        let v = &s.json["shard"];
        match (v[0].as_u64(), v[1].as_u64()) {
            (Some(k), Some(n)) if k >= 1 && k <= n => Ok((k, n)),
            _ => bail!("{}: not a shard (run with --shard K/N)", name(s)),
        }
    };
    let n = kn(&shards[0])?.1;
    // the same sweep: the grid and problem, then the checksum of its definition (the config
    // text after --set and the axes)
    let sum = |s: &Shard| s.json["definition_checksum"].as_str().map(String::from);
    for s in &shards {
        let (_, ni) = kn(s)?;
        if ni != n {
            bail!("{}: shard of {ni}, but {} is a shard of {n}", name(s), name(&shards[0]));
        }
        for key in ["paths", "grid", "points", "problem"] {
            if s.json[key] != shards[0].json[key] {
                bail!("{}: a different sweep than {} (its {key} differ)", name(s), name(&shards[0]));
            }
        }
        if sum(s) != sum(&shards[0]) {
            let show = |x: Option<String>| x.unwrap_or_else(|| "none (an older autobal)".into());
            bail!(
                "{} and {}: shards of different sweeps (definition checksums {} and {}: the config, --set or axes differ)",
                name(&shards[0]),
                name(s),
                show(sum(&shards[0])),
                show(sum(s))
            );
        }
        if s.json["complete"] != Value::Bool(true) {
            bail!("{}: incomplete (interrupted); run this shard again", name(s));
        }
    }
    // each shard once: a duplicate names both files, a gap every missing shard
    let mut seen: Vec<Option<&Shard>> = vec![None; n as usize];
    for s in &shards {
        let k = kn(s)?.0;
        if let Some(first) = seen[(k - 1) as usize] {
            if crate::outfile::same_file(&first.path, &s.path) {
                bail!("shard {k} of {n} is given twice ({})", name(s));
            }
            bail!("shard {k} of {n} is given twice: {} and {}", name(first), name(s));
        }
        seen[(k - 1) as usize] = Some(s);
    }
    let missing: Vec<String> = seen.iter().enumerate().filter(|(_, s)| s.is_none()).map(|(k, _)| (k + 1).to_string()).collect();
    if !missing.is_empty() {
        bail!("shard{} {} of {n} {} missing", if missing.len() > 1 { "s" } else { "" }, missing.join(", "), if missing.len() > 1 { "are" } else { "is" });
    }
    shards.sort_by_key(|s| kn(s).map(|x| x.0).unwrap_or(0));
    let head = shards[0].csv.lines().next().unwrap_or_default().to_string();
    let paths: Vec<&str> = shards[0].json["paths"].as_array().map(|p| p.iter().filter_map(Value::as_str).collect()).unwrap_or_default();
    if head != columns(&paths, SUMMARY_COLUMNS).join(",") && head != columns(&paths, SPATIAL_SUMMARY_COLUMNS).join(",") {
        bail!("{}: its CSV header is not a sweep's over {} (`{head}`)", name(&shards[0]), paths.join(", "));
    }
    let mut csv = String::with_capacity(shards.iter().map(|s| s.csv.len()).sum());
    csv.push_str(&head);
    csv.push('\n');
    let mut runs = vec![];
    let mut next = 0u64;
    for s in &shards {
        if s.csv.lines().next() != Some(head.as_str()) {
            bail!("{}: its CSV header differs from {}", name(s), name(&shards[0]));
        }
        if s.json["range"][0].as_u64() != Some(next) {
            bail!("{}: starts at point {} where {next} was expected", name(s), s.json["range"][0]);
        }
        for l in verify_rows(s, &head, control)? {
            csv.push_str(&l);
            csv.push('\n');
            next += 1;
        }
        runs.extend(s.json["runs"].as_array().cloned().unwrap_or_default());
    }
    let points = shards[0].json["points"].as_u64().unwrap_or(0);
    if next != points {
        bail!("the shards hold {next} of the sweep's {points} points");
    }
    let mut json = shards[0].json.clone();
    json["shard"] = Value::Null;
    json["range"] = json!([0, points]);
    json["runs"] = Value::Array(runs);
    // every file to a temporary name; renamed into place only when all are written
    let mut pq = None;
    if a.parquet {
        let names: Vec<String> = head.split(',').map(String::from).collect();
        let mut t = crate::parquet::Table::create(&pp, &names, true)?;
        for l in csv.lines().skip(1) {
            if control.should_stop().is_some() {
                bail!("interrupted: nothing written");
            }
            let row = l.split(',').map(|v| v.parse::<f64>()).collect::<std::result::Result<Vec<_>, _>>();
            t.push(&row.map_err(|e| anyhow!("{}: a value that is not a number in the row `{l}`: {e}", cp.display()))?)?;
        }
        pq = Some(t);
    }
    let mut c = crate::outfile::Staged::create("--out", &cp)?;
    c.write_all(csv.as_bytes()).with_context(|| format!("--out: cannot write {}", cp.display()))?;
    let mut j = crate::outfile::Staged::create("--out", &jp)?;
    j.write_all(serde_json::to_string_pretty(&json)?.as_bytes()).with_context(|| format!("--out: cannot write {}", jp.display()))?;
    if control.should_stop().is_some() {
        bail!("interrupted: nothing written");
    }
    c.commit()?;
    j.commit()?;
    if let Some(t) = pq {
        crate::term::note(&format!("wrote {}", t.finish()?.display()));
    }
    crate::term::print(&format!("merged {n} shards, {points} points: wrote {}, {}\n", cp.display(), jp.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_specs() {
        assert_eq!(parse_shard("1/4").unwrap(), (0, 4));
        assert_eq!(parse_shard("4/4").unwrap(), (3, 4));
        for bad in ["0/4", "5/4", "x/4", "1", "1/0", "-1/3"] {
            assert!(parse_shard(bad).unwrap_err().to_string().starts_with("--shard"), "{bad}");
        }
    }
}
