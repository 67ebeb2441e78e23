//! Integrators of ordinary differential equations shared by both dynamic models: an explicit
//! DOP853 ([`dop853`]) and a linearly implicit RODAS ([`rosenbrock`]) for stiff runs, over one
//! set of types (state, tolerances, counters, stop reasons).

pub mod dop853;
#[allow(missing_docs)]
pub mod dop853_tableau;
pub mod rosenbrock;

/// Largest state dimension.
pub const CAP: usize = 24;

/// A state vector (the first `dim` components are used).
pub type State = [f64; CAP];

/// Right-hand side `y' = f(t, y)` of a system of `dim` equations.
pub trait System {
    /// Number of equations (at most [`CAP`]).
    fn dim(&self) -> usize;
    /// Write `f(t, y)` into `dy`; both slices have length [`System::dim`].
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
}

/// Tolerances and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance, per component (first `dim` used).
    pub atol: State,
    /// Largest step (`f64::INFINITY` for none).
    pub h_max: f64,
    /// Give up after this many steps.
    pub max_steps: u64,
}

/// Work counters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Evaluations of the right-hand side.
    pub rhs_evaluations: u64,
}

/// Why the integration stopped early.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stop {
    /// The step size underflowed at time `t`.
    StepTooSmall { t: f64 },
    /// More than `max_steps` steps.
    TooManySteps { t: f64 },
    /// The state became non-finite at time `t`.
    NotFinite { t: f64 },
    /// The observer asked to stop at time `t`.
    Requested { t: f64 },
}

