//! `autobal campbell` by the general route says what it knows (issue 18, session 18): the JSON
//! and the table of a periodic case whose Floquet multipliers fall below the monodromy's
//! round-off give bounds, not numbers; a rotor whose balls' capacity falls short follows the
//! partially balanced state and says so. The physics is checked in
//! crates/autobal/tests/rotor_campbell_18.rs; here what a user reads.

use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// examples/planar.toml with its race centred, the balls' mass `m3` and `extra` lines in
/// `[planar]`, written to a temporary file.
fn planar(name: &str, m3: &str, extra: &str) -> String {
    let text = std::fs::read_to_string(format!("{}/../../examples/planar.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let mut text = text.replace("s2 = 0.0005", "s2 = 0.0").replace("m3 = 0.03 ", &format!("m3 = {m3} "));
    if !extra.is_empty() {
        // supports per direction: k_x and k_y in place of k
        text = text.replace("k = 104509.44 ", &format!("k_x = 104509.44\n{extra} "));
    }
    let path = std::env::temp_dir().join(format!("autobal-campbell18-{name}-{}.toml", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn multipliers_below_round_off_are_printed_as_bounds() {
    // k_y = k (1 + 1e-7): periodic for the pipeline. Session 17's case: at 36.08 rad/s the
    // exponent of a multiplier e^{−955.8 T} ~ 1e-45 was printed as −428.8. Now: every point
    // with `decay_at_least` has `re` and `log_decrement` null (lines and fixed-axes view), the
    // JSON says why, the table prints σ as a bound; and there are such points at these speeds
    // (the ball-drag modes, |e^{λT}| < 1e-40 against δ ~ 1e-8). Fails on main (no bound).
    let cfg = planar("aniso", "0.03", "k_y = 104509.450450944");
    let (code, out, err) = autobal(&["campbell", "--config", &cfg, "--omega-max", "108.24", "--points", "3", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["stationary_state"], "periodic_orbit");
    let pts: Vec<&serde_json::Value> = v["lines"].as_array().unwrap().iter().flat_map(|l| l["points"].as_array().unwrap()).filter(|p| !p.is_null()).collect();
    let bounded: Vec<_> = pts.iter().filter(|p| p.get("decay_at_least").is_some()).collect();
    assert!(!bounded.is_empty(), "no bound at 18, 54 and 90 rad/s");
    for p in &bounded {
        assert!(p["re"].is_null() && p["log_decrement"].is_null(), "{p}");
        assert!(p["decay_at_least"].as_f64().unwrap() > 0.0, "{p}");
    }
    assert!(pts.iter().filter(|p| p.get("decay_at_least").is_none()).all(|p| p["re"].is_number()));
    assert!(v["undetermined"].as_str().unwrap().contains("decays at least that fast"));
    for m in v["fixed_axes_modes"].as_array().unwrap() {
        for p in m["points"].as_array().unwrap() {
            assert_eq!(p["re"].is_null(), p.get("decay_at_least").is_some(), "{p}");
        }
    }
    let (code, table, err) = autobal(&["campbell", "--config", &cfg, "--omega-max", "108.24", "--points", "3"]);
    assert_eq!(code, 0, "{err}");
    assert!(table.contains("σ < −r: a Floquet multiplier below the monodromy's round-off") && table.contains(" < −"), "{table}");
    std::fs::remove_file(&cfg).ok();
}

#[test]
fn a_capacity_short_rotor_follows_the_partially_balanced_state() {
    // Two 20 g balls: capacity 0.0024 kg m < the unbalance 0.003 kg m. Main: "no balanced
    // state to lock the balls in" at every speed. Now every speed has a state, `state` names
    // it as `stability` does (partially balanced above the critical speed), and the JSON and
    // the table say which state is followed.
    let cfg = planar("short", "0.02", "");
    let (code, out, err) = autobal(&["campbell", "--config", &cfg, "--points", "30", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["failures"].as_array().unwrap().iter().all(|f| f.is_null()), "{}", v["failures"]);
    let states: Vec<&str> = v["state"].as_array().unwrap().iter().map(|s| s.as_str().unwrap()).collect();
    assert!(states.iter().all(|s| matches!(*s, "partially_balanced" | "not_balanced")), "{states:?}");
    assert!(states.iter().filter(|s| **s == "partially_balanced").count() >= 15, "{states:?}");
    assert!(v["state_followed"].as_str().unwrap().contains("no balanced state exists"));
    let st: serde_json::Value = {
        let (code, out, err) = autobal(&["stability", "--config", &cfg, "--format", "json"]);
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&out).unwrap()
    };
    assert!(st["points"].as_array().unwrap().iter().any(|p| p["state"] == "partially_balanced"));
    let (code, table, err) = autobal(&["campbell", "--config", &cfg, "--points", "30"]);
    assert_eq!(code, 0, "{err}");
    assert!(table.contains("state: the balls' capacity falls short of the unbalance") && !table.contains("lock the balls"), "{table}");
    std::fs::remove_file(&cfg).ok();
}
