//! Stability maps over two parameters: the spectral abscissa `max Re λ` (or the stability
//! verdict) of the balanced state at every point of a grid, computed in parallel and delivered
//! row by row in grid order, in bounded memory.
//!
//! An axis ([`Axis`], the one of [`crate::paths`]) is a parameter path ([`crate::spatial::paths`],
//! e.g. `dimensionless.z_a`) or [`OMEGA`], the speed, with its values. Along the speed axis a model is fixed, and the work is done per *line*
//! (one model, all speeds) with the exact characteristic polynomial in `Ω`
//! ([`crate::linalg::charpoly`]):
//! - the **margin** by continuation of the rightmost eigenvalue with a Routh certificate at
//!   every speed; where another eigenvalue overtakes, by continuation of all eigenvalues from
//!   the last speed that had them (certified by disjoint inclusion disks), and by the QR
//!   eigenvalues where that cannot certify or no spectrum is known yet ([`AbscissaTracker`]);
//!   with 16 lines or more, each group of 16 starts from the QR spectrum of its first line at
//!   the first speed (the same seeds whichever axis is the speed);
//! - the **verdict** by the Routh–Hurwitz test on the coefficients at each speed; every change
//!   of verdict along a line, and the ends of each block of speeds, are confirmed by the direct
//!   test on the state matrix (Hessenberg characteristic polynomial), and cells found wrong are
//!   corrected until every change of verdict has been confirmed on both sides.
//!
//! Without a speed axis every point is its own model, evaluated at the fixed speed by the QR
//! eigenvalues or the direct Routh–Hurwitz test.
//!
//! Rows are computed in blocks in parallel (rayon, in the caller's thread pool) and handed to
//! the caller's `on_row` in order, whatever the number of threads; memory is one block plus one
//! state per line.

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use crate::builder::builder;
use crate::control::{Control, StopReason};
use crate::error::{Error, Result};
use crate::linalg::charpoly::{AbscissaTracker, PencilTerms, PlanePolynomial, SpeedPolynomial};
use crate::linalg::eigen::{eigenvalues, routh_hurwitz_stable, spectral_abscissa};
pub use crate::paths::Axis;
use crate::spatial::boundary::ParamTerms;
use crate::spatial::linear_model::{Balls, Pencil, StateSpace};
use crate::spatial::params::SpatialModel;
use crate::spatial::paths::SpatialSpec;
use crate::spatial::ranges::{autobalancing_ranges, SpeedRange};
use crate::spatial::stability::{counts_as_stable, no_conv, strictly_stable_at};
use rayon::prelude::*;

/// The path of the speed axis.
pub const OMEGA: &str = "omega";

/// Speeds below this are evaluated at it (at `Ω = 0` the free balls are neutral and the
/// eigenvalues multiple).
pub const OMEGA_FLOOR: f64 = 1e-9;

/// Whether the axis is the speed [`OMEGA`] (the speed axes in SI are
/// [`stability_map_units`]'s).
fn is_omega(a: &Axis) -> bool {
    a.path == OMEGA
}

/// What each point stores.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The spectral abscissa `max Re λ` (and the verdict from it).
    Margin,
    /// The Routh–Hurwitz verdict only (strict: every `Re λ < 0`); `margin` is NaN.
    Verdict,
}

/// One point of a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// `max Re λ` (NaN for [`Quantity::Verdict`]).
    pub margin: f64,
    /// Stable by [`counts_as_stable`] (margin) or by Routh–Hurwitz (verdict).
    pub stable: bool,
    /// Inside 003's necessary ranges (eqs (1)-(3)).
    pub necessary: bool,
}

/// Settings of a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapSettings {
    /// Balls free (12 states) or locked (8).
    pub balls: Balls,
    /// Margin or verdict.
    pub quantity: Quantity,
    /// The speed when neither axis is [`OMEGA`].
    pub omega: Option<f64>,
}

/// Balls free, the margin, the speed from an axis.
impl Default for MapSettings {
    fn default() -> Self {
        MapSettings { balls: Balls::Free, quantity: Quantity::Margin, omega: None }
    }
}

impl MapSettings {
    /// A builder starting from [`MapSettings::default`].
    pub fn builder() -> MapSettingsBuilder {
        MapSettingsBuilder::default()
    }

    /// Check the settings that do not depend on the axes: a fixed speed `omega`, when given,
    /// is a finite number `≥ 0` (the error names `omega`). Whether it is needed depends on the
    /// axes ([`stability_map`] checks that).
    pub fn validate(&self) -> Result<()> {
        check_fixed_speed(self.omega)
    }
}

/// A fixed speed, when given, is a finite number `≥ 0` (the error names `omega`).
pub(crate) fn check_fixed_speed(omega: Option<f64>) -> Result<()> {
    if let Some(w) = omega {
        if !(w >= 0.0 && w.is_finite()) {
            return Err(Error::invalid(OMEGA, format!("the speed must be a finite number ≥ 0, got {w}")));
        }
    }
    Ok(())
}

builder!(
    /// Builder of [`MapSettings`]; `build()` runs [`MapSettings::validate`].
    ///
    /// ```
    /// use autobal::spatial::map::{MapSettings, Quantity};
    /// use autobal::spatial::linear_model::Balls;
    /// let s = MapSettings::builder().balls(Balls::Locked).quantity(Quantity::Verdict).omega(Some(1.5)).build().unwrap();
    /// assert_eq!((s.balls, s.quantity, s.omega), (Balls::Locked, Quantity::Verdict, Some(1.5)));
    /// let e = MapSettings::builder().omega(Some(-1.0)).build().unwrap_err();
    /// assert!(e.to_string().starts_with("omega"), "{e}");
    /// ```
    MapSettingsBuilder for MapSettings, |s| s.validate();
    balls: Balls, quantity: Quantity, omega: Option<f64>,
);

/// How a map ended, and how its points were computed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MapOutcome {
    /// Rows handed to `on_row`.
    pub rows: usize,
    /// Whether every row was computed (`false`: the control or `on_row` stopped it); the same
    /// as `stopped.is_none()`.
    pub complete: bool,
    /// Why it stopped before every row was computed (`None`: complete).
    pub stopped: Option<StopReason>,
    /// Points answered by continuation or by the characteristic polynomial.
    pub continued: usize,
    /// Direct solves on the state matrix (QR fall-backs of the margin, confirmations of the
    /// verdict, and every point of a map without a speed axis).
    pub direct: usize,
}

