//! Linear stability: the eigen-solver against nalgebra and the pencil's determinant, the
//! textbook limits, and the analytic critical speeds.

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use autobal::linalg::eigen::{characteristic_polynomial, complex_det, eigenvalues, routh_hurwitz_stable};
use autobal::spatial::critical_speeds::critical_speeds_at;
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, Mat12, Pencil};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
use autobal::spatial::stability::{campbell, eigenvalues_at, margin, stability_ranges, Group, Whirl};
use num_complex::Complex64;

mod common;
use common::{direct_model as model, Rng};

/// Random physical parameters: `2 ΔĀ ≤ C̄Σ` (triangle inequality of the principal moments).
fn random_model(rng: &mut Rng) -> SpatialModel {
    let c_sigma = rng.range(0.2, 1.6);
    model(
        c_sigma,
        rng.range(0.2, 0.8),
        rng.range(-0.3, 1.4),
        rng.range(-1.0, 1.0),
        rng.range(0.0, 0.2).min(0.5 * c_sigma),
        rng.range(0.0, 0.2),
        rng.range(0.01, 0.5),
        Some((rng.range(0.005, 0.1), rng.range(0.0, 1.0))),
    )
}

fn nalgebra_eigs(a: &Mat12, n: usize) -> Vec<Complex64> {
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| a[i][j]);
    let s = nalgebra::linalg::Schur::try_new(m, 1e-15, 10_000).expect("nalgebra converges");
    s.complex_eigenvalues().iter().map(|z| Complex64::new(z.re, z.im)).collect()
}

/// Largest distance from each of `a` to the nearest unused of `b` (a matching distance).
fn match_dist(a: &[Complex64], b: &[Complex64]) -> f64 {
    let mut used = vec![false; b.len()];
    let mut worst: f64 = 0.0;
    for x in a {
        let (j, d) = b.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, y)| (j, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
        used[j] = true;
        worst = worst.max(d);
    }
    worst
}

#[test]
fn eigenvalues_match_nalgebra_on_state_matrices() {
    let mut rng = Rng(21);
    for _ in 0..300 {
        let m = random_model(&mut rng);
        let w = rng.range(0.05, 5.0);
        for balls in [Balls::Free, Balls::Locked] {
            let p = Pencil::new(&m, w, balls).unwrap();
            let a = p.state_matrix();
            let n = p.states();
            let ours = eigenvalues(&a, n).unwrap();
            let theirs = nalgebra_eigs(&a, n);
            let scale = theirs.iter().map(|z| z.norm()).fold(1.0, f64::max);
            // multiple eigenvalues (e.g. symmetric layouts) are sensitive at sqrt(ε)
            assert!(match_dist(&ours, &theirs) < 1e-7 * scale, "{ours:?}\n{theirs:?}");
        }
    }
}

#[test]
fn balancing_handles_badly_scaled_matrices() {
    // D A D⁻¹ with D spanning 1e6, as physical units produce: same eigenvalues
    let mut rng = Rng(22);
    for _ in 0..50 {
        let m = random_model(&mut rng);
        let p = Pencil::new(&m, rng.range(0.1, 4.0), Balls::Free).unwrap();
        let a = p.state_matrix();
        let n = p.states();
        let d: Vec<f64> = (0..n).map(|i| 10f64.powf(6.0 * i as f64 / (n - 1) as f64)).collect();
        let mut b = a;
        for i in 0..n {
            for j in 0..n {
                b[i][j] = d[i] * a[i][j] / d[j];
            }
        }
        let ea = eigenvalues(&a, n).unwrap();
        let eb = eigenvalues(&b, n).unwrap();
        let scale = ea.iter().map(|z| z.norm()).fold(1.0, f64::max);
        assert!(match_dist(&ea, &eb) < 1e-7 * scale);
    }
}

#[test]
fn eigenvalues_are_roots_of_the_pencil_determinant() {
    let mut rng = Rng(23);
    for _ in 0..200 {
        let m = random_model(&mut rng);
        let w = rng.range(0.05, 5.0);
        let (p, ev) = eigenvalues_at(&m, w, Balls::Free).unwrap();
        for lam in ev {
            let mat: Vec<Vec<Complex64>> = (0..p.n).map(|i| (0..p.n).map(|j| lam * lam * p.m[i][j] + lam * p.g[i][j] + p.k[i][j]).collect()).collect();
            // Hadamard's bound: |det| ≤ Π ‖row‖; at an eigenvalue det vanishes to round-off of that size
            let bound: f64 = mat.iter().map(|r| r.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt()).product();
            assert!(complex_det(&mat).norm() < 1e-10 * bound, "λ = {lam}: |det| = {} vs {bound}", complex_det(&mat).norm());
        }
    }
}

#[test]
fn isotropic_symmetric_rotor_decouples_into_jeffcott_and_tilt() {
    // ΔĀ = 0, l̄_L = 0.5: w and χ decouple. Fixed frame: Jeffcott μ² + h μ + 1 = 0 and the
    // gyroscopic tilt μ² + (h_α − i C̄Σ Ω) μ + p̄α² = 0 (complex form); rotating frame λ = μ − iΩ,
    // with the conjugates.
    let mut rng = Rng(24);
    for _ in 0..100 {
        let (cs, rho, h) = (rng.range(0.2, 1.8), rng.range(0.2, 0.8), rng.range(0.0, 0.3));
        let m = model(cs, rho, 0.5, 0.3, 0.0, h, 0.1, None);
        let w = rng.range(0.0, 4.0);
        let (_, ev) = eigenvalues_at(&m, w, Balls::Locked).unwrap();
        let i = Complex64::new(0.0, 1.0);
        let mut expect = vec![];
        let quad = |b: Complex64, c: Complex64| {
            let d = (b * b - 4.0 * c).sqrt();
            [(-b + d) / 2.0, (-b - d) / 2.0]
        };
        let ha = m.damping.h_alpha;
        for mu in quad(Complex64::new(h, 0.0), Complex64::new(1.0, 0.0)).into_iter().chain(quad(ha - i * cs * w, Complex64::new(m.p_alpha_sq, 0.0))) {
            let lam = mu - i * w;
            expect.push(lam);
            expect.push(lam.conj());
        }
        assert!(match_dist(&ev, &expect) < 1e-9 * (1.0 + w * w), "{ev:?}\n{expect:?}");
    }
}

