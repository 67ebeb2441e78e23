//! Review 34's D3, D5, D6 and D8c: `critical` words its exact stable ranges as `stability` does
//! (the states each covers, the family of balanced states, the member named, the family's own
//! ranges), `campbell` names the family and the member its values are of, the planar partially
//! balanced placement is said on the side of the unbalance where the balls are, and the
//! family's free parameters over two planes read as their sum.

mod common;
use common::{json, text};
use serde_json::Value;

/// A config written to a file of the test's own (`name` unique per test).
fn config(name: &str, body: &str) -> String {
    let dir = std::env::temp_dir().join(format!("autobal-critical-words-34-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, body).unwrap();
    path.to_string_lossy().into_owned()
}

/// Review 34's j2/j3/j4.toml: paper 004's rotor with its race centred (a Jeffcott rotor) and
/// `n` balls.
fn jeffcott(n: usize) -> String {
    format!(
        "[planar]\nm1 = 1.0\nm2 = 0.2\nm3 = 0.03\nn = {n}\ns1 = 0.003\ns2 = 0.0\ngamma = 0.0\nr = 0.06\nk = 104509.44\nc = 50.0\nc_psi = 0.1\nc_theta = 0.0\ni_g = 0.0025\n"
    )
}

/// Review 34's cp.toml: a rigid rotor on supports of different stiffness, a pure couple
/// unbalance, a balancer plane at each end (`balls` balls each), no gravity.
fn couple(balls: usize) -> String {
    format!(
        "[rotor]\nmass = 20.0\nequatorial_moment = 0.60\npolar_moment = 0.15\nz = 0.25\n\n[supports]\nz_left = 0.0\nz_right = 0.50\nstiffness_left = 2.0e6\nstiffness_right = 3.0e6\ndamping_left = 300.0\ndamping_right = 300.0\n\n[unbalance]\nmass = 0.010\nradius = 0.10\nangle = 0.0\n\n[couple]\nmass = 0.010\nradius = 0.10\nangle = 3.141592653589793\nz = 0.05\n\n[balancer]\nz = 0.45\nballs = {balls}\nball_mass = 0.0045\nrace_radius = 0.12\ndrag = 0.5\n\n[balancer2]\nz = 0.05\nballs = {balls}\nball_mass = 0.0045\nrace_radius = 0.12\ndrag = 0.5\n\n[analysis]\nanisotropy = \"exact\"\n"
    )
}

/// The states of `stability`'s JSON points in `[from, to]` that are stable, in order, each once
/// in a row: the states a range covers, read from `stability`'s own points.
fn states_in(st: &Value, from: f64, to: f64) -> Vec<String> {
    let mut k: Vec<String> = st["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| {
            let w = p["omega"].as_f64().unwrap();
            w >= from && w <= to && p["abscissa"].as_f64().is_some_and(|a| a < 0.0)
        })
        .filter_map(|p| p["state"].as_str().map(str::to_string))
        .collect();
    k.dedup();
    k
}

/// `critical`'s exact stable ranges are `stability`'s, each with the states `stability`'s
/// points have there; the table's range lines are `stability`'s range lines.
fn assert_ranges_as_stability(args: &[&str]) {
    // the command first, then the config's arguments, then the rest
    let with = |extra: &[&'static str]| extra[..1].iter().copied().chain(args.iter().copied()).chain(extra[1..].iter().copied()).collect::<Vec<&str>>();
    let c = json(&with(&["critical", "--format", "json"]));
    let s = json(&with(&["stability", "--format", "json"]));
    let (cr, sr) = (c["exact_stable_ranges"].as_array().unwrap(), s["stable_ranges"].as_array().unwrap());
    assert_eq!(cr.len(), sr.len(), "{cr:?} vs {sr:?}");
    assert!(!cr.is_empty());
    for (a, b) in cr.iter().zip(sr) {
        assert_eq!((&a["from"], &a["to"]), (&b["from"], &b["to"]));
        let want = states_in(&s, b["from"].as_f64().unwrap(), b["to"].as_f64().unwrap());
        let got: Vec<String> = a["states"].as_array().unwrap_or_else(|| panic!("no states in {a}")).iter().map(|k| k.as_str().unwrap().to_string()).collect();
        assert_eq!(got, want, "{a}");
        // the key and its names are `stability`'s
        assert_eq!(b["states"], a["states"]);
    }
    // each range line of `stability`'s table, as `critical` prints it
    let ct = text(&with(&["critical"]));
    let st = text(&with(&["stability"]));
    let lines: Vec<&str> = st.lines().filter(|l| l.contains(" to ") && (l.starts_with("stable") || l.contains(", stable:"))).collect();
    assert_eq!(lines.len(), sr.len(), "{st}");
    for l in lines {
        assert!(ct.lines().any(|c| c.trim() == l), "critical lacks `{l}`:\n{ct}");
    }
}

#[test]
fn critical_words_a_range_of_states_that_add_to_the_unbalance_as_stability_does() {
    // review 34's D3: both planes' balls 91 % of their share; main printed "stable: 21.8842
    // rad/s ... to 425.707 rad/s" bare where `stability` says "not balanced, stable" (the balls
    // add to the unbalance)
    let cfg = config("cp.toml", &couple(2));
    let args = ["--config", cfg.as_str(), "--set", "balancer.ball_mass=0.0041", "--set", "balancer2.ball_mass=0.0041"];
    // the command first, then the config's arguments, then the rest
    let with = |extra: &[&'static str]| extra[..1].iter().copied().chain(args.iter().copied()).chain(extra[1..].iter().copied()).collect::<Vec<&str>>();
    let t = text(&with(&["critical"]));
    assert!(t.contains("  not balanced, stable: "), "{t}");
    assert!(!t.lines().any(|l| l.starts_with("  stable:")), "a bare \"stable\" range: {t}");
    let v = json(&with(&["critical", "--format", "json"]));
    assert_eq!(v["exact_stable_ranges"][0]["states"], serde_json::json!(["not_balanced"]), "{}", v["exact_stable_ranges"]);
    assert_ranges_as_stability(&args);
}

#[test]
fn critical_words_the_planar_partial_range_as_stability_does() {
    // review 34's D3 on the planar rotor: capacity 2.94e-3 kg m against 3e-3; main printed
    // "stable: 8.67796 ... to 867.796" where `stability` says "not balanced then partially
    // balanced, stable"
    let cfg = config("j2.toml", &jeffcott(2));
    let args = ["--config", cfg.as_str(), "--set", "planar.m3=0.0245"];
    let t = text(&["critical", "--config", &cfg, "--set", "planar.m3=0.0245"]);
    assert!(t.contains("  not balanced then partially balanced, stable: "), "{t}");
    assert_ranges_as_stability(&args);
}

#[test]
fn critical_names_the_family_its_member_and_the_familys_ranges_as_stability_does() {
    // review 34's D3 on a family (three balls): main printed the closed-form member's range as
    // "the balanced state", without the member or the ranges over the members
    let cfg = config("j3.toml", &jeffcott(3));
    let c = json(&["critical", "--config", &cfg, "--format", "json"]);
    let s = json(&["stability", "--config", &cfg, "--format", "json"]);
    assert_eq!(c["family_dimension"], 1);
    assert_eq!(c["member_psi"], s["member_psi"]);
    // the family's ranges over the members: stability's, the same computation
    assert!(s["family"]["all_members_stable"].as_array().is_some_and(|a| !a.is_empty()), "{}", s["family"]);
    assert_eq!(c["family"]["all_members_stable"], s["family"]["all_members_stable"], "{}", c["family"]);
    assert_eq!(c["family"]["some_members_stable"], s["family"]["some_members_stable"]);
    assert_eq!(c["family"]["parameterisation"], s["family"]["parameterisation"]);
    assert_ranges_as_stability(&["--config", &cfg]);
    // the family's lines of `stability`'s table, word for word
    let ct = text(&["critical", "--config", &cfg]);
    let st = text(&["stability", "--config", &cfg]);
    let family: Vec<&str> = st.lines().filter(|l| l.starts_with("family") || l.starts_with("the balanced states form a family")).collect();
    assert_eq!(family.len(), 3, "{st}");
    for l in family {
        assert!(ct.lines().any(|c| c.trim() == l), "critical lacks `{l}`:\n{ct}");
    }
    assert!(ct.contains("  stable (the one member per speed reached from the closed form): "), "{ct}");
}

#[test]
fn campbell_names_the_family_and_the_member_its_values_are_of() {
    // review 34's D5: `campbell` on three balls named neither the family nor the member
    let cfg = config("j3c.toml", &jeffcott(3));
    let v = json(&["campbell", "--config", &cfg, "--format", "json"]);
    let s = json(&["stability", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["family_dimension"], 1, "{}", v["family_dimension"]);
    // the closed-form member (race centred: the same at every speed), as `stability` names it
    let (a, b) = (v["member_psi"].as_array().unwrap(), s["member_psi"].as_array().unwrap());
    assert_eq!(a.len(), 3);
    for (x, y) in a.iter().zip(b) {
        assert!((x.as_f64().unwrap() - y.as_f64().unwrap()).abs() < 1e-9, "{a:?} vs {b:?}");
    }
    let t = text(&["campbell", "--config", &cfg]);
    let line = t.lines().find(|l| l.starts_with("the balanced states form a family of dimension 1")).unwrap_or_else(|| panic!("no family line:\n{t}"));
    assert!(line.contains("the member reached from the closed form") && line.contains("ball angles"), "{line}");
}

#[test]
fn the_planar_partial_placement_is_said_on_the_side_the_balls_are() {
    // review 34's D6: the balls locked at 359.98° (the planar ψ is measured from the disk's
    // mass centre: on the unbalance) were said "bunched against the unbalance"
    let cfg = config("j2p.toml", &jeffcott(2));
    let t = text(&["critical", "--config", &cfg, "--set", "planar.m3=0.0245"]);
    let line = t.lines().find(|l| l.trim_start().starts_with("balls locked at")).unwrap_or_else(|| panic!("{t}"));
    let v = json(&["critical", "--config", &cfg, "--set", "planar.m3=0.0245", "--format", "json"]);
    let angles: Vec<f64> = v["locked_critical_speeds"]["ball_angles"].as_array().unwrap().iter().map(|a| a.as_f64().unwrap()).collect();
    // the unbalance m1 s1 is at ψ = 0 (race centred): the balls printed are on its side
    assert!(angles.iter().all(|a| a.cos() > 0.99), "{angles:?}");
    assert!(line.contains("on the unbalance's side") && !line.contains("against the unbalance"), "{line}");
}

#[test]
fn two_planes_of_three_balls_count_their_free_parameters_per_plane() {
    // review 34's D8c: "(n − 2 = 2 free parameters)" for two planes of three balls, where each
    // plane has n − 2 = 1
    let cfg = config("cp3.toml", &couple(3));
    let v = json(&["stability", "--config", &cfg, "--samples", "10", "--omega-max", "900", "--format", "json"]);
    assert_eq!(v["family_dimension"], 2, "{}", v["family_dimension"]);
    let p = v["family"]["parameterisation"].as_str().unwrap();
    assert!(p.starts_with("2-parameter family (Σ (n − 2) over the ball planes = 2 free parameters)"), "{p}");
}
