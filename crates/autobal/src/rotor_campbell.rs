//! The Campbell diagram and the locked critical speeds of **every rotor autobal can run**
//! (issue "Analyse every rotor", §3): the general route of `autobal campbell` and
//! `autobal critical`, through the model-agnostic pipeline of [`crate::analysis`] on the
//! models' own equations ([`Rotor`]: the planar rotor, the spatial rotor with one or two ball
//! planes, couple unbalance, supports that differ by direction, gravity).
//!
//! # Campbell diagram ([`campbell_over_speed`])
//! At each speed the stationary state is found as `stability` finds it
//! ([`crate::rotor_stability`]: Newton from the closed-form balanced state, else from the
//! previous speed's state; shooting for a periodic orbit). Its linearisation gives, in axes
//! turning with the rotor:
//! - **an equilibrium**: the eigenvalues `λ = σ + iν` of the exact (AD) Jacobian;
//! - **a periodic orbit** (supports that differ by direction, gravity across the axis): the
//!   Floquet exponents `ρ = ln μ / T` of the monodromy matrix's multipliers `μ`. Their
//!   imaginary parts are defined only modulo `Ω = 2π/T`. **Branch**: with `v` the multiplier's
//!   eigenvector (the Floquet mode's state at `t = 0`, scaled by the field's
//!   [`scales`](crate::analysis::VectorField::scales)), the branch `ρ = ρ₀ + i k Ω` (`ρ₀` the
//!   principal logarithm) is the one whose `Im ρ` is nearest `Im` of the Rayleigh quotient
//!   `vᴴ J(0) v / vᴴ v` of the Jacobian at the orbit's start. A Floquet mode is
//!   `p(t) e^{ρt}` with `p` periodic, and `ρ v + ṗ(0) = J(0) v`: when the field is autonomous
//!   (`ṗ = 0`) the quotient is the eigenvalue itself, so the branch continues the equilibrium
//!   case exactly as the anisotropy or gravity vanishes and is `λ` to the Floquet accuracy on a
//!   nearly isotropic rotor (tests/rotor_campbell.rs); for a strongly periodic mode (`p` with
//!   several harmonics) it is a convention, said in every output.
//!
//! Eigenvalues are tracked into continuous lines by matching each speed's values to the
//! previous lines' linear extrapolations, nearest pair first. The fixed-axes view is that of
//! [`crate::spatial::campbell`]: in turning axes a mode moves the rotor's circular coordinate
//! `ξ + iη` (and, for the spatial rotor, the spin axis' tip `θ − iδ` times the radius of
//! gyration) as components at `Ω + ν` (amplitude `|x_ξ + i x_η|`) and `Ω − ν`
//! (`|x_ξ − i x_η|`); the curve's signed fixed-axes frequency `f` is that of the dominant
//! component (`f > 0` forward whirl, `f < 0` backward), the log decrement per fixed-axes cycle
//! `δ = −2π σ/|f|`. Modes with no rotor motion (the balls alone) have no whirl.
//!
//! # Critical speeds ([`locked_critical_speeds`])
//! The rotor with its balls **locked** at the closed-form balanced position (each ball becomes
//! a point mass of the rotor: [`locked_rotor`]) and **without damping** (as 000 eq (16)). In
//! turning axes its linearisation about the centred rotor is `q̈ = A q + B q̇`; a critical
//! speed is where a natural frequency in fixed axes equals the speed, i.e. where a whirl at
//! `Ω` stands still in turning axes: `A(Ω) q = 0` has a solution. `A = M⁻¹ S` (`M` the mass
//! matrix, `S` symmetric without damping) has real eigenvalues; the number of positive ones
//! changes exactly at the critical speeds, by the number of eigenvalues crossing 0 (2 for the
//! circular whirl of an axisymmetric rotor). The changes are bracketed on a grid and bisected
//! to `1e-12` relative. `A` is read from the exact (AD) Jacobian `[[0, I], [A, B]]` of the
//! model's field. With supports that differ by direction `A` turns with the rotor (no constant
//! `A`): [`crate::Error::NoLinearisation`] says so (the Floquet Campbell diagram still applies).
//! Gravity moves the stationary state (the sag) but not this linearisation about the centred
//! rotor, which is checked (`J(0) = J(T/4)` to 1e-9).

