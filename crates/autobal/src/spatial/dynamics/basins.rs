//! Basins of attraction: where runs end over a grid of initial conditions (the balls' initial
//! angles and/or the initial speed), computed in parallel, cancellable.

use super::rotor::SpatialRotor;
use super::simulate::{simulate_summary, Initial, Settings, Summary};
use crate::control::{Control, Outcome, StopReason};
use crate::drive::Drive;
use crate::error::Result;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

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

/// Run every case in parallel (rayon's pool) under `control`: its progress observer hears
/// `(runs done, runs in all)` after each run (from the worker threads); when it stops (its
/// cancel flag, its budget), the runs not yet started are skipped and those running stop: their
/// entries are `None`, and the outcome's `stopped` says why. Inputs are validated before any
/// run starts.
///
/// ```
/// use autobal::control::{Control, StopReason};
/// use autobal::drive::Drive;
/// use autobal::spatial::dynamics::basins::{angle_grid, basins};
/// use autobal::spatial::dynamics::{Initial, Settings, SpatialRotor};
/// // paper 000's base case at Ω = 1.6, 2 × 2 initial angles, a short run each
/// let rotor = SpatialRotor::default();
/// let cases = angle_grid(&Initial::at_rest(&rotor), &Drive::Speed { omega0: 1.6 }, 2, 2);
/// let settings = Settings { t_end: 20.0, ..Settings::default() };
/// let ends = basins(&rotor, &cases, &settings, &Control::none()).unwrap();
/// assert!(ends.is_complete());
/// assert!(ends.value.iter().all(|e| e.as_ref().is_some_and(|s| s.status.is_completed())));
/// // cancelled: no run is reported as if it had ended
/// let control = Control::new();
/// control.cancel();
/// let ends = basins(&rotor, &cases, &settings, &control).unwrap();
/// assert_eq!(ends.stopped, Some(StopReason::Interrupted));
/// assert!(ends.value.iter().all(Option::is_none));
/// ```
pub fn basins(rotor: &SpatialRotor, cases: &[Case], settings: &Settings, control: &Control) -> Result<Outcome<Vec<Option<Summary>>>> {
    rotor.validate()?;
    settings.validate()?;
    for c in cases {
        c.drive.validate()?;
        let eq = super::Equations::new(rotor, &c.drive);
        super::simulate::initial_state(&eq, &c.initial)?;
    }
    let done = AtomicUsize::new(0);
    let total = cases.len() as u64;
    let runs: Vec<Option<Summary>> = cases
        .par_iter()
        .map(|c| {
            if control.should_stop().is_some() {
                return Ok(None);
            }
            // summaries only, from the same steps as `simulate` (dt is the automatic method's time resolution)
            let s = simulate_summary(rotor, &c.drive, &c.initial, settings, control)?;
            control.report(done.fetch_add(1, Ordering::Relaxed) as u64 + 1, total);
            // a run the control stopped is no run that ended
            let by_control = matches!(s.status.stop_reason(), Some(StopReason::Interrupted | StopReason::Budget { .. }));
            Ok((!by_control).then_some(s))
        })
        .collect::<Result<_>>()?;
    let skipped = runs.iter().any(Option::is_none);
    Ok(match control.should_stop() {
        Some(why) if skipped => Outcome::stopped(runs, why),
        _ => Outcome::complete(runs),
    })
}
