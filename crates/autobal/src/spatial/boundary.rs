//! Stability boundaries in a two-parameter plane, followed as curves: pseudo-arclength
//! continuation of the Hopf condition (a pair `λ = ±iω` on the imaginary axis) and of the fold
//! condition (`λ = 0`), as AUTO and BifurcationKit do, with the codimension-two points where
//! the boundary changes from one curve to another.
//!
//! The conditions are written on the characteristic polynomial `p(λ) = Σ_j a_j λ^j` (`a_N = 1`)
//! of the linearised equations at a point of the plane (the exact expansion of
//! `det(M λ² + G λ + K)/det M`, [`crate::linalg::charpoly::pencil_polynomial`]). With `λ = iω`
//! and `w = ω²`: `p(iω) = E(w) + iω O(w)`, `E(w) = Σ_m a_{2m} (−w)^m`,
//! `O(w) = Σ_m a_{2m+1} (−w)^m`, so
//! - **Hopf**: `E(w) = O(w) = 0` with `w > 0` (unknowns: the two parameters and `w`); the same
//!   curve continues through `w = 0` (a **Bogdanov–Takens** point, where it meets the fold
//!   curve) into `w < 0`, a real pair `±√(−w)` (a neutral saddle, no boundary);
//! - **fold**: `a_0 = p(0) = 0` (unknowns: the two parameters).
//!
//! A point of a curve lies on the **stability boundary** when every other eigenvalue has
//! `Re λ < 0`: Routh's count of the roots right of `−δ` is then exactly 2 (Hopf) or 1 (fold).
//! Where that count changes along a curve another eigenvalue crosses the axis: a **double Hopf**
//! or **fold–Hopf** point, located by regula falsi on the real part of the crossing eigenvalue;
//! the other curve through it is traced too.
//!
//! Curves are seeded from the changes of verdict on a coarse grid (along the speed axis, if
//! there is one, with the analytic critical speeds and the middles of their split pairs added,
//! as [`crate::spatial::stability::stability_ranges`] does; the lines across the speed take
//! their nodes' verdicts from those lines' polynomials in `Ω`), each seed located by bisection
//! and then corrected by Newton's method onto its condition.
//!
//! **Cost.** When one axis is the speed and the model is a polynomial of degree ≤ 2 along the
//! other (checked against the derived model: `z̄_A`, the damping coefficients, ...), the whole
//! plane's characteristic polynomial is expanded once
//! ([`crate::linalg::charpoly::PlanePolynomial`]): every point's coefficients, residual, exact
//! Jacobian and stability flag then cost a few hundred multiply-adds, and no model is derived;
//! the residual and the Jacobian at an iterate come from one evaluation, and a point's
//! stability flag from the corrector's last.
//! Otherwise the corrector's residuals are determinants of the pencil at `λ = iω` (or `±√(−w)`,
//! or 0) by elimination, a fraction of an expansion's cost; the model is held as a pencil in
//! the speed, so a step along the speed derives no model; the Jacobian (forward differences) is
//! refreshed while the steps are large and then kept (the chord method). The expansion is
//! needed once per traced point (Routh's count: is it on the stability boundary?) and for the
//! bisections across the speed. Every point of a curve satisfies its condition to the
//! corrector's tolerance (the error left after the last step, estimated from the steps'
//! quadratic convergence, below 1e-12 of the plane scaled to the unit square, or a last step
//! below 1e-10): it is located far inside the 1e-8 required. The chord error of the polyline
//! is bounded through the product of a step and its turn (`h·turn ≤ 0.15·max_step`, sagitta
//! of a chord `c ≤ 2h` at most `c·turn/8 ≤ h·turn/4`), so a short step may turn further (up to 0.6 rad): a tight tip of a curve is
//! passed in few points.

use crate::builder::builder;
use crate::control::{Control, StopReason};
use crate::error::{Error, Result};
use crate::linalg::charpoly::{aberth_roots, det_dual, pencil_polynomial, routh_count_right_of, PencilTerms, PlanePolynomial, SpeedPolynomial};
use crate::linalg::dense::Lu;
use crate::linalg::eigen::eigenvalues;
pub use crate::paths::Axis;
use crate::spatial::critical_speeds::{critical_speeds_at, ModeKind};
use crate::spatial::linear_model::{Balls, Pencil};
use crate::spatial::map::OMEGA;
use crate::spatial::paths::SpatialSpec;
use num_complex::Complex64;
use serde::Serialize;

/// Settings of [`trace_boundary`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceSettings {
    /// Balls free or locked.
    pub balls: Balls,
    /// The speed when neither axis is [`OMEGA`].
    pub omega: Option<f64>,
    /// Coarse grid for the seeds (points along x, along y).
    pub coarse: (usize, usize),
    /// Largest step along a curve in the plane scaled to the unit square.
    pub max_step: f64,
}

/// Balls free, the speed from an axis, a 24 × 24 seed grid, steps of at most 1/20 of the plane.
impl Default for TraceSettings {
    fn default() -> Self {
        TraceSettings { balls: Balls::Free, omega: None, coarse: (24, 24), max_step: 0.05 }
    }
}

impl TraceSettings {
    /// A builder starting from [`TraceSettings::default`].
    pub fn builder() -> TraceSettingsBuilder {
        TraceSettingsBuilder::default()
    }

    /// Check the settings that do not depend on the axes (errors name `omega`, `coarse`,
    /// `max_step`): a fixed speed, when given, finite and `≥ 0`; at least 2 seed lines each way;
    /// `0 < max_step ≤ 1` (a step is measured in the plane scaled to the unit square). Whether
    /// the speed is needed depends on the axes ([`trace_boundary`] checks that).
    pub fn validate(&self) -> Result<()> {
        crate::spatial::map::check_fixed_speed(self.omega)?;
        if self.coarse.0 < 2 || self.coarse.1 < 2 {
            return Err(Error::invalid("coarse", format!("the seed grid needs at least 2 lines each way, got {:?}", self.coarse)));
        }
        if !(self.max_step > 0.0 && self.max_step <= 1.0) {
            return Err(Error::invalid("max_step", format!("must lie in (0, 1] (a fraction of the plane), got {}", self.max_step)));
        }
        Ok(())
    }
}

builder!(
    /// Builder of [`TraceSettings`]; `build()` runs [`TraceSettings::validate`].
    ///
    /// ```
    /// use autobal::spatial::boundary::TraceSettings;
    /// let s = TraceSettings::builder().coarse((40, 12)).max_step(0.02).build().unwrap();
    /// assert_eq!((s.coarse, s.max_step, s.omega), ((40, 12), 0.02, None));
    /// let e = TraceSettings::builder().max_step(0.0).build().unwrap_err();
    /// assert!(e.to_string().starts_with("max_step"), "{e}");
    /// let e = TraceSettings::builder().coarse((1, 24)).build().unwrap_err();
    /// assert!(e.to_string().starts_with("coarse"), "{e}");
    /// ```
    TraceSettingsBuilder for TraceSettings, |s| s.validate();
    balls: Balls, omega: Option<f64>, coarse: (usize, usize), max_step: f64,
);

/// Which condition a curve follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CurveKind {
    /// A pair of eigenvalues `±iω` (`w = ω² > 0`; `w < 0`: a neutral saddle).
    Hopf,
    /// A zero eigenvalue.
    Fold,
}

/// A point of a curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurvePoint {
    /// First parameter.
    pub x: f64,
    /// Second parameter.
    pub y: f64,
    /// `ω²` of the pair on the axis (Hopf), 0 for a fold.
    pub w: f64,
    /// Whether every other eigenvalue has `Re λ < 0` here (the curve is the stability boundary).
    pub on_boundary: bool,
}

/// A traced curve.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoundaryCurve {
    /// Hopf or fold.
    pub kind: CurveKind,
    /// Its points in order.
    pub points: Vec<CurvePoint>,
    /// Whether it closes on itself inside the plane.
    pub closed: bool,
}

/// Kinds of codimension-two points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Codim2Kind {
    /// Hopf meets fold with `ω → 0` (a double zero eigenvalue).
    BogdanovTakens,
    /// Two pairs on the imaginary axis.
    DoubleHopf,
    /// A pair on the axis and a zero eigenvalue.
    FoldHopf,
}

/// A codimension-two point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Codim2Point {
    /// Kind.
    pub kind: Codim2Kind,
    /// First parameter.
    pub x: f64,
    /// Second parameter.
    pub y: f64,
}

/// The result of [`trace_boundary`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Boundary {
    /// The plane.
    pub x: Axis,
    /// The plane.
    pub y: Axis,
    /// Every curve traced.
    pub curves: Vec<BoundaryCurve>,
    /// Codimension-two points found on them.
    pub codim2: Vec<Codim2Point>,
    /// Characteristic polynomials evaluated (the cost): from the plane's polynomial, or
    /// (without one) expanded at one point (the seed search across the speed, every traced
    /// point's stability flag) or as determinants at one point (the corrector's residuals).
    pub evaluations: usize,
    /// Whether the whole plane was searched (`false`: stopped by [`trace_boundary_with`]'s
    /// control; the curves traced until then are complete curves); `stopped.is_none()`.
    pub complete: bool,
    /// Why the search stopped early (`None`: complete).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopReason>,
}

/// Points of the plane → characteristic polynomials.
struct Plane<'a> {
    spec: &'a SpatialSpec,
    x: &'a Axis,
    y: &'a Axis,
    balls: Balls,
    omega: Option<f64>,
    evaluations: std::cell::Cell<usize>,
    /// Residuals evaluated as determinants ([`Plane::residual`]).
    determinants: std::cell::Cell<usize>,
    /// The last point evaluated and its polynomial.
    last: std::cell::Cell<Option<(f64, f64, [f64; D], usize)>>,
    /// The two models used last (most recent first), by the values of the axes that are not the
    /// speed, as pencils in the speed: a step along the speed, or back to the point of a
    /// difference quotient, derives no model.
    models: std::cell::RefCell<[Option<([f64; 2], PencilTerms)>; 2]>,
    /// `∂T/∂u`, `∂T/∂v` of the model's [`PencilTerms`] along the axes that are not the speed,
    /// by a forward difference at the first iterate of the current correction
    /// ([`correct`] clears them): the later Jacobians of that correction derive no model.
    dterms: std::cell::RefCell<[Option<PencilTerms>; 2]>,
    /// The model along the one axis that is not the speed as an exact polynomial in its scaled
    /// coordinate, where it is one ([`ParamTerms::fit`]): no model is derived while tracing.
    param: Option<ParamTerms>,
    /// With `param` of degree ≤ 2: the characteristic polynomial of the whole plane
    /// ([`PlanePolynomial`]), so that a point's polynomial, residual and exact Jacobian cost a
    /// few hundred multiply-adds instead of an expansion or determinants.
    plane: Option<PlanePolynomial>,
}

const D: usize = 13;

/// The six matrices of [`PencilTerms`] (`M`, `G0`, `G1`, `K0`, `K1`, `K2`).
fn mats(t: &PencilTerms) -> [&[[f64; 6]; 6]; 6] {
    [&t.m, &t.g[0], &t.g[1], &t.k[0], &t.k[1], &t.k[2]]
}

/// [`mats`], mutable.
fn mats_mut(t: &mut PencilTerms) -> [&mut [[f64; 6]; 6]; 6] {
    let PencilTerms { m, g, k, .. } = t;
    let [g0, g1] = g;
    let [k0, k1, k2] = k;
    [m, g0, g1, k0, k1, k2]
}

