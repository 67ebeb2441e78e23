//! The linear rotor with its balls at constant speed as a [`VectorField`] (derivation in the
//! module docs of [`crate::linear_rotor`]): state `x = (p, ψ, ṗ, ψ̇)`, `p` the `N` structural
//! DOFs in the frame's axes, `ψ` the balls' angles relative to the rotor (plane by plane).
//!
//! ```
//! use autobal::analysis::{stability, stationary, NewtonOptions, Verdict};
//! use autobal::linear_rotor::{BalancerPlane, Frame, LinearRotor, LinearRotorField};
//! // a Jeffcott rotor, ω_n = 100 rad/s, balanced at 150 rad/s by two balls
//! let b = BalancerPlane { node: 0, radius: 0.05, balls: 2, ball_mass: 0.02, drag: 0.01, offset: 0.0 };
//! let rotor = LinearRotor::jeffcott(1.0, 1e4 * 1.04, 20.0, 1e-3, b);
//! let f = LinearRotorField::new(&rotor, 150.0, Frame::Rotating).unwrap();
//! let s = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
//! assert!(s.x[0].hypot(s.x[1]) < 1e-15); // the node rests on the axis
//! assert_eq!(stability(&f, &s).unwrap().verdict, Verdict::Stable);
//! ```

use super::LinearRotor;
use crate::analysis::VectorField;
use crate::error::{finite, Error, Result};
use crate::ode::dual::{Dual, Real};
use crate::ode::lu::Lu;
use num_complex::Complex64 as C;
use std::f64::consts::PI;

/// The axes the equations are written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frame {
    /// Axes turning with the rotor (`ν = Ω`): autonomous for an isotropic structure without
    /// gravity, else periodic with `π/Ω` (anisotropic structure) or `2π/Ω` (gravity, which turns
    /// once per revolution in these axes); the balanced state is an equilibrium (isotropic, no
    /// gravity) or a periodic orbit (the rotor sags, the balls swing).
    Rotating,
    /// Fixed axes (`ν = 0`): periodic with `2π/Ω`; the form for time simulation.
    Fixed,
}

/// Directions seeded per forward-mode pass of the Jacobian.
pub(crate) const SEEDS: usize = 8;

/// One ball: its plane's node DOFs `(x, y)` and `(α, β)` (where the layout has them), race
/// radius, mass, drag, axial offset of the race plane.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Ball {
    ix: usize,
    iy: usize,
    tilt: Option<(usize, usize)>,
    r: f64,
    m: f64,
    drag: f64,
    z: f64,
}

/// The linear rotor at constant speed `Ω` in a [`Frame`] (module docs of [`crate::linear_rotor`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearRotorField {
    rotor: LinearRotor,
    omega: f64,
    frame: Frame,
    isotropic: bool,
    balls: Vec<Ball>,
    /// `C + Ω G`.
    d: Vec<f64>,
    /// The reference frequency of the real balls' default contact stiffness (rad/s): the
    /// lowest nonzero undamped natural frequency with the balls as rings; 0 without real balls.
    reference: f64,
}

/// The rotor's motion at one time: speed `Ω`, acceleration `Ω̇`, the frame's rate `ν`, the
/// rotor's angle in the frame `χ` (`(Ω − ν) t` at constant speed; `φ(t)` of a drive in fixed
/// axes, [`super::runup`]) and the frame's angle from the fixed axes `ν t` (0 in fixed axes),
/// by which gravity turns in the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Kin {
    pub w: f64,
    pub wdot: f64,
    pub nu: f64,
    pub chi: f64,
    pub frame: f64,
}

/// Increments `δχ`, `δΩ` (value 0) of the rotor's angle and speed carried by the residual
/// ([`LinearRotorField::residual_spin`]), with `∂(C + ΩG)/∂Ω = G + C'(Ω)` (`dd`) and
/// `∂K/∂Ω = K'(Ω)` (`dk`), row-major `N × N` (fixed axes).
pub(crate) struct SpinVar<'a, T> {
    pub chi: T,
    pub w: T,
    pub dd: &'a [f64],
    pub dk: &'a [f64],
}

/// The structure's matrices in the frame at one time: `M_r`, `(C + ΩG)_r`, `K_r`.
pub(crate) struct Mats<'a> {
    pub m: std::borrow::Cow<'a, [f64]>,
    pub d: std::borrow::Cow<'a, [f64]>,
    pub k: std::borrow::Cow<'a, [f64]>,
}

impl LinearRotorField {
    /// The field of `rotor` at speed `omega` (rad/s) in `frame`; the rotor is validated.
    /// Real balls ([`LinearRotor::ball_physics`]) are refused with [`Error::NoLinearisation`]:
    /// a friction dead zone or a resting contact has no linearisation (they run in
    /// [`super::runup`]).
    pub fn new(rotor: &LinearRotor, omega: f64, frame: Frame) -> Result<Self> {
        if rotor.ball_physics.iter().any(|p| p.is_active()) {
            rotor.validate()?;
            return Err(Error::NoLinearisation {
                reason: "real balls (linear_rotor.balancer contact, rolling_resistance) have friction dead zones and resting contacts".into(),
            });
        }
        Self::with_real_balls(rotor, omega, frame)
    }

    /// [`LinearRotorField::new`] with real balls allowed, for time simulation: their torques
    /// enter the accelerations ([`LinearRotorField::accelerations`]) but not the exact Jacobian
    /// of [`VectorField::jacobian`] (the run-ups use differences then).
    pub(crate) fn with_real_balls(rotor: &LinearRotor, omega: f64, frame: Frame) -> Result<Self> {
        rotor.validate()?;
        finite("omega", omega)?;
        // the speed-dependent bearings at this speed, folded into C and K
        let rotor = &if rotor.speed_bearings.is_empty() { rotor.clone() } else { rotor.at_speed(omega) };
        let mut balls = vec![];
        for b in &rotor.balancers {
            let (ix, iy) = (rotor.dof(b.node, super::Direction::X), rotor.dof(b.node, super::Direction::Y));
            let (Some(ix), Some(iy)) = (ix, iy) else { return Err(Error::invalid("linear_rotor.balancers.node", "has no x, y DOFs")) };
            let tilt = rotor.dof(b.node, super::Direction::Alpha).zip(rotor.dof(b.node, super::Direction::Beta));
            for _ in 0..b.balls {
                balls.push(Ball { ix, iy, tilt, r: b.radius, m: b.ball_mass, drag: b.drag, z: b.offset });
            }
        }
        let d = rotor.c.iter().zip(&rotor.g).map(|(c, g)| c + omega * g).collect();
        let reference = if rotor.ball_physics.iter().any(|p| p.is_active()) {
            // as the planar model's sqrt(k/m0): the lowest mode with the balls as rings
            rotor.natural_frequencies(&[], true).ok().and_then(|w| w.into_iter().find(|v| *v > 0.0)).unwrap_or(1.0)
        } else {
            0.0
        };
        Ok(LinearRotorField { isotropic: rotor.is_isotropic(), rotor: rotor.clone(), omega, frame, balls, d, reference })
    }

