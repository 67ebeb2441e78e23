//! The general linear rotor with ball balancers ([`autobal::linear_rotor`]): the Jeffcott preset
//! against the native planar model, the exact Jacobian against differences, the rotating-frame
//! matrices against the formulas stated in the module docs, the two frames against each other
//! by integration, an anisotropic rotor's periodic orbit against its closed form, the shaft
//! builder against beam theory, and the balancer on a flexible shaft over speed.

use autobal::analysis::{speed_scan, stability, stationary, Kind, NewtonOptions, ScanOptions, Stability, VectorField, Verdict};
use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, Direction, Frame, Layout, LinearRotor, LinearRotorField, TimeSystem, Unbalance};
use autobal::ode::{Control, Method, Options, Solver};
use autobal::planar::field::PlanarField;
use autobal::planar::PlanarRotor;
use num_complex::Complex64;
use std::f64::consts::PI;

mod common;
use common::Sys;

/// A small deterministic generator (xorshift64*), uniform in `[a, b)`.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self, a: f64, b: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let u = (self.0.wrapping_mul(0x2545F4914F6CDD1D) >> 11) as f64 / (1u64 << 53) as f64;
        a + (b - a) * u
    }
}

fn all_eigenvalues(st: &Stability) -> Vec<Complex64> {
    st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).collect()
}

/// Largest distance from each of `a` to its nearest unused member of `b` (greedy matching).
fn spectrum_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut used = vec![false; b.len()];
    let mut worst = 0.0f64;
    for x in a {
        let (j, d) = b.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, y)| (j, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
        used[j] = true;
        worst = worst.max(d);
    }
    worst
}

fn random_planar(rng: &mut Rng) -> PlanarRotor {
    let n = rng.uniform(2.0, 5.0) as usize;
    let m1 = rng.uniform(0.5, 5.0);
    let m3 = rng.uniform(0.01, 0.1);
    let r = rng.uniform(0.03, 0.1);
    // the balls can cancel the unbalance: m1 s1 / (n m3 r) in (0.2, 0.8)
    let s1 = rng.uniform(0.2, 0.8) * n as f64 * m3 * r / m1;
    let p = PlanarRotor { m1, m2: rng.uniform(0.0, 1.0), m3, n, s1, s2: 0.0, gamma: 0.0, r, c: 0.0, c_psi: rng.uniform(0.01, 0.5), ..PlanarRotor::paper() };
    let wn = rng.uniform(50.0, 500.0);
    PlanarRotor { k: wn * wn * p.total_mass(), c: rng.uniform(0.02, 0.2) * 2.0 * wn * p.total_mass(), ..p }
}