#[test]
fn locked_undamped_rotor_has_zero_eigenvalues_at_the_critical_speeds() {
    for (l, d) in [(0.8, 0.1), (1.2, 0.1), (0.5, 0.05), (0.3, 0.15)] {
        let m = model(0.75, 0.4, l, 0.8, d, 0.0, 0.0, None);
        for (wk, _, _) in critical_speeds_at(&m, d) {
            let (_, ev) = eigenvalues_at(&m, wk, Balls::Locked).unwrap();
            let smallest = ev.iter().map(|z| z.norm()).fold(f64::INFINITY, f64::min);
            // a double zero at the end of a split range: accurate to ~sqrt(ε)
            assert!(smallest < 1e-6, "Ω_K = {wk}: smallest |λ| = {smallest}");
        }
    }
}

#[test]
fn locked_undamped_instability_lies_exactly_between_split_critical_speeds() {
    // Every analytic critical speed ends an unstable range (to 1e-6), the middle of each split
    // pair is a divergence (a real positive eigenvalue), and any other end of an unstable range
    // is a flutter boundary (unstable eigenvalues with Im λ ≠ 0): the exact analysis finds
    // flutter of the coupled anisotropic rotor that the papers' sign conditions do not see.
    let mut rng = Rng(25);
    let mut flutter_seen = 0;
    for _ in 0..40 {
        let d = rng.range(0.03, 0.2);
        let m = model(rng.range(0.3, 0.9), rng.range(0.3, 0.6), rng.range(0.2, 1.3), 0.5, d, 0.0, 0.0, None);
        let crit = critical_speeds_at(&m, d);
        let ks: Vec<f64> = crit.iter().map(|r| r.0).collect();
        let wmax = ks.last().unwrap() * 1.3;
        let st = stability_ranges(&m, wmax, 800, Balls::Locked, 1e-9).unwrap();
        let mut ends: Vec<f64> = vec![];
        // (a range stable at the first speed analysed starts there: no located end)
        let first = st.max_real_part[0].0;
        for r in &st.stable_ranges {
            if r.lo > first {
                ends.push(r.lo);
            }
            if let Some(h) = r.hi {
                ends.push(h);
            }
        }
        for k in &ks {
            assert!(ends.iter().any(|e| (e - k).abs() < 1e-6), "Ω_K = {k} is no end of {:?}", st.stable_ranges);
        }
        for kind in [autobal::spatial::critical_speeds::ModeKind::Transverse, autobal::spatial::critical_speeds::ModeKind::Angular] {
            let pair: Vec<f64> = crit.iter().filter(|r| r.1 == kind).map(|r| r.0).collect();
            if pair.len() == 2 {
                let (_, ev) = eigenvalues_at(&m, 0.5 * (pair[0] + pair[1]), Balls::Locked).unwrap();
                assert!(ev.iter().any(|z| z.re > 1e-9 && z.im == 0.0), "divergence between {pair:?}: {ev:?}");
            }
        }
        for e in ends.iter().filter(|e| !ks.iter().any(|k| (*e - k).abs() < 1e-6)) {
            let inside = [e - 1e-4, e + 1e-4].into_iter().find(|w| margin(&m, *w, Balls::Locked).unwrap() > 1e-9).unwrap();
            let (_, ev) = eigenvalues_at(&m, inside, Balls::Locked).unwrap();
            assert!(ev.iter().filter(|z| z.re > 1e-9).all(|z| z.im.abs() > 1e-3), "flutter at {inside}: {ev:?}");
            flutter_seen += 1;
        }
    }
    assert!(flutter_seen > 0, "the sample should contain flutter ranges");
}

#[test]
fn routh_hurwitz_agrees_with_the_eigenvalues_away_from_the_boundary() {
    let mut rng = Rng(26);
    let (mut checked, mut stable_seen) = (0, 0);
    for _ in 0..3000 {
        let m = random_model(&mut rng);
        let w = rng.range(0.05, 5.0);
        for balls in [Balls::Free, Balls::Locked] {
            let p = Pencil::new(&m, w, balls).unwrap();
            let n = p.states();
            let a = p.state_matrix();
            let alpha = margin(&m, w, balls).unwrap();
            if alpha.abs() < 1e-6 {
                continue;
            }
            let c = characteristic_polynomial(&a, n);
            assert_eq!(routh_hurwitz_stable(&c[..=n]), alpha < 0.0, "α = {alpha}, Ω = {w}, {m:?}");
            checked += 1;
            stable_seen += (alpha < 0.0) as usize;
        }
    }
    assert!(checked > 4000 && stable_seen > 500, "{checked} checked, {stable_seen} stable");
}

#[test]
fn characteristic_polynomial_vanishes_at_the_eigenvalues() {
    let mut rng = Rng(27);
    for _ in 0..200 {
        let m = random_model(&mut rng);
        let p = Pencil::new(&m, rng.range(0.1, 4.0), Balls::Free).unwrap();
        let n = p.states();
        let a = p.state_matrix();
        let c = characteristic_polynomial(&a, n);
        for lam in eigenvalues(&a, n).unwrap() {
            let (mut v, mut mag) = (Complex64::new(0.0, 0.0), 0.0);
            for (k, ck) in c[..=n].iter().enumerate() {
                v += ck * lam.powu((n - k) as u32);
                mag += ck.abs() * lam.norm().powi((n - k) as i32);
            }
            assert!(v.norm() < 1e-10 * mag, "p(λ) = {} vs {mag}", v.norm());
        }
    }
}

#[test]
fn jeffcott_whirl_frequencies_in_fixed_axes() {
    // isotropic symmetric undamped rotor: the translation modes whirl at ±1 in fixed axes
    // whatever the speed; the rotating-frame frequencies are 1 − Ω and −1 − Ω.
    let m = model(0.6, 0.4, 0.5, 0.0, 0.0, 0.0, 0.0, None);
    let omegas: Vec<f64> = (0..60).map(|i| 0.05 * i as f64).collect();
    let c = campbell(&m, &omegas, Balls::Locked).unwrap();
    let mut seen_fw = false;
    let mut seen_bw = false;
    for line in &c.lines {
        for md in &line.modes {
            if md.group == Group::Translation && md.im >= 0.0 {
                assert!((md.fixed_frequency.abs() - 1.0).abs() < 1e-9, "{md:?}");
                match md.whirl {
                    Whirl::Forward => seen_fw = true,
                    Whirl::Backward => seen_bw = true,
                    Whirl::None => {}
                }
            }
        }
    }
    assert!(seen_fw && seen_bw);
}

