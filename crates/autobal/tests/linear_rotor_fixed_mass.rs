//! The inertia fixed to the rotor ([`LinearRotor::rotor_fixed_mass`], `M_rot`) in the linear
//! rotor's files and its reduction (issue 19): read from configs (`linear_rotor.rotor_fixed_mass`,
//! a Matrix Market or `.npy` file, or the array `M_rot` of the `.npz` archive) and refused with a
//! one-line error naming the key where it is not a mass; written by `export` (`export-model`) so
//! that the spatial preset with unbalance inertia, a couple and a tilted principal axis reads
//! back as itself; and projected by model reduction, whose basis is closed under the quarter
//! turn `J`, so that `Bᵀ T(φ) M_rot T(φ)ᵀ B = T_r(φ) (Bᵀ M_rot B) T_r(φ)ᵀ` at every angle.

mod common;

use autobal::analysis::{stability, stationary, NewtonOptions};
use autobal::drive::Drive;
use autobal::linear_rotor::config::{export, linear_rotor_bytes, write_matrix_market};
use autobal::linear_rotor::reduce::reduce;
use autobal::linear_rotor::runup::{simulate, RunSample, RunSettings};
use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::spec::LinearRotorSpec;
use autobal::linear_rotor::{BalancerPlane, Frame, LinearRotor, LinearRotorField, Unbalance};
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialField, SpatialRotor, Support};
use common::match_distance;
use num_complex::Complex64;
use std::collections::HashMap;
use std::f64::consts::PI;

/// The rigid rotor of `tests/linear_rotor_spatial_preset.rs` with two balancer planes, an
/// unbalance mass out of both (a couple), the principal axis tilted by `κ = 0.002` and two
/// opposite 0.5 kg masses at 0.1 m (`ΔA = 0.01` kg m² fixed to the rotor); supports `k` and
/// `1.2 k` per direction.
fn spatial(k: [f64; 2], gravity: [f64; 3]) -> SpatialRotor {
    let ball = |z: f64| BallPlane { z, n: 2, ball_mass: 0.02, race_radius: 0.1, drag: 0.01, physics: Default::default() };
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.02, axis_tilt: 0.002, axis_tilt_angle: 0.7 },
        supports: vec![
            Support { z: -0.3, stiffness: k, damping: [20.0, 20.0] },
            Support { z: 0.4, stiffness: [k[0] * 1.2, k[1] * 1.2], damping: [25.0, 25.0] },
        ],
        unbalances: vec![
            PointMass { mass: 0.01, radius: 0.1, angle: 0.4, z: 0.15 },
            PointMass { mass: 0.006, radius: 0.08, angle: 2.2, z: 0.05 },
            PointMass { mass: 0.5, radius: 0.1, angle: 0.9, z: 0.02 },
            PointMass { mass: 0.5, radius: 0.1, angle: 0.9 + PI, z: 0.02 },
        ],
        planes: vec![ball(0.15), ball(-0.2)],
        gravity,
        spin_drag: 0.05,
        lock_tilt: false,
    }
}

/// A `.npy` file (format 1.0, little-endian `f8`, C order) of the row-major `n × n` matrix `a`.
fn npy(a: &[f64], n: usize) -> Vec<u8> {
    let mut h = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, {n}), }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut b = b"\x93NUMPY\x01\x00".to_vec();
    b.extend_from_slice(&(h.len() as u16).to_le_bytes());
    b.extend_from_slice(h.as_bytes());
    a.iter().for_each(|v| b.extend_from_slice(&v.to_le_bytes()));
    b
}

