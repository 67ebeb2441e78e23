//! Run-ups and run-downs of a [`LinearRotor`] with its balls in time, in fixed axes, under a
//! prescribed speed history ([`Drive::Speed`], [`Drive::Acceleration`], [`Drive::SpeedSchedule`])
//! or a torque ([`Drive::Torque`], [`Drive::Motor`], [`Drive::TorqueSchedule`]).
//!
//! **Prescribed speed.** With the rotor's angle `φ(t) = ∫ Ω dt` (exact for the drive's
//! piecewise-linear speed), the equations of [`crate::linear_rotor`] in fixed axes hold with
//! `Ω(t)` in place of `Ω`, the gyroscopic `Ω(t) G` with `Ω̇ K_st q` (from the kinetic energy's
//! `½ φ̇ q̇ᵀ G' q`, [`LinearRotor::spin_stiffness`]; `K_st = ½ G` by default; the rotor-fixed
//! chart's terms of [`LinearRotor::spin_chart`] where there is one), the speed-dependent
//! bearings at `Ω(t)`, and two more terms from the
//! acceleration `Ω̇`: the unbalance's inertia force `m e (Ω² − i Ω̇) e^{i(φ + phase)}` and the
//! balls' absolute angular acceleration `θ̈_j = Ω̇ + ψ̈_j` (`ψ_j` stays the angle relative to the
//! rotor). State `(q, ψ, q̇, ψ̇)`.
//!
//! **Torque.** The spin is a coordinate: state `(q, ψ, φ, q̇, ψ̇, φ̇)`, the speed `Ω = φ̇`, and the
//! spin's equation of [`crate::linear_rotor`] ("Torque drives and gravity") with the rotor's
//! polar moment [`LinearRotor::polar_inertia`] (required, > 0) and spin drag
//! [`LinearRotor::spin_damping`]. The structure's and balls' equations are those above with
//! `Ω̇ = φ̈` unknown; they are linear in `φ̈`, with the column `a_φ` of `φ̈` in the mass matrix,
//! which is also the spin equation's row (the mass matrix of a Lagrangian is symmetric), and
//! the spin's diagonal `I_p + Σ_j m_b R²`, plus the spin's own terms of `K_st` and of the chart
//! (`q̇ᵀ K_st q̇`, `(I_p + Σ_j m_b R²)(2 ∂s/∂φ φ̈ + …)`: `spin_extra`). The accelerations solve the bordered system
//! `[[A, a_φ], [a_φᵀ, I_p + Σ m_b R²]] (q̈, ψ̈, φ̈) = (R, R_φ)`.
//!
//! **Real balls** ([`LinearRotor::ball_physics`]): the contact and rolling-resistance torques
//! of [`crate::balls`] are added to the balls' equations (their relative angles only: they are
//! internal to the rotor with its balls, so not in `R_φ`), with the normal force of
//! [`LinearRotorField`]'s real-ball forces; the implicit method then uses a Jacobian by
//! differences, and the balls' rates get the tolerance of [`crate::balls::BallPhysics::rate_tolerance`].

use super::field::{Frame, Kin, LinearRotorField, Mats, SpinVar, SEEDS};
use super::{Direction, LinearRotor};
use crate::drive::Drive;
use crate::error::{Error, Result};
use crate::ode::dual::{Dual, Real};
use crate::ode::lu::Lu;
use crate::ode::{Control, Method, Options, Solver, Status, System};
use crate::simulation::{run, Hooks, Peak, Recorder, RevolutionWindow, Timeline};
use serde::Serialize;
use std::borrow::Cow;

/// `∫₀ᵗ Ω dt` of a prescribed drive (piecewise linear in `t`, held outside a schedule, a run-down
/// held at rest once it stops).
pub fn drive_angle(drive: &Drive, t: f64) -> f64 {
    match drive {
        Drive::Speed { omega0 } => omega0 * t,
        Drive::Acceleration { omega0, b } => {
            let stop = if *b < 0.0 && *omega0 > 0.0 { omega0 / -b } else { f64::INFINITY };
            let s = t.min(stop);
            omega0 * s + 0.5 * b * s * s
        }
        Drive::SpeedSchedule { points } => {
            // trapezoids of the piecewise-linear speed, held constant outside the points
            let (t0, w0) = points[0];
            if t <= t0 {
                return w0 * t;
            }
            let mut phi = w0 * t0;
            for w in points.windows(2) {
                let (a, b) = (w[0], w[1]);
                if t <= b.0 {
                    let wt = a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0);
                    return phi + 0.5 * (a.1 + wt) * (t - a.0);
                }
                phi += 0.5 * (a.1 + b.1) * (b.0 - a.0);
            }
            let last = points[points.len() - 1];
            phi + last.1 * (t - last.0)
        }
        _ => 0.0,
    }
}

/// The equations of a run in fixed axes as an ODE system: state `(q, ψ, q̇, ψ̇)` under a
/// prescribed speed, `(q, ψ, φ, q̇, ψ̇, φ̇)` under a torque (module docs).
pub struct RunUpSystem<'a> {
    field: LinearRotorField,
    /// The rotor with its speed-dependent bearings (the field's has them at `Ω(0)`).
    rotor: &'a LinearRotor,
    drive: &'a Drive,
    /// The spin is a coordinate (torque drives).
    spin: bool,
}

/// `Ω̇` used to read the column of `φ̈` off the residual, which is affine in `Ω̇` (a power of 2:
/// the difference quotient is the column to the rounding of the residual at that `Ω̇`).
const WDOT_PROBE: f64 = 1073741824.0;

