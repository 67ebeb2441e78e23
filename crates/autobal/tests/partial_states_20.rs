//! Which partially balanced state the speed scan analyses (audit 20's F11) and Newton's crawl
//! on balls weakly held at low speed (F10), on audit 20's random rotor rnd/r19_00_sp.toml: two
//! ball planes 6 mm apart near one end, each far short of its share of the unbalance
//! (resultants 0.062 / 0.061 kg m needed against capacities 0.0097 / 0.0054).

use autobal::analysis::Verdict;
use autobal::drive::Drive;
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::dynamics::{simulate, Initial, Settings};

const CONFIG: &str = r#"
[rotor]
mass = 46.664120516751666
equatorial_moment = 0.786533610324064
polar_moment = 0.15894477820460573
z = 0.2520976099083526
[supports]
z_left = 0.0
z_right = 0.5942651570104825
stiffness_left = 2731306.9873414813
stiffness_right = 1195087.4125867065
stiffness_left_y = 2731306.9873414813
stiffness_right_y = 1195087.4125867065
damping_left = 181.2806702692893
damping_right = 56.82962005680965
damping_left_y = 181.2806702692893
damping_right_y = 56.82962005680965
[unbalance]
mass = 0.021872562528218502
radius = 0.0931472841480755
angle = 4.481490050757566
[couple]
mass = 0.016056265220186786
radius = 0.0931472841480755
angle = 2.7190017978173358
z = 0.26605743053696157
[balancer]
z = 0.5198125020812846
balls = 2
ball_mass = 0.041998780998431635
race_radius = 0.11547814635592414
drag = 1.8398343882912835
[balancer2]
z = 0.5260839034642559
balls = 2
ball_mass = 0.02353430019590341
race_radius = 0.11547814635592414
drag = 0.22480517320785448
[spatial]
gravity = [0.0, 0.0, 0.0]
"#;

fn rotor() -> autobal::spatial::dynamics::SpatialRotor {
    autobal::config::spatial_simulation(&autobal::config::parse(CONFIG, "r19_00_sp").unwrap()).unwrap().rotor
}

fn wrap(a: f64) -> f64 {
    use std::f64::consts::PI;
    (a + PI).rem_euclid(2.0 * PI) - PI
}

/// At 435.108 rad/s Newton from each plane's share (the two planes' balls bunched opposite
/// each other) reaches a state unstable at +7.88 1/s, and the scan analysed it until session
/// 20 ("stable: nowhere"); from every ball against the static unbalance it reaches one stable
/// at −0.75 1/s. The scan now analyses the least growth rate among the candidates and lists the
/// others. Checked against a run of the full equations started 0.01 rad off the stable state
/// (balls of a plane split ±0.01): the run approaches it at the rate of its slowest mode, so
/// the remaining distance is extrapolated from three samples 0.32 s apart (Aitken's Δ²: a
/// geometric approach `a + b q^k`), and the limit must be the state to 1e-3 rad (seen: the
/// run's last sample 7.8e-3 rad short of the state, the extrapolated limit 1.6e-4 from it, the
/// other modes' remnant and the state's complex pair not being one geometric term; the other
/// states found lie more than 1 rad away). Fails on main at e506c10 (the verdict there is
/// unstable, the balls at −0.72 and 2.38 rad).
#[test]
fn the_scan_analyses_the_stable_partial_state_a_run_settles_on() {
    let r = rotor();
    let w = 435.10760820384417;
    let st = stability_over_speed(&Rotor::Spatial(r.clone()), &[w]).unwrap();
    let p = &st.points[0];
    eprintln!("{:?} {:?} {:?} {:?}", p.verdict, p.abscissa, p.member_psi, p.other_orbits);
    assert_eq!(p.verdict, Some(Verdict::Stable), "{p:?}");
    assert!((p.abscissa.unwrap() + 0.75).abs() < 0.01, "{p:?}");
    // the state analysed before is among the others, unstable
    assert!(
        p.other_orbits
            .iter()
            .any(|o| o.verdict == Verdict::Unstable && wrap(o.member_psi[0] + 0.7235).abs() < 1e-3 && wrap(o.member_psi[2] - 2.3842).abs() < 1e-3),
        "{:?}",
        p.other_orbits
    );
    let psi = p.member_psi.clone();
    let start: Vec<f64> = psi.iter().enumerate().map(|(i, a)| a + if i % 2 == 0 { 0.01 } else { -0.01 }).collect();
    let init = Initial { psi: start, ..Initial::at_rest(&r) };
    let set = Settings { method: Default::default(), t_end: 8.0, dt: 0.005, rtol: 1e-10, atol: 1e-13 };
    let mut samples: Vec<Vec<f64>> = vec![];
    simulate(&r, &Drive::Speed { omega0: w }, &init, &set, |s| {
        samples.push(s.psi.clone());
        true
    })
    .unwrap();
    let k = samples.len();
    assert!(k > 129, "{k} samples");
    for i in 0..psi.len() {
        let (a, b, c) = (samples[k - 129][i], samples[k - 65][i], samples[k - 1][i]);
        let limit = c - (c - b) * (c - b) / ((c - b) - (b - a));
        eprintln!("ball {i}: run {c}, extrapolated {limit}, state {}", psi[i]);
        assert!(
            wrap(limit - psi[i]).abs() < 1e-3 && wrap(limit - psi[i]).abs() < 0.5 * wrap(c - psi[i]).abs(),
            "ball {i}: run {c}, extrapolated {limit}, state {}",
            psi[i]
        );
    }
}

/// F10: at 11.6-23.2 rad/s (1/24 to 1/12 of the first critical speed) the balls are held by
/// equations ~1e-8 as strong as the structure's (scaled), and Newton crawled at steps of 1/128
/// to "iteration limit" at scaled residuals 1.7e-10 to 1e-11 (main at e506c10; with 5000
/// iterations the same Newton reached the state at 23.2 rad/s after 110, at 5.8 after 1073):
/// with the natural monotonicity test each is found within the 50 iterations, an equilibrium
/// to the tolerance.
#[test]
fn the_weakly_held_balls_at_low_speed_are_found() {
    let speeds = [11.602867, 17.404301, 23.205734];
    let st = stability_over_speed(&Rotor::Spatial(rotor()), &speeds).unwrap();
    for p in &st.points {
        assert!(p.verdict.is_some(), "{} rad/s: {:?}", p.omega, p.failure);
    }
}
