//! Nonlinear passage through resonance of the planar rotor with an eccentric ball balancer
//! (paper 004; docs/notes/model.md §2), in coordinates rotating with the rotor.
//!
//! ## Model
//! A disk (mass `m1`, centre of mass G at `s1` from the shaft point C, central moment `I_G`)
//! on a massless shaft (stiffness `k`, external damping `c`), an ABB housing (mass `m2`, centre E
//! at `s2` from C at angle `γ` from CG) and `n` balls (mass `m3`) on a race of radius `r` about
//! E, drag `c_ψ` on their motion relative to the housing, bearing drag `c_θ`.
//!
//! ## Equations (re-derived by d'Alembert's principle; see docs/notes/simulation.md)
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
//! linear in `(ü, θ̈, ψ̈)` with a symmetric mass matrix with the arrow pattern (each ball couples
//! only to the rotor): [`Equations`] eliminates the balls in closed form, so a right-hand side
//! costs `O(n)`, and gives the implicit method an exact structured Jacobian (also `O(n)`). In
//! these coordinates a steady synchronous whirl is a fixed point, so the integrator is not held
//! to the period of rotation; tests check the equations against the paper's fixed-frame eq (1)
//! (after correcting its sign) and against energy conservation.
//!
//! ```
//! use autobal::planar::{simulate, Drive, PlanarRotor, Settings};
//! // paper 004's rotor run up at 20 1/s² from 200 to 500 rad/s, through its resonance at 288
//! let rotor = PlanarRotor::paper();
//! let drive = Drive::Acceleration { omega0: 200.0, b: 20.0 };
//! let settings = Settings::new(&rotor, 15.0);
//! let summary = simulate(&rotor, &drive, &settings, |_sample| true).unwrap();
//! assert!(summary.status.is_completed());
//! assert!(summary.omega_at_peak > 280.0 && summary.omega_at_peak < 320.0);
//! assert!(summary.balanced, "{:?}", summary.warnings); // semi-balanced: C whirls at s2
//! ```

mod equations;
pub mod field;
pub mod friction;
pub mod paper004;
pub mod problem;
pub mod stationary;

use crate::balls::{BallForces, BallPhysics, EventCounter};
pub use crate::drive::Drive;
use crate::error::{finite, non_negative, positive, Error, Result};
pub use crate::ode::Method;
use crate::ode::{Control, Direction, Event, Options, Solver, Status, StopReason, System};
use crate::simulation::{run, Hooks, Peak, RevolutionWindow, Timeline};
pub use equations::{energy, Equations};
use serde::Serialize;

/// Most balls the simulator takes. The cost of a step is linear in `n` (about 110 instructions
/// per ball and right-hand side, as many again in the integrators' vector operations: 64 balls
/// cost about 9× two); the limit only keeps a mistyped number from allocating gigabytes.
pub const MAX_BALLS: usize = crate::limits::PLANAR_MAX_BALLS;

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
    /// Shaft stiffness `k` (N/m): along the fixed x axis, and along y too unless `k_y` is set.
    pub k: f64,
    /// External viscous damping `c` (kg/s): along x, and along y too unless `c_y` is set.
    pub c: f64,
    /// Stiffness along the fixed y axis (N/m) where the supports differ by direction
    /// (`planar.k_x`, `planar.k_y`: then `k` is `k_x`); `None`: `k` in every direction.
    pub k_y: Option<f64>,
    /// Damping along the fixed y axis (kg/s), as `k_y`; `None`: `c` in every direction.
    pub c_y: Option<f64>,
    /// Ball drag `c_ψ` (N·m·s).
    pub c_psi: f64,
    /// The mass of each ball (kg, `planar.ball_masses`, one per ball); `None`: `m3` each.
    pub ball_masses: Option<Vec<f64>>,
    /// The drag on each ball (N·m·s, `planar.ball_drags`, one per ball); `None`: `c_ψ` each.
    pub ball_drags: Option<Vec<f64>>,
    /// Bearing drag `c_θ` (N·m·s).
    pub c_theta: f64,
    /// Central moment of inertia of the disk (and housing) `I_G` (kg·m²).
    pub i_g: f64,
    /// Real balls: diameter, contact, rolling resistance ([`crate::balls`]); default: the
    /// paper's point masses.
    pub balls: BallPhysics,
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
            k_y: None,
            c_y: None,
            c_psi: 0.1,
            ball_masses: None,
            ball_drags: None,
            c_theta: 0.0,
            i_g: 0.0025,
            balls: BallPhysics::default(),
        }
    }

    /// Check every field; errors name it as `planar.<field>`.
    pub fn validate(&self) -> Result<()> {
        check_ranges(self)?;
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
        if let Some(ky) = self.k_y {
            positive("planar.k_y", ky)?;
        }
        if let Some(cy) = self.c_y {
            non_negative("planar.c_y", cy)?;
        }
        for (key, list, what) in [("planar.ball_masses", &self.ball_masses, "mass"), ("planar.ball_drags", &self.ball_drags, "drag")] {
            let Some(v) = list else { continue };
            if v.len() != self.n {
                return Err(Error::invalid(key, format!("needs one {what} per ball (planar.n = {}), got {}", self.n, v.len())));
            }
            for (j, x) in v.iter().enumerate() {
                let field = format!("{key}[{}]", j + 1);
                if what == "mass" {
                    positive(&field, *x)?;
                } else {
                    non_negative(&field, *x)?;
                }
            }
            if self.balls.is_active() {
                return Err(Error::invalid(
                    key,
                    "real balls (planar.contact, planar.rolling_resistance) are modelled as equal balls: give m3 and c_psi instead of one value per ball",
                ));
            }
        }
        self.balls.validate("planar", self.m3, self.r, self.n)?;
        Ok(())
    }

    /// The mass of ball `j` (`ball_masses[j]`, else `m3`).
    #[inline]
    pub fn ball_mass(&self, j: usize) -> f64 {
        self.ball_masses.as_ref().map_or(self.m3, |m| m[j])
    }

    /// The drag on ball `j` (`ball_drags[j]`, else `c_ψ`).
    #[inline]
    pub fn ball_drag(&self, j: usize) -> f64 {
        self.ball_drags.as_ref().map_or(self.c_psi, |c| c[j])
    }

    /// Whether every ball has the same mass and drag (`m3`, `c_ψ`): the fast elimination of
    /// [`Equations`] applies.
    pub fn equal_balls(&self) -> bool {
        self.ball_masses.is_none() && self.ball_drags.is_none()
    }

    /// The mass of all balls `Σ m_j` (`n m3` for equal balls).
    pub fn balls_mass(&self) -> f64 {
        match &self.ball_masses {
            Some(m) => m.iter().sum(),
            None => self.n as f64 * self.m3,
        }
    }

    /// Stiffness along the fixed x and y axes `(k_x, k_y)` (N/m).
    pub fn stiffness_xy(&self) -> (f64, f64) {
        (self.k, self.k_y.unwrap_or(self.k))
    }

    /// Damping along the fixed x and y axes `(c_x, c_y)` (kg/s).
    pub fn damping_xy(&self) -> (f64, f64) {
        (self.c, self.c_y.unwrap_or(self.c))
    }

    /// Whether the supports differ by direction (`k_x ≠ k_y` or `c_x ≠ c_y`): then the
    /// equations in rotor axes depend on the rotor angle, with period `π` in it.
    pub fn anisotropic(&self) -> bool {
        let ((kx, ky), (cx, cy)) = (self.stiffness_xy(), self.damping_xy());
        kx != ky || cx != cy
    }

    /// The mean support stiffness and damping `(k̄, c̄) = ((k_x + k_y)/2, (c_x + c_y)/2)`.
    pub fn mean_supports(&self) -> (f64, f64) {
        let ((kx, ky), (cx, cy)) = (self.stiffness_xy(), self.damping_xy());
        (0.5 * (kx + ky), 0.5 * (cx + cy))
    }

    /// `m0 = m1 + m2 + Σ m_j` (`m1 + m2 + n m3` for equal balls).
    pub fn total_mass(&self) -> f64 {
        self.m1 + self.m2 + self.balls_mass()
    }

    /// `J_C = I_G + m1 s1² + (m2 + Σ m_j) s2²` (the paper's polar moment about C).
    pub fn polar_moment(&self) -> f64 {
        self.i_g + self.m1 * self.s1 * self.s1 + (self.m2 + self.balls_mass()) * self.s2 * self.s2
    }

    /// Natural frequency `sqrt(k/m0)` (rad/s); for supports that differ by direction the lower
    /// one, `sqrt(min(k_x, k_y)/m0)` (the first resonance of a run-up).
    pub fn natural_frequency(&self) -> f64 {
        let (kx, ky) = self.stiffness_xy();
        (kx.min(ky) / self.total_mass()).sqrt()
    }

    /// The natural frequencies along x and y, `(sqrt(k_x/m0), sqrt(k_y/m0))` (rad/s).
    pub fn natural_frequencies_xy(&self) -> (f64, f64) {
        let (kx, ky) = self.stiffness_xy();
        ((kx / self.total_mass()).sqrt(), (ky / self.total_mass()).sqrt())
    }
}