impl<'a> RunUpSystem<'a> {
    /// The system of `rotor` under `drive`; a torque drive needs the rotor's polar moment
    /// ([`LinearRotor::polar_inertia`] > 0, the error names it).
    pub fn new(rotor: &'a LinearRotor, drive: &'a Drive) -> Result<Self> {
        drive.validate()?;
        let spin = !drive.prescribed();
        if spin && rotor.polar_inertia <= 0.0 {
            return Err(Error::invalid(
                "linear_rotor.polar_inertia",
                "a torque drive (\"torque\", \"motor\", a torque \"schedule\") needs the rotor's polar moment of inertia about its axis (kg m², > 0): M, C, G, K do not hold it",
            ));
        }
        // a spin lighter than the balls it carries: no rotor (its race and disk alone exceed
        // them), and a run stiff beyond use, the spin relative to the balls relaxing at their
        // drag over I_p (1e-9 kg m² on examples/linear_rotor_shaft.toml: 1e-6 s simulated in
        // 30 s, the speed at -1.8e10 rad/s)
        let balls: f64 = rotor.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius * b.radius).sum();
        if spin && rotor.polar_inertia < balls {
            return Err(Error::invalid(
                "linear_rotor.polar_inertia",
                format!(
                    "{:e} kg m² is below the balls' own moment about the axis, Σ n m_b R² = {balls:.6e} kg m²: under a torque drive the rotor would turn with less inertia than the balls riding on its race (a real rotor's race and disk alone exceed them), and the run is stiff beyond use (the spin against the balls' drag relaxes at drag / I_p); give the rotor's polar moment (disks, shaft, race)",
                    rotor.polar_inertia
                ),
            ));
        }
        Ok(RunUpSystem { field: LinearRotorField::with_real_balls(rotor, drive.omega0(), Frame::Fixed)?, rotor, drive, spin })
    }

    /// The field (at the drive's initial speed; for the rotor and the coordinates).
    pub fn field(&self) -> &LinearRotorField {
        &self.field
    }

    /// Whether the spin `(φ, φ̇)` is part of the state (torque drives): then `φ` follows the
    /// coordinates `(q, ψ)` and `φ̇` their rates.
    pub fn spin(&self) -> bool {
        self.spin
    }

    /// The speed `Ω` at `(t, y)`: the drive's, or `φ̇` of the state under a torque.
    pub fn omega(&self, t: f64, y: &[f64]) -> f64 {
        if self.spin {
            y[y.len() - 1]
        } else {
            self.drive.kinematics(t).0
        }
    }

    fn mats(&self, w: f64) -> Mats<'_> {
        let r = self.rotor;
        let (c, k) = r.damping_stiffness_at(w);
        let d: Vec<f64> = c.iter().zip(&r.g).map(|(c, g)| c + w * g).collect();
        Mats { m: Cow::Borrowed(&r.m), d: Cow::Owned(d), k: Cow::Owned(k) }
    }

    fn at(&self, t: f64) -> (Mats<'_>, Kin) {
        let (w, wdot) = self.drive.kinematics(t);
        (self.mats(w), Kin { w, wdot, nu: 0.0, chi: drive_angle(self.drive, t), frame: 0.0 })
    }

    /// The accelerations `(q̈, ψ̈, φ̈)` under a torque at `(t, y)`, `y = (q, ψ, φ, q̇, ψ̇, φ̇)`: the
    /// bordered system of the module docs.
    pub fn spin_accelerations(&self, t: f64, y: &[f64]) -> Option<Vec<f64>> {
        let f = &self.field;
        let r = self.rotor;
        let n = r.dofs();
        let nc = f.coords();
        let n1 = nc + 1;
        let (phi, w) = (y[nc], y[n1 + nc]);
        let mut x = Vec::with_capacity(2 * nc);
        x.extend_from_slice(&y[..nc]);
        x.extend_from_slice(&y[n1..n1 + nc]);
        let mats = self.mats(w);
        let kin = Kin { w, wdot: 0.0, nu: 0.0, chi: phi, frame: 0.0 };
        let zero = vec![0.0; nc];
        let mut r0 = vec![0.0; nc];
        f.residual::<f64>(&mats, &kin, &x, &zero, &mut r0);
        let mut r1 = vec![0.0; nc];
        f.residual::<f64>(&mats, &Kin { wdot: WDOT_PROBE, ..kin }, &x, &zero, &mut r1);
        // the column of φ̈: the residual is R − A a − a_φ φ̈
        let a_phi: Vec<f64> = r0.iter().zip(&r1).map(|(a, b)| (a - b) / WDOT_PROBE).collect();
        let a = f.mass_matrix(&mats, phi, &x);
        let mut big = vec![0.0; n1 * n1];
        for i in 0..nc {
            big[i * n1..i * n1 + nc].copy_from_slice(&a[i * nc..(i + 1) * nc]);
            big[i * n1 + nc] = a_phi[i];
            big[nc * n1 + i] = a_phi[i];
        }
        let balls: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius * b.radius).sum();
        let (diag, extra) = spin_extra(f, r, phi, w, &x[..n], &x[nc..nc + n]);
        big[nc * n1 + nc] = r.polar_inertia + balls + diag;
        // R_φ: the drive, the spin drag, gravity on the unbalances, and the balls' equations'
        // non-inertial parts without their drag (which does no work on φ)
        let mut rphi = self.drive.torque(t, w) - r.spin_damping * w + extra;
        if let Some(g) = &r.gravity {
            for u in &r.unbalances {
                let (s, c) = (phi + u.phase).sin_cos();
                rphi += u.me * (-s * g.g[0] + c * g.g[1]);
            }
        }
        rphi += rotor_fixed_torque(r, phi, &x[nc..nc + n]);
        let mut k = n;
        for b in &r.balancers {
            for _ in 0..b.balls {
                rphi += r0[k] + b.drag * y[n1 + k];
                k += 1;
            }
        }
        let mut rhs = r0;
        // real balls' torques act on their relative angles only (not in R_φ)
        f.add_real_balls(&kin, &x, &mut rhs);
        rhs.push(rphi);
        let lu = Lu::factored(big, n1)?;
        lu.solve(&mut rhs);
        Some(rhs)
    }
}

