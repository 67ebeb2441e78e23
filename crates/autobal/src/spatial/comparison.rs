//! The exact stability of the balanced state compared with 003's necessary conditions
//! (eqs (1)-(3)): where they agree, where 003's condition holds but the state is unstable, and
//! where the state is stable although the condition fails.
//!
//! ```
//! use autobal::spatial::comparison::compare;
//! use autobal::spatial::linear_model::Balls;
//! use autobal::spatial::params::{DimensionlessInput, SpatialModel};
//!
//! let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
//! let c = compare(&m, 5.0, 400, Balls::Free).unwrap();
//! // 003's upper range Ω > Ω_K4 is not stable in the papers' own base case
//! assert!(!c.necessary_not_stable.is_empty());
//! ```

use crate::error::Result;
use crate::spatial::linear_model::Balls;
use crate::spatial::params::SpatialModel;
use crate::spatial::ranges::{autobalancing_ranges, SpeedRange};
use crate::spatial::stability::{stability_ranges, StabilityRanges};
use serde::Serialize;

/// Bisection tolerance on the ends of the exact ranges (dimensionless speed).
pub const RANGE_TOLERANCE: f64 = 1e-9;

/// Exact stability against 003's necessary conditions over `(0, Ω_max]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// The exact ranges ([`stability_ranges`]).
    pub exact: StabilityRanges,
    /// 003's necessary ranges, clipped to `(0, Ω_max]` (`hi = None`: reaches `Ω_max`).
    pub necessary: Vec<SpeedRange>,
    /// Where 003's condition holds but the balanced state is unstable.
    pub necessary_not_stable: Vec<SpeedRange>,
    /// Where the balanced state is stable but 003's condition fails.
    pub stable_not_necessary: Vec<SpeedRange>,
    /// The end of the span.
    pub omega_max: f64,
}

/// Clip ranges to `[0, w]` as closed pairs.
fn clip(r: &[SpeedRange], w: f64) -> Vec<(f64, f64)> {
    r.iter().filter(|x| x.lo < w).map(|x| (x.lo, x.hi.map_or(w, |h| h.min(w)))).collect()
}

/// `a \ b` for sorted disjoint interval lists (pieces shorter than 1e-9 dropped).
fn minus(a: &[(f64, f64)], b: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out = vec![];
    for &(lo, hi) in a {
        let mut cur = lo;
        for &(blo, bhi) in b {
            if bhi <= cur || blo >= hi {
                continue;
            }
            if blo > cur {
                out.push((cur, blo));
            }
            cur = cur.max(bhi);
        }
        if cur < hi {
            out.push((cur, hi));
        }
    }
    out.into_iter().filter(|(l, h)| h - l > 1e-9).collect()
}

fn to_ranges(v: &[(f64, f64)], w: f64) -> Vec<SpeedRange> {
    v.iter().map(|&(lo, hi)| SpeedRange { lo, hi: if hi >= w { None } else { Some(hi) } }).collect()
}

/// Exact stability ranges (`samples` grid speeds, ends to [`RANGE_TOLERANCE`]) against 003's
/// necessary ranges over `(0, omega_max]`.
pub fn compare(model: &SpatialModel, omega_max: f64, samples: usize, balls: Balls) -> Result<Comparison> {
    let exact = stability_ranges(model, omega_max, samples, balls, RANGE_TOLERANCE)?;
    let nec = autobalancing_ranges(model).ranges;
    let (e, n) = (clip(&exact.stable_ranges, omega_max), clip(&nec, omega_max));
    Ok(Comparison {
        necessary: to_ranges(&n, omega_max),
        necessary_not_stable: to_ranges(&minus(&n, &e), omega_max),
        stable_not_necessary: to_ranges(&minus(&e, &n), omega_max),
        exact,
        omega_max,
    })
}

/// Total length of ranges, `hi = None` counted to `w`.
fn total(r: &[SpeedRange], w: f64) -> f64 {
    r.iter().map(|x| x.hi.unwrap_or(w) - x.lo).sum::<f64>() + 0.0 // + 0.0: an empty sum is −0
}

/// `a – b` or `a – ∞` (a range without upper end, as 003's ranges above `Ω_K4`).
pub fn fmt_range(r: &SpeedRange, prec: usize) -> String {
    fmt_range_in(r, prec, None)
}

/// `a – b`; without upper end `a – ∞` (`span_end = None`), or `a – W (end of the span)` for
/// ranges computed over `(0, W]` only ([`Comparison`]), which reach `W` and are not known
/// beyond it.
pub fn fmt_range_in(r: &SpeedRange, prec: usize, span_end: Option<f64>) -> String {
    match (r.hi, span_end) {
        (Some(h), _) => format!("{:.prec$} – {:.prec$}", r.lo, h),
        (None, None) => format!("{:.prec$} – ∞", r.lo),
        (None, Some(w)) => {
            // the span's end as given (`2`, not `2.000000`), at most to the ranges' precision
            let end = format!("{w:.prec$}");
            let end = if end.contains('.') { end.trim_end_matches('0').trim_end_matches('.') } else { &end };
            format!("{:.prec$} – {end} (end of the span)", r.lo)
        }
    }
}

/// Ranges as `a – b, c – ∞`, or `none`.
pub fn fmt_ranges(r: &[SpeedRange], prec: usize) -> String {
    fmt_ranges_in(r, prec, None)
}

/// Ranges as `a – b, c – W (end of the span)` ([`fmt_range_in`]), or `none`.
pub fn fmt_ranges_in(r: &[SpeedRange], prec: usize, span_end: Option<f64>) -> String {
    if r.is_empty() {
        "none".into()
    } else {
        r.iter().map(|x| fmt_range_in(x, prec, span_end)).collect::<Vec<_>>().join(", ")
    }
}

impl Comparison {
    /// The difference in one sentence.
    pub fn difference(&self) -> String {
        let w = self.omega_max;
        match (self.necessary_not_stable.is_empty(), self.stable_not_necessary.is_empty()) {
            (true, true) => "the exact stability ranges coincide with 003's necessary ranges".into(),
            _ => format!(
                "003's condition holds but the balanced state is unstable on {} (total {:.4}); the balanced state is stable where 003's condition fails on {} (total {:.4})",
                fmt_ranges_in(&self.necessary_not_stable, 4, Some(w)),
                total(&self.necessary_not_stable, w),
                fmt_ranges_in(&self.stable_not_necessary, 4, Some(w)),
                total(&self.stable_not_necessary, w)
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interval_difference() {
        assert_eq!(minus(&[(0.0, 5.0)], &[(1.0, 2.0), (3.0, 4.0)]), vec![(0.0, 1.0), (2.0, 3.0), (4.0, 5.0)]);
        assert_eq!(minus(&[(1.0, 2.0)], &[(0.0, 3.0)]), vec![]);
        assert_eq!(to_ranges(&[(1.0, 5.0)], 5.0), vec![SpeedRange { lo: 1.0, hi: None }]);
        assert_eq!(total(&[], 1.0).to_bits(), 0.0f64.to_bits());
        // a range cut at the span's end is not an unbounded one
        let cut = [SpeedRange { lo: 1.5, hi: None }];
        assert_eq!(fmt_ranges(&cut, 2), "1.50 – ∞");
        assert_eq!(fmt_ranges_in(&cut, 2, Some(2.0)), "1.50 – 2 (end of the span)");
    }
}
