//! Hostile input, round 3: one regression test per defect, named after it, end to end with a
//! wall-clock limit on every run (a hang fails the test instead of hanging the suite).

mod common;
use common::{examples, run_in, wait_for};
use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn scratch(name: &str) -> std::path::PathBuf {
    common::scratch_in("r3", name)
}

/// The command fails with status 2 and one line on stderr, `error: ` then `field`; the line.
#[track_caller]
fn rejects_in(dir: &std::path::Path, args: &[&str], field: &str) -> String {
    let (code, out, err) = run_in(dir, Duration::from_secs(60), args);
    assert_eq!(code, 2, "autobal {}: exit {code}, stdout {out}, stderr {err}", args.join(" "));
    let line = err.trim_end();
    assert_eq!(line.lines().count(), 1, "one line: {line}");
    assert!(line.starts_with(&format!("error: {field}")), "names {field}: {line}");
    line.to_string()
}

/// `examples/linear_rotor_shaft.toml` with a short run-up (0.05 s), in `dir`.
fn short_shaft(dir: &std::path::Path) -> String {
    let text = std::fs::read_to_string(examples("linear_rotor_shaft.toml")).unwrap();
    assert_eq!(text.matches("t_end = 6.0").count(), 1);
    let p = dir.join("shaft.toml");
    std::fs::write(&p, text.replace("t_end = 6.0", "t_end = 0.05")).unwrap();
    p.to_str().unwrap().to_string()
}

/// `autobal sweep` of `points` runs of drive.b (3000 s each, one thread, `--out cc` in `dir`),
/// behind `nohup` when `nohup` is set; stdout as given, stderr read on a thread. Returns once
/// the sweep has started writing (its `cc.csv.PID.part` exists), panicking if it ended first.
#[cfg(unix)]
fn long_sweep(dir: &std::path::Path, points: usize, nohup: bool, stdout: Stdio) -> (std::process::Child, std::thread::JoinHandle<String>) {
    let bin = env!("CARGO_BIN_EXE_autobal");
    let mut cmd = if nohup {
        let mut c = Command::new("nohup");
        c.arg(bin);
        c
    } else {
        Command::new(bin)
    };
    // the signals' dispositions as a terminal gives them, whatever this test inherited: a suite
    // run under `nohup` (SIGHUP ignored) passes the ignore on through exec, and the sweep then
    // rightly keeps running on HUP (CI ran the 4000 points past the 60 s limit)
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: `signal` is async-signal-safe, the only call made between fork and exec
        unsafe {
            cmd.pre_exec(|| {
                libc::signal(libc::SIGHUP, libc::SIG_DFL);
                libc::signal(libc::SIGTERM, libc::SIG_DFL);
                Ok(())
            });
        }
    }
    let x = format!("drive.b=0.5:12.5:{points}");
    let mut child = cmd
        .args(["sweep", "--x", &x, "--set", "drive.t_end=3000", "--threads", "1", "--out", "cc", "--no-plots"])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let t0 = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            panic!("the sweep ended ({s}) before it started writing: {}", reader.join().unwrap());
        }
        let started = std::fs::read_dir(dir).unwrap().any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".part"));
        if started {
            return (child, reader);
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "the sweep wrote nothing in 60 s");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Send `sig` (`-INT`, `-TERM`, `-HUP`) to `child`, which must still be running.
#[cfg(unix)]
fn signal(child: &mut std::process::Child, sig: &str) {
    assert!(child.try_wait().unwrap().is_none(), "the sweep is still running when {sig} is sent");
    let ok = Command::new("kill").args([sig, &child.id().to_string()]).status().unwrap();
    assert!(ok.success());
}

