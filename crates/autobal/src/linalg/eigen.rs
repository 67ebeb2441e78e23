//! Eigenvalues of small dense real matrices (at most 12×12, on the stack), eigenvalues only:
//! balancing (LAPACK `dgebal`-style, powers of two), reduction to Hessenberg form by stabilised
//! elimination (EISPACK `elmhes`), and the Francis double-shift QR iteration (EISPACK `hqr`).
//! Also the characteristic polynomial of a Hessenberg matrix and the Routh–Hurwitz test, for a
//! stability verdict at a fraction of the cost of the eigenvalues.
//!
//! Why our own: the general-purpose solvers (faer, nalgebra) accumulate Schur vectors and
//! allocate; a stability map needs neither. The tests check every routine against nalgebra's
//! Schur decomposition and against the pencil's determinant.

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use super::small::{Mat12, MAX_STATES};
use num_complex::Complex64;

const N1: usize = MAX_STATES + 1;
/// A square matrix indexed from 1, as in the EISPACK algorithms this module follows (row and
/// column 0 unused).
pub type A1 = [[f64; N1]; N1];

/// The eigen-solver did not converge (more than 60 QR iterations on one eigenvalue).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NoConvergence;

/// The leading `n × n` block of `a` copied into a one-based [`A1`].
pub fn to_one_based(a: &Mat12, n: usize) -> A1 {
    let mut b = [[0.0; N1]; N1];
    for i in 0..n {
        for j in 0..n {
            b[i + 1][j + 1] = a[i][j];
        }
    }
    b
}

/// Diagonal similarity `D⁻¹ A D` with powers of two making row and column norms comparable
/// (Parlett–Reinsch; LAPACK `dgebal` without permutations). Exact in floating point.
pub fn balance(a: &mut A1, n: usize) {
    const RADIX: f64 = 2.0;
    let sqrdx = RADIX * RADIX;
    let mut done = false;
    let mut sweeps = 0;
    while !done && sweeps < 100 {
        done = true;
        sweeps += 1;
        for i in 1..=n {
            let (mut r, mut c) = (0.0, 0.0);
            for j in 1..=n {
                if j != i {
                    c += a[j][i].abs();
                    r += a[i][j].abs();
                }
            }
            if c != 0.0 && r != 0.0 {
                let mut g = r / RADIX;
                let mut f = 1.0;
                let s = c + r;
                while c < g {
                    f *= RADIX;
                    c *= sqrdx;
                }
                g = r * RADIX;
                while c > g {
                    f /= RADIX;
                    c /= sqrdx;
                }
                if (c + r) / f < 0.95 * s {
                    done = false;
                    let g = 1.0 / f;
                    for j in 1..=n {
                        a[i][j] *= g;
                    }
                    for j in 1..=n {
                        a[j][i] *= f;
                    }
                }
            }
        }
    }
}

/// Reduce to upper Hessenberg form by Gaussian elimination with pivoting (EISPACK `elmhes`);
/// entries below the subdiagonal are zeroed.
pub fn hessenberg(a: &mut A1, n: usize) {
    for m in 2..n {
        let mut x: f64 = 0.0;
        let mut i = m;
        for j in m..=n {
            if a[j][m - 1].abs() > x.abs() {
                x = a[j][m - 1];
                i = j;
            }
        }
        if i != m {
            for j in (m - 1)..=n {
                let t = a[i][j];
                a[i][j] = a[m][j];
                a[m][j] = t;
            }
            for row in a.iter_mut().take(n + 1).skip(1) {
                row.swap(i, m);
            }
        }
        if x != 0.0 {
            for i in (m + 1)..=n {
                let mut y = a[i][m - 1];
                if y != 0.0 {
                    y /= x;
                    a[i][m - 1] = y;
                    for j in m..=n {
                        a[i][j] -= y * a[m][j];
                    }
                    for j in 1..=n {
                        a[j][m] += y * a[j][i];
                    }
                }
            }
        }
    }
    for i in 3..=n {
        for j in 1..i - 1 {
            a[i][j] = 0.0;
        }
    }
}

fn sign(a: f64, b: f64) -> f64 {
    if b >= 0.0 {
        a.abs()
    } else {
        -a.abs()
    }
}

