//! The model-agnostic stationary-state and stability pipeline ([`autobal::analysis`]) on the
//! planar rotor ([`autobal::planar::field::PlanarField`]) and on test fields with closed-form
//! answers, each verdict checked against something independent.

mod common;

use autobal::analysis::{
    mode, speed_scan, stability, stationary, AnalysisError, Kind, NewtonOptions, ScanOptions, Stability, StationaryState, VectorField, Verdict,
};
use autobal::ode::{Control, Method, Options, Solver, System};
use autobal::planar::field::PlanarField;
use autobal::planar::PlanarRotor;
use autobal::planar::{simulate, Drive, Settings};
use common::python_with;
use num_complex::Complex64;

/// Paper 004's rotor with the race centred (`s2 = 0`): the Jeffcott rotor with two balls.
fn jeffcott() -> PlanarRotor {
    PlanarRotor { s2: 0.0, ..PlanarRotor::paper() }
}

fn analyse(p: &PlanarRotor, omega: f64) -> (PlanarField, StationaryState, Stability) {
    let f = PlanarField::new(p, omega).unwrap();
    let g = f.semi_balanced_guess().expect("the balanced state exists");
    let s = stationary(&f, &g, &NewtonOptions::default()).unwrap();
    let st = stability(&f, &s).unwrap();
    (f, s, st)
}

/// The spectrum at a state, structural members included.
fn all_eigenvalues(st: &Stability) -> Vec<Complex64> {
    st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).collect()
}

