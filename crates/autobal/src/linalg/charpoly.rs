//! The characteristic polynomial of a quadratic pencil as an exact polynomial in the speed, and
//! what it buys along a speed axis: stability verdicts, spectral abscissae and all eigenvalues at
//! a fraction of the cost of a QR iteration per speed.
//!
//! The linearised equations `M q'' + G(Ω) q' + K(Ω) q = 0` have `M` constant, `G` linear and `K`
//! quadratic in `Ω` (000, eq (6)). Every entry of `P(λ, Ω) = M λ² + G(Ω) λ + K(Ω)` is therefore a
//! polynomial of total degree ≤ 2 in `(λ, Ω)`, and
//!
//! ```text
//! det P(λ, Ω) = det M · Σ_k c_k(Ω) λ^{N−k},   deg c_k ≤ k,   N = 2n states,
//! ```
//!
//! with `c_k(Ω)` polynomials whose coefficients are found once per model by expanding the
//! determinant (Laplace along rows, memoised over column subsets: exact polynomial arithmetic, no
//! interpolation). At one speed the `N + 1` coefficients then cost `N(N+3)/2` multiply-adds
//! (Horner in `Ω`), against ~17 000 flops for the eigenvalues of the `N×N` state matrix.
//!
//! What is built on them, each tested against the QR eigenvalues of the state matrix:
//! - [`routh_count_right_of`]: the number of roots with `Re λ > s` from the Routh array of the
//!   shifted polynomial (Routh's theorem), the certificate used by the continuation of the
//!   spectral abscissa ([`AbscissaTracker`]) and of all eigenvalues ([`continue_roots`]);
//! - [`polish_root`]: Newton's method on the polynomial, with an inclusion radius
//!   `N |p(z)/p'(z)|` (a disk around `z` of that radius contains a root).

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use num_complex::Complex64;

/// Largest number of states (12: balls free).
pub const MAX_N: usize = 12;
const D: usize = MAX_N + 1;

/// The matrices of a quadratic pencil whose damping is linear and whose stiffness is quadratic
/// in the speed: `P(λ, Ω) = M λ² + (G0 + Ω G1) λ + K0 + Ω K1 + Ω² K2` (`n ≤ 6` coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PencilTerms {
    /// Number of coordinates.
    pub n: usize,
    /// `M`.
    pub m: [[f64; 6]; 6],
    /// `G0`, `G1`.
    pub g: [[[f64; 6]; 6]; 2],
    /// `K0`, `K1`, `K2`.
    pub k: [[[f64; 6]; 6]; 3],
}

/// The characteristic polynomial `Σ_k c_k(Ω) λ^{N−k}` (`c_0 = 1`) of the state matrix of a
/// [`PencilTerms`], as exact polynomials `c_k(Ω)` of degree ≤ k.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedPolynomial {
    /// State dimension `N = 2n`.
    pub states: usize,
    /// `by_power[j][k]`: coefficient of `Ω^j` in `c_k` (exact zeros for `j > k` and `k > N`),
    /// stored by power of `Ω` so that [`SpeedPolynomial::at`] runs Horner on all `c_k` at once.
    by_power: [[f64; D]; D],
    /// `Σ_j |coef[k][j]| Ω^j` bounds rounding; kept per k for the error estimate.
    abs: [[f64; D]; D],
}

impl SpeedPolynomial {
    /// Expand `det P(λ, Ω) / det M`; `None` when `M` is singular.
    ///
    /// Laplace expansion along rows: `D_r(S) = Σ_{j ∈ S} ± P[r][j] D_{r−1}(S \ {j})` over the
    /// column subsets `S` of size `r + 1` (`6·2⁵ = 192` products of bivariate polynomials for
    /// `n = 6`).
    pub fn new(t: &PencilTerms) -> Option<Self> {
        let det = expand::<D>(t)?;
        Self::from_expansion(&det, 2 * t.n)
    }

    /// From `det[k][j]`, the coefficient of `λ^k Ω^j` of `det P` (`N = nn` states).
    fn from_expansion(det: &[[f64; D]; D], nn: usize) -> Option<Self> {
        let lead = det[nn][0];
        if lead == 0.0 || !lead.is_finite() {
            return None;
        }
        let mut by_power = [[0.0; D]; D];
        let mut abs = [[0.0; D]; D];
        for k in 0..=nn {
            for j in 0..=k {
                by_power[j][k] = det[nn - k][j] / lead;
                abs[k][j] = by_power[j][k].abs();
            }
        }
        Some(SpeedPolynomial { states: nn, by_power, abs })
    }

    /// Coefficients `c_0..c_N` at speed `omega` (Horner in `Ω`; `c_k = 0` for `k > N`).
    ///
    /// All `c_k` at once, over the coefficients by power of `Ω` with fixed bounds (vectorised:
    /// 13 steps of 13 multiply-adds, against 78 dependent scalar steps row by row). For each
    /// `c_k` the powers above `k` are exact zeros, so the steps before `Ω^k` leave `0·Ω + 0 = 0`
    /// and the one at `Ω^k` gives its coefficient exactly: the same operations in the same
    /// order as Horner on `c_k` alone, the same doubles (a zero's sign aside).
    ///
    /// The step with the coefficients of `Ω^j` updates only the `c_k` with `k ≥ j` (the others
    /// are exact zeros there and stay so: `0·Ω + 0 = 0`), each step's bounds known: the same
    /// operations on the values that can be non-zero, 91 multiply-adds instead of 169.
    #[inline]
    pub fn at(&self, omega: f64) -> [f64; D] {
        /// `c_k ← c_k Ω + row_k` for `k ≥ J`.
        #[inline(always)]
        fn step<const J: usize>(c: &mut [f64; D], row: &[f64; D], omega: f64) {
            for k in J..D {
                c[k] = c[k] * omega + row[k];
            }
        }
        let b = &self.by_power;
        let mut c = b[D - 1];
        step::<11>(&mut c, &b[11], omega);
        step::<10>(&mut c, &b[10], omega);
        step::<9>(&mut c, &b[9], omega);
        step::<8>(&mut c, &b[8], omega);
        step::<7>(&mut c, &b[7], omega);
        step::<6>(&mut c, &b[6], omega);
        step::<5>(&mut c, &b[5], omega);
        step::<4>(&mut c, &b[4], omega);
        step::<3>(&mut c, &b[3], omega);
        step::<2>(&mut c, &b[2], omega);
        step::<1>(&mut c, &b[1], omega);
        step::<0>(&mut c, &b[0], omega);
        c
    }

    /// `Σ_j |c_kj| |Ω|^j` for each k: the size of the terms summed into `c_k(Ω)`, which bounds
    /// its rounding error (times a few ε).
    pub fn magnitudes(&self, omega: f64) -> [f64; D] {
        let w = omega.abs();
        let mut c = [0.0; D];
        for k in 0..=self.states {
            let row = &self.abs[k];
            let mut v = row[k];
            for j in (0..k).rev() {
                v = v * w + row[j];
            }
            c[k] = v;
        }
        c
    }
}

/// The memoised Laplace expansion along rows over column subsets, shared by [`expand`] and
/// [`pencil_polynomial`]: `minors[S] = Σ_{j ∈ S} ± P[r][j] minors[S \ {j}]` with `r = |S| − 1`,
/// `minors[∅]` given (`minors` holds it alone on entry, every subset's minor on return, by bit
/// mask). Subsets in increasing order of their bit masks: a subset's minors come from subsets
/// with one column less, whose masks are smaller, so each is built in place at the end of the
/// list (no zeroed table of all `2ⁿ`, no copy). `add(acc, minor, r, j, sign)` adds the term of
/// column `j`.
fn laplace<T: Copy>(n: usize, minors: &mut Vec<T>, zero: T, add: impl Fn(&mut T, &T, usize, usize, f64)) {
    debug_assert_eq!(minors.len(), 1);
    minors.reserve((1 << n) - 1);
    for mask in 1usize..1 << n {
        let r = mask.count_ones() as usize - 1;
        minors.push(zero);
        let (done, cur) = minors.split_at_mut(mask);
        let acc = &mut cur[0];
        let mut pos = 0;
        for j in 0..n {
            if mask & (1 << j) == 0 {
                continue;
            }
            let sign = if (r + pos).is_multiple_of(2) { 1.0 } else { -1.0 };
            pos += 1;
            add(acc, &done[mask & !(1 << j)], r, j, sign);
        }
    }
}

/// `det P(λ, Ω)` of a [`PencilTerms`] as a polynomial in `(λ, Ω)` with at most `B` powers of
/// `Ω` (`B = 1`: the terms in `Ω` are ignored, a polynomial in `λ` alone), by Laplace expansion
/// along rows memoised over column subsets: `D_r(S) = Σ_{j ∈ S} ± P[r][j] D_{r−1}(S \ {j})`,
/// every subset's minor stored once by its bit mask (row `r` = size of `S` − 1).
fn expand<const B: usize>(t: &PencilTerms) -> Option<[[f64; B]; D]> {
    let n = t.n;
    let in_omega = B > 1;
    // entries as polynomials: (λ-degree, Ω-degree, matrix)
    let entry = |i: usize, j: usize| -> [(usize, usize, f64); 6] {
        [(2, 0, t.m[i][j]), (1, 0, t.g[0][i][j]), (1, 1, t.g[1][i][j]), (0, 0, t.k[0][i][j]), (0, 1, t.k[1][i][j]), (0, 2, t.k[2][i][j])]
    };
    let mut empty = [[0.0; B]; D];
    empty[0][0] = 1.0;
    let mut minors = vec![empty];
    laplace(n, &mut minors, [[0.0; B]; D], |acc, minor, r, j, sign| {
        let deg = 2 * r; // total degree of the minors of size r
        for (ea, eb, v) in entry(r, j) {
            if v == 0.0 || (eb > 0 && !in_omega) {
                continue;
            }
            let f = sign * v;
            for a in 0..=deg {
                let len = if in_omega { (deg - a + 1).min(B - eb) } else { 1 };
                let src = &minor[a][..len];
                let dst = &mut acc[a + ea][eb..eb + len];
                for (d, x) in dst.iter_mut().zip(src) {
                    *d += f * x;
                }
            }
        }
    });
    minors.pop()
}

/// Highest degree in the parameter of the matrices of a [`PlanePolynomial`].
pub const PLANE_PARAM_DEGREE: usize = 2;
/// Pairs `(k, j)`, `j ≤ N − k`, for `N =` [`MAX_N`].
const PAIRS: usize = D * (D + 1) / 2;

/// The characteristic polynomial of a [`PencilTerms`] family whose matrices are polynomials in
/// a parameter `u`, `T(u) = Σ_l T_l u^l` (degree ≤ [`PLANE_PARAM_DEGREE`]): the exact expansion
///
/// ```text
/// det P(λ, Ω, u) = Σ_{k,j,l} b_kjl λ^k Ω^j u^l,   P = M(u) λ² + (G0(u) + Ω G1(u)) λ + K0(u) + Ω K1(u) + Ω² K2(u)
/// ```
///
/// (Laplace along rows memoised over column subsets, as [`SpeedPolynomial::new`], with a third
/// variable), so that the characteristic polynomial over a whole plane of one speed and one
/// parameter costs one expansion, and each point `~N²·deg/2` multiply-adds with its exact
/// derivatives in `Ω` and `u` ([`PlanePolynomial::at`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanePolynomial {
    /// State dimension `N = 2n`.
    pub states: usize,
    /// Degree in `u` (`≤ n ·` the matrices' degree).
    du: usize,
    /// Number of pairs `(k, j)` with `j ≤ N − k` (the powers of `λ` and `Ω` that occur).
    pairs: usize,
    /// `b[l·pairs + off_k + j]`: coefficient of `λ^k Ω^j u^l` (ascending in `λ`; `off_k` the
    /// pairs before `k`), one block per power of `u`: Horner in `u` runs over whole blocks.
    b: Vec<f64>,
}