impl RunUpSystem<'_> {
    /// The exact Jacobian `∂f/∂y` at `(t, y)` (row-major `dim²`) that the implicit method uses,
    /// by forward-mode dual numbers, under a prescribed speed and under a torque (module docs);
    /// `None` with real balls (the method takes differences then).
    pub fn jacobian_matrix(&self, t: f64, y: &[f64]) -> Option<Vec<f64>> {
        let d = System::dim(self);
        let mut j = vec![0.0; d * d];
        if self.field.real_balls() {
            return None;
        }
        if self.spin {
            self.spin_jacobian(t, y, &mut j);
        } else {
            let (mats, kin) = self.at(t);
            let dim = 2 * self.field.coords();
            self.field.jacobian_with(&mats, &kin, y, &mut j, dim);
        }
        Some(j)
    }

    /// `∂C/∂Ω` and `∂K/∂Ω` of the speed-dependent bearings at `w`: the slopes of their tables
    /// (0 outside; at a table speed the interval above it, as [`super::SpeedBearing::at`]
    /// interpolates), plus `G` in the first: `(G + C'(Ω), K'(Ω))`.
    fn speed_derivatives(&self, w: f64) -> (Vec<f64>, Vec<f64>) {
        let r = self.rotor;
        let n = r.dofs();
        let (mut dd, mut dk) = (r.g.clone(), vec![0.0; n * n]);
        for b in &r.speed_bearings {
            let sp = &b.speeds;
            if sp.len() < 2 || w < sp[0] || w >= sp[sp.len() - 1] {
                continue;
            }
            let i = sp.partition_point(|v| *v <= w) - 1;
            let h = sp[i + 1] - sp[i];
            let slope = |t: &[[f64; 4]]| -> [f64; 4] { std::array::from_fn(|j| (t[i + 1][j] - t[i][j]) / h) };
            r.add_bearing_block(b.node, b.link, &slope(&b.k), &mut dk);
            r.add_bearing_block(b.node, b.link, &slope(&b.c), &mut dd);
        }
        (dd, dk)
    }

    /// The exact Jacobian under a torque, `y = (q, ψ, φ, q̇, ψ̇, φ̇)` (module docs): with
    /// `a = (q̈, ψ̈, φ̈)` the solution of `B(y) a = F(y)` (the bordered system), `∂a/∂y =
    /// B⁻¹ ∂(F − B a)/∂y` at the current `a`; `F − B a` is the structure's and balls' residual
    /// at `a` (with `Ω̇ = φ̈`) and the spin's row `R_φ − a_φᵀ (q̈, ψ̈) − (I_p + Σ m_b R²) φ̈`, all
    /// differentiated by forward-mode dual numbers in every state, the spin angle and speed
    /// included ([`SpinVar`]; the drive's torque by [`Drive::torque_slope`]).
    fn spin_jacobian(&self, t: f64, y: &[f64], jac: &mut [f64]) {
        let f = &self.field;
        let r = self.rotor;
        let n = r.dofs();
        let nc = f.coords();
        let n1 = nc + 1;
        let dim = 2 * n1;
        jac.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..n1 {
            jac[i * dim + n1 + i] = 1.0;
        }
        let (phi, w) = (y[nc], y[n1 + nc]);
        let Some(acc) = self.spin_accelerations(t, y) else {
            jac[n1 * dim..].iter_mut().for_each(|v| *v = f64::NAN);
            return;
        };
        let (qa, phidd) = (&acc[..nc], acc[nc]);
        let mut x = Vec::with_capacity(2 * nc);
        x.extend_from_slice(&y[..nc]);
        x.extend_from_slice(&y[n1..n1 + nc]);
        let mats = self.mats(w);
        let kin = Kin { w, wdot: phidd, nu: 0.0, chi: phi, frame: 0.0 };
        let kin0 = Kin { wdot: 0.0, ..kin };
        let kin1 = Kin { wdot: WDOT_PROBE, ..kin };
        let zero = vec![0.0; nc];
        // the bordered matrix B at y, as in spin_accelerations
        let mut r0 = vec![0.0; nc];
        f.residual::<f64>(&mats, &kin0, &x, &zero, &mut r0);
        let mut r1 = vec![0.0; nc];
        f.residual::<f64>(&mats, &kin1, &x, &zero, &mut r1);
        let a = f.mass_matrix(&mats, phi, &x);
        let mut big = vec![0.0; n1 * n1];
        for i in 0..nc {
            big[i * n1..i * n1 + nc].copy_from_slice(&a[i * nc..(i + 1) * nc]);
            let ap = (r0[i] - r1[i]) / WDOT_PROBE;
            big[i * n1 + nc] = ap;
            big[nc * n1 + i] = ap;
        }
        let balls: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius * b.radius).sum();
        let inertia = r.polar_inertia + balls;
        big[nc * n1 + nc] = inertia + spin_extra(f, r, phi, w, &x[..n], &x[nc..nc + n]).0;
        let Some(lu) = Lu::factored(big, n1) else {
            jac[n1 * dim..].iter_mut().for_each(|v| *v = f64::NAN);
            return;
        };
        let (dd, dk) = self.speed_derivatives(w);
        let slope = self.drive.torque_slope(t, w);
        type D = Dual<SEEDS>;
        let mut xd = vec![D::cst(0.0); 2 * nc];
        let (mut g, mut g0, mut g1) = (vec![D::cst(0.0); nc], vec![D::cst(0.0); nc], vec![D::cst(0.0); nc]);
        let mut col = vec![0.0; n1];
        for start in (0..dim).step_by(SEEDS) {
            // state index k of y seeded in direction k − start
            let seed = |k: usize, v: f64| if k >= start && k < start + SEEDS { D::var(v, k - start) } else { D::cst(v) };
            for i in 0..nc {
                xd[i] = seed(i, y[i]);
                xd[nc + i] = seed(n1 + i, y[n1 + i]);
            }
            let sv = SpinVar { chi: seed(nc, 0.0), w: seed(n1 + nc, 0.0), dd: &dd, dk: &dk };
            f.residual_spin(&mats, &kin, Some(&sv), &xd, qa, &mut g);
            f.residual_spin(&mats, &kin0, Some(&sv), &xd, &zero, &mut g0);
            f.residual_spin(&mats, &kin1, Some(&sv), &xd, &zero, &mut g1);
            // the spin's row: R_φ − a_φᵀ (q̈, ψ̈) − (I_p + Σ m_b R²) φ̈
            let phid = sv.chi + phi;
            let mut gs = sv.w * (slope - r.spin_damping) + (self.drive.torque(t, w) - r.spin_damping * w - inertia * phidd);
            if let Some(gr) = &r.gravity {
                for u in &r.unbalances {
                    let (s, c) = (phid + u.phase).sin_cos();
                    gs = gs + (c * gr.g[1] - s * gr.g[0]) * u.me;
                }
            }
            gs = gs + rotor_fixed_torque(r, phid, &xd[nc..nc + n]);
            let (diag, extra) = spin_extra(f, r, phid, sv.w + w, &xd[..n], &xd[nc..nc + n]);
            gs = gs + extra - diag * phidd;
            let mut k = n;
            for b in &r.balancers {
                for _ in 0..b.balls {
                    gs = gs + g0[k] + xd[nc + k] * b.drag;
                    k += 1;
                }
            }
            for i in 0..nc {
                gs = gs - (g0[i] - g1[i]) * (qa[i] / WDOT_PROBE);
            }
            for kk in 0..SEEDS.min(dim - start) {
                for i in 0..nc {
                    col[i] = g[i].d[kk];
                }
                col[nc] = gs.d[kk];
                lu.solve(&mut col);
                for (i, c) in col.iter().enumerate() {
                    jac[(n1 + i) * dim + start + kk] = *c;
                }
            }
        }
    }
}

