//! The equations of motion of the spatial rotor with balls, in axes turning with the rotor
//! (docs/spatial.md derives them).
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

#![allow(clippy::needless_range_loop)] // index loops read as the formulas

use super::rotor::{SpatialRotor, MAX_BALLS};
use crate::balls::BallForces;
use crate::drive::Drive;
use crate::ode::System;

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn mat_vec(m: &M3, v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
/// `Σ m (|r|² I − r rᵀ)` increment for a point mass.
fn add_point_inertia(j: &mut M3, m: f64, r: V3) {
    let r2 = dot(r, r);
    for a in 0..3 {
        for b in 0..3 {
            j[a][b] += m * (if a == b { r2 } else { 0.0 } - r[a] * r[b]);
        }
    }
}

/// Number of rotor coordinates `(ξ, η, δ, θ, φ)`.
pub const ROTOR_COORDS: usize = 5;
/// Index of the spin angle `φ` among the coordinates.
pub const PHI: usize = 4;

#[derive(Debug, Clone, Copy)]
struct Ball {
    m: f64,
    r: f64,
    zeta: f64,
    drag: f64,
}

#[derive(Debug, Clone, Copy)]
struct SupportAt {
    zeta: f64,
    k: [f64; 2],
    c: [f64; 2],
}

/// The equations of a [`SpatialRotor`] under a [`Drive`]; state
/// `y = (ξ, η, δ, θ, φ, ψ_1..N, ξ̇, η̇, δ̇, θ̇, φ̇, ψ̇_1..N)` (SI: m, rad, s).
#[derive(Debug, Clone)]
pub struct Equations<'a> {
    /// The rotor.
    pub rotor: &'a SpatialRotor,
    /// How it is driven.
    pub drive: &'a Drive,
    carrier_mass: f64,
    carrier_first: V3,
    carrier_inertia: M3,
    total_mass: f64,
    balls: Vec<Ball>,
    supports: Vec<SupportAt>,
    z_ref: f64,
    /// Real-ball forces of each plane that has them switched on: (index of its first ball, forces).
    ball_forces: Vec<(usize, BallForces)>,
}

/// Body-frame quantities of the rigid carrier (rotor + unbalance masses) about O:
/// mass, first moment `S = Σ m ρ`, inertia tensor `J = Σ m (|ρ|² I − ρ ρᵀ)` (rotor's own tensor
/// `A I + (C − A) e eᵀ` about G, `e` its principal axis, moved to O).
fn carrier(rotor: &SpatialRotor, z_ref: f64) -> (f64, V3, M3) {
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
    let mut s = scale(d, r.mass);
    let mut m = r.mass;
    for u in &rotor.unbalances {
        let rho = [u.radius * u.angle.cos(), u.radius * u.angle.sin(), u.z - z_ref];
        add_point_inertia(&mut j, u.mass, rho);
        s = add(s, scale(rho, u.mass));
        m += u.mass;
    }
    (m, s, j)
}

/// Kinematics of one state shared by the right-hand side and the energy.
struct Kin {
    u: V3,
    v_o: V3,
    w: V3,
    rt: M3,
    g: [V3; ROTOR_COORDS],
    v: [V3; ROTOR_COORDS],
    phi_d: f64,
}

impl<'a> Equations<'a> {
    /// Prepare the equations (the carrier's mass properties are computed once).
    pub fn new(rotor: &'a SpatialRotor, drive: &'a Drive) -> Self {
        let z_ref = rotor.z_reference();
        let (carrier_mass, carrier_first, carrier_inertia) = carrier(rotor, z_ref);
        let balls =
            rotor.planes.iter().flat_map(|p| (0..p.n).map(move |_| Ball { m: p.ball_mass, r: p.race_radius, zeta: p.z - z_ref, drag: p.drag })).collect();
        let supports: Vec<SupportAt> = rotor.supports.iter().map(|s| SupportAt { zeta: s.z - z_ref, k: s.stiffness, c: s.damping }).collect();
        // reference frequency of the default contact stiffness: the rotor's translation on its supports
        let w_ref = (supports.iter().map(|s| s.k[0]).sum::<f64>() / rotor.total_mass()).sqrt();
        let mut first = 0;
        let mut ball_forces = vec![];
        for p in &rotor.planes {
            if let Some(f) = BallForces::new(&p.physics, p.ball_mass, p.race_radius, p.n, w_ref) {
                ball_forces.push((first, f));
            }
            first += p.n;
        }
        Equations { rotor, drive, carrier_mass, carrier_first, carrier_inertia, total_mass: rotor.total_mass(), balls, supports, z_ref, ball_forces }
    }

