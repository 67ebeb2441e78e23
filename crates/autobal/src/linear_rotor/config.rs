//! The `[linear_rotor]` config: a [`LinearRotor`] from matrix files (Matrix Market text or
//! NumPy `.npy` arrays, or one `.npz` archive as `matrices`, the DOFs in ROSS's order) or from the built-in shaft builder ([`super::shaft`]), with its
//! unbalances, balancer planes and bearings (constant or tabulated over speed), plus the
//! `[drive]` and `[integration]` tables of the simulations. Errors name the key
//! (`linear_rotor.elements[2].length`), or the key, the file and the line
//! (`linear_rotor.k: rotor_K.mtx: line 7: …`).
//!
//! Further keys of `[linear_rotor]`: `polar_inertia` (kg m², the spin's inertia for torque
//! drives; the shaft builder computes it, the key replaces that), `spin_damping` (N m s) and
//! `gravity = [g_x, g_y]` (m/s², fixed axes; [`super::Gravity`]), `gravity_load` (N, one per
//! DOF: the weight, where it is not `M r_g`, as export writes it for a reduced rotor); of the elements, `g_s` (the
//! shear modulus: Timoshenko elements) and `kappa` (their shear coefficient; Cowper's for a
//! circular section when absent, [`super::shaft::cowper_kappa`]); `rotor_fixed_mass` (a matrix
//! file as `m`, or the array `M_rot` of the `.npz` archive; with matrix files or the shaft
//! builder): the inertia fixed to the rotor `M_rot`, constant in axes turning with it
//! ([`LinearRotor::rotor_fixed_mass`]: symmetric, `M + T(φ) M_rot T(φ)ᵀ` positive definite).
//!
//! The library reads no files: [`linear_rotor`] takes a loader that returns a named file's text
//! (the front end resolves the path against the config's folder).
//!
//! ```
//! use autobal::linear_rotor::config::{linear_rotor, export, parse_matrix_market};
//! let text = r#"
//! [linear_rotor]
//! [[linear_rotor.elements]]
//! length = 0.1
//! diameter = 0.02
//! e = 2.1e11
//! rho = 7850.0
//! count = 6
//! [[linear_rotor.bearings]]
//! node = 0
//! k = 1e6
//! [[linear_rotor.bearings]]
//! node = 6
//! k = 1e6
//! [[linear_rotor.balancer]]
//! node = 3
//! radius = 0.05
//! balls = 2
//! ball_mass = 0.01
//! drag = 0.001
//! "#;
//! let root: toml::Table = text.parse().unwrap();
//! let cfg = linear_rotor(&root, &mut |_| Err("no files".into())).unwrap();
//! assert_eq!(cfg.rotor.nodes, 7);
//! // exported to Matrix Market and read back: the same matrices, bit for bit
//! let (toml_text, files) = export(&cfg.rotor, "shaft");
//! let back: toml::Table = toml_text.parse().unwrap();
//! let again = linear_rotor(&back, &mut |p| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or("missing".into())).unwrap();
//! assert_eq!(again.rotor, cfg.rotor);
//! ```

use super::npz::{parse_npy, parse_npz, NpyArray};
use super::shaft::{Bearing, Disk, Element, ShaftBuilder};
use super::{BalancerPlane, Direction, Layout, LinearRotor, SpeedBearing, Unbalance};
use crate::config::{drive, integration, Integration, Section};
use crate::drive::Drive;
use crate::error::{Error, Result};
use toml::{Table, Value};

/// Why an axial offset from a node is bounded by a kilometre.
const OFFSET: &str = "an axial offset from the node; no rotor is a kilometre long";

/// The keys of `[linear_rotor]` and of its arrays of tables.
const KEYS: &[(&str, &[&str])] = &[
    (
        "linear_rotor",
        &[
            "layout",
            "m",
            "c",
            "g",
            "k",
            "kst",
            "spin_chart",
            "dofs",
            "rotary_inertia",
            "gyroscopic",
            "omega_max",
            "operating_speed",
            "modes",
            "matrices",
            "polar_inertia",
            "spin_damping",
            "gravity",
            "gravity_load",
            "rotor_fixed_mass",
            "elements",
            "disks",
            "bearings",
            "unbalance",
            "balancer",
        ],
    ),
    ("elements", &["length", "diameter", "inner_diameter", "area", "inertia", "e", "rho", "g_s", "kappa", "count"]),
    ("disks", &["node", "mass", "id", "ip"]),
    ("bearings", &["node", "link", "k", "c", "speeds", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"]),
    ("unbalance", &["node", "me", "phase", "offset"]),
    (
        "balancer",
        &[
            "node",
            "radius",
            "balls",
            "ball_mass",
            "drag",
            "offset",
            "ball_diameter",
            "contact",
            "restitution",
            "contact_stiffness",
            "rolling_resistance",
            "slip_rate",
        ],
    ),
];

/// A linear rotor config.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearRotorConfig {
    /// The rotor with its unbalances, balancers and bearings.
    pub rotor: LinearRotor,
    /// Where the structure came from: `"matrices"` (files) or `"shaft"` (the builder).
    pub source: &'static str,
    /// `linear_rotor.omega_max` (rad/s): the top of speed axes, if given.
    pub omega_max: Option<f64>,
    /// `linear_rotor.operating_speed` (rad/s, `[lo, hi]`, equal for one speed): the speed or
    /// range the machine runs at (`"1400 rpm"`, `"1200-1400 rpm"`, `"150 Hz"`, or a number in
    /// rad/s), as `analysis.operating_speed` of a spatial config: `stability` and the report
    /// give the verdict there first, and the default speed axis reaches past it.
    pub operating_speed: Option<[f64; 2]>,
    /// `linear_rotor.modes`: reduce to this many interior mode pairs ([`super::reduce`]);
    /// `None` (absent or 0): the full model.
    pub modes: Option<usize>,
    /// `[drive]` and its `t_end`, if the config has the table.
    pub drive: Option<(Drive, f64)>,
    /// `[integration]` (its `dt` default from `t_end`).
    pub integration: Integration,
}

/// The keys of `[linear_rotor]` whose values name files the reader loads (matrices, the `.npz`
/// archive, the rotor-fixed mass).
pub const FILE_KEYS: &[&str] = &["matrices", "m", "c", "g", "k", "kst", "spin_chart", "rotor_fixed_mass"];

/// The files a linear rotor config names (`linear_rotor.KEY = "name"` for the keys of
/// [`FILE_KEYS`]), as `(linear_rotor.KEY, name)`, relative to the config's folder as the
/// reader loads them; empty for a config without `[linear_rotor]`. A command registers them as
/// inputs that no output may overwrite.
pub fn file_names(root: &Table) -> Vec<(String, String)> {
    let Some(lr) = root.get("linear_rotor").and_then(Value::as_table) else { return vec![] };
    FILE_KEYS.iter().filter_map(|k| lr.get(*k).and_then(Value::as_str).map(|v| (format!("linear_rotor.{k}"), v.to_string()))).collect()
}

/// `value` within `[lo, hi]` (`(lo, hi]` where `lo.1` says open) in `unit`, else an error
/// naming `field` with the range and why (`must lie in (0, 1e13] Pa, got 1e300 (...)`); a
/// value below zero where zero is allowed or open says `must be positive`/`must not be
/// negative` as the other checks do.
/// Why a bearing's stiffness is bounded (limits.rs's support stiffness).
const STIFF: &str = "the stiffest bearings are ~1e10 N/m (as the spatial rotor's supports)";
/// Why a bearing's damping is bounded.
const DAMP: &str = "1e12 N·s/m is the critical damping 2mω of a 1e9 kg rotor at 500 rad/s, beyond every bearing";

/// `value` finite and at most `hi` in magnitude; the error prints the value as given (an
/// offset of -2e3 was reported as "got 2000").
fn within_magnitude(field: &str, value: f64, hi: f64, unit: &str, why: &str) -> Result<f64> {
    crate::error::finite(field, value)?;
    if value.abs() > hi {
        let f = crate::error::fmt_num;
        return Err(Error::invalid(field, format!("must lie in [-{}, {}] {unit}, got {} ({why})", f(hi), f(hi), f(value))));
    }
    Ok(value)
}

/// The constant bearings' damping through the dimensionless damping it implies, as the
/// spatial rotor's supports (`h̄x`, [`crate::spatial::dynamics::SpatialRotor::to_dimensionless`]):
/// `Σ c/(M ω0)` with `ω0 = sqrt(Σ k/M)`, over the constant bearings (`(key of c, k, c)`), `M`
/// the rotor's mass along x (`uᵀ M u` for the unit translation `u` along x of every node), within the
/// range of `dimensionless.h_x` (a damping ratio up to 500; beyond, the supports do not move).
/// The error names the `c` of the bearing of the largest damping; without stiffness in the
/// constant bearings there is no `ω0` and nothing to check. (`c = 1e12` on the shaft example was
/// taken.)
fn check_bearing_damping(rotor: &LinearRotor, bearings: &[(String, f64, f64)]) -> Result<()> {
    let (k, c) = bearings.iter().fold((0.0, 0.0), |(k, c), b| (k + b.1, c + b.2));
    let Some(worst) = bearings.iter().reduce(|w, b| if b.2 > w.2 { b } else { w }) else { return Ok(()) };
    let mass = mass_along_x(rotor);
    if !(k > 0.0 && mass > 0.0) {
        return Ok(());
    }
    let f = crate::error::fmt_num;
    let omega0 = (k / mass).sqrt();
    let what = format!(
        "the constant bearings' Σ c/(M ω0) with ω0 = sqrt(Σ k/M) = {} rad/s (Σ c = {} N·s/m, Σ k = {} N/m, the rotor's mass M = {} kg)",
        f(omega0),
        f(c),
        f(k),
        f(mass)
    );
    crate::limits::check_derived(&worst.0, "dimensionless.h_x", c / (mass * omega0), &what).map(|_| ())
}

/// The rotor's mass along x, `uᵀ M u` for the unit translation `u` along x of every node (a
/// rigid translation: no rotary inertia's energy).
fn mass_along_x(rotor: &LinearRotor) -> f64 {
    let n = rotor.dofs();
    let along_x: Vec<usize> = (0..n).filter(|&i| matches!(rotor.dof_node(i), Some((_, Direction::X)))).collect();
    along_x.iter().map(|&i| along_x.iter().map(|&j| rotor.m[i * n + j]).sum::<f64>()).sum()
}

/// The tabulated bearings' damping (`speed_bearings`, each with its config name
/// `linear_rotor.bearings[i]` and whether it gave `cyy`), every value of `cxx`, `cxy`, `cyx`,
/// `cyy` at its table row through the dimensionless damping it implies, as the constant
/// bearings' `c` ([`check_bearing_damping`]): `|c|/(M ω0)` with `ω0 = sqrt(K/M)` within the
/// range of `dimensionless.h_x`, `M` the rotor's mass along x ([`mass_along_x`]) and `K` the
/// supports' stiffness along the value's force direction (x for `cxx`, `cxy`; y for `cyx`,
/// `cyy`) at that row's speed `w_j`: every constant bearing's `k` plus every table's direct
/// stiffness (`kxx`, `kyy`) at `w_j`, interpolated as the rotor does ([`SpeedBearing::at`]).
///
/// Why that stiffness: a table's row holds at its speed, and a fluid film's stiffness and
/// damping both grow with speed, so what the row's damping acts against is the stiffness the
/// rotor sits on at that speed. The constant bearings' `ω0` alone would miss the tables'
/// stiffness (none at all beside tabulated bearings only, which left `cxx = 1e12` unbounded:
/// it was taken and ran for minutes), the row's own stiffness alone the supports in parallel
/// (a pure damper row, `kxx = 0`, beside stiff constant bearings). Each value is held on its
/// own, so the error names the user's key and row (`linear_rotor.bearings[1].cxx[2]`; `cxx`
/// for `cyy` where `cyy` falls back to it); the cross-coupled terms may be negative, their
/// magnitude is held. Where `K ≤ 0` at a row (no `ω0`: no stiffness, or a film's negative
/// one) only the absolute bound of 1e12 N·s/m holds there.
fn check_table_damping(rotor: &LinearRotor, constant_k: f64, names: &[(String, bool)]) -> Result<()> {
    let mass = mass_along_x(rotor);
    if !(mass > 0.0) {
        return Ok(());
    }
    let f = crate::error::fmt_num;
    for (b, (name, gave_cyy)) in rotor.speed_bearings.iter().zip(names) {
        for (j, (&w, c)) in b.speeds.iter().zip(&b.c).enumerate() {
            // the supports' stiffness along x and y at this row's speed
            let (kx, ky) = rotor.speed_bearings.iter().fold((constant_k, constant_k), |(x, y), o| {
                let (k, _) = o.at(w);
                (x + k[0], y + k[3])
            });
            for (e, key) in ["cxx", "cxy", "cyx", "cyy"].into_iter().enumerate() {
                let (k, dir) = if e < 2 { (kx, "x") } else { (ky, "y") };
                if !(k > 0.0) {
                    continue;
                }
                let given = if key == "cyy" && !gave_cyy { "cxx" } else { key };
                let stands = if given == key { "" } else { " (cyy too: not given)" };
                let omega0 = (k / mass).sqrt();
                let what = format!(
                    "|{given}|/(M ω0) at {} rad/s with ω0 = sqrt(K/M) = {} rad/s ({given} = {} N·s/m{stands}; K = {} N/m, the supports' stiffness along {dir} at that speed: the constant bearings' k and the tables' k{dir}{dir}; the rotor's mass M = {} kg)",
                    f(w),
                    f(omega0),
                    f(c[e]),
                    f(k),
                    f(mass)
                );
                crate::limits::check_derived(&format!("{name}.{given}[{j}]"), "dimensionless.h_x", c[e].abs() / (mass * omega0), &what)?;
            }
        }
    }
    Ok(())
}

fn within(field: &str, value: f64, lo: (f64, bool), hi: f64, unit: &str, why: &str) -> Result<f64> {
    crate::error::finite(field, value)?;
    if lo.0 == 0.0 {
        if lo.1 {
            crate::error::positive(field, value)?;
        } else {
            crate::error::non_negative(field, value)?;
        }
    }
    let below = if lo.1 { value <= lo.0 } else { value < lo.0 };
    if below || value > hi {
        let (open, fmt) = (if lo.1 { "(" } else { "[" }, crate::error::fmt_num);
        // (a dimensionless key's range read "(0, 10] , got")
        let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
        return Err(Error::invalid(field, format!("must lie in {open}{}, {}]{unit}, got {} ({why})", fmt(lo.0), fmt(hi), fmt(value))));
    }
    Ok(value)
}

/// Whether a config describes a linear rotor (has `[linear_rotor]`).
pub fn is_linear_rotor(root: &Table) -> bool {
    root.contains_key("linear_rotor")
}

fn num(v: &Value, field: &str) -> Result<f64> {
    match v {
        Value::Float(f) => Ok(*f),
        Value::Integer(i) => Ok(*i as f64),
        _ => Err(Error::invalid(field, "expected a number")),
    }
}

/// A table of an array of tables with its keys checked.
struct Item<'a> {
    name: String,
    t: &'a Table,
}