/// What a map varies: a family of models reached through parameter paths. [`SpatialSpec`] is
/// one (the config's paths; the model is derived again at every point); a front end may give
/// another, e.g. a derived model whose dimensionless coefficients are set directly.
pub trait ModelFamily: Clone + Sync {
    /// The member with the parameter at `path` set to `value` (errors name the path).
    fn with(&self, path: &str, value: f64) -> Result<Self>;
    /// Its model.
    fn model(&self) -> Result<SpatialModel>;
}

impl ModelFamily for SpatialSpec {
    fn with(&self, path: &str, value: f64) -> Result<Self> {
        let mut t = self.clone();
        t.set(path, value)?;
        Ok(t)
    }
    fn model(&self) -> Result<SpatialModel> {
        self.build()
    }
}

/// A model fixed along the speed axis.
struct Line {
    ss: StateSpace,
    poly: Option<SpeedPolynomial>,
    nec: Vec<SpeedRange>,
    tracker: AbscissaTracker,
    /// Verdict at the last speed of the previous block (confirmed directly).
    last: Option<bool>,
    continued: usize,
    direct: usize,
}

impl Line {
    /// The line of `spec`; with `plane` (the family over the other axis and this line's value
    /// on it) the speed polynomial is the plane's at that value where the plane reproduces this
    /// model's pencil ([`LinePlane::speed_polynomial`]), and expanded from the model otherwise.
    fn new(spec: &impl ModelFamily, balls: Balls, plane: Option<(&LinePlane, f64)>) -> Result<Self> {
        let model = spec.model()?;
        let ss = StateSpace::new(&model, balls)?;
        let terms = Pencil::terms(&model, balls)?;
        let poly = match plane.and_then(|(p, v)| p.speed_polynomial(v, &terms)) {
            Some(p) => Some(p),
            None => SpeedPolynomial::new(&terms),
        };
        let nec = autobalancing_ranges(&model).ranges;
        Ok(Line { ss, poly, nec, tracker: AbscissaTracker::new(), last: None, continued: 0, direct: 0 })
    }

    /// Cells at the ascending `speeds`, continuing from the previous call.
    fn cells(&mut self, speeds: &[f64], q: Quantity, balls: Balls, out: &mut Vec<Cell>) -> Result<()> {
        let n = self.ss.states;
        let start = out.len();
        for &w0 in speeds {
            let w = w0.max(OMEGA_FLOOR);
            let necessary = self.nec.iter().any(|r| r.contains(w));
            let cell = match (q, &self.poly) {
                (Quantity::Margin, Some(p)) => {
                    let c = p.at(w);
                    let before = self.tracker.fallbacks;
                    let ss = &self.ss;
                    let a = self.tracker.abscissa(w, &c[..=n], || eigenvalues(&ss.at(w), n).map_err(|_| no_conv(w)))?;
                    if self.tracker.fallbacks > before {
                        self.direct += 1;
                    } else {
                        self.continued += 1;
                    }
                    Cell { margin: a, stable: counts_as_stable(a, balls), necessary }
                }
                (Quantity::Margin, None) => {
                    self.direct += 1;
                    let a = spectral_abscissa(&self.ss.at(w), n).map_err(|_| no_conv(w))?;
                    Cell { margin: a, stable: counts_as_stable(a, balls), necessary }
                }
                (Quantity::Verdict, Some(p)) => {
                    self.continued += 1;
                    let c = p.at(w);
                    Cell { margin: f64::NAN, stable: routh_hurwitz_stable(&c[..=n]), necessary }
                }
                (Quantity::Verdict, None) => {
                    self.direct += 1;
                    Cell { margin: f64::NAN, stable: strictly_stable_at(&self.ss, w), necessary }
                }
            };
            out.push(cell);
        }
        if q == Quantity::Verdict && self.poly.is_some() {
            self.confirm(speeds, &mut out[start..]);
        }
        Ok(())
    }

