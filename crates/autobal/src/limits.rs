//! The range of every input: where the physics means something and double precision still
//! carries it. One table ([`LIMITS`]) serves the model constructors, the CLI's config check and
//! the documentation (`docs/reference/robustness.md` shows [`markdown_table`], a test keeps them equal).
//!
//! Two kinds of bound:
//! - **SI inputs** get generous physical bounds (a rotor of at most 1e9 kg, lengths within
//!   ±10 km, ...): wide enough for any machine, narrow enough that the products the models form
//!   (`c_L l_cL²`, `m R²`, `k/m`) stay far inside double precision. Their ratios are checked
//!   through the dimensionless parameters they imply ([`check_derived`]).
//! - **Dimensionless inputs** (papers 000/003) get the bounds of the rigid-rotor model: a
//!   radius of gyration between 1/1000 and 1000 support spans, the triangle inequality of a
//!   rigid body's principal moments (`C̄Σ ≤ 2`, `2 ΔĀ ≤ C̄Σ`), mass fractions below 1.
//!
//! ```
//! use autobal::limits::check;
//! assert!(check("rotor.mass", 20.0).is_ok());
//! let e = check("rotor.mass", 1e308).unwrap_err();
//! assert!(e.to_string().starts_with("rotor.mass: must lie in (0, 1e9] kg, got 1e308"));
//! ```

use crate::error::{fmt_num, Error, Result};

/// Most balls of one plane of the spatial model (`balancer.balls`, `balancer2.balls`,
/// `dimensionless.n`); [`crate::spatial::dynamics::SpatialRotor::validate`] holds every plane
/// to it, and the simulation's right-hand side costs `O(N)` in all. The exact anisotropy
/// interval costs `O(n)`, at most `200 000 + 8000 n` evaluations (see
/// [`crate::spatial::inertia::exact_interval`]; about 0.1 s for 100 balls); a balancer with
/// more than a hundred balls is better modelled as a fluid ring than as point masses.
pub const MAX_BALLS_SPATIAL: u32 = 100;

/// Most planar balls with real-ball physics (contact or rolling resistance) under a method that
/// takes implicit steps (`rodas`, `auto`): their Jacobian is dense (contact couples neighbouring
/// balls, so the arrow structure of point-mass balls, `crate::ode::arrow`, does not hold), an
/// implicit step costs `O(n³)` and `O(n²)` memory. Measured on paper 004's rotor with balls
/// packed against each other (debug-optimised build, loaded machine, user CPU per implicit
/// step): 2 ms at 100 balls, 10 ms at 200, 70 ms at 400, so about 0.2 s at 300 and over a
/// second at 1000; the explicit `dop853` costs `O(n log n)` per step and takes up to
/// `planar::MAX_BALLS`.
pub const MAX_BALLS_IMPLICIT_REAL: usize = 300;

/// Most balls of the planar rotor (`planar.n`; `crate::planar::MAX_BALLS`): a step costs
/// `O(n)`, the limit keeps a mistyped number from allocating gigabytes.
pub const PLANAR_MAX_BALLS: usize = 100_000;

/// The range of one input field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// The field as the config spells it (`table.key`).
    pub field: &'static str,
    /// Lower bound.
    pub lo: f64,
    /// Whether `lo` itself is excluded.
    pub lo_open: bool,
    /// Upper bound.
    pub hi: f64,
    /// Whether `hi` itself is excluded.
    pub hi_open: bool,
    /// Unit (empty for dimensionless quantities).
    pub unit: &'static str,
    /// Why these bounds.
    pub why: &'static str,
}

const fn lim(field: &'static str, lo: f64, lo_open: bool, hi: f64, hi_open: bool, unit: &'static str, why: &'static str) -> Limit {
    Limit { field, lo, lo_open, hi, hi_open, unit, why }
}

pub(crate) const MASS: &str = "no machine rotor exceeds 1e9 kg; keeps m·l² and k/m inside double precision";
const MOMENT: &str = "1e9 kg at 30 m; the ratio to mass and span is checked through ρ̄s";
const LENGTH: &str = "±10 km; ratios are checked through l̄_L, z̄_A, ρ̄s";
pub(crate) const RADIUS: &str = "a race or unbalance radius of at most 1 km";
const STIFF: &str = "the stiffest bearings are ~1e10 N/m; ω0 and its ratios stay finite";
const DAMP: &str = "the dimensionless damping it implies is checked as well";
const ANGLE: &str = "an angle: beyond ±1000 rad sin and cos lose digits; give it modulo 2π";
const SPEED: &str = "±1e6 rad/s (~1e7 rpm), beyond every machine";
const TIME: &str = "1e7 s of simulated time (115 days)";

