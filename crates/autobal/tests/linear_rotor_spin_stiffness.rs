//! The angular-acceleration stiffness `K_st` of a linear rotor ([`LinearRotor::spin_stiffness`]):
//! the run-up's equations against an independent integration of the FE codes' form
//! `M q̈ + (C + Ω G) q̇ + (K + Ω̇ K_st) q = f` (ROSS's time response), the config key `kst`
//! through `export` and back, the reduction's `Bᵀ K_st B`, and the validation's errors.

use autobal::drive::Drive;
use autobal::linear_rotor::config::{export, linear_rotor};
use autobal::linear_rotor::runup::RunUpSystem;
use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{Direction, LinearRotor, Unbalance};
use autobal::ode::{Control, Method, Options, Solver, System};

/// A shaft (4 Euler–Bernoulli elements, rotary inertia and gyroscopic terms) with a disk of
/// polar moment 0.2 kg m² at node 2, bearings at the ends, an unbalance on the disk with an
/// offset (so that it tilts the disk), no balls.
fn shaft() -> LinearRotor {
    let mut b = ShaftBuilder::uniform(4, 0.8, 0.03, 2.1e11, 7800.0);
    b.disks.push(Disk { node: 2, mass: 8.0, id: 0.1, ip: 0.2 });
    b.bearings.push(Bearing { node: 0, k: 2e6, c: 200.0 });
    b.bearings.push(Bearing { node: 4, k: 3e6, c: 200.0 });
    let mut r = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 2, me: 2e-4, phase: 0.3, offset: 0.05 });
    r
}

/// `K_st = ½ G + S`, `S` symmetric on the disk's tilts (another chart, `K_st − K_stᵀ = G`), or
/// ROSS's form for the disk, `K_st[β][α] = I_p` and `½` of the shaft's `G` elsewhere (no
/// Lagrangian: the run-up's equations do not need one).
fn with_kst(ross_like: bool) -> LinearRotor {
    let mut r = shaft();
    let n = r.dofs();
    let mut ks: Vec<f64> = r.g.iter().map(|g| 0.5 * g).collect();
    let (a, b) = (2 * 4 + 2, 2 * 4 + 3);
    if ross_like {
        // the disk's own ½ G block (±½ I_p) replaced by I_p at [β][α]
        ks[a * n + b] -= 0.1;
        ks[b * n + a] += 0.1 + 0.2;
    } else {
        ks[a * n + b] += 0.2;
        ks[b * n + a] += 0.2;
    }
    r.spin_stiffness = ks;
    r
}

/// The FE codes' equations written out, state `(q, q̇)`: `q̈ = M⁻¹ (f − (C + Ω G) q̇ − (K + Ω̇
/// K_st) q)`, `f` the unbalance's `m e (Ω² − i Ω̇) e^{i(φ + phase)}` at its node with the moments
/// `−z F_y`, `z F_x` of its offset, `Ω = ω0 + b t`, `φ = ω0 t + ½ b t²` (Gaussian elimination on
/// `M` at every call: independent of the library's LU and residual).
struct Fe<'a> {
    r: &'a LinearRotor,
    kst: Vec<f64>,
    w0: f64,
    b: f64,
}

