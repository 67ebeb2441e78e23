//! The stationary state: an equilibrium by Newton's method, a periodic orbit by single shooting
//! (module docs of [`crate::analysis`]).

// Index loops follow the formulas (rows, columns).
#![allow(clippy::needless_range_loop)]

use super::linear::{lu_solve, min_norm_solve};
use super::{AnalysisError, Result, VectorField};
use crate::ode::{lean, Control, Method, Options, Solver, System};
use serde::Serialize;
use std::cell::RefCell;

/// Tolerances and limits of [`stationary()`] (module docs of [`crate::analysis`] for why).
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonOptions {
    /// Scaled residual at which an equilibrium counts as found (default `1e-12`).
    pub tolerance: f64,
    /// Scaled residual `‖S⁻¹(x0 − x(T))‖∞` at which a periodic orbit counts as found (default
    /// `1e-10`).
    pub periodic_tolerance: f64,
    /// Most Newton iterations (default 50).
    pub max_iterations: usize,
    /// Relative tolerance of the integration over one period (default `1e-12`; absolute
    /// tolerances are this times [`VectorField::scales`]).
    pub rtol: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions { tolerance: 1e-12, periodic_tolerance: 1e-10, max_iterations: 50, rtol: 1e-12 }
    }
}

/// A stationary state found by [`stationary()`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StationaryState {
    /// The equilibrium, or the periodic orbit's state at `t = 0`.
    pub x: Vec<f64>,
    /// The orbit's period `T`, `None` for an equilibrium.
    pub period: Option<f64>,
    /// Newton iterations used.
    pub iterations: usize,
    /// The scaled residual reached (module docs of [`crate::analysis`]).
    pub residual: f64,
    /// Dimension of the family of stationary states through `x`
    /// ([`VectorField::structural_zeros`]).
    pub family_dimension: usize,
    /// The monodromy matrix `Φ(T)` at `x` (row-major), for a periodic orbit.
    #[serde(skip)]
    pub monodromy: Option<Vec<f64>>,
}

/// The stationary state of `f` nearest `guess`: an equilibrium `f(x) = 0` when `f` is
/// autonomous, else the periodic orbit `x(T; x0) = x0` of its period `T` (module docs of
/// [`crate::analysis`]: damped Newton with the exact Jacobian, minimum-norm steps on a family,
/// single shooting with the variational equations `Φ' = J Φ`).
pub fn stationary<F: VectorField + ?Sized>(f: &F, guess: &[f64], opts: &NewtonOptions) -> Result<StationaryState> {
    stationary_near(f, guess, None, opts)
}

/// [`stationary()`] with, for a periodic orbit, `monodromy_hint`: the monodromy matrix `Φ(T)`
/// (row-major) of a neighbouring orbit (the previous speed's in a continuation), used as the
/// shooting's starting matrix `I − Φ` in place of integrating the variational equations at the
/// guess; ignored for an equilibrium, or when of the wrong size or not finite. The result is
/// the same orbit (to the tolerance) with its own monodromy matrix.
pub fn stationary_near<F: VectorField + ?Sized>(f: &F, guess: &[f64], monodromy_hint: Option<&[f64]>, opts: &NewtonOptions) -> Result<StationaryState> {
    let hint = monodromy_hint;
    let n = f.dim();
    if guess.len() != n {
        return Err(AnalysisError::InvalidInput { field: "guess".into(), reason: format!("has {} components, the field {n}", guess.len()) });
    }
    if let Some(i) = guess.iter().position(|v| !v.is_finite()) {
        return Err(AnalysisError::InvalidInput { field: "guess".into(), reason: format!("{} is not finite", f.component_name(i)) });
    }
    let s = f.scales();
    if s.len() != n || s.iter().any(|v| !(*v > 0.0 && v.is_finite())) {
        return Err(AnalysisError::InvalidInput { field: "scales".into(), reason: "need one positive finite scale per state".into() });
    }
    let k = f.structural_zeros(guess);
    match f.period() {
        None => equilibrium(f, guess, &s, k, opts),
        Some(t) if t > 0.0 && t.is_finite() => periodic(f, guess, t, &s, k, opts, hint),
        Some(t) => {
            Err(AnalysisError::InvalidInput { field: "period".into(), reason: format!("must be positive and finite, got {}", crate::error::fmt_num(t)) })
        }
    }
}

fn non_finite<F: VectorField + ?Sized>(f: &F, v: &[f64], what: &str) -> Result<()> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(AnalysisError::NonFinite { component: f.component_name(i % f.dim()), what: what.into() }),
        None => Ok(()),
    }
}

