//! The rotor the nonlinear spatial model simulates, in SI units (or in the papers' units, where
//! `M_s = 1`, `ω0 = 1`, `ρ_s = 1`): a rigid rotor with unbalance masses and a tilted principal
//! axis, one or two elastic supports that may differ by direction, ball sets in one or more
//! planes, gravity.
//!
//! Axial positions `z` are along the shaft in one common coordinate (any origin). The
//! reference point O of the equations is the axis point at the common centre of mass C of the
//! composite rotor with its balls at balance, `z_C = (M_r z_G + Σ m_u z_u + Σ n m z_p)/M_s`;
//! body axial coordinates are `ζ = z − z_C`.
//!
//! It is also the SI rotor of the analytic commands: an SI config's `[rotor]`, `[supports]`,
//! `[unbalance]` and `[balancer]` are a [`SpatialRotor`] (`config::spatial`, the parameter
//! paths of `spatial::paths`), and [`SpatialRotor::to_dimensionless`] derives the papers'
//! dimensionless [`SpatialModel`] from it; [`SpatialRotor::from_dimensionless`] goes back.

use crate::error::{finite, fmt_num, non_negative, positive, Error, Result};
use crate::limits::{check_all, check_count, check_derived};
use crate::spatial::inertia::{self, AnisotropyMethod};
use crate::spatial::params::{ball_coupling, Damping, MassSet, Scale, SpatialModel};
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

impl RigidRotor {
    /// A rotor whose principal axis is the shaft axis (`κ = 0`): mass `M_r`, equatorial moment
    /// `A_r` about G, polar moment `C_r`, G at `z`.
    pub fn aligned(mass: f64, equatorial_moment: f64, polar_moment: f64, z: f64) -> Self {
        RigidRotor { mass, equatorial_moment, polar_moment, z, axis_tilt: 0.0, axis_tilt_angle: 0.0 }
    }
}

impl Support {
    /// A support alike in x and y: stiffness `k` (N/m) and damping `c` (N·s/m) in both
    /// directions, at `z` (the papers' isotropic support).
    pub fn isotropic(z: f64, stiffness: f64, damping: f64) -> Self {
        Support { z, stiffness: [stiffness; 2], damping: [damping; 2] }
    }
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

impl BallPlane {
    /// `n` balls of mass `m` on a race of radius `R` in the plane at `z`, drag `h_A`, as the
    /// papers' point masses ([`crate::balls::BallPhysics::default`]).
    pub fn point_masses(z: f64, n: usize, ball_mass: f64, race_radius: f64, drag: f64) -> Self {
        BallPlane { z, n, ball_mass, race_radius, drag, physics: Default::default() }
    }
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
    /// The rotor with these parts, without gravity or spin drag, its tilt free.
    pub fn new(rotor: RigidRotor, supports: Vec<Support>, unbalances: Vec<PointMass>, planes: Vec<BallPlane>) -> Self {
        SpatialRotor { rotor, supports, unbalances, planes, gravity: [0.0; 3], spin_drag: 0.0, lock_tilt: false }
    }

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

