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