impl<'a> Item<'a> {
    fn field(&self, k: &str) -> String {
        format!("{}.{k}", self.name)
    }
    fn f64(&self, k: &str) -> Result<Option<f64>> {
        self.t.get(k).map(|v| num(v, &self.field(k))).transpose()
    }
    fn req(&self, k: &str) -> Result<f64> {
        self.f64(k)?.ok_or_else(|| Error::invalid(self.field(k), "missing (required)"))
    }
    fn usize(&self, k: &str) -> Result<Option<usize>> {
        match self.t.get(k) {
            None => Ok(None),
            Some(Value::Integer(i)) if *i >= 0 => Ok(Some(*i as usize)),
            Some(_) => Err(Error::invalid(self.field(k), "expected a whole number ≥ 0 (written without a decimal point)")),
        }
    }
    fn req_usize(&self, k: &str) -> Result<usize> {
        self.usize(k)?.ok_or_else(|| Error::invalid(self.field(k), "missing (required)"))
    }
    fn array(&self, k: &str) -> Result<Option<Vec<f64>>> {
        match self.t.get(k) {
            None => Ok(None),
            Some(Value::Array(a)) => a.iter().enumerate().map(|(i, v)| num(v, &format!("{}[{i}]", self.field(k)))).collect::<Result<Vec<_>>>().map(Some),
            Some(_) => Err(Error::invalid(self.field(k), "expected an array of numbers")),
        }
    }
}

fn check_keys(name: &str, kind: &str, t: &Table) -> Result<()> {
    let keys = KEYS.iter().find(|(k, _)| *k == kind).map(|(_, k)| *k).unwrap_or(&[]);
    for k in t.keys() {
        if !keys.contains(&k.as_str()) {
            return Err(Error::invalid(format!("{name}.{k}"), format!("unknown key (known keys: {})", keys.join(", "))));
        }
    }
    Ok(())
}

fn items<'a>(lr: &'a Table, kind: &str) -> Result<Vec<Item<'a>>> {
    let name = format!("linear_rotor.{kind}");
    match lr.get(kind) {
        None => Ok(vec![]),
        Some(Value::Array(a)) => a
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let item_name = format!("{name}[{i}]");
                let t = v.as_table().ok_or_else(|| Error::invalid(&item_name, format!("expected a table ([[{name}]])")))?;
                check_keys(&item_name, kind, t)?;
                Ok(Item { name: item_name, t })
            })
            .collect(),
        Some(_) => Err(Error::invalid(name.clone(), format!("expected an array of tables ([[{name}]])"))),
    }
}

/// Read `[linear_rotor]`, `[drive]`, `[integration]` of `root` into a validated rotor. `load`
/// returns the text of a matrix file named in the config (or a one-line reason it cannot); NumPy
/// files need [`linear_rotor_bytes`].
pub fn linear_rotor(root: &Table, load: &mut dyn FnMut(&str) -> std::result::Result<String, String>) -> Result<LinearRotorConfig> {
    linear_rotor_bytes(root, &mut |p| load(p).map(String::into_bytes))
}