/// Eigenvalues of an upper Hessenberg matrix by the Francis double-shift QR iteration
/// (EISPACK `hqr`, eigenvalues only; the matrix is destroyed).
#[allow(unused_assignments)] // the working scalars carry values between the stages, as in EISPACK
fn hqr(a: &mut A1, n: usize, wr: &mut [f64], wi: &mut [f64]) -> Result<(), NoConvergence> {
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in (i.max(2) - 1)..=n {
            anorm += a[i][j].abs();
        }
    }
    let mut nn = n as isize;
    let mut t = 0.0;
    let (mut p, mut q, mut r, mut s, mut w, mut x, mut y, mut z) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    while nn >= 1 {
        let mut its = 0;
        loop {
            let nu = nn as usize;
            let mut l = nu;
            while l >= 2 {
                s = a[l - 1][l - 1].abs() + a[l][l].abs();
                if s == 0.0 {
                    s = anorm;
                }
                if a[l][l - 1].abs() <= f64::EPSILON * s {
                    a[l][l - 1] = 0.0;
                    break;
                }
                l -= 1;
            }
            x = a[nu][nu];
            if l == nu {
                wr[nu - 1] = x + t;
                wi[nu - 1] = 0.0;
                nn -= 1;
            } else {
                y = a[nu - 1][nu - 1];
                w = a[nu][nu - 1] * a[nu - 1][nu];
                if l == nu - 1 {
                    p = 0.5 * (y - x);
                    q = p * p + w;
                    z = q.abs().sqrt();
                    x += t;
                    if q >= 0.0 {
                        z = p + sign(z, p);
                        wr[nu - 2] = x + z;
                        wr[nu - 1] = x + z;
                        if z != 0.0 {
                            wr[nu - 1] = x - w / z;
                        }
                        wi[nu - 2] = 0.0;
                        wi[nu - 1] = 0.0;
                    } else {
                        wr[nu - 2] = x + p;
                        wr[nu - 1] = x + p;
                        wi[nu - 2] = -z;
                        wi[nu - 1] = z;
                    }
                    nn -= 2;
                } else {
                    if its == 60 {
                        return Err(NoConvergence);
                    }
                    if its % 10 == 0 && its > 0 {
                        // exceptional shift
                        t += x;
                        for i in 1..=nu {
                            a[i][i] -= x;
                        }
                        s = a[nu][nu - 1].abs() + a[nu - 1][nu - 2].abs();
                        x = 0.75 * s;
                        y = x;
                        w = -0.4375 * s * s;
                    }
                    its += 1;
                    let mut m = nu - 2;
                    loop {
                        z = a[m][m];
                        r = x - z;
                        s = y - z;
                        p = (r * s - w) / a[m + 1][m] + a[m][m + 1];
                        q = a[m + 1][m + 1] - z - r - s;
                        r = a[m + 2][m + 1];
                        s = p.abs() + q.abs() + r.abs();
                        p /= s;
                        q /= s;
                        r /= s;
                        if m == l {
                            break;
                        }
                        let u = a[m][m - 1].abs() * (q.abs() + r.abs());
                        let v = p.abs() * (a[m - 1][m - 1].abs() + z.abs() + a[m + 1][m + 1].abs());
                        if u <= f64::EPSILON * v {
                            break;
                        }
                        m -= 1;
                    }
                    for i in (m + 2)..=nu {
                        a[i][i - 2] = 0.0;
                        if i != m + 2 {
                            a[i][i - 3] = 0.0;
                        }
                    }
                    let mut k = m;
                    while k < nu {
                        if k != m {
                            p = a[k][k - 1];
                            q = a[k + 1][k - 1];
                            r = 0.0;
                            if k != nu - 1 {
                                r = a[k + 2][k - 1];
                            }
                            x = p.abs() + q.abs() + r.abs();
                            if x != 0.0 {
                                p /= x;
                                q /= x;
                                r /= x;
                            }
                        }
                        s = sign((p * p + q * q + r * r).sqrt(), p);
                        if s != 0.0 {
                            if k == m {
                                if l != m {
                                    a[k][k - 1] = -a[k][k - 1];
                                }
                            } else {
                                a[k][k - 1] = -s * x;
                            }
                            p += s;
                            x = p / s;
                            y = q / s;
                            z = r / s;
                            q /= p;
                            r /= p;
                            // rows k, k+1 (, k+2), columns k..=nu; then columns k, k+1
                            // (, k+2), rows l..=mmin: the same operations in the same order
                            // as the indexed form, over slices (no bounds check per entry)
                            let (rk, rest) = a[k..].split_at_mut(1);
                            let (rk1, rest) = rest.split_at_mut(1);
                            let (rk, rk1) = (&mut rk[0][k..=nu], &mut rk1[0][k..=nu]);
                            if k != nu - 1 {
                                let rk2 = &mut rest[0][k..=nu];
                                for ((u0, u1), u2) in rk.iter_mut().zip(rk1.iter_mut()).zip(rk2.iter_mut()) {
                                    p = *u0 + q * *u1;
                                    p += r * *u2;
                                    *u2 -= p * z;
                                    *u1 -= p * y;
                                    *u0 -= p * x;
                                }
                            } else {
                                for (u0, u1) in rk.iter_mut().zip(rk1.iter_mut()) {
                                    p = *u0 + q * *u1;
                                    *u1 -= p * y;
                                    *u0 -= p * x;
                                }
                            }
                            let mmin = if nu < k + 3 { nu } else { k + 3 };
                            if k != nu - 1 {
                                for row in a[l..=mmin].iter_mut() {
                                    let c = &mut row[k..k + 3];
                                    p = x * c[0] + y * c[1];
                                    p += z * c[2];
                                    c[2] -= p * r;
                                    c[1] -= p * q;
                                    c[0] -= p;
                                }
                            } else {
                                for row in a[l..=mmin].iter_mut() {
                                    let c = &mut row[k..k + 2];
                                    p = x * c[0] + y * c[1];
                                    c[1] -= p * q;
                                    c[0] -= p;
                                }
                            }
                        }
                        k += 1;
                    }
                }
            }
            if nn < 1 || l + 1 >= nn as usize {
                break;
            }
        }
    }
    Ok(())
}

