//! The planar rotor at a constant speed as a [`VectorField`] for the model-agnostic stationary
//! and stability analysis ([`crate::analysis`]).
//!
//! Under a constant speed `Ω` the rotor angle `θ = Ω t` and its rate are prescribed, so the
//! state is reduced to `x = (ξ, η, ψ_1..n, ξ̇, η̇, ψ̇_1..n)` (`u = ξ + iη` the shaft point C in
//! rotor axes, `ψ_j` the balls' angles from CG). The right-hand side is [`Equations`] under
//! `Drive::Speed` (which does not depend on `θ`); the Jacobian is exact: with the residual
//! `R = F − M q̈` differentiated by forward-mode dual numbers (the arrow linearisation of the
//! implicit integrator, [`ArrowSystem::linearize`]), `∂q̈/∂q = M⁻¹ ∂R/∂q` and
//! `∂q̈/∂q̇ = M⁻¹ ∂R/∂q̇` (`M` the mass matrix; `R(q, q̇, q̈(q, q̇)) = 0`). The supports are
//! isotropic and there is no gravity, so the field is autonomous (`period() = None`) and the
//! stationary states are equilibria.
//!
//! The semi-balanced state (race centre E on the axis, `u = −s2 e^{iγ}`, balls at rest
//! supplying `B`, [`crate::planar::stationary`]) is a closed-form starting point
//! ([`PlanarField::semi_balanced_guess`]); with the race centred (`s2 = 0`) it is the balanced
//! state of the Jeffcott rotor. With `n ≥ 3` balls such states form a family of dimension
//! `n − 2` (the balls only have to sum to `B`), which [`VectorField::structural_zeros`] reports.
//!
//! ```
//! use autobal::analysis::{speed_scan, stability, stationary, NewtonOptions, ScanOptions, Verdict};
//! use autobal::planar::field::PlanarField;
//! use autobal::planar::PlanarRotor;
//! // paper 004's rotor (eccentric race): semi-balanced and stable at 400 rad/s, above 288
//! let rotor = PlanarRotor::paper();
//! let f = PlanarField::new(&rotor, 400.0).unwrap();
//! let state = stationary(&f, &f.semi_balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
//! assert!((state.x[0].hypot(state.x[1]) - rotor.s2).abs() < 1e-15); // C whirls at s2
//! assert_eq!(stability(&f, &state).unwrap().verdict, Verdict::Stable);
//! // the stable range over 50..2040 rad/s starts a little above the critical speed
//! let speeds: Vec<f64> = (0..200).map(|i| 50.0 + 10.0 * i as f64).collect();
//! let scan = speed_scan(|w| PlanarField::new(&rotor, w), |f, _| f.semi_balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
//! assert!((scan.stable_ranges[0].from - 300.951).abs() < 1e-3);
//! ```

use super::equations::Equations;
use super::{Drive, PlanarRotor};
use crate::analysis::VectorField;
use crate::error::{finite, Error, Result};
use crate::ode::arrow::{Arrow, ArrowLinearization, ArrowSystem};
use crate::ode::lu::Lu;
use crate::ode::System;
use num_complex::Complex64 as C;

/// The planar rotor at constant speed `Ω`, reduced state `x = (ξ, η, ψ_1..n, ξ̇, η̇, ψ̇_1..n)`
/// (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarField {
    rotor: PlanarRotor,
    drive: Drive,
    omega: f64,
    cache: TrigJacobian,
}

/// Supports that differ by direction, at a state `x` held fixed: the rotor angle enters the
/// equations only through the support force, affine in `cos 2θ`, `sin 2θ` (the mass matrix not
/// at all; the accelerations, and the `∂M/∂q q̈` terms with them, are affine in the same two), so
/// `J(t, x) = J_a + cos(2Ωt) J_c + sin(2Ωt) J_s` exactly. At the balanced state, stationary at
/// every instant, the variational equations over a period then need three Jacobians, not one
/// per right-hand side (3x faster Floquet scans). Built when two calls in a row come at the same state (to `1e-13` in units
/// of the scales, far below the integration's error); used while calls stay there; a state that
/// moves (a periodic orbit, a shooting iterate) never builds it.
#[derive(Default)]
struct TrigJacobian(std::sync::Mutex<TrigState>);