fn norm_inf(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The Newton direction `d` of `A d = −r` in scaled variables: LU, or the minimum-norm
/// solution without the `k` smallest singular values when the states form a family (or when
/// LU meets an exactly zero pivot).
fn direction(a: &[f64], n: usize, r: &[f64], k: usize) -> Option<Vec<f64>> {
    let mut d: Vec<f64> = r.iter().map(|v| -v).collect();
    if k == 0 {
        let mut m = a.to_vec();
        if lu_solve(&mut m, n, &mut d) {
            return Some(d);
        }
        // an exactly singular matrix the model did not declare: the minimum-norm step over
        // the singular values above 1e-12 σ_max
        d = r.iter().map(|v| -v).collect();
    }
    let d = min_norm_solve(a, n, &d, k);
    d.iter().all(|v| v.is_finite()).then_some(d)
}

/// Deuflhard's restricted monotonicity test (natural level function; P. Deuflhard, *Newton
/// Methods for Nonlinear Problems*, 2004, §3.3, NLEQ-ERR): the trial point's residual `rn`
/// passes where the simplified Newton correction `d̄ = −J(x)⁻¹ rn` (the Jacobian of the current
/// iterate, not the trial's) is shorter than `(1 − λ/4)` times the step `‖d‖₂ = d0`. Unlike the
/// residual norm, this measure does not depend on how the equations' rows are scaled: where
/// some of the state is held by equations far weaker than the rest (a balancer's balls at low
/// speed: their scaled rows are ~1e-8 of the structure's), the full step's second-order
/// residual in the strong rows exceeds the weak rows' whole residual and the residual test
/// takes steps of 1/128, a crawl of hundreds of iterations (audit 20's F10: rnd/r19_00_sp.toml
/// at 5.8 rad/s took 1073 iterations), while `d̄` measures that residual as the small move in
/// the state it is.
fn natural_descent(jac: &[f64], n: usize, rn: &[f64], k: usize, lambda: f64, d0: f64) -> bool {
    direction(jac, n, rn, k).is_some_and(|dn| norm2(&dn) <= (1.0 - 0.25 * lambda) * d0)
}

/// Damped Newton on `g(x) = 0` in variables scaled by `s`: `eval(x)` returns the scaled
/// residual vector `S⁻¹ g(x) / rate` and the scaled Jacobian `S⁻¹ (∂g/∂x) S / rate`; the test
/// is `‖·‖∞ ≤ tol`; with `polish`, one more step is taken after it is met.
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn newton(
    what: &str,
    n: usize,
    x0: &[f64],
    s: &[f64],
    k: usize,
    tol: f64,
    max_iterations: usize,
    polish: bool,
    mut eval: impl FnMut(&[f64], bool) -> Result<(Vec<f64>, Option<Vec<f64>>)>,
) -> Result<(Vec<f64>, usize, f64, Option<Vec<f64>>)> {
    let fail = |iterations: usize, residual: f64, detail: &str| AnalysisError::NoConvergence {
        what: what.into(),
        iterations,
        residual,
        tolerance: tol,
        detail: detail.into(),
    };
    let mut x = x0.to_vec();
    let (mut r, mut jac) = eval(&x, true)?;
    for it in 0..max_iterations {
        let res = norm_inf(&r);
        if res <= tol {
            if polish {
                // one more full step (quadratic convergence: to round-off), kept only if it
                // cuts the residual tenfold: a step from a residual already at round-off is
                // round-off divided by the Jacobian's smallest singular value, which near a
                // bifurcation (a real eigenvalue crossing zero) is a large move along the
                // near-null direction that leaves the residual at round-off but shifts the
                // Jacobian, and with it the abscissa, by far more than its own error
                if let Some(d) = direction(jac.as_ref().expect("Jacobian requested"), n, &r, k) {
                    let xn: Vec<f64> = x.iter().zip(&d).zip(s).map(|((xi, di), si)| xi + di * si).collect();
                    if let Ok((rn, _)) = eval(&xn, false) {
                        let rn = norm_inf(&rn);
                        if rn <= 0.1 * res {
                            return Ok((xn, it + 1, rn, None));
                        }
                    }
                }
            }
            return Ok((x, it, res, jac));
        }
        let Some(d) = direction(jac.as_ref().expect("Jacobian requested"), n, &r, k) else {
            // no step, so nothing shows a residual above the tolerance to be round-off
            return Err(fail(it, res, "the Jacobian is singular (a family of states the model does not declare, or a turning point)"));
        };
        let r0 = norm2(&r);
        let d0 = norm2(&d);
        let mut lambda = 1.0;
        let mut accepted = None;
        while lambda >= 1e-10 {
            let xn: Vec<f64> = x.iter().zip(&d).zip(s).map(|((xi, di), si)| xi + lambda * di * si).collect();
            match eval(&xn, false) {
                Ok((rn, _)) if norm2(&rn) < (1.0 - 1e-4 * lambda) * r0 || natural_descent(jac.as_ref().expect("Jacobian requested"), n, &rn, k, lambda, d0) => {
                    accepted = Some(xn);
                    break;
                }
                _ => lambda *= 0.5,
            }
        }
        let Some(xn) = accepted else {
            // round-off level (no step can reduce it further) only where the root is within
            // the allowance in the state too: the exact Newton step is no longer than 1e3
            // tolerances (scaled). A residual with no root near (past a turning point) lies
            // along a direction the Jacobian barely moves, ‖d‖ ≈ res / σ_min, and the line
            // search fails there only once σ_min is down to ~√(round-off): a step ≫ res
            let step = norm_inf(&d);
            if res <= 1e3 * tol && step <= 1e3 * tol {
                return Ok((x, it, res, jac));
            }
            if res <= 1e3 * tol {
                return Err(fail(
                    it,
                    res,
                    &format!(
                        "no step along the Newton direction reduces the residual, which is no round-off: the Newton step there is {} (scaled), longer than 1e3 tolerances (no root near)",
                        crate::error::fmt_num(step)
                    ),
                ));
            }
            return Err(fail(it, res, "no step along the Newton direction reduces the residual"));
        };
        x = xn;
        (r, jac) = eval(&x, true)?;
    }
    let res = norm_inf(&r);
    if res <= tol {
        return Ok((x, max_iterations, res, jac));
    }
    Err(fail(max_iterations, res, "iteration limit"))
}

fn equilibrium<F: VectorField + ?Sized>(f: &F, guess: &[f64], s: &[f64], k: usize, opts: &NewtonOptions) -> Result<StationaryState> {
    let n = f.dim();
    let mut jac = vec![0.0; n * n];
    // the characteristic rate ‖S⁻¹ J S‖∞, from the guess's Jacobian (held fixed so that the
    // residual measure does not change between iterations)
    f.jacobian(0.0, guess, &mut jac);
    non_finite(f, &jac, "Jacobian")?;
    let rate = scaled_rate(&jac, s, n);
    // the guess's Jacobian is Newton's first too (newton evaluates at the guess first)
    let mut at_guess = Some(jac);
    let eval = |x: &[f64], with_jac: bool| -> Result<(Vec<f64>, Option<Vec<f64>>)> {
        let mut fx = vec![0.0; n];
        f.rhs(0.0, x, &mut fx);
        non_finite(f, &fx, "right-hand side")?;
        let r: Vec<f64> = fx.iter().zip(s).map(|(v, si)| v / si / rate).collect();
        if !with_jac {
            return Ok((r, None));
        }
        let mut j = match at_guess.take() {
            Some(j) if x == guess => j,
            _ => {
                let mut j = vec![0.0; n * n];
                f.jacobian(0.0, x, &mut j);
                j
            }
        };
        non_finite(f, &j, "Jacobian")?;
        for a in 0..n {
            for b in 0..n {
                j[a * n + b] *= s[b] / s[a] / rate;
            }
        }
        Ok((r, Some(j)))
    };
    let (x, iterations, residual, _) = newton("equilibrium", n, guess, s, k, opts.tolerance, opts.max_iterations, true, eval)?;
    Ok(StationaryState { family_dimension: f.structural_zeros(&x), x, period: None, iterations, residual, monodromy: None })
}

/// `‖S⁻¹ J S‖∞` (1 where it vanishes).
fn scaled_rate(jac: &[f64], s: &[f64], n: usize) -> f64 {
    let r = (0..n).map(|a| (0..n).map(|b| (jac[a * n + b] * s[b] / s[a]).abs()).sum::<f64>()).fold(0.0, f64::max);
    if r > 0.0 && r.is_finite() {
        r
    } else {
        1.0
    }
}

/// `x' = f(t, x)` with the variational equations `Φ' = J(t, x) Φ` (Φ row-major `n × m` after
/// `x` in the state): with `m = n` ([`VariationalSystem::new`]) the ODE system whose solution
/// over one period gives the monodromy matrix `Φ(T)`; with `m = 1` the tangent flow of one
/// deviation `v' = J v` (the shooting's growth check).
pub struct VariationalSystem<'a, F: VectorField + ?Sized> {
    f: &'a F,
    n: usize,
    /// The columns of `Φ`.
    m: usize,
    jac: RefCell<Vec<f64>>,
}

impl<'a, F: VectorField + ?Sized> VariationalSystem<'a, F> {
    /// The variational system of `f`.
    pub fn new(f: &'a F) -> Self {
        Self::with_columns(f, f.dim())
    }

    /// The variational equations of `m` deviations (the columns of `Φ`).
    fn with_columns(f: &'a F, m: usize) -> Self {
        let n = f.dim();
        VariationalSystem { f, n, m, jac: RefCell::new(vec![0.0; n * n]) }
    }
}

impl<F: VectorField + ?Sized> System for VariationalSystem<'_, F> {
    fn dim(&self) -> usize {
        self.n + self.n * self.m
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let (n, m) = (self.n, self.m);
        let (x, phi) = y.split_at(n);
        let (dx, dphi) = dy.split_at_mut(n);
        self.f.rhs(t, x, dx);
        let mut j = self.jac.borrow_mut();
        self.f.jacobian(t, x, &mut j);
        for a in 0..n {
            let row = &mut dphi[a * m..(a + 1) * m];
            row.iter_mut().for_each(|v| *v = 0.0);
            for c in 0..n {
                let jac = j[a * n + c];
                if jac != 0.0 {
                    for (o, p) in row.iter_mut().zip(&phi[c * m..(c + 1) * m]) {
                        *o += jac * p;
                    }
                }
            }
        }
    }

    fn component_name(&self, i: usize) -> String {
        if i < self.n {
            self.f.component_name(i)
        } else if self.m == self.n {
            let (a, b) = ((i - self.n) / self.n, (i - self.n) % self.n);
            format!("Φ[{a}][{b}] (∂{} / ∂{} at t = 0)", self.f.component_name(a), self.f.component_name(b))
        } else {
            let (a, b) = ((i - self.n) / self.m, (i - self.n) % self.m);
            format!("δ{} (deviation {b})", self.f.component_name(a))
        }
    }
}

/// The field alone as an ODE system (for trial points of the line search, which need no `Φ`).
struct Plain<'a, F: VectorField + ?Sized>(&'a F);

impl<F: VectorField + ?Sized> System for Plain<'_, F> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.0.rhs(t, y, dy)
    }
    fn component_name(&self, i: usize) -> String {
        self.0.component_name(i)
    }
}

/// Integrate `sys` from `y` at `t = 0` to `period` by DOP853 at `rtol`, absolute tolerances
/// `atol` per component ([`crate::ode::lean`]: the steps and bits of [`Solver`] under
/// `Method::Dop853`, with stage sums over contiguous vectors, which on the `n²` variational
/// states cost a third of `Solver`'s per-component sums in the dev profile).
fn integrate_period<S: System>(sys: &S, y: &mut [f64], period: f64, rtol: f64, atol: Vec<f64>) -> Result<()> {
    integrate_period_capped(sys, y, period, rtol, atol, u64::MAX).map(|_| ())
}

/// Chunks of a period over which [`growth_beyond`] measures the growth.
const GROWTH_CHUNKS: usize = 16;

/// Whether the flow over `period` from `x0` amplifies a deviation by more than `limit`: `x`
/// and one deviation `v` (scaled components of one magnitude, mixed signs) integrated by
/// DOP853 at [`MATRIX_RTOL`] over [`GROWTH_CHUNKS`] chunks of the period, stopped at the end of
/// the first chunk where `‖S⁻¹ v(t)‖∞` exceeds `limit` (that growth and the time `t` reached);
/// `None` where it stays within `limit` over the period or an integration fails. What it
/// measures is the flow linearised along the trajectory from `x0`, not along the orbit:
/// `v(t) = Φ(t; x0) v(0)`, `‖S⁻¹ v(0)‖∞ = 1`, so `‖S⁻¹ v(t)‖∞ ≤ ‖S⁻¹ Φ(t; x0) S‖∞`, a lower
/// bound on that trajectory's growth over `[0, t]`; it is the orbit's only where `x0` lies on
/// the orbit (a start far off it, on a nonlinear model, can grow where the orbit does not).
/// It stops while the deviation is still small, where the plain flow from a start off the
/// orbit runs on until the deviation is enormous (and its steps with it).
fn growth_beyond<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], limit: f64) -> Option<(f64, f64)> {
    let n = f.dim();
    let sys = VariationalSystem::with_columns(f, 1);
    let mut y = x0.to_vec();
    y.extend((0..n).map(|i| if i % 2 == 0 { s[i] } else { -0.7 * s[i] }));
    let mut atol: Vec<f64> = s.iter().map(|v| MATRIX_RTOL * v).collect();
    atol.extend_from_slice(&atol.clone());
    let mut work = lean::Lean::new(2 * n);
    for c in 1..=GROWTH_CHUNKS {
        let (t0, t1) = (period * (c - 1) as f64 / GROWTH_CHUNKS as f64, period * c as f64 / GROWTH_CHUNKS as f64);
        let out = lean::integrate(&sys, &mut work, t0, &mut y, t1, MATRIX_RTOL, &atol);
        if !out.status.is_completed() {
            return None;
        }
        let growth = (0..n).map(|i| (y[n + i] / s[i]).abs()).fold(0.0, f64::max);
        if growth > limit {
            return Some((growth, t1));
        }
    }
    None
}