/// The matrices of a `.npz` archive named by `linear_rotor.matrices`: `M`, `K` (required), `C`,
/// `G` and the DOF table `dofs` (optional), by these names (or lower case).
fn npz_arrays(path: &str, bytes: &[u8]) -> Result<Vec<(String, NpyArray)>> {
    let field = "linear_rotor.matrices";
    let members = parse_npz(bytes).map_err(|e| Error::invalid(field, format!("{path}: {e}")))?;
    let mut out: Vec<(String, NpyArray)> = vec![];
    // the member each key came from: a second member for one key (`K` beside `k`, or two
    // members `K.npy`) is refused; the first was read and the other silently ignored
    let mut from: Vec<(&str, String)> = vec![];
    for (name, data) in members {
        let key = match name.as_str() {
            "M" | "m" => "m",
            "C" | "c" => "c",
            "G" | "g" => "g",
            "K" | "k" => "k",
            "M_rot" | "m_rot" | "rotor_fixed_mass" => "rotor_fixed_mass",
            "Kst" | "KST" | "kst" => "kst",
            "spin_chart" | "Sigma" => "spin_chart",
            "dofs" | "DOFS" => "dofs",
            o => return Err(Error::invalid(field, format!("{path}: array \"{o}\" is not read (M, C, G, K, M_rot, Kst, spin_chart, dofs)"))),
        };
        if let Some((_, first)) = from.iter().find(|(k, _)| *k == key) {
            return Err(Error::invalid(field, format!("{path}: members \"{first}\" and \"{name}\" both give the array {key}: give it once")));
        }
        from.push((key, name.clone()));
        let a = parse_npy(&data).map_err(|e| Error::invalid(field, format!("{path}: {name}: {e}")))?;
        out.push((key.to_string(), a));
    }
    Ok(out)
}

/// Largest magnitude of a matrix file's entry: far beyond any rotor's (a stiffness term
/// `12 E I / L³` of the builder's extreme element is ~1e44), far enough below overflow that
/// the analyses' products stay finite (`M` times 1e300 was reported as "the eigenvalue iteration
/// did not converge at Ω = 0", naming no key).
const MAX_ENTRY: f64 = 1e100;

/// Every entry of the `n × n` matrix `a` of the file `what` at most [`MAX_ENTRY`] in magnitude.
fn bounded_entries(field: &str, what: &str, n: usize, a: &[f64]) -> Result<()> {
    if let Some(i) = a.iter().position(|v| v.abs() > MAX_ENTRY) {
        return Err(Error::invalid(
            field,
            format!(
                "{what}: entry [{}, {}] is {}, beyond ±1e100 (no rotor's matrix comes near; overflow follows in the analyses)",
                i / n,
                i % n,
                crate::error::fmt_num(a[i])
            ),
        ));
    }
    Ok(())
}

/// A square real matrix from a parsed NumPy array: `(n, row-major entries)`.
fn npy_matrix(a: NpyArray, field: &str, what: &str) -> Result<(usize, Vec<f64>)> {
    match a {
        NpyArray::Real { shape, data } if shape.len() == 2 => {
            if shape[0] != shape[1] || shape[0] == 0 || shape[0] > super::MAX_DOFS {
                return Err(Error::invalid(field, format!("{what}: is {} × {}, must be square, 1..{} rows", shape[0], shape[1], super::MAX_DOFS)));
            }
            if let Some(i) = data.iter().position(|v| !v.is_finite()) {
                return Err(Error::invalid(field, format!("{what}: entry [{}, {}] is {}, not finite", i / shape[1], i % shape[1], data[i])));
            }
            bounded_entries(field, what, shape[0], &data)?;
            Ok((shape[0], data))
        }
        NpyArray::Real { shape, .. } => Err(Error::invalid(field, format!("{what}: has {} dimensions, a matrix has 2", shape.len()))),
        NpyArray::Strings(_) => Err(Error::invalid(field, format!("{what}: is an array of strings, expected numbers"))),
    }
}

/// A square matrix from the file `path` named by the key `field`: Matrix Market text or a
/// `.npy` array (`(n, row-major entries)`).
fn matrix_file(field: &str, path: &str, load: &mut dyn FnMut(&str) -> std::result::Result<Vec<u8>, String>) -> Result<(usize, Vec<f64>)> {
    empty_name(field, path)?;
    if path.ends_with(".npz") {
        return Err(Error::invalid(field, format!("{path}: an .npz archive holds all the matrices: name it as linear_rotor.matrices")));
    }
    let bytes = load(path).map_err(|e| Error::invalid(field, format!("{path}: {e}")))?;
    if path.ends_with(".npy") {
        let a = parse_npy(&bytes).map_err(|e| Error::invalid(field, format!("{path}: {e}")))?;
        return npy_matrix(a, field, path);
    }
    let text = String::from_utf8(bytes).map_err(|e| Error::invalid(field, format!("{path}: not UTF-8 text (byte {})", e.utf8_error().valid_up_to())))?;
    let (rows, cols, a) = parse_matrix_market(&text).map_err(|e| Error::invalid(field, format!("{path}: {e}")))?;
    if rows != cols {
        return Err(Error::invalid(field, format!("{path}: is {rows} × {cols}, must be square")));
    }
    bounded_entries(field, path, rows, &a)?;
    Ok((rows, a))
}

/// A file name given as the empty string: named as such (`rotor_fixed_mass = ""` said
/// "linear_rotor.rotor_fixed_mass: : : cannot read: …", the empty name between colons).
fn empty_name(field: &str, path: &str) -> Result<()> {
    if path.trim().is_empty() {
        return Err(Error::invalid(field, format!("the file name is empty ({path:?}): give the matrix file's name, relative to the config's folder")));
    }
    Ok(())
}