    /// Whether gravity has a component across the spin axis (fixed x or y): it then turns
    /// against the rotor once a revolution, and the stationary motion is a periodic orbit.
    pub fn gravity_across(&self) -> bool {
        self.gravity[0] != 0.0 || self.gravity[1] != 0.0
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
        self.check_damping_ratios()?;
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

    /// The supports' damping in each fixed direction through the dimensionless damping it
    /// implies, as [`Self::to_dimensionless`] checks the x direction's `h̄x`:
    /// `h_d = (Σ damping_d)/(M_s ω0_d)` with `ω0_d = sqrt((Σ stiffness_d)/M_s)`, `d` = x, y,
    /// within the range of `dimensionless.h_x` (a damping ratio up to 500). The error names
    /// the support of the larger damping as the config spells it (`supports.damping_left_y`):
    /// a y damping of 1e12 N·s/m was taken and the general route then ran for minutes.
    /// The stiffnesses must be positive (checked before).
    fn check_damping_ratios(&self) -> Result<()> {
        let ms = self.total_mass();
        for (d, suffix) in [(0, ""), (1, "_y")] {
            let stiffness: f64 = self.supports.iter().map(|s| s.stiffness[d]).sum();
            let damping: f64 = self.supports.iter().map(|s| s.damping[d]).sum();
            let omega0 = (stiffness / ms).sqrt();
            // the support of the larger damping (the left one at a tie, as to_dimensionless)
            let worse = (0..self.supports.len()).fold(0, |w, i| if self.supports[i].damping[d] > self.supports[w].damping[d] { i } else { w });
            let side = ["left", "right"][worse];
            let what = if self.supports.len() == 2 {
                format!("(damping_left{suffix} + damping_right{suffix})/(M_s ω0{suffix}), ω0{suffix} = sqrt((stiffness_left{suffix} + stiffness_right{suffix})/M_s),")
            } else {
                format!("damping_left{suffix}/(M_s ω0{suffix}), ω0{suffix} = sqrt(stiffness_left{suffix}/M_s),")
            };
            check_derived(&format!("supports.damping_{side}{suffix}"), "dimensionless.h_x", damping / (ms * omega0), &what)?;
        }
        Ok(())
    }

    /// The papers' dimensionless model of this SI rotor, with its SI scale (000, eqs (4), (5),
    /// (8), (10)): `M_s = M_r + m0 + n m`, `z_C` from `M_r z_G + (m0 + n m) z_A = 0`,
    /// `A_Σ = A_r + M_r z_G² + (m0 + n m) z_A² + ½ m0 R0² + ½ n m R²`,
    /// `C_Σ = C_r + m0 R0² + n m R²`, `c_x = c_L + c_R`, `c_α = c_L l_cL² + c_R l_cR²`,
    /// `c_yα = c_L l_cL − c_R l_cR` (and likewise for damping), `ω0 = sqrt(c_x/M_s)`.
    ///
    /// The papers' rotor is the part of a [`SpatialRotor`] that an SI config's `[rotor]`,
    /// `[supports]`, `[unbalance]` and `[balancer]` describe (`config::spatial`): two isotropic
    /// supports (left, right), at most one unbalance mass (`[unbalance]`, its angle a rotation of
    /// the rotor frame that no result depends on), at most one balancer plane (`[balancer]`,
    /// possibly with `n = 0` balls: its ball mass, race radius and drag are kept for the
    /// parameter paths and checked, `balancer.balls = 0` with a ball mass is an error), the
    /// unbalance in that plane; no tilted axis, gravity, locked tilt, contact or rolling
    /// resistance (each is an error naming its key: the general route of `rotor_stability`
    /// takes them). The spin drag has no effect at the prescribed speeds of these analyses.
    /// Without a plane, the balancer plane is the unbalance's (else `z = 0`).
    ///
    /// Errors name the field as the config spells it (`rotor.mass`, `supports.z_right`, …); the
    /// ratios the SI inputs imply are checked against the dimensionless ranges
    /// ([`crate::limits::check_derived`]).
    ///
    /// ```
    /// use autobal::spatial::dynamics::SpatialRotor;
    /// use autobal::spatial::inertia::AnisotropyMethod;
    /// let r = SpatialRotor::dimensional_example();
    /// let m = r.to_dimensionless(AnisotropyMethod::Exact).unwrap();
    /// let s = m.scale.unwrap();
    /// // ω0 = sqrt((c_L + c_R)/M_s), M_s = 20 kg + 10 g + 2 × 20 g
    /// assert!((s.omega0 - (5.0e6_f64 / 20.05).sqrt()).abs() < 1e-9 * s.omega0);
    /// let mut tilted = r.clone();
    /// tilted.supports[1].stiffness[1] = 1.0e6;
    /// let e = tilted.to_dimensionless(AnisotropyMethod::Exact).unwrap_err().to_string();
    /// assert!(e.starts_with("supports.stiffness_right_y"), "{e}");
    /// ```
    pub fn to_dimensionless(&self, method: AnisotropyMethod) -> Result<SpatialModel> {
        let (left, right, unbalance, plane) = self.analytic_parts()?;
        let rotor = &self.rotor;
        let (unbalance_mass, unbalance_radius) = unbalance.map_or((0.0, 0.0), |u| (u.mass, u.radius));
        let z_balancer = plane.map(|p| p.z).or(unbalance.map(|u| u.z)).unwrap_or(0.0);
        let (balls, ball_mass, race_radius, ball_drag) = plane.map_or((0, 0.0, 0.0, 0.0), |p| (p.n, p.ball_mass, p.race_radius, p.drag));
        check_all(&[
            ("rotor.mass", rotor.mass),
            ("rotor.equatorial_moment", rotor.equatorial_moment),
            ("rotor.polar_moment", rotor.polar_moment),
            ("rotor.z", rotor.z),
            ("balancer.z", z_balancer),
            ("supports.z_left", left.z),
            ("supports.z_right", right.z),
        ])?;
        if rotor.polar_moment > 2.0 * rotor.equatorial_moment {
            return Err(Error::invalid(
                "rotor.polar_moment",
                format!(
                    "C_r = {} kg·m² exceeds twice the equatorial moment A_r = {} kg·m²: no rigid body has a polar moment above the sum of its equatorial ones",
                    fmt_num(rotor.polar_moment),
                    fmt_num(rotor.equatorial_moment)
                ),
            ));
        }
        if right.z <= left.z {
            return Err(Error::invalid(
                "supports.z_right",
                format!(
                    "the right support must lie beyond the left one (z_right = {} ≤ z_left = {}): the span l = z_right − z_left must be positive",
                    fmt_num(right.z),
                    fmt_num(left.z)
                ),
            ));
        }
        check_all(&[
            ("supports.stiffness_left", left.stiffness[0]),
            ("supports.stiffness_right", right.stiffness[0]),
            ("supports.damping_left", left.damping[0]),
            ("supports.damping_right", right.damping[0]),
            ("unbalance.mass", unbalance_mass),
            ("unbalance.radius", unbalance_radius),
            ("balancer.ball_mass", ball_mass),
            ("balancer.race_radius", race_radius),
            ("balancer.drag", ball_drag),
        ])?;
        check_count("balancer.balls", balls as u64)?;
        if balls == 0 && ball_mass > 0.0 {
            return Err(Error::invalid("balancer.balls", "is 0 but balancer.ball_mass is given: set the number of balls, or ball_mass = 0"));
        }
        if balls > 0 && ball_mass == 0.0 {
            return Err(Error::invalid("balancer.ball_mass", "must be positive when balancer.balls > 0"));
        }
        if balls > 0 && race_radius == 0.0 {
            return Err(Error::invalid("balancer.race_radius", "must be positive when balancer.balls > 0"));
        }
        let n = balls as f64;
        let m_ab = unbalance_mass + n * ball_mass; // mass in plane A
        let ms = rotor.mass + m_ab;
        let z_c = (rotor.mass * rotor.z + m_ab * z_balancer) / ms;
        let z_g = rotor.z - z_c;
        let z_a = z_balancer - z_c;
        let l_cl = z_c - left.z;
        let l_cr = right.z - z_c;
        let span = right.z - left.z;
        let a_m0 = unbalance_mass * unbalance_radius.powi(2);
        let a_m = n * ball_mass * race_radius.powi(2);
        let a_s = rotor.equatorial_moment + rotor.mass * z_g * z_g + m_ab * z_a * z_a;
        let a_sigma = a_s + 0.5 * a_m0 + 0.5 * a_m;
        let c_sigma_abs = rotor.polar_moment + a_m0 + a_m;
        let (cl, cr) = (left.stiffness[0], right.stiffness[0]);
        let c_x = cl + cr;
        let c_alpha = cl * l_cl * l_cl + cr * l_cr * l_cr;
        let c_ya = cl * l_cl - cr * l_cr;
        let (hl, hr) = (left.damping[0], right.damping[0]);
        let h_x = hl + hr;
        let h_alpha = hl * l_cl * l_cl + hr * l_cr * l_cr;
        let h_ya = hl * l_cl - hr * l_cr;
        let omega0 = (c_x / ms).sqrt();
        let rho = (a_sigma / ms).sqrt();
        // at most limits::MAX_BALLS_SPATIAL balls (checked above): the count fits a u32
        let masses = MassSet { m0: unbalance_mass / ms, r0: unbalance_radius / rho, m: n * ball_mass / ms, r: race_radius / rho, n: balls as u32 };
        let anisotropy = inertia::anisotropy(&masses.ball_set(), None, method)?;
        let h_s = if balls > 0 { ball_drag / (ball_mass * omega0) } else { 0.0 };
        // the ratios of the SI inputs, through the dimensionless parameters they imply
        let rho_bar = rho / span;
        let what_rho = format!("the radius of gyration sqrt(A_Σ/M_s) = {} m over the span {} m", fmt_num(rho), fmt_num(span));
        check_derived(if rho_bar < 1.0 { "supports.z_right" } else { "rotor.equatorial_moment" }, "dimensionless.rho_s", rho_bar, &what_rho)?;
        check_derived("rotor.z", "dimensionless.l_left", l_cl / span, "the centre of mass's distance from the left support over the span")?;
        check_derived("balancer.z", "dimensionless.z_a", z_a / rho, "the balancer plane's distance from the centre of mass over the radius of gyration")?;
        let worse_support = if hl >= hr { "supports.damping_left" } else { "supports.damping_right" };
        check_derived(worse_support, "dimensionless.h_x", h_x / (ms * omega0), "(damping_left + damping_right)/(M_s ω0)")?;
        check_derived("balancer.drag", "dimensionless.h_s", h_s, "drag/(ball_mass ω0)")?;
        Ok(SpatialModel {
            balls: ball_coupling(&masses, &anisotropy),
            c_sigma: c_sigma_abs / a_sigma,
            rho_s: Some(rho / span),
            l_left: Some(l_cl / span),
            p_alpha_sq: c_alpha / (a_sigma * omega0 * omega0),
            c_y_alpha: c_ya / (omega0 * omega0 * (ms * a_sigma).sqrt()),
            z_a: z_a / rho,
            anisotropy,
            delta_a0: 0.5 * masses.a_m0(),
            damping: Damping { h_x: h_x / (ms * omega0), h_alpha: h_alpha / (a_sigma * omega0), h_y_alpha: h_ya / (omega0 * (ms * a_sigma).sqrt()), h_s },
            masses: Some(masses),
            scale: Some(Scale { omega0, total_mass: ms, rho_s: rho, span }),
        })
    }

    /// The parts of the rotor the analytic model of papers 000/003 describes ([`Self::to_dimensionless`]):
    /// the left and right supports, the unbalance mass and the balancer plane, if any; an error
    /// naming the key of anything else.
    fn analytic_parts(&self) -> Result<(&Support, &Support, Option<&PointMass>, Option<&BallPlane>)> {
        const MODEL: &str = "the analytic model of papers 000/003";
        // equal as the config's one value copied twice is (NaN included: the range checks name it)
        let same = |a: f64, b: f64| a == b || (a.is_nan() && b.is_nan());
        let [left, right] = self.supports.as_slice() else {
            return Err(Error::invalid("supports", format!("{MODEL} has two supports, got {}", self.supports.len())));
        };
        for (s, side) in [(left, "left"), (right, "right")] {
            for (what, v) in [("stiffness", s.stiffness), ("damping", s.damping)] {
                if !same(v[0], v[1]) {
                    return Err(Error::invalid(
                        format!("supports.{what}_{side}_y"),
                        format!("differs from supports.{what}_{side}: {MODEL} has isotropic supports (the general route takes the rotor as it is)"),
                    ));
                }
            }
        }
        if self.rotor.axis_tilt != 0.0 {
            return Err(Error::invalid("rotor.axis_tilt", format!("{MODEL} has the principal axis along the shaft")));
        }
        if self.unbalances.len() > 1 {
            return Err(Error::invalid("couple", format!("{MODEL} has one unbalance mass, in the balancer plane")));
        }
        if self.planes.len() > 1 {
            return Err(Error::invalid("balancer2", format!("{MODEL} has one balancer plane")));
        }
        let (unbalance, plane) = (self.unbalances.first(), self.planes.first());
        if let (Some(u), Some(p)) = (unbalance, plane) {
            if !same(u.z, p.z) {
                return Err(Error::invalid(
                    "unbalance.z",
                    format!("{} m lies off the balancer plane at {} m: {MODEL} has the unbalance in the balancer plane", fmt_num(u.z), fmt_num(p.z)),
                ));
            }
        }
        if let Some(p) = plane {
            if p.physics.contact {
                return Err(Error::invalid("balancer.contact", format!("{MODEL} has point-mass balls")));
            }
            if p.physics.rolling_resistance != 0.0 {
                return Err(Error::invalid("balancer.rolling_resistance", format!("{MODEL} has no rolling resistance")));
            }
        }
        if self.gravity != [0.0; 3] {
            return Err(Error::invalid("spatial.gravity", format!("{MODEL} has no gravity")));
        }
        if self.lock_tilt {
            return Err(Error::invalid("spatial.lock_tilt", format!("{MODEL} has the tilt free")));
        }
        Ok((left, right, unbalance, plane))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::params::DimensionlessInput;

    /// Two routes: the rotor that [`SpatialRotor::from_dimensionless`] builds in the units
    /// `M_s = ω0 = ρ_s = 1`, taken back through [`SpatialRotor::to_dimensionless`] (000, eqs
    /// (4), (5), (8), (10)), is the model it came from, and its scale is 1. Tolerance: the
    /// forward route sums `A_Σ = 1` from five terms of order 1 and the backward route divides by
    /// it, a few ulps each; `1e-13` leaves a factor ~100 over that and fails on any algebra slip.
    #[test]
    fn to_dimensionless_inverts_from_dimensionless() {
        for l_left in [0.3, 0.8, 1.2] {
            for (z_a, h_x, h_s) in [(0.8, 0.05, 0.1), (-0.4, 0.2, 0.0), (0.0, 0.0, 0.3)] {
                let model = SpatialModel::from_dimensionless(&DimensionlessInput { z_a, h_x, h_s, ..DimensionlessInput::paper_000(l_left) }).unwrap();
                let rotor = SpatialRotor::from_dimensionless(&model).unwrap();
                let back = rotor.to_dimensionless(model.anisotropy.method).unwrap();
                let s = back.scale.unwrap();
                let near = |a: f64, b: f64, what: &str| assert!((a - b).abs() <= 1e-13 * (1.0 + b.abs()), "{what}: {a} vs {b} (l_L = {l_left}, z_A = {z_a})");
                for (a, b, what) in [
                    (s.omega0, 1.0, "ω0"),
                    (s.total_mass, 1.0, "M_s"),
                    (s.rho_s, 1.0, "ρ_s"),
                    (back.c_sigma, model.c_sigma, "C̄Σ"),
                    (back.rho_s.unwrap(), model.rho_s.unwrap(), "ρ̄s"),
                    (back.l_left.unwrap(), model.l_left.unwrap(), "l̄_L"),
                    (back.p_alpha_sq, model.p_alpha_sq, "p̄α²"),
                    (back.c_y_alpha, model.c_y_alpha, "c̄yα"),
                    (back.z_a, model.z_a, "z̄_A"),
                    (back.anisotropy.used, model.anisotropy.used, "ΔĀ"),
                    (back.delta_a0, model.delta_a0, "ΔĀ0"),
                    (back.damping.h_x, model.damping.h_x, "h̄x"),
                    (back.damping.h_alpha, model.damping.h_alpha, "h̄α"),
                    (back.damping.h_y_alpha, model.damping.h_y_alpha, "h̄yα"),
                    (back.damping.h_s, model.damping.h_s, "h̄s"),
                ] {
                    near(a, b, what);
                }
            }
        }
    }

    /// What the analytic model does not describe is an error naming its key, not ignored.
    #[test]
    fn to_dimensionless_refuses_what_the_papers_rotor_lacks() {
        let base = SpatialRotor::dimensional_example();
        let cases: [(&str, fn(&mut SpatialRotor)); 9] = [
            ("supports.damping_left_y", |r| r.supports[0].damping[1] = 1.0),
            ("rotor.axis_tilt", |r| r.rotor.axis_tilt = 0.01),
            ("couple", |r| r.unbalances.push(r.unbalances[0])),
            ("balancer2", |r| r.planes.push(r.planes[0])),
            ("unbalance.z", |r| r.unbalances[0].z = 0.2),
            ("balancer.contact", |r| r.planes[0].physics.contact = true),
            ("spatial.gravity", |r| r.gravity = [0.0, -9.81, 0.0]),
            ("spatial.lock_tilt", |r| r.lock_tilt = true),
            ("supports", |r| {
                r.supports.pop();
            }),
        ];
        for (field, change) in cases {
            let mut r = base.clone();
            change(&mut r);
            let e = r.to_dimensionless(AnisotropyMethod::Exact).unwrap_err().to_string();
            assert!(e.starts_with(&format!("{field}: ")), "{e}");
        }
        // the unbalance's angle and the spin drag change no result of the analytic model
        let mut r = base.clone();
        r.unbalances[0].angle = 1.0;
        r.spin_drag = 0.1;
        assert_eq!(r.to_dimensionless(AnisotropyMethod::Exact).unwrap(), base.to_dimensionless(AnisotropyMethod::Exact).unwrap());
    }
}