/// The spin equation's terms of [`LinearRotor::spin_stiffness`] and [`LinearRotor::spin_chart`]
/// beyond the column of `φ̈` (which the structure's and balls' equations give, the mass matrix
/// being symmetric) and beyond the balls' own `m_b R² s̈` (in their equations' non-inertial
/// parts): `(d, τ)` with `d φ̈` on the inertia side and `τ` on the torque side, at the rotor's
/// angle `phi` and speed `w`, positions `q` and velocities `v` (fixed axes). From
/// `T ⊃ φ̇ q̇ᵀ K_st q + (I_p φ̇ + Σ_j m_b R² θ̇_j) ṡ`: `d/dt ∂T/∂φ̇ − ∂T/∂φ` adds
/// `q̈ᵀ K_st q + q̇ᵀ K_st q̇` (so `τ ⊃ −q̇ᵀ K_st q̇`, zero for the default skew `½ G`) and
/// `I_c s̈ + (I_p φ̈ + Σ_j m_b R² θ̈_j) ∂s/∂φ` (`I_c = I_p + Σ_j m_b R²`), of which
/// `d = 2 I_c ∂s/∂φ` and `τ ⊃ −I_p V` ([`LinearRotorField::chart`]) are left.
fn spin_extra<T: Real>(f: &LinearRotorField, r: &LinearRotor, phi: T, w: T, q: &[T], v: &[T]) -> (T, T) {
    let n = r.dofs();
    let (mut d, mut tau) = (T::cst(0.0), T::cst(0.0));
    if !r.spin_stiffness.is_empty() {
        for i in 0..n {
            for j in 0..n {
                let k = r.spin_stiffness[i * n + j];
                if k != 0.0 {
                    tau = tau - v[i] * v[j] * k;
                }
            }
        }
    }
    if let Some((_, s_phi, rest)) = f.chart(phi, w, q, v) {
        let balls: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius * b.radius).sum();
        d = s_phi * (2.0 * (r.polar_inertia + balls));
        tau = tau - rest * r.polar_inertia;
    }
    (d, tau)
}

/// The spin's torque from the inertia fixed to the rotor ([`LinearRotor::rotor_fixed_mass`]):
/// `∂T/∂φ = ½ q̇ᵀ (∂/∂φ T(φ) M_rot T(φ)ᵀ) q̇ = q̇ᵀ J M_f q̇`, `M_f = T(φ) M_rot T(φ)ᵀ` (the
/// kinetic energy depends on the rotor's angle, not on its rate), fixed axes; 0 without it.
fn rotor_fixed_torque<T: Real>(r: &LinearRotor, phi: T, v: &[T]) -> T {
    let n = r.dofs();
    let mut t = T::cst(0.0);
    if r.rotor_fixed_mass.is_empty() {
        return t;
    }
    let mf = super::turn_blocks(&r.rotor_fixed_mass, n, phi);
    for m in 0..n / 2 {
        let (mut u0, mut u1) = (T::cst(0.0), T::cst(0.0));
        for j in 0..n {
            u0 = u0 + mf[2 * m * n + j] * v[j];
            u1 = u1 + mf[(2 * m + 1) * n + j] * v[j];
        }
        // (J u)_{2m} = −u_{2m+1}, (J u)_{2m+1} = u_{2m}: vᵀ J u
        t = t + v[2 * m + 1] * u0 - v[2 * m] * u1;
    }
    t
}

impl System for RunUpSystem<'_> {
    fn dim(&self) -> usize {
        2 * (self.field.coords() + usize::from(self.spin))
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        if self.spin {
            let n1 = self.field.coords() + 1;
            dy[..n1].copy_from_slice(&y[n1..]);
            match self.spin_accelerations(t, y) {
                Some(a) => dy[n1..].copy_from_slice(&a),
                None => dy[n1..].iter_mut().for_each(|v| *v = f64::NAN),
            }
            return;
        }
        let nc = self.field.coords();
        dy[..nc].copy_from_slice(&y[nc..]);
        let (mats, kin) = self.at(t);
        match self.field.accelerations_with(&mats, &kin, y) {
            Some(a) => dy[nc..].copy_from_slice(&a),
            None => dy[nc..].iter_mut().for_each(|v| *v = f64::NAN),
        }
    }

    fn jacobian(&self) -> Box<dyn crate::ode::Jacobian + '_> {
        if self.field.real_balls() {
            // forward differences of the right-hand side (the real balls' contact and friction
            // are not written for dual numbers); used only by the implicit method
            return Box::new(crate::ode::DenseJacobian::differences(self));
        }
        if self.spin {
            return Box::new(crate::ode::DenseJacobian::analytic(self, move |t, y, j| self.spin_jacobian(t, y, j)));
        }
        Box::new(crate::ode::DenseJacobian::analytic(self, move |t, y, j| {
            let (mats, kin) = self.at(t);
            let dim = 2 * self.field.coords();
            self.field.jacobian_with(&mats, &kin, y, j, dim)
        }))
    }

    fn component_name(&self, i: usize) -> String {
        crate::analysis::VectorField::component_name(&self.field, i)
    }
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// End of the run (s).
    pub t_end: f64,
    /// Output interval (s).
    pub dt: f64,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on displacements (m; angles: divided by the race radius; rates: times
    /// the largest speed of the drive).
    pub atol: f64,
    /// Integrator.
    pub method: Method,
    /// Step budget.
    pub max_steps: u64,
    /// Wall-clock budget (s).
    pub max_wall_s: Option<f64>,
    /// The first nodes that are physical (a reduced rotor's boundary nodes,
    /// [`super::reduce`]); `None`: every node. [`RunSample::max_radius`] looks at these.
    pub physical_nodes: Option<usize>,
}

/// One sample of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSample {
    /// Time (s).
    pub t: f64,
    /// Speed `Ω` (rad/s).
    pub omega: f64,
    /// Per balancer plane, the race centre's `(x, y)` in fixed axes (m).
    pub planes: Vec<(f64, f64)>,
    /// The largest translation radius `sqrt(x² + y²)` over the (physical) nodes (m).
    pub max_radius: f64,
    /// The balls' angles relative to the rotor (rad, all planes in order).
    pub psi: Vec<f64>,
}

