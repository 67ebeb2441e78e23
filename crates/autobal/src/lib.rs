//! # autobal: rotors with passive automatic balancing devices
//!
//! Models and analyses only: no printing, no files. The command-line front end lives in the
//! `autobal-cli` crate.
//!
//! ## A tour
//! - [`params`]: the SI description of a rigid rotor on two supports with an unbalance mass
//!   and an n-ball balancer ([`params::SpatialRotorSi`]) and the papers' dimensionless model
//!   ([`params::SpatialModel`]) every analysis works on.
//! - [`inertia`]: composite inertia and its anisotropy `ΔĀ`, by paper 000's eq (17) and by
//!   the exact inertia tensor of the point masses at their balancing positions.
//! - [`critical_speeds`]: exact roots of `Δ1 Δ2 = 0` (000, eq (16)), approximations (18)-(20),
//!   Table 1.
//! - [`sensitivity`]: the criterion of 000 eqs (21)-(22) / 003 eqs (4)-(5).
//! - [`ranges`]: antiresonance speed and the speed ranges where autobalancing is possible
//!   (003, eqs (1)-(3)).
//! - [`linear_model`]: the linearised equations of the balanced state (000, eq (6)), balls free
//!   (12 states) or locked (8 states).
//! - [`eigen`]: eigenvalues of small dense matrices (balancing, Hessenberg, Francis QR),
//!   characteristic polynomial and Routh–Hurwitz test.
//! - [`stability`]: exact stability ranges, Campbell diagrams, stability verdicts for maps.
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

pub mod critical_speeds;
mod dense;
pub mod eigen;
pub mod error;
pub mod inertia;
pub mod linear_model;
pub mod params;
pub mod ranges;
pub mod sensitivity;
pub mod simulation;
pub mod stability;

pub use error::{Error, Result};
