//! `autobal sweep` and `autobal merge`: simulation sweeps over a grid of parameter paths (the
//! library's [`autobal::sweep`] runs them; this module reads the config, writes CSV/JSON rows as
//! they arrive and prints the table), sharded for batch systems and merged back.

use crate::config;
use crate::{emit, Format};
use anyhow::{anyhow, bail, Context, Result};
use autobal::planar::problem::PlanarProblem;
use autobal::sweep::{shard, simulate_grid, summary_values, Axis, Grid, SUMMARY_COLUMNS};
use clap::Args;
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

#[derive(Args)]
pub struct SweepArgs {
    /// Config file with the planar rotor of paper 004 ([planar], [drive], [integration]);
    /// default: the embedded examples/planar.toml
    #[arg(long, short)]
    config: Option<PathBuf>,
    /// Override a config field for every run, e.g. --set planar.c_psi=0.1 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// First axis (varies fastest): PATH=LO:HI:N, PATH=V1,V2,… or PATH=V (e.g. drive.b=0.5:12.5:5)
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
    /// Output stem: STEM.csv (one row per run, written as runs finish) and STEM.json
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
    /// Output stem: STEM.csv and STEM.json, as the unsharded sweep writes them
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

/// The columns: point index, the axes' paths, the summary's columns, the wall time.
fn columns(paths: &[&str]) -> Vec<String> {
    let mut cols = vec!["point"];
    cols.extend(paths);
    cols.extend(SUMMARY_COLUMNS);
    cols.push("wall_s");
    cols.into_iter().map(String::from).collect()
}

/// Points whose warnings a sweep prints on standard error; the others are counted.
const PRINTED_WARNINGS: usize = 10;

pub fn run(a: SweepArgs) -> Result<()> {
    let (root, source) = config::read_planar_set(a.config.as_deref(), &a.set)?;
    if autobal::config::is_spatial(&root) && !root.contains_key("planar") {
        bail!("config: `sweep` runs the planar rotor of paper 004 only ([planar], [drive]); the spatial rotor of papers 000/003 is simulated by `simulate` (and `basins` over the balls' initial angles)");
    }
    let cfg = config::build_planar(&root, &source)?;
    let base = PlanarProblem { rotor: cfg.rotor, drive: cfg.drive, settings: cfg.settings };
    let mut axes = vec![("--x", a.x.as_str())];
    axes.extend(a.y.as_deref().map(|y| ("--y", y)));
    axes.extend(a.axes.iter().map(|s| ("--axis", s.as_str())));
    let axes = axes
        .into_iter()
        .map(|(flag, spec)| {
            let ax = Axis::parse(spec).map_err(|e| anyhow!("{flag} {e}"))?;
            if ax.path == "omega" {
                bail!("{flag} {spec}: a sweep varies parameter paths (e.g. drive.b, planar.c_psi), not omega");
            }
            Ok((flag, ax))
        })
        .collect::<Result<Vec<_>>>()?;
    for (i, (flag, ax)) in axes.iter().enumerate() {
        if let Some((first, _)) = axes[..i].iter().find(|(_, b)| b.path == ax.path) {
            bail!("{flag} {}: the same key as {first}; give this axis another field", ax.path);
        }
        // an unknown path, or one the drive does not have, before anything runs
        let mut p = base.clone();
        autobal::paths::Parameters::set(&mut p, &ax.path, ax.values[0]).map_err(|e| anyhow!("{flag} {e}"))?;
    }
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
    autobal::sweep::check_grid(&base, &grid, range.clone())?;
    let _ = ctrlc::set_handler(|| crate::sim::INTERRUPTED.store(true, Ordering::Relaxed));
    let out = &crate::output::out_stem(&a.out, &["csv", "json", "parquet"]);
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("--out: cannot create {}", dir.display()))?;
    }
    let csv_path = crate::output::with_suffix(out, "csv");
    let file = std::fs::File::create(&csv_path).with_context(|| format!("--out: cannot create {}", csv_path.display()))?;
    let mut csv = std::io::BufWriter::new(file);
    let paths = grid.paths();
    writeln!(csv, "{}", columns(&paths).join(","))?;
    let mut pq = match a.parquet {
        true => Some(crate::parquet::Table::create(&crate::output::with_suffix(out, "parquet"), &columns(&paths), true)?),
        false => None,
    };
    let mut table = String::new();
    for k in paths.iter().take(2) {
        table.push_str(&format!("{k:>14} "));
    }
    table.push_str(&format!("{:>12} {:>12} {:>12} {:>9} {:>10}\n", "peak (mm)", "ω at peak", "final (mm)", "balanced", "steps"));
    let bar = std::io::IsTerminal::is_terminal(&std::io::stderr()).then(|| indicatif::ProgressBar::new(range.len() as u64));
    let mut runs = vec![];
    // points whose runs have warnings: the first few are printed, the rest counted (every run's
    // warnings are in STEM.json)
    let mut warned = 0usize;
    let mut io_error = None;
    let outcome = simulate_grid(
        &base,
        &grid,
        range.clone(),
        &mut |i, values, r| {
            let mut line = format!("{i}");
            for v in values.iter().chain(&summary_values(&r.summary)) {
                line.push(',');
                line.push_str(&crate::num::Csv(*v).to_string());
            }
            line.push_str(&format!(",{}\n", crate::num::Csv(r.wall_s)));
            if let Err(e) = csv.write_all(line.as_bytes()) {
                io_error = Some(anyhow!("--out: cannot write {}: {e}", csv_path.display()));
                return false;
            }
            if let Some(t) = pq.as_mut() {
                let row: Vec<f64> = std::iter::once(i as f64).chain(values.iter().copied()).chain(summary_values(&r.summary)).chain([r.wall_s]).collect();
                if let Err(e) = t.push(&row) {
                    io_error = Some(e);
                    return false;
                }
            }
            let s = &r.summary;
            for v in values.iter().take(2) {
                table.push_str(&format!("{v:>14} "));
            }
            table.push_str(&format!(
                "{:>12.4} {:>12.2} {:>12.4} {:>9} {:>10}{}\n",
                1e3 * s.peak_amplitude,
                s.omega_at_peak,
                1e3 * s.final_amplitude,
                s.balanced,
                s.steps,
                s.stopped.as_ref().or(s.warnings.first()).map_or(String::new(), |w| format!("  ({w})"))
            ));
            if s.stopped.is_some() || !s.warnings.is_empty() {
                warned += 1;
                if warned <= PRINTED_WARNINGS {
                    for w in s.stopped.iter().chain(&s.warnings) {
                        crate::output::note(&format!("warning: point {i} ({}): {w}", values.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", ")));
                    }
                }
            }
            runs.push(autobal::reports::sweep_run(i, values, r));
            if let Some(b) = &bar {
                b.inc(1);
            }
            !crate::sim::INTERRUPTED.load(Ordering::Relaxed)
        },
        &|| crate::sim::INTERRUPTED.load(Ordering::Relaxed),
    )?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if warned > PRINTED_WARNINGS {
        crate::output::note(&format!(
            "warning: {} more points have warnings (each run's warnings and stop reason are in {})",
            warned - PRINTED_WARNINGS,
            crate::output::with_suffix(out, "json").display()
        ));
    }
    csv.flush()?;
    if let Some(e) = io_error {
        return Err(e);
    }
    if let Some(t) = pq {
        crate::output::note(&format!("wrote {}", t.finish()?.display()));
    }
    let info = autobal::reports::SweepInfo { problem: &base, grid: &grid, shard: shard_kn, range: range.clone(), complete: outcome.complete };
    let json = autobal::reports::sweep(&info, runs);
    let json_path = crate::output::with_suffix(out, "json");
    std::fs::write(&json_path, serde_json::to_string_pretty(&json)?).with_context(|| format!("--out: cannot write {}", json_path.display()))?;
    emit(a.format, json, table)?;
    if !outcome.complete {
        bail!("interrupted: {} of {} runs complete, kept in {}", outcome.delivered, outcome.points, csv_path.display());
    }
    Ok(())
}

