//! A linear rotor config (`[linear_rotor]`) from the command line with NumPy matrix files
//! (`.npz` archives and `.npy` arrays, issue 19 item 2b) and with the parameter paths of one
//! balancer plane or unbalance of several (`linear_rotor.balancer[j].KEY`, issue 19 item 4).
//!
//! The `.npz` archive is written here, by a ZIP writer of the test's own (stored members, as
//! `np.savez` writes them), from the Matrix Market files `export-model` writes: the same
//! numbers by another file format and another reader must give the same stability, number for
//! number.

use std::path::{Path, PathBuf};
use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = autobal(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-linfiles-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The dense row-major matrix of a `coordinate real general` Matrix Market file (what
/// `export-model` writes), read with Rust's `f64` parser: exact for the digits written.
fn read_mtx(p: &Path) -> (usize, Vec<f64>) {
    let text = std::fs::read_to_string(p).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('%'));
    let size: Vec<usize> = lines.next().unwrap().split_whitespace().map(|s| s.parse().unwrap()).collect();
    let n = size[0];
    let mut a = vec![0.0; n * n];
    for l in lines {
        let f: Vec<&str> = l.split_whitespace().collect();
        let (i, j, v): (usize, usize, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap(), f[2].parse().unwrap());
        a[(i - 1) * n + j - 1] += v;
    }
    (n, a)
}

/// A `.npy` file (format 1.0) of the `n × n` row-major matrix `a`, little-endian `f8`, C order,
/// its header padded to a multiple of 64 bytes as NumPy pads it.
fn npy(a: &[f64], n: usize) -> Vec<u8> {
    let mut h = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, {n}), }}");
    while !(10 + h.len() + 1).is_multiple_of(64) {
        h.push(' ');
    }
    h.push('\n');
    let mut b = b"\x93NUMPY\x01\x00".to_vec();
    b.extend_from_slice(&(h.len() as u16).to_le_bytes());
    b.extend_from_slice(h.as_bytes());
    for v in a {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b
}

/// CRC-32 (ISO-HDLC, the ZIP checksum), bit by bit.
fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for &b in data {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 { (c >> 1) ^ 0xEDB8_8320 } else { c >> 1 };
        }
    }
    !c
}

/// A ZIP archive of stored members (method 0), as `np.savez` writes one: local headers and
/// data, the central directory, the end record.
fn zip(members: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let (mut out, mut central) = (vec![], vec![]);
    for (name, data) in members {
        let (crc, size, offset) = (crc32(data), data.len() as u32, out.len() as u32);
        let common = |v: &mut Vec<u8>| {
            v.extend_from_slice(&20u16.to_le_bytes()); // version needed
            v.extend_from_slice(&0u16.to_le_bytes()); // flags
            v.extend_from_slice(&0u16.to_le_bytes()); // stored
            v.extend_from_slice(&0u32.to_le_bytes()); // time, date
            v.extend_from_slice(&crc.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&size.to_le_bytes());
            v.extend_from_slice(&(name.len() as u16).to_le_bytes());
            v.extend_from_slice(&0u16.to_le_bytes()); // extra
        };
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        common(&mut out);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&20u16.to_le_bytes()); // version made by
        common(&mut central);
        central.extend_from_slice(&[0; 6]); // comment length, disk, internal attributes
        central.extend_from_slice(&0u32.to_le_bytes()); // external attributes
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd = out.len() as u32;
    out.extend_from_slice(&central);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0; 4]);
    out.extend_from_slice(&(members.len() as u16).to_le_bytes());
    out.extend_from_slice(&(members.len() as u16).to_le_bytes());
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&cd.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

/// The exported config with its Matrix Market keys replaced by `keys`.
fn with_matrices(exported: &str, keys: &str) -> String {
    let kept: Vec<&str> = exported.lines().filter(|l| !["m = ", "c = ", "g = ", "k = "].iter().any(|k| l.starts_with(k))).collect();
    kept.join("\n").replace("[linear_rotor]\n", &format!("[linear_rotor]\n{keys}")) + "\n"
}

