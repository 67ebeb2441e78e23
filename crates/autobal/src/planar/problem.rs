//! A planar simulation problem as one value: the rotor, its drive and the integration settings
//! ([`PlanarProblem`]), with paper 004's rotor as presets and defaults, builders, and the table
//! of parameter paths that sweeps use (`planar.c_psi`, `drive.b`, `drive.psi0[2]`, ...).
//!
//! ```
//! use autobal::planar::problem::PlanarProblem;
//! use autobal::planar::Drive;
//! use autobal::paths::Parameters;
//!
//! // paper 004's rotor with the light balls (m3 = 10 g), run up at 50 1/s² through resonance
//! let mut p = PlanarProblem::paper_004(0.01);
//! p.drive = Drive::Acceleration { omega0: 200.0, b: 50.0 };
//! p.set("drive.t_end", 4.0).unwrap();
//! let s = p.simulate_summary(&autobal::control::Control::none()).unwrap();
//! assert!(s.stopped.is_none());
//! assert!(s.omega_at_peak > 250.0 && s.omega_at_peak < 330.0);
//! assert!(!s.balanced); // too little ball mass: α∞ = 0.48 < 1
//! ```

use super::{Drive, PlanarRotor, Settings, Summary, MAX_BALLS};
use crate::builder::builder;
use crate::error::{Error, Result};
use crate::paths::{indexed, whole, ParameterPath, Parameters};
use serde::Serialize;

/// Shaft stiffness of paper 004's rotor (N/m): `sqrt(k/m0) = 288 1/s` with `m0 = 1.26 kg`
/// (`m3 = 0.03 kg`); kept when the ball mass changes, as in the paper's comparison.
pub const PAPER_004_K: f64 = 288.0 * 288.0 * 1.26;

impl PlanarRotor {
    /// Paper 004's rotor with ball mass `m3` (kg): the paper compares `m3 = 0.03` (balances)
    /// and `m3 = 0.01` (too little ball mass) on the same shaft ([`PAPER_004_K`]).
    pub fn paper_004(m3: f64) -> Self {
        PlanarRotor { m3, k: PAPER_004_K, ..PlanarRotor::paper() }
    }

    /// A builder starting from paper 004's rotor ([`PlanarRotor::paper`]).
    pub fn builder() -> PlanarRotorBuilder {
        PlanarRotorBuilder::default()
    }
}

/// Paper 004's rotor with `m3 = 0.03` kg ([`PlanarRotor::paper`]).
impl Default for PlanarRotor {
    fn default() -> Self {
        PlanarRotor::paper()
    }
}

builder!(
    /// Builder of a [`PlanarRotor`]; `build()` runs [`PlanarRotor::validate`], real balls
    /// included (they must fit on the race).
    ///
    /// ```
    /// use autobal::balls::BallPhysics;
    /// use autobal::planar::PlanarRotor;
    /// let touching = BallPhysics { contact: true, ..BallPhysics::default() };
    /// let r = PlanarRotor::builder().balls(touching.clone()).build().unwrap();
    /// assert!(r.balls.contact);
    /// // 20 balls of 30 g (19.4 mm steel) do not fit on paper 004's 60 mm race
    /// let e = PlanarRotor::builder().n(20).balls(touching).build().unwrap_err();
    /// assert!(e.to_string().starts_with("planar.ball_diameter"), "{e}");
    /// ```
    PlanarRotorBuilder for PlanarRotor, |r| r.validate();
    m1: f64, m2: f64, m3: f64, n: usize, s1: f64, s2: f64, gamma: f64, r: f64, k: f64, c: f64, c_psi: f64, c_theta: f64, i_g: f64,
    balls: crate::balls::BallPhysics,
);

/// Paper 004's run: from rest at `b = 2.5 1/s²` (`examples/planar.toml`).
impl Default for Drive {
    fn default() -> Self {
        Drive::Acceleration { omega0: 0.0, b: 2.5 }
    }
}

