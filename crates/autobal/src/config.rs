//! Configs: the raw tables a user writes (TOML text, or the same tables from a front end: a
//! Python dict, keyword arguments) converted into validated descriptions: the spatial model of
//! papers 000/003 ([`spatial`]) and the planar simulation of paper 004 ([`planar`]).
//!
//! Every table and key is checked against one [`SCHEMA`], every number against its range
//! ([`crate::limits`]); every error names the key as the config spells it (`planar.m3`,
//! `dimensionless.delta_a`). The front ends only read files and parse `--set` text; the
//! interpretation (defaults, required keys, which keys go together, the `delta_a` override)
//! lives here, once.
//!
//! ```
//! use autobal::config;
//! let mut root = config::parse(config::DEFAULT_SPATIAL, "default").unwrap();
//! config::set(&mut root, "dimensionless.delta_a", config::parse_value("0.1")).unwrap();
//! let c = config::spatial(&root).unwrap();
//! assert_eq!(c.model.anisotropy.used, 0.1); // 003's worked example on 000's base case
//! let e = config::set(&mut root, "dimensionless.l_lef", 1.0.into()).unwrap_err();
//! assert!(e.to_string().starts_with("dimensionless.l_lef: unknown key"));
//! ```

use crate::error::{Error, Result};
use crate::planar::problem::PlanarProblem;
use crate::planar::{Drive, Method, PlanarRotor, Settings};
use crate::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
use crate::spatial::inertia::AnisotropyMethod;
use crate::spatial::params::{check_delta_a, AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
use crate::spatial::paths::{SpatialInput, SpatialSpec};
pub use toml::{Table, Value};

/// Paper 000's base case, the default config of the spatial model (`examples/default.toml`).
pub const DEFAULT_SPATIAL: &str = include_str!("../../../examples/default.toml");

/// Paper 004's passage, the default config of the planar simulation (`examples/planar.toml`).
pub const DEFAULT_PLANAR: &str = include_str!("../../../examples/planar.toml");

/// Every table and key a config may have.
pub const SCHEMA: &[(&str, &[&str])] = &[
    ("rotor", &["mass", "equatorial_moment", "polar_moment", "z", "axis_tilt", "axis_tilt_angle"]),
    (
        "supports",
        &[
            "z_left",
            "z_right",
            "stiffness_left",
            "stiffness_right",
            "damping_left",
            "damping_right",
            "stiffness_left_y",
            "stiffness_right_y",
            "damping_left_y",
            "damping_right_y",
        ],
    ),
    ("unbalance", &["mass", "radius", "angle"]),
    (
        "balancer",
        &["z", "balls", "ball_mass", "race_radius", "drag", "ball_diameter", "contact", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"],
    ),
    // spatial simulation only (docs/notes/spatial.md, examples/spatial_two_plane.toml)
    ("couple", &["mass", "radius", "angle", "z"]),
    (
        "balancer2",
        &["z", "balls", "ball_mass", "race_radius", "drag", "ball_diameter", "contact", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"],
    ),
    ("spatial", &["gravity", "lock_tilt", "spin_drag"]),
    ("initial", &["position", "velocity", "tilt", "tilt_rate"]),
    ("dimensionless", &["c_sigma", "rho_s", "l_left", "z_a", "delta_a", "m0", "r0", "m", "r", "n", "d_a", "h_x", "h_s"]),
    ("analysis", &["anisotropy", "sensitivity_limit", "omega_max", "operating_speed"]),
    (
        "planar",
        &[
            "m1",
            "m2",
            "m3",
            "n",
            "s1",
            "s2",
            "gamma",
            "r",
            "k",
            "c",
            "k_x",
            "k_y",
            "c_x",
            "c_y",
            "c_psi",
            "ball_masses",
            "ball_drags",
            "c_theta",
            "i_g",
            "ball_diameter",
            "contact",
            "restitution",
            "contact_stiffness",
            "rolling_resistance",
            "slip_rate",
        ],
    ),
    ("drive", &["kind", "omega0", "b", "torque", "omega_idle", "t_off", "t_end", "psi0", "psi_rate0", "xy0", "xy_rate0", "schedule", "schedule_of"]),
    ("integration", &["method", "rtol", "atol", "dt", "max_steps", "max_wall_s"]),
];

/// The keys read as whole numbers (numbers of balls).
const COUNTS: &[&str] = &["balancer.balls", "balancer2.balls", "dimensionless.n", "planar.n"];

/// Longest array in a config (`drive.schedule` points).
pub const MAX_ARRAY_LEN: usize = 100_000;

/// Parse config text; errors name `source` and the line.
pub fn parse(text: &str, source: &str) -> Result<Table> {
    text.parse::<Table>().map_err(|e| {
        let msg = e.message().replace('\n', " ");
        match e.span().map(|s| text[..s.start.min(text.len())].lines().count().max(1)) {
            Some(l) => Error::invalid(source, format!("line {l}: {msg}")),
            None => Error::invalid(source, msg),
        }
    })
}

/// A value as typed after `--set key=`: TOML (number, bool, array, quoted string), else the
/// bare text as a string.
pub fn parse_value(raw: &str) -> Value {
    match format!("v = {raw}").parse::<Table>() {
        Ok(mut t) => t.remove("v").unwrap_or_else(|| Value::String(raw.to_string())),
        // a whole number beyond i64 (TOML's integers) is still a number
        Err(_) => raw.parse::<f64>().map(Value::Float).unwrap_or_else(|_| Value::String(raw.to_string())),
    }
}

/// Set `table.key` (a key of [`SCHEMA`]) to `value`, creating the table if needed.
pub fn set(root: &mut Table, key: &str, value: Value) -> Result<()> {
    let (t, k) = split_key(key)?;
    let table = root
        .entry(t.to_string())
        .or_insert_with(|| Value::Table(Table::new()))
        .as_table_mut()
        .ok_or_else(|| Error::invalid(key, format!("`{t}` is not a table")))?;
    table.insert(k.to_string(), value);
    Ok(())
}

/// Set element `j` (0-based) of the array `table.key` to `value`: `path` is the indexed form
/// as given (`drive.psi0[2]`: 1-based, [`crate::paths::indexed`]) and names the errors. The key
/// must be one of [`SCHEMA`] and an array in `root` already (a default that the config leaves
/// out, such as balls spread evenly, has no element to set: the message asks for the whole
/// array first).
///
/// ```
/// use autobal::config;
/// let mut root = config::parse("[drive]\npsi0 = [1.0, 2.0]\n", "c.toml").unwrap();
/// config::set_element(&mut root, "drive.psi0[2]", "drive.psi0", 1, 0.5).unwrap();
/// assert_eq!(root["drive"]["psi0"].as_array().unwrap()[1].as_float(), Some(0.5));
/// let e = config::set_element(&mut root, "drive.psi0[3]", "drive.psi0", 2, 0.5).unwrap_err();
/// assert!(e.to_string().contains("has 2 elements"), "{e}");
/// ```
pub fn set_element(root: &mut Table, path: &str, key: &str, j: usize, value: f64) -> Result<()> {
    let (t, k) = split_key(key)?;
    crate::limits::check_as(path, key, value)?;
    let old = root.get(t).and_then(|v| v.get(k)).cloned();
    let Some(Value::Array(mut a)) = old else {
        return Err(Error::invalid(path, format!("`{key}` is not an array in the config (give it in full first, e.g. {key} = [...])")));
    };
    let n = a.len();
    let slot = a.get_mut(j).ok_or_else(|| Error::invalid(path, format!("element {} of {n}: `{key}` has {n} elements", j + 1)))?;
    *slot = Value::Float(value);
    set(root, key, Value::Array(a))
}

/// Set a numeric `table.key`, keeping a whole-number key whole (the ball count).
pub fn set_number(root: &mut Table, key: &str, value: f64) -> Result<()> {
    let (t, k) = split_key(key)?;
    let whole = matches!(root.get(t).and_then(|v| v.get(k)), Some(Value::Integer(_))) || COUNTS.contains(&key);
    let v = if whole && value.fract() == 0.0 && value.abs() < 9e15 { Value::Integer(value as i64) } else { Value::Float(value) };
    set(root, key, v)
}

fn split_key(key: &str) -> Result<(&str, &str)> {
    let parts: Vec<&str> = key.split('.').collect();
    if parts.len() != 2 || parts.iter().any(|p| p.is_empty()) {
        return Err(Error::invalid(key, "expected a dotted key table.field, e.g. dimensionless.l_left"));
    }
    check_key(parts[0], Some(parts[1]))?;
    Ok((parts[0], parts[1]))
}

/// Every table and key of `root` must be in [`SCHEMA`], and every number in its range
/// ([`crate::limits`]).
pub fn check_schema(root: &Table) -> Result<()> {
    for (name, value) in root {
        check_key(name, None)?;
        let t = value.as_table().ok_or_else(|| Error::invalid(name.as_str(), format!("expected a table [{name}]")))?;
        for (k, v) in t {
            check_key(name, Some(k))?;
            check_range(&format!("{name}.{k}"), v)?;
        }
    }
    Ok(())
}

/// Numbers (and the numbers in arrays, one level of nesting for `drive.schedule`) against their
/// limits; counts are checked where they are read, as whole numbers.
pub(crate) fn check_range(field: &str, v: &Value) -> Result<()> {
    let is_count = COUNTS.contains(&field);
    match v {
        Value::Float(_) | Value::Integer(_) if !is_count => {
            crate::limits::check(field, number(v, field)?)?;
        }
        Value::Array(a) => {
            if a.len() > MAX_ARRAY_LEN {
                return Err(Error::TooLarge { what: field.into(), size: a.len() as u64, limit: MAX_ARRAY_LEN as u64, reason: "entries".into() });
            }
            for x in a {
                match x {
                    Value::Array(inner) => {
                        for y in inner {
                            if let Value::Float(_) | Value::Integer(_) = y {
                                crate::limits::check(field, number(y, field)?)?;
                            }
                        }
                    }
                    Value::Float(_) | Value::Integer(_) => {
                        crate::limits::check(field, number(x, field)?)?;
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
        return Err(Error::invalid(table, format!("unknown table (known tables: {})", known.join(", "))));
    };
    if let Some(k) = key {
        if !keys.contains(&k) {
            return Err(Error::invalid(format!("{table}.{k}"), format!("unknown key (known keys of [{table}]: {})", keys.join(", "))));
        }
    }
    Ok(())
}

/// A TOML number (integer or float) as `f64`; `field` names it in the error.
fn number(v: &Value, field: &str) -> Result<f64> {
    match v {
        Value::Float(f) => Ok(*f),
        Value::Integer(i) => Ok(*i as f64),
        // a string with a unit (walk 27: `drive.omega0 = "1400 rpm"`): the config's numbers
        // carry no units; say which, and what a speed's string reads as
        Value::String(t) if t.len() <= 100 && t.trim().parse::<f64>().is_err() && starts_with_number_then_letters(t) => {
            Err(Error::invalid(
                field,
                format!(
                    "expected a bare number, got {}: numbers here carry no unit (SI in a dimensional config: kg, m, s, N/m, N s/m, rad/s; dimensionless ones in a [dimensionless] config; only analysis.operating_speed and analysis.omega_max of a dimensional config read units){}",
                    describe(v),
                    crate::units::speed_hint(t).map_or(String::new(), |h| format!("; as an SI speed, {h}"))
                ),
            ))
        }
        o => Err(Error::invalid(field, format!("expected a number, got {}", describe(o)))),
    }
}

/// Whether `t` (trimmed) is a number followed by a unit-like word: `"1400 rpm"`, `"2e5 N/m"`,
/// `"+3 rpm"` (not `"-"`, `"."`, `"1,5"`, `"fast"`).
fn starts_with_number_then_letters(t: &str) -> bool {
    let t = t.trim();
    let end = t.find(|c: char| c.is_alphabetic() && c != 'e' && c != 'E').unwrap_or(t.len());
    let (num, rest) = t.split_at(end);
    // "1e5x": the exponent's e is the number's; a word is what follows the number
    let num = num.trim();
    !rest.is_empty() && num.parse::<f64>().is_ok()
}

fn describe(v: &Value) -> String {
    match v {
        Value::Float(f) => crate::error::fmt_num(*f),
        Value::String(s) => format!("the string \"{}\"", s.chars().take(40).collect::<String>()),
        Value::Table(_) => "a table".into(),
        Value::Array(_) => "an array".into(),
        other => other.to_string(),
    }
}

/// One table of a config, read key by key with errors that name `table.key`.
pub struct Section<'a> {
    /// The table's name (`drive`).
    pub name: &'static str,
    /// The table, if the config has it.
    pub table: Option<&'a Table>,
}

impl<'a> Section<'a> {
    /// The table `name` of `root` (absent: every key reads as not given).
    pub fn of(root: &'a Table, name: &'static str) -> Self {
        Section { name, table: root.get(name).and_then(Value::as_table) }
    }
    /// `table.key`, as errors name it.
    pub fn field(&self, key: &str) -> String {
        format!("{}.{key}", self.name)
    }
    /// The raw value of `key`; a given key counts as used by the model being built
    /// ([`entry_use`]).
    pub fn get(&self, key: &str) -> Option<&'a Value> {
        let v = self.table.and_then(|t| t.get(key));
        if v.is_some() {
            uses::record(&self.field(key));
        }
        v
    }
    /// Unless `cond`, the `keys` read so far count as not used by the model being built, because
    /// of `why` (`"with balancer2.balls = 0"`): they were read (and checked) but, with the rest
    /// of the config, have no effect on the model ([`entry_use`]).
    pub fn used_only_if(&self, cond: bool, keys: &[&str], why: &str) {
        if !cond {
            for k in keys {
                uses::unuse(&self.field(k), why);
            }
        }
    }
    /// The `keys` (if given) are read by the model being built but its own parts do not take
    /// them: inputs of paper 000's 12-state linear model only, which this model consults for
    /// defaults alone ([`EntryUse::linear_only`]: `dimensionless.delta_a` and `d_a` beside the
    /// masses, where the spatial simulation's rotor is the masses').
    pub fn linear_model_only(&self, keys: &[&str]) {
        for k in keys {
            if self.table.is_some_and(|t| t.contains_key(*k)) {
                uses::linear_only(&self.field(k));
            }
        }
    }
    /// A number, if given.
    pub fn f64(&self, key: &str) -> Result<Option<f64>> {
        self.get(key).map(|v| number(v, &self.field(key))).transpose()
    }
    /// A required number.
    pub fn req(&self, key: &str) -> Result<f64> {
        self.f64(key)?.ok_or_else(|| Error::invalid(self.field(key), "missing (required)"))
    }
    /// A whole number ≥ 0 (a number of balls), if given.
    pub fn count(&self, key: &str) -> Result<Option<u32>> {
        let field = self.field(key);
        match self.get(key) {
            None => Ok(None),
            Some(Value::Integer(i)) if *i < 0 => Err(Error::invalid(field, format!("must be a whole number ≥ 0, got {i}"))),
            Some(Value::Integer(i)) => {
                crate::limits::check_count(&field, *i as u64)?;
                u32::try_from(*i).map(Some).map_err(|_| Error::invalid(field, format!("{i} is too large")))
            }
            // a float that happens to be whole ("2.0"): say what was wrong with it, not "got 2"
            Some(Value::Float(f)) if f.fract() == 0.0 && f.is_finite() => Err(Error::invalid(
                field,
                format!("expected a whole number written without a decimal point (write {}), got the decimal number {f:?}", crate::error::fmt_num(*f)),
            )),
            Some(v) => Err(Error::invalid(field, format!("expected a whole number, got {}", describe(v)))),
        }
    }
    /// `true` or `false`, if given.
    pub fn boolean(&self, key: &str) -> Result<Option<bool>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(v) => Err(Error::invalid(self.field(key), format!("expected true or false, got {}", describe(v)))),
        }
    }
    /// A string, if given.
    pub fn string(&self, key: &str) -> Result<Option<&'a str>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s)),
            Some(v) => Err(Error::invalid(self.field(key), format!("expected a string, got {}", describe(v)))),
        }
    }
    /// An array of numbers, if given.
    pub fn array_f64(&self, key: &str) -> Result<Option<Vec<f64>>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Array(a)) => a.iter().map(|v| number(v, &self.field(key))).collect::<Result<Vec<_>>>().map(Some),
            Some(v) => Err(Error::invalid(self.field(key), format!("expected an array of numbers, got {}", describe(v)))),
        }
    }
}

