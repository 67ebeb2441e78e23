//! Ball balancers on a general linear rotor–bearing model (issue 19, "your own rotor"): the
//! structure is given by its matrices, the balls are added by this module.
//!
//! # The structure
//! [`LinearRotor`] holds the structural equations in **fixed axes**
//!
//! ```text
//! M q̈ + (C + Ω G) q̇ + K q = f(t),
//! ```
//!
//! `q` the `N` degrees of freedom named by node and direction in ROSS's order: per node
//! `x, y` ([`Layout::Translation`]) or `x, y, α, β` ([`Layout::TranslationTilt`]), the same at
//! every node ([`LinearRotor::layout`]) or node by node ([`LinearRotor::node_layouts`]: a
//! support mass, ROSS's `PointMass` at the far end of an `n_link` bearing, has `x, y` only), `α` the tilt
//! about `x` and `β` the tilt about `y` (a point at axial offset `z` from the node moves by
//! `(x + z β, y − z α)`). `M` is symmetric positive definite, `G` skew (gyroscopic, multiplied
//! by the spin speed `Ω`), `C` and `K` any real matrices (cross-coupled bearings give
//! non-symmetric `K`). The balls' mass is **not** in `M`: the balancer planes bring it.
//! Unbalances ([`Unbalance`]: node, `m·e`, phase, axial offset `z`) apply, at constant speed, the
//! force `F = m e Ω² e^{i(φ + phase)}` at the node (`φ = Ω t` the spin angle) and, through the
//! offset, the moments `f_α = −z F_y`, `f_β = z F_x` (virtual work of `F` on `(x + zβ, y − zα)`).
//!
//! # The balls (derivation)
//! A balancer plane ([`BalancerPlane`]) at node `k` carries `n` point balls of mass `m_b` on a
//! race of radius `R` whose centre sits at the axial offset `z` from the node, at
//! `c_k = (x_k + z β_k, y_k − z α_k)` (complex `c_k = z_k − i z τ_k`... written below as the
//! vector `c = u − z J τ`, `τ = (α, β)`, `J (a, b) = (−b, a)`). The race plane tilts with the node
//! and spins with the rotor (`φ = Ω t`); ball `j` is at the angle `θ_j = φ + ψ_j`, `ψ_j` its angle
//! relative to the rotor. To second order in the structure's small motions (exact in `ψ`, `ψ̇`),
//! its velocity is the race centre's plus `R θ̇_j e⊥_j` in the plane (`e_j = (cos θ_j, sin θ_j)`,
//! `e⊥_j = (−sin θ_j, cos θ_j)`) plus the axial `R σ_j`, `σ_j = α̇ sin θ_j − β̇ cos θ_j`, from the
//! race's tilt rate; and the spin about the tilted axis is `θ̇_j + ½(α̇β − β̇α)` (the symmetric
//! form; the `α`-then-`β` and `β`-then-`α` tilt sequences differ from it by terms in `θ̈ τ`,
//! second order at any stationary state). With `ω = τ̇` the Lagrangian and the drag are
//!
//! ```text
//! L = ½ q̇ᵀ M q̇ + ½ Ω q̇ᵀ G q − ½ qᵀ K q + f·q
//!     + Σ_j [ ½ m_b |ċ + R θ̇_j e⊥_j|² + ½ m_b R² σ_j² + ½ m_b R² θ̇_j (ω × τ) ],
//! Q_ψj = −c_b ψ̇_j,     Q_q = −C q̇,
//! ```
//!
//! (`ω × τ = α̇β − β̇α`; the term `½ Ω q̇ᵀ G q` gives the gyroscopic `Ω G q̇`). Evenly spread
//! balls at rest make the last two terms a ring's `½ I_d |ω|²`, `I_d = n m_b R²/2`, and
//! `½ I_p Ω (α̇β − β̇α)`, `I_p = n m_b R²`: ROSS's disk (`G[α][β] = I_p`). Lagrange's equations,
//! with `a_j = c̈ + R(ψ̈_j e⊥_j − θ̇_j² e_j)` the ball's in-plane acceleration (constant `Ω`):
//!
//! ```text
//! M q̈ + (C + Ω G) q̇ + K q + Σ_j [ m_b Pᵀ a_j + T_j ] = f,        (P: q ↦ c)
//! m_b R e⊥_j·a_j + ½ m_b R² (ω̇ × τ) − m_b R² σ_j (ω·e_j) = −c_b ψ̇_j,
//! T_j = −m_b R² (σ̇_j e⊥_j − θ̇_j σ_j e_j) − ½ m_b R² θ̈_j J τ − m_b R² θ̇_j J ω   (on α, β),
//! ```
//!
//! `σ̇_j = ω̇·(sin θ_j, −cos θ_j) + θ̇_j ω·e_j`. Without tilt DOFs (or `R² → 0`) the ball equation
//! is `m_b R² ψ̈_j + m_b R (−sin θ_j ẍ_k + cos θ_j ÿ_k) = −c_b ψ̇_j`.
//!
//! This is the **fixed-axes form** ([`Frame::Fixed`]): state `(q, ψ, q̇, ψ̇)`, periodic in `t`
//! with `2π/Ω` (the unbalance force and the balls' absolute angles turn with the rotor); it is the
//! form for time simulation at constant speed. The balanced state is **not** an equilibrium of it.
//!
//! # Axes turning with the rotor
//! Each pair `(x, y)`, `(α, β)` is a plane vector and turns with the frame: `q = T(φ) p`,
//! `T` block-diagonal with 2×2 rotations `R(φ)` (complex: `u = e^{−iφ}(x + i y)`, tilt likewise),
//! `Ṫ = Ω T J`, `J` block-diagonal `[[0, −1], [1, 0]]` (multiplication by `i`), `T J = J T`.
//! Then `q̇ = T(ṗ + Ω J p)`, `q̈ = T(p̈ + 2Ω J ṗ − Ω² p)`, and with `X_r = Tᵀ X T`:
//!
//! ```text
//! M_r (p̈ + 2Ω J ṗ − Ω² p) + (C_r + Ω G_r)(ṗ + Ω J p) + K_r p + balls = Tᵀ f.
//! ```
//!
//! **Isotropic** structure (every 2×2 block of `M, C, G, K` between two pairs has the form
//! `[[a, −b], [b, a]]`, i.e. commutes with `J`: `X_r = X`): the equations are autonomous,
//!
//! ```text
//! M p̈ + (C + Ω G + 2Ω M J) ṗ + (K − Ω² M + Ω C J + Ω² G J) p + balls = f_r,
//! ```
//!
//! Coriolis `2Ω M J`, centrifugal `−Ω² M`, the rotating damping's `Ω C J` (the circulatory term
//! of damping seen from the rotor), and the gyroscopic `Ω² G J`; the unbalance force is constant,
//! `f_r = m e Ω² e^{i phase}`, and the ball terms become
//! `a_j = c̈ + 2iΩ ċ − Ω² c + R(i ψ̈_j − (Ω + ψ̇_j)²) e^{iψ_j}` (complex), with the same rule for the
//! tilt rates and accelerations (`ω = τ̇ + ΩJτ`, `ω̇ = τ̈ + 2ΩJτ̇ − Ω²τ` in turning components: the
//! ball terms are invariant under rotations), no longer depending on time.
//! The balanced state (rotor at rest in these axes, balls at rest cancelling the unbalance) is an
//! equilibrium of this form ([`Frame::Rotating`]). **Anisotropic** structure: the part of a 2×2
//! block that anticommutes with `J` turns as `e^{±2iφ}` under `R(φ)ᵀ · R(φ)`, so the field is
//! periodic with period `π/Ω` (the unbalance and the ball terms are constant in these axes).
//! [`LinearRotorField`]'s `period()` ([`crate::analysis::VectorField::period`]) returns `π/Ω`, the least period (`2π/Ω` is also one).
//!
//! # The equations as solved
//! Both frames share one residual (generalised forces minus inertia forces), with frame rate
//! `ν` (`Ω` turning, `0` fixed) and the rotor's angle in the frame `χ = (Ω − ν) t`: the ball's
//! angle in the frame is `θ_j = χ + ψ_j`, its acceleration in frame components
//! `a_j = a_c + R(i ψ̈_j − (Ω + ψ̇_j)²) e^{iθ_j}` (`a_c` the race centre's absolute acceleration in
//! the frame's components), and the unbalance force `m e Ω² e^{i(phase + χ)}`. The accelerations
//! solve `A(ψ, τ) (p̈, ψ̈) = R(p, ψ, ṗ, ψ̇)`, `A` symmetric: `M_r` plus `m_b Pᵀ P` per ball, the
//! ball columns `Pᵀ m_b R e⊥_j` and (tilt) `−½ m_b R² J τ`, `m_b R² e⊥_j e⊥_jᵀ` on the tilts,
//! `m_b R²` on the balls' diagonal. The Jacobian is
//! exact: `∂(p̈, ψ̈)/∂x = A⁻¹ ∂(R − A a)/∂x` at the current accelerations `a`, the residual
//! differentiated by forward-mode dual numbers ([`crate::ode::dual`]).
//!
//! # Presets and builders
//! - [`LinearRotor::from_planar`]: paper 004's planar rotor with its race centred (a Jeffcott
//!   rotor: one node, `M = (m1 + m2) I`, `K = k I`, `C = c I`, the disk's `m1 s1` as unbalance):
//!   equal to [`crate::planar::field::PlanarField`] at `s2 = 0`.
//! - [`LinearRotor::from_spatial`]: the rigid rotor on two supports of papers 000/003 (one node
//!   `x, y, α, β` at the centre of mass, supports as stiffness at their offsets, the balancer
//!   planes at theirs, the inertia that turns with the rotor in [`LinearRotor::rotor_fixed_mass`]):
//!   its linearisation at the balanced state equals the native
//!   [`crate::spatial::dynamics::SpatialField`]'s (the charts agree to first order; see the
//!   function's docs for where they part).
//! - [`shaft::ShaftBuilder`]: Euler–Bernoulli or Timoshenko beam elements, rigid disks, linear
//!   isotropic bearings.
//!
//! # Inertia fixed to the rotor
//! [`LinearRotor::rotor_fixed_mass`] `M_rot` is constant in axes turning with the rotor: kinetic
//! energy `½ q̇ᵀ T(φ) M_rot T(φ)ᵀ q̇`, so in the residual, in a frame in which the rotor has
//! turned by `χ`, the inertia force `M_f a + Ω (J M_f − M_f J) v` with `M_f = T(χ) M_rot T(χ)ᵀ`
//! (`a`, `v` the absolute acceleration and velocity in the frame's components), `M_f` in the
//! mass matrix, and under a torque drive the spin's torque `∂T/∂φ = q̇ᵀ J M_f q̇`. At constant
//! speed in turning axes it is autonomous (`χ = 0`): it changes neither frame's period.
//!
//! # Torque drives and gravity
//! Under a torque drive ([`runup`]) the spin angle `φ` is a coordinate: the kinetic energy adds
//! `½ I_p φ̇²` ([`LinearRotor::polar_inertia`]) and each unbalance's `m e φ̇ e⊥_u·ċ_u`
//! (`ċ_u` the velocity of its plane's centre), the gyroscopic term is `½ φ̇ q̇ᵀ G q` (which gives
//! `φ̇ G q̇ + ½ φ̈ G q` in the structure's equations; another tilt chart adds a symmetric part,
//! [`LinearRotor::spin_stiffness`] and [`LinearRotor::spin_chart`]), and the balls' absolute angles are
//! `θ_j = φ + ψ_j`. Lagrange's equation for `φ` in the coordinates `(q, φ, ψ)` is the sum of the
//! rotor's and of every ball's (`∂/∂φ̇` at fixed `ψ̇` is `∂/∂φ̇ + Σ_j ∂/∂θ̇_j`), the balls'
//! drag `−c_b ψ̇_j` does no work on it, and:
//!
//! ```text
//! I_p φ̈ + Σ_u m e e⊥_u·c̈_u + ½ q̈ᵀ G q + Σ_j I_j = M(t, φ̇) − c_θ φ̇ + Σ_u m e e⊥_u·g + Σ_j m_b R e⊥_j·g,
//! ```
//!
//! `I_j` the inertia side of ball `j`'s equation. The kinetic energy is a quadratic form in the
//! velocities `(q̇, ψ̇, φ̇)`, so without damping the energy `T + V` changes by the drive's work
//! `∫ M φ̇ dt`. [`Gravity`] is a constant load in fixed axes; in axes turning with the rotor each
//! pair of it turns as `R(−Ω t)`, the field is periodic with `2π/Ω` and the balanced state is a
//! periodic orbit (the rotor sags, the balls swing), analysed by its Floquet multipliers.