impl Settings {
    /// Settings for a rotor with `n` balls run to `t_end` (s): the automatic method (DOP853,
    /// switching to RODAS while stiff), `rtol = 1e-8`, `atol = 1e-9 m`, 2000 output intervals
    /// (`dt = t_end/2000`), balls spread evenly ([`Settings::default_psi0`]) at rest relative to
    /// the disk, C at rest on the axis, at most 20 million steps.
    pub fn for_balls(n: usize, t_end: f64) -> Self {
        Settings {
            method: Default::default(),
            t_end,
            dt: t_end / 2000.0,
            rtol: 1e-8,
            atol: 1e-9,
            psi0: Settings::default_psi0(n),
            psi_rate0: vec![0.0; n],
            xy0: [0.0; 2],
            xy_rate0: [0.0; 2],
            max_steps: 20_000_000,
            max_wall_s: None,
        }
    }
}

/// Paper 004's run for its two-ball rotor: 240 s sampled every 0.05 s (`examples/planar.toml`).
impl Default for Settings {
    fn default() -> Self {
        Settings { dt: 0.05, ..Settings::for_balls(2, 240.0) }
    }
}

impl Settings {
    /// A builder starting from [`Settings::default`] (paper 004's run).
    pub fn builder() -> SettingsBuilder {
        SettingsBuilder::default()
    }
}

builder!(
    /// Builder of the planar [`Settings`]; `build()` checks every field that does not depend on
    /// the rotor (as for a rotor with `psi0.len()` point-mass balls);
    /// [`PlanarProblem::validate`] checks them against the rotor they run.
    ///
    /// ```
    /// use autobal::planar::Settings;
    /// let s = Settings::builder().t_end(10.0).dt(0.01).rtol(1e-10).build().unwrap();
    /// assert_eq!((s.t_end, s.psi0.len()), (10.0, 2));
    /// assert!(Settings::builder().dt(-1.0).build().unwrap_err().to_string().starts_with("integration.dt"));
    /// ```
    SettingsBuilder for Settings, |s| s.validate(&PlanarRotor { n: s.psi0.len(), ..PlanarRotor::paper() });
    method: crate::ode::Method, t_end: f64, dt: f64, rtol: f64, atol: f64, psi0: Vec<f64>, psi_rate0: Vec<f64>, xy0: [f64; 2],
    xy_rate0: [f64; 2], max_steps: u64, max_wall_s: Option<f64>,
);

/// One simulation of the planar rotor: what [`simulate`](crate::planar::simulate) takes, as one value that paths
/// address and sweeps vary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanarProblem {
    /// The rotor.
    pub rotor: PlanarRotor,
    /// How it is driven.
    pub drive: Drive,
    /// Integration settings and initial ball positions.
    pub settings: Settings,
}

/// Paper 004's passage ([`PlanarProblem::paper_004`] with `m3 = 0.03` kg): the embedded
/// default of `autobal simulate`.
impl Default for PlanarProblem {
    fn default() -> Self {
        PlanarProblem::paper_004(0.03)
    }
}

impl PlanarProblem {
    /// Paper 004's passage with ball mass `m3` (kg): the rotor of [`PlanarRotor::paper_004`]
    /// run up from rest at `2.5 1/s²` for 240 s, samples every 0.05 s.
    pub fn paper_004(m3: f64) -> Self {
        PlanarProblem { rotor: PlanarRotor::paper_004(m3), drive: Drive::default(), settings: Settings::default() }
    }

    /// A builder starting from [`PlanarProblem::default`].
    pub fn builder() -> PlanarProblemBuilder {
        PlanarProblemBuilder::default()
    }

    /// Check rotor, drive and settings (errors name the field).
    pub fn validate(&self) -> Result<()> {
        // the rotor first (its ranges, then what its fields must satisfy together, e.g. a ball
        // diameter that fits the race), then every parameter path, derived ones included (the
        // default contact stiffness is derived from the ball's fit: checked after it)
        self.rotor.validate()?;
        check_ranges(self)?;
        check_natural_frequency(&self.rotor)?;
        self.drive.validate()?;
        self.settings.validate(&self.rotor)
    }

    /// Run it, keeping only the summary (sampled only at the ends; the same steps and summary as
    /// [`simulate`](crate::planar::simulate), see [`crate::planar::simulate_summary`]) under
    /// `control`.
    pub fn simulate_summary(&self, control: &crate::control::Control) -> Result<Summary> {
        crate::planar::simulate_summary(&self.rotor, &self.drive, &self.settings, control)
    }

