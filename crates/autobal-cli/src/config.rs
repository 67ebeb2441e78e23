//! Config files: TOML in a dimensional (SI) or a dimensionless form, `--set` overrides, and
//! validation with errors that name the field.

use anyhow::{anyhow, bail, Result};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel, SpatialRotorSi};
use autobal::spatial::paths::{SpatialInput, SpatialSpec};
use toml::{Table, Value};

/// The embedded default example (paper 000's base case).
pub const DEFAULT_CONFIG: &str = include_str!("../../../examples/default.toml");

/// Every table and key the config understands.
pub(crate) const SCHEMA: &[(&str, &[&str])] = &[
    ("rotor", &["mass", "equatorial_moment", "polar_moment", "z", "axis_tilt", "axis_tilt_angle"]),
    (
        "supports",
        &[
            "z_left", "z_right", "stiffness_left", "stiffness_right", "damping_left", "damping_right",
            "stiffness_left_y", "stiffness_right_y", "damping_left_y", "damping_right_y",
        ],
    ),
    ("unbalance", &["mass", "radius", "angle"]),
    ("balancer", &["z", "balls", "ball_mass", "race_radius", "drag", "ball_diameter", "contact", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"]),
    // spatial simulation only (docs/spatial.md, examples/spatial_two_plane.toml)
    ("couple", &["mass", "radius", "angle", "z"]),
    ("balancer2", &["z", "balls", "ball_mass", "race_radius", "drag", "ball_diameter", "contact", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"]),
    ("spatial", &["gravity", "lock_tilt", "spin_drag"]),
    ("initial", &["position", "velocity", "tilt", "tilt_rate"]),
    (
        "dimensionless",
        &["c_sigma", "rho_s", "l_left", "z_a", "delta_a", "m0", "r0", "m", "r", "n", "d_a", "h_x", "h_s"],
    ),
    ("analysis", &["anisotropy", "sensitivity_limit", "omega_max"]),
    (
        "planar",
        &[
            "m1", "m2", "m3", "n", "s1", "s2", "gamma", "r", "k", "c", "c_psi", "c_theta", "i_g", "ball_diameter", "contact", "restitution", "contact_stiffness",
            "rolling_resistance", "slip_rate",
        ],
    ),
    (
        "drive",
        &["kind", "omega0", "b", "torque", "omega_idle", "t_off", "t_end", "psi0", "psi_rate0", "xy0", "xy_rate0", "schedule", "schedule_of"],
    ),
    ("integration", &["method", "rtol", "atol", "dt", "max_steps", "max_wall_s"]),
];

/// Real balls of one ball set (`[planar]`, `[balancer]`, `[balancer2]`): `ball_diameter`,
/// `contact`, `restitution`, `contact_stiffness`, `rolling_resistance`, `slip_rate`
/// ([`autobal::balls::BallPhysics`]; absent keys: its defaults, the papers' point masses).
pub fn ball_physics_of(sec: &Section) -> Result<autobal::balls::BallPhysics> {
    let d = autobal::balls::BallPhysics::default();
    Ok(autobal::balls::BallPhysics {
        diameter: sec.f64("ball_diameter")?,
        contact: sec.boolean("contact")?.unwrap_or(d.contact),
        restitution: sec.f64("restitution")?.unwrap_or(d.restitution),
        contact_stiffness: sec.f64("contact_stiffness")?,
        rolling_resistance: sec.f64("rolling_resistance")?.unwrap_or(d.rolling_resistance),
        slip_rate: sec.f64("slip_rate")?.unwrap_or(d.slip_rate),
    })
}

/// The embedded default of `simulate` and `sweep` (paper 004's rotor).
pub const DEFAULT_PLANAR: &str = include_str!("../../../examples/planar.toml");

/// Analysis settings from the `[analysis]` table.
#[derive(Debug, Clone)]
pub struct Analysis {
    pub sensitivity_limit: f64,
    /// Upper end of speed axes in plots (dimensionless); default from the critical speeds.
    pub omega_max: Option<f64>,
}

/// A loaded, validated config.
#[derive(Debug, Clone)]
pub struct Config {
    pub model: SpatialModel,
    /// What the model was built from: parameter paths act on it (maps).
    pub spec: SpatialSpec,
    pub analysis: Analysis,
    /// Where it came from, for the report.
    pub source: String,
    /// The merged TOML text, for the report.
    pub text: String,
    pub dimensional: bool,
}

impl Config {
    /// The SI rotor of a dimensional config (the spatial simulation's input).
    pub fn si(&self) -> Option<&SpatialRotorSi> {
        match &self.spec.input {
            SpatialInput::Si { rotor, .. } => Some(rotor),
            SpatialInput::Dimensionless(_) => None,
        }
    }
}

/// Parse a `--set key=value` value as TOML (number, bool, array, quoted string), falling back
/// to a bare string.
fn parse_value(raw: &str) -> Value {
    match format!("v = {raw}").parse::<Table>() {
        Ok(mut t) => t.remove("v").unwrap_or(Value::String(raw.to_string())),
        // a whole number beyond i64 (TOML's integers) is still a number
        Err(_) => raw.parse::<f64>().map(Value::Float).unwrap_or_else(|_| Value::String(raw.to_string())),
    }
}

/// Apply one `key=value` override with a dotted key.
pub fn apply_set(root: &mut Table, assignment: &str) -> Result<()> {
    let (key, value) = assignment
        .split_once('=')
        .ok_or_else(|| anyhow!("--set {assignment}: expected key=value, e.g. --set dimensionless.l_left=1.2"))?;
    let key = key.trim();
    let parts: Vec<&str> = key.split('.').collect();
    if parts.len() != 2 || parts.iter().any(|p| p.is_empty()) {
        bail!("--set {key}: expected a dotted key table.field, e.g. dimensionless.l_left");
    }
    check_key(parts[0], Some(parts[1]))?;
    let table = root
        .entry(parts[0].to_string())
        .or_insert_with(|| Value::Table(Table::new()))
        .as_table_mut()
        .ok_or_else(|| anyhow!("--set {key}: `{}` is not a table", parts[0]))?;
    table.insert(parts[1].to_string(), parse_value(value.trim()));
    Ok(())
}

/// Every table and key of `root` must be in [`SCHEMA`], and every number in its range
/// ([`autobal::limits`]): one place for the ranges of all commands.
fn check_schema(root: &Table) -> Result<()> {
    for (name, value) in root {
        check_key(name, None)?;
        let t = value.as_table().ok_or_else(|| anyhow!("{name}: expected a table [{name}]"))?;
        for (k, v) in t {
            check_key(name, Some(k))?;
            check_range(&format!("{name}.{k}"), v)?;
        }
    }
    Ok(())
}

/// The keys read as whole numbers (numbers of balls).
const COUNTS: &[&str] = &["balancer.balls", "dimensionless.n", "planar.n"];

/// Numbers (and the numbers in arrays, one level of nesting for `drive.schedule`) against their
/// limits; counts are checked where they are read, as whole numbers.
fn check_range(field: &str, v: &Value) -> Result<()> {
    let is_count = COUNTS.contains(&field);
    match v {
        Value::Float(_) | Value::Integer(_) if !is_count => {
            autobal::limits::check(field, number(v, field)?)?;
        }
        Value::Array(a) => {
            if a.len() > MAX_ARRAY_LEN {
                return Err(autobal::Error::TooLarge { what: field.into(), size: a.len() as u64, limit: MAX_ARRAY_LEN as u64, reason: "entries".into() }.into());
            }
            for x in a {
                match x {
                    Value::Array(inner) => {
                        for y in inner {
                            if let Value::Float(_) | Value::Integer(_) = y {
                                autobal::limits::check(field, number(y, field)?)?;
                            }
                        }
                    }
                    Value::Float(_) | Value::Integer(_) => {
                        autobal::limits::check(field, number(x, field)?)?;
                    }
                    _ => {}
                }
            }
        }
        _ => {}
    }
    Ok(())
}

fn check_key(table: &str, key: Option<&str>) -> Result<()> {
    let Some((_, keys)) = SCHEMA.iter().find(|(t, _)| *t == table) else {
        let known: Vec<&str> = SCHEMA.iter().map(|(t, _)| *t).collect();
        bail!("{table}: unknown table (known tables: {})", known.join(", "));
    };
    if let Some(k) = key {
        if !keys.contains(&k) {
            bail!("{table}.{k}: unknown key (known keys of [{table}]: {})", keys.join(", "));
        }
    }
    Ok(())
}

pub(crate) struct Section<'a> {
    pub(crate) name: &'static str,
    pub(crate) table: Option<&'a Table>,
}

/// A TOML number (integer or float) as `f64`; `field` names it in the error.
pub(crate) fn number(v: &Value, field: &str) -> Result<f64> {
    match v {
        Value::Float(f) => Ok(*f),
        Value::Integer(i) => Ok(*i as f64),
        o => bail!("{field}: expected a number, got {}", describe(o)),
    }
}

impl<'a> Section<'a> {
    pub(crate) fn get(&self, key: &str) -> Option<&'a Value> {
        self.table.and_then(|t| t.get(key))
    }
    pub(crate) fn f64(&self, key: &str) -> Result<Option<f64>> {
        self.get(key).map(|v| number(v, &format!("{}.{key}", self.name))).transpose()
    }
    pub(crate) fn req(&self, key: &str) -> Result<f64> {
        self.f64(key)?.ok_or_else(|| anyhow!("{}.{key}: missing (required)", self.name))
    }
    pub(crate) fn count(&self, key: &str) -> Result<Option<u32>> {
        let field = format!("{}.{key}", self.name);
        match self.get(key) {
            None => Ok(None),
            Some(Value::Integer(i)) if *i < 0 => bail!("{field}: must be a whole number ≥ 0, got {i}"),
            Some(Value::Integer(i)) => {
                autobal::limits::check_count(&field, *i as u64)?;
                u32::try_from(*i).map(Some).map_err(|_| anyhow!("{field}: {i} is too large"))
            }
            Some(v) => bail!("{field}: expected a whole number, got {}", describe(v)),
        }
    }
    pub(crate) fn boolean(&self, key: &str) -> Result<Option<bool>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(v) => bail!("{}.{key}: expected true or false, got {}", self.name, describe(v)),
        }
    }
    pub(crate) fn string(&self, key: &str) -> Result<Option<&'a str>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s)),
            Some(v) => bail!("{}.{key}: expected a string, got {}", self.name, describe(v)),
        }
    }
}