/// [`linear_rotor`] with a loader of bytes: matrix files are Matrix Market text, `.npy` arrays
/// (`m = "M.npy"`), or one `.npz` archive for all (`matrices = "rotor.npz"`, with the arrays
/// `M`, `K` and optionally `C`, `G`, `dofs`; [`super::npz`]).
pub fn linear_rotor_bytes(root: &Table, load: &mut dyn FnMut(&str) -> std::result::Result<Vec<u8>, String>) -> Result<LinearRotorConfig> {
    for k in root.keys() {
        if !["linear_rotor", "drive", "integration"].contains(&k.as_str()) {
            return Err(Error::invalid(
                k.as_str(),
                "unknown table in a linear rotor config (known: [linear_rotor] with its arrays of tables, [drive], [integration])",
            ));
        }
    }
    let lr = root.get("linear_rotor").and_then(Value::as_table).ok_or_else(|| Error::invalid("linear_rotor", "expected a table [linear_rotor]"))?;
    check_keys("linear_rotor", "linear_rotor", lr)?;
    check_run_keys(root)?;
    let top = Item { name: "linear_rotor".into(), t: lr };
    let string = |k: &str| -> Result<Option<&str>> {
        match lr.get(k) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.as_str())),
            Some(_) => Err(Error::invalid(format!("linear_rotor.{k}"), "expected a string (a file name)")),
        }
    };
    let boolean = |k: &str| -> Result<Option<bool>> {
        match lr.get(k) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(_) => Err(Error::invalid(format!("linear_rotor.{k}"), "expected true or false")),
        }
    };
    let has_files = ["m", "c", "g", "k", "matrices"].iter().any(|k| lr.contains_key(*k));
    // the .npz archive, read once: its arrays by key
    let mut archive: Option<Vec<(String, NpyArray)>> = None;
    if let Some(path) = string("matrices")? {
        empty_name("linear_rotor.matrices", path)?;
        if let Some(k) = ["m", "c", "g", "k", "kst", "spin_chart"].iter().find(|k| lr.contains_key(**k)) {
            return Err(Error::invalid(format!("linear_rotor.{k}"), "give the matrices either in the archive linear_rotor.matrices or one by one, not both"));
        }
        if !path.ends_with(".npz") {
            return Err(Error::invalid(
                "linear_rotor.matrices",
                format!("{path}: expected a NumPy .npz archive (np.savez(\"rotor.npz\", M=M, K=K, C=C, G=G))"),
            ));
        }
        let bytes = load(path).map_err(|e| Error::invalid("linear_rotor.matrices", format!("{path}: {e}")))?;
        archive = Some(npz_arrays(path, &bytes)?);
    }
    // the DOF table: of the config (linear_rotor.dofs) or of the archive (its array dofs)
    let mut tables: Vec<(Vec<Value>, &str)> = vec![];
    if let Some(a) = archive.iter().flatten().find(|(k, _)| k == "dofs").map(|(_, a)| a.clone()) {
        let NpyArray::Strings(names) = a else {
            return Err(Error::invalid("linear_rotor.matrices", "dofs: expected an array of strings (np.array([\"x0\", \"y0\", …]))"));
        };
        tables.push((names.into_iter().map(Value::String).collect(), "linear_rotor.matrices: dofs"));
    }
    match lr.get("dofs") {
        None => {}
        Some(Value::Array(names)) => tables.push((names.clone(), "linear_rotor.dofs")),
        Some(_) => return Err(Error::invalid("linear_rotor.dofs", "expected an array of DOF names (\"x0\", \"y0\", \"alpha0\", \"beta0\", \"x1\", …)")),
    }
    let elements = items(lr, "elements")?;
    let disks = items(lr, "disks")?;
    let (mut rotor, source) = if has_files {
        if !elements.is_empty() || !disks.is_empty() {
            return Err(Error::invalid("linear_rotor.elements", "give either matrix files (m, k, …) or the shaft builder's elements and disks, not both"));
        }
        let layout_key = match string("layout")? {
            None => None,
            Some("x,y") => Some(Layout::Translation),
            Some("x,y,alpha,beta") => Some(Layout::TranslationTilt),
            Some(o) => return Err(Error::invalid("linear_rotor.layout", format!("must be \"x,y\" or \"x,y,alpha,beta\" (ROSS's order), got \"{o}\""))),
        };
        let layout = layout_key.unwrap_or(Layout::TranslationTilt);
        // the nodes' DOFs from the DOF table, where it differs from node to node
        let mut node_layouts: Option<Vec<Layout>> = None;
        for (names, field) in &tables {
            let l = match layout_key {
                // alike at every node: the table must name them so (check_dofs below)
                Some(l) => vec![l; names.len().div_ceil(l.per_node())],
                // else the table says each node's DOFs
                None => layouts_from_dofs(names).map_err(|e| rename(e, "linear_rotor.dofs", field))?,
            };
            if node_layouts.as_ref().is_some_and(|p| *p != l) {
                return Err(Error::invalid(*field, "names other DOFs than linear_rotor.dofs: give the DOF table once"));
            }
            node_layouts = Some(l);
        }
        let matrices_path = string("matrices")?.unwrap_or("");
        let mut read = |k: &str, required: bool| -> Result<Option<(usize, Vec<f64>)>> {
            if let Some(arrays) = archive.as_mut() {
                let Some(i) = arrays.iter().position(|(key, _)| key == k) else {
                    return if required {
                        Err(Error::invalid("linear_rotor.matrices", format!("{matrices_path}: has no array {} (required)", k.to_uppercase())))
                    } else {
                        Ok(None)
                    };
                };
                let (_, a) = arrays.remove(i);
                return npy_matrix(a, "linear_rotor.matrices", &format!("{matrices_path}: {}", k.to_uppercase())).map(Some);
            }
            let Some(path) = string(k)? else {
                return if required { Err(Error::invalid(format!("linear_rotor.{k}"), "missing (required with matrix files)")) } else { Ok(None) };
            };
            matrix_file(&format!("linear_rotor.{k}"), path, load).map(Some)
        };
        let (n, m) = read("m", true)?.expect("required");
        // a positive diagonal this small is no mass or inertia in any units (the builder's
        // extreme element has ~1e-25): `M` times 1e-300 was reported as "the eigenvalue
        // iteration did not converge at Ω = 0", naming no key
        if let Some(i) = (0..n).find(|&i| m[i * n + i] > 0.0 && m[i * n + i] < 1.0 / MAX_ENTRY) {
            let field = if archive.is_some() { "linear_rotor.matrices" } else { "linear_rotor.m" };
            return Err(Error::invalid(
                field,
                format!("M[{i}, {i}] = {}: a mass or inertia below 1e-100 (the frequencies √(k/m) overflow)", crate::error::fmt_num(m[i * n + i])),
            ));
        }
        let mut r = match &node_layouts {
            Some(l) => {
                let r = LinearRotor::with_layouts(l);
                if r.dofs() != n {
                    return Err(Error::invalid(tables[0].1, format!("has {} names, the matrices {n} DOFs", tables[0].0.len())));
                }
                r
            }
            None => {
                if n % layout.per_node() != 0 {
                    return Err(Error::invalid("linear_rotor.m", format!("{n} DOFs is no multiple of {} DOFs per node (layout)", layout.per_node())));
                }
                LinearRotor::zeros(n / layout.per_node(), layout)
            }
        };
        // the shaft builder's switches mean nothing for matrices given as files (their G is
        // the gyroscopic matrix, their M holds whatever inertia they hold): refused by name,
        // not silently ignored (an independent check found `gyroscopic = false` with a G file
        // leaving G acting)
        for key in ["rotary_inertia", "gyroscopic"] {
            if lr.contains_key(key) {
                return Err(Error::invalid(
                    format!("linear_rotor.{key}"),
                    "is a shaft builder option (its elements' matrices); with matrix files the inertia is M's and the gyroscopic matrix the g file (leave g out for none)",
                ));
            }
        }
        r.m = m;
        r.polar_inertia = top.f64("polar_inertia")?.unwrap_or(0.0);
        for (k, required) in [("k", true), ("c", false), ("g", false), ("kst", false), ("spin_chart", false)] {
            if let Some((nk, a)) = read(k, required)? {
                if nk != n {
                    return Err(Error::invalid(format!("linear_rotor.{k}"), format!("is {nk} × {nk}, M is {n} × {n}")));
                }
                match k {
                    "k" => r.k = a,
                    "c" => r.c = a,
                    // the angular-acceleration stiffness K_st (LinearRotor::spin_stiffness)
                    "kst" => r.spin_stiffness = a,
                    // the tilt chart fixed to the rotor (LinearRotor::spin_chart)
                    "spin_chart" => r.spin_chart = a,
                    _ => r.g = a,
                }
            }
        }
        (r, "matrices")
    } else {
        if lr.contains_key("kst") {
            return Err(Error::invalid("linear_rotor.kst", "is read with matrix files (m, k, …); the shaft builder's rotor has K_st = G/2"));
        }
        if lr.contains_key("spin_chart") {
            return Err(Error::invalid("linear_rotor.spin_chart", "is read with matrix files (m, k, …); the shaft builder's rotor has no chart of its own"));
        }
        if let Some(l) = string("layout")? {
            if l != "x,y,alpha,beta" {
                return Err(Error::invalid("linear_rotor.layout", "the shaft builder's nodes have x, y, alpha, beta"));
            }
        }
        if elements.is_empty() {
            return Err(Error::invalid("linear_rotor", "give matrix files (m, k, and optionally c, g) or [[linear_rotor.elements]] for the shaft builder"));
        }
        let mut b = ShaftBuilder {
            rotary_inertia: boolean("rotary_inertia")?.unwrap_or(true),
            gyroscopic: boolean("gyroscopic")?.unwrap_or(true),
            ..Default::default()
        };
        for el in &elements {
            let length = el.req("length")?;
            let (e, rho) = (el.req("e")?, el.req("rho")?);
            // generous physical bounds, so that the element matrices (∝ E I / L³, ρ A L³) stay
            // finite and the eigenvalue solver meets no overflow: `length = 1e300` was reported
            // as `linear_rotor.m[0,3]: ... inf`, `e = 1e300` as a solver that did not converge
            within(&el.field("length"), length, (1e-6, false), 1e4, "m", "a micrometre to 10 km")?;
            within(&el.field("e"), e, (0.0, true), 1e13, "Pa", "stiffer than diamond (1.2e12 Pa) tenfold")?;
            within(&el.field("rho"), rho, (0.0, true), 1e5, "kg/m³", "denser than osmium (2.3e4 kg/m³) fourfold")?;
            let count = el.usize("count")?.unwrap_or(1);
            if count == 0 || count > 10_000 {
                return Err(Error::invalid(el.field("count"), "must be from 1 to 10000"));
            }
            // Timoshenko with the shear modulus g_s (κ: Cowper's for a circular section)
            let g_s = el.f64("g_s")?;
            if let Some(g) = g_s {
                // as e (`g_s = 1e300` was reported against `elements[0].shear`, no key)
                within(&el.field("g_s"), g, (0.0, true), 1e13, "Pa", "stiffer than diamond (1.2e12 Pa) tenfold")?;
            }
            let kappa = el.f64("kappa")?;
            if let Some(k) = kappa {
                within(&el.field("kappa"), k, (0.0, true), 10.0, "", "a shear coefficient: Cowper's for real sections lie between 0.5 and 1")?;
                if g_s.is_none() {
                    return Err(Error::invalid(el.field("kappa"), "is the shear coefficient of a Timoshenko element: give the shear modulus g_s too"));
                }
            }
            let element = match (el.f64("diameter")?, el.f64("area")?, el.f64("inertia")?) {
                (Some(d), None, None) => {
                    // (`diameter = 0` was reported against inner_diameter)
                    within(&el.field("diameter"), d, (1e-6, false), 1e3, "m", "a micrometre to a kilometre")?;
                    let di = el.f64("inner_diameter")?.unwrap_or(0.0);
                    if !(di >= 0.0 && di < d) {
                        return Err(Error::invalid(el.field("inner_diameter"), "must lie in [0, diameter)"));
                    }
                    let (o, i) = (Element::circular(length, d, e, rho), Element::circular(length, di, e, rho));
                    let area = o.area - i.area;
                    let shear = g_s.map(|g| kappa.unwrap_or_else(|| super::shaft::cowper_kappa(e / (2.0 * g) - 1.0, di / d)) * g * area);
                    Element { area, inertia: o.inertia - i.inertia, shear, ..o }
                }
                (None, Some(area), Some(inertia)) => {
                    // (it was silently ignored: the section is area and inertia as given)
                    if el.t.contains_key("inner_diameter") {
                        return Err(Error::invalid(
                            el.field("inner_diameter"),
                            "goes with diameter; with area and inertia the section is theirs (give the hollow section's area and inertia)",
                        ));
                    }
                    within(&el.field("area"), area, (0.0, true), 1e6, "m²", "the section of a kilometre-wide shaft")?;
                    within(&el.field("inertia"), inertia, (0.0, true), 1e12, "m⁴", "the section of a kilometre-wide shaft")?;
                    let shear = match (g_s, kappa) {
                        (Some(g), Some(k)) => Some(k * g * area),
                        (Some(_), None) => {
                            return Err(Error::invalid(el.field("kappa"), "required with g_s and area/inertia (the shear coefficient of the section)"))
                        }
                        _ => None,
                    };
                    Element { length, e, rho, area, inertia, shear }
                }
                _ => return Err(Error::invalid(el.field("diameter"), "give either diameter (and optionally inner_diameter) or both area and inertia")),
            };
            // the shear stiffness κ G A and the shear parameter Φ = 12 E I / (κ G A L²) that the
            // element's matrices hold (Φ²): finite and positive, or the key that made them not
            // (`g_s = 1e-300` was reported as `elements[0].shear: NaN`, `kappa = 1e-300` as
            // `linear_rotor.m[0,0]: NaN`)
            if let Some(sh) = element.shear {
                let phi = element.shear_parameter();
                if !(sh.is_finite() && sh > 0.0 && phi.is_finite() && phi <= 1e100) {
                    let f = crate::error::fmt_num;
                    let key = if kappa.is_some() { "kappa" } else { "g_s" };
                    return Err(Error::invalid(
                        el.field(key),
                        format!(
                            "gives the shear stiffness κ G A = {} N and the shear parameter Φ = 12 E I/(κ G A L²) = {}: not a Timoshenko element (κ G A must be positive and Φ at most 1e100; g_s is the shear modulus, ~E/2.6 for steel)",
                            f(sh),
                            f(phi)
                        ),
                    ));
                }
            }
            for _ in 0..count {
                b.elements.push(element);
            }
            // 4 DOFs per node, one node more than elements: name the entry whose count passes
            // the limit (`elements[0].count = 10000` said "linear_rotor DOFs: 40004 exceeds
            // the limit", naming no key)
            let dofs = 4 * (b.elements.len() + 1);
            if dofs > super::MAX_DOFS {
                return Err(Error::invalid(
                    el.field("count"),
                    format!(
                        "{count} elements bring the shaft to {} elements, {dofs} DOFs (4 per node), past the limit of {} (dense matrices): at most {} elements in all, fewer with balancer balls",
                        b.elements.len(),
                        super::MAX_DOFS,
                        super::MAX_DOFS / 4 - 1
                    ),
                ));
            }
        }
        for d in &disks {
            let disk = Disk { node: d.req_usize("node")?, mass: d.req("mass")?, id: d.f64("id")?.unwrap_or(0.0), ip: d.f64("ip")?.unwrap_or(0.0) };
            // (1e300 was taken, and gave natural frequencies of 1e-148 rad/s)
            within(&d.field("mass"), disk.mass, (0.0, false), 1e9, "kg", "no machine rotor exceeds 1e9 kg")?;
            within(&d.field("id"), disk.id, (0.0, false), 1e12, "kg·m²", "1e9 kg at 30 m")?;
            within(&d.field("ip"), disk.ip, (0.0, false), 1e12, "kg·m²", "1e9 kg at 30 m")?;
            b.disks.push(disk);
        }
        let mut r = b.build().map_err(|e| rename(e, "shaft.", "linear_rotor."))?;
        if let Some(ip) = top.f64("polar_inertia")? {
            // the config's value replaces the builder's Σ ρ J L + Σ I_p
            r.polar_inertia = ip;
        }
        (r, "shaft")
    };
    // the inertia fixed to the rotor (LinearRotor::rotor_fixed_mass), with matrix files or the
    // shaft builder: a file of its own, or the archive's array M_rot
    let archived = archive.as_mut().and_then(|a| a.iter().position(|(k, _)| k == "rotor_fixed_mass").map(|i| a.remove(i).1));
    let matrices_path = string("matrices")?.unwrap_or("");
    let fixed = match (string("rotor_fixed_mass")?, archived) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                "linear_rotor.rotor_fixed_mass",
                format!("{matrices_path} has M_rot too: give it either in the archive or as a file, not both"),
            ))
        }
        (Some(path), None) => Some(("linear_rotor.rotor_fixed_mass", matrix_file("linear_rotor.rotor_fixed_mass", path, load)?)),
        (None, Some(a)) => Some(("linear_rotor.matrices", npy_matrix(a, "linear_rotor.matrices", &format!("{matrices_path}: M_rot"))?)),
        (None, None) => None,
    };
    if let Some((field, (nf, a))) = fixed {
        let n = rotor.dofs();
        if nf != n {
            return Err(Error::invalid(field, format!("rotor_fixed_mass is {nf} × {nf}, M is {n} × {n}")));
        }
        rotor.rotor_fixed_mass = a;
    }
    // bearings: constant isotropic ones into K, C; tables over speed kept as speed bearings
    let mut constant_bearings: Vec<(String, f64, f64)> = Vec::new();
    // each table's name and whether it gave `cyy` (else `cxx` stands for it), as `speed_bearings`
    let mut table_names: Vec<(String, bool)> = Vec::new();
    for (i, br) in items(lr, "bearings")?.iter().enumerate() {
        let node = br.req_usize("node")?;
        if node >= rotor.nodes {
            return Err(Error::invalid(br.field("node"), format!("{node} is not a node (the nodes are 0 to {})", rotor.nodes.saturating_sub(1))));
        }
        // the node at the bearing's other side (a support mass), else ground
        let link = br.usize("link")?;
        if let Some(l) = link {
            if l >= rotor.nodes || l == node {
                return Err(Error::invalid(
                    br.field("link"),
                    format!("{l} is not a node other than the bearing's {node} (the nodes are 0 to {})", rotor.nodes.saturating_sub(1)),
                ));
            }
        }
        match br.array("speeds")? {
            None => {
                for k in ["kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"] {
                    if br.t.contains_key(k) {
                        return Err(Error::invalid(br.field(k), "tables over speed need `speeds`; a constant isotropic bearing has `k` and `c`"));
                    }
                }
                let (k, c) = (br.req("k")?, br.f64("c")?.unwrap_or(0.0));
                // limits.rs's bounds of the spatial rotor's supports (`k = 1e300` ended in an
                // eigenvalue solver that did not converge, naming no field)
                within(&br.field("k"), k, (0.0, false), 1e13, "N/m", STIFF)?;
                within(&br.field("c"), c, (0.0, false), 1e12, "N·s/m", DAMP)?;
                constant_bearings.push((br.field("c"), k, c));
                let Bearing { node, k, c } = Bearing { node, k, c };
                let (mut kk, mut cc) = (std::mem::take(&mut rotor.k), std::mem::take(&mut rotor.c));
                rotor.add_bearing_block(node, link, &[k, 0.0, 0.0, k], &mut kk);
                rotor.add_bearing_block(node, link, &[c, 0.0, 0.0, c], &mut cc);
                (rotor.k, rotor.c) = (kk, cc);
            }
            Some(speeds) => {
                let len = speeds.len();
                // (an empty table was reported against kxx: "has 2 entries, one per speed: 0")
                if len == 0 {
                    return Err(Error::invalid(br.field("speeds"), "is empty: give the speeds (rad/s) of the table, at least one"));
                }
                // a speed of the config's speed range (as drive.omega0: `speeds = [0, 1e300]`
                // was taken; `inf` was named against the i-th bearing with a table)
                for (j, w) in speeds.iter().enumerate() {
                    within_magnitude(&format!("{}[{j}]", br.field("speeds")), *w, 1e6, "rad/s", "±1e6 rad/s (~1e7 rpm), beyond every machine")?;
                }
                // (checked by the rotor's validation too, which named the i-th bearing with a
                // table, `bearings[0]` for the config's `bearings[1]`)
                if let Some(j) = (1..len).find(|&j| !(speeds[j] > speeds[j - 1])) {
                    let f = crate::error::fmt_num;
                    return Err(Error::invalid(
                        format!("{}[{j}]", br.field("speeds")),
                        format!("must increase strictly: {} after {}", f(speeds[j]), f(speeds[j - 1])),
                    ));
                }
                let col = |k: &str, fallback: Option<&str>| -> Result<Vec<f64>> {
                    let v = match br.array(k)? {
                        Some(v) => v,
                        None => match fallback.map(|f| br.array(f)).transpose()?.flatten() {
                            Some(v) => v,
                            None => vec![0.0; len],
                        },
                    };
                    if v.len() != len {
                        return Err(Error::invalid(br.field(k), format!("has {} entries, one per speed: {len}", v.len())));
                    }
                    // cross-coupled terms (kxy, kyx, cxy, cyx) may be negative, and so may a
                    // fluid film's direct stiffness: their magnitude is bounded. The direct
                    // damping cxx, cyy may not, as a constant bearing's `c` may not: a motion
                    // along x alone takes the power cxx ẋ² from the damper, negative for cxx < 0
                    // (a bearing that feeds the whirl; `cxx = -1e3` ran). (cyy's fallback is cxx.)
                    let (hi, unit, why) = if k.starts_with('k') { (1e13, "N/m", STIFF) } else { (1e12, "N·s/m", DAMP) };
                    let direct_damping = k == "cxx" || k == "cyy";
                    for (j, x) in v.iter().enumerate() {
                        let field = format!("{}[{j}]", br.field(k));
                        if direct_damping {
                            within(&field, *x, (0.0, false), hi, unit, why)?;
                        } else {
                            within_magnitude(&field, *x, hi, unit, why)?;
                        }
                    }
                    Ok(v)
                };
                if br.t.contains_key("k") || br.t.contains_key("c") {
                    return Err(Error::invalid(br.field("k"), "a bearing tabulated over speed takes kxx, kyy (kxy, kyx) and cxx, cyy (cxy, cyx), not k and c"));
                }
                if !br.t.contains_key("kxx") {
                    return Err(Error::invalid(br.field("kxx"), "missing (required with speeds)"));
                }
                let (kxx, kxy, kyx) = (col("kxx", None)?, col("kxy", None)?, col("kyx", None)?);
                let kyy = col("kyy", Some("kxx"))?;
                let (cxx, cxy, cyx) = (col("cxx", None)?, col("cxy", None)?, col("cyx", None)?);
                let cyy = col("cyy", Some("cxx"))?;
                let _ = i;
                table_names.push((br.name.clone(), br.t.contains_key("cyy")));
                rotor.speed_bearings.push(SpeedBearing {
                    node,
                    link,
                    speeds,
                    k: (0..len).map(|j| [kxx[j], kxy[j], kyx[j], kyy[j]]).collect(),
                    c: (0..len).map(|j| [cxx[j], cxy[j], cyx[j], cyy[j]]).collect(),
                });
            }
        }
    }
    check_bearing_damping(&rotor, &constant_bearings)?;
    check_table_damping(&rotor, constant_bearings.iter().map(|b| b.1).sum(), &table_names)?;
    for u in items(lr, "unbalance")? {
        if let Some(me) = u.f64("me")? {
            within_magnitude(&u.field("me"), me, 1e12, "kg·m", "1e9 kg at 1e3 m")?;
        }
        // (`offset = 1e300` ran to a step size of 0 at t = 0, `phase = 1e300` to an angle
        // without a digit left, neither naming the key)
        if let Some(o) = u.f64("offset")? {
            within_magnitude(&u.field("offset"), o, 1e3, "m", OFFSET)?;
        }
        if let Some(p) = u.f64("phase")? {
            within_magnitude(&u.field("phase"), p, 1e3, "rad", "an angle: 1e3 rad is ~160 turns, and every phase equals one within a turn")?;
        }
        rotor.unbalances.push(Unbalance {
            node: u.req_usize("node")?,
            me: u.req("me")?,
            phase: u.f64("phase")?.unwrap_or(0.0),
            offset: u.f64("offset")?.unwrap_or(0.0),
        });
    }
    for b in items(lr, "balancer")? {
        // (1e300 was taken: no stationary state at any speed, said as a failure of the solver)
        if let Some(r) = b.f64("radius")? {
            within(&b.field("radius"), r, (0.0, true), 1e3, "m", crate::limits::RADIUS)?;
        }
        if let Some(m) = b.f64("ball_mass")? {
            within(&b.field("ball_mass"), m, (0.0, true), 1e9, "kg", crate::limits::MASS)?;
        }
        // (`offset = 1e200` was reported as `linear_rotor.m: is not positive definite`)
        if let Some(o) = b.f64("offset")? {
            within_magnitude(&b.field("offset"), o, 1e3, "m", OFFSET)?;
        }
        // the ranges of the planar rotor's keys of the same meaning (`drag = 1e300` ran to
        // "neutral at every speed"; `rolling_resistance = -1` was taken as none, and
        // `contact_stiffness = 1e300` ran, both without a word)
        for (k, limit) in [
            ("drag", "planar.c_psi"),
            ("ball_diameter", "planar.ball_diameter"),
            ("restitution", "planar.restitution"),
            ("contact_stiffness", "planar.contact_stiffness"),
            ("rolling_resistance", "planar.rolling_resistance"),
            ("slip_rate", "planar.slip_rate"),
        ] {
            if let Some(v) = b.f64(k)? {
                // above 1 the balls' own check words it, as Python's `from_ross` reads it
                // (`BallPhysics::validate`: "… is not a rolling resistance (at most 1 …)")
                if k == "rolling_resistance" && v > 1.0 {
                    continue;
                }
                crate::limits::check_as(&b.field(k), limit, v)?;
            }
        }
        rotor.balancers.push(BalancerPlane {
            node: b.req_usize("node")?,
            radius: b.req("radius")?,
            balls: b.req_usize("balls")?,
            ball_mass: b.req("ball_mass")?,
            drag: b.f64("drag")?.unwrap_or(0.0),
            offset: b.f64("offset")?.unwrap_or(0.0),
        });
        // real balls (crate::balls), as the planar and spatial configs' keys
        let d = crate::balls::BallPhysics::default();
        let contact = match b.t.get("contact") {
            None => d.contact,
            Some(Value::Boolean(c)) => *c,
            Some(_) => return Err(Error::invalid(b.field("contact"), "expected true or false")),
        };
        let physics = crate::balls::BallPhysics {
            diameter: b.f64("ball_diameter")?,
            contact,
            restitution: b.f64("restitution")?.unwrap_or(d.restitution),
            contact_stiffness: b.f64("contact_stiffness")?,
            rolling_resistance: b.f64("rolling_resistance")?.unwrap_or(d.rolling_resistance),
            slip_rate: b.f64("slip_rate")?.unwrap_or(d.slip_rate),
        };
        // the contact law acts only through contact, the slip rate only with rolling resistance
        // (crate::balls): given without them they would have no effect, so they are refused
        // (this reader has no warnings to give; Python's add_balancer refuses them too)
        if let Some((k, why)) = crate::balls::moot_key(&physics, |k| b.t.contains_key(k)) {
            let lacks = match why {
                crate::balls::Moot::Contact => "contact = true",
                crate::balls::Moot::Rolling => "a rolling_resistance",
            };
            return Err(Error::invalid(b.field(k), format!("has no effect without {lacks}")));
        }
        rotor.ball_physics.push(physics);
    }
    if rotor.ball_physics.iter().all(|p| !p.is_active()) {
        rotor.ball_physics.clear();
    }
    rotor.spin_damping = top.f64("spin_damping")?.unwrap_or(0.0);
    // bounded as the rigid rotor's polar moment and a damper (`spin_damping = 1e300` ended a
    // torque-driven run at t = 0 with "the step size fell to 0", naming no key; `polar_inertia
    // = 1e300` was taken)
    within("linear_rotor.spin_damping", rotor.spin_damping, (0.0, false), 1e12, "N·m·s", "as planar.c_psi")?;
    if let Some(ip) = top.f64("polar_inertia")? {
        within("linear_rotor.polar_inertia", ip, (0.0, false), 1e12, "kg·m²", "1e9 kg at 30 m, as rotor.polar_moment")?;
    }
    match top.array("gravity")? {
        None => {}
        Some(g) if g.len() == 2 => {
            // spatial.gravity's range (`gravity = [0, -1e300]` ran, and stability said "stable:
            // nowhere" after every speed's integration became non-finite)
            for (i, v) in g.iter().enumerate() {
                within_magnitude(&format!("linear_rotor.gravity[{i}]"), *v, 1e6, "m/s²", "a million g")?;
            }
            rotor.set_gravity([g[0], g[1]])
        }
        Some(g) => {
            return Err(Error::invalid("linear_rotor.gravity", format!("expected [g_x, g_y] (m/s², across the axis in fixed axes), got {} numbers", g.len())))
        }
    }
    if let Some(load) = top.array("gravity_load")? {
        // the weight as written by export (a reduced rotor's Bᵀ load is not its M r_g)
        let Some(g) = rotor.gravity.as_mut() else { return Err(Error::invalid("linear_rotor.gravity_load", "needs gravity = [g_x, g_y]")) };
        if load.len() != g.load.len() {
            return Err(Error::invalid("linear_rotor.gravity_load", format!("has {} entries, one per DOF: {}", load.len(), g.load.len())));
        }
        // named as the config spells it (a NaN was reported against `gravity.load[0]`); the
        // weight of 1e9 kg under a million g at most
        for (i, v) in load.iter().enumerate() {
            within_magnitude(&format!("linear_rotor.gravity_load[{i}]"), *v, 1e15, "N", "the weight of 1e9 kg under a million g")?;
        }
        g.load = load;
    }
    for (names, field) in &tables {
        check_dofs(&rotor, names).map_err(|e| rename(e, "linear_rotor.dofs", field))?;
    }
    // the model's names: linear_rotor.unbalances[i] -> the config's linear_rotor.unbalance[i]
    rotor.validate().map_err(|e| rename(rename(e, "linear_rotor.unbalances", "linear_rotor.unbalance"), "linear_rotor.balancers", "linear_rotor.balancer"))?;
    let omega_max = top.f64("omega_max")?;
    if let Some(w) = omega_max {
        crate::error::positive("linear_rotor.omega_max", w)?;
        // the speed axis is sampled up to it: 1e308 overflowed to an infinite speed, reported
        // as "speeds: speeds: inf is not a finite speed" (limits.rs's SPEED bound)
        axis_speed("linear_rotor.omega_max", w)?;
    }
    // a number is rad/s (as omega_max), a string a speed with its unit; the bounds of omega_max
    let operating_speed = top.t.get("operating_speed").map(operating_speed).transpose()?;
    // 0: the full model (so that `--set linear_rotor.modes=0` undoes a config's reduction)
    let modes = top.usize("modes")?.filter(|m| *m > 0);
    // as the sweep path `linear_rotor.modes` (`modes = 99999999999` was taken; more pairs
    // than the interior has keep them all, and the run says how many)
    if let Some(m) = modes.filter(|m| *m > super::MAX_DOFS) {
        return Err(Error::invalid("linear_rotor.modes", format!("must be a whole number between 0 and {}, got {m}", super::MAX_DOFS)));
    }
    // the numbers of [drive] and [integration] in the ranges of the papers' configs
    // (`limits.rs`): `drive.omega0 = 1e300` at a constant speed ran, and ended at t = 0 with
    // "the state became non-finite", naming no key (a basins grid of such runs said "0 of 4
    // balanced", status 0)
    for name in ["drive", "integration"] {
        if let Some(t) = root.get(name).and_then(Value::as_table) {
            for (k, v) in t {
                crate::config::check_range(&format!("{name}.{k}"), v)?;
            }
        }
    }
    let d = Section::of(root, "drive");
    let drive = if d.table.is_some() { Some(drive(&d)?) } else { None };
    let t_end = drive.as_ref().map_or(10.0, |d| d.1);
    let integration = integration(&Section::of(root, "integration"), t_end)?;
    Ok(LinearRotorConfig { rotor, source, omega_max, operating_speed, modes, drive, integration })
}

