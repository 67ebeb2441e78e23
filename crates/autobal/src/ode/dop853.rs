//! An allocation-free DOP853 integrator (Dormand–Prince 8(5,3), Hairer's `dop853.f`) with
//! 7th-order dense output, for states of at most [`CAP`] components.
//!
//! Why our own: of the crates measured (docs/dependencies.md), `ode_solvers` has a wrong
//! node `c₁₂` in its DOP853 tableau and wrong dense output, and `differential-equations` swaps
//! `s` and `1 − s` in the 7th-order dense-output correction. This one follows Hairer's step-size
//! control and error norm; tests compare it with closed-form solutions and check the order.

use super::dop853_tableau as tab;
use super::{State, Stats, Stop, System, Tolerances, CAP};

/// What the observer sees after each accepted step: the step's ends and a dense-output
/// evaluator on `[t_old, t_new]`.
pub struct Step<'a, S: System> {
    pub sys: &'a S,
    pub t_old: f64,
    pub t_new: f64,
    pub y_old: &'a State,
    pub y_new: &'a State,
    k: &'a [State; tab::N_STAGES_EXTENDED],
    f_new: &'a State,
    dense: std::cell::RefCell<Option<[State; tab::INTERPOLATOR_POWER]>>,
    extra_evals: std::cell::Cell<u64>,
}

impl<S: System> Step<'_, S> {
    /// The 7th-order interpolant at `t ∈ [t_old, t_new]` (3 extra right-hand sides on first use).
    pub fn interpolate(&self, t: f64) -> State {
        let n = self.sys.dim();
        if self.dense.borrow().is_none() {
            let h = self.t_new - self.t_old;
            let mut k = *self.k;
            for s in tab::N_STAGES + 1..tab::N_STAGES_EXTENDED {
                let mut y = *self.y_old;
                for i in 0..n {
                    let mut acc = 0.0;
                    for (j, kj) in k.iter().enumerate().take(s) {
                        acc += tab::A[s][j] * kj[i];
                    }
                    y[i] += h * acc;
                }
                let mut dy = [0.0; CAP];
                self.sys.rhs(self.t_old + tab::C[s] * h, &y[..n], &mut dy[..n]);
                k[s] = dy;
            }
            self.extra_evals.set(self.extra_evals.get() + 3);
            let mut f = [[0.0; CAP]; tab::INTERPOLATOR_POWER];
            for i in 0..n {
                let dy = self.y_new[i] - self.y_old[i];
                f[0][i] = dy;
                f[1][i] = h * k[0][i] - dy;
                f[2][i] = 2.0 * dy - h * (self.f_new[i] + k[0][i]);
                for r in 0..4 {
                    let mut acc = 0.0;
                    for (j, kj) in k.iter().enumerate() {
                        acc += tab::D[r][j] * kj[i];
                    }
                    f[3 + r][i] = h * acc;
                }
            }
            *self.dense.borrow_mut() = Some(f);
        }
        let f = self.dense.borrow().expect("set above");
        let x = (t - self.t_old) / (self.t_new - self.t_old);
        let mut y = [0.0; CAP];
        for i in 0..n {
            let mut v = 0.0;
            for (r, fr) in f.iter().enumerate().rev() {
                v += fr[i];
                // Horner in x and (1 − x) alternately, as in Hairer's CONTD8
                if (tab::INTERPOLATOR_POWER - 1 - r).is_multiple_of(2) {
                    v *= x;
                } else {
                    v *= 1.0 - x;
                }
            }
            y[i] = v + self.y_old[i];
        }
        y
    }
}

fn error_norm(n: usize, k: &[State; tab::N_STAGES_EXTENDED], h: f64, scale: &State) -> f64 {
    let (mut e5, mut e3) = (0.0, 0.0);
    for i in 0..n {
        let (mut a5, mut a3) = (0.0, 0.0);
        for j in 0..=tab::N_STAGES {
            a5 += tab::E5[j] * k[j][i];
            a3 += tab::E3[j] * k[j][i];
        }
        e5 += (a5 / scale[i]).powi(2);
        e3 += (a3 / scale[i]).powi(2);
    }
    if e5 == 0.0 && e3 == 0.0 {
        return 0.0;
    }
    h.abs() * e5 / ((e5 + 0.01 * e3) * n as f64).sqrt()
}

