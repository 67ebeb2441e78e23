//! Tests of the pipeline on fields with closed-form answers: a nonlinear equilibrium, a circle
//! of equilibria (a family), and a periodically forced oscillator in rotating coordinates whose
//! periodic orbit and Floquet multipliers are known exactly.

use super::*;
use crate::ode::{Control, Method, Options, Solver, System};
use num_complex::Complex64;

/// `x' = (1 − |x|²) x`, `y` likewise: the unit circle is a family of equilibria (plus the
/// origin); radially `r' = (1 − r²) r`, so on the circle `λ = −2` and 0 (tangential).
struct Circle;

impl VectorField for Circle {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, x: &[f64], dx: &mut [f64]) {
        let g = 1.0 - x[0] * x[0] - x[1] * x[1];
        dx[0] = g * x[0];
        dx[1] = g * x[1];
    }
    fn jacobian(&self, _t: f64, x: &[f64], j: &mut [f64]) {
        let g = 1.0 - x[0] * x[0] - x[1] * x[1];
        j[0] = g - 2.0 * x[0] * x[0];
        j[1] = -2.0 * x[0] * x[1];
        j[2] = -2.0 * x[1] * x[0];
        j[3] = g - 2.0 * x[1] * x[1];
    }
    fn period(&self) -> Option<f64> {
        None
    }
    fn structural_zeros(&self, x: &[f64]) -> usize {
        usize::from(x[0].hypot(x[1]) > 0.5)
    }
}

#[test]
fn newton_lands_on_the_nearest_member_of_a_family_and_sets_its_zero_apart() {
    // the minimum-norm step from g is radial (the null space is tangential), so Newton
    // converges to g/|g| exactly: the nearest point of the circle
    let g = [1.3, -0.6];
    let s = stationary(&Circle, &g, &NewtonOptions::default()).unwrap();
    let r = g[0].hypot(g[1]);
    assert!((s.x[0] - g[0] / r).abs() < 1e-14 && (s.x[1] - g[1] / r).abs() < 1e-14, "{:?} against {:?}", s.x, [g[0] / r, g[1] / r]);
    assert_eq!(s.family_dimension, 1);
    let st = stability(&Circle, &s).unwrap();
    assert_eq!(st.structural.len(), 1);
    assert!(st.structural[0].complex().norm() < 1e-14);
    assert_eq!(st.spectrum.len(), 1);
    assert!((st.spectrum[0].re + 2.0).abs() < 1e-13, "{:?}", st.spectrum);
    assert_eq!(st.verdict, Verdict::Stable);
    // the origin (no family): λ = 1 twice, unstable
    let s = stationary(&Circle, &[0.1, 0.05], &NewtonOptions::default()).unwrap();
    assert!(s.x[0].abs() < 1e-15 && s.x[1].abs() < 1e-15);
    let st = stability(&Circle, &s).unwrap();
    assert_eq!((st.verdict, st.structural.len()), (Verdict::Unstable, 0));
    assert!((st.abscissa - 1.0).abs() < 1e-14);
}

/// `x' = (ωJ + R C Rᵀ) x + β(|x|² − ρ²) x + R g0`, `R = R(ωt)` the rotation by `ωt`: in the
/// turning coordinates `y = Rᵀ x` it is the autonomous `y' = C y + g0 + β(|y|² − ρ²) y`, so with
/// `y* = −C⁻¹ g0`, `ρ = |y*|` the periodic orbit is `x*(t) = R(ωt) y*`, and since `R(2π) = I`
/// the monodromy matrix is `exp(K T)`, `K = C + 2β y* y*ᵀ`: multipliers `exp(λ_K T)`, whereas
/// the frozen-time matrix `ωJ + R C Rᵀ` has other eigenvalues (those of `ωJ + C`).
struct Rotating {
    c: [[f64; 2]; 2],
    g0: [f64; 2],
    beta: f64,
    rho2: f64,
    omega: f64,
}

