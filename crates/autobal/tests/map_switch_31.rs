//! A map's traced boundary between two cells that hold different kinds of state (walk 30,
//! finding A): the washer of examples/washing_machine.toml under gravity, mapped over
//! 200-450 rpm. At 200 rpm the balls cannot cancel the unbalance (a partially balanced orbit,
//! unstable), at 450 rpm the balanced orbit is stable; the balanced orbit's own boundary lies
//! between (~303 rpm at balancer.z = 0.1). Until session 31 `--boundary` refused to bisect
//! between cells of different kinds ("a switch of state") and reported nothing there, though
//! a grid starting at 280 rpm (balanced on both sides) found the point.
//!
//! Second route: the speed scan (`stability_over_speed`, Brent's method on the abscissa with
//! its own switch rule) over another grid gives the start of the stable range, a located
//! boundary; the map's point agrees with it and does not depend on the map's grid. Tolerance
//! 1e-7 relative: both are bisected to 1e-9 relative, on Floquet exponents from shootings at
//! rtol 1e-10 (multipliers near 1 good to ~1e-9, `rotor_map`), which over a margin slope of
//! order 1e-3 per τ per rpm moves the zero by ~1e-6 rpm, 3e-9 relative.

use autobal::control::Control;
use autobal::rotor_map::{general_map_traced, BoundaryPoint};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::map::Axis;
use std::f64::consts::PI;

const WASHER: &str = include_str!("../../../examples/washing_machine.toml");

fn washer(z: Option<f64>) -> toml::Table {
    let mut root = autobal::config::parse(WASHER, "washer").unwrap();
    autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, -9.81, 0.0]")).unwrap();
    if let Some(z) = z {
        autobal::config::set_number(&mut root, "balancer.z", z).unwrap();
    }
    root
}

fn boundary(speeds: Vec<f64>, zs: Vec<f64>) -> Vec<BoundaryPoint> {
    let root = washer(None);
    let x = Axis { path: "speed_rpm".into(), values: speeds };
    let y = Axis { path: "balancer.z".into(), values: zs };
    let mut points = vec![];
    general_map_traced(&root, &x, &y, None, true, &Control::none(), &mut |_, _, p| {
        points.extend_from_slice(p);
        true
    })
    .unwrap();
    points
}

/// The speed scan's first located stable-range start at `z`, in rpm.
fn scan_start(z: f64) -> f64 {
    let rotor = Rotor::Spatial(autobal::config::spatial_simulation(&washer(Some(z))).unwrap().rotor);
    let speeds: Vec<f64> = (0..11).map(|i| (210.0 + 23.0 * i as f64) * PI / 30.0).collect();
    let scan = stability_over_speed(&rotor, &speeds).unwrap();
    let r = scan.stable_ranges.iter().find(|r| r.from_is_boundary).expect("a located range start");
    r.from * 30.0 / PI
}

#[test]
fn the_boundary_between_a_partially_balanced_and_a_balanced_cell_is_traced() {
    for z in [0.1, 0.4] {
        let expected = scan_start(z);
        for grid in [vec![200.0, 450.0], vec![200.0, 250.0, 300.0, 350.0, 400.0, 450.0], vec![280.0, 450.0]] {
            let points = boundary(grid.clone(), vec![z]);
            assert_eq!(points.len(), 1, "z = {z}, grid {grid:?}: {points:?}");
            let p = points[0];
            assert!((p.x - expected).abs() <= 1e-7 * expected, "z = {z}, grid {grid:?}: map {} rpm, scan {expected} rpm", p.x);
            assert_eq!((p.from.map(|v| v.name()), p.to.map(|v| v.name())), (Some("unstable"), Some("stable")), "{p:?}");
        }
    }
}

/// Where the partially balanced orbit appears (its fold, ~188.58 rpm at balancer.z = 0.1) in a
/// row that starts without a state (walk 31, findings 1-2): the point is the fold on every grid
/// (it was the first midpoint of the bracket, 200.0000001 rpm on 150-350 and 210.0000001 on
/// 100-320, where one Newton jump from the far end failed), the verdict beside it is the
/// orbit's (unstable, as the cell at 200 rpm reads on a grid from 200 rpm), not the far cell's,
/// and the balanced orbit's own boundary behind it is traced too (it was lost). The fold is
/// located where continuation in halved steps stops converging, so the tolerance is looser:
/// 1e-6 relative between grids (seen: 3e-9).
#[test]
fn where_a_state_appears_the_point_is_its_fold_and_its_own_boundary_follows() {
    let expected = scan_start(0.1);
    let mut folds = vec![];
    for grid in [vec![150.0, 350.0], vec![100.0, 320.0], vec![180.0, 350.0], vec![150.0, 200.0, 250.0, 300.0, 350.0]] {
        let points = boundary(grid.clone(), vec![0.1]);
        let names = |p: &BoundaryPoint| (p.from.map(|v| v.name()), p.to.map(|v| v.name()));
        let fold: Vec<&BoundaryPoint> = points.iter().filter(|p| p.from.is_none()).collect();
        assert_eq!(fold.len(), 1, "grid {grid:?}: {points:?}");
        assert_eq!(names(fold[0]), (None, Some("unstable")), "grid {grid:?}: {points:?}");
        folds.push(fold[0].x);
        let own: Vec<&BoundaryPoint> = points.iter().filter(|p| p.from.is_some()).collect();
        assert_eq!(own.len(), 1, "grid {grid:?}: {points:?}");
        assert!((own[0].x - expected).abs() <= 1e-7 * expected, "grid {grid:?}: map {} rpm, scan {expected} rpm", own[0].x);
    }
    for f in &folds {
        assert!((f - folds[0]).abs() <= 1e-6 * folds[0] && (f - 188.58).abs() < 0.01, "{folds:?}");
    }
    // the orbit beside the fold is the partially balanced one the cell at 200 rpm holds
    let root = washer(Some(0.1));
    let x = Axis { path: "speed_rpm".into(), values: vec![200.0, 450.0] };
    let y = Axis { path: "balancer.z".into(), values: vec![0.1] };
    let mut cells = vec![];
    autobal::rotor_map::general_map(&root, &x, &y, None, &Control::none(), &mut |_, r| {
        cells = r.to_vec();
        true
    })
    .unwrap();
    assert_eq!(cells[0].verdict.map(|v| v.name()), Some("unstable"), "{:?}", cells[0]);
    assert_eq!(format!("{:?}", cells[0].state), "Some(PartiallyBalanced)");
}
