//! Parameter paths of a linear rotor config (`[linear_rotor]`, issue 19): a [`LinearRotorSpec`]
//! is the config's tables with the bytes of its matrix files (read once, by the front end), and
//! a point of a map or a sweep is that config with numbers set at paths, read again by
//! [`super::config::linear_rotor_bytes`] as `simulate` and `stability` read it, so that every
//! value a path takes is checked (and its error named) as the config's own.
//!
//! The paths ([`PATHS`], [`crate::paths`]' style; each acts on the config's tables):
//!
//! | path | what it sets |
//! |---|---|
//! | `linear_rotor.ball_mass`, `.radius`, `.drag`, `.balls` | that key of **every** `[[linear_rotor.balancer]]` |
//! | `linear_rotor.balancer[j].KEY` | that key of balancer plane `j` alone (`node`, `radius`, `balls`, `ball_mass`, `drag`, `offset`, `ball_diameter`, `restitution`, `contact_stiffness`, `rolling_resistance`, `slip_rate`) |
//! | `linear_rotor.me` | `me` of the config's only `[[linear_rotor.unbalance]]` |
//! | `linear_rotor.unbalance[j].KEY` | that key of unbalance `j` alone (`node`, `me`, `phase`, `offset`) |
//! | `linear_rotor.elements[j].KEY` | that key of the shaft builder's `[[linear_rotor.elements]]` entry `j` (every one of its `count` elements: `length`, `diameter`, `inner_diameter`, `area`, `inertia`, `e`, `rho`, `g_s`, `kappa`, `count`) |
//! | `linear_rotor.disks[j].KEY` | that key of disk `j` (`node`, `mass`, `id`, `ip`) |
//! | `linear_rotor.bearings[j].KEY` | that key of bearing `j` (`node`, `link`, `k`, `c`); `linear_rotor.bearings[j].kxx[i]`: entry `i` of its table over speed (`speeds`, `kxx`, …, `cyy`) |
//! | `linear_rotor.unbalance_scale` | a factor on every unbalance's `me` |
//! | `linear_rotor.support_stiffness_scale` | a factor on every `[[linear_rotor.bearings]]`' stiffness (`k`, or the tables `kxx`, `kxy`, `kyx`, `kyy`) |
//! | `linear_rotor.support_damping_scale` | the same on their damping (`c`, `cxx`, …) |
//! | `linear_rotor.polar_inertia`, `.spin_damping`, `.omega_max`, `.modes` | that key of `[linear_rotor]` |
//! | `drive.KEY`, `integration.KEY` | a number of `[drive]` (`omega0`, `b`, `torque`, `omega_idle`, `t_off`, `t_end`) or `[integration]` (`dt`, `rtol`, `atol`, `max_steps`, `max_wall_s`) |
//!
//! The index `j` counts the config's `[[linear_rotor.balancer]]` (or `unbalance`, `elements`, …) tables from 0, in
//! their order, as the config's own errors name them (`linear_rotor.balancer[0].ball_mass`) and
//! as nodes are numbered; an index past the last is an error naming the path and the count.
//! `node`, `link`, `balls` and `count` take whole numbers.
//!
//! A map's speed axis is `omega` or `speed` (rad/s), `speed_rpm`, `speed_hz`
//! ([`crate::units::SPEED_PATHS`]). Bearings inside matrix files are part of `K`, `C`: the scales
//! act on the bearings the config lists, and a config without any is an error naming the path.
//!
//! ```
//! use autobal::linear_rotor::spec::LinearRotorSpec;
//! let text = "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.02\ne = 2.1e11\nrho = 7850.0\ncount = 4\n\
//!             [[linear_rotor.bearings]]\nnode = 0\nk = 1e6\n[[linear_rotor.bearings]]\nnode = 4\nk = 1e6\n\
//!             [[linear_rotor.balancer]]\nnode = 2\nradius = 0.05\nballs = 2\nball_mass = 0.01\n";
//! let spec = LinearRotorSpec::new(toml::from_str(text).unwrap(), &mut |_| Err("no files".into())).unwrap();
//! let cfg = spec.config_at(&[("linear_rotor.ball_mass", 0.02), ("linear_rotor.support_stiffness_scale", 2.0)]).unwrap();
//! assert_eq!(cfg.rotor.balancers[0].ball_mass, 0.02);
//! let e = spec.config_at(&[("linear_rotor.nope", 1.0)]).unwrap_err().to_string();
//! assert!(e.starts_with("linear_rotor.nope: unknown parameter path"));
//! // one plane of several: the config's own index, from 0
//! let cfg = spec.config_at(&[("linear_rotor.balancer[0].drag", 0.3)]).unwrap();
//! assert_eq!(cfg.rotor.balancers[0].drag, 0.3);
//! let e = spec.config_at(&[("linear_rotor.balancer[1].drag", 0.3)]).unwrap_err().to_string();
//! assert!(e.starts_with("linear_rotor.balancer[1].drag: the config has 1 [[linear_rotor.balancer]]"), "{e}");
//! ```

use super::config::{linear_rotor_bytes, LinearRotorConfig};
use super::runup::RunSettings;
use super::LinearRotor;
use crate::drive::Drive;
use crate::error::{fmt_num, Error, Result};
use crate::paths::whole;
use std::collections::BTreeMap;
use toml::{Table, Value};