/// Every numeric input field with its range.
pub const LIMITS: &[Limit] = &[
    // spatial rotor, SI (papers 000/003)
    lim("rotor.mass", 0.0, true, 1e9, false, "kg", MASS),
    lim("rotor.equatorial_moment", 0.0, true, 1e12, false, "kg·m²", MOMENT),
    lim(
        "rotor.polar_moment",
        0.0,
        true,
        1e12,
        false,
        "kg·m²",
        "also at most 2 equatorial_moment: a body's polar moment is at most the sum of its equatorial ones",
    ),
    lim("rotor.z", -1e4, false, 1e4, false, "m", LENGTH),
    lim("supports.z_left", -1e4, false, 1e4, false, "m", LENGTH),
    lim("supports.z_right", -1e4, false, 1e4, false, "m", "also beyond z_left: a positive span"),
    lim("supports.stiffness_left", 0.0, true, 1e13, false, "N/m", STIFF),
    lim("supports.stiffness_right", 0.0, true, 1e13, false, "N/m", STIFF),
    lim("supports.damping_left", 0.0, false, 1e12, false, "N·s/m", DAMP),
    lim("supports.damping_right", 0.0, false, 1e12, false, "N·s/m", DAMP),
    lim("unbalance.mass", 0.0, false, 1e9, false, "kg", MASS),
    lim("unbalance.radius", 0.0, false, 1e3, false, "m", RADIUS),
    lim("balancer.z", -1e4, false, 1e4, false, "m", LENGTH),
    lim("balancer.balls", 0.0, false, MAX_BALLS_SPATIAL as f64, false, "", "point-mass balls; the anisotropy interval costs O(n); more balls are a fluid ring"),
    lim("balancer.ball_mass", 0.0, false, 1e9, false, "kg", MASS),
    lim("balancer.race_radius", 0.0, false, 1e3, false, "m", RADIUS),
    lim("balancer.drag", 0.0, false, 1e12, false, "N·s/m", DAMP),
    // spatial simulation only (docs/notes/spatial.md)
    lim("rotor.axis_tilt", -1e3, false, 1e3, false, "rad", ANGLE),
    lim("rotor.axis_tilt_angle", -1e3, false, 1e3, false, "rad", ANGLE),
    lim("supports.stiffness_left_y", 0.0, true, 1e13, false, "N/m", STIFF),
    lim("supports.stiffness_right_y", 0.0, true, 1e13, false, "N/m", STIFF),
    lim("supports.damping_left_y", 0.0, false, 1e12, false, "N·s/m", DAMP),
    lim("supports.damping_right_y", 0.0, false, 1e12, false, "N·s/m", DAMP),
    lim("unbalance.angle", -1e3, false, 1e3, false, "rad", ANGLE),
    lim("couple.mass", 0.0, false, 1e9, false, "kg", MASS),
    lim("couple.radius", 0.0, false, 1e3, false, "m", RADIUS),
    lim("couple.angle", -1e3, false, 1e3, false, "rad", ANGLE),
    lim("couple.z", -1e4, false, 1e4, false, "m", LENGTH),
    lim("balancer2.z", -1e4, false, 1e4, false, "m", LENGTH),
    lim("balancer2.balls", 0.0, false, MAX_BALLS_SPATIAL as f64, false, "", "as balancer.balls"),
    lim("balancer2.ball_mass", 0.0, false, 1e9, false, "kg", MASS),
    lim("balancer2.race_radius", 0.0, false, 1e3, false, "m", RADIUS),
    lim("balancer2.drag", 0.0, false, 1e12, false, "N·s/m", DAMP),
    lim("balancer.ball_diameter", 0.0, true, 1e3, false, "m", "as planar.ball_diameter"),
    lim("balancer.restitution", 0.0, false, 1.0, false, "", "as planar.restitution"),
    lim("balancer.contact_stiffness", 0.0, true, 1e15, false, "N/m", "as planar.contact_stiffness"),
    lim("balancer.rolling_resistance", 0.0, false, 1.0, false, "", "as planar.rolling_resistance"),
    lim("balancer.slip_rate", 1e-12, false, 1e6, false, "rad/s", "as planar.slip_rate"),
    lim("balancer2.ball_diameter", 0.0, true, 1e3, false, "m", "as planar.ball_diameter"),
    lim("balancer2.restitution", 0.0, false, 1.0, false, "", "as planar.restitution"),
    lim("balancer2.contact_stiffness", 0.0, true, 1e15, false, "N/m", "as planar.contact_stiffness"),
    lim("balancer2.rolling_resistance", 0.0, false, 1.0, false, "", "as planar.rolling_resistance"),
    lim("balancer2.slip_rate", 1e-12, false, 1e6, false, "rad/s", "as planar.slip_rate"),
    lim("spatial.gravity", -1e6, false, 1e6, false, "m/s² (ρ_s ω0² dimensionless)", "a million g in SI"),
    lim("spatial.spin_drag", 0.0, false, 1e12, false, "N·m·s", "as support damping"),
    lim("initial.position", -1e3, false, 1e3, false, "m (ρ_s dimensionless)", "within 1 km (1000 radii of gyration) of the axis"),
    lim("initial.velocity", -1e6, false, 1e6, false, "m/s (ρ_s ω0 dimensionless)", "far beyond any whirl velocity"),
    lim("initial.tilt", -1.5, false, 1.5, false, "rad", "the tilt chart is singular at ±π/2"),
    lim("initial.tilt_rate", -1e6, false, 1e6, false, "rad/s (ω0 dimensionless)", SPEED),
    // spatial rotor, dimensionless (papers' symbols)
    lim("dimensionless.c_sigma", 0.0, true, 2.0, false, "", "C̄Σ = C_Σ/A_Σ ≤ 2: a body's polar moment is at most the sum of its equatorial ones"),
    lim(
        "dimensionless.rho_s",
        1e-3,
        false,
        1e3,
        false,
        "",
        "radius of gyration from 1/1000 to 1000 spans; outside, the shaft is no rigid body on two supports",
    ),
    lim("dimensionless.l_left", -1e3, false, 1e3, false, "", "centre of mass within 1000 spans of the supports"),
    lim("dimensionless.z_a", -1e3, false, 1e3, false, "", "balancer plane within 1000 radii of gyration of the centre of mass"),
    lim(
        "dimensionless.delta_a",
        0.0,
        false,
        1.0,
        true,
        "",
        "ΔĀ < 1 keeps the smaller principal moment positive; also 2 ΔĀ ≤ C̄Σ, the triangle inequality of the principal moments",
    ),
    lim("dimensionless.m0", 0.0, false, 1.0, true, "", "a fraction of the total mass; m0 + m < 1"),
    lim("dimensionless.r0", 0.0, false, 1e3, false, "", "with m0 r0² ≤ C̄Σ: the unbalance's polar moment is part of C_Σ"),
    lim("dimensionless.m", 0.0, false, 1.0, true, "", "a fraction of the total mass; m0 + m < 1"),
    lim("dimensionless.r", 0.0, false, 1e3, false, "", "with m0 r0² + m r² ≤ C̄Σ"),
    lim("dimensionless.n", 0.0, false, MAX_BALLS_SPATIAL as f64, false, "", "as balancer.balls"),
    lim("dimensionless.d_a", 0.0, false, 1.0, false, "", "D_A, the modulus of the mean of exp(2iα_j), is at most 1"),
    lim("dimensionless.h_x", 0.0, false, 1e3, false, "", "a damping ratio up to 500; beyond, the supports do not move"),
    lim("dimensionless.h_s", 0.0, false, 1e3, false, "", "beyond, the balls do not move on the time scale 1/ω0; use --balls locked"),
    lim("analysis.sensitivity_limit", 0.0, true, 1.0, true, "", "a relative error of the critical speeds"),
    lim("analysis.omega_max", 0.0, true, 1e6, false, "", "dimensionless speed; the largest critical speed the ranges above allow is ~1e6"),
    // planar rotor (paper 004), SI
    lim("planar.m1", 0.0, true, 1e9, false, "kg", MASS),
    lim("planar.m2", 0.0, false, 1e9, false, "kg", MASS),
    lim("planar.m3", 0.0, false, 1e9, false, "kg", MASS),
    lim("planar.n", 0.0, false, PLANAR_MAX_BALLS as f64, false, "", "a step costs O(n); the limit keeps a mistyped number from allocating gigabytes"),
    lim("planar.s1", 0.0, false, 1e3, false, "m", RADIUS),
    lim("planar.s2", 0.0, false, 1e3, false, "m", RADIUS),
    lim("planar.gamma", -1e3, false, 1e3, false, "rad", ANGLE),
    lim("planar.r", 0.0, false, 1e3, false, "m", RADIUS),
    lim("planar.k", 0.0, true, 1e13, false, "N/m", STIFF),
    lim("planar.c", 0.0, false, 1e12, false, "kg/s", "as support damping; also c/(m0 ω) ≤ 1000 with ω = sqrt(k/m0), as dimensionless.h_x"),
    lim("planar.k_x", 0.0, true, 1e13, false, "N/m", "as planar.k (supports that differ by direction)"),
    lim("planar.k_y", 0.0, true, 1e13, false, "N/m", "as planar.k (supports that differ by direction)"),
    lim("planar.c_x", 0.0, false, 1e12, false, "kg/s", "as planar.c (supports that differ by direction), with k_x"),
    lim("planar.c_y", 0.0, false, 1e12, false, "kg/s", "as planar.c (supports that differ by direction), with k_y"),
    lim("planar.ball_masses", 0.0, true, 1e9, false, "kg", "each, as planar.m3; one per ball"),
    lim("planar.ball_drags", 0.0, false, 1e12, false, "N·m·s", "each, as planar.c_psi; one per ball"),
    lim("planar.c_psi", 0.0, false, 1e12, false, "N·m·s", "as support damping"),
    lim("planar.c_theta", 0.0, false, 1e12, false, "N·m·s", "as support damping"),
    lim("planar.i_g", 0.0, true, 1e12, false, "kg·m²", MOMENT),
    lim("planar.ball_diameter", 0.0, true, 1e3, false, "m", "as the race radius; it must also fit the race (d < 2r, n balls side by side)"),
    lim("planar.restitution", 0.0, false, 1.0, false, "", "0: plastic impact, 1: elastic"),
    lim("planar.contact_stiffness", 0.0, true, 1e15, false, "N/m", "beyond the Hertz stiffness of any ball pair"),
    lim("planar.rolling_resistance", 0.0, false, 1.0, false, "", "a moment arm over the ball radius; steel on steel is ~1e-3"),
    lim("planar.slip_rate", 1e-12, false, 1e6, false, "rad/s", "the regularisation of the rolling resistance's sign; smaller is more exact and stiffer; below 1e-12 the ball angles' tolerance (0.1 of it) asks for digits an f64 angle does not hold"),
    // drive
    lim("drive.omega0", -1e6, false, 1e6, false, "rad/s", SPEED),
    lim("drive.b", -1e6, false, 1e6, false, "rad/s²", "reaches 1e6 rad/s in a second"),
    lim("drive.torque", -1e9, false, 1e9, false, "N·m", "the largest machine torques are ~1e7 N·m"),
    lim("drive.omega_idle", 0.0, true, 1e6, false, "rad/s", SPEED),
    lim("drive.t_off", 0.0, false, 1e7, false, "s", TIME),
    lim("drive.t_end", 0.0, true, 1e7, false, "s", TIME),
    lim("drive.psi0", -1e3, false, 1e3, false, "rad", ANGLE),
    lim("drive.psi_rate0", -1e6, false, 1e6, false, "rad/s", SPEED),
    lim("drive.xy0", -1e3, false, 1e3, false, "m", RADIUS),
    lim("drive.xy_rate0", -1e6, false, 1e6, false, "m/s", "far beyond any whirl velocity"),
    lim("drive.schedule", -1e9, false, 1e9, false, "s, rad/s or N·m", "times within the simulated span, speeds and torques as above"),
    // integration
    lim(
        "integration.rtol",
        1e-14,
        false,
        1e-2,
        false,
        "",
        "below 1e-14 double precision cannot reach it; above 1e-2 the error estimate no longer controls the error",
    ),
    lim("integration.atol", 0.0, true, 1e-2, false, "m", "absolute tolerance on displacements; above 1 cm it controls nothing"),
    lim("integration.dt", 0.0, true, 1e7, false, "s", "also t_end/dt ≤ 5e7 samples"),
    lim("integration.max_steps", 1.0, false, 1e15, false, "", "a step budget; a whole number"),
    lim("integration.max_wall_s", 0.0, true, 1e9, false, "s", "a wall-clock budget"),
];

