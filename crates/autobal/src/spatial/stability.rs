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

use crate::linalg::eigen::{characteristic_polynomial, complex_solve, eigenvalues, routh_hurwitz_stable, spectral_abscissa};
use crate::spatial::critical_speeds::{critical_speeds_at, ModeKind};
use crate::error::{Error, Result};
use crate::spatial::linear_model::{Balls, Pencil, StateSpace};
use crate::spatial::params::SpatialModel;
use crate::spatial::ranges::SpeedRange;
use num_complex::Complex64;
use serde::Serialize;

/// Real parts within this distance of zero count as zero.
pub const STABILITY_TOLERANCE: f64 = 1e-11;

/// The stability verdict from the spectral abscissa (module docs): strict with the balls free,
/// neutral allowed with the balls locked.
pub fn counts_as_stable(alpha: f64, balls: Balls) -> bool {
    match balls {
        Balls::Free => alpha < -STABILITY_TOLERANCE,
        Balls::Locked => alpha <= STABILITY_TOLERANCE,
    }
}

fn no_conv(omega: f64) -> Error {
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
    /// Logarithmic decrement `−2π σ/|ν|` (`None` for a real eigenvalue).
    pub log_decrement: Option<f64>,
    /// Dominant coordinate group of the eigenvector.
    pub group: Group,
    /// Whirl frequency in fixed axes: `Ω + ν` or `Ω − ν`, whichever of the eigenvector's
    /// forward and backward circular components dominates; positive = forward.
    pub fixed_frequency: f64,
    /// Whirl direction in fixed axes.
    pub whirl: Whirl,
}

/// Interpret eigenvalue `lam` of `pencil` at speed `omega` from its eigenvector (two steps
/// of inverse iteration on `M λ² + G λ + K`).
pub fn classify(p: &Pencil, omega: f64, lam: Complex64) -> Mode {
    let n = p.n;
    let mat: Vec<Vec<Complex64>> =
        (0..n).map(|i| (0..n).map(|j| lam * lam * p.m[i][j] + lam * p.g[i][j] + p.k[i][j]).collect()).collect();
    let mut x = vec![Complex64::new(1.0, 0.3); n];
    for _ in 0..2 {
        x = complex_solve(&mat, &x);
        let nrm = x.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        if nrm > 0.0 && nrm.is_finite() {
            for z in x.iter_mut() {
                *z /= nrm;
            }
        }
    }
    // kinetic-energy weights: s is the balls' unbalance, about m̄ times their displacement,
    // so the balls' share is |s|²/m̄ (translation and tilt are normalised alike by the papers)
    let ball_weight = 1.0 / p.m[4][0].abs().max(p.m[5][1].abs()).max(1e-12);
    let energy = |k: usize| (x[2 * k].norm_sqr() + x[2 * k + 1].norm_sqr()) * if k == 2 { ball_weight } else { 1.0 };
    let groups = n / 2;
    let e: Vec<f64> = (0..groups).map(energy).collect();
    let g = (0..groups).max_by(|&a, &b| e[a].total_cmp(&e[b])).unwrap_or(0);
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
        log_decrement: (nu.abs() > 1e-12).then(|| -2.0 * std::f64::consts::PI * lam.re / nu.abs()),
        group,
        fixed_frequency: fixed,
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
    /// Speeds `0 < Ω ≤ Ω_max` that are stable by [`counts_as_stable`];
    /// ends located by bisection to `tolerance`; `hi = None` when the range reaches `Ω_max`.
    pub stable_ranges: Vec<SpeedRange>,
    /// `(Ω, max Re λ)` on the grid.
    pub max_real_part: Vec<(f64, f64)>,
    /// Bisection tolerance on the ends (dimensionless speed).
    pub tolerance: f64,
}

