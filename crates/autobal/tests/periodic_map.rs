//! A map of a periodic configuration continues each cell's orbit from its neighbour's
//! (rotor_map): cells the closed form cannot reach are found from the neighbouring cell's
//! converged orbit, and agree with the speed scan.

use autobal::rotor_map::{general_map, Kind};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::map::Axis;

#[test]
fn a_periodic_cell_below_the_closed_forms_reach_is_continued_from_its_neighbour() {
    // examples/spatial_two_plane.toml (gravity, supports stiffer in y: a periodic orbit) at
    // 1200 rpm: Newton from the closed form (the rotor at rest, balls cancelling the unbalance)
    // finds no orbit there (nor does the speed scan coming up from below), but the orbit at
    // 1300 rpm continues down to it. The map's margin (the largest Floquet exponent per unit
    // τ = ω0 t) at 1200 and 1300 rpm in the ratio of the speed scan's (1/s; ω0 cancels) run
    // downwards over the same speeds, to 1e-6 (both shoot at rtol 1e-10; the multipliers are
    // good to ~1e-9).
    let root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    let x = Axis { path: "speed_rpm".into(), values: vec![1200.0, 1300.0] };
    let y = Axis { path: "balancer.drag".into(), values: vec![0.5] };
    let mut cells = vec![];
    general_map(&root, &x, &y, None, &autobal::control::Control::none(), &mut |_, r| {
        cells.extend_from_slice(r);
        true
    })
    .unwrap();
    assert!(cells.iter().all(|c| c.kind == Some(Kind::PeriodicOrbit)), "{cells:?}");
    assert!(cells[0].continued, "the 1200 rpm cell comes from its neighbour: {:?}", cells[0]);
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    let rpm = std::f64::consts::PI / 30.0;
    let scan = stability_over_speed(&Rotor::Spatial(sim.rotor), &[1300.0 * rpm, 1200.0 * rpm]).unwrap();
    let a: Vec<f64> = scan.points.iter().map(|p| p.abscissa.expect("the scan continues down to 1200 rpm")).collect();
    let (ours, theirs) = (cells[0].margin / cells[1].margin, a[1] / a[0]);
    assert!((ours - theirs).abs() <= 1e-6 * theirs.abs(), "margin ratio {ours} against the scan's {theirs}");
}