use crate::analysis::{mode, stability, stationary, stationary_near, Kind, NewtonOptions, StationaryState, VectorField};
use crate::error::{Error, Result};
use crate::linalg::eigen_dyn::eigenvalues;
use crate::rotor_stability::{Field, Rotor};
use crate::spatial::dynamics::PointMass;
use num_complex::Complex64;
use serde::Serialize;

/// The branch rule of the Floquet exponents' imaginary parts, as every output states it.
pub const FLOQUET_BRANCH: &str = "Floquet exponents ρ = ln μ / T are defined modulo iΩ: the branch shown is the one whose Im ρ is nearest Im of the Rayleigh quotient vᴴJ(0)v/vᴴv of the Floquet mode's start vector v (exact continuation of the equilibrium eigenvalues as the anisotropy or gravity vanishes; a convention for strongly periodic modes)";

/// Whirl direction in fixed axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Whirl {
    /// `f > 0`: the mode whirls with the rotor.
    Forward,
    /// `f < 0`: against it.
    Backward,
    /// No rotor motion (a ball mode), or `f = 0`.
    None,
}

/// One eigenvalue (or Floquet exponent) at one speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CampbellPoint {
    /// Speed `Ω` (rad/s, or the papers' unit).
    pub omega: f64,
    /// `σ = Re λ` in turning axes (1/s).
    pub re: f64,
    /// `ν = Im λ` in turning axes (for a periodic orbit on the branch of [`FLOQUET_BRANCH`]).
    pub im: f64,
    /// Signed natural frequency in fixed axes `f = Ω ± ν` of the dominant circular component
    /// (rad/s; `> 0` forward).
    pub fixed_frequency: f64,
    /// Share of the forward component `|x_ξ + i x_η|²` in the rotor's amplitude squared (½
    /// where the rotor does not move).
    pub forward_share: f64,
    /// Whirl direction in fixed axes.
    pub whirl: Whirl,
    /// Logarithmic decrement per fixed-axes cycle `−2π σ/|f|` (`None` where `|f|` is 0).
    pub log_decrement: Option<f64>,
    /// A structural eigenvalue (the family of balanced states: 0, multiplier 1), not a mode.
    pub structural: bool,
}

/// One tracked line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CampbellLine {
    /// One entry per speed of the diagram (`None` where no stationary state was found).
    pub points: Vec<Option<CampbellPoint>>,
}

/// The Campbell diagram of the general route ([`campbell_over_speed`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RotorCampbell {
    /// `"planar"` or `"spatial"`.
    pub model: &'static str,
    /// Equilibrium (eigenvalues) or periodic orbit (Floquet exponents).
    pub kind: Kind,
    /// The speeds.
    pub omega: Vec<f64>,
    /// The tracked lines (one per eigenvalue).
    pub lines: Vec<CampbellLine>,
    /// Why a speed has no state, per speed (`None` where it has one).
    pub failures: Vec<Option<String>>,
}