    /// Confirm by the direct test the last cell of the block (and the first speed of the line),
    /// and every change of verdict (including the one from the previous block's last cell,
    /// which is confirmed), correcting cells until each change has been confirmed on both
    /// sides.
    fn confirm(&mut self, speeds: &[f64], cells: &mut [Cell]) {
        let k = cells.len();
        if k == 0 {
            return;
        }
        let mut checked = vec![false; k];
        let check = |i: usize, cells: &mut [Cell], checked: &mut [bool], direct: &mut usize| {
            if !checked[i] {
                checked[i] = true;
                *direct += 1;
                cells[i].stable = strictly_stable_at(&self.ss, speeds[i].max(OMEGA_FLOOR));
            }
        };
        match self.last {
            None => check(0, cells, &mut checked, &mut self.direct),
            Some(prev) if prev != cells[0].stable => check(0, cells, &mut checked, &mut self.direct),
            _ => {}
        }
        check(k - 1, cells, &mut checked, &mut self.direct);
        loop {
            let mut changed = false;
            if let Some(prev) = self.last {
                if prev != cells[0].stable && !checked[0] {
                    check(0, cells, &mut checked, &mut self.direct);
                    changed = true;
                }
            }
            for i in 0..k.saturating_sub(1) {
                if cells[i].stable != cells[i + 1].stable && !(checked[i] && checked[i + 1]) {
                    check(i, cells, &mut checked, &mut self.direct);
                    check(i + 1, cells, &mut checked, &mut self.direct);
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        self.last = Some(cells[k - 1].stable);
    }
}

/// Lines per group whose margins start from one spectrum: the first line's QR eigenvalues at
/// the first speed, continued to every line of the group by route 2 of [`AbscissaTracker`]
/// (the QR only where that does not certify). Used from [`PLANE_LINES`] lines on; the seed of a
/// group depends only on its first line and the first speed, so the rows and the transposed
/// map compute the same seeds and the same cells.
const SEED_GROUP: usize = 16;

/// The QR spectrum of the model of `spec` at speed `w` (the seed of a group of lines).
fn seed_spectrum(ss: &StateSpace, w: f64) -> Option<Vec<num_complex::Complex64>> {
    eigenvalues(&ss.at(w), ss.states).ok()
}

/// [`seed_spectrum`] of the model of `spec` with `path` at `v` (a group's first line, built
/// for its seed alone): `None` when that model fails (its line reports the error).
fn seed_of(spec: &impl ModelFamily, path: &str, v: f64, balls: Balls, w: f64) -> Option<Vec<num_complex::Complex64>> {
    let ss = (|| StateSpace::new(&spec.with(path, v)?.model()?, balls))().ok()?;
    seed_spectrum(&ss, w)
}

/// Fewest lines for which [`LinePlane`] is fitted: below, its ten sample models and the
/// plane's expansion (~7 line expansions) cost more than expanding every line.
const PLANE_LINES: usize = 16;

/// Largest difference, relative to each matrix's largest entry, between a line's pencil and
/// the fitted family's at its value for the line to take the plane's polynomial: the bound
/// [`ParamTerms::fit`] accepts (rounding of the model's own arithmetic; the tracked abscissa is
/// certified to `1e-10 (1 + |λ|)`, far above what a perturbation of the entries this small moves
/// the eigenvalues of these well-conditioned 12-state models).
const PLANE_MATCH: f64 = 1e-12;

/// The family along the axis of the lines (the one that is not the speed) as an exact
/// polynomial in its scaled coordinate `u = (v − lo)/(hi − lo)` ([`ParamTerms::fit`]: eq (6) is
/// affine in `z̄_A` and the damping coefficients), and with degree ≤ 2 its characteristic
/// polynomial over the whole plane `det P(λ, Ω, u)` ([`PlanePolynomial`]), expanded once: each
/// line's [`SpeedPolynomial`] is then one Horner pass in `u` over its coefficients instead of a
/// Laplace expansion of its own pencil (171 k instructions a line).
struct LinePlane {
    param: ParamTerms,
    plane: PlanePolynomial,
    lo: f64,
    hi: f64,
}

impl LinePlane {
    /// Fit the family over the values of `a` (at least [`PLANE_LINES`] of them, not all equal);
    /// `None` where it is not a polynomial of degree ≤ 2 or a sample is refused.
    fn new(spec: &impl ModelFamily, a: &Axis, balls: Balls) -> Option<Self> {
        if a.values.len() < PLANE_LINES {
            return None;
        }
        let lo = a.values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = a.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !(hi > lo) {
            return None;
        }
        let param = ParamTerms::fit(0, |u| Pencil::terms(&spec.with(&a.path, (lo + (hi - lo) * u).clamp(lo, hi))?.model()?, balls))?;
        let plane = PlanePolynomial::new(&param.coef)?;
        Some(LinePlane { param, plane, lo, hi })
    }

    /// The speed polynomial of the line at `v` whose model's pencil is `t`, from the plane,
    /// when the fitted family at `v` reproduces `t` (every entry within [`PLANE_MATCH`] of its
    /// matrix's largest entry); `None` otherwise (the caller expands `t`).
    fn speed_polynomial(&self, v: f64, t: &PencilTerms) -> Option<SpeedPolynomial> {
        let u = ((v - self.lo) / (self.hi - self.lo)).clamp(0.0, 1.0);
        let f = self.param.at(u);
        if f.n != t.n {
            return None;
        }
        let n = t.n;
        let mats = |t: &PencilTerms| [t.m, t.g[0], t.g[1], t.k[0], t.k[1], t.k[2]];
        for (a, b) in mats(&f).iter().zip(&mats(t)) {
            let mut scale = 0.0f64;
            let mut diff = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    scale = scale.max(a[i][j].abs()).max(b[i][j].abs());
                    diff = diff.max((a[i][j] - b[i][j]).abs());
                }
            }
            // `!(≤)`: a NaN refuses the plane
            if !(diff <= PLANE_MATCH * scale) {
                return None;
            }
        }
        self.plane.speed_polynomial(u)
    }
}

/// Number of cells computed between two hand-overs of rows (bounds memory and the latency of
/// a stop).
const BLOCK_CELLS: usize = 1 << 18;

/// Compute the map of `spec` (a [`SpatialSpec`], or any [`ModelFamily`]) over `x × y`; row `j` (all `x` at `y[j]`) goes to `on_row(j, cells)`
/// in order of `j`. `on_row` returns `false` to stop (the rows handed over are complete; the
/// outcome says the map is not).
///
/// Errors name the parameter path (unknown path, a value the model refuses) or the speed (QR
/// without convergence).
///
/// ```
/// use autobal::spatial::map::{stability_map, Axis, MapSettings, Quantity};
/// use autobal::spatial::linear_model::Balls;
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
/// let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, 21);
/// let y = Axis::linspace("omega", 0.05, 4.5, 30);
/// let settings = MapSettings { balls: Balls::Free, quantity: Quantity::Margin, omega: None };
/// let mut stable = 0;
/// let out = stability_map(&spec, &x, &y, &settings, &autobal::control::Control::none(), &mut |_j, row| {
///     stable += row.iter().filter(|c| c.stable).count();
///     true
/// }).unwrap();
/// assert!(out.complete && out.rows == 30 && stable > 0);
/// ```
pub fn stability_map<F: ModelFamily>(
    spec: &F,
    x: &Axis,
    y: &Axis,
    s: &MapSettings,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[Cell]) -> bool,
) -> Result<MapOutcome> {
    map_at(spec, x, y, s, None, control, on_row)
}

/// [`stability_map`], or with `si` (rad/s) the map at that one speed, each cell at its own
/// `Ω = si/ω0` ([`stability_map_at_speed`]).
fn map_at<F: ModelFamily>(
    spec: &F,
    x: &Axis,
    y: &Axis,
    s: &MapSettings,
    si: Option<f64>,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[Cell]) -> bool,
) -> Result<MapOutcome> {
    s.validate()?;
    for a in [x, y] {
        if a.values.is_empty() {
            return Err(Error::invalid(a.path.clone(), "the axis has no values"));
        }
        if a.values.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(a.path.clone(), "axis values must be finite"));
        }
        if is_omega(a) {
            if a.values.iter().any(|v| *v < 0.0) || a.values.windows(2).any(|w| w[1] < w[0]) {
                return Err(Error::invalid(OMEGA, "the speeds must be non-negative and ascending"));
            }
        } else {
            // fail early on an unknown path or a value the model refuses
            spec.with(&a.path, a.values[0])?.model()?;
        }
    }
    if is_omega(x) && is_omega(y) {
        return Err(Error::invalid(OMEGA, "only one axis can be the speed"));
    }
    let w = match (is_omega(x), is_omega(y), si) {
        (false, false, Some(w)) => Some(CellSpeed::Si(w)),
        (false, false, None) => {
            Some(CellSpeed::Omega(s.omega.ok_or_else(|| Error::invalid(OMEGA, "required when neither axis is the speed (the speed at which to map)"))?))
        }
        (_, _, Some(_)) => return Err(Error::invalid(OMEGA, "the map's speed is given (one speed in SI): its axes are two other parameters")),
        _ => None,
    };
    if let Some(why) = control.should_stop() {
        return Ok(MapOutcome { stopped: Some(why), ..Default::default() });
    }
    let mut why = None;
    let mut asked = ask_control(control, y.values.len(), on_row, &mut why);
    let mut out = match (is_omega(x), w) {
        (false, None) => map_speed_rows(spec, x, y, s, &mut asked),
        (true, _) => map_speed_columns(spec, x, y, s, &mut asked),
        (false, Some(w)) => map_fixed_speed(spec, x, y, w, s, &mut asked),
    }?;
    drop(asked);
    out.stopped = (!out.complete).then_some(why.unwrap_or(StopReason::Observer));
    Ok(out)
}

