//! RODAS: Hairer and Wanner's linearly implicit (Rosenbrock) method of order 4, stiffly
//! accurate and L-stable, with an embedded order-3 error estimate and a third-order dense output
//! (*Solving Ordinary Differential Equations II*, 2nd ed., 1996, section IV.7; the coefficients
//! of `rodas.f`). Each step solves six linear systems with one matrix `I/(γh) − J`, through the
//! system's [`super::Jacobian`] (dense by differences unless the system gives a structured one).
//! The step loop is shared with DOP853 ([`super::Solver`]); this module holds the kernels.
//!
//! When it pays: where the step of an explicit method is held at its stability limit by a fast
//! decaying mode (for the ball balancers: the balls' relative motion, relaxing with the time
//! constant `m r²/c_ψ`), this method takes steps set by accuracy alone.

use super::{Jacobian, System};

/// Order of the method (step-size exponent `1/4`).
pub const ORDER: i32 = 4;
/// The diagonal coefficient `γ`: the linear systems have the matrix `I/(γh) − J`.
pub const GAMMA: f64 = 0.25;
const A: [[f64; 4]; 5] = [
    [0.0; 4],
    [1.544, 0.0, 0.0, 0.0],
    [0.9466785280815826, 0.2557011698983284, 0.0, 0.0],
    [3.314825187068521, 2.896124015972201, 0.9986419139977817, 0.0],
    [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895],
];
const CC: [[f64; 5]; 6] = [
    [0.0; 5],
    [-5.6688, 0.0, 0.0, 0.0, 0.0],
    [-2.430093356833875, -0.2063599157091915, 0.0, 0.0, 0.0],
    [-0.1073529058151375, -9.594562251023355, -20.47028614809616, 0.0, 0.0],
    [7.496443313967647, -10.24680431464352, -33.99990352819905, 11.7089089320616, 0.0],
    [8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136, -6.058818238834054],
];
const C: [f64; 6] = [0.0, 0.386, 0.21, 0.63, 1.0, 1.0];
const D: [f64; 6] = [0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0];
const H2: [f64; 5] = [10.12623508344586, -7.487995877610167, -34.80091861555747, -7.992771707568823, 1.025137723295662];
const H3: [f64; 5] = [-0.6762803392801253, 6.087714651680015, 16.43084320892478, 24.76722511418386, -6.594389125716872];

/// The stage state `y + Σ_{j<i} a_ij k_j` of stage `st` (1 ≤ st ≤ 5) into `ys`; the sixth stage
/// (stiffly accurate) starts from the fifth's result `y + Σ a_5j k_j + k_5`. One pass over the
/// components, the terms added in the order of `j` (as a pass per `j` would: the same
/// rounding); the stage is a compile-time constant in the kernel dispatched to.
fn stage_state(st: usize, k: &[f64], y: &[f64], ys: &mut [f64]) {
    match st {
        1 => stage_state_of::<1>(k, y, ys),
        2 => stage_state_of::<2>(k, y, ys),
        3 => stage_state_of::<3>(k, y, ys),
        4 => stage_state_of::<4>(k, y, ys),
        5 => stage_state_of::<5>(k, y, ys),
        _ => panic!("RODAS has no stage {st}"),
    }
}

/// `J` stage increments as slices of length `n` each.
#[inline(always)]
fn increments<const J: usize>(k: &[f64], n: usize) -> [&[f64]; J] {
    std::array::from_fn(|j| &k[j * n..j * n + n])
}

#[inline(always)]
fn stage_state_of<const ST: usize>(k: &[f64], y: &[f64], ys: &mut [f64]) {
    let n = ys.len();
    let ks = increments::<5>(k, n);
    let y = &y[..n];
    let row = if ST < 4 { ST } else { 4 };
    for i in 0..n {
        let mut x = y[i];
        for j in 0..row {
            x += A[row][j] * ks[j][i];
        }
        if ST == 5 {
            x += ks[4][i];
        }
        ys[i] = x;
    }
}

/// The right-hand side `f(stage) + h d_i ∂f/∂t + Σ_{j<i} (C_ij/h) k_j` of stage `st`'s linear
/// system into `ki` (`done`: the increments `k_0..k_{st−1}`). One pass over the components, the
/// terms added in the order of `j` (bit for bit what a pass per `j` gives).
fn stage_rhs(st: usize, done: &[f64], fs: &[f64], dfdt: &[f64], h: f64, ki: &mut [f64]) {
    match st {
        0 => stage_rhs_of::<0>(done, fs, dfdt, h, ki),
        1 => stage_rhs_of::<1>(done, fs, dfdt, h, ki),
        2 => stage_rhs_of::<2>(done, fs, dfdt, h, ki),
        3 => stage_rhs_of::<3>(done, fs, dfdt, h, ki),
        4 => stage_rhs_of::<4>(done, fs, dfdt, h, ki),
        5 => stage_rhs_of::<5>(done, fs, dfdt, h, ki),
        _ => panic!("RODAS has no stage {st}"),
    }
}

