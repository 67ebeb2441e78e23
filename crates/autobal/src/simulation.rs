//! Time simulation of a dynamic model, the machinery every model shares on top of the
//! integrators ([`crate::ode`]): the run is integrated piecewise between the drive's breakpoints
//! (no step straddles a jump of the torque or the acceleration), samples are taken at a fixed
//! interval from the dense output (the steps do not stop at the samples), hooks see every step
//! (peak tracking) and every sample (output, progress), and the run ends early only with an
//! explicit [`Status`] (interrupted, budget spent, non-finite state…), never as a silent success.
//!
//! A model supplies its [`System`] and [`Hooks`]; see `planar::simulate` for a complete use:
//!
//! ```
//! use autobal::ode::{Control, Options, Solver, System};
//! use autobal::simulation::{run, Hooks, Peak, Timeline};
//!
//! struct Decay;
//! impl System for Decay {
//!     fn dim(&self) -> usize { 1 }
//!     fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) { dy[0] = -y[0]; }
//! }
//! struct Record { samples: Vec<(f64, f64)>, peak: Peak<()> }
//! impl Hooks for Record {
//!     fn step(&mut self, t: f64, y: &[f64]) { self.peak.observe(y[0], t, ()); }
//!     fn sample(&mut self, t: f64, y: &[f64]) -> Control {
//!         self.samples.push((t, y[0]));
//!         Control::Continue
//!     }
//! }
//! let mut solver = Solver::new(&Decay, Options::new(1e-10, 1e-12)).unwrap();
//! let mut y = [1.0];
//! let mut rec = Record { samples: vec![], peak: Peak::new(()) };
//! let out = run(&mut solver, &mut y, &Timeline { t_end: 2.0, dt: 0.5, breakpoints: &[1.2] }, &mut rec);
//! assert!(out.status.is_completed());
//! assert_eq!(rec.samples.len(), 5); // t = 0, 0.5, 1, 1.5, 2
//! assert!((rec.samples[3].1 - (-1.5f64).exp()).abs() < 1e-9);
//! ```

pub mod window;

pub use window::{Recorder, RevolutionWindow};

use crate::error::{Error, Result};
use crate::ode::{Control, Outcome, Solver, Stats, Status, StopReason, System};

/// When to sample and where to break the integration.
#[derive(Debug, Clone, Copy)]
pub struct Timeline<'a> {
    /// End of the run (the run starts at 0).
    pub t_end: f64,
    /// Output interval: samples at `k dt`, `k = 0, 1, …` up to `t_end`, and at `t_end`.
    pub dt: f64,
    /// Times where the equations change abruptly (outside `(0, t_end)` ignored).
    pub breakpoints: &'a [f64],
}

/// What a model does during a run.
pub trait Hooks {
    /// At the start of every piece (at 0 and at each breakpoint), with the state there; e.g.
    /// put a prescribed speed back exactly on its schedule.
    fn start_piece(&mut self, _t: f64, _y: &mut [f64]) {}
    /// After every accepted step, with the state at its end (e.g. peak tracking between samples).
    fn step(&mut self, _t: f64, _y: &[f64]) {}
    /// After every accepted step, before [`Hooks::step`]: the step from `t_old` (state `y_old`)
    /// to `t_new` (state `y_new`) and its dense output, `interpolate(t, out)` for `t` in
    /// `[t_old, t_new]` (DOP853's costs 3 right-hand sides on its first use in a step, counted in
    /// the run's statistics: call it only where needed).
    fn dense_step(&mut self, _t_old: f64, _t_new: f64, _y_old: &[f64], _y_new: &[f64], _interpolate: &mut dyn FnMut(f64, &mut [f64])) {}
    /// A sample at `t = k dt` (interpolated from the dense output); [`Control::Stop`] ends the
    /// run ([`Status::Stopped`] with [`StopReason::Observer`]).
    fn sample(&mut self, t: f64, y: &[f64]) -> Control;
    /// A non-terminal event `index` of the solver ([`Solver::add_event`]) located at `t`, with
    /// the state there (e.g. a maximum of the whirl radius between step ends).
    fn event(&mut self, _index: usize, _t: f64, _y: &[f64]) {}
}

/// The largest value of some quantity seen so far, when, and what went with it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Peak<X> {
    /// The largest value (−∞ before the first observation).
    pub value: f64,
    /// When it occurred.
    pub t: f64,
    /// What went with it (e.g. the speed).
    pub with: X,
}

