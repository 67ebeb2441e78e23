//! Stability maps of a linear rotor config (issue 19 item 4): [`linear_map_traced`] over the
//! parameter paths of [`autobal::linear_rotor::spec`], against the native planar route on the
//! Jeffcott preset and against per-point eigenvalues computed here on a flexible shaft.

use autobal::analysis::{stationary, NewtonOptions, VectorField, Verdict};
use autobal::config;
use autobal::control::Control;
use autobal::linalg::eigen_dyn;
use autobal::linear_rotor::config::{export, linear_rotor};
use autobal::linear_rotor::spec::LinearRotorSpec;
use autobal::linear_rotor::{Frame, LinearRotor, LinearRotorField};
use autobal::rotor_map::{general_map_traced, linear_map_traced, BoundaryPoint, GeneralCell};
use autobal::spatial::map::Axis;
use autobal::units::Speed;
use toml::Table;

/// examples/planar.toml with its race centred (`s2 = 0`): a Jeffcott rotor with two balls.
fn planar_root() -> Table {
    let mut root = config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
    config::set_number(&mut root, "planar.s2", 0.0).unwrap();
    root
}

/// The same rotor as a linear rotor config written by `export-model`
/// ([`LinearRotor::from_planar`], Matrix Market files read back exactly).
fn preset_spec(root: &Table) -> LinearRotorSpec {
    let p = config::planar(root).unwrap().rotor;
    let (text, files) = export(&LinearRotor::from_planar(&p).unwrap(), "jeffcott");
    LinearRotorSpec::new(text.parse().unwrap(), &mut |name| files.iter().find(|f| f.0 == name).map(|f| f.1.clone().into_bytes()).ok_or("missing".into()))
        .unwrap()
}

type Rows = (Vec<Vec<GeneralCell>>, Vec<BoundaryPoint>);

fn collect(
    run: impl FnOnce(&mut dyn FnMut(usize, &[GeneralCell], &[BoundaryPoint]) -> bool) -> autobal::Result<autobal::rotor_map::GeneralMapOutcome>,
) -> autobal::Result<Rows> {
    let (mut rows, mut pts) = (vec![], vec![]);
    let out = run(&mut |_, r, p| {
        rows.push(r.to_vec());
        pts.extend_from_slice(p);
        true
    })?;
    assert!(out.complete);
    Ok((rows, pts))
}

/// The map of the preset over the speed and the balls' drag equals the planar route's over
/// the speed and `planar.c_psi`, cell by cell, with the same bisected boundary. The two models
/// share no equations and their eigenvalues agree to 1e-10 of the spectrum's rate
/// (tests/linear_rotor.rs, `jeffcott_preset_equals_the_planar_model`); the rate is a few ω_n
/// here, so margins agree to 1e-8 ω_n, and the boundaries, each bisected to 1e-9 relative, to
/// 2e-9 relative (both last intervals).
#[test]
fn the_jeffcott_preset_maps_as_the_planar_route() {
    let root = planar_root();
    let spec = preset_spec(&root);
    let wn = config::planar(&root).unwrap().rotor.natural_frequency();
    let speeds: Vec<f64> = (1..=7).map(|i| 0.4 * wn * i as f64).collect();
    let x = Axis { path: "omega".into(), values: speeds };
    let (ya, yb) = (Axis { path: "planar.c_psi".into(), values: vec![0.02, 0.3] }, Axis { path: "linear_rotor.drag".into(), values: vec![0.02, 0.3] });
    let (a, pa) = collect(|f| general_map_traced(&root, &x, &ya, None, true, &Control::none(), f)).unwrap();
    let (b, pb) = collect(|f| linear_map_traced(&spec, &x, &yb, None, true, &Control::none(), f)).unwrap();
    for (ra, rb) in a.iter().zip(&b) {
        for (ca, cb) in ra.iter().zip(rb) {
            assert_eq!(ca.verdict, cb.verdict, "{ca:?} vs {cb:?}");
            assert!((ca.margin - cb.margin).abs() <= 1e-8 * wn, "{} vs {}", ca.margin, cb.margin);
            assert_eq!(ca.family_dimension, cb.family_dimension);
        }
    }
    // the map is not trivial: unstable below the critical speed, stable above it somewhere
    assert!(b.iter().all(|r| r[0].verdict == Some(Verdict::Unstable)));
    assert!(b.iter().flatten().any(|c| c.verdict == Some(Verdict::Stable)));
    assert_eq!(pa.len(), pb.len());
    assert!(!pb.is_empty());
    for (p, q) in pa.iter().zip(&pb) {
        assert!((p.x - q.x).abs() <= 2e-9 * p.x, "{} vs {}", p.x, q.x);
        assert_eq!((p.from, p.to), (q.from, q.to));
    }
}

