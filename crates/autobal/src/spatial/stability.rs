//! Exact linear stability of the balanced state: eigenvalues of the linearised equations
//! ([`crate::spatial::linear_model`]) along the speed axis, stability ranges located by bisection,
//! and Campbell diagrams with mode tracking and whirl classification.
//!
//! A speed is **stable** ([`counts_as_stable`]) when the spectral abscissa `α(Ω) = max Re λ` is
//! below `−`[`STABILITY_TOLERANCE`] with the balls free (asymptotic stability: the balanced state
//! attracts; at Ω → 0 the balls are neutral and do not count), and at most
//! `+`[`STABILITY_TOLERANCE`] with the balls locked (an undamped rotor, whose eigenvalues sit on
//! the imaginary axis, counts as neutrally stable, as the papers' critical-speed analysis
//! assumes). The tolerance only absorbs round-off: eigenvalues of the dimensionless state
//! matrices are accurate to ~1e-14.

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use crate::control::{Control, Outcome};
use crate::error::{Error, Result};
use crate::linalg::charpoly::{continue_roots, modulus, SpeedPolynomial};
use crate::linalg::eigen::{characteristic_polynomial, eigenvalues, routh_hurwitz_stable, spectral_abscissa};
use crate::spatial::critical_speeds::{critical_speeds_at, ModeKind};
use crate::spatial::linear_model::{Balls, Pencil, StateSpace, MAX_STATES};
use crate::spatial::params::SpatialModel;
use crate::spatial::ranges::SpeedRange;
use num_complex::Complex64;
use serde::Serialize;

/// Real parts within this distance of zero count as zero.
pub const STABILITY_TOLERANCE: f64 = 1e-11;

/// `√ε = 2⁻²⁶ ≈ 1.49e-8`: a frequency at most this times the spectrum's scale
/// ([`spectrum_scale`]) is not resolved by the eigenvalue computation ([`log_decrement`]).
pub const FREQUENCY_RESOLUTION: f64 = 1.490_116_119_384_765_6e-8;

/// The logarithmic decrement `δ = −2π σ/|f|` of an eigenvalue of real part `σ` whose motion has
/// the frequency `f` (`ν = Im λ` in rotating axes, `Ω ± ν` in fixed axes), `None` where `|f|`
/// is not resolved: `|f| ≤ `[`FREQUENCY_RESOLUTION`]` · scale`, `scale` the largest `|λ|` of the
/// spectrum at that speed ([`spectrum_scale`]). The one rule of every route and view.
///
/// Why `√ε · scale`: QR returns the exact eigenvalues of `A + E`, `‖E‖ ≈ ε‖A‖`; a simple
/// eigenvalue moves by `κ ε ‖A‖`, but a double one (two real eigenvalues meeting, where a pair
/// reaches the real axis) by up to `√(ε ‖A‖ · ‖N‖)`, `N` the nilpotent part coupling them
/// (`‖N‖ ≤ ‖A‖`): `√ε ‖A‖` at most, and the balanced state matrix's norm is of the order of
/// its spectral radius (examples/spatial.toml at `Ω` = 0.00716: `‖A‖₂` = 2.51, largest `|λ|`
/// = 1.59). A smaller `|f|` can be round-off, and `−2πσ/|f|` then any large number of either
/// whirl; a larger one is the eigenvalue's. A nearly real pair above it keeps its large `δ`:
/// that is its value (the two balls' drag modes of examples/spatial.toml with `h_s` = 0.03 at
/// `Ω` = 0.00716, `σ ± iν = −0.0300011 ± 1.2086e-6 i`, `δ` = 1.56e5 in rotating axes: the same
/// `ν` to 5 digits from 60-digit eigenvalues of the same matrix, with every entry perturbed
/// by an ulp, and smooth in `h_s`, `∝ √(h* − h_s)` down to 1e-11 near where the two meet).
pub fn log_decrement(sigma: f64, f: f64, scale: f64) -> Option<f64> {
    (f.abs() > FREQUENCY_RESOLUTION * scale).then(|| -2.0 * std::f64::consts::PI * sigma / f.abs())
}

