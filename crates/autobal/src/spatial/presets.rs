//! Presets, defaults and builders of the spatial model's inputs: the papers' base cases as
//! values, so that a user (and the tests, the report) start from the same numbers.
//!
//! ```
//! use autobal::spatial::params::{DimensionlessInput, SpatialModel};
//! use autobal::spatial::critical_speeds::critical_speeds;
//!
//! // 003's worked example at l̄_L = 0.8: Ω_K4 = 3.80 as printed
//! let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_003(0.8)).unwrap();
//! let k4 = critical_speeds(&m).speeds[3].omega;
//! assert_eq!((k4 * 100.0).round() / 100.0, 3.80);
//!
//! // the base case with a balancer plane closer to the centre of mass
//! let m = DimensionlessInput::builder().z_a(0.3).build_model().unwrap();
//! assert_eq!(m.z_a, 0.3);
//! ```

use crate::builder::builder;
use crate::error::Result;
use crate::spatial::inertia::AnisotropyMethod;
use crate::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};

/// Unbalance and balls of paper 000's base case: `m̄0 = 0.025`, `R̄0 = 2`, two balls of
/// `m̄ = 0.05` in all on `R̄ = 2` (capacity `E = 2`).
pub const PAPER_000_MASSES: MassSet = MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 };

impl DimensionlessInput {
    /// Paper 000's base case at layout `l̄_L` (`examples/default.toml` at `l̄_L = 0.8`): the
    /// long rotor `C̄Σ = 0.75`, `ρ̄s = 0.4`, `z̄_A = 0.8` with [`PAPER_000_MASSES`], the exact
    /// anisotropy, and the damping of autobal's example (`h̄x = 0.05`, `h̄s = 0.1`; the paper's
    /// worked numbers are undamped).
    pub fn paper_000(l_left: f64) -> Self {
        DimensionlessInput {
            c_sigma: 0.75,
            rho_s: 0.4,
            l_left,
            z_a: 0.8,
            anisotropy: AnisotropyInput::Masses { masses: PAPER_000_MASSES, d_a: None },
            h_x: 0.05,
            h_s: 0.1,
            method: AnisotropyMethod::Exact,
            direct_balls: None,
        }
    }

    /// Paper 003's worked examples at `l̄_L` = 0.5, 0.8 or 1.2 (any layout is accepted): the
    /// same rotor with `ΔĀ = ΔĀ0 = 0.1` given directly and no damping, whose critical speeds
    /// and antiresonance 003 prints.
    pub fn paper_003(l_left: f64) -> Self {
        DimensionlessInput { anisotropy: AnisotropyInput::Direct(0.1), h_x: 0.0, h_s: 0.0, ..Self::paper_000(l_left) }
    }

    /// A builder starting from paper 000's base case at `l̄_L = 0.8`.
    pub fn builder() -> DimensionlessInputBuilder {
        DimensionlessInputBuilder::default()
    }
}

/// Paper 000's base case at `l̄_L = 0.8` ([`DimensionlessInput::paper_000`]).
impl Default for DimensionlessInput {
    fn default() -> Self {
        Self::paper_000(0.8)
    }
}

builder!(
    /// Builder of a [`DimensionlessInput`]; `build()` checks it by deriving the model,
    /// `build_model()` returns the model.
    DimensionlessInputBuilder for DimensionlessInput, |d| SpatialModel::from_dimensionless(d).map(|_| ());
    c_sigma: f64, rho_s: f64, l_left: f64, z_a: f64, anisotropy: AnisotropyInput, h_x: f64, h_s: f64, method: AnisotropyMethod,
    direct_balls: Option<(f64, f64)>,
);