impl PlanePolynomial {
    /// Expand `det P(λ, Ω, u)` for the family `T(u) = Σ_l terms[l] u^l`; `None` with more than
    /// [`PLANE_PARAM_DEGREE`]` + 1` terms or none.
    pub fn new(terms: &[PencilTerms]) -> Option<Self> {
        let dp = terms.len().checked_sub(1)?;
        if dp > PLANE_PARAM_DEGREE {
            return None;
        }
        let n = terms[0].n;
        // Laplace along rows memoised over column subsets (as `laplace`). A minor of `r` rows
        // has degree ≤ 2r in (λ, Ω) together and ≤ r·dp in u, so it is kept in a block of
        // (2r + 1)² (r·dp + 1) slots (`λ^a Ω^b u^c` at `(a (2r + 1) + b)(r·dp + 1) + c`), every
        // subset's block side by side in one zeroed allocation: 240 kB for 6 rows and dp = 2,
        // instead of a (N+1)³ block a subset (1.1 MB), most of whose pages a small minor never
        // wrote but its neighbours touched. The sums are the same, in the same order.
        let dims = |rows: usize| (2 * rows + 1, rows * dp + 1);
        let size = |rows: usize| {
            let (a, c) = dims(rows);
            a * a * c
        };
        let subsets = 1usize << n;
        let mut start = Vec::with_capacity(subsets);
        let mut total = 0;
        for mask in 0..subsets {
            start.push(total);
            total += size(mask.count_ones() as usize);
        }
        let mut minors = vec![0.0f64; total];
        minors[0] = 1.0;
        for mask in 1..subsets {
            let r = mask.count_ones() as usize - 1;
            let (done, cur) = minors.split_at_mut(start[mask]);
            let acc = &mut cur[..size(r + 1)];
            // the minors of r rows read, the minor of r + 1 rows written
            let ((sa, sc), (da, dc)) = (dims(r), dims(r + 1));
            let mut pos = 0;
            for j in 0..n {
                if mask & (1 << j) == 0 {
                    continue;
                }
                let sign = if (r + pos).is_multiple_of(2) { 1.0 } else { -1.0 };
                pos += 1;
                let sub = mask & !(1 << j);
                let minor = &done[start[sub]..start[sub] + size(r)];
                for (l, t) in terms.iter().enumerate() {
                    for (ea, eb, v) in
                        [(2, 0, t.m[r][j]), (1, 0, t.g[0][r][j]), (1, 1, t.g[1][r][j]), (0, 0, t.k[0][r][j]), (0, 1, t.k[1][r][j]), (0, 2, t.k[2][r][j])]
                    {
                        if v == 0.0 {
                            continue;
                        }
                        let f = sign * v;
                        let lu = sc;
                        for a in 0..=2 * r {
                            for b in 0..=2 * r - a {
                                let (src, dst) = ((a * sa + b) * sc, ((a + ea) * da + b + eb) * dc + l);
                                for (d, x) in acc[dst..dst + lu].iter_mut().zip(&minor[src..src + lu]) {
                                    *d += f * x;
                                }
                            }
                        }
                    }
                }
            }
        }
        let det = &minors[start[subsets - 1]..];
        let nn = 2 * n;
        let (dn, cn) = dims(n);
        let idx = |a: usize, b: usize, c: usize| (a * dn + b) * cn + c;
        // the degree in u: the highest power with a coefficient not exactly 0 (entries that do
        // not depend on u have exactly zero higher terms, and zero entries are skipped)
        let du = (0..=n * dp).rev().find(|&l| (0..=nn).any(|k| (0..=nn).any(|j| det[idx(k, j, l)] != 0.0))).unwrap_or(0);
        let pairs = (nn + 1) * (nn + 2) / 2;
        let mut b = Vec::with_capacity(pairs * (du + 1));
        for l in 0..=du {
            for k in 0..=nn {
                for j in 0..=nn - k {
                    b.push(det[idx(k, j, l)]);
                }
            }
        }
        Some(PlanePolynomial { states: nn, du, pairs, b })
    }

    /// `g_kj(u) = Σ_l b_kjl u^l` for every pair into `g[..pairs]` (Horner over whole blocks,
    /// started from the highest block), and with `gu` also `dg_kj/du` into it.
    fn in_u(&self, u: f64, g: &mut [f64; PAIRS], gu: Option<&mut [f64; PAIRS]>) {
        let p = self.pairs;
        let mut blocks = self.b.chunks_exact(p).rev();
        let Some(top) = blocks.next() else { return };
        let g = &mut g[..p];
        g.copy_from_slice(top);
        match gu {
            Some(gu) => {
                let gu = &mut gu[..p];
                gu.fill(0.0);
                for block in blocks {
                    for ((d, x), c) in gu.iter_mut().zip(g.iter_mut()).zip(block) {
                        *d = *d * u + *x;
                        *x = *x * u + c;
                    }
                }
            }
            None => {
                for block in blocks {
                    for (x, c) in g.iter_mut().zip(block) {
                        *x = *x * u + c;
                    }
                }
            }
        }
    }

    /// Ascending coefficients `a_0..a_N` (`a_N = 1`) of `det P(λ, Ω, u)/det M(u)` (Horner in
    /// `u`, then in `Ω`; the value of [`PlanePolynomial::at`] without its derivatives). `None`
    /// where `M(u)` is singular.
    pub fn value(&self, omega: f64, u: f64) -> Option<[f64; D]> {
        let nn = self.states;
        let mut g = [0.0; PAIRS];
        self.in_u(u, &mut g, None);
        let mut a = [0.0; D];
        let mut off = 0;
        for k in 0..=nn {
            let len = nn - k + 1;
            a[k] = g[off..off + len].iter().rev().fold(0.0, |v, c| v * omega + c);
            off += len;
        }
        let lead = a[nn];
        if lead == 0.0 || !lead.is_finite() {
            return None;
        }
        for x in &mut a[..=nn] {
            *x /= lead;
        }
        Some(a)
    }

    /// The [`SpeedPolynomial`] of the family at `u` (its coefficients in `Ω` from the plane's,
    /// Horner in `u`: no expansion). `None` where `M(u)` is singular.
    pub fn speed_polynomial(&self, u: f64) -> Option<SpeedPolynomial> {
        let nn = self.states;
        let mut g = [0.0; PAIRS];
        self.in_u(u, &mut g, None);
        let mut det = [[0.0; D]; D];
        let mut off = 0;
        for k in 0..=nn {
            let len = nn - k + 1;
            det[k][..len].copy_from_slice(&g[off..off + len]);
            off += len;
        }
        SpeedPolynomial::from_expansion(&det, nn)
    }

    /// Ascending coefficients `a_0..a_N` (`a_N = 1`) of `det P(λ, Ω, u)/det M(u)` and their
    /// exact derivatives `∂a/∂Ω`, `∂a/∂u` (`∂a = (∂b − a ∂b_N)/b_N`, `b_N = det M(u)` free of
    /// `Ω`); Horner in `u`, then in `Ω`. `None` where `M(u)` is singular.
    #[allow(clippy::type_complexity)]
    pub fn at(&self, omega: f64, u: f64) -> Option<([f64; D], [f64; D], [f64; D])> {
        let nn = self.states;
        let (mut g, mut gu) = ([0.0; PAIRS], [0.0; PAIRS]);
        self.in_u(u, &mut g, Some(&mut gu));
        let (mut a, mut da_w, mut da_u) = ([0.0; D], [0.0; D], [0.0; D]);
        let mut off = 0;
        for k in 0..=nn {
            // Σ_j g_kj(u) Ω^j: degree ≤ N − k in Ω (total degree ≤ N in (λ, Ω))
            let len = nn - k + 1;
            let (mut v, mut vw, mut vu) = (0.0, 0.0, 0.0);
            for (x, xu) in g[off..off + len].iter().zip(&gu[off..off + len]).rev() {
                vw = vw * omega + v;
                v = v * omega + x;
                vu = vu * omega + xu;
            }
            off += len;
            a[k] = v;
            da_w[k] = vw;
            da_u[k] = vu;
        }
        let (lead, dlead) = (a[nn], da_u[nn]);
        if lead == 0.0 || !lead.is_finite() {
            return None;
        }
        for k in 0..=nn {
            a[k] /= lead;
            da_w[k] /= lead;
            da_u[k] = (da_u[k] - a[k] * dlead) / lead;
        }
        Some((a, da_w, da_u))
    }
}

/// Ascending coefficients `a_0..a_N` (`a_N = 1`) of `det(M λ² + G λ + K) / det M` for one
/// pencil (the characteristic polynomial of its state matrix), by the exact expansion;
/// `None` when `M` is singular.
///
/// The expansion of [`SpeedPolynomial::new`] without the speed, specialised: the subsets in increasing order (no sort), zero entries skipped (the same sums in
/// the same order as the general expansion, a fraction of its instructions; the boundary
/// tracer calls it thousands of times).
pub fn pencil_polynomial(p: &super::small::Pencil) -> Option<[f64; D]> {
    let n = p.n;
    let mut empty = [0.0f64; D];
    empty[0] = 1.0;
    let mut minors = vec![empty];
    laplace(n, &mut minors, [0.0; D], |acc, minor, r, j, sign| {
        // most entries of M, G, K are 0; a minor of r rows has degree ≤ 2r, so only its
        // 2r + 1 lowest slots can be non-zero (the slots above hold exact zeros, whose terms
        // would add nothing: the same sums as over all 11 slots, about half the work)
        let len = 2 * r + 1;
        for (shift, v) in [(2, p.m[r][j]), (1, p.g[r][j]), (0, p.k[r][j])] {
            if v != 0.0 {
                let f = sign * v;
                for (d, x) in acc[shift..shift + len].iter_mut().zip(&minor[..len]) {
                    *d += f * x;
                }
            }
        }
    });
    let det = minors[(1 << n) - 1];
    let nn = 2 * n;
    let lead = det[nn];
    if lead == 0.0 || !lead.is_finite() {
        return None;
    }
    let mut a = [0.0; D];
    for k in 0..=nn {
        a[k] = det[k] / lead;
    }
    Some(a)
}