/// Settings of the analytic commands (`[analysis]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// `[δΩ_Kα]`, the permissible relative error of the angular critical speeds.
    pub sensitivity_limit: f64,
    /// Upper end of speed axes as `Ω`, if given (`analysis.omega_max`: a bare number is `Ω`,
    /// `"1500 rpm"`, `"157 rad/s"`, `"25 Hz"` are converted with `ω0`; [`crate::units`]).
    pub omega_max: Option<f64>,
    /// The machine's operating speed `[lo, hi]` as `Ω` (`lo = hi` for one speed), if given
    /// (`analysis.operating_speed = "1400 rpm"` or `"1200-1400 rpm"`). Every automatic speed axis
    /// covers it with margin ([`OPERATING_SPEED_MARGIN`]); the default run-up of the spatial
    /// simulation goes to its top ([`Analysis::run_up_end`]).
    pub operating_speed: Option<[f64; 2]>,
}

impl Default for Analysis {
    fn default() -> Self {
        Analysis { sensitivity_limit: crate::spatial::sensitivity::DEFAULT_LIMIT, omega_max: None, operating_speed: None }
    }
}

/// An automatic speed axis reaches at least this multiple of the top of the operating speed.
pub const OPERATING_SPEED_MARGIN: f64 = 1.25;

impl Analysis {
    /// The upper end of an automatic speed axis (`Ω`): `analysis.omega_max` when given (the
    /// user's choice is kept), else the larger of `automatic` (from the critical speeds, e.g.
    /// [`crate::reports::default_omega_max`]) and [`OPERATING_SPEED_MARGIN`] times the top of the
    /// operating speed.
    ///
    /// ```
    /// let a = autobal::config::Analysis { operating_speed: Some([2.0, 4.0]), ..Default::default() };
    /// assert_eq!(a.speed_axis_max(3.0), 5.0); // 1.25 × 4 covers the operating range
    /// assert_eq!(a.speed_axis_max(6.0), 6.0);
    /// ```
    pub fn speed_axis_max(&self, automatic: f64) -> f64 {
        self.omega_max.unwrap_or_else(|| self.operating_speed.map_or(automatic, |[_, hi]| automatic.max(OPERATING_SPEED_MARGIN * hi)))
    }

    /// Where the default run-up of the spatial simulation ends (`Ω`), if the config says: the top
    /// of the operating speed, else `analysis.omega_max` ([`default_run_up`]).
    pub fn run_up_end(&self) -> Option<f64> {
        self.operating_speed.map(|[_, hi]| hi).or(self.omega_max)
    }
}

/// Read a speed key of `[analysis]` (`field`, e.g. `analysis.omega_max`) as `Ω`: a number is
/// `Ω`, a string is a speed with a unit ([`crate::units`]) converted with `ω0` (a dimensionless
/// config, `omega0 = None`, refuses units). Checked against the range of `analysis.omega_max`
/// (`(0, 1e6]` in `Ω`).
fn analysis_speed(field: &str, v: &Value, omega0: Option<f64>) -> Result<[f64; 2]> {
    let (lo, hi) = if field.ends_with("operating_speed") {
        crate::units::speed_range_of_value(field, v)?
    } else {
        let s = crate::units::speed_of_value(field, v)?;
        (s, s)
    };
    let (lo, hi) = (lo.to_omega(field, omega0)?, hi.to_omega(field, omega0)?);
    crate::limits::check_as(field, "analysis.omega_max", lo)?;
    crate::limits::check_as(field, "analysis.omega_max", hi)?;
    Ok([lo, hi])
}

/// A spatial config (papers 000/003) converted: the model and the analysis settings.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialConfig {
    /// The validated model.
    pub model: SpatialModel,
    /// What the model was built from: parameter paths act on it (maps).
    pub spec: SpatialSpec,
    /// `[analysis]`.
    pub analysis: Analysis,
    /// Whether it was given in SI (`[rotor]`, `[supports]`, ...).
    pub dimensional: bool,
}

