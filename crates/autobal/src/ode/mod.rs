//! Integrators of ordinary differential equations `y' = f(t, y)`, shared by every dynamic
//! model: one step loop over an explicit DOP853 (order 8, Hairer's `dop853.f`) and a linearly
//! implicit RODAS (order 4, L-stable, Hairer and Wanner's `rodas.f`), with automatic stiffness
//! detection and switching between them, dense output, event location, cancellation and budgets.
//!
//! # How to use the ode layer
//! 1. Implement [`System`] for your equations: [`System::dim`] and [`System::rhs`] are all that
//!    is required (any dimension; slices of length `dim`). For stiff runs of large systems,
//!    override [`System::jacobian`] with a structured solver ([`Jacobian`]); the default is a
//!    dense Jacobian by forward differences (cost `O(dim³)` per implicit step).
//! 2. Make a [`Solver`] once per run ([`Solver::new`] allocates every buffer; the step loop then
//!    allocates nothing) with [`Options`]: tolerances, [`Method`] (default [`Method::Auto`]),
//!    limits. Optionally run it under a [`crate::control::Control`] ([`Solver::control`]: its
//!    cancel flag is asked before every step, its wall-time budget every
//!    [`crate::control::BUDGET_CHECK_EVERY`] steps) and [`Solver::add_event`] to locate
//!    `g(t, y) = 0` on the dense output.
//! 3. Call [`Solver::integrate`] from `t0` to `t_end` with the state in a slice that is advanced
//!    in place; the observer sees every accepted [`Step`] and can interpolate inside it
//!    ([`Step::interpolate`]). Call it again to go on (e.g. piecewise between the breakpoints of a
//!    drive; the step size and stiffness state carry over).
//! 4. Read the [`Outcome`]: its [`Status`] says whether the run completed, hit an event, was
//!    stopped early ([`Status::Stopped`] with the library's one [`StopReason`]: interrupted, a
//!    budget spent, the observer) or failed; an early stop is never reported as a completed run.
//!
//! [`crate::simulation`] builds on this the machinery a time simulation needs (samples at a
//! fixed interval, pieces between breakpoints, peak tracking, budgets).
//!
//! ```
//! use autobal::ode::{Control, Options, Solver, Status, System};
//!
//! /// A damped oscillator `x'' + 0.1 x' + x = 0`.
//! struct Oscillator;
//! impl System for Oscillator {
//!     fn dim(&self) -> usize { 2 }
//!     fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
//!         dy[0] = y[1];
//!         dy[1] = -y[0] - 0.1 * y[1];
//!     }
//! }
//!
//! let mut solver = Solver::new(&Oscillator, Options::new(1e-10, 1e-12)).unwrap();
//! let mut y = [1.0, 0.0];
//! let mut x_at_half = [0.0; 2];
//! let out = solver.integrate(0.0, &mut y, 10.0, |step| {
//!     if step.t_old <= 0.5 && 0.5 < step.t_new {
//!         step.interpolate(0.5, &mut x_at_half); // dense output inside the step
//!     }
//!     Control::Continue
//! });
//! assert_eq!(out.status, Status::Completed);
//! // x(t) = e^{-t/20} (cos ωt + sin(ωt)/(20ω)), ω = sqrt(1 - 1/400)
//! let w = (1.0f64 - 1.0 / 400.0).sqrt();
//! let x = |t: f64| (-t / 20.0).exp() * ((w * t).cos() + (w * t).sin() / (20.0 * w));
//! assert!((y[0] - x(10.0)).abs() < 1e-9);
//! assert!((x_at_half[0] - x(0.5)).abs() < 1e-9);
//! ```

// The method kernels take the state, its buffers and the tolerances as separate slices.
#![allow(clippy::too_many_arguments)]

pub mod arrow;
pub mod dop853;
#[allow(missing_docs)]
#[rustfmt::skip] // the tableau is laid out as Hairer prints it
pub mod dop853_tableau;
pub mod dual;
mod events;
pub mod lean;
pub(crate) mod lu;
pub mod rosenbrock;
mod solver;