/// Where the model along a parameter axis is sampled ([`ParamTerms::fit`]): a polynomial of
/// degree `d` interpolates the first `d + 1` and is checked at the other `9 − d` (at least 5;
/// irrational points, so that no check coincides with a node).
const PARAM_SAMPLES: [f64; 10] =
    [0.0, 1.0, 0.5, 0.146_446_609_4, 0.853_553_390_6, 0.309_016_994_4, std::f64::consts::FRAC_1_SQRT_2, 0.073_223_304_7, 0.951_056_516_3, 0.414_213_562_4];

/// Highest degree tried by [`ParamTerms::fit`].
const PARAM_DEGREE: usize = 4;

/// The model's [`PencilTerms`] along one axis that is a parameter (the other being the speed),
/// `T(u) = Σ_d C_d u^d` in the axis's scaled coordinate `u ∈ [0, 1]`: eq (6) is affine in
/// `z̄_A` and in the damping coefficients, and most paths enter it polynomially. Exact where
/// it is used: [`ParamTerms::fit`] accepts the polynomial only when it reproduces the derived
/// model at every check point to 1e-12 of each matrix's size (rounding of the model's own
/// arithmetic; a dependence that is not polynomial of degree ≤ 4 misses by far more).
#[derive(Debug, Clone)]
pub(crate) struct ParamTerms {
    /// The coordinate of the parameter axis (0: `x`, 1: `y`).
    axis: usize,
    /// `C_0..C_d`.
    pub(crate) coef: Vec<PencilTerms>,
}

impl ParamTerms {
    /// Sample `terms(u)` at [`PARAM_SAMPLES`] and find the lowest degree `d ≤` [`PARAM_DEGREE`]
    /// whose interpolant (Newton's divided differences on the first `d + 1` samples, then
    /// monomial coefficients) reproduces every other sample within `1e-12` of the largest
    /// entry of that matrix over the samples; `None` when none does or a sample is refused.
    pub(crate) fn fit(axis: usize, terms: impl Fn(f64) -> Result<PencilTerms>) -> Option<ParamTerms> {
        let mut s = Vec::with_capacity(PARAM_SAMPLES.len());
        for u in PARAM_SAMPLES {
            s.push(terms(u).ok()?);
        }
        let n = s[0].n;
        if s.iter().any(|t| t.n != n) {
            return None;
        }
        let mut scale = [0.0f64; 6];
        for t in &s {
            for (q, m) in mats(t).into_iter().enumerate() {
                for row in &m[..n] {
                    for x in &row[..n] {
                        scale[q] = scale[q].max(x.abs());
                    }
                }
            }
        }
        'degree: for d in 0..=PARAM_DEGREE {
            let nodes = &PARAM_SAMPLES[..=d];
            let zero = PencilTerms { n, m: [[0.0; 6]; 6], g: [[[0.0; 6]; 6]; 2], k: [[[0.0; 6]; 6]; 3] };
            let mut coef = vec![zero; d + 1];
            for q in 0..6 {
                for i in 0..n {
                    for j in 0..n {
                        // divided differences, then the Newton form expanded into monomials
                        let mut dd: Vec<f64> = (0..=d).map(|k| mats(&s[k])[q][i][j]).collect();
                        for l in 1..=d {
                            for k in (l..=d).rev() {
                                dd[k] = (dd[k] - dd[k - 1]) / (nodes[k] - nodes[k - l]);
                            }
                        }
                        let mut c = vec![0.0; d + 1];
                        c[0] = dd[d];
                        for k in (0..d).rev() {
                            // c ← c · (u − nodes[k]) + dd[k]
                            for e in (1..=d).rev() {
                                c[e] = c[e - 1] - nodes[k] * c[e];
                            }
                            c[0] = dd[k] - nodes[k] * c[0];
                        }
                        for (e, ce) in c.into_iter().enumerate() {
                            mats_mut(&mut coef[e])[q][i][j] = ce;
                        }
                    }
                }
            }
            let p = ParamTerms { axis, coef };
            for (k, &u) in PARAM_SAMPLES.iter().enumerate().skip(d + 1) {
                let t = p.at(u);
                for q in 0..6 {
                    let (a, b) = (mats(&t)[q], mats(&s[k])[q]);
                    for i in 0..n {
                        for j in 0..n {
                            if (a[i][j] - b[i][j]).abs() > 1e-12 * scale[q] {
                                continue 'degree;
                            }
                        }
                    }
                }
            }
            return Some(p);
        }
        None
    }

    /// `T(u)` (Horner).
    pub(crate) fn at(&self, u: f64) -> PencilTerms {
        let d = self.coef.len() - 1;
        let mut t = self.coef[d];
        let n = t.n;
        for e in (0..d).rev() {
            let c = &self.coef[e];
            let (src, dst) = (mats(c), mats_mut(&mut t));
            for (a, b) in dst.into_iter().zip(src) {
                for i in 0..n {
                    for j in 0..n {
                        a[i][j] = a[i][j] * u + b[i][j];
                    }
                }
            }
        }
        t
    }

    /// `dT/du` (Horner on the derivative).
    fn derivative(&self, u: f64) -> PencilTerms {
        let d = self.coef.len() - 1;
        let n = self.coef[0].n;
        let mut t = PencilTerms { n, m: [[0.0; 6]; 6], g: [[[0.0; 6]; 6]; 2], k: [[[0.0; 6]; 6]; 3] };
        for e in (1..=d).rev() {
            let c = &self.coef[e];
            let (src, dst) = (mats(c), mats_mut(&mut t));
            for (a, b) in dst.into_iter().zip(src) {
                for i in 0..n {
                    for j in 0..n {
                        a[i][j] = a[i][j] * u + e as f64 * b[i][j];
                    }
                }
            }
        }
        t
    }
}

/// Where `|w| = |ω²|` is at most this, a Hopf residual is evaluated on the expanded
/// polynomial (`E(w)`, `O(w)` by Horner) instead of determinants at `λ = ±iω` or `λ = ±√(−w)`,
/// whose `O = Im p(iω)/ω` (or `(p(s) − p(−s))/2s`) loses `log10(1/ω)` digits to cancellation as
/// `ω → 0` (near a Bogdanov–Takens point): at most one digit here.
const W_EXPANDED: f64 = 1e-2;

/// The pencil `M λ² + (G0 + Ω G1) λ + K0 + Ω K1 + Ω² K2` of [`PencilTerms`] at the speed `Ω`.
fn pencil_at(t: &PencilTerms, omega: f64) -> Pencil {
    let mut p = Pencil { n: t.n, m: t.m, g: t.g[0], k: t.k[0] };
    for i in 0..t.n {
        for j in 0..t.n {
            p.g[i][j] += omega * t.g[1][i][j];
            p.k[i][j] += omega * (t.k[1][i][j] + omega * t.k[2][i][j]);
        }
    }
    p
}

/// `det A` of the leading `n × n` block (LU with partial pivoting; 0 when a pivot is exactly 0).
fn det_real(a: &crate::spatial::linear_model::Mat6, n: usize) -> f64 {
    Lu::new(*a, n).map_or(0.0, |lu| lu.det())
}

impl<'a> Plane<'a> {
    /// The plane, with its model along the parameter axis fitted as a polynomial
    /// ([`ParamTerms::fit`]) when the other axis is the speed.
    fn new(spec: &'a SpatialSpec, x: &'a Axis, y: &'a Axis, balls: Balls, omega: Option<f64>) -> Self {
        let mut pl = Plane {
            spec,
            x,
            y,
            balls,
            omega,
            evaluations: std::cell::Cell::new(0),
            determinants: std::cell::Cell::new(0),
            last: std::cell::Cell::new(None),
            models: std::cell::RefCell::new([None, None]),
            dterms: std::cell::RefCell::new([None, None]),
            param: None,
            plane: None,
        };
        if (x.path == OMEGA) != (y.path == OMEGA) {
            let axis = if x.path == OMEGA { 1 } else { 0 };
            pl.param = ParamTerms::fit(axis, |u| {
                let mut vals = [0.0; 2];
                vals[axis] = Plane::value([x, y][axis], u);
                pl.derive(vals)
            });
            pl.plane = pl.param.as_ref().and_then(|p| PlanePolynomial::new(&p.coef));
        }
        pl
    }

    /// The speed `Ω` and the parameter's clamped coordinate at scaled `(u, v)` (with `param`).
    fn plane_coords(&self, u: f64, v: f64) -> (f64, f64) {
        let pa = self.param.as_ref().map_or(0, |p| p.axis);
        let c = [u, v];
        let omega = Plane::value([self.x, self.y][1 - pa], c[1 - pa]).max(crate::spatial::map::OMEGA_FLOOR);
        (omega, c[pa].clamp(0.0, 1.0))
    }

    /// With the plane's polynomial: the coefficients `a_0..a_N` at scaled `(u, v)` and their
    /// exact derivatives along `u` and along `v` (the speed's from `∂a/∂Ω` times its span;
    /// at the clamped ends the derivative of the polynomial continued).
    fn plane_at(&self, u: f64, v: f64) -> Option<Result<([f64; D], [[f64; D]; 2])>> {
        let (pp, param) = (self.plane.as_ref()?, self.param.as_ref()?);
        let (pa, sa) = (param.axis, 1 - param.axis);
        let speed = [self.x, self.y][sa];
        let (omega, pu) = self.plane_coords(u, v);
        self.evaluations.set(self.evaluations.get() + 1);
        Some(match pp.at(omega, pu) {
            None => Err(Error::invalid(self.x.path.clone(), "the mass matrix is singular here")),
            Some((a, dw, du)) => {
                let mut d = [[0.0; D]; 2];
                let span = speed.hi() - speed.lo();
                for k in 0..D {
                    d[sa][k] = dw[k] * span;
                    d[pa][k] = du[k];
                }
                Ok((a, d))
            }
        })
    }

    /// The axis value at the scaled coordinate `u`, never outside the axis's `[lo, hi]` (which
    /// was checked against the field's range): the ends exactly at `u = 0, 1`, and a point the
    /// tracer steps to beyond an edge (a predictor, a difference quotient, a rounding below 0)
    /// evaluates the model on that edge. Without it an axis over a field's full documented range
    /// was refused by that range (`balancer.z=-10000:10000:3`: "must lie in [-10000, 10000] m,
    /// got 10000", `dimensionless.h_s=0:1000:3`: "got -9.5e-33", issue 23).
    fn value(a: &Axis, u: f64) -> f64 {
        if u <= 0.0 {
            a.lo()
        } else if u >= 1.0 {
            a.hi()
        } else {
            (a.lo() + (a.hi() - a.lo()) * u).clamp(a.lo().min(a.hi()), a.lo().max(a.hi()))
        }
    }

    /// Ascending coefficients `a_0..a_N` (`a_N = 1`) at scaled coordinates `(u, v)`.
    fn poly(&self, u: f64, v: f64) -> Result<([f64; D], usize)> {
        if let Some((lu, lv, c, n)) = self.last.get() {
            if lu == u && lv == v {
                return Ok((c, n));
            }
        }
        if let Some(pp) = &self.plane {
            let (omega, pu) = self.plane_coords(u, v);
            self.evaluations.set(self.evaluations.get() + 1);
            let c = pp.value(omega, pu).ok_or_else(|| Error::invalid(self.x.path.clone(), "the mass matrix is singular here"))?;
            self.last.set(Some((u, v, c, pp.states)));
            return Ok((c, pp.states));
        }
        self.evaluations.set(self.evaluations.get() + 1);
        let p = self.pencil(u, v)?;
        let n = p.states();
        let c = pencil_polynomial(&p).ok_or_else(|| Error::invalid(self.x.path.clone(), "the mass matrix is singular here"))?;
        self.last.set(Some((u, v, c, n)));
        Ok((c, n))
    }

