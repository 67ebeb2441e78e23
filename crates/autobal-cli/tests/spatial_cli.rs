//! `autobal simulate` and `autobal basins` on the spatial rotor of papers 000/003.

use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn simulate_runs_the_spatial_model_on_the_analytic_config() {
    let dir = std::env::temp_dir().join(format!("autobal-spatial-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.csv");
    let (code, stdout, err) = autobal(&["simulate", "--config", &example("spatial.toml"), "--format", "json", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["model"], "spatial");
    for k in ["balanced", "residual_unbalance", "peak_amplitude", "omega_at_peak", "final_amplitude", "steps", "rhs_evaluations", "wall_time_s"] {
        assert!(!v[k].is_null(), "{k}");
    }
    // the example starts the balls 57° off balance inside the exactly stable range: they balance
    assert_eq!(v["balanced"], true);
    assert!(v["residual_unbalance"].as_f64().unwrap() < 1e-6);
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), "t,omega,x,y,tilt_x,tilt_y,amplitude_left,amplitude_right,amplitude_plane1,psi_1,psi_2");
    assert_eq!(lines.count(), 2501);
    for s in ["amplitude_omega", "amplitude_t", "psi_t", "omega_t"] {
        assert!(dir.join(format!("run_{s}.svg")).exists(), "{s}");
    }
    // the planar model stays as it was
    let (code, stdout, err) = autobal(&["simulate", "--format", "json", "--out", dir.join("p.csv").to_str().unwrap(), "--set", "drive.t_end=1"]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("\"model\": \"planar\""));
}

