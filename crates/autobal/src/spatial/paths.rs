//! Parameter paths: the description a spatial model was built from ([`SpatialSpec`]) and one
//! table of dotted paths (`dimensionless.z_a`, `rotor.mass`, ...) that change it, so that maps
//! and sweeps vary a parameter without going back through a config file.
//!
//! A path is spelled as the config spells the field (`table.key`); setting one changes the input
//! and [`SpatialSpec::build`] derives the model again (microseconds: the derivation of 000,
//! eqs (4), (5), (8), (10), and the anisotropy). Errors name the path. The table
//! ([`PARAMETER_PATHS`]: entries of the one [`ParameterPath`] type, read and written through
//! [`Parameters`] as the planar problem's are) is the single place to add a parameter.

use crate::error::{Error, Result};
use crate::paths::{ParameterPath, Parameters};
use crate::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
use crate::spatial::inertia::{Anisotropy, AnisotropyMethod};
use crate::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};

/// The two ways to describe a spatial model.
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialInput {
    /// The papers' dimensionless parameters (`[dimensionless]`).
    Dimensionless(DimensionlessInput),
    /// An SI rotor (`[rotor]`, `[supports]`, `[unbalance]`, `[balancer]`) and the anisotropy
    /// method of `[analysis]`.
    Si {
        /// The rotor: what [`SpatialRotor::to_dimensionless`] takes (two isotropic supports, the
        /// unbalance mass and the balancer plane, with `n = 0` balls when `[balancer]` has none).
        rotor: SpatialRotor,
        /// Which anisotropy the analyses use.
        method: AnisotropyMethod,
    },
}

/// What a [`SpatialModel`] is built from: its input and, for a dimensionless model described by
/// its masses, an anisotropy given directly that overrides the one the masses imply (serving as
/// `ΔĀ` and `ΔĀ0`, as in 003's worked examples).
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialSpec {
    /// The input.
    pub input: SpatialInput,
    /// `dimensionless.delta_a` beside the masses.
    pub delta_a_override: Option<f64>,
}

impl SpatialSpec {
    /// Derive the model (validating every field; errors name it).
    pub fn build(&self) -> Result<SpatialModel> {
        let mut m = match &self.input {
            SpatialInput::Dimensionless(d) => SpatialModel::from_dimensionless(d)?,
            SpatialInput::Si { rotor, method } => rotor.to_dimensionless(*method)?,
        };
        if let Some(v) = self.delta_a_override {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(Error::invalid("dimensionless.delta_a", format!("must be a finite number ≥ 0, got {}", crate::error::fmt_num(v))));
            }
            let computed = m.anisotropy.clone();
            m.anisotropy = Anisotropy::given(v);
            m.anisotropy.warnings.push(format!(
                "dimensionless.delta_a = {} overrides the anisotropy of the masses (exact tensor {}, eq (17) {}); it serves as ΔĀ and ΔĀ0",
                crate::error::fmt_num(v),
                crate::error::fmt_num(computed.exact[1]),
                crate::error::fmt_num(computed.paper)
            ));
            m.delta_a0 = v;
        }
        Ok(m)
    }

    /// Set the parameter at `path` to `value` (the model is derived again by [`Self::build`]);
    /// [`Parameters::set`] on [`PARAMETER_PATHS`], callable without the trait in scope.
    pub fn set(&mut self, path: &str, value: f64) -> Result<()> {
        <Self as Parameters>::set(self, path, value)
    }

    /// The value of the parameter at `path` ([`Parameters::get`]).
    pub fn get(&self, path: &str) -> Result<f64> {
        <Self as Parameters>::get(self, path)
    }
}

/// The spatial description's paths are [`PARAMETER_PATHS`]; an unknown path's error also lists
/// the speed axes of maps and boundaries (`omega`, `speed_rpm`, ...), which are not fields.
impl Parameters for SpatialSpec {
    fn parameter_paths() -> &'static [ParameterPath<Self>] {
        PARAMETER_PATHS
    }
    fn other_paths() -> &'static [&'static str] {
        &["omega", "speed_rpm", "speed", "speed_hz"]
    }
}