    /// The model at scaled coordinates `(u, v)` as a pencil in the speed ([`Pencil::terms`],
    /// exact: eq (6) is quadratic in `Ω`), and the speed there. The model is derived only when
    /// the axes that are not the speed moved since the last two models.
    fn terms(&self, u: f64, v: f64) -> Result<(PencilTerms, f64)> {
        let vals = [Self::value(self.x, u), Self::value(self.y, v)];
        let mut omega = self.omega.unwrap_or(0.0);
        let mut key = [0.0; 2];
        for (c, a) in [self.x, self.y].into_iter().enumerate() {
            if a.path == OMEGA {
                omega = vals[c];
            } else {
                key[c] = vals[c];
            }
        }
        let omega = omega.max(crate::spatial::map::OMEGA_FLOOR);
        let mut cache = self.models.borrow_mut();
        for slot in 0..2 {
            if let Some((k, t)) = cache[slot] {
                if k == key {
                    cache.swap(0, slot);
                    return Ok((t, omega));
                }
            }
        }
        let t = match &self.param {
            Some(p) => p.at([u, v][p.axis].clamp(0.0, 1.0)),
            None => self.derive(vals)?,
        };
        cache[1] = cache[0];
        cache[0] = Some((key, t));
        Ok((t, omega))
    }

    /// The model's terms derived from the spec at the axis values `vals` (the speed's ignored).
    fn derive(&self, vals: [f64; 2]) -> Result<PencilTerms> {
        let mut spec = self.spec.clone();
        for (c, a) in [self.x, self.y].into_iter().enumerate() {
            if a.path != OMEGA {
                spec.set(&a.path, vals[c])?;
            }
        }
        Pencil::terms(&spec.build()?, self.balls)
    }

    fn pencil(&self, u: f64, v: f64) -> Result<Pencil> {
        let (t, omega) = self.terms(u, v)?;
        Ok(pencil_at(&t, omega))
    }

    fn eigen(&self, u: f64, v: f64) -> Result<Vec<Complex64>> {
        let p = self.pencil(u, v)?;
        eigenvalues(&p.state_matrix(), p.states()).map_err(|_| Error::NoConvergence { omega: Plane::value(self.y, v) })
    }

    /// Residual of a condition at `z` (`(u, v)` for a fold, `(u, v, w)` for Hopf), with
    /// `p(λ) = det(M λ² + G λ + K)/det M` (the characteristic polynomial, `a_N = 1`) evaluated
    /// as determinants by elimination (a fraction of an expansion's cost):
    /// - fold: `a_0 = p(0) = det K/det M`;
    /// - Hopf, `w > 0`: `p(iω) = E(w) + iω O(w)` with `ω = √w`, so `E = Re p(iω)`,
    ///   `O = Im p(iω)/ω`;
    /// - Hopf, `w < 0` (a real pair `±s`, `s = √(−w)`): `p(±s) = E(w) ± s O(w)`, so
    ///   `E = (p(s) + p(−s))/2`, `O = (p(s) − p(−s))/2s`;
    /// - Hopf, `|w| ≤` [`W_EXPANDED`]: `E`, `O` by Horner on the expanded polynomial.
    fn residual(&self, kind: CurveKind, z: &[f64]) -> Result<[f64; 2]> {
        if self.plane.is_some() {
            // the plane's polynomial: a_0 (fold), E(w) and O(w) by Horner (Hopf)
            let (a, n) = self.poly(z[0], z[1])?;
            return Ok(residual_of_poly(kind, &a, n, z[2]));
        }
        if kind == CurveKind::Hopf && z[2].abs() <= W_EXPANDED {
            let (a, n) = self.poly(z[0], z[1])?;
            return Ok(residual_of_poly(kind, &a, n, z[2]));
        }
        let p = self.pencil(z[0], z[1])?;
        self.residual_of(&p, kind, z[2])
    }

    /// [`Plane::residual`] of the pencil `p` (with `w` for Hopf).
    fn residual_of(&self, p: &Pencil, kind: CurveKind, w: f64) -> Result<[f64; 2]> {
        if kind == CurveKind::Hopf && w.abs() <= W_EXPANDED {
            self.evaluations.set(self.evaluations.get() + 1);
            let a = pencil_polynomial(p).ok_or_else(|| Error::invalid(self.x.path.clone(), "the mass matrix is singular here"))?;
            let r = eo(&a, p.states(), w);
            return Ok([r[0], r[1]]);
        }
        self.determinants.set(self.determinants.get() + 1);
        let n = p.n;
        let dm = det_real(&p.m, n);
        if dm == 0.0 || !dm.is_finite() {
            return Err(Error::invalid(self.x.path.clone(), "the mass matrix is singular here"));
        }
        Ok(match kind {
            CurveKind::Fold => [det_real(&p.k, n) / dm, 0.0],
            CurveKind::Hopf if w > 0.0 => {
                // P(iω) = K − w M + iω G
                let om = w.sqrt();
                let mut a = [[Complex64::new(0.0, 0.0); 6]; 6];
                for i in 0..n {
                    for j in 0..n {
                        a[i][j] = Complex64::new(p.k[i][j] - w * p.m[i][j], om * p.g[i][j]);
                    }
                }
                let q = det_dual::<0>(&a, &[], n).0 / dm;
                [q.re, q.im / om]
            }
            CurveKind::Hopf => {
                // P(±s) = K − w M ± s G (s² = −w)
                let s = (-w).sqrt();
                let (mut ap, mut am) = (p.k, p.k);
                for i in 0..n {
                    for j in 0..n {
                        let base = p.k[i][j] - w * p.m[i][j];
                        ap[i][j] = base + s * p.g[i][j];
                        am[i][j] = base - s * p.g[i][j];
                    }
                }
                let (qp, qm) = (det_real(&ap, n) / dm, det_real(&am, n) / dm);
                [0.5 * (qp + qm), (qp - qm) / (2.0 * s)]
            }
        })
    }

    /// Whether the point is on the stability boundary (all other roots left of −δ,
    /// [`boundary_flag`] on the polynomial at the point).
    fn on_boundary(&self, kind: CurveKind, z: &[f64; 3]) -> Result<bool> {
        if kind == CurveKind::Hopf && z[2] <= 0.0 {
            return Ok(false);
        }
        let (a, n) = self.poly(z[0], z[1])?;
        Ok(boundary_flag(kind, z, &a, n))
    }
}

/// Whether a point of a curve is on the stability boundary, from the polynomial `a` there (or
/// within 1e-8 of it): the critical pair `λ² + w` (Hopf, `w > 0`) or root `λ` (fold) divided
/// out, Routh's count of the quotient's roots right of −δ is 0 (every other eigenvalue has
/// `Re λ < −δ`). At the point itself the same as Routh's count of `p` being 2 (or 1); at an
/// iterate ≤ 1e-8 away the pair is off the axis by ~1e-8, which the quotient does not see.
fn boundary_flag(kind: CurveKind, z: &[f64; 3], a: &[f64; D], n: usize) -> bool {
    if kind == CurveKind::Hopf && z[2] <= 0.0 {
        return false;
    }
    let mut c = [0.0; D];
    for k in 0..=n {
        c[k] = a[n - k];
    }
    let m = if kind == CurveKind::Hopf { n - 2 } else { n - 1 };
    let mut q = [0.0; D];
    for k in 0..=m {
        q[k] = c[k] - if kind == CurveKind::Hopf && k >= 2 { z[2] * q[k - 2] } else { 0.0 };
    }
    routh_count_right_of(&q[..=m], -1e-7) == Some(0)
}

/// `E(w)`, `O(w)` of the module docs and their derivatives in `w`.
fn eo(a: &[f64; D], n: usize, w: f64) -> [f64; 4] {
    let (mut e, mut o, mut de, mut dd) = (0.0, 0.0, 0.0, 0.0);
    for k in (0..=n / 2).rev() {
        // Horner in x = −w: d/dw = −d/dx
        de = de * (-w) - e;
        e = e * (-w) + a[2 * k];
        if 2 * k < n {
            dd = dd * (-w) - o;
            o = o * (-w) + a[2 * k + 1];
        }
    }
    [e, o, de, dd]
}

/// Unknowns and equations of a condition.
fn dims(kind: CurveKind) -> (usize, usize) {
    match kind {
        CurveKind::Fold => (2, 1),
        CurveKind::Hopf => (3, 2),
    }
}

/// The residual ([`Plane::residual`]) and its Jacobian ([`jacobian`]) at `z`. With the plane's
/// polynomial both come from one evaluation with derivatives ([`PlanePolynomial::at`], whose
/// coefficients are the same numbers as [`PlanePolynomial::value`]'s), kept as the plane's last
/// polynomial, so that a later [`Plane::poly`] at the same point costs nothing.
fn residual_jacobian(pl: &Plane, kind: CurveKind, z: &[f64; 3]) -> Result<([f64; 2], [[f64; 3]; 2])> {
    if let Some(r) = pl.plane_at(z[0], z[1]) {
        let (a, d) = r?;
        let n = pl.plane.as_ref().map_or(0, |p| p.states);
        pl.last.set(Some((z[0], z[1], a, n)));
        return Ok((residual_of_poly(kind, &a, n, z[2]), jacobian_of_poly(kind, &a, &d, n, z[2])));
    }
    let f = pl.residual(kind, z)?;
    Ok((f, jacobian(pl, kind, z, &f)?))
}

/// The residual of a condition from the coefficients `a` (`a_0` for a fold; `E(w)`, `O(w)` for Hopf).
fn residual_of_poly(kind: CurveKind, a: &[f64; D], n: usize, w: f64) -> [f64; 2] {
    match kind {
        CurveKind::Fold => [a[0], 0.0],
        CurveKind::Hopf => {
            let r = eo(a, n, w);
            [r[0], r[1]]
        }
    }
}

/// The exact Jacobian of [`residual_of_poly`] from the coefficients `a` and their derivatives
/// `d` along `u` and `v` (the residuals are linear in the coefficients; in `w` by Horner).
fn jacobian_of_poly(kind: CurveKind, a: &[f64; D], d: &[[f64; D]; 2], n: usize, w: f64) -> [[f64; 3]; 2] {
    let mut j = [[0.0; 3]; 2];
    match kind {
        CurveKind::Fold => {
            j[0][0] = d[0][0];
            j[0][1] = d[1][0];
        }
        CurveKind::Hopf => {
            for c in 0..2 {
                let r = eo(&d[c], n, w);
                j[0][c] = r[0];
                j[1][c] = r[1];
            }
            let r = eo(a, n, w);
            j[0][2] = r[2];
            j[1][2] = r[3];
        }
    }
    j
}

