//! The balanced state of a [`LinearRotor`] and its stability over speed: the pipeline of
//! [`crate::rotor_stability`] (the same [`RotorStability`] result, model `"linear"`) on
//! [`LinearRotorField`] in axes turning with the rotor — an equilibrium (eigenvalues) for an
//! isotropic structure without gravity, a periodic orbit (Floquet multipliers) otherwise: of
//! half a revolution for direction-dependent supports, of one under gravity —
//! started at each speed from [`LinearRotorField::balanced_guess`].

use super::field::{Frame, LinearRotorField};
use super::LinearRotor;
use crate::analysis::{speed_scan, Kind, ScanOptions, VectorField};
use crate::error::{Error, Result};
use crate::rotor_stability::{RotorStability, SpeedPoint};

/// The stationary state of `rotor` and its stability at each of `speeds` (ascending, rad/s),
/// with the ends of the stable ranges bisected (as [`crate::rotor_stability::stability_over_speed`]).
pub fn stability_over_speed(rotor: &LinearRotor, speeds: &[f64]) -> Result<RotorStability> {
    if speeds.is_empty() {
        return Err(Error::invalid("speeds", "no speed to analyse"));
    }
    let field = |w: f64| LinearRotorField::new(rotor, w, Frame::Rotating);
    let first = field(speeds[0])?;
    let kind = if first.period().is_some() { Kind::PeriodicOrbit } else { Kind::Equilibrium };
    let mut opts = ScanOptions::default();
    if kind == Kind::PeriodicOrbit {
        opts.newton.max_iterations = 20;
        opts.newton.rtol = 1e-10;
    }
    let scan = speed_scan(field, |f: &LinearRotorField, _| f.balanced_guess(), speeds, &opts).map_err(|e| match e {
        crate::analysis::AnalysisError::Model(e) => e,
        e => Error::invalid("speeds", e.to_string()),
    })?;
    let n = rotor.dofs();
    let nc = n + rotor.total_balls();
    let mut member_psi = vec![];
    let mut family_dimension = 0;
    let points = scan
        .points
        .iter()
        .map(|p| {
            let fam = p.state.as_ref().map_or(0, |s| s.family_dimension);
            family_dimension = family_dimension.max(fam);
            let psi = p.state.as_ref().map_or(vec![], |s| s.x[n..nc].to_vec());
            let amplitude = p.state.as_ref().map(|s| {
                if member_psi.is_empty() {
                    member_psi = s.x[n..nc].to_vec();
                }
                super::runup::plane_positions(rotor, &s.x).first().map_or(0.0, |c| c.0.hypot(c.1))
            });
            SpeedPoint {
                omega: p.omega,
                verdict: p.stability.as_ref().map(|s| s.verdict),
                abscissa: p.stability.as_ref().map(|s| s.abscissa),
                threshold: p.stability.as_ref().map(|s| s.threshold),
                family_dimension: fam,
                amplitude,
                // the linear rotor's state comes from its balanced guess only (no partially
                // balanced branch yet); families are not sampled: one member, named by its angles
                state: p.state.as_ref().map(|_| crate::rotor_stability::StateKind::Balanced),
                member_psi: psi,
                family: None,
                family_verdict: None,
                failure: p.failure.as_ref().map(|f| {
                    if f.starts_with("no starting point") {
                        "no balanced state: one balancer plane with at least 2 balls whose capacity n m_b R covers the unbalance is needed (LinearRotorField::balanced_guess)".to_string()
                    } else {
                        f.clone()
                    }
                }),
            }
        })
        .collect();
    Ok(RotorStability { model: "linear", kind, stable_ranges: scan.stable_ranges, points, family_dimension, member_psi, family: None })
}
