//! Nonlinear passage through resonance of the planar rotor with an eccentric ball balancer
//! (paper 004; docs/model.md §2), in coordinates rotating with the rotor.
//!
//! ## Model
//! A disk (mass `m1`, centre of mass G at `s1` from the shaft point C, central moment `I_G`)
//! on a massless shaft (stiffness `k`, external damping `c`), an ABB housing (mass `m2`, centre E
//! at `s2` from C at angle `γ` from CG) and `n` balls (mass `m3`) on a race of radius `r` about
//! E, drag `c_ψ` on their motion relative to the housing, bearing drag `c_θ`.
//!
//! ## Equations (re-derived by d'Alembert's principle; see docs/simulation.md)
//! With `u = (X + iY) e^{−iθ}` the shaft point in rotor axes and body-frame offsets
//! `a_G = s1`, `a_E = s2 e^{iγ}`, `a_j = s2 e^{iγ} + r e^{iψ_j}`, each mass point has absolute
//! acceleration `e^{iθ} A_b`,
//! `A_b = ü + ä_b + iθ̈ (u + a_b) + 2iθ̇ (u̇ + ȧ_b) − θ̇² (u + a_b)`. The equations are
//!
//! ```text
//! Σ_b m_b A_b = −k u − c (u̇ + iθ̇ u)                                   (translation)
//! Σ_b m_b Re(conj(i(u + a_b)) A_b) + I_G θ̈ = M + Re(conj(iu)(−ku − c(u̇ + iθ̇u))) − c_θ θ̇   (θ)
//! m3 Re(conj(i r e^{iψ_j}) A_j) = −c_ψ ψ̇_j                             (ball j)
//! ```
//!
//! linear in `(ü, θ̈, ψ̈)` with a symmetric mass matrix (solved each step). In these coordinates
//! a steady synchronous whirl is a fixed point, so the integrator is not held to the period of
//! rotation; tests check the equations against the paper's fixed-frame eq (1) (after correcting
//! its sign) and against energy conservation.

pub mod problem;
pub mod stationary;

pub use crate::drive::Drive;
use crate::error::{finite, non_negative, positive, Error, Result};
use crate::ode::dop853::integrate;
use crate::ode::{rosenbrock, State, Stats, Stop, System, Tolerances, CAP};
use serde::Serialize;

/// Most balls the simulator takes (`2 (3 + n) ≤` [`CAP`]).
pub const MAX_BALLS: usize = 9;

/// The planar rotor of paper 004, SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanarRotor {
    /// Disk mass `m1` (kg).
    pub m1: f64,
    /// ABB housing mass `m2` (kg).
    pub m2: f64,
    /// Mass of one ball `m3` (kg).
    pub m3: f64,
    /// Number of balls.
    pub n: usize,
    /// Static eccentricity of the disk `s1 = |CG|` (m).
    pub s1: f64,
    /// Eccentricity of the ABB `s2 = |CE|` (m).
    pub s2: f64,
    /// Angle `γ` between CG and CE (rad).
    pub gamma: f64,
    /// Race radius `r` (m).
    pub r: f64,
    /// Shaft stiffness `k` (N/m).
    pub k: f64,
    /// External viscous damping `c` (kg/s).
    pub c: f64,
    /// Ball drag `c_ψ` (N·m·s).
    pub c_psi: f64,
    /// Bearing drag `c_θ` (N·m·s).
    pub c_theta: f64,
    /// Central moment of inertia of the disk (and housing) `I_G` (kg·m²).
    pub i_g: f64,
}

impl PlanarRotor {
    /// Paper 004's rotor with `m3 = 0.03` kg: `m1 = 1`, `m2 = 0.2`, `s1 = 3` mm, `s2 = 0.5` mm,
    /// `γ = 0`, `r = 60` mm, `c = 50`, `c_ψ = 0.1`, two balls, `k` such that
    /// `sqrt(k/m0) = 288 1/s`. `I_G` and `c_θ` are not given in the paper: `I_G = 0.0025 kg·m²`
    /// (a 1 kg disk of radius 70 mm), `c_θ = 0`.
    pub fn paper() -> Self {
        let m0 = 1.0 + 0.2 + 2.0 * 0.03;
        PlanarRotor {
            m1: 1.0,
            m2: 0.2,
            m3: 0.03,
            n: 2,
            s1: 0.003,
            s2: 0.0005,
            gamma: 0.0,
            r: 0.06,
            k: 288.0 * 288.0 * m0,
            c: 50.0,
            c_psi: 0.1,
            c_theta: 0.0,
            i_g: 0.0025,
        }
    }

