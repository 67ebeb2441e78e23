//! Steady synchronous whirls of the rotor with its balls held fixed relative to it: the
//! stationary response curves beside which a run-up is drawn (the rotor of the papers with the
//! balls locked where they start, `s ≢ 0`).
//!
//! In axes turning with the rotor a synchronous whirl is a fixed point of the equations
//! ([`super::equations`]): `q̈ = 0` with `q̇ = 0` and `φ̇ = Ω`. It is found by Newton's method on
//! the nonlinear equations themselves (no linearisation of the unbalance forcing), continued
//! along the speed axis. With supports that differ by direction no synchronous whirl exists
//! (the response is elliptical, with a 2Ω component in turning axes); the curves then use the
//! supports averaged over direction, `½ (k_x + k_y)`, `½ (c_x + c_y)`.

use super::equations::{Equations, ROTOR_COORDS};
use super::rotor::{PointMass, SpatialRotor, Support};
use crate::drive::Drive;
use crate::ode::System;
use serde::Serialize;

/// One steady whirl.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Whirl {
    /// Speed.
    pub omega: f64,
    /// `(ξ, η, δ, θ)` in the turning frame.
    pub position: [f64; 4],
    /// Whirl radius of the shaft at each balancer plane (at the first unbalance mass's plane
    /// when there are no balls).
    pub amplitude_planes: Vec<f64>,
    /// Whirl radius of the shaft at each support.
    pub amplitude_supports: Vec<f64>,
}

/// The rotor with its balls turned into fixed point masses at `psi` (all planes in order),
/// supports averaged over direction, no gravity.
pub fn locked_rotor(rotor: &SpatialRotor, psi: &[f64]) -> SpatialRotor {
    let mut r = rotor.clone();
    let mut k = 0;
    for p in &rotor.planes {
        for _ in 0..p.n {
            r.unbalances.push(PointMass { mass: p.ball_mass, radius: p.race_radius, angle: psi.get(k).copied().unwrap_or(0.0), z: p.z });
            k += 1;
        }
    }
    r.planes.clear();
    r.gravity = [0.0; 3];
    r.supports = rotor
        .supports
        .iter()
        .map(|s| Support { z: s.z, stiffness: [0.5 * (s.stiffness[0] + s.stiffness[1]); 2], damping: [0.5 * (s.damping[0] + s.damping[1]); 2] })
        .collect();
    r
}

fn residual(eq: &Equations, x: &[f64; 4], omega: f64, free: usize) -> [f64; 4] {
    let nc = eq.coords();
    let mut y = vec![0.0; 2 * nc];
    y[..4].copy_from_slice(x);
    y[nc + 4] = omega;
    let mut dy = vec![0.0; 2 * nc];
    eq.rhs(0.0, &y, &mut dy);
    let mut r = [0.0; 4];
    r[..free].copy_from_slice(&dy[nc..nc + free]);
    r
}

/// The steady whirl at `omega` by Newton's method from `guess` (finite-difference Jacobian);
/// `None` if it does not converge (e.g. an undamped rotor at a critical speed).
pub fn whirl(rotor: &SpatialRotor, psi: &[f64], omega: f64, guess: [f64; 4]) -> Option<Whirl> {
    let locked = locked_rotor(rotor, psi);
    let drive = Drive::Speed { omega0: omega };
    let eq = Equations::new(&locked, &drive);
    let free = if locked.lock_tilt { 2 } else { ROTOR_COORDS - 1 };
    let mut x = guess;
    if locked.lock_tilt {
        x[2] = 0.0;
        x[3] = 0.0;
    }
    let len = rotor.length_scale();
    for _ in 0..40 {
        let r = residual(&eq, &x, omega, free);
        let mut jac = [[0.0; 4]; 4];
        for c in 0..free {
            let h = 1e-7 * (len + x[c].abs());
            let (mut xp, mut xm) = (x, x);
            xp[c] += h;
            xm[c] -= h;
            let (rp, rm) = (residual(&eq, &xp, omega, free), residual(&eq, &xm, omega, free));
            for i in 0..free {
                jac[i][c] = (rp[i] - rm[i]) / (2.0 * h);
            }
        }
        let mut dx = r;
        if !crate::linalg::dense::solve_once(&mut jac, &mut dx, free) {
            return None;
        }
        let mut step: f64 = 0.0;
        for c in 0..free {
            x[c] -= dx[c];
            step = step.max(dx[c].abs());
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if step <= 1e-13 * (len + x.iter().fold(0.0f64, |m, v| m.max(v.abs()))) {
            let nc = eq.coords();
            let mut y = vec![0.0; 2 * nc];
            y[..4].copy_from_slice(&x);
            let amp = |z: f64| {
                let d = eq.displacement_at(&y, z);
                d[0].hypot(d[1])
            };
            let planes = if rotor.planes.is_empty() {
                rotor.unbalances.first().map(|u| amp(u.z)).into_iter().collect()
            } else {
                rotor.planes.iter().map(|p| amp(p.z)).collect()
            };
            return Some(Whirl { omega, position: x, amplitude_planes: planes, amplitude_supports: rotor.supports.iter().map(|s| amp(s.z)).collect() });
        }
    }
    None
}

/// Steady whirls along `omegas`, each Newton iteration started from the previous whirl.
pub fn response_curve(rotor: &SpatialRotor, psi: &[f64], omegas: &[f64]) -> Vec<Option<Whirl>> {
    let mut guess = [0.0; 4];
    omegas
        .iter()
        .map(|&w| {
            let r = whirl(rotor, psi, w, guess).or_else(|| whirl(rotor, psi, w, [0.0; 4]));
            if let Some(s) = &r {
                guess = s.position;
            }
            r
        })
        .collect()
}
