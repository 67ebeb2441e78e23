//! A map's traced boundary (general route) after walk 32.
//!
//! Finding 5: two neighbouring cells on the same side holding different kinds of state were
//! never bisected. The planar rotor of examples/planar.toml over 100-600 rad/s (6 speeds): at
//! 200 rad/s the balls sit not balanced (stable), at 300 rad/s the semi-balanced state is
//! stable for `c_psi` ≥ 0.11, and that state's own stable range starts between them (296.2 rad/s
//! at `c_psi` 0.15): the map reported nothing there. Conversely, the not-balanced state, followed
//! after a switch, is lost at a fold at 277.65 rad/s, which the map reported as a change "stable
//! to unstable" that no `stability` range ends at.
//!
//! Second route: the speed scan of `stability` (`stability_over_speed`, its own grid of 200
//! speeds from 3 to 600 rad/s as the CLI's default, Brent's method on the abscissa) gives the
//! located range ends; the map's row points are exactly those, each within 2e-9 relative
//! (both located to 1e-9 relative on the same equilibria's eigenvalues).
//!
//! Finding 6: a point where a state appears (a fold) was said to be "bisected to 1e-9"; it is
//! where continuation stops converging, and the same fold on three grids spreads over 1.4e-5
//! relative (examples/dimensional.toml under gravity). Such points now carry
//! `rtol = FOLD_RTOL` (1e-4), the others `BOUNDARY_RTOL`, and the folds agree to `FOLD_RTOL`.
//!
//! Finding 8a: an invalid rotor at a bisection's midpoint names the axis, the value and the
//! map's range.

use autobal::control::Control;
use autobal::rotor_map::{general_map_traced, BoundaryPoint, Verdict, BOUNDARY_RTOL, FOLD_RTOL};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::map::Axis;

fn planar(c_psi: Option<f64>) -> toml::Table {
    let mut root = autobal::config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
    if let Some(c) = c_psi {
        autobal::config::set_number(&mut root, "planar.c_psi", c).unwrap();
    }
    root
}

fn traced(root: &toml::Table, x: Axis, y: Axis) -> Vec<BoundaryPoint> {
    let mut points = vec![];
    general_map_traced(root, &x, &y, None, true, &Control::none(), &mut |_, _, p| {
        points.extend_from_slice(p);
        true
    })
    .unwrap();
    points
}

#[test]
fn a_states_boundary_between_two_stable_cells_of_different_kinds_is_traced() {
    let drags = vec![0.05, 0.1, 0.125, 0.15, 0.175, 0.2];
    let x = Axis { path: "omega".into(), values: (1..=6).map(|i| 100.0 * i as f64).collect() };
    let points = traced(&planar(None), x, Axis { path: "planar.c_psi".into(), values: drags.clone() });
    let speeds: Vec<f64> = (1..=200).map(|i| 3.0 * i as f64).collect();
    let mut same_side = 0;
    for &c in &drags {
        let rotor = Rotor::Planar(autobal::config::planar(&planar(Some(c))).unwrap().rotor);
        let scan = stability_over_speed(&rotor, &speeds).unwrap();
        let ends: Vec<f64> =
            scan.stable_ranges.iter().flat_map(|r| [(r.from, r.from_is_boundary), (r.to, r.to_is_boundary)]).filter(|e| e.1).map(|e| e.0).collect();
        let row: Vec<&BoundaryPoint> = points.iter().filter(|p| p.along == autobal::rotor_map::Along::X && p.y == c).collect();
        assert_eq!(row.len(), ends.len(), "c_psi {c}: map {row:?}, stability {ends:?}");
        for (p, e) in row.iter().zip(&ends) {
            assert!((p.x - e).abs() <= 2e-9 * e, "c_psi {c}: map {}, stability {e}", p.x);
            assert_eq!((p.from, p.to, p.rtol), (Some(Verdict::Unstable), Some(Verdict::Stable), BOUNDARY_RTOL), "{p:?}");
            // no point at the not-balanced state's fold (277.65 rad/s, every c_psi)
            assert!((p.x - 277.65).abs() > 1.0, "{p:?}");
        }
        // the cells at 200 and 300 rad/s are both stable from c_psi 0.125 on: the case of
        // finding 5 (the point lies between them)
        if c >= 0.125 {
            assert!(ends.len() == 1 && ends[0] > 200.0 && ends[0] < 300.0, "c_psi {c}: {ends:?}");
            same_side += 1;
        }
    }
    assert_eq!(same_side, 4);
    // the walk's numbers: 298.047 at c_psi 0.125, 294.005 at 0.2
    let at = |c: f64| points.iter().find(|p| p.along == autobal::rotor_map::Along::X && p.y == c).unwrap().x;
    assert!((at(0.125) - 298.047).abs() < 1e-3 && (at(0.2) - 294.005).abs() < 1e-3, "{} {}", at(0.125), at(0.2));
}

/// The fold where the orbit of examples/dimensional.toml under gravity first exists (no state
/// below, an unstable partially balanced orbit above, ~1130.32 rpm at `balancer.drag` 0.5):
/// on grids of 3, 5 and 7 speeds over 300-1500 rpm the point agrees to its claimed tolerance
/// `FOLD_RTOL` (seen: 1.4e-5 relative), and says so (`rtol`); the points where a verdict
/// changes claim `BOUNDARY_RTOL`.
#[test]
fn a_fold_is_the_same_on_three_grids_to_its_claimed_tolerance() {
    let mut root = autobal::config::parse(include_str!("../../../examples/dimensional.toml"), "dimensional").unwrap();
    autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, -9.81, 0.0]")).unwrap();
    let mut folds = vec![];
    for n in [3, 5, 7] {
        let x = Axis { path: "speed_rpm".into(), values: (0..n).map(|i| 300.0 + 1200.0 * i as f64 / (n - 1) as f64).collect() };
        let points = traced(&root, x, Axis { path: "balancer.drag".into(), values: vec![0.5] });
        let fold: Vec<&BoundaryPoint> = points.iter().filter(|p| p.from.is_none()).collect();
        assert_eq!(fold.len(), 1, "{n} speeds: {points:?}");
        assert_eq!((fold[0].to, fold[0].rtol), (Some(Verdict::Unstable), FOLD_RTOL), "{:?}", fold[0]);
        for p in points.iter().filter(|p| p.from.is_some() && p.to.is_some()) {
            assert_eq!(p.rtol, BOUNDARY_RTOL, "{p:?}");
        }
        folds.push(fold[0].x);
    }
    for f in &folds {
        assert!((f - folds[0]).abs() <= FOLD_RTOL * folds[0] && (f - 1130.32).abs() < 0.05, "{folds:?}");
    }
}

/// An integer key as an axis (`planar.n`): the boundary's bisection meets 2.5 balls, which the
/// config refuses; the error names the axis, the value and the map's range.
#[test]
fn an_invalid_rotor_at_a_midpoint_names_the_axis_and_the_range() {
    let x = Axis { path: "omega".into(), values: (1..=6).map(|i| 100.0 * i as f64).collect() };
    let y = Axis { path: "planar.n".into(), values: vec![2.0, 3.0, 4.0] };
    let e = general_map_traced(&planar(None), &x, &y, None, true, &Control::none(), &mut |_, _, _| true).unwrap_err();
    assert_eq!(e.field(), Some("planar.n"));
    let text = e.to_string();
    // (which midpoint is met first depends on the threads: 2.5 or 3.5, or a follower's step)
    assert!(
        text.starts_with("planar.n: ") && text.contains(", inside the map's range 2 to 4 (where the boundary is bisected), gives an invalid rotor: "),
        "{text}"
    );
}