/// The limit of `field`, if it has one.
pub fn limit(field: &str) -> Option<&'static Limit> {
    LIMITS.iter().find(|l| l.field == field)
}

impl Limit {
    /// Whether `value` lies in the range (NaN never does).
    pub fn contains(&self, value: f64) -> bool {
        let above = if self.lo_open { value > self.lo } else { value >= self.lo };
        let below = if self.hi_open { value < self.hi } else { value <= self.hi };
        above && below
    }

    /// `(0, 1e9] kg`.
    pub fn describe(&self) -> String {
        format!(
            "{}{}, {}{}{}",
            if self.lo_open { "(" } else { "[" },
            fmt_num(self.lo),
            fmt_num(self.hi),
            if self.hi_open { ")" } else { "]" },
            if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) }
        )
    }

    /// The error for `value` outside the range, naming `name`.
    pub fn error(&self, name: &str, value: f64) -> Error {
        Error::invalid(name, format!("must lie in {}, got {} ({})", self.describe(), fmt_num(value), self.why))
    }
}

/// Check `value` against the range of `field`; the error names `field`. A field without a limit
/// is only checked to be finite.
pub fn check(field: &str, value: f64) -> Result<f64> {
    check_as(field, field, value)
}

/// [`check`] each `(field, value)` in turn; the first error.
pub fn check_all(fields: &[(&str, f64)]) -> Result<()> {
    fields.iter().try_for_each(|(f, v)| check(f, *v).map(|_| ()))
}