    /// Whether real balls act ([`LinearRotor::ball_physics`]).
    pub fn real_balls(&self) -> bool {
        self.reference > 0.0
    }

    /// Add the real balls' generalised forces on their angles ([`crate::balls`]: contact
    /// between balls, rolling resistance) to `out[N..N + Σ n]` at state `x` and kinematics `kin`.
    /// The rolling resistance's normal force is the centripetal part of the ball's acceleration
    /// as in the planar model, `N_j = m_b (R θ̇_j² − Ω² c·e_j − 2Ω (J ċ)·e_j + g·e_j)` (`c`, `ċ`
    /// the race centre's position and absolute velocity, `e_j` the ball's direction, all in the
    /// frame's components: the dot products do not depend on the frame); the race centre's
    /// acceleration relative to axes turning with the rotor (terms of relative size `|c|/R`)
    /// is left out. Ball–ball and ball–race forces are internal to the rotor with its balls:
    /// they act on the relative angles `ψ_j` only, not on the spin.
    pub(crate) fn add_real_balls(&self, kin: &Kin, x: &[f64], out: &mut [f64]) {
        if !self.real_balls() {
            return;
        }
        let n = self.rotor.dofs();
        let nc = self.coords();
        let nu = kin.nu;
        let w = kin.w;
        let (gx, gy) = match &self.rotor.gravity {
            Some(gr) => {
                let (s, c) = kin.frame.sin_cos();
                (c * gr.g[0] + s * gr.g[1], c * gr.g[1] - s * gr.g[0])
            }
            None => (0.0, 0.0),
        };
        let mut first = n;
        for (k, plane) in self.rotor.balancers.iter().enumerate() {
            let nb = plane.balls;
            let forces = self.rotor.ball_physics.get(k).and_then(|p| crate::balls::BallForces::new(p, plane.ball_mass, plane.radius, nb, self.reference));
            if let Some(f) = forces {
                let b = self.balls[first - n];
                let abs_v = |i: usize, j: usize| (x[nc + i] - nu * x[j], x[nc + j] + nu * x[i]);
                let (mut cx, mut cy) = (x[b.ix], x[b.iy]);
                let (mut vx, mut vy) = abs_v(b.ix, b.iy);
                if let Some((ia, ib)) = b.tilt {
                    let (va, vb) = abs_v(ia, ib);
                    cx += b.z * x[ib];
                    cy -= b.z * x[ia];
                    vx += b.z * vb;
                    vy -= b.z * va;
                }
                let psi = &x[first..first + nb];
                let rate = &x[nc + first..nc + first + nb];
                let normal = |j: usize| {
                    let (s, c) = (psi[j] + kin.chi).sin_cos();
                    let wr = w + rate[j];
                    b.m * (b.r * wr * wr - w * w * (cx * c + cy * s) - 2.0 * w * (vx * s - vy * c) + gx * c + gy * s)
                };
                let mut q = vec![0.0; nb];
                f.torques(psi, rate, normal, &mut q);
                for (o, v) in out[first..first + nb].iter_mut().zip(&q) {
                    *o += v;
                }
            }
            first += nb;
        }
    }

    /// The rotor.
    pub fn rotor(&self) -> &LinearRotor {
        &self.rotor
    }

    /// The speed `Ω` (rad/s).
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// The frame.
    pub fn frame(&self) -> Frame {
        self.frame
    }

    /// Number of coordinates `N + Σ n`.
    pub fn coords(&self) -> usize {
        self.rotor.dofs() + self.balls.len()
    }

    /// The frame's rate `ν`: `Ω` turning, 0 fixed.
    fn nu(&self) -> f64 {
        match self.frame {
            Frame::Rotating => self.omega,
            Frame::Fixed => 0.0,
        }
    }

    /// The kinematics at constant speed at time `t`.
    fn kin(&self, t: f64) -> Kin {
        let nu = self.nu();
        Kin { w: self.omega, wdot: 0.0, nu, chi: (self.omega - nu) * t, frame: nu * t }
    }

