//! The divergence threshold from the eigen-solver's error bound (review 22): a mode at
//! `ω² ≈ −1 (rad/s)²` on a rotor whose stiffest mode is `1e10 (rad/s)²` is a real static
//! instability (growing at 1 1/s) that the fixed rule `ω² < −1e-9 max|ω²|` (here −10) read as a
//! rigid-body mode's rounding, "0 rad/s". The rule is now
//! `ω² < −100 N ε max|ω²|` ([`divergence_threshold`]), 6.2e-3 (rad/s)² here; rigid-body modes
//! (rounding of either sign) still are not divergent on rotors of several sizes.

use autobal::linear_rotor::shaft::{Disk, ShaftBuilder};
use autobal::linear_rotor::{divergence_threshold, diverges, static_divergence, Layout, LinearRotor};

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
    let r = congruence(&spectrum(-1.0));
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    let threshold = divergence_threshold(&got);
    let div = static_divergence(&got);
    assert_eq!(div.len(), 1, "one mode at ω² = −1 is divergent: {got:?}");
    // 100 · 28 · 2.2e-16 · 1e10 = 6.2e-3 (rad/s)²: well below the mode's 1; the old rule's
    // 1e-9 · 1e10 = 10 was above it
    assert!((threshold - 100.0 * 28.0 * f64::EPSILON * 1e10).abs() <= 1e-6 * threshold, "{threshold}");
    // to the solver's accuracy: the eigenvalues of a backward-stable solve are off by at most
    // the threshold's c N ε max|ω²| (K itself rounded to ε of its entries adds as much)
    assert!((div[0] + 1.0).abs() <= threshold, "ω² = {} against −1 (threshold {threshold})", div[0]);
    assert!(diverges(div[0], &got) && !diverges(got[1], &got));
    // the others are the known spectrum, each to the same absolute accuracy
    for (g, w) in got.iter().zip(&spectrum(-1.0)) {
        assert!((g - w).abs() <= threshold.max(1e-12 * w.abs()), "{g} vs {w}");
    }
}

#[test]
fn the_same_mode_at_plus_one_is_a_frequency_of_1_rad_s() {
    let r = congruence(&spectrum(1.0));
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    assert!(static_divergence(&got).is_empty(), "{got:?}");
    let w = r.natural_frequencies(&[], false).unwrap();
    // ω = sqrt(1 ± threshold): within threshold/2 of 1 rad/s
    assert!((w[0] - 1.0).abs() <= 0.5 * divergence_threshold(&got), "{}", w[0]);
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
    // measured within 2.4e-16 of max|ω²| on these and larger (to 804 DOFs): the 1.5e-13 · N/28
    // of the threshold leaves them at least a thousand-fold margin, asserted here as 100-fold
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
            assert!(got[..4].iter().all(|l| l.abs() <= 0.01 * threshold), "n = {n}, {dressed}: {:?} (threshold {threshold})", &got[..4]);
            // the fifth is the first flexible mode, above the threshold (5e3-fold on the
            // 50-element shaft, whose stiffest mode is 4.5e7 times its first)
            assert!(got[4] > 1e3 * threshold, "n = {n}: {} (threshold {threshold})", got[4]);
        }
    }
}