impl System for Fe<'_> {
    fn dim(&self) -> usize {
        2 * self.r.dofs()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let r = self.r;
        let n = r.dofs();
        let (w, wd, phi) = (self.w0 + self.b * t, self.b, self.w0 * t + 0.5 * self.b * t * t);
        let mut f = vec![0.0; n];
        for u in &r.unbalances {
            let (s, c) = (phi + u.phase).sin_cos();
            let (fx, fy) = (u.me * (w * w * c + wd * s), u.me * (w * w * s - wd * c));
            f[4 * u.node] += fx;
            f[4 * u.node + 1] += fy;
            f[4 * u.node + 2] -= u.offset * fy;
            f[4 * u.node + 3] += u.offset * fx;
        }
        for i in 0..n {
            for j in 0..n {
                f[i] -= (r.c[i * n + j] + w * r.g[i * n + j]) * y[n + j] + (r.k[i * n + j] + wd * self.kst[i * n + j]) * y[j];
            }
        }
        // solve M a = f by Gaussian elimination with partial pivoting
        let mut m = r.m.clone();
        for col in 0..n {
            let p = (col..n).max_by(|&a, &b| m[a * n + col].abs().total_cmp(&m[b * n + col].abs())).unwrap();
            for k in 0..n {
                m.swap(col * n + k, p * n + k);
            }
            f.swap(col, p);
            for row in col + 1..n {
                let l = m[row * n + col] / m[col * n + col];
                for k in col..n {
                    m[row * n + k] -= l * m[col * n + k];
                }
                f[row] -= l * f[col];
            }
        }
        for row in (0..n).rev() {
            let mut s = f[row];
            for k in row + 1..n {
                s -= m[row * n + k] * f[k];
            }
            f[row] = s / m[row * n + row];
        }
        dy[..n].copy_from_slice(&y[n..]);
        dy[n..].copy_from_slice(&f);
    }
}

/// The run-up under a prescribed acceleration (`Drive::Acceleration`, 150 → 450 rad/s in 0.1 s,
/// `Ω̇ = 3000` rad/s²) equals the FE codes' equations integrated on their own, for the default
/// `K_st = ½ G`, a Lagrangian chart and ROSS's form of the disk's: the displacements at 20
/// times agree to `1e-9` of their largest value (both DOP853 at `rtol = 1e-11`, so each
/// integration's error is ~1e-10 of it; measured 3e-13 to 6e-13). Each `K_st` must matter: the run with `½ G` differs from
/// the others by more than `1e-4` of the peak (`Ω̇ I_p/κ_tilt` is ~1e-3 here), so the check
/// sees the matrix, not only the rest of the equations.
#[test]
fn run_up_solves_the_fe_codes_equations_with_k_st() {
    let (w0, b, t_end) = (150.0, 3000.0, 0.1);
    let drive = Drive::Acceleration { omega0: w0, b };
    let mut histories = vec![];
    for r in [shaft(), with_kst(false), with_kst(true)] {
        let n = r.dofs();
        let kst = r.spin_stiffness_matrix().into_owned();
        let sys = RunUpSystem::new(&r, &drive).unwrap();
        assert_eq!(sys.dim(), 2 * n);
        let fe = Fe { r: &r, kst, w0, b };
        let o = || Options::new(1e-11, 1e-15).method(Method::Dop853);
        let (mut s1, mut s2) = (Solver::new(&sys, o()).unwrap(), Solver::new(&fe, o()).unwrap());
        let (mut y1, mut y2) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        let mut h = vec![];
        let mut peak = 0.0f64;
        let mut diff = 0.0f64;
        let mut t = 0.0;
        for k in 1..=20 {
            let t1 = t_end * k as f64 / 20.0;
            s1.integrate(t, &mut y1, t1, |_| Control::Continue);
            s2.integrate(t, &mut y2, t1, |_| Control::Continue);
            t = t1;
            for i in 0..n {
                peak = peak.max(y2[i].abs());
                diff = diff.max((y1[i] - y2[i]).abs());
            }
            h.push(y1[..n].to_vec());
        }
        eprintln!("K_st {}: displacements differ by {:.2e} of the peak {peak:.3e}", if r.spin_stiffness.is_empty() { "½ G" } else { "given" }, diff / peak);
        assert!(diff <= 1e-9 * peak, "run-up vs the FE equations: {diff:e} of {peak:e}");
        histories.push((h, peak));
    }
    for other in &histories[1..] {
        let d = histories[0].0.iter().zip(&other.0).flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs())).fold(0.0, f64::max);
        eprintln!("K_st changes the run by {:.2e} of the peak", d / other.1);
        assert!(d > 1e-4 * other.1, "K_st has no effect: {d:e}");
    }
}

