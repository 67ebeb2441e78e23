//! Mass properties of the whole spatial rotor as the simulation builds it ([`SpatialRotor`]):
//! the rigid rotor with its tilted principal axis, every unbalance mass, every ball of every
//! plane at given angles. Total mass, centre of mass, inertia tensor about it, principal
//! moments and the tilt of the principal axis nearest the shaft (the residual couple).
//!
//! In the rotor frame (x, y across the shaft, z along it, in the config's axial coordinate):
//!
//! - the rigid rotor, mass `M_r` at `g = (0, 0, z_G)`, has about `G` the tensor
//!   `I_r = A_r 1 + (C_r − A_r) e eᵀ`, `e = (sin κ cos β, sin κ sin β, cos κ)` (its principal
//!   axis tilted by `κ` towards `β`: [`RigidRotor`](super::RigidRotor));
//! - a point mass `m_i` (unbalance mass, or a ball of plane `p` at angle `ψ_j`) sits at
//!   `p_i = (ρ_i cos a_i, ρ_i sin a_i, z_i)`;
//! - `M = M_r + Σ m_i`, `c = (M_r g + Σ m_i p_i)/M`;
//! - about `c`: `I = I_r + M_r (|g − c|² 1 − (g − c)(g − c)ᵀ) + Σ m_i (|p_i − c|² 1 − (p_i − c)(p_i − c)ᵀ)`
//!   (parallel axes; off-diagonal `I_xz = −Σ m x z` is the product of inertia `J_xz`);
//! - principal moments: the eigenvalues of `I` (Jacobi rotations, to round-off); the polar one
//!   is that whose axis `u` is nearest the shaft (`|u_z|` largest, `u_z ≥ 0`); its tilt from the
//!   shaft is `acos u_z` towards `atan2(u_y, u_x)`: zero exactly when the couple
//!   `(−I_xz, −I_yz)` about `c` vanishes. For a small couple `J` on an axisymmetric rotor the
//!   tilt is `|J|/(C − A)` to first order (`tan 2θ = 2|J|/(C − A)` exactly when the couple
//!   lies in one plane).
//!
//! Supports and gravity do not enter: they act on the rotor, they are not part of it.
//! Balls are point masses at their centres (real balls' own rotational inertia is left out, as
//! in the equations of motion).
//!
//! Where the balls sit: [`SpatialRotor::balanced_ball_angles`] places them as the simulation's
//! balanced state ([`SpatialField::balanced_guess`](super::SpatialField::balanced_guess)'s
//! closed form), or, where no balanced state exists, says so and places them as stated there.

use super::field::arc_angles;
use super::rotor::SpatialRotor;
use crate::error::{Error, Result};
use serde::Serialize;

/// How the balls were placed by [`SpatialRotor::balanced_ball_angles`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// Every plane carries its share: the balls cancel the static unbalance (one plane) or the
    /// static and couple unbalance (two planes).
    Balanced,
    /// One plane whose capacity `n m R` falls short of the static unbalance: the balls are
    /// bunched opposite it, the partially balanced state (residual `|s0| − n m R`).
    PartiallyBalanced,
    /// No balanced state (a plane short of its share, two planes at one axial position, or
    /// more than two planes): each plane's balls bunched towards its share, a placement, not a
    /// stationary state.
    Bunched,
    /// No balls.
    NoBalls,
}

/// Ball angles of every plane with balls (rotor frame, rad, planes in order) and how they were
/// found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BallPlacement {
    /// The angles `ψ_j`.
    pub angles: Vec<f64>,
    /// What they are.
    pub placement: Placement,
    /// One line saying which state (and, for `n ≥ 3`, which member of the family) they are.
    pub note: String,
}

/// The mass properties of the whole rotor ([module docs](self)), SI (or the papers' units for a
/// dimensionless config: `M_s = 1`, `ρ_s = 1`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MassProperties {
    /// Total mass `M`.
    pub total_mass: f64,
    /// Centre of mass `(x, y, z)`, rotor frame (`z` in the config's axial coordinate).
    pub centre_of_mass: [f64; 3],
    /// Inertia tensor about the centre of mass, rotor frame (symmetric).
    pub inertia: [[f64; 3]; 3],
    /// Principal moments, descending.
    pub principal_moments: [f64; 3],
    /// The principal moment whose axis is nearest the shaft.
    pub polar_moment: f64,
    /// The other two, larger first.
    pub equatorial_moments: [f64; 2],
    /// Unit principal axis nearest the shaft (`z ≥ 0`).
    pub principal_axis: [f64; 3],
    /// Its angle from the shaft (rad).
    pub axis_tilt: f64,
    /// Direction of that tilt in the rotor frame, from the body x axis (rad; 0 without tilt).
    pub axis_tilt_angle: f64,
    /// Residual static unbalance `M (c_x, c_y)` (kg·m).
    pub static_unbalance: [f64; 2],
    /// Residual couple about the centre of mass `(−I_xz, −I_yz)` (kg·m²).
    pub couple_unbalance: [f64; 2],
}