    /// Set the number of balls, keeping the initial ball angles and rates when their number
    /// still fits and spreading the balls evenly otherwise.
    pub fn set_balls(&mut self, n: usize) {
        self.rotor.n = n;
        if self.settings.psi0.len() != n {
            self.settings.psi0 = Settings::default_psi0(n);
        }
        if self.settings.psi_rate0.len() != n {
            self.settings.psi_rate0 = vec![0.0; n];
        }
        // per-ball masses and drags: new balls get the mean (`m3`, `c_ψ`)
        let (m3, c_psi) = (self.rotor.m3, self.rotor.c_psi);
        for (list, fill) in [(&mut self.rotor.ball_masses, m3), (&mut self.rotor.ball_drags, c_psi)] {
            if let Some(v) = list {
                v.resize(n, fill);
            }
        }
    }
}

/// The shaft's natural frequency `sqrt(k/m0)` from 1e-3 to 1e7 rad/s (0.16 mHz to 1.6 MHz):
/// below, the shaft has no stiffness on any drive's time scale; above, it is rigid on them, and
/// the integrator would need ~100 steps per period of a vibration that plays no part.
pub fn check_natural_frequency(rotor: &PlanarRotor) -> Result<()> {
    let wn = rotor.natural_frequency();
    if !(1e-3..=1e7).contains(&wn) {
        return Err(Error::invalid(
            "planar.k",
            format!(
                "the natural frequency sqrt(k/m0) = {} rad/s (k = {} N/m, m0 = {} kg) lies outside [0.001, 1e7] rad/s",
                crate::error::fmt_num(wn),
                crate::error::fmt_num(rotor.k),
                crate::error::fmt_num(rotor.total_mass())
            ),
        ));
    }
    Ok(())
}

builder!(
    /// Builder of a [`PlanarProblem`]; `build()` runs [`PlanarProblem::validate`].
    PlanarProblemBuilder for PlanarProblem, |p| p.validate();
    rotor: PlanarRotor, drive: Drive, settings: Settings,
);

fn kind_error(d: &Drive, key: &str, kinds: &str) -> String {
    let kind = match d {
        Drive::Speed { .. } => "speed",
        Drive::Acceleration { .. } => "acceleration",
        Drive::Torque { .. } => "torque",
        Drive::Motor { .. } => "motor",
        Drive::TorqueSchedule { .. } => "torque schedule",
        Drive::SpeedSchedule { .. } => "speed schedule",
    };
    format!("the drive is of kind {kind}, which has no {key} (only {kinds})")
}

macro_rules! rotor_path {
    ($path:literal, $doc:literal, $field:ident) => {
        ParameterPath {
            path: $path,
            doc: $doc,
            set: |p, v| {
                p.rotor.$field = v;
                Ok(())
            },
            get: |p| Ok(p.rotor.$field),
        }
    };
}

/// A path to a number of the rotor's real-ball physics (`planar.restitution`, ...).
macro_rules! balls_path {
    ($path:literal, $doc:literal, $field:ident) => {
        ParameterPath {
            path: $path,
            doc: $doc,
            set: |p, v| {
                p.rotor.balls.$field = v;
                Ok(())
            },
            get: |p| Ok(p.rotor.balls.$field),
        }
    };
}

macro_rules! settings_path {
    ($path:literal, $doc:literal, $field:ident) => {
        ParameterPath {
            path: $path,
            doc: $doc,
            set: |p, v| {
                p.settings.$field = v;
                Ok(())
            },
            get: |p| Ok(p.settings.$field),
        }
    };
}

