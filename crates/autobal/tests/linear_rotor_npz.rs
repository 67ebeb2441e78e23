//! NumPy matrices for the linear rotor config ([`autobal::linear_rotor::npz`], issue 19, 2b):
//! the same rotor from an `.npz` archive written by NumPy (`np.savez`, `np.savez_compressed`,
//! Fortran order, the DOF table as strings), from `.npy` files, and from Matrix Market text gives
//! bit-identical matrices; damaged or unfit archives give a one-line error naming the key.

mod common;

use autobal::linear_rotor::config::{export, linear_rotor, linear_rotor_bytes};
use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, LinearRotor, SpeedBearing, Unbalance};
use std::collections::HashMap;
use std::path::PathBuf;

fn rotor() -> LinearRotor {
    let mut b = ShaftBuilder::uniform(5, 0.6, 0.03, 2.1e11, 7850.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 2, mass: 1.3, id: 2e-3, ip: 4e-3 });
    b.bearings.push(Bearing { node: 0, k: 1e6, c: 30.0 });
    b.bearings.push(Bearing { node: 5, k: 2e6, c: 40.0 });
    let mut r = b.build().unwrap();
    // a cross-coupled bearing in K, C: not symmetric
    let n = r.dofs();
    r.k[20 * n + 21] += 3e5;
    r.k[21 * n + 20] -= 3e5;
    r.c[20 * n + 21] += 7.0;
    r.speed_bearings.push(SpeedBearing { node: 5, link: None, speeds: vec![0.0, 100.0], k: vec![[1e5, 0.0, 0.0, 1e5]; 2], c: vec![[1.0, 0.0, 0.0, 1.0]; 2] });
    r.unbalances.push(Unbalance { node: 2, me: 1e-4, phase: 0.2, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.05, balls: 2, ball_mass: 0.01, drag: 0.01, offset: 0.0 });
    r
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("autobal-npz-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The rotor exported to Matrix Market, converted by NumPy (reading the text with Python's
/// `float`, which is exact for the shortest round-trip digits the export writes) into `.npz`
/// archives and `.npy` files, read back: the same `LinearRotor` as from the Matrix Market
/// files, bit for bit.
#[test]
fn npz_and_npy_equal_matrix_market_bit_for_bit() {
    let Some(py) = common::python_with(&["numpy"]) else { return };
    let r = rotor();
    let (toml_text, files) = export(&r, "r");
    let dir = tmp("same");
    for (name, text) in &files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let script = r#"
import sys, numpy as np
d = sys.argv[1]
def mtx(name):
    lines = [l for l in open(f"{d}/r_{name}.mtx").read().splitlines() if not l.startswith("%")]
    n = int(lines[0].split()[0])
    a = np.zeros((n, n))
    for l in lines[1:]:
        i, j, v = l.split()
        a[int(i) - 1, int(j) - 1] = float(v)
    return a
M, C, G, K = (mtx(x) for x in "MCGK")
n = M.shape[0]
dofs = np.array([f"{['x', 'y', 'alpha', 'beta'][i % 4]}{i // 4}" for i in range(n)])
np.savez(f"{d}/plain.npz", M=M, C=C, G=G, K=K, dofs=dofs)
np.savez_compressed(f"{d}/packed.npz", M=np.asfortranarray(M), C=C, G=G, K=np.asfortranarray(K))
np.save(f"{d}/M.npy", np.asfortranarray(M))
np.save(f"{d}/K.npy", K)
np.save(f"{d}/C.npy", C)
np.save(f"{d}/G.npy", G.astype(">f8"))
np.savez(f"{d}/partial.npz", M=M, C=C)
np.savez(f"{d}/vector.npz", M=M, K=K[0])
"#;
    let out = std::process::Command::new(&py).args(["-c", script, dir.to_str().unwrap()]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mm: toml::Table = toml_text.parse().unwrap();
    let text_files: HashMap<String, String> = files.into_iter().collect();
    let reference = linear_rotor(&mm, &mut |p| text_files.get(p).cloned().ok_or_else(|| "missing".to_string())).unwrap().rotor;
    assert_eq!(reference, r);
    let mut load = |p: &str| std::fs::read(dir.join(p)).map_err(|e| e.to_string());
    // the same config with the matrices from NumPy: the archive, or one .npy file per matrix
    let strip = |t: &str| -> String {
        t.lines().filter(|l| !["m = ", "c = ", "g = ", "k = ", "dofs = "].iter().any(|k| l.starts_with(k))).collect::<Vec<_>>().join("\n")
    };
    for (what, keys) in [
        ("np.savez", "matrices = \"plain.npz\"\n"),
        ("np.savez_compressed, Fortran order", "matrices = \"packed.npz\"\n"),
        (".npy files", "m = \"M.npy\"\nk = \"K.npy\"\nc = \"C.npy\"\ng = \"G.npy\"\n"),
    ] {
        let text = strip(&toml_text).replace("[linear_rotor]\n", &format!("[linear_rotor]\n{keys}"));
        let root: toml::Table = text.parse().unwrap();
        let got = linear_rotor_bytes(&root, &mut load).unwrap_or_else(|e| panic!("{what}: {e}")).rotor;
        assert_eq!(got, reference, "{what}");
    }
    // errors: a required array missing, a vector for a matrix, a damaged archive, .npz per key
    let bad = std::fs::read(dir.join("plain.npz")).unwrap();
    let mut damaged = bad.clone();
    let mid = damaged.len() / 2;
    damaged[mid] ^= 0x55;
    std::fs::write(dir.join("damaged.npz"), damaged).unwrap();
    for (keys, want) in [
        ("matrices = \"partial.npz\"\n", "linear_rotor.matrices: partial.npz: has no array K (required)"),
        ("matrices = \"vector.npz\"\n", "linear_rotor.matrices: vector.npz: K: has 1 dimensions, a matrix has 2"),
        ("matrices = \"damaged.npz\"\n", "linear_rotor.matrices: damaged.npz:"),
        ("m = \"plain.npz\"\nk = \"K.npy\"\n", "linear_rotor.m: plain.npz: an .npz archive holds all the matrices"),
        ("matrices = \"plain.npz\"\nk = \"K.npy\"\n", "linear_rotor.k: give the matrices either in the archive"),
    ] {
        let text = strip(&toml_text).replace("[linear_rotor]\n", &format!("[linear_rotor]\n{keys}"));
        let root: toml::Table = text.parse().unwrap();
        let e = linear_rotor_bytes(&root, &mut load).unwrap_err().to_string();
        assert!(e.starts_with(want), "{keys}: {e}");
        assert!(!e.contains('\n'), "{e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