#[test]
fn a_config_without_drive_runs_up_through_its_critical_speeds() {
    // the SI rotor an engineer analysed with `critical`, simulated as it is: no [drive] gives
    // the library's default run-up (docs/notes/spatial.md), said on stderr and in the JSON
    let dir = std::env::temp_dir().join(format!("autobal-runup-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = example("dimensional.toml");
    let (code, stdout, err) = autobal(&["simulate", "--config", &cfg, "--format", "json", "--out", dir.join("r.csv").to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("note: the config has no [drive]: running up from rest"), "{err}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["drive_is_default"], true);
    assert_eq!(v["drive"]["kind"], "acceleration");
    // it ends at 1.3 times the highest critical speed of `critical`, in rad/s
    let (code, crit, err) = autobal(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let c: serde_json::Value = serde_json::from_str(&crit).unwrap();
    let top = c["critical_speeds"].as_array().unwrap().iter().map(|k| k["omega_rad_s"].as_f64().unwrap()).fold(0.0, f64::max);
    let end = v["final_omega"].as_f64().unwrap();
    assert!((end / (1.3 * top) - 1.0).abs() < 1e-9, "{end} vs 1.3 × {top}");
    assert!(v["omega_at_peak"].as_f64().unwrap() < end);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spatial_real_balls_from_the_balancer_tables() {
    // [balancer] and [balancer2] take the real-ball keys of [planar] (docs/notes/balls.md): each plane
    // its own; the summary counts contacts and stick-slip transitions
    let cfg = example("spatial_two_plane.toml");
    let dir = std::env::temp_dir().join(format!("autobal-spatial-balls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.csv");
    let out = out.to_str().unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["simulate", "--config", &cfg, "--format", "json", "--out", out, "--set", "drive.t_end=3"];
        args.extend_from_slice(extra);
        let (code, stdout, err) = autobal(&args);
        assert_eq!(code, 0, "{err}");
        // the simulation uses [couple], [balancer2], ...: no warning that they are ignored
        assert!(!err.contains("uses the rotor of papers"), "{err}");
        serde_json::from_str::<serde_json::Value>(&stdout).unwrap()
    };
    let off = run(&[]);
    assert_eq!((off["contacts"].as_u64(), off["stick_slip_transitions"].as_u64()), (Some(0), Some(0)));
    let on = run(&[
        "--set",
        "balancer.contact=true",
        "--set",
        "balancer2.contact=true",
        "--set",
        "balancer.rolling_resistance=1e-3",
        "--set",
        "balancer2.rolling_resistance=1e-3",
    ]);
    assert!(on["contacts"].as_u64().unwrap() > 0 && on["stick_slip_transitions"].as_u64().unwrap() > 0, "{on}");
    assert_eq!(on["rotor"]["planes"][1]["physics"]["rolling_resistance"], 1e-3);
    for (set, msg) in [
        ("balancer.restitution=2", "balancer.restitution: must lie in"),
        ("balancer2.contact=1", "balancer2.contact: expected true or false"),
        ("balancer2.rolling_resistance=-1", "balancer2.rolling_resistance: must"),
    ] {
        let (code, _, err) = autobal(&["simulate", "--config", &cfg, "--set", set]);
        assert_eq!(code, 2, "{set}: {err}");
        assert!(err.contains(msg), "{set}: {err}");
    }
    let (code, _, err) = autobal(&["simulate", "--config", &cfg, "--set", "balancer.contact=true", "--set", "drive.psi0=[0, 0.05, 0, 3]"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("drive.psi0: balls 1 and 2 overlap"), "{err}");
}

#[test]
fn spatial_errors_name_the_field() {
    let (code, _, err) = autobal(&["simulate", "--config", &example("spatial.toml"), "--set", "drive.psi0=[1.0]"]);
    assert_eq!(code, 2);
    assert!(err.contains("drive.psi0: needs 2 angles"), "{err}");
    let (code, _, err) = autobal(&["simulate", "--config", &example("spatial.toml"), "--set", "spatial.gravity=[1, 2]"]);
    assert_eq!(code, 2);
    assert!(err.contains("spatial.gravity"), "{err}");
    let (code, _, err) =
        autobal(&["simulate", "--config", &example("dimensional.toml"), "--set", "drive.kind=\"speed\"", "--set", "supports.stiffness_left_y=-1"]);
    assert_eq!(code, 2);
    assert!(err.contains("supports.stiffness_left_y: must"), "{err}");
}

#[test]
fn basins_map_where_runs_end() {
    let out = std::env::temp_dir().join(format!("autobal-basins-{}.csv", std::process::id()));
    let (code, stdout, err) = autobal(&[
        "basins",
        "--config",
        &example("spatial.toml"),
        "--n",
        "3",
        "--set",
        "drive.t_end=300",
        "--set",
        "spatial.gravity=[0, -0.01, 0]",
        "--format",
        "json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("uses the rotor of papers"), "{err}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["runs"], 9);
    assert_eq!(std::fs::read_to_string(&out).unwrap().lines().count(), 10);
}

#[test]
fn the_summary_says_the_units() {
    // SI: rad/s, rpm and s; dimensionless: the papers' Ω and τ
    let dir = std::env::temp_dir().join(format!("autobal-spatial-units-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.csv");
    let (code, stdout, err) =
        autobal(&["simulate", "--config", &example("spatial_two_plane.toml"), "--set", "drive.t_end=0.2", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("(spatial rotor, 4 balls in 2 planes)"), "{stdout}");
    let peak = stdout.lines().find(|l| l.starts_with("peak whirl radius")).unwrap();
    let (w, rest) = peak.split_once("at ω = ").unwrap().1.split_once(" rad/s = ").unwrap();
    let (rpm, t) = rest.split_once(" rpm (t = ").unwrap();
    let (w, rpm): (f64, f64) = (w.parse().unwrap(), rpm.parse().unwrap());
    assert!((rpm - w * 30.0 / std::f64::consts::PI).abs() < 0.06, "{peak}");
    assert!(t.ends_with(" s)") && peak.contains(" mm at "), "{peak}");
    assert!(stdout.lines().any(|l| l.starts_with("final: radius") && l.contains(" rad/s = ") && l.contains(" rpm;")), "{stdout}");
    let (code, stdout, err) = autobal(&["simulate", "--config", &example("spatial.toml"), "--set", "drive.t_end=10", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("(spatial rotor, 2 balls in 1 plane)"), "{stdout}");
    assert!(stdout.contains(" ρ_s at Ω = 1.6000 (τ = ") && stdout.contains(" ρ_s at Ω = 1.6000;"), "{stdout}");
    std::fs::remove_dir_all(&dir).ok();
}
