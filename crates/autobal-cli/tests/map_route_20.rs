//! A map's route where one of its axes passes through zero unbalance or one ball (session 20):
//! the route was decided from the config as given, so a map over `unbalance.mass = 0:…` drew
//! its zero row by paper 000's closed form, which counts the balancing family's neutral
//! direction as "not stable" (margin ~1e-27): that row read unstable at every speed, where
//! `stability` on the same config (the general route since session 19) finds the family's
//! stable members and a time simulation balances (session 19's audit, at 1500 rad/s).

mod common;
use common::{examples, run_in, scratch_in};
use serde_json::Value;
use std::time::Duration;

fn run(d: &std::path::Path, args: &[&str]) -> String {
    let (code, out, err) = run_in(d, Duration::from_secs(300), args);
    assert_eq!(code, 0, "autobal {}: {err}", args.join(" "));
    out
}

#[test]
fn a_map_through_zero_unbalance_agrees_with_stability_on_its_zero_row() {
    let d = scratch_in("m20", "route");
    let cfg = examples("dimensional.toml");
    // speeds across the stable range `stability` gives without unbalance (route_19.rs: it
    // contains 1500 rad/s) and below it
    let speeds = "speed=300:1800:6";
    run(&d, &["map", "--config", &cfg, "--x", speeds, "--y", "unbalance.mass=0:0.01:3", "--out", "m"]);
    let csv = std::fs::read_to_string(d.join("m.csv")).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no {name} in {head:?}"));
    // the general route's columns: a verdict word per cell (the closed form's are 0/1 flags)
    let (verdict, mass) = (col("verdict"), col("unbalance.mass"));
    let s: Value = serde_json::from_str(&run(&d, &["stability", "--config", &cfg, "--set", "unbalance.mass=0", "--format", "json"])).unwrap();
    let ranges = s["stable_ranges"].as_array().unwrap();
    let inside = |w: f64| ranges.iter().any(|r| r["from"].as_f64().unwrap() < w && w < r["to"].as_f64().unwrap());
    let mut checked = 0;
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        if f[mass].parse::<f64>().unwrap() != 0.0 {
            continue;
        }
        let w: f64 = f[0].parse().unwrap();
        // the range ends are not on this grid (checked: none within 1 rad/s of a grid speed)
        assert!(ranges.iter().all(|r| (r["from"].as_f64().unwrap() - w).abs() > 1.0 && (r["to"].as_f64().unwrap() - w).abs() > 1.0));
        assert_eq!(f[verdict] == "stable", inside(w), "{w} rad/s: map says {}, stability's ranges {ranges:?}", f[verdict]);
        checked += 1;
    }
    assert_eq!(checked, 6);
    // and at least one stable cell on the zero row (the closed form had none)
    assert!(csv.lines().skip(1).any(|l| l.split(',').nth(mass) == Some("0") && l.split(',').nth(verdict) == Some("stable")), "{csv}");
    std::fs::remove_dir_all(&d).ok();
}
