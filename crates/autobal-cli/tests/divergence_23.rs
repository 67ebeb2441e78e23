//! The linear rotor's static divergence at every scale and in every line that lists modes
//! (review 22's *Left*): a divergence above the threshold `1e-9 max|ω²|` (the matrices' data
//! rounding, review 23) on a stiff rotor is named with its `ω²`; the modal reduction's line
//! names divergent modes instead of "0 ± 0"; with every mode divergent the frequency lines say
//! so instead of ending empty; the quick report's run-up of a divergent rotor says it failed and
//! why instead of "interrupted".

use std::path::{Path, PathBuf};
use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}\n{out}"))
}

fn tmp(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("divergence_23").join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A dense `n × n` matrix (row-major) as a Matrix Market file, its nonzero entries.
fn mtx(path: &Path, a: &[f64], n: usize) {
    let entries: Vec<String> = (0..n * n).filter(|ij| a[*ij] != 0.0).map(|ij| format!("{} {} {:e}", ij / n + 1, ij % n + 1, a[ij])).collect();
    std::fs::write(path, format!("%%MatrixMarket matrix coordinate real general\n{n} {n} {}\n{}\n", entries.len(), entries.join("\n"))).unwrap();
}

/// A linear rotor of `nodes` nodes `x, y` with `M`, `K` (row-major), `C = 40 I`, an unbalance
/// and three balls of 0.1 kg at node 0, and `extra` TOML lines under `[linear_rotor]`.
fn rotor(dir: &Path, nodes: usize, m: &[f64], k: &[f64], extra: &str) -> String {
    let n = 2 * nodes;
    mtx(&dir.join("M.mtx"), m, n);
    mtx(&dir.join("K.mtx"), k, n);
    let c: Vec<f64> = (0..n * n).map(|ij| if ij / n == ij % n { 40.0 } else { 0.0 }).collect();
    mtx(&dir.join("C.mtx"), &c, n);
    let cfg = dir.join("rotor.toml");
    std::fs::write(
        &cfg,
        format!(
            "[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"K.mtx\"\nc = \"C.mtx\"\n{extra}\n\
             [[linear_rotor.unbalance]]\nnode = 0\nme = 1e-3\n\
             [[linear_rotor.balancer]]\nnode = 0\nradius = 0.05\nballs = 3\nball_mass = 0.1\ndrag = 0.01\n"
        ),
    )
    .unwrap();
    cfg.to_str().unwrap().to_string()
}

/// One node, `M = m I`, `K = diag(kx, ky)`: with the balls as rings (`3 mb = 0.3` kg on each
/// translation) `ω² = kx/(m + 0.3)`, `ky/(m + 0.3)` exactly (a diagonal problem).
fn diagonal(dir: &Path, m: f64, kx: f64, ky: f64, extra: &str) -> String {
    rotor(dir, 1, &[m, 0.0, 0.0, m], &[kx, 0.0, 0.0, ky], extra)
}

#[test]
fn a_slow_divergence_on_a_stiff_rotor_is_named() {
    // ω² = −100 (rad/s)² and 1e10 (rad/s)²: above the threshold max(1e-9, 100 · 2 · ε) · 1e10
    // = 10, so named (a divergence weaker than the matrices' data rounding, 1e-9 of the
    // largest, is not: review 23)
    let (m, mr) = (10.0, 10.3);
    let cfg = diagonal(&tmp("slow"), m, -100.0 * mr, 1e10 * mr, "");
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    let div = v["static_divergence"].as_array().unwrap();
    assert_eq!(div.len(), 1, "{v}");
    // a diagonal problem through a Cholesky factor: ω² to a few ulps (1e-12 relative)
    let l = div[0]["omega_squared"].as_f64().unwrap();
    assert!((l + 100.0).abs() <= 1e-10, "{l}");
    assert!((div[0]["growth_rate"].as_f64().unwrap() - 10.0).abs() <= 1e-12, "{v}");
    assert_eq!(v["natural_frequencies"].as_array().unwrap().len(), 1, "{v}");
    assert_eq!(v["every_mode_diverges"], false, "{v}");
    let (code, out, err) = autobal(&["critical", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("statically unstable at rest: 1 mode(s) with ω² < 0, ω² = -100 (rad/s)², growing as exp(sqrt(-ω²) t) at 10 1/s"), "{out}");
    assert!(out.contains("  1. 100000 rad/s") && !out.contains(" 0 rad/s"), "{out}");
    // the same rotor with the mode at +100: a frequency of 10 rad/s, nothing divergent
    let cfg = diagonal(&tmp("slow_plus"), m, 100.0 * mr, 1e10 * mr, "");
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["static_divergence"].as_array().unwrap().len(), 0, "{v}");
    let w = v["natural_frequencies"].as_array().unwrap();
    assert!((w[0].as_f64().unwrap() - 10.0).abs() <= 1e-12, "{v}");
    // and a free direction (kx = 0, a rigid-body mode): 0 rad/s, not divergent
    let cfg = diagonal(&tmp("slow_free"), m, 0.0, 1e10 * mr, "");
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["static_divergence"].as_array().unwrap().len(), 0, "{v}");
    assert_eq!(v["natural_frequencies"][0], 0.0, "{v}");
}