/// Real balls of one ball set (`[planar]`, `[balancer]`, `[balancer2]`): `ball_diameter`,
/// `contact`, `restitution`, `contact_stiffness`, `rolling_resistance`, `slip_rate`
/// ([`crate::balls::BallPhysics`]; absent keys: its defaults, the papers' point masses).
pub fn ball_physics_of(sec: &Section) -> Result<crate::balls::BallPhysics> {
    let d = crate::balls::BallPhysics::default();
    let b = crate::balls::BallPhysics {
        diameter: sec.f64("ball_diameter")?,
        contact: sec.boolean("contact")?.unwrap_or(d.contact),
        restitution: sec.f64("restitution")?.unwrap_or(d.restitution),
        contact_stiffness: sec.f64("contact_stiffness")?,
        rolling_resistance: sec.f64("rolling_resistance")?.unwrap_or(d.rolling_resistance),
        slip_rate: sec.f64("slip_rate")?.unwrap_or(d.slip_rate),
    };
    // the size and the contact law act only through contact, the slip rate only with rolling
    // resistance (crate::balls)
    sec.used_only_if(b.contact, &crate::balls::CONTACT_KEYS, &format!("with {} = false", sec.field("contact")));
    sec.used_only_if(b.rolling_resistance != 0.0, &["slip_rate"], &format!("with {} = 0", sec.field("rolling_resistance")));
    Ok(b)
}

