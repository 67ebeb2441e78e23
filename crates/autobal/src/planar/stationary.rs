//! Stationary (steady synchronous) whirls of the planar rotor at constant speed ω, for the
//! dashed curves of the transient plots (004, Figs 2-4).
//!
//! In rotor axes a steady whirl has `u̇ = 0`, `ψ̇ = 0`; the translation equation gives
//! `u (k + i c ω − m0 ω²) = ω² U`, `U = m1 s1 + (m2 + n m3) s2 e^{iγ} + m3 r Σ e^{iψ_j}`
//! (the total unbalance about C in rotor axes).
//!
//! - **Balls locked** at given angles: `|u| = ω² |U| / |k − m0 ω² + i c ω|` (closed form).
//! - **Semi-balanced** (balls free): the race centre E on the axis, `u = −s2 e^{iγ}`, so C whirls
//!   at radius `s2` whatever ω; the balls must then supply
//!   `B = m3 r Σ e^{iψ_j} = −s2 e^{iγ} (k/ω² + i c/ω) + m1 (s2 e^{iγ} − s1)`, possible while
//!   `|B| ≤ n m3 r` (n ≥ 2). At high speed the capacity ratio tends to
//!   `α∞ = n m3 r / (m1 |s1 − s2 e^{iγ}|)`.
//! - **Aligned** (balls free, E off the axis): each ball is in equilibrium only on the line
//!   through the axis and E (tangential centrifugal force zero), far side or near side; with
//!   `q = n_far − n_near` and `w = u + s2 e^{iγ} = ρ e^{iφ}`:
//!   `e^{iφ}(ρ D − m3 r q ω²) = ω² U0 + s2 e^{iγ} D`, `D = k + icω − m0 ω²`,
//!   `U0 = m1 s1 + (m2 + n m3) s2 e^{iγ}`, a quadratic in `ρ ≥ 0`.
//!
//! These are the closed forms of **equal supports**: where they differ by direction
//! (`planar.k_x ≠ planar.k_y`, `c_x ≠ c_y`) a steady whirl is elliptic, periodic in rotor axes,
//! and the forms below use the mean stiffness and damping `k̄ = (k_x + k_y)/2`, `c̄` (the
//! dashed guide curves of the plots; the exact stationary motion is [`crate::planar::field`]'s
//! periodic orbit). Balls of unequal mass enter through their sums (`Σ m_j`, `Σ m_j e^{iψ_j}`);
//! the aligned whirls take each ball as the mean `m3`.

use super::PlanarRotor;
use num_complex::Complex64 as C;

fn d_of(p: &PlanarRotor, w: f64) -> C {
    let (k, c) = p.mean_supports();
    C::new(k - p.total_mass() * w * w, c * w)
}

/// Steady whirl radius of C with the balls locked at angles `psi` (closed form).
pub fn locked_amplitude(p: &PlanarRotor, w: f64, psi: &[f64]) -> f64 {
    locked_whirl(p, w, psi).norm()
}

/// Steady whirl `u = H(ω) U` of C in rotor axes with the balls locked at angles `psi`:
/// `H = ω²/(k − m0 ω² + i c ω)` ([`receptance`]), `U` the total unbalance about C.
pub fn locked_whirl(p: &PlanarRotor, w: f64, psi: &[f64]) -> C {
    let e = C::from_polar(p.s2, p.gamma);
    let mut u = C::new(p.m1 * p.s1, 0.0) + e * (p.m2 + p.balls_mass());
    for (j, a) in psi.iter().enumerate() {
        u += C::from_polar(p.ball_mass(j) * p.r, *a);
    }
    receptance(p, w) * u
}

/// `H(ω) = ω²/(k − m0 ω² + i c ω)`: the steady whirl of C per unit unbalance (m/(kg·m)).
pub fn receptance(p: &PlanarRotor, w: f64) -> C {
    C::new(w * w, 0.0) / d_of(p, w)
}

/// The unbalance the balls must supply in the semi-balanced whirl at speed `w`.
pub fn semi_balanced_demand(p: &PlanarRotor, w: f64) -> f64 {
    let e = C::from_polar(p.s2, p.gamma);
    let (k, c) = p.mean_supports();
    // the supports' term `e (k/ω² + i c/ω)`: none with the race centred (at rest too, where
    // `0 · (k/0)` would be NaN); unbounded at rest with an eccentric race
    let supports = if p.s2 == 0.0 {
        C::new(0.0, 0.0)
    } else if w == 0.0 {
        return f64::INFINITY;
    } else {
        e * C::new(k / (w * w), c / w)
    };
    let d = (-supports + (e - C::new(p.s1, 0.0)) * p.m1).norm();
    if d.is_nan() {
        f64::INFINITY
    } else {
        d
    }
}

