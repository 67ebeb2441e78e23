//! Time simulation of the spatial rotor: initial conditions, samples at a fixed interval from
//! the dense output, peak tracking and the end-of-run verdict (balanced or not).

use super::equations::{Equations, PHI, ROTOR_COORDS};
use super::rotor::SpatialRotor;
use crate::balls::EventCounter;
use crate::drive::Drive;
use crate::error::{finite, positive, Error, Result};
use crate::ode::{Control, Method, Options, Outcome, Solver, Stats, Status};
use crate::simulation::{run, Hooks, Timeline};
use serde::Serialize;

/// Initial conditions (velocities in fixed axes; at `t = 0` the turning frame coincides with
/// the fixed one).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Initial {
    /// Lateral position `(x, y)` of the reference point C (m).
    pub position: [f64; 2],
    /// Its velocity `(ẋ, ẏ)` (m/s).
    pub velocity: [f64; 2],
    /// Tilt `(δ, θ)`: rotations about the x and y axes (rad).
    pub tilt: [f64; 2],
    /// Tilt rates about the fixed x and y axes (rad/s).
    pub tilt_rate: [f64; 2],
    /// Ball angles from the body x axis (the unbalance direction of the analytic models),
    /// all planes in order (rad).
    pub psi: Vec<f64>,
    /// Ball rates relative to the rotor (rad/s).
    pub psi_rate: Vec<f64>,
}

impl Initial {
    /// At rest on the axis, balls of each plane spread evenly across the unbalance
    /// (`ψ = π/2 + 2π j/n`: no net ball unbalance).
    pub fn at_rest(rotor: &SpatialRotor) -> Self {
        let psi: Vec<f64> =
            rotor.planes.iter().flat_map(|p| (0..p.n).map(move |j| std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * j as f64 / p.n as f64)).collect();
        let n = psi.len();
        Initial { position: [0.0; 2], velocity: [0.0; 2], tilt: [0.0; 2], tilt_rate: [0.0; 2], psi, psi_rate: vec![0.0; n] }
    }
}

/// Integration settings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Settings {
    /// The integrator.
    pub method: Method,
    /// End time (s, or `τ` in the papers' units).
    pub t_end: f64,
    /// Output interval; also the time resolution of the automatic and implicit methods (implicit
    /// steps of at most `4 dt`, see [`tolerances`]); samples are read from the dense output.
    pub dt: f64,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on displacements (m, or `ρ_s`); angles scaled by the race radius,
    /// rates by the natural frequency.
    pub atol: f64,
}

impl Settings {
    /// Validate (errors name `drive.t_end` or `integration.<field>`).
    pub fn validate(&self) -> Result<()> {
        positive("drive.t_end", self.t_end)?;
        positive("integration.dt", self.dt)?;
        if self.t_end / self.dt > 5e7 {
            return Err(Error::invalid("integration.dt", format!("{} samples is too many; raise dt", self.t_end / self.dt)));
        }
        positive("integration.rtol", self.rtol)?;
        positive("integration.atol", self.atol)?;
        if self.rtol < 1e-14 {
            return Err(Error::invalid("integration.rtol", "below 1e-14 the step cannot reach it in double precision"));
        }
        Ok(())
    }
}

/// One output sample.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// Spin rate `φ̇`.
    pub omega: f64,
    /// `x`, `y` of C in fixed axes.
    pub x: f64,
    /// `y` of C.
    pub y: f64,
    /// Tilt about the fixed x axis.
    pub tilt_x: f64,
    /// Tilt about the fixed y axis.
    pub tilt_y: f64,
    /// Whirl radius of the shaft at each support.
    pub amplitude_supports: Vec<f64>,
    /// Whirl radius of the shaft at each balancer plane (at the first unbalance plane when
    /// there are no balls).
    pub amplitude_planes: Vec<f64>,
    /// Ball angles relative to the rotor, all planes in order.
    pub psi: Vec<f64>,
}

