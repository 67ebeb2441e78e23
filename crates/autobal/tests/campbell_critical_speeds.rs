//! The critical speeds of the fixed-axes Campbell diagram ([`autobal::spatial::campbell`]) are a
//! property of the model: the same on every speed grid, each one a crossing of a circular
//! component of the state matrix's spectrum with `hΩ` checked on its own, and an isotropic
//! rotor's (circular modes) without minor components.

use autobal::config;
use autobal::spatial::campbell::{fixed_axes, CriticalSpeed};
use autobal::spatial::linear_model::{Balls, Pencil};
use autobal::spatial::params::SpatialModel;
use autobal::spatial::stability::{campbell, Whirl};

mod common;
use common::{direct_model as model, Rng};

use common::{campbell_grid as grid, dimensional_model as dimensional};

fn crossings(m: &SpatialModel, omegas: &[f64], balls: Balls, h: &[u32]) -> Vec<CriticalSpeed> {
    let c = campbell(m, omegas, balls).unwrap();
    fixed_axes(m, &c, balls, h).unwrap().critical_speeds
}

/// The eigenvalues of the state matrix at `w`.
fn spectrum(m: &SpatialModel, w: f64, balls: Balls) -> Vec<num_complex::Complex64> {
    let p = Pencil::new(m, w, balls).unwrap();
    autobal::linalg::eigen::eigenvalues(&p.state_matrix(), p.states()).unwrap()
}

/// Independent check of one crossing on the spectrum at its speed. Bisection stops at 1e-13
/// relative and `|d(ν̂ − cΩ)/dΩ|` is below ~50 for these rotors away from the real axis, so a
/// component meets `hΩ` to 1e-9 relative; on the real axis (`h = 1`, share 1) the number of
/// real eigenvalues (`|Im λ| ≤ 1e-10`, the band of the search) differs 1e-8 relative either
/// side (a collision leaves the axis like `sqrt(Ω − Ω*)`, ≫ 1e-10 at 1e-8, a passage linearly:
/// the search merges its band, ~1e-10/slope, into one speed, so the check steps past it).
/// Away from the axis the component's share is recomputed from nalgebra's SVD null vector.
fn check(m: &SpatialModel, k: &CriticalSpeed, balls: Balls, what: &str) {
    let w = k.omega;
    let h = k.harmonic as f64;
    let tol = 1e-9 * (h * w).max(1.0);
    assert!((k.frequency - h * w).abs() <= 1e-15 * (h * w).max(1.0), "{what}: {k:?}");
    let ev = spectrum(m, w, balls);
    if k.harmonic == 1 && k.whirl == Whirl::Forward {
        assert_eq!(k.share, 1.0, "{what}: a forward 1× crossing is ν = 0, the whole motion: {k:?}");
        let real = |x: f64| spectrum(m, x, balls).iter().filter(|z| z.im.abs() <= 1e-10 * x.max(1.0)).count();
        let d = 1e-8 * w.max(1.0);
        let (a, b) = (real(w - d), real(w + d));
        let c = real(w);
        assert!(a != b || c != a, "{what}: no pair reaches the real axis at Ω = {w}: {a} {c} {b} real eigenvalues");
        assert!(ev.iter().any(|z| z.im.abs() <= 1e-6), "{what}: no real eigenvalue at Ω = {w}");
    } else {
        // Ω + ν̂ = hΩ (forward) or Ω − ν̂ = −hΩ (backward)
        let c = if k.whirl == Whirl::Forward { h - 1.0 } else { h + 1.0 };
        let lam =
            ev.iter().map(|z| num_complex::Complex64::new(z.re, z.im.abs())).min_by(|a, b| (a.im - c * w).abs().total_cmp(&(b.im - c * w).abs())).unwrap();
        let best = (lam.im - c * w).abs();
        assert!(best <= tol, "{what}: no component at {h}Ω at Ω = {w}: off by {best:e}");
        // the share, from nalgebra's SVD null vector of A − λI (y = (q, q'), q in (ξ, η) pairs):
        // Σ|q_ξ + i q_η|² over the total, the Ω + ν̂ component's; a simple eigenvalue's vector
        // is accurate to ~1e-12 here, 1e-7 leaves room for a close neighbour
        let p = Pencil::new(m, w, balls).unwrap();
        let (a, ns) = (p.state_matrix(), p.states());
        let mat = nalgebra::DMatrix::from_fn(ns, ns, |i, j| {
            nalgebra::Complex::new(a[i][j], 0.0) - if i == j { nalgebra::Complex::new(lam.re, lam.im) } else { nalgebra::Complex::new(0.0, 0.0) }
        });
        let svd = mat.svd(false, true);
        let vt = svd.v_t.unwrap();
        let (imin, _) = svd.singular_values.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).unwrap();
        let x: Vec<nalgebra::Complex<f64>> = (0..ns / 2).map(|i| vt[(imin, i)].conj()).collect();
        let i1 = nalgebra::Complex::new(0.0, 1.0);
        let (mut fw, mut bw) = (0.0, 0.0);
        for g in 0..ns / 4 {
            fw += (x[2 * g] + i1 * x[2 * g + 1]).norm_sqr();
            bw += (x[2 * g] - i1 * x[2 * g + 1]).norm_sqr();
        }
        let up = fw / (fw + bw);
        let want = if k.whirl == Whirl::Forward { up } else { 1.0 - up };
        assert!((k.share - want).abs() <= 1e-7, "{what}: share {} vs nalgebra's {want} at Ω = {w}", k.share);
        assert!(k.share > 1e-9 && k.share <= 1.0, "{what}: share {}", k.share);
    }
}