/// Every parameter path of a linear rotor config with what it sets (module docs); `drive.KEY`
/// and `integration.KEY` are listed as such.
pub const PATHS: &[(&str, &str)] = &[
    ("linear_rotor.ball_mass", "mass of one ball m_b (kg), in every balancer plane"),
    ("linear_rotor.radius", "race radius R (m), in every balancer plane"),
    ("linear_rotor.drag", "viscous drag per ball c_b (N m s), in every balancer plane"),
    ("linear_rotor.balls", "number of balls n (whole), in every balancer plane"),
    ("linear_rotor.balancer[j].KEY", "KEY of balancer plane j alone (from 0): node, radius, balls, ball_mass, drag, offset, ball_diameter, restitution, contact_stiffness, rolling_resistance, slip_rate"),
    ("linear_rotor.me", "m·e (kg m) of the config's only unbalance"),
    ("linear_rotor.unbalance[j].KEY", "KEY of unbalance j alone (from 0): node, me, phase, offset"),
    ("linear_rotor.elements[j].KEY", "KEY of the shaft builder's element entry j (from 0; all its count elements): length, diameter, inner_diameter, area, inertia, e, rho, g_s, kappa, count"),
    ("linear_rotor.disks[j].KEY", "KEY of disk j (from 0): node, mass, id, ip"),
    ("linear_rotor.bearings[j].KEY", "KEY of bearing j (from 0): node, link, k, c; one number of its table over speed as speeds[i], kxx[i], …, cyy[i]"),
    ("linear_rotor.unbalance_scale", "factor on every unbalance's m·e"),
    ("linear_rotor.support_stiffness_scale", "factor on the stiffness of every [[linear_rotor.bearings]] (k or kxx, kxy, kyx, kyy)"),
    ("linear_rotor.support_damping_scale", "factor on the damping of every [[linear_rotor.bearings]] (c or cxx, cxy, cyx, cyy)"),
    ("linear_rotor.polar_inertia", "polar moment of inertia I_p (kg m²) for torque drives"),
    ("linear_rotor.spin_damping", "drag on the spin c_θ (N m s)"),
    ("linear_rotor.omega_max", "top of the speed axis (rad/s)"),
    ("linear_rotor.modes", "interior mode pairs of the reduction (whole; 0: the full model)"),
    ("drive.KEY", "omega0, b, torque, omega_idle, t_off, t_end"),
    ("integration.KEY", "dt, rtol, atol, max_steps, max_wall_s"),
];

const DRIVE_KEYS: &[&str] = &["omega0", "b", "torque", "omega_idle", "t_off", "t_end"];
const INTEGRATION_KEYS: &[&str] = &["dt", "rtol", "atol", "max_steps", "max_wall_s"];
/// The numbers of one `[[linear_rotor.balancer]]` a path `linear_rotor.balancer[j].KEY` sets
/// (`contact`, a boolean, is not a number).
const BALANCER_KEYS: &[&str] =
    &["node", "radius", "balls", "ball_mass", "drag", "offset", "ball_diameter", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"];
/// The numbers of one `[[linear_rotor.unbalance]]` (`linear_rotor.unbalance[j].KEY`).
const UNBALANCE_KEYS: &[&str] = &["node", "me", "phase", "offset"];
/// The numbers of one `[[linear_rotor.elements]]` of the shaft builder
/// (`linear_rotor.elements[j].KEY`; `count` whole).
const ELEMENT_KEYS: &[&str] = &["length", "diameter", "inner_diameter", "area", "inertia", "e", "rho", "g_s", "kappa", "count"];
/// The numbers of one `[[linear_rotor.disks]]` (`linear_rotor.disks[j].KEY`).
const DISK_KEYS: &[&str] = &["node", "mass", "id", "ip"];
/// The numbers of one constant `[[linear_rotor.bearings]]` (`linear_rotor.bearings[j].KEY`).
const BEARING_KEYS: &[&str] = &["node", "link", "k", "c"];
/// The tables over speed of one `[[linear_rotor.bearings]]`, whose entries are set one at a time
/// (`linear_rotor.bearings[j].kxx[i]`, `i` from 0).
const BEARING_TABLE_KEYS: &[&str] = &["speeds", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"];
/// The most elements one `[[linear_rotor.elements]]` repeats (`count`, as the config reads it).
const MAX_ELEMENT_COUNT: u64 = 10_000;
/// The arrays of tables of `[linear_rotor]` whose entries' numbers a path `linear_rotor.KIND[j].KEY`
/// sets, with their keys.
const ENTRY_KEYS: &[(&str, &[&str])] =
    &[("balancer", BALANCER_KEYS), ("unbalance", UNBALANCE_KEYS), ("elements", ELEMENT_KEYS), ("disks", DISK_KEYS), ("bearings", BEARING_KEYS)];

/// A linear rotor config and the bytes of the matrix files it names (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearRotorSpec {
    root: Table,
    files: BTreeMap<String, Vec<u8>>,
}

impl LinearRotorSpec {
    /// The config `root` (it must read as it is), its files read once through `load`.
    pub fn new(root: Table, load: &mut dyn FnMut(&str) -> std::result::Result<Vec<u8>, String>) -> Result<Self> {
        let mut files = BTreeMap::new();
        linear_rotor_bytes(&root, &mut |p| {
            let b = load(p)?;
            files.insert(p.to_string(), b.clone());
            Ok(b)
        })?;
        Ok(LinearRotorSpec { root, files })
    }

    /// The config's tables.
    pub fn root(&self) -> &Table {
        &self.root
    }

    /// The bytes of the matrix files the config names, by the name it gives them (what a
    /// process without the files needs, with [`LinearRotorSpec::root`], to rebuild the spec).
    pub fn files(&self) -> &BTreeMap<String, Vec<u8>> {
        &self.files
    }

    /// The config with every `(path, value)` set, read again; errors name the path (and the
    /// value where the config refuses it). The values are set in [`precedence`] order, whatever
    /// the order of `set`: the values for every entry, then one entry's, then the factors, so
    /// that a point of a map or a sweep is the same whichever axis is `x`.
    pub fn config_at(&self, set: &[(&str, f64)]) -> Result<LinearRotorConfig> {
        let mut root = self.root.clone();
        let mut ordered: Vec<&(&str, f64)> = set.iter().collect();
        // stable: paths of one rank keep their order (they touch different numbers)
        ordered.sort_by_key(|(p, _)| precedence(p));
        for (p, v) in ordered {
            set_path(&mut root, p, *v)?;
        }
        linear_rotor_bytes(&root, &mut |p| self.files.get(p).cloned().ok_or_else(|| format!("{p}: not among the files read with the config"))).map_err(|e| {
            match set {
                [(p, v)] if e.field() != Some(*p) => Error::invalid(*p, format!("at {p} = {}: {e}", fmt_num(*v))),
                _ => e,
            }
        })
    }

    /// The model the analyses run at that point ([`model`]).
    pub fn model_at(&self, set: &[(&str, f64)]) -> Result<LinearRotor> {
        model(&self.config_at(set)?)
    }
}

/// The rotor the analyses run on a config: its rotor, or the reduction to `linear_rotor.modes`
/// interior mode pairs ([`super::reduce::reduce`], as `stability` and `simulate` run it).
pub fn model(cfg: &LinearRotorConfig) -> Result<LinearRotor> {
    match cfg.modes {
        None => Ok(cfg.rotor.clone()),
        Some(p) => Ok(super::reduce::reduce(&cfg.rotor, p, &[])?.rotor),
    }
}

/// One run of `simulate` on a config: the model ([`model`]), the drive and the solver settings.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearRun {
    /// The model integrated.
    pub rotor: LinearRotor,
    /// The drive: `[drive]`, or from rest to [`default_omega_max`] at constant acceleration in
    /// 1000 revolutions (`φ = ½ b t² = 2π·1000` at `Ω = b t = ω_max`).
    pub drive: Drive,
    /// `t_end`, `dt` (`integration.dt`, or `t_end/2000` with the default drive), tolerances,
    /// budgets; the physical nodes of a reduction.
    pub settings: RunSettings,
    /// Whether the drive is the default run-up.
    pub default_drive: bool,
}

