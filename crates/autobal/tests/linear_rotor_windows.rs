//! Exploration (ignored): the balanced state's stable speed ranges of a flexible shaft with a
//! balancer, against the balancer plane's position relative to the bending modes.

use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, LinearRotor, Unbalance};

fn shaft(balancer: usize) -> LinearRotor {
    let mut b = ShaftBuilder::uniform(8, 1.0, 0.025, 2.1e11, 7800.0);
    b.disks.push(Disk { node: 2, mass: 4.0, id: 0.02, ip: 0.04 });
    b.disks.push(Disk { node: 6, mass: 4.0, id: 0.02, ip: 0.04 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 500.0 });
    b.bearings.push(Bearing { node: 8, k: 5e6, c: 500.0 });
    b.rotary_inertia = true;
    b.gyroscopic = true;
    let mut r = b.build().unwrap();
    let alpha = 3.0;
    for (cv, mv) in r.c.iter_mut().zip(&r.m) {
        *cv += alpha * mv;
    }
    r.unbalances.push(Unbalance { node: balancer, me: 2e-4, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: balancer, radius: 0.08, balls: 2, ball_mass: 0.03, drag: 0.05, offset: 0.0 });
    r
}

#[test]
#[ignore]
fn stable_windows_against_the_balancer_plane() {
    for node in [2, 3, 4] {
        let r = shaft(node);
        let w = r.natural_frequencies(&[], true).unwrap();
        let w1 = w[0];
        let speeds: Vec<f64> = (0..60).map(|i| w1 * (0.3 + 0.1 * i as f64)).collect();
        let s = autobal::linear_rotor::stability::stability_over_speed(&r, &speeds).unwrap();
        let ranges: Vec<String> = s.stable_ranges.iter().map(|g| format!("[{:.4}, {:.4}]", g.from / w1, g.to / w1)).collect();
        eprintln!("balancer at node {node}: ω/ω1 = {:?}; stable (Ω/ω1) {}", w.iter().take(6).map(|v| v / w1).collect::<Vec<_>>(), ranges.join(" "));
    }
}
