//! Fixed-size matrices on the stack for the small linear models (at most 6 generalised
//! coordinates, 12 states: the rigid rotor of papers 000/003 with its two balls' coordinate
//! pair), and the quadratic pencil `M λ² + G λ + K` their linearisations are written as.
//! Shared by the eigenvalue solver ([`super::eigen`]), the characteristic polynomial
//! ([`super::charpoly`]) and the ODE solver's small Krylov spaces; the models build them.

/// Largest number of generalised coordinates of a pencil.
pub const MAX_COORDS: usize = 6;
/// Largest state dimension (`2 MAX_COORDS`).
pub const MAX_STATES: usize = 2 * MAX_COORDS;

/// A square matrix of at most [`MAX_COORDS`] rows, stored on the stack.
pub type Mat6 = [[f64; MAX_COORDS]; MAX_COORDS];
/// A square matrix of at most [`MAX_STATES`] rows, stored on the stack.
pub type Mat12 = [[f64; MAX_STATES]; MAX_STATES];

/// The pencil `M λ² + G λ + K` of a linearisation `M q̈ + G q̇ + K q = 0` at one speed, its
/// eigenvalues the roots of `det(M λ² + G λ + K) = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pencil {
    /// Number of coordinates (4 or 6).
    pub n: usize,
    /// Mass matrix.
    pub m: Mat6,
    /// Gyroscopic + damping matrix.
    pub g: Mat6,
    /// Stiffness + circulatory matrix.
    pub k: Mat6,
}