/// Paper 004's rotor with its race centred, as a linear rotor, equals the native planar model
/// (`PlanarField` at `s2 = 0`): the right-hand sides and exact Jacobians at random states agree
/// to round-off, and the balanced state and its eigenvalues (through the analysis pipeline) to
/// `1e-10` relative, over random parameters and speeds below and above the critical speed. The
/// two codes share no equations (the planar one eliminates the ball accelerations from the
/// d'Alembert equations of each body in rotor axes; this one rotates fixed-axes matrices), so
/// round-off (`1e-16` on each term, amplified by at most the condition of the balanced QR) is
/// the only difference; `1e-10` leaves 1e5 for that amplification.
#[test]
fn jeffcott_preset_equals_the_planar_model() {
    let mut rng = Rng(0x9E3779B97F4A7C15);
    for case in 0..12 {
        let p = random_planar(&mut rng);
        let omega = p.natural_frequency() * rng.uniform(0.4, 3.0);
        let native = PlanarField::new(&p, omega).unwrap();
        let lin = LinearRotorField::new(&LinearRotor::from_planar(&p).unwrap(), omega, Frame::Rotating).unwrap();
        assert_eq!(native.dim(), lin.dim());
        assert_eq!(lin.period(), None);
        let d = lin.dim();
        let scales = native.scales();
        // right-hand side and Jacobian at a random state
        let x: Vec<f64> = scales.iter().enumerate().map(|(i, s)| s * rng.uniform(-1.0, 1.0) * if i % (d / 2) < 2 { 1.0 } else { 3.0 }).collect();
        let (mut fa, mut fb) = (vec![0.0; d], vec![0.0; d]);
        native.rhs(0.0, &x, &mut fa);
        lin.rhs(0.0, &x, &mut fb);
        let (mut ja, mut jb) = (vec![0.0; d * d], vec![0.0; d * d]);
        native.jacobian(0.0, &x, &mut ja);
        lin.jacobian(0.0, &x, &mut jb);
        for i in 0..d {
            // scaled by the component's rate scale: terms of f_i are at most |J_i·| s
            let row_scale = (0..d).map(|j| (ja[i * d + j] * scales[j]).abs()).fold(0.0, f64::max).max(scales[i]);
            assert!((fa[i] - fb[i]).abs() <= 1e-12 * row_scale, "case {case}: f[{i}] {} vs {}", fa[i], fb[i]);
            for j in 0..d {
                let tol = 1e-12 * row_scale / scales[j];
                assert!((ja[i * d + j] - jb[i * d + j]).abs() <= tol, "case {case}: J[{i}][{j}] {} vs {}", ja[i * d + j], jb[i * d + j]);
            }
        }
        // the balanced state and its eigenvalues through the pipeline
        let guess = native.semi_balanced_guess().unwrap();
        let sa = stationary(&native, &guess, &NewtonOptions::default()).unwrap();
        let sb = stationary(&lin, &lin.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
        assert_eq!(sa.family_dimension, sb.family_dimension);
        assert_eq!(sb.family_dimension, p.n - 2);
        for i in 0..d {
            // ball angles are defined modulo 2π
            let mut diff = sa.x[i] - sb.x[i];
            if (2..2 + p.n).contains(&i) {
                diff -= (diff / (2.0 * PI)).round() * 2.0 * PI;
            }
            assert!(diff.abs() <= 1e-10 * scales[i], "case {case}: x[{i}] {} vs {}", sa.x[i], sb.x[i]);
        }
        let (sta, stb) = (stability(&native, &sa).unwrap(), stability(&lin, &sb).unwrap());
        let (ea, eb) = (all_eigenvalues(&sta), all_eigenvalues(&stb));
        let dist = spectrum_distance(&ea, &eb);
        assert!(dist <= 1e-10 * sta.rate, "case {case}: eigenvalues differ by {dist:e} (rate {})", sta.rate);
        assert_eq!(sta.verdict, stb.verdict, "case {case}");
    }
}

/// The stable speed range of the Jeffcott rotor with two balls, by the speed scan on each model:
/// the same ends (bisected to `1e-9` relative; `1e-8` allows both bisections' last intervals).
#[test]
fn jeffcott_stable_range_equals_the_planar_models() {
    let p = PlanarRotor { s2: 0.0, ..PlanarRotor::paper() };
    let lin = LinearRotor::from_planar(&p).unwrap();
    let speeds: Vec<f64> = (0..60).map(|i| 100.0 + 10.0 * i as f64).collect();
    let a = speed_scan(|w| PlanarField::new(&p, w), |f, _| f.semi_balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
    let b = speed_scan(|w| LinearRotorField::new(&lin, w, Frame::Rotating), |f, _| f.balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
    assert_eq!(a.stable_ranges.len(), b.stable_ranges.len());
    assert!(!a.stable_ranges.is_empty());
    for (ra, rb) in a.stable_ranges.iter().zip(&b.stable_ranges) {
        assert!((ra.from - rb.from).abs() <= 1e-8 * ra.from, "{} vs {}", ra.from, rb.from);
        assert!((ra.to - rb.to).abs() <= 1e-8 * ra.to);
    }
    // unstable below the critical speed sqrt(k/m0) = 288 rad/s, as for the Jeffcott rotor
    assert!(a.stable_ranges[0].from > 288.0);
}

/// A shaft on anisotropic bearings with a disk, an offset unbalance and a balancer: the exact
/// (forward-mode) Jacobian against central differences, in both frames, at a random state and
/// time. Central differences with step `h = 1e-6` of each component's scale have truncation
/// error `O(h²)` and round-off `O(ε/h) ≈ 1e-10` relative: `1e-6` of the row's size is far above
/// both and far below any error in a term.
#[test]
fn exact_jacobian_matches_differences() {
    let mut b = ShaftBuilder::uniform(4, 0.8, 0.02, 2.1e11, 7800.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 2, mass: 3.0, id: 0.01, ip: 0.02 });
    b.bearings.push(Bearing { node: 0, k: 1e6, c: 100.0 });
    b.bearings.push(Bearing { node: 4, k: 1e6, c: 100.0 });
    let mut r = b.build().unwrap();
    let n = r.dofs();
    r.k[n + 1] += 5e5; // node 0 y stiffer: anisotropic
    r.unbalances.push(Unbalance { node: 2, me: 1e-4, phase: 0.3, offset: 0.02 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.08, balls: 3, ball_mass: 0.02, drag: 0.01, offset: 0.03 });
    assert!(!r.is_isotropic());
    let mut rng = Rng(12345);
    for frame in [Frame::Rotating, Frame::Fixed] {
        let f = LinearRotorField::new(&r, 300.0, frame).unwrap();
        let d = f.dim();
        let s = f.scales();
        let x: Vec<f64> = s.iter().map(|v| v * rng.uniform(-1.0, 1.0)).collect();
        let t = 0.0037;
        let mut jac = vec![0.0; d * d];
        f.jacobian(t, &x, &mut jac);
        let (mut fp, mut fm) = (vec![0.0; d], vec![0.0; d]);
        let mut num = vec![0.0; d * d];
        for j in 0..d {
            let h = 1e-6 * s[j];
            let mut xp = x.clone();
            xp[j] += h;
            f.rhs(t, &xp, &mut fp);
            xp[j] -= 2.0 * h;
            f.rhs(t, &xp, &mut fm);
            for i in 0..d {
                num[i * d + j] = (fp[i] - fm[i]) / (2.0 * h);
            }
        }
        for i in 0..d {
            let row = (0..d).map(|j| (num[i * d + j] * s[j]).abs()).fold(0.0, f64::max);
            for j in 0..d {
                assert!((jac[i * d + j] - num[i * d + j]).abs() * s[j] <= 1e-6 * row, "{frame:?}: J[{i}][{j}] {} vs {}", jac[i * d + j], num[i * d + j]);
            }
        }
    }
}

/// The mass matrix `A(ψ)` is symmetric, equals the residual's dependence on the accelerations
/// (the residual is linear in them: `A e_i = R(0) − R(e_i)`), and the residual vanishes at the
/// computed accelerations.
#[test]
fn mass_matrix_and_residual_are_consistent() {
    let mut r = ShaftBuilder::uniform(3, 0.6, 0.02, 2.1e11, 7800.0).build().unwrap();
    r.unbalances.push(Unbalance { node: 1, me: 1e-4, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 1, radius: 0.05, balls: 2, ball_mass: 0.03, drag: 0.02, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 3, radius: 0.04, balls: 3, ball_mass: 0.01, drag: 0.02, offset: -0.02 });
    let f = LinearRotorField::new(&r, 200.0, Frame::Fixed).unwrap();
    let nc = f.coords();
    let mut rng = Rng(7);
    let x: Vec<f64> = f.scales().iter().map(|v| v * rng.uniform(-1.0, 1.0)).collect();
    let t = 0.01;
    let a = f.mass(t, &x);
    let r0 = f.residuals(t, &x, &vec![0.0; nc]);
    // the differences R(0) − R(e_i) cancel terms of the size of R(0): round-off ε |R(0)|
    let big = a.iter().chain(&r0).fold(0.0f64, |s, v| s.max(v.abs()));
    for i in 0..nc {
        let mut e = vec![0.0; nc];
        e[i] = 1.0;
        let ri = f.residuals(t, &x, &e);
        for k in 0..nc {
            assert!((a[k * nc + i] - a[i * nc + k]).abs() <= 1e-15 * big);
            assert!((r0[k] - ri[k] - a[k * nc + i]).abs() <= 1e-12 * big, "A[{k}][{i}]");
        }
    }
    let acc = f.accelerations(t, &x).unwrap();
    let res = f.residuals(t, &x, &acc);
    let size = r0.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    assert!(res.iter().all(|v| v.abs() <= 1e-10 * size));
}

/// For an isotropic structure without balls the field in turning axes is the linear system of the
/// module docs: `M p̈ + (C + ΩG + 2Ω M J) ṗ + (K − Ω² M + Ω C J + Ω² G J) p = f_r`. Its Jacobian
/// built from those formulas equals the field's (which rotates the fixed-axes kinematics
/// instead), to round-off.
#[test]
fn rotating_frame_matrices_as_stated() {
    let mut b = ShaftBuilder::uniform(3, 0.6, 0.03, 2.1e11, 7800.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 1, mass: 2.0, id: 0.02, ip: 0.04 });
    b.bearings.push(Bearing { node: 0, k: 2e6, c: 300.0 });
    b.bearings.push(Bearing { node: 3, k: 3e6, c: 200.0 });
    let r = b.build().unwrap();
    assert!(r.is_isotropic());
    let n = r.dofs();
    let w = 400.0;
    let f = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
    assert_eq!(f.period(), None);
    let mut jac = vec![0.0; 4 * n * n];
    f.jacobian(0.0, &vec![0.0; 2 * n], &mut jac);
    // J (block-diagonal [[0, −1], [1, 0]]) applied on the right: (X J)[i][j]
    let xj = |x: &[f64], i: usize, j: usize| if j.is_multiple_of(2) { x[i * n + j + 1] } else { -x[i * n + j - 1] };
    let mut kr = vec![0.0; n * n];
    let mut cr = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            kr[i * n + j] = r.k[i * n + j] - w * w * r.m[i * n + j] + w * xj(&r.c, i, j) + w * w * xj(&r.g, i, j);
            cr[i * n + j] = r.c[i * n + j] + w * r.g[i * n + j] + 2.0 * w * xj(&r.m, i, j);
        }
    }
    // M X = −[K_r | C_r] column by column, compared with the field's lower blocks times M
    for i in 0..n {
        for j in 0..2 * n {
            let mx: f64 = (0..n).map(|k| r.m[i * n + k] * jac[(n + k) * 2 * n + j]).sum();
            let want = if j < n { -kr[i * n + j] } else { -cr[i * n + j - n] };
            let size = kr[i * n..(i + 1) * n].iter().chain(&cr[i * n..(i + 1) * n]).fold(0.0f64, |s, v| s.max(v.abs()));
            assert!((mx - want).abs() <= 1e-9 * size, "row {i} col {j}: {mx} vs {want}");
        }
    }
}