/// The scale of a spectrum for [`log_decrement`]: its largest `|λ|` (0 for none).
pub fn spectrum_scale(ev: impl IntoIterator<Item = Complex64>) -> f64 {
    ev.into_iter().map(|z| z.norm()).filter(|x| x.is_finite()).fold(0.0, f64::max)
}

/// The stability verdict from the spectral abscissa (module docs): strict with the balls free,
/// neutral allowed with the balls locked.
pub fn counts_as_stable(alpha: f64, balls: Balls) -> bool {
    match balls {
        Balls::Free => alpha < -STABILITY_TOLERANCE,
        Balls::Locked => alpha <= STABILITY_TOLERANCE,
    }
}

pub(crate) fn no_conv(omega: f64) -> Error {
    Error::NoConvergence { omega }
}

/// Spectral abscissa `max Re λ` at speed `omega`.
pub fn margin(model: &SpatialModel, omega: f64, balls: Balls) -> Result<f64> {
    let p = Pencil::new(model, omega, balls)?;
    spectral_abscissa(&p.state_matrix(), p.states()).map_err(|_| no_conv(omega))
}

/// Spectral abscissa at `omega` from a factored [`StateSpace`] (many speeds of one model).
pub fn margin_at(ss: &StateSpace, omega: f64) -> Result<f64> {
    spectral_abscissa(&ss.at(omega), ss.states).map_err(|_| no_conv(omega))
}

/// Routh–Hurwitz verdict (every `Re λ < 0`) at `omega` from a factored [`StateSpace`].
pub fn strictly_stable_at(ss: &StateSpace, omega: f64) -> bool {
    let c = characteristic_polynomial(&ss.at(omega), ss.states);
    routh_hurwitz_stable(&c[..=ss.states])
}

/// Stability verdict from the Routh–Hurwitz test on the characteristic polynomial: strict
/// (every `Re λ < 0`); several times cheaper than the eigenvalues, for maps.
pub fn is_strictly_stable(model: &SpatialModel, omega: f64, balls: Balls) -> Result<bool> {
    let p = Pencil::new(model, omega, balls)?;
    let n = p.states();
    let c = characteristic_polynomial(&p.state_matrix(), n);
    Ok(routh_hurwitz_stable(&c[..=n]))
}

/// Which coordinates dominate a mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    /// Translation `w` of the centre of mass.
    Translation,
    /// Tilt `χ`.
    Tilt,
    /// The balls' total unbalance `s`.
    Balls,
}

/// Whirl direction in fixed axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Whirl {
    /// In the direction of rotation.
    Forward,
    /// Against it.
    Backward,
    /// Non-oscillating in the rotating frame with no dominant direction.
    None,
}

/// One eigenvalue with its interpretation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Mode {
    /// Eigenvalue in rotating axes, `λ = σ + iν` (dimensionless, unit `ω0`).
    pub re: f64,
    /// Imaginary part `ν`.
    pub im: f64,
    /// Decay rate `−σ`.
    pub decay_rate: f64,
    /// Logarithmic decrement `−2π σ/|ν|` per rotating-axes cycle (`None` for a real
    /// eigenvalue, or where `|ν|` is not resolved: [`log_decrement`]).
    pub log_decrement: Option<f64>,
    /// Dominant coordinate group of the eigenvector.
    pub group: Group,
    /// Whirl frequency in fixed axes of the dominant circular component: `Ω + ν` or `Ω − ν`
    /// (see `forward_share`); positive = forward. It changes branch where the shares cross ½.
    pub fixed_frequency: f64,
    /// Share of the eigenvector's circular component `x_ξ + i x_η` (summed over the coordinate
    /// pairs): in fixed axes the mode whirls at `Ω + ν` with this share of its amplitude squared
    /// and at `Ω − ν` with the rest (an anisotropic rotor has both).
    pub forward_share: f64,
    /// Whirl direction in fixed axes.
    pub whirl: Whirl,
}