/// Two lists of crossings equal: count, harmonic, whirl, speed to 1e-8 relative (bisection to
/// 1e-13 on the same eigenvalues; the bracketing grid points differ), share to 1e-6 (the
/// eigenvector at speeds 1e-13 apart).
fn same(a: &[CriticalSpeed], b: &[CriticalSpeed], what: &str) {
    let list = |v: &[CriticalSpeed]| {
        v.iter().map(|k| format!("{:.10}{}{}", k.omega, if k.whirl == Whirl::Forward { "f" } else { "b" }, k.harmonic)).collect::<Vec<_>>()
    };
    assert_eq!(a.len(), b.len(), "{what}: {:?} vs {:?}", list(a), list(b));
    for (x, y) in a.iter().zip(b) {
        assert!((x.omega - y.omega).abs() <= 1e-8 * y.omega.max(1.0), "{what}: {x:?} vs {y:?}");
        assert_eq!((x.harmonic, x.whirl), (y.harmonic, y.whirl), "{what}: {x:?} vs {y:?}");
        assert!((x.share - y.share).abs() <= 1e-6, "{what}: {x:?} vs {y:?}");
        // the overdamped mark is the model's too (its half-power points located on the
        // spectrum), not the grid's (review 33)
        assert_eq!(x.overdamped, y.overdamped, "{what}: {x:?} vs {y:?}");
    }
}

#[test]
fn the_dimensional_examples_critical_speeds_do_not_depend_on_the_grid() {
    // `autobal campbell examples/dimensional.toml` gave 12, 14 or 13 critical speeds by grid:
    // the followed component switched at a share near ½ on some grids (a jump of 2|ν| across
    // the 1× line read as crossings), and a divergence range 4e-5 wide at Ω ≈ 1.1292 fell
    // between grid points on others. Grids of 500 to 4000 speeds, harmonics 1 and 2.
    let m = dimensional();
    let w = 2.2;
    let reference = crossings(&m, &grid(w, 1000), Balls::Free, &[1, 2]);
    for k in &reference {
        check(&m, k, Balls::Free, "dimensional.toml");
    }
    // the tiny divergence range: both ends
    let tiny: Vec<f64> = reference.iter().filter(|k| k.harmonic == 1 && (k.omega - 1.12926).abs() < 1e-4).map(|k| k.omega).collect();
    assert_eq!(tiny.len(), 2, "{tiny:?}");
    for n in [500, 1001, 2000, 2001, 4000] {
        same(&crossings(&m, &grid(w, n), Balls::Free, &[1, 2]), &reference, &format!("{n} speeds"));
    }
    eprintln!("{} critical speeds on every grid", reference.len());
}

