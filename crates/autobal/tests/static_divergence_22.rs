//! A stiffness matrix that is not positive semi-definite (audit 21's F6: ROSS's rotor with two
//! diagonal entries of `K` lowered) has modes with `ω² < 0` that diverge at rest; they read
//! "0 rad/s" before, like a rigid-body mode. [`LinearRotor::natural_frequencies_squared`] keeps
//! the sign and [`static_divergence`] names them; a rigid-body mode (`K` semi-definite) is not one.

use autobal::linear_rotor::{static_divergence, Layout, LinearRotor};

/// One node `x, y`, `M = diag(m1, m2)`, `K = [[a, b], [b, d]]`.
fn rotor(m1: f64, m2: f64, a: f64, b: f64, d: f64) -> LinearRotor {
    let mut r = LinearRotor::zeros(1, Layout::Translation);
    r.m = vec![m1, 0.0, 0.0, m2];
    r.k = vec![a, b, b, d];
    r
}

/// The roots of `det(K − λ M) = m1 m2 λ² − (a m2 + d m1) λ + (a d − b²) = 0`, ascending: the
/// closed form of the 2 × 2 generalised problem.
fn closed_form(m1: f64, m2: f64, a: f64, b: f64, d: f64) -> [f64; 2] {
    let (qa, qb, qc) = (m1 * m2, -(a * m2 + d * m1), a * d - b * b);
    let disc = (qb * qb - 4.0 * qa * qc).sqrt();
    [(-qb - disc) / (2.0 * qa), (-qb + disc) / (2.0 * qa)]
}

#[test]
fn an_indefinite_stiffness_has_a_negative_omega_squared_named_as_divergent() {
    // a d − b² = 2e4 · (−5e3) − 1e8 < 0: one negative and one positive λ (Sylvester)
    let (m1, m2, a, b, d) = (2.0, 3.0, 2e4, 1e4, -5e3);
    let r = rotor(m1, m2, a, b, d);
    let want = closed_form(m1, m2, a, b, d);
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    assert!(want[0] < 0.0 && want[1] > 0.0, "{want:?}");
    // a 2 × 2 eigenproblem after a Cholesky congruence: exact to a few ulps of the largest
    // |λ| (1e-12 relative: a thousand times the rounding)
    let scale = want[1].abs().max(want[0].abs());
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= 1e-12 * scale, "{got:?} vs {want:?}");
    }
    // the divergent mode is named, with its ω² itself; the frequencies clamp it to 0 (the
    // reason the commands ask static_divergence before printing them)
    let div = static_divergence(&got);
    assert_eq!(div.len(), 1, "{got:?}");
    assert!((div[0] - want[0]).abs() <= 1e-12 * scale);
    let w = r.natural_frequencies(&[], false).unwrap();
    assert_eq!(w[0], 0.0);
    assert!((w[1] - want[1].sqrt()).abs() <= 1e-12 * want[1].sqrt());
}

#[test]
fn a_rigid_body_mode_is_not_divergent() {
    // a d − b² = 0: K positive semi-definite, one rigid-body mode (λ = 0 exactly, computed to
    // rounding of either sign) and λ = (a m2 + d m1)/(m1 m2) (the trace's root)
    let (m1, m2, a, b, d) = (2.0, 3.0, 4e4, 2e4, 1e4);
    let r = rotor(m1, m2, a, b, d);
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    let top = (a * m2 + d * m1) / (m1 * m2);
    assert!(got[0].abs() <= 1e-12 * top, "{got:?}");
    assert!((got[1] - top).abs() <= 1e-12 * top, "{got:?}");
    assert!(static_divergence(&got).is_empty(), "{got:?}");
    // made slightly indefinite beyond rounding (d lowered by 1e-6 relative: λ0 ≈ −1e-6 ·
    // (a d)/(a m2 + d m1), 1e-7 of the largest, far above the threshold 1e-9 of the largest):
    // divergent
    let r = rotor(m1, m2, a, b, d * (1.0 - 1e-6));
    let got = r.natural_frequencies_squared(&[], false).unwrap();
    assert_eq!(static_divergence(&got).len(), 1, "{got:?}");
    // a rounding-sized negative λ (1e-15 of the largest: free rotors' rigid-body modes were
    // measured within 2.4e-16 of it, static_divergence_23.rs) is not one
    assert!(static_divergence(&[-1e-15 * top, top]).is_empty());
}
