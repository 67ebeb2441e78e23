//! The equations of motion of the planar rotor in rotor axes, in three forms that check each
//! other: the right-hand side with the ball accelerations eliminated in closed form (what the
//! integrators call, cost linear in the number of balls), the residual of every body's
//! d'Alembert equation (the definition; exact Jacobians by forward-mode differentiation of it),
//! and the full mass matrix assembled body by body (a second route, for tests).
//!
//! ## Elimination
//! The unknowns are `x = (ü, θ̈)` (`θ̈` prescribed under a speed drive) and the ball
//! accelerations `ψ̈_j`. Ball `j`'s equation involves only `x` and its own `ψ̈_j`:
//!
//! ```text
//! m3 r b_j · x + m3 r² ψ̈_j = h_j,    b_j = (−sin ψ_j, cos ψ_j, e^{iψ_j}·(u + a_E) + r),
//! h_j = −c_ψ ψ̇_j − m3 r (2θ̇ e^{iψ_j}·u̇ − θ̇² (i e^{iψ_j})·(u + a_E))
//! ```
//!
//! (`a·b = Re(conj(a) b)`), so the mass matrix is an arrow: the rotor block `A` (3×3), border
//! columns `m3 r b_j`, diagonal `m3 r²`. Its Schur complement gives
//! `(A − m3 Σ b_j b_jᵀ) x = f − Σ b_j h_j / r`, a 3×3 (2×2) symmetric positive definite system
//! solved in closed form (LDLᵀ), then `ψ̈_j = h_j/(m3 r²) − b_j·x / r`.

use super::{Drive, PlanarRotor};
use crate::balls::BallForces;
use crate::ode::arrow::{ArrowJacobian, ArrowLinearization, ArrowSystem};
use crate::ode::dual::{sin_cos, sin_cos_reduced, Dual, Real, SIN_COS_LIMIT};
use crate::ode::{DenseJacobian, Jacobian, System};
use std::cell::RefCell;

/// A complex number over any [`Real`] (plane vectors in rotor axes).
#[derive(Clone, Copy, Debug)]
struct Cx<T> {
    re: T,
    im: T,
}

impl<T: Real> Cx<T> {
    fn new(re: T, im: T) -> Self {
        Cx { re, im }
    }
    fn c(re: f64, im: f64) -> Self {
        Cx { re: T::cst(re), im: T::cst(im) }
    }
    fn add(self, o: Self) -> Self {
        Cx::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: Self) -> Self {
        Cx::new(self.re - o.re, self.im - o.im)
    }
    fn scale(self, s: T) -> Self {
        Cx::new(self.re * s, self.im * s)
    }
    fn scalef(self, s: f64) -> Self {
        Cx::new(self.re * s, self.im * s)
    }
    fn mul_i(self) -> Self {
        Cx::new(-self.im, self.re)
    }
    /// `conj(self) · (c + i s)`: the mirror image in the x axis turned by the constant angle
    /// whose cosine and sine are `c`, `s`.
    fn conj_turn(self, c: f64, s: f64) -> Self {
        Cx::new(self.re * c + self.im * s, self.re * s - self.im * c)
    }
    /// `Re(conj(self) · o)`: the dot product of two plane vectors.
    fn dot(self, o: Self) -> T {
        self.re * o.re + self.im * o.im
    }
}

/// The equations in rotor axes: state `y = (ξ, η, θ, ψ_1..n, ξ̇, η̇, θ̇, ψ̇_1..n)`, with
/// `u = ξ + iη = (X + iY) e^{−iθ}` the shaft point C seen from the rotor.
///
/// Under a prescribed speed the rotor's `θ̇` component follows `θ̈ = a(t)` (it equals the
/// schedule's `ω(t)` when started on it, as `simulate` does at each piece) and the dynamics use
/// the schedule's `ω(t)` itself.
pub struct Equations<'a> {
    /// The rotor.
    pub rotor: &'a PlanarRotor,
    /// How it is driven.
    pub drive: &'a Drive,
    e: (f64, f64),
    prescribed: bool,
    /// The supports: mean stiffness and damping `(k̄, c̄)`, and where they differ by direction
    /// `(Δk, Δc) = ((k_x − k_y)/2, (c_x − c_y)/2)` (module docs of [`Equations::support_force`]).
    supports: (f64, f64, Option<(f64, f64)>),
    /// Per-ball masses and `κ_j = c_ψj/(m_j r)`, where the balls differ (`None`: all `m3`, `c_ψ`).
    unequal: Option<UnequalBalls>,
    /// Contact and rolling resistance of real balls, when switched on (`None`: point masses).
    pub(crate) balls: Option<BallForces>,
    /// The balls' generalised forces of the current right-hand side (scratch).
    ball_q: RefCell<Vec<f64>>,
}

/// The balls' own masses and drags ([`PlanarRotor::ball_masses`], [`PlanarRotor::ball_drags`]).
struct UnequalBalls {
    /// `m_j` (kg).
    masses: Vec<f64>,
    /// `c_ψj / r`.
    drags: Vec<f64>,
    /// `κ_j = c_ψj/(m_j r)`.
    kappa: Vec<f64>,
    /// `Σ m_j`.
    total: f64,
}

