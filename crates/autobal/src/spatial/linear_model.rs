//! The linearised equations of the balanced state in axes rotating with the rotor
//! (000, eq (6); docs/notes/model.md §1), as a quadratic pencil `M q'' + G q' + K q = 0` and as the
//! first-order system `y' = A y`.
//!
//! Coordinates `q = (ξ_c, η_c, δ, θ, s_ξ, s_η)`: translation `w` of the common centre of mass,
//! tilt `χ`, total unbalance `s` of balls plus unbalance mass. With `E_c = [[0, −1], [1, 0]]`,
//! `E_A = diag(−1, 1)`:
//!
//! ```text
//! w'' + H_w w' + K_w w + h̄yα E_c χ' + K_wχ χ + s'' + 2Ω E_c s' − Ω² s = 0
//! I_C χ'' + H_χ χ' + K_χ χ − h̄yα E_c w' − K_wχ w + z̄_A E_c (s'' + 2Ω E_c s' − Ω² s) = 0
//! s'' + h̄s s' + ½ m̄ d_A (w'' + 2Ω E_c w' − Ω² w − z̄_A E_c (χ'' + 2Ω E_c χ' − Ω² χ)) = 0
//! H_w = h̄x E + 2Ω E_c            H_χ = h̄α E + Ω (2 − C̄Σ) E_c
//! K_w = (1 − Ω²) E + Ω h̄x E_c    K_wχ = −Ω h̄yα E + c̄yα E_c
//! K_χ = (p̄α² − Ω² (1 − C̄Σ)) E + ΔĀ Ω² E_A + Ω h̄α E_c      I_C = E + ΔĀ E_A
//! ```
//!
//! The mass matrix is not block-diagonal: `s` couples into `w` and `χ` through `M`. The
//! anisotropy `ΔĀ ≥ 0` and `d_A` are in the composite's principal frame
//! (`inertia::ball_coupling_exact`), or the paper's `diag(1 ∓ D_A)` on request.

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use crate::error::{Error, Result};
use crate::linalg::charpoly::PencilTerms;
use crate::linalg::dense::Lu;
use crate::spatial::params::SpatialModel;

pub use crate::linalg::small::{Mat12, Mat6, Pencil, MAX_COORDS, MAX_STATES};

/// Whether the balls move (12 states) or are locked at balance (`s ≡ 0`, 8 states).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Balls {
    /// Balls free: coordinates `w, χ, s`.
    Free,
    /// Balls locked: the bare anisotropic rotor, coordinates `w, χ`.
    Locked,
}

type B2 = [[f64; 2]; 2];
const E: B2 = [[1.0, 0.0], [0.0, 1.0]];
const EC: B2 = [[0.0, -1.0], [1.0, 0.0]];
const EA: B2 = [[-1.0, 0.0], [0.0, 1.0]];

fn lin(terms: &[(f64, B2)]) -> B2 {
    let mut r = [[0.0; 2]; 2];
    for (a, b) in terms {
        for i in 0..2 {
            for j in 0..2 {
                r[i][j] += a * b[i][j];
            }
        }
    }
    r
}

fn mul(a: B2, b: B2) -> B2 {
    let mut r = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    r
}

fn put(m: &mut Mat6, bi: usize, bj: usize, b: B2) {
    for i in 0..2 {
        for j in 0..2 {
            m[2 * bi + i][2 * bj + j] = b[i][j];
        }
    }
}