impl<X: Copy> Peak<X> {
    /// Nothing seen yet.
    pub fn new(with: X) -> Self {
        Peak { value: f64::NEG_INFINITY, t: f64::NAN, with }
    }
    /// Keep `(value, t, with)` if `value` is the largest so far.
    pub fn observe(&mut self, value: f64, t: f64, with: X) {
        if value > self.value {
            *self = Peak { value, t, with };
        }
    }
}

/// Integrate `y` (the state at 0) to `timeline.t_end` in pieces between the breakpoints,
/// sampling at `k dt` (the first sample is the initial state, the last the state at `t_end`,
/// also where `t_end` is no multiple of `dt`). A terminal event of the solver
/// ends the run with [`Status::Event`] (the caller may change the equations and call again). The outcome's `t` is the time
/// reached and `stats` the work of the whole run; `y` holds the state at that time.
pub fn run<S: System>(solver: &mut Solver<'_, S>, y: &mut [f64], timeline: &Timeline, hooks: &mut impl Hooks) -> Outcome {
    let t_end = timeline.t_end;
    let dt = timeline.dt;
    let mut ends: Vec<f64> = timeline.breakpoints.iter().copied().filter(|b| *b > 0.0 && *b < t_end).collect();
    ends.push(t_end);
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    let mut buf = vec![0.0; y.len()];
    let mut stats = Stats::default();
    let mut t = 0.0;
    let mut k: u64 = 0; // next sample index
    let slack = 1e-12 * t_end.abs().max(dt);
    hooks.start_piece(0.0, y);
    if hooks.sample(0.0, y) == Control::Stop {
        return Outcome { status: Status::Stopped(StopReason::Observer), t, stats };
    }
    k += 1;
    for end in ends {
        if t > 0.0 {
            hooks.start_piece(t, y);
        }
        let out = solver.integrate(t, y, end, |step| {
            for k in 0..step.events.len() {
                let (i, te) = step.events[k];
                step.interpolate(te, &mut buf);
                hooks.event(i, te, &buf);
            }
            let (t_old, t_new, y_old, y_new) = (step.t_old, step.t_new, step.y_old, step.y_new);
            hooks.dense_step(t_old, t_new, y_old, y_new, &mut |t, out| step.interpolate(t, out));
            hooks.step(step.t_new, step.y_new);
            loop {
                let ts = k as f64 * dt;
                if ts > step.t_new + slack || ts > t_end + slack {
                    return Control::Continue;
                }
                if (ts - step.t_new).abs() <= slack {
                    buf.copy_from_slice(step.y_new);
                } else {
                    step.interpolate(ts.max(step.t_old), &mut buf);
                }
                k += 1;
                if hooks.sample(ts, &buf) == Control::Stop {
                    return Control::Stop;
                }
            }
        });
        stats.add(&out.stats);
        t = out.t;
        if !out.status.is_completed() {
            return Outcome { status: out.status, t, stats };
        }
    }
    // the last sample is the end of the run, also where t_end is no multiple of dt
    if (k - 1) as f64 * dt < t_end - slack && hooks.sample(t_end, y) == Control::Stop {
        return Outcome { status: Status::Stopped(StopReason::Observer), t, stats };
    }
    Outcome { status: Status::Completed, t, stats }
}

/// How a run ended, as the library's result: `Ok` when it reached `t_end` (or a terminal
/// event), else the early stop as a typed error at the time `t` it was reached:
/// [`Error::Interrupted`] (the control's cancel flag or wall-time budget, an observer that
/// stopped it), [`Error::TooManySteps`] (the step budget), [`Error::StepTooSmall`],
/// [`Error::NonFinite`].
/// The models' summaries offer it as `into_result`, so that a caller who wants no partial
/// result writes `simulate(..)?.into_result()?`.
pub fn status_result(status: &Status, t: f64) -> Result<()> {
    match status {
        Status::Completed | Status::Event(_) => Ok(()),
        Status::Stopped(why) => Err(why.into_error(t)),
        Status::StepTooSmall { .. } => Err(Error::StepTooSmall { t }),
        Status::NotFinite { name, .. } => Err(Error::NonFinite { what: name.clone(), t: Some(t) }),
    }
}
