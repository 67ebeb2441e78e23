//! Dense LU with partial pivoting of a row-major `n×n` matrix held in one buffer (allocated
//! once), for the default difference Jacobian of the implicit method. The linear model's
//! fixed-size factorisation (`linalg::dense`) works on stack arrays of a size known at compile
//! time; this one serves any dimension.

pub(crate) struct Lu {
    n: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
}

impl Lu {
    pub(crate) fn new(n: usize) -> Self {
        Lu { n, a: vec![0.0; n * n], piv: vec![0; n] }
    }

    /// The factorisation of the row-major `n × n` matrix `a`; `None` when a pivot is exactly
    /// zero or not finite (singular).
    pub(crate) fn factored(a: Vec<f64>, n: usize) -> Option<Self> {
        debug_assert_eq!(a.len(), n * n);
        let mut lu = Lu { n, a, piv: vec![0; n] };
        lu.factor().then_some(lu)
    }

    /// The matrix to factor (row-major), to be filled before [`Lu::factor`].
    pub(crate) fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.a
    }

    /// Factor in place; `false` when a pivot is exactly zero or not finite.
    pub(crate) fn factor(&mut self) -> bool {
        let n = self.n;
        let a = &mut self.a;
        for k in 0..n {
            let mut p = k;
            for i in k + 1..n {
                if a[i * n + k].abs() > a[p * n + k].abs() {
                    p = i;
                }
            }
            let pivot = a[p * n + k];
            if pivot == 0.0 || !pivot.is_finite() {
                return false;
            }
            if p != k {
                for j in 0..n {
                    a.swap(k * n + j, p * n + j);
                }
            }
            self.piv[k] = p;
            let inv = 1.0 / pivot;
            for i in k + 1..n {
                let f = a[i * n + k] * inv;
                a[i * n + k] = f;
                if f != 0.0 {
                    let (top, bottom) = a.split_at_mut(i * n);
                    let row_k = &top[k * n + k + 1..k * n + n];
                    for (x, y) in bottom[k + 1..n].iter_mut().zip(row_k) {
                        *x -= f * y;
                    }
                }
            }
        }
        true
    }

    /// Solve `A x = b` in place (after a successful [`Lu::factor`]).
    pub(crate) fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        let a = &self.a;
        for k in 0..n {
            b.swap(k, self.piv[k]);
        }
        for k in 0..n {
            let bk = b[k];
            if bk != 0.0 {
                for i in k + 1..n {
                    b[i] -= a[i * n + k] * bk;
                }
            }
        }
        for k in (0..n).rev() {
            let mut v = b[k];
            for j in k + 1..n {
                v -= a[k * n + j] * b[j];
            }
            b[k] = v / a[k * n + k];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_random_systems_and_refuses_singular_ones() {
        // a zero leading pivot forces row exchanges; residuals to rounding
        let n = 7;
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let a: Vec<f64> = (0..n * n).map(|k| if k == 0 { 0.0 } else { next() }).collect();
        let b: Vec<f64> = (0..n).map(|_| next()).collect();
        let mut lu = Lu::new(n);
        lu.matrix_mut().copy_from_slice(&a);
        assert!(lu.factor());
        let mut x = b.clone();
        lu.solve(&mut x);
        for i in 0..n {
            let r: f64 = (0..n).map(|j| a[i * n + j] * x[j]).sum::<f64>() - b[i];
            assert!(r.abs() < 1e-13, "residual {r}");
        }
        let mut s = Lu::new(2);
        s.matrix_mut().copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(!s.factor());
    }
}
