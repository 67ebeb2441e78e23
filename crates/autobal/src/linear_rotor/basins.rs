//! Basins of a linear rotor (issue 19 item 4): where runs of `simulate` end over a grid of the
//! first two balls' initial angles `ψ1 × ψ2 ∈ [0, 2π)²` (the other balls evenly spread as
//! [`super::runup::initial_state`] places them, the structure at rest), in parallel — the
//! linear rotor's counterpart of [`crate::spatial::dynamics::basins`].
//!
//! Each end ([`BasinEnd`]) has the balls' final angles relative to the rotor, the first balancer
//! plane's final whirl radius, the static residual unbalance of the rotor with its balls
//! ([`residual_unbalance`]), and the verdict `balanced`: the run's own outcome
//! ([`RunSummary::outcome`] balanced: settled, and no plane's race whirling at more than
//! [`BALANCE_TOLERANCE`](crate::spatial::dynamics::simulate::BALANCE_TOLERANCE) of its whirl
//! with the balls spread evenly, `simulate`'s and `stability`'s rule on the linear route). One
//! rule: a start is balanced in the basins where `simulate` from it says balanced (before
//! 2026-11-30 the basins had their own, the plane's final radius within 5 % of the eccentricity
//! scale `Σ|m e| / m_t` with the balls at rest over the last output interval, which called
//! balanced ends the run called not settled, and the balanced ends of a rotor with its
//! unbalance away from the balancer plane, whose race whirl is not the eccentricity's, not
//! balanced).
//!
//! ```
//! use autobal::control::Control;
//! use autobal::drive::Drive;
//! use autobal::linear_rotor::basins::{angle_grid, basins};
//! use autobal::linear_rotor::runup::RunSettings;
//! use autobal::linear_rotor::spec::LinearRun;
//! use autobal::linear_rotor::LinearRotor;
//! use autobal::planar::PlanarRotor;
//! let rotor = LinearRotor::from_planar(&PlanarRotor { s2: 0.0, ..PlanarRotor::paper() }).unwrap();
//! let settings = RunSettings { t_end: 0.2, dt: 0.01, rtol: 1e-8, atol: 1e-9, method: autobal::ode::Method::Auto, max_steps: 1_000_000, max_wall_s: None, physical_nodes: None };
//! let run = LinearRun { rotor: rotor.clone(), drive: Drive::Speed { omega0: 450.0 }, settings, default_drive: false };
//! let ends = basins(&run, &angle_grid(&rotor, 2, "n").unwrap(), &Control::none()).unwrap();
//! assert!(ends.is_complete() && ends.value.len() == 4);
//! ```

use super::runup::{simulate_from, RunSummary};
use super::spec::LinearRun;
use super::LinearRotor;
use crate::control::{Control, Outcome};
use crate::error::{Error, Result};
use rayon::prelude::*;
use serde::Serialize;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Where one run ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BasinEnd {
    /// The run's summary ([`RunSummary`]).
    pub summary: RunSummary,
    /// The balls' initial angles relative to the rotor (rad).
    pub psi0: Vec<f64>,
    /// Their final angles, in `[0, 2π)`.
    pub psi: Vec<f64>,
    /// The first plane's final whirl radius (m).
    pub final_amplitude: f64,
    /// [`residual_unbalance`] at the end.
    pub residual_unbalance: f64,
    /// The verdict: the run's outcome is balanced (module docs).
    pub balanced: bool,
}

