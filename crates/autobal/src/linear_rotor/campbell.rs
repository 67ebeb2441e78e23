//! The Campbell diagram of the structure without its balls: the eigenvalues of
//! `M q̈ + (C(Ω) + Ω G) q̇ + K(Ω) q = 0` in fixed axes at each speed (what ROSS's
//! `run_campbell` computes), from the first-order form
//! `ẋ = [[0, I], [−M⁻¹K, −M⁻¹(C + ΩG)]] x` by the dense eigenvalue routine.

use super::LinearRotor;
use crate::error::{Error, Result};
use crate::linalg::eigen_dyn;
use crate::ode::lu::Lu;
use num_complex::Complex64;

impl LinearRotor {
    /// The `2N` eigenvalues of the structure (no balls, no unbalance) at speed `omega`, sorted
    /// by imaginary part then real part.
    pub fn structure_eigenvalues(&self, omega: f64) -> Result<Vec<Complex64>> {
        self.validate()?;
        let n = self.dofs();
        let (c, k) = self.damping_stiffness_at(omega);
        let lu = Lu::factored(self.m.clone(), n).ok_or_else(|| Error::invalid("linear_rotor.m", "is singular"))?;
        let d2 = 2 * n;
        let mut a = vec![0.0; d2 * d2];
        for i in 0..n {
            a[i * d2 + n + i] = 1.0;
        }
        // columns of −M⁻¹K and −M⁻¹(C + ΩG)
        let mut col = vec![0.0; n];
        for j in 0..n {
            for (i, v) in col.iter_mut().enumerate() {
                *v = -k[i * n + j];
            }
            lu.solve(&mut col);
            for i in 0..n {
                a[(n + i) * d2 + j] = col[i];
            }
            for (i, v) in col.iter_mut().enumerate() {
                *v = -(c[i * n + j] + omega * self.g[i * n + j]);
            }
            lu.solve(&mut col);
            for i in 0..n {
                a[(n + i) * d2 + n + j] = col[i];
            }
        }
        let mut ev = eigen_dyn::eigenvalues(&a, d2).map_err(|_| Error::NoConvergence { omega })?;
        ev.sort_by(|x, y| x.im.total_cmp(&y.im).then(x.re.total_cmp(&y.re)));
        Ok(ev)
    }
}