#[derive(Default)]
struct TrigState {
    /// The state of the previous call.
    last: Vec<f64>,
    /// The state and `(J_a, J_c, J_s)` of the decomposition.
    built: Option<(Vec<f64>, [Vec<f64>; 3])>,
}

impl Clone for TrigJacobian {
    fn clone(&self) -> Self {
        TrigJacobian::default()
    }
}

impl PartialEq for TrigJacobian {
    fn eq(&self, _: &Self) -> bool {
        true // a cache: no part of the field's value
    }
}

impl std::fmt::Debug for TrigJacobian {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("TrigJacobian")
    }
}

impl PlanarField {
    /// The field of `rotor` at speed `omega` (rad/s). Real balls (contact, rolling resistance:
    /// [`crate::balls`]) have stationary sets with a friction dead zone or resting contact and
    /// no linearisation: [`Error::NoLinearisation`].
    pub fn new(rotor: &PlanarRotor, omega: f64) -> Result<Self> {
        rotor.validate()?;
        finite("omega", omega)?;
        if rotor.balls.is_active() {
            return Err(Error::NoLinearisation {
                reason: "planar.contact / planar.rolling_resistance make the balls' stationary set a friction dead zone or a resting contact; switch them off to analyse the point-mass balls".into(),
            });
        }
        Ok(PlanarField { rotor: rotor.clone(), drive: Drive::Speed { omega0: omega }, omega, cache: TrigJacobian::default() })
    }

    /// The rotor.
    pub fn rotor(&self) -> &PlanarRotor {
        &self.rotor
    }

    /// The speed `Ω` (rad/s).
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Number of reduced coordinates `2 + n`.
    fn nr(&self) -> usize {
        2 + self.rotor.n
    }

    /// Full coordinate index (`ξ, η, θ, ψ_j`) of reduced coordinate `i < 2 + n`.
    fn full_coord(i: usize) -> usize {
        if i < 2 {
            i
        } else {
            i + 1
        }
    }

    /// The full state `y = (ξ, η, θ, ψ, ξ̇, η̇, θ̇, ψ̇)` of [`Equations`] at `θ = 0`, `θ̇ = Ω`.
    pub fn full_state(&self, x: &[f64]) -> Vec<f64> {
        self.full_state_at(0.0, x)
    }

    /// The full state at time `t`: `θ = Ω t` (which only supports that differ by direction
    /// feel), `θ̇ = Ω`.
    pub fn full_state_at(&self, t: f64, x: &[f64]) -> Vec<f64> {
        let (nr, nc) = (self.nr(), self.nr() + 1);
        let mut y = vec![0.0; 2 * nc];
        for i in 0..nr {
            y[Self::full_coord(i)] = x[i];
            y[nc + Self::full_coord(i)] = x[nr + i];
        }
        y[nc + 2] = self.omega;
        y[2] = self.omega * t;
        y
    }

    /// The reduced state of a full state `y` of [`Equations`] (drops `θ`, `θ̇`).
    pub fn reduced_state(&self, y: &[f64]) -> Vec<f64> {
        let (nr, nc) = (self.nr(), self.nr() + 1);
        let mut x = vec![0.0; 2 * nr];
        for i in 0..nr {
            x[i] = y[Self::full_coord(i)];
            x[nr + i] = y[nc + Self::full_coord(i)];
        }
        x
    }

    /// Length scale of the whirl: `s1 + s2 + n m3 r / m0` (the unbalances), or the race radius
    /// when all vanish.
    fn length(&self) -> f64 {
        let p = &self.rotor;
        let l = p.s1 + p.s2 + p.balls_mass() * p.r / p.total_mass();
        if l > 0.0 {
            l
        } else {
            p.r.max(1e-3)
        }
    }

