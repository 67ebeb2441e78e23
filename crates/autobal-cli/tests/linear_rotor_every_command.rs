//! Every command on a linear rotor config (`[linear_rotor]`, issue 19): a right answer or a
//! right one-line reason. `inertia` gives the structure's mass, polar moment and balls from the
//! matrices (checked against closed forms), `critical` the natural frequencies at rest with the
//! balls as rings (checked against `sqrt(k/(m + n m_b))`), `ranges` says 003's ranges are not
//! defined and gives `stability`'s exact ranges, `merge` joins a linear sweep's shards.

use std::path::PathBuf;
use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-lr-every-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// bench/linear_rotor.py's shaft (40 steel elements of 30 mm, 25 mm diameter, a 4 kg disk at
/// node 13), with one balancer plane, or two (nodes 5 and 13) and a second unbalance.
fn shaft(two_planes: bool) -> String {
    let mut s = String::from(
        "[linear_rotor]\nmodes = 4\n[[linear_rotor.elements]]\nlength = 0.03\ndiameter = 0.025\ne = 2.1e11\nrho = 7850.0\ncount = 40\n\
         [[linear_rotor.disks]]\nnode = 13\nmass = 4.0\nid = 0.01\nip = 0.02\n\
         [[linear_rotor.bearings]]\nnode = 0\nk = 2e6\nc = 300.0\n[[linear_rotor.bearings]]\nnode = 40\nk = 2e6\nc = 300.0\n\
         [[linear_rotor.unbalance]]\nnode = 13\nme = 2e-4\n",
    );
    if two_planes {
        s.push_str("[[linear_rotor.unbalance]]\nnode = 30\nme = 1e-4\nphase = 1.0\n");
        s.push_str("[[linear_rotor.balancer]]\nnode = 5\nradius = 0.06\nballs = 2\nball_mass = 0.02\ndrag = 0.1\n");
    }
    s.push_str("[[linear_rotor.balancer]]\nnode = 13\nradius = 0.06\nballs = 2\nball_mass = 0.02\ndrag = 0.1\n");
    s
}

/// A Jeffcott rotor from Matrix Market files: `M = m I`, `K = k I`, `C = c I` on one node `x, y`.
fn jeffcott_files(dir: &std::path::Path, m: f64, k: f64, c: f64) -> PathBuf {
    let mtx = |v: f64| format!("%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 {v:e}\n2 2 {v:e}\n");
    std::fs::write(dir.join("M.mtx"), mtx(m)).unwrap();
    std::fs::write(dir.join("K.mtx"), mtx(k)).unwrap();
    std::fs::write(dir.join("C.mtx"), mtx(c)).unwrap();
    let cfg = dir.join("jeffcott.toml");
    std::fs::write(
        &cfg,
        "[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"K.mtx\"\nc = \"C.mtx\"\n\
         [[linear_rotor.unbalance]]\nnode = 0\nme = 1e-3\n\
         [[linear_rotor.balancer]]\nnode = 0\nradius = 0.05\nballs = 3\nball_mass = 0.01\ndrag = 0.01\n",
    )
    .unwrap();
    cfg
}