/// Real and imaginary parts of the eigenvalues of the leading `n×n` block of `a`: balancing,
/// Hessenberg reduction, Francis QR.
fn eigen_parts(a: &Mat12, n: usize) -> Result<([f64; MAX_STATES], [f64; MAX_STATES]), NoConvergence> {
    let mut b = to_one_based(a, n);
    balance(&mut b, n);
    hessenberg(&mut b, n);
    let mut wr = [0.0; MAX_STATES];
    let mut wi = [0.0; MAX_STATES];
    hqr(&mut b, n, &mut wr, &mut wi)?;
    Ok((wr, wi))
}

/// All eigenvalues of the leading `n×n` block of `a` (balanced, Hessenberg, Francis QR).
pub fn eigenvalues(a: &Mat12, n: usize) -> Result<Vec<Complex64>, NoConvergence> {
    let (wr, wi) = eigen_parts(a, n)?;
    Ok((0..n).map(|i| Complex64::new(wr[i], wi[i])).collect())
}

/// All eigenvalues of the leading `n×n` block of `h`, an upper Hessenberg matrix (e.g. Arnoldi's
/// projection, whose orthonormal basis leaves it well scaled): the Francis QR iteration alone,
/// without balancing or reduction.
pub fn hessenberg_eigenvalues(h: &Mat12, n: usize) -> Result<Vec<Complex64>, NoConvergence> {
    let mut b = to_one_based(h, n);
    let mut wr = [0.0; MAX_STATES];
    let mut wi = [0.0; MAX_STATES];
    hqr(&mut b, n, &mut wr, &mut wi)?;
    Ok((0..n).map(|i| Complex64::new(wr[i], wi[i])).collect())
}

/// Spectral abscissa `max Re λ` of the leading `n×n` block of `a`.
pub fn spectral_abscissa(a: &Mat12, n: usize) -> Result<f64, NoConvergence> {
    let (wr, _) = eigen_parts(a, n)?;
    Ok(wr[..n].iter().copied().fold(f64::NEG_INFINITY, f64::max))
}