/// CRC-32 (IEEE, reflected), as ZIP uses.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// A `.npz` archive as `np.savez` writes it (a ZIP of stored `NAME.npy` members).
fn npz(members: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let (mut out, mut cd) = (vec![], vec![]);
    for (name, data) in members {
        let name = format!("{name}.npy");
        let (crc, len, off) = (crc32(data), data.len() as u32, out.len() as u32);
        let fixed = |sig: u32, central: bool| -> Vec<u8> {
            let mut h = sig.to_le_bytes().to_vec();
            if central {
                h.extend_from_slice(&20u16.to_le_bytes());
            }
            for v in [20u16, 0, 0, 0, 0] {
                h.extend_from_slice(&v.to_le_bytes());
            }
            for v in [crc, len, len] {
                h.extend_from_slice(&v.to_le_bytes());
            }
            h.extend_from_slice(&(name.len() as u16).to_le_bytes());
            h.extend_from_slice(&0u16.to_le_bytes());
            if central {
                for v in [0u16, 0, 0] {
                    h.extend_from_slice(&v.to_le_bytes());
                }
                h.extend_from_slice(&0u32.to_le_bytes());
                h.extend_from_slice(&off.to_le_bytes());
            }
            h.extend_from_slice(name.as_bytes());
            h
        };
        out.extend(fixed(0x0403_4b50, false));
        out.extend_from_slice(data);
        cd.extend(fixed(0x0201_4b50, true));
    }
    let (cd_off, cd_len, count) = (out.len() as u32, cd.len() as u32, members.len() as u16);
    out.extend(cd);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    for v in [0u16, 0, count, count] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&cd_len.to_le_bytes());
    out.extend_from_slice(&cd_off.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

/// Read the config text with the files `files` (by name).
fn read(text: &str, files: &HashMap<String, Vec<u8>>) -> autobal::Result<LinearRotor> {
    let root: toml::Table = text.parse().unwrap();
    linear_rotor_bytes(&root, &mut |p| files.get(p).cloned().ok_or_else(|| format!("{p}: missing"))).map(|c| c.rotor)
}

/// Every eigenvalue of the balanced state at `omega` in axes turning with the rotor (without
/// gravity an equilibrium: the rotor-fixed inertia is constant in those axes), Newton's method
/// from `guess` (the field's own balanced guess where `None`).
fn balanced_eigenvalues(r: &LinearRotor, omega: f64, guess: Option<&[f64]>) -> Vec<Complex64> {
    let f = LinearRotorField::new(r, omega, Frame::Rotating).unwrap();
    let g = guess.map_or_else(|| f.balanced_guess().unwrap(), |g| g.to_vec());
    let s = stationary(&f, &g, &NewtonOptions::default()).unwrap_or_else(|e| panic!("Ω {omega}: {e}"));
    common::all_eigenvalues(&stability(&f, &s).unwrap())
}

/// The spatial preset of a rotor with unbalance inertia, a couple and a tilted principal axis
/// (so `rotor_fixed_mass` is not empty), with equal and direction-dependent supports and with
/// gravity across the axis: written by `export` (Matrix Market, shortest round-trip floats) and
/// read back through a config it is the preset bit for bit, so its balanced state's eigenvalues
/// and a run of 20 revolutions at constant speed are the preset's exactly (0 difference: the
/// same numbers through the same code; any key lost or rounded by the files shows here). The
/// same inertia from a `.npy` file and as the array `M_rot` of an `.npz` archive: the same rotor,
/// also at a point of a map or sweep ([`LinearRotorSpec`]).
#[test]
fn spatial_preset_with_rotor_fixed_inertia_round_trips_through_export() {
    for (k, gravity) in [([1e5, 1e5], [0.0; 3]), ([1e5, 1.3e5], [0.5, -9.81, 0.0])] {
        let preset = LinearRotor::from_spatial(&spatial(k, gravity)).unwrap();
        assert!(!preset.rotor_fixed_mass.is_empty());
        let (text, files) = export(&preset, "p");
        assert!(text.contains("rotor_fixed_mass = \"p_M_rot.mtx\"\n"), "{text}");
        let names: Vec<&str> = files.iter().map(|f| f.0.as_str()).collect();
        assert_eq!(names, ["p_M.mtx", "p_C.mtx", "p_G.mtx", "p_K.mtx", "p_chart.mtx", "p_M_rot.mtx"]);
        let mut bytes: HashMap<String, Vec<u8>> = files.into_iter().map(|(n, t)| (n, t.into_bytes())).collect();
        let back = read(&text, &bytes).unwrap();
        assert_eq!(back, preset, "supports {k:?}");
        if gravity == [0.0; 3] {
            // two planes: the balanced state from the native model's (tests/linear_rotor_spatial_preset.rs)
            let w = 140.0;
            let s = spatial(k, gravity);
            let fs = SpatialField::new(&s, w).unwrap();
            let x = stationary(&fs, &fs.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap().x;
            let (a, b) = (balanced_eigenvalues(&preset, w, Some(&x)), balanced_eigenvalues(&back, w, Some(&x)));
            assert_eq!(match_distance(&a, &b), 0.0);
        }
        let w = 170.0;
        let settings = RunSettings {
            t_end: 20.0 * 2.0 * PI / w,
            dt: 0.2 * 2.0 * PI / w,
            rtol: 1e-9,
            atol: 1e-12,
            method: Default::default(),
            max_steps: 1_000_000,
            max_wall_s: None,
            physical_nodes: None,
        };
        let run = |r: &LinearRotor| {
            let mut samples: Vec<RunSample> = vec![];
            let sum = simulate(r, &Drive::Speed { omega0: w }, &settings, &autobal::control::Control::none(), |s| {
                samples.push(s.clone());
                true
            })
            .unwrap();
            assert!(sum.stopped.is_none(), "{:?}", sum.stopped);
            samples
        };
        let (a, b) = (run(&preset), run(&back));
        assert_eq!(a.len(), 101);
        assert_eq!(a, b, "supports {k:?}: the runs differ");
        // the same inertia from a .npy file, and in the archive as M_rot
        let n = preset.dofs();
        bytes.insert("Mrot.npy".into(), npy(&preset.rotor_fixed_mass, n));
        let npy_text = text.replace("rotor_fixed_mass = \"p_M_rot.mtx\"", "rotor_fixed_mass = \"Mrot.npy\"");
        assert_eq!(read(&npy_text, &bytes).unwrap(), preset, "from .npy");
        let archive = npz(&[
            ("M", npy(&preset.m, n)),
            ("C", npy(&preset.c, n)),
            ("G", npy(&preset.g, n)),
            ("K", npy(&preset.k, n)),
            ("M_rot", npy(&preset.rotor_fixed_mass, n)),
            ("spin_chart", npy(&preset.spin_chart, n)),
        ]);
        bytes.insert("p.npz".into(), archive);
        let npz_text: String = text
            .lines()
            .filter(|l| !["m = ", "c = ", "g = ", "k = ", "spin_chart = ", "rotor_fixed_mass = "].iter().any(|p| l.starts_with(p)))
            .map(|l| if l == "[linear_rotor]" { "[linear_rotor]\nmatrices = \"p.npz\"\n".to_string() } else { format!("{l}\n") })
            .collect();
        assert_eq!(read(&npz_text, &bytes).unwrap(), preset, "from .npz");
        // a map's or sweep's point reads the config again from the bytes read once: the
        // inertia comes with them
        let spec = LinearRotorSpec::new(npz_text.parse().unwrap(), &mut |p| bytes.get(p).cloned().ok_or_else(|| format!("{p}: missing"))).unwrap();
        let point = spec.model_at(&[("linear_rotor.ball_mass", 0.03)]).unwrap();
        assert_eq!((point.rotor_fixed_mass.as_slice(), point.balancers[1].ball_mass), (preset.rotor_fixed_mass.as_slice(), 0.03));
        // the archive's M_rot and a file too: refused
        let both = npz_text.replace("matrices = \"p.npz\"\n", "matrices = \"p.npz\"\nrotor_fixed_mass = \"p_M_rot.mtx\"\n");
        let e = read(&both, &bytes).unwrap_err().to_string();
        assert!(e.starts_with("linear_rotor.rotor_fixed_mass: p.npz has M_rot too"), "{e}");
    }
}

/// Files that are no inertia are refused with one line naming the key: the wrong size, an entry
/// that is not finite, a non-symmetric matrix, and one with which `M + T(φ) M_rot T(φ)ᵀ` is not
/// positive definite (an anisotropy larger than the mean equatorial moment); an absent key is no
/// inertia, and the shaft builder takes the key too.
#[test]
fn unfit_rotor_fixed_inertia_is_refused_naming_the_key() {
    let preset = LinearRotor::from_spatial(&spatial([1e5, 1e5], [0.0; 3])).unwrap();
    let (text, files) = export(&preset, "p");
    let mut bytes: HashMap<String, Vec<u8>> = files.into_iter().map(|(n, t)| (n, t.into_bytes())).collect();
    let n = 4;
    let with = |a: &[f64], size: usize| write_matrix_market(a, size, "test").into_bytes();
    let mut asym = preset.rotor_fixed_mass.clone();
    asym[3 * n + 2] += 1e-3;
    // the mean equatorial moment is M[α][α] = A; ±1.5 A on the diagonal leaves A − 1.5 A < 0
    let a = preset.m[2 * n + 2];
    let mut big = vec![0.0; n * n];
    big[2 * n + 2] = 1.5 * a;
    big[3 * n + 3] = -1.5 * a;
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (with(&[1.0, 0.0, 0.0, 1.0], 2), "linear_rotor.rotor_fixed_mass: rotor_fixed_mass is 2 × 2, M is 4 × 4"),
        (b"%%MatrixMarket matrix coordinate real general\n4 4 1\n3 3 nan\n".to_vec(), "linear_rotor.rotor_fixed_mass: p_M_rot.mtx: line 3: nan is not finite"),
        (with(&asym, n), "linear_rotor.rotor_fixed_mass[3,2]: must equal rotor_fixed_mass[2,3] (symmetric)"),
        (with(&big, n), "linear_rotor.rotor_fixed_mass: M + T(φ) M_rot T(φ)ᵀ is not positive definite at φ = "),
    ];
    for (file, want) in cases {
        bytes.insert("p_M_rot.mtx".into(), file);
        let e = read(&text, &bytes).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}");
        assert!(!e.contains('\n'), "{e}");
    }
    // without the key: no rotor-fixed inertia
    let none = read(&text.replace("rotor_fixed_mass = \"p_M_rot.mtx\"\n", ""), &bytes).unwrap();
    assert!(none.rotor_fixed_mass.is_empty());
    // the shaft builder with a rotor-fixed inertia file (4 elements: 20 DOFs)
    let shaft = "[linear_rotor]\nrotor_fixed_mass = \"s.mtx\"\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.02\ne = 2.1e11\nrho = 7850.0\ncount = 4\n\
                 [[linear_rotor.bearings]]\nnode = 0\nk = 1e6\n[[linear_rotor.bearings]]\nnode = 4\nk = 1e6\n";
    let mut m = vec![0.0; 400];
    m[10 * 20 + 10] = 1e-6;
    m[11 * 20 + 11] = -1e-6;
    bytes.insert("s.mtx".into(), with(&m, 20));
    assert_eq!(read(shaft, &bytes).unwrap().rotor_fixed_mass, m);
    bytes.insert("s.mtx".into(), with(&big, n));
    let e = read(shaft, &bytes).unwrap_err().to_string();
    assert_eq!(e, "linear_rotor.rotor_fixed_mass: rotor_fixed_mass is 4 × 4, M is 20 × 20");
}