/// Integration settings and initial conditions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Settings {
    /// The integrator ([`Method::Auto`]: DOP853, switching to RODAS while the problem is stiff).
    pub method: Method,
    /// End time (s).
    pub t_end: f64,
    /// Output interval (s); also the time resolution of [`Method::Auto`] and
    /// [`Method::Rodas`] (implicit steps of at most `4 dt`, see [`tolerances`]); samples are
    /// read from the dense output.
    pub dt: f64,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on displacements (m); angles and rates are scaled from it.
    pub atol: f64,
    /// Initial ball angles `ψ_j` in the disk frame, from CG (rad).
    pub psi0: Vec<f64>,
    /// Initial ball rates relative to the disk (rad/s).
    pub psi_rate0: Vec<f64>,
    /// Initial position `(X, Y)` of the shaft point C in fixed axes (m); the rotor angle starts
    /// at 0, so rotor and fixed axes coincide at `t = 0`.
    pub xy0: [f64; 2],
    /// Initial velocity `(Ẋ, Ẏ)` of C in fixed axes (m/s).
    pub xy_rate0: [f64; 2],
    /// Step budget: the run stops (and says so) after this many integrator steps.
    pub max_steps: u64,
    /// Wall-clock budget (s), if any.
    pub max_wall_s: Option<f64>,
}