/// Coefficients `c[0..=n]` of `det(λ I − A) = Σ c_k λ^{n−k}` (`c[0] = 1`) from the Hessenberg
/// form of `a` (no balancing: the coefficients are invariant under it, and the dimensionless
/// state matrices are well scaled; tests compare the verdict with the eigenvalues), by the recurrence on the leading principal submatrices
/// `p_k = (λ − h_kk) p_{k−1} − Σ_{i<k} h_ik (Π_{j=i+1..k} h_{j,j−1}) p_{i−1}`.
pub fn characteristic_polynomial(a: &Mat12, n: usize) -> [f64; MAX_STATES + 1] {
    let mut h = *a;
    hessenberg0(&mut h, n);
    // p[k] holds the coefficients of p_k (leading k×k block) in ascending powers of λ
    let mut p = [[0.0; N1]; N1];
    p[0][0] = 1.0;
    for k in 1..=n {
        let hkk = h[k - 1][k - 1];
        let (done, rest) = p.split_at_mut(k);
        let pk = &mut rest[0];
        let prev = &done[k - 1];
        pk[0] = -hkk * prev[0];
        for d in 1..k {
            pk[d] = prev[d - 1] - hkk * prev[d];
        }
        pk[k] = prev[k - 1];
        let mut beta = 1.0;
        for i in (1..k).rev() {
            beta *= h[i][i - 1];
            let f = h[i - 1][k - 1] * beta;
            if f != 0.0 {
                for (x, y) in pk[..i].iter_mut().zip(&done[i - 1][..i]) {
                    *x -= f * y;
                }
            }
        }
    }
    let mut c = [0.0; MAX_STATES + 1];
    for k in 0..=n {
        c[k] = p[n][n - k];
    }
    c
}

/// [`hessenberg`] on a 0-based matrix, with the row updates as slice operations.
fn hessenberg0(a: &mut Mat12, n: usize) {
    for m in 1..n.saturating_sub(1) {
        // pivot: largest |a[j][m−1]|, j ≥ m
        let mut piv = m;
        for j in m + 1..n {
            if a[j][m - 1].abs() > a[piv][m - 1].abs() {
                piv = j;
            }
        }
        if piv != m {
            a.swap(piv, m);
            for row in a[..n].iter_mut() {
                row.swap(piv, m);
            }
        }
        let x = a[m][m - 1];
        if x == 0.0 {
            continue;
        }
        let (top, bottom) = a.split_at_mut(m + 1);
        let pivot_row = &top[m];
        let mut mult = [0.0; MAX_STATES];
        for (r, row) in bottom[..n - m - 1].iter_mut().enumerate() {
            let y = row[m - 1] / x;
            mult[r] = y;
            row[m - 1] = 0.0;
            if y != 0.0 {
                for (u, v) in row[m..n].iter_mut().zip(&pivot_row[m..n]) {
                    *u -= y * v;
                }
            }
        }
        // column update a[:, m] += Σ_i y_i a[:, i]
        for row in a[..n].iter_mut() {
            let mut acc = 0.0;
            for (y, v) in mult[..n - m - 1].iter().zip(&row[m + 1..n]) {
                acc += y * v;
            }
            row[m] += acc;
        }
    }
}

/// Routh–Hurwitz: whether every root of `Σ c_k λ^{n−k}` (`c[0] > 0`) has negative real part,
/// from the signs of the first column of the Routh array. A zero in the first column (a root
/// on the imaginary axis, or a singular case) counts as not stable.
pub fn routh_hurwitz_stable(c: &[f64]) -> bool {
    let n = c.len() - 1;
    if c[0] <= 0.0 || c.iter().any(|x| !x.is_finite()) {
        return false;
    }
    // necessary condition: all coefficients positive
    if c.iter().any(|&x| x <= 0.0) {
        return false;
    }
    if let Ok(c) = <&[f64; 13]>::try_from(c) {
        return routh_hurwitz_12(c);
    }
    let mut r0: [f64; MAX_STATES / 2 + 2] = [0.0; MAX_STATES / 2 + 2];
    let mut r1 = r0;
    for (i, x) in c.iter().enumerate() {
        if i % 2 == 0 {
            r0[i / 2] = *x;
        } else {
            r1[i / 2] = *x;
        }
    }
    for _ in 1..n {
        if r1[0] <= 0.0 {
            return false;
        }
        let mut next = [0.0; MAX_STATES / 2 + 2];
        for j in 0..MAX_STATES / 2 + 1 {
            next[j] = r0[j + 1] - r0[0] * r1[j + 1] / r1[0];
        }
        r0 = r1;
        r1 = next;
    }
    r1[0] > 0.0
}

