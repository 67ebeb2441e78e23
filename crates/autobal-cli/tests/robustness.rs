//! Regression tests for hostile input, end to end, each named after the defect it guards
//! against (issue 12). Every run has a wall-clock limit: a hang fails the test instead of
//! hanging the suite. The ranges are stated in `autobal::limits` and docs/reference/robustness.md.

mod common;
use common::{examples, run_in};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Run the binary with `args` for at most `limit` in this test binary's scratch folder;
/// `(exit code, stdout, stderr)`. A run past the limit is killed and fails the test.
fn run_for(limit: Duration, args: &[&str]) -> (i32, String, String) {
    let dir = std::env::temp_dir().join(format!("autobal-robustness-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    run_in(&dir, limit, args)
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

// ---- issue 23: outputs that never destroy or corrupt, merge that verifies -------------------

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-out-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &std::path::Path) -> String {
    p.to_str().unwrap().to_string()
}

/// No temporary `*.part` file left in `d`.
#[track_caller]
fn no_part_files(d: &std::path::Path) {
    let left: Vec<String> =
        std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).filter(|n| n.ends_with(".part")).collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}

/// Every line of a CSV is complete: ends with a line end and has the header's field count.
#[track_caller]
fn csv_is_whole(p: &std::path::Path) -> usize {
    let text = std::fs::read_to_string(p).unwrap();
    assert!(text.ends_with('\n'), "{}: ends mid-row", p.display());
    let mut lines = text.lines();
    let width = lines.next().unwrap().split(',').count();
    let mut n = 0;
    for (i, l) in lines.enumerate() {
        assert_eq!(l.split(',').count(), width, "{} line {}: `{l}`", p.display(), i + 2);
        for f in l.split(',') {
            assert!(f.is_empty() || f.parse::<f64>().is_ok(), "{} line {}: `{f}`", p.display(), i + 2);
        }
        n += 1;
    }
    n
}

/// A small planar sweep's args over 6 points.
const SMALL_SWEEP: [&str; 8] = ["sweep", "--threads", "1", "--x", "drive.b=2:3:6", "--set", "drive.t_end=0.5", "--format=json"];

#[test]
fn regression_out_equal_to_an_input_overwrote_it() {
    let d = scratch("same");
    // the config as the CSV simulate writes
    let cfg = d.join("run.csv");
    std::fs::copy(examples("planar.toml"), &cfg).unwrap();
    let before = std::fs::read(&cfg).unwrap();
    let line = rejects(&["simulate", "--config", &s(&cfg), "--out", &s(&cfg)], "--out");
    assert!(line.contains("--config"), "{line}");
    // a sweep whose JSON would be the config, spelled another way (./)
    let cfg2 = d.join("sw.json");
    std::fs::copy(examples("planar.toml"), &cfg2).unwrap();
    let mut a = SMALL_SWEEP.to_vec();
    let stem = format!("{}/./sw", d.display());
    a.extend(["--config", cfg2.to_str().unwrap(), "--out", &stem]);
    rejects(&a, "--out");
    assert_eq!(std::fs::read(&cfg).unwrap(), before);
    assert_eq!(std::fs::read(&cfg2).unwrap(), before);
    // a shard as the merge's output
    let mut a = SMALL_SWEEP.to_vec();
    let sh = s(&d.join("sh1"));
    a.extend(["--shard", "1/1", "--out", &sh]);
    let (code, _, err) = run_for(Duration::from_secs(60), &a);
    assert_eq!(code, 0, "{err}");
    let shard_before = std::fs::read(d.join("sh1.csv")).unwrap();
    let line = rejects(&["merge", &format!("{sh}.csv"), "--out", &sh], "--out");
    assert!(line.contains("shard"), "{line}");
    assert_eq!(std::fs::read(d.join("sh1.csv")).unwrap(), shard_before);
    no_part_files(&d);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_out_folder_wrote_hidden_nameless_files() {
    let d = scratch("dir");
    let runs = format!("{}/runs/", d.display());
    let (code, _, err) = run_for(Duration::from_secs(60), &["simulate", "--set", "drive.t_end=1", "--out", &runs]);
    assert_eq!(code, 0, "{err}");
    assert!(d.join("runs/simulation.csv").is_file() && !d.join("runs/.csv").exists(), "{err}");
    assert!(d.join("runs/simulation_amplitude_omega.svg").is_file());
    // an existing folder without the slash
    let (code, _, err) = run_for(Duration::from_secs(60), &["map", "--x", "dimensionless.z_a=-2:2:3", "--y", "omega=0.1:2:3", "--out", &s(&d)]);
    assert_eq!(code, 0, "{err}");
    assert!(d.join("stability-map.csv").is_file() && d.join("stability-map.png").is_file());
    let mut a = SMALL_SWEEP.to_vec();
    a.extend(["--out", &runs]);
    let (code, _, err) = run_for(Duration::from_secs(60), &a);
    assert_eq!(code, 0, "{err}");
    assert!(d.join("runs/sweep.csv").is_file() && d.join("runs/sweep.json").is_file());
    no_part_files(&d);
    no_part_files(&d.join("runs"));
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_basins_found_its_out_unusable_after_the_grid() {
    // --n 1000 is a million runs: the unusable --out must fail before any of them
    for out in ["/dev/null/basins.csv", "/dev/null"] {
        rejects(&["basins", "--config", &examples("spatial.toml"), "--n", "1000", "--out", out], "--out");
    }
    rejects(&["map", "--x", "dimensionless.z_a=-2:2:3", "--y", "omega=0.1:2:3", "--out", "/dev/null/m"], "--out");
    rejects(&["stability", "--svg", "/dev/null/x.svg"], "--svg");
    rejects(&["campbell", "--svg", "/dev/null/x"], "--svg");
    rejects(&["report", "--quick", "--out", "/dev/null/rep"], "--out");
}

/// Every file under `d`, relative, sorted (folders end with `/`).
fn tree(d: &std::path::Path) -> Vec<String> {
    fn walk(base: &std::path::Path, d: &std::path::Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(base).unwrap().to_string_lossy().into_owned();
            if p.is_dir() {
                out.push(format!("{rel}/"));
                walk(base, &p, out);
            } else {
                out.push(rel);
            }
        }
    }
    let mut v = vec![];
    walk(d, d, &mut v);
    v.sort();
    v
}

#[test]
fn regression_out_dev_full_was_a_stem_and_wrote_into_dev() {
    // `--out /dev/full` was taken as a stem: `/dev/full.csv` and the figures were written into
    // /dev (as root). An output named after a device, FIFO or socket, or put into /dev, /proc,
    // /sys, is refused before the run, with nothing written.
    let map = ["map", "--x", "dimensionless.z_a=-2:2:3", "--y", "omega=0.1:2:3", "--out"];
    let sim = ["simulate", "--set", "drive.t_end=1", "--out"];
    let mut sweep = SMALL_SWEEP.to_vec();
    sweep.push("--out");
    let stem = format!("/dev/autobal-test-{}", std::process::id());
    for out in ["/dev/full", "/dev/null", stem.as_str()] {
        if out != stem && !std::path::Path::new(out).exists() {
            continue;
        }
        for cmd in [&map[..], &sim[..], &sweep[..]] {
            let line = rejects(&[cmd, &[out]].concat(), "--out");
            assert!(line.contains("device") || line.contains("system folder /dev"), "{line}");
        }
        rejects(&["campbell", "--svg", out], "--svg");
        rejects(&["stability", "--svg", out], "--svg");
        rejects(&["basins", "--config", &examples("spatial.toml"), "--n", "2", "--out", out], "--out");
        rejects(&["report", "--quick", "--out", out], "--out");
        rejects(&["export-model", "--out", out], "--out");
        let left: Vec<_> = std::fs::read_dir("/dev")
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(std::path::Path::new(out).file_name().unwrap().to_str().unwrap()) && n.contains(['.', '_']))
            .collect();
        assert!(left.is_empty(), "written into /dev: {left:?}");
    }
    for out in ["/proc/autobal-x", "/sys/autobal/x"] {
        let line = rejects(&[&sim[..], &[out]].concat(), "--out");
        assert!(line.contains("system folder"), "{line}");
    }
    // a relative folder not made yet, run from /proc: looked up from the current folder (was
    // "cannot create the folder zz"; as root in /dev it would have made /dev/zz)
    if std::path::Path::new("/proc").is_dir() {
        let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args([&sim[..], &["zz/m"]].concat()).current_dir("/proc").output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.starts_with("error: --out: zz/m.csv is in the system folder /proc"), "{err}");
    }
    #[cfg(unix)]
    {
        // a FIFO as the stem: its outputs would go beside it
        let d = scratch("fifo");
        let fifo = d.join("pipe");
        if Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
            for cmd in [&map[..], &sim[..]] {
                let line = rejects(&[cmd, &[s(&fifo).as_str()]].concat(), "--out");
                assert!(line.contains("FIFO"), "{line}");
            }
            assert_eq!(tree(&d), ["pipe"]);
            // a single file named with its extension is that file, whatever sits at its stem
            // (was refused: "pipe is a FIFO ... outputs would go beside it")
            let svg = d.join("pipe.svg");
            let (code, _, err) = run_for(Duration::from_secs(120), &["stability", "--svg", &s(&svg)]);
            assert_eq!(code, 0, "{err}");
            assert_eq!(tree(&d), ["pipe", "pipe.svg"]);
        }
        std::fs::remove_dir_all(&d).ok();
    }
}

