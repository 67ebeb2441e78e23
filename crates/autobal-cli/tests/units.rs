//! Speeds in the user's units (issue 21): SI in (`--omega-max 1500rpm`, `analysis.omega_max`,
//! `analysis.operating_speed`, map axes `speed_rpm`, `speed`, `speed_hz`), SI out (every
//! dimensionless speed of a dimensional config beside its SI value), the operating speed's
//! verdict in the first lines, and messages with one name per concept.

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

fn washer() -> String {
    format!("{}/../../examples/washing_machine.toml", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("units");
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// ω0 of the washer (rad/s), as `critical` reports it.
fn omega0() -> f64 {
    json(&["critical", "--config", &washer(), "--format", "json"])["model"]["scale"]["omega0"].as_f64().unwrap()
}

#[test]
fn speeds_with_units_are_the_same_speed_in_every_spelling() {
    let w0 = omega0();
    let cfg = washer();
    // 1500 rpm = 25 Hz = 50π rad/s; the span is that speed over ω0 (relative 1e-15: one division)
    let expect = 1500.0 * std::f64::consts::PI / 30.0 / w0;
    for spelling in ["1500rpm", "1500 rpm", "25Hz", "157.07963267948966 rad/s"] {
        let v = json(&["stability", "--config", &cfg, "--format", "json", "--samples", "50", "--omega-max", spelling]);
        let w = v["omega_max"].as_f64().unwrap();
        assert!((w - expect).abs() < 1e-14 * expect, "{spelling}: {w} vs {expect}");
        assert!((v["omega_max_rpm"].as_f64().unwrap() - 1500.0).abs() < 1e-9, "{spelling}");
    }
    // the config key takes the same text
    let v = json(&["stability", "--config", &cfg, "--format", "json", "--samples", "50", "--set", "analysis.omega_max=\"25 Hz\""]);
    assert!((v["omega_max"].as_f64().unwrap() - expect).abs() < 1e-14 * expect);
    // a bare number is Ω, with a note naming the speed it is on a dimensional config
    let (code, _, err) = autobal(&["stability", "--config", &cfg, "--samples", "50", "--omega-max", "5.2"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("note: --omega-max 5.2 is the dimensionless Ω = 5.2, i.e. 1505 rpm"), "{err}");
    let (code, _, err) = autobal(&["critical", "--config", &cfg, "--set", "analysis.omega_max=5.2"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("note: analysis.omega_max = 5.2 is the dimensionless Ω = ω/ω0; write a unit for SI"), "{err}");
    // not on a config with units, nor on a dimensionless config (where Ω is the only speed)
    assert!(!autobal(&["critical", "--config", &cfg]).2.contains("note:"));
    assert!(!autobal(&["critical", "--set", "analysis.omega_max=5.2"]).2.contains("note:"));
}

#[test]
fn bad_speeds_are_one_line_naming_the_option() {
    let cfg = washer();
    for (args, start) in [
        (vec!["stability", "--config", &cfg, "--omega-max", "1500 rmp"], "error: --omega-max: unknown unit \"rmp\""),
        (vec!["stability", "--config", &cfg, "--omega-max=-3rpm"], "error: --omega-max: a speed must be a finite number ≥ 0"),
        (vec!["critical", "--config", &cfg, "--set", "analysis.operating_speed=\"1400-1200 rpm\""], "error: analysis.operating_speed: the range"),
        (vec!["critical", "--config", &cfg, "--set", "analysis.operating_speed=true"], "error: analysis.operating_speed: expected a speed"),
        // a dimensionless config has no ω0: units are refused with the way out
        (vec!["stability", "--omega-max", "1500rpm"], "error: --omega-max: 1500 rpm needs a dimensional config"),
        (vec!["critical", "--set", "analysis.omega_max=\"3 Hz\""], "error: analysis.omega_max: 3 Hz needs a dimensional config"),
        (
            vec!["map", "--config", &cfg, "--x", "balancer.z=0.1:0.2:3", "--y", "speed_rpm=0:1e308:3", "--out", "/nonexistent/m"],
            "error: --y speed_rpm: must lie in (0, 1e6]",
        ),
        (
            vec!["map", "--x", "dimensionless.z_a=-1:1:3", "--y", "speed_rpm=100:900:3", "--out", "/nonexistent/m"],
            "error: --y speed_rpm: a speed in SI needs a dimensional config",
        ),
    ] {
        let (code, _, err) = autobal(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(err.starts_with(start) && err.trim_end().lines().count() == 1, "{args:?}: {err}");
    }
}

#[test]
fn the_operating_speed_is_judged_first_and_covered_by_every_axis() {
    let cfg = washer();
    // the washer's 1400 rpm spin (examples/washing_machine.toml)
    let (code, out, err) = autobal(&["stability", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(out.lines().nth(1).unwrap().starts_with("operating speed 1400 rpm (146.6 rad/s, Ω = 4.837): the balanced state is STABLE"), "{out}");
    let (_, crit, _) = autobal(&["critical", "--config", &cfg]);
    let first = crit.lines().take(6).find(|l| l.starts_with("operating speed")).unwrap_or_else(|| panic!("{crit}"));
    assert!(first.contains("STABLE"), "{crit}");
    // critical and stability agree (same exact ranges over the same span)
    let s = json(&["stability", "--config", &cfg, "--format", "json"]);
    let c = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(s["operating_speed"], c["operating_speed"]);
    let op = &s["operating_speed"];
    assert_eq!(op["stable"], true);
    // the margin is the distance to the nearest end of the stable range that holds the speed
    let w = op["omega"][0].as_f64().unwrap();
    let lo = op["stable_range"]["lo"].as_f64().unwrap();
    let hi = op["stable_range"]["hi"].as_f64();
    assert!(lo < w && hi.is_none_or(|h| w < h));
    let m = op["margin"].as_f64().unwrap();
    assert_eq!(m, hi.map_or(w - lo, |h| (w - lo).min(h - w)));
    assert!((op["margin_rpm"].as_f64().unwrap() / m - op["rpm"][0].as_f64().unwrap() / w).abs() < 1e-9);
    // max Re λ at the speed, negative where stable, as `map --omega 1400rpm` computes it at a point
    assert!(op["max_real_part"].as_f64().unwrap() < 0.0);
    // the automatic axes reach 1.25 × 1400 rpm: stability's span, campbell's speeds
    assert!((s["omega_max_rpm"].as_f64().unwrap() - 1750.0).abs() < 1e-6, "{}", s["omega_max_rpm"]);
    let cb = json(&["campbell", "--config", &cfg, "--format", "json", "--points", "10"]);
    assert!(cb["omega_rpm"].as_array().unwrap().last().unwrap().as_f64().unwrap() > 1400.0);
    // where the balanced state is not stable the verdict says so and names the nearest stable range
    let (_, out, _) = autobal(&["stability", "--config", &cfg, "--set", "balancer.z=0.40", "--set", "analysis.operating_speed=\"900-1000 rpm\""]);
    assert!(
        out.contains("operating speed 900-1000 rpm (Ω = 3.11-3.455): the balanced state is NOT STABLE") && out.contains("nearest stable range 312-529 rpm"),
        "{out}"
    );
}

#[test]
fn the_default_run_up_goes_to_the_operating_speed() {
    let out = tmp("runup");
    let v = json(&["simulate", "--config", &washer(), "--format", "json", "--out", out.to_str().unwrap()]);
    assert_eq!(v["drive_is_default"], true);
    let end = v["final_omega"].as_f64().unwrap();
    // 1400 rpm = 146.6077 rad/s, reached at t_end by the constant acceleration (relative 1e-9)
    assert!((end - 1400.0 * std::f64::consts::PI / 30.0).abs() < 1e-9 * end, "{end}");
    assert_eq!(v["balanced"], true, "the spin speed is in the stable range: {v}");
}

/// The keys of a JSON object that hold a dimensionless speed (or rate in units of ω0), each of
/// which must have an SI sibling in a dimensional config's output.
fn is_speed_key(k: &str) -> bool {
    const SPEEDS: &[&str] = &[
        "omega",
        "omega_max",
        "span",
        "margin",
        "margin_below",
        "margin_above",
        "interval",
        "re",
        "im",
        "decay_rate",
        "fixed_frequency",
        "max_real_part",
        "stable_range",
        "nearest_stable_range",
    ];
    let si = ["_rpm", "_rad_s", "_hz", "_per_s", "_si"].iter().any(|s| k.ends_with(s));
    !si && (SPEEDS.contains(&k) || k.ends_with("_speed") || k.ends_with("_speeds") || k.ends_with("_ranges") || k.starts_with("approx_"))
}

/// Every speed key (by [`is_speed_key`]) of every object under `v` with a value (not null, not
/// a list of objects: a container) has a sibling `K_rpm`, `K_rad_s`, `K_hz`, `K_per_s` or `K_si`
/// (`omega`: also `rpm`); an object under a speed-like name (`operating_speed`) is searched, not
/// judged; `model`, `anisotropy`, `sensitivity` (inputs, ratios) and `open_at_span_end`
/// (booleans) are not speeds.
fn speeds_without_si(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                if ["model", "anisotropy", "sensitivity", "open_at_span_end"].contains(&k.as_str()) {
                    continue;
                }
                let container = x.is_object() || x.as_array().is_some_and(|a| a.first().is_some_and(|e| e.is_object()));
                if is_speed_key(k) && !x.is_null() && !x.is_boolean() && !container {
                    let has = ["_rpm", "_rad_s", "_hz", "_per_s", "_si"].iter().any(|s| o.contains_key(&format!("{k}{s}")))
                        || (k == "omega" && o.contains_key("rpm"));
                    if !has {
                        out.push(format!("{path}.{k}"));
                    }
                }
                speeds_without_si(x, &format!("{path}.{k}"), out);
            }
        }
        serde_json::Value::Array(a) => {
            for x in a.iter().take(3) {
                speeds_without_si(x, path, out);
            }
        }
        _ => {}
    }
}

#[test]
fn a_dimensional_config_reports_no_speed_without_its_si_value() {
    let cfg = washer();
    for args in [vec!["critical"], vec!["stability", "--samples", "200"], vec!["campbell", "--points", "12"], vec!["ranges"]] {
        let mut a = args.clone();
        a.extend(["--config", &cfg, "--format", "json"]);
        let v = json(&a);
        let mut missing = vec![];
        speeds_without_si(&v, args[0], &mut missing);
        assert!(missing.is_empty(), "{}: dimensionless speeds without SI: {missing:?}", args[0]);
        // the rule finds what it is meant to: the checker is not vacuous
        let mut probe = vec![];
        speeds_without_si(&serde_json::json!({ "omega_max": 2.0, "x": { "re": 1.0, "re_per_s": 3.0 } }), "probe", &mut probe);
        assert_eq!(probe, ["probe.omega_max"]);
    }
    // the tables: Campbell's speeds in rpm and its whirl frequencies in Hz and rpm
    let (code, out, err) = autobal(&["campbell", "--config", &cfg, "--points", "12"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("fixed Hz") && out.contains("fixed rpm") && out.contains("\nspeed ") && out.contains(" rpm (") && !out.contains("\nΩ = "), "{out}");
    // SI values are the Ω values times ω0 (rad/s) and 30 ω0/π (rpm)
    let v = json(&["campbell", "--config", &cfg, "--format", "json", "--points", "12"]);
    let w0 = omega0();
    let m = &v["lines"][0]["modes"][5];
    assert!((m["fixed_frequency_rad_s"].as_f64().unwrap() - m["fixed_frequency"].as_f64().unwrap() * w0).abs() < 1e-12 * w0);
    assert!((v["omega_rpm"][5].as_f64().unwrap() - v["omega"][5].as_f64().unwrap() * w0 * 30.0 / std::f64::consts::PI).abs() < 1e-9);
}

#[test]
fn messages_say_each_thing_once_under_one_name() {
    let cfg = washer();
    // the washer's 3 balls: eq (17) and the exact tensor differ; only `inertia` says so
    let (_, crit, err) = autobal(&["critical", "--config", &cfg]);
    assert!(!crit.contains("eq (17) gives") && !err.contains("eq (17) gives"), "{crit}{err}");
    let (_, inertia, _) = autobal(&["inertia", "--config", &cfg]);
    assert!(inertia.contains("paper 000's eq (17) gives") && inertia.contains("they differ by"), "{inertia}");
    let c = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert!(c["anisotropy"]["warnings"].as_array().unwrap().iter().all(|w| !w.as_str().unwrap().contains("eq (17) gives")));
    // 003's ranges are a necessary condition, and the two classifications have their own names
    assert!(crit.contains("necessary condition for autobalancing (003):") && !crit.contains("autobalancing possible"), "{crit}");
    assert!(crit.contains("inertia class (000 Table 1): long") && crit.contains("autobalancing class (003): long"), "{crit}");
    assert!(!crit.contains("rotor class") && !crit.contains("Short") && !crit.contains("NearSpherical"), "{crit}");
    // where the exact verdict is computed, the exact stable ranges stand beside the necessary ones
    assert!(crit.contains("exact stable ranges (eigenvalues, balls free)"), "{crit}");
}

fn read_csv(p: &std::path::Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(p).unwrap().lines().map(|l| l.split(',').map(String::from).collect()).collect()
}

#[test]
fn a_map_over_rpm_is_the_map_over_the_same_omegas() {
    let cfg = washer();
    let w0 = omega0();
    let to_omega = |n: f64| n * std::f64::consts::PI / 30.0 / w0;
    let (a, b) = (tmp("rpm"), tmp("omega"));
    let (code, _, err) =
        autobal(&["map", "--config", &cfg, "--x", "balancer.z=0.1:0.4:7", "--y", "speed_rpm=300:1500:20", "--threads", "2", "--out", a.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let omega = format!("omega={}:{}:20", to_omega(300.0), to_omega(1500.0));
    let (code, _, err) = autobal(&["map", "--config", &cfg, "--x", "balancer.z=0.1:0.4:7", "--y", &omega, "--threads", "2", "--out", b.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (ra, rb) = (read_csv(&a.with_extension("csv")), read_csv(&b.with_extension("csv")));
    assert_eq!(ra[0], ["balancer.z", "speed_rpm", "max_real_part_per_tau", "stable", "necessary"]);
    assert_eq!(ra.len(), rb.len());
    for (x, y) in ra.iter().zip(&rb).skip(1) {
        // the axis printed in rpm is the Ω axis times 30 ω0/π
        let (n, w): (f64, f64) = (x[1].parse().unwrap(), y[1].parse().unwrap());
        assert!((to_omega(n) - w).abs() < 1e-11 * w, "{x:?} {y:?}");
        // the same cells: margins to the rounding of the grid's 12 digits, verdicts equal
        let (ma, mb): (f64, f64) = (x[2].parse().unwrap(), y[2].parse().unwrap());
        assert!((ma - mb).abs() < 1e-9, "{x:?} {y:?}");
        assert_eq!(x[3..], y[3..], "{x:?} {y:?}");
    }
}

#[test]
fn a_map_over_rpm_and_a_mass_converts_with_each_lines_omega0() {
    // the ball mass changes M_s and so ω0: each line of the mass axis has its own Ω for one rpm;
    // every cell's margin equals the eigenvalues' max Re λ of that model at that Ω (stability
    // at one point: `stability --omega-max` is not a point, so compare with a one-line map)
    let cfg = washer();
    let a = tmp("mass");
    let (code, _, err) =
        autobal(&["map", "--config", &cfg, "--x", "speed_rpm=300:1500:9", "--y", "balancer.ball_mass=0.06:0.3:3", "--out", a.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let rows = read_csv(&a.with_extension("csv"));
    for (i, mass) in ["0.06", "0.3"].into_iter().enumerate() {
        let set = format!("balancer.ball_mass={mass}");
        let w0 = json(&["critical", "--config", &cfg, "--set", &set, "--format", "json"])["model"]["scale"]["omega0"].as_f64().unwrap();
        for (j, r) in rows.iter().skip(1).filter(|r| r[1] == mass).enumerate() {
            let n: f64 = r[0].parse().unwrap();
            let b = tmp(&format!("point-{i}-{j}"));
            let om = n * std::f64::consts::PI / 30.0 / w0;
            // a map without a speed axis evaluates each point directly (QR) at the fixed Ω
            let (code, _, err) = autobal(&[
                "map",
                "--config",
                &cfg,
                "--set",
                &set,
                "--x",
                "balancer.z=0.26:0.27:2",
                "--y",
                "balancer.drag=1.5:1.6:2",
                "--omega",
                &om.to_string(),
                "--out",
                b.to_str().unwrap(),
            ]);
            assert_eq!(code, 0, "{err}");
            let p = read_csv(&b.with_extension("csv"));
            let (ma, mb): (f64, f64) = (r[2].parse().unwrap(), p[1][2].parse().unwrap());
            // continuation along the line against a direct solve: agree to 1e-9 (Routh-certified)
            assert!((ma - mb).abs() < 1e-9 * mb.abs().max(1e-3), "{mass} {n} rpm: {ma} vs {mb}");
            assert_eq!(r[3], p[1][3], "{mass} {n} rpm");
        }
    }
    // a fixed speed in SI over an axis that does not move ω0 is one Ω for the whole map
    let (code, out, err) =
        autobal(&["map", "--config", &cfg, "--x", "balancer.drag=0.5:3:3", "--y", "balancer.z=0.1:0.4:3", "--omega", "1400rpm", "--out", a.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("its own Ω"), "{out}");
}

#[test]
fn a_design_map_at_an_si_speed_puts_every_cell_at_its_own_omega() {
    // the engineer's question: this machine at 6000 rpm over its ball mass and a support's
    // stiffness, both of which move ω0 = sqrt(c_x/M_s). Two routes: paper 000's 12-state
    // polynomial at each cell's Ω = ω/ω0 (the closed form), and the general route (Newton on
    // the nonlinear equations in rad/s, their exact Jacobian's eigenvalues), which never
    // converts to Ω. Two balls: one isolated balanced state, the same in both.
    let cfg = format!("{}/../../examples/dimensional.toml", env!("CARGO_MANIFEST_DIR"));
    let axes = ["--x", "balancer.ball_mass=0.01:0.05:6", "--y", "supports.stiffness_left=1e6:4e6:5"];
    let (a, g, f) = (tmp("design-closed"), tmp("design-general"), tmp("design-one-omega"));
    let (code, out, err) = autobal(&[&["map", "--config", &cfg, "--omega", "6000rpm", "--out", a.to_str().unwrap()], &axes[..]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("every cell at 6000 rpm: its own Ω"), "{out}");
    let (code, _, err) = autobal(&[&["map", "--config", &cfg, "--omega", "6000rpm", "--route", "general", "--out", g.to_str().unwrap()], &axes[..]].concat());
    assert_eq!(code, 0, "{err}");
    let (ra, rg) = (read_csv(&a.with_extension("csv")), read_csv(&g.with_extension("csv")));
    assert_eq!(ra.len(), 31);
    assert_eq!(ra.len(), rg.len());
    let m = |r: &Vec<String>| r[2].parse::<f64>().unwrap();
    let scale = ra.iter().skip(1).map(|r| m(r).abs()).fold(0.0, f64::max);
    let (mut stable, mut unstable) = (0, 0);
    for (x, y) in ra.iter().zip(&rg).skip(1) {
        assert_eq!((&x[0], &x[1]), (&y[0], &y[1]));
        // the same linearisation by two routes: the spectral abscissa to the eigensolvers'
        // round-off (as in tests/general_map.rs: 1e-7 of the map's largest |margin|)
        assert!((m(x) - m(y)).abs() <= 1e-7 * scale, "{x:?} vs {y:?}");
        assert_eq!(x[3] == "1", y[3] == "stable", "{x:?} vs {y:?}");
        if x[3] == "1" {
            stable += 1;
        } else {
            unstable += 1;
        }
    }
    assert!(stable > 0 && unstable > 0, "{stable} {unstable}");
    // not the map at the config's own Ω for 6000 rpm: the cells whose rotor has another ω0
    // are at another Ω, so some verdict or margin differs (the check above can fail)
    let w0 = json(&["critical", "--config", &cfg, "--format", "json"])["model"]["scale"]["omega0"].as_f64().unwrap();
    let om = (6000.0 * std::f64::consts::PI / 30.0 / w0).to_string();
    let (code, _, err) = autobal(&[&["map", "--config", &cfg, "--omega", &om, "--out", f.to_str().unwrap()], &axes[..]].concat());
    assert_eq!(code, 0, "{err}");
    let rf = read_csv(&f.with_extension("csv"));
    assert!(ra.iter().zip(&rf).skip(1).any(|(x, y)| (m(x) - m(y)).abs() > 1e-3 * scale), "the per-cell Ω changed nothing");
    // the boundary of such a map is not traced (each cell at its own Ω): one line, exit 2
    let (code, _, err) = autobal(&[&["map", "--config", &cfg, "--omega", "6000rpm", "--boundary", "--out", a.to_str().unwrap()], &axes[..]].concat());
    assert_eq!(code, 2);
    assert!(err.starts_with("error: --boundary: at a fixed speed in SI over axes that move ω0") && err.trim().lines().count() == 1, "{err}");
}

#[test]
fn the_boundary_over_rpm_is_drawn_in_rpm() {
    let cfg = washer();
    let a = tmp("boundary");
    let (code, _, err) =
        autobal(&["map", "--config", &cfg, "--x", "balancer.z=0.0:0.45:12", "--y", "speed_rpm=200:1750:12", "--boundary", "--out", a.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let b = std::fs::read_to_string(format!("{}_boundary.csv", a.display())).unwrap();
    assert!(b.starts_with("curve,kind,balancer.z,speed_rpm,"), "{b}");
    // the boundary points lie at speeds of the rpm plane (hundreds of rpm), not at Ω (units)
    let speeds: Vec<f64> = b.lines().skip(1).filter(|l| !l.starts_with('-')).map(|l| l.split(',').nth(3).unwrap().parse().unwrap()).collect();
    assert!(!speeds.is_empty() && speeds.iter().any(|&n| n > 250.0), "{b}");
}

/// The general route and the map's `omega` axis note a bare speed on a dimensional config as
/// the 12-state route's `--omega-max` does (session 17: `stability --route general
/// --omega-max 1500` and `map --x omega=100:160:6` on the washer ran silently at Ω = 1500 and
/// 100-160, i.e. ~45 000 and ~3 000-4 800 rad/s, where the user wrote rad/s).
#[test]
fn bare_speeds_on_the_general_route_and_map_axes_are_noted() {
    let cfg = washer();
    let w0 = omega0();
    let (code, _, err) = autobal(&["stability", "--config", &cfg, "--route", "general", "--samples", "10", "--omega-max", "5.2"]);
    assert_eq!(code, 0, "{err}");
    let want = format!("note: --omega-max 5.2 is the dimensionless Ω = 5.2, i.e. {} rad/s", autobal::error::fmt_num(5.2 * w0));
    assert!(err.contains(&want), "{err}\nwant {want}");
    let (code, _, err) = autobal(&["stability", "--config", &cfg, "--route", "general", "--samples", "10", "--omega-max", "157 rad/s"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("note:"), "{err}");
    for (axis, noted) in [("omega=1:2:3", true), ("speed=30:60:3", false)] {
        let out = tmp(&format!("bare_{noted}"));
        let (code, _, err) = autobal(&["map", "--config", &cfg, "--x", axis, "--y", "balancer.ball_mass=0.1:0.12:2", "--out", out.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
        assert_eq!(err.contains("note: --x omega is the dimensionless Ω = ω/ω0 on this dimensional config"), noted, "{axis}: {err}");
    }
}
