//! Audit 21's F2: `stability` with three balls on a 28-DOF linear rotor ran for minutes with no
//! sign of life: the speed scan told its observer the grid speeds done, then the family of
//! balanced states was followed at every grid speed (the costly part: a continuation of ~110
//! members per speed there) with nothing said. This test checks the progress through the
//! family phase on a Jeffcott linear rotor with three balls (a one-parameter family of balanced
//! states wherever they exist).

use autobal::control::Control;
use autobal::linear_rotor::{BalancerPlane, LinearRotor};
use autobal::rotor_stability::{speed_grid, stability_over_speed_with, Rotor};
use std::sync::{Arc, Mutex};

/// The Jeffcott linear rotor (`m = 1 kg`, `k = 1e4 N/m`: `ω_n = 100 rad/s`) with three balls
/// that can cancel its unbalance (`me = 1e-4 kg m` against `n m_b R = 1.5e-3 kg m`).
fn rotor() -> Rotor {
    let balancer = BalancerPlane { node: 0, radius: 0.05, balls: 3, ball_mass: 0.01, drag: 0.01, offset: 0.0 };
    Rotor::Linear(LinearRotor::jeffcott(1.0, 1e4, 1.0, 1e-4, balancer))
}

/// Every report's `done` is at most its `total`, and the family phase reports each of
/// `grid + 1 ..= grid + f` once of `grid + f`, `f` the speeds whose state is a member of a family
/// (each followed, or tried, once; in any order: in parallel): counted after the grid speeds
/// (main at f1d4624 ended at `(grid, grid)` and then followed the families in silence).
#[test]
fn the_family_phase_reports_its_speeds_after_the_grid() {
    let speeds = speed_grid(300.0, 12).unwrap();
    let seen: Arc<Mutex<Vec<(u64, u64)>>> = Arc::default();
    let s = seen.clone();
    let control = Control::new().with_progress(move |p| s.lock().unwrap().push((p.done, p.total)));
    let out = stability_over_speed_with(&rotor(), &speeds, &control).unwrap();
    assert!(out.stopped.is_none());
    let r = out.value;
    let grid = speeds.len() as u64;
    let families = r.points.iter().filter(|p| p.family_dimension > 0).count() as u64;
    let followed = r.points.iter().filter(|p| p.family.is_some()).count() as u64;
    assert!(r.family_dimension == 1 && followed >= 3, "a family followed at several speeds: {followed} of {families}");
    let seen = seen.lock().unwrap().clone();
    assert!(seen.iter().all(|&(d, t)| d <= t), "{seen:?}");
    // the family phase's reports: totals past the grid, each done once (any order: parallel)
    let mut phase: Vec<u64> = seen
        .iter()
        .filter(|&&(_, t)| t > grid)
        .map(|&(d, t)| {
            assert_eq!(t, grid + families, "{seen:?}");
            d
        })
        .collect();
    phase.sort_unstable();
    assert_eq!(phase, (grid + 1..=grid + families).collect::<Vec<_>>(), "{seen:?}");
}