/// [`pencil_polynomial`] with its exact derivatives along `K` directions: given the pencil `p`
/// and the derivatives `dp[k]` of its three matrices along direction `k`, the ascending
/// coefficients `a_0..a_N` (`a_N = 1`) of `det(M λ² + G λ + K)/det M` and `∂a_j/∂θ_k`.
///
/// Dual numbers through the same expansion: every minor carries its `K` derivatives, and each
/// term `± P[r][j] D(S \ {j})` adds `± (P'[r][j] D + P[r][j] D')` to them (the product rule), so
/// the derivatives are exact for the given `dp` (no difference quotient); then
/// `∂a_j = (∂det_j − a_j ∂det M)/det M` for the normalisation. `None` when `M` is singular.
pub fn pencil_polynomial_dual<const K: usize>(p: &super::small::Pencil, dp: &[super::small::Pencil; K]) -> Option<([f64; D], [[f64; D]; K])> {
    let n = p.n;
    let mut empty = ([0.0f64; D], [[0.0f64; D]; K]);
    empty.0[0] = 1.0;
    let mut minors = vec![empty];
    laplace(n, &mut minors, ([0.0; D], [[0.0; D]; K]), |acc, minor, r, j, sign| {
        for (shift, v, dv) in [
            (2, p.m[r][j], std::array::from_fn::<f64, K, _>(|k| dp[k].m[r][j])),
            (1, p.g[r][j], std::array::from_fn(|k| dp[k].g[r][j])),
            (0, p.k[r][j], std::array::from_fn(|k| dp[k].k[r][j])),
        ] {
            if v == 0.0 && dv.iter().all(|d| *d == 0.0) {
                continue;
            }
            let f = sign * v;
            for t in 0..11 {
                acc.0[shift + t] += f * minor.0[t];
            }
            for k in 0..K {
                let fd = sign * dv[k];
                for t in 0..11 {
                    acc.1[k][shift + t] += f * minor.1[k][t] + fd * minor.0[t];
                }
            }
        }
    });
    let (det, ddet) = minors[(1 << n) - 1];
    let nn = 2 * n;
    let lead = det[nn];
    if lead == 0.0 || !lead.is_finite() {
        return None;
    }
    let mut a = [0.0; D];
    let mut da = [[0.0; D]; K];
    for j in 0..=nn {
        a[j] = det[j] / lead;
    }
    for k in 0..K {
        for j in 0..=nn {
            da[k][j] = (ddet[k][j] - a[j] * ddet[k][nn]) / lead;
        }
    }
    Some((a, da))
}

/// `det A` of an `n × n` complex matrix (`n ≤ 6`) and its derivatives along `K` directions
/// given the entries' derivatives `da[k]`: Gaussian elimination with partial pivoting carried
/// out on dual numbers `a + Σ_k a'_k ε_k` (forward-mode differentiation of the elimination:
/// the product and quotient rules at every operation), `det = ± Π u_ii` differentiated by the
/// product rule. Exact derivatives of the computed determinant, at the cost of about `K + 1`
/// eliminations; no division by `det A`, so they stay finite where `A` is singular (a point of
/// a boundary), unlike Jacobi's formula `det A · tr(A⁻¹ A')`.
pub fn det_dual<const K: usize>(a: &[[Complex64; 6]; 6], da: &[[[Complex64; 6]; 6]; K], n: usize) -> (Complex64, [Complex64; K]) {
    let mut v = *a;
    let mut d = *da;
    let mut det = Complex64::new(1.0, 0.0);
    let mut ddet = [Complex64::new(0.0, 0.0); K];
    for c in 0..n {
        // pivot: the largest value in the column
        let mut piv = c;
        for r in c + 1..n {
            if modulus(v[r][c]) > modulus(v[piv][c]) {
                piv = r;
            }
        }
        if piv != c {
            v.swap(piv, c);
            for dk in d.iter_mut() {
                dk.swap(piv, c);
            }
            det = -det;
            for x in ddet.iter_mut() {
                *x = -*x;
            }
        }
        let p = v[c][c];
        // det ← det · p (product rule)
        for k in 0..K {
            ddet[k] = ddet[k] * p + det * d[k][c][c];
        }
        det *= p;
        if p == Complex64::new(0.0, 0.0) {
            // singular to the last bit (a measure-zero event): the derivatives would need the
            // pivots not formed; NaN makes the caller's Newton step refuse the point
            return (det, [Complex64::new(f64::NAN, f64::NAN); K]);
        }
        let inv = p.inv();
        for r in c + 1..n {
            let l = v[r][c] * inv;
            let dl: [Complex64; K] = std::array::from_fn(|k| (d[k][r][c] - l * d[k][c][c]) * inv);
            if l == Complex64::new(0.0, 0.0) && dl.iter().all(|x| *x == Complex64::new(0.0, 0.0)) {
                continue;
            }
            for j in c + 1..n {
                let u = v[c][j];
                v[r][j] -= l * u;
                for k in 0..K {
                    d[k][r][j] -= dl[k] * u + l * d[k][c][j];
                }
            }
        }
    }
    (det, ddet)
}

/// Coefficients of `q(μ) = p(μ + s)` for `p(λ) = Σ_k c_k λ^{N−k}` (repeated synthetic division).
pub fn taylor_shift(c: &[f64], s: f64) -> [f64; D] {
    let n = c.len() - 1;
    let mut a = [0.0; D];
    a[..=n].copy_from_slice(c);
    for i in 0..n {
        for k in 1..=n - i {
            a[k] += s * a[k - 1];
        }
    }
    a
}

/// [`taylor_shift`] of a polynomial of degree `M − 1` held in an array (the same operations in
/// the same order, the loop bounds known: unrolled, the coefficients in registers).
#[inline(always)]
fn taylor_shift_fixed<const M: usize>(c: &[f64; M], s: f64) -> [f64; M] {
    let mut a = *c;
    for i in 0..M - 1 {
        for k in 1..M - i {
            a[k] += s * a[k - 1];
        }
    }
    a
}

/// Number of roots of `Σ_k c_k λ^{N−k}` (`c_0 > 0`) with `Re λ > 0`, by Routh's theorem (sign
/// changes in the first column of the Routh array); `None` in the singular case (a zero in the
/// first column: a root on the imaginary axis, or a pair symmetric about it).
pub fn routh_right_half_plane(c: &[f64]) -> Option<usize> {
    let n = c.len() - 1;
    // every coefficient finite, without a branch per coefficient (`|x| < ∞` is false for NaN)
    if !(c[0] > 0.0) || !c.iter().fold(true, |ok, x| ok & (x.abs() < f64::INFINITY)) {
        return None;
    }
    match <&[f64; 13]>::try_from(c) {
        Ok(c) => routh_rows_12(c),
        Err(_) => routh_rows_n(c, n),
    }
}

/// [`routh_rows_n`] for degree 12 (the map's 12 states): the rows in two arrays of fixed length
/// 8, written over in turn (`e` the even row, `o` the odd one), each step computing the entries
/// its row holds (a fixed number per step: the loops have fixed bounds) and zeroing the one
/// after, as [`routh_rows_n`] does: the same operations on the same values.
#[inline(always)]
fn routh_rows_12(c: &[f64; 13]) -> Option<usize> {
    /// One step: the new row `t[j] = t[j+1] − q b[j+1]`, `q = t[0] / b[0]`, over the older
    /// `t`, for the `L` entries it holds; its entry `L` set to zero, as `0 − q·0` is (the
    /// entries beyond are zeros already).
    #[inline(always)]
    fn step<const L: usize>(t: &mut [f64; 8], b: &[f64; 8], last: &mut f64, changes: &mut usize) -> Option<()> {
        let lead = b[0];
        if lead == 0.0 {
            return None;
        }
        if (lead > 0.0) != (*last > 0.0) {
            *changes += 1;
        }
        *last = lead;
        let q = t[0] / lead;
        if !q.is_finite() {
            return None;
        }
        for j in 0..L {
            t[j] = t[j + 1] - q * b[j + 1];
        }
        t[L] = 0.0;
        Some(())
    }
    let mut e = [c[0], c[2], c[4], c[6], c[8], c[10], c[12], 0.0];
    let mut o = [c[1], c[3], c[5], c[7], c[9], c[11], 0.0, 0.0];
    let mut changes = 0;
    let mut last = e[0];
    // rows of 7 and 6 entries; each new row one entry shorter than the row two above it
    step::<6>(&mut e, &o, &mut last, &mut changes)?;
    step::<5>(&mut o, &e, &mut last, &mut changes)?;
    step::<5>(&mut e, &o, &mut last, &mut changes)?;
    step::<4>(&mut o, &e, &mut last, &mut changes)?;
    step::<4>(&mut e, &o, &mut last, &mut changes)?;
    step::<3>(&mut o, &e, &mut last, &mut changes)?;
    step::<3>(&mut e, &o, &mut last, &mut changes)?;
    step::<2>(&mut o, &e, &mut last, &mut changes)?;
    step::<2>(&mut e, &o, &mut last, &mut changes)?;
    step::<1>(&mut o, &e, &mut last, &mut changes)?;
    step::<1>(&mut e, &o, &mut last, &mut changes)?;
    step::<0>(&mut o, &e, &mut last, &mut changes)?;
    Some(changes)
}

/// The Routh array's first column, its sign changes counted (`c_0 > 0`, all finite). Two rows
/// are kept, each new row written over the older one (`r[t][j] = r[t][j+1] − q r[b][j+1]`,
/// `q = r[t][0] / r[b][0]`); only the entries that can be non-zero are computed: the first row
/// holds `⌊n/2⌋ + 1`, and each new row one less than the row two above it (the entries beyond
/// are exact zeros, `0 − q·0`).
#[inline(always)]
fn routh_rows_n(c: &[f64], n: usize) -> Option<usize> {
    const W: usize = MAX_N / 2 + 2;
    let mut r = [[0.0f64; W]; 2];
    for i in 0..=n {
        r[i % 2][i / 2] = c[i];
    }
    let mut len = [n / 2 + 1, n.div_ceil(2)];
    let mut changes = 0;
    let mut last = r[0][0];
    for row in 0..n {
        let (t, b) = (row % 2, 1 - row % 2);
        let lead = r[b][0];
        if lead == 0.0 {
            return None;
        }
        if (lead > 0.0) != (last > 0.0) {
            changes += 1;
        }
        last = lead;
        let q = r[t][0] / lead;
        let l = len[t].saturating_sub(1);
        for j in 0..l {
            r[t][j] = r[t][j + 1] - q * r[b][j + 1];
        }
        r[t][l] = 0.0;
        len[t] = l;
    }
    Some(changes)
}

/// Whether no root of `Σ_k c_k λ^{12−k}` (degree 12) has `Re λ > s` and Routh's array of the
/// shifted polynomial is regular: exactly `routh_count_right_of(c, s) == Some(0)`, by the same
/// operations on the same values (the Taylor shift, then the Routh rows of
/// [`routh_rows_12`]), with the count replaced by what a zero count means. The count is `Some(0)`
/// iff the shifted coefficients are finite with `c_0 > 0`, every first-column entry is non-zero
/// with no change of sign from `c_0 > 0` (all `> 0`: a NaN counts as a change there), and every
/// quotient `q` is finite; here each of these is a flag and-ed in (no branch per row, no count).
#[inline(always)]
fn routh_none_right_of_12(c: &[f64; 13], s: f64) -> bool {
    #[inline(always)]
    fn step<const L: usize>(t: &mut [f64; 8], b: &[f64; 8], ok: &mut bool) {
        let lead = b[0];
        let q = t[0] / lead;
        *ok &= (lead > 0.0) & (q.abs() < f64::INFINITY);
        for j in 0..L {
            t[j] = t[j + 1] - q * b[j + 1];
        }
        t[L] = 0.0;
    }
    let c = taylor_shift_fixed(c, s);
    let mut ok = (c[0] > 0.0) & c.iter().fold(true, |ok, x| ok & (x.abs() < f64::INFINITY));
    let mut e = [c[0], c[2], c[4], c[6], c[8], c[10], c[12], 0.0];
    let mut o = [c[1], c[3], c[5], c[7], c[9], c[11], 0.0, 0.0];
    step::<6>(&mut e, &o, &mut ok);
    step::<5>(&mut o, &e, &mut ok);
    step::<5>(&mut e, &o, &mut ok);
    step::<4>(&mut o, &e, &mut ok);
    step::<4>(&mut e, &o, &mut ok);
    step::<3>(&mut o, &e, &mut ok);
    step::<3>(&mut e, &o, &mut ok);
    step::<2>(&mut o, &e, &mut ok);
    step::<2>(&mut e, &o, &mut ok);
    step::<1>(&mut o, &e, &mut ok);
    step::<1>(&mut e, &o, &mut ok);
    step::<0>(&mut o, &e, &mut ok);
    ok
}

