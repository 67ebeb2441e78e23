//! The monodromy matrix of a periodic orbit with the Jacobian interpolated in time
//! (analysis::stationary: Chebyshev–Lobatto samples of J(t, x(t)), Φ' = J̃ Φ) against the full
//! variational equations integrated at a tighter tolerance.

use autobal::analysis::{stability, stationary, NewtonOptions, StationaryState, VariationalSystem, VectorField};
use autobal::ode::{Control, Method, Options, Solver};
use autobal::rotor_stability::Rotor;
use num_complex::Complex64;

/// Greatest distance from a member of `a` to the member of `b` paired with it (closest first).
fn match_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    let mut used = vec![false; b.len()];
    let mut worst: f64 = 0.0;
    for x in a {
        let (k, d) = b.iter().enumerate().filter(|(k, _)| !used[*k]).map(|(k, y)| (k, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
        used[k] = true;
        worst = worst.max(d);
    }
    worst
}

#[test]
fn interpolated_jacobian_monodromy_equals_the_full_variational_equations() {
    // examples/spatial_two_plane.toml (16 states, gravity, supports stiffer in y) across its
    // speeds, shot at rtol 1e-10 as rotor_stability does: the multipliers from the
    // interpolated Jacobian equal those of the full variational equations n + n² integrated at
    // rtol 1e-13 from the same orbit to 1e-8 (measured: 2e-10 … 4e-9, the level of the full
    // route's own error at rtol 1e-10), and the largest Floquet exponent to 1e-8 / T.
    let root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    let rotor = Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor);
    let opts = NewtonOptions { max_iterations: 20, rtol: 1e-10, ..NewtonOptions::default() };
    for w in [300.0, 1000.0, 2500.0] {
        let f = rotor.field(w).unwrap();
        let t = f.period().unwrap();
        let s = stationary(&f, &Rotor::guess(&f).unwrap(), &opts).unwrap();
        let st = stability(&f, &s).unwrap();
        let n = f.dim();
        let sys = VariationalSystem::new(&f);
        let mut y = vec![0.0; n + n * n];
        y[..n].copy_from_slice(&s.x);
        for a in 0..n {
            y[n + a * n + a] = 1.0;
        }
        let sc = f.scales();
        let mut atol: Vec<f64> = sc.iter().map(|v| 1e-13 * v).collect();
        for a in 0..n {
            for b in 0..n {
                atol.push(1e-13 * sc[a] / sc[b]);
            }
        }
        let mut solver = Solver::new(&sys, Options::new(1e-13, 1e-13).method(Method::Dop853).atol_per_component(atol)).unwrap();
        assert!(solver.integrate(0.0, &mut y, t, |_| Control::Continue).status.is_completed());
        let reference = stability(&f, &StationaryState { monodromy: Some(y[n..].to_vec()), ..s.clone() }).unwrap();
        let ours: Vec<_> = st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).collect();
        let theirs: Vec<_> = reference.spectrum.iter().chain(&reference.structural).map(|e| e.complex()).collect();
        let d = match_distance(&ours, &theirs);
        assert!(d <= 1e-8, "Ω = {w}: multipliers differ by {d:e}");
        assert!((st.abscissa - reference.abscissa).abs() <= 1e-8 / t, "Ω = {w}: {} against {}", st.abscissa, reference.abscissa);
    }
}
