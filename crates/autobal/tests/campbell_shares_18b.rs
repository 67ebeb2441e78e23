//! `forward_share` of the linear rotor's Campbell points against an independent eigenvector
//! (share18). The shaft of examples/linear_rotor_shaft.toml as
//! bench/independent/check_campbell_linear.py's L2 runs it (full model, the elements' rotary
//! inertia and gyroscopic matrices off) at Ω = 12.5 rad/s: its forward and backward modes are
//! 2Ω apart at |λ| ~ 2.3e4 (max|λ| 1.9e5) while the raw Jacobian's entries span 1 to 5e11, and
//! the inverse iteration's pivot floor (ε max|a_ij|) mixed their eigenvectors: shares 0.30 and
//! 0.94 where the modes are nearly pure (0.0049, 0.995).
//!
//! The reference: numpy's `eig` (LAPACK, balanced) of autobal's own Jacobian at the same state,
//! the documented share `Σ w_p² |x_a + i x_b|² / Σ w_p² (|x_a + i x_b|² + |x_a − i x_b|²)` with
//! `w_p² = M̄_p / M_s` (docs/reference/outputs.md), every complex eigenvalue whose nearest other
//! is at least 1e-4 of max|λ| away (the independent check's rule: the shares of near-double
//! values are not defined). The same values follow from the script's own SymPy model
//! (check_campbell_linear.py, L2, now agreeing to 1e-6). Tolerance 1e-6 (the independent
//! check's): an eigenvector's direction is good to ε‖B‖/gap (‖B‖ ~ 3e5 balanced, gap ≥ 19),
//! ~3e-12; the two routes agree to 1e-12 here.

use autobal::analysis::{stationary, NewtonOptions};
use autobal::rotor_stability::Rotor;

/// (re, im, forward share) by numpy, sorted by im.
const REFERENCE: &[(f64, f64, f64)] = &[
    (-2.502478034358e+03, -1.896405183529e+05, 9.998471037261e-01),
    (-2.502478446211e+03, -1.896155107987e+05, 1.529432123407e-04),
    (-2.504236068968e+03, -1.895887858054e+05, 9.999832319937e-01),
    (-2.504235941024e+03, -1.895637887938e+05, 1.677206368088e-05),
    (-7.082174375017e+02, -9.547539294464e+04, 9.958030112742e-01),
    (-7.082151928156e+02, -9.545018222812e+04, 4.196141048989e-03),
    (-7.104362692621e+02, -9.521445687424e+04, 9.993797354321e-01),
    (-7.104361105888e+02, -9.518947222500e+04, 6.202431965200e-04),
    (-6.127311035625e+02, -5.094082354664e+04, 9.957368239986e-01),
    (-6.127204770260e+02, -5.091561069443e+04, 4.254699988516e-03),
    (-6.123932054111e+02, -5.070699186655e+04, 9.988100905252e-01),
    (-6.123917407015e+02, -5.068205278346e+04, 1.188128640136e-03),
    (-5.391039746636e+02, -2.291798806529e+04, 9.957749423055e-01),
    (-5.390869056977e+02, -2.289277957687e+04, 4.217505993967e-03),
    (-5.360188433744e+02, -2.279681946912e+04, 9.951066982621e-01),
    (-5.360040661805e+02, -2.277211395992e+04, 4.891646294482e-03),
    (-5.370380376979e+02, -8.985773146207e+03, 9.551973318531e-01),
    (-5.368870837921e+02, -8.962493813561e+03, 4.466664786775e-02),
    (-5.974858592430e+02, -8.697661276598e+03, 9.963738919342e-01),
    (-5.974425263594e+02, -8.672493668450e+03, 3.603442880942e-03),
    (-4.241197019688e+02, -2.892391988475e+03, 9.996548039963e-01),
    (-4.241083979379e+02, -2.867394863676e+03, 3.321360228477e-04),
    (-2.300122779515e+00, -3.839291804488e+02, 9.999423273758e-01),
    (-2.312274796434e+00, -3.589316659937e+02, 4.443202983425e-05),
    (-2.312274796434e+00, 3.589316659937e+02, 9.999555679702e-01),
    (-2.300122779515e+00, 3.839291804488e+02, 5.767262417057e-05),
    (-4.241083979379e+02, 2.867394863676e+03, 9.996678639772e-01),
    (-4.241197019688e+02, 2.892391988475e+03, 3.451960036692e-04),
    (-5.974425263594e+02, 8.672493668450e+03, 9.963965571191e-01),
    (-5.974858592430e+02, 8.697661276598e+03, 3.626108065844e-03),
    (-5.368870837921e+02, 8.962493813561e+03, 9.553333521323e-01),
    (-5.370380376979e+02, 8.985773146207e+03, 4.480266814691e-02),
    (-5.360040661805e+02, 2.277211395992e+04, 9.951083537055e-01),
    (-5.360188433744e+02, 2.279681946912e+04, 4.893301737851e-03),
    (-5.390869056977e+02, 2.289277957687e+04, 9.957824940060e-01),
    (-5.391039746636e+02, 2.291798806529e+04, 4.225057694506e-03),
    (-6.123917407015e+02, 5.068205278346e+04, 9.988118713599e-01),
    (-6.123932054111e+02, 5.070699186655e+04, 1.189909474767e-03),
    (-6.127204770260e+02, 5.091561069443e+04, 9.957453000115e-01),
    (-6.127311035625e+02, 5.094082354664e+04, 4.263176001353e-03),
    (-7.104361105888e+02, 9.518947222500e+04, 9.993797568035e-01),
    (-7.104362692621e+02, 9.521445687424e+04, 6.202645679048e-04),
    (-7.082151928156e+02, 9.545018222812e+04, 9.958038589510e-01),
    (-7.082174375017e+02, 9.547539294464e+04, 4.196988725816e-03),
    (-2.504235941024e+03, 1.895637887938e+05, 9.999832279363e-01),
    (-2.504236068968e+03, 1.895887858054e+05, 1.676800630203e-05),
    (-2.502478446211e+03, 1.896155107987e+05, 9.998470567877e-01),
    (-2.502478034358e+03, 1.896405183529e+05, 1.528962738981e-04),
];