impl<'a> Equations<'a> {
    /// The equations of `rotor` under `drive`.
    pub fn new(rotor: &'a PlanarRotor, drive: &'a Drive) -> Self {
        let e = (rotor.s2 * rotor.gamma.cos(), rotor.s2 * rotor.gamma.sin());
        let balls = BallForces::new(&rotor.balls, rotor.m3, rotor.r, rotor.n, rotor.natural_frequency());
        let ball_q = RefCell::new(vec![0.0; if balls.is_some() { rotor.n } else { 0 }]);
        let supports = if rotor.anisotropic() {
            let ((kx, ky), (cx, cy)) = (rotor.stiffness_xy(), rotor.damping_xy());
            let (k, c) = rotor.mean_supports();
            (k, c, Some((0.5 * (kx - ky), 0.5 * (cx - cy))))
        } else {
            (rotor.k, rotor.c, None)
        };
        let unequal = (!rotor.equal_balls()).then(|| {
            let masses: Vec<f64> = (0..rotor.n).map(|j| rotor.ball_mass(j)).collect();
            let drags: Vec<f64> = (0..rotor.n).map(|j| rotor.ball_drag(j) / rotor.r).collect();
            let kappa = (0..rotor.n).map(|j| rotor.ball_drag(j) / (masses[j] * rotor.r)).collect();
            UnequalBalls { total: masses.iter().sum(), masses, drags, kappa }
        });
        Equations { rotor, drive, e, prescribed: drive.prescribed(), supports, unequal, balls, ball_q }
    }

    /// The support force on C in rotor axes, `−K(θ) u − C(θ)(u̇ + iθ̇u)`, generic over the
    /// number type. In fixed axes the force is `−(k_x X, k_y Y) − (c_x Ẋ, c_y Ẏ)`, i.e. with
    /// `z = X + iY`: `−(k̄ z + Δk z̄) − (c̄ ż + Δc conj(ż))`; with `z = u e^{iθ}`,
    /// `ż = (u̇ + iθ̇u) e^{iθ}` and the force turned back by `e^{−iθ}`:
    ///
    /// ```text
    /// F = −k̄ u − c̄ v − (Δk ū + Δc v̄) e^{−2iθ},   v = u̇ + iθ̇ u
    /// ```
    ///
    /// so the equations depend on the rotor angle through `e^{−2iθ}` alone: period `π` in `θ`
    /// (`π/Ω` in time at constant speed). Equal supports: the first two terms, as before.
    fn support_force<T: Real>(&self, u: Cx<T>, ud: Cx<T>, w: T, theta: f64) -> Cx<T> {
        let (k, c, aniso) = self.supports;
        let v = ud.add(u.mul_i().scale(w));
        let f = u.scalef(-k).sub(v.scalef(c));
        match aniso {
            None => f,
            Some((dk, dc)) => {
                let (s2, c2) = (2.0 * theta).sin_cos();
                // conj(a) e^{−2iθ} = conj(a e^{2iθ})
                f.sub(u.conj_turn(c2, -s2).scalef(dk)).sub(v.conj_turn(c2, -s2).scalef(dc))
            }
        }
    }

    /// `∂F/∂θ` of [`Equations::support_force`] at a plain state: `2i (Δk ū + Δc v̄) e^{−2iθ}`
    /// (zero for equal supports).
    fn support_force_theta(&self, u: Cx<f64>, ud: Cx<f64>, w: f64, theta: f64) -> Cx<f64> {
        match self.supports.2 {
            None => Cx::new(0.0, 0.0),
            Some((dk, dc)) => {
                let (s2, c2) = (2.0 * theta).sin_cos();
                let v = ud.add(u.mul_i().scalef(w));
                u.conj_turn(c2, -s2).scalef(dk).add(v.conj_turn(c2, -s2).scalef(dc)).mul_i().scalef(2.0)
            }
        }
    }

    /// The real balls' generalised forces `Q_j` at `(y, θ̇ = w)` into `q` ([`crate::balls`]):
    /// contact, and rolling resistance with the race's normal force
    /// `N_j = m3 (r (θ̇ + ψ̇_j)² + θ̇² P·e^{iψ_j} − 2θ̇ (i u̇)·e^{iψ_j})` (the centripetal part of
    /// the ball's acceleration; terms in `ü`, `θ̈`, of relative size `|u|/r`, left out).
    fn ball_forces(&self, f: &BallForces, w: f64, y: &[f64], q: &mut [f64]) {
        let p = self.rotor;
        let nc = self.coords();
        let (px, py) = (y[0] + self.e.0, y[1] + self.e.1);
        let (vx, vy) = (y[nc], y[nc + 1]);
        let normal = |j: usize| {
            let (s, c) = y[3 + j].sin_cos();
            let wr = w + y[nc + 3 + j];
            p.m3 * (p.r * wr * wr + w * w * (px * c + py * s) - 2.0 * w * (vx * s - vy * c))
        };
        f.torques(&y[3..nc], &y[nc + 3..2 * nc], normal, q);
    }

