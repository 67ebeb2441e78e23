//! Time simulation of the spatial rotor: initial conditions, samples at a fixed interval from
//! the dense output, peak tracking and the end-of-run verdict (balanced or not).

use super::equations::{Equations, PHI, ROTOR_COORDS};
use super::rotor::SpatialRotor;
use crate::balls::EventCounter;
use crate::drive::Drive;
use crate::error::{finite, positive, Error, Result};
use crate::ode::{Control, Method, Options, Outcome, Solver, Stats, Status, StopReason};
use crate::simulation::{run, Hooks, RevolutionWindow, Timeline};
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
            return Err(Error::invalid("integration.dt", format!("{} samples is too many; raise dt", crate::error::fmt_num(self.t_end / self.dt))));
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
    /// Largest distance from the axis `|r|` of the shaft at the (first) balancer plane (a sag
    /// included), at step ends and samples.
    pub peak_amplitude: f64,
    /// Spin rate at that moment.
    pub omega_at_peak: f64,
    /// Time of the peak.
    pub t_at_peak: f64,
    /// Whirl radius at the (first) balancer plane about its stationary position: the RMS over
    /// the run's last revolution of `|r(t) − r̄|`, `r` the shaft's displacement there in fixed
    /// axes and `r̄` its mean over that revolution ([`Summary::mean_displacement`]); a circular
    /// whirl of radius `a` about `r̄` gives `a`. The distance from the axis at the end where no
    /// revolution was recorded (the run turned less than one, or stopped before its last
    /// revolutions). The means over a revolution come from the dense output at 32 spin angles
    /// (`crate::simulation::RevolutionWindow`): those of the periodic stationary motion
    /// wherever in the revolution the run ends.
    pub final_amplitude: f64,
    /// Mean lateral displacement `r̄ = (1/T) ∫ r dt` of the shaft at the (first) balancer plane
    /// in fixed axes over the last revolution (m, or `ρ_s`): the stationary motion without the
    /// whirl, e.g. the sag under gravity across the axis (`≈ M g / Σ k`). `None` when the run
    /// recorded no revolution: there is none to average over (it read `[0, 0]`
    /// before round 3, session 18).
    pub mean_displacement: Option<[f64; 2]>,
    /// `|r̄|`, the static sag at the (first) balancer plane (see [`Summary::mean_displacement`]),
    /// where it is one: the run turned at least a revolution (a mean was taken) and settled
    /// (the stationary motion's mean position; under gravity across the axis
    /// [`SpatialRotor::gravity_across`] the sag it causes, `≈ M g / Σ k`). `None` otherwise:
    /// a run that did not settle has no sag to measure, its last revolution's mean
    /// displacement is the transient's (until session 29 it was reported under gravity
    /// anyway: 0.969 mm on a run whose settled sag is 0.079 mm).
    pub static_sag: Option<f64>,
    /// Spin rate at the end.
    pub final_omega: f64,
    /// Static unbalance of unbalance masses and balls, rotor frame, averaged over the last
    /// revolution (`|(1/T) ∫ Σ m ρ_⊥ dt|`), relative to the unbalance masses' own; relative to
    /// the balls' capacity `Σ m R` where that is at most
    /// [`crate::rotor_stability::NO_UNBALANCE`] of the capacity (none to speak of, as
    /// `stability` measures its residuals). At the end where no revolution was recorded.
    pub residual_unbalance: f64,
    /// Couple unbalance about C relative to the unbalance's own couple (tilted axis included),
    /// averaged over the last revolution as `residual_unbalance`; `None` when the unbalance has
    /// no couple: none beside its static unbalance (at most `1e-12` of it times the length
    /// scale), or the rotor has no unbalance at all
    /// ([`crate::rotor_stability::Rotor::has_unbalance`]: static and couple at round-off).
    pub residual_couple: Option<f64>,
    /// The largest change of a ball's mean angle (its average over a revolution, relative to
    /// the rotor) between the last two revolutions (rad); `None` without balls or when the run
    /// recorded less than two revolutions.
    pub ball_drift: Option<f64>,
    /// Whether `final_amplitude`, `residual_unbalance` and `residual_couple` are means over the
    /// run's last revolution; `false` where no revolution was recorded (the run turned less
    /// than one, or stopped early: Ctrl-C, a step or wall budget, before its last revolutions)
    /// and they are the end state's.
    pub averaged: bool,
    /// What the run ended in ([`RunOutcome`]): balanced, partially balanced, not balanced, not
    /// settled.
    pub outcome: RunOutcome,
    /// `outcome == RunOutcome::Balanced`: the balls cancel the unbalance on average over the last
    /// revolution (residual static and couple unbalance at most [`BALANCE_TOLERANCE`] of the
    /// unbalance's, the balls' capacity sufficing) and their motion relative to the rotor is
    /// periodic (at rest, or swinging once per revolution under gravity or direction-dependent
    /// supports; mean angles drift by at most [`drift_tolerance`] per revolution).
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
    /// What the verdict alone does not say: a balanced end at a constant prescribed speed next
    /// to a balanced state (or a family of them with no stable member sampled) that the exact
    /// linear stability finds unstable there
    /// ([`crate::rotor_stability::unstable_balanced_state`]: the outcome is then
    /// [`RunOutcome::NotSettled`], the balls creeping away from it).
    pub warnings: Vec<String>,
}

