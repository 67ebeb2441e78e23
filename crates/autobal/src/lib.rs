//! # autobal: rotors with passive automatic balancing devices
//!
//! Models and analyses only: no printing, no files. The command-line front end lives in the
//! `autobal-cli` crate.
//!
//! ## A tour
//! Two physical models over shared machinery:
//!
//! - [`spatial`]: the rigid rotor on two supports of papers 000 and 003.
//! - [`planar`]: the planar rotor with an eccentric ball balancer of paper 004, in time.
//! - [`drive`]: speed and torque histories shared by the dynamic models.
//! - [`balls`]: real balls shared by the dynamic models: finite size and contact, rolling
//!   resistance, and their closed forms (capacity of touching balls, where friction lets a ball rest).
//! - [`ode`]: the integrators (DOP853, RODAS, automatic switching between them), dense output,
//!   events, structured Jacobians.
//! - [`simulation`]: what every time simulation needs on top of them (pieces between a drive's
//!   breakpoints, samples at a fixed interval, peak tracking, budgets, interruption).
//! - [`linalg`]: small dense LU and eigenvalues.
//! - [`error`], [`limits`]: typed errors, and the range of every input.
//!
//! Inside [`spatial`]:
//! - [`spatial::params`]: the papers' dimensionless model ([`spatial::params::SpatialModel`]) every
//!   analysis works on, derived from the SI rotor ([`spatial::dynamics::SpatialRotor::to_dimensionless`])
//!   or given in the papers' symbols ([`spatial::params::DimensionlessInput`]).
//! - [`spatial::inertia`]: composite inertia and its anisotropy `ΔĀ`, by paper 000's eq (17) and by
//!   the exact inertia tensor of the point masses at their balancing positions.
//! - [`spatial::critical_speeds`]: exact roots of `Δ1 Δ2 = 0` (000, eq (16)), approximations (18)-(20),
//!   Table 1.
//! - [`spatial::sensitivity`]: the criterion of 000 eqs (21)-(22) / 003 eqs (4)-(5).
//! - [`spatial::ranges`]: antiresonance speed and the speed ranges where autobalancing is possible
//!   (003, eqs (1)-(3)).
//! - [`spatial::linear_model`]: the linearised equations of the balanced state (000, eq (6)), balls free
//!   (12 states) or locked (8 states).
//! - [`linalg::eigen`]: eigenvalues of small dense matrices (balancing, Hessenberg, Francis QR),
//!   characteristic polynomial and Routh–Hurwitz test.
//! - [`spatial::stability`]: exact stability ranges, Campbell diagrams, stability verdicts for maps.
//! - [`spatial::dynamics`]: the SI rotor ([`spatial::dynamics::SpatialRotor`], also what an SI
//!   config's `[rotor]`, `[supports]`, `[unbalance]`, `[balancer]` describe) and its nonlinear
//!   equations with its balls in time (one or two supports and balancer planes, static and couple
//!   unbalance, anisotropic supports, gravity, any drive), whose linearisation is 000's eq (6);
//!   simulation.
//!
//! ## Starting points
//! Every model and settings type has a `Default` (each paper's base case) and presets named
//! after the papers ([`planar::PlanarRotor::paper_004`], [`planar::problem::PlanarProblem::paper_004`],
//! [`spatial::params::DimensionlessInput::paper_000`] and `paper_003`,
//! [`spatial::dynamics::SpatialRotor::paper_000`], [`spatial::dynamics::SpatialRotor::dimensional_example`],
//! the settings of `examples/`); the models and the simulations' settings have builders whose
//! `build()` validates (errors name the field as the config spells it). Parameters are
//! addressed by path (`planar.c_psi`, `drive.psi0[2]`, `dimensionless.z_a`, `rotor.mass`):
//! [`paths::Parameters`] (one [`paths::ParameterPath`] table each) for the planar problem and
//! the spatial model ([`spatial::paths::SpatialSpec`]); [`sweep`], [`spatial::map`] and
//! [`spatial::boundary`] vary them along a [`paths::Axis`], the one axis type.
//!
//! ## How long computations end
//! Every long computation runs under one [`control::Control`] (a cancel flag shared across
//! threads, an optional wall-time budget, an optional progress observer; [`control::Control::none`]
//! to run to the end) and says why it stopped early with one [`control::StopReason`]
//! (interrupted, budget spent, step budget spent, a sink that asked to stop), keeping what it
//! computed until then. It never returns a silent `Ok` that looks like a whole result. Failures
//! that are no decision to stop (a non-finite state, a step size that underflows) are errors or
//! the run's [`ode::Status`].
//!
//! | entry point | runs under | an early stop is |
//! |---|---|---|
//! | [`ode::Solver::integrate`] | [`ode::Solver::control`] (flag every step, budget every [`control::BUDGET_CHECK_EVERY`] steps) | [`ode::Status::Stopped`] with the reason |
//! | [`planar::simulate_with`], [`planar::simulate_summary`], [`planar::problem::PlanarProblem::simulate_summary`] | `&Control` | [`planar::Summary::status`] (and `stopped` in words); [`planar::Summary::into_result`] makes it [`Error::Interrupted`], [`Error::TooManySteps`], … |
//! | [`spatial::dynamics::simulate_with`], [`spatial::dynamics::simulate_summary`] | `&Control` | [`spatial::dynamics::Summary::status`]; [`spatial::dynamics::Summary::into_result`] |
//! | [`sweep::simulate_grid`], [`sweep::simulate_batch`] ([`sweep::SweepModel::run`]) | `&Control` | [`sweep::SweepOutcome::stopped`] (`into_result`: [`Error::Interrupted`] with the fraction done); each point's summary has its own `completed` and `t_reached` |
//! | [`rotor_map::general_map`], [`rotor_map::general_map_traced`] | `&Control` | [`rotor_map::GeneralMapOutcome::stopped`] (the rows handed over are whole) |
//! | [`spatial::boundary::trace_boundary_with`], [`spatial::boundary::trace_boundary_units`] | `&Control` | [`spatial::boundary::Boundary::stopped`] (the curves traced are whole) |
//! | [`spatial::dynamics::basins::basins`] | `&Control` | [`control::Outcome::stopped`]; `None` for each run not run or cut short |
//! | [`planar::paper004::torque_run_with`] / [`planar::paper004::torque_outcomes`] | `&Control` | the run's `summary.status` / a typed error |
//! | [`spatial::map::stability_map`], [`spatial::map::stability_map_units`] | `&Control` (asked between rows) | [`spatial::map::MapOutcome::stopped`] (the rows handed over are whole) |
//! | [`spatial::stability::campbell_stream`] | `on_speed` returns `false` (likewise) | [`spatial::stability::CampbellStats::complete`] |
//! | [`planar::friction::residual`] | none (one bounded run; callers ask the control between runs) | [`planar::friction::Residual::completed`] |
//!
//! The analyses without a callback ([`spatial::stability::stability_ranges`],
//! [`spatial::stability::campbell`], [`spatial::critical_speeds::critical_speeds`], …) either
//! finish or return an error ([`Error::NoConvergence`] with the speed, …).
//!
//! ## Symbols (papers 000 and 003)
//! | symbol | meaning |
//! |---|---|
//! | `ω0 = sqrt(c_x/M_s)` | unit of speed; `Ω = ω/ω0`, `τ = ω0 t` |
//! | `C̄Σ = C_Σ/A_Σ` | polar over mean equatorial moment: long `< 1`, short `> 1` |
//! | `ρ_s = sqrt(A_Σ/M_s)`, `ρ̄s = ρ_s/l` | radius of gyration, relative to the support span |
//! | `l̄_L = l_cL/l` | position of the centre of mass C from the left support (`> 1` overhung) |
//! | `z̄_A = z_A/ρ_s` | position of the balancer plane A from C |
//! | `p̄α² = c_α/(A_Σ ω0²)` | angular stiffness of the supports |
//! | `c̄yα = c_yα/(ω0² sqrt(M_s A_Σ))` | translation–tilt coupling (0 for a symmetric layout) |
//! | `ΔĀ = ΔA/A_Σ` | inertia anisotropy at balance; `ΔĪ_1,2 = 1 − C̄Σ ± ΔĀ` |
//! | `ΔĀ0 = ½ m̄0 R̄0²` | anisotropy of the unbalance mass alone (003) |
//! | `m̄0 = m0/M_s`, `R̄0 = R0/ρ_s` | unbalance mass and radius |
//! | `m̄ = n m/M_s`, `R̄ = R/ρ_s` | all balls' mass and race radius |
//! | `E = m̄ R̄/(m̄0 R̄0)` | balancer capacity |
//! | `D_A = |(1/n) Σ exp(2 i α_j)|` | ball-geometry factor of eq (17) |
//! | `h̄x, h̄α, h̄yα, h̄s` | dimensionless damping and ball drag |

// Every public item says what it is (the formula or paper equation it implements); CI denies
// warnings, so an undocumented public item fails the build.
#![warn(missing_docs)]

pub mod analysis;
pub mod balls;
pub(crate) mod builder;
pub mod config;
pub mod control;
pub mod drive;
pub mod error;
pub mod limits;
pub mod linalg;
pub mod linear_rotor;
pub mod ode;
pub mod paths;
pub mod planar;
pub mod reports;
pub mod rotor_campbell;
pub mod rotor_map;
pub mod rotor_partial;
pub mod rotor_stability;
pub mod simulation;
pub mod spatial;
pub mod sweep;
pub mod tolerance;
pub mod units;

pub use error::{Error, Result};
