//! The equations of motion of the spatial rotor with balls, in axes turning with the rotor
//! (docs/notes/spatial.md derives them).
//!
//! Coordinates `q = (ξ, η, δ, θ, φ, ψ_1..N)`: the frame F turns by `φ` about the fixed
//! bearing axis z; `u = (ξ, η, 0)` is the displacement of the reference point O (the axis point
//! at the composite's centre of mass C) in F; the tilt is `R_t = R_x(δ) R_y(θ)` relative to F,
//! so that a body point with body coordinates `ρ` sits at `R_z(φ) (u + R_t ρ)` in fixed axes;
//! ball j sits at `ρ_j = (R cos ψ_j, R sin ψ_j, ζ_p)`. Nothing is linearised: the kinetic
//! energy is exact for any tilt (up to the chart's singularity at `δ = ±90°`) and any ball
//! angle. A steady synchronous whirl (`φ̇` constant, everything else at rest) is a fixed point.
//!
//! With `ω = (δ̇, θ̇ cos δ, φ̇ + θ̇ sin δ)` the body's angular velocity and `v_O` the velocity of
//! O (both in F components), the partial velocities are `V_k = ∂v_O/∂q̇_k`, `G_k = ∂ω/∂q̇_k`;
//! d'Alembert–Lagrange gives, for each rotor coordinate `k`,
//!
//! ```text
//! V_k · (Σ m a) + G_k · (Σ m r × a) = V_k · F_ext + G_k · T_ext (+ drive torque for φ)
//! m t_j · a_j = −h_A R² ψ̇_j + m g · t_j                          (ball j, t_j = ∂r_j/∂ψ_j)
//! ```
//!
//! with the carrier's inertia forces `Σ m a = M a_O + α × s + ω × (ω × s)`,
//! `Σ m r × a = s × a_O + J α + ω × (J ω)` (`s`, `J`: first moment and inertia tensor about O)
//! and each ball's acceleration
//! `a_j = a_O + α × r_j + ω × (ω × r_j) + 2 ψ̇_j ω × t_j + ψ̇_j² n_j + ψ̈_j t_j`.
//! The mass matrix is an arrow: a dense 5×5 rotor block, one column per ball, and the
//! diagonal `m R²` of the balls; the rotor accelerations come from the 5×5 Schur complement,
//! so the cost is linear in the number of balls.
//!
//! ## One computation for values and derivatives
//! The generalised forces at `q̈ = 0` (`Q`, rotor rows, and the balls' `b_j`) and the mass
//! matrix's blocks (rotor block `M_rr`, ball rows `B_j`, diagonal `m R²`) come from one
//! function generic over the number type ([`Real`]): on `f64` it feeds the right-hand side
//! (Schur complement solve); on [`Dual`] numbers it gives the residual
//! `R(y) = Q(y) − M(y) q̈0` with `q̈0` the accelerations at `y` held constant, whose exact
//! derivative gives the Jacobian `∂q̈/∂y = M⁻¹ ∂R/∂y` (exact at the solution, where `R = 0`:
//! `∂(M⁻¹Q)/∂y = M⁻¹(∂Q/∂y − (∂M/∂y) M⁻¹Q)`), see [`Equations::exact_jacobian`].

#![allow(clippy::needless_range_loop)] // index loops read as the formulas

use super::rotor::SpatialRotor;
use crate::balls::BallForces;
use crate::drive::Drive;
use crate::error::{Error, Result};
use crate::ode::dual::{Dual, Real};
use crate::ode::System;
use std::cell::RefCell;

type V3<T> = [T; 3];
type M3<T> = [[T; 3]; 3];