    /// The semi-balanced state at this speed (module docs of [`crate::planar::stationary`]):
    /// `u = −s2 e^{iγ}`, the balls at rest with `m3 r Σ e^{iψ_j} = B`,
    /// `B = −s2 e^{iγ}(k/Ω² + i c/Ω) + m1 (s2 e^{iγ} − s1)`; one member of the family for
    /// `n ≥ 3` (pairs at `arg B ± φ`, and for odd `n` one ball at `arg B`). `None` where it
    /// does not exist (`|B| > n m3 r`, `n < 2`, `Ω = 0`).
    pub fn semi_balanced_guess(&self) -> Option<Vec<f64>> {
        let p = &self.rotor;
        let n = p.n;
        let w = self.omega;
        if n < 2 || w == 0.0 {
            return None;
        }
        let e = C::from_polar(p.s2, p.gamma);
        // supports that differ by direction: the mean ones (exact for the balanced state,
        // s2 = 0, where no support force acts; a start for the shooting otherwise)
        let (k, c) = p.mean_supports();
        let b = -e * C::new(k / (w * w), c / w) + (e - C::new(p.s1, 0.0)) * p.m1;
        let nr = self.nr();
        let state = |psi: &[f64]| {
            let mut x = vec![0.0; 2 * nr];
            x[0] = -e.re;
            x[1] = -e.im;
            x[2..nr].copy_from_slice(psi);
            x
        };
        if !p.equal_balls() {
            let masses: Vec<f64> = (0..n).map(|j| p.ball_mass(j)).collect();
            return unequal_balls_balancing(&masses, p.r, b).map(|psi| state(&psi));
        }
        let ratio = b.norm() / (p.m3 * p.r);
        if ratio > n as f64 {
            return None;
        }
        let phase = if b.norm() > 0.0 { b.arg() } else { 0.0 };
        let mut psi = Vec::with_capacity(n);
        let pairs = n / 2;
        let cos_phi = if n.is_multiple_of(2) { ratio / n as f64 } else { (ratio - 1.0) / (n - 1) as f64 };
        let phi = cos_phi.clamp(-1.0, 1.0).acos();
        if !n.is_multiple_of(2) {
            psi.push(phase);
        }
        for _ in 0..pairs {
            psi.push(phase + phi);
            psi.push(phase - phi);
        }
        Some(state(&psi))
    }

    /// Starts for the isolated periodic orbits of `n ≥ 3` equal balls on supports that differ
    /// by direction: the balls in **two groups**, `p` balls at `α` and `n − p` at `β`
    /// (`⌈n/2⌉ ≤ p < n`, both mirror placements of an uneven split), with
    /// `m3 r (p e^{iα} + (n − p) e^{iβ}) = B` ([`PlanarField::semi_balanced_guess`]'s `B` and
    /// `u`). An eccentric race on such supports breaks the family of balanced states into
    /// isolated orbits with the balls in two groups, much as gravity does for the spatial rotor
    /// ([`crate::spatial::dynamics::field::SpatialField::split_guesses`]); the family's member
    /// of the closed form is then no orbit. Empty where the field is autonomous, for `n < 3`,
    /// unequal balls, or where no two groups give `B`.
    pub fn split_guesses(&self) -> Vec<Vec<f64>> {
        let p = &self.rotor;
        let n = p.n;
        let w = self.omega;
        if n < 3 || w == 0.0 || !p.equal_balls() || self.period().is_none() {
            return vec![];
        }
        let e = C::from_polar(p.s2, p.gamma);
        let (k, c) = p.mean_supports();
        let b = -e * C::new(k / (w * w), c / w) + (e - C::new(p.s1, 0.0)) * p.m1;
        let nr = self.nr();
        crate::spatial::dynamics::field::two_groups(n, p.m3 * p.r, [b.re, b.im])
            .into_iter()
            .map(|angles| {
                let mut x = vec![0.0; 2 * nr];
                x[0] = -e.re;
                x[1] = -e.im;
                x[2..nr].copy_from_slice(&angles);
                x
            })
            .collect()
    }
}

