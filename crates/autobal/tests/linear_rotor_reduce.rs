//! Modal reduction of the linear rotor ([`autobal::linear_rotor::reduce`]) on a 40-element
//! shaft (164 DOFs): the reduced natural frequencies converge to the full model's from above as
//! mode pairs are added (Rayleigh–Ritz; the lowest eight: 1.7e-1, 1.1e-3, 2.2e-5, 7.9e-7
//! relative with 2, 4, 8, 16 pairs), each stated Krylov–Weinstein interval holds a full-model
//! frequency, the stated estimate (the difference to twice the pairs) is 90–100 % of the true
//! error from 4 pairs on (at 2 pairs, where 4 are not yet converged, it underestimates the third
//! mode's error 7-fold), and the balanced state's eigenvalues with the balls equal the full
//! model's (16 pairs, 36 DOFs: 2.7e-6 rad/s below the critical speed, 8.8e-4 rad/s = 5e-6 ω1
//! above it, among eigenvalues up to 4 ω1).

use autobal::analysis::{stability, stationary, NewtonOptions};
use autobal::linear_rotor::reduce::reduce;
use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, Frame, LinearRotor, LinearRotorField, Unbalance};
use num_complex::Complex64;

/// 1.2 m steel shaft, 30 mm, 40 elements, bearings at both ends, a disk with the balancer and
/// the unbalance at node 14 (off centre, so that every bending mode moves the balancer plane).
fn shaft() -> LinearRotor {
    let mut b = ShaftBuilder::uniform(40, 1.2, 0.03, 2.1e11, 7850.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 14, mass: 5.0, id: 0.02, ip: 0.04 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 500.0 });
    b.bearings.push(Bearing { node: 40, k: 5e6, c: 500.0 });
    let mut r = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 14, me: 1e-4, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 14, radius: 0.07, balls: 2, ball_mass: 0.02, drag: 0.005, offset: 0.0 });
    r
}

#[test]
fn natural_frequencies_converge_with_the_modes_and_the_bounds_hold() {
    let full_rotor = shaft();
    let full = full_rotor.natural_frequencies(&[], false).unwrap();
    let lowest = 8; // four bending modes, each a pair (x, y)
    let mut last = f64::INFINITY;
    for pairs in [2, 4, 8, 16] {
        let red = reduce(&full_rotor, pairs, &[]).unwrap();
        let w = red.rotor.natural_frequencies(&[], false).unwrap();
        let mut worst: f64 = 0.0;
        for k in 0..lowest {
            // Rayleigh–Ritz: the reduced frequencies bound the full ones from above
            assert!(w[k] >= full[k] * (1.0 - 1e-12), "{pairs} pairs, mode {k}: {} < {}", w[k], full[k]);
            worst = worst.max((w[k] - full[k]) / full[k]);
        }
        // the stated intervals hold a full-model frequency
        for f in red.frequencies.iter().take(lowest) {
            assert!(full.iter().any(|w| *w >= f.low * (1.0 - 1e-12) && *w <= f.high * (1.0 + 1e-12)), "{pairs} pairs: [{}, {}] holds none", f.low, f.high);
        }
        // the stated estimate (difference to twice the pairs) is the error to within 10 %
        for k in (0..lowest).filter(|_| pairs >= 4) {
            let err = w[k] - full[k];
            let est = red.frequencies[k].estimate.unwrap();
            assert!(
                est <= err * (1.0 + 1e-6) + 1e-9 * full[k] && est >= 0.9 * err - 1e-9 * full[k],
                "{pairs} pairs, mode {k}: error {err:e}, estimate {est:e}"
            );
        }
        eprintln!(
            "{pairs} pairs: {} DOFs, worst relative error of the lowest {lowest}: {worst:e}; cut-off {:?}, first neglected {:?}, bound of mode 0: {:e}",
            red.dofs.1,
            red.cutoff,
            red.first_neglected,
            (red.frequencies[0].high - red.frequencies[0].low) / red.frequencies[0].omega
        );
        assert!(worst <= last, "not converging: {worst} after {last}");
        last = worst;
    }
    assert!(last < 2e-6, "16 pairs: {last}");
}

#[test]
fn balanced_state_eigenvalues_equal_the_full_model() {
    let full_rotor = shaft();
    let w1 = full_rotor.natural_frequencies(&[], true).unwrap()[0];
    let red = reduce(&full_rotor, 16, &[]).unwrap();
    for omega in [0.7 * w1, 1.6 * w1] {
        let eig = |r: &LinearRotor| -> (Vec<Complex64>, f64) {
            let f = LinearRotorField::new(r, omega, Frame::Rotating).unwrap();
            let s = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
            let st = stability(&f, &s).unwrap();
            let mut e: Vec<Complex64> = st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).filter(|z| z.norm() < 4.0 * w1).collect();
            e.sort_by(|a, b| a.im.total_cmp(&b.im).then(a.re.total_cmp(&b.re)));
            (e, st.abscissa)
        };
        let (a, sa) = eig(&full_rotor);
        let (b, sb) = eig(&red.rotor);
        assert_eq!(a.len(), b.len(), "Ω = {omega}");
        // greedy nearest matching
        let mut used = vec![false; b.len()];
        let mut worst: f64 = 0.0;
        for x in &a {
            let (j, d) = b.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, y)| (j, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
            used[j] = true;
            worst = worst.max(d);
        }
        eprintln!("Ω = {:.4} ω1: {} low eigenvalues, worst difference {worst:e} (|λ| up to {:e}); abscissa {sa:e} vs {sb:e}", omega / w1, a.len(), 4.0 * w1);
        assert!(worst < 1e-5 * w1, "Ω = {omega}: {worst}");
        assert!((sa - sb).abs() < 1e-7 * w1, "Ω = {omega}: abscissa {sa} vs {sb}");
    }
}
