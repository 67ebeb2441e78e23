//! Axes that change nothing (session 27's hostile-input hunt): `sweep --x analysis.omega_max=2,3`
//! on a config with a `[drive]`, or `map --x drive.t_end=1:2:2`, ran every point on the same
//! rotor and wrote a table of equal rows, exit 0, no word; the user read it as a rotor
//! insensitive to that key. Every axis now goes through the check `--set` has
//! (`autobal::config::entry_use`, docs/reference/robustness.md "Every entry is used") and the
//! commands' own unused keys, before anything runs: such an axis is refused on one line naming
//! it, and nothing is written; an axis that changes the runs is still taken.

mod common;
use common::{examples, run_in, scratch_in};
use std::time::Duration;

/// `args` refused with exactly `line` on standard error (its only line), a non-zero exit, and
/// nothing written in the scratch folder.
fn refused(d: &std::path::Path, args: &[&str], line: &str) {
    let (code, out, err) = run_in(d, Duration::from_secs(120), args);
    assert_ne!(code, 0, "autobal {}: accepted\n{out}", args.join(" "));
    assert_eq!(err.trim_end(), line, "autobal {}", args.join(" "));
    let written: Vec<_> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(written.is_empty(), "autobal {}: wrote {written:?}", args.join(" "));
}

/// `args` run, and the rows of its CSV `stem.csv` after the header.
fn rows(d: &std::path::Path, args: &[&str], stem: &str) -> Vec<String> {
    let (code, _, err) = run_in(d, Duration::from_secs(120), args);
    assert_eq!(code, 0, "autobal {}: {err}", args.join(" "));
    let csv = std::fs::read_to_string(d.join(format!("{stem}.csv"))).unwrap();
    csv.lines().skip(1).map(str::to_string).collect()
}

#[test]
fn sweep_refuses_an_axis_that_changes_no_run() {
    let two = examples("spatial_two_plane.toml");
    let shaft = examples("linear_rotor_shaft.toml");
    let short = ["--set", "drive.t_end=0.05", "--out", "s"];
    let with = |args: &[&'static str]| -> Vec<String> { args.iter().chain(short.iter()).map(|s| s.to_string()).collect() };
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            [vec!["sweep".to_string(), "--config".into(), two.clone()], with(&["--x", "analysis.omega_max=2,3"])].concat(),
            "error: --x analysis.omega_max: no effect on `sweep` with the rest of this config (it sets only the default run-up's end, and this config gives [drive]); every point would be the same",
        ),
        (
            [vec!["sweep".to_string(), "--config".into(), two.clone()], with(&["--x", "analysis.sensitivity_limit=0.1,0.2"])].concat(),
            "error: --x analysis.sensitivity_limit: no effect on `sweep` with the rest of this config (an analytic commands' setting (the sensitivity's limit), which the simulation does not use); every point would be the same",
        ),
        (
            // the tilt's direction with no tilt (axis_tilt = 0 in the example)
            [vec!["sweep".to_string(), "--config".into(), two.clone()], with(&["--x", "rotor.axis_tilt_angle=0.1,0.2"])].concat(),
            "error: --x rotor.axis_tilt_angle: no effect on `sweep` with the rest of this config (with rotor.axis_tilt = 0); every point would be the same",
        ),
        (
            // a torque on the example's speed schedule
            [vec!["sweep".to_string(), "--config".into(), two.clone()], with(&["--y", "drive.torque=1,2", "--x", "balancer.drag=0.4,0.5"])].concat(),
            "error: --y drive.torque: no effect on `sweep` with the rest of this config (with drive.kind = \"schedule\", schedule_of = \"speed\"); every point would be the same",
        ),
        (
            [vec!["sweep".to_string(), "--config".into(), two.clone()], with(&["--x", "spatial.spin_drag=0,1"])].concat(),
            "error: --x spatial.spin_drag: no effect on `sweep` with the rest of this config (with drive.kind = \"schedule\", schedule_of = \"speed\": the speed is prescribed, the drag acts on a spin a torque drives); every point would be the same",
        ),
        (
            // the linear rotor's speed top with the config's [drive]
            vec!["sweep".into(), "--config".into(), shaft, "--x".into(), "linear_rotor.omega_max=500,1000".into(), "--out".into(), "s".into()],
            "error: --x linear_rotor.omega_max: no effect on `sweep` with the rest of this config (it sets only the default run-up's end, and this config gives [drive]); every point would be the same",
        ),
    ];
    for (i, (args, line)) in cases.iter().enumerate() {
        let d = scratch_in("axes27", &format!("sweep{i}"));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&d, &args, line);
    }
    // an axis the rest of the config makes moot only at some values of another axis is taken:
    // the tilt's direction matters once the tilt is not 0, and the rows say so
    let d = scratch_in("axes27", "sweep_ok");
    let r = rows(
        &d,
        &["sweep", "--config", &two, "--x", "rotor.axis_tilt_angle=0.1,0.2", "--y", "rotor.axis_tilt=0,0.01", "--set", "drive.t_end=0.05", "--out", "s"],
        "s",
    );
    assert_eq!(r.len(), 4, "{r:?}");
    // (with a torque drive the spin drag is taken too)
    let d = scratch_in("axes27", "sweep_torque");
    let r = rows(
        &d,
        &[
            "sweep",
            "--config",
            &two,
            "--x",
            "spatial.spin_drag=0,1",
            "--set",
            "drive.kind=torque",
            "--set",
            "drive.torque=1",
            "--set",
            "drive.t_end=0.05",
            "--out",
            "s",
        ],
        "s",
    );
    assert_eq!(r.len(), 2, "{r:?}");
}