/// The two angles `(φ_a, φ_b)` at which two balls of unbalances `a = m_a r`, `b = m_b r`
/// (kg·m) sum to the unbalance `d = |D| e^{iβ}`: the triangle with sides `a`, `b`, `|D|`,
/// `φ_a = β + δ_a`, `φ_b = β − δ_b`, `cos δ_a = (|D|² + a² − b²)/(2|D| a)`,
/// `cos δ_b = (|D|² + b² − a²)/(2|D| b)` (the other solution is its mirror image in `β`).
/// Exists while `|a − b| ≤ |D| ≤ a + b`: unequal balls cannot cancel an unbalance smaller than
/// their difference. `None` otherwise.
pub fn two_ball_angles(a: f64, b: f64, d: C) -> Option<(f64, f64)> {
    let dn = d.norm();
    // 1e-12 relative slack: the triangle's degenerate ends are reached to round-off
    let slack = 1e-12 * (a + b);
    if !(dn >= (a - b).abs() - slack && dn <= a + b + slack) || a <= 0.0 || b <= 0.0 {
        return None;
    }
    let beta = if dn > 0.0 { d.arg() } else { 0.0 };
    if dn == 0.0 {
        // a = b: opposite
        return Some((beta + std::f64::consts::FRAC_PI_2, beta - std::f64::consts::FRAC_PI_2));
    }
    let ca = ((dn * dn + a * a - b * b) / (2.0 * dn * a)).clamp(-1.0, 1.0);
    let cb = ((dn * dn + b * b - a * a) / (2.0 * dn * b)).clamp(-1.0, 1.0);
    Some((beta + ca.acos(), beta - cb.acos()))
}

/// Ball angles at which balls of masses `masses` on a race of radius `r` sum to the unbalance
/// `b` (`r Σ m_j e^{iψ_j} = b`): for two balls the closed form [`two_ball_angles`]; for more,
/// balls 3.. placed first (spread evenly, or all along `b`, or all against it: the first of
/// these that leaves the remainder within reach of balls 1 and 2), then balls 1 and 2 by the
/// closed form; where none of those three does, balls 3.. placed one by one so that what is
/// left stays within reach of the balls still free (`place_in_reach`). One member of the
/// family (`n ≥ 3`); `None` exactly where no placement exists: `|b|` outside the annulus
/// `max(0, 2 max l − Σ l) ≤ |b| ≤ Σ l` of the lengths `l_j = m_j r` (a polygon closes with
/// sides `l_j` and `|b|` exactly then).
pub fn unequal_balls_balancing(masses: &[f64], r: f64, b: C) -> Option<Vec<f64>> {
    let n = masses.len();
    if n < 2 {
        return None;
    }
    let beta = if b.norm() > 0.0 { b.arg() } else { 0.0 };
    let rest = n - 2;
    let placements: [Box<dyn Fn(usize) -> f64>; 3] = [
        Box::new(|i| beta + 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / rest.max(1) as f64),
        Box::new(|_| beta),
        Box::new(|_| beta + std::f64::consts::PI),
    ];
    for place in placements.iter().take(if rest == 0 { 1 } else { 3 }) {
        let angles: Vec<f64> = (0..rest).map(place).collect();
        let sum: C = angles.iter().zip(&masses[2..]).map(|(a, m)| C::from_polar(m * r, *a)).sum();
        if let Some((pa, pb)) = two_ball_angles(masses[0] * r, masses[1] * r, b - sum) {
            let mut psi = vec![pa, pb];
            psi.extend(angles);
            return Some(psi);
        }
    }
    // (review 25a: with n >= 3 unequal balls those three placements missed reachable
    // unbalances, so `critical` and `stability` reported "no balanced state" where one exists,
    // and the answer depended on the order the balls were listed in)
    place_in_reach(masses, r, b)
}

/// The reach of balls of lengths `l` (kg·m): the annulus `[max(0, 2 max l − Σ l), Σ l]` of the
/// magnitudes their sum `Σ l_j e^{iψ_j}` can take.
fn reach(l: &[f64]) -> (f64, f64) {
    let sum: f64 = l.iter().sum();
    let max = l.iter().copied().fold(0.0, f64::max);
    ((2.0 * max - sum).max(0.0), sum)
}

