//! `autobal stability`, `simulate` and `export-model` on a linear rotor config
//! (`[linear_rotor]`, docs/guide/your-own-rotor.md).

use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-linrotor-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

/// The shaft example (reduced to 4 mode pairs) exported as Matrix Market files and read back
/// gives the same stability over speed, number for number (the files hold every digit); its
/// balancer balances above the first critical speed; the full model's onset agrees to 1e-5.
#[test]
fn export_model_reads_back_to_the_same_stability() {
    let dir = tmp("export");
    let cfg = example("linear_rotor_shaft.toml");
    let (code, _, err) = autobal(&["export-model", "--config", &cfg, "--out", dir.to_str().unwrap(), "--stem", "shaft"]);
    assert_eq!(code, 0, "{err}");
    for f in ["shaft.toml", "shaft_M.mtx", "shaft_C.mtx", "shaft_G.mtx", "shaft_K.mtx"] {
        assert!(dir.join(f).exists(), "{f}");
    }
    let a = json(&["stability", "--config", &cfg, "--samples", "20", "--omega-max", "2500 rad/s", "--format", "json"]);
    let b = json(&["stability", "--config", dir.join("shaft.toml").to_str().unwrap(), "--samples", "20", "--omega-max", "2500 rad/s", "--format", "json"]);
    assert_eq!(a["model"], "linear");
    assert_eq!(a["source"], "shaft");
    assert_eq!(b["source"], "matrices");
    assert_eq!(a["points"], b["points"]);
    assert_eq!(a["stable_ranges"], b["stable_ranges"]);
    assert_eq!(a["natural_frequencies"], b["natural_frequencies"]);
    let w1 = a["natural_frequencies"][0].as_f64().unwrap();
    let from = a["stable_ranges"][0]["from"].as_f64().unwrap();
    assert!(from > w1, "stable from {from} below the first critical speed {w1}");
    assert_eq!(a["reduction"]["dofs_reduced"], 16);
    let full = json(&["stability", "--config", &cfg, "--samples", "20", "--omega-max", "2500 rad/s", "--format", "json", "--set", "linear_rotor.modes=0"]);
    assert!(full["reduction"].is_null());
    let from_full = full["stable_ranges"][0]["from"].as_f64().unwrap();
    assert!((from - from_full).abs() < 1e-5 * from_full, "onset {from} reduced, {from_full} full");
    // without a config: paper 004's rotor with its race centred, as a Jeffcott rotor
    let (code, _, err) = autobal(&["export-model", "--out", dir.to_str().unwrap(), "--stem", "jeffcott"]);
    assert_eq!(code, 0, "{err}");
    let j = std::fs::read_to_string(dir.join("jeffcott.toml")).unwrap();
    assert!(j.contains("layout = \"x,y\"") && j.contains("[[linear_rotor.balancer]]"), "{j}");
    let c = json(&["stability", "--config", dir.join("jeffcott.toml").to_str().unwrap(), "--samples", "20", "--omega-max", "2500 rad/s", "--format", "json"]);
    assert!(!c["stable_ranges"].as_array().unwrap().is_empty());
}

/// A short run of the shaft example: the CSV's columns and rows, the JSON summary.
#[test]
fn simulate_writes_the_run() {
    let dir = tmp("sim");
    let out = dir.join("run.csv");
    let v =
        json(&["simulate", "--config", &example("linear_rotor_shaft.toml"), "--set", "drive.t_end=0.2", "--format", "json", "--out", out.to_str().unwrap()]);
    assert_eq!(v["model"], "linear");
    assert_eq!(v["t_end_reached"], 0.2);
    assert!(v["stopped"].is_null());
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), "t,omega,x_0,y_0,r_0,r_max,psi_0,psi_1");
    assert_eq!(lines.count(), 101); // dt = 0.002
}