pub mod basins;
pub mod campbell;
pub mod config;
pub mod field;
pub mod npz;
pub mod partial;
pub mod reduce;
pub mod runup;
pub mod shaft;
pub mod spec;
pub mod stability;

use crate::error::{finite, non_negative, positive, Error, Result};
use crate::linalg::eigen_dyn;
use crate::planar::PlanarRotor;
use crate::spatial::dynamics::SpatialRotor;
use serde::Serialize;

pub use field::{Frame, LinearRotorField, TimeSystem};

/// The degrees of freedom of a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Layout {
    /// `x, y` per node (2 DOFs).
    Translation,
    /// `x, y, α, β` per node (4 DOFs, ROSS's order).
    TranslationTilt,
}

impl Layout {
    /// DOFs per node: 2 or 4.
    pub fn per_node(self) -> usize {
        match self {
            Layout::Translation => 2,
            Layout::TranslationTilt => 4,
        }
    }
}

/// A direction of a node's motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Direction {
    /// Translation along `x`.
    X,
    /// Translation along `y`.
    Y,
    /// Tilt `α` about `x` (`y` of a point at axial offset `z` moves by `−z α`).
    Alpha,
    /// Tilt `β` about `y` (`x` of a point at axial offset `z` moves by `z β`).
    Beta,
}

impl Direction {
    /// The four directions in their order within a node.
    pub const ALL: [Direction; 4] = [Direction::X, Direction::Y, Direction::Alpha, Direction::Beta];
    /// Offset within a node: `x 0, y 1, α 2, β 3`.
    fn offset(self) -> usize {
        match self {
            Direction::X => 0,
            Direction::Y => 1,
            Direction::Alpha => 2,
            Direction::Beta => 3,
        }
    }
    /// Symbol.
    fn symbol(self) -> &'static str {
        match self {
            Direction::X => "x",
            Direction::Y => "y",
            Direction::Alpha => "α",
            Direction::Beta => "β",
        }
    }
    /// The name in the config's DOF table (`linear_rotor.dofs`, ROSS's spelling): `x`, `y`,
    /// `alpha`, `beta` (followed there by the node number).
    pub fn key(self) -> &'static str {
        match self {
            Direction::X => "x",
            Direction::Y => "y",
            Direction::Alpha => "alpha",
            Direction::Beta => "beta",
        }
    }
}

/// A static unbalance: the force `m e Ω² e^{i(φ + phase)}` at `node` (constant speed), and
/// through the axial `offset` `z` the moments `f_α = −z F_y`, `f_β = z F_x`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Unbalance {
    /// Node index.
    pub node: usize,
    /// `m·e` (kg·m).
    pub me: f64,
    /// Angle of the unbalance in rotor axes (rad).
    pub phase: f64,
    /// Axial offset `z` of its plane from the node (m); nonzero needs the node's tilts
    /// ([`Layout::TranslationTilt`]).
    pub offset: f64,
}

/// A ball balancer plane: `balls` point balls of mass `ball_mass` on a race of radius `radius`
/// centred on `node`, each with viscous drag `drag` on its angle relative to the rotor
/// (`Q_ψ = −drag · ψ̇`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BalancerPlane {
    /// Node index.
    pub node: usize,
    /// Race radius `R` (m).
    pub radius: f64,
    /// Number of balls `n`.
    pub balls: usize,
    /// Mass of one ball `m_b` (kg).
    pub ball_mass: f64,
    /// Drag per ball `c_b` (N·m·s).
    pub drag: f64,
    /// Axial offset `z` of the race plane from the node (m): the race centre is at
    /// `(x + z β, y − z α)`; nonzero needs the node's tilts ([`Layout::TranslationTilt`]).
    pub offset: f64,
}

/// A bearing whose stiffness and damping depend on the speed: tables over `speeds` (rad/s,
/// increasing), interpolated linearly between them and held constant outside; each entry
/// `B = [xx, xy, yx, yy]` acts on the node's `(x, y)` (`K[x][y] = k_xy`, …), added to `K` and
/// `C`; with a `link` node on the difference `(x, y)_node − (x, y)_link` (ROSS's `n_link`: the
/// support its outer race sits in), the blocks `[[B, −B], [−B, B]]` on the two nodes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedBearing {
    /// Node index.
    pub node: usize,
    /// The node at the bearing's other side (`None`: ground).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub link: Option<usize>,
    /// The speeds of the table (rad/s), increasing.
    pub speeds: Vec<f64>,
    /// Stiffness `[k_xx, k_xy, k_yx, k_yy]` at each speed (N/m).
    pub k: Vec<[f64; 4]>,
    /// Damping `[c_xx, c_xy, c_yx, c_yy]` at each speed (N·s/m).
    pub c: Vec<[f64; 4]>,
}

impl SpeedBearing {
    /// `(k, c)` at speed `omega` (linear interpolation in the table, held outside).
    pub fn at(&self, omega: f64) -> ([f64; 4], [f64; 4]) {
        let s = &self.speeds;
        let last = s.len() - 1;
        let (i, f) = if omega <= s[0] {
            (0, 0.0)
        } else if omega >= s[last] {
            (last, 0.0)
        } else {
            let i = s.partition_point(|v| *v <= omega) - 1;
            (i, (omega - s[i]) / (s[i + 1] - s[i]))
        };
        let lerp = |a: &[[f64; 4]]| -> [f64; 4] {
            if f == 0.0 {
                a[i]
            } else {
                std::array::from_fn(|j| a[i][j] + f * (a[i + 1][j] - a[i][j]))
            }
        };
        (lerp(&self.k), lerp(&self.c))
    }
}

