//! `autobal campbell` and `autobal critical` by the general route (issue 18 §3): on any
//! config, no ignored-entries warning, and on a one-plane config equal to the 12-state route.

use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    assert!(!err.contains(" uses the rotor of papers"), "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}\n{out}"))
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn general_critical_speeds_equal_eq_16_on_a_one_plane_config() {
    // examples/spatial.toml (dimensionless, one plane): the general route's locked critical
    // speeds (the stiffness block of the AD Jacobian, bisected to 1e-12) against eq (16)'s roots
    // that the closed-form route prints: equal to 1e-9
    let cfg = example("spatial.toml");
    let c = json(&["critical", "--format", "json", "--config", &cfg]);
    let mut want: Vec<f64> = c["critical_speeds"].as_array().unwrap().iter().map(|s| s["omega"].as_f64().unwrap()).collect();
    want.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let g = json(&["critical", "--route", "general", "--omega-max", "4", "--format", "json", "--config", &cfg]);
    assert_eq!(g["route"], "general");
    let got: Vec<f64> = g["locked_critical_speeds"]["speeds"].as_array().unwrap().iter().map(|s| s["omega"].as_f64().unwrap()).collect();
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (a, b) in got.iter().zip(&want) {
        assert!((a - b).abs() <= 1e-9 * b, "{a} vs eq (16) {b}");
    }
    // the exact ranges beside 003's necessary condition, labelled as such
    assert!(g["exact_stable_ranges"].is_array());
    assert!(g["necessary_condition_003"]["what"].as_str().unwrap().contains("not sufficient"));
    let (_, table, _) = autobal(&["critical", "--route", "general", "--omega-max", "4", "--config", &cfg]);
    assert!(table.contains("necessary, not sufficient"), "{table}");
}

#[test]
fn general_campbell_equals_the_12_state_campbell_on_a_one_plane_config() {
    // the same speeds on both routes; at each, every general-route eigenvalue has a partner
    // among the 12-state model's within 1e-10 (relative to max(1, |λ|))
    let cfg = example("spatial.toml");
    let a = json(&["campbell", "--points", "12", "--omega-max", "3", "--format", "json", "--config", &cfg]);
    let b = json(&["campbell", "--route", "general", "--points", "12", "--omega-max", "3", "--format", "json", "--config", &cfg]);
    assert_eq!(b["route"], "general");
    assert_eq!(b["stationary_state"], "equilibrium");
    let wa: Vec<f64> = a["omega"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let wb: Vec<f64> = b["omega"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(wa.len(), wb.len());
    for (k, (x, y)) in wa.iter().zip(&wb).enumerate() {
        assert!((x - y).abs() <= 1e-15 * x, "speed {k}: {x} vs {y}");
        let theirs: Vec<(f64, f64)> =
            a["lines"].as_array().unwrap().iter().map(|l| (l["modes"][k]["re"].as_f64().unwrap(), l["modes"][k]["im"].as_f64().unwrap())).collect();
        let ours: Vec<(f64, f64)> =
            b["lines"].as_array().unwrap().iter().map(|l| (l["points"][k]["re"].as_f64().unwrap(), l["points"][k]["im"].as_f64().unwrap())).collect();
        assert_eq!(ours.len(), theirs.len());
        for o in &ours {
            let d = theirs.iter().map(|t| (t.0 - o.0).hypot(t.1 - o.1)).fold(f64::INFINITY, f64::min);
            assert!(d <= 1e-10 * o.0.hypot(o.1).max(1.0), "Ω = {x}: {o:?} has no 12-state partner ({d})");
        }
    }
}

#[test]
fn campbell_and_critical_analyse_planar_and_periodic_configs() {
    // the planar rotor: its locked critical speed is sqrt(k/m_total) = 288 1/s (paper 004's
    // rotor is built so), and the Campbell table says it is the general route
    let p = example("planar.toml");
    let c = json(&["critical", "--format", "json", "--config", &p]);
    let w = c["locked_critical_speeds"]["speeds"][0]["omega"].as_f64().unwrap();
    assert!((w - 288.0).abs() < 1e-6 * 288.0, "{w}");
    let (code, out, err) = autobal(&["campbell", "--config", &p]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("general route") && !err.contains("uses the rotor of papers"), "{out}{err}");
    // gravity and y supports: Floquet exponents, their branch said in the output
    let two = example("spatial_two_plane.toml");
    let v = json(&["campbell", "--points", "3", "--omega-max", "1.5", "--format", "json", "--config", &two]);
    assert_eq!(v["stationary_state"], "periodic_orbit");
    assert!(v["branch"].as_str().unwrap().contains("modulo"), "{}", v["branch"]);
    let dir = std::env::temp_dir().join(format!("autobal-gcampbell-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("c.svg");
    let (code, _, err) = autobal(&["campbell", "--points", "4", "--config", &p, "--svg", svg.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let _ = std::fs::remove_dir_all(&dir);
}
