//! The linear rotor's config, Matrix Market files, speed-dependent bearings and runs in time
//! ([`autobal::linear_rotor::config`], [`autobal::linear_rotor::runup`]): export and read back
//! gives the same rotor and eigenvalues; errors name the key, file and line; a tabulated bearing
//! equals the constant bearing with the interpolated values; a run-up of the Jeffcott preset
//! equals the native planar model's run-up sample by sample.

use autobal::analysis::{stability, stationary, NewtonOptions, VectorField};
use autobal::drive::Drive;
use autobal::linear_rotor::config::{export, linear_rotor, parse_matrix_market, write_matrix_market};
use autobal::linear_rotor::runup::{drive_angle, simulate, RunSettings};
use autobal::linear_rotor::stability::stability_over_speed;
use autobal::linear_rotor::{Frame, LinearRotor, LinearRotorField, SpeedBearing};
use autobal::ode::Method;
use autobal::planar::{PlanarRotor, Settings};
use std::collections::HashMap;

fn jeffcott() -> LinearRotor {
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    LinearRotor::from_planar(&p).unwrap()
}

fn parse(text: &str) -> toml::Table {
    text.parse().unwrap()
}

fn load(root: &toml::Table, files: &HashMap<String, String>) -> autobal::Result<autobal::linear_rotor::config::LinearRotorConfig> {
    linear_rotor(root, &mut |p| files.get(p).cloned().ok_or_else(|| format!("no such file {p}")))
}

fn shaft_config() -> String {
    r#"
[linear_rotor]
[[linear_rotor.elements]]
length = 0.1
diameter = 0.025
e = 2.1e11
rho = 7850.0
count = 6
[[linear_rotor.disks]]
node = 3
mass = 4.0
id = 0.01
ip = 0.02
[[linear_rotor.bearings]]
node = 0
k = 2e6
c = 300.0
[[linear_rotor.bearings]]
node = 6
k = 2e6
c = 300.0
[[linear_rotor.unbalance]]
node = 3
me = 2e-4
[[linear_rotor.balancer]]
node = 3
radius = 0.06
balls = 2
ball_mass = 0.02
drag = 0.002
"#
    .into()
}

/// Export to Matrix Market and read back: the same rotor bit for bit, hence the same eigenvalues
/// of the balanced state and the same natural frequencies (the Jeffcott preset of paper 004 and
/// a shaft from the builder).
#[test]
fn export_and_read_back_is_exact() {
    let shaft = load(&parse(&shaft_config()), &HashMap::new()).unwrap().rotor;
    for rotor in [jeffcott(), shaft] {
        let (text, files) = export(&rotor, "m");
        let files: HashMap<String, String> = files.into_iter().collect();
        let back = load(&parse(&text), &files).unwrap();
        assert_eq!(back.source, "matrices");
        assert_eq!(back.rotor, rotor);
        assert_eq!(back.rotor.natural_frequencies(&[], true).unwrap(), rotor.natural_frequencies(&[], true).unwrap());
        let w = 1.5 * rotor.natural_frequencies(&[], true).unwrap()[0];
        let eig = |r: &LinearRotor| {
            let f = LinearRotorField::new(r, w, Frame::Rotating).unwrap();
            let s = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
            stability(&f, &s).unwrap().abscissa
        };
        assert_eq!(eig(&back.rotor), eig(&rotor));
    }
}

/// Matrix Market: symmetric and skew-symmetric storage expand, array storage is column-major,
/// and the writer's numbers read back exactly.
#[test]
fn matrix_market_reads_the_standard_forms() {
    let (r, c, a) = parse_matrix_market("%%MatrixMarket matrix coordinate real symmetric\n% c\n2 2 2\n1 1 4.0\n2 1 -1.5\n").unwrap();
    assert_eq!((r, c, a), (2, 2, vec![4.0, -1.5, -1.5, 0.0]));
    let (_, _, a) = parse_matrix_market("%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 3\n").unwrap();
    assert_eq!(a, vec![0.0, -3.0, 3.0, 0.0]);
    let (_, _, a) = parse_matrix_market("%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n").unwrap();
    assert_eq!(a, vec![1.0, 3.0, 2.0, 4.0]);
    let m = vec![0.1, 1.0 / 3.0, -2e-300, 7.25e12];
    let (_, _, back) = parse_matrix_market(&write_matrix_market(&m, 2, "x")).unwrap();
    assert_eq!(back, m);
}

