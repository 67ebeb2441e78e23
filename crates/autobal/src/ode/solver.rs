//! The one step loop of both integrators: step-size control, acceptance, dense output, events,
//! cancellation, budgets, and the switching between DOP853 and RODAS.

use super::events::{crosses, locate};
use super::{dop853, rosenbrock, Control, Event, Jacobian, Method, Options, Outcome, Stats, Status, StopReason, System};
use crate::control::BUDGET_CHECK_EVERY;
use crate::error::{Error, Result};

/// Accepted DOP853 steps with `h |λ|` above the threshold before [`Method::Auto`] switches to
/// RODAS (Hairer's `dop853.f` reports stiffness after 15).
const STIFF_STEPS: u32 = 15;
/// Consecutive non-stiff tests that clear the count (Hairer: 6).
const NONSTIFF_RESET: u32 = 6;
/// In RODAS phases of [`Method::Auto`], the spectral radius is estimated every this many steps;
/// so are the unresolved modes (the cap on the implicit step), unless they are far from
/// binding ([`FAR`]).
const TEST_EVERY: u64 = 5;
/// Longest interval between two checks for unresolved modes, in implicit steps: the interval
/// doubles from [`TEST_EVERY`] up to this after each check that finds every mode [`FAR`] from
/// capping the step and none approaching (the least decay margin of the modes that could cap
/// a step, extrapolated linearly from the last check over the doubled interval, stays beyond
/// `DECAYED + NEAR`; the first check of a phase has nothing to extrapolate from and does not
/// back off), or the cap binding and steady ([`DRIFT`]), and is back to [`TEST_EVERY`] after
/// any other. The test for a switch back to DOP853 backs off the same way while DOP853 would
/// need steps [`FAR`] times shorter than the implicit one.
const TEST_EVERY_FAR: u64 = 20;
/// A check finds the modes far from capping the step when the longest implicit step allowed
/// ([`super::Options::h_max_implicit`]; never where it is infinite) is at most `1/FAR` of the
/// cap under more generous criteria (a mode counts from `Re(h_ref λ) > −(DECAYED + NEAR)`, and
/// it oscillates from `|Im(h_ref λ)| > κ/2`, allowed `|hλ| ≤ κ/2`): a mode that could cap a step
/// must first grow `2 FAR`-fold in `|λ|`, or its decay over `h_ref` weaken by `e^NEAR`, or its
/// frequency double.
const FAR: f64 = 4.0;
/// See [`FAR`]: `e^{−0.5}` of decay over `h_ref` (a mode at `Re(h_ref λ) = −3.5` is near).
const NEAR: f64 = 0.5;
/// Where the cap binds and is steady (one mode sets it under both criteria of [`FAR`], and
/// so no other mode is near: every counted mode is slower than the capping one, every mode
/// that could become counted must first weaken its decay by `e^NEAR` or double its frequency),
/// the interval between checks may double from [`TEST_EVERY`] up to [`TEST_EVERY_FAR`] while
/// the cap's relative drift over the interval, extrapolated from the last two checks, is at
/// most this, and the least decay margin of the modes other than the capping one that could
/// cap a step of `FAR h_ref`, extrapolated likewise, stays beyond `DECAYED + NEAR` (as for
/// [`FAR`]: a second mode that starts to count is then caught as a check every [`TEST_EVERY`]
/// steps would; one that appears abruptly, a frequency or damping that jumps, is seen at the
/// next check only, up to [`TEST_EVERY_FAR`] steps later, by this back-off as by [`FAR`]'s). The cap held until the next check is then the new one shrunk by that
/// extrapolated drift (`cap · e^{−d m}`, `d` the drift per implicit step, `m` the interval):
/// no longer than the cap the mode is expected to set at the end of the interval, where a
/// check every [`TEST_EVERY`] steps holds the unshrunk cap for 5 steps. A 5 % shorter cap
/// costs at most 5 % more steps while it binds.
const DRIFT: f64 = 0.05;
/// Power iterations per spectral-radius estimate.
const POWER_ITERATIONS: usize = 10;
/// Largest Krylov dimension of the check for unresolved modes (the Ritz values are the
/// eigenvalues of an at most 12×12 Hessenberg matrix).
const KRYLOV: usize = 12;
/// A mode decays enough to be left unresolved by the implicit method when
/// `Re(h_ref λ) ≤ −DECAYED` (a factor `e^{−3}` over `h_ref`, the longest implicit step allowed:
/// [`super::Options::h_max_implicit`] where finite, else the longest taken).
const DECAYED: f64 = 3.0;
/// `|h λ|` allowed for a mode that is not [`DECAYED`], at `rtol = 1e-8`. RODAS damps an
/// undamped oscillation by `log |R(iy)| = −6.3e-5, −1.9e-3, −0.34` per step at `y = 1, 2, 10`: at
/// `|hλ| = 1` a mode that grows through 30 e-folds over 400 of its radians is off by 0.03 of an
/// e-fold. Scaled with `rtol^{1/6}` (the per-step error in the growth exponent goes as `|hλ|⁶`).
const RESOLVED_AT_1E8: f64 = 1.0;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Explicit,
    Implicit,
}

/// An integrator for one system, with every buffer allocated once ([`Solver::new`]); calls of
/// [`Solver::integrate`] allocate nothing.
pub struct Solver<'s, S: System> {
    sys: &'s S,
    opts: Options,
    n: usize,
    atol: Vec<f64>,
    control: Option<&'s crate::control::Control>,
    events: Vec<Box<dyn Event + 's>>,
    jac: Option<Box<dyn Jacobian + 's>>,
    y: Vec<f64>,
    f: Vec<f64>,
    y_new: Vec<f64>,
    y_event: Vec<f64>,
    tmp1: Vec<f64>,
    tmp2: Vec<f64>,
    g_old: Vec<f64>,
    hits: Vec<(usize, f64)>,
    dop: dop853::Work,
    rodas: rosenbrock::Work,
    /// Arnoldi basis of the check for unresolved modes (`(KRYLOV + 1) × dim`, made on first use).
    krylov: Vec<f64>,
    /// Cap on the implicit step from that check (`∞`: none).
    mode_cap: f64,
    /// The step the error control asked for when the cap was set.
    h_free: f64,
    /// The longest implicit step so far.
    h_implicit_max: f64,
    // control state carried from one call to the next
    h_next: f64,
    mode: Mode,
    stiff_count: u32,
    nonstiff_count: u32,
    stiff_needed: u32,
    phase_steps: u64,
    /// The implicit step (of the phase) at which the next check for unresolved modes runs.
    next_cap_test: u64,
    /// Implicit steps from one check for unresolved modes to the next.
    cap_interval: u64,
    /// The longest such interval ([`TEST_EVERY_FAR`]; [`TEST_EVERY`] in tests: the schedule
    /// without the back-off).
    far_interval: u64,
    /// The longest interval where the cap binds and is steady ([`DRIFT`]; [`TEST_EVERY_FAR`],
    /// [`TEST_EVERY`] in tests: the schedule without that back-off).
    bound_interval: u64,
    /// Checks for unresolved modes so far.
    cap_checks: u64,
    /// The implicit step (of the phase) at which the next test for a switch back to DOP853
    /// runs, and the interval to it ([`FAR`]: it doubles, up to [`TEST_EVERY_FAR`], while
    /// DOP853 would need steps `FAR` times shorter than the implicit one).
    next_stiff_test: (u64, u64),
    /// The cap found by the last check (unshrunk; `∞`: none, or no check yet in this phase)
    /// and the implicit step of the phase it ran at ([`DRIFT`]).
    last_cap: (f64, u64),
    /// The least decay margins of the last check ([`Solver::unresolved_mode_cap`]: of all the
    /// modes, and of those other than the capping one), and the implicit step it ran at (`∞`:
    /// no check yet in this phase).
    last_margin: (f64, f64, u64),
    total: Stats,
    started: Option<std::time::Instant>,
}

