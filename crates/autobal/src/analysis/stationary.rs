//! The stationary state: an equilibrium by Newton's method, a periodic orbit by single shooting
//! (module docs of [`crate::analysis`]).

// Index loops follow the formulas (rows, columns).
#![allow(clippy::needless_range_loop)]

use super::linear::{lu_solve, min_norm_solve};
use super::{AnalysisError, Result, VectorField};
use crate::ode::{Control, Method, Options, Solver, System};
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
            if res <= 1e3 * tol {
                return Ok((x, it, res, jac));
            }
            return Err(fail(it, res, "the Jacobian is singular (a family of states the model does not declare, or a turning point)"));
        };
        let r0 = norm2(&r);
        let mut lambda = 1.0;
        let mut accepted = None;
        while lambda >= 1e-10 {
            let xn: Vec<f64> = x.iter().zip(&d).zip(s).map(|((xi, di), si)| xi + lambda * di * si).collect();
            match eval(&xn, false) {
                Ok((rn, _)) if norm2(&rn) < (1.0 - 1e-4 * lambda) * r0 => {
                    accepted = Some(xn);
                    break;
                }
                _ => lambda *= 0.5,
            }
        }
        let Some(xn) = accepted else {
            if res <= 1e3 * tol {
                return Ok((x, it, res, jac)); // round-off level: no step can reduce it further
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
    let eval = |x: &[f64], with_jac: bool| -> Result<(Vec<f64>, Option<Vec<f64>>)> {
        let mut fx = vec![0.0; n];
        f.rhs(0.0, x, &mut fx);
        non_finite(f, &fx, "right-hand side")?;
        let r: Vec<f64> = fx.iter().zip(s).map(|(v, si)| v / si / rate).collect();
        if !with_jac {
            return Ok((r, None));
        }
        let mut j = vec![0.0; n * n];
        f.jacobian(0.0, x, &mut j);
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

/// `x' = f(t, x)` with the variational equations `Φ' = J(t, x) Φ` (Φ row-major `n × n` after
/// `x` in the state): the ODE system whose solution over one period gives the monodromy
/// matrix `Φ(T)`.
pub struct VariationalSystem<'a, F: VectorField + ?Sized> {
    f: &'a F,
    n: usize,
    jac: RefCell<Vec<f64>>,
}

impl<'a, F: VectorField + ?Sized> VariationalSystem<'a, F> {
    /// The variational system of `f`.
    pub fn new(f: &'a F) -> Self {
        let n = f.dim();
        VariationalSystem { f, n, jac: RefCell::new(vec![0.0; n * n]) }
    }
}

impl<F: VectorField + ?Sized> System for VariationalSystem<'_, F> {
    fn dim(&self) -> usize {
        self.n + self.n * self.n
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        let (x, phi) = y.split_at(n);
        let (dx, dphi) = dy.split_at_mut(n);
        self.f.rhs(t, x, dx);
        let mut j = self.jac.borrow_mut();
        self.f.jacobian(t, x, &mut j);
        for a in 0..n {
            let row = &mut dphi[a * n..(a + 1) * n];
            row.iter_mut().for_each(|v| *v = 0.0);
            for c in 0..n {
                let jac = j[a * n + c];
                if jac != 0.0 {
                    for (o, p) in row.iter_mut().zip(&phi[c * n..(c + 1) * n]) {
                        *o += jac * p;
                    }
                }
            }
        }
    }

    fn component_name(&self, i: usize) -> String {
        if i < self.n {
            self.f.component_name(i)
        } else {
            let (a, b) = ((i - self.n) / self.n, (i - self.n) % self.n);
            format!("Φ[{a}][{b}] (∂{} / ∂{} at t = 0)", self.f.component_name(a), self.f.component_name(b))
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
/// `atol` per component.
fn integrate_period<S: System>(sys: &S, y: &mut [f64], period: f64, rtol: f64, atol: Vec<f64>) -> Result<()> {
    let opts = Options::new(rtol, rtol).method(Method::Dop853).atol_per_component(atol);
    let mut solver = Solver::new(sys, opts)?;
    let out = solver.integrate(0.0, y, period, |_| Control::Continue);
    if !out.status.is_completed() {
        return Err(AnalysisError::Integration { period, reason: out.to_string() });
    }
    Ok(())
}

/// Most Chebyshev intervals of the interpolated Jacobian ([`interpolated_variational`]) before
/// the full variational equations are integrated instead.
const MAX_CHEBYSHEV: usize = 128;

/// `Φ' = J̃(t) Φ`: the variational equations with the Jacobian along the orbit replaced by its
/// Chebyshev interpolant in `t` on `[0, T]` (barycentric form on the Lobatto points). Entries
/// equal at every node (the kinematic rows `∂q̇/∂(q, v) = (0, I)`, structural zeros) are kept
/// as constants; only the others are interpolated.
struct InterpolatedVariational {
    n: usize,
    /// The Lobatto points `t_j`.
    nodes: Vec<f64>,
    /// The barycentric weights `(−1)^j`, halved at the ends.
    weights: Vec<f64>,
    /// `J` with its constant entries, row-major.
    constant: Vec<f64>,
    /// The indices of the entries that vary between nodes.
    varying: Vec<usize>,
    /// Those entries of `J(t_j, x(t_j))`, one vector per node.
    values: Vec<Vec<f64>>,
    jac: RefCell<Vec<f64>>,
    coef: RefCell<Vec<f64>>,
}

impl InterpolatedVariational {
    fn new(n: usize, nodes: Vec<f64>, weights: Vec<f64>, jacobians: Vec<Vec<f64>>) -> Self {
        let first = &jacobians[0];
        let varying: Vec<usize> = (0..n * n).filter(|&e| jacobians.iter().any(|j| j[e] != first[e])).collect();
        let values = jacobians.iter().map(|j| varying.iter().map(|&e| j[e]).collect()).collect();
        let m = nodes.len();
        InterpolatedVariational {
            n,
            nodes,
            weights,
            constant: first.clone(),
            varying,
            values,
            jac: RefCell::new(first.clone()),
            coef: RefCell::new(vec![0.0; m]),
        }
    }

    /// `J̃(t)` into `out`.
    fn eval(&self, t: f64, out: &mut [f64]) {
        out.copy_from_slice(&self.constant);
        if self.varying.is_empty() {
            return;
        }
        let mut acc = vec![0.0; self.varying.len()];
        if let Some(j) = self.nodes.iter().position(|tj| *tj == t) {
            acc.copy_from_slice(&self.values[j]);
        } else {
            let mut coef = self.coef.borrow_mut();
            let mut den = 0.0;
            for (j, tj) in self.nodes.iter().enumerate() {
                coef[j] = self.weights[j] / (t - tj);
                den += coef[j];
            }
            for (c, v) in coef.iter().zip(&self.values) {
                let c = c / den;
                for (a, x) in acc.iter_mut().zip(v) {
                    *a += c * x;
                }
            }
        }
        for (&e, a) in self.varying.iter().zip(&acc) {
            out[e] = *a;
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
        self.eval(t, &mut j);
        for a in 0..n {
            let row = &mut dphi[a * n..(a + 1) * n];
            row.iter_mut().for_each(|v| *v = 0.0);
            for c in 0..n {
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

/// `x(T; x0)` and `Φ(T)` with the Jacobian evaluated only at the Chebyshev–Lobatto points of
/// `[0, T]` and interpolated between them (module docs of [`crate::analysis`], "Floquet"): the
/// orbit `x(t)` by DOP853 (dense output at the points), `J(t_j, x(t_j))` there by the model's
/// automatic differentiation, and `Φ' = J̃(t) Φ` by DOP853 at the same tolerances as the full
/// variational equations. The number of intervals `N` doubles from 16 (reusing the points)
/// until the interpolant on `N/2` intervals, evaluated at the `N/2` new points, is within
/// `1e-2 · rtol` of the Jacobian there in the scaled max-row-sum norm `‖S⁻¹ · S‖∞` relative to
/// `‖S⁻¹ J S‖∞` (the interpolant on `N` intervals is then much closer still: the error of
/// Chebyshev interpolation of an analytic function falls geometrically in `N`); `None` when
/// `N` = [`MAX_CHEBYSHEV`] does not reach it (the full variational equations are integrated).
fn interpolated_variational<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64) -> Result<Option<(Vec<f64>, Vec<f64>)>> {
    let n = f.dim();
    // the orbit at the Lobatto points of MAX_CHEBYSHEV intervals (coarser sets are subsets)
    let big = MAX_CHEBYSHEV;
    let times: Vec<f64> = (0..=big).map(|j| 0.5 * period * (1.0 - (std::f64::consts::PI * j as f64 / big as f64).cos())).collect();
    let mut samples: Vec<Option<Vec<f64>>> = vec![None; big + 1];
    samples[0] = Some(x0.to_vec());
    let plain = Plain(f);
    // the orbit 100x tighter than the tolerance: the sampled Jacobians' own error (through
    // x's) then stays below the interpolation test's threshold
    let tight = 1e-2 * rtol;
    let opts = Options::new(tight, tight).method(Method::Dop853).atol_per_component(s.iter().map(|v| tight * v).collect());
    let mut solver = Solver::new(&plain, opts)?;
    let mut y = x0.to_vec();
    let mut next = 1;
    let out = solver.integrate(0.0, &mut y, period, |step| {
        while next < big && times[next] <= step.t_new {
            let mut v = vec![0.0; n];
            step.interpolate(times[next], &mut v);
            samples[next] = Some(v);
            next += 1;
        }
        Control::Continue
    });
    if !out.status.is_completed() {
        return Err(AnalysisError::Integration { period, reason: out.to_string() });
    }
    samples[big] = Some(y.clone());
    let scaled_norm = |m: &[f64]| (0..n).map(|a| (0..n).map(|b| (m[a * n + b] * s[b] / s[a]).abs()).sum::<f64>()).fold(0.0, f64::max);
    let mut jacobians: Vec<Option<Vec<f64>>> = vec![None; big + 1];
    let mut jac_at = |k: usize| -> Result<Vec<f64>> {
        if let Some(j) = &jacobians[k] {
            return Ok(j.clone());
        }
        let mut j = vec![0.0; n * n];
        f.jacobian(times[k], samples[k].as_ref().expect("sampled"), &mut j);
        non_finite(f, &j, "Jacobian")?;
        jacobians[k] = Some(j.clone());
        Ok(j)
    };
    let system = |intervals: usize, jac: Vec<Vec<f64>>| {
        let stride = big / intervals;
        let nodes: Vec<f64> = (0..=intervals).map(|j| times[j * stride]).collect();
        let weights: Vec<f64> = (0..=intervals).map(|j| if j % 2 == 0 { 1.0 } else { -1.0 } * if j == 0 || j == intervals { 0.5 } else { 1.0 }).collect();
        InterpolatedVariational::new(n, nodes, weights, jac)
    };
    let mut intervals = 8;
    let mut coarse: Vec<Vec<f64>> = (0..=intervals).map(|j| jac_at(j * big / intervals)).collect::<Result<_>>()?;
    let accepted = loop {
        let fine_n = 2 * intervals;
        let stride = big / fine_n;
        let fine: Vec<Vec<f64>> = (0..=fine_n).map(|j| jac_at(j * stride)).collect::<Result<_>>()?;
        let interp = system(intervals, coarse);
        let mut worst: f64 = 0.0;
        let mut size: f64 = 0.0;
        let mut tmp = vec![0.0; n * n];
        for (j, jf) in fine.iter().enumerate() {
            size = size.max(scaled_norm(jf));
            if j % 2 == 1 {
                interp.eval(times[j * stride], &mut tmp);
                tmp.iter_mut().zip(jf).for_each(|(a, b)| *a -= b);
                worst = worst.max(scaled_norm(&tmp));
            }
        }
        if worst <= rtol * size {
            break Some(system(fine_n, fine));
        }
        if fine_n >= big {
            break None;
        }
        intervals = fine_n;
        coarse = fine;
    };
    let Some(sys) = accepted else { return Ok(None) };
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
    Ok(Some((y, phi)))
}

/// `x(T; x0)`, and with `variational` also `Φ(T)`, by DOP853 from `t = 0` (module docs of
/// [`crate::analysis`]): `Φ` with the interpolated Jacobian where it converges
/// ([`interpolated_variational`]), else by the full variational equations.
fn flow<F: VectorField + ?Sized>(f: &F, x0: &[f64], period: f64, s: &[f64], rtol: f64, variational: bool) -> Result<(Vec<f64>, Option<Vec<f64>>)> {
    let n = f.dim();
    let atol_x = s.iter().map(|v| rtol * v);
    if !variational {
        let mut y = x0.to_vec();
        integrate_period(&Plain(f), &mut y, period, rtol, atol_x.collect())?;
        return Ok((y, None));
    }
    if let Some((y, phi)) = interpolated_variational(f, x0, period, s, rtol)? {
        return Ok((y, Some(phi)));
    }
    let sys = VariationalSystem::new(f);
    let mut atol: Vec<f64> = atol_x.collect();
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
    let phi = y.split_off(n);
    Ok((y, Some(phi)))
}

/// `S⁻¹ (I − Φ) S`: the shooting residual's Jacobian in scaled variables.
fn shooting_matrix(phi: &[f64], s: &[f64], n: usize) -> Vec<f64> {
    (0..n * n).map(|ab| (if ab / n == ab % n { 1.0 } else { 0.0 }) - phi[ab] * s[ab % n] / s[ab / n]).collect()
}

/// The periodic orbit by single shooting (module docs of [`crate::analysis`]): quasi-Newton
/// (Broyden) iterations on `r(x0) = S⁻¹ (x0 − x(T; x0))` whose trial points need only the
/// flow `x(T; x0)`, the matrix `S⁻¹ (I − Φ) S` taken exact from the variational equations at
/// the start (or from `hint`, a neighbouring orbit's monodromy matrix) and updated by rank one
/// after each step; the variational equations are integrated again only where the updated
/// matrix gives no descent or a step fails to halve the residual (then the iteration is
/// Newton's; at most `max_iterations / 2` times, then the search is reported as stagnating),
/// and once at the orbit found, for its monodromy matrix.
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
    // the matrix, and Φ(T) at x where it was integrated there (then the matrix is exact)
    let (mut r, mut b, mut phi_at_x) = match hint.filter(|h| h.len() == n * n && h.iter().all(|v| v.is_finite())) {
        Some(h) => {
            let (xt, _) = flow(f, &x, period, s, opts.rtol, false)?;
            (residual(&x, &xt), shooting_matrix(h, s, n), None)
        }
        None => {
            let (xt, phi) = flow(f, &x, period, s, opts.rtol, true)?;
            let phi = phi.expect("variational flow");
            (residual(&x, &xt), shooting_matrix(&phi, s, n), Some(phi))
        }
    };
    let mut it = 0;
    // the exact matrix is integrated again at most max_iterations / 2 times: each such
    // integration is a Newton step, and where they do not converge within that many (a
    // start with no orbit near, e.g. far below the speeds where the balls follow the rotor,
    // where a revolution is long and each integration dear) more would not either
    let max_refreshes = (opts.max_iterations / 2).max(2);
    let mut refreshes = 0;
    loop {
        non_finite(f, &r, "right-hand side")?;
        let res = norm_inf(&r);
        if res <= tol {
            let phi = match phi_at_x {
                Some(phi) => phi,
                None => {
                    // Φ(T) at the orbit, and with it one Newton step with the exact matrix
                    // (quadratic: from a residual at the tolerance to the integration's error;
                    // the quasi-Newton iteration stops just below the tolerance), taken only
                    // if it is a small move (≤ 1e3 tolerances, scaled), with the residual
                    // before it reported
                    let (xt, phi) = flow(f, &x, period, s, opts.rtol, true)?;
                    let phi = phi.expect("variational flow");
                    let rv = residual(&x, &xt);
                    if let Some(d) = direction(&shooting_matrix(&phi, s, n), n, &rv, k) {
                        if norm_inf(&d) <= 1e3 * tol {
                            x.iter_mut().zip(&d).zip(s).for_each(|((xi, di), si)| *xi += di * si);
                        }
                    }
                    phi
                }
            };
            return Ok(StationaryState {
                family_dimension: f.structural_zeros(&x),
                x,
                period: Some(period),
                iterations: it,
                residual: res,
                monodromy: Some(phi),
            });
        }
        if it >= opts.max_iterations {
            return Err(fail(it, res, "iteration limit"));
        }
        it += 1;
        // backtracking on the scaled residual, as in `newton`; with an updated (not exact)
        // matrix only down to 1/16, then the exact matrix is worth its integration
        let shortest = if phi_at_x.is_some() { 1e-10 } else { 1.0 / 16.0 };
        let step = direction(&b, n, &r, k).and_then(|d| {
            let r0 = norm2(&r);
            let mut lambda = 1.0;
            while lambda >= shortest {
                let xn: Vec<f64> = x.iter().zip(&d).zip(s).map(|((xi, di), si)| xi + lambda * di * si).collect();
                if let Ok((xt, _)) = flow(f, &xn, period, s, opts.rtol, false) {
                    let rn = residual(&xn, &xt);
                    if norm2(&rn) < (1.0 - 1e-4 * lambda) * r0 {
                        return Some((xn, rn, lambda, d));
                    }
                }
                lambda *= 0.5;
            }
            None
        });
        match step {
            Some((xn, rn, lambda, d)) => {
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
                // the start was poor), so the exact one at the new point
                let stalled = norm2(&rn) > 0.5 * norm2(&r);
                x = xn;
                r = rn;
                phi_at_x = None;
                if stalled {
                    refreshes += 1;
                    if refreshes > max_refreshes {
                        return Err(fail(
                            it,
                            norm_inf(&r),
                            &format!("stagnates ({max_refreshes} integrations of the variational equations without converging)"),
                        ));
                    }
                    let (xt, phi) = flow(f, &x, period, s, opts.rtol, true)?;
                    let phi = phi.expect("variational flow");
                    r = residual(&x, &xt);
                    b = shooting_matrix(&phi, s, n);
                    phi_at_x = Some(phi);
                }
            }
            None if phi_at_x.is_none() => {
                // the updated matrix gives no descent: the exact one at x
                refreshes += 1;
                if refreshes > max_refreshes {
                    return Err(fail(it, res, &format!("stagnates ({max_refreshes} integrations of the variational equations without converging)")));
                }
                let (xt, phi) = flow(f, &x, period, s, opts.rtol, true)?;
                let phi = phi.expect("variational flow");
                r = residual(&x, &xt);
                b = shooting_matrix(&phi, s, n);
                phi_at_x = Some(phi);
            }
            None if res <= 1e3 * tol => {
                // round-off level of the integration: no step can reduce it further
                let phi = phi_at_x.expect("exact matrix");
                return Ok(StationaryState {
                    family_dimension: f.structural_zeros(&x),
                    x,
                    period: Some(period),
                    iterations: it,
                    residual: res,
                    monodromy: Some(phi),
                });
            }
            None => return Err(fail(it, res, "no step along the Newton direction reduces the residual")),
        }
    }
}