/// Errors name the key, the file and the line.
#[test]
fn errors_name_key_file_and_line() {
    let bad = [
        ("%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 x\n", "line 3: \"x\" is not a number"),
        ("%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1.0\n", "line 3: index \"3\" outside 1..2"),
        ("%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n", "1 entries, the size line announces 2"),
        ("%%MatrixMarket matrix coordinate complex general\n2 2 1\n1 1 1 0\n", "line 1: field \"complex\""),
        ("2 2 1\n", "line 1: expected the header"),
    ];
    for (text, want) in bad {
        let e = parse_matrix_market(text).unwrap_err();
        assert!(e.contains(want), "{e}");
    }
    let root = parse("[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"K.mtx\"\n");
    let mut files = HashMap::new();
    files.insert("M.mtx".to_string(), "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 1.0\n".to_string());
    files.insert("K.mtx".to_string(), "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 nan\n".to_string());
    let e = load(&root, &files).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.k: K.mtx: line 3: nan is not finite"), "{e}");
    files.remove("K.mtx");
    let e = load(&root, &files).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.k: K.mtx: no such file"), "{e}");
    // the shaft builder's switches with matrix files: refused by name, not ignored (main at
    // bb89c7b took `gyroscopic = false` beside a G file and left G acting)
    files.insert("K.mtx".to_string(), "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 1.0\n".to_string());
    assert!(load(&root, &files).is_ok());
    for key in ["gyroscopic", "rotary_inertia"] {
        let with = parse(&format!("[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"K.mtx\"\n{key} = false\n"));
        let e = load(&with, &files).unwrap_err().to_string();
        assert!(e.starts_with(&format!("linear_rotor.{key}: is a shaft builder option")), "{e}");
    }
    let cases = [
        (shaft_config().replace("length = 0.1\n", ""), "linear_rotor.elements[0].length: missing"),
        (shaft_config().replace("mass = 4.0", "mas = 4.0"), "linear_rotor.disks[0].mas: unknown key"),
        (shaft_config().replace("node = 3\nradius", "node = 9\nradius"), "linear_rotor.balancer[0].node: 9 is not a node"),
        (shaft_config().replace("balls = 2", "balls = 2.0"), "linear_rotor.balancer[0].balls: expected a whole number"),
        (shaft_config() + "[planar]\nm1 = 1\n", "planar: unknown table in a linear rotor config"),
        (shaft_config().replace("[linear_rotor]\n", "[linear_rotor]\npolar_inertia = 0.0\n") + "[drive]\nkind = \"torque\"\ntorque = 1.0\n", ""),
        (shaft_config().replace("[linear_rotor]\n", "[linear_rotor]\ndofs = [\"x0\"]\n"), "linear_rotor.dofs: has 1 names, the matrices 28 DOFs"),
    ];
    for (text, want) in cases {
        match load(&parse(&text), &HashMap::new()) {
            Err(e) => assert!(e.to_string().starts_with(want), "{e}"),
            Ok(c) => {
                // a torque drive is read, and refused where a run needs it when the rotor's
                // polar moment is not known (here set to 0 over the builder's)
                assert!(want.is_empty());
                let (d, t) = c.drive.unwrap();
                let s = RunSettings { t_end: t, dt: 0.1, rtol: 1e-8, atol: 1e-9, method: Method::Auto, max_steps: 10, max_wall_s: None, physical_nodes: None };
                let e = simulate(&c.rotor, &d, &s, &autobal::control::Control::none(), |_| true).unwrap_err().to_string();
                assert!(e.starts_with("linear_rotor.polar_inertia: a torque drive"), "{e}");
            }
        }
    }
    // the DOF table in ROSS's order
    let mut t = String::from("[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"M.mtx\"\ndofs = [\"x0\", \"x1\"]\n");
    files.insert("M.mtx".into(), "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 1.0\n".into());
    let e = load(&parse(&t), &files).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.dofs[1]: is \"x1\", ROSS's order has \"y0\" there"), "{e}");
    t = t.replace("\"x1\"", "\"y0\"");
    assert!(load(&parse(&t), &files).is_ok());
}

