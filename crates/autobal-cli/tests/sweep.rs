//! `autobal sweep` end to end: sharded runs merged equal the unsharded sweep, bit for bit
//! (every column but the wall time), and merge refuses what does not make one sweep.

use std::path::{Path, PathBuf};
use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn ok(args: &[&str]) -> String {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// The CSV without its last column (the wall time, which differs between runs).
fn without_wall_time(p: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(p).unwrap();
    text.lines().map(|l| l.rsplit_once(',').unwrap().0.to_string()).collect()
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-sweep-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

const GRID: &[&str] =
    &["--x", "drive.b=100:200:3", "--y", "planar.c_psi=0.05,0.1", "--axis", "drive.psi0[1]=1.4,1.6", "--set", "drive.t_end=1.5", "--set", "drive.omega0=250"];

#[test]
fn merged_shards_equal_the_unsharded_sweep() {
    let d = dir("merge");
    let s = |p: &str| d.join(p).to_str().unwrap().to_string();
    let mut args = vec!["sweep", "--out"];
    let full = s("full");
    args.push(&full);
    args.extend(GRID);
    ok(&args);
    let whole = without_wall_time(&d.join("full.csv"));
    assert_eq!(whole.len(), 1 + 12, "header and 3 × 2 × 2 points");
    assert!(whole[0].starts_with("point,drive.b,planar.c_psi,drive.psi0[1],peak_amplitude,"), "{}", whole[0]);
    // 5 shards of 12 points (sizes 3, 3, 2, 2, 2), run on one thread each, merged out of order
    let mut shards = vec![];
    for k in 1..=5 {
        let stem = s(&format!("part{k}"));
        let spec = format!("{k}/5");
        let mut a = vec!["sweep", "--threads", "1", "--shard", &spec, "--out", &stem];
        a.extend(GRID);
        ok(&a);
        shards.push(format!("{stem}.csv"));
    }
    let merged = s("merged");
    let mut a = vec!["merge", "--out", &merged];
    a.extend(shards.iter().rev().map(String::as_str));
    ok(&a);
    assert_eq!(without_wall_time(&d.join("merged.csv")), whole);
    let jw: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("full.json")).unwrap()).unwrap();
    let jm: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(d.join("merged.json")).unwrap()).unwrap();
    let strip = |v: &serde_json::Value| {
        let mut v = v.clone();
        for r in v["runs"].as_array_mut().unwrap() {
            r.as_object_mut().unwrap().remove("wall_time_s");
        }
        v
    };
    assert_eq!(strip(&jm), strip(&jw));
    // merge refuses a missing shard, a shard given twice, and shards of another sweep
    let (code, _, err) = autobal(&["merge", "--out", &s("x"), &shards[0], &shards[1], &shards[3], &shards[4]]);
    assert_eq!((code, err.trim()), (2, "error: shard 3 of 5 is missing"));
    let (code, _, err) = autobal(&["merge", "--out", &s("x"), &shards[0], &shards[0], &shards[1], &shards[2], &shards[3]]);
    assert_eq!(code, 2);
    assert!(err.contains("given twice"), "{err}");
    let other = s("other");
    let mut a = vec!["sweep", "--shard", "3/5", "--out", &other];
    a.extend(GRID);
    a.extend(["--set", "planar.c=40"]);
    ok(&a);
    let (code, _, err) = autobal(&["merge", "--out", &s("x"), &shards[0], &shards[1], &format!("{other}.csv"), &shards[3], &shards[4]]);
    assert_eq!(code, 2);
    assert!(err.contains("a different sweep") && err.contains("problem"), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn sweep_errors_name_the_option_and_path() {
    let spatial = format!("{}/../../examples/spatial.toml", env!("CARGO_MANIFEST_DIR"));
    for (args, start) in [
        (
            vec!["sweep", "--config", &spatial, "--x", "drive.omega0=1.5:1.7:2"],
            "error: config: `sweep` runs the planar rotor of paper 004 only ([planar], [drive]); the spatial rotor of papers 000/003 is simulated by `simulate`",
        ),
        (vec!["sweep", "--x", "drive.torque=1:2:2"], "error: --x drive.torque: the drive is of kind acceleration"),
        (vec!["sweep", "--x", "planar.c_pis=1:2:2"], "error: --x planar.c_pis: unknown parameter path"),
        (vec!["sweep", "--x", "drive.b=1:2:2", "--shard", "0/3"], "error: --shard 0/3: expected K/N"),
        (vec!["sweep", "--x", "drive.b=1:2:2", "--axis", "drive.b=3,4"], "error: --axis drive.b: the same key as --x"),
        (vec!["sweep", "--x", "planar.m3=0.03,-1"], "error: planar.m3: must"),
    ] {
        let d = dir("errors");
        let stem = d.join("nothing");
        let mut args = args.clone();
        args.extend(["--out", stem.to_str().unwrap()]);
        let (code, _, err) = autobal(&args);
        assert!(!d.join("nothing.csv").exists(), "{args:?}: no output for a sweep that cannot run");
        assert_eq!(code, 2, "{args:?}");
        assert!(err.starts_with(start), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}

/// `--out` is a stem: only the command's own extensions are taken off, so a dot inside a name
/// (`slow0.05`) stays; `simulate --out m3` writes m3.csv like the other commands, `--out x.csv`
/// writes x.csv as given.
#[test]
fn out_stems_keep_dots_and_simulate_adds_csv() {
    let d = dir("stems");
    let s = |p: &str| d.join(p).to_str().unwrap().to_string();
    let stem = s("slow0.05");
    let mut args = vec!["sweep", "--threads", "1", "--x", "drive.b=100,200", "--set", "drive.t_end=0.5", "--set", "drive.omega0=250", "--out", &stem];
    ok(&args);
    assert!(d.join("slow0.05.csv").exists() && d.join("slow0.05.json").exists(), "sweep kept the stem");
    assert!(!d.join("slow0.csv").exists(), "the stem's '.05' was taken for an extension");
    // a known extension given with the stem is not doubled
    let with_csv = s("b.csv");
    args.pop();
    args.push(&with_csv);
    ok(&args);
    assert!(d.join("b.csv").exists() && d.join("b.json").exists() && !d.join("b.csv.csv").exists());
    for (out, file) in [("m3", "m3.csv"), ("m3.5", "m3.5.csv"), ("given.csv", "given.csv")] {
        let o = s(out);
        ok(&["simulate", "--set", "drive.t_end=0.5", "--set", "drive.omega0=250", "--out", &o]);
        let text = std::fs::read_to_string(d.join(file)).unwrap_or_else(|e| panic!("--out {out}: no {file}: {e}"));
        assert!(text.starts_with("t,omega,"), "--out {out}: {file} is the samples' CSV");
    }
    assert!(!d.join("m3").exists() && !d.join("m3.5").exists(), "simulate wrote a file without .csv");
    assert!(d.join("m3.5_amplitude_t.svg").exists(), "plots beside the CSV as STEM_*.svg");
}

/// Every number in `p` (a CSV) in the shortest text that reads back to it: positional or with an
/// exponent, whichever is shorter (Rust's `{}` and `{:e}` both print the fewest round-trip
/// digits). Returns how many fields use an exponent.
fn check_shortest_numbers(p: &Path) -> usize {
    let text = std::fs::read_to_string(p).unwrap();
    let mut exponents = 0;
    for l in text.lines().skip(1) {
        for f in l.split(',') {
            let Ok(v) = f.parse::<f64>() else { continue };
            let (pos, exp) = (format!("{v}"), format!("{v:e}"));
            let want = if exp.len() < pos.len() { exp } else { pos };
            assert_eq!(f, want, "{}: {f} is not the shortest exact form of {v:e}", p.display());
            exponents += f.contains('e') as usize;
        }
    }
    exponents
}

#[test]
fn csv_numbers_are_shortest_round_trip() {
    let d = dir("numbers");
    let sim = d.join("sim.csv");
    ok(&["simulate", "--set", "drive.t_end=0.01", "--dt", "0.0001", "--set", "drive.omega0=250", "--out", sim.to_str().unwrap()]);
    // samples every 1e-4 s from rest: times and displacements this small are written with exponents
    assert!(check_shortest_numbers(&sim) > 0, "no tiny value written with an exponent");
    let stem = d.join("sweep");
    ok(&["sweep", "--threads", "1", "--x", "drive.b=100,200", "--set", "drive.t_end=0.5", "--set", "drive.omega0=250", "--out", stem.to_str().unwrap()]);
    check_shortest_numbers(&d.join("sweep.csv"));
}
