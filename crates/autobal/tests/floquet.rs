//! The monodromy matrix of a periodic orbit with the Jacobian interpolated in time
//! (analysis::stationary: equispaced samples of J(t, x(t)), its trigonometric interpolant J̃,
//! Φ' = J̃ Φ) against the full variational equations integrated at a tighter tolerance.

use autobal::analysis::{stability, stationary, NewtonOptions, StationaryState, VectorField};
use autobal::rotor_stability::Rotor;

mod common;
use common::{full_variational_flow, match_distance};

/// The multipliers of the monodromy matrix of the orbit `s` of `f` by the full variational
/// equations `n + n²` integrated at rtol 1e-13 from the same orbit, against ours: their
/// greatest distance (paired), and the largest Floquet exponents of both.
fn against_full_equations<F: VectorField>(f: &F, s: &StationaryState) -> (f64, f64, f64) {
    let st = stability(f, s).unwrap();
    let t = f.period().unwrap();
    let n = f.dim();
    let y = full_variational_flow(f, &s.x, t);
    let reference = stability(f, &StationaryState { monodromy: Some(y[n..].to_vec()), ..s.clone() }).unwrap();
    let ours: Vec<_> = st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).collect();
    let theirs: Vec<_> = reference.spectrum.iter().chain(&reference.structural).map(|e| e.complex()).collect();
    (match_distance(&ours, &theirs), st.abscissa, reference.abscissa)
}

#[test]
fn interpolated_jacobian_monodromy_equals_the_full_variational_equations() {
    // examples/spatial_two_plane.toml (16 states, gravity, supports stiffer in y) across its
    // speeds, shot at rtol 1e-10 as rotor_stability does: the multipliers from the
    // interpolated Jacobian (equispaced samples of the shooting's last flow, trigonometric
    // interpolant) equal those of the full variational equations n + n² integrated at
    // rtol 1e-13 from the same orbit to 1e-8, the verdict's FLOQUET_TOLERANCE (the full route's
    // own error at rtol 1e-10 is of that order: 4e-9 measured), and the largest Floquet
    // exponent to 1e-8 / T. 150 rad/s is the weakest case for the interpolant: the lowest
    // speed with a balanced orbit (none at 100), where gravity's sag and the balls' swing are
    // largest against the whirl, so J(t, x(t)) has the most harmonics.
    let root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    let rotor = Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor);
    let opts = NewtonOptions { max_iterations: 20, rtol: 1e-10, ..NewtonOptions::default() };
    for w in [150.0, 300.0, 1000.0, 2500.0] {
        let f = rotor.field(w).unwrap();
        let t = f.period().unwrap();
        let s = stationary(&f, &Rotor::guess(&f).unwrap(), &opts).unwrap();
        let (d, ours, theirs) = against_full_equations(&f, &s);
        eprintln!("two-plane, Ω = {w}: multipliers differ by {d:.1e}, abscissa {ours} against {theirs}");
        assert!(d <= 1e-8, "Ω = {w}: multipliers differ by {d:e}");
        assert!((ours - theirs).abs() <= 1e-8 / t, "Ω = {w}: {ours} against {theirs}");
    }
}

#[test]
fn the_moving_orbit_of_an_eccentric_race_on_unequal_supports_has_the_full_equations_multipliers() {
    // paper 004's rotor with its race eccentric (s2 = 0.5 mm: the semi-balanced orbit moves,
    // no three-Jacobian shortcut) on supports k_x, k_y = (1 ∓ 0.15) k: the planar field's
    // orbit of period π/Ω, below, near and above the critical speeds; tolerance as above
    let p0 = autobal::planar::PlanarRotor::paper();
    let p = autobal::planar::PlanarRotor { k: 0.85 * p0.k, k_y: Some(1.15 * p0.k), ..p0 };
    let rotor = Rotor::Planar(p.clone());
    let opts = NewtonOptions { max_iterations: 20, rtol: 1e-10, ..NewtonOptions::default() };
    let wn = p.natural_frequency();
    let mut checked = 0;
    for w in [0.9 * wn, 1.3 * wn, 2.5 * wn] {
        let f = rotor.field(w).unwrap();
        let t = f.period().unwrap();
        let Some(s) = Rotor::guess(&f).and_then(|g| stationary(&f, &g, &opts).ok()) else { continue };
        let (d, ours, theirs) = against_full_equations(&f, &s);
        eprintln!("planar eccentric, Ω = {w}: multipliers differ by {d:.1e}, abscissa {ours} against {theirs}");
        assert!(d <= 1e-8, "Ω = {w}: multipliers differ by {d:e}");
        assert!((ours - theirs).abs() <= 1e-8 / t, "Ω = {w}: {ours} against {theirs}");
        checked += 1;
    }
    assert!(checked >= 2, "the semi-balanced orbit was found at {checked} of 3 speeds");
}