/// `on_row`, then the control asked after each row but the last (its progress observer hears
/// `(rows, rows in all)`); `why` receives the reason when either stops the map.
pub(crate) fn ask_control<'a>(
    control: &'a Control,
    rows: usize,
    on_row: &'a mut dyn FnMut(usize, &[Cell]) -> bool,
    why: &'a mut Option<StopReason>,
) -> impl FnMut(usize, &[Cell]) -> bool + 'a {
    let mut done = 0;
    move |j, cells| {
        done += 1;
        if !on_row(j, cells) {
            *why = Some(StopReason::Observer);
            return false;
        }
        control.report(done as u64, rows as u64);
        if done < rows {
            if let Some(r) = control.should_stop() {
                *why = Some(r);
                return false;
            }
        }
        true
    }
}

/// `y` is the speed: one line per `x`, rows are speeds.
///
/// Memory: each line's block of cells is kept compactly in its own [`Column`], allocated once
/// and reused by every block. When the speeds fit in one block (`nx·ny ≤` [`BLOCK_CELLS`], e.g.
/// 400 × 400), each line is built, seeded and run inside its job and dropped there: the
/// lines (~8 kB each) are never stored side by side. Otherwise they are built once into a vector
/// sized for the axis (rayon's indexed `collect_into_vec`, in place) and kept across blocks.
/// Where lines fail, the error is the one of the lowest-numbered line, whatever the threads.
fn map_speed_rows<F: ModelFamily>(spec: &F, x: &Axis, y: &Axis, s: &MapSettings, on_row: &mut dyn FnMut(usize, &[Cell]) -> bool) -> Result<MapOutcome> {
    map_speed_rows_in(spec, x, y, s, BLOCK_CELLS, on_row)
}

/// [`map_speed_rows`] with blocks of `block_cells` cells (the tests take both paths).
fn map_speed_rows_in<F: ModelFamily>(
    spec: &F,
    x: &Axis,
    y: &Axis,
    s: &MapSettings,
    block_cells: usize,
    on_row: &mut dyn FnMut(usize, &[Cell]) -> bool,
) -> Result<MapOutcome> {
    let plane = LinePlane::new(spec, x, s.balls);
    let nx = x.values.len();
    let ny = y.values.len();
    let block = (block_cells / nx).max(1);
    let mut out = MapOutcome { complete: true, ..Default::default() };
    let line = |i: usize| -> Result<Line> {
        let v = x.values[i];
        Line::new(&spec.with(&x.path, v)?, s.balls, plane.as_ref().map(|p| (p, v)))
    };
    // lines kept across blocks: only when there is more than one block
    let mut kept: Vec<Result<Line>> = Vec::new();
    if ny > block {
        (0..nx).into_par_iter().map(line).collect_into_vec(&mut kept);
        first_error(&mut kept)?;
    }
    // the seed of each group of lines: the QR spectrum of its first line's model at the first
    // speed (a model that fails gives no seed; its line reports the error)
    let w = y.values[0].max(OMEGA_FLOOR);
    let seeds: Vec<Option<Vec<_>>> = if s.quantity == Quantity::Margin && nx >= PLANE_LINES {
        (0..nx.div_ceil(SEED_GROUP))
            .into_par_iter()
            .map(|g| match kept.get(g * SEED_GROUP) {
                Some(Ok(l)) => seed_spectrum(&l.ss, w),
                _ => seed_of(spec, &x.path, x.values[g * SEED_GROUP], s.balls, w),
            })
            .collect()
    } else {
        vec![]
    };
    out.direct += seeds.len();
    let seed = |i: usize, l: &mut Line| {
        if let Some(Some(r)) = seeds.get(i / SEED_GROUP) {
            l.tracker.seed(w, r);
        }
    };
    for (i, l) in kept.iter_mut().enumerate() {
        if let Ok(l) = l {
            seed(i, l);
        }
    }
    let margin = s.quantity == Quantity::Margin;
    let k = block.min(ny);
    let mut cols: Vec<Column> = (0..nx).map(|_| Column { margin: Vec::with_capacity(if margin { k } else { 0 }), flags: Vec::with_capacity(k) }).collect();
    // each line's (continued, direct) counts when built in its job; an error otherwise
    let mut counts: Vec<Result<(usize, usize)>> = Vec::with_capacity(nx);
    let mut row = Vec::with_capacity(nx);
    let mut j0 = 0;
    while j0 < ny {
        let j1 = (j0 + block).min(ny);
        let speeds = &y.values[j0..j1];
        let scratch = || Vec::with_capacity(speeds.len());
        if kept.is_empty() {
            cols.par_iter_mut()
                .enumerate()
                .map_init(scratch, |cells, (i, col)| {
                    let mut l = line(i)?;
                    seed(i, &mut l);
                    cells.clear();
                    l.cells(speeds, s.quantity, s.balls, cells)?;
                    col.set(cells, margin);
                    Ok((l.continued, l.direct))
                })
                .collect_into_vec(&mut counts);
        } else {
            cols.par_iter_mut()
                .zip(kept.par_iter_mut())
                .map_init(scratch, |cells, (col, l)| {
                    cells.clear();
                    if let Ok(l) = l {
                        l.cells(speeds, s.quantity, s.balls, cells)?;
                    }
                    col.set(cells, margin);
                    Ok((0, 0))
                })
                .collect_into_vec(&mut counts);
        }
        first_error(&mut counts)?;
        for (c, d) in counts.iter().flatten() {
            out.continued += c;
            out.direct += d;
        }
        for jj in 0..speeds.len() {
            row.clear();
            row.extend(cols.iter().map(|c| c.cell(jj)));
            out.rows += 1;
            if !on_row(j0 + jj, &row) {
                out.complete = false;
                break;
            }
        }
        if !out.complete {
            break;
        }
        j0 = j1;
    }
    for l in kept.iter().flatten() {
        out.continued += l.continued;
        out.direct += l.direct;
    }
    Ok(out)
}

