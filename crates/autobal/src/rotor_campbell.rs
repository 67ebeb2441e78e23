//! The Campbell diagram and the locked critical speeds of **every rotor autobal can run**
//! (issue "Analyse every rotor", §3): the general route of `autobal campbell` and
//! `autobal critical`, through the model-agnostic pipeline of [`crate::analysis`] on the
//! models' own equations ([`Rotor`]: the planar rotor, the spatial rotor with one or two ball
//! planes, couple unbalance, supports that differ by direction, gravity; the linear
//! rotor-bearing model with its balls free: [`crate::linear_rotor`], whose diagram without the
//! balls is [`crate::linear_rotor::LinearRotor::structure_eigenvalues`]; the analyses with the
//! balls locked refuse it).
//!
//! # Campbell diagram ([`campbell_over_speed`])
//! At each speed the stationary state is found as `stability` finds it
//! ([`crate::rotor_stability`]: Newton from the closed-form balanced state, else from the
//! previous speed's state; shooting for a periodic orbit). Its linearisation gives, in axes
//! turning with the rotor:
//! - **an equilibrium**: the eigenvalues `λ = σ + iν` of the exact (AD) Jacobian;
//! - **a periodic orbit** (supports that differ by direction, gravity across the axis): the
//!   Floquet exponents `ρ = ln μ / T` of the monodromy matrix's multipliers `μ`. Their
//!   imaginary parts are defined only modulo `ω_T = 2π/T` (`Ω` under gravity, `2Ω` where only
//!   the supports differ by direction). **Branch**: the one a fixed observer sees. A Floquet
//!   mode is `x(t) = Φ(t) v = e^{ρ₀ t} p(t)` (`v` the multiplier's eigenvector, `ρ₀` the
//!   principal logarithm over `T`, `p` periodic): in fixed axes each circular coordinate of
//!   the rotor (below) moves as a sum of components at the frequencies `Ω ± (Im ρ₀ + k ω_T)`,
//!   one per harmonic `k` of `p` and sign. The fundamental matrix `Φ(t)` is integrated over one
//!   period (64 samples, DOP853 at 1e-6, once per speed), and the branch `ρ = ρ₀ + i k ω_T` is
//!   that of the **largest component of the rotor's displacement in fixed axes** (what a
//!   displacement probe, or the FFT of a run's `x + iy`, shows largest; ties to the forward
//!   one: `dominant_harmonic`). Its `fixed_frequency` is that component's `Ω ± Im ρ`, its
//!   `forward_share` the `Ω + Im ρ` component's share of the two on this branch. Where the
//!   field is autonomous `p` is constant and this is the eigenvalue's own rule; on a rigid rotor
//!   on supports that differ by direction (constant in fixed axes) it gives the fixed-axes
//!   frequencies exactly, whatever the speed, and a negligible gravity (which doubles the
//!   period) changes nothing (tests/rotor_campbell_branch_20.rs). Modes that do not move the
//!   rotor (the balls alone) and multipliers below 1e-3 of the monodromy's norm (decaying
//!   1000-fold in a period, where the sampled `Φ` no longer resolves them) keep the branch
//!   whose `Im ρ` is nearest `Im` of the Rayleigh quotient `vᴴ J(0) v / vᴴ v` (scaled): a
//!   fixed observer sees nothing of them. (Until session 20 every mode took that quotient's
//!   branch, exact only as the field becomes autonomous: on the two-plane example it put
//!   translation modes `Ω` or `2Ω` off, and flipped with a gravity of 0.001 m/s².)
//!
//! Eigenvalues are tracked into continuous lines by matching each speed's values to the
//! previous lines' linear extrapolations, nearest pair first. The fixed-axes view is that of
//! [`crate::spatial::campbell`]: in turning axes a mode moves the rotor's circular coordinate
//! `ξ + iη` (and, for the spatial rotor, the spin axis' tip `θ − iδ` times the radius of
//! gyration; for the linear rotor every node's `x + iy` and `α + iβ`, each weighted by its
//! kinetic energy: `linear_whirl_pairs`) as components at `Ω + ν` (amplitude
//! `|x_ξ + i x_η|`) and `Ω − ν` (`|x_ξ − i x_η|`, summed in squares over the pairs); the curve's signed fixed-axes frequency `f` is that of the dominant
//! component (`f > 0` forward whirl, `f < 0` backward), the log decrement per fixed-axes cycle
//! `δ = −2π σ/|f|`. Modes with no rotor motion (the balls alone) have no whirl.
//!
//! # Locked balls and the fixed-axes view ([`campbell_locked`], [`fixed_view`])
//! What the 12-state route ([`crate::spatial::campbell`]) gives, on every configuration:
//! [`campbell_locked`] is the diagram of the rotor with its balls locked where the closed form
//! puts them ([`locked_rotor`], damping kept: paper 000's 8-state model on a one-plane config);
//! [`fixed_view`] turns a diagram into one continuous curve per mode in fixed axes with its log
//! decrement, and the critical speeds where a circular component meets an excitation line
//! `h Ω`, found by the 12-state route's search on the stationary state's spectrum (not on the
//! drawn curves nor on the drawn grid: it refines between the drawn speeds, to 1e-6 relative,
//! where a crossing may hide; with the balls locked and no damping, the crossings of `1×` are
//! the critical speeds of eq (16) on a one-plane rotor). Each mode also carries its dominant
//! coordinate group ([`CampbellPoint::group`]). For a periodic orbit the crossings are not
//! defined (a Floquet exponent's `Im ρ` is defined modulo `Ω`, so a crossing of `h×` is one of
//! every other harmonic on another branch) and are not computed.
//!
//! # Critical speeds ([`locked_critical_speeds`])
//! The rotor with its balls **locked** at the closed-form balanced position (each ball becomes
//! a point mass of the rotor: [`locked_rotor`]; where no balanced state exists, at the partially
//! balanced placement, each plane's balls bunched against its share: [`partial_words`]) and
//! **without damping** (as 000 eq (16)),
//! linearised about the centred rotor (exact AD Jacobian `[[0, I], [A, B]]` of the model's
//! field). A critical speed is where a natural frequency in fixed axes equals the speed:
//! - **turning axes**, where this Jacobian does not depend on time (supports equal in every
//!   direction; gravity moves the stationary state, the sag, but not this linearisation, which
//!   is checked: `J(0) = J(T/4)` to 1e-9): a forward whirl at `Ω` stands still in turning axes,
//!   `A(Ω) q = 0`. `A = M⁻¹ S` (`S` symmetric without damping) has real eigenvalues; the number
//!   of positive ones changes exactly at the critical speeds, by the number crossing zero (2 for
//!   the circular whirl of an axisymmetric rotor, 1 for each of the split pair of a rotor whose
//!   inertia differs by direction);
//! - **fixed axes**, where the supports differ by direction (the Jacobian turns with the rotor):
//!   the coordinate pairs (translation, tilt) are rotated into fixed axes, where the locked
//!   rotor's linearisation `[[0, I], [A_f, B_f]]` is constant if its inertia is the same in
//!   every direction (checked at `t = 0` and `T/4`); `λ = iΩ` is an eigenvalue iff
//!   `Q(Ω) = −A_f − iΩ B_f − Ω² I = M⁻¹(K − Ω² M + iΩ² G)` is singular, whose eigenvalues are
//!   real (Hermitian up to `M`): the same count. Here backward modes whose frequency equals the
//!   speed are critical too (the supports' anisotropy lets an unbalance excite them), each
//!   labelled by its whirl. Where the inertia **and** the supports differ by direction (locked
//!   balls or unbalance masses on anisotropic supports) the linearisation is periodic in both
//!   frames, no single frequency defines a critical speed, and
//!   [`crate::Error::NoLinearisation`] says so (the Floquet Campbell diagram still applies).
//!
//! The changes of the count are bracketed on a grid and bisected to `1e-12` relative; speeds of
//! one motion and whirl closer than [`SAME_SPEED`] are merged into one.

use crate::analysis::{mode, stability, stationary, stationary_near, Kind, NewtonOptions, StationaryState, VectorField};
use crate::control::{Control, Outcome};
use crate::error::{Error, Result};
use crate::linalg::eigen_dyn::eigenvalues;
use crate::rotor_stability::{newton_options, Field, Rotor, StateKind};
use crate::spatial::campbell::{FixedCampbell, FixedCurve, FixedPoint};
use crate::spatial::dynamics::PointMass;
pub use crate::spatial::linear_model::Balls;
pub use crate::spatial::stability::Group;
use crate::spatial::stability::Whirl as FixedWhirl;
use crate::spatial::stability::{log_decrement, spectrum_scale};
use num_complex::Complex64;
use serde::Serialize;

/// The branch rule of the Floquet exponents' imaginary parts, as every output states it.
pub const FLOQUET_BRANCH: &str = "Floquet exponents ρ = ln μ / T are defined modulo i2π/T (iΩ where the period is a revolution, under gravity; 2iΩ where only the supports differ by direction, T = π/Ω): the branch shown is that of the largest component of the rotor's displacement in fixed axes over one period (the mode x(t) = e^{ρt} p(t), p periodic, has components at Ω ± Im ρ for each harmonic of p: what a displacement probe or a run's FFT shows largest; ties to the forward one), and fixed_frequency is that component's; modes that do not move the rotor, or decay 1000-fold in a period, take the branch nearest Im of the Rayleigh quotient vᴴJ(0)v/vᴴv of their start vector v";

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
#[serde(into = "PointJson")]
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
    /// Share of the forward component in the rotor's motion, from the mode's eigenvector `x`:
    /// `Σ_p w_p² |x_a + i s_p x_b|² / Σ_p w_p² (|x_a + i s_p x_b|² + |x_a − i s_p x_b|²)` over
    /// the rotor's circular coordinate pairs `p = (a, b, s_p, w_p)` (`whirl_pairs`): the
    /// planar rotor's `ξ + iη` (`w = 1`); the spatial rotor's `ξ + iη` and its tilt `θ − iδ`
    /// at the radius of gyration `w = sqrt(I_eq/M)`; the linear rotor's every node's `x + iy`
    /// and `α + iβ` with `w_p² = M̄_p / M_s` (the pair's mean diagonal mass or inertia over
    /// the structure's translating mass plus the balls', `linear_whirl_pairs`), each term a
    /// kinetic energy per unit of `M_s`. The balls' angles do not enter; ½ where the rotor
    /// does not move (its amplitude below 1e-9 of the mode's largest scaled entry). For a
    /// Floquet exponent the two components of its branch over one period ([`FLOQUET_BRANCH`]):
    /// the `Ω + ν` harmonic's share of the `Ω ± ν` ones, `x` the mode's motion `Φ(t) v`.
    pub forward_share: f64,
    /// Whirl direction in fixed axes.
    pub whirl: Whirl,
    /// Logarithmic decrement per fixed-axes cycle `−2π σ/|f|` (`None` where `|f|` is not
    /// resolved: [`crate::spatial::stability::log_decrement`], on the scale of the values of
    /// the speed whose `re` is known).
    pub log_decrement: Option<f64>,
    /// A structural eigenvalue (the family of balanced states: 0, multiplier 1), not a mode.
    pub structural: bool,
    /// Where the Floquet multiplier `μ` is below what the monodromy's round-off resolves
    /// (`|μ| < δ`, [`undetermined_multiplier_bound`]): the exponent `ln|μ|/T` is not
    /// determined, only bounded, `σ ≤ ln(|μ| + δ)/T`, and this is that bound as a decay rate
    /// `−ln(|μ| + δ)/T > 0` (1/s): the mode decays at least this fast. `re` and `log_decrement`
    /// are then printed as null (JSON) or `< −rate` (table), and `im` (the phase of a
    /// multiplier at round-off) is not determined either. `None` for a determined exponent and
    /// for every eigenvalue of an equilibrium.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub decay_at_least: Option<f64>,
    /// The coordinates that carry most of the mode's kinetic energy per unit of `M_s`: the
    /// translation `|x_ξ|² + |x_η|²`, the tilt `ρ² (|x_δ|² + |x_θ|²)` (`ρ` the rotor's radius
    /// of gyration) or the balls `Σ_j (m_j/M_s) R_j² |x_ψj|²` (as the 12-state route's
    /// [`Group`], which weighs the balls' unbalance `s` alike).
    pub group: Group,
}

