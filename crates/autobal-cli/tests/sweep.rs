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
        (vec!["sweep", "--config", &spatial, "--x", "planar.c_psi=0.1,0.2"], "error: --x planar.c_psi: a key of the planar rotor of paper 004"),
        (vec!["sweep", "--config", &spatial, "--x", "dimensionless.z_q=1,2"], "error: --x dimensionless.z_q:"),
        (vec!["sweep", "--config", &spatial, "--x", "drive.psi0[3]=1,2"], "error: --x drive.psi0[3]: element 3 of 2"),
        (vec!["sweep", "--config", &spatial, "--x", "dimensionless.m0=0.01,-0.01"], "error: dimensionless.m0:"),
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

/// The two-plane SI example (static and couple unbalance, two ball sets, gravity, anisotropic
/// supports) cut to half a second: every table of the spatial simulation takes part.
fn two_plane() -> String {
    format!("{}/../../examples/spatial_two_plane.toml", env!("CARGO_MANIFEST_DIR"))
}

const SPATIAL_GRID: &[&str] =
    &["--x", "balancer.ball_mass=0.015,0.02,0.025", "--y", "supports.stiffness_left_y=2e6,2.6e6", "--axis", "balancer2.drag=0.5,1", "--set", "drive.t_end=0.5"];

