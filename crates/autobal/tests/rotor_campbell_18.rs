//! Issue 18, session 18: the general route's Campbell diagram says what it knows.
//! (1) Floquet multipliers below the monodromy's round-off give a bound, not a number
//! (`CampbellPoint::decay_at_least`), checked against the exact eigenvalues of a nearly
//! isotropic rotor; (2) a rotor whose balls' capacity falls short follows the partially
//! balanced state that `stability` analyses; (3) the balls' slow lines keep their identity at
//! the lowest speeds.

use autobal::analysis::{stability, VectorField};
use autobal::planar::PlanarRotor;
use autobal::rotor_campbell::{campbell_over_speed, stationary_at, undetermined_multiplier_bound};
use autobal::rotor_stability::Rotor;
use num_complex::Complex64;

/// The Jeffcott rotor of paper 004 with its race centred (the balanced state is at rest in
/// turning axes) and `k_y = k (1 + aniso)`.
fn jeffcott(aniso: f64) -> PlanarRotor {
    let p = PlanarRotor { s2: 0.0, ..PlanarRotor::paper() };
    PlanarRotor { k_y: (aniso != 0.0).then_some(p.k * (1.0 + aniso)), ..p }
}

#[test]
fn floquet_exponents_below_round_off_are_bounds_that_hold() {
    // Supports that differ by 1e-9 make the pipeline treat the rotor as periodic (shooting,
    // monodromy over T = π/Ω) while physically it is the isotropic rotor, whose eigenvalues λ
    // (equilibrium route, exact AD Jacobian) are the exact answer: the multipliers are e^{λT}.
    // At low speed T is long and the heavily damped modes' multipliers e^{Re λ T} fall far below
    // the monodromy's round-off δ (rotor_campbell::undetermined_multiplier_bound). Checked:
    // - every λ with |e^{λT}| < δ/10 is reported as a bound (no number), and each bound holds:
    //   the mode decays at least that fast, −Re λ ≥ decay_at_least for every leftover λ;
    // - every λ with |e^{λT}| > 10 δ is a number: a determined point within 1e-6 max(|λ|, Ω)
    //   (the multipliers are good to ~1e-9, the anisotropy moves λ by ~1e-9 of it);
    // - at 1e-9 the measured error of the computed multipliers against e^{λT}, over δ, is
    //   below 1 (the factor 100 in δ is then a margin of the measured error, printed: 0.09).
    // On main (no bound) the low-speed exponents are printed as ln|μ̂|/T, numbers of round-off.
    // Also 1e-7 at 36.08 rad/s, session 17's case (printed −428.8 where λ = −955.8), where
    // the anisotropy moves λ by ~1e-7 of it: 1e-5 there.
    let iso = Rotor::Planar(jeffcott(0.0));
    let wn = jeffcott(0.0).natural_frequency();
    let mut bounds = 0;
    let mut worst_ratio = 0.0f64;
    let cases = [(1e-9, 0.05 * wn, 1e-6), (1e-9, 0.1 * wn, 1e-6), (1e-9, 0.2 * wn, 1e-6), (1e-9, 0.5 * wn, 1e-6), (1e-9, 1.5 * wn, 1e-6), (1e-7, 36.08, 1e-5)];
    for (aniso, omega, tol) in cases {
        let near = Rotor::Planar(jeffcott(aniso));
        let t = std::f64::consts::PI / omega;
        let exact = campbell_over_speed(&iso, &[omega]).unwrap();
        let lam: Vec<Complex64> = exact.lines.iter().filter_map(|l| l.points[0]).map(|p| Complex64::new(p.re, p.im)).collect();
        let c = campbell_over_speed(&near, &[omega]).unwrap();
        assert_eq!(c.kind, autobal::analysis::Kind::PeriodicOrbit);
        let pts: Vec<_> = c.lines.iter().filter_map(|l| l.points[0]).collect();
        assert_eq!(pts.len(), lam.len());
        let (f, s) = stationary_at(&near, omega).unwrap();
        let st = stability(&f, &s).unwrap();
        let delta = undetermined_multiplier_bound(&st.matrix, &f.scales());
        let mu = |z: Complex64| (z * t).exp();
        // the determined ones: one to one with the exact λ of multiplier above 10 δ
        let mut left: Vec<Complex64> = lam.clone();
        for p in pts.iter().filter(|p| p.decay_at_least.is_none()) {
            let r = Complex64::new(p.re, p.im);
            let (i, d) = left.iter().enumerate().map(|(i, l)| (i, (l - r).norm())).fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
            let scale = r.norm().max(omega);
            assert!(d < tol * scale || mu(left[i]).norm() < 10.0 * delta, "Ω = {omega}: ρ = {r} is {d} from the exact λ {lam:?}");
            // (at 1e-7 the anisotropy itself moves the multipliers near 1 by ~3e-6 ≫ δ)
            if aniso < 1e-8 {
                worst_ratio = worst_ratio.max((mu(r) - mu(left[i])).norm() / delta);
            }
            left.remove(i);
        }
        // the rest are bounds, and hold for every λ left
        let undetermined: Vec<_> = pts.iter().filter_map(|p| p.decay_at_least).collect();
        assert_eq!(undetermined.len(), left.len());
        bounds += undetermined.len();
        for l in &left {
            assert!(mu(*l).norm() < 10.0 * delta, "Ω = {omega}: λ = {l} (|e^(λT)| = {:e}, δ = {delta:e}) has no number", mu(*l).norm());
            for b in &undetermined {
                assert!(*b > 0.0 && -l.re >= *b, "Ω = {omega}: the bound 'decays faster than {b}' fails for λ = {l}");
            }
        }
        for l in &lam {
            if mu(*l).norm() < 0.1 * delta {
                assert!(left.contains(l), "Ω = {omega}: λ = {l}, |e^(λT)| = {:e} < δ/10 = {:e}, is printed as a number", mu(*l).norm(), 0.1 * delta);
            }
        }
        println!("Ω = {omega:.1}: δ = {delta:.2e}, {} bounds", undetermined.len());
    }
    println!("worst |μ̂ − e^(λT)| / δ over the determined multipliers: {worst_ratio:.2e}");
    assert!(bounds > 0, "the case must have multipliers below round-off");
    assert!(worst_ratio < 1.0);
}

