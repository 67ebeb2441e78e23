//! The spatial rigid rotor of papers 000 and 003 on two elastic supports, with an unbalance
//! mass and an n-ball balancer: parameters, composite inertia, critical speeds, sensitivity,
//! autobalancing ranges, the linearised equations of the balanced state and their exact
//! stability.

pub mod boundary;
pub mod campbell;
pub mod comparison;
pub mod critical_speeds;
pub mod dynamics;
pub mod inertia;
pub mod linear_model;
pub mod map;
pub mod params;
pub mod paths;
pub mod presets;
pub mod ranges;
pub mod sensitivity;
pub mod stability;