/// An eigenvector of the pencil `M λ² + G λ + K` for the eigenvalue `lam`, normalised to unit
/// length, on the stack.
///
/// With the balls free the balls' block of `P(λ)` is `μ E` (`μ = λ² + h̄s λ`: the ball rows
/// of eq (6) have `s'' + h̄s s'` alone), so `s = −P_sr r / μ` and `r = (w, χ)` is the null vector
/// of the 4×4 Schur complement `P_rr − P_rs P_sr / μ`; where `|μ|² < 1e-6 (1 + |λ|⁴)` (the balls'
/// neutral and drag modes at `Ω → 0`) the whole 6×6 `P(λ)` is eliminated instead. The null
/// vector comes from Gaussian elimination with complete pivoting (the last pivot is the one that
/// vanishes).
pub fn pencil_null_vector(p: &Pencil, lam: Complex64) -> [Complex64; 6] {
    let n = p.n;
    let zero = Complex64::new(0.0, 0.0);
    let l2 = lam * lam;
    let entry = |i: usize, j: usize| {
        let (m, g, k) = (p.m[i][j], p.g[i][j], p.k[i][j]);
        Complex64::new(m * l2.re + g * lam.re + k, m * l2.im + g * lam.im)
    };
    let mut a = [[zero; 6]; 6];
    let mut x = [zero; 6];
    let scalar_balls = n == 6 && [&p.m, &p.g, &p.k].iter().all(|b| b[4][5] == 0.0 && b[5][4] == 0.0 && b[4][4] == b[5][5]);
    let mu = if scalar_balls { entry(4, 4) } else { zero };
    if scalar_balls && mu.norm_sqr() >= 1e-6 * (1.0 + l2.norm_sqr()) {
        let inv = mu.inv();
        let p_sr = [[entry(4, 0), entry(4, 1), entry(4, 2), entry(4, 3)], [entry(5, 0), entry(5, 1), entry(5, 2), entry(5, 3)]];
        for i in 0..4 {
            let (r0, r1) = (entry(i, 4) * inv, entry(i, 5) * inv);
            for j in 0..4 {
                a[i][j] = entry(i, j) - (r0 * p_sr[0][j] + r1 * p_sr[1][j]);
            }
        }
        let r = null_vector(&mut a, 4);
        x[..4].copy_from_slice(&r[..4]);
        for b in 0..2 {
            let mut v = zero;
            for j in 0..4 {
                v += p_sr[b][j] * r[j];
            }
            x[4 + b] = -v * inv;
        }
    } else {
        for i in 0..n {
            for j in 0..n {
                a[i][j] = entry(i, j);
            }
        }
        x = null_vector(&mut a, n);
    }
    let nrm = x.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
    if nrm > 0.0 && nrm.is_finite() {
        let s = 1.0 / nrm;
        for z in x.iter_mut() {
            *z *= s;
        }
    }
    x
}

/// A null vector of the (numerically) singular `n×n` matrix `a` (overwritten): Gaussian
/// elimination with complete pivoting, then `U y = 0` with the last entry 1 (the last pivot is
/// the one that vanishes). Not normalised.
fn null_vector(a: &mut [[Complex64; 6]; 6], n: usize) -> [Complex64; 6] {
    let zero = Complex64::new(0.0, 0.0);
    let mut col = [0usize, 1, 2, 3, 4, 5];
    for k in 0..n {
        let (mut pi, mut pj, mut best) = (k, k, -1.0);
        for i in k..n {
            for j in k..n {
                let v = a[i][j].norm_sqr();
                if v > best {
                    (pi, pj, best) = (i, j, v);
                }
            }
        }
        a.swap(k, pi);
        if pj != k {
            for row in a.iter_mut() {
                row.swap(k, pj);
            }
            col.swap(k, pj);
        }
        if best == 0.0 {
            break;
        }
        let inv = a[k][k].inv();
        let pivot_row = a[k];
        for row in a[k + 1..n].iter_mut() {
            let f = row[k] * inv;
            for j in k + 1..n {
                row[j] -= f * pivot_row[j];
            }
        }
    }
    let mut y = [zero; 6];
    y[n - 1] = Complex64::new(1.0, 0.0);
    for k in (0..n - 1).rev() {
        let mut v = zero;
        for j in k + 1..n {
            v -= a[k][j] * y[j];
        }
        y[k] = if a[k][k] != zero { v / a[k][k] } else { Complex64::new(1.0, 0.0) };
    }
    let mut x = [zero; 6];
    for k in 0..n {
        x[col[k]] = y[k];
    }
    x
}