/// Check `value` against the range of `field`, naming `name` in the error (a command-line
/// option that sets that field, e.g. `--omega-max` for `analysis.omega_max`).
pub fn check_as(name: &str, field: &str, value: f64) -> Result<f64> {
    match limit(field) {
        Some(l) if !l.contains(value) => Err(l.error(name, value)),
        Some(_) => Ok(value),
        None => crate::error::finite(name, value),
    }
}

/// Check a count (balls) against the range of `field`.
pub fn check_count(field: &str, value: u64) -> Result<u64> {
    match limit(field) {
        Some(l) if !l.contains(value as f64) => Err(Error::TooLarge { what: field.into(), size: value, limit: l.hi as u64, reason: l.why.into() }),
        _ => Ok(value),
    }
}

/// Every number of a description that has a limit, read through its parameter paths
/// ([`crate::paths::Parameters`]): what a sweep or a front end may have set.
pub fn check_parameters<T: crate::paths::Parameters>(t: &T) -> Result<()> {
    for p in T::parameter_paths() {
        if limit(p.path).is_some() {
            if let Ok(v) = (p.get)(t) {
                check(p.path, v)?;
            }
        }
    }
    Ok(())
}

/// Check a derived dimensionless quantity against the range of the dimensionless field
/// `field`, blaming the SI input `name` that set it: `what` says how it follows.
pub fn check_derived(name: &str, field: &str, value: f64, what: &str) -> Result<f64> {
    match limit(field) {
        Some(l) if !l.contains(value) => Err(Error::invalid(
            name,
            format!("{what} gives {} = {}, outside {} ({})", field.trim_start_matches("dimensionless."), fmt_num(value), l.describe(), l.why),
        )),
        _ => Ok(value),
    }
}