/// Integrating the fixed-axes equations from a state and the turning-axes equations from the
/// same state seen from the rotor gives the same motion (rotated back), to the integration
/// tolerance: the two frames are one model. Four balls in two planes, anisotropic bearings.
#[test]
fn fixed_and_rotating_frames_agree_in_time() {
    let mut r = LinearRotor::zeros(2, Layout::Translation);
    let n = r.dofs();
    for (i, (m, k)) in [(1.0, 4e4), (1.2, 5e4), (0.8, 3e4), (1.1, 6e4)].iter().enumerate() {
        r.m[i * n + i] = *m;
        r.k[i * n + i] = *k;
        r.c[i * n + i] = 10.0;
    }
    r.k[2] = -1e4; // x0–x1 coupling
    r.k[2 * n] = -1e4;
    r.unbalances.push(Unbalance { node: 0, me: 2e-3, phase: 1.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 0, radius: 0.05, balls: 2, ball_mass: 0.05, drag: 0.02, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 1, radius: 0.04, balls: 2, ball_mass: 0.03, drag: 0.03, offset: 0.0 });
    let w = 250.0;
    let rot = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
    let fix = LinearRotorField::new(&r, w, Frame::Fixed).unwrap();
    assert_eq!(rot.period(), Some(PI / w));
    assert_eq!(fix.period(), Some(2.0 * PI / w));
    let mut rng = Rng(99);
    let x0: Vec<f64> = rot.scales().iter().map(|v| v * rng.uniform(-1.0, 1.0)).collect();
    let t_end = 3.0 * 2.0 * PI / w;
    let integrate = |f: &LinearRotorField, y: &mut Vec<f64>| {
        let opts = Options::new(1e-11, 1e-13).method(Method::Dop853);
        let sys = Sys(f);
        let mut s = Solver::new(&sys, opts).unwrap();
        assert!(s.integrate(0.0, y, t_end, |_| Control::Continue).status.is_completed());
    };
    let mut yr = x0.clone();
    integrate(&rot, &mut yr);
    let mut yf = rot.rotating_to_fixed(0.0, &x0);
    integrate(&fix, &mut yf);
    let back = rot.rotating_to_fixed(t_end, &yr);
    let s = rot.scales();
    for i in 0..yf.len() {
        // 1e-11 relative integration error over 3 revolutions, times a growth of O(10)
        assert!((back[i] - yf[i]).abs() <= 1e-8 * s[i], "{}: {} vs {}", rot.component_name(i), back[i], yf[i]);
    }
}