/// The eigenvalues (or Floquet exponents) of the stationary state at one speed, with their
/// fixed-axes data, unsorted: `field` at its speed `omega`, `state` its stationary state.
pub fn spectrum_at(rotor: &Rotor, field: &Field, omega: f64, state: &StationaryState) -> Result<Vec<CampbellPoint>> {
    let st = stability(field, state).map_err(|e| Error::invalid("campbell", e.to_string()))?;
    let n = field.dim();
    let scales = field.scales();
    let jac0 = {
        let mut j = vec![0.0; n * n];
        field.jacobian(0.0, &state.x, &mut j);
        j
    };
    let pairs = whirl_pairs(rotor, field);
    let mut out = Vec::with_capacity(n);
    let all = st.spectrum.iter().map(|e| (e.complex(), false)).chain(st.structural.iter().map(|e| (e.complex(), true)));
    for (value, structural) in all {
        let v = mode(&st.matrix, n, value);
        let lam = match state.period {
            None => value,
            Some(t) => {
                let rho0 = Complex64::new(value.norm().max(f64::MIN_POSITIVE).ln(), value.arg()) / t;
                // the Rayleigh quotient of J(0) in scaled coordinates
                let w: Vec<Complex64> = v.iter().zip(&scales).map(|(z, s)| z / s).collect();
                let (mut num, mut den) = (Complex64::new(0.0, 0.0), 0.0);
                for i in 0..n {
                    let mut jw = Complex64::new(0.0, 0.0);
                    for j in 0..n {
                        jw += jac0[i * n + j] * scales[j] / scales[i] * w[j];
                    }
                    num += w[i].conj() * jw;
                    den += w[i].norm_sqr();
                }
                let q = if den > 0.0 { num / den } else { rho0 };
                let big = 2.0 * std::f64::consts::PI / t;
                let k = ((q.im - rho0.im) / big).round();
                Complex64::new(rho0.re, rho0.im + k * big)
            }
        };
        let (fwd, bwd) = pairs.iter().fold((0.0, 0.0), |(f, b), &(a, bi, sign, w)| {
            let (xa, xb) = (v[a] * w, v[bi] * (sign * w));
            let i = Complex64::new(0.0, 1.0);
            (f + (xa + i * xb).norm_sqr(), b + (xa - i * xb).norm_sqr())
        });
        let total = fwd + bwd;
        let vmax = v.iter().zip(&scales).map(|(z, s)| z.norm() / s).fold(0.0, f64::max);
        // the rotor's share of the mode, in scaled units: below 1e-9 it is a ball mode
        let rotor_amp = pairs.iter().map(|&(a, b, _, _)| (v[a].norm() / scales[a]).max(v[b].norm() / scales[b])).fold(0.0, f64::max);
        let moves = total > 0.0 && rotor_amp > 1e-9 * vmax;
        let share = if moves { fwd / total } else { 0.5 };
        let f = if share >= 0.5 { omega + lam.im } else { omega - lam.im };
        let whirl = if !moves || f == 0.0 {
            Whirl::None
        } else if f > 0.0 {
            Whirl::Forward
        } else {
            Whirl::Backward
        };
        out.push(CampbellPoint {
            omega,
            re: lam.re,
            im: lam.im,
            fixed_frequency: f,
            forward_share: share,
            whirl,
            log_decrement: (f.abs() > 0.0).then(|| -2.0 * std::f64::consts::PI * lam.re / f.abs()),
            structural,
        });
    }
    Ok(out)
}

/// The rotor's circular coordinate pairs `(a, b, sign, weight)`: the whirl is `x_a + i sign x_b`
/// times `weight` (a length per unit of the coordinate, so that pairs add up in metres).
fn whirl_pairs(rotor: &Rotor, field: &Field) -> Vec<(usize, usize, f64, f64)> {
    match (rotor, field) {
        (_, Field::Planar(_)) => vec![(0, 1, 1.0, 1.0)],
        (Rotor::Spatial(r), Field::Spatial(s)) => {
            let mut p = vec![(0, 1, 1.0, 1.0)];
            if s.coords() - r.balls() == 4 {
                // tilt δ about x, then θ about y': the axis' tip moves by (θ, −δ) per unit length
                let gyration = (r.rotor.equatorial_moment / r.total_mass()).sqrt();
                p.push((3, 2, -1.0, gyration));
            }
            p
        }
        _ => vec![(0, 1, 1.0, 1.0)],
    }
}

/// Newton's options of the general route (as [`crate::rotor_stability::stability_over_speed`]).
fn newton_options(periodic: bool) -> NewtonOptions {
    let mut o = NewtonOptions::default();
    if periodic {
        o.max_iterations = 20;
        o.rtol = 1e-10;
    }
    o
}

/// The Campbell diagram of `rotor` over `speeds` (module docs): at each speed the stationary
/// state (closed form first, then the previous speed's state), its eigenvalues or Floquet
/// exponents with their fixed-axes data, tracked into lines.
pub fn campbell_over_speed(rotor: &Rotor, speeds: &[f64]) -> Result<RotorCampbell> {
    if speeds.is_empty() {
        return Err(Error::invalid("speeds", "no speed to analyse"));
    }
    if let Some(w) = speeds.iter().find(|w| !(w.is_finite() && **w != 0.0)) {
        return Err(Error::invalid("speeds", format!("{w} is not a finite non-zero speed")));
    }
    let first = rotor.field(speeds[0])?;
    let kind = if first.period().is_some() { Kind::PeriodicOrbit } else { Kind::Equilibrium };
    let opts = newton_options(kind == Kind::PeriodicOrbit);
    let mut previous: Option<StationaryState> = None;
    let mut per_speed: Vec<Option<Vec<CampbellPoint>>> = Vec::with_capacity(speeds.len());
    let mut failures = Vec::with_capacity(speeds.len());
    for &w in speeds {
        let f = rotor.field(w)?;
        let guess = Rotor::guess(&f);
        let near = previous.as_ref().map(|p| p.x.clone());
        let hint = previous.as_ref().and_then(|p| p.monodromy.clone());
        let mut result = Err("no starting point (no closed-form state and no previous one)".to_string());
        for start in [guess, near].into_iter().flatten() {
            match stationary_near(&f, &start, hint.as_deref(), &opts) {
                Ok(s) => {
                    result = Ok(s);
                    break;
                }
                Err(e) => result = Err(e.to_string()),
            }
        }
        match result.and_then(|s| spectrum_at(rotor, &f, w, &s).map(|p| (s, p)).map_err(|e| e.to_string())) {
            Ok((s, p)) => {
                previous = Some(s);
                per_speed.push(Some(p));
                failures.push(None);
            }
            Err(e) => {
                previous = None;
                per_speed.push(None);
                failures.push(Some(e));
            }
        }
    }
    Ok(RotorCampbell { model: rotor.model_name(), kind, omega: speeds.to_vec(), lines: track(&per_speed), failures })
}