    /// The balls' generalised forces at `(t, y)` (empty when the balls are point masses).
    pub fn ball_torques(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let Some(f) = &self.balls else { return vec![] };
        let mut q = vec![0.0; self.rotor.n];
        self.ball_forces(f, self.speed(t, y).0, y, &mut q);
        q
    }

    /// Number of generalised coordinates `3 + n`.
    pub fn coords(&self) -> usize {
        3 + self.rotor.n
    }

    /// `(θ̇, θ̈)` used by the dynamics at `(t, y)`: the schedule's under a prescribed speed
    /// (`θ̈` then known), else the state's `θ̇` and `None`.
    #[inline(always)]
    fn speed(&self, t: f64, y: &[f64]) -> (f64, Option<f64>) {
        if self.prescribed {
            let (w, a) = self.drive.kinematics(t);
            (w, Some(a))
        } else {
            (y[self.coords() + 2], None)
        }
    }

    /// The residual of every equation, `R = F − M q̈` (zero at the solution), generic over the
    /// number type so that [`Dual`] numbers give exact derivatives. `ψ̇_j`, `ψ_j` of ball `j`
    /// come from `ball(j)`; `u`, `u̇`, `θ̇` are given; the accelerations `qdd` are plain numbers.
    /// `on_ball(j, R_rotor_part, R_ball)` receives each ball's contributions (rotor rows:
    /// translation x, y, rotation) before they are summed; returns the rotor rows' total.
    #[allow(clippy::too_many_arguments)]
    fn residual<T: Real>(
        &self,
        t: f64,
        theta: f64,
        u: Cx<T>,
        ud: Cx<T>,
        w: T,
        qdd: &[f64],
        ball: impl Fn(usize) -> (T, T),
        mut on_ball: impl FnMut(usize, [T; 3], T),
    ) -> [T; 3] {
        let p = self.rotor;
        let n = p.n;
        let udd = Cx::<T>::c(qdd[0], qdd[1]);
        let wd = T::cst(qdd[2]);
        let e = Cx::<T>::c(self.e.0, self.e.1);
        let zero = Cx::<T>::c(0.0, 0.0);
        // absolute acceleration of a body at offset a (rate ad, acceleration add), rotor axes
        let acc = |pos: Cx<T>, ad: Cx<T>, add: Cx<T>| udd.add(add).add(pos.mul_i().scale(wd)).add(ud.add(ad).mul_i().scale(w * 2.0)).sub(pos.scale(w * w));
        let force = self.support_force(u, ud, w, theta);
        let mut trans = force;
        let mut rot = u.mul_i().dot(force) - w * p.c_theta - wd * p.i_g;
        if !self.prescribed {
            rot = rot + T::cst(self.drive.torque(t, w.value())) + (w + (-w.value())) * self.drive.torque_slope(t, w.value());
        }
        for (m, a) in [(p.m1, Cx::c(p.s1, 0.0)), (p.m2, e)] {
            let pos = u.add(a);
            let ab = acc(pos, zero, zero);
            trans = trans.sub(ab.scalef(m));
            rot = rot - pos.mul_i().dot(ab) * m;
        }
        for j in 0..n {
            let (psi, psid) = ball(j);
            let (s, c) = psi.sin_cos();
            let d = Cx::new(c, s);
            let t_j = d.mul_i().scalef(p.r); // ∂(position)/∂ψ_j
            let pos = u.add(e).add(d.scalef(p.r));
            let ad = t_j.scale(psid);
            let add = t_j.scalef(qdd[3 + j]).sub(d.scale(psid * psid).scalef(p.r));
            let ab = acc(pos, ad, add);
            let mj = p.ball_mass(j);
            let r_tr = ab.scalef(-mj);
            let r_rot = pos.mul_i().dot(ab) * (-mj);
            let r_ball = psid * (-p.ball_drag(j)) - t_j.dot(ab) * mj;
            on_ball(j, [r_tr.re, r_tr.im, r_rot], r_ball);
            trans = trans.add(r_tr);
            rot = rot + r_rot;
        }
        if self.prescribed {
            rot = T::cst(qdd[2]) * 0.0; // θ̈ = a(t): nothing depends on the state
        }
        [trans.re, trans.im, rot]
    }

    /// The residuals `F − M q̈` of all `3 + n` equations at `(t, y)` for accelerations `qdd`
    /// (translation x, y, rotation, balls); zero when `qdd` is the right-hand side's. For checks.
    pub fn residuals(&self, t: f64, y: &[f64], qdd: &[f64]) -> Vec<f64> {
        let nc = self.coords();
        let (w, wd) = self.speed(t, y);
        let mut qdd = qdd.to_vec();
        if let Some(a) = wd {
            qdd[2] = a;
        }
        let mut out = vec![0.0; nc];
        let r =
            self.residual::<f64>(t, y[2], Cx::new(y[0], y[1]), Cx::new(y[nc], y[nc + 1]), w, &qdd, |j| (y[3 + j], y[nc + 3 + j]), |j, _, rb| out[3 + j] = rb);
        out[..3].copy_from_slice(&r);
        for (j, q) in self.ball_torques(t, y).iter().enumerate() {
            out[3 + j] += q;
        }
        if wd.is_some() {
            out[2] = 0.0;
        }
        out
    }

