//! Small dense linear algebra on stack arrays: LU factorisation (`dense`, crate-internal) and
//! eigenvalues with the Routh–Hurwitz test ([`eigen`]).

pub mod charpoly;
pub(crate) mod dense;
pub mod eigen;