/// Attempted steps of a shooting's first flow (from its start, [`periodic`]) after which it is
/// asked whether the growth over the period is beyond the shooting ([`growth_beyond`]); where it
/// is not, the flow goes on to its end. Periodic orbits at 1e-10 take hundreds to a few
/// thousand steps a period (408 on tests/indefinite_stiffness_33.rs at 5.97 rad/s); a flow
/// from a start off an orbit that grows by `e^{ΛT}` runs on while its deviation grows and the
/// motion with it (more than a million steps there from a start carried from 20 rad/s).
const FIRST_FLOW_STEPS: u64 = 20_000;

/// [`integrate_period`] with at most `max_steps` attempted steps ([`lean::integrate_capped`]);
/// the steps it attempted (accepted and rejected).
fn integrate_period_capped<S: System>(sys: &S, y: &mut [f64], period: f64, rtol: f64, atol: Vec<f64>, max_steps: u64) -> Result<Option<u64>> {
    // the options' own checks (positive finite tolerances), as Solver::new makes them
    Options::new(rtol, rtol).method(Method::Dop853).atol_per_component(atol.clone()).validate()?;
    let out = lean::integrate_capped(sys, &mut lean::Lean::new(y.len()), 0.0, y, period, rtol, &atol, max_steps);
    if out.status == crate::ode::Status::Stopped(crate::control::StopReason::TooManySteps { max_steps }) {
        return Ok(None);
    }
    if !out.status.is_completed() {
        return Err(AnalysisError::Integration { period, reason: out.to_string() });
    }
    Ok(Some(out.stats.steps + out.stats.rejected))
}

/// Most equispaced samples per period of the interpolated Jacobian ([`monodromy`]) before the
/// full variational equations are integrated instead (a power of two: the coarser sets are its
/// subsets).
const MAX_NODES: usize = 64;

/// The fewest samples tried (the interpolant on half of them is checked at the other half).
const FIRST_NODES: usize = 8;

/// A period's orbit `x(t)` from `x(0) = x0`: its end `x(T)`, and its samples at the
/// [`MAX_NODES`] equispaced times `t_j = j T / MAX_NODES`, `j = 0 .. MAX_NODES − 1` (row-major,
/// `j = 0` is `x0`), from DOP853's dense output.
struct Orbit {
    end: Vec<f64>,
    samples: Vec<f64>,
}

/// `x(T; x0)` by DOP853 at `1e-2 · rtol` (absolute tolerances that times `S`), sampled at the
/// nodes of [`Orbit`] by the step's 7th-order dense output (three more right-hand sides per
/// step). 100x tighter than the shooting's flows: the sampled Jacobians' own error (through
/// `x`'s) then stays below the interpolation test's threshold. (Sampled at `rtol`, the test
/// stalls at ~2e-10 of `‖S⁻¹JS‖∞` on the two-plane example at `rtol = 1e-10`, the samples'
/// noise, where it must reach 1e-10.)
fn orbit<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64) -> Result<Orbit> {
    let n = f.dim();
    let mut samples = vec![0.0; MAX_NODES * n];
    samples[..n].copy_from_slice(x0);
    let plain = Plain(f);
    let tight = 1e-2 * rtol;
    let opts = Options::new(tight, tight).method(Method::Dop853).atol_per_component(s.iter().map(|v| tight * v).collect());
    let mut solver = Solver::new(&plain, opts)?;
    let mut y = x0.to_vec();
    let mut next = 1;
    let node = |j: usize| period * j as f64 / MAX_NODES as f64;
    let out = solver.integrate(0.0, &mut y, period, |step| {
        while next < MAX_NODES && node(next) <= step.t_new {
            step.interpolate(node(next), &mut samples[next * n..(next + 1) * n]);
            next += 1;
        }
        Control::Continue
    });
    if !out.status.is_completed() || next < MAX_NODES {
        return Err(AnalysisError::Integration { period, reason: out.to_string() });
    }
    Ok(Orbit { end: y, samples })
}

/// The periodic orbit through `x0` (period `period`) at 64 equispaced times
/// `t_j = j T / 64` over one period, row-major (`j = 0` is `x0`): DOP853 at `1e-2 · rtol` with
/// the field's scales, sampled by its dense output (the samples [`stationary`]'s Floquet
/// route uses). For averages over a revolution: the trapezoidal rule on these samples is
/// exact for the orbit's harmonics below the 64th (spectral accuracy for an analytic orbit).
pub fn orbit_samples<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, rtol: f64) -> Result<Vec<f64>> {
    Ok(orbit(f, x0, period, &f.scales(), rtol)?.samples)
}

/// The trigonometric interpolant of a periodic matrix function `J(t)` (period `T`) from its
/// values at `N` equispaced times `t_j = j T / N` (`N` even):
/// `J̃(t) = A_0 + Σ_{k=1}^{N/2} (A_k cos kθ + B_k sin kθ)`, `θ = 2π t / T`, with
/// `A_0 = Σ_j J_j / N`, `A_k = 2 Σ_j J_j cos kθ_j / N`, `B_k = 2 Σ_j J_j sin kθ_j / N` (`k < N/2`)
/// and `A_{N/2} = Σ_j (−1)^j J_j / N`, `B_{N/2} = 0` (the discrete Fourier transform; `J̃(t_j) =
/// J_j`). For a function analytic on the real line its error falls geometrically in `N` at the
/// rate of the Fourier coefficients' decay (Trefethen, *Spectral Methods in MATLAB*, ch. 4),
/// where a Chebyshev interpolant, which ignores the periodicity, needs ~π/2 times the samples.
/// Entries equal at every sample (the kinematic rows `(0, I)`, structural zeros) are kept as
/// constants; only the others are transformed and evaluated, each with its own harmonics: the
/// terms `A_k[e] cos kθ + B_k[e] sin kθ` are kept entry by entry ([`TrigInterpolant::truncate`]
/// drops the smallest of each row within a budget), so an entry that varies with `2θ` alone
/// (a support's stiffness) costs one term, not `N/2`.
struct TrigInterpolant {
    n: usize,
    /// `2π / T`.
    frequency: f64,
    /// `J` with its constant entries, row-major.
    constant: Vec<f64>,
    /// The indices of the entries that vary between samples.
    varying: Vec<usize>,
    /// `A_0` over `varying`.
    mean: Vec<f64>,
    /// For `k = 1 ..= K` (`K` the highest harmonic kept), the terms kept: `(slot in varying,
    /// A_k, B_k)`.
    harmonics: Vec<Vec<(usize, f64, f64)>>,
    /// `harmonics` as [`TrigInterpolant::eval`] reads them ([`Packed`]), one per harmonic.
    packed: Vec<Packed>,
}

/// One harmonic's terms laid out for [`TrigInterpolant::eval`]: `Dense` where at least
/// [`DENSE_SHARE`] of the varying entries have a term (`A_k`, `B_k` over every slot, zero
/// where the term was dropped: a loop the compiler vectorises, two slots a pass, ~4
/// instructions a slot in the release build), else `Sparse` (the terms alone, one scattered
/// update each, ~12 instructions). The dense zeros add `c · 0 + s · 0 = ±0` to a sum, which
/// leaves it unchanged (bar the sign of a zero sum): the same `J̃` bit for bit.
enum Packed {
    Dense { a: Vec<f64>, b: Vec<f64> },
    Sparse(Vec<(usize, f64, f64)>),
}

/// The share of the varying entries with a term from which a harmonic is evaluated dense
/// ([`Packed`]). On the two-plane scan (`bench_floquet two-plane`, release build) 1/2 took the
/// fewest instructions; 1/4 0.4 M more, 1/3 0.9 M, all dense 14.8 M, all sparse 16.1 M, of
/// ~314 M (docs/notes/benchmarks.md, round 3, session 19).
const DENSE_SHARE: f64 = 0.5;

