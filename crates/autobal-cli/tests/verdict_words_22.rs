//! Words a user reads as answers (session 22): a stiffness that is not positive semi-definite is
//! named as a static instability, never printed as "0 rad/s" natural frequencies (audit 21's
//! F6); the quick report says its stable ranges are a coarse grid's (review 21: it read one range
//! over an unstable gap narrower than its step); the map CSV's margin column on a dimensional
//! spatial config says it is per τ.

use std::path::{Path, PathBuf};
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

fn tmp(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("verdict_words_22").join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// An isotropic Jeffcott rotor from Matrix Market files: `M = m I`, `K = k I`, `C = c I` on one
/// node `x, y`, three balls of `mb` (rings: `M + 3 mb I` at rest).
fn jeffcott(dir: &Path, m: f64, k: f64, mb: f64) -> String {
    let mtx = |v: f64| format!("%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 {v:e}\n2 2 {v:e}\n");
    std::fs::write(dir.join("M.mtx"), mtx(m)).unwrap();
    std::fs::write(dir.join("K.mtx"), mtx(k)).unwrap();
    std::fs::write(dir.join("C.mtx"), mtx(40.0)).unwrap();
    let cfg = dir.join("jeffcott.toml");
    std::fs::write(
        &cfg,
        format!(
            "[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"K.mtx\"\nc = \"C.mtx\"\n\
             [[linear_rotor.unbalance]]\nnode = 0\nme = 1e-3\n\
             [[linear_rotor.balancer]]\nnode = 0\nradius = 0.05\nballs = 3\nball_mass = {mb:e}\ndrag = 0.01\n"
        ),
    )
    .unwrap();
    cfg.to_str().unwrap().to_string()
}

#[test]
fn an_indefinite_stiffness_is_named_not_printed_as_zero_frequencies() {
    // K = −4e4 I: both modes diverge at rest, ω² = k/(m + 3 mb) exactly (the balls as rings
    // add n mb to each translation), the rate sqrt(−ω²); relative 1e-12: a 2 × 2 problem
    let (m, k, mb) = (10.0, -4e4, 0.1);
    let cfg = jeffcott(&tmp("indefinite"), m, k, mb);
    let w2 = k / (m + 3.0 * mb);
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    let div = v["static_divergence"].as_array().unwrap();
    assert_eq!(div.len(), 2, "{v}");
    for d in div {
        let (l, rate) = (d["omega_squared"].as_f64().unwrap(), d["growth_rate"].as_f64().unwrap());
        assert!((l - w2).abs() <= 1e-12 * w2.abs(), "{d}");
        assert!((rate - (-w2).sqrt()).abs() <= 1e-12 * (-w2).sqrt(), "{d}");
    }
    // no mode is left to have a frequency: none is listed as 0
    assert_eq!(v["natural_frequencies"].as_array().unwrap().len(), 0, "{v}");
    let (code, out, err) = autobal(&["critical", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("statically unstable at rest: 2 mode(s) with ω² < 0, ω² = -3883.5, -3883.5 (rad/s)²"), "{out}");
    assert!(out.contains("the stiffness K is not positive semi-definite") && !out.contains("0 rad/s"), "{out}");
    // stability: the same line before its (empty) frequencies, and the verdict
    let (code, out, err) = autobal(&["stability", "--config", &cfg, "--omega-max", "200 rad/s", "--samples", "10"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("statically unstable at rest: 2 mode(s)") && !out.contains(" 0 rad/s (0 rpm)"), "{out}");
    assert!(out.contains("stable: nowhere"), "{out}");
    let v = json(&["stability", "--config", &cfg, "--omega-max", "200 rad/s", "--samples", "10", "--format", "json"]);
    assert_eq!(v["static_divergence"].as_array().unwrap().len(), 2, "{v}");
}

#[test]
fn a_free_rotor_still_has_zero_frequencies_and_no_divergence() {
    // K = 0: two rigid-body modes, ω = 0 as before (positive semi-definite), nothing divergent
    let cfg = jeffcott(&tmp("free"), 10.0, 0.0, 0.1);
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["static_divergence"].as_array().unwrap().len(), 0, "{v}");
    assert_eq!(v["natural_frequencies"], serde_json::json!([0.0, 0.0]), "{v}");
    let (code, out, err) = autobal(&["critical", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("1. 0 rad/s (0 rpm)") && !out.contains("statically unstable"), "{out}");
}

#[test]
fn the_quick_report_says_its_ranges_are_a_coarse_grids() {
    // review 21's case: the shaft example with me = 5e-3 (balls short of the unbalance) and an
    // operating speed of 700 rpm. `stability` on 200 speeds finds an unstable gap (386-411 rad/s)
    // narrower than the quick report's grid step (2543/60 = 42.4 rad/s), which reads one range
    // from the axis' start to its end: the quick report must say its ranges are that grid's
    let dir = tmp("quick");
    let text = std::fs::read_to_string(example("linear_rotor_shaft.toml")).unwrap();
    assert!(text.contains("\nme = 2e-4\n"));
    let text = text.replace("\nme = 2e-4\n", "\nme = 5e-3\n").replace("# operating_speed = \"6000 rpm\"", "operating_speed = \"700 rpm\"\n#");
    let cfg = dir.join("shaft.toml");
    std::fs::write(&cfg, text).unwrap();
    let cfg = cfg.to_str().unwrap();
    let v = json(&["stability", "--config", cfg, "--samples", "200", "--format", "json"]);
    let omega_max = v["omega_max"].as_f64().unwrap();
    let ranges = v["stable_ranges"].as_array().unwrap();
    let gaps: Vec<f64> = ranges.windows(2).map(|p| p[1]["from"].as_f64().unwrap() - p[0]["to"].as_f64().unwrap()).collect();
    assert!(gaps.iter().any(|g| *g > 0.0 && *g < omega_max / 60.0), "a gap narrower than the quick step: {ranges:?}");
    let out = dir.join("r");
    let (code, _, err) = autobal(&["report", "--config", cfg, "--set", "drive.t_end=0.5", "--quick", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    let step = format!("{} rad/s", (omega_max / 60.0 * 100.0).round() / 100.0);
    // the summary's ranges line and the stability section, each with the grid's step
    let caveat = format!("(quick report: a grid of 60 speeds {step}");
    assert!(page.matches(&caveat).count() >= 2, "the summary's verdict and ranges lines: {caveat}");
    assert!(page.contains(&format!("The ranges are on a grid of 60 speeds {step}")), "the section");
    assert!(page.contains("an unstable gap narrower than that between two stable grid speeds can go unseen"), "the section");
}

#[test]
fn the_map_csv_names_the_margin_per_tau_on_a_dimensional_spatial_config() {
    // examples/dimensional.toml (SI, two balls: no family, one state): the map's margin is per
    // τ = ω0 t; `stability` prints 1/s. One cell at the config's balancer.z and 900 rpm against
    // stability's `max_real_part_si` there: per τ × ω0 is 1/s (relative 1e-9: the two runs
    // solve the same eigenproblem at one speed given in rpm, up to the rounding of the speed
    // conversions)
    let dir = tmp("map");
    let cfg = example("dimensional.toml");
    let w0 = json(&["critical", "--config", &cfg, "--format", "json"])["model"]["scale"]["omega0"].as_f64().unwrap();
    let stem = dir.join("m");
    let (code, _, err) = autobal(&["map", "--config", &cfg, "--x", "balancer.z=0.45:0.48:2", "--y", "speed_rpm=900:1000:2", "--out", stem.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(stem.with_extension("csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("balancer.z,speed_rpm,max_real_part_per_tau,stable,necessary"));
    let first: Vec<f64> = lines.next().unwrap().split(',').map(|s| s.parse().unwrap()).collect();
    assert_eq!((first[0], first[1]), (0.45, 900.0));
    let v = json(&["stability", "--config", &cfg, "--omega-max", "900 rpm", "--samples", "10", "--format", "json"]);
    let last = v["max_real_part_si"].as_array().unwrap().last().unwrap().clone();
    let (rpm, per_s) = (last[0].as_f64().unwrap(), last[1].as_f64().unwrap());
    assert!((rpm - 900.0).abs() < 1e-9, "{last}");
    assert!((first[2] * w0 - per_s).abs() <= 1e-9 * per_s.abs(), "{} per τ × ω0 {w0} vs {per_s} 1/s", first[2]);
    // the general route's CSV says the same
    let (code, _, err) = autobal(&[
        "map",
        "--config",
        &cfg,
        "--route",
        "general",
        "--x",
        "balancer.z=0.45:0.48:2",
        "--y",
        "speed_rpm=900:1000:2",
        "--out",
        stem.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(stem.with_extension("csv")).unwrap();
    assert!(csv.starts_with("balancer.z,speed_rpm,max_real_part_per_tau,verdict,"), "{csv}");
}