#[test]
fn map_refuses_an_axis_that_changes_no_cell() {
    let two = examples("spatial_two_plane.toml");
    let planar = examples("planar.toml");
    let spatial = examples("spatial.toml");
    let run_setting = "a run's setting: `map` computes the stationary states at each speed and runs nothing; every point would be the same";
    let spin = "acts on the spin only, and `map` prescribes the speed (its speed axis or --omega); every point would be the same";
    let cases: Vec<(Vec<&str>, String)> = vec![
        // the general route of a two-plane rotor
        (vec!["--config", &two, "--y", "speed_rpm=12000:20000:2", "--x", "drive.t_end=1:2:2"], format!("error: --x drive.t_end: {run_setting}")),
        (vec!["--config", &two, "--y", "speed_rpm=12000:20000:2", "--x", "spatial.spin_drag=0:2:2"], format!("error: --x spatial.spin_drag: {spin}")),
        // the planar rotor
        (vec!["--config", &planar, "--y", "omega=300:400:2", "--x", "planar.c_theta=0:2:2"], format!("error: --x planar.c_theta: {spin}")),
        (
            vec!["--config", &planar, "--y", "omega=300:400:2", "--x", "planar.restitution=0.1:0.2:2"],
            "error: --x planar.restitution: no effect on `map` with the rest of this config (with planar.contact = false); every point would be the same"
                .into(),
        ),
        // on either axis
        (
            vec!["--config", &two, "--x", "speed_rpm=12000:20000:2", "--y", "integration.rtol=1e-8:1e-6:2"],
            format!("error: --y integration.rtol: {run_setting}"),
        ),
    ];
    for (i, (args, line)) in cases.iter().enumerate() {
        let d = scratch_in("axes27", &format!("map{i}"));
        let args: Vec<&str> = ["map"].iter().copied().chain(args.iter().copied()).chain(["--out", "m"]).collect();
        refused(&d, &args, line);
    }
    // axes that change the cells are taken, on each route
    for (i, args) in [
        vec!["--config", &two, "--y", "speed_rpm=12000:20000:2", "--x", "balancer.drag=0.4:0.5:2"],
        vec!["--config", &planar, "--y", "omega=300:400:2", "--x", "planar.c_psi=0.05:0.1:2"],
        vec!["--config", &spatial, "--x", "omega=0.5:2:3", "--y", "dimensionless.z_a=0.1:0.5:3"],
    ]
    .iter()
    .enumerate()
    {
        let d = scratch_in("axes27", &format!("map_ok{i}"));
        let args: Vec<&str> = ["map"].iter().copied().chain(args.iter().copied()).chain(["--out", "m"]).collect();
        assert!(!rows(&d, &args, "m").is_empty());
    }
}