impl Rotating {
    fn new(c: [[f64; 2]; 2], g0: [f64; 2], beta: f64, omega: f64) -> Self {
        let det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
        let y = [-(c[1][1] * g0[0] - c[0][1] * g0[1]) / det, -(-c[1][0] * g0[0] + c[0][0] * g0[1]) / det];
        Rotating { c, g0, beta, rho2: y[0] * y[0] + y[1] * y[1], omega }
    }
    fn orbit_start(&self) -> [f64; 2] {
        let c = self.c;
        let det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
        [-(c[1][1] * self.g0[0] - c[0][1] * self.g0[1]) / det, -(-c[1][0] * self.g0[0] + c[0][0] * self.g0[1]) / det]
    }
    /// `(R C Rᵀ, R g0)` at `t`.
    fn coefficients(&self, t: f64) -> ([[f64; 2]; 2], [f64; 2]) {
        let (s, c) = (self.omega * t).sin_cos();
        let r = [[c, -s], [s, c]];
        let mut m = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                for k in 0..2 {
                    for l in 0..2 {
                        m[i][j] += r[i][k] * self.c[k][l] * r[j][l];
                    }
                }
            }
        }
        (m, [c * self.g0[0] - s * self.g0[1], s * self.g0[0] + c * self.g0[1]])
    }
    /// The exact multipliers `exp(λ_K T)`.
    fn multipliers(&self) -> [Complex64; 2] {
        let y = self.orbit_start();
        let k = [
            [self.c[0][0] + 2.0 * self.beta * y[0] * y[0], self.c[0][1] + 2.0 * self.beta * y[0] * y[1]],
            [self.c[1][0] + 2.0 * self.beta * y[1] * y[0], self.c[1][1] + 2.0 * self.beta * y[1] * y[1]],
        ];
        let (tr, det) = (k[0][0] + k[1][1], k[0][0] * k[1][1] - k[0][1] * k[1][0]);
        let d = Complex64::new(tr * tr / 4.0 - det, 0.0).sqrt();
        let t = 2.0 * std::f64::consts::PI / self.omega;
        [((tr / 2.0 + d) * t).exp(), ((tr / 2.0 - d) * t).exp()]
    }
}

impl VectorField for Rotating {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, t: f64, x: &[f64], dx: &mut [f64]) {
        let (m, g) = self.coefficients(t);
        let h = self.beta * (x[0] * x[0] + x[1] * x[1] - self.rho2);
        dx[0] = -self.omega * x[1] + m[0][0] * x[0] + m[0][1] * x[1] + h * x[0] + g[0];
        dx[1] = self.omega * x[0] + m[1][0] * x[0] + m[1][1] * x[1] + h * x[1] + g[1];
    }
    fn jacobian(&self, t: f64, x: &[f64], j: &mut [f64]) {
        let (m, _) = self.coefficients(t);
        let h = self.beta * (x[0] * x[0] + x[1] * x[1] - self.rho2);
        j[0] = m[0][0] + h + 2.0 * self.beta * x[0] * x[0];
        j[1] = -self.omega + m[0][1] + 2.0 * self.beta * x[0] * x[1];
        j[2] = self.omega + m[1][0] + 2.0 * self.beta * x[1] * x[0];
        j[3] = m[1][1] + h + 2.0 * self.beta * x[1] * x[1];
    }
    fn period(&self) -> Option<f64> {
        Some(2.0 * std::f64::consts::PI / self.omega)
    }
}

/// The field as an ODE system, for simulation.
struct Ode<'a>(&'a Rotating);

impl System for Ode<'_> {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.0.rhs(t, y, dy)
    }
}