/// Interpret eigenvalue `lam` of `pencil` at speed `omega` from its eigenvector
/// ([`pencil_null_vector`]; the scale of [`log_decrement`] from the pencil's spectrum).
pub fn classify(p: &Pencil, omega: f64, lam: Complex64) -> Mode {
    let scale = eigenvalues(&p.state_matrix(), p.states()).map_or(lam.norm(), spectrum_scale);
    classify_vector(p, omega, lam, &pencil_null_vector(p, lam), scale)
}

/// [`classify`] with the eigenvector given, and the scale of the spectrum at `omega`
/// ([`spectrum_scale`]) for the log decrement's resolution ([`log_decrement`]).
pub fn classify_vector(p: &Pencil, omega: f64, lam: Complex64, x: &[Complex64; 6], scale: f64) -> Mode {
    let n = p.n;
    // kinetic-energy weights: s is the balls' unbalance, about m̄ times their displacement,
    // so the balls' share is |s|²/m̄ (translation and tilt are normalised alike by the papers)
    let ball_weight = 1.0 / p.m[4][0].abs().max(p.m[5][1].abs()).max(1e-12);
    let energy = |k: usize| (x[2 * k].norm_sqr() + x[2 * k + 1].norm_sqr()) * if k == 2 { ball_weight } else { 1.0 };
    let groups = n / 2;
    let mut g = 0;
    for k in 1..groups {
        if energy(k) > energy(g) {
            g = k;
        }
    }
    let group = [Group::Translation, Group::Tilt, Group::Balls][g];
    let i = Complex64::new(0.0, 1.0);
    let (mut fw, mut bw) = (0.0, 0.0);
    for k in 0..groups {
        fw += (x[2 * k] + i * x[2 * k + 1]).norm_sqr();
        bw += (x[2 * k] - i * x[2 * k + 1]).norm_sqr();
    }
    let nu = lam.im;
    let fixed = if fw >= bw { omega + nu } else { omega - nu };
    let whirl = if nu.abs() < 1e-12 && (fw - bw).abs() < 1e-9 * (fw + bw) {
        Whirl::None
    } else if fixed >= 0.0 {
        Whirl::Forward
    } else {
        Whirl::Backward
    };
    Mode {
        re: lam.re,
        im: lam.im,
        decay_rate: -lam.re,
        log_decrement: log_decrement(lam.re, nu, scale),
        group,
        fixed_frequency: fixed,
        forward_share: if fw + bw > 0.0 { fw / (fw + bw) } else { 0.5 },
        whirl,
    }
}

/// All eigenvalues at one speed, sorted by imaginary then real part.
pub fn eigenvalues_at(model: &SpatialModel, omega: f64, balls: Balls) -> Result<(Pencil, Vec<Complex64>)> {
    let p = Pencil::new(model, omega, balls)?;
    let mut ev = eigenvalues(&p.state_matrix(), p.states()).map_err(|_| no_conv(omega))?;
    ev.sort_by(|a, b| a.im.total_cmp(&b.im).then(a.re.total_cmp(&b.re)));
    Ok((p, ev))
}

/// Result of [`stability_ranges`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StabilityRanges {
    /// Speeds `0 < Ω ≤ Ω_max` that are stable by [`counts_as_stable`], from the grid's speeds
    /// `Ω_max/1000 … Ω_max` ([`stability_grid`]); ends located by bisection to `tolerance`,
    /// except a range stable at the first speed analysed, which starts there with the balls
    /// free (nothing below it is analysed, and free balls are unstable below the lowest
    /// critical speed) and at 0 with the balls locked; `hi = None` when the range reaches
    /// `Ω_max`.
    pub stable_ranges: Vec<SpeedRange>,
    /// `(Ω, max Re λ)` on the grid.
    pub max_real_part: Vec<(f64, f64)>,
    /// Bisection tolerance on the ends (dimensionless speed).
    pub tolerance: f64,
}

