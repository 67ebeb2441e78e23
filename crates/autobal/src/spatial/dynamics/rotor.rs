//! The rotor the nonlinear spatial model simulates, in SI units (or in the papers' units, where
//! `M_s = 1`, `ω0 = 1`, `ρ_s = 1`): a rigid rotor with unbalance masses and a tilted principal
//! axis, one or two elastic supports that may differ by direction, ball sets in one or more
//! planes, gravity.
//!
//! Axial positions `z` are along the shaft in one common coordinate (any origin). The
//! reference point O of the equations is the axis point at the common centre of mass C of the
//! composite rotor with its balls at balance, `z_C = (M_r z_G + Σ m_u z_u + Σ n m z_p)/M_s`;
//! body axial coordinates are `ζ = z − z_C`.

use crate::error::{finite, non_negative, positive, Error, Result};
use crate::spatial::params::{SpatialModel, SpatialRotorSi};
use serde::Serialize;

/// The rigid rotor without unbalance masses and balls.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RigidRotor {
    /// Mass `M_r` (kg).
    pub mass: f64,
    /// Equatorial moment `A_r` about its own centre of mass G (kg·m²).
    pub equatorial_moment: f64,
    /// Polar moment `C_r` about its principal axis (kg·m²).
    pub polar_moment: f64,
    /// Axial position of G (m).
    pub z: f64,
    /// Angle `κ` between the rotor's principal axis and the shaft axis (rad): a couple
    /// unbalance with products of inertia `(C_r − A_r) sin κ cos κ`.
    pub axis_tilt: f64,
    /// Direction in the rotor frame (from the body x axis, rad) of the plane in which the
    /// principal axis is tilted.
    pub axis_tilt_angle: f64,
}

/// An elastic-viscous support acting on the shaft point at `z`, with stiffness and damping
/// along the fixed axes x and y (they may differ: an anisotropic bearing or foundation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Support {
    /// Axial position (m).
    pub z: f64,
    /// Stiffness `(k_x, k_y)` (N/m).
    pub stiffness: [f64; 2],
    /// Viscous damping `(c_x, c_y)` (N·s/m).
    pub damping: [f64; 2],
}

/// A point mass fixed to the rotor: an unbalance mass.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PointMass {
    /// Mass (kg).
    pub mass: f64,
    /// Distance from the shaft axis (m).
    pub radius: f64,
    /// Angle in the rotor frame from the body x axis (rad).
    pub angle: f64,
    /// Axial position (m).
    pub z: f64,
}

/// A set of `n` equal balls on a race of radius `R` centred on the shaft axis in plane `z`,
/// each with viscous drag `h` on its speed relative to the race.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BallPlane {
    /// Axial position of the plane (m).
    pub z: f64,
    /// Number of balls.
    pub n: usize,
    /// Mass of one ball `m` (kg).
    pub ball_mass: f64,
    /// Race radius `R` (radius of the balls' centres) (m).
    pub race_radius: f64,
    /// Drag coefficient `h_A` (N·s/m): the force on a ball is `h_A R ψ̇` against its motion
    /// relative to the race (000's `h_A`; `h̄s = h_A/(m ω0)`).
    pub drag: f64,
    /// Real balls: diameter, contact, rolling resistance ([`crate::balls`]); default: point
    /// masses.
    pub physics: crate::balls::BallPhysics,
}

/// The spatial rotor with its supports, unbalance and balls.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpatialRotor {
    /// The rigid rotor.
    pub rotor: RigidRotor,
    /// One or two supports.
    pub supports: Vec<Support>,
    /// Unbalance masses (static and couple unbalance).
    pub unbalances: Vec<PointMass>,
    /// Ball sets (none, one or two balancer planes).
    pub planes: Vec<BallPlane>,
    /// Gravity `g` in fixed axes (m/s²), e.g. `[0, −9.81, 0]` for a horizontal machine.
    pub gravity: [f64; 3],
    /// Drag torque on the spin `−c_φ φ̇` (N·m·s), e.g. bearing friction; torque drives only.
    pub spin_drag: f64,
    /// Hold the tilt at zero (a rotor guided so that it only translates: the planar Jeffcott
    /// rotor of paper 004's kind).
    pub lock_tilt: bool,
}