/// Greatest distance from a member of `a` to the member of `b` paired with it (closest first).
fn match_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut used = vec![false; b.len()];
    let mut worst: f64 = 0.0;
    for x in a {
        let (k, d) = b.iter().enumerate().filter(|(k, _)| !used[*k]).map(|(k, y)| (k, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
        used[k] = true;
        worst = worst.max(d);
    }
    worst
}

/// One case for tests/planar_linearisation.py.
fn case_json(p: &PlanarRotor, omega: f64, x: &[f64]) -> serde_json::Value {
    serde_json::json!({
        "p": {"m1": p.m1, "m2": p.m2, "m3": p.m3, "n": p.n, "s1": p.s1, "s2": p.s2, "gamma": p.gamma, "r": p.r, "k": p.k, "c": p.c, "c_psi": p.c_psi},
        "omega": omega,
        "x": x,
    })
}

/// The independent SymPy/numpy linearisation of each case: (eigenvalues, right-hand side).
fn sympy_linearisation(python: &str, cases: &[serde_json::Value]) -> Vec<(Vec<Complex64>, Vec<f64>)> {
    let script = format!("{}/tests/planar_linearisation.py", env!("CARGO_MANIFEST_DIR"));
    let mut child =
        std::process::Command::new(python).arg(script).stdin(std::process::Stdio::piped()).stdout(std::process::Stdio::piped()).spawn().expect("python runs");
    use std::io::Write;
    child.stdin.take().unwrap().write_all(serde_json::to_string(cases).unwrap().as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    v.iter()
        .map(|c| {
            let l = c["eigenvalues"].as_array().unwrap().iter().map(|e| Complex64::new(e[0].as_f64().unwrap(), e[1].as_f64().unwrap())).collect();
            let f = c["rhs"].as_array().unwrap().iter().map(|e| e.as_f64().unwrap()).collect();
            (l, f)
        })
        .collect()
}

#[test]
fn eigenvalues_equal_an_independent_lagrangian_linearisation() {
    // SymPy derives Lagrange's equations from the energies in rotor axes and numpy's LAPACK
    // takes the eigenvalues (tests/planar_linearisation.py); we eliminate the balls from
    // d'Alembert's equations and differentiate with dual numbers. Cases: the Jeffcott limit
    // (s2 = 0) across the critical speed and three ball drags, paper 004's eccentric race
    // (semi-balanced state), and three balls (a family: one structural zero). Both are exact,
    // so only round-off separates them: eigenvalues to 1e-9 ρ (ρ = max |λ| ~ 1e3 1/s), and our
    // stationary state has a right-hand side below 1e-12 of its scale in their equations.
    let Some(python) = python_with(&["sympy", "numpy"]) else { return };
    let mut cases = vec![];
    let mut ours = vec![];
    let mut rotors = vec![];
    for c_psi in [0.01, 0.1, 1.0] {
        for w in [100.0, 250.0, 288.0, 350.0, 600.0, 1500.0] {
            rotors.push((PlanarRotor { c_psi, ..jeffcott() }, w));
        }
    }
    for w in [300.0, 500.0, 900.0] {
        rotors.push((PlanarRotor::paper(), w));
        rotors.push((PlanarRotor { n: 3, m3: 0.02, gamma: 0.7, ..PlanarRotor::paper() }, w));
    }
    for (p, w) in &rotors {
        let (f, s, st) = analyse(p, *w);
        cases.push(case_json(p, *w, &s.x));
        ours.push((f, s, st));
    }
    let theirs = sympy_linearisation(&python, &cases);
    for ((f, s, st), (l, rhs)) in ours.iter().zip(&theirs) {
        let rho = st.rate;
        let d = match_distance(&all_eigenvalues(st), l);
        assert!(d <= 1e-9 * rho, "Ω = {}: eigenvalues differ by {d:e} (ρ = {rho}):\nours {:?}\nSymPy {l:?}", f.omega(), all_eigenvalues(st));
        let scales = f.scales();
        for (i, v) in rhs.iter().enumerate() {
            assert!(v.abs() <= 1e-12 * scales[i] * rho, "Ω = {}: {} rate {v:e} at our stationary state", f.omega(), f.component_name(i));
        }
        assert_eq!(st.structural.len(), s.family_dimension);
        assert_eq!(s.family_dimension, f.rotor().n.saturating_sub(2));
    }
}

/// Lower end of the stable range of the balanced Jeffcott state over 50..2040 rad/s (200
/// speeds), and the scan.
fn lowest_stable_speed(p: &PlanarRotor) -> (Option<f64>, autobal::analysis::SpeedScan) {
    let speeds: Vec<f64> = (0..200).map(|i| 50.0 + 10.0 * i as f64).collect();
    let scan = speed_scan(|w| PlanarField::new(p, w), |f, _| f.semi_balanced_guess(), &speeds, &ScanOptions::default()).unwrap();
    (scan.stable_ranges.first().map(|r| r.from), scan)
}

#[test]
fn the_jeffcott_balanced_state_is_stable_only_above_the_critical_speed() {
    // The classic result (Thearle; Chung & Ro 1999; Green et al. 2006): below ω_n = sqrt(k/m0)
    // the balanced state of a Jeffcott rotor with two balls is unstable whatever the ball drag;
    // above, it becomes stable from a speed that falls towards ω_n as the drag grows. The
    // boundary, bisected to 1e-9 by our pipeline, is confirmed by the independent
    // linearisation: growing 1e-5 below it, decaying 1e-5 above (closer, the slowest
    // growth rate, ~1e-7 1/s at c_ψ = 10, is below what either eigen-solver resolves).
    let p0 = jeffcott();
    let wn = p0.natural_frequency();
    let drags = [0.003, 0.01, 0.1, 1.0, 10.0];
    let mut ends = vec![];
    let mut checks = vec![];
    for c_psi in drags {
        let p = PlanarRotor { c_psi, ..p0.clone() };
        let (end, scan) = lowest_stable_speed(&p);
        let end = end.expect("a stable range");
        assert!(end > wn, "c_ψ = {c_psi}: stable from {end} ≤ ω_n = {wn}");
        for pt in scan.points.iter().filter(|pt| pt.omega < wn) {
            // never stable, and growing: Unstable, or at the lowest speeds with the heaviest
            // drag Neutral (a growth rate of 3e-5 1/s against ρ ~ 1e5 1/s, inside 1e-9 ρ)
            let st = pt.stability.as_ref().unwrap();
            assert!(
                st.verdict != Verdict::Stable && st.abscissa > 0.0,
                "c_ψ = {c_psi}, Ω = {}: {:?}, α = {:e}, threshold {:e}",
                pt.omega,
                st.verdict,
                st.abscissa,
                st.threshold
            );
            assert!(st.verdict == Verdict::Unstable || pt.omega < 0.5 * wn, "c_ψ = {c_psi}, Ω = {}: {:?}", pt.omega, st.verdict);
        }
        assert!(scan.stable_ranges.len() == 1 && !scan.stable_ranges[0].to_is_boundary, "{:?}", scan.stable_ranges);
        ends.push(end);
        for w in [end * (1.0 - 1e-5), end * (1.0 + 1e-5)] {
            let (_, s, _) = analyse(&p, w);
            checks.push(case_json(&p, w, &s.x));
        }
    }
    // the lowest stable speed falls with the drag, towards ω_n (within 0.1 % at c_ψ = 10)
    for w in ends.windows(2) {
        assert!(w[1] < w[0], "{ends:?}");
    }
    assert!(ends[4] < 1.001 * wn && ends[0] > 1.4 * wn, "{ends:?}, ω_n = {wn}");
    let Some(python) = python_with(&["sympy", "numpy"]) else { return };
    let theirs = sympy_linearisation(&python, &checks);
    let alphas: Vec<f64> = theirs.iter().map(|(l, _)| l.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max)).collect();
    for (k, pair) in alphas.chunks(2).enumerate() {
        // α is linear across the boundary at this scale: the zero between ±1e-5 sits at
        // 1e-5 (α₋ + α₊)/(α₋ − α₊) relative from our end; below 1e-3 of that: 1e-8
        let offset = (pair[0] + pair[1]) / (pair[0] - pair[1]);
        assert!(offset.abs() < 1e-3, "c_ψ = {}: SymPy's zero of α is {:e} relative from ours", drags[k], 1e-5 * offset);
    }
    for (k, (l, _)) in theirs.iter().enumerate() {
        let alpha = l.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max);
        let below = k % 2 == 0;
        assert!(
            if below { alpha > 0.0 } else { alpha < 0.0 },
            "c_ψ = {}: SymPy's abscissa {alpha:e} {} the boundary {}",
            drags[k / 2],
            if below { "below" } else { "above" },
            ends[k / 2]
        );
    }
}
