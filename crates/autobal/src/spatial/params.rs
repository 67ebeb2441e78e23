//! Parameters of the spatial rotor of papers 000 and 003: the papers' dimensionless model
//! ([`SpatialModel`]) and its inputs in the papers' symbols ([`DimensionlessInput`]). The SI
//! rotor an engineer writes down is [`crate::spatial::dynamics::SpatialRotor`]; its
//! [`to_dimensionless`](crate::spatial::dynamics::SpatialRotor::to_dimensionless) derives the
//! model (000, eqs (4), (5), (8), (10)).
//!
//! Axis convention: `z` runs along the shaft from the left support towards the right one.
//! `l_cL = z_C − z_L`, `l_cR = z_R − z_C` (negative for an overhung rotor beyond the right
//! support), `z_A = z_plane − z_C`. With this convention the papers' coupling coefficient
//! `c_yα = c_L l_cL − c_R l_cR` and their antiresonance formula (003, eq (1)) follow from the
//! forced response of the locked rotor (see `ranges::antiresonance_speed`).

use crate::error::{fmt_num, positive, Error, Result};
use crate::limits::{check, check_all, check_count};
use crate::spatial::inertia::{self, Anisotropy, AnisotropyMethod, BallSet, CompositeInertia};
use serde::Serialize;

/// Masses and radii of unbalance and balls in the papers' dimensionless form (000, eq (17)):
/// `m̄0 = m0/M_s`, `R̄0 = R0/ρ_s`, `m̄ = n m/M_s` (all balls together), `R̄ = R/ρ_s`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MassSet {
    /// `m̄0`, relative unbalance mass.
    pub m0: f64,
    /// `R̄0`, relative unbalance radius.
    pub r0: f64,
    /// `m̄`, relative mass of all balls together.
    pub m: f64,
    /// `R̄`, relative race radius.
    pub r: f64,
    /// `n`, number of balls.
    pub n: u32,
}

impl MassSet {
    /// `Ā_m0 = m̄0 R̄0²`: the unbalance mass's polar moment relative to `A_Σ`.
    pub fn a_m0(&self) -> f64 {
        self.m0 * self.r0 * self.r0
    }
    /// `Ā_m = m̄ R̄²`: the balls' polar moment relative to `A_Σ`.
    pub fn a_m(&self) -> f64 {
        self.m * self.r * self.r
    }
    /// Balancer capacity `E = m̄ R̄ / (m̄0 R̄0)` (000): the balls can cancel the unbalance
    /// only when `E ≥ 1` (and, for one ball, `E = 1`). Infinite when there is no unbalance.
    pub fn capacity(&self) -> f64 {
        let s0 = self.m0 * self.r0;
        if s0 == 0.0 {
            f64::INFINITY
        } else {
            self.m * self.r / s0
        }
    }
    /// The set of balls as the inertia module sees it.
    pub fn ball_set(&self) -> BallSet {
        BallSet { n: self.n, a_m0: self.a_m0(), a_m: self.a_m(), capacity: self.capacity() }
    }
}

/// Dimensionless damping coefficients (000, eq (10)): `h̄x = h_x/(M_s ω0)`,
/// `h̄α = h_α/(A_Σ ω0)`, `h̄yα = h_yα/(ω0 sqrt(M_s A_Σ))`, `h̄s = h_A/(m ω0)`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Damping {
    /// `h̄x`, translational support damping.
    pub h_x: f64,
    /// `h̄α`, angular support damping.
    pub h_alpha: f64,
    /// `h̄yα`, cross damping between translation and tilt.
    pub h_y_alpha: f64,
    /// `h̄s`, drag on the balls' relative motion.
    pub h_s: f64,
}

/// Scale factors back to SI, present when the model was built from a dimensional rotor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Scale {
    /// `ω0 = sqrt(c_x / M_s)` (rad/s): the unit of every dimensionless speed Ω.
    pub omega0: f64,
    /// `M_s = M_r + m0 + n m` (kg).
    pub total_mass: f64,
    /// `ρ_s = sqrt(A_Σ / M_s)` (m).
    pub rho_s: f64,
    /// Support span `l = z_R − z_L` (m).
    pub span: f64,
}