/// The config key `kst`: `export` writes `STEM_KST.mtx` and reading it back gives the same rotor
/// (matrices bit for bit); a rotor without `K_st` writes no such file; the shaft builder refuses
/// the key by name; the reduction projects it, `Bᵀ K_st B`, which for `K_st = ½ G` is half the
/// reduced `G` (to round-off of the projection sums, 1e-12 of the largest entry).
#[test]
fn kst_is_read_written_and_reduced() {
    let r = with_kst(true);
    let (text, files) = export(&r, "s");
    assert!(text.contains("kst = \"s_KST.mtx\""), "{text}");
    let root: toml::Table = text.parse().unwrap();
    let back = linear_rotor(&root, &mut |p| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or("missing".into())).unwrap();
    assert_eq!(back.rotor.spin_stiffness, r.spin_stiffness);
    assert_eq!(back.rotor, r);
    let (text, files) = export(&shaft(), "s");
    assert!(!text.contains("kst") && files.len() == 4);
    let bad = "[linear_rotor]\nkst = \"K.mtx\"\n[[linear_rotor.elements]]\nlength = 0.2\ndiameter = 0.02\ne = 2.1e11\nrho = 7800.0\n";
    let e = linear_rotor(&bad.parse().unwrap(), &mut |_| Err("no files".into())).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.kst:"), "{e}");
    let mut half = shaft();
    half.spin_stiffness = half.g.iter().map(|g| 0.5 * g).collect();
    let red = autobal::linear_rotor::reduce::reduce(&half, 2, &[]).unwrap();
    let rr = &red.rotor;
    let scale = rr.g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert_eq!(rr.spin_stiffness.len(), rr.g.len());
    for (k, g) in rr.spin_stiffness.iter().zip(&rr.g) {
        assert!((k - 0.5 * g).abs() <= 1e-12 * scale, "{k} vs {}", 0.5 * g);
    }
    // a chart on the disk's tilts (the spatial preset's Σ[α][β] = ½ at every node): kept every
    // mode, the reduction reproduces it exactly (Bᵀ Σ B, the basis closed under the quarter turn)
    let mut chart = shaft();
    let n = chart.dofs();
    chart.spin_chart = vec![0.0; n * n];
    for node in 0..chart.nodes {
        let (a, b) = (chart.dof(node, Direction::Alpha).unwrap(), chart.dof(node, Direction::Beta).unwrap());
        chart.spin_chart[a * n + b] = 0.5;
        chart.spin_chart[b * n + a] = 0.5;
    }
    let red = autobal::linear_rotor::reduce::reduce(&chart, 2, &[]).unwrap();
    let rc = &red.rotor.spin_chart;
    let rn = red.rotor.dofs();
    assert_eq!(rc.len(), rn * rn);
    assert!(rc.iter().any(|v| v.abs() > 1e-3), "the projected chart is not zero");
    for i in 0..rn {
        for j in 0..rn {
            assert_eq!(rc[i * rn + j], rc[j * rn + i], "symmetric");
        }
    }
    let (text, files) = export(&chart, "s");
    assert!(text.contains("spin_chart = \"s_chart.mtx\""), "{text}");
    let root: toml::Table = text.parse().unwrap();
    let back = linear_rotor(&root, &mut |p| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or("missing".into())).unwrap();
    assert_eq!(back.rotor, chart);
}

/// Validation names the field: a `K_st` of the wrong size or with a NaN, an asymmetric chart.
#[test]
fn validation_names_the_field() {
    let mut r = shaft();
    r.spin_stiffness = vec![0.0; 3];
    assert!(r.validate().unwrap_err().to_string().starts_with("linear_rotor.spin_stiffness:"));
    let n = r.dofs();
    r.spin_stiffness = vec![0.0; n * n];
    r.spin_stiffness[5] = f64::NAN;
    assert!(r.validate().unwrap_err().to_string().starts_with("linear_rotor.spin_stiffness[0,5]"));
    let mut r = shaft();
    r.spin_chart = vec![0.0; n * n];
    r.spin_chart[1] = 1.0;
    assert!(r.validate().unwrap_err().to_string().starts_with("linear_rotor.spin_chart[1,0]"));
}