#[test]
fn shooting_finds_the_forced_orbit_and_its_exact_floquet_multipliers_which_simulation_confirms() {
    // Two cases: C stable (Re λ_K < 0) while the frozen-time matrix is unstable, and C
    // unstable. Shooting from 0.3 off the orbit finds x*(0) = y* to 1e-10 (the integration's
    // tolerance 1e-12 over a period, amplified by ‖(I − Φ)⁻¹‖); the multipliers equal exp(λ_K T)
    // to 1e-9. Then a simulation (DOP853 at rtol 1e-12) of a 1e-6 perturbation δ0 = Re v along
    // the least stable multiplier's eigenvector over one and two periods gives
    // det[δ1 δ2] / det[δ0 δ1] = det Φ = |μ|² (complex pair) exactly in linear theory: the growth
    // per period it measures equals the computed Floquet exponent to 1e-4 relative (the
    // nonlinearity is 1e-6 of the perturbation).
    let g0 = [0.5, 0.2];
    for (c, expect) in [([[-0.1, 1.3], [-0.6, -0.3]], Verdict::Stable), ([[0.15, 1.3], [-0.6, -0.05]], Verdict::Unstable)] {
        let f = Rotating::new(c, g0, 0.3, 1.0);
        let frozen = crate::linalg::eigen_dyn::spectral_abscissa(&[c[0][0], c[0][1] - 1.0, c[1][0] + 1.0, c[1][1]], 2).unwrap();
        let ystar = f.orbit_start();
        let s = stationary(&f, &[ystar[0] + 0.3, ystar[1] - 0.2], &NewtonOptions::default()).unwrap();
        assert!((s.x[0] - ystar[0]).abs() < 1e-10 && (s.x[1] - ystar[1]).abs() < 1e-10, "{:?} against {ystar:?}", s.x);
        let st = stability(&f, &s).unwrap();
        assert_eq!((st.kind, st.verdict), (Kind::PeriodicOrbit, expect), "frozen-time abscissa {frozen}");
        let exact = f.multipliers();
        for m in &st.spectrum {
            let d = exact.iter().map(|e| (e - m.complex()).norm()).fold(f64::INFINITY, f64::min);
            assert!(d < 1e-9, "{m:?} against {exact:?}");
        }
        if expect == Verdict::Stable {
            assert!(frozen > 0.0, "the frozen-time matrix is unstable ({frozen}) where Floquet says stable");
        }
        // simulation
        let t = f.period().unwrap();
        let mu = st.spectrum[st.least_stable.unwrap()].complex();
        assert!(mu.im != 0.0, "a complex pair: {mu}");
        let v = super::mode(&st.matrix, 2, mu);
        let d0 = [1e-6 * v[0].re, 1e-6 * v[1].re];
        let sys = Ode(&f);
        let mut solver = Solver::new(&sys, Options::new(1e-12, 1e-16).method(Method::Dop853)).unwrap();
        let mut y = [s.x[0] + d0[0], s.x[1] + d0[1]];
        let mut deltas = vec![d0];
        for k in 1..=2 {
            let out = solver.integrate((k - 1) as f64 * t, &mut y, k as f64 * t, |_| Control::Continue);
            assert!(out.status.is_completed());
            deltas.push([y[0] - s.x[0], y[1] - s.x[1]]);
        }
        let det = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
        let ratio = det(deltas[1], deltas[2]) / det(deltas[0], deltas[1]);
        let measured = ratio.ln() / (2.0 * t);
        assert!((measured - st.abscissa).abs() < 1e-4 * st.abscissa.abs(), "measured {measured}, computed {}", st.abscissa);
    }
}

#[test]
fn shooting_from_a_neighbours_monodromy_finds_the_same_orbit_and_multipliers() {
    // stationary_near: the quasi-Newton shooting started with another matrix than the exact
    // one at the guess must end at the same orbit (to the shooting's 1e-10) with its own
    // exact multipliers exp(λ_K T) (to 1e-9, as above): with a neighbouring speed's monodromy
    // (ω 5% higher: the continuation's case), with a useless one (Φ = 0, so I − Φ = I: the
    // exact matrix must be fetched when the steps stall), and with one of the wrong size
    // (ignored). The monodromy returned is integrated at the orbit, not the hint updated.
    let g0 = [0.5, 0.2];
    let c = [[-0.1, 1.3], [-0.6, -0.3]];
    let f = Rotating::new(c, g0, 0.3, 1.0);
    let neighbour = Rotating::new(c, g0, 0.3, 1.05);
    let y = neighbour.orbit_start();
    let hint = stationary(&neighbour, &y, &NewtonOptions::default()).unwrap().monodromy.unwrap();
    let ystar = f.orbit_start();
    let exact = f.multipliers();
    for h in [hint, vec![0.0; 4], vec![1.0; 3]] {
        let s = stationary_near(&f, &[ystar[0] + 0.3, ystar[1] - 0.2], Some(&h), &NewtonOptions::default()).unwrap();
        assert!((s.x[0] - ystar[0]).abs() < 1e-10 && (s.x[1] - ystar[1]).abs() < 1e-10, "hint {h:?}: {:?} against {ystar:?}", s.x);
        let st = stability(&f, &s).unwrap();
        for m in &st.spectrum {
            let d = exact.iter().map(|e| (e - m.complex()).norm()).fold(f64::INFINITY, f64::min);
            assert!(d < 1e-9, "hint {h:?}: {m:?} against {exact:?}");
        }
    }
}