/// `routh_count_right_of(c, s) == Some(0)`: no root with `Re λ > s` and Routh's array regular;
/// for degree 12 by the Routh rows of 12 written over in turn (the same arithmetic, flags
/// instead of a count).
#[inline]
pub fn routh_none_right_of(c: &[f64], s: f64) -> bool {
    match <&[f64; 13]>::try_from(c) {
        Ok(c) => routh_none_right_of_12(c, s),
        Err(_) => routh_count_right_of(c, s) == Some(0),
    }
}

/// Number of roots with `Re λ > s` (Routh's theorem on the shifted polynomial); `None` in the
/// singular case.
pub fn routh_count_right_of(c: &[f64], s: f64) -> Option<usize> {
    let n = c.len() - 1;
    if let Ok(c) = <&[f64; 13]>::try_from(c) {
        // the 12 states of the balls-free model: unrolled
        return routh_right_half_plane(&taylor_shift_fixed(c, s));
    }
    routh_right_half_plane(&taylor_shift(c, s)[..=n])
}

/// `|z|` as `√(re² + im²)`: within 1.5 ulp of `hypot` and a fraction of its cost; `hypot` only
/// where the square would overflow or lose digits to underflow.
#[inline]
pub fn modulus(z: Complex64) -> f64 {
    let s = z.norm_sqr();
    if (f64::MIN_POSITIVE..=f64::MAX).contains(&s) {
        s.sqrt()
    } else {
        z.norm()
    }
}

/// `p(z)` and `p'(z)` for `p(λ) = Σ_k c_k λ^{N−k}` (complex Horner).
#[inline(always)]
pub fn eval_with_derivative(c: &[f64], z: Complex64) -> (Complex64, Complex64) {
    let mut p = Complex64::new(c[0], 0.0);
    let mut dp = Complex64::new(0.0, 0.0);
    for &ck in &c[1..] {
        dp = dp * z + p;
        p = p * z + ck;
    }
    (p, dp)
}

/// Newton's method on the polynomial from `z`: at most `iterations` steps, stopping when a step
/// is below `tol`. Returns the root and an inclusion radius `N |p(z)/p'(z)|` widened by the
/// evaluation's rounding (a disk of that radius around the returned point contains a root of
/// `p`, whatever the other roots), or `None`
/// when the iteration did not settle.
pub fn polish_root(c: &[f64], mut z: Complex64, iterations: usize, tol: f64) -> Option<(Complex64, f64)> {
    for _ in 0..iterations {
        let (p, dp) = eval_with_derivative(c, z);
        if dp == Complex64::new(0.0, 0.0) || !dp.is_finite() || !p.is_finite() {
            return None;
        }
        let step = p / dp;
        z -= step;
        if modulus(step) <= tol {
            let (p, dp) = eval_with_derivative(c, z);
            return inclusion_radius(c, z, p, dp).map(|r| (z, r));
        }
    }
    None
}

/// Inclusion radius `N (|p(z)| + e_p) / (|p'(z)| − e_dp)` around `z`, with `p`, `dp` the computed
/// values and `e_p`, `e_dp` bounds on their rounding errors (complex Horner: `4Nε` times Horner on
/// the coefficients' and `z`'s magnitudes): the disk contains a root of the polynomial whatever
/// the rounding. Without `e_p` two starts that converged to one root could carry disjoint disks
/// of radius ~1e-20 about points 5e-19 apart, and be taken for two roots. `None` when `p'` is not
/// known to be non-zero.
#[inline(always)]
fn inclusion_radius(c: &[f64], z: Complex64, p: Complex64, dp: Complex64) -> Option<f64> {
    let n = c.len() - 1;
    let a = modulus(z);
    let (mut mp, mut mdp) = (c[0].abs(), 0.0);
    for &ck in &c[1..] {
        mdp = mdp * a + mp;
        mp = mp * a + ck.abs();
    }
    let gamma = 4.0 * n as f64 * f64::EPSILON;
    let den = modulus(dp) - gamma * mdp;
    let r = n as f64 * (modulus(p) + gamma * mp) / den;
    (den > 0.0 && r.is_finite()).then_some(r)
}

/// Newton on the polynomial until the step stalls at round-off: returns the point and its
/// inclusion radius `N |p/p'|` when the radius is at most `accept` (relative to `1 + |z|`).
fn converge(c: &[f64], mut z: Complex64, accept: f64) -> Option<(Complex64, f64)> {
    let mut last = f64::INFINITY;
    for it in 0..16 {
        let (p, dp) = eval_with_derivative(c, z);
        if dp == Complex64::new(0.0, 0.0) || !p.is_finite() || !dp.is_finite() {
            return None;
        }
        let step = p / dp;
        let s = modulus(step);
        let scale = 1.0 + modulus(z);
        // quadratic convergence has stopped (round-off floor), or the step is negligible
        if s <= 1e-15 * scale || (it >= 2 && s > 0.5 * last) {
            let r = inclusion_radius(c, z, p, dp)?;
            return (r <= accept * scale).then_some((z, r));
        }
        z -= step;
        last = s;
    }
    None
}

/// Most real Newton steps ([`real_newton_step`]) before [`converge_to`]'s certified ones.
const REAL_STEPS: usize = 4;

/// The Newton step `p(z)/p'(z)` of a real polynomial `p(λ) = Σ_k c_k λ^{N−k}` (`N ≥ 4`) in real
/// arithmetic: `p` divided by the real quadratic `(λ − z)(λ − z̄) = λ² − tλ + s` (`t = 2 Re z`,
/// `s = |z|²`; Bairstow's recurrence `b_k = c_k + t b_{k−1} − s b_{k−2}`) leaves the remainder
/// `b_{N−1}(λ − t) + b_N`, so `p(z) = b_N − x b_{N−1} + i y b_{N−1}` (`z = x + iy`); the quotient
/// `Q` divided again (`d_k`) gives `Q(z)`, and `p'(z) = Q(z)(2z − t) + b_{N−1} = 2iy Q(z) + b_{N−1}`.
/// Four real multiply-adds a coefficient against eight for complex Horner with its derivative.
/// Its rounding is not bounded here: it only moves a start (the certificate is evaluated by
/// [`eval_with_derivative`]). `None` for `N < 4`, or where the step is not finite.
#[inline(always)]
fn real_newton_step(c: &[f64], z: Complex64) -> Option<Complex64> {
    let n = c.len() - 1;
    if n < 4 {
        return None;
    }
    let (x, y) = (z.re, z.im);
    let (t, s) = (2.0 * x, x * x + y * y);
    let (mut b2, mut b1) = (c[0], c[1] + t * c[0]);
    let (mut d2, mut d1) = (b2, b1 + t * b2);
    for k in 2..n - 1 {
        let b = c[k] + t * b1 - s * b2;
        let d = b + t * d1 - s * d2;
        (b2, b1, d2, d1) = (b1, b, d1, d);
    }
    // b1 = b_{N−2}, b2 = b_{N−3}; d1 = d_{N−2}, d2 = d_{N−3}
    let bn1 = c[n - 1] + t * b1 - s * b2;
    let bn = c[n] + t * bn1 - s * b1;
    let p = Complex64::new(bn - x * bn1, y * bn1);
    let q = Complex64::new(d1 - x * d2, y * d2);
    let dp = Complex64::new(bn1 - 2.0 * y * q.im, 2.0 * y * q.re);
    let step = p / dp;
    step.is_finite().then_some(step)
}

/// Newton on the polynomial from `z` until the step certifies the root to `accept` (relative
/// to `1 + |z|`): at a point `z` with step `σ = p(z)/p'(z)`, the disk of radius
/// `r = N (|p| + e_p) / (|p'| − e_p')` ([`inclusion_radius`]) about `z` holds a root, so the
/// disk of radius `r + |σ|` about `z − σ` does. Returns `z − σ` and that radius at the first
/// point where it is at most `accept (1 + |z|)`; the radius is computed only once `N |σ|` is
/// that small (`r ≥ N |σ|`). From a start a continuation predicts (`|z₀ − root| ≲ 1e-6`) this
/// is two evaluations where iterating to round-off ([`converge`]) takes three or four; the point
/// returned is Newton's next iterate, within `K σ²` of the root, the radius the certified bound.
/// The first step, which certifies nothing from such a start, is the cheaper real one
/// ([`real_newton_step`]); every point certified is evaluated by complex Horner with its
/// rounding bounded.
#[inline(always)]
fn converge_to(c: &[f64], mut z: Complex64, accept: f64) -> Option<(Complex64, f64)> {
    let n = (c.len() - 1) as f64;
    let mut last = f64::INFINITY;
    // the first steps from the prediction certify nothing in practice: taken by the cheaper
    // real evaluation while they are finite, not certifying, contracting, and large (a step
    // above 1e-6 (1 + |z|) leaves an error ~K·1e-12 that the next step may not certify)
    for _ in 0..REAL_STEPS {
        let Some(step) = real_newton_step(c, z) else { break };
        let s = modulus(step);
        let scale = 1.0 + modulus(z);
        if n * s <= accept * scale || s > 0.5 * last {
            break;
        }
        z -= step;
        last = s;
        if s <= 1e-6 * scale {
            break;
        }
    }
    for it in 0..16 {
        let (p, dp) = eval_with_derivative(c, z);
        if dp == Complex64::new(0.0, 0.0) || !p.is_finite() || !dp.is_finite() {
            return None;
        }
        let step = p / dp;
        let s = modulus(step);
        let tol = accept * (1.0 + modulus(z));
        if n * s <= tol {
            let r = inclusion_radius(c, z, p, dp)? + s;
            if r <= tol {
                return Some((z - step, r));
            }
        }
        // not converging quadratically (a cluster of roots, or round-off): not certified here,
        // as in `converge`
        if it >= 2 && s > 0.5 * last {
            return None;
        }
        z -= step;
        last = s;
    }
    None
}