/// The structural model `M q̈ + (C + Ω G) q̇ + K q = f` in fixed axes with its unbalances and
/// balancer planes (module docs). Matrices row-major `N × N`, `N` the sum of the nodes' DOFs
/// (`nodes · layout.per_node()` where every node has `layout`), node after node in ROSS's order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearRotor {
    /// Number of nodes.
    pub nodes: usize,
    /// The DOFs of every node where [`LinearRotor::node_layouts`] is empty; with per-node
    /// layouts, the widest of them ([`LinearRotor::with_layouts`] sets both).
    pub layout: Layout,
    /// The DOFs node by node (empty: every node has [`LinearRotor::layout`]), e.g. a shaft's
    /// nodes `x, y, α, β` and the support masses of its bearings `x, y`: node `k`'s DOFs start at
    /// `Σ_{j<k} per_node(j)` ([`LinearRotor::node_start`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub node_layouts: Vec<Layout>,
    /// Mass matrix `M` (symmetric positive definite, without the balls).
    pub m: Vec<f64>,
    /// Damping matrix `C`.
    pub c: Vec<f64>,
    /// Gyroscopic matrix `G` (skew), multiplied by `Ω`.
    pub g: Vec<f64>,
    /// Stiffness matrix `K`.
    pub k: Vec<f64>,
    /// Unbalances.
    pub unbalances: Vec<Unbalance>,
    /// Balancer planes.
    pub balancers: Vec<BalancerPlane>,
    /// Bearings whose `k`, `c` depend on the speed, added to `K`, `C` at each speed.
    pub speed_bearings: Vec<SpeedBearing>,
    /// The rotor's polar moment of inertia about its spin axis `I_p` (kg·m², the unbalance
    /// masses' `m e²` included, the balls excluded): the speed's inertia under a torque drive
    /// ([`runup`]); 0: not known (torque drives are refused).
    pub polar_inertia: f64,
    /// Viscous drag on the spin `c_θ` (N·m·s): the torque `−c_θ Ω` under a torque drive.
    pub spin_damping: f64,
    /// Gravity, a constant load across the axis (`None`: none).
    pub gravity: Option<Gravity>,
    /// Real balls of each balancer plane, in order (planes beyond the list: point masses):
    /// contact and rolling resistance ([`crate::balls`]), in run-ups ([`runup`]); the
    /// stationary analyses refuse them ([`Error::NoLinearisation`]).
    pub ball_physics: Vec<crate::balls::BallPhysics>,
    /// Inertia fixed to the rotor `M_rot` (row-major `N × N`, symmetric; empty: none): a mass
    /// matrix constant in axes turning with the rotor, for the inertia that turns with it (an
    /// unbalance mass's or a rigid body's inertia anisotropy `ΔA`, paper 000's eq (17)). Its
    /// kinetic energy is `½ q̇ᵀ T(φ) M_rot T(φ)ᵀ q̇` in fixed axes (`T(φ)` the block rotation
    /// of every pair `(x, y)`, `(α, β)` by the rotor's angle `φ`), so it adds to the structure's
    /// inertia forces `T(φ) [M_rot a_r + φ̇ (J M_rot − M_rot J) v_r]` (`a_r = T(φ)ᵀ q̈`,
    /// `v_r = T(φ)ᵀ q̇`; in axes turning with the rotor at constant speed
    /// `M_rot p̈ + Ω (M_rot J + J M_rot) ṗ + Ω² J M_rot J p`) and, under a torque drive, the
    /// torque `½ v_rᵀ (J M_rot − M_rot J) v_r` to the spin's equation (`−∂T/∂φ`). `M` is the
    /// part fixed in space: `M + T(φ) M_rot T(φ)ᵀ` must be positive definite at every `φ`.
    /// Used by the time and stationary analyses of [`LinearRotorField`] and [`runup`];
    /// [`LinearRotor::natural_frequencies`] takes it at rest in the rotor's angle 0 (`M + M_rot`),
    /// [`LinearRotor::ball_mass_matrix`] leaves it out; model reduction projects it ([`reduce`]); configs read
    /// it as `linear_rotor.rotor_fixed_mass` ([`config`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rotor_fixed_mass: Vec<f64>,
    /// The angular-acceleration stiffness `K_st` of rotordynamics FE codes (ROSS's `Ksdt`;
    /// row-major `N × N`, fixed axes; empty: `½ G`): the structure's equations under a changing
    /// speed are `M q̈ + (C + Ω G) q̇ + (K + Ω̇ K_st) q = f`. It comes from the kinetic energy's
    /// `½ φ̇ q̇ᵀ G' q` (`φ` the rotor's angle), which gives `Ω ½(G' − G'ᵀ) q̇ + ½ Ω̇ G' q`: so
    /// `K_st = ½ G'` with `K_st − K_stᵀ = G`, and its symmetric part is the choice of the tilt
    /// chart (what "the rotor's angle" means for a tilted rotor; `½ G`, no symmetric part, is
    /// the symmetric chart of the module docs, a sequence `R_x(α) R_y(β)` of a disk of polar
    /// moment `I_p` has `K_st[α][β] = I_p`). Under a torque drive ([`runup`]) the spin's equation
    /// gets the matching `q̈ᵀ K_st q + q̇ᵀ K_st q̇` (`d/dt ∂T/∂φ̇`), so that energy is conserved
    /// when `K_st − K_stᵀ = G`; a matrix that does not satisfy it (ROSS's `Ksdt` has
    /// `Ksdt − Ksdtᵀ = −G` for its disks, and its shaft elements leave out the shear terms of
    /// their `G`) gives the FE code's equations under a prescribed speed, but no Lagrangian.
    /// Constant-speed analyses do not see it.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub spin_stiffness: Vec<f64>,
    /// A tilt chart fixed to the rotor `Σ` (row-major `N × N`, symmetric; empty: none): the
    /// rotor's angle in the symmetric chart of the module docs is `φ + s`, `s = ½ q_rᵀ Σ q_r` (`q_r = T(φ)ᵀ q` the
    /// coordinates in the rotor's axes), the same for the rotor and for its balls, so the
    /// kinetic energy gains `(I_p φ̇ + Σ_j m_b R² θ̇_j) ṡ` ([`LinearRotor::polar_inertia`] `I_p`;
    /// `θ_j = φ + ψ_j`). Then, with `Σ_f = T(φ) Σ T(φ)ᵀ`, the structure's equations gain
    /// `(I_p Ω̇ + Σ_j m_b R² θ̈_j) Σ_f q` (an angular-acceleration stiffness `I_p Σ_f` that turns
    /// with the rotor, plus the balls'), each ball's `m_b R² s̈`, and under a torque drive the
    /// spin's `(I_p + Σ_j m_b R²) s̈ + (I_p φ̈ + Σ_j m_b R² θ̈_j) ∂s/∂φ` (Lagrange's equations of
    /// that term; the total derivative `I_p Ω ṡ` it adds at constant speed changes nothing
    /// there, the balls' `m_b R² ψ̇_j ṡ` acts at second order in the amplitudes). A native
    /// chart `R_x(δ) R_y(θ)` in the rotor's axes is `s = δθ/2`: `Σ[α][β] = Σ[β][α] = ½`
    /// ([`LinearRotor::from_spatial`]). Read from configs (`linear_rotor.spin_chart`), written by
    /// `export-model` and reduced (`Bᵀ Σ B`: the reduction basis is closed under the quarter turn).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub spin_chart: Vec<f64>,
}

/// Gravity across the axis: the acceleration `g = (g_x, g_y)` (m/s², fixed axes) and the
/// structure's weight `load` (N, length `N`), `M r_g` for a structure that can translate
/// rigidly (`r_g` the rigid translation by `g`: `g_x` on every `x`, `g_y` on every `y`, 0 on the
/// tilts; the consistent load of the beam elements and the exact one of lumped masses), the
/// same projected (`Bᵀ load`) for a reduced rotor. The balls' weight `m_b g` acts on their race
/// centre and gives each ball the torque `m_b R e⊥_j·g` about the axis; the unbalances' weight
/// is in `load` (their masses are in `M`), and under a torque drive gives the spin the torque
/// `Σ m e e⊥·g` (`e⊥ = (−sin θ_u, cos θ_u)`, `θ_u` the unbalance's angle). The potential is
/// `V_g = −loadᵀ q − Σ_j m_b g·(c + R e_j) − Σ m e g·e_u`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Gravity {
    /// `(g_x, g_y)` (m/s²) in fixed axes.
    pub g: [f64; 2],
    /// The structure's weight on each DOF (N, N·m on the tilts).
    pub load: Vec<f64>,
}

/// Largest number of DOFs accepted (dense matrices of `N²` entries).
pub const MAX_DOFS: usize = 2000;

/// The constant `c` of the divergence threshold `c · N · ε · max|ω²|` ([`divergence_threshold`]).
pub const DIVERGENCE_ROUNDING: f64 = 100.0;

/// Below this fraction of `max|ω²|` a negative `ω²` is not told from 0 ([`divergence_threshold`]):
/// the rounding of the matrices' data, not the solver's.
pub const DATA_ROUNDING: f64 = 1e-9;

