//! The half-revolution symmetry of the spatial rotor on supports that differ by direction,
//! without gravity across the axis: in axes turning with the rotor the support force is
//! `R(φ)ᵀ K R(φ) r`, and `R(φ + π) = −R(φ)`, so the equations repeat after `π/Ω`
//! (`SpatialField::period`). The orbit is then shot, and its monodromy integrated, over half a
//! revolution; its multipliers over a revolution are the squares. Checked here against the full
//! variational equations `n + n²` integrated over a whole revolution `2π/Ω` from the same
//! state, which use no symmetry: if the equations did not repeat after `π/Ω`, the state would
//! not close after `2π/Ω`, or the squares would differ.

use autobal::analysis::{stability, stationary, NewtonOptions, VectorField};
use autobal::rotor_stability::Rotor;
use std::f64::consts::PI;

mod common;
use common::{all_eigenvalues, full_variational_flow, match_distance};

/// examples/spatial_two_plane.toml (16 states, supports stiffer in y), with gravity as given.
fn two_plane(gravity: &str) -> Rotor {
    let mut root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value(gravity)).unwrap();
    Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor)
}

#[test]
fn multipliers_over_half_a_revolution_squared_are_those_over_a_revolution() {
    // Tolerances: the reference integrates x and Φ together at rtol 1e-13 over 2π/Ω, ours Φ over
    // π/Ω at the default rtol 1e-12 (the module's multipliers are good to ~1e-10 there); the
    // squares double a multiplier's error. 1e-10 absolute on multipliers of modulus ≤ 1 (the
    // module's stated accuracy; 1.5e-12 to 5.4e-12 measured) is 1e7 below what a wrong symmetry gives: the
    // supports' anisotropy (k_y / k_x = 1.2-1.3) moves the multipliers by more than 1e-3
    // against the isotropic rotor's (checked below), so `R(φ + π) = +R(φ)` in place of `−R(φ)`,
    // or a factor 2 in the period, would show.
    let rotor = two_plane("[0.0, 0.0, 0.0]");
    let iso = {
        let mut root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, 0.0, 0.0]")).unwrap();
        autobal::config::set_number(&mut root, "supports.stiffness_left_y", 2.0e6).unwrap();
        autobal::config::set_number(&mut root, "supports.stiffness_right_y", 3.0e6).unwrap();
        Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor)
    };
    let opts = NewtonOptions::default();
    for w in [300.0, 1300.0, 2500.0] {
        let f = rotor.field(w).unwrap();
        let half = f.period().unwrap();
        assert_eq!(half, PI / w, "no gravity, unequal supports: half a revolution");
        let s = stationary(&f, &Rotor::guess(&f).unwrap(), &opts).unwrap();
        assert_eq!(s.period, Some(half));
        let st = stability(&f, &s).unwrap();
        let squares: Vec<_> = all_eigenvalues(&st).iter().map(|m| m * m).collect();
        // the reference: x and Φ over a whole revolution, no symmetry used
        let n = f.dim();
        let y = full_variational_flow(&f, &s.x, 2.0 * PI / w);
        let sc = f.scales();
        // the orbit closes after a revolution (to the shooting's 1e-10 of the scales, with room)
        for i in 0..n {
            assert!((y[i] - s.x[i]).abs() <= 1e-9 * sc[i], "Ω = {w}: {} moved by {:e} over a revolution", f.component_name(i), y[i] - s.x[i]);
        }
        let full = autobal::linalg::eigen_dyn::eigenvalues(&y[n..], n).unwrap();
        let d = match_distance(&squares, &full);
        // the isotropic twin's multipliers over a revolution, exp(λ 2π/Ω): far from these
        let fi = iso.field(w).unwrap();
        let si = stationary(&fi, &Rotor::guess(&fi).unwrap(), &opts).unwrap();
        let twin: Vec<_> = all_eigenvalues(&stability(&fi, &si).unwrap()).iter().map(|l| (l * (2.0 * PI / w)).exp()).collect();
        let moved = match_distance(&twin, &full);
        eprintln!("Ω = {w}: squares of the π/Ω multipliers against the 2π/Ω ones: {d:.1e}; anisotropy moves them by {moved:.1e}");
        assert!(d <= 1e-10, "Ω = {w}: multipliers differ by {d:e}");
        assert!(moved > 1e-3, "Ω = {w}: the anisotropy moved the multipliers by only {moved:e}");
    }
    // gravity across the axis: g(t + π/Ω) = −g(t), a whole revolution
    let g = two_plane("[0.0, -9.81, 0.0]").field(1300.0).unwrap();
    assert_eq!(g.period(), Some(2.0 * PI / 1300.0));
}