/// A Jeffcott rotor on anisotropic supports without balls: in turning axes its field is periodic
/// with `π/Ω`, and the periodic orbit the pipeline finds by shooting is the closed-form unbalance
/// response `x = Re(X e^{iΩt})`, `X = m e Ω²/(k_x − mΩ² + i cΩ)`, `y = Re(−i m e Ω² e^{iΩt}/(k_y − mΩ² + i cΩ))`
/// seen from the rotor at `t = 0` (`p = q`, `ṗ = q̇ − Ω J q`), to the shooting's `1e-10`.
#[test]
fn anisotropic_supports_give_the_closed_form_orbit() {
    let (m, kx, ky, c, me, w) = (2.0, 8e4, 1.2e5, 30.0, 1e-3, 230.0);
    let mut r = LinearRotor::zeros(1, Layout::Translation);
    r.m = vec![m, 0.0, 0.0, m];
    r.k = vec![kx, 0.0, 0.0, ky];
    r.c = vec![c, 0.0, 0.0, c];
    r.unbalances.push(Unbalance { node: 0, me, phase: 0.0, offset: 0.0 });
    let f = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
    assert_eq!(f.period(), Some(PI / w));
    let s = stationary(&f, &[0.0; 4], &NewtonOptions::default()).unwrap();
    let i = Complex64::i();
    let xa = me * w * w / (kx - m * w * w + i * c * w);
    let ya = -i * me * w * w / (ky - m * w * w + i * c * w);
    let q = [xa.re, ya.re];
    let qd = [(i * w * xa).re, (i * w * ya).re];
    let want = [q[0], q[1], qd[0] + w * q[1], qd[1] - w * q[0]];
    let l = xa.norm().max(ya.norm());
    for k in 0..4 {
        let scale = if k < 2 { l } else { l * w };
        assert!((s.x[k] - want[k]).abs() <= 1e-9 * scale, "x[{k}] {} vs {}", s.x[k], want[k]);
    }
    let st = stability(&f, &s).unwrap();
    assert_eq!(st.kind, Kind::PeriodicOrbit);
    assert_eq!(st.verdict, Verdict::Stable);
}

fn ss_first_frequencies(elements: usize) -> (Vec<f64>, f64) {
    let (l, d, e, rho) = (1.2, 0.04, 2.1e11, 7800.0);
    let r = ShaftBuilder::uniform(elements, l, d, e, rho).build().unwrap();
    let last = elements;
    let fixed = [r.dof(0, Direction::X).unwrap(), r.dof(0, Direction::Y).unwrap(), r.dof(last, Direction::X).unwrap(), r.dof(last, Direction::Y).unwrap()];
    let w = r.natural_frequencies(&fixed, false).unwrap();
    let (a, i) = (PI * d * d / 4.0, PI * d.powi(4) / 64.0);
    (w, (e * i / (rho * a)).sqrt() / (l * l))
}

/// A simply supported uniform Euler–Bernoulli shaft: `ω_k = (kπ/L)² sqrt(EI/(ρA))`, each twice
/// (the `x–z` and `y–z` planes). The consistent-mass element converges as `h⁴`: the first mode's
/// error with 20 elements is below `1e-4` (observed 1.07e-4, 6.75e-6, 4.22e-7 with 5, 10, 20
/// elements: order 3.99 and 4.00) and the observed order is 4 within 0.2.
#[test]
fn simply_supported_shaft_frequencies() {
    let mut errs = vec![];
    for ne in [5, 10, 20] {
        let (w, unit) = ss_first_frequencies(ne);
        // the two planes give equal frequencies
        assert!((w[0] - w[1]).abs() <= 1e-9 * w[0]);
        let e1 = (w[0] / (PI * PI * unit) - 1.0).abs();
        let e2 = (w[2] / (4.0 * PI * PI * unit) - 1.0).abs();
        errs.push(e1);
        if ne == 20 {
            assert!(e1 < 1e-4, "first mode error {e1:e}");
            assert!(e2 < 1e-3, "second mode error {e2:e}");
        }
    }
    for k in 0..2 {
        let order = (errs[k] / errs[k + 1]).log2();
        assert!((order - 4.0).abs() < 0.2, "observed order {order} from errors {errs:?}");
    }
}

/// A free-free uniform beam: four rigid-body modes (two per plane) at zero, then the first elastic
/// frequency `(β1 L)² sqrt(EI/(ρ A L⁴))`, `β1 L = 4.730040745`, twice; to `1e-4` with 20 elements.
#[test]
fn free_free_beam_frequencies() {
    let (l, d, e, rho) = (1.0, 0.05, 7e10, 2700.0);
    let r = ShaftBuilder::uniform(20, l, d, e, rho).build().unwrap();
    let w = r.natural_frequencies(&[], false).unwrap();
    let (a, i) = (PI * d * d / 4.0, PI * d.powi(4) / 64.0);
    let w1 = 4.730040744862704f64.powi(2) * (e * i / (rho * a * l.powi(4))).sqrt();
    for z in &w[..4] {
        assert!(*z < 1e-5 * w1, "rigid-body mode at {z}");
    }
    for k in [4, 5] {
        assert!((w[k] / w1 - 1.0).abs() < 1e-4, "{} vs {w1}", w[k]);
    }
    let w2 = 7.853204624095838f64.powi(2) * (e * i / (rho * a * l.powi(4))).sqrt();
    assert!((w[6] / w2 - 1.0).abs() < 1e-3);
}