/// Jacobian of the residual by forward differences (the corrector's accuracy does not depend
/// on it, only its speed): a step along the speed or `w` derives no model ([`Plane::terms`]);
/// in `w` exact where the residual is the expanded polynomial's.
fn jacobian(pl: &Plane, kind: CurveKind, z: &[f64; 3], f0: &[f64; 2]) -> Result<[[f64; 3]; 2]> {
    let (nz, nf) = dims(kind);
    let mut j = [[0.0; 3]; 2];
    if let Some(r) = pl.plane_at(z[0], z[1]) {
        // exact: the residuals are linear in the coefficients, whose derivatives are exact
        let (a, d) = r?;
        let n = pl.plane.as_ref().map_or(0, |p| p.states);
        return Ok(jacobian_of_poly(kind, &a, &d, n, z[2]));
    }
    let exact_w = kind == CurveKind::Hopf && z[2].abs() <= W_EXPANDED;
    if exact_w {
        // in w: exact (the polynomial does not depend on w)
        let (a, n) = pl.poly(z[0], z[1])?;
        let r = eo(&a, n, z[2]);
        j[0][2] = r[2];
        j[1][2] = r[3];
    }
    for c in 0..nz {
        if c == 2 && exact_w {
            continue;
        }
        // a forward difference, backward on the square's far edge (inside the axis range)
        let h = 1e-7 * (1.0 + z[c].abs());
        let h = if c < 2 && z[c] + h > 1.0 { -h } else { h };
        let mut zz = *z;
        zz[c] += h;
        let along_parameter = c < 2 && [pl.x, pl.y][c].path != OMEGA;
        if along_parameter {
            // the model's polynomial along the axis: its exact derivative at this iterate
            if let Some(p) = pl.param.as_ref().filter(|p| p.axis == c) {
                pl.dterms.borrow_mut()[c] = Some(p.derivative(z[c].clamp(0.0, 1.0)));
            }
        }
        let f = match along_parameter.then(|| pl.dterms.borrow()[c]).flatten() {
            // the pencil moved along the stored derivative: no model derived
            Some(dt) => {
                let (t, om) = pl.terms(z[0], z[1])?;
                let (mut p, dp) = (pencil_at(&t, om), pencil_at(&dt, om));
                for i in 0..p.n {
                    for k in 0..p.n {
                        p.m[i][k] += h * dp.m[i][k];
                        p.g[i][k] += h * dp.g[i][k];
                        p.k[i][k] += h * dp.k[i][k];
                    }
                }
                pl.residual_of(&p, kind, z[2])?
            }
            None => {
                if along_parameter {
                    let (t0, _) = pl.terms(z[0], z[1])?;
                    let (t1, _) = pl.terms(zz[0], zz[1])?;
                    let mut dt = t1;
                    let d = |a: &mut [[f64; 6]; 6], b: &[[f64; 6]; 6]| {
                        for i in 0..t0.n {
                            for k in 0..t0.n {
                                a[i][k] = (a[i][k] - b[i][k]) / h;
                            }
                        }
                    };
                    d(&mut dt.m, &t0.m);
                    for q in 0..2 {
                        d(&mut dt.g[q], &t0.g[q]);
                    }
                    for q in 0..3 {
                        d(&mut dt.k[q], &t0.k[q]);
                    }
                    pl.dterms.borrow_mut()[c] = Some(dt);
                }
                pl.residual(kind, &zz)?
            }
        };
        for r in 0..nf {
            j[r][c] = (f[r] - f0[r]) / h;
        }
    }
    Ok(j)
}

/// Unit tangent: the null vector of the `nf × nz` Jacobian, oriented along `prev`.
fn tangent(kind: CurveKind, j: &[[f64; 3]; 2], prev: Option<&[f64; 3]>) -> [f64; 3] {
    let mut t = match kind {
        CurveKind::Fold => [-j[0][1], j[0][0], 0.0],
        CurveKind::Hopf => [j[0][1] * j[1][2] - j[0][2] * j[1][1], j[0][2] * j[1][0] - j[0][0] * j[1][2], j[0][0] * j[1][1] - j[0][1] * j[1][0]],
    };
    let nrm = t.iter().map(|x| x * x).sum::<f64>().sqrt();
    for x in t.iter_mut() {
        *x /= nrm;
    }
    if let Some(p) = prev {
        if t.iter().zip(p).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
            for x in t.iter_mut() {
                *x = -*x;
            }
        }
    }
    t
}