/// The balls as the linear model's ball equation sees them (000, eq (6)):
/// `s'' + h̄s s' + ½ m̄ d_A (…) = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BallCoupling {
    /// `m̄ = n m / M_s`.
    pub m_bar: f64,
    /// `d_A` in the frame of the model's inertia (see `inertia::ball_coupling_exact`).
    pub d_a: [[f64; 2]; 2],
}

/// The dimensionless spatial model every analysis of papers 000/003 works on.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpatialModel {
    /// `C̄Σ = C_Σ / A_Σ`: rotor type (long `< 1`, spherical `= 1`, short `> 1`).
    pub c_sigma: f64,
    /// `ρ̄s = ρ_s / l`, when known.
    pub rho_s: Option<f64>,
    /// `l̄_L = l_cL / l`, when known.
    pub l_left: Option<f64>,
    /// `p̄α² = c_α / (A_Σ ω0²)`: squared angular natural frequency of the supports.
    pub p_alpha_sq: f64,
    /// `c̄yα = c_yα / (ω0² sqrt(M_s A_Σ))`: translation–tilt coupling of the supports.
    pub c_y_alpha: f64,
    /// `z̄_A = z_A / ρ_s`: position of plane A relative to the common centre of mass C.
    pub z_a: f64,
    /// Inertia anisotropy of the composite rotor at balance (000, eq (17) and exact tensor).
    pub anisotropy: Anisotropy,
    /// `ΔĀ0`: anisotropy of the unbalance mass alone (003), used by the autobalancing ranges.
    pub delta_a0: f64,
    /// Dimensionless damping.
    pub damping: Damping,
    /// Masses, when the anisotropy was derived from them.
    pub masses: Option<MassSet>,
    /// SI scale factors, when built from a dimensional rotor.
    pub scale: Option<Scale>,
    /// Ball coupling for the linear model with free balls, when the balls are described.
    pub balls: Option<BallCoupling>,
}

/// Support coefficients for identical supports from `l̄_L` and `ρ̄s` (000, eq (10)):
/// `p̄α² = (l̄_L² + (1 − l̄_L)²)/(2 ρ̄s²)`, `c̄yα = (2 l̄_L − 1)/(2 ρ̄s)`.
pub fn identical_support_coefficients(l_left: f64, rho_s: f64) -> (f64, f64) {
    let p_sq = (l_left * l_left + (1.0 - l_left) * (1.0 - l_left)) / (2.0 * rho_s * rho_s);
    let c = (2.0 * l_left - 1.0) / (2.0 * rho_s);
    (p_sq, c)
}

/// How the anisotropy of a dimensionless model is specified.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnisotropyInput {
    /// `ΔĀ` given directly; it also serves as `ΔĀ0`, as in the worked examples of 003.
    Direct(f64),
    /// From masses and radii; `d_a` optionally fixes `D_A` for eq (17) when `n ≥ 3`.
    Masses {
        /// The unbalance and ball masses and radii.
        masses: MassSet,
        /// `D_A`, the modulus of the mean of `exp(2iα_j)` over the balls, for eq (17).
        d_a: Option<f64>,
    },
}

/// Inputs of a dimensionless model in the papers' symbols, identical supports assumed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DimensionlessInput {
    /// `C̄Σ`.
    pub c_sigma: f64,
    /// `ρ̄s`.
    pub rho_s: f64,
    /// `l̄_L`.
    pub l_left: f64,
    /// `z̄_A`.
    pub z_a: f64,
    /// The anisotropy specification.
    pub anisotropy: AnisotropyInput,
    /// `h̄x`; `h̄α`, `h̄yα` follow for identical supports.
    pub h_x: f64,
    /// `h̄s`.
    pub h_s: f64,
    /// Which anisotropy the analyses use.
    pub method: AnisotropyMethod,
    /// With `delta_a` given directly: the balls' `m̄` and `D_A` for the linear model's ball
    /// equation (`d_A = diag(1 − D_A, 1 + D_A)`), if the balls are to be free.
    pub direct_balls: Option<(f64, f64)>,
}