impl Settings {
    /// Defaults for `rotor` run to `t_end` ([`Settings::for_balls`] with its number of balls).
    pub fn new(rotor: &PlanarRotor, t_end: f64) -> Self {
        Settings::for_balls(rotor.n, t_end)
    }

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
        if self.rtol > 1e-2 {
            return Err(Error::invalid("integration.rtol", format!("{} is too loose for a meaningful result (at most 1e-2)", self.rtol)));
        }
        if self.psi0.len() != rotor.n {
            return Err(Error::invalid("drive.psi0", format!("needs {} angles (planar.n), got {}", rotor.n, self.psi0.len())));
        }
        if self.psi_rate0.len() != rotor.n {
            return Err(Error::invalid("drive.psi_rate0", format!("needs {} rates (planar.n), got {}", rotor.n, self.psi_rate0.len())));
        }
        for a in &self.psi0 {
            finite("drive.psi0", *a)?;
        }
        for a in &self.psi_rate0 {
            finite("drive.psi_rate0", *a)?;
        }
        rotor.balls.check_initial("drive.psi0", rotor.m3, rotor.r, &self.psi0)?;
        // real balls make the implicit step's Jacobian dense (equations.rs): O(n³) per step,
        // O(n²) memory
        let max = crate::limits::MAX_BALLS_IMPLICIT_REAL;
        if rotor.balls.is_active() && rotor.n > max && self.method != Method::Dop853 {
            return Err(Error::invalid(
                "integration.method",
                format!(
                    "with real balls (contact or rolling resistance) an implicit step costs O(n³) in the balls (a dense Jacobian): at most {max} balls with \"rodas\" or \"auto\", got planar.n = {}; use \"dop853\" (O(n log n) per step)",
                    rotor.n
                ),
            ));
        }
        for a in self.xy0 {
            finite("drive.xy0", a)?;
        }
        for a in self.xy_rate0 {
            finite("drive.xy_rate0", a)?;
        }
        if self.max_steps == 0 {
            return Err(Error::invalid("integration.max_steps", "must be at least 1"));
        }
        if let Some(w) = self.max_wall_s {
            positive("integration.max_wall_s", w)?;
        }
        Ok(())
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

/// The planar rotor (paper 004): every field in its range, and the shaft's natural frequency
/// `sqrt(k/m0)` within `[1e-3, 1e7]` rad/s (0.16 mHz to 1.6 MHz): below, the shaft has no
/// stiffness on any drive's time scale; above, it is rigid on them, and an integrator would
/// need ~100 steps per period of a vibration that plays no part. [`PlanarRotor::validate`]
/// calls it.
pub(crate) fn check_ranges(r: &PlanarRotor) -> Result<()> {
    use crate::error::fmt_num;
    use crate::limits::{check, check_all, check_as, check_count};
    check_all(&[
        ("planar.m1", r.m1),
        ("planar.m2", r.m2),
        ("planar.m3", r.m3),
        ("planar.s1", r.s1),
        ("planar.s2", r.s2),
        ("planar.gamma", r.gamma),
        ("planar.r", r.r),
        ("planar.k", r.k),
        ("planar.c", r.c),
        ("planar.c_psi", r.c_psi),
        ("planar.c_theta", r.c_theta),
        ("planar.i_g", r.i_g),
    ])?;
    if let Some(v) = r.k_y {
        check("planar.k_y", v)?;
    }
    if let Some(v) = r.c_y {
        check("planar.c_y", v)?;
    }
    for (field, list) in [("planar.ball_masses", &r.ball_masses), ("planar.ball_drags", &r.ball_drags)] {
        for (j, v) in list.iter().flatten().enumerate() {
            check_as(&format!("{field}[{}]", j + 1), field, *v)?;
        }
    }
    check_count("planar.n", r.n as u64)?;
    // each direction's natural frequency (supports that differ by direction: k_x, k_y)
    let (kx, ky) = r.stiffness_xy();
    let directions: &[(&str, &str, f64)] = if r.k_y.is_some() { &[("planar.k_x", "k_x", kx), ("planar.k_y", "k_y", ky)] } else { &[("planar.k", "k", kx)] };
    for &(field, key, k) in directions {
        let wn = (k / r.total_mass()).sqrt();
        if !(1e-3..=1e7).contains(&wn) {
            return Err(Error::invalid(
                field,
                format!(
                    "the natural frequency sqrt({key}/m0) = {} rad/s ({key} = {} N/m, m0 = {} kg) lies outside [0.001, 1e7] rad/s",
                    fmt_num(wn),
                    fmt_num(k),
                    fmt_num(r.total_mass())
                ),
            ));
        }
    }
    check_damping_ratios(r)
}

/// Each direction's support damping through the dimensionless damping it implies, as the
/// spatial rotor's supports (`h̄x`, [`crate::spatial::dynamics::SpatialRotor::to_dimensionless`]):
/// `c_d/(m0 ω_d)` with `ω_d = sqrt(k_d/m0)`, within the range of `dimensionless.h_x` (a
/// damping ratio up to 500; beyond, the supports do not move). The error names the damping
/// key the config gives: `planar.c` (the same in every direction, held against the smaller
/// stiffness where `k_x` and `k_y` differ), else `planar.c_x` or `planar.c_y`. (`c_y = 1e12`
/// was taken, and `stability` then ran for minutes.)
fn check_damping_ratios(r: &PlanarRotor) -> Result<()> {
    let m0 = r.total_mass();
    let ((kx, ky), (cx, cy)) = (r.stiffness_xy(), r.damping_xy());
    let k_keys = if r.k_y.is_some() { ["k_x", "k_y"] } else { ["k", "k"] };
    let c_keys = if r.c_y.is_some() { ["c_x", "c_y"] } else { ["c", "c"] };
    // x then y; the isotropic c against the smaller stiffness, named once
    let mut order = [(0, kx, cx), (1, ky, cy)];
    if r.c_y.is_none() && ky < kx {
        order.swap(0, 1);
    }
    for (d, k, c) in order {
        let (kk, ck) = (k_keys[d], c_keys[d]);
        let omega = (k / m0).sqrt();
        let what = format!(
            "{ck}/(m0 ω) with ω = sqrt({kk}/m0) = {} rad/s (m0 = {} kg), the dimensionless damping of the supports,",
            crate::error::fmt_num(omega),
            crate::error::fmt_num(m0)
        );
        crate::limits::check_derived(&format!("planar.{ck}"), "dimensionless.h_x", c / (m0 * omega), &what)?;
    }
    Ok(())
}

/// Summary of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Largest whirl radius of C (m), located on the dense output between step ends.
    pub peak_amplitude: f64,
    /// Rotor speed at that moment (rad/s).
    pub omega_at_peak: f64,
    /// Time of the peak (s).
    pub t_at_peak: f64,
    /// Whirl radius at the end (m).
    pub final_amplitude: f64,
    /// Speed at the end (rad/s).
    pub final_omega: f64,
    /// Whether the end state is the balanced/semi-balanced whirl: C's mean position in rotor
    /// axes over the last revolution (the end state where the run turned less; the whirl's
    /// radius for a steady whirl, about which the radius of an elliptic one swings) within 5 %
    /// of `s2` from the axis (or below 5 % of `s1` when `s2 = 0`) and the balls at rest relative to the rotor
    /// (their rates within the limit of `settled`), and [`Summary::outcome`] balanced (a
    /// partially or not balanced run can leave C within that 5 %).
    pub balanced: bool,
    /// The residual the balls leave, averaged over the run's last revolution (of the rotor
    /// angle `θ`; the end state where the run turned less): the race centre E's mean distance
    /// from the axis, `|⟨u⟩ + s2 e^{iγ}|` (`u` the shaft point C in rotor axes), over its
    /// distance without the balls' resultant at the final speed
    /// ([`stationary::race_offset_scale`]), as `stability`'s planar residual. For a centred race
    /// (`s2 = 0`) at a steady whirl this is the residual unbalance `|m1 s1 + Σ m_j r e^{iψ_j}|
    /// / (m1 s1)`, a fraction of the unbalance as the spatial run's; 0 in the semi-balanced
    /// state (E on the axis, C whirling at `s2`). At rest ([`at_rest`]) no balancing measure:
    /// E's distance over its distance without the balls (`s2`), or over a length scale for a
    /// centred race (`s1 + s2 + n m3 r / m0`, [`stationary::race_offset_scale`]).
    pub residual_unbalance: f64,
    /// What the run ended in, decided by the spatial run's rule
    /// ([`crate::spatial::dynamics::RunOutcome`]): not settled (see `settled`, or the run stopped
    /// early); where no balanced or semi-balanced state exists at the final speed (the balls'
    /// capacity short of [`stationary::semi_balanced_demand`], or fewer than two balls)
    /// partially balanced when the balls ended together (their mean resultant at least 99 % of
    /// [`stationary::ball_capacity`]) with `residual_unbalance` within
    /// [`PARTIAL_TOLERANCE`](crate::spatial::dynamics::simulate::PARTIAL_TOLERANCE) of the
    /// bunched whirl's closed form ([`stationary::bunched_residual`]; `1 − n m3 r / (m1 s1)`
    /// for a centred race) and both below 1 (a residual of 1 or more: the race centre no
    /// nearer the axis than without the balls), else not balanced; else balanced (with an
    /// eccentric race: the semi-balanced state, E on the axis) with `residual_unbalance` at most
    /// [`stationary::balance_allowance`] (5 % of the residual's reference; on supports that
    /// differ by direction of it or of `s2`, the smaller), else not balanced. On supports that
    /// differ by direction with an eccentric race and two balls or more (no closed form for
    /// either question) the end state alone decides: balanced within the allowance, else
    /// partially balanced where the balls ended together with the residual below 1, else not
    /// balanced.
    /// Without balls, or at rest (final speed below [`REST_FRACTION`] of `sqrt(k/m0)`), not
    /// balanced.
    pub outcome: crate::spatial::dynamics::RunOutcome,
    /// Whether the motion had settled at the end: the whirl radius and the balls' angles change
    /// no faster (relative rate, 1/s) than the limit `3 |ω̇/ω| + 1e-4 sqrt(k/m0)`, i.e.
    /// quasi-statically. Where the run turned at least two revolutions near its end (its last
    /// eight at the speed of the moment) this is asked of the means over a revolution (from the
    /// dense output at 32 angles a revolution), as the spatial run does: the balls' mean angles over the last
    /// revolution differ from those over the one before by at most the limit times the period
    /// `2π/|ω|`, and C's mean position in rotor axes by at most that times the radius (or the
    /// balance tolerance of `balanced` where the radius is smaller), so that a periodic orbit
    /// (supports that differ by direction) settles; in a shorter run of the rates at the end.
    pub settled: bool,
    /// Whether `residual_unbalance` is a mean over the run's last revolution; `false` where no
    /// revolution was recorded (the run turned less than one, or stopped early: Ctrl-C, a step
    /// or wall budget, before its last revolutions) and it is the end state's.
    pub averaged: bool,
    /// Integrator steps (accepted).
    pub steps: u64,
    /// Of which by the implicit method.
    pub implicit_steps: u64,
    /// Switches between the explicit and the implicit method.
    pub switches: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Right-hand-side evaluations (including dense output).
    pub rhs_evaluations: u64,
    /// Ball–ball contacts that began (real balls with `planar.contact`; counted between step
    /// ends, so a contact that begins and ends inside one step is not counted).
    pub contacts: u64,
    /// Transitions of the balls between sticking (`|ψ̇| ≤ 10 planar.slip_rate`) and slipping
    /// (with `planar.rolling_resistance`), all balls together.
    pub stick_slip_transitions: u64,
    /// End time reached (s).
    pub t_end: f64,
    /// How the run ended (typed; `stopped` says it in words).
    #[serde(skip)]
    pub status: Status,
    /// Why the run stopped before `t_end`, if it did (e.g. "interrupted at t = …").
    pub stopped: Option<String>,
    /// Where the run did not do what it evidently was meant to (a passage that never reaches
    /// resonance, a run that ends before the motion settled), one sentence each.
    pub warnings: Vec<String>,
}

