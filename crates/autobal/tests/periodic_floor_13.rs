//! The periodic-orbit floor (`Rotor::periodic_floor`, the speed scan's one rule) in maps and
//! Campbell diagrams (issue 18, round 3 session 13): a periodic orbit's speed below the fastest
//! natural frequency over 1000 is not analysed (said so, counted), and a request whose every
//! speed is below it is refused naming the key that set the speed. On main at e3f0650 both
//! shot a revolution at every such speed: a map down to 1e-6 rad/s ran for more than 60 s.

use autobal::control::Control;
use autobal::rotor_campbell::{campbell_over_speed, NOT_ANALYSED};
use autobal::rotor_map::{general_map_traced, GeneralCell, GeneralMapOutcome};
use autobal::rotor_stability::Rotor;
use autobal::spatial::map::Axis;
use autobal::units::{Speed, SpeedUnit};

/// examples/spatial_two_plane.toml: gravity across the axis, supports stiffer along y, so its
/// stationary state is a periodic orbit of the revolution.
fn two_plane() -> toml::Table {
    autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap()
}

fn rotor() -> Rotor {
    Rotor::Spatial(autobal::config::spatial_simulation(&two_plane()).unwrap().rotor)
}

fn map(x: &Axis, y: &Axis, speed: Option<Speed>) -> autobal::Result<(Vec<GeneralCell>, GeneralMapOutcome)> {
    let mut cells = vec![];
    let out = general_map_traced(&two_plane(), x, y, speed, true, &Control::none(), &mut |_, r, _| {
        cells.extend_from_slice(r);
        true
    })?;
    Ok((cells, out))
}

/// The floor of the example is its fastest natural frequency over 1000: 0.81 rad/s (the
/// spatial rotor's stiffer translation-tilt pair; `Rotor::fastest_natural_frequency`, checked
/// against its closed form in rotor_stability's unit tests). 0.5 rad/s lies below it (a
/// revolution spans ~1600 of the fastest periods), 450 and 500 rad/s far above.
#[test]
fn a_maps_cells_below_the_floor_are_not_analysed_and_the_rest_unchanged() {
    let r = rotor();
    let floor = r.periodic_floor(0.5).expect("a periodic orbit");
    assert!(0.5 < floor && floor < 450.0, "{floor}");
    let y = Axis { path: "balancer.drag".into(), values: vec![0.5] };
    let (cells, out) = map(&Axis { path: "speed".into(), values: vec![0.5, 450.0, 500.0] }, &y, None).unwrap();
    // below the floor: no state sought, said so, counted apart from "no state found"
    assert!(!cells[0].analysed && cells[0].verdict.is_none() && cells[0].margin.is_nan(), "{:?}", cells[0]);
    assert_eq!((out.not_analysed, out.none), (1, 0), "{out:?}");
    // above it: the very cells of a map without the slow speed (the slow cell hands on no
    // state, so the row's continuation is the same), bit for bit
    let (above, _) = map(&Axis { path: "speed".into(), values: vec![450.0, 500.0] }, &y, None).unwrap();
    assert!(cells[1..].iter().all(|c| c.analysed && c.verdict.is_some()), "{cells:?}");
    assert_eq!(format!("{:?}", &cells[1..]), format!("{above:?}"));
}

/// Every speed below the floor: refused at once, naming the key that set the speed (the speed
/// axis' path, or `omega` for a map at one speed), both numbers in its unit, written.
#[test]
fn a_map_with_every_speed_below_the_floor_is_refused_naming_the_speed() {
    let y = Axis { path: "balancer.drag".into(), values: vec![0.4, 0.5] };
    let e = map(&Axis { path: "speed".into(), values: vec![1e-6, 1e-5] }, &y, None).unwrap_err();
    assert_eq!(e.field(), Some("speed"), "{e}");
    let msg = e.to_string();
    assert!(msg.starts_with("speed: 1e-5 rad/s is below 0.809787 rad/s,") && !msg.contains('\n'), "{msg}");
    // on the vertical axis, in rpm: the floor in rpm (0.81 rad/s = 7.7 rpm)
    let e = map(&y, &Axis { path: "speed_rpm".into(), values: vec![1e-4, 1.0] }, None).unwrap_err();
    assert!(e.to_string().starts_with("speed_rpm: 1 rpm is below 7.73289 rpm,"), "{e}");
    // at one speed, over two parameters
    let x = Axis { path: "balancer2.drag".into(), values: vec![0.4, 0.5] };
    let e = map(&x, &y, Some(Speed { value: 1e-3, unit: SpeedUnit::RadPerS })).unwrap_err();
    assert_eq!(e.field(), Some("omega"), "{e}");
    assert!(e.to_string().starts_with("omega: 0.001 rad/s is below 0.809787 rad/s,"), "{e}");
}

