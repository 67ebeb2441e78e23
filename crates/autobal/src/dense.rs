//! Small dense linear solves on stack arrays (Gaussian elimination with partial pivoting),
//! shared by the linear model (`M⁻¹[K G]`) and the simulation (the mass matrix at each step).

/// Solve `A X = B` in place: on return the first `cols` columns of `b` hold `X`. Only the
/// leading `n×n` block of `a` and the first `n` rows of `b` are used; `a` is destroyed.
pub(crate) fn solve_in_place<const N: usize, const M: usize>(a: &mut [[f64; N]; N], b: &mut [[f64; M]; N], n: usize, cols: usize) {
    for col in 0..n {
        let mut p = col;
        for r in col + 1..n {
            if a[r][col].abs() > a[p][col].abs() {
                p = r;
            }
        }
        a.swap(col, p);
        b.swap(col, p);
        let piv = a[col][col];
        for r in col + 1..n {
            let g = a[r][col] / piv;
            if g != 0.0 {
                for k in col..n {
                    a[r][k] -= g * a[col][k];
                }
                for k in 0..cols {
                    b[r][k] -= g * b[col][k];
                }
            }
        }
    }
    for col in (0..n).rev() {
        for k in 0..cols {
            let mut v = b[col][k];
            for j in col + 1..n {
                v -= a[col][j] * b[j][k];
            }
            b[col][k] = v / a[col][col];
        }
    }
}
