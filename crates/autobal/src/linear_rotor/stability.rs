//! The balanced state of a [`LinearRotor`] and its stability over speed: the general route
//! [`crate::rotor_stability::stability_over_speed`] on [`Rotor::Linear`] (the same
//! [`RotorStability`] result, model `"linear"`), on [`super::LinearRotorField`] in axes turning
//! with the rotor — an equilibrium (eigenvalues) for an isotropic structure without gravity, a
//! periodic orbit (Floquet multipliers) otherwise: of half a revolution for direction-dependent
//! supports, of one under gravity — started at each speed from
//! [`super::LinearRotorField::balanced_guess`]. With `n ≥ 3` balls in the plane the family of
//! balanced states is followed at each speed as for the other models
//! ([`RotorStability::family`]).

use super::LinearRotor;
use crate::error::Result;
use crate::rotor_stability::{Rotor, RotorStability};

/// The stationary state of `rotor` and its stability at each of `speeds` (ascending, rad/s),
/// with the ends of the stable ranges bisected: [`crate::rotor_stability::stability_over_speed`]
/// on [`Rotor::Linear`].
pub fn stability_over_speed(rotor: &LinearRotor, speeds: &[f64]) -> Result<RotorStability> {
    crate::rotor_stability::stability_over_speed(&Rotor::Linear(rotor.clone()), speeds)
}