    /// Check every field; errors name it as `planar.<field>`.
    pub fn validate(&self) -> Result<()> {
        positive("planar.m1", self.m1)?;
        non_negative("planar.m2", self.m2)?;
        non_negative("planar.m3", self.m3)?;
        non_negative("planar.s1", self.s1)?;
        non_negative("planar.s2", self.s2)?;
        finite("planar.gamma", self.gamma)?;
        positive("planar.k", self.k)?;
        non_negative("planar.c", self.c)?;
        non_negative("planar.c_theta", self.c_theta)?;
        positive("planar.i_g", self.i_g)?;
        if self.n > MAX_BALLS {
            return Err(Error::invalid("planar.n", format!("at most {MAX_BALLS} balls, got {}", self.n)));
        }
        if self.n > 0 {
            positive("planar.m3", self.m3)?;
            positive("planar.r", self.r)?;
            non_negative("planar.c_psi", self.c_psi)?;
        }
        Ok(())
    }

    /// `m0 = m1 + m2 + n m3`.
    pub fn total_mass(&self) -> f64 {
        self.m1 + self.m2 + self.n as f64 * self.m3
    }

    /// `J_C = I_G + m1 s1² + (m2 + n m3) s2²` (the paper's polar moment about C).
    pub fn polar_moment(&self) -> f64 {
        self.i_g + self.m1 * self.s1 * self.s1 + (self.m2 + self.n as f64 * self.m3) * self.s2 * self.s2
    }

    /// Natural frequency `sqrt(k/m0)` (rad/s).
    pub fn natural_frequency(&self) -> f64 {
        (self.k / self.total_mass()).sqrt()
    }
}

/// Which integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Explicit DOP853 (default): fastest unless the balls relax much faster than the whirl.
    #[default]
    Dop853,
    /// Linearly implicit 4th-order Rosenbrock ([`rosenbrock`]): for stiff runs (light balls,
    /// heavy ball drag: `m3 r²/c_ψ` far below the whirl's time scales).
    Rosenbrock,
}

/// Integration settings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Settings {
    /// The integrator.
    pub method: Method,
    /// End time (s).
    pub t_end: f64,
    /// Output interval (s), independent of the internal steps.
    pub dt: f64,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on displacements (m); angles and rates are scaled from it.
    pub atol: f64,
    /// Initial ball angles `ψ_j` in the disk frame, from CG (rad).
    pub psi0: Vec<f64>,
    /// Initial ball rates relative to the disk (rad/s).
    pub psi_rate0: Vec<f64>,
}

impl Settings {
    /// Default initial ball angles: spread evenly, `ψ_j = π/2 + 2π j/n`, so the balls start with no
    /// net unbalance (for n = 2: across the unbalance direction).
    pub fn default_psi0(n: usize) -> Vec<f64> {
        (0..n).map(|j| std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * j as f64 / n as f64).collect()
    }

    /// Validate against the rotor (errors name `drive.<field>` or `integration.<field>`).
    pub fn validate(&self, rotor: &PlanarRotor) -> Result<()> {
        positive("drive.t_end", self.t_end)?;
        positive("integration.dt", self.dt)?;
        if self.t_end / self.dt > 5e7 {
            return Err(Error::invalid("integration.dt", format!("{} samples is too many; raise dt", crate::error::fmt_num(self.t_end / self.dt))));
        }
        positive("integration.rtol", self.rtol)?;
        positive("integration.atol", self.atol)?;
        if self.rtol < 1e-14 {
            return Err(Error::invalid("integration.rtol", "below 1e-14 the step cannot reach it in double precision"));
        }
        if self.psi0.len() != rotor.n {
            return Err(Error::invalid("drive.psi0", format!("needs {} angles (planar.n), got {}", rotor.n, self.psi0.len())));
        }
        if self.psi_rate0.len() != rotor.n {
            return Err(Error::invalid("drive.psi_rate0", format!("needs {} rates (planar.n), got {}", rotor.n, self.psi_rate0.len())));
        }
        for a in self.psi0.iter().chain(&self.psi_rate0) {
            finite("drive.psi0", *a)?;
        }
        Ok(())
    }
}