impl Pencil {
    /// Assemble the pencil of `model` at dimensionless speed `omega` (000, eq (6)).
    ///
    /// Fails when the balls are to be free but the model does not describe them.
    pub fn new(model: &SpatialModel, omega: f64, balls: Balls) -> Result<Self> {
        let w = omega;
        let w2 = w * w;
        let d = model.anisotropy.used;
        let dm = &model.damping;
        let (p2, c, z, cs) = (model.p_alpha_sq, model.c_y_alpha, model.z_a, model.c_sigma);
        let h_w = lin(&[(dm.h_x, E), (2.0 * w, EC)]);
        let h_chi = lin(&[(dm.h_alpha, E), (w * (2.0 - cs), EC)]);
        let k_w = lin(&[(1.0 - w2, E), (w * dm.h_x, EC)]);
        let k_wchi = lin(&[(-w * dm.h_y_alpha, E), (c, EC)]);
        let k_chi = lin(&[(p2 - w2 * (1.0 - cs), E), (d * w2, EA), (w * dm.h_alpha, EC)]);
        let i_c = lin(&[(1.0, E), (d, EA)]);
        let mut pen = Pencil { n: 4, m: [[0.0; 6]; 6], g: [[0.0; 6]; 6], k: [[0.0; 6]; 6] };
        put(&mut pen.m, 0, 0, E);
        put(&mut pen.m, 1, 1, i_c);
        put(&mut pen.g, 0, 0, h_w);
        put(&mut pen.g, 0, 1, lin(&[(dm.h_y_alpha, EC)]));
        put(&mut pen.g, 1, 0, lin(&[(-dm.h_y_alpha, EC)]));
        put(&mut pen.g, 1, 1, h_chi);
        put(&mut pen.k, 0, 0, k_w);
        put(&mut pen.k, 0, 1, k_wchi);
        put(&mut pen.k, 1, 0, lin(&[(-1.0, k_wchi)]));
        put(&mut pen.k, 1, 1, k_chi);
        if balls == Balls::Locked {
            return Ok(pen);
        }
        let b = model.balls.ok_or_else(|| {
            Error::invalid(
                "dimensionless.m",
                "the linear model with free balls needs the balls: give the masses (m0, r0, m, r, n), or m and d_a beside delta_a, or a dimensional [balancer]",
            )
        })?;
        pen.n = 6;
        let hm = 0.5 * b.m_bar;
        let da = b.d_a;
        // w rows: s'' + 2Ω E_c s' − Ω² s
        put(&mut pen.m, 0, 2, E);
        put(&mut pen.g, 0, 2, lin(&[(2.0 * w, EC)]));
        put(&mut pen.k, 0, 2, lin(&[(-w2, E)]));
        // χ rows: z̄ E_c (s'' + 2Ω E_c s' − Ω² s)
        put(&mut pen.m, 1, 2, lin(&[(z, EC)]));
        put(&mut pen.g, 1, 2, lin(&[(-2.0 * w * z, E)]));
        put(&mut pen.k, 1, 2, lin(&[(-w2 * z, EC)]));
        // s rows: s'' + h̄s s' + ½ m̄ d_A (w'' + 2Ω E_c w' − Ω² w − z̄ E_c (χ'' + 2Ω E_c χ' − Ω² χ))
        let da_ec = mul(da, EC);
        put(&mut pen.m, 2, 0, lin(&[(hm, da)]));
        put(&mut pen.g, 2, 0, lin(&[(2.0 * w * hm, da_ec)]));
        put(&mut pen.k, 2, 0, lin(&[(-w2 * hm, da)]));
        put(&mut pen.m, 2, 1, lin(&[(-z * hm, da_ec)]));
        put(&mut pen.g, 2, 1, lin(&[(2.0 * w * z * hm, da)]));
        put(&mut pen.k, 2, 1, lin(&[(w2 * z * hm, da_ec)]));
        put(&mut pen.m, 2, 2, E);
        put(&mut pen.g, 2, 2, lin(&[(dm.h_s, E)]));
        Ok(pen)
    }

    /// The pencil's dependence on the speed, `M λ² + (G0 + Ω G1) λ + K0 + Ω K1 + Ω² K2`, from
    /// the pencils at `Ω = 0, ±1` (eq (6) is linear in `Ω` in `G` and quadratic in `K`).
    pub fn terms(model: &SpatialModel, balls: Balls) -> Result<PencilTerms> {
        let p0 = Pencil::new(model, 0.0, balls)?;
        let pp = Pencil::new(model, 1.0, balls)?;
        let pm = Pencil::new(model, -1.0, balls)?;
        let mut t = PencilTerms { n: p0.n, m: p0.m, g: [p0.g, p0.g], k: [p0.k, p0.k, p0.k] };
        for i in 0..p0.n {
            for j in 0..p0.n {
                t.g[1][i][j] = 0.5 * (pp.g[i][j] - pm.g[i][j]);
                t.k[1][i][j] = 0.5 * (pp.k[i][j] - pm.k[i][j]);
                t.k[2][i][j] = 0.5 * (pp.k[i][j] + pm.k[i][j]) - p0.k[i][j];
            }
        }
        Ok(t)
    }

    /// State dimension `2n`.
    pub fn states(&self) -> usize {
        2 * self.n
    }

    /// First-order state matrix `A = [[0, I], [−M⁻¹K, −M⁻¹G]]` for `y = (q, q')`
    /// (Gaussian elimination with partial pivoting on `M`).
    pub fn state_matrix(&self) -> Mat12 {
        self.state_matrix_by(Lu::new(self.m, self.n).as_ref())
    }

    /// [`Pencil::state_matrix`] with `M` factored by the caller (`None`: singular); the
    /// columns of `[K G]` solved together ([`Lu::solve_columns`], each column bit for bit
    /// `Lu::solve`'s).
    fn state_matrix_by(&self, lu: Option<&Lu<MAX_COORDS>>) -> Mat12 {
        let n = self.n;
        // solve M [X Y] = [K G] (a singular M, impossible for physical inputs, gives NaN)
        let mut rhs = [[f64::NAN; 2 * MAX_COORDS]; MAX_COORDS];
        if let Some(lu) = lu {
            for i in 0..n {
                rhs[i][..n].copy_from_slice(&self.k[i][..n]);
                rhs[i][n..2 * n].copy_from_slice(&self.g[i][..n]);
            }
            lu.solve_columns(&mut rhs, 2 * n);
        }
        let mut a = [[0.0; MAX_STATES]; MAX_STATES];
        for i in 0..n {
            a[i][n + i] = 1.0;
            for j in 0..2 * n {
                a[n + i][j] = -rhs[i][j];
            }
        }
        a
    }
}

