//! `autobal campbell` (session 31): an overdamped end on the real axis is listed and marked in
//! the table and the JSON of both routes, and a resolved nearly real pair's `ν` is printed beside
//! its large log decrement (the library's tests: crates/autobal/tests/campbell_overdamped_31.rs).

use std::process::Command;

fn autobal(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn the_drag_modes_crossings_are_marked_overdamped_on_both_routes() {
    // examples/default.toml: the two balls' drag pair meets the axis at 0.0773556 and leaves it
    // at 0.131932 (overdamped: marked), a ball pair lies on it from 2.101767 to 2.106803 (one
    // resonance, AF ≈ 9.6: neither end marked; session 31 marked 2.106803)
    let cfg = example("default.toml");
    for route in ["auto", "general"] {
        let v: serde_json::Value = serde_json::from_str(&autobal(&["campbell", "-c", &cfg, "--route", route, "--format", "json"])).unwrap();
        let ks = v["critical_speeds"].as_array().unwrap();
        let mark = |w: f64| -> Vec<bool> {
            ks.iter().filter(|k| (k["omega"].as_f64().unwrap() - w).abs() < 1e-6).map(|k| k["overdamped"].as_bool().unwrap()).collect()
        };
        assert_eq!(mark(0.0773556), [true], "{route}: {ks:?}");
        assert_eq!(mark(0.131932), [true], "{route}: {ks:?}");
        assert_eq!(mark(2.101767), [false], "{route}: {ks:?}");
        assert_eq!(mark(2.106803), [false], "{route}: {ks:?}");
        let table = autobal(&["campbell", "-c", &cfg, "--route", route]);
        assert_eq!(table.matches("overdamped, no resonance (see the note)").count(), ks.iter().filter(|k| k["overdamped"] == true).count(), "{table}");
        assert!(table.contains("note: overdamped, no resonance: ν = 0 is reached"), "{table}");
    }
}

#[test]
fn a_nearly_real_pairs_nu_is_printed_beside_its_log_decrement() {
    // examples/spatial.toml with h_s = 0.03: at the first speed the balls' drag pair is
    // −0.0300011 ± 1.2086e-6 i, resolved, δ = 2π·0.0300011/1.20859e-6 = 155969.4 per
    // turning-axes cycle; its ν was printed as 0.00000 beside that
    let table = autobal(&["campbell", "-c", &example("spatial.toml"), "--set", "dimensionless.h_s=0.03"]);
    let row = table.lines().find(|l| l.contains("155969.")).unwrap_or_else(|| panic!("{table}"));
    assert!(row.trim_start().starts_with("1.209e-6"), "{row}");
}
