//! A map's traced boundary (general route) at the ball mass where a balanced state first
//! exists (walk 34, finding D4).
//!
//! Below that mass the balls sit bunched opposite the unbalance (partially balanced); at it the
//! balanced state branches off the bunched balls, whose spreading mode is neutral there; above
//! it the map's state is the balanced one. On the two-plane rotor with couple unbalance both
//! states are stable at 900-1000 rad/s (margins about -5.5e-4 and -5.3e-4 per τ on the cells
//! either side), and `stability` stepping plane 1's ball mass across 0.0041667 kg at 950 rad/s
//! finds every state stable, the growth rate touching 0 only at the threshold. The bunched balls,
//! followed past the threshold, turn unstable: the map reported that as a "stable to unstable"
//! point at the threshold, between two stable cells (the map's state there is the balanced one).
//! The planar rotor's threshold gave a "neutral to neutral" point along the speed, on the
//! column of cells at the threshold itself (every one neutral, its margin ±1e-17 of round-off).
//!
//! Second route: `stability_over_speed` on the two-plane rotor at ball masses either side of
//! the threshold (its own eigenvalues of the state the speed scan analyses) is stable there.

use autobal::control::Control;
use autobal::rotor_map::{general_map_traced, Along, BoundaryPoint, Verdict};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::map::Axis;

/// Walk 34's cp.toml: two planes, couple unbalance 0.001 kg m at z = 0.45 and -0.001 at 0.05,
/// no gravity, isotropic supports, two balls of 0.0045 kg in each plane.
const TWO_PLANES: &str = r#"
[rotor]
mass = 20.0
equatorial_moment = 0.60
polar_moment = 0.15
z = 0.25

[supports]
z_left = 0.0
z_right = 0.50
stiffness_left = 2.0e6
stiffness_right = 3.0e6
damping_left = 300.0
damping_right = 300.0

[unbalance]
mass = 0.010
radius = 0.10
angle = 0.0

[couple]
mass = 0.010
radius = 0.10
angle = 3.141592653589793
z = 0.05

[balancer]
z = 0.45
balls = 2
ball_mass = 0.0045
race_radius = 0.12
drag = 0.5

[balancer2]
z = 0.05
balls = 2
ball_mass = 0.0045
race_radius = 0.12
drag = 0.5

[drive]
kind = "schedule"
schedule_of = "speed"
schedule = [[0.0, 1400.0], [20.0, 1400.0]]
t_end = 20.0

[integration]
method = "dop853"
rtol = 1e-9
atol = 1e-11
dt = 0.001

[analysis]
anisotropy = "exact"
"#;

/// Walk 34's j2.toml: paper 004's Jeffcott rotor, race centred, two balls.
const JEFFCOTT: &str = r#"
[planar]
m1 = 1.0
m2 = 0.2
m3 = 0.03
n = 2
s1 = 0.003
s2 = 0.0
gamma = 0.0
r = 0.06
k = 104509.44
c = 50.0
c_psi = 0.1
c_theta = 0.0
i_g = 0.0025

[drive]
kind = "speed"
omega0 = 400.0
t_end = 20.0

[integration]
rtol = 1e-9
atol = 1e-11
dt = 0.01
"#;

fn traced(root: &toml::Table, x: Axis, y: Axis) -> Vec<BoundaryPoint> {
    let mut points = vec![];
    general_map_traced(root, &x, &y, None, true, &Control::none(), &mut |_, _, p| {
        points.extend_from_slice(p);
        true
    })
    .unwrap();
    points
}

/// Plane 1's threshold: its two balls at the race radius cancel the couple's share there when
/// `2 m r = 0.001 kg m` (the couple unbalance 0.001 kg m), m = 0.001 / 0.24 kg.
const THRESHOLD: f64 = 0.001 / 0.24;

#[test]
fn two_stable_cells_across_the_threshold_give_no_stable_to_unstable_point() {
    let root = autobal::config::parse(TWO_PLANES, "cp").unwrap();
    let masses = Axis::new("balancer.ball_mass", (0..5).map(|i| 0.0040 + 0.0001 * i as f64).collect());
    let speeds = Axis::new("speed", (0..5).map(|i| 800.0 + 50.0 * i as f64).collect());
    let points = traced(&root, masses, speeds);
    // main wrote 0.004166666667,{900,950,1000},stable,unstable,x
    for p in &points {
        assert!(!(p.along == Along::X && (p.x - THRESHOLD).abs() < 1e-6 * THRESHOLD), "a point at the threshold: {p:?}");
    }
    // the rows at 900-1000 rad/s are stable throughout: no point along them
    assert!(!points.iter().any(|p| p.along == Along::X && p.y >= 900.0), "{points:?}");
    // what stays: the row at 850 (the bunched balls' own change at 0.0040378, both cells
    // partially balanced) and each column's unstable-to-stable speed
    let row: Vec<&BoundaryPoint> = points.iter().filter(|p| p.along == Along::X).collect();
    assert_eq!(row.len(), 1, "{row:?}");
    assert!(row[0].y == 850.0 && (row[0].x - 0.0040378).abs() < 1e-7, "{row:?}");
    assert_eq!((row[0].from, row[0].to), (Some(Verdict::Stable), Some(Verdict::Unstable)));
    let columns: Vec<&BoundaryPoint> = points.iter().filter(|p| p.along == Along::Y).collect();
    assert_eq!(columns.len(), 5, "{columns:?}");
    assert!(columns.iter().all(|p| (p.from, p.to) == (Some(Verdict::Unstable), Some(Verdict::Stable))), "{columns:?}");

    // second route: the speed scan's state at 950 rad/s either side of the threshold is stable
    for m in [0.0041, 0.0042] {
        let mut r = root.clone();
        autobal::config::set_number(&mut r, "balancer.ball_mass", m).unwrap();
        let rotor = Rotor::Spatial(autobal::config::spatial_simulation(&r).unwrap().rotor);
        let scan = stability_over_speed(&rotor, &[950.0]).unwrap();
        assert_eq!(scan.points[0].verdict, Some(Verdict::Stable), "ball mass {m}: {:?}", scan.points[0]);
    }
}

#[test]
fn the_planar_threshold_gives_no_neutral_to_neutral_point() {
    let root = autobal::config::parse(JEFFCOTT, "j2").unwrap();
    // the threshold, 2 m3 r = m1 s1 (0.003 kg m): m3 = 0.025, the grid's middle value
    let m3 = Axis::new("planar.m3", vec![0.024, 0.0245, 0.025, 0.0255, 0.026]);
    let omega = Axis::new("omega", vec![400.0, 500.0, 600.0]);
    let points = traced(&root, m3, omega);
    // main wrote 0.025,429.83,neutral,neutral,y
    assert!(!points.iter().any(|p| p.from == Some(Verdict::Neutral) && p.to == Some(Verdict::Neutral)), "{points:?}");
    assert!(!points.iter().any(|p| p.along == Along::Y), "{points:?}");
}