/// [`unequal_balls_balancing`]'s general placement: balls 3.. one at a time, each at the angle
/// that leaves a remainder `D'` of magnitude `ρ` within the reach of the balls still free (the
/// middle of `[||D| − l_k|, |D| + l_k] ∩ reach(rest)`, not empty whenever `|D|` is within the
/// reach of all of them: the reach of a set is the circle of radius `l_k` swept over the
/// annulus of the rest), by the triangle `(|D|, l_k, ρ)`; then balls 1 and 2 by
/// [`two_ball_angles`]. `None` where `|b|` is outside the balls' reach.
fn place_in_reach(masses: &[f64], r: f64, b: C) -> Option<Vec<f64>> {
    let l: Vec<f64> = masses.iter().map(|m| m * r).collect();
    let (lo, hi) = reach(&l);
    // a relative slack of round-off (the triangle limits themselves are reachable)
    let tol = 1e-12 * hi;
    if b.norm() < lo - tol || b.norm() > hi + tol {
        return None;
    }
    let n = l.len();
    let mut d = b;
    let mut rest = vec![0.0; n - 2];
    for k in 2..n {
        // the balls still free after k: 1, 2 and k+1..
        let free: Vec<f64> = [l[0], l[1]].into_iter().chain(l[k + 1..].iter().copied()).collect();
        let (rlo, rhi) = reach(&free);
        let dn = d.norm();
        let (a, z) = (((dn - l[k]).abs()).max(rlo), (dn + l[k]).min(rhi));
        if a > z + tol {
            return None;
        }
        let rho = 0.5 * (a + z.max(a));
        let phi = if dn > 0.0 && l[k] > 0.0 {
            let c = ((dn * dn + l[k] * l[k] - rho * rho) / (2.0 * dn * l[k])).clamp(-1.0, 1.0);
            d.arg() + c.acos()
        } else {
            0.0
        };
        rest[k - 2] = phi;
        d -= C::from_polar(l[k], phi);
    }
    let (pa, pb) = two_ball_angles(l[0], l[1], d)?;
    let mut psi = vec![pa, pb];
    psi.extend(rest);
    Some(psi)
}

impl VectorField for PlanarField {
    fn dim(&self) -> usize {
        2 * self.nr()
    }