    /// The full mass matrix `M` (row-major `(3+n)²`) and forces `F` of `M q̈ = F` at `(t, y)`,
    /// assembled body by body from `A_b = ü + ä_b + iθ̈(u + a_b) + 2iθ̇(u̇ + ȧ_b) − θ̇²(u + a_b)`
    /// (independently of the elimination in [`System::rhs`]; for checks). Under a prescribed
    /// speed the rotation row is `θ̈ = a(t)`.
    pub fn mass_matrix(&self, t: f64, y: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let p = self.rotor;
        let n = p.n;
        let nc = 3 + n;
        let (w, wd) = self.speed(t, y);
        let u = Cx::<f64>::new(y[0], y[1]);
        let ud = Cx::<f64>::new(y[nc], y[nc + 1]);
        let e = Cx::<f64>::new(self.e.0, self.e.1);
        let mut m = vec![0.0; nc * nc];
        let mut f = vec![0.0; nc];
        let force = self.support_force(u, ud, w, y[2]);
        f[0] = force.re;
        f[1] = force.im;
        f[2] = u.mul_i().dot(force) - p.c_theta * w + self.drive.torque(t, w);
        m[2 * nc + 2] = p.i_g;
        // bodies: (mass, offset, offset rate, velocity-dependent part of ä, ∂offset/∂ψ (ball index))
        let mut bodies = vec![(p.m1, Cx::new(p.s1, 0.0), Cx::new(0.0, 0.0), Cx::new(0.0, 0.0), None), (p.m2, e, Cx::new(0.0, 0.0), Cx::new(0.0, 0.0), None)];
        for j in 0..n {
            let (s, c) = y[3 + j].sin_cos();
            let d = Cx::new(c, s);
            let tj = d.mul_i().scalef(p.r);
            let psid = y[nc + 3 + j];
            bodies.push((p.ball_mass(j), e.add(d.scalef(p.r)), tj.scalef(psid), d.scalef(-p.r * psid * psid), Some((j, tj))));
        }
        for (mb, a, ad, add_v, ball) in bodies {
            let pos = u.add(a);
            // velocity-dependent part of the acceleration
            let rv = add_v.add(ud.add(ad).mul_i().scalef(2.0 * w)).sub(pos.scalef(w * w));
            let ipos = pos.mul_i();
            // rows: translation (x, y), rotation, own ball; columns ü_x, ü_y, θ̈, ψ̈_own
            let mut rows: Vec<(usize, Cx<f64>)> = vec![(0, Cx::new(1.0, 0.0)), (1, Cx::new(0.0, 1.0)), (2, ipos)];
            if let Some((j, tj)) = ball {
                rows.push((3 + j, tj));
            }
            let mut cols: Vec<(usize, Cx<f64>)> = vec![(0, Cx::new(1.0, 0.0)), (1, Cx::new(0.0, 1.0)), (2, ipos)];
            if let Some((j, tj)) = ball {
                cols.push((3 + j, tj));
            }
            for &(r, dir) in &rows {
                for &(cidx, cdir) in &cols {
                    m[r * nc + cidx] += mb * dir.dot(cdir);
                }
                f[r] -= mb * dir.dot(rv);
            }
        }
        for j in 0..n {
            f[3 + j] -= p.ball_drag(j) * y[nc + 3 + j];
        }
        for (j, q) in self.ball_torques(t, y).iter().enumerate() {
            f[3 + j] += q;
        }
        if let Some(a) = wd {
            for r in 0..nc {
                if r != 2 {
                    f[r] -= m[r * nc + 2] * a;
                }
                m[r * nc + 2] = 0.0;
                m[2 * nc + r] = 0.0;
            }
            m[2 * nc + 2] = 1.0;
            f[2] = a;
        }
        (m, f)
    }
}

/// `x` of the symmetric positive definite `a x = g` (3×3 or, with `p = 2`, the leading 2×2),
/// by LDLᵀ in closed form.
#[inline]
fn solve_spd(a: [[f64; 3]; 3], g: [f64; 3], p: usize) -> [f64; 3] {
    let d1 = a[0][0];
    let l21 = a[1][0] / d1;
    let d2 = a[1][1] - l21 * a[1][0];
    let z1 = g[0];
    let z2 = g[1] - l21 * z1;
    if p == 2 {
        let x2 = z2 / d2;
        return [z1 / d1 - l21 * x2, x2, 0.0];
    }
    let l31 = a[2][0] / d1;
    let l32 = (a[2][1] - l31 * a[1][0]) / d2;
    let d3 = a[2][2] - l31 * a[2][0] - l32 * l32 * d2;
    let z3 = g[2] - l31 * z1 - l32 * z2;
    let x3 = z3 / d3;
    let x2 = z2 / d2 - l32 * x3;
    [z1 / d1 - l21 * x2 - l31 * x3, x2, x3]
}

