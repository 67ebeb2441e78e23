//! Real balls (contact, rolling resistance: [`autobal::balls`]) on the linear rotor: a run-up of
//! the Jeffcott preset with real balls against the native planar model's, sample by sample; the
//! stationary analyses refuse them with a typed one-line error; the config keys.

use autobal::balls::BallPhysics;
use autobal::drive::Drive;
use autobal::linear_rotor::runup::{simulate, RunSettings};
use autobal::linear_rotor::{Frame, LinearRotor, LinearRotorField};
use autobal::ode::Method;
use autobal::planar::{PlanarRotor, Settings};
use autobal::Error;

/// A run-up through the critical speed of paper 004's rotor (race centred) with real balls that
/// collide (restitution 0.5, the default contact stiffness) and roll with resistance (`μ_r =
/// 2e-3`): the linear rotor (fixed axes, its Jeffcott preset with the planar rotor's ball
/// physics) against the native planar model (turning axes), sample by sample. The two share the
/// contact and rolling laws ([`autobal::balls`]) but not the equations they enter, nor the
/// normal force's assembly (here from fixed-axes velocities, there in turning axes), so a
/// wrong sign of a normal-force term or a torque on the wrong coordinate shows. Both at rtol
/// 1e-10; a contact's stiffness makes the passage through each impact sensitive (an impact's
/// timing error grows the relative angle's error by the ratio of the contact's frequency to the
/// run's, ~20), so the bound is `1e-6` of the peak whirl radius and `1e-6` rad, 100× the
/// point-mass comparison's (tests/linear_rotor_config.rs). The run is checked to have contacts
/// (the balls come within a ball's diameter of each other).
#[test]
fn real_ball_run_up_equals_the_planar_model() {
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    p.balls = BallPhysics::builder().contact(true).restitution(0.5).rolling_resistance(2e-3).build().unwrap();
    let rotor = LinearRotor::from_planar(&p).unwrap();
    assert_eq!(rotor.ball_physics, vec![p.balls]);
    let wn = p.natural_frequency();
    let t_end = 2.0;
    let drive = Drive::Acceleration { omega0: 0.2 * wn, b: 1.6 * wn / t_end };
    let mut settings = Settings::new(&p, t_end);
    settings.dt = t_end / 200.0;
    settings.rtol = 1e-10;
    settings.atol = 1e-12;
    settings.psi0 = (0..p.n).map(|j| std::f64::consts::TAU * j as f64 / p.n as f64).collect();
    let mut native = vec![];
    autobal::planar::simulate(&p, &drive, &settings, |s| {
        native.push((s.t, s.x, s.y, s.psi.clone()));
        true
    })
    .unwrap();
    let mut ours = vec![];
    let rs =
        RunSettings { t_end, dt: settings.dt, rtol: 1e-10, atol: 1e-12, method: Method::Auto, max_steps: 10_000_000, max_wall_s: None, physical_nodes: None };
    let sum = simulate(&rotor, &drive, &rs, &autobal::control::Control::none(), |s| {
        ours.push((s.t, s.planes[0].0, s.planes[0].1, s.psi.clone()));
        true
    })
    .unwrap();
    assert!(sum.stopped.is_none(), "{:?}", sum.stopped);
    assert_eq!(native.len(), ours.len());
    let peak = native.iter().map(|s| s.1.hypot(s.2)).fold(0.0, f64::max);
    let (mut worst, mut worst_psi): (f64, f64) = (0.0, 0.0);
    let mut closest = f64::INFINITY;
    for (a, b) in native.iter().zip(&ours) {
        assert!((a.0 - b.0).abs() < 1e-12);
        worst = worst.max((a.1 - b.1).hypot(a.2 - b.2));
        for (x, y) in a.3.iter().zip(&b.3) {
            worst_psi = worst_psi.max((x - y).abs());
        }
        let d = (a.3[1] - a.3[0]).rem_euclid(std::f64::consts::TAU);
        closest = closest.min(2.0 * p.r * (0.5 * d).sin().abs());
    }
    let diameter = p.balls.diameter(p.m3);
    eprintln!(
        "peak {peak:e} m; differences: position {:e} of the peak, ball angles {worst_psi:e} rad; closest approach {closest:e} m, diameter {diameter:e} m",
        worst / peak
    );
    assert!(closest < diameter, "the balls never touched: closest {closest:e} m, diameter {diameter:e} m");
    assert!(worst < 1e-6 * peak, "largest difference {worst:e} m, peak {peak:e} m");
    assert!(worst_psi < 1e-6, "ball angles differ by {worst_psi:e} rad");
}

/// The same run with point masses ends elsewhere: the real balls' torques act (the comparison
/// above would pass with them dropped from one model only if they did nothing).
#[test]
fn real_balls_change_the_run() {
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    p.balls = BallPhysics::builder().contact(true).rolling_resistance(2e-3).build().unwrap();
    let real = LinearRotor::from_planar(&p).unwrap();
    let mut point = real.clone();
    point.ball_physics.clear();
    let wn = p.natural_frequency();
    let drive = Drive::Acceleration { omega0: 0.2 * wn, b: 0.8 * wn };
    let rs = RunSettings { t_end: 2.0, dt: 0.01, rtol: 1e-9, atol: 1e-12, method: Method::Auto, max_steps: 10_000_000, max_wall_s: None, physical_nodes: None };
    let end = |r: &LinearRotor| {
        let mut last = None;
        simulate(r, &drive, &rs, &autobal::control::Control::none(), |s| {
            last = Some(s.psi.clone());
            true
        })
        .unwrap();
        last.unwrap()
    };
    let (a, b) = (end(&real), end(&point));
    let moved = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(moved > 1e-3, "the real balls moved the end angles by only {moved:e} rad");
}