impl Summary {
    /// The summary if the run reached `t_end`, else its early stop as a typed error
    /// ([`crate::simulation::status_result`]): [`Error::Interrupted`] with the time reached for
    /// a cancel callback or a sink that returned `false`, [`Error::TooManySteps`] for a spent
    /// step budget, and so on. `simulate` itself returns the partial summary (what was
    /// computed, with [`Summary::status`] saying why it ended), never a silent success.
    ///
    /// ```
    /// use autobal::error::Error;
    /// use autobal::planar::{simulate, Drive, PlanarRotor, Settings};
    /// let rotor = PlanarRotor::paper();
    /// let drive = Drive::Acceleration { omega0: 200.0, b: 20.0 };
    /// let settings = Settings::new(&rotor, 15.0);
    /// // a sink that stops at its tenth sample (t = 9 dt): an interruption at the time the
    /// // integrator had reached then
    /// let mut seen = 0;
    /// let s = simulate(&rotor, &drive, &settings, |_| { seen += 1; seen < 10 }).unwrap();
    /// assert!(!s.status.is_completed());
    /// match s.into_result() {
    ///     Err(Error::Interrupted { t }) => assert!(t >= 9.0 * settings.dt && t < 10.0 * settings.dt, "{t}"),
    ///     other => panic!("{other:?}"),
    /// }
    /// // a step budget too small for the run
    /// let tight = Settings { max_steps: 20, ..settings.clone() };
    /// let s = simulate(&rotor, &drive, &tight, |_| true).unwrap();
    /// assert!(matches!(s.into_result(), Err(Error::TooManySteps { .. })));
    /// // a complete run passes through
    /// assert!(simulate(&rotor, &drive, &settings, |_| true).unwrap().into_result().is_ok());
    /// ```
    pub fn into_result(self) -> Result<Self> {
        crate::simulation::status_result(&self.status, self.t_end).map(|()| self)
    }
}

