//! One way to run long work: every computation that can run long (a simulation, a sweep, a
//! stability map, a boundary trace, basins, a speed scan) takes a [`Control`] and, when it ends
//! early, says why with one [`StopReason`], keeping what it computed so far.
//!
//! # Design
//! As in argmin's executor (a solver is run under one set of termination checks and observers,
//! and its result carries the termination status next to the best state found), the caller
//! decides *when to stop* and the computation decides *where it can stop*:
//! - [`Control`] holds a cancel flag shared across threads (a Ctrl-C handler, Python's
//!   `KeyboardInterrupt`, another thread, a worker that failed), an optional wall-time budget
//!   whose clock starts when the budget is set, and an optional progress observer. One control is
//!   made per front-end invocation and handed by reference to every long computation of it, so
//!   one Ctrl-C stops all of them; [`Control::none`] (the default) never stops anything.
//! - A computation asks [`Control::should_stop`] at its natural boundaries (before each sample,
//!   point, row, line, or every few hundred integrator steps). Asking for the flag alone
//!   ([`Control::is_cancelled`]) is one relaxed atomic load, cheap enough for every integrator
//!   step; asking for the budget reads the clock, so the integrator does it every
//!   [`BUDGET_CHECK_EVERY`] steps and loops with costly items do it per item.
//! - An early stop is never a silent success: its reason is a [`StopReason`] (interrupted,
//!   budget spent, step budget spent, a sink that asked to stop) and the result carries it next
//!   to what was computed, as an [`Outcome`] or as the `stopped`/`status` of the computation's
//!   own result type. Failures that are not a decision to stop (a non-finite state, a step size
//!   that underflows, bad input) remain errors ([`crate::Error`]).
//!
//! Not to be confused with [`crate::ode::Control`], an ODE observer's verdict after one step.
//!
//! ```
//! use autobal::control::{Control, Outcome, StopReason};
//! use std::time::Duration;
//!
//! /// A long loop: sums `0..n`, asking the control before each term.
//! fn long_sum(n: u64, control: &Control) -> Outcome<u64> {
//!     let mut sum = 0;
//!     for i in 0..n {
//!         if let Some(why) = control.should_stop() {
//!             return Outcome::stopped(sum, why); // what was computed so far, and why it stopped
//!         }
//!         sum += i;
//!         control.report(i + 1, n);
//!     }
//!     Outcome::complete(sum)
//! }
//!
//! assert_eq!(long_sum(10, &Control::none()), Outcome::complete(45));
//!
//! // cancelled from another thread (here before the start): nothing summed, and it says so
//! let c = Control::new();
//! c.cancel();
//! let out = long_sum(10, &c);
//! assert_eq!((out.value, out.stopped), (0, Some(StopReason::Interrupted)));
//! assert!(out.into_result().is_err());
//!
//! // a budget of zero seconds is spent before the first term
//! let out = long_sum(10, &Control::new().with_budget(Duration::ZERO));
//! assert!(matches!(out.stopped, Some(StopReason::Budget { .. })));
//! ```

use crate::error::{Error, Result};
use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The ODE solver checks the wall-time budget once every this many steps (the cancel flag it
/// checks at every step).
pub const BUDGET_CHECK_EVERY: u64 = 256;

/// Why a computation ended before it was complete. Each is a decision to stop (by the user, a
/// budget, a sink), not a failure: the result keeps what was computed until then.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum StopReason {
    /// The control's cancel flag was set (Ctrl-C, `KeyboardInterrupt`, another thread).
    Interrupted,
    /// The wall-time budget was spent.
    Budget {
        /// The budget (s).
        seconds: f64,
    },
    /// The integrator's step budget (`integration.max_steps`) was spent.
    TooManySteps {
        /// The budget.
        max_steps: u64,
    },
    /// A sink or observer of the computation (a callback receiving its samples or rows) asked
    /// to stop.
    Observer,
}

impl fmt::Display for StopReason {
    /// "interrupted", "time budget of 2 s spent", "step budget of 1000 steps spent", "stopped by
    /// the receiver of the output".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StopReason::Interrupted => write!(f, "interrupted"),
            StopReason::Budget { seconds } => write!(f, "time budget of {seconds} s spent"),
            StopReason::TooManySteps { max_steps } => write!(f, "step budget of {max_steps} steps spent"),
            StopReason::Observer => write!(f, "stopped by the receiver of the output"),
        }
    }
}

impl StopReason {
    /// The library's error for this stop at time `t` (simulated time, or `NaN` where there is
    /// none): [`Error::TooManySteps`] for a step budget, else [`Error::Interrupted`].
    pub fn into_error(self, t: f64) -> Error {
        match self {
            StopReason::TooManySteps { .. } => Error::TooManySteps { t },
            _ => Error::Interrupted { t },
        }
    }
}

