//! Small dense linear algebra on stack arrays: LU factorisation (`dense`, crate-internal) and
//! eigenvalues with the Routh–Hurwitz test ([`eigen`]); eigenvalues of
//! dense matrices of any size on the heap ([`eigen_dyn`]).

pub mod charpoly;
pub(crate) mod dense;
pub mod eigen;
pub mod eigen_dyn;