impl Summary {
    /// The summary if the run reached `t_end`, else its early stop as a typed error
    /// ([`crate::simulation::status_result`]: [`crate::Error::Interrupted`] with the time
    /// reached, [`crate::Error::TooManySteps`], …).
    pub fn into_result(self) -> Result<Self> {
        crate::simulation::status_result(&self.status, self.t_end).map(|()| self)
    }
}

/// Residual unbalance (static and couple, relative to the unbalance's) up to which a settled run
/// counts as balanced: 5 %.
pub const BALANCE_TOLERANCE: f64 = 0.05;

/// How far (absolute, as a fraction of the unbalance) the residual of a partially balanced run
/// may lie from the closed form `1 − Σ m R / |U|`: 0.02. The balls settle on the direction of
/// the whirl, which with damping lags a few degrees behind exactly against the unbalance: an
/// angle `α` off raises the residual by `≈ c α² / (2 (1 − c))`, `c = Σ m R / |U|` (the washer
/// of examples/washing_machine.toml with half its ball mass: `α = 5°`, residual 0.326 against
/// 0.318). Balls "together": the resultant of each plane's balls is at least `1 − 0.01` of the
/// plane's capacity (within about ±8° of each other).
pub const PARTIAL_TOLERANCE: f64 = 0.02;

/// The fraction of a plane's capacity its balls' resultant reaches at least when they are
/// "together" (see [`PARTIAL_TOLERANCE`]).
pub(crate) const TOGETHER: f64 = 0.99;

/// Whether balls whose resultant has the magnitude `resultant` are "together": at least
/// [`TOGETHER`] of `capacity`, the most they can produce (the same units). The one rule of the
/// three runs' capacity-short test ([`Ending::short`]); each passes its own capacity: the
/// spatial and linear runs a plane's ball count against the sum of the balls' unit vectors
/// ([`plane_together`]), the planar run `|Σ m_j r e^{iψ_j}|` against
/// `crate::planar::stationary::ball_capacity`, which for balls of finite size
/// (`planar.contact`) is that of the touching balls packed in one arc, below `n m3 r`: they
/// cannot coincide, so "together" is measured against the packing they can reach.
pub(crate) fn together(resultant: f64, capacity: f64) -> bool {
    resultant >= TOGETHER * capacity
}

/// [`together`] for one plane's balls given by their unit vectors `e^{iψ_j}` (or their means
/// over a revolution): `|Σ_j u_j| ≥ TOGETHER · n`, `n` the number of vectors (equal balls of one
/// plane: the resultant over `m R`).
pub(crate) fn plane_together(units: impl IntoIterator<Item = [f64; 2]>) -> bool {
    let (mut sum, mut n) = ([0.0, 0.0], 0usize);
    for u in units {
        sum[0] += u[0];
        sum[1] += u[1];
        n += 1;
    }
    together(sum[0].hypot(sum[1]), n as f64)
}

/// The largest change of a ball's mean angle from one revolution to the next that still counts
/// as periodic motion: `2π · 10⁻³ · max(1, ω_n/|ω|)` rad, i.e. a mean relative rate below
/// `10⁻³ max(|ω|, ω_n)` (the criterion `|ψ̇| < 10⁻³ max(|ω|, ω_n)` of balls at rest, applied to
/// the mean over a revolution), `ω_n` the rotor's natural frequency.
pub fn drift_tolerance(omega: f64, natural_frequency: f64) -> f64 {
    2.0 * std::f64::consts::PI * 1e-3 * (natural_frequency / omega.abs()).max(1.0)
}