/// A [`CampbellPoint`] as the JSON gives it: `re` and `log_decrement` null where only a bound
/// is known ([`CampbellPoint::decay_at_least`]).
#[derive(Serialize)]
struct PointJson {
    omega: f64,
    re: Option<f64>,
    im: f64,
    fixed_frequency: f64,
    forward_share: f64,
    whirl: Whirl,
    log_decrement: Option<f64>,
    structural: bool,
    group: Group,
    #[serde(skip_serializing_if = "Option::is_none")]
    decay_at_least: Option<f64>,
}

impl From<CampbellPoint> for PointJson {
    fn from(p: CampbellPoint) -> Self {
        let known = p.decay_at_least.is_none();
        PointJson {
            omega: p.omega,
            re: known.then_some(p.re),
            im: p.im,
            fixed_frequency: p.fixed_frequency,
            forward_share: p.forward_share,
            whirl: p.whirl,
            log_decrement: p.log_decrement.filter(|_| known),
            structural: p.structural,
            group: p.group,
            decay_at_least: p.decay_at_least,
        }
    }
}

/// The relative accuracy of the monodromy matrices of the general route's Floquet analyses:
/// the shooting's `rtol` of the general route (`rotor_stability::newton_options`, shared by the
/// Campbell scans, the speed scan and the map's cells), at which the orbit's monodromy matrix is
/// integrated (DOP853, its Jacobian interpolated to the same `rtol`: [`crate::analysis`]).
pub const MONODROMY_RTOL: f64 = 1e-10;

/// The multiplier size below which a Floquet multiplier is round-off of the monodromy matrix
/// `Φ`, not a number: `δ = 100 · rtol · ‖S⁻¹ Φ S‖∞` (`S` the field's
/// [`scales`](crate::analysis::VectorField::scales), in which the integration's tolerances are
/// set; `rtol` = [`MONODROMY_RTOL`]). Why: the variational equations are integrated at `rtol`
/// per step (atol `rtol · S`) with a Jacobian interpolated to `rtol ‖S⁻¹JS‖∞`, so the scaled
/// monodromy carries an absolute error `‖δΦ‖ ≈ c · rtol · ‖S⁻¹ΦS‖`, and a multiplier `μ`
/// computed from it an error `≤ κ ‖δΦ‖` (`κ` its condition number). A computed `|μ| < δ` is
/// then indistinguishable from 0; the true `|μ| ≤ |μ̂| + δ`. The factor 100 holds `c κ`:
/// measured (tests/rotor_campbell_18.rs) the computed multipliers of a nearly isotropic
/// Jeffcott rotor differ from their exact `e^{λT}` by at most 0.09 δ (9e-12 of `‖S⁻¹ΦS‖∞` at
/// `rtol = 1e-10`).
pub fn undetermined_multiplier_bound(monodromy: &[f64], scales: &[f64]) -> f64 {
    let n = scales.len();
    let norm = (0..n).map(|i| (0..n).map(|j| (monodromy[i * n + j] * scales[j] / scales[i]).abs()).sum::<f64>()).fold(0.0, f64::max);
    100.0 * MONODROMY_RTOL * norm
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
    /// `"planar"`, `"spatial"` or `"linear"` ([`Rotor::model_name`]).
    pub model: &'static str,
    /// Equilibrium (eigenvalues) or periodic orbit (Floquet exponents).
    pub kind: Kind,
    /// The speeds.
    pub omega: Vec<f64>,
    /// The tracked lines (one per eigenvalue).
    pub lines: Vec<CampbellLine>,
    /// Why a speed has no state, per speed (`None` where it has one).
    pub failures: Vec<Option<String>>,
    /// Whether each speed was analysed: `false` for a periodic orbit's speed below the
    /// periodic-orbit floor ([`Rotor::periodic_floor`], the rule of
    /// [`crate::rotor_stability`]), where no state was sought and `failures` says so (not "no
    /// stationary state found").
    pub analysed: Vec<bool>,
    /// What the stationary state followed is at each speed ([`Rotor::state_kind`], the words
    /// of `stability`'s `state`; `None` without a state): balanced (semi-balanced), or
    /// partially balanced where the balls' capacity falls short of the unbalance and no
    /// balanced state exists (the starts of `stability`'s scan). The locked diagram's are `None` (its state is
    /// the locked rotor's).
    pub states: Vec<Option<StateKind>>,
}

/// The eigenvalues (or Floquet exponents) of the stationary state at one speed, with their
/// fixed-axes data, unsorted: `field` at its speed `omega`, `state` its stationary state.
pub fn spectrum_at(rotor: &Rotor, field: &Field, omega: f64, state: &StationaryState) -> Result<Vec<CampbellPoint>> {
    spectrum_and_modes_at(rotor, field, omega, state).map(|(p, _)| p)
}

/// [`spectrum_at`] with the scaled coordinates' part (`S⁻¹ v`) of each value's eigenvector,
/// for the tracking ([`Tracker`]).
fn spectrum_and_modes_at(rotor: &Rotor, field: &Field, omega: f64, state: &StationaryState) -> Result<(Vec<CampbellPoint>, Vec<Vec<Complex64>>)> {
    let st = stability(field, state).map_err(|e| Error::invalid("campbell", e.to_string()))?;
    let n = field.dim();
    let scales = field.scales();
    let jac0 = {
        let mut j = vec![0.0; n * n];
        field.jacobian(0.0, &state.x, &mut j);
        j
    };
    let pairs = whirl_pairs(rotor, field);
    // a periodic orbit's multipliers below the monodromy's round-off: only a bound
    let roundoff = state.period.map(|_| undetermined_multiplier_bound(&st.matrix, &scales));
    let mut out = Vec::with_capacity(n);
    let mut modes = Vec::with_capacity(n);
    let all = st.spectrum.iter().map(|e| (e.complex(), false)).chain(st.structural.iter().map(|e| (e.complex(), true)));
    // a periodic orbit's fundamental matrix Φ(t_j) over one period, for the modes' harmonics
    // in fixed axes (integrated once, on the first mode that moves the rotor)
    let mut fundamental: Option<Vec<f64>> = None;
    for (value, structural) in all {
        let v = balanced_mode(&st.matrix, n, value);
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
        // a multiplier the sampled Φ(t) resolves to 1e-3 (its error HARMONIC_RTOL ‖S⁻¹ΦS‖∞;
        // the round-off bound is 100 MONODROMY_RTOL of that norm)
        let undetermined = matches!(roundoff, Some(d) if value.norm() < d * 1e3 * HARMONIC_RTOL / (100.0 * MONODROMY_RTOL));
        let (lam, share, f) = match state.period {
            None => {
                let share = if moves { fwd / total } else { 0.5 };
                (value, share, if share >= 0.5 { omega + value.im } else { omega - value.im })
            }
            Some(t) => {
                let rho0 = Complex64::new(value.norm().max(f64::MIN_POSITIVE).ln(), value.arg()) / t;
                let big = 2.0 * std::f64::consts::PI / t;
                let harmonic = if moves && !undetermined {
                    if fundamental.is_none() {
                        fundamental = Some(fundamental_samples(field, &state.x, t)?);
                    }
                    fundamental.as_deref().and_then(|phi| dominant_harmonic(phi, n, &v, rho0, omega, t, &pairs))
                } else {
                    None
                };
                match harmonic {
                    // the branch of the largest circular component of the rotor's motion in
                    // fixed axes (FLOQUET_BRANCH)
                    Some(Harmonic { k, plus, share }) => {
                        let lam = Complex64::new(rho0.re, rho0.im + k as f64 * big);
                        (lam, share, if plus { omega + lam.im } else { omega - lam.im })
                    }
                    // a ball mode, or a multiplier below the monodromy's round-off: the branch
                    // nearest the Rayleigh quotient of J(0) in scaled coordinates
                    None => {
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
                        let k = ((q.im - rho0.im) / big).round();
                        let lam = Complex64::new(rho0.re, rho0.im + k * big);
                        let share = if moves { fwd / total } else { 0.5 };
                        (lam, share, if share >= 0.5 { omega + lam.im } else { omega - lam.im })
                    }
                }
            }
        };
        let group = group_of(rotor, field, &pairs, &v);
        let whirl = if !moves || f == 0.0 {
            Whirl::None
        } else if f > 0.0 {
            Whirl::Forward
        } else {
            Whirl::Backward
        };
        let decay_at_least = match (state.period, roundoff) {
            (Some(t), Some(d)) if value.norm() < d => Some(-(value.norm() + d).ln() / t),
            _ => None,
        };
        out.push(CampbellPoint {
            omega,
            re: lam.re,
            im: lam.im,
            fixed_frequency: f,
            forward_share: share,
            whirl,
            // set below, on the scale of the whole spectrum
            log_decrement: None,
            structural,
            group,
            decay_at_least,
        });
        // the coordinates' half (the state is [q, q̇]), as the 12-state route's MAC of the
        // pencil's q
        modes.push(v.iter().zip(&scales).take(n / 2).map(|(z, s)| z / s).collect());
    }
    // the log decrement on the scale of the values whose real part is known (a multiplier
    // below round-off has none, and an exponent far below every other)
    let scale = spectrum_scale(out.iter().filter(|p| p.decay_at_least.is_none()).map(|p| Complex64::new(p.re, p.im)));
    for p in &mut out {
        p.log_decrement = log_decrement(p.re, p.fixed_frequency, scale);
    }
    Ok((out, modes))
}

/// Samples per period of a Floquet mode's motion for its harmonics ([`dominant_harmonic`]):
/// the discrete Fourier transform of `N` samples gives the harmonics `|k| < N/2` of the
/// mode's periodic part exactly where the higher ones vanish (a smooth `p(t)`: its
/// coefficients fall geometrically, as the Jacobian's of the orbit do, which the monodromy's
/// interpolant resolves with at most 64 samples: module docs of [`crate::analysis`]).
const HARMONIC_NODES: usize = 64;

/// Relative tolerance of the fundamental matrix `Φ(t)` sampled for the harmonics
/// ([`fundamental_samples`]; absolute `rtol · s_a / s_b` on `Φ_ab`, as the monodromy's). The
/// harmonics only rank the components: an error of `1e-6` of `‖Φ‖` moves them by far less
/// than any gap that decides a branch (the pick breaks ties within [`HARMONIC_TIE`]).
const HARMONIC_RTOL: f64 = 1e-6;

/// Relative difference of two components' sizes below which they count as equal and the pick
/// goes to the one of positive fixed-axes frequency (forward whirl). A mode of a rotor that is
/// the same in every direction on supports that are not (no gyroscopic coupling, no balls)
/// whirls on a line: its forward and backward components at `±f` are equal, and only the sign
/// of `f` is at stake; well above [`HARMONIC_RTOL`].
const HARMONIC_TIE: f64 = 1e-4;

/// The fundamental matrix `Φ(t_j)` (`Φ' = J(t, x(t)) Φ`, `Φ(0) = I`) of the periodic orbit
/// through `x0` at the [`HARMONIC_NODES`] times `t_j = j T / N`, `j = 0 .. N − 1`, row-major
/// `n × n` each: the variational equations with the orbit, DOP853 at [`HARMONIC_RTOL`]
/// (absolute tolerances by the field's scales), sampled by its dense output.
fn fundamental_samples(field: &Field, x0: &[f64], period: f64) -> Result<Vec<f64>> {
    use crate::ode::{Control as Step, Method, Options, Solver};
    let n = field.dim();
    let s = field.scales();
    let sys = crate::analysis::VariationalSystem::new(field);
    let mut atol: Vec<f64> = s.iter().map(|v| HARMONIC_RTOL * v).collect();
    for a in 0..n {
        for b in 0..n {
            atol.push(HARMONIC_RTOL * s[a] / s[b]);
        }
    }
    let opts = Options::new(HARMONIC_RTOL, HARMONIC_RTOL).method(Method::Dop853).atol_per_component(atol);
    let mut solver = Solver::new(&sys, opts)?;
    let mut y = vec![0.0; n + n * n];
    y[..n].copy_from_slice(x0);
    for a in 0..n {
        y[n + a * n + a] = 1.0;
    }
    let mut samples = vec![0.0; HARMONIC_NODES * n * n];
    samples[..n * n].copy_from_slice(&y[n..]);
    let node = |j: usize| period * j as f64 / HARMONIC_NODES as f64;
    let mut next = 1;
    let mut buf = vec![0.0; n + n * n];
    let out = solver.integrate(0.0, &mut y, period, |step| {
        while next < HARMONIC_NODES && node(next) <= step.t_new {
            step.interpolate(node(next), &mut buf);
            samples[next * n * n..(next + 1) * n * n].copy_from_slice(&buf[n..]);
            next += 1;
        }
        Step::Continue
    });
    if !out.status.is_completed() || next < HARMONIC_NODES {
        return Err(Error::invalid("campbell", format!("the Floquet modes' integration over one period did not complete: {out}")));
    }
    Ok(samples)
}