/// Check that every number in `value` (any result that serialises: critical speeds, ranges,
/// summaries) is finite. The error is [`Error::NonFinite`] naming `what` and the path to the
/// first offending number (`critical_speeds[2].omega`): JSON would silently print it as `null`.
///
/// ```
/// use autobal::limits::check_finite;
/// assert!(check_finite("speeds", &vec![1.0, 2.0]).is_ok());
/// let e = check_finite("speeds", &vec![1.0, f64::NAN]).unwrap_err();
/// assert_eq!(e.to_string(), "speeds[1] became non-finite");
/// ```
pub fn check_finite<T: serde::Serialize + ?Sized>(what: &str, value: &T) -> Result<()> {
    // a first walk builds no path (no allocation per number: it was 40 % of `autobal
    // campbell`'s instructions); only a value that holds a non-finite number is walked again
    // for the path of the message
    let mut quick = finite_walk::Walker { path: vec![], index: vec![], track: false };
    if value.serialize(&mut quick).is_ok() {
        return Ok(());
    }
    let mut w = finite_walk::Walker { path: vec![what.to_string()], index: vec![], track: true };
    value.serialize(&mut w).map_err(|e| Error::NonFinite { what: e.0, t: None })
}

/// A serde serializer that only walks the value and stops at the first non-finite float.
mod finite_walk {
    use serde::ser::{self, Serialize};
    use std::fmt::Display;

