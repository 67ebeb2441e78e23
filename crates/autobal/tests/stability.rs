//! Linear stability: the eigen-solver against nalgebra and the pencil's determinant, the
//! textbook limits, and the analytic critical speeds.

use autobal::spatial::critical_speeds::critical_speeds_at;
use autobal::linalg::eigen::{characteristic_polynomial, complex_det, eigenvalues, routh_hurwitz_stable};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, Mat12, Pencil};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
use autobal::spatial::stability::{campbell, eigenvalues_at, margin, stability_ranges, Group, Whirl};
use num_complex::Complex64;

mod common;
use common::Rng;

#[allow(clippy::too_many_arguments)]
fn model(c_sigma: f64, rho: f64, l: f64, z: f64, delta_a: f64, h_x: f64, h_s: f64, balls: Option<(f64, f64)>) -> SpatialModel {
    SpatialModel::from_dimensionless(&DimensionlessInput {
        c_sigma,
        rho_s: rho,
        l_left: l,
        z_a: z,
        anisotropy: AnisotropyInput::Direct(delta_a),
        h_x,
        h_s,
        method: AnisotropyMethod::Exact,
        direct_balls: balls,
    })
    .unwrap()
}

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
        let (j, d) = b
            .iter()
            .enumerate()
            .filter(|(j, _)| !used[*j])
            .map(|(j, y)| (j, (x - y).norm()))
            .min_by(|p, q| p.1.total_cmp(&q.1))
            .unwrap();
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
            let mat: Vec<Vec<Complex64>> =
                (0..p.n).map(|i| (0..p.n).map(|j| lam * lam * p.m[i][j] + lam * p.g[i][j] + p.k[i][j]).collect()).collect();
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
        for mu in quad(Complex64::new(h, 0.0), Complex64::new(1.0, 0.0))
            .into_iter()
            .chain(quad(ha - i * cs * w, Complex64::new(m.p_alpha_sq, 0.0)))
        {
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
        for r in &st.stable_ranges {
            if r.lo > 0.0 {
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
fn two_ball_base_case_frame_is_consistent() {
    // 000's base case with masses: exact anisotropy 0, d_A = [[1 − D', 0], [0, 1 + D']], D' = −0.5
    let m = SpatialModel::from_dimensionless(&DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left: 0.8,
        z_a: 0.8,
        anisotropy: AnisotropyInput::Masses { masses: MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 }, d_a: None },
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: None,
    })
    .unwrap();
    let b = m.balls.unwrap();
    assert!((b.d_a[0][0] - 1.5).abs() < 1e-15 && (b.d_a[1][1] - 0.5).abs() < 1e-15);
    assert_eq!(b.d_a[0][1], 0.0);
    assert!(stability_ranges(&m, 6.0, 300, Balls::Free, 1e-9).is_ok());
}


#[test]
fn undamped_model_has_lagrangian_structure() {
    // Scaling the ball rows by S = (2/m̄) d_A⁻¹ must make M and K symmetric and G skew when all
    // damping is zero: the linearisation of a conservative gyroscopic system. A sign slip in any
    // coupling block of eq (6) breaks this.
    let mut rng = Rng(29);
    for _ in 0..200 {
        let c_sigma = rng.range(0.2, 1.6);
        let m = model(c_sigma, rng.range(0.2, 0.8), rng.range(-0.3, 1.4), rng.range(-1.0, 1.0), rng.range(0.0, 0.2).min(0.5 * c_sigma), 0.0, 0.0, Some((rng.range(0.01, 0.1), rng.range(0.0, 0.9))));
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
