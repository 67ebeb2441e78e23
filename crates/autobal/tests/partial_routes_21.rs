//! The linear route and `map` analyse the partially balanced state the spatial scan analyses
//! (session 21): audit 20's random rotor rnd/r19_00_sp.toml (two ball planes 6 mm apart near
//! one end, each far short of its share of the unbalance; tests/partial_states_20.rs) written
//! as a linear rotor ([`LinearRotor::from_spatial`]: the two models share no equations). Until
//! session 21 the linear route and the map tried one start where no balanced state exists,
//! and analysed another state than the spatial scan (at 372-434 rad/s a state unstable at
//! +10 to +21 1/s where the spatial scan's is at +0.27 to +1.9; at 81-249 rad/s an unstable
//! state beside the stable one the spatial scan analyses).

use autobal::analysis::Verdict;
use autobal::control::Control;
use autobal::linear_rotor::config::export;
use autobal::linear_rotor::spec::LinearRotorSpec;
use autobal::linear_rotor::LinearRotor;
use autobal::rotor_map::{general_map, linear_map_traced, GeneralCell};
use autobal::rotor_stability::{stability_over_speed, Rotor, RotorStability};
use autobal::spatial::map::Axis;
use std::f64::consts::TAU;

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

fn root() -> toml::Table {
    autobal::config::parse(CONFIG, "r19_00_sp").unwrap()
}

fn spatial() -> autobal::spatial::dynamics::SpatialRotor {
    autobal::config::spatial_simulation(&root()).unwrap().rotor
}

/// The distance (rad) between two placements, each plane's two balls matched in either order.
fn psi_distance(a: &[f64], b: &[f64]) -> f64 {
    let d = |x: f64, y: f64| {
        let w = (x - y).rem_euclid(TAU);
        w.min(TAU - w)
    };
    a.chunks(2).zip(b.chunks(2)).map(|(p, q)| (d(p[0], q[0]).max(d(p[1], q[1]))).min(d(p[0], q[1]).max(d(p[1], q[0])))).fold(0.0, f64::max)
}

/// The grid of `autobal stability` on this rotor up to 580 rad/s (the audit's axis to
/// 1160.287 rad/s at 200 samples, its first 100): the scan carries each speed's states to the
/// next, so the grid is the audit's.
fn speeds() -> Vec<f64> {
    (1..=100).map(|k| 1160.286955210251 * k as f64 / 200.0).collect()
}

fn scans() -> (RotorStability, RotorStability) {
    let s = spatial();
    let l = LinearRotor::from_spatial(&s).unwrap();
    let w = speeds();
    (stability_over_speed(&Rotor::Spatial(s), &w).unwrap(), stability_over_speed(&Rotor::Linear(l), &w).unwrap())
}

/// The linear route's stable ranges are the spatial scan's, and at every grid speed it
/// analyses the same state with the same verdict. Tolerances: a partially balanced state
/// whirls (the residual unbalance), and the linear model keeps the kinetic energy to second
/// order in the whirl where the native one is exact, so the two states differ at second order
/// (not to round-off as the balanced states of tests/linear_rotor_two_planes.rs, 1e-9 rad):
/// measured up to 1.02e-3 rad in the balls (at 11.6 rad/s, where the balls are held weakly;
/// 9.1e-4 at 568.5 rad/s, next to a range's end), hence 2e-3 rad; another state lies more than 0.25 rad away at every speed
/// (the nearest, at 464.1 rad/s before this change). The range ends, bisected on abscissae
/// that differ by that much, within 1e-4 relative (measured: 4.9e-5 at 570.7 rad/s, the others
/// below 6e-6), as against the 1e-6 of tests/linear_rotor_gravity.rs, where the models differ
/// at second order in the tilt under gravity's sag, a smaller amplitude than this whirl.
/// Fails before session 21 (the linear route analysed a state unstable at 81-249 rad/s where the
/// spatial scan's is stable, and at 372-434 another unstable one).
#[test]
fn the_linear_route_analyses_the_spatial_scans_partial_state() {
    let (s, l) = scans();
    eprintln!("spatial {:?}\nlinear {:?}", s.stable_ranges, l.stable_ranges);
    let mut worst: f64 = 0.0;
    for (p, q) in s.points.iter().zip(&l.points) {
        let (Some(a), Some(b)) = (p.verdict, q.verdict) else { continue };
        let d = psi_distance(&p.member_psi, &q.member_psi);
        worst = worst.max(d);
        assert!(d <= 2e-3, "{} rad/s: spatial {:?} ({a:?}), linear {:?} ({b:?})", p.omega, p.member_psi, q.member_psi);
        assert_eq!(a, b, "{} rad/s: abscissa {:?} vs {:?}", p.omega, p.abscissa, q.abscissa);
    }
    eprintln!("largest ball distance {worst:e} rad");
    // the grid speeds both solved: all but a few where Newton fails in one route
    let both = s.points.iter().zip(&l.points).filter(|(p, q)| p.verdict.is_some() && q.verdict.is_some()).count();
    assert!(both >= 95, "{both} of 100 speeds solved by both");
    assert_eq!(s.stable_ranges.len(), l.stable_ranges.len());
    assert!(s.stable_ranges.len() >= 3, "{:?}", s.stable_ranges);
    for (a, b) in s.stable_ranges.iter().zip(&l.stable_ranges) {
        assert!((a.from - b.from).abs() <= 1e-4 * a.from && (a.to - b.to).abs() <= 1e-4 * a.to, "{a:?} vs {b:?}");
    }
}