/// The branch of a Floquet mode from its motion in fixed axes ([`dominant_harmonic`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Harmonic {
    /// The branch `ρ = ρ₀ + i k 2π/T`.
    k: i64,
    /// Whether the largest component is the `Ω + Im ρ` one (else `Ω − Im ρ`).
    plus: bool,
    /// The `Ω + Im ρ` component's share of the two on this branch (as an eigenvalue's
    /// [`CampbellPoint::forward_share`]).
    share: f64,
}

/// The harmonic of a Floquet mode that a fixed observer sees largest ([`FLOQUET_BRANCH`]).
/// The mode is `x(t) = Φ(t) v = e^{ρ₀ t} p(t)` (`v` the multiplier's eigenvector, `ρ₀` the
/// principal exponent, `p` periodic with `T`); each circular pair's coordinate in turning axes
/// `z_± = w (x_a ± i s x_b)` ([`whirl_pairs`]) has the harmonics `Z_±,k` of
/// `z_±(t) e^{−ρ₀ t}` (discrete Fourier transform of the `phi` samples,
/// [`fundamental_samples`]), and the real motion `Re x` moves the pair's point in fixed axes
/// (`e^{iΩt}` times the turning coordinate) as `½ Σ_k Z_+,k e^{i(Ω + ν₀ + k ω_T)t} +
/// conj(Z_−,k) e^{i(Ω − ν₀ − k ω_T)t}` times `e^{σt}` (`ν₀ = Im ρ₀`, `ω_T = 2π/T`): components
/// at the fixed-axes frequencies `Ω ± (ν₀ + k ω_T)` of sizes `F_k = Σ_p |Z_+,k|²`,
/// `B_k = Σ_p |Z_−,k|²` over the pairs. The largest, ties ([`HARMONIC_TIE`]) to the positive
/// frequency, gives the branch. `None` where the rotor does not move or a sample is not finite.
fn dominant_harmonic(phi: &[f64], n: usize, v: &[Complex64], rho0: Complex64, omega: f64, period: f64, pairs: &[(usize, usize, f64, f64)]) -> Option<Harmonic> {
    let nodes = HARMONIC_NODES;
    let i = Complex64::new(0.0, 1.0);
    // z_± of every pair at every node, without the exponential e^{ρ₀ t}
    let mut plus = vec![Complex64::new(0.0, 0.0); nodes * pairs.len()];
    let mut minus = plus.clone();
    let mut x = vec![Complex64::new(0.0, 0.0); n];
    for j in 0..nodes {
        let t = period * j as f64 / nodes as f64;
        let phase = (-rho0 * t).exp();
        let m = &phi[j * n * n..(j + 1) * n * n];
        for (a, xa) in x.iter_mut().enumerate() {
            *xa = m[a * n..(a + 1) * n].iter().zip(v).map(|(p, z)| *p * z).sum::<Complex64>() * phase;
        }
        for (q, &(a, b, sign, w)) in pairs.iter().enumerate() {
            plus[j * pairs.len() + q] = w * (x[a] + i * sign * x[b]);
            minus[j * pairs.len() + q] = w * (x[a] - i * sign * x[b]);
        }
    }
    if plus.iter().chain(&minus).any(|z| !z.is_finite()) {
        return None;
    }
    let half = (nodes / 2) as i64;
    let twiddle: Vec<Complex64> = (0..nodes).map(|j| Complex64::from_polar(1.0, -2.0 * std::f64::consts::PI * j as f64 / nodes as f64)).collect();
    let power = |z: &[Complex64], k: i64| -> f64 {
        (0..pairs.len())
            .map(|q| {
                let c: Complex64 = (0..nodes).map(|j| z[j * pairs.len() + q] * twiddle[((k.rem_euclid(nodes as i64) as usize) * j) % nodes]).sum();
                c.norm_sqr()
            })
            .sum()
    };
    let big = 2.0 * std::f64::consts::PI / period;
    let nu0 = rho0.im;
    // (size, fixed-axes frequency sign > 0, k, plus, F_k, B_k)
    let mut best: Option<(f64, bool, i64, bool, f64, f64)> = None;
    for k in -half..half {
        let (fk, bk) = (power(&plus, k), power(&minus, k));
        let shift = nu0 + k as f64 * big;
        for (size, pl) in [(fk, true), (bk, false)] {
            // the sign of the component's frequency in fixed axes
            let forward = if pl { omega + shift > 0.0 } else { omega - shift > 0.0 };
            let better = match best {
                None => true,
                Some((s0, fw0, ..)) => {
                    let tie = (size - s0).abs() <= HARMONIC_TIE * size.max(s0);
                    if tie {
                        !fw0 && forward
                    } else {
                        size > s0
                    }
                }
            };
            if better {
                best = Some((size, forward, k, pl, fk, bk));
            }
        }
    }
    let (size, _, k, pl, fk, bk) = best?;
    (size > 0.0).then(|| Harmonic { k, plus: pl, share: fk / (fk + bk) })
}

/// [`Error::InvalidParameter`] naming `linear_rotor` for [`Rotor::Linear`]: the analyses with
/// the balls **locked** (the locked rotor, its Campbell diagram and critical speeds) do not
/// lock the linear rotor's balls into its structure yet (each ball a point mass of the node:
/// mass on the translations, an inertia that turns with the rotor on the tilts).
fn refuse_linear(rotor: &Rotor, what: &str) -> Result<()> {
    match rotor {
        Rotor::Linear(_) => Err(linear_refused(what)),
        _ => Ok(()),
    }
}

fn linear_refused(what: &str) -> Error {
    Error::invalid(
        "linear_rotor",
        format!("{what} of the general route does not take the linear rotor yet: its balls are not locked into the structure (the Campbell diagram with the balls free does; without them, LinearRotor::structure_eigenvalues)"),
    )
}

/// The eigenvector of the `n × n` matrix `a` (row-major) for its eigenvalue `value`:
/// [`mode`]'s inverse iteration on the balanced matrix `D⁻¹ A D` (Parlett–Reinsch, powers of
/// two, so exact; LAPACK `dgebal` without permutations), mapped back, `v = D v_b`, largest
/// component 1. [`mode`]'s solver replaces any pivot below `ε max|a_ij|` by that bound: on the
/// raw Jacobian of a shaft model (entries from 1 to 5e11: `K/M` of the tilts) legitimate pivots
/// fall below it and the vector came out mixed with its neighbour's (the linear rotor's
/// forward and backward modes `2Ω` apart read shares 0.30 and 0.94 where numpy's `eig` of
/// the same matrix, and the balanced iteration, give 0.0049 and 0.995: share18).
fn balanced_mode(a: &[f64], n: usize, value: Complex64) -> Vec<Complex64> {
    const RADIX: f64 = 2.0;
    let mut b = a.to_vec();
    let mut d = vec![1.0; n];
    let mut done = false;
    let mut sweeps = 0;
    while !done && sweeps < 100 {
        done = true;
        sweeps += 1;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in (0..n).filter(|&j| j != i) {
                c += b[j * n + i].abs();
                r += b[i * n + j].abs();
            }
            if c == 0.0 || r == 0.0 || !(c + r).is_finite() {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            while c < r / RADIX {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            while c > r * RADIX {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if (c + r) / f < 0.95 * s {
                done = false;
                d[i] *= f;
                for j in 0..n {
                    b[i * n + j] /= f;
                    b[j * n + i] *= f;
                }
            }
        }
    }
    let mut v = mode(&b, n, value);
    v.iter_mut().zip(&d).for_each(|(z, s)| *z *= *s);
    let big = v.iter().copied().max_by(|p, q| p.norm().total_cmp(&q.norm())).unwrap_or(Complex64::new(1.0, 0.0));
    if big.norm() > 0.0 && big.is_finite() {
        v.iter_mut().for_each(|z| *z /= big);
    }
    v
}

/// The coordinate group of a mode `v` ([`CampbellPoint::group`]): translation (the first
/// whirl pair), tilt (the second, weighted by the radius of gyration), or the balls (each
/// angle `ψ_j` weighted by `m_j R_j² / M_s`); ties go to the first.
fn group_of(rotor: &Rotor, field: &Field, pairs: &[(usize, usize, f64, f64)], v: &[Complex64]) -> Group {
    let energy = |&(a, b, _, w): &(usize, usize, f64, f64)| w * w * (v[a].norm_sqr() + v[b].norm_sqr());
    let pair = |k: usize| pairs.get(k).map_or(0.0, energy);
    let balls: f64 = ball_coordinates(rotor, field).iter().map(|&(i, w)| w * v[i].norm_sqr()).sum();
    let (t, c) = match field {
        // the linear rotor: every node's translation pair, and every tilt pair
        Field::Linear(l) => {
            let tilt = |a: usize| matches!(l.rotor().dof_node(a), Some((_, crate::linear_rotor::Direction::Alpha)));
            let sum = |want: bool| pairs.iter().filter(|p| tilt(p.0) == want).map(energy).sum::<f64>();
            (sum(false), sum(true))
        }
        _ => (pair(0), pair(1)),
    };
    if balls > t && balls > c {
        Group::Balls
    } else if c > t {
        Group::Tilt
    } else {
        Group::Translation
    }
}

/// The balls' angle coordinates and their weights `(index, m_j R_j² / M_s)`.
fn ball_coordinates(rotor: &Rotor, field: &Field) -> Vec<(usize, f64)> {
    match (rotor, field) {
        (Rotor::Planar(p), Field::Planar(_)) => {
            let m = p.total_mass();
            (0..p.n).map(|j| (2 + j, p.ball_mass(j) * p.r * p.r / m)).collect()
        }
        (Rotor::Spatial(r), Field::Spatial(s)) => {
            let m = r.total_mass();
            let start = s.coords() - r.balls();
            r.planes
                .iter()
                .flat_map(|p| std::iter::repeat_n(p.ball_mass * p.race_radius * p.race_radius / m, p.n))
                .enumerate()
                .map(|(j, w)| (start + j, w))
                .collect()
        }
        (_, Field::Linear(l)) => {
            let r = l.rotor();
            let m = linear_mass(r);
            r.balancers
                .iter()
                .flat_map(|p| std::iter::repeat_n(p.ball_mass * p.radius * p.radius / m, p.balls))
                .enumerate()
                .map(|(j, w)| (r.dofs() + j, w))
                .collect()
        }
        _ => vec![],
    }
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
        (_, Field::Linear(l)) => linear_whirl_pairs(l.rotor()),
        _ => vec![(0, 1, 1.0, 1.0)],
    }
}

/// The linear rotor's mass `M_s` for the weights of [`linear_whirl_pairs`] and the balls'
/// [`ball_coordinates`]: `Σ M_ii` over the `x` DOFs (the structure's translating mass; each
/// node's `M_xx`) plus the balls' `Σ n m_b`.
fn linear_mass(r: &crate::linear_rotor::LinearRotor) -> f64 {
    let n = r.dofs();
    let structure: f64 = (0..n).filter(|&i| matches!(r.dof_node(i), Some((_, crate::linear_rotor::Direction::X)))).map(|i| r.m[i * n + i]).sum();
    let balls: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass).sum();
    structure + balls
}