pub use crate::control::StopReason;
pub use events::{Direction, Event};
pub use solver::{Solver, Step};
use std::fmt;

/// Right-hand side `y' = f(t, y)` of a system of `dim` equations.
pub trait System {
    /// Number of equations (any size).
    fn dim(&self) -> usize;

    /// Write `f(t, y)` into `dy`; both slices have length [`System::dim`].
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);

    /// The linear algebra of the implicit method at this system: `J = ∂f/∂y` and solves with
    /// `α I − J`. Default: a dense Jacobian by forward differences of [`System::rhs`]
    /// ([`DenseJacobian`]). Override with a structured solver where the Jacobian has structure
    /// (e.g. a mass matrix with an arrow pattern: cost linear in the number of bodies), or with
    /// [`DenseJacobian::analytic`] when a closed-form dense Jacobian is at hand.
    fn jacobian(&self) -> Box<dyn Jacobian + '_>
    where
        Self: Sized,
    {
        Box::new(DenseJacobian::differences(self))
    }

    /// Name of component `i` of the state, for messages (e.g. "the state became non-finite in …").
    fn component_name(&self, i: usize) -> String {
        format!("y[{i}]")
    }
}

/// The linear algebra an implicit (Rosenbrock) step needs: the Jacobian `J = ∂f/∂y` at the
/// start of the step, the factorisation of `α I − J` for the step's `α = 1/(γ h)`, and solves.
pub trait Jacobian {
    /// Evaluate `J` at `(t, y)`, where `f0 = f(t, y)`. Returns the number of right-hand sides
    /// used (for the counters).
    fn update(&mut self, t: f64, y: &[f64], f0: &[f64]) -> u64;
    /// Factor `α I − J` (after [`Jacobian::update`]); `false` when singular.
    fn factor(&mut self, alpha: f64) -> bool;
    /// Solve `(α I − J) x = b` in place (after [`Jacobian::factor`]).
    fn solve(&mut self, b: &mut [f64]);
    /// Typical magnitude of each component (from the tolerances: `atol_i / rtol`), a hint for
    /// difference increments. Default: ignored.
    fn set_typical(&mut self, _typical: &[f64]) {}
    /// Write `∂f/∂t` at `(t, y)` into `out` and return `true`, where a closed form is at hand;
    /// default `false`: the integrator takes a central difference (one-sided at the ends of the
    /// interval, so never across a breakpoint).
    fn time_derivative(&mut self, _t: f64, _y: &[f64], _f0: &[f64], _out: &mut [f64]) -> bool {
        false
    }
}

/// `f(t, y, out)`: a right-hand side, Jacobian or time derivative written into `out`.
type Eval<'a> = Box<dyn Fn(f64, &[f64], &mut [f64]) + 'a>;

/// Dense `J` (by differences or a closed form) and a dense LU of `α I − J` (partial pivoting).
pub struct DenseJacobian<'a> {
    n: usize,
    rhs: Eval<'a>,
    analytic: Option<Eval<'a>>,
    dfdt: Option<Eval<'a>>,
    jac: Vec<f64>,
    lu: lu::Lu,
    typical: Vec<f64>,
    ys: Vec<f64>,
    fs: Vec<f64>,
}

impl<'a> DenseJacobian<'a> {
    /// `J` column by column from forward differences of `sys.rhs` (`dim` evaluations).
    pub fn differences<S: System>(sys: &'a S) -> Self {
        let n = sys.dim();
        DenseJacobian {
            n,
            rhs: Box::new(move |t, y, dy| sys.rhs(t, y, dy)),
            analytic: None,
            dfdt: None,
            jac: vec![0.0; n * n],
            lu: lu::Lu::new(n),
            typical: vec![1e-6; n],
            ys: vec![0.0; n],
            fs: vec![0.0; n],
        }
    }

    /// `J` from a closed form: `jac(t, y, J)` writes `∂f_i/∂y_j` into `J[i·dim + j]`.
    pub fn analytic<S: System>(sys: &'a S, jac: impl Fn(f64, &[f64], &mut [f64]) + 'a) -> Self {
        let mut d = Self::differences(sys);
        d.analytic = Some(Box::new(jac));
        d
    }