/// The largest `|ω²|` that rounding can give a mode whose true `ω²` is 0 (a rigid-body mode)
/// in [`LinearRotor::natural_frequencies_squared`]'s eigenvalues `omega_squared` (all of them,
/// `N` = their number): `max(DATA_ROUNDING, DIVERGENCE_ROUNDING · N · ε) · max|ω²|`.
///
/// Two roundings. The solver's: it is backward stable, the computed eigenvalues exact for
/// `S + E` with `‖E‖₂ ≲ c₀ N ε ‖S‖₂` (the Hessenberg QR's backward error: Golub & Van Loan,
/// *Matrix Computations*), `S = L⁻¹ K L⁻ᵀ` symmetric up to that rounding, so by Bauer–Fike each
/// eigenvalue moves by at most `‖E‖₂`, `‖S‖₂ = max|ω²|`; the factor
/// [`DIVERGENCE_ROUNDING`] = 100 covers `c₀` and the congruence's rounding. Measured on matrices
/// built in memory (free shafts of 8 to 804 DOFs, ROSS's `rotor_example` without bearings, a
/// 2-DOF semi-definite `K`): rigid-body modes within 2.4e-16 of `max|ω²|`. The data's: matrix
/// files written to 8-10 significant digits (fixed-width FE exports) are not exactly
/// semi-definite, and a free rotor's rigid-body modes then come out genuinely negative
/// (review 23: a free stepped shaft, 400 kg disk, `max|ω²|` 3.07e9, its exported M and K
/// rounded to 10, 9, 8 digits: `ω² = −0.005`, `−0.047`, `−0.78`, up to 2.5e-10 of `max|ω²|`;
/// the solver's bound alone, 8e-3 there, called that rotor statically unstable). The data's
/// precision is not known, so [`DATA_ROUNDING`] = 1e-9 (data to 8 digits, with a margin of 4)
/// is the floor, the rule of session 22: on a rotor whose stiffest mode is 1.3e10 (rad/s)² a
/// mode at `ω² = −1.34` (growing at 1.16 1/s, review 22) reads "0 rad/s" still, and on a
/// 804-DOF fine mesh whose `max|ω²|` is 1.5e13 so does one at −85 (review 23): a true `ω²`
/// closer to 0 than the threshold is not told from 0 (docs/guide/your-own-rotor.md). With at most
/// 2000 DOFs (`MAX_DOFS`) the solver's term is below 4.4e-11: the data's decides.
pub fn divergence_threshold(omega_squared: &[f64]) -> f64 {
    let scale = omega_squared.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    DATA_ROUNDING.max(DIVERGENCE_ROUNDING * omega_squared.len() as f64 * f64::EPSILON) * scale
}

/// The divergent modes at rest among `omega_squared` ([`LinearRotor::natural_frequencies_squared`]):
/// the `ω² < −`[`divergence_threshold`]`(omega_squared)`, ascending (the most negative first).
/// Each is a static instability: `q̈ = −ω² q` grows as `exp(sqrt(−ω²) t)`, the stiffness matrix
/// `K` not positive semi-definite. Empty for a positive semi-definite `K` (a rigid-body mode's
/// `ω² ≈ 0` of either sign is not one).
pub fn static_divergence(omega_squared: &[f64]) -> Vec<f64> {
    let threshold = divergence_threshold(omega_squared);
    omega_squared.iter().copied().filter(|v| *v < -threshold).collect()
}

impl LinearRotor {
    /// A structure of `nodes` nodes with zero matrices, no unbalance and no balancer.
    pub fn zeros(nodes: usize, layout: Layout) -> Self {
        let n = nodes * layout.per_node();
        LinearRotor {
            nodes,
            layout,
            node_layouts: vec![],
            m: vec![0.0; n * n],
            c: vec![0.0; n * n],
            g: vec![0.0; n * n],
            k: vec![0.0; n * n],
            unbalances: vec![],
            balancers: vec![],
            speed_bearings: vec![],
            polar_inertia: 0.0,
            spin_damping: 0.0,
            gravity: None,
            ball_physics: vec![],
            rotor_fixed_mass: vec![],
            spin_stiffness: vec![],
            spin_chart: vec![],
        }
    }