/// `linear_rotor.operating_speed` in rad/s, `[lo, hi]`: a speed or range with its unit
/// ([`crate::units::speed_range_of_value`]), a bare number in rad/s, each in `(0, 1e6]` rad/s
/// (`linear_rotor.omega_max`'s range); the messages in rad/s (the spatial config's reader,
/// `crate::config::analysis_speed`, speaks of the dimensionless Ω). Python's
/// `LinearRotor.stability(operating_speed=...)` reads its argument here too.
pub fn operating_speed(v: &Value) -> Result<[f64; 2]> {
    const FIELD: &str = "linear_rotor.operating_speed";
    let reword = |e: Error| match e {
        Error::InvalidParameter { field, reason } => {
            Error::InvalidParameter { field, reason: reason.replace("a bare number for the dimensionless Ω", "a bare number in rad/s") }
        }
        e => e,
    };
    let (lo, hi) = crate::units::speed_range_of_value(FIELD, v).map_err(reword)?;
    let (lo, hi) = (lo.to_omega(FIELD, Some(1.0)).map_err(reword)?, hi.to_omega(FIELD, Some(1.0)).map_err(reword)?);
    axis_speed(FIELD, lo)?;
    axis_speed(FIELD, hi)?;
    Ok([lo, hi])
}

/// A speed on the linear rotor's speed axis (`linear_rotor.omega_max`, `operating_speed`) in
/// `(0, 1e6]` rad/s (limits.rs's SPEED bound).
fn axis_speed(field: &str, w: f64) -> Result<()> {
    if w > 0.0 && w <= 1e6 {
        return Ok(());
    }
    Err(Error::invalid(field, format!("must lie in (0, 1e6] rad/s, got {} (±1e6 rad/s, ~1e7 rpm, beyond every machine)", crate::error::fmt_num(w))))
}

