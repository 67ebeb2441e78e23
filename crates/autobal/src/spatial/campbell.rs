//! The Campbell diagram as engineers read it: one continuous natural-frequency curve per mode
//! in **fixed** axes, with its whirl direction and logarithmic decrement at every speed, and the
//! critical speeds where the curves cross the `h×` excitation lines.
//!
//! In rotating axes an eigenvalue `λ = σ + iν` with eigenvector `x` moves each coordinate pair
//! `(ξ, η)` as `Re(x e^{λt})`; in fixed axes (multiplied by `e^{iΩt}`) that is a circular
//! component at `Ω + ν` (amplitude `|x_ξ + i x_η|`) and one at `Ω − ν` (amplitude
//! `|x_ξ − i x_η|`): see [`Mode::forward_share`](crate::spatial::stability::Mode::forward_share). A curve follows the dominant component; where
//! the dominance switches (an elliptic mode whose minor component grows past the major one) the
//! dominant frequency jumps by `2|ν|`, so the curve keeps the component that continues its
//! previous values: it leaves the dominant component only where the other one lies closer to
//! the curve's linear extrapolation by more than two speed steps. The frequency is signed: `f > 0` forward whirl, `f < 0`
//! backward; the curve is drawn at `|f|`.
//!
//! The logarithmic decrement per fixed-axes cycle is `δ = −2π σ/|f|` (the fixed-axes eigenvalue
//! of the component is `σ + i f`, ROSS's convention); `δ > 0` decays. (The rotating-axes
//! [`Mode::log_decrement`](crate::spatial::stability::Mode::log_decrement) divides by `|ν|` instead.)
//!
//! A curve meets the line `h Ω` where `g(Ω) = |f(Ω)| − hΩ` vanishes. With `h = 1` and forward
//! whirl, `g = ±ν`: the rotating-axes eigenvalue is real, and with the balls locked and no
//! damping it is `λ = 0`, i.e. `det K(Ω) = 0`: 000 eq (15)-(16)'s critical speeds. Crossings
//! are bracketed on the grid and located by bisection on the model's eigenvalues; where a curve
//! runs along the line over an interval (a divergence range between split critical speeds,
//! where the rotating-axes pair is real) both ends are reported.

use crate::error::{Error, Result};
use crate::linalg::eigen::eigenvalues;
use crate::spatial::linear_model::{Balls, Pencil};
use crate::spatial::params::SpatialModel;
use crate::spatial::stability::{classify_vector, no_conv, pencil_null_vector, Campbell, Whirl};
use num_complex::Complex64;
use serde::Serialize;

/// `|Im λ|` below this counts as a real eigenvalue (QR round-off on real roots).
const REAL_TOL: f64 = 1e-9;
/// `|g| = ||f| − hΩ|` at most this (times `max(1, hΩ)`) counts as on the excitation line. A
/// linear crossing (`|g'|` ≳ 0.01) is then located to ~1e-8 by the band's midpoint; at a split
/// critical speed (`g ~ sqrt(Ω − Ω_K)`, eigenvalues accurate to ~1e-8 at the double root) the
/// error is the square of that noise, ~1e-16.
const ON_LINE_TOL: f64 = 1e-10;
/// Bisection stops at this width (relative to `max(1, Ω)`).
const BISECT_TOL: f64 = 1e-13;
/// Entry and exit of an excitation line closer than this (relative) are one crossing.
const MERGE_TOL: f64 = 1e-9;

/// One speed of a fixed-axes curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FixedPoint {
    /// Speed `Ω`.
    pub omega: f64,
    /// Natural frequency in fixed axes `|f|`, `f = Ω ± ν` the followed component (unit `ω0`).
    pub frequency: f64,
    /// The signed frequency `f` (positive: forward whirl).
    pub fixed_frequency: f64,
    /// Whirl direction: forward where `f > 0`, backward where `f < 0` (the previous one at `f = 0`).
    pub whirl: Whirl,
    /// Real part `σ` of the eigenvalue (unit `ω0`).
    pub re: f64,
    /// Rotating-axes frequency `ν = Im λ`.
    pub nu: f64,
    /// Logarithmic decrement per fixed-axes cycle `δ = −2π σ/|f|` (`None` where `|f| < 1e-12`).
    pub log_decrement: Option<f64>,
    /// Share of the followed component in the eigenvector's amplitude squared (`≥ ½` where the
    /// curve follows the dominant one).
    pub share: f64,
}

/// One mode's curve in fixed axes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FixedCurve {
    /// The tracked line of the [`Campbell`] it comes from.
    pub line: usize,
    /// One point per speed of the diagram.
    pub points: Vec<FixedPoint>,
}

