//! Critical speeds of the composite rotor with the balls locked at balance (000, eqs (14)-(20),
//! Table 1).
//!
//! With `s ≡ 0` and no damping the frequency equation in rotating axes is
//! `det K(Ω) = Δ1 Δ2 = 0` (000, eq (15)),
//! `Δ_k = ΔĪ_k Ω⁴ − (p̄α² + ΔĪ_k) Ω² + p̄α² − c̄yα²`, `ΔĪ_1,2 = 1 − C̄Σ ± ΔĀ`.
//! Each `Δ_k` is a quadratic in `x = Ω²` whose discriminant is
//! `(p̄α² − ΔĪ)² + 4 ΔĪ c̄yα² ≥ 0` whenever `p̄α² ≥ c̄yα²` (always so for real supports).
//! The roots are computed with the cancellation-free form `q = ½(p̄α² + ΔĪ + sqrt(disc))`,
//! `x₁ = q/ΔĪ`, `x₂ = (p̄α² − c̄yα²)/q`, which also covers the spherical limit `ΔĪ → 0`
//! (`x₂ → 1 − c̄yα²/p̄α²`, `x₁ → ∞`).

use crate::spatial::params::SpatialModel;
use serde::Serialize;

/// Dominant motion of a critical speed, by continuation to the uncoupled limit `c̄yα → 0`,
/// where the transverse root is `Ω² = 1` and the angular one `Ω² = p̄α²/ΔĪ`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ModeKind {
    /// Translation of the centre of mass dominates (`Ω_Kx`).
    Transverse,
    /// Tilt dominates (`Ω_Kα`).
    Angular,
}

/// Rotor class of 000's Table 1 (short-rotor boundary corrected to `C̄Σ > 1 + ΔĀ`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RotorClass {
    /// `C̄Σ < 1 − ΔĀ`: both `ΔĪ_k > 0`.
    Long,
    /// `1 − ΔĀ ≤ C̄Σ ≤ 1 + ΔĀ`: `ΔĪ_1 ≥ 0 ≥ ΔĪ_2`.
    NearSpherical,
    /// `C̄Σ > 1 + ΔĀ`: both `ΔĪ_k < 0`.
    Short,
}

impl RotorClass {
    /// Class of 000's Table 1, with its short-rotor typo corrected (the table prints
    /// `C̄Σ > 1 − ΔĀ`; its own `ΔĪ_1,2 < 0` column requires `C̄Σ > 1 + ΔĀ`).
    pub fn of(c_sigma: f64, delta_a: f64) -> Self {
        if c_sigma < 1.0 - delta_a {
            RotorClass::Long
        } else if c_sigma <= 1.0 + delta_a {
            RotorClass::NearSpherical
        } else {
            RotorClass::Short
        }
    }

    /// The class as every output names it: "inertia class (000 Table 1)" with its kebab-case
    /// name (`long`, `near-spherical`, `short`) and its defining inequality. 003 classifies
    /// rotors again, by their autobalancing ranges ([`crate::spatial::ranges::BalancingClass`],
    /// "autobalancing class (003)"): the two can differ for one rotor (003's boundary has
    /// `+ z̄_A²`), hence the two labels.
    pub fn label(self) -> &'static str {
        match self {
            RotorClass::Long => "long (C̄Σ < 1 − ΔĀ: both ΔĪ_k > 0)",
            RotorClass::NearSpherical => "near-spherical (1 − ΔĀ ≤ C̄Σ ≤ 1 + ΔĀ: ΔĪ_1 ≥ 0 ≥ ΔĪ_2)",
            RotorClass::Short => "short (C̄Σ > 1 + ΔĀ: both ΔĪ_k < 0)",
        }
    }

    /// Number of distinct critical speeds Table 1 predicts (generic parameters).
    pub fn table1_count(self, delta_a: f64, symmetric: bool) -> usize {
        // below 1e-9 the split (of order ΔĀ) is below the resolution of `distinct_count`
        if delta_a <= 1e-9 {
            return if self == RotorClass::Long { 2 } else { 1 };
        }
        match (self, symmetric) {
            (RotorClass::Long, false) => 4,
            (RotorClass::NearSpherical, false) => 3,
            (RotorClass::Short, false) => 2,
            (RotorClass::Long, true) => 3,
            (RotorClass::NearSpherical, true) => 2,
            (RotorClass::Short, true) => 1,
        }
    }
}

