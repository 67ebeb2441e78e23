//! Dense linear solves for Newton's method on a state of any size: LU with partial pivoting,
//! and the minimum-norm solution of a system whose matrix has a known null space (a family of
//! stationary states) by the singular value decomposition (one-sided Jacobi).

// Index loops follow the algorithms' formulas.
#![allow(clippy::needless_range_loop)]

/// Solve `A x = b` in place (`a` row-major `n × n`, destroyed) by Gaussian elimination with
/// partial pivoting; `false` when a pivot is exactly zero or not finite.
pub(crate) fn lu_solve(a: &mut [f64], n: usize, b: &mut [f64]) -> bool {
    for col in 0..n {
        let p = (col..n).max_by(|&i, &j| a[i * n + col].abs().total_cmp(&a[j * n + col].abs())).unwrap_or(col);
        let piv = a[p * n + col];
        if piv == 0.0 || !piv.is_finite() {
            return false;
        }
        if p != col {
            for k in 0..n {
                a.swap(p * n + k, col * n + k);
            }
            b.swap(p, col);
        }
        for r in col + 1..n {
            let f = a[r * n + col] / piv;
            if f != 0.0 {
                for k in col..n {
                    a[r * n + k] -= f * a[col * n + k];
                }
                b[r] -= f * b[col];
            }
        }
    }
    for col in (0..n).rev() {
        let mut v = b[col];
        for j in col + 1..n {
            v -= a[col * n + j] * b[j];
        }
        b[col] = v / a[col * n + col];
    }
    b.iter().all(|x| x.is_finite())
}

/// The minimum-norm least-squares solution of `A x = b` with the `drop` smallest singular
/// values of `A` (row-major `n × n`), and any below `1e-12 σ_max`, treated as zero:
/// `x = V Σ⁺ Uᵀ b`. The SVD by one-sided
/// Jacobi rotations on the columns of `A V` (Hestenes), to relative orthogonality `n ε` (a
/// tighter test is not met in floating point and only spends sweeps).
/// Where `A` is the Jacobian at a family of equilibria (rank `n − drop`), this Newton step
/// moves to the member of the family nearest the current point.
pub(crate) fn min_norm_solve(a: &[f64], n: usize, b: &[f64], drop: usize) -> Vec<f64> {
    let (w, v, sigma) = svd(a, n);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| sigma[i].total_cmp(&sigma[j]));
    let cut = 1e-12 * sigma.iter().fold(0.0f64, |m, v| m.max(*v));
    let mut x = vec![0.0; n];
    for &j in order.iter().skip(drop) {
        if sigma[j] <= cut {
            continue;
        }
        // u_j = w_j / σ_j; coefficient (u_j · b)/σ_j
        let coef = w[j * n..(j + 1) * n].iter().zip(b).map(|(u, bb)| u * bb).sum::<f64>() / (sigma[j] * sigma[j]);
        for i in 0..n {
            x[i] += coef * v[j * n + i];
        }
    }
    x
}

/// The right singular vectors of the `k` smallest singular values of `A` (row-major `n × n`),
/// each of unit length, smallest first: where `A` is the (scaled) Jacobian at a member of a
/// family of stationary states of dimension `k`, an orthonormal basis of the family's tangent
/// space there.
pub(crate) fn null_space(a: &[f64], n: usize, k: usize) -> Vec<Vec<f64>> {
    let (_, v, sigma) = svd(a, n);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| sigma[i].total_cmp(&sigma[j]));
    order.iter().take(k.min(n)).map(|&j| v[j * n..(j + 1) * n].to_vec()).collect()
}

/// The singular value decomposition of `A` (row-major `n × n`) by one-sided Jacobi rotations
/// on the columns of `A V` (Hestenes), to relative orthogonality `n ε` (a tighter test is not
/// met in floating point and only spends sweeps): `(W, V, σ)`, `W = A V` and `V` column-major
/// (column `j` at `[j n .. (j + 1) n]`), `σ_j = |w_j|`, unordered.
fn svd(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    // columns of W = A V, stored column-major for the rotations
    let mut w: Vec<f64> = (0..n * n).map(|k| a[(k % n) * n + k / n]).collect();
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    let orthogonal = n.max(1) as f64 * f64::EPSILON;
    for _sweep in 0..60 {
        let mut rotated = false;
        for p in 0..n {
            for q in p + 1..n {
                let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
                for i in 0..n {
                    let (x, y) = (w[p * n + i], w[q * n + i]);
                    alpha += x * x;
                    beta += y * y;
                    gamma += x * y;
                }
                if gamma == 0.0 || gamma.abs() <= orthogonal * (alpha * beta).sqrt() {
                    continue;
                }
                rotated = true;
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let t = if zeta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                for i in 0..n {
                    let (x, y) = (w[p * n + i], w[q * n + i]);
                    w[p * n + i] = c * x - s * y;
                    w[q * n + i] = s * x + c * y;
                    let (x, y) = (v[p * n + i], v[q * n + i]);
                    v[p * n + i] = c * x - s * y;
                    v[q * n + i] = s * x + c * y;
                }
            }
        }
        if !rotated {
            break;
        }
    }
    let sigma: Vec<f64> = (0..n).map(|j| w[j * n..(j + 1) * n].iter().map(|x| x * x).sum::<f64>().sqrt()).collect();
    (w, v, sigma)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_and_min_norm_finds_the_nearest_solution() {
        // A x = b against a hand solution
        let mut a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let mut b = vec![0.0; 3];
        let x0 = [1.0, 2.0, 3.0];
        for i in 0..3 {
            b[i] = (0..3).map(|j| a[i * 3 + j] * x0[j]).sum();
        }
        assert!(lu_solve(&mut a, 3, &mut b));
        for i in 0..3 {
            assert!((b[i] - x0[i]).abs() < 1e-15, "{b:?}");
        }
        assert!(!lu_solve(&mut [1.0, 2.0, 2.0, 4.0], 2, &mut [1.0, 1.0]));
        // rank 2 in R³: A = diag(2, 3, 0) rotated; the minimum-norm solution has no component
        // along the null vector, and the full-rank case equals the inverse
        let (c, s) = (0.6f64, 0.8f64);
        let q = [c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0]; // rotation about z, then columns mixed
        let d = [2.0, 3.0, 0.0];
        // A = Q diag(d) Qᵀ: null vector Q e3 = e3
        let mut m = vec![0.0; 9];
        for i in 0..3 {
            for j in 0..3 {
                m[i * 3 + j] = (0..3).map(|k| q[i * 3 + k] * d[k] * q[j * 3 + k]).sum();
            }
        }
        let b = [1.0, -1.0, 0.0];
        let x = min_norm_solve(&m, 3, &b, 1);
        assert!(x[2].abs() < 1e-15, "{x:?}");
        let r: Vec<f64> = (0..3).map(|i| (0..3).map(|j| m[i * 3 + j] * x[j]).sum::<f64>() - b[i]).collect();
        assert!(r.iter().all(|v| v.abs() < 1e-14), "{r:?}");
        let full = [4.0, 1.0, 0.5, 1.0, 3.0, -1.0, 0.5, -1.0, 2.0];
        let x = min_norm_solve(&full, 3, &b, 0);
        let mut a2 = full.to_vec();
        let mut b2 = b.to_vec();
        assert!(lu_solve(&mut a2, 3, &mut b2));
        for i in 0..3 {
            assert!((x[i] - b2[i]).abs() < 1e-14, "{x:?} {b2:?}");
        }
    }
}