/// One accepted step, as the observer of [`Solver::integrate`] sees it.
pub struct Step<'a, S: System> {
    /// Start of the step.
    pub t_old: f64,
    /// End of the step (the time of a terminal event when one cut the step short).
    pub t_new: f64,
    /// State at `t_old`.
    pub y_old: &'a [f64],
    /// State at `t_new`.
    pub y_new: &'a [f64],
    /// Which method took it ([`Method::Dop853`] or [`Method::Rodas`]).
    pub method: Method,
    /// Events located in the step, `(index, time)` in time order (a terminal one last).
    pub events: &'a [(usize, f64)],
    sys: &'a S,
    h: f64,
    y_end: &'a [f64],
    dop: &'a mut dop853::Work,
    rodas: &'a rosenbrock::Work,
    extra_rhs: &'a mut u64,
}

impl<S: System> Step<'_, S> {
    /// The dense output at `t ∈ [t_old, t_new]` into `out` (length `dim`): DOP853's 7th-order
    /// interpolant (3 more right-hand sides on first use in a step) or RODAS's 3rd-order one.
    pub fn interpolate(&mut self, t: f64, out: &mut [f64]) {
        interpolate(self.method, self.sys, self.dop, self.rodas, self.t_old, self.h, self.y_old, self.y_end, t, out, self.extra_rhs);
    }
}

#[allow(clippy::too_many_arguments)]
fn interpolate<S: System + ?Sized>(
    method: Method,
    sys: &S,
    dop: &mut dop853::Work,
    rodas: &rosenbrock::Work,
    t_old: f64,
    h: f64,
    y_old: &[f64],
    y_new: &[f64],
    t: f64,
    out: &mut [f64],
    rhs: &mut u64,
) {
    if t == t_old + h {
        out.copy_from_slice(y_new);
        return;
    }
    match method {
        Method::Rodas => rodas.interpolate(t_old, h, y_old, y_new, t, out),
        _ => *rhs += dop.interpolate(sys, t_old, h, y_old, y_new, t, out),
    }
}

impl<'s, S: System> Solver<'s, S> {
    /// A solver for `sys`; checks the options ([`Options::validate`], and one `atol` or one per
    /// component; errors name `integration.rtol`, `integration.atol`, ...) and allocates every
    /// buffer.
    pub fn new(sys: &'s S, opts: Options) -> Result<Self> {
        let n = sys.dim();
        opts.validate()?;
        let atol = match opts.atol.len() {
            1 => vec![opts.atol[0]; n],
            m if m == n => opts.atol.clone(),
            m => return Err(Error::invalid("integration.atol", format!("needs 1 or {n} values, got {m}"))),
        };
        let mode = if opts.method == Method::Rodas { Mode::Implicit } else { Mode::Explicit };
        Ok(Solver {
            sys,
            opts,
            n,
            atol,
            control: None,
            events: vec![],
            jac: None,
            y: vec![0.0; n],
            f: vec![0.0; n],
            y_new: vec![0.0; n],
            y_event: vec![0.0; n],
            tmp1: vec![0.0; n],
            tmp2: vec![0.0; n],
            g_old: vec![],
            hits: vec![],
            dop: dop853::Work::new(n),
            rodas: rosenbrock::Work::new(n),
            krylov: vec![],
            mode_cap: f64::INFINITY,
            h_free: 0.0,
            h_implicit_max: 0.0,
            h_next: 0.0,
            mode,
            stiff_count: 0,
            nonstiff_count: 0,
            stiff_needed: STIFF_STEPS,
            phase_steps: 0,
            next_cap_test: TEST_EVERY,
            cap_interval: TEST_EVERY,
            far_interval: TEST_EVERY_FAR,
            bound_interval: TEST_EVERY_FAR,
            cap_checks: 0,
            last_cap: (f64::INFINITY, 0),
            last_margin: (f64::INFINITY, f64::INFINITY, 0),
            next_stiff_test: (TEST_EVERY, TEST_EVERY),
            total: Stats::default(),
            started: None,
        })
    }

    /// Run under `control`: stop ([`Status::Stopped`]) with [`StopReason::Interrupted`] at the
    /// first step after its cancel flag is set (one atomic load before every step), with
    /// [`StopReason::Budget`] once its wall-time budget is spent (the clock is read every
    /// [`BUDGET_CHECK_EVERY`] steps, so a step loop of cheap steps stays cheap).
    pub fn control(&mut self, control: &'s crate::control::Control) {
        self.control = Some(control);
    }

    /// Locate the zeros of `event` on the dense output; returns its index (in
    /// [`Step::events`] and [`Status::Event`]).
    pub fn add_event(&mut self, event: impl Event + 's) -> usize {
        self.events.push(Box::new(event));
        self.g_old.push(0.0);
        self.hits.reserve(self.events.len());
        self.events.len() - 1
    }

    /// Counters of every call so far.
    pub fn stats(&self) -> Stats {
        self.total
    }

    /// The options.
    pub fn options(&self) -> &Options {
        &self.opts
    }

    /// The method that will take the next step ([`Method::Dop853`] or [`Method::Rodas`]).
    pub fn current_method(&self) -> Method {
        match self.mode {
            Mode::Explicit => Method::Dop853,
            Mode::Implicit => Method::Rodas,
        }
    }

    /// Forget the step size and stiffness state (e.g. after the equations changed at an
    /// event); the next call starts with a fresh initial step.
    pub fn reset(&mut self) {
        self.h_next = 0.0;
        self.stiff_count = 0;
        self.nonstiff_count = 0;
        self.phase_steps = 0;
        self.next_cap_test = TEST_EVERY;
        self.cap_interval = TEST_EVERY;
        self.mode_cap = f64::INFINITY;
        self.last_cap = (f64::INFINITY, 0);
        self.last_margin = (f64::INFINITY, f64::INFINITY, 0);
        self.next_stiff_test = (TEST_EVERY, TEST_EVERY);
        self.h_free = 0.0;
        self.mode = if self.opts.method == Method::Rodas { Mode::Implicit } else { Mode::Explicit };
    }

    fn non_finite(&self, v: &[f64]) -> Option<Status> {
        v.iter().position(|x| !x.is_finite()).map(|i| Status::NotFinite { component: i, name: self.sys.component_name(i) })
    }