    /// The real-ball forces of the planes that have them switched on: (index of the plane's
    /// first ball among all balls, its forces); empty for point masses.
    pub fn ball_forces(&self) -> &[(usize, BallForces)] {
        &self.ball_forces
    }

    /// Number of generalised coordinates `5 + N`.
    pub fn coords(&self) -> usize {
        ROTOR_COORDS + self.balls.len()
    }

    /// Axial position of the reference point O (= C).
    pub fn z_reference(&self) -> f64 {
        self.z_ref
    }

    /// Spin rate at `t`: prescribed by the drive, or the state's `φ̇`.
    pub fn spin_rate(&self, t: f64, y: &[f64]) -> f64 {
        if self.drive.prescribed() {
            self.drive.kinematics(t).0
        } else {
            y[self.coords() + PHI]
        }
    }

    fn kin(&self, t: f64, y: &[f64]) -> Kin {
        let nc = self.coords();
        let (xi, eta, de, th) = (y[0], y[1], y[2], y[3]);
        let (xid, etad, ded, thd) = (y[nc], y[nc + 1], y[nc + 2], y[nc + 3]);
        let phi_d = self.spin_rate(t, y);
        let (sd, cd) = de.sin_cos();
        let (st, ct) = th.sin_cos();
        let rt = [[ct, 0.0, st], [sd * st, cd, -sd * ct], [-cd * st, sd, cd * ct]];
        let u = [xi, eta, 0.0];
        let v_o = [xid - phi_d * eta, etad + phi_d * xi, 0.0];
        let w = [ded, thd * cd, phi_d + thd * sd];
        let z = [0.0; 3];
        let g = [z, z, [1.0, 0.0, 0.0], [0.0, cd, sd], [0.0, 0.0, 1.0]];
        let v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], z, z, [-eta, xi, 0.0]];
        Kin { u, v_o, w, rt, g, v, phi_d }
    }

    fn ball_geometry(&self, k: &Kin, b: &Ball, psi: f64) -> (V3, V3, V3) {
        let (sp, cp) = psi.sin_cos();
        let r = mat_vec(&k.rt, [b.r * cp, b.r * sp, b.zeta]);
        let t = mat_vec(&k.rt, [-b.r * sp, b.r * cp, 0.0]);
        let n = mat_vec(&k.rt, [-b.r * cp, -b.r * sp, 0.0]);
        (r, t, n)
    }

    /// First moment `s` and inertia tensor `J` of the carrier about O in F components.
    fn carrier_in_f(&self, k: &Kin) -> (V3, M3) {
        let s = mat_vec(&k.rt, self.carrier_first);
        // J = R_t J_b R_tᵀ
        let mut rj = [[0.0; 3]; 3];
        for a in 0..3 {
            for b in 0..3 {
                rj[a][b] = (0..3).map(|c| k.rt[a][c] * self.carrier_inertia[c][b]).sum();
            }
        }
        let mut j = [[0.0; 3]; 3];
        for a in 0..3 {
            for b in 0..3 {
                j[a][b] = (0..3).map(|c| rj[a][c] * k.rt[b][c]).sum();
            }
        }
        (s, j)
    }

    /// Lateral position and velocity of the shaft point at body axial coordinate `zeta`, in F
    /// components: `(r, v)` with `r = u + R_t ζ e_z` (its third component is axial).
    fn shaft_point(&self, k: &Kin, zeta: f64) -> (V3, V3, V3) {
        let rho = [zeta * k.rt[0][2], zeta * k.rt[1][2], zeta * k.rt[2][2]];
        let r = add(k.u, rho);
        let v = add(k.v_o, cross(k.w, rho));
        (rho, r, v)
    }

    /// Total mechanical energy `T + V` (J): kinetic energy of carrier and balls, elastic
    /// energy of the supports, potential of gravity. For the energy-balance tests.
    pub fn energy(&self, t: f64, y: &[f64]) -> f64 {
        let nc = self.coords();
        let k = self.kin(t, y);
        let (s, j) = self.carrier_in_f(&k);
        let mut e = 0.5 * self.carrier_mass * dot(k.v_o, k.v_o) + dot(k.v_o, cross(k.w, s)) + 0.5 * dot(k.w, mat_vec(&j, k.w));
        let phi = y[PHI];
        let (sp, cp) = phi.sin_cos();
        let g = self.rotor.gravity;
        let g_f = [g[0] * cp + g[1] * sp, -g[0] * sp + g[1] * cp, g[2]];
        let mut first = add(scale(k.u, self.carrier_mass), s);
        for (i, b) in self.balls.iter().enumerate() {
            let (r, t_j, _) = self.ball_geometry(&k, b, y[ROTOR_COORDS + i]);
            let v = add(add(k.v_o, cross(k.w, r)), scale(t_j, y[nc + ROTOR_COORDS + i]));
            e += 0.5 * b.m * dot(v, v);
            first = add(first, scale(add(k.u, r), b.m));
        }
        e -= dot(g_f, first);
        for sup in &self.supports {
            let (_, r, _) = self.shaft_point(&k, sup.zeta);
            let (x, yy) = (cp * r[0] - sp * r[1], sp * r[0] + cp * r[1]);
            e += 0.5 * (sup.k[0] * x * x + sup.k[1] * yy * yy);
        }
        e
    }

    /// Power dissipated by the dampers and the ball drag at a state (W, ≥ 0): for the power
    /// balance `dE/dt = P_drive − P_dissipated`.
    pub fn dissipated_power(&self, t: f64, y: &[f64]) -> f64 {
        let nc = self.coords();
        let k = self.kin(t, y);
        let (sp, cp) = y[PHI].sin_cos();
        let mut p = 0.0;
        for sup in &self.supports {
            let (_, _, v) = self.shaft_point(&k, sup.zeta);
            let (vx, vy) = (cp * v[0] - sp * v[1], sp * v[0] + cp * v[1]);
            p += sup.c[0] * vx * vx + sup.c[1] * vy * vy;
        }
        for (i, b) in self.balls.iter().enumerate() {
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
        let k = self.kin(0.0, y);
        let (_, r, _) = self.shaft_point(&k, z - self.z_ref);
        let (sp, cp) = y[PHI].sin_cos();
        [cp * r[0] - sp * r[1], sp * r[0] + cp * r[1]]
    }

    /// Residual unbalance of unbalance masses and balls together, rotor frame:
    /// static `Σ m ρ_⊥` (kg·m) and couple about C `Σ m ζ ρ_⊥` plus the tilted principal
    /// axis's products of inertia (kg·m²).
    pub fn residual_unbalance(&self, y: &[f64]) -> ([f64; 2], [f64; 2]) {
        let (mut st, mut cp) = (self.rotor.static_unbalance(), self.rotor.couple_unbalance());
        for (i, b) in self.balls.iter().enumerate() {
            let (s, c) = y[ROTOR_COORDS + i].sin_cos();
            st[0] += b.m * b.r * c;
            st[1] += b.m * b.r * s;
            cp[0] += b.m * b.r * b.zeta * c;
            cp[1] += b.m * b.r * b.zeta * s;
        }
        (st, cp)
    }

    /// Which rotor coordinates are integrated (not prescribed, not locked).
    fn free(&self) -> [bool; ROTOR_COORDS] {
        let tilt = !self.rotor.lock_tilt;
        [true, true, tilt, tilt, !self.drive.prescribed()]
    }
}