/// Exact stability ranges over `(0, omega_max]`: a grid of `samples` speeds, seeded with the
/// analytic critical speeds and the middles of their split pairs, then bisection on every
/// change of verdict down to `tol` in Ω. A flutter range narrower than the grid spacing can
/// escape the grid; split-pair ranges cannot.
pub fn stability_ranges(model: &SpatialModel, omega_max: f64, samples: usize, balls: Balls, tol: f64) -> Result<StabilityRanges> {
    if !(omega_max > 0.0 && omega_max.is_finite()) {
        return Err(Error::invalid("omega_max", format!("must be a positive number, got {}", crate::error::fmt_num(omega_max))));
    }
    let samples = samples.max(2);
    let lo0 = omega_max * 1e-3;
    let mut grid: Vec<f64> = (0..samples).map(|i| lo0 + (omega_max - lo0) * i as f64 / (samples - 1) as f64).collect();
    // Seed the grid with the analytic split pairs (locked rotor, ΔĀ and ΔĀ0): their instability
    // ranges can be far narrower than the grid spacing (near-symmetric layouts).
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
    let samples = grid.len();
    let ss = StateSpace::new(model, balls)?;
    let mut alpha = Vec::with_capacity(samples);
    for &w in &grid {
        alpha.push((w, margin_at(&ss, w)?));
    }
    let stable = |a: f64| counts_as_stable(a, balls);
    let mut ranges: Vec<SpeedRange> = vec![];
    let mut start: Option<f64> = if stable(alpha[0].1) { Some(0.0) } else { None };
    for k in 1..samples {
        let (w0, a0) = alpha[k - 1];
        let (w1, a1) = alpha[k];
        if stable(a0) != stable(a1) {
            let (mut lo, mut hi) = (w0, w1);
            while hi - lo > tol {
                let mid = 0.5 * (lo + hi);
                if stable(margin_at(&ss, mid)?) == stable(a0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let edge = 0.5 * (lo + hi);
            if stable(a1) {
                start = Some(edge);
            } else if let Some(s) = start.take() {
                ranges.push(SpeedRange { lo: s, hi: Some(edge) });
            }
        }
    }
    if let Some(s) = start {
        ranges.push(SpeedRange { lo: s, hi: None });
    }
    Ok(StabilityRanges { stable_ranges: ranges, max_real_part: alpha, tolerance: tol })
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

/// Campbell diagram over `omegas` (ascending). Lines are continued by matching each new
/// eigenvalue to the linear extrapolation of the previous two points (greedy nearest pairs),
/// so lines do not jump between modes where they pass close.
pub fn campbell(model: &SpatialModel, omegas: &[f64], balls: Balls) -> Result<Campbell> {
    let mut lines: Vec<Vec<(Complex64, Mode)>> = vec![];
    for (step, &w) in omegas.iter().enumerate() {
        let (p, ev) = eigenvalues_at(model, w, balls)?;
        if step == 0 {
            lines = ev.iter().map(|&l| vec![(l, classify(&p, w, l))]).collect();
            continue;
        }
        let pred: Vec<Complex64> = lines
            .iter()
            .map(|l| {
                let last = l[l.len() - 1].0;
                if l.len() >= 2 {
                    let prev = l[l.len() - 2].0;
                    let h0 = omegas[step - 1] - omegas[step - 2];
                    let h1 = w - omegas[step - 1];
                    last + (last - prev) * (h1 / h0)
                } else {
                    last
                }
            })
            .collect();
        let mut pairs: Vec<(f64, usize, usize)> = vec![];
        for (i, pr) in pred.iter().enumerate() {
            for (j, e) in ev.iter().enumerate() {
                pairs.push(((pr - e).norm(), i, j));
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut used_line = vec![false; lines.len()];
        let mut used_ev = vec![false; ev.len()];
        let mut assign = vec![usize::MAX; lines.len()];
        for (_, i, j) in pairs {
            if !used_line[i] && !used_ev[j] {
                used_line[i] = true;
                used_ev[j] = true;
                assign[i] = j;
            }
        }
        for (i, l) in lines.iter_mut().enumerate() {
            let lam = ev[assign[i]];
            l.push((lam, classify(&p, w, lam)));
        }
    }
    Ok(Campbell {
        omega: omegas.to_vec(),
        lines: lines.into_iter().map(|l| CampbellLine { modes: l.into_iter().map(|x| x.1).collect() }).collect(),
    })
}
