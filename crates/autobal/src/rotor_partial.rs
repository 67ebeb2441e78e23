//! The **partially balanced state** (issue 18 item 4): where the balls' capacity falls short, no
//! balanced state exists, and the balls come to rest where the rotor's whirl puts them, leaving
//! a residual unbalance. Here it is computed as a stationary state of the equations in turning
//! axes, with its stability, for any rotor of [`crate::rotor_stability`]: in particular the
//! two-plane rotor (Rodrigues et al. 2008) whose planes cannot both carry their share of the
//! static and couple unbalance, where [`crate::spatial::dynamics::SpatialRotor::balanced_ball_angles`]
//! only places the balls.
//!
//! # What the state is
//! At a constant speed `Ω` on isotropic supports without gravity, in axes turning with the rotor,
//! a ball of plane `k` is in equilibrium when the race centre's displacement `d_k` at its plane
//! is zero or points along the ball (`ψ = arg d_k` or `arg d_k + π`): the tangential force on it
//! is `m Ω² |d_k| sin(ψ − arg d_k)` (the race centre's centripetal acceleration `−Ω² d_k`),
//! whatever the drag. A balanced state has `d_k = 0` in every plane; where the capacity falls
//! short, the balls of a short plane are **bunched** along `d_k ≠ 0` (all at one angle, the
//! residual of that plane at its limit `n m R`), and a plane that can carry more may still keep
//! `d_k = 0` with its balls apart. With two planes and one of them short the state is therefore
//! not in closed form: the rotor's response to the residual (translation and tilt) decides where
//! the other plane's balls sit. With supports that differ by direction, or gravity, it is the
//! periodic orbit near that equilibrium.
//!
//! # How
//! [`partially_balanced`] solves the stationary equations by Newton's method with the exact
//! Jacobian ([`crate::analysis::stationary`]; shooting for a periodic orbit) from the starting
//! points of [`Start`] — each plane's balls bunched towards its share, or only the short
//! plane's, or all bunched opposite the static unbalance — keeps each distinct state found,
//! and gives each its residual static unbalance `s0 + Σ m R e^{iψ_j}` and couple
//! `c0 + Σ ζ_j m R e^{iψ_j}` about C (as [`crate::spatial::dynamics::Summary::residual_unbalance`]
//! and `residual_couple` measure them at the end of a run), the whirl radius at each ball
//! plane, and its stability (eigenvalues, or Floquet multipliers).
//!
//! ```
//! use autobal::rotor_partial::partially_balanced;
//! use autobal::rotor_stability::{Rotor, StateKind};
//! use autobal::planar::PlanarRotor;
//! // the Jeffcott rotor with two 20 g balls: capacity 0.8 of the unbalance
//! let p = PlanarRotor { s2: 0.0, m3: 0.02, ..PlanarRotor::paper() };
//! let w = 2.0 * p.natural_frequency();
//! let states = partially_balanced(&Rotor::Planar(p), w).unwrap();
//! let s = &states[0];
//! assert_eq!(s.kind, StateKind::PartiallyBalanced);
//! // the balls together opposite the unbalance: a residual of 1 − 0.8 and a little more
//! assert!(s.residual_static_fraction > 0.2 - 1e-9 && s.residual_static_fraction < 0.25);
//! ```

use crate::analysis::{stability, stationary, NewtonOptions, Stability, VectorField, Verdict};
use crate::error::{Error, Result};
use crate::rotor_stability::{amplitude, ball_angles, Field, Rotor, StateKind};
use serde::Serialize;

/// Where Newton's method started ([`partially_balanced`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// [`Rotor::bunched_guess`]: every plane's balls bunched at the angle of its share (the
    /// planar rotor: the aligned whirl with the balls on the far side), the rotor at rest.
    Bunched,
    /// [`crate::spatial::dynamics::SpatialRotor::balanced_ball_angles`]: the balls of a plane
    /// short of its share bunched towards it, the others on the arc that carries their share;
    /// the rotor at rest.
    ShortPlaneBunched,
    /// Every ball of every plane bunched opposite the static unbalance, the rotor at rest.
    AllOpposite,
}