/// The largest unbalance the balls can supply (kg·m): `n m3 r` for point masses, and for balls
/// of finite size (`planar.contact`) that of the touching balls packed in one arc,
/// `m3 r sin(nΔc/2)/sin(Δc/2)` ([`crate::balls::capacity`]).
pub fn ball_capacity(p: &PlanarRotor) -> f64 {
    if p.balls.contact {
        crate::balls::capacity(p.n, p.m3, p.balls.diameter(p.m3), p.r)
    } else {
        p.balls_mass() * p.r
    }
}

/// Whether the semi-balanced whirl (radius `s2`) exists at speed `w`.
pub fn semi_balanced_exists(p: &PlanarRotor, w: f64) -> bool {
    p.n >= 2 && semi_balanced_demand(p, w) <= ball_capacity(p)
}

/// High-speed capacity ratio `α∞ = n m3 r / (m1 |s1 − s2 e^{iγ}|)`; the semi-balanced whirl
/// exists at high speed when `α∞ > 1` (our reading of the paper's garbled eq (3)).
pub fn capacity_ratio(p: &PlanarRotor) -> f64 {
    let e = C::from_polar(p.s2, p.gamma);
    ball_capacity(p) / (p.m1 * (C::new(p.s1, 0.0) - e).norm())
}

/// One aligned (unbalanced) steady whirl.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aligned {
    /// `n_far − n_near`.
    pub q: i32,
    /// Whirl radius of C.
    pub amplitude: f64,
}

/// All aligned steady whirls at speed `w` (balls free, E off the axis): every
/// `q = −n, −n + 2, …, n` ([`aligned_whirls_of`]), O(n).
pub fn aligned_whirls(p: &PlanarRotor, w: f64) -> Vec<Aligned> {
    let n = p.n as i32;
    let mut out = vec![];
    let mut q = -n;
    while q <= n {
        aligned_whirls_of(p, w, q, &mut out);
        q += 2;
    }
    out
}

/// The aligned steady whirls at speed `w` with `q = n_far − n_near` (at most two), appended to
/// `out`: O(1), for a caller that needs one `q` of many balls (e.g. all balls on one side,
/// `q = ±n`).
pub fn aligned_whirls_of(p: &PlanarRotor, w: f64, q: i32, out: &mut Vec<Aligned>) {
    let e = C::from_polar(p.s2, p.gamma);
    let d = d_of(p, w);
    let u0 = C::new(p.m1 * p.s1, 0.0) + e * (p.m2 + p.balls_mass());
    let rhs = u0 * (w * w) + e * d;
    let qq = p.m3 * p.r * q as f64 * w * w;
    // |ρ D − qq|² = |rhs|²  →  ρ²|D|² − 2ρ qq Re D + qq² − |rhs|² = 0
    let (a, b, c) = (d.norm_sqr(), -2.0 * qq * d.re, qq * qq - rhs.norm_sqr());
    let disc = b * b - 4.0 * a * c;
    if disc >= 0.0 && a > 0.0 {
        for s in [-1.0, 1.0] {
            let rho = (-b + s * disc.sqrt()) / (2.0 * a);
            if rho > 0.0 {
                let phase = rhs.arg() - (d * rho - qq).arg();
                let u = C::from_polar(rho, phase) - e;
                out.push(Aligned { q, amplitude: u.norm() });
            }
            if disc == 0.0 {
                break;
            }
        }
    }
}

/// The race centre E's distance from the axis in the steady whirl at speed `w` without the
/// balls' resultant (their mass carried, their resultant zero): `|ω² u0 / D + s2 e^{iγ}|`,
/// `u0 = m1 s1 + (m2 + Σ m_j) s2 e^{iγ}`, `D = k̄ − m0 ω² + i c̄ ω` (the supports' means); where
/// that is not finite or below `1e-12` of the length scale `s1 + s2 + Σ m_j r / m0`, that scale.
/// What a planar residual is a fraction of: a run's [`crate::planar::Summary::residual_unbalance`],
/// as `stability`'s (`crate::rotor_stability::Rotor::residual`). For a centred race (`s2 = 0`)
/// at a steady whirl the ratio `|E| / race_offset_scale` is the residual unbalance
/// `|m1 s1 + Σ m_j r e^{iψ_j}| / (m1 s1)` itself (`E = C = H(ω) U`).
pub fn race_offset_scale(p: &PlanarRotor, w: f64) -> f64 {
    let race = C::from_polar(p.s2, p.gamma);
    let u0 = C::new(p.m1 * p.s1, 0.0) + race * (p.total_mass() - p.m1);
    let free = (u0 * (w * w) / d_of(p, w) + race).norm();
    let scale = (p.s1 + p.s2 + p.balls_mass() * p.r / p.total_mass()).max(f64::MIN_POSITIVE);
    if free.is_finite() && free > 1e-12 * scale {
        free
    } else {
        scale
    }
}

