//! The critical speeds of the fixed-axes Campbell diagram do not depend on the speed grid the
//! diagram is drawn on (issue 18 item 3, round 3 session 13): a coarse grid finds what a fine
//! one finds, with the same mode numbers.

use autobal::config;
use autobal::spatial::campbell::{fixed_axes, CriticalSpeed};
use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::SpatialModel;
use autobal::spatial::stability::campbell;

/// The model of examples/dimensional.toml (anisotropic supports, two balls at balance).
fn dimensional() -> SpatialModel {
    let mut root = config::parse(include_str!("../../../examples/dimensional.toml"), "test").unwrap();
    for t in ["drive", "initial"] {
        root.remove(t);
    }
    config::spatial_simulation(&root).unwrap().config.model
}

/// `n` speeds `w (k + ½)/n` (the grid of `autobal campbell --points n`).
fn grid(w: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| w * (k as f64 + 0.5) / n as f64).collect()
}

fn crossings(m: &SpatialModel, omegas: &[f64], balls: Balls, h: &[u32]) -> Vec<CriticalSpeed> {
    let c = campbell(m, omegas, balls).unwrap();
    fixed_axes(m, &c, balls, h).unwrap().critical_speeds
}

/// 40 speeds (`autobal campbell --points 40`) and 400 over the same range give the same
/// crossings, with the same harmonic, whirl and mode number, and speeds equal to
/// 1e-9 relative (both bisected on the model's spectrum to 1e-13; the tolerance of
/// campbell_critical_speeds.rs, whose `check` tests each crossing on its own against the
/// spectrum). On main at e3f0650 the 40-speed grid missed the 4e-5-wide divergence range at
/// 1.1292 and the stretch off the axis 1.148153-1.151660 and gave three 1× crossings (1.174,
/// 1.567, 1.610) another mode; the balls locked (8 states) agree as well.
#[test]
fn forty_and_four_hundred_speeds_give_the_same_crossings() {
    let m = dimensional();
    for balls in [Balls::Free, Balls::Locked] {
        let coarse = grid(2.5, 40);
        let (lo, hi) = (coarse[0], coarse[39]);
        let a = crossings(&m, &coarse, balls, &[1, 2]);
        // the same range (the end of a run off the axis that starts before the first speed is
        // no crossing on either: the balls' stretch 0.0272-0.0922 starts below 0.03125)
        let fine: Vec<f64> = (0..400).map(|k| lo + (hi - lo) * k as f64 / 399.0).collect();
        let b = crossings(&m, &fine, balls, &[1, 2]);
        assert!(b.len() >= 10, "{balls:?}: {b:?}");
        assert_eq!(a.len(), b.len(), "{balls:?}:\n{a:?}\n{b:?}");
        for (p, q) in a.iter().zip(&b) {
            assert!((p.omega - q.omega).abs() <= 1e-9 * q.omega, "{balls:?}: {p:?} vs {q:?}");
            assert_eq!((p.harmonic, p.whirl, p.curve), (q.harmonic, q.whirl, q.curve), "{balls:?}: {p:?} vs {q:?}");
        }
    }
}
