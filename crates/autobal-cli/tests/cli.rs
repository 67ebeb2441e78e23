//! End-to-end tests of the `autobal` binary: outputs, JSON schema, errors.

use std::process::Command;

/// The Python that has `modules`: `$AUTOBAL_PYTHON`, else the repository's `.venv`, else
/// `python3`. `None` (the test is skipped, with a message saying what to install) when none
/// has them, unless `AUTOBAL_REQUIRE_PYTHON` is set (scripts/test.sh and CI set it): then the
/// test fails with the same message.
fn python_with(modules: &[&str]) -> Option<String> {
    let venv = format!("{}/../../.venv/bin/python", env!("CARGO_MANIFEST_DIR"));
    let candidates = std::env::var("AUTOBAL_PYTHON").into_iter().chain([venv, "python3".to_string()]);
    let import = format!("import {}", modules.join(", "));
    for py in candidates {
        if Command::new(&py).args(["-c", &import]).output().is_ok_and(|o| o.status.success()) {
            return Some(py);
        }
    }
    let msg = format!(
        "this cross-check needs Python with {}: run scripts/test.sh (it creates .venv with them), \
         or set AUTOBAL_PYTHON to a python that has them",
        modules.join(", ")
    );
    if std::env::var_os("AUTOBAL_REQUIRE_PYTHON").is_some() {
        panic!("{msg}");
    }
    eprintln!("skipped: {msg}");
    None
}

/// The `autobal` command under test: `$AUTOBAL_BIN` (scripts/test.sh runs these tests once more
/// on the wheel's console script, `.venv/bin/autobal`), else the binary cargo built.
fn bin() -> String {
    std::env::var("AUTOBAL_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_autobal").to_string())
}

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(bin()).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).expect("valid JSON")
}