    fn rhs(&self, t: f64, x: &[f64], dx: &mut [f64]) {
        let eq = Equations::new(&self.rotor, &self.drive);
        let y = self.full_state_at(t, x);
        let mut dy = vec![0.0; y.len()];
        eq.rhs(0.0, &y, &mut dy);
        dx.copy_from_slice(&self.reduced_state(&dy));
    }

    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) {
        if self.period().is_none() {
            return self.jacobian_at(t, x, jac);
        }
        let s = self.scales();
        let same = |a: &[f64]| a.len() == x.len() && a.iter().zip(x).zip(&s).all(|((a, b), s)| (a - b).abs() <= 1e-13 * s);
        let mut c = self.cache.0.lock().unwrap_or_else(|e| e.into_inner());
        if c.built.as_ref().is_none_or(|(key, _)| !same(key)) {
            if !same(&c.last) {
                c.last = x.to_vec();
                drop(c);
                return self.jacobian_at(t, x, jac);
            }
            // J(θ) = J_a + cos 2θ J_c + sin 2θ J_s from θ = 0, π/2, π/4
            let n = x.len();
            let w = self.omega;
            let mut j = [vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]];
            for (m, th) in j.iter_mut().zip([0.0, std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_4]) {
                self.jacobian_at(th / w, x, m);
            }
            let [j0, j90, j45] = j;
            let ja: Vec<f64> = j0.iter().zip(&j90).map(|(a, b)| 0.5 * (a + b)).collect();
            let jc: Vec<f64> = j0.iter().zip(&j90).map(|(a, b)| 0.5 * (a - b)).collect();
            let js: Vec<f64> = j45.iter().zip(&ja).map(|(a, b)| a - b).collect();
            c.built = Some((x.to_vec(), [ja, jc, js]));
        }
        let (_, [ja, jc, js]) = c.built.as_ref().expect("built above");
        let (sn, cs) = (2.0 * self.omega * t).sin_cos();
        for (i, o) in jac.iter_mut().enumerate() {
            *o = ja[i] + cs * jc[i] + sn * js[i];
        }
    }

    /// `None` for equal supports; where they differ by direction, `π/Ω`: the equations
    /// depend on the rotor angle through `e^{−2iθ}` alone ([`Equations`]' support force), so the
    /// field's period is half a revolution. (At `Ω = 0` nothing turns: `None`.)
    fn period(&self) -> Option<f64> {
        (self.rotor.anisotropic() && self.omega != 0.0).then(|| std::f64::consts::PI / self.omega.abs())
    }

    fn structural_zeros(&self, x: &[f64]) -> usize {
        let p = &self.rotor;
        if p.n < 3 {
            return 0;
        }
        // E on the axis: u + s2 e^{iγ} = 0 (to 1e-6 of the whirl's length scale)
        let off = (x[0] + p.s2 * p.gamma.cos()).hypot(x[1] + p.s2 * p.gamma.sin());
        // balls bunched (within 1e-9 rad of one angle): the capacity exactly full, the state
        // isolated (|Σ e^{iψ_j}| = n only with every ball at one angle): no family, whatever
        // the rank (SpatialField::bunched_surplus)
        let psi = &x[2..2 + p.n];
        let bunched = psi.iter().all(|a| {
            let w = (a - psi[0]).rem_euclid(std::f64::consts::TAU);
            w.min(std::f64::consts::TAU - w) <= 1e-9
        });
        if off <= 1e-6 * self.length() && !bunched {
            p.n - 2
        } else {
            0
        }
    }

    fn component_name(&self, i: usize) -> String {
        let nr = self.nr();
        let (rate, k) = if i >= nr { (true, i - nr) } else { (false, i) };
        let base = match k {
            0 => "ξ (x of C in rotor axes)".to_string(),
            1 => "η (y of C in rotor axes)".to_string(),
            j => format!("ψ_{} (ball {} angle)", j - 1, j - 1),
        };
        if rate {
            format!("rate of {base}")
        } else {
            base
        }
    }

    fn scales(&self) -> Vec<f64> {
        let l = self.length();
        let w = self.omega.abs().max(self.rotor.natural_frequency());
        let nr = self.nr();
        (0..2 * nr)
            .map(|i| {
                let base = if i % nr < 2 { l } else { 1.0 };
                if i >= nr {
                    base * w
                } else {
                    base
                }
            })
            .collect()
    }
}

impl PlanarField {
    /// The exact Jacobian at `(t, x)` (the [`VectorField::jacobian`] of the module docs).
    fn jacobian_at(&self, t: f64, x: &[f64], jac: &mut [f64]) {
        let eq = Equations::new(&self.rotor, &self.drive);
        let (nr, nc) = (self.nr(), self.nr() + 1);
        let n = 2 * nr;
        let y = self.full_state_at(t, x);
        let mut dy = vec![0.0; y.len()];
        eq.rhs(0.0, &y, &mut dy);
        let z = Arrow::zeros(3, self.rotor.n);
        let mut lin = ArrowLinearization { mass: z.clone(), g_q: z.clone(), g_v: z };
        eq.linearize(0.0, &y, &dy[nc..], &mut lin);
        // M X = [G_q | G_v] for the reduced columns
        let m = lin.mass.to_dense();
        let (gq, gv) = (lin.g_q.to_dense(), lin.g_v.to_dense());
        jac.iter_mut().for_each(|v| *v = 0.0);
        // the mass matrix is symmetric positive definite; were it singular, the rows of the
        // accelerations are not finite, as the right-hand side's would be
        let Some(lu) = Lu::factored(m, nc) else {
            jac[nr * n..].iter_mut().for_each(|v| *v = f64::NAN);
            return;
        };
        for i in 0..nr {
            jac[i * n + nr + i] = 1.0;
        }
        let mut col = vec![0.0; nc];
        for (half, g) in [(0, &gq), (nr, &gv)] {
            for j in 0..nr {
                let cj = Self::full_coord(j);
                for (r, c) in col.iter_mut().enumerate() {
                    *c = g[r * nc + cj];
                }
                lu.solve(&mut col);
                for i in 0..nr {
                    jac[(nr + i) * n + half + j] = col[Self::full_coord(i)];
                }
            }
        }
    }
}