/// The sample at `(t, y)` into `out` (its ball angles' allocation reused from sample to sample).
fn sample_into(rotor: &PlanarRotor, drive: &Drive, t: f64, y: &[f64], out: &mut Sample) {
    let nc = 3 + rotor.n;
    let omega = if drive.prescribed() { drive.kinematics(t).0 } else { y[nc + 2] };
    let (s, c) = y[2].sin_cos();
    let x = y[0] * c - y[1] * s;
    let yy = y[0] * s + y[1] * c;
    (out.t, out.omega, out.theta, out.x, out.y, out.amplitude) = (t, omega, y[2], x, yy, y[0].hypot(y[1]));
    out.psi.clear();
    out.psi.extend_from_slice(&y[3..3 + rotor.n]);
}

/// Initial state from the drive and settings: C at `xy0` with velocity `xy_rate0` (fixed axes,
/// `θ = 0`: `u = X + iY`, `u̇ = Ż − iω0 u`), balls as set, speed `ω0`.
pub fn initial_state(rotor: &PlanarRotor, drive: &Drive, settings: &Settings) -> Vec<f64> {
    let nc = 3 + rotor.n;
    let mut y = vec![0.0; 2 * nc];
    let w0 = drive.omega0();
    let [x0, y0] = settings.xy0;
    let [vx, vy] = settings.xy_rate0;
    y[0] = x0;
    y[1] = y0;
    y[nc] = vx + w0 * y0;
    y[nc + 1] = vy - w0 * x0;
    for j in 0..rotor.n {
        y[3 + j] = settings.psi0[j];
        y[nc + 3 + j] = settings.psi_rate0[j];
    }
    y[nc + 2] = w0;
    y
}

/// Integrator options for a run: the method and budgets of `settings`; absolute tolerances per
/// component, `atol` on displacements, `atol/s_ref` on angles (`s_ref = max(s1, s2, r, atol)`),
/// and the same times `ω_n` on rates; steps of the implicit method at most 4 output intervals
/// (its dense output is third order).
pub fn tolerances(rotor: &PlanarRotor, settings: &Settings) -> Options {
    let nc = 3 + rotor.n;
    let s_ref = rotor.s1.max(rotor.s2).max(rotor.r).max(settings.atol);
    let wn = rotor.natural_frequency();
    let mut atol = vec![1.0; 2 * nc];
    for i in 0..nc {
        let base = if i < 2 { settings.atol } else { settings.atol / s_ref };
        atol[i] = base;
        atol[nc + i] = base * wn;
        if i >= 3 {
            atol[nc + i] = rotor.balls.rate_tolerance(atol[nc + i]);
        }
    }
    let mut o = Options::new(settings.rtol, settings.atol).method(settings.method).atol_per_component(atol);
    o.h_max_implicit = 4.0 * settings.dt;
    o.max_steps = settings.max_steps;
    o.max_wall = settings.max_wall_s.map(std::time::Duration::from_secs_f64);
    o
}

/// Simulate; `sink` receives every sample (at multiples of `dt`) and may return `false` to
/// stop (an interruption): the summary then covers what was computed and says so.
pub fn simulate(rotor: &PlanarRotor, drive: &Drive, settings: &Settings, sink: impl FnMut(&Sample) -> bool) -> Result<Summary> {
    simulate_with(rotor, drive, settings, &crate::control::Control::none(), sink)
}

/// [`simulate`] under `control` (its cancel flag is asked before every integrator step, so a
/// run with few samples stops as promptly as any; its budget every few hundred steps): an early
/// stop is the summary's [`Summary::status`].
pub fn simulate_with(
    rotor: &PlanarRotor,
    drive: &Drive,
    settings: &Settings,
    control: &crate::control::Control,
    sink: impl FnMut(&Sample) -> bool,
) -> Result<Summary> {
    simulate_sampled(rotor, drive, settings, control, settings.dt, sink)
}

/// The run of [`simulate_with`] with samples only at its start and end, for its summary (sweeps,
/// batches): the same settings, `dt` included, so the same steps and the same summary as
/// [`simulate`] (`dt` is also the automatic method's time resolution, see [`tolerances`]).
///
/// ```
/// use autobal::control::Control;
/// use autobal::planar::{simulate, simulate_summary, Drive, PlanarRotor, Settings};
/// let rotor = PlanarRotor::default();
/// let drive = Drive::Acceleration { omega0: 0.0, b: 25.0 };
/// let settings = Settings { dt: 0.01, ..Settings::new(&rotor, 16.0) };
/// let full = simulate(&rotor, &drive, &settings, |_| true).unwrap();
/// let summary = simulate_summary(&rotor, &drive, &settings, &Control::none()).unwrap();
/// assert_eq!((summary.steps, summary.final_amplitude), (full.steps, full.final_amplitude));
/// ```
pub fn simulate_summary(rotor: &PlanarRotor, drive: &Drive, settings: &Settings, control: &crate::control::Control) -> Result<Summary> {
    simulate_sampled(rotor, drive, settings, control, settings.t_end, |_| true)
}