/// The keys a linear rotor config's `[drive]` and `[integration]` take ([`crate::config::drive`],
/// [`crate::config::integration`]); any other is refused by name, as the planar and spatial
/// configs refuse theirs. The planar rotor's start (`psi0`, `psi_rate0`, `xy0`, `xy_rate0`) is
/// refused with the linear rotor's: its run starts at rest with the balls spread evenly
/// (`2π j / n` in each plane).
fn check_run_keys(root: &Table) -> Result<()> {
    // the planar rotor's start, which a linear config's run does not take
    const START: &[&str] = &["psi0", "psi_rate0", "xy0", "xy_rate0"];
    for name in ["drive", "integration"] {
        let Some(v) = root.get(name) else { continue };
        let t = v.as_table().ok_or_else(|| Error::invalid(name, "expected a table"))?;
        // the keys the shared readers take (crate::config::SCHEMA) but the start
        let known: Vec<&str> =
            crate::config::SCHEMA.iter().find(|(t, _)| *t == name).map_or(&[][..], |(_, k)| *k).iter().copied().filter(|k| !START.contains(k)).collect();
        for k in t.keys() {
            if known.contains(&k.as_str()) {
                continue;
            }
            let field = format!("{name}.{k}");
            return Err(if START.contains(&k.as_str()) {
                Error::invalid(field, "a linear rotor's run starts with the structure at rest on the axis and the balls spread evenly at rest relative to the rotor (2π j/n in each plane); its start is not set in the config (`autobal basins` varies the balls' angles)")
            } else {
                Error::invalid(field, format!("unknown key (known keys of [{name}] in a linear rotor config: {})", known.join(", ")))
            });
        }
    }
    Ok(())
}

