//! The commands on a linear rotor config (`[linear_rotor]`, issue 19 "your own rotor"): reading
//! the config and its Matrix Market files ([`load`]), `stability` (the balanced state over
//! speed, [`autobal::linear_rotor::stability`]), `simulate` (a run in time with a prescribed
//! speed, [`autobal::linear_rotor::runup`]) and `export-model` (a rotor written as config plus
//! matrix files, [`autobal::linear_rotor::config::export`]).

use crate::config;
use crate::num::Csv;
use crate::outfile;
use anyhow::{anyhow, bail, Result};
use autobal::analysis::{Kind, Verdict};
use autobal::error::fmt_num;
use autobal::linear_rotor::config::{export, linear_rotor, LinearRotorConfig};
use autobal::linear_rotor::reduce::{reduce, Reduction};
use autobal::linear_rotor::runup::{simulate, RunSample, RunSettings, RunSummary};
use autobal::linear_rotor::LinearRotor;
use autobal::rotor_stability::{speed_grid, RotorStability};
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};
use toml::Table;

/// Largest matrix file read (bytes): a dense 2000-DOF matrix in text is about 100 MB.
pub const MAX_MATRIX_BYTES: u64 = 256 << 20;

/// Whether the config at `path` (after `--set`) is a linear rotor config.
pub fn is_linear(root: &Table) -> bool {
    autobal::linear_rotor::config::is_linear_rotor(root)
}

/// Read a matrix file named in the config, relative to the config's folder.
fn read_matrix(dir: &Path, name: &str) -> std::result::Result<String, String> {
    use std::io::Read;
    let p = dir.join(name);
    let f = std::fs::File::open(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))?;
    let mut bytes = vec![];
    f.take(MAX_MATRIX_BYTES + 1).read_to_end(&mut bytes).map_err(|e| format!("cannot read {}: {e}", p.display()))?;
    if bytes.len() as u64 > MAX_MATRIX_BYTES {
        return Err(format!("larger than {} bytes", MAX_MATRIX_BYTES));
    }
    String::from_utf8(bytes).map_err(|e| format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
}

/// The linear rotor config of a parsed table; matrix files are read relative to `dir`.
pub fn from_table(root: &Table, dir: &Path) -> Result<LinearRotorConfig> {
    Ok(linear_rotor(root, &mut |name| read_matrix(dir, name))?)
}

/// Apply one `--set table.key=value` to a linear rotor config (its own tables, not the schema of
/// the papers' configs): `linear_rotor.KEY`, `drive.KEY`, `integration.KEY`.
pub fn apply_set(root: &mut Table, assignment: &str) -> Result<()> {
    let (key, value) = assignment.split_once('=').ok_or_else(|| anyhow!("--set {assignment}: expected key=value, e.g. --set linear_rotor.omega_max=1500"))?;
    let (t, k) = key.trim().split_once('.').ok_or_else(|| anyhow!("--set {key}: expected a dotted key table.field, e.g. --set drive.t_end=2"))?;
    if !["linear_rotor", "drive", "integration"].contains(&t) || k.is_empty() || k.contains('.') {
        bail!("--set {key}: a linear rotor config sets linear_rotor.KEY, drive.KEY or integration.KEY (entries of [[linear_rotor.balancer]] and the like are edited in the file)");
    }
    let table = root.entry(t.to_string()).or_insert_with(|| toml::Value::Table(Table::new()));
    let table = table.as_table_mut().ok_or_else(|| anyhow!("--set {key}: `{t}` is not a table"))?;
    table.insert(k.to_string(), autobal::config::parse_value(value.trim()));
    Ok(())
}

/// Read the config at `path` (or the embedded default) and apply `--set`: a linear rotor
/// config's own way ([`apply_set`]), any other config's through [`config::apply_set`].
pub fn read_set(path: Option<&Path>, sets: &[String]) -> Result<(Table, String)> {
    let (mut root, source) = config::read(path)?;
    let linear = is_linear(&root);
    for s in sets {
        if linear {
            apply_set(&mut root, s)?;
        } else {
            config::apply_set(&mut root, s)?;
        }
    }
    Ok((root, source))
}

/// Read the config at `path`, apply `--set`, build the rotor.
pub fn load(path: &Path, sets: &[String]) -> Result<LinearRotorConfig> {
    let (root, _) = read_set(Some(path), sets)?;
    from_table(&root, path.parent().unwrap_or(Path::new(".")))
}

