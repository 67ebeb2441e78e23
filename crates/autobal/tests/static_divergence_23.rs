//! The divergence threshold (reviews 22 and 23): `ω² < −max(1e-9, 100 N ε) max|ω²|`
//! ([`divergence_threshold`]): the larger of the matrices' data rounding (files to 8 significant
//! digits: a free rotor's rigid-body modes come out genuinely negative, review 23) and the
//! eigen-solver's error bound. On a rotor whose stiffest mode is `1e10 (rad/s)²` a mode at
//! `ω² = −100` (growing at 10 1/s) is named with its `ω²` to the solver's accuracy, the same
//! mode at +100 is a frequency; rigid-body modes (rounding of either sign) are not divergent on
//! rotors of several sizes, nor with the stiffness rounded to 9 significant digits.

use autobal::linear_rotor::shaft::{Disk, ShaftBuilder};
use autobal::linear_rotor::{divergence_threshold, static_divergence, Layout, LinearRotor};

/// 7 nodes `x, y, α, β` (28 DOFs) with `M = diag(m)` and `K = M^½ H D H M^½`, `H` a Householder
/// reflection (`I − 2 v vᵀ / vᵀv`, orthogonal and symmetric, dense), so that `K v = λ M v` has
/// exactly the eigenvalues `D` (`M^-½ K M^-½ = H D H`, similar to `D`): a congruence of a known
/// diagonal, the closed form of the test.
fn congruence(d: &[f64]) -> LinearRotor {
    let n = d.len();
    assert_eq!(n, 28);
    let m: Vec<f64> = (0..n).map(|i| if i % 4 < 2 { 1.0 + (i % 5) as f64 } else { 0.01 * (1.0 + (i % 3) as f64) }).collect();
    let v: Vec<f64> = (0..n).map(|i| 1.0 + ((i * 7) % 11) as f64 / 11.0).collect();
    let vv: f64 = v.iter().map(|x| x * x).sum();
    let h = |i: usize, j: usize| f64::from(u8::from(i == j)) - 2.0 * v[i] * v[j] / vv;
    let mut r = LinearRotor::zeros(7, Layout::TranslationTilt);
    for i in 0..n {
        r.m[i * n + i] = m[i];
        for j in 0..n {
            let hdh: f64 = (0..n).map(|k| h(i, k) * d[k] * h(k, j)).sum();
            r.k[i * n + j] = m[i].sqrt() * hdh * m[j].sqrt();
        }
    }
    // symmetric to the last bit, as a symmetric K is given
    for i in 0..n {
        for j in 0..i {
            r.k[i * n + j] = r.k[j * n + i];
        }
    }
    r
}

/// `D`: the mode under test `first`, two more low ones and the rest spread geometrically up to
/// 1e10 (rad/s)² (the stiffest mode of review 22's ROSS rotor is 1.3e10).
fn spectrum(first: f64) -> Vec<f64> {
    let mut d = vec![first, 40.0, 90.0];
    d.extend((0..25).map(|k| 1e2 * 1e8f64.powf(k as f64 / 24.0)));
    d
}

#[test]
fn a_slow_divergence_on_a_stiff_rotor_is_named_with_its_omega_squared() {
    let r = congruence(&spectrum(-100.0));
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    let threshold = divergence_threshold(&got);
    let div = static_divergence(&got);
    assert_eq!(div.len(), 1, "one mode at ω² = −100 is divergent: {got:?}");
    // the data's 1e-9 · 1e10 = 10 (rad/s)², above the solver's 100 · 28 · ε · 1e10 = 6.2e-3
    assert!((threshold - 1e-9 * 1e10).abs() <= 1e-6 * threshold, "{threshold}");
    // to the solver's accuracy: the eigenvalues of a backward-stable solve are off by at most
    // c N ε max|ω²| (K itself rounded to ε of its entries adds as much)
    let solver = 100.0 * 28.0 * f64::EPSILON * 1e10;
    assert!((div[0] + 100.0).abs() <= solver, "ω² = {} against −100 (solver's bound {solver})", div[0]);
    // the others are the known spectrum, each to the same absolute accuracy
    for (g, w) in got.iter().zip(&spectrum(-100.0)) {
        assert!((g - w).abs() <= solver.max(1e-12 * w.abs()), "{g} vs {w}");
    }
}