/// At a fixed speed over two paths (ball mass, drag): the same verdicts and margins as the
/// planar route over `planar.m3` and `planar.c_psi`, including the cells where the balls cannot
/// cancel the unbalance (n m_b r < m1 s1: no balanced state; both routes start from the balls
/// bunched there and reach the partially balanced state).
#[test]
fn a_fixed_speed_map_over_two_paths_matches_the_planar_route() {
    let root = planar_root();
    let spec = preset_spec(&root);
    let wn = config::planar(&root).unwrap().rotor.natural_frequency();
    let masses = vec![0.02, 0.03, 0.05];
    let drags = vec![0.05, 0.2];
    let speed = Some(Speed::omega(1.6 * wn));
    let (a, _) = collect(|f| {
        general_map_traced(
            &root,
            &Axis { path: "planar.m3".into(), values: masses.clone() },
            &Axis { path: "planar.c_psi".into(), values: drags.clone() },
            speed,
            false,
            &Control::none(),
            f,
        )
    })
    .unwrap();
    let (b, _) = collect(|f| {
        linear_map_traced(
            &spec,
            &Axis { path: "linear_rotor.ball_mass".into(), values: masses.clone() },
            &Axis { path: "linear_rotor.drag".into(), values: drags.clone() },
            speed,
            false,
            &Control::none(),
            f,
        )
    })
    .unwrap();
    for (ra, rb) in a.iter().zip(&b) {
        for (ca, cb) in ra.iter().zip(rb) {
            assert_eq!(ca.verdict, cb.verdict);
            assert!(ca.margin.is_nan() == cb.margin.is_nan() && (ca.margin.is_nan() || (ca.margin - cb.margin).abs() <= 1e-8 * wn));
        }
        // 2 × 0.02 kg × 0.06 m = 0.0024 kg m < m1 s1 = 0.003 kg m: no balanced state, so no
        // closed form; on both routes the cell starts from the balls bunched (the speed scan's
        // start, Rotor::first_start; until session 17 it was continued from its neighbour):
        // the partially balanced state, the same on both
        assert!(!rb[0].continued && !ra[0].continued && rb[0].verdict.is_some());
        assert!(ra[0].state == Some(autobal::rotor_stability::StateKind::PartiallyBalanced) && rb[0].state == ra[0].state, "{:?} {:?}", ra[0], rb[0]);
        assert!(!rb[1].continued && rb[1].verdict.is_some());
    }
}

/// A four-element steel shaft on two bearings with a two-ball balancer at mid-span.
fn shaft_text(k: f64) -> String {
    format!(
        "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.15\ndiameter = 0.03\ne = 2.1e11\nrho = 7850.0\ncount = 4\n\
         [[linear_rotor.disks]]\nnode = 2\nmass = 4.0\nid = 0.01\nip = 0.02\n\
         [[linear_rotor.bearings]]\nnode = 0\nk = {k:e}\nc = 200.0\n[[linear_rotor.bearings]]\nnode = 4\nk = {k:e}\nc = 200.0\n\
         [[linear_rotor.unbalance]]\nnode = 2\nme = 2e-4\n\
         [[linear_rotor.balancer]]\nnode = 2\nradius = 0.08\nballs = 2\nball_mass = 0.02\ndrag = 0.02\n"
    )
}

/// The margin of the balanced state of `rotor` at `w`, computed here: Newton from the closed
/// form, the Jacobian in turning axes, and the largest real part of its eigenvalues from the
/// dense eigenvalue routine (two balls: an isolated state, no structural zero to remove).
fn margin_here(rotor: &LinearRotor, w: f64) -> Option<f64> {
    let f = LinearRotorField::new(rotor, w, Frame::Rotating).unwrap();
    let s = stationary(&f, &f.balanced_guess()?, &NewtonOptions::default()).ok()?;
    let d = f.dim();
    let mut j = vec![0.0; d * d];
    f.jacobian(0.0, &s.x, &mut j);
    let ev = eigen_dyn::eigenvalues(&j, d).unwrap();
    Some(ev.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max))
}