    /// The angular-acceleration stiffness `K_st` ([`LinearRotor::spin_stiffness`]), `½ G` where
    /// none is given (row-major `N × N`).
    pub fn spin_stiffness_matrix(&self) -> std::borrow::Cow<'_, [f64]> {
        if self.spin_stiffness.is_empty() {
            std::borrow::Cow::Owned(self.g.iter().map(|g| 0.5 * g).collect())
        } else {
            std::borrow::Cow::Borrowed(&self.spin_stiffness)
        }
    }

    /// A structure with the nodes' DOFs `layouts` (one per node), zero matrices, no unbalance
    /// and no balancer: [`LinearRotor::zeros`] where all are alike (`node_layouts` empty), else
    /// `node_layouts = layouts` and `layout` the widest.
    pub fn with_layouts(layouts: &[Layout]) -> Self {
        let first = layouts.first().copied().unwrap_or(Layout::TranslationTilt);
        if layouts.iter().all(|l| *l == first) {
            return LinearRotor::zeros(layouts.len(), first);
        }
        let mut r = LinearRotor::zeros(0, Layout::TranslationTilt);
        r.nodes = layouts.len();
        r.node_layouts = layouts.to_vec();
        let n = r.dofs();
        for a in [&mut r.m, &mut r.c, &mut r.g, &mut r.k] {
            *a = vec![0.0; n * n];
        }
        r
    }

    /// The DOFs of node `k` ([`LinearRotor::node_layouts`], else [`LinearRotor::layout`]).
    pub fn node_layout(&self, k: usize) -> Layout {
        self.node_layouts.get(k).copied().unwrap_or(self.layout)
    }

    /// Index of node `k`'s first DOF (its `x`): `Σ_{j<k} per_node(j)`.
    pub fn node_start(&self, k: usize) -> usize {
        if self.node_layouts.is_empty() {
            k * self.layout.per_node()
        } else {
            self.node_layouts[..k.min(self.node_layouts.len())].iter().map(|l| l.per_node()).sum()
        }
    }

    /// [`LinearRotor::node_start`] of every node.
    pub fn node_starts(&self) -> Vec<usize> {
        (0..self.nodes)
            .scan(0, |start, k| {
                let s = *start;
                *start += self.node_layout(k).per_node();
                Some(s)
            })
            .collect()
    }

    /// The node and direction of DOF `i` (`None` past the last DOF).
    pub fn dof_node(&self, i: usize) -> Option<(usize, Direction)> {
        if self.node_layouts.is_empty() {
            let per = self.layout.per_node();
            return (i < self.dofs()).then(|| (i / per, Direction::ALL[i % per]));
        }
        let mut start = 0;
        for (k, l) in self.node_layouts.iter().enumerate() {
            if i < start + l.per_node() {
                return Some((k, Direction::ALL[i - start]));
            }
            start += l.per_node();
        }
        None
    }

    /// The DOFs `(x, y)` of node `k` and its tilts `(α, β)` where it has them (the place of a
    /// balancer plane, an unbalance or a bearing).
    pub fn node_dofs(&self, k: usize) -> (usize, usize, Option<(usize, usize)>) {
        let s = self.node_start(k);
        (s, s + 1, (self.node_layout(k) == Layout::TranslationTilt).then_some((s + 2, s + 3)))
    }

    /// Set gravity `g = (g_x, g_y)` (m/s², fixed axes) with the weight `M r_g` ([`Gravity`]);
    /// `g = (0, 0)` removes it.
    pub fn set_gravity(&mut self, g: [f64; 2]) {
        if g == [0.0, 0.0] {
            self.gravity = None;
            return;
        }
        let n = self.dofs();
        let r: Vec<f64> = (0..n)
            .map(|i| match self.dof_node(i).map(|d| d.1) {
                Some(Direction::X) => g[0],
                Some(Direction::Y) => g[1],
                _ => 0.0,
            })
            .collect();
        let load = (0..n).map(|i| (0..n).map(|j| self.m[i * n + j] * r[j]).sum()).collect();
        self.gravity = Some(Gravity { g, load });
    }

    /// A Jeffcott rotor: one node (`x, y`), `M = m I`, `K = k I`, `C = c I`, `G = 0`, one
    /// unbalance `me` at phase 0 and one balancer plane.
    pub fn jeffcott(mass: f64, k: f64, c: f64, me: f64, balancer: BalancerPlane) -> Self {
        let mut r = LinearRotor::zeros(1, Layout::Translation);
        for i in 0..2 {
            r.m[i * 3] = mass;
            r.k[i * 3] = k;
            r.c[i * 3] = c;
        }
        r.unbalances.push(Unbalance { node: 0, me, phase: 0.0, offset: 0.0 });
        r.balancers.push(BalancerPlane { node: 0, offset: 0.0, ..balancer });
        r
    }

    /// Paper 004's planar rotor with its race centred (`s2 = 0`): the Jeffcott rotor with
    /// `M = (m1 + m2) I` (the balls' `n m3` come with the balancer), `K = k I`, `C = c I`, the
    /// disk's eccentric mass as the unbalance `m·e = m1 s1` at phase 0 (exact at constant speed:
    /// the disk's inertia force `m1 (ü + 2iΩu̇ − Ω²(u + s1))` is `m1 ü + …` plus the unbalance
    /// force `m1 s1 Ω²`), and the balancer `(r, n, m3, c_ψ)`; the spin's polar moment
    /// `I_p = I_G + m1 s1²` and drag `c_θ` for torque drives (the kinetic energy in fixed axes
    /// is then the planar model's term by term). Real balls carry over ([`LinearRotor::ball_physics`]). Errors: `planar.s2` nonzero, or the rotor's own checks.
    pub fn from_planar(p: &PlanarRotor) -> Result<Self> {
        p.validate()?;
        if p.s2 != 0.0 {
            return Err(Error::invalid("planar.s2", "the linear rotor's race is centred on the node: s2 must be 0"));
        }
        if p.anisotropic() {
            return Err(Error::invalid("planar.k_y", "the linear rotor's Jeffcott form has equal supports: k_x = k_y and c_x = c_y"));
        }
        if !p.equal_balls() {
            return Err(Error::invalid("planar.ball_masses", "the linear rotor's balancer has equal balls: give m3 and c_psi"));
        }
        let mut r = LinearRotor::jeffcott(
            p.m1 + p.m2,
            p.k,
            p.c,
            p.m1 * p.s1,
            BalancerPlane { node: 0, radius: p.r, balls: p.n, ball_mass: p.m3, drag: p.c_psi, offset: 0.0 },
        );
        // the spin under a torque drive: the disk's I_G about its centre of mass plus m1 s1²
        // about the shaft (the kinetic energy ½(I_G + m1 s1²) θ̇² of the planar model)
        r.polar_inertia = p.i_g + p.m1 * p.s1 * p.s1;
        r.spin_damping = p.c_theta;
        if p.balls.is_active() {
            r.ball_physics = vec![p.balls];
        }
        Ok(r)
    }

    /// The rigid rotor on one or two supports of papers 000/003 ([`SpatialRotor`], the native
    /// model of [`crate::spatial::dynamics`]) as a one-node rotor.
    ///
    /// **Coordinates.** The node is the native reference point O, the common centre of mass C
    /// of the rotor with its balls at balance (`z_C` = [`SpatialRotor::z_reference`]); every
    /// axial position becomes the offset `ζ = z − z_C`. The native state in axes turning with
    /// the rotor, `(ξ, η, δ, θ, ψ_j)` with the tilt `R_x(δ) R_y(θ)` relative to those axes, maps
    /// to this model's `(x, y, α, β, ψ_j)` in [`Frame::Rotating`] one to one to first order (a
    /// shaft point at `ζ` sits at `(ξ + ζ sin θ, η − ζ sin δ cos θ)`, here `(x + ζ β, y − ζ α)`;
    /// `ψ_j` is the ball's angle from the rotor's x axis in both), so the two linearisations at a
    /// stationary state with the rotor on the axis are the same matrices. Beyond first order the
    /// charts differ: the sequence `R_x(δ) R_y(θ)` is the rotation vector `(δ, θ, δθ/2)`, i.e.
    /// the native spin angle is the symmetric chart's less `δθ/2`; the preset carries that
    /// chart ([`LinearRotor::spin_chart`] `Σ[α][β] = Σ[β][α] = ½`), without which a changing
    /// speed would leave the moment `½ C Ω̇ τ` between the two (first order in the amplitude).
    /// The native model is exact in the tilt and displacement where this one keeps the kinetic
    /// energy to second order, so time histories, run-ups included, agree to second order in
    /// the amplitudes, not to round-off.
    ///
    /// **Carrier.** The rotor with its unbalance masses is a rigid body with mass `M_c`, first
    /// moment `s = (s_x, s_y, s_z)` and inertia tensor `J` about O in rotor axes (the rotor's
    /// `A_r I + (C_r − A_r) e eᵀ` about G, `e` its tilted principal axis, moved to O, plus each
    /// unbalance mass). Its kinetic energy to second order in the small motions, with the body's
    /// rates `ω_⊥ = τ̇ + Ω J τ` across the axis and `ω_3 = Ω (1 − |τ|²/2) + δ̇ θ`, is
    /// `½ M_c |ċ|² + s_z ċ·(β̇, −α̇) + ½ ω_⊥ᵀ J_⊥ ω_⊥ + ½ J_33 ω_3² + Ω (J_13, J_23)·ω_⊥`:
    /// - `M`: `M_c` on `x, y`, `M[x][β] = s_z`, `M[y][α] = −s_z`, the mean `A = (J_11 + J_22)/2`
    ///   on `α, β`;
    /// - [`LinearRotor::rotor_fixed_mass`]: the rest of `J_⊥`, `[[J_11 − A, J_12], [J_12, J_22 − A]]`
    ///   on `α, β` (the inertia anisotropy `ΔA` of paper 000's eq (17) that turns with the rotor);
    /// - `G[α][β] = −G[β][α] = J_33`, also [`LinearRotor::polar_inertia`] (its `½ Ω q̇ᵀ G q`
    ///   equals `½ J_33 ω_3²` to second order up to the time derivative `½ J_33 Ω d(δθ)/dt`);
    /// - the lateral first moment and `(J_13, J_23)` enter only linearly: each unbalance mass is
    ///   an [`Unbalance`] `m ρ` at its angle and offset `ζ` (whose couple is its `−J_13, −J_23`), and
    ///   the tilted principal axis's products `(C_r − A_r) sin κ cos κ (cos β_κ, sin β_κ)` are a
    ///   pair of opposite unbalances at offsets `±1` m (a pure couple).
    ///
    /// **Supports** at offsets `ζ`: `k_x`, `c_x` on `x + ζ β` and `k_y`, `c_y` on `y − ζ α` (fixed
    /// axes, so direction-dependent supports are anisotropic `K`, `C`). **Balls**: one
    /// [`BalancerPlane`] per plane with balls, at offset `ζ_p`, drag `h_A R²` (the native force
    /// `h_A R ψ̇` on the race). Spin drag [`SpatialRotor::spin_drag`] becomes
    /// [`LinearRotor::spin_damping`]; gravity across the axis the load `M r_g` ([`LinearRotor::set_gravity`]).
    /// With the tilt locked ([`SpatialRotor::lock_tilt`]) the node has `x, y` only.
    ///
    /// Errors: the rotor's own checks, gravity along the axis (`spatial.gravity[2]`, which this
    /// model does not carry).
    pub fn from_spatial(s: &SpatialRotor) -> Result<Self> {
        s.validate()?;
        if s.gravity[2] != 0.0 {
            return Err(Error::invalid("spatial.gravity[2]", "the linear rotor carries gravity across the axis only: set it to 0"));
        }
        let zc = s.z_reference();
        let r = &s.rotor;
        // the carrier about O in rotor axes (as the native model's carrier)
        let (sk, ck) = r.axis_tilt.sin_cos();
        let (sb, cb) = r.axis_tilt_angle.sin_cos();
        let e = [sk * cb, sk * sb, ck];
        let mut j = [[0.0; 3]; 3];
        for (a, row) in j.iter_mut().enumerate() {
            for (b, v) in row.iter_mut().enumerate() {
                *v = if a == b { r.equatorial_moment } else { 0.0 } + (r.polar_moment - r.equatorial_moment) * e[a] * e[b];
            }
        }
        // products of the rotor's own tensor (before the point masses): a pure couple
        let own_products = [j[0][2], j[1][2]];
        let point = |j: &mut [[f64; 3]; 3], m: f64, p: [f64; 3]| {
            let p2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
            for a in 0..3 {
                for b in 0..3 {
                    j[a][b] += m * (if a == b { p2 } else { 0.0 } - p[a] * p[b]);
                }
            }
        };
        let zr = r.z - zc;
        point(&mut j, r.mass, [0.0, 0.0, zr]);
        let (mut mc, mut sz) = (r.mass, r.mass * zr);
        let mut unbalances = vec![];
        for u in &s.unbalances {
            let zeta = u.z - zc;
            point(&mut j, u.mass, [u.radius * u.angle.cos(), u.radius * u.angle.sin(), zeta]);
            mc += u.mass;
            sz += u.mass * zeta;
            unbalances.push(Unbalance { node: 0, me: u.mass * u.radius, phase: u.angle, offset: zeta });
        }
        let mut planes = vec![];
        let mut physics = vec![];
        for p in s.planes.iter().filter(|p| p.n > 0) {
            planes.push(BalancerPlane {
                node: 0,
                radius: p.race_radius,
                balls: p.n,
                ball_mass: p.ball_mass,
                drag: p.drag * p.race_radius * p.race_radius,
                offset: p.z - zc,
            });
            physics.push(p.physics);
        }
        let mut lr = if s.lock_tilt {
            let mut lr = LinearRotor::zeros(1, Layout::Translation);
            for i in 0..2 {
                lr.m[i * 3] = mc;
                for sup in &s.supports {
                    lr.k[i * 3] += sup.stiffness[i];
                    lr.c[i * 3] += sup.damping[i];
                }
            }
            for u in &mut unbalances {
                u.offset = 0.0;
            }
            for b in &mut planes {
                b.offset = 0.0;
            }
            lr
        } else {
            let mut lr = LinearRotor::zeros(1, Layout::TranslationTilt);
            let n = 4;
            let a = 0.5 * (j[0][0] + j[1][1]);
            let mm = [[mc, 0.0, 0.0, sz], [0.0, mc, -sz, 0.0], [0.0, -sz, a, 0.0], [sz, 0.0, 0.0, a]];
            for i in 0..n {
                for k in 0..n {
                    lr.m[i * n + k] = mm[i][k];
                }
            }
            let mut mrot = vec![0.0; n * n];
            mrot[2 * n + 2] = j[0][0] - a;
            mrot[2 * n + 3] = j[0][1];
            mrot[3 * n + 2] = j[1][0];
            mrot[3 * n + 3] = j[1][1] - a;
            if mrot.iter().any(|v| *v != 0.0) {
                lr.rotor_fixed_mass = mrot;
            }
            lr.g[2 * n + 3] = j[2][2];
            lr.g[3 * n + 2] = -j[2][2];
            // the native tilt R_x(δ) R_y(θ) in the rotor's axes: the rotation vector
            // (δ, θ, δθ/2): the rotor's angle in the symmetric chart is the native one plus
            // s = δθ/2 (LinearRotor::spin_chart)
            lr.spin_chart = vec![0.0; n * n];
            lr.spin_chart[2 * n + 3] = 0.5;
            lr.spin_chart[3 * n + 2] = 0.5;
            for sup in &s.supports {
                let z = sup.z - zc;
                // x + ζ β with k_x, c_x; y − ζ α with k_y, c_y
                for (d, rows) in [(0, [(0, 1.0), (3, z)]), (1, [(1, 1.0), (2, -z)])] {
                    for &(i, ci) in &rows {
                        for &(k, ckk) in &rows {
                            lr.k[i * n + k] += sup.stiffness[d] * ci * ckk;
                            lr.c[i * n + k] += sup.damping[d] * ci * ckk;
                        }
                    }
                }
            }
            // the tilted principal axis's products (J_13, J_23) as two opposite unbalances at
            // offsets ±1 m: −Σ m e z e_u = (J_13, J_23) (module docs of from_spatial)
            let pc = own_products[0].hypot(own_products[1]);
            if pc > 0.0 {
                let phase = (-own_products[1]).atan2(-own_products[0]);
                unbalances.push(Unbalance { node: 0, me: 0.5 * pc, phase, offset: 1.0 });
                unbalances.push(Unbalance { node: 0, me: 0.5 * pc, phase: phase + std::f64::consts::PI, offset: -1.0 });
            }
            lr
        };
        lr.unbalances = unbalances;
        lr.balancers = planes;
        if physics.iter().any(|p| p.is_active()) {
            lr.ball_physics = physics;
        }
        lr.polar_inertia = j[2][2];
        lr.spin_damping = s.spin_drag;
        lr.set_gravity([s.gravity[0], s.gravity[1]]);
        lr.validate()?;
        Ok(lr)
    }

    /// `C(Ω)` and `K(Ω)`: `C`, `K` plus the speed-dependent bearings at `omega`.
    pub fn damping_stiffness_at(&self, omega: f64) -> (Vec<f64>, Vec<f64>) {
        let (mut c, mut k) = (self.c.clone(), self.k.clone());
        for b in &self.speed_bearings {
            let (kb, cb) = b.at(omega);
            self.add_bearing_block(b.node, b.link, &kb, &mut k);
            self.add_bearing_block(b.node, b.link, &cb, &mut c);
        }
        (c, k)
    }

    /// Add a bearing's 2×2 block `B = [xx, xy, yx, yy]` to the row-major `N × N` matrix `a`:
    /// `B` on `node`'s `(x, y)`, and with a `link` node `−B` on (node, link) and (link, node)
    /// and `B` on the link's `(x, y)` ([`SpeedBearing`]).
    pub(crate) fn add_bearing_block(&self, node: usize, link: Option<usize>, blk: &[f64; 4], a: &mut [f64]) {
        let n = self.dofs();
        let i = self.node_start(node);
        let mut put = |r0: usize, c0: usize, s: f64| {
            for (j, (r, col)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
                a[(r0 + r) * n + c0 + col] += s * blk[j];
            }
        };
        put(i, i, 1.0);
        if let Some(l) = link {
            let l = self.node_start(l);
            put(i, l, -1.0);
            put(l, i, -1.0);
            put(l, l, 1.0);
        }
    }

    /// The rotor at speed `omega` with its speed-dependent bearings folded into `C` and `K`
    /// (and removed from the list).
    pub fn at_speed(&self, omega: f64) -> LinearRotor {
        let (c, k) = self.damping_stiffness_at(omega);
        LinearRotor { c, k, speed_bearings: vec![], ..self.clone() }
    }

    /// Number of structural DOFs `N`.
    pub fn dofs(&self) -> usize {
        if self.node_layouts.is_empty() {
            self.nodes * self.layout.per_node()
        } else {
            self.node_layouts.iter().map(|l| l.per_node()).sum()
        }
    }

    /// `T(φ) M_rot T(φ)ᵀ`: the rotor-fixed inertia ([`LinearRotor::rotor_fixed_mass`]) in the
    /// axes from which the rotor has turned by `φ` (row-major `N × N`; zeros when there is none).
    pub fn rotor_fixed_in(&self, phi: f64) -> Vec<f64> {
        let n = self.dofs();
        if self.rotor_fixed_mass.is_empty() {
            return vec![0.0; n * n];
        }
        turn_blocks(&self.rotor_fixed_mass, n, phi)
    }

    /// Index of DOF `(node, direction)`: `node_start(node) + offset` (`x 0, y 1, α 2, β 3`),
    /// `None` where the node has no such DOF (a tilt of an `x, y` node, or no such node).
    pub fn dof(&self, node: usize, dir: Direction) -> Option<usize> {
        (node < self.nodes && dir.offset() < self.node_layout(node).per_node()).then(|| self.node_start(node) + dir.offset())
    }

    /// Name of DOF `i`, e.g. `"node 3 α"` (`"DOF i"` past the last).
    pub fn dof_name(&self, i: usize) -> String {
        match self.dof_node(i) {
            Some((k, dir)) => format!("node {k} {}", dir.symbol()),
            None => format!("DOF {i}"),
        }
    }

    /// Total number of balls `Σ n` over the balancer planes.
    pub fn total_balls(&self) -> usize {
        self.balancers.iter().map(|b| b.balls).sum()
    }

    /// Check every field; errors name it (`linear_rotor.m[2,3]`, `linear_rotor.balancers[0].radius`, …).
    pub fn validate(&self) -> Result<()> {
        if self.nodes == 0 {
            return Err(Error::invalid("linear_rotor.nodes", "must be at least 1"));
        }
        if !self.node_layouts.is_empty() {
            if self.node_layouts.len() != self.nodes {
                return Err(Error::invalid("linear_rotor.node_layouts", format!("has {} entries, one per node: {}", self.node_layouts.len(), self.nodes)));
            }
            let widest = if self.node_layouts.contains(&Layout::TranslationTilt) { Layout::TranslationTilt } else { Layout::Translation };
            if self.layout != widest {
                return Err(Error::invalid("linear_rotor.layout", format!("must be the widest of node_layouts, {widest:?}")));
            }
        }
        let n = self.dofs();
        if n > MAX_DOFS {
            return Err(Error::TooLarge { what: "linear_rotor DOFs".into(), size: n as u64, limit: MAX_DOFS as u64, reason: "dense matrices".into() });
        }
        for (name, a) in [("m", &self.m), ("c", &self.c), ("g", &self.g), ("k", &self.k)] {
            if a.len() != n * n {
                return Err(Error::invalid(format!("linear_rotor.{name}"), format!("has {} entries, N² = {} for N = {n} DOFs", a.len(), n * n)));
            }
            for (i, v) in a.iter().enumerate() {
                finite(&format!("linear_rotor.{name}[{},{}]", i / n, i % n), *v)?;
            }
        }
        non_negative("linear_rotor.polar_inertia", self.polar_inertia)?;
        non_negative("linear_rotor.spin_damping", self.spin_damping)?;
        if let Some(g) = &self.gravity {
            finite("linear_rotor.gravity[0]", g.g[0])?;
            finite("linear_rotor.gravity[1]", g.g[1])?;
            if g.load.len() != n {
                return Err(Error::invalid("linear_rotor.gravity.load", format!("has {} entries, one per DOF: {n}", g.load.len())));
            }
            for (i, v) in g.load.iter().enumerate() {
                finite(&format!("linear_rotor.gravity.load[{i}]"), *v)?;
            }
        }
        let scale = |a: &[f64]| a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let (sm, sg) = (scale(&self.m), scale(&self.g));
        for i in 0..n {
            for j in 0..i {
                if (self.m[i * n + j] - self.m[j * n + i]).abs() > 1e-12 * sm {
                    return Err(Error::invalid(format!("linear_rotor.m[{i},{j}]"), format!("must equal m[{j},{i}] (M symmetric)")));
                }
            }
            for j in 0..=i {
                if (self.g[i * n + j] + self.g[j * n + i]).abs() > 1e-12 * sg {
                    return Err(Error::invalid(format!("linear_rotor.g[{i},{j}]"), format!("must equal −g[{j},{i}] (G skew)")));
                }
            }
        }
        if let Err(i) = cholesky(&self.m, n) {
            return Err(Error::invalid("linear_rotor.m", format!("is not positive definite (pivot {i}, {})", self.dof_name(i))));
        }
        if !self.rotor_fixed_mass.is_empty() {
            let a = &self.rotor_fixed_mass;
            if a.len() != n * n {
                return Err(Error::invalid("linear_rotor.rotor_fixed_mass", format!("has {} entries, N² = {} for N = {n} DOFs", a.len(), n * n)));
            }
            for (i, v) in a.iter().enumerate() {
                finite(&format!("linear_rotor.rotor_fixed_mass[{},{}]", i / n, i % n), *v)?;
            }
            let sa = scale(a);
            for i in 0..n {
                for j in 0..i {
                    if (a[i * n + j] - a[j * n + i]).abs() > 1e-12 * sa {
                        return Err(Error::invalid(
                            format!("linear_rotor.rotor_fixed_mass[{i},{j}]"),
                            format!("must equal rotor_fixed_mass[{j},{i}] (symmetric)"),
                        ));
                    }
                }
            }
            // M + T(φ) M_rot T(φ)ᵀ = A0 + T(2φ) Q, A0 = M + P, P = (M_rot + Jᵀ M_rot J)/2 the part
            // of M_rot that commutes with J, Q = M_rot − P the part that anticommutes
            // (T(φ) Q T(φ)ᵀ = T(2φ) Q). Where M commutes with J the spectrum does not depend on φ
            // (T(φ)ᵀ (M + T(φ) M_rot T(φ)ᵀ) T(φ) = M + M_rot): φ = 0 decides. Otherwise, for each
            // x, xᵀ(…)x = a + b cos 2φ + d sin 2φ is positive at every φ iff a > √(b² + d²);
            // at the angles 2φ_k = 2πk/K, cos(π/K) A0 + T(2φ_k) Q positive definite for every k
            // implies it (the sample nearest the minimum is within π/K of it), A0 + T(2φ_k) Q
            // positive definite is necessary: K = 8, then 64; a matrix that neither decides is
            // within 1 − cos(π/64) = 0.12 % of singular at some angle, and refused as such.
            let per_pair = |a: &[f64]| {
                (0..n * n).all(|ij| {
                    let (i, j) = (ij / n, ij % n);
                    let (pi, si) = if i % 2 == 0 { (i + 1, 1.0) } else { (i - 1, -1.0) };
                    let (pj, sj) = if j % 2 == 0 { (j + 1, 1.0) } else { (j - 1, -1.0) };
                    (a[ij] - si * sj * a[pi * n + pj]).abs() <= 1e-12 * sm
                })
            };
            let refuse = |phi: f64, i: usize| {
                Error::invalid(
                    "linear_rotor.rotor_fixed_mass",
                    format!("M + T(φ) M_rot T(φ)ᵀ is not positive definite at φ = {phi:.4} (pivot {i}, {})", self.dof_name(i)),
                )
            };
            // c M + T(φ) M_rot T(φ)ᵀ − (1 − c) P = c A0 + T(2φ) Q
            let p: Vec<f64> = self.rotor_fixed_in(0.0).iter().zip(self.rotor_fixed_in(std::f64::consts::FRAC_PI_2)).map(|(a, b)| 0.5 * (a + b)).collect();
            let at = |phi: f64, c: f64| -> Vec<f64> {
                let t = self.rotor_fixed_in(phi);
                (0..n * n).map(|ij| c * self.m[ij] + t[ij] - (1.0 - c) * p[ij]).collect()
            };
            if per_pair(&self.m) {
                cholesky(&at(0.0, 1.0), n).map_err(|i| refuse(0.0, i))?;
            } else {
                let mut decided = false;
                for k in [8usize, 64] {
                    let angles = (0..k).map(|j| std::f64::consts::PI * j as f64 / k as f64);
                    let c = (std::f64::consts::PI / k as f64).cos();
                    if angles.clone().all(|phi| cholesky(&at(phi, c), n).is_ok()) {
                        decided = true;
                        break;
                    }
                    for phi in angles {
                        cholesky(&at(phi, 1.0), n).map_err(|i| refuse(phi, i))?;
                    }
                }
                if !decided {
                    return Err(Error::invalid(
                        "linear_rotor.rotor_fixed_mass",
                        "M + T(φ) M_rot T(φ)ᵀ is within 0.12 % of singular at some angle φ (positive definiteness not decided)",
                    ));
                }
            }
        }
        for (name, a) in [("spin_stiffness", &self.spin_stiffness), ("spin_chart", &self.spin_chart)] {
            if a.is_empty() {
                continue;
            }
            if a.len() != n * n {
                return Err(Error::invalid(format!("linear_rotor.{name}"), format!("has {} entries, N² = {} for N = {n} DOFs", a.len(), n * n)));
            }
            for (i, v) in a.iter().enumerate() {
                finite(&format!("linear_rotor.{name}[{},{}]", i / n, i % n), *v)?;
            }
        }
        let sc = scale(&self.spin_chart);
        for i in 0..n {
            for j in 0..i {
                if !self.spin_chart.is_empty() && (self.spin_chart[i * n + j] - self.spin_chart[j * n + i]).abs() > 1e-12 * sc {
                    return Err(Error::invalid(format!("linear_rotor.spin_chart[{i},{j}]"), format!("must equal spin_chart[{j},{i}] (symmetric)")));
                }
            }
        }
        for (i, u) in self.unbalances.iter().enumerate() {
            let f = |s: &str| format!("linear_rotor.unbalances[{i}].{s}");
            if u.node >= self.nodes {
                return Err(Error::invalid(f("node"), format!("{} is not a node (the nodes are 0 to {})", u.node, self.nodes.saturating_sub(1))));
            }
            finite(&f("me"), u.me)?;
            finite(&f("phase"), u.phase)?;
            finite(&f("offset"), u.offset)?;
            if u.offset != 0.0 && self.node_layout(u.node) == Layout::Translation {
                return Err(Error::invalid(f("offset"), format!("an axial offset needs the tilt DOFs, node {} has x, y only", u.node)));
            }
        }
        for (i, b) in self.speed_bearings.iter().enumerate() {
            let f = |s: &str| format!("linear_rotor.bearings[{i}].{s}");
            if b.node >= self.nodes {
                return Err(Error::invalid(f("node"), format!("{} is not a node (the nodes are 0 to {})", b.node, self.nodes.saturating_sub(1))));
            }
            if let Some(l) = b.link {
                if l >= self.nodes || l == b.node {
                    return Err(Error::invalid(
                        f("link"),
                        format!("{l} is not a node other than the bearing's {} (the nodes are 0 to {})", b.node, self.nodes.saturating_sub(1)),
                    ));
                }
            }
            if b.speeds.is_empty() {
                return Err(Error::invalid(f("speeds"), "needs at least one speed"));
            }
            for (name, len) in [("k", b.k.len()), ("c", b.c.len())] {
                if len != b.speeds.len() {
                    return Err(Error::invalid(f(name), format!("has {len} entries, one per speed: {}", b.speeds.len())));
                }
            }
            for (j, w) in b.speeds.iter().enumerate() {
                finite(&format!("{}[{j}]", f("speeds")), *w)?;
                if j > 0 && *w <= b.speeds[j - 1] {
                    return Err(Error::invalid(f("speeds"), "must increase strictly"));
                }
                for (name, t) in [("k", &b.k[j]), ("c", &b.c[j])] {
                    for v in t {
                        finite(&format!("{}[{j}]", f(name)), *v)?;
                    }
                }
            }
        }
        // the balls are coordinates beside the N DOFs: the equations' mass matrix and the
        // analyses' Jacobians are dense in N + n_b (the same limit as the DOFs')
        let mut coordinates = n;
        for (i, b) in self.balancers.iter().enumerate() {
            let f = |s: &str| format!("linear_rotor.balancers[{i}].{s}");
            if b.node >= self.nodes {
                return Err(Error::invalid(f("node"), format!("{} is not a node (the nodes are 0 to {})", b.node, self.nodes.saturating_sub(1))));
            }
            positive(&f("radius"), b.radius)?;
            positive(&f("ball_mass"), b.ball_mass)?;
            non_negative(&f("drag"), b.drag)?;
            finite(&f("offset"), b.offset)?;
            if b.offset != 0.0 && self.node_layout(b.node) == Layout::Translation {
                return Err(Error::invalid(f("offset"), format!("an axial offset needs the tilt DOFs, node {} has x, y only", b.node)));
            }
            if b.balls == 0 {
                return Err(Error::invalid(f("balls"), "must be at least 1"));
            }
            let room = MAX_DOFS.saturating_sub(coordinates);
            if b.balls > room {
                let reason = format!("the {n} DOFs and every plane's balls together at most {MAX_DOFS}: the matrices are dense");
                return Err(Error::TooLarge { what: f("balls"), size: b.balls as u64, limit: room as u64, reason });
            }
            coordinates += b.balls;
            if let Some(p) = self.ball_physics.get(i) {
                p.validate(&format!("linear_rotor.balancers[{i}]"), b.ball_mass, b.radius, b.balls)?;
            }
        }
        if self.ball_physics.len() > self.balancers.len() {
            return Err(Error::invalid(
                "linear_rotor.ball_physics",
                format!("has {} entries, one per balancer plane: {}", self.ball_physics.len(), self.balancers.len()),
            ));
        }
        Ok(())
    }

    /// Whether `M, C, G, K` are isotropic: every 2×2 block between two pairs `(x, y)`, `(α, β)`
    /// has the form `[[a, −b], [b, a]]` (commutes with `J`), to `1e-12` of the matrix's largest
    /// entry. Then the equations in axes turning with the rotor are autonomous (module docs).
    pub fn is_isotropic(&self) -> bool {
        let n = self.dofs();
        [&self.m, &self.c, &self.g, &self.k].iter().all(|a| {
            let tol = 1e-12 * a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            (0..n / 2).all(|bi| {
                (0..n / 2).all(|bj| {
                    let e = |r: usize, c: usize| a[(2 * bi + r) * n + 2 * bj + c];
                    (e(0, 0) - e(1, 1)).abs() <= tol && (e(0, 1) + e(1, 0)).abs() <= tol
                })
            })
        })
    }

    /// The undamped natural frequencies `ω_i` (rad/s, ascending) of the rotor at rest,
    /// `(M + M_rot) q̈ + K q = 0`, with the DOFs in `constrained` held at zero and, where
    /// `with_balls`, the balls as rings ([`LinearRotor::ball_mass_matrix`]) added to the mass.
    /// The rotor-fixed inertia [`LinearRotor::rotor_fixed_mass`] is taken at the rotor's angle
    /// 0 (`T(0) M_rot T(0)ᵀ = M_rot`): the rotor at rest in its reference position, with
    /// everything that turns with it as part of its body, so that two descriptions of one rotor
    /// that split its inertia differently between `M` and `M_rot` give the same frequencies.
    /// `K` must be symmetric; the generalised problem `K v = ω² M v` is reduced to the standard one `L⁻¹ K L⁻ᵀ w = ω² w` by the Cholesky factor
    /// `M = L Lᵀ` and solved by [`eigen_dyn`]; `ω = sqrt(max(λ, 0))` (rigid-body modes give 0).
    /// A `K` that is not positive semi-definite has modes with `λ = ω² < 0` (the structure
    /// diverges at rest at the rate `sqrt(−λ)`), which read 0 here: ask
    /// [`LinearRotor::natural_frequencies_squared`] and [`static_divergence`] to tell them
    /// from a rigid-body mode.
    pub fn natural_frequencies(&self, constrained: &[usize], with_balls: bool) -> Result<Vec<f64>> {
        Ok(self.natural_frequencies_squared(constrained, with_balls)?.into_iter().map(|l| l.max(0.0).sqrt()).collect())
    }

    /// The eigenvalues `λ_i = ω_i²` ((rad/s)², ascending, with their signs) of the undamped
    /// problem at rest `K v = λ (M + M_rot) v` of [`LinearRotor::natural_frequencies`] (the
    /// same constraints, balls and rotor-fixed inertia): negative where `K` is not positive
    /// semi-definite on the free DOFs (by Sylvester's law of inertia the Cholesky congruence
    /// `L⁻¹ K L⁻ᵀ` keeps the number of negative eigenvalues of `K`).
    pub fn natural_frequencies_squared(&self, constrained: &[usize], with_balls: bool) -> Result<Vec<f64>> {
        self.validate()?;
        let n = self.dofs();
        let mut m = self.m.clone();
        if !self.rotor_fixed_mass.is_empty() {
            m.iter_mut().zip(&self.rotor_fixed_mass).for_each(|(a, b)| *a += b);
        }
        if with_balls {
            for (i, v) in self.ball_mass_matrix().iter().enumerate() {
                m[i] += v;
            }
        }
        let keep: Vec<usize> = (0..n).filter(|i| !constrained.contains(i)).collect();
        let r = keep.len();
        let sub = |a: &[f64]| -> Vec<f64> { keep.iter().flat_map(|&i| keep.iter().map(move |&j| a[i * n + j])).collect() };
        let (mr, kr) = (sub(&m), sub(&self.k));
        let l = cholesky(&mr, r).map_err(|i| Error::invalid("linear_rotor.m", format!("is not positive definite on the free DOFs (pivot {i})")))?;
        // S = L⁻¹ K L⁻ᵀ: solve L X = K, then L Sᵀ = Xᵀ
        let x = lower_solve_columns(&l, &kr, r);
        let xt: Vec<f64> = (0..r * r).map(|ij| x[(ij % r) * r + ij / r]).collect();
        let s = lower_solve_columns(&l, &xt, r);
        let ev = eigen_dyn::eigenvalues(&s, r).map_err(|_| Error::NoConvergence { omega: 0.0 })?;
        let mut w: Vec<f64> = ev.iter().map(|z| z.re).collect();
        w.sort_by(f64::total_cmp);
        Ok(w)
    }

    /// The balls as rings, a lumped mass matrix (e.g. for critical speeds of the rotor with its
    /// balls): each plane's mass `n m_b` at its race centre `(x + z β, y − z α)`, i.e.
    /// `n m_b Pᵀ P` with `P` the map from the node's DOFs to the race centre's translation, and
    /// with tilt DOFs the ring's diametral moment `n m_b R²/2` on `α, β` (the exact average of
    /// the balls' tilt inertia `m_b R² (α̇ sin θ − β̇ cos θ)²` over evenly spread balls).
    pub fn ball_mass_matrix(&self) -> Vec<f64> {
        let n = self.dofs();
        let mut a = vec![0.0; n * n];
        for b in &self.balancers {
            let mass = b.balls as f64 * b.ball_mass;
            let (Some(ix), Some(iy)) = (self.dof(b.node, Direction::X), self.dof(b.node, Direction::Y)) else { continue };
            let tilt = self.dof(b.node, Direction::Alpha).zip(self.dof(b.node, Direction::Beta));
            // race centre: x + z β, y − z α
            let mut rows: Vec<Vec<(usize, f64)>> = vec![vec![(ix, 1.0)], vec![(iy, 1.0)]];
            if let Some((ia, ib)) = tilt {
                rows[0].push((ib, b.offset));
                rows[1].push((ia, -b.offset));
                for i in [ia, ib] {
                    a[i * n + i] += 0.5 * mass * b.radius * b.radius;
                }
            }
            for row in &rows {
                for &(i, ci) in row {
                    for &(j, cj) in row {
                        a[i * n + j] += mass * ci * cj;
                    }
                }
            }
        }
        a
    }
}