static PLANAR_PATHS: &[ParameterPath<PlanarProblem>] = &[
    rotor_path!("planar.m1", "disk mass m1 (kg)", m1),
    rotor_path!("planar.m2", "balancer housing mass m2 (kg)", m2),
    ParameterPath {
        path: "planar.m3",
        doc: "mass of one ball m3 (kg)",
        set: |p, v| {
            if p.rotor.ball_masses.is_some() {
                return Err("the balls have their own masses (planar.ball_masses): set planar.ball_masses[j]".into());
            }
            p.rotor.m3 = v;
            Ok(())
        },
        get: |p| Ok(p.rotor.m3),
    },
    ParameterPath {
        path: "planar.n",
        doc: "number of balls (initial angles spread evenly when their number changes)",
        set: |p, v| {
            p.set_balls(whole(v, MAX_BALLS as u64)? as usize);
            Ok(())
        },
        get: |p| Ok(p.rotor.n as f64),
    },
    rotor_path!("planar.s1", "static eccentricity of the disk s1 = |CG| (m)", s1),
    rotor_path!("planar.s2", "eccentricity of the balancer s2 = |CE| (m)", s2),
    rotor_path!("planar.gamma", "angle γ between CG and CE (rad)", gamma),
    rotor_path!("planar.r", "race radius r (m)", r),
    ParameterPath {
        path: "planar.k",
        doc: "shaft stiffness k (N/m), the same in every direction",
        set: |p, v| {
            if p.rotor.k_y.is_some() {
                return Err("the supports are given per direction (planar.k_x, planar.k_y): set one of those".into());
            }
            p.rotor.k = v;
            Ok(())
        },
        get: |p| match p.rotor.k_y {
            Some(ky) if ky != p.rotor.k => Err("the supports differ by direction: read planar.k_x or planar.k_y".into()),
            _ => Ok(p.rotor.k),
        },
    },
    ParameterPath {
        path: "planar.k_x",
        doc: "support stiffness along the fixed x axis k_x (N/m)",
        set: |p, v| {
            p.rotor.k_y = Some(p.rotor.k_y.unwrap_or(p.rotor.k));
            p.rotor.k = v;
            Ok(())
        },
        get: |p| Ok(p.rotor.k),
    },
    ParameterPath {
        path: "planar.k_y",
        doc: "support stiffness along the fixed y axis k_y (N/m)",
        set: |p, v| {
            p.rotor.k_y = Some(v);
            Ok(())
        },
        get: |p| Ok(p.rotor.k_y.unwrap_or(p.rotor.k)),
    },
    ParameterPath {
        path: "planar.c",
        doc: "external damping c (kg/s), the same in every direction",
        set: |p, v| {
            if p.rotor.c_y.is_some() {
                return Err("the damping is given per direction (planar.c_x, planar.c_y): set one of those".into());
            }
            p.rotor.c = v;
            Ok(())
        },
        get: |p| match p.rotor.c_y {
            Some(cy) if cy != p.rotor.c => Err("the damping differs by direction: read planar.c_x or planar.c_y".into()),
            _ => Ok(p.rotor.c),
        },
    },
    ParameterPath {
        path: "planar.c_x",
        doc: "support damping along the fixed x axis c_x (kg/s)",
        set: |p, v| {
            p.rotor.c_y = Some(p.rotor.c_y.unwrap_or(p.rotor.c));
            p.rotor.c = v;
            Ok(())
        },
        get: |p| Ok(p.rotor.c),
    },
    ParameterPath {
        path: "planar.c_y",
        doc: "support damping along the fixed y axis c_y (kg/s)",
        set: |p, v| {
            p.rotor.c_y = Some(v);
            Ok(())
        },
        get: |p| Ok(p.rotor.c_y.unwrap_or(p.rotor.c)),
    },
    ParameterPath {
        path: "planar.c_psi",
        doc: "drag on each ball c_ψ (N·m·s)",
        set: |p, v| {
            if p.rotor.ball_drags.is_some() {
                return Err("the balls have their own drags (planar.ball_drags): set planar.ball_drags[j]".into());
            }
            p.rotor.c_psi = v;
            Ok(())
        },
        get: |p| Ok(p.rotor.c_psi),
    },
    rotor_path!("planar.c_theta", "bearing drag c_θ (N·m·s)", c_theta),
    rotor_path!("planar.i_g", "central moment of inertia I_G (kg·m²)", i_g),
    ParameterPath {
        path: "planar.ball_diameter",
        doc: "ball diameter (m; default: steel balls of mass m3)",
        set: |p, v| {
            p.rotor.balls.diameter = Some(v);
            Ok(())
        },
        get: |p| Ok(p.rotor.balls.diameter(p.rotor.m3)),
    },
    ParameterPath {
        path: "planar.contact",
        doc: "balls of finite size that collide: 1 on, 0 off",
        set: |p, v| {
            p.rotor.balls.contact = whole(v, 1)? == 1;
            Ok(())
        },
        get: |p| Ok(if p.rotor.balls.contact { 1.0 } else { 0.0 }),
    },
    balls_path!("planar.restitution", "restitution coefficient e of ball–ball impacts", restitution),
    ParameterPath {
        path: "planar.contact_stiffness",
        doc: "ball–ball contact stiffness (N/m; default: contact frequency 20 sqrt(k/m0))",
        set: |p, v| {
            p.rotor.balls.contact_stiffness = Some(v);
            Ok(())
        },
        get: |p| {
            Ok(crate::balls::BallForces::new(
                &crate::balls::BallPhysics { contact: true, ..p.rotor.balls },
                p.rotor.m3,
                p.rotor.r,
                p.rotor.n.max(2),
                p.rotor.natural_frequency(),
            )
            .and_then(|f| f.contact)
            .map_or(f64::NAN, |c| c.stiffness))
        },
    },
    balls_path!("planar.rolling_resistance", "rolling-resistance coefficient μ_r of the balls on their race", rolling_resistance),
    balls_path!("planar.slip_rate", "regularisation v_ε of the rolling resistance's sign (rad/s)", slip_rate),
    ParameterPath {
        path: "drive.omega0",
        doc: "initial speed ω0 (rad/s)",
        set: |p, v| {
            match &mut p.drive {
                Drive::Speed { omega0 }
                | Drive::Acceleration { omega0, .. }
                | Drive::Torque { omega0, .. }
                | Drive::Motor { omega0, .. }
                | Drive::TorqueSchedule { omega0, .. } => *omega0 = v,
                d @ Drive::SpeedSchedule { .. } => return Err(kind_error(d, "omega0", "kinds speed, acceleration, torque, motor, torque schedule")),
            }
            Ok(())
        },
        get: |p| match &p.drive {
            Drive::SpeedSchedule { .. } => Err(kind_error(&p.drive, "omega0", "kinds speed, acceleration, torque, motor, torque schedule")),
            d => Ok(d.omega0()),
        },
    },
    ParameterPath {
        path: "drive.b",
        doc: "angular acceleration b (rad/s²), kind acceleration",
        set: |p, v| match &mut p.drive {
            Drive::Acceleration { b, .. } => {
                *b = v;
                Ok(())
            }
            d => Err(kind_error(d, "b", "kind acceleration")),
        },
        get: |p| match &p.drive {
            Drive::Acceleration { b, .. } => Ok(*b),
            d => Err(kind_error(d, "b", "kind acceleration")),
        },
    },
    ParameterPath {
        path: "drive.torque",
        doc: "torque M (N·m), kinds torque and motor (stall torque)",
        set: |p, v| match &mut p.drive {
            Drive::Torque { torque, .. } | Drive::Motor { torque, .. } => {
                *torque = v;
                Ok(())
            }
            d => Err(kind_error(d, "torque", "kinds torque, motor")),
        },
        get: |p| match &p.drive {
            Drive::Torque { torque, .. } | Drive::Motor { torque, .. } => Ok(*torque),
            d => Err(kind_error(d, "torque", "kinds torque, motor")),
        },
    },
    ParameterPath {
        path: "drive.omega_idle",
        doc: "no-load speed of the motor ω_idle (rad/s), kind motor",
        set: |p, v| match &mut p.drive {
            Drive::Motor { omega_idle, .. } => {
                *omega_idle = v;
                Ok(())
            }
            d => Err(kind_error(d, "omega_idle", "kind motor")),
        },
        get: |p| match &p.drive {
            Drive::Motor { omega_idle, .. } => Ok(*omega_idle),
            d => Err(kind_error(d, "omega_idle", "kind motor")),
        },
    },
    ParameterPath {
        path: "drive.t_off",
        doc: "time the torque is switched off (s), kinds torque and motor",
        set: |p, v| match &mut p.drive {
            Drive::Torque { t_off, .. } | Drive::Motor { t_off, .. } => {
                *t_off = Some(v);
                Ok(())
            }
            d => Err(kind_error(d, "t_off", "kinds torque, motor")),
        },
        get: |p| match &p.drive {
            Drive::Torque { t_off, .. } | Drive::Motor { t_off, .. } => t_off.ok_or_else(|| "not set: the torque stays on".to_string()),
            d => Err(kind_error(d, "t_off", "kinds torque, motor")),
        },
    },
    settings_path!("drive.t_end", "simulated time (s)", t_end),
    settings_path!("integration.rtol", "relative tolerance", rtol),
    settings_path!("integration.atol", "absolute tolerance on displacements (m)", atol),
    settings_path!("integration.dt", "output interval (s)", dt),
    // documented here; set through the indexed form `drive.psi0[j]`
    ParameterPath {
        path: "drive.psi0[j]",
        doc: "initial angle of ball j = 1…n from CG (rad)",
        set: |_, _| Err("give the ball's number, e.g. drive.psi0[1]".into()),
        get: |_| Err("give the ball's number, e.g. drive.psi0[1]".into()),
    },
    ParameterPath {
        path: "planar.ball_masses[j]",
        doc: "mass of ball j = 1…n (kg; the others keep m3 when first set)",
        set: |_, _| Err("give the ball's number, e.g. planar.ball_masses[1]".into()),
        get: |_| Err("give the ball's number, e.g. planar.ball_masses[1]".into()),
    },
    ParameterPath {
        path: "planar.ball_drags[j]",
        doc: "drag on ball j = 1…n (N·m·s; the others keep c_psi when first set)",
        set: |_, _| Err("give the ball's number, e.g. planar.ball_drags[1]".into()),
        get: |_| Err("give the ball's number, e.g. planar.ball_drags[1]".into()),
    },
    ParameterPath {
        path: "drive.psi_rate0[j]",
        doc: "initial rate of ball j = 1…n relative to the disk (rad/s)",
        set: |_, _| Err("give the ball's number, e.g. drive.psi_rate0[1]".into()),
        get: |_| Err("give the ball's number, e.g. drive.psi_rate0[1]".into()),
    },
];