#[inline(always)]
fn cross<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
#[inline(always)]
fn dot<T: Real>(a: V3<T>, b: V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline(always)]
fn add<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline(always)]
fn sub<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline(always)]
fn scale<T: Real>(a: V3<T>, s: T) -> V3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline(always)]
fn scalef<T: Real>(a: V3<T>, s: f64) -> V3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline(always)]
fn mat_vec<T: Real>(m: &M3<T>, v: V3<T>) -> V3<T> {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
/// `m v` for a constant vector `v`.
#[inline(always)]
fn mat_vecf<T: Real>(m: &M3<T>, v: [f64; 3]) -> V3<T> {
    let row = |r: [T; 3]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    [row(m[0]), row(m[1]), row(m[2])]
}
/// `Σ m (|r|² I − r rᵀ)` increment for a point mass.
#[inline(always)]
fn add_point_inertia<T: Real>(j: &mut M3<T>, m: f64, r: V3<T>) {
    let r2 = dot(r, r);
    for a in 0..3 {
        for b in 0..3 {
            let d = if a == b { r2 } else { T::cst(0.0) } - r[a] * r[b];
            j[a][b] = j[a][b] + d * m;
        }
    }
}

/// Ball `b` at angle `ψ`: its position `r = R_t (R cos ψ, R sin ψ, ζ)` from O, the tangent
/// `t = ∂r/∂ψ = R_t (−R sin ψ, R cos ψ, 0)` and `n = ∂t/∂ψ = −R_t (R cos ψ, R sin ψ, 0)`, in F
/// components. The in-plane part `p = R_t (R cos ψ, R sin ψ, 0)` is formed once (`r = p +
/// ζ R_t e_z`, `n = −p`) and the zero third terms are not multiplied: the same sums in the same
/// order as the full products `R_t v` (so the same numbers, up to the sign of a zero).
#[inline(always)]
fn ball_geometry<T: Real>(k: &Kin<T>, b: &Ball, psi: T) -> (V3<T>, V3<T>, V3<T>) {
    let (sp, cp) = psi.sin_cos_fast();
    let (x, y) = (cp * b.r, sp * b.r);
    let rt = &k.rt;
    let p = [rt[0][0] * x + rt[0][1] * y, rt[1][0] * x + rt[1][1] * y, rt[2][0] * x + rt[2][1] * y];
    let r = [p[0] + rt[0][2] * b.zeta, p[1] + rt[1][2] * b.zeta, p[2] + rt[2][2] * b.zeta];
    let ny = -y;
    let t = [rt[0][0] * ny + rt[0][1] * x, rt[1][0] * ny + rt[1][1] * x, rt[2][0] * ny + rt[2][1] * x];
    (r, t, [-p[0], -p[1], -p[2]])
}

/// `(V_c·f + G_c·τ)` for the five rotor coordinates `c`: the generalised force of a force `f`
/// and a moment `τ` about O (or, with `f = t_j`, `τ = r_j × t_j`, ball `j`'s row of the mass
/// matrix over its mass). The partial velocities are sparse: `V = (e_x, e_y, 0, 0, (−η, ξ, 0))`,
/// `G = (0, 0, e_x, (0, cos δ, sin δ), e_z)` ([`Model::kin`]), so the dot products reduce to
/// their nonzero terms, added in the same order (the dropped terms are exact zeros: the same
/// number as the full dot products, up to the sign of a zero).
#[inline(always)]
fn partial_sums<T: Real>(k: &Kin<T>, f: V3<T>, tau: V3<T>) -> [T; ROTOR_COORDS] {
    let (neta, xi) = (k.v[4][0], k.v[4][1]);
    [f[0], f[1], tau[0], k.cd * tau[1] + k.sd * tau[2], (neta * f[0] + xi * f[1]) + tau[2]]
}

/// The rotor block of the mass matrix, `M_ab = (V_a·V_b) m + V_a·(G_b × s) + V_b·(G_a × s) +
/// G_a·(J G_b)` (`m`, `s`, `J`: total mass, first moment and inertia tensor about O, balls
/// included), written out for the sparse partial velocities of [`partial_sums`] term by term
/// in the order of the full sum (so the same numbers up to the sign of a zero).
#[inline(always)]
fn rotor_block<T: Real>(k: &Kin<T>, mt: f64, s: V3<T>, j: &M3<T>) -> [[T; ROTOR_COORDS]; ROTOR_COORDS] {
    let (neta, xi) = (k.v[4][0], k.v[4][1]);
    let (sd, cd) = (k.sd, k.cd);
    let zero = T::cst(0.0);
    // G_3 × s and J G_3 (G_3 = (0, cos δ, sin δ)); G_2 × s = (0, −s_z, s_y), G_4 × s = (−s_y, s_x, 0)
    let gxs3 = [cd * s[2] - sd * s[1], sd * s[0], -(cd * s[0])];
    let jg3 = [j[0][1] * cd + j[0][2] * sd, j[1][1] * cd + j[1][2] * sd, j[2][1] * cd + j[2][2] * sd];
    // V_4·(G_4 × s)
    let v4g4 = neta * -s[1] + xi * s[0];
    let m00 = T::cst(mt);
    let m03 = gxs3[0];
    let m04 = neta * mt + -s[1];
    let m12 = -s[2];
    let m13 = gxs3[1];
    let m14 = xi * mt + s[0];
    let m22 = j[0][0];
    let m23 = jg3[0];
    let m24 = xi * -s[2] + j[0][2];
    let m33 = cd * jg3[1] + sd * jg3[2];
    let m34 = (neta * gxs3[0] + xi * gxs3[1]) + (cd * j[1][2] + sd * j[2][2]);
    let m44 = (neta * neta + xi * xi) * mt + v4g4 + v4g4 + j[2][2];
    [[m00, zero, zero, m03, m04], [zero, m00, m12, m13, m14], [zero, m12, m22, m23, m24], [m03, m13, m23, m33, m34], [m04, m14, m24, m34, m44]]
}

/// `x` of `A x = b` (in place in `b`) for the leading `N × N` block of `A`, symmetric positive
/// definite (the Schur complement of the mass matrix on the free rotor coordinates: kinetic
/// energy), by `LDLᵀ` without pivoting, which is backward stable for such matrices (Higham,
/// *Accuracy and Stability of Numerical Algorithms*, 2nd ed., §10.1); only the lower triangle is
/// read. `false` when a pivot is not positive and finite (not positive definite, or a
/// non-finite state): the caller then reports a non-finite derivative.
#[inline(always)]
fn solve_spd<const N: usize>(a: &[[f64; ROTOR_COORDS]; ROTOR_COORDS], b: &mut [f64; ROTOR_COORDS]) -> bool {
    // l[i][k] = L_ik below the diagonal; ld[i][k] = L_ik d_k
    let mut l = [[0.0; N]; N];
    let mut ld = [[0.0; N]; N];
    let mut d = [0.0; N];
    for j in 0..N {
        let mut dj = a[j][j];
        for k in 0..j {
            dj -= ld[j][k] * l[j][k];
        }
        if !(dj > 0.0 && dj.is_finite()) {
            return false;
        }
        d[j] = dj;
        for i in j + 1..N {
            let mut v = a[i][j];
            for k in 0..j {
                v -= ld[i][k] * l[j][k];
            }
            ld[i][j] = v;
            l[i][j] = v / dj;
        }
    }
    for i in 0..N {
        for k in 0..i {
            b[i] -= l[i][k] * b[k];
        }
    }
    for i in 0..N {
        b[i] /= d[i];
    }
    for i in (0..N).rev() {
        for k in i + 1..N {
            b[i] -= l[k][i] * b[k];
        }
    }
    true
}

/// Number of rotor coordinates `(ξ, η, δ, θ, φ)`.
pub const ROTOR_COORDS: usize = 5;
/// Index of the spin angle `φ` among the coordinates.
pub const PHI: usize = 4;

#[derive(Debug, Clone, Copy)]
pub(super) struct Ball {
    pub(super) m: f64,
    pub(super) r: f64,
    pub(super) zeta: f64,
    drag: f64,
}

#[derive(Debug, Clone, Copy)]
struct SupportAt {
    zeta: f64,
    k: [f64; 2],
    c: [f64; 2],
}

/// How the spin enters the equations at one instant: prescribed (`φ̇`, `φ̈` given, the `φ`
/// row dropped) or free under a torque `M(t, φ̇)` (its value and slope `∂M/∂φ̇` at the state).
#[derive(Debug, Clone, Copy)]
pub(super) enum Spin {
    /// `φ̇ = rate`, `φ̈ = acc`.
    Prescribed { rate: f64, acc: f64 },
    /// `φ̇` from the state; drive torque and its slope at that `φ̇`.
    Free { torque: f64, slope: f64 },
}

/// Everything the equations need of a rotor, owned (computed once): carrier mass properties
/// about O, balls and supports in body axial coordinates, gravity, spin drag, locked tilt.
#[derive(Debug, Clone)]
pub(super) struct Model {
    carrier_mass: f64,
    carrier_first: [f64; 3],
    carrier_inertia: [[f64; 3]; 3],
    total_mass: f64,
    pub(super) balls: Vec<Ball>,
    supports: Vec<SupportAt>,
    z_ref: f64,
    gravity: [f64; 3],
    spin_drag: f64,
    lock_tilt: bool,
}

/// Scratch of the right-hand side: ball rows of the mass matrix, ball forces, normal forces.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    brow: Vec<[f64; ROTOR_COORDS]>,
    bf: Vec<f64>,
    normal: Vec<f64>,
    /// Real balls' generalised forces of one plane.
    qb: Vec<f64>,
}