/// The top of the speed axis: `linear_rotor.omega_max`, else 1.5 × the highest undamped natural
/// frequency (balls as rings, at rest) among the lowest four, at least 3 × the first.
pub fn default_omega_max(cfg: &LinearRotorConfig) -> Result<f64> {
    if let Some(w) = cfg.omega_max {
        return Ok(w);
    }
    let w = cfg.rotor.at_speed(0.0).natural_frequencies(&[], true)?;
    let pos: Vec<f64> = w.into_iter().filter(|v| *v > 0.0).collect();
    let first =
        *pos.first().ok_or_else(|| Error::invalid("linear_rotor.omega_max", "the rotor has no positive natural frequency: give linear_rotor.omega_max"))?;
    Ok((1.5 * pos[pos.len().min(4) - 1]).max(3.0 * first))
}

/// The run `autobal simulate` makes on `cfg` (without `--dt`).
pub fn run_of(cfg: &LinearRotorConfig) -> Result<LinearRun> {
    let (drive, t_end, default_drive) = match &cfg.drive {
        Some((d, t)) => (d.clone(), *t, false),
        None => {
            let w = default_omega_max(cfg)?;
            let t_end = 2.0 * std::f64::consts::TAU * 1000.0 / w;
            (Drive::Acceleration { omega0: 0.0, b: w / t_end }, t_end, true)
        }
    };
    let (rotor, physical_nodes) = match cfg.modes {
        None => (cfg.rotor.clone(), None),
        Some(p) => {
            let r = super::reduce::reduce(&cfg.rotor, p, &[])?;
            let nodes = r.boundary.len();
            (r.rotor, Some(nodes))
        }
    };
    let ig = &cfg.integration;
    let settings = RunSettings {
        t_end,
        dt: if default_drive { t_end / 2000.0 } else { ig.dt },
        rtol: ig.rtol,
        atol: ig.atol,
        method: ig.method,
        max_steps: ig.max_steps.unwrap_or(10_000_000),
        max_wall_s: ig.max_wall_s,
        physical_nodes,
    };
    Ok(LinearRun { rotor, drive, settings, default_drive })
}

/// Set `path` to `value` in the config's tables (module docs); an unknown path is an error
/// naming it and listing the known ones.
pub fn set_path(root: &mut Table, path: &str, value: f64) -> Result<()> {
    let bad = |why: String| Error::invalid(path, why);
    if !value.is_finite() {
        return Err(bad(format!("{} is not a finite value", fmt_num(value))));
    }
    let (table, key) = path.split_once('.').unwrap_or((path, ""));
    let unknown = || {
        let known: Vec<&str> = PATHS.iter().map(|p| p.0).collect();
        Error::invalid(path, format!("unknown parameter path (known: omega, speed, speed_rpm, speed_hz, {})", known.join(", ")))
    };
    match table {
        "drive" | "integration" => {
            let keys = if table == "drive" { DRIVE_KEYS } else { INTEGRATION_KEYS };
            if !keys.contains(&key) {
                return Err(unknown());
            }
            let t = root.entry(table.to_string()).or_insert_with(|| Value::Table(Table::new()));
            let t = t.as_table_mut().ok_or_else(|| bad(format!("`{table}` is not a table")))?;
            t.insert(key.to_string(), Value::Float(value));
            Ok(())
        }
        "linear_rotor" => {
            let lr = root.get_mut("linear_rotor").and_then(Value::as_table_mut).ok_or_else(|| bad("the config has no [linear_rotor] table".into()))?;
            if let Some((item, field)) = key.split_once('.') {
                return set_entry(lr, path, item, field, value).unwrap_or_else(|| Err(unknown()));
            }
            match key {
                "ball_mass" | "radius" | "drag" => each(lr, "balancer", path)?.iter_mut().try_for_each(|t| insert(t, key, Value::Float(value), path)),
                "balls" => {
                    let n = whole(value, crate::planar::MAX_BALLS as u64).map_err(bad)?;
                    each(lr, "balancer", path)?.iter_mut().try_for_each(|t| insert(t, key, Value::Integer(n as i64), path))
                }
                "me" => {
                    let u = each(lr, "unbalance", path)?;
                    if u.len() != 1 {
                        return Err(bad(format!(
                            "the config has {} unbalances: set one with linear_rotor.unbalance[j].me (j from 0), or scale them together with linear_rotor.unbalance_scale",
                            u.len()
                        )));
                    }
                    insert(&mut u[0], "me", Value::Float(value), path)
                }
                "unbalance_scale" => scale(each(lr, "unbalance", path)?, &["me"], value, path),
                "support_stiffness_scale" => scale(each(lr, "bearings", path)?, &["k", "kxx", "kxy", "kyx", "kyy"], value, path),
                "support_damping_scale" => scale(each(lr, "bearings", path)?, &["c", "cxx", "cxy", "cyx", "cyy"], value, path),
                "polar_inertia" | "spin_damping" | "omega_max" => {
                    lr.insert(key.to_string(), Value::Float(value));
                    Ok(())
                }
                "modes" => {
                    let n = whole(value, super::MAX_DOFS as u64).map_err(bad)?;
                    lr.insert(key.to_string(), Value::Integer(n as i64));
                    Ok(())
                }
                _ => Err(unknown()),
            }
        }
        _ => Err(unknown()),
    }
}