/// The per-ball vector an indexed path names, and the checked index.
fn ball_slot<'a>(p: &'a mut PlanarProblem, path: &str) -> Option<Result<&'a mut f64>> {
    let (name, j) = indexed(path)?;
    let n = p.rotor.n;
    let v = match name {
        "drive.psi0" => &mut p.settings.psi0,
        "drive.psi_rate0" => &mut p.settings.psi_rate0,
        "planar.ball_masses" => p.rotor.ball_masses.get_or_insert_with(|| vec![p.rotor.m3; n]),
        "planar.ball_drags" => p.rotor.ball_drags.get_or_insert_with(|| vec![p.rotor.c_psi; n]),
        _ => return None,
    };
    Some(match j {
        Ok(j) if j < n && j < v.len() => Ok(&mut v[j]),
        Ok(j) => Err(Error::invalid(path, format!("ball {} does not exist: the rotor has {n} (planar.n)", j + 1))),
        Err(reason) => Err(Error::invalid(path, reason)),
    })
}

impl Parameters for PlanarProblem {
    fn parameter_paths() -> &'static [ParameterPath<Self>] {
        PLANAR_PATHS
    }

    fn set(&mut self, path: &str, value: f64) -> Result<()> {
        if let Some(slot) = ball_slot(self, path) {
            *slot? = value;
            // m3 and c_ψ stay the balls' means (the reference of tolerances and scales)
            let mean = |v: &[f64]| if v.is_empty() { None } else { Some(v.iter().sum::<f64>() / v.len() as f64) };
            if let Some(m) = self.rotor.ball_masses.as_deref().and_then(mean) {
                self.rotor.m3 = m;
            }
            if let Some(c) = self.rotor.ball_drags.as_deref().and_then(mean) {
                self.rotor.c_psi = c;
            }
            return Ok(());
        }
        let p = crate::paths::find::<Self>(path)?;
        (p.set)(self, value).map_err(|reason| Error::invalid(path, reason))
    }

    fn get(&self, path: &str) -> Result<f64> {
        let mut copy = self.clone();
        if let Some(slot) = ball_slot(&mut copy, path) {
            return slot.map(|v| *v);
        }
        let p = crate::paths::find::<Self>(path)?;
        (p.get)(self).map_err(|reason| Error::invalid(path, reason))
    }
}