#[test]
fn campbell_lines_are_continuous() {
    // mode tracking: on a fine grid consecutive points of a line differ by at most a few grid
    // steps' worth of change (|dλ/dΩ| ≤ ~2 for these models), also for a symmetric rotor
    for l in [0.5, 0.8] {
        let m = model(0.75, 0.4, l, 0.8, 0.1, 0.05, 0.1, Some((0.05, 0.5)));
        let omegas: Vec<f64> = (1..400).map(|i| 0.01 * i as f64).collect();
        let c = campbell(&m, &omegas, Balls::Free).unwrap();
        assert_eq!(c.lines.len(), 12);
        for line in &c.lines {
            for k in 1..line.modes.len() {
                let (a, b) = (&line.modes[k - 1], &line.modes[k]);
                let jump = ((a.re - b.re).powi(2) + (a.im - b.im).powi(2)).sqrt();
                assert!(jump < 0.1, "jump {jump} at Ω = {}", omegas[k]);
            }
        }
    }
}

#[test]
fn light_balls_leave_the_rotor_modes_unchanged() {
    // m̄ → 0: the 12-state spectrum contains the 8 locked-rotor eigenvalues to O(m̄)
    let mut rng = Rng(28);
    for _ in 0..50 {
        let mut m = random_model(&mut rng);
        let w = rng.range(0.2, 4.0);
        let (_, locked) = eigenvalues_at(&m, w, Balls::Locked).unwrap();
        let mut b = m.balls.unwrap();
        b.m_bar = 1e-9;
        m.balls = Some(b);
        let (_, free) = eigenvalues_at(&m, w, Balls::Free).unwrap();
        // each locked eigenvalue appears in the free spectrum (unless it nearly coincides with
        // a ball eigenvalue, where the perturbation is O(sqrt(m̄)))
        for lam in &locked {
            let d = free.iter().map(|z| (z - lam).norm()).fold(f64::INFINITY, f64::min);
            assert!(d < 1e-4, "locked λ = {lam} missing from free spectrum ({d})");
        }
    }
}