/// [`simulate_with`], sampling every `sample_dt` (the integrator's settings unchanged).
fn simulate_sampled(
    rotor: &PlanarRotor,
    drive: &Drive,
    settings: &Settings,
    control: &crate::control::Control,
    sample_dt: f64,
    mut sink: impl FnMut(&Sample) -> bool,
) -> Result<Summary> {
    rotor.validate()?;
    drive.validate()?;
    settings.validate(rotor)?;
    let eq = Equations::new(rotor, drive);
    let mut y = initial_state(rotor, drive, settings);
    let mut solver = Solver::new(&eq, tolerances(rotor, settings))?;
    solver.control(control);
    let nc = 3 + rotor.n;
    solver.add_event(RadiusMaximum { nc });
    let breakpoints = drive.breakpoints();
    let timeline = Timeline { t_end: settings.t_end, dt: sample_dt, breakpoints: &breakpoints };
    let recorder = PlanarRecorder { rotor, nc };
    let mut hooks = PlanarHooks {
        rotor,
        drive,
        sink: &mut sink,
        peak: Peak::new(drive.omega0()),
        speed: (f64::INFINITY, f64::NEG_INFINITY),
        nc,
        balls: eq.balls.as_ref().map(|f| (f, EventCounter::default())),
        sample: Sample { t: 0.0, omega: 0.0, theta: 0.0, x: 0.0, y: 0.0, amplitude: 0.0, psi: Vec::with_capacity(rotor.n) },
        window: RevolutionWindow::new(recorder.width(), settings.t_end),
        recorder,
    };
    let out = run(&mut solver, &mut y, &timeline, &mut hooks);
    let peak = hooks.peak;
    let speed_range = hooks.speed;
    let (contacts, stick_slip_transitions) = hooks.balls.as_ref().map_or((0, 0), |(_, c)| (c.contacts, c.stick_slip));
    let final_amp = y[0].hypot(y[1]);
    let final_omega = if drive.prescribed() { drive.kinematics(out.t).0 } else { y[nc + 2] };
    // settled: the whirl radius and the balls change no faster than the drive's speed does
    // (quasi-static) plus a floor of 1e-4 ω_n
    let mut f = vec![0.0; y.len()];
    eq.rhs(out.t, &y, &mut f);
    let w_dot = f[nc + 2];
    let rate_limit = 3.0 * if final_omega.abs() > 0.0 { (w_dot / final_omega).abs() } else { 0.0 } + 1e-4 * rotor.natural_frequency();
    let target = if rotor.s2 > 0.0 { rotor.s2 } else { 0.0 };
    let tolerance = if rotor.s2 > 0.0 { 0.05 * rotor.s2 } else { 0.05 * rotor.s1.max(1e-9) };
    // the radius's rate d|u|/dt = u·u̇/|u| relative to the radius, or to the balance tolerance
    // where the radius is smaller: a balanced whirl of 1e-18 m changing by 1e-20 m/s has
    // settled (relative to its own radius it would read as a fast change)
    let r_ref = final_amp.max(tolerance);
    let radius_rate = if final_amp > 0.0 { (y[0] * y[nc] + y[1] * y[nc + 1]).abs() / (final_amp * r_ref) } else { 0.0 };
    let rates_small = (0..rotor.n).all(|j| y[nc + 3 + j].abs() <= rate_limit);
    let completed = out.status.is_completed();
    // the residual and the balls' resultant averaged over the last revolution (the end state
    // where the run turned less), decided by the spatial run's rule
    let (last, previous) = (hooks.window.mean(0), hooks.window.mean(1));
    let settled = match (&last, &previous) {
        // the spatial run's rule with this run's rate limit: the balls' mean angles (and C's
        // mean position in rotor axes, relative to `r_ref`) drift from one revolution to the
        // next by at most the limit times the revolution's period; a periodic orbit's
        // instantaneous rates never vanish. (The spatial `drift_tolerance`, `1e-3 max(ω, ω_n)`
        // as a rate, is six times looser here and calls a run-up ending just past resonance,
        // the balls still slipping, settled.)
        (Some(a), Some(b)) => {
            let drift = rate_limit * std::f64::consts::TAU / final_omega.abs();
            let balls = (4..a.len()).all(|k| (a[k] - b[k]).abs() <= drift);
            balls && (a[0] - b[0]).hypot(a[1] - b[1]) <= drift * r_ref
        }
        _ => rates_small && radius_rate <= rate_limit,
    };
    let averaged = last.is_some();
    let [ex, ey, bx, by] = match last {
        Some(m) => [m[0], m[1], m[2], m[3]],
        None => {
            let b = stationary::ball_resultant(rotor, y[3..nc].iter().copied());
            [y[0], y[1], b[0], b[1]]
        }
    };
    let race = (rotor.s2 * rotor.gamma.cos(), rotor.s2 * rotor.gamma.sin());
    let residual_unbalance = (ex + race.0).hypot(ey + race.1) / stationary::race_offset_scale(rotor, final_omega);
    let capacity = stationary::ball_capacity(rotor);
    let together = crate::spatial::dynamics::simulate::together(bx.hypot(by), capacity);
    let allowance = stationary::balance_allowance(rotor, final_omega);
    // where the supports differ by direction the closed forms (the supports' means) say neither
    // whether the semi-balanced orbit exists (an eccentric race, two balls or more: the end
    // state decides, balanced within the allowance) nor what the bunched orbit leaves (there
    // the balls count as partially balancing where they ended together nearer the axis than no
    // balls would leave E, residual below 1), as `stability`'s state words
    // (`crate::rotor_stability::Rotor::classify`). A centred race's balanced state needs
    // `Σ m_j r ≥ m1 s1` whatever the supports, and one ball has no semi-balanced state: the
    // closed form's existence there
    let by_end_state = rotor.anisotropic() && rotor.s2 > 0.0 && rotor.n >= 2;
    let short = if by_end_state { residual_unbalance > allowance } else { !stationary::semi_balanced_exists(rotor, final_omega) };
    // at (or near) rest nothing turns the balls against the unbalance: no balanced or partially
    // balanced state to read (the semi-balanced demand and the residual's scale degenerate)
    let at_rest = at_rest(rotor, final_omega);
    let outcome = crate::spatial::dynamics::simulate::run_outcome(&crate::spatial::dynamics::simulate::Ending {
        balls: rotor.n > 0 && !at_rest,
        settled: settled && completed,
        short: short.then(|| {
            // the bunched whirl `stability` follows there (none in closed form: no residual to
            // compare, never partially balanced). The balls count as partially balancing only
            // where they bring the race centre nearer the axis than no balls would (residual
            // below 1), for either race, as `stability`'s state words
            // (`crate::rotor_stability::Rotor::state_kind`): with the race centred, below the
            // critical speed they join the unbalance (`≈ 1 + α`); with an eccentric one stuck
            // below resonance they can leave E further out than without them
            let least = if rotor.anisotropic() { residual_unbalance } else { stationary::bunched_residual(rotor, final_omega).unwrap_or(f64::INFINITY) };
            (least, together && least < 1.0 && residual_unbalance < 1.0)
        }),
        residual: residual_unbalance,
        residual_couple: None,
        tolerance: allowance,
        race_whirl_basis: false,
    });
    // the end checks (`crate::rotor_stability::end_checks`); this run's gate requires the run
    // completed as well (the outcome balanced or partially balanced implies it, not balanced
    // does not: no balls, or at rest); the end state in rotor axes already. (`w_dot` above is
    // the drive's `θ̈` itself where the speed is prescribed: the same gate as the other runs'.)
    let checks = crate::rotor_stability::end_checks(
        &crate::rotor_stability::Rotor::Planar(rotor.clone()),
        final_omega,
        true,
        completed && drive.constant_speed_at(out.t),
        outcome,
        settled,
        || Some(field::PlanarField::new(rotor, final_omega).ok()?.reduced_state(&y)),
    );
    let (outcome, settled) = (checks.outcome, checks.settled);
    // the radius test as well: C at s2 (or near the axis) where the outcome says balanced, by
    // C's mean position in rotor axes over the last revolution (the end state's where the run
    // turned less): the whirl's radius for a steady whirl; on supports that differ by
    // direction C's path is an ellipse whose radius swings about it twice a revolution
    let balanced = outcome == crate::spatial::dynamics::RunOutcome::Balanced && (ex.hypot(ey) - target).abs() <= tolerance;
    let stopped = match &out.status {
        Status::Completed => None,
        Status::Stopped(StopReason::Observer) => Some(format!("interrupted at t = {:.6} s", out.t)),
        _ => Some(format!("{out}").replace(&format!("t = {:.6}", out.t), &format!("t = {:.6} s", out.t))),
    };
    // (an overriding check's own warning says why the end is not settled: not also "raise
    // drive.t_end")
    let mut warnings = if completed { passage_warnings(rotor, drive, settings, speed_range, final_omega, settled || checks.warning.is_some()) } else { vec![] };
    warnings.extend(checks.warning);
    Ok(Summary {
        peak_amplitude: peak.value,
        omega_at_peak: peak.with,
        t_at_peak: peak.t,
        final_amplitude: final_amp,
        final_omega,
        balanced,
        residual_unbalance,
        outcome,
        settled,
        averaged,
        steps: out.stats.steps,
        implicit_steps: out.stats.implicit_steps,
        switches: out.stats.switches,
        rejected_steps: out.stats.rejected,
        rhs_evaluations: out.stats.rhs_evaluations,
        contacts,
        stick_slip_transitions,
        t_end: out.t,
        status: out.status,
        stopped,
        warnings,
    })
}