/// The default top of the speed axis: `linear_rotor.omega_max`, else 1.5 × the highest
/// undamped natural frequency (with the balls as rings) among the lowest four, at least 3 × the
/// first.
pub fn default_omega_max(cfg: &LinearRotorConfig) -> Result<f64> {
    if let Some(w) = cfg.omega_max {
        return Ok(w);
    }
    let r = cfg.rotor.at_speed(0.0);
    let w = r.natural_frequencies(&[], true)?;
    let pos: Vec<f64> = w.into_iter().filter(|v| *v > 0.0).collect();
    let first = *pos.first().ok_or_else(|| anyhow!("linear_rotor: the rotor has no positive natural frequency; give linear_rotor.omega_max"))?;
    Ok((1.5 * pos[pos.len().min(4) - 1]).max(3.0 * first))
}

fn rpm(w: f64) -> f64 {
    w * 30.0 / std::f64::consts::PI
}

fn speed_text(w: f64) -> String {
    format!("{} rad/s ({} rpm)", fmt_num(crate::num::round_sig(w, 6).unwrap_or(w)), fmt_num(crate::num::round_sig(rpm(w), 6).unwrap_or(w)))
}

/// The rotor the commands run: the config's, or its reduction (`linear_rotor.modes`).
pub fn model(cfg: &LinearRotorConfig) -> Result<(LinearRotor, Option<Reduction>)> {
    match cfg.modes {
        None => Ok((cfg.rotor.clone(), None)),
        Some(p) => {
            let r = reduce(&cfg.rotor, p, &[])?;
            Ok((r.rotor.clone(), Some(r)))
        }
    }
}

/// The reduction's JSON: sizes, cut-off, and the lowest natural frequencies with their interval
/// and estimated error.
pub fn reduction_json(r: &Option<Reduction>) -> Value {
    match r {
        None => Value::Null,
        Some(r) => json!({
            "dofs_full": r.dofs.0,
            "dofs_reduced": r.dofs.1,
            "boundary_nodes": r.boundary,
            "mode_pairs": r.mode_pairs,
            "cutoff": r.cutoff,
            "first_neglected": r.first_neglected,
            "frequencies": r.frequencies.iter().take(8).collect::<Vec<_>>(),
        }),
    }
}

/// The reduction in one or two lines of the table.
pub fn reduction_text(r: &Option<Reduction>) -> String {
    let Some(r) = r else { return String::new() };
    let mut s = format!(
        "reduced: {} of {} DOFs (boundary nodes {:?} physical, {} interior mode pairs up to {}; first neglected {})\n",
        r.dofs.1,
        r.dofs.0,
        r.boundary,
        r.mode_pairs,
        r.cutoff.map_or("-".into(), speed_text),
        r.first_neglected.map_or("none".into(), speed_text)
    );
    let est: Vec<String> = r
        .frequencies
        .iter()
        .take(4)
        .map(|f| {
            format!(
                "{} ± {}",
                fmt_num(crate::num::round_sig(f.omega, 6).unwrap_or(f.omega)),
                f.estimate.map_or("?".into(), |e| fmt_num(crate::num::round_sig(e, 2).unwrap_or(e)))
            )
        })
        .collect();
    s.push_str(&format!("reduced natural frequencies at rest without the balls (rad/s, ± the estimated error): {}\n", est.join(", ")));
    s
}

/// `stability`: the balanced state over `(0, omega_max]` with `samples` speeds, on the model of
/// [`model`].
pub fn stability(cfg: &LinearRotorConfig, omega_max: f64, samples: usize) -> Result<(RotorStability, Option<Reduction>)> {
    let speeds = speed_grid(omega_max, samples)?;
    let (rotor, red) = model(cfg)?;
    Ok((autobal::linear_rotor::stability::stability_over_speed(&rotor, &speeds)?, red))
}

/// The undamped natural frequencies (rad/s) of the rotor at rest with its balls as rings, the
/// lowest `count`.
pub fn natural_frequencies(rotor: &LinearRotor, count: usize) -> Result<Vec<f64>> {
    let mut w = rotor.at_speed(0.0).natural_frequencies(&[], true)?;
    w.truncate(count);
    Ok(w)
}

/// The JSON of `stability`; the natural frequencies (with the balls as rings) are those of the
/// model analysed (the reduced one where the config reduces).
pub fn stability_json(cfg: &LinearRotorConfig, r: &RotorStability, red: &Option<Reduction>, omega_max: f64) -> Result<Value> {
    let ranges: Vec<Value> = r
        .stable_ranges
        .iter()
        .map(|s| json!({ "from": s.from, "to": s.to, "from_rpm": rpm(s.from), "to_rpm": rpm(s.to), "from_is_boundary": s.from_is_boundary, "to_is_boundary": s.to_is_boundary }))
        .collect();
    Ok(json!({
        "route": "general",
        "model": r.model,
        "source": cfg.source,
        "dofs": cfg.rotor.dofs(),
        "balls": cfg.rotor.total_balls(),
        "natural_frequencies": natural_frequencies(red.as_ref().map_or(&cfg.rotor, |r| &r.rotor), 6)?,
        "reduction": reduction_json(red),
        "stationary_state": r.kind,
        "speed_unit": "rad/s",
        "omega_max": omega_max,
        "stable_ranges": ranges,
        "family_dimension": r.family_dimension,
        "member_psi": r.member_psi,
        "points": r.points,
    }))
}