#[test]
fn every_mode_divergent_says_none_in_text_and_json() {
    // K = −4e4 I: both modes diverge (ω² = −4e4/10.3)
    let cfg = diagonal(&tmp("all"), 10.0, -4e4, -4e4, "");
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["every_mode_diverges"], true, "{v}");
    assert_eq!(v["natural_frequencies"].as_array().unwrap().len(), 0, "{v}");
    let (code, out, err) = autobal(&["critical", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("(of the modes that do not diverge):\n  none (every mode diverges at rest)\n"), "{out}");
    let args = ["stability", "--config", &cfg, "--omega-max", "200 rad/s", "--samples", "10"];
    let (code, out, err) = autobal(&args);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("natural frequencies at rest, balls as rings (of the other modes): none (every mode diverges at rest)\n"), "{out}");
    let v = json(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(v["every_mode_diverges"], true, "{v}");
    // a rotor with a frequency: false
    let cfg = diagonal(&tmp("all_not"), 10.0, 4e4, 4e4, "");
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    assert_eq!(v["every_mode_diverges"], false, "{v}");
}

#[test]
fn the_reduction_line_names_divergent_modes() {
    // three nodes x, y in a chain (springs 1e6 N/m between neighbours, 1e6 to ground at node 2
    // and −5e5 at node 0), M = I: per direction det(K) = 1e18 (1 + 3 · (−0.5)) < 0, one negative
    // ω² (Sylvester: K's inertia), two in all; reduced to the balancer's node and one interior
    // mode pair (modes = 1)
    let n = 6;
    let mut k = vec![0.0; n * n];
    let mut add = |i: usize, j: Option<usize>, s: f64| {
        for d in 0..2 {
            let a = 2 * i + d;
            k[a * n + a] += s;
            if let Some(j) = j {
                let b = 2 * j + d;
                k[b * n + b] += s;
                k[a * n + b] -= s;
                k[b * n + a] -= s;
            }
        }
    };
    add(0, Some(1), 1e6);
    add(1, Some(2), 1e6);
    add(2, None, 1e6);
    add(0, None, -5e5);
    let m: Vec<f64> = (0..n * n).map(|ij| if ij / n == ij % n { 1.0 } else { 0.0 }).collect();
    let cfg = rotor(&tmp("reduced"), 3, &m, &k, "modes = 1");
    let v = json(&["critical", "--config", &cfg, "--format", "json"]);
    let f = v["reduction"]["frequencies"].as_array().unwrap();
    let div: Vec<&serde_json::Value> = f.iter().filter(|f| f["divergent"] == true).collect();
    assert_eq!(div.len(), 2, "{v}");
    for d in &div {
        assert!(d["omega_squared"].as_f64().unwrap() < 0.0 && d["estimate"].is_null(), "{d}");
    }
    let (code, out, err) = autobal(&["critical", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("reduced model (without the balls): statically unstable at rest: 2 mode(s) with ω² < 0, ω² = "), "{out}");
    assert!(out.contains("reduced natural frequencies at rest without the balls of the other modes (rad/s, ± the estimated error): "), "{out}");
    assert!(!out.contains("0 ± 0"), "{out}");
}

#[test]
fn the_quick_reports_run_up_of_a_divergent_rotor_failed_and_says_why() {
    // K = −4e8 I: diverging at 6232 1/s; the run-up cannot reach its end (a step budget of
    // 20000 keeps the test short: the integrator's reason is then that budget, spent by a run
    // that grows without bound, not a Ctrl-C)
    let dir = tmp("report");
    let cfg = diagonal(&dir, 10.0, -4e8, -4e8, "omega_max = 200.0\n[integration]\nmax_steps = 20000");
    let out = dir.join("r");
    let (code, _, err) = autobal(&["report", "--config", &cfg, "--quick", "--out", out.to_str().unwrap()]);
    // exit 2 (the report written, its run-up failed: a script sees it, as `simulate`'s exit 2
    // on the same budget; review 23), not "interrupted"
    assert_eq!(code, 2, "{err}");
    assert!(err.lines().any(|l| l.starts_with("error: the report in ") && l.contains("is written, but ") && l.contains("the run-up failed at t = ")), "{err}");
    assert!(err.contains("your linear rotor: done, but the run-up failed at t = ") && !err.contains("interrupted"), "{err}");
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(!page.contains("Interrupted"), "the page");
    assert!(page.contains("The run-up failed at t = ") && page.contains("the integrator stopped (step budget of 20000 steps spent"), "the page");
    assert!(page.contains("The stiffness K is not positive semi-definite (2 mode(s) diverge at rest, the fastest as exp(6232 t) with t in s)"), "the page");
    assert!(page.contains("Linear rotor run-up: failed at t = "), "the summary");
}