/// Summary of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Largest whirl radius at the (first) balancer plane, at step ends and samples.
    pub peak_amplitude: f64,
    /// Spin rate at that moment.
    pub omega_at_peak: f64,
    /// Time of the peak.
    pub t_at_peak: f64,
    /// Whirl radius at the (first) balancer plane at the end.
    pub final_amplitude: f64,
    /// Spin rate at the end.
    pub final_omega: f64,
    /// Static unbalance of unbalance masses and balls at the end, relative to the unbalance
    /// masses' own (relative to the balls' capacity `Σ m R` when there is none).
    pub residual_unbalance: f64,
    /// Couple unbalance about C at the end relative to the unbalance's own couple (tilted axis
    /// included); `None` when the unbalance has no couple.
    pub residual_couple: Option<f64>,
    /// Whether the balls ended at rest relative to the rotor with the residual static (and
    /// couple) unbalance below 5 % of the unbalance's.
    pub balanced: bool,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Right-hand-side evaluations (dense output included).
    pub rhs_evaluations: u64,
    /// Ball–ball contacts that began, all planes together (real balls with contact; counted
    /// between step ends, [`crate::balls::EventCounter`]).
    pub contacts: u64,
    /// Transitions of the balls between sticking and slipping (real balls with rolling
    /// resistance), all planes together.
    pub stick_slip_transitions: u64,
    /// Time reached.
    pub t_end: f64,
    /// How the run ended (typed; `stopped` says it in words).
    #[serde(skip)]
    pub status: Status,
    /// Why the run stopped before `t_end`, if it did.
    pub stopped: Option<String>,
}

impl Summary {
    /// The summary if the run reached `t_end`, else its early stop as a typed error
    /// ([`crate::simulation::status_result`]: [`crate::Error::Interrupted`] with the time
    /// reached, [`crate::Error::TooManySteps`], …).
    pub fn into_result(self) -> Result<Self> {
        crate::simulation::status_result(&self.status, self.t_end).map(|()| self)
    }
}

/// The state vector of an initial condition (turning-frame coordinates at `t = 0`).
pub fn initial_state(eq: &Equations, init: &Initial) -> Result<Vec<f64>> {
    let nc = eq.coords();
    let nb = nc - ROTOR_COORDS;
    if init.psi.len() != nb {
        return Err(Error::invalid("drive.psi0", format!("needs {nb} angles (all balls of all planes), got {}", init.psi.len())));
    }
    if init.psi_rate.len() != nb {
        return Err(Error::invalid("drive.psi_rate0", format!("needs {nb} rates, got {}", init.psi_rate.len())));
    }
    for (name, v) in
        [("initial.position", init.position), ("initial.velocity", init.velocity), ("initial.tilt", init.tilt), ("initial.tilt_rate", init.tilt_rate)]
    {
        finite(name, v[0])?;
        finite(name, v[1])?;
    }
    for a in &init.psi {
        finite("drive.psi0", *a)?;
    }
    for a in &init.psi_rate {
        finite("drive.psi_rate0", *a)?;
    }
    let mut first = 0;
    for p in &eq.rotor.planes {
        p.physics.check_initial("drive.psi0", p.ball_mass, p.race_radius, &init.psi[first..first + p.n])?;
        first += p.n;
    }
    if eq.rotor.lock_tilt && (init.tilt != [0.0; 2] || init.tilt_rate != [0.0; 2]) {
        return Err(Error::invalid("initial.tilt", "must be zero with the tilt locked (spatial.lock_tilt)"));
    }
    let w = eq.drive.omega0();
    let [x, y] = init.position;
    let [d, th] = init.tilt;
    let mut s = vec![0.0; 2 * nc];
    s[0] = x;
    s[1] = y;
    s[2] = d;
    s[3] = th;
    // rates in the turning frame: u̇ = v − ω e_z × u, χ̇ = χ̇_fixed − ω e_z × χ
    s[nc] = init.velocity[0] + w * y;
    s[nc + 1] = init.velocity[1] - w * x;
    s[nc + 2] = init.tilt_rate[0] + w * th;
    s[nc + 3] = init.tilt_rate[1] - w * d;
    s[nc + PHI] = w;
    for j in 0..nb {
        s[ROTOR_COORDS + j] = init.psi[j];
        s[nc + ROTOR_COORDS + j] = init.psi_rate[j];
    }
    Ok(s)
}

/// Absolute tolerances per component: `atol` on displacements, `atol/L` on angles (`L` the
/// largest race or unbalance radius), times the natural frequency on rates.
pub fn tolerances(eq: &Equations, settings: &Settings) -> Options {
    let nc = eq.coords();
    let l = eq.rotor.length_scale().max(settings.atol);
    let wn = eq.rotor.natural_frequency();
    let mut atol = vec![1.0; 2 * nc];
    for i in 0..nc {
        let base = if i < 2 { settings.atol } else { settings.atol / l };
        atol[i] = base;
        atol[nc + i] = base * wn;
    }
    // ball rates of planes with rolling resistance: resolve its regularised sign
    let mut i = nc + ROTOR_COORDS;
    for p in &eq.rotor.planes {
        for _ in 0..p.n {
            atol[i] = p.physics.rate_tolerance(atol[i]);
            i += 1;
        }
    }
    let mut o = Options::new(settings.rtol, settings.atol).method(settings.method).atol_per_component(atol);
    // the implicit method's dense output is third order: steps of at most 4 output intervals
    o.h_max_implicit = 4.0 * settings.dt;
    o.max_steps = 200_000_000;
    o
}