impl Equations<'_> {
    /// The right-hand side by the elimination of the module docs; `FREE`: the rotor angle is a
    /// degree of freedom (torque drives, 3×3 Schur complement), else its motion is prescribed
    /// (2×2, and the rotation row is not formed).
    ///
    /// Each ball's `h_j/(m3 r) = −κ ψ̇_j + α cos ψ_j + β sin ψ_j + γ₀` is affine in
    /// `(ψ̇_j, cos ψ_j, sin ψ_j)` with coefficients common to all balls (`κ = c_ψ/(m3 r)`,
    /// `α = −2θ̇ u̇_x + θ̇² P_y − θ̈ P_x`, `β = −2θ̇ u̇_y − θ̇² P_x − θ̈ P_y`, `γ₀ = −θ̈ r`, `θ̈` the
    /// prescribed one or 0), and so is `b_j` in `(cos ψ_j, sin ψ_j)`: every ball sum of the
    /// elimination is a combination of ten moments (`Σ c`, `Σ s`, `Σ c²`, `Σ s c`, `Σ s²`,
    /// `Σ c ψ̇`, `Σ s ψ̇`, `Σ c ψ̇²`, `Σ s ψ̇²`, `Σ ψ̇`), and `ψ̈_j` is affine in
    /// `(ψ̇_j, cos ψ_j, sin ψ_j)` again. Two passes over the balls of a few operations each (and
    /// one `sin_cos`); `dy`'s ball slots hold `cos ψ_j`, `sin ψ_j` between them.
    ///
    /// Balls of unequal mass or drag ([`PlanarRotor::ball_masses`]): the same moments weighted
    /// by `m_j` (the mass factor `m3` taken as 1), the drag terms `κ ψ̇` summed with their own
    /// weights `c_ψj / r`, and `κ_j` per ball in the second pass.
    #[inline(always)]
    fn rhs_balls<const FREE: bool>(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let p = self.rotor;
        let n = p.n;
        let nc = 3 + n;
        let (w, wd_known) = self.speed(t, y);
        let (ux, uy) = (y[0], y[1]);
        let (vx, vy) = (y[nc], y[nc + 1]);
        let (px, py) = (ux + self.e.0, uy + self.e.1); // P = u + a_E
        let weighted = self.unequal.as_ref();
        let (m3, m3r, r) = if weighted.is_some() { (1.0, p.r, p.r) } else { (p.m3, p.m3 * p.r, p.r) };
        let wd_b = wd_known.unwrap_or(0.0);
        let (two_w, w2) = (2.0 * w, w * w);
        // pass 1: the moments of the balls
        let (psi, rest) = dy.split_at_mut(nc);
        let (cos_j, sin_j) = (&mut psi[3..], &mut rest[3..]);
        let (rates, angles) = (&y[nc + 3..], &y[3..nc]);
        let (mut s_c, mut s_s, mut s_cc, mut s_sc, mut s_ss) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let (mut s_cd, mut s_sd, mut s_cq, mut s_sq, mut s_d) = (0.0, 0.0, 0.0, 0.0, 0.0);
        if angles.iter().all(|x| x.abs() <= SIN_COS_LIMIT) {
            for ((&psi_j, cos_j), sin_j) in angles.iter().zip(cos_j.iter_mut()).zip(sin_j.iter_mut()) {
                (*sin_j, *cos_j) = sin_cos_reduced(psi_j);
            }
        } else {
            for ((&psi_j, cos_j), sin_j) in angles.iter().zip(cos_j.iter_mut()).zip(sin_j.iter_mut()) {
                (*sin_j, *cos_j) = sin_cos(psi_j);
            }
        }
        // the drag moments Σ κ c ψ̇, Σ κ s ψ̇, Σ κ ψ̇ (times m3)
        let (kd_c, kd_s, kd_d, nf, kappa);
        if let Some(wb) = weighted {
            let (mut dc, mut ds, mut dd) = (0.0, 0.0, 0.0);
            for j in 0..n {
                let (d, c, s, mu, cr) = (rates[j], cos_j[j], sin_j[j], wb.masses[j], wb.drags[j]);
                s_c += mu * c;
                s_s += mu * s;
                s_cc += mu * c * c;
                s_sc += mu * s * c;
                s_ss += mu * s * s;
                let (cd, sd) = (c * d, s * d);
                s_cd += mu * cd;
                s_sd += mu * sd;
                s_cq += mu * cd * d;
                s_sq += mu * sd * d;
                dc += cr * cd;
                ds += cr * sd;
                dd += cr * d;
            }
            (kd_c, kd_s, kd_d, nf, kappa) = (dc, ds, dd, wb.total, 0.0);
        } else {
            for ((&d, &c), &s) in rates.iter().zip(cos_j.iter()).zip(sin_j.iter()) {
                s_c += c;
                s_s += s;
                s_cc += c * c;
                s_sc += s * c;
                s_ss += s * s;
                let (cd, sd) = (c * d, s * d);
                s_cd += cd;
                s_sd += sd;
                s_cq += cd * d;
                s_sq += sd * d;
                if FREE {
                    s_d += d;
                }
            }
            nf = n as f64;
            // no balls: no drag (m3 may be 0 then)
            kappa = if n > 0 { p.c_psi / m3r } else { 0.0 };
            (kd_c, kd_s, kd_d) = (kappa * s_cd, kappa * s_sd, kappa * s_d);
        }
        let alpha = -two_w * vx + w2 * py - wd_b * px;
        let beta = -two_w * vy - w2 * px - wd_b * py;
        let gamma0 = -wd_b * r;
        // Σ s_j h_j/(m3 r), Σ c_j h_j/(m3 r)
        let mut hs = -kd_s + alpha * s_sc + beta * s_ss + gamma0 * s_s;
        let mut hc = -kd_c + alpha * s_cc + beta * s_sc + gamma0 * s_c;
        // real balls (contact, rolling resistance): generalised forces Q_j added to h_j, their
        // moments to the sums; nothing for point masses
        let mut q_buf = self.ball_q.borrow_mut();
        let mut q_1 = 0.0; // Σ Q_j/(m3 r)
        if let Some(f) = &self.balls {
            self.ball_forces(f, w, y, &mut q_buf);
            for j in 0..n {
                let qj = q_buf[j] / m3r;
                hs += sin_j[j] * qj;
                hc += cos_j[j] * qj;
                q_1 += qj;
            }
        }
        let m0 = p.total_mass();
        let me = p.m2 + nf * m3;
        let sx = m0 * ux + p.m1 * p.s1 + me * self.e.0 + m3r * s_c;
        let sy = m0 * uy + me * self.e.1 + m3r * s_s;
        // forces and velocity-dependent inertia terms
        let force = self.support_force(Cx::new(ux, uy), Cx::new(vx, vy), w, y[2]);
        let (fx, fy) = (force.re, force.im);
        let (bx, by) = (m0 * vx - m3r * s_sd, m0 * vy + m3r * s_cd); // m0 u̇ + m3 r Σ i d ψ̇
        let rx = -two_w * by - w2 * sx - m3r * s_cq;
        let ry = two_w * bx - w2 * sy - m3r * s_sq;
        // (A − m3 Σ b bᵀ) x = f − m3 Σ b h/(m3 r), b_j = (−s_j, c_j, β_j), β_j = P·d_j + r
        let (isx, isy) = (-sy, sx);
        let (bs, bc) = if FREE { (px * s_sc + py * s_ss + r * s_s, px * s_cc + py * s_sc + r * s_c) } else { (0.0, 0.0) };
        let a = [[m0 - m3 * s_ss, m3 * s_sc, isx + m3 * bs], [m3 * s_sc, m0 - m3 * s_cc, isy - m3 * bc], [0.0; 3]];
        let mut g = [fx - rx + m3 * hs, fy - ry - m3 * hc, 0.0];
        let x = if FREE {
            let (gx, gy) = (ux + p.s1, uy);
            let inertia = p.i_g + p.m1 * (gx * gx + gy * gy) + me * (px * px + py * py) + m3 * (2.0 * r * (px * s_c + py * s_s) + nf * r * r);
            let rot_b = two_w * (py * s_cd - px * s_sd) + py * s_cq - px * s_sq; // Σ ψ̇ (2θ̇ + ψ̇) P·(i d)
            let rot_r = two_w * ((p.m1 * gx + me * px) * vx + (p.m1 * gy + me * py) * vy + m3r * (vx * s_c + vy * s_s)) + m3r * rot_b;
            let bbeta = px * px * s_cc + 2.0 * px * py * s_sc + py * py * s_ss + 2.0 * r * (px * s_c + py * s_s) + nf * r * r;
            let hb = px * hc + py * hs + r * (-kd_d + alpha * s_c + beta * s_s + gamma0 * nf + q_1);
            g[2] = self.drive.torque(t, w) + (-uy * fx + ux * fy) - p.c_theta * w - rot_r - m3 * hb;
            let a = [a[0], a[1], [a[0][2], a[1][2], inertia - m3 * bbeta]];
            solve_spd(a, g, 3)
        } else {
            g[0] -= isx * wd_b;
            g[1] -= isy * wd_b;
            solve_spd(a, g, 2)
        };
        let (wd, x2) = if FREE { (x[2], x[2]) } else { (wd_b, 0.0) };
        // pass 2: ψ̈_j = h_j/(m3 r²) − b_j·x / r, affine in (ψ̇_j, c_j, s_j)
        let inv_r = 1.0 / r;
        let k_d = -kappa * inv_r;
        let k_c = (alpha - x[1] - px * x2) * inv_r;
        let k_s = (beta + x[0] - py * x2) * inv_r;
        let k_1 = (gamma0 - r * x2) * inv_r;
        if let Some(wb) = weighted {
            for (((out, &d), &c), &kj) in sin_j.iter_mut().zip(rates).zip(cos_j.iter()).zip(&wb.kappa) {
                *out = -kj * inv_r * d + k_c * c + k_s * *out + k_1;
            }
        } else {
            for ((out, &d), &c) in sin_j.iter_mut().zip(rates).zip(cos_j.iter()) {
                *out = k_d * d + k_c * c + k_s * *out + k_1;
            }
        }
        if self.balls.is_some() {
            for j in 0..n {
                sin_j[j] += q_buf[j] * inv_r / m3r;
            }
        }
        dy[..nc].copy_from_slice(&y[nc..2 * nc]);
        dy[nc] = x[0];
        dy[nc + 1] = x[1];
        dy[nc + 2] = wd;
    }
}

