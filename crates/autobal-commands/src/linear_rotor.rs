//! The commands on a linear rotor config (`[linear_rotor]`, issue 19 "your own rotor"): reading
//! the config and its Matrix Market files ([`load`]), `stability` (the balanced state over
//! speed, [`autobal::linear_rotor::stability`]), `simulate` (a run in time with a prescribed
//! speed, [`autobal::linear_rotor::runup`]), `export-model` (a rotor written as config plus
//! matrix files, [`autobal::linear_rotor::config::export`]), and the bases of `map`
//! ([`map_traced`]) and `sweep` ([`sweep_base`]) over the config's parameter paths
//! ([`autobal::linear_rotor::spec`]).

use crate::config;
use crate::num::Csv;
use crate::outfile;
use crate::plot::{Plot, Series, Shade, PALETTE};
use anyhow::{anyhow, bail, Result};
use autobal::analysis::{Kind, Verdict};
use autobal::error::fmt_num;
use autobal::linear_rotor::config::{export, linear_rotor_bytes, LinearRotorConfig};
use autobal::linear_rotor::reduce::{reduce, Reduction};
use autobal::linear_rotor::runup::{simulate, RunSample, RunSettings, RunSummary};
use autobal::linear_rotor::spec::LinearRotorSpec;
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
/// The bytes of a matrix file named in the config (Matrix Market text, `.npy` or `.npz`: the
/// library parses them), relative to the config's folder, at most [`MAX_MATRIX_BYTES`].
fn read_matrix(dir: &Path, name: &str) -> std::result::Result<Vec<u8>, String> {
    let p = dir.join(name);
    // (a FIFO nobody writes hung the blocking open, then read as "empty file": one reader with
    // the config's, config::read_input_file)
    let bytes = config::read_input_file(&p, MAX_MATRIX_BYTES, "a matrix file").map_err(|e| format!("{}: {e}", p.display()))?;
    if bytes.len() as u64 > MAX_MATRIX_BYTES {
        return Err(format!("larger than {} bytes", MAX_MATRIX_BYTES));
    }
    Ok(bytes)
}

/// The linear rotor config of a parsed table; matrix files are read relative to `dir`.
pub fn from_table(root: &Table, dir: &Path) -> Result<LinearRotorConfig> {
    Ok(linear_rotor_bytes(root, &mut |name| read_matrix(dir, name))?)
}

/// Apply one `--set table.key=value` to a linear rotor config (its own tables, not the schema of
/// the papers' configs): `linear_rotor.KEY`, `drive.KEY`, `integration.KEY`; a map's or a
/// sweep's parameter path under `linear_rotor` ([`autobal::linear_rotor::spec::PATHS`]: the
/// number of one entry of its arrays of tables, `linear_rotor.balancer[j].KEY`,
/// `linear_rotor.unbalance[j].KEY`, the shaft builder's `linear_rotor.elements[j].KEY`,
/// `linear_rotor.disks[j].KEY`, `linear_rotor.bearings[j].KEY` (`.kxx[i]`), and the paths that act on every entry,
/// `linear_rotor.drag`, `.ball_mass`, `.me`, `.unbalance_scale`, …) as the map sets it
/// ([`autobal::linear_rotor::spec::set_path`]); a plane's real-ball switch
/// `linear_rotor.balancer[j].contact=true|false` ([`autobal::linear_rotor::spec::set_contact`]).
pub fn apply_set(root: &mut Table, assignment: &str) -> Result<()> {
    let (key, value) = assignment.split_once('=').ok_or_else(|| anyhow!("--set {assignment}: expected key=value, e.g. --set linear_rotor.omega_max=1500"))?;
    let (t, k) = key.trim().split_once('.').ok_or_else(|| anyhow!("--set {key}: expected a dotted key table.field, e.g. --set drive.t_end=2"))?;
    if t == "linear_rotor" && (k.contains('[') || autobal::linear_rotor::spec::PATHS.iter().any(|(p, _)| p.strip_prefix("linear_rotor.") == Some(k))) {
        // a parameter path: one entry of an array of tables (linear_rotor.balancer[j].KEY), or a
        // path on every entry (linear_rotor.drag: each [[linear_rotor.balancer]]'s drag); the
        // one boolean, a plane's `contact`, apart
        if k.starts_with("balancer[") && k.ends_with("].contact") {
            let on = match value.trim() {
                "true" => true,
                "false" => false,
                v => bail!("--set {}: expected true or false, got `{v}`", key.trim()),
            };
            return Ok(autobal::linear_rotor::spec::set_contact(root, key.trim(), on)?);
        }
        let v: f64 = value.trim().parse().map_err(|_| anyhow!("--set {key}: `{}` is not a number", value.trim()))?;
        return Ok(autobal::linear_rotor::spec::set_path(root, key.trim(), v)?);
    }
    if !["linear_rotor", "drive", "integration"].contains(&t) || k.is_empty() || k.contains('.') {
        bail!("--set {key}: a linear rotor config sets linear_rotor.KEY, drive.KEY, integration.KEY, a parameter path of its maps (linear_rotor.drag, .ball_mass, .radius, .balls, .me, …: every entry), or one entry's number as linear_rotor.balancer[j].KEY, linear_rotor.unbalance[j].KEY, linear_rotor.elements[j].KEY, linear_rotor.disks[j].KEY, linear_rotor.bearings[j].KEY (j from 0)");
    }
    let table = root.entry(t.to_string()).or_insert_with(|| toml::Value::Table(Table::new()));
    let table = table.as_table_mut().ok_or_else(|| anyhow!("--set {key}: `{t}` is not a table"))?;
    table.insert(k.to_string(), autobal::config::parse_value(value.trim()));
    Ok(())
}

