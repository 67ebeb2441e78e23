//! Config files: reading them (with a size limit), `--set` overrides, and the library's
//! conversion of the tables into validated models ([`autobal::config`], where the schema, the
//! defaults and every check live).

use anyhow::{anyhow, bail, Result};
use autobal::config::SpatialConfig;
use toml::Table;

/// The embedded default example (paper 000's base case).
pub const DEFAULT_CONFIG: &str = autobal::config::DEFAULT_SPATIAL;

/// The embedded default of `simulate` and `sweep` (paper 004's rotor).
pub const DEFAULT_PLANAR: &str = autobal::config::DEFAULT_PLANAR;

pub use autobal::config::Analysis;
#[cfg(test)]
pub use autobal::config::SCHEMA;

/// A loaded, validated spatial config: the library's [`SpatialConfig`] (model, spec, analysis,
/// units) and where it came from (`source`: the file's name or the embedded default, for the
/// tables and the report). It dereferences to the [`SpatialConfig`], so that `cfg.model`,
/// `cfg.analysis`, ... read the library's one copy.
#[derive(Debug, Clone)]
pub struct Config {
    /// The converted config ([`autobal::config::spatial`]).
    pub config: SpatialConfig,
    /// Where it came from, for the tables and the report.
    pub source: String,
}

impl std::ops::Deref for Config {
    type Target = SpatialConfig;
    fn deref(&self) -> &SpatialConfig {
        &self.config
    }
}

/// Apply one `key=value` override with a dotted key.
pub fn apply_set(root: &mut Table, assignment: &str) -> Result<()> {
    let (key, value) = assignment.split_once('=').ok_or_else(|| anyhow!("--set {assignment}: expected key=value, e.g. --set dimensionless.l_left=1.2"))?;
    let key = key.trim();
    if key.is_empty() {
        bail!("--set {assignment}: no key before `=`; expected key=value, e.g. --set dimensionless.l_left=1.2");
    }
    // one element of an array key: `--set drive.psi0[2]=0.3` (1-based, as the sweep's paths)
    if let Some((name, j)) = autobal::paths::indexed(key) {
        let j = j.map_err(|reason| anyhow!("--set {key}: {reason}"))?;
        let v: f64 = value.trim().parse().map_err(|_| anyhow!("--set {key}: `{}` is not a number", value.trim()))?;
        return Ok(autobal::config::set_element(root, key, name.trim(), j, v)?);
    }
    // `--set dimensionless={c_sigma=1}`: a whole table is not set at once; the option is named
    let parts: Vec<&str> = key.split('.').collect();
    if parts.len() != 2 || parts.iter().any(|p| p.trim().is_empty()) {
        bail!("--set {key}: expected a dotted key table.field (one field at a time), e.g. --set dimensionless.l_left=1.2");
    }
    Ok(autobal::config::set(root, key, autobal::config::parse_value(value.trim()))?)
}

/// Read and parse the config text (or the embedded default) into a TOML table.
pub fn read(path: Option<&std::path::Path>) -> Result<(Table, String)> {
    read_with_default(path, DEFAULT_CONFIG, "embedded default (examples/default.toml)")
}

/// Largest config file read (bytes): a config is a few dozen lines; this bounds the memory and
/// time a wrong path (`/dev/zero`, a log file) can cost.
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Open an input file without waiting on a named pipe that nobody writes: a FIFO is opened
/// non-blocking on Linux (a blocking open waits for a writer, forever: `--config fifo` hung),
/// so that without a writer it reads as empty at once; with one (`--config /dev/stdin` fed by
/// a pipe, `<(...)`), [`read_input`] reads it to the end.
pub fn open_input(p: &std::path::Path) -> std::io::Result<std::fs::File> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
        if std::fs::metadata(p).is_ok_and(|m| m.file_type().is_fifo()) {
            // O_NONBLOCK on Linux (every architecture Rust supports there but alpha/sparc/mips,
            // which are not targets of this project)
            return std::fs::File::options().read(true).custom_flags(0o4000).open(p);
        }
    }
    std::fs::File::open(p)
}