#[test]
fn regression_shaft_builder_keys_were_unknown_parameter_paths() {
    // `--set linear_rotor.elements[0].length=0.3` said "unknown parameter path": the shaft
    // builder's arrays of tables (elements, disks, bearings) could be neither set nor swept
    let d = scratch("shaft-keys");
    let shaft = short_shaft(&d);
    let text = std::fs::read_to_string(&shaft).unwrap();
    // a second route: the config edited by hand
    assert_eq!(text.matches("length = 0.1").count(), 1);
    let edited = d.join("edited.toml");
    std::fs::write(&edited, text.replace("length = 0.1", "length = 0.12").replace("mass = 4.0", "mass = 5.0")).unwrap();
    let st = |cfg: &str, set: &[&str]| {
        let mut a = vec!["stability", "--config", cfg, "--samples", "12", "--omega-max", "2500 rad/s", "--format", "json"];
        a.extend_from_slice(set);
        let (code, out, err) = run_in(&d, Duration::from_secs(120), &a);
        assert_eq!(code, 0, "{a:?}: {err}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()["points"].clone()
    };
    let by_set = st(&shaft, &["--set", "linear_rotor.elements[0].length=0.12", "--set", "linear_rotor.disks[0].mass=5"]);
    assert_eq!(by_set, st(edited.to_str().unwrap(), &[]));
    assert_ne!(by_set, st(&shaft, &[]), "a longer shaft and a heavier disk change the margins");
    // out of range, a wrong field: refused naming the key and the valid range or keys
    let line = rejects_in(&d, &["stability", "--config", &shaft, "--set", "linear_rotor.elements[1].length=0.3"], "linear_rotor.elements[1].length");
    assert!(line.ends_with("the config has 1 [[linear_rotor.elements]] (j from 0 to 0)"), "{line}");
    let line = rejects_in(&d, &["stability", "--config", &shaft, "--set", "linear_rotor.disks[0].radius=0.3"], "linear_rotor.disks[0].radius");
    assert!(line.contains("unknown key of [[linear_rotor.disks]] (known: node, mass, id, ip)"), "{line}");
    let line = rejects_in(&d, &["stability", "--config", &shaft, "--set", "linear_rotor.bearings[1].kxx[2]=1e6"], "linear_rotor.bearings[1].kxx[2]");
    assert!(line.contains("has 2 entries (i from 0 to 1)"), "{line}");
    // a sweep's axis: each row is the run of `simulate` on the config with that value
    let (code, _, err) =
        run_in(&d, Duration::from_secs(120), &["sweep", "--config", &shaft, "--x", "linear_rotor.elements[0].length=0.1,0.12", "--out", "sw", "--no-plots"]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(d.join("sw.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows[0][1], "linear_rotor.elements[0].length");
    assert_eq!((rows.len(), rows[1][1], rows[2][1]), (3, "0.1", "0.12"));
    let peak = rows[0].iter().position(|c| *c == "peak_amplitude").unwrap();
    assert_ne!(rows[1][peak], rows[2][peak], "the length changes the run");
    let (code, _, err) =
        run_in(&d, Duration::from_secs(120), &["simulate", "--config", edited.to_str().unwrap(), "--set", "linear_rotor.disks[0].mass=4", "--out", "one"]);
    assert_eq!(code, 0, "{err}");
    let one = std::fs::read_to_string(d.join("one.csv")).unwrap();
    let (code, _, err) =
        run_in(&d, Duration::from_secs(120), &["simulate", "--config", &shaft, "--set", "linear_rotor.elements[0].length=0.12", "--out", "two"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(one, std::fs::read_to_string(d.join("two.csv")).unwrap(), "the edited config with its disk set back is the length alone");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_shard_count_past_the_points_and_repeated_values_were_taken() {
    // `--shard 1/1000000000000` on a one-point grid ran, and so did `--x drive.b=1,1,1` (one
    // point three times); both refused now, naming the numbers, before anything is written
    let d = scratch("shards");
    let line = rejects_in(&d, &["sweep", "--x", "drive.b=1", "--set", "drive.t_end=1", "--shard", "1/1000000000000", "--out", "s"], "--shard 1/1000000000000");
    assert!(line.contains("1000000000000 shards of a grid of 1 point: give N ≤ 1"), "{line}");
    let line = rejects_in(&d, &["sweep", "--x", "drive.b=1,2", "--set", "drive.t_end=1", "--shard", "3/3", "--out", "s"], "--shard 3/3");
    assert!(line.contains("3 shards of a grid of 2 points"), "{line}");
    let line = rejects_in(&d, &["sweep", "--x", "drive.b=1,1,1", "--set", "drive.t_end=1", "--out", "s"], "--x drive.b=1,1,1");
    assert!(line.contains("the value 1 is given more than once"), "{line}");
    let line = rejects_in(&d, &["sweep", "--x", "drive.b=1,2", "--y", "planar.c_psi=0.1,0.2,0.1", "--set", "drive.t_end=1", "--out", "s"], "--y");
    assert!(line.contains("the value 0.1 is given more than once"), "{line}");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "nothing written");
    // as many shards as points: each runs one, and they merge
    for k in ["1/2", "2/2"] {
        let (code, _, err) = run_in(
            &d,
            Duration::from_secs(60),
            &["sweep", "--x", "drive.b=1,2", "--set", "drive.t_end=1", "--shard", k, "--out", &format!("p{}", &k[..1]), "--no-plots"],
        );
        assert_eq!(code, 0, "{err}");
    }
    let (code, _, err) = run_in(&d, Duration::from_secs(60), &["merge", "p1.csv", "p2.csv", "--out", "m"]);
    assert_eq!(code, 0, "{err}");
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_a_matrix_file_that_is_a_fifo_read_as_an_empty_file() {
    // the config's path said "is a named pipe with no writer"; a matrix file that was such a
    // pipe read as an empty file ("empty file: expected the header %%MatrixMarket ..."). One
    // reader for both now.
    let d = scratch("fifo-matrix");
    let st = Command::new("mkfifo").arg(d.join("K.mtx")).status().unwrap();
    assert!(st.success());
    let m = "%%MatrixMarket matrix coordinate real general\n4 4 4\n1 1 1.0\n2 2 1.0\n3 3 1.0\n4 4 1.0\n";
    std::fs::write(d.join("M.mtx"), m).unwrap();
    std::fs::write(d.join("rotor.toml"), "[linear_rotor]\nm = \"M.mtx\"\nk = \"K.mtx\"\n").unwrap();
    let line = rejects_in(&d, &["stability", "--config", "rotor.toml"], "linear_rotor.k");
    assert!(line.ends_with("K.mtx: is a named pipe with no writer (nothing to read); start the program that writes it first, or give a file"), "{line}");
    // and a folder where the file goes is named as such
    std::fs::remove_file(d.join("K.mtx")).unwrap();
    std::fs::create_dir(d.join("K.mtx")).unwrap();
    let line = rejects_in(&d, &["stability", "--config", "rotor.toml"], "linear_rotor.k");
    assert!(line.ends_with("K.mtx: is a directory, not a matrix file"), "{line}");
    std::fs::remove_dir_all(&d).ok();
}

/// Every command (quick runs) with its standard output, its standard error or both closed by the
/// reader before it writes (`autobal … | head -c0`, `2>&-` on a pipe): no panic (status 101), no
/// hang, the status of the run with both open (a broken pipe ends quietly: the reader has gone,
/// as with SIGPIPE's early exit, but with the run's own status), and the files written as with
/// both open.
#[test]
fn closed_stdout_or_stderr_never_panics_nor_changes_the_status() {
    let d = scratch("closed-pipes");
    let shaft = short_shaft(&d);
    let spatial = examples("spatial.toml");
    let cases: Vec<Vec<&str>> = vec![
        vec!["inertia"],
        vec!["critical", "--format", "json"],
        vec!["ranges"],
        vec!["stability", "--samples", "50"],
        vec!["campbell", "--format", "json"],
        vec!["map", "--x", "omega=0.5:2:6", "--y", "dimensionless.z_a=0:1:3", "--out", "m"],
        vec!["simulate", "--set", "drive.t_end=2", "--out", "sim"],
        vec!["sweep", "--x", "drive.b=1,2", "--set", "drive.t_end=2", "--out", "sw", "--format", "json"],
        vec!["sweep", "--config", &shaft, "--x", "linear_rotor.disks[0].mass=3,4", "--out", "lsw", "--no-plots"],
        vec!["export-model", "--out", "em/"],
        vec!["basins", "--config", &spatial, "--n", "2", "--set", "drive.t_end=0.2", "--out", "b"],
        vec!["stability", "--config", &shaft, "--samples", "10", "--omega-max", "1000 rad/s"],
        vec!["critical", "--set", "nope.x=1"],
        vec!["sweep", "--x", "drive.b=1,1"],
        vec!["--help"],
        vec!["--version"],
        vec!["nocommand"],
    ];
    for a in &cases {
        let what = a.join(" ");
        let run = |close_out: bool, close_err: bool| {
            let mut child = Command::new(env!("CARGO_BIN_EXE_autobal")).args(a).current_dir(&d).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
            let (out, err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
            let keep_out = (!close_out).then(|| {
                std::thread::spawn(move || {
                    let mut s = String::new();
                    let mut out = out;
                    let _ = out.read_to_string(&mut s);
                    s
                })
            });
            let keep_err = (!close_err).then(|| {
                std::thread::spawn(move || {
                    let mut s = String::new();
                    let mut err = err;
                    let _ = err.read_to_string(&mut s);
                    s
                })
            });
            let status = wait_for(child, Duration::from_secs(120), &what);
            let err = keep_err.map(|t| t.join().unwrap()).unwrap_or_default();
            let _ = keep_out.map(|t| t.join().unwrap());
            (status.code(), err)
        };
        let (open, _) = run(false, false);
        for (close_out, close_err) in [(true, false), (false, true), (true, true)] {
            let (code, err) = run(close_out, close_err);
            assert!(!err.contains("panicked"), "autobal {what}: {err}");
            assert_eq!(code, open, "autobal {what} with stdout closed {close_out}, stderr closed {close_err}: {err}");
        }
    }
    for f in ["m.csv", "sim.csv", "sw.csv", "sw.json", "lsw.csv", "em/rotor.toml", "b"] {
        assert!(d.join(f).is_file(), "{f}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_ctrl_c_with_stdout_closed_ended_a_sweep_with_status_0() {
    // a sweep stopped by Ctrl-C says what it kept and exits 2; with standard output closed the
    // broken pipe of its table ended it quietly with status 0 instead, the partial sweep
    // passed on as complete
    let d = scratch("ctrlc-stdout-closed");
    // 4000 runs of 3000 s (tens of milliseconds each at least): the Ctrl-C lands mid-sweep
    let (mut child, reader) = long_sweep(&d, 4000, false, Stdio::piped());
    drop(child.stdout.take());
    signal(&mut child, "-INT");
    let status = wait_for(child, Duration::from_secs(60), "sweep");
    let err = reader.join().unwrap();
    assert_eq!(status.code(), Some(2), "{err}");
    let last = err.trim_end().lines().last().unwrap_or("");
    assert!(last.starts_with("error: interrupted: ") && last.ends_with("of 4000 runs complete, kept in cc.csv"), "{err}");
    assert!(d.join("cc.csv").is_file());
    std::fs::remove_dir_all(&d).ok();
}

/// A tmpfs of `kib` KiB at a fresh folder (root only); `None` where it cannot be mounted.
#[cfg(target_os = "linux")]
fn tiny_disk(name: &str, kib: u32) -> Option<std::path::PathBuf> {
    let d = scratch(name);
    let ok =
        Command::new("mount").args(["-t", "tmpfs", "-o", &format!("size={kib}k"), "tmpfs"]).arg(&d).stderr(Stdio::null()).status().is_ok_and(|s| s.success());
    if ok {
        Some(d)
    } else {
        eprintln!("skipped: {name}: cannot mount a tmpfs at {} (needs root and `mount`)", d.display());
        std::fs::remove_dir_all(&d).ok();
        None
    }
}

#[cfg(target_os = "linux")]
fn unmount(d: &std::path::Path) {
    let _ = Command::new("umount").arg(d).status();
    std::fs::remove_dir_all(d).ok();
}

#[cfg(target_os = "linux")]
#[test]
fn regression_a_full_disk_left_a_partial_model_and_an_unnamed_error() {
    // on an 8 KiB disk `export-model` wrote two of its matrices and stopped, leaving a model
    // folder without its config; `map` said only "No space left on device (os error 28)",
    // naming neither the flag nor the file
    let Some(d) = tiny_disk("full-disk", 8) else { return };
    let shaft = examples("linear_rotor_shaft.toml");
    let line = rejects_in(&d, &["export-model", "--config", &shaft, "--out", "em/"], "--out: cannot write em/");
    assert!(line.contains("No space left on device"), "{line}");
    assert!(
        !d.join("em").exists(),
        "nothing of the model is left: {:?}",
        std::fs::read_dir(d.join("em")).map(|r| r.map(|e| e.unwrap().file_name()).collect::<Vec<_>>())
    );
    let line = rejects_in(&d, &["map", "--x", "omega=0.5:2:60", "--y", "dimensionless.z_a=0:1:40", "--out", "m"], "--out: cannot write m.csv: ");
    assert!(line.contains("No space left on device"), "{line}");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "no file left on the full disk");
    unmount(&d);
}

#[test]
fn regression_a_negative_speed_with_its_unit_was_a_usage_error() {
    // `--omega-max "-5 rpm"` was taken by the argument parser for a flag `-5` ("unexpected
    // argument '-5' found", three lines naming no field); every speed flag reads it and says
    // what is wrong with the value, as for "--omega-max=-5 rpm"
    let d = scratch("negative-speed");
    let dim = examples("dimensional.toml");
    for a in [&["stability"][..], &["critical", "--route", "general"], &["campbell"]] {
        let mut a = a.to_vec();
        a.extend(["--config", &dim, "--omega-max", "-5 rpm"]);
        let line = rejects_in(&d, &a, "--omega-max");
        assert!(line.contains("-5 rpm"), "{line}");
    }
    let line = rejects_in(
        &d,
        &["map", "--config", &dim, "--x", "dimensionless.z_a=0:1:3", "--y", "dimensionless.m=0.01:0.02:3", "--omega", "-1400 rpm", "--out", "m"],
        "--omega",
    );
    assert!(line.contains("-1400 rpm"), "{line}");
    // `-.5` too (a hyphen then a dot)
    let line = rejects_in(&d, &["stability", "--config", &dim, "--omega-max", "-.5"], "--omega-max");
    assert!(line.contains("-.5"), "{line}");
    // a flag after a speed flag is not its value: clap says the value is missing (accepting
    // every hyphen value took the flag as the speed: `stability --omega-max --samples 10`
    // refused `10` as an unexpected argument)
    for (cmd, flag) in [("stability", "--omega-max"), ("campbell", "--omega-max"), ("map", "--omega")] {
        let (code, _, err) = run_in(&d, Duration::from_secs(60), &[cmd, flag, "--config", &dim]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains(&format!("a value is required for '{flag} <SPEED>'")), "{cmd}: {err}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_linear_rotor_drive_of_1e300_ran_and_basins_called_it_unbalanced() {
    // `[drive]` and `[integration]` of a linear rotor config were not held to the ranges of the
    // papers' configs: `drive.omega0 = 1e300` at constant speed ended at t = 0 with "the state
    // became non-finite" (no key named), and `basins` reported the four failed runs as
    // "0 of 4 runs balanced", status 0
    let d = scratch("linear-drive-range");
    let shaft = short_shaft(&d);
    for cmd in [&["simulate", "--out", "s"][..], &["basins", "--n", "2", "--out", "b"], &["sweep", "--x", "drive.t_end=0.01,0.02", "--out", "w"]] {
        let mut a = cmd.to_vec();
        a.extend(["--config", &shaft, "--set", "drive.kind=\"speed\"", "--set", "drive.omega0=1e300"]);
        let line = rejects_in(&d, &a, "drive.omega0");
        assert!(line.contains("must lie in [-1e6, 1e6] rad/s, got 1e300"), "{line}");
    }
    let line = rejects_in(&d, &["simulate", "--config", &shaft, "--set", "integration.rtol=1e300", "--out", "s"], "integration.rtol");
    assert!(line.contains("got 1e300"), "the number as typed, not 300 digits: {line}");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1, "nothing written beside the config");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_one_entry_had_several_paths_and_the_last_set_won() {
    // `--set 'linear_rotor.balancer[00].drag=0.1' --set 'linear_rotor.balancer[0].drag=0.2'`
    // ran with 0.2 without a word (a key given twice is refused, but these were two spellings
    // of one key); an index is now spelled one way, digits without sign, space or leading zero
    let d = scratch("index-spelling");
    let shaft = short_shaft(&d);
    for j in ["00", "+0", " 0"] {
        let key = format!("linear_rotor.balancer[{j}].drag");
        let line = rejects_in(&d, &["stability", "--config", &shaft, "--set", &format!("{key}=0.1"), "--set", "linear_rotor.balancer[0].drag=0.2"], &key);
        assert!(line.contains(&format!("the index in [{j}] must be a whole number from 0")), "{line}");
    }
    let line =
        rejects_in(&d, &["sweep", "--config", &shaft, "--x", "linear_rotor.elements[01].length=0.1,0.2", "--out", "w"], "linear_rotor.elements[01].length");
    assert!(line.contains("the index in [01] must be a whole number from 0"), "{line}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_drive_made_by_set_asked_for_b_without_saying_why() {
    // the embedded default config has no [drive] and runs a default run-up; `--set
    // drive.t_end=0.1` makes a [drive] table that replaces it, and the error said only
    // "drive.b: required for kind = "acceleration"", a key the user never gave
    let d = scratch("drive-by-set");
    let spatial = examples("default.toml");
    for cmd in ["basins", "simulate"] {
        let line = rejects_in(&d, &[cmd, "--config", &spatial, "--set", "drive.t_end=0.1", "--out", "x"], "drive.b");
        assert!(line.contains("a [drive] table, even one made by --set, replaces the default run-up"), "{line}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_export_model_wrote_a_config_that_did_not_parse() {
    // `--stem 'a"b'` wrote `m = "a"b_M.mtx"` (the name unquoted into TOML): the exported
    // config could not be read back; a stem with a line break wrote files named across lines
    let d = scratch("export-stem");
    for stem in ["a\"b", "it's ä"] {
        let (code, _, err) = run_in(&d, Duration::from_secs(60), &["export-model", "--out", "o/", "--stem", stem]);
        assert_eq!(code, 0, "{stem}: {err}");
        let cfg = format!("o/{stem}.toml");
        let (code, _, err) = run_in(&d, Duration::from_secs(60), &["stability", "--config", &cfg, "--samples", "10", "--omega-max", "100 rad/s"]);
        assert_eq!(code, 0, "{stem}: the export reads back: {err}");
    }
    let line = rejects_in(&d, &["export-model", "--out", "p/", "--stem", "x\ny"], "--stem");
    assert!(line.contains("control character"), "{line}");
    assert!(!d.join("p").exists());
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_sigterm_left_the_streamed_csv_under_its_temporary_name() {
    // a batch system's time limit (SIGTERM) or a closed terminal (SIGHUP) killed a sweep at
    // once, leaving `STEM.csv.PID.part` and no JSON; both are handled as Ctrl-C now: the runs
    // finished are kept in STEM.csv, and the run says so and exits 2
    for sig in ["-TERM", "-HUP"] {
        let d = scratch(&format!("sig{sig}"));
        let (mut child, reader) = long_sweep(&d, 4000, false, Stdio::null());
        signal(&mut child, sig);
        let status = wait_for(child, Duration::from_secs(60), "sweep");
        let err = reader.join().unwrap();
        assert_eq!(status.code(), Some(2), "{sig}: {err}");
        assert!(
            err.trim_end().lines().last().is_some_and(|l| l.starts_with("error: interrupted: ") && l.ends_with("of 4000 runs complete, kept in cc.csv")),
            "{sig}: {err}"
        );
        let mut names: Vec<String> = std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        names.sort();
        assert_eq!(names, ["cc.csv", "cc.json"], "{sig}: no temporary file left");
        std::fs::remove_dir_all(&d).ok();
    }
}

#[test]
fn regression_shaft_entry_values_were_blamed_on_other_keys() {
    // found by setting each shaft-builder path to hostile values: a bearing table's speeds out
    // of order were reported against `bearings[0]` for the config's `bearings[1]` (the rotor's
    // validation counted the bearings with tables); `balancer[0].offset = 1e200` as
    // "linear_rotor.m: is not positive definite"; `unbalance[0].offset = 1e300` ran to a step
    // size of 0 at t = 0 and `phase = 1e300` ran, neither naming the key
    let d = scratch("entry-values");
    let shaft = short_shaft(&d);
    let cases = [
        ("linear_rotor.bearings[1].speeds[1]=0", "linear_rotor.bearings[1].speeds[1]", "must increase strictly: 0 after 0"),
        ("linear_rotor.balancer[0].offset=1e200", "linear_rotor.balancer[0].offset", "got 1e200"),
        ("linear_rotor.unbalance[0].offset=-1e300", "linear_rotor.unbalance[0].offset", "got -1e300"),
        ("linear_rotor.unbalance[0].phase=1e300", "linear_rotor.unbalance[0].phase", "got 1e300"),
    ];
    for (set, field, why) in cases {
        for cmd in [&["stability", "--samples", "10", "--omega-max", "1000 rad/s"][..], &["simulate", "--out", "s"]] {
            let mut a = cmd.to_vec();
            a.extend(["--config", &shaft, "--set", set]);
            let line = rejects_in(&d, &a, field);
            assert!(line.contains(why), "{line}");
        }
    }
    // in range they run (a metre's offset, a phase of a few turns)
    let (code, _, err) = run_in(&d, Duration::from_secs(60), &["simulate", "--config", &shaft, "--set", "linear_rotor.unbalance[0].phase=20", "--out", "s"]);
    assert_eq!(code, 0, "{err}");
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn regression_nohup_no_longer_kept_a_sweep_from_sighup() {
    // ctrlc's `termination` feature installed its handler for SIGHUP over the SIG_IGN that
    // `nohup` set: `nohup autobal sweep …` stopped on `kill -HUP` ("interrupted: 0 of 3 runs",
    // exit 2). A SIGHUP ignored at start stays ignored: the sweep runs on to the end
    let d = scratch("nohup");
    // 30 runs (a few seconds in all): the SIGHUP is sent while it runs, and it completes
    let (mut child, reader) = long_sweep(&d, 30, true, Stdio::null());
    signal(&mut child, "-HUP");
    let status = wait_for(child, Duration::from_secs(300), "nohup sweep");
    let err = reader.join().unwrap();
    assert_eq!(status.code(), Some(0), "{err}");
    assert!(!err.contains("interrupted"), "{err}");
    let csv = std::fs::read_to_string(d.join("cc.csv")).unwrap();
    assert_eq!(csv.lines().count(), 31, "a header and the 30 runs");
    // SIGTERM (not ignored) still stops it, as Ctrl-C does
    std::fs::remove_dir_all(&d).ok();
    let d = scratch("nohup-term");
    let (mut child, reader) = long_sweep(&d, 4000, true, Stdio::null());
    signal(&mut child, "-TERM");
    let status = wait_for(child, Duration::from_secs(60), "nohup sweep");
    let err = reader.join().unwrap();
    assert_eq!(status.code(), Some(2), "{err}");
    assert!(err.trim_end().ends_with("of 4000 runs complete, kept in cc.csv"), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_map_point_depended_on_which_axis_was_x() {
    // at k = 1e6, support_stiffness_scale = 3 one order gave max_real_part -0.0365 (the scale
    // applied first, then k set over it), the other +3.648; the factors now apply last
    let d = scratch("axis-order");
    let shaft = examples("linear_rotor_shaft.toml");
    let (scale, k) = ("linear_rotor.support_stiffness_scale=1:3:2", "linear_rotor.bearings[0].k=1e6:3e6:2");
    let mut rows = Vec::new();
    for (x, y, out) in [(scale, k, "m1"), (k, scale, "m2")] {
        let (code, _, err) = run_in(&d, Duration::from_secs(120), &["map", "--config", &shaft, "--omega", "400", "--x", x, "--y", y, "--out", out]);
        assert_eq!(code, 0, "{err}");
        // (scale, k) -> max_real_part, whichever column is which
        let csv = std::fs::read_to_string(d.join(format!("{out}.csv"))).unwrap();
        let mut m: Vec<(String, String, String)> = csv
            .lines()
            .skip(1)
            .map(|l| {
                let c: Vec<&str> = l.split(',').collect();
                let (s, k) = if out == "m1" { (c[0], c[1]) } else { (c[1], c[0]) };
                (s.to_string(), k.to_string(), c[2].to_string())
            })
            .collect();
        m.sort();
        rows.push(m);
    }
    assert_eq!(rows[0].len(), 4);
    assert_eq!(rows[0], rows[1], "the same grid point, the same number, bit for bit");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_two_spellings_of_one_ball_index_let_an_axis_be_ignored() {
    // `drive.psi0[01]` was trimmed and parsed as `drive.psi0[1]`: two axes on one number, the
    // x axis silently ignored; now the grid refuses them naming both, and the spelling alone
    // is refused as the linear rotor's `balancer[00]` is
    let d = scratch("psi0-spelling");
    // (the grid compares the paths' canonical forms too: sweep::tests)
    let line =
        rejects_in(&d, &["sweep", "--x", "drive.psi0[01]=1,2", "--y", "drive.psi0[1]=0,1", "--set", "drive.t_end=0.1", "--out", "s"], "--x drive.psi0[01]");
    assert!(line.contains("the index in [01] must be a whole number from 1"), "{line}");
    assert!(!d.join("s.csv").exists());
    let line = rejects_in(&d, &["sweep", "--x", "drive.psi0[ 1]=1,2", "--set", "drive.t_end=0.1", "--out", "s"], "--x drive.psi0[ 1]");
    assert!(line.contains("without sign, space or leading zero"), "{line}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_set_took_no_element_of_an_array() {
    // `--set drive.psi0[1]=0.3` was "unknown key" on every config although sweeps and maps take
    // that path; it now sets the element of an array the config gives, and a whole array after
    // its element (which would silently undo it) is refused
    let d = scratch("set-element");
    let planar = examples("planar.toml");
    let run = |extra: &[&str], stem: &str| {
        let mut args = vec!["simulate", "--config", &planar, "--set", "drive.t_end=0.5", "--out", stem];
        args.extend_from_slice(extra);
        let (code, out, err) = run_in(&d, Duration::from_secs(60), &args);
        assert_eq!(code, 0, "{args:?}: {out} {err}");
        std::fs::read(d.join(format!("{stem}.csv"))).unwrap()
    };
    let by_element = run(&["--set", "drive.psi0=[0.1, 0.2]", "--set", "drive.psi0[1]=0.3"], "a");
    let whole = run(&["--set", "drive.psi0=[0.3, 0.2]"], "b");
    let unset = run(&["--set", "drive.psi0=[0.1, 0.2]"], "c");
    assert_eq!(by_element, whole, "the element set is the whole array with that element");
    assert_ne!(by_element, unset, "the element was set");
    let line =
        rejects_in(&d, &["simulate", "--config", &planar, "--set", "drive.psi0[1]=0.3", "--set", "drive.psi0=[0.1, 0.2]", "--out", "x"], "--set drive.psi0");
    assert!(line.contains("give the whole array first"), "{line}");
    let line = rejects_in(&d, &["simulate", "--config", &planar, "--set", "drive.psi0[1]=0.3", "--out", "x"], "drive.psi0[1]");
    assert!(line.contains("not an array in the config"), "{line}");
    let line =
        rejects_in(&d, &["simulate", "--config", &planar, "--set", "drive.psi0=[0.1, 0.2]", "--set", "drive.psi0[3]=0.3", "--out", "x"], "drive.psi0[3]");
    assert!(line.contains("has 2 elements"), "{line}");
    let line = rejects_in(&d, &["stability", "--config", &examples("spatial.toml"), "--set", "drive.psi0[2]=nan"], "drive.psi0[2]");
    assert!(line.contains("NaN"), "{line}");
    let line = rejects_in(&d, &["stability", "--set", "drive.psi0[1]=1", "--set", "drive.psi0[1]=2"], "--set drive.psi0[1]");
    assert!(line.contains("given twice"), "{line}");
    let line = rejects_in(&d, &["stability", "--set", "drive.psi0=[1, 2]", "--set", "drive.psi0[01]=2"], "--set drive.psi0[01]");
    assert!(line.contains("without sign, space or leading zero"), "{line}");
    assert!(!d.join("x.csv").exists());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_linear_rotor_below_the_periodic_floor_was_refused_without_units() {
    // `stability` on a linear rotor with bearings stiffer along y (a periodic orbit) and
    // `--omega-max "1 rpm"` said "0.10472 is below 41.2111": numbers without their unit, where
    // `campbell` and the spatial route say rad/s and rpm
    let d = scratch("linear-floor-units");
    let text = std::fs::read_to_string(examples("linear_rotor_shaft.toml")).unwrap();
    assert_eq!(text.matches("kyy = [2e6, 3e6]").count(), 1);
    std::fs::write(d.join("aniso.toml"), text.replace("kyy = [2e6, 3e6]", "kyy = [2.5e6, 3.5e6]")).unwrap();
    for (args, field) in [
        (vec!["stability", "--config", "aniso.toml", "--omega-max", "1 rpm"], "--omega-max"),
        (vec!["stability", "--config", "aniso.toml", "--set", "linear_rotor.omega_max=0.01"], "linear_rotor.omega_max"),
    ] {
        let line = rejects_in(&d, &args, field);
        assert!(line.contains(" rad/s (") && line.contains(" rpm), the grid's top speed, is below "), "{line}");
        assert!(line.contains("the slowest speed the periodic-orbit analysis resolves"), "{line}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(target_os = "linux")]
#[test]
fn regression_a_report_on_a_full_disk_left_half_a_folder() {
    // `report` wrote its figures one by one: a full disk left a folder of some figures and no
    // page, and a rerun into a previous report's folder left the old page beside some new
    // figures; now every file is written all or none (the page last)
    let Some(d) = tiny_disk("full-disk-report", 2048) else { return };
    let planar = examples("planar.toml");
    // (the report's progress lines come first: the error is the last line)
    let fails = |d: &std::path::Path, args: &[&str]| {
        let (code, out, err) = run_in(d, Duration::from_secs(120), args);
        assert_eq!(code, 2, "{out} {err}");
        let line = err.trim_end().lines().last().unwrap_or_default().to_string();
        assert!(line.starts_with("error: --out: cannot write r/") && line.contains("No space left on device"), "{err}");
    };
    fails(&d, &["report", "--quick", "--config", &planar, "--out", "r"]);
    assert!(!d.join("r").exists(), "the folder the run made is gone");
    unmount(&d);
    // a previous report: room for it once, not twice
    let Some(d) = tiny_disk("full-disk-report2", 6144) else { return };
    let (code, out, err) = run_in(&d, Duration::from_secs(120), &["report", "--quick", "--config", &planar, "--out", "r"]);
    assert_eq!(code, 0, "{out} {err}");
    let files = |d: &std::path::Path| {
        let mut v: Vec<(std::ffi::OsString, Vec<u8>)> =
            std::fs::read_dir(d).unwrap().map(|e| e.unwrap()).map(|e| (e.file_name(), std::fs::read(e.path()).unwrap())).collect();
        v.sort();
        v
    };
    let before = files(&d.join("r"));
    assert!(before.iter().any(|(n, _)| n == "index.html") && before.len() > 10, "{} files", before.len());
    fails(&d, &["report", "--quick", "--config", &planar, "--set", "drive.t_end=200", "--out", "r"]);
    assert!(files(&d.join("r")) == before, "the previous report is left as it was, byte for byte");
    unmount(&d);
}

#[test]
fn regression_a_top_speed_below_one_rpm_was_printed_as_0_rpm() {
    // `stability --omega-max "1e-3 rpm"` on a dimensional config printed "(up to 0 rpm, 0.0 rad/s)"
    let d = scratch("tiny-omega-max");
    let (code, out, err) = run_in(&d, Duration::from_secs(60), &["stability", "--config", &examples("dimensional.toml"), "--omega-max", "1e-3 rpm"]);
    assert_eq!(code, 0, "{out} {err}");
    assert!(out.contains("(up to 0.001 rpm, 1.0472e-4 rad/s)"), "{out}");
    let (code, out, err) = run_in(&d, Duration::from_secs(60), &["stability", "--config", &examples("dimensional.toml")]);
    assert_eq!(code, 0, "{out} {err}");
    assert!(out.contains("(up to 10434 rpm, 1092.7 rad/s)"), "{out}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_a_planar_config_without_drive_is_analysed() {
    // session 19's audit: `stability`, `critical`, `campbell` and `map` refused a planar
    // config with no [drive] table ("drive.b: required for kind = "acceleration" ... a [drive]
    // table ... replaces the default run-up": there is neither a table nor a default run-up);
    // an analysis at a constant speed needs no run. `simulate` still needs one, and says so.
    let d = scratch("planar-no-drive");
    let text = std::fs::read_to_string(examples("planar.toml")).unwrap();
    let rotor_only = &text[..text.find("[drive]").expect("examples/planar.toml has [drive]")];
    std::fs::write(d.join("p.toml"), rotor_only).unwrap();
    for args in [
        &["stability", "--config", "p.toml", "--samples", "20"][..],
        &["critical", "--config", "p.toml"],
        &["campbell", "--config", "p.toml", "--points", "20"],
        &["map", "--config", "p.toml", "--x", "planar.m3=0.02:0.04:3", "--y", "omega=100:600:3", "--out", "m"],
    ] {
        let (code, _, err) = run_in(&d, Duration::from_secs(120), args);
        assert_eq!(code, 0, "autobal {}: {err}", args.join(" "));
    }
    // the same analysis as with the example's drive (which it does not use)
    let (_, with, _) = run_in(&d, Duration::from_secs(120), &["stability", "--config", &examples("planar.toml"), "--samples", "20", "--format", "json"]);
    let (_, without, _) = run_in(&d, Duration::from_secs(120), &["stability", "--config", "p.toml", "--samples", "20", "--format", "json"]);
    let ranges = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap()["stable_ranges"].clone();
    assert_eq!(ranges(&with), ranges(&without));
    let line = rejects_in(&d, &["simulate", "--config", "p.toml", "--out", "s"], "drive");
    assert!(line.contains("a planar run needs a [drive] table") && !line.contains("replaces the default run-up"), "{line}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_report_replaced_a_users_own_index_html() {
    // review 25a: `report --out DIR` replaced a user's own `index.html` (and files named as
    // the report's assets) in DIR; review 26a F5: the refusal was tested on the folder check
    // alone, not through the command. Refused before any section runs, the files untouched,
    // nothing added to the folder.
    let d = scratch("report-own-index");
    let planar = examples("planar.toml");
    let r = d.join("r");
    std::fs::create_dir_all(&r).unwrap();
    std::fs::write(r.join("index.html"), "<html><title>my notes</title></html>").unwrap();
    let line = rejects_in(&d, &["report", "--quick", "--config", &planar, "--out", "r"], "--out r: holds an index.html that is not an autobal report");
    assert!(line.contains("give a new or empty folder"), "{line}");
    assert_eq!(std::fs::read_to_string(r.join("index.html")).unwrap(), "<html><title>my notes</title></html>");
    assert_eq!(std::fs::read_dir(&r).unwrap().count(), 1, "nothing written beside it");
    // no page, but a file named as one of the report's assets
    std::fs::remove_file(r.join("index.html")).unwrap();
    std::fs::write(r.join("report.js"), "my script").unwrap();
    let line = rejects_in(&d, &["report", "--quick", "--config", &planar, "--out", "r"], "--out r: holds a file report.js that no autobal report page links");
    assert!(line.contains("give a new or empty folder"), "{line}");
    assert_eq!(std::fs::read_to_string(r.join("report.js")).unwrap(), "my script");
    assert_eq!(std::fs::read_dir(&r).unwrap().count(), 1, "nothing written beside it");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_sweeps_note_says_no_runs_end_was_checked_against_a_tighter_tolerance() {
    // issue 18 item 4, review 26a F5: a sweep's outcomes are each run's end at its own
    // tolerance; the note on stderr and the JSON's `tolerance_check` say so (rtol null: an
    // axis may move it), for the planar and spatial rotors; a linear rotor's runs (no balls'
    // basins) get neither
    let d = scratch("sweep-tolerance-note");
    let note = "note: each run's end state is that at its tolerance, none checked against a tighter one: a start near a basin boundary or a chaotic transient can end elsewhere at another tolerance; simulate --check-tolerance checks one run";
    let (code, out, err) = run_in(
        &d,
        Duration::from_secs(120),
        &["sweep", "--threads", "1", "--x", "drive.b=100,200", "--set", "drive.t_end=0.5", "--set", "drive.omega0=250", "--out", "s"],
    );
    assert_eq!(code, 0, "{out} {err}");
    assert_eq!(err.lines().filter(|l| *l == note).count(), 1, "{err}");
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    let c = &j["tolerance_check"];
    assert_eq!((&c["checked"], &c["rtol"]), (&serde_json::json!(false), &serde_json::Value::Null), "{c}");
    assert_eq!(format!("note: {}", c["what"].as_str().unwrap()), note);
    let shaft = short_shaft(&d);
    let (code, out, err) = run_in(&d, Duration::from_secs(120), &["sweep", "--threads", "1", "--config", &shaft, "--x", "drive.t_end=0.04,0.05", "--out", "l"]);
    assert_eq!(code, 0, "{out} {err}");
    assert!(!err.contains("none checked against a tighter one"), "{err}");
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("l.json")).unwrap()).unwrap();
    assert!(j.get("tolerance_check").is_none(), "{}", j["tolerance_check"]);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_an_output_overwrote_a_matrix_file_named_by_set() {
    // hunt 27: the files a linear rotor config names were protected from the outputs only as
    // the file on disk names them: `--set 'linear_rotor.kst="kst.svg"' --svg kst.svg` wrote
    // the figure over the matrix file. Refused before anything runs, the file untouched.
    let d = scratch("set-named-input");
    let shaft = short_shaft(&d);
    std::fs::write(d.join("kst.svg"), "my matrix").unwrap();
    std::fs::write(d.join("fix.csv"), "my masses").unwrap();
    let line = rejects_in(&d, &["stability", "--config", &shaft, "--samples", "10", "--set", "linear_rotor.kst=\"kst.svg\"", "--svg", "kst.svg"], "--svg");
    assert!(line.contains("kst.svg"), "{line}");
    let line = rejects_in(
        &d,
        &[
            "map",
            "--config",
            &shaft,
            "--set",
            "linear_rotor.rotor_fixed_mass=\"fix.csv\"",
            "--x",
            "speed=100:2000:2",
            "--y",
            "linear_rotor.drag=0.05:0.1:2",
            "--out",
            "fix",
        ],
        "--out",
    );
    assert!(line.contains("fix.csv"), "{line}");
    assert_eq!(std::fs::read_to_string(d.join("kst.svg")).unwrap(), "my matrix");
    assert_eq!(std::fs::read_to_string(d.join("fix.csv")).unwrap(), "my masses");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_report_wrote_over_its_own_config_in_the_output_folder() {
    // hunt 27: a config kept in the report's folder under a figure's name was overwritten
    // (`--config rep/stability_margin.svg --out rep`) or removed as a stale figure; refused
    // before any section runs, the config untouched. Another name there is safe and runs.
    let d = scratch("report-own-config");
    let text = std::fs::read_to_string(examples("planar.toml")).unwrap();
    std::fs::create_dir_all(d.join("rep")).unwrap();
    std::fs::write(d.join("rep/stability_margin.svg"), &text).unwrap();
    let line = rejects_in(&d, &["report", "--quick", "--config", "rep/stability_margin.svg", "--out", "rep"], "--out rep: holds the run's input");
    assert!(line.contains("stability_margin.svg"), "{line}");
    assert_eq!(std::fs::read_to_string(d.join("rep/stability_margin.svg")).unwrap(), text);
    assert_eq!(std::fs::read_dir(d.join("rep")).unwrap().count(), 1, "nothing written beside it");
    std::fs::remove_dir_all(&d).ok();
}

/// Review 25b R4: `dimensionless.delta_a` and `d_a` beside the masses are inputs of the 12-state
/// linear model only (ΔĀ, D_A); the spatial simulation's rotor has the masses' inertia and balls.
/// Where a command runs that rotor alone, they were taken without a word; session 26's warning
/// "no effect" was false (reverted): the linear model's critical speeds set the default run-up's
/// end and the general route's default speed range. One line now names them and what they set
/// in the run, and each claim is checked against the runs themselves: the numbers it prints are
/// the runs' end speeds and speed ranges, and the run without the keys, given what the line says
/// they set, is the same run (byte for byte, JSON but for the wall time).
#[test]
fn regression_delta_a_beside_the_masses_was_taken_by_the_simulation_without_a_word() {
    use serde_json::Value;
    let d = scratch("delta-a-beside-the-masses");
    let text = std::fs::read_to_string(examples("spatial.toml")).unwrap();
    // the example without its [drive] table (the next table is [initial]): the default run-up
    let (head, rest) = text.split_at(text.find("\n[drive]").expect("examples/spatial.toml has [drive]"));
    let bare = format!("{head}\n{}", &rest[rest.find("\n[initial]").unwrap()..]);
    std::fs::write(d.join("bare.toml"), &bare).unwrap();
    let keys = ["--set", "dimensionless.delta_a=0.1", "--set", "dimensionless.d_a=0.5"];
    let run = |args: &[&str]| {
        let (code, out, err) = run_in(&d, Duration::from_secs(120), args);
        assert_eq!(code, 0, "autobal {}: {err}", args.join(" "));
        (out, err)
    };
    let with_keys = |args: &[&str]| run(&[args, &keys[..]].concat());
    let lines = |err: &str| err.lines().filter(|l| l.contains("beside the masses")).map(String::from).collect::<Vec<_>>();
    let head = |cmd: &str| {
        format!("warning: {cmd}: dimensionless.d_a, dimensionless.delta_a beside the masses are inputs of the 12-state linear model only: the spatial simulation's rotor, which {cmd} runs, has the masses' inertia and balls (m0, r0, m, r, n); ")
    };
    let json = |s: &str| serde_json::from_str::<Value>(s).unwrap();
    let without = |mut v: Value, keys: &[&str]| {
        for k in keys {
            v.as_object_mut().unwrap().remove(*k);
        }
        v
    };
    // a number as the JSON printed it (every digit: the shortest text that reads back the same)
    let raw = |s: &str, key: &str| {
        let at = s.find(&format!("\"{key}\": ")).unwrap_or_else(|| panic!("{key} in {s}")) + key.len() + 4;
        s[at..].split([',', '\n']).next().unwrap().trim().to_string()
    };
    // the line's "X with them, Y without": each the printed 6 digits of the run's own value
    let printed = |line: &str, before: &str| -> [f64; 2] {
        let t = &line[line.find(before).unwrap_or_else(|| panic!("{before} in {line}")) + before.len()..];
        let w: Vec<&str> = t.split(' ').collect();
        assert_eq!((w[1], w[2], w[4].trim_end_matches(',')), ("with", "them,", "without"), "{line}");
        [w[0].parse().unwrap(), w[3].trim_end_matches(',').parse().unwrap()]
    };
    let six = |x: f64, y: f64| (x / y - 1.0).abs() < 5e-6; // 6 significant digits printed

    // simulate without [drive]: they set only where the default run-up ends
    let (out_k, err_k) = with_keys(&["simulate", "--config", "bare.toml", "--format", "json", "--out", "k.csv"]);
    let (out_m, err_m) = run(&["simulate", "--config", "bare.toml", "--format", "json", "--out", "m.csv"]);
    assert!(lines(&err_m).is_empty(), "{err_m}");
    let l = lines(&err_k);
    assert_eq!(l.len(), 1, "{err_k}");
    assert!(
        l[0].starts_with(&format!(
            "{}in this run they set only where the default run-up ends (no [drive]; its acceleration and duration follow): Ω = ",
            head("simulate")
        )),
        "{}",
        l[0]
    );
    assert!(l[0].ends_with(" without, from the linear model's critical speeds"), "{}", l[0]);
    let [w_k, w_m] = printed(&l[0], "Ω = ");
    let (k, m) = (json(&out_k), json(&out_m));
    assert!(six(w_k, k["final_omega"].as_f64().unwrap()) && six(w_m, m["final_omega"].as_f64().unwrap()), "{} {k} {m}", l[0]);
    assert!(w_k / w_m > 1.2, "ΔĀ = 0.1 moves the linear model's top critical speed: {}", l[0]);
    // ... and nothing else: the masses alone, given that run-up as their [drive], run the same run
    let given = format!("{bare}\n[drive]\nkind = \"acceleration\"\nomega0 = 0.0\nb = {}\nt_end = {}\n", raw(&out_k, "b"), raw(&out_k, "t_end"));
    std::fs::write(d.join("given.toml"), given).unwrap();
    let (out_g, err_g) = run(&["simulate", "--config", "given.toml", "--format", "json", "--out", "g.csv"]);
    assert!(lines(&err_g).is_empty(), "{err_g}");
    let g = json(&out_g);
    assert_eq!((&k["drive_is_default"], &g["drive_is_default"]), (&Value::Bool(true), &Value::Bool(false)));
    assert!(without(k, &["wall_time_s", "drive_is_default"]) == without(g, &["wall_time_s", "drive_is_default"]), "{out_k}\n{out_g}");
    assert!(std::fs::read(d.join("k.csv")).unwrap() == std::fs::read(d.join("g.csv")).unwrap(), "the samples, byte for byte");

    // simulate with its own [drive]: they set nothing
    let spatial = examples("spatial.toml");
    let (out_k, err_k) = with_keys(&["simulate", "--config", &spatial, "--set", "drive.t_end=200", "--format", "json", "--out", "k2.csv"]);
    assert_eq!(lines(&err_k), [format!("{}they set nothing in this run", head("simulate"))]);
    let (out_m, _) = run(&["simulate", "--config", &spatial, "--set", "drive.t_end=200", "--format", "json", "--out", "m2.csv"]);
    assert!(without(json(&out_k), &["wall_time_s"]) == without(json(&out_m), &["wall_time_s"]), "{out_k}\n{out_m}");
    assert!(std::fs::read(d.join("k2.csv")).unwrap() == std::fs::read(d.join("m2.csv")).unwrap(), "the samples, byte for byte");

    // stability's general route: only its default speed range
    let stab = ["stability", "--config", &spatial, "--route", "general", "--samples", "20", "--format", "json"];
    let (out_k, err_k) = with_keys(&stab);
    let (out_m, _) = run(&stab);
    let l = lines(&err_k);
    assert_eq!(l.len(), 1, "{err_k}");
    assert!(l[0].starts_with(&format!("{}in this run they set only the default speed range (--omega-max sets it): 0 < Ω ≤ ", head("stability"))), "{}", l[0]);
    let [w_k, w_m] = printed(&l[0], "0 < Ω ≤ ");
    assert!(six(w_k, json(&out_k)["omega_max"].as_f64().unwrap()) && six(w_m, json(&out_m)["omega_max"].as_f64().unwrap()), "{}", l[0]);
    assert_ne!(json(&out_k), json(&out_m));
    // the masses alone over that range: the same scan
    let top = raw(&out_k, "omega_max");
    let (out_g, err_g) = run(&[&stab[..], &["--omega-max", &top]].concat());
    assert!(lines(&err_g).is_empty(), "{err_g}");
    assert_eq!(json(&out_k), json(&out_g));
    // given the range, they set nothing
    let (_, err_k) = with_keys(&[&stab[..], &["--omega-max", &top]].concat());
    assert_eq!(lines(&err_k), [format!("{}they set nothing in this run", head("stability"))]);

    // critical's general route over a given range: only paper 003's necessary ranges printed beside
    let crit = ["critical", "--config", &spatial, "--route", "general", "--omega-max", "3", "--format", "json"];
    let (out_k, err_k) = with_keys(&crit);
    assert_eq!(
        lines(&err_k),
        [format!("{}in this run they set only paper 003's necessary ranges printed beside the exact ones (the linear model's)", head("critical"))]
    );
    let (out_m, _) = run(&crit);
    let (k, m) = (json(&out_k), json(&out_m));
    assert_ne!(k["necessary_condition_003"], m["necessary_condition_003"]);
    assert_eq!(without(k, &["necessary_condition_003"]), without(m, &["necessary_condition_003"]));

    // a map on the general route (an axis through zero unbalance) at given speeds: nothing
    let map = ["map", "--config", &spatial, "--x", "dimensionless.m0=0:0.05:3", "--y", "omega=1:2:3", "--set", "dimensionless.delta_a=0.1"];
    let (_, err_k) = run(&[&map[..], &["--out", "mk"]].concat());
    assert_eq!(
        lines(&err_k),
        ["warning: map: dimensionless.delta_a beside the masses is an input of the 12-state linear model only: the spatial simulation's rotor, which map runs, has the masses' inertia and balls (m0, r0, m, r, n); it sets nothing in this run"]
    );
    let (_, err_m) = run(&["map", "--config", &spatial, "--x", "dimensionless.m0=0:0.05:3", "--y", "omega=1:2:3", "--out", "mm"]);
    assert!(lines(&err_m).is_empty(), "{err_m}");
    assert!(std::fs::read(d.join("mk.csv")).unwrap() == std::fs::read(d.join("mm.csv")).unwrap(), "the map, byte for byte");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn regression_basins_refused_every_set_of_a_linear_rotor() {
    // hunt 27: `basins` read a linear rotor config's `--set` as the spatial rotor's ("linear_rotor:
    // unknown table"), which every other command takes; the set is applied, and it is used
    let d = scratch("basins-linear-set");
    let shaft = short_shaft(&d);
    let run = |set: &str| {
        let (code, out, err) =
            run_in(&d, Duration::from_secs(120), &["basins", "--config", &shaft, "--n", "2", "--no-plots", "--set", set, "--format", "json", "--out", "b.csv"]);
        assert_eq!(code, 0, "--set {set}: {out} {err}");
        std::fs::read_to_string(d.join("b.csv")).unwrap()
    };
    let heavier = run("linear_rotor.balancer[0].ball_mass=0.05");
    let lighter = run("linear_rotor.balancer[0].ball_mass=0.01");
    assert_ne!(heavier, lighter, "the set is used");
    std::fs::remove_dir_all(&d).ok();
}