/// Read the config at `path` (or the embedded default) and apply `--set`: a linear rotor
/// config's own way ([`apply_set`]), any other config's through [`config::apply_set`].
pub fn read_set(path: Option<&Path>, sets: &[String]) -> Result<(Table, String)> {
    config::check_repeated_sets(sets)?;
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
/// first, and at least [`autobal::config::OPERATING_SPEED_MARGIN`] × the top of
/// `linear_rotor.operating_speed`.
pub fn default_omega_max(cfg: &LinearRotorConfig) -> Result<f64> {
    if let Some(w) = cfg.omega_max {
        return Ok(w);
    }
    let r = cfg.rotor.at_speed(0.0);
    let w = r.natural_frequencies(&[], true)?;
    let pos: Vec<f64> = w.into_iter().filter(|v| *v > 0.0).collect();
    let first = *pos.first().ok_or_else(|| anyhow!("linear_rotor: the rotor has no positive natural frequency; give linear_rotor.omega_max"))?;
    let automatic = (1.5 * pos[pos.len().min(4) - 1]).max(3.0 * first);
    // past the operating speed with margin, as a spatial config's automatic axes
    Ok(cfg.operating_speed.map_or(automatic, |[_, hi]| automatic.max(autobal::config::OPERATING_SPEED_MARGIN * hi)))
}

/// The top of the speed axis of `stability` and `campbell` on a linear rotor: `--omega-max`
/// with its unit (rad/s, rpm, Hz; a bare number has no meaning for an SI rotor), checked as
/// every speed flag is, else [`default_omega_max`].
pub fn omega_max(flag: Option<&str>, cfg: &LinearRotorConfig) -> Result<f64> {
    let Some(t) = flag else { return default_omega_max(cfg) };
    // (its error names no dimensionless Ω: a linear rotor has none)
    let s = crate::general_campbell::parse_speed_rad_s("--omega-max", t, "")?;
    let w = s.value * s.unit.rad_s().ok_or_else(|| anyhow!("--omega-max: give a speed with its unit (rad/s, rpm, Hz) for a linear rotor"))?;
    crate::command::check_speed_rad_s("--omega-max", t, w)?;
    Ok(w)
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
    // a divergent mode has no frequency: named in the heading's words, never "0 ± 0"
    let diverging: Vec<f64> = r.frequencies.iter().filter(|f| f.divergent).map(|f| f.omega_squared).collect();
    if !diverging.is_empty() {
        s.push_str(&format!("reduced model (without the balls): {}", divergence_words(&diverging)));
    }
    let est: Vec<String> = r
        .frequencies
        .iter()
        .filter(|f| !f.divergent)
        .take(4)
        .map(|f| {
            format!(
                "{} ± {}",
                fmt_num(crate::num::round_sig(f.omega, 6).unwrap_or(f.omega)),
                f.estimate.map_or("?".into(), |e| fmt_num(crate::num::round_sig(e, 2).unwrap_or(e)))
            )
        })
        .collect();
    let others = if diverging.is_empty() { "" } else { " of the other modes" };
    s.push_str(&format!(
        "reduced natural frequencies at rest without the balls{others} (rad/s, ± the estimated error): {}\n",
        if est.is_empty() { EVERY_MODE_DIVERGES.to_string() } else { est.join(", ") }
    ));
    s
}

/// `stability`: the balanced state over `(0, omega_max]` with `samples` speeds, on the model of
/// [`model`].
pub fn stability(cfg: &LinearRotorConfig, omega_max: f64, samples: usize) -> Result<(RotorStability, Option<Reduction>)> {
    let speeds = speed_grid(omega_max, samples)?;
    let (rotor, red) = model(cfg)?;
    Ok((autobal::linear_rotor::stability::stability_over_speed(&rotor, &speeds)?, red))
}

/// The rotor at rest with its balls as rings, from one eigenproblem: the undamped natural
/// frequencies (rad/s), the lowest `count` of the modes that do not diverge at rest, and the
/// divergent modes' `ω² < 0` ((rad/s)², the most negative first;
/// [`autobal::linear_rotor::static_divergence`]), empty where `K` is positive semi-definite: a
/// negative `ω²` has no frequency and never reads 0 rad/s here; a rigid-body mode's does.
pub fn modes_at_rest(rotor: &LinearRotor, count: usize) -> Result<(Vec<f64>, Vec<f64>)> {
    let w2 = rotor.at_speed(0.0).natural_frequencies_squared(&[], true)?;
    let diverging = autobal::linear_rotor::static_divergence(&w2);
    let w = w2[diverging.len()..].iter().take(count).map(|l| l.max(0.0).sqrt()).collect();
    Ok((w, diverging))
}

/// The JSON of the divergent modes of [`modes_at_rest`]: one `{omega_squared, growth_rate}` per divergent mode (`ω²` in
/// (rad/s)², the rate `sqrt(−ω²)` in 1/s at which it grows at rest), `[]` for none.
pub fn divergence_json(d: &[f64]) -> Value {
    Value::Array(d.iter().map(|l| json!({"omega_squared": l, "growth_rate": (-l).sqrt()})).collect())
}

/// What the natural-frequency lines say where every mode diverges at rest (no mode has a
/// frequency); the JSON's `every_mode_diverges` is then `true`.
pub const EVERY_MODE_DIVERGES: &str = "none (every mode diverges at rest)";

/// The natural frequencies `w` (rad/s) as a line's list: each in rad/s with its rpm, or
/// [`EVERY_MODE_DIVERGES`] where there are none because every mode diverges (`diverging`
/// non-empty), or "none" where there are none at all.
pub fn frequencies_text(w: &[f64], diverging: &[f64]) -> String {
    match (w.is_empty(), diverging.is_empty()) {
        (false, _) => w.iter().map(|w| speed_text(*w)).collect::<Vec<_>>().join(", "),
        (true, false) => EVERY_MODE_DIVERGES.to_string(),
        (true, true) => "none".to_string(),
    }
}

/// The line that says the structure is statically unstable ([`modes_at_rest`]'s divergent modes), empty where it is not.
pub fn divergence_text(d: &[f64]) -> String {
    if d.is_empty() {
        return String::new();
    }
    divergence_words(d)
}

/// "statically unstable at rest: N mode(s) with ω² < 0, ω² = …" for the divergent `ω²` `d`
/// (non-empty), one line.
fn divergence_words(d: &[f64]) -> String {
    let six = |v: f64| fmt_num(crate::num::round_sig(v, 6).unwrap_or(v));
    format!(
        "statically unstable at rest: {} mode(s) with ω² < 0, ω² = {} (rad/s)², growing as exp(sqrt(-ω²) t) at {} 1/s: the stiffness K is not positive semi-definite (these modes have no natural frequency)\n",
        d.len(),
        d.iter().map(|l| six(*l)).collect::<Vec<_>>().join(", "),
        d.iter().map(|l| six((-l).sqrt())).collect::<Vec<_>>().join(", ")
    )
}

/// The JSON of `stability`; the natural frequencies (with the balls as rings) are those of the
/// model analysed (the reduced one where the config reduces).
pub fn stability_json(cfg: &LinearRotorConfig, r: &RotorStability, red: &Option<Reduction>, omega_max: f64) -> Result<Value> {
    let (wn, diverging) = modes_at_rest(red.as_ref().map_or(&cfg.rotor, |r| &r.rotor), 6)?;
    let ranges: Vec<Value> = r
        .stable_ranges
        .iter()
        .map(|s| {
            let mut v = crate::general::stable_range_json(s);
            v["from_rpm"] = json!(rpm(s.from));
            v["to_rpm"] = json!(rpm(s.to));
            v
        })
        .collect();
    Ok(json!({
        "route": "general",
        "model": r.model,
        "source": cfg.source,
        "dofs": cfg.rotor.dofs(),
        "balls": cfg.rotor.total_balls(),
        "natural_frequencies": wn,
        "static_divergence": divergence_json(&diverging),
        "every_mode_diverges": wn.is_empty() && !diverging.is_empty(),
        "reduction": reduction_json(red),
        "stationary_state": r.kind,
        "speed_unit": "rad/s",
        "omega_max": omega_max,
        "stable_ranges": ranges,
        "family_dimension": r.family_dimension,
        "member_psi": r.member_psi,
        "family": r.family,
        "has_unbalance": r.has_unbalance,
        "residual_scale": r.residual_scale,
        "neutral_tolerance": crate::general::neutral_tolerance(r.kind),
        "points": r.points,
    }))
}

/// The table of `stability`.
pub fn stability_table(cfg: &LinearRotorConfig, r: &RotorStability, red: &Option<Reduction>, omega_max: f64) -> Result<String> {
    let mut s = String::from("Linear rotor: the stationary state's exact linear stability over speed (balanced, else partially balanced)\n");
    s.push_str(&format!(
        "model: {} DOFs ({}), {} balancer plane(s) with {} balls, {} unbalance(s); {}\n",
        cfg.rotor.dofs(),
        if cfg.source == "shaft" { "built-in shaft builder" } else { "matrix files" },
        cfg.rotor.balancers.len(),
        cfg.rotor.total_balls(),
        cfg.rotor.unbalances.len(),
        match r.kind {
            Kind::Equilibrium => "isotropic: an equilibrium in axes turning with the rotor (eigenvalues)",
            Kind::PeriodicOrbit if cfg.rotor.gravity.is_some() =>
                "gravity: a periodic orbit of one revolution, the rotor sagging and the balls swinging (Floquet multipliers)",
            Kind::PeriodicOrbit => "anisotropic: a periodic orbit of half a revolution (Floquet multipliers)",
        }
    ));
    let (wn, diverging) = modes_at_rest(red.as_ref().map_or(&cfg.rotor, |r| &r.rotor), 4)?;
    s.push_str(&divergence_text(&diverging));
    let others = if diverging.is_empty() { "" } else { " (of the other modes)" };
    s.push_str(&format!("natural frequencies at rest, balls as rings{others}: {}\n", frequencies_text(&wn, &diverging)));
    s.push_str(&reduction_text(red));
    s.push_str(&partial_text(cfg, r));
    s.push_str(&linear_residual_text(r));
    s.push_str(&crate::general::not_balanced_text(r, speed_text));
    if let Some(line) = crate::general::stopped_before_first_speed(r) {
        s.push_str(line);
    } else if r.stable_ranges.is_empty() {
        s.push_str(&format!("stable: nowhere in (0, {}]\n", speed_text(crate::general::analysed_span(r, omega_max))));
    }
    for st in &r.stable_ranges {
        // an end not located: the axis' start or end, or next to a speed without a verdict
        let from = crate::general::end_text(r, st, false, speed_text);
        let to = crate::general::end_text(r, st, true, speed_text);
        // the states the range covers: "partially balanced, stable" never reads "stable"
        let kinds = crate::general::range_states(r, st);
        let label = if kinds.iter().any(|k| *k != "balanced") { format!("{}, stable", kinds.join(" then ")) } else { "stable".to_string() };
        s.push_str(&format!("{label}: {from} to {to}\n"));
    }
    if let Some(f) = &r.family {
        let list = |v: &[autobal::analysis::StableRange]| {
            if v.is_empty() {
                "nowhere on the axis".to_string()
            } else {
                v.iter().map(|st| format!("{} to {}", speed_text(st.from), speed_text(st.to))).collect::<Vec<_>>().join(", ")
            }
        };
        s.push_str(&format!(
            "the balanced states form a family of dimension {}{} (the ranges above are one member's): all members sampled stable: {}; at least one member sampled stable (which is not \"stable\"): {}\n",
            f.dimension,
            crate::general::members_words(f),
            list(&f.all_members_stable),
            list(&f.some_members_stable)
        ));
    }
    let neutral = r.points.iter().filter(|p| p.verdict == Some(Verdict::Neutral)).count();
    if neutral > 0 {
        s.push_str(&format!(
            "neutral (the growth rate within the neutral tolerance of zero: undecided at that tolerance, not a verdict) at {neutral} of {} speeds\n",
            r.points.len()
        ));
    }
    s.push_str(&crate::general::missing_lines(r, speed_text));
    // the floor is the fastest natural frequency over 1000: a full finite-element model's
    // fastest mode (~1e5 rad/s on a Timoshenko shaft) puts it above the critical speeds (audit
    // 21's F1: a ROSS rotor's onset at 58 rad/s under a floor of 115.7), and the reduction
    // removes those modes (the same rotor with `modes = 4`: the whole axis, 5 s)
    if cfg.modes.is_none() && r.points.iter().any(|p| !p.analysed) {
        s.push_str("the floor is set by the full model's fastest mode: a modal reduction (linear_rotor.modes = 4, --set linear_rotor.modes=4) keeps the slow modes and lowers it\n");
    }
    Ok(s)
}

/// The line of `stability`'s table where the linear rotor's balanced states (its race-whirl
/// rule, [`autobal::linear_rotor::partial::state_kind`]: no race centre whirling at more than
/// 0.05 of its whirl without the balls' resultant, `simulate`'s tolerance) leave a residual static unbalance above
/// 1e-6 of the unbalance: the balls centre their races, which on a flexible shaft with the
/// unbalance at other nodes (or on an orbit, the balls swinging) does not cancel the static
/// unbalance; the line says so rather than "balanced to" it. Empty where there is none.
fn linear_residual_text(r: &autobal::rotor_stability::RotorStability) -> String {
    let with: Vec<_> =
        r.points.iter().filter(|p| p.state == Some(autobal::rotor_stability::StateKind::Balanced) && p.residual.is_some_and(|v| v > 1e-6)).collect();
    let (Some(a), Some(b)) = (with.first(), with.last()) else { return String::new() };
    format!(
        "balanced by the race-whirl rule (no race centre whirls at more than 0.05 of its whirl without the balls' resultant, simulate's tolerance), not by the residual: a residual static unbalance of {} {} (above the tolerance 1e-6) at {} of {} speeds, {} to {} (the balls centre their races; with the unbalance at other nodes, or swinging on an orbit, that does not cancel the static unbalance)\n",
        crate::general::residual_range(&with),
        r.residual_scale.words(),
        with.len(),
        r.points.len(),
        speed_text(a.omega),
        speed_text(b.omega)
    )
}

/// The line of `stability`'s table where the balls cannot balance: no balanced state where the
/// capacity `n m_b R` falls short, the partially balanced state (balls bunched) analysed
/// instead, with its residual static unbalance ([`autobal::linear_rotor::partial`]); empty
/// where every state found is balanced.
pub fn partial_text(cfg: &LinearRotorConfig, r: &RotorStability) -> String {
    use autobal::linear_rotor::partial::{residual_static, static_unbalance};
    use autobal::rotor_stability::StateKind;
    let partial: Vec<_> = r.points.iter().filter(|p| p.state == Some(StateKind::PartiallyBalanced)).collect();
    let (Some(a), Some(b)) = (partial.first(), partial.last()) else { return String::new() };
    let rotor = &cfg.rotor;
    let s0 = static_unbalance(rotor);
    let cap: f64 = rotor.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius).sum();
    let res = |p: &autobal::rotor_stability::SpeedPoint| {
        let v = residual_static(rotor, &p.member_psi);
        v[0].hypot(v[1])
    };
    let (lo, hi) = partial.iter().map(|p| res(p)).fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
    // what is compared: with every unbalance in the one plane its capacity against the static
    // unbalance; with an unbalance away from the plane the force the plane must cancel (the
    // static unbalance is not what its balls balance)
    let in_plane = matches!(rotor.balancers.as_slice(), [b] if rotor.unbalances.iter().all(|u| u.node == b.node && u.offset == b.offset));
    let why = if let [b] = rotor.balancers.as_slice().iter().filter(|b| b.balls < 2).collect::<Vec<_>>().as_slice() {
        format!("the plane at node {} has {} ball(s), balancing needs 2", b.node, b.balls)
    } else if rotor.balancers.len() == 1 && in_plane {
        format!(
            "the balls' capacity n m R = {} kg m < the static unbalance {} kg m",
            fmt_num(crate::num::round_sig(cap, 6).unwrap_or(cap)),
            fmt_num(crate::num::round_sig(s0[0].hypot(s0[1]), 6).unwrap_or(0.0))
        )
    } else if rotor.balancers.len() == 1 {
        format!(
            "the balls' capacity n m R = {} kg m short of the force their plane must cancel, the unbalance lying away from it; the static unbalance {} kg m is not what the plane balances",
            fmt_num(crate::num::round_sig(cap, 6).unwrap_or(cap)),
            fmt_num(crate::num::round_sig(s0[0].hypot(s0[1]), 6).unwrap_or(0.0))
        )
    } else {
        "a plane's capacity n m R is below its share of the unbalance".to_string()
    };
    format!(
        "no balanced state at {} of {} speeds, {} to {} ({why}): the verdicts there are the partially balanced state's (balls bunched, residual static unbalance {} to {} kg m)\n",
        partial.len(),
        r.points.len(),
        speed_text(a.omega),
        speed_text(b.omega),
        fmt_num(crate::num::round_sig(lo, 4).unwrap_or(lo)),
        fmt_num(crate::num::round_sig(hi, 4).unwrap_or(hi))
    )
}