/// A crossing of a curve with the excitation line `h Ω`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CriticalSpeed {
    /// Speed `Ω` of the crossing.
    pub omega: f64,
    /// Harmonic `h` of the excitation line.
    pub harmonic: u32,
    /// Index of the curve in [`FixedCampbell::curves`] (the mode number − 1).
    pub curve: usize,
    /// Whirl direction of the curve there.
    pub whirl: Whirl,
    /// Natural frequency there, `hΩ`.
    pub frequency: f64,
}

/// A Campbell diagram in fixed axes: curves sorted by their frequency at the first speed
/// (mode 1 the lowest), and the critical speeds sorted by speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FixedCampbell {
    /// The speeds.
    pub omega: Vec<f64>,
    /// One curve per mode (a conjugate line describes the same real motion and is left out).
    pub curves: Vec<FixedCurve>,
    /// Crossings with the excitation lines.
    pub critical_speeds: Vec<CriticalSpeed>,
    /// The harmonics `h` searched.
    pub harmonics: Vec<u32>,
}

fn lam(m: &crate::spatial::stability::Mode) -> Complex64 {
    Complex64::new(m.re, m.im)
}

/// Whether two lines are conjugates at speed `k`.
fn conj_at(c: &Campbell, i: usize, j: usize, k: usize) -> bool {
    let (a, b) = (lam(&c.lines[i].modes[k]), lam(&c.lines[j].modes[k]));
    (b - a.conj()).norm() <= 1e-7 * (1.0 + a.norm())
}

/// The fixed-axes view of a Campbell diagram of `model` (computed with `balls`): one curve per
/// pair of conjugate lines, the log decrement per point and the crossings with `h Ω` for each
/// `h` of `harmonics` (module docs).
///
/// Where a kept line is real (e.g. a divergence range, where a pair splits into two real
/// eigenvalues) its point carries the largest real part of the real eigenvalues of its
/// conjugacy component that are left out there, so that the sign of the log decrement is the
/// stability of all of them.
pub fn fixed_axes(model: &SpatialModel, c: &Campbell, balls: Balls, harmonics: &[u32]) -> Result<FixedCampbell> {
    if let Some(h) = harmonics.iter().find(|&&h| h == 0) {
        return Err(Error::invalid("harmonics", format!("must be positive integers, got {h}")));
    }
    let n = c.omega.len();
    if c.lines.iter().any(|l| l.modes.len() != n) {
        return Err(Error::invalid("campbell", "every line needs one mode per speed"));
    }
    // Conjugate lines describe the same real motion. Tracked pairs can change partners where
    // eigenvalues collide on the real axis (a damped rotor's pair turns into two real ones and
    // back, possibly pairing with another line), so the kept lines are a 2-colouring of the
    // graph whose edges join lines that are conjugates (and complex) at some speed: at every
    // speed each complex pair then has exactly one kept line. Each connected component keeps
    // the colour with more points of Im λ ≥ 0; a line never complex is kept (a real mode).
    let nl = c.lines.len();
    let is_real = |i: usize, k: usize| c.lines[i].modes[k].im.abs() <= REAL_TOL;
    let (component, dropped) = keep_one_of_each_pair(
        nl,
        |i, j| (0..n).any(|k| !is_real(i, k) && !is_real(j, k) && conj_at(c, i, j, k)),
        |l| c.lines[l].modes.iter().filter(|m| m.im >= 0.0).count() as i64,
    );
    let mut curves = vec![];
    for (li, line) in c.lines.iter().enumerate() {
        if dropped[li] || n == 0 {
            continue;
        }
        let mut pts: Vec<FixedPoint> = Vec::with_capacity(n);
        for k in 0..n {
            let m = &line.modes[k];
            let w = c.omega[k];
            let cand = [(w + m.im, m.forward_share), (w - m.im, 1.0 - m.forward_share)];
            let dominant = if m.forward_share >= 0.5 { 0 } else { 1 };
            let pick = if k == 0 {
                dominant
            } else {
                let prev = pts[k - 1].fixed_frequency;
                let pred = if k >= 2 {
                    let (w1, w2) = (c.omega[k - 2], c.omega[k - 1]);
                    prev + (prev - pts[k - 2].fixed_frequency) * (w - w2) / (w2 - w1).max(1e-300)
                } else {
                    prev
                };
                // stay on the dominant component unless the other continues the curve better
                // by more than the continuity bound (two speed steps)
                let h = (w - c.omega[k - 1]).abs();
                let d = |i: usize| (cand[i].0 - pred).abs();
                if d(dominant) > d(1 - dominant) + 2.0 * h {
                    1 - dominant
                } else {
                    dominant
                }
            };
            let (f, share) = cand[pick];
            let mut sigma = m.re;
            if is_real(li, k) {
                // the real eigenvalues of the component left out here: their decay counts
                for j in (0..nl).filter(|&j| dropped[j] && component[j] == component[li] && is_real(j, k)) {
                    sigma = sigma.max(c.lines[j].modes[k].re);
                }
            }
            let whirl = if f > 0.0 {
                Whirl::Forward
            } else if f < 0.0 {
                Whirl::Backward
            } else {
                pts.last().map_or(Whirl::Forward, |p: &FixedPoint| p.whirl)
            };
            pts.push(FixedPoint {
                omega: w,
                frequency: f.abs(),
                fixed_frequency: f,
                whirl,
                re: sigma,
                nu: m.im,
                log_decrement: (f.abs() >= 1e-12).then(|| -2.0 * std::f64::consts::PI * sigma / f.abs()),
                share,
            });
        }
        curves.push(FixedCurve { line: li, points: pts });
    }
    curves.sort_by(|a, b| a.points[0].frequency.total_cmp(&b.points[0].frequency).then(a.line.cmp(&b.line)));
    let mut crit = vec![];
    for &h in harmonics {
        for (ci, cv) in curves.iter().enumerate() {
            crossings(model, c, balls, cv, ci, h, &mut crit)?;
        }
    }
    crit.sort_by(|a: &CriticalSpeed, b| a.omega.total_cmp(&b.omega));
    Ok(FixedCampbell { omega: c.omega.clone(), curves, critical_speeds: crit, harmonics: harmonics.to_vec() })
}

