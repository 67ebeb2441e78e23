//! `autobal sweep` and `autobal basins` write their figures as SVG beside their other outputs
//! (`STEM_peak.svg`, `STEM_final.svg`; `STEM.svg`), on every rotor (planar, spatial, linear):
//! each file is well-formed (read back by the SVG renderer the PNGs go through), draws one point
//! per run (a sweep's curves: a polyline per value of the other axes, a vertex per run; the
//! basins' heatmap: an `n × n` raster, a pixel per run), is the figure Python's `.plot()` draws
//! (`figures_api`, computed in-process on the same config: the same SVG text), and is named on
//! standard error (sweep) or in the table and JSON (basins). `--no-plots` writes none; a figure's
//! path that is the config is refused before anything runs, as for the other outputs.

use autobal::control::Control;
use autobal_commands::figures_api::{figures, Options};
use std::path::{Path, PathBuf};
use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn ok(args: &[&str]) -> (String, String) {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    (out, err)
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-figs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn s(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

/// The SVG at `p`, checked to be a well-formed figure: the renderer (usvg, a strict XML
/// reader) reads and draws it.
fn svg(p: &Path) -> String {
    let text = std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    assert!(text.starts_with("<svg ") && text.trim_end().ends_with("</svg>"), "{}", p.display());
    autobal_commands::plot::svg_to_png(&text, 0.5).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    text
}

/// The vertices of each `<polyline>` (a curve), and the `<circle>` markers of the plot area
/// (a curve of one point; the legend's circles carry no `stroke="none"`).
fn curves(svg: &str) -> Vec<usize> {
    let mut out: Vec<usize> =
        svg.match_indices("<polyline points=\"").map(|(i, m)| svg[i + m.len()..].split('"').next().unwrap().split_whitespace().count()).collect();
    out.extend(svg.lines().filter(|l| l.starts_with("<circle ") && l.contains("stroke=\"none\"")).map(|_| 1));
    out
}

/// The CSV's data rows.
fn rows(p: &Path) -> usize {
    std::fs::read_to_string(p).unwrap().lines().count() - 1
}

/// The config's tables with `sets` applied as the CLI's `--set` (any rotor's).
fn tables(path: &str, sets: &[&str]) -> toml::Table {
    let mut root: toml::Table = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for set in sets {
        let (k, v) = set.split_once('=').unwrap();
        let (t, key) = k.split_once('.').unwrap();
        let v: toml::Value = toml::from_str::<toml::Table>(&format!("v = {v}")).unwrap()["v"].clone();
        root.entry(t).or_insert_with(|| toml::Value::Table(Default::default())).as_table_mut().unwrap().insert(key.into(), v);
    }
    root
}

/// `(width, height)` of the first PNG embedded in the SVG (the heatmap's raster), from its
/// IHDR chunk.
fn raster_size(svg: &str) -> (u32, u32) {
    let at = svg.find("data:image/png;base64,").expect("an embedded raster") + "data:image/png;base64,".len();
    let b64 = &svg[at..at + svg[at..].find('"').unwrap()];
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    } as u32;
    let mut bytes = vec![];
    for q in b64.as_bytes()[..32].chunks(4) {
        let n = q.iter().fold(0, |n, &c| n << 6 | val(c));
        bytes.extend([(n >> 16) as u8, (n >> 8) as u8, n as u8]);
    }
    assert_eq!(&bytes[1..4], b"PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    (be(&bytes[16..20]), be(&bytes[20..24]))
}

/// One sweep through the CLI: its figures exist, are well-formed, draw a vertex per run (the
/// CSV's rows), a curve per value of the other axes, are named on standard error and are the
/// figures Python draws (`figures_api`, the same config and axes).
fn check_sweep(name: &str, config: Option<&str>, sets: &[&str], x: &str, y: Option<&str>, curves_want: usize) {
    let d = dir(name);
    let stem = d.join("sw");
    let mut args = vec!["sweep".to_string(), "--threads".into(), "1".into(), "--x".into(), x.into(), "--out".into(), s(&stem)];
    if let Some(c) = config {
        args.extend(["--config".into(), c.into()]);
    }
    if let Some(y) = y {
        args.extend(["--y".into(), y.into()]);
    }
    for set in sets {
        args.extend(["--set".into(), set.to_string()]);
    }
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    let (_, err) = ok(&a);
    let runs = rows(&d.join("sw.csv"));
    let (peak, fin) = (d.join("sw_peak.svg"), d.join("sw_final.svg"));
    assert!(err.contains(&format!("wrote {} and {}", peak.display(), fin.display())), "{name}: {err}");
    let root = match config {
        Some(c) => tables(c, sets),
        None => tables(&example("planar.toml"), sets),
    };
    let o = Options { x: Some(x.into()), y: y.map(String::from), ..Default::default() };
    let python = figures("sweep", &root, "test", &o, &Control::none()).unwrap();
    for (file, id) in [(&peak, "sweep_peak"), (&fin, "sweep_final")] {
        let text = svg(file);
        let c = curves(&text);
        assert_eq!(c.len(), curves_want, "{name} {id}: {c:?}");
        assert_eq!(c.iter().sum::<usize>(), runs, "{name} {id}: a vertex per run");
        let want = python.iter().find(|f| f.id == id).unwrap().plot.to_svg();
        assert!(text == want, "{name} {id}: the CLI's figure is not Python's");
    }
    // --no-plots: no figure, none named
    let more: Vec<&str> = a.iter().copied().chain(["--no-plots"]).collect();
    std::fs::remove_dir_all(&d).unwrap();
    let (_, err) = ok(&more);
    assert!(d.join("sw.csv").is_file() && !peak.exists() && !fin.exists(), "{name}: --no-plots");
    assert!(!err.contains(".svg"), "{name}: {err}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn planar_sweep_writes_its_figures() {
    // 3 × 2 points: a curve per value of planar.c_psi, 3 vertices each
    check_sweep("planar", None, &["drive.t_end=0.5", "drive.omega0=250"], "drive.b=100:200:3", Some("planar.c_psi=0.05,0.1"), 2);
}

#[test]
fn spatial_sweep_writes_its_figures() {
    // one axis: one curve through both runs
    check_sweep("spatial", Some(&example("spatial.toml")), &["drive.t_end=5"], "drive.omega0=1.5,1.6", None, 1);
}

#[test]
fn linear_sweep_writes_its_figures() {
    // 2 × 2 points on the shaft example: a curve per drag
    check_sweep(
        "linear",
        Some(&example("linear_rotor_shaft.toml")),
        &["drive.t_end=0.1"],
        "linear_rotor.ball_mass=0.02,0.03",
        Some("linear_rotor.balancer[0].drag=0.1,0.2"),
        2,
    );
}

/// One basins grid through the CLI: the figure beside the CSV, well-formed, an `n × n` raster
/// (a pixel per run), named in the table and the JSON, Python's figure; `--no-plots` none.
fn check_basins(name: &str, config: &str, sets: &[&str], n: usize) {
    let d = dir(name);
    let csv = d.join("b.csv");
    let nn = n.to_string();
    let mut a = vec!["basins", "--threads", "1", "--config", config, "--n", &nn, "--out"];
    let c = s(&csv);
    a.push(&c);
    for set in sets {
        a.extend(["--set", set]);
    }
    let (table, _) = ok(&a);
    let fig = d.join("b.svg");
    // the first line names the files (a second says the runs' ends were not checked against a
    // tighter tolerance, on the spatial rotor)
    assert!(table.lines().next().unwrap().ends_with(&format!("; wrote {} and {}", csv.display(), fig.display())), "{name}: {table}");
    let text = svg(&fig);
    assert_eq!(raster_size(&text), (n as u32, n as u32), "{name}: a cell per run");
    assert_eq!(rows(&csv), n * n, "{name}: every run done");
    let python = figures("basins", &tables(config, sets), "test", &Options { n: Some(n), ..Default::default() }, &Control::none()).unwrap();
    assert!(text == python[0].plot.to_svg(), "{name}: the CLI's figure is not Python's");
    let json: Vec<&str> = a.iter().copied().chain(["--format", "json"]).collect();
    let v: serde_json::Value = serde_json::from_str(&ok(&json).0).unwrap();
    assert_eq!(v["svg"], serde_json::json!(s(&fig)));
    assert_eq!(v["csv"], serde_json::json!(c));
    std::fs::remove_dir_all(&d).unwrap();
    let more: Vec<&str> = a.iter().copied().chain(["--no-plots"]).collect();
    let (table, _) = ok(&more);
    assert!(csv.is_file() && !fig.exists(), "{name}: --no-plots");
    assert!(!table.contains(".svg"), "{name}: {table}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn spatial_basins_write_their_figure() {
    check_basins("basins-spatial", &example("spatial.toml"), &["drive.t_end=20"], 3);
}

#[test]
fn linear_basins_write_their_figure() {
    check_basins("basins-linear", &example("linear_rotor_shaft.toml"), &["drive.t_end=0.1"], 2);
}

/// A figure's file that is the config (a TOML file named like the figure) is refused before
/// anything runs, naming `--out`, as the CSV would be; with `--no-plots` there is no figure and
/// the same command runs.
#[test]
fn a_figure_colliding_with_the_config_is_refused() {
    let d = dir("collide");
    let cfg = d.join("sw_peak.svg");
    std::fs::copy(example("planar.toml"), &cfg).unwrap();
    let base = ["sweep", "--config", &s(&cfg), "--x", "drive.b=100,200", "--set", "drive.t_end=0.5", "--set", "drive.omega0=250", "--out", &s(&d.join("sw"))];
    let (code, _, err) = autobal(&base);
    assert_eq!(code, 2);
    assert!(err.starts_with(&format!("error: --out: {} is the input --config", cfg.display())), "{err}");
    assert!(!d.join("sw.csv").exists(), "nothing written");
    ok(&[&base[..], &["--no-plots"]].concat());
    assert!(d.join("sw.csv").is_file());
    let cfg = d.join("b.svg");
    std::fs::copy(example("spatial.toml"), &cfg).unwrap();
    let base = ["basins", "--config", &s(&cfg), "--n", "2", "--set", "drive.t_end=5", "--out", &s(&d.join("b.csv"))];
    let (code, _, err) = autobal(&base);
    assert_eq!(code, 2);
    assert!(err.starts_with(&format!("error: --out: {} is the input --config", cfg.display())), "{err}");
    assert!(!d.join("b.csv").exists(), "nothing written");
    ok(&[&base[..], &["--no-plots"]].concat());
    assert!(d.join("b.csv").is_file());
    std::fs::remove_dir_all(&d).ok();
}