/// What a run ended in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunOutcome {
    /// The balls cancel the unbalance on average over a revolution (see [`Summary::balanced`]).
    Balanced,
    /// Settled with a residual unbalance below 1 (the balls reduce the unbalance) but not
    /// balanced: above the tolerance, or the balls' capacity `Σ m R` short of the unbalance
    /// (then never `Balanced`; the balls usually end together against the unbalance, the
    /// residual near the closed form `1 − Σ m R / |U|`). The one rule of `stability`'s states
    /// (`crate::rotor_stability::state_from_residual`).
    PartiallyBalanced,
    /// Settled with a residual unbalance of 1 or more (the balls do not reduce the unbalance,
    /// or add to it: e.g. on the heavy side below the critical speed), or no balls.
    NotBalanced,
    /// The balls' mean angles still drift between the last two revolutions by more than
    /// [`drift_tolerance`] (a transient, or balls circulating round the race), or the run turned
    /// less than two revolutions, or it stopped early.
    NotSettled,
}

/// What a run's summary decides its [`RunOutcome`] on: the one rule of the spatial and the
/// planar runs ([`run_outcome`]).
pub(crate) struct Ending {
    /// Whether the rotor has balls.
    pub balls: bool,
    /// Whether the motion had settled (spatial: the balls' mean angles drift by at most
    /// [`drift_tolerance`] per revolution; planar: `crate::planar::Summary::settled`) and the
    /// run completed.
    pub settled: bool,
    /// Where no balanced state exists (`stability`'s test: a plane's capacity short of its
    /// share, or one plane against a couple): the least residual of the balls together against
    /// the unbalance, read only on the linear rotor's race-whirl basis (the spatial run passes
    /// `max(0, 1 − Σ m R/|s0|)`, which it does not read), and whether they ended together
    /// (their resultant at least 99 % of the capacity).
    pub short: Option<(f64, bool)>,
    /// The residual unbalance, a fraction of the unbalance, averaged over the last revolution.
    pub residual: f64,
    /// The residual couple, a fraction of the unbalance's couple, if it has one.
    pub residual_couple: Option<f64>,
    /// The residual (and couple) up to which the run is balanced: [`BALANCE_TOLERANCE`], or
    /// less where the residual's reference resonates (the planar run's
    /// `crate::planar::stationary::balance_allowance`).
    pub tolerance: f64,
    /// The linear rotor's run: `residual` is its race whirl (`stability`'s `race_whirl`
    /// basis, [`crate::linear_rotor::partial::state_kind`]), not a residual unbalance, so
    /// [`crate::rotor_stability::state_from_residual`]'s "below 1 reduces the unbalance" does
    /// not apply: balanced within the tolerance, partially balanced only with the balls
    /// together at the capacity-short residual (within [`PARTIAL_TOLERANCE`]), else not
    /// balanced, the linear `stability`'s words.
    pub race_whirl_basis: bool,
}

/// The outcome of a run from its [`Ending`]: without balls not balanced; not settled while
/// the balls move; else the one rule of `stability`'s states
/// (`crate::rotor_stability::state_from_residual`) on the larger of the residual and the
/// couple's: balanced at most [`Ending::tolerance`] where a balanced state exists, partially
/// balanced below 1, not balanced at 1 or more.
pub(crate) fn run_outcome(e: &Ending) -> RunOutcome {
    if !e.balls {
        RunOutcome::NotBalanced
    } else if !e.settled {
        RunOutcome::NotSettled
    } else if e.race_whirl_basis {
        match e.short {
            Some((least, together)) if together && (e.residual - least).abs() <= PARTIAL_TOLERANCE => RunOutcome::PartiallyBalanced,
            Some(_) => RunOutcome::NotBalanced,
            None if e.residual <= e.tolerance => RunOutcome::Balanced,
            None => RunOutcome::NotBalanced,
        }
    } else {
        // the one rule of `stability`'s states (crate::rotor_stability::state_from_residual):
        // balanced within the tolerance where a balanced state exists; else partially balanced
        // below 1 (the balls reduce the unbalance), not balanced at 1 or more. Before session
        // 29 a run whose balls reduced the unbalance without being together at the capacity
        // limit read "not balanced" where `stability` read the same state "partially balanced"
        // (review 29: the washer with a tilted axis, residual 0.17, couple 0.29)
        let residual = e.residual.max(e.residual_couple.unwrap_or(0.0));
        match crate::rotor_stability::state_from_residual(residual, e.tolerance, e.short.is_none()) {
            crate::rotor_stability::StateKind::Balanced => RunOutcome::Balanced,
            crate::rotor_stability::StateKind::NotBalanced => RunOutcome::NotBalanced,
            _ => RunOutcome::PartiallyBalanced,
        }
    }
}