/// The summary of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// The time reached (s).
    pub t: f64,
    /// Why it ended, when it ended early (a one-line message).
    pub stopped: Option<String>,
    /// The largest whirl radius of the first balancer plane's race centre seen at the samples,
    /// with the speed then (rad/s).
    pub peak: Peak<f64>,
    /// The largest translation radius of any node at the samples, with the speed then.
    pub peak_any_node: Peak<f64>,
    /// The first plane's whirl radius at the end (m).
    pub final_radius: f64,
    /// Speed at the end (rad/s).
    pub final_omega: f64,
    /// The residual static unbalance the balls leave, averaged by time over the run's last
    /// revolution (from the dense output at 32 rotor angles a revolution,
    /// [`crate::simulation::RevolutionWindow`]; the end state's where no revolution was
    /// recorded: the run turned less than one, or stopped early, [`RunSummary::averaged`]), as
    /// `stability` measures it on the linear route
    /// ([`crate::rotor_stability::Rotor::residual`]): `|s0 + Σ_j m_b R ⟨e^{iψ_j}⟩| / |s0|`,
    /// `s0 = Σ m e e^{i phase}` ([`super::partial::residual_static`]), over the balls' capacity
    /// `Σ n m_b R` where `|s0|` is at most [`crate::rotor_stability::NO_UNBALANCE`] of it. On a
    /// flexible shaft with the unbalance away from the balancer plane(s) the balls centre
    /// their races rather than cancel `s0`, so a balanced run can carry a residual well above
    /// [`crate::spatial::dynamics::simulate::BALANCE_TOLERANCE`]: the word is decided on the
    /// race whirl there ([`RunSummary::race_whirl`]).
    pub residual_unbalance: f64,
    /// What [`RunSummary::outcome`] is decided on where a balanced state exists at the final
    /// speed, as `stability`'s `state_basis` `race_whirl`
    /// ([`super::partial::state_kind`]): the largest over the balancer planes of the race
    /// centre's mean position in axes turning with the rotor over the last revolution (the end
    /// state's where no revolution was recorded, as for the residual), `|⟨d_k⟩|`, over the plane's whirl with the balls
    /// spread evenly (their resultant zero) at the final speed; a plane whose mean whirl is at
    /// most `1e-6 ℓ` ([`super::partial::length_scale`]) counts 0, as there. `None` without
    /// balls, where no balanced state exists (the word is then decided on
    /// [`RunSummary::residual_unbalance`]), or where the whirl without the resultant cannot be
    /// solved for (the structure's stationary equations singular: not balanced).
    pub race_whirl: Option<f64>,
    /// The largest change of a ball's mean angle (its average over a revolution, relative to
    /// the rotor) between the last two revolutions (rad); `None` without balls or where the run
    /// recorded less than two revolutions (it turned less, or stopped early).
    pub ball_drift: Option<f64>,
    /// Whether [`RunSummary::residual_unbalance`] and [`RunSummary::race_whirl`] are means
    /// over the run's last revolution; `false` where no revolution was recorded (the run
    /// turned less than one, or stopped early: Ctrl-C, a step or wall budget, before its last
    /// revolutions) and they are the end state's.
    pub averaged: bool,
    /// Whether the run ended settled: it completed, at a constant speed (the mean speed over
    /// the last revolution equal to that over the one before to `1e-6` of it: a run still
    /// speeding up is not settled), and the balls' mean angles drift between the last two
    /// revolutions by at most [`crate::spatial::dynamics::simulate::drift_tolerance`] (with
    /// the rotor's lowest natural frequency, balls as rings).
    pub settled: bool,
    /// What the run ended in, decided by the spatial run's rule
    /// ([`crate::spatial::dynamics::RunOutcome`], the one rule of every route): not settled
    /// (see [`RunSummary::settled`]); where no balanced state exists at the final speed
    /// ([`super::LinearRotorField::balanced_guess`] has none, as for `stability`: the balls'
    /// capacity short of the force the plane must cancel) partially balanced when every
    /// plane's balls ended together (their mean resultant at least 99 % of the plane's `n`)
    /// with [`RunSummary::residual_unbalance`] within
    /// [`PARTIAL_TOLERANCE`](crate::spatial::dynamics::simulate::PARTIAL_TOLERANCE) of the
    /// least residual (closed form `1 − n m_b R / |s0|` where one plane holds every unbalance;
    /// else the static residual of `stability`'s partially balanced state there,
    /// [`crate::rotor_partial::partially_balanced`]), else not balanced; else balanced with
    /// [`RunSummary::race_whirl`] (not the static residual: `stability`'s `state_basis`) at most
    /// [`BALANCE_TOLERANCE`](crate::spatial::dynamics::simulate::BALANCE_TOLERANCE), else not
    /// balanced (e.g. the balls on the heavy side below the first critical speed, the race
    /// whirling more than without them). Without balls not balanced.
    pub outcome: crate::spatial::dynamics::RunOutcome,
    /// `outcome == RunOutcome::Balanced`.
    pub balanced: bool,
    /// Accepted steps.
    pub steps: u64,
    /// The creep check: where a run at a prescribed, constant final speed would read balanced
    /// next to a balanced state that is unstable there by its exact linear stability (or a
    /// family of them with no stable member sampled:
    /// [`crate::rotor_stability::unstable_balanced_state`]), that state's growth rate (1/s); the
    /// outcome is then not settled (the balls creep away from it). `None` otherwise.
    pub creep_rate: Option<f64>,
    /// What the words above do not say, one line each (the creep check's, with its growth rate).
    pub warnings: Vec<String>,
}

/// The race centre `(x + z β, y − z α)` of each balancer plane in the state `y`.
pub fn plane_positions(rotor: &LinearRotor, y: &[f64]) -> Vec<(f64, f64)> {
    rotor
        .balancers
        .iter()
        .map(|b| {
            let ix = rotor.dof(b.node, Direction::X).unwrap_or(0);
            let (mut x, mut yy) = (y[ix], y[ix + 1]);
            if let (Some(ia), Some(ib)) = (rotor.dof(b.node, Direction::Alpha), rotor.dof(b.node, Direction::Beta)) {
                x += b.offset * y[ib];
                yy -= b.offset * y[ia];
            }
            (x, yy)
        })
        .collect()
}

/// What the linear rotor's run summary averages over its last revolutions
/// ([`crate::simulation::RevolutionWindow`], on the grid of the rotor's angle `φ`: the spin
/// state's under a torque, the drive's (`drive_angle`) where the speed is prescribed): per
/// record the speed, each ball's `cos ψ`, `sin ψ` and `ψ` (as integrated: not reduced to one
/// turn), each plane's race centre in axes turning with the rotor.
struct LinearRecorder<'a> {
    rotor: &'a LinearRotor,
    drive: &'a Drive,
    /// Whether the spin is a state (a torque drive).
    spin: bool,
}

/// Where a [`LinearRecorder`]'s record holds the speed, `cos ψ`, `sin ψ`, `ψ` and the race
/// centres, for `nb` balls.
fn columns(nb: usize) -> (usize, usize, usize, usize, usize) {
    (0, 1, 1 + nb, 1 + 2 * nb, 1 + 3 * nb)
}

impl LinearRecorder<'_> {
    fn width(&self) -> usize {
        1 + 3 * self.rotor.total_balls() + 2 * self.rotor.balancers.len()
    }
}

