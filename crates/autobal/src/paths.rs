//! Parameter paths: a dotted name for every number of a model's description, spelled as the
//! config spells it (`planar.c_psi`, `drive.b`, `dimensionless.z_a`), so that sweeps, maps and
//! front ends change a parameter without going back through a config file.
//!
//! Each description type has **one table** of its paths ([`Parameters::parameter_paths`]) of
//! one entry type, [`ParameterPath`] (paper 004's [`crate::planar::problem::PlanarProblem`],
//! the spatial rotor's [`crate::spatial::paths::SpatialSpec`]); a path is read and written
//! through it, and every error names the path. Setting a path changes the description only;
//! validation happens when the description is used (a simulation, a model derivation), where
//! the error names the field again.
//!
//! An [`Axis`] is a path and the values it takes: the one axis type of sweeps
//! ([`crate::sweep::Grid`]), stability maps ([`crate::spatial::map`], [`crate::rotor_map`]) and
//! traced boundaries ([`crate::spatial::boundary`], which follow curves over the axis's range
//! `[first, last]` instead of visiting its values).
//!
//! ```
//! use autobal::paths::Parameters;
//! use autobal::planar::problem::PlanarProblem;
//!
//! let mut p = PlanarProblem::paper_004(0.03);
//! p.set("planar.c_psi", 0.2).unwrap();
//! p.set("drive.b", 5.0).unwrap();
//! assert_eq!(p.get("planar.c_psi").unwrap(), 0.2);
//! let e = p.set("planar.c_pis", 1.0).unwrap_err();
//! assert!(e.to_string().starts_with("planar.c_pis: unknown parameter path"));
//! ```

use crate::error::{fmt_num, Error, Result};
use serde::Serialize;

/// One settable number of a description `T`: its path, what it is, and how to read and write it.
/// The accessors return a bare reason; [`Parameters::set`] and [`Parameters::get`] put the path
/// in front of it.
pub struct ParameterPath<T: 'static> {
    /// Dotted path as the config spells it (`table.key`).
    pub path: &'static str,
    /// What it is, with its unit.
    pub doc: &'static str,
    /// Write the value.
    pub set: fn(&mut T, f64) -> std::result::Result<(), String>,
    /// Read the value.
    pub get: fn(&T) -> std::result::Result<f64, String>,
}

/// A description (model input, problem) whose numbers can be addressed by path.
pub trait Parameters: Sized + 'static {
    /// The table of every path of this description.
    fn parameter_paths() -> &'static [ParameterPath<Self>];

    /// Names an axis may take beside the table's paths, which are not fields of the
    /// description (the spatial maps' speed axes `omega`, `speed_rpm`, ...): listed first in the
    /// error for an unknown path. None by default.
    fn other_paths() -> &'static [&'static str] {
        &[]
    }

    /// Set the number at `path` to `value`.
    fn set(&mut self, path: &str, value: f64) -> Result<()> {
        let p = find::<Self>(path)?;
        (p.set)(self, value).map_err(|reason| Error::invalid(path, reason))
    }

    /// The number at `path`.
    fn get(&self, path: &str) -> Result<f64> {
        let p = find::<Self>(path)?;
        (p.get)(self).map_err(|reason| Error::invalid(path, reason))
    }

    /// A copy with every `(path, value)` set, in order.
    fn with(&self, assignments: &[(&str, f64)]) -> Result<Self>
    where
        Self: Clone,
    {
        let mut t = self.clone();
        for (p, v) in assignments {
            t.set(p, *v)?;
        }
        Ok(t)
    }
}

/// The entry of `path` in `T`'s table; an unknown path is an error listing the known ones.
pub fn find<T: Parameters>(path: &str) -> Result<&'static ParameterPath<T>> {
    T::parameter_paths().iter().find(|p| p.path == path).ok_or_else(|| {
        let known: Vec<&str> = T::other_paths().iter().copied().chain(T::parameter_paths().iter().map(|p| p.path)).collect();
        Error::invalid(path, format!("unknown parameter path (known: {})", known.join(", ")))
    })
}

/// One axis of a sweep, a map or a traced boundary: a parameter path (or a map's speed axis,
/// `omega`, `speed_rpm`, ...) and its values in order. A linear range `lo..=hi` of `n` points is
/// [`Axis::linspace`]; a list is [`Axis::new`]; the text forms are [`Axis::parse`]. Serialised
/// as its range `{path, lo, hi}` (a large map's values are not repeated in a JSON).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Parameter path (`planar.c_psi`, `drive.b`, `dimensionless.z_a`, `omega`, ...).
    pub path: String,
    /// The values, in order.
    pub values: Vec<f64>,
}

impl Serialize for Axis {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("Axis", 3)?;
        st.serialize_field("path", &self.path)?;
        st.serialize_field("lo", &self.lo())?;
        st.serialize_field("hi", &self.hi())?;
        st.end()
    }
}

impl Axis {
    /// An axis with the given values.
    pub fn new(path: impl Into<String>, values: Vec<f64>) -> Self {
        Axis { path: path.into(), values }
    }