/// Continuous lines through each speed's values: each line's next value predicted by linear
/// extrapolation of its last two, pairs matched nearest first.
pub fn track(per_speed: &[Option<Vec<CampbellPoint>>]) -> Vec<CampbellLine> {
    let n = per_speed.iter().flatten().map(|v| v.len()).max().unwrap_or(0);
    let mut lines: Vec<CampbellLine> = (0..n).map(|_| CampbellLine { points: Vec::with_capacity(per_speed.len()) }).collect();
    let z = |p: &CampbellPoint| Complex64::new(p.re, p.im);
    for (k, vals) in per_speed.iter().enumerate() {
        let Some(vals) = vals else {
            lines.iter_mut().for_each(|l| l.points.push(None));
            continue;
        };
        let predict = |l: &CampbellLine| -> Option<Complex64> {
            let last = l.points.last().copied().flatten()?;
            match l.points.len().checked_sub(2).and_then(|i| l.points[i]) {
                Some(p2) if k >= 2 => {
                    let (w0, w1, w2) = (per_speed_omega(p2), last.omega, vals.first().map_or(last.omega, |p| p.omega));
                    let t = if w1 != w0 { (w2 - w1) / (w1 - w0) } else { 0.0 };
                    Some(z(&last) + (z(&last) - z(&p2)) * t)
                }
                _ => Some(z(&last)),
            }
        };
        let preds: Vec<Option<Complex64>> = lines.iter().map(predict).collect();
        let mut cand: Vec<(f64, usize, usize)> = vec![];
        for (li, p) in preds.iter().enumerate() {
            for (vi, v) in vals.iter().enumerate() {
                let d = p.map_or(f64::INFINITY, |p| (p - z(v)).norm());
                cand.push((d, li, vi));
            }
        }
        cand.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        let mut line_used = vec![false; n];
        let mut val_used = vec![false; vals.len()];
        let mut assigned: Vec<Option<CampbellPoint>> = vec![None; n];
        for (_, li, vi) in cand {
            if !line_used[li] && !val_used[vi] {
                line_used[li] = true;
                val_used[vi] = true;
                assigned[li] = Some(vals[vi]);
            }
        }
        for (l, a) in lines.iter_mut().zip(assigned) {
            l.points.push(a);
        }
    }
    lines
}

fn per_speed_omega(p: CampbellPoint) -> f64 {
    p.omega
}

