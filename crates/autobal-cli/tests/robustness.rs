//! Regression tests for hostile input, end to end, each named after the defect it guards
//! against (issue 12). Every run has a wall-clock limit: a hang fails the test instead of
//! hanging the suite. The ranges are stated in `autobal::limits` and docs/robustness.md.

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Run the binary with `args` for at most `limit`; `(exit code, stdout, stderr)`. A run past the
/// limit is killed and fails the test.
fn run_for(limit: Duration, args: &[&str]) -> (i32, String, String) {
    let dir = std::env::temp_dir().join(format!("autobal-robustness-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut child =
        Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).current_dir(&dir).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("binary runs");
    let (mut out, mut err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out.read_to_string(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let t0 = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("autobal {} ran longer than {:?}", args.join(" "), limit);
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    (status.code().unwrap_or(-1), reader.join().unwrap(), err_reader.join().unwrap())
}

fn examples(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// The command must fail with exit code 2 and one line `error: FIELD: …` naming `field`.
#[track_caller]
fn rejects(args: &[&str], field: &str) -> String {
    let (code, out, err) = run_for(Duration::from_secs(20), args);
    assert_eq!(code, 2, "autobal {}: exit {code}, stdout {out}, stderr {err}", args.join(" "));
    let line = err.trim_end();
    assert!(!line.contains('\n'), "more than one line: {err}");
    assert!(line.starts_with(&format!("error: {field}: ")), "autobal {}: `{line}` does not name {field}", args.join(" "));
    assert!(line.len() < 400, "{line}");
    // numbers to a sensible precision: no run of more than 12 digits
    let longest = line.split(|c: char| !c.is_ascii_digit()).map(str::len).max().unwrap_or(0);
    assert!(longest <= 12, "a {longest}-digit number in `{line}`");
    line.to_string()
}

fn dim(set: &str) -> Vec<String> {
    vec!["critical".into(), "--config".into(), examples("dimensional.toml"), "--set".into(), set.into()]
}

fn args(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

#[test]
fn regression_rotor_mass_1e308_gave_zero_critical_speeds() {
    rejects(&args(&dim("rotor.mass=1e308")), "rotor.mass");
}

#[test]
fn regression_z_right_1e308_wrote_null() {
    for cmd in ["critical", "stability", "inertia", "ranges"] {
        rejects(&[cmd, "--config", &examples("dimensional.toml"), "--set", "supports.z_right=1e308", "--format", "json"], "supports.z_right");
    }
    // a long span relative to the rotor: caught through ρ̄s, naming the span
    rejects(&args(&dim("supports.z_right=5000")), "supports.z_right");
}

#[test]
fn regression_support_stiffness_1e308_gave_stable_none() {
    for side in ["left", "right"] {
        let set = format!("supports.stiffness_{side}=1e308");
        rejects(&["stability", "--config", &examples("dimensional.toml"), "--set", &set], &format!("supports.stiffness_{side}"));
    }
}

#[test]
fn regression_dimensionless_extremes_gave_infinities_and_300_digit_numbers() {
    for (set, field) in [
        ("dimensionless.rho_s=1e-308", "dimensionless.rho_s"),
        ("dimensionless.l_left=-1e308", "dimensionless.l_left"),
        ("dimensionless.delta_a=1e308", "dimensionless.delta_a"),
        ("dimensionless.z_a=1e308", "dimensionless.z_a"),
        ("dimensionless.c_sigma=1e308", "dimensionless.c_sigma"),
        ("dimensionless.h_x=1e308", "dimensionless.h_x"),
        ("dimensionless.r0=1e308", "dimensionless.r0"),
    ] {
        rejects(&["critical", "--set", set], field);
    }
}

#[test]
fn regression_planar_extremes_were_accepted_or_unnamed() {
    for (set, field) in [
        ("planar.gamma=1e308", "planar.gamma"),
        ("planar.k=1e308", "planar.k"),
        ("drive.torque=1e308", "drive.torque"),
        ("planar.m3=1e308", "planar.m3"),
        ("integration.rtol=1", "integration.rtol"),
    ] {
        let mut a = vec!["simulate", "--set", set];
        if set.starts_with("drive.torque") {
            a.extend(["--set", "drive.kind=torque"]);
        }
        rejects(&a, field);
    }
}

#[test]
fn regression_omega_max_1e308_printed_a_309_digit_speed() {
    rejects(&["stability", "--omega-max", "1e308"], "--omega-max");
    rejects(&["campbell", "--omega-max", "1e308"], "--omega-max");
    rejects(&["critical", "--set", "analysis.omega_max=1e308"], "analysis.omega_max");
}

#[test]
fn regression_negative_ball_drag_named_balancer_ball_drag() {
    rejects(&args(&dim("balancer.drag=-1")), "balancer.drag");
}

#[test]
fn regression_same_key_on_both_sweep_axes_let_one_win() {
    rejects(&["sweep", "--x", "drive.b=1:2:2", "--y", "drive.b=3:4:2"], "--y drive.b");
    rejects(&["map", "--x", "dimensionless.z_a=0:1:3", "--y", "dimensionless.z_a=0:1:3"], "--y dimensionless.z_a");
}

#[test]
fn regression_config_dev_zero_read_until_memory_ran_out() {
    if std::path::Path::new("/dev/zero").exists() {
        rejects(&["critical", "--config", "/dev/zero"], "--config /dev/zero");
    }
}

#[test]
fn regression_a_thousand_balls_hung_critical() {
    rejects(&args(&dim("balancer.balls=1000")), "balancer.balls");
    rejects(&["critical", "--set", "dimensionless.n=10000"], "dimensionless.n");
    // at the limit every analytic command finishes (n = 30 took 4.5 s, n = 100 80 s before)
    for cmd in ["critical", "stability", "campbell", "inertia"] {
        let (code, _, err) = run_for(
            Duration::from_secs(60),
            &[cmd, "--config", &examples("dimensional.toml"), "--set", "balancer.balls=100", "--set", "balancer.ball_mass=0.001"],
        );
        assert_eq!(code, 0, "{cmd}: {err}");
    }
}

#[test]
fn regression_closed_stdout_panicked() {
    // `autobal … | head -1`: the reader goes away; the command must end quietly
    for a in [&["campbell", "--points", "3000", "--format", "json"][..], &["critical"][..], &["stability", "--format", "json"][..]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_autobal")).args(a).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
        drop(child.stdout.take()); // closed before the command writes
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.is_empty(), "autobal {}: {err}", a.join(" "));
        assert_eq!(out.status.code(), Some(0), "autobal {}", a.join(" "));
    }
}

#[test]
fn regression_map_omega_axis_1e308_failed_in_the_eigen_solver() {
    rejects(&["map", "--x", "omega=0:1e308:3", "--y", "dimensionless.z_a=0:1:3", "--out", "m"], "--x omega");
}

#[test]
fn regression_planar_k_1e_300_stopped_without_naming_the_field() {
    // sqrt(k/m0) = 1e-150 rad/s: the integrator stopped with "step size underflow at t = 0"
    rejects(&["simulate", "--set", "planar.k=1e-300", "--set", "drive.t_end=1"], "planar.k");
    // and 1e13 N/m on 1e-9 kg: 1e11 rad/s, billions of steps per simulated second
    rejects(&["simulate", "--set", "planar.k=1e13", "--set", "planar.m1=1e-9", "--set", "planar.m2=0", "--set", "planar.m3=1e-9"], "planar.k");
}

#[test]
fn regression_numbers_in_type_errors_printed_in_full() {
    // found by the fuzzing harness: "expected an array of numbers, got 0.000…(300 digits)…9456"
    let line = rejects(&["simulate", "--set", "drive.psi0=1e-300"], "drive.psi0");
    assert!(line.contains("got 1e-300"), "{line}");
    // an integer beyond i64 was read as a string ("expected a number, got the string …")
    let line = rejects(&["critical", "--set", "dimensionless.c_sigma=-27213779405634345000000000"], "dimensionless.c_sigma");
    assert!(line.contains("must lie in"), "{line}");
}

#[test]
fn regression_unbalance_on_the_axis_gave_an_infinite_mass_limit() {
    // found by the fuzzing harness: r0 = 1e-300 made [m̄0] = 2 [ΔĀ0]/r0² infinite (JSON null)
    let (code, out, err) = run_for(Duration::from_secs(20), &["critical", "--set", "dimensionless.r0=1e-300", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["sensitivity"]["m0_limit"].is_null(), "no limit for an unbalance on the axis");
}

#[test]
fn regression_sweep_axes_bypassed_the_ranges() {
    // sweeps set their axes through the library's parameter paths, which checked only finiteness:
    // planar.gamma = 1e300 ran; the ranges now hold in PlanarRotor/PlanarProblem::validate
    rejects(&["sweep", "--x", "planar.gamma=1e300:1e301:2", "--out", "sw"], "planar.gamma");
    rejects(&["sweep", "--x", "planar.k=1e-300:1e-299:2", "--out", "sw"], "planar.k");
    rejects(&["sweep", "--x", "integration.rtol=0.5:1:2", "--out", "sw"], "integration.rtol");
}

#[test]
fn regression_boundary_stepped_off_the_plane_and_failed() {
    // `map --boundary` over h_s from 0.001: the tracer's corrector stepped to h_s = -0.0105 just
    // beyond the plane's end, the model refused it, and the whole command failed naming a value
    // the user never gave; a curve now ends where the model refuses its parameter
    let (code, _, err) =
        run_for(Duration::from_secs(60), &["map", "--x", "dimensionless.h_s=0.001:2:3", "--y", "omega=0.05:10:3", "--boundary", "--out", "hs"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("boundary: ") && !err.contains("boundary: 0 curves"), "{err}");
}