/// A flexible shaft mapped over the speed and the bearings' stiffness scale: each cell's margin
/// against the one computed here from a config written with that stiffness (the path's edit of
/// the tables, the grid's continuation and the verdict are what is checked). Both solve the
/// same equations with Newton to its tolerance (1e-12 relative in the state): the margins agree
/// to 1e-9 of the largest eigenvalue's modulus.
#[test]
fn a_flexible_shaft_map_matches_per_point_eigenvalues() {
    let spec = LinearRotorSpec::new(shaft_text(2e6).parse().unwrap(), &mut |_| Err("no files".into())).unwrap();
    let rotor = linear_rotor(spec.root(), &mut |_| Err("no files".into())).unwrap().rotor;
    let wn = rotor.natural_frequencies(&[], true).unwrap()[0];
    let x = Axis { path: "omega".into(), values: vec![0.5 * wn, 1.5 * wn, 2.5 * wn] };
    let y = Axis { path: "linear_rotor.support_stiffness_scale".into(), values: vec![0.5, 2.0] };
    let (rows, _) = collect(|f| linear_map_traced(&spec, &x, &y, None, false, &Control::none(), f)).unwrap();
    let mut stable = 0;
    for (j, s) in y.values.iter().enumerate() {
        let root: Table = shaft_text(2e6 * s).parse().unwrap();
        let r = linear_rotor(&root, &mut |_| Err("no files".into())).unwrap().rotor;
        let scale = {
            let f = LinearRotorField::new(&r, x.values[2], Frame::Rotating).unwrap();
            let st = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
            let mut jac = vec![0.0; f.dim() * f.dim()];
            f.jacobian(0.0, &st.x, &mut jac);
            eigen_dyn::eigenvalues(&jac, f.dim()).unwrap().iter().map(|z| z.norm()).fold(0.0, f64::max)
        };
        for (i, &w) in x.values.iter().enumerate() {
            let cell = rows[j][i];
            let m = margin_here(&r, w).expect("a balanced state");
            assert!((cell.margin - m).abs() <= 1e-9 * scale, "cell ({i}, {j}): {} vs {m}", cell.margin);
            assert_eq!(cell.verdict, Some(if m < 0.0 { Verdict::Stable } else { Verdict::Unstable }), "cell ({i}, {j}): margin {m}");
            stable += usize::from(m < 0.0);
        }
        // below the first critical speed the balls make the balanced state unstable
        assert_eq!(rows[j][0].verdict, Some(Verdict::Unstable));
    }
    assert!(stable > 0, "no stable cell: {rows:?}");
}

/// Bad axes and refusals: one line naming the path.
#[test]
fn bad_paths_and_refusals_name_the_path() {
    let spec = LinearRotorSpec::new(shaft_text(2e6).parse().unwrap(), &mut |_| Err("no files".into())).unwrap();
    let speeds = Axis { path: "omega".into(), values: vec![100.0, 200.0] };
    let run = |spec: &LinearRotorSpec, y: &Axis| collect(|f| linear_map_traced(spec, &speeds, y, None, false, &Control::none(), f)).unwrap_err().to_string();
    let e = run(&spec, &Axis { path: "linear_rotor.nope".into(), values: vec![1.0, 2.0] });
    assert!(e.starts_with("linear_rotor.nope: unknown parameter path"), "{e}");
    let e = run(&spec, &Axis { path: "linear_rotor.ball_mass".into(), values: vec![0.01, -1.0] });
    assert!(e.starts_with("linear_rotor.ball_mass"), "{e}");
    let e = run(&spec, &Axis { path: "drive.nope".into(), values: vec![1.0, 2.0] });
    assert!(e.starts_with("drive.nope: unknown parameter path"), "{e}");
    // the Jeffcott preset has its support inside K: no bearing table to scale
    let e = run(&preset_spec(&planar_root()), &Axis { path: "linear_rotor.support_stiffness_scale".into(), values: vec![1.0, 2.0] });
    assert!(e.starts_with("linear_rotor.support_stiffness_scale") && e.contains("no [[linear_rotor.bearings]]"), "{e}");
}

/// Gravity turns once per revolution in axes turning with the rotor: the map's stationary
/// state is then a periodic orbit, judged by its Floquet multipliers (never an equilibrium's
/// eigenvalues), in every cell where one is found.
#[test]
fn with_gravity_the_map_judges_periodic_orbits() {
    let mut text = shaft_text(2e6);
    text = text.replacen("[linear_rotor]\n", "[linear_rotor]\ngravity = [0.0, -9.81]\n", 1);
    let g = LinearRotorSpec::new(text.parse().unwrap(), &mut |_| Err("no files".into())).unwrap();
    let speeds = Axis { path: "omega".into(), values: vec![100.0, 200.0] };
    let drag = Axis { path: "linear_rotor.drag".into(), values: vec![0.01, 0.02] };
    let (rows, _) = collect(|f| linear_map_traced(&g, &speeds, &drag, None, false, &Control::none(), f)).unwrap();
    let cells: Vec<&GeneralCell> = rows.iter().flatten().collect();
    assert!(cells.iter().any(|c| c.verdict.is_some()), "no stationary state found: {rows:?}");
    for c in cells.iter().filter(|c| c.verdict.is_some()) {
        assert_eq!(c.kind, Some(autobal::analysis::Kind::PeriodicOrbit), "{c:?}");
        assert!(c.margin.is_finite(), "{c:?}");
    }
}