/// One plane's capacity against its share.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlaneShare {
    /// `n m R` (kg·m).
    pub capacity: f64,
    /// `|b_k|`, the unbalance the plane must carry for balance (kg·m): `|s0|` for one plane,
    /// `|(ζ_2 s0 − c0)/(ζ_1 − ζ_2)|` and `|s0 + b_1|` for two (Rodrigues et al. 2008).
    pub share: f64,
    /// Whether the plane's balls sit at one angle (within 1e-6 rad): at its capacity limit.
    pub bunched: bool,
}

/// A stationary state found by [`partially_balanced`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PartialState {
    /// The speed (rad/s, or `Ω` for a dimensionless spatial rotor).
    pub omega: f64,
    /// The start Newton's method reached it from (the first, when several did).
    pub start: Start,
    /// What it is (partially balanced, or balanced where Newton found a balanced state).
    pub kind: StateKind,
    /// The reduced state in turning axes ([`crate::analysis::StationaryState::x`]).
    pub x: Vec<f64>,
    /// The balls' angles (rad, all planes in order, modulo `2π` in `(−π, π]`).
    pub psi: Vec<f64>,
    /// Each plane with balls: capacity, share, bunched.
    pub planes: Vec<PlaneShare>,
    /// Residual static unbalance `s0 + Σ m R e^{iψ_j}` (kg·m, rotor frame; the planar rotor:
    /// `m1 s1 + (m2 + n m3) s2 e^{iγ} + m3 r Σ e^{iψ_j}`).
    pub residual_static: [f64; 2],
    /// `|residual_static|` relative to the unbalance's own `|s0|` (without one: to the balls'
    /// capacity).
    pub residual_static_fraction: f64,
    /// Residual couple `c0 + Σ ζ_j m R e^{iψ_j}` about C (kg·m²; `[0, 0]` for the planar rotor).
    pub residual_couple: [f64; 2],
    /// `|residual_couple|` relative to the unbalance's own couple `|c0|`; `None` where it has
    /// none.
    pub residual_couple_fraction: Option<f64>,
    /// Whirl radius at each ball plane (m, or `ρ_s`; the planar rotor: of C): the rotor's
    /// displacement there in turning axes, constant in time for an equilibrium (for a periodic
    /// orbit: at `t = 0`). Zero at a plane whose balls sit apart (module docs).
    pub whirl: Vec<f64>,
    /// Newton's scaled residual at the state.
    pub newton_residual: f64,
    /// Its stability (eigenvalues, or Floquet multipliers).
    pub stability: Stability,
}

/// The residual static unbalance (kg·m) and couple about C (kg·m²) of the state `x`, with the
/// unbalance's own static and couple magnitudes (module docs).
fn residuals(field: &Field, x: &[f64]) -> ([f64; 2], [f64; 2], f64, f64) {
    let psi = ball_angles(field, x);
    match field {
        // no axial positions: no couple
        Field::Linear(f) => {
            let s0 = crate::linear_rotor::partial::static_unbalance(f.rotor());
            (crate::linear_rotor::partial::residual_static(f.rotor(), &psi), [0.0; 2], s0[0].hypot(s0[1]), 0.0)
        }
        Field::Planar(f) => {
            let p = f.rotor();
            let (es, ec) = p.gamma.sin_cos();
            let mut s = [p.m1 * p.s1 + (p.m2 + p.n as f64 * p.m3) * p.s2 * ec, (p.m2 + p.n as f64 * p.m3) * p.s2 * es];
            let own = s[0].hypot(s[1]);
            for (j, a) in psi.iter().enumerate() {
                let mr = p.ball_mass(j) * p.r;
                s[0] += mr * a.cos();
                s[1] += mr * a.sin();
            }
            (s, [0.0; 2], own, 0.0)
        }
        Field::Spatial(f) => {
            let r = f.rotor();
            let (mut s, mut c) = (r.static_unbalance(), r.couple_unbalance());
            let own = (s[0].hypot(s[1]), c[0].hypot(c[1]));
            let zr = r.z_reference();
            let mut j = 0;
            for p in r.planes.iter().filter(|p| p.n > 0) {
                let (mr, z) = (p.ball_mass * p.race_radius, p.z - zr);
                for _ in 0..p.n {
                    let (sn, cs) = psi[j].sin_cos();
                    s[0] += mr * cs;
                    s[1] += mr * sn;
                    c[0] += z * mr * cs;
                    c[1] += z * mr * sn;
                    j += 1;
                }
            }
            (s, c, own.0, own.1)
        }
    }
}

