//! Small dense LU factorisations on stack arrays (partial pivoting, LAPACK `getrf`/`getrs`
//! order), shared by the linear model (`M⁻¹[K G]`), the spatial simulation (its mass matrix at each
//! step) and the structured Jacobians of the integrators (the small border block of an arrow matrix).

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

/// Row of the largest `|a[i][col]|`, `i ≥ col` (partial pivoting).
fn pivot_row<const N: usize>(a: &[[f64; N]; N], col: usize, n: usize) -> usize {
    let mut p = col;
    for i in col + 1..n {
        if a[i][col].abs() > a[p][col].abs() {
            p = i;
        }
    }
    p
}

/// LU factors of the leading `n×n` block of an `N×N` array.
pub(crate) struct Lu<const N: usize> {
    a: [[f64; N]; N],
    piv: [usize; N],
    n: usize,
}

impl<const N: usize> Lu<N> {
    /// Factor; `None` when a pivot is exactly zero (singular matrix).
    pub(crate) fn new(mut a: [[f64; N]; N], n: usize) -> Option<Self> {
        let mut piv = [0usize; N];
        for k in 0..n {
            let p = pivot_row(&a, k, n);
            if a[p][k] == 0.0 {
                return None;
            }
            a.swap(k, p);
            piv[k] = p;
            for i in k + 1..n {
                let f = a[i][k] / a[k][k];
                a[i][k] = f;
                if f != 0.0 {
                    for j in k + 1..n {
                        a[i][j] -= f * a[k][j];
                    }
                }
            }
        }
        Some(Lu { a, piv, n })
    }

    /// `det A = (−1)^s Π u_kk`: the product of the pivots, `s` the number of row interchanges.
    pub(crate) fn det(&self) -> f64 {
        let mut d = 1.0;
        for k in 0..self.n {
            d *= self.a[k][k];
            if self.piv[k] != k {
                d = -d;
            }
        }
        d
    }

    /// Solve `A x = b` in place (the first `n` entries of `b`): the tests' reference for
    /// [`Lu::solve_columns`], which the library uses.
    #[cfg(test)]
    pub(crate) fn solve(&self, b: &mut [f64; N]) {
        let n = self.n;
        // the factorisation swapped whole rows (multipliers included): apply every interchange
        // first, then the unit lower triangle, then the upper one
        for k in 0..n {
            b.swap(k, self.piv[k]);
        }
        for k in 0..n {
            for i in k + 1..n {
                b[i] -= self.a[i][k] * b[k];
            }
        }
        for k in (0..n).rev() {
            for j in k + 1..n {
                b[k] -= self.a[k][j] * b[j];
            }
            b[k] /= self.a[k][k];
        }
    }
}

impl<const N: usize> Lu<N> {
    /// Solve `A X = B` in place for the first `m` columns of `b` (`b[i][c]`, rows `0..n`):
    /// `Lu::solve` (the tests' reference) on every column, the same operations on each
    /// element in the same order (each column's result is `solve`'s bit for bit), done row by
    /// row so that the columns' updates run together instead of one column's whole solve after
    /// another (the linear model's `M⁻¹[K G]`: 12 columns). The columns from `m` on are only
    /// permuted with the rows (the interchanges swap whole rows), the rows from `n` on untouched.
    pub(crate) fn solve_columns<const M: usize>(&self, b: &mut [[f64; M]; N], m: usize) {
        let n = self.n;
        for k in 0..n {
            b.swap(k, self.piv[k]);
        }
        for k in 0..n {
            let bk = b[k];
            for i in k + 1..n {
                let f = self.a[i][k];
                for c in 0..m {
                    b[i][c] -= f * bk[c];
                }
            }
        }
        for k in (0..n).rev() {
            for j in k + 1..n {
                let (f, bj) = (self.a[k][j], b[j]);
                for c in 0..m {
                    b[k][c] -= f * bj[c];
                }
            }
            let d = self.a[k][k];
            for c in 0..m {
                b[k][c] /= d;
            }
        }
    }
}

