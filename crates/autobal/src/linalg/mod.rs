//! Small dense linear algebra on stack arrays: LU factorisation (`dense`, crate-internal) and
//! eigenvalues with the Routh–Hurwitz test ([`eigen`]) on the fixed-size matrices of
//! [`small`]; eigenvalues of dense matrices of any size on the heap ([`eigen_dyn`]). Nothing
//! here imports a model. The Hungarian method for optimal assignment ([`assignment`]).

pub mod assignment;
pub mod charpoly;
pub(crate) mod dense;
pub mod eigen;
pub mod eigen_dyn;
pub mod small;