/// The whirl pairs of the linear rotor ([`whirl_pairs`]): every DOF pair `(x, y)` and `(α, β)`
/// of every node (the pairs that turn together with the frame: [`crate::linear_rotor::LinearRotorField::rotating_to_fixed`]),
/// `x + i y` and `α + i β`, weighted by `sqrt(M̄/M_s)` with `M̄ = (M_aa + M_bb)/2` the pair's
/// mean diagonal mass (inertia for the tilts) and `M_s` [`linear_mass`], so that each pair's
/// `w² (|x_a|² + |x_b|²)` is its kinetic energy per unit of `M_s` alone (as the spatial rotor's
/// tilt at its radius of gyration). The tilt pair counts as `α + iβ`: a point at offset `z`
/// moves by `z (β, −α)`, whose circular components `|zβ ± i(−zα)|` are `z |α ± iβ|`, the
/// same split (the spatial rotor's `θ − iδ`). Pairs of a reduced rotor's
/// modal pseudo-nodes `(φ, Jφ)` split likewise: the forward part of `η_a φ + η_b Jφ` is
/// `(η_a + iη_b)` times `φ`'s, the backward `(η_a − iη_b)` times `φ`'s, of equal size for a
/// real `φ`.
fn linear_whirl_pairs(r: &crate::linear_rotor::LinearRotor) -> Vec<(usize, usize, f64, f64)> {
    let n = r.dofs();
    let ms = linear_mass(r);
    (0..n / 2)
        .map(|p| {
            let (a, b) = (2 * p, 2 * p + 1);
            let mean = 0.5 * (r.m[a * n + a] + r.m[b * n + b]);
            (a, b, 1.0, (mean.max(0.0) / ms).sqrt())
        })
        .collect()
}

/// The Campbell diagram of `rotor` over `speeds` (module docs): at each speed the stationary
/// state (closed form first, then the previous speed's state), its eigenvalues or Floquet
/// exponents with their fixed-axes data, tracked into lines. Runs to the end:
/// [`campbell_over_speed_with`] under a [`Control`].
pub fn campbell_over_speed(rotor: &Rotor, speeds: &[f64]) -> Result<RotorCampbell> {
    campbell_over_speed_with(rotor, speeds, &Control::none()).map(|o| o.value)
}

/// [`campbell_over_speed`] under `control`, asked once per speed; the progress observer is told
/// the speeds done. Stopped, the outcome holds the diagram over the speeds done until then
/// (`omega`, `lines` and `failures` of those speeds).
pub fn campbell_over_speed_with(rotor: &Rotor, speeds: &[f64], control: &Control) -> Result<Outcome<RotorCampbell>> {
    if speeds.is_empty() {
        return Err(Error::invalid("speeds", "no speed to analyse"));
    }
    if let Some(w) = speeds.iter().find(|w| !(w.is_finite() && **w != 0.0)) {
        return Err(Error::invalid("speeds", format!("{w} is not a finite non-zero speed")));
    }
    let first = rotor.field(speeds[0])?;
    let kind = if first.period().is_some() { Kind::PeriodicOrbit } else { Kind::Equilibrium };
    let floor = below_floor_of(rotor, kind, speeds)?;
    let opts = newton_options(kind == Kind::PeriodicOrbit);
    let mut previous: Option<StationaryState> = None;
    // one entry per speed done; the lines are the tracker's (with the eigenvectors)
    let mut per_speed: Vec<Option<()>> = Vec::with_capacity(speeds.len());
    let mut tracker = Tracker::default();
    let mut failures = Vec::with_capacity(speeds.len());
    let mut analysed = Vec::with_capacity(speeds.len());
    let mut states: Vec<Option<StateKind>> = vec![None; speeds.len()];
    let mut stopped = None;
    for &w in speeds {
        if let Some(why) = control.should_stop() {
            stopped = Some(why);
            break;
        }
        if let Some(why) = floor(w) {
            tracker.push(None, None);
            per_speed.push(None);
            failures.push(Some(why));
            analysed.push(false);
            control.report(per_speed.len() as u64, speeds.len() as u64);
            continue;
        }
        analysed.push(true);
        let f = rotor.field(w)?;
        // under gravity with n >= 3 balls in a plane: the orbit with the balls in two groups
        // (the family's arc member is no orbit; Rotor::gravity_orbit_start), or none at all
        if let Some(why) = f.gravity_circulation() {
            previous = None;
            tracker.push(None, None);
            per_speed.push(None);
            failures.push(Some(why));
            control.report(per_speed.len() as u64, speeds.len() as u64);
            continue;
        }
        // under the control's stop probe: a stop ends this speed's integrations early, and a
        // speed that failed then is dropped, not reported as a speed without a state
        let computed = crate::control::with_probe(control, || {
            let guess = free_start(rotor, &f, &opts);
            let near = previous.as_ref().map(|p| p.x.clone());
            let hint = previous.as_ref().and_then(|p| p.monodromy.clone());
            let mut result = Err(reason(no_state_free(rotor)));
            // the closed form, shot from first with `hint` (Rotor::settle_balanced does not repeat it)
            let guess_tried = guess.clone();
            for start in [guess, near].into_iter().flatten() {
                match stationary_near(&f, &start, hint.as_deref(), &opts) {
                    Ok(s) => {
                        result = Ok(s);
                        break;
                    }
                    Err(e) => result = Err(e.to_string()),
                }
            }
            // the balanced (semi-balanced) state wherever Newton reaches one, as `stability` and
            // `map` analyse (Rotor::settle_balanced, the commands' one rule), classified once
            let result = result.map(|s| Rotor::settle_balanced(&f, s, hint.as_deref(), guess_tried.as_deref(), &opts));
            result.and_then(|(s, class)| spectrum_and_modes_at(rotor, &f, w, &s).map(|p| (s, class, p)).map_err(|e| e.to_string()))
        });
        match computed {
            Ok((s, class, (p, modes))) => {
                states[per_speed.len()] = Some(class.0);
                previous = Some(s);
                tracker.push(Some(&p), Some(modes));
                per_speed.push(Some(()));
                failures.push(None);
            }
            Err(_) if control.should_stop().is_some() => {
                analysed.pop();
                stopped = control.should_stop();
                break;
            }
            Err(e) => {
                previous = None;
                tracker.push(None, None);
                per_speed.push(None);
                failures.push(Some(e));
            }
        }
        control.report(per_speed.len() as u64, speeds.len() as u64);
    }
    let done = per_speed.len();
    states.truncate(done);
    let value = RotorCampbell { model: rotor.model_name(), kind, omega: speeds[..done].to_vec(), lines: tracker.lines, failures, analysed, states };
    Ok(Outcome { value, stopped })
}

/// What a Campbell scan over `speeds` of a stationary state of `kind` does at each speed below
/// the periodic-orbit floor ([`Rotor::below_periodic_floor`], the speed scan's rule): the
/// closure gives the failure's words there (`None`: the speed is analysed). Every speed below
/// it is refused, naming `omega_max` (the top speed), as [`crate::rotor_stability`] refuses it.
fn below_floor_of<'a>(rotor: &'a Rotor, kind: Kind, speeds: &[f64]) -> Result<impl Fn(f64) -> Option<String> + 'a> {
    let periodic = kind == Kind::PeriodicOrbit;
    let top = speeds.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if let Some(f) = periodic.then(|| rotor.below_periodic_floor(top)).flatten() {
        return Err(Error::invalid("omega_max", crate::rotor_stability::below_floor(top, f)));
    }
    Ok(move |w: f64| {
        periodic.then(|| rotor.below_periodic_floor(w)).flatten().map(|f| format!("{NOT_ANALYSED}: {}", crate::rotor_stability::below_floor(w, f)))
    })
}

/// The words of a speed below the periodic-orbit floor in [`RotorCampbell::failures`].
pub const NOT_ANALYSED: &str = "not analysed (below the periodic-orbit floor)";

/// Continuous lines through each speed's values: each line's next value predicted by linear
/// extrapolation of its last two, pairs matched nearest first (by value alone: [`Tracker`]
/// adds the eigenvectors where they are known).
pub fn track(per_speed: &[Option<Vec<CampbellPoint>>]) -> Vec<CampbellLine> {
    let mut t = Tracker::default();
    for vals in per_speed {
        t.push(vals.as_deref(), None);
    }
    t.lines
}

/// The tracking of [`track`], one speed at a time, with the modes' eigenvectors where they are
/// given. By value alone the balls' slow real eigenvalues swapped lines at the lowest speeds of
/// the general route (session 17's check; the Jeffcott rotor of paper 004, 300 speeds: the two
/// are `a Ω⁴` and `2.27 a Ω⁴`, accurate, but a step multiplies them by up to 81 while they are
/// 1e-9 apart, so the linear prediction's error exceeds their gap and the nearest value is the
/// other line's). With eigenvectors, the **slow block** (lines whose last value, and values,
/// of modulus at most [`SLOW`] of the speed's largest) is matched first, by the optimal
/// assignment (Hungarian method) of the cost `|λ_pred − λ| / u + 4 (1 − MAC)`: `u` the line's
/// own prediction uncertainty (the second difference of its last three values, else the
/// first, else its value, plus 1e-12 of the largest `|λ|`), `MAC = |aᴴb|² / (|a|² |b|²)` of
/// the scaled coordinates' part of the eigenvectors (`S⁻¹ v`, [`VectorField::scales`]), as
/// the 12-state route's term ([`crate::spatial::campbell`]). The other lines continue by value,
/// nearest pairs first, as before (MAC and the optimal assignment over every line moved the
/// kept line at real-axis collisions away from the 12-state route's:
/// tests/rotor_campbell_views.rs).
#[derive(Debug, Default)]
pub struct Tracker {
    /// The lines so far.
    pub lines: Vec<CampbellLine>,
    /// Each line's last eigenvector (scaled), where known.
    last: Vec<Option<Vec<Complex64>>>,
    /// The speeds pushed so far (a line begun late has `None` at the earlier ones).
    speeds: usize,
}

impl Tracker {
    /// Add one speed: its values (`None`: no state there) and, optionally, each value's
    /// eigenvector (scaled, in the values' order).
    pub fn push(&mut self, vals: Option<&[CampbellPoint]>, vecs: Option<Vec<Vec<Complex64>>>) {
        let k = self.speeds;
        self.speeds += 1;
        let Some(vals) = vals else {
            self.lines.iter_mut().for_each(|l| l.points.push(None));
            return;
        };
        while self.lines.len() < vals.len() {
            self.lines.push(CampbellLine { points: vec![None; k] });
            self.last.push(None);
        }
        let n = self.lines.len();
        let z = |p: &CampbellPoint| Complex64::new(p.re, p.im);
        let w2 = vals.first().map(|p| p.omega);
        let predict = |l: &CampbellLine| -> Option<Complex64> {
            let last = l.points.last().copied().flatten()?;
            match l.points.len().checked_sub(2).and_then(|i| l.points[i]) {
                Some(p2) if k >= 2 => {
                    let (w0, w1, w2) = (p2.omega, last.omega, w2.unwrap_or(last.omega));
                    let t = if w1 != w0 { (w2 - w1) / (w1 - w0) } else { 0.0 };
                    Some(z(&last) + (z(&last) - z(&p2)) * t)
                }
                _ => Some(z(&last)),
            }
        };
        let mac = |a: &[Complex64], b: &[Complex64]| {
            let dot: Complex64 = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
            let (na, nb) = (a.iter().map(|x| x.norm_sqr()).sum::<f64>(), b.iter().map(|x| x.norm_sqr()).sum::<f64>());
            if na > 0.0 && nb > 0.0 {
                dot.norm_sqr() / (na * nb)
            } else {
                0.0
            }
        };
        // a line's prediction error, estimated from its last points: the second difference
        // (the linear extrapolation's error one step ago), else the first, else the value
        // itself, above a floor of round-off
        let floor = 1e-12 * vals.iter().map(|p| z(p).norm()).fold(0.0, f64::max) + f64::MIN_POSITIVE;
        let uncertainty = |l: &CampbellLine| -> f64 {
            let tail: Vec<Complex64> = l.points.iter().rev().take(3).map_while(|p| p.as_ref().map(z)).collect();
            floor
                + match tail.as_slice() {
                    [a, b, c] => (a - b * 2.0 + c).norm(),
                    [a, b] => (a - b).norm(),
                    [a] => a.norm(),
                    _ => 0.0,
                }
        };
        let top = floor / 1e-12;
        let slow_value = |p: &CampbellPoint| z(p).norm() <= SLOW * top;
        let slow_line = |l: &CampbellLine| l.points.last().copied().flatten().is_some_and(|p| slow_value(&p));
        let mut assigned: Vec<Option<usize>> = vec![None; n];
        let mut line_used = vec![false; n];
        let mut val_used = vec![false; vals.len()];
        // the slow block first: its lines continued optimally at the cost of their prediction
        // error relative to their own uncertainty, and their eigenvectors' MAC
        let slow_lines: Vec<usize> = (0..n).filter(|&li| slow_line(&self.lines[li])).collect();
        let slow_vals: Vec<usize> = (0..vals.len()).filter(|&vi| slow_value(&vals[vi])).collect();
        if let (Some(m), false) = (vecs.as_ref(), slow_lines.is_empty() || slow_vals.is_empty()) {
            // square: dummy rows or columns of cost 0 take what is left over (a line whose
            // value left the block, a value that entered it), for the value order below
            let ns = slow_lines.len().max(slow_vals.len());
            let mut cost = vec![0.0; ns * ns];
            for (a, &li) in slow_lines.iter().enumerate() {
                let l = &self.lines[li];
                let (p, u) = (predict(l), uncertainty(l));
                for (b, &vi) in slow_vals.iter().enumerate() {
                    let d = p.map_or(f64::INFINITY, |p| (p - z(&vals[vi])).norm());
                    let shape = match (&self.last[li], m.get(vi)) {
                        (Some(x), Some(y)) => 4.0 * (1.0 - mac(x, y)),
                        _ => 0.0,
                    };
                    cost[a * ns + b] = d / u + shape;
                }
            }
            if cost.iter().all(|c| c.is_finite()) {
                for (a, b) in crate::linalg::assignment::assignment(|r, c| cost[r * ns + c], ns).into_iter().enumerate() {
                    let (Some(&li), Some(&vi)) = (slow_lines.get(a), slow_vals.get(b)) else { continue };
                    assigned[li] = Some(vi);
                    line_used[li] = true;
                    val_used[vi] = true;
                }
            }
        }
        // the rest by value, nearest pairs first
        let mut cand: Vec<(f64, usize, usize)> = vec![];
        for (li, l) in self.lines.iter().enumerate().filter(|(li, _)| !line_used[*li]) {
            let p = predict(l);
            for (vi, v) in vals.iter().enumerate().filter(|(vi, _)| !val_used[*vi]) {
                cand.push((p.map_or(f64::INFINITY, |p| (p - z(v)).norm()), li, vi));
            }
        }
        cand.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        for (_, li, vi) in cand {
            if !line_used[li] && !val_used[vi] {
                line_used[li] = true;
                val_used[vi] = true;
                assigned[li] = Some(vi);
            }
        }
        for (li, a) in assigned.into_iter().enumerate() {
            self.lines[li].points.push(a.map(|vi| vals[vi]));
            if let Some(vi) = a {
                self.last[li] = vecs.as_ref().and_then(|m| m.get(vi).cloned());
            }
        }
    }
}