impl System for Equations<'_> {
    fn dim(&self) -> usize {
        2 * self.coords()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        if self.prescribed {
            self.rhs_balls::<false>(t, y, dy)
        } else {
            self.rhs_balls::<true>(t, y, dy)
        }
    }

    fn jacobian(&self) -> Box<dyn Jacobian + '_> {
        if self.balls.is_some() {
            // contact couples neighbouring balls (no arrow); balancers have few balls
            return Box::new(DenseJacobian::differences(self));
        }
        Box::new(ArrowJacobian::new(self))
    }

    fn component_name(&self, i: usize) -> String {
        let nc = self.coords();
        let (rate, k) = if i >= nc { (true, i - nc) } else { (false, i) };
        let base = match k {
            0 => "ξ (x of C in rotor axes)".to_string(),
            1 => "η (y of C in rotor axes)".to_string(),
            2 => "θ (rotor angle)".to_string(),
            j => format!("ψ_{} (ball {} angle)", j - 2, j - 2),
        };
        if rate {
            format!("rate of {base}")
        } else {
            base
        }
    }
}

/// Seeds of the Jacobian's forward differentiation: border `ξ, η, ξ̇, η̇, θ̇`, then the own
/// ball's `ψ_j, ψ̇_j`.
type D7 = Dual<7>;