/// Solve `A x = b` once, eliminating on `a` and `b` together (no factors kept): the
/// simulation's mass-matrix solve at every right-hand side, where keeping factors costs ~30 %.
/// Returns `false` (and leaves `b` undefined) when a pivot is exactly zero.
pub(crate) fn solve_once<const N: usize>(a: &mut [[f64; N]; N], b: &mut [f64; N], n: usize) -> bool {
    for col in 0..n {
        let p = pivot_row(a, col, n);
        if a[p][col] == 0.0 {
            return false;
        }
        a.swap(col, p);
        b.swap(col, p);
        for r in col + 1..n {
            let g = a[r][col] / a[col][col];
            if g != 0.0 {
                for c in col..n {
                    a[r][c] -= g * a[col][c];
                }
                b[r] -= g * b[col];
            }
        }
    }
    for r in (0..n).rev() {
        let mut v = b[r];
        for c in r + 1..n {
            v -= a[r][c] * b[c];
        }
        b[r] = v / a[r][r];
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_systems_that_need_pivoting() {
        // a regression: applying the interchanges interleaved with the elimination, while the
        // factorisation swaps whole rows, solves 1-D problems and fails on most systems
        let m = [[0.0, 2.0, 1.0, 3.0], [1.0, 1.0, 0.0, -1.0], [4.0, -1.0, 2.0, 0.5], [2.0, 0.0, -3.0, 1.0]];
        let x = [1.0, -2.0, 0.5, 3.0];
        let mut b = [0.0; 4];
        for i in 0..4 {
            b[i] = (0..4).map(|j| m[i][j] * x[j]).sum();
        }
        let mut b2 = b;
        Lu::new(m, 4).unwrap().solve(&mut b);
        let mut m2 = m;
        assert!(solve_once(&mut m2, &mut b2, 4));
        for i in 0..4 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
            assert!((b2[i] - x[i]).abs() < 1e-14, "{b2:?}");
        }
        assert!(Lu::new([[1.0, 2.0], [2.0, 4.0]], 2).is_none());
    }

    /// The columns solved together are `solve`'s on each column bit for bit (the same
    /// operations in the same order), on a system that needs pivoting, with fewer columns
    /// than the array holds (the rest only permuted with the rows) and fewer rows (the rest
    /// untouched); and they solve the system.
    #[test]
    fn columns_solved_together_are_each_columns_solve_bit_for_bit() {
        let m = [[0.0, 2.0, 1.0, 3.0, 0.0], [1.0, 1.0, 0.0, -1.0, 0.0], [4.0, -1.0, 2.0, 0.5, 0.0], [2.0, 0.0, -3.0, 1.0, 0.0], [0.0; 5]];
        let lu = Lu::new(m, 4).unwrap();
        let mut b = [[0.0; 6]; 5];
        for i in 0..5 {
            for c in 0..6 {
                b[i][c] = ((7 * i + 3 * c) % 11) as f64 / 3.0 - 1.7 + 0.1 * c as f64;
            }
        }
        let orig = b;
        lu.solve_columns(&mut b, 5);
        for c in 0..5 {
            let mut col = [0.0; 5];
            for i in 0..4 {
                col[i] = orig[i][c];
            }
            lu.solve(&mut col);
            for i in 0..4 {
                assert_eq!(b[i][c].to_bits(), col[i].to_bits(), "row {i}, column {c}");
                // the residual of row i: integer-sized entries, 1e-13 of them
                let r: f64 = (0..4).map(|j| m[i][j] * b[j][c]).sum::<f64>() - orig[i][c];
                assert!(r.abs() < 1e-13, "row {i}, column {c}: residual {r}");
            }
        }
        // the column beyond `m`: its entries permuted with the rows, not changed; the row
        // beyond `n` left as it was
        let mut was: Vec<u64> = (0..4).map(|i| orig[i][5].to_bits()).collect();
        let mut now: Vec<u64> = (0..4).map(|i| b[i][5].to_bits()).collect();
        was.sort_unstable();
        now.sort_unstable();
        assert_eq!(was, now);
        assert_eq!(b[4], orig[4]);
    }

    #[test]
    fn determinant_is_the_product_of_the_pivots_with_the_interchanges_sign() {
        // against the Leibniz sum over the 24 permutations of a 4 × 4 matrix that needs
        // pivoting (integer entries: both sides exact to a few ulp of the terms' size, ~200;
        // tolerance 1e-12 of it), and a permutation matrix (det −1, one interchange)
        let m = [[0.0, 2.0, 1.0, 3.0], [1.0, 1.0, 0.0, -1.0], [4.0, -1.0, 2.0, 0.5], [2.0, 0.0, -3.0, 1.0]];
        let mut leibniz = 0.0;
        let mut perm = [0, 1, 2, 3];
        // Heap's algorithm: every permutation, the sign flipping at each swap
        let mut c = [0usize; 4];
        let mut sign = 1.0;
        let term = |p: &[usize; 4]| (0..4).map(|i| m[i][p[i]]).product::<f64>();
        leibniz += sign * term(&perm);
        let mut i = 1;
        while i < 4 {
            if c[i] < i {
                if i % 2 == 0 {
                    perm.swap(0, i);
                } else {
                    perm.swap(c[i], i);
                }
                sign = -sign;
                leibniz += sign * term(&perm);
                c[i] += 1;
                i = 1;
            } else {
                c[i] = 0;
                i += 1;
            }
        }
        let d = Lu::new(m, 4).unwrap().det();
        assert!((d - leibniz).abs() < 1e-12 * 200.0, "{d} against {leibniz}");
        assert_eq!(Lu::new([[0.0, 1.0], [1.0, 0.0]], 2).unwrap().det(), -1.0);
    }
}