/// Eigenvalues and eigenvectors (columns) of a symmetric 3×3 matrix by cyclic Jacobi rotations.
fn jacobi(a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut a = a;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..64 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diag = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= f64::EPSILON * 1e-3 * diag || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J with J the rotation in the (p, q) plane
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

impl SpatialRotor {
    /// The mass properties of the whole rotor with its balls at `ball_angles` (rotor frame,
    /// rad; one per ball of the planes with balls, in order): the formulas of the
    /// [module docs](super::mass_properties). Errors name `ball_angles` when their count is not
    /// the number of balls or one is not finite.
    pub fn mass_properties(&self, ball_angles: &[f64]) -> Result<MassProperties> {
        if ball_angles.len() != self.balls() {
            return Err(Error::invalid("ball_angles", format!("expected {} angles (one per ball), got {}", self.balls(), ball_angles.len())));
        }
        if let Some(a) = ball_angles.iter().find(|a| !a.is_finite()) {
            return Err(Error::invalid("ball_angles", format!("must be finite, got {a}")));
        }
        let r = &self.rotor;
        // point masses: (m, [x, y, z])
        let mut points: Vec<(f64, [f64; 3])> = self.unbalances.iter().map(|u| (u.mass, [u.radius * u.angle.cos(), u.radius * u.angle.sin(), u.z])).collect();
        let mut k = 0;
        for p in self.planes.iter().filter(|p| p.n > 0) {
            for &a in &ball_angles[k..k + p.n] {
                points.push((p.ball_mass, [p.race_radius * a.cos(), p.race_radius * a.sin(), p.z]));
            }
            k += p.n;
        }
        let total = r.mass + points.iter().map(|(m, _)| m).sum::<f64>();
        let mut c = [0.0, 0.0, r.mass * r.z];
        for (m, p) in &points {
            for i in 0..3 {
                c[i] += m * p[i];
            }
        }
        c.iter_mut().for_each(|x| *x /= total);
        let e = [r.axis_tilt.sin() * r.axis_tilt_angle.cos(), r.axis_tilt.sin() * r.axis_tilt_angle.sin(), r.axis_tilt.cos()];
        let mut inertia = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                inertia[i][j] = (r.polar_moment - r.equatorial_moment) * e[i] * e[j] + if i == j { r.equatorial_moment } else { 0.0 };
            }
        }
        let mut add_point = |m: f64, p: [f64; 3]| {
            let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
            let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            for i in 0..3 {
                for j in 0..3 {
                    inertia[i][j] += m * (if i == j { d2 } else { 0.0 } - d[i] * d[j]);
                }
            }
        };
        add_point(r.mass, [0.0, 0.0, r.z]);
        for (m, p) in &points {
            add_point(*m, *p);
        }
        // symmetric by construction; make it so to the bit
        for i in 0..3 {
            for j in 0..i {
                inertia[i][j] = inertia[j][i];
            }
        }
        let (vals, vecs) = jacobi(inertia);
        let axis_of = |k: usize| [vecs[0][k], vecs[1][k], vecs[2][k]];
        let polar_k = (0..3).max_by(|&a, &b| vecs[2][a].abs().total_cmp(&vecs[2][b].abs())).unwrap_or(2);
        let mut u = axis_of(polar_k);
        if u[2] < 0.0 {
            u.iter_mut().for_each(|x| *x = -*x);
        }
        let mut eq: Vec<f64> = (0..3).filter(|&k| k != polar_k).map(|k| vals[k]).collect();
        eq.sort_by(|a, b| b.total_cmp(a));
        let mut pm = vals;
        pm.sort_by(|a, b| b.total_cmp(a));
        let across = u[0].hypot(u[1]);
        let tilt = across.atan2(u[2]);
        Ok(MassProperties {
            total_mass: total,
            centre_of_mass: c,
            inertia,
            principal_moments: pm,
            polar_moment: vals[polar_k],
            equatorial_moments: [eq[0], eq[1]],
            principal_axis: u,
            axis_tilt: tilt,
            axis_tilt_angle: if across > 0.0 { u[1].atan2(u[0]) } else { 0.0 },
            static_unbalance: [total * c[0], total * c[1]],
            couple_unbalance: [-inertia[0][2], -inertia[1][2]],
        })
    }

    /// Where the balls of every plane sit at the balanced state, by the closed form of
    /// [`SpatialField::balanced_guess`](super::SpatialField::balanced_guess): one plane takes
    /// `−s0` (the unbalance masses' static unbalance), two planes at `ζ_1 ≠ ζ_2` (from the
    /// reference point) take `b_1 = (ζ_2 s0 − c0)/(ζ_1 − ζ_2)`, `b_2 = −s0 − b_1` (static and
    /// couple `c0` cancelled, Rodrigues et al. 2008), each as the arc of equally spaced balls of
    /// [`arc_angles`] (for `n ≥ 3` one member of the family: the one the simulation and the
    /// general route of `stability` use). Where a plane's capacity falls short, the balls of
    /// that plane are bunched towards its share ([`Placement`] says which case).
    pub fn balanced_ball_angles(&self) -> BallPlacement {
        let planes: Vec<_> = self.planes.iter().filter(|p| p.n > 0).collect();
        let s0 = self.static_unbalance();
        let member =
            |n: usize| if n >= 3 { " (n ≥ 3: the member with each plane's balls in an equally spaced arc, as the simulation's balanced state)" } else { "" };
        let bunched = |n: usize, t: [f64; 2]| vec![t[1].atan2(t[0]); n];
        match planes.len() {
            0 => BallPlacement { angles: vec![], placement: Placement::NoBalls, note: "no balls".into() },
            1 => {
                let p = planes[0];
                let t = [-s0[0], -s0[1]];
                match arc_angles(p.n, p.ball_mass * p.race_radius, t) {
                    Some(a) => {
                        let couple = if self.unbalances.len() > 1 || self.rotor.axis_tilt != 0.0 {
                            "; one plane cannot cancel a couple unbalance: it remains"
                        } else {
                            ""
                        };
                        BallPlacement {
                            angles: a,
                            placement: Placement::Balanced,
                            note: format!("balanced state: the balls cancel the static unbalance{}{couple}", member(p.n)),
                        }
                    }
                    None => {
                        let cap = p.n as f64 * p.ball_mass * p.race_radius;
                        let need = s0[0].hypot(s0[1]);
                        BallPlacement {
                            angles: bunched(p.n, t),
                            placement: Placement::PartiallyBalanced,
                            note: format!(
                                "no balanced state: the capacity n m R = {} kg·m differs from the static unbalance {} kg·m{}; the balls are bunched opposite it (the partially balanced state)",
                                crate::error::fmt_num(cap),
                                crate::error::fmt_num(need),
                                if p.n == 1 { " (one ball balances only an equal unbalance)" } else { "" }
                            ),
                        }
                    }
                }
            }
            2 => {
                let zr = self.z_reference();
                let (z1, z2) = (planes[0].z - zr, planes[1].z - zr);
                let c0 = self.couple_unbalance();
                let shares = if z1 == z2 {
                    None
                } else {
                    let b1 = [(z2 * s0[0] - c0[0]) / (z1 - z2), (z2 * s0[1] - c0[1]) / (z1 - z2)];
                    Some([b1, [-s0[0] - b1[0], -s0[1] - b1[1]]])
                };
                let Some(shares) = shares else {
                    let half = [-0.5 * s0[0], -0.5 * s0[1]];
                    let angles = planes.iter().flat_map(|p| bunched(p.n, half)).collect();
                    return BallPlacement {
                        angles,
                        placement: Placement::Bunched,
                        note: "no balanced state computed: the two ball planes are at one axial position; the balls are bunched opposite the static unbalance"
                            .into(),
                    };
                };
                let mut angles = vec![];
                let mut short = vec![];
                for (k, (p, t)) in planes.iter().zip(shares).enumerate() {
                    match arc_angles(p.n, p.ball_mass * p.race_radius, t) {
                        Some(a) => angles.extend(a),
                        None => {
                            short.push(format!(
                                "plane {} (capacity {} kg·m, share {} kg·m)",
                                k + 1,
                                crate::error::fmt_num(p.n as f64 * p.ball_mass * p.race_radius),
                                crate::error::fmt_num(t[0].hypot(t[1]))
                            ));
                            angles.extend(bunched(p.n, t));
                        }
                    }
                }
                if short.is_empty() {
                    let n = planes.iter().map(|p| p.n).max().unwrap_or(0);
                    BallPlacement {
                        angles,
                        placement: Placement::Balanced,
                        note: format!("balanced state: the two planes cancel the static and the couple unbalance{}", member(n)),
                    }
                } else {
                    BallPlacement {
                        angles,
                        placement: Placement::Bunched,
                        note: format!(
                            "no balanced state: {} cannot carry its share of the static and couple unbalance; its balls are bunched towards the share (a placement: the partially balanced state itself is `autobal::rotor_partial`, and the general route of `stability` starts from this placement)",
                            short.join(" and ")
                        ),
                    }
                }
            }
            _ => BallPlacement {
                angles: planes.iter().flat_map(|p| bunched(p.n, [-s0[0], -s0[1]])).collect(),
                placement: Placement::Bunched,
                note: "no balanced state computed for more than two ball planes: the balls are bunched opposite the static unbalance".into(),
            },
        }
    }
}