/// `Δ_k(Ω) = ΔĪ Ω⁴ − (p̄α² + ΔĪ) Ω² + p̄α² − c̄yα²` (000, eq (15)).
pub fn delta_k(delta_i: f64, p_sq: f64, c: f64, omega: f64) -> f64 {
    let x = omega * omega;
    (delta_i * x - (p_sq + delta_i)) * x + p_sq - c * c
}

/// Positive roots `x = Ω²` of `Δ_k`, ascending, each with its kind (see module docs).
pub fn branch_roots(delta_i: f64, p_sq: f64, c: f64) -> Vec<(f64, ModeKind)> {
    let c0 = p_sq - c * c;
    let disc = ((p_sq - delta_i).powi(2) + 4.0 * delta_i * c * c).max(0.0);
    let q = 0.5 * (p_sq + delta_i + disc.sqrt());
    let mut roots: Vec<f64> = vec![];
    if q != 0.0 {
        roots.push(c0 / q);
        if delta_i != 0.0 {
            roots.push(q / delta_i);
        }
    } else if delta_i != 0.0 {
        // b = 0 and disc = 0: ΔĪ x² + (p̄α² − c̄yα²) = 0
        let x2 = -c0 / delta_i;
        if x2 > 0.0 {
            roots.push(x2.sqrt());
        }
    }
    let mut pos: Vec<f64> = roots.into_iter().filter(|x| *x > 0.0 && x.is_finite()).collect();
    pos.sort_by(f64::total_cmp);
    let lower_is_transverse = delta_i <= 0.0 || p_sq >= delta_i;
    match pos.len() {
        0 => vec![],
        1 => {
            // ΔĪ ≤ 0: the one positive root continues to Ω² = 1 (transverse). ΔĪ > 0 with
            // p̄α² ≤ c̄yα² (not reachable with real supports): only the upper root survives.
            let kind = if delta_i > 0.0 && lower_is_transverse { ModeKind::Angular } else { ModeKind::Transverse };
            vec![(pos[0], kind)]
        }
        _ => {
            let (lo, hi) = if lower_is_transverse { (ModeKind::Transverse, ModeKind::Angular) } else { (ModeKind::Angular, ModeKind::Transverse) };
            vec![(pos[0], lo), (pos[1], hi)]
        }
    }
}

/// One critical speed with its approximations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalSpeed {
    /// Dimensionless critical speed `Ω_K = ω_K/ω0` (exact root of eq (16)).
    pub omega: f64,
    /// Transverse or angular.
    pub kind: ModeKind,
    /// Which factor it is a root of: 1 (`ΔĪ_1 = 1 − C̄Σ + ΔĀ`) or 2 (`ΔĪ_2 = 1 − C̄Σ − ΔĀ`).
    pub branch: u8,
    /// Eq (18), symmetric layout: `Ω² = 1` or `p̄α²/ΔĪ_k`.
    pub approx_symmetric: Option<f64>,
    /// Eq (19), near-symmetric layout: `Ω² ≈ 1 − c̄yα²/(p̄α² − ΔĪ_k)` or
    /// `p̄α²/ΔĪ_k + c̄yα²/(p̄α² − ΔĪ_k)`.
    pub approx_near_symmetric: Option<f64>,
    /// Eq (20), small anisotropy: `Ω² ≈ Ω0² (1 ∓ (Ω0² − 1) ΔĀ / (2(1 − C̄Σ)Ω0² − p̄α² − 1 + C̄Σ))`,
    /// `−` for branch 1, `+` for branch 2 (the paper prints the branch-1 sign only).
    pub approx_small_anisotropy: Option<f64>,
    /// Range of this critical speed over the anisotropy interval in use (multi-ball
    /// balancers); `None` when it exists only at one end.
    pub interval: Option<[f64; 2]>,
    /// SI value (rad/s) when the model is dimensional.
    pub omega_rad_s: Option<f64>,
    /// SI value (rpm) when the model is dimensional.
    pub rpm: Option<f64>,
}

