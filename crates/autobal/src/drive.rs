//! How a rotor is driven: a prescribed speed history (kinematic drive) or a torque acting on a
//! free rotor. Shared by the dynamic models.

use crate::error::{finite, non_negative, positive, Error, Result};
use serde::Serialize;

/// How the rotor is driven.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Drive {
    /// Constant speed `θ̇ = ω0`.
    Speed {
        /// The speed `ω0` (rad/s, or Ω in a dimensionless model).
        omega0: f64,
    },
    /// Constant angular acceleration `θ̇ = ω0 + b t` (`b < 0`: reverse passage); the speed is
    /// held at 0 once reached.
    Acceleration {
        /// Speed at `t = 0`.
        omega0: f64,
        /// Angular acceleration `b` (rad/s², or the papers' dimensionless rate).
        b: f64,
    },
    /// Free rotor under a constant torque `M` (N·m) until `t_off` (run-down after it).
    Torque {
        /// Speed at `t = 0`.
        omega0: f64,
        /// The constant torque `M` (N·m).
        torque: f64,
        /// When the torque is switched off (`None`: never).
        t_off: Option<f64>,
    },
    /// Free rotor under a motor with a linear characteristic `M(ω) = M0 (1 − ω/ω_idle)`, the
    /// classical non-ideal source of the Sommerfeld effect; switched off at `t_off`.
    Motor {
        /// Speed at `t = 0`.
        omega0: f64,
        /// Stall torque `M0` (N·m), the torque at `ω = 0`.
        torque: f64,
        /// Idle speed `ω_idle`, where the motor's torque falls to zero.
        omega_idle: f64,
        /// When the motor is switched off (`None`: never).
        t_off: Option<f64>,
    },
    /// Piecewise-linear torque (free rotor) through `(t, M)` points.
    TorqueSchedule {
        /// Speed at `t = 0`.
        omega0: f64,
        /// `(t, M)` points, times increasing; the torque is held constant outside them.
        points: Vec<(f64, f64)>,
    },
    /// Piecewise-linear prescribed speed through `(t, ω)` points.
    SpeedSchedule {
        /// `(t, ω)` points, times increasing; the speed is held constant outside them.
        points: Vec<(f64, f64)>,
    },
}

fn interp(points: &[(f64, f64)], t: f64) -> (f64, f64) {
    // value and slope of the piecewise-linear function (held constant outside)
    if t <= points[0].0 {
        return (points[0].1, 0.0);
    }
    for w in points.windows(2) {
        if t <= w[1].0 {
            let s = (w[1].1 - w[0].1) / (w[1].0 - w[0].0);
            return (w[0].1 + s * (t - w[0].0), s);
        }
    }
    (points[points.len() - 1].1, 0.0)
}

impl Drive {
    /// Validate (errors name `drive.<field>`).
    pub fn validate(&self) -> Result<()> {
        let check_points = |pts: &[(f64, f64)]| -> Result<()> {
            if pts.len() < 2 {
                return Err(Error::invalid("drive.schedule", "needs at least two [t, value] points"));
            }
            for w in pts.windows(2) {
                if w[1].0.partial_cmp(&w[0].0) != Some(std::cmp::Ordering::Greater) {
                    return Err(Error::invalid("drive.schedule", "times must increase strictly"));
                }
            }
            for p in pts {
                finite("drive.schedule", p.0)?;
                finite("drive.schedule", p.1)?;
            }
            Ok(())
        };
        match self {
            Drive::Speed { omega0 } => finite("drive.omega0", *omega0).map(|_| ()),
            Drive::Acceleration { omega0, b } => {
                finite("drive.omega0", *omega0)?;
                finite("drive.b", *b)?;
                if *b == 0.0 {
                    return Err(Error::invalid("drive.b", "must not be 0 for kind = \"acceleration\" (use kind = \"speed\")"));
                }
                Ok(())
            }
            Drive::Torque { omega0, torque, t_off } => {
                finite("drive.omega0", *omega0)?;
                finite("drive.torque", *torque)?;
                if let Some(t) = t_off {
                    non_negative("drive.t_off", *t)?;
                }
                Ok(())
            }
            Drive::Motor { omega0, torque, omega_idle, t_off } => {
                finite("drive.omega0", *omega0)?;
                finite("drive.torque", *torque)?;
                positive("drive.omega_idle", *omega_idle)?;
                if let Some(t) = t_off {
                    non_negative("drive.t_off", *t)?;
                }
                Ok(())
            }
            Drive::TorqueSchedule { omega0, points } => {
                finite("drive.omega0", *omega0)?;
                check_points(points)
            }
            Drive::SpeedSchedule { points } => check_points(points),
        }
    }

    /// Whether the speed is prescribed (kinematic drive) rather than the result of a torque.
    pub fn prescribed(&self) -> bool {
        matches!(self, Drive::Speed { .. } | Drive::Acceleration { .. } | Drive::SpeedSchedule { .. })
    }