/// The slow block of [`Tracker`]: values of modulus at most this fraction of the speed's
/// largest `|λ|` (the balls' slow modes at low speed, `∝ Ω⁴` on the Jeffcott rotor).
pub const SLOW: f64 = 1e-3;

/// The rotor with its balls locked where the closed form at speed `omega` puts them (each ball a
/// point mass of the rotor) and, with `undamped`, no support damping: the rotor of the
/// critical speeds. The planar rotor's balls join its housing (`m2`, at the race centre) as one
/// mass at their common centre; the spatial rotor's become unbalance masses in their planes.
pub fn locked_rotor(rotor: &Rotor, omega: f64, undamped: bool) -> Result<Rotor> {
    lock(rotor, omega, undamped, false).map(|(r, _)| r)
}

/// Where the critical speeds lock the balls, on the field `f` of the point-mass rotor: the
/// closed-form balanced (semi-balanced) state ([`Rotor::guess`]), `false`; where none exists and
/// `partial` (the balls' capacity short of the unbalance; paper 004's eccentric race below its
/// semi-balanced speed) the placement the balls rest at with too little capacity, `true`: two
/// planes each on its share ([`Rotor::placed_guess`]), else each plane's balls bunched against
/// its share ([`Rotor::bunched_guess`]). A locked ball changes the rotor's critical speeds only
/// through its point mass (the mass, and the inertia `m R²` whose direction moves with `2ψ`), so
/// the placement moves them little (review 29: the critical speeds were "none" wherever the balls
/// could not balance).
/// The planar rotor's balls join its housing's mass, and their placement does not enter the
/// locked rotor's linearisation (`the_jeffcott_rotors_locked_critical_speed_is_sqrt_k_over_m_total`):
/// where neither closed form places them (an eccentric race on supports that differ by
/// direction, below its semi-balanced speed), they are locked opposite the race centre's offset.
fn lock_state(f: &Field, partial: bool) -> Option<(Vec<f64>, bool)> {
    let planar_any = || match f {
        Field::Planar(pf) if pf.rotor().n > 0 => {
            let p = pf.rotor();
            let nr = 2 + p.n;
            let mut x = vec![0.0; 2 * nr];
            x[2..nr].iter_mut().for_each(|v| *v = p.gamma + std::f64::consts::PI);
            Some(x)
        }
        _ => None,
    };
    Rotor::guess(f).map(|x| (x, false)).or_else(|| {
        if partial {
            Rotor::placed_guess(f).or_else(|| Rotor::bunched_guess(f)).or_else(planar_any).map(|x| (x, true))
        } else {
            None
        }
    })
}

/// [`locked_rotor`], with the balls at [`lock_state`]'s placement (`partial`: the partially
/// balanced one where no balanced state exists), and whether that placement is the partial one.
fn lock(rotor: &Rotor, omega: f64, undamped: bool, partial: bool) -> Result<(Rotor, bool)> {
    refuse_linear(rotor, "the locked rotor")?;
    // the closed form does not depend on the balls' contact and rolling physics (which have no
    // linearisation): it is taken on point-mass balls, which are locked anyway
    let f = point_mass_balls(rotor).field(omega)?;
    let state = lock_state(&f, partial);
    let is_partial = state.as_ref().is_some_and(|s| s.1);
    Ok((locked_at(rotor, &f, state.map(|s| s.0), undamped)?, is_partial))
}