impl Scratch {
    pub(super) fn new(balls: usize, real_balls: bool) -> RefCell<Self> {
        let real = if real_balls { balls } else { 0 };
        RefCell::new(Scratch { brow: vec![[0.0; ROTOR_COORDS]; balls], bf: vec![0.0; balls], normal: vec![0.0; real], qb: vec![0.0; real] })
    }
}

/// Body-frame quantities of the rigid carrier (rotor + unbalance masses) about O:
/// mass, first moment `S = Σ m ρ`, inertia tensor `J = Σ m (|ρ|² I − ρ ρᵀ)` (rotor's own tensor
/// `A I + (C − A) e eᵀ` about G, `e` its principal axis, moved to O).
fn carrier(rotor: &SpatialRotor, z_ref: f64) -> (f64, [f64; 3], [[f64; 3]; 3]) {
    let r = &rotor.rotor;
    let (sk, ck) = r.axis_tilt.sin_cos();
    let (sb, cb) = r.axis_tilt_angle.sin_cos();
    let e = [sk * cb, sk * sb, ck];
    let mut j = [[0.0; 3]; 3];
    for a in 0..3 {
        for b in 0..3 {
            j[a][b] = if a == b { r.equatorial_moment } else { 0.0 } + (r.polar_moment - r.equatorial_moment) * e[a] * e[b];
        }
    }
    let d = [0.0, 0.0, r.z - z_ref];
    add_point_inertia(&mut j, r.mass, d);
    let mut s = scalef(d, r.mass);
    let mut m = r.mass;
    for u in &rotor.unbalances {
        let rho = [u.radius * u.angle.cos(), u.radius * u.angle.sin(), u.z - z_ref];
        add_point_inertia(&mut j, u.mass, rho);
        s = add(s, scalef(rho, u.mass));
        m += u.mass;
    }
    (m, s, j)
}

/// Kinematics of one state shared by the right-hand side and the energy.
struct Kin<T> {
    u: V3<T>,
    v_o: V3<T>,
    w: V3<T>,
    rt: M3<T>,
    /// Partial velocities `V_c = ∂v_O/∂q̇_c` (those of the angular velocity, `G_c = ∂ω/∂q̇_c`,
    /// are `(0, 0, e_x, (0, cos δ, sin δ), e_z)`: [`partial_sums`]).
    v: [V3<T>; ROTOR_COORDS],
    phi_d: T,
    sd: T,
    cd: T,
}

impl Model {
    pub(super) fn new(rotor: &SpatialRotor) -> Self {
        let z_ref = rotor.z_reference();
        let (carrier_mass, carrier_first, carrier_inertia) = carrier(rotor, z_ref);
        let balls =
            rotor.planes.iter().flat_map(|p| (0..p.n).map(move |_| Ball { m: p.ball_mass, r: p.race_radius, zeta: p.z - z_ref, drag: p.drag })).collect();
        let supports = rotor.supports.iter().map(|s| SupportAt { zeta: s.z - z_ref, k: s.stiffness, c: s.damping }).collect();
        Model {
            carrier_mass,
            carrier_first,
            carrier_inertia,
            total_mass: rotor.total_mass(),
            balls,
            supports,
            z_ref,
            gravity: rotor.gravity,
            spin_drag: rotor.spin_drag,
            lock_tilt: rotor.lock_tilt,
        }
    }

    /// Number of generalised coordinates `5 + N`.
    pub(super) fn coords(&self) -> usize {
        ROTOR_COORDS + self.balls.len()
    }

    /// Which rotor coordinates are integrated (not prescribed, not locked).
    fn free(&self, prescribed: bool) -> [bool; ROTOR_COORDS] {
        let tilt = !self.lock_tilt;
        [true, true, tilt, tilt, !prescribed]
    }

    #[inline(always)]
    fn kin<T: Real>(&self, y: &[T], phi_d: T) -> Kin<T> {
        let nc = self.coords();
        let (xi, eta, de, th) = (y[0], y[1], y[2], y[3]);
        let (xid, etad, ded, thd) = (y[nc], y[nc + 1], y[nc + 2], y[nc + 3]);
        let (sd, cd) = de.sin_cos_fast();
        let (st, ct) = th.sin_cos_fast();
        let (zero, one) = (T::cst(0.0), T::cst(1.0));
        let rt = [[ct, zero, st], [sd * st, cd, -(sd * ct)], [-(cd * st), sd, cd * ct]];
        let u = [xi, eta, zero];
        let v_o = [xid - phi_d * eta, etad + phi_d * xi, zero];
        let w = [ded, thd * cd, phi_d + thd * sd];
        let z = [zero; 3];
        let v = [[one, zero, zero], [zero, one, zero], z, z, [-eta, xi, zero]];
        Kin { u, v_o, w, rt, v, phi_d, sd, cd }
    }

    #[inline(always)]
    fn ball_geometry<T: Real>(&self, k: &Kin<T>, b: &Ball, psi: T) -> (V3<T>, V3<T>, V3<T>) {
        ball_geometry(k, b, psi)
    }

    /// First moment `s` and inertia tensor `J` of the carrier about O in F components.
    #[inline(always)]
    fn carrier_in_f<T: Real>(&self, k: &Kin<T>) -> (V3<T>, M3<T>) {
        let s = mat_vecf(&k.rt, self.carrier_first);
        // J = R_t J_b R_tᵀ
        let zero = T::cst(0.0);
        let mut rj = [[zero; 3]; 3];
        for a in 0..3 {
            for b in 0..3 {
                let ji = &self.carrier_inertia;
                rj[a][b] = k.rt[a][0] * ji[0][b] + k.rt[a][1] * ji[1][b] + k.rt[a][2] * ji[2][b];
            }
        }
        let mut j = [[zero; 3]; 3];
        for a in 0..3 {
            for b in 0..3 {
                j[a][b] = rj[a][0] * k.rt[b][0] + rj[a][1] * k.rt[b][1] + rj[a][2] * k.rt[b][2];
            }
        }
        (s, j)
    }

