//! Parameter paths: a dotted name for every number of a model's description, spelled as the
//! config spells it (`planar.c_psi`, `drive.b`, `dimensionless.z_a`), so that sweeps, maps and
//! front ends change a parameter without going back through a config file.
//!
//! Each description type has **one table** of its paths ([`Parameters::parameter_paths`]); a
//! path is read and written through it, and every error names the path. Setting a path changes
//! the description only; validation happens when the description is used (a simulation, a
//! model derivation), where the error names the field again.
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
        let known: Vec<&str> = T::parameter_paths().iter().map(|p| p.path).collect();
        Error::invalid(path, format!("unknown parameter path (known: {})", known.join(", ")))
    })
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
/// the name and the 0-based index, or `None` when `path` has no index.
pub fn indexed(path: &str) -> Option<(&str, std::result::Result<usize, String>)> {
    let (name, rest) = path.split_once('[')?;
    let j = rest.strip_suffix(']')?;
    Some((
        name,
        match j.trim().parse::<usize>() {
            Ok(j) if j >= 1 => Ok(j - 1),
            _ => Err(format!("the index in [{j}] must be a whole number from 1 (the first ball)")),
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

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