#[inline(always)]
fn stage_rhs_of<const ST: usize>(done: &[f64], fs: &[f64], dfdt: &[f64], h: f64, ki: &mut [f64]) {
    let n = ki.len();
    let ks = increments::<ST>(done, n);
    let (fs, dfdt) = (&fs[..n], &dfdt[..n]);
    let hd = h * D[ST];
    let c: [f64; ST] = std::array::from_fn(|j| CC[ST][j] / h);
    for i in 0..n {
        let mut x = fs[i] + hd * dfdt[i];
        for j in 0..ST {
            x += c[j] * ks[j][i];
        }
        ki[i] = x;
    }
}

/// Buffers: the six stage increments, `∂f/∂t`, stage state and derivative, the two dense-output
/// coefficient vectors.
pub(crate) struct Work {
    n: usize,
    k: Vec<f64>,
    pub(crate) dfdt: Vec<f64>,
    ys: Vec<f64>,
    fs: Vec<f64>,
    d2: Vec<f64>,
    d3: Vec<f64>,
}

impl Work {
    pub(crate) fn new(n: usize) -> Self {
        Work { n, k: vec![0.0; 6 * n], dfdt: vec![0.0; n], ys: vec![0.0; n], fs: vec![0.0; n], d2: vec![0.0; n], d3: vec![0.0; n] }
    }

    /// One attempted step from `(t, y)` with `f = f(t, y)`, the Jacobian already updated at
    /// `(t, y)` and `dfdt` filled: factor `I/(γh) − J`, six stages, the solution in `y_new`.
    /// Returns the error norm (`≤ 1` to accept; RMS of the embedded estimate over
    /// `atol + rtol max(|y|, |y_new|)`), or `None` when the matrix is singular.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn attempt<S: System + ?Sized>(
        &mut self,
        sys: &S,
        jac: &mut dyn Jacobian,
        t: f64,
        h: f64,
        y: &[f64],
        f: &[f64],
        y_new: &mut [f64],
        atol: &[f64],
        rtol: f64,
        rhs_count: &mut u64,
    ) -> Option<f64> {
        let n = self.n;
        if !jac.factor(1.0 / (GAMMA * h)) {
            return None;
        }
        for st in 0..6 {
            if st > 0 {
                stage_state(st, &self.k, y, &mut self.ys);
                sys.rhs(t + C[st] * h, &self.ys, &mut self.fs);
                *rhs_count += 1;
            }
            // (1/(γh) − J) k_i = f(stage) + h d_i ∂f/∂t + Σ_j (C_ij/h) k_j
            let (done, rest) = self.k.split_at_mut(st * n);
            let ki = &mut rest[..n];
            stage_rhs(st, done, if st == 0 { f } else { &self.fs }, &self.dfdt, h, ki);
            jac.solve(ki);
        }
        let mut err = 0.0;
        for i in 0..n {
            let mut v = y[i] + self.k[4 * n + i] + self.k[5 * n + i];
            for j in 0..4 {
                v += A[4][j] * self.k[j * n + i];
            }
            y_new[i] = v;
            let sk = atol[i] + rtol * y[i].abs().max(v.abs());
            err += (self.k[5 * n + i] / sk).powi(2);
        }
        Some((err / n as f64).sqrt())
    }

    /// After acceptance: the dense-output coefficients of the step.
    pub(crate) fn finish(&mut self) {
        let n = self.n;
        for i in 0..n {
            let (mut a, mut b) = (0.0, 0.0);
            for j in 0..5 {
                a += H2[j] * self.k[j * n + i];
                b += H3[j] * self.k[j * n + i];
            }
            self.d2[i] = a;
            self.d3[i] = b;
        }
    }

    /// `y(θ) = (1 − θ) y0 + θ (y1 + (1 − θ)(K₂ + θ K₃))`, `θ = (t − t_old)/h`.
    pub(crate) fn interpolate(&self, t_old: f64, h: f64, y_old: &[f64], y_new: &[f64], t: f64, out: &mut [f64]) {
        let th = (t - t_old) / h;
        let th1 = 1.0 - th;
        for i in 0..self.n {
            out[i] = th1 * y_old[i] + th * (y_new[i] + th1 * (self.d2[i] + th * self.d3[i]));
        }
    }
}