/// Sign of `g = |f| − hΩ` with the on-line band (module docs): −1, 0 or 1.
fn side(f: f64, omega: f64, h: u32) -> i8 {
    let target = h as f64 * omega;
    let g = f.abs() - target;
    if g.abs() <= ON_LINE_TOL * target.max(1.0) {
        0
    } else if g > 0.0 {
        1
    } else {
        -1
    }
}

/// The curve's signed frequency at a speed `w` between grid points `k` and `k + 1`: the
/// eigenvalue nearest the line's interpolated one, its component with the share nearest the
/// interpolated share of the followed component (the nearer frequency where the two shares
/// are within 0.1 of ½).
fn frequency_at(model: &SpatialModel, c: &Campbell, balls: Balls, cv: &FixedCurve, k: usize, w: f64) -> Result<f64> {
    let (w0, w1) = (c.omega[k], c.omega[k + 1]);
    let t = if w1 != w0 { (w - w0) / (w1 - w0) } else { 0.0 };
    let line = &c.lines[cv.line];
    let guess = lam(&line.modes[k]) * (1.0 - t) + lam(&line.modes[k + 1]) * t;
    let f_guess = cv.points[k].fixed_frequency * (1.0 - t) + cv.points[k + 1].fixed_frequency * t;
    let p = Pencil::new(model, w, balls)?;
    let ev = eigenvalues(&p.state_matrix(), p.states()).map_err(|_| no_conv(w))?;
    let l = ev.iter().copied().min_by(|a, b| (a - guess).norm().total_cmp(&(b - guess).norm())).ok_or_else(|| no_conv(w))?;
    let x = pencil_null_vector(&p, l);
    let m = classify_vector(&p, w, l, &x);
    // the component with the followed one's share (at a crossing of 1x the two frequencies
    // differ by less than the interpolation error, their shares not), else the nearer frequency
    let share_guess = cv.points[k].share * (1.0 - t) + cv.points[k + 1].share * t;
    let cand = [(w + m.im, m.forward_share), (w - m.im, 1.0 - m.forward_share)];
    let pick = if (2.0 * m.forward_share - 1.0).abs() > 0.2 {
        if (cand[0].1 - share_guess).abs() <= (cand[1].1 - share_guess).abs() {
            0
        } else {
            1
        }
    } else if (cand[0].0 - f_guess).abs() <= (cand[1].0 - f_guess).abs() {
        0
    } else {
        1
    };
    Ok(cand[pick].0)
}