/// The initial ball angles of an `n × n` grid over the first two balls' angles, row-major with
/// `ψ2` outer: `ψ1 = 2π i/n`, `ψ2 = 2π j/n`, the others as [`super::runup::initial_state`]
/// spreads them. Errors: fewer than two balls (naming `linear_rotor.balancer`), `n` outside
/// `2..=1000` (naming `n_field`, the front end's spelling).
pub fn angle_grid(rotor: &LinearRotor, n: usize, n_field: &str) -> Result<Vec<Vec<f64>>> {
    if rotor.total_balls() < 2 {
        return Err(Error::invalid("linear_rotor.balancer", "basins need at least two balls (the map is over the first two balls' initial angles)"));
    }
    if !(2..=1000).contains(&n) {
        return Err(Error::invalid(n_field, format!("must lie between 2 and 1000, got {n}")));
    }
    let nd = rotor.dofs();
    let base: Vec<f64> = super::runup::initial_state(rotor)[nd..nd + rotor.total_balls()].to_vec();
    let tau = std::f64::consts::TAU;
    let mut out = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let mut p = base.clone();
            p[0] = tau * i as f64 / n as f64;
            p[1] = tau * j as f64 / n as f64;
            out.push(p);
        }
    }
    Ok(out)
}

/// The static residual unbalance of the rotor with its balls at angles `psi` (relative to the
/// rotor): `|Σ_u m e_u e^{i phase_u} + Σ_j m_b R e^{iψ_j}| / Σ_u |m e_u|` (0: the balls cancel
/// the unbalances' resultant; NaN without unbalance). Axial positions are not weighed: a couple
/// is not seen.
pub fn residual_unbalance(rotor: &LinearRotor, psi: &[f64]) -> f64 {
    let (mut x, mut y, mut total) = (0.0, 0.0, 0.0);
    for u in &rotor.unbalances {
        x += u.me * u.phase.cos();
        y += u.me * u.phase.sin();
        total += u.me.abs();
    }
    let mut k = 0;
    for b in &rotor.balancers {
        for _ in 0..b.balls {
            let a = psi[k];
            x += b.ball_mass * b.radius * a.cos();
            y += b.ball_mass * b.radius * a.sin();
            k += 1;
        }
    }
    if total > 0.0 {
        x.hypot(y) / total
    } else {
        f64::NAN
    }
}

/// Run `run` from each of `starts` (initial ball angles, e.g. [`angle_grid`]) in parallel under
/// `control` (its progress observer hears `(runs done, runs)`); when it stops, the runs not yet
/// started or cut short are `None` and the outcome says why. Every start is checked first.
pub fn basins(run: &LinearRun, starts: &[Vec<f64>], control: &Control) -> Result<Outcome<Vec<Option<BasinEnd>>>> {
    let balls = run.rotor.total_balls();
    if let Some(p) = starts.iter().find(|p| p.len() != balls || p.iter().any(|v| !v.is_finite())) {
        return Err(Error::invalid("psi0", format!("a start has {} angles (finite, one per ball: {balls})", p.len())));
    }
    let done = AtomicUsize::new(0);
    let total = starts.len() as u64;
    let ends: Vec<Option<BasinEnd>> = starts
        .par_iter()
        .map(|psi0| -> Result<Option<BasinEnd>> {
            if control.should_stop().is_some() {
                return Ok(None);
            }
            let mut last: Option<Vec<f64>> = None;
            let mut radius = f64::NAN;
            let summary = simulate_from(&run.rotor, &run.drive, &run.settings, Some(psi0.as_slice()), control, |s| {
                radius = s.planes.first().map_or(f64::NAN, |c| c.0.hypot(c.1));
                last = Some(s.psi.clone());
                true
            })?;
            control.report(done.fetch_add(1, Ordering::Relaxed) as u64 + 1, total);
            if control.should_stop().is_some() && summary.stopped.is_some() {
                return Ok(None);
            }
            let Some(psi) = last else { return Ok(None) };
            let residual = residual_unbalance(&run.rotor, &psi);
            // the run's own word (one rule with `simulate`)
            let balanced = summary.stopped.is_none() && summary.balanced;
            let wrapped = psi.iter().map(|a| a.rem_euclid(std::f64::consts::TAU)).collect();
            Ok(Some(BasinEnd { summary, psi0: psi0.clone(), psi: wrapped, final_amplitude: radius, residual_unbalance: residual, balanced }))
        })
        .collect::<Result<_>>()?;
    let skipped = ends.iter().any(Option::is_none);
    Ok(match control.should_stop() {
        Some(why) if skipped => Outcome::stopped(ends, why),
        _ => Outcome::complete(ends),
    })
}