/// Exact stability ranges over `[omega_max/1000, omega_max]`: a grid of `samples` speeds,
/// seeded with the analytic critical speeds and the middles of their split pairs, then bisection
/// on every change of verdict down to `tol` in Ω (a range stable at the grid's first speed starts
/// there with the balls free, at 0 with the balls locked). A flutter range narrower than the grid spacing can
/// escape the grid; split-pair ranges cannot.
///
/// ```
/// use autobal::spatial::linear_model::Balls;
/// use autobal::spatial::params::{DimensionlessInput, SpatialModel};
/// use autobal::spatial::stability::stability_ranges;
/// // paper 000's base case: balancing is stable at Ω = 1.6, not at 1.72 (between two ranges)
/// let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
/// let s = stability_ranges(&m, 5.0, 2000, Balls::Free, 1e-9).unwrap();
/// assert!(s.stable_ranges.iter().any(|r| r.contains(1.6)));
/// assert!(!s.stable_ranges.iter().any(|r| r.contains(1.72)));
/// ```
pub fn stability_ranges(model: &SpatialModel, omega_max: f64, samples: usize, balls: Balls, tol: f64) -> Result<StabilityRanges> {
    Ok(stability_ranges_with(model, omega_max, samples, balls, tol, &Control::none())?.value)
}

/// [`stability_ranges`] under `control`, asked before each grid speed and each trial speed of
/// a range end's bisection; the progress observer is told the grid speeds done (of the grid's
/// length, the seeded speeds included). Stopped, the outcome holds the grid speeds done until
/// then (`max_real_part`) and the stable ranges among them: an end whose bisection the stop
/// cut short is the stable side's grid speed (stable there, not located), and a range that
/// reaches the last speed analysed ends there (`hi = Some`: nothing is known beyond it), never
/// open to `omega_max`.
pub fn stability_ranges_with(
    model: &SpatialModel,
    omega_max: f64,
    samples: usize,
    balls: Balls,
    tol: f64,
    control: &Control,
) -> Result<Outcome<StabilityRanges>> {
    if !(omega_max > 0.0 && omega_max.is_finite()) {
        return Err(Error::invalid("omega_max", format!("must be a positive number, got {}", crate::error::fmt_num(omega_max))));
    }
    let grid = stability_grid(model, omega_max, samples);
    let ss = StateSpace::new(model, balls)?;
    let mut alpha = Vec::with_capacity(grid.len());
    let mut stopped = None;
    for &w in &grid {
        if let Some(why) = control.should_stop() {
            stopped = Some(why);
            break;
        }
        alpha.push((w, margin_at(&ss, w)?));
        control.report(alpha.len() as u64, grid.len() as u64);
    }
    let stable = |a: f64| counts_as_stable(a, balls);
    let mut ranges: Vec<SpeedRange> = vec![];
    let Some(&(_, a_first)) = alpha.first() else {
        return Ok(Outcome { value: StabilityRanges { stable_ranges: ranges, max_real_part: alpha, tolerance: tol }, stopped });
    };
    // a range stable at the first speed analysed: with the balls free it starts there (the
    // balanced state of free balls is unstable below the lowest critical speed, so a stable
    // first speed means the axis began above it, and nothing below is known: walk 27's axis
    // read "stable 0 – …"); with the balls locked at 0 (a damped rotor near rest is stable,
    // neutral without damping, which the locked verdict allows)
    let mut start: Option<f64> = if stable(a_first) { Some(if balls == Balls::Locked { 0.0 } else { alpha[0].0 }) } else { None };
    for k in 1..alpha.len() {
        let (w0, a0) = alpha[k - 1];
        let (w1, a1) = alpha[k];
        if stable(a0) != stable(a1) {
            let (mut lo, mut hi) = (w0, w1);
            let mut cut = false;
            while hi - lo > tol {
                if let Some(why) = control.should_stop() {
                    stopped = Some(why);
                    cut = true;
                    break;
                }
                let mid = 0.5 * (lo + hi);
                if stable(margin_at(&ss, mid)?) == stable(a0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            // not located (stopped): the stable side's grid speed, where it is known stable
            let edge = if cut {
                if stable(a1) {
                    w1
                } else {
                    w0
                }
            } else {
                0.5 * (lo + hi)
            };
            if stable(a1) {
                start = Some(edge);
            } else if let Some(s) = start.take() {
                ranges.push(SpeedRange { lo: s, hi: Some(edge) });
            }
        }
    }
    if let Some(s) = start {
        // open to omega_max only where the whole grid was analysed
        let hi = (alpha.len() < grid.len()).then(|| alpha[alpha.len() - 1].0);
        ranges.push(SpeedRange { lo: s, hi });
    }
    Ok(Outcome { value: StabilityRanges { stable_ranges: ranges, max_real_part: alpha, tolerance: tol }, stopped })
}

/// The speeds [`stability_ranges`] analyses over `(0, omega_max]`: `samples` (at least 2)
/// evenly spaced from `omega_max / 1000`, with the analytic split pairs (locked rotor, ΔĀ and
/// ΔĀ0) and their middles added: their instability ranges can be far narrower than the grid
/// spacing (near-symmetric layouts); ascending, each once.
pub fn stability_grid(model: &SpatialModel, omega_max: f64, samples: usize) -> Vec<f64> {
    let samples = samples.max(2);
    let lo0 = omega_max * 1e-3;
    let mut grid: Vec<f64> = (0..samples).map(|i| lo0 + (omega_max - lo0) * i as f64 / (samples - 1) as f64).collect();
    for d in [model.anisotropy.used, model.delta_a0] {
        let roots = critical_speeds_at(model, d);
        for kind in [ModeKind::Transverse, ModeKind::Angular] {
            let pair: Vec<f64> = roots.iter().filter(|r| r.1 == kind).map(|r| r.0).collect();
            for w in &pair {
                grid.push(*w);
            }
            if pair.len() == 2 {
                grid.push(0.5 * (pair[0] + pair[1]));
            }
        }
    }
    grid.retain(|w| *w >= lo0 && *w <= omega_max);
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    grid
}

/// One tracked eigenvalue line of a Campbell diagram.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CampbellLine {
    /// One entry per speed of the diagram.
    pub modes: Vec<Mode>,
}

/// Campbell diagram: eigenvalues along a speed grid, tracked into lines.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Campbell {
    /// The speeds.
    pub omega: Vec<f64>,
    /// Tracked lines (all `2n` eigenvalues; conjugate lines have `im < 0`).
    pub lines: Vec<CampbellLine>,
}