/// `inertia` on a linear config answers from its matrices (it said "this is a planar-rotor
/// config" before): the shaft's `u_xᵀ M u_x` is the steel's mass `ρ π d² L / 4` plus the disk's
/// (the consistent mass matrix integrates the density exactly on a rigid translation), its
/// `I_p` the solid shaft's `ρ π d⁴ L / 32` plus the disk's, to `1e-12` (sums of 164 rows, each
/// exact to round-off); the balls' mass and capacity `n m_b R`; two planes list both.
#[test]
fn inertia_of_a_linear_rotor_is_its_mass_polar_moment_and_balls() {
    let dir = tmp("inertia");
    let one = dir.join("one.toml");
    std::fs::write(&one, shaft(false)).unwrap();
    let v = json(&["inertia", "--config", one.to_str().unwrap(), "--format", "json"]);
    let (rho, d, l) = (7850.0, 0.025, 1.2);
    let pi = std::f64::consts::PI;
    let mass = rho * pi * d * d / 4.0 * l + 4.0;
    let ip = rho * pi * d.powi(4) / 32.0 * l + 0.02;
    let get = |p: &str| v.pointer(p).and_then(serde_json::Value::as_f64).unwrap_or_else(|| panic!("{p}: {v}"));
    for p in ["/structure/mass_x", "/structure/mass_y"] {
        assert!((get(p) - mass).abs() <= 1e-12 * mass, "{p}: {} vs {mass}", get(p));
    }
    assert!(get("/structure/mass_xy").abs() <= 1e-12 * mass);
    assert!((get("/polar_inertia") - ip).abs() <= 1e-12 * ip, "{} vs {ip}", get("/polar_inertia"));
    assert!((get("/balancers/0/capacity") - 2.0 * 0.02 * 0.06).abs() < 1e-15);
    assert!((get("/total_mass") - mass - 0.04).abs() <= 1e-12 * mass);
    assert_eq!(v["model"], "linear");
    let (code, table, err) = autobal(&["inertia", "--config", one.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(!table.contains("planar") && table.contains("capacity n m R = 0.0024 kg m"), "{table}");
    // two planes, --set on a linear path
    let two = dir.join("two.toml");
    std::fs::write(&two, shaft(true)).unwrap();
    let v = json(&["inertia", "--config", two.to_str().unwrap(), "--format", "json", "--set", "linear_rotor.ball_mass=0.03"]);
    assert_eq!(v["balancers"].as_array().unwrap().len(), 2);
    assert_eq!(v["balancers"][1]["node"], 13);
    assert!((v["balls_mass"].as_f64().unwrap() - 4.0 * 0.03).abs() < 1e-15);
    // matrix files: the Jeffcott rotor's mass
    let cfg = jeffcott_files(&dir, 3.5, 4e5, 20.0);
    let v = json(&["inertia", "--config", cfg.to_str().unwrap(), "--format", "json"]);
    assert_eq!(v["structure"]["mass_x"], 3.5);
    assert!(v["polar_inertia"].is_null());
    std::fs::remove_dir_all(&dir).ok();
}

/// `critical` on a linear config gives the natural frequencies at rest with the balls as rings
/// (it refused the config as an unknown table before): on the Jeffcott rotor from files
/// `sqrt(k/(m + n m_b))` to `1e-12` (a 2 × 2 symmetric eigenproblem: round-off); on the shaft the
/// same numbers `stability` prints; `--omega-max` is refused in one line naming it.
#[test]
fn critical_of_a_linear_rotor_gives_its_natural_frequencies_with_balls_as_rings() {
    let dir = tmp("critical");
    let cfg = jeffcott_files(&dir, 3.5, 4e5, 20.0);
    let v = json(&["critical", "--config", cfg.to_str().unwrap(), "--format", "json"]);
    let w = (4e5f64 / (3.5 + 3.0 * 0.01)).sqrt();
    let got: Vec<f64> = v["natural_frequencies"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(got.len(), 2);
    for g in &got {
        assert!((g - w).abs() <= 1e-12 * w, "{g} vs {w}");
    }
    let one = dir.join("one.toml");
    std::fs::write(&one, shaft(false)).unwrap();
    let c = json(&["critical", "--config", one.to_str().unwrap(), "--format", "json"]);
    let s = json(&["stability", "--config", one.to_str().unwrap(), "--samples", "10", "--format", "json"]);
    let c6: Vec<_> = c["natural_frequencies"].as_array().unwrap()[..6].to_vec();
    assert_eq!(c6, s["natural_frequencies"].as_array().unwrap().clone());
    let (code, table, _) = autobal(&["critical", "--config", one.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(table.contains("balls as rings") && table.contains("autobal campbell"), "{table}");
    let (code, _, err) = autobal(&["critical", "--config", one.to_str().unwrap(), "--omega-max", "100 rad/s"]);
    assert_eq!(code, 2);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("--omega-max") && err.contains("natural frequencies at rest"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `ranges` on a linear config says 003's necessary ranges are not defined and gives the exact
/// ranges of `stability` over its default axis and grid (it refused the config as an unknown
/// table before): the same ranges, number for number.
#[test]
fn ranges_of_a_linear_rotor_are_the_exact_ranges_of_stability() {
    let cfg = example("linear_rotor_shaft.toml");
    let r = json(&["ranges", "--config", &cfg, "--format", "json"]);
    let s = json(&["stability", "--config", &cfg, "--format", "json"]);
    assert!(r["autobalancing_ranges"].is_null());
    assert!(r["necessary_not_defined"].as_str().unwrap().contains("linear rotor"));
    assert_eq!(r["exact"]["stable_ranges"], s["stable_ranges"]);
    assert!(!s["stable_ranges"].as_array().unwrap().is_empty());
    let (code, table, err) = autobal(&["ranges", "--config", &cfg]);
    assert_eq!(code, 0, "{err}");
    assert!(table.contains("not defined for this config: a linear rotor") && table.contains("stable: "), "{table}");
}

/// `merge` joins the shards of a linear rotor's sweep (it refused their CSV header before):
/// the merged CSV is the unsharded sweep's in every column but the wall time, and it draws the
/// sweep's figures beside it.
#[test]
fn merge_joins_a_linear_sweeps_shards() {
    let dir = tmp("merge");
    let cfg = example("linear_rotor_shaft.toml");
    let sets = ["--set", "drive.kind=\"speed\"", "--set", "drive.omega0=300", "--set", "drive.t_end=0.05"];
    let sweep = |out: &PathBuf, shard: Option<&str>| {
        let mut a = vec!["sweep", "--config", &cfg, "--x", "linear_rotor.drag=0.05:0.15:3", "--threads", "1", "--no-plots", "--out"];
        let o = out.to_str().unwrap().to_string();
        a.push(&o);
        a.extend(sets);
        if let Some(s) = shard {
            a.extend(["--shard", s]);
        }
        let (code, _, err) = autobal(&a);
        assert_eq!(code, 0, "{err}");
    };
    sweep(&dir.join("whole"), None);
    sweep(&dir.join("p1"), Some("1/2"));
    sweep(&dir.join("p2"), Some("2/2"));
    let (code, _, err) =
        autobal(&["merge", "--out", dir.join("merged").to_str().unwrap(), dir.join("p2.csv").to_str().unwrap(), dir.join("p1.csv").to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let rows =
        |p: &str| -> Vec<String> { std::fs::read_to_string(dir.join(p)).unwrap().lines().map(|l| l.rsplit_once(',').map_or(l, |x| x.0).to_string()).collect() };
    let whole = rows("whole.csv");
    assert_eq!(whole.len(), 4);
    assert_eq!(rows("merged.csv"), whole);
    // merge draws the sweep's figures from the merged table (it drew none before)
    for f in ["merged_peak.svg", "merged_final.svg"] {
        let svg = std::fs::read_to_string(dir.join(f)).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("Linear rotor sweep"), "{f}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The windows example's natural frequencies at rest with the balls as rings are quoted as the
/// command prints them, to the two decimals quoted: `ω2 = 535.21` as reduced (the example's
/// `modes = 4`), `535.19` for the full model (the guide said `535.19` for the reduced rotor).
#[test]
fn the_docs_quote_the_windows_examples_natural_frequencies() {
    let cfg = example("linear_rotor_windows.toml");
    let w = |sets: &[&str]| -> Vec<f64> {
        let mut a = vec!["critical", "--config", &cfg, "--format", "json"];
        a.extend(sets);
        json(&a)["natural_frequencies"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
    };
    let (red, full) = (w(&[]), w(&["--set", "linear_rotor.modes=0"]));
    // pairs (x and y): the first and third of each list
    let (r1, r2, f1, f2) = (format!("{:.2}", red[0]), format!("{:.2}", red[2]), format!("{:.2}", full[0]), format!("{:.2}", full[2]));
    assert_eq!((r1.as_str(), r2.as_str(), f1.as_str(), f2.as_str()), ("175.21", "535.21", "175.21", "535.19"));
    let root = format!("{}/../..", env!("CARGO_MANIFEST_DIR"));
    let guide = std::fs::read_to_string(format!("{root}/docs/guide/your-own-rotor.md")).unwrap().replace('\n', " ");
    let note = std::fs::read_to_string(format!("{root}/docs/notes/flexible-shaft-literature.md")).unwrap().replace('\n', " ");
    for (name, text) in [("guide", &guide), ("note", &note)] {
        assert!(text.contains(&format!("`ω1 = {r1}`, `ω2 = {r2} =")), "{name}: the reduced rotor's frequencies");
        assert!(text.contains(&format!("`{f1}`, `{f2}` rad/s")), "{name}: the full model's frequencies");
        assert!(!text.contains(&format!("`ω2 = {f2}")), "{name}: the full model's ω2 quoted as the reduced rotor's");
    }
}