impl RunOutcome {
    /// `"balanced"`, `"partially balanced"`, `"not balanced"`, `"not settled"`: the words of
    /// `stability`'s states (`crate::rotor_stability::StateKind::name`) for the same state.
    pub fn name(self) -> &'static str {
        match self {
            RunOutcome::Balanced => "balanced",
            RunOutcome::PartiallyBalanced => "partially balanced",
            RunOutcome::NotBalanced => "not balanced",
            RunOutcome::NotSettled => "not settled",
        }
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

/// Axial position where the whirl is measured: the first balancer plane, else the first
/// unbalance, else C.
fn amplitude_z(eq: &Equations) -> f64 {
    eq.rotor.planes.first().map(|p| p.z).or_else(|| eq.rotor.unbalances.first().map(|u| u.z)).unwrap_or(eq.z_reference())
}

fn plane_amplitude(eq: &Equations, y: &[f64]) -> f64 {
    let d = eq.displacement_at(y, amplitude_z(eq));
    d[0].hypot(d[1])
}

/// What the spatial run's summary averages over its last revolutions
/// ([`crate::simulation::RevolutionWindow`], on the grid of the spin angle `φ`): per record the
/// residual static and couple unbalance in the rotor frame (4), the shaft's displacement `r` at
/// the (first) balancer plane in fixed axes (2), the ball angles.
struct SpatialRecorder<'a> {
    eq: &'a Equations<'a>,
}

/// Where a [`SpatialRecorder`]'s record holds the displacement `r` and the ball angles.
const REC_R: usize = 4;
const REC_PSI: usize = 6;

impl SpatialRecorder<'_> {
    fn width(&self) -> usize {
        REC_PSI + self.eq.rotor.balls()
    }
}

impl crate::simulation::Recorder for SpatialRecorder<'_> {
    fn spin(&self, t: f64, y: &[f64]) -> (f64, f64) {
        (y[PHI], self.eq.spin_rate(t, y))
    }

    fn record(&self, _t: f64, y: &[f64], out: &mut [f64]) {
        let (st, cp) = self.eq.residual_unbalance(y);
        let r = self.eq.displacement_at(y, amplitude_z(self.eq));
        out[..REC_PSI].copy_from_slice(&[st[0], st[1], cp[0], cp[1], r[0], r[1]]);
        out[REC_PSI..].copy_from_slice(&y[ROTOR_COORDS..self.eq.coords()]);
    }
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
    simulate_with(rotor, drive, init, settings, &crate::control::Control::none(), sink)
}

/// [`simulate`] under `control` (its cancel flag is asked before every integrator step, so a
/// run with sparse samples stops as promptly as any; its budget every few hundred steps): an
/// early stop is the summary's [`Summary::status`], the summary covering what was computed.
pub fn simulate_with(
    rotor: &SpatialRotor,
    drive: &Drive,
    init: &Initial,
    settings: &Settings,
    control: &crate::control::Control,
    sink: impl FnMut(&Sample) -> bool,
) -> Result<Summary> {
    simulate_sampled(rotor, drive, init, settings, control, settings.dt, sink)
}

/// The run of [`simulate`] with samples only at its start and end, for its summary (basins):
/// the same settings, `dt` included, so the same steps and the same summary (`dt` is also the
/// automatic method's time resolution, see [`tolerances`]), under `control` as
/// [`simulate_with`] and [`crate::planar::simulate_summary`].
pub fn simulate_summary(rotor: &SpatialRotor, drive: &Drive, init: &Initial, settings: &Settings, control: &crate::control::Control) -> Result<Summary> {
    simulate_sampled(rotor, drive, init, settings, control, settings.t_end, |_| true)
}