    /// Lateral position and velocity of the shaft point at body axial coordinate `zeta`, in F
    /// components: `(ρ, r, v)` with `ρ = R_t ζ e_z`, `r = u + ρ` (its third component is axial).
    #[inline(always)]
    fn shaft_point<T: Real>(&self, k: &Kin<T>, zeta: f64) -> (V3<T>, V3<T>, V3<T>) {
        let rho = [k.rt[0][2] * zeta, k.rt[1][2] * zeta, k.rt[2][2] * zeta];
        let r = add(k.u, rho);
        let v = add(k.v_o, cross(k.w, rho));
        (rho, r, v)
    }

    /// The generalised forces at `q̈ = 0` and the mass matrix at a state `y` (full state, any
    /// number type), the known `φ̈` of a prescribed spin moved to the forces:
    /// returns the rotor rows `Q` and the rotor block `M_rr`; writes ball `j`'s row of the
    /// mass matrix `B_j = m (V_c·t_j + G_c·(r_j × t_j))` into `brow[j]`, its force
    /// `b_j = −h_A R² ψ̇_j + m g·t_j − t_j·(m a_j|_{q̈=0})` into `bf[j]` and, when `normal` is not
    /// empty, the race's normal force `m a_j·n_j/R` (real balls) into `normal[j]`. The
    /// equations are `M_rr q̈ + Σ_j B_jᵀ ψ̈_j = Q`, `B_j q̈ + m R² ψ̈_j = b_j` (balls' diagonal
    /// constant), restricted to the free rotor coordinates.
    #[inline(always)]
    fn forces<T: Real>(
        &self,
        spin: Spin,
        y: &[T],
        brow: &mut [[T; ROTOR_COORDS]],
        bf: &mut [T],
        normal: &mut [T],
    ) -> ([T; ROTOR_COORDS], [[T; ROTOR_COORDS]; ROTOR_COORDS]) {
        let nc = self.coords();
        let phi_d = match spin {
            Spin::Prescribed { rate, .. } => T::cst(rate),
            Spin::Free { .. } => y[nc + PHI],
        };
        let k = self.kin(y, phi_d);
        let (ded, thd) = (y[nc + 2], y[nc + 3]);
        let (sd, cd) = (k.sd, k.cd);
        let (xid, etad) = (y[nc], y[nc + 1]);
        let zero = T::cst(0.0);
        // accelerations with q̈ = 0
        let a_o = [-(phi_d * etad * 2.0) - phi_d * phi_d * y[0], phi_d * xid * 2.0 - phi_d * phi_d * y[1], zero];
        let alpha = [-(phi_d * thd * cd), -(thd * ded * sd) + phi_d * ded, thd * ded * cd];
        let (s, j) = self.carrier_in_f(&k);
        let w = k.w;
        let mc = self.carrier_mass;
        let mut f_in = add(add(scalef(a_o, mc), cross(alpha, s)), cross(w, cross(w, s)));
        let mut t_in = add(add(cross(s, a_o), mat_vec(&j, alpha)), cross(w, mat_vec(&j, w)));
        let mut s_tot = s;
        let mut j_tot = j;
        let (sp, cp) = y[PHI].sin_cos_fast();
        let gr = self.gravity;
        let g_f = [cp * gr[0] + sp * gr[1], -(sp * gr[0]) + cp * gr[1], T::cst(gr[2])];
        // balls: inertia forces, rows of the arrow
        let real_balls = !normal.is_empty();
        for (i, b) in self.balls.iter().enumerate() {
            let psi_d = y[nc + ROTOR_COORDS + i];
            let (r, t_j, n_j) = self.ball_geometry(&k, b, y[ROTOR_COORDS + i]);
            let a_j = add(add(add(a_o, cross(alpha, r)), cross(w, cross(w, r))), add(scale(cross(w, t_j), psi_d * 2.0), scale(n_j, psi_d * psi_d)));
            let ma = scalef(a_j, b.m);
            f_in = add(f_in, ma);
            t_in = add(t_in, cross(r, ma));
            s_tot = add(s_tot, scalef(r, b.m));
            add_point_inertia(&mut j_tot, b.m, r);
            brow[i] = partial_sums(&k, t_j, cross(r, t_j)).map(|x| x * b.m);
            bf[i] = psi_d * (-b.drag * b.r * b.r) + dot(g_f, t_j) * b.m - dot(t_j, ma);
            if real_balls {
                // the race's normal force: the centripetal part of the ball's acceleration
                // (n_j = −R e_r), the terms in q̈ left out as in the planar model
                normal[i] = dot(ma, n_j) / b.r;
            }
        }
        // external forces and moments about O: gravity and supports
        let mut f_ex = scalef(g_f, self.total_mass);
        let mut t_ex = cross(s_tot, g_f);
        for sup in &self.supports {
            let (rho, r, v) = self.shaft_point(&k, sup.zeta);
            let (x, yy) = (cp * r[0] - sp * r[1], sp * r[0] + cp * r[1]);
            let (vx, vy) = (cp * v[0] - sp * v[1], sp * v[0] + cp * v[1]);
            let (fx, fy) = (x * -sup.k[0] - vx * sup.c[0], yy * -sup.k[1] - vy * sup.c[1]);
            let f = [cp * fx + sp * fy, -(sp * fx) + cp * fy, zero];
            f_ex = add(f_ex, f);
            t_ex = add(t_ex, cross(rho, f));
        }
        let (df, dt_) = (sub(f_ex, f_in), sub(t_ex, t_in));
        let mut q = partial_sums(&k, df, dt_);
        // rotor block of the mass matrix
        let m = rotor_block(&k, self.total_mass, s_tot, &j_tot);
        match spin {
            Spin::Prescribed { acc, .. } => {
                for c in 0..ROTOR_COORDS {
                    q[c] = q[c] - m[c][PHI] * acc;
                }
                for i in 0..self.balls.len() {
                    bf[i] = bf[i] - brow[i][PHI] * acc;
                }
            }
            Spin::Free { torque, slope } => {
                // M(φ̇) to first order about the state's φ̇ (exact value, exact slope)
                let mut drive = T::cst(torque);
                if slope != 0.0 {
                    drive = drive + (phi_d - T::cst(phi_d.value())) * slope;
                }
                q[PHI] = q[PHI] + (drive - phi_d * self.spin_drag);
            }
        }
        (q, m)
    }