/// [`lock`]'s rotor: the balls of `rotor` locked at the state `guess` of its point-mass field
/// `f` (`None`: no placement, an error).
fn locked_at(rotor: &Rotor, f: &Field, guess: Option<Vec<f64>>, undamped: bool) -> Result<Rotor> {
    Ok(match rotor {
        Rotor::Planar(p) => {
            let mut q = p.clone();
            if p.n > 0 {
                let x = guess.ok_or_else(|| no_balance(rotor))?;
                let e = Complex64::from_polar(p.s2, p.gamma);
                // each ball at its own mass (`planar.ball_masses`, else m3)
                let balls: Complex64 = x[2..2 + p.n].iter().enumerate().map(|(j, &psi)| (e + Complex64::from_polar(p.r, psi)) * p.ball_mass(j)).sum();
                let m = p.m2 + (0..p.n).map(|j| p.ball_mass(j)).sum::<f64>();
                let centre = (e * p.m2 + balls) / m;
                q.m2 = m;
                q.s2 = centre.norm();
                q.gamma = if centre.norm() > 0.0 { centre.arg() } else { 0.0 };
                q.n = 0;
                // no balls left: their per-ball lists go with them
                q.ball_masses = None;
                q.ball_drags = None;
            }
            if undamped {
                q.c = 0.0;
                q.c_y = q.c_y.map(|_| 0.0);
            }
            Rotor::Planar(q)
        }
        Rotor::Spatial(s) => {
            let mut q = s.clone();
            if s.balls() > 0 {
                let x = guess.ok_or_else(|| no_balance(rotor))?;
                let angles = crate::rotor_stability::ball_angles(f, &x);
                let mut psi = angles.iter();
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
        Rotor::Linear(_) => return Err(linear_refused("the locked rotor")),
    })
}

/// `rotor` with its balls as the papers' point masses (no contact, no rolling resistance).
fn point_mass_balls(rotor: &Rotor) -> Rotor {
    match rotor {
        Rotor::Planar(p) => {
            let mut q = p.clone();
            q.balls = Default::default();
            Rotor::Planar(q)
        }
        Rotor::Spatial(s) => {
            let mut q = s.clone();
            q.planes.iter_mut().for_each(|p| p.physics = Default::default());
            Rotor::Spatial(q)
        }
        Rotor::Linear(l) => {
            let mut q = l.clone();
            q.ball_physics.clear();
            Rotor::Linear(q)
        }
    }
}

/// Where Newton starts at a speed for the diagram with the balls free (and the search for its
/// crossings): under gravity across the axis with `n ≥ 3` balls in a plane the orbit with the
/// balls in two groups ([`Rotor::gravity_orbit_start`]), else the closed-form balanced
/// (semi-balanced) state ([`Rotor::guess`]); where none exists because the balls' capacity
/// falls short of the unbalance at every speed (the spatial and the linear rotor; the planar
/// rotor with its race centred), the partially balanced state, from the starts of
/// `stability`'s scan ([`Rotor::first_start`]: each plane's balls on its share, else bunched).
/// With an eccentric race, supports that differ by direction and `n ≥ 3` equal balls, the
/// two-group orbit of least growth rate ([`Rotor::planar_split_orbits`]) first.
/// Not for paper 004's eccentric race below its semi-balanced speed: there the diagram follows
/// the semi-balanced state only (a switch to the balls bunched there added crossings that
/// depend on the grid; tried and reverted in session 17), and a speed without it has no point.
fn free_start(rotor: &Rotor, f: &Field, opts: &NewtonOptions) -> Option<Vec<f64>> {
    let start = Rotor::gravity_orbit_start(f, opts).or_else(|| Rotor::guess(f));
    match rotor {
        // an eccentric race on supports that differ by direction with n >= 3 equal balls: the
        // two-group orbit of least growth rate, as `stability` and `map` analyse (review 25b:
        // from the closed form's member, no orbit there, the diagram followed an unstable 2+2
        // orbit of four balls where the scan analyses a stable 3+1 one); else the closed form
        Rotor::Planar(p) if p.s2 != 0.0 => Rotor::planar_split_orbits(f, opts).into_iter().next().map(|(x, _)| x).or(start),
        _ if start.is_some() => start,
        _ => Rotor::first_start(f, None),
    }
}

/// Why a speed of the diagram with the balls free has no state where no start was found.
fn no_state_free(rotor: &Rotor) -> Error {
    Error::invalid(
        "balancer",
        match rotor {
            // (audit 25's F2: `stability` and `map` analyse a state there; say why this does not)
            Rotor::Planar(p) if p.s2 != 0.0 => {
                "no semi-balanced state at this speed: the balls cannot supply the unbalance (|B| > n m3 r); with an eccentric race the diagram follows the semi-balanced state only (`stability` analyses the state the balls rest in here)"
            }
            _ => "no balanced state (the balls' capacity falls short of the unbalance) and no start for the partially balanced one",
        },
    )
}

fn no_balance(rotor: &Rotor) -> Error {
    Error::invalid(
        "balancer",
        match rotor {
            Rotor::Planar(_) => "no semi-balanced state to lock the balls in: the balls cannot supply the unbalance (|B| > n m3 r)",
            Rotor::Spatial(_) => "no balanced state to lock the balls in: the balls' capacity Σ m R of a plane is below the unbalance it must cancel",
            Rotor::Linear(r) => return crate::linear_rotor::partial::no_balanced_state(r, "no balanced state to lock the balls in"),
        },
    )
}

/// The words of [`LockedCriticalSpeeds::unlocked`] (`critical`'s table and the report): the
/// critical speeds lock the balls at the (semi-)balanced state, else at the partially balanced
/// placement ([`partial_words`]); a speed with neither is not searched.
pub fn unlocked_words(unlocked: usize, samples: usize) -> String {
    format!(
        "{unlocked} of {samples} speeds of the grid have neither a (semi-)balanced state nor a partially balanced placement to lock the balls at and were not searched; with the balls free, `autobal stability` analyses the state they rest in there"
    )
}

/// The words of [`LockedCriticalSpeeds::partial`]: the speeds where no balanced state exists
/// and the balls are locked at the partially balanced placement: spatial and linear, bunched
/// against the unbalance; planar, bunched on the line of the whirl ([`Rotor::bunched_guess`]),
/// on the unbalance's side below the critical speed (where they add to it), against it above.
pub fn partial_words(partial: usize, samples: usize) -> String {
    let at = if partial == samples { "at any speed of the grid".to_string() } else { format!("at {partial} of {samples} speeds of the grid") };
    format!(
        "no balanced state {at} (the balls cannot supply the unbalance): there the balls are locked where they rest with too little capacity, bunched (the partially balanced placement: spatial and linear, against the unbalance, each plane's against its share; planar, on the line of the rotor's whirl, on the unbalance's side below the critical speed, where they add to it, against it above); a locked ball moves the critical speeds only through its point mass"
    )
}

/// Two critical speeds closer than this, relative, are one ([`LockedCriticalSpeed::split`]):
/// the table prints 6 significant digits, so two speeds at least this far apart (a unit of the
/// sixth digit at most) always print apart, and no support stiffness is known to 1e-5. On
/// review 29's r1.toml the translational pair, split by the locked balls' inertia through a
/// coupling that nearly vanishes (`k_L z_L = k_R z_R` about the rotor's centre of mass), lay
/// 5.3e-8 apart: one speed, printed twice with multiplicity 1 each.
pub const SAME_SPEED: f64 = 1e-5;

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
    /// How many eigenvalues cross zero there: in turning axes 2 for the circular whirl of an
    /// axisymmetric rotor, 1 for one of the split pair of a rotor whose inertia differs by
    /// direction; in fixed axes 1 per (elliptical) whirl.
    pub multiplicity: usize,
    /// What moves most in the synchronous whirl (tilt at the radius of gyration).
    pub motion: Motion,
    /// Forward (the rotor's own sense: what an unbalance excites on supports equal in every
    /// direction) or backward (a backward mode whose frequency equals the speed: excited by an
    /// unbalance only through supports that differ by direction).
    pub whirl: Whirl,
    /// Where speeds closer than [`SAME_SPEED`] (relative) were merged into this one (their mean,
    /// with their multiplicities summed): the lowest and the highest; `None` for one speed.
    pub split: Option<[f64; 2]>,
    /// Whether the balls were locked at the partially balanced placement there (no balanced
    /// state: [`LockedCriticalSpeeds::partial`]).
    pub partial: bool,
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
    /// Speeds of the grid where the closed form has no balanced state to lock the balls in,
    /// and none for the partially balanced placement ([`LockedCriticalSpeeds::partial`]):
    /// not searched.
    pub unlocked: usize,
    /// Speeds of the grid without a balanced state (too little capacity; paper 004's eccentric
    /// race at low speed), where the balls are locked at the partially balanced placement
    /// instead ([`partial_words`]).
    pub partial: usize,
    /// The balls' locked angles (rad, all planes in order) at the first speed searched: with
    /// `n ≥ 3` balls in a plane the balanced states form a family, and the critical speeds
    /// depend on the member (its inertia), which these angles name (the closed form's).
    pub ball_angles: Vec<f64>,
}

/// The matrix whose eigenvalues change sign at the critical speeds, for the locked undamped
/// rotor linearised about the centred rotor: `(matrix, dim, copies, field)`. Turning axes, where
/// the Jacobian is constant there: `A(Ω)`, `m × m`, each eigenvalue once. Otherwise (supports that
/// differ by direction) fixed axes, where the balanced locked rotor's linearisation is constant:
/// `Q(Ω) = −A_f − iΩ B_f − Ω² I` (`λ = iΩ` an eigenvalue of `[[0, I], [A_f, B_f]]` iff `Q` is
/// singular; `Q = M⁻¹ (K − Ω² M + iΩ² G)`, Hermitian up to `M`, real eigenvalues) as its real
/// `2m × 2m` embedding `[[Re Q, −Im Q], [Im Q, Re Q]]`, each eigenvalue twice.
fn stiffness_block(rotor: &Rotor, omega: f64) -> Result<(Vec<f64>, usize, usize, Field)> {
    stiffness_block_of(&lock(rotor, omega, true, true)?.0, omega)
}

/// [`stiffness_block`] of the rotor already `locked` (undamped, its balls at their placement).
fn stiffness_block_of(locked: &Rotor, omega: f64) -> Result<(Vec<f64>, usize, usize, Field)> {
    let f = locked.field(omega)?;
    let n = f.dim();
    let m = n / 2;
    let x = vec![0.0; n];
    let mut j = vec![0.0; n * n];
    f.jacobian(0.0, &x, &mut j);
    // the field is q' = q̇, q̇' = A q + B q̇
    for i in 0..m {
        for k in 0..n {
            let want = if k == m + i { 1.0 } else { 0.0 };
            if j[i * n + k] != want {
                return Err(Error::invalid("critical", "the model's state is not (positions, their rates): no stiffness block"));
            }
        }
    }
    let big = j.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let rotating = match f.period() {
        None => false,
        Some(t) => {
            let mut j4 = vec![0.0; n * n];
            f.jacobian(0.25 * t, &x, &mut j4);
            j.iter().zip(&j4).any(|(a, b)| (a - b).abs() > 1e-9 * big)
        }
    };
    if !rotating {
        let a: Vec<f64> = (0..m).flat_map(|i| j[(m + i) * n..(m + i) * n + m].to_vec()).collect();
        return Ok((a, m, 1, f));
    }
    // fixed axes: constant for the balanced locked rotor (checked at t = 0 and T/4)
    let t4 = 0.25 * f.period().unwrap_or(0.0);
    let jf0 = fixed_axes_jacobian(&f, omega, 0.0)?;
    let jf4 = fixed_axes_jacobian(&f, omega, t4)?;
    let bigf = jf0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if jf0.iter().zip(&jf4).any(|(a, b)| (a - b).abs() > 1e-9 * bigf) {
        return Err(Error::NoLinearisation {
            reason: "the locked rotor's linearisation is periodic in both turning and fixed axes (supports that differ by direction, and an inertia that differs by direction: the locked balls and unbalance masses); critical speeds are not defined by one frequency there and are not located; `autobal campbell` shows the Floquet exponents".into(),
        });
    }
    let mut q = vec![0.0; 4 * m * m];
    let d = 2 * m;
    for r in 0..m {
        for c in 0..m {
            let re = -jf0[(m + r) * n + c] - if r == c { omega * omega } else { 0.0 };
            let im = -omega * jf0[(m + r) * n + m + c];
            q[r * d + c] = re;
            q[r * d + m + c] = -im;
            q[(m + r) * d + c] = im;
            q[(m + r) * d + m + c] = re;
        }
    }
    Ok((q, d, 2, f))
}

/// The Jacobian of `f` (a rotor without balls: every coordinate in rotating pairs `(0, 1)` and,
/// with the tilt free, `(2, 3)`) at the centred rotor and time `t`, in fixed axes:
/// `z = T(t) x` with positions `p_f = R p` and rates `v_f = R (v + Ω J p)` (`R` the rotation by
/// `Ωt`, `J` by a right angle), so `J_f = (Ṫ + T J(t)) T⁻¹`.
fn fixed_axes_jacobian(f: &Field, omega: f64, t: f64) -> Result<Vec<f64>> {
    let n = f.dim();
    let m = n / 2;
    if !m.is_multiple_of(2) {
        return Err(Error::invalid("critical", "the locked rotor's coordinates do not come in pairs"));
    }
    // T is linear in (cos Ωt, sin Ωt): Ṫ = Ω T(−sin, cos)
    let transform = |c: f64, s: f64| {
        let mut tm = vec![0.0; n * n];
        for p in (0..m).step_by(2) {
            let (a, b) = (p, p + 1);
            tm[a * n + a] = c;
            tm[a * n + b] = -s;
            tm[b * n + a] = s;
            tm[b * n + b] = c;
            let (va, vb) = (m + a, m + b);
            // v_f,a = c (v_a − Ω p_b) − s (v_b + Ω p_a); v_f,b = s (v_a − Ω p_b) + c (v_b + Ω p_a)
            tm[va * n + va] = c;
            tm[va * n + vb] = -s;
            tm[va * n + b] = -c * omega;
            tm[va * n + a] = -s * omega;
            tm[vb * n + va] = s;
            tm[vb * n + vb] = c;
            tm[vb * n + b] = -s * omega;
            tm[vb * n + a] = c * omega;
        }
        tm
    };
    let (s, c) = (omega * t).sin_cos();
    let tm = transform(c, s);
    let td: Vec<f64> = transform(-s, c).iter().map(|v| v * omega).collect();
    let x = vec![0.0; n];
    let mut j = vec![0.0; n * n];
    f.jacobian(t, &x, &mut j);
    // X = Ṫ + T J; J_f = X T⁻¹, i.e. Tᵀ J_fᵀ = Xᵀ
    let mut xm = td;
    for r in 0..n {
        for k in 0..n {
            let mut acc = 0.0;
            for l in 0..n {
                acc += tm[r * n + l] * j[l * n + k];
            }
            xm[r * n + k] += acc;
        }
    }
    let tt: Vec<f64> = (0..n * n).map(|i| tm[(i % n) * n + i / n]).collect();
    let lu = crate::ode::lu::Lu::factored(tt, n).ok_or_else(|| Error::invalid("critical", "singular axes transformation"))?;
    let mut jf = vec![0.0; n * n];
    let mut col = vec![0.0; n];
    for r in 0..n {
        // row r of J_f is column r of J_fᵀ = T⁻ᵀ (row r of X)ᵀ
        col.copy_from_slice(&xm[r * n..(r + 1) * n]);
        lu.solve(&mut col);
        jf[r * n..(r + 1) * n].copy_from_slice(&col);
    }
    Ok(jf)
}

/// The number of eigenvalues of `A(Ω)` with a positive real part, and whether the balls are
/// locked at the partially balanced placement ([`lock_state`]); `None` where there is no
/// placement to lock the balls in.
fn positive_count(rotor: &Rotor, omega: f64) -> Result<Option<(usize, bool)>> {
    let has_balls = match rotor {
        Rotor::Planar(p) => p.n > 0,
        Rotor::Spatial(s) => s.balls() > 0,
        Rotor::Linear(l) => l.total_balls() > 0,
    };
    // the placement found once: the point-mass field and its closed form are what `lock` builds
    let (locked, partial) = if has_balls {
        let f = point_mass_balls(rotor).field(omega)?;
        let Some((x, partial)) = lock_state(&f, true) else { return Ok(None) };
        (locked_at(rotor, &f, Some(x), true)?, partial)
    } else {
        (lock(rotor, omega, true, true)?.0, false)
    };
    let (a, d, copies, _) = stiffness_block_of(&locked, omega)?;
    let ev = eigenvalues(&a, d).map_err(|e| Error::invalid("critical", format!("the eigenvalues of the stiffness block did not converge: {e}")))?;
    Ok(Some((ev.iter().filter(|z| z.re > 0.0).count().div_ceil(copies), partial)))
}

/// The critical speeds of `rotor` with its balls locked at balance and no damping, in
/// `(0, omega_max]` on a grid of `samples` speeds (module docs): where the count of positive
/// eigenvalues of the turning-axes stiffness block `A(Ω)` changes, bisected to `1e-12`
/// (several crossings in one grid step are found one after the other where the count moves
/// one way; a crossing and its return within one step cancel and are missed).
pub fn locked_critical_speeds(rotor: &Rotor, omega_max: f64, samples: usize) -> Result<LockedCriticalSpeeds> {
    refuse_linear(rotor, "the locked critical speeds")?;
    let speeds = crate::rotor_stability::speed_grid(omega_max, samples)?;
    let found: Vec<Option<(usize, bool)>> = speeds.iter().map(|&w| positive_count(rotor, w)).collect::<Result<_>>()?;
    let counts: Vec<Option<usize>> = found.iter().map(|c| c.map(|c| c.0)).collect();
    let mut out: Vec<LockedCriticalSpeed> = vec![];
    for k in 0..speeds.len() - 1 {
        let (Some(c0), Some(c1)) = (counts[k], counts[k + 1]) else { continue };
        let partial = found[k].is_some_and(|c| c.1) || found[k + 1].is_some_and(|c| c.1);
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
                match positive_count(rotor, mid)?.map(|c| c.0) {
                    Some(c) if c == c_lo => lo = mid,
                    Some(c) => {
                        hi = mid;
                        c_hi = c;
                    }
                    None => break,
                }
            }
            let w = 0.5 * (lo + hi);
            let (motion, whirl) = motion_at(rotor, w)?;
            out.push(LockedCriticalSpeed { omega: w, multiplicity: c_lo.abs_diff(c_hi), motion, whirl, split: None, partial });
            if hi >= speeds[k + 1] {
                break;
            }
            start = hi;
            c_lo = c_hi;
        }
    }
    let gaps = counts.iter().filter(|c| c.is_none()).count();
    let partial = found.iter().filter(|c| c.is_some_and(|c| c.1)).count();
    // the angles of the first speed with a balanced placement, else of the first with any
    let first = found.iter().position(|c| c.is_some_and(|c| !c.1)).or_else(|| found.iter().position(|c| c.is_some()));
    let ball_angles = first
        .and_then(|k| {
            let f = point_mass_balls(rotor).field(speeds[k]).ok()?;
            let (x, _) = lock_state(&f, true)?;
            Some(crate::rotor_stability::ball_angles(&f, &x))
        })
        .unwrap_or_default();
    Ok(LockedCriticalSpeeds { speeds: merge_same_speeds(out), omega_max, samples: speeds.len(), unlocked: gaps, partial, ball_angles })
}

