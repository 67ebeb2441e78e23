//! A linear rotor config's `[drive]` and `[integration]` refuse keys they do not read (found by a
//! reviewer on 2026-11-28: `psi0 = [0.3, 2.5]` and `bogus_key = 7` in `[drive]` ran, ignored),
//! with one line naming the key, exit code 2 and no output written; in the config and through
//! `--set`.

use std::process::Command;

const SHAFT: &str = "[linear_rotor]\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.03\ne = 2.1e11\nrho = 7850.0\ncount = 4\n\
    [[linear_rotor.disks]]\nnode = 2\nmass = 3.0\nid = 0.01\nip = 0.02\n\
    [[linear_rotor.bearings]]\nnode = 0\nk = 2e6\nc = 300.0\n[[linear_rotor.bearings]]\nnode = 4\nk = 2e6\nc = 300.0\n\
    [[linear_rotor.unbalance]]\nnode = 2\nme = 1e-4\n\
    [[linear_rotor.balancer]]\nnode = 2\nradius = 0.05\nballs = 2\nball_mass = 0.02\ndrag = 0.05\n";

fn run(dir: &std::path::Path, extra: &str, set: &[&str]) -> (i32, String, bool) {
    let cfg = dir.join("rotor.toml");
    std::fs::write(&cfg, format!("{SHAFT}{extra}")).unwrap();
    let out_stem = dir.join("run");
    let mut args = vec!["simulate".to_string(), "--config".into(), cfg.display().to_string(), "--out".into(), out_stem.display().to_string()];
    for s in set {
        args.push("--set".into());
        args.push(s.to_string());
    }
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(&args).output().unwrap();
    let written = std::fs::read_dir(dir).unwrap().any(|e| e.unwrap().file_name().to_string_lossy().starts_with("run"));
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned(), written)
}

#[test]
fn unknown_drive_and_integration_keys_are_refused_by_name() {
    let dir = std::env::temp_dir().join(format!("autobal-lr-run-keys-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases: [(&str, &[&str], &str); 4] = [
        (
            "[drive]\nkind = \"speed\"\nomega0 = 300.0\nt_end = 0.1\npsi0 = [0.3, 2.5]\n",
            &[],
            "drive.psi0: a linear rotor's run starts with the structure at rest",
        ),
        ("[drive]\nkind = \"speed\"\nomega0 = 300.0\nt_end = 0.1\nbogus_key = 7\n", &[], "drive.bogus_key: unknown key"),
        ("[integration]\nrtol = 1e-8\nrtoll = 1e-9\n", &[], "integration.rtoll: unknown key"),
        ("[drive]\nkind = \"speed\"\nomega0 = 300.0\nt_end = 0.1\n", &["drive.psi0[0]=1.0"], "drive.psi0"),
    ];
    for (extra, set, want) in cases {
        let (code, err, written) = run(&dir, extra, set);
        assert_eq!(code, 2, "{extra}: {err}");
        assert!(err.starts_with(&format!("error: {want}")), "{extra}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(!written, "{extra}: an output was written");
    }
    // the keys it reads still run
    let (code, err, written) = run(&dir, "[drive]\nkind = \"speed\"\nomega0 = 300.0\nt_end = 0.05\n[integration]\nrtol = 1e-7\ndt = 0.01\n", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(written);
    std::fs::remove_dir_all(&dir).ok();
}

/// 100 000 balls on a linear rotor (the planar rotor's limit) made every analysis allocate a
/// dense Jacobian of (2 (N + n_b))² doubles, 320 GB, and abort; the balls are coordinates of
/// the same dense matrices as the DOFs and share their limit of 2000 (found 2026-11-28).
#[test]
fn too_many_balls_for_the_dense_matrices_are_refused_by_name() {
    let dir = std::env::temp_dir().join(format!("autobal-lr-many-balls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cfg = dir.join("rotor.toml");
    std::fs::write(&cfg, SHAFT.replace("balls = 2\n", "balls = 100000\n")).unwrap();
    let out_stem = dir.join("x");
    for args in [vec!["stability"], vec!["campbell"], vec!["simulate", "--out", out_stem.to_str().unwrap()]] {
        let cmd = args[0];
        let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(&args).args(["--config", cfg.to_str().unwrap()]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{cmd}: {err}");
        assert!(err.starts_with("error: linear_rotor.balancer[0].balls: 100000 exceeds the limit of 1980"), "{cmd}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
