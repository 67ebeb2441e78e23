//! The exact Jacobian of a torque-driven run-up of the linear rotor ([`RunUpSystem`]: the spin
//! angle and speed are states, the accelerations solve a bordered system) against central
//! differences of the right-hand side.

use autobal::drive::Drive;
use autobal::linear_rotor::runup::RunUpSystem;
use autobal::linear_rotor::shaft::{Bearing, Disk, Element, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, SpeedBearing, Unbalance};
use autobal::ode::System;

/// A shaft with tilt DOFs, gyroscopic terms, an unbalance and a three-ball balancer off their
/// node's plane, a bearing tabulated over speed (anisotropic, cross-coupled), gravity, under a
/// motor whose torque falls with speed; at a state off equilibrium (every component at a random
/// fraction of its scale: `1e-4` m, `1e-3` rad for the tilts, 1 rad for the angles, times the
/// speed for the rates), at a speed inside the bearing's table (so that `∂K/∂Ω`, `∂C/∂Ω` act).
/// Central differences with step `h = 1e-6` of each component's scale have truncation error
/// `O(h²)` and round-off `O(ε/h) ≈ 1e-10` relative: `1e-6` of the row's size (each entry
/// weighted by its column's scale) is far above both and far below any error in a term (a
/// missing `½ φ̈ G q`, unbalance `Ω̇` term or bearing slope changes entries by 1e-3 to 1 of the
/// row).
#[test]
fn torque_jacobian_is_exact() {
    let mut b = ShaftBuilder { rotary_inertia: true, gyroscopic: true, ..Default::default() };
    for _ in 0..3 {
        b.elements.push(Element::circular(0.15, 0.03, 2.1e11, 7800.0));
    }
    b.disks.push(Disk { node: 1, mass: 2.0, id: 4e-3, ip: 8e-3 });
    b.bearings.push(Bearing { node: 3, k: 3e6, c: 150.0 });
    let mut r = b.build().unwrap();
    r.speed_bearings.push(SpeedBearing {
        node: 0,
        link: None,
        speeds: vec![100.0, 300.0, 700.0],
        k: vec![[1e6, 0.0, 0.0, 2e6], [2e6, 1e5, -1e5, 3e6], [4e6, 0.0, 0.0, 4e6]],
        c: vec![[100.0, 0.0, 0.0, 100.0], [300.0, 20.0, 0.0, 200.0], [500.0, 0.0, 0.0, 500.0]],
    });
    r.unbalances.push(Unbalance { node: 1, me: 2e-4, phase: 0.3, offset: 0.02 });
    r.balancers.push(BalancerPlane { node: 1, radius: 0.05, balls: 3, ball_mass: 0.02, drag: 0.01, offset: -0.03 });
    r.set_gravity([1.0, -9.81]);
    r.spin_damping = 1e-3;
    let w = 250.0;
    let drive = Drive::Motor { omega0: w, torque: 3.0, omega_idle: 600.0, t_off: None };
    let sys = RunUpSystem::new(&r, &drive).unwrap();
    assert!(sys.spin());
    let d = sys.dim();
    let nc = d / 2 - 1;
    let n = r.dofs();
    let per = r.layout.per_node();
    let scale: Vec<f64> = (0..d)
        .map(|i| {
            let k = i % (nc + 1);
            let base = if k < n {
                if k % per < 2 {
                    1e-4
                } else {
                    1e-3
                }
            } else {
                1.0
            };
            if i > nc {
                base * w
            } else {
                base
            }
        })
        .collect();
    // a fixed pseudo-random state (xorshift), the speed itself at w
    let mut seed = 0x2545F4914F6CDD1Du64;
    let mut y: Vec<f64> = scale
        .iter()
        .map(|s| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            s * ((seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0)
        })
        .collect();
    y[d - 1] = w;
    let t = 0.013;
    let jac = sys.jacobian_matrix(t, &y).unwrap();
    let (mut fp, mut fm) = (vec![0.0; d], vec![0.0; d]);
    let mut num = vec![0.0; d * d];
    for j in 0..d {
        let h = 1e-6 * scale[j];
        let mut yp = y.clone();
        yp[j] += h;
        sys.rhs(t, &yp, &mut fp);
        yp[j] -= 2.0 * h;
        sys.rhs(t, &yp, &mut fm);
        for i in 0..d {
            num[i * d + j] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    let mut worst: f64 = 0.0;
    for i in 0..d {
        let row = (0..d).map(|j| (num[i * d + j] * scale[j]).abs()).fold(0.0, f64::max);
        for j in 0..d {
            let e = (jac[i * d + j] - num[i * d + j]).abs() * scale[j] / row.max(f64::MIN_POSITIVE);
            worst = worst.max(e);
            assert!(e <= 1e-6, "J[{i}][{j}] ({}, by {}) {} vs {}", sys.component_name(i), sys.component_name(j), jac[i * d + j], num[i * d + j]);
        }
    }
    eprintln!("largest difference {worst:.2e} of the row");
    // the spin's columns are not trivial: the speed moves the accelerations
    let spin_col: f64 = (d / 2..d).map(|i| jac[i * d + d - 1].abs()).fold(0.0, f64::max);
    assert!(spin_col > 0.0);
}