/// [`simulate_with`], sampling every `sample_dt` (the integrator's settings unchanged).
fn simulate_sampled(
    rotor: &SpatialRotor,
    drive: &Drive,
    init: &Initial,
    settings: &Settings,
    control: &crate::control::Control,
    sample_dt: f64,
    mut sink: impl FnMut(&Sample) -> bool,
) -> Result<Summary> {
    rotor.validate()?;
    drive.validate()?;
    settings.validate()?;
    let eq = Equations::new(rotor, drive);
    let mut y = initial_state(&eq, init)?;
    let mut solver = Solver::new(&eq, tolerances(&eq, settings))?;
    solver.control(control);
    let breakpoints = drive.breakpoints();
    let timeline = Timeline { t_end: settings.t_end, dt: sample_dt, breakpoints: &breakpoints };
    let counters = vec![EventCounter::default(); eq.ball_forces().len()];
    let recorder = SpatialRecorder { eq: &eq };
    let window = RevolutionWindow::new(recorder.width(), settings.t_end);
    let mut hooks = SpatialHooks { eq: &eq, sink: &mut sink, peak: (plane_amplitude(&eq, &y), drive.omega0(), 0.0), counters, window, recorder };
    let out = run(&mut solver, &mut y, &timeline, &mut hooks);
    let peak = hooks.peak;
    let mut s = summarise(&eq, out.t, &y, peak, out.stats, &out, &hooks.window);
    s.contacts = hooks.counters.iter().map(|c| c.contacts).sum();
    s.stick_slip_transitions = hooks.counters.iter().map(|c| c.stick_slip).sum();
    Ok(s)
}

/// Peak tracking at step ends and samples, the prescribed spin put back on its schedule at
/// each piece, samples to the sink, real balls' contacts and stick-slip counted per plane, the
/// last revolutions recorded for the summary's averages ([`SpatialRecorder`]).
struct SpatialHooks<'a, F: FnMut(&Sample) -> bool> {
    eq: &'a Equations<'a>,
    sink: &'a mut F,
    peak: (f64, f64, f64),
    counters: Vec<EventCounter>,
    window: RevolutionWindow,
    recorder: SpatialRecorder<'a>,
}