/// The rotor with its balls locked where the closed form at speed `omega` puts them (each ball a
/// point mass of the rotor) and, with `undamped`, no support damping: the rotor of the
/// critical speeds. The planar rotor's balls join its housing (`m2`, at the race centre) as one
/// mass at their common centre; the spatial rotor's become unbalance masses in their planes.
pub fn locked_rotor(rotor: &Rotor, omega: f64, undamped: bool) -> Result<Rotor> {
    let f = rotor.field(omega)?;
    let guess = Rotor::guess(&f);
    Ok(match rotor {
        Rotor::Planar(p) => {
            let mut q = p.clone();
            if p.n > 0 {
                let x = guess.ok_or_else(|| no_balance(rotor))?;
                let e = Complex64::from_polar(p.s2, p.gamma);
                let balls: Complex64 = x[2..2 + p.n].iter().map(|&psi| e + Complex64::from_polar(p.r, psi)).sum();
                let m = p.m2 + p.n as f64 * p.m3;
                let centre = (e * p.m2 + balls * p.m3) / m;
                q.m2 = m;
                q.s2 = centre.norm();
                q.gamma = if centre.norm() > 0.0 { centre.arg() } else { 0.0 };
                q.n = 0;
            }
            if undamped {
                q.c = 0.0;
            }
            Rotor::Planar(q)
        }
        Rotor::Spatial(s) => {
            let mut q = s.clone();
            if s.balls() > 0 {
                let x = guess.ok_or_else(|| no_balance(rotor))?;
                let Field::Spatial(sf) = &f else { unreachable!("a spatial rotor's field is spatial") };
                let m = sf.coords();
                let mut psi = x[m - s.balls()..m].iter();
                for plane in q.planes.iter_mut() {
                    for _ in 0..plane.n {
                        let angle = psi.next().copied().unwrap_or(0.0);
                        q.unbalances.push(PointMass { mass: plane.ball_mass, radius: plane.race_radius, angle, z: plane.z });
                    }
                    plane.n = 0;
                }
            }
            if undamped {
                for sup in q.supports.iter_mut() {
                    sup.damping = [0.0, 0.0];
                }
            }
            Rotor::Spatial(q)
        }
    })
}

fn no_balance(rotor: &Rotor) -> Error {
    Error::invalid(
        "balancer",
        match rotor {
            Rotor::Planar(_) => "no semi-balanced state to lock the balls in: the balls cannot supply the unbalance (|B| > n m3 r)",
            Rotor::Spatial(_) => "no balanced state to lock the balls in: the balls' capacity Σ m R of a plane is below the unbalance it must cancel",
        },
    )
}

/// What moves most at a critical speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Motion {
    /// Translation of the rotor (the tilt's tip motion, at the radius of gyration, smaller).
    Translation,
    /// Tilt of the rotor.
    Tilt,
}

/// A critical speed of the locked rotor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LockedCriticalSpeed {
    /// The speed (rad/s, or the papers' unit `ω0`).
    pub omega: f64,
    /// How many eigenvalues of `A` cross zero there (2: the circular whirl of an axisymmetric
    /// rotor; 1: one of the split pair of an anisotropic one).
    pub multiplicity: usize,
    /// What moves most in the standing whirl (null vector of `A`, tilt at the radius of gyration).
    pub motion: Motion,
}

/// The critical speeds of the locked rotor up to `omega_max` ([`locked_critical_speeds`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LockedCriticalSpeeds {
    /// Ascending.
    pub speeds: Vec<LockedCriticalSpeed>,
    /// The top of the speed range searched.
    pub omega_max: f64,
    /// The grid's number of speeds (a crossing and its return within one grid step cancel in
    /// the count and are missed).
    pub samples: usize,
    /// Speeds of the grid where the closed form has no balanced state to lock the balls in
    /// (too little capacity; paper 004's eccentric race at low speed): not searched.
    pub unlocked: usize,
}

/// `A(Ω)` of the locked undamped rotor linearised about the centred rotor, `m × m`.
fn stiffness_block(rotor: &Rotor, omega: f64) -> Result<(Vec<f64>, usize, Field)> {
    let locked = locked_rotor(rotor, omega, true)?;
    let f = locked.field(omega)?;
    let n = f.dim();
    let m = n / 2;
    let x = vec![0.0; n];
    let mut j = vec![0.0; n * n];
    f.jacobian(0.0, &x, &mut j);
    if let Some(t) = f.period() {
        let mut j4 = vec![0.0; n * n];
        f.jacobian(0.25 * t, &x, &mut j4);
        let big = j.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if j.iter().zip(&j4).any(|(a, b)| (a - b).abs() > 1e-9 * big) {
            return Err(Error::NoLinearisation {
                reason: "the locked rotor's linearisation turns with the rotor (supports that differ by direction): its critical speeds are not located by this version; `autobal campbell` shows the Floquet exponents".into(),
            });
        }
    }
    // the field is q' = q̇, q̇' = A q + B q̇
    for i in 0..m {
        for k in 0..n {
            let want = if k == m + i { 1.0 } else { 0.0 };
            if j[i * n + k] != want {
                return Err(Error::invalid("critical", "the model's state is not (positions, their rates): no stiffness block"));
            }
        }
    }
    let a: Vec<f64> = (0..m).flat_map(|i| j[(m + i) * n..(m + i) * n + m].to_vec()).collect();
    Ok((a, m, f))
}