/// A flexible shaft (16 elements, 68 DOFs) with two disks: the balancer, the unbalance and an
/// unbalance mass's anisotropy on the disk at node 5 (the boundary), a disk at node 11 (interior)
/// whose equatorial moments differ by `ΔA` (20 % of them, principal axes at 0.6 rad in the rotor).
/// `anisotropic`: a bearing at node 8 (interior) with `k_x = 2 k_y`.
fn shaft(anisotropic: bool) -> LinearRotor {
    let mut b = ShaftBuilder::uniform(16, 0.8, 0.03, 2.1e11, 7850.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 5, mass: 4.0, id: 0.02, ip: 0.035 });
    b.disks.push(Disk { node: 11, mass: 6.0, id: 0.2, ip: 0.3 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 500.0 });
    b.bearings.push(Bearing { node: 16, k: 5e6, c: 500.0 });
    let mut r = b.build().unwrap();
    let n = r.dofs();
    if anisotropic {
        r.k[32 * n + 32] += 2e6;
        r.k[33 * n + 33] += 1e6;
    }
    r.unbalances.push(Unbalance { node: 5, me: 1e-4, phase: 0.3, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 5, radius: 0.07, balls: 2, ball_mass: 0.02, drag: 0.005, offset: 0.0 });
    let mut mr = vec![0.0; n * n];
    let mut put = |node: usize, half: f64, angle: f64| {
        let (s, c) = (2.0 * angle).sin_cos();
        let (a, bb) = (4 * node + 2, 4 * node + 3);
        mr[a * n + a] += half * c;
        mr[bb * n + bb] -= half * c;
        mr[a * n + bb] += half * s;
        mr[bb * n + a] += half * s;
    };
    put(11, 0.5 * 0.04, 0.6);
    put(5, 0.5 * 2e-4, 1.9);
    r.rotor_fixed_mass = mr;
    r
}