    /// Integrate from `(t0, y)` to `t_end ≥ t0`, advancing `y` (length `dim`) in place, calling
    /// `observe` after every accepted step. The step size, the method in use and the stiffness
    /// state carry over to the next call (so a run can go on piecewise, e.g. between the
    /// breakpoints of a drive); budgets ([`Options::max_steps`], [`Options::max_wall`]) count
    /// all calls together.
    pub fn integrate(&mut self, t0: f64, y: &mut [f64], t_end: f64, mut observe: impl FnMut(&mut Step<'_, S>) -> Control) -> Outcome {
        let n = self.n;
        assert_eq!(y.len(), n, "state of length dim");
        let mut stats = Stats::default();
        let started = *self.started.get_or_insert_with(std::time::Instant::now);
        let mut t = t0;
        let done = |status: Status, t: f64, stats: Stats, total: &mut Stats| {
            total.add(&stats);
            Outcome { status, t, stats }
        };
        if let Some(s) = self.non_finite(y) {
            return done(s, t, stats, &mut self.total);
        }
        if !(t_end > t0) {
            return done(Status::Completed, t, stats, &mut self.total);
        }
        self.y.copy_from_slice(y);
        self.sys.rhs(t, &self.y, &mut self.f);
        stats.rhs_evaluations += 1;
        if let Some(s) = self.non_finite(&self.f) {
            return done(s, t, stats, &mut self.total);
        }
        for (g, e) in self.g_old.iter_mut().zip(&self.events) {
            *g = e.g(t, &self.y);
        }
        let rtol = self.opts.rtol;
        let h_max = |mode: Mode, o: &Options| if mode == Mode::Implicit { o.h_max.min(o.h_max_implicit) } else { o.h_max };
        let mut h = if let Some(hf) = self.opts.fixed_step {
            hf
        } else if self.h_next > 0.0 {
            self.h_next
        } else if let Some(h0) = self.opts.h_initial {
            h0
        } else {
            for i in 0..n {
                self.tmp1[i] = self.atol[i] + rtol * self.y[i].abs();
            }
            let order = if self.mode == Mode::Implicit { rosenbrock::ORDER } else { dop853::ORDER };
            let scale = std::mem::take(&mut self.tmp1);
            let h0 = dop853::initial_step(self.sys, t, &self.y, &self.f, h_max(self.mode, &self.opts), order, &scale, &mut self.y_new, &mut self.tmp2);
            self.tmp1 = scale;
            stats.rhs_evaluations += 1;
            h0
        };
        let mut rejected_last = false;
        // the Jacobian of the implicit method: made on first use, updated once per step
        let mut jac_fresh = false;
        loop {
            if t >= t_end {
                y.copy_from_slice(&self.y);
                self.h_next = if self.opts.fixed_step.is_some() { self.h_next } else { h };
                return done(Status::Completed, t, stats, &mut self.total);
            }
            if let Some(c) = self.control {
                let why = if c.is_cancelled() {
                    Some(StopReason::Interrupted)
                } else if stats.steps.is_multiple_of(BUDGET_CHECK_EVERY) {
                    c.budget_spent()
                } else {
                    None
                };
                if let Some(why) = why {
                    y.copy_from_slice(&self.y);
                    return done(Status::Stopped(why), t, stats, &mut self.total);
                }
            }
            if self.total.steps + stats.steps >= self.opts.max_steps {
                y.copy_from_slice(&self.y);
                return done(Status::Stopped(StopReason::TooManySteps { max_steps: self.opts.max_steps }), t, stats, &mut self.total);
            }
            if let Some(w) = self.opts.max_wall {
                if stats.steps.is_multiple_of(BUDGET_CHECK_EVERY) && started.elapsed() > w {
                    y.copy_from_slice(&self.y);
                    return done(Status::Stopped(StopReason::Budget { seconds: w.as_secs_f64() }), t, stats, &mut self.total);
                }
            }
            let hm = h_max(self.mode, &self.opts);
            h = h.min(hm);
            if self.mode == Mode::Implicit {
                h = h.min(self.mode_cap);
            }
            if self.opts.fixed_step.is_some() {
                h = self.opts.fixed_step.unwrap_or(h).min(t_end - t);
            }
            let last = t + 1.01 * h >= t_end;
            if last {
                h = t_end - t;
            }
            let min_step = 16.0 * f64::EPSILON * t.abs().max(t_end.abs() * 1e-3).max(f64::MIN_POSITIVE);
            if h < min_step {
                y.copy_from_slice(&self.y);
                return done(Status::StepTooSmall { h }, t, stats, &mut self.total);
            }
            // attempt
            let err = match self.mode {
                Mode::Explicit => {
                    self.dop.k[..n].copy_from_slice(&self.f);
                    let e = self.dop.attempt(self.sys, t, h, &self.y, &mut self.y_new, &self.atol, rtol);
                    stats.rhs_evaluations += 11;
                    Some(e)
                }
                Mode::Implicit => {
                    let jac = self.jac.get_or_insert_with(|| {
                        let mut j = self.sys.jacobian();
                        let typical: Vec<f64> = self.atol.iter().map(|a| a / rtol).collect();
                        j.set_typical(&typical);
                        j
                    });
                    if !jac_fresh {
                        stats.rhs_evaluations += jac.update(t, &self.y, &self.f);
                        stats.jacobians += 1;
                        if !jac.time_derivative(t, &self.y, &self.f, &mut self.rodas.dfdt) {
                            // ∂f/∂t by a central difference inside [t0, t_end] (one-sided at
                            // its ends: never across a breakpoint)
                            let dt = f64::EPSILON.cbrt() * t.abs().max(h).max(1e-3 * (t_end - t0));
                            let (lo, hi) = (t - dt >= t0, t + dt <= t_end);
                            if lo && hi {
                                self.sys.rhs(t + dt, &self.y, &mut self.tmp1);
                                self.sys.rhs(t - dt, &self.y, &mut self.tmp2);
                                stats.rhs_evaluations += 2;
                                for i in 0..n {
                                    self.rodas.dfdt[i] = (self.tmp1[i] - self.tmp2[i]) / (2.0 * dt);
                                }
                            } else {
                                let dt = if hi { f64::EPSILON.sqrt() * t.abs().max(h) } else { -f64::EPSILON.sqrt() * t.abs().max(h) };
                                self.sys.rhs(t + dt, &self.y, &mut self.tmp1);
                                stats.rhs_evaluations += 1;
                                for i in 0..n {
                                    self.rodas.dfdt[i] = (self.tmp1[i] - self.f[i]) / dt;
                                }
                            }
                        }
                        jac_fresh = true;
                    }
                    stats.factorizations += 1;
                    self.rodas.attempt(self.sys, jac.as_mut(), t, h, &self.y, &self.f, &mut self.y_new, &self.atol, rtol, &mut stats.rhs_evaluations)
                }
            };
            let (q, grow_max, shrink_min) = match self.mode {
                Mode::Explicit => (dop853::ORDER as f64, 6.0, 1.0 / 3.0),
                Mode::Implicit => (rosenbrock::ORDER as f64, 6.0, 0.2),
            };
            let fixed = self.opts.fixed_step.is_some();
            let bad = match err {
                None => true,
                Some(e) => !e.is_finite() || self.y_new.iter().any(|v| !v.is_finite()),
            };
            if bad && fixed {
                y.copy_from_slice(&self.y);
                let s = self.non_finite(&self.y_new).unwrap_or(Status::StepTooSmall { h });
                return done(s, t, stats, &mut self.total);
            }
            if bad {
                // singular matrix or overflow: much smaller steps
                stats.rejected += 1;
                rejected_last = true;
                h *= 0.2;
                if h < min_step {
                    y.copy_from_slice(&self.y);
                    let s = self.non_finite(&self.y_new).unwrap_or(Status::StepTooSmall { h });
                    return done(s, t, stats, &mut self.total);
                }
                continue;
            }
            let err = err.unwrap_or(f64::NAN);
            if !(fixed || err <= 1.0) {
                stats.rejected += 1;
                rejected_last = true;
                h *= (0.9 * err.powf(-1.0 / q)).clamp(shrink_min, 1.0);
                continue;
            }
            // accepted: the derivative at the new point (the next step's first stage)
            let t_new = if last { t_end } else { t + h };
            let method = match self.mode {
                Mode::Explicit => {
                    self.dop.finish(self.sys, t_new, &self.y_new);
                    stats.rhs_evaluations += 1;
                    Method::Dop853
                }
                Mode::Implicit => {
                    self.rodas.finish();
                    self.sys.rhs(t_new, &self.y_new, &mut self.tmp2);
                    stats.rhs_evaluations += 1;
                    Method::Rodas
                }
            };
            stats.steps += 1;
            if method == Method::Rodas {
                stats.implicit_steps += 1;
            }
            // events on the dense output
            self.hits.clear();
            let mut t_cut = t_new;
            let mut terminal: Option<usize> = None;
            for (i, e) in self.events.iter().enumerate() {
                let g1 = e.g(t_new, &self.y_new);
                let g0 = self.g_old[i];
                if crosses(e.direction(), g0, g1) {
                    let (sys, dop, rodas, y_old, y_new, buf) = (self.sys, &mut self.dop, &self.rodas, &self.y, &self.y_new, &mut self.y_event);
                    let rhs = &mut stats.rhs_evaluations;
                    let te = locate(
                        |tt| {
                            interpolate(method, sys, dop, rodas, t, h, y_old, y_new, tt, buf, rhs);
                            e.g(tt, buf)
                        },
                        t,
                        g0,
                        t_new,
                        g1,
                    );
                    self.hits.push((i, te));
                    if e.terminal() && te <= t_cut {
                        t_cut = te;
                        terminal = Some(i);
                    }
                }
            }
            if let Some(ti) = terminal {
                self.hits.retain(|&(i, te)| te < t_cut || i == ti);
            }
            self.hits.sort_by(|a, b| a.1.total_cmp(&b.1));
            if terminal.is_some() {
                interpolate(method, self.sys, &mut self.dop, &self.rodas, t, h, &self.y, &self.y_new, t_cut, &mut self.y_event, &mut stats.rhs_evaluations);
            } else {
                self.y_event.copy_from_slice(&self.y_new);
            }
            let control = {
                let mut step = Step {
                    t_old: t,
                    t_new: t_cut,
                    y_old: &self.y,
                    y_new: &self.y_event,
                    method,
                    events: &self.hits,
                    sys: self.sys,
                    h,
                    y_end: &self.y_new,
                    dop: &mut self.dop,
                    rodas: &self.rodas,
                    extra_rhs: &mut stats.rhs_evaluations,
                };
                observe(&mut step)
            };
            // advance
            if let Some(ti) = terminal {
                y.copy_from_slice(&self.y_event);
                self.y.copy_from_slice(&self.y_event);
                self.dop.invalidate();
                self.h_next = h;
                return done(Status::Event(ti), t_cut, stats, &mut self.total);
            }
            std::mem::swap(&mut self.y, &mut self.y_new);
            match method {
                Method::Rodas => self.f.copy_from_slice(&self.tmp2),
                _ => self.f.copy_from_slice(self.dop.k(12)),
            }
            let h_old = h;
            t = t_new;
            jac_fresh = false;
            for (g, e) in self.g_old.iter_mut().zip(&self.events) {
                *g = e.g(t, &self.y);
            }
            if let Some(s) = self.non_finite(&self.f) {
                y.copy_from_slice(&self.y);
                return done(s, t, stats, &mut self.total);
            }
            // next step size
            if !fixed {
                let fac = if err == 0.0 { grow_max } else { (0.9 * err.powf(-1.0 / q)).clamp(shrink_min, grow_max) };
                let fac = if rejected_last { fac.min(1.0) } else { fac };
                h = h_old * fac;
            }
            rejected_last = false;
            // implicit steps must not step over a mode that grows or decays slowly: RODAS damps
            // an unresolved oscillation (|R(iy)| → 0 as y → ∞), so a slow instability would
            // never get going. Every TEST_EVERY implicit steps (up to TEST_EVERY_FAR while every
            // mode is FAR from capping the step): the modes of J, and a cap on h.
            if self.mode == Mode::Implicit && !fixed {
                self.phase_steps += 1;
                if self.phase_steps.is_multiple_of(TEST_EVERY) {
                    self.h_implicit_max = self.h_implicit_max.max(h_old);
                }
                if self.phase_steps >= self.next_cap_test {
                    let hm = h_max(self.mode, &self.opts);
                    let h_ref = if hm.is_finite() { hm } else { h.max(self.h_free).max(self.h_implicit_max) };
                    let (cap, loose, margin, other) = self.unresolved_mode_cap(h_old, h_ref);
                    self.cap_checks += 1;
                    if cap.is_finite() && self.mode_cap.is_infinite() {
                        self.h_free = h_ref;
                    } else if cap.is_infinite() {
                        self.h_free = 0.0;
                    }
                    // far, and not getting near fast: the decay margin of the modes that could
                    // cap a step, extrapolated from the last check over the doubled interval,
                    // stays beyond DECAYED + NEAR (a mode whose damping falls steadily is
                    // caught before it counts, not up to TEST_EVERY_FAR steps after)
                    let (last_margin, last_other, margin_at) = self.last_margin;
                    let since = (self.phase_steps - margin_at).max(1) as f64;
                    let fall = ((last_margin - margin) / since).max(0.0);
                    let far_doubled = (2 * self.cap_interval).min(self.far_interval);
                    let far = hm.is_finite() && loose >= FAR * hm && !(margin - fall * far_doubled as f64 <= DECAYED + NEAR);
                    // the same margin for the modes other than the capping one: where the cap
                    // binds, the back-off needs them far and not approaching too (a second
                    // mode that starts to count would otherwise go unseen for the whole
                    // interval); a mode that appears abruptly (a frequency or damping that
                    // jumps) is seen by no extrapolation, only at the next check, as here
                    let fall_other = ((last_other - other) / since).max(0.0);
                    let bound_doubled = (2 * self.cap_interval).min(self.bound_interval);
                    let others_far = !(other - fall_other * bound_doubled as f64 <= DECAYED + NEAR);
                    self.last_margin = (margin, other, self.phase_steps);
                    // binding and steady: one mode sets both caps (`loose ≤ cap/2` always, as
                    // that mode is among those of the generous criteria), the last check found
                    // a cap too, and the drift since it extrapolates to at most DRIFT
                    let (last, at) = self.last_cap;
                    let drift = (cap / last).ln().abs() / (self.phase_steps - at).max(1) as f64;
                    let doubled = 2 * self.cap_interval;
                    let steady = cap < hm && last.is_finite() && loose >= 0.5 * cap && others_far && drift * doubled.min(self.bound_interval) as f64 <= DRIFT;
                    self.cap_interval = if far {
                        doubled.min(self.far_interval)
                    } else if steady {
                        doubled.min(self.bound_interval)
                    } else {
                        TEST_EVERY
                    };
                    self.mode_cap = if steady && !far && self.cap_interval > TEST_EVERY { cap * (-drift * self.cap_interval as f64).exp() } else { cap };
                    self.last_cap = (cap, self.phase_steps);
                    self.next_cap_test = self.phase_steps + self.cap_interval;
                }
            }
            // automatic switching
            if self.opts.method == Method::Auto && !fixed {
                match self.mode {
                    Mode::Explicit => {
                        // Hairer's test: h|λ| at the stability boundary in STIFF_STEPS steps
                        let hl = self.dop.h_lambda(h_old, &self.y);
                        if hl > dop853::STIFFNESS_THRESHOLD {
                            self.nonstiff_count = 0;
                            self.stiff_count += 1;
                            if self.stiff_count >= self.stiff_needed {
                                self.mode = Mode::Implicit;
                                self.stiff_count = 0;
                                self.phase_steps = 0;
                                self.next_cap_test = TEST_EVERY;
                                self.cap_interval = TEST_EVERY;
                                self.mode_cap = f64::INFINITY;
                                self.last_cap = (f64::INFINITY, 0);
                                self.last_margin = (f64::INFINITY, f64::INFINITY, 0);
                                self.next_stiff_test = (TEST_EVERY, TEST_EVERY);
                                self.h_free = 0.0;
                                stats.switches += 1;
                            }
                        } else {
                            self.nonstiff_count += 1;
                            if self.nonstiff_count >= NONSTIFF_RESET {
                                self.stiff_count = 0;
                            }
                        }
                    }
                    Mode::Implicit => {
                        if self.phase_steps >= self.next_stiff_test.0 {
                            let rho = self.spectral_radius(t, &mut stats);
                            // the switch saves work, it does not decide accuracy (RODAS's steps
                            // are error-controlled and capped for unresolved modes like any
                            // other): where DOP853 would need FAR times shorter steps, test less
                            // often, as the check for unresolved modes does where it is far
                            let hr = h.min(self.mode_cap) * rho;
                            let interval =
                                if hr > FAR * 0.9 * dop853::STABILITY_RADIUS { (2 * self.next_stiff_test.1).min(self.far_interval) } else { TEST_EVERY };
                            self.next_stiff_test = (self.phase_steps + interval, interval);
                            // back to DOP853 when it could take the implicit step stably (the
                            // step as capped for unresolved modes: where that cap is as short
                            // as DOP853's stable step, RODAS has nothing left to gain)
                            if hr <= 0.9 * dop853::STABILITY_RADIUS {
                                self.mode = Mode::Explicit;
                                stats.switches += 1;
                                // a short implicit phase was not worth it: ask for more evidence
                                // of stiffness next time (and forgive once it pays again)
                                self.stiff_needed =
                                    if self.phase_steps <= 4 * TEST_EVERY { (self.stiff_needed * 2).min(STIFF_STEPS << 8) } else { STIFF_STEPS };
                                self.stiff_count = 0;
                                self.nonstiff_count = 0;
                                h = h.min(0.9 * dop853::STABILITY_RADIUS / rho.max(f64::MIN_POSITIVE));
                            }
                        }
                    }
                }
            }
            self.h_next = h;
            if control == Control::Stop {
                y.copy_from_slice(&self.y);
                return done(Status::Stopped(StopReason::Observer), t, stats, &mut self.total);
            }
        }
    }

    /// The largest implicit step that resolves every mode of `J` that does not decay within a
    /// step of `h_ref`: `min |κ/λ|` over the eigenvalues `λ` with `Re(h_ref λ) > −DECAYED`
    /// (`κ` = [`RESOLVED_AT_1E8`] `(rtol/1e-8)^{1/6}`), `∞` when there is none. The eigenvalues
    /// come from Arnoldi's method on the shift-invert operator `(α I − J)⁻¹` with the step's
    /// factorisation (`α = 1/(γ h)`, `h` the step just taken): it finds the eigenvalues nearest
    /// `α`, i.e. the slow ones, first; with at most [`KRYLOV`] states the Krylov space is the
    /// whole space and the eigenvalues are exact. In the weighted variables `y_i/(atol_i +
    /// rtol |y_i|)`. Returns the cap, the same under the more generous criteria of
    /// [`FAR`] (at most the cap), and the least decay `−Re(h_ref λ)` of the modes that
    /// oscillate by those criteria (or grow) and are fast enough to cap a step of `FAR h_ref`
    /// (`∞`: none), and the same without the mode that sets the cap (both eigenvalues of its
    /// pair: those within `1e-9` relative of it in real part and `|Im|`).
    fn unresolved_mode_cap(&mut self, h: f64, h_ref: f64) -> (f64, f64, f64, f64) {
        let n = self.n;
        let Some(jac) = self.jac.as_mut() else { return (f64::INFINITY, f64::INFINITY, f64::INFINITY, f64::INFINITY) };
        let m = n.min(KRYLOV);
        if self.krylov.len() < (KRYLOV + 1) * n {
            self.krylov = vec![0.0; (KRYLOV + 1) * n];
        }
        let rtol = self.opts.rtol;
        let scale: &mut Vec<f64> = &mut self.tmp1;
        for i in 0..n {
            scale[i] = self.atol[i] + rtol * self.y[i].abs();
        }
        let v = &mut self.krylov;
        for i in 0..n {
            let hsh = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 61;
            v[i] = (1.0 + hsh as f64) * if i % 3 == 1 { -1.0 } else { 1.0 };
        }
        let norm = |x: &[f64]| x.iter().map(|a| a * a).sum::<f64>().sqrt();
        let nv = norm(&v[..n]);
        v[..n].iter_mut().for_each(|x| *x /= nv);
        let mut hess: crate::linalg::small::Mat12 = Default::default();
        let mut size = m;
        let w = &mut self.tmp2;
        for k in 0..m {
            for i in 0..n {
                w[i] = v[k * n + i] * scale[i];
            }
            jac.solve(w);
            for i in 0..n {
                w[i] /= scale[i];
            }
            let before = norm(w);
            // modified Gram–Schmidt, twice (the sizes of the models' states unrolled)
            let mut col = [0.0; KRYLOV];
            let r = match n {
                6 => orthogonalize::<6>(v, n, k, w, &mut col),
                8 => orthogonalize::<8>(v, n, k, w, &mut col),
                10 => orthogonalize::<10>(v, n, k, w, &mut col),
                12 => orthogonalize::<12>(v, n, k, w, &mut col),
                _ => orthogonalize::<0>(v, n, k, w, &mut col),
            };
            for j in 0..=k {
                hess[j][k] = col[j];
            }
            if !(r > 1e-12 * before) || k + 1 == m {
                // an invariant subspace (or the last column): the Ritz values of what is found
                size = k + 1;
                break;
            }
            hess[k + 1][k] = r;
            let (_, next) = v.split_at_mut((k + 1) * n);
            next[..n].iter_mut().zip(w.iter()).for_each(|(a, x)| *a = x / r);
        }
        let Ok(mu) = crate::linalg::eigen::hessenberg_eigenvalues(&hess, size) else { return (self.mode_cap, 0.0, 0.0, 0.0) };
        let alpha = 1.0 / (rosenbrock::GAMMA * h);
        let kappa = RESOLVED_AT_1E8 * (rtol / 1e-8).powf(1.0 / 6.0);
        let (mut cap, mut loose, mut margin) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
        let mut capping = num_complex::Complex64::new(f64::NAN, f64::NAN);
        for &mu in &mu {
            if !(mu.norm() > 0.0) {
                continue; // an eigenvalue at infinity
            }
            let lambda = alpha - mu.inv();
            if !(lambda.norm() > 0.0) {
                continue;
            }
            // a real decaying mode is only damped faster (0 < R(z) < 1): harmless
            let oscillates = lambda.im.abs() * h_ref > kappa;
            if lambda.re * h_ref > -DECAYED && (oscillates || lambda.re > 0.0) && kappa / lambda.norm() < cap {
                cap = kappa / lambda.norm();
                capping = lambda;
            }
            if lambda.re * h_ref > -(DECAYED + NEAR) && (lambda.im.abs() * h_ref > 0.5 * kappa || lambda.re > 0.0) {
                loose = loose.min(0.5 * kappa / lambda.norm());
            }
            // the decay over h_ref of a mode fast enough to cap a step FAR times h_ref, were
            // it not decayed (the modes slower than that never matter to the back-off)
            if (lambda.im.abs() * h_ref > 0.5 * kappa || lambda.re > 0.0) && 0.5 * kappa / lambda.norm() < FAR * h_ref {
                margin = margin.min(-lambda.re * h_ref);
            }
        }
        // the margin of the other modes (a second pass: which mode caps is known only now)
        let mut other = f64::INFINITY;
        for &mu in &mu {
            let lambda = alpha - mu.inv();
            let same = (lambda.re - capping.re).abs() <= 1e-9 * capping.norm() && (lambda.im.abs() - capping.im.abs()).abs() <= 1e-9 * capping.norm();
            if mu.norm() > 0.0
                && lambda.norm() > 0.0
                && !same
                && (lambda.im.abs() * h_ref > 0.5 * kappa || lambda.re > 0.0)
                && 0.5 * kappa / lambda.norm() < FAR * h_ref
            {
                other = other.min(-lambda.re * h_ref);
            }
        }
        (cap, loose, margin, other)
    }

    /// Spectral radius of `J` at `(t, self.y)` by power iteration on difference products
    /// `J v ≈ (f(y + εv) − f(y))/ε`, in the norm weighted by the tolerances; the geometric mean
    /// of the last growth ratios (a complex pair makes single ratios oscillate).
    fn spectral_radius(&mut self, t: f64, stats: &mut Stats) -> f64 {
        let n = self.n;
        let rtol = self.opts.rtol;
        let scale = |i: usize, y: &[f64]| self.atol[i] + rtol * y[i].abs();
        // start: a fixed pattern of signs (deterministic), unit weighted norm
        let mut u: Vec<f64> = std::mem::take(&mut self.tmp1);
        for (i, ui) in u.iter_mut().enumerate() {
            let h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 61;
            *ui = (1.0 + h as f64) * if i % 3 == 1 { -1.0 } else { 1.0 };
        }
        let norm = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / n as f64).sqrt();
        let nu = norm(&u);
        u.iter_mut().for_each(|x| *x /= nu);
        let eps = f64::EPSILON.sqrt() / rtol;
        let mut log_sum = 0.0;
        let mut counted = 0;
        for it in 0..POWER_ITERATIONS {
            for i in 0..n {
                self.y_event[i] = self.y[i] + eps * u[i] * scale(i, &self.y);
            }
            self.sys.rhs(t, &self.y_event, &mut self.tmp2);
            stats.rhs_evaluations += 1;
            for i in 0..n {
                u[i] = (self.tmp2[i] - self.f[i]) / (eps * scale(i, &self.y));
            }
            let r = norm(&u);
            if !(r > 0.0 && r.is_finite()) {
                self.tmp1 = u;
                return if r == 0.0 { 0.0 } else { f64::INFINITY };
            }
            u.iter_mut().for_each(|x| *x /= r);
            if it >= POWER_ITERATIONS / 2 {
                log_sum += r.ln();
                counted += 1;
            }
        }
        self.tmp1 = u;
        (log_sum / counted as f64).exp()
    }
}

