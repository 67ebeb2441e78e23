//! Basins of attraction: where runs end over a grid of initial conditions (the balls' initial
//! angles and/or the initial speed), computed in parallel, cancellable.

use super::rotor::SpatialRotor;
use super::simulate::{simulate_summary, Initial, Settings, Summary};
use crate::drive::Drive;
use crate::error::Result;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// One run of a basin map: its drive and initial conditions.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The drive (e.g. a constant speed, or an acceleration from an initial speed).
    pub drive: Drive,
    /// Initial conditions.
    pub initial: Initial,
}

/// The cases of a map over the first two balls' initial angles `ψ1 × ψ2 ∈ [0, 2π)²`
/// (`n1 × n2` points, row-major with `ψ2` outer), the other balls and the rotor as in `base`.
pub fn angle_grid(base: &Initial, drive: &Drive, n1: usize, n2: usize) -> Vec<Case> {
    let tau = 2.0 * std::f64::consts::PI;
    let mut out = Vec::with_capacity(n1 * n2);
    for j in 0..n2 {
        for i in 0..n1 {
            let mut init = base.clone();
            if !init.psi.is_empty() {
                init.psi[0] = tau * i as f64 / n1 as f64;
            }
            if init.psi.len() > 1 {
                init.psi[1] = tau * j as f64 / n2 as f64;
            }
            out.push(Case { drive: drive.clone(), initial: init });
        }
    }
    out
}

/// Check a map over the first two balls' initial angles of `n × n` points before it runs: the
/// rotor needs at least two balls, and `2 ≤ n ≤ 1000` (a million runs); `n_field` names `n` in
/// the error as the front end spells it (`--n`, `n`).
pub fn check_angle_grid(rotor: &SpatialRotor, n: usize, n_field: &str) -> Result<()> {
    if rotor.balls() < 2 {
        return Err(crate::Error::invalid("balancer.balls", "basins need at least two balls (the map is over the first two balls' initial angles)"));
    }
    if !(2..=1000).contains(&n) {
        return Err(crate::Error::invalid(n_field, format!("must lie between 2 and 1000, got {n}")));
    }
    Ok(())
}

/// Run every case in parallel (rayon's pool). `progress(done)` is called after each run (from
/// the worker threads); when `cancel` is set, the runs not yet started are skipped and the one
/// running stops: their entries are `None`. Inputs are validated before any run starts.
///
/// ```
/// use autobal::drive::Drive;
/// use autobal::spatial::dynamics::basins::{angle_grid, basins};
/// use autobal::spatial::dynamics::{Initial, Settings, SpatialRotor};
/// use std::sync::atomic::{AtomicBool, Ordering};
/// // paper 000's base case at Ω = 1.6, 2 × 2 initial angles, a short run each
/// let rotor = SpatialRotor::default();
/// let cases = angle_grid(&Initial::at_rest(&rotor), &Drive::Speed { omega0: 1.6 }, 2, 2);
/// let settings = Settings { t_end: 20.0, ..Settings::default() };
/// let cancel = AtomicBool::new(false);
/// let ends = basins(&rotor, &cases, &settings, |_| {}, &cancel).unwrap();
/// assert!(ends.iter().all(|e| e.as_ref().is_some_and(|s| s.status.is_completed())));
/// // cancelled: no run is reported as if it had ended
/// cancel.store(true, Ordering::Relaxed);
/// assert!(basins(&rotor, &cases, &settings, |_| {}, &cancel).unwrap().iter().all(Option::is_none));
/// ```
pub fn basins(rotor: &SpatialRotor, cases: &[Case], settings: &Settings, progress: impl Fn(usize) + Sync, cancel: &AtomicBool) -> Result<Vec<Option<Summary>>> {
    rotor.validate()?;
    settings.validate()?;
    for c in cases {
        c.drive.validate()?;
        let eq = super::Equations::new(rotor, &c.drive);
        super::simulate::initial_state(&eq, &c.initial)?;
    }
    let done = AtomicUsize::new(0);
    cases
        .par_iter()
        .map(|c| {
            if cancel.load(Ordering::Relaxed) {
                return Ok(None);
            }
            // summaries only, from the same steps as `simulate` (dt is the automatic method's time resolution)
            let s = simulate_summary(rotor, &c.drive, &c.initial, settings, Some(&|| cancel.load(Ordering::Relaxed)))?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok((s.stopped.is_none() || !cancel.load(Ordering::Relaxed)).then_some(s))
        })
        .collect()
}