#[test]
fn random_anisotropic_rotors_critical_speeds_do_not_depend_on_the_grid() {
    // damped rotors with free balls and an anisotropic inertia (ΔĀ ≠ 0), on grids of 300, 301,
    // 757 and 1500 speeds; each crossing checked on the spectrum
    let mut rng = Rng(2026);
    let mut total = 0;
    for case in 0..3 {
        let c_sigma = rng.range(0.4, 1.4);
        let m = model(
            c_sigma,
            rng.range(0.2, 0.8),
            rng.range(0.2, 1.2),
            rng.range(-0.8, 0.8),
            rng.range(0.03, 0.2).min(0.5 * c_sigma),
            rng.range(0.01, 0.1),
            rng.range(0.01, 0.3),
            Some((rng.range(0.01, 0.1), rng.range(0.0, 1.0))),
        );
        let w = 3.0;
        let reference = crossings(&m, &grid(w, 1500), Balls::Free, &[1, 2]);
        for k in &reference {
            check(&m, k, Balls::Free, &format!("case {case}"));
        }
        for n in [300, 301, 757] {
            same(&crossings(&m, &grid(w, n), Balls::Free, &[1, 2]), &reference, &format!("case {case}, {n} speeds"));
        }
        total += reference.len();
    }
    eprintln!("{total} crossings on 3 rotors, the same on every grid");
    assert!(total >= 6, "only {total} crossings compared");
}

#[test]
fn an_isotropic_rotor_has_no_minor_components() {
    // ΔĀ = 0, balls locked: every mode is circular (shares 0 and 1 to round-off), so no
    // crossing of a minor component; the undamped rotor's translation modes whirl at ±1, each
    // crossing 1× at Ω = 1 (forward: ν passes through 0, one speed; backward: ν̂ = 2Ω), the
    // damped one's crossings are where each circular mode's frequency meets hΩ. Every
    // crossing is checked on the spectrum.
    for (hx, hs) in [(0.0, 0.0), (0.05, 0.1)] {
        let m = model(0.6, 0.4, 0.5, 0.0, 0.0, hx, hs, None);
        for n in [600, 601] {
            let ks = crossings(&m, &grid(3.0, n), Balls::Locked, &[1, 2]);
            assert!(!ks.is_empty());
            for k in &ks {
                assert!(k.share >= 1.0 - 1e-9, "damping {hx}: a minor component crosses: {k:?}");
                check(&m, k, Balls::Locked, &format!("isotropic, damping {hx}"));
            }
            if hx == 0.0 {
                for w in [Whirl::Forward, Whirl::Backward] {
                    let at1: Vec<_> = ks.iter().filter(|k| k.harmonic == 1 && k.whirl == w && (k.omega - 1.0).abs() < 1e-9).collect();
                    assert_eq!(at1.len(), 1, "{w:?}: {ks:?}");
                }
            }
        }
    }
}

/// Two lists of crossings the same to 1e-9 relative: both are bisected to 1e-13 on the same
/// spectrum (on the count of real eigenvalues for `h = 1` forward, on `ν̂ − cΩ` otherwise);
/// only the brackets differ with the grid. Shares to 1e-6 (eigenvectors at speeds 1e-13 apart),
/// the overdamped marks equal.
fn identical(a: &[CriticalSpeed], b: &[CriticalSpeed], what: &str) {
    let list = |v: &[CriticalSpeed]| {
        v.iter().map(|k| format!("{:.10}{}{}", k.omega, if k.whirl == Whirl::Forward { "f" } else { "b" }, k.harmonic)).collect::<Vec<_>>()
    };
    assert_eq!(a.len(), b.len(), "{what}: {:?} vs {:?}", list(a), list(b));
    for (x, y) in a.iter().zip(b) {
        assert!((x.omega - y.omega).abs() <= 1e-9 * y.omega.abs().max(1.0), "{what}: {x:?} vs {y:?}");
        assert_eq!((x.harmonic, x.whirl), (y.harmonic, y.whirl), "{what}: {x:?} vs {y:?}");
        assert!((x.share - y.share).abs() <= 1e-6, "{what}: {x:?} vs {y:?}");
        // the overdamped mark is the model's too (its half-power points located on the
        // spectrum), not the grid's (review 33)
        assert_eq!(x.overdamped, y.overdamped, "{what}: {x:?} vs {y:?}");
    }
}