/// Errors name the key, the file and the line.
#[test]
fn errors_name_the_key_file_and_line() {
    let dir = tmp("err");
    std::fs::write(dir.join("M.mtx"), "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 one\n").unwrap();
    std::fs::write(dir.join("r.toml"), "[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"M.mtx\"\n").unwrap();
    let (code, _, err) = autobal(&["stability", "--config", dir.join("r.toml").to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("linear_rotor.m: M.mtx: line 4: \"one\" is not a number"), "{err}");
    let (code, _, err) = autobal(&["stability", "--config", &example("linear_rotor_shaft.toml"), "--set", "linear_rotor.gyroscopic=1"]);
    assert_ne!(code, 0);
    assert!(err.contains("linear_rotor.gyroscopic: expected true or false"), "{err}");
}

/// `simulate` writes what it writes for the other models: the CSV, the Parquet file
/// (`--parquet`) with the same columns, the four figures beside the stem, the JSON summary;
/// `stability --svg` draws the margin. Every file through outfile: an output that cannot be
/// written is named before the run and nothing is left behind.
#[test]
fn simulate_writes_csv_parquet_and_figures_and_stability_draws_its_margin() {
    let dir = tmp("files");
    let cfg = example("linear_rotor_shaft.toml");
    let stem = dir.join("run");
    let v = json(&["simulate", "--config", &cfg, "--set", "drive.t_end=0.2", "--parquet", "--format", "json", "--out", stem.to_str().unwrap()]);
    assert_eq!(v["t_end_reached"], 0.2);
    let csv = std::fs::read_to_string(dir.join("run.csv")).unwrap();
    assert_eq!(csv.lines().count(), 102);
    let parquet = std::fs::read(dir.join("run.parquet")).unwrap();
    // a complete Parquet file: the magic at both ends (the footer written), the column names
    assert!(parquet.starts_with(b"PAR1") && parquet.ends_with(b"PAR1"));
    for name in csv.lines().next().unwrap().split(',') {
        assert!(parquet.windows(name.len()).any(|w| w == name.as_bytes()), "{name} not in the Parquet schema");
    }
    for suffix in ["amplitude_omega", "amplitude_t", "psi_t", "omega_t"] {
        let svg = std::fs::read_to_string(dir.join(format!("run_{suffix}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("Linear rotor"), "{suffix}");
    }
    // the figure of stability
    let svg = dir.join("margin.svg");
    let s = json(&["stability", "--config", &cfg, "--samples", "20", "--svg", svg.to_str().unwrap(), "--format", "json"]);
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(drawn.contains("stability margin") && !s["stable_ranges"].as_array().unwrap().is_empty());
    // an output that cannot be written (the Parquet name is a folder): refused before the run,
    // nothing written, no temporary file left
    let bad = tmp("files-bad");
    std::fs::create_dir_all(bad.join("run.parquet")).unwrap();
    let (code, _, err) = autobal(&["simulate", "--config", &cfg, "--set", "drive.t_end=0.2", "--parquet", "--out", bad.join("run").to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("--parquet") && err.contains("is a folder"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&bad).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    assert_eq!(left, vec!["run.parquet".to_string()]);
    // a run that fails (a bad --dt) leaves no file either
    let (code, _, err) = autobal(&["simulate", "--config", &cfg, "--dt=-1", "--out", bad.join("x").to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("--dt"), "{err}");
    assert_eq!(std::fs::read_dir(&bad).unwrap().count(), 1);
    // --svg in a "folder" that is a file: named before the computation
    std::fs::write(bad.join("file"), "").unwrap();
    let (code, _, err) = autobal(&["stability", "--config", &cfg, "--samples", "20", "--svg", bad.join("file").join("m.svg").to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("--svg") && err.contains("is not a folder"), "{err}");
}

/// The report on a linear rotor config: its own section (modes at the balancer plane, the
/// stability over speed, the Campbell diagram, the run-up), every figure as SVG and PNG.
#[test]
fn the_report_has_a_section_for_the_linear_rotor() {
    let dir = tmp("report");
    let (code, _, err) =
        autobal(&["report", "--config", &example("linear_rotor_shaft.toml"), "--set", "drive.t_end=0.5", "--quick", "--out", dir.join("r").to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let page = std::fs::read_to_string(dir.join("r").join("index.html")).unwrap();
    for id in ["linear_rotor_modes", "linear_rotor_stability", "linear_rotor_campbell", "linear_rotor_runup"] {
        assert!(page.contains(&format!("id=\"{id}\"")), "{id}");
    }
    assert!(page.contains("Linear rotor: the balanced state is stable"), "the summary");
    for fig in ["linear_rotor_modes_0", "linear_rotor_stability_margin", "linear_rotor_campbell_diagram", "linear_rotor_runup_amplitude_omega"] {
        for ext in ["svg", "png"] {
            assert!(dir.join("r").join(format!("{fig}.{ext}")).exists(), "{fig}.{ext}");
        }
    }
}