/// `J B = B J_r` for the reduction's basis (its columns turn with the frame as the reduced
/// coordinates do, also with a direction-dependent bearing inside, where the modes are a Ritz
/// basis of the isotropic part), and so the projection of the rotor-fixed inertia at any angle
/// is the reduced rotor's turned: `Bᵀ T(φ) M_rot T(φ)ᵀ B = T_r(φ) M_rot,r T_r(φ)ᵀ`. Both to
/// `1e-12` of the largest term (`max|B|² max|M_rot|` times the sums' length would be the
/// round-off's bound; the Gram–Schmidt of the pairs leaves `J B − B J_r` at round-off).
#[test]
fn the_basis_is_closed_under_the_quarter_turn() {
    for anisotropic in [false, true] {
        let r = shaft(anisotropic);
        let red = reduce(&r, 4, &[]).unwrap();
        let (n, m) = red.dofs;
        let b = &red.basis;
        let bmax = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let turn = |i: usize| if i.is_multiple_of(2) { (i + 1, 1.0) } else { (i - 1, -1.0) };
        // J e_k = s e_p, so (J B)[p][j] = s B[k][j]; J_r e_j = t e_q, so (B J_r)[p][j] = t B[p][q]
        let mut worst: f64 = 0.0;
        for k in 0..n {
            let (p, s) = turn(k);
            for j in 0..m {
                let (q, t) = turn(j);
                worst = worst.max((s * b[k * m + j] - t * b[p * m + q]).abs());
            }
        }
        assert!(worst <= 1e-12 * bmax, "anisotropic {anisotropic}: J B − B J_r = {worst:e} (max |B| {bmax:e})");
        let mmax = r.rotor_fixed_mass.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for phi in [0.3, 1.1, 2.0] {
            let full = r.rotor_fixed_in(phi);
            let got = red.rotor.rotor_fixed_in(phi);
            for i in 0..m {
                for j in 0..m {
                    let want: f64 = (0..n).map(|k| b[k * m + i] * (0..n).map(|l| full[k * n + l] * b[l * m + j]).sum::<f64>()).sum();
                    let d = (want - got[i * m + j]).abs();
                    assert!(d <= 1e-12 * bmax * bmax * mmax, "anisotropic {anisotropic}, φ {phi}: [{i},{j}] {want:e} vs {:e}", got[i * m + j]);
                }
            }
        }
        eprintln!("anisotropic {anisotropic}: {n} → {m} DOFs, J B − B J_r {worst:.1e} (max |B| {bmax:.2e})");
    }
}