    /// The same, with `∂f/∂t` in closed form: `dfdt(t, y, out)`.
    pub fn with_time_derivative(mut self, dfdt: impl Fn(f64, &[f64], &mut [f64]) + 'a) -> Self {
        self.dfdt = Some(Box::new(dfdt));
        self
    }
}

impl Jacobian for DenseJacobian<'_> {
    fn update(&mut self, t: f64, y: &[f64], f0: &[f64]) -> u64 {
        let n = self.n;
        if let Some(a) = &self.analytic {
            a(t, y, &mut self.jac);
            return 0;
        }
        self.ys.copy_from_slice(y);
        for j in 0..n {
            let dj = f64::EPSILON.sqrt() * y[j].abs().max(self.typical[j]).max(1e-300);
            let yj = self.ys[j];
            self.ys[j] = yj + dj;
            let dj = self.ys[j] - yj; // the increment actually represented
            (self.rhs)(t, &self.ys, &mut self.fs);
            self.ys[j] = yj;
            for i in 0..n {
                self.jac[i * n + j] = (self.fs[i] - f0[i]) / dj;
            }
        }
        n as u64
    }

    fn factor(&mut self, alpha: f64) -> bool {
        let n = self.n;
        let a = self.lu.matrix_mut();
        for (dst, src) in a.iter_mut().zip(&self.jac) {
            *dst = -src;
        }
        for i in 0..n {
            a[i * n + i] += alpha;
        }
        self.lu.factor()
    }

    fn solve(&mut self, b: &mut [f64]) {
        self.lu.solve(b);
    }

    fn set_typical(&mut self, typical: &[f64]) {
        self.typical.copy_from_slice(typical);
    }

    fn time_derivative(&mut self, t: f64, y: &[f64], _f0: &[f64], out: &mut [f64]) -> bool {
        match &self.dfdt {
            Some(d) => {
                d(t, y, out);
                true
            }
            None => false,
        }
    }
}

/// Which integrator takes the steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Explicit DOP853 (order 8, 7th-order dense output): non-stiff problems.
    Dop853,
    /// Linearly implicit RODAS (order 4, L-stable, 3rd-order dense output): stiff problems.
    Rodas,
    /// DOP853 while the problem is not stiff; switches to RODAS when Hairer's stiffness test
    /// (`h |λ|` at DOP853's stability boundary in 15 accepted steps) fires, and back when the
    /// implicit step falls inside DOP853's stability region (`h ρ(J) ≤ 5.4`, spectral radius by
    /// power iteration). In RODAS phases (of this method and of [`Method::Rodas`]) the implicit
    /// step is capped so that it resolves every mode of `J` that does not decay within the
    /// longest implicit step (`|h λ| ≤ 1` at `rtol = 1e-8`): an L-stable step damps an
    /// unresolved oscillation, and would hold a state whose slow oscillatory instability
    /// (a Hopf bifurcation under a slowly changing speed) should set in.
    #[default]
    Auto,
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Method::Dop853 => "dop853",
            Method::Rodas => "rodas",
            Method::Auto => "auto",
        })
    }
}

/// Tolerances, method and limits.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Which integrator ([`Method::Auto`] by default).
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance: one value for every component, or one per component.
    pub atol: Vec<f64>,
    /// Largest step (`f64::INFINITY` for none).
    pub h_max: f64,
    /// Largest step of the implicit method (its dense output is only third order; a caller
    /// sampling at an interval `dt` may cap it at a few `dt`).
    pub h_max_implicit: f64,
    /// First step; `None`: chosen from the derivatives (Hairer's `HINIT`).
    pub h_initial: Option<f64>,
    /// Take every step of exactly this size, without error control (for convergence studies;
    /// the last step of an interval may be shorter).
    pub fixed_step: Option<f64>,
    /// Give up after this many accepted steps (per call of [`Solver::integrate`]).
    pub max_steps: u64,
    /// Give up after this much wall-clock time (per call), checked every 256 steps.
    pub max_wall: Option<std::time::Duration>,
}

