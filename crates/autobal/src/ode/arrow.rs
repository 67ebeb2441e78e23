//! Jacobians of mechanical systems whose bodies couple only through a few shared coordinates:
//! a rotor (the "border": its translation, tilt, spin) carrying `n` balls, each coupled to the
//! rotor and not to the other balls. Their mass matrix `M(q)` and the derivatives of the forces
//! have the arrow pattern
//!
//! ```text
//! [ B  B  B  B  B ]      B: border × border, dense (p × p, p small)
//! [ B  d  .  .  . ]      border × ball and ball × border: dense strips
//! [ B  .  d  .  . ]      ball × ball: diagonal
//! [ B  .  .  d  . ]
//! ```
//!
//! For `M(q) q̈ = F(t, q, q̇)` written as `y = (q, q̇)`, `y' = (q̇, M⁻¹F)`, the Jacobian is dense
//! (the balls feel each other through the rotor), but the implicit step's system
//! `(α I − J) x = b` reduces to one with an arrow matrix:
//! with `G_q = ∂R/∂q`, `G_v = ∂R/∂q̇` of the residual `R = F − M q̈` (accelerations held),
//!
//! ```text
//! (α² M − α G_v − G_q) x_q = M b_v + (α M − G_v) b_q,      x_v = α x_q − b_q,
//! ```
//!
//! solved by eliminating the diagonal block (a Schur complement of size `p`): cost `O(n p²)`,
//! linear in the number of balls, where a dense LU costs `O(n³)`.

use super::{Jacobian, System};

/// Largest border handled (rotor coordinates coupled to every ball).
pub const MAX_BORDER: usize = 6;

/// A square matrix with the arrow pattern: `p` border rows/columns, `m` diagonal entries.
#[derive(Debug, Clone, PartialEq)]
pub struct Arrow {
    /// Border size `p`.
    pub p: usize,
    /// Number of diagonal (ball) entries `m`.
    pub m: usize,
    /// Border × border block, row-major `p × p`.
    pub rr: Vec<f64>,
    /// Border rows × ball `j` column: `rb[j·p + i]` is entry `(i, p + j)`.
    pub rb: Vec<f64>,
    /// Ball `j` row × border columns: `br[j·p + i]` is entry `(p + j, i)`.
    pub br: Vec<f64>,
    /// Diagonal of the ball block: entry `(p + j, p + j)`.
    pub bb: Vec<f64>,
}

impl Arrow {
    /// Zeros, for `p` border and `m` ball coordinates.
    pub fn zeros(p: usize, m: usize) -> Self {
        Arrow { p, m, rr: vec![0.0; p * p], rb: vec![0.0; m * p], br: vec![0.0; m * p], bb: vec![0.0; m] }
    }

    /// Set every entry to zero.
    pub fn clear(&mut self) {
        self.rr.iter_mut().chain(&mut self.rb).chain(&mut self.br).chain(&mut self.bb).for_each(|x| *x = 0.0);
    }

    /// `out += s · A x` (`x` and `out` of length `p + m`).
    pub fn mul_add(&self, s: f64, x: &[f64], out: &mut [f64]) {
        match self.p {
            0 => self.mul_add_p::<0>(s, x, out),
            1 => self.mul_add_p::<1>(s, x, out),
            2 => self.mul_add_p::<2>(s, x, out),
            3 => self.mul_add_p::<3>(s, x, out),
            4 => self.mul_add_p::<4>(s, x, out),
            5 => self.mul_add_p::<5>(s, x, out),
            6 => self.mul_add_p::<6>(s, x, out),
            p => panic!("arrow border {p} above MAX_BORDER"),
        }
    }

    /// [`Arrow::mul_add`] for the border size `P == self.p` known at compile time (the loops
    /// over the border unroll); the same operations in the same order.
    #[inline(always)]
    fn mul_add_p<const P: usize>(&self, s: f64, x: &[f64], out: &mut [f64]) {
        let m = self.m;
        let (xr, xb) = x.split_at(P);
        let (or, ob) = out.split_at_mut(P);
        let (xb, ob, bb) = (&xb[..m], &mut ob[..m], &self.bb[..m]);
        let rr = &self.rr[..P * P];
        for i in 0..P {
            let mut v = 0.0;
            for k in 0..P {
                v += rr[i * P + k] * xr[k];
            }
            or[i] += s * v;
        }
        if P == 0 {
            for j in 0..m {
                ob[j] += s * (bb[j] * xb[j]);
            }
            return;
        }
        for (j, (rb, br)) in self.rb.chunks_exact(P).zip(self.br.chunks_exact(P)).take(m).enumerate() {
            let xj = xb[j];
            let mut v = bb[j] * xj;
            for i in 0..P {
                or[i] += s * rb[i] * xj;
                v += br[i] * xr[i];
            }
            ob[j] += s * v;
        }
    }

