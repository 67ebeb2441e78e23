//! `--set` on a linear rotor config takes every parameter path a map or a sweep takes
//! (`autobal::linear_rotor::spec::PATHS`, issue 19): `linear_rotor.drag` (the drag of every
//! balancer plane) was refused as an unknown key of `[linear_rotor]` while
//! `linear_rotor.balancer[0].drag` and the map's axis `linear_rotor.drag` worked.
//!
//! Two routes to the same config: `--set PATH=V` (`autobal_commands::linear_rotor::load`, what
//! the CLI runs) against the map's own `LinearRotorSpec::config_at(&[(PATH, V)])`, for each
//! path; and on the command line, the stability with `--set linear_rotor.drag=V` against the
//! config edited by hand.

use autobal::linear_rotor::spec::{LinearRotorSpec, PATHS};
use std::path::PathBuf;
use std::process::Command;

fn example(name: &str) -> PathBuf {
    PathBuf::from(format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR")))
}

/// A value each `linear_rotor.KEY` path of [`PATHS`] takes on `linear_rotor_shaft.toml` (one
/// balancer plane, one unbalance, two bearings), other than the config's own where it has one.
fn value(key: &str) -> f64 {
    match key {
        "ball_mass" => 0.035,
        "radius" => 0.05,
        "drag" => 0.3,
        "balls" => 3.0,
        "me" => 3e-4,
        "unbalance_scale" | "support_stiffness_scale" | "support_damping_scale" => 1.5,
        "polar_inertia" => 0.02,
        "spin_damping" => 1e-3,
        "omega_max" => 2000.0,
        "modes" => 3.0,
        o => panic!("a path this test does not know: linear_rotor.{o} (give it a value)"),
    }
}

/// Every `linear_rotor.KEY` parameter path (not the per-entry `balancer[j].KEY`, checked by
/// `linear_rotor_files.rs`) set by `--set` gives the config the map's path gives, exactly
/// (`LinearRotorConfig: PartialEq`, matrices and all), and not the config without it.
#[test]
fn every_map_path_is_a_set_path() {
    let shaft = example("linear_rotor_shaft.toml");
    let root: toml::Table = toml::from_str(&std::fs::read_to_string(&shaft).unwrap()).unwrap();
    let spec = LinearRotorSpec::new(root, &mut |p| Err(format!("no files: {p}"))).unwrap();
    let plain = autobal_commands::linear_rotor::load(&shaft, &[]).unwrap();
    let mut seen = 0;
    for &(path, _) in PATHS {
        let Some(key) = path.strip_prefix("linear_rotor.").filter(|k| !k.contains('[')) else { continue };
        let v = value(key);
        let by_set = autobal_commands::linear_rotor::load(&shaft, &[format!("{path}={v}")]).unwrap_or_else(|e| panic!("--set {path}={v}: {e:#}"));
        let by_map = spec.config_at(&[(path, v)]).unwrap();
        assert_eq!(by_set, by_map, "{path}");
        assert_ne!(by_set, plain, "{path}={v} changes the config");
        seen += 1;
    }
    assert!(seen >= 12, "the paths of PATHS under linear_rotor: {seen}");
}

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// On the command line: `--set linear_rotor.drag=0.3` gives the stability of the config with
/// `drag = 0.3` written in its only balancer plane, point for point, the same as
/// `--set linear_rotor.balancer[0].drag=0.3`, and not the config's own (drag 0.1); an unknown key
/// is still refused in one line naming it and the accepted forms.
#[test]
fn drag_of_every_plane_by_set() {
    let dir = std::env::temp_dir().join(format!("autobal-setpaths-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shaft = example("linear_rotor_shaft.toml");
    let text = std::fs::read_to_string(&shaft).unwrap();
    assert_eq!(text.matches("drag = 0.1").count(), 1, "one balancer plane with drag 0.1");
    let edited = dir.join("edited.toml");
    std::fs::write(&edited, text.replace("drag = 0.1", "drag = 0.3")).unwrap();
    let st = |cfg: &str, set: &[&str]| {
        let mut a = vec!["stability", "--config", cfg, "--samples", "12", "--omega-max", "2500 rad/s", "--format", "json"];
        a.extend_from_slice(set);
        let (code, out, err) = autobal(&a);
        assert_eq!(code, 0, "{a:?}: {err}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()["points"].clone()
    };
    let shaft = shaft.to_str().unwrap();
    let by_set = st(shaft, &["--set", "linear_rotor.drag=0.3"]);
    assert_eq!(by_set, st(edited.to_str().unwrap(), &[]));
    assert_eq!(by_set, st(shaft, &["--set", "linear_rotor.balancer[0].drag=0.3"]));
    assert_ne!(by_set, st(shaft, &[]), "the drag changes the margins");
    let (code, _, err) = autobal(&["stability", "--config", shaft, "--set", "linear_rotor.dragg=0.3"]);
    assert_ne!(code, 0);
    assert!(err.contains("linear_rotor.dragg"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