/// The name of DOF `i` in the DOF table: direction and node, `x3`, `alpha3` (ROSS's spelling).
pub fn dof_key(rotor: &LinearRotor, i: usize) -> String {
    rotor.dof_node(i).map_or_else(|| format!("dof{i}"), |(k, d)| format!("{}{k}", d.key()))
}

/// The DOF table: `names[i]` must name DOF `i` in ROSS's order (`x3`, `alpha3`, …).
fn check_dofs(rotor: &LinearRotor, names: &[Value]) -> Result<()> {
    let n = rotor.dofs();
    if names.len() != n {
        return Err(Error::invalid("linear_rotor.dofs", format!("has {} names, the matrices {n} DOFs", names.len())));
    }
    for (i, v) in names.iter().enumerate() {
        let want = dof_key(rotor, i);
        if v.as_str() != Some(want.as_str()) {
            return Err(Error::invalid(format!("linear_rotor.dofs[{i}]"), format!("is {v}, ROSS's order has \"{want}\" there (x, y, alpha, beta per node)")));
        }
    }
    Ok(())
}

/// The nodes' DOFs named by a DOF table in ROSS's order: node after node from 0, each `x_k, y_k`
/// followed by `alpha_k, beta_k` where the node has tilts (`["x0", "y0", "alpha0", "beta0",
/// "x1", "y1"]`: node 0 `x, y, α, β`, node 1 `x, y`). Errors name the entry and what ROSS's
/// order has there.
pub fn layouts_from_dofs(names: &[Value]) -> Result<Vec<Layout>> {
    let mut layouts = vec![];
    // (node, DOFs of it seen so far)
    let (mut node, mut seen) = (0usize, 0usize);
    let is = |v: &Value, d: Direction, k: usize| v.as_str() == Some(format!("{}{k}", d.key()).as_str());
    for (i, v) in names.iter().enumerate() {
        let field = format!("linear_rotor.dofs[{i}]");
        let want =
            |w: String| Error::invalid(&field, format!("is {v}, ROSS's order has {w} there (x, y, then alpha, beta where the node has tilts, per node)"));
        match seen {
            0 | 1 => {
                let d = Direction::ALL[seen];
                if !is(v, d, node) {
                    return Err(want(format!("\"{}{node}\"", d.key())));
                }
                seen += 1;
            }
            2 if is(v, Direction::X, node + 1) => {
                layouts.push(Layout::Translation);
                (node, seen) = (node + 1, 1);
            }
            2 if is(v, Direction::Alpha, node) => seen = 3,
            2 => return Err(want(format!("\"alpha{node}\" or \"x{}\"", node + 1))),
            _ => {
                if !is(v, Direction::Beta, node) {
                    return Err(want(format!("\"beta{node}\"")));
                }
                layouts.push(Layout::TranslationTilt);
                (node, seen) = (node + 1, 0);
            }
        }
    }
    match seen {
        0 if layouts.is_empty() => Err(Error::invalid("linear_rotor.dofs", "names no DOF")),
        0 => Ok(layouts),
        2 => {
            layouts.push(Layout::Translation);
            Ok(layouts)
        }
        _ => Err(Error::invalid("linear_rotor.dofs", format!("ends inside node {node}: ROSS's order has {} next", if seen == 1 { "y" } else { "beta" }))),
    }
}

/// The model's field names in an error (`linear_rotor.balancers[0]`) as the config spells them
/// (`linear_rotor.balancer[0]`): a parameter's and a size limit's.
fn rename(e: Error, from: &str, to: &str) -> Error {
    match e {
        Error::InvalidParameter { field, reason } if field.starts_with(from) => Error::InvalidParameter { field: field.replacen(from, to, 1), reason },
        Error::TooLarge { what, size, limit, reason } if what.starts_with(from) => Error::TooLarge { what: what.replacen(from, to, 1), size, limit, reason },
        e => e,
    }
}