#[test]
fn a_capacity_short_rotor_follows_the_partially_balanced_state_that_stability_analyses() {
    // Two 20 g balls on the Jeffcott rotor: capacity n m3 r = 0.0024 kg m against the unbalance
    // m1 s1 = 0.003 kg m, so no balanced state exists at any speed. `stability` analyses the
    // partially balanced state (the balls bunched at their capacity limit, rotor_partial); the
    // Campbell diagram must follow that state (main: "no balanced state to lock the balls in" at
    // every speed, although the balls are free) and say which it is. Checked against the
    // stability scan, a second route to the state (its own starts and Newton, its own
    // eigenvalue routine over the spectrum): at every speed where it has a state, the diagram
    // has one, classed as the scan classes it, and its largest non-structural Re λ is the scan's
    // abscissa to 1e-9 of max|λ| (both the eigenvalues of one Jacobian at one state found to a
    // residual of 1e-12: round-off of the QR, ~1e-14 relative).
    use autobal::rotor_stability::{stability_over_speed, StateKind};
    let p = PlanarRotor { m3: 0.02, ..jeffcott(0.0) };
    let wn = p.natural_frequency();
    let rotor = Rotor::Planar(p);
    let speeds: Vec<f64> = (1..=30).map(|i| 0.1 * wn * i as f64).collect();
    let c = campbell_over_speed(&rotor, &speeds).unwrap();
    let st = stability_over_speed(&rotor, &speeds).unwrap();
    assert!(c.lines.iter().all(|l| l.points.len() == speeds.len()) && c.states.len() == speeds.len());
    let (mut compared, mut partial) = (0, 0);
    for (k, sp) in st.points.iter().enumerate() {
        let Some(a) = sp.abscissa else { continue };
        assert_eq!(c.failures[k], None, "Ω = {}: stability has a state, campbell says {:?}", speeds[k], c.failures[k]);
        // the bunched balls: partially balanced above the critical speed, not balanced below
        // it (on the unbalance's side, a residual above 1), as `stability` words them
        assert_eq!(c.states[k], sp.state, "Ω = {}", speeds[k]);
        assert!(matches!(sp.state, Some(StateKind::PartiallyBalanced | StateKind::NotBalanced)));
        partial += usize::from(sp.state == Some(StateKind::PartiallyBalanced));
        let pts: Vec<_> = c.lines.iter().filter_map(|l| l.points[k]).collect();
        let top = pts.iter().filter(|p| !p.structural).map(|p| p.re).fold(f64::NEG_INFINITY, f64::max);
        let scale = pts.iter().map(|p| p.re.hypot(p.im)).fold(0.0, f64::max);
        assert!((top - a).abs() <= 1e-9 * scale, "Ω = {}: campbell's max Re λ {top}, stability's abscissa {a}", speeds[k]);
        compared += 1;
    }
    assert!(compared >= 25 && partial >= 15, "only {compared} speeds with a state, {partial} partially balanced");
}