/// The number of eigenvalues of `A(Ω)` with a positive real part; `None` where the closed form
/// has no balanced state to lock the balls in.
fn positive_count(rotor: &Rotor, omega: f64) -> Result<Option<usize>> {
    let has_balls = match rotor {
        Rotor::Planar(p) => p.n > 0,
        Rotor::Spatial(s) => s.balls() > 0,
    };
    if has_balls && Rotor::guess(&rotor.field(omega)?).is_none() {
        return Ok(None);
    }
    let (a, m, _) = stiffness_block(rotor, omega)?;
    let ev = eigenvalues(&a, m).map_err(|e| Error::invalid("critical", format!("the eigenvalues of the stiffness block did not converge: {e}")))?;
    Ok(Some(ev.iter().filter(|z| z.re > 0.0).count()))
}

/// The critical speeds of `rotor` with its balls locked at balance and no damping, in
/// `(0, omega_max]` on a grid of `samples` speeds (module docs): where the count of positive
/// eigenvalues of the turning-axes stiffness block `A(Ω)` changes, bisected to `1e-12`
/// (several crossings in one grid step are found one after the other where the count moves
/// one way; a crossing and its return within one step cancel and are missed).
pub fn locked_critical_speeds(rotor: &Rotor, omega_max: f64, samples: usize) -> Result<LockedCriticalSpeeds> {
    let speeds = crate::rotor_stability::speed_grid(omega_max, samples)?;
    let counts: Vec<Option<usize>> = speeds.iter().map(|&w| positive_count(rotor, w)).collect::<Result<_>>()?;
    let mut out = vec![];
    for k in 0..speeds.len() - 1 {
        let (Some(c0), Some(c1)) = (counts[k], counts[k + 1]) else { continue };
        let (mut start, mut c_lo) = (speeds[k], c0);
        // one crossing after the other while the count still differs from the step's end
        while c_lo != c1 {
            let (mut lo, mut hi) = (start, speeds[k + 1]);
            let mut c_hi = c1;
            while hi - lo > 1e-12 * hi {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                match positive_count(rotor, mid)? {
                    Some(c) if c == c_lo => lo = mid,
                    Some(c) => {
                        hi = mid;
                        c_hi = c;
                    }
                    None => break,
                }
            }
            let w = 0.5 * (lo + hi);
            out.push(LockedCriticalSpeed { omega: w, multiplicity: c_lo.abs_diff(c_hi), motion: motion_at(rotor, w)? });
            if hi >= speeds[k + 1] {
                break;
            }
            start = hi;
            c_lo = c_hi;
        }
    }
    let gaps = counts.iter().filter(|c| c.is_none()).count();
    Ok(LockedCriticalSpeeds { speeds: out, omega_max, samples: speeds.len(), unlocked: gaps })
}

/// What moves most in the standing whirl at a critical speed `w`.
fn motion_at(rotor: &Rotor, w: f64) -> Result<Motion> {
    let (a, m, f) = stiffness_block(rotor, w)?;
    let ev = eigenvalues(&a, m).map_err(|e| Error::invalid("critical", e.to_string()))?;
    let zero = ev.iter().copied().min_by(|p, q| p.norm().total_cmp(&q.norm())).unwrap_or_default();
    let v = mode(&a, m, zero);
    Ok(match (&f, rotor) {
        (Field::Spatial(_), Rotor::Spatial(r)) if m >= 4 => {
            let gyration = (r.rotor.equatorial_moment / r.total_mass()).sqrt();
            let tr = v[0].norm().max(v[1].norm());
            let tilt = gyration * v[2].norm().max(v[3].norm());
            if tilt > tr {
                Motion::Tilt
            } else {
                Motion::Translation
            }
        }
        _ => Motion::Translation,
    })
}

/// The stationary state of `rotor` at `omega` from its closed form (for tests and figures).
pub fn stationary_at(rotor: &Rotor, omega: f64) -> Result<(Field, StationaryState)> {
    let f = rotor.field(omega)?;
    let guess = Rotor::guess(&f).unwrap_or_else(|| vec![0.0; f.dim()]);
    let s = stationary(&f, &guess, &newton_options(f.period().is_some())).map_err(|e| Error::invalid("speeds", e.to_string()))?;
    Ok((f, s))
}