fn describe(v: &Value) -> String {
    match v {
        Value::Float(f) => autobal::error::fmt_num(*f),
        Value::String(s) => format!("the string \"{}\"", s.chars().take(40).collect::<String>()),
        Value::Table(_) => "a table".into(),
        Value::Array(_) => "an array".into(),
        other => other.to_string(),
    }
}

/// Read and parse the config text (or the embedded default) into a TOML table.
pub fn read(path: Option<&std::path::Path>) -> Result<(Table, String)> {
    read_with_default(path, DEFAULT_CONFIG, "embedded default (examples/default.toml)")
}

/// Largest config file read (bytes): a config is a few dozen lines; this bounds the memory and
/// time a wrong path (`/dev/zero`, a log file) can cost.
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Longest array in a config (`drive.schedule` points).
pub const MAX_ARRAY_LEN: usize = 100_000;

/// Read at most [`MAX_CONFIG_BYTES`] of a config file as UTF-8.
fn read_limited(p: &std::path::Path) -> Result<String> {
    use std::io::Read;
    let name = format!("--config {}", p.display());
    let file = std::fs::File::open(p).map_err(|e| anyhow!("{name}: cannot read: {e}"))?;
    if file.metadata().map(|m| m.is_dir()).unwrap_or(false) {
        bail!("{name}: is a directory, not a config file");
    }
    let mut bytes = Vec::new();
    file.take(MAX_CONFIG_BYTES + 1).read_to_end(&mut bytes).map_err(|e| anyhow!("{name}: cannot read: {e}"))?;
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
    let root = parse_text(&text, &source)?;
    Ok((root, source))
}