#[test]
fn regression_a_failed_run_left_the_empty_output_folder_it_made() {
    // the output check created a missing `--out` folder before the config was read: a run that
    // then failed left an empty folder. Now a check writes nothing; the folder is made when the
    // first output is written. Each bad `--out` spelling also leaves the inputs as they were.
    let d = scratch("nothing");
    let cfg = d.join("bad.toml");
    std::fs::write(&cfg, "[planar]\nm3 = -1\n").unwrap();
    let c = s(&cfg);
    let out = |n: &str| s(&d.join(n).join("deeper/x"));
    let runs: Vec<(Vec<String>, &str)> = vec![
        (vec!["simulate".into(), "--config".into(), c.clone(), "--out".into(), out("a")], "planar.m3"),
        (vec!["sweep".into(), "--config".into(), c.clone(), "--x".into(), "drive.b=2:3:2".into(), "--out".into(), out("b")], "planar.m3"),
        (vec!["basins".into(), "--config".into(), c.clone(), "--n".into(), "2".into(), "--out".into(), out("c")], "planar.m3"),
        (vec!["stability".into(), "--config".into(), c.clone(), "--svg".into(), out("d")], "planar.m3"),
        (vec!["campbell".into(), "--config".into(), c.clone(), "--svg".into(), out("e")], "planar.m3"),
        (vec!["report".into(), "--config".into(), c.clone(), "--out".into(), out("f")], "planar.m3"),
        (
            vec![
                "map".into(),
                "--config".into(),
                c.clone(),
                "--x".into(),
                "planar.k=1:2:2".into(),
                "--y".into(),
                "omega=1:2:2".into(),
                "--out".into(),
                out("g"),
            ],
            "--x",
        ),
    ];
    for (a, field) in &runs {
        rejects(&args(a), field);
    }
    // an input as the output, a folder, a path under a file: refused, inputs untouched
    let before = std::fs::read(&cfg).unwrap();
    rejects(&["stability", "--config", &c, "--svg", &c], "--svg");
    rejects(&["basins", "--config", &c, "--out", &c], "--out");
    rejects(&["stability", "--svg", &format!("{c}/x.svg")], "--svg");
    rejects(&["basins", "--out", &format!("{c}/x.csv")], "--out");
    assert_eq!(std::fs::read(&cfg).unwrap(), before);
    assert_eq!(tree(&d), ["bad.toml"], "a failed run left files or folders");
    // a run that succeeds makes its folders
    let (code, _, err) = run_for(Duration::from_secs(60), &["stability", "--svg", &out("ok")]);
    assert_eq!(code, 0, "{err}");
    assert!(d.join("ok/deeper/x").is_file());
    std::fs::remove_dir_all(&d).ok();
}

/// Two shards of [`SMALL_SWEEP`] in `d`: `a1.csv`, `a2.csv` (with their JSON).
fn two_shards(d: &std::path::Path) -> (String, String) {
    let mut names = vec![];
    for k in 1..=2 {
        let stem = s(&d.join(format!("a{k}")));
        let spec = format!("{k}/2");
        let mut a = SMALL_SWEEP.to_vec();
        a.extend(["--shard", &spec, "--out", &stem]);
        let (code, _, err) = run_for(Duration::from_secs(60), &a);
        assert_eq!(code, 0, "{err}");
        names.push(format!("{stem}.csv"));
    }
    (names[0].clone(), names[1].clone())
}