/// The sample of a state.
pub fn sample_of(eq: &Equations, t: f64, y: &[f64]) -> Sample {
    let nc = eq.coords();
    let r = eq.rotor;
    let c = eq.displacement_at(y, eq.z_reference());
    let (sp, cp) = y[PHI].sin_cos();
    let planes: Vec<f64> = if r.planes.is_empty() {
        r.unbalances.first().map(|u| eq.displacement_at(y, u.z)).into_iter().map(|d| d[0].hypot(d[1])).collect()
    } else {
        r.planes.iter().map(|p| eq.displacement_at(y, p.z)).map(|d| d[0].hypot(d[1])).collect()
    };
    Sample {
        t,
        omega: eq.spin_rate(t, y),
        x: c[0],
        y: c[1],
        tilt_x: cp * y[2] - sp * y[3],
        tilt_y: sp * y[2] + cp * y[3],
        amplitude_supports: r.supports.iter().map(|s| eq.displacement_at(y, s.z)).map(|d| d[0].hypot(d[1])).collect(),
        amplitude_planes: planes,
        psi: y[ROTOR_COORDS..nc].to_vec(),
    }
}

fn plane_amplitude(eq: &Equations, y: &[f64]) -> f64 {
    let z = eq.rotor.planes.first().map(|p| p.z).or_else(|| eq.rotor.unbalances.first().map(|u| u.z)).unwrap_or(eq.z_reference());
    let d = eq.displacement_at(y, z);
    d[0].hypot(d[1])
}

/// Simulate from `init`; `sink` receives every sample (at multiples of `dt`) and may return
/// `false` to stop (an interruption): the summary then covers what was computed.
///
/// ```
/// use autobal::drive::Drive;
/// use autobal::spatial::dynamics::{simulate, Initial, Settings, SpatialRotor};
/// use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
/// use autobal::spatial::inertia::AnisotropyMethod;
/// // paper 000's base case at Ω = 1.6, inside the exactly stable range
/// let model = SpatialModel::from_dimensionless(&DimensionlessInput {
///     c_sigma: 0.75, rho_s: 0.4, l_left: 0.8, z_a: 0.8,
///     anisotropy: AnisotropyInput::Masses { masses: MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 }, d_a: None },
///     h_x: 0.05, h_s: 0.1, method: AnisotropyMethod::Exact, direct_balls: None,
/// }).unwrap();
/// let rotor = SpatialRotor::from_dimensionless(&model).unwrap();
/// let drive = Drive::Speed { omega0: 1.6 };
/// let settings = Settings { method: Default::default(), t_end: 3000.0, dt: 10.0, rtol: 1e-8, atol: 1e-9 };
/// let s = simulate(&rotor, &drive, &Initial::at_rest(&rotor), &settings, |_| true).unwrap();
/// assert!(s.balanced && s.residual_unbalance < 1e-3);
/// ```
pub fn simulate(rotor: &SpatialRotor, drive: &Drive, init: &Initial, settings: &Settings, sink: impl FnMut(&Sample) -> bool) -> Result<Summary> {
    simulate_sampled(rotor, drive, init, settings, None, settings.dt, sink)
}

/// The run of [`simulate`] with samples only at its start and end, for its summary (basins):
/// the same settings, `dt` included, so the same steps and the same summary (`dt` is also the
/// automatic method's time resolution, see [`tolerances`]). `cancel` is asked before every
/// step; `true` stops the run (an interruption, as in [`simulate`]), as in
/// [`crate::planar::simulate_summary`].
pub fn simulate_summary(rotor: &SpatialRotor, drive: &Drive, init: &Initial, settings: &Settings, cancel: Option<&dyn Fn() -> bool>) -> Result<Summary> {
    simulate_sampled(rotor, drive, init, settings, cancel, settings.t_end, |_| true)
}

