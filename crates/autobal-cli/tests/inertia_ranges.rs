//! `autobal inertia` and `autobal ranges` on every config (issue 18 §3): no entry is ignored
//! and no warning says so; the whole rotor's inertia on spatial configs, the exact ranges of
//! `stability`'s own grid where 003's necessary ranges are not defined.

use std::process::Command;

fn bin() -> String {
    std::env::var("AUTOBAL_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_autobal").to_string())
}

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(bin()).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn json(args: &[&str]) -> (serde_json::Value, String) {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{err}");
    (serde_json::from_str(&out).expect("valid JSON"), err)
}

fn examples(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn inertia_of_a_two_plane_rotor_is_its_whole_inertia_without_a_warning() {
    let two = examples("spatial_two_plane.toml");
    let (v, err) = json(&["inertia", "--config", &two, "--format", "json"]);
    assert!(!err.contains("warning"), "{err}");
    assert!(v["inertia"].is_null() && v["anisotropy"].is_null(), "000's composite inertia is not this rotor's");
    let why = v["paper_000_not_applicable"].as_str().unwrap();
    assert!(why.contains("[couple]") && why.contains("[balancer2]") && !why.contains("gravity") && !why.contains("supports"), "{why}");
    let w = &v["whole_rotor"];
    assert_eq!(w["placement"]["placement"], "balanced");
    // rotor 20 kg + two unbalance masses of 10 g + four balls of 20 g
    assert!((w["properties"]["total_mass"].as_f64().unwrap() - 20.1).abs() < 1e-12);
    // the balls cancel static and couple unbalance: the shaft is a principal axis
    assert!(w["properties"]["axis_tilt"].as_f64().unwrap() < 1e-12);
    assert_eq!(w["placement"]["angles"].as_array().unwrap().len(), 4);
    let (code, table, err) = autobal(&["inertia", "--config", &two]);
    assert_eq!(code, 0);
    assert!(err.is_empty(), "{err}");
    assert!(table.contains("whole rotor as the simulation builds it") && table.contains("along the shaft"), "{table}");
}

#[test]
fn inertia_of_a_one_plane_rotor_keeps_paper_000_and_agrees_with_it() {
    for sets in [vec![], vec!["--set", "balancer.balls=4"]] {
        let mut a = vec!["inertia", "--config", "PLACEHOLDER", "--format", "json"];
        let dim = examples("dimensional.toml");
        a[2] = &dim;
        a.extend(sets.iter());
        let (v, err) = json(&a);
        assert!(!err.contains("warning"), "{err}");
        assert!(v["paper_000_not_applicable"].is_null());
        let p = &v["whole_rotor"]["properties"];
        let i = &v["inertia"];
        for (a, b) in [
            (&p["polar_moment"], &i["c_sigma"]),
            (&p["equatorial_moments"][0], &i["a_c1"]),
            (&p["equatorial_moments"][1], &i["a_c2"]),
            (&p["total_mass"], &i["total_mass"]),
        ] {
            let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{sets:?}: {a} vs {b}");
        }
    }
    // gravity and direction-dependent supports: no warning, nothing changes
    let dim = examples("dimensional.toml");
    let (a, _) = json(&["inertia", "--config", &dim, "--format", "json"]);
    let (b, err) =
        json(&["inertia", "--config", &dim, "--format", "json", "--set", "spatial.gravity=[0, -9.81, 0]", "--set", "supports.stiffness_left_y=2.5e6"]);
    assert!(err.is_empty(), "{err}");
    assert_eq!(a["whole_rotor"], b["whole_rotor"]);
    assert_eq!(a["inertia"], b["inertia"]);
}

#[test]
fn inertia_refuses_a_planar_config_in_one_line() {
    let (code, out, err) = autobal(&["inertia", "--config", &examples("planar.toml")]);
    assert_ne!(code, 0);
    assert!(out.is_empty());
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("planar") && err.contains("tilting"), "{err}");
}

/// Where 003's ranges are not defined, `ranges` gives the exact ones on `stability`'s own axis
/// and grid: the same ranges as `stability`'s JSON, to the bit.
#[test]
fn ranges_beyond_paper_003_are_the_exact_ranges_of_stability() {
    for (cfg, feature) in [("spatial_two_plane.toml", "[balancer2]"), ("planar.toml", "[planar]")] {
        let c = examples(cfg);
        let (r, err) = json(&["ranges", "--config", &c, "--format", "json"]);
        assert!(!err.contains("warning"), "{err}");
        assert!(r["autobalancing_ranges"].is_null());
        assert!(r["necessary_not_defined"].as_str().unwrap().contains(feature), "{}", r["necessary_not_defined"]);
        let (s, _) = json(&["stability", "--config", &c, "--format", "json"]);
        assert_eq!(r["exact"]["route"], "general");
        assert_eq!(r["exact"]["stable_ranges"], s["stable_ranges"], "{cfg}");
        assert_eq!(r["exact"]["omega_max"], s["omega_max"], "{cfg}");
        assert!(!r["exact"]["stable_ranges"].as_array().unwrap().is_empty(), "{cfg}: a range to compare");
        let (code, table, _) = autobal(&["ranges", "--config", &c]);
        assert_eq!(code, 0);
        assert!(table.contains("necessary condition, paper 003): not defined for this config") && table.contains("stable:"), "{table}");
    }
}

/// On a one-plane config both: 003's necessary ranges, labelled so, and the exact ones of
/// `stability`'s default route (the 12-state model on its 2000-speed grid), equal to its JSON's.
#[test]
fn ranges_of_a_one_plane_config_keep_003_beside_the_exact_ones() {
    let dim = examples("dimensional.toml");
    let (r, err) = json(&["ranges", "--config", &dim, "--format", "json"]);
    assert!(!err.contains("warning"), "{err}");
    assert!(r["autobalancing_ranges_are"].as_str().unwrap().starts_with("necessary condition (paper 003"));
    assert!(!r["autobalancing_ranges"].as_array().unwrap().is_empty());
    let (s, _) = json(&["stability", "--config", &dim, "--format", "json"]);
    assert_eq!(r["exact"]["stable_ranges"], s["stable_ranges"]);
    assert_eq!(r["exact"]["omega_max"], s["omega_max"]);
    let (_, table, _) = autobal(&["ranges", "--config", &dim]);
    assert!(table.contains("necessary condition for autobalancing (003)") && table.contains("exact stable ranges"), "{table}");
}