/// The equations in rotor axes: state `y = (ξ, η, θ, ψ_1..n, ξ̇, η̇, θ̇, ψ̇_1..n)`.
pub struct Equations<'a> {
    pub rotor: &'a PlanarRotor,
    pub drive: &'a Drive,
}

impl Equations<'_> {
    /// Number of generalised coordinates `3 + n`.
    pub fn coords(&self) -> usize {
        3 + self.rotor.n
    }
}

#[derive(Clone, Copy)]
struct C64 {
    re: f64,
    im: f64,
}
impl C64 {
    fn new(re: f64, im: f64) -> Self {
        C64 { re, im }
    }
    fn add(self, o: C64) -> C64 {
        C64::new(self.re + o.re, self.im + o.im)
    }
    fn scale(self, s: f64) -> C64 {
        C64::new(self.re * s, self.im * s)
    }
    fn mul_i(self) -> C64 {
        C64::new(-self.im, self.re)
    }
    /// `Re(conj(self) · o)`: the dot product of two plane vectors.
    fn dot(self, o: C64) -> f64 {
        self.re * o.re + self.im * o.im
    }
}

impl System for Equations<'_> {
    fn dim(&self) -> usize {
        2 * self.coords()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let p = self.rotor;
        let n = p.n;
        let nc = 3 + n;
        let u = C64::new(y[0], y[1]);
        let ud = C64::new(y[nc], y[nc + 1]);
        let th_d = if self.drive.prescribed() { self.drive.kinematics(t).0 } else { y[nc + 2] };
        // offsets and their rates
        let e_off = C64::new(p.s2 * p.gamma.cos(), p.s2 * p.gamma.sin());
        let mut a = [C64::new(0.0, 0.0); MAX_BALLS + 2];
        let mut ad = [C64::new(0.0, 0.0); MAX_BALLS + 2];
        let mut dir = [C64::new(0.0, 0.0); MAX_BALLS]; // e^{iψ_j}
        let mut mass = [0.0; MAX_BALLS + 2];
        a[0] = C64::new(p.s1, 0.0);
        mass[0] = p.m1;
        a[1] = e_off;
        mass[1] = p.m2;
        for j in 0..n {
            let (s, c) = y[3 + j].sin_cos();
            dir[j] = C64::new(c, s);
            a[2 + j] = e_off.add(dir[j].scale(p.r));
            ad[2 + j] = dir[j].mul_i().scale(p.r * y[nc + 3 + j]);
            mass[2 + j] = p.m3;
        }
        let nb = 2 + n;
        // velocity-dependent part R_b of each acceleration
        let mut rb = [C64::new(0.0, 0.0); MAX_BALLS + 2];
        for b in 0..nb {
            let pos = u.add(a[b]);
            let mut r = ud.add(ad[b]).mul_i().scale(2.0 * th_d).add(pos.scale(-th_d * th_d));
            if b >= 2 {
                let j = b - 2;
                let psd = y[nc + 3 + j];
                r = r.add(dir[j].scale(-p.r * psd * psd));
            }
            rb[b] = r;
        }
        // mass matrix Mx = f for x = (ü_re, ü_im, θ̈, ψ̈_1..n)
        let mut m = [[0.0; MAX_BALLS + 3]; MAX_BALLS + 3];
        let mut f = [0.0; MAX_BALLS + 3];
        let m0 = p.total_mass();
        let force = u.scale(-p.k).add(ud.add(u.mul_i().scale(th_d)).scale(-p.c));
        // translation: m0 ü + iθ̈ S + Σ m3 i r e^{iψ_j} ψ̈_j = F − Σ m_b R_b
        let mut s_sum = C64::new(0.0, 0.0);
        let mut r_sum = C64::new(0.0, 0.0);
        let mut inertia = p.i_g;
        for b in 0..nb {
            let pos = u.add(a[b]);
            s_sum = s_sum.add(pos.scale(mass[b]));
            r_sum = r_sum.add(rb[b].scale(mass[b]));
            inertia += mass[b] * pos.dot(pos);
        }
        let is = s_sum.mul_i();
        m[0][0] = m0;
        m[1][1] = m0;
        m[0][2] = is.re;
        m[1][2] = is.im;
        f[0] = force.re - r_sum.re;
        f[1] = force.im - r_sum.im;
        // θ row: Re(conj(iS) ü) + θ̈ (I_G + Σ m_b |u + a_b|²) + Σ m3 Re(conj(u + a_j) r e^{iψ_j}) ψ̈_j
        m[2][0] = is.re;
        m[2][1] = is.im;
        m[2][2] = inertia;
        let mut rot_rhs = u.mul_i().dot(force) - p.c_theta * th_d;
        for b in 0..nb {
            rot_rhs -= mass[b] * u.add(a[b]).mul_i().dot(rb[b]);
        }
        f[2] = rot_rhs;
        for j in 0..n {
            let b = 2 + j;
            let tj = dir[j].mul_i().scale(p.r); // ∂(u + a_j)/∂ψ_j
            let coup = p.m3 * u.add(a[b]).mul_i().dot(tj);
            m[2][3 + j] = coup;
            m[3 + j][2] = coup;
            m[0][3 + j] = p.m3 * tj.re;
            m[1][3 + j] = p.m3 * tj.im;
            m[3 + j][0] = p.m3 * tj.re;
            m[3 + j][1] = p.m3 * tj.im;
            m[3 + j][3 + j] = p.m3 * p.r * p.r;
            f[3 + j] = -p.c_psi * y[nc + 3 + j] - p.m3 * tj.dot(rb[b]);
        }
        if self.drive.prescribed() {
            let (_, acc) = self.drive.kinematics(t);
            // θ̈ known: drop its row, move its column to the right-hand side
            for r in 0..nc {
                if r != 2 {
                    f[r] -= m[r][2] * acc;
                }
                m[r][2] = 0.0;
            }
            m[2] = [0.0; MAX_BALLS + 3];
            m[2][2] = 1.0;
            f[2] = acc;
        } else {
            f[2] += self.drive.torque(t, th_d);
        }
        // the mass matrix is positive definite for validated inputs; NaN stops the integrator
        if !crate::linalg::dense::solve_once(&mut m, &mut f, nc) {
            f = [f64::NAN; MAX_BALLS + 3];
        }
        dy[..nc].copy_from_slice(&y[nc..2 * nc]);
        dy[nc..2 * nc].copy_from_slice(&f[..nc]);
        if self.drive.prescribed() {
            // keep θ̇ on the schedule exactly (its derivative is the prescribed acceleration)
            let (w, _) = self.drive.kinematics(t);
            dy[2] = w;
        }
    }
}