    /// The dense matrix (row-major `(p + m)²`), for tests.
    pub fn to_dense(&self) -> Vec<f64> {
        let (p, m) = (self.p, self.m);
        let n = p + m;
        let mut a = vec![0.0; n * n];
        for i in 0..p {
            for k in 0..p {
                a[i * n + k] = self.rr[i * p + k];
            }
        }
        for j in 0..m {
            for i in 0..p {
                a[i * n + p + j] = self.rb[j * p + i];
                a[(p + j) * n + i] = self.br[j * p + i];
            }
            a[(p + j) * n + p + j] = self.bb[j];
        }
        a
    }
}

/// LU factors (partial pivoting, LAPACK `getrf`/`getrs` order: the largest `|a_ik|` of the
/// column as pivot, the first on ties; whole rows swapped) of the `p × p` Schur complement of an
/// arrow matrix. The algorithm of `linalg::dense::Lu`, operation for operation, with a solve
/// for the border size known at compile time (its loops unroll).
struct BorderLu {
    a: [[f64; MAX_BORDER]; MAX_BORDER],
    piv: [usize; MAX_BORDER],
}

impl BorderLu {
    /// Factor the leading `p × p` block; `None` when a pivot is exactly zero.
    fn new(mut a: [[f64; MAX_BORDER]; MAX_BORDER], p: usize) -> Option<Self> {
        let mut piv = [0usize; MAX_BORDER];
        for k in 0..p {
            let mut r = k;
            for i in k + 1..p {
                if a[i][k].abs() > a[r][k].abs() {
                    r = i;
                }
            }
            if a[r][k] == 0.0 {
                return None;
            }
            a.swap(k, r);
            piv[k] = r;
            for i in k + 1..p {
                let f = a[i][k] / a[k][k];
                a[i][k] = f;
                if f != 0.0 {
                    for j in k + 1..p {
                        a[i][j] -= f * a[k][j];
                    }
                }
            }
        }
        Some(BorderLu { a, piv })
    }

    /// Solve `A x = b` in place (the first `P` entries of `b`, `P` the factored size): every
    /// interchange first, then the unit lower triangle, then the upper one.
    #[inline(always)]
    fn solve<const P: usize>(&self, b: &mut [f64; MAX_BORDER]) {
        for k in 0..P {
            b.swap(k, self.piv[k]);
        }
        for k in 0..P {
            for i in k + 1..P {
                b[i] -= self.a[i][k] * b[k];
            }
        }
        for k in (0..P).rev() {
            for j in k + 1..P {
                b[k] -= self.a[k][j] * b[j];
            }
            b[k] /= self.a[k][k];
        }
    }
}

/// `M(q)`, `G_q = ∂R/∂q` and `G_v = ∂R/∂q̇` of a second-order system at one state, each with
/// the arrow pattern (coordinates ordered border first, then balls).
#[derive(Debug, Clone, PartialEq)]
pub struct ArrowLinearization {
    /// Mass matrix.
    pub mass: Arrow,
    /// Derivative of the residual `F − M q̈` with respect to the coordinates.
    pub g_q: Arrow,
    /// Derivative of the residual with respect to the velocities.
    pub g_v: Arrow,
}

/// A second-order system `M(q) q̈ = F(t, q, q̇)`, state `y = (q, q̇)` (`dim = 2 nq`, `y' = (q̇,
/// q̈)`), whose mass matrix and force derivatives have the arrow pattern. A coordinate whose
/// motion is prescribed (e.g. the rotor angle under a speed drive) has the row `q̈_k = a(t)`:
/// `M_kk = 1` and nothing else in its row and column.
pub trait ArrowSystem: System {
    /// `(p, m)`: border and ball coordinate counts (`p + m = dim/2`, `p ≤` [`MAX_BORDER`]).
    fn arrow_shape(&self) -> (usize, usize);
    /// Fill `lin` at `(t, y)`, where `qdd` are the accelerations there (the second half of
    /// `f(t, y)`).
    fn linearize(&self, t: f64, y: &[f64], qdd: &[f64], lin: &mut ArrowLinearization);
}

/// The [`Jacobian`] of an [`ArrowSystem`]: solves `(α I − J) x = b` in `O(n)`.
pub struct ArrowJacobian<'a, S: ArrowSystem> {
    sys: &'a S,
    lin: ArrowLinearization,
    k: Arrow,
    schur: Option<BorderLu>,
    alpha: f64,
    rhs: Vec<f64>,
}

impl<'a, S: ArrowSystem> ArrowJacobian<'a, S> {
    /// Buffers for `sys` (allocated once).
    pub fn new(sys: &'a S) -> Self {
        let (p, m) = sys.arrow_shape();
        assert!(p <= MAX_BORDER && 2 * (p + m) == sys.dim(), "arrow shape ({p}, {m}) against dim {}", sys.dim());
        let z = Arrow::zeros(p, m);
        ArrowJacobian { sys, lin: ArrowLinearization { mass: z.clone(), g_q: z.clone(), g_v: z.clone() }, k: z, schur: None, alpha: 0.0, rhs: vec![0.0; p + m] }
    }

    /// The last linearisation.
    pub fn linearization(&self) -> &ArrowLinearization {
        &self.lin
    }
}

