//! Where rolling resistance leaves the balls: the end state of the planar rotor held at a
//! constant speed with rolling-resistant balls, and the residual unbalance it keeps
//! ([`residual`]); the data of the report's friction figure and of docs/notes/balls.md.
//!
//! The balls start spread evenly, at rest relative to the disk, with the shaft point C already in
//! the steady whirl of that configuration (no shaft transient), and move towards the balanced
//! state until every ball can rest: `|P| |sin(ψ_j − arg P)| ≤ μ_r (r + P·e^{iψ_j})`
//! ([`crate::balls::can_rest`]), `P = u + s2 e^{iγ}` the race centre E. What is left is E's
//! eccentricity `|P|` and the residual unbalance `|P/H(ω)|` (`H = ω²/(k − m0 ω² + i c ω)`, the
//! unbalance that would move E by `P`), of the order `μ_r r` and `μ_r r/|H|`.
//!
//! ```
//! use autobal::planar::{friction::residual, PlanarRotor};
//! // paper 004's rotor at twice its critical speed, μ_r = 1e-3: E stays off the axis by ~μ_r r
//! let rotor = PlanarRotor::paper_004(0.03);
//! let r = residual(&rotor, 2.0 * rotor.natural_frequency(), 1e-3, 40.0).unwrap();
//! assert!(r.completed && r.settled && r.at_rest);
//! assert!(r.eccentricity > 0.2e-3 * rotor.r && r.eccentricity < 3e-3 * rotor.r);
//! ```

use super::stationary::{locked_whirl, receptance};
use super::{simulate, Drive, PlanarRotor, Settings};
use crate::error::Result;
use serde::Serialize;

/// The end state of [`residual`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Residual {
    /// Speed (rad/s).
    pub omega: f64,
    /// Rolling-resistance coefficient `μ_r`.
    pub rolling_resistance: f64,
    /// Eccentricity `|P|` of the race centre E at the end (m); 0 in the semi-balanced state.
    pub eccentricity: f64,
    /// Residual unbalance `|P/H(ω)|` (kg·m): what the balls leave uncancelled.
    pub unbalance: f64,
    /// Whether every ball satisfies the static resting condition at the end (closed form, on the
    /// steady whirl of the end configuration).
    pub at_rest: bool,
    /// Stick-slip transitions counted over the run.
    pub stick_slip_transitions: u64,
    /// Whether the run settled (see [`super::Summary::settled`]).
    pub settled: bool,
    /// Whether the run reached its end (not interrupted, no budget spent).
    pub completed: bool,
}

/// Hold `rotor` at speed `omega` for `t_end` seconds with rolling resistance `mu` (replacing
/// the rotor's own), from balls spread evenly, and report where they stop.
pub fn residual(rotor: &PlanarRotor, omega: f64, mu: f64, t_end: f64) -> Result<Residual> {
    let mut p = rotor.clone();
    p.balls.rolling_resistance = mu;
    let mut settings = Settings { dt: t_end / 20.0, ..Settings::new(&p, t_end) };
    let u = locked_whirl(&p, omega, &settings.psi0);
    let v = num_complex::Complex64::new(0.0, omega) * u;
    settings.xy0 = [u.re, u.im];
    settings.xy_rate0 = [v.re, v.im];
    let mut last = None;
    let s = simulate(&p, &Drive::Speed { omega0: omega }, &settings, |x| {
        last = Some(x.psi.clone());
        true
    })?;
    let psi = last.unwrap_or_default();
    let e = num_complex::Complex64::from_polar(p.s2, p.gamma);
    let pp = locked_whirl(&p, omega, &psi) + e;
    let at_rest = psi.iter().all(|a| crate::balls::can_rest(mu, p.r, (pp.re, pp.im), *a) >= -1e-3 * mu * p.r);
    Ok(Residual {
        omega,
        rolling_resistance: mu,
        eccentricity: pp.norm(),
        unbalance: pp.norm() / receptance(&p, omega).norm(),
        at_rest,
        stick_slip_transitions: s.stick_slip_transitions,
        settled: s.settled,
        completed: s.status.is_completed(),
    })
}