/// One output sample.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Rotor speed `θ̇` (rad/s).
    pub omega: f64,
    /// Rotor angle `θ` (rad).
    pub theta: f64,
    /// `X` of the shaft point C in fixed axes (m).
    pub x: f64,
    /// `Y` of C (m).
    pub y: f64,
    /// Whirl radius of C, `sqrt(X² + Y²)` (m).
    pub amplitude: f64,
    /// Ball angles in the disk frame (rad).
    pub psi: Vec<f64>,
}

/// Summary of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Largest whirl radius of C, at step ends and samples (m).
    pub peak_amplitude: f64,
    /// Rotor speed at that moment (rad/s).
    pub omega_at_peak: f64,
    /// Time of the peak (s).
    pub t_at_peak: f64,
    /// Whirl radius at the end (m).
    pub final_amplitude: f64,
    /// Speed at the end (rad/s).
    pub final_omega: f64,
    /// Whether the end state is the balanced/semi-balanced whirl: radius of C within 5 % of
    /// `s2` (or below 5 % of `s1` when `s2 = 0`) and balls at rest relative to the disk.
    pub balanced: bool,
    /// Integrator work.
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Right-hand-side evaluations (including dense output).
    pub rhs_evaluations: u64,
    /// End time reached (s).
    pub t_end: f64,
    /// Why the run stopped before `t_end`, if it did.
    pub stopped: Option<String>,
}

