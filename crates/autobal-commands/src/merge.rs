//! `autobal merge`: the outputs of `autobal sweep --shard K/N` joined into the unsharded sweep's
//! `STEM.csv` and `STEM.json` (and `STEM.parquet`) with its figures `STEM_peak.svg` and
//! `STEM_final.svg` ([`merged_figures`]), every shard checked first (the same sweep,
//! each shard once and complete, every row its JSON's run), as one command ([`Args`] ->
//! `run` -> [`Output`]).

use crate::command;
use crate::sweep::{columns, SPATIAL_SUMMARY_COLUMNS, SUMMARY_COLUMNS};
use anyhow::{anyhow, bail, Context, Result};
use autobal::control::Control;
use autobal::sweep::LINEAR_SUMMARY_COLUMNS;
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};

/// `autobal merge`'s arguments.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The shards' CSV files (each with its `STEM.json` beside it), in any order.
    pub shards: Vec<PathBuf>,
    /// The output stem (a folder, `DIR/`: `DIR/sweep.*`).
    pub out: PathBuf,
    /// Also write `STEM.parquet`.
    pub parquet: bool,
}

/// `merge`'s result: the merged sweep's JSON and the files written.
pub struct Output {
    /// The merged JSON (the unsharded sweep's).
    pub json: Value,
    /// Shards merged, points in all.
    pub shards: u64,
    pub points: u64,
    /// The files written.
    pub csv: PathBuf,
    pub json_path: PathBuf,
    pub parquet: Option<PathBuf>,
    /// The figures drawn from the merged table, as `sweep` draws them ([`merged_figures`]),
    /// and the files they were written to (`STEM_peak.svg`, `STEM_final.svg`).
    pub figures: Vec<command::Figure>,
    pub figure_paths: Vec<PathBuf>,
}

impl command::Output for Output {
    fn json(&self) -> Result<Value> {
        Ok(self.json.clone())
    }
    fn table(&self) -> Result<String> {
        let figs: Vec<String> = self.figure_paths.iter().map(|p| format!(", {}", p.display())).collect();
        Ok(format!("merged {} shards, {} points: wrote {}, {}{}\n", self.shards, self.points, self.csv.display(), self.json_path.display(), figs.concat()))
    }
    /// `sweep_peak` and `sweep_final`, as the unsharded sweep's ([`merged_figures`]).
    fn figures(&self) -> Result<Vec<command::Figure>> {
        Ok(self.figures.iter().map(|f| command::Figure::new(&f.id, f.plot.clone())).collect())
    }
}

/// The figures of a merged sweep, drawn from its table as `sweep` draws them
/// ([`crate::linear_rotor::sweep_plots_of`]): each run's `peak_amplitude` and `final_amplitude`
/// against the first axis' value, a curve per value of the other axes; the model and the unit
/// of lengths from the header's columns and the JSON's problem (a spatial config with
/// `[dimensionless]`: `ρ_s`, else mm). At most [`crate::sweep::FIGURE_POINTS`] runs are drawn
/// (none past that, as `sweep`'s figures of a spilled sweep).
pub fn merged_figures(head: &str, csv: &str, json: &Value) -> Vec<command::Figure> {
    let paths: Vec<String> = json["paths"].as_array().map(|p| p.iter().filter_map(Value::as_str).map(String::from).collect()).unwrap_or_default();
    let refs: Vec<&str> = paths.iter().map(String::as_str).collect();
    let is = |c: &[&str]| head == columns(&refs, c).join(",");
    let (model, of, units) = if is(LINEAR_SUMMARY_COLUMNS) {
        ("Linear rotor", "first balancer plane", ("mm", 1e3))
    } else if is(SPATIAL_SUMMARY_COLUMNS) {
        let dimensionless = json["problem"]["config"].get("dimensionless").is_some();
        ("Spatial rotor", "first balancer plane", if dimensionless { ("ρ_s", 1.0) } else { ("mm", 1e3) })
    } else {
        ("Planar rotor", "rotor", ("mm", 1e3))
    };
    let names: Vec<&str> = head.split(',').collect();
    let col = |n: &str| names.iter().position(|h| *h == n);
    let (Some(pk), Some(fi)) = (col("peak_amplitude"), col("final_amplitude")) else { return vec![] };
    let rows: Vec<(Vec<f64>, [f64; 2])> = csv
        .lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<f64> = l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect();
            (f.len() == names.len()).then(|| (f[1..1 + paths.len()].to_vec(), [f[pk], f[fi]]))
        })
        .collect();
    if rows.is_empty() || rows.len() > crate::sweep::FIGURE_POINTS {
        return vec![];
    }
    crate::linear_rotor::sweep_plots_of(model, of, &paths, &rows, units).into_iter().map(|(id, plot)| command::Figure { id, plot }).collect()
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

impl command::Command for Args {
    const NAME: &'static str = "merge";
    type Output = Output;