/// The table of `stability`.
pub fn stability_table(cfg: &LinearRotorConfig, r: &RotorStability, red: &Option<Reduction>, omega_max: f64) -> Result<String> {
    let mut s = String::from("Linear rotor: the balanced state's exact linear stability over speed\n");
    s.push_str(&format!(
        "model: {} DOFs ({}), {} balancer plane(s) with {} balls, {} unbalance(s); {}\n",
        cfg.rotor.dofs(),
        if cfg.source == "shaft" { "built-in shaft builder" } else { "matrix files" },
        cfg.rotor.balancers.len(),
        cfg.rotor.total_balls(),
        cfg.rotor.unbalances.len(),
        match r.kind {
            Kind::Equilibrium => "isotropic: an equilibrium in axes turning with the rotor (eigenvalues)",
            Kind::PeriodicOrbit => "anisotropic: a periodic orbit of half a revolution (Floquet multipliers)",
        }
    ));
    let wn = natural_frequencies(red.as_ref().map_or(&cfg.rotor, |r| &r.rotor), 4)?;
    s.push_str(&format!("natural frequencies at rest, balls as rings: {}\n", wn.iter().map(|w| speed_text(*w)).collect::<Vec<_>>().join(", ")));
    s.push_str(&reduction_text(red));
    if r.stable_ranges.is_empty() {
        s.push_str(&format!("stable: nowhere in (0, {}]\n", speed_text(omega_max)));
    }
    for st in &r.stable_ranges {
        let to = if st.to_is_boundary { speed_text(st.to) } else { format!("{} (end of the axis)", speed_text(st.to)) };
        s.push_str(&format!("stable: {} to {to}\n", speed_text(st.from)));
    }
    let neutral = r.points.iter().filter(|p| p.verdict == Some(Verdict::Neutral)).count();
    if neutral > 0 {
        s.push_str(&format!("neutral (linearisation cannot decide) at {neutral} of {} speeds\n", r.points.len()));
    }
    let missing: Vec<_> = r.points.iter().filter(|p| p.verdict.is_none()).collect();
    if let Some(p) = missing.first() {
        s.push_str(&format!("no balanced state found at {} of {} speeds (first: {})\n", missing.len(), r.points.len(), p.failure.clone().unwrap_or_default()));
    }
    Ok(s)
}

/// The drive of `simulate`: `[drive]`, or a run-up at constant acceleration from rest to
/// `omega_max` in 1000 revolutions.
pub fn drive_of(cfg: &LinearRotorConfig, omega_max: f64) -> (autobal::drive::Drive, f64, bool) {
    match &cfg.drive {
        Some((d, t)) => (d.clone(), *t, false),
        None => {
            // φ = ½ b t² = 2π · 1000 at Ω = b t = omega_max
            let t_end = 2.0 * std::f64::consts::TAU * 1000.0 / omega_max;
            (autobal::drive::Drive::Acceleration { omega0: 0.0, b: omega_max / t_end }, t_end, true)
        }
    }
}

/// The CSV header of `simulate`.
pub fn csv_header(rotor: &LinearRotor) -> String {
    let mut h = vec!["t".to_string(), "omega".into()];
    for i in 0..rotor.balancers.len() {
        h.push(format!("x_{i}"));
        h.push(format!("y_{i}"));
        h.push(format!("r_{i}"));
    }
    h.push("r_max".into());
    for j in 0..rotor.total_balls() {
        h.push(format!("psi_{j}"));
    }
    h.join(",")
}

fn csv_row(s: &RunSample) -> String {
    let mut v = vec![Csv(s.t).to_string(), Csv(s.omega).to_string()];
    for (x, y) in &s.planes {
        v.push(Csv(*x).to_string());
        v.push(Csv(*y).to_string());
        v.push(Csv(x.hypot(*y)).to_string());
    }
    v.push(Csv(s.max_radius).to_string());
    v.extend(s.psi.iter().map(|p| Csv(*p).to_string()));
    v.join(",")
}

