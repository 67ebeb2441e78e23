//! Speed ranges where autobalancing is possible (003, eqs (1)-(3)).
//!
//! Necessary condition (1), written without dividing by anything that may vanish:
//! `N(Ω) / Δ_2(Ω) > 0` with `N = (ΔĪ02 + z̄²) Ω² − (p̄α² + 2 z̄ c̄yα + z̄²)` and
//! `Δ_2` the factor of eq (15) at `ΔĪ02 = 1 − C̄Σ − ΔĀ0` (its leading coefficient cancels the
//! `1/ΔĪ02` of the printed form). Split-pair instability: `Δ_1 Δ_2 < 0`. The ranges are the
//! speeds where the first holds and the second does not, found from the signs between the
//! sorted roots, so unusual orderings of `Ω_K2, Ω_a, Ω_K3, Ω_K4` come out right.
//!
//! Sign conventions: the forced response of the locked rotor to the unbalance in plane A is
//! `ξ̄_A = −m̄0 R̄0 Ω² N(Ω)/Δ_2(Ω)` (in units of `ρ_s`), so (1) is the statement that A moves
//! against the unbalance (003's "engineering phase criterion").

use crate::spatial::critical_speeds::{branch_roots, delta_k};
use crate::spatial::params::SpatialModel;
use serde::Serialize;

/// A speed interval `[lo, hi)`, `hi = None` when unbounded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpeedRange {
    /// Lower end.
    pub lo: f64,
    /// Upper end, `None` for `+∞`.
    pub hi: Option<f64>,
}

impl SpeedRange {
    /// Whether `omega` lies strictly inside.
    pub fn contains(&self, omega: f64) -> bool {
        omega > self.lo && self.hi.is_none_or(|h| omega < h)
    }
}

/// Rotor class for autobalancing (003): long `C̄Σ0 < 1 − ΔĀ0`, near-spherical
/// `1 − ΔĀ0 ≤ C̄Σ0 ≤ 1 − ΔĀ0 + z̄²`, short beyond.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BalancingClass {
    /// Two ranges expected: `Ω1 < Ω < Ω2` and `Ω > Ω3`.
    Long,
    /// One bounded range.
    NearSpherical,
    /// One range bounded below.
    Short,
}

impl BalancingClass {
    /// The class as every output names it: "autobalancing class (003)" with its kebab-case name
    /// and defining inequality (not 000's Table 1 class,
    /// [`crate::spatial::critical_speeds::RotorClass`], "inertia class", which counts critical
    /// speeds from `ΔĀ` rather than `ΔĀ0` and `z̄_A`).
    pub fn label(self) -> &'static str {
        match self {
            BalancingClass::Long => "long (C̄Σ0 < 1 − ΔĀ0: two ranges expected, Ω1 < Ω < Ω2 and Ω > Ω3)",
            BalancingClass::NearSpherical => "near-spherical (1 − ΔĀ0 ≤ C̄Σ0 ≤ 1 − ΔĀ0 + z̄_A²: one bounded range)",
            BalancingClass::Short => "short (C̄Σ0 > 1 − ΔĀ0 + z̄_A²: one range bounded below)",
        }
    }
}

/// Result of the autobalancing-range analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AutobalancingRanges {
    /// Antiresonance speed `Ω_a` (003, eq (1)), when real.
    pub antiresonance_speed: Option<f64>,
    /// Critical speeds of the unbalanced rotor `Ω_K1..4` (anisotropy `ΔĀ0`), ascending.
    pub critical_speeds: Vec<f64>,
    /// Where condition (1) holds.
    pub phase_condition: Vec<SpeedRange>,
    /// Split-pair instability ranges (`Δ_1 Δ_2 < 0`).
    pub instability: Vec<SpeedRange>,
    /// Where autobalancing is possible: (1) holds and the rotor is not unstable.
    pub ranges: Vec<SpeedRange>,
    /// 003's classification.
    pub class: BalancingClass,
}

/// `N(Ω) = (ΔĪ02 + z̄²) Ω² − (p̄α² + 2 z̄ c̄yα + z̄²)`.
fn numerator(model: &SpatialModel, omega: f64) -> f64 {
    let (p, c, z) = (model.p_alpha_sq, model.c_y_alpha, model.z_a);
    let di02 = 1.0 - model.c_sigma - model.delta_a0;
    (di02 + z * z) * omega * omega - (p + 2.0 * z * c + z * z)
}