#[test]
fn the_same_mode_at_plus_100_is_a_frequency_of_10_rad_s() {
    let r = congruence(&spectrum(100.0));
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    assert!(static_divergence(&got).is_empty(), "{got:?}");
    let w = r.natural_frequencies(&[], false).unwrap();
    // ω = sqrt(100 ± the solver's bound): within bound/20 of 10 rad/s
    // (the lowest are 40 and 90 (rad/s)²: the third)
    assert!((w[2] - 10.0).abs() <= 100.0 * 28.0 * f64::EPSILON * 1e10 / 20.0, "{w:?}");
}

/// Review 23: a free rotor's stiffness written to 9 significant digits (a fixed-width FE
/// export) is not exactly semi-definite; its rigid-body modes come out at up to ~1e-11 of
/// `max|ω²|`, of either sign, above the solver's bound (which called such a rotor statically
/// unstable) and below the data's.
#[test]
fn rigid_body_modes_of_a_stiffness_rounded_to_nine_digits_are_not_divergent() {
    let mut d = spectrum(0.0);
    d[1] = 0.0;
    let mut r = congruence(&d);
    for v in r.k.iter_mut() {
        *v = format!("{v:.8e}").parse().unwrap();
    }
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    let solver = 100.0 * 28.0 * f64::EPSILON * 1e10;
    assert!(got[0] < -solver, "the rounding is above the solver's bound (else this tests nothing): {:?}", &got[..3]);
    assert!(static_divergence(&got).is_empty(), "{:?} (threshold {})", &got[..3], divergence_threshold(&got));
}

#[test]
fn rigid_body_modes_stay_zero_on_rotors_of_several_sizes() {
    // the congruence with two exact zeros (a semi-definite K): not divergent, ω² within the
    // threshold of 0 (rounding of either sign)
    let mut d = spectrum(0.0);
    d[1] = 0.0;
    let got = congruence(&d).natural_frequencies_squared(&[], false).unwrap();
    let threshold = divergence_threshold(&got);
    assert!(static_divergence(&got).is_empty(), "{got:?}");
    assert!(got[..2].iter().all(|l| l.abs() <= threshold), "{got:?} (threshold {threshold})");
    // free shafts of the shaft builder (no bearings: four rigid-body modes, two translations and
    // two tilts): 1, 6 and 50 steel elements (8, 28, 204 DOFs; the stiffest modes 1.6e7 to
    // 1.8e14 (rad/s)²), bare and with a disk and rotary inertia. The rigid-body modes were
    // measured within 2.4e-16 of max|ω²| on these and larger (to 804 DOFs): asserted within a
    // hundredth of the solver's own bound 100 N ε max|ω²| (the threshold, 1e-9 max|ω²|, is far
    // above both)
    for n in [1usize, 6, 50] {
        for dressed in [false, true] {
            let mut b = ShaftBuilder::uniform(n, 0.6, 0.025, 2.1e11, 7850.0);
            b.rotary_inertia = dressed;
            if dressed {
                b.disks.push(Disk { node: n / 2, mass: 4.0, id: 0.01, ip: 0.02 });
            }
            let got = b.build().unwrap().natural_frequencies_squared(&[], false).unwrap();
            let threshold = divergence_threshold(&got);
            assert!(static_divergence(&got).is_empty(), "n = {n}, {dressed}: {:?}", &got[..4]);
            let solver = 100.0 * got.len() as f64 * f64::EPSILON * got.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert!(got[..4].iter().all(|l| l.abs() <= 0.01 * solver), "n = {n}, {dressed}: {:?} (solver's bound {solver})", &got[..4]);
            // the fifth is the first flexible mode, above the threshold (22-fold on the
            // 50-element shaft, whose stiffest mode is 4.5e7 times its first: the data's 1e-9
            // leaves a divergence weaker than 1/22 of that mode unseen)
            assert!(got[4] > 10.0 * threshold, "n = {n}: {} (threshold {threshold})", got[4]);
        }
    }
}
