//! The margin map's spectral abscissa against an independent dense eigen-solver (nalgebra's
//! real Schur form) at random cells of random rotors.

use autobal::control::Control;
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, StateSpace};
use autobal::spatial::map::{stability_map, Axis, MapSettings, Quantity};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
use autobal::spatial::paths::{SpatialInput, SpatialSpec};

mod common;
use common::Rng;

/// `max Re λ` of the state matrix by nalgebra's Schur decomposition, and `max |λ|`.
fn nalgebra_abscissa(ss: &StateSpace, w: f64) -> (f64, f64) {
    let a = ss.at(w);
    let n = ss.states;
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| a[i][j]);
    let s = nalgebra::linalg::Schur::try_new(m, 1e-15, 10_000).expect("nalgebra converges");
    let ev = s.complex_eigenvalues();
    (ev.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max), ev.iter().map(|z| z.norm()).fold(0.0, f64::max))
}

#[test]
fn margin_map_cells_are_the_dense_solvers_abscissa() {
    // Every cell of a margin map (continuation of the rightmost root of the characteristic
    // polynomial, certified by Newton's inclusion radius and a Routh count; QR where it cannot
    // certify) against max Re λ from nalgebra's Schur form of the state matrix, at random cells
    // of maps of random rotors, balls free and locked. The map's answer is certified to
    // `ACCEPT (1 + |λ|) + GAP = 1e-10 (1 + |λ|) + 1e-12`; a backward-stable dense solver is
    // within ~n ε ‖A‖ κ of the exact abscissa (1e-13 here for the well-separated rightmost
    // eigenvalues of these models), so 1e-10 (1 + max |λ|) bounds the difference; a wrong
    // eigenvalue (another root overtaking unseen) differs by O(0.01-1).
    let mut rng = Rng(20_261_128);
    let (mut checked, mut worst) = (0, 0.0f64);
    for _ in 0..16 {
        let c_sigma = rng.range(0.2, 1.6);
        let d = DimensionlessInput {
            c_sigma,
            rho_s: rng.range(0.2, 0.8),
            l_left: rng.range(-0.3, 1.4),
            z_a: rng.range(-1.0, 1.0),
            // 2 ΔĀ ≤ C̄Σ (triangle inequality of the principal moments)
            anisotropy: AnisotropyInput::Direct(rng.range(0.0, 0.2).min(0.5 * c_sigma)),
            h_x: rng.range(0.0, 0.2),
            h_s: rng.range(0.01, 0.5),
            method: AnisotropyMethod::Exact,
            direct_balls: Some((rng.range(0.005, 0.1), rng.range(0.0, 1.0))),
        };
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
        let x = Axis::linspace("dimensionless.z_a", d.z_a - 0.5, d.z_a + 0.5, 5);
        let y = Axis::linspace("omega", 0.05, 6.0, 400);
        for balls in [Balls::Free, Balls::Locked] {
            let s = MapSettings { balls, quantity: Quantity::Margin, omega: None };
            let mut rows = vec![];
            stability_map(&spec, &x, &y, &s, &Control::none(), &mut |_, r| {
                rows.push(r.to_vec());
                true
            })
            .unwrap();
            for _ in 0..40 {
                let i = (rng.next() * x.values.len() as f64) as usize;
                let j = (rng.next() * y.values.len() as f64) as usize;
                let mut di = d;
                di.z_a = x.values[i];
                let ss = StateSpace::new(&SpatialModel::from_dimensionless(&di).unwrap(), balls).unwrap();
                let (want, size) = nalgebra_abscissa(&ss, y.values[j]);
                let got = rows[j][i].margin;
                let err = (got - want).abs() / (1.0 + size);
                worst = worst.max(err);
                assert!(err <= 1e-10, "z_a = {}, Ω = {}, {balls:?}: map {got} vs nalgebra {want}", x.values[i], y.values[j]);
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 16 * 2 * 40);
    eprintln!("worst relative difference {worst:e}");
}

#[test]
fn maps_of_many_lines_share_one_plane_polynomial_and_keep_every_cell() {
    // With 16 or more lines along z̄_A (eq (6) is affine in it) each line's characteristic
    // polynomial in Ω comes from one expansion of the whole plane (Horner in z̄_A) instead of
    // its own. Every cell against independent routes: the margin against the QR abscissa of
    // the state matrix at that point (bound as in the margin test above: the certified
    // 1e-10 (1 + |λ|) + 1e-12, with |λ| ≤ 1 + Ω² for these dimensionless models), the verdict
    // against the direct Routh–Hurwitz test on the state matrix (the map confirms every change
    // of verdict by it, so they agree at every cell, whatever polynomial proposed them).
    use autobal::linalg::eigen::spectral_abscissa;
    use autobal::spatial::stability::strictly_stable_at;
    let mut rng = Rng(20_261_129);
    let mut worst = 0.0f64;
    let mut stable = 0;
    for _ in 0..3 {
        let c_sigma = rng.range(0.2, 1.6);
        let d = DimensionlessInput {
            c_sigma,
            rho_s: rng.range(0.2, 0.8),
            l_left: rng.range(-0.3, 1.4),
            z_a: 0.0,
            anisotropy: AnisotropyInput::Direct(rng.range(0.0, 0.2).min(0.5 * c_sigma)),
            h_x: rng.range(0.0, 0.2),
            h_s: rng.range(0.01, 0.5),
            method: AnisotropyMethod::Exact,
            direct_balls: Some((rng.range(0.005, 0.1), rng.range(0.0, 1.0))),
        };
        let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
        let x = Axis::linspace("dimensionless.z_a", -1.5, 1.5, 17);
        let y = Axis::linspace("omega", 0.05, 5.0, 150);
        for q in [Quantity::Margin, Quantity::Verdict] {
            let s = MapSettings { balls: Balls::Free, quantity: q, omega: None };
            let mut rows = vec![];
            stability_map(&spec, &x, &y, &s, &Control::none(), &mut |_, r| {
                rows.push(r.to_vec());
                true
            })
            .unwrap();
            for (i, &z) in x.values.iter().enumerate() {
                let mut di = d;
                di.z_a = z;
                let ss = StateSpace::new(&SpatialModel::from_dimensionless(&di).unwrap(), Balls::Free).unwrap();
                for (j, &w) in y.values.iter().enumerate() {
                    let cell = rows[j][i];
                    match q {
                        Quantity::Margin => {
                            let want = spectral_abscissa(&ss.at(w), ss.states).unwrap();
                            worst = worst.max((cell.margin - want).abs());
                            assert!((cell.margin - want).abs() <= 1e-10 * (1.0 + w * w) + 1e-12, "z_a = {z}, Ω = {w}: {} vs QR {want}", cell.margin);
                        }
                        Quantity::Verdict => {
                            assert_eq!(cell.stable, strictly_stable_at(&ss, w), "z_a = {z}, Ω = {w}");
                            stable += usize::from(cell.stable);
                        }
                    }
                }
            }
        }
    }
    assert!(stable > 100, "{stable}");
    eprintln!("worst difference to QR {worst:e}");
}

#[test]
fn the_margins_three_routes_each_give_the_qr_abscissa() {
    // The tracker of the margin map along lines of random rotors (balls free and locked, 600
    // speeds in [0.05, 6]): at every speed its abscissa against the QR eigenvalues of the state
    // matrix there. Route 1 (the rightmost root by Newton, a Routh count) and route 2 (all
    // roots continued from the last spectrum by Aberth's iteration, disjoint inclusion disks)
    // are certified to ACCEPT (1 + |λ|) + GAP = 1e-10 (1 + |λ|) + 1e-12 of the polynomial's
    // abscissa; the QR abscissa is within ~1e-13 of the exact one for these separated
    // rightmost roots, so 1e-10 (1 + max |λ|) + 1e-12 bounds the difference (a wrong root, an
    // overtake missed, errs by O(0.01-1)). The verdicts (`counts_as_stable`) agree wherever
    // the abscissa is not within 1e-9 of 0. Route 2 must answer some speeds (overtakes occur
    // on these lines), and the counts of the routes are reported.
    use autobal::linalg::charpoly::{AbscissaTracker, SpeedPolynomial};
    use autobal::linalg::eigen::eigenvalues;
    use autobal::spatial::linear_model::Pencil;
    use autobal::spatial::stability::counts_as_stable;
    let mut rng = Rng(202_611_291);
    let (mut routes, mut worst) = ([0usize; 3], 0.0f64);
    for _ in 0..8 {
        let c_sigma = rng.range(0.2, 1.6);
        let d = DimensionlessInput {
            c_sigma,
            rho_s: rng.range(0.2, 0.8),
            l_left: rng.range(-0.3, 1.4),
            z_a: rng.range(-2.0, 2.0),
            anisotropy: AnisotropyInput::Direct(rng.range(0.0, 0.2).min(0.5 * c_sigma)),
            h_x: rng.range(0.0, 0.2),
            h_s: rng.range(0.01, 0.5),
            method: AnisotropyMethod::Exact,
            direct_balls: Some((rng.range(0.005, 0.1), rng.range(0.0, 1.0))),
        };
        let model = SpatialModel::from_dimensionless(&d).unwrap();
        for balls in [Balls::Free, Balls::Locked] {
            let ss = StateSpace::new(&model, balls).unwrap();
            let sp = SpeedPolynomial::new(&Pencil::terms(&model, balls).unwrap()).unwrap();
            let n = ss.states;
            let mut t = AbscissaTracker::new();
            for j in 0..600 {
                let w = 0.05 + (6.0 - 0.05) * j as f64 / 599.0;
                let c = sp.at(w);
                let a = t.abscissa(w, &c[..=n], || eigenvalues(&ss.at(w), n)).unwrap();
                let ev = eigenvalues(&ss.at(w), n).unwrap();
                let qr = ev.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max);
                let size = ev.iter().map(|z| z.norm()).fold(0.0, f64::max);
                let err = (a - qr).abs();
                worst = worst.max(err / (1e-10 * (1.0 + size) + 1e-12));
                assert!(err <= 1e-10 * (1.0 + size) + 1e-12, "Ω = {w}, {balls:?}: tracker {a} vs QR {qr}");
                if qr.abs() > 1e-9 {
                    assert_eq!(counts_as_stable(a, balls), counts_as_stable(qr, balls), "Ω = {w}, {balls:?}");
                }
            }
            routes[0] += t.continued;
            routes[1] += t.all_roots;
            routes[2] += t.fallbacks;
        }
    }
    assert_eq!(routes.iter().sum::<usize>(), 8 * 2 * 600);
    assert!(routes[1] > 0, "overtakes occur on these lines and route 2 answers some: {routes:?}");
    assert!(routes[2] >= 16, "each line starts with the full solver: {routes:?}");
    eprintln!("rightmost root {}, all roots {}, QR {} (first speeds: 16); worst error / bound {worst:e}", routes[0], routes[1], routes[2]);
}

#[test]
fn a_margin_maps_lines_start_from_one_spectrum_per_group_and_keep_every_cell() {
    // From 16 lines on, each group of 16 lines starts from the QR spectrum of its first line at
    // the first speed, continued to the other lines by route 2 (certified, or QR where not):
    // fewer direct solves than lines, and every cell against the QR abscissa of its own state
    // matrix within the certificate 1e-10 (1 + |λ|) + 1e-12 (|λ| ≤ 1 + Ω² for these models,
    // as in the plane test above). The rows and the transposed map (speed on x) hold the same
    // margins bit for bit: the seeds depend only on each group's first line and the first speed.
    use autobal::linalg::eigen::spectral_abscissa;
    let d = DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left: 0.8,
        z_a: 0.0,
        anisotropy: AnisotropyInput::Direct(0.1),
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: Some((0.05, 0.5)),
    };
    let spec = SpatialSpec { input: SpatialInput::Dimensionless(d), delta_a_override: None };
    let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, 40);
    let y = Axis::linspace("omega", 0.05, 4.5, 120);
    let s = MapSettings { balls: Balls::Free, quantity: Quantity::Margin, omega: None };
    let mut rows = vec![];
    let out = stability_map(&spec, &x, &y, &s, &Control::none(), &mut |_, r| {
        rows.push(r.to_vec());
        true
    })
    .unwrap();
    // each line alone (one line: no seed) starts with the QR: the seeded map saves most of the
    // 40 starts (3 groups: 3 QR seeds, 37 starts by route 2 where it certifies)
    let mut alone = 0;
    for &z in &x.values {
        let one = Axis { path: x.path.clone(), values: vec![z] };
        alone += stability_map(&spec, &one, &y, &s, &Control::none(), &mut |_, _| true).unwrap().direct;
    }
    assert!(out.direct + 20 <= alone, "the lines' starts are continued from the groups' seeds: {} vs {alone} alone", out.direct);
    for (i, &z) in x.values.iter().enumerate() {
        let mut di = d;
        di.z_a = z;
        let ss = StateSpace::new(&SpatialModel::from_dimensionless(&di).unwrap(), Balls::Free).unwrap();
        for (j, &w) in y.values.iter().enumerate() {
            let want = spectral_abscissa(&ss.at(w), ss.states).unwrap();
            assert!((rows[j][i].margin - want).abs() <= 1e-10 * (1.0 + w * w) + 1e-12, "z_a = {z}, Ω = {w}: {} vs QR {want}", rows[j][i].margin);
        }
    }
    let mut t = vec![];
    stability_map(&spec, &y, &x, &s, &Control::none(), &mut |_, r| {
        t.push(r.to_vec());
        true
    })
    .unwrap();
    for j in 0..y.values.len() {
        for i in 0..x.values.len() {
            assert_eq!(rows[j][i].margin.to_bits(), t[i][j].margin.to_bits());
        }
    }
}