/// Column `k` of Arnoldi's Hessenberg matrix by modified Gram–Schmidt, twice, against the
/// basis rows `v_0 … v_k` (row `j` at `v[j n..(j+1) n]`): for each pass and each `j ≤ k`,
/// `d = v_j · w`, `H_jk += d`, `w ← w − d v_j`; the `H_jk` into `col` (from `+0`), `w` left
/// orthogonal, and `‖w‖₂` returned. Each dot product is summed in index order from `−0`
/// (as `Iterator::sum`), the next one fused into the loop of the update before it, and the norm
/// into the last: the same operations in the same order as the two plain loops, so the same bits
/// (tested against them), with fewer loads and, for `N = n > 0`, loops of known length. `N = 0`:
/// any `n`.
fn orthogonalize<const N: usize>(v: &[f64], n: usize, k: usize, w: &mut [f64], col: &mut [f64]) -> f64 {
    let len = if N == 0 { n } else { N };
    let w = &mut w[..len];
    let row = |j: usize| &v[j * len..j * len + len];
    let mut d = -0.0;
    for (vi, wi) in row(0).iter().zip(w.iter()) {
        d += vi * wi;
    }
    for pass in 0..2 {
        for j in 0..=k {
            col[j] += d;
            let vj = row(j);
            let mut s = -0.0;
            if pass == 1 && j == k {
                for i in 0..len {
                    w[i] -= d * vj[i];
                    s += w[i] * w[i];
                }
            } else {
                let u = row(if j == k { 0 } else { j + 1 });
                for i in 0..len {
                    w[i] -= d * vj[i];
                    s += u[i] * w[i];
                }
            }
            d = s;
        }
    }
    d.sqrt()
}