    /// The right-hand side `dy` at the full state `y`: [`Model::forces`] on `f64`, real-ball
    /// forces added, then the arrow solved by its Schur complement on the free rotor coordinates.
    #[inline(always)]
    pub(super) fn rhs(&self, spin: Spin, y: &[f64], dy: &mut [f64], ball_forces: &[(usize, BallForces)], scratch: &RefCell<Scratch>) {
        let nc = self.coords();
        let nb = self.balls.len();
        let mut guard = scratch.borrow_mut();
        let Scratch { brow, bf, normal, qb } = &mut *guard;
        let (q, m) = self.forces::<f64>(spin, y, brow, bf, normal);
        // real balls: contact and rolling resistance, generalised forces on the ball angles
        for (first, f) in ball_forces {
            let (a, e) = (*first, first + f.n);
            f.torques(&y[ROTOR_COORDS + a..ROTOR_COORDS + e], &y[nc + ROTOR_COORDS + a..nc + ROTOR_COORDS + e], |j| normal[a + j], &mut qb[..f.n]);
            for j in 0..f.n {
                bf[a + j] += qb[j];
            }
        }
        let prescribed = matches!(spin, Spin::Prescribed { .. });
        let (idx_buf, nf) = self.free_indices(prescribed);
        let idx = &idx_buf[..nf];
        let (a, mut rhs) = self.schur(&m, brow, idx, &q, bf);
        let ok = match nf {
            2 => solve_spd::<2>(&a, &mut rhs),
            3 => solve_spd::<3>(&a, &mut rhs),
            4 => solve_spd::<4>(&a, &mut rhs),
            5 => solve_spd::<5>(&a, &mut rhs),
            _ => {
                let mut a = a;
                crate::linalg::dense::solve_once(&mut a, &mut rhs, nf)
            }
        };
        let mut acc = [0.0; ROTOR_COORDS];
        for (ia, &ca) in idx.iter().enumerate() {
            acc[ca] = rhs[ia];
        }
        dy[..nc].copy_from_slice(&y[nc..2 * nc]);
        dy[nc..nc + ROTOR_COORDS].copy_from_slice(&acc);
        if let Spin::Prescribed { rate, acc } = spin {
            dy[PHI] = rate;
            dy[nc + PHI] = acc;
        }
        for i in 0..nb {
            let d = self.balls[i].m * self.balls[i].r * self.balls[i].r;
            let mut v = bf[i];
            for &c in idx {
                v -= brow[i][c] * acc[c];
            }
            dy[nc + ROTOR_COORDS + i] = v / d;
        }
        if !ok {
            dy.iter_mut().for_each(|v| *v = f64::NAN);
        }
    }

    /// The free rotor coordinates (not locked, `φ` unless prescribed) and their number.
    #[inline(always)]
    fn free_indices(&self, prescribed: bool) -> ([usize; ROTOR_COORDS], usize) {
        let free = self.free(prescribed);
        let mut idx_buf = [0usize; ROTOR_COORDS];
        let mut nf = 0;
        for c in 0..ROTOR_COORDS {
            if free[c] {
                idx_buf[nf] = c;
                nf += 1;
            }
        }
        (idx_buf, nf)
    }

    /// The Schur complement `A = M_ff − Σ_j B_jᵀ B_j/(m R²)` on the free coordinates `idx`
    /// and its right-hand side `Q_f − Σ_j B_jᵀ b_j/(m R²)`.
    #[inline(always)]
    fn schur(
        &self,
        m: &[[f64; ROTOR_COORDS]; ROTOR_COORDS],
        brow: &[[f64; ROTOR_COORDS]],
        idx: &[usize],
        q: &[f64; ROTOR_COORDS],
        bf: &[f64],
    ) -> ([[f64; ROTOR_COORDS]; ROTOR_COORDS], [f64; ROTOR_COORDS]) {
        let mut a = [[0.0; ROTOR_COORDS]; ROTOR_COORDS];
        let mut rhs = [0.0; ROTOR_COORDS];
        for (ia, &ca) in idx.iter().enumerate() {
            rhs[ia] = q[ca];
            for (ib, &cb) in idx.iter().enumerate() {
                a[ia][ib] = m[ca][cb];
            }
        }
        for (i, b) in self.balls.iter().enumerate() {
            let d = b.m * b.r * b.r;
            for (ia, &ca) in idx.iter().enumerate() {
                let bi = brow[i][ca] / d;
                rhs[ia] -= bi * bf[i];
                for (ib, &cb) in idx.iter().enumerate() {
                    a[ia][ib] -= bi * brow[i][cb];
                }
            }
        }
        (a, rhs)
    }