impl ArrowSystem for Equations<'_> {
    fn arrow_shape(&self) -> (usize, usize) {
        (3, self.rotor.n)
    }

    fn linearize(&self, t: f64, y: &[f64], qdd: &[f64], lin: &mut ArrowLinearization) {
        let p = self.rotor;
        let n = p.n;
        let nc = 3 + n;
        let (w, wd) = self.speed(t, y);
        let mut acc = qdd.to_vec();
        if let Some(a) = wd {
            acc[2] = a;
        }
        lin.g_q.clear();
        lin.g_v.clear();
        // mass matrix (arrow): rotor block, border columns m3 r b_j, diagonal m3 r²
        let m0 = p.total_mass();
        let mb = p.balls_mass();
        let me = p.m2 + mb;
        let (px, py) = (y[0] + self.e.0, y[1] + self.e.1);
        let m = &mut lin.mass;
        m.clear();
        // Σ m_j e^{iψ_j}
        let (mut sdx, mut sdy) = (0.0, 0.0);
        for j in 0..n {
            let (s, c) = y[3 + j].sin_cos();
            let mj = p.ball_mass(j);
            sdx += mj * c;
            sdy += mj * s;
            let beta = if self.prescribed { 0.0 } else { px * c + py * s + p.r };
            let col = [-s * mj * p.r, c * mj * p.r, beta * mj * p.r];
            m.rb[3 * j..3 * j + 3].copy_from_slice(&col);
            m.br[3 * j..3 * j + 3].copy_from_slice(&col);
            m.bb[j] = mj * p.r * p.r;
        }
        m.rr[0] = m0;
        m.rr[4] = m0;
        if self.prescribed {
            m.rr[8] = 1.0;
        } else {
            let sx = m0 * y[0] + p.m1 * p.s1 + me * self.e.0 + p.r * sdx;
            let sy = m0 * y[1] + me * self.e.1 + p.r * sdy;
            let (gx, gy) = (y[0] + p.s1, y[1]);
            m.rr[2] = -sy;
            m.rr[6] = -sy;
            m.rr[5] = sx;
            m.rr[7] = sx;
            m.rr[8] = p.i_g + p.m1 * (gx * gx + gy * gy) + me * (px * px + py * py) + 2.0 * p.r * (px * sdx + py * sdy) + mb * p.r * p.r;
        }
        // residual derivatives by forward differentiation of the equations themselves
        let u = Cx::new(D7::var(y[0], 0), D7::var(y[1], 1));
        let ud = Cx::new(D7::var(y[nc], 2), D7::var(y[nc + 1], 3));
        let wv = if self.prescribed { D7::cst(w) } else { D7::var(w, 4) };
        let (gq, gv) = (&mut lin.g_q, &mut lin.g_v);
        let rows = self.residual::<D7>(
            t,
            y[2],
            u,
            ud,
            wv,
            &acc,
            |j| (D7::var(y[3 + j], 5), D7::var(y[nc + 3 + j], 6)),
            |j, r_rot, r_ball| {
                for i in 0..3 {
                    gq.rb[3 * j + i] = r_rot[i].d[5];
                    gv.rb[3 * j + i] = r_rot[i].d[6];
                }
                gq.br[3 * j] = r_ball.d[0];
                gq.br[3 * j + 1] = r_ball.d[1];
                gv.br[3 * j] = r_ball.d[2];
                gv.br[3 * j + 1] = r_ball.d[3];
                gv.br[3 * j + 2] = r_ball.d[4];
                gq.bb[j] = r_ball.d[5];
                gv.bb[j] = r_ball.d[6];
            },
        );
        let rows = if self.prescribed { [rows[0], rows[1], D7::cst(0.0)] } else { rows };
        if self.prescribed {
            for j in 0..n {
                gq.rb[3 * j + 2] = 0.0;
                gv.rb[3 * j + 2] = 0.0;
            }
        }
        for (i, r) in rows.iter().enumerate() {
            gq.rr[3 * i] = r.d[0];
            gq.rr[3 * i + 1] = r.d[1];
            gv.rr[3 * i] = r.d[2];
            gv.rr[3 * i + 1] = r.d[3];
            gv.rr[3 * i + 2] = r.d[4];
        }
        // the rotor angle enters only through supports that differ by direction: ∂R/∂θ is the
        // support force's (translation rows, and its moment about the axis in the rotation row)
        if self.supports.2.is_some() {
            let (u, ud) = (Cx::new(y[0], y[1]), Cx::new(y[nc], y[nc + 1]));
            let df = self.support_force_theta(u, ud, w, y[2]);
            gq.rr[2] = df.re;
            gq.rr[5] = df.im;
            if !self.prescribed {
                gq.rr[8] = u.mul_i().dot(df);
            }
        }
    }
}