#[test]
fn a_periodic_range_end_is_located_to_1e_9_in_few_trials() {
    // The rotating field above with C(p) = C0 + (p − 1.3)/4 · I: the orbit's exact Floquet
    // abscissa α(p) = Re λ_max(K(p)) (K = C + 2β y* y*ᵀ, y* = −C⁻¹ g0: nonlinear in p) crosses
    // zero once in [1, 2]; its root p* by bisection on the closed form to round-off. The scan
    // (shooting, monodromy, Floquet) over a grid of 5 must place the end at p* to
    // 1e-9 p* (the bracket's 1e-9 relative width, plus the computed α's own error over its
    // slope: multipliers exact to ~1e-10 at rtol 1e-12 (test above: < 1e-9), so α to
    // ~1e-10 / T = 2e-11, over α' ≈ 0.25: 1e-10 in p), in at most 10 trial speeds where
    // bisection on the verdict would take log2(0.25 / 1.5e-9) ≈ 28.
    let g0 = [0.5, 0.2];
    let c_at = |p: f64| {
        let d = 0.25 * (p - 1.3);
        [[-0.1 + d, 1.3], [-0.6, -0.3 + d]]
    };
    let exact_alpha = |p: f64| {
        let f = Rotating::new(c_at(p), g0, 0.3, 1.0);
        let mu = f.multipliers();
        mu.iter().map(|m| m.norm().ln()).fold(f64::NEG_INFINITY, f64::max) / f.period().unwrap()
    };
    let (mut lo, mut hi) = (1.0, 2.0);
    assert!(exact_alpha(lo) < 0.0 && exact_alpha(hi) > 0.0, "{} {}", exact_alpha(lo), exact_alpha(hi));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            break;
        }
        if exact_alpha(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let root = 0.5 * (lo + hi);
    let calls = std::cell::Cell::new(0);
    let grid = [1.0, 1.25, 1.5, 1.75, 2.0];
    let scan = speed_scan(
        |p| {
            calls.set(calls.get() + 1);
            Ok(Rotating::new(c_at(p), g0, 0.3, 1.0))
        },
        |f, _| {
            let y = f.orbit_start();
            Some(vec![y[0] + 1e-3, y[1] - 1e-3])
        },
        &grid,
        &ScanOptions::default(),
    )
    .unwrap();
    let ends: Vec<f64> = scan.stable_ranges.iter().filter(|r| r.to_is_boundary).map(|r| r.to).collect();
    assert_eq!(ends.len(), 1, "{:?}", scan.stable_ranges);
    let trials = calls.get() - grid.len();
    eprintln!("end {} against {root}: {:.1e} relative, {trials} trials", ends[0], (ends[0] - root).abs() / root);
    assert!((ends[0] - root).abs() <= 1e-9 * root, "end {} against {root}", ends[0]);
    assert!(trials <= 10, "{trials} trial speeds");
}

/// `f₁ = x₁ + x₂²/2`, `f₂ = ε (x₂ − 1)`: the root `(−1/2, 1)` in closed form, one state held by
/// an equation `ε = 1e-8` as strong as the other (a balancer's balls at low speed against its
/// structure: the scaled rows measured ~1e-8 apart on audit 20's rnd/r19_00_sp.toml at 11.6
/// rad/s).
struct WeakRow;