    /// The exact Jacobian columns `∂f/∂y_c` for the full-state indices `cols`, by forward
    /// differentiation of [`Model::forces`] (no real-ball forces): `jac[r * cols.len() + k]` is
    /// `∂f_r/∂y_{cols[k]}` for every row `r` of the full state (row-major
    /// `2(5 + N) × cols.len()`). `dy` is `f(y)` (from [`Model::rhs`]).
    ///
    /// With `q̈0` the accelerations in `dy`, the residual `R(y) = Q(y) − M(y) q̈0` (free rotor
    /// rows and ball rows) is differentiated in chunks of [`JAC_CHUNK`] directions; then
    /// `∂q̈/∂y_c = M⁻¹ ∂R/∂y_c` (Schur complement again). The first half of the rows is
    /// `∂q̇/∂y`: one where `y_c` is the rate itself, except the prescribed `φ̇`.
    pub(super) fn jacobian_columns(&self, spin: Spin, y: &[f64], dy: &[f64], cols: &[usize], jac: &mut [f64]) {
        let nc = self.coords();
        let nb = self.balls.len();
        let dim = 2 * nc;
        let ncol = cols.len();
        debug_assert_eq!(jac.len(), dim * ncol);
        jac.iter_mut().for_each(|v| *v = 0.0);
        let prescribed = matches!(spin, Spin::Prescribed { .. });
        // q̇ rows
        for (k, &c) in cols.iter().enumerate() {
            if c >= nc && !(prescribed && c == nc + PHI) {
                jac[(c - nc) * ncol + k] = 1.0;
            }
        }
        let (idx_buf, nf) = self.free_indices(prescribed);
        let idx = &idx_buf[..nf];
        let qdd = &dy[nc..];
        // f64 mass matrix (for the solve)
        let mut brow = vec![[0.0; ROTOR_COORDS]; nb];
        let mut bf = vec![0.0; nb];
        let (q, m) = self.forces::<f64>(spin, y, &mut brow, &mut bf, &mut []);
        let (a, _) = self.schur(&m, &brow, idx, &q, &bf);
        // residual derivatives, JAC_CHUNK directions at a time
        type D = Dual<JAC_CHUNK>;
        let mut yd: Vec<D> = y.iter().map(|&v| D::cst(v)).collect();
        let mut browd = vec![[D::cst(0.0); ROTOR_COORDS]; nb];
        let mut bfd = vec![D::cst(0.0); nb];
        let mut dr_rot = [[0.0; JAC_CHUNK]; ROTOR_COORDS];
        let mut dr_ball = vec![[0.0; JAC_CHUNK]; nb];
        for (chunk_no, chunk) in cols.chunks(JAC_CHUNK).enumerate() {
            for (s, &c) in chunk.iter().enumerate() {
                yd[c] = D::var(y[c], s);
            }
            let (q, md) = self.forces::<D>(spin, &yd, &mut browd, &mut bfd, &mut []);
            for &c in chunk {
                yd[c] = D::cst(y[c]);
            }
            // R = Q − M q̈0 on free rotor rows and ball rows
            for &ca in idx {
                let mut r = q[ca];
                for &cb in idx {
                    r = r - md[ca][cb] * qdd[cb];
                }
                for i in 0..nb {
                    r = r - browd[i][ca] * qdd[ROTOR_COORDS + i];
                }
                dr_rot[ca] = r.d;
            }
            // (the balls' diagonal m R² is constant: no derivative)
            for i in 0..nb {
                let mut r = bfd[i];
                for &cb in idx {
                    r = r - browd[i][cb] * qdd[cb];
                }
                dr_ball[i] = r.d;
            }
            // solve M x = ∂R/∂y_c for each direction of the chunk
            for s in 0..chunk.len() {
                let k = chunk_no * JAC_CHUNK + s;
                let mut rhs = [0.0; ROTOR_COORDS];
                for (ia, &ca) in idx.iter().enumerate() {
                    rhs[ia] = dr_rot[ca][s];
                }
                for (i, b) in self.balls.iter().enumerate() {
                    let d = b.m * b.r * b.r;
                    for (ia, &ca) in idx.iter().enumerate() {
                        rhs[ia] -= brow[i][ca] / d * dr_ball[i][s];
                    }
                }
                let mut aa = a;
                crate::linalg::dense::solve_once(&mut aa, &mut rhs, nf);
                let mut x = [0.0; ROTOR_COORDS];
                for (ia, &ca) in idx.iter().enumerate() {
                    x[ca] = rhs[ia];
                    jac[(nc + ca) * ncol + k] = rhs[ia];
                }
                for (i, b) in self.balls.iter().enumerate() {
                    let d = b.m * b.r * b.r;
                    let mut v = dr_ball[i][s];
                    for &c in idx {
                        v -= brow[i][c] * x[c];
                    }
                    jac[(nc + ROTOR_COORDS + i) * ncol + k] = v / d;
                }
            }
        }
    }
}

/// Directions differentiated together by [`Equations::exact_jacobian`] (the [`Dual`] width).
pub const JAC_CHUNK: usize = 8;

/// The equations of a [`SpatialRotor`] under a [`Drive`]; state
/// `y = (ξ, η, δ, θ, φ, ψ_1..N, ξ̇, η̇, δ̇, θ̇, φ̇, ψ̇_1..N)` (SI: m, rad, s).
#[derive(Debug, Clone)]
pub struct Equations<'a> {
    /// The rotor.
    pub rotor: &'a SpatialRotor,
    /// How it is driven.
    pub drive: &'a Drive,
    model: Model,
    /// Real-ball forces of each plane that has them switched on: (index of its first ball, forces).
    ball_forces: Vec<(usize, BallForces)>,
    scratch: RefCell<Scratch>,
}

impl<'a> Equations<'a> {
    /// Prepare the equations (the carrier's mass properties are computed once).
    pub fn new(rotor: &'a SpatialRotor, drive: &'a Drive) -> Self {
        let model = Model::new(rotor);
        // reference frequency of the default contact stiffness: the rotor's translation on its supports
        let w_ref = (model.supports.iter().map(|s| s.k[0]).sum::<f64>() / rotor.total_mass()).sqrt();
        let mut first = 0;
        let mut ball_forces = vec![];
        for p in &rotor.planes {
            if let Some(f) = BallForces::new(&p.physics, p.ball_mass, p.race_radius, p.n, w_ref) {
                ball_forces.push((first, f));
            }
            first += p.n;
        }
        let scratch = Scratch::new(model.balls.len(), !ball_forces.is_empty());
        Equations { rotor, drive, model, ball_forces, scratch }
    }

    /// The real-ball forces of the planes that have them switched on: (index of the plane's
    /// first ball among all balls, its forces); empty for point masses.
    pub fn ball_forces(&self) -> &[(usize, BallForces)] {
        &self.ball_forces
    }

    /// Number of generalised coordinates `5 + N`.
    pub fn coords(&self) -> usize {
        self.model.coords()
    }

    /// Axial position of the reference point O (= C).
    pub fn z_reference(&self) -> f64 {
        self.model.z_ref
    }

    /// Spin rate at `t`: prescribed by the drive, or the state's `φ̇`.
    pub fn spin_rate(&self, t: f64, y: &[f64]) -> f64 {
        if self.drive.prescribed() {
            self.drive.kinematics(t).0
        } else {
            y[self.coords() + PHI]
        }
    }