#[cfg(test)]
mod tests {
    use super::{orthogonalize, Solver, KRYLOV};
    use crate::ode::{Control, Options, System};

    /// A stiff decaying component (`z' = −1e4 z`: the automatic method goes implicit and stays)
    /// beside an oscillator at 13 rad/s whose damping falls linearly through zero, driven by a
    /// slow force: `x'' + 2σ(t) x' + 13² x = 1 + 0.1 t`, `σ = 10 − 0.25 t`. Strongly damped at
    /// first (no mode near capping a step of 1 s: the checks back off), its mode counts for the
    /// cap from `σ < 3` (t > 28 s) and grows from t = 40 s, from a seed below the tolerances.
    struct Ramp;
    impl System for Ramp {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            let sigma = 10.0 - 0.25 * t;
            dy[0] = -1e4 * y[0];
            dy[1] = y[2];
            dy[2] = -169.0 * y[1] - 2.0 * sigma * y[2] + 1.0 + 0.1 * t;
        }
    }

    /// Where no mode is near capping the step, checking less often changes nothing: on the ramp
    /// (the mode arrives after a stretch of backed-off checks, and decides the run: without any
    /// check RODAS's steps of 1 s damp it, and the oscillation at t = 55 s is ~1 450 times
    /// smaller) the automatic method with the back-off takes the same steps and ends in the same
    /// state, bit for bit, as with a check every `TEST_EVERY` steps, with fewer checks.
    #[test]
    fn checking_less_often_where_no_mode_is_near_changes_nothing() {
        let run = |far_interval: u64| {
            let mut opts = Options::new(1e-8, 1e-10);
            opts.h_max_implicit = 1.0;
            let mut s = Solver::new(&Ramp, opts).unwrap();
            s.far_interval = far_interval;
            // the back-off where the cap binds (from t = 29.8 s here) changes the steps by
            // rounding (another cap held); it has its own test (`…_where_the_cap_binds_…`)
            s.bound_interval = super::TEST_EVERY;
            let mut y = [1.0, 0.0, 0.0];
            let out = s.integrate(0.0, &mut y, 55.0, |_| Control::Continue);
            assert!(out.status.is_completed(), "{out:?}");
            (y.map(f64::to_bits), out.stats, s.cap_checks)
        };
        let (y_far, stats_far, checks_far) = run(super::TEST_EVERY_FAR);
        let (y_5, stats_5, checks_5) = run(super::TEST_EVERY);
        assert!(stats_5.implicit_steps > 1000, "{stats_5:?}");
        // the same steps and end state; fewer right-hand sides (the test for a switch back to
        // DOP853 backs off too, where DOP853 would need steps FAR times shorter)
        let same = |s: crate::ode::Stats| (s.steps, s.implicit_steps, s.rejected, s.jacobians, s.factorizations, s.switches);
        assert_eq!((y_far, same(stats_far)), (y_5, same(stats_5)));
        assert!(stats_far.rhs_evaluations < stats_5.rhs_evaluations, "{stats_far:?} {stats_5:?}");
        assert!(checks_far < checks_5, "{checks_far} checks with the back-off, {checks_5} without");
        // the oscillation grew (about 28 e-folds from t = 40 s): the checks decide this run
        let amp = |y: [u64; 3]| (f64::from_bits(y[1]) - 6.5 / 169.0).hypot(f64::from_bits(y[2]) / 13.0);
        assert!(amp(y_5) > 1e-2, "{}", amp(y_5));
        // the default schedule (both back-offs) on the same ramp: the mode must still grow
        // (4.97e-2 against 7.66e-2 with a check every TEST_EVERY steps where the cap binds).
        // What grows is the local error (the exact free oscillation is damped by ~e^-200 by
        // t = 40 s; `amp` is 2.5e-5 at rtol 1e-12, the forced response's offset from 6.5/169),
        // seeded at the tolerances' level, so only its order says whether the checks held
        // the steps to the mode: without them it ends ~1 450 times smaller
        let mut opts = Options::new(1e-8, 1e-10);
        opts.h_max_implicit = 1.0;
        let mut s = Solver::new(&Ramp, opts).unwrap();
        let mut y = [1.0, 0.0, 0.0];
        let out = s.integrate(0.0, &mut y, 55.0, |_| Control::Continue);
        assert!(out.status.is_completed(), "{out:?}");
        assert!(amp(y.map(f64::to_bits)) > 1e-2, "{}", amp(y.map(f64::to_bits)));
    }

    /// A stiff decaying component beside an oscillator at rest whose frequency rises linearly,
    /// `x'' + 2σ(t) x' + ω(t)² x = 0`, `ω = 13 + 0.13 t` rad/s, `σ = max(10 − 0.5 t, 0.05)`
    /// 1/s: strongly damped at first, then nearly undamped, so from `σ < 3` (t > 14 s) its
    /// mode caps RODAS's steps (`κ/ω` < 1 s = `h_max_implicit`; at rest it sets no error, so
    /// nothing else limits them) and the cap shrinks as `ω` rises. The mode's eigenvalues are
    /// `−σ ± i √(ω² − σ²)`, `|λ| = ω` in closed form.
    struct Chirp;
    impl System for Chirp {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            let (sigma, omega) = ((10.0 - 0.5 * t).max(0.05), 13.0 + 0.13 * t);
            dy[0] = -1e4 * y[0];
            dy[1] = y[2];
            dy[2] = -omega * omega * y[1] - 2.0 * sigma * y[2];
        }
    }

    /// The checks' back-offs must not let implicit steps outrun the mode. Where no mode is
    /// near, the back-off ([`super::FAR`]) must still catch the mode within `TEST_EVERY` steps
    /// of the time it starts to count (its damping falls steadily: the decay margin is
    /// extrapolated). Where the cap binds ([`super::DRIFT`]), measured against the closed-form
    /// `|λ(t)| = ω(t)` at the end of every implicit step from t = 21 s (σ = 0.05), `h ω / κ`
    /// (`κ` = 1 at rtol 1e-8)
    /// is never larger with the back-off than with a check every `TEST_EVERY` steps, with
    /// fewer checks. Holding the cap found at a check for the longer interval without
    /// shrinking it by the drift fails this (the rising frequency makes a held cap too long
    /// by the drift over the whole interval, ~1.5 % at 20 steps against ~0.4 % at 5).
    #[test]
    fn checking_less_often_where_the_cap_binds_keeps_steps_within_it() {
        let run = |bound_interval: u64| {
            let mut opts = Options::new(1e-8, 1e-10);
            opts.h_max_implicit = 1.0;
            let mut s = Solver::new(&Chirp, opts).unwrap();
            s.bound_interval = bound_interval;
            let mut y = [1.0, 0.0, 0.0];
            let (mut worst, mut steps, mut caught) = (0.0f64, 0, f64::INFINITY);
            let out = s.integrate(0.0, &mut y, 60.0, |st| {
                let h_omega = (st.t_new - st.t_old) * (13.0 + 0.13 * st.t_new);
                if st.method == crate::ode::Method::Rodas && st.t_old >= 15.0 && h_omega <= 1.05 {
                    caught = caught.min(st.t_old);
                }
                if st.method == crate::ode::Method::Rodas && st.t_old >= 21.0 {
                    worst = worst.max(h_omega);
                    steps += 1;
                }
                Control::Continue
            });
            assert!(out.status.is_completed(), "{out:?}");
            (worst, steps, s.cap_checks, caught)
        };
        let (worst_far, steps_far, checks_far, caught_far) = run(super::TEST_EVERY_FAR);
        let (worst_5, steps_5, checks_5, caught_5) = run(super::TEST_EVERY);
        // the mode counts from t = 15 s (σ < 3): caught (a step within 5 % of κ/ω: a held cap
        // is stale by the drift of up to 20 steps) within TEST_EVERY steps of 1 s (the
        // schedule's own latency), in both runs; the back-off where no mode is near, were it
        // not to extrapolate the falling decay margin, would find it only at t = 29.96 s
        // TEST_EVERY implicit steps of at most h_max_implicit = 1 s each span at most this (s)
        let latency = super::TEST_EVERY as f64 * 1.0;
        assert!(caught_far <= 15.0 + latency && caught_5 <= 15.0 + latency, "{caught_far} {caught_5}");
        // the cap binds (steps at it, not below it by the error control) and is tested often
        assert!(worst_5 > 0.99 && steps_5 > 300, "{worst_5} {steps_5}");
        assert!(worst_far <= worst_5, "h ω/κ at most {worst_far} with the back-off, {worst_5} without");
        // the back-off happened: at most half the checks, for at most 5 % more steps (DRIFT)
        assert!(2 * checks_far <= checks_5, "{checks_far} checks with the back-off, {checks_5} without");
        assert!(steps_far as f64 <= 1.05 * steps_5 as f64, "{steps_far} steps with the back-off, {steps_5} without");
    }

    /// A stiff decaying component, mode 1 undamped at 13 rad/s (at rest: its cap `κ/13` binds
    /// and is steady, so the checks back off where only that mode counts), and mode 2: `kind`
    /// 0: undamped at 5 rad/s (resolved, slower than mode 1) until `t0`, then at `w` with
    /// damping −0.2 (it grows: a mode appearing abruptly); `kind` 1: at `w` throughout, its
    /// damping `σ` = 5 until `t0`, then falling at `rate` 1/s to −0.2 (a decay weakening).
    struct Two {
        w: f64,
        kind: u8,
        rate: f64,
        t0: f64,
    }
    impl Two {
        fn sigma_omega(&self, t: f64) -> (f64, f64) {
            match self.kind {
                0 if t < self.t0 => (0.0, 5.0),
                0 => (-0.2, self.w),
                _ => ((5.0 - self.rate * (t - self.t0).max(0.0)).max(-0.2), self.w),
            }
        }
    }
    impl System for Two {
        fn dim(&self) -> usize {
            5
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            let (sigma, omega) = self.sigma_omega(t);
            dy[0] = -1e4 * y[0];
            dy[1] = y[2];
            dy[2] = -169.0 * y[1];
            dy[3] = y[4];
            dy[4] = -omega * omega * y[3] - 2.0 * sigma * y[4];
        }
    }

    /// The back-off where the cap binds must watch the modes other than the capping one: a
    /// second, faster mode that starts to count (`Two`) must be resolved (`h w ≤ 1.05 κ`, κ = 1
    /// at rtol 1e-8; 5 % for the cap's drift allowance) on no fewer implicit steps, from the
    /// time it counts, than with a check every `TEST_EVERY` steps there. Pass 14's back-off
    /// looked only at the capping mode's drift and failed this (w = 300, t0 = 30.39–30.91: 13–20
    /// steps at `h w` up to 23 against at most 5; the weakening decay: 16 against 1).
    #[test]
    fn checking_less_often_where_the_cap_binds_sees_other_modes() {
        let run = |sys: &Two, bound_interval: u64| {
            let mut opts = Options::new(1e-8, 1e-10);
            opts.h_max_implicit = 1.0;
            let mut s = Solver::new(sys, opts).unwrap();
            s.bound_interval = bound_interval;
            // it counts (within the cap's criteria) from t0 (kind 0), or from σ < 3 (kind 1)
            let t_count = if sys.kind == 0 { sys.t0 } else { sys.t0 + 2.0 / sys.rate };
            let mut y = [1.0, 0.0, 0.0, if sys.kind == 0 { 1e-13 } else { 1.0 }, 0.0];
            let mut over = 0;
            let out = s.integrate(0.0, &mut y, 45.0, |st| {
                if st.method == crate::ode::Method::Rodas && st.t_old >= t_count && (st.t_new - st.t_old) * sys.w > 1.05 {
                    over += 1;
                }
                Control::Continue
            });
            assert!(out.status.is_completed(), "{out:?}");
            over
        };
        let mut cases: Vec<Two> = [30.39, 30.52, 30.65, 30.78, 30.91].iter().map(|&t0| Two { w: 300.0, kind: 0, rate: 0.0, t0 }).collect();
        cases.push(Two { w: 100.0, kind: 1, rate: 2.0, t0: 30.3 });
        for sys in &cases {
            let (over_far, over_5) = (run(sys, super::TEST_EVERY_FAR), run(sys, super::TEST_EVERY));
            assert!(over_far <= over_5, "t0 {} kind {}: {over_far} steps past the mode with the back-off, {over_5} without", sys.t0, sys.kind);
        }
    }

    /// The two plain loops `orthogonalize` replaces (modified Gram–Schmidt, twice, then the
    /// norm), as the check for unresolved modes ran them before.
    fn plain(v: &[f64], n: usize, k: usize, w: &mut [f64], col: &mut [f64]) -> f64 {
        for _ in 0..2 {
            for j in 0..=k {
                let vj = &v[j * n..(j + 1) * n];
                let d: f64 = vj.iter().zip(w.iter()).map(|(a, b)| a * b).sum();
                col[j] += d;
                w.iter_mut().zip(vj).for_each(|(x, a)| *x -= d * a);
            }
        }
        w.iter().map(|a| a * a).sum::<f64>().sqrt()
    }

    /// Bit for bit the plain loops (the mode cap's eigenvalues, and so every run's steps, stay
    /// the same), for every state size the dispatch unrolls and two it does not, every column,
    /// on basis rows and vectors of mixed signs and magnitudes 1e-8..1e8, with exact zeros and
    /// negative zeros among them (the sign of a zero sum is where a different start would show).
    #[test]
    fn orthogonalize_is_the_plain_loops_bit_for_bit() {
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
            match seed % 11 {
                0 => 0.0,
                1 => -0.0,
                _ => (2.0 * u - 1.0) * 10f64.powi((seed % 17) as i32 - 8),
            }
        };
        let mut cases = 0;
        for n in [3, 6, 8, 10, 12, 14] {
            for k in 0..n.min(KRYLOV) {
                for _ in 0..40 {
                    let v: Vec<f64> = (0..(k + 1) * n).map(|_| next()).collect();
                    let w0: Vec<f64> = (0..n).map(|_| next()).collect();
                    let (mut w1, mut w2) = (w0.clone(), w0.clone());
                    let (mut c1, mut c2) = ([0.0; KRYLOV], [0.0; KRYLOV]);
                    let r1 = plain(&v, n, k, &mut w1, &mut c1);
                    let r2 = match n {
                        6 => orthogonalize::<6>(&v, n, k, &mut w2, &mut c2),
                        8 => orthogonalize::<8>(&v, n, k, &mut w2, &mut c2),
                        10 => orthogonalize::<10>(&v, n, k, &mut w2, &mut c2),
                        12 => orthogonalize::<12>(&v, n, k, &mut w2, &mut c2),
                        _ => orthogonalize::<0>(&v, n, k, &mut w2, &mut c2),
                    };
                    let bits = |x: &[f64]| x.iter().map(|a| a.to_bits()).collect::<Vec<_>>();
                    assert_eq!(r1.to_bits(), r2.to_bits(), "norm, n {n} k {k}");
                    assert_eq!(bits(&w1), bits(&w2), "w, n {n} k {k}");
                    assert_eq!(bits(&c1), bits(&c2), "column, n {n} k {k}");
                    // and the generic path agrees with the unrolled one
                    let mut w3 = w0.clone();
                    let mut c3 = [0.0; KRYLOV];
                    assert_eq!(orthogonalize::<0>(&v, n, k, &mut w3, &mut c3).to_bits(), r1.to_bits());
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 40 * (3 + 6 + 8 + 10 + 12 + 12));
    }
}