/// How the eigenvalues of a Campbell diagram were found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct CampbellStats {
    /// Speeds handed to the caller.
    pub speeds: usize,
    /// Whether every speed was computed (`false`: the caller asked to stop).
    pub complete: bool,
    /// Speeds whose spectrum came from certified continuation of the roots of the
    /// characteristic polynomial.
    pub continued: usize,
    /// Speeds that needed the QR eigenvalues.
    pub direct: usize,
}

/// Optimal assignment of the first `n×n` of `cost` ([`crate::linalg::assignment::assignment`]).
fn assignment(cost: &[[f64; MAX_STATES]; MAX_STATES], n: usize) -> [usize; MAX_STATES] {
    let mut out = [0usize; MAX_STATES];
    out[..n].copy_from_slice(&crate::linalg::assignment::assignment(|r, c| cost[r][c], n));
    out
}

/// Modal assurance criterion `|x·y|²` of two unit vectors.
fn mac(x: &[Complex64; 6], y: &[Complex64; 6]) -> f64 {
    let (mut re, mut im) = (0.0, 0.0);
    for k in 0..6 {
        re += x[k].re * y[k].re + x[k].im * y[k].im;
        im += x[k].re * y[k].im - x[k].im * y[k].re;
    }
    re * re + im * im
}