    /// `M_r = Tᵀ M T` etc. at time `t`, `T = T(ν t)` (the matrices themselves where the frame
    /// does not turn or the structure is isotropic).
    fn mats(&self, t: f64) -> Mats<'_> {
        use std::borrow::Cow;
        let phi = self.nu() * t;
        if self.isotropic || phi == 0.0 {
            return Mats { m: Cow::Borrowed(&self.rotor.m), d: Cow::Borrowed(&self.d), k: Cow::Borrowed(&self.rotor.k) };
        }
        let n = self.rotor.dofs();
        let (s, c) = phi.sin_cos();
        let rot = |a: &[f64]| -> Vec<f64> {
            let mut out = vec![0.0; n * n];
            for bi in 0..n / 2 {
                for bj in 0..n / 2 {
                    let e = |r: usize, cc: usize| a[(2 * bi + r) * n + 2 * bj + cc];
                    // Rᵀ B R, R = [[c, −s], [s, c]]
                    let b = [[e(0, 0), e(0, 1)], [e(1, 0), e(1, 1)]];
                    let br = [[b[0][0] * c + b[0][1] * s, -b[0][0] * s + b[0][1] * c], [b[1][0] * c + b[1][1] * s, -b[1][0] * s + b[1][1] * c]];
                    let o = [[c * br[0][0] + s * br[1][0], c * br[0][1] + s * br[1][1]], [-s * br[0][0] + c * br[1][0], -s * br[0][1] + c * br[1][1]]];
                    for r in 0..2 {
                        for cc in 0..2 {
                            out[(2 * bi + r) * n + 2 * bj + cc] = o[r][cc];
                        }
                    }
                }
            }
            out
        };
        Mats { m: Cow::Owned(rot(&self.rotor.m)), d: Cow::Owned(rot(&self.d)), k: Cow::Owned(rot(&self.rotor.k)) }
    }

    /// The unbalance forces in the frame's axes at time `t` (length `N`): `m e Ω² e^{i(phase + χ)}`
    /// at the node, `f_α = −z F_y`, `f_β = z F_x`; `χ = (Ω − ν) t`.
    pub fn forcing(&self, t: f64) -> Vec<f64> {
        self.forcing_kin(&self.kin(t))
    }

    /// The unbalance forces for kinematics `k`: `m e (Ω² − i Ω̇) e^{i(phase + χ)}` (the
    /// unbalance mass's inertia force `−m r̈`, `r = e e^{iφ}`).
    pub(crate) fn forcing_kin(&self, k: &Kin) -> Vec<f64> {
        let r = &self.rotor;
        let mut f = vec![0.0; r.dofs()];
        for u in &r.unbalances {
            let force = C::new(u.me * k.w * k.w, -u.me * k.wdot) * C::from_polar(1.0, u.phase + k.chi);
            let (ix, iy, tilt) = r.node_dofs(u.node);
            f[ix] += force.re;
            f[iy] += force.im;
            if let Some((ia, ib)) = tilt {
                f[ia] += -u.offset * force.im;
                f[ib] += u.offset * force.re;
            }
        }
        f
    }

    /// [`LinearRotorField::forcing_kin`] with the speed `w` and the rotor's angle `chi` of type
    /// `T`: `m e (Ω² − i Ω̇) e^{i(phase + χ)}` at the node, the offset's moments.
    fn forcing_generic<T: Real>(&self, w: T, wdot: f64, chi: T) -> Vec<T> {
        let r = &self.rotor;
        let mut f = vec![T::cst(0.0); r.dofs()];
        for u in &r.unbalances {
            let (s, c) = (chi + u.phase).sin_cos();
            let w2 = w * w * u.me;
            // (m e Ω² − i m e Ω̇)(cos + i sin)
            let re = w2 * c + s * (u.me * wdot);
            let im = w2 * s - c * (u.me * wdot);
            let (ix, iy, tilt) = r.node_dofs(u.node);
            f[ix] = f[ix] + re;
            f[iy] = f[iy] + im;
            if let Some((ia, ib)) = tilt {
                f[ia] = f[ia] - im * u.offset;
                f[ib] = f[ib] + re * u.offset;
            }
        }
        f
    }

    /// The residual `R(x) − A a` of the `N + Σ n` equations (generalised forces minus inertia
    /// forces, module docs) at state `x` and accelerations `acc`, generic over the number type.
    pub(crate) fn residual<T: Real>(&self, mats: &Mats, kin: &Kin, x: &[T], acc: &[f64], out: &mut [T]) {
        self.residual_spin(mats, kin, None, x, acc, out)
    }

    /// [`LinearRotorField::residual`] with the rotor's angle and speed carried as numbers of
    /// type `T` too (`spin`: `χ + δχ`, `Ω + δΩ`, the increments of value 0; in fixed axes, for
    /// the exact Jacobian of a torque-driven run-up, [`super::runup`]).
    pub(crate) fn residual_spin<T: Real>(&self, mats: &Mats, kin: &Kin, spin: Option<&SpinVar<T>>, x: &[T], acc: &[f64], out: &mut [T]) {
        let n = self.rotor.dofs();
        let nc = self.coords();
        let nu = kin.nu;
        let (w, chi) = match spin {
            None => (T::cst(kin.w), T::cst(kin.chi)),
            Some(sp) => (sp.w + kin.w, sp.chi + kin.chi),
        };
        let (p, pd) = (&x[..n], &x[nc..nc + n]);
        // v = ṗ + ν J p, a_s = p̈ + 2ν J ṗ − ν² p (J (a, b) = (−b, a) per pair)
        let mut v = Vec::with_capacity(n);
        let mut a = Vec::with_capacity(n);
        for m in 0..n / 2 {
            let (i, j) = (2 * m, 2 * m + 1);
            v.push(pd[i] - p[j] * nu);
            v.push(pd[j] + p[i] * nu);
            a.push(pd[j] * (-2.0 * nu) - p[i] * (nu * nu) + acc[i]);
            a.push(pd[i] * (2.0 * nu) - p[j] * (nu * nu) + acc[j]);
        }
        let f: Vec<T> = match spin {
            None => self.forcing_kin(kin).into_iter().map(T::cst).collect(),
            Some(_) => self.forcing_generic(w, kin.wdot, chi),
        };
        for i in 0..n {
            let mut s = f[i];
            let (mr, dr, kr) = (&mats.m[i * n..(i + 1) * n], &mats.d[i * n..(i + 1) * n], &mats.k[i * n..(i + 1) * n]);
            for j in 0..n {
                if mr[j] != 0.0 {
                    s = s - a[j] * mr[j];
                }
                if dr[j] != 0.0 {
                    s = s - v[j] * dr[j];
                }
                if kr[j] != 0.0 {
                    s = s - p[j] * kr[j];
                }
            }
            out[i] = s;
        }
        if !self.rotor.rotor_fixed_mass.is_empty() {
            // inertia fixed to the rotor (LinearRotor::rotor_fixed_mass): with M_f = T(χ) M_rot
            // T(χ)ᵀ, the force M_f a + Ω (J M_f − M_f J) v in the frame's components
            let mf = super::turn_blocks(&self.rotor.rotor_fixed_mass, n, chi);
            let jv: Vec<T> = (0..n).map(|i| if i.is_multiple_of(2) { -v[i + 1] } else { v[i - 1] }).collect();
            let mut mv = vec![T::cst(0.0); n];
            let mut rest = vec![T::cst(0.0); n];
            for i in 0..n {
                let row = &mf[i * n..(i + 1) * n];
                let (mut sv, mut sr) = (T::cst(0.0), T::cst(0.0));
                for j in 0..n {
                    sv = sv + row[j] * v[j];
                    sr = sr + row[j] * a[j] - row[j] * jv[j] * w;
                }
                mv[i] = sv;
                rest[i] = sr;
            }
            for i in 0..n {
                let jmv = if i.is_multiple_of(2) { -mv[i + 1] } else { mv[i - 1] };
                out[i] = out[i] - rest[i] - jmv * w;
            }
        }
        if let Some(sp) = spin {
            // the speed's increment through C(Ω) + Ω G and K(Ω)
            for i in 0..n {
                let mut s = T::cst(0.0);
                for j in 0..n {
                    let (dd, dk) = (sp.dd[i * n + j], sp.dk[i * n + j]);
                    if dd != 0.0 {
                        s = s + v[j] * dd;
                    }
                    if dk != 0.0 {
                        s = s + p[j] * dk;
                    }
                }
                out[i] = out[i] - sp.w * s;
            }
        }
        if kin.wdot != 0.0 {
            // Ω̇ K_st q, K_st = ½ G by default, from the term ½ φ̇ q̇ᵀ G' q of the kinetic energy
            // (LinearRotor::spin_stiffness; module docs of crate::linear_rotor, "Torque drives
            // and gravity"); run-ups are in fixed axes
            let ks = self.rotor.spin_stiffness_matrix();
            for i in 0..n {
                for j in 0..n {
                    let kij = ks[i * n + j];
                    if kij != 0.0 {
                        out[i] = out[i] - p[j] * (kin.wdot * kij);
                    }
                }
            }
        }
        // gravity: the structure's weight, constant in fixed axes; in the frame's components
        // each pair (x, y), (α, β) of the load and g itself turn by R(−ν t) (Tᵀ f)
        let grav = self.rotor.gravity.as_ref().map(|gr| {
            let (s, c) = kin.frame.sin_cos();
            let turn = |a: f64, b: f64| if kin.frame == 0.0 { (a, b) } else { (c * a + s * b, c * b - s * a) };
            for m in 0..n / 2 {
                let (lx, ly) = turn(gr.load[2 * m], gr.load[2 * m + 1]);
                out[2 * m] = out[2 * m] + lx;
                out[2 * m + 1] = out[2 * m + 1] + ly;
            }
            let (gx, gy) = turn(gr.g[0], gr.g[1]);
            [gx, gy]
        });
        for (g, b) in self.balls.iter().enumerate() {
            let (psi, psid) = (x[n + g], x[nc + n + g]);
            let (s, c) = (psi + chi).sin_cos();
            let rate = psid + w;
            let w2 = rate * rate;
            // θ̈ = ψ̈ + Ω̇
            let pdd = acc[n + g] + kin.wdot;
            let mr2 = b.m * b.r * b.r;
            // the race centre's acceleration a_u − z J ω̇ (J (a, b) = (−b, a))
            let (mut ax, mut ay) = (a[b.ix], a[b.iy]);
            if let Some((ia, ib)) = b.tilt {
                ax = ax + a[ib] * b.z;
                ay = ay - a[ia] * b.z;
            }
            let ax = ax + (s * pdd + c * w2) * (-b.r);
            let ay = ay + (c * pdd - s * w2) * b.r;
            out[b.ix] = out[b.ix] - ax * b.m;
            out[b.iy] = out[b.iy] - ay * b.m;
            out[n + g] = psid * (-b.drag) - (c * ay - s * ax) * (b.m * b.r);
            if let Some([gx, gy]) = grav {
                // the ball's weight m_b g on the race centre (x + z β, y − z α) and its torque
                // m_b R e⊥·g about the axis (g in the frame's components)
                out[b.ix] = out[b.ix] + b.m * gx;
                out[b.iy] = out[b.iy] + b.m * gy;
                if let Some((ia, ib)) = b.tilt {
                    out[ib] = out[ib] + b.z * b.m * gx;
                    out[ia] = out[ia] + (-b.z * b.m * gy);
                }
                out[n + g] = out[n + g] + (s * (-gx) + c * gy) * (b.m * b.r);
            }
            if let Some((ia, ib)) = b.tilt {
                // generalised inertia on the tilts through the offset: z J F, F = m a_j
                out[ia] = out[ia] + ay * (b.m * b.z);
                out[ib] = out[ib] - ax * (b.m * b.z);
                // the balls' tilt inertia (module docs): τ = (α, β), ω = τ̇, ω̇ the absolute
                // rates and accelerations in the frame's components; e = (c, s), e⊥ = (−s, c)
                let (ta, tb) = (p[ia], p[ib]);
                let (oa, ob) = (v[ia], v[ib]);
                let (da, db) = (a[ia], a[ib]);
                let sigma = oa * s - ob * c;
                let o_e = oa * c + ob * s;
                let sigma_dot = (da * s - db * c) + rate * o_e;
                // I = −mR² (σ̇ e⊥ − θ̇ σ e) − ½ mR² θ̈ J τ − mR² θ̇ J ω
                let ia_x = (sigma_dot * s + rate * sigma * c) * mr2 + tb * (0.5 * mr2 * pdd) + rate * ob * mr2;
                let ia_y = (sigma_dot * (-c) + rate * sigma * s) * mr2 - ta * (0.5 * mr2 * pdd) - rate * oa * mr2;
                out[ia] = out[ia] - ia_x;
                out[ib] = out[ib] - ia_y;
                // ball: ½ mR² (ω̇ × τ) − mR² σ (ω·e)
                out[n + g] = out[n + g] - (da * tb - db * ta) * (0.5 * mr2) + sigma * o_e * mr2;
            }
        }
        if let Some((y, s_phi, rest)) = self.chart(chi, w, p, &v) {
            // the rotor-fixed chart (LinearRotor::spin_chart): (I_p Ω̇ + Σ_j m_b R² θ̈_j) Σ_χ q
            // on the structure, m_b R² s̈ on each ball, s̈ = a·Y + Ω̇ ∂s/∂φ + V (after the balls'
            // own terms, which set their rows)
            let mut theta = self.rotor.polar_inertia * kin.wdot;
            for (g, b) in self.balls.iter().enumerate() {
                let mr2 = b.m * b.r * b.r;
                theta += mr2 * (kin.wdot + acc[n + g]);
            }
            let ay = (0..n).fold(T::cst(0.0), |acc_, i| acc_ + a[i] * y[i]);
            let sdd = ay + s_phi * kin.wdot + rest;
            for i in 0..n {
                out[i] = out[i] - y[i] * theta;
            }
            for (g, b) in self.balls.iter().enumerate() {
                out[n + g] = out[n + g] - sdd * (b.m * b.r * b.r);
            }
        }
    }

    /// The rotor-fixed chart's terms ([`LinearRotor::spin_chart`]) at positions `p` and absolute
    /// velocities `v` in the frame's components, the rotor's angle in the frame `chi` and its
    /// speed `w`: `Y = Σ_χ p` (`Σ_χ = T(χ) Σ T(χ)ᵀ`), `∂s/∂φ = −(J p)·Y` and the rest of `s̈`
    /// beyond the accelerations, `V = −2Ω (J v)·Y − Ω² p·Y + uᵀ Σ_χ u` (`u = v − Ω J p`): from
    /// `s = ½ q_rᵀ Σ q_r` with `q_r = T(χ)ᵀ p`, `q̇_r = T(χ)ᵀ u`,
    /// `q̈_r = T(χ)ᵀ (a − Ω̇ J p − 2Ω J v − Ω² p)`, so `s̈ = a·Y + Ω̇ ∂s/∂φ + V`. `None` without a
    /// chart.
    pub(crate) fn chart<T: Real>(&self, chi: T, w: T, p: &[T], v: &[T]) -> Option<(Vec<T>, T, T)> {
        if self.rotor.spin_chart.is_empty() {
            return None;
        }
        let n = self.rotor.dofs();
        let sf = super::turn_blocks(&self.rotor.spin_chart, n, chi);
        let jm = |z: &[T], i: usize| if i.is_multiple_of(2) { -z[i + 1] } else { z[i - 1] };
        let u: Vec<T> = (0..n).map(|i| v[i] - jm(p, i) * w).collect();
        let (mut y, mut quad) = (vec![T::cst(0.0); n], T::cst(0.0));
        for i in 0..n {
            let (mut yi, mut ui) = (T::cst(0.0), T::cst(0.0));
            for j in 0..n {
                yi = yi + sf[i * n + j] * p[j];
                ui = ui + sf[i * n + j] * u[j];
            }
            y[i] = yi;
            quad = quad + u[i] * ui;
        }
        let (mut jpy, mut jvy, mut py) = (T::cst(0.0), T::cst(0.0), T::cst(0.0));
        for i in 0..n {
            jpy = jpy + jm(p, i) * y[i];
            jvy = jvy + jm(v, i) * y[i];
            py = py + p[i] * y[i];
        }
        let rest = quad - w * jvy * 2.0 - w * w * py;
        Some((y, -jpy, rest))
    }

    /// The symmetric mass matrix `A(ψ)` of the `N + Σ n` accelerations at time `t` (module docs).
    pub(crate) fn mass_matrix(&self, mats: &Mats, chi: f64, x: &[f64]) -> Vec<f64> {
        let n = self.rotor.dofs();
        let nc = self.coords();
        let mut a = vec![0.0; nc * nc];
        for i in 0..n {
            a[i * nc..i * nc + n].copy_from_slice(&mats.m[i * n..(i + 1) * n]);
        }
        if !self.rotor.spin_chart.is_empty() {
            // the chart's m_b R² Σ_χ q between the structure and each ball
            let sf = super::turn_blocks(&self.rotor.spin_chart, n, chi);
            let y: Vec<f64> = (0..n).map(|i| (0..n).map(|j| sf[i * n + j] * x[j]).sum()).collect();
            for (g, b) in self.balls.iter().enumerate() {
                let mr2 = b.m * b.r * b.r;
                for i in 0..n {
                    a[i * nc + n + g] += mr2 * y[i];
                    a[(n + g) * nc + i] += mr2 * y[i];
                }
            }
        }
        if !self.rotor.rotor_fixed_mass.is_empty() {
            let mf = self.rotor.rotor_fixed_in(chi);
            for i in 0..n {
                for j in 0..n {
                    a[i * nc + j] += mf[i * n + j];
                }
            }
        }
        for (g, b) in self.balls.iter().enumerate() {
            let (s, c) = (x[n + g] + chi).sin_cos();
            let j = n + g;
            let mr2 = b.m * b.r * b.r;
            // race centre (x + z β, y − z α): rows of P
            let mut px = vec![(b.ix, 1.0)];
            let mut py = vec![(b.iy, 1.0)];
            if let Some((ia, ib)) = b.tilt {
                px.push((ib, b.z));
                py.push((ia, -b.z));
            }
            for (row, e) in [(&px, -b.m * b.r * s), (&py, b.m * b.r * c)] {
                for &(i, ci) in row.iter() {
                    for &(k, ck) in row.iter() {
                        a[i * nc + k] += b.m * ci * ck;
                    }
                    a[i * nc + j] += ci * e;
                    a[j * nc + i] += ci * e;
                }
            }
            a[j * nc + j] += mr2;
            if let Some((ia, ib)) = b.tilt {
                // mR² e⊥ e⊥ᵀ on the tilts, −½ mR² J τ between the tilts and the ball
                a[ia * nc + ia] += mr2 * s * s;
                a[ia * nc + ib] -= mr2 * s * c;
                a[ib * nc + ia] -= mr2 * s * c;
                a[ib * nc + ib] += mr2 * c * c;
                let (ta, tb) = (x[ia], x[ib]);
                a[ia * nc + j] += 0.5 * mr2 * tb;
                a[j * nc + ia] += 0.5 * mr2 * tb;
                a[ib * nc + j] -= 0.5 * mr2 * ta;
                a[j * nc + ib] -= 0.5 * mr2 * ta;
            }
        }
        a
    }

    /// The accelerations `(p̈, ψ̈)` at `(t, x)`: `A⁻¹ R` (`None` if `A` is singular, which a
    /// validated rotor's positive definite `M` rules out).
    pub fn accelerations(&self, t: f64, x: &[f64]) -> Option<Vec<f64>> {
        self.accelerations_with(&self.mats(t), &self.kin(t), x)
    }

    /// [`LinearRotorField::accelerations`] for given matrices and kinematics.
    pub(crate) fn accelerations_with(&self, mats: &Mats, kin: &Kin, x: &[f64]) -> Option<Vec<f64>> {
        let nc = self.coords();
        let mut r = vec![0.0; nc];
        self.residual::<f64>(mats, kin, x, &vec![0.0; nc], &mut r);
        self.add_real_balls(kin, x, &mut r);
        let lu = Lu::factored(self.mass_matrix(mats, kin.chi, x), nc)?;
        lu.solve(&mut r);
        Some(r)
    }

    /// The residuals of the `N + Σ n` equations at `(t, x)` for accelerations `acc`: zero at the
    /// accelerations of [`LinearRotorField::accelerations`]. For checks.
    pub fn residuals(&self, t: f64, x: &[f64], acc: &[f64]) -> Vec<f64> {
        let mats = self.mats(t);
        let mut r = vec![0.0; self.coords()];
        let kin = self.kin(t);
        self.residual::<f64>(&mats, &kin, x, acc, &mut r);
        self.add_real_balls(&kin, x, &mut r);
        r
    }

    /// The mass matrix `A(ψ)` at `(t, x)` (row-major, `(N + Σ n)²`). For checks.
    pub fn mass(&self, t: f64, x: &[f64]) -> Vec<f64> {
        self.mass_matrix(&self.mats(t), self.kin(t).chi, x)
    }

    /// Displacement scale: `(Σ|m e| + Σ n m_b R) / m̄`, `m̄` the mean diagonal of `M` over the
    /// translations plus the balls' mass, or `1e-6` m when that vanishes.
    fn length(&self) -> f64 {
        let r = &self.rotor;
        let n = r.dofs();
        let mass: f64 = r.node_starts().into_iter().map(|i| r.m[i * n + i]).sum::<f64>() / r.nodes as f64 + self.balls.iter().map(|b| b.m).sum::<f64>();
        let me: f64 = r.unbalances.iter().map(|u| u.me.abs()).sum::<f64>() + self.balls.iter().map(|b| b.m * b.r).sum::<f64>();
        let l = me / mass;
        if l > 0.0 && l.is_finite() {
            l
        } else {
            1e-6
        }
    }

    /// The balanced state's closed-form start: every race centre at rest on the axis.
    ///
    /// At a balanced state every ball rests relative to the rotor, so the tangential force on
    /// each vanishes, `e⊥_j · u_p = 0` with `u_p = E_p p` the race centre's displacement
    /// `(x + z β, y − z α)`; two non-collinear balls give `u_p = 0`. With `b_q` plane `q`'s
    /// resultant ball force `m_b R Ω² Σ e^{iψ_j}` (two components) and `G_q = E_qᵀ` its placement
    /// (the offset's moments included), the linear stationary equations in turning axes at
    /// `t = 0`, `A p = f_r + Σ_q G_q b_q` with `A = K_r − Ω² M_r − Ω² M_b + Ω D_r J` (+ the
    /// rotor-fixed inertia's `Ω² J M_rot J`; `M_b` the balls' lumped mass), and `E_p p = 0` give
    /// the `2P × 2P` system `Σ_q (E_p A⁻¹ G_q) b_q = −E_p A⁻¹ f_r`; each plane's balls then follow
    /// from its resultant (`m_b R Σ e^{iψ_j} = b_q / Ω²`: pairs at `arg ± φ`, an odd ball on the
    /// resultant) and `p` from `A p = f_r + Σ G_q b_q`. One plane is the case `P = 1`: where the
    /// unbalances sit in the balancer's plane its resultant is `−Ω² Σ m e e^{i phase}` (taken so,
    /// exactly) and `p = 0`; where they sit elsewhere on a flexible shaft the balls must cancel the
    /// unbalances' response at the race, not their sum (`b = −(E A⁻¹ G)⁻¹ E A⁻¹ f_r`, which
    /// grows without bound near an antiresonance of the race: no balanced state there once it
    /// exceeds the capacity). Taking the sum instead (before 2026-11-28) started Newton's method
    /// closer to the equilibrium with the balls opposite each other, which it then reported as
    /// the balanced state.
    /// Exact where the balancer nodes do not tilt at balance (a rigid rotor: both race centres
    /// on the axis put it on the axis); where they tilt (a flexible shaft) the tilted ring's
    /// push `−m_b R² σ_j (ω·e_j)` on the balls and the balls' tilt inertia (lumped in `M_b`)
    /// move the state at second and first order in the tilt: a start for Newton's method.
    ///
    /// Transformed to fixed axes (`q̇ = Ω J p`) for [`Frame::Fixed`]. With gravity the
    /// static sag `q_s = K⁻¹ (load + Σ m_b Pᵀ g)` (fixed axes: at rest there, so `ṗ = −Ω J q_s`
    /// in turning axes) is added, the balls' swing is left to the shooting (zero where `K` is
    /// singular). `None` where a plane cannot supply its resultant (`|b_p| > n_p m_b R Ω²`), a
    /// plane has fewer than 2 balls, the planes cannot hold the race centres on the axis (the
    /// `2P × 2P` system singular, e.g. two planes at one node without offsets), or at `Ω = 0`.
    pub fn balanced_guess(&self) -> Option<Vec<f64>> {
        let r = &self.rotor;
        if r.balancers.is_empty() || r.balancers.iter().any(|b| b.balls < 2) || self.omega == 0.0 {
            return None;
        }
        let b = r.balancers[0];
        if r.balancers.len() > 1 || r.unbalances.iter().any(|u| u.node != b.node || u.offset != b.offset) {
            return self.balanced_guess_planes();
        }
        // one plane with every unbalance in it: the resultant is −Σ m e e^{i phase} exactly
        // (the P-plane solve gives it to round-off, whose sign of a zero imaginary part would
        // move the balls' angles by 2π between calls: arg(−a) = π here)
        let res: C = r.unbalances.iter().map(|u| C::from_polar(u.me, u.phase)).sum();
        let need = -res + C::new(0.0, 0.0);
        let psi = ball_angles(b.balls, b.ball_mass, b.radius, need)?;
        self.state_with_balls(self.unbalance_forces(), &psi, None)
    }

    /// The balanced state's start from the balls' angles `psi` (all planes in order): the
    /// structure from `A p = f + Σ_q G_q m_b R Ω² Σ_j e^{iψ_j}` with `lu` the factored `A`
    /// ([`Self::stationary_matrix`]; `None`: factored here, and `p = 0` without a solve where
    /// the forces cancel), then [`Self::guess_state`].
    fn state_with_balls(&self, mut f: Vec<f64>, psi: &[f64], lu: Option<&Lu>) -> Option<Vec<f64>> {
        let w = self.omega;
        let mut first = 0;
        for (q, b) in self.rotor.balancers.iter().enumerate() {
            let ball_f: C = psi[first..first + b.balls].iter().map(|&p| C::from_polar(b.ball_mass * b.radius * w * w, p)).sum();
            self.add_plane_force(q, ball_f, &mut f);
            first += b.balls;
        }
        let n = self.rotor.dofs();
        let p = match lu {
            Some(lu) => {
                lu.solve(&mut f);
                f
            }
            None if f.iter().all(|v| *v == 0.0) => vec![0.0; n],
            None => {
                Lu::factored(self.stationary_matrix(), n)?.solve(&mut f);
                f
            }
        };
        Some(self.guess_state(&p, psi))
    }

    /// [`LinearRotorField::balanced_guess`]: the race centres on the axis, `P ≥ 1` planes.
    fn balanced_guess_planes(&self) -> Option<Vec<f64>> {
        let r = &self.rotor;
        let (lu, f, shares) = self.shares_planes()?;
        let mut psi = vec![];
        for (b, &need) in r.balancers.iter().zip(&shares) {
            psi.extend(ball_angles(b.balls, b.ball_mass, b.radius, need)?);
        }
        self.state_with_balls(f, &psi, Some(&lu))
    }

    /// Each balancer plane's **share**: the resultant `m_b R Σ e^{iψ_j}` (kg·m, complex,
    /// turning axes) its balls must supply for every race centre to rest on the axis, from the
    /// `2P × 2P` system of [`LinearRotorField::balanced_guess`] (one plane with every unbalance
    /// in it: `−Σ m e e^{i phase}` exactly, as there), whether or not the plane's capacity
    /// `n m_b R` reaches it. `None` at `Ω = 0`, without a balancer, or where the system is
    /// singular. The partially balanced state's starts
    /// ([`crate::linear_rotor::partial::share_guesses`]).
    pub fn plane_shares(&self) -> Option<Vec<C>> {
        let r = &self.rotor;
        if r.balancers.is_empty() || self.omega == 0.0 {
            return None;
        }
        let b = r.balancers[0];
        if r.balancers.len() > 1 || r.unbalances.iter().any(|u| u.node != b.node || u.offset != b.offset) {
            return self.shares_planes().map(|(_, _, s)| s);
        }
        let res: C = r.unbalances.iter().map(|u| C::from_polar(u.me, u.phase)).sum();
        Some(vec![-res + C::new(0.0, 0.0)])
    }

    /// The structure's stationary state (turning axes, the balls at rest at `psi`, all planes
    /// in order) from `A p = f_r + Σ_q G_q m_b R Ω² Σ_j e^{iψ_j}`: the linear stationary
    /// equations at fixed balls ([`LinearRotorField::balanced_guess`]'s), a start for Newton's
    /// method where the balls are not balanced. `None` where `A` is singular.
    pub fn state_at_balls(&self, psi: &[f64]) -> Option<Vec<f64>> {
        if psi.len() != self.rotor.total_balls() {
            return None;
        }
        self.state_with_balls(self.unbalance_forces(), psi, None)
    }

    /// The factored `A`, the unbalances' forces and each plane's share (the resultant
    /// `m_b R Σ e^{iψ}`, kg·m) of the `2P × 2P` system ([`LinearRotorField::balanced_guess`]).
    fn shares_planes(&self) -> Option<(Lu, Vec<f64>, Vec<C>)> {
        let r = &self.rotor;
        let n = r.dofs();
        let w = self.omega;
        let np = r.balancers.len();
        let lu = Lu::factored(self.stationary_matrix(), n)?;
        let f = self.unbalance_forces();
        let mut y0 = f.clone();
        lu.solve(&mut y0);
        // A⁻¹ G_q, columns (re, im) of each plane's unit force
        let mut cols = vec![];
        for q in 0..np {
            for unit in [C::new(1.0, 0.0), C::new(0.0, 1.0)] {
                let mut g = vec![0.0; n];
                self.add_plane_force(q, unit, &mut g);
                lu.solve(&mut g);
                cols.push(g);
            }
        }
        // E_p v: the race centre's displacement (x + z β, y − z α) of plane p
        let race = |p: usize, v: &[f64]| -> [f64; 2] {
            let mut e = vec![0.0; n];
            self.add_plane_force(p, C::new(1.0, 0.0), &mut e);
            let ex: f64 = e.iter().zip(v).map(|(a, b)| a * b).sum();
            e.iter_mut().for_each(|x| *x = 0.0);
            self.add_plane_force(p, C::new(0.0, 1.0), &mut e);
            let ey: f64 = e.iter().zip(v).map(|(a, b)| a * b).sum();
            [ex, ey]
        };
        let m = 2 * np;
        let mut s = vec![0.0; m * m];
        let mut rhs = vec![0.0; m];
        for p in 0..np {
            let u0 = race(p, &y0);
            rhs[2 * p] = -u0[0];
            rhs[2 * p + 1] = -u0[1];
            for (k, col) in cols.iter().enumerate() {
                let u = race(p, col);
                s[2 * p * m + k] = u[0];
                s[(2 * p + 1) * m + k] = u[1];
            }
        }
        let lu_s = Lu::factored(s, m)?;
        lu_s.solve(&mut rhs);
        if rhs.iter().any(|v| !v.is_finite()) {
            return None;
        }
        // each plane's resultant m_b R Σ e^{iψ} = b_q / Ω²
        let shares = (0..np).map(|q| C::new(rhs[2 * q], rhs[2 * q + 1]) / (w * w)).collect();
        Some((lu, f, shares))
    }

    /// The unbalances' forces `Ω² m e e^{i phase}` in turning axes at `t = 0` with the moments
    /// of their offsets (`N` components).
    fn unbalance_forces(&self) -> Vec<f64> {
        let r = &self.rotor;
        let w = self.omega;
        let mut f = vec![0.0; r.dofs()];
        for u in &r.unbalances {
            let force = C::from_polar(u.me * w * w, u.phase);
            let (ix, iy, tilt) = r.node_dofs(u.node);
            f[ix] += force.re;
            f[iy] += force.im;
            if let Some((ia, ib)) = tilt {
                f[ia] -= u.offset * force.im;
                f[ib] += u.offset * force.re;
            }
        }
        f
    }

    /// Adds `G_q F`: a force `F` (complex, turning axes) on the race centre of plane `q`, with
    /// its offset's moments, to `f`.
    fn add_plane_force(&self, q: usize, force: C, f: &mut [f64]) {
        let first: usize = self.rotor.balancers[..q].iter().map(|b| b.balls).sum();
        let ball = self.balls[first];
        let z = self.rotor.balancers[q].offset;
        f[ball.ix] += force.re;
        f[ball.iy] += force.im;
        if let Some((ia, ib)) = ball.tilt {
            f[ia] -= z * force.im;
            f[ib] += z * force.re;
        }
    }

    /// The stationary equations' matrix in turning axes at `t = 0`,
    /// `A = K − Ω² (M + M_b) + Ω D J` (+ `Ω² J M_rot J`), row-major `N × N`.
    fn stationary_matrix(&self) -> Vec<f64> {
        let r = &self.rotor;
        let n = r.dofs();
        let w = self.omega;
        let mb = r.ball_mass_matrix();
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                // (D J)_{ij}: column j of D J is D times column j of J
                let dj = if j.is_multiple_of(2) { self.d[i * n + j + 1] } else { -self.d[i * n + j - 1] };
                a[i * n + j] = r.k[i * n + j] - w * w * (r.m[i * n + j] + mb[i * n + j]) + w * dj;
            }
        }
        if !r.rotor_fixed_mass.is_empty() {
            // the rotor-fixed inertia's Ω² J M_rot J p (LinearRotor::rotor_fixed_mass)
            let mr = &r.rotor_fixed_mass;
            let mj = |i: usize, j: usize| if j.is_multiple_of(2) { mr[i * n + j + 1] } else { -mr[i * n + j - 1] };
            for i in 0..n {
                for j in 0..n {
                    let jmj = if i.is_multiple_of(2) { -mj(i + 1, j) } else { mj(i - 1, j) };
                    a[i * n + j] += w * w * jmj;
                }
            }
        }
        a
    }

    /// The state of the structure `p` (turning axes) and the balls `psi` at rest in the field's
    /// frame, with gravity's sag added ([`LinearRotorField::balanced_guess`]).
    fn guess_state(&self, p: &[f64], psi: &[f64]) -> Vec<f64> {
        let n = self.rotor.dofs();
        let w = self.omega;
        let nc = self.coords();
        let mut x = vec![0.0; 2 * nc];
        x[..n].copy_from_slice(p);
        x[n..nc].copy_from_slice(psi);
        if self.frame == Frame::Fixed {
            for m in 0..n / 2 {
                x[nc + 2 * m] = -w * p[2 * m + 1];
                x[nc + 2 * m + 1] = w * p[2 * m];
            }
        }
        if let Some(sag) = self.sag() {
            for i in 0..n {
                x[i] += sag[i];
            }
            if self.frame == Frame::Rotating {
                // at rest in fixed axes: ṗ = −Ω J q_s
                for m in 0..n / 2 {
                    x[nc + 2 * m] += w * sag[2 * m + 1];
                    x[nc + 2 * m + 1] -= w * sag[2 * m];
                }
            }
        }
        x
    }

    /// The static sag under gravity in fixed axes, `q_s = K⁻¹ (load + Σ_planes n m_b Pᵀ g)`
    /// (`P` the map to the race centre `(x + z β, y − z α)`): `None` without gravity or where `K`
    /// is singular.
    pub fn sag(&self) -> Option<Vec<f64>> {
        let gr = self.rotor.gravity.as_ref()?;
        let n = self.rotor.dofs();
        let mut f = gr.load.clone();
        for b in &self.balls {
            f[b.ix] += b.m * gr.g[0];
            f[b.iy] += b.m * gr.g[1];
            if let Some((ia, ib)) = b.tilt {
                f[ib] += b.z * b.m * gr.g[0];
                f[ia] -= b.z * b.m * gr.g[1];
            }
        }
        let lu = Lu::factored(self.rotor.k.clone(), n)?;
        lu.solve(&mut f);
        f.iter().all(|v| v.is_finite()).then_some(f)
    }

    /// The state in fixed axes at time `t` of the state `x` in turning axes at `t` (same ball
    /// angles): `q = T(Ω t) p`, `q̇ = T(Ω t)(ṗ + Ω J p)`.
    pub fn rotating_to_fixed(&self, t: f64, x: &[f64]) -> Vec<f64> {
        let n = self.rotor.dofs();
        let nc = self.coords();
        let w = self.omega;
        let (s, c) = (w * t).sin_cos();
        let mut y = x.to_vec();
        for m in 0..n / 2 {
            let (i, j) = (2 * m, 2 * m + 1);
            let (px, py) = (x[i], x[j]);
            let (vx, vy) = (x[nc + i] - w * py, x[nc + j] + w * px);
            y[i] = c * px - s * py;
            y[j] = s * px + c * py;
            y[nc + i] = c * vx - s * vy;
            y[nc + j] = s * vx + c * vy;
        }
        y
    }

    /// The Jacobian of the first `2 N_c` components for given matrices and kinematics into the
    /// row-major `jac` with row length `dim ≥ 2 N_c` (the columns beyond `2 N_c` untouched).
    pub(crate) fn jacobian_with(&self, mats: &Mats, kin: &Kin, x: &[f64], jac: &mut [f64], dim: usize) {
        let nc = self.coords();
        let d2 = 2 * nc;
        for r in 0..d2 {
            jac[r * dim..r * dim + d2].iter_mut().for_each(|v| *v = 0.0);
        }
        for i in 0..nc {
            jac[i * dim + nc + i] = 1.0;
        }
        let Some(lu) = Lu::factored(self.mass_matrix(mats, kin.chi, x), nc) else {
            for r in nc..d2 {
                jac[r * dim..r * dim + d2].iter_mut().for_each(|v| *v = f64::NAN);
            }
            return;
        };
        let mut acc = vec![0.0; nc];
        self.residual::<f64>(mats, kin, x, &vec![0.0; nc], &mut acc);
        lu.solve(&mut acc);
        // ∂(R − A a)/∂x at the current a, SEEDS directions per pass; then A⁻¹ of each column
        let mut xd = vec![Dual::<SEEDS>::cst(0.0); d2];
        let mut out = vec![Dual::<SEEDS>::cst(0.0); nc];
        let mut col = vec![0.0; nc];
        // a large rotor's Jacobian (~n³ operations, seconds at 800 DOFs) asks the thread's stop
        // probe once per pass: stopped, it is left NaN, which the analysis reports as non-finite
        // and its scan, asking the same probe, drops (the speed was not finished)
        let ask = d2 >= crate::analysis::STOPPABLE_EIGEN_N;
        for start in (0..d2).step_by(SEEDS) {
            if ask && crate::control::probe().is_some() {
                for r in nc..d2 {
                    jac[r * dim..r * dim + d2].iter_mut().for_each(|v| *v = f64::NAN);
                }
                return;
            }
            for (i, v) in xd.iter_mut().enumerate() {
                *v = if i >= start && i < start + SEEDS { Dual::var(x[i], i - start) } else { Dual::cst(x[i]) };
            }
            self.residual(mats, kin, &xd, &acc, &mut out);
            for k in 0..SEEDS.min(d2 - start) {
                for (c, o) in col.iter_mut().zip(&out) {
                    *c = o.d[k];
                }
                lu.solve(&mut col);
                for (r, c) in col.iter().enumerate() {
                    jac[(nc + r) * dim + start + k] = *c;
                }
            }
        }
    }
}

