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

    /// `ys = y + h Σ_{j<s} a_sj k_j` for the stage row `s` ([`stage_state`]).
    fn stage_state(&mut self, s: usize, y: &[f64], h: f64) {
        stage_state(s, &self.k, y, h, &mut self.ys);
    }

    /// One attempted step from `(t, y)` with `k_0 = f(t, y)` already in stage 0: 11 right-hand
    /// sides, the 8th-order solution `y_new = y + h Σ b_j k_j` (Hairer's `k4`, `k5`), and the
    /// error norm (Hairer's combination of the 5th- and 3rd-order estimates
    /// `err5 = Σ e5_j k_j`, `err3 = Σ b_j k_j − bhh₁ k_1 − bhh₂ k_9 − bhh₃ k_12`, `≤ 1` to
    /// accept). The derivative at the new point is not yet computed ([`Work::finish`]).
    pub(crate) fn attempt<S: System + ?Sized>(&mut self, sys: &S, t: f64, h: f64, y: &[f64], y_new: &mut [f64], atol: &[f64], rtol: f64) -> f64 {
        let n = self.n;
        self.ready = false;
        for s in 1..tab::N_STAGES {
            self.stage_state(s, y, h);
            let (_, hi) = self.k.split_at_mut(s * n);
            sys.rhs(t + tab::C[s] * h, &self.ys, &mut hi[..n]);
        }
        // the state of the last stage (c = 1), for the stiffness test
        self.y12.copy_from_slice(&self.ys);
        let (e5, e3) = solution_and_error(&self.k, y, h, y_new, atol, rtol);
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
            let ks = stages::<{ tab::N_STAGES_EXTENDED }>(&self.k, n);
            for i in 0..n {
                let dy = y_new[i] - y_old[i];
                let k0 = ks[0][i];
                let f_new = ks[tab::N_STAGES][i];
                self.cont[i] = dy;
                self.cont[n + i] = h * k0 - dy;
                self.cont[2 * n + i] = 2.0 * dy - h * (f_new + k0);
                let d = dense_rows(&ks, i);
                for (r, dr) in d.iter().enumerate() {
                    self.cont[(3 + r) * n + i] = h * dr;
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

/// `ys = y + h Σ_{j<s} a_sj k_j` for the stage row `s` (1 ≤ s < 16), `k` the stage
/// derivatives one after another (`k_j` = `k[j n..(j + 1) n]`, `n = ys.len()`): one pass over the
/// components, the sum formed before the product with `h` as in Hairer's `dop853.f`
/// (`y1(i) = y(i) + h*(a21*k1(i) + …)`). The row is a compile-time constant in each of the
/// kernels dispatched to, so the sum over `j` is unrolled and the tableau's zeros drop out.
pub(crate) fn stage_state(s: usize, k: &[f64], y: &[f64], h: f64, ys: &mut [f64]) {
    match s {
        1 => stage_row::<1>(k, y, h, ys),
        2 => stage_row::<2>(k, y, h, ys),
        3 => stage_row::<3>(k, y, h, ys),
        4 => stage_row::<4>(k, y, h, ys),
        5 => stage_row::<5>(k, y, h, ys),
        6 => stage_row::<6>(k, y, h, ys),
        7 => stage_row::<7>(k, y, h, ys),
        8 => stage_row::<8>(k, y, h, ys),
        9 => stage_row::<9>(k, y, h, ys),
        10 => stage_row::<10>(k, y, h, ys),
        11 => stage_row::<11>(k, y, h, ys),
        12 => stage_row::<12>(k, y, h, ys),
        13 => stage_row::<13>(k, y, h, ys),
        14 => stage_row::<14>(k, y, h, ys),
        15 => stage_row::<15>(k, y, h, ys),
        _ => panic!("DOP853 has no stage row {s}"),
    }
}

/// The stages `k_0..k_{J-1}` as `J` slices of length `n` each (their lengths are then known to
/// be `n`, so indexing them by a component `< n` needs no check).
#[inline(always)]
fn stages<const J: usize>(k: &[f64], n: usize) -> [&[f64]; J] {
    std::array::from_fn(|j| &k[j * n..j * n + n])
}

/// [`stage_state`] for the constant row `S`.
#[inline(always)]
fn stage_row<const S: usize>(k: &[f64], y: &[f64], h: f64, ys: &mut [f64]) {
    let n = ys.len();
    let ks = stages::<S>(k, n);
    let y = &y[..n];
    for i in 0..n {
        let mut acc = 0.0;
        for (j, kj) in ks.iter().enumerate() {
            let a = tab::A[S][j];
            if a != 0.0 {
                acc += a * kj[i];
            }
        }
        ys[i] = y[i] + h * acc;
    }
}

/// The 8th-order solution `y_new = y + h Σ b_j k_j` of a step from `y` with the 12 stages in
/// `k`, and the squared weighted norms `(Σ (err5_i/sk_i)², Σ (err3_i/sk_i)²)` of Hairer's 5th-
/// and 3rd-order estimates `err5 = Σ e5_j k_j`, `err3 = Σ b_j k_j − bhh₁ k_1 − bhh₂ k_9 −
/// bhh₃ k_12` (`dop853.f`: `erri = k4(i) − bhh1*k1(i) − bhh2*k9(i) − bhh3*k3(i)`), with
/// `sk_i = atol_i + rtol max(|y_i|, |y_new,i|)`. One pass over the components.
#[inline(always)]
fn solution_and_error(k: &[f64], y: &[f64], h: f64, y_new: &mut [f64], atol: &[f64], rtol: f64) -> (f64, f64) {
    let n = y_new.len();
    let ks = stages::<{ tab::N_STAGES }>(k, n);
    let (y, atol) = (&y[..n], &atol[..n]);
    let (mut e5, mut e3) = (0.0, 0.0);
    for i in 0..n {
        let (mut b, mut a5) = (0.0, 0.0);
        for (j, kj) in ks.iter().enumerate() {
            if tab::B[j] != 0.0 {
                b += tab::B[j] * kj[i];
            }
            if tab::E5[j] != 0.0 {
                a5 += tab::E5[j] * kj[i];
            }
        }
        let a3 = b - tab::BHH[0] * ks[0][i] - tab::BHH[1] * ks[8][i] - tab::BHH[2] * ks[11][i];
        let v = y[i] + h * b;
        y_new[i] = v;
        let sk = atol[i] + rtol * y[i].abs().max(v.abs());
        e5 += (a5 / sk) * (a5 / sk);
        e3 += (a3 / sk) * (a3 / sk);
    }
    (e5, e3)
}

/// `Σ_j D_rj k_j[i]` for the four rows of the dense-output matrix at component `i` (the 16
/// stages as from [`stages`]; the matrix's zeros drop out at compile time).
#[inline(always)]
fn dense_rows(ks: &[&[f64]; tab::N_STAGES_EXTENDED], i: usize) -> [f64; 4] {
    let mut d = [0.0; 4];
    for (r, dr) in d.iter_mut().enumerate() {
        for (j, kj) in ks.iter().enumerate() {
            if tab::D[r][j] != 0.0 {
                *dr += tab::D[r][j] * kj[i];
            }
        }
    }
    d
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

    #[test]
    fn hairers_bhh_give_the_third_order_weights() {
        // E3 = B − bhh at stages 1, 9, 12 (Hairer's err3 = k4 − bhh1 k1 − bhh2 k9 − bhh3 k12),
        // E3 = B elsewhere: exact in f64 (each difference rounds to the tabulated E3)
        let bhh_at = |j: usize| match j {
            0 => tab::BHH[0],
            8 => tab::BHH[1],
            11 => tab::BHH[2],
            _ => 0.0,
        };
        for j in 0..tab::N_STAGES {
            assert_eq!(tab::B[j] - bhh_at(j), tab::E3[j], "stage {j}");
        }
    }

    /// Deterministic numbers in [−1, 1) (xorshift).
    fn numbers(seed: u64, len: usize) -> Vec<f64> {
        let mut x = seed;
        (0..len)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            })
            .collect()
    }

    #[test]
    fn fused_kernels_equal_the_tableau_sums_term_by_term() {
        // the one-pass kernels against the plain double sums over the tableau (a second route:
        // every coefficient of A, B, E5, E3 and D used as tabulated, zeros included). The two
        // differ only by the order of rounding: at most (terms + 2) ε times the sum of the
        // terms' magnitudes, so 20 ε of that sum bounds it for the ≤ 16 terms here; a dropped,
        // misplaced or wrong coefficient is off by ~1e-3 of it or more.
        let n = 7;
        let (h, rtol) = (0.37, 1e-6);
        let k = numbers(3, tab::N_STAGES_EXTENDED * n);
        let y = numbers(5, n);
        let atol: Vec<f64> = numbers(7, n).iter().map(|a| 1e-8 * (2.0 + a)).collect();
        let kk = |j: usize, i: usize| k[j * n + i];
        let tol = |mag: f64| 20.0 * f64::EPSILON * mag;
        for s in 1..tab::N_STAGES_EXTENDED {
            let mut ys = vec![0.0; n];
            stage_state(s, &k, &y, h, &mut ys);
            for i in 0..n {
                let want: f64 = y[i] + (0..s).map(|j| h * tab::A[s][j] * kk(j, i)).sum::<f64>();
                let mag = y[i].abs() + (0..s).map(|j| (h * tab::A[s][j] * kk(j, i)).abs()).sum::<f64>();
                assert!((ys[i] - want).abs() <= tol(mag), "row {s}, component {i}: {} vs {want}", ys[i]);
            }
        }
        let mut y_new = vec![0.0; n];
        let (e5, e3) = solution_and_error(&k, &y, h, &mut y_new, &atol, rtol);
        let (mut w5, mut w3, mut m5, mut m3) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let want: f64 = y[i] + (0..tab::N_STAGES).map(|j| h * tab::B[j] * kk(j, i)).sum::<f64>();
            let mag = y[i].abs() + (0..tab::N_STAGES).map(|j| (h * tab::B[j] * kk(j, i)).abs()).sum::<f64>();
            assert!((y_new[i] - want).abs() <= tol(mag), "solution, component {i}");
            let sk = atol[i] + rtol * y[i].abs().max(want.abs());
            let a5: f64 = (0..tab::N_STAGES).map(|j| tab::E5[j] * kk(j, i)).sum();
            let a3: f64 = (0..tab::N_STAGES).map(|j| tab::E3[j] * kk(j, i)).sum();
            let g5: f64 = (0..tab::N_STAGES).map(|j| (tab::E5[j] * kk(j, i)).abs()).sum();
            // the fused err3 subtracts from the full 8th-order sum: its rounding scales with B's terms
            let g3: f64 = (0..tab::N_STAGES).map(|j| (tab::B[j] * kk(j, i)).abs() + (tab::E3[j] * kk(j, i)).abs()).sum();
            w5 += (a5 / sk).powi(2);
            w3 += (a3 / sk).powi(2);
            m5 += 2.0 * (a5 / sk).abs() * g5 / sk;
            m3 += 2.0 * (a3 / sk).abs() * g3 / sk;
        }
        assert!((e5 - w5).abs() <= tol(m5), "err5: {e5} vs {w5}");
        assert!((e3 - w3).abs() <= tol(m3), "err3: {e3} vs {w3}");
        let ks = stages::<{ tab::N_STAGES_EXTENDED }>(&k, n);
        for i in 0..n {
            let d = dense_rows(&ks, i);
            for r in 0..4 {
                let want: f64 = (0..tab::N_STAGES_EXTENDED).map(|j| tab::D[r][j] * kk(j, i)).sum();
                let mag: f64 = (0..tab::N_STAGES_EXTENDED).map(|j| (tab::D[r][j] * kk(j, i)).abs()).sum();
                assert!((d[r] - want).abs() <= tol(mag), "dense row {r}, component {i}");
            }
        }
    }
}
