//! `autobal campbell` in fixed axes (issue 21 item 5): the default figure (one curve per mode,
//! PREFIX.svg), the components view, the critical speeds in the JSON and the table.

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

#[test]
fn locked_undamped_critical_speeds_are_those_of_critical() {
    // the default rotor undamped with the balls locked: its forward 1x crossings are the roots
    // of 000 eq (16) that `autobal critical` prints (located by bisection, to 1e-6)
    let set = ["--set", "dimensionless.h_x=0"];
    let c = json(&["critical", "--format", "json", set[0], set[1]]);
    let mut want: Vec<f64> = c["critical_speeds"].as_array().unwrap().iter().map(|s| s["omega"].as_f64().unwrap()).collect();
    want.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let v = json(&["campbell", "--balls", "locked", "--format", "json", "--points", "400", set[0], set[1]]);
    let modes = v["fixed_axes_modes"].as_array().unwrap();
    assert_eq!(modes.len(), 4, "8 states, 4 modes");
    for m in modes {
        let p = &m["points"][0];
        assert!(p["fixed_frequency"].is_f64() && p["whirl"].is_string() && p.get("log_decrement").is_some(), "{p}");
    }
    let got: Vec<f64> = v["critical_speeds"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|k| k["whirl"] == "forward" && k["harmonic"] == 1)
        .map(|k| k["omega"].as_f64().unwrap())
        .collect();
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (a, b) in got.iter().zip(&want) {
        assert!((a - b).abs() < 1e-6, "{a} vs eq (16) {b}");
    }
}

#[test]
fn the_default_figure_is_one_file_and_components_the_two_files() {
    let dir = std::env::temp_dir().join(format!("autobal-cb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("cb");
    let p = prefix.to_str().unwrap();
    let (code, out, err) = autobal(&["campbell", "--points", "60", "--harmonics", "1,2", "--svg", p]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("critical speeds (a mode's natural frequency in fixed axes crosses 1×, 2×)"), "{out}");
    assert!(out.contains("modes in fixed axes"), "{out}");
    let svg = std::fs::read_to_string(dir.join("cb.svg")).unwrap();
    for s in ["mode 1:", "1× (excitation)", "2× (excitation)", "critical 1:", "log dec", "natural frequency / ω0"] {
        assert!(svg.contains(s), "cb.svg lacks {s}");
    }
    assert!(!dir.join("cb_fixed.svg").exists());
    let (code, _, err) = autobal(&["campbell", "--points", "60", "--view", "components", "--svg", p]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.join("cb_fixed.svg").exists() && dir.join("cb_rotating.svg").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_dimensional_rotor_is_drawn_in_rpm_and_hz() {
    let dir = std::env::temp_dir().join(format!("autobal-cb-dim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = example("dimensional.toml");
    let prefix = dir.join("dim");
    let v = json(&["campbell", "--config", &cfg, "--format", "json", "--points", "80", "--svg", prefix.to_str().unwrap()]);
    let svg = std::fs::read_to_string(dir.join("dim.svg")).unwrap();
    assert!(svg.contains("rotor speed n (rpm)") && svg.contains("natural frequency (Hz)"));
    let ks = v["critical_speeds"].as_array().unwrap();
    assert!(!ks.is_empty());
    for k in ks {
        // the SI speed is Ω ω0 · 30/π, the frequency h Ω in Hz
        let (w, rpm, hz) = (k["omega"].as_f64().unwrap(), k["omega_rpm"].as_f64().unwrap(), k["frequency_hz"].as_f64().unwrap());
        assert!((rpm / 60.0 - hz / k["harmonic"].as_f64().unwrap()).abs() < 1e-9 * rpm, "{k}");
        assert!(w > 0.0 && k["mode"].as_u64().unwrap() >= 1);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_harmonics_name_the_flag() {
    for h in ["0", "21", "x"] {
        let (code, _, err) = autobal(&["campbell", "--points", "5", "--harmonics", h]);
        assert_ne!(code, 0);
        assert!(err.contains("--harmonics"), "{h}: {err}");
    }
}