/// [`routh_hurwitz_stable`]'s array for 12 states (coefficients checked positive and finite):
/// the two rows in fixed arrays of 8, each new row written over the older one, each step
/// computing the entries its row holds (one fewer than the row two above it; a fixed number
/// per step, so that the loops have fixed bounds) and zeroing the one after, which the full
/// row would have computed as `0 − t0·0/b0 = 0`: the same operations on the same values.
fn routh_hurwitz_12(c: &[f64; 13]) -> bool {
    /// `t[j] = t[j+1] − t[0] b[j+1] / b[0]` for the `L` entries of the new row over the older
    /// row `t`; false when `b[0] ≤ 0`.
    #[inline(always)]
    fn step<const L: usize>(t: &mut [f64; 8], b: &[f64; 8]) -> bool {
        if b[0] <= 0.0 {
            return false;
        }
        let t0 = t[0];
        for j in 0..L {
            t[j] = t[j + 1] - t0 * b[j + 1] / b[0];
        }
        t[L] = 0.0;
        true
    }
    let mut e = [c[0], c[2], c[4], c[6], c[8], c[10], c[12], 0.0];
    let mut o = [c[1], c[3], c[5], c[7], c[9], c[11], 0.0, 0.0];
    // rows 2 … 12 (11 steps), the newest row last in `e`
    step::<6>(&mut e, &o)
        && step::<5>(&mut o, &e)
        && step::<5>(&mut e, &o)
        && step::<4>(&mut o, &e)
        && step::<4>(&mut e, &o)
        && step::<3>(&mut o, &e)
        && step::<3>(&mut e, &o)
        && step::<2>(&mut o, &e)
        && step::<2>(&mut e, &o)
        && step::<1>(&mut o, &e)
        && step::<1>(&mut e, &o)
        && e[0] > 0.0
}

/// Gaussian elimination with partial pivoting of a complex matrix, applied alike to `x`:
/// returns the upper triangle and the sign of the row permutation. With `regularise`, a zero
/// pivot is replaced by `ε‖a‖` (so that inverse iteration works on singular matrices).
fn complex_eliminate(a: &[Vec<Complex64>], x: &mut [Complex64], regularise: bool) -> (Vec<Vec<Complex64>>, f64) {
    let n = a.len();
    let mut m: Vec<Vec<Complex64>> = a.to_vec();
    let mut sign = 1.0;
    let scale = m.iter().flatten().map(|z| z.norm()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    for col in 0..n {
        let p = (col..n).max_by(|&i, &j| m[i][col].norm().total_cmp(&m[j][col].norm())).unwrap();
        if p != col {
            m.swap(col, p);
            x.swap(col, p);
            sign = -sign;
        }
        if regularise && m[col][col].norm() < f64::EPSILON * scale {
            m[col][col] = Complex64::new(f64::EPSILON * scale, 0.0);
        } else if m[col][col].norm() == 0.0 {
            return (m, 0.0);
        }
        for r in col + 1..n {
            let f = m[r][col] / m[col][col];
            for k in col..n {
                let t = m[col][k];
                m[r][k] -= f * t;
            }
            let t = x[col];
            x[r] -= f * t;
        }
    }
    (m, sign)
}

/// Solve the complex `n×n` system `a x = b` (partial pivoting; a zero pivot is replaced by
/// `ε‖a‖`, so it serves inverse iteration on singular matrices).
pub fn complex_solve(a: &[Vec<Complex64>], b: &[Complex64]) -> Vec<Complex64> {
    let n = b.len();
    let mut x = b.to_vec();
    let (m, _) = complex_eliminate(a, &mut x, true);
    for col in (0..n).rev() {
        let mut v = x[col];
        for j in col + 1..n {
            v -= m[col][j] * x[j];
        }
        x[col] = v / m[col][col];
    }
    x
}

/// Determinant of a complex `n×n` matrix (partial pivoting).
pub fn complex_det(a: &[Vec<Complex64>]) -> Complex64 {
    let mut dummy = vec![Complex64::new(0.0, 0.0); a.len()];
    let (m, sign) = complex_eliminate(a, &mut dummy, false);
    if sign == 0.0 {
        return Complex64::new(0.0, 0.0);
    }
    (0..a.len()).fold(Complex64::new(sign, 0.0), |d, i| d * m[i][i])
}