/// The keys of a ball set (`[balancer]`, `[balancer2]`) that describe its balls: no effect
/// without balls.
const BALL_KEYS: [&str; 9] =
    ["ball_mass", "race_radius", "drag", "ball_diameter", "contact", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"];

const DIMENSIONAL_TABLES: [&str; 4] = ["rotor", "supports", "unbalance", "balancer"];

/// Convert a spatial config: `[dimensionless]` or the SI tables, and `[analysis]`.
///
/// With `delta_a` beside the masses in `[dimensionless]`, the masses describe the balls (linear
/// model) and `delta_a` overrides the anisotropy they imply, serving as `ΔĀ` and `ΔĀ0` as in
/// 003's worked examples (with a warning in the model's anisotropy).
pub fn spatial(root: &Table) -> Result<SpatialConfig> {
    check_schema(root)?;
    let an = Section::of(root, "analysis");
    let method = match an.string("anisotropy")? {
        None | Some("exact") => AnisotropyMethod::Exact,
        Some("paper") => AnisotropyMethod::Paper,
        Some(o) => return Err(Error::invalid("analysis.anisotropy", format!("must be \"exact\" or \"paper\", got \"{o}\""))),
    };
    let sensitivity_limit = an.f64("sensitivity_limit")?.unwrap_or(crate::spatial::sensitivity::DEFAULT_LIMIT);
    crate::limits::check("analysis.sensitivity_limit", sensitivity_limit)?;
    let has_dim = DIMENSIONAL_TABLES.iter().any(|t| root.contains_key(*t));
    let has_nondim = root.contains_key("dimensionless");
    if !has_dim && !has_nondim && root.contains_key("planar") {
        return Err(Error::invalid("config", "this is a planar-rotor config ([planar], [drive]): use it with `autobal simulate` or `autobal sweep`"));
    }
    let spec = match (has_dim, has_nondim) {
        (true, true) => {
            return Err(Error::invalid(
                "dimensionless",
                "give either the dimensional tables [rotor], [supports], [unbalance], [balancer] or [dimensionless], not both",
            ))
        }
        (false, false) => return Err(Error::invalid("config", "no model: give [dimensionless] or the dimensional tables [rotor] and [supports]")),
        (true, false) => SpatialSpec { input: SpatialInput::Si { rotor: rotor_si(root)?, method }, delta_a_override: None },
        (false, true) => dimensionless(root, method)?,
    };
    let model = spec.build()?;
    let omega0 = model.scale.map(|s| s.omega0);
    let omega_max = an.get("omega_max").map(|v| analysis_speed("analysis.omega_max", v, omega0).map(|w| w[1])).transpose()?;
    let operating_speed = an.get("operating_speed").map(|v| analysis_speed("analysis.operating_speed", v, omega0)).transpose()?;
    Ok(SpatialConfig { model, spec, analysis: Analysis { sensitivity_limit, omega_max, operating_speed }, dimensional: has_dim })
}

/// The SI rotor of `[rotor]`, `[supports]`, `[unbalance]`, `[balancer]`: two isotropic supports,
/// the unbalance mass at angle 0 and the balancer plane (with its ball mass, race radius and
/// drag even when `balls = 0`, so that `balancer.balls = 0` with a ball mass is an error), both
/// in plane A ([`SpatialRotor::to_dimensionless`]).
fn rotor_si(root: &Table) -> Result<SpatialRotor> {
    let (r, s, u, b) = (Section::of(root, "rotor"), Section::of(root, "supports"), Section::of(root, "unbalance"), Section::of(root, "balancer"));
    // the phase of the one unbalance: a rotation of the rotor frame, which the linear model's
    // results do not depend on (the spatial simulation reads it again with [couple])
    u.f64("angle")?;
    // read in this order, so that the first missing or wrong key is the one named
    let rigid = RigidRotor::aligned(r.req("mass")?, r.req("equatorial_moment")?, r.req("polar_moment")?, r.req("z")?);
    // plane A carries balls and unbalance: required when either is described
    let z_balancer = match b.f64("z")? {
        Some(z) => z,
        None if b.table.is_some() || u.table.is_some() => return Err(Error::invalid("balancer.z", "missing (required: the plane of balls and unbalance)")),
        None => 0.0,
    };
    let (z_left, z_right) = (s.req("z_left")?, s.req("z_right")?);
    let (stiffness_left, stiffness_right) = (s.req("stiffness_left")?, s.req("stiffness_right")?);
    let (damping_left, damping_right) = (s.f64("damping_left")?.unwrap_or(0.0), s.f64("damping_right")?.unwrap_or(0.0));
    let unbalance = PointMass { mass: u.f64("mass")?.unwrap_or(0.0), radius: u.f64("radius")?.unwrap_or(0.0), angle: 0.0, z: z_balancer };
    let balls = b.count("balls")?.unwrap_or(0) as usize;
    let plane =
        BallPlane::point_masses(z_balancer, balls, b.f64("ball_mass")?.unwrap_or(0.0), b.f64("race_radius")?.unwrap_or(0.0), b.f64("drag")?.unwrap_or(0.0));
    b.used_only_if(balls > 0, &BALL_KEYS, "with balancer.balls = 0");
    u.used_only_if(unbalance.mass != 0.0, &["radius", "angle"], "with unbalance.mass = 0");
    let supports = vec![Support::isotropic(z_left, stiffness_left, damping_left), Support::isotropic(z_right, stiffness_right, damping_right)];
    Ok(SpatialRotor::new(rigid, supports, vec![unbalance], vec![plane]))
}

fn dimensionless(root: &Table, method: AnisotropyMethod) -> Result<SpatialSpec> {
    let d = Section::of(root, "dimensionless");
    let direct = d.f64("delta_a")?;
    let any_mass = ["m0", "r0", "r"].iter().any(|k| d.get(k).is_some());
    let mut direct_balls = None;
    let override_delta = if any_mass { direct } else { None };
    if let (Some(v), Some(cs)) = (override_delta, d.f64("c_sigma")?) {
        check_delta_a(v, cs)?;
    }
    let anisotropy = match (direct, any_mass) {
        (Some(v), false) => {
            match (d.f64("m")?, d.f64("d_a")?) {
                (Some(m), Some(da)) => direct_balls = Some((m, da)),
                (None, None) => {}
                (Some(_), None) => return Err(Error::invalid("dimensionless.d_a", "required with delta_a and m (D_A of the balls for the linear model)")),
                (None, Some(_)) => {
                    return Err(Error::invalid("dimensionless.m", "required with delta_a and d_a (the balls' mass fraction for the linear model)"))
                }
            }
            AnisotropyInput::Direct(v)
        }
        (_, true) => AnisotropyInput::Masses {
            masses: MassSet { m0: d.req("m0")?, r0: d.req("r0")?, m: d.f64("m")?.unwrap_or(0.0), r: d.f64("r")?.unwrap_or(0.0), n: d.count("n")?.unwrap_or(0) },
            d_a: d.f64("d_a")?,
        },
        (None, false) => AnisotropyInput::Direct(0.0),
    };
    let input = SpatialInput::Dimensionless(DimensionlessInput {
        c_sigma: d.req("c_sigma")?,
        rho_s: d.req("rho_s")?,
        l_left: d.req("l_left")?,
        z_a: d.f64("z_a")?.unwrap_or(0.0),
        anisotropy,
        h_x: d.f64("h_x")?.unwrap_or(0.0),
        h_s: d.f64("h_s")?.unwrap_or(0.0),
        method,
        direct_balls,
    });
    Ok(SpatialSpec { input, delta_a_override: override_delta })
}

/// Convert a planar config (`[planar]`, `[drive]`, `[integration]`) into a validated problem.
/// Defaults: no housing or balls unless given, `drive.kind = "acceleration"` from rest,
/// `t_end = 10 s`, `dt = t_end/2000`, `rtol = 1e-8`, `atol = 1e-9 m`, balls spread evenly at rest.
pub fn planar(root: &Table) -> Result<PlanarProblem> {
    let rotor = planar_rotor(root)?;
    if !root.contains_key("drive") {
        // (the shared drive reader's words speak of a default run-up, which only the spatial
        // rotor has)
        return Err(Error::invalid(
            "drive",
            "missing: a planar run needs a [drive] table (the planar rotor has no default run-up): give drive.kind and its keys (examples/planar.toml); the analyses at a constant speed (stability, ranges, critical, campbell, map) need none",
        ));
    }
    let (d, ig) = (Section::of(root, "drive"), Section::of(root, "integration"));
    planar_run(rotor, &d, &ig)
}

/// The rotor of a planar config (`[planar]`), validated, without its run (`[drive]`,
/// `[integration]`): what the analyses at a constant speed need (`stability`, `critical`,
/// `campbell`, `map`), which read a config without `[drive]` (they refused one: "drive.b:
/// required for kind = "acceleration"", session 19's audit). [`planar`] is this and the run.
pub fn planar_rotor(root: &Table) -> Result<PlanarRotor> {
    check_schema(root)?;
    if !root.contains_key("planar") {
        // every command reads a config that is neither spatial nor linear as a planar one: the
        // message names what a config may hold, not one command (an empty file reached here
        // from `stability` and said "`simulate` needs")
        return Err(Error::invalid(
            "planar",
            "missing: the config has no rotor: give [planar] (paper 004, examples/planar.toml), [rotor] or [dimensionless] (papers 000/003, examples/default.toml) or [linear_rotor] (examples/linear_rotor_shaft.toml)",
        ));
    }
    let p = Section::of(root, "planar");
    let (k, k_y) = planar_direction_pair(&p, "k", None)?;
    let (c, c_y) = planar_direction_pair(&p, "c", Some(0.0))?;
    let ball_masses = planar_per_ball(&p, "m3", "ball_masses")?;
    let ball_drags = planar_per_ball(&p, "c_psi", "ball_drags")?;
    let n = match (p.count("n")?, ball_masses.as_ref().or(ball_drags.as_ref())) {
        (Some(n), _) => n as usize,
        (None, Some(v)) => v.len(),
        (None, None) => 0,
    };
    let mean = |v: &Option<Vec<f64>>| v.as_ref().filter(|v| !v.is_empty()).map(|v| v.iter().sum::<f64>() / v.len() as f64);
    let rotor = PlanarRotor {
        m1: p.req("m1")?,
        m2: p.f64("m2")?.unwrap_or(0.0),
        m3: mean(&ball_masses).map_or_else(|| p.f64("m3").map(|v| v.unwrap_or(0.0)), Ok)?,
        n,
        s1: p.req("s1")?,
        s2: p.f64("s2")?.unwrap_or(0.0),
        gamma: p.f64("gamma")?.unwrap_or(0.0),
        r: p.f64("r")?.unwrap_or(0.0),
        k,
        c,
        k_y,
        c_y,
        c_psi: mean(&ball_drags).map_or_else(|| p.f64("c_psi").map(|v| v.unwrap_or(0.0)), Ok)?,
        ball_masses,
        ball_drags,
        c_theta: p.f64("c_theta")?.unwrap_or(0.0),
        i_g: p.req("i_g")?,
        balls: ball_physics_of(&p)?,
    };
    rotor.validate()?;
    p.used_only_if(
        rotor.n > 0,
        &["m3", "r", "c_psi", "ball_diameter", "contact", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"],
        "with planar.n = 0",
    );
    crate::planar::problem::check_natural_frequency(&rotor)?;
    Ok(rotor)
}

/// The planar rotor an analysis at a constant speed reads (`stability`, `critical`,
/// `campbell`, `map`, `ranges`): the whole config where it has `[drive]` (so a bad drive is
/// still named), else [`planar_rotor`] alone.
pub fn planar_rotor_for_analysis(root: &Table) -> Result<PlanarRotor> {
    if root.contains_key("drive") {
        Ok(planar(root)?.rotor)
    } else {
        planar_rotor(root)
    }
}

/// [`planar`]'s run of `rotor`: the drive and the integration settings.
fn planar_run(rotor: PlanarRotor, d: &Section, ig: &Section) -> Result<PlanarProblem> {
    let (drive, t_end) = drive(d)?;
    let ig = integration(ig, t_end)?;
    let pair = |key: &str| -> Result<[f64; 2]> {
        match d.array_f64(key)? {
            None => Ok([0.0; 2]),
            Some(v) if v.len() == 2 => Ok([v[0], v[1]]),
            Some(v) => Err(Error::invalid(d.field(key), format!("needs 2 numbers [X, Y], got {}", v.len()))),
        }
    };
    let defaults = Settings::for_balls(rotor.n, t_end);
    let settings = Settings {
        method: ig.method,
        dt: ig.dt,
        rtol: ig.rtol,
        atol: ig.atol,
        psi0: d.array_f64("psi0")?.unwrap_or(defaults.psi0),
        psi_rate0: d.array_f64("psi_rate0")?.unwrap_or(defaults.psi_rate0),
        xy0: pair("xy0")?,
        xy_rate0: pair("xy_rate0")?,
        max_steps: ig.max_steps.unwrap_or(defaults.max_steps),
        max_wall_s: ig.max_wall_s,
        t_end,
    };
    settings.validate(&rotor)?;
    Ok(PlanarProblem { rotor, drive, settings })
}

/// A support coefficient of `[planar]` given once (`k`, the same in every direction) or per
/// direction (`k_x` and `k_y`): `(x value, Some(y value))` for the pair, `(value, None)` for the
/// isotropic key, `default` when neither is given (`None`: required). Giving the isotropic key
/// and a per-direction one, or one of the pair alone, is an error naming both keys.
fn planar_direction_pair(p: &Section, key: &str, default: Option<f64>) -> Result<(f64, Option<f64>)> {
    let (kx, ky) = (format!("{key}_x"), format!("{key}_y"));
    let iso = p.f64(key)?;
    let (x, y) = (p.f64(&kx)?, p.f64(&ky)?);
    if iso.is_some() {
        if let Some(given) = [(&kx, x), (&ky, y)].iter().find(|(_, v)| v.is_some()).map(|(k, _)| k) {
            return Err(Error::invalid(
                p.field(given),
                format!("conflicts with {}: give {key} (the same in every direction) or {kx} and {ky}, not both", p.field(key)),
            ));
        }
    }
    match (iso, x, y) {
        (Some(v), _, _) => Ok((v, None)),
        (None, Some(a), Some(b)) => Ok((a, Some(b))),
        (None, Some(_), None) => {
            Err(Error::invalid(p.field(&ky), format!("missing: {} needs {} (or give {} alone)", p.field(&kx), p.field(&ky), p.field(key))))
        }
        (None, None, Some(_)) => {
            Err(Error::invalid(p.field(&kx), format!("missing: {} needs {} (or give {} alone)", p.field(&ky), p.field(&kx), p.field(key))))
        }
        (None, None, None) => default.map(|v| (v, None)).ok_or_else(|| Error::invalid(p.field(key), format!("missing (required; or give {kx} and {ky})"))),
    }
}

/// A per-ball list of `[planar]` (`ball_masses`, `ball_drags`), if given; giving it beside the
/// common value `common` (`m3`, `c_psi`) is an error naming both. Its length is checked against
/// `planar.n` by [`PlanarRotor::validate`].
fn planar_per_ball(p: &Section, common: &str, key: &str) -> Result<Option<Vec<f64>>> {
    let v = p.array_f64(key)?;
    if v.is_some() && p.get(common).is_some() {
        return Err(Error::invalid(p.field(key), format!("conflicts with {}: give one value for every ball or one per ball, not both", p.field(common))));
    }
    if v.as_ref().is_some_and(|v| v.is_empty()) {
        return Err(Error::invalid(p.field(key), "empty: give one value per ball"));
    }
    Ok(v)
}

/// `[drive]`: the drive (shared by the planar and the spatial simulation) and `t_end`
/// (default 10 s).
pub fn drive(d: &Section) -> Result<(Drive, f64)> {
    let omega0 = d.f64("omega0")?.unwrap_or(0.0);
    let t_off = d.f64("t_off")?;
    let given_kind = d.string("kind")?;
    let kind = given_kind.unwrap_or("acceleration");
    // (`basins --set drive.t_end=1` on a config without [drive] said only "drive.b: required
    // for kind = "acceleration"": the table the --set made replaces the default run-up)
    let why =
        if given_kind.is_none() { " (the default kind; a [drive] table, even one made by --set, replaces the default run-up: give its keys)" } else { "" };
    let need = |key: &str| d.f64(key)?.ok_or_else(|| Error::invalid(d.field(key), format!("required for kind = \"{kind}\"{why}")));
    let schedule = || -> Result<Vec<(f64, f64)>> {
        match d.get("schedule") {
            Some(Value::Array(rows)) => rows
                .iter()
                .map(|r| match r {
                    Value::Array(pair) if pair.len() == 2 => Ok((number(&pair[0], "drive.schedule")?, number(&pair[1], "drive.schedule")?)),
                    _ => Err(Error::invalid("drive.schedule", "each entry must be a [t, value] pair")),
                })
                .collect(),
            Some(v) => Err(Error::invalid("drive.schedule", format!("expected an array of [t, value] pairs, got {}", describe(v)))),
            None => Err(Error::invalid("drive.schedule", "required for kind = \"schedule\"")),
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
            o => return Err(Error::invalid("drive.schedule_of", format!("must be \"speed\" or \"torque\", got \"{o}\""))),
        },
        o => return Err(Error::invalid("drive.kind", format!("must be one of \"speed\", \"acceleration\", \"torque\", \"motor\", \"schedule\", got \"{o}\""))),
    };
    drive.validate()?;
    // the parameters of the other kinds are a menu (examples/planar.toml keeps `torque` and
    // `omega_idle` beside kind = "acceleration", so that `--set drive.kind=motor` switches):
    // they count as used (docs/reference/robustness.md, "Every entry is used")
    for key in ["b", "torque", "omega_idle", "t_off", "schedule", "schedule_of"] {
        d.get(key);
    }
    let t_end = d.f64("t_end")?.unwrap_or(10.0);
    Ok((drive, t_end))
}

/// The `[integration]` table, shared by the planar and the spatial simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Integration {
    /// `integration.method`: `auto` (default), `dop853` or `rodas` (also spelled `rosenbrock`).
    pub method: Method,
    /// Output interval (default `t_end/2000`).
    pub dt: f64,
    /// Relative tolerance (default 1e-8).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-9).
    pub atol: f64,
    /// Step budget (`None`: the model's default).
    pub max_steps: Option<u64>,
    /// Wall-clock budget in seconds.
    pub max_wall_s: Option<f64>,
}

/// `[integration]`: method, output interval, tolerances, budgets.
pub fn integration(ig: &Section, t_end: f64) -> Result<Integration> {
    let method = match ig.string("method")? {
        None | Some("auto") => Method::Auto,
        Some("dop853") => Method::Dop853,
        Some("rodas") | Some("rosenbrock") => Method::Rodas,
        Some(o) => {
            return Err(Error::invalid("integration.method", format!("must be \"auto\", \"dop853\", \"rodas\" or \"rosenbrock\" (the same), got \"{o}\"")))
        }
    };
    let max_steps = match ig.f64("max_steps")? {
        None => None,
        Some(v) if (1.0..=1e15).contains(&v) && v.fract() == 0.0 => Some(v as u64),
        Some(v) => return Err(Error::invalid("integration.max_steps", format!("must be a whole number from 1 to 1e15, got {v}"))),
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

/// Whether a config describes the spatial rotor of papers 000/003 (the analytic commands'
/// tables `[dimensionless]`, `[rotor]`, `[supports]`, `[unbalance]`, `[balancer]`) rather than
/// the planar rotor of paper 004 (`[planar]`).
pub fn is_spatial(root: &Table) -> bool {
    root.contains_key("dimensionless") || DIMENSIONAL_TABLES.iter().any(|t| root.contains_key(*t))
}

/// The entries of a spatial config that the linear model of papers 000/003 (the analytic
/// commands: inertia, critical speeds, ranges, stability, Campbell diagrams, maps) does not use:
/// that model has isotropic supports, one balancer plane of point-mass balls and a static
/// unbalance, so these describe the rotor only for the spatial simulation
/// ([`spatial_simulation`]). In the order of [`SCHEMA`], as the config spells them:
///
/// - `[couple]`, `[balancer2]`: whenever present (a second unbalance mass, a second ball set);
/// - `supports.stiffness_left_y` … `damping_right_y`: where they differ from the x value;
/// - `rotor.axis_tilt` (with `rotor.axis_tilt_angle`): where the tilt is not 0;
/// - `balancer.contact`, `balancer.rolling_resistance` (real balls): where they switch the
///   physics on;
/// - `spatial.gravity`, `spatial.lock_tilt`, `spatial.spin_drag`: where not 0 / `false`.
///
/// Keys at the value that reproduces the linear model are not listed (an example written out
/// in full, `gravity = [0, 0, 0]`, is not a difference); nor are the run's settings (`[drive]`,
/// `[integration]`, `[initial]`), which describe a run rather than the rotor. It is
/// [`entry_use`]'s `simulation_only` for [`Model::Linear`]: the entries the spatial simulation
/// reads and the linear model does not (none for a config [`spatial`] rejects).
///
/// ```
/// use autobal::config;
/// let two = config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two").unwrap();
/// assert_eq!(
///     config::ignored_by_linear_model(&two),
///     ["supports.stiffness_left_y", "supports.stiffness_right_y", "[couple]", "[balancer2]", "spatial.gravity"]
/// );
/// let one = config::parse(include_str!("../../../examples/spatial.toml"), "one").unwrap();
/// assert!(config::ignored_by_linear_model(&one).is_empty()); // gravity 0, no tilt lock
/// ```
pub fn ignored_by_linear_model(root: &Table) -> Vec<String> {
    entry_use(root, &[Model::Linear]).simulation_only
}

/// A spatial simulation's config converted (`autobal simulate` and `autobal basins` on the
/// rotor of papers 000/003): the analytic config plus `[drive]`, `[integration]` and, optionally,
/// `[initial]`, `[spatial]`, `[couple]`, `[balancer2]` (docs/notes/spatial.md).
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialSimulation {
    /// The analytic config the rotor was built from (units, source of the model).
    pub config: SpatialConfig,
    /// The rotor in time.
    pub rotor: crate::spatial::dynamics::SpatialRotor,
    /// `[drive]` (speeds and times in rad/s and s for an SI config, Ω and τ for a
    /// dimensionless one).
    pub drive: Drive,
    /// Initial state: `[initial]` (rotor position, velocity, tilt, tilt rate) and
    /// `drive.psi0`, `drive.psi_rate0` (balls).
    pub initial: crate::spatial::dynamics::Initial,
    /// `[integration]` and `drive.t_end`.
    pub settings: crate::spatial::dynamics::Settings,
    /// Whether the config had no `[drive]`, so that the run is [`default_run_up`]'s.
    pub default_drive: bool,
}

/// Revolutions of the run-up a spatial simulation gets when its config has no `[drive]`.
pub const DEFAULT_RUN_UP_REVOLUTIONS: f64 = 1000.0;

/// The `[drive]` and `[integration]` a spatial config gets when it has no `[drive]`: from rest at
/// constant acceleration `b` to `ω_end`, 1.3 times the highest critical speed of the balanced
/// rotor, or `omega_max` when given ([`Analysis::run_up_end`]: the top of the config's
/// `analysis.operating_speed`, else its `analysis.omega_max`), in `revolutions` revolutions: `φ = ω_end²/(2b) = 2π N`, so
/// `b = ω_end²/(4π N)` and `t_end = ω_end/b`; samples every `t_end/3000`. Speeds in rad/s for an
/// SI config, in Ω for a dimensionless one. The given `[integration]` keys are kept, but for a
/// missing `dt`.
///
/// ```
/// let root = autobal::config::parse(include_str!("../../../examples/dimensional.toml"), "dimensional.toml").unwrap();
/// let config = autobal::config::spatial(&root).unwrap();
/// let (drive, integration) = autobal::config::default_run_up(&config.model, config.analysis.omega_max, &autobal::config::Table::new(), 1000.0);
/// let (b, t_end) = (drive["b"].as_float().unwrap(), drive["t_end"].as_float().unwrap());
/// let omega_end = b * t_end;
/// assert!((0.5 * b * t_end * t_end - 2.0 * std::f64::consts::PI * 1000.0).abs() < 1e-6); // 1000 revolutions
/// assert!((integration["dt"].as_float().unwrap() - t_end / 3000.0).abs() < 1e-12);
/// # let _ = omega_end;
/// ```
pub fn default_run_up(model: &SpatialModel, omega_max: Option<f64>, integration: &Table, revolutions: f64) -> (Table, Table) {
    let w0 = model.scale.map_or(1.0, |s| s.omega0);
    let top = crate::spatial::critical_speeds::critical_speeds(model).speeds.iter().map(|c| c.omega).fold(0.0, f64::max);
    let omega_end = w0 * omega_max.unwrap_or(1.3 * top.max(1.0));
    let b = omega_end * omega_end / (4.0 * std::f64::consts::PI * revolutions);
    let t_end = omega_end / b;
    let mut d = Table::new();
    d.insert("kind".into(), Value::String("acceleration".into()));
    d.insert("omega0".into(), Value::Float(0.0));
    d.insert("b".into(), Value::Float(b));
    d.insert("t_end".into(), Value::Float(t_end));
    let mut ig = integration.clone();
    ig.entry("dt").or_insert(Value::Float(t_end / 3000.0));
    (d, ig)
}

/// Convert a spatial simulation's config ([`SpatialSimulation`]); every error names the key.
///
/// ```
/// let root = autobal::config::parse(include_str!("../../../examples/spatial.toml"), "spatial.toml").unwrap();
/// let sim = autobal::config::spatial_simulation(&root).unwrap();
/// assert_eq!(sim.rotor, autobal::spatial::dynamics::SpatialRotor::default()); // 000's base case
/// // without [drive]: the default run-up through the critical speeds
/// let mut no_drive = root.clone();
/// no_drive.remove("drive");
/// let run_up = autobal::config::spatial_simulation(&no_drive).unwrap();
/// assert!(run_up.default_drive && matches!(run_up.drive, autobal::drive::Drive::Acceleration { .. }));
/// ```
pub fn spatial_simulation(root: &Table) -> Result<SpatialSimulation> {
    use crate::spatial::dynamics::{simulate::initial_state, Equations, Initial, Settings as SpatialSettings};
    let config = spatial(root)?;
    let sec = |name: &'static str| Section::of(root, name);
    let pair = |s: &Section, key: &str| -> Result<Option<[f64; 2]>> {
        match s.array_f64(key)? {
            None => Ok(None),
            Some(v) if v.len() == 2 => Ok(Some([v[0], v[1]])),
            Some(v) => Err(Error::invalid(s.field(key), format!("expected 2 numbers, got {}", v.len()))),
        }
    };
    let mut rotor = match &config.spec.input {
        SpatialInput::Si { rotor: si, .. } => {
            let mut r = si.clone();
            // the simulation's rotor has no empty ball plane (its [balancer2] is then the first)
            r.planes.retain(|p| p.n > 0);
            let balancer_has_balls = !r.planes.is_empty();
            let (ro, su, un) = (sec("rotor"), sec("supports"), sec("unbalance"));
            r.rotor.axis_tilt = ro.f64("axis_tilt")?.unwrap_or(0.0);
            r.rotor.axis_tilt_angle = ro.f64("axis_tilt_angle")?.unwrap_or(0.0);
            for (i, side) in ["left", "right"].iter().enumerate() {
                if let Some(k) = su.f64(&format!("stiffness_{side}_y"))? {
                    r.supports[i].stiffness[1] = k;
                }
                if let Some(c) = su.f64(&format!("damping_{side}_y"))? {
                    r.supports[i].damping[1] = c;
                }
            }
            r.unbalances[0].angle = un.f64("angle")?.unwrap_or(0.0);
            let c = sec("couple");
            if c.table.is_some() {
                r.unbalances.push(PointMass { mass: c.req("mass")?, radius: c.req("radius")?, angle: c.f64("angle")?.unwrap_or(0.0), z: c.req("z")? });
            }
            let b = sec("balancer2");
            if b.table.is_some() {
                let plane = BallPlane {
                    z: b.req("z")?,
                    n: b.count("balls")?.ok_or_else(|| Error::invalid("balancer2.balls", "missing (required)"))? as usize,
                    ball_mass: b.req("ball_mass")?,
                    race_radius: b.req("race_radius")?,
                    drag: b.f64("drag")?.unwrap_or(0.0),
                    physics: ball_physics_of(&b)?,
                };
                // as the first plane (spatial::params): a ball mass without balls is a mistake
                if plane.n == 0 && plane.ball_mass != 0.0 {
                    return Err(Error::invalid("balancer2.balls", "is 0 but balancer2.ball_mass is given: set the number of balls, or ball_mass = 0"));
                }
                b.used_only_if(plane.n > 0, &BALL_KEYS, "with balancer2.balls = 0");
                r.planes.push(plane);
            }
            // [balancer]'s own plane only (without balls, the first plane is [balancer2]'s)
            let balancer_physics = ball_physics_of(&sec("balancer"))?;
            if balancer_has_balls {
                r.planes[0].physics = balancer_physics;
            }
            ro.used_only_if(r.rotor.axis_tilt != 0.0, &["axis_tilt_angle"], "with rotor.axis_tilt = 0");
            r
        }
        SpatialInput::Dimensionless(_) => {
            for t in ["couple", "balancer2"] {
                if root.contains_key(t) {
                    return Err(Error::invalid(t, "a second unbalance mass or balancer plane needs the dimensional tables ([rotor], [supports], ...)"));
                }
            }
            let rotor = SpatialRotor::from_dimensionless(&config.model)?;
            // its inertia and balls are the masses' (m0, r0, m, r, n): `delta_a` and `d_a`
            // beside them set the 12-state linear model's anisotropy (ΔĀ, D_A) only, which a run
            // still consults for its defaults (the default run-up's end below; the general
            // route's default speed range): the commands say what a run takes from them (review
            // 25b R4; session 26's "no effect" was false where those defaults are used)
            sec("dimensionless").linear_model_only(&LINEAR_MODEL_ONLY);
            rotor
        }
    };
    let sp = sec("spatial");
    if let Some(g) = sp.array_f64("gravity")? {
        if g.len() != 3 {
            return Err(Error::invalid("spatial.gravity", format!("expected 3 numbers [g_x, g_y, g_z], got {}", g.len())));
        }
        rotor.gravity = [g[0], g[1], g[2]];
    }
    rotor.spin_drag = sp.f64("spin_drag")?.unwrap_or(0.0);
    rotor.lock_tilt = sp.boolean("lock_tilt")?.unwrap_or(false);
    rotor.validate()?;
    let default_drive = !root.contains_key("drive");
    let defaults = default_drive.then(|| {
        let given = root.get("integration").and_then(Value::as_table).cloned().unwrap_or_default();
        default_run_up(&config.model, config.analysis.run_up_end(), &given, DEFAULT_RUN_UP_REVOLUTIONS)
    });
    let (d, ig) = match &defaults {
        Some((d, ig)) => (Section { name: "drive", table: Some(d) }, Section { name: "integration", table: Some(ig) }),
        None => (sec("drive"), sec("integration")),
    };
    let (drive, t_end) = drive(&d)?;
    let ig = integration(&ig, t_end)?;
    if ig.max_steps.is_some() || ig.max_wall_s.is_some() {
        let key = if ig.max_steps.is_some() { "max_steps" } else { "max_wall_s" };
        return Err(Error::invalid(format!("integration.{key}"), "the spatial simulation takes no budget (Ctrl-C stops it, keeping what it wrote)"));
    }
    let settings = SpatialSettings { method: ig.method, t_end, dt: ig.dt, rtol: ig.rtol, atol: ig.atol };
    settings.validate()?;
    let mut initial = Initial::at_rest(&rotor);
    let ini = sec("initial");
    initial.position = pair(&ini, "position")?.unwrap_or(initial.position);
    initial.velocity = pair(&ini, "velocity")?.unwrap_or(initial.velocity);
    initial.tilt = pair(&ini, "tilt")?.unwrap_or(initial.tilt);
    initial.tilt_rate = pair(&ini, "tilt_rate")?.unwrap_or(initial.tilt_rate);
    if let Some(p) = d.array_f64("psi0")? {
        initial.psi = p;
    }
    if let Some(p) = d.array_f64("psi_rate0")? {
        initial.psi_rate = p;
    }
    initial_state(&Equations::new(&rotor, &drive), &initial)?;
    Ok(SpatialSimulation { config, rotor, drive, initial, settings, default_drive })
}

/// The keys of `[dimensionless]` that, given beside the masses (`m0`, `r0`, `m`, `r`, `n`), are
/// inputs of the 12-state linear model only: the spatial simulation's rotor takes its inertia and
/// balls from the masses ([`SpatialRotor::from_dimensionless`]), the linear model its anisotropy
/// from `delta_a` (ΔĀ = ΔĀ0, overriding the masses') and `D_A` from `d_a` (eq (17), `n ≥ 3`).
pub const LINEAR_MODEL_ONLY: [&str; 2] = ["delta_a", "d_a"];

/// Which entries the model being built reads: [`Section::get`] records every given key while a
/// [`track`] is running on this thread, [`Section::used_only_if`] takes back those the rest of
/// the config makes moot. A thread-local, so that every reader (and every reader added later)
/// reports through [`Section`] without passing a recorder along; outside [`track`] it costs a
/// branch.
mod uses {
    use std::cell::RefCell;
    use std::collections::{BTreeMap, BTreeSet};

    /// What one build read.
    #[derive(Debug, Default, Clone)]
    pub struct Uses {
        /// `table.key` of every given entry the model used.
        pub read: BTreeSet<String>,
        /// Entries read but of no effect, with why (`"with balancer2.balls = 0"`).
        pub moot: BTreeMap<String, String>,
        /// Entries read that the model's own parts do not take: inputs of the linear model
        /// only, consulted for defaults ([`super::Section::linear_model_only`]).
        pub linear_only: BTreeSet<String>,
    }

    thread_local! {
        static USES: RefCell<Option<Uses>> = const { RefCell::new(None) };
    }

    pub fn record(field: &str) {
        USES.with(|u| {
            if let Some(u) = u.borrow_mut().as_mut() {
                u.read.insert(field.to_string());
            }
        })
    }

    pub fn unuse(field: &str, why: &str) {
        USES.with(|u| {
            if let Some(u) = u.borrow_mut().as_mut() {
                u.read.remove(field);
                u.moot.entry(field.to_string()).or_insert_with(|| why.to_string());
            }
        })
    }

    pub fn linear_only(field: &str) {
        USES.with(|u| {
            if let Some(u) = u.borrow_mut().as_mut() {
                u.read.remove(field);
                u.linear_only.insert(field.to_string());
            }
        })
    }

    /// Run `f`, recording what it reads (a [`track`] inside another records for both).
    pub fn track<T>(f: impl FnOnce() -> T) -> (T, Uses) {
        let outer = USES.with(|u| u.borrow_mut().replace(Uses::default()));
        let out = f();
        let mine = USES.with(|u| u.borrow_mut().take()).unwrap_or_default();
        if let Some(mut o) = outer {
            o.read.extend(mine.read.iter().cloned());
            o.moot.extend(mine.moot.clone());
            o.linear_only.extend(mine.linear_only.iter().cloned());
            USES.with(|u| *u.borrow_mut() = Some(o));
        }
        (out, mine)
    }
}

/// A model a command runs on a config ([`entry_use`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// The linear model of papers 000/003 ([`spatial`]): the analytic commands.
    Linear,
    /// The spatial simulation ([`spatial_simulation`]): `simulate`, `sweep`, `basins`, the
    /// general route of `stability` and `map` on a spatial config.
    Spatial,
    /// The planar rotor of paper 004 ([`planar`]).
    Planar,
}

impl Model {
    /// The model as messages name it.
    pub fn describe(self) -> &'static str {
        match self {
            Model::Linear => "the linear model of papers 000/003",
            Model::Spatial => "the spatial simulation of papers 000/003",
            Model::Planar => "the planar rotor of paper 004",
        }
    }

    fn build(self, root: &Table) -> Result<()> {
        match self {
            Model::Linear => spatial(root).map(drop),
            Model::Spatial => spatial_simulation(root).map(drop),
            Model::Planar => planar(root).map(drop),
        }
    }

    /// Whether `table.key` belongs to this model's rotor at all (with some value of the other
    /// entries): the spatial rotor has no `[planar]` and starts from `[initial]`, not from the
    /// planar rotor's `drive.xy0`; the planar rotor has only `[planar]`, `[drive]`,
    /// `[integration]`.
    fn owns(self, table: &str, key: &str) -> bool {
        match self {
            Model::Planar => matches!(table, "planar" | "drive" | "integration"),
            Model::Linear | Model::Spatial => table != "planar" && !(table == "drive" && matches!(key, "xy0" | "xy_rate0")),
        }
    }
}

/// The tables that describe a run (its drive, integrator and start) rather than the rotor.
pub const RUN_TABLES: [&str; 3] = ["drive", "integration", "initial"];

/// An entry of a config that the command's model does not use, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unused {
    /// As the config spells it: `spatial.gravity`, or `[couple]` for a whole table.
    pub key: String,
    /// Why, e.g. `belongs to the spatial rotor of papers 000/003` or `with drive.kind = "speed"`.
    pub why: String,
}