/// A shard's outputs: its JSON sidecar and its CSV text.
struct Shard {
    path: PathBuf,
    json: Value,
    csv: String,
}

fn read_shard(p: &Path) -> Result<Shard> {
    let csv = std::fs::read_to_string(p).with_context(|| format!("{}: cannot read", p.display()))?;
    let jp = p.with_extension("json");
    let text = std::fs::read_to_string(&jp).with_context(|| format!("{}: cannot read the shard's JSON beside its CSV", jp.display()))?;
    let json: Value = serde_json::from_str(&text).with_context(|| format!("{}: not a sweep's JSON", jp.display()))?;
    Ok(Shard { path: p.to_path_buf(), json, csv })
}

pub fn merge(a: MergeArgs) -> Result<()> {
    let mut shards = a.shards.iter().map(|p| read_shard(p)).collect::<Result<Vec<_>>>()?;
    let name = |s: &Shard| s.path.display().to_string();
    let kn = |s: &Shard| -> Result<(u64, u64)> {
        let v = &s.json["shard"];
        match (v[0].as_u64(), v[1].as_u64()) {
            (Some(k), Some(n)) => Ok((k, n)),
            _ => bail!("{}: not a shard (run with --shard K/N)", name(s)),
        }
    };
    let n = kn(&shards[0])?.1;
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
        if s.json["complete"] != Value::Bool(true) {
            bail!("{}: incomplete (interrupted); run this shard again", name(s));
        }
    }
    shards.sort_by_key(|s| kn(s).map(|x| x.0).unwrap_or(0));
    for (i, s) in shards.iter().enumerate() {
        let k = kn(s)?.0;
        if k != i as u64 + 1 {
            let dup = k <= i as u64;
            bail!("shard {} of {n} is {}", i + 1, if dup { format!("given twice ({})", name(s)) } else { "missing".into() });
        }
    }
    if shards.len() as u64 != n {
        bail!("shard {} of {n} is missing", shards.len() + 1);
    }
    let head = shards[0].csv.lines().next().unwrap_or_default().to_string();
    let mut csv = format!("{head}\n");
    let mut runs = vec![];
    let mut next = 0u64;
    for s in &shards {
        let mut lines = s.csv.lines();
        if lines.next() != Some(head.as_str()) {
            bail!("{}: its CSV header differs from {}", name(s), name(&shards[0]));
        }
        for l in lines {
            let point: u64 = l.split(',').next().and_then(|p| p.parse().ok()).ok_or_else(|| anyhow!("{}: a row without its point index", name(s)))?;
            if point != next {
                bail!("{}: point {point} where {next} was expected (edited or truncated shard?)", name(s));
            }
            next += 1;
            csv.push_str(l);
            csv.push('\n');
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
    let out = crate::output::out_stem(&a.out, &["csv", "json", "parquet"]);
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("--out: cannot create {}", dir.display()))?;
    }
    let (cp, jp) = (crate::output::with_suffix(&out, "csv"), crate::output::with_suffix(&out, "json"));
    if a.parquet {
        let names: Vec<String> = head.split(',').map(String::from).collect();
        let mut t = crate::parquet::Table::create(&crate::output::with_suffix(&out, "parquet"), &names, true)?;
        for l in csv.lines().skip(1) {
            let row = l.split(',').map(|v| v.parse::<f64>()).collect::<std::result::Result<Vec<_>, _>>();
            t.push(&row.map_err(|e| anyhow!("{}: a value that is not a number in the row `{l}`: {e}", cp.display()))?)?;
        }
        crate::output::note(&format!("wrote {}", t.finish()?.display()));
    }
    std::fs::write(&cp, csv).with_context(|| format!("--out: cannot write {}", cp.display()))?;
    std::fs::write(&jp, serde_json::to_string_pretty(&json)?).with_context(|| format!("--out: cannot write {}", jp.display()))?;
    crate::output::print(&format!("merged {n} shards, {points} points: wrote {}, {}\n", cp.display(), jp.display()))
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