/// The optimal assignment of lines (rows) to eigenvalues (columns) for the tracking cost
/// `cost(i, j) ≥ dist[i][j]`, evaluating `cost` only where needed: each row's minimum is found
/// among the columns whose `dist` is below the best cost so far; when those minima fall in
/// different columns they are the optimum (their sum bounds every assignment from below),
/// otherwise the full matrix goes to the Hungarian method ([`assignment`]).
fn tracking_assignment(dist: &[[f64; MAX_STATES]; MAX_STATES], cost: &dyn Fn(usize, usize) -> f64, n: usize) -> [usize; MAX_STATES] {
    let mut order = [0usize; MAX_STATES];
    let mut used = [false; MAX_STATES];
    let mut permutation = true;
    for i in 0..n {
        let mut first = 0;
        for j in 1..n {
            if dist[i][j] < dist[i][first] {
                first = j;
            }
        }
        let (mut best_j, mut best) = (first, cost(i, first));
        for j in 0..n {
            if j != first && dist[i][j] < best {
                let c = cost(i, j);
                if c < best {
                    (best_j, best) = (j, c);
                }
            }
        }
        order[i] = best_j;
        permutation &= !used[best_j];
        used[best_j] = true;
    }
    if permutation {
        return order;
    }
    let mut full = [[0.0; MAX_STATES]; MAX_STATES];
    for i in 0..n {
        for j in 0..n {
            full[i][j] = cost(i, j);
        }
    }
    assignment(&full, n)
}