/// `simulate`: run and write the samples as CSV to `out` (complete rows, also when stopped).
pub fn run_to_csv(
    cfg: &LinearRotorConfig,
    omega_max: f64,
    dt: Option<f64>,
    out: &Path,
    control: &autobal::control::Control,
) -> Result<(RunSummary, PathBuf, f64, bool, Option<Reduction>)> {
    let (drive, t_end, default) = drive_of(cfg, omega_max);
    let (rotor, red) = model(cfg)?;
    let ig = &cfg.integration;
    let dt = dt.unwrap_or(if cfg.drive.is_some() { ig.dt } else { t_end / 2000.0 });
    let settings = RunSettings {
        t_end,
        dt,
        rtol: ig.rtol,
        atol: ig.atol,
        method: ig.method,
        max_steps: ig.max_steps.unwrap_or(10_000_000),
        max_wall_s: ig.max_wall_s,
        physical_nodes: red.as_ref().map(|r| r.boundary.len()),
    };
    let mut w = outfile::Staged::create("--out", out)?;
    writeln!(w, "{}", csv_header(&cfg.rotor))?;
    let mut err = None;
    let start = std::time::Instant::now();
    let summary = simulate(&rotor, &drive, &settings, control, |s| match writeln!(w, "{}", csv_row(s)) {
        Ok(()) => true,
        Err(e) => {
            err = Some(e);
            false
        }
    })?;
    if let Some(e) = err {
        bail!("--out {}: cannot write: {e}", out.display());
    }
    let wall = start.elapsed().as_secs_f64();
    Ok((summary, w.commit()?, wall, default, red))
}

/// The JSON summary of `simulate`.
pub fn simulate_json(cfg: &LinearRotorConfig, s: &RunSummary, red: &Option<Reduction>, wall: f64) -> Value {
    json!({
        "model": "linear",
        "reduction": reduction_json(red),
        "dofs": cfg.rotor.dofs(),
        "balls": cfg.rotor.total_balls(),
        "t_end_reached": s.t,
        "stopped": s.stopped,
        "peak_radius": s.peak.value, "peak_t": s.peak.t, "peak_omega": s.peak.with,
        "peak_radius_any_node": s.peak_any_node.value, "peak_any_node_t": s.peak_any_node.t, "peak_any_node_omega": s.peak_any_node.with,
        "final_radius": s.final_radius,
        "steps": s.steps,
        "wall_s": wall,
    })
}

/// The table of `simulate`.
pub fn simulate_table(s: &RunSummary, red: &Option<Reduction>, wall: f64) -> String {
    let mut t = String::from("Linear rotor: run in time (fixed axes, prescribed speed)\n");
    t.push_str(&reduction_text(red));
    t.push_str(&format!("reached t = {} s in {} steps ({} s)\n", fmt_num(s.t), s.steps, fmt_num(crate::num::round_sig(wall, 3).unwrap_or(wall))));
    if s.peak.value.is_finite() {
        t.push_str(&format!(
            "peak whirl radius at the first balancer plane: {} m at t = {} s, {}\n",
            fmt_num(crate::num::round_sig(s.peak.value, 6).unwrap_or(0.0)),
            fmt_num(crate::num::round_sig(s.peak.t, 6).unwrap_or(0.0)),
            speed_text(s.peak.with)
        ));
        t.push_str(&format!("final whirl radius there: {} m\n", fmt_num(crate::num::round_sig(s.final_radius, 6).unwrap_or(0.0))));
    }
    t.push_str(&format!(
        "peak radius of any node: {} m at {}\n",
        fmt_num(crate::num::round_sig(s.peak_any_node.value, 6).unwrap_or(0.0)),
        speed_text(s.peak_any_node.with)
    ));
    if let Some(st) = &s.stopped {
        t.push_str(&format!("stopped early: {st}\n"));
    }
    t
}

/// The preset `export-model` writes without a config: paper 004's planar rotor with its race
/// centred as a Jeffcott rotor with two balls ([`LinearRotor::from_planar`]).
pub fn preset() -> Result<LinearRotor> {
    let mut p = autobal::planar::PlanarRotor::paper();
    p.s2 = 0.0;
    Ok(LinearRotor::from_planar(&p)?)
}

/// `export-model`: write `STEM.toml` and `STEM_{M,C,G,K}.mtx` into `dir`; returns the paths.
pub fn export_model(rotor: &LinearRotor, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| anyhow!("--out {}: cannot create the folder: {e}", dir.display()))?;
    let (text, files) = export(rotor, stem);
    let mut o = outfile::Outputs::new();
    let toml_path = dir.join(format!("{stem}.toml"));
    o.output("--out", &toml_path);
    for (name, _) in &files {
        o.output("--out", &dir.join(name));
    }
    o.check()?;
    let mut written = vec![];
    for (name, body) in files {
        let p = dir.join(name);
        outfile::write_atomic("--out", &p, body)?;
        written.push(p);
    }
    outfile::write_atomic("--out", &toml_path, text)?;
    written.insert(0, toml_path);
    Ok(written)
}