impl VectorField for LinearRotorField {
    fn dim(&self) -> usize {
        2 * self.coords()
    }

    fn rhs(&self, t: f64, x: &[f64], dx: &mut [f64]) {
        let nc = self.coords();
        dx[..nc].copy_from_slice(&x[nc..]);
        match self.accelerations(t, x) {
            Some(acc) => dx[nc..].copy_from_slice(&acc),
            None => dx[nc..].iter_mut().for_each(|v| *v = f64::NAN),
        }
    }

    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) {
        self.jacobian_with(&self.mats(t), &self.kin(t), x, jac, 2 * self.coords())
    }

    fn period(&self) -> Option<f64> {
        if self.omega == 0.0 {
            return None;
        }
        match self.frame {
            // gravity across the axis turns once per revolution in these axes
            Frame::Rotating if self.rotor.gravity.is_some() => Some(2.0 * PI / self.omega.abs()),
            Frame::Rotating if self.isotropic => None,
            Frame::Rotating => Some(PI / self.omega.abs()),
            Frame::Fixed => Some(2.0 * PI / self.omega.abs()),
        }
    }

    /// `Σ (n − 2)` over the planes with `n ≥ 3` balls whose race centre is on the axis and whose
    /// race is not tilted (to `1e-6` of the length scale, the tilt measured by its displacement
    /// `|τ| max(R, |z|)` of the race): there the balls only have to sum to their resultant, a
    /// family of dimension `n − 2`. (A tilted race breaks the family at second order in the tilt.)
    fn structural_zeros(&self, x: &[f64]) -> usize {
        let l = self.length();
        let r = &self.rotor;
        r.balancers
            .iter()
            .filter(|b| b.balls >= 3)
            .filter_map(|b| {
                let ix = r.dof(b.node, super::Direction::X)?;
                let (mut cx, mut cy, mut tilt) = (x[ix], x[ix + 1], 0.0);
                if let (Some(ia), Some(ib)) = (r.dof(b.node, super::Direction::Alpha), r.dof(b.node, super::Direction::Beta)) {
                    cx += b.offset * x[ib];
                    cy -= b.offset * x[ia];
                    tilt = x[ia].hypot(x[ib]) * b.radius.max(b.offset.abs());
                }
                (cx.hypot(cy) <= 1e-6 * l && tilt <= 1e-6 * l).then_some(b.balls - 2)
            })
            .sum()
    }

    fn component_name(&self, i: usize) -> String {
        let nc = self.coords();
        let n = self.rotor.dofs();
        let (rate, k) = if i >= nc { (true, i - nc) } else { (false, i) };
        let base = if k < n { self.rotor.dof_name(k) } else { format!("ψ_{} (ball {} angle)", k - n, k - n) };
        if rate {
            format!("rate of {base}")
        } else {
            base
        }
    }

    fn scales(&self) -> Vec<f64> {
        let l = self.length();
        let n = self.rotor.dofs();
        let nc = self.coords();
        let w = if self.omega != 0.0 { self.omega.abs() } else { 1.0 };
        (0..2 * nc)
            .map(|i| {
                let base = if i % nc < n { l } else { 1.0 };
                if i >= nc {
                    base * w
                } else {
                    base
                }
            })
            .collect()
    }
}