impl crate::simulation::Recorder for LinearRecorder<'_> {
    fn spin(&self, t: f64, y: &[f64]) -> (f64, f64) {
        if self.spin {
            let nc = self.rotor.dofs() + self.rotor.total_balls();
            (y[nc], y[y.len() - 1])
        } else {
            (drive_angle(self.drive, t), self.drive.kinematics(t).0)
        }
    }

    fn record(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let (phi, w) = self.spin(t, y);
        let (n, nb) = (self.rotor.dofs(), self.rotor.total_balls());
        let (speed, cos0, sin0, psi0, d0) = columns(nb);
        out[speed] = w;
        for (j, a) in y[n..n + nb].iter().enumerate() {
            let (s, c) = a.sin_cos();
            out[cos0 + j] = c;
            out[sin0 + j] = s;
            out[psi0 + j] = *a;
        }
        let (s, c) = phi.sin_cos();
        for (k, (x, yy)) in plane_positions(self.rotor, y).into_iter().enumerate() {
            out[d0 + 2 * k] = c * x + s * yy;
            out[d0 + 2 * k + 1] = -s * x + c * yy;
        }
    }
}

struct RunHooks<'a, F: FnMut(&RunSample) -> bool> {
    rotor: &'a LinearRotor,
    nodes: usize,
    drive: &'a Drive,
    spin: bool,
    sink: F,
    peak: Peak<f64>,
    peak_any: Peak<f64>,
    last_radius: f64,
    window: RevolutionWindow,
    recorder: LinearRecorder<'a>,
}

impl<F: FnMut(&RunSample) -> bool> Hooks for RunHooks<'_, F> {
    fn dense_step(&mut self, t_old: f64, t_new: f64, y_old: &[f64], y_new: &[f64], interpolate: &mut dyn FnMut(f64, &mut [f64])) {
        self.window.dense_step(&self.recorder, t_old, t_new, y_old, y_new, interpolate);
    }

    fn sample(&mut self, t: f64, y: &[f64]) -> Control {
        let r = self.rotor;
        let n = r.dofs();
        let nc = n + r.total_balls();
        let omega = if self.spin { y[y.len() - 1] } else { self.drive.kinematics(t).0 };
        let planes = plane_positions(r, y);
        let max_radius = r.node_starts().into_iter().take(self.nodes).map(|i| y[i].hypot(y[i + 1])).fold(0.0, f64::max);
        if let Some(p) = planes.first() {
            self.last_radius = p.0.hypot(p.1);
            self.peak.observe(self.last_radius, t, omega);
        }
        self.peak_any.observe(max_radius, t, omega);
        let s = RunSample { t, omega, planes, max_radius, psi: y[n..nc].to_vec() };
        if (self.sink)(&s) {
            Control::Continue
        } else {
            Control::Stop
        }
    }
}

/// The initial state: the structure at rest on the axis, the balls evenly spread at rest
/// relative to the rotor (`ψ_j = 2π j/n` in each plane); under a torque `drive` the spin
/// `(φ, φ̇) = (0, ω0)` too (state `(q, ψ, φ, q̇, ψ̇, φ̇)`).
pub fn initial_state_for(rotor: &LinearRotor, drive: &Drive) -> Vec<f64> {
    let mut y = initial_state(rotor);
    if !drive.prescribed() {
        let nc = y.len() / 2;
        y.insert(nc, 0.0);
        y.push(drive.omega0());
    }
    y
}

/// The initial state under a prescribed speed ([`initial_state_for`]): the structure at rest on
/// the axis, the balls evenly spread at rest relative to the rotor (`ψ_j = 2π j/n` in each plane).
pub fn initial_state(rotor: &LinearRotor) -> Vec<f64> {
    let n = rotor.dofs();
    let nc = n + rotor.total_balls();
    let mut y = vec![0.0; 2 * nc];
    let mut g = n;
    for b in &rotor.balancers {
        for j in 0..b.balls {
            y[g] = std::f64::consts::TAU * j as f64 / b.balls as f64;
            g += 1;
        }
    }
    y
}

/// Run `rotor` under `drive` from [`initial_state_for`]; `sink` gets every sample and may return
/// `false` to stop. The run stops at the `control`'s cancel or budget (checked by the solver).
pub fn simulate(
    rotor: &LinearRotor,
    drive: &Drive,
    settings: &RunSettings,
    control: &crate::control::Control,
    sink: impl FnMut(&RunSample) -> bool,
) -> Result<RunSummary> {
    simulate_from(rotor, drive, settings, None, control, sink)
}