/// The state matrix as a polynomial in Ω, `A(Ω) = A0 + Ω A1 + Ω² A2`, for evaluating many
/// speeds of one model: `M` does not depend on Ω, `G` is linear and `K` quadratic in Ω
/// (eq (6)), so `M⁻¹G` and `M⁻¹K` are factored once. Built from the state matrices at
/// Ω = 0, ±1.
#[derive(Debug, Clone)]
pub struct StateSpace {
    /// State dimension.
    pub states: usize,
    a0: Mat12,
    a1: Mat12,
    a2: Mat12,
}

impl StateSpace {
    /// Factor the model's linearised equations once.
    pub fn new(model: &SpatialModel, balls: Balls) -> Result<Self> {
        let (p0, pp, pm) = (Pencil::new(model, 0.0, balls)?, Pencil::new(model, 1.0, balls)?, Pencil::new(model, -1.0, balls)?);
        // `M` does not depend on Ω (eq (6)): one factorisation serves the three pencils where
        // their mass matrices are the same bits (each is then what `state_matrix` gives)
        let lu = Lu::new(p0.m, p0.n);
        let same_m = |p: &Pencil| p.m.iter().flatten().zip(p0.m.iter().flatten()).all(|(a, b)| a.to_bits() == b.to_bits());
        let by = |p: &Pencil| if same_m(p) { p.state_matrix_by(lu.as_ref()) } else { p.state_matrix() };
        let (a0, ap, am) = (by(&p0), by(&pp), by(&pm));
        let states = p0.states();
        let mut a1 = [[0.0; MAX_STATES]; MAX_STATES];
        let mut a2 = [[0.0; MAX_STATES]; MAX_STATES];
        for i in 0..states {
            for j in 0..states {
                a1[i][j] = 0.5 * (ap[i][j] - am[i][j]);
                a2[i][j] = 0.5 * (ap[i][j] + am[i][j]) - a0[i][j];
            }
        }
        Ok(StateSpace { states, a0, a1, a2 })
    }

    /// `A(Ω)`.
    pub fn at(&self, omega: f64) -> Mat12 {
        let mut a = self.a0;
        let w2 = omega * omega;
        for i in self.states / 2..self.states {
            for j in 0..self.states {
                a[i][j] += omega * self.a1[i][j] + w2 * self.a2[i][j];
            }
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::params::DimensionlessInput;

    /// `StateSpace::new`'s matrices (one LU of `M` shared by the three pencils, the columns
    /// solved together) are bit for bit those built from each pencil's own
    /// `Pencil::state_matrix`, the route they replaced: balls free and locked, on paper 003's
    /// rotor at two bearing positions with `bench_map`'s balls (the map's outputs depend on these bits). Fails if a
    /// pencil's `G` or `K` is paired with another's (the three differ in `Ω`).
    #[test]
    fn state_space_is_each_pencils_state_matrix_bit_for_bit() {
        for l_left in [0.8, 0.35] {
            let input = DimensionlessInput { direct_balls: Some((0.05, 0.5)), ..DimensionlessInput::paper_003(l_left) };
            let model = SpatialModel::from_dimensionless(&input).unwrap();
            for balls in [Balls::Free, Balls::Locked] {
                let ss = StateSpace::new(&model, balls).unwrap();
                let a = |w: f64| Pencil::new(&model, w, balls).unwrap().state_matrix();
                let (a0, ap, am) = (a(0.0), a(1.0), a(-1.0));
                let bits = |m: &Mat12| m.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>();
                let mut a1 = [[0.0; MAX_STATES]; MAX_STATES];
                let mut a2 = [[0.0; MAX_STATES]; MAX_STATES];
                for i in 0..ss.states {
                    for j in 0..ss.states {
                        a1[i][j] = 0.5 * (ap[i][j] - am[i][j]);
                        a2[i][j] = 0.5 * (ap[i][j] + am[i][j]) - a0[i][j];
                    }
                }
                assert_eq!(bits(&ss.a0), bits(&a0), "A0, {balls:?}, l_left {l_left}");
                assert_eq!(bits(&ss.a1), bits(&a1), "A1, {balls:?}, l_left {l_left}");
                assert_eq!(bits(&ss.a2), bits(&a2), "A2, {balls:?}, l_left {l_left}");
                assert_eq!(ss.states, Pencil::new(&model, 0.0, balls).unwrap().states());
                // and the matrices are not trivially equal: the speed terms are there
                assert!(ss.a1.iter().flatten().any(|v| *v != 0.0) && ss.a2.iter().flatten().any(|v| *v != 0.0));
            }
        }
    }
}