#[test]
fn exact_ranges_of_the_three_layouts_are_the_printed_table() {
    // docs/notes/stability.md, "What the exact analysis shows that the papers do not": 000's base case
    // with masses at l̄_L = 0.5, 0.8, 1.2, computed as `autobal stability` does (its default
    // Ω_max and 2000 grid speeds, ends bisected to 1e-9), against the table's 4 decimals.
    use autobal::reports::default_omega_max;
    use autobal::spatial::comparison::compare;
    use autobal::spatial::ranges::SpeedRange;
    // the frame of the balls at balance: two balls at π ± acos(1/E), E = 2, give
    // D' = cos(2 acos(1/E)) = 2/E² − 1 = −0.5 and d_A = [[1 − D', 0], [0, 1 + D']]
    let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
    let b = m.balls.unwrap();
    assert!((b.d_a[0][0] - 1.5).abs() < 1e-15 && (b.d_a[1][1] - 0.5).abs() < 1e-15 && b.d_a[0][1] == 0.0, "{:?}", b.d_a);
    let r4 = |x: f64| (x * 1e4).round() / 1e4;
    let ends = |v: &[SpeedRange]| -> Vec<(f64, Option<f64>)> { v.iter().map(|r| (r4(r.lo), r.hi.map(r4))).collect() };
    type Table = [(f64, &'static [(f64, Option<f64>)], &'static [(f64, Option<f64>)], &'static [(f64, Option<f64>)])];
    // (l̄_L, exactly stable, 003's necessary ranges, stable where 003's condition fails)
    let table: &Table = &[
        (0.5, &[(1.4469, Some(1.6745))], &[(1.0, Some(1.6193)), (2.7951, None)], &[(1.6193, Some(1.6745))]),
        (0.8, &[(1.4122, Some(1.7071)), (1.7317, Some(2.2384))], &[(0.8463, Some(2.1726)), (3.3029, None)], &[(2.1726, Some(2.2384))]),
        (1.2, &[(1.0716, Some(3.0625))], &[(0.5730, Some(3.0986)), (4.8782, None)], &[]),
    ];
    for &(l, exact, necessary, outside) in table {
        let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(l)).unwrap();
        let c = compare(&m, default_omega_max(&m), 2000, Balls::Free).unwrap();
        assert_eq!(c.exact.tolerance, 1e-9);
        assert_eq!(ends(&c.exact.stable_ranges), exact, "l̄_L = {l}: exactly stable");
        assert_eq!(ends(&c.necessary), necessary, "l̄_L = {l}: 003's necessary ranges");
        // finding 4: stable speeds outside 003's ranges are rare and narrow
        assert_eq!(ends(&c.stable_not_necessary), outside, "l̄_L = {l}: stable outside 003's ranges");
        // finding 2: the lower exact range starts well above 003's lower bound (Ω_K2 or 1)
        assert!(exact[0].0 > necessary[0].0 + 0.3, "l̄_L = {l}");
        // finding 1: 003's upper range (Ω > Ω_K4) is unstable at every speed up to 6: the
        // spectral abscissa is positive on a grid of 200 speeds (docs: "not stable here")
        let lo = necessary[1].0;
        let mut least = f64::INFINITY;
        for i in 1..=200 {
            let w = lo + (6.0 - lo) * i as f64 / 200.0;
            least = least.min(margin(&m, w, Balls::Free).unwrap());
        }
        assert!(least > 0.0, "l̄_L = {l}: a stable speed above Ω_K4 ({least})");
    }
}

#[test]
fn undamped_model_has_lagrangian_structure() {
    // Scaling the ball rows by S = (2/m̄) d_A⁻¹ must make M and K symmetric and G skew when all
    // damping is zero: the linearisation of a conservative gyroscopic system. A sign slip in any
    // coupling block of eq (6) breaks this.
    let mut rng = Rng(29);
    for _ in 0..200 {
        let c_sigma = rng.range(0.2, 1.6);
        let m = model(
            c_sigma,
            rng.range(0.2, 0.8),
            rng.range(-0.3, 1.4),
            rng.range(-1.0, 1.0),
            rng.range(0.0, 0.2).min(0.5 * c_sigma),
            0.0,
            0.0,
            Some((rng.range(0.01, 0.1), rng.range(0.0, 0.9))),
        );
        let p = Pencil::new(&m, rng.range(0.0, 4.0), Balls::Free).unwrap();
        let b = m.balls.unwrap();
        let d = b.d_a;
        let det = d[0][0] * d[1][1] - d[0][1] * d[1][0];
        let s = [[2.0 / b.m_bar * d[1][1] / det, -2.0 / b.m_bar * d[0][1] / det], [-2.0 / b.m_bar * d[1][0] / det, 2.0 / b.m_bar * d[0][0] / det]];
        let scaled = |a: &[[f64; 6]; 6]| {
            let mut r = *a;
            for j in 0..6 {
                for i in 0..2 {
                    r[4 + i][j] = s[i][0] * a[4][j] + s[i][1] * a[5][j];
                }
            }
            r
        };
        let (ms, gs, ks) = (scaled(&p.m), scaled(&p.g), scaled(&p.k));
        for i in 0..6 {
            for j in 0..6 {
                let tol = 1e-12 * (1.0 + ms[i][j].abs() + ks[i][j].abs() + gs[i][j].abs());
                assert!((ms[i][j] - ms[j][i]).abs() < tol, "M not symmetric at ({i},{j})");
                assert!((ks[i][j] - ks[j][i]).abs() < tol, "K not symmetric at ({i},{j})");
                assert!((gs[i][j] + gs[j][i]).abs() < tol, "G not skew at ({i},{j})");
            }
        }
    }
}

#[test]
fn state_space_polynomial_matches_direct_assembly() {
    use autobal::spatial::linear_model::StateSpace;
    let mut rng = Rng(30);
    for _ in 0..100 {
        let m = random_model(&mut rng);
        for balls in [Balls::Free, Balls::Locked] {
            let ss = StateSpace::new(&m, balls).unwrap();
            let w = rng.range(0.0, 6.0);
            let p = Pencil::new(&m, w, balls).unwrap();
            let (a, b) = (p.state_matrix(), ss.at(w));
            for i in 0..p.states() {
                for j in 0..p.states() {
                    assert!((a[i][j] - b[i][j]).abs() < 1e-12 * (1.0 + a[i][j].abs()) * (1.0 + w * w));
                }
            }
        }
    }
}

// ---- the characteristic polynomial in Ω, maps and Campbell diagrams built on it ----

use autobal::linalg::charpoly::{routh_count_right_of, SpeedPolynomial};
use autobal::linalg::eigen::spectral_abscissa;
use autobal::spatial::linear_model::StateSpace;
use autobal::spatial::map::{stability_map, Axis, Cell, MapSettings, Quantity};
use autobal::spatial::paths::{SpatialInput, SpatialSpec};
use autobal::spatial::stability::strictly_stable_at;

fn random_input(rng: &mut Rng) -> DimensionlessInput {
    DimensionlessInput {
        c_sigma: rng.range(0.2, 1.6),
        rho_s: rng.range(0.2, 0.8),
        l_left: rng.range(-0.3, 1.4),
        z_a: rng.range(-1.0, 1.0),
        anisotropy: AnisotropyInput::Direct(rng.range(0.0, 0.2)),
        h_x: rng.range(0.0, 0.2),
        h_s: rng.range(0.01, 0.5),
        method: AnisotropyMethod::Exact,
        direct_balls: Some((rng.range(0.005, 0.1), rng.range(0.0, 1.0))),
    }
}

#[test]
fn speed_polynomial_roots_are_the_eigenvalues() {
    // The exact expansion of det(M λ² + G(Ω) λ + K(Ω)) / det M, evaluated at Ω, has the QR
    // eigenvalues of the state matrix (and nalgebra's) as roots: the Newton inclusion radius
    // N |p(λ)/p'(λ)| at each is within the sensitivity of a double root, N sqrt(ε) (1 + |λ|).
    let mut rng = Rng(31);
    for _ in 0..200 {
        let m = random_model(&mut rng);
        for balls in [Balls::Free, Balls::Locked] {
            let sp = SpeedPolynomial::new(&Pencil::terms(&m, balls).unwrap()).unwrap();
            let w = rng.range(0.0, 6.0);
            let p = Pencil::new(&m, w, balls).unwrap();
            let n = p.states();
            assert_eq!(sp.states, n);
            let c = sp.at(w);
            for lam in nalgebra_eigs(&p.state_matrix(), n) {
                let (v, dv) = autobal::linalg::charpoly::eval_with_derivative(&c[..=n], lam);
                let radius = n as f64 * (v / dv).norm();
                assert!(radius < n as f64 * f64::EPSILON.sqrt() * (1.0 + lam.norm()), "Ω = {w}, λ = {lam}: radius {radius}");
            }
        }
    }
}

#[test]
fn routh_count_is_the_number_of_eigenvalues_right_of_a_shift() {
    let mut rng = Rng(32);
    let mut checked = 0;
    for _ in 0..1500 {
        let m = random_model(&mut rng);
        let sp = SpeedPolynomial::new(&Pencil::terms(&m, Balls::Free).unwrap()).unwrap();
        let w = rng.range(0.05, 5.0);
        let ev = eigenvalues_at(&m, w, Balls::Free).unwrap().1;
        let s = rng.range(-0.3, 0.1);
        if ev.iter().any(|z| (z.re - s).abs() < 1e-6) {
            continue;
        }
        let count = ev.iter().filter(|z| z.re > s).count();
        assert_eq!(routh_count_right_of(&sp.at(w)[..=12], s), Some(count), "Ω = {w}, s = {s}: {ev:?}");
        checked += 1;
    }
    assert!(checked > 1400);
}

fn spec_of(d: DimensionlessInput) -> SpatialSpec {
    SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None }
}

fn collect_map(spec: &SpatialSpec, x: &Axis, y: &Axis, s: &MapSettings) -> (Vec<Vec<Cell>>, autobal::spatial::map::MapOutcome) {
    let mut rows = vec![];
    let out = stability_map(spec, x, y, s, &autobal::control::Control::none(), &mut |j, r| {
        assert_eq!(j, rows.len(), "rows arrive in grid order");
        rows.push(r.to_vec());
        true
    })
    .unwrap();
    (rows, out)
}