/// Progress of a computation, handed to the observer of [`Control::with_progress`]: `done` of
/// `total` items (points, rows, runs; the computation's docs say which).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Items finished.
    pub done: u64,
    /// Items in all.
    pub total: u64,
}

type Observer = Arc<dyn Fn(Progress) + Send + Sync>;

thread_local! {
    /// This thread's stop probe ([`with_probe`]).
    static PROBE: std::cell::RefCell<Option<Control>> = const { std::cell::RefCell::new(None) };
}

/// Run `f` with `control` as this thread's *stop probe*: the inner loops that take no control
/// of their own (the analyses' integrations over one period, [`crate::ode::lean`]) ask it
/// every few hundred steps ([`probe`]) and end early when it says stop, so that Ctrl-C, a
/// signal or a budget stops one speed's shooting or monodromy within milliseconds instead of
/// after that speed (minutes on a stiff rotor: hunts 27 and 28). The caller, which asks
/// `control` itself, then drops what the stopped loop left unfinished. The previous probe is
/// restored afterwards (also on a panic). Worker threads have their own: a parallel loop
/// installs it in each task.
pub fn with_probe<T>(control: &Control, f: impl FnOnce() -> T) -> T {
    struct Restore(Option<Control>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let prev = self.0.take();
            PROBE.with(|p| *p.borrow_mut() = prev);
        }
    }
    let _restore = Restore(PROBE.with(|p| p.replace(Some(control.clone()))));
    f()
}

/// Why this thread's stop probe ([`with_probe`]) says stop; `None` without a probe or while it
/// goes on.
pub fn probe() -> Option<StopReason> {
    PROBE.with(|p| p.borrow().as_ref().and_then(Control::should_stop))
}

/// What every long computation is run under: a cancel flag shared across threads, an optional
/// wall-time budget, an optional progress observer (see the [module docs](self)). Cloning shares
/// the flag, the budget's clock and the observer.
#[derive(Clone, Default)]
pub struct Control {
    flag: Arc<AtomicBool>,
    budget: Option<(Instant, Duration)>,
    observer: Option<Observer>,
}

impl fmt::Debug for Control {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Control")
            .field("cancelled", &self.is_cancelled())
            .field("budget", &self.budget.map(|(_, d)| d))
            .field("observer", &self.observer.is_some())
            .finish()
    }
}

impl Control {
    /// A control that stops nothing until [`Control::cancel`] is called: a fresh flag, no
    /// budget, no observer.
    pub fn new() -> Self {
        Control::default()
    }

    /// A control that is never cancelled by anyone else (no budget, no observer): for callers
    /// that run a computation to its end.
    pub fn none() -> Self {
        Control::default()
    }

    /// A control whose cancel flag is `flag` (shared, e.g. with a Ctrl-C handler that sets it).
    pub fn with_flag(flag: Arc<AtomicBool>) -> Self {
        Control { flag, ..Control::default() }
    }

    /// The same control with a wall-time budget of `budget`, counted from now.
    pub fn with_budget(mut self, budget: Duration) -> Self {
        self.budget = Some((Instant::now(), budget));
        self
    }

    /// The same control with a progress observer (called from worker threads, so `Sync`).
    pub fn with_progress(mut self, observer: impl Fn(Progress) + Send + Sync + 'static) -> Self {
        self.observer = Some(Arc::new(observer));
        self
    }

    /// The cancel flag, to share with a signal handler or another thread.
    pub fn flag(&self) -> &Arc<AtomicBool> {
        &self.flag
    }

    /// Ask every computation under this control (and its clones) to stop.
    pub fn cancel(&self) {
        self.flag.store(true, Ordering::Relaxed);
    }

    /// Whether the cancel flag is set: one relaxed atomic load (cheap enough for every
    /// integrator step).
    pub fn is_cancelled(&self) -> bool {
        self.flag.load(Ordering::Relaxed)
    }

    /// The wall-time budget, if any.
    pub fn budget(&self) -> Option<Duration> {
        self.budget.map(|(_, d)| d)
    }

    /// Whether the wall-time budget is spent (reads the clock; `None` without a budget).
    pub fn budget_spent(&self) -> Option<StopReason> {
        let (start, d) = self.budget?;
        (start.elapsed() >= d).then_some(StopReason::Budget { seconds: d.as_secs_f64() })
    }