/// The stationary analyses (the field in either frame, the stability over speed) refuse real
/// balls with [`Error::NoLinearisation`], one line naming the keys: a friction dead zone and a
/// resting contact have no linearisation. A run-up takes them.
#[test]
fn stationary_analyses_refuse_real_balls() {
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    p.balls = BallPhysics::builder().rolling_resistance(1e-3).build().unwrap();
    let r = LinearRotor::from_planar(&p).unwrap();
    for frame in [Frame::Rotating, Frame::Fixed] {
        let e = LinearRotorField::new(&r, 400.0, frame).unwrap_err();
        assert!(matches!(e, Error::NoLinearisation { .. }), "{e:?}");
        let m = e.to_string();
        assert!(!m.contains('\n') && m.contains("rolling_resistance"), "{m}");
    }
    let e = autobal::linear_rotor::stability::stability_over_speed(&r, &[300.0, 400.0]).unwrap_err();
    assert!(matches!(e, Error::NoLinearisation { .. }), "{e:?}");
    // point masses: analysed
    let mut q = r.clone();
    q.ball_physics.clear();
    assert!(autobal::linear_rotor::stability::stability_over_speed(&q, &[300.0, 400.0]).is_ok());
}

/// The config's real-ball keys on a balancer plane (the planar and spatial configs' names), read
/// into [`LinearRotor::ball_physics`], written back by export, checked against the plane (a
/// diameter that does not fit the race is named).
#[test]
fn config_reads_real_ball_keys() {
    use autobal::linear_rotor::config::{export, linear_rotor};
    let text = "[linear_rotor]\nlayout = \"x,y\"\nm = \"m.mtx\"\nk = \"k.mtx\"\n[[linear_rotor.balancer]]\nnode = 0\nradius = 0.05\nballs = 2\nball_mass = 0.02\ndrag = 1e-3\n\
                contact = true\nrestitution = 0.7\nrolling_resistance = 1e-3\nball_diameter = 0.012\n";
    let files = [
        ("m.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 1.0\n"),
        ("k.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1e4\n2 2 1e4\n"),
    ];
    let mut load = |p: &str| files.iter().find(|f| f.0 == p).map(|f| f.1.to_string()).ok_or_else(|| "missing".to_string());
    let root: toml::Table = text.parse().unwrap();
    let cfg = linear_rotor(&root, &mut load).unwrap();
    let want = BallPhysics::builder().contact(true).restitution(0.7).rolling_resistance(1e-3).diameter(Some(0.012)).build().unwrap();
    assert_eq!(cfg.rotor.ball_physics, vec![want]);
    let (t, fs) = export(&cfg.rotor, "x");
    let back = linear_rotor(&t.parse().unwrap(), &mut |p| fs.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or("missing".into())).unwrap();
    assert_eq!(back.rotor, cfg.rotor);
    let bad: toml::Table = text.replace("ball_diameter = 0.012", "ball_diameter = 0.2").parse().unwrap();
    let e = linear_rotor(&bad, &mut load).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.balancer[0].ball_diameter"), "{e}");
    let bad: toml::Table = text.replace("contact = true", "contact = 1").parse().unwrap();
    let e = linear_rotor(&bad, &mut load).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.balancer[0].contact"), "{e}");
    // a key of no effect is refused, not ignored: the contact law without contact, the slip
    // rate without rolling resistance
    let bad: toml::Table = text.replace("contact = true", "contact = false").parse().unwrap();
    let e = linear_rotor(&bad, &mut load).unwrap_err().to_string();
    assert_eq!(e, "linear_rotor.balancer[0].ball_diameter: has no effect without contact = true");
    let bad: toml::Table = text.replace("rolling_resistance = 1e-3", "slip_rate = 1e-3").parse().unwrap();
    let e = linear_rotor(&bad, &mut load).unwrap_err().to_string();
    assert_eq!(e, "linear_rotor.balancer[0].slip_rate: has no effect without a rolling_resistance");
    // rolling resistance alone (no contact) round-trips through export: only the keys that act
    let rolling = text.replace("contact = true\nrestitution = 0.7\n", "").replace("ball_diameter = 0.012\n", "");
    let cfg = linear_rotor(&rolling.parse().unwrap(), &mut load).unwrap();
    assert_eq!(cfg.rotor.ball_physics, vec![BallPhysics::builder().rolling_resistance(1e-3).build().unwrap()]);
    let (t, fs) = export(&cfg.rotor, "x");
    assert!(!t.contains("restitution") && t.contains("slip_rate"), "{t}");
    let back = linear_rotor(&t.parse().unwrap(), &mut |p| fs.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or("missing".into())).unwrap();
    assert_eq!(back.rotor, cfg.rotor);
}