/// The map's cells at 372-434 rad/s analyse the scan's state: the general route's map on the
/// spatial config against the spatial scan, the linear route's map on the same rotor exported
/// as a linear config (`export-model`) against the linear scan, the scans over the cells'
/// speeds (carried states and all, as `autobal stability` over that axis). Each cell's verdict
/// is the scans' (the two routes' verdicts agree there), its margin the scan's abscissa: the
/// spatial map's per unit τ, its ratio to the scan's the same at every cell to 1e-9, as
/// tests/map_partial_17.rs; the linear map's in 1/s, equal to 1e-9 relative (one state of one
/// model from different starts: Newton's states agree to ~1e-12, their eigenvalues to ~1e-10
/// of the rate). The two routes' abscissas differ at second order in the whirl (1e-3
/// relative at most here) where both analyse one state; at 420 rad/s the linear route reaches a
/// state with less growth (+0.379 against +0.399 1/s) that the spatial route's starts miss on
/// this grid (its scan over the audit's grid finds it at 417.7 and 423.5 rad/s), so the routes
/// are compared by verdict only. Fails before session 21: the spatial map analysed another
/// state than the scan at 412-434 rad/s (margin 4.48e-3 per unit τ against the scan's 1.41e-3
/// at 412 rad/s).
#[test]
fn map_cells_give_the_scans_partial_state() {
    // unstable to 428 rad/s, stable at 434 (the range from 430.4)
    let speeds: Vec<f64> = vec![372.0, 390.0, 404.0, 412.0, 420.0, 428.0, 434.0];
    let scan = stability_over_speed(&Rotor::Spatial(spatial()), &speeds).unwrap();
    let lscan = stability_over_speed(&Rotor::Linear(LinearRotor::from_spatial(&spatial()).unwrap()), &speeds).unwrap();
    let x = Axis { path: "speed".into(), values: speeds.clone() };
    let mut rows: Vec<Vec<GeneralCell>> = vec![];
    let y = Axis { path: "balancer.drag".into(), values: vec![1.8398343882912835] };
    general_map(&root(), &x, &y, None, &Control::none(), &mut |_, r| {
        rows.push(r.to_vec());
        true
    })
    .unwrap();
    let (text, files) = export(&LinearRotor::from_spatial(&spatial()).unwrap(), "r19");
    let spec =
        LinearRotorSpec::new(text.parse().unwrap(), &mut |name| files.iter().find(|f| f.0 == name).map(|f| f.1.clone().into_bytes()).ok_or("missing".into()))
            .unwrap();
    let mut lin: Vec<Vec<GeneralCell>> = vec![];
    let y = Axis { path: "linear_rotor.balancer[0].ball_mass".into(), values: vec![spatial().planes[0].ball_mass] };
    linear_map_traced(&spec, &x, &y, None, false, &Control::none(), &mut |_, r, _| {
        lin.push(r.to_vec());
        true
    })
    .unwrap();
    let mut ratio = None;
    for (((c, d), p), q) in rows[0].iter().zip(&lin[0]).zip(&scan.points).zip(&lscan.points) {
        eprintln!(
            "{} rad/s: spatial scan {:?} {:?}, map {:?} {}; linear scan {:?} {:?}, map {:?} {}",
            p.omega, p.verdict, p.abscissa, c.verdict, c.margin, q.verdict, q.abscissa, d.verdict, d.margin
        );
        assert!(p.verdict.is_some(), "{p:?}");
        assert_eq!(c.verdict, p.verdict, "{} rad/s: {c:?}", p.omega);
        assert_eq!(q.verdict, p.verdict, "{} rad/s: {q:?}", p.omega);
        assert_eq!(d.verdict, p.verdict, "{} rad/s: {d:?}", p.omega);
        let r = p.abscissa.unwrap() / c.margin;
        let r0 = *ratio.get_or_insert(r);
        assert!(r > 0.0 && (r - r0).abs() <= 1e-9 * r0, "{} rad/s: {r} vs {r0}", p.omega);
        let a = q.abscissa.unwrap();
        assert!((d.margin - a).abs() <= 1e-9 * a.abs(), "{} rad/s: linear map {} vs scan {a}", p.omega, d.margin);
    }
    assert_eq!(scan.points.last().unwrap().verdict, Some(Verdict::Stable));
}