impl Options {
    /// Tolerances `rtol` and one `atol` for every component; [`Method::Auto`], no step limit,
    /// at most 10⁸ steps.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Options {
            method: Method::Auto,
            rtol,
            atol: vec![atol],
            h_max: f64::INFINITY,
            h_max_implicit: f64::INFINITY,
            h_initial: None,
            fixed_step: None,
            max_steps: 100_000_000,
            max_wall: None,
        }
    }

    /// The same, with this method.
    pub fn method(mut self, m: Method) -> Self {
        self.method = m;
        self
    }

    /// The same, with one absolute tolerance per component.
    pub fn atol_per_component(mut self, atol: Vec<f64>) -> Self {
        self.atol = atol;
        self
    }

    /// A builder starting from [`Options::default`].
    pub fn builder() -> OptionsBuilder {
        OptionsBuilder::default()
    }

    /// Check every field that does not depend on the system's dimension (errors name
    /// `integration.FIELD`): `1e-14 ≤ rtol < 1` (below 1e-14 double precision cannot reach it);
    /// at least one `atol`, each positive and finite; `h_max` and `h_max_implicit` positive
    /// (`∞`: no limit); `h_initial` and `fixed_step`, when given, positive and finite;
    /// `max_steps ≥ 1`. [`Solver::new`] runs it and checks the number of `atol` values against
    /// the dimension.
    pub fn validate(&self) -> crate::error::Result<()> {
        use crate::error::{positive, Error};
        let rtol = self.rtol;
        if !(rtol > 0.0 && rtol.is_finite()) {
            return Err(Error::invalid("integration.rtol", format!("must be positive and finite, got {rtol}")));
        }
        if rtol < 1e-14 {
            return Err(Error::invalid("integration.rtol", format!("{rtol} is below what double precision can reach (1e-14)")));
        }
        if rtol >= 1.0 {
            return Err(Error::invalid("integration.rtol", format!("must be below 1, got {rtol}")));
        }
        if self.atol.is_empty() {
            return Err(Error::invalid("integration.atol", "needs at least one value"));
        }
        if let Some(a) = self.atol.iter().find(|a| !(**a > 0.0 && a.is_finite())) {
            return Err(Error::invalid("integration.atol", format!("must be positive and finite, got {a}")));
        }
        for (field, h) in [("integration.h_max", self.h_max), ("integration.h_max_implicit", self.h_max_implicit)] {
            if !(h > 0.0) {
                return Err(Error::invalid(field, format!("must be positive (inf: no limit), got {h}")));
            }
        }
        if let Some(h) = self.h_initial {
            positive("integration.h_initial", h)?;
        }
        if let Some(h) = self.fixed_step {
            if !(h > 0.0 && h.is_finite()) {
                return Err(Error::invalid("integration.fixed_step", format!("must be positive and finite, got {h}")));
            }
        }
        if self.max_steps == 0 {
            return Err(Error::invalid("integration.max_steps", "must be at least 1"));
        }
        Ok(())
    }
}

/// `rtol = 1e-8`, `atol = 1e-10` for every component (the simulations' defaults), then as
/// [`Options::new`]: [`Method::Auto`], no step limit, at most 10⁸ steps.
impl Default for Options {
    fn default() -> Self {
        Options::new(1e-8, 1e-10)
    }
}

crate::builder::builder!(
    /// Builder of the integrator's [`Options`]; `build()` runs [`Options::validate`] (the
    /// number of `atol` values is checked against the system by [`Solver::new`]).
    ///
    /// ```
    /// use autobal::ode::{Method, Options};
    /// let o = Options::builder().method(Method::Rodas).rtol(1e-6).atol(vec![1e-9, 1e-7]).h_max(0.1).build().unwrap();
    /// assert_eq!((o.method, o.rtol, o.atol.len(), o.max_steps), (Method::Rodas, 1e-6, 2, 100_000_000));
    /// let e = Options::builder().rtol(1e-16).build().unwrap_err();
    /// assert!(e.to_string().starts_with("integration.rtol"), "{e}");
    /// let e = Options::builder().fixed_step(Some(-0.1)).build().unwrap_err();
    /// assert!(e.to_string().starts_with("integration.fixed_step"), "{e}");
    /// ```
    OptionsBuilder for Options, |o| o.validate();
    method: Method, rtol: f64, atol: Vec<f64>, h_max: f64, h_max_implicit: f64, h_initial: Option<f64>, fixed_step: Option<f64>,
    max_steps: u64, max_wall: Option<std::time::Duration>,
);