impl TrigInterpolant {
    /// From `values[j] = J(j T / N)`, `N = values.len()` even.
    fn new(n: usize, period: f64, values: &[&[f64]]) -> Self {
        let m = values.len();
        let first = values[0];
        let varying: Vec<usize> = (0..n * n).filter(|&e| values.iter().any(|j| j[e] != first[e])).collect();
        let (cos, sin): (Vec<f64>, Vec<f64>) = (0..m).map(|p| (std::f64::consts::TAU * p as f64 / m as f64).sin_cos()).map(|(s, c)| (c, s)).unzip();
        let half = m / 2;
        // the varying entries of each sample, contiguous (row j: sample j)
        let nv = varying.len();
        let gathered: Vec<f64> = values.iter().flat_map(|v| varying.iter().map(|&e| v[e])).collect();
        let mut coefficients: Vec<(Vec<f64>, Vec<f64>)> = (0..=half)
            .map(|k| {
                let mut a = vec![0.0; nv];
                let mut b = vec![0.0; nv];
                // sin 0 and sin(N/2 θ_j) vanish at the samples: B_0 = B_{N/2} = 0
                let odd = k != 0 && k != half;
                for (j, v) in gathered.chunks_exact(nv.max(1)).enumerate() {
                    let w = if odd { 2.0 } else { 1.0 } / m as f64;
                    let (c, s) = (w * cos[(k * j) % m], w * sin[(k * j) % m]);
                    for (ae, x) in a.iter_mut().zip(v) {
                        *ae += c * x;
                    }
                    if odd {
                        for (be, x) in b.iter_mut().zip(v) {
                            *be += s * x;
                        }
                    }
                }
                (a, b)
            })
            .collect();
        let mean = std::mem::take(&mut coefficients[0].0);
        let harmonics =
            coefficients[1..].iter().map(|(a, b)| (0..varying.len()).filter(|&v| a[v] != 0.0 || b[v] != 0.0).map(|v| (v, a[v], b[v])).collect()).collect();
        let mut interp = TrigInterpolant { n, frequency: std::f64::consts::TAU / period, constant: first.to_vec(), varying, mean, harmonics, packed: vec![] };
        interp.pack();
        interp
    }

    /// Lay `harmonics` out for [`TrigInterpolant::eval`] ([`Packed`]).
    fn pack(&mut self) {
        let nv = self.varying.len();
        self.packed = self
            .harmonics
            .iter()
            .map(|h| {
                if h.len() as f64 >= DENSE_SHARE * nv as f64 {
                    let (mut a, mut b) = (vec![0.0; nv], vec![0.0; nv]);
                    for &(v, av, bv) in h {
                        a[v] = av;
                        b[v] = bv;
                    }
                    Packed::Dense { a, b }
                } else {
                    Packed::Sparse(h.clone())
                }
            })
            .collect();
    }

    /// The highest harmonic kept, `K`.
    #[cfg(test)]
    fn degree(&self) -> usize {
        self.harmonics.len()
    }

    /// The terms kept (over every entry and harmonic `k ≥ 1`).
    #[cfg(test)]
    fn terms(&self) -> usize {
        self.harmonics.iter().map(Vec::len).sum()
    }

    /// Drop, row by row, the smallest terms `A_k[e] cos kθ + B_k[e] sin kθ` (`k ≥ 1`) while the
    /// sum of their scaled sizes `Σ (|A_k[e]| + |B_k[e]|) s_b / s_a` (entry `e = (a, b)`) stays
    /// within `budget`: a bound on the change of `J̃` at every `t` in the scaled max-row-sum
    /// norm `‖S⁻¹ · S‖∞`. An entry left with no term becomes a constant (its mean `A_0`).
    fn truncate(&mut self, s: &[f64], budget: f64) {
        let n = self.n;
        // (row, scaled size, k, slot) of every term, in the order row, size, then (k, slot) (the
        // order of a stable sort on (row, size) of the terms listed by k and slot), sorted as
        // one integer key: row above the size's bits (a non-negative float's bits order as its
        // value) above k and slot
        let mut keys: Vec<u128> = vec![];
        let nv = self.varying.len() as u128;
        for (k, h) in self.harmonics.iter().enumerate() {
            for &(v, a, b) in h {
                let e = self.varying[v];
                let size = (a.abs() + b.abs()) * s[e % n] / s[e / n];
                if size > budget {
                    continue; // never dropped (nor counted): not sorted
                }
                keys.push((((e / n) as u128) << 96) | ((size.to_bits() as u128) << 32) | (k as u128 * nv + v as u128));
            }
        }
        keys.sort_unstable();
        let all: Vec<(usize, f64, usize, usize)> = keys
            .iter()
            .map(|&key| {
                let (row, size, kv) = ((key >> 96) as usize, f64::from_bits((key >> 32) as u64), (key & 0xffff_ffff) as usize);
                (row, size, kv / self.varying.len(), kv % self.varying.len())
            })
            .collect();
        let mut dropped = vec![vec![false; self.varying.len()]; self.harmonics.len()];
        let mut i = 0;
        while i < all.len() {
            let row = all[i].0;
            let mut sum = 0.0;
            while i < all.len() && all[i].0 == row {
                if sum + all[i].1 <= budget {
                    sum += all[i].1;
                    dropped[all[i].2][all[i].3] = true;
                }
                i += 1;
            }
        }
        for (h, d) in self.harmonics.iter_mut().zip(&dropped) {
            h.retain(|&(v, _, _)| !d[v]);
        }
        while self.harmonics.last().is_some_and(Vec::is_empty) {
            self.harmonics.pop();
        }
        // entries with no term left: constants
        let mut live = vec![false; self.varying.len()];
        self.harmonics.iter().flatten().for_each(|&(v, _, _)| live[v] = true);
        let mut slot = vec![usize::MAX; self.varying.len()];
        let (mut varying, mut mean) = (vec![], vec![]);
        for v in 0..self.varying.len() {
            if live[v] {
                slot[v] = varying.len();
                varying.push(self.varying[v]);
                mean.push(self.mean[v]);
            } else {
                self.constant[self.varying[v]] = self.mean[v];
            }
        }
        for h in &mut self.harmonics {
            h.iter_mut().for_each(|t| t.0 = slot[t.0]);
        }
        self.varying = varying;
        self.mean = mean;
        self.pack();
    }

    /// `J̃(t)` into `out` (`cos kθ`, `sin kθ` by the three-term recurrence from `k = 1`; the
    /// varying entries summed in `acc`, contiguous, harmonic by harmonic in increasing `k`
    /// ([`Packed`]), then scattered).
    fn eval(&self, t: f64, out: &mut [f64], acc: &mut Vec<f64>) {
        out.copy_from_slice(&self.constant);
        if self.varying.is_empty() {
            return;
        }
        let (s1, c1) = (self.frequency * t).sin_cos();
        acc.clear();
        acc.extend_from_slice(&self.mean);
        let (mut c_prev, mut s_prev, mut c, mut s) = (1.0, 0.0, c1, s1);
        for h in &self.packed {
            match h {
                Packed::Dense { a, b } => {
                    for ((o, a), b) in acc.iter_mut().zip(a).zip(b) {
                        *o += c * a + s * b;
                    }
                }
                Packed::Sparse(terms) => {
                    for &(v, a, b) in terms {
                        acc[v] += c * a + s * b;
                    }
                }
            }
            let (cn, sn) = (2.0 * c1 * c - c_prev, 2.0 * c1 * s - s_prev);
            (c_prev, s_prev, c, s) = (c, s, cn, sn);
        }
        for (&e, v) in self.varying.iter().zip(acc.iter()) {
            out[e] = *v;
        }
    }
}

/// Columns of `Φ` summed together in [`pair_rows`] (four SSE2 registers a row).
const BLOCK: usize = 8;

/// Rows `a`, `a + 1` of `J̃ Φ` (`jac`: those two rows of `J̃`, `n` each) over the columns
/// `cols` of `J̃` (increasing), into `first` and `second`: each entry `Σ_c J̃[a][c] Φ[c][b]`
/// term by term in increasing `c` (the same sums as the row-by-row loop, whose skipped zeros
/// add an exact zero here), `BLOCK` columns of `Φ` at a time for both rows, so each block of a
/// row of `Φ` is loaded once for two rows and the sums stay in registers.
fn pair_rows(jac: &[f64], phi: &[f64], n: usize, cols: &[usize], first: &mut [f64], second: &mut [f64]) {
    let (j1, j2) = jac.split_at(n);
    let blocks = n / BLOCK;
    for q in 0..blocks {
        let (mut s1, mut s2) = ([0.0f64; BLOCK], [0.0f64; BLOCK]);
        for &c in cols {
            let (u, v) = (j1[c], j2[c]);
            let p: &[f64; BLOCK] = phi[c * n + q * BLOCK..c * n + (q + 1) * BLOCK].try_into().expect("a block");
            for i in 0..BLOCK {
                s1[i] += u * p[i];
                s2[i] += v * p[i];
            }
        }
        first[q * BLOCK..(q + 1) * BLOCK].copy_from_slice(&s1);
        second[q * BLOCK..(q + 1) * BLOCK].copy_from_slice(&s2);
    }
    for b in blocks * BLOCK..n {
        let (mut s1, mut s2) = (0.0, 0.0);
        for &c in cols {
            s1 += j1[c] * phi[c * n + b];
            s2 += j2[c] * phi[c * n + b];
        }
        first[b] = s1;
        second[b] = s2;
    }
}