    /// The path of the first non-finite number.
    #[derive(Debug)]
    pub struct Found(pub String);

    impl Display for Found {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str(&self.0)
        }
    }
    impl std::error::Error for Found {}
    impl ser::Error for Found {
        fn custom<T: Display>(msg: T) -> Self {
            Found(msg.to_string())
        }
    }

    pub struct Walker {
        pub path: Vec<String>,
        pub index: Vec<usize>,
        /// Build the path of the first non-finite number (else only find whether there is one).
        pub track: bool,
    }

    type R = Result<(), Found>;

    impl Walker {
        fn float(&self, v: f64) -> R {
            if v.is_finite() {
                Ok(())
            } else {
                Err(Found(self.path.concat()))
            }
        }
        fn nested<T: Serialize + ?Sized>(&mut self, part: impl FnOnce() -> String, v: &T) -> R {
            if !self.track {
                return v.serialize(&mut *self);
            }
            self.path.push(part());
            v.serialize(&mut *self)?;
            self.path.pop();
            Ok(())
        }
        fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
            let i = self.index.last().copied().unwrap_or(0);
            if let Some(last) = self.index.last_mut() {
                *last += 1;
            }
            self.nested(|| format!("[{i}]"), v)
        }
        fn open(&mut self) -> Result<&mut Self, Found> {
            self.index.push(0);
            Ok(self)
        }
        fn close(&mut self) -> R {
            self.index.pop();
            Ok(())
        }
    }

    macro_rules! ignore {
        ($($f:ident: $t:ty),*) => {
            $(fn $f(self, _: $t) -> R { Ok(()) })*
        };
    }

    impl ser::Serializer for &mut Walker {
        type Ok = ();
        type Error = Found;
        type SerializeSeq = Self;
        type SerializeTuple = Self;
        type SerializeTupleStruct = Self;
        type SerializeTupleVariant = Self;
        type SerializeMap = Self;
        type SerializeStruct = Self;
        type SerializeStructVariant = Self;
        ignore!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32, serialize_i64: i64,
            serialize_u8: u8, serialize_u16: u16, serialize_u32: u32, serialize_u64: u64, serialize_char: char,
            serialize_str: &str, serialize_bytes: &[u8], serialize_unit_struct: &'static str);
        fn serialize_f32(self, v: f32) -> R {
            self.float(v as f64)
        }
        fn serialize_f64(self, v: f64) -> R {
            self.float(v)
        }
        fn serialize_none(self) -> R {
            Ok(())
        }
        fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> R {
            v.serialize(self)
        }
        fn serialize_unit(self) -> R {
            Ok(())
        }
        fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> R {
            Ok(())
        }
        fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> R {
            v.serialize(self)
        }
        fn serialize_newtype_variant<T: Serialize + ?Sized>(self, _: &'static str, _: u32, variant: &'static str, v: &T) -> R {
            self.nested(|| format!(".{variant}"), v)
        }
        fn serialize_seq(self, _: Option<usize>) -> Result<Self, Found> {
            self.open()
        }
        fn serialize_tuple(self, _: usize) -> Result<Self, Found> {
            self.open()
        }
        fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Self, Found> {
            self.open()
        }
        fn serialize_tuple_variant(self, _: &'static str, _: u32, _: &'static str, _: usize) -> Result<Self, Found> {
            self.open()
        }
        fn serialize_map(self, _: Option<usize>) -> Result<Self, Found> {
            self.open()
        }
        fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self, Found> {
            Ok(self)
        }
        fn serialize_struct_variant(self, _: &'static str, _: u32, _: &'static str, _: usize) -> Result<Self, Found> {
            Ok(self)
        }
    }

    macro_rules! sequence {
        ($($tr:ident: $f:ident),*) => {$(
            impl ser::$tr for &mut Walker {
                type Ok = ();
                type Error = Found;
                fn $f<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
                    self.element(v)
                }
                fn end(self) -> R {
                    self.close()
                }
            }
        )*};
    }
    sequence!(SerializeSeq: serialize_element, SerializeTuple: serialize_element, SerializeTupleStruct: serialize_field, SerializeTupleVariant: serialize_field);

    impl ser::SerializeMap for &mut Walker {
        type Ok = ();
        type Error = Found;
        fn serialize_key<T: Serialize + ?Sized>(&mut self, _: &T) -> R {
            Ok(())
        }
        fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
            self.element(v)
        }
        fn end(self) -> R {
            self.close()
        }
    }

    macro_rules! structure {
        ($($tr:ident),*) => {$(
            impl ser::$tr for &mut Walker {
                type Ok = ();
                type Error = Found;
                fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> R {
                    self.nested(|| format!(".{key}"), v)
                }
                fn end(self) -> R {
                    Ok(())
                }
            }
        )*};
    }
    structure!(SerializeStruct, SerializeStructVariant);
}

