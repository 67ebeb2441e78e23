//! Model-agnostic analysis of stationary motions (issue "Analyse every rotor"): a model supplies
//! its equations in axes turning with the rotor at a constant speed as a [`VectorField`]
//! (right-hand side and exact Jacobian by automatic differentiation); this module supplies the
//! stationary state (an equilibrium when the field is autonomous, a periodic orbit of the
//! revolution's period when it is not), its linearisation, and its stability (eigenvalues, or
//! Floquet multipliers of the monodromy matrix).
//!
//! Imports nothing from a model: `planar`, `spatial` and any later model implement
//! [`VectorField`] themselves.

/// `x' = f(t, x)`: a model's equations at a constant rotor speed, in axes turning with the rotor,
/// with the prescribed coordinates (the spin angle and its rate) removed from the state.
///
/// Autonomous (`period() == None`) when nothing in the equations depends on the rotor's angle
/// (supports equal in every direction, no gravity); otherwise periodic with the revolution,
/// `f(t + T, x) = f(t, x)` with `T = 2π/Ω` (supports that differ by direction, gravity).
pub trait VectorField {
    /// Number of states.
    fn dim(&self) -> usize;
    /// `f(t, x)` into `dx` (both of length [`VectorField::dim`]).
    fn rhs(&self, t: f64, x: &[f64], dx: &mut [f64]);
    /// The exact Jacobian `∂f/∂x` at `(t, x)`, row-major `dim × dim` into `jac`: by automatic
    /// (forward-mode) differentiation of the equations, never by difference quotients.
    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]);
    /// The period of the explicit time dependence, `Some(2π/Ω)`, or `None` when autonomous.
    fn period(&self) -> Option<f64>;
    /// The number of zero eigenvalues (Floquet multipliers 1) that a stationary state `x` has by
    /// the model's structure rather than by instability: the dimension of a family of stationary
    /// states through `x` (e.g. `n − 2` for `n ≥ 3` balls balancing one plane). Default 0.
    fn structural_zeros(&self, _x: &[f64]) -> usize {
        0
    }
    /// Name of state component `i`, for messages.
    fn component_name(&self, i: usize) -> String {
        format!("x[{i}]")
    }
}