/// Spectral abscissa `max Re λ` along a speed axis by continuation of the rightmost root, with a
/// certificate at every speed, a continuation of all roots where that one cannot certify, and a
/// fall-back to a full eigen-solver.
///
/// At each speed, three routes in turn, the first that certifies its answer wins:
/// 1. **the rightmost root**: Newton's method on the characteristic polynomial from the
///    rightmost root of the previous speeds (extrapolated by the cubic through the last four
///    on equal steps, by the parabola through the last three otherwise), then Routh's count of
///    the roots right of `Re z + δ` must be zero (`δ` = the Newton inclusion radius plus
///    [`AbscissaTracker::GAP`]): the abscissa is within `δ ≤ ACCEPT (1 + |λ|) + GAP` of the
///    true one. Where the root was real and that fails, Newton again from
///    the pair of the quadratic Taylor model about the prediction (two real roots that met and
///    became a pair since the last speed), with the same certificate;
/// 2. **all roots** (where Newton fails or the count is not zero: another eigenvalue has
///    overtaken, or two roots collided): the whole spectrum of the last speed that had one
///    (route 2 or 3), if it is at most [`AbscissaTracker::SPECTRUM_REACH`] away, continued to
///    this speed by the Aberth–Ehrlich iteration ([`aberth_roots`]),
///    certified when the `N` inclusion disks are pairwise disjoint (then each holds exactly one
///    root: they are the whole spectrum) and each radius is at most `ACCEPT (1 + |z|)`: the
///    largest real part of the centres is within `ACCEPT (1 + |λ|)` of the true abscissa;
/// 3. **the full solver** (the caller's, e.g. the QR eigenvalues of the state matrix) where
///    route 2 has no spectrum to start from (the first speed of a line) or does not certify:
///    exact to the full solver's accuracy.
///
/// After route 2 or 3 the continuation of route 1 restarts from the rightmost root found. The
/// returned abscissa is therefore within `ACCEPT (1 + |λ|) + GAP` of the true one whenever route
/// 1 or 2 answered, and exact to the full solver's accuracy otherwise.
#[derive(Debug, Clone, Default)]
pub struct AbscissaTracker {
    hist: [(f64, Complex64); 4],
    len: usize,
    /// The whole spectrum at the last speed that had one (route 2 or 3); `nroots` of them (0:
    /// none yet).
    roots: [Complex64; MAX_N],
    nroots: usize,
    /// The speed of that spectrum.
    roots_at: f64,
    /// Number of speeds that fell back to the full solver (route 3).
    pub fallbacks: usize,
    /// Number of speeds certified by the continuation of all roots (route 2).
    pub all_roots: usize,
    /// Number of speeds certified by continuation of the rightmost root (route 1).
    pub continued: usize,
}

impl AbscissaTracker {
    /// Margin added to the Newton radius in the Routh certificate (dimensionless): a root with
    /// real part within this distance of the tracked one may be missed, so the abscissa is
    /// certified to this accuracy (far below the stability tolerance of 1e-11 in relative
    /// terms of the dimensionless eigenvalues, which are O(1)).
    pub const GAP: f64 = 1e-12;

    /// Radius to which Newton's method certifies the tracked root, and the Aberth iteration each
    /// root of the whole spectrum (relative to `1 + |λ|`): the abscissa returned by either
    /// continuation is within `ACCEPT (1 + |λ|) + GAP` of the true one.
    pub const ACCEPT: f64 = 1e-10;

    /// Largest distance in `Ω` (dimensionless) over which route 2 continues a spectrum: from
    /// farther, Aberth's iteration certifies under half of the time (measured on the default
    /// rotor's 400 × 400 map: 13 % from 1-2, 47 % from 0.6-1, 79 % from 0.3-0.6), and a refusal
    /// (ten sweeps, ~80 k instructions) plus the full solver costs more than the solver alone.
    pub const SPECTRUM_REACH: f64 = 0.6;

    /// A fresh tracker (the first speed uses the full solver).
    pub fn new() -> Self {
        Self::default()
    }

    /// Start from the whole spectrum `roots` of a nearby polynomial at `omega` (e.g. a
    /// neighbouring line's at the same speed), forgetting the history: the next speed is
    /// answered by route 2 from it where that certifies (the certificate does not depend on the
    /// starts), by the full solver otherwise.
    pub fn seed(&mut self, omega: f64, roots: &[Complex64]) {
        self.len = 0;
        if roots.len() <= MAX_N {
            self.roots[..roots.len()].copy_from_slice(roots);
            self.nroots = roots.len();
            self.roots_at = omega;
        } else {
            self.nroots = 0;
        }
    }

    /// Forget the history (the next speed uses the full solver).
    pub fn reset(&mut self) {
        self.len = 0;
        self.nroots = 0;
    }

    /// The abscissa at `omega` from the coefficients `c` (`c_0 = 1`) there; `full` returns all
    /// eigenvalues when neither continuation can certify its answer.
    pub fn abscissa<E>(&mut self, omega: f64, c: &[f64], full: impl FnOnce() -> Result<Vec<Complex64>, E>) -> Result<f64, E> {
        if let Some(a) = self.try_continue(omega, c) {
            self.continued += 1;
            return Ok(a);
        }
        let n = c.len() - 1;
        if self.nroots == n && n <= MAX_N && (omega - self.roots_at).abs() <= Self::SPECTRUM_REACH {
            let starts = self.roots;
            let mut all = [Complex64::new(0.0, 0.0); MAX_N];
            if aberth_roots(c, &starts[..n], &mut all[..n], Self::ACCEPT).is_some() {
                self.all_roots += 1;
                return Ok(self.restart(omega, &all[..n]));
            }
        }
        self.fallbacks += 1;
        let ev = full()?;
        Ok(self.restart(omega, &ev))
    }

    /// Keep the whole spectrum `ev` at `omega` and restart the continuation from its rightmost
    /// root; returns its real part.
    fn restart(&mut self, omega: f64, ev: &[Complex64]) -> f64 {
        let mut best = Complex64::new(f64::NEG_INFINITY, 0.0);
        for &z in ev {
            // prefer the member with Im ≥ 0 of a pair
            if z.re > best.re || (z.re == best.re && z.im > best.im) {
                best = z;
            }
        }
        if ev.len() <= MAX_N {
            self.roots_at = omega;
            self.roots[..ev.len()].copy_from_slice(ev);
            self.nroots = ev.len();
        } else {
            self.nroots = 0;
        }
        let best = Complex64::new(best.re, best.im.abs());
        // the history extrapolates to the new point only if it is the same root (the rightmost
        // one may have changed: then it restarts from this point)
        if self.predict(omega).is_some_and(|p| modulus(p - best) > 1e-2 * (1.0 + modulus(best))) {
            self.len = 0;
        }
        self.push(omega, best);
        best.re
    }

    /// The rightmost root at `omega` extrapolated from the history: on equal steps (a grid's
    /// speeds: the last four and `omega` equally spaced to 1e-9 of a step) the cubic through the
    /// last four speeds, `4 z₃ − 6 z₂ + 4 z₁ − z₀` (error O(h⁴)); otherwise the parabola through
    /// the last three (Lagrange; error O(h³)), the line through two, or the last root.
    fn predict(&self, omega: f64) -> Option<Complex64> {
        let (w1, z1) = *self.hist[..self.len].last()?;
        Some(match self.len {
            4 => {
                let [(a, za), (b, zb), (c, zc), (d, zd)] = self.hist;
                let h = omega - d;
                let tol = 1e-9 * h.abs();
                if ((d - c) - h).abs() <= tol && ((c - b) - h).abs() <= tol && ((b - a) - h).abs() <= tol {
                    // Newton's backward differences: z₃ + ∇z₃ + ∇²z₃ + ∇³z₃
                    let (d1, d2, d3) = (zd - zc, zc - zb, zb - za);
                    let (e1, e2) = (d1 - d2, d2 - d3);
                    zd + d1 + e1 + (e1 - e2)
                } else {
                    lagrange3([(b, zb), (c, zc), (d, zd)], omega)
                }
            }
            3 => lagrange3([self.hist[0], self.hist[1], self.hist[2]], omega),
            2 => {
                let (w0, z0) = self.hist[0];
                z1 + (z1 - z0) * ((omega - w1) / (w1 - w0))
            }
            _ => z1,
        })
    }

    fn push(&mut self, omega: f64, z: Complex64) {
        if self.len > 0 && self.hist[self.len - 1].0 == omega {
            self.hist[self.len - 1] = (omega, z);
            return;
        }
        if self.len == 4 {
            self.hist = [self.hist[1], self.hist[2], self.hist[3], self.hist[3]];
            self.len = 3;
        }
        self.hist[self.len] = (omega, z);
        self.len += 1;
    }

    fn try_continue(&mut self, omega: f64, c: &[f64]) -> Option<f64> {
        let predicted = self.predict(omega)?;
        let mut z0 = predicted;
        if z0.im.abs() < 1e-300 {
            // a real start stays real under Newton: nudge it so that a pair can form
            z0.im = 1e-7 * (1.0 + z0.re.abs());
        }
        if let Some(z) = Self::certify(c, z0) {
            self.push(omega, z);
            return Some(z.re);
        }
        if predicted.im.abs() <= 1e-9 * (1.0 + predicted.re.abs()) {
            // the real root may have met its neighbour and become a pair since the last speed
            // (Newton from the real axis then wanders): start from the quadratic model's pair
            let z = Self::certify(c, pair_start(c, predicted.re)?)?;
            // the history is the real root's; the pair's continues from here
            self.len = 0;
            self.push(omega, z);
            return Some(z.re);
        }
        None
    }

    /// Newton from `z0` ([`converge_to`]) to a point `z` (`Im z ≥ 0`) with a root within `r ≤
    /// ACCEPT (1 + |z|)` of it, and Routh's count of the roots right of `Re z + r + GAP` zero:
    /// the abscissa lies in `[Re z − r, Re z + r + GAP]`.
    #[inline(always)]
    fn certify(c: &[f64], z0: Complex64) -> Option<Complex64> {
        let (z, r) = match <&[f64; 13]>::try_from(c) {
            // the 12 states of the balls-free model: the loops' bounds known (unrolled)
            Ok(c) => converge_to(c.as_slice(), z0, Self::ACCEPT)?,
            Err(_) => converge_to(c, z0, Self::ACCEPT)?,
        };
        let z = Complex64::new(z.re, z.im.abs());
        routh_none_right_of(c, z.re + r + Self::GAP).then_some(z)
    }
}

/// The parabola through three points `(ω, z)` at `omega` (Lagrange; error O(h³)).
fn lagrange3(p: [(f64, Complex64); 3], omega: f64) -> Complex64 {
    let [(a, za), (b, zb), (c, zc)] = p;
    let la = (omega - b) * (omega - c) / ((a - b) * (a - c));
    let lb = (omega - a) * (omega - c) / ((b - a) * (b - c));
    let lc = (omega - a) * (omega - b) / ((c - a) * (c - b));
    za * la + zb * lb + zc * lc
}

/// A start for the pair that two real roots of `p` near `x` have become: the upper root of
/// the quadratic Taylor model `p(x) + p'(x) h + p''(x) h²/2` when its discriminant
/// `p'² − 2 p p''` is negative (`None` otherwise: the model's roots are real). Near a double
/// root `x_d` (`p(x_d) = p'(x_d) = 0`) the pair is `x_d ± i √(2 p(x_d)/p''(x_d))` to first
/// order, which the model reproduces.
fn pair_start(c: &[f64], x: f64) -> Option<Complex64> {
    // p, p', p''/2 by Horner
    let (mut p, mut d1, mut d2) = (c[0], 0.0, 0.0);
    for &ck in &c[1..] {
        d2 = d2 * x + d1;
        d1 = d1 * x + p;
        p = p * x + ck;
    }
    let disc = d1 * d1 - 4.0 * p * d2;
    if !(disc < 0.0) || d2 == 0.0 {
        return None;
    }
    let z = Complex64::new(x - d1 / (2.0 * d2), (-disc).sqrt() / (2.0 * d2.abs()));
    (z.re.is_finite() && z.im.is_finite()).then_some(z)
}