    /// Check the outputs against each other and the shards, read and check every shard, then
    /// write every file under a temporary name, renamed into place only when all are written
    /// (Ctrl-C before then: nothing written).
    fn run(&self, control: &Control) -> Result<Output> {
        let a = self;
        if a.shards.is_empty() {
            return Err(autobal::Error::invalid("shards", "give the shards' CSV files (each with its STEM.json beside it)").into());
        }
        if a.out.as_os_str().is_empty() {
            return Err(autobal::Error::invalid("--out", "required: the merged sweep's stem").into());
        }
        // the outputs, checked against each other and the shards before anything is read
        let given = crate::outfile::resolve(&a.out, "sweep");
        let out = crate::term::out_stem(&given, &["csv", "json", "parquet"]);
        let (cp, jp, pp) = (crate::term::with_suffix(&out, "csv"), crate::term::with_suffix(&out, "json"), crate::term::with_suffix(&out, "parquet"));
        let mut outputs = crate::outfile::Outputs::new();
        for s in &a.shards {
            outputs.input("shard", s).input("shard JSON", &json_of(s));
        }
        outputs.stem("--out", &given, &out).output("--out", &cp).output("--out", &jp);
        let svg = crate::sweep::figure_paths(&out);
        for (p, _) in &svg {
            outputs.output("--out", p);
        }
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
        if ![SUMMARY_COLUMNS, SPATIAL_SUMMARY_COLUMNS, LINEAR_SUMMARY_COLUMNS].iter().any(|c| head == columns(&paths, c).join(",")) {
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
        let figures = merged_figures(&head, &csv, &json);
        let mut staged_svg = vec![];
        for (p, id) in &svg {
            if let Some(f) = figures.iter().find(|f| f.id == *id) {
                let mut s = crate::outfile::Staged::create("--out", p)?;
                s.write_all(f.plot.to_svg().as_bytes()).with_context(|| format!("--out: cannot write {}", p.display()))?;
                staged_svg.push((s, p.clone()));
            }
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
        let mut figure_paths = vec![];
        for (s, p) in staged_svg {
            s.commit()?;
            figure_paths.push(p);
        }
        let parquet = match pq {
            Some(t) => Some(t.finish()?),
            None => None,
        };
        Ok(Output { json, shards: n, points, csv: cp, json_path: jp, parquet, figures, figure_paths })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::{Command as _, ConfigSource, Output as _};
    use crate::sweep;

    /// Two shards written as the CLI writes them (CSV and JSON), given out of order, merge into
    /// the whole sweep: every run (but its wall time) and the definition's checksum; a shard
    /// given twice is refused naming it, before anything is written.
    #[test]
    fn merged_shards_are_the_whole_sweep() {
        let dir = std::env::temp_dir().join(format!("autobal-merge-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut root = crate::config::parse_text(crate::config::DEFAULT_PLANAR, "test").unwrap();
        for s in ["drive.t_end=1.0", "drive.omega0=250.0", "drive.b=100.0"] {
            crate::config::apply_set(&mut root, s).unwrap();
        }
        let args = sweep::Args {
            config: ConfigSource::tables(root, "test"),
            x: sweep::parse_axis("--x", "planar.c_psi=0.05:0.15:3").unwrap(),
            y: Some(sweep::parse_axis("--y", "drive.b=80,120").unwrap()),
            ..Default::default()
        };
        let mut shards = vec![];
        for k in [2, 1] {
            let plan = sweep::Args { shard: Some((k, 2)), ..args.clone() }.prepare().unwrap();
            let mut csv = vec![];
            let out = plan.run(&Control::none(), sweep::Rows::Files { csv: &mut csv, parquet: None, runs: None }).unwrap();
            let p = dir.join(format!("p{k}.csv"));
            std::fs::write(&p, csv).unwrap();
            std::fs::write(p.with_extension("json"), serde_json::to_string_pretty(&out.json().unwrap()).unwrap()).unwrap();
            shards.push(p);
        }
        let merged = Args { shards: shards.clone(), out: dir.join("merged"), parquet: false }.run(&Control::none()).unwrap();
        assert_eq!(
            merged.table().unwrap(),
            format!(
                "merged 2 shards, 6 points: wrote {}, {}, {}, {}\n",
                dir.join("merged.csv").display(),
                dir.join("merged.json").display(),
                dir.join("merged_peak.svg").display(),
                dir.join("merged_final.svg").display()
            )
        );
        // the figures are the unsharded sweep's, drawn from the merged table
        let whole_figs = args.run(&Control::none()).unwrap().figures().unwrap();
        let merged_figs = merged.figures().unwrap();
        assert_eq!(merged_figs.len(), 2);
        for (a, b) in whole_figs.iter().zip(&merged_figs) {
            assert_eq!((a.id.as_str(), a.plot.to_svg()), (b.id.as_str(), b.plot.to_svg()));
            assert_eq!(std::fs::read_to_string(dir.join(format!("merged_{}.svg", &a.id[6..]))).unwrap(), a.plot.to_svg());
        }
        let whole = args.run(&Control::none()).unwrap().json().unwrap();
        let runs = |v: &Value| -> Vec<Value> {
            v["runs"]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| {
                    let s: serde_json::Map<String, Value> =
                        r["summary"].as_object().unwrap().iter().filter(|(k, _)| !k.starts_with("wall")).map(|(k, v)| (k.clone(), v.clone())).collect();
                    json!([r["point"], r["values"], s])
                })
                .collect()
        };
        assert_eq!(runs(&merged.json), runs(&whole));
        assert_eq!(merged.json["definition_checksum"], whole["definition_checksum"]);
        assert_eq!((merged.json["complete"].clone(), merged.json["shard"].clone()), (json!(true), Value::Null));
        let read = std::fs::read_to_string(dir.join("merged.csv")).unwrap();
        assert_eq!(read.lines().count(), 7);
        let e = Args { shards: vec![shards[0].clone(), shards[0].clone()], out: dir.join("twice"), parquet: false }
            .run(&Control::none())
            .err()
            .unwrap()
            .to_string();
        assert!(e.starts_with("shard 2 of 2 is given twice"), "{e}");
        assert!(!dir.join("twice.csv").exists());
        std::fs::remove_dir_all(&dir).ok();
    }
}