/// The shaft example (reduced) exported, its matrices written as one `.npz` archive and as
/// `.npy` files: `stability` from the command line gives the same points, ranges and natural
/// frequencies as from the Matrix Market files, to the last digit (the same doubles reach the
/// library by either reader); an archive without `K` is an error naming the key and the file.
#[test]
fn npz_and_npy_matrices_from_the_command_line() {
    let dir = tmp("npz");
    let (code, _, err) = autobal(&["export-model", "--config", &example("linear_rotor_shaft.toml"), "--out", dir.to_str().unwrap(), "--stem", "shaft"]);
    assert_eq!(code, 0, "{err}");
    let exported = std::fs::read_to_string(dir.join("shaft.toml")).unwrap();
    let mats: Vec<(&str, (usize, Vec<f64>))> = ["M", "C", "G", "K"].iter().map(|m| (*m, read_mtx(&dir.join(format!("shaft_{m}.mtx"))))).collect();
    let n = mats[0].1 .0;
    assert_eq!(n, 16, "the example reduced to 4 mode pairs");
    let members: Vec<(String, Vec<u8>)> = mats.iter().map(|(m, (n, a))| (format!("{m}.npy"), npy(a, *n))).collect();
    let refs: Vec<(&str, Vec<u8>)> = members.iter().map(|(k, v)| (k.as_str(), v.clone())).collect();
    std::fs::write(dir.join("shaft.npz"), zip(&refs)).unwrap();
    std::fs::write(dir.join("partial.npz"), zip(&refs[..2])).unwrap();
    for (m, b) in &members {
        std::fs::write(dir.join(m), b).unwrap();
    }
    std::fs::write(dir.join("npz.toml"), with_matrices(&exported, "matrices = \"shaft.npz\"\n")).unwrap();
    std::fs::write(dir.join("npy.toml"), with_matrices(&exported, "m = \"M.npy\"\nc = \"C.npy\"\ng = \"G.npy\"\nk = \"K.npy\"\n")).unwrap();
    std::fs::write(dir.join("partial.toml"), with_matrices(&exported, "matrices = \"partial.npz\"\n")).unwrap();
    let stability =
        |cfg: &str| json(&["stability", "--config", dir.join(cfg).to_str().unwrap(), "--samples", "20", "--omega-max", "2500 rad/s", "--format", "json"]);
    let mm = stability("shaft.toml");
    assert!(!mm["stable_ranges"].as_array().unwrap().is_empty(), "the example balances somewhere: the comparison is not of empty lists");
    for cfg in ["npz.toml", "npy.toml"] {
        let got = stability(cfg);
        assert_eq!(got["source"], "matrices", "{cfg}");
        for key in ["points", "stable_ranges", "natural_frequencies", "reduction"] {
            assert_eq!(got[key], mm[key], "{cfg}: {key}");
        }
    }
    // the run in time reads the archive too
    let (code, _, err) = autobal(&[
        "simulate",
        "--config",
        dir.join("npz.toml").to_str().unwrap(),
        "--set",
        "drive.b=100",
        "--set",
        "drive.t_end=0.05",
        "--format",
        "json",
        "--out",
        dir.join("run.csv").to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = autobal(&["stability", "--config", dir.join("partial.toml").to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("linear_rotor.matrices: partial.npz: has no array K (required)"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `linear_rotor.balancer[j].KEY` on the command line: as a `--set`, it gives the stability of
/// the config edited by hand; as a sweep axis on a one-plane config, the runs of
/// `linear_rotor.ball_mass` (two routes to the same tables); an index past the last plane is an
/// error naming the path and the count.
#[test]
fn one_balancer_plane_by_its_path() {
    let dir = tmp("paths");
    let shaft = example("linear_rotor_shaft.toml");
    let edited = std::fs::read_to_string(&shaft).unwrap().replace("ball_mass = 0.02", "ball_mass = 0.035");
    assert!(edited.contains("ball_mass = 0.035"));
    std::fs::write(dir.join("edited.toml"), edited).unwrap();
    let st = |cfg: &str, set: &[&str]| {
        let mut a = vec!["stability", "--config", cfg, "--samples", "20", "--omega-max", "2500 rad/s", "--format", "json"];
        a.extend_from_slice(set);
        json(&a)
    };
    let by_set = st(&shaft, &["--set", "linear_rotor.balancer[0].ball_mass=0.035"]);
    let by_hand = st(dir.join("edited.toml").to_str().unwrap(), &[]);
    assert_eq!(by_set["points"], by_hand["points"]);
    assert_ne!(by_set["points"], st(&shaft, &[])["points"], "the ball mass changes the margins");
    let sweep = |x: &str| {
        let stem = dir.join(x.split('=').next().unwrap().replace(['[', ']'], "_"));
        let v = json(&["sweep", "--config", &shaft, "--set", "drive.t_end=0.1", "--x", x, "--format", "json", "--out", stem.to_str().unwrap()]);
        v["runs"].as_array().unwrap().iter().map(|r| (r["values"].clone(), r["summary"].clone())).collect::<Vec<_>>()
    };
    let a = sweep("linear_rotor.balancer[0].ball_mass=0.02,0.03");
    let b = sweep("linear_rotor.ball_mass=0.02,0.03");
    assert_eq!(a.len(), 2);
    for ((va, sa), (vb, sb)) in a.iter().zip(&b) {
        assert_eq!(va, vb);
        assert_eq!(sa, sb);
    }
    assert_ne!(a[0].1, a[1].1, "the ball mass changes the run");
    let (code, _, err) = autobal(&[
        "map",
        "--config",
        &shaft,
        "--x",
        "speed=100:1500:3",
        "--y",
        "linear_rotor.balancer[1].drag=0.1:0.2:2",
        "--out",
        dir.join("m").to_str().unwrap(),
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("linear_rotor.balancer[1].drag: the config has 1 [[linear_rotor.balancer]] (j from 0 to 0)"), "{err}");
    let (code, _, err) = autobal(&["stability", "--config", &shaft, "--set", "linear_rotor.unbalance[0].mass=1"]);
    assert_ne!(code, 0);
    assert!(err.contains("linear_rotor.unbalance[0].mass: unknown key of [[linear_rotor.unbalance]] (known: node, me, phase, offset)"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