/// [`simulate`] with the balls' initial angles relative to the rotor `psi0` (one per ball, plane
/// by plane; `None`: [`initial_state_for`]'s even spread), the rest of the initial state as there.
pub fn simulate_from(
    rotor: &LinearRotor,
    drive: &Drive,
    settings: &RunSettings,
    psi0: Option<&[f64]>,
    control: &crate::control::Control,
    sink: impl FnMut(&RunSample) -> bool,
) -> Result<RunSummary> {
    crate::error::positive("drive.t_end", settings.t_end)?;
    crate::error::positive("integration.dt", settings.dt)?;
    let sys = RunUpSystem::new(rotor, drive)?;
    let n = rotor.dofs();
    let nc = sys.field().coords();
    let spin = sys.spin();
    // coordinates including the spin angle under a torque
    let ncs = nc + usize::from(spin);
    let w_max =
        drive.breakpoints().iter().chain([0.0, settings.t_end].iter()).map(|&t| drive.kinematics(t).0.abs()).fold(drive.omega0().abs(), f64::max).max(1.0);
    let r_min = rotor.balancers.iter().map(|b| b.radius).fold(f64::INFINITY, f64::min);
    let r_min = if r_min.is_finite() { r_min } else { 1.0 };
    let mut atol = vec![0.0; 2 * ncs];
    for i in 0..ncs {
        // displacements; angles (the balls', the spin's) as the race's arc length
        let base = if i < n { settings.atol } else { settings.atol / r_min };
        atol[i] = base;
        atol[ncs + i] = base * w_max;
    }
    // real balls' rates: below a tenth of the slip rate with rolling resistance, so that the
    // regularised sign is resolved (crate::balls)
    let mut first = n;
    for (k, b) in rotor.balancers.iter().enumerate() {
        if let Some(p) = rotor.ball_physics.get(k) {
            for a in &mut atol[ncs + first..ncs + first + b.balls] {
                *a = p.rate_tolerance(*a);
            }
        }
        first += b.balls;
    }
    let mut o = Options::new(settings.rtol, settings.atol).method(settings.method).atol_per_component(atol);
    o.h_max_implicit = 4.0 * settings.dt;
    o.max_steps = settings.max_steps;
    o.max_wall = settings.max_wall_s.map(std::time::Duration::from_secs_f64);
    let mut solver = Solver::new(&sys, o)?;
    solver.control(control);
    let mut y = initial_state_for(rotor, drive);
    if let Some(p) = psi0 {
        if p.len() != nc - n {
            return Err(Error::invalid("drive.psi0", format!("has {} angles, the rotor {} balls", p.len(), nc - n)));
        }
        y[n..nc].copy_from_slice(p);
    }
    let breakpoints = drive.breakpoints();
    let timeline = Timeline { t_end: settings.t_end, dt: settings.dt, breakpoints: &breakpoints };
    let recorder = LinearRecorder { rotor, drive, spin };
    let mut hooks = RunHooks {
        rotor,
        nodes: settings.physical_nodes.unwrap_or(rotor.nodes).min(rotor.nodes),
        drive,
        spin,
        sink,
        peak: Peak::new(0.0),
        peak_any: Peak::new(0.0),
        last_radius: 0.0,
        window: RevolutionWindow::new(recorder.width(), settings.t_end),
        recorder,
    };
    let out = run(&mut solver, &mut y, &timeline, &mut hooks);
    let stopped = match &out.status {
        Status::Completed | Status::Event(_) => None,
        _ => Some(out.to_string()),
    };
    let (phi_end, final_omega) = hooks.recorder.spin(out.t, &y);
    let end = ending(rotor, &hooks.window, &y, phi_end, final_omega, stopped.is_none());
    // the end checks (`crate::rotor_stability::end_checks`); the end state turned into the
    // rotor's turning axes
    let checks = crate::rotor_stability::end_checks(
        &crate::rotor_stability::Rotor::Linear(rotor.clone()),
        final_omega,
        true,
        drive.constant_speed_at(out.t),
        end.outcome,
        end.settled,
        || turned_end(rotor, &y, phi_end),
    );
    Ok(RunSummary {
        t: out.t,
        stopped,
        peak: hooks.peak,
        peak_any_node: hooks.peak_any,
        final_radius: hooks.last_radius,
        final_omega,
        residual_unbalance: end.residual_unbalance,
        race_whirl: end.race_whirl,
        ball_drift: end.ball_drift,
        averaged: end.averaged,
        settled: checks.settled,
        outcome: checks.outcome,
        balanced: checks.outcome == crate::spatial::dynamics::RunOutcome::Balanced,
        steps: out.stats.steps,
        creep_rate: checks.creep_rate,
        warnings: checks.warning.into_iter().collect(),
    })
}

/// The end-state check's start ([`crate::rotor_stability::settled_end_check`]): a run's end
/// `y` (fixed axes, the rotor at angle `phi`) as the state of [`LinearRotorField`] in turning
/// axes, each (x, y) pair (and tilt pair) turned back through `φ`, the balls' angles as they
/// are, velocities zero (Newton's start only); `None` without balls or for an odd number of
/// rotor coordinates.
fn turned_end(rotor: &LinearRotor, y: &[f64], phi: f64) -> Option<Vec<f64>> {
    let (n, nb) = (rotor.dofs(), rotor.total_balls());
    if nb == 0 || n % 2 != 0 || y.len() < n + nb {
        return None;
    }
    let (s, c) = phi.sin_cos();
    let mut x = vec![0.0; 2 * (n + nb)];
    for m in 0..n / 2 {
        let (a, b) = (y[2 * m], y[2 * m + 1]);
        x[2 * m] = c * a + s * b;
        x[2 * m + 1] = -s * a + c * b;
    }
    x[n..n + nb].copy_from_slice(&y[n..n + nb]);
    Some(x)
}

/// What [`ending`] gives the summary.
struct End {
    residual_unbalance: f64,
    race_whirl: Option<f64>,
    ball_drift: Option<f64>,
    averaged: bool,
    settled: bool,
    outcome: crate::spatial::dynamics::RunOutcome,
}