/// One line's cells of a block, as [`map_speed_rows`] keeps them until the block's rows are
/// handed over: the margins (only for [`Quantity::Margin`]; the verdict's are NaN) and the two
/// flags in a byte, 9 or 1 bytes a cell instead of a [`Cell`]'s 16 (fewer pages touched).
struct Column {
    margin: Vec<f64>,
    flags: Vec<u8>,
}

impl Column {
    const STABLE: u8 = 1;
    const NECESSARY: u8 = 2;

    /// Keep `cells` (their margins when `margin`).
    fn set(&mut self, cells: &[Cell], margin: bool) {
        self.flags.clear();
        self.flags.extend(cells.iter().map(|c| (c.stable as u8 * Self::STABLE) | (c.necessary as u8 * Self::NECESSARY)));
        self.margin.clear();
        if margin {
            self.margin.extend(cells.iter().map(|c| c.margin));
        }
    }

    /// The cell at `j`: the one [`Column::set`] was given, bit for bit (a verdict's margin is
    /// the NaN that [`Line::cells`] stores).
    fn cell(&self, j: usize) -> Cell {
        Self::unpack(self.flags[j], self.margin.get(j).copied().unwrap_or(f64::NAN))
    }

    fn unpack(f: u8, margin: f64) -> Cell {
        Cell { margin, stable: f & Self::STABLE != 0, necessary: f & Self::NECESSARY != 0 }
    }
}