/// How the entries of a config are used by the models a command runs ([`entry_use`]).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct EntryUse {
    /// Entries no model of the command has (another rotor's tables and keys): an error.
    pub foreign: Vec<Unused>,
    /// Entries of the rotor that the linear model leaves out and the spatial simulation uses
    /// ([`ignored_by_linear_model`]): a warning of the analytic commands.
    pub simulation_only: Vec<String>,
    /// Entries the model has, of no effect with the rest of the config (`drive.b` with
    /// `kind = "speed"`, a ball mass with no balls, a restitution without contact): a warning.
    pub moot: Vec<Unused>,
    /// Entries that are inputs of the 12-state linear model only, on a command that runs the
    /// spatial simulation's rotor and not that model: `dimensionless.delta_a` and `d_a` beside
    /// the masses ([`LINEAR_MODEL_ONLY`]; the rotor's inertia and balls are the masses'). Not of
    /// no effect: the linear model's critical speeds set the default run-up's end (no `[drive]`)
    /// and the general route's default speed range. A warning naming what they set in the
    /// command's run, which the command knows (`check_entries` in the commands crate).
    pub linear_only: Vec<String>,
}

impl EntryUse {
    /// Whether every entry is used.
    pub fn is_empty(&self) -> bool {
        self.foreign.is_empty() && self.simulation_only.is_empty() && self.moot.is_empty() && self.linear_only.is_empty()
    }
}