#[test]
fn the_dimensional_examples_critical_speeds_are_the_same_on_coarse_grids() {
    // grids of 240 (the report's) to 520 speeds missed a stretch off the real axis between two
    // grid points on it (1.148153-1.151660) and the exit where a pair lands on the axis and
    // swaps partners: 13 or 14 crossings of 1× instead of 16 (22 with 2×). The ends are now
    // bisected on the count of real eigenvalues itself.
    let m = dimensional();
    let w = 2.2;
    let reference = crossings(&m, &grid(w, 1000), Balls::Free, &[1, 2]);
    let stretch = reference.iter().filter(|k| k.harmonic == 1 && k.omega > 1.148 && k.omega < 1.152).count();
    assert_eq!(stretch, 2, "{reference:?}");
    for n in [240, 300, 401, 520] {
        identical(&crossings(&m, &grid(w, n), Balls::Free, &[1, 2]), &reference, &format!("{n} speeds"));
    }
}

/// The general route's crossings (`rotor_campbell::fixed_view`) of `rotor` on `n` speeds up to `w`.
fn general(rotor: &autobal::rotor_stability::Rotor, w: f64, n: usize, h: &[u32]) -> Vec<CriticalSpeed> {
    let c = autobal::rotor_campbell::campbell_over_speed(rotor, &grid(w, n)).unwrap();
    autobal::rotor_campbell::fixed_view(rotor, Balls::Free, &c, h).unwrap().critical_speeds
}

#[test]
fn the_general_routes_critical_speeds_do_not_depend_on_the_grid() {
    // before, the general route located the crossings of the drawn curves, whose switches of
    // component read as crossings on some grids (linear_rotor_shaft.toml: 13 at 500 speeds,
    // 11 at 300), and gave a forward 1× crossing share 1 without checking ν = 0 there. Now the
    // search is the 12-state route's, on the stationary state's spectrum.
    use autobal::rotor_stability::Rotor;
    let root = config::parse(include_str!("../../../examples/planar.toml"), "test").unwrap();
    let planar = Rotor::Planar(config::planar(&root).unwrap().rotor);
    let root = config::parse(include_str!("../../../examples/linear_rotor_shaft.toml"), "test").unwrap();
    // the model the commands run: reduced to `linear_rotor.modes = 4` mode pairs
    let cfg = autobal::linear_rotor::config::linear_rotor(&root, &mut |_| Err("no files".into())).unwrap();
    let linear = Rotor::Linear(autobal::linear_rotor::reduce::reduce(&cfg.rotor, cfg.modes.unwrap(), &[]).unwrap().rotor);
    // speeds up to 3 ω_n (the command's default) on the planar rotor, up to 2500 rad/s on the
    // shaft (its default 1.5 times the 4th natural frequency is ~2700): 5 and 23 crossings (21
    // before session 33, without the two ends of the shaft's exchange at 373.576 and 374.635)
    let cases = [
        ("planar.toml", &planar, 3.0 * planar.natural_frequency(), 1000, &[60, 100, 150, 240, 401][..], 5),
        ("linear_rotor_shaft.toml", &linear, 2500.0, 240, &[60, 100, 150][..], 23),
    ];
    for (name, rotor, w, fine, grids, count) in cases {
        let reference = general(rotor, w, fine, &[1, 2]);
        assert_eq!(reference.len(), count, "{name}: {reference:?}");
        for k in &reference {
            if k.harmonic == 1 && k.whirl == Whirl::Forward {
                assert_eq!(k.share, 1.0, "{name}: {k:?}");
            } else {
                assert!(k.share > 1e-9 && k.share <= 1.0, "{name}: {k:?}");
            }
        }
        // The shaft's forward pair at 374.6348 rad/s, left out of this comparison until session
        // 33 as a near miss of the axis seen only on some grids (150 speeds), lands on it: an
        // independent numpy model has ν̂ = 0.102 at 374.634 and two real eigenvalues −3.856,
        // −3.708 at 374.635. It was the start of a run to the last speed, left out where judged
        // in its step and listed where a window found it; as one end of an exchange
        // (spatial::campbell::exchanges) it is now listed on every grid, and compared.
        for &n in grids {
            identical(&general(rotor, w, n, &[1, 2]), &reference, &format!("{name}, {n} speeds"));
        }
        eprintln!("{name}: {} critical speeds on every grid", reference.len());
    }
}