/// All `N` roots of the polynomial by Newton's method from the predictions `starts` (the roots
/// at a nearby speed), certified: each converged point carries an inclusion disk
/// (`N |p/p'|`), and when the `N` disks are pairwise disjoint each holds exactly one root, so the
/// points are the whole spectrum. `None` when a start does not converge or two disks overlap
/// (roots close together, or two starts drawn to one root): the caller uses a full solver.
///
/// The coefficients are real, so the roots are symmetric about the real axis: a start in the
/// lower half-plane that mirrors one in the upper half-plane (to 1e-9 relative) gets the mirror
/// of that one's root and disk (a disk's mirror contains the mirrored root), and only the
/// upper and real starts are iterated. `out[i]` is the root continued from `starts[i]`.
pub fn continue_roots(c: &[f64], starts: &[Complex64], out: &mut [Complex64]) -> Option<()> {
    let n = c.len() - 1;
    if starts.len() != n || out.len() != n {
        return None;
    }
    // mirror[i]: the upper start whose conjugate start i is, or NONE
    const NONE: usize = usize::MAX;
    let mut mirror = [NONE; MAX_N];
    let mut taken = [false; MAX_N];
    for i in 0..n {
        if starts[i].im >= 0.0 {
            continue;
        }
        let target = starts[i].conj();
        let mut best = (NONE, f64::INFINITY);
        for j in 0..n {
            if starts[j].im > 0.0 && !taken[j] {
                let d = (starts[j] - target).norm_sqr();
                if d < best.1 {
                    best = (j, d);
                }
            }
        }
        let tol = 1e-9 * (1.0 + modulus(target));
        if best.0 != NONE && best.1 <= tol * tol {
            mirror[i] = best.0;
            taken[best.0] = true;
        }
    }
    let mut r = [0.0; MAX_N];
    for i in 0..n {
        if mirror[i] != NONE {
            continue;
        }
        let mut z0 = starts[i];
        if z0.im == 0.0 {
            z0.im = 1e-7 * (1.0 + z0.re.abs()) * if i % 2 == 0 { 1.0 } else { -1.0 };
        }
        let (z, ri) = converge(c, z0, 1e-10)?;
        out[i] = z;
        r[i] = ri;
    }
    for i in 0..n {
        if mirror[i] != NONE {
            out[i] = out[mirror[i]].conj();
            r[i] = r[mirror[i]];
        }
    }
    for i in 0..n {
        for j in i + 1..n {
            if modulus(out[i] - out[j]) <= r[i] + r[j] {
                return None;
            }
        }
    }
    // a root that is real to within its radius is real (conjugate symmetry of real polynomials)
    for i in 0..n {
        if out[i].im.abs() <= r[i] {
            out[i].im = 0.0;
        }
    }
    Some(())
}

/// Largest number of sweeps of [`aberth_roots`] (from a spectrum a few speeds old it certifies
/// in 3-5; more means the starts were too far, and a full solver is cheaper).
const ABERTH_SWEEPS: usize = 10;