/// Solve the square system `a x = b` (≤ 3×3) by elimination with partial pivoting.
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3], n: usize) -> Option<[f64; 3]> {
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[p][k] == 0.0 || !a[p][k].is_finite() {
            return None;
        }
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..n {
            let f = a[i][k] / a[k][k];
            for c in k..n {
                a[i][c] -= f * a[k][c];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = [0.0; 3];
    for k in (0..n).rev() {
        let mut s = b[k];
        for c in k + 1..n {
            s -= a[k][c] * x[c];
        }
        x[k] = s / a[k][k];
    }
    Some(x)
}

/// Newton's method on the condition plus the hyperplane `t · (z − z0) = 0` (pseudo-arclength
/// corrector; with `t` a coordinate vector it holds that coordinate fixed). The Jacobian is
/// `j0` (the previous point's, when given) for the first iteration, then refreshed at every
/// iterate while the steps are above 1e-5, stop contracting, or were taken more than 1e-6 from
/// the Jacobian's point, and kept once they are small (the chord method: its contraction is
/// then ~1e-5 times the curvature). Stops once the error left after a step, estimated from the
/// convergence (Newton's `K s²` with `K ≈ s/s_prev²`; the chord method's `s θ/(1 − θ)`,
/// `θ = s/s_prev`), is below 1e-12 with the step below 1e-6, or once a step is below 1e-10, in
/// the plane scaled to the unit square; gives up (`None`: the caller shortens its step) when
/// a step from the fourth on is more than a quarter of the one before. Returns the point and the Jacobian there
/// (computed at the point, or at an iterate within 1e-6 of it: the tangent is the curve's).
fn correct(pl: &Plane, kind: CurveKind, z0: [f64; 3], t: &[f64; 3], j0: Option<&[[f64; 3]; 2]>) -> Result<Option<([f64; 3], [[f64; 3]; 2])>> {
    // the derivatives of the model stored by this correction's first Jacobian serve it alone
    pl.dterms.replace([None, None]);
    let r = newton(pl, kind, z0, t, j0);
    pl.dterms.replace([None, None]);
    r
}

/// The iteration of [`correct`].
fn newton(pl: &Plane, kind: CurveKind, z0: [f64; 3], t: &[f64; 3], j0: Option<&[[f64; 3]; 2]>) -> Result<Option<([f64; 3], [[f64; 3]; 2])>> {
    let (nz, nf) = dims(kind);
    let mut z = z0;
    let mut j = j0.map(|j| (*j, [f64::INFINITY; 3]));
    let mut last = f64::INFINITY;
    for iteration in 0..16 {
        // a fresh Jacobian: with the residual, from one evaluation of the plane's polynomial
        let (f, jz, at, fresh) = match j {
            Some((jz, at)) => (pl.residual(kind, &z)?, jz, at, false),
            None => {
                let (f, jz) = residual_jacobian(pl, kind, &z)?;
                (f, jz, z, true)
            }
        };
        let mut a = [[0.0; 3]; 3];
        let mut b = [0.0; 3];
        for r in 0..nf {
            a[r][..nz].copy_from_slice(&jz[r][..nz]);
            b[r] = -f[r];
        }
        a[nf][..nz].copy_from_slice(&t[..nz]);
        b[nf] = -(0..nz).map(|c| t[c] * (z[c] - z0[c])).sum::<f64>();
        let Some(dz) = solve3(a, b, nz) else { return Ok(None) };
        let mut step = 0.0f64;
        for c in 0..nz {
            z[c] += dz[c];
            step = step.max(dz[c].abs() / if c == 2 { 1.0 + z[2].abs() } else { 1.0 });
        }
        if !z.iter().all(|x| x.is_finite()) || step > 0.5 {
            return Ok(None);
        }
        // the error left after this step: Newton's (a Jacobian at this iterate) converges
        // quadratically, e' ≈ K s² with K ≈ s/s_prev² (an over-estimate when the previous step
        // was a chord step, which contracts less than Newton's); the chord method linearly,
        // e' ≈ s θ/(1 − θ) with θ = s/s_prev
        let left = if !last.is_finite() {
            f64::INFINITY
        } else if fresh {
            step * (step / last).powi(2)
        } else if step < last {
            step * step / (last - step)
        } else {
            f64::INFINITY
        };
        if step < 1e-10 || (step <= 1e-6 && left <= 1e-12) {
            // the tangent at the point: from a Jacobian computed there (or within 1e-6)
            if (0..nz).any(|c| (z[c] - at[c]).abs() > 1e-6) {
                return Ok(Some((z, residual_jacobian(pl, kind, &z)?.1)));
            }
            return Ok(Some((z, jz)));
        }
        // a fresh Jacobian at the next iterate unless the steps are small and contracting
        if iteration >= 3 && step > 0.25 * last {
            // Newton's method from a good start has converged by now (quadratically); steps that
            // still do not shrink fourfold wander, or creep towards a singular point of the
            // curve: a shorter step along the curve is cheaper than more iterations
            return Ok(None);
        }
        // a fresh Jacobian at the next iterate unless the steps are small and contracting and
        // the Jacobian's point is within 1e-6 (the point's tangent needs one that near anyway)
        let near = (0..nz).all(|c| (z[c] - at[c]).abs() <= 1e-6);
        j = (step < 1e-5 && step < 0.25 * last && near).then_some((jz, at));
        last = step;
    }
    Ok(None)
}

/// Trace the stability boundary of `spec` over the plane `x × y`: each an [`Axis`] (a parameter
/// path or `omega`) of which the range `[first, last]` is traced (the values between are not
/// visited; [`Axis::range`] gives the two ends alone, a map's axis may be passed as it is).
///
/// ```
/// use autobal::spatial::boundary::{trace_boundary, Axis, TraceSettings};
/// use autobal::spatial::params::{AnisotropyInput, DimensionlessInput};
/// use autobal::spatial::paths::{SpatialInput, SpatialSpec};
/// use autobal::spatial::inertia::AnisotropyMethod;
///
/// let spec = SpatialSpec {
///     input: SpatialInput::Dimensionless(DimensionlessInput {
///         c_sigma: 0.75, rho_s: 0.4, l_left: 0.8, z_a: 0.8,
///         anisotropy: AnisotropyInput::Direct(0.1), h_x: 0.05, h_s: 0.1,
///         method: AnisotropyMethod::Exact, direct_balls: Some((0.05, 0.5)),
///     }),
///     delta_a_override: None,
/// };
/// let x = Axis::range("dimensionless.z_a", -2.0, 2.0);
/// let y = Axis::range("omega", 0.05, 4.5);
/// let b = trace_boundary(&spec, &x, &y, &TraceSettings::default()).unwrap();
/// assert!(b.curves.iter().any(|c| c.points.iter().any(|p| p.on_boundary)));
/// ```
pub fn trace_boundary(spec: &SpatialSpec, x: &Axis, y: &Axis, s: &TraceSettings) -> Result<Boundary> {
    trace_boundary_with(spec, x, y, s, &Control::none())
}

/// [`trace_boundary`] under `control` (asked before each line of the coarse grid and before
/// each curve is traced): when it stops, the result holds the curves traced so far, `complete`
/// is `false` and `stopped` says why. Its progress observer hears `(lines searched, lines)`
/// after each line and after each curve traced.
pub fn trace_boundary_with(spec: &SpatialSpec, x: &Axis, y: &Axis, s: &TraceSettings, control: &Control) -> Result<Boundary> {
    s.validate()?;
    for a in [x, y] {
        if !(a.lo().is_finite() && a.hi().is_finite() && a.hi() > a.lo()) {
            return Err(Error::invalid(a.path.clone(), "the range must be finite with hi > lo"));
        }
        if a.path != OMEGA {
            let mut t = spec.clone();
            t.set(&a.path, a.lo())?;
        }
    }
    if x.path == OMEGA && y.path == OMEGA {
        return Err(Error::invalid(OMEGA, "only one axis can be the speed"));
    }
    if x.path != OMEGA && y.path != OMEGA && s.omega.is_none() {
        return Err(Error::invalid(OMEGA, "required when neither axis is the speed"));
    }
    let pl = Plane::new(spec, x, y, s.balls, s.omega);
    let mut out = Boundary { x: x.clone(), y: y.clone(), curves: vec![], codim2: vec![], evaluations: 0, complete: true, stopped: None };
    // 1. lines across the plane (along the speed if there is one): changes of verdict
    let first_dir = if x.path == OMEGA { 1 } else { 0 };
    let mut queue: Vec<(CurveKind, [f64; 3])> = vec![];
    // the first pass's polynomials in Ω, one per line along the speed
    let mut speed_lines: Vec<Option<SpeedPolynomial>> = vec![];
    // 2. then lines the other way (closed curves between the first lines); a change of verdict
    // that a traced boundary already crosses is not looked at again
    let all_lines = (s.coarse.0.max(2) + s.coarse.1.max(2)) as u64;
    let mut searched = 0;
    'search: for dir in [first_dir, 1 - first_dir] {
        let lines = if dir == 0 { s.coarse.0.max(2) } else { s.coarse.1.max(2) };
        for li in 0..lines {
            if let Some(why) = control.should_stop() {
                (out.complete, out.stopped) = (false, Some(why));
                break 'search;
            }
            for raw in line_crossings(&pl, s, dir, li, &out.curves, &mut speed_lines)? {
                if let Some(seed) = seed_at(&pl, raw.0, raw.1, dir)? {
                    queue.push(seed);
                }
                if let Some(why) = process(&pl, s, &mut queue, &mut out, control, (searched, all_lines))? {
                    (out.complete, out.stopped) = (false, Some(why));
                    break 'search;
                }
            }
            searched += 1;
            control.report(searched, all_lines);
        }
    }
    // one codimension-two point found from both of its curves is one point
    let mut merged: Vec<Codim2Point> = vec![];
    for p in out.codim2.drain(..) {
        let dup = merged.iter().any(|q| q.kind == p.kind && ((q.x - p.x) / (x.hi() - x.lo())).abs() < 1e-6 && ((q.y - p.y) / (y.hi() - y.lo())).abs() < 1e-6);
        if !dup {
            merged.push(p);
        }
    }
    out.codim2 = merged;
    out.evaluations = pl.evaluations.get() + pl.determinants.get();
    Ok(out)
}

/// Trace the queued seeds that no traced curve already contains; `Some(why)` when the control
/// asked to stop; `progress` is reported after each curve.
fn process(
    pl: &Plane,
    s: &TraceSettings,
    queue: &mut Vec<(CurveKind, [f64; 3])>,
    out: &mut Boundary,
    control: &Control,
    progress: (u64, u64),
) -> Result<Option<StopReason>> {
    let mut guard = 0;
    while let Some((kind, z)) = queue.pop() {
        if let Some(why) = control.should_stop() {
            return Ok(Some(why));
        }
        guard += 1;
        if guard > 100 || out.curves.len() > 200 {
            break;
        }
        if out.curves.iter().any(|c| c.kind == kind && near_curve(c, pl, &z)) {
            continue;
        }
        if let Some(curve) = trace_curve(pl, kind, z, s.max_step, &mut out.codim2, queue)? {
            out.curves.push(curve);
            control.report(progress.0, progress.1);
        }
    }
    Ok(None)
}

/// Whether the segment `a → b` (scaled) crosses the stability-boundary part of a traced curve.
fn crossed(curves: &[BoundaryCurve], pl: &Plane, a: (f64, f64), b: (f64, f64)) -> bool {
    let sc = |p: &CurvePoint| ((p.x - pl.x.lo()) / (pl.x.hi() - pl.x.lo()), (p.y - pl.y.lo()) / (pl.y.hi() - pl.y.lo()));
    let cross = |o: (f64, f64), p: (f64, f64), q: (f64, f64)| (p.0 - o.0) * (q.1 - o.1) - (p.1 - o.1) * (q.0 - o.0);
    curves.iter().any(|c| {
        c.points.windows(2).filter(|w| w[0].on_boundary && w[1].on_boundary).any(|w| {
            let (c0, c1) = (sc(&w[0]), sc(&w[1]));
            let d1 = cross(c0, c1, a);
            let d2 = cross(c0, c1, b);
            let d3 = cross(a, b, c0);
            let d4 = cross(a, b, c1);
            d1 * d2 <= 0.0 && d3 * d4 <= 0.0
        })
    })
}

/// Whether `z` (scaled) lies on the curve already traced (within the step of its points).
fn near_curve(c: &BoundaryCurve, pl: &Plane, z: &[f64; 3]) -> bool {
    let sc = |p: &CurvePoint| ((p.x - pl.x.lo()) / (pl.x.hi() - pl.x.lo()), (p.y - pl.y.lo()) / (pl.y.hi() - pl.y.lo()));
    for k in 0..c.points.len().saturating_sub(1) {
        let (a, b) = (sc(&c.points[k]), sc(&c.points[k + 1]));
        // distance from z to the segment ab, and the same pair frequency
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 { (((z[0] - a.0) * dx + (z[1] - a.1) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
        let (px, py) = (a.0 + t * dx, a.1 + t * dy);
        let d = ((z[0] - px).powi(2) + (z[1] - py).powi(2)).sqrt();
        let w = c.points[k].w + t * (c.points[k + 1].w - c.points[k].w);
        if d < 1e-3 + 0.05 * l2.sqrt()
            && (c.kind == CurveKind::Fold || (w - z[2]).abs() < 1e-3 * (1.0 + w.abs()) + 0.05 * (c.points[k + 1].w - c.points[k].w).abs())
        {
            return true;
        }
    }
    false
}

/// Changes of verdict along the lines of a coarse grid in direction `dir` (0: lines along the
/// second axis at fixed first coordinate; 1: the other way), located by bisection to 1e-9 of the
/// unit square along the speed and to 1e-6 across it (the seed is then corrected by Newton's
/// method): points `(u, v)`. Along the speed the line's exact polynomial in `Ω` answers
/// every point, and the analytic critical speeds and the middles of their split pairs are added
/// to the line; across it, the nodes are those lines' (`speed_lines`, filled by the first pass)
/// and are answered by their polynomials. A segment that a traced curve crosses is not bisected.
fn line_crossings(
    pl: &Plane,
    s: &TraceSettings,
    dir: usize,
    li: usize,
    traced: &[BoundaryCurve],
    speed_lines: &mut Vec<Option<SpeedPolynomial>>,
) -> Result<Vec<(f64, f64)>> {
    let (nx, ny) = (s.coarse.0.max(2), s.coarse.1.max(2));
    let (nl, np) = if dir == 0 { (nx, ny) } else { (ny, nx) };
    let along = if dir == 0 { pl.y } else { pl.x };
    let fixed = if dir == 0 { pl.x } else { pl.y };
    let mut out = vec![];
    {
        let c = li as f64 / (nl - 1) as f64;
        let at = |t: f64| if dir == 0 { (c, t) } else { (t, c) };
        let mut ts: Vec<f64> = (0..np).map(|k| k as f64 / (np - 1) as f64).collect();
        // the line's model when the line runs along the speed
        let line_poly = if along.path == OMEGA {
            let mut spec = pl.spec.clone();
            for (a, val) in [(pl.x, at(0.0).0), (pl.y, at(0.0).1)] {
                if a.path != OMEGA {
                    spec.set(&a.path, Plane::value(a, val))?;
                }
            }
            let m = spec.build()?;
            for d in [m.anisotropy.used, m.delta_a0] {
                let roots = critical_speeds_at(&m, d);
                for kind in [ModeKind::Transverse, ModeKind::Angular] {
                    let pair: Vec<f64> = roots.iter().filter(|r| r.1 == kind).map(|r| r.0).collect();
                    let mid = if pair.len() == 2 { Some(0.5 * (pair[0] + pair[1])) } else { None };
                    for w in pair.iter().chain(mid.iter()) {
                        ts.push((w - along.lo()) / (along.hi() - along.lo()));
                    }
                }
            }
            ts.retain(|t| (0.0..=1.0).contains(t));
            ts.sort_by(f64::total_cmp);
            ts.dedup();
            match &pl.plane {
                // the plane's polynomial at the line's parameter value: no expansion
                Some(pp) => pp.speed_polynomial(pl.plane_coords(at(0.0).0, at(0.0).1).1),
                None => SpeedPolynomial::new(&Pencil::terms(&m, pl.balls)?),
            }
        } else {
            None
        };
        let stable = |t: f64| -> Result<bool> {
            let c = match &line_poly {
                Some(sp) => {
                    let c = sp.at(Plane::value(along, t).max(crate::spatial::map::OMEGA_FLOOR));
                    (c, sp.states)
                }
                None => {
                    let (u, v) = at(t);
                    let (a, n) = pl.poly(u, v)?;
                    let mut cc = [0.0; D];
                    for k in 0..=n {
                        cc[k] = a[n - k];
                    }
                    (cc, n)
                }
            };
            Ok(crate::linalg::eigen::routh_hurwitz_stable(&c.0[..=c.1]))
        };
        // a line at a fixed speed across the lines along the speed: its nodes are theirs, each
        // answered by that line's polynomial in Ω (no expansion)
        let reuse = fixed.path == OMEGA && along.path != OMEGA && speed_lines.len() == np && ts.len() == np;
        let node = |k: usize| -> Result<bool> {
            match speed_lines.get(k) {
                Some(Some(sp)) if reuse => {
                    let c = sp.at(Plane::value(fixed, c).max(crate::spatial::map::OMEGA_FLOOR));
                    Ok(crate::linalg::eigen::routh_hurwitz_stable(&c[..=sp.states]))
                }
                _ => stable(ts[k]),
            }
        };
        // bisection to 1e-9 of the line along the speed (its polynomial answers each point),
        // to 1e-6 across it (each point an expansion): the seed is then corrected onto its
        // condition by Newton's method from there
        let tol = if line_poly.is_some() { 1e-9 } else { 1e-6 };
        let mut prev = node(0)?;
        for k in 1..ts.len() {
            let cur = node(k)?;
            if cur != prev && !crossed(traced, pl, at(ts[k - 1]), at(ts[k])) {
                let (mut lo, mut hi) = (ts[k - 1], ts[k]);
                while hi - lo > tol {
                    let mid = 0.5 * (lo + hi);
                    if stable(mid)? == prev {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                out.push(at(0.5 * (lo + hi)));
            }
            prev = cur;
        }
        if along.path == OMEGA {
            if speed_lines.len() <= li {
                speed_lines.resize(li + 1, None);
            }
            speed_lines[li] = line_poly;
        }
    }
    Ok(out)
}

/// Correct a boundary point found by bisection onto its condition, the line's fixed coordinate
/// held fixed.
fn seed_at(pl: &Plane, u: f64, v: f64, dir: usize) -> Result<Option<(CurveKind, [f64; 3])>> {
    let ev = pl.eigen(u, v)?;
    let crit = ev.iter().copied().max_by(|a, b| a.re.total_cmp(&b.re)).unwrap_or_default();
    let kind = if crit.im.abs() < 1e-6 { CurveKind::Fold } else { CurveKind::Hopf };
    let z0 = [u, v, crit.im * crit.im];
    let fix = if dir == 0 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    Ok(correct(pl, kind, z0, &fix, None)?.map(|(z, _)| (kind, z)))
}

/// Follow the curve through `z0` in both directions.
fn trace_curve(
    pl: &Plane,
    kind: CurveKind,
    z0: [f64; 3],
    max_step: f64,
    codim2: &mut Vec<Codim2Point>,
    queue: &mut Vec<(CurveKind, [f64; 3])>,
) -> Result<Option<BoundaryCurve>> {
    let (_, j) = residual_jacobian(pl, kind, &z0)?;
    let t0 = tangent(kind, &j, None);
    let mut halves: Vec<(Vec<Traced>, bool)> = vec![];
    for sign in [1.0, -1.0] {
        let t = t0.map(|x| sign * x);
        let (pts, closed) = march(pl, kind, z0, t, max_step)?;
        let closed_loop = closed;
        halves.push((pts, closed_loop));
        if closed_loop {
            break;
        }
    }
    let closed = halves[0].1;
    let mut traced: Vec<Traced> = vec![];
    if halves.len() == 2 {
        traced.extend(halves[1].0.iter().rev());
        traced.extend(&halves[0].0[1..]);
    } else {
        traced = halves.remove(0).0;
    }
    if traced.len() < 2 {
        return Ok(None);
    }
    // the spectrum at the last end of a chord searched for a crossing (the next chord's start)
    let mut spectra: Option<([f64; 3], Vec<Complex64>)> = None;
    // stability-boundary flags (from the polynomial the corrector evaluated last, within 1e-8
    // of the point, where there is one), and codimension-two points where they change
    let mut flags = Vec::with_capacity(traced.len());
    for (z, near) in &traced {
        flags.push(match near {
            Some((a, n)) => boundary_flag(kind, z, a, *n),
            None => pl.on_boundary(kind, z)?,
        });
    }
    let pts: Vec<[f64; 3]> = traced.iter().map(|p| p.0).collect();
    for k in 0..pts.len() - 1 {
        let (a, b) = (pts[k], pts[k + 1]);
        if kind == CurveKind::Hopf && (a[2] > 0.0) != (b[2] > 0.0) {
            // Bogdanov–Takens: w = 0, interpolated along the chord, then corrected onto the
            // Hopf condition with w held at 0 (a0 = a1 = 0: a double zero eigenvalue); the
            // interpolation alone was 1.8e-3 of the plane off on the bench plane, where a
            // tip's chord is long. Kept only within the chord's length of the interpolation.
            let t = a[2] / (a[2] - b[2]);
            let p0 = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
            let chord = (b[0] - a[0]).hypot(b[1] - a[1]);
            let p = match correct(pl, kind, [p0[0], p0[1], 0.0], &[0.0, 0.0, 1.0], None)? {
                Some((z, _)) if z[2] == 0.0 && (z[0] - p0[0]).hypot(z[1] - p0[1]) <= chord => [z[0], z[1]],
                _ => p0,
            };
            codim2.push(Codim2Point { kind: Codim2Kind::BogdanovTakens, x: Plane::value(pl.x, p[0]), y: Plane::value(pl.y, p[1]) });
            continue;
        }
        // (a chord from a codimension-two point already found, such as the start of the other
        // curve through it, changes its flag at that point: nothing to locate)
        let known = |z: &[f64; 3]| {
            let sc = |v: f64, a: &Axis| (v - a.lo()) / (a.hi() - a.lo());
            codim2.iter().any(|c| (sc(c.x, pl.x) - z[0]).abs() <= 1e-9 && (sc(c.y, pl.y) - z[1]).abs() <= 1e-9)
        };
        if flags[k] != flags[k + 1] && (kind == CurveKind::Fold || (a[2] > 0.0 && b[2] > 0.0)) && !known(&a) && !known(&b) {
            if let Some((p, other)) = locate_crossing(pl, kind, a, b, &mut spectra)? {
                let k2 = if other.im.abs() < 1e-6 || kind == CurveKind::Fold && other.im.abs() > 1e-6 { Codim2Kind::FoldHopf } else { Codim2Kind::DoubleHopf };
                codim2.push(Codim2Point { kind: k2, x: Plane::value(pl.x, p[0]), y: Plane::value(pl.y, p[1]) });
                // the other curve through the point
                let other_kind = if other.im.abs() < 1e-6 { CurveKind::Fold } else { CurveKind::Hopf };
                queue.push((other_kind, [p[0], p[1], other.im * other.im]));
            }
        }
    }
    let points = pts
        .iter()
        .zip(&flags)
        .map(|(z, &f)| CurvePoint {
            x: Plane::value(pl.x, z[0]),
            y: Plane::value(pl.y, z[1]),
            w: if kind == CurveKind::Hopf { z[2] } else { 0.0 },
            on_boundary: f,
        })
        .collect();
    Ok(Some(BoundaryCurve { kind, points, closed }))
}

/// Where along the chord `a → b` (corrected onto the curve) another eigenvalue crosses the
/// axis: regula falsi (Illinois) on its real part. Returns the point and that eigenvalue.
/// `last` holds the spectrum at the end of the chord searched before (continued from, when it
/// is near `a`), and receives the spectrum at `b`.
fn locate_crossing(
    pl: &Plane,
    kind: CurveKind,
    a: [f64; 3],
    b: [f64; 3],
    last: &mut Option<([f64; 3], Vec<Complex64>)>,
) -> Result<Option<([f64; 3], Complex64)>> {
    let d: [f64; 3] = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let nrm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    let t = d.map(|x| x / nrm);
    // the spectrum at a point: continued from `from` (a spectrum nearby) by the Aberth–Ehrlich
    // iteration on the point's polynomial where it certifies every root (disjoint inclusion
    // disks), else the eigenvalues of the state matrix (QR)
    let spectrum = |z: &[f64; 3], from: Option<&[Complex64]>| -> Result<Vec<Complex64>> {
        if let Some(st) = from {
            let (a, n) = pl.poly(z[0], z[1])?;
            if st.len() == n {
                let mut c = [0.0; D];
                for k in 0..=n {
                    c[k] = a[n - k];
                }
                let mut out = vec![Complex64::default(); n];
                if aberth_roots(&c[..=n], st, &mut out, 1e-10).is_some() {
                    return Ok(out);
                }
            }
        }
        pl.eigen(z[0], z[1])
    };
    // the eigenvalue nearest the axis other than the critical ones
    let other = |z: &[f64; 3], mut cand: Vec<Complex64>| -> Complex64 {
        let wc = if kind == CurveKind::Hopf { z[2].max(0.0).sqrt() } else { 0.0 };
        // drop the critical pair (or zero)
        for target in [Complex64::new(0.0, wc), Complex64::new(0.0, -wc)] {
            if let Some(i) = (0..cand.len()).min_by(|&i, &j| (cand[i] - target).norm().total_cmp(&(cand[j] - target).norm())) {
                cand.remove(i);
            }
            if kind == CurveKind::Fold {
                break;
            }
        }
        cand.into_iter().max_by(|x, y| x.re.total_cmp(&y.re)).unwrap_or_default()
    };
    // the same from the polynomial: the critical pair (or zero) divided out, the rightmost root
    // of the quotient by Newton's method from `guess`, certified by Routh's count right of it
    // (no root of the quotient beyond its inclusion disk); `None` when the certificate fails
    let other_poly = |z: &[f64; 3], guess: Complex64| -> Result<Option<Complex64>> {
        let (a, n) = pl.poly(z[0], z[1])?;
        let mut c = [0.0; D];
        for k in 0..=n {
            c[k] = a[n - k];
        }
        let m = if kind == CurveKind::Hopf { n - 2 } else { n - 1 };
        let mut q = [0.0; D];
        for k in 0..=m {
            q[k] = c[k] - if kind == CurveKind::Hopf && k >= 2 { z[2] * q[k - 2] } else { 0.0 };
        }
        let mut g = guess;
        if g.im == 0.0 {
            g.im = 1e-7;
        }
        let Some((r, rad)) = crate::linalg::charpoly::polish_root(&q[..=m], g, 30, 1e-14 * (1.0 + g.norm())) else { return Ok(None) };
        Ok((routh_count_right_of(&q[..=m], r.re + rad + 1e-12) == Some(0)).then_some(Complex64::new(r.re, r.im.abs())))
    };
    let point = |s: f64| -> Result<Option<[f64; 3]>> {
        let z0 = [a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]];
        Ok(correct(pl, kind, z0, &t, None)?.map(|r| r.0))
    };
    let (mut s0, mut s1) = (0.0, 1.0);
    // the spectrum by QR at one end (or continued from the last chord's end, within 0.1), and
    // continued to the other
    let from = last.take().filter(|(z, _)| (0..3).all(|c| (z[c] - a[c]).abs() <= 0.1));
    let ea = spectrum(&a, from.as_ref().map(|f| &f.1[..]))?;
    let eb = spectrum(&b, Some(&ea))?;
    *last = Some((b, eb.clone()));
    let (oa, ob) = (other(&a, ea.clone()), other(&b, eb.clone()));
    let (mut g0, mut g1) = (oa.re, ob.re);
    if g0.signum() == g1.signum() {
        return Ok(None);
    }
    // Newton's start on the quotient: the crossing eigenvalue where it is right of the axis
    // (on the other side the rightmost may be another), then the last one found
    let mut guess = if oa.re > ob.re { oa } else { ob };
    let mut best = (a, Complex64::default());
    let mut side = 0;
    for _ in 0..40 {
        let s = (s0 * g1 - s1 * g0) / (g1 - g0);
        let Some(z) = point(s)? else { return Ok(None) };
        let o = match other_poly(&z, guess)? {
            Some(o) => o,
            None => other(&z, spectrum(&z, Some(if s < 0.5 { &ea } else { &eb }))?),
        };
        guess = o;
        best = (z, o);
        if o.re.abs() < 1e-10 || (s1 - s0) < 1e-10 {
            break;
        }
        if o.re.signum() == g0.signum() {
            s0 = s;
            g0 = o.re;
            if side == -1 {
                g1 *= 0.5;
            }
            side = -1;
        } else {
            s1 = s;
            g1 = o.re;
            if side == 1 {
                g0 *= 0.5;
            }
            side = 1;
        }
    }
    Ok(Some(best))
}

/// A traced point and the polynomial that the corrector evaluated last, when that was within
/// 1e-8 of the point (its stability flag, [`boundary_flag`], then costs no evaluation).
type Traced = ([f64; 3], Option<([f64; D], usize)>);

/// The polynomial the plane evaluated last, if it was at most 1e-8 from `z` (scaled).
fn near_poly(pl: &Plane, z: &[f64; 3]) -> Option<([f64; D], usize)> {
    let (u, v, a, n) = pl.last.get()?;
    ((u - z[0]).abs() <= 1e-8 && (v - z[1]).abs() <= 1e-8).then_some((a, n))
}

/// March from `z0` along `t`: predictor–corrector with step control, until the curve leaves the
/// unit square (the last point clipped to its edge), closes on itself, or 4000 points.
fn march(pl: &Plane, kind: CurveKind, z0: [f64; 3], t0: [f64; 3], max_step: f64) -> Result<(Vec<Traced>, bool)> {
    let mut pts: Vec<Traced> = vec![(z0, None)];
    let mut z = z0;
    let mut t = t0;
    let mut jz = residual_jacobian(pl, kind, &z0)?.1;
    let mut h = 0.25 * max_step;
    let mut travelled = 0.0;
    // the curve's bend, dt/ds from the last two tangents: the predictor follows the osculating
    // parabola `z + h t + h²/2 dt/ds` (its error O(h³) instead of the tangent's O(h²·curvature))
    let mut bend = [0.0; 3];
    while pts.len() < 4000 {
        let pred: [f64; 3] = std::array::from_fn(|c| z[c] + h * t[c] + 0.5 * h * h * bend[c]);
        // a step the model refuses (beyond an end of the plane where the parameter has no
        // meaning, e.g. a negative drag): the curve leaves the plane there
        let step = match correct(pl, kind, pred, &t, Some(&jz)) {
            Err(Error::InvalidParameter { .. }) => return Ok((pts, false)),
            r => r?,
        };
        match step {
            Some((zn, j)) => {
                let tn = tangent(kind, &j, Some(&t));
                let turn = (t.iter().zip(&tn).map(|(a, b)| a * b).sum::<f64>()).clamp(-1.0, 1.0).acos();
                let dist = ((zn[0] - z[0]).powi(2) + (zn[1] - z[1]).powi(2) + (zn[2] - z[2]).powi(2)).sqrt();
                // the chord error (sagitta ≤ c·turn/8 ≤ h·turn/4, chords c ≤ 2h) is bounded through h·turn ≤ 0.15·max_step,
                // as with the largest step: a shorter step may turn further (a tight tip is
                // passed in fewer steps), up to 0.6 rad
                let most = (0.15 * max_step / h).clamp(0.15, 0.6);
                if (turn > most || dist > 2.0 * h) && h > 1e-7 {
                    h *= 0.5;
                    continue;
                }
                let inside = |p: &[f64; 3]| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1]);
                if !inside(&zn) {
                    // clip the chord at the edge of the square
                    let (mut s, mut hit) = (1.0f64, 0);
                    for c in 0..2 {
                        for edge in [0.0, 1.0] {
                            let dz = zn[c] - z[c];
                            if dz != 0.0 {
                                let r = (edge - z[c]) / dz;
                                if r > 0.0 && r < s {
                                    (s, hit) = (r, c);
                                }
                            }
                        }
                    }
                    let mut zc = [z[0] + s * (zn[0] - z[0]), z[1] + s * (zn[1] - z[1]), z[2] + s * (zn[2] - z[2])];
                    zc[hit] = zc[hit].round();
                    // onto the curve, on the edge
                    let mut normal = [0.0; 3];
                    normal[hit] = 1.0;
                    // (a point that does not correct onto the curve, e.g. in a corner, is left out)
                    let edge =
                        correct(pl, kind, zc, &normal, Some(&jz)).or_else(|e| if matches!(e, Error::InvalidParameter { .. }) { Ok(None) } else { Err(e) })?;
                    if let Some((ze, _)) = edge {
                        if (-1e-9..=1.0 + 1e-9).contains(&ze[0]) && (-1e-9..=1.0 + 1e-9).contains(&ze[1]) {
                            pts.push((ze, near_poly(pl, &ze)));
                        }
                    }
                    return Ok((pts, false));
                }
                travelled += dist;
                let back = ((zn[0] - z0[0]).powi(2) + (zn[1] - z0[1]).powi(2) + (zn[2] - z0[2]).powi(2)).sqrt();
                pts.push((zn, near_poly(pl, &zn)));
                // closed: the chord z → zn passes through the start (within the sagitta of a
                // step, ≤ h·turn/8 ≤ 1e-3; near the start alone is not enough, the curve may
                // still have a tip to go round)
                let through_start = {
                    let d = [zn[0] - z[0], zn[1] - z[1], zn[2] - z[2]];
                    let l2 = d.iter().map(|x| x * x).sum::<f64>();
                    let s = if l2 > 0.0 { ((0..3).map(|c| (z0[c] - z[c]) * d[c]).sum::<f64>() / l2).clamp(0.0, 1.0) } else { 0.0 };
                    (0..3).map(|c| (z[c] + s * d[c] - z0[c]).powi(2)).sum::<f64>().sqrt() < 2e-3
                };
                if travelled > 4.0 * h && back < 1.5 * h && through_start {
                    pts.push((z0, None));
                    return Ok((pts, true));
                }
                if dist > 0.0 {
                    bend = std::array::from_fn(|c| (tn[c] - t[c]) / dist);
                }
                z = zn;
                t = tn;
                jz = j;
                if turn < most / 3.0 {
                    h = (h * 1.5).min(max_step);
                }
            }
            None => {
                h *= 0.5;
                if h < 1e-9 {
                    return Ok((pts, false));
                }
            }
        }
    }
    Ok((pts, false))
}

/// The stability boundary ([`trace_boundary_with`]) over a plane
/// whose speed axis may be in SI (as [`crate::spatial::map::stability_map_units`]): traced in the plane of `Ω`
/// (from the slowest speed over the largest `ω0` to the fastest over the smallest, `ω0` sampled
/// at 65 points of the other axis) and every point carried to the SI speed `Ω ω0/k` with the
/// `ω0` of its own model; the boundary's axes are the SI ones.
pub fn trace_boundary_units(spec: &SpatialSpec, x: &Axis, y: &Axis, s: &TraceSettings, control: &crate::control::Control) -> Result<Boundary> {
    use crate::spatial::paths::{omega0_at, si_speed_axis};
    let Some((i, k)) = si_speed_axis(spec, [&x.path, &y.path])? else { return trace_boundary_with(spec, x, y, s, control) };
    let (speed, other) = if i == 0 { (x, y) } else { (y, x) };
    if !(speed.lo() >= 0.0 && speed.hi() > speed.lo() && speed.hi().is_finite()) {
        return Err(Error::invalid(speed.path.clone(), "the speeds must be finite, non-negative, with hi > lo"));
    }
    let mut w0s = vec![];
    for n in 0..=64 {
        w0s.push(omega0_at(spec, &other.path, other.lo() + (other.hi() - other.lo()) * n as f64 / 64.0)?);
    }
    let (lo, hi) = w0s.iter().fold((f64::INFINITY, 0.0f64), |(a, b), w| (a.min(*w), b.max(*w)));
    let om = Axis::range(OMEGA, speed.lo() * k / hi, speed.hi() * k / lo);
    let mut b = if i == 0 { trace_boundary_with(spec, &om, y, s, control)? } else { trace_boundary_with(spec, x, &om, s, control)? };
    let carry = |sp: &mut f64, ot: f64| -> Result<()> {
        *sp *= omega0_at(spec, &other.path, ot)? / k;
        Ok(())
    };
    for c in &mut b.curves {
        for p in &mut c.points {
            if i == 0 {
                carry(&mut p.x, p.y)?
            } else {
                carry(&mut p.y, p.x)?
            }
        }
    }
    for p in &mut b.codim2 {
        if i == 0 {
            carry(&mut p.x, p.y)?
        } else {
            carry(&mut p.y, p.x)?
        }
    }
    if i == 0 {
        b.x = x.clone();
    } else {
        b.y = y.clone();
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::params::DimensionlessInput;
    use crate::spatial::paths::SpatialInput;

    #[test]
    fn tracing_refuses_invalid_settings_naming_them() {
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(DimensionlessInput::default()), delta_a_override: None };
        let x = Axis::range("dimensionless.z_a", -1.0, 1.0);
        let y = Axis::range(OMEGA, 0.1, 2.0);
        for (s, field) in [
            (TraceSettings { max_step: f64::NAN, ..Default::default() }, "max_step"),
            (TraceSettings { coarse: (24, 0), ..Default::default() }, "coarse"),
            (TraceSettings { omega: Some(-1.0), ..Default::default() }, OMEGA),
        ] {
            let e = trace_boundary(&spec, &x, &y, &s).unwrap_err();
            assert_eq!(e.field(), Some(field), "{e}");
        }
    }

    #[test]
    fn the_model_along_a_parameter_is_its_polynomial_or_is_derived() {
        // ParamTerms against the model derived from the spec (a second route) at points that
        // are none of its samples: z̄_A and h̄s enter eq (6) affinely, so the fit must be found
        // and reproduce every matrix to a few ulp of its size (1e-13: the model's own rounding),
        // and its derivative must be the central difference of the derived model (step 1e-4 in
        // the scaled coordinate: exact for an affine model but for rounding, ~1e-12/1e-4 of the
        // size). ρ̄s enters through p̄α² ∝ 1/ρ̄s²: no polynomial of degree ≤ 4 reproduces it over
        // [0.2, 0.8] to 1e-12, so the plane must derive the model at every point (None).
        let d = DimensionlessInput {
            anisotropy: crate::spatial::params::AnisotropyInput::Direct(0.1),
            direct_balls: Some((0.05, 0.5)),
            ..DimensionlessInput::default()
        };
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
        let y = Axis::range(OMEGA, 0.05, 4.5);
        for (path, lo, hi) in [("dimensionless.z_a", -2.0, 2.0), ("dimensionless.h_s", 0.01, 0.5)] {
            let x = Axis::range(path, lo, hi);
            let pl = Plane::new(&spec, &x, &y, Balls::Free, None);
            let p = pl.param.as_ref().unwrap_or_else(|| panic!("{path}: no polynomial fitted"));
            assert_eq!(p.axis, 0);
            assert!(p.coef.len() <= 2, "{path}: degree {}", p.coef.len() - 1);
            let derived = |u: f64| pl.derive([Plane::value(&x, u), 0.0]).unwrap();
            for u in [0.123, 0.618, 0.987] {
                let (a, b) = (p.at(u), derived(u));
                let (da, h) = (p.derivative(u), 1e-4);
                let (bp, bm) = (derived(u + h), derived(u - h));
                for q in 0..6 {
                    let size = mats(&b)[q].iter().flatten().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
                    for i in 0..6 {
                        for j in 0..6 {
                            let e = (mats(&a)[q][i][j] - mats(&b)[q][i][j]).abs();
                            assert!(e <= 1e-13 * size, "{path} matrix {q} ({i}, {j}) at {u}: {e}");
                            let fd = (mats(&bp)[q][i][j] - mats(&bm)[q][i][j]) / (2.0 * h);
                            let e = (mats(&da)[q][i][j] - fd).abs();
                            assert!(e <= 1e-8 * size, "{path} d/du of matrix {q} ({i}, {j}) at {u}: {e}");
                        }
                    }
                }
            }
        }
        let x = Axis::range("dimensionless.rho_s", 0.2, 0.8);
        assert!(Plane::new(&spec, &x, &y, Balls::Free, None).param.is_none());
        // neither axis the speed: no polynomial (the model is derived at every point)
        let (x, y2) = (Axis::range("dimensionless.z_a", -1.0, 1.0), Axis::range("dimensionless.h_s", 0.01, 0.5));
        assert!(Plane::new(&spec, &x, &y2, Balls::Free, Some(1.0)).param.is_none());
    }

    #[test]
    fn residuals_by_determinants_are_the_expanded_polynomials() {
        // The corrector's residuals (determinants by elimination at λ = iω, at λ = ±√(−w), at
        // λ = 0; and Horner on the plane's polynomial, PlanePolynomial) against `E(w)`, `O(w)` by Horner on the exact expansion of the same pencil
        // (`pencil_polynomial`, a second route): both exact but for rounding, a few ulp of the
        // terms summed (Σ_j |a_j| |w|^(j/2) ≤ ~1e3 here), so 1e-11 of that size. A wrong sign
        // (E − iωO), a missing 1/ω or normalisation by det M errs at O(1). Points on both
        // sides of W_EXPANDED, off the curves (the residual not small) and at both ends of z̄_A.
        let d = DimensionlessInput {
            anisotropy: crate::spatial::params::AnisotropyInput::Direct(0.1),
            direct_balls: Some((0.05, 0.5)),
            ..DimensionlessInput::default()
        };
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
        let x = Axis::range("dimensionless.z_a", -2.0, 2.0);
        let y = Axis::range(OMEGA, 0.05, 4.5);
        for balls in [Balls::Free, Balls::Locked] {
            // the derived model at every point (determinants), and the plane's polynomial
            let mut pl = Plane::new(&spec, &x, &y, balls, None);
            let whole = Plane::new(&spec, &x, &y, balls, None);
            assert!(whole.plane.is_some());
            (pl.param, pl.plane) = (None, None);
            for z in [[0.4, 0.3, 0.8], [0.7, 0.55, 2.3], [0.0, 0.9, 0.05], [1.0, 0.1, 5.0], [0.6, 0.2, -0.3], [0.2, 0.7, -2.0], [0.45, 0.35, 0.0]] {
                let (a, n) = pl.poly(z[0], z[1]).unwrap();
                let size = (0..=n).map(|j| a[j].abs() * z[2].abs().sqrt().powi(j as i32)).sum::<f64>();
                let r = eo(&a, n, z[2]);
                let hopf = pl.residual(CurveKind::Hopf, &z).unwrap();
                let om = z[2].abs().sqrt();
                assert!((hopf[0] - r[0]).abs() < 1e-11 * size, "{balls:?} E at {z:?}: {} against {}", hopf[0], r[0]);
                assert!((hopf[1] - r[1]).abs() * om < 1e-11 * size, "{balls:?} O at {z:?}: {} against {}", hopf[1], r[1]);
                let fold = pl.residual(CurveKind::Fold, &z).unwrap();
                assert!((fold[0] - a[0]).abs() < 1e-11 * a.iter().map(|x| x.abs()).fold(0.0, f64::max), "{balls:?} a_0 at {z:?}: {} against {}", fold[0], a[0]);
                let (hw, fw) = (whole.residual(CurveKind::Hopf, &z).unwrap(), whole.residual(CurveKind::Fold, &z).unwrap());
                assert!((hw[0] - r[0]).abs() < 1e-11 * size, "{balls:?} plane's E at {z:?}: {} against {}", hw[0], r[0]);
                assert!((hw[1] - r[1]).abs() * om < 1e-11 * size, "{balls:?} plane's O at {z:?}: {} against {}", hw[1], r[1]);
                assert!(
                    (fw[0] - a[0]).abs() < 1e-11 * a.iter().map(|x| x.abs()).fold(0.0, f64::max),
                    "{balls:?} plane's a_0 at {z:?}: {} against {}",
                    fw[0],
                    a[0]
                );
            }
            assert!(pl.determinants.get() > 0);
        }
    }

    /// The rotor of the benchmark's plane (`examples/bench_boundary.rs`, `bench/boundary.py`).
    fn bench_plane_rotor() -> DimensionlessInput {
        DimensionlessInput {
            c_sigma: 0.75,
            rho_s: 0.4,
            l_left: 0.8,
            anisotropy: crate::spatial::params::AnisotropyInput::Direct(0.1),
            h_x: 0.05,
            h_s: 0.1,
            method: crate::spatial::inertia::AnisotropyMethod::Exact,
            direct_balls: Some((0.05, 0.5)),
            ..DimensionlessInput::default()
        }
    }

    /// A Bogdanov–Takens point has a double zero eigenvalue: at each one traced on the bench
    /// plane (z̄_A × Ω, free balls) the two smallest eigenvalues of the state matrix (QR, an
    /// independent route) are below 1e-5 (a residual ~1e-12 in the polynomial's low
    /// coefficients moves a double root by ~1e-6: measured 1.3e-6; the chord's interpolation
    /// alone left 6.9e-3 and 3.2e-2, a review found).
    #[test]
    fn bogdanov_takens_points_have_a_double_zero_eigenvalue() {
        let bench = bench_plane_rotor();
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(bench), delta_a_override: None };
        let x = Axis::range("dimensionless.z_a", -2.0, 2.0);
        let y = Axis::range(OMEGA, 0.05, 4.5);
        let b = trace_boundary(&spec, &x, &y, &TraceSettings::default()).unwrap();
        let pl = Plane::new(&spec, &x, &y, Balls::Free, None);
        let bt: Vec<_> = b.codim2.iter().filter(|c| c.kind == Codim2Kind::BogdanovTakens).collect();
        assert!(!bt.is_empty(), "{:?}", b.codim2);
        for c in bt {
            let (u, v) = ((c.x + 2.0) / 4.0, (c.y - 0.05) / 4.45);
            let mut ev: Vec<f64> = pl.eigen(u, v).unwrap().iter().map(|l| l.norm()).collect();
            ev.sort_by(f64::total_cmp);
            eprintln!("BT at ({}, {}): |λ| {:.3e} {:.3e}", c.x, c.y, ev[0], ev[1]);
            assert!(ev[1] <= 1e-5, "BT at ({}, {}): smallest |λ| {:?}", c.x, c.y, &ev[..3]);
        }
    }

    #[test]
    fn every_change_of_verdict_of_the_map_lies_on_the_traced_boundary() {
        // Coverage of the coarse seed grid (24 × 24), checked against the map of the same plane
        // (an independent route: Routh–Hurwitz on each cell's polynomial, changes confirmed on
        // the state matrix): wherever two neighbouring cells of a 120 × 120 verdict map differ,
        // the stability boundary crosses the segment between their centres, so a traced
        // stability-boundary segment must pass within half that segment (0.5/119 of the plane)
        // plus the polyline's chord error (2e-3: steps h ≤ 0.05 with h·turn ≤ 0.05 · 0.15 rad) of its
        // middle. A piece of boundary the seeds missed is a run of such cells far from every
        // traced curve. Planes: the benchmark's and the docs' (`map --x dimensionless.z_a=-2:2
        // --y omega=0.05:4.5 --boundary` on the default rotor).
        use crate::spatial::map::{stability_map, MapSettings, Quantity};
        let bench = bench_plane_rotor();
        for d in [bench, DimensionlessInput::default()] {
            let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
            let n = 120;
            let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, n);
            let y = Axis::linspace(OMEGA, 0.05, 4.5, n);
            let mut v = vec![];
            let s = MapSettings { quantity: Quantity::Verdict, ..MapSettings::default() };
            stability_map(&spec, &x, &y, &s, &Control::none(), &mut |_, row| {
                v.push(row.iter().map(|c| c.stable).collect::<Vec<_>>());
                true
            })
            .unwrap();
            let b = trace_boundary(&spec, &x, &y, &TraceSettings::default()).unwrap();
            let segs: Vec<[f64; 4]> = b
                .curves
                .iter()
                .flat_map(|c| c.points.windows(2).filter(|w| w[0].on_boundary || w[1].on_boundary).map(|w| [w[0].x, w[0].y, w[1].x, w[1].y]))
                .map(|[a, b, c, d]| [(a + 2.0) / 4.0, (b - 0.05) / 4.45, (c + 2.0) / 4.0, (d - 0.05) / 4.45])
                .collect();
            let dist = |px: f64, py: f64| {
                segs.iter()
                    .map(|&[ax, ay, bx, by]| {
                        let (dx, dy) = (bx - ax, by - ay);
                        let l2 = dx * dx + dy * dy;
                        let t = if l2 > 0.0 { (((px - ax) * dx + (py - ay) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
                        ((ax + t * dx - px).powi(2) + (ay + t * dy - py).powi(2)).sqrt()
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let cell = 1.0 / (n - 1) as f64;
            let tol = 0.5 * cell + 2e-3;
            let mut changes = 0;
            for j in 0..n {
                for i in 0..n {
                    for (i2, j2) in [(i + 1, j), (i, j + 1)] {
                        if i2 < n && j2 < n && v[j][i] != v[j2][i2] {
                            changes += 1;
                            let (px, py) = (0.5 * (i + i2) as f64 * cell, 0.5 * (j + j2) as f64 * cell);
                            let d = dist(px, py);
                            assert!(d < tol, "the verdict changes between cells ({i}, {j}) and ({i2}, {j2}), {d} from the traced boundary");
                        }
                    }
                }
            }
            assert!(changes > 50, "{changes} changes of verdict");
        }
    }
    /// The polyline's chord error, measured on the model: the march bounds each chord's sagitta
    /// by `h·turn/4 ≤ 0.15·max_step/4` (module docs; 1.875e-3 of the unit plane at the default
    /// `max_step` 0.05). For every traced segment of a fold or Hopf curve (`w ≥ 0` at both ends:
    /// an eigenvalue on the imaginary axis, not a neutral saddle) on the bench plane and the
    /// docs' plane, the number of eigenvalues of the state matrix with `Re λ > 0` (QR: an
    /// independent route from the polynomial conditions the tracer solves) is followed along the
    /// chord's normal through its midpoint; it changes where a curve is crossed, and the nearest
    /// change must lie within that bound (the chord's own curve lies within its sagitta; another
    /// curve nearer only makes the test weaker there). Both ends on the stability boundary is
    /// not enough to use the spectral abscissa instead: a chord can span two double-Hopf points
    /// between which its curve is not the boundary (docs' plane, (0.80, 0.41)-(0.76, 0.44): 3.1e-3
    /// from the stability boundary). Measured worst 8.6e-4 (bench plane) and 7.9e-4; a step rule
    /// allowing four times the turn (`0.6·max_step / h`) leaves a chord 2.0e-3 from its curve
    /// and fails here, where the coverage test above (half a 120-cell step, 4.2e-3, plus 2e-3)
    /// cannot see it.
    #[test]
    fn every_traced_chord_lies_within_its_sagitta_bound_of_the_spectrum() {
        let bound = 0.15 * TraceSettings::default().max_step / 4.0;
        for d in [bench_plane_rotor(), DimensionlessInput::default()] {
            let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
            let x = Axis::range("dimensionless.z_a", -2.0, 2.0);
            let y = Axis::range(OMEGA, 0.05, 4.5);
            let b = trace_boundary(&spec, &x, &y, &TraceSettings::default()).unwrap();
            let pl = Plane::new(&spec, &x, &y, Balls::Free, None);
            let unstable = |u: f64, v: f64| pl.eigen(u, v).unwrap().iter().filter(|l| l.re > 0.0).count();
            let (mut checked, mut worst) = (0, 0.0f64);
            for c in &b.curves {
                for w in c.points.windows(2).filter(|w| w[0].w >= 0.0 && w[1].w >= 0.0) {
                    let (ua, va, ub, vb) = ((w[0].x + 2.0) / 4.0, (w[0].y - 0.05) / 4.45, (w[1].x + 2.0) / 4.0, (w[1].y - 0.05) / 4.45);
                    let len = (ub - ua).hypot(vb - va);
                    if len < 1e-9 {
                        continue;
                    }
                    let (mu, mv) = (0.5 * (ua + ub), 0.5 * (va + vb));
                    let (nu, nv) = (-(vb - va) / len, (ub - ua) / len);
                    let a = |s: f64| unstable(mu + s * nu, mv + s * nv);
                    // the nearest change of the count on a scan of ±2·bound in steps of bound/8
                    // (closer to the midpoint first), then bisected
                    let mut found = None;
                    'scan: for k in 1..=16 {
                        for sg in [-1.0, 1.0] {
                            let (s0, s1) = (sg * (k - 1) as f64 * bound / 8.0, sg * k as f64 * bound / 8.0);
                            let (f0, f1) = (a(s0), a(s1));
                            if f0 != f1 {
                                let (mut lo, mut hi, mut flo) = (s0, s1, f0);
                                for _ in 0..40 {
                                    let m = 0.5 * (lo + hi);
                                    let fm = a(m);
                                    if fm == flo {
                                        (lo, flo) = (m, fm);
                                    } else {
                                        hi = m;
                                    }
                                }
                                found = Some(0.5 * (lo + hi));
                                break 'scan;
                            }
                        }
                    }
                    let s = found.unwrap_or_else(|| panic!("no curve within {} of the chord ({ua}, {va})-({ub}, {vb})", 2.0 * bound));
                    assert!(s.abs() <= bound, "the chord ({ua}, {va})-({ub}, {vb}) lies {} from the nearest curve (bound {bound})", s.abs());
                    worst = worst.max(s.abs());
                    checked += 1;
                }
            }
            eprintln!("{checked} chords of fold and Hopf curves, worst sagitta {worst:.2e} (bound {bound:.3e})");
            assert!(checked > 50, "{checked} chords checked");
        }
    }
}