/// Read at most `limit + 1` bytes of a file from [`open_input`] (a non-blocking FIFO's "no data
/// yet" waited out in 5 ms steps while a writer holds it open).
pub fn read_input(file: std::fs::File, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    let mut r = file.take(limit + 1);
    loop {
        match r.read_to_end(&mut bytes) {
            Ok(_) => return Ok(bytes),
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock || e.kind() == std::io::ErrorKind::Interrupted => {
                std::thread::sleep(std::time::Duration::from_millis(5))
            }
            Err(e) => return Err(e),
        }
    }
}

/// Why [`read_input_file`] read nothing.
pub const NO_WRITER: &str = "is a named pipe with no writer (nothing to read); start the program that writes it first, or give a file";

/// The bytes of an input file (a config, a matrix file), at most `limit + 1` of them
/// ([`open_input`], [`read_input`]); `what` names it in "is a directory, not {what}". The error
/// is the reason alone (the caller puts the file's name in front): `cannot read: …`, a folder,
/// or a named pipe with no writer ([`NO_WRITER`]: opened without waiting, no writer reads as an
/// empty file, which the caller would report as a file without content).
pub fn read_input_file(p: &std::path::Path, limit: u64, what: &str) -> std::result::Result<Vec<u8>, String> {
    let file = open_input(p).map_err(|e| format!("cannot read: {e}"))?;
    let meta = file.metadata().ok();
    if meta.as_ref().is_some_and(|m| m.is_dir()) {
        return Err(format!("is a directory, not {what}"));
    }
    #[cfg(unix)]
    let fifo = {
        use std::os::unix::fs::FileTypeExt;
        meta.is_some_and(|m| m.file_type().is_fifo())
    };
    #[cfg(not(unix))]
    let fifo = false;
    let bytes = read_input(file, limit).map_err(|e| format!("cannot read: {e}"))?;
    if fifo && bytes.is_empty() {
        return Err(NO_WRITER.into());
    }
    Ok(bytes)
}