fn sample_of(rotor: &PlanarRotor, drive: &Drive, t: f64, y: &State) -> Sample {
    let nc = 3 + rotor.n;
    let omega = if drive.prescribed() { drive.kinematics(t).0 } else { y[nc + 2] };
    let (s, c) = y[2].sin_cos();
    let x = y[0] * c - y[1] * s;
    let yy = y[0] * s + y[1] * c;
    Sample { t, omega, theta: y[2], x, y: yy, amplitude: y[0].hypot(y[1]), psi: y[3..3 + rotor.n].to_vec() }
}

/// Initial state from the drive and settings: C at rest on the axis, balls as set.
pub fn initial_state(rotor: &PlanarRotor, drive: &Drive, settings: &Settings) -> State {
    let nc = 3 + rotor.n;
    let mut y = [0.0; CAP];
    for j in 0..rotor.n {
        y[3 + j] = settings.psi0[j];
        y[nc + 3 + j] = settings.psi_rate0[j];
    }
    y[nc + 2] = drive.omega0();
    y
}

/// Absolute tolerances per component: `atol` on displacements, `atol/s_ref` on angles
/// (`s_ref = max(s1, s2, r, atol)`), and the same divided by a time scale `1/ω_n` on rates.
pub fn tolerances(rotor: &PlanarRotor, settings: &Settings) -> Tolerances {
    let nc = 3 + rotor.n;
    let s_ref = rotor.s1.max(rotor.s2).max(rotor.r).max(settings.atol);
    let wn = rotor.natural_frequency();
    let mut atol = [1.0; CAP];
    for i in 0..nc {
        let base = if i < 2 { settings.atol } else { settings.atol / s_ref };
        atol[i] = base;
        atol[nc + i] = base * wn;
    }
    Tolerances { rtol: settings.rtol, atol, h_max: f64::INFINITY, max_steps: 200_000_000 }
}

/// Simulate; `sink` receives every sample (at multiples of `dt`) and may return `false` to
/// stop (an interruption): the summary then covers what was computed.
pub fn simulate(rotor: &PlanarRotor, drive: &Drive, settings: &Settings, mut sink: impl FnMut(&Sample) -> bool) -> Result<Summary> {
    rotor.validate()?;
    drive.validate()?;
    settings.validate(rotor)?;
    let eq = Equations { rotor, drive };
    let y0 = initial_state(rotor, drive, settings);
    let tol = tolerances(rotor, settings);
    let mut obs = Observer { rotor, drive, settings, sink: &mut sink, peak: (rotor_amp(&y0), drive.omega0(), 0.0), next_sample: 0 };
    let first = sample_of(rotor, drive, 0.0, &y0);
    let keep_going = (obs.sink)(&first);
    obs.next_sample = 1;
    let nc = 3 + rotor.n;
    let mut stats = Stats::default();
    let (mut t, mut y, mut stop) = (0.0, y0, None);
    if !keep_going {
        stop = Some(Stop::Requested { t: 0.0 });
    }
    // integrate piecewise between the drive's breakpoints
    let mut ends: Vec<f64> = drive.breakpoints().into_iter().filter(|b| *b > 0.0 && *b < settings.t_end).collect();
    ends.push(settings.t_end);
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    for end in ends {
        if stop.is_some() {
            break;
        }
        if drive.prescribed() {
            y[nc + 2] = drive.kinematics(t).0; // start each piece exactly on the schedule
        }
        let (t1, y1, st, s1) = match settings.method {
            Method::Dop853 => integrate(&eq, t, &y, end, &tol, |s| obs.on_step(s.t_new, s.y_new, |t| s.interpolate(t))),
            Method::Rosenbrock => {
                // the dense output is third order: keep steps within a few sample intervals
                let tol = Tolerances { h_max: 4.0 * settings.dt, ..tol };
                rosenbrock::integrate(&eq, t, &y, end, &tol, |s| obs.on_step(s.t_new, s.y_new, |t| s.interpolate(t)))
            }
        };
        (t, y, stop) = (t1, y1, s1);
        stats.steps += st.steps;
        stats.rejected += st.rejected;
        stats.rhs_evaluations += st.rhs_evaluations;
    }
    let peak = obs.peak;
    let final_amp = rotor_amp(&y);
    let rates_small = (0..rotor.n).all(|j| y[nc + 3 + j].abs() < 1e-3 * y[nc + 2].abs().max(1.0));
    let target = if rotor.s2 > 0.0 { rotor.s2 } else { 0.0 };
    let tolerance = if rotor.s2 > 0.0 { 0.05 * rotor.s2 } else { 0.05 * rotor.s1.max(1e-9) };
    let balanced = rotor.n > 0 && (final_amp - target).abs() <= tolerance && rates_small;
    Ok(Summary {
        peak_amplitude: peak.0,
        omega_at_peak: peak.1,
        t_at_peak: peak.2,
        final_amplitude: final_amp,
        final_omega: y[nc + 2],
        balanced,
        steps: stats.steps,
        rejected_steps: stats.rejected,
        rhs_evaluations: stats.rhs_evaluations,
        t_end: t,
        stopped: stop.map(|s| match s {
            Stop::StepTooSmall { t } => format!("step size underflow at t = {t}"),
            Stop::TooManySteps { t } => format!("too many steps at t = {t}"),
            Stop::NotFinite { t } => format!("the state became non-finite at t = {t}"),
            Stop::Requested { t } => format!("interrupted at t = {t}"),
        }),
    })
}