/// The reduction with the rotor-fixed inertia on the shaft of [`shaft`]: every mode kept (the
/// basis square, so the reduced rotor is the full one in other coordinates) gives the full
/// model's balanced-state eigenvalues, balls included, to `1e-10` of the largest `|λ|` (both are
/// eigenvalues of well-separated, damped spectra of matrices equal up to an exact change of
/// coordinates; the rounding of the projection is ~1e-15 relative); fewer pairs converge to them.
/// Measured (worst distance of the full model's eigenvalues below `3 ω1` to the nearest reduced
/// one, over 0.7 ω1 and 1.6 ω1, relative to ω1; 16 interior nodes, so 32 pairs are every mode):
///
/// ```text
/// pairs  DOFs   worst / ω1
///  2      8     3.9e-3
///  4     12     4.3e-4
///  8     20     3.4e-5
/// 16     36     1.7e-6
/// 32     68     every eigenvalue: 3.9e-15 of |λ|max (5.7e5 rad/s)
/// ```
///
/// Leaving the rotor-fixed inertia out moves those eigenvalues by 2.4e-3 ω1, so a reduction that
/// lost or misplaced it would fail (at 16 pairs by 1000 times its error).
#[test]
fn reduction_keeps_the_rotor_fixed_inertia() {
    let r = shaft(false);
    let w1 = r.natural_frequencies(&[], true).unwrap()[0];
    let speeds = [0.7 * w1, 1.6 * w1];
    let full: Vec<Vec<Complex64>> = speeds.iter().map(|w| balanced_eigenvalues(&r, *w, None)).collect();
    // every mode: 16 interior nodes, 32 pairs
    let all = reduce(&r, 32, &[]).unwrap();
    assert_eq!(all.dofs, (68, 68));
    assert!(all.first_neglected.is_none());
    assert!(!all.rotor.rotor_fixed_mass.is_empty());
    for (w, f) in speeds.iter().zip(&full) {
        let e = balanced_eigenvalues(&all.rotor, *w, None);
        let big = f.iter().fold(0.0f64, |s, z| s.max(z.norm()));
        let d = match_distance(f, &e);
        eprintln!("every mode, Ω {:.2} ω1: {} eigenvalues differ by {:.1e} of |λ|max {big:.2e}", w / w1, f.len(), d / big);
        assert!(d <= 1e-10 * big, "Ω {w}: {d:e} of {big:e}");
    }
    let mut last = f64::INFINITY;
    for pairs in [2, 4, 8, 16] {
        let red = reduce(&r, pairs, &[]).unwrap();
        let mut worst: f64 = 0.0;
        for (w, f) in speeds.iter().zip(&full) {
            let e = balanced_eigenvalues(&red.rotor, *w, None);
            for z in f.iter().filter(|z| z.norm() < 3.0 * w1) {
                let d = e.iter().map(|y| (y - z).norm()).fold(f64::INFINITY, f64::min);
                worst = worst.max(d / w1);
            }
        }
        eprintln!("{pairs} pairs ({} DOFs): worst {worst:.1e} ω1", red.dofs.1);
        assert!(worst < last, "{pairs} pairs: {worst:e} after {last:e}");
        last = worst;
    }
    assert!(last < 5e-6, "16 pairs: {last:e}");
    // what the rotor-fixed inertia moves: far more than the reduction's error, so a reduction
    // that lost or misplaced it fails above
    let mut plain = r.clone();
    plain.rotor_fixed_mass.clear();
    let mut effect: f64 = 0.0;
    for (w, f) in speeds.iter().zip(&full) {
        let e = balanced_eigenvalues(&plain, *w, None);
        for z in f.iter().filter(|z| z.norm() < 3.0 * w1) {
            effect = effect.max(e.iter().map(|y| (y - z).norm()).fold(f64::INFINITY, f64::min) / w1);
        }
    }
    eprintln!("without the rotor-fixed inertia: {effect:.1e} ω1");
    assert!(effect > 100.0 * last, "{effect:e}");
}