/// Each plane with balls: its capacity and share, and whether `psi` bunches it.
fn plane_shares(field: &Field, psi: &[f64]) -> Vec<PlaneShare> {
    let bunched = |a: &[f64]| a.iter().all(|v| wrap(v - a[0]).abs() <= 1e-6);
    match field {
        // one plane's share is the static unbalance; with more it depends on the speed (NaN)
        Field::Linear(f) => {
            let r = f.rotor();
            let s0 = crate::linear_rotor::partial::static_unbalance(r);
            let mut j = 0;
            r.balancers
                .iter()
                .filter(|b| b.balls > 0)
                .map(|b| {
                    let a = &psi[j..j + b.balls];
                    j += b.balls;
                    let share = if r.balancers.len() == 1 { s0[0].hypot(s0[1]) } else { f64::NAN };
                    PlaneShare { capacity: b.balls as f64 * b.ball_mass * b.radius, share, bunched: bunched(a) }
                })
                .collect()
        }
        Field::Planar(f) => {
            let p = f.rotor();
            let cap = (0..p.n).map(|j| p.ball_mass(j) * p.r).sum();
            let (es, ec) = p.gamma.sin_cos();
            let u = [p.m1 * p.s1 + (p.m2 + p.n as f64 * p.m3) * p.s2 * ec, (p.m2 + p.n as f64 * p.m3) * p.s2 * es];
            vec![PlaneShare { capacity: cap, share: u[0].hypot(u[1]), bunched: !psi.is_empty() && bunched(psi) }]
        }
        Field::Spatial(f) => {
            let r = f.rotor();
            let planes: Vec<_> = r.planes.iter().filter(|p| p.n > 0).collect();
            let s0 = r.static_unbalance();
            let shares: Vec<f64> = match planes.len() {
                1 => vec![s0[0].hypot(s0[1])],
                2 if planes[0].z != planes[1].z => {
                    let zr = r.z_reference();
                    let (z1, z2) = (planes[0].z - zr, planes[1].z - zr);
                    let c0 = r.couple_unbalance();
                    let b1 = [(z2 * s0[0] - c0[0]) / (z1 - z2), (z2 * s0[1] - c0[1]) / (z1 - z2)];
                    vec![b1[0].hypot(b1[1]), (s0[0] + b1[0]).hypot(s0[1] + b1[1])]
                }
                _ => vec![f64::NAN; planes.len()],
            };
            let mut j = 0;
            planes
                .iter()
                .zip(shares)
                .map(|(p, share)| {
                    let a = &psi[j..j + p.n];
                    j += p.n;
                    PlaneShare { capacity: p.n as f64 * p.ball_mass * p.race_radius, share, bunched: bunched(a) }
                })
                .collect()
        }
    }
}

/// The whirl radius at each ball plane ([`PartialState::whirl`]).
fn whirl(field: &Field, x: &[f64]) -> Vec<f64> {
    match field {
        Field::Planar(_) => vec![amplitude(field, x)],
        Field::Linear(f) => crate::linear_rotor::partial::plane_whirl(f.rotor(), x),
        Field::Spatial(f) => {
            let r = f.rotor();
            let y = f.full_state(0.0, x);
            let drive = crate::drive::Drive::Speed { omega0: f.omega() };
            let eq = crate::spatial::dynamics::Equations::new(r, &drive);
            r.planes
                .iter()
                .filter(|p| p.n > 0)
                .map(|p| {
                    let d = eq.displacement_at(&y, p.z);
                    d[0].hypot(d[1])
                })
                .collect()
        }
    }
}

/// `a` modulo `2π` in `(−π, π]`.
fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let w = a - t * (a / t).round();
    if w <= -std::f64::consts::PI {
        w + t
    } else {
        w
    }
}