/// A planar problem (after [`PlanarRotor::validate`]), drive and integration settings through
/// their parameter paths, the initial ball angles and rates and the rotor's initial position and
/// velocity one by one, and the step and wall-clock budgets.
/// [`PlanarProblem::validate`] calls it.
fn check_ranges(p: &PlanarProblem) -> Result<()> {
    use crate::limits::{check, check_parameters};
    check_parameters(p)?;
    let s = &p.settings;
    s.psi0.iter().try_for_each(|v| check("drive.psi0", *v).map(|_| ()))?;
    s.psi_rate0.iter().try_for_each(|v| check("drive.psi_rate0", *v).map(|_| ()))?;
    s.xy0.iter().try_for_each(|v| check("drive.xy0", *v).map(|_| ()))?;
    s.xy_rate0.iter().try_for_each(|v| check("drive.xy_rate0", *v).map(|_| ()))?;
    check("integration.max_steps", s.max_steps as f64)?;
    s.max_wall_s.map_or(Ok(()), |w| check("integration.max_wall_s", w).map(|_| ()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_path_round_trips_or_names_itself() {
        for p in PLANAR_PATHS {
            let mut s = PlanarProblem::default();
            match s.get(p.path) {
                Ok(v) => {
                    let w = match p.path {
                        "planar.n" => 3.0,
                        "planar.contact" => 1.0 - v,
                        _ => v + 0.5,
                    };
                    s.set(p.path, w).unwrap();
                    assert_eq!(s.get(p.path).unwrap(), w, "{}", p.path);
                }
                Err(e) => assert!(e.to_string().starts_with(p.path), "{e}"),
            }
        }
    }

    #[test]
    fn paths_name_themselves_in_errors() {
        let mut p = PlanarProblem::default();
        let e = p.set("drive.torque", 3.0).unwrap_err().to_string();
        assert!(e.starts_with("drive.torque: the drive is of kind acceleration"), "{e}");
        let e = p.set("drive.psi0[3]", 1.0).unwrap_err().to_string();
        assert!(e.starts_with("drive.psi0[3]: ball 3 does not exist"), "{e}");
        p.set("drive.psi0[2]", 1.0).unwrap();
        assert_eq!(p.settings.psi0[1], 1.0);
        assert_eq!(p.get("drive.psi0[2]").unwrap(), 1.0);
        let e = p.set("planar.n", 2.5).unwrap_err().to_string();
        assert!(e.starts_with("planar.n: must be a whole number"), "{e}");
        // more balls: their initial angles are spread again, so the problem stays valid
        p.set("planar.n", 3.0).unwrap();
        assert_eq!(p.settings.psi0.len(), 3);
        p.validate().unwrap();
        // a value the model refuses is refused when the problem is used, naming the field
        p.set("planar.k", -1.0).unwrap();
        assert!(p.validate().unwrap_err().to_string().starts_with("planar.k"));
    }

    #[test]
    fn presets_are_paper_004() {
        let p = PlanarProblem::default();
        assert_eq!(p, PlanarProblem::paper_004(0.03));
        // sqrt(k/m0) = 288 1/s for the heavier balls, the same shaft for the lighter ones
        assert!((p.rotor.natural_frequency() - 288.0).abs() < 1e-9);
        assert_eq!(PlanarRotor::paper_004(0.01).k, p.rotor.k);
        assert_eq!(PlanarRotor::paper(), PlanarRotor::paper_004(0.03));
        p.validate().unwrap();
        let b = PlanarProblem::builder().drive(Drive::Speed { omega0: 100.0 }).build().unwrap();
        assert_eq!(b.drive, Drive::Speed { omega0: 100.0 });
        assert!(PlanarProblem::builder().settings(Settings::for_balls(3, 1.0)).build().unwrap_err().to_string().starts_with("drive.psi0"));
    }
}