/// Integrate from `(t0, y0)` to `t_end`, calling `observe` after every accepted step
/// (return `false` to stop). Returns the final time, state and counters.
pub fn integrate<S: System>(
    sys: &S,
    t0: f64,
    y0: &State,
    t_end: f64,
    tol: &Tolerances,
    mut observe: impl FnMut(&Step<S>) -> bool,
) -> (f64, State, Stats, Option<Stop>) {
    let n = sys.dim();
    let dir = if t_end >= t0 { 1.0 } else { -1.0 };
    let mut stats = Stats::default();
    let mut t = t0;
    let mut y = *y0;
    let mut f = [0.0; CAP];
    sys.rhs(t, &y[..n], &mut f[..n]);
    stats.rhs_evaluations += 1;
    // initial step (Hairer, HINIT)
    let scale0: State = std::array::from_fn(|i| if i < n { tol.atol[i] + tol.rtol * y[i].abs() } else { 1.0 });
    let norm = |v: &State| (0..n).map(|i| (v[i] / scale0[i]).powi(2)).sum::<f64>().sqrt() / (n as f64).sqrt();
    let (d0, d1) = (norm(&y), norm(&f));
    let h0 = if d0 < 1e-5 || d1 < 1e-5 { 1e-6 } else { 0.01 * d0 / d1 };
    let mut y1 = y;
    for i in 0..n {
        y1[i] += dir * h0 * f[i];
    }
    let mut f1 = [0.0; CAP];
    sys.rhs(t + dir * h0, &y1[..n], &mut f1[..n]);
    stats.rhs_evaluations += 1;
    let mut df = [0.0; CAP];
    for i in 0..n {
        df[i] = f1[i] - f[i];
    }
    let d2 = norm(&df) / h0;
    let h1 = if d1 <= 1e-15 && d2 <= 1e-15 { (h0 * 1e-3).max(1e-6) } else { (0.01 / d1.max(d2)).powf(1.0 / 8.0) };
    let mut h = (100.0 * h0).min(h1).min(tol.h_max).min((t_end - t0).abs());
    let mut k = [[0.0; CAP]; tab::N_STAGES_EXTENDED];
    let mut rejected_last = false;
    const SAFETY: f64 = 0.9;
    while dir * (t_end - t) > 0.0 {
        if stats.steps >= tol.max_steps {
            return (t, y, stats, Some(Stop::TooManySteps { t }));
        }
        let min_step = 10.0 * (t.abs() * f64::EPSILON).max(f64::MIN_POSITIVE);
        if h < min_step {
            return (t, y, stats, Some(Stop::StepTooSmall { t }));
        }
        let mut hs = dir * h;
        if dir * (t + hs - t_end) > 0.0 {
            hs = t_end - t;
        }
        k[0] = f;
        for s in 1..tab::N_STAGES {
            let mut ys = y;
            for i in 0..n {
                let mut acc = 0.0;
                for (j, kj) in k.iter().enumerate().take(s) {
                    acc += tab::A[s][j] * kj[i];
                }
                ys[i] += hs * acc;
            }
            sys.rhs(t + tab::C[s] * hs, &ys[..n], &mut k[s][..n]);
        }
        let mut y_new = y;
        for i in 0..n {
            let mut acc = 0.0;
            for (j, kj) in k.iter().enumerate().take(tab::N_STAGES) {
                acc += tab::B[j] * kj[i];
            }
            y_new[i] += hs * acc;
        }
        let t_new = t + hs;
        let mut f_new = [0.0; CAP];
        sys.rhs(t_new, &y_new[..n], &mut f_new[..n]);
        k[tab::N_STAGES] = f_new;
        stats.rhs_evaluations += tab::N_STAGES as u64;
        let scale: State = std::array::from_fn(|i| if i < n { tol.atol[i] + tol.rtol * y[i].abs().max(y_new[i].abs()) } else { 1.0 });
        let err = error_norm(n, &k, hs, &scale);
        if !err.is_finite() || !(0..n).all(|i| y_new[i].is_finite()) {
            h *= 0.2;
            stats.rejected += 1;
            if h < min_step {
                return (t, y, stats, Some(Stop::NotFinite { t }));
            }
            rejected_last = true;
            continue;
        }
        if err <= 1.0 {
            let factor = if err == 0.0 { 10.0 } else { (SAFETY * err.powf(-1.0 / 8.0)).clamp(0.2, 10.0) };
            let factor = if rejected_last { factor.min(1.0) } else { factor };
            stats.steps += 1;
            let step = Step {
                sys,
                t_old: t,
                t_new,
                y_old: &y,
                y_new: &y_new,
                k: &k,
                f_new: &f_new,
                dense: std::cell::RefCell::new(None),
                extra_evals: std::cell::Cell::new(0),
            };
            let go_on = observe(&step);
            stats.rhs_evaluations += step.extra_evals.get();
            t = t_new;
            y = y_new;
            f = f_new;
            h = (hs.abs() * factor).min(tol.h_max);
            rejected_last = false;
            if !go_on {
                return (t, y, stats, Some(Stop::Requested { t }));
            }
        } else {
            stats.rejected += 1;
            h = hs.abs() * (SAFETY * err.powf(-1.0 / 8.0)).max(0.2);
            rejected_last = true;
        }
    }
    (t, y, stats, None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_conditions() {
        // Σ b_i c_i^q = 1/(q+1), q = 0..7, and row sums of A equal c
        for q in 0..8 {
            let s: f64 = (0..tab::N_STAGES).map(|i| tab::B[i] * tab::C[i].powi(q)).sum();
            assert!((s - 1.0 / (q as f64 + 1.0)).abs() < 1e-14, "q = {q}: {s}");
        }
        for i in 0..tab::N_STAGES_EXTENDED {
            let r: f64 = tab::A[i].iter().sum();
            assert!((r - tab::C[i]).abs() < 1e-14, "row {i}");
        }
        assert_eq!(tab::C[tab::N_STAGES], 1.0, "c₁₂ = 1 (the node ode_solvers got wrong)");
    }

    struct Osc;
    impl System for Osc {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -y[0];
            dy[2] = (3.0 * t).cos(); // non-autonomous: y₂ = sin(3t)/3
        }
    }

    fn tol(rtol: f64) -> Tolerances {
        Tolerances { rtol, atol: [rtol; CAP], h_max: f64::INFINITY, max_steps: 1_000_000 }
    }

    #[test]
    fn oscillator_and_dense_output_are_accurate() {
        let mut y0 = [0.0; CAP];
        y0[0] = 1.0;
        let mut worst_dense: f64 = 0.0;
        let (t, y, st, stop) = integrate(&Osc, 0.0, &y0, 20.0, &tol(1e-10), |s| {
            for k in 1..5 {
                let tt = s.t_old + (s.t_new - s.t_old) * k as f64 / 5.0;
                let v = s.interpolate(tt);
                worst_dense = worst_dense.max((v[0] - tt.cos()).abs()).max((v[2] - (3.0 * tt).sin() / 3.0).abs());
            }
            true
        });
        assert!(stop.is_none());
        assert_eq!(t, 20.0);
        assert!((y[0] - 20f64.cos()).abs() < 1e-8, "{}", y[0] - 20f64.cos());
        assert!((y[2] - (60f64).sin() / 3.0).abs() < 1e-8);
        assert!(worst_dense < 1e-8, "dense output error {worst_dense}");
        assert!(st.steps > 10 && st.steps < 400, "{st:?}");
    }

    #[test]
    fn error_falls_at_eighth_order_with_the_step() {
        // global error ∝ tol^(8/9) roughly; check tightening tolerance 100× shrinks it ≥ 30×
        let mut y0 = [0.0; CAP];
        y0[0] = 1.0;
        let e = |r: f64| {
            let (_, y, _, _) = integrate(&Osc, 0.0, &y0, 10.0, &tol(r), |_| true);
            (y[0] - 10f64.cos()).abs()
        };
        let (a, b) = (e(1e-6), e(1e-8));
        assert!(b < a / 30.0, "{a} → {b}");
    }
}