/// The starting points of [`Start`] at `field` that exist.
fn starts(field: &Field) -> Vec<(Start, Vec<f64>)> {
    let mut out = vec![];
    if let Some(x) = Rotor::bunched_guess(field) {
        out.push((Start::Bunched, x));
    }
    if let Field::Spatial(f) = field {
        let r = f.rotor();
        let m = f.coords();
        let nb = r.balls();
        let at_rest = |psi: &[f64]| {
            let mut x = vec![0.0; 2 * m];
            x[m - nb..m].copy_from_slice(psi);
            x
        };
        let placed = r.balanced_ball_angles();
        if placed.angles.len() == nb {
            out.push((Start::ShortPlaneBunched, at_rest(&placed.angles)));
        }
        let s0 = r.static_unbalance();
        if s0 != [0.0, 0.0] {
            out.push((Start::AllOpposite, at_rest(&vec![(-s0[1]).atan2(-s0[0]); nb])));
        }
    }
    out
}

/// The partially balanced state(s) of `rotor` at speed `omega` (module docs): every distinct
/// stationary state Newton's method reaches from the starts of [`Start`], each with its
/// residual unbalance and its stability, **stable states first** (then by residual static
/// unbalance). Errors: the model's refusals ([`Rotor::field`]: real balls have no
/// linearisation), and `omega` when no start converges.
pub fn partially_balanced(rotor: &Rotor, omega: f64) -> Result<Vec<PartialState>> {
    let field = rotor.field(omega)?;
    let periodic = field.period().is_some();
    let mut opts = NewtonOptions::default();
    if periodic {
        // as rotor_stability: multipliers near 1 good to ~1e-9 at rtol 1e-10
        opts.max_iterations = 30;
        opts.rtol = 1e-10;
    }
    let sc = field.scales();
    let angles: Vec<usize> = {
        let n = field.dim() / 2;
        let nb = ball_angles(&field, &vec![0.0; field.dim()]).len();
        (n - nb..n).collect()
    };
    let same = |a: &[f64], b: &[f64]| {
        (0..a.len()).all(|i| {
            let d = if angles.contains(&i) { wrap(a[i] - b[i]) } else { a[i] - b[i] };
            d.abs() <= 1e-6 * sc[i]
        })
    };
    let mut found: Vec<PartialState> = vec![];
    let mut last_error = None;
    for (start, guess) in starts(&field) {
        let state = match stationary(&field, &guess, &opts) {
            Ok(s) => s,
            Err(e) => {
                last_error = Some(e.to_string());
                continue;
            }
        };
        if found.iter().any(|f| same(&f.x, &state.x)) {
            continue;
        }
        let st = match stability(&field, &state) {
            Ok(s) => s,
            Err(e) => {
                last_error = Some(e.to_string());
                continue;
            }
        };
        let psi: Vec<f64> = ball_angles(&field, &state.x).into_iter().map(wrap).collect();
        let (rs, rc, own_s, own_c) = residuals(&field, &state.x);
        let planes = plane_shares(&field, &psi);
        // without an unbalance of its own, relative to the balls' capacity
        let per = if own_s > 0.0 { own_s } else { planes.iter().map(|p| p.capacity).sum::<f64>().max(f64::MIN_POSITIVE) };
        found.push(PartialState {
            omega,
            start,
            kind: Rotor::state_kind(&field, &state.x),
            planes,
            residual_static: rs,
            residual_static_fraction: rs[0].hypot(rs[1]) / per,
            residual_couple: rc,
            residual_couple_fraction: (own_c > 0.0).then(|| rc[0].hypot(rc[1]) / own_c),
            whirl: whirl(&field, &state.x),
            newton_residual: state.residual,
            x: state.x,
            psi,
            stability: st,
        });
    }
    if found.is_empty() {
        return Err(Error::invalid(
            "omega",
            format!(
                "no partially balanced state found at {}: Newton's method converged from none of its starts{}",
                crate::error::fmt_num(omega),
                last_error.map(|e| format!(" ({e})")).unwrap_or_default()
            ),
        ));
    }
    let rank = |s: &PartialState| if s.stability.verdict == Verdict::Stable { 0 } else { 1 };
    found.sort_by(|a, b| rank(a).cmp(&rank(b)).then(a.residual_static_fraction.total_cmp(&b.residual_static_fraction)));
    Ok(found)
}