/// The model of an example of the closed-form route, as [`dimensional`] reads it.
fn example(toml: &str) -> SpatialModel {
    let mut root = config::parse(toml, "test").unwrap();
    for t in ["drive", "initial"] {
        root.remove(t);
    }
    config::spatial_simulation(&root).unwrap().config.model
}

#[test]
fn an_end_of_a_run_from_the_first_speed_is_no_crossing_on_any_grid() {
    // washing_machine.toml: two near-zero real eigenvalues, real from the first speed, meet at
    // Ω = 0.630864 and leave the axis (the end of a run from the first speed: no crossing);
    // another pair leaves it 0.0107 earlier, at 0.620133 (a crossing). Before, one quiet flag
    // per grid step ("all movers quiet") was given to every change of the count in it, so on
    // grids where both share a step (60, 100, 240 = the report's, 300 speeds) the quiet end was
    // reported too. The speeds: those of `autobal campbell --config
    // examples/washing_machine.toml` (0.050388668616103 is its first speed at 60 points).
    let m = example(include_str!("../../../examples/washing_machine.toml"));
    let w = 0.050388668616103 * 120.0;
    let reference = crossings(&m, &grid(w, 1000), Balls::Free, &[1]);
    let near = |v: &[CriticalSpeed], at: f64| v.iter().filter(|k| k.harmonic == 1 && k.whirl == Whirl::Forward && (k.omega - at).abs() < 1e-5).count();
    assert_eq!(near(&reference, 0.620133), 1, "{reference:?}");
    assert_eq!(near(&reference, 0.630864), 0, "{reference:?}");
    for n in [60, 100, 240, 300] {
        identical(&crossings(&m, &grid(w, n), Balls::Free, &[1]), &reference, &format!("{n} speeds"));
    }
    // dimensional.toml on 60 speeds: a quiet end at 0.954097 shared a step with a crossing
    let d = dimensional();
    let got = crossings(&d, &grid(2.2, 60), Balls::Free, &[1]);
    assert!(got.iter().all(|k| (k.omega - 0.954097).abs() > 1e-5), "{got:?}");
}

#[test]
fn two_pairs_changing_realness_in_one_step_are_both_searched() {
    // linear_rotor_windows.toml (4 mode pairs, as the command runs it), harmonic 1: in the
    // step [534, 538] of 500 speeds a pair lands on the real axis (535.529) and another leaves
    // it (534.593, a forward 1× crossing), so the count of real eigenvalues is the same at both
    // ends; the tracker swapped labels there and the leaving line was skipped because its
    // conjugate (not itself changing realness on the grid) had a smaller index. Also missed on
    // 100 and 240 speeds; found on 1000 and 8000. Also, a landing on the axis that its step
    // judged the start of a run to the last speed (176.797) was reported on 60-240 speeds when
    // a window around a local minimum of another line's ν̂ found it too. Since session 14
    // (campbell_grid_14.rs) that landing is a crossing on every grid: like 535.529 it leaves
    // one real eigenvalue on the axis to the end and one that leaves at 1162.95, so 1000
    // speeds give 7 forward 1× crossings, and 100, 240 and 500 the same.
    use autobal::rotor_stability::Rotor;
    let root = config::parse(include_str!("../../../examples/linear_rotor_windows.toml"), "test").unwrap();
    let cfg = autobal::linear_rotor::config::linear_rotor(&root, &mut |_| Err("no files".into())).unwrap();
    let rotor = Rotor::Linear(autobal::linear_rotor::reduce::reduce(&cfg.rotor, cfg.modes.unwrap(), &[]).unwrap().rotor);
    let reference = general(&rotor, 2000.0, 1000, &[1]);
    let forward = reference.iter().filter(|k| k.whirl == Whirl::Forward).count();
    assert_eq!(forward, 7, "{reference:?}");
    for n in [100, 240, 500] {
        let got = general(&rotor, 2000.0, n, &[1]);
        let found = got.iter().filter(|k| k.whirl == Whirl::Forward && (k.omega - 534.592578).abs() < 1e-4).count();
        assert_eq!(found, 1, "{n} speeds: {got:?}");
        identical(&got, &reference, &format!("{n} speeds"));
    }
}