/// Whether `value` of `table.key` is what the models assume without it: 0, `false`, an array of
/// zeros, a y support value equal to its x value. Such an entry (an example written out in full,
/// `gravity = [0, 0, 0]`) changes nothing whichever model runs it, so it is never reported.
fn neutral(root: &Table, table: &str, key: &str, value: &Value) -> bool {
    fn zero(v: &Value) -> bool {
        match v {
            Value::Boolean(b) => !b,
            Value::Integer(i) => *i == 0,
            Value::Float(f) => *f == 0.0,
            Value::Array(a) => a.iter().all(zero),
            _ => false,
        }
    }
    if table == "supports" {
        if let Some(x) = key.strip_suffix("_y") {
            let xv = root.get("supports").and_then(|t| t.get(x)).and_then(|v| number(v, "").ok()).unwrap_or(0.0);
            return number(value, "").ok() == Some(xv);
        }
    }
    zero(value)
}

/// Which entries of `root` the `models` a command runs use, every entry of the config sorted
/// into one class (docs/reference/robustness.md, "Every entry is used"):
///
/// - read by a model (through [`Section`]): used, but see `simulation_only`;
/// - at its neutral value (0, `false`, an array of zeros, a y support equal to x): nothing to
///   report;
/// - of no model of the command (`[planar]` for the spatial rotor; `[spatial]`, `[initial]`,
///   `[couple]`, … for the planar one; the planar start `drive.xy0` on a spatial run):
///   [`EntryUse::foreign`], an error: the user wrote physics that would silently not happen;
/// - a run's settings (`[drive]`, `[integration]`, `[initial]`) when the only model is the
///   linear one: not reported (the analytic commands describe the rotor; the same config serves
///   `simulate`);
/// - read by the spatial simulation but not by the linear model ([`Model::Linear`] among
///   `models`): [`EntryUse::simulation_only`], a warning;
/// - read by the spatial simulation as an input of the 12-state linear model only
///   (`dimensionless.delta_a`, `d_a` beside the masses), with [`Model::Linear`] not among
///   `models`: [`EntryUse::linear_only`], a warning saying what they set in the run;
/// - otherwise the model has the entry but the rest of the config makes it moot:
///   [`EntryUse::moot`], a warning saying why.
///
/// A table all of whose entries land in one class, none read, is reported once as `[table]`.
/// A model whose build fails is left out (its command reports the error). Keys appear in the
/// order of [`SCHEMA`]'s tables, alphabetically within a table.
///
/// ```
/// use autobal::config::{self, Model};
/// let mut root = config::parse(config::DEFAULT_PLANAR, "planar").unwrap();
/// config::set(&mut root, "spatial.gravity", config::parse_value("[0, -9.81, 0]")).unwrap();
/// config::set(&mut root, "planar.restitution", 0.9.into()).unwrap(); // planar.contact = false
/// let u = config::entry_use(&root, &[Model::Planar]);
/// assert_eq!(u.foreign[0].key, "spatial.gravity");
/// assert_eq!((u.moot[0].key.as_str(), u.moot[0].why.as_str()), ("planar.restitution", "with planar.contact = false"));
/// ```
pub fn entry_use(root: &Table, models: &[Model]) -> EntryUse {
    let mut read = std::collections::BTreeSet::new();
    let mut moot = std::collections::BTreeMap::new();
    let mut linear_only = std::collections::BTreeSet::new();
    let mut linear = None;
    let mut simulation = None;
    let mut any_built = false;
    for &m in models {
        let (ok, u) = uses::track(|| m.build(root));
        if ok.is_err() {
            continue;
        }
        any_built = true;
        read.extend(u.read.iter().cloned());
        for (k, v) in &u.moot {
            moot.entry(k.clone()).or_insert_with(|| v.clone());
        }
        linear_only.extend(u.linear_only.iter().cloned());
        match m {
            Model::Linear => linear = Some(u.read),
            Model::Spatial => simulation = Some(u.read),
            Model::Planar => {}
        }
    }
    if !any_built {
        // no model accepts the config: its build error is what to report
        return EntryUse::default();
    }
    // the spatial simulation is what the linear model's omissions are measured against
    if linear.is_some() && simulation.is_none() {
        let (ok, u) = uses::track(|| Model::Spatial.build(root));
        simulation = ok.is_ok().then_some(u.read);
    }
    let only_linear = models.iter().all(|m| *m == Model::Linear);
    let mut out = EntryUse::default();
    for (table, _) in SCHEMA {
        let Some(t) = root.get(*table).and_then(Value::as_table) else { continue };
        let mut classes: Vec<(u8, Unused)> = vec![];
        let mut any_read = false;
        for (key, value) in t {
            let field = format!("{table}.{key}");
            let sim_has = simulation.as_ref().map(|s| s.contains(&field));
            let linear_has = linear.as_ref().map(|l| l.contains(&field));
            if read.contains(&field) {
                if linear_has == Some(false) && sim_has == Some(true) && !RUN_TABLES.contains(table) && !neutral(root, table, key, value) {
                    classes.push((1, Unused { key: field, why: String::new() }));
                } else {
                    any_read = true;
                }
                continue;
            }
            // before the neutral values: `delta_a = 0` beside the masses is ΔĀ = 0, not the
            // masses' anisotropy (read by the linear model, it is in `read` above)
            if linear_only.contains(&field) {
                classes.push((3, Unused { key: field, why: String::new() }));
                continue;
            }
            if neutral(root, table, key, value) {
                any_read = true; // a neutral entry keeps the others from reading as the whole table
                continue;
            }
            if !models.iter().any(|m| m.owns(table, key)) {
                let owner = match (*table, key.as_str()) {
                    ("planar", _) => "belongs to the planar rotor of paper 004 ([planar] configs)".to_string(),
                    ("drive", "xy0" | "xy_rate0") => "is the planar rotor's start; the spatial rotor starts from [initial]".to_string(),
                    _ => "belongs to the spatial rotor of papers 000/003".to_string(),
                };
                classes.push((0, Unused { key: field, why: owner }));
            } else if only_linear && RUN_TABLES.contains(table) {
                any_read = true;
            } else if only_linear && sim_has != Some(false) && !moot.contains_key(&field) {
                classes.push((1, Unused { key: field, why: String::new() }));
            } else {
                let why = moot.get(&field).cloned().unwrap_or_else(|| "not used with the rest of this config".to_string());
                classes.push((2, Unused { key: field, why }));
            }
        }
        let whole = !any_read && classes.len() == t.len() && t.len() > 1 && classes.iter().all(|(c, _)| *c == classes[0].0 && *c < 2);
        if whole {
            let (c, first) = classes.swap_remove(0);
            classes = vec![(c, Unused { key: format!("[{table}]"), why: first.why })];
        }
        for (c, u) in classes {
            match c {
                0 => out.foreign.push(u),
                1 => out.simulation_only.push(u.key),
                3 => out.linear_only.push(u.key),
                _ => out.moot.push(u),
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A number written with a unit (walk 27: `drive.omega0 = "1400 rpm"` read "expected a
    /// number, got the string …"): the message says numbers carry no unit, which keys read
    /// one, and what a speed's string is in rad/s (1400·π/30 = 146.608 rad/s); a number in a
    /// string, or a word, keeps the plain message.
    #[test]
    fn a_number_with_a_unit_is_told_that_numbers_carry_none() {
        let e = number(&Value::String("1400 rpm".into()), "drive.omega0").unwrap_err().to_string();
        assert_eq!(
            e,
            "drive.omega0: expected a bare number, got the string \"1400 rpm\": numbers here carry no unit (SI in a dimensional config: kg, m, s, N/m, N s/m, rad/s; dimensionless ones in a [dimensionless] config; only analysis.operating_speed and analysis.omega_max of a dimensional config read units); as an SI speed, 1400 rpm = 146.608 rad/s"
        );
        let e = number(&Value::String("2e5 N/m".into()), "supports.stiffness_left").unwrap_err().to_string();
        assert!(
            e.starts_with("supports.stiffness_left: expected a bare number, got the string \"2e5 N/m\": numbers here carry no unit")
                && e.ends_with("read units)"),
            "{e}"
        );
        assert_eq!(number(&Value::String("0.08".into()), "x").unwrap_err().to_string(), "x: expected a number, got the string \"0.08\"");
        assert_eq!(number(&Value::String("fast".into()), "x").unwrap_err().to_string(), "x: expected a number, got the string \"fast\"");
        for plain in ["-", ".", "1,5", "e5"] {
            assert!(number(&Value::String(plain.into()), "x").unwrap_err().to_string().starts_with("x: expected a number, got"), "{plain}");
        }
        assert!(number(&Value::String("  +3 rpm".into()), "x").unwrap_err().to_string().ends_with("as an SI speed, 3 rpm = 0.314159 rad/s"));
        // a long string is not searched for a speed (quadratic): the plain message
        assert!(number(&Value::String("1".repeat(200) + " rpm"), "x").unwrap_err().to_string().starts_with("x: expected a number, got"));
        assert_eq!(crate::units::speed_hint("25 Hz").as_deref(), Some("25 Hz = 157.08 rad/s"));
        assert_eq!(crate::units::speed_hint("157 rad/s"), None);
    }

    #[test]
    fn the_defaults_are_the_presets() {
        // the embedded configs and the library's presets describe the same runs
        let p = planar(&parse(DEFAULT_PLANAR, "planar").unwrap()).unwrap();
        assert_eq!(p, PlanarProblem::default());
        let c = spatial(&parse(DEFAULT_SPATIAL, "default").unwrap()).unwrap();
        assert_eq!(c.model, SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap());
        // the library's defaults of the spatial model in time describe examples/spatial.toml's run
        let sim = spatial_simulation(&parse(include_str!("../../../examples/spatial.toml"), "spatial.toml").unwrap()).unwrap();
        assert_eq!(sim.rotor, crate::spatial::dynamics::SpatialRotor::default());
        assert_eq!(sim.settings, crate::spatial::dynamics::Settings::default());
        assert_eq!(sim.drive, Drive::Speed { omega0: 1.6 });
    }

    #[test]
    fn speeds_in_analysis_take_units_and_the_operating_speed_drives_the_defaults() {
        let washer = include_str!("../../../examples/washing_machine.toml");
        let mut root = parse(washer, "washer").unwrap();
        let c = spatial(&root).unwrap();
        let w0 = c.model.scale.unwrap().omega0;
        // 1400 rpm = 1400 π/30 rad/s, over ω0 (one product and one division: 1e-15 relative)
        let op = 1400.0 * std::f64::consts::PI / 30.0 / w0;
        let [lo, hi] = c.analysis.operating_speed.unwrap();
        assert!((lo - op).abs() < 1e-15 * op && lo == hi, "{lo} {op}");
        // the automatic axis covers 1.25 × the operating speed; the critical speeds' 1.3 × do not
        let auto = crate::reports::default_omega_max(&c.model);
        assert!(auto < op && c.analysis.speed_axis_max(auto) == OPERATING_SPEED_MARGIN * hi);
        // the default run-up ends at it: b t_end = ω_op (rad/s)
        let sim = spatial_simulation(&root).unwrap();
        let Drive::Acceleration { omega0, b } = sim.drive else { panic!("{:?}", sim.drive) };
        assert_eq!(omega0, 0.0);
        assert!((b * sim.settings.t_end - op * w0).abs() < 1e-12 * op * w0);
        // a range, and omega_max in Hz or as a bare Ω
        set(&mut root, "analysis.operating_speed", parse_value("\"20-25 Hz\"")).unwrap();
        set(&mut root, "analysis.omega_max", parse_value("\"30 Hz\"")).unwrap();
        let a = spatial(&root).unwrap().analysis;
        let hz = |f: f64| 2.0 * std::f64::consts::PI * f / w0;
        assert_eq!(a.operating_speed, Some([hz(20.0), hz(25.0)]));
        assert_eq!(a.omega_max, Some(hz(30.0)));
        assert_eq!(a.speed_axis_max(0.1), hz(30.0), "a given omega_max is kept");
        set(&mut root, "analysis.omega_max", parse_value("5.2")).unwrap();
        assert_eq!(spatial(&root).unwrap().analysis.omega_max, Some(5.2));
        // errors name the key, on one line
        for (v, why) in [("\"fast\"", "is not a speed"), ("\"0 rpm\"", "must lie in (0, 1e6]"), ("-1", "must lie in (0, 1e6]"), ("[1, 2]", "expected a speed")]
        {
            set(&mut root, "analysis.omega_max", parse_value(v)).unwrap();
            let e = spatial(&root).unwrap_err().to_string();
            assert!(e.starts_with("analysis.omega_max: ") && e.contains(why) && !e.contains('\n'), "{v}: {e}");
        }
    }

    /// `delta_a` and `d_a` beside the masses are inputs of the 12-state linear model only
    /// (review 25b R4): the spatial simulation reads them (their checks apply) but its rotor's
    /// inertia and balls are the masses', so on the simulation alone they are
    /// [`EntryUse::linear_only`], neither used nor moot (session 26 reported them as of no
    /// effect, which is false where the run takes the linear model's defaults: the next test);
    /// where the linear model runs they are used. `delta_a = 0` is ΔĀ = 0, not a neutral value.
    #[test]
    fn delta_a_beside_the_masses_is_an_input_of_the_linear_model_only() {
        let mut root = parse(DEFAULT_SPATIAL, "default").unwrap();
        set(&mut root, "dimensionless.delta_a", 0.1.into()).unwrap();
        // n = 2 at E = 2: the balancing positions give D_A = |2/E² − 1| = 0.5, the only value taken
        set(&mut root, "dimensionless.d_a", 0.5.into()).unwrap();
        let u = entry_use(&root, &[Model::Spatial]);
        assert_eq!(u.linear_only, ["dimensionless.d_a", "dimensionless.delta_a"]);
        assert!(u.foreign.is_empty() && u.simulation_only.is_empty() && u.moot.is_empty(), "{u:?}");
        assert!(entry_use(&root, &[Model::Linear]).is_empty());
        assert!(entry_use(&root, &[Model::Linear, Model::Spatial]).is_empty());
        set(&mut root, "dimensionless.delta_a", 0.0.into()).unwrap();
        assert_eq!(entry_use(&root, &[Model::Spatial]).linear_only, ["dimensionless.d_a", "dimensionless.delta_a"]);
        // ΔĀ given directly, no masses: the simulation cannot be built (it needs the masses),
        // and the linear model uses both
        let mut direct = parse(DEFAULT_SPATIAL, "default").unwrap();
        let d = direct.get_mut("dimensionless").and_then(Value::as_table_mut).unwrap();
        for k in ["m0", "r0", "r", "n"] {
            d.remove(k);
        }
        d.insert("delta_a".into(), 0.1.into());
        d.insert("d_a".into(), 0.5.into());
        assert!(spatial_simulation(&direct).is_err());
        assert!(entry_use(&direct, &[Model::Linear]).is_empty());
        assert!(entry_use(&direct, &[Model::Spatial]).is_empty());
    }

    /// What `delta_a` and `d_a` beside the masses set in the spatial simulation (review 25b R4,
    /// measured): with a `[drive]`, nothing (the rotor, drive, start and settings are those of
    /// the config without them); without one, where the default run-up ends: 1.3 times the
    /// highest critical speed of the linear model, whose ΔĀ they move (Ω 3.85 → 4.94 here), and
    /// nothing else: the config without them, told to end the run-up there
    /// (`analysis.omega_max`), runs the same run.
    #[test]
    fn delta_a_beside_the_masses_sets_only_the_default_run_ups_end() {
        let given = parse(include_str!("../../../examples/spatial.toml"), "spatial").unwrap();
        let mut keys = given.clone();
        set(&mut keys, "dimensionless.delta_a", 0.1.into()).unwrap();
        set(&mut keys, "dimensionless.d_a", 0.5.into()).unwrap();
        let sim = |t: &Table| spatial_simulation(t).unwrap();
        let (a, b) = (sim(&given), sim(&keys));
        // the linear model's anisotropy moved (the masses': 0, 000's base case is isotropic)
        assert!((a.config.model.anisotropy.used - b.config.model.anisotropy.used).abs() > 0.05);
        assert!(!b.default_drive);
        assert_eq!((&a.rotor, &a.drive, &a.initial, &a.settings), (&b.rotor, &b.drive, &b.initial, &b.settings));
        // no [drive]: the default run-up
        let (mut bare, mut bare_keys) = (given.clone(), keys.clone());
        bare.remove("drive");
        bare_keys.remove("drive");
        let (a, b) = (sim(&bare), sim(&bare_keys));
        assert!(a.default_drive && b.default_drive);
        assert_eq!((&a.rotor, &a.initial), (&b.rotor, &b.initial));
        let end = |s: &SpatialSimulation| s.drive.kinematics(s.settings.t_end).0;
        // 1.3 times the linear model's highest critical speed (eq (16)), to the rounding of
        // b·t_end (a few ulp)
        let top =
            |s: &SpatialSimulation| 1.3 * crate::spatial::critical_speeds::critical_speeds(&s.config.model).speeds.iter().map(|c| c.omega).fold(1.0, f64::max);
        for s in [&a, &b] {
            assert!((end(s) / top(s) - 1.0).abs() < 1e-14, "{} {}", end(s), top(s));
        }
        assert!(end(&b) / end(&a) > 1.2, "Ω_end {} with the keys, {} without", end(&b), end(&a));
        // told to end where theirs ends, the config without them runs their run
        let mut told = bare.clone();
        set(&mut told, "analysis.omega_max", end(&b).into()).unwrap();
        let c = sim(&told);
        assert_eq!((&c.rotor, &c.initial), (&b.rotor, &b.initial));
        let (Drive::Acceleration { omega0: w_c, b: b_c }, Drive::Acceleration { omega0: w_b, b: b_b }) = (&c.drive, &b.drive) else {
            panic!("the default run-up accelerates: {:?} {:?}", c.drive, b.drive)
        };
        // the same to the rounding of the end speed read back as b·t_end (a few ulp)
        let near = |x: f64, y: f64| (x - y).abs() <= 1e-14 * y.abs();
        assert!(*w_c == 0.0 && *w_b == 0.0 && near(*b_c, *b_b), "{b_c} {b_b}");
        assert!(near(c.settings.t_end, b.settings.t_end) && c.settings.dt == b.settings.dt, "{:?} {:?}", c.settings, b.settings);
        assert_eq!((c.settings.method, c.settings.rtol, c.settings.atol), (b.settings.method, b.settings.rtol, b.settings.atol));
    }

    /// One test per class of [`entry_use`], on the three models.
    #[test]
    fn every_entry_is_used_or_classed() {
        let with = |text: &str, sets: &[(&str, &str)]| {
            let mut root = parse(text, "t").unwrap();
            for (k, v) in sets {
                set(&mut root, k, parse_value(v)).unwrap();
            }
            root
        };
        let keys = |u: &[Unused]| u.iter().map(|u| u.key.clone()).collect::<Vec<_>>();
        // the examples use every entry with the models that run them
        assert!(entry_use(&parse(DEFAULT_PLANAR, "p").unwrap(), &[Model::Planar]).is_empty());
        let two = include_str!("../../../examples/spatial_two_plane.toml");
        assert!(entry_use(&parse(two, "two").unwrap(), &[Model::Spatial]).is_empty());
        let one = include_str!("../../../examples/spatial.toml");
        assert!(entry_use(&parse(one, "one").unwrap(), &[Model::Linear]).is_empty());
        // foreign: the spatial rotor's tables on the planar rotor, and the reverse
        let u = entry_use(&with(DEFAULT_PLANAR, &[("spatial.gravity", "[0, -9.81, 0]"), ("initial.position", "[1e-3, 0]")]), &[Model::Planar]);
        assert_eq!(keys(&u.foreign), ["spatial.gravity", "initial.position"]);
        assert!(u.foreign[0].why.contains("spatial rotor"));
        let u = entry_use(&with(one, &[("planar.m1", "1"), ("planar.k", "1e5"), ("drive.xy0", "[1e-3, 0]")]), &[Model::Spatial]);
        assert_eq!(keys(&u.foreign), ["[planar]", "drive.xy0"]);
        assert!(u.foreign[1].why.contains("[initial]"), "{:?}", u.foreign);
        // neutral values are nothing to report, wherever they are
        assert!(entry_use(&with(DEFAULT_PLANAR, &[("spatial.gravity", "[0, 0, 0]"), ("spatial.lock_tilt", "false")]), &[Model::Planar]).is_empty());
        // moot: a second plane with no balls but a ball mass; real-ball keys without contact
        let u = entry_use(&with(two, &[("balancer2.balls", "0"), ("balancer2.ball_mass", "0")]), &[Model::Spatial]);
        assert_eq!(keys(&u.moot), ["balancer2.drag", "balancer2.race_radius"]);
        // (with a ball mass it is the build's error, as on the first plane: nothing to sort)
        assert!(entry_use(&with(two, &[("balancer2.balls", "0")]), &[Model::Spatial]).is_empty());
        assert_eq!(u.moot[0].why, "with balancer2.balls = 0");
        let u = entry_use(&with(DEFAULT_PLANAR, &[("planar.ball_diameter", "0.01"), ("planar.slip_rate", "1e-3")]), &[Model::Planar]);
        assert_eq!(keys(&u.moot), ["planar.ball_diameter", "planar.slip_rate"]);
        assert_eq!(u.moot[1].why, "with planar.rolling_resistance = 0");
        // what the simulation uses and the linear model does not; a run's settings are silent
        // for the linear model, used by the simulation
        let root = with(one, &[("initial.position", "[0.1, 0]"), ("spatial.lock_tilt", "true")]);
        let u = entry_use(&root, &[Model::Linear]);
        assert_eq!(u.simulation_only, ["spatial.lock_tilt"]);
        assert!(u.foreign.is_empty() && u.moot.is_empty());
        assert!(entry_use(&root, &[Model::Spatial]).is_empty());
        // the report runs both: the linear sections' omissions are still named, as the linear
        // model alone names them
        assert_eq!(entry_use(&root, &[Model::Linear, Model::Spatial]).simulation_only, ["spatial.lock_tilt"]);
        let two = parse(two, "two").unwrap();
        assert_eq!(entry_use(&two, &[Model::Linear, Model::Spatial]).simulation_only, entry_use(&two, &[Model::Linear]).simulation_only);
    }

    #[test]
    fn values_parse_as_typed() {
        assert_eq!(parse_value("1.5"), Value::Float(1.5));
        assert_eq!(parse_value("2"), Value::Integer(2));
        assert_eq!(parse_value("paper"), Value::String("paper".into()));
        assert_eq!(parse_value("\"paper\""), Value::String("paper".into()));
        let mut t = Table::new();
        set_number(&mut t, "planar.n", 3.0).unwrap();
        assert_eq!(t["planar"]["n"], Value::Integer(3));
        assert!(set_number(&mut t, "planar", 3.0).unwrap_err().to_string().starts_with("planar: expected a dotted key"));
        let e = parse("[planar]\nm1 = = 2", "my.toml").unwrap_err().to_string();
        assert!(e.starts_with("my.toml: line 2:"), "{e}");
    }
}