/// All critical speeds of a model, with Table 1's classification.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalSpeeds {
    /// Ascending.
    pub speeds: Vec<CriticalSpeed>,
    /// Number of distinct values (a double root counts once).
    pub distinct_count: usize,
    /// Table 1 class.
    pub rotor_class: RotorClass,
    /// Count Table 1 predicts for this class and layout.
    pub table1_count: usize,
}

fn sqrt_pos(x: f64) -> Option<f64> {
    (x > 0.0 && x.is_finite()).then(|| x.sqrt())
}

/// Exact critical speeds at a given `ΔĀ` (roots of both factors, ascending, labelled).
pub fn critical_speeds_at(model: &SpatialModel, delta_a: f64) -> Vec<(f64, ModeKind, u8)> {
    let (p, c) = (model.p_alpha_sq, model.c_y_alpha);
    let di0 = 1.0 - model.c_sigma;
    let mut all = vec![];
    for (branch, di) in [(1u8, di0 + delta_a), (2u8, di0 - delta_a)] {
        for (x, kind) in branch_roots(di, p, c) {
            all.push((x.sqrt(), kind, branch));
        }
    }
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.2.cmp(&b.2)));
    all
}

/// Critical speeds of the composite rotor (000, eq (16)) with approximations (18)-(20),
/// Table 1 classification, intervals over the anisotropy interval, and SI values.
///
/// ```
/// use autobal::spatial::critical_speeds::critical_speeds;
/// use autobal::spatial::params::{DimensionlessInput, SpatialModel};
/// // 003's worked example at l̄_L = 0.8 (ΔĀ = 0.1): Ω_K = 0.84, 0.85, 2.52, 3.80 as printed
/// let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_003(0.8)).unwrap();
/// let k: Vec<f64> = critical_speeds(&m).speeds.iter().map(|c| (c.omega * 100.0).round() / 100.0).collect();
/// assert_eq!(k, [0.84, 0.85, 2.52, 3.80]);
/// ```
pub fn critical_speeds(model: &SpatialModel) -> CriticalSpeeds {
    let d = model.anisotropy.used;
    let (p, c) = (model.p_alpha_sq, model.c_y_alpha);
    let di0 = 1.0 - model.c_sigma;
    let iso = branch_roots(di0, p, c);
    let [ilo, ihi] = model.anisotropy.used_interval;
    let at_lo = critical_speeds_at(model, ilo);
    let at_hi = critical_speeds_at(model, ihi);
    let speeds: Vec<CriticalSpeed> = critical_speeds_at(model, d)
        .into_iter()
        .map(|(omega, kind, branch)| {
            let di = if branch == 1 { di0 + d } else { di0 - d };
            let s = if branch == 1 { 1.0 } else { -1.0 };
            let (sym, near) = match kind {
                ModeKind::Transverse => (Some(1.0), sqrt_pos(1.0 - c * c / (p - di))),
                ModeKind::Angular => (sqrt_pos(p / di), sqrt_pos(p / di + c * c / (p - di))),
            };
            let small = iso.iter().find(|(_, k)| *k == kind).and_then(|&(x0, _)| sqrt_pos(x0 * (1.0 - s * (x0 - 1.0) * d / (2.0 * di0 * x0 - p - di0))));
            let find = |v: &[(f64, ModeKind, u8)]| v.iter().find(|r| r.1 == kind && r.2 == branch).map(|r| r.0);
            let interval = match (find(&at_lo), find(&at_hi)) {
                (Some(a), Some(b)) => Some([a.min(b), a.max(b)]),
                _ => None,
            };
            let omega0 = model.scale.map(|s| s.omega0);
            CriticalSpeed {
                omega,
                kind,
                branch,
                approx_symmetric: sym,
                approx_near_symmetric: near,
                approx_small_anisotropy: small,
                interval,
                omega_rad_s: omega0.map(|w| w * omega),
                rpm: omega0.map(|w| w * omega * 30.0 / std::f64::consts::PI),
            }
        })
        .collect();
    let mut distinct = 0;
    let mut last = f64::NEG_INFINITY;
    for s in &speeds {
        if (s.omega - last).abs() > 1e-9 * s.omega.max(1.0) {
            distinct += 1;
        }
        last = s.omega;
    }
    let class = RotorClass::of(model.c_sigma, d);
    CriticalSpeeds { speeds, distinct_count: distinct, rotor_class: class, table1_count: class.table1_count(d, c == 0.0) }
}