impl DimensionlessInputBuilder {
    /// The validated model.
    pub fn build_model(self) -> Result<SpatialModel> {
        SpatialModel::from_dimensionless(&self.build()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::dynamics::SpatialRotor;

    #[test]
    fn builders_validate_and_name_the_field() {
        let e = DimensionlessInput::builder().rho_s(-1.0).build().unwrap_err().to_string();
        assert!(e.starts_with("dimensionless.rho_s"), "{e}");
        let mut r = SpatialRotor::dimensional_example();
        r.to_dimensionless(AnisotropyMethod::Exact).unwrap();
        r.supports[1].z = -1.0;
        let e = r.to_dimensionless(AnisotropyMethod::Exact).unwrap_err().to_string();
        assert!(e.starts_with("supports.z_right"), "{e}");
    }
}

/// The spatial model in time: paper 000's base case as the nonlinear rotor, and the run of
/// `examples/spatial.toml`.
mod dynamics_presets {
    use super::*;
    use crate::ode::Method;
    use crate::spatial::dynamics::{BallPlane, PointMass, RigidRotor, Settings, SpatialRotor, Support};

    impl SpatialRotor {
        /// Paper 000's base case at layout `l̄_L` ([`DimensionlessInput::paper_000`]) as the
        /// nonlinear rotor, in the papers' units (`M_s = ρ_s = ω0 = 1`): what
        /// `examples/spatial.toml` describes.
        ///
        /// ```
        /// use autobal::spatial::dynamics::SpatialRotor;
        /// let r = SpatialRotor::paper_000(0.8).unwrap();
        /// assert!((r.total_mass() - 1.0).abs() < 1e-12 && (r.natural_frequency() - 1.0).abs() < 1e-12);
        /// assert_eq!(r, SpatialRotor::default());
        /// ```
        pub fn paper_000(l_left: f64) -> Result<Self> {
            SpatialRotor::from_dimensionless(&SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(l_left))?)
        }

        /// The rotor of `examples/dimensional.toml`, in SI: 20 kg on supports 0.5 m apart (2 and
        /// 3 MN/m, 300 N·s/m each), 10 g of unbalance at 100 mm and two 20 g balls on a 120 mm
        /// race (drag 0.5 N·s/m) in the plane at 0.45 m; the rotor's G at 0.25 m, `A_r = 0.6`,
        /// `C_r = 0.15 kg·m²`.
        ///
        /// ```
        /// use autobal::spatial::dynamics::SpatialRotor;
        /// use autobal::spatial::paths::SpatialInput;
        /// let root = autobal::config::parse(include_str!("../../../../examples/dimensional.toml"), "dimensional.toml").unwrap();
        /// let SpatialInput::Si { rotor, .. } = autobal::config::spatial(&root).unwrap().spec.input else { panic!() };
        /// assert_eq!(rotor, SpatialRotor::dimensional_example());
        /// ```
        pub fn dimensional_example() -> Self {
            SpatialRotor::new(
                RigidRotor::aligned(20.0, 0.60, 0.15, 0.25),
                vec![Support::isotropic(0.0, 2.0e6, 300.0), Support::isotropic(0.50, 3.0e6, 300.0)],
                vec![PointMass { mass: 0.010, radius: 0.10, angle: 0.0, z: 0.45 }],
                vec![BallPlane::point_masses(0.45, 2, 0.020, 0.12, 0.5)],
            )
        }

        /// A builder starting from [`SpatialRotor::default`].
        pub fn builder() -> SpatialRotorBuilder {
            SpatialRotorBuilder::default()
        }
    }

    /// Paper 000's base case at `l̄_L = 0.8` ([`SpatialRotor::paper_000`]).
    impl Default for SpatialRotor {
        fn default() -> Self {
            // a constant, valid input (tested by the doc example above)
            SpatialRotor::paper_000(0.8).expect("paper 000's base case is a valid model")
        }
    }

    builder!(
        /// Builder of a [`SpatialRotor`]; `build()` runs [`SpatialRotor::validate`].
        SpatialRotorBuilder for SpatialRotor, |r| r.validate();
        rotor: RigidRotor, supports: Vec<Support>, unbalances: Vec<PointMass>, planes: Vec<BallPlane>, gravity: [f64; 3], spin_drag: f64,
        lock_tilt: bool,
    );

    /// The run of `examples/spatial.toml`: DOP853, `τ` to 2500 sampled every 1,
    /// `rtol = 1e-8`, `atol = 1e-10 ρ_s`.
    impl Default for Settings {
        fn default() -> Self {
            Settings { method: Method::Dop853, t_end: 2500.0, dt: 1.0, rtol: 1e-8, atol: 1e-10 }
        }
    }

    impl Settings {
        /// A builder starting from [`Settings::default`].
        pub fn builder() -> SpatialSettingsBuilder {
            SpatialSettingsBuilder::default()
        }
    }

    builder!(
        /// Builder of the spatial simulation's [`Settings`]; `build()` runs [`Settings::validate`].
        SpatialSettingsBuilder for Settings, |s| s.validate();
        method: Method, t_end: f64, dt: f64, rtol: f64, atol: f64,
    );
}

pub use dynamics_presets::{SpatialRotorBuilder, SpatialSettingsBuilder};