/// The rank of `path` in the order [`LinearRotorSpec::config_at`] sets several paths, so that
/// two paths touching one number give the same point in either order (a map at
/// `bearings[0].k = 1e6`, `support_stiffness_scale = 3` gave −0.0365 one way round and +3.648
/// the other): 0, a value for every entry of a kind (`linear_rotor.ball_mass`, `.radius`,
/// `.drag`, `.balls`, `.me`); 1, the rest (one entry's value, `balancer[j].drag`,
/// `bearings[j].k`, `unbalance[j].me`, a table's entry, `[drive]`, …), which thus overrides the
/// value for every entry; 2, the factors (`unbalance_scale`, `support_stiffness_scale`,
/// `support_damping_scale`), which thus scale the values set at the point.
pub fn precedence(path: &str) -> u8 {
    match path.strip_prefix("linear_rotor.") {
        Some("ball_mass" | "radius" | "drag" | "balls" | "me") => 0,
        Some("unbalance_scale" | "support_stiffness_scale" | "support_damping_scale") => 2,
        _ => 1,
    }
}

/// Set the one boolean of a `[[linear_rotor.balancer]]`, `linear_rotor.balancer[j].contact`
/// (the balls touch: [`crate::balls::BallPhysics::contact`]), which [`set_path`] cannot take
/// (its values are numbers). Errors name `path`: another path, an index past the entries.
pub fn set_contact(root: &mut Table, path: &str, value: bool) -> Result<()> {
    let bad = |why: String| Error::invalid(path, why);
    let j = path
        .strip_prefix("linear_rotor.balancer[")
        .and_then(|s| s.strip_suffix("].contact"))
        .ok_or_else(|| bad("only linear_rotor.balancer[j].contact takes true or false".into()))?;
    let j = index(j).ok_or_else(|| bad(format!("the index in [{j}] must be a whole number from 0 (the first [[linear_rotor.balancer]])")))?;
    let lr = root.get_mut("linear_rotor").and_then(Value::as_table_mut).ok_or_else(|| bad("the config has no [linear_rotor] table".into()))?;
    let entries = each(lr, "balancer", path)?;
    let n = entries.len();
    let entry = entries.get_mut(j).ok_or_else(|| bad(format!("the config has {n} [[linear_rotor.balancer]] (j from 0 to {})", n - 1)))?;
    insert(entry, "contact", Value::Boolean(value), path)
}

/// Set `field` of one entry `item` (`KIND[j]`, `j` from 0, `KIND` one of [`ENTRY_KEYS`]) of
/// `[linear_rotor]`; `None` where `item` is not of that form (the caller then lists the known
/// paths).
fn set_entry(lr: &mut Table, path: &str, item: &str, field: &str, value: f64) -> Option<Result<()>> {
    let (kind, j) = item.strip_suffix(']').and_then(|s| s.split_once('['))?;
    let (_, keys) = ENTRY_KEYS.iter().find(|(k, _)| *k == kind)?;
    Some(set_entry_of(lr, path, kind, keys, j, field, value))
}

fn set_entry_of(lr: &mut Table, path: &str, kind: &str, keys: &[&str], j: &str, field: &str, value: f64) -> Result<()> {
    let bad = |why: String| Error::invalid(path, why);
    // one number of a bearing's table over speed: `kxx[i]`, `speeds[i]` (i from 0)
    let (name, at) = match field.strip_suffix(']').and_then(|s| s.split_once('[')) {
        Some((name, i)) => (name, Some(i)),
        None => (field, None),
    };
    let known = || {
        let tables = if kind == "bearings" { format!("; one number of a table over speed as {}[i]", BEARING_TABLE_KEYS.join("[i], ")) } else { String::new() };
        bad(format!("unknown key of [[linear_rotor.{kind}]] (known: {}{tables})", keys.join(", ")))
    };
    if at.is_some() && !(kind == "bearings" && BEARING_TABLE_KEYS.contains(&name)) || at.is_none() && !keys.contains(&field) {
        return Err(known());
    }
    let j = index(j).ok_or_else(|| bad(format!("the index in [{j}] must be a whole number from 0 (the first [[linear_rotor.{kind}]])")))?;
    let entries = each(lr, kind, path)?;
    let n = entries.len();
    let entry = entries.get_mut(j).ok_or_else(|| bad(format!("the config has {n} [[linear_rotor.{kind}]] (j from 0 to {})", n - 1)))?;
    let v = match name {
        "balls" => Value::Integer(whole(value, crate::planar::MAX_BALLS as u64).map_err(bad)? as i64),
        "node" | "link" => Value::Integer(whole(value, super::MAX_DOFS as u64).map_err(bad)? as i64),
        "count" if kind == "elements" => Value::Integer(whole(value, MAX_ELEMENT_COUNT).map_err(bad)? as i64),
        _ => Value::Float(value),
    };
    let Some(i) = at else { return insert(entry, field, v, path) };
    let i = index(i).ok_or_else(|| bad(format!("the index in [{i}] must be a whole number from 0 (the first speed of the table)")))?;
    let t = entry.as_table_mut().ok_or_else(|| bad("an entry of the array is not a table".into()))?;
    let tabulated = t.contains_key("speeds");
    match t.get_mut(name) {
        Some(Value::Array(a)) => {
            let len = a.len();
            let x = a.get_mut(i).ok_or_else(|| {
                bad(format!(
                    "linear_rotor.{kind}[{j}].{name} has {len} entries ({})",
                    if len == 0 { "none to set".to_string() } else { format!("i from 0 to {}", len - 1) }
                ))
            })?;
            *x = v;
            Ok(())
        }
        // a tabulated bearing without this table (kxy, kyx, cxy, cyx default to zeros, kyy and
        // cyy to kxx and cxx): its entries are set in the config, not made by a path
        _ if tabulated => Err(bad(format!(
            "linear_rotor.{kind}[{j}] has no table {name} (without one it is {}): add `{name} = [...]`, one value per speed, to the bearing in the config to set its entries",
            match name {
                "kyy" => "kxx's table",
                "cyy" => "cxx's table",
                _ => "zero at every speed",
            }
        ))),
        _ => Err(bad(format!("linear_rotor.{kind}[{j}] has no table {name} over speed (a constant bearing's numbers are k and c)"))),
    }
}