#[test]
fn map_margin_by_continuation_matches_the_qr_eigenvalues_on_fine_grids() {
    // Continuation of the rightmost root with a Routh certificate at every speed, against the
    // full QR eigenvalues at every point: the certificate bounds the error by the Newton
    // radius accepted (1e-10 (1 + |λ|)) plus the gap of the count (1e-12). Overtaking
    // eigenvalues must be detected (fall-backs beyond the first speed of each line).
    let mut rng = Rng(33);
    let (mut fallbacks, mut worst) = (0, 0.0f64);
    for _ in 0..12 {
        let d = random_input(&mut rng);
        let spec = spec_of(d);
        let x = Axis { path: "dimensionless.z_a".into(), values: vec![d.z_a, d.z_a + 0.3, d.z_a - 0.4] };
        let y = Axis::linspace("omega", 0.0, 6.0, 1500);
        for balls in [Balls::Free, Balls::Locked] {
            let s = MapSettings { balls, quantity: Quantity::Margin, omega: None };
            let (rows, out) = collect_map(&spec, &x, &y, &s);
            fallbacks += out.direct - x.values.len();
            for (i, &z) in x.values.iter().enumerate() {
                let mut di = d;
                di.z_a = z;
                let ss = StateSpace::new(&SpatialModel::from_dimensionless(&di).unwrap(), balls).unwrap();
                for (j, &w) in y.values.iter().enumerate() {
                    let qr = spectral_abscissa(&ss.at(w.max(1e-9)), ss.states).unwrap();
                    let a = rows[j][i].margin;
                    worst = worst.max((a - qr).abs());
                    assert!((a - qr).abs() <= 1e-10 * (1.0 + w * w) + 1e-12, "Ω = {w}: continuation {a} vs QR {qr}");
                    if qr.abs() > 1e-9 {
                        assert_eq!(rows[j][i].stable, qr < 0.0);
                    }
                }
            }
        }
    }
    assert!(fallbacks > 50, "overtaking eigenvalues should occur and be caught: {fallbacks}");
    assert!(worst < 1e-10, "{worst}");
}

#[test]
fn map_verdict_equals_the_direct_routh_hurwitz_test_at_every_point() {
    // Routh–Hurwitz on the polynomial coefficients, every change of verdict confirmed by the
    // direct test on the state matrix: the map equals the direct test everywhere, and the
    // eigenvalues away from the boundary.
    let mut rng = Rng(34);
    let mut stable = 0;
    for _ in 0..12 {
        let d = random_input(&mut rng);
        let spec = spec_of(d);
        let x = Axis { path: "dimensionless.h_s".into(), values: vec![d.h_s, 0.5 * d.h_s, 2.0 * d.h_s] };
        let y = Axis::linspace("omega", 0.0, 6.0, 2000);
        let s = MapSettings { balls: Balls::Free, quantity: Quantity::Verdict, omega: None };
        let (rows, _) = collect_map(&spec, &x, &y, &s);
        for (i, &h) in x.values.iter().enumerate() {
            let mut di = d;
            di.h_s = h;
            let m = SpatialModel::from_dimensionless(&di).unwrap();
            let ss = StateSpace::new(&m, Balls::Free).unwrap();
            for (j, &w) in y.values.iter().enumerate() {
                let w = w.max(1e-9);
                assert_eq!(rows[j][i].stable, strictly_stable_at(&ss, w), "Ω = {w}");
                let a = spectral_abscissa(&ss.at(w), 12).unwrap();
                if a.abs() > 1e-6 {
                    assert_eq!(rows[j][i].stable, a < 0.0, "Ω = {w}, α = {a}");
                }
                stable += rows[j][i].stable as usize;
            }
        }
    }
    assert!(stable > 1000, "{stable}");
}

#[test]
fn map_rows_are_the_same_in_grid_order_whatever_the_thread_count() {
    let mut rng = Rng(35);
    let spec = spec_of(random_input(&mut rng));
    let x = Axis::linspace("dimensionless.z_a", -1.0, 1.0, 37);
    let y = Axis::linspace("omega", 0.05, 4.0, 1100);
    for q in [Quantity::Margin, Quantity::Verdict] {
        let s = MapSettings { balls: Balls::Free, quantity: q, omega: None };
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| collect_map(&spec, &x, &y, &s).0)
        };
        let one = run(1);
        let three = run(3);
        assert_eq!(one.len(), 1100);
        for (a, b) in one.iter().zip(&three) {
            for (p, q) in a.iter().zip(b) {
                assert!(p.margin.to_bits() == q.margin.to_bits() && p.stable == q.stable && p.necessary == q.necessary);
            }
        }
        // the speed on x: the same cells, transposed
        let s2 = s;
        let t = collect_map(&spec, &y, &x, &s2).0;
        for j in 0..y.values.len() {
            for i in 0..x.values.len() {
                assert_eq!(one[j][i].stable, t[i][j].stable);
                assert!(one[j][i].margin.to_bits() == t[i][j].margin.to_bits() || q == Quantity::Verdict);
            }
        }
    }
}