fn examples(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn critical_json_has_the_documented_fields() {
    let v = json(&["critical", "--format", "json", "--set", "dimensionless.l_left=0.8", "--set", "analysis.anisotropy=paper"]);
    let cs = v["critical_speeds"].as_array().unwrap();
    assert_eq!(cs.len(), 4);
    let w: Vec<f64> = cs.iter().map(|c| c["omega"].as_f64().unwrap()).collect();
    assert!(w.windows(2).all(|p| p[0] <= p[1]), "ascending");
    assert_eq!(cs[0]["kind"], "transverse");
    assert_eq!(cs[3]["kind"], "angular");
    assert!(cs[0]["branch"].is_u64());
    assert!((w[3] - 3.80).abs() < 0.005);
    assert_eq!(v["rotor_type"], "long");
    assert_eq!(v["anisotropy"]["used"], v["anisotropy"]["paper"]);
    assert_eq!(v["anisotropy"]["exact"].as_f64(), Some(0.0));
    let r = v["autobalancing_ranges"].as_array().unwrap();
    assert!(r.last().unwrap()[1].is_null(), "last range unbounded");
    // audit 25's F4: 003's ranges are labelled a necessary condition in the JSON too
    assert!(v["autobalancing_ranges_are"].as_str().unwrap().starts_with("necessary condition (paper 003"), "{}", v["autobalancing_ranges_are"]);
    assert!(v["antiresonance_speed"].as_f64().unwrap() > 0.0);
}

#[test]
fn delta_a_given_directly_reproduces_003() {
    // `delta_a` serves as ΔĀ and ΔĀ0: 003's worked example for l_L = 0.8
    let dir = std::env::temp_dir().join(format!("autobal-cfg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = dir.join("c.toml");
    std::fs::write(&cfg, "[dimensionless]\nc_sigma = 0.75\nrho_s = 0.4\nl_left = 0.8\nz_a = 0.8\ndelta_a = 0.1\n").unwrap();
    let v = json(&["critical", "--format", "json", "--config", cfg.to_str().unwrap()]);
    assert!((v["antiresonance_speed"].as_f64().unwrap() - 2.24).abs() < 0.005);
    let r = v["autobalancing_ranges"].as_array().unwrap();
    assert!((r[0][0].as_f64().unwrap() - 0.849).abs() < 0.0005);
    assert!((r[1][0].as_f64().unwrap() - 3.80).abs() < 0.005);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn dimensional_example_runs_and_reports_si() {
    let v = json(&["critical", "--config", &examples("dimensional.toml"), "--format", "json"]);
    let c = &v["critical_speeds"][0];
    assert!(c["rpm"].as_f64().unwrap() > 1000.0);
    let ratio = c["omega_rad_s"].as_f64().unwrap() / c["omega"].as_f64().unwrap();
    assert!((ratio - v["model"]["scale"]["omega0"].as_f64().unwrap()).abs() < 1e-9 * ratio);
}

#[test]
fn ranges_and_inertia_commands() {
    let v = json(&["ranges", "--format", "json"]);
    assert!(v["autobalancing_ranges"].is_array());
    let v = json(&["inertia", "--format", "json"]);
    assert!(v["inertia"]["a_c1"].as_f64().unwrap() >= v["inertia"]["a_c2"].as_f64().unwrap());
    let (code, out, _) = autobal(&["critical"]);
    assert_eq!(code, 0);
    // 003's condition is printed as what it is, a necessary one
    assert!(out.contains("critical speeds") && out.contains("necessary condition for autobalancing (003)"));
}

#[test]
fn bad_input_is_one_line_naming_the_field() {
    let dim = examples("dimensional.toml");
    for (args, field) in [
        (vec!["critical", "--set", "dimensionless.rho_s=-1"], "dimensionless.rho_s"),
        (vec!["critical", "--set", "dimensionless.bogus=1"], "dimensionless.bogus"),
        (vec!["critical", "--set", "dimensionless.m0=nan"], "dimensionless.m0"),
        (vec!["critical", "--config", &dim, "--set", "supports.z_right=-1"], "supports.z_right"),
        (vec!["critical", "--config", &dim, "--set", "rotor.mass=-3"], "rotor.mass"),
        (vec!["critical", "--config", &dim, "--set", "balancer.balls=0"], "balancer.balls"),
        (vec!["critical", "--config", "/nonexistent.toml"], "--config"),
    ] {
        let (code, out, err) = autobal(&args);
        assert_ne!(code, 0, "{args:?} should fail");
        assert!(out.is_empty());
        assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
        assert!(err.contains(field), "{err} should name {field}");
        assert!(!err.contains("panicked") && !err.contains("backtrace"));
    }
}

/// One quick report of the papers (`report --papers`) shared by the report tests (written once
/// per test run).
fn quick_report() -> &'static std::path::Path {
    static DIR: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        // under target/ (replaced by the next run, so nothing piles up in /tmp)
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-quick");
        let _ = std::fs::remove_dir_all(&dir);
        let (code, _, err) = autobal(&["report", "--papers", "--quick", "--out", dir.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
        let n = err.lines().filter(|l| l.starts_with("report: [")).count();
        assert!(n >= 6 && err.contains(&format!("[{n}/{n}]")), "progress per section: {err}");
        assert!(err.contains("report: the papers' reproductions"), "{err}");
        dir
    })
}

/// The papers' report has every paper's section; `--papers` is the papers' report only, so a
/// config beside it is refused (the report of a config is about that rotor).
#[test]
fn papers_report_has_the_papers_sections() {
    let index = std::fs::read_to_string(quick_report().join("index.html")).unwrap();
    for id in ["paper000", "paper003", "paper004", "paper004torque", "friction", "stability"] {
        assert!(index.contains(&format!("<section id=\"{id}\">")), "section {id}");
    }
    assert!(!index.contains("id=\"summary\""), "the papers' report has no summary of a user's rotor");
    let (code, _, err) = autobal(&["report", "--papers", "--config", &examples("washing_machine.toml"), "--out", "/nonexistent/r"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("'--papers' cannot be used with '--config"), "{err}");
}

/// The summary's verdict marker of a user's report: `data-stable` of `<span id="verdict">`.
fn report_verdict(index: &str) -> Option<bool> {
    let at = index.find("<span id=\"verdict\" data-stable=\"")? + "<span id=\"verdict\" data-stable=\"".len();
    Some(index[at..].starts_with("true"))
}

#[test]
fn report_writes_index_and_figures() {
    let dir = quick_report();
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let files: Vec<String> = std::fs::read_dir(dir).unwrap().filter_map(|e| e.ok()).map(|e| e.file_name().into_string().unwrap()).collect();
    let svgs: Vec<&String> = files.iter().filter(|f| f.ends_with(".svg")).collect();
    assert!(svgs.len() >= 30, "{} figures", svgs.len());
    for name in &svgs {
        assert!(index.contains(name.as_str()), "index links {name}");
        let png = name.replace(".svg", ".png");
        assert!(files.contains(&png), "{png} beside {name}");
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
        assert!(!text.contains("NaN") && !text.contains("inf"));
    }
    // self-contained: the plotting library and its licence are in the folder, nothing is fetched
    for f in ["plotly-cartesian.min.js", "plotly-LICENSE.txt", "report.js"] {
        assert!(files.iter().any(|x| x == f), "{f} in the report folder");
    }
    assert!(!index.contains("http://") && !index.contains("https://") && !index.contains("//cdn"), "no network at view time");
    // every figure's data is embedded, and printed floats keep at most 6 significant digits
    let figures = index.matches("<div class=\"plot\" data-fig=").count();
    assert_eq!(figures, index.matches("<script type=\"application/json\"").count());
    assert_eq!(figures, svgs.len());
    assert!(!index.contains("0.014492753623188406"));
    // the figures of both papers, including those once missing, and real balls' residual against
    // friction (the browser test draws every one of them)
    for id in [
        "fig000_3_spectrum",
        "fig000_9a_sensitivity_vs_anisotropy",
        "fig000_9b_sensitivity_vs_ball_mass",
        "fig003_3_signed_response",
        "campbell_fixed",
        "campbell_modes",
        "stability_map_z_a",
        "balls_residual_vs_friction",
    ] {
        assert!(files.iter().any(|f| f == &format!("{id}.svg")), "{id}");
    }
    // 003's figures use 003's own ΔĀ0 = 0.1: its printed Ω_K4 = 3.80 and Ω_a = 2.24 appear
    let fig3 = std::fs::read_to_string(dir.join("fig003_3_signed_response.svg")).unwrap();
    assert!(fig3.contains("K4 = 3.8") && fig3.contains("Ω_a = 2.24"), "003 Fig. 3 markers");
}

/// Where the browser test can run: `(node, script)`, or why not. The test is skipped with that
/// message unless `AUTOBAL_REQUIRE_BROWSER` or `CI` is set (scripts/test.sh sets the former when
/// it could install Chromium and the npm packages): then it fails with it.
fn browser() -> Option<(String, String)> {
    let dir = format!("{}/tests/browser", env!("CARGO_MANIFEST_DIR"));
    let chromium = std::env::var("AUTOBAL_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    let node_ok = Command::new("node").arg("--version").output().is_ok_and(|o| o.status.success());
    let missing: Vec<String> = [
        (!std::path::Path::new(&chromium).exists())
            .then(|| format!("Chromium at {chromium} (Debian/Ubuntu: sudo apt-get install chromium; or set AUTOBAL_CHROMIUM)")),
        (!node_ok).then(|| "Node.js (Debian/Ubuntu: sudo apt-get install nodejs npm)".to_string()),
        (!std::path::Path::new(&format!("{dir}/node_modules/playwright-core")).exists())
            .then(|| format!("the npm packages of {dir} (cd there and run: npm ci; playwright-core never downloads a browser)")),
    ]
    .into_iter()
    .flatten()
    .collect();
    if missing.is_empty() {
        return Some(("node".into(), format!("{dir}/report.mjs")));
    }
    let msg = format!("the report's browser test needs {}; scripts/test.sh installs them when run as root", missing.join(", "));
    if std::env::var_os("AUTOBAL_REQUIRE_BROWSER").is_some() || std::env::var_os("CI").is_some() {
        panic!("{msg}");
    }
    eprintln!("skipped: {msg}");
    None
}

#[test]
fn report_renders_in_a_headless_browser() {
    // crates/autobal-cli/tests/browser/report.mjs: Debian's Chromium driven by playwright-core
    // opens the quick report and checks: no console or page errors and no request outside the
    // folder, every figure drawn by Plotly with all its data points, every contents link lands.
    let Some((node, script)) = browser() else { return };
    let dir = quick_report();
    let out = Command::new(node).arg(&script).arg(dir).output().expect("node runs");
    let (so, se) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{so}\n{se}");
    assert!(so.contains(" passed, 0 failed"), "{so}");
}

/// A real machine in SI (examples/washing_machine.toml): the report is about that rotor only
/// (no paper's section), its summary's verdict at the operating speed is `autobal stability`'s,
/// it analyses and simulates that rotor with speeds in rad/s and rpm and amplitudes in mm, on
/// the axes, in the tables and in the captions, and it renders in the browser like the papers'.
#[test]
fn dimensional_report_is_in_si_and_renders() {
    let cfg = examples("washing_machine.toml");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-washer");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, _, err) = autobal(&["report", "--quick", "--config", &cfg, "--out", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("report: about the config's rotor"), "{err}");
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(index.contains("Your rotor (dimensional config)"));
    // the user's rotor only: no paper's section, no paper's figure
    for id in ["paper000", "paper003", "paper004", "paper004torque", "friction"] {
        assert!(!index.contains(&format!("<section id=\"{id}\">")), "no section {id}");
    }
    let files: Vec<String> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).map(|e| e.file_name().into_string().unwrap()).collect();
    assert!(files.iter().all(|f| !f.starts_with("fig0")), "no paper's figure: {files:?}");
    // every section that does not apply says why, on the page and in the progress line
    for l in err.lines().filter(|l| l.starts_with("report: [")) {
        assert!(!l.contains("not applicable") || l.contains("not applicable ("), "a reason: {l}");
    }
    assert!(index.contains("needs a [planar] config: not applicable to a spatial rotor"), "the passage says why");
    // the summary at the top: the verdict at 1400 rpm is `stability`'s, word for word
    let st = json(&["stability", "--config", &cfg, "--format", "json"]);
    assert_eq!(report_verdict(&index), st["operating_speed"]["stable"].as_bool(), "the summary's verdict is stability's");
    let (_, table, _) = autobal(&["stability", "--config", &cfg]);
    let line = table.lines().find(|l| l.starts_with("operating speed")).expect("stability's verdict line");
    let summary = &index[index.find("id=\"summary\"").unwrap()..index.find("<nav id=\"toc\"").unwrap()];
    assert!(summary.contains(&line.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")), "{line} in {summary}");
    assert!(summary.contains("The run-up (from rest to 1\u{202F}400 rpm) peaks at"), "{summary}");
    // the rotor the closed form represents: 003's ranges with what they are (audit 20, F4)
    assert!(index.contains("</b> by 003's necessary condition (necessary, not sufficient"), "003's caveat");
    // the basins at 1400 rpm: the count of balanced runs is `autobal basins`' with the same
    // drive (200 revolutions at the operating speed, the quick report's 6 × 6 grid)
    let w = 1400.0 * std::f64::consts::PI / 30.0;
    let t_end = 200.0 * std::f64::consts::TAU / w;
    let csv = dir.join("basins-check.csv");
    let sets =
        [r#"drive.kind="speed""#.to_string(), format!("drive.omega0={w:?}"), format!("drive.t_end={t_end:?}"), format!("integration.dt={:?}", t_end / 200.0)];
    let mut args = vec!["basins", "--config", &cfg, "--n", "6", "--format", "json", "--out", csv.to_str().unwrap()];
    for s in &sets {
        args.extend(["--set", s]);
    }
    let b = json(&args);
    let want = format!("{} of {} starts of the balls", b["balanced"], b["runs"]);
    assert!(summary.contains(&want), "{want} in {summary}");
    // the design maps of the brief: balancer position, ball mass, ball drag, against rpm
    for name in ["design_balancer_z", "design_balancer_ball_mass", "design_balancer_drag"] {
        let t = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
        assert!(t.contains("speed n (rpm)") && t.contains("operating speed"), "{name}");
    }
    // the critical speeds in rpm as `autobal critical` computes them, in the report's table
    let c = json(&["critical", "--config", &cfg, "--format", "json"]);
    for k in c["critical_speeds"].as_array().unwrap() {
        // grouped by thousands with a narrow no-break space, as the report prints them
        let digits = format!("{:.0}", k["rpm"].as_f64().unwrap());
        let grouped: String =
            digits.chars().enumerate().flat_map(|(i, ch)| ((i > 0 && (digits.len() - i) % 3 == 0).then_some('\u{202F}')).into_iter().chain([ch])).collect();
        let rpm = format!("<td>{grouped}</td>");
        assert!(index.contains(&rpm), "{rpm} in the critical speeds' table");
    }
    let svg = |name: &str| std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
    // speed axes in rad/s with rpm along the top; amplitudes in mm; growth rates in 1/s
    for name in ["rotor_response", "campbell_fixed", "campbell_rotating", "stability_margin", "spatial_run_amplitude_omega"] {
        let t = svg(name);
        assert!(t.contains("ω (rad/s)") && t.contains("n (rpm)"), "{name}: speed in rad/s and rpm");
    }
    assert!(svg("rotor_response").contains("(mm)") && svg("spatial_run_amplitude_omega").contains("radius (mm)"));
    assert!(svg("stability_margin").contains("1/s"));
    assert!(svg("stability_margin").contains("operating speed"), "the operating speed marked");
    // the user's rotor is simulated (its 3 balls), not paper 004's
    assert!(index.contains("simulated in time with its 3 balls"));
    // Campbell in fixed axes: one legend entry per mode (both components toggled together)
    let fixed = svg("campbell_fixed");
    assert!(!fixed.contains("(Ω − ν)") && !fixed.contains("(Ω + ν)"));
    for k in 1..=12 {
        assert!(fixed.matches(&format!(">mode {k}:")).count() <= 1, "mode {k} once in the legend");
    }
    if let Some((node, script)) = browser() {
        let out = Command::new(node).arg(&script).arg(&dir).output().expect("node runs");
        let (so, se) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        assert!(out.status.success() && so.contains(" passed, 0 failed"), "{so}\n{se}");
    }
}

/// The summary's verdict follows `stability` where it is NOT stable too (the marker is not a
/// constant): the washer's balancer moved to the front is stable only at 312-529 rpm
/// (examples/washing_machine.toml), so not at its 1400 rpm spin.
#[test]
fn report_verdict_is_stabilitys_where_unstable() {
    let cfg = examples("washing_machine.toml");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-washer-front");
    let _ = std::fs::remove_dir_all(&dir);
    let set = ["--set", "balancer.z=0.40"];
    let mut args = vec!["report", "--quick", "--config", &cfg, "--out", dir.to_str().unwrap()];
    args.extend(set);
    let (code, _, err) = autobal(&args);
    assert_eq!(code, 0, "{err}");
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let mut args = vec!["stability", "--config", &cfg, "--format", "json"];
    args.extend(set);
    let st = json(&args);
    assert_eq!(st["operating_speed"]["stable"].as_bool(), Some(false));
    assert_eq!(report_verdict(&index), Some(false), "{err}");
    assert!(err.contains("report: summary: operating speed 1400 rpm") && err.contains("NOT STABLE"), "{err}");
}

/// A config the 12-state model does not represent as given (here a spin drag; also two planes,
/// gravity, supports that differ by direction) takes the general route in the report as in
/// `stability`: the summary's verdict is `stability`'s at the operating speed (JSON
/// `operating`, the state solved there), which lies in one of the stable ranges it prints
/// (rad/s).
#[test]
fn report_takes_the_general_route_as_stability_does() {
    let cfg = examples("washing_machine.toml");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-washer-general");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, _, err) = autobal(&["report", "--quick", "--config", &cfg, "--set", "spatial.spin_drag=0.01", "--out", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warning: the report's tables of papers 000/003 (parameters, eq (16) critical speeds, sensitivity, 003's ranges) use the rotor of papers 000/003 (isotropic supports, one balancer plane of point-mass balls, static unbalance): spatial.spin_drag is used only by `simulate`/`basins` and the report's general-route sections (stability, Campbell diagrams, critical speeds of the rotor as given, design maps) and run-up"),
        "{err}"
    );
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(index.contains("(general route)"), "the stability section by the general route");
    let st = json(&["stability", "--config", &cfg, "--set", "spatial.spin_drag=0.01", "--format", "json"]);
    assert_eq!(st["route"], "general");
    let op = 1400.0 * std::f64::consts::PI / 30.0;
    let inside = st["stable_ranges"].as_array().unwrap().iter().any(|r| r["from"].as_f64().unwrap() <= op && op <= r["to"].as_f64().unwrap());
    assert_eq!(report_verdict(&index), st["operating"]["stable"].as_bool());
    assert_eq!(report_verdict(&index), Some(inside));
    // the 000/003 tables say they are of the one-plane model, which leaves the spin drag out;
    // the critical speeds, Campbell diagrams and design maps are the rotor's as given
    assert!(index.contains("which leaves out spatial.spin_drag"));
    assert!(index.contains("Critical speeds of the rotor as given (general route)") && index.contains("by the general map on the rotor as given"));
    // the first section names what the one-plane model leaves out (as the warning above does)
    let first = &index[index.find("<section id=\"rotor\">").unwrap()..];
    let first = &first[..first.find("</section>").unwrap()];
    assert!(first.contains("The config has what that one-plane model leaves out: spatial.spin_drag"), "{first}");
    // 003's condition is not applied where `critical` says it does not apply (audit 20, F4)
    let (_, crit, _) = autobal(&["critical", "--config", &cfg, "--set", "spatial.spin_drag=0.01"]);
    assert!(crit.contains("003's necessary condition does not apply"), "{crit}");
    assert!(!index.contains("Autobalancing possible on") && first.contains("003's necessary condition does not apply to this configuration"), "{first}");
    // the run-up quotes the critical speeds of the rotor as given, `critical`'s, in rpm as the
    // report prints them (grouped by a narrow no-break space), not the one-plane model's alone
    // (audit 20, F5)
    let run = &index[index.find("<section id=\"spatial-run\">").unwrap()..];
    let run = &run[..run.find("</section>").unwrap()];
    assert!(run.contains("The critical speeds of the rotor as given, its balls held at balance (general route"), "{run}");
    let c = json(&["critical", "--config", &cfg, "--set", "spatial.spin_drag=0.01", "--format", "json"]);
    let speeds = c["locked_critical_speeds"]["speeds"].as_array().unwrap();
    assert!(!speeds.is_empty());
    for k in speeds {
        let digits = format!("{:.0}", k["rpm"].as_f64().unwrap());
        let grouped: String =
            digits.chars().enumerate().flat_map(|(i, ch)| ((i > 0 && (digits.len() - i) % 3 == 0).then_some('\u{202F}')).into_iter().chain([ch])).collect();
        assert!(run.contains(&format!("({grouped} rpm)")), "{grouped} rpm in {run}");
    }
}

#[test]
fn stability_json_has_ranges_and_margin() {
    let v = json(&["stability", "--format", "json", "--omega-max", "5", "--samples", "400"]);
    for k in ["stable_ranges", "necessary_ranges", "max_real_part"] {
        assert!(v[k].is_array(), "{k}");
    }
    let samples = v["max_real_part"].as_array().unwrap();
    assert!(samples.len() >= 400);
    assert!(samples.iter().all(|p| p[0].as_f64().unwrap() <= 5.0));
    // 003's last necessary range is unbounded: reported with hi = null
    assert!(v["necessary_ranges"].as_array().unwrap().last().unwrap()[1].is_null());
    // locked balls and no damping: stable everywhere except between split critical speeds,
    // whose ends are the analytic critical speeds
    let v = json(&[
        "stability",
        "--format",
        "json",
        "--balls",
        "locked",
        "--omega-max",
        "4.5",
        "--set",
        "analysis.anisotropy=paper",
        "--set",
        "dimensionless.h_x=0",
    ]);
    let c = json(&["critical", "--format", "json", "--set", "analysis.anisotropy=paper"]);
    let ks: Vec<f64> = c["critical_speeds"].as_array().unwrap().iter().map(|k| k["omega"].as_f64().unwrap()).collect();
    let ends: Vec<f64> = v["stable_ranges"].as_array().unwrap().iter().flat_map(|r| [r[0].as_f64(), r[1].as_f64()]).flatten().filter(|x| *x > 0.0).collect();
    for k in ks {
        assert!(ends.iter().any(|e| (e - k).abs() < 1e-6), "{k} not among {ends:?}");
    }
}

#[test]
fn campbell_and_map_write_their_files() {
    let dir = std::env::temp_dir().join(format!("autobal-lin-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("cb");
    let v = json(&["campbell", "--format", "json", "--points", "40", "--view", "components", "--svg", prefix.to_str().unwrap()]);
    assert_eq!(v["lines"].as_array().unwrap().len(), 12);
    assert!(dir.join("cb_fixed.svg").exists() && dir.join("cb_rotating.svg").exists());
    let stem = dir.join("map");
    let (code, _, err) = autobal(&["map", "--x", "dimensionless.z_a=-1:1:12", "--y", "omega=0.1:4:10", "--out", stem.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(dir.join("map.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 12 * 10);
    assert!(csv.starts_with("dimensionless.z_a,omega,max_real_part,stable,necessary"));
    let png = std::fs::read(dir.join("map.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(std::fs::read_to_string(dir.join("map.svg")).unwrap().contains("data:image/png;base64,"));
    // bad axis specs name the flag
    for (x, flag) in [("omega=1:0:10", "--x"), ("dimensionless.nope=0:1:5", "dimensionless.nope"), ("omega=0:1", "--x")] {
        let (code, _, err) = autobal(&["map", "--x", x, "--y", "dimensionless.z_a=0:1:3", "--out", stem.to_str().unwrap()]);
        assert_ne!(code, 0);
        assert!(err.contains(flag), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn interrupted_map_keeps_the_rows_written() {
    let dir = std::env::temp_dir().join(format!("autobal-int-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("big");
    let (code, _, err) =
        interrupted_after(&["map", "--x", "dimensionless.z_a=-2:2:1500", "--y", "omega=0.05:5:8000", "--threads", "1", "--out", stem.to_str().unwrap()], 1500);
    assert_ne!(code, Some(0), "should report the interruption");
    assert!(err.contains("interrupted"), "{err}");
    let csv = std::fs::read_to_string(dir.join("big.csv")).unwrap();
    let lines = csv.lines().count() - 1;
    assert!(lines > 0 && lines.is_multiple_of(1500), "whole rows only: {lines} lines");
    assert!(lines < 1500 * 8000);
    assert!(dir.join("big.png").exists(), "plots of the rows computed are written");
    std::fs::remove_dir_all(&dir).ok();
}

/// Run `autobal args`, send SIGINT after `ms` milliseconds, and return exit code, stdout, stderr.
///
/// With `AUTOBAL_BIN` the installed Python script (scripts/test.sh's last step), a SIGINT that
/// arrives while Python is still importing NumPy, before autobal has started, is Python's
/// `KeyboardInterrupt` in an import, not the command's interruption (session 33: CI at load 6-8
/// took over 0.5 s to import); such a run, or one killed silently before the CLI installed its
/// handler, is tried again with twice the delay, up to 4 times.
#[cfg(unix)]
fn interrupted_after(args: &[&str], ms: u64) -> (Option<i32>, String, String) {
    let mut ms = ms;
    for _ in 0..4 {
        let child = Command::new(bin()).args(args).stdout(std::process::Stdio::piped()).stderr(std::process::Stdio::piped()).spawn().unwrap();
        std::thread::sleep(std::time::Duration::from_millis(ms));
        let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
        let out = child.wait_with_output().unwrap();
        let err: String = String::from_utf8_lossy(&out.stderr).into();
        // Python's handler still in place (a traceback), or the default disposition between
        // `_cli.main` resetting it and the CLI installing its own (killed, nothing said)
        let before_start = err.contains("KeyboardInterrupt") || (out.status.code().is_none() && err.trim().is_empty());
        if !before_start {
            return (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), err);
        }
        // said, so that a handler installed later and later shows in the test's output
        eprintln!("{args:?}: SIGINT after {ms} ms came before the command had started; again after {} ms", 2 * ms);
        ms *= 2;
    }
    panic!("{args:?}: every SIGINT arrived before the command had installed its handler");
}

#[cfg(unix)]
#[test]
fn interrupted_shooting_stops_inside_the_first_speed() {
    // hunts 27-28: a stiff rotor (damping along y near its bound: the supports' damping ratio
    // ~900) takes seconds to minutes per speed in its shooting, which asked no control, so a
    // Ctrl-C was answered only after that speed. Now the integrations ask the thread's stop
    // probe: a Ctrl-C 0.5 s in stops the first speed's shooting, and nothing of it is reported
    // (before: the first speed finished and was reported, "1 of 10 speeds analysed")
    let cfg = format!("{}/../../examples/spatial_two_plane.toml", env!("CARGO_MANIFEST_DIR"));
    for cmd in [&["stability", "--samples", "10"][..], &["campbell", "--points", "5"][..]] {
        let args = [cmd, &["--config", &cfg, "--set", "supports.damping_left_y=1e7"][..]].concat();
        let (code, _, err) = interrupted_after(&args, 500);
        assert_eq!(code, Some(2), "{cmd:?}: {err}");
        assert!(err.contains("error: interrupted: 0 of"), "{cmd:?}: {err}");
    }
}

#[cfg(unix)]
#[test]
fn interrupted_campbell_writes_the_speeds_computed() {
    // ten million speeds take minutes: Ctrl-C after 1.5 s stops the run; the JSON holds the
    // speeds computed (every line as long as the speed axis), says it is incomplete, the figures
    // are written, and the command exits with 2 saying it was interrupted
    let dir = std::env::temp_dir().join(format!("autobal-campbell-int-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("cb");
    let (code, out, err) =
        interrupted_after(&["campbell", "--points", "10000000", "--format", "json", "--view", "components", "--svg", prefix.to_str().unwrap()], 1500);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("error: interrupted") && err.contains("of 10000000 speeds computed"), "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("the JSON of the speeds computed");
    assert_eq!(v["complete"], false);
    let done = v["omega"].as_array().unwrap().len();
    assert!(done > 0 && done < 10_000_000, "{done} speeds");
    for l in v["lines"].as_array().unwrap() {
        assert_eq!(l["modes"].as_array().unwrap().len(), done);
    }
    assert!(dir.join("cb_fixed.svg").exists() && dir.join("cb_rotating.svg").exists());
    // the table says where it stopped too
    let (code, out, err) = interrupted_after(&["campbell", "--points", "10000000"], 1500);
    assert_eq!(code, Some(2), "{err}");
    assert!(out.contains("Ω = "), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn interrupted_map_with_boundary_keeps_what_it_wrote() {
    // Ctrl-C in `map --boundary`: while the curves are traced (about 0.4 s here), the curves
    // traced so far are written and no map is computed (no empty CSV left); later, in the
    // 1500 × 8000 map, the whole boundary and the map's rows so far are kept. Either way the
    // command exits with 2 saying it was interrupted. (The tracer's own stop is tested in
    // autobal's tests/stability.rs, where it does not depend on timing.)
    let dir = std::env::temp_dir().join(format!("autobal-boundary-int-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("b");
    let (code, _, err) = interrupted_after(
        &["map", "--x", "dimensionless.z_a=-2:2:1500", "--y", "omega=0.05:4.5:8000", "--threads", "1", "--boundary", "--out", stem.to_str().unwrap()],
        1500,
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("error: interrupted"), "{err}");
    let boundary = std::fs::read_to_string(dir.join("b_boundary.csv")).unwrap();
    assert!(boundary.lines().next().is_some_and(|h| h.contains("dimensionless.z_a")), "{boundary}");
    if err.contains("while tracing the boundary") {
        assert!(!dir.join("b.csv").exists(), "no empty map");
    } else {
        let rows = std::fs::read_to_string(dir.join("b.csv")).unwrap().lines().count() - 1;
        assert!(rows.is_multiple_of(1500) && rows < 1500 * 8000, "{rows} lines");
        assert!(dir.join("b.png").exists());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn interrupted_report_says_so_and_fails() {
    // Ctrl-C during the full report (paper 004's passages take many seconds): the page is still
    // written, says it is incomplete, marks the runs cut short instead of printing their
    // numbers, and the command exits with 2.
    let dir = std::env::temp_dir().join(format!("autobal-report-int-{}", std::process::id()));
    let (code, _, err) = interrupted_after(&["report", "--out", dir.to_str().unwrap()], 2000);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("error: interrupted"), "{err}");
    // without --config the report is the papers'
    assert!(err.contains("report: the papers' reproductions"), "{err}");
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(index.contains("id=\"interrupted\""), "the page says it is incomplete");
    assert!(index.contains("interrupted at t = "), "runs cut short are marked, not reported as numbers");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn simulation_agrees_with_an_independent_scipy_integration_in_fixed_axes() {
    // bench/passage.py --check: paper 004's equations in fixed axes, written independently in
    // Python and integrated by SciPy's DOP853, against `autobal simulate` (rotor axes), both
    // against an autobal reference at rtol 1e-12: sampled radius of C within 1e-4 of the peak.
    // NumPy and SciPy come with scripts/test.sh (the README's test command).
    let Some(python) = python_with(&["numpy", "scipy"]) else { return };
    let script = format!("{}/../../bench/passage.py", env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(python).args([&script, "--check", "--exe", &bin()]).output().expect("python runs");
    assert!(out.status.success(), "{}\n{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
}

#[test]
fn spatial_benchmark_equations_agree_with_sympy_and_autobal() {
    // bench/spatial.py --check: the benchmark's NumPy right-hand side of the spatial rotor
    // against the tests' independent SymPy derivation (1e-9 relative; measured 7e-16) and a
    // 60 τ run-up integrated by SciPy's DOP853 against `autobal simulate` (1e-6 of the peak;
    // measured 6e-9): the benchmark times the same equations.
    let Some(python) = python_with(&["numpy", "scipy", "sympy"]) else { return };
    let script = format!("{}/../../bench/spatial.py", env!("CARGO_MANIFEST_DIR"));
    let out = Command::new(python).args([&script, "--check", "--exe", &bin()]).output().expect("python runs");
    assert!(out.status.success(), "{}\n{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
}

#[test]
fn simulate_writes_csv_summary_and_plots() {
    let dir = std::env::temp_dir().join(format!("autobal-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.csv");
    let v = json(&["simulate", "--format", "json", "--out", out.to_str().unwrap(), "--set", "drive.omega0=200", "--set", "drive.t_end=10", "--dt", "0.01"]);
    for k in ["peak_amplitude", "omega_at_peak", "final_amplitude", "balanced", "steps", "rhs_evaluations"] {
        assert!(!v[k].is_null(), "{k}");
    }
    let csv = std::fs::read_to_string(&out).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), "t,omega,x,y,amplitude,psi_1,psi_2");
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 1001);
    for r in &rows {
        assert!((r[4] - r[2].hypot(r[3])).abs() <= 1e-12 + 1e-9 * r[4], "amplitude = |(x, y)|");
    }
    assert!((rows[1000][0] - 10.0).abs() < 1e-9);
    for s in ["amplitude_omega", "amplitude_t", "psi_t", "omega_t"] {
        assert!(dir.join(format!("run_{s}.svg")).exists(), "{s}");
    }
    // errors name the field
    for (set, field) in [("planar.m1=-1", "planar.m1"), ("drive.kind=warp", "drive.kind"), ("drive.psi0=[1.0]", "drive.psi0"), ("planar.nope=1", "planar.nope")]
    {
        let (code, _, err) = autobal(&["simulate", "--out", out.to_str().unwrap(), "--set", set]);
        assert_ne!(code, 0);
        assert!(err.contains(field), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    // a sweep over two fields
    let stem = dir.join("sw");
    let v = json(&[
        "sweep",
        "--format",
        "json",
        "--out",
        stem.to_str().unwrap(),
        "--x",
        "drive.b=20:40:2",
        "--y",
        "planar.c_psi=0.05:0.1:2",
        "--set",
        "drive.t_end=20",
    ]);
    assert_eq!(v["runs"].as_array().unwrap().len(), 4);
    assert!(dir.join("sw.csv").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn map_csv_is_in_grid_order_whatever_the_thread_count() {
    let dir = std::env::temp_dir().join(format!("autobal-order-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut texts = vec![];
    for t in ["1", "2", "3"] {
        let stem = dir.join(format!("m{t}"));
        let (code, _, err) = autobal(&["map", "--x", "dimensionless.z_a=-1:1:23", "--y", "omega=0.1:4:150", "--threads", t, "--out", stem.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
        texts.push(std::fs::read_to_string(stem.with_extension("csv")).unwrap());
    }
    assert!(texts[0] == texts[1] && texts[1] == texts[2], "CSV differs with the thread count");
    // row-major: y outer, x inner
    let rows: Vec<Vec<f64>> = texts[0].lines().skip(1).map(|l| l.split(',').take(2).map(|v| v.parse().unwrap()).collect()).collect();
    for (k, r) in rows.iter().enumerate() {
        assert!((r[0] - (-1.0 + 2.0 * (k % 23) as f64 / 22.0)).abs() < 1e-9, "row {k}: {r:?}");
        assert!((r[1] - (0.1 + 3.9 * (k / 23) as f64 / 149.0)).abs() < 1e-9, "row {k}: {r:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn map_traces_the_boundary_as_curves() {
    let dir = std::env::temp_dir().join(format!("autobal-bnd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("m");
    let (code, _, err) = autobal(&["map", "--x", "dimensionless.z_a=-2:2:30", "--y", "omega=0.05:4.5:30", "--boundary", "--out", stem.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("boundary:") && err.contains("curves"), "{err}");
    let csv = std::fs::read_to_string(dir.join("m_boundary.csv")).unwrap();
    assert!(csv.starts_with("curve,kind,dimensionless.z_a,omega,hopf_frequency_squared,on_boundary"), "{csv}");
    let on = csv.lines().skip(1).filter(|l| l.ends_with(",1") && l.contains(",hopf,")).count();
    assert!(on > 20, "{on} Hopf points on the boundary");
    assert!(std::fs::read_to_string(dir.join("m.svg")).unwrap().contains("traced boundary"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The warning of the analytic commands on entries only the spatial simulation uses.
fn ignored_warning(command: &str, keys: &str, verb: &str) -> String {
    format!(
        "warning: {command} uses the rotor of papers 000/003 (isotropic supports, one balancer plane of point-mass balls, static unbalance): {keys} {verb} used only by `simulate`/`basins`"
    )
}

#[test]
fn analytic_commands_warn_about_entries_only_the_simulation_uses() {
    let two = examples("spatial_two_plane.toml");
    let keys = "supports.stiffness_left_y, supports.stiffness_right_y, [couple], [balancer2], spatial.gravity";
    // no analytic command ignores them any more: inertia gives the whole rotor's mass properties
    // and ranges the exact ranges (tests/inertia_ranges.rs); the others below
    for args in [["inertia"], ["ranges"]] {
        let mut a = args.to_vec();
        a.extend(["--config", &two]);
        let (code, _, err) = autobal(&a);
        assert_eq!(code, 0, "{err}");
        assert!(!err.contains(&ignored_warning(args[0], keys, "are")), "{err}");
        assert!(!err.contains(&format!("warning: {} uses", args[0])), "{err}");
    }
    // stability, critical and campbell use them all: they take the general route (the
    // nonlinear equations), say so, and warn about nothing
    let general: [&[&str]; 3] =
        [&["stability", "--samples", "10", "--omega-max", "1.5"], &["critical", "--omega-max", "1.5"], &["campbell", "--points", "3", "--omega-max", "1.5"]];
    for args in general {
        let mut a = args.to_vec();
        a.extend(["--format", "json", "--config", &two]);
        let (code, out, err) = autobal(&a);
        assert_eq!(code, 0, "{err}");
        assert!(!err.contains(&format!("warning: {} uses", args[0])), "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["route"], "general", "{}", args[0]);
        assert_eq!(v["stationary_state"], "periodic_orbit", "gravity and y supports make the stationary motion periodic");
    }
    // entries at the linear model's values (a tilt of 0, y stiffness equal to x, examples/
    // spatial.toml's zero gravity) are no difference; a tilt takes critical to the general route
    let dim = examples("dimensional.toml");
    let (code, out, err) = autobal(&["critical", "--format", "json", "--config", &dim, "--set", "rotor.axis_tilt=0.01", "--set", "rotor.axis_tilt_angle=0"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning: critical uses"), "{err}");
    assert_eq!(serde_json::from_str::<serde_json::Value>(&out).unwrap()["route"], "general");
    // real balls too: the locked critical speeds by the general route, the stability said to be
    // not analysed (no linearisation), nothing ignored
    let (code, out, err) = autobal(&["critical", "--format", "json", "--config", &dim, "--set", "balancer.contact=true"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning: critical uses"), "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["route"], "general");
    assert!(v["stability_not_analysed"].is_string(), "{v}");
    let (code, _, err) = autobal(&["critical", "--config", &dim, "--set", "rotor.axis_tilt=0", "--set", "supports.stiffness_left_y=2.0e6"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning: critical uses"), "{err}");
    let (code, _, err) = autobal(&["critical", "--config", &examples("spatial.toml")]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning: critical uses"), "{err}");
    // the map takes the general route (autobal::rotor_map) for such a config: nothing ignored
    let dir = std::env::temp_dir().join(format!("autobal-ignored-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("m");
    let (code, out, err) = autobal(&[
        "map",
        "--config",
        &examples("spatial.toml"),
        "--set",
        "spatial.lock_tilt=true",
        "--x",
        "dimensionless.z_a=0:1:3",
        "--y",
        "omega=0.5:2:3",
        "--out",
        stem.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("general route") && !err.contains("warning: map uses"), "{out}{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn ranges_cut_at_the_span_end_are_not_unbounded() {
    // paper 000's base case: the last stable range ends at 2.2384, 003's last necessary range at
    // 2.17 (both beyond Ω = 2); cut at --omega-max 2 they reach the end of the span, not ∞
    let (code, out, err) = autobal(&["stability", "--omega-max", "2", "--samples", "400"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("1.412184 – 1.707095, 1.731747 – 2 (end of the span)\n"), "{out}");
    assert!(out.contains("necessary (003, eqs (1)-(3)):   0.846264 – 2 (end of the span)\n"), "{out}");
    assert!(!out.contains('∞'), "{out}");
    let v = json(&["stability", "--format", "json", "--omega-max", "2", "--samples", "400"]);
    assert!(v["stable_ranges"].as_array().unwrap().last().unwrap()[1].is_null());
    assert_eq!(v["open_at_span_end"]["stable_ranges"], true);
    assert_eq!(v["open_at_span_end"]["necessary_ranges"], true);
    assert_eq!(v["open_at_span_end"]["necessary_not_stable"], false);
    // over a longer span the stable range ends inside it
    let v = json(&["stability", "--format", "json", "--omega-max", "5", "--samples", "400"]);
    assert!(v["stable_ranges"].as_array().unwrap().last().unwrap()[1].as_f64().is_some_and(|h| (h - 2.2384).abs() < 1e-3), "{v}");
    assert_eq!(v["open_at_span_end"]["stable_ranges"], false);
    // the automatic span's end is printed as a number is, not to 16 digits
    let (code, out, err) = autobal(&["stability", "--config", &examples("dimensional.toml"), "--samples", "100"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("0 < Ω ≤ 2.188091 (up to 10434 rpm,"), "{out}");
    assert!(out.contains(" – 2.188091 (end of the span)") && out.contains(" – 10434 (end of the span)"), "{out}");
}

#[test]
fn every_option_has_a_description() {
    for c in ["inertia", "critical", "ranges", "stability", "campbell", "map", "simulate", "sweep", "merge", "basins", "report"] {
        let (code, out, err) = autobal(&[c, "--help"]);
        assert_eq!(code, 0, "{err}");
        let mut listed = false;
        for line in out.lines().skip_while(|l| !l.starts_with("Arguments:") && !l.starts_with("Options:")) {
            let l = line.trim_start();
            if !(l.starts_with('-') || l.starts_with('<')) {
                continue;
            }
            listed = true;
            let text = l.split_once("  ").map(|(_, t)| t.trim_start()).unwrap_or("");
            assert!(!text.is_empty() && !text.starts_with('['), "{c}: `{line}` has no description");
        }
        assert!(listed, "{c}: {out}");
    }
    let (_, out, _) = autobal(&["simulate", "--help"]);
    assert!(out.contains("Output interval (s, or τ for a dimensionless config)"), "{out}");
}

#[test]
fn integration_method_errors_list_every_accepted_name() {
    let (code, _, err) = autobal(&["simulate", "--set", "integration.method=euler"]);
    assert_eq!(code, 2);
    let names: Vec<&str> = err.split('"').skip(1).step_by(2).filter(|n| *n != "euler").collect();
    assert_eq!(names, ["auto", "dop853", "rodas", "rosenbrock"], "{err}");
    let dir = std::env::temp_dir().join(format!("autobal-methods-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for n in names {
        let (code, out, err) =
            autobal(&["simulate", "--set", &format!("integration.method=\"{n}\""), "--set", "drive.t_end=1", "--out", dir.join("p.csv").to_str().unwrap()]);
        assert_eq!(code, 0, "{n}: {err}");
        // counts in the singular where there is one (this run switches once under `auto`)
        let line = out.lines().find(|l| l.starts_with("integration (")).unwrap();
        assert!(!line.contains(" 1 switches") && !line.contains(" 1 steps"), "{line}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A dimensional config's analytic outputs give speeds in rad/s and rpm beside Ω (= ω / ω0):
/// critical's JSON has the autobalancing ranges in rpm as ranges' JSON has them, both have the
/// antiresonance speed in SI, stability has its ranges in rpm; the text prints Ω_a and the
/// unbalanced rotor's critical speeds in rad/s and rpm. A dimensionless config gets `null`s.
#[test]
fn dimensional_analytic_outputs_give_si_speeds() {
    let dim = examples("dimensional.toml");
    let c = json(&["critical", "--config", &dim, "--format", "json"]);
    let r = json(&["ranges", "--config", &dim, "--format", "json"]);
    let w0 = c["model"]["scale"]["omega0"].as_f64().unwrap();
    let rpm = w0 * 30.0 / std::f64::consts::PI;
    assert_eq!(c["autobalancing_ranges_rpm"], r["autobalancing_ranges_rpm"]);
    assert!(c["autobalancing_ranges_rpm"].as_array().is_some_and(|a| !a.is_empty()), "{}", c["autobalancing_ranges_rpm"]);
    let close = |a: &serde_json::Value, b: f64| (a.as_f64().unwrap() - b).abs() <= 1e-12 * b.abs();
    for v in [&c, &r] {
        let wa = v["antiresonance_speed"].as_f64().expect("the example has an antiresonance");
        assert!(close(&v["antiresonance_speed_rad_s"], wa * w0) && close(&v["antiresonance_speed_rpm"], wa * rpm), "{v}");
    }
    let cs = r["critical_speeds_unbalanced_rotor"].as_array().unwrap();
    for (i, w) in cs.iter().enumerate() {
        let w = w.as_f64().unwrap();
        assert!(close(&r["critical_speeds_unbalanced_rotor_rad_s"][i], w * w0) && close(&r["critical_speeds_unbalanced_rotor_rpm"][i], w * rpm));
    }
    let s = json(&["stability", "--config", &dim, "--format", "json"]);
    for k in ["stable_ranges", "necessary_ranges"] {
        let (a, b) = (s[k].as_array().unwrap(), s[format!("{k}_rpm")].as_array().unwrap_or_else(|| panic!("{k}_rpm: {}", s[format!("{k}_rpm")])));
        assert_eq!(a.len(), b.len(), "{k}");
        for (x, y) in a.iter().zip(b) {
            assert!(close(&y[0], x[0].as_f64().unwrap() * rpm), "{k}: {x} vs {y}");
        }
    }
    let (code, text, err) = autobal(&["ranges", "--config", &dim]);
    assert_eq!(code, 0, "{err}");
    let line = |p: &str| text.lines().find(|l| l.contains(p)).unwrap_or_else(|| panic!("no '{p}' in {text}")).to_string();
    for p in ["antiresonance Ω_a", "critical speeds of the unbalanced rotor"] {
        assert!(line(p).contains("rad/s") && line(p).contains("rpm"), "{}", line(p));
    }
    let d = json(&["ranges", "--format", "json"]);
    assert!(d["antiresonance_speed_rpm"].is_null() && d["autobalancing_ranges_rpm"].is_null(), "a dimensionless config has no SI speeds");
}

#[test]
fn regression_stability_gave_a_verdict_on_a_balanced_state_that_cannot_exist() {
    // capacity E = 0.7955 < 1 (a new user's washer with lighter balls): the balls cannot cancel
    // the unbalance, so stability must say that no balanced state exists, in the table and JSON
    let washer = examples("washing_machine.toml");
    let (code, out, err) = autobal(&["stability", "--config", &washer, "--set", "balancer.ball_mass=0.07"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("warning: no balanced state exists: the balancer's capacity E = 0.7955 < 1"), "{out}");
    let v = json(&["stability", "--format", "json", "--config", &washer, "--set", "balancer.ball_mass=0.07"]);
    assert_eq!(v["balanced_state_exists"], false);
    let v = json(&["stability", "--format", "json", "--config", &washer]);
    assert_eq!(v["balanced_state_exists"], true);
    assert!(v["balancer_capacity"].as_f64().unwrap() > 1.0);
}

/// `simulate --check-tolerance` (issue 18: say where the end state depends on the tolerance):
/// paper 004's passage (the embedded default, balanced at its end) and the spatial example give
/// the same end state at rtol 1e-8 and 1e-9, reported in the JSON with both classes, and the
/// runs' own summary is unchanged by the check (same `steps` as without it).
#[test]
fn check_tolerance_reports_both_end_states() {
    let dir = std::env::temp_dir().join(format!("autobal-tol-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.csv");
    let o = out.to_str().unwrap();
    let plain = json(&["simulate", "--format", "json", "--out", o]);
    let v = json(&["simulate", "--format", "json", "--out", o, "--check-tolerance"]);
    let c = &v["tolerance_check"];
    assert_eq!(c["end_state"], "balanced", "{c}");
    assert_eq!(c["tighter_end_state"], "balanced", "{c}");
    assert_eq!(c["depends_on_tolerance"], false);
    assert_eq!(c["rtol"], 1e-8);
    assert_eq!(c["tighter_rtol"], 1e-9);
    assert_eq!(v["steps"], plain["steps"]);
    // without the check the JSON says the end state was not checked (audit 25's F5)
    assert_eq!(plain["tolerance_check"]["checked"], false, "{}", plain["tolerance_check"]);
    assert_eq!(c["checked"], true);
    let s = json(&["simulate", "--config", &examples("spatial.toml"), "--set", "drive.t_end=200", "--format", "json", "--out", o, "--check-tolerance"]);
    assert_eq!(s["tolerance_check"]["end_state"], s["outcome"], "{s}");
    let (code, _, err) = autobal(&["simulate", "--config", &examples("linear_rotor_shaft.toml"), "--out", o, "--check-tolerance"]);
    assert_eq!(code, 2);
    assert!(err.contains("--check-tolerance:"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_stopped_before_its_last_revolution_says_its_residual_is_the_end_state_s() {
    // a step budget of 300 stops the linear example at t = 0.05 s (its run-up lasts seconds),
    // long before the window records: the summary says its residual is no mean over a
    // revolution (`averaged` false), and the table's line says so rather than "mean over the
    // last revolution"; the planar run's JSON the same
    let dir = std::env::temp_dir().join(format!("autobal-averaged-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = examples("linear_rotor_shaft.toml");
    let out = dir.join("l");
    let budget = ["--set", "integration.max_steps=300"];
    let (code, text, err) = autobal(&[&["simulate", "--config", &cfg, "--out", out.to_str().unwrap()][..], &budget].concat());
    assert_eq!(code, 2, "{err}");
    assert!(text.contains("(at the end: no revolution recorded)") && !text.contains("mean over the last revolution"), "{text}");
    let (code, text, err) = autobal(&[&["simulate", "--config", &cfg, "--format", "json", "--out", out.to_str().unwrap()][..], &budget].concat());
    assert_eq!(code, 2, "{err}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["averaged"], false, "{v}");
    let out = dir.join("p");
    let (code, text, err) = autobal(&[&["simulate", "--format", "json", "--out", out.to_str().unwrap()][..], &budget].concat());
    assert_eq!(code, 2, "{err}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["averaged"], false, "{v}");
    // a completed run's residuals are means
    let v = json(&["simulate", "--format", "json", "--out", out.to_str().unwrap(), "--set", "drive.omega0=200", "--set", "drive.t_end=10", "--dt", "0.01"]);
    assert_eq!(v["averaged"], true, "{v}");
    std::fs::remove_dir_all(&dir).ok();
}