/// An index as a path spells it ([`crate::paths::index_digits`]: decimal digits, no sign,
/// space or leading zero), so that one entry has one path (`balancer[00]` and `balancer[ 0]`
/// beside `balancer[0]` were two `--set` keys for one number, the last winning without a word).
fn index(s: &str) -> Option<usize> {
    crate::paths::index_digits(s)
}

/// The tables of `[[linear_rotor.KIND]]`; none is an error naming `path`.
fn each<'a>(lr: &'a mut Table, kind: &str, path: &str) -> Result<&'a mut Vec<Value>> {
    match lr.get_mut(kind) {
        Some(Value::Array(a)) if !a.is_empty() => Ok(a),
        _ => Err(Error::invalid(
            path,
            format!(
                "the config has no [[linear_rotor.{kind}]] to set{}",
                if kind == "bearings" { " (bearings inside the matrices K, C are part of the structure)" } else { "" }
            ),
        )),
    }
}

fn insert(t: &mut Value, key: &str, v: Value, path: &str) -> Result<()> {
    t.as_table_mut().ok_or_else(|| Error::invalid(path, "an entry of the array is not a table"))?.insert(key.to_string(), v);
    Ok(())
}

/// Multiply `keys` (numbers or arrays of numbers) of every table by `factor` (finite, ≥ 0).
fn scale(tables: &mut [Value], keys: &[&str], factor: f64, path: &str) -> Result<()> {
    if factor < 0.0 {
        return Err(Error::invalid(path, format!("a factor must not be negative, got {}", fmt_num(factor))));
    }
    let times = |v: &Value| -> Result<Value> {
        match v {
            Value::Float(f) => Ok(Value::Float(f * factor)),
            Value::Integer(i) => Ok(Value::Float(*i as f64 * factor)),
            _ => Err(Error::invalid(path, "the value to scale is not a number")),
        }
    };
    for t in tables {
        let t = t.as_table_mut().ok_or_else(|| Error::invalid(path, "an entry of the array is not a table"))?;
        for k in keys {
            let new = match t.get(*k) {
                None => continue,
                Some(Value::Array(a)) => Value::Array(a.iter().map(times).collect::<Result<_>>()?),
                Some(v) => times(v)?,
            };
            t.insert(k.to_string(), new);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pinned shaft of 6 elements with two balancer planes and two unbalances.
    fn two_planes() -> LinearRotorSpec {
        let text = "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.02\ne = 2.1e11\nrho = 7850.0\ncount = 6\n\
                    [[linear_rotor.bearings]]\nnode = 0\nk = 1e6\n[[linear_rotor.bearings]]\nnode = 6\nk = 1e6\n\
                    [[linear_rotor.unbalance]]\nnode = 2\nme = 1e-4\n[[linear_rotor.unbalance]]\nnode = 4\nme = 2e-4\nphase = 1.0\n\
                    [[linear_rotor.balancer]]\nnode = 2\nradius = 0.05\nballs = 2\nball_mass = 0.01\n\
                    [[linear_rotor.balancer]]\nnode = 4\nradius = 0.04\nballs = 3\nball_mass = 0.02\ndrag = 0.1\n";
        LinearRotorSpec::new(toml::from_str(text).unwrap(), &mut |_| Err("no files".into())).unwrap()
    }

    /// Two paths touching one number give one point in either order (a map's `x` and `y`
    /// swapped): the factors scale the values set at the point, one entry's value overrides the
    /// value for every entry. Checked against the config written out by hand (a second route):
    /// k = 3e6 for `bearings[0].k = 1e6` scaled by 3, the other bearing 3e6 too.
    #[test]
    fn paths_on_one_number_give_one_point_in_either_order() {
        let s = two_planes();
        let pairs: [[(&str, f64); 2]; 4] = [
            [("linear_rotor.support_stiffness_scale", 3.0), ("linear_rotor.bearings[0].k", 1e6)],
            [("linear_rotor.support_damping_scale", 2.0), ("linear_rotor.bearings[1].c", 10.0)],
            [("linear_rotor.drag", 0.1), ("linear_rotor.balancer[0].drag", 0.3)],
            [("linear_rotor.unbalance_scale", 2.0), ("linear_rotor.unbalance[1].me", 5e-4)],
        ];
        let by_hand: [&[(&str, f64)]; 4] = [
            &[("linear_rotor.bearings[0].k", 3e6), ("linear_rotor.bearings[1].k", 3e6)],
            &[("linear_rotor.bearings[1].c", 20.0)],
            &[("linear_rotor.balancer[0].drag", 0.3), ("linear_rotor.balancer[1].drag", 0.1)],
            &[("linear_rotor.unbalance[0].me", 2e-4), ("linear_rotor.unbalance[1].me", 1e-3)],
        ];
        for ([a, b], hand) in pairs.iter().zip(by_hand) {
            let ab = s.config_at(&[*a, *b]).unwrap();
            assert_eq!(ab, s.config_at(&[*b, *a]).unwrap(), "{} and {}", a.0, b.0);
            assert_eq!(ab, s.config_at(hand).unwrap(), "{} and {}", a.0, b.0);
        }
        // `linear_rotor.me` (the only unbalance's) yields to unbalance[0].me either way
        let text = "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.02\ne = 2.1e11\nrho = 7850.0\ncount = 4\n\
                    [[linear_rotor.bearings]]\nnode = 0\nk = 1e6\n[[linear_rotor.bearings]]\nnode = 4\nk = 1e6\n\
                    [[linear_rotor.unbalance]]\nnode = 2\nme = 1e-4\n\
                    [[linear_rotor.balancer]]\nnode = 2\nradius = 0.05\nballs = 2\nball_mass = 0.01\n";
        let one = LinearRotorSpec::new(toml::from_str(text).unwrap(), &mut |_| Err("no files".into())).unwrap();
        let (a, b) = (("linear_rotor.me", 1e-3), ("linear_rotor.unbalance[0].me", 3e-4));
        assert_eq!(one.config_at(&[a, b]).unwrap(), one.config_at(&[b, a]).unwrap());
        assert_eq!(one.config_at(&[a, b]).unwrap().rotor.unbalances[0].me, 3e-4);
    }

    /// A path of one plane sets that plane and no other; the same value in every plane, set
    /// plane by plane, is the config `linear_rotor.KEY` gives (a second route to the same tables).
    #[test]
    fn one_plane_or_unbalance_of_several() {
        let s = two_planes();
        let base = s.config_at(&[]).unwrap().rotor;
        for key in ["ball_mass", "radius", "drag", "offset"] {
            let one = s.config_at(&[(&format!("linear_rotor.balancer[1].{key}"), 0.03)]).unwrap().rotor;
            assert_eq!(one.balancers[0], base.balancers[0], "{key}: plane 0 untouched");
            assert_ne!(one.balancers[1], base.balancers[1], "{key}: plane 1 set");
            if key != "offset" {
                let each = s.config_at(&[(&format!("linear_rotor.balancer[0].{key}"), 0.03), (&format!("linear_rotor.balancer[1].{key}"), 0.03)]).unwrap();
                assert_eq!(each, s.config_at(&[(&format!("linear_rotor.{key}"), 0.03)]).unwrap(), "{key}");
            }
        }
        let r = s.config_at(&[("linear_rotor.balancer[0].balls", 4.0), ("linear_rotor.balancer[1].node", 3.0)]).unwrap().rotor;
        assert_eq!((r.balancers[0].balls, r.balancers[1].balls, r.balancers[1].node), (4, 3, 3));
        assert_eq!(r.balancers[1].ball_mass, 0.02);
        // the balls' states follow the planes: 4 + 3 balls
        assert_eq!(r.balancers.iter().map(|b| b.balls).sum::<usize>(), 7);
        let r = s.config_at(&[("linear_rotor.unbalance[1].me", 5e-4), ("linear_rotor.unbalance[0].phase", 0.5)]).unwrap().rotor;
        assert_eq!((r.unbalances[0].me, r.unbalances[0].phase, r.unbalances[1].me, r.unbalances[1].phase), (1e-4, 0.5, 5e-4, 1.0));
        // the real-ball keys reach the plane's ball physics
        let r = s.config_at(&[("linear_rotor.balancer[1].rolling_resistance", 1e-3)]).unwrap().rotor;
        assert_eq!(r.ball_physics.len(), 2);
        assert_eq!(r.ball_physics[1].rolling_resistance, 1e-3);
        assert_ne!(r.ball_physics[0].rolling_resistance, 1e-3);
    }

    /// Errors name the path: an index past the last (with the count), an unknown key, an index
    /// that is no number, a fraction where a whole number goes, a value the config refuses.
    #[test]
    fn errors_name_the_path() {
        let s = two_planes();
        let err = |p: &str, v: f64| s.config_at(&[(p, v)]).unwrap_err().to_string();
        assert_eq!(
            err("linear_rotor.balancer[2].ball_mass", 0.1),
            "linear_rotor.balancer[2].ball_mass: the config has 2 [[linear_rotor.balancer]] (j from 0 to 1)"
        );
        assert_eq!(err("linear_rotor.unbalance[5].me", 0.1), "linear_rotor.unbalance[5].me: the config has 2 [[linear_rotor.unbalance]] (j from 0 to 1)");
        assert!(err("linear_rotor.balancer[0].mass", 0.1)
            .starts_with("linear_rotor.balancer[0].mass: unknown key of [[linear_rotor.balancer]] (known: node, radius"));
        assert!(err("linear_rotor.balancer[x].drag", 0.1).starts_with("linear_rotor.balancer[x].drag: the index in [x] must be a whole number from 0"));
        assert!(err("linear_rotor.balancer[-1].drag", 0.1).contains("must be a whole number from 0"));
        // one spelling per entry: no sign, space or leading zero
        for j in ["00", "+0", " 0", "0 ", "01", ""] {
            let p = format!("linear_rotor.balancer[{j}].drag");
            assert!(err(&p, 0.1).starts_with(&format!("{p}: the index in [{j}] must be a whole number from 0")), "{}", err(&p, 0.1));
        }
        assert!(s.config_at(&[("linear_rotor.balancer[1].drag", 0.1)]).is_ok());
        assert!(err("linear_rotor.shafts[0].mass", 0.1).starts_with("linear_rotor.shafts[0].mass: unknown parameter path"));
        assert_eq!(err("linear_rotor.disks[0].mass", 0.1), "linear_rotor.disks[0].mass: the config has no [[linear_rotor.disks]] to set");
        assert!(err("linear_rotor.balancer[0].balls", 2.5).starts_with("linear_rotor.balancer[0].balls: must be a whole number"));
        assert!(err("linear_rotor.balancer[1].node", 9.0).starts_with("linear_rotor.balancer[1].node"), "{}", err("linear_rotor.balancer[1].node", 9.0));
        let e = err("linear_rotor.balancer[1].ball_mass", -1.0);
        assert!(e.starts_with("linear_rotor.balancer[1].ball_mass"), "{e}");
        assert!(err("linear_rotor.me", 1.0).contains("linear_rotor.unbalance[j].me"));
    }

    /// The shaft builder's arrays of tables (elements, disks, bearings and their tables over
    /// speed): each path gives the config the TOML text edited by hand gives (a second route
    /// to the same tables: the text is parsed, not set), and no other.
    #[test]
    fn shaft_builder_entries_are_paths() {
        let text = "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.02\ne = 2.1e11\nrho = 7850.0\ncount = 3\n\
                    [[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.03\ne = 2.1e11\nrho = 7850.0\ncount = 3\n\
                    [[linear_rotor.disks]]\nnode = 3\nmass = 4.0\nid = 0.01\nip = 0.02\n\
                    [[linear_rotor.bearings]]\nnode = 0\nk = 1e6\nc = 100.0\n\
                    [[linear_rotor.bearings]]\nnode = 6\nspeeds = [0.0, 1000.0]\nkxx = [2e6, 3e6]\ncxx = [300.0, 300.0]\n";
        let spec = |t: &str| LinearRotorSpec::new(toml::from_str(t).unwrap(), &mut |_| Err("no files".into())).unwrap();
        let s = spec(text);
        let base = s.config_at(&[]).unwrap();
        for (path, v, from, to) in [
            ("linear_rotor.elements[1].length", 0.2, "length = 0.1\ndiameter = 0.03", "length = 0.2\ndiameter = 0.03"),
            ("linear_rotor.elements[0].diameter", 0.025, "diameter = 0.02", "diameter = 0.025"),
            (
                "linear_rotor.elements[1].count",
                4.0,
                "diameter = 0.03\ne = 2.1e11\nrho = 7850.0\ncount = 3",
                "diameter = 0.03\ne = 2.1e11\nrho = 7850.0\ncount = 4",
            ),
            ("linear_rotor.disks[0].mass", 5.5, "mass = 4.0", "mass = 5.5"),
            ("linear_rotor.disks[0].node", 2.0, "node = 3\nmass", "node = 2\nmass"),
            ("linear_rotor.bearings[0].k", 3e6, "k = 1e6", "k = 3e6"),
            ("linear_rotor.bearings[1].kxx[1]", 4e6, "kxx = [2e6, 3e6]", "kxx = [2e6, 4e6]"),
            ("linear_rotor.bearings[1].speeds[1]", 800.0, "speeds = [0.0, 1000.0]", "speeds = [0.0, 800.0]"),
        ] {
            assert_eq!(text.matches(from).count(), 1, "{from}");
            let edited = text.replace(from, to);
            let by_path = s.config_at(&[(path, v)]).unwrap();
            assert!(by_path == spec(&edited).config_at(&[]).unwrap(), "{path} = {v}: not the config edited by hand");
            assert!(by_path != base, "{path} = {v} changes the config");
        }
        let err = |p: &str, v: f64| s.config_at(&[(p, v)]).unwrap_err().to_string();
        assert_eq!(err("linear_rotor.elements[2].length", 0.1), "linear_rotor.elements[2].length: the config has 2 [[linear_rotor.elements]] (j from 0 to 1)");
        assert!(err("linear_rotor.elements[0].mass", 0.1)
            .starts_with("linear_rotor.elements[0].mass: unknown key of [[linear_rotor.elements]] (known: length, diameter"));
        assert!(err("linear_rotor.disks[0].radius", 0.1)
            .starts_with("linear_rotor.disks[0].radius: unknown key of [[linear_rotor.disks]] (known: node, mass, id, ip)"));
        assert!(
            err("linear_rotor.bearings[0].kxx", 0.1).contains("one number of a table over speed as speeds[i], kxx[i]"),
            "{}",
            err("linear_rotor.bearings[0].kxx", 0.1)
        );
        assert_eq!(err("linear_rotor.bearings[1].kxx[2]", 1e6), "linear_rotor.bearings[1].kxx[2]: linear_rotor.bearings[1].kxx has 2 entries (i from 0 to 1)");
        assert!(err("linear_rotor.bearings[0].kxx[0]", 1e6).contains("linear_rotor.bearings[0] has no table kxx over speed"));
        assert!(err("linear_rotor.disks[0].mass[0]", 1.0).contains("unknown key of [[linear_rotor.disks]]"));
        assert!(err("linear_rotor.elements[0].count", 0.5).starts_with("linear_rotor.elements[0].count: must be a whole number"));
        // a value the config refuses names the path: a length of zero, a node past the shaft
        assert!(err("linear_rotor.elements[0].length", 0.0).starts_with("linear_rotor.elements[0].length"), "{}", err("linear_rotor.elements[0].length", 0.0));
        assert!(err("linear_rotor.disks[0].node", 9.0).starts_with("linear_rotor.disks[0].node"), "{}", err("linear_rotor.disks[0].node", 9.0));
        // k on a bearing tabulated over speed is refused, not ignored
        assert!(err("linear_rotor.bearings[1].k", 1e6).starts_with("linear_rotor.bearings[1].k"), "{}", err("linear_rotor.bearings[1].k", 1e6));
        // a table the tabulated bearing lacks: say to add it (it said "a constant bearing's
        // numbers are k and c", of a bearing that is not constant)
        assert_eq!(
            err("linear_rotor.bearings[1].kxy[0]", 1e5),
            "linear_rotor.bearings[1].kxy[0]: linear_rotor.bearings[1] has no table kxy (without one it is zero at every speed): add `kxy = [...]`, one value per speed, to the bearing in the config to set its entries"
        );
        assert!(err("linear_rotor.bearings[1].cyy[1]", 1.0).contains("(without one it is cxx's table)"));
        // the tables' bounds name the entry: direct damping as a constant `c` (not negative),
        // cross-coupled damping and stiffness by magnitude (negative allowed), speeds finite and
        // within the config's speed range; the value as given
        let edit = |from: &str, to: &str| {
            assert_eq!(text.matches(from).count(), 1, "{from}");
            LinearRotorSpec::new(toml::from_str(&text.replace(from, to)).unwrap(), &mut |_| Err("no files".into())).map(|_| ()).map_err(|e| e.to_string())
        };
        assert_eq!(edit("cxx = [300.0, 300.0]", "cxx = [300.0, -1e3]").unwrap_err(), "linear_rotor.bearings[1].cxx[1]: must not be negative, got -1000");
        assert!(edit("cxx = [300.0, 300.0]", "cxx = [300.0, 300.0]\ncyy = [-1.0, 300.0]")
            .unwrap_err()
            .starts_with("linear_rotor.bearings[1].cyy[0]: must not be negative"));
        assert_eq!(edit("cxx = [300.0, 300.0]", "cxx = [300.0, 300.0]\ncxy = [-50.0, 50.0]\ncyx = [50.0, -50.0]"), Ok(()));
        assert_eq!(edit("kxx = [2e6, 3e6]", "kxx = [2e6, 3e6]\nkxy = [-1e6, 1e6]"), Ok(()));
        assert_eq!(
            edit("cxx = [300.0, 300.0]", "cxx = [300.0, 300.0]\ncxy = [0.0, -2e12]").unwrap_err(),
            "linear_rotor.bearings[1].cxy[1]: must lie in [-1e12, 1e12] N·s/m, got -2e12 (1e12 N·s/m is the critical damping 2mω of a 1e9 kg rotor at 500 rad/s, beyond every bearing)"
        );
        assert_eq!(
            edit("speeds = [0.0, 1000.0]", "speeds = [0.0, 1e300]").unwrap_err(),
            "linear_rotor.bearings[1].speeds[1]: must lie in [-1e6, 1e6] rad/s, got 1e300 (±1e6 rad/s (~1e7 rpm), beyond every machine)"
        );
        assert!(edit("speeds = [0.0, 1000.0]", "speeds = [0.0, inf]").unwrap_err().starts_with("linear_rotor.bearings[1].speeds[1]: "));
        assert!(edit("speeds = [0.0, 1000.0]", "speeds = [nan, 1000.0]").unwrap_err().starts_with("linear_rotor.bearings[1].speeds[0]: "));
        assert_eq!(edit("speeds = [0.0, 1000.0]", "speeds = [-1e6, 1e6]"), Ok(()));
    }

    /// The offsets, `me` and `phase` are bounded in magnitude and the error prints the value as
    /// given (-2e3 was reported as "got 2000"); the phase's reason speaks of the phase.
    #[test]
    fn magnitudes_are_reported_as_given() {
        let s = two_planes();
        let err = |p: &str, v: f64| s.config_at(&[(p, v)]).unwrap_err().to_string();
        assert_eq!(
            err("linear_rotor.balancer[0].offset", -2e3),
            "linear_rotor.balancer[0].offset: must lie in [-1000, 1000] m, got -2000 (an axial offset from the node; no rotor is a kilometre long)"
        );
        assert!(err("linear_rotor.unbalance[1].offset", -2e3).ends_with("got -2000 (an axial offset from the node; no rotor is a kilometre long)"));
        assert!(err("linear_rotor.unbalance[0].me", -2e12).contains("got -2e12"));
        let e = err("linear_rotor.unbalance[0].phase", -1e300);
        assert!(e.contains("got -1e300 (an angle: 1e3 rad is ~160 turns") && !e.contains("psi0"), "{e}");
        assert!(s.config_at(&[("linear_rotor.unbalance[0].phase", -1e3), ("linear_rotor.balancer[1].offset", -1e3)]).is_ok());
        // too many elements name the count that passes the limit (at the limit, 497 elements:
        // 4 × 498 DOFs and 5 balls within 2000, is taken)
        assert_eq!(
            err("linear_rotor.elements[0].count", 10000.0),
            "linear_rotor.elements[0].count: 10000 elements bring the shaft to 10000 elements, 40004 DOFs (4 per node), past the limit of 2000 (dense matrices): at most 499 elements in all, fewer with balancer balls"
        );
        let at_limit = s.config_at(&[("linear_rotor.elements[0].count", 497.0)]);
        assert!(at_limit.is_ok(), "{at_limit:?}");
        assert!(err("linear_rotor.elements[0].count", 500.0).contains("2004 DOFs"));
    }

    /// The path reaches the physics: a 4 kg disk at the middle of a pinned shaft of nearly
    /// massless steel (ρ = 1 kg/m³), rigid bearings, has its first natural frequency at the
    /// closed form `ω² = 48 E I / (L³ m)` (the stiffness at mid-span of a pinned beam, exact for
    /// cubic elements loaded at a node) for the span `L` the path `elements[0].length` sets,
    /// 0.6 m and 1.2 m. Tolerance 2e-4 relative: the shaft's own mass (ρ A L ≈ 6e-4 kg, of
    /// which ~17/35 acts at mid-span, against 4 kg) lowers ω by ~4e-5; the bearings (1e13 N/m
    /// against 1e5 N/m) by ~1e-8.
    #[test]
    fn element_length_path_moves_the_first_frequency_as_the_closed_form() {
        let text = "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.025\ne = 2.1e11\nrho = 1.0\ncount = 6\n\
                    [[linear_rotor.disks]]\nnode = 3\nmass = 4.0\n\
                    [[linear_rotor.bearings]]\nnode = 0\nk = 1e13\n[[linear_rotor.bearings]]\nnode = 6\nk = 1e13\n";
        let s = LinearRotorSpec::new(toml::from_str(text).unwrap(), &mut |_| Err("no files".into())).unwrap();
        let i = std::f64::consts::PI * 0.025f64.powi(4) / 64.0;
        for (set, l) in [(0.1, 0.6), (0.2, 1.2)] {
            let cfg = s.config_at(&[("linear_rotor.elements[0].length", set)]).unwrap();
            let w = cfg.rotor.natural_frequencies(&[], false).unwrap();
            let w1 = w.into_iter().find(|w| *w > 0.0).unwrap();
            let closed = (48.0 * 2.1e11 * i / (l * l * l * 4.0)).sqrt();
            assert!((w1 / closed - 1.0).abs() < 2e-4, "L = {l}: {w1} rad/s against {closed}");
        }
    }
}