#[test]
fn map_without_a_speed_axis_and_its_errors() {
    let mut rng = Rng(36);
    let d = random_input(&mut rng);
    let spec = spec_of(d);
    let x = Axis::linspace("dimensionless.c_sigma", 0.3, 1.5, 5);
    let y = Axis::linspace("dimensionless.l_left", 0.2, 1.2, 4);
    let s = MapSettings { balls: Balls::Free, quantity: Quantity::Margin, omega: Some(1.7) };
    let (rows, out) = collect_map(&spec, &x, &y, &s);
    assert!(out.complete && out.rows == 4);
    for (j, &l) in y.values.iter().enumerate() {
        for (i, &c) in x.values.iter().enumerate() {
            let mut di = d;
            di.c_sigma = c;
            di.l_left = l;
            let a = margin(&SpatialModel::from_dimensionless(&di).unwrap(), 1.7, Balls::Free).unwrap();
            // the map uses A(Ω) = A0 + Ω A1 + Ω² A2, `margin` the pencil at Ω: round-off apart
            assert!((rows[j][i].margin - a).abs() < 64.0 * f64::EPSILON, "{} vs {a}", rows[j][i].margin);
        }
    }
    // stopping early: the rows handed over are complete, the outcome says so
    let mut seen = 0;
    let out = stability_map(
        &spec,
        &Axis::linspace("dimensionless.z_a", -1.0, 1.0, 9),
        &Axis::linspace("omega", 0.1, 3.0, 50),
        &MapSettings { omega: None, ..s },
        &autobal::control::Control::none(),
        &mut |_, _| {
            seen += 1;
            seen < 7
        },
    )
    .unwrap();
    assert!(!out.complete && out.rows == 7 && out.stopped == Some(autobal::control::StopReason::Observer));
    let e = stability_map(
        &spec,
        &Axis::linspace("dimensionless.zz", 0.0, 1.0, 3),
        &Axis::linspace("omega", 0.1, 3.0, 5),
        &s,
        &autobal::control::Control::none(),
        &mut |_, _| true,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("dimensionless.zz: unknown parameter path"), "{e}");
    let e = stability_map(
        &spec,
        &Axis::linspace("dimensionless.rho_s", -1.0, 1.0, 3),
        &Axis::linspace("omega", 0.1, 3.0, 5),
        &s,
        &autobal::control::Control::none(),
        &mut |_, _| true,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("dimensionless.rho_s: "), "{e}");
    let e = stability_map(&spec, &x, &y, &MapSettings { omega: None, ..s }, &autobal::control::Control::none(), &mut |_, _| true).unwrap_err();
    assert!(e.to_string().starts_with("omega: required"), "{e}");
}

#[test]
fn campbell_lines_follow_crossing_modes_by_their_eigenvectors() {
    // Isotropic symmetric undamped rotor: translation (Jeffcott) and tilt decouple, and their
    // rotating-frame eigenvalues collide (equal λ, not only equal frequency) at the crossings.
    // Each tracked line must stay on one mode: the translation lines are exactly the straight
    // lines ±i(1 ∓ Ω) at every speed, and every line keeps its group.
    for (cs, rho) in [(0.6, 0.4), (1.3, 0.5), (0.9, 0.3)] {
        let m = model(cs, rho, 0.5, 0.0, 0.0, 0.0, 0.0, None);
        let omegas: Vec<f64> = (0..700).map(|i| 0.0037 + 0.0071 * i as f64).collect();
        let c = campbell(&m, &omegas, Balls::Locked).unwrap();
        let i = Complex64::new(0.0, 1.0);
        let branches = [
            |w: f64| Complex64::new(0.0, 1.0 - w),
            |w: f64| Complex64::new(0.0, -1.0 - w),
            |w: f64| Complex64::new(0.0, -(1.0 - w)),
            |w: f64| Complex64::new(0.0, 1.0 + w),
        ];
        let mut translation_lines = 0;
        for line in &c.lines {
            let g = line.modes[0].group;
            assert!(line.modes.iter().all(|md| md.group == g), "a line changed group (C̄Σ = {cs})");
            if g == Group::Translation {
                translation_lines += 1;
                let l0 = Complex64::new(line.modes[0].re, line.modes[0].im);
                let b = branches.iter().min_by(|f, g| (f(omegas[0]) - l0).norm().total_cmp(&(g(omegas[0]) - l0).norm())).unwrap();
                for (md, &w) in line.modes.iter().zip(&omegas) {
                    let lam = Complex64::new(md.re, md.im);
                    assert!((lam - b(w)).norm() < 1e-9, "C̄Σ = {cs}, Ω = {w}: {lam} left its branch {}", b(w));
                }
            }
        }
        let _ = i;
        assert_eq!(translation_lines, 4);
    }
}

#[test]
fn campbell_of_the_default_rotor_has_continuous_lines() {
    // 000's base case with masses (the default config): every tracked line moves by less than
    // the largest |dλ/dΩ| times the step between neighbouring speeds.
    let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
    let h = 0.002;
    let omegas: Vec<f64> = (0..2500).map(|i| 0.001 + h * i as f64).collect();
    let c = campbell(&m, &omegas, Balls::Free).unwrap();
    for line in &c.lines {
        for k in 1..line.modes.len() {
            let (a, b) = (&line.modes[k - 1], &line.modes[k]);
            let jump = ((a.re - b.re).powi(2) + (a.im - b.im).powi(2)).sqrt();
            assert!(jump < 4.0 * h, "jump {jump} at Ω = {}", omegas[k]);
        }
    }
}

// ---- stability boundaries traced as curves ----

use autobal::spatial::boundary::{trace_boundary, Boundary, CurveKind, TraceSettings};