#[test]
fn regression_merge_copied_a_shard_cut_mid_row() {
    let d = scratch("cut");
    let (a1, a2) = two_shards(&d);
    let out = s(&d.join("m"));
    let (code, _, err) = run_for(Duration::from_secs(30), &["merge", &a1, &a2, "--out", &out]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(csv_is_whole(&d.join("m.csv")), 6);
    std::fs::remove_file(d.join("m.csv")).unwrap();
    std::fs::remove_file(d.join("m.json")).unwrap();
    // cut mid-row: the last row loses its end
    let text = std::fs::read_to_string(&a2).unwrap();
    std::fs::write(&a2, &text[..text.len() - 7]).unwrap();
    let line = rejects(&["merge", &a1, &a2, "--out", &out], &a2);
    assert!(line.contains("line 4"), "{line}");
    // cut at a line end: a whole row is missing against the shard's JSON
    let cut = text[..text.len() - 1].rfind('\n').unwrap() + 1;
    std::fs::write(&a2, &text[..cut]).unwrap();
    rejects(&["merge", &a1, &a2, "--out", &out], &a2);
    // a number edited into garbage
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[2] = lines[2].replacen(",", ",x", 1);
    std::fs::write(&a2, lines.join("\n") + "\n").unwrap();
    let line = rejects(&["merge", &a1, &a2, "--out", &out], &a2);
    assert!(line.contains("line 3") && line.contains("not a number"), "{line}");
    assert!(!d.join("m.csv").exists() && !d.join("m.json").exists());
    no_part_files(&d);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_merge_accepted_another_sweeps_shard() {
    let d = scratch("other");
    let (a1, a2) = two_shards(&d);
    let j2 = a2.replace(".csv", ".json");
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&j2).unwrap()).unwrap();
    let sum = v["definition_checksum"].as_str().expect("a checksum in the shard's JSON").to_string();
    assert!(sum.starts_with("fnv1a64:"), "{sum}");
    v["definition_checksum"] = serde_json::json!("fnv1a64:0000000000000000");
    std::fs::write(&j2, v.to_string()).unwrap();
    let (code, _, err) = run_for(Duration::from_secs(30), &["merge", &a1, &a2, "--out", &s(&d.join("m"))]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("different sweeps") && err.contains(&a1) && err.contains(&a2), "{err}");
    assert!(!d.join("m.csv").exists());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_merge_named_the_wrong_shard_as_duplicated() {
    let d = scratch("dup");
    let (a1, a2) = two_shards(&d);
    let copy = s(&d.join("copy.csv"));
    std::fs::copy(&a1, &copy).unwrap();
    std::fs::copy(a1.replace(".csv", ".json"), d.join("copy.json")).unwrap();
    let (code, _, err) = run_for(Duration::from_secs(30), &["merge", &a2, &copy, &a1, "--out", &s(&d.join("m"))]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("shard 1 of 2 is given twice") && err.contains(&copy) && err.contains(&a1), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_merge_dev_zero_read_2_gb() {
    let d = scratch("zero");
    if std::path::Path::new("/dev/zero").exists() {
        rejects(&["merge", "/dev/zero", "--out", &s(&d.join("m"))], "/dev/zero");
    }
    rejects(&["merge", &s(&d), "--out", &s(&d.join("m"))], &s(&d));
    // an empty file with an empty JSON beside it
    std::fs::write(d.join("e.csv"), "").unwrap();
    std::fs::write(d.join("e.json"), "").unwrap();
    rejects(&["merge", &s(&d.join("e.csv")), "--out", &s(&d.join("m"))], &s(&d.join("e.json")));
    assert!(!d.join("m.csv").exists());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_verdict_map_wrote_nan_margins() {
    let d = scratch("verdict");
    let (code, _, err) = run_for(
        Duration::from_secs(60),
        &["map", "--quantity", "verdict", "--x", "dimensionless.z_a=-2:2:3", "--y", "omega=0.1:2:3", "--out", &s(&d.join("v"))],
    );
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(d.join("v.csv")).unwrap();
    assert!(!text.to_lowercase().contains("nan"), "{text}");
    assert_eq!(csv_is_whole(&d.join("v.csv")), 9);
    assert!(text.lines().nth(1).unwrap().contains(",,"), "the margin field is empty: {text}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_set_without_key_or_with_a_table_did_not_name_set() {
    rejects(&["critical", "--set", "=1"], "--set =1");
    rejects(&["critical", "--set", "dimensionless={c_sigma=1}"], "--set dimensionless");
    rejects(&["critical", "--set", "dimensionless.c_sigma.x=1"], "--set dimensionless.c_sigma.x");
    // a table as a field's value names the field
    rejects(&["critical", "--set", "dimensionless.c_sigma={a=1}"], "dimensionless.c_sigma");
}

/// Start `args` in `d`, send SIGINT after `after`, and return `(exit code, stdout, stderr)`.
#[cfg(unix)]
fn interrupt_after(d: &std::path::Path, after: Duration, args: &[&str]) -> (i32, String, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).current_dir(d).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    std::thread::sleep(after);
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let t0 = Instant::now();
    let out = child.wait_with_output().unwrap();
    assert!(t0.elapsed() < Duration::from_secs(60), "autobal {} ignored Ctrl-C", args.join(" "));
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn regression_an_empty_config_said_simulate_needs_a_planar_table() {
    // every command reads a config that is neither spatial nor linear as a planar one; an
    // empty file made `stability`, `critical`, ... say "`simulate` needs a [planar] table"
    let d = scratch("empty-config");
    let e = d.join("empty.toml");
    std::fs::write(&e, "").unwrap();
    for cmd in ["stability", "critical", "campbell", "ranges", "simulate"] {
        let line = rejects(&[cmd, "--config", &s(&e)], "planar");
        assert!(line.contains("no rotor") && line.contains("[linear_rotor]") && !line.contains("`simulate`"), "{line}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_set_key_given_twice_let_the_last_win_silently() {
    // `--set rotor.mass=2 --set rotor.mass=3` ran with 3, the first ignored without a word
    let dim = examples("dimensional.toml");
    let shaft = examples("linear_rotor_shaft.toml");
    let cases: [&[&str]; 5] = [
        &["critical", "--config", &dim, "--set", "rotor.mass=2", "--set", " rotor.mass = 3"],
        &["simulate", "--set", "planar.k=1", "--set", "planar.k=2"],
        &["stability", "--config", &shaft, "--set", "linear_rotor.drag=1", "--set", "linear_rotor.drag=2"],
        &["sweep", "--x", "drive.b=1", "--set", "drive.t_end=1", "--set", "drive.t_end=1"],
        &["basins", "--n", "2", "--set", "drive.t_end=1", "--set", "drive.t_end=2"],
    ];
    for a in cases {
        let key = a[a.len() - 1].split('=').next().unwrap().trim();
        let line = rejects(a, &format!("--set {key}"));
        assert!(line.contains("given twice"), "{line}");
    }
}

#[test]
fn regression_linear_rotor_omega_max_1e308_named_speeds_twice() {
    let shaft = examples("linear_rotor_shaft.toml");
    let line = rejects(&["stability", "--config", &shaft, "--set", "linear_rotor.omega_max=1e308"], "linear_rotor.omega_max");
    assert!(line.contains("(0, 1e6] rad/s"), "{line}");
    // the bound itself is taken
    let (code, _, err) = run_for(Duration::from_secs(120), &["stability", "--config", &shaft, "--set", "linear_rotor.omega_max=1e6", "--samples", "10"]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn regression_shaft_builder_extremes_named_internal_matrices_or_passed() {
    // the shaft builder's inputs had no upper bounds: `length = 1e300` failed as
    // `linear_rotor.m[0,3]: ... inf`, `diameter = 0` was blamed on inner_diameter, `e = 1e300`
    // as an eigenvalue solver that did not converge (no field), a disk of 1e300 kg was taken
    let d = scratch("shaft-extremes");
    let text = std::fs::read_to_string(examples("linear_rotor_shaft.toml")).unwrap();
    let cases = [
        ("length = 0.1", "length = 1e300", "linear_rotor.elements[0].length", "[1e-6, 10000] m"),
        ("length = 0.1", "length = 1e-300", "linear_rotor.elements[0].length", "[1e-6, 10000] m"),
        ("diameter = 0.025", "diameter = 0", "linear_rotor.elements[0].diameter", "[1e-6, 1000] m"),
        ("diameter = 0.025", "diameter = 1e200", "linear_rotor.elements[0].diameter", "[1e-6, 1000] m"),
        ("e = 2.1e11", "e = 1e300", "linear_rotor.elements[0].e", "(0, 1e13] Pa"),
        ("rho = 7850.0", "rho = 1e300", "linear_rotor.elements[0].rho", "(0, 100000] kg/m³"),
        ("mass = 4.0", "mass = 1e300", "linear_rotor.disks[0].mass", "[0, 1e9] kg"),
        ("id = 0.01", "id = 1e300", "linear_rotor.disks[0].id", "[0, 1e12] kg·m²"),
        ("ip = 0.02", "ip = 1e300", "linear_rotor.disks[0].ip", "[0, 1e12] kg·m²"),
        // bearings (`k = 1e300` ended in an eigenvalue solver that did not converge), the
        // balancer and the unbalance (1e300 was taken) get the spatial rotor's bounds
        ("k = 2e6", "k = 1e300", "linear_rotor.bearings[0].k", "[0, 1e13] N/m"),
        ("c = 300.0", "c = 1e300", "linear_rotor.bearings[0].c", "[0, 1e12] N·s/m"),
        ("kxx = [2e6, 3e6]", "kxx = [2e6, -1e300]", "linear_rotor.bearings[1].kxx[1]", "[-1e13, 1e13] N/m"),
        ("radius = 0.06", "radius = 1e300", "linear_rotor.balancer[0].radius", "(0, 1000] m"),
        ("ball_mass = 0.02", "ball_mass = 1e300", "linear_rotor.balancer[0].ball_mass", "(0, 1e9] kg"),
        ("me = 2e-4", "me = 1e300", "linear_rotor.unbalance[0].me", "[-1e12, 1e12] kg·m"),
    ];
    let cfg = d.join("c.toml");
    for (from, to, field, range) in cases {
        assert!(text.contains(from), "{from}");
        std::fs::write(&cfg, text.replacen(from, to, 1)).unwrap();
        let line = rejects(&["stability", "--config", &s(&cfg), "--samples", "10"], field);
        assert!(line.contains(range), "{line}");
    }
    // the bounds themselves are taken (each alone on the example)
    for (from, to) in [
        ("length = 0.1", "length = 1e-6"),
        ("diameter = 0.025", "diameter = 1e3"),
        ("e = 2.1e11", "e = 1e13"),
        ("mass = 4.0", "mass = 1e9"),
        ("k = 2e6", "k = 1e13"),
    ] {
        std::fs::write(&cfg, text.replacen(from, to, 1)).unwrap();
        let (code, _, err) = run_for(Duration::from_secs(120), &["stability", "--config", &s(&cfg), "--samples", "10"]);
        assert_eq!(code, 0, "{to}: {err}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(target_os = "linux")]
#[test]
fn regression_a_fifo_nobody_writes_as_config_or_matrix_hung() {
    // the blocking open of a named pipe waits for a writer: `--config fifo` and a matrix file
    // that is a FIFO hung for ever. Opened non-blocking, with no writer they read as empty at
    // once (one line naming the field; a config pipe with no writer is named as such, was
    // reported as a config without a rotor); `run_for`'s limit fails a hang
    let d = scratch("fifo-input");
    let fifo = d.join("pipe");
    if !Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
        return;
    }
    for cmd in ["critical", "simulate", "stability"] {
        let line = rejects(&[cmd, "--config", &s(&fifo)], &format!("--config {}", s(&fifo)));
        assert!(line.ends_with("is a named pipe with no writer (nothing to read); start the program that writes it first, or give a file"), "{line}");
    }
    // a pipe with its writer's data is read (`--config /dev/stdin`): written and closed
    // before the binary opens it, the data stays in the pipe (the child's stdin holds it open)
    let mut child = Command::new(env!("CARGO_BIN_EXE_autobal"))
        .args(["critical", "--config", "/dev/stdin"])
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    {
        use std::io::Write;
        let mut stdin = child.stdin.take().unwrap();
        stdin.write_all(std::fs::read_to_string(examples("default.toml")).unwrap().as_bytes()).unwrap();
    }
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    let cfg = d.join("c.toml");
    std::fs::write(&cfg, "[linear_rotor]\nm = \"pipe\"\nk = \"pipe\"\n").unwrap();
    let line = rejects(&["stability", "--config", &s(&cfg)], "linear_rotor.m");
    // (read as "empty file" before round 3; named as the config's pipe is now)
    assert!(line.ends_with("is a named pipe with no writer (nothing to read); start the program that writes it first, or give a file"), "{line}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_an_empty_bearing_speed_table_was_blamed_on_kxx() {
    // `speeds = []` was reported as "kxx: has 2 entries, one per speed: 0"
    let d = scratch("empty-speeds");
    let text = std::fs::read_to_string(examples("linear_rotor_shaft.toml")).unwrap();
    assert!(text.contains("speeds = [0.0, 1000.0]"));
    let cfg = d.join("c.toml");
    std::fs::write(&cfg, text.replace("speeds = [0.0, 1000.0]", "speeds = []")).unwrap();
    let line = rejects(&["stability", "--config", &s(&cfg)], "linear_rotor.bearings[1].speeds");
    assert!(line.contains("is empty"), "{line}");
    std::fs::remove_dir_all(&d).ok();
}

// Session 23: the closed-form and general routes of `stability` ended at once on Ctrl-C (exit
// 130, "this command keeps no partial result", regression_ctrl_c_ended_stability_without_a_word);
// now every route keeps what it analysed, as a linear rotor's (below).
/// Ctrl-C during a million speeds (which no machine analyses in 1.5 s: the closed form's 12 × 12
/// eigenvalues take microseconds a speed, the general route's Newton more) on the closed-form
/// route (examples/default.toml) and the general route (examples/planar.toml): exit status 2,
/// one line on standard error saying how many speeds were analysed; the table printed, its
/// first line INCOMPLETE; the `--svg` figure written and marked incomplete; the JSON valid,
/// `complete: false`, holding as many speeds as the line says.
#[cfg(unix)]
#[test]
fn ctrl_c_keeps_what_every_route_s_stability_analysed() {
    let d = scratch("ctrlc-routes");
    // the speeds each route's JSON keeps: the closed form's margins, the general route's points
    for (cfg, kept_key) in [("default.toml", "max_real_part"), ("planar.toml", "points")] {
        let cfg = examples(cfg);
        let (code, out, err) = interrupt_after(&d, Duration::from_millis(1500), &["stability", "--config", &cfg, "--samples", "1000000", "--svg", "s.svg"]);
        assert_eq!(code, 2, "{cfg}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.starts_with("error: interrupted: ")
                && err.contains(" speeds analysed; what was analysed is printed (its stable ranges end where the scan stopped"),
            "{err}"
        );
        assert!(out.starts_with("INCOMPLETE (interrupted: "), "{cfg}: {out}");
        let svg = std::fs::read_to_string(d.join("s.svg")).expect("the figure of what was analysed");
        assert!(svg.contains("INCOMPLETE: ") && svg.contains("scan stopped"), "{cfg}: the figure is not marked");
        std::fs::remove_file(d.join("s.svg")).unwrap();
        let (code, out, err) = interrupt_after(&d, Duration::from_millis(1500), &["stability", "--config", &cfg, "--samples", "1000000", "--format", "json"]);
        assert_eq!(code, 2, "{cfg}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).expect("the kept speeds as valid JSON");
        assert_eq!(v["complete"], false);
        let kept = v[kept_key].as_array().map_or(0, |p| p.len());
        assert!(kept > 0 && err.contains(&format!("interrupted: {kept} of ")), "{cfg}: {kept} {err}");
        assert_eq!(v["stopped"].as_str(), err.trim_end().strip_prefix("error: "));
    }
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_ctrl_c_on_a_linear_rotor_s_stability_kept_nothing() {
    // audit 21's F2: on a linear rotor config `stability` can run for minutes (three balls on
    // a 28-DOF rotor), and Ctrl-C ended it at once with nothing. Now its scan stops, prints the
    // speeds analysed and ends with one line saying how many (exit 2, not 130).
    // (a million speeds cannot finish in 1.5 s: the run is always stopped). Review 22: the
    // first version sent standard output to nothing, so it passed whether or not anything was
    // kept; what is printed is now read: valid JSON, `complete: false`, the speeds analysed.
    let d = scratch("ctrlc-linear");
    let cfg = examples("linear_rotor_shaft.toml");
    let child = Command::new(env!("CARGO_BIN_EXE_autobal"))
        .args(["stability", "--config", &cfg, "--samples", "1000000", "--format", "json"])
        .current_dir(&d)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.starts_with("error: interrupted: ") && err.contains(" of 1000000 speeds analysed; what was analysed is printed"), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("the kept speeds as valid JSON");
    assert_eq!(v["complete"], false);
    let kept = v["points"].as_array().map_or(0, |p| p.len());
    assert!((1..1_000_000).contains(&kept) && err.contains(&format!("interrupted: {kept} of 1000000")), "{kept} {err}");
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_ctrl_c_with_stderr_closed_killed_the_handler_not_the_process() {
    // the Ctrl-C handler wrote its line with `eprintln!`, which panics when standard error is a
    // closed pipe: the handler's thread died before its `exit(130)` and the process ran on,
    // ignoring every further Ctrl-C. Now the line's write error is ignored and it exits.
    // (`ranges`, which does not poll the control, on the washer under gravity: ~2 s of
    // periodic orbits; `stability` with a million samples until session 23, when it came to
    // poll the control and so to end by its own stop, exit 2, not by the handler)
    let d = scratch("ctrlc-closed-stderr");
    let cfg = examples("washing_machine.toml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_autobal"))
        .args(["ranges", "--config", &cfg, "--set", "spatial.gravity=[0.0, -9.81, 0.0]"])
        .current_dir(&d)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    std::thread::sleep(Duration::from_millis(300));
    if child.try_wait().unwrap().is_some() {
        // finished before the Ctrl-C (a machine far faster than this one's 2 s)
        std::fs::remove_dir_all(&d).ok();
        return;
    }
    let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
    let t0 = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        // the handler exits at once; 20 s is far beyond a loaded machine's scheduling delay
        if t0.elapsed() > Duration::from_secs(20) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("still running 20 s after Ctrl-C with standard error closed");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    // running when the Ctrl-C came (checked just before it: the run takes seconds, the check
    // and the signal milliseconds), so it must end by the handler's exit, not by finishing
    assert_eq!(status.code(), Some(130), "{status:?}");
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_ctrl_c_left_truncated_or_footerless_files() {
    let d = scratch("ctrlc");
    // long runs, each stopped after a while: exit 2 saying so, or done (exit 0); either way
    // every file under its final name is whole, and no temporary file is left
    let spatial = examples("spatial.toml");
    let runs: Vec<(&str, Vec<&str>)> = vec![
        ("sim.csv", vec!["simulate", "--parquet", "--set", "drive.t_end=2000", "--set", "integration.dt=0.002", "--out", "sim.csv"]),
        ("sw.csv", vec!["sweep", "--parquet", "--threads", "1", "--x", "drive.b=1:2:4000", "--out", "sw"]),
        ("map.csv", vec!["map", "--x", "dimensionless.z_a=-2:2:2000", "--y", "omega=0.1:3:2000", "--threads", "1", "--out", "map"]),
        ("b.csv", vec!["basins", "--config", &spatial, "--n", "200", "--threads", "1", "--out", "b.csv"]),
    ];
    for (file, args) in &runs {
        let (code, _, err) = interrupt_after(&d, Duration::from_millis(1500), args);
        assert!(code == 0 || (code == 2 && err.contains("interrupted")), "autobal {}: exit {code}: {err}", args.join(" "));
        let p = d.join(file);
        if p.exists() {
            csv_is_whole(&p);
        } else {
            assert!(code != 0 && err.contains("interrupted"), "{err}");
        }
        let pq = p.with_extension("parquet");
        if pq.exists() {
            let bytes = std::fs::read(&pq).unwrap();
            assert!(bytes.len() >= 8 && &bytes[bytes.len() - 4..] == b"PAR1", "{}: no Parquet footer", pq.display());
        }
        no_part_files(&d);
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_spatial_simulate_refused_parquet_its_help_promises() {
    let d = scratch("spq");
    let stem = s(&d.join("sp"));
    let (code, _, err) =
        run_for(Duration::from_secs(60), &["simulate", "--config", &examples("spatial.toml"), "--set", "drive.t_end=20", "--parquet", "--out", &stem]);
    assert_eq!(code, 0, "{err}");
    let rows = csv_is_whole(&d.join("sp.csv"));
    let bytes = std::fs::read(d.join("sp.parquet")).unwrap();
    assert!(rows > 0 && &bytes[..4] == b"PAR1" && &bytes[bytes.len() - 4..] == b"PAR1", "{err}");
    no_part_files(&d);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_whole_number_written_2_0_was_refused_as_got_2() {
    // "expected a whole number, got 2" for `2.0`: the message must say what is wrong with it
    let (code, _, err) = run_for(Duration::from_secs(20), &["critical", "--set", "dimensionless.n=2.0"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("dimensionless.n: expected a whole number written without a decimal point (write 2), got the decimal number 2.0"), "{err}");
}

#[test]
fn regression_spatial_sample_count_was_printed_with_303_digits() {
    let spatial = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/spatial.toml");
    let (code, _, err) = run_for(Duration::from_secs(20), &["simulate", "--config", spatial, "--dt", "1e-300"]);
    assert_eq!(code, 2, "{err}");
    let line = err.lines().find(|l| l.contains("samples is too many")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.len() < 120, "{line}");
}

/// The command must succeed and say, on one warning line, that `key` has no effect.
#[track_caller]
fn warns(args: &[&str], key: &str) -> String {
    let (code, out, err) = run_for(Duration::from_secs(60), args);
    assert_eq!(code, 0, "autobal {}: exit {code}, stdout {out}, stderr {err}", args.join(" "));
    let line = err
        .lines()
        .find(|l| l.starts_with("warning: ") && l.contains(key))
        .unwrap_or_else(|| panic!("autobal {}: no warning naming {key}: {err}", args.join(" ")));
    line.to_string()
}

/// Entries silently ignored (issue 23): every entry of a config is used by the model that runs
/// it, or an error (another rotor's entry) or a warning (moot with the rest of the config)
/// names it, for every command family (autobal::config::entry_use, docs/reference/robustness.md).
#[test]
fn regression_entries_of_another_model_passed_silently() {
    let planar = ["--set", "drive.t_end=0.05", "--set", "integration.dt=0.01"];
    // the spatial rotor's entries on the planar rotor: simulate, sweep, stability, map
    for (set, key) in
        [("spatial.gravity=[0,-9.81,0]", "spatial.gravity"), ("initial.position=[1e-3,0]", "initial.position"), ("couple.mass=0.01", "couple.mass")]
    {
        let mut a = vec!["simulate", "--set", set, "--out", "s"];
        a.extend(planar);
        let line = rejects(&a, key);
        assert!(line.contains("belongs to the spatial rotor"), "{line}");
        rejects(&["sweep", "--set", set, "--x", "drive.b=1:2:2", "--out", "sw"], key);
        let p = examples("planar.toml");
        rejects(&["stability", "--config", &p, "--set", set, "--samples", "10"], key);
        rejects(&["map", "--config", &p, "--set", set, "--x", "planar.c_psi=0.1:0.2:2", "--y", "omega=100:200:2", "--out", "m"], key);
    }
    // the planar rotor's entries on the spatial rotor: simulate, sweep, basins, the analytic
    // commands, the report
    let spatial = examples("spatial.toml");
    let sp = |v: &[&'static str]| -> Vec<String> { v.iter().map(|s| s.to_string()).collect() };
    for (set, key, why) in [("drive.xy0=[1e-3,0]", "drive.xy0", "starts from [initial]"), ("planar.m1=1", "planar.m1", "planar rotor of paper 004")] {
        let short = ["--set", "drive.t_end=2", "--set", "integration.dt=1"];
        let runs: Vec<Vec<String>> = vec![
            [sp(&["simulate", "--out", "s"]), sp(&short)].concat(),
            [sp(&["sweep", "--x", "drive.omega0=1.5:1.6:2", "--out", "sw"]), sp(&short)].concat(),
            [sp(&["basins", "--n", "2", "--out", "b"]), sp(&short)].concat(),
            sp(&["critical"]),
            sp(&["campbell", "--points", "3"]),
            sp(&["report", "--quick", "--out", "rep"]),
        ];
        for mut a in runs {
            if a[0] == "report" && key == "planar.m1" {
                continue; // the report runs every rotor its config describes, [planar] too
            }
            a.extend(["--config".to_string(), spatial.clone(), "--set".to_string(), set.to_string()]);
            let line = rejects(&args(&a), key);
            assert!(line.contains(why), "{line}");
        }
    }
}

#[test]
fn regression_moot_entries_passed_silently() {
    // a second plane with zero balls but a ball mass: an error, as on the first plane; its other
    // ball keys then have no effect (the spatial simulation)
    let two = examples("spatial_two_plane.toml");
    let short = ["--set", "drive.t_end=0.01", "--set", "integration.dt=0.005", "--out", "s"];
    rejects(&[&["simulate", "--config", &two, "--set", "balancer2.balls=0"][..], &short].concat(), "balancer2.balls");
    let line =
        warns(&[&["simulate", "--config", &two, "--set", "balancer2.balls=0", "--set", "balancer2.ball_mass=0"][..], &short].concat(), "balancer2.race_radius");
    assert!(line.contains("balancer2.drag, balancer2.race_radius (with balancer2.balls = 0)") && line.contains("no effect"), "{line}");
    // real-ball keys without contact (the planar rotor)
    let line = warns(
        &["simulate", "--set", "planar.restitution=0.9", "--set", "drive.t_end=0.05", "--set", "integration.dt=0.01", "--out", "s"],
        "planar.restitution",
    );
    assert!(line.contains("(with planar.contact = false)"), "{line}");
    // the analytic commands: ball keys with no balls
    let line =
        warns(&["critical", "--config", &examples("dimensional.toml"), "--set", "balancer.balls=0", "--set", "balancer.ball_mass=0"], "balancer.race_radius");
    assert!(line.contains("(with balancer.balls = 0)"), "{line}");
    // neutral values are no entry to report: the spatial rotor's zero gravity on the planar one
    let (code, _, err) = run_for(
        Duration::from_secs(60),
        &[
            "simulate",
            "--set",
            "spatial.gravity=[0,0,0]",
            "--set",
            "spatial.lock_tilt=false",
            "--set",
            "drive.t_end=0.05",
            "--set",
            "integration.dt=0.01",
            "--out",
            "s",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning: simulate"), "{err}");
}

/// Limits stated once and true (issue 23): every limit of docs/reference/robustness.md's "Bounded cost
/// and resources" table is reached by a run that succeeds (small runs: tiny `t_end`, the
/// smallest grids) and one past it is refused with that limit's message. The input ranges
/// (`autobal::limits::LIMITS`) have their own test, crates/autobal/tests/limits_table.rs. Not
/// run at the limit, only past it (each would take minutes): `t_end/dt = 5e7` samples, axes of
/// 100 000 points, `--samples 1000000`, `--points 10000000`.
#[test]
fn regression_the_resource_limits_are_reached_and_one_past_them_refused() {
    let tiny = ["--set", "drive.t_end=1e-4", "--set", "integration.dt=1e-4"];
    let ok = |a: &[&str]| {
        let (code, out, err) = run_for(Duration::from_secs(120), a);
        assert_eq!(code, 0, "autobal {}: exit {code}, {out}{err}", a.join(" "));
    };
    // the config file: 1 MiB
    let d = std::env::temp_dir().join(format!("autobal-limits-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let text = std::fs::read_to_string(examples("planar.toml")).unwrap();
    let at = d.join("at.toml");
    let pad = (1usize << 20) - text.len() - 2;
    std::fs::write(&at, format!("{text}\n#{}", "x".repeat(pad))).unwrap();
    assert_eq!(std::fs::metadata(&at).unwrap().len(), 1 << 20);
    let (at_s, past_s) = (at.to_str().unwrap().to_string(), d.join("past.toml").to_str().unwrap().to_string());
    std::fs::write(&past_s, format!("{text}\n#{}", "x".repeat(pad + 1))).unwrap();
    ok(&[&["simulate", "--config", &at_s, "--out", "s"][..], &tiny].concat());
    let e = rejects(&["simulate", "--config", &past_s, "--out", "s"], &format!("--config {past_s}"));
    assert!(e.contains("exceeds the limit of 1048576"), "{e}");
    // balls of the planar model, and array entries (drive.psi0): 100 000 each, together (in a
    // file: the command line is too short for them)
    let psi: Vec<String> = (0..100_000).map(|i| format!("{:.6}", i as f64 * 6.283e-5)).collect();
    let many = d.join("many.toml");
    let with_psi = |extra: &str| text.replace("[drive]\n", &format!("[drive]\npsi0 = [{}{extra}]\n", psi.join(",")));
    std::fs::write(&many, with_psi("")).unwrap();
    let many = many.to_str().unwrap().to_string();
    ok(&[&["simulate", "--config", &many, "--set", "planar.n=100000", "--out", "s"][..], &tiny].concat());
    let e = rejects(&["simulate", "--set", "planar.n=100001", "--out", "s"], "planar.n");
    assert!(e.contains("exceeds the limit of 100000"), "{e}");
    let past = d.join("many_past.toml");
    std::fs::write(&past, with_psi(",0")).unwrap();
    let e = rejects(&["simulate", "--config", past.to_str().unwrap(), "--out", "s"], "drive.psi0");
    assert!(e.contains("exceeds the limit of 100000"), "{e}");
    // real balls under a method that takes implicit steps (a dense Jacobian): 300; with the
    // explicit method the planar limit, 100 000 balls in contact checked for overlaps at the
    // start in O(n log n) (that check and the contact events were O(n²))
    let real = ["--set", "planar.m3=1e-4", "--set", "planar.contact=true", "--set", "planar.ball_diameter=1e-3"];
    ok(&[&["simulate", "--set", "planar.n=300", "--out", "s"][..], &real, &tiny].concat());
    let e = rejects(&[&["simulate", "--set", "planar.n=301", "--out", "s"][..], &real].concat(), "integration.method");
    assert!(e.contains("at most 300 balls") && e.contains("dop853"), "{e}");
    let many_real = [
        "--set",
        "planar.n=100000",
        "--set",
        "planar.m3=1e-3",
        "--set",
        "planar.c_psi=0",
        "--set",
        "planar.ball_diameter=1e-6",
        "--set",
        "planar.contact=true",
    ];
    ok(&[&["simulate", "--set", "integration.method=\"dop853\"", "--set", "drive.t_end=1e-5", "--set", "integration.dt=1e-5", "--out", "s"][..], &many_real]
        .concat());
    // balls of the spatial model: 100 per plane, in the analytic commands and the simulation
    ok(&["critical", "--set", "dimensionless.n=100"]);
    rejects(&["critical", "--set", "dimensionless.n=101"], "dimensionless.n");
    let two = examples("spatial_two_plane.toml");
    let planes = ["--set", "balancer.balls=100", "--set", "balancer2.balls=100", "--set", "balancer.ball_mass=1e-4", "--set", "balancer2.ball_mass=1e-4"];
    ok(&[&["simulate", "--config", &two, "--out", "s"][..], &planes, &tiny].concat());
    rejects(&["simulate", "--config", &two, "--set", "balancer2.balls=101", "--out", "s"], "balancer2.balls");
    // the commands' own counts
    ok(&["stability", "--samples", "10"]);
    assert!(rejects(&["stability", "--samples", "9"], "--samples").contains("between 10 and 1000000"));
    assert!(rejects(&["stability", "--samples", "1000001"], "--samples").contains("between 10 and 1000000"));
    ok(&["campbell", "--points", "3"]);
    assert!(rejects(&["campbell", "--points", "2"], "--points").contains("between 3 and 10000000"));
    assert!(rejects(&["campbell", "--points", "10000001"], "--points").contains("between 3 and 10000000"));
    ok(&["map", "--x", "dimensionless.z_a=0:1:2", "--y", "omega=1:2:2", "--out", "m"]);
    assert!(
        rejects(&["map", "--x", "dimensionless.z_a=0:1:1", "--y", "omega=1:2:2", "--out", "m"], "--x dimensionless.z_a=0:1:1").contains("between 2 and 100000")
    );
    assert!(rejects(&["map", "--x", "dimensionless.z_a=0:1:100001", "--y", "omega=1:2:2", "--out", "m"], "--x dimensionless.z_a=0:1:100001")
        .contains("between 2 and 100000"));
    // simulation samples: t_end/dt ≤ 5e7
    let e = rejects(&["simulate", "--set", "drive.t_end=5.0001", "--set", "integration.dt=1e-7", "--out", "s"], "integration.dt");
    assert!(e.contains("too many"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

/// Ranges that contradicted themselves (issue 23): `map --boundary` over a field's full
/// documented range was refused by that range, the tracer stepping past the axis's ends (a
/// difference quotient beyond the closed end: "must lie in [-10000, 10000] m, got 10000"; a
/// rounding below 0: "got -9.54715e-33"; a predictor: "got -0.624512"). Found by
/// scripts/hostile.sh's generated rows over every field's range.
#[test]
fn regression_boundary_axis_over_a_fields_full_range_was_refused_by_it() {
    let dim = examples("dimensional.toml");
    for ax in ["balancer.z=-10000:10000:3", "unbalance.radius=0:1000:3", "supports.stiffness_left=10000:1e13:3"] {
        let (code, _, err) =
            run_for(Duration::from_secs(120), &["map", "--config", &dim, "--x", ax, "--y", "speed_rpm=100:20000:3", "--boundary", "--out", "mb"]);
        assert_eq!(code, 0, "--x {ax}: {err}");
    }
    for ax in ["dimensionless.h_s=0:1000:3", "dimensionless.delta_a=0:0.999999999:3"] {
        let (code, _, err) = run_for(Duration::from_secs(120), &["map", "--x", ax, "--y", "omega=0.05:4.5:3", "--boundary", "--out", "mb"]);
        assert_eq!(code, 0, "--x {ax}: {err}");
    }
}

#[test]
fn regression_a_tiny_slip_rate_was_a_non_finite_state_and_a_misfit_ball_a_contact_stiffness() {
    // issue 23's "messages that mislead": a legal but absurd slip_rate (1e-300) ended in "the
    // state became non-finite (rate of ξ)"; the range now starts at 1e-12 rad/s and says why
    for set in ["planar.slip_rate=1e-300", "planar.slip_rate=1e-13"] {
        let line = rejects(&["simulate", "--set", "planar.rolling_resistance=0.01", "--set", set, "--set", "drive.t_end=0.05"], "planar.slip_rate");
        assert!(line.contains("1e-12"), "{line}");
    }
    // a sweep over a ball diameter that does not fit the race named a negative
    // contact_stiffness nobody gave (derived from the misfit); it names the diameter now
    let line =
        rejects(&["sweep", "--x", "planar.ball_diameter=0.001:0.5:3", "--set", "planar.contact=true", "--set", "drive.t_end=0.05"], "planar.ball_diameter");
    assert!(line.contains("does not fit"), "{line}");
}

#[test]
fn regression_map_boundary_along_the_y_axis_was_0_points() {
    // hunt 28: --boundary bisected only within rows; with the speed on --y every column turns
    // from unstable to stable along it, and the map said "0 points" with an empty CSV
    let dir = common::scratch_in("robustness", "boundary-y");
    let shaft = examples("linear_rotor_shaft.toml");
    let (code, _, err) = run_in(
        &dir,
        Duration::from_secs(120),
        &["map", "--config", &shaft, "--x", "linear_rotor.support_stiffness_scale=0.5:2:3", "--y", "speed=100:3000:6", "--boundary", "--out", "m"],
    );
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("boundary: 3 points between neighbouring cells") && err.contains("3 along speed within a column") && err.contains("bisected to 1e-9"),
        "{err}"
    );
    let csv = std::fs::read_to_string(dir.join("m_boundary.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 3, "{csv}");
    assert!(rows.iter().all(|r| r.ends_with(",unstable,stable,y")), "{csv}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn regression_map_refused_the_documented_planar_ball_masses_j() {
    // hunt 28: config.md lists planar.ball_masses[j], planar.ball_drags[j] "for maps and
    // sweeps"; map said "unknown key (known keys of [planar]: ... ball_masses ...)"
    let planar = examples("planar.toml");
    for ax in ["planar.ball_drags[1]=0.05:0.1:2", "planar.ball_masses[2]=0.02:0.04:2"] {
        let (code, out, err) = run_for(Duration::from_secs(60), &["map", "--config", &planar, "--x", ax, "--y", "omega=20:900:3", "--out", "mbm"]);
        assert_eq!(code, 0, "--x {ax}: {err}");
        assert!(out.contains("3 rows × 2 points"), "{out}");
    }
    // a ball the rotor does not have (planar.toml: n = 2) is refused naming the path
    let line = rejects(&["map", "--config", &planar, "--x", "planar.ball_masses[3]=0.02:0.04:2", "--y", "omega=20:900:3", "--out", "mbm"], "--x");
    assert!(line.contains("planar.ball_masses[3]") && line.contains("has 2 elements"), "{line}");
}

#[test]
fn regression_a_map_without_any_stationary_state_claimed_an_equilibrium() {
    // hunt 28: no cell has a state (gravity: it would be a periodic orbit), and the table and
    // the figure's title said "stationary state: equilibrium (eigenvalues)"
    let dir = common::scratch_in("robustness", "no-state");
    let cfg = examples("spatial_two_plane.toml");
    let (code, out, err) =
        run_in(&dir, Duration::from_secs(120), &["map", "--config", &cfg, "--x", "balancer.drag=0.1:1:2", "--y", "speed_rpm=500:1000:2", "--out", "m"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("stationary state: none found (no cell has a stationary state)") && !out.contains("equilibrium"), "{out}");
    let svg = std::fs::read_to_string(dir.join("m.svg")).unwrap();
    assert!(!svg.contains("equilibrium") && !svg.contains("Floquet"), "the figure claims a kind of state");
    std::fs::remove_dir_all(&dir).ok();
}

/// `stability --svg st.png` wrote SVG text under a .png name, and `campbell --svg c.png` wrote
/// `c.png.svg` (session 28's hunt): refused in one line naming `--svg`, before the run, writing
/// nothing; `export-model --stem .` wrote the hidden `sub/..toml`, `--stem ..` wrote
/// `sub/...toml`: refused naming `--stem`, writing nothing.
#[test]
fn regression_an_svg_name_of_another_format_and_a_folder_stem_are_refused() {
    let d = scratch("svgname");
    let line = rejects(&["stability", "--samples", "10", "--svg", &s(&d.join("st.png"))], "--svg");
    assert!(line.contains("SVG only") && line.contains(".svg"), "{line}");
    rejects(&["campbell", "--points", "10", "--svg", &s(&d.join("c.png"))], "--svg");
    for stem in [".", "..", ""] {
        rejects(&["export-model", "--out", &s(&d.join("sub")), "--stem", stem], &format!("--stem {stem:?}"));
    }
    assert!(tree(&d).is_empty(), "{:?}", tree(&d));
    std::fs::remove_dir_all(&d).ok();
}