/// Work counters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Stats {
    /// Accepted steps (both methods).
    pub steps: u64,
    /// Accepted steps of the implicit method.
    pub implicit_steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Evaluations of the right-hand side (stages, dense output, difference Jacobians,
    /// stiffness estimates).
    pub rhs_evaluations: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// LU factorisations of `α I − J`.
    pub factorizations: u64,
    /// Switches between the methods ([`Method::Auto`]).
    pub switches: u64,
}

impl Stats {
    /// Add another run's counters.
    pub fn add(&mut self, o: &Stats) {
        self.steps += o.steps;
        self.implicit_steps += o.implicit_steps;
        self.rejected += o.rejected;
        self.rhs_evaluations += o.rhs_evaluations;
        self.jacobians += o.jacobians;
        self.factorizations += o.factorizations;
        self.switches += o.switches;
    }
}

/// What the observer tells the integrator after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// Stop here ([`Status::Stopped`]).
    Stop,
}

/// How an integration ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// Reached `t_end`.
    Completed,
    /// Stopped before `t_end` on a decision to stop: the control's cancel flag
    /// ([`StopReason::Interrupted`]) or wall-time budget ([`StopReason::Budget`],
    /// [`Options::max_wall`] too), the step budget [`Options::max_steps`]
    /// ([`StopReason::TooManySteps`]), or the observer returned [`Control::Stop`]
    /// ([`StopReason::Observer`]).
    Stopped(StopReason),
    /// A terminal event ([`Solver::add_event`]) was located; its index.
    Event(usize),
    /// The step size fell below what double precision resolves at `t` (a singularity, or
    /// tolerances that cannot be met).
    StepTooSmall {
        /// The last step size tried.
        h: f64,
    },
    /// A component of the state or its derivative became NaN or infinite and smaller steps
    /// did not help.
    NotFinite {
        /// Index of the first offending component.
        component: usize,
        /// Its name ([`System::component_name`]).
        name: String,
    },
}

impl Status {
    /// Whether `t_end` was reached.
    pub fn is_completed(&self) -> bool {
        *self == Status::Completed
    }

    /// The reason of an early stop ([`Status::Stopped`]), if it is one.
    pub fn stop_reason(&self) -> Option<&StopReason> {
        match self {
            Status::Stopped(r) => Some(r),
            _ => None,
        }
    }
}

/// The result of [`Solver::integrate`]; the state itself is in the caller's slice.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Why it ended.
    pub status: Status,
    /// The time reached (the state in the caller's slice is at this time).
    pub t: f64,
    /// Work of this call.
    pub stats: Stats,
}

impl fmt::Display for Outcome {
    /// One line: "completed at t = …", "interrupted at t = …", "step size underflow (h = …) at
    /// t = …", "too many steps (…) at t = …", "the state became non-finite (…) at t = …".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = self.t;
        match &self.status {
            Status::Completed => write!(f, "completed at t = {t:.6}"),
            Status::Stopped(StopReason::Observer) => write!(f, "stopped by the observer at t = {t:.6}"),
            Status::Stopped(r) => write!(f, "{r} at t = {t:.6}"),
            Status::Event(i) => write!(f, "event {i} at t = {t:.9}"),
            Status::StepTooSmall { h } => {
                write!(f, "the step size fell to {h:.3e} at t = {t:.6}: the tolerances cannot be met there (a singularity or an unphysical input)")
            }
            Status::NotFinite { name, .. } => write!(f, "the state became non-finite ({name}) at t = {t:.6}"),
        }
    }
}