impl SpatialRotor {
    /// Total mass `M_s` (kg).
    pub fn total_mass(&self) -> f64 {
        self.rotor.mass + self.unbalances.iter().map(|u| u.mass).sum::<f64>() + self.planes.iter().map(|p| p.n as f64 * p.ball_mass).sum::<f64>()
    }

    /// Axial position of the reference point O: the common centre of mass C of the composite
    /// rotor with its balls at balance.
    pub fn z_reference(&self) -> f64 {
        let first = self.rotor.mass * self.rotor.z
            + self.unbalances.iter().map(|u| u.mass * u.z).sum::<f64>()
            + self.planes.iter().map(|p| p.n as f64 * p.ball_mass * p.z).sum::<f64>();
        first / self.total_mass()
    }

    /// Number of balls in all planes.
    pub fn balls(&self) -> usize {
        self.planes.iter().map(|p| p.n).sum()
    }

    /// `sqrt((Σ k_x)/M_s)`: the translational natural frequency `ω0` of the papers (x direction).
    pub fn natural_frequency(&self) -> f64 {
        (self.supports.iter().map(|s| s.stiffness[0]).sum::<f64>() / self.total_mass()).sqrt()
    }

    /// A length typical of the motion (largest of the radii and of the unbalance eccentricity),
    /// for absolute tolerances on angles.
    pub fn length_scale(&self) -> f64 {
        let r = self.planes.iter().map(|p| p.race_radius).chain(self.unbalances.iter().map(|u| u.radius)).fold(0.0, f64::max);
        if r > 0.0 {
            r
        } else {
            (self.rotor.equatorial_moment / self.total_mass()).sqrt()
        }
    }

    /// The static unbalance `Σ m_u ρ_u` of the unbalance masses alone (kg·m), rotor frame.
    pub fn static_unbalance(&self) -> [f64; 2] {
        self.unbalances.iter().fold([0.0; 2], |a, u| [a[0] + u.mass * u.radius * u.angle.cos(), a[1] + u.mass * u.radius * u.angle.sin()])
    }

    /// The couple unbalance about C of the unbalance masses and the tilted principal axis
    /// alone (kg·m²), rotor frame: `Σ m_u ζ_u ρ_u − (C_r − A_r) sin κ cos κ (cos β, sin β)`, the
    /// products of inertia `(−J_xz, −J_yz)` that make the rotor wobble. (A point mass has
    /// `J_xz = −m x z`, so its couple `m ζ x` is `−J_xz`; the rotor's own tensor
    /// `A I + (C − A) e eᵀ` with `e = (sin κ cos β, sin κ sin β, cos κ)` has
    /// `J_xz = (C − A) sin κ cos κ cos β`, hence the minus: with it, balls that cancel this
    /// couple leave the rotor at rest on the axis, `tests/spatial_field.rs`.)
    pub fn couple_unbalance(&self) -> [f64; 2] {
        let zc = self.z_reference();
        let r = &self.rotor;
        let k = -(r.polar_moment - r.equatorial_moment) * r.axis_tilt.sin() * r.axis_tilt.cos();
        self.unbalances.iter().fold([k * r.axis_tilt_angle.cos(), k * r.axis_tilt_angle.sin()], |a, u| {
            let s = u.mass * u.radius * (u.z - zc);
            [a[0] + s * u.angle.cos(), a[1] + s * u.angle.sin()]
        })
    }