/// Campbell diagram over the speeds `omegas` (ascending), streamed: at each speed `on_speed(k, modes)`
/// receives the modes in line order (line `i` is the same tracked eigenvalue at every speed);
/// it returns `false` to stop. Memory does not grow with the number of speeds. A speed that
/// does not increase on the one before is an error (`omega`), after the speeds before it.
///
/// The spectrum at each speed comes from the exact characteristic polynomial in `Ω`
/// ([`SpeedPolynomial`]): Newton's method from the previous speeds' eigenvalues, certified by
/// disjoint inclusion disks (then they are all `N` roots), else the QR eigenvalues. Lines are
/// continued by an optimal assignment (Hungarian method) between the extrapolated eigenvalues
/// and eigenvectors of the previous speeds and the new ones, with cost
/// `|λ_pred − λ| / h + 4 (1 − MAC)` (`h` the speed step, MAC the modal assurance criterion of
/// the eigenvectors): where two eigenvalues pass close, the eigenvectors decide.
///
/// The outcome says whether every speed was computed ([`CampbellStats::complete`]):
///
/// ```
/// use autobal::spatial::linear_model::Balls;
/// use autobal::spatial::params::{DimensionlessInput, SpatialModel};
/// use autobal::spatial::stability::campbell_stream;
/// let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
/// let speeds = (1..=300).map(|k| 5.0 * k as f64 / 300.0);
/// let mut seen = 0;
/// let stats = campbell_stream(&m, speeds.clone(), Balls::Free, &mut |_, modes| {
///     assert_eq!(modes.len(), 12); // 12 states with the balls free
///     seen += 1;
///     seen < 10 // stop after ten speeds
/// }).unwrap();
/// assert!(!stats.complete && stats.speeds == 10);
/// let all = campbell_stream(&m, speeds, Balls::Free, &mut |_, _| true).unwrap();
/// assert!(all.complete && all.speeds == 300);
/// ```
pub fn campbell_stream(
    model: &SpatialModel,
    omegas: impl IntoIterator<Item = f64>,
    balls: Balls,
    on_speed: &mut dyn FnMut(usize, &[Mode]) -> bool,
) -> Result<CampbellStats> {
    let ss = StateSpace::new(model, balls)?;
    let n = ss.states;
    let terms = Pencil::terms(model, balls)?;
    let poly = SpeedPolynomial::new(&terms);
    let zero = Complex64::new(0.0, 0.0);
    // line i: eigenvalues at the last two speeds, eigenvector at the last
    let mut lam = [[zero; MAX_STATES]; 2];
    let mut vec = [[zero; 6]; MAX_STATES];
    let mut stats = CampbellStats { complete: true, ..Default::default() };
    let mut modes = Vec::with_capacity(n);
    let mut prev_w = [0.0f64; 2];
    for (step, w) in omegas.into_iter().enumerate() {
        // the tracking extrapolates over the speed step: a speed that does not increase (a
        // repeated one made the step 0/0 and the root continuation never settled) is refused
        if step > 0 && !(w > prev_w[1]) {
            return Err(Error::invalid(
                "omega",
                format!("the speeds must increase: {} follows {}", crate::error::fmt_num(w), crate::error::fmt_num(prev_w[1])),
            ));
        }
        let p = Pencil::new(model, w, balls)?;
        let mut ev = [zero; MAX_STATES];
        // each line's eigenvalue extrapolated linearly from the last two speeds
        let f = if step >= 2 { (w - prev_w[1]) / (prev_w[1] - prev_w[0]) } else { 0.0 };
        let predict = |i: usize| lam[1][i] + (lam[1][i] - lam[0][i]) * f;
        let mut found = false;
        if let (Some(sp), true) = (&poly, step > 0) {
            let c = sp.at(w);
            let mut starts = [zero; MAX_STATES];
            for i in 0..n {
                starts[i] = predict(i);
            }
            found = continue_roots(&c[..=n], &starts[..n], &mut ev[..n]).is_some();
        }
        if found {
            stats.continued += 1;
        } else {
            stats.direct += 1;
            let e = eigenvalues(&ss.at(w), n).map_err(|_| no_conv(w))?;
            ev[..n].copy_from_slice(&e);
        }
        // eigenvectors: one elimination per eigenvalue with Im ≥ 0, conjugates mirrored
        let mut xs = [[zero; 6]; MAX_STATES];
        for j in 0..n {
            if ev[j].im >= 0.0 {
                xs[j] = pencil_null_vector(&p, ev[j]);
            }
        }
        for j in 0..n {
            if ev[j].im < 0.0 {
                // the conjugate partner: nearest conj among Im > 0
                let partner =
                    (0..n).filter(|&k| ev[k].im > 0.0).min_by(|&a, &b| (ev[a].conj() - ev[j]).norm_sqr().total_cmp(&(ev[b].conj() - ev[j]).norm_sqr()));
                xs[j] = match partner {
                    Some(k) => xs[k].map(|z| z.conj()),
                    None => pencil_null_vector(&p, ev[j]),
                };
            }
        }
        let order: [usize; MAX_STATES] = if step == 0 {
            // first speed: lines sorted by imaginary then real part
            let mut idx: Vec<usize> = (0..n).collect();
            idx.sort_by(|&a, &b| ev[a].im.total_cmp(&ev[b].im).then(ev[a].re.total_cmp(&ev[b].re)));
            let mut o = [0; MAX_STATES];
            o[..n].copy_from_slice(&idx);
            o
        } else {
            let h = (w - prev_w[1]).abs().max(1e-12);
            let mut dist = [[0.0; MAX_STATES]; MAX_STATES];
            for i in 0..n {
                let pred = predict(i);
                for j in 0..n {
                    dist[i][j] = modulus(pred - ev[j]) / h;
                }
            }
            let cost_of = |i: usize, j: usize| dist[i][j] + 4.0 * (1.0 - mac(&vec[i], &xs[j]));
            tracking_assignment(&dist, &cost_of, n)
        };
        modes.clear();
        let scale = spectrum_scale(ev[..n].iter().copied());
        for i in 0..n {
            let j = order[i];
            lam[0][i] = lam[1][i];
            lam[1][i] = ev[j];
            vec[i] = xs[j];
            modes.push(classify_vector(&p, w, ev[j], &xs[j], scale));
        }
        prev_w = [prev_w[1], w];
        stats.speeds += 1;
        if !on_speed(step, &modes) {
            stats.complete = false;
            break;
        }
    }
    Ok(stats)
}

/// Campbell diagram over `omegas` (ascending), kept in memory ([`campbell_stream`] for large
/// ones).
pub fn campbell(model: &SpatialModel, omegas: &[f64], balls: Balls) -> Result<Campbell> {
    let mut lines: Vec<CampbellLine> = vec![];
    campbell_stream(model, omegas.iter().copied(), balls, &mut |_, modes| {
        if lines.is_empty() {
            lines = modes.iter().map(|_| CampbellLine { modes: Vec::with_capacity(omegas.len()) }).collect();
        }
        for (l, m) in lines.iter_mut().zip(modes) {
            l.modes.push(*m);
        }
        true
    })?;
    Ok(Campbell { omega: omegas.to_vec(), lines })
}
