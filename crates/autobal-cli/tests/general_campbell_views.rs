//! `autobal campbell` by the general route with what the 12-state route has (issue 18 §8):
//! `--balls locked`, `--view components`, and the crossings with `h×Ω` (critical speeds), on a
//! one-plane config equal to the 12-state route's, and said to be undefined for Floquet exponents.

use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}\n{out}"))
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn forward_1x(v: &serde_json::Value) -> Vec<f64> {
    let mut w: Vec<f64> = v["critical_speeds"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|k| k["whirl"] == "forward" && k["harmonic"] == 1)
        .map(|k| k["omega"].as_f64().unwrap())
        .collect();
    w.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * b.abs());
    w
}

#[test]
fn locked_crossings_of_the_general_route_are_the_12_state_routes_and_eq_16() {
    // examples/spatial.toml undamped, balls locked: both routes' forward 1x crossings on the
    // same 400 speeds are the roots of 000 eq (16) that `autobal critical` prints; the general
    // route's to 1e-9 relative (bisected to 1e-13 on the spectrum of the same 8 x 8 linear
    // model), and equal to the 12-state route's to the 12-state route's own accuracy
    // (tests/campbell.rs: 1e-6)
    let cfg = example("spatial.toml");
    let set = ["--set", "dimensionless.h_x=0"];
    let c = json(&["critical", "--format", "json", "--config", &cfg, set[0], set[1]]);
    let mut want: Vec<f64> = c["critical_speeds"].as_array().unwrap().iter().map(|s| s["omega"].as_f64().unwrap()).collect();
    want.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * b.abs());
    let base = ["campbell", "--balls", "locked", "--format", "json", "--points", "400", "--omega-max", "3", "--config", &cfg, set[0], set[1]];
    let a = json(&base);
    let mut g = base.to_vec();
    g.extend(["--route", "general"]);
    let b = json(&g);
    assert_eq!(b["route"], "general");
    assert_eq!(b["balls"], "locked");
    assert_eq!(b["fixed_axes_modes"].as_array().unwrap().len(), 4, "8 states, 4 modes");
    let (theirs, ours) = (forward_1x(&a), forward_1x(&b));
    let want: Vec<f64> = want.into_iter().filter(|w| *w < 3.0).collect();
    assert!(!want.is_empty());
    assert_eq!(ours.len(), want.len(), "general {ours:?} vs eq (16) {want:?}");
    assert_eq!(theirs.len(), want.len(), "12-state {theirs:?} vs eq (16) {want:?}");
    for ((o, t), w) in ours.iter().zip(&theirs).zip(&want) {
        assert!((o - w).abs() <= 1e-9 * w, "general {o} vs eq (16) {w}");
        assert!((o - t).abs() <= 1e-6, "general {o} vs 12-state {t}");
    }
    // the 8 eigenvalues at each speed are the 12-state route's locked ones (1e-10 relative)
    for k in [0, 133, 399] {
        for l in b["lines"].as_array().unwrap() {
            let (re, im) = (l["points"][k]["re"].as_f64().unwrap(), l["points"][k]["im"].as_f64().unwrap());
            let d = a["lines"]
                .as_array()
                .unwrap()
                .iter()
                .map(|m| (m["modes"][k]["re"].as_f64().unwrap() - re).hypot(m["modes"][k]["im"].as_f64().unwrap() - im))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 1e-10 * re.hypot(im).max(1.0), "speed {k}: ({re}, {im}) has no 12-state partner ({d})");
        }
    }
}

#[test]
fn components_view_and_harmonics_on_the_general_route() {
    let dir = std::env::temp_dir().join(format!("autobal-gviews-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("c");
    // the planar rotor: both figures of the components view, a mode's group in the table, the
    // crossings of 1x and 2x listed
    let p = example("planar.toml");
    let (code, out, err) =
        autobal(&["campbell", "--points", "60", "--config", &p, "--view", "components", "--harmonics", "1,2", "--svg", prefix.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    for s in ["rotating", "fixed"] {
        let svg = std::fs::read_to_string(dir.join(format!("c_{s}.svg"))).unwrap();
        assert!(svg.contains("<svg") && svg.contains("mode 1:"), "{s}");
    }
    assert!(out.contains("group") && out.contains("translation"), "{out}");
    assert!(out.contains("crosses 1×, 2×"), "{out}");
    let v = json(&["campbell", "--points", "60", "--config", &p, "--harmonics", "1,2", "--format", "json"]);
    assert_eq!(v["harmonics"], serde_json::json!([1, 2]));
    assert!(v["critical_speeds"].is_array(), "{}", v["critical_speeds"]);
    assert!(v["fixed_axes_modes"][0]["points"][0]["frequency_hz"].is_f64());
    // locked balls on the planar rotor: the Jeffcott rotor of mass m_total, whose forward 1x
    // crossing is near sqrt(k/m_total) = 288 rad/s (damped: the crossing of a damped mode, within 1 %)
    let l = json(&["campbell", "--points", "60", "--config", &p, "--balls", "locked", "--format", "json"]);
    let w = forward_1x(&l);
    assert!(w.iter().any(|w| (w - 288.0).abs() < 0.01 * 288.0), "{w:?}");
    // gravity and supports that differ by direction: Floquet exponents, no crossing speeds but
    // the reason; the fixed view is drawn
    let two = example("spatial_two_plane.toml");
    let v = json(&["campbell", "--points", "4", "--omega-max", "1.5", "--format", "json", "--config", &two, "--svg", prefix.to_str().unwrap()]);
    assert_eq!(v["stationary_state"], "periodic_orbit");
    assert!(v["critical_speeds"].is_null());
    assert!(v["critical_speeds_not_given"].as_str().unwrap().contains("modulo 2π/T"), "{v}");
    assert!(std::fs::read_to_string(dir.join("c.svg")).unwrap().contains("<svg"));
    let _ = std::fs::remove_dir_all(&dir);
}