/// The Campbell diagram applies the same rule: a speed below the floor has no point, its
/// failure says "not analysed", `analysed` is false; the speeds above have the spectrum of a
/// diagram without it (the same eigenvalues: the slow speed hands on no state). Every speed
/// below: refused naming `omega_max`.
#[test]
fn a_campbell_diagrams_speeds_below_the_floor_are_not_analysed() {
    let r = rotor();
    let c = campbell_over_speed(&r, &[0.5, 450.0, 500.0]).unwrap();
    assert_eq!(c.analysed, vec![false, true, true]);
    assert!(c.failures[0].as_deref().is_some_and(|f| f.starts_with(NOT_ANALYSED)), "{:?}", c.failures[0]);
    assert!(c.failures[1..].iter().all(|f| f.is_none()), "{:?}", c.failures);
    let above = campbell_over_speed(&r, &[450.0, 500.0]).unwrap();
    let at = |c: &autobal::rotor_campbell::RotorCampbell, k: usize| {
        let mut v: Vec<String> = c.lines.iter().filter_map(|l| l.points[k].as_ref()).map(|p| format!("{p:?}")).collect();
        v.sort();
        v
    };
    assert!(c.lines.iter().all(|l| l.points[0].is_none()));
    assert!(!at(&above, 0).is_empty());
    assert_eq!((at(&c, 1), at(&c, 2)), (at(&above, 0), at(&above, 1)));
    let e = campbell_over_speed(&r, &[1e-6, 2e-6]).unwrap_err();
    assert_eq!(e.field(), Some("omega_max"), "{e}");
    assert!(e.to_string().starts_with("omega_max: 2e-6 is below 0.8"), "{e}");
}

/// The slip the failure prints, in rad per revolution (the number after "slip behind it at ~").
fn printed_slip(failure: &str) -> Option<f64> {
    let rest = failure.split("slip behind it at ~").nth(1)?;
    rest.split_whitespace().next()?.parse().ok()
}

/// The two-plane example with supports of 5e8/6e8 N/m in both directions.
fn stiff_root() -> toml::Table {
    let mut root = two_plane();
    for (k, v) in [("supports.stiffness_left", 5e8), ("supports.stiffness_right", 6e8), ("supports.stiffness_left_y", 5e8), ("supports.stiffness_right_y", 6e8)]
    {
        autobal::config::set_number(&mut root, k, v).unwrap();
    }
    root
}

/// Stiff supports under gravity: no periodic orbit at 30 rad/s, and the verdict says why,
/// with the slip per revolution that a time run at that constant speed measures. The run
/// (0.84 s: four revolutions; the balls' start transient decays as exp(−β t), β = h/m = 25/s,
/// to e⁻¹⁰ in the first two) gives the simulation's `ball_drift`, the change of the balls'
/// mean angle between the last two revolutions: 0.015352 rad. The printed slip is the
/// second-order average g²/(2ΩR²(Ω² + β²)) · 2π/Ω = 0.015297; the average neglects terms of
/// relative order ε² (ε = g/(RΩ√(Ω² + β²)) = 0.070, the balls' swing: 0.5 %), and the hold
/// (m²R²Ω⁴/|k − MΩ²| = 4e-9 N m against a drag of 5e-4 N m) changes nothing, so 2 % (four times
/// ε²) separates the formula from one off by a factor (without β: 0.0258, 69 % off).
#[test]
fn stiff_supports_under_gravity_slip_as_a_time_run_does() {
    let root = stiff_root();
    let stiff = Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor);
    let r = autobal::rotor_stability::stability_over_speed(&stiff, &[30.0]).unwrap();
    let f = r.points[0].failure.clone().unwrap_or_default();
    assert!(f.starts_with("no periodic orbit found"), "{f}");
    let printed = printed_slip(&f).unwrap_or_else(|| panic!("no slip in {f:?}"));
    // the time run at a constant 30 rad/s
    let text = toml::to_string(&root).unwrap();
    let mut run = autobal::config::parse(&text, "stiff").unwrap();
    autobal::config::set(&mut run, "drive.schedule", toml::Value::try_from(vec![vec![0.0, 30.0], vec![0.84, 30.0]]).unwrap()).unwrap();
    autobal::config::set_number(&mut run, "drive.t_end", 0.84).unwrap();
    let sim = autobal::config::spatial_simulation(&run).unwrap();
    let s = autobal::spatial::dynamics::simulate::simulate_summary(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, &Control::none()).unwrap();
    let drift = s.ball_drift.expect("two revolutions at least");
    assert!((printed - drift).abs() <= 0.02 * drift, "printed {printed}, run {drift}");
}

/// The words come only where the drag exceeds the hold ten times: on the example's own
/// supports (5e6 N/m along x) the ratio drag/hold is m g² β/(2Ω(Ω² + β²)) · |k − MΩ²|/(m²R²Ω⁴):
/// 6.3 at 60 rad/s (no slip words, whatever the verdict) and 51 at 43.7 rad/s (the words),
/// and at 450 rad/s an orbit is found.
#[test]
fn the_slip_words_need_the_drag_ten_times_the_hold() {
    let ratio = |w: f64| {
        let (m, g, beta, r, k, mt) = (0.02f64, 9.81f64, 25.0f64, 0.12f64, 5e6f64, 20.0 + 0.02 + 0.08);
        m * g * g * beta / (2.0 * w * (w * w + beta * beta)) * (k - mt * w * w).abs() / (m * m * r * r * w.powi(4))
    };
    assert!(ratio(60.0) < 10.0 && ratio(43.7) > 10.0, "{} {}", ratio(60.0), ratio(43.7));
    let slips = |w: f64| {
        let r = autobal::rotor_stability::stability_over_speed(&rotor(), &[w]).unwrap();
        let p = &r.points[0];
        (p.verdict.is_some(), p.failure.clone().unwrap_or_default())
    };
    let (_, at60) = slips(60.0);
    assert!(!at60.contains("slip"), "{at60}");
    let (found, at43) = slips(43.7);
    assert!(!found && at43.contains("the balls slip behind it at ~"), "{at43}");
    let ok = autobal::rotor_stability::stability_over_speed(&rotor(), &[450.0]).unwrap();
    assert!(ok.points[0].verdict.is_some() && ok.points[0].failure.is_none(), "{:?}", ok.points[0]);
}