/// The table of ranges as Markdown (docs/reference/robustness.md shows it).
pub fn markdown_table() -> String {
    let mut s = String::from("| field | range | why |\n|---|---|---|\n");
    for l in LIMITS {
        s.push_str(&format!("| `{}` | {} | {} |\n", l.field, l.describe(), l.why));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_ordered_and_fields_unique() {
        for (i, l) in LIMITS.iter().enumerate() {
            assert!(l.lo < l.hi, "{}", l.field);
            assert!(l.lo.is_finite() && l.hi.is_finite());
            assert!(LIMITS[..i].iter().all(|o| o.field != l.field), "{} twice", l.field);
            assert!(!l.contains(f64::NAN) && !l.contains(f64::INFINITY) && !l.contains(f64::NEG_INFINITY));
            assert!(!l.contains(1e308) && !l.contains(-1e308), "{}", l.field);
        }
    }

    #[test]
    fn the_docs_state_these_ranges() {
        let docs = include_str!("../../../docs/reference/robustness.md");
        assert!(docs.contains(&markdown_table()), "docs/reference/robustness.md must contain limits::markdown_table() verbatim:\n{}", markdown_table());
    }

    #[test]
    fn non_finite_outputs_are_found_with_their_path() {
        #[derive(serde::Serialize)]
        struct Speed {
            omega: f64,
            rpm: Option<f64>,
        }
        #[derive(serde::Serialize)]
        struct Out {
            name: String,
            speeds: Vec<Speed>,
            range: (f64, Option<f64>),
        }
        let mut out = Out { name: "x".into(), speeds: vec![Speed { omega: 1.0, rpm: None }, Speed { omega: 2.0, rpm: Some(3.0) }], range: (0.0, None) };
        assert!(check_finite("critical", &out).is_ok());
        out.speeds[1].rpm = Some(f64::INFINITY);
        assert_eq!(check_finite("critical", &out).unwrap_err(), Error::NonFinite { what: "critical.speeds[1].rpm".into(), t: None });
        out.speeds[1].rpm = None;
        out.range.1 = Some(f64::NAN);
        assert_eq!(check_finite("critical", &out).unwrap_err().to_string(), "critical.range[1] became non-finite");
    }

    #[test]
    fn open_and_closed_ends() {
        let m = limit("dimensionless.delta_a").unwrap();
        assert!(m.contains(0.0) && !m.contains(1.0) && m.contains(0.999));
        let k = limit("planar.k").unwrap();
        assert!(!k.contains(0.0) && k.contains(1e13) && !k.contains(1.0000001e13));
        assert_eq!(k.describe(), "(0, 1e13] N/m");
        assert_eq!(
            check("integration.rtol", 1.0).unwrap_err().to_string(),
            "integration.rtol: must lie in [1e-14, 0.01], got 1 (below 1e-14 double precision cannot reach it; above 1e-2 the error estimate no longer controls the error)"
        );
        assert_eq!(check_as("--omega-max", "analysis.omega_max", 1e308).unwrap_err().field(), Some("--omega-max"));
    }
}