    /// The drive at `(t, y)` as the equations use it; `slope`: also `∂M/∂φ̇` (Jacobians).
    #[inline(always)]
    fn spin(&self, t: f64, y: &[f64], slope: bool) -> Spin {
        if self.drive.prescribed() {
            let (rate, acc) = self.drive.kinematics(t);
            Spin::Prescribed { rate, acc }
        } else {
            let w = y[self.coords() + PHI];
            Spin::Free { torque: self.drive.torque(t, w), slope: if slope { self.drive.torque_slope(t, w) } else { 0.0 } }
        }
    }

    fn kin(&self, t: f64, y: &[f64]) -> Kin<f64> {
        self.model.kin(y, self.spin_rate(t, y))
    }

    /// Total mechanical energy `T + V` (J): kinetic energy of carrier and balls, elastic
    /// energy of the supports, potential of gravity. For the energy-balance tests.
    pub fn energy(&self, t: f64, y: &[f64]) -> f64 {
        let nc = self.coords();
        let md = &self.model;
        let k = self.kin(t, y);
        let (s, j) = md.carrier_in_f(&k);
        let mut e = 0.5 * md.carrier_mass * dot(k.v_o, k.v_o) + dot(k.v_o, cross(k.w, s)) + 0.5 * dot(k.w, mat_vec(&j, k.w));
        let phi = y[PHI];
        let (sp, cp) = phi.sin_cos();
        let g = md.gravity;
        let g_f = [g[0] * cp + g[1] * sp, -g[0] * sp + g[1] * cp, g[2]];
        let mut first = add(scalef(k.u, md.carrier_mass), s);
        for (i, b) in md.balls.iter().enumerate() {
            let (r, t_j, _) = md.ball_geometry(&k, b, y[ROTOR_COORDS + i]);
            let v = add(add(k.v_o, cross(k.w, r)), scalef(t_j, y[nc + ROTOR_COORDS + i]));
            e += 0.5 * b.m * dot(v, v);
            first = add(first, scalef(add(k.u, r), b.m));
        }
        e -= dot(g_f, first);
        for sup in &md.supports {
            let (_, r, _) = md.shaft_point(&k, sup.zeta);
            let (x, yy) = (cp * r[0] - sp * r[1], sp * r[0] + cp * r[1]);
            e += 0.5 * (sup.k[0] * x * x + sup.k[1] * yy * yy);
        }
        e
    }

    /// Power dissipated by the dampers and the ball drag at a state (W, ≥ 0): for the power
    /// balance `dE/dt = P_drive − P_dissipated`.
    pub fn dissipated_power(&self, t: f64, y: &[f64]) -> f64 {
        let nc = self.coords();
        let md = &self.model;
        let k = self.kin(t, y);
        let (sp, cp) = y[PHI].sin_cos();
        let mut p = 0.0;
        for sup in &md.supports {
            let (_, _, v) = md.shaft_point(&k, sup.zeta);
            let (vx, vy) = (cp * v[0] - sp * v[1], sp * v[0] + cp * v[1]);
            p += sup.c[0] * vx * vx + sup.c[1] * vy * vy;
        }
        for (i, b) in md.balls.iter().enumerate() {
            let r = y[nc + ROTOR_COORDS + i];
            p += b.drag * b.r * b.r * r * r;
        }
        if !self.drive.prescribed() {
            p += self.rotor.spin_drag * k.phi_d * k.phi_d;
        }
        p
    }

    /// Lateral displacement, in fixed axes, of the shaft point at axial position `z` (m).
    pub fn displacement_at(&self, y: &[f64], z: f64) -> [f64; 2] {
        let k = self.model.kin(y, 0.0);
        let (_, r, _) = self.model.shaft_point(&k, z - self.model.z_ref);
        let (sp, cp) = y[PHI].sin_cos_fast();
        [cp * r[0] - sp * r[1], sp * r[0] + cp * r[1]]
    }

    /// Residual unbalance of unbalance masses and balls together, rotor frame:
    /// static `Σ m ρ_⊥` (kg·m) and couple about C `Σ m ζ ρ_⊥` plus the tilted principal
    /// axis's products of inertia (kg·m²).
    pub fn residual_unbalance(&self, y: &[f64]) -> ([f64; 2], [f64; 2]) {
        residual_unbalance(self.rotor, &self.model, y)
    }

    /// The exact Jacobian `∂f/∂y` of [`System::rhs`] at `(t, y)`, row-major `dim × dim`, by
    /// forward-mode differentiation of the same code that computes the right-hand side
    /// (module docs): no difference increments. Under a prescribed spin the `φ̇` column is zero
    /// (the schedule's rate is used) and the `φ̇`, `φ̈` rows are zero; under a torque drive the
    /// torque's slope [`Drive::torque_slope`] enters the `φ̇` column.
    ///
    /// Errors with [`Error::NoLinearisation`] for real balls (contact, rolling resistance):
    /// their dead zones and resting contacts have no derivative. Panics when `jac` does not
    /// hold `dim²` entries (a caller's bug, not an input).
    pub fn exact_jacobian(&self, t: f64, y: &[f64], jac: &mut [f64]) -> Result<()> {
        if !self.ball_forces.is_empty() {
            return Err(real_balls_error());
        }
        let dim = self.dim();
        assert_eq!(jac.len(), dim * dim, "exact_jacobian: jac must hold dim² = {} entries", dim * dim);
        let mut dy = vec![0.0; dim];
        self.rhs(t, y, &mut dy);
        let cols: Vec<usize> = (0..dim).collect();
        self.model.jacobian_columns(self.spin(t, y, true), y, &dy, &cols, jac);
        Ok(())
    }
}

/// The refusal of real balls by the linearisations.
pub(super) fn real_balls_error() -> Error {
    Error::NoLinearisation {
        reason: "balls with contact or rolling resistance (balancer.contact, balancer.rolling_resistance) have friction dead zones and resting contacts".into(),
    }
}