/// Read at most [`MAX_CONFIG_BYTES`] of a config file as UTF-8.
pub(crate) fn read_limited(p: &std::path::Path) -> Result<String> {
    let name = format!("--config {}", p.display());
    let bytes = read_input_file(p, MAX_CONFIG_BYTES, "a config file").map_err(|e| anyhow!("{name}: {e}"))?;
    if bytes.len() as u64 > MAX_CONFIG_BYTES {
        return Err(autobal::Error::TooLarge {
            what: name,
            size: bytes.len() as u64,
            limit: MAX_CONFIG_BYTES,
            reason: "bytes; a config is a few dozen lines".into(),
        }
        .into());
    }
    String::from_utf8(bytes).map_err(|e| anyhow!("{name}: not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
}

/// [`read`] with another embedded default.
pub fn read_with_default(path: Option<&std::path::Path>, default: &str, default_name: &str) -> Result<(Table, String)> {
    let (text, source) = match path {
        Some(p) => (read_limited(p)?, p.display().to_string()),
        None => (default.to_string(), default_name.to_string()),
    };
    Ok((parse_text(&text, &source)?, source))
}

/// Parse config text into a TOML table; errors say `SOURCE: line N: …` on one line.
pub fn parse_text(text: &str, source: &str) -> Result<Table> {
    Ok(autobal::config::parse(text, source)?)
}

/// Refuse a `--set` key given twice (`--set rotor.mass=2 --set rotor.mass=3`): the later one
/// would silently win over the earlier. Keys compare trimmed (an index spelled otherwise than
/// [`autobal::paths::index_digits`] reads it, `drive.psi0[01]`, is refused where it is
/// applied); a whole array given after one of its elements (`--set drive.psi0[1]=0.2 --set
/// drive.psi0=[…]`) is refused too.
pub fn check_repeated_sets(sets: &[String]) -> Result<()> {
    let mut seen: Vec<String> = Vec::with_capacity(sets.len());
    for s in sets {
        let Some((key, _)) = s.split_once('=') else { continue };
        let key = key.trim();
        // (another spelling of an index, `drive.psi0[01]`, is refused where it is applied)
        if seen.iter().any(|k| k == key) {
            // (the values are not echoed: a fuzzed one may be 80 digits or control characters)
            bail!("--set {key}: given twice (the later would silently replace the earlier); give it once");
        }
        // a whole array after one of its elements would silently undo the element
        if let Some(element) = seen.iter().find(|k| autobal::paths::indexed(k).is_some_and(|(name, _)| name.trim() == key)) {
            bail!("--set {key}: given after --set {element} (the whole array would silently replace that element); give the whole array first");
        }
        seen.push(key.to_string());
    }
    Ok(())
}

/// Read the config text (or the embedded default) and apply the overrides.
pub fn read_set(path: Option<&std::path::Path>, sets: &[String]) -> Result<(Table, String)> {
    check_repeated_sets(sets)?;
    let (mut root, source) = read(path)?;
    for s in sets {
        apply_set(&mut root, s)?;
    }
    Ok((root, source))
}

/// Load the config text (or the embedded default), apply overrides, validate, build the model.
#[cfg(test)]
pub fn load(path: Option<&std::path::Path>, sets: &[String]) -> Result<Config> {
    let (root, source) = read_set(path, sets)?;
    build(&root, &source)
}

pub use autobal::config::Model;

/// The warning of an analytic `command` (`critical`, `map`, `report`, ...) on a config with
/// `keys` that only the spatial simulation uses ([`autobal::config::EntryUse::simulation_only`]),
/// or `None`.
pub fn ignored_warning(keys: &[String], command: &str) -> Option<String> {
    if keys.is_empty() {
        return None;
    }
    let (who, also) = match command {
        "report" => (
            "the report's tables of papers 000/003 (parameters, eq (16) critical speeds, sensitivity, 003's ranges) use".to_string(),
            " and the report's general-route sections (stability, Campbell diagrams, critical speeds of the rotor as given, design maps) and run-up",
        ),
        _ => (format!("{command} uses"), ""),
    };
    Some(format!(
        "warning: {who} the rotor of papers 000/003 (isotropic supports, one balancer plane of point-mass balls, static unbalance): {} {} used only by `simulate`/`basins`{also}",
        keys.join(", "),
        if keys.len() == 1 { "is" } else { "are" }
    ))
}

/// The one check every command makes on its config after building its model(s): that every
/// entry is used by the `models` `command` runs ([`autobal::config::entry_use`]; the classes in
/// docs/reference/robustness.md, "Every entry is used"). An entry no model of the command has (another
/// rotor's table or key) is an error naming it; entries only the spatial simulation uses (for
/// the linear model) and entries the rest of the config makes moot are one warning line each
/// on standard error; a bare speed in a dimensional config gets its note ([`bare_speed_notes`]).
/// A run on the spatial simulation's rotor that takes something from the 12-state linear model
/// calls [`check_entries_with`] instead, saying what.
pub fn check_entries(root: &Table, command: &str, models: &[Model]) -> Result<()> {
    check_entries_with(root, command, models, FromLinear::Nothing)
}

/// What a run on the spatial simulation's rotor takes from paper 000's 12-state linear model,
/// through which `dimensionless.delta_a` and `d_a` given beside the masses still act there
/// ([`autobal::config::EntryUse::linear_only`]; the rotor's inertia and balls are the masses').
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FromLinear {
    /// Nothing: a map on the general route (its speeds are an axis or `--omega`).
    Nothing,
    /// A run in time (`simulate`, `sweep`, `basins`): where the default run-up ends when the
    /// config has no `[drive]` (1.3 times the linear model's highest critical speed, unless
    /// `analysis.operating_speed` or `analysis.omega_max` says;
    /// [`autobal::config::default_run_up`]).
    RunUp,
    /// The general route's stationary analysis (`stability`, `campbell`, `critical`): its
    /// default speed range, unless `--omega-max` gives it (`omega_max_given`)
    /// ([`crate::general::default_omega_max`]), and for `critical` (`necessary`) paper 003's
    /// necessary ranges printed beside the exact ones
    /// ([`crate::general_campbell::necessary_ranges`]).
    SpeedRange {
        /// `--omega-max` was given: the default range is not used.
        omega_max_given: bool,
        /// The run prints 003's necessary ranges where they are defined.
        necessary: bool,
    },
}

/// [`check_entries`], for a run that takes `from_linear` from the 12-state linear model: its
/// line on the entries that are that model's inputs only says what they set in this run.
pub fn check_entries_with(root: &Table, command: &str, models: &[Model], from_linear: FromLinear) -> Result<()> {
    let u = autobal::config::entry_use(root, models);
    if let Some(first) = u.foreign.first() {
        let runs: Vec<&str> = models.iter().map(|m| m.describe()).collect();
        let also = match &u.foreign[1..] {
            [] => String::new(),
            rest => format!(" (and {})", rest.iter().map(|u| u.key.as_str()).collect::<Vec<_>>().join(", ")),
        };
        bail!("{}: not used by `{command}`, which runs {}: this entry {}; remove it{also}", first.key, runs.join(" and "), first.why);
    }
    if models.contains(&Model::Linear) {
        if let Some(w) = ignored_warning(&u.simulation_only, command) {
            crate::term::note(&w);
        }
    }
    if !u.moot.is_empty() {
        // grouped by reason, in the order of the config
        let mut groups: Vec<(&str, Vec<&str>)> = vec![];
        for m in &u.moot {
            match groups.iter_mut().find(|(why, _)| *why == m.why) {
                Some((_, keys)) => keys.push(&m.key),
                None => groups.push((&m.why, vec![&m.key])),
            }
        }
        let list: Vec<String> = groups.iter().map(|(why, keys)| format!("{} ({why})", keys.join(", "))).collect();
        crate::term::note(&format!(
            "warning: {command}: {} {} no effect with the rest of this config",
            list.join(", "),
            if u.moot.len() == 1 { "has" } else { "have" }
        ));
    }
    if !u.linear_only.is_empty() {
        crate::term::note(&linear_only_warning(root, command, &u.linear_only, from_linear));
    }
    for n in bare_speed_notes(root) {
        crate::term::note(&n);
    }
    Ok(())
}

/// The warning on `keys`, inputs of the 12-state linear model only
/// ([`autobal::config::EntryUse::linear_only`]), on `command`'s run on the spatial simulation's
/// rotor: that rotor's inertia and balls are the masses', and what the keys still set in this
/// run, found by running the defaults of `from_linear` on the config with and without them
/// (the values are printed), or that they set nothing.
pub fn linear_only_warning(root: &Table, command: &str, keys: &[String], from_linear: FromLinear) -> String {
    let mut without = root.clone();
    for k in keys {
        if let Some((table, key)) = k.split_once('.') {
            if let Some(t) = without.get_mut(table).and_then(toml::Value::as_table_mut) {
                t.remove(key);
            }
        }
    }
    let one = keys.len() == 1;
    let them = if one { "it" } else { "them" };
    let num = |w: Option<f64>| w.map_or_else(|| "none".to_string(), autobal::error::fmt_num);
    let mut set = vec![];
    match from_linear {
        FromLinear::Nothing => {}
        FromLinear::RunUp => {
            // the end speed of the default run-up (its acceleration and duration follow from it
            // and the fixed number of revolutions), `None` where the config has its own [drive]
            let end = |t: &Table| autobal::config::spatial_simulation(t).ok().filter(|s| s.default_drive).map(|s| s.drive.kinematics(s.settings.t_end).0);
            let (with, wo) = (end(root), end(&without));
            if with.is_some() && with != wo {
                set.push(format!(
                    "where the default run-up ends (no [drive]; its acceleration and duration follow){}: Ω = {} with {them}, {} without, from the linear model's critical speeds",
                    if command == "sweep" { " on the base config" } else { "" },
                    num(with),
                    num(wo),
                ));
            }
        }
        FromLinear::SpeedRange { omega_max_given, necessary } => {
            if !omega_max_given {
                let top = |t: &Table| crate::general::rotor_of(t).and_then(|g| crate::general::default_omega_max(&g, t)).ok();
                let (with, wo) = (top(root), top(&without));
                if with.is_some() && with != wo {
                    set.push(format!("the default speed range (--omega-max sets it): 0 < Ω ≤ {} with {them}, {} without", num(with), num(wo)));
                }
            }
            if necessary {
                let ranges = |t: &Table| crate::general_campbell::necessary_ranges(t, 1.0).ok().flatten();
                let with = ranges(root);
                if with.is_some() && with != ranges(&without) {
                    set.push("paper 003's necessary ranges printed beside the exact ones (the linear model's)".to_string());
                }
            }
        }
    }
    let (subject, verb) = if one { ("it", "sets") } else { ("they", "set") };
    let run = if command == "sweep" { "these runs" } else { "this run" };
    let effect = if set.is_empty() { format!("{subject} {verb} nothing in {run}") } else { format!("in {run} {subject} {verb} only {}", set.join(", and ")) };
    format!(
        "warning: {command}: {} beside the masses {} of the 12-state linear model only: the spatial simulation's rotor, which {command} runs, has the masses' inertia and balls (m0, r0, m, r, n); {effect}",
        keys.join(", "),
        if one { "is an input" } else { "are inputs" },
    )
}

/// The one check of `sweep`'s and `map`'s axes (`(flag, axis)`, e.g. `("--x", axis)`), on the
/// config `root` the `models` of `command` run, before anything runs: an axis whose key no
/// model of the command reads, or whose key the rest of the config makes moot, would give the
/// same result at every point (a user reads that as a rotor insensitive to the key), so it is
/// refused, naming the axis. Each axis that is a plain config key ([`autobal::config::set_number`]
/// takes it; speeds and derived paths such as `drive.psi0[1]` are left to the commands' own
/// checks) is set, in a copy of `root` with the other axes at their first or last values, to a
/// few of its values and classified by [`autobal::config::entry_use`] (the classes of
/// docs/reference/robustness.md, "Every entry is used") and by `unused`: the command's own
/// keys that no model's build tells apart (`Some(reason)` for a key the command does not use
/// on that config). The axis is taken when one of those configs uses the key; a value at the
/// key's neutral 0 (which [`autobal::config::entry_use`] never reports) decides nothing.
pub fn check_axes(
    root: &Table,
    command: &str,
    models: &[Model],
    axes: &[(&str, &autobal::paths::Axis)],
    unused: &dyn Fn(&Table, &str) -> Option<String>,
) -> Result<()> {
    // the values tried of an axis: at most 8, its ends among them
    fn sample(values: &[f64]) -> Vec<f64> {
        let n = values.len();
        let k = n.min(8);
        (0..k).map(|i| values[if k == 1 { 0 } else { i * (n - 1) / (k - 1) }]).collect()
    }
    let plain: Vec<bool> = axes.iter().map(|(_, a)| autobal::config::set_number(&mut root.clone(), &a.path, 1.0).is_ok()).collect();
    for (i, (flag, ax)) in axes.iter().enumerate() {
        if !plain[i] || ax.values.is_empty() {
            continue;
        }
        let table = ax.path.split('.').next().unwrap_or_default();
        let whole = format!("[{table}]");
        // the other axes at their first or last values (every combination of at most 4 of them)
        let others: Vec<&autobal::paths::Axis> = axes.iter().enumerate().filter(|(j, _)| *j != i && plain[*j]).map(|(_, (_, a))| *a).take(4).collect();
        let mut reason: Option<String> = None;
        let mut used = false;
        'contexts: for combo in 0..(1usize << others.len()) {
            let mut ctx = root.clone();
            for (j, a) in others.iter().enumerate() {
                let v = if combo >> j & 1 == 0 { a.values.first() } else { a.values.last() };
                if let Some(&v) = v {
                    let _ = autobal::config::set_number(&mut ctx, &a.path, v);
                }
            }
            for v in sample(&ax.values) {
                let mut c = ctx.clone();
                if autobal::config::set_number(&mut c, &ax.path, v).is_err() {
                    continue;
                }
                if let Some(why) = unused(&c, &ax.path) {
                    reason.get_or_insert(why);
                    continue;
                }
                let u = autobal::config::entry_use(&c, models);
                let is = |k: &str| k == ax.path || k == whole;
                if let Some(f) = u.foreign.iter().find(|f| is(&f.key)) {
                    let runs: Vec<&str> = models.iter().map(|m| m.describe()).collect();
                    reason.get_or_insert(format!("not used by `{command}`, which runs {}: this entry {}", runs.join(" and "), f.why));
                } else if let Some(m) = u.moot.iter().find(|m| is(&m.key)) {
                    reason.get_or_insert(if m.why == "not used with the rest of this config" {
                        format!("no effect on `{command}` with the rest of this config")
                    } else {
                        format!("no effect on `{command}` with the rest of this config ({})", m.why)
                    });
                } else if models == [Model::Linear] && u.simulation_only.iter().any(|k| is(k)) {
                    reason.get_or_insert(format!("used only by `simulate`/`basins`: `{command}` runs the linear model of papers 000/003, which leaves it out"));
                } else if v != 0.0 {
                    used = true;
                    break 'contexts;
                }
            }
        }
        if let (false, Some(why)) = (used, reason) {
            bail!("{flag} {}: {why}; every point would be the same", ax.path);
        }
    }
    Ok(())
}

/// Why the `[drive]` key `path` (`drive.torque`, …) of the config `c` has no effect: its drive's
/// kind does not use it (`with drive.kind = "schedule"`), or `None`. The builds read every
/// kind's parameters as a menu ([`autobal::config::drive`]: a `--set drive.kind=motor` switches),
/// so [`autobal::config::entry_use`] counts them as used; an axis over one ([`check_axes`]) is
/// still the same run at every point.
pub fn drive_key_unused(c: &Table, path: &str) -> Option<String> {
    let key = path.strip_prefix("drive.")?;
    let d = c.get("drive")?.as_table()?;
    let kind = d.get("kind").and_then(toml::Value::as_str).unwrap_or("acceleration");
    let of = d.get("schedule_of").and_then(toml::Value::as_str).unwrap_or("speed");
    let kinds: &[&str] = match key {
        "b" => &["acceleration"],
        "torque" | "t_off" => &["torque", "motor"],
        "omega_idle" => &["motor"],
        "omega0" => &["speed", "acceleration", "torque", "motor", "schedule"],
        _ => return None,
    };
    let speed_schedule = kind == "schedule" && of == "speed";
    if kinds.contains(&kind) && !(key == "omega0" && speed_schedule) {
        return None;
    }
    Some(match speed_schedule {
        true => format!("with drive.kind = \"{kind}\", schedule_of = \"{of}\""),
        false => format!("with drive.kind = \"{kind}\""),
    })
}

/// The models `command` runs on a simulation config: the spatial simulation for a spatial
/// config ([`autobal::config::is_spatial`]), else the planar rotor.
pub fn simulation_model(root: &Table) -> Model {
    if autobal::config::is_spatial(root) {
        Model::Spatial
    } else {
        Model::Planar
    }
}

/// A note for each speed key of `[analysis]` given as a bare number in a dimensional config: a
/// bare number is the dimensionless `Ω = ω/ω0` ([`autobal::units`]), which a user writing SI may
/// not mean.
pub fn bare_speed_notes(root: &Table) -> Vec<String> {
    let dimensional = is_dimensional(root);
    let an = root.get("analysis").and_then(toml::Value::as_table);
    let mut out = vec![];
    for key in ["omega_max", "operating_speed"] {
        if let Some(v @ (toml::Value::Float(_) | toml::Value::Integer(_))) = an.and_then(|a| a.get(key)).filter(|_| dimensional) {
            out.push(format!(
                "note: analysis.{key} = {v} is the dimensionless Ω = ω/ω0; write a unit for SI, e.g. analysis.{key} = \"1500 rpm\" (or rad/s, Hz)"
            ));
        }
    }
    out
}

/// Whether a spatial config is dimensional (SI: the `[rotor]`, `[supports]`, `[unbalance]`,
/// `[balancer]` tables), where a bare speed is the dimensionless `Ω = ω/ω0`, not rad/s.
pub fn is_dimensional(root: &Table) -> bool {
    ["rotor", "supports", "unbalance", "balancer"].iter().any(|t| root.contains_key(*t))
}

/// Validate a config table and build the model.
pub fn build(root: &Table, source: &str) -> Result<Config> {
    Ok(Config { config: autobal::config::spatial(root)?, source: source.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(sets: &[&str]) -> String {
        let s: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        format!("{:#}", load(None, &s).unwrap_err())
    }

    #[test]
    fn default_loads() {
        let c = load(None, &[]).unwrap();
        assert!((c.model.c_sigma - 0.75).abs() < 1e-15);
    }

    #[test]
    fn errors_name_the_field() {
        assert!(err(&["dimensionless.l_lef=1"]).starts_with("dimensionless.l_lef: unknown key"));
        assert!(err(&["dimensionless.rho_s=0"]).starts_with("dimensionless.rho_s: must lie in [0.001, 1000], got 0"));
        assert!(err(&["dimensionless.m0=-0.1"]).starts_with("dimensionless.m0: must lie in [0, 1), got -0.1"));
        assert!(err(&["dimensionless.c_sigma=nan"]).starts_with("dimensionless.c_sigma: must lie in (0, 2], got NaN"));
        assert!(err(&["dimensionless.c_sigma=\"big\""]).starts_with("dimensionless.c_sigma: expected a number"));
        assert!(err(&["analysis.anisotropy=sideways"]).starts_with("analysis.anisotropy: must be"));
        assert!(err(&["rotor.mass=1"]).starts_with("dimensionless: give either"));
        assert!(err(&["nonsense"]).starts_with("--set nonsense: expected key=value"));
        assert!(err(&["foo.bar=1"]).starts_with("foo: unknown table"));
        assert!(err(&["dimensionless.n=0"]).starts_with("dimensionless.n: is 0 but"));
        assert!(err(&["dimensionless.d_a=0.3"]).starts_with("dimensionless.d_a: with n = 2"));
        assert!(err(&["dimensionless.delta_a=-0.1"]).starts_with("dimensionless.delta_a: must lie in [0, 1), got -0.1"));
    }

    /// The keys of the schema that hold text, not numbers (`analysis.operating_speed`: a speed
    /// with its unit, checked in `Ω` against the range of `analysis.omega_max`).
    const TEXT_KEYS: &[&str] = &[
        "analysis.anisotropy",
        "analysis.operating_speed",
        "drive.kind",
        "drive.schedule_of",
        "integration.method",
        "spatial.lock_tilt",
        "planar.contact",
        "balancer.contact",
        "balancer2.contact",
    ];

    fn schema_keys() -> Vec<String> {
        SCHEMA.iter().flat_map(|(t, ks)| ks.iter().map(move |k| format!("{t}.{k}"))).collect()
    }

    #[test]
    fn every_numeric_key_has_a_limit_and_every_limit_a_key() {
        let keys = schema_keys();
        for k in &keys {
            if !TEXT_KEYS.contains(&k.as_str()) {
                assert!(autobal::limits::limit(k).is_some(), "{k} has no range in autobal::limits");
            }
        }
        for l in autobal::limits::LIMITS {
            assert!(keys.iter().any(|k| k == l.field), "limit for {}, which is no config key", l.field);
        }
    }

    /// Set every key of the schema to hostile values, on the config where it belongs: every
    /// error must name a real key (`table.key:` or a table), a range error the key that was set.
    #[test]
    fn every_validation_error_names_a_real_key() {
        let dimensional = include_str!("../../../examples/dimensional.toml");
        let keys = schema_keys();
        let tables: Vec<&str> = SCHEMA.iter().map(|(t, _)| *t).collect();
        let hostile = [
            "1e308",
            "-1e308",
            "nan",
            "inf",
            "-inf",
            "0",
            "-1",
            "1e-308",
            "-1e-308",
            "0.5",
            "1",
            "2",
            "3",
            "1000",
            "100000",
            "9223372036854775807",
            "-9223372036854775808",
            "\"x\"",
            "true",
            "[1, 2]",
            "[[0, 1], [1, 1e308]]",
            "{a = 1}",
        ];
        let mut errors = 0;
        for key in &keys {
            let table = key.split('.').next().unwrap();
            for v in hostile {
                let set = vec![format!("{key}={v}")];
                let r = match table {
                    "rotor" | "supports" | "unbalance" | "balancer" => {
                        let mut root: Table = dimensional.parse().unwrap();
                        apply_set(&mut root, &set[0]).and_then(|_| build(&root, "test").map(|_| ()))
                    }
                    "planar" | "drive" | "integration" => load_planar(None, &set).map(|_| ()),
                    _ => load(None, &set).map(|_| ()),
                };
                let Err(e) = r else { continue };
                errors += 1;
                let msg = format!("{e:#}");
                let named = msg.split(':').next().unwrap();
                assert!(keys.iter().any(|k| k == named) || tables.contains(&named), "{key}={v}: `{msg}` names no config key");
                if msg.contains("must lie in") {
                    assert_eq!(named, key, "{key}={v}: `{msg}`");
                }
                assert!(!msg.contains('\n') && msg.len() < 400, "{key}={v}: `{msg}`");
            }
        }
        assert!(errors > 500, "{errors}");
    }

    #[test]
    fn config_files_are_read_with_a_size_limit() {
        let dir = std::env::temp_dir().join(format!("autobal-config-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let big = dir.join("big.toml");
        std::fs::write(&big, "#".repeat(MAX_CONFIG_BYTES as usize + 1)).unwrap();
        let e = format!("{:#}", load(Some(&big), &[]).unwrap_err());
        assert!(e.contains("exceeds the limit of 1048576"), "{e}");
        let e = format!("{:#}", load(Some(&dir), &[]).unwrap_err());
        assert!(e.contains("is a directory"), "{e}");
        std::fs::write(&big, [0xff, 0xfe, 0x00]).unwrap();
        let e = format!("{:#}", load(Some(&big), &[]).unwrap_err());
        assert!(e.contains("not UTF-8"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn delta_a_overrides_the_masses() {
        // 003's worked example on the default config: delta_a serves as ΔĀ and ΔĀ0, the masses
        // still describe the balls
        let c = load(None, &["dimensionless.delta_a=0.1".into()]).unwrap();
        assert_eq!(c.model.anisotropy.used, 0.1);
        assert_eq!(c.model.delta_a0, 0.1);
        assert!(c.model.balls.is_some());
        assert!(c.model.anisotropy.warnings.iter().any(|w| w.contains("overrides")));
        let ks: Vec<f64> = autobal::spatial::critical_speeds::critical_speeds(&c.model).speeds.iter().map(|s| s.omega).collect();
        assert!((ks[3] - 3.80).abs() < 0.005, "{ks:?}");
    }

    #[test]
    fn set_overrides_and_types() {
        let c = load(None, &["dimensionless.l_left=1.2".into(), "dimensionless.c_sigma=1".into()]).unwrap();
        assert_eq!(c.model.l_left, Some(1.2));
        assert_eq!(c.model.c_sigma, 1.0);
    }
}

/// A loaded planar-rotor simulation (paper 004).
#[derive(Debug, Clone)]
pub struct PlanarConfig {
    pub rotor: autobal::planar::PlanarRotor,
    pub drive: autobal::planar::Drive,
    pub settings: autobal::planar::Settings,
    pub source: String,
}

/// Load a planar config (embedded default: examples/planar.toml) with overrides.
pub fn load_planar(path: Option<&std::path::Path>, sets: &[String]) -> Result<PlanarConfig> {
    let (root, source) = read_planar_set(path, sets)?;
    build_planar(&root, &source)
}

/// Read a planar config (embedded default: examples/planar.toml) and apply the overrides.
pub fn read_planar_set(path: Option<&std::path::Path>, sets: &[String]) -> Result<(Table, String)> {
    check_repeated_sets(sets)?;
    let (mut root, source) = read_with_default(path, DEFAULT_PLANAR, "embedded default (examples/planar.toml)")?;
    for s in sets {
        apply_set(&mut root, s)?;
    }
    Ok((root, source))
}

/// Validate a planar config table.
pub fn build_planar(root: &Table, source: &str) -> Result<PlanarConfig> {
    let p = autobal::config::planar(root)?;
    Ok(PlanarConfig { rotor: p.rotor, drive: p.drive, settings: p.settings, source: source.to_string() })
}
