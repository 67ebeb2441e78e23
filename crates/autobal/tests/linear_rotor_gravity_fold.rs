//! Why the balanced orbit of the linear rotor with gravity is not found at 0.6 ω_n
//! (docs/guide/your-own-rotor.md, "What is left of issue 19"): not a tolerance or iteration
//! floor and not a resonance, but a fold. The rotor of tests/linear_rotor_gravity.rs (one node,
//! k = 1e5 N/m, 10.01 kg: ω_n ≈ 99.9 rad/s; two balls of 20 g on a 0.1 m race, drag 5e-3 N m s)
//! at Ω = 60 rad/s: gravity swings the balls once per revolution, and with their drag the swing
//! gives them a mean torque, while below the critical speed their restoring rate at the balanced
//! state is nearly zero (a real eigenvalue ~0.02 1/s: a Floquet multiplier ~1.002). Followed in
//! the gravity g from 0, the balanced orbit's balls move off their gravity-free angles and a
//! multiplier approaches 1 as `sqrt(g_f − g)`: a fold at g_f ≈ 6.86 m/s², past which this
//! branch has no orbit. At 9.81 m/s² there is none to find, and the shooting says why.

use autobal::analysis::{stability, stationary, NewtonOptions};
use autobal::linear_rotor::{BalancerPlane, Frame, Layout, LinearRotor, LinearRotorField, Unbalance};

/// The linear rotor of tests/linear_rotor_gravity.rs (its `linear(spatial([1e5, 1e5], g))`).
fn rotor(g: f64) -> LinearRotor {
    let mut r = LinearRotor::zeros(1, Layout::Translation);
    let m = 10.0 + 0.01;
    r.m = vec![m, 0.0, 0.0, m];
    r.k = vec![1e5, 0.0, 0.0, 1e5];
    r.c = vec![40.0, 0.0, 0.0, 40.0];
    r.unbalances.push(Unbalance { node: 0, me: 0.01 * 0.1, phase: 0.3, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 0, radius: 0.1, balls: 2, ball_mass: 0.02, drag: 0.5 * 0.01, offset: 0.0 });
    r.set_gravity([0.0, -g]);
    r
}

#[test]
fn below_the_critical_speed_gravity_folds_the_balanced_orbit_away() {
    let w = 60.0;
    // stability's options (20 iterations, rtol 1e-10): no orbit at g = 9.81, and the message
    // names the multiplier near 1; more iterations or a tighter integration do not change that
    let g_full = rotor(9.81);
    let f = LinearRotorField::new(&g_full, w, Frame::Rotating).unwrap();
    for (iterations, rtol) in [(20, 1e-10), (50, 1e-12)] {
        let opts = NewtonOptions { max_iterations: iterations, rtol, ..NewtonOptions::default() };
        let e = stationary(&f, &f.balanced_guess().unwrap(), &opts).unwrap_err().to_string();
        eprintln!("g = 9.81, {iterations} iterations, rtol {rtol:e}: {e}");
        assert!(e.contains("no periodic orbit found") && e.contains("of 1 there"), "{e}");
    }
    // the orbit followed in g from the gravity-free balanced state
    let opts = NewtonOptions { max_iterations: 50, rtol: 1e-10, ..NewtonOptions::default() };
    let r0 = rotor(0.0);
    let f0 = LinearRotorField::new(&r0, w, Frame::Rotating).unwrap();
    let mut x = f0.balanced_guess().unwrap();
    let psi0 = [x[2], x[3]];
    let mut seen = vec![];
    // steps small enough that the balls move by under 0.2 rad each (one branch: a step of
    // 1.5 m/s² from g = 1 lands on another orbit)
    for g in [0.25, 0.6, 1.2, 2.0, 3.0, 4.0, 5.0, 6.0, 6.5, 6.7, 6.8, 6.84] {
        let r = rotor(g);
        let f = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
        let s = stationary(&f, &x, &opts).unwrap_or_else(|e| panic!("g = {g}: {e}"));
        let st = stability(&f, &s).unwrap();
        let d = st.spectrum.iter().chain(&st.structural).map(|m| (m.complex() - 1.0).norm()).fold(f64::INFINITY, f64::min);
        eprintln!("g = {g}: balls at {:.4} {:.4} rad, nearest multiplier to 1 at {d:.3e}", s.x[2], s.x[3]);
        assert!((s.x[2] - x[2]).abs() < 0.2 && (s.x[3] - x[3]).abs() < 0.2, "g = {g}: the balls jumped from {:?} to {:?}", &x[2..4], &s.x[2..4]);
        x = s.x;
        seen.push((g, d));
    }
    // the balls moved by more than half a radian from their gravity-free angles
    assert!((x[2] - psi0[0]).abs() > 0.5 && (x[3] - psi0[1]).abs() > 0.5, "{:?} against {psi0:?}", &x[2..4]);
    // |μ − 1| falls monotonically from g = 4 and, as at a fold, as sqrt(g_f − g): the fold from the last
    // two points, g_f = (g2 d1² − g1 d2²) / (d1² − d2²), lies just past the last g and far
    // below 9.81; the third-last point predicts the same fold within 0.05 m/s² (the square-root
    // law holds, not just any decrease)
    assert!(seen[6..].windows(2).all(|p| p[1].1 < p[0].1), "{seen:?}");
    let fold = |(g1, d1): (f64, f64), (g2, d2): (f64, f64)| (g2 * d1 * d1 - g1 * d2 * d2) / (d1 * d1 - d2 * d2);
    let k = seen.len();
    let (gf, gf2) = (fold(seen[k - 2], seen[k - 1]), fold(seen[k - 3], seen[k - 1]));
    eprintln!("fold at g = {gf:.4} (from the last two), {gf2:.4} (last and third-last)");
    assert!(gf > 6.84 && gf < 7.2 && (gf - gf2).abs() < 0.05, "{gf} {gf2}");
}