/// What `simulate` does after each accepted step, whichever the integrator: track the peak and
/// emit the samples that fall in the step (from the dense output).
struct Observer<'a, F: FnMut(&Sample) -> bool> {
    rotor: &'a PlanarRotor,
    drive: &'a Drive,
    settings: &'a Settings,
    sink: &'a mut F,
    peak: (f64, f64, f64),
    next_sample: usize,
}

impl<F: FnMut(&Sample) -> bool> Observer<'_, F> {
    fn on_step(&mut self, t_new: f64, y_new: &State, interpolate: impl Fn(f64) -> State) -> bool {
        let nc = 3 + self.rotor.n;
        let a = rotor_amp(y_new);
        if a > self.peak.0 {
            self.peak = (a, y_new[nc + 2], t_new);
        }
        loop {
            let ts = self.next_sample as f64 * self.settings.dt;
            if ts > t_new + 1e-12 * t_new.abs() || ts > self.settings.t_end * (1.0 + 1e-12) {
                return true;
            }
            let ys = if (ts - t_new).abs() <= 1e-12 * ts.abs().max(1.0) { *y_new } else { interpolate(ts) };
            let s = sample_of(self.rotor, self.drive, ts, &ys);
            if s.amplitude > self.peak.0 {
                self.peak = (s.amplitude, s.omega, ts);
            }
            self.next_sample += 1;
            if !(self.sink)(&s) {
                return false;
            }
        }
    }
}

fn rotor_amp(y: &State) -> f64 {
    y[0].hypot(y[1])
}

/// Total mechanical energy `T + V` of a state (J): for the energy-balance tests.
pub fn energy(rotor: &PlanarRotor, y: &State) -> f64 {
    let n = rotor.n;
    let nc = 3 + n;
    let u = C64::new(y[0], y[1]);
    let ud = C64::new(y[nc], y[nc + 1]);
    let w = y[nc + 2];
    let e_off = C64::new(rotor.s2 * rotor.gamma.cos(), rotor.s2 * rotor.gamma.sin());
    let vel = |a: C64, ad: C64| ud.add(ad).add(u.add(a).mul_i().scale(w));
    let mut t = 0.5 * rotor.i_g * w * w;
    let v_g = vel(C64::new(rotor.s1, 0.0), C64::new(0.0, 0.0));
    t += 0.5 * rotor.m1 * v_g.dot(v_g);
    let v_e = vel(e_off, C64::new(0.0, 0.0));
    t += 0.5 * rotor.m2 * v_e.dot(v_e);
    for j in 0..n {
        let (s, c) = y[3 + j].sin_cos();
        let d = C64::new(c, s);
        let v = vel(e_off.add(d.scale(rotor.r)), d.mul_i().scale(rotor.r * y[nc + 3 + j]));
        t += 0.5 * rotor.m3 * v.dot(v);
    }
    t + 0.5 * rotor.k * u.dot(u)
}