/// A bearing tabulated over speed: at each speed the field equals the field of the rotor with a
/// constant bearing of the linearly interpolated values (bit for bit: the same sums), inside the
/// table and held outside it; read from the config the same.
#[test]
fn speed_dependent_bearing_interpolates() {
    let base = load(&parse(&shaft_config().replace("[[linear_rotor.bearings]]\nnode = 6\nk = 2e6\nc = 300.0\n", "")), &HashMap::new()).unwrap().rotor;
    let table = SpeedBearing {
        node: 6,
        link: None,
        speeds: vec![100.0, 300.0, 700.0],
        k: vec![[1e6, 0.0, 0.0, 2e6], [2e6, 1e5, -1e5, 3e6], [4e6, 0.0, 0.0, 4e6]],
        c: vec![[100.0, 0.0, 0.0, 100.0], [300.0, 0.0, 0.0, 200.0], [500.0, 0.0, 0.0, 500.0]],
    };
    let mut r = base.clone();
    r.speed_bearings.push(table.clone());
    let n = base.dofs();
    let i = 6 * 4;
    for (w, k, c) in [
        (50.0, [1e6, 0.0, 0.0, 2e6], [100.0, 0.0, 0.0, 100.0]),
        (200.0, [1.5e6, 0.5e5, -0.5e5, 2.5e6], [200.0, 0.0, 0.0, 150.0]),
        (600.0, [3.5e6, 0.25e5, -0.25e5, 3.75e6], [450.0, 0.0, 0.0, 425.0]),
        (900.0, [4e6, 0.0, 0.0, 4e6], [500.0, 0.0, 0.0, 500.0]),
    ] {
        let mut fixed = base.clone();
        for (j, (a, b)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
            fixed.k[(i + a) * n + i + b] += k[j];
            fixed.c[(i + a) * n + i + b] += c[j];
        }
        let (cc, kk) = r.damping_stiffness_at(w);
        for (x, y) in kk.iter().zip(&fixed.k).chain(cc.iter().zip(&fixed.c)) {
            assert!((x - y).abs() <= 1e-9 * y.abs().max(1.0), "Ω = {w}: {x} vs {y}");
        }
        let fa = LinearRotorField::new(&r, w, Frame::Fixed).unwrap();
        let fb = LinearRotorField::new(&r.at_speed(w), w, Frame::Fixed).unwrap();
        let x: Vec<f64> = (0..fa.dim()).map(|j| 1e-5 * ((j * 7 % 13) as f64 - 6.0)).collect();
        let (mut da, mut db) = (vec![0.0; fa.dim()], vec![0.0; fa.dim()]);
        fa.rhs(0.3, &x, &mut da);
        fb.rhs(0.3, &x, &mut db);
        assert_eq!(da, db);
    }
    // from the config: the same table
    let text = shaft_config().replace(
        "node = 6\nk = 2e6\nc = 300.0\n",
        "node = 6\nspeeds = [100.0, 300.0, 700.0]\nkxx = [1e6, 2e6, 4e6]\nkxy = [0.0, 1e5, 0.0]\nkyx = [0.0, -1e5, 0.0]\nkyy = [2e6, 3e6, 4e6]\ncxx = [100.0, 300.0, 500.0]\ncyy = [100.0, 200.0, 500.0]\n",
    );
    let c = load(&parse(&text), &HashMap::new()).unwrap();
    assert_eq!(c.rotor.speed_bearings, vec![table]);
    let e = load(&parse(&text.replace("cyy = [100.0, 200.0, 500.0]", "cyy = [100.0, 200.0]")), &HashMap::new()).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.bearings[1].cyy: has 2 entries, one per speed: 3"), "{e}");
    let e = load(&parse(&text.replace("speeds = [100.0, 300.0, 700.0]", "speeds = [100.0, 300.0, 200.0]")), &HashMap::new()).unwrap_err().to_string();
    // the config's index of the bearing (the second), and the entry (named `bearings[0]`, the
    // first bearing with a table, before round 3)
    assert!(e.starts_with("linear_rotor.bearings[1].speeds[2]: must increase strictly: 200 after 300"), "{e}");
}