/// A spatial sweep's row is `autobal simulate` of the config with the point's values set, bit
/// for bit in every column but the wall time; shards merged equal the unsharded sweep.
#[test]
fn spatial_sweep_points_are_simulate_runs_and_shards_merge() {
    let d = dir("spatial");
    let s = |p: &str| d.join(p).to_str().unwrap().to_string();
    let cfg = two_plane();
    let full = s("full");
    let mut args = vec!["sweep", "--config", &cfg, "--out", &full, "--format", "json"];
    args.extend(SPATIAL_GRID);
    let printed: serde_json::Value = serde_json::from_str(&ok(&args)).unwrap();
    assert_eq!(printed["problem"]["model"], "spatial");
    let text = std::fs::read_to_string(d.join("full.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12, "3 × 2 × 2 points");
    assert_eq!(
        head[4..].join(","),
        "peak_amplitude,omega_at_peak,t_at_peak,final_amplitude,final_omega,balanced,completed,t_reached,steps,rejected_steps,rhs_evaluations,\
         contacts,stick_slip_transitions,outcome,residual_unbalance,residual_couple,static_sag,wall_s"
    );
    // the axes reach the rotor: the points differ
    let col = |c: &str| head.iter().position(|h| *h == c).unwrap();
    assert_ne!(rows[0][col("peak_amplitude")], rows[1][col("peak_amplitude")]);
    // points 0, 7 and 11 (every axis at another value) against `autobal simulate --set`
    for r in [&rows[0], &rows[7], &rows[11]] {
        let sets: Vec<String> = (1..4).map(|j| format!("{}={}", head[j], r[j])).collect();
        let mut a = vec!["simulate", "--config", &cfg, "--set", "drive.t_end=0.5", "--format", "json"];
        for set in &sets {
            a.extend(["--set", set.as_str()]);
        }
        let out = s(&format!("sim{}", r[0]));
        a.extend(["--out", &out]);
        let text = ok(&a);
        let j: serde_json::Value = serde_json::from_str(&text).unwrap();
        // a number as printed (the shortest text that reads back to it), read with Rust's exact
        // parser: serde_json's own may be 1 ulp off
        let num = |k: &str| -> f64 {
            let at = text.find(&format!("\n  \"{k}\": ")).unwrap_or_else(|| panic!("no top-level {k}")) + k.len() + 7;
            let end = text[at..].find([',', '\n']).unwrap() + at;
            text[at..end].parse().unwrap_or_else(|_| panic!("{k}: {}", &text[at..end]))
        };
        let outcome = ["not_settled", "not_balanced", "partially_balanced", "balanced"].iter().position(|o| j["outcome"] == *o).unwrap() as f64;
        let expected = [
            ("peak_amplitude", num("peak_amplitude")),
            ("omega_at_peak", num("omega_at_peak")),
            ("t_at_peak", num("t_at_peak")),
            ("final_amplitude", num("final_amplitude")),
            ("final_omega", num("final_omega")),
            ("balanced", if j["balanced"] == true { 1.0 } else { 0.0 }),
            ("completed", if j["stopped"].is_null() { 1.0 } else { 0.0 }),
            ("t_reached", num("t_end")),
            ("steps", num("steps")),
            ("rejected_steps", num("rejected_steps")),
            ("rhs_evaluations", num("rhs_evaluations")),
            ("contacts", num("contacts")),
            ("stick_slip_transitions", num("stick_slip_transitions")),
            ("outcome", outcome),
            ("residual_unbalance", num("residual_unbalance")),
            ("residual_couple", if j["residual_couple"].is_null() { f64::NAN } else { num("residual_couple") }),
            // (null where the run has not settled, session 29: NaN in the CSV)
            ("static_sag", if j["static_sag"].is_null() { f64::NAN } else { num("static_sag") }),
        ];
        for (c, want) in expected {
            let got: f64 = r[col(c)].parse().unwrap();
            assert_eq!(got.to_bits(), want.to_bits(), "point {}: {c} = {got:e} in the sweep, {want:e} by simulate ({sets:?})", r[0]);
        }
        assert_eq!(num("t_end"), 0.5, "the run completed");
    }
    // 5 shards on one thread each, merged out of order, equal the unsharded sweep
    let whole = without_wall_time(&d.join("full.csv"));
    let mut shards = vec![];
    for k in 1..=5 {
        let stem = s(&format!("part{k}"));
        let spec = format!("{k}/5");
        let mut a = vec!["sweep", "--config", &cfg, "--threads", "1", "--shard", &spec, "--out", &stem];
        a.extend(SPATIAL_GRID);
        ok(&a);
        shards.push(format!("{stem}.csv"));
    }
    let merged = s("merged");
    let mut a = vec!["merge", "--out", &merged];
    a.extend(shards.iter().rev().map(String::as_str));
    ok(&a);
    assert_eq!(without_wall_time(&d.join("merged.csv")), whole);
    // a shard of the same grid on another config is refused
    let other = s("other");
    let mut a = vec!["sweep", "--config", &cfg, "--shard", "2/5", "--out", &other];
    a.extend(SPATIAL_GRID);
    a.extend(["--set", "balancer.drag=0.7"]);
    ok(&a);
    let (code, _, err) = autobal(&["merge", "--out", &s("x"), &shards[0], &format!("{other}.csv"), &shards[2], &shards[3], &shards[4]]);
    assert_eq!(code, 2);
    assert!(err.contains("a different sweep") && err.contains("problem"), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

/// `--format json` prints `STEM.json` as written (streamed from the runs spilled to a scratch
/// file, which is gone afterwards), valid JSON with every run, one run per line.
#[test]
fn printed_json_is_the_json_file_and_no_scratch_is_left() {
    let d = dir("stream");
    let stem = d.join("s").to_str().unwrap().to_string();
    let mut args = vec!["sweep", "--out", &stem, "--format", "json"];
    args.extend(GRID);
    let printed = ok(&args);
    let file = std::fs::read_to_string(d.join("s.json")).unwrap();
    assert_eq!(printed, file);
    let j: serde_json::Value = serde_json::from_str(&file).unwrap();
    assert_eq!(j["runs"].as_array().unwrap().len(), 12);
    assert_eq!(file.lines().filter(|l| l.starts_with("    {\"point\":")).count(), 12);
    let mut names: Vec<String> = std::fs::read_dir(&d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["s.csv", "s.json", "s_final.svg", "s_peak.svg"], "only the outputs are left");
    std::fs::remove_dir_all(&d).ok();
}