#[test]
fn the_balls_slow_lines_keep_their_identity_at_the_lowest_speeds() {
    // The Jeffcott rotor (paper 004's, race centred) on the first 12 of 300 speeds up to 3 ω_n:
    // the balls' two slow real eigenvalues are a Ω⁴ and 2.27 a Ω⁴ (the balls' restoring
    // stiffness ∝ Ω² over a drag-dominated motion; measured: the ratio of the two is 2.27 at
    // every one of these speeds, each value's log-slope in Ω 4.0), below 1e-6 of max|λ|. They
    // never cross, so a line that changes from the larger to the smaller has jumped to the
    // other mode. Main tracked by value alone and swapped them twice (speeds 1 and 3: the
    // values grow 81-fold over the first step while 1e-9 apart). Checked: each of the two
    // lines stays on one side of the other, and grows with log-slope 4 ± 0.5 at every step
    // (a swap moves the slope by ln 2.27 / ln(Ω_{k+1}/Ω_k) ≥ 1.2 here).
    let p = jeffcott(0.0);
    let wn = p.natural_frequency();
    let speeds: Vec<f64> = (0..12).map(|i| 3.0 * wn * (i as f64 + 0.5) / 300.0).collect();
    let c = campbell_over_speed(&Rotor::Planar(p), &speeds).unwrap();
    let big = c.lines.iter().flat_map(|l| l.points.iter().flatten()).map(|p| p.re.hypot(p.im)).fold(0.0, f64::max);
    let slow: Vec<Vec<f64>> = c
        .lines
        .iter()
        .filter(|l| l.points.iter().all(|p| p.is_some_and(|p| p.im == 0.0 && p.re.abs() < 1e-5 * big)))
        .map(|l| l.points.iter().map(|p| p.unwrap().re).collect())
        .collect();
    assert_eq!(slow.len(), 2, "the balls' two slow lines");
    let above: Vec<bool> = (0..speeds.len()).map(|k| slow[0][k] > slow[1][k]).collect();
    assert!(above.iter().all(|a| *a == above[0]), "the slow lines swap: {slow:?}");
    for l in &slow {
        for k in 1..speeds.len() {
            let slope = (l[k] / l[k - 1]).ln() / (speeds[k] / speeds[k - 1]).ln();
            assert!((slope - 4.0).abs() < 0.5, "log-slope {slope} at speed {k}: {l:?}");
        }
    }
}