impl System for Equations<'_> {
    fn dim(&self) -> usize {
        2 * self.coords()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let nc = self.coords();
        let k = self.kin(t, y);
        let (ded, thd) = (y[nc + 2], y[nc + 3]);
        let (sd, cd) = y[2].sin_cos();
        let phi_d = k.phi_d;
        let (xid, etad) = (y[nc], y[nc + 1]);
        // accelerations with q̈ = 0
        let a_o = [-2.0 * phi_d * etad - phi_d * phi_d * y[0], 2.0 * phi_d * xid - phi_d * phi_d * y[1], 0.0];
        let alpha = [-phi_d * thd * cd, -thd * ded * sd + phi_d * ded, thd * ded * cd];
        let (s, j) = self.carrier_in_f(&k);
        let w = k.w;
        let mc = self.carrier_mass;
        let mut f_in = add(add(scale(a_o, mc), cross(alpha, s)), cross(w, cross(w, s)));
        let mut t_in = add(add(cross(s, a_o), mat_vec(&j, alpha)), cross(w, mat_vec(&j, w)));
        let mut s_tot = s;
        let mut j_tot = j;
        let (sp, cp) = y[PHI].sin_cos();
        let gr = self.rotor.gravity;
        let g_f = [gr[0] * cp + gr[1] * sp, -gr[0] * sp + gr[1] * cp, gr[2]];
        // balls: inertia forces, rows of the arrow
        let nb = self.balls.len();
        let mut brow = [[0.0; ROTOR_COORDS]; MAX_BALLS];
        let mut bf = [0.0; MAX_BALLS];
        let mut normal = [0.0; MAX_BALLS];
        let real_balls = !self.ball_forces.is_empty();
        for (i, b) in self.balls.iter().enumerate() {
            let psi_d = y[nc + ROTOR_COORDS + i];
            let (r, t_j, n_j) = self.ball_geometry(&k, b, y[ROTOR_COORDS + i]);
            let a_j = add(add(add(a_o, cross(alpha, r)), cross(w, cross(w, r))), add(scale(cross(w, t_j), 2.0 * psi_d), scale(n_j, psi_d * psi_d)));
            let ma = scale(a_j, b.m);
            f_in = add(f_in, ma);
            t_in = add(t_in, cross(r, ma));
            s_tot = add(s_tot, scale(r, b.m));
            add_point_inertia(&mut j_tot, b.m, r);
            let rxt = cross(r, t_j);
            for c in 0..ROTOR_COORDS {
                brow[i][c] = b.m * (dot(k.v[c], t_j) + dot(k.g[c], rxt));
            }
            bf[i] = -b.drag * b.r * b.r * psi_d + b.m * dot(g_f, t_j) - dot(t_j, ma);
            if real_balls {
                // the race's normal force: the centripetal part of the ball's acceleration
                // (n_j = −R e_r), the terms in q̈ left out as in the planar model
                normal[i] = dot(ma, n_j) / b.r;
            }
        }
        // real balls: contact and rolling resistance, generalised forces on the ball angles
        for (first, f) in &self.ball_forces {
            let (a, e) = (*first, first + f.n);
            let mut q = [0.0; MAX_BALLS];
            f.torques(&y[ROTOR_COORDS + a..ROTOR_COORDS + e], &y[nc + ROTOR_COORDS + a..nc + ROTOR_COORDS + e], |j| normal[a + j], &mut q[..f.n]);
            for j in 0..f.n {
                bf[a + j] += q[j];
            }
        }
        // external forces and moments about O: gravity and supports
        let mut f_ex = scale(g_f, self.total_mass);
        let mut t_ex = cross(s_tot, g_f);
        for sup in &self.supports {
            let (rho, r, v) = self.shaft_point(&k, sup.zeta);
            let (x, yy) = (cp * r[0] - sp * r[1], sp * r[0] + cp * r[1]);
            let (vx, vy) = (cp * v[0] - sp * v[1], sp * v[0] + cp * v[1]);
            let (fx, fy) = (-sup.k[0] * x - sup.c[0] * vx, -sup.k[1] * yy - sup.c[1] * vy);
            let f = [cp * fx + sp * fy, -sp * fx + cp * fy, 0.0];
            f_ex = add(f_ex, f);
            t_ex = add(t_ex, cross(rho, f));
        }
        let (df, dt_) = (sub(f_ex, f_in), sub(t_ex, t_in));
        let mut q = [0.0; ROTOR_COORDS];
        for c in 0..ROTOR_COORDS {
            q[c] = dot(k.v[c], df) + dot(k.g[c], dt_);
        }
        // rotor block of the mass matrix
        let mt = self.total_mass;
        let mut m = [[0.0; ROTOR_COORDS]; ROTOR_COORDS];
        let mut gxs = [[0.0; 3]; ROTOR_COORDS];
        let mut jg = [[0.0; 3]; ROTOR_COORDS];
        for c in 0..ROTOR_COORDS {
            gxs[c] = cross(k.g[c], s_tot);
            jg[c] = mat_vec(&j_tot, k.g[c]);
        }
        for a in 0..ROTOR_COORDS {
            for b in a..ROTOR_COORDS {
                let v = mt * dot(k.v[a], k.v[b]) + dot(k.v[a], gxs[b]) + dot(k.v[b], gxs[a]) + dot(k.g[a], jg[b]);
                m[a][b] = v;
                m[b][a] = v;
            }
        }
        let free = self.free();
        let prescribed = self.drive.prescribed();
        let phi_dd = if prescribed {
            let acc = self.drive.kinematics(t).1;
            for c in 0..ROTOR_COORDS {
                q[c] -= m[c][PHI] * acc;
            }
            for i in 0..nb {
                bf[i] -= brow[i][PHI] * acc;
            }
            acc
        } else {
            q[PHI] += self.drive.torque(t, phi_d) - self.rotor.spin_drag * phi_d;
            0.0
        };
        // Schur complement on the free rotor coordinates
        let mut idx_buf = [0usize; ROTOR_COORDS];
        let mut nf = 0;
        for c in 0..ROTOR_COORDS {
            if free[c] {
                idx_buf[nf] = c;
                nf += 1;
            }
        }
        let idx = &idx_buf[..nf];
        let mut a = [[0.0; ROTOR_COORDS]; ROTOR_COORDS];
        let mut rhs = [0.0; ROTOR_COORDS];
        for (ia, &ca) in idx.iter().enumerate() {
            rhs[ia] = q[ca];
            for (ib, &cb) in idx.iter().enumerate() {
                a[ia][ib] = m[ca][cb];
            }
        }
        for i in 0..nb {
            let d = self.balls[i].m * self.balls[i].r * self.balls[i].r;
            for (ia, &ca) in idx.iter().enumerate() {
                let bi = brow[i][ca] / d;
                rhs[ia] -= bi * bf[i];
                for (ib, &cb) in idx.iter().enumerate() {
                    a[ia][ib] -= bi * brow[i][cb];
                }
            }
        }
        let ok = crate::linalg::dense::solve_once(&mut a, &mut rhs, nf);
        let mut acc = [0.0; ROTOR_COORDS];
        for (ia, &ca) in idx.iter().enumerate() {
            acc[ca] = rhs[ia];
        }
        dy[..nc].copy_from_slice(&y[nc..2 * nc]);
        dy[nc..nc + ROTOR_COORDS].copy_from_slice(&acc);
        if prescribed {
            dy[PHI] = phi_d;
            dy[nc + PHI] = phi_dd;
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
}