/// Parse config text into a TOML table; errors say `SOURCE: line N: …` on one line.
pub fn parse_text(text: &str, source: &str) -> Result<Table> {
    text.parse::<Table>().map_err(|e| {
        let msg = e.message().replace('\n', " ");
        let line = e.span().map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        match line {
            Some(l) => anyhow!("{source}: line {l}: {msg}"),
            None => anyhow!("{source}: {msg}"),
        }
    })
}

/// Load the config text (or the embedded default), apply overrides, validate, build the model.
pub fn load(path: Option<&std::path::Path>, sets: &[String]) -> Result<Config> {
    let (mut root, source) = read(path)?;
    for s in sets {
        apply_set(&mut root, s)?;
    }
    build(&root, &source)
}

/// Validate a config table and build the model.
pub fn build(root: &Table, source: &str) -> Result<Config> {
    let source = source.to_string();
    let text = String::new();
    check_schema(root)?;
    let sec = |name: &'static str| Section { name, table: root.get(name).and_then(Value::as_table) };
    let an = sec("analysis");
    let method = match an.string("anisotropy")? {
        None | Some("exact") => AnisotropyMethod::Exact,
        Some("paper") => AnisotropyMethod::Paper,
        Some(o) => bail!("analysis.anisotropy: must be \"exact\" or \"paper\", got \"{o}\""),
    };
    let sensitivity_limit = an.f64("sensitivity_limit")?.unwrap_or(autobal::spatial::sensitivity::DEFAULT_LIMIT);
    autobal::limits::check("analysis.sensitivity_limit", sensitivity_limit)?;
    let omega_max = an.f64("omega_max")?;
    let dimensional_tables = ["rotor", "supports", "unbalance", "balancer"];
    if !dimensional_tables.iter().any(|t| root.contains_key(*t)) && !root.contains_key("dimensionless") && root.contains_key("planar") {
        bail!("config: this is a planar-rotor config ([planar], [drive]): use it with `autobal simulate` or `autobal sweep`");
    }
    let has_dim = dimensional_tables.iter().any(|t| root.contains_key(*t));
    let has_nondim = root.contains_key("dimensionless");
    let spec = match (has_dim, has_nondim) {
        (true, true) => bail!(
            "dimensionless: give either the dimensional tables [rotor], [supports], [unbalance], [balancer] or [dimensionless], not both"
        ),
        (false, false) => bail!("config: no model: give [dimensionless] or the dimensional tables [rotor] and [supports]"),
        (true, false) => {
            let (r, s, u, b) = (sec("rotor"), sec("supports"), sec("unbalance"), sec("balancer"));
            let si = SpatialRotorSi {
                rotor_mass: r.req("mass")?,
                equatorial_moment: r.req("equatorial_moment")?,
                polar_moment: r.req("polar_moment")?,
                z_rotor: r.req("z")?,
                // plane A carries balls and unbalance: required when either is described
                z_balancer: match b.f64("z")? {
                    Some(z) => z,
                    None if b.table.is_some() || u.table.is_some() => bail!("balancer.z: missing (required: the plane of balls and unbalance)"),
                    None => 0.0,
                },
                z_left: s.req("z_left")?,
                z_right: s.req("z_right")?,
                stiffness_left: s.req("stiffness_left")?,
                stiffness_right: s.req("stiffness_right")?,
                damping_left: s.f64("damping_left")?.unwrap_or(0.0),
                damping_right: s.f64("damping_right")?.unwrap_or(0.0),
                unbalance_mass: u.f64("mass")?.unwrap_or(0.0),
                unbalance_radius: u.f64("radius")?.unwrap_or(0.0),
                balls: b.count("balls")?.unwrap_or(0),
                ball_mass: b.f64("ball_mass")?.unwrap_or(0.0),
                race_radius: b.f64("race_radius")?.unwrap_or(0.0),
                ball_drag: b.f64("drag")?.unwrap_or(0.0),
            };
            SpatialSpec { input: SpatialInput::Si { rotor: si, method }, delta_a_override: None }
        }
        (false, true) => {
            let d = sec("dimensionless");
            let direct = d.f64("delta_a")?;
            let any_mass = ["m0", "r0", "r"].iter().any(|k| d.get(k).is_some());
            let mut direct_balls = None;
            // delta_a beside the masses: the masses describe the balls (linear model) and delta_a,
            // given directly, overrides the anisotropy they imply (as ΔĀ and ΔĀ0, like 003's
            // worked examples), so that `--set dimensionless.delta_a=…` works on any config
            let override_delta = if any_mass { direct } else { None };
            if let (Some(v), Some(cs)) = (override_delta, d.f64("c_sigma")?) {
                autobal::spatial::params::check_delta_a(v, cs)?;
            }
            let anisotropy = match (direct, any_mass) {
                (Some(v), false) => {
                    match (d.f64("m")?, d.f64("d_a")?) {
                        (Some(m), Some(da)) => direct_balls = Some((m, da)),
                        (None, None) => {}
                        (Some(_), None) => bail!("dimensionless.d_a: required with delta_a and m (D_A of the balls for the linear model)"),
                        (None, Some(_)) => bail!("dimensionless.m: required with delta_a and d_a (the balls' mass fraction for the linear model)"),
                    }
                    AnisotropyInput::Direct(v)
                }
                (_, true) => AnisotropyInput::Masses {
                    masses: MassSet {
                        m0: d.req("m0")?,
                        r0: d.req("r0")?,
                        m: d.f64("m")?.unwrap_or(0.0),
                        r: d.f64("r")?.unwrap_or(0.0),
                        n: d.count("n")?.unwrap_or(0),
                    },
                    d_a: d.f64("d_a")?,
                },
                (None, false) => AnisotropyInput::Direct(0.0),
            };
            SpatialSpec {
                input: SpatialInput::Dimensionless(DimensionlessInput {
                    c_sigma: d.req("c_sigma")?,
                    rho_s: d.req("rho_s")?,
                    l_left: d.req("l_left")?,
                    z_a: d.f64("z_a")?.unwrap_or(0.0),
                    anisotropy,
                    h_x: d.f64("h_x")?.unwrap_or(0.0),
                    h_s: d.f64("h_s")?.unwrap_or(0.0),
                    method,
                    direct_balls,
                }),
                delta_a_override: override_delta,
            }
        }
    };
    let model = spec.build()?;
    Ok(Config {
        model,
        spec,
        analysis: Analysis { sensitivity_limit, omega_max },
        source,
        text: toml::to_string(root).unwrap_or(text),
        dimensional: has_dim,
    })
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

    /// The keys of the schema that hold text, not numbers.
    const TEXT_KEYS: &[&str] = &["analysis.anisotropy", "drive.kind", "drive.schedule_of", "integration.method", "spatial.lock_tilt", "planar.contact", "balancer.contact", "balancer2.contact"];

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
            "1e308", "-1e308", "nan", "inf", "-inf", "0", "-1", "1e-308", "-1e-308", "0.5", "1", "2", "3", "1000", "100000",
            "9223372036854775807", "-9223372036854775808", "\"x\"", "true", "[1, 2]", "[[0, 1], [1, 1e308]]", "{a = 1}",
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

pub(crate) fn array_f64(sec: &Section, key: &str) -> Result<Option<Vec<f64>>> {
    match sec.get(key) {
        None => Ok(None),
        Some(Value::Array(a)) => a.iter().map(|v| number(v, &format!("{}.{key}", sec.name))).collect::<Result<Vec<_>>>().map(Some),
        Some(v) => bail!("{}.{key}: expected an array of numbers, got {}", sec.name, describe(v)),
    }
}

/// Load a planar config (embedded default: examples/planar.toml) with overrides.
pub fn load_planar(path: Option<&std::path::Path>, sets: &[String]) -> Result<PlanarConfig> {
    let (mut root, source) = read_with_default(path, DEFAULT_PLANAR, "embedded default (examples/planar.toml)")?;
    for s in sets {
        apply_set(&mut root, s)?;
    }
    build_planar(&root, &source)
}

/// Validate a planar config table.
pub fn build_planar(root: &Table, source: &str) -> Result<PlanarConfig> {
    use autobal::planar::{PlanarRotor, Settings};
    check_schema(root)?;
    if !root.contains_key("planar") {
        bail!("planar: missing: `simulate` needs a [planar] table (see examples/planar.toml)");
    }
    let sec = |name: &'static str| Section { name, table: root.get(name).and_then(Value::as_table) };
    let (p, d, ig) = (sec("planar"), sec("drive"), sec("integration"));
    let rotor = PlanarRotor {
        m1: p.req("m1")?,
        m2: p.f64("m2")?.unwrap_or(0.0),
        m3: p.f64("m3")?.unwrap_or(0.0),
        n: p.count("n")?.unwrap_or(0) as usize,
        s1: p.req("s1")?,
        s2: p.f64("s2")?.unwrap_or(0.0),
        gamma: p.f64("gamma")?.unwrap_or(0.0),
        r: p.f64("r")?.unwrap_or(0.0),
        k: p.req("k")?,
        c: p.f64("c")?.unwrap_or(0.0),
        c_psi: p.f64("c_psi")?.unwrap_or(0.0),
        c_theta: p.f64("c_theta")?.unwrap_or(0.0),
        i_g: p.req("i_g")?,
        balls: ball_physics_of(&p)?,
    };
    rotor.validate()?;
    let (drive, t_end) = drive_of(&d)?;
    let ig = integration_of(&ig, t_end)?;
    let pair = |key: &str| -> Result<[f64; 2]> {
        match array_f64(&d, key)? {
            None => Ok([0.0; 2]),
            Some(v) if v.len() == 2 => Ok([v[0], v[1]]),
            Some(v) => bail!("drive.{key}: needs 2 numbers [X, Y], got {}", v.len()),
        }
    };
    let defaults = Settings::new(&rotor, t_end);
    let settings = Settings {
        method: ig.method,
        t_end,
        dt: ig.dt,
        rtol: ig.rtol,
        atol: ig.atol,
        psi0: array_f64(&d, "psi0")?.unwrap_or_else(|| Settings::default_psi0(rotor.n)),
        psi_rate0: array_f64(&d, "psi_rate0")?.unwrap_or_else(|| vec![0.0; rotor.n]),
        xy0: pair("xy0")?,
        xy_rate0: pair("xy_rate0")?,
        max_steps: ig.max_steps.unwrap_or(defaults.max_steps),
        max_wall_s: ig.max_wall_s,
    };
    settings.validate(&rotor)?;
    Ok(PlanarConfig { rotor, drive, settings, source: source.to_string() })
}

/// `[drive]`: the drive (shared by the planar and the spatial simulation) and `t_end`.
pub(crate) fn drive_of(d: &Section) -> Result<(autobal::drive::Drive, f64)> {
    use autobal::drive::Drive;
    let omega0 = d.f64("omega0")?.unwrap_or(0.0);
    let t_off = d.f64("t_off")?;
    let kind = d.string("kind")?.unwrap_or("acceleration");
    let need = |key: &str| d.f64(key)?.ok_or_else(|| anyhow!("drive.{key}: required for kind = \"{kind}\""));
    let schedule = || -> Result<Vec<(f64, f64)>> {
        match d.get("schedule") {
            Some(Value::Array(rows)) => rows
                .iter()
                .map(|r| match r {
                    Value::Array(pair) if pair.len() == 2 => Ok((number(&pair[0], "drive.schedule")?, number(&pair[1], "drive.schedule")?)),
                    _ => Err(anyhow!("drive.schedule: each entry must be a [t, value] pair")),
                })
                .collect(),
            Some(v) => bail!("drive.schedule: expected an array of [t, value] pairs, got {}", describe(v)),
            None => bail!("drive.schedule: required for kind = \"schedule\""),
        }
    };
    let drive = match kind {
        "speed" => Drive::Speed { omega0 },
        "acceleration" => Drive::Acceleration { omega0, b: need("b")? },
        "torque" => Drive::Torque { omega0, torque: need("torque")?, t_off },
        "motor" => Drive::Motor { omega0, torque: need("torque")?, omega_idle: need("omega_idle")?, t_off },
        "schedule" => match d.string("schedule_of")?.unwrap_or("speed") {
            "speed" => Drive::SpeedSchedule { points: schedule()? },
            "torque" => Drive::TorqueSchedule { omega0, points: schedule()? },
            o => bail!("drive.schedule_of: must be \"speed\" or \"torque\", got \"{o}\""),
        },
        o => bail!("drive.kind: must be one of \"speed\", \"acceleration\", \"torque\", \"motor\", \"schedule\", got \"{o}\""),
    };
    drive.validate()?;
    let t_end = d.f64("t_end")?.unwrap_or(10.0);
    Ok((drive, t_end))
}

/// The `[integration]` table, shared by the planar and the spatial simulation.
pub(crate) struct Integration {
    pub(crate) method: autobal::planar::Method,
    /// Output interval (default `t_end/2000`).
    pub(crate) dt: f64,
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
    /// Step budget (`None`: the model's default).
    pub(crate) max_steps: Option<u64>,
    /// Wall-clock budget in seconds.
    pub(crate) max_wall_s: Option<f64>,
}

/// `[integration]`: method, output interval, tolerances, budgets.
pub(crate) fn integration_of(ig: &Section, t_end: f64) -> Result<Integration> {
    let method = match ig.string("method")? {
        None | Some("auto") => autobal::planar::Method::Auto,
        Some("dop853") => autobal::planar::Method::Dop853,
        Some("rodas") | Some("rosenbrock") => autobal::planar::Method::Rodas,
        Some(o) => bail!("integration.method: must be \"auto\", \"dop853\" or \"rodas\", got \"{o}\""),
    };
    let max_steps = match ig.f64("max_steps")? {
        None => None,
        Some(v) if (1.0..=1e15).contains(&v) && v.fract() == 0.0 => Some(v as u64),
        Some(v) => bail!("integration.max_steps: must be a whole number from 1 to 1e15, got {v}"),
    };
    Ok(Integration {
        method,
        dt: ig.f64("dt")?.unwrap_or(t_end / 2000.0),
        rtol: ig.f64("rtol")?.unwrap_or(1e-8),
        atol: ig.f64("atol")?.unwrap_or(1e-9),
        max_steps,
        max_wall_s: ig.f64("max_wall_s")?,
    })
}
