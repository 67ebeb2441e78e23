//! One stationary state found twice is one state (review 21): at a stable range's end the two
//! sides of the located bracket are solved from different starts, and Newton leaves weakly held
//! balls ~1e-3 rad from the state, so at the shooting's accuracy alone (1e-8) one state reached
//! twice read as "a switch of state" at a plain change of stability. The rotor: Rodrigues et
//! al.'s two-plane rotor (the `RODRIGUES_097` of the map tests) with each plane's balls at half
//! the threshold mass, so no balanced state exists; its partially balanced state loses
//! stability at 495.145 rad/s with the balls moving continuously through it (the JSON's ball
//! angles -3.1077 and -3.1089 rad on the two sides, growth -0.0078 and +0.41 1/s).

use autobal::rotor_stability::{speed_grid, stability_over_speed, Rotor};

const CONFIG: &str = r#"
[rotor]
mass = 10.0
equatorial_moment = 0.16
polar_moment = 0.08
z = 0.2
[supports]
z_left = 0.0
z_right = 0.4
stiffness_left = 500000.0
stiffness_right = 500000.0
damping_left = 100.0
damping_right = 100.0
[unbalance]
mass = 0.01
radius = 0.1
angle = 0.0
[couple]
mass = 0.01
radius = 0.1
angle = 0.0
z = 0.08
[balancer]
z = 0.32
balls = 2
ball_mass = 0.003125
race_radius = 0.08
drag = 0.3
[balancer2]
z = 0.08
balls = 2
ball_mass = 0.003125
race_radius = 0.08
drag = 0.3
"#;

#[test]
fn a_change_of_stability_of_one_partial_state_is_a_boundary_not_a_switch() {
    let r = autobal::config::spatial_simulation(&autobal::config::parse(CONFIG, "rodrigues_half").unwrap()).unwrap().rotor;
    let st = stability_over_speed(&Rotor::Spatial(r), &speed_grid(1500.0, 200).unwrap()).unwrap();
    // the first range ends where its state turns unstable, 495.145 rad/s (the CLI's figure)
    let first = &st.stable_ranges[0];
    assert!((first.to - 495.145).abs() < 1e-3, "{:?}", st.stable_ranges);
    assert!(first.to_is_boundary && !first.to_is_switch, "{first:?}");
}
