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
    // the example is stable to the end of the axis (`autobal stability`: "412.692 rad/s to
    // 2543 rad/s (end of the axis)"): the summary and the section say so, as `stability` does,
    // rather than presenting the axis' end as where the stable range ends
    let summary = page.split("Linear rotor: the balanced state is stable").nth(1).unwrap_or("");
    let summary = &summary[..summary.find('.').map_or(summary.len(), |i| summary[i + 1..].find('.').map_or(summary.len(), |j| i + 1 + j))];
    assert!(summary.contains("(end of the axis)"), "the summary: {summary}");
    assert!(page.matches("(end of the axis)").count() >= 2, "the summary and the stability section");
    for fig in ["linear_rotor_modes_0", "linear_rotor_stability_margin", "linear_rotor_campbell_diagram", "linear_rotor_runup_amplitude_omega"] {
        for ext in ["svg", "png"] {
            assert!(dir.join("r").join(format!("{fig}.{ext}")).exists(), "{fig}.{ext}");
        }
    }
}

/// Two exact descriptions of one rigid rotor (paper 000's dimensional preset) give the same
/// natural frequencies at rest: `export-model`'s (node at the composite centre, the unbalance
/// mass's tilt inertia split ±m0R0²/2 between `M` and `M_rot`) and an independent one (audit
/// 20: node at the rotor's own centre of mass, `M_rot = m0R0²` on β alone, written below).
/// Both are the rotor at rest in its angle 0 with the balls as rings; the x/β and y/α blocks of
/// the second decouple, so each pair of frequencies is the closed-form root of the 2×2
/// `det(K − ω² (M + M_rot + rings)) = 0`. Without `M_rot` the two differ by 4e-5 (audit: 732.214
/// against 732.185 rad/s). Tolerance 1e-9 relative: the 4×4 eigenvalues by Cholesky and QR
/// on matrices of condition ~1e2, and the exported preset's digits (printed to 17).
#[test]
fn natural_frequencies_do_not_depend_on_how_the_inertia_is_split() {
    let dir = tmp("split");
    let mtx = |name: &str, entries: &[(usize, usize, f64)]| {
        let mut s = format!("%%MatrixMarket matrix coordinate real general\n4 4 {}\n", entries.len());
        for (i, j, v) in entries {
            s.push_str(&format!("{i} {j} {v:e}\n"));
        }
        std::fs::write(dir.join(name), s).unwrap();
    };
    // M_r = 20 kg, A_r = 0.6 kg m², the unbalance m0 = 0.01 kg at R0 = 0.1 m, s = 0.2 m from G;
    // supports k = 2.5e6 N/m at z_G ± 0.25 m (sum 5e6, moment k s² 3.125e5), c 300 N s/m each
    let (m0, s0, r0) = (0.01, 0.2, 0.1);
    mtx(
        "M.mtx",
        &[
            (1, 1, 20.0 + m0),
            (1, 4, m0 * s0),
            (2, 2, 20.0 + m0),
            (2, 3, -m0 * s0),
            (3, 2, -m0 * s0),
            (3, 3, 0.6 + m0 * s0 * s0),
            (4, 1, m0 * s0),
            (4, 4, 0.6 + m0 * s0 * s0),
        ],
    );
    mtx("K.mtx", &[(1, 1, 5e6), (1, 4, 2.5e5), (2, 2, 5e6), (2, 3, -2.5e5), (3, 2, -2.5e5), (3, 3, 3.125e5), (4, 1, 2.5e5), (4, 4, 3.125e5)]);
    mtx("C.mtx", &[(1, 1, 600.0), (2, 2, 600.0), (3, 3, 37.5), (4, 4, 37.5)]);
    mtx("G.mtx", &[(3, 4, 0.15 + m0 * r0 * r0), (4, 3, -(0.15 + m0 * r0 * r0))]);
    mtx("Mrot.mtx", &[(4, 4, m0 * r0 * r0)]);
    std::fs::write(
        dir.join("g.toml"),
        "[linear_rotor]\nlayout = \"x,y,alpha,beta\"\nm = \"M.mtx\"\nk = \"K.mtx\"\nc = \"C.mtx\"\ng = \"G.mtx\"\nrotor_fixed_mass = \"Mrot.mtx\"\n\
         [[linear_rotor.unbalance]]\nnode = 0\nme = 0.001\noffset = 0.2\n\
         [[linear_rotor.balancer]]\nnode = 0\nradius = 0.12\nballs = 2\nball_mass = 0.02\ndrag = 0.0072\noffset = 0.2\n",
    )
    .unwrap();
    let (code, _, err) = autobal(&["export-model", "--config", &example("dimensional.toml"), "--out", dir.join("c").to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let freqs = |cfg: &std::path::Path| -> Vec<f64> {
        let v = json(&["critical", "--config", cfg.to_str().unwrap(), "--format", "json"]);
        v["natural_frequencies"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
    };
    let (g, c) = (freqs(&dir.join("g.toml")), freqs(&dir.join("c").join("rotor.toml")));
    // the closed form of the 2×2 blocks: x/β (sign +1, M_rot on β) and y/α (sign −1)
    let (mb, rb, eb) = (0.04, 0.12, 0.2);
    let mut want = vec![];
    for (sign, mrot) in [(1.0, m0 * r0 * r0), (-1.0, 0.0)] {
        let m = [20.0 + m0 + mb, sign * (m0 * s0 + mb * eb), 0.6 + m0 * s0 * s0 + mrot + mb * eb * eb + 0.5 * mb * rb * rb];
        let k = [5e6, sign * 2.5e5, 3.125e5];
        // det(K − λM) = a λ² + b λ + c
        let a = m[0] * m[2] - m[1] * m[1];
        let b = -(k[0] * m[2] + k[2] * m[0] - 2.0 * k[1] * m[1]);
        let cc = k[0] * k[2] - k[1] * k[1];
        let d = (b * b - 4.0 * a * cc).sqrt();
        want.extend([((-b - d) / (2.0 * a)).sqrt(), ((-b + d) / (2.0 * a)).sqrt()]);
    }
    want.sort_by(f64::total_cmp);
    assert_eq!((g.len(), c.len()), (4, 4), "{g:?} {c:?}");
    for i in 0..4 {
        assert!((g[i] / want[i] - 1.0).abs() < 1e-9, "the rotor as given: {g:?} against the closed form {want:?}");
        assert!((c[i] / want[i] - 1.0).abs() < 1e-9, "export-model's: {c:?} against the closed form {want:?}");
    }
}