impl SpatialModel {
    /// The composite rotor's inertia from the anisotropy in use: `A_C1,2 = A_Σ ± ΔA`, `C_Σ`
    /// (000, eqs (4)-(5)), in SI when the model came from a dimensional config, else relative to
    /// `A_Σ`.
    pub fn composite_inertia(&self) -> CompositeInertia {
        let (scale_a, total_mass, si) = match self.scale {
            Some(s) => (s.total_mass * s.rho_s * s.rho_s, Some(s.total_mass), true),
            None => (1.0, None, false),
        };
        let d = self.anisotropy.used * scale_a;
        CompositeInertia { total_mass, a_sigma: scale_a, c_sigma: self.c_sigma * scale_a, a_c1: scale_a + d, a_c2: scale_a - d, delta_a: d, si }
    }
    /// Build from the papers' dimensionless parameters, identical supports.
    ///
    /// Damping for identical supports: `h̄α = h̄x (l̄_L² + (1 − l̄_L)²)/(2 ρ̄s²)`,
    /// `h̄yα = h̄x (2 l̄_L − 1)/(2 ρ̄s)` (same algebra as the stiffnesses).
    pub fn from_dimensionless(inp: &DimensionlessInput) -> Result<Self> {
        let p = "dimensionless";
        check_all(&[
            ("dimensionless.c_sigma", inp.c_sigma),
            ("dimensionless.rho_s", inp.rho_s),
            ("dimensionless.l_left", inp.l_left),
            ("dimensionless.z_a", inp.z_a),
            ("dimensionless.h_x", inp.h_x),
            ("dimensionless.h_s", inp.h_s),
        ])?;
        let (p_alpha_sq, c_y_alpha) = identical_support_coefficients(inp.l_left, inp.rho_s);
        let (anisotropy, delta_a0, masses) = match inp.anisotropy {
            AnisotropyInput::Direct(d) => {
                check_delta_a(d, inp.c_sigma)?;
                if let Some((m, d_a)) = inp.direct_balls {
                    positive("dimensionless.m", m)?;
                    check("dimensionless.m", m)?;
                    check("dimensionless.d_a", d_a)?;
                }
                (Anisotropy::given(d), d, None)
            }
            AnisotropyInput::Masses { masses, d_a } => {
                validate_masses(p, &masses, inp.c_sigma)?;
                let a = inertia::anisotropy(&masses.ball_set(), d_a, inp.method).map_err(|e| prefix_field(e, p))?;
                (a, 0.5 * masses.a_m0(), Some(masses))
            }
        };
        let damping = Damping { h_x: inp.h_x, h_alpha: inp.h_x * p_alpha_sq, h_y_alpha: inp.h_x * c_y_alpha, h_s: inp.h_s };
        let balls = match (masses, inp.direct_balls) {
            (Some(ms), _) => ball_coupling(&ms, &anisotropy),
            (None, Some((m_bar, d_a))) => Some(BallCoupling { m_bar, d_a: inertia::ball_coupling_paper(d_a) }),
            _ => None,
        };
        Ok(SpatialModel {
            balls,
            c_sigma: inp.c_sigma,
            rho_s: Some(inp.rho_s),
            l_left: Some(inp.l_left),
            p_alpha_sq,
            c_y_alpha,
            z_a: inp.z_a,
            anisotropy,
            delta_a0,
            damping,
            masses,
            scale: None,
        })
    }