/// The field as an ODE system for the integrators of [`crate::ode`] (time simulation at constant
/// speed, usually in [`Frame::Fixed`]): the right-hand side of [`LinearRotorField`], and for the
/// implicit method (RODAS, or [`crate::ode::Method::Auto`] when the problem is stiff, as a shaft
/// model's high modes make it) the exact Jacobian of [`VectorField::jacobian`].
pub struct TimeSystem<'a>(pub &'a LinearRotorField);

impl crate::ode::System for TimeSystem<'_> {
    fn dim(&self) -> usize {
        VectorField::dim(self.0)
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        VectorField::rhs(self.0, t, y, dy)
    }

    fn jacobian(&self) -> Box<dyn crate::ode::Jacobian + '_> {
        Box::new(crate::ode::DenseJacobian::analytic(self, move |t, y, j| VectorField::jacobian(self.0, t, y, j)))
    }

    fn component_name(&self, i: usize) -> String {
        VectorField::component_name(self.0, i)
    }
}

/// The angles of `nb ≥ 2` balls of mass `m` on a race of radius `radius` at rest with
/// `m R Σ e^{iψ_j} = need`: pairs at `arg(need) ± φ`, an odd ball on `arg(need)`, with
/// `cos φ = |need|/(n m R)` (even `n`) or `(|need|/(m R) − 1)/(n − 1)` (odd); `None` where
/// `|need| > n m R`.
fn ball_angles(nb: usize, m: f64, radius: f64, need: C) -> Option<Vec<f64>> {
    let ratio = need.norm() / (m * radius);
    if ratio > nb as f64 || !ratio.is_finite() {
        return None;
    }
    let phase = if need.norm() > 0.0 { need.arg() } else { 0.0 };
    let cos_phi = if nb.is_multiple_of(2) { ratio / nb as f64 } else { (ratio - 1.0) / (nb - 1) as f64 };
    let phi = cos_phi.clamp(-1.0, 1.0).acos();
    let mut psi = vec![];
    if !nb.is_multiple_of(2) {
        psi.push(phase);
    }
    for _ in 0..nb / 2 {
        psi.push(phase + phi);
        psi.push(phase - phi);
    }
    Some(psi)
}