/// Antiresonance speed `Ω_a² = (p̄α² + 2 z̄ c̄yα + z̄²)/(ΔĪ02 + z̄²)` (003, eq (1)); the speed where
/// plane A of the locked, undamped rotor stands still. `None` when `Ω_a²` is not positive.
pub fn antiresonance_speed(model: &SpatialModel) -> Option<f64> {
    let (p, c, z) = (model.p_alpha_sq, model.c_y_alpha, model.z_a);
    let di02 = 1.0 - model.c_sigma - model.delta_a0;
    let x = (p + 2.0 * z * c + z * z) / (di02 + z * z);
    (x > 0.0 && x.is_finite()).then(|| x.sqrt())
}

/// Signed synchronous response of plane A per unit unbalance `m̄0 R̄0`:
/// `ξ̄_A / (m̄0 R̄0) = −Ω² N(Ω)/Δ_2(Ω)` (003, Fig. 3). Negative where A moves against the
/// unbalance, i.e. where autobalancing is possible.
pub fn point_a_response(model: &SpatialModel, omega: f64) -> f64 {
    let d2 = delta_k(1.0 - model.c_sigma - model.delta_a0, model.p_alpha_sq, model.c_y_alpha, omega);
    -omega * omega * numerator(model, omega) / d2
}

/// Intervals of `Ω > 0` where `pred` holds, given every point where it may change.
fn sign_set(mut breaks: Vec<f64>, pred: impl Fn(f64) -> bool) -> Vec<SpeedRange> {
    breaks.retain(|b| *b > 0.0 && b.is_finite());
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() <= 1e-14 * b.abs());
    let mut edges = vec![0.0];
    edges.extend(breaks);
    let mut out: Vec<SpeedRange> = vec![];
    for i in 0..edges.len() {
        let lo = edges[i];
        let hi = edges.get(i + 1).copied();
        let mid = match hi {
            Some(h) => 0.5 * (lo + h),
            None => 2.0 * lo + 1.0,
        };
        if pred(mid) {
            match out.last_mut() {
                Some(last) if last.hi == Some(lo) => last.hi = hi,
                _ => out.push(SpeedRange { lo, hi }),
            }
        }
    }
    out
}

/// Autobalancing ranges of 003 from the sign conditions themselves.
///
/// ```
/// use autobal::spatial::params::{DimensionlessInput, SpatialModel};
/// use autobal::spatial::ranges::autobalancing_ranges;
/// let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_003(0.8)).unwrap();
/// let r = autobalancing_ranges(&m);
/// let round = |x: f64| (x * 1e4).round() / 1e4;
/// // 003's long rotor: from the upper end of the first split pair to the antiresonance, and
/// // beyond the second split pair
/// assert_eq!(round(r.antiresonance_speed.unwrap()), 2.2403);
/// let ends: Vec<(f64, Option<f64>)> = r.ranges.iter().map(|x| (round(x.lo), x.hi.map(round))).collect();
/// assert_eq!(ends, [(0.8492, Some(2.2403)), (3.8007, None)]);
/// ```
pub fn autobalancing_ranges(model: &SpatialModel) -> AutobalancingRanges {
    let (p, c, z) = (model.p_alpha_sq, model.c_y_alpha, model.z_a);
    let d0 = model.delta_a0;
    let di = [1.0 - model.c_sigma + d0, 1.0 - model.c_sigma - d0];
    let mut crit: Vec<f64> = di.iter().flat_map(|&d| branch_roots(d, p, c)).map(|r| r.0.sqrt()).collect();
    crit.sort_by(f64::total_cmp);
    let wa = antiresonance_speed(model);
    let mut breaks = crit.clone();
    breaks.extend(wa);
    let d1 = |w: f64| delta_k(di[0], p, c, w);
    let d2 = |w: f64| delta_k(di[1], p, c, w);
    let phase = |w: f64| numerator(model, w) * d2(w) > 0.0;
    let unstable = |w: f64| d1(w) * d2(w) < 0.0;
    let class = if model.c_sigma < 1.0 - d0 {
        BalancingClass::Long
    } else if model.c_sigma <= 1.0 - d0 + z * z {
        BalancingClass::NearSpherical
    } else {
        BalancingClass::Short
    };
    AutobalancingRanges {
        antiresonance_speed: wa,
        critical_speeds: crit.clone(),
        phase_condition: sign_set(breaks.clone(), phase),
        instability: sign_set(crit, unstable),
        ranges: sign_set(breaks, |w| phase(w) && !unstable(w)),
        class,
    }
}