    /// `ΔĪ_1,2 = 1 − C̄Σ ± ΔĀ` (000, eq (15)) for the anisotropy in use.
    pub fn delta_i(&self) -> [f64; 2] {
        let d = self.anisotropy.used;
        [1.0 - self.c_sigma + d, 1.0 - self.c_sigma - d]
    }

    /// Copy of the model with the anisotropy in use replaced by `delta_a` (e.g. an end of the
    /// interval of a multi-ball balancer, or 0 for the isotropic comparison rotor).
    pub fn with_anisotropy(&self, delta_a: f64) -> Self {
        let mut m = self.clone();
        m.anisotropy.used = delta_a;
        m
    }
}

/// Ball coupling of the linear model from the masses and the anisotropy in use: none without
/// balls; else `m̄` and `d_A`, by eq (17)'s `D_A` (`diag(1 − D_A, 1 + D_A)`) or from the balls'
/// balancing angles ([`inertia::ball_coupling_exact`]).
pub(crate) fn ball_coupling(ms: &MassSet, a: &Anisotropy) -> Option<BallCoupling> {
    if ms.n == 0 || ms.m == 0.0 {
        return None;
    }
    let d_a = match (a.method, &a.ball_angles) {
        (AnisotropyMethod::Paper, _) | (_, None) => inertia::ball_coupling_paper(a.d_a.unwrap_or(1.0)),
        (_, Some(angles)) => inertia::ball_coupling_exact(&ms.ball_set(), angles),
    };
    Some(BallCoupling { m_bar: ms.m, d_a })
}

fn prefix_field(e: Error, prefix: &str) -> Error {
    match e {
        Error::InvalidParameter { field, reason } if !field.contains('.') => Error::InvalidParameter { field: format!("{prefix}.{field}"), reason },
        other => other,
    }
}

/// `ΔĀ` given directly: in its range, and `2 ΔĀ ≤ C̄Σ` (the principal moments `1 ± ΔĀ`, `C̄Σ`
/// of a rigid body satisfy the triangle inequality).
pub fn check_delta_a(delta_a: f64, c_sigma: f64) -> Result<()> {
    check("dimensionless.delta_a", delta_a)?;
    if 2.0 * delta_a > c_sigma {
        return Err(Error::invalid(
            "dimensionless.delta_a",
            format!(
                "2 ΔĀ = {} exceeds C̄Σ = {}: the principal moments 1 + ΔĀ, 1 − ΔĀ, C̄Σ of a rigid body satisfy the triangle inequality",
                fmt_num(2.0 * delta_a),
                fmt_num(c_sigma)
            ),
        ));
    }
    Ok(())
}

fn validate_masses(p: &str, m: &MassSet, c_sigma: f64) -> Result<()> {
    check_all(&[("dimensionless.m0", m.m0), ("dimensionless.r0", m.r0), ("dimensionless.m", m.m), ("dimensionless.r", m.r)])?;
    check_count(&format!("{p}.n"), m.n as u64)?;
    // the point masses' polar moment is part of C_Σ (and half of it part of A_Σ = 1)
    let polar = m.a_m0() + m.a_m();
    if polar > c_sigma {
        return Err(Error::invalid(
            if m.a_m0() >= m.a_m() { format!("{p}.r0") } else { format!("{p}.r") },
            format!("the polar moment of unbalance and balls m0 r0² + m r² = {} exceeds C̄Σ = {}, of which it is a part", fmt_num(polar), fmt_num(c_sigma)),
        ));
    }
    if m.n == 0 && m.m > 0.0 {
        return Err(Error::invalid(format!("{p}.n"), "is 0 but the ball mass m is given: set n, or m = 0"));
    }
    if m.n > 0 && m.m == 0.0 {
        return Err(Error::invalid(format!("{p}.m"), "must be positive when n > 0"));
    }
    if m.m0 + m.m >= 1.0 {
        return Err(Error::invalid(format!("{p}.m0"), format!("m0 + m = {} must stay below 1: they are fractions of the total mass M_s", fmt_num(m.m0 + m.m))));
    }
    Ok(())
}