/// Distance (in the plane scaled to the unit square) from `(x, y)` to the stability-boundary
/// parts of the traced curves (segments with both ends on the boundary) and codim-2 points.
fn distance_to_boundary(b: &Boundary, x: f64, y: f64) -> f64 {
    let (sx, sy) = (b.x.hi() - b.x.lo(), b.y.hi() - b.y.lo());
    let mut best = f64::INFINITY;
    for c in &b.curves {
        for w in c.points.windows(2) {
            if !(w[0].on_boundary || w[1].on_boundary) {
                continue;
            }
            let (ax, ay, bx, by) = ((w[0].x - x) / sx, (w[0].y - y) / sy, (w[1].x - x) / sx, (w[1].y - y) / sy);
            let (dx, dy) = (bx - ax, by - ay);
            let l2 = dx * dx + dy * dy;
            let t = if l2 > 0.0 { (-(ax * dx + ay * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
            best = best.min(((ax + t * dx).powi(2) + (ay + t * dy).powi(2)).sqrt());
        }
    }
    best
}

/// The papers' base case with free balls, the first plane of the boundary tests.
fn boundary_base() -> DimensionlessInput {
    DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left: 0.8,
        z_a: 0.8,
        anisotropy: AnisotropyInput::Direct(0.1),
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: Some((0.05, 0.5)),
    }
}

#[test]
fn traced_boundary_is_located_to_1e_8_and_agrees_with_a_fine_grid() {
    // Three planes with the speed: every traced point satisfies its condition (an eigenvalue
    // pair ±i√w, or a zero eigenvalue, within 1e-8 of the QR eigenvalues there), and on 23 fine
    // lines across each plane every end of an exact stable range (QR margins on 1500 speeds,
    // bisection to 1e-11) lies on a traced stability boundary, within the chord error of the
    // drawn polyline (steps h ≤ 0.05 of the plane with h·turn ≤ 0.05 · 0.15 rad, chords ≤ 2h:
    // sagitta ≤ h·turn/4 < 2e-3).
    let base = boundary_base();
    let mut rng = Rng(37);
    let cases = [
        (base, "dimensionless.z_a", -2.0, 2.0),
        (random_input(&mut rng), "dimensionless.c_sigma", 0.3, 1.8),
        (random_input(&mut rng), "dimensionless.h_s", 0.02, 0.5),
    ];
    let mut total = 0;
    for (d, path, lo, hi) in cases {
        let spec = spec_of(d);
        let x = Axis::range(path, lo, hi);
        let y = Axis::range("omega", 0.05, 4.5);
        let b = trace_boundary(&spec, &x, &y, &TraceSettings::default()).unwrap();
        let model_at = |v: f64| {
            let mut s = spec.clone();
            s.set(path, v).unwrap();
            s.build().unwrap()
        };
        for c in &b.curves {
            for p in &c.points {
                let (_, ev) = eigenvalues_at(&model_at(p.x), p.y, Balls::Free).unwrap();
                let target = match c.kind {
                    CurveKind::Hopf if p.w > 0.0 => Complex64::new(0.0, p.w.sqrt()),
                    CurveKind::Hopf => Complex64::new((-p.w).sqrt(), 0.0),
                    CurveKind::Fold => Complex64::new(0.0, 0.0),
                };
                let d = ev.iter().map(|z| (z - target).norm()).fold(f64::INFINITY, f64::min);
                assert!(d < 1e-8, "{path}: {:?} point ({}, {}) is {d} from its condition", c.kind, p.x, p.y);
            }
        }
        let mut ends = 0;
        for i in 0..23 {
            let xv = lo + (hi - lo) * (i as f64 + 0.37) / 23.0;
            let st = stability_ranges(&model_at(xv), 4.5, 1500, Balls::Free, 1e-11).unwrap();
            for r in &st.stable_ranges {
                for e in [Some(r.lo), r.hi].into_iter().flatten() {
                    if e > 0.06 && e < 4.49 {
                        ends += 1;
                        let dist = distance_to_boundary(&b, xv, e);
                        assert!(dist < 2e-3, "{path} = {xv}: stability changes at Ω = {e}, {dist} from the traced boundary");
                    }
                }
            }
        }
        eprintln!("{path}: {} curves, {} codim-2 points, {ends} range ends checked", b.curves.len(), b.codim2.len());
        assert!(ends > 5, "{path}: {ends} ends");
        total += ends;
    }
    assert!(total > 40, "{total} ends checked");
}

#[test]
fn cancelled_boundary_keeps_whole_curves_and_says_it_is_incomplete() {
    // Ctrl-C in `map --boundary` reaches the tracer through `cancel`: asked at once, nothing is
    // traced; asked after a few checks, the curves kept are the first curves of the full trace,
    // point for point (whole curves, never half of one), and `complete` says the search stopped
    use autobal::control::{Control, StopReason};
    use autobal::spatial::boundary::trace_boundary_with;
    let spec = spec_of(boundary_base());
    let x = Axis::range("dimensionless.z_a", -2.0, 2.0);
    let y = Axis::range("omega", 0.05, 4.5);
    let s = TraceSettings::default();
    let full = trace_boundary(&spec, &x, &y, &s).unwrap();
    assert!(full.complete && full.curves.len() >= 3, "{} curves", full.curves.len());
    let cancelled = Control::new();
    cancelled.cancel();
    let none = trace_boundary_with(&spec, &x, &y, &s, &cancelled).unwrap();
    assert!(!none.complete && none.curves.is_empty() && none.stopped == Some(StopReason::Interrupted));
    // a zero budget: nothing traced, the budget named
    let spent = trace_boundary_with(&spec, &x, &y, &s, &Control::new().with_budget(std::time::Duration::ZERO)).unwrap();
    assert!(!spent.complete && spent.curves.is_empty() && matches!(spent.stopped, Some(StopReason::Budget { .. })));
    // cancelled from the progress observer at its k-th report (after a line or a curve): the
    // checks before the next line or curve see it
    let mut stopped_at = None;
    for k in 1..200 {
        let calls = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let c = Control::new();
        let (flag, n) = (c.flag().clone(), calls.clone());
        let c = c.with_progress(move |_| {
            if n.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1 >= k {
                flag.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        });
        let part = trace_boundary_with(&spec, &x, &y, &s, &c).unwrap();
        if !part.curves.is_empty() {
            assert!(!part.complete && part.curves.len() < full.curves.len() && part.stopped == Some(StopReason::Interrupted));
            assert_eq!(part.curves[..], full.curves[..part.curves.len()]);
            stopped_at = Some(k);
            break;
        }
    }
    assert!(stopped_at.is_some(), "a partial trace with curves");
}

// ---- Campbell: eigenvectors, root continuation, branch tracking ----

use autobal::linalg::charpoly::continue_roots;
use autobal::spatial::stability::pencil_null_vector;

#[test]
fn eigenvectors_are_null_vectors_of_the_pencil_on_both_elimination_paths() {
    // Every eigenvalue (QR) of random models, balls free and locked, speeds down to Ω = 0.001
    // where the balls' neutral and drag modes have μ = λ² + h̄s λ ≈ 0 (the 6×6 path) and above
    // (the 4×4 Schur complement): the unit vector's residual |P(λ) x| is round-off times the
    // size of P(λ) and the conditioning of the Schur step (|μ| ≥ 1e-3 (1 + |λ|²), so ≤ 1e3):
    // 1e-10 relative, where a wrong eigenvector has a residual of order one.
    let mut rng = Rng(41);
    let (mut schur, mut full, mut worst) = (0, 0, 0.0f64);
    for _ in 0..300 {
        let mut d = random_input(&mut rng);
        d.anisotropy = AnisotropyInput::Direct(rng.range(0.0, 0.5 * d.c_sigma).min(0.2));
        let h_s = d.h_s;
        let m = SpatialModel::from_dimensionless(&d).unwrap();
        for w in [0.001, rng.range(0.05, 5.0)] {
            for balls in [Balls::Free, Balls::Locked] {
                let (p, ev) = eigenvalues_at(&m, w, balls).unwrap();
                for &lam in &ev {
                    let x = pencil_null_vector(&p, lam);
                    let nx: f64 = x.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
                    assert!((nx - 1.0).abs() < 1e-12, "not unit: {nx}");
                    let (mut res, mut size) = (0.0f64, 0.0f64);
                    for i in 0..p.n {
                        let mut v = Complex64::new(0.0, 0.0);
                        for j in 0..p.n {
                            let e = lam * lam * p.m[i][j] + lam * p.g[i][j] + p.k[i][j];
                            v += e * x[j];
                            size = size.max(e.norm());
                        }
                        res = res.max(v.norm());
                    }
                    worst = worst.max(res / size);
                    assert!(res < 1e-10 * size, "Ω = {w}, λ = {lam}: |P(λ)x| = {res:e}, |P| = {size:e}");
                    if balls == Balls::Free {
                        let mu = lam * lam + h_s * lam;
                        if mu.norm_sqr() >= 1e-6 * (1.0 + (lam * lam).norm_sqr()) {
                            schur += 1;
                        } else {
                            full += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(schur > 5000 && full > 300, "both paths: {schur} Schur, {full} full");
    eprintln!("worst relative residual {worst:e} ({schur} Schur, {full} 6×6)");
}

#[test]
fn root_continuation_mirrors_conjugates_and_refuses_overlapping_disks() {
    // From starts 1e-4 off the QR eigenvalues (conjugate-symmetric, as the Campbell lines
    // are, or not), the continued roots are the eigenvalues to 1e-11 (inclusion radius at
    // round-off); two starts drawn to one root give overlapping disks: None, never a spectrum
    // with a root missing.
    let mut rng = Rng(43);
    for _ in 0..200 {
        let m = random_model(&mut rng);
        let w = rng.range(0.05, 5.0);
        let sp = SpeedPolynomial::new(&Pencil::terms(&m, Balls::Free).unwrap()).unwrap();
        let c = sp.at(w);
        let ev = eigenvalues_at(&m, w, Balls::Free).unwrap().1;
        let kick = Complex64::new(rng.range(-1e-4, 1e-4), rng.range(-1e-4, 1e-4));
        let symmetric: Vec<Complex64> = ev.iter().map(|z| if z.im >= 0.0 { z + kick } else { z + kick.conj() }).collect();
        let asymmetric: Vec<Complex64> = ev.iter().map(|z| z + kick).collect();
        for starts in [&symmetric, &asymmetric] {
            let mut out = [Complex64::new(0.0, 0.0); 12];
            if continue_roots(&c[..=12], starts, &mut out).is_some() {
                assert!(match_dist(&out, &ev) < 1e-11, "Ω = {w}: {out:?} vs {ev:?}");
                for (o, s) in out.iter().zip(starts.iter()) {
                    assert!((o - s).norm() < 1e-3, "a root continued from the wrong start");
                }
            }
        }
        // the first upper root twice, its conjugate twice: overlapping disks
        let k = ev.iter().position(|z| z.im > 0.0).unwrap();
        let l = ev.iter().position(|z| z.im > 0.0 && (z - ev[k]).norm() > 1e-3).unwrap();
        let mut dup = symmetric.clone();
        dup[l] = dup[k];
        let lc = ev.iter().position(|z| (z - ev[l].conj()).norm() < 1e-12).unwrap();
        let kc = ev.iter().position(|z| (z - ev[k].conj()).norm() < 1e-12).unwrap();
        dup[lc] = dup[kc];
        let mut out = [Complex64::new(0.0, 0.0); 12];
        assert!(continue_roots(&c[..=12], &dup, &mut out).is_none(), "Ω = {w}: a duplicated start certified");
    }
}

#[test]
fn campbell_lines_of_a_coarse_grid_are_the_fine_grids_lines() {
    // Tracking never switches branches: the default rotor's lines (balls free and locked) on a
    // grid 10× coarser (h = 0.02) are, line by line, the same eigenvalues as on the fine grid
    // (h = 0.002, where no line moves by more than 4h, see above) at the shared speeds, up to
    // conjugation: where a complex pair meets on the real axis and splits into two real
    // eigenvalues (Ω ≈ 2.12 here) which real branch continues the upper line is arbitrary,
    // and a pair and its conjugate are one real motion.
    let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
    let fine: Vec<f64> = (0..2500).map(|i| 0.001 + 0.002 * i as f64).collect();
    let coarse: Vec<f64> = fine.iter().step_by(10).copied().collect();
    for balls in [Balls::Free, Balls::Locked] {
        let f = campbell(&m, &fine, balls).unwrap();
        let c = campbell(&m, &coarse, balls).unwrap();
        assert_eq!(f.lines.len(), c.lines.len());
        for (lf, lc) in f.lines.iter().zip(&c.lines) {
            for (k, mc) in lc.modes.iter().enumerate() {
                let mf = &lf.modes[10 * k];
                let d = ((mf.re - mc.re).powi(2) + (mf.im.abs() - mc.im.abs()).powi(2)).sqrt();
                assert!(d < 1e-9, "{balls:?}: Ω = {}: coarse line at {} {}, fine at {} {}", coarse[k], mc.re, mc.im, mf.re, mf.im);
                assert_eq!(mf.group, mc.group, "{balls:?}: Ω = {}", coarse[k]);
            }
        }
    }
}

#[test]
fn pencil_polynomial_is_the_speed_polynomial_at_that_speed() {
    // Two routes to det(M λ² + G λ + K)/det M at one speed: the expansion of the pencil at Ω
    // (boundary tracing) and the expansion in (λ, Ω) evaluated at Ω (maps, Campbell). They agree
    // to the rounding of the sums, bounded by 1e-13 times Σ_j |c_kj| |Ω|^j (the terms summed).
    let mut rng = Rng(47);
    for _ in 0..300 {
        let m = random_model(&mut rng);
        let w = rng.range(0.0, 6.0);
        for balls in [Balls::Free, Balls::Locked] {
            let p = Pencil::new(&m, w, balls).unwrap();
            let n = p.states();
            let a = autobal::linalg::charpoly::pencil_polynomial(&p).unwrap();
            let sp = SpeedPolynomial::new(&Pencil::terms(&m, balls).unwrap()).unwrap();
            let (c, mag) = (sp.at(w), sp.magnitudes(w));
            for k in 0..=n {
                assert!((a[n - k] - c[k]).abs() <= 1e-13 * mag[k].max(1.0), "Ω = {w}, c_{k}: {} vs {}", a[n - k], c[k]);
            }
        }
    }
}