/// `T(φ) A T(φ)ᵀ` of a row-major `n × n` matrix `A`, `T(φ)` block-diagonal with the 2×2
/// rotations `R(φ) = [[cos, −sin], [sin, cos]]` (every pair `(x, y)`, `(α, β)`), generic over
/// the number type (the angle carried as a dual number in the exact Jacobians).
pub(crate) fn turn_blocks<T: crate::ode::dual::Real>(a: &[f64], n: usize, phi: T) -> Vec<T> {
    let (s, c) = phi.sin_cos();
    let mut out = vec![T::cst(0.0); n * n];
    for bi in 0..n / 2 {
        for bj in 0..n / 2 {
            let e = |r: usize, cc: usize| a[(2 * bi + r) * n + 2 * bj + cc];
            // B Rᵀ, then R (B Rᵀ)
            let br = [[c * e(0, 0) - s * e(0, 1), s * e(0, 0) + c * e(0, 1)], [c * e(1, 0) - s * e(1, 1), s * e(1, 0) + c * e(1, 1)]];
            let o = [[c * br[0][0] - s * br[1][0], c * br[0][1] - s * br[1][1]], [s * br[0][0] + c * br[1][0], s * br[0][1] + c * br[1][1]]];
            for r in 0..2 {
                for cc in 0..2 {
                    out[(2 * bi + r) * n + 2 * bj + cc] = o[r][cc];
                }
            }
        }
    }
    out
}

/// Cholesky factor `L` (row-major, lower) of a symmetric positive definite `n × n` matrix, or
/// the index of the first non-positive pivot.
pub(crate) fn cholesky(a: &[f64], n: usize) -> std::result::Result<Vec<f64>, usize> {
    let mut l = vec![0.0; n * n];
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= l[j * n + k] * l[j * n + k];
        }
        if d.is_nan() || d <= 0.0 {
            return Err(j);
        }
        let d = d.sqrt();
        l[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= l[i * n + k] * l[j * n + k];
            }
            l[i * n + j] = s / d;
        }
    }
    Ok(l)
}

/// `L⁻¹ B` for lower-triangular `L` and `n × n` `B` (row-major), column by column.
fn lower_solve_columns(l: &[f64], b: &[f64], n: usize) -> Vec<f64> {
    let mut x = b.to_vec();
    for c in 0..n {
        for r in 0..n {
            let mut s = x[r * n + c];
            for k in 0..r {
                s -= l[r * n + k] * x[k * n + c];
            }
            x[r * n + c] = s / l[r * n + r];
        }
    }
    x
}