/// Total mechanical energy `T + V` of a state (J), the contacts' elastic energy included: for
/// the energy-balance tests.
pub fn energy(rotor: &PlanarRotor, y: &[f64]) -> f64 {
    let n = rotor.n;
    let nc = 3 + n;
    let u = Cx::<f64>::new(y[0], y[1]);
    let ud = Cx::<f64>::new(y[nc], y[nc + 1]);
    let w = y[nc + 2];
    let e_off = Cx::<f64>::new(rotor.s2 * rotor.gamma.cos(), rotor.s2 * rotor.gamma.sin());
    let vel = |a: Cx<f64>, ad: Cx<f64>| ud.add(ad).add(u.add(a).mul_i().scalef(w));
    let mut t = 0.5 * rotor.i_g * w * w;
    // the supports' elastic energy ½(k_x X² + k_y Y²), (X, Y) = u e^{iθ} in fixed axes
    let (kx, ky) = rotor.stiffness_xy();
    let (st, ct) = y[2].sin_cos();
    let (xf, yf) = (u.re * ct - u.im * st, u.re * st + u.im * ct);
    let elastic = if rotor.anisotropic() { 0.5 * (kx * xf * xf + ky * yf * yf) } else { 0.5 * rotor.k * u.dot(u) };
    let v_g = vel(Cx::new(rotor.s1, 0.0), Cx::new(0.0, 0.0));
    t += 0.5 * rotor.m1 * v_g.dot(v_g);
    let v_e = vel(e_off, Cx::new(0.0, 0.0));
    t += 0.5 * rotor.m2 * v_e.dot(v_e);
    for j in 0..n {
        let (s, c) = y[3 + j].sin_cos();
        let d = Cx::new(c, s);
        let v = vel(e_off.add(d.scalef(rotor.r)), d.mul_i().scalef(rotor.r * y[nc + 3 + j]));
        t += 0.5 * rotor.ball_mass(j) * v.dot(v);
    }
    let contact = BallForces::new(&rotor.balls, rotor.m3, rotor.r, n, rotor.natural_frequency()).map_or(0.0, |f| f.contact_energy(&y[3..nc]));
    t + elastic + contact
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    #[test]
    fn sin_cos_agrees_with_the_library_to_two_ulp() {
        // deterministic arguments over the whole reduced range, near multiples of π/2 (where
        // the reduction cancels) and beyond the limit (the library's path)
        let mut worst: f64 = 0.0;
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 0..200_000 {
            let x = match i % 4 {
                0 => (next() - 0.5) * 20.0,
                1 => (next() - 0.5) * 2e6,
                2 => (i as f64 - 1e5) * std::f64::consts::FRAC_PI_2 + (next() - 0.5) * 1e-9,
                _ => (next() - 0.5) * 1e4,
            };
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            worst = worst.max((s - s0).abs()).max((c - c0).abs());
        }
        assert!(worst <= 2.0 * f64::EPSILON, "largest difference {worst:e}");
        for x in [0.0, -0.0, f64::NAN, f64::INFINITY, 1e300] {
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!(s.to_bits() == s0.to_bits() || (s.is_nan() && s0.is_nan()) || (s == s0), "{x}");
            assert!(c.to_bits() == c0.to_bits() || (c.is_nan() && c0.is_nan()) || (c == c0), "{x}");
        }
    }
}
