//! DOP853: Dormand and Prince's explicit Runge–Kutta method of order 8 with error estimators of
//! orders 5 and 3 and a 7th-order dense output, as in Hairer's `dop853.f` (step-size control,
//! error norm, stiffness test). The step loop is shared with RODAS ([`super::Solver`]); this
//! module holds the method's kernels.
//!
//! Why our own: of the crates measured (docs/notes/dependencies.md), `ode_solvers` has a wrong node
//! `c₁₂` in its DOP853 tableau and wrong dense output, and `differential-equations` swaps `s` and
//! `1 − s` in the 7th-order dense-output correction. Tests check the tableau's order conditions
//! and measure the orders of the step (8) and of the dense output (7) under step halving.

use super::dop853_tableau as tab;
use super::System;

/// Order of the method (step-size exponent `1/8`).
pub const ORDER: i32 = 8;

/// Hairer's stiffness threshold: `h |λ|` estimated at the end of a step above this (the edge of
/// DOP853's stability region on the negative real axis is at 6.4; along the imaginary axis ≈ 5.9).
pub const STIFFNESS_THRESHOLD: f64 = 6.1;

/// Radius of DOP853's stability region in the left half-plane used to predict the largest stable
/// step `5.9/ρ` from a spectral radius `ρ` (smallest radius between the imaginary and the negative
/// real axis, computed from the tableau's stability function).
pub const STABILITY_RADIUS: f64 = 5.9;

/// Buffers of one step: the 16 stage derivatives (12 of the step, 1 at the new point, 3 of the
/// dense output), the state at the 12th stage (for the stiffness test), the 7 coefficient vectors
/// of the dense output.
pub(crate) struct Work {
    n: usize,
    pub(crate) k: Vec<f64>,
    pub(crate) y12: Vec<f64>,
    cont: Vec<f64>,
    ys: Vec<f64>,
    ready: bool,
}

impl Work {
    pub(crate) fn new(n: usize) -> Self {
        Work { n, k: vec![0.0; tab::N_STAGES_EXTENDED * n], y12: vec![0.0; n], cont: vec![0.0; tab::INTERPOLATOR_POWER * n], ys: vec![0.0; n], ready: false }
    }

    /// Stage derivative `s`.
    pub(crate) fn k(&self, s: usize) -> &[f64] {
        &self.k[s * self.n..(s + 1) * self.n]
    }

    /// `ys = y + h Σ_{j<s} a_sj k_j` for the stage row `s`.
    fn stage_state(&mut self, s: usize, y: &[f64], h: f64) {
        let n = self.n;
        self.ys.copy_from_slice(y);
        for j in 0..s {
            let a = tab::A[s][j];
            if a != 0.0 {
                let ha = h * a;
                for (x, kj) in self.ys.iter_mut().zip(&self.k[j * n..(j + 1) * n]) {
                    *x += ha * kj;
                }
            }
        }
    }

    /// One attempted step from `(t, y)` with `k_0 = f(t, y)` already in stage 0: 11 right-hand
    /// sides, the 8th-order solution in `y_new`, and the error norm (Hairer's combination of the
    /// 5th- and 3rd-order estimates, `≤ 1` to accept). The derivative at the new point is not yet
    /// computed ([`Work::finish`]).
    pub(crate) fn attempt<S: System + ?Sized>(&mut self, sys: &S, t: f64, h: f64, y: &[f64], y_new: &mut [f64], atol: &[f64], rtol: f64) -> f64 {
        let n = self.n;
        self.ready = false;
        for s in 1..tab::N_STAGES {
            self.stage_state(s, y, h);
            let (lo, hi) = self.k.split_at_mut(s * n);
            let _ = lo;
            sys.rhs(t + tab::C[s] * h, &self.ys, &mut hi[..n]);
        }
        // the state of the last stage (c = 1), for the stiffness test
        self.y12.copy_from_slice(&self.ys);
        y_new.copy_from_slice(y);
        for j in 0..tab::N_STAGES {
            let b = tab::B[j];
            if b != 0.0 {
                let hb = h * b;
                for (x, kj) in y_new.iter_mut().zip(&self.k[j * n..(j + 1) * n]) {
                    *x += hb * kj;
                }
            }
        }
        let (mut e5, mut e3) = (0.0, 0.0);
        for i in 0..n {
            let (mut a5, mut a3) = (0.0, 0.0);
            for j in 0..tab::N_STAGES {
                let kj = self.k[j * n + i];
                a5 += tab::E5[j] * kj;
                a3 += tab::E3[j] * kj;
            }
            let sk = atol[i] + rtol * y[i].abs().max(y_new[i].abs());
            e5 += (a5 / sk).powi(2);
            e3 += (a3 / sk).powi(2);
        }
        let mut deno = e5 + 0.01 * e3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * e5 * (1.0 / (n as f64 * deno)).sqrt()
    }