/// The error of the lowest-numbered item of `v` that failed, if any (taken out of `v`, whose
/// order is then not kept).
fn first_error<T>(v: &mut Vec<Result<T>>) -> Result<()> {
    match v.iter().position(|r| r.is_err()).and_then(|i| v.swap_remove(i).err()) {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// `x` is the speed: one line per row, handed over as computed (no [`Column`]: packing the
/// cells and unpacking them would cost more instructions than the pages it saves). A block's
/// row buffers are allocated once and reused; where lines fail, the error is the
/// lowest-numbered line's.
fn map_speed_columns<F: ModelFamily>(spec: &F, x: &Axis, y: &Axis, s: &MapSettings, on_row: &mut dyn FnMut(usize, &[Cell]) -> bool) -> Result<MapOutcome> {
    let nx = x.values.len();
    let ny = y.values.len();
    let block = (BLOCK_CELLS / nx).max(2 * rayon::current_num_threads());
    let plane = LinePlane::new(spec, y, s.balls);
    let mut out = MapOutcome { complete: true, ..Default::default() };
    let seeded = s.quantity == Quantity::Margin && ny >= PLANE_LINES;
    let w = x.values[0].max(OMEGA_FLOOR);
    let mut rows: Vec<Vec<Cell>> = (0..block.min(ny)).map(|_| Vec::with_capacity(nx)).collect();
    let mut counts: Vec<Result<(usize, usize)>> = Vec::with_capacity(block.min(ny));
    let mut j0 = 0;
    while j0 < ny {
        let j1 = (j0 + block).min(ny);
        // the seeds of the groups this block's lines are in (as `map_speed_rows` computes them;
        // a model that fails gives no seed, its line reports the error)
        let g0 = j0 / SEED_GROUP;
        let seeds: Vec<Option<Vec<_>>> = if seeded {
            (g0..(j1 - 1) / SEED_GROUP + 1).into_par_iter().map(|g| seed_of(spec, &y.path, y.values[g * SEED_GROUP], s.balls, w)).collect()
        } else {
            vec![]
        };
        out.direct += seeds.len();
        rows[..j1 - j0]
            .par_iter_mut()
            .enumerate()
            .map(|(jj, r)| {
                let j = j0 + jj;
                let v = y.values[j];
                let mut l = Line::new(&spec.with(&y.path, v)?, s.balls, plane.as_ref().map(|p| (p, v)))?;
                if let Some(Some(sp)) = seeds.get(j / SEED_GROUP - g0) {
                    l.tracker.seed(w, sp);
                }
                r.clear();
                l.cells(&x.values, s.quantity, s.balls, r)?;
                Ok((l.continued, l.direct))
            })
            .collect_into_vec(&mut counts);
        first_error(&mut counts)?;
        for (jj, (c, d)) in counts.iter().flatten().enumerate() {
            out.rows += 1;
            out.continued += c;
            out.direct += d;
            if !on_row(j0 + jj, &rows[jj]) {
                out.complete = false;
                return Ok(out);
            }
        }
        j0 = j1;
    }
    Ok(out)
}

/// A map's speed when neither axis is one.
#[derive(Debug, Clone, Copy)]
enum CellSpeed {
    /// `Ω`, the same for every cell.
    Omega(f64),
    /// One speed in rad/s: each cell at `Ω = ω/ω0` of its own model.
    Si(f64),
}

/// Neither axis is the speed: every point its own model at speed `w`. A block's row buffers
/// are allocated once and reused; where points fail, the error is the one of the
/// lowest-numbered row's first failing point.
fn map_fixed_speed<F: ModelFamily>(
    spec: &F,
    x: &Axis,
    y: &Axis,
    w: CellSpeed,
    s: &MapSettings,
    on_row: &mut dyn FnMut(usize, &[Cell]) -> bool,
) -> Result<MapOutcome> {
    // the model's Ω at this speed (a model without an SI scale has no Ω for a speed in SI)
    let omega_of = |m: &SpatialModel| -> Result<f64> {
        let w = match w {
            CellSpeed::Omega(w) => w,
            CellSpeed::Si(w) => {
                w / m.scale.map(|k| k.omega0).ok_or_else(|| Error::invalid(OMEGA, "a speed in SI needs the rotor's ω0 (a dimensional config): give it as Ω"))?
            }
        };
        Ok(w.max(OMEGA_FLOOR))
    };
    let nx = x.values.len();
    let ny = y.values.len();
    let block = (BLOCK_CELLS / nx).max(2 * rayon::current_num_threads());
    let mut rows: Vec<Vec<Cell>> = (0..block.min(ny)).map(|_| Vec::with_capacity(nx)).collect();
    let mut done: Vec<Result<()>> = Vec::with_capacity(block.min(ny));
    let mut out = MapOutcome { complete: true, ..Default::default() };
    let mut j0 = 0;
    while j0 < ny {
        let j1 = (j0 + block).min(ny);
        rows[..j1 - j0]
            .par_iter_mut()
            .zip(&y.values[j0..j1])
            .map(|(cells, &yv)| {
                let sy = spec.with(&y.path, yv)?;
                cells.clear();
                for &xv in &x.values {
                    let m = sy.with(&x.path, xv)?.model()?;
                    let w = omega_of(&m)?;
                    let ss = StateSpace::new(&m, s.balls)?;
                    let necessary = autobalancing_ranges(&m).ranges.iter().any(|r| r.contains(w));
                    cells.push(match s.quantity {
                        Quantity::Margin => {
                            let a = spectral_abscissa(&ss.at(w), ss.states).map_err(|_| no_conv(w))?;
                            Cell { margin: a, stable: counts_as_stable(a, s.balls), necessary }
                        }
                        Quantity::Verdict => Cell { margin: f64::NAN, stable: strictly_stable_at(&ss, w), necessary },
                    });
                }
                Ok(())
            })
            .collect_into_vec(&mut done);
        first_error(&mut done)?;
        for jj in 0..j1 - j0 {
            out.rows += 1;
            out.direct += nx;
            if !on_row(j0 + jj, &rows[jj]) {
                out.complete = false;
                return Ok(out);
            }
        }
        j0 = j1;
    }
    Ok(out)
}

/// A stability map ([`stability_map`]) whose speed axis may be given in SI:
/// `speed_rpm`, `speed` (rad/s) or `speed_hz` beside `omega` (`Ω`), for a dimensional config.
/// Each speed is converted to `Ω = ω/ω0` with the `ω0 = sqrt(c_x/M_s)` of the model at that
/// point: where the other axis does not change `ω0` (a position, a drag, a damping), the map is
/// the map over the `omega` axis of the converted speeds, cell for cell; where it does (a mass,
/// a stiffness), every line of the other axis is mapped over its own `Ω` values. The cells
/// are the same either way; rows go to `on_row` in order.
///
/// ```
/// use autobal::spatial::map::{stability_map, stability_map_units, Axis, MapSettings};
/// let root = autobal::config::parse(include_str!("../../../../examples/washing_machine.toml"), "w").unwrap();
/// let c = autobal::config::spatial(&root).unwrap();
/// let w0 = c.model.scale.unwrap().omega0;
/// let x = Axis::linspace("balancer.z", 0.05, 0.15, 3);
/// let rpm = Axis::linspace("speed_rpm", 300.0, 1500.0, 5);
/// let omega = Axis { path: "omega".into(), values: rpm.values.iter().map(|n| n * std::f64::consts::PI / 30.0 / w0).collect() };
/// let (mut a, mut b) = (vec![], vec![]);
/// let none = autobal::control::Control::none();
/// stability_map_units(&c.spec, &x, &rpm, &MapSettings::default(), &none, &mut |_, r| { a.push(r.to_vec()); true }).unwrap();
/// stability_map(&c.spec, &x, &omega, &MapSettings::default(), &none, &mut |_, r| { b.push(r.to_vec()); true }).unwrap();
/// assert_eq!(a, b);
/// ```
pub fn stability_map_units(
    spec: &SpatialSpec,
    x: &Axis,
    y: &Axis,
    s: &MapSettings,
    control: &crate::control::Control,
    on_row: &mut dyn FnMut(usize, &[Cell]) -> bool,
) -> Result<MapOutcome> {
    use crate::control::StopReason;
    use crate::spatial::paths::{omega0_at, si_speed_axis};
    use rayon::prelude::*;
    let Some((i, k)) = si_speed_axis(spec, [&x.path, &y.path])? else { return stability_map(spec, x, y, s, control, on_row) };
    let (speed, other) = if i == 0 { (x, y) } else { (y, x) };
    if speed.values.iter().any(|v| !(v.is_finite() && *v >= 0.0)) || speed.values.windows(2).any(|w| w[1] < w[0]) {
        return Err(Error::invalid(speed.path.clone(), "the speeds must be finite, non-negative and ascending"));
    }
    let w0: Vec<f64> = other.values.par_iter().map(|&v| omega0_at(spec, &other.path, v)).collect::<Result<_>>()?;
    let to_omega = |w0: f64| Axis { path: OMEGA.into(), values: speed.values.iter().map(|v| v * k / w0).collect() };
    if w0.iter().all(|w| *w == w0[0]) {
        // ω0 the same on every line: one map over the converted speeds
        let om = to_omega(w0[0]);
        return if i == 0 { stability_map(spec, &om, y, s, control, on_row) } else { stability_map(spec, x, &om, s, control, on_row) };
    }
    // ω0 changes with the other axis: each line over its own Ω values
    let line = |j: usize, speeds: std::ops::Range<usize>| -> Result<(Vec<Cell>, MapOutcome)> {
        let one = Axis { path: other.path.clone(), values: vec![other.values[j]] };
        let mut om = to_omega(w0[j]);
        om.values = om.values[speeds].to_vec();
        let mut cells = vec![];
        // the line stops before it starts once the control says so (a Ctrl-C during a block
        // of lines computed in parallel); the block is then dropped whole, below
        let out = stability_map(spec, &om, &one, s, control, &mut |_, r| {
            cells.extend_from_slice(r);
            true
        })?;
        Ok((cells, out))
    };
    let nx = x.values.len();
    if let Some(why) = control.should_stop() {
        return Ok(MapOutcome { stopped: Some(why), ..Default::default() });
    }
    let mut why = None;
    let mut on_row = ask_control(control, y.values.len(), on_row, &mut why);
    let mut out = MapOutcome { complete: true, ..Default::default() };
    let block = ((1usize << 18) / nx).max(2 * rayon::current_num_threads());
    let mut j0 = 0;
    while j0 < y.values.len() {
        let j1 = (j0 + block).min(y.values.len());
        let stopped = |out: &mut MapOutcome| -> bool {
            match control.should_stop() {
                Some(why) => {
                    out.complete = false;
                    out.stopped = Some(why);
                    true
                }
                None => false,
            }
        };
        let rows: Vec<Vec<Cell>> = if i == 0 {
            // rows are the lines
            let lines: Vec<_> = (j0..j1).into_par_iter().map(|j| line(j, 0..nx)).collect::<Result<_>>()?;
            if stopped(&mut out) {
                return Ok(out);
            }
            lines
                .into_iter()
                .map(|(c, o)| {
                    out.continued += o.continued;
                    out.direct += o.direct;
                    c
                })
                .collect()
        } else {
            // rows are speeds: every line over this block of speeds
            let cols: Vec<_> = (0..nx).into_par_iter().map(|j| line(j, j0..j1)).collect::<Result<_>>()?;
            if stopped(&mut out) {
                return Ok(out);
            }
            for (_, o) in &cols {
                out.continued += o.continued;
                out.direct += o.direct;
            }
            (0..j1 - j0).map(|jj| cols.iter().map(|(c, _)| c[jj]).collect()).collect()
        };
        for (jj, row) in rows.iter().enumerate() {
            out.rows += 1;
            if !on_row(j0 + jj, row) {
                out.complete = false;
                drop(on_row);
                out.stopped = Some(why.unwrap_or(StopReason::Observer));
                return Ok(out);
            }
        }
        j0 = j1;
    }
    Ok(out)
}

/// A stability map at one speed given in SI, `w` rad/s, over two axes that may move the
/// rotor's `ω0 = sqrt(c_x/M_s)` (a mass, a stiffness): every cell at its own
/// `Ω = w/ω0(x, y)` of paper 000's eqs (8), (10) for that cell's rotor (whose every
/// dimensionless coefficient is scaled by that `ω0`), so that the whole
/// map is the one speed an engineer asks about (a washer's spin at 1400 rpm over its ball mass
/// and suspension). Each cell is its own model solved directly at its `Ω`, as every cell of a
/// map without a speed axis is (`s.omega` is not read); a cell equals the one-point map at
/// that `Ω` (the example). Rows go to `on_row` in order; the control is asked between rows.
///
/// Errors: an axis that is a speed (the speed is `w`), a path the model refuses, a rotor
/// without an SI scale (a dimensionless config: give `Ω`).
///
/// ```
/// use autobal::spatial::map::{stability_map, stability_map_at_speed, Axis, MapSettings};
/// let root = autobal::config::parse(include_str!("../../../../examples/washing_machine.toml"), "w").unwrap();
/// let c = autobal::config::spatial(&root).unwrap();
/// let w = 1400.0 * std::f64::consts::PI / 30.0; // 1400 rpm in rad/s
/// let x = Axis::linspace("balancer.ball_mass", 0.1, 0.5, 3);
/// let y = Axis::linspace("supports.stiffness_left", 1e4, 3e4, 2);
/// let mut rows = vec![];
/// stability_map_at_speed(&c.spec, &x, &y, w, &MapSettings::default(), &autobal::control::Control::none(), &mut |_, r| {
///     rows.push(r.to_vec());
///     true
/// })
/// .unwrap();
/// // the last cell is the rotor with 0.5 kg of balls on 3e4 N/m springs, at its own Ω
/// let mut one = c.spec.clone();
/// one.set("balancer.ball_mass", 0.5).unwrap();
/// one.set("supports.stiffness_left", 3e4).unwrap();
/// let omega = w / one.build().unwrap().scale.unwrap().omega0;
/// let point = |path: &str, v: f64| Axis { path: path.into(), values: vec![v] };
/// let s = MapSettings { omega: Some(omega), ..MapSettings::default() };
/// let mut cell = vec![];
/// stability_map(&c.spec, &point("balancer.ball_mass", 0.5), &point("supports.stiffness_left", 3e4), &s, &autobal::control::Control::none(), &mut |_, r| {
///     cell = r.to_vec();
///     true
/// })
/// .unwrap();
/// assert_eq!(rows[1][2], cell[0]);
/// ```
pub fn stability_map_at_speed<F: ModelFamily>(
    spec: &F,
    x: &Axis,
    y: &Axis,
    w: f64,
    s: &MapSettings,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[Cell]) -> bool,
) -> Result<MapOutcome> {
    for a in [x, y] {
        if crate::units::speed_path_unit(&a.path).is_some() {
            return Err(Error::invalid(a.path.clone(), "the map's speed is given (one speed in SI): its axes are two other parameters"));
        }
    }
    if !(w.is_finite() && w >= 0.0) {
        return Err(Error::invalid(OMEGA, format!("the speed must be finite and non-negative, got {w} rad/s")));
    }
    map_at(spec, x, y, s, Some(w), control, on_row)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::params::DimensionlessInput;
    use crate::spatial::paths::SpatialInput;

    #[test]
    fn a_lines_polynomial_from_the_plane_is_its_own_expansion() {
        // z̄_A enters eq (6) affinely, so the plane's polynomial at each line is the exact
        // characteristic polynomial of that line's pencil, computed by other sums (Horner in u
        // over the plane's expansion) than the line's own Laplace expansion: equal to rounding.
        // Bound: 1e-11 of the size of the terms summed into each c_k(Ω)
        // (`SpeedPolynomial::magnitudes`), a few hundred ε for the ≤ 12-fold products of the
        // expansion and the fit's rounding (the pencil reproduced to ≤ 1e-15 of each matrix
        // here; measured below 1e-13).
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(DimensionlessInput::default()), delta_a_override: None };
        let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, 21);
        let plane = LinePlane::new(&spec, &x, Balls::Free).expect("z_a is affine");
        let mut worst = 0.0f64;
        for &v in &x.values {
            let t = Pencil::terms(&spec.with(&x.path, v).unwrap().model().unwrap(), Balls::Free).unwrap();
            let got = plane.speed_polynomial(v, &t).expect("the plane reproduces the line's pencil");
            let want = SpeedPolynomial::new(&t).unwrap();
            for w in [0.05, 0.7, 1.3, 2.9, 4.5] {
                let (a, b, size) = (got.at(w), want.at(w), want.magnitudes(w));
                for k in 0..=12 {
                    let e = (a[k] - b[k]).abs() / size[k];
                    worst = worst.max(e);
                    assert!(e <= 1e-11, "z_a = {v}, Ω = {w}: c_{k} {} vs {} (size {})", a[k], b[k], size[k]);
                }
            }
            // a pencil the plane does not reproduce takes its own expansion
            let mut off = t;
            off.m[0][0] *= 1.0 + 1e-9;
            assert!(plane.speed_polynomial(v, &off).is_none());
        }
        eprintln!("worst relative difference {worst:e}");
        // too few lines, or a parameter the model does not follow as a polynomial of degree
        // ≤ 2 (ρ̄s): no plane
        assert!(LinePlane::new(&spec, &Axis::linspace("dimensionless.z_a", -2.0, 2.0, PLANE_LINES - 1), Balls::Free).is_none());
        assert!(LinePlane::new(&spec, &Axis::linspace("dimensionless.rho_s", 0.2, 0.8, 20), Balls::Free).is_none());
    }

    /// The dimensionless family, refusing the `z_a` values above `bad` (the error names the
    /// value), as a front end's family might refuse some of its values.
    #[derive(Clone)]
    struct Refusing {
        spec: SpatialSpec,
        bad: f64,
    }

    impl ModelFamily for Refusing {
        fn with(&self, path: &str, value: f64) -> Result<Self> {
            if path == "dimensionless.z_a" && value > self.bad {
                return Err(Error::invalid(path, format!("refused {value}")));
            }
            Ok(Refusing { spec: self.spec.with(path, value)?, bad: self.bad })
        }
        fn model(&self) -> Result<SpatialModel> {
            self.spec.model()
        }
    }

    #[test]
    fn lines_kept_across_blocks_give_the_cells_of_lines_built_in_their_jobs() {
        // One block (each line built, seeded and dropped in its job) and blocks of 5 and 7
        // speeds (the lines built once and kept): the margin is continued line by line through
        // the same speeds from the same seeds whatever the blocks, so the cells are equal bit for
        // bit (compared as bits: NaN-free here, and equality must be exact, not to a tolerance),
        // and so are the counts of the routes. 20 lines: the plane and the seeds of groups of
        // 16 lines (a partial group) are used.
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(DimensionlessInput::default()), delta_a_override: None };
        let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, 20);
        let y = Axis::linspace(OMEGA, 0.05, 4.5, 23);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        for q in [Quantity::Margin, Quantity::Verdict] {
            let s = MapSettings { quantity: q, ..MapSettings::default() };
            let run = |block_cells: usize| {
                let mut cells = vec![];
                let mut rows = vec![];
                let o = pool
                    .install(|| {
                        map_speed_rows_in(&spec, &x, &y, &s, block_cells, &mut |j, r| {
                            rows.push(j);
                            cells.extend(r.iter().map(|c| (c.margin.to_bits(), c.stable, c.necessary)));
                            true
                        })
                    })
                    .unwrap();
                (cells, rows, o)
            };
            let (one, rows, o1) = run(BLOCK_CELLS);
            assert_eq!(rows, (0..23).collect::<Vec<_>>());
            assert_eq!(one.len(), 20 * 23);
            assert!(one.iter().any(|c| c.1) && one.iter().any(|c| !c.1), "both verdicts occur");
            for block_cells in [5 * 20, 7 * 20] {
                let (kept, rows, o) = run(block_cells);
                assert_eq!(rows, (0..23).collect::<Vec<_>>());
                if q == Quantity::Margin {
                    assert_eq!(kept, one, "blocks of {}", block_cells / 20);
                    assert_eq!((o.continued, o.direct, o.rows), (o1.continued, o1.direct, o1.rows));
                } else {
                    // the verdict confirms the ends of each block directly as well: more direct
                    // tests, and the same verdicts (none of the polynomial's is wrong here)
                    assert_eq!(kept, one, "blocks of {}", block_cells / 20);
                    assert!(o.direct > o1.direct && o.continued == o1.continued);
                }
            }
        }
    }

    #[test]
    fn a_map_reports_the_error_of_its_lowest_failing_line() {
        // lines 12..20 refuse their model (z_a > 0.3): the error is line 12's, whichever
        // thread reached a failing line first, with the lines built in their jobs or kept, and
        // on the other two paths of a map
        let spec = Refusing { spec: SpatialSpec { input: SpatialInput::Dimensionless(DimensionlessInput::default()), delta_a_override: None }, bad: 0.3 };
        let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, 21);
        let y = Axis::linspace(OMEGA, 0.05, 4.5, 9);
        let want = format!("refused {}", x.values[12]);
        for threads in [1, 4] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for q in [Quantity::Margin, Quantity::Verdict] {
                let s = MapSettings { quantity: q, ..MapSettings::default() };
                for block_cells in [BLOCK_CELLS, 2 * 21] {
                    for _ in 0..5 {
                        let e = pool.install(|| map_speed_rows_in(&spec, &x, &y, &s, block_cells, &mut |_, _| panic!("no row of a failed block"))).unwrap_err();
                        assert!(e.to_string().ends_with(&want), "{e}, want {want}");
                    }
                }
                // the lines as rows (speed on x), and every point its own model (the failing
                // axis on y, a fixed speed): the lowest failing row's error
                for _ in 0..5 {
                    let e = pool.install(|| stability_map(&spec, &y, &x, &s, &Control::none(), &mut |_, _| panic!("no row of a failed block"))).unwrap_err();
                    assert!(e.to_string().ends_with(&want), "{e}, want {want}");
                    let h = Axis::linspace("dimensionless.h_x", 0.02, 0.1, 3);
                    let fixed = MapSettings { omega: Some(1.2), ..s };
                    let e =
                        pool.install(|| stability_map(&spec, &h, &x, &fixed, &Control::none(), &mut |_, _| panic!("no row of a failed block"))).unwrap_err();
                    assert!(e.to_string().ends_with(&want), "{e}, want {want}");
                }
            }
        }
    }

    #[test]
    fn a_map_refuses_a_speed_that_is_not_one_even_with_a_speed_axis() {
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(DimensionlessInput::default()), delta_a_override: None };
        let x = Axis::linspace("dimensionless.z_a", -1.0, 1.0, 3);
        let y = Axis::linspace(OMEGA, 0.1, 2.0, 3);
        let s = MapSettings { omega: Some(f64::NAN), ..MapSettings::default() };
        let e = stability_map(&spec, &x, &y, &s, &Control::none(), &mut |_, _| panic!("no row before the settings are checked")).unwrap_err();
        assert_eq!(e.field(), Some(OMEGA), "{e}");
        let mut rows = 0;
        stability_map(&spec, &x, &y, &MapSettings::builder().omega(Some(1.0)).build().unwrap(), &Control::none(), &mut |_, _| {
            rows += 1;
            true
        })
        .unwrap();
        assert_eq!(rows, 3);
    }
}