/// `speeds` (ascending) with each run of speeds of one motion and whirl closer than
/// [`SAME_SPEED`] (relative, from the run's lowest) merged into one: their mean, the sum of
/// their multiplicities, [`LockedCriticalSpeed::split`] their lowest and highest.
fn merge_same_speeds(speeds: Vec<LockedCriticalSpeed>) -> Vec<LockedCriticalSpeed> {
    let mut out: Vec<(LockedCriticalSpeed, Vec<f64>)> = vec![];
    for s in speeds {
        if let Some((last, members)) = out.last_mut() {
            let lo = members[0];
            if last.motion == s.motion && last.whirl == s.whirl && s.omega - lo <= SAME_SPEED * s.omega {
                members.push(s.omega);
                last.multiplicity += s.multiplicity;
                last.partial |= s.partial;
                continue;
            }
        }
        out.push((s, vec![s.omega]));
    }
    out.into_iter()
        .map(|(mut s, members)| {
            if members.len() > 1 {
                s.omega = members.iter().sum::<f64>() / members.len() as f64;
                s.split = Some([members[0], members[members.len() - 1]]);
            }
            s
        })
        .collect()
}

/// What moves most in the synchronous whirl at a critical speed `w`, and its sense: from the
/// null vector of `A` (turning axes: a whirl standing still there is forward) or of `Q` (fixed
/// axes: `u e^{iΩt}`, forward where `Σ|u_a + i u_b|² > Σ|u_a − i u_b|²` over the pairs).
fn motion_at(rotor: &Rotor, w: f64) -> Result<(Motion, Whirl)> {
    let (a, d, copies, f) = stiffness_block(rotor, w)?;
    let ev = eigenvalues(&a, d).map_err(|e| Error::invalid("critical", e.to_string()))?;
    let zero = ev.iter().copied().min_by(|p, q| p.norm().total_cmp(&q.norm())).unwrap_or_default();
    let v = mode(&a, d, zero);
    let m = d / copies;
    // a real null vector; for Q's embedding [Re u; Im u]
    let re: Vec<f64> = v.iter().map(|z| z.re).collect();
    let real: Vec<f64> = if re.iter().any(|x| *x != 0.0) { re } else { v.iter().map(|z| z.im).collect() };
    let u: Vec<Complex64> = (0..m).map(|i| if copies == 2 { Complex64::new(real[i], real[m + i]) } else { Complex64::new(real[i], 0.0) }).collect();
    let gyration = match rotor {
        Rotor::Spatial(r) => (r.rotor.equatorial_moment / r.total_mass()).sqrt(),
        Rotor::Planar(_) | Rotor::Linear(_) => 0.0,
    };
    let motion = match &f {
        Field::Spatial(_) if m >= 4 => {
            let tr = u[0].norm().max(u[1].norm());
            let tilt = gyration * u[2].norm().max(u[3].norm());
            if tilt > tr {
                Motion::Tilt
            } else {
                Motion::Translation
            }
        }
        _ => Motion::Translation,
    };
    let whirl = if copies == 1 {
        Whirl::Forward
    } else {
        let i = Complex64::new(0.0, 1.0);
        let (mut fw, mut bw) = (0.0, 0.0);
        for (p, weight) in [(0, 1.0), (2, gyration)] {
            if p + 1 < m {
                fw += weight * weight * (u[p] + i * u[p + 1]).norm_sqr();
                bw += weight * weight * (u[p] - i * u[p + 1]).norm_sqr();
            }
        }
        if fw >= bw {
            Whirl::Forward
        } else {
            Whirl::Backward
        }
    };
    Ok((motion, whirl))
}

/// The stationary state of `rotor` at `omega` from its closed form (for tests and figures).
pub fn stationary_at(rotor: &Rotor, omega: f64) -> Result<(Field, StationaryState)> {
    let f = rotor.field(omega)?;
    let guess = Rotor::guess(&f).unwrap_or_else(|| vec![0.0; f.dim()]);
    let s = stationary(&f, &guess, &newton_options(f.period().is_some())).map_err(|e| Error::invalid("speeds", e.to_string()))?;
    Ok((f, s))
}

/// The stationary state of the rotor the diagram is of (`rotor` itself with its balls free, or
/// [`locked_rotor`] at `omega`, damping kept, with them locked) and its spectrum at `omega`
/// ([`spectrum_at`]); `near` is a state to start Newton from where the closed form fails (the
/// previous speed's), `hint` that state's monodromy matrix.
fn state_and_spectrum(
    rotor: &Rotor,
    balls: Balls,
    omega: f64,
    near: Option<&StationaryState>,
) -> std::result::Result<(StationaryState, Vec<CampbellPoint>), String> {
    let (of, f, s) = state_of(rotor, balls, omega, near)?;
    let p = spectrum_at(&of, &f, omega, &s).map_err(reason)?;
    Ok((s, p))
}

/// The one-line reason of an error, for [`RotorCampbell::failures`].
fn reason(e: Error) -> String {
    match e {
        Error::InvalidParameter { reason, .. } => reason,
        e => e.to_string(),
    }
}

/// The rotor the diagram is of at `omega` ([`state_and_spectrum`]), its field and stationary
/// state.
fn state_of(rotor: &Rotor, balls: Balls, omega: f64, near: Option<&StationaryState>) -> std::result::Result<(Rotor, Field, StationaryState), String> {
    let of = match balls {
        Balls::Free => rotor.clone(),
        Balls::Locked => locked_rotor(rotor, omega, false).map_err(reason)?,
    };
    let f = of.field(omega).map_err(reason)?;
    let opts = newton_options(f.period().is_some());
    // under gravity with n >= 3 balls in a plane the orbit has the balls in two groups (the
    // family's arc member is no orbit: Rotor::gravity_orbit_start), or there is none
    if let (Balls::Free, Some(why)) = (balls, f.gravity_circulation()) {
        return Err(why);
    }
    let guess = match balls {
        Balls::Free => free_start(rotor, &f, &opts),
        // the locked rotor has no balls left: its balanced state is the centred rotor (or, with
        // gravity, its sag), reached by Newton from rest
        Balls::Locked => Rotor::guess(&f).or_else(|| Some(vec![0.0; f.dim()])),
    };
    let hint = near.and_then(|p| p.monodromy.clone());
    let mut result = Err(reason(match balls {
        Balls::Free => no_state_free(rotor),
        Balls::Locked => no_balance(rotor),
    }));
    for start in [guess, near.map(|p| p.x.clone())].into_iter().flatten() {
        match stationary_near(&f, &start, hint.as_deref(), &opts) {
            Ok(s) => {
                result = Ok(s);
                break;
            }
            Err(e) => result = Err(e.to_string()),
        }
    }
    let s = result?;
    Ok((of, f, s))
}