    /// Check every field; errors name it as the config spells it (`rotor.mass`,
    /// `supports.stiffness_left`, `balancer.ball_mass`, …).
    pub fn validate(&self) -> Result<()> {
        let r = &self.rotor;
        positive("rotor.mass", r.mass)?;
        positive("rotor.equatorial_moment", r.equatorial_moment)?;
        non_negative("rotor.polar_moment", r.polar_moment)?;
        finite("rotor.z", r.z)?;
        finite("rotor.axis_tilt", r.axis_tilt)?;
        finite("rotor.axis_tilt_angle", r.axis_tilt_angle)?;
        if self.supports.is_empty() || self.supports.len() > 2 {
            return Err(Error::invalid("supports", format!("one or two supports, got {}", self.supports.len())));
        }
        let names = ["left", "right"];
        for (s, name) in self.supports.iter().zip(names) {
            finite(&format!("supports.z_{name}"), s.z)?;
            for (d, suffix) in [(0, ""), (1, "_y")] {
                positive(&format!("supports.stiffness_{name}{suffix}"), s.stiffness[d])?;
                non_negative(&format!("supports.damping_{name}{suffix}"), s.damping[d])?;
            }
        }
        if self.supports.len() == 2 && self.supports[1].z <= self.supports[0].z {
            return Err(Error::invalid("supports.z_right", "the right support must lie beyond the left one"));
        }
        if self.supports.len() == 1 && !self.lock_tilt {
            return Err(Error::invalid("supports", "one support cannot hold the tilt: give two supports or lock the tilt (spatial.lock_tilt = true)"));
        }
        for (i, u) in self.unbalances.iter().enumerate() {
            let t = if i == 0 { "unbalance" } else { "couple" };
            non_negative(&format!("{t}.mass"), u.mass)?;
            non_negative(&format!("{t}.radius"), u.radius)?;
            finite(&format!("{t}.angle"), u.angle)?;
            finite(&format!("{t}.z"), u.z)?;
        }
        for (i, p) in self.planes.iter().enumerate() {
            let t = if i == 0 { "balancer" } else { "balancer2" };
            // at most crate::limits::MAX_BALLS_SPATIAL per plane, as the limits table says
            crate::limits::check_count(&format!("{t}.balls"), p.n as u64)?;
            finite(&format!("{t}.z"), p.z)?;
            if p.n > 0 {
                positive(&format!("{t}.ball_mass"), p.ball_mass)?;
                positive(&format!("{t}.race_radius"), p.race_radius)?;
                non_negative(&format!("{t}.drag"), p.drag)?;
            }
            p.physics.validate(t, p.ball_mass, p.race_radius, p.n)?;
        }
        for (i, g) in self.gravity.iter().enumerate() {
            finite(&format!("spatial.gravity[{i}]"), *g)?;
        }
        non_negative("spatial.spin_drag", self.spin_drag)?;
        Ok(())
    }

    /// The SI rotor of the analytic commands (`[rotor]`, `[supports]`, `[unbalance]`,
    /// `[balancer]`): isotropic supports, the unbalance mass at angle 0 in the balancer plane.
    pub fn from_si(r: &SpatialRotorSi) -> Self {
        SpatialRotor {
            rotor: RigidRotor {
                mass: r.rotor_mass,
                equatorial_moment: r.equatorial_moment,
                polar_moment: r.polar_moment,
                z: r.z_rotor,
                axis_tilt: 0.0,
                axis_tilt_angle: 0.0,
            },
            supports: vec![
                Support { z: r.z_left, stiffness: [r.stiffness_left; 2], damping: [r.damping_left; 2] },
                Support { z: r.z_right, stiffness: [r.stiffness_right; 2], damping: [r.damping_right; 2] },
            ],
            unbalances: vec![PointMass { mass: r.unbalance_mass, radius: r.unbalance_radius, angle: 0.0, z: r.z_balancer }],
            planes: if r.balls > 0 {
                vec![BallPlane {
                    z: r.z_balancer,
                    n: r.balls as usize,
                    ball_mass: r.ball_mass,
                    race_radius: r.race_radius,
                    drag: r.ball_drag,
                    physics: Default::default(),
                }]
            } else {
                vec![]
            },
            gravity: [0.0; 3],
            spin_drag: 0.0,
            lock_tilt: false,
        }
    }