/// The config's parameter paths with its matrix files read once, relative to `dir`
/// ([`autobal::linear_rotor::spec`]): the base of `map` and `sweep`.
pub fn spec(root: &Table, dir: &Path) -> autobal::Result<LinearRotorSpec> {
    LinearRotorSpec::new(root.clone(), &mut |name| read_matrix(dir, name))
}

/// `map` on a linear rotor config: the library's [`autobal::rotor_map::linear_map_traced`] over
/// its parameter paths or the speed (rad/s), the matrix files read relative to `dir` (the
/// config's folder, [`crate::command::ConfigSource::dir`]); `on_row` as [`autobal::rotor_map::general_map_traced`]'s (`crate::map::run_general`
/// writes the rows, the figures and the bisected boundary as for any config).
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn map_traced(
    root: &Table,
    dir: &Path,
    x: &autobal::spatial::map::Axis,
    y: &autobal::spatial::map::Axis,
    speed: Option<autobal::units::Speed>,
    trace: bool,
    control: &autobal::control::Control,
    on_row: &mut dyn FnMut(usize, &[autobal::rotor_map::GeneralCell], &[autobal::rotor_map::BoundaryPoint]) -> bool,
) -> autobal::Result<autobal::rotor_map::GeneralMapOutcome> {
    let base = spec(root, dir)?;
    autobal::rotor_map::linear_map_traced(&base, x, y, speed, trace, control, on_row)
}

/// The base of `sweep` when the config at `path` (after `--set`) is a linear rotor config: its
/// tables, its [`LinearRotorSpec`] and the sweep JSON's `problem` (`model: "linear"`, the config's
/// tables, the model's DOFs and balls, and the run of a point without values: drive, settings);
/// `None` for any other config.
pub fn sweep_base(path: Option<&Path>, sets: &[String]) -> Result<Option<(Table, LinearRotorSpec, Value)>> {
    let Some(p) = path else { return Ok(None) };
    let (root, _) = read_set(Some(p), sets)?;
    if !is_linear(&root) {
        return Ok(None);
    }
    sweep_base_of(root, p.parent().unwrap_or(Path::new("."))).map(Some)
}

/// [`sweep_base`] of a linear rotor config's tables `root` (after any `--set`), its matrix
/// files read relative to `dir`.
pub fn sweep_base_of(root: Table, dir: &Path) -> Result<(Table, LinearRotorSpec, Value)> {
    let base = spec(&root, dir)?;
    let cfg = base.config_at(&[])?;
    let run = autobal::linear_rotor::spec::run_of(&cfg)?;
    let problem = json!({
        "model": "linear",
        "config": root,
        "source": cfg.source,
        "dofs": run.rotor.dofs(),
        "dofs_full": cfg.rotor.dofs(),
        "balls": cfg.rotor.total_balls(),
        "drive": run.drive,
        "drive_is_default": run.default_drive,
        "t_end": run.settings.t_end,
        "dt": run.settings.dt,
        "rtol": run.settings.rtol,
        "atol": run.settings.atol,
    });
    Ok((root, base, problem))
}