/// `∫ Ω dt` of the prescribed drives against the trapezoid sums and closed forms.
#[test]
fn drive_angle_integrates_the_speed() {
    let d = Drive::Acceleration { omega0: 2.0, b: -0.5 };
    assert!((drive_angle(&d, 3.0) - (6.0 - 0.25 * 9.0)).abs() < 1e-14);
    assert!((drive_angle(&d, 10.0) - 4.0).abs() < 1e-14); // stops at t = 4: 2·4 − ¼·16
    let s = Drive::SpeedSchedule { points: vec![(1.0, 10.0), (3.0, 30.0), (4.0, 30.0)] };
    for (t, want) in [(0.5, 5.0), (2.0, 10.0 + 15.0), (3.5, 10.0 + 40.0 + 15.0), (6.0, 10.0 + 40.0 + 30.0 + 60.0)] {
        assert!((drive_angle(&s, t) - want).abs() < 1e-12, "t = {t}");
    }
}

/// A run-up through the critical speed of paper 004's rotor with its race centred: the Jeffcott
/// preset in fixed axes (`Ω(t)`, `Ω̇` in the unbalance force and the balls) against the native
/// planar model (`planar::simulate`, its own equations in turning axes), sample by sample. Both
/// integrate at rtol 1e-10; they agree to 2e-10 of the peak whirl radius (bound 1e-8: the
/// tolerance's scale over a passage through resonance) and the ball angles to 2e-10 rad; a wrong
/// sign of the unbalance's `Ω̇` term misses by 2e-2 of the peak, a ball term without `Ω̇` by 0.17.
#[test]
fn jeffcott_run_up_equals_the_planar_model() {
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    let rotor = LinearRotor::from_planar(&p).unwrap();
    let wn = p.natural_frequency();
    let t_end = 2.0;
    let drive = Drive::Acceleration { omega0: 0.2 * wn, b: 1.6 * wn / t_end };
    let mut settings = Settings::new(&p, t_end);
    settings.dt = t_end / 200.0;
    settings.rtol = 1e-10;
    settings.atol = 1e-12;
    settings.psi0 = vec![0.0, std::f64::consts::PI];
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
    assert!(sum.stopped.is_none());
    assert_eq!(native.len(), ours.len());
    let peak = native.iter().map(|s| s.1.hypot(s.2)).fold(0.0, f64::max);
    assert!(peak > 0.0);
    let mut worst: f64 = 0.0;
    let mut worst_psi: f64 = 0.0;
    for (a, b) in native.iter().zip(&ours) {
        assert!((a.0 - b.0).abs() < 1e-12);
        worst = worst.max((a.1 - b.1).hypot(a.2 - b.2));
        for (x, y) in a.3.iter().zip(&b.3) {
            worst_psi = worst_psi.max((x - y).abs());
        }
    }
    assert!(worst < 1e-8 * peak, "largest difference {worst:e} m, peak {peak:e} m");
    assert!(worst_psi < 1e-8, "ball angles differ by {worst_psi:e} rad");
}

/// The stability over speed of the Jeffcott preset: the same ranges as the general route on
/// the native planar rotor (`rotor_stability`), to the bisection's 1e-9.
#[test]
fn stability_over_speed_equals_the_native_route() {
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    let rotor = LinearRotor::from_planar(&p).unwrap();
    let speeds: Vec<f64> = (1..=40).map(|i| 0.075 * p.natural_frequency() * i as f64).collect();
    let ours = stability_over_speed(&rotor, &speeds).unwrap();
    let native = autobal::rotor_stability::stability_over_speed(&autobal::rotor_stability::Rotor::Planar(p), &speeds).unwrap();
    assert_eq!(ours.model, "linear");
    assert!(!ours.stable_ranges.is_empty());
    assert_eq!(ours.stable_ranges.len(), native.stable_ranges.len());
    for (a, b) in ours.stable_ranges.iter().zip(&native.stable_ranges) {
        assert!((a.from - b.from).abs() <= 1e-8 * b.from, "{} vs {}", a.from, b.from);
        assert!((a.to - b.to).abs() <= 1e-8 * b.to);
    }
}