/// [`simulate`], stopping when `cancel()` returns true and sampling every `sample_dt` (the
/// integrator's settings unchanged).
fn simulate_sampled(
    rotor: &SpatialRotor,
    drive: &Drive,
    init: &Initial,
    settings: &Settings,
    cancel: Option<&dyn Fn() -> bool>,
    sample_dt: f64,
    mut sink: impl FnMut(&Sample) -> bool,
) -> Result<Summary> {
    rotor.validate()?;
    drive.validate()?;
    settings.validate()?;
    let eq = Equations::new(rotor, drive);
    let mut y = initial_state(&eq, init)?;
    let mut solver = Solver::new(&eq, tolerances(&eq, settings))?;
    if let Some(c) = cancel {
        solver.cancel_if(c);
    }
    let breakpoints = drive.breakpoints();
    let timeline = Timeline { t_end: settings.t_end, dt: sample_dt, breakpoints: &breakpoints };
    let counters = vec![EventCounter::default(); eq.ball_forces().len()];
    let mut hooks = SpatialHooks { eq: &eq, sink: &mut sink, peak: (plane_amplitude(&eq, &y), drive.omega0(), 0.0), counters };
    let out = run(&mut solver, &mut y, &timeline, &mut hooks);
    let peak = hooks.peak;
    let mut s = summarise(&eq, out.t, &y, peak, out.stats, &out);
    s.contacts = hooks.counters.iter().map(|c| c.contacts).sum();
    s.stick_slip_transitions = hooks.counters.iter().map(|c| c.stick_slip).sum();
    Ok(s)
}

/// Peak tracking at step ends and samples, the prescribed spin put back on its schedule at
/// each piece, samples to the sink, real balls' contacts and stick-slip counted per plane.
struct SpatialHooks<'a, F: FnMut(&Sample) -> bool> {
    eq: &'a Equations<'a>,
    sink: &'a mut F,
    peak: (f64, f64, f64),
    counters: Vec<EventCounter>,
}

impl<F: FnMut(&Sample) -> bool> Hooks for SpatialHooks<'_, F> {
    fn start_piece(&mut self, t: f64, y: &mut [f64]) {
        if self.eq.drive.prescribed() {
            y[self.eq.coords() + PHI] = self.eq.drive.kinematics(t).0;
        }
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let a = plane_amplitude(self.eq, y);
        if a > self.peak.0 {
            self.peak = (a, self.eq.spin_rate(t, y), t);
        }
        let nc = self.eq.coords();
        for ((first, f), c) in self.eq.ball_forces().iter().zip(&mut self.counters) {
            let a = ROTOR_COORDS + first;
            c.observe(f, &y[a..a + f.n], &y[nc + a..nc + a + f.n]);
        }
    }

    fn sample(&mut self, t: f64, y: &[f64]) -> Control {
        let s = sample_of(self.eq, t, y);
        let a = plane_amplitude(self.eq, y);
        if a > self.peak.0 {
            self.peak = (a, s.omega, t);
        }
        if (self.sink)(&s) {
            Control::Continue
        } else {
            Control::Stop
        }
    }
}

fn summarise(eq: &Equations, t: f64, y: &[f64], peak: (f64, f64, f64), stats: Stats, out: &Outcome) -> Summary {
    let nc = eq.coords();
    let r = eq.rotor;
    let omega = eq.spin_rate(t, y);
    let (st, cp) = eq.residual_unbalance(y);
    let (s0, c0) = (r.static_unbalance(), r.couple_unbalance());
    let capacity: f64 = r.planes.iter().map(|p| p.n as f64 * p.ball_mass * p.race_radius).sum();
    let s0n = s0[0].hypot(s0[1]);
    let residual_unbalance = st[0].hypot(st[1]) / if s0n > 0.0 { s0n } else { capacity.max(f64::MIN_POSITIVE) };
    let c0n = c0[0].hypot(c0[1]);
    let residual_couple = (c0n > 1e-12 * (s0n * r.length_scale()).max(f64::MIN_POSITIVE)).then(|| cp[0].hypot(cp[1]) / c0n);
    let wn = r.natural_frequency();
    let at_rest = (ROTOR_COORDS..nc).all(|i| y[nc + i].abs() < 1e-3 * omega.abs().max(wn));
    let balanced = r.balls() > 0 && at_rest && residual_unbalance <= 0.05 && !matches!(residual_couple, Some(c) if c > 0.05);
    Summary {
        peak_amplitude: peak.0,
        omega_at_peak: peak.1,
        t_at_peak: peak.2,
        final_amplitude: plane_amplitude(eq, y),
        final_omega: omega,
        residual_unbalance,
        residual_couple,
        balanced,
        steps: stats.steps,
        rejected_steps: stats.rejected,
        rhs_evaluations: stats.rhs_evaluations,
        contacts: 0,
        stick_slip_transitions: 0,
        t_end: t,
        stopped: match &out.status {
            Status::Completed => None,
            Status::Stopped => Some(format!("interrupted at t = {}", crate::error::fmt_num(t))),
            _ => Some(out.to_string()),
        },
        status: out.status.clone(),
    }
}