    /// `n` equally spaced values from `lo` to `hi` (both included, exactly; `n = 1` gives `lo`):
    /// `v_i = lo + (hi − lo) i/(n − 1)`. Inner values are rounded to 12 significant digits so
    /// that they read as typed (`0.4`, not `0.39999999999999997`): a grid value is the same
    /// number whichever process computes it.
    pub fn linspace(path: impl Into<String>, lo: f64, hi: f64, n: usize) -> Self {
        let values = (0..n)
            .map(|i| {
                if i == 0 {
                    return lo;
                }
                if i + 1 == n {
                    return hi;
                }
                round12(lo + (hi - lo) * i as f64 / (n - 1) as f64)
            })
            .collect();
        Axis { path: path.into(), values }
    }

    /// A range `[lo, hi]` for the boundary tracer, which needs no values between: the two ends.
    pub fn range(path: impl Into<String>, lo: f64, hi: f64) -> Self {
        Axis { path: path.into(), values: vec![lo, hi] }
    }

    /// The first value (NaN for an axis without values).
    pub fn lo(&self) -> f64 {
        self.values.first().copied().unwrap_or(f64::NAN)
    }

    /// The last value (NaN for an axis without values).
    pub fn hi(&self) -> f64 {
        self.values.last().copied().unwrap_or(f64::NAN)
    }

    /// An axis from its text form: `PATH=LO:HI:N` (`N ≥ 2` equally spaced values, see
    /// [`Axis::linspace`]), `PATH=V1,V2,…` (a list) or `PATH=V` (one value). Errors quote the
    /// spec (the caller puts the option in front).
    ///
    /// ```
    /// use autobal::paths::Axis;
    /// assert_eq!(Axis::parse("drive.b=0.5:2.5:3").unwrap().values, vec![0.5, 1.5, 2.5]);
    /// assert_eq!(Axis::parse("planar.m3=0.01,0.03").unwrap().values, vec![0.01, 0.03]);
    /// assert!(Axis::parse("drive.b=2:1:3").unwrap_err().to_string().contains("HI must exceed LO"));
    /// // a repeated value would run the same point twice
    /// assert!(Axis::parse("drive.b=1,2,1").unwrap_err().to_string().contains("the value 1 is given more than once"));
    /// ```
    pub fn parse(spec: &str) -> Result<Self> {
        let bad = |why: String| Error::invalid(spec, why);
        let (path, range) = spec.split_once('=').ok_or_else(|| bad("expected PATH=LO:HI:N, PATH=V1,V2,… or PATH=V, e.g. drive.b=0.5:12.5:5".into()))?;
        let path = path.trim();
        if path.is_empty() {
            return Err(bad("the parameter path is empty".into()));
        }
        let num = |s: &str, what: &str| -> Result<f64> {
            match s.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(bad(format!("{what} must be finite"))),
                Err(_) => Err(bad(format!("{what} `{}` is not a number", s.trim()))),
            }
        };
        let parts: Vec<&str> = range.split(':').collect();
        match parts.len() {
            3 => {
                let (lo, hi) = (num(parts[0], "LO")?, num(parts[1], "HI")?);
                let n: usize = parts[2].trim().parse().map_err(|_| bad(format!("N `{}` is not a whole number", parts[2].trim())))?;
                if !(2..=1_000_000).contains(&n) {
                    return Err(bad(format!("N must lie between 2 and 1000000, got {n}")));
                }
                if !(hi > lo) {
                    return Err(bad("HI must exceed LO".into()));
                }
                let ax = Axis::linspace(path, lo, hi, n);
                // (1:1.000000000001:1000 rounded its inner values to 12 digits onto each other)
                if let Some(v) = repeated(&ax.values) {
                    return Err(bad(format!(
                        "{n} points from LO to HI repeat the value {} (values are rounded to 12 significant digits): give fewer points or a wider range",
                        fmt_num(v)
                    )));
                }
                Ok(ax)
            }
            1 => {
                let values = range.split(',').map(|s| num(s, "value")).collect::<Result<Vec<_>>>()?;
                // (drive.b=1,1,1 ran one point three times)
                if let Some(v) = repeated(&values) {
                    return Err(bad(format!("the value {} is given more than once: each value is one point of the grid", fmt_num(v))));
                }
                Ok(Axis::new(path, values))
            }
            _ => Err(bad("expected PATH=LO:HI:N".into())),
        }
    }
}

/// A value that occurs more than once in `values` (`0` and `-0` are one value), if any.
pub(crate) fn repeated(values: &[f64]) -> Option<f64> {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    v.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
}

/// `v` rounded to 12 significant digits (0 stays 0).
fn round12(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let mag = 10f64.powi(11 - v.abs().log10().floor() as i32);
    let r = (v * mag).round() / mag;
    if r.is_finite() {
        r
    } else {
        v
    }
}

/// A whole number from a path value (numbers of balls): `0 ≤ v ≤ max`, no fraction.
pub fn whole(v: f64, max: u64) -> std::result::Result<u64, String> {
    if v.fract() == 0.0 && v >= 0.0 && v <= max as f64 {
        Ok(v as u64)
    } else {
        Err(format!("must be a whole number between 0 and {max}, got {}", fmt_num(v)))
    }
}