/// `Φ' = J̃(t) Φ`: the variational equations with the Jacobian along the orbit replaced by its
/// trigonometric interpolant ([`TrigInterpolant`]).
struct InterpolatedVariational {
    n: usize,
    interpolant: TrigInterpolant,
    /// How each row of `J̃ Φ` is formed ([`Row`]).
    rows: Vec<Row>,
    jac: RefCell<Vec<f64>>,
    /// The time `jac` holds `J̃` at (DOP853's last stage and the next step's first are at the
    /// same `t`: `J̃` is evaluated once for both).
    jac_time: std::cell::Cell<f64>,
    acc: RefCell<Vec<f64>>,
}

/// A row `a` of `J̃ Φ`: `Copy(c)` where row `a` of `J̃` is the constant unit row `e_c` (a
/// kinematic row `ẋ_a = x_c`: row `c` of `Φ`, exactly what the sum gives), else `Sum` over the
/// columns where `J̃` can be non-zero (its constant non-zero entries and those that vary), in
/// increasing order as the full sum, so the same numbers without the `n²` tests of zero; two
/// consecutive `Sum` rows over the same columns are one `Pair` ([`pair_rows`]).
enum Row {
    Copy(usize),
    Sum(Vec<usize>),
    /// Rows `a` and `a + 1`, both a `Sum` over these columns, formed together.
    Pair(Vec<usize>),
    /// The second row of the `Pair` before it.
    Paired,
}

impl InterpolatedVariational {
    fn new(n: usize, interpolant: TrigInterpolant) -> Self {
        let mut live = interpolant.constant.iter().map(|v| *v != 0.0).collect::<Vec<bool>>();
        interpolant.varying.iter().for_each(|&e| live[e] = true);
        let mut rows: Vec<Row> = (0..n)
            .map(|a| {
                let cols: Vec<usize> = (0..n).filter(|&c| live[a * n + c]).collect();
                match cols.as_slice() {
                    [c] if interpolant.constant[a * n + c] == 1.0 && !interpolant.varying.contains(&(a * n + c)) => Row::Copy(*c),
                    _ => Row::Sum(cols),
                }
            })
            .collect();
        // consecutive rows over the same columns formed two at a time (a mechanical model's
        // acceleration rows: all of them)
        let mut a = 0;
        while a + 1 < n {
            if matches!((&rows[a], &rows[a + 1]), (Row::Sum(p), Row::Sum(q)) if p == q) {
                if let Row::Sum(cols) = std::mem::replace(&mut rows[a + 1], Row::Paired) {
                    rows[a] = Row::Pair(cols);
                }
                a += 2;
            } else {
                a += 1;
            }
        }
        InterpolatedVariational {
            n,
            interpolant,
            rows,
            jac: RefCell::new(vec![0.0; n * n]),
            jac_time: std::cell::Cell::new(f64::NAN),
            acc: RefCell::new(vec![]),
        }
    }
}

