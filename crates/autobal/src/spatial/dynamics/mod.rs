//! Nonlinear dynamics of the spatial rotor of papers 000/003 with its balls, in time
//! (docs/notes/spatial.md): a rigid rotor on one or two elastic supports (translation and tilt,
//! 4 DOF), its spin (prescribed or driven by any [`crate::drive::Drive`]), unbalance as static
//! plus couple, and any number of balls in one or more balancer planes, with no small-angle
//! or small-displacement assumption on the balls and an exact rigid-body kinetic energy.
//!
//! - [`rotor`]: the parameters ([`SpatialRotor`]), from the analytic commands' SI or
//!   dimensionless description.
//! - [`equations`]: the equations of motion in axes turning with the rotor ([`Equations`]),
//!   energy and dissipated power, the exact Jacobian by forward-mode differentiation.
//! - [`field`]: the rotor at a constant speed as an [`crate::analysis::VectorField`]
//!   ([`SpatialField`]: reduced state, exact Jacobian, period, family of balanced states).
//! - [`mass_properties`]: total mass, centre of mass, inertia tensor, principal axes of the
//!   whole rotor with its balls placed ([`SpatialRotor::mass_properties`]).
//! - [`simulate`](mod@simulate): initial conditions, integration under a drive, samples, the
//!   verdict ([`simulate()`]).
//! - [`stationary`]: steady synchronous whirls with the balls held (the stationary response
//!   curves a run-up is drawn against).
//! - [`basins`]: where runs end over a grid of initial conditions, in parallel.

pub mod basins;
pub mod equations;
pub mod field;
pub mod mass_properties;
pub mod rotor;
pub mod simulate;
pub mod stationary;

pub use equations::Equations;
pub use field::SpatialField;
pub use mass_properties::{BallPlacement, MassProperties, Placement};
pub use rotor::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
pub use simulate::{simulate, simulate_summary, simulate_with, Initial, RunOutcome, Sample, Settings, Summary};
