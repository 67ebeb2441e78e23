//! Sensitivity criterion of the critical speeds to the balancer's inertia anisotropy
//! (000, eqs (21)-(22); 003, eqs (4)-(5)).

use crate::spatial::critical_speeds::{branch_roots, ModeKind};
use crate::spatial::params::SpatialModel;
use serde::Serialize;

/// Recommended permissible relative error of the angular critical speeds, `[δΩ_Kα] = 0.15`.
pub const DEFAULT_LIMIT: f64 = 0.15;

/// Verdict of the sensitivity criterion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivity {
    /// `δΩ_Kα1,2 = (Ω_Kα1,2 − Ω_Kα0)/Ω_Kα1,2` from the exact roots of eq (16) (000, eq (21)).
    /// An angular critical speed that the anisotropy pushes to infinity counts as its
    /// limit `δ = 1`; `None` when the isotropic rotor has no angular critical speed.
    pub delta_exact: [Option<f64>; 2],
    /// Eq (22): `δΩ_Kα1,2 ≈ 1 − sqrt(1 ± ΔĀ/(1 − C̄Σ))`; `None` where the root is imaginary.
    pub delta_approx: [Option<f64>; 2],
    /// `δΩ_Kα = max |δΩ_Kα1,2|` (exact).
    pub coefficient: Option<f64>,
    /// The same from eq (22).
    pub coefficient_approx: Option<f64>,
    /// `[δΩ_Kα]`, the permissible error.
    pub limit: f64,
    /// Threshold `[ΔĀ0] = |1 − C̄Σ| (1 − (1 − [δΩ_Kα])²)` (003, eq (5)).
    pub delta_a_limit: f64,
    /// `[m̄0] = 2 [ΔĀ0] / R̄0²`, the unbalance mass at the threshold, when `R̄0` is known.
    pub m0_limit: Option<f64>,
    /// Whether the finite-mass model is needed (`δΩ_Kα > [δΩ_Kα]`).
    pub finite_mass_model_needed: bool,
    /// One sentence explaining the verdict.
    pub reason: String,
}

fn angular_root(delta_i: f64, p: f64, c: f64) -> Option<f64> {
    branch_roots(delta_i, p, c).into_iter().find(|r| r.1 == ModeKind::Angular).map(|r| r.0.sqrt())
}

/// Evaluate the criterion for the anisotropy in use and permissible error `limit`.
pub fn sensitivity(model: &SpatialModel, limit: f64) -> Sensitivity {
    let (p, c, d) = (model.p_alpha_sq, model.c_y_alpha, model.anisotropy.used);
    let di0 = 1.0 - model.c_sigma;
    let iso = angular_root(di0, p, c);
    let delta_exact = [di0 + d, di0 - d].map(|di| {
        iso.map(|w0| match angular_root(di, p, c) {
            Some(w) => (w - w0) / w,
            None => 1.0,
        })
    });
    let delta_approx = [1.0, -1.0].map(|s| {
        let arg = 1.0 + s * d / di0;
        (arg >= 0.0 && di0 != 0.0).then(|| 1.0 - arg.sqrt())
    });
    let maxabs = |v: [Option<f64>; 2]| -> Option<f64> {
        match (v[0], v[1]) {
            (Some(a), Some(b)) => Some(a.abs().max(b.abs())),
            (Some(a), None) | (None, Some(a)) => Some(a.abs()),
            _ => None,
        }
    };
    let coefficient = maxabs(delta_exact);
    let coefficient_approx = maxabs(delta_approx);
    let delta_a_limit = di0.abs() * (1.0 - (1.0 - limit).powi(2));
    // an unbalance (almost) on the axis has no mass limit
    let m0_limit = model.masses.filter(|m| m.r0 > 0.0).map(|m| 2.0 * delta_a_limit / (m.r0 * m.r0)).filter(|v| v.is_finite());
    let (needed, reason) = match coefficient {
        None => (false, "the isotropic rotor has no angular critical speed (short rotor): the simplified model suffices (003)".to_string()),
        Some(k) if k > limit => (true, format!("δΩ_Kα = {k:.4} exceeds [δΩ_Kα] = {limit}: the masses of unbalance and balls must be modelled")),
        Some(k) => (false, format!("δΩ_Kα = {k:.4} ≤ [δΩ_Kα] = {limit}: the simplified model suffices")),
    };
    Sensitivity { delta_exact, delta_approx, coefficient, coefficient_approx, limit, delta_a_limit, m0_limit, finite_mass_model_needed: needed, reason }
}