/// Where a completed run did not do what its drive evidently asked: a run-up (or run-down)
/// that never reaches `sqrt(k/m0)`, a run that ends before the motion settled.
fn passage_warnings(rotor: &PlanarRotor, drive: &Drive, settings: &Settings, (w_min, w_max): (f64, f64), final_omega: f64, settled: bool) -> Vec<String> {
    let wn = rotor.natural_frequency();
    let mut w = vec![];
    let passage = match drive {
        Drive::Acceleration { omega0, b } => Some((*omega0, *b)),
        Drive::Torque { omega0, torque, .. } | Drive::Motor { omega0, torque, .. } => Some((*omega0, *torque)),
        _ => None,
    };
    if let Some((w0, sense)) = passage {
        if sense > 0.0 && w0.abs() < wn && w_max < wn {
            let hint = match drive {
                // (b and t_end through fmt_num: `{}` wrote b = 1e-300 with 300 zeros, hunt 27)
                Drive::Acceleration { b, .. } => {
                    format!("; at b = {} it gets there at t = {:.4e} s: raise drive.t_end", crate::error::fmt_num(*b), (wn - w0) / b)
                }
                _ => " (the torque cannot pass it, or drive.t_end is too short)".to_string(),
            };
            w.push(format!(
                "resonance was never reached: the speed stays below sqrt(k/m0) = {wn:.2} rad/s (at most {w_max:.2} rad/s by t = {} s){hint}",
                crate::error::fmt_num(settings.t_end)
            ));
        }
        if sense < 0.0 && w0.abs() > wn && w_min > wn {
            w.push(format!("resonance was never reached: the run-down ends at {final_omega:.2} rad/s, above sqrt(k/m0) = {wn:.2} rad/s: raise drive.t_end"));
        }
    }
    if !settled {
        w.push(format!(
            "the run ends before the motion settled (at {final_omega:.2} rad/s the balls still move relative to the rotor or the whirl is still changing): final_amplitude and balanced describe no stationary state: a transient (raise drive.t_end) or balls circulating round the race"
        ));
    }
    w
}

