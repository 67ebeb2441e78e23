//! Dense linear solves for Newton's method on a state of any size: LU with partial pivoting,
//! and the minimum-norm solution of a system whose matrix has a known null space (a family of
//! stationary states) by the singular value decomposition (nalgebra's Golub–Kahan SVD).

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
/// `x = V Σ⁺ Uᵀ b`, by nalgebra's SVD (`svd`).
/// Where `A` is the Jacobian at a family of equilibria (rank `n − drop`), this Newton step
/// moves to the member of the family nearest the current point.
pub(crate) fn min_norm_solve(a: &[f64], n: usize, b: &[f64], drop: usize) -> Vec<f64> {
    let (u, v, sigma) = svd(a, n);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| sigma[i].total_cmp(&sigma[j]));
    let cut = 1e-12 * sigma.iter().fold(0.0f64, |m, v| m.max(*v));
    let mut x = vec![0.0; n];
    for &j in order.iter().skip(drop) {
        if sigma[j] <= cut {
            continue;
        }
        // coefficient (u_j · b)/σ_j
        let coef = u[j * n..(j + 1) * n].iter().zip(b).map(|(uu, bb)| uu * bb).sum::<f64>() / sigma[j];
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

/// The singular value decomposition `A = U Σ Vᵀ` of `A` (row-major `n × n`) by nalgebra's
/// Golub–Kahan bidiagonalisation and implicit-shift QR (`SVD::try_new_unordered`, its default
/// tolerance `5 ε`): `(U, V, σ)`, `U` and `V` column-major (column `j` at `[j n .. (j + 1) n]`),
/// `σ_j ≥ 0`, unordered. It replaced a one-sided Jacobi SVD that took ~17 sweeps on the
/// 62 × 62 Jacobians of a three-ball family (docs/notes/dependencies.md). Where `A` is not
/// finite, or the iteration does not converge within `6 n²` QR steps (LAPACK `dbdsqr`'s
/// bound), every entry is NaN, as the Jacobi rotations gave for a non-finite `A`, and the
/// callers refuse the step.
fn svd(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let nan = || vec![f64::NAN; n * n];
    if n == 0 {
        return (vec![], vec![], vec![]);
    }
    if !a.iter().all(|x| x.is_finite()) {
        return (nan(), nan(), vec![f64::NAN; n]);
    }
    let m = nalgebra::DMatrix::from_row_slice(n, n, a);
    let eps = 5.0 * f64::EPSILON;
    let Some(svd) = nalgebra::SVD::try_new_unordered(m, true, true, eps, 6 * n * n) else {
        return (nan(), nan(), vec![f64::NAN; n]);
    };
    let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
        return (nan(), nan(), vec![f64::NAN; n]);
    };
    // nalgebra's storage is column-major: U's column j is already contiguous; Vᵀ's row j is V's
    // column j
    let u = u.as_slice().to_vec();
    let v = v_t.transpose().as_slice().to_vec();
    (u, v, svd.singular_values.as_slice().to_vec())
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

    #[test]
    fn svd_reconstructs_and_null_space_spans_the_kernel() {
        // A = U Σ Vᵀ with U, V orthonormal, against the matrix itself (an invariant, not a second
        // SVD); 1e-13 is ~100 ε times the largest entry, ample for backward-stable QR at n = 7
        let n = 7;
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        // rank n − 2: the last two columns are combinations of the first two, so the kernel
        // is spanned by (c, d, 0, …, −1, 0) and (e, f, 0, …, 0, −1)
        let mut a: Vec<f64> = (0..n * n).map(|_| rnd()).collect();
        let (c, d, e, f) = (0.5, -1.5, 2.0, 0.25);
        for i in 0..n {
            a[i * n + n - 2] = c * a[i * n] + d * a[i * n + 1];
            a[i * n + n - 1] = e * a[i * n] + f * a[i * n + 1];
        }
        let (u, v, sigma) = svd(&a, n);
        for i in 0..n {
            for j in 0..n {
                let r: f64 = (0..n).map(|k| u[k * n + i] * sigma[k] * v[k * n + j]).sum();
                assert!((r - a[i * n + j]).abs() < 1e-13, "A[{i}][{j}] = {} vs {r}", a[i * n + j]);
                let uu: f64 = (0..n).map(|k| u[i * n + k] * u[j * n + k]).sum();
                let vv: f64 = (0..n).map(|k| v[i * n + k] * v[j * n + k]).sum();
                let delta = if i == j { 1.0 } else { 0.0 };
                assert!((uu - delta).abs() < 1e-13 && (vv - delta).abs() < 1e-13, "{uu} {vv}");
            }
        }
        // the two smallest right singular vectors: unit length, A t = 0 to round-off, and in the
        // span of the kernel vectors above (no component along the first two unit vectors'
        // complement other than the kernel's own)
        let basis = null_space(&a, n, 2);
        assert_eq!(basis.len(), 2);
        for t in &basis {
            let norm: f64 = t.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((norm - 1.0).abs() < 1e-14, "{norm}");
            let at: f64 = (0..n).map(|i| (0..n).map(|j| a[i * n + j] * t[j]).sum::<f64>().abs()).fold(0.0, f64::max);
            assert!(at < 1e-13, "{at}");
            // t = α (c, d, 0…, −1, 0) + β (e, f, 0…, 0, −1): α = −t[n−2], β = −t[n−1]
            let (al, be) = (-t[n - 2], -t[n - 1]);
            assert!((t[0] - (al * c + be * e)).abs() < 1e-13 && (t[1] - (al * d + be * f)).abs() < 1e-13, "{t:?}");
            assert!(t[2..n - 2].iter().all(|x| x.abs() < 1e-13), "{t:?}");
        }
        // a non-finite matrix: NaN throughout (the Newton step refuses it), no panic
        let mut bad = a.clone();
        bad[3] = f64::NAN;
        assert!(min_norm_solve(&bad, n, &[1.0; 7], 0).iter().all(|x| x.is_nan()));
    }
}