    /// Why the computation should stop now, if it should: [`StopReason::Interrupted`] when the
    /// flag is set, else [`StopReason::Budget`] when the budget is spent (reads the clock when
    /// there is a budget: ask it per item, not per integrator step).
    pub fn should_stop(&self) -> Option<StopReason> {
        if self.is_cancelled() {
            return Some(StopReason::Interrupted);
        }
        self.budget_spent()
    }

    /// The same control (its flag, budget and observer) for a later phase of one run, whose
    /// reports are counted on after the `before` items of the phases before it: `done` of
    /// `total` reaches the observer as `before + done` of `before + total`, so that one progress
    /// bar counts the whole run (`stability`'s verdict at the operating speed after its scan
    /// restarted the count at 1 of 1).
    ///
    /// ```
    /// use autobal::control::Control;
    /// use std::sync::{Arc, Mutex};
    /// let seen = Arc::new(Mutex::new(vec![]));
    /// let s = seen.clone();
    /// let control = Control::new().with_progress(move |p| s.lock().unwrap().push((p.done, p.total)));
    /// control.counted_after(24).report(1, 2);
    /// assert_eq!(*seen.lock().unwrap(), [(25, 26)]);
    /// ```
    pub fn counted_after(&self, before: u64) -> Control {
        let mut c = self.clone();
        if let Some(o) = self.observer.clone() {
            c.observer = Some(Arc::new(move |p: Progress| o(Progress { done: before + p.done, total: before + p.total })));
        }
        c
    }

    /// Tell the progress observer (if any) that `done` of `total` items are finished.
    pub fn report(&self, done: u64, total: u64) {
        if let Some(o) = &self.observer {
            o(Progress { done, total });
        }
    }
}

/// What a long computation computed, and why it stopped early if it did (`None`: complete).
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome<T> {
    /// The result: the whole result when complete, else what was computed until the stop.
    pub value: T,
    /// Why it stopped before completing (`None`: it completed).
    pub stopped: Option<StopReason>,
}

impl<T> Outcome<T> {
    /// A complete result.
    pub fn complete(value: T) -> Self {
        Outcome { value, stopped: None }
    }

    /// A partial result and why it stopped.
    pub fn stopped(value: T, why: StopReason) -> Self {
        Outcome { value, stopped: Some(why) }
    }

    /// Whether the computation completed.
    pub fn is_complete(&self) -> bool {
        self.stopped.is_none()
    }

    /// The value if complete, else the stop as an error ([`StopReason::into_error`], no time).
    pub fn into_result(self) -> Result<T> {
        match self.stopped {
            None => Ok(self.value),
            Some(why) => Err(why.into_error(f64::NAN)),
        }
    }

    /// The outcome with its value mapped.
    pub fn map<U>(self, f: impl FnOnce(T) -> U) -> Outcome<U> {
        Outcome { value: f(self.value), stopped: self.stopped }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fresh_control_does_not_stop_and_a_clone_shares_the_flag() {
        let c = Control::new();
        assert_eq!(c.should_stop(), None);
        let d = c.clone();
        d.cancel();
        assert_eq!(c.should_stop(), Some(StopReason::Interrupted));
        // an unspent budget does not stop; the flag wins over a spent budget
        let long = Control::new().with_budget(Duration::from_secs(3600));
        assert_eq!(long.should_stop(), None);
        let both = Control::with_flag(c.flag().clone()).with_budget(Duration::ZERO);
        assert_eq!(both.should_stop(), Some(StopReason::Interrupted));
        assert_eq!(Control::none().with_budget(Duration::ZERO).should_stop(), Some(StopReason::Budget { seconds: 0.0 }));
    }

    #[test]
    fn progress_reaches_the_observer() {
        let seen = Arc::new(std::sync::Mutex::new(vec![]));
        let s = seen.clone();
        let c = Control::new().with_progress(move |p| s.lock().unwrap().push(p));
        c.report(1, 3);
        c.report(3, 3);
        assert_eq!(*seen.lock().unwrap(), vec![Progress { done: 1, total: 3 }, Progress { done: 3, total: 3 }]);
        Control::none().report(1, 1); // no observer: nothing happens
    }

    #[test]
    fn stop_reasons_become_the_matching_errors() {
        assert!(matches!(StopReason::TooManySteps { max_steps: 5 }.into_error(1.0), Error::TooManySteps { t } if t == 1.0));
        assert!(matches!(StopReason::Budget { seconds: 1.0 }.into_error(2.0), Error::Interrupted { t } if t == 2.0));
        assert_eq!(Outcome::complete(3).map(|x| x * 2), Outcome::complete(6));
        assert!(Outcome::stopped(1, StopReason::Observer).into_result().is_err());
    }
}