/// Bisection between `lo` (side `s_lo`) and `hi` (another side) for the end of side `s_lo`;
/// `from_left = false` runs it mirrored (the end of `hi`'s side seen from the right).
#[allow(clippy::too_many_arguments)]
fn bisect(model: &SpatialModel, c: &Campbell, balls: Balls, cv: &FixedCurve, k: usize, h: u32, keep: i8, from_left: bool) -> Result<f64> {
    let (mut lo, mut hi) = (c.omega[k], c.omega[k + 1]);
    while hi - lo > BISECT_TOL * hi.max(1.0) {
        let mid = 0.5 * (lo + hi);
        let s = side(frequency_at(model, c, balls, cv, k, mid)?, mid, h);
        if (s == keep) == from_left {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The crossings of curve `cv` (index `ci`) with `h Ω`, appended to `out`. Each interval of
/// the grid where the side of `g` changes gives the end of the old side and the start of the
/// new one; two ends closer than the on-line band of a linear crossing (`2 tol/|g'|`, `g'` the
/// grid slope) are one crossing at their midpoint, farther ones (a curve running along the
/// line, e.g. between split critical speeds) are both reported.
#[allow(clippy::too_many_arguments)]
fn crossings(model: &SpatialModel, c: &Campbell, balls: Balls, cv: &FixedCurve, ci: usize, h: u32, out: &mut Vec<CriticalSpeed>) -> Result<()> {
    let pts = &cv.points;
    let g = |k: usize| pts[k].frequency - h as f64 * pts[k].omega;
    // (speed, whirl, half-width of the on-line band of a linear crossing there)
    let mut ends: Vec<(f64, Whirl, f64)> = vec![];
    for k in 0..pts.len().saturating_sub(1) {
        let (a, b) = (side(pts[k].fixed_frequency, pts[k].omega, h), side(pts[k + 1].fixed_frequency, pts[k + 1].omega, h));
        if a == b {
            continue;
        }
        let slope = ((g(k + 1) - g(k)) / (pts[k + 1].omega - pts[k].omega)).abs().max(1e-3);
        let band = ON_LINE_TOL * (h as f64 * pts[k + 1].omega).max(1.0) / slope;
        // a curve on the line from the first speed (a real mode whirling with the rotor) has no
        // crossing where it leaves it, nor one on the line up to the last speed where it joins it
        let first_run = pts[..=k].iter().all(|p| side(p.fixed_frequency, p.omega, h) == 0);
        let last_run = pts[k + 1..].iter().all(|p| side(p.fixed_frequency, p.omega, h) == 0);
        if a != 0 && !last_run {
            ends.push((bisect(model, c, balls, cv, k, h, a, true)?, pts[k].whirl, band));
        }
        if b != 0 && !first_run {
            ends.push((bisect(model, c, balls, cv, k, h, b, false)?, pts[k + 1].whirl, band));
        }
    }
    let mut i = 0;
    while i < ends.len() {
        let (t1, whirl, band) = ends[i];
        if i + 1 < ends.len() && ends[i + 1].0 - t1 <= 2.0 * band.max(ends[i + 1].2) + MERGE_TOL * t1.max(1.0) {
            let t = 0.5 * (t1 + ends[i + 1].0);
            out.push(CriticalSpeed { omega: t, harmonic: h, curve: ci, whirl, frequency: h as f64 * t });
            i += 2;
        } else {
            out.push(CriticalSpeed { omega: t1, harmonic: h, curve: ci, whirl, frequency: h as f64 * t1 });
            i += 1;
        }
    }
    Ok(())
}

/// Which tracked lines to keep so that each complex-conjugate pair is drawn once: the lines are
/// the nodes of a graph whose edges join lines `i`, `j` that are conjugates at some speed
/// (`conjugate(i, j)`), the graph is 2-coloured by breadth-first search, and each connected
/// component keeps the colour whose lines have more points with Im λ ≥ 0 (`up(l)` points for
/// line `l`); a line with no edge is kept. Returns each line's component (its first line) and
/// whether it is left out.
pub(crate) fn keep_one_of_each_pair(nl: usize, conjugate: impl Fn(usize, usize) -> bool, up: impl Fn(usize) -> i64) -> (Vec<usize>, Vec<bool>) {
    let mut edges: Vec<Vec<usize>> = vec![vec![]; nl];
    for i in 0..nl {
        for j in i + 1..nl {
            if conjugate(i, j) {
                edges[i].push(j);
                edges[j].push(i);
            }
        }
    }
    let mut colour: Vec<Option<bool>> = vec![None; nl];
    let mut component = vec![0usize; nl];
    let mut dropped = vec![false; nl];
    for start in 0..nl {
        if colour[start].is_some() {
            continue;
        }
        colour[start] = Some(true);
        component[start] = start;
        let mut members = vec![start];
        let mut q = 0;
        while q < members.len() {
            let i = members[q];
            q += 1;
            for &j in &edges[i] {
                if colour[j].is_none() {
                    colour[j] = Some(!colour[i].unwrap_or(true));
                    component[j] = start;
                    members.push(j);
                }
            }
        }
        if members.len() > 1 {
            let score: i64 = members.iter().map(|&l| if colour[l] == Some(true) { up(l) } else { -up(l) }).sum();
            for &l in &members {
                dropped[l] = (colour[l] == Some(true)) != (score >= 0);
            }
        }
    }
    (component, dropped)
}