fn dimless(s: &mut SpatialSpec) -> std::result::Result<&mut DimensionlessInput, String> {
    match &mut s.input {
        SpatialInput::Dimensionless(d) => Ok(d),
        SpatialInput::Si { .. } => Err("the model is dimensional ([rotor], [supports], ...): vary its SI fields instead".into()),
    }
}

fn dimless_ref(s: &SpatialSpec) -> std::result::Result<&DimensionlessInput, String> {
    match &s.input {
        SpatialInput::Dimensionless(d) => Ok(d),
        SpatialInput::Si { .. } => Err("the model is dimensional ([rotor], [supports], ...): vary its SI fields instead".into()),
    }
}

fn si(s: &mut SpatialSpec) -> std::result::Result<&mut SpatialRotor, String> {
    match &mut s.input {
        SpatialInput::Si { rotor, .. } => Ok(rotor),
        SpatialInput::Dimensionless(_) => Err("the model is dimensionless ([dimensionless]): vary its dimensionless fields instead".into()),
    }
}

fn si_ref(s: &SpatialSpec) -> std::result::Result<&SpatialRotor, String> {
    match &s.input {
        SpatialInput::Si { rotor, .. } => Ok(rotor),
        SpatialInput::Dimensionless(_) => Err("the model is dimensionless ([dimensionless]): vary its dimensionless fields instead".into()),
    }
}

// The parts of the SI rotor the paths name (an SI config's rotor has them all; one built
// otherwise may lack a support, the unbalance or the plane: an error, not a panic).
fn rigid(r: &SpatialRotor) -> std::result::Result<&RigidRotor, String> {
    Ok(&r.rotor)
}
fn rigid_mut(r: &mut SpatialRotor) -> std::result::Result<&mut RigidRotor, String> {
    Ok(&mut r.rotor)
}
fn no_support(i: usize) -> String {
    format!("the rotor has no {} support", ["left", "right"][i])
}
fn left(r: &SpatialRotor) -> std::result::Result<&Support, String> {
    r.supports.first().ok_or_else(|| no_support(0))
}
fn left_mut(r: &mut SpatialRotor) -> std::result::Result<&mut Support, String> {
    r.supports.first_mut().ok_or_else(|| no_support(0))
}
fn right(r: &SpatialRotor) -> std::result::Result<&Support, String> {
    r.supports.get(1).ok_or_else(|| no_support(1))
}
fn right_mut(r: &mut SpatialRotor) -> std::result::Result<&mut Support, String> {
    r.supports.get_mut(1).ok_or_else(|| no_support(1))
}
fn unbalance(r: &SpatialRotor) -> std::result::Result<&PointMass, String> {
    r.unbalances.first().ok_or_else(|| "the rotor has no unbalance mass".into())
}
fn unbalance_mut(r: &mut SpatialRotor) -> std::result::Result<&mut PointMass, String> {
    r.unbalances.first_mut().ok_or_else(|| "the rotor has no unbalance mass".into())
}
fn plane(r: &SpatialRotor) -> std::result::Result<&BallPlane, String> {
    r.planes.first().ok_or_else(|| "the rotor has no balancer plane".into())
}
fn plane_mut(r: &mut SpatialRotor) -> std::result::Result<&mut BallPlane, String> {
    r.planes.first_mut().ok_or_else(|| "the rotor has no balancer plane".into())
}

fn masses_only() -> String {
    "the model gives delta_a directly: this field belongs to a description by masses (m0, r0, m, r, n)".into()
}

/// A number of balls: a whole number in `0..=10000` ([`crate::paths::whole`]).
fn whole(v: f64) -> std::result::Result<u32, String> {
    crate::paths::whole(v, 10_000).map(|n| n as u32)
}

macro_rules! dimless_field {
    ($path:literal, $doc:literal, $field:ident) => {
        ParameterPath {
            path: $path,
            doc: $doc,
            set: |s, v| {
                dimless(s)?.$field = v;
                Ok(())
            },
            get: |s| Ok(dimless_ref(s)?.$field),
        }
    };
}