/// Positive definiteness of `M + T(φ) M_rot T(φ)ᵀ` at every angle, decided where `M` does not
/// commute with the quarter turn (a mass that differs in `x` and `y`, where the spectrum depends
/// on `φ`). One node `(x, y)`, `M = diag(1, 3)`, `M_rot = q [[cos 2γ, sin 2γ], [sin 2γ, −cos 2γ]]`:
/// with `ψ = 2φ + 2γ`, `det = m1 m2 − q² + q (m2 − m1) cos ψ` and the `x` pivot `1 + q cos ψ`, so
/// the matrix is positive definite at every angle iff `3 − q² − 2q > 0`, i.e. `q < 1`. With
/// `2γ = 20°` and `q = 1.2` it fails only for `cos ψ < −0.65` (`φ` from 55° to 105°), not at
/// `φ = 0` or 45°: refused, at the first of the sampled angles `πk/8` inside that band
/// (`φ = 3π/8`, `ψ = 155°`). `q = 0.9` (`det ≥ 0.39`) and `q = 0.999` (`det ≥ 0.004`, decided at
/// the 64 angles) are accepted; `q = 0.9999` (`det ≥ 0.0004`, positive definite, but the `x`
/// pivot's margin `1 − q` is below `1 − cos(π/64)`) is refused as undecided.
#[test]
fn positive_definiteness_at_every_angle_with_a_direction_dependent_mass() {
    let rotor = |q: f64| {
        let mut r = LinearRotor::zeros(1, autobal::linear_rotor::Layout::Translation);
        r.m = vec![1.0, 0.0, 0.0, 3.0];
        r.k = vec![1e3, 0.0, 0.0, 1e3];
        let (s, c) = 20f64.to_radians().sin_cos();
        r.rotor_fixed_mass = vec![q * c, q * s, q * s, -q * c];
        r
    };
    let e = rotor(1.2).validate().unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.rotor_fixed_mass: M + T(φ) M_rot T(φ)ᵀ is not positive definite at φ = 1.1781"), "{e}");
    assert!(rotor(0.9).validate().is_ok());
    assert!(rotor(0.999).validate().is_ok());
    let e = rotor(0.9999).validate().unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.rotor_fixed_mass: M + T(φ) M_rot T(φ)ᵀ is within 0.12 % of singular"), "{e}");
    // the same matrices checked by hand at 3600 angles: the verdicts above are the truth
    for (q, want) in [(1.2, false), (0.9, true), (0.999, true), (0.9999, true)] {
        let r = rotor(q);
        let pd = (0..3600).all(|k| {
            let t = r.rotor_fixed_in(PI * k as f64 / 3600.0);
            let (a, b, d) = (r.m[0] + t[0], r.m[1] + t[1], r.m[3] + t[3]);
            a > 0.0 && a * d - b * b > 0.0
        });
        assert_eq!(pd, want, "q {q}");
    }
}