    /// After acceptance: `k_12 = f(t + h, y_new)` (also the next step's first stage).
    pub(crate) fn finish<S: System + ?Sized>(&mut self, sys: &S, t_new: f64, y_new: &[f64]) {
        let n = self.n;
        sys.rhs(t_new, y_new, &mut self.k[tab::N_STAGES * n..(tab::N_STAGES + 1) * n]);
    }

    /// Hairer's stiffness estimate `h |λ| ≈ |h| ‖f(y_new) − f(y₁₂)‖ / ‖y_new − y₁₂‖` after
    /// [`Work::finish`].
    pub(crate) fn h_lambda(&self, h: f64, y_new: &[f64]) -> f64 {
        let n = self.n;
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            num += (self.k[tab::N_STAGES * n + i] - self.k[(tab::N_STAGES - 1) * n + i]).powi(2);
            den += (y_new[i] - self.y12[i]).powi(2);
        }
        if den > 0.0 {
            h.abs() * (num / den).sqrt()
        } else {
            0.0
        }
    }

    /// Drop the dense output of the previous step (a new step was accepted).
    pub(crate) fn invalidate(&mut self) {
        self.ready = false;
    }

    /// The 7th-order interpolant on the last accepted step `[t_old, t_old + h]` at `t`, into
    /// `out` (3 more right-hand sides on first use in a step; returns how many were used).
    pub(crate) fn interpolate<S: System + ?Sized>(&mut self, sys: &S, t_old: f64, h: f64, y_old: &[f64], y_new: &[f64], t: f64, out: &mut [f64]) -> u64 {
        let n = self.n;
        let mut used = 0;
        if !self.ready {
            for s in tab::N_STAGES + 1..tab::N_STAGES_EXTENDED {
                self.stage_state(s, y_old, h);
                let (_, hi) = self.k.split_at_mut(s * n);
                sys.rhs(t_old + tab::C[s] * h, &self.ys, &mut hi[..n]);
            }
            used = 3;
            for i in 0..n {
                let dy = y_new[i] - y_old[i];
                let k0 = self.k[i];
                let f_new = self.k[tab::N_STAGES * n + i];
                self.cont[i] = dy;
                self.cont[n + i] = h * k0 - dy;
                self.cont[2 * n + i] = 2.0 * dy - h * (f_new + k0);
                for r in 0..4 {
                    let mut acc = 0.0;
                    for j in 0..tab::N_STAGES_EXTENDED {
                        acc += tab::D[r][j] * self.k[j * n + i];
                    }
                    self.cont[(3 + r) * n + i] = h * acc;
                }
            }
            self.ready = true;
        }
        let x = (t - t_old) / h;
        let x1 = 1.0 - x;
        for i in 0..n {
            // Horner in x and (1 − x) alternately, as in Hairer's CONTD8
            let c = |r: usize| self.cont[r * n + i];
            let v = c(4) + x1 * (c(5) + x * c(6));
            let v = c(2) + x1 * (c(3) + x * v);
            let v = c(0) + x1 * (c(1) + x * v);
            out[i] = y_old[i] + x * v;
        }
        used
    }
}

/// Hairer's initial step (`HINIT`) for a method of order `order`.
pub(crate) fn initial_step<S: System + ?Sized>(
    sys: &S,
    t: f64,
    y: &[f64],
    f: &[f64],
    h_max: f64,
    order: i32,
    scale: &[f64],
    y1: &mut [f64],
    f1: &mut [f64],
) -> f64 {
    let n = y.len();
    let norm = |v: &[f64]| (v.iter().zip(scale).map(|(a, s)| (a / s).powi(2)).sum::<f64>() / n as f64).sqrt();
    let (dny, dnf) = (norm(y), norm(f));
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 { 1e-6 } else { 0.01 * dny / dnf };
    h = h.min(h_max);
    for i in 0..n {
        y1[i] = y[i] + h * f[i];
    }
    sys.rhs(t + h, y1, f1);
    for i in 0..n {
        y1[i] = f1[i] - f[i];
    }
    let der2 = norm(y1) / h;
    let der12 = der2.max(dnf);
    let h1 = if der12 <= 1e-15 { (1e-6f64).max(h.abs() * 1e-3) } else { (0.01 / der12).powf(1.0 / order as f64) };
    (100.0 * h).min(h1).min(h_max)
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
}