impl<S: ArrowSystem> Jacobian for ArrowJacobian<'_, S> {
    fn update(&mut self, t: f64, y: &[f64], f0: &[f64]) -> u64 {
        let nq = y.len() / 2;
        self.sys.linearize(t, y, &f0[nq..], &mut self.lin);
        0
    }

    fn factor(&mut self, alpha: f64) -> bool {
        let (p, m) = (self.k.p, self.k.m);
        let (mm, gq, gv) = (&self.lin.mass, &self.lin.g_q, &self.lin.g_v);
        let a2 = alpha * alpha;
        let comb = |x: f64, v: f64, q: f64| a2 * x - alpha * v - q;
        for (i, o) in self.k.rr.iter_mut().enumerate() {
            *o = comb(mm.rr[i], gv.rr[i], gq.rr[i]);
        }
        for (i, o) in self.k.rb.iter_mut().enumerate() {
            *o = comb(mm.rb[i], gv.rb[i], gq.rb[i]);
        }
        for (i, o) in self.k.br.iter_mut().enumerate() {
            *o = comb(mm.br[i], gv.br[i], gq.br[i]);
        }
        for (i, o) in self.k.bb.iter_mut().enumerate() {
            *o = comb(mm.bb[i], gv.bb[i], gq.bb[i]);
        }
        // Schur complement of the diagonal block: S = K_rr − Σ_j K_rb[j] K_br[j]ᵀ / K_bb[j]
        let mut s = [[0.0; MAX_BORDER]; MAX_BORDER];
        for i in 0..p {
            for k in 0..p {
                s[i][k] = self.k.rr[i * p + k];
            }
        }
        for j in 0..m {
            let d = self.k.bb[j];
            let scale = self.k.rb[j * p..(j + 1) * p].iter().chain(&self.k.br[j * p..(j + 1) * p]).fold(0.0f64, |a, x| a.max(x.abs()));
            if !(d.abs() > 1e-14 * scale) || !d.is_finite() {
                return false; // a vanishing ball pivot: the caller retries with a smaller step
            }
            let inv = 1.0 / d;
            for i in 0..p {
                let a = self.k.rb[j * p + i] * inv;
                for k in 0..p {
                    s[i][k] -= a * self.k.br[j * p + k];
                }
            }
        }
        self.alpha = alpha;
        self.schur = BorderLu::new(s, p);
        self.schur.is_some()
    }

    fn solve(&mut self, b: &mut [f64]) {
        match self.k.p {
            0 => self.solve_p::<0>(b),
            1 => self.solve_p::<1>(b),
            2 => self.solve_p::<2>(b),
            3 => self.solve_p::<3>(b),
            4 => self.solve_p::<4>(b),
            5 => self.solve_p::<5>(b),
            6 => self.solve_p::<6>(b),
            p => panic!("arrow border {p} above MAX_BORDER"),
        }
    }
}

impl<S: ArrowSystem> ArrowJacobian<'_, S> {
    /// [`Jacobian::solve`] for the border size `P == p` known at compile time (the loops over
    /// the border unroll); the same operations in the same order as for any `p`.
    #[inline(always)]
    fn solve_p<const P: usize>(&mut self, b: &mut [f64]) {
        let m = self.k.m;
        let nq = P + m;
        let alpha = self.alpha;
        let (bq, bv) = b.split_at_mut(nq);
        let (bq, bv) = (&mut bq[..nq], &mut bv[..nq]);
        // r = M (b_v + α b_q) − G_v b_q (b_v is overwritten below anyway)
        self.rhs.iter_mut().for_each(|x| *x = 0.0);
        for (v, q) in bv.iter_mut().zip(bq.iter()) {
            *v += alpha * q;
        }
        self.lin.mass.mul_add_p::<P>(1.0, bv, &mut self.rhs);
        self.lin.g_v.mul_add_p::<P>(-1.0, bq, &mut self.rhs);
        // K x = r by the Schur complement
        let (rr, rb) = self.rhs.split_at_mut(P);
        let (rb, kbb) = (&mut rb[..m], &self.k.bb[..m]);
        let mut g = [0.0; MAX_BORDER];
        g[..P].copy_from_slice(rr);
        if P > 0 {
            for (j, krb) in self.k.rb.chunks_exact(P).take(m).enumerate() {
                let yj = rb[j] / kbb[j];
                for i in 0..P {
                    g[i] -= krb[i] * yj;
                }
            }
        }
        if let Some(lu) = &self.schur {
            lu.solve::<P>(&mut g);
        }
        if P > 0 {
            for (j, kbr) in self.k.br.chunks_exact(P).take(m).enumerate() {
                let mut v = rb[j];
                for i in 0..P {
                    v -= kbr[i] * g[i];
                }
                rb[j] = v / kbb[j];
            }
        } else {
            for j in 0..m {
                rb[j] /= kbb[j];
            }
        }
        rr.copy_from_slice(&g[..P]);
        // x_v = α x_q − b_q
        for i in 0..nq {
            let xq = self.rhs[i];
            bv[i] = alpha * xq - bq[i];
            bq[i] = xq;
        }
    }
}