/// `name[j]` with a 1-based index `j` (`drive.psi0[2]`: the second ball's initial angle):
/// the name and the 0-based index, or `None` when `path` has no index. The index is spelled as
/// [`index_digits`] reads it (`drive.psi0[01]` and `drive.psi0[ 1]` were taken as
/// `drive.psi0[1]`, so that two axes could set one number, one of them silently lost).
pub fn indexed(path: &str) -> Option<(&str, std::result::Result<usize, String>)> {
    let (name, rest) = path.split_once('[')?;
    let j = rest.strip_suffix(']')?;
    Some((
        name,
        match index_digits(j) {
            Some(j) if j >= 1 => Ok(j - 1),
            _ => Err(format!("the index in [{j}] must be a whole number from 1 (the first ball), in digits without sign, space or leading zero")),
        },
    ))
}

/// An index as every parameter path spells it (`drive.psi0[2]`, `linear_rotor.balancer[0]`):
/// decimal digits, no sign, space or leading zero, so that one number has one path.
pub fn index_digits(s: &str) -> Option<usize> {
    let canonical = !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) && (s == "0" || !s.starts_with('0'));
    canonical.then(|| s.parse().ok()).flatten()
}

/// `path` with every bracketed index that is a whole number written as [`index_digits`]
/// spells it (`drive.psi0[01]` -> `drive.psi0[1]`, `a[ 2 ].b` -> `a[2].b`), the rest as it is:
/// the form in which two paths naming one number compare equal.
pub fn canonical(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut rest = path;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..=open]);
        rest = &rest[open + 1..];
        let Some(close) = rest.find(']') else { break };
        let inner = rest[..close].trim();
        let digits = inner.strip_prefix('+').unwrap_or(inner);
        match digits.parse::<u128>() {
            Ok(j) if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) => out.push_str(&j.to_string()),
            _ => out.push_str(&rest[..close]),
        }
        rest = &rest[close..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A list with a value twice, or a range whose rounded values collide, is refused naming the
    /// value; distinct values (in any order, `0` and a tiny one) are kept as given.
    #[test]
    fn repeated_values_are_refused() {
        let e = Axis::parse("drive.b=1,1,1").unwrap_err().to_string();
        assert_eq!(e, "drive.b=1,1,1: the value 1 is given more than once: each value is one point of the grid");
        assert!(Axis::parse("drive.b=0,-0").unwrap_err().to_string().contains("the value 0 is given more than once"));
        let e = Axis::parse("drive.b=1:1.000000000001:1000").unwrap_err().to_string();
        assert!(e.contains("1000 points from LO to HI repeat the value"), "{e}");
        assert_eq!(Axis::parse("drive.b=3,1,2,1e-300,0").unwrap().values, vec![3.0, 1.0, 2.0, 1e-300, 0.0]);
        assert_eq!(Axis::parse("drive.b=1:1.0000000001:3").unwrap().values, vec![1.0, 1.00000000005, 1.0000000001]);
        // (the middle of 1 and 1.00000000001 rounds onto one of them)
        assert!(Axis::parse("drive.b=1:1.00000000001:3").unwrap_err().to_string().contains("repeat the value"));
    }

    /// One number, one path: an index with a leading zero, a sign or a space is refused (it was
    /// trimmed and parsed, so `drive.psi0[01]` set `drive.psi0[1]`), and such spellings have
    /// the canonical form of the index they spell.
    #[test]
    fn index_spelled_one_way() {
        for j in ["01", " 1", "1 ", "+1", "", "1.0", "-1"] {
            let p = format!("drive.psi0[{j}]");
            let e = indexed(&p).unwrap().1.unwrap_err();
            assert!(e.contains("without sign, space or leading zero"), "{p}: {e}");
        }
        assert_eq!(indexed("drive.psi0[10]"), Some(("drive.psi0", Ok(9))));
        assert_eq!(index_digits("0"), Some(0));
        assert_eq!(index_digits("00"), None);
        assert_eq!(canonical("drive.psi0[01]"), "drive.psi0[1]");
        assert_eq!(canonical("drive.psi0[ +1 ]"), "drive.psi0[1]");
        assert_eq!(canonical("linear_rotor.bearings[00].kxx[003]"), "linear_rotor.bearings[0].kxx[3]");
        assert_eq!(canonical("a[x].b[-1]"), "a[x].b[-1]");
        assert_eq!(canonical("drive.b"), "drive.b");
        assert_eq!(canonical("a[1"), "a[1");
    }

    #[test]
    fn indices_are_one_based_and_checked() {
        assert_eq!(indexed("drive.psi0[2]"), Some(("drive.psi0", Ok(1))));
        assert!(indexed("drive.psi0[0]").unwrap().1.is_err());
        assert!(indexed("drive.psi0[x]").unwrap().1.is_err());
        assert_eq!(indexed("drive.psi0"), None);
        assert_eq!(whole(3.0, 9), Ok(3));
        assert!(whole(2.5, 9).is_err() && whole(10.0, 9).is_err() && whole(-1.0, 9).is_err() && whole(f64::NAN, 9).is_err());
    }
}