/// All `N` roots of the real polynomial `p(λ) = Σ_k c_k λ^{N−k}` (`c_0 ≠ 0`) by the
/// Aberth–Ehrlich iteration from `starts` (e.g. the roots at a nearby speed), certified.
///
/// Each sweep updates every root in turn (Gauss–Seidel) by
///
/// ```text
/// z_i ← z_i − w_i / (1 − w_i Σ_{j≠i} 1/(z_i − z_j)),   w_i = p(z_i)/p'(z_i)
/// ```
///
/// (Aberth 1973, Ehrlich 1967: Newton's method on `p(z)/Π_{j≠i}(z − z_j)`, cubically convergent
/// to simple roots, and the other roots repel each iterate so that two starts are not drawn to
/// one root). The disk about `z_i` of radius `N (|p| + e_p)/(|p'| − e_p')` holds a root
/// (`inclusion_radius`), so the disk of that radius plus the correction's size about the
/// corrected point does. It stops at the first sweep where every such radius is at most
/// `accept (1 + |z_i|)`, and certifies when the `N` disks are pairwise disjoint: each then holds
/// exactly one root, and the centres are the whole spectrum. Returns the largest radius.
///
/// The coefficients are real: a start in the upper half-plane stands for itself and its
/// conjugate, a real start for a real root (kept real: its correction is real), and the starts
/// in the lower half-plane are not read; `None` unless twice the upper plus the real starts
/// make `N`. A pair pushed onto the real axis becomes two real iterates either side of the
/// crossing (a pair that split into two real roots as the speed moved); two real starts whose
/// roots have become a pair do not settle. `None` when a sweep meets a non-finite value, when
/// `ABERTH_SWEEPS` sweeps do not certify, or when two disks overlap (two roots closer than
/// their radii): the caller then uses a full solver. `out` receives the roots, each upper one
/// followed by its conjugate.
pub fn aberth_roots(c: &[f64], starts: &[Complex64], out: &mut [Complex64], accept: f64) -> Option<f64> {
    let n = c.len() - 1;
    if n == 0 || n > MAX_N || starts.len() != n || out.len() != n || c[0] == 0.0 {
        return None;
    }
    // slots: one per upper start (a conjugate pair) or real start
    let mut z = [Complex64::new(0.0, 0.0); MAX_N];
    let mut pair = [false; MAX_N];
    let (mut m, mut count) = (0, 0);
    for &s in starts {
        if !(s.re.is_finite() && s.im.is_finite()) {
            return None;
        }
        if s.im >= 0.0 {
            z[m] = s;
            pair[m] = s.im > 0.0;
            count += 1 + usize::from(pair[m]);
            m += 1;
        }
    }
    if count != n {
        return None;
    }
    let nf = n as f64;
    let mut r = [0.0f64; MAX_N];
    let inv = |d: Complex64| -> Complex64 {
        let q = d.norm_sqr();
        Complex64::new(d.re / q, -d.im / q)
    };
    for _ in 0..ABERTH_SWEEPS {
        let mut certified = true;
        let slots = m;
        for i in 0..slots {
            let zi = z[i];
            let (p, dp) = eval_with_derivative(c, zi);
            if !(p.is_finite() && dp.is_finite()) {
                return None;
            }
            // Σ_{j≠i} 1/(z_i − z_j) over all N roots (a pair slot: both members)
            let mut sum = Complex64::new(0.0, 0.0);
            for j in 0..m {
                if j != i {
                    sum += inv(zi - z[j]);
                    if pair[j] {
                        sum += inv(zi - z[j].conj());
                    }
                }
            }
            if pair[i] {
                // 1/(z − z̄) = 1/(2i Im z)
                sum += Complex64::new(0.0, -0.5 / zi.im);
            }
            // w/(1 − w Σ) = p/(p' − p Σ)
            let den = dp - p * sum;
            if den == Complex64::new(0.0, 0.0) || !den.is_finite() {
                return None;
            }
            let mut corr = p / den;
            if !pair[i] {
                corr.im = 0.0;
            }
            let step = modulus(corr);
            let tol = accept * (1.0 + modulus(zi));
            // the radius only where it can pass (it is at least N |p/p'|)
            if certified && nf * modulus(p) <= tol * modulus(dp) {
                match inclusion_radius(c, zi, p, dp) {
                    Some(ri) if ri + step <= tol => r[i] = ri + step,
                    _ => certified = false,
                }
            } else {
                certified = false;
            }
            z[i] = zi - corr;
            if pair[i] && z[i].im <= 0.0 {
                // a pair pushed onto the real axis: the roots there are two real ones (a pair
                // that split as the speed moved); the slot becomes two real slots either side
                // of the crossing, as far apart as the pair's members were
                let (x, h) = (z[i].re, zi.im);
                z[i] = Complex64::new(x - h, 0.0);
                pair[i] = false;
                z[m] = Complex64::new(x + h, 0.0);
                pair[m] = false;
                m += 1;
                certified = false;
            }
        }
        if certified {
            // pairwise disjoint disks (a pair's members: 2 Im z > 2 r)
            for i in 0..m {
                if pair[i] && z[i].im <= r[i] {
                    return None;
                }
                for j in i + 1..m {
                    let rr = r[i] + r[j];
                    if modulus(z[i] - z[j]) <= rr || (pair[j] && modulus(z[i] - z[j].conj()) <= rr) {
                        return None;
                    }
                }
            }
            let mut k = 0;
            for i in 0..m {
                out[k] = z[i];
                k += 1;
                if pair[i] {
                    out[k] = z[i].conj();
                    k += 1;
                }
            }
            return Some(r[..m].iter().copied().fold(0.0, f64::max));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::small::Pencil;

    /// A pencil quadratic in θ, `P(θ) = P0 + θ P1 + θ² P2` (entries from a fixed sequence, `M`
    /// kept near the identity so that it is well conditioned), and its exact `∂P/∂θ`.
    fn family(n: usize, theta: f64) -> (Pencil, Pencil) {
        let mut x = 0.123_456_789f64;
        let mut next = || {
            x = (x * 3.987_654_321 + 0.271_828_459).fract();
            x - 0.5
        };
        let zero = Pencil { n, m: [[0.0; 6]; 6], g: [[0.0; 6]; 6], k: [[0.0; 6]; 6] };
        let (mut p, mut d) = (zero, zero);
        for i in 0..n {
            for j in 0..n {
                for (pv, dv, diag) in [(&mut p.m[i][j], &mut d.m[i][j], 1.0), (&mut p.g[i][j], &mut d.g[i][j], 0.0), (&mut p.k[i][j], &mut d.k[i][j], 2.0)] {
                    let (a, b, c) = (next(), next(), next());
                    let base = if i == j { diag } else { 0.0 };
                    *pv = base + 0.3 * a + b * theta + c * theta * theta;
                    *dv = b + 2.0 * c * theta;
                }
            }
        }
        (p, d)
    }

    /// Ascending-power product `Π (λ − r_i)` as `c_0..c_N` (`c_0 = 1`, descending powers).
    fn poly_of_roots(roots: &[Complex64]) -> Vec<f64> {
        let mut c = vec![Complex64::new(1.0, 0.0)];
        for &r in roots {
            let mut next = c.clone();
            next.push(Complex64::new(0.0, 0.0));
            for k in 1..next.len() {
                next[k] -= r * c[k - 1];
            }
            c = next;
        }
        c.iter().map(|z| z.re).collect()
    }

    /// Well-separated O(1) roots, real and in conjugate pairs, on both sides of the imaginary
    /// axis: the tests of the tracker's real Newton step and Routh zero test add a twelfth.
    const ELEVEN_ROOTS: [Complex64; 11] = [
        Complex64::new(-0.3, 1.2),
        Complex64::new(-0.3, -1.2),
        Complex64::new(0.05, 0.4),
        Complex64::new(0.05, -0.4),
        Complex64::new(-1.0, 0.0),
        Complex64::new(-2.5, 0.0),
        Complex64::new(-0.7, 2.1),
        Complex64::new(-0.7, -2.1),
        Complex64::new(0.2, 0.0),
        Complex64::new(-0.01, 0.3),
        Complex64::new(-0.01, -0.3),
    ];

    /// The real evaluation's Newton step against complex Horner's (an independent evaluation
    /// of the same `p/p'`) at points near and far from the axis, near a root and away: equal to
    /// rounding (1e-12 relative: both are backward stable for these well-separated O(1) roots,
    /// the step's conditioning at most ~1e3 here). Wrong indices in either recurrence (e.g. `Q`
    /// evaluated one coefficient short) move the step by O(1).
    #[test]
    fn real_newton_step_is_complex_horners_step() {
        let roots: Vec<Complex64> = ELEVEN_ROOTS.iter().copied().chain([Complex64::new(-4.0, 0.0)]).collect();
        for deg in [4usize, 5, 9, 12] {
            let c = poly_of_roots(&roots[..deg]);
            for z in [Complex64::new(0.06, 0.41), Complex64::new(-0.29, 1.19), Complex64::new(0.7, 0.9), Complex64::new(-1.01, 1e-7), Complex64::new(3.0, -2.0)]
            {
                let (p, dp) = eval_with_derivative(&c, z);
                let want = p / dp;
                let got = real_newton_step(&c, z).expect("finite");
                assert!(modulus(got - want) <= 1e-12 * modulus(want).max(1e-3), "deg {deg} z {z}: {got} vs {want}");
            }
        }
        assert!(real_newton_step(&[1.0, 2.0, 3.0, 4.0], Complex64::new(0.1, 0.2)).is_none());
    }

    /// The Routh zero test of the tracker ([`routh_none_right_of`], degree 12: flags instead of
    /// a count) is exactly `routh_count_right_of(c, s) == Some(0)`, at shifts around every root
    /// (counts 0 to 12 each side), and on the singular and non-finite cases (a root on the
    /// shifted axis, a zero or NaN or infinite coefficient, `c_0 ≤ 0`). A test that dropped a
    /// row's sign or a quotient's finiteness would differ from the count in one of these.
    #[test]
    fn routh_zero_test_is_the_count_being_zero() {
        let roots: Vec<Complex64> = ELEVEN_ROOTS.iter().copied().chain([Complex64::new(0.0, 0.0)]).collect();
        let c = poly_of_roots(&roots);
        let mut shifts: Vec<f64> = roots.iter().flat_map(|r| [r.re - 1e-3, r.re, r.re + 1e-13, r.re + 1e-3]).collect();
        shifts.extend([-10.0, -3.0, 0.0, 0.3, 5.0, 1e300, f64::NAN]);
        let (mut zero, mut other) = (0, 0);
        for &s in &shifts {
            let want = routh_count_right_of(&c, s) == Some(0);
            assert_eq!(routh_none_right_of(&c, s), want, "shift {s}");
            if want {
                zero += 1;
            } else {
                other += 1;
            }
        }
        assert!(zero >= 3 && other >= 40, "{zero} {other}");
        // a polynomial with every root left of the shift and another with one right of it
        let stable = poly_of_roots(&roots[4..8].iter().chain(&roots[..2]).chain(&roots[9..11]).chain(&roots[4..8]).copied().collect::<Vec<_>>());
        assert!(routh_none_right_of(&stable, 0.0) && !routh_none_right_of(&stable, -0.02));
        // singular or not finite: zeros, NaN, infinities in each position, a negative lead, a
        // subnormal (its quotient overflows: the count is `None`, e.g. `c_12` of the stable
        // polynomial at the shift 0, the Routh array's last entry)
        for p in [&c, &stable] {
            for k in 0..13 {
                for v in [0.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0, 1e-300, 1e-310, 1e300] {
                    let mut d = p.clone();
                    d[k] = v;
                    for s in [0.0, 0.25, 0.3, 5.0] {
                        assert_eq!(routh_none_right_of(&d, s), routh_count_right_of(&d, s) == Some(0), "c[{k}] = {v}, shift {s}");
                    }
                }
            }
        }
        let mut d = stable.clone();
        d[12] = 1e-310;
        assert_eq!(routh_count_right_of(&d, 0.0), None);
    }

    /// The predictor against closed forms: on equal steps it reproduces a cubic path exactly
    /// (to rounding: 1e-12 of values O(10)), on unequal steps it is the parabola through the
    /// last three points (exact on a quadratic path, not on the cubic). A wrong difference
    /// weight (e.g. `∇³` dropped, or `4, −6, 3, −1`) misses the cubic by O(h³) ≥ 1e-3 here.
    #[test]
    fn tracker_predicts_cubic_paths_on_equal_steps_and_parabolas_otherwise() {
        let cubic = |w: f64| Complex64::new(0.3 - 1.5 * w + 2.0 * w * w - 0.7 * w * w * w, 0.8 + w * w * w);
        let quad = |w: f64| Complex64::new(0.1 + 0.5 * w - 0.9 * w * w, 1.0 - 0.3 * w * w);
        let mut t = AbscissaTracker::new();
        for w in [0.5, 0.6, 0.7, 0.8] {
            t.push(w, cubic(w));
        }
        let p = t.predict(0.9).expect("history");
        assert!(modulus(p - cubic(0.9)) <= 1e-12, "{p} vs {}", cubic(0.9));
        // five points: the oldest is dropped, still equal steps
        t.push(0.9, cubic(0.9));
        assert!(modulus(t.predict(1.0).expect("history") - cubic(1.0)) <= 1e-12);
        // unequal steps: the parabola through the last three
        let mut t = AbscissaTracker::new();
        for w in [0.5, 0.6, 0.75, 0.8] {
            t.push(w, quad(w));
        }
        let p = t.predict(0.95).expect("history");
        assert!(modulus(p - quad(0.95)) <= 1e-12, "{p} vs {}", quad(0.95));
        let mut t = AbscissaTracker::new();
        for w in [0.5, 0.6, 0.75, 0.8] {
            t.push(w, cubic(w));
        }
        assert!(modulus(t.predict(0.95).expect("history") - cubic(0.95)) > 1e-4);
    }

    #[test]
    fn tracker_follows_two_real_roots_through_their_merger_into_a_pair() {
        // p(λ; Ω) = (λ² − 2aλ + a² + b(Ω)) (λ + 1)(λ + 2)(λ² + λ/2 + 4), b = (Ω − 1/2)/100: the
        // two roots a ± √(−b) are real below Ω = 1/2, meet at a and become the pair a ± i√b
        // above (the rightmost root's derivative is infinite at the meeting). Exact abscissa:
        // a + √(max(−b, 0)). The tracker's answer must be within its certificate,
        // ACCEPT (1 + |λ|) + GAP (|λ| ≤ a + 0.1 here, so 1.2e-10 + 1e-12), at every speed, and
        // the merger must be continued (route 1 from the quadratic model's pair) without the full
        // solver, which answers only the first speed.
        let a = 0.05;
        let mut t = AbscissaTracker::new();
        let mut full_calls = 0;
        // speeds off the meeting point (b = 0 would be a double root, whose computed coefficients
        // move it by √ε; at |b| ≥ 2.5e-5 the roots are 0.01 apart and move by ~1e-14)
        for j in 0..200 {
            let w = (j as f64 + 0.5) / 200.0;
            let b = (w - 0.5) / 100.0;
            let mut roots = vec![Complex64::new(-1.0, 0.0), Complex64::new(-2.0, 0.0)];
            let q = (4.0f64 - 1.0 / 16.0).sqrt();
            roots.extend([Complex64::new(-0.25, q), Complex64::new(-0.25, -q)]);
            if b < 0.0 {
                roots.extend([Complex64::new(a + (-b).sqrt(), 0.0), Complex64::new(a - (-b).sqrt(), 0.0)]);
            } else {
                roots.extend([Complex64::new(a, b.sqrt()), Complex64::new(a, -b.sqrt())]);
            }
            let c = poly_of_roots(&roots);
            let exact = a + (-b).max(0.0).sqrt();
            let got = t
                .abscissa(w, &c, || {
                    full_calls += 1;
                    Ok::<_, ()>(roots.clone())
                })
                .unwrap();
            let bound = AbscissaTracker::ACCEPT * (1.0 + a + 0.1) + AbscissaTracker::GAP;
            assert!((got - exact).abs() <= bound, "Ω = {w}: {got} vs {exact}");
        }
        assert_eq!(full_calls, 1, "only the first speed needs the full solver: {t:?}");
        assert_eq!(t.fallbacks, 1);
    }

    #[test]
    fn aberth_continues_a_whole_spectrum_and_certifies_only_what_holds() {
        // Polynomials with known roots (5 conjugate pairs and 2 real roots, or 6 pairs; real
        // and imaginary parts in [-2, 1] x [0.1, 3], separated), their coefficients the rounded
        // expansion:
        // the computed polynomial's roots are within ~1e-13 of the chosen ones for these
        // separated roots (κ ε ‖c‖). Starts: the roots moved by up to `d` times the smallest
        // distance between two roots (relative), or by up to `d` (absolute), as a nearby speed's
        // spectrum is. Whenever `aberth_roots` certifies, every output must lie within its
        // radius (≤ the returned largest, ≤ 1e-10 (1 + |z|)) plus 1e-11 of a distinct chosen
        // root: a certificate that is wrong fails here whatever the starts. Starts within a
        // fifth of the separation lie in each root's basin: it must certify nearly always
        // (≥ 95 % of 200); starts up to 1 away may be refused (those certified still checked).
        let mut x = 0.412_345_678_9f64;
        let mut next = || {
            x = (x * 3.987_654_321 + 0.271_828_459).fract();
            x
        };
        for (d, relative, want) in [(0.2, true, 0.95), (0.05, false, 0.0), (1.0, false, 0.0)] {
            let (mut ok, mut tries) = (0, 0);
            for t in 0..200 {
                let reals = if t % 2 == 0 { 2 } else { 0 };
                let mut roots = vec![];
                // one root in each cell of a 3 x 2 grid over the box (its middle 60 %), the real
                // ones in the two halves of [-2, 1]: separated by ≥ 0.2
                for k in 0..(12 - reals) / 2 {
                    let (cx, cy) = ((k % 3) as f64, (k / 3) as f64);
                    let z = Complex64::new(-2.0 + cx + 0.2 + 0.6 * next(), 0.1 + 1.45 * (cy + 0.2 + 0.6 * next()));
                    roots.extend([z, z.conj()]);
                }
                for k in 0..reals {
                    roots.push(Complex64::new(-2.0 + 1.5 * (k as f64 + 0.2 + 0.6 * next()), 0.0));
                }
                let mut sep = f64::INFINITY;
                for i in 0..12 {
                    for j in i + 1..12 {
                        sep = sep.min(modulus(roots[i] - roots[j]));
                    }
                }
                let size = if relative { d * sep } else { d };
                let mut starts = vec![];
                for z in &roots {
                    if z.im > 0.0 {
                        let s = *z + Complex64::new(size * (next() - 0.5), size * (next() - 0.5));
                        starts.extend([s, s.conj()]);
                    } else if z.im == 0.0 {
                        starts.push(*z + size * (next() - 0.5));
                    }
                }
                let c = poly_of_roots(&roots);
                let mut out = [Complex64::new(0.0, 0.0); 12];
                tries += 1;
                let Some(r) = aberth_roots(&c, &starts, &mut out, 1e-10) else { continue };
                ok += 1;
                let mut used = [false; 12];
                for z in out {
                    assert!(r <= 1e-10 * (1.0 + 3.5), "radius {r} at {z}");
                    let (i, e) = roots.iter().enumerate().filter(|(i, _)| !used[*i]).map(|(i, w)| (i, modulus(z - w))).fold((99, f64::INFINITY), |a, b| {
                        if b.1 < a.1 {
                            b
                        } else {
                            a
                        }
                    });
                    assert!(e <= r + 1e-11, "d = {d}: certified {z} is {e} from the nearest unused root (radius {r})");
                    used[i] = true;
                }
            }
            assert!(ok as f64 >= want * tries as f64, "d = {d}: certified {ok} of {tries}");
            eprintln!("d = {d}: certified {ok} of {tries}");
        }
        // starts that do not make N (a pair given as one real start), or a real pair where the
        // roots are a complex pair (the iterate cannot leave the real axis): not certified
        let roots = [Complex64::new(-0.5, 1.0), Complex64::new(-0.5, -1.0), Complex64::new(-1.0, 0.0), Complex64::new(-2.0, 0.0)];
        let c = poly_of_roots(&roots);
        let mut out = [Complex64::new(0.0, 0.0); 4];
        let short = [Complex64::new(-0.5, 0.0), Complex64::new(-1.0, 0.0), Complex64::new(-2.0, 0.0), Complex64::new(-0.5, -1.0)];
        assert!(aberth_roots(&c, &short, &mut out, 1e-10).is_none());
        let real_pair = [Complex64::new(-0.4, 0.0), Complex64::new(-0.6, 0.0), Complex64::new(-1.0, 0.0), Complex64::new(-2.0, 0.0)];
        assert!(aberth_roots(&c, &real_pair, &mut out, 1e-10).is_none());
        // the right starts: the roots
        assert!(aberth_roots(&c, &roots, &mut out, 1e-10).is_some());
        // a pair whose roots have split into two real ones (-1.1 ± 0.05 i against -1.0, -1.2):
        // pushed onto the real axis, the pair becomes two real iterates, and certifies
        let split = [Complex64::new(-0.5, 1.0), Complex64::new(-0.5, -1.0), Complex64::new(-1.0, 0.0), Complex64::new(-1.2, 0.0)];
        let c = poly_of_roots(&split);
        let starts = [Complex64::new(-0.5, 1.01), Complex64::new(-0.5, -1.01), Complex64::new(-1.1, 0.05), Complex64::new(-1.1, -0.05)];
        aberth_roots(&c, &starts, &mut out, 1e-10).expect("the split pair certifies");
        let mut re: Vec<f64> = out.iter().filter(|z| z.im == 0.0).map(|z| z.re).collect();
        re.sort_by(f64::total_cmp);
        assert!(re.len() == 2 && (re[0] + 1.2).abs() < 1e-12 && (re[1] + 1.0).abs() < 1e-12, "{out:?}");
    }

    #[test]
    fn plane_polynomial_is_the_expansion_at_each_point_and_its_derivatives() {
        // A family quadratic in u (`family`'s θ, its terms from its values at θ = 0, ±1) with the
        // speed's terms added (G1, K1, K2 from a second family), against the expansion of the
        // pencil at each (Ω, u) (`pencil_polynomial`, a second route): both exact but for
        // rounding of the terms summed (size ≤ ~1e3 here), 1e-11 relative to the largest
        // coefficient. Derivatives against central differences of that expansion (h = 1e-5:
        // truncation h²/6 |a‴| ~ 1e-11, rounding ε/h ~ 1e-11; 1e-7 of the size fails any
        // wrong term, which errs at O(1)).
        let n = 6;
        let terms_at = |theta: f64| {
            let (p, _) = family(n, theta);
            let (q, _) = family(n, 0.5 * theta - 0.2);
            PencilTerms { n, m: p.m, g: [p.g, q.g], k: [p.k, q.m, q.k] }
        };
        let (t0, tp, tm) = (terms_at(0.0), terms_at(1.0), terms_at(-1.0));
        let mut c = [t0, t0, t0];
        let get = |t: &PencilTerms, q: usize| -> [[f64; 6]; 6] { [t.m, t.g[0], t.g[1], t.k[0], t.k[1], t.k[2]][q] };
        for q in 0..6 {
            let (a0, ap, am) = (get(&t0, q), get(&tp, q), get(&tm, q));
            for i in 0..n {
                for j in 0..n {
                    let (d1, d2) = (0.5 * (ap[i][j] - am[i][j]), 0.5 * (ap[i][j] + am[i][j]) - a0[i][j]);
                    for (e, v) in [(1, d1), (2, d2)] {
                        let t = &mut c[e];
                        match q {
                            0 => t.m[i][j] = v,
                            1 | 2 => t.g[q - 1][i][j] = v,
                            _ => t.k[q - 3][i][j] = v,
                        }
                    }
                }
            }
        }
        let pp = PlanePolynomial::new(&c).unwrap();
        let direct = |omega: f64, u: f64| {
            let t = terms_at(u);
            let mut p = Pencil { n, m: t.m, g: t.g[0], k: t.k[0] };
            for i in 0..n {
                for j in 0..n {
                    p.g[i][j] += omega * t.g[1][i][j];
                    p.k[i][j] += omega * t.k[1][i][j] + omega * omega * t.k[2][i][j];
                }
            }
            pencil_polynomial(&p).unwrap()
        };
        // (u ≤ 0.5: `M(u)` well conditioned; near a singular `M` the coefficients and their
        // third derivatives grow and the central difference is no reference)
        for (omega, u) in [(0.3, 0.1), (1.7, -0.4), (0.05, 0.3), (2.5, 0.5)] {
            let (a, dw, du) = pp.at(omega, u).unwrap();
            let e = direct(omega, u);
            let size = e.iter().map(|x| x.abs()).fold(0.0, f64::max);
            let h = 1e-5;
            let (wp, wm, up, um) = (direct(omega + h, u), direct(omega - h, u), direct(omega, u + h), direct(omega, u - h));
            for k in 0..=2 * n {
                assert!((a[k] - e[k]).abs() < 1e-11 * size, "a_{k} at ({omega}, {u}): {} against {}", a[k], e[k]);
                let (fw, fu) = ((wp[k] - wm[k]) / (2.0 * h), (up[k] - um[k]) / (2.0 * h));
                assert!((dw[k] - fw).abs() < 1e-7 * size, "da_{k}/dΩ at ({omega}, {u}): {} against {fw}", dw[k]);
                assert!((du[k] - fu).abs() < 1e-7 * size, "da_{k}/du at ({omega}, {u}): {} against {fu}", du[k]);
            }
        }
        // the value alone and the line's polynomial in Ω are the same sums
        let (a, _, _) = pp.at(1.3, 0.2).unwrap();
        assert_eq!(pp.value(1.3, 0.2).unwrap(), a);
        let sp = pp.speed_polynomial(0.2).unwrap().at(1.3);
        for k in 0..=2 * n {
            assert!((sp[k] - a[2 * n - k]).abs() < 1e-12 * a.iter().map(|x| x.abs()).fold(0.0, f64::max), "c_{k}: {} against {}", sp[k], a[2 * n - k]);
        }
        assert!(PlanePolynomial::new(&[t0; 4]).is_none());
        // families of lower degree in u (one term, two): the minors' blocks are sized by the
        // degree; against the same expansion of the pencil summed from the terms directly,
        // the same 1e-11 (a block sized one power short would drop or misplace a term: O(1))
        for len in [1, 2] {
            let pl = PlanePolynomial::new(&c[..len]).unwrap();
            let direct = |omega: f64, u: f64| {
                let mut p = Pencil { n, m: [[0.0; 6]; 6], g: [[0.0; 6]; 6], k: [[0.0; 6]; 6] };
                for (l, t) in c[..len].iter().enumerate() {
                    let w = u.powi(l as i32);
                    for i in 0..n {
                        for j in 0..n {
                            p.m[i][j] += w * t.m[i][j];
                            p.g[i][j] += w * (t.g[0][i][j] + omega * t.g[1][i][j]);
                            p.k[i][j] += w * (t.k[0][i][j] + omega * t.k[1][i][j] + omega * omega * t.k[2][i][j]);
                        }
                    }
                }
                pencil_polynomial(&p).unwrap()
            };
            for (omega, u) in [(0.3, 0.1), (1.7, -0.4), (2.5, 0.5)] {
                let (a, e) = (pl.value(omega, u).unwrap(), direct(omega, u));
                let size = e.iter().map(|x| x.abs()).fold(0.0, f64::max);
                for k in 0..=2 * n {
                    assert!((a[k] - e[k]).abs() < 1e-11 * size, "{len} terms: a_{k} at ({omega}, {u}): {} against {}", a[k], e[k]);
                }
            }
        }
    }

    #[test]
    fn dual_expansion_is_the_expansion_and_its_derivative() {
        // The value part is the same sums in the same order as `pencil_polynomial` (equal to
        // the bit); the derivative equals the central difference of `pencil_polynomial` with
        // h = 1e-5: a_j(θ) is a ratio of polynomials in θ with O(1) derivatives here, so the
        // difference errs by h²/6 |a'''| ~ 1e-11 plus rounding ~ε |a|/h ~ 1e-11; 1e-8 (relative
        // to the coefficients' size) leaves a margin of 1000 and fails any wrong product-rule
        // term, which errs at O(1).
        for n in [4, 6] {
            let theta = 0.37;
            let (p, d) = family(n, theta);
            let (a, da) = pencil_polynomial_dual(&p, &[d]).unwrap();
            assert_eq!(a, pencil_polynomial(&p).unwrap());
            let h = 1e-5;
            let ap = pencil_polynomial(&family(n, theta + h).0).unwrap();
            let am = pencil_polynomial(&family(n, theta - h).0).unwrap();
            let size = a.iter().chain(da[0].iter()).map(|x| x.abs()).fold(0.0, f64::max);
            for j in 0..=2 * n {
                let fd = (ap[j] - am[j]) / (2.0 * h);
                assert!((da[0][j] - fd).abs() < 1e-8 * size, "n = {n}, a_{j}: dual {} central {fd}", da[0][j]);
            }
        }
    }

    #[test]
    fn dual_determinant_is_the_polynomial_at_lambda_and_its_derivatives() {
        // det P(λ) by elimination equals det M · p(λ) of the expansion (both exact but for
        // rounding: 1e-12 relative to the terms' size Σ|a_j||λ|^j det M); its derivatives along θ
        // (the entries' dP/dθ) and along λ (dP/dλ = 2Mλ + G) equal central differences with
        // h = 1e-5 (errors h²/6 ~ 2e-11 and ε/h ~ 2e-11 of the size; tolerance 1e-8).
        let n = 6;
        let theta = -0.21;
        let lam = Complex64::new(0.3, 1.7);
        let det_at = |theta: f64, lam: Complex64| -> (Complex64, [Complex64; 2]) {
            let (p, d) = family(n, theta);
            let z = Complex64::new(0.0, 0.0);
            let (mut a, mut da) = ([[z; 6]; 6], [[[z; 6]; 6]; 2]);
            for i in 0..n {
                for j in 0..n {
                    a[i][j] = lam * lam * p.m[i][j] + lam * p.g[i][j] + p.k[i][j];
                    da[0][i][j] = lam * lam * d.m[i][j] + lam * d.g[i][j] + d.k[i][j];
                    da[1][i][j] = lam * (2.0 * p.m[i][j]) + p.g[i][j];
                }
            }
            det_dual(&a, &da, n)
        };
        let (q, dq) = det_at(theta, lam);
        let (p, _) = family(n, theta);
        let a = pencil_polynomial(&p).unwrap();
        let z = Complex64::new(0.0, 0.0);
        let mut m = [[z; 6]; 6];
        for i in 0..n {
            for j in 0..n {
                m[i][j] = Complex64::new(p.m[i][j], 0.0);
            }
        }
        let (det_m, _) = det_dual::<1>(&m, &[[[z; 6]; 6]], n);
        let pl = (0..=2 * n).rev().fold(z, |acc, j| acc * lam + a[j]);
        let size = (0..=2 * n).map(|j| a[j].abs() * lam.norm().powi(j as i32)).sum::<f64>() * det_m.norm();
        assert!((q - det_m * pl).norm() < 1e-12 * size, "{q} against {}", det_m * pl);
        let h = 1e-5;
        let fd_theta = (det_at(theta + h, lam).0 - det_at(theta - h, lam).0) / (2.0 * h);
        let fd_lam = (det_at(theta, lam + h).0 - det_at(theta, lam - h).0) / (2.0 * h);
        assert!((dq[0] - fd_theta).norm() < 1e-8 * size, "d/dθ {} against {fd_theta}", dq[0]);
        assert!((dq[1] - fd_lam).norm() < 1e-8 * size, "d/dλ {} against {fd_lam}", dq[1]);
    }
}