/// The verdict of a run ([`RunSummary::outcome`] and the fields it is decided on) from the
/// records of its last revolutions `window` ([`LinearRecorder`]), the end state `y` with the rotor at angle `phi`
/// and speed `omega`, and whether it `completed`: the spatial run's rule
/// ([`crate::spatial::dynamics::simulate::run_outcome`]) on the linear route's measures.
fn ending(rotor: &LinearRotor, window: &RevolutionWindow, y: &[f64], phi: f64, omega: f64, completed: bool) -> End {
    use crate::spatial::dynamics::simulate::{drift_tolerance, plane_together, run_outcome, Ending};
    let (n, nb, np) = (rotor.dofs(), rotor.total_balls(), rotor.balancers.len());
    let (last, previous) = (window.mean(0), window.mean(1));
    // columns of a record: ω, cos ψ, sin ψ, ψ, the race centres in turning axes
    let (speed, cos0, sin0, psi0, d0) = columns(nb);
    // ⟨e^{iψ_j}⟩ and ⟨d_k⟩ over the last revolution, or the end state's
    let (units, centres): (Vec<[f64; 2]>, Vec<[f64; 2]>) = match &last {
        Some(m) => ((0..nb).map(|j| [m[cos0 + j], m[sin0 + j]]).collect(), (0..np).map(|k| [m[d0 + 2 * k], m[d0 + 2 * k + 1]]).collect()),
        None => {
            let (s, c) = phi.sin_cos();
            (
                y[n..n + nb].iter().map(|a| [a.cos(), a.sin()]).collect(),
                plane_positions(rotor, y).into_iter().map(|(x, yy)| [c * x + s * yy, -s * x + c * yy]).collect(),
            )
        }
    };
    // the static residual as stability's linear route measures it (Rotor::residual)
    let s0 = super::partial::static_unbalance(rotor);
    let s0n = s0[0].hypot(s0[1]);
    let mut s = s0;
    let mut cap = 0.0;
    let mut together = true;
    let mut j = 0;
    for b in &rotor.balancers {
        for u in &units[j..j + b.balls] {
            s[0] += b.ball_mass * b.radius * u[0];
            s[1] += b.ball_mass * b.radius * u[1];
        }
        together &= plane_together(units[j..j + b.balls].iter().copied());
        cap += b.balls as f64 * b.ball_mass * b.radius;
        j += b.balls;
    }
    // over the unbalance, or the capacity where there is none to speak of: stability's rule
    let residual_unbalance = s[0].hypot(s[1]) / crate::rotor_stability::unbalance_scale(s0n, cap);
    // settled: a constant speed over the last two revolutions and the balls' mean angles
    // drifting by at most the shared tolerance
    let ball_drift = if nb > 0 { window.drift(psi0..psi0 + nb) } else { None };
    let constant = match (&last, &previous) {
        (Some(a), Some(b)) => a[speed] != 0.0 && (a[speed] - b[speed]).abs() <= 1e-6 * a[speed].abs(),
        _ => false,
    };
    let wn = rotor.natural_frequencies(&[], true).ok().and_then(|w| w.first().copied()).unwrap_or(f64::NAN);
    let settled = completed && constant && ball_drift.is_some_and(|d| d <= drift_tolerance(omega, wn));
    // whether a balanced state exists at the final speed: stability's test
    let field = LinearRotorField::with_real_balls(rotor, omega, Frame::Rotating).ok();
    let short = nb > 0 && omega != 0.0 && field.as_ref().is_some_and(|f| f.balanced_guess().is_none());
    let race_whirl = if nb == 0 || short {
        None
    } else {
        field.as_ref().and_then(|f| {
            let free = super::partial::spread_whirl(f)?;
            let tol = 1e-6 * super::partial::length_scale(rotor);
            Some(
                rotor
                    .balancers
                    .iter()
                    .zip(centres.iter().zip(&free))
                    .filter(|(b, _)| b.balls > 0)
                    .map(|(_, (d, f))| {
                        let w = d[0].hypot(d[1]);
                        if w <= tol {
                            0.0
                        } else {
                            w / f
                        }
                    })
                    .fold(0.0, f64::max),
            )
        })
    };
    let least = || {
        // one plane holding every unbalance: the balls bunched against it leave 1 − cap/|s0|
        let one_plane = matches!(rotor.balancers.as_slice(), [b] if rotor.unbalances.iter().all(|u| u.node == b.node && u.offset == b.offset));
        if one_plane && cap < s0n {
            1.0 - cap / s0n
        } else {
            crate::rotor_partial::partially_balanced(&crate::rotor_stability::Rotor::Linear(rotor.clone()), omega)
                .ok()
                .and_then(|v| v.into_iter().find(|p| p.kind == crate::rotor_stability::StateKind::PartiallyBalanced))
                .map_or(f64::INFINITY, |p| p.residual_static_fraction)
        }
    };
    let outcome = run_outcome(&Ending {
        balls: nb > 0,
        settled,
        // (the least residual only where it decides: a run not settled is that whatever it is)
        short: short.then(|| (if settled { least() } else { f64::INFINITY }, together)),
        residual: if short { residual_unbalance } else { race_whirl.unwrap_or(f64::INFINITY) },
        residual_couple: None,
        tolerance: crate::spatial::dynamics::simulate::BALANCE_TOLERANCE,
        race_whirl_basis: true,
    });
    End { residual_unbalance, race_whirl, ball_drift, averaged: last.is_some(), settled, outcome }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotor_stability::{Rotor, StateKind};
    use crate::spatial::dynamics::RunOutcome;

    /// An overhung disk on a flexible shaft, its two balls (drag 0.05) at the disk, the
    /// unbalance 0.3 m away from the balancer plane (partial.rs's test rotor).
    fn overhung() -> LinearRotor {
        crate::linear_rotor::partial::overhung_rotor(2e-3, -0.3, 0.02, 0.0, 0.05)
    }

    /// Where `stability` decides on the race whirl, so does the run: the end of a run on the
    /// balanced state of a rotor whose unbalance lies away from the balancer plane (stable at
    /// 660 rad/s, 2.8 ω_n; the balls centre their race, which leaves a static residual of
    /// 0.73) reads balanced, `stability`'s word, with that residual reported. The state is
    /// approached at the rate 0.068/s (370 s to e^{-25}, too long for a test), so the window is
    /// fed the stationary state itself turned through three revolutions in fixed axes as the
    /// dense output (exact means of a state constant in turning axes). On the static residual
    /// (the spatial and planar basis) the word would be not balanced.
    #[test]
    fn the_run_decides_on_the_race_whirl_where_stability_does() {
        let r = overhung();
        let w = 660.0;
        let st = crate::linear_rotor::stability::stability_over_speed(&r, &[w]).unwrap();
        let p = &st.points[0];
        assert_eq!(p.state, Some(StateKind::Balanced));
        let (_, s) = crate::rotor_campbell::stationary_at(&Rotor::Linear(r.clone()), w).unwrap();
        let n = r.dofs();
        let nb = r.total_balls();
        // the state at t: the stationary state turned through φ = ω t into fixed axes
        let turned = |t: f64| {
            let (sn, cs) = (w * t).sin_cos();
            let mut y = vec![0.0; 2 * (n + nb)];
            for m in 0..n / 2 {
                let (a, b) = (s.x[2 * m], s.x[2 * m + 1]);
                y[2 * m] = cs * a - sn * b;
                y[2 * m + 1] = sn * a + cs * b;
            }
            y[n..n + nb].copy_from_slice(&s.x[n..n + nb]);
            y
        };
        let drive = Drive::Speed { omega0: w };
        let recorder = LinearRecorder { rotor: &r, drive: &drive, spin: false };
        // three revolutions in steps of a quarter revolution, the turned state itself as the
        // dense output
        let h = std::f64::consts::TAU / w / 4.0;
        let t_end = 12.0 * h;
        let mut window = RevolutionWindow::new(recorder.width(), t_end);
        for k in 0..12 {
            let (t0, t1) = (k as f64 * h, (k + 1) as f64 * h);
            window.dense_step(&recorder, t0, t1, &turned(t0), &turned(t1), &mut |t, out| out.copy_from_slice(&turned(t)));
        }
        let (y, phi) = (turned(t_end), w * t_end);
        let e = ending(&r, &window, &y, phi, w, true);
        assert!(e.settled);
        assert_eq!(e.outcome, RunOutcome::Balanced, "race whirl {:?}, residual {}", e.race_whirl, e.residual_unbalance);
        assert_eq!(e.outcome.name(), StateKind::Balanced.name());
        // the static residual as stability's (same balls' angles: to round-off)
        assert!((e.residual_unbalance - p.residual.unwrap()).abs() < 1e-9 && e.residual_unbalance > 0.5, "{} vs {:?}", e.residual_unbalance, p.residual);
        // the race whirl from the state in turning axes directly (its own second-order whirl
        // of the tilting ring, 3e-4 of the whirl without the resultant): the window's means of
        // the turned records give it to round-off (1e-9 relative: 32 records summed)
        let (f, _) = crate::rotor_campbell::stationary_at(&Rotor::Linear(r.clone()), w).unwrap();
        let crate::rotor_stability::Field::Linear(lf) = &f else { unreachable!() };
        let direct = super::super::partial::plane_whirl(&r, &s.x)[0] / super::super::partial::spread_whirl(lf).unwrap()[0];
        assert!((e.race_whirl.unwrap() - direct).abs() <= 1e-9 * direct, "{:?} vs {direct}", e.race_whirl);
    }
}