/// The CSV of a linear rotor's basins (the complete runs):
/// `psi_1,psi_2,balanced,residual_unbalance,final_amplitude` as the spatial rotor's, then
/// `completed` and every ball's final angle `psi_end_j` (rad, relative to the rotor).
pub fn basins_csv(ends: &[Option<autobal::linear_rotor::basins::BasinEnd>]) -> String {
    let balls = ends.iter().flatten().next().map_or(0, |e| e.psi.len());
    let mut csv = String::from("psi_1,psi_2,balanced,residual_unbalance,final_amplitude,completed");
    for j in 0..balls {
        csv.push_str(&format!(",psi_end_{}", j + 1));
    }
    csv.push('\n');
    for e in ends.iter().flatten() {
        let mut row = vec![Csv(e.psi0[0]).to_string(), Csv(e.psi0[1]).to_string(), (e.balanced as u8).to_string()];
        row.extend([e.residual_unbalance, e.final_amplitude].map(|v| Csv(v).to_string()));
        row.push((e.summary.stopped.is_none() as u8).to_string());
        row.extend(e.psi.iter().map(|v| Csv(*v).to_string()));
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    csv
}

/// The JSON of a linear rotor's basins: the spatial rotor's keys (`runs`, `completed`,
/// `balanced`, `fraction_balanced`, `wall_time_s`) with `model: "linear"` and the rule in force
/// (`balanced_rule`, `balance_tolerance`): a start counts balanced where `simulate` from it
/// says balanced ([`autobal::linear_rotor::basins`]).
pub fn basins_json(ends: &[Option<autobal::linear_rotor::basins::BasinEnd>], wall: f64) -> Value {
    let done = ends.iter().flatten().count();
    let balanced = ends.iter().flatten().filter(|s| s.balanced).count();
    json!({
        "model": "linear",
        "runs": ends.len(),
        "completed": done,
        "balanced": balanced,
        "fraction_balanced": balanced as f64 / done.max(1) as f64,
        "balanced_rule": "the run's outcome, as simulate's: settled, and no race centre whirling at more than balance_tolerance of its whirl with the balls spread evenly (stability's race_whirl basis)",
        "balance_tolerance": autobal::spatial::dynamics::simulate::BALANCE_TOLERANCE,
        "wall_time_s": wall,
    })
}

/// The figure of a linear rotor's basins (`basins`, id `basins`): each run of the `n × n` grid a
/// cell at the first two balls' initial angles (degrees), green where the run ends balanced,
/// orange where it does not, grey where it was not run (stopped) — the report's basins figure
/// (`report::basins`) for a linear rotor. `angles` and `ends` as the `basins` command's output (`crate::basins::Output`).
pub fn basins_plot(angles: &[[f64; 2]], ends: &[Option<autobal::linear_rotor::basins::BasinEnd>]) -> Plot {
    use crate::plot::{ColorScale, Heatmap};
    let n = (angles.len() as f64).sqrt().round() as usize;
    let n = n.max(1);
    let tau = std::f64::consts::TAU;
    let xs: Vec<f64> = (0..n).map(|i| (tau * i as f64 / n as f64).to_degrees()).collect();
    let mut z = vec![vec![f64::NAN; n]; n];
    for (a, e) in angles.iter().zip(ends) {
        if let Some(e) = e {
            let cell = |psi: f64| ((psi / tau * n as f64).round() as usize).min(n - 1);
            z[cell(a[1])][cell(a[0])] = if e.balanced { -1.0 } else { 1.0 };
        }
    }
    let step = 360.0 / n as f64;
    Plot {
        title: "Linear rotor: where the balls end, by their initial angles".into(),
        x_label: "initial angle of ball 1 (°, relative to the rotor)".into(),
        y_label: "initial angle of ball 2 (°, relative to the rotor)".into(),
        x_range: Some((-step / 2.0, 360.0 - step / 2.0)),
        y_range: Some((-step / 2.0, 360.0 - step / 2.0)),
        heatmap: Some(Heatmap { x: xs.clone(), y: xs, z, scale: ColorScale::Verdict, label: "end (stable = balanced)".into() }),
        ..Default::default()
    }
}

/// The figures of a linear rotor's sweep (`sweep`): the first balancer plane's peak whirl radius
/// (id `sweep_peak`) and its final radius (id `sweep_final`, mm) against the first axis' value,
/// one curve per combination of the other axes' values (in the grid's order), a point per run
/// (`runs`: each run's values, in the order of `paths`, and its summary; a run without a
/// balancer plane's radius is a gap): [`sweep_plots_of`] on each run's `peak_amplitude` and
/// `final_amplitude` ([`autobal::sweep::linear_summary_values`]).
pub fn sweep_plots(paths: &[String], runs: &[(Vec<f64>, RunSummary)]) -> Vec<(String, Plot)> {
    let runs: Vec<(Vec<f64>, [f64; 2])> = runs
        .iter()
        .map(|(v, s)| {
            let x = autobal::sweep::linear_summary_values(s);
            (v.clone(), [x[0], x[5]])
        })
        .collect();
    sweep_plots_of("Linear rotor", "first balancer plane", paths, &runs, ("mm", 1e3))
}

/// The figures of a sweep of any rotor: the peak whirl radius (id `sweep_peak`) and the final
/// radius (id `sweep_final`) of the `of` (e.g. "first balancer plane"), in `unit.0` (`unit.1`
/// of them per config unit), against the first axis' value, one curve per combination of the
/// other axes' values (in the grid's order), a point per run (`runs`: each run's values, in
/// the order of `paths`, and its `[peak, final]` radius; a NaN is a gap); `model` starts the
/// titles ("Linear rotor": "Linear rotor sweep: …").
pub fn sweep_plots_of(model: &str, of: &str, paths: &[String], runs: &[(Vec<f64>, [f64; 2])], unit: (&str, f64)) -> Vec<(String, Plot)> {
    let Some(x_path) = paths.first() else { return vec![] };
    let (lu, ls) = unit;
    // the curves: runs grouped by the values of the other axes, in the order met
    let mut groups: Vec<(Vec<f64>, Vec<usize>)> = vec![];
    for (i, (v, _)) in runs.iter().enumerate() {
        let key = v.get(1..).unwrap_or(&[]).to_vec();
        match groups.iter_mut().find(|g| g.0 == key) {
            Some(g) => g.1.push(i),
            None => groups.push((key, vec![i])),
        }
    }
    let label = |key: &[f64]| -> String {
        if key.is_empty() {
            of.to_string()
        } else {
            paths[1..].iter().zip(key).map(|(p, v)| format!("{p} = {}", fmt_num(*v))).collect::<Vec<_>>().join(", ")
        }
    };
    let figure = |what: &str, col: usize| -> Plot {
        let series = groups
            .iter()
            .enumerate()
            .map(|(k, (key, idx))| {
                let pts = idx.iter().map(|&i| (runs[i].0[0], ls * runs[i].1[col])).collect();
                let mut s = Series::new(label(key), pts, PALETTE[k % PALETTE.len()]);
                s.markers = idx.len() < 2;
                s
            })
            .collect();
        Plot { title: format!("{model} sweep: {what}"), x_label: x_path.clone(), y_label: format!("{what} ({lu})"), series, ..Default::default() }
    };
    vec![
        ("sweep_peak".into(), figure(&format!("peak whirl radius of the {of}"), 0)),
        ("sweep_final".into(), figure(&format!("final whirl radius of the {of}"), 1)),
    ]
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

/// The columns of `simulate`'s samples (CSV header, Parquet columns, Python's arrays), in
/// order: `t, omega`, per balancer plane `i` its race centre `x_i, y_i` (m, fixed axes) and
/// radius `r_i = sqrt(x_i² + y_i²)`, `r_max` (the largest translation radius of any physical
/// node), then every ball's angle `psi_j` relative to the rotor (rad).
pub fn columns(rotor: &LinearRotor) -> Vec<String> {
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
    h
}

/// The CSV header of `simulate` ([`columns`] joined by commas).
pub fn csv_header(rotor: &LinearRotor) -> String {
    columns(rotor).join(",")
}

/// One sample as the values of [`columns`].
pub fn row(s: &RunSample) -> Vec<f64> {
    let mut v = Vec::with_capacity(3 + 3 * s.planes.len() + s.psi.len());
    v.extend([s.t, s.omega]);
    for (x, y) in &s.planes {
        v.extend([*x, *y, x.hypot(*y)]);
    }
    v.push(s.max_radius);
    v.extend(&s.psi);
    v
}

/// A run of `simulate` set up from a config: the model run (the config's rotor, or its
/// reduction), the drive, the solver settings.
pub struct RunSetup {
    /// The model that is integrated ([`model`]).
    pub rotor: LinearRotor,
    /// The reduction, where the config reduces.
    pub reduction: Option<Reduction>,
    /// The prescribed speed.
    pub drive: autobal::drive::Drive,
    /// End time, output interval, tolerances, budgets.
    pub settings: RunSettings,
    /// True when the config has no `[drive]` ([`drive_of`]'s default run-up).
    pub default_drive: bool,
    /// The top of the speed axis (rad/s): the default run-up's end speed.
    pub omega_max: f64,
    /// The sample columns ([`columns`]).
    pub columns: Vec<String>,
}

/// Set up `simulate` on `cfg`: the drive of [`drive_of`] up to `omega_max`, the output interval
/// `dt` (default `integration.dt`, or `t_end / 2000` for the default run-up).
pub fn setup(cfg: &LinearRotorConfig, omega_max: f64, dt: Option<f64>) -> Result<RunSetup> {
    let (drive, t_end, default_drive) = drive_of(cfg, omega_max);
    if let Some(d) = dt {
        if !(d.is_finite() && d > 0.0) {
            bail!("--dt: must be a positive number of seconds, got {d}");
        }
    }
    let (rotor, reduction) = model(cfg)?;
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
        physical_nodes: reduction.as_ref().map(|r| r.boundary.len()),
    };
    Ok(RunSetup { columns: columns(&cfg.rotor), rotor, reduction, drive, settings, default_drive, omega_max })
}

/// What a run gives besides its samples: the summary, the samples kept for the figures (per
/// bucket of consecutive samples the ones with the smallest and the largest radius at the
/// first balancer plane, so that peaks survive the decimation; every sample up to 6000), and
/// the wall time (s).
pub struct RunOutput {
    pub summary: RunSummary,
    pub kept: Vec<Vec<f64>>,
    pub wall: f64,
}

/// Run `setup`, handing every sample (the values of [`columns`]) to `sink`; an error of the
/// sink stops the run and is returned.
pub fn run(setup: &RunSetup, control: &autobal::control::Control, mut sink: impl FnMut(&[f64]) -> Result<()>) -> Result<RunOutput> {
    let expected = (setup.settings.t_end / setup.settings.dt) as usize + 1;
    let bucket = expected.div_ceil(6000).max(1);
    // the first plane's radius, else the largest of any node
    let key = if setup.rotor.balancers.is_empty() { 2 } else { 4 };
    let mut current: Vec<Vec<f64>> = vec![];
    let mut kept: Vec<Vec<f64>> = vec![];
    let flush = |current: &mut Vec<Vec<f64>>, kept: &mut Vec<Vec<f64>>| {
        if current.len() > 2 {
            let by = |a: &usize, b: &usize| current[*a][key].total_cmp(&current[*b][key]);
            let imin = (0..current.len()).min_by(by).unwrap_or(0);
            let imax = (0..current.len()).max_by(by).unwrap_or(0);
            let (a, b) = (imin.min(imax), imin.max(imax));
            let mut keep = vec![std::mem::take(&mut current[a])];
            if b != a {
                keep.push(std::mem::take(&mut current[b]));
            }
            current.clear();
            kept.append(&mut keep);
        } else {
            kept.append(current);
        }
    };
    let mut err = None;
    let start = std::time::Instant::now();
    let summary = simulate(&setup.rotor, &setup.drive, &setup.settings, control, |s| {
        let r = row(s);
        if let Err(e) = sink(&r) {
            err = Some(e);
            return false;
        }
        current.push(r);
        if current.len() >= bucket {
            flush(&mut current, &mut kept);
        }
        true
    })?;
    flush(&mut current, &mut kept);
    if let Some(e) = err {
        return Err(e);
    }
    Ok(RunOutput { summary, kept, wall: start.elapsed().as_secs_f64() })
}

/// `simulate`: run and write the samples as CSV to `csv` (the header first; complete rows,
/// also when stopped) and to `parquet` if given.
pub fn run_to_files(
    setup: &RunSetup,
    csv: &mut dyn Write,
    parquet: Option<&mut crate::parquet::Table>,
    control: &autobal::control::Control,
) -> Result<RunOutput> {
    let mut sink = crate::sim::RowSink::new(Some(csv), parquet, None);
    sink.header(&setup.columns)?;
    let out = run(setup, control, |r| sink.push(r).map_err(|e| anyhow!("--out: cannot write: {e}")))?;
    sink.finish().map_err(|e| anyhow!("--out: cannot write: {e}"))?;
    Ok(out)
}

/// The figures of `simulate` as `(suffix, plot)` ([`crate::sim::PLOTS`]'s suffixes): the whirl
/// radius of each balancer plane's race centre and the largest radius of any node against
/// speed and against time (mm), the balls' angles relative to the rotor (degrees), the speed.
pub fn plots(setup: &RunSetup, kept: &[Vec<f64>]) -> Vec<(String, Plot)> {
    let planes = setup.rotor.balancers.len();
    let rmax = 2 + 3 * planes;
    let title = "Linear rotor";
    let radii = |x: usize| -> Vec<Series> {
        let mut s: Vec<Series> = (0..planes)
            .map(|i| {
                Series::new(
                    format!("balancer plane {i} (node {})", setup.rotor_node(i)),
                    kept.iter().map(|r| (r[x], 1e3 * r[4 + 3 * i])).collect(),
                    PALETTE[i % 7],
                )
            })
            .collect();
        s.push(Series::new("largest of any node", kept.iter().map(|r| (r[x], 1e3 * r[rmax])).collect(), PALETTE[6]).dashed());
        s
    };
    let mut out = vec![
        (
            "amplitude_omega".to_string(),
            Plot {
                title: format!("{title}: whirl radius against speed"),
                x_label: "speed ω (rad/s)".into(),
                y_label: "radius (mm)".into(),
                series: radii(1),
                ..Default::default()
            },
        ),
        (
            "amplitude_t".to_string(),
            Plot { title: format!("{title}: whirl radii"), x_label: "t (s)".into(), y_label: "radius (mm)".into(), series: radii(0), ..Default::default() },
        ),
    ];
    let balls = setup.rotor.total_balls();
    let psi: Vec<Series> = (0..balls)
        .map(|j| Series::new(format!("ψ{j}"), crate::sim::wrapped_degrees(kept.iter().map(|r| (r[0], r[rmax + 1 + j]))), PALETTE[(j + 1) % 7]))
        .collect();
    out.push((
        "psi_t".into(),
        Plot {
            title: format!("{title}: ball angles"),
            x_label: "t (s)".into(),
            y_label: "ψ (degrees, relative to the rotor)".into(),
            series: psi,
            ..Default::default()
        },
    ));
    out.push((
        "omega_t".into(),
        Plot {
            title: format!("{title}: speed"),
            x_label: "t (s)".into(),
            y_label: "speed ω (rad/s)".into(),
            series: vec![Series::new("speed", kept.iter().map(|r| (r[0], r[1])).collect(), PALETTE[0])],
            ..Default::default()
        },
    ));
    out
}

impl RunSetup {
    /// The node of balancer plane `i` in the config's numbering.
    fn rotor_node(&self, i: usize) -> usize {
        let k = self.rotor.balancers[i].node;
        self.reduction.as_ref().and_then(|r| r.boundary.get(k).copied()).unwrap_or(k)
    }
}

/// The paths of `simulate`'s figures beside `stem` (`STEM_amplitude_omega.svg`, …).
pub fn plot_paths(stem: &Path) -> Vec<PathBuf> {
    crate::sim::plot_paths(stem)
}

/// Write the figures of [`plots`] as SVG beside `stem`, each through [`outfile::write_atomic`].
pub fn write_plots(setup: &RunSetup, kept: &[Vec<f64>], stem: &Path) -> Result<Vec<PathBuf>> {
    let mut files = vec![];
    for (suffix, plot) in plots(setup, kept) {
        let path = crate::sim::plot_path(stem, &suffix);
        outfile::write_atomic("--out", &path, plot.to_svg())?;
        files.push(path);
    }
    Ok(files)
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
        "final_omega": s.final_omega,
        "outcome": s.outcome,
        "balanced": s.balanced,
        "residual_unbalance": s.residual_unbalance,
        "balance_tolerance": autobal::spatial::dynamics::simulate::BALANCE_TOLERANCE,
        "state_basis": if s.race_whirl.is_some() { "race_whirl" } else { "residual" },
        "race_whirl": s.race_whirl,
        "ball_drift": s.ball_drift,
        "averaged": s.averaged,
        "settled": s.settled,
        "creep_rate": s.creep_rate,
        "warnings": run_warnings(s),
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
    t.push_str(&outcome_line(s));
    if let Some(st) = &s.stopped {
        t.push_str(&format!("stopped early: {st}\n"));
    }
    t
}

/// The table's line with the run's word ([`RunSummary::outcome`], the spatial run's words),
/// what it is decided on, and a warning where the balls have not settled.
fn outcome_line(s: &RunSummary) -> String {
    use autobal::spatial::dynamics::RunOutcome;
    let word = match s.outcome {
        RunOutcome::Balanced => "balanced",
        RunOutcome::PartiallyBalanced => {
            "partially balanced: no balanced state at the final speed (the balls' capacity short of the force their plane must cancel), they rest together against the unbalance"
        }
        RunOutcome::NotBalanced => "not balanced",
        RunOutcome::NotSettled => "not settled",
    };
    let basis = match s.race_whirl {
        Some(w) => format!(
            "; race whirl {w:.3e} of the race's whirl with the balls spread evenly (what the word is decided on, as stability's race_whirl; balanced up to {})",
            autobal::spatial::dynamics::simulate::BALANCE_TOLERANCE
        ),
        None => String::new(),
    };
    let mut t = format!(
        "final: {}; residual static unbalance {:.3e} of the unbalance ({}){basis}: {word}\n",
        speed_text(s.final_omega),
        s.residual_unbalance,
        autobal::simulation::window::basis_words(s.averaged)
    );
    for w in &run_warnings(s) {
        t.push_str(&format!("warning: {w}\n"));
    }
    t
}

/// The run's warnings: the summary's, or where the run completed not settled without one that
/// says why, that it is no stationary state (audit 25: the table said so, the JSON's
/// `warnings` was empty).
pub fn run_warnings(s: &RunSummary) -> Vec<String> {
    use autobal::spatial::dynamics::RunOutcome;
    // (a creep, or an end at no stationary state, has its own line among the warnings: its
    // balls' drift passed the test)
    if s.outcome == RunOutcome::NotSettled && s.stopped.is_none() && s.warnings.is_empty() {
        return vec![format!(
            "not settled: the speed still changes over the last two revolutions, or the balls' mean angles still drift from one revolution to the next{}: a transient (raise drive.t_end), a run-up, or balls circulating round the race; the residual is no stationary state's",
            s.ball_drift.map_or(", or it turned less than two revolutions".to_string(), |d| format!(" (by {d:.2e} rad)"))
        )];
    }
    s.warnings.clone()
}

/// The stability margin over speed as a figure (`stability --svg`, the report): the largest
/// real part of the balanced state's eigenvalues (or the largest Floquet exponent of its
/// periodic orbit) per speed, stable ranges shaded.
pub fn margin_plot(r: &RotorStability, omega_max: f64) -> Plot {
    let pts: Vec<(f64, f64)> = r.points.iter().filter_map(|p| p.abscissa.map(|a| (p.omega, a))).collect();
    let lo = pts.iter().map(|p| p.1).fold(0.0, f64::min);
    let hi = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    let pad = 0.1 * (hi - lo).max(1e-6);
    let shades = r.stable_ranges.iter().map(|s| Shade { x: (s.from, s.to), y: (None, Some(0.0)), color: "#009E73".into() }).collect();
    let periodic = r.kind == Kind::PeriodicOrbit;
    Plot {
        title: format!("Linear rotor: stability margin of the {} over speed", if periodic { "stationary orbit" } else { "balanced state" }),
        x_label: "speed ω (rad/s)".into(),
        y_label: format!("{} (1/s; < 0: stable)", if periodic { "largest Floquet exponent" } else { "max Re λ" }),
        series: vec![Series::new("margin", pts, PALETTE[1])],
        shades,
        shade_legend: vec![("#009E73".into(), "exactly stable (shaded below 0)".into())],
        x_range: Some((0.0, omega_max)),
        y_range: Some((lo - pad, hi + pad)),
        ..Default::default()
    }
}

/// Write [`margin_plot`] as SVG to `path` (through [`outfile::write_atomic`]).
pub fn write_svg(r: &RotorStability, omega_max: f64, path: &Path) -> Result<()> {
    outfile::write_atomic("--svg", path, margin_plot(r, omega_max).to_svg())
}

/// The undamped modes of the rotor at rest (the balls as rings, the rotor-fixed inertia at the
/// rotor's angle 0, the symmetric part of `K` at `Ω = 0`) at one balancer plane: for the lowest
/// `count` modes `K φ = ω² (M + M_rot + M_balls) φ`, the translation radius of the plane's race
/// centre, `|(φ_x + e φ_β, φ_y − e φ_α)|` (`e` the plane's offset from its node, the model's
/// convention of [`LinearRotor::ball_mass_matrix`]), and the tilt at its node
/// `|(φ_α, φ_β)|`, both divided by the largest translation radius of any node or balancer
/// plane of the mode (so the translation is 1 where the plane sits at the mode's antinode, 0
/// at a node of the mode; the tilt is in rad per metre of that largest translation). These ratios do not
/// depend on which vector of a pair of equal frequencies is taken when the rotor is
/// isotropic (a pair is `(φ, J φ)`, `J` the quarter turn). The vectors come from inverse
/// iteration with the shift `ω_k²` on `K − σ M` (three steps, `M`-orthogonal to the modes
/// found before, which separates the members of a pair). `shape` is the mode's translation
/// along the direction of its largest one, node by node.
pub fn modes_at_plane(rotor: &LinearRotor, plane: usize, count: usize) -> Result<Vec<ModeAtPlane>> {
    let b = rotor.balancers.get(plane).ok_or_else(|| anyhow!("balancer plane {plane}: the rotor has {} planes", rotor.balancers.len()))?;
    let r0 = rotor.at_speed(0.0);
    let n = r0.dofs();
    // M + M_rot (at rest, the rotor's angle 0) + the balls as rings: the mass matrix of
    // LinearRotor::natural_frequencies
    let mut m = r0.m.clone();
    for (i, (v, f)) in r0.ball_mass_matrix().iter().zip(r0.rotor_fixed_in(0.0)).enumerate() {
        m[i] += v + f;
    }
    let k: Vec<f64> = (0..n * n).map(|ij| 0.5 * (r0.k[ij] + r0.k[(ij % n) * n + ij / n])).collect();
    let mut sym = r0.clone();
    sym.k = k.clone();
    // ω² with its sign: a divergent mode (K not positive semi-definite) has its own shift
    let w2 = sym.natural_frequencies_squared(&[], true)?;
    let scale = w2.iter().fold(0.0, |a: f64, b| a.max(b.abs())).max(f64::MIN_POSITIVE);
    let threshold = autobal::linear_rotor::divergence_threshold(&w2);
    let starts = rotor.node_starts();
    let mut found: Vec<Vec<f64>> = vec![];
    let mut out = vec![];
    let mdot = |a: &[f64], b: &[f64]| -> f64 { (0..n).map(|i| a[i] * (0..n).map(|j| m[i * n + j] * b[j]).sum::<f64>()).sum() };
    for (idx, &lk) in w2.iter().take(count.min(n)).enumerate() {
        let wk = lk.max(0.0).sqrt();
        // a shift just below ω²: K − σM stays regular, the mode dominates by (ω² − σ)⁻¹
        // (rigid-body modes, ω = 0, get a shift 1e-15 of the highest |ω²| below them)
        // (ω² of a mode that does not diverge as before: wk², a rigid-body mode's rounding 0)
        let lk = if lk < -threshold { lk } else { wk * wk };
        let sigma = lk - 1e-9 * lk.abs().max(1e-6 * scale);
        let a: Vec<f64> = (0..n * n).map(|ij| k[ij] - sigma * m[ij]).collect();
        let singular = || anyhow!("linear_rotor: the mode shapes at rest: K − ω²M is singular at mode {idx}");
        let factors = lu(&a, n).ok_or_else(singular)?;
        let mut v: Vec<f64> = (0..n).map(|i| 1.0 + ((i * 7 + idx * 3) % 11) as f64 / 11.0).collect();
        for _ in 0..3 {
            for f in &found {
                let c = mdot(f, &v);
                v.iter_mut().zip(f).for_each(|(x, y)| *x -= c * y);
            }
            let rhs: Vec<f64> = (0..n).map(|i| (0..n).map(|j| m[i * n + j] * v[j]).sum()).collect();
            v = lu_solve(&factors, &rhs).ok_or_else(singular)?;
            for f in &found {
                let c = mdot(f, &v);
                v.iter_mut().zip(f).for_each(|(x, y)| *x -= c * y);
            }
            let norm = mdot(&v, &v).sqrt();
            if !norm.is_finite() || norm <= 0.0 {
                bail!("linear_rotor: the mode shapes at rest: mode {idx} did not converge");
            }
            v.iter_mut().for_each(|x| *x /= norm);
        }
        let radius = |node: usize| v[starts[node]].hypot(v[starts[node] + 1]);
        // a plane's race centre moves by (x + e β, y − e α), e its offset from its node
        // (the model's convention: LinearRotor::ball_mass_matrix)
        let at_plane = |p: &autobal::linear_rotor::BalancerPlane| {
            let s = starts[p.node];
            let (a, be) = rotor.node_dofs(p.node).2.map_or((0.0, 0.0), |(ia, ib)| (v[ia], v[ib]));
            (v[s] + p.offset * be).hypot(v[s + 1] - p.offset * a)
        };
        let top = (0..rotor.nodes).max_by(|a, b| radius(*a).total_cmp(&radius(*b))).unwrap_or(0);
        let largest = radius(top);
        // the scale of the ratios: the largest translation of any node or balancer plane
        let scale = rotor.balancers.iter().map(at_plane).fold(largest, f64::max);
        if largest.is_nan() || scale.is_nan() || scale <= 0.0 {
            bail!("linear_rotor: mode {idx} at rest ({} rad/s) moves no node's translation", fmt_num(wk));
        }
        let tilt = rotor.node_dofs(b.node).2.map_or(0.0, |(ia, ib)| v[ia].hypot(v[ib]) / scale);
        let shape = if largest > 0.0 {
            let (ux, uy) = (v[starts[top]] / largest, v[starts[top] + 1] / largest);
            starts.iter().map(|&s| (v[s] * ux + v[s + 1] * uy) / largest).collect()
        } else {
            vec![0.0; starts.len()]
        };
        out.push(ModeAtPlane { omega: wk, omega_squared: lk, translation: at_plane(b) / scale, tilt, node: b.node, shape });
        found.push(v);
    }
    Ok(out)
}

/// One undamped mode at a balancer plane ([`modes_at_plane`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeAtPlane {
    /// Natural frequency at rest (rad/s), 0 for a divergent mode (`omega_squared < 0`).
    pub omega: f64,
    /// `ω²` at rest ((rad/s)²) with its sign: negative for a mode that diverges at rest
    /// ([`autobal::linear_rotor::static_divergence`]).
    pub omega_squared: f64,
    /// The translation radius of the plane's race centre (its node's translation plus its
    /// offset times the tilt) over the mode's largest of any node or plane (0 to 1).
    pub translation: f64,
    /// The tilt at the plane's node over the mode's largest translation of any node or plane
    /// (rad/m).
    pub tilt: f64,
    /// The plane's node.
    pub node: usize,
    /// The mode's translation at every node along the direction of its largest one (signed,
    /// the largest 1): the mode shape of a planar mode.
    pub shape: Vec<f64>,
}