/// [`Equations::residual_unbalance`] of `rotor` at the ball angles of `y`.
pub(super) fn residual_unbalance(rotor: &SpatialRotor, model: &Model, y: &[f64]) -> ([f64; 2], [f64; 2]) {
    let (mut st, mut cp) = (rotor.static_unbalance(), rotor.couple_unbalance());
    for (i, b) in model.balls.iter().enumerate() {
        let (s, c) = y[ROTOR_COORDS + i].sin_cos_fast();
        st[0] += b.m * b.r * c;
        st[1] += b.m * b.r * s;
        cp[0] += b.m * b.r * b.zeta * c;
        cp[1] += b.m * b.r * b.zeta * s;
    }
    (st, cp)
}

impl System for Equations<'_> {
    fn dim(&self) -> usize {
        2 * self.coords()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.model.rhs(self.spin(t, y, false), y, dy, &self.ball_forces, &self.scratch);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic numbers in [−1, 1) (xorshift).
    fn numbers(seed: u64, len: usize) -> Vec<f64> {
        let mut x = seed;
        (0..len)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            })
            .collect()
    }

    #[test]
    fn ldlt_solves_positive_definite_systems_as_partial_pivoting_does() {
        // a second route: the same systems by Gaussian elimination with partial pivoting
        // (linalg::dense::solve_once). A = Bᵀ B + 0.05 I (B random, entries in [−1, 1]: the
        // eigenvalues lie in [0.05, 25], condition number ≤ 500); both solvers are backward
        // stable here, so their solutions agree to a few κ ε ≈ 1e-12 of |x|: 1e-10 leaves room
        for seed in 1..100u64 {
            let r = numbers(seed, 60);
            for nf in 2..=ROTOR_COORDS {
                let mut a = [[0.0; ROTOR_COORDS]; ROTOR_COORDS];
                for i in 0..nf {
                    for j in 0..nf {
                        a[i][j] = (0..nf).map(|k| r[k * 5 + i] * r[k * 5 + j]).sum::<f64>() + if i == j { 0.05 } else { 0.0 };
                    }
                }
                let mut b = [0.0; ROTOR_COORDS];
                b[..nf].copy_from_slice(&r[40..40 + nf]);
                let mut x = b;
                let ok = match nf {
                    2 => solve_spd::<2>(&a, &mut x),
                    3 => solve_spd::<3>(&a, &mut x),
                    4 => solve_spd::<4>(&a, &mut x),
                    _ => solve_spd::<5>(&a, &mut x),
                };
                assert!(ok, "seed {seed}, size {nf}: positive definite");
                let (mut y, mut a2) = (b, a);
                assert!(crate::linalg::dense::solve_once(&mut a2, &mut y, nf));
                let scale = y[..nf].iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for i in 0..nf {
                    assert!((x[i] - y[i]).abs() <= 1e-10 * scale, "seed {seed}, size {nf}: x[{i}] {} vs {}", x[i], y[i]);
                }
            }
        }
        // not positive definite, or not finite: refused
        let mut a = [[0.0; ROTOR_COORDS]; ROTOR_COORDS];
        a[0][0] = 1.0;
        a[1][1] = -1.0;
        assert!(!solve_spd::<2>(&a, &mut [1.0; ROTOR_COORDS]));
        a[1][1] = f64::NAN;
        assert!(!solve_spd::<2>(&a, &mut [1.0; ROTOR_COORDS]));
    }

    #[test]
    fn sparse_partial_velocities_give_the_full_dot_products_exactly() {
        // the written-out generalised forces and rotor block against the definitions with the
        // full partial velocities V_c, G_c (every zero multiplied and added): the dropped terms
        // are exact zeros, so the numbers are equal (`==`: up to the sign of a zero), not close
        for seed in 1..200u64 {
            let r = numbers(seed, 40);
            let (xi, eta, de) = (r[0], r[1], 1.5 * r[2]);
            let (sd, cd) = de.sin_cos();
            let zero = 0.0;
            let z = [zero; 3];
            let v = [[1.0, zero, zero], [zero, 1.0, zero], z, z, [-eta, xi, zero]];
            let g = [z, z, [1.0, zero, zero], [zero, cd, sd], [zero, zero, 1.0]];
            let k = Kin { u: [xi, eta, 0.0], v_o: z, w: z, rt: [z; 3], v, phi_d: 0.0, sd, cd };
            let (f, tau, s) = ([r[3], r[4], r[5]], [r[6], r[7], r[8]], [r[9], r[10], r[11]]);
            let mut j = [[0.0; 3]; 3];
            for a in 0..3 {
                for b in a..3 {
                    j[a][b] = r[12 + 3 * a + b] + if a == b { 3.0 } else { 0.0 };
                    j[b][a] = j[a][b];
                }
            }
            let mt = 2.0 + r[30];
            let q = partial_sums(&k, f, tau);
            for c in 0..ROTOR_COORDS {
                assert_eq!(q[c], dot(v[c], f) + dot(g[c], tau), "seed {seed}, coordinate {c}");
            }
            // the ball's geometry against the full products R_t v
            let (st, ct) = (1.3 * r[31]).sin_cos();
            let rt = [[ct, zero, st], [sd * st, cd, -(sd * ct)], [-(cd * st), sd, cd * ct]];
            let kb = Kin { u: k.u, v_o: z, w: z, rt, v, phi_d: 0.0, sd, cd };
            let b = Ball { m: 1.0, r: 1.0 + r[32], zeta: r[33], drag: 0.0 };
            let psi = 7.0 * r[34];
            let (sp, cp) = psi.sin_cos_fast();
            let (rb, tb, nb) = ball_geometry(&kb, &b, psi);
            let full = (mat_vec(&rt, [cp * b.r, sp * b.r, b.zeta]), mat_vec(&rt, [-(sp * b.r), cp * b.r, 0.0]), mat_vec(&rt, [-(cp * b.r), -(sp * b.r), 0.0]));
            assert_eq!((rb, tb, nb), full, "seed {seed}: ball geometry");
            let m = rotor_block(&k, mt, s, &j);
            for a in 0..ROTOR_COORDS {
                for b in 0..ROTOR_COORDS {
                    let (lo, hi) = (a.min(b), a.max(b));
                    let want = dot(v[lo], v[hi]) * mt + dot(v[lo], cross(g[hi], s)) + dot(v[hi], cross(g[lo], s)) + dot(g[lo], mat_vec(&j, g[hi]));
                    assert_eq!(m[a][b], want, "seed {seed}, entry ({a}, {b})");
                }
            }
        }
    }
}