impl System for InterpolatedVariational {
    fn dim(&self) -> usize {
        self.n * self.n
    }
    fn rhs(&self, t: f64, phi: &[f64], dphi: &mut [f64]) {
        let n = self.n;
        let mut j = self.jac.borrow_mut();
        if t != self.jac_time.get() {
            self.interpolant.eval(t, &mut j, &mut self.acc.borrow_mut());
            self.jac_time.set(t);
        }
        for (a, r) in self.rows.iter().enumerate() {
            if let Row::Pair(cols) = r {
                let (first, second) = dphi[a * n..(a + 2) * n].split_at_mut(n);
                pair_rows(&j[a * n..(a + 2) * n], phi, n, cols, first, second);
                continue;
            }
            let row = &mut dphi[a * n..(a + 1) * n];
            match r {
                Row::Pair(_) | Row::Paired => {}
                Row::Copy(c) => row.copy_from_slice(&phi[c * n..(c + 1) * n]),
                Row::Sum(cols) => {
                    row.iter_mut().for_each(|v| *v = 0.0);
                    for &c in cols {
                        let jac = j[a * n + c];
                        if jac != 0.0 {
                            for (o, p) in row.iter_mut().zip(&phi[c * n..(c + 1) * n]) {
                                *o += jac * p;
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The monodromy matrix `Φ(T)` of the orbit `x` (its samples from [`orbit`]) with the Jacobian
/// evaluated only at equispaced times and interpolated between them (module docs of
/// [`crate::analysis`], "Floquet"): `J(t_j, x(t_j))` by the model's automatic differentiation,
/// the trigonometric interpolant of the `N` samples ([`TrigInterpolant`]; `J(t, x(t))` is
/// periodic with the orbit), `N` doubled from [`FIRST_NODES`] (reusing the samples) until the
/// interpolant on `N/2` of them, evaluated at the `N/2` others, is within `rtol ‖S⁻¹ J S‖∞`
/// (plus twice the periodicity defect `‖S⁻¹(J(T, x(T)) − J(0, x(0)))S‖∞`, the jump that the
/// shooting's residual leaves) of the Jacobian there in the scaled max-row-sum norm (the interpolant on `N` is then closer
/// still: the error falls geometrically in `N`); its harmonics above what `0.1 rtol ‖S⁻¹ J S‖∞`
/// bounds are dropped; then `Φ' = J̃(t) Φ`, `Φ(0) = I`, by DOP853 at `rtol` (absolute tolerances
/// `rtol s_a / s_b`). `None` when [`MAX_NODES`] samples do not pass the check.
fn interpolated_monodromy<F: VectorField + ?Sized>(f: &F, orbit: &Orbit, period: f64, s: &[f64], rtol: f64) -> Result<Option<Vec<f64>>> {
    let n = f.dim();
    let Some(interpolant) = jacobian_interpolant(f, orbit, period, s, rtol)? else { return Ok(None) };
    let sys = InterpolatedVariational::new(n, interpolant);
    let mut atol = Vec::with_capacity(n * n);
    for a in 0..n {
        for b in 0..n {
            atol.push(rtol * s[a] / s[b]);
        }
    }
    let mut phi = vec![0.0; n * n];
    for a in 0..n {
        phi[a * n + a] = 1.0;
    }
    integrate_period(&sys, &mut phi, period, rtol, atol)?;
    Ok(Some(phi))
}

/// The interpolant `J̃` of [`interpolated_monodromy`] (its samples, test and truncation), `None`
/// when [`MAX_NODES`] samples do not pass the test.
fn jacobian_interpolant<F: VectorField + ?Sized>(f: &F, orbit: &Orbit, period: f64, s: &[f64], rtol: f64) -> Result<Option<TrigInterpolant>> {
    let n = f.dim();
    let scaled_norm = |m: &[f64]| (0..n).map(|a| (0..n).map(|b| (m[a * n + b] * s[b] / s[a]).abs()).sum::<f64>()).fold(0.0, f64::max);
    let mut jacobians: Vec<Option<Vec<f64>>> = vec![None; MAX_NODES];
    let node = |j: usize| period * j as f64 / MAX_NODES as f64;
    let fill = |jacobians: &mut [Option<Vec<f64>>], stride: usize| -> Result<()> {
        for k in (0..MAX_NODES).step_by(stride) {
            if jacobians[k].is_none() {
                let mut j = vec![0.0; n * n];
                f.jacobian(node(k), &orbit.samples[k * n..(k + 1) * n], &mut j);
                non_finite(f, &j, "Jacobian")?;
                jacobians[k] = Some(j);
            }
        }
        Ok(())
    };
    let at = |jacobians: &[Option<Vec<f64>>], stride: usize| -> Vec<Vec<f64>> {
        (0..MAX_NODES).step_by(stride).map(|k| jacobians[k].clone().expect("filled")).collect()
    };
    // the periodicity defect of the sampled J: x(T) differs from x(0) by the shooting's
    // residual, so J(t, x(t)) has a jump of this size at t = T, which no periodic interpolant
    // resolves (its error near the jump is of the jump's order) and which bounds how well J
    // along the computed orbit is known anyway: the test allows twice it
    let defect = {
        let mut jt = vec![0.0; n * n];
        f.jacobian(period, &orbit.end, &mut jt);
        non_finite(f, &jt, "Jacobian")?;
        fill(&mut jacobians, MAX_NODES)?;
        jt.iter_mut().zip(jacobians[0].as_ref().expect("filled")).for_each(|(a, b)| *a -= b);
        scaled_norm(&jt)
    };
    let mut nodes = FIRST_NODES;
    let accepted = loop {
        let stride = MAX_NODES / nodes;
        fill(&mut jacobians, stride)?;
        let fine = at(&jacobians, stride);
        let coarse: Vec<&[f64]> = fine.iter().step_by(2).map(|v| v.as_slice()).collect();
        let interp = TrigInterpolant::new(n, period, &coarse);
        let size = fine.iter().map(|j| scaled_norm(j)).fold(0.0, f64::max);
        let mut worst: f64 = 0.0;
        let mut tmp = vec![0.0; n * n];
        let mut acc = vec![];
        for (j, jf) in fine.iter().enumerate().skip(1).step_by(2) {
            interp.eval(node(j * stride), &mut tmp, &mut acc);
            tmp.iter_mut().zip(jf).for_each(|(a, b)| *a -= b);
            worst = worst.max(scaled_norm(&tmp));
        }
        if worst <= rtol * size + 2.0 * defect {
            let values: Vec<&[f64]> = fine.iter().map(|v| v.as_slice()).collect();
            let mut interp = TrigInterpolant::new(n, period, &values);
            interp.truncate(s, 0.1 * rtol * size);
            break Some(interp);
        }
        if nodes >= MAX_NODES {
            break None;
        }
        nodes *= 2;
    };
    Ok(accepted)
}

/// The monodromy matrix `Φ(T)` of the orbit from `x0` (its [`orbit`]): with the interpolated
/// Jacobian where that converges ([`interpolated_monodromy`]), else by the full variational
/// equations `n + n²` from `x0`.
fn monodromy<F: VectorField + ?Sized>(f: &F, x0: &[f64], orbit: &Orbit, period: f64, s: &[f64], rtol: f64) -> Result<Vec<f64>> {
    if let Some(phi) = interpolated_monodromy(f, orbit, period, s, rtol)? {
        return Ok(phi);
    }
    let n = f.dim();
    let sys = VariationalSystem::new(f);
    let mut atol: Vec<f64> = s.iter().map(|v| rtol * v).collect();
    for a in 0..n {
        for b in 0..n {
            atol.push(rtol * s[a] / s[b]);
        }
    }
    let mut y = vec![0.0; n + n * n];
    y[..n].copy_from_slice(x0);
    for a in 0..n {
        y[n + a * n + a] = 1.0;
    }
    integrate_period(&sys, &mut y, period, rtol, atol)?;
    Ok(y.split_off(n))
}

/// `x(T; x0)` by DOP853 at `rtol` (absolute tolerances `rtol · S`): a shooting trial.
fn flow<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64) -> Result<Vec<f64>> {
    let mut y = x0.to_vec();
    integrate_period(&Plain(f), &mut y, period, rtol, s.iter().map(|v| rtol * v).collect())?;
    Ok(y)
}

/// [`flow`] with at most `max_steps` attempted steps, and the steps it attempted; `None` where
/// it needed more.
fn flow_capped<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64, max_steps: u64) -> Result<Option<(Vec<f64>, u64)>> {
    let mut y = x0.to_vec();
    let steps = integrate_period_capped(&Plain(f), &mut y, period, rtol, s.iter().map(|v| rtol * v).collect(), max_steps)?;
    Ok(steps.map(|k| (y, k)))
}

/// The most steps a line search's trial flow of [`periodic`] may take: this many times those of
/// the flow from the current point (at least [`TRIAL_STEPS_FLOOR`]). A trial point whose flow
/// needs far more steps than the current point's lies where the motion is far faster, outside
/// the neighbourhood where the shooting's linear model holds; it counts as a failed trial (the
/// step is halved), as a trial whose integration fails, so the cap can only shorten a step,
/// never accept one. Without it a statically unstable rotor (`K` indefinite,
/// tests/indefinite_stiffness_33.rs) took 1.18 million steps (20 s in debug) on one trial flow
/// at 5.97 rad/s, against 408 from the current point: the rotor's deviation grew by ~e^51 over
/// the period and drove the balls round ever faster.
const TRIAL_STEPS_FACTOR: u64 = 20;

/// The least step cap of a trial flow ([`TRIAL_STEPS_FACTOR`]).
const TRIAL_STEPS_FLOOR: u64 = 2000;

/// `x(T; x0)` and `Φ(T)` (module docs of [`crate::analysis`]): the [`orbit`], then its
/// [`monodromy`].
fn variational_flow<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64) -> Result<(Orbit, Vec<f64>)> {
    let o = orbit(f, x0, period, s, rtol)?;
    let phi = monodromy(f, x0, &o, period, s, rtol)?;
    Ok((o, phi))
}

/// `S⁻¹ (I − Φ) S`: the shooting residual's Jacobian in scaled variables.
fn shooting_matrix(phi: &[f64], s: &[f64], n: usize) -> Vec<f64> {
    (0..n * n).map(|ab| (if ab / n == ab % n { 1.0 } else { 0.0 }) - phi[ab] * s[ab % n] / s[ab / n]).collect()
}

/// Relative tolerance of the monodromy matrices that serve only as the shooting's matrix
/// `S⁻¹ (I − Φ) S` away from the orbit ([`periodic`]): an error of `1e-6` in the matrix makes
/// each quasi-Newton step cut the residual by ~`1e-6` (times the matrix's condition) instead of
/// to round-off, which the next flow absorbs; the orbit's own monodromy matrix, which the
/// multipliers come from, is integrated at the shooting's `rtol`. At `1e-6` DOP853 takes
/// ~`(1e-6 / 1e-10)^{1/8}` ≈ 3x fewer steps than at `1e-10` and 8 Jacobian samples pass
/// where 16 were needed. (At `1e-4`, 6 % fewer instructions on the two-plane scan, the
/// shooting stagnated at 150 rad/s on that rotor, where `I − Φ` has a singular value ~3.5e-4:
/// the matrix's error must stay well below it.)
const MATRIX_RTOL: f64 = 1e-6;

/// `Φ(T)` at `x0` for the shooting's matrix alone: [`variational_flow`] at
/// `max(rtol, MATRIX_RTOL)` ([`MATRIX_RTOL`]).
fn matrix_monodromy<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64) -> Result<Vec<f64>> {
    variational_flow(f, x0, period, s, rtol.max(MATRIX_RTOL)).map(|(_, phi)| phi)
}

/// The periodic orbit by single shooting (module docs of [`crate::analysis`]): quasi-Newton
/// (Broyden) iterations on `r(x0) = S⁻¹ (x0 − x(T; x0))` whose trial points need only the
/// flow `x(T; x0)` at `rtol`, the matrix `S⁻¹ (I − Φ) S` taken from `hint` (a neighbouring
/// orbit's monodromy matrix) or else from the variational equations at the start, and updated
/// by rank one after each step; the variational equations are integrated again only where the
/// updated matrix gives no descent or a step fails to halve the residual (then the iteration is
/// Newton's; at most `max_iterations / 2` times, then the search is reported as stagnating).
/// Those matrices only steer the iteration and are integrated at [`MATRIX_RTOL`]; the
/// monodromy matrix of the orbit found, whose multipliers are its stability, at `rtol`, once.
/// What a failed shooting adds to its message when its last matrix `S⁻¹(I − Φ)S` (`n × n`,
/// the variational equations' or its rank-one updates) has an eigenvalue `1 − μ` within
/// `1e-2` of zero: a Floquet multiplier near 1 makes `I − Φ` nearly singular, as at a fold of
/// periodic orbits, where the orbit ceases to exist as a parameter moves (or a family the model
/// does not declare); else nothing.
fn near_unit_multiplier(b: &[f64], n: usize) -> String {
    if b.len() != n * n {
        return String::new();
    }
    let Ok(values) = crate::linalg::eigen_dyn::eigenvalues(b, n) else { return String::new() };
    let d = values.iter().map(|z| z.norm()).fold(f64::INFINITY, f64::min);
    if d <= 1e-2 {
        format!(
            "; a Floquet multiplier lies within {} of 1 there (I − Φ nearly singular): near a fold, where the periodic orbit ceases to exist, or with no orbit near the start; following the orbit in a parameter from where one is found tells which",
            crate::error::fmt_num(d)
        )
    } else {
        String::new()
    }
}

/// `‖S⁻¹ Φ S‖∞`: how much the flow over a period amplifies a deviation, in scaled variables.
fn scaled_growth(phi: &[f64], s: &[f64], n: usize) -> f64 {
    (0..n).map(|a| (0..n).map(|c| (phi[a * n + c] * s[c] / s[a]).abs()).sum::<f64>()).fold(0.0, f64::max)
}

/// [`AnalysisError::Unresolvable`] where the monodromy matrix `phi` (integrated at the
/// shooting's point) amplifies a deviation by more than `1/rtol` (module docs of
/// [`crate::analysis`]), else `phi`'s shooting matrix.
fn resolvable_matrix(phi: &[f64], s: &[f64], n: usize, period: f64, rtol: f64) -> Result<Vec<f64>> {
    let (growth, limit) = (scaled_growth(phi, s, n), 1.0 / rtol);
    if growth > limit || !growth.is_finite() {
        return Err(AnalysisError::Unresolvable { period, growth, within: period, limit });
    }
    Ok(shooting_matrix(phi, s, n))
}

fn periodic<F: VectorField + ?Sized>(
    f: &F,
    guess: &[f64],
    period: f64,
    s: &[f64],
    k: usize,
    opts: &NewtonOptions,
    hint: Option<&[f64]>,
) -> Result<StationaryState> {
    let n = f.dim();
    let tol = opts.periodic_tolerance;
    let residual = |x0: &[f64], xt: &[f64]| -> Vec<f64> { (0..n).map(|i| (x0[i] - xt[i]) / s[i]).collect() };
    let fail = |iterations: usize, residual: f64, detail: &str| AnalysisError::NoConvergence {
        what: "periodic orbit".into(),
        iterations,
        residual,
        tolerance: tol,
        detail: detail.into(),
    };
    let mut x = guess.to_vec();
    // the residual at x (from a flow at rtol) and the matrix; `fresh`: the matrix was
    // integrated at x (not carried from a neighbour or updated since)
    // the first flow, from the start: past FIRST_FLOW_STEPS, asked whether the growth over the
    // period is beyond the shooting before it goes on
    let limit = 1.0 / opts.rtol;
    let (xt, mut steps) = match flow_capped(f, &x, period, s, opts.rtol, FIRST_FLOW_STEPS)? {
        Some(done) => done,
        None => {
            if let Some((growth, within)) = growth_beyond(f, &x, period, s, limit) {
                return Err(AnalysisError::Unresolvable { period, growth, within, limit });
            }
            flow_capped(f, &x, period, s, opts.rtol, u64::MAX)?.ok_or_else(|| AnalysisError::Integration { period, reason: "no step budget".into() })?
        }
    };
    let mut r = residual(&x, &xt);
    let (mut b, mut fresh) = match hint.filter(|h| h.len() == n * n && h.iter().all(|v| v.is_finite())) {
        Some(h) => (shooting_matrix(h, s, n), false),
        // a guess that is the orbit already (the planar rotor's balanced state on unequal
        // supports) needs no matrix to steer: only the orbit's monodromy below
        None if norm_inf(&r) <= tol => (vec![], true),
        None => (resolvable_matrix(&matrix_monodromy(f, &x, period, s, opts.rtol)?, s, n, period, opts.rtol)?, true),
    };
    // the orbit found: one Newton step with its exact matrix (quadratic: from a residual at
    // the tolerance to the integration's error; the quasi-Newton iteration stops just below
    // the tolerance), taken only if it is a small move (≤ 1e3 tolerances, scaled), with the
    // residual before it reported
    let finish = |mut x: Vec<f64>, it: usize, r_rtol: &[f64]| -> Result<StationaryState> {
        let res = norm_inf(r_rtol);
        let (o, phi) = variational_flow(f, &x, period, s, opts.rtol)?;
        let rv = residual(&x, &o.end);
        let d = direction(&shooting_matrix(&phi, s, n), n, &rv, k);
        if res > tol {
            // accepted only as round-off (the caller's allowance up to 1e3 tolerances), i.e.
            // where an orbit lies within the integration's error of x: the exact Newton step d
            // (monodromy at rtol) must bring the residual, in the flow at 1e-2 rtol, to
            // at most max(tol, res / 10, 1e-3 |d|). The slack is tied to the step, not to the
            // rtol flow's error at x (its difference from the tighter flow's): that error lies
            // in directions the step removes, a creep's drift in one it cannot, so a drift
            // below a tenth of the error passed a rule on it (examples/spatial_two_plane.toml
            // without unbalance at 1049.6-1312 rad/s, rtol 1e-10). Near a true orbit d is the
            // offset to it and the step lands within the tighter flow's error and the
            // step's second-order error, a small fraction of |d|; a creep keeps its drift
            // however far d goes. Measured rn/|d|: the forced oscillator's orbit 4.5e-7,
            // 3.2e-7, 6.8e-5 (rtol 1e-6, 1e-8, 1e-10; tests/round_off_16.rs); creeps
            // 0.043-0.19 (two-plane without unbalance, 1006-1399 rad/s), 4.1 (washer under
            // gravity, 1750 rpm), 129 (two-plane, 393.6 rad/s): 1e-3 sits 15x above the
            // orbits and 43x below the creeps
            let Some(d) = d.as_ref() else {
                return Err(fail(
                    it,
                    res,
                    "no step along the Newton direction reduces the residual, and the monodromy matrix gives no Newton step to show it is round-off",
                ));
            };
            let xn: Vec<f64> = x.iter().zip(d).zip(s).map(|((xi, di), si)| xi + di * si).collect();
            let rn = flow(f, &xn, period, s, 1e-2 * opts.rtol).map(|xt| norm_inf(&residual(&xn, &xt)));
            match rn {
                Ok(rn) if rn <= tol.max(0.1 * res).max(1e-3 * norm_inf(d)) => {}
                Err(e) => {
                    return Err(fail(
                        it,
                        res,
                        &format!("no step along the Newton direction reduces the residual, which is no round-off: the flow from the exact Newton step fails ({e}), no orbit near"),
                    ))
                }
                Ok(_) => {
                    return Err(fail(it, res, &format!("no step along the Newton direction reduces the residual, which is no round-off: the exact Newton step with the flow 100x tighter leaves it above a tenth of itself and a thousandth of the step (a slow drift, no orbit near){}", near_unit_multiplier(&shooting_matrix(&phi, s, n), n))))
                }
            }
        }
        if let Some(d) = d {
            if norm_inf(&d) <= 1e3 * tol {
                x.iter_mut().zip(&d).zip(s).for_each(|((xi, di), si)| *xi += di * si);
            }
        }
        Ok(StationaryState { family_dimension: f.structural_zeros(&x), x, period: Some(period), iterations: it, residual: res, monodromy: Some(phi) })
    };
    let mut it = 0;
    // the matrix is integrated again at most max_iterations / 2 times: each such integration
    // is a Newton step, and where they do not converge within that many (a start with no orbit
    // near, e.g. far below the speeds where the balls follow the rotor, where a revolution is
    // long and each integration dear) more would not either
    let max_refreshes = (opts.max_iterations / 2).max(2);
    let mut refreshes = 0;
    let stagnates = || format!("stagnates ({max_refreshes} integrations of the variational equations without converging)");
    loop {
        non_finite(f, &r, "right-hand side")?;
        let res = norm_inf(&r);
        if res <= tol {
            return finish(x, it, &r);
        }
        if it >= opts.max_iterations {
            return Err(fail(it, res, &format!("iteration limit{}", near_unit_multiplier(&b, n))));
        }
        it += 1;
        // backtracking on the scaled residual, as in `newton`; with an updated or carried (not
        // integrated here) matrix only down to 1/16, then a fresh one is worth its integration
        // (a floor of 1/2 saved 5 M instructions of 311 M on the two-plane scan, but a step
        // that is accepted only at 1/4 or 1/8, e.g. a direction a few times too long, would
        // then cost a refresh, and refreshes are capped: kept at 1/16)
        let shortest = if fresh { 1e-10 } else { 1.0 / 16.0 };
        // each trial flow capped at TRIAL_STEPS_FACTOR times the current point's steps
        let cap = steps.saturating_mul(TRIAL_STEPS_FACTOR).max(TRIAL_STEPS_FLOOR);
        let step = direction(&b, n, &r, k).and_then(|d| {
            let r0 = norm2(&r);
            let mut lambda = 1.0;
            while lambda >= shortest {
                let xn: Vec<f64> = x.iter().zip(&d).zip(s).map(|((xi, di), si)| xi + lambda * di * si).collect();
                if let Ok(Some((xt, used))) = flow_capped(f, &xn, period, s, opts.rtol, cap) {
                    let rn = residual(&xn, &xt);
                    if norm2(&rn) < (1.0 - 1e-4 * lambda) * r0 {
                        return Some((xn, rn, lambda, d, used));
                    }
                }
                lambda *= 0.5;
            }
            None
        });
        match step {
            Some((xn, rn, lambda, d, used)) => {
                // Broyden's update B ← B + (Δr − B p) pᵀ / pᵀp, p = λ d the scaled step
                let p: Vec<f64> = d.iter().map(|v| lambda * v).collect();
                let pp: f64 = p.iter().map(|v| v * v).sum();
                if pp > 0.0 {
                    for a in 0..n {
                        let bp: f64 = (0..n).map(|c| b[a * n + c] * p[c]).sum();
                        let w = (rn[a] - r[a] - bp) / pp;
                        for c in 0..n {
                            b[a * n + c] += w * p[c];
                        }
                    }
                }
                // a step that did not halve the residual: the updated matrix has drifted (or
                // the start was poor), so a fresh one at the new point
                let stalled = norm2(&rn) > 0.5 * norm2(&r);
                x = xn;
                r = rn;
                steps = used;
                fresh = false;
                if stalled && norm_inf(&r) > tol {
                    refreshes += 1;
                    if refreshes > max_refreshes {
                        return Err(fail(it, norm_inf(&r), &format!("{}{}", stagnates(), near_unit_multiplier(&b, n))));
                    }
                    b = resolvable_matrix(&matrix_monodromy(f, &x, period, s, opts.rtol)?, s, n, period, opts.rtol)?;
                    fresh = true;
                }
            }
            None if !fresh => {
                // the updated matrix gives no descent: a fresh one at x
                refreshes += 1;
                if refreshes > max_refreshes {
                    return Err(fail(it, res, &format!("{}{}", stagnates(), near_unit_multiplier(&b, n))));
                }
                b = resolvable_matrix(&matrix_monodromy(f, &x, period, s, opts.rtol)?, s, n, period, opts.rtol)?;
                fresh = true;
            }
            // round-off level of the integration: no step can reduce it further
            None if res <= 1e3 * tol => return finish(x, it, &r),
            None => return Err(fail(it, res, &format!("no step along the Newton direction reduces the residual{}", near_unit_multiplier(&b, n)))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{pair_rows, Packed, TrigInterpolant};
    use std::f64::consts::TAU;

    #[test]
    fn two_rows_of_the_product_formed_together_are_the_term_by_term_sums() {
        // n = 19 (two blocks of 8 and a remainder of 3), a column of J̃ missing from the rows'
        // pattern and an exact zero in it: every entry must be Σ_c J̃[a][c] Φ[c][b] summed in
        // increasing c, bit for bit (the same sums as the row-by-row loop: the multipliers, and
        // the range ends located from them, do not move)
        let n = 19;
        let v = |i: usize| ((i as f64 * 0.618_033_988_749_895).fract() - 0.5) * 10f64.powi((i % 7) as i32 - 3);
        let phi: Vec<f64> = (0..n * n).map(|i| v(i + 5)).collect();
        let mut jac: Vec<f64> = (0..2 * n).map(v).collect();
        jac[3] = 0.0;
        let cols: Vec<usize> = (0..n).filter(|&c| c != 7).collect();
        let (mut first, mut second) = (vec![f64::NAN; n], vec![f64::NAN; n]);
        pair_rows(&jac, &phi, n, &cols, &mut first, &mut second);
        for (r, got) in [first, second].iter().enumerate() {
            for b in 0..n {
                let mut want = 0.0;
                for &c in &cols {
                    if jac[r * n + c] != 0.0 {
                        want += jac[r * n + c] * phi[c * n + b];
                    }
                }
                assert_eq!(got[b].to_bits(), want.to_bits(), "row {r}, column {b}");
            }
        }
    }

    /// A 2 × 2 matrix function of θ = 2π t / T, row-major.
    fn sample(g: &dyn Fn(f64) -> [f64; 4], m: usize) -> Vec<Vec<f64>> {
        (0..m).map(|j| g(TAU * j as f64 / m as f64).to_vec()).collect()
    }

    #[test]
    fn the_trigonometric_interpolant_reproduces_a_trigonometric_polynomial() {
        // degree 3 (< N/2 = 4) from 8 samples: exact up to round-off at every t, the constant
        // entry kept as a constant
        let g = |th: f64| [1.0 + th.cos(), 2.0 * (3.0 * th).sin(), 5.0, 0.5 * (2.0 * th).cos() - 0.25 * th.sin()];
        let period = 0.7;
        let v = sample(&g, 8);
        let refs: Vec<&[f64]> = v.iter().map(|x| x.as_slice()).collect();
        let mut p = TrigInterpolant::new(2, period, &refs);
        assert_eq!(p.varying, vec![0, 1, 3]);
        // entry by entry, only the harmonics present survive a truncation at round-off: cos θ
        // (entry 0), sin 3θ (1), cos 2θ and sin θ (3), four terms of the 3 × 4 computed
        p.truncate(&[1.0, 1.0], 1e-13);
        assert_eq!((p.terms(), p.degree()), (4, 3));
        let mut out = [0.0; 4];
        for k in 0..50 {
            let t = period * (k as f64 * 0.137).fract();
            p.eval(t, &mut out, &mut vec![]);
            let want = g(TAU * t / period);
            for e in 0..4 {
                assert!((out[e] - want[e]).abs() < 1e-13, "t = {t}, entry {e}: {} against {}", out[e], want[e]);
            }
        }
    }

    #[test]
    fn the_packed_evaluation_gives_the_term_by_term_sums_bit_for_bit() {
        // a 4 × 4 J(θ): entry 0 constant, entry e ≥ 1 with harmonics 1 ..= 1 + e % 6, so after
        // a truncation at round-off harmonic 1 has a term in all 15 varying entries (dense),
        // harmonic 6 in 2 (sparse): J̃(t) must be, bit for bit, the sum of the terms in
        // increasing k per entry (the layout before session 19), bar the sign of a zero
        let g = |th: f64| -> Vec<f64> {
            (0..16)
                .map(|e| {
                    let top = if e == 0 { 0 } else { 1 + e % 6 };
                    e as f64 + (1..=top).map(|k| ((k as f64 * th).cos() - 0.5 * (k as f64 * th).sin()) / (k * k) as f64).sum::<f64>()
                })
                .collect()
        };
        let (period, m) = (0.3, 16);
        let v: Vec<Vec<f64>> = (0..m).map(|j| g(TAU * j as f64 / m as f64)).collect();
        let refs: Vec<&[f64]> = v.iter().map(|x| x.as_slice()).collect();
        let mut p = TrigInterpolant::new(4, period, &refs);
        p.truncate(&[1.0; 4], 1e-12);
        assert_eq!((p.varying.len(), p.degree()), (15, 6));
        assert!(p.packed.iter().any(|h| matches!(h, Packed::Dense { .. })) && p.packed.iter().any(|h| matches!(h, Packed::Sparse(_))));
        let mut out = [0.0; 16];
        for k in 0..40 {
            let t = period * (k as f64 * 0.377).fract();
            p.eval(t, &mut out, &mut vec![]);
            let mut want = p.constant.clone();
            let (s1, c1) = (p.frequency * t).sin_cos();
            let mut acc = p.mean.clone();
            let (mut c_prev, mut s_prev, mut c, mut s) = (1.0, 0.0, c1, s1);
            for h in &p.harmonics {
                for &(v, a, b) in h {
                    acc[v] += c * a + s * b;
                }
                (c_prev, s_prev, c, s) = (c, s, 2.0 * c1 * c - c_prev, 2.0 * c1 * s - s_prev);
            }
            p.varying.iter().zip(&acc).for_each(|(&e, v)| want[e] = *v);
            for e in 0..16 {
                assert!(out[e].to_bits() == want[e].to_bits() || out[e] == 0.0 && want[e] == 0.0, "t = {t}, entry {e}: {} against {}", out[e], want[e]);
            }
        }
    }

    #[test]
    fn the_interpolation_error_falls_as_the_aliasing_bound_and_truncation_stays_in_its_budget() {
        // f(θ) = 1/(a − cos θ): Fourier coefficients ρ^|k| / sqrt(a² − 1), ρ = a − sqrt(a² − 1)
        // (Gradshteyn & Ryzhik 1.447), so the interpolant on N samples errs by at most twice the
        // coefficients it cannot represent, 2 Σ_{|k| ≥ N/2} ρ^|k| / sqrt(a² − 1)
        // = 4 ρ^{N/2} / ((1 − ρ) sqrt(a² − 1)) (Trefethen, Spectral Methods in MATLAB, thm 3):
        // the measured error must lie under that bound, and within 1e3 of it (the bound is
        // reached up to a modest factor: the geometric rate is real, not an accident of t)
        let a: f64 = 1.5;
        let rho = a - (a * a - 1.0).sqrt();
        let g = |th: f64| [1.0 / (a - th.cos()), 0.0, 1.0, (th.sin()).exp()];
        let period = 2.0;
        let mut last = f64::INFINITY;
        for m in [8, 16, 32] {
            let v = sample(&g, m);
            let refs: Vec<&[f64]> = v.iter().map(|x| x.as_slice()).collect();
            let p = TrigInterpolant::new(2, period, &refs);
            let mut out = [0.0; 4];
            let mut err: f64 = 0.0;
            for k in 0..400 {
                let t = period * (k as f64 + 0.5) / 400.0;
                p.eval(t, &mut out, &mut vec![]);
                err = err.max((out[0] - g(TAU * t / period)[0]).abs());
            }
            let bound = 4.0 * rho.powi(m as i32 / 2) / ((1.0 - rho) * (a * a - 1.0).sqrt());
            assert!(err <= bound && err >= 1e-3 * bound, "N = {m}: error {err:e}, bound {bound:e}");
            assert!(err < last);
            last = err;
            // dropping the top harmonics within a budget moves J̃ by at most that budget
            // (scaled max-row-sum norm, unit scales: row 0 holds entry 0 alone)
            let mut q = TrigInterpolant::new(2, period, &refs);
            let budget = 1e-4;
            q.truncate(&[1.0, 1.0], budget);
            if m == 32 {
                assert!(q.degree() < p.degree(), "harmonics near 16 are ~1e-7: dropped");
                assert!(q.terms() < p.terms());
            }
            let mut o2 = [0.0; 4];
            for k in 0..100 {
                let t = period * k as f64 / 100.0;
                p.eval(t, &mut out, &mut vec![]);
                q.eval(t, &mut o2, &mut vec![]);
                let row0 = (out[0] - o2[0]).abs() + (out[1] - o2[1]).abs();
                let row1 = (out[2] - o2[2]).abs() + (out[3] - o2[3]).abs();
                assert!(row0.max(row1) <= budget, "N = {m}: truncation moved J̃ by {} > {budget}", row0.max(row1));
            }
        }
    }
}

/// Magnus integrators on `Φ' = J̃ Φ`, measured against DOP853 (docs/notes/benchmarks.md,
/// "Round 3, session 7 (magnus)").
#[cfg(test)]
#[path = "magnus_measurement.rs"]
mod magnus_measurement;