/// The LU factors of `A` (row-major `n × n`) with partial pivoting, `P A = L U` stored in
/// place with the row order; `None` when a pivot vanishes.
fn lu(a: &[f64], n: usize) -> Option<(Vec<f64>, Vec<usize>)> {
    let mut a = a.to_vec();
    let mut perm: Vec<usize> = (0..n).collect();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))?;
        if a[p * n + c] == 0.0 {
            return None;
        }
        if p != c {
            for j in 0..n {
                a.swap(p * n + j, c * n + j);
            }
            perm.swap(p, c);
        }
        for i in c + 1..n {
            let f = a[i * n + c] / a[c * n + c];
            a[i * n + c] = f;
            if f != 0.0 {
                for j in c + 1..n {
                    a[i * n + j] -= f * a[c * n + j];
                }
            }
        }
    }
    Some((a, perm))
}

/// `A x = b` from [`lu`]'s factors; `None` when the solution is not finite.
fn lu_solve((a, perm): &(Vec<f64>, Vec<usize>), b: &[f64]) -> Option<Vec<f64>> {
    let n = perm.len();
    let mut x: Vec<f64> = perm.iter().map(|&p| b[p]).collect();
    for i in 0..n {
        let s: f64 = (0..i).map(|j| a[i * n + j] * x[j]).sum();
        x[i] -= s;
    }
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| a[i * n + j] * x[j]).sum();
        x[i] = (x[i] - s) / a[i * n + i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The preset `export-model` writes without a config: paper 004's planar rotor with its race
/// centred as a Jeffcott rotor with two balls ([`LinearRotor::from_planar`]).
pub fn preset() -> Result<LinearRotor> {
    let mut p = autobal::planar::PlanarRotor::paper();
    p.s2 = 0.0;
    Ok(LinearRotor::from_planar(&p)?)
}

/// `export-model`: write `STEM.toml` and `STEM_{M,C,G,K}.mtx` into `dir`; returns the paths.
/// `inputs`: the config it was read from (`None`: the preset) and that config's tables with the
/// folder its files are read from; none of them (the config, its matrix files) is overwritten.
pub fn export_model(rotor: &LinearRotor, inputs: (Option<&Path>, Option<(&Table, &Path)>), dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    // the folder is made by the first file written, after the check (which refuses `/dev/x`)
    let (text, files) = export(rotor, stem);
    let mut o = outfile::Outputs::new();
    o.config_inputs(inputs.0, inputs.1);
    let toml_path = dir.join(format!("{stem}.toml"));
    o.output("--out", &toml_path);
    for (name, _) in &files {
        o.output("--out", &dir.join(name));
    }
    o.check()?;
    // the config and its matrices whole, or none of them (a full disk left some matrices
    // without their config)
    let mut all = vec![(toml_path, text.into_bytes())];
    all.extend(files.into_iter().map(|(name, body)| (dir.join(name), body.into_bytes())));
    outfile::write_all_or_none("--out", &all)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example() -> (Table, PathBuf) {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/linear_rotor_shaft.toml");
        (read_set(Some(&path), &[]).unwrap().0, path)
    }

    /// A linear rotor config's matrix files are inputs: `simulate --out` and `export-model` whose
    /// outputs would replace one (a matrix named `r.csv`, `simulate --out DIR/r`; an export of the
    /// config into its own folder under a stem its files use) are refused naming the key, and
    /// the files are left byte for byte (on b7bef73 both overwrote them).
    #[test]
    fn outputs_never_replace_the_matrix_files_a_config_names() {
        use crate::command::{Command, ConfigSource};
        use autobal::control::Control;
        let d = std::env::temp_dir().join(format!("autobal-lr-inputs-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        export_model(&preset().unwrap(), (None, None), &d, "rotor").unwrap();
        std::fs::rename(d.join("rotor_M.mtx"), d.join("r.csv")).unwrap();
        let text = std::fs::read_to_string(d.join("rotor.toml")).unwrap().replace("rotor_M.mtx", "r.csv");
        std::fs::write(d.join("rotor.toml"), &text).unwrap();
        let m = std::fs::read(d.join("r.csv")).unwrap();
        let cfg = d.join("rotor.toml");
        let sim = crate::simulate::Args {
            config: ConfigSource::file(Some(&cfg), &[]),
            dt: None,
            check_tolerance: false,
            files: Some(crate::simulate::Files { out: d.join("r"), parquet: false }),
            columns: false,
        };
        let e = sim.run(&Control::none()).err().expect("refused").to_string();
        assert!(e.contains("is the input --config's linear_rotor.m"), "{e}");
        // export-model: the file's own names, and a name only --set gives
        let ex = |sets: &[String], stem: &str| {
            crate::export_model::Args { config: ConfigSource::file(Some(&cfg), sets), out: d.clone(), stem: stem.into() }.run(&Control::none())
        };
        std::fs::copy(d.join("rotor_C.mtx"), d.join("other_C.mtx")).unwrap();
        let e = ex(&[], "rotor").err().expect("refused").to_string();
        assert!(e.contains("is the input --config"), "{e}");
        let e = ex(&["linear_rotor.c=\"other_C.mtx\"".to_string()], "other").err().expect("refused").to_string();
        assert!(e.contains("is the input --config's linear_rotor.c"), "{e}");
        assert_eq!(std::fs::read(d.join("r.csv")).unwrap(), m);
        assert_eq!(std::fs::read_to_string(&cfg).unwrap(), text);
        let _ = std::fs::remove_dir_all(&d);
    }

    /// `--set linear_rotor.balancer[j].contact=true` turns real balls on as the key in the
    /// config does (the config then reads with contact on that plane), `false` off; anything
    /// else, or an index past the planes, is refused naming the key.
    #[test]
    fn set_takes_a_planes_contact_as_true_or_false() {
        let (mut root, path) = example();
        apply_set(&mut root, "linear_rotor.balancer[0].contact=true").unwrap();
        let cfg = from_table(&root, path.parent().unwrap()).unwrap();
        assert!(cfg.rotor.ball_physics[0].contact);
        apply_set(&mut root, "linear_rotor.balancer[0].contact = false").unwrap();
        let cfg = from_table(&root, path.parent().unwrap()).unwrap();
        assert!(cfg.rotor.ball_physics.iter().all(|p| !p.contact));
        let e = apply_set(&mut root, "linear_rotor.balancer[0].contact=1").unwrap_err().to_string();
        assert_eq!(e, "--set linear_rotor.balancer[0].contact: expected true or false, got `1`");
        let e = apply_set(&mut root, "linear_rotor.balancer[3].contact=true").unwrap_err().to_string();
        assert!(e.starts_with("linear_rotor.balancer[3].contact: the config has 1 [[linear_rotor.balancer]]"), "{e}");
    }

    /// With three balls the balanced states form a one-parameter family, which `stability`
    /// follows at each speed (the general route, as for the other models): the JSON has it and
    /// the table names it, and at each speed the member analysed lies in the family, its
    /// abscissa between the family's most and least stable members' (to 1e-9 1/s: the same
    /// eigenvalue computation on the same Newton-converged member, round-off of |λ| ≲ 1e3 1/s).
    #[test]
    fn stability_with_three_balls_follows_the_family() {
        let (mut root, path) = example();
        let mut bal = root["linear_rotor"]["balancer"][0].as_table().cloned().unwrap();
        bal.insert("balls".into(), toml::Value::Integer(3));
        root.get_mut("linear_rotor").and_then(|t| t.get_mut("balancer")).and_then(|b| b.as_array_mut()).unwrap()[0] = toml::Value::Table(bal);
        let cfg = from_table(&root, path.parent().unwrap()).unwrap();
        let omega_max = default_omega_max(&cfg).unwrap();
        let (r, red) = stability(&cfg, omega_max, 6).unwrap();
        assert_eq!(r.family_dimension, 1);
        let fam = r.family.as_ref().unwrap();
        assert_eq!(fam.dimension, 1);
        let mut followed = 0;
        for p in &r.points {
            let (Some(a), Some(f)) = (p.abscissa, p.family.as_ref()) else { continue };
            followed += 1;
            assert!(f.most_stable.abscissa <= a + 1e-9 && a <= f.least_stable.abscissa + 1e-9, "Ω {}: {a} outside {f:?}", p.omega);
        }
        assert!(followed > 0);
        let json = stability_json(&cfg, &r, &red, omega_max).unwrap();
        assert_eq!(json["family"]["dimension"], 1);
        assert!(stability_table(&cfg, &r, &red, omega_max).unwrap().contains("family of dimension 1"));
    }

    fn summary(peak: f64, last: f64) -> RunSummary {
        let p = autobal::simulation::Peak { value: peak, t: 1.0, with: 100.0 };
        RunSummary {
            t: 1.0,
            stopped: None,
            peak: p,
            peak_any_node: p,
            final_radius: last,
            final_omega: 1.0,
            residual_unbalance: 1.0,
            race_whirl: None,
            ball_drift: None,
            averaged: false,
            settled: false,
            outcome: autobal::spatial::dynamics::RunOutcome::NotSettled,
            balanced: false,
            steps: 10,
            creep_rate: None,
            warnings: vec![],
        }
    }

    /// The sweep's figures: a curve per value of the second axis, its points the runs at that
    /// value in the grid's order, the radii in mm; a run never sampled is a gap (NaN).
    #[test]
    fn sweep_figures_have_a_curve_per_value_of_the_other_axes() {
        let paths = vec!["linear_rotor.ball_mass".to_string(), "linear_rotor.drag".to_string()];
        let runs: Vec<(Vec<f64>, RunSummary)> = [(0.02, 0.1, 1e-3), (0.03, 0.1, 2e-3), (0.02, 0.2, 3e-3), (0.03, 0.2, f64::NEG_INFINITY)]
            .iter()
            .map(|&(m, c, r)| (vec![m, c], summary(r, r / 2.0)))
            .collect();
        let figs = sweep_plots(&paths, &runs);
        assert_eq!(figs.iter().map(|f| f.0.as_str()).collect::<Vec<_>>(), ["sweep_peak", "sweep_final"]);
        let s = &figs[0].1.series;
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].label, "linear_rotor.drag = 0.1");
        assert_eq!(s[0].points, vec![(0.02, 1.0), (0.03, 2.0)]);
        assert_eq!(s[1].points[0], (0.02, 3.0));
        assert!(s[1].points[1].1.is_nan(), "a peak never seen is a gap");
        assert_eq!(figs[1].1.series[0].points, vec![(0.02, 0.5), (0.03, 1.0)]);
        assert_eq!(figs[0].1.x_label, "linear_rotor.ball_mass");
        // one axis: one curve
        let one: Vec<(Vec<f64>, RunSummary)> = runs.iter().take(2).map(|(v, s)| (vec![v[0]], s.clone())).collect();
        assert_eq!(sweep_plots(&paths[..1], &one)[0].1.series.len(), 1);
    }

    /// The basins' figure: each run a cell at its initial angles (ψ1 the column, ψ2 the row),
    /// balanced -1, not +1, not run NaN.
    #[test]
    fn basins_figure_places_each_run_at_its_angles() {
        use autobal::linear_rotor::basins::BasinEnd;
        let pi = std::f64::consts::PI;
        let angles = [[0.0, 0.0], [pi, 0.0], [0.0, pi], [pi, pi]];
        let end = |balanced: bool| {
            Some(BasinEnd { summary: summary(1e-3, 1e-4), psi0: vec![], psi: vec![], final_amplitude: 1e-4, residual_unbalance: 0.0, balanced })
        };
        let ends = vec![end(true), end(false), end(true), None];
        let p = basins_plot(&angles, &ends);
        let z = &p.heatmap.as_ref().unwrap().z;
        assert_eq!((z[0][0], z[0][1], z[1][0]), (-1.0, 1.0, -1.0));
        assert!(z[1][1].is_nan());
        assert_eq!(p.heatmap.as_ref().unwrap().x, vec![0.0, 180.0]);
    }

    /// A sweep's point without values is the run `simulate` makes (this module's [`setup`]): the
    /// library's `run_of` repeats its rules (reduction, default run-up to `default_omega_max`,
    /// `dt`), here with the example's reduction, without its `[drive]` (the default run-up),
    /// then with it (`drive.b` set by its path).
    #[test]
    fn a_sweep_point_is_the_run_of_simulate() {
        let (root, path) = example();
        let dir = path.parent().unwrap();
        for extra in [None, Some(("drive.b", 40.0))] {
            let mut root = root.clone();
            match extra {
                // without [drive]: simulate's default run-up
                None => {
                    root.remove("drive");
                }
                Some((k, v)) => autobal::linear_rotor::spec::set_path(&mut root, k, v).unwrap(),
            }
            let cfg = from_table(&root, dir).unwrap();
            let s = setup(&cfg, default_omega_max(&cfg).unwrap(), None).unwrap();
            let base = spec(&root, dir).unwrap();
            let run = autobal::sweep::SweepModel::at(&base, &[], &[]).unwrap();
            assert_eq!((&run.rotor, &run.drive, &run.settings, run.default_drive), (&s.rotor, &s.drive, &s.settings, s.default_drive));
            assert_eq!(run.default_drive, extra.is_none());
        }
    }

    /// A uniform steel shaft of 12 Euler–Bernoulli elements (1.2 m, 25 mm) pinned at both ends
    /// (bearings of 1e12 N/m: their compliance is 1e-9 of the shaft's, EI/L³ ≈ 2.3e3 N/m), a
    /// balancer of negligible mass (1e-9 kg against the shaft's 4.6 kg) at `node`.
    fn pinned_shaft(node: usize) -> LinearRotor {
        let text = format!(
            "[linear_rotor]\nrotary_inertia = false\ngyroscopic = false\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.025\ne = 2.1e11\nrho = 7850.0\ncount = 12\n\
             [[linear_rotor.bearings]]\nnode = 0\nk = 1e12\n[[linear_rotor.bearings]]\nnode = 12\nk = 1e12\n\
             [[linear_rotor.balancer]]\nnode = {node}\nradius = 0.05\nballs = 2\nball_mass = 1e-9\n"
        );
        let root: Table = toml::from_str(&text).unwrap();
        from_table(&root, Path::new(".")).unwrap().rotor
    }

    /// The simply supported shaft's modes are `sin(kπx/L)` at `ω_k = (kπ/L)² sqrt(EI/(ρA))`
    /// (a closed form independent of the finite elements): at the balancer plane at x = L/4
    /// (node 3) mode k's translation is |sin(kπ/4)| of its largest at the nodes, its tilt
    /// (kπ/L)|cos(kπ/4)| per metre of that, and mode 4 has a node there. Each frequency comes
    /// twice (x and y). Tolerances: the 12 cubic elements' nodal values of modes 1-4 (3 to 12
    /// elements per half wave), measured 5e-4 at most on the translation and 1e-3 relative on
    /// the tilt, bounded at 4×; the frequencies to 1e-3 (FE error ∝ (kh/L)⁴).
    #[test]
    fn modes_at_the_plane_of_a_pinned_shaft_are_the_sine_modes() {
        let rotor = pinned_shaft(3);
        let m = modes_at_plane(&rotor, 0, 8).unwrap();
        let (l, d, e, rho) = (1.2, 0.025, 2.1e11, 7850.0);
        let (area, inertia) = (std::f64::consts::PI * d * d / 4.0, std::f64::consts::PI * d.powi(4) / 64.0);
        let pi = std::f64::consts::PI;
        for k in 1..=4usize {
            let kf = k as f64;
            let w = (kf * pi / l).powi(2) * (e * inertia / (rho * area)).sqrt();
            let largest = (0..=12).map(|j| (kf * pi * j as f64 / 12.0).sin().abs()).fold(0.0, f64::max);
            let want_t = (kf * pi / 4.0).sin().abs() / largest;
            let want_tilt = kf * pi / l * (kf * pi / 4.0).cos().abs() / largest;
            for got in &m[2 * (k - 1)..2 * k] {
                assert!((got.omega / w - 1.0).abs() < 1e-3, "mode {k}: ω {} against {w}", got.omega);
                assert!((got.translation - want_t).abs() < 2e-3, "mode {k}: translation {} against {want_t}", got.translation);
                assert!((got.tilt - want_tilt).abs() < 4e-3 * want_tilt.max(1.0), "mode {k}: tilt {} against {want_tilt}", got.tilt);
                assert_eq!(got.shape.len(), 13);
                // the shape itself: sin(kπ j/12) over its largest, up to the sign
                let sign = if got.shape[1] * (kf * pi / 12.0).sin() >= 0.0 { 1.0 } else { -1.0 };
                for (j, v) in got.shape.iter().enumerate() {
                    let want = (kf * pi * j as f64 / 12.0).sin() / largest;
                    assert!((sign * v - want).abs() < 2e-3, "mode {k} node {j}: {v} against {want}");
                }
            }
        }
        // the balancer at mid-span (node 6): the even modes have a node there
        let mid = modes_at_plane(&pinned_shaft(6), 0, 4).unwrap();
        assert!(mid[0].translation > 0.999 && mid[2].translation < 2e-3, "{mid:?}");
    }

    /// A plane 0.05 m beyond its node (node 3 at x = L/4 of the pinned shaft) moves with its
    /// node's translation plus the offset times the slope, `sin(kπ/4) + e (kπ/L) cos(kπ/4)`
    /// (the race centre `x + e β`, `β = dx/dz`): mode 4, which has a node at node 3, moves the
    /// plane by 0.52 of its largest (node 0.5236), and modes 1 and 3 differ by the sign of the
    /// slope (0.800 and 0.429; the other sign would give 0.614 and 0.985). The largest of the
    /// nodes and the plane is the scale (1 for these modes, the plane moving less). Tolerance
    /// as in the test above (the 12 elements' nodal values and slopes, 2e-3).
    #[test]
    fn a_plane_off_its_node_moves_with_the_tilt() {
        let mut rotor = pinned_shaft(3);
        rotor.balancers[0].offset = 0.05;
        let m = modes_at_plane(&rotor, 0, 8).unwrap();
        let (l, e, pi) = (1.2, 0.05, std::f64::consts::PI);
        for k in 1..=4usize {
            let kf = k as f64;
            let largest = (0..=12).map(|j| (kf * pi * j as f64 / 12.0).sin().abs()).fold(0.0, f64::max);
            let want = ((kf * pi / 4.0).sin() + e * kf * pi / l * (kf * pi / 4.0).cos()).abs() / largest;
            for got in &m[2 * (k - 1)..2 * k] {
                assert!((got.translation - want).abs() < 2e-3, "mode {k}: translation at the plane {} against {want}", got.translation);
            }
        }
    }
}