    /// The same rotor as a dimensionless model of papers 000/003 describes it, in the units
    /// `M_s = 1`, `ω0 = 1`, `ρ_s = 1` (so `A_Σ = 1`, `c_L + c_R = 1`), identical supports:
    /// `M_r = 1 − m̄0 − m̄`, `z_G = −(m̄0 + m̄) z̄_A/M_r`,
    /// `A_r = 1 − M_r z_G² − (m̄0 + m̄) z̄_A² − ½ m̄0 R̄0² − ½ m̄ R̄²`,
    /// `C_r = C̄Σ − m̄0 R̄0² − m̄ R̄²`, supports at `−l̄_L/ρ̄s` and `(1 − l̄_L)/ρ̄s` with
    /// `c = ½`, `h = ½ h̄x` each, ball drag `h_A = h̄s m̄/n`.
    ///
    /// Needs the masses (`m0`, `r0`, `m`, `r`, `n`), `rho_s` and `l_left`.
    pub fn from_dimensionless(model: &SpatialModel) -> Result<Self> {
        let p = "dimensionless";
        let ms = model.masses.ok_or_else(|| {
            Error::invalid(format!("{p}.m0"), "the simulation needs the masses and radii of unbalance and balls (m0, r0, m, r, n), not only delta_a")
        })?;
        let rho = model.rho_s.ok_or_else(|| Error::invalid(format!("{p}.rho_s"), "required by the simulation"))?;
        let l_left = model.l_left.ok_or_else(|| Error::invalid(format!("{p}.l_left"), "required by the simulation"))?;
        let m_plane = ms.m0 + ms.m;
        let m_r = 1.0 - m_plane;
        let z_a = model.z_a;
        let z_g = -m_plane * z_a / m_r;
        let a_r = 1.0 - m_r * z_g * z_g - m_plane * z_a * z_a - 0.5 * ms.a_m0() - 0.5 * ms.a_m();
        if a_r <= 0.0 {
            return Err(Error::invalid(
                format!("{p}.z_a"),
                format!("no rigid rotor has these parameters: the masses in plane A alone exceed the mean equatorial moment (A_r = {a_r:.4} ≤ 0)"),
            ));
        }
        let c_r = model.c_sigma - ms.a_m0() - ms.a_m();
        if c_r < 0.0 {
            return Err(Error::invalid(
                format!("{p}.c_sigma"),
                format!("C̄Σ = {} is less than the polar moment of unbalance and balls alone ({})", model.c_sigma, ms.a_m0() + ms.a_m()),
            ));
        }
        let span = 1.0 / rho;
        let h = 0.5 * model.damping.h_x;
        let n = ms.n as usize;
        Ok(SpatialRotor {
            rotor: RigidRotor { mass: m_r, equatorial_moment: a_r, polar_moment: c_r, z: z_g, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
            supports: vec![
                Support { z: -l_left * span, stiffness: [0.5; 2], damping: [h; 2] },
                Support { z: (1.0 - l_left) * span, stiffness: [0.5; 2], damping: [h; 2] },
            ],
            unbalances: vec![PointMass { mass: ms.m0, radius: ms.r0, angle: 0.0, z: z_a }],
            planes: if n > 0 {
                vec![BallPlane {
                    z: z_a,
                    n,
                    ball_mass: ms.m / n as f64,
                    race_radius: ms.r,
                    drag: model.damping.h_s * ms.m / n as f64,
                    physics: Default::default(),
                }]
            } else {
                vec![]
            },
            gravity: [0.0; 3],
            spin_drag: 0.0,
            lock_tilt: false,
        })
    }
}