/// Parse Matrix Market text (`%%MatrixMarket matrix coordinate|array real|integer
/// general|symmetric|skew-symmetric`) into `(rows, cols, row-major entries)`; symmetric storage
/// holds the lower triangle (without the diagonal where skew), in the array format column by
/// column (as SciPy's `mmwrite` writes a dense symmetric matrix). Errors say the line.
pub fn parse_matrix_market(text: &str) -> std::result::Result<(usize, usize, Vec<f64>), String> {
    let mut lines = text.lines().enumerate();
    let (_, header) = lines.next().ok_or("empty file: expected the header %%MatrixMarket matrix coordinate real general")?;
    let h: Vec<String> = header.split_whitespace().map(|s| s.to_ascii_lowercase()).collect();
    if h.len() != 5 || h[0] != "%%matrixmarket" || h[1] != "matrix" {
        return Err(format!(
            "line 1: expected the header %%MatrixMarket matrix coordinate real general, got \"{}\"",
            header.chars().take(60).collect::<String>()
        ));
    }
    let coordinate = match h[2].as_str() {
        "coordinate" => true,
        "array" => false,
        o => return Err(format!("line 1: format \"{o}\" is not read (coordinate or array)")),
    };
    if !["real", "integer", "double"].contains(&h[3].as_str()) {
        return Err(format!("line 1: field \"{}\" is not read (real or integer)", h[3]));
    }
    let sym: i8 = match h[4].as_str() {
        "general" => 0,
        "symmetric" => 1,
        "skew-symmetric" => -1,
        o => return Err(format!("line 1: symmetry \"{o}\" is not read (general, symmetric, skew-symmetric)")),
    };
    let mut data = lines.filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('%'));
    let (ln, size) = data.next().ok_or("no size line after the header")?;
    let sz: Vec<usize> = size
        .split_whitespace()
        .map(|s| s.parse::<usize>().map_err(|_| format!("line {}: size: \"{s}\" is not a whole number", ln + 1)))
        .collect::<std::result::Result<_, _>>()?;
    let (rows, cols, nnz) = match (coordinate, sz.as_slice()) {
        (true, [r, c, nnz]) => (*r, *c, *nnz),
        (false, [r, c]) => (*r, *c, 0),
        _ => return Err(format!("line {}: expected the size line \"{}\"", ln + 1, if coordinate { "rows cols entries" } else { "rows cols" })),
    };
    // the size is checked before the array format's count is formed from it (`10000000000
    // 10000000000` overflowed r · c, a panic in a debug build)
    if rows == 0 || cols == 0 || rows > super::MAX_DOFS || cols > super::MAX_DOFS {
        return Err(format!("line {}: size {rows} × {cols} outside 1..{}", ln + 1, super::MAX_DOFS));
    }
    // the array format of a symmetric (skew-symmetric) matrix holds its lower triangle
    // (without the diagonal), column by column, as SciPy's `mmwrite` writes a dense one
    let count = if coordinate {
        nnz
    } else if sym == 0 {
        rows * cols
    } else if sym > 0 {
        rows * (rows + 1) / 2
    } else {
        rows * (rows - 1) / 2
    };
    if sym != 0 && rows != cols {
        return Err(format!("line {}: a {} matrix must be square, got {rows} × {cols}", ln + 1, h[4]));
    }
    // the array format's (row, column) of each entry in turn: column-major, the lower triangle
    // where the matrix is symmetric
    let array_at: Vec<(usize, usize)> = if coordinate {
        vec![]
    } else {
        (0..cols).flat_map(|j| (0..rows).filter(move |i| sym == 0 || (sym > 0 && *i >= j) || (sym < 0 && *i > j)).map(move |i| (i, j))).collect()
    };
    let mut a = vec![0.0; rows * cols];
    let value = |s: &str, ln: usize| -> std::result::Result<f64, String> {
        let v: f64 = s.parse().map_err(|_| format!("line {}: \"{s}\" is not a number", ln + 1))?;
        if !v.is_finite() {
            return Err(format!("line {}: {s} is not finite", ln + 1));
        }
        Ok(v)
    };
    let mut seen = 0;
    for (ln, line) in data {
        let f: Vec<&str> = line.split_whitespace().collect();
        if seen == count {
            return Err(format!("line {}: more entries than the {count} the size line announces", ln + 1));
        }
        if coordinate {
            let [i, j, v] = f.as_slice() else { return Err(format!("line {}: expected \"row col value\", got {} fields", ln + 1, f.len())) };
            let idx = |s: &str, max: usize| -> std::result::Result<usize, String> {
                match s.parse::<usize>() {
                    Ok(k) if k >= 1 && k <= max => Ok(k - 1),
                    _ => Err(format!("line {}: index \"{s}\" outside 1..{max}", ln + 1)),
                }
            };
            let (i, j, v) = (idx(i, rows)?, idx(j, cols)?, value(v, ln)?);
            a[i * cols + j] += v;
            if sym != 0 && i != j {
                a[j * cols + i] += sym as f64 * v;
            }
        } else {
            let [v] = f.as_slice() else { return Err(format!("line {}: expected one value, got {} fields", ln + 1, f.len())) };
            let (i, j) = array_at[seen];
            let v = value(v, ln)?;
            a[i * cols + j] = v;
            if sym != 0 && i != j {
                a[j * cols + i] = sym as f64 * v;
            }
        }
        seen += 1;
    }
    if seen != count {
        return Err(format!("{seen} entries, the size line announces {count}"));
    }
    Ok((rows, cols, a))
}

/// Matrix Market text (`coordinate real general`, the nonzero entries, numbers written so that
/// they read back exactly) of the row-major `n × n` matrix `a`, with a comment line.
pub fn write_matrix_market(a: &[f64], n: usize, comment: &str) -> String {
    let nz: Vec<(usize, f64)> = a.iter().copied().enumerate().filter(|(_, v)| *v != 0.0).collect();
    let mut s = format!("%%MatrixMarket matrix coordinate real general\n% {comment}\n{n} {n} {}\n", nz.len());
    for (ij, v) in nz {
        s.push_str(&format!("{} {} {v:e}\n", ij / n + 1, ij % n + 1));
    }
    s
}

/// The config text and the matrix files (`STEM_M.mtx`, `STEM_C.mtx`, `STEM_G.mtx`,
/// `STEM_K.mtx`, `STEM_M_rot.mtx` where the rotor has inertia fixed to it
/// ([`LinearRotor::rotor_fixed_mass`]), `STEM_KST.mtx` where it has a
/// [`LinearRotor::spin_stiffness`] and `STEM_chart.mtx` where it has a
/// [`LinearRotor::spin_chart`]: name and text) of `rotor`: reading them back with
/// [`linear_rotor`] gives the same rotor.
pub fn export(rotor: &LinearRotor, stem: &str) -> (String, Vec<(String, String)>) {
    let n = rotor.dofs();
    let mut files = vec![];
    let mut t = String::from("# A linear rotor (autobal export-model): M q'' + (C + Ω G) q' + K q = f, DOFs in ROSS's order\n[linear_rotor]\n");
    if rotor.node_layouts.is_empty() {
        // alike at every node (else the DOF table below says each node's)
        t.push_str(&format!("layout = \"{}\"\n", if rotor.layout == Layout::Translation { "x,y" } else { "x,y,alpha,beta" }));
    }
    for (key, a, what) in [
        ("m", &rotor.m, "mass matrix M (kg, kg m²)"),
        ("c", &rotor.c, "damping matrix C"),
        ("g", &rotor.g, "gyroscopic matrix G (multiplied by Ω)"),
        ("k", &rotor.k, "stiffness matrix K"),
        ("kst", &rotor.spin_stiffness, "angular-acceleration stiffness K_st (multiplied by dΩ/dt)"),
        ("spin_chart", &rotor.spin_chart, "tilt chart Σ fixed to the rotor (spin angle s = ½ q_rᵀ Σ q_r)"),
    ] {
        if a.is_empty() {
            // no K_st: G/2 (LinearRotor::spin_stiffness); no chart (LinearRotor::spin_chart)
            continue;
        }
        let name = if key == "spin_chart" { format!("{stem}_chart.mtx") } else { format!("{stem}_{}.mtx", key.to_uppercase()) };
        // quoted as TOML quotes it (a stem with `"` or `\\` wrote a config that did not parse)
        t.push_str(&format!("{key} = {}\n", Value::String(name.clone())));
        files.push((name, write_matrix_market(a, n, &format!("{what}, {n} DOFs"))));
    }
    if !rotor.rotor_fixed_mass.is_empty() {
        let name = format!("{stem}_M_rot.mtx");
        t.push_str(&format!("rotor_fixed_mass = {}\n", Value::String(name.clone())));
        files.push((
            name,
            write_matrix_market(&rotor.rotor_fixed_mass, n, &format!("inertia fixed to the rotor M_rot (kg, kg m², in axes turning with it), {n} DOFs")),
        ));
    }
    let names: Vec<String> = (0..n).map(|i| format!("\"{}\"", dof_key(rotor, i))).collect();
    t.push_str(&format!("dofs = [{}]\n", names.join(", ")));
    if rotor.polar_inertia != 0.0 {
        t.push_str(&format!("polar_inertia = {:?}\n", rotor.polar_inertia));
    }
    if rotor.spin_damping != 0.0 {
        t.push_str(&format!("spin_damping = {:?}\n", rotor.spin_damping));
    }
    if let Some(g) = &rotor.gravity {
        // the weight is recomputed from M on reading (M r_g), or written where it is not that
        // (a reduced rotor's Bᵀ load)
        t.push_str(&format!("gravity = [{:?}, {:?}]\n", g.g[0], g.g[1]));
        let mut again = rotor.clone();
        again.set_gravity(g.g);
        if again.gravity.as_ref().map(|a| &a.load) != Some(&g.load) {
            t.push_str(&format!("gravity_load = {:?}\n", g.load));
        }
    }
    for b in &rotor.speed_bearings {
        t.push_str(&format!("\n[[linear_rotor.bearings]]\nnode = {}\n", b.node));
        if let Some(l) = b.link {
            t.push_str(&format!("link = {l}\n"));
        }
        t.push_str(&format!("speeds = {:?}\n", b.speeds));
        for (j, k) in ["kxx", "kxy", "kyx", "kyy"].iter().enumerate() {
            t.push_str(&format!("{k} = {:?}\n", b.k.iter().map(|v| v[j]).collect::<Vec<_>>()));
        }
        for (j, k) in ["cxx", "cxy", "cyx", "cyy"].iter().enumerate() {
            t.push_str(&format!("{k} = {:?}\n", b.c.iter().map(|v| v[j]).collect::<Vec<_>>()));
        }
    }
    for u in &rotor.unbalances {
        t.push_str(&format!("\n[[linear_rotor.unbalance]]\nnode = {}\nme = {:?}\nphase = {:?}\noffset = {:?}\n", u.node, u.me, u.phase, u.offset));
    }
    for (i, b) in rotor.balancers.iter().enumerate() {
        t.push_str(&format!(
            "\n[[linear_rotor.balancer]]\nnode = {}\nradius = {:?}\nballs = {}\nball_mass = {:?}\ndrag = {:?}\noffset = {:?}\n",
            b.node, b.radius, b.balls, b.ball_mass, b.drag, b.offset
        ));
        if let Some(p) = rotor.ball_physics.get(i).filter(|p| p.is_active()) {
            // only the keys that act (the reader refuses the others)
            t.push_str(&format!("contact = {}\n", p.contact));
            if p.contact {
                t.push_str(&format!("restitution = {:?}\n", p.restitution));
                if let Some(d) = p.diameter {
                    t.push_str(&format!("ball_diameter = {d:?}\n"));
                }
                if let Some(k) = p.contact_stiffness {
                    t.push_str(&format!("contact_stiffness = {k:?}\n"));
                }
            }
            if p.rolling_resistance != 0.0 {
                t.push_str(&format!("rolling_resistance = {:?}\nslip_rate = {:?}\n", p.rolling_resistance, p.slip_rate));
            }
        }
    }
    (t, files)
}