/// `g = u·u̇ = ½ d|u|²/dt` falling through zero: a maximum of the whirl radius, located on the
/// dense output so the peak is as accurate as the integration, not as coarse as the steps.
struct RadiusMaximum {
    nc: usize,
}

impl Event for RadiusMaximum {
    fn g(&self, _t: f64, y: &[f64]) -> f64 {
        y[0] * y[self.nc] + y[1] * y[self.nc + 1]
    }
    fn direction(&self) -> Direction {
        Direction::Falling
    }
    fn terminal(&self) -> bool {
        false
    }
}

/// What `simulate` does during the run: keep the prescribed speed on its schedule at each piece,
/// track the peak and the speed range, emit the samples.
struct PlanarHooks<'a, F: FnMut(&Sample) -> bool> {
    rotor: &'a PlanarRotor,
    drive: &'a Drive,
    sink: &'a mut F,
    peak: Peak<f64>,
    speed: (f64, f64),
    nc: usize,
    balls: Option<(&'a BallForces, EventCounter)>,
    /// The sample handed to the sink, refilled at each sample time.
    sample: Sample,
    /// The last two revolutions from the dense output, for the summary's averages.
    window: RevolutionWindow,
    /// What the window records.
    recorder: PlanarRecorder<'a>,
}

/// What the planar run's summary averages over its last revolutions
/// ([`crate::simulation::RevolutionWindow`], on the grid of the rotor angle `θ`, weights
/// `1/|θ̇|`): per record the shaft point C in rotor axes `u` (2), the balls' resultant
/// `Σ m_j r e^{iψ_j}` in rotor axes (2, that of the record's angles) and the ball angles
/// `ψ_j` (`n`).
struct PlanarRecorder<'a> {
    rotor: &'a PlanarRotor,
    /// Coordinates (the index of `θ̇` is `nc + 2`).
    nc: usize,
}

impl PlanarRecorder<'_> {
    /// Values per record.
    fn width(&self) -> usize {
        4 + self.rotor.n
    }
}

impl crate::simulation::Recorder for PlanarRecorder<'_> {
    fn spin(&self, _t: f64, y: &[f64]) -> (f64, f64) {
        (y[2], y[self.nc + 2])
    }

    fn record(&self, _t: f64, y: &[f64], out: &mut [f64]) {
        let b = stationary::ball_resultant(self.rotor, y[3..self.nc].iter().copied());
        out[..4].copy_from_slice(&[y[0], y[1], b[0], b[1]]);
        out[4..].copy_from_slice(&y[3..self.nc]);
    }
}

/// The fraction of `sqrt(k/m0)` below which a run's final speed counts as rest: its outcome is
/// then not balanced (nothing turns the balls against the unbalance; the semi-balanced demand
/// grows as `k s2 / ω²` and has no limit at rest).
pub const REST_FRACTION: f64 = 1e-3;

/// Whether the speed `omega` counts as rest for `rotor`: `|ω|` below [`REST_FRACTION`] of
/// `sqrt(k/m0)` (or not a number). A run that ends there is not balanced and its
/// [`Summary::residual_unbalance`] is no balancing measure (nothing turns the balls against the
/// unbalance): the race centre's distance from the axis over a length scale.
pub fn at_rest(rotor: &PlanarRotor, omega: f64) -> bool {
    !(omega.abs() >= REST_FRACTION * rotor.natural_frequency())
}

impl<F: FnMut(&Sample) -> bool> Hooks for PlanarHooks<'_, F> {
    fn start_piece(&mut self, t: f64, y: &mut [f64]) {
        if self.drive.prescribed() {
            y[self.nc + 2] = self.drive.kinematics(t).0; // start each piece exactly on the schedule
        }
    }

    fn dense_step(&mut self, t_old: f64, t_new: f64, y_old: &[f64], y_new: &[f64], interpolate: &mut dyn FnMut(f64, &mut [f64])) {
        self.window.dense_step(&self.recorder, t_old, t_new, y_old, y_new, interpolate);
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let w = if self.drive.prescribed() { self.drive.kinematics(t).0 } else { y[self.nc + 2] };
        self.peak.observe(y[0].hypot(y[1]), t, w);
        self.speed = (self.speed.0.min(w), self.speed.1.max(w));
        if let Some((f, counter)) = &mut self.balls {
            counter.observe(f, &y[3..self.nc], &y[self.nc + 3..2 * self.nc]);
        }
    }

    fn event(&mut self, _index: usize, t: f64, y: &[f64]) {
        let w = if self.drive.prescribed() { self.drive.kinematics(t).0 } else { y[self.nc + 2] };
        self.peak.observe(y[0].hypot(y[1]), t, w);
    }

    fn sample(&mut self, t: f64, y: &[f64]) -> Control {
        sample_into(self.rotor, self.drive, t, y, &mut self.sample);
        let s = &self.sample;
        self.peak.observe(s.amplitude, t, s.omega);
        self.speed = (self.speed.0.min(s.omega), self.speed.1.max(s.omega));
        if (self.sink)(s) {
            Control::Continue
        } else {
            Control::Stop
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The never-reached warning writes `b` and `t_end` as numbers are written in messages
    /// (`fmt_num`): `b = 1e-300` was 302 characters of `0.000…1` (hunt 27).
    #[test]
    fn the_never_reached_warning_writes_a_tiny_acceleration_as_a_number() {
        let rotor = PlanarRotor::paper();
        let drive = Drive::Acceleration { omega0: 0.0, b: 1e-300 };
        let w = passage_warnings(&rotor, &drive, &Settings::new(&rotor, 0.5), (0.0, 5e-301), 5e-301, true);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].contains("by t = 0.5 s); at b = 1e-300 it gets there at t = "), "{}", w[0]);
        assert!(w[0].len() < 250, "{}", w[0]);
    }
}