/// A flexible shaft with a disk at mid-span carrying a two-ball balancer and the unbalance: the
/// balanced state (node at rest on the axis in turning axes) over speed by the pipeline's speed
/// scan. As for the Jeffcott rotor, it is unstable below the first critical speed (the first
/// bending frequency of the shaft with the balls' mass, `ω1`) and becomes stable a little above
/// it.
#[test]
fn balancer_on_a_flexible_shaft_over_speed() {
    let mut b = ShaftBuilder::uniform(6, 0.9, 0.025, 2.1e11, 7800.0);
    b.disks.push(Disk { node: 3, mass: 6.0, id: 0.03, ip: 0.06 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 2000.0 });
    b.bearings.push(Bearing { node: 6, k: 5e6, c: 2000.0 });
    b.rotary_inertia = true;
    b.gyroscopic = true;
    let mut r = b.build().unwrap();
    let n = r.dofs();
    // light external damping at the disk (air), so that the mode above the critical speed decays
    for d in [12, 13] {
        r.c[d * n + d] += 20.0;
    }
    r.unbalances.push(Unbalance { node: 3, me: 2e-4, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 3, radius: 0.1, balls: 2, ball_mass: 0.04, drag: 0.05, offset: 0.0 });
    let w1 = r.natural_frequencies(&[], true).unwrap()[0];
    let speeds: Vec<f64> = (0..30).map(|i| w1 * (0.3 + 0.05 * i as f64)).collect();
    let scan = speed_scan(|w| LinearRotorField::new(&r, w, Frame::Rotating), |f, _| f.balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
    for p in &scan.points {
        let st = p.state.as_ref().expect("the balanced state exists at every speed");
        assert!(st.x[12].hypot(st.x[13]) < 1e-12, "node 3 on the axis");
        if p.omega < w1 {
            assert_eq!(p.stability.as_ref().unwrap().verdict, Verdict::Unstable, "Ω = {} below ω1 = {w1}", p.omega);
        }
    }
    let first = scan.stable_ranges.first().expect("a stable range above the critical speed");
    // 1.39 ω1 here; the Jeffcott rotor of the same disk, balls and damping ratio starts at 1.43
    assert!(first.from_is_boundary && first.from > w1 && first.from < 1.6 * w1, "stable from {} (ω1 = {w1})", first.from);
}

/// The flexible shaft in its Jeffcott limit: a nearly massless shaft (density `1e-4` of steel's:
/// shaft mass `5.7e-5` of the disk's) on stiff undamped bearings with the disk, balancer and
/// unbalance at mid-span is the planar rotor with `m1` the disk, `k = 1/(1/k_s + 1/(2 k_b))`
/// (`k_s = 48 EI/L³`: cubic elements give the static deflection under nodal loads exactly) and
/// the disk's share `α m_disk` of the damping `αM`. The stable range's lower end agrees to `2e-4`
/// relative (observed 2.3e-5: the shaft's residual mass shifts it by about its mass ratio).
#[test]
fn flexible_shaft_tends_to_the_jeffcott_rotor() {
    let (l, d, e) = (0.9, 0.025, 2.1e11);
    let mut b = ShaftBuilder::uniform(6, l, d, e, 0.78);
    b.disks.push(Disk { node: 3, mass: 6.0, id: 0.03, ip: 0.06 });
    let kb = 1e8;
    b.bearings.push(Bearing { node: 0, k: kb, c: 0.0 });
    b.bearings.push(Bearing { node: 6, k: kb, c: 0.0 });
    let mut r = b.build().unwrap();
    // mass-proportional damping αM: every undamped mode decays at α/2 (without damping the
    // shaft's and the disk's tilt modes are neutral), and the disk's translation gets α m_disk:
    // the Jeffcott rotor's external damping c = α m_disk (plus α times the shaft's mass, 6e-5 of it)
    let alpha = 20.0 / 6.0;
    for (cv, mv) in r.c.iter_mut().zip(&r.m) {
        *cv += alpha * mv;
    }
    let me = 2e-4;
    r.unbalances.push(Unbalance { node: 3, me, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 3, radius: 0.1, balls: 2, ball_mass: 0.04, drag: 0.05, offset: 0.0 });
    let ks = 48.0 * e * (PI * d.powi(4) / 64.0) / l.powi(3);
    let k = 1.0 / (1.0 / ks + 1.0 / (2.0 * kb));
    let c = alpha * 6.0;
    let p = PlanarRotor { m1: 6.0, m2: 0.0, m3: 0.04, n: 2, s1: me / 6.0, s2: 0.0, gamma: 0.0, r: 0.1, k, c, c_psi: 0.05, ..PlanarRotor::paper() };
    let wn = p.natural_frequency();
    let speeds: Vec<f64> = (0..20).map(|i| wn * (0.5 + 0.1 * i as f64)).collect();
    let a = speed_scan(|w| PlanarField::new(&p, w), |f, _| f.semi_balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
    let s = speed_scan(|w| LinearRotorField::new(&r, w, Frame::Rotating), |f, _| f.balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
    let (fa, fs) = (a.stable_ranges[0].from, s.stable_ranges[0].from);
    assert!((fa - fs).abs() <= 2e-4 * fa, "Jeffcott {fa} vs shaft {fs}");
}

/// Bad input gives a typed error naming the field.
#[test]
fn invalid_models_name_the_field() {
    let good = LinearRotor::jeffcott(1.0, 1e4, 1.0, 1e-4, BalancerPlane { node: 0, radius: 0.05, balls: 2, ball_mass: 0.01, drag: 0.01, offset: 0.0 });
    good.validate().unwrap();
    let field_of = |r: &LinearRotor| r.validate().unwrap_err().field().unwrap().to_string();
    let mut r = good.clone();
    r.m[1] = 0.1;
    assert_eq!(field_of(&r), "linear_rotor.m[1,0]");
    let mut r = good.clone();
    r.m[3] = -1.0;
    assert_eq!(field_of(&r), "linear_rotor.m");
    let mut r = good.clone();
    r.g[1] = 0.1;
    assert_eq!(field_of(&r), "linear_rotor.g[1,0]");
    let mut r = good.clone();
    r.k[2] = f64::NAN;
    assert_eq!(field_of(&r), "linear_rotor.k[1,0]");
    let mut r = good.clone();
    r.k.pop();
    assert_eq!(field_of(&r), "linear_rotor.k");
    let mut r = good.clone();
    r.balancers[0].radius = 0.0;
    assert_eq!(field_of(&r), "linear_rotor.balancers[0].radius");
    let mut r = good.clone();
    r.balancers[0].node = 1;
    assert_eq!(field_of(&r), "linear_rotor.balancers[0].node");
    let mut r = good.clone();
    r.balancers[0].offset = 0.1;
    assert_eq!(field_of(&r), "linear_rotor.balancers[0].offset");
    let mut r = good.clone();
    r.unbalances[0].offset = 0.1;
    assert_eq!(field_of(&r), "linear_rotor.unbalances[0].offset");
    let p = PlanarRotor::paper();
    assert_eq!(LinearRotor::from_planar(&p).unwrap_err().field(), Some("planar.s2"));
    let mut s = ShaftBuilder::uniform(2, 1.0, 0.02, 2e11, 7800.0);
    s.disks.push(Disk { node: 5, mass: 1.0, id: 0.0, ip: 0.0 });
    assert_eq!(s.build().unwrap_err().field(), Some("shaft.disks[0].node"));
    assert!(LinearRotorField::new(&good, f64::NAN, Frame::Rotating).is_err());
}

/// Rigid-body invariants of the shaft element, which fix its sign conventions (`β = dx/dz`,
/// `α = −dy/dz`) independently of the formulas: rigid translations and rigid tilts (`x = z β`,
/// `y = −z α`, cubic shape functions hold them exactly) store no strain energy (`K t = 0`); the
/// kinetic energy of a rigid translation is the shaft's mass `ρ A L`, of a rigid tilt about the
/// left end `ρ A L³/3 + ρ I L` (with rotary inertia); and the gyroscopic coupling of the two rigid
/// tilts is the polar moment `t_αᵀ G t_β = 2 ρ I L` (a rigid body's `I_p`, as for a disk).
#[test]
fn shaft_element_rigid_body_invariants() {
    let (l, d, e, rho) = (0.7, 0.03, 2.1e11, 7800.0);
    let mut b = ShaftBuilder::uniform(5, l, d, e, rho);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    let r = b.build().unwrap();
    let n = r.dofs();
    let el = b.elements[0];
    let (a, i) = (el.area, el.inertia);
    let quad = |m: &[f64], u: &[f64], v: &[f64]| -> f64 { (0..n).map(|p| u[p] * (0..n).map(|q| m[p * n + q] * v[q]).sum::<f64>()).sum() };
    let mut tx = vec![0.0; n];
    let mut talpha = vec![0.0; n];
    let mut tbeta = vec![0.0; n];
    for node in 0..r.nodes {
        let z = l * node as f64 / 5.0;
        tx[r.dof(node, Direction::X).unwrap()] = 1.0;
        tbeta[r.dof(node, Direction::X).unwrap()] = z;
        tbeta[r.dof(node, Direction::Beta).unwrap()] = 1.0;
        talpha[r.dof(node, Direction::Y).unwrap()] = -z;
        talpha[r.dof(node, Direction::Alpha).unwrap()] = 1.0;
    }
    let kscale = r.k.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for t in [&tx, &talpha, &tbeta] {
        for p in 0..n {
            let kt: f64 = (0..n).map(|q| r.k[p * n + q] * t[q]).sum();
            assert!(kt.abs() <= 1e-12 * kscale * l, "K t ≠ 0 at {}", r.dof_name(p));
        }
    }
    let mass = rho * a * l;
    assert!((quad(&r.m, &tx, &tx) / mass - 1.0).abs() < 1e-13);
    let tilt = rho * a * l.powi(3) / 3.0 + rho * i * l;
    assert!((quad(&r.m, &talpha, &talpha) / tilt - 1.0).abs() < 1e-13);
    assert!((quad(&r.m, &tbeta, &tbeta) / tilt - 1.0).abs() < 1e-13);
    let ip = 2.0 * rho * i * l;
    assert!((quad(&r.g, &talpha, &tbeta) / ip - 1.0).abs() < 1e-12);
    assert!((quad(&r.g, &tbeta, &talpha) / ip + 1.0).abs() < 1e-12);
}

/// The balanced state seen from fixed axes is a periodic orbit of period `2π/Ω`: shooting on the
/// fixed-axes field finds the turning-axes equilibrium rotated (`q = p`, `q̇ = Ω J p` at `t = 0`),
/// and its Floquet multipliers are `exp(λ T)` of the equilibrium's eigenvalues `λ` (the frame's
/// `± iΩ` shifts change `λ T` by `2πi`). Tolerances: the shooting's `1e-10` on the state and the
/// multipliers' accuracy `~1e-10` from the `1e-12` integration (module docs of `analysis`), so `1e-8`.
#[test]
fn fixed_axes_orbit_is_the_rotating_equilibrium() {
    let p = PlanarRotor { s2: 0.0, n: 3, ..PlanarRotor::paper() };
    let r = LinearRotor::from_planar(&p).unwrap();
    let w = 400.0;
    let rot = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
    let fix = LinearRotorField::new(&r, w, Frame::Fixed).unwrap();
    let se = stationary(&rot, &rot.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    let so = stationary(&fix, &fix.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    assert_eq!(so.period, Some(2.0 * PI / w));
    assert_eq!(so.family_dimension, 1);
    let want = rot.rotating_to_fixed(0.0, &se.x);
    let s = fix.scales();
    for k in 0..want.len() {
        assert!((so.x[k] - want[k]).abs() <= 1e-8 * s[k], "{}: {} vs {}", fix.component_name(k), so.x[k], want[k]);
    }
    let (ste, sto) = (stability(&rot, &se).unwrap(), stability(&fix, &so).unwrap());
    assert_eq!(sto.kind, Kind::PeriodicOrbit);
    assert_eq!(ste.verdict, sto.verdict);
    let t = 2.0 * PI / w;
    let mu: Vec<Complex64> = all_eigenvalues(&ste).iter().map(|l| (l * t).exp()).collect();
    let dist = spectrum_distance(&mu, &all_eigenvalues(&sto));
    assert!(dist <= 1e-8, "multipliers differ by {dist:e}");
}

/// Four evenly spread balls resting on the race act on the structure as a rigid ring, i.e. as a
/// ROSS disk of mass `4 m_b`, diametral moment `I_d = 4 m_b R²/2` and polar moment `I_p = 4 m_b R²`
/// at the race centre (offset `z` from the node): at rest in fixed axes, the structure block of
/// the mass matrix is `M + Pᵀ D P` (`P` the node's DOFs to the race centre's `x + zβ, y − zα, α,
/// β`, `D = diag(m, m, I_d, I_d)`), the residual's derivative by the structure's rates is
/// `−(C + Ω (G + G_ring))` with `G_ring[α][β] = I_p = −G_ring[β][α]`, and by its displacements
/// `−K`. The residual is quadratic in the rates, so central differences with a unit step are
/// exact up to round-off (`1e-12` of the matrices).
#[test]
fn evenly_spread_balls_act_as_a_ring() {
    let mut b = ShaftBuilder::uniform(4, 0.8, 0.03, 2.1e11, 7800.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.bearings.push(Bearing { node: 0, k: 1e6, c: 150.0 });
    b.bearings.push(Bearing { node: 4, k: 2e6, c: 150.0 });
    let mut r = b.build().unwrap();
    let (mb, rr, z, nb) = (0.05, 0.09, 0.04, 4);
    r.balancers.push(BalancerPlane { node: 2, radius: rr, balls: nb, ball_mass: mb, drag: 0.1, offset: z });
    let n = r.dofs();
    let w = 350.0;
    let f = LinearRotorField::new(&r, w, Frame::Fixed).unwrap();
    let nc = f.coords();
    let mut x = vec![0.0; 2 * nc];
    for j in 0..nb {
        x[n + j] = 0.3 + 2.0 * PI * j as f64 / nb as f64;
    }
    let (ix, iy, ia, ib) = (8, 9, 10, 11);
    let (m, id, ip) = (nb as f64 * mb, nb as f64 * mb * rr * rr / 2.0, nb as f64 * mb * rr * rr);
    // P: rows x + zβ, y − zα, α, β of the node's (x, y, α, β)
    let p = [[1.0, 0.0, 0.0, z], [0.0, 1.0, -z, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];
    let d = [m, m, id, id];
    let dofs = [ix, iy, ia, ib];
    let mut want_m = r.m.clone();
    for a in 0..4 {
        for c in 0..4 {
            want_m[dofs[a] * n + dofs[c]] += (0..4).map(|k| p[k][a] * d[k] * p[k][c]).sum::<f64>();
        }
    }
    let mut g = r.g.clone();
    g[ia * n + ib] += ip;
    g[ib * n + ia] -= ip;
    let a = f.mass(0.0, &x);
    let scale_m = want_m.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for i in 0..n {
        for j in 0..n {
            assert!((a[i * nc + j] - want_m[i * n + j]).abs() <= 1e-12 * scale_m, "A[{}][{}]", r.dof_name(i), r.dof_name(j));
        }
    }
    let zero = vec![0.0; nc];
    let scale_d = r.c.iter().zip(&g).map(|(c, g)| (c + w * g).abs()).fold(0.0, f64::max);
    let scale_k = r.k.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for j in 0..n {
        for (offset, scale) in [(nc, scale_d), (0, scale_k)] {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[offset + j] += 1e-3_f64.max(if offset == 0 { 0.0 } else { 1.0 });
            xm[offset + j] -= 1e-3_f64.max(if offset == 0 { 0.0 } else { 1.0 });
            let h = xp[offset + j] - x[offset + j];
            let (rp, rm) = (f.residuals(0.0, &xp, &zero), f.residuals(0.0, &xm, &zero));
            for i in 0..n {
                let got = (rp[i] - rm[i]) / (2.0 * h);
                let want = if offset == nc { -(r.c[i * n + j] + w * g[i * n + j]) } else { -r.k[i * n + j] };
                assert!(
                    (got - want).abs() <= 1e-9 * scale,
                    "∂R[{}]/∂{}{}: {got} vs {want}",
                    r.dof_name(i),
                    if offset == nc { "rate of " } else { "" },
                    r.dof_name(j)
                );
            }
        }
    }
}

/// Without damping or drag, in axes turning with an isotropic rotor, the equations are those of
/// an autonomous Lagrangian, so the Jacobi integral `h = Σ q̇ ∂L/∂q̇ − L = L2 − L0` is conserved.
/// `L` is written here independently of the module's residual, from the model's kinetic energy:
/// `½ wᵀ M w + (Ω/2) wᵀ G p − ½ pᵀ K p + f_r·p + Σ_j [½ m |w_c + R θ̇ e⊥|² + ½ m R² σ² + ½ m R² θ̇ (ω × τ)]`
/// (`w = ṗ + Ω J p`, `w_c` the race centre's velocity, `τ = (α, β)`, `ω = τ̇` absolute,
/// `σ = ω_α sin θ − ω_β cos θ`, `θ̇ = Ω + ψ̇`). A wrong sign or factor in any inertia term of the
/// equations makes `h` drift by the power of that term; the integration at `rtol = 1e-12` over two
/// revolutions keeps `h` to about `1e-10` of its terms; the bound is `1e-8`.
#[test]
fn jacobi_integral_is_conserved_in_turning_axes() {
    let mut b = ShaftBuilder::uniform(3, 0.6, 0.03, 2.1e11, 7800.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 1, mass: 2.0, id: 0.01, ip: 0.02 });
    b.bearings.push(Bearing { node: 0, k: 1e6, c: 0.0 });
    b.bearings.push(Bearing { node: 3, k: 1e6, c: 0.0 });
    let mut r = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 1, me: 1e-4, phase: 0.5, offset: 0.01 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.07, balls: 3, ball_mass: 0.04, drag: 0.0, offset: 0.03 });
    let n = r.dofs();
    let w = 300.0;
    let f = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
    let nc = f.coords();
    let fr = f.forcing(0.0);
    let lagrangian = |x: &[f64]| -> f64 {
        let (p, pd) = (&x[..n], &x[nc..nc + n]);
        let wv: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { pd[i] - w * p[i + 1] } else { pd[i] + w * p[i - 1] }).collect();
        let quad = |a: &[f64], u: &[f64], v: &[f64]| -> f64 { (0..n).map(|i| u[i] * (0..n).map(|j| a[i * n + j] * v[j]).sum::<f64>()).sum() };
        let mut l = 0.5 * quad(&r.m, &wv, &wv) + 0.5 * w * quad(&r.g, &wv, p) - 0.5 * quad(&r.k, p, p) + (0..n).map(|i| fr[i] * p[i]).sum::<f64>();
        let bal = r.balancers[0];
        let (ix, iy, ia, ib) = (8, 9, 10, 11);
        let (mb, rr, z) = (bal.ball_mass, bal.radius, bal.offset);
        for j in 0..bal.balls {
            let (s, c) = x[n + j].sin_cos();
            let th = w + x[nc + n + j];
            let (om_a, om_b) = (wv[ia], wv[ib]);
            let (vx, vy) = (wv[ix] + z * om_b - rr * th * s, wv[iy] - z * om_a + rr * th * c);
            let sigma = om_a * s - om_b * c;
            l += 0.5 * mb * (vx * vx + vy * vy) + 0.5 * mb * rr * rr * sigma * sigma + 0.5 * mb * rr * rr * th * (om_a * p[ib] - om_b * p[ia]);
        }
        l
    };
    let h = |x: &[f64]| -> (f64, f64) {
        let mut xm = x.to_vec();
        let mut x0 = x.to_vec();
        for i in nc..2 * nc {
            xm[i] = -x[i];
            x0[i] = 0.0;
        }
        let (lp, lm, l0) = (lagrangian(x), lagrangian(&xm), lagrangian(&x0));
        ((lp + lm) / 2.0 - 2.0 * l0, lp.abs() + l0.abs())
    };
    let mut rng = Rng(2024);
    let s = f.scales();
    let mut y: Vec<f64> = s.iter().map(|v| v * rng.uniform(-1.0, 1.0)).collect();
    let (h0, size) = h(&y);
    let opts = Options::new(1e-12, 1e-12).method(Method::Dop853).atol_per_component(s.iter().map(|v| 1e-12 * v).collect());
    let sys = Sys(&f);
    let mut solver = Solver::new(&sys, opts).unwrap();
    let t_end = 2.0 * 2.0 * PI / w;
    assert!(solver.integrate(0.0, &mut y, t_end, |_| Control::Continue).status.is_completed());
    let (h1, _) = h(&y);
    assert!((h1 - h0).abs() <= 1e-8 * size, "h drifted from {h0} to {h1} (size {size})");
}

/// A run at constant speed in fixed axes with the implicit RODAS (exact Jacobian through
/// [`TimeSystem`]) equals the explicit DOP853 run to their tolerances: a flexible shaft with a
/// balancer, from rest with the balls bunched, over five revolutions. `rtol = 1e-8` on both; the
/// difference bound `1e-5` of the scales allows the two methods' global errors (each ~ `rtol`
/// times the growth over 5 revolutions) with room.
#[test]
fn time_simulation_with_the_exact_jacobian() {
    let mut b = ShaftBuilder::uniform(4, 0.8, 0.025, 2.1e11, 7800.0);
    b.disks.push(Disk { node: 2, mass: 4.0, id: 0.02, ip: 0.04 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 500.0 });
    b.bearings.push(Bearing { node: 4, k: 5e6, c: 500.0 });
    let mut r = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 2, me: 2e-4, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.08, balls: 2, ball_mass: 0.04, drag: 0.05, offset: 0.01 });
    let w = 300.0;
    let f = LinearRotorField::new(&r, w, Frame::Fixed).unwrap();
    let nc = f.coords();
    let mut y0 = vec![0.0; 2 * nc];
    y0[r.dofs()] = 0.1;
    y0[r.dofs() + 1] = -0.1;
    let t_end = 5.0 * 2.0 * PI / w;
    let s = f.scales();
    let run = |m: Method| {
        let opts = Options::new(1e-8, 1e-8).method(m).atol_per_component(s.iter().map(|v| 1e-8 * v).collect());
        let sys = TimeSystem(&f);
        let mut solver = Solver::new(&sys, opts).unwrap();
        let mut y = y0.clone();
        let out = solver.integrate(0.0, &mut y, t_end, |_| Control::Continue);
        assert!(out.status.is_completed(), "{m:?}: {out}");
        y
    };
    let (ya, yb) = (run(Method::Dop853), run(Method::Rodas));
    for i in 0..ya.len() {
        assert!((ya[i] - yb[i]).abs() <= 1e-5 * s[i], "{}: {} vs {}", f.component_name(i), ya[i], yb[i]);
    }
}

/// Three balls on a flexible shaft whose unbalance sits in the balancer's plane, offset from the
/// node: the balanced state (structure at rest on the axis, balls cancelling the unbalance) is a
/// family of dimension `n − 2 = 1`, found exactly at the closed-form start, with one structural
/// zero eigenvalue; with the unbalance in another plane the node cannot rest on the axis and
/// there is no family.
#[test]
fn three_balls_on_a_shaft_form_a_family() {
    let mut b = ShaftBuilder::uniform(4, 0.8, 0.025, 2.1e11, 7800.0);
    b.disks.push(Disk { node: 2, mass: 4.0, id: 0.02, ip: 0.04 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 500.0 });
    b.bearings.push(Bearing { node: 4, k: 5e6, c: 500.0 });
    let mut r = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 2, me: 2e-4, phase: 0.7, offset: 0.02 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.08, balls: 3, ball_mass: 0.02, drag: 0.05, offset: 0.02 });
    let f = LinearRotorField::new(&r, 400.0, Frame::Rotating).unwrap();
    let guess = f.balanced_guess().unwrap();
    // forces cancel to round-off (1e-16 of m e Ω² = 32 N): displacements of order 1e-20 m
    assert!(guess[..r.dofs()].iter().all(|v| v.abs() < 1e-15));
    let s = stationary(&f, &guess, &NewtonOptions::default()).unwrap();
    assert_eq!(s.family_dimension, 1);
    assert!(s.x[..r.dofs()].iter().all(|v| v.abs() < 1e-15));
    let st = stability(&f, &s).unwrap();
    assert_eq!(st.structural.len(), 1);
    assert!(st.structural[0].complex().norm() <= 1e-9 * st.rate);
    r.unbalances[0].node = 1;
    let f = LinearRotorField::new(&r, 400.0, Frame::Rotating).unwrap();
    let s = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    assert_eq!(s.family_dimension, 0);
}