#[test]
fn the_linear_shafts_shares_match_an_independent_eigenvector() {
    let src = include_str!("../../../examples/linear_rotor_shaft.toml")
        .replace("rotary_inertia = true", "rotary_inertia = false")
        .replace("gyroscopic = true", "gyroscopic = false")
        .replace("modes = 4 ", "modes = 0 ");
    assert!(src.contains("modes = 0 ") && src.contains("gyroscopic = false") && src.contains("rotary_inertia = false"));
    let root = autobal::config::parse(&src, "test").unwrap();
    let cfg = autobal::linear_rotor::config::linear_rotor(&root, &mut |_| Err("no files".into())).unwrap();
    let rotor = Rotor::Linear(cfg.rotor.clone());
    let w = 12.5;
    let f = rotor.field(w).unwrap();
    let s = stationary(&f, &Rotor::guess(&f).unwrap(), &NewtonOptions::default()).unwrap();
    let pts = autobal::rotor_campbell::spectrum_at(&rotor, &f, w, &s).unwrap();
    let scale = pts.iter().map(|p| p.re.hypot(p.im)).fold(0.0, f64::max);
    let mut worst = 0.0f64;
    for &(re, im, share) in REFERENCE {
        let p = pts.iter().min_by(|a, b| (a.re - re).hypot(a.im - im).total_cmp(&(b.re - re).hypot(b.im - im))).unwrap();
        // the same eigenvalue (the independent check's 1e-8 of max|λ|)
        assert!((p.re - re).hypot(p.im - im) < 1e-8 * scale, "({re}, {im}): nearest ({}, {})", p.re, p.im);
        worst = worst.max((p.forward_share - share).abs());
        assert!((p.forward_share - share).abs() < 1e-6, "({re}, {im}): share {} against {share}", p.forward_share);
    }
    eprintln!("{} points, worst share difference {worst:.1e}", REFERENCE.len());
}