/// The Campbell diagram of `rotor` with its balls **locked** (`--balls locked`): at each speed
/// the balls are fixed where the closed form puts them at that speed and become point masses of
/// the rotor ([`locked_rotor`], damping kept), and the spectrum is that of the locked rotor's
/// stationary state (the centred rotor, or its sag and once-per-revolution motion under
/// gravity or on supports that differ by direction: Floquet exponents, [`FLOQUET_BRANCH`]),
/// tracked into lines as [`campbell_over_speed`] does. With one plane, supports equal in every
/// direction and no gravity this is paper 000's 8-state locked model (eq (6) without the ball
/// rows, the exact inertia tensor of the locked composite rotor). A speed without a balanced
/// state to lock the balls in (too little capacity) has no point, with the reason in
/// [`RotorCampbell::failures`].
pub fn campbell_locked(rotor: &Rotor, speeds: &[f64]) -> Result<RotorCampbell> {
    if speeds.is_empty() {
        return Err(Error::invalid("speeds", "no speed to analyse"));
    }
    refuse_linear(rotor, "the Campbell diagram with locked balls")?;
    if let Some(w) = speeds.iter().find(|w| !(w.is_finite() && **w != 0.0)) {
        return Err(Error::invalid("speeds", format!("{w} is not a finite non-zero speed")));
    }
    // the kind: the locked rotor's field turns with the rotor where the supports differ by
    // direction or gravity acts across the axis (whether or not the balls can be locked)
    let kind = match locked_rotor(rotor, speeds[0], false) {
        Ok(l) => l.field(speeds[0])?.period(),
        Err(_) => rotor.field(speeds[0])?.period(),
    }
    .map_or(Kind::Equilibrium, |_| Kind::PeriodicOrbit);
    let floor = below_floor_of(rotor, kind, speeds)?;
    let mut previous: Option<StationaryState> = None;
    let mut per_speed = Vec::with_capacity(speeds.len());
    let mut failures = Vec::with_capacity(speeds.len());
    let mut analysed = Vec::with_capacity(speeds.len());
    for &w in speeds {
        let not = floor(w);
        analysed.push(not.is_none());
        if let Some(why) = not {
            per_speed.push(None);
            failures.push(Some(why));
            continue;
        }
        match state_and_spectrum(rotor, Balls::Locked, w, previous.as_ref()) {
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
    let states = vec![None; speeds.len()];
    Ok(RotorCampbell { model: rotor.model_name(), kind, omega: speeds.to_vec(), lines: track(&per_speed), failures, analysed, states })
}

/// `|Im λ|` at most this times `max(1, |λ|)` counts as a real eigenvalue (QR round-off).
const REAL_TOL: f64 = 1e-9;

/// The fixed-axes view of a general-route Campbell diagram `c` of `rotor` (computed with
/// `balls`), as [`crate::spatial::campbell::fixed_axes`] gives it for paper 000's 12-state
/// model and with its types: one continuous curve of natural frequency `|f|` in fixed axes per
/// pair of conjugate lines (the kept line of each pair found by 2-colouring the graph of lines
/// that are conjugate somewhere; structural zeros and speeds without a state left out), the
/// followed component `f = Ω ± ν` the dominant one unless the other continues the curve better
/// by more than two speed steps, each point's `σ` and `ν` its own line's (where the line is
/// real, the largest real eigenvalue left out of its conjugacy component is beside it as
/// `paired_re`, `paired_line`), `δ = −2π σ/|f|` per fixed-axes cycle, and the crossings with
/// the excitation lines `h Ω` for each `h` of `harmonics` by the 12-state route's rule and
/// search ([`crate::spatial::campbell`]: a circular component's frequency meets `hΩ`, `ν̂ = 0`
/// for the forward `1×`, bisected to `1e-13` relative on the stationary state's spectrum
/// recomputed at each trial speed, the ends on the real axis on the count of real
/// eigenvalues; the drawn curves are not used, and the search refines the drawn grid on that
/// spectrum, so its crossings and mode numbers do not depend on the grid down to 1e-6
/// relative). Modes are numbered by the 12-state route's rule
/// ([`crate::spatial::campbell`], mode numbers): the rank of the undamped natural frequency at
/// `0.001 ω_n` ([`Rotor::natural_frequency`]) on the stationary state's spectrum, a conjugate
/// pair or two real eigenvalues counted once; a periodic orbit's at the first speed (where
/// its spectrum is known). The curves are in the order of their numbers.
///
/// **Periodic orbits**: the Floquet exponents' imaginary parts are defined modulo `Ω`, so
/// `|f| = hΩ` for one harmonic is `|f| = h'Ω` on another branch: crossings are not defined, and
/// `critical_speeds` is empty (the commands say so); the curves are drawn on the branch of
/// [`FLOQUET_BRANCH`], each point at its dominant component (the point's `fixed_frequency`):
/// the other component of a branch is an alias of ~0 share, which the continuity rule above
/// would otherwise follow up a line of slope ~2 (to 4800 rad/s on the two-plane example).
pub fn fixed_view(rotor: &Rotor, balls: Balls, c: &RotorCampbell, harmonics: &[u32]) -> Result<FixedCampbell> {
    fixed_view_with(rotor, balls, c, harmonics, &crate::control::Control::none())
}

/// [`fixed_view`] under `control`: the search for the critical speeds asks it before each
/// stationary state's spectrum and stops with its error (`Error::Interrupted` for Ctrl-C).
pub fn fixed_view_with(rotor: &Rotor, balls: Balls, c: &RotorCampbell, harmonics: &[u32], control: &crate::control::Control) -> Result<FixedCampbell> {
    if let Some(h) = harmonics.iter().find(|&&h| h == 0) {
        return Err(Error::invalid("harmonics", format!("must be positive integers, got {h}")));
    }
    let n = c.omega.len();
    if c.lines.iter().any(|l| l.points.len() != n) || c.failures.len() != n {
        return Err(Error::invalid("campbell", "every line needs one entry per speed"));
    }
    let nl = c.lines.len();
    let at = |i: usize, k: usize| c.lines[i].points[k].filter(|p| !p.structural);
    let z = |p: &CampbellPoint| Complex64::new(p.re, p.im);
    let is_real = |p: &CampbellPoint| p.im.abs() <= REAL_TOL * z(p).norm().max(1.0);
    let conj = |i: usize, j: usize, k: usize| match (at(i, k), at(j, k)) {
        (Some(a), Some(b)) if !is_real(&a) && !is_real(&b) => (z(&b) - z(&a).conj()).norm() <= 1e-7 * (1.0 + z(&a).norm()),
        _ => false,
    };
    // the kept colour of each component: the one with more points of Im λ ≥ 0
    let (component, dropped) = crate::spatial::campbell::keep_one_of_each_pair(
        nl,
        |i, j| (0..n).any(|k| conj(i, j, k)),
        |l| (0..n).filter_map(|k| at(l, k)).filter(|p| p.im >= 0.0).count() as i64,
    );
    // the scale of each speed's spectrum (the values whose real part is known), for the log
    // decrement's resolution
    let scales: Vec<f64> = (0..n).map(|k| spectrum_scale((0..nl).filter_map(|i| at(i, k)).filter(|p| p.decay_at_least.is_none()).map(|p| z(&p)))).collect();
    // (curve, the speed index of each of its points)
    let mut curves: Vec<(FixedCurve, Vec<usize>)> = vec![];
    for (li, &left_out) in dropped.iter().enumerate() {
        if left_out {
            continue;
        }
        let mut pts: Vec<FixedPoint> = vec![];
        let mut idx = vec![];
        for k in 0..n {
            let Some(m) = at(li, k) else { continue };
            let w = c.omega[k];
            let cand = [(w + m.im, m.forward_share), (w - m.im, 1.0 - m.forward_share)];
            let dominant = if m.forward_share >= 0.5 { 0 } else { 1 };
            // a Floquet point's other component on its branch is an alias the motion hardly has
            // (its share ~0: FLOQUET_BRANCH): the curve follows the dominant one
            let pick = match pts.len() {
                _ if c.kind == Kind::PeriodicOrbit => dominant,
                0 => dominant,
                len => {
                    let prev = pts[len - 1].fixed_frequency;
                    let pred = if len >= 2 {
                        let (w1, w2) = (pts[len - 2].omega, pts[len - 1].omega);
                        prev + (prev - pts[len - 2].fixed_frequency) * (w - w2) / (w2 - w1).max(1e-300)
                    } else {
                        prev
                    };
                    let h = (w - pts[len - 1].omega).abs();
                    let d = |i: usize| (cand[i].0 - pred).abs();
                    if d(dominant) > d(1 - dominant) + 2.0 * h {
                        1 - dominant
                    } else {
                        dominant
                    }
                }
            };
            let (f, share) = cand[pick];
            // the line's own σ (session 29: before, a real point carried the largest of the
            // real eigenvalues left out of its component, another line's value under this
            // line's number: j.toml at 25 rad/s, line 4 with line 7's 0.275); that largest
            // one is given beside it as `paired_re`, `paired_line`
            let sigma = m.re;
            let mut paired: Option<(f64, usize)> = None;
            if is_real(&m) {
                for j in (0..nl).filter(|&j| dropped[j] && component[j] == component[li]) {
                    if let Some(p) = at(j, k).filter(|p| is_real(p)) {
                        if paired.is_none_or(|(r, _)| p.re > r) {
                            paired = Some((p.re, j));
                        }
                    }
                }
            }
            let whirl = if f > 0.0 {
                FixedWhirl::Forward
            } else if f < 0.0 {
                FixedWhirl::Backward
            } else {
                pts.last().map_or(FixedWhirl::Forward, |p| p.whirl)
            };
            pts.push(FixedPoint {
                omega: w,
                frequency: f.abs(),
                fixed_frequency: f,
                whirl,
                re: sigma,
                nu: m.im,
                log_decrement: log_decrement(sigma, f, scales[k]).filter(|_| m.decay_at_least.is_none()),
                share,
                decay_at_least: m.decay_at_least,
                paired_re: paired.map(|(r, _)| r),
                paired_line: paired.map(|(_, j)| j),
            });
            idx.push(k);
        }
        if !pts.is_empty() {
            curves.push((FixedCurve { line: li, mode: 0, points: pts }, idx));
        }
    }
    let lines = crate::spatial::campbell::Lines {
        omega: &c.omega,
        z: (0..nl).map(|i| (0..n).map(|k| at(i, k).map(|p| z(&p))).collect()).collect(),
        known: c.failures.iter().map(|f| f.is_none()).collect(),
    };
    let spec = StateSpectrum { rotor, balls, last: std::cell::RefCell::new(None) };
    // the mode numbers of the 12-state route's rule (spatial::campbell::mode_numbers): at
    // 0.001 ω_n on the stationary state's spectrum; a periodic orbit's Floquet exponents, at
    // the first speed
    let w_ref = crate::spatial::campbell::MODE_REFERENCE * rotor.natural_frequency();
    let (modes, modes_at_first_speed) = match c.kind {
        Kind::Equilibrium => crate::spatial::campbell::mode_numbers(&lines, Some(&spec), w_ref, control)?,
        Kind::PeriodicOrbit => crate::spatial::campbell::mode_numbers::<StateSpectrum>(&lines, None, w_ref, control)?,
    };
    // in the order of their numbers, then of the undamped natural frequency at the first point
    // (ties broken by |ν|, Re λ, line)
    let zk = |i: usize, k: usize| at(i, k).map(|p| z(&p));
    let key: Vec<f64> = curves.iter().map(|cv| crate::spatial::campbell::natural_key(zk, nl, cv.0.line, cv.1[0], &component, &dropped)).collect();
    let curves: Vec<FixedCurve> = crate::spatial::campbell::number_curves(curves.into_iter().map(|c| c.0).collect(), &modes, &key);
    let crit = if c.kind == Kind::Equilibrium { crate::spatial::campbell::crossings(&lines, &spec, harmonics, &curves, &modes, control)? } else { vec![] };
    Ok(FixedCampbell { omega: c.omega.clone(), curves, critical_speeds: crit, harmonics: harmonics.to_vec(), modes_at_first_speed, line_modes: modes })
}

/// The spectrum of the stationary state at a trial speed, for the search for critical speeds
/// shared with the 12-state route ([`crate::spatial::campbell`]): the state found from the
/// closed form at that speed ([`state_and_spectrum`]), its eigenvalues without the structural
/// zeros; the last speed's kept (the share at a crossing asks for the speed just located).
struct StateSpectrum<'a> {
    rotor: &'a Rotor,
    balls: Balls,
    last: std::cell::RefCell<Option<(f64, Vec<CampbellPoint>)>>,
}

impl StateSpectrum<'_> {
    fn points(&self, w: f64) -> Result<Vec<CampbellPoint>> {
        if let Some((x, p)) = self.last.borrow().as_ref() {
            if *x == w {
                return Ok(p.clone());
            }
        }
        let (_, pts) = state_and_spectrum(self.rotor, self.balls, w, None)
            .map_err(|e| Error::invalid("campbell", format!("no stationary state at {w} to locate a critical speed: {e}")))?;
        let pts: Vec<CampbellPoint> = pts.into_iter().filter(|p| !p.structural).collect();
        *self.last.borrow_mut() = Some((w, pts.clone()));
        Ok(pts)
    }
}

impl crate::spatial::campbell::Spectrum for StateSpectrum<'_> {
    fn eigenvalues(&self, w: f64) -> Result<Vec<Complex64>> {
        if let Some((x, p)) = self.last.borrow().as_ref() {
            if *x == w {
                return Ok(p.iter().map(|p| Complex64::new(p.re, p.im)).collect());
            }
        }
        // the eigenvalues alone (no eigenvectors): the searches ask for many speeds
        let no_state = |e: String| Error::invalid("campbell", format!("no stationary state at {w} to locate a critical speed: {e}"));
        let (_, f, s) = state_of(self.rotor, self.balls, w, None).map_err(no_state)?;
        let st = stability(&f, &s).map_err(|e| no_state(e.to_string()))?;
        Ok(st.spectrum.iter().map(|e| e.complex()).collect())
    }

    fn shares(&self, w: f64, lam: Complex64) -> Result<(f64, f64)> {
        let pts = self.points(w)?;
        let up = |p: &CampbellPoint| Complex64::new(p.re, p.im.abs());
        let p = pts
            .iter()
            .min_by(|a, b| (up(a) - lam).norm().total_cmp(&(up(b) - lam).norm()))
            .ok_or_else(|| Error::invalid("campbell", format!("no eigenvalue at {w}")))?;
        // a mode of the balls alone moves no rotor coordinate: no whirl component at all
        if p.whirl == Whirl::None && p.fixed_frequency != 0.0 {
            return Ok((0.0, 0.0));
        }
        // the conjugate's forward component is the pair's Ω − ν̂ one
        let s = p.forward_share;
        Ok(if p.im >= 0.0 { (s, 1.0 - s) } else { (1.0 - s, s) })
    }
}

#[cfg(test)]
mod tests_18b {
    use super::*;

    /// The round-off bound of the multipliers ([`MONODROMY_RTOL`]) assumes the orbits were
    /// shot at that `rtol`: the general route's Newton options (one function since session 32)
    /// must integrate at it, and the equilibria keep the defaults.
    #[test]
    fn the_general_routes_shooting_integrates_at_the_monodromy_rtol() {
        assert_eq!(newton_options(true).rtol, MONODROMY_RTOL);
        assert_eq!(newton_options(true).max_iterations, 20);
        assert_eq!(newton_options(false).rtol, NewtonOptions::default().rtol);
    }

    /// The isotropic undamped 2-DOF rotor in turning axes, `ẍ − 2Ωẏ + (ω² − Ω²) x = 0`,
    /// `ÿ + 2Ωẋ + (ω² − Ω²) y = 0` (state `[x, y, ẋ, ẏ]`). By hand: `z = x + iy` obeys
    /// `z̈ + 2iΩż + (ω² − Ω²) z = 0`, so `λ = i(ω − Ω)` has `y = −ix`: `x − iy = 0`, a pure
    /// forward whirl (share 1 exactly), and its neighbour `i(ω + Ω)` (the backward whirl's
    /// conjugate) is only `2Ω` away. With `ω = 1e6`, `Ω = 12.5` the matrix spans 1 to 1e12, and
    /// the raw inverse iteration ([`mode`]: pivots below `ε max|a_ij|` replaced) read 0.79 at
    /// `ω = 1e6` and 0.50 at `1e7` (share18); balanced, the error is `ε ω / 2Ω` ~ 1e-8 at most.
    #[test]
    fn a_pure_forward_whirl_reads_share_one_at_any_scale() {
        for w in [1e3, 1e5, 1e6, 1e7] {
            let o: f64 = 12.5;
            let k = w * w - o * o;
            let a = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -k, 0.0, 0.0, 2.0 * o, 0.0, -k, -2.0 * o, 0.0];
            let v = balanced_mode(&a, 4, Complex64::new(0.0, w - o));
            let i = Complex64::new(0.0, 1.0);
            let (f, b) = ((v[0] + i * v[1]).norm_sqr(), (v[0] - i * v[1]).norm_sqr());
            // ε ω / 2Ω ≤ 1e-7 at ω = 1e7; 1e-6 leaves room for the eigenvalue's own error
            assert!(b / (f + b) < 1e-6, "ω = {w}: share {}", f / (f + b));
        }
    }
}