impl<F: FnMut(&Sample) -> bool> Hooks for SpatialHooks<'_, F> {
    fn start_piece(&mut self, t: f64, y: &mut [f64]) {
        if self.eq.drive.prescribed() {
            y[self.eq.coords() + PHI] = self.eq.drive.kinematics(t).0;
        }
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let d = self.eq.displacement_at(y, amplitude_z(self.eq));
        let a = d[0].hypot(d[1]);
        if a > self.peak.0 {
            self.peak = (a, self.eq.spin_rate(t, y), t);
        }
        let nc = self.eq.coords();
        for ((first, f), c) in self.eq.ball_forces().iter().zip(&mut self.counters) {
            let a = ROTOR_COORDS + first;
            c.observe(f, &y[a..a + f.n], &y[nc + a..nc + a + f.n]);
        }
    }

    fn dense_step(&mut self, t_old: f64, t_new: f64, y_old: &[f64], y_new: &[f64], interpolate: &mut dyn FnMut(f64, &mut [f64])) {
        self.window.dense_step(&self.recorder, t_old, t_new, y_old, y_new, interpolate);
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

/// The summary at the end of a run: averages over the last revolution from `window`, the
/// verdict ([`RunOutcome`]).
fn summarise(eq: &Equations, t: f64, y: &[f64], peak: (f64, f64, f64), stats: Stats, out: &Outcome, window: &RevolutionWindow) -> Summary {
    let r = eq.rotor;
    let omega = eq.spin_rate(t, y);
    let (s0, c0) = (r.static_unbalance(), r.couple_unbalance());
    let capacity: f64 = r.planes.iter().map(|p| p.n as f64 * p.ball_mass * p.race_radius).sum();
    let s0n = s0[0].hypot(s0[1]);
    let c0n = c0[0].hypot(c0[1]);
    // (`stability`'s rotor, for its rule on what "no unbalance" is and the end checks)
    let rotor = crate::rotor_stability::Rotor::Spatial(r.clone());
    // a couple to judge: one beside the static unbalance, on a rotor with an unbalance at all
    // (a round-off couple beside a round-off static unbalance is none, as in `stability`)
    let has_couple = c0n > 1e-12 * (s0n * r.length_scale()).max(f64::MIN_POSITIVE) && rotor.has_unbalance();
    let nb = r.balls();
    // averages over the last revolution, or the end state where it was not recorded (the run
    // turned less, or stopped before the window began)
    let (st, cp, mean_psi, mean_r, whirl) = match window.mean(0) {
        Some(m) => {
            let mean_r = [m[REC_R], m[REC_R + 1]];
            // the RMS of |r − r̄|, from the records' distances to the mean (no cancellation of
            // a mean square less a squared mean under a sag much larger than the whirl)
            let var = window.mean_of(0, |v| (v[REC_R] - mean_r[0]).powi(2) + (v[REC_R + 1] - mean_r[1]).powi(2)).unwrap_or(0.0);
            ([m[0], m[1]], [m[2], m[3]], m[REC_PSI..].to_vec(), Some(mean_r), var.max(0.0).sqrt())
        }
        None => {
            let (st, cp) = eq.residual_unbalance(y);
            let d = eq.displacement_at(y, amplitude_z(eq));
            (st, cp, y[ROTOR_COORDS..ROTOR_COORDS + nb].to_vec(), None, d[0].hypot(d[1]))
        }
    };
    // over the unbalance, or the capacity where there is none to speak of: stability's rule
    let residual_unbalance = st[0].hypot(st[1]) / crate::rotor_stability::unbalance_scale(s0n, capacity);
    let residual_couple = has_couple.then(|| cp[0].hypot(cp[1]) / c0n);
    // the balls' drift: mean angles over the last revolution against the one before
    let ball_drift = if nb > 0 { window.drift(REC_PSI..REC_PSI + nb) } else { None };
    let settled = out.status.is_completed() && matches!(ball_drift, Some(d) if d <= drift_tolerance(omega, r.natural_frequency()));
    // no balanced state: the least residual is the balls together against the unbalance
    let together = || {
        let mut first = 0;
        r.planes.iter().all(|p| {
            let units = mean_psi[first..first + p.n].iter().map(|psi| [psi.cos(), psi.sin()]);
            first += p.n;
            plane_together(units)
        })
    };
    // whether a balanced state exists: `stability`'s test (each plane's capacity against its
    // share of the static and couple unbalance, one plane against a couple never), not the
    // total capacity against the static unbalance alone (walk 34: two planes each 1.6 % short
    // of a pure couple's share, and the washer with a couple, read "balanced")
    let exists = crate::rotor_stability::spatial_balance_exists(r);
    let outcome = run_outcome(&Ending {
        balls: nb > 0,
        settled,
        // (the closed-form residual of the first element is read on the linear rotor's race
        // whirl basis only; here `short` says that no balanced state exists)
        short: (!exists).then(|| ((1.0 - capacity / s0n.max(f64::MIN_POSITIVE)).max(0.0), together())),
        residual: residual_unbalance,
        residual_couple,
        tolerance: BALANCE_TOLERANCE,
        race_whirl_basis: false,
    });
    // the end checks (`crate::rotor_stability::end_checks`), in the model's own units (`si`
    // false); the end state in turning axes already: the field's reduced state
    let checks = crate::rotor_stability::end_checks(&rotor, omega, false, eq.drive.constant_speed_at(t), outcome, settled, || {
        Some(super::field::SpatialField::new(r, omega).ok()?.reduced_state(y))
    });
    let (outcome, settled) = (checks.outcome, checks.settled);
    let warnings = checks.warning.into_iter().collect();
    Summary {
        peak_amplitude: peak.0,
        omega_at_peak: peak.1,
        t_at_peak: peak.2,
        final_amplitude: whirl,
        mean_displacement: mean_r,
        // a sag only where the run settled: the stationary motion's mean position (under
        // gravity ≈ M g / Σ k). While the orbit drifts the last revolution's mean is the
        // transient's (review 29: r1.toml 0.969 mm against 0.079 mm settled, the two-plane
        // example 0.774 mm against m g/k = 0.0284 mm), and no window tells the two apart
        // (a run without balls, or otherwise not called "not settled", under gravity: its
        // whirl is steady about the sag, as before)
        static_sag: mean_r.filter(|_| settled || (r.gravity_across() && outcome != RunOutcome::NotSettled)).map(|m| m[0].hypot(m[1])),
        final_omega: omega,
        residual_unbalance,
        residual_couple,
        ball_drift,
        averaged: mean_r.is_some(),
        outcome,
        balanced: outcome == RunOutcome::Balanced,
        steps: stats.steps,
        rejected_steps: stats.rejected,
        rhs_evaluations: stats.rhs_evaluations,
        contacts: 0,
        stick_slip_transitions: 0,
        t_end: t,
        stopped: match &out.status {
            Status::Completed => None,
            Status::Stopped(StopReason::Observer) => Some(format!("interrupted at t = {}", crate::error::fmt_num(t))),
            _ => Some(out.to_string()),
        },
        status: out.status.clone(),
        warnings,
    }
}