impl VectorField for WeakRow {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, x: &[f64], dx: &mut [f64]) {
        dx[0] = x[0] + 0.5 * x[1] * x[1];
        dx[1] = 1e-8 * (x[1] - 1.0);
    }
    fn jacobian(&self, _t: f64, x: &[f64], j: &mut [f64]) {
        j.copy_from_slice(&[1.0, x[1], 0.0, 1e-8]);
    }
    fn period(&self) -> Option<f64> {
        None
    }
}

/// Newton from `(0, 0)` on [`WeakRow`]: the first step `d = (0, 1)` lands exactly on `x₂ = 1`,
/// leaving `f₁ = 1/2` (its second-order term), which is 5e7 times the start's residual `ε`:
/// backtracking on the residual alone accepts only `λ ≈ √(2ε) ≈ 1.4e-4` and crawls (main at
/// e506c10: "iteration limit" at 50 iterations, residual ~1e-8), while the simplified Newton
/// correction there is `(−1/2, 0)`, shorter than `3/4 |d|`: the natural monotonicity test takes
/// the full step, and the next (exact, `f` being linear in `x₁`) ends on the root. The root to
/// 1e-15 (the residual's tolerance 1e-12 over the weak row's 1e-8 gives `x₂` to 1e-4 at worst;
/// the two exact steps land on it to rounding).
#[test]
fn newton_takes_the_full_step_where_a_weak_row_makes_the_residual_grow() {
    let s = stationary(&WeakRow, &[0.0, 0.0], &NewtonOptions::default()).unwrap();
    assert!(s.iterations <= 3, "{s:?}");
    assert!((s.x[0] + 0.5).abs() <= 1e-15 && (s.x[1] - 1.0).abs() <= 1e-15, "{s:?}");
}

/// `x' = A x` with `A` a fixed `n × n` matrix: the origin is an equilibrium with the spectrum
/// of `A`.
struct Linear {
    a: Vec<f64>,
    n: usize,
}

impl VectorField for Linear {
    fn dim(&self) -> usize {
        self.n
    }
    fn rhs(&self, _t: f64, x: &[f64], dx: &mut [f64]) {
        for (i, d) in dx.iter_mut().enumerate() {
            *d = (0..self.n).map(|j| self.a[i * self.n + j] * x[j]).sum();
        }
    }
    fn jacobian(&self, _t: f64, _x: &[f64], j: &mut [f64]) {
        j.copy_from_slice(&self.a);
    }
    fn period(&self) -> Option<f64> {
        None
    }
}

#[test]
fn a_stop_asked_through_the_probe_ends_a_large_eigenvalue_solve_with_a_typed_error() {
    // at STOPPABLE_EIGEN_N states a cancelled control installed as the thread's probe ends the
    // solve (Stopped, its reason Interrupted); one state fewer, or without the probe, the solve
    // is never asked and finishes: the verdict of A = −I + a small skew part is stable
    let field = |n: usize| {
        let a: Vec<f64> = (0..n * n)
            .map(|k| {
                if k / n == k % n {
                    -1.0
                } else if k / n + 1 == k % n {
                    0.5
                } else if k % n + 1 == k / n {
                    -0.5
                } else {
                    0.0
                }
            })
            .collect();
        Linear { a, n }
    };
    let stopped = crate::control::Control::new();
    stopped.cancel();
    let big = field(STOPPABLE_EIGEN_N);
    let state = |n: usize| StationaryState { x: vec![0.0; n], period: None, iterations: 0, residual: 0.0, family_dimension: 0, monodromy: None };
    let e = crate::control::with_probe(&stopped, || stability(&big, &state(big.n))).unwrap_err();
    assert!(matches!(e, AnalysisError::Stopped { reason: crate::control::StopReason::Interrupted, .. }), "{e:?}");
    assert_eq!(e.to_string(), "the Jacobian's eigenvalues were not computed: interrupted");
    assert_eq!(stability(&big, &state(big.n)).unwrap().verdict, Verdict::Stable);
    let small = field(STOPPABLE_EIGEN_N - 1);
    assert_eq!(crate::control::with_probe(&stopped, || stability(&small, &state(small.n))).unwrap().verdict, Verdict::Stable);
}