    /// Whether the speed is prescribed and constant at time `t`: a kinematic drive
    /// ([`Drive::prescribed`]) whose `θ̈` ([`Drive::kinematics`]) is exactly 0 there (a
    /// [`Drive::Speed`], a schedule's hold or its end, a run-down stopped at rest). The runs'
    /// end checks ask it at the end time: only then is the end a rotor turned at the constant
    /// speed whose stationary states `stability` analyses.
    pub fn constant_speed_at(&self, t: f64) -> bool {
        self.prescribed() && self.kinematics(t).1 == 0.0
    }

    /// Initial speed.
    pub fn omega0(&self) -> f64 {
        match self {
            Drive::Speed { omega0 }
            | Drive::Acceleration { omega0, .. }
            | Drive::Torque { omega0, .. }
            | Drive::Motor { omega0, .. }
            | Drive::TorqueSchedule { omega0, .. } => *omega0,
            Drive::SpeedSchedule { points } => interp(points, 0.0).0,
        }
    }

    /// Times where the drive changes abruptly (schedule points, switch-off, the stop of a
    /// run-down): `simulate` integrates piecewise between them, so that no step straddles a jump
    /// of the torque or the acceleration.
    pub fn breakpoints(&self) -> Vec<f64> {
        match self {
            Drive::Acceleration { omega0, b } if *b < 0.0 && *omega0 > 0.0 => vec![omega0 / -b],
            Drive::Torque { t_off: Some(t), .. } | Drive::Motor { t_off: Some(t), .. } => vec![*t],
            Drive::TorqueSchedule { points, .. } | Drive::SpeedSchedule { points } => points.iter().map(|p| p.0).collect(),
            _ => vec![],
        }
    }

    /// Prescribed `(θ̇, θ̈)` at time `t`, for kinematic drives.
    pub fn kinematics(&self, t: f64) -> (f64, f64) {
        match self {
            Drive::Speed { omega0 } => (*omega0, 0.0),
            Drive::Acceleration { omega0, b } => {
                let w = omega0 + b * t;
                if *b < 0.0 && w <= 0.0 {
                    (0.0, 0.0) // a run-down stops at rest
                } else {
                    (w, *b)
                }
            }
            Drive::SpeedSchedule { points } => interp(points, t),
            _ => (0.0, 0.0),
        }
    }

    /// `∂M/∂ω` of the applied torque at `(t, ω)` (for exact Jacobians): `−M0/ω_idle` for a
    /// running motor, 0 otherwise.
    pub fn torque_slope(&self, t: f64, _omega: f64) -> f64 {
        match self {
            Drive::Motor { torque, omega_idle, t_off, .. } if !t_off.is_some_and(|off| t >= off) => -torque / omega_idle,
            _ => 0.0,
        }
    }

    /// Applied torque at time `t` and speed `omega`, for free-rotor drives.
    pub fn torque(&self, t: f64, omega: f64) -> f64 {
        match self {
            Drive::Torque { torque, t_off, .. } => {
                if t_off.is_some_and(|off| t >= off) {
                    0.0
                } else {
                    *torque
                }
            }
            Drive::Motor { torque, omega_idle, t_off, .. } => {
                if t_off.is_some_and(|off| t >= off) {
                    0.0
                } else {
                    torque * (1.0 - omega / omega_idle)
                }
            }
            Drive::TorqueSchedule { points, .. } => interp(points, t).0,
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Drive;

    /// The end checks' gate: constant exactly where the prescribed speed's slope is zero
    /// (read off each drive's definition), never for a torque drive, whose speed is the
    /// motion's own.
    #[test]
    fn constant_speed_at_is_a_prescribed_speed_of_zero_slope() {
        assert!(Drive::Speed { omega0: 100.0 }.constant_speed_at(5.0));
        assert!(!Drive::Acceleration { omega0: 0.0, b: 2.5 }.constant_speed_at(5.0));
        // a run-down from 10 rad/s at −2 rad/s² stops at t = 5 s and is held at rest
        let down = Drive::Acceleration { omega0: 10.0, b: -2.0 };
        assert!(!down.constant_speed_at(4.0) && down.constant_speed_at(6.0));
        // a ramp to 1400 rad/s by 6 s, then a hold to 12 s (examples/spatial_two_plane.toml)
        let schedule = Drive::SpeedSchedule { points: vec![(0.0, 100.0), (6.0, 1400.0), (12.0, 1400.0)] };
        assert!(!schedule.constant_speed_at(3.0) && schedule.constant_speed_at(9.0) && schedule.constant_speed_at(12.0));
        assert!(!Drive::Torque { omega0: 0.0, torque: 0.0, t_off: None }.constant_speed_at(1.0));
    }
}
