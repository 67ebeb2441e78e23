//! Review 29's findings on `autobal critical` (the general route): the critical speeds where
//! the balls cannot balance (they read "none"), "stable: nowhere" where no stationary state was
//! found, the verdict at the operating speed first, the family note for two balls, and one
//! speed listed twice.

mod common;
use common::{examples as example, json, text};

/// A config written to a file of the test's own (`name` unique per test).
fn config(name: &str, body: &str) -> String {
    let dir = std::env::temp_dir().join(format!("autobal-critical-29-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, body).unwrap();
    path.to_string_lossy().into_owned()
}

/// The washing machine example with gravity across its axis (review 29's w.toml).
fn washer_with_gravity(name: &str) -> String {
    let text = std::fs::read_to_string(example("washing_machine.toml")).unwrap();
    config(name, &format!("{text}\n[spatial]\ngravity = [0.0, -9.81, 0.0]\n"))
}

/// Review 29's j.toml: a Jeffcott rotor (planar, race centred), two balls.
const JEFFCOTT: &str = "[planar]\nm1 = 2.0\nm2 = 0.1\nm3 = 0.02\nn = 2\ns1 = 0.0005\ns2 = 0.0\ngamma = 0.0\nr = 0.05\nk = 2.0e4\nc = 10.0\nc_psi = 1.0e-4\nc_theta = 0.0\ni_g = 0.01\n";

fn speeds(v: &serde_json::Value) -> Vec<f64> {
    v["locked_critical_speeds"]["speeds"].as_array().unwrap_or_else(|| panic!("{v}")).iter().map(|s| s["omega"].as_f64().unwrap()).collect()
}

#[test]
fn critical_gives_the_jeffcott_speed_where_the_balls_cannot_balance() {
    // 2 balls of 8 g at 5 cm (capacity 0.8 g m) against 2 kg at 0.5 mm (1 g m): no balanced
    // state at any speed. Main at 0166ba1 printed "none up to 291.661 rad/s" (no speed was
    // searched); the locked rotor's critical speed is sqrt(k/m0), m0 = m1 + m2 + n m3, whatever
    // the balls' placement (they join the rotor's mass)
    let cfg = config("j.toml", JEFFCOTT);
    let v = json(&["critical", "--config", &cfg, "--set", "planar.m3=0.008", "--format", "json"]);
    let want = (2.0e4f64 / (2.0 + 0.1 + 2.0 * 0.008)).sqrt();
    let got = speeds(&v);
    assert_eq!(got.len(), 1, "{v}");
    assert!((got[0] - want).abs() <= 1e-9 * want, "{} vs sqrt(k/m0) {want}", got[0]);
    let l = &v["locked_critical_speeds"];
    assert_eq!(l["speeds"][0]["multiplicity"], 2);
    assert_eq!(l["speeds_locked_partially_balanced"], l["grid"], "{l}");
    assert_eq!(l["speeds_not_searched"], 0);
    let t = text(&["critical", "--config", &cfg, "--set", "planar.m3=0.008"]);
    assert!(!t.contains("none up to") && !t.contains("were not searched"), "{t}");
    assert!(t.contains("partially balanced placement"), "{t}");
}

#[test]
fn critical_gives_the_washers_speeds_where_the_balls_cannot_balance() {
    // the washer with gravity and 3 balls of 50 g (capacity 0.0375 kg m against 0.066): main
    // printed "none up to 283.851 rad/s"; paper 000's eq (16) on the same washer without
    // gravity (the closed-form route; gravity does not enter the locked rotor's stiffness)
    // gives the four speeds, with the locked balls' inertia as its exact anisotropy
    let cfg = washer_with_gravity("w005.toml");
    let v = json(&["critical", "--config", &cfg, "--set", "balancer.ball_mass=0.05", "--format", "json"]);
    let got = speeds(&v);
    let closed = json(&["critical", "--config", &example("washing_machine.toml"), "--set", "balancer.ball_mass=0.05", "--format", "json"]);
    let want: Vec<f64> = closed["critical_speeds"].as_array().unwrap().iter().map(|s| s["omega_rad_s"].as_f64().unwrap()).collect();
    assert_eq!(got.len(), want.len(), "{got:?} vs eq (16) {want:?}");
    for (a, b) in got.iter().zip(&want) {
        assert!((a - b).abs() <= 5e-4 * b, "{a} vs eq (16) {b}");
    }
}

/// The line of `stability`'s table on the ranges (the one after its header lines) that
/// `critical` must repeat: "no verdict: ...", "stable: nowhere ..." or the first range.
fn ranges_line(t: &str) -> String {
    let keys = ["no verdict: no stationary state was found", "stable: nowhere", "stable:"];
    keys.iter().find_map(|k| t.lines().map(str::trim).find(|l| l.starts_with(k))).unwrap_or_else(|| panic!("no ranges line in\n{t}")).to_string()
}

#[test]
fn critical_words_the_stability_ranges_as_stability_does() {
    // the washer with gravity and balls of 0.3 kg (one ball's m R above the 0.066 kg m the
    // plane needs): main's `critical` said "stable: nowhere in (0, 3303.08 rpm]" where
    // `stability` says "no verdict: no stationary state was found at any of the 50 speeds"
    // (no state found is no verdict). Whatever the search finds, the two say the same.
    let cfg = washer_with_gravity("w03.toml");
    let c = text(&["critical", "--config", &cfg, "--set", "balancer.ball_mass=0.3"]);
    let s = text(&["stability", "--config", &cfg, "--set", "balancer.ball_mass=0.3"]);
    assert_eq!(ranges_line(&c), ranges_line(&s), "critical:\n{c}\nstability:\n{s}");
    let v = json(&["critical", "--config", &cfg, "--set", "balancer.ball_mass=0.3", "--format", "json"]);
    let without = v["speeds_without_stationary_state"].as_u64().unwrap();
    if v["exact_stable_ranges"].as_array().unwrap().is_empty() && without == 50 {
        assert!(c.contains("no verdict") && !c.contains("nowhere"), "{c}");
    }
}

#[test]
fn critical_opens_with_the_verdict_at_the_operating_speed() {
    // the washer with gravity, operating_speed 1400 rpm: `stability` and the closed-form route
    // open with the verdict there (the example's comment and docs/notes/stability.md say
    // `critical` does too); main's general route printed none
    let cfg = washer_with_gravity("w.toml");
    let c = text(&["critical", "--config", &cfg]);
    let s = text(&["stability", "--config", &cfg]);
    let first = c.lines().next().unwrap();
    assert!(first.starts_with("operating speed 146.608 rad/s (1400 rpm): the balanced state is STABLE"), "{c}");
    assert_eq!(first, s.lines().next().unwrap());
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["operating"]["stable"], true, "{}", v["operating"]);
}

#[test]
fn the_family_note_needs_three_balls_and_equal_speeds_merge() {
    // two balls form no family: main printed "with 3 or more balls in a plane the balanced
    // states form a family" for the Jeffcott rotor's two
    let cfg = config("j2.toml", JEFFCOTT);
    let t = text(&["critical", "--config", &cfg]);
    assert!(!t.contains("3 or more") && t.contains("the closed-form balanced placement"), "{t}");
    // review 29's r1.toml: its translational pair lies 5.3e-8 apart (the supports' coupling
    // about the centre of mass nearly vanishes: 4e5 × 0.15 = 6e5 × 0.1), printed twice as
    // "353.017 rad/s, multiplicity 1"; now one speed of multiplicity 2 with the split
    let r1 = "[rotor]\nmass = 8.0\nequatorial_moment = 0.12\npolar_moment = 0.05\nz = 0.15\n[supports]\nz_left = 0.0\nz_right = 0.25\nstiffness_left = 4.0e5\nstiffness_right = 6.0e5\ndamping_left = 60.0\ndamping_right = 80.0\ndamping_left_y = 120.0\ndamping_right_y = 40.0\n[unbalance]\nmass = 0.004\nradius = 0.08\nangle = 1.0\n[balancer]\nz = 0.32\nballs = 2\nball_mass = 0.01\nrace_radius = 0.09\ndrag = 0.3\n[spatial]\ngravity = [0.0, -9.81, 0.0]\n";
    let cfg = config("r1.toml", r1);
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    let s = v["locked_critical_speeds"]["speeds"].as_array().unwrap();
    assert_eq!(s[0]["multiplicity"], 2, "{s:?}");
    let [a, b] = [s[0]["split"][0].as_f64().unwrap(), s[0]["split"][1].as_f64().unwrap()];
    assert!(a < b && (b - a) / b < 1e-5, "{a} {b}");
    // no two speeds left closer than the tolerance, so none prints twice
    for w in s.windows(2) {
        let (x, y) = (w[0]["omega"].as_f64().unwrap(), w[1]["omega"].as_f64().unwrap());
        assert!(y - x > 1e-5 * y, "{x} {y}");
    }
    let t = text(&["critical", "--config", &cfg]);
    let listed: Vec<&str> = t.lines().filter(|l| l.contains(" whirl, ")).map(|l| l.split("  ").nth(1).unwrap_or("")).collect();
    let mut unique = listed.clone();
    unique.dedup();
    assert_eq!(listed, unique, "{t}");
    assert!(!t.contains("3 or more"), "{t}");
}

#[test]
fn critical_locks_an_eccentric_race_on_anisotropic_supports_at_every_speed() {
    // review 29's rnd/p29_0.toml: one ball, an eccentric race, k_x != k_y: neither closed form
    // places the ball below its semi-balanced speed, and 1362 of 2000 speeds went unsearched
    // ("none at the 638 of 2000 speeds searched"); the planar balls' placement does not enter
    // the locked rotor's linearisation: sqrt(k_x/m0) and sqrt(k_y/m0)
    let body = "[planar]\nm1 = 3.1436141458374456\nm2 = 0.39240696184087503\nm3 = 0.18361361972000573\nn = 1\ns1 = 0.0028800158767381913\ns2 = 0.001061530016035415\ngamma = 1.2474803919927735\nr = 0.08550002539798886\nk_x = 7231.015059248485\nk_y = 8807.02932861872\nc_x = 10.147903131522126\nc_y = 16.91317188587021\nc_psi = 0.028810620939040302\nc_theta = 0.0\ni_g = 0.03143614145837446\n";
    let cfg = config("p29_0.toml", body);
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    let m0 = 3.1436141458374456 + 0.39240696184087503 + 0.18361361972000573;
    let want = [(7231.015059248485f64 / m0).sqrt(), (8807.02932861872f64 / m0).sqrt()];
    let got = speeds(&v);
    assert_eq!(got.len(), 2, "{v}");
    for (a, b) in got.iter().zip(want) {
        assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
    }
    assert_eq!(v["locked_critical_speeds"]["speeds_not_searched"], 0);
}