/// A field of one part of the SI rotor: `$part`/`$part_mut` find the part, the field is read
/// as `$get` and written by `$set` (both a plain field unless given).
macro_rules! si_field {
    ($path:literal, $doc:literal, $part:ident / $part_mut:ident, $field:ident) => {
        si_field!($path, $doc, $part / $part_mut, |p| p.$field, |q, v| q.$field = v)
    };
    ($path:literal, $doc:literal, $part:ident / $part_mut:ident, |$p:ident| $get:expr, |$q:ident, $v:ident| $set:expr) => {
        ParameterPath {
            path: $path,
            doc: $doc,
            set: |s, $v| {
                let $q = $part_mut(si(s)?)?;
                $set;
                Ok(())
            },
            get: |s| {
                let $p = $part(si_ref(s)?)?;
                Ok($get)
            },
        }
    };
}

/// Every parameter a path can name, as the config spells it.
pub static PARAMETER_PATHS: &[ParameterPath<SpatialSpec>] = &[
    dimless_field!("dimensionless.c_sigma", "C̄Σ, polar over equatorial moment", c_sigma),
    dimless_field!("dimensionless.rho_s", "ρ̄s, radius of gyration over the span", rho_s),
    dimless_field!("dimensionless.l_left", "l̄_L, centre of mass from the left support", l_left),
    dimless_field!("dimensionless.z_a", "z̄_A, balancer plane from the centre of mass", z_a),
    dimless_field!("dimensionless.h_x", "h̄x, support damping", h_x),
    dimless_field!("dimensionless.h_s", "h̄s, ball drag", h_s),
    ParameterPath {
        path: "dimensionless.delta_a",
        doc: "ΔĀ (and ΔĀ0), given directly",
        set: |s, v| {
            let d = dimless(s)?;
            match &mut d.anisotropy {
                AnisotropyInput::Direct(x) => *x = v,
                AnisotropyInput::Masses { .. } => s.delta_a_override = Some(v),
            }
            Ok(())
        },
        get: |s| match (&dimless_ref(s)?.anisotropy, s.delta_a_override) {
            (AnisotropyInput::Direct(x), _) => Ok(*x),
            (AnisotropyInput::Masses { .. }, Some(v)) => Ok(v),
            (AnisotropyInput::Masses { .. }, None) => Err("not given: the masses imply the anisotropy".into()),
        },
    },
    ParameterPath {
        path: "dimensionless.m0",
        doc: "m̄0, unbalance mass",
        set: |s, v| match &mut dimless(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => {
                masses.m0 = v;
                Ok(())
            }
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
        get: |s| match &dimless_ref(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => Ok(masses.m0),
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
    },
    ParameterPath {
        path: "dimensionless.r0",
        doc: "R̄0, unbalance radius",
        set: |s, v| match &mut dimless(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => {
                masses.r0 = v;
                Ok(())
            }
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
        get: |s| match &dimless_ref(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => Ok(masses.r0),
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
    },
    ParameterPath {
        path: "dimensionless.m",
        doc: "m̄, mass of all balls",
        set: |s, v| {
            let d = dimless(s)?;
            match (&mut d.anisotropy, &mut d.direct_balls) {
                (AnisotropyInput::Masses { masses, .. }, _) => masses.m = v,
                (AnisotropyInput::Direct(_), Some(b)) => b.0 = v,
                (AnisotropyInput::Direct(_), None) => return Err("the model does not describe the balls (give m and d_a beside delta_a)".into()),
            }
            Ok(())
        },
        get: |s| {
            let d = dimless_ref(s)?;
            match (&d.anisotropy, d.direct_balls) {
                (AnisotropyInput::Masses { masses, .. }, _) => Ok(masses.m),
                (AnisotropyInput::Direct(_), Some(b)) => Ok(b.0),
                (AnisotropyInput::Direct(_), None) => Err("the model does not describe the balls".into()),
            }
        },
    },
    ParameterPath {
        path: "dimensionless.r",
        doc: "R̄, race radius",
        set: |s, v| match &mut dimless(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => {
                masses.r = v;
                Ok(())
            }
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
        get: |s| match &dimless_ref(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => Ok(masses.r),
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
    },
    ParameterPath {
        path: "dimensionless.n",
        doc: "n, number of balls",
        set: |s, v| {
            let n = whole(v)?;
            match &mut dimless(s)?.anisotropy {
                AnisotropyInput::Masses { masses, .. } => {
                    masses.n = n;
                    Ok(())
                }
                AnisotropyInput::Direct(_) => Err(masses_only()),
            }
        },
        get: |s| match &dimless_ref(s)?.anisotropy {
            AnisotropyInput::Masses { masses, .. } => Ok(masses.n as f64),
            AnisotropyInput::Direct(_) => Err(masses_only()),
        },
    },
    ParameterPath {
        path: "dimensionless.d_a",
        doc: "D_A, ball-geometry factor",
        set: |s, v| {
            let d = dimless(s)?;
            match (&mut d.anisotropy, &mut d.direct_balls) {
                (AnisotropyInput::Masses { d_a, .. }, _) => *d_a = Some(v),
                (AnisotropyInput::Direct(_), Some(b)) => b.1 = v,
                (AnisotropyInput::Direct(_), None) => return Err("the model does not describe the balls (give m and d_a beside delta_a)".into()),
            }
            Ok(())
        },
        get: |s| {
            let d = dimless_ref(s)?;
            match (&d.anisotropy, d.direct_balls) {
                (AnisotropyInput::Masses { d_a: Some(x), .. }, _) => Ok(*x),
                (AnisotropyInput::Masses { d_a: None, .. }, _) => Err("not given".into()),
                (AnisotropyInput::Direct(_), Some(b)) => Ok(b.1),
                (AnisotropyInput::Direct(_), None) => Err("the model does not describe the balls".into()),
            }
        },
    },
    si_field!("rotor.mass", "rotor mass M_r (kg)", rigid / rigid_mut, mass),
    si_field!("rotor.equatorial_moment", "A_r (kg·m²)", rigid / rigid_mut, equatorial_moment),
    si_field!("rotor.polar_moment", "C_r (kg·m²)", rigid / rigid_mut, polar_moment),
    si_field!("rotor.z", "axial position of G (m)", rigid / rigid_mut, z),
    ParameterPath {
        path: "balancer.z",
        doc: "axial position of the balancer plane (m)",
        // plane A carries the balls and the unbalance: both move (the plane's z, else the
        // unbalance's, as SpatialRotor::to_dimensionless reads it)
        set: |s, v| {
            let r = si(s)?;
            if r.planes.is_empty() && r.unbalances.is_empty() {
                return Err("the rotor has no balancer plane".into());
            }
            r.planes.iter_mut().take(1).for_each(|p| p.z = v);
            r.unbalances.iter_mut().take(1).for_each(|u| u.z = v);
            Ok(())
        },
        get: |s| {
            let r = si_ref(s)?;
            plane(r).map(|p| p.z).or_else(|e| unbalance(r).map(|u| u.z).map_err(|_| e))
        },
    },
    si_field!("supports.z_left", "left support position (m)", left / left_mut, z),
    si_field!("supports.z_right", "right support position (m)", right / right_mut, z),
    // an SI config's supports are isotropic: x and y together
    si_field!("supports.stiffness_left", "c_L (N/m)", left / left_mut, |p| p.stiffness[0], |q, v| q.stiffness = [v; 2]),
    si_field!("supports.stiffness_right", "c_R (N/m)", right / right_mut, |p| p.stiffness[0], |q, v| q.stiffness = [v; 2]),
    si_field!("supports.damping_left", "h_L (N·s/m)", left / left_mut, |p| p.damping[0], |q, v| q.damping = [v; 2]),
    si_field!("supports.damping_right", "h_R (N·s/m)", right / right_mut, |p| p.damping[0], |q, v| q.damping = [v; 2]),
    si_field!("unbalance.mass", "m0 (kg)", unbalance / unbalance_mut, mass),
    si_field!("unbalance.radius", "R0 (m)", unbalance / unbalance_mut, radius),
    si_field!("balancer.ball_mass", "mass of one ball (kg)", plane / plane_mut, ball_mass),
    si_field!("balancer.race_radius", "race radius R (m)", plane / plane_mut, race_radius),
    si_field!("balancer.drag", "drag on each ball h_A (N·s/m)", plane / plane_mut, drag),
    ParameterPath {
        path: "balancer.balls",
        doc: "number of balls",
        set: |s, v| {
            let n = whole(v)?;
            plane_mut(si(s)?)?.n = n as usize;
            Ok(())
        },
        get: |s| Ok(plane(si_ref(s)?)?.n as f64),
    },
];

/// The speed axis in SI of a map or boundary (`speed_rpm`, `speed` in rad/s, `speed_hz`,
/// [`crate::units::SPEED_PATHS`]): its index (0 = x, 1 = y) and rad/s per unit; `None` when
/// neither axis is one. Errors: both axes speeds, or a unit on a dimensionless model.
pub(crate) fn si_speed_axis(spec: &SpatialSpec, paths: [&str; 2]) -> Result<Option<(usize, f64)>> {
    let units = paths.map(crate::units::speed_path_unit);
    let si = units.iter().position(|u| u.is_some_and(|u| u != crate::units::SpeedUnit::Omega));
    let Some(i) = si else { return Ok(None) };
    if units[1 - i].is_some() {
        return Err(Error::invalid(paths[i], "only one axis can be the speed"));
    }
    let u = units[i].and_then(|u| u.rad_s()).unwrap_or(1.0);
    if matches!(spec.input, SpatialInput::Dimensionless(_)) {
        return Err(Error::invalid(
            paths[i],
            "a speed in SI needs a dimensional config (the rotor's ω0); this config is dimensionless: use the axis omega (Ω)",
        ));
    }
    Ok(Some((i, u)))
}

/// `ω0` (rad/s) of the model with the parameter at `path` set to `v`.
pub(crate) fn omega0_at(spec: &SpatialSpec, path: &str, v: f64) -> Result<f64> {
    let mut t = spec.clone();
    t.set(path, v)?;
    t.build()?.scale.map(|s| s.omega0).ok_or_else(|| Error::invalid(path, "the model has no SI scale ω0"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::params::MassSet;

    fn base() -> SpatialSpec {
        SpatialSpec {
            input: SpatialInput::Dimensionless(DimensionlessInput {
                c_sigma: 0.75,
                rho_s: 0.4,
                l_left: 0.8,
                z_a: 0.8,
                anisotropy: AnisotropyInput::Masses { masses: MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 }, d_a: None },
                h_x: 0.05,
                h_s: 0.1,
                method: AnisotropyMethod::Exact,
                direct_balls: None,
            }),
            delta_a_override: None,
        }
    }

    #[test]
    fn every_path_round_trips_or_names_itself() {
        for p in PARAMETER_PATHS {
            let mut s = base();
            match s.get(p.path) {
                Ok(v) => {
                    s.set(p.path, v + 1.0).unwrap();
                    assert_eq!(s.get(p.path).unwrap(), v + 1.0, "{}", p.path);
                }
                Err(e) => assert!(e.to_string().starts_with(p.path), "{e}"),
            }
        }
        let e = base().set("dimensionless.zz", 1.0).unwrap_err().to_string();
        assert!(e.starts_with("dimensionless.zz: unknown parameter path"), "{e}");
        let e = base().set("dimensionless.n", 2.5).unwrap_err().to_string();
        assert!(e.starts_with("dimensionless.n: must be a whole number"), "{e}");
    }

    fn si_base() -> SpatialSpec {
        SpatialSpec { input: SpatialInput::Si { rotor: SpatialRotor::dimensional_example(), method: AnisotropyMethod::Exact }, delta_a_override: None }
    }

    #[test]
    fn every_si_path_round_trips_and_the_other_kind_names_itself() {
        let si_paths: Vec<_> = PARAMETER_PATHS.iter().filter(|p| !p.path.starts_with("dimensionless.")).collect();
        assert_eq!(si_paths.len(), 17);
        for p in &si_paths {
            let mut s = si_base();
            let v = s.get(p.path).unwrap();
            s.set(p.path, v + 1.0).unwrap();
            assert_eq!(s.get(p.path).unwrap(), v + 1.0, "{}", p.path);
            let e = base().set(p.path, 1.0).unwrap_err().to_string();
            assert_eq!(e, format!("{}: the model is dimensionless ([dimensionless]): vary its dimensionless fields instead", p.path));
        }
        let e = si_base().get("dimensionless.z_a").unwrap_err().to_string();
        assert_eq!(e, "dimensionless.z_a: the model is dimensional ([rotor], [supports], ...): vary its SI fields instead");
    }

    #[test]
    fn si_paths_change_the_rotor_as_the_config_keys_do() {
        let mut s = si_base();
        // a support's stiffness and damping: both directions (the config's isotropic support)
        s.set("supports.stiffness_right", 4.0e6).unwrap();
        s.set("supports.damping_left", 100.0).unwrap();
        // the balancer plane carries the unbalance: both move
        s.set("balancer.z", 0.40).unwrap();
        let SpatialInput::Si { rotor, .. } = &s.input else { unreachable!() };
        assert_eq!((rotor.supports[1].stiffness, rotor.supports[0].damping), ([4.0e6; 2], [100.0; 2]));
        assert_eq!((rotor.planes[0].z, rotor.unbalances[0].z), (0.40, 0.40));
        // ω0 = sqrt((c_L + c_R)/M_s) follows (M_s = 20 kg + 10 g + 2 × 20 g)
        let w0 = s.build().unwrap().scale.unwrap().omega0;
        assert!((w0 - (6.0e6_f64 / 20.05).sqrt()).abs() < 1e-12 * w0, "{w0}");
        // balancer.balls = 0 keeps the ball mass: a ball mass without balls is an error, as in a config
        s.set("balancer.balls", 0.0).unwrap();
        let e = s.build().unwrap_err().to_string();
        assert_eq!(e, "balancer.balls: is 0 but balancer.ball_mass is given: set the number of balls, or ball_mass = 0");
        s.set("balancer.ball_mass", 0.0).unwrap();
        let m = s.build().unwrap();
        assert!(m.balls.is_none() && m.masses.unwrap().n == 0);
        // a whole number of balls
        let e = s.set("balancer.balls", 2.5).unwrap_err().to_string();
        assert!(e.starts_with("balancer.balls: must be a whole number"), "{e}");
        // a rotor without a balancer plane: an error naming the path, no panic
        let mut bare = si_base();
        if let SpatialInput::Si { rotor, .. } = &mut bare.input {
            rotor.planes.clear();
        }
        let e = bare.set("balancer.drag", 1.0).unwrap_err().to_string();
        assert_eq!(e, "balancer.drag: the rotor has no balancer plane");
        // ... and its balancer plane is the unbalance's, as to_dimensionless reads it
        bare.set("balancer.z", 0.3).unwrap();
        assert_eq!(bare.get("balancer.z").unwrap(), 0.3);
        assert_eq!(bare.build().unwrap().scale, {
            let mut t = si_base();
            t.set("balancer.z", 0.3).unwrap();
            t.set("balancer.balls", 0.0).unwrap();
            t.set("balancer.ball_mass", 0.0).unwrap();
            t.build().unwrap().scale
        });
    }

    #[test]
    fn a_path_changes_the_model_as_the_field_does() {
        let mut s = base();
        s.set("dimensionless.z_a", -0.3).unwrap();
        assert_eq!(s.build().unwrap().z_a, -0.3);
        // l_left acts through the support coefficients (000, eq (10))
        s.set("dimensionless.l_left", 1.2).unwrap();
        let m = s.build().unwrap();
        let (p2, c) = crate::spatial::params::identical_support_coefficients(1.2, 0.4);
        assert_eq!((m.p_alpha_sq, m.c_y_alpha), (p2, c));
        // delta_a beside the masses overrides ΔĀ and ΔĀ0, keeping the balls
        s.set("dimensionless.delta_a", 0.1).unwrap();
        let m = s.build().unwrap();
        assert_eq!((m.anisotropy.used, m.delta_a0), (0.1, 0.1));
        assert!(m.balls.is_some());
        // invalid values are refused by the model's own validation, naming the field
        s.set("dimensionless.rho_s", -1.0).unwrap();
        assert!(s.build().unwrap_err().to_string().starts_with("dimensionless.rho_s"));
    }
}