/// The residual (a fraction of [`race_offset_scale`]) up to which a periodic orbit, or a run's
/// end, counts as balanced (semi-balanced with an eccentric race):
/// [`BALANCE_TOLERANCE`](crate::spatial::dynamics::simulate::BALANCE_TOLERANCE) (5 %) of the
/// scale on supports equal in every direction; where they differ by direction 5 % of the
/// smaller of the scale and a length that does not resonate, `s2` (`s1` for a centred race):
/// the race centre E within 5 % of `s2` of the axis on average, so C's mean position is at `s2`
/// to within 5 % (the run's own radius test, [`crate::planar::Summary::balanced`]). Why there:
/// the scale, E's offset without the balls' resultant by the supports' means, grows without
/// bound between the split critical speeds; 5 % of it was 1.2 mm on a rotor with `s2` = 1.3 mm
/// (audit 23, F1: balls at their capacity limit read semi-balanced), while a semi-balanced
/// orbit's swing leaves E's mean 0.2-15 µm off the axis on that rotor (0.02-1.1 % of `s2`),
/// its second order. On equal supports the closed forms decide whether the balls' capacity
/// falls short ([`semi_balanced_exists`]), so a capacity-limited end is never read as balanced
/// there, and the allowance keeps its meaning of sessions 15-23 (review 24a: tightening it
/// called a fast ramp's end, its balls lagging, not balanced on examples/planar.toml).
pub fn balance_allowance(p: &PlanarRotor, w: f64) -> f64 {
    let tolerance = crate::spatial::dynamics::simulate::BALANCE_TOLERANCE;
    if !p.anisotropic() {
        return tolerance;
    }
    let length = if p.s2 > 0.0 { p.s2 } else { p.s1 };
    let ratio = length / race_offset_scale(p, w);
    tolerance * if ratio > 0.0 && ratio < 1.0 { ratio } else { 1.0 }
}

/// The balls' resultant `Σ m_j r e^{iψ_j}` (kg·m, rotor axes) at the angles `psi` (rad, from
/// CG), each ball its own mass ([`PlanarRotor::ball_mass`]).
pub fn ball_resultant(p: &PlanarRotor, psi: impl Iterator<Item = f64>) -> [f64; 2] {
    let mut b = [0.0; 2];
    for (j, a) in psi.enumerate() {
        let (s, c) = a.sin_cos();
        let m = p.ball_mass(j) * p.r;
        b[0] += m * c;
        b[1] += m * s;
    }
    b
}

/// The residual of the bunched steady whirl at speed `w`, as a fraction of
/// [`race_offset_scale`]: every ball at one angle on the far side of the line through the axis
/// and the race centre E, their resultant the capacity `B` ([`ball_capacity`]): the aligned
/// whirl of [`aligned_whirls_of`] with `q = n`, `e^{iφ}(ρ D − B ω²) = ω² U0 + s2 e^{iγ} D`, of its
/// (at most two) roots the one of least whirl radius of C, the state `stability` follows where
/// no balanced or semi-balanced state exists (`crate::rotor_stability::Rotor::bunched_guess`).
/// Its residual is `ρ = |E|` over the scale. For a centred race above the critical speed the
/// balls lie against the unbalance, `≈ 1 − B / (m1 s1)` (exactly without damping; with damping
/// they lag that line by the whirl's phase and it is a little larger); below it they join the
/// unbalance, `≈ 1 + B / (m1 s1)`. `None` without balls or where no such whirl exists.
pub fn bunched_residual(p: &PlanarRotor, w: f64) -> Option<f64> {
    if p.n == 0 {
        return None;
    }
    let e = C::from_polar(p.s2, p.gamma);
    let d = d_of(p, w);
    let u0 = C::new(p.m1 * p.s1, 0.0) + e * (p.m2 + p.balls_mass());
    let rhs = u0 * (w * w) + e * d;
    let qq = ball_capacity(p) * w * w;
    let (a, b, c) = (d.norm_sqr(), -2.0 * qq * d.re, qq * qq - rhs.norm_sqr());
    let disc = b * b - 4.0 * a * c;
    if !(disc >= 0.0 && a > 0.0) {
        return None;
    }
    let rho = [-1.0, 1.0]
        .iter()
        .map(|s| (-b + s * disc.sqrt()) / (2.0 * a))
        .filter(|rho| *rho >= 0.0)
        .map(|rho| (rho, (C::from_polar(rho, rhs.arg() - (d * rho - qq).arg()) - e).norm()))
        .min_by(|x, y| x.1.total_cmp(&y.1))?
        .0;
    Some(rho / race_offset_scale(p, w))
}
