//! Mass-inertia properties of the composite rotor (rotor + unbalance mass + balls at balance),
//! 000 eqs (4), (5), (17), and the exact inertia tensor of the point masses.
//!
//! In plane A, a point mass `m_k` at radius `r_k` and angle `φ_k` (rotor frame) adds
//! `½ m_k r_k²` to each equatorial moment and the anisotropic part
//! `½ m_k r_k² exp(2 i φ_k)`. The composite's equatorial anisotropy is the modulus of the sum,
//! `ΔA = |½ A_m0 + ½ A_m D|`, `D = (1/n) Σ exp(2 i α_j)`, with the unbalance at `φ = 0`.
//! Paper 000's eq (17) adds magnitudes instead, `ΔA = ½ A_m0 + ½ A_m |D|`, which is right only
//! when the balls' principal axes line up with the unbalance's (`Re D ≥ 0`, `Im D = 0`).
//! For two balls at balance `α = π ± acos(1/E)`, `D = 2/E² − 1`, negative once `E > √2`: in
//! 000's own base case (`E = 2`) the exact anisotropy is zero while eq (17) gives 0.1.

use crate::error::{fmt_num, Error, Result};
use serde::Serialize;
use std::f64::consts::PI;

/// Which anisotropy the analyses use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum AnisotropyMethod {
    /// Exact inertia tensor of the point masses at their balancing positions (default).
    Exact,
    /// Paper 000's eq (17), `ΔĀ = ½ Ā_m0 + ½ Ā_m D_A`.
    Paper,
    /// `ΔĀ` given directly by the user (both methods agree by definition).
    Given,
}

/// The balls and unbalance of plane A, relative to `A_Σ` (000, eq (17)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallSet {
    /// Number of balls.
    pub n: u32,
    /// `Ā_m0 = m̄0 R̄0²`.
    pub a_m0: f64,
    /// `Ā_m = m̄ R̄²` (all balls).
    pub a_m: f64,
    /// Capacity `E = m̄ R̄ / (m̄0 R̄0)`.
    pub capacity: f64,
}

/// The relative inertia anisotropy `ΔĀ = ΔA / A_Σ` of the composite rotor, both ways.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Anisotropy {
    /// Eq (17) of 000 with the `D_A` in force (for `n ≥ 3`: `d_a` if given, else 1).
    pub paper: f64,
    /// Eq (17) over `D_A ∈ [0, 1]`, the papers' bound for `n ≥ 3` (`[paper, paper]` otherwise).
    pub paper_interval: [f64; 2],
    /// Exact tensor: `[min, max]` over all balancing positions (a single value for `n ≤ 2`).
    pub exact: [f64; 2],
    /// The value the analyses use.
    pub used: f64,
    /// The interval the analyses use (critical speeds are reported over it).
    pub used_interval: [f64; 2],
    /// Which of the above is used.
    pub method: AnisotropyMethod,
    /// `D_A` of eq (17) in force.
    pub d_a: Option<f64>,
    /// Ball angles at balance relative to the unbalance direction (rad): the unique balancing
    /// position for `n ≤ 2`; for `n ≥ 3` the member of the family with the largest exact
    /// anisotropy (the worst case, which `exact[1]` and the linear model refer to).
    pub ball_angles: Option<Vec<f64>>,
    /// Whether the balls can cancel the unbalance (`E ≥ 1`; `E = 1` for one ball).
    pub can_balance: bool,
    /// Notes for the user (method disagreement, capacity too small, ...).
    pub warnings: Vec<String>,
}

impl Anisotropy {
    /// `ΔĀ` given directly: both methods coincide by definition.
    pub fn given(delta_a: f64) -> Self {
        Anisotropy {
            paper: delta_a,
            paper_interval: [delta_a; 2],
            exact: [delta_a; 2],
            used: delta_a,
            used_interval: [delta_a; 2],
            method: AnisotropyMethod::Given,
            d_a: None,
            ball_angles: None,
            can_balance: true,
            warnings: vec![],
        }
    }

    /// Relative difference between the exact value and eq (17), `|paper − exact| / paper`
    /// (upper ends of the intervals); 0 when both vanish.
    pub fn relative_difference(&self) -> f64 {
        let (p, e) = (self.paper_interval[1], self.exact[1]);
        let scale = p.abs().max(e.abs());
        if scale == 0.0 {
            0.0
        } else {
            (p - e).abs() / scale
        }
    }
}

/// Exact anisotropy of given ball angles: `|½ Ā_m0 + ½ Ā_m (1/n) Σ exp(2 i α_j)|`.
pub fn exact_anisotropy_of(set: &BallSet, angles: &[f64]) -> f64 {
    let (dc, ds) = mean_double_angle(angles);
    0.5 * (set.a_m0 + set.a_m * dc).hypot(set.a_m * ds)
}

/// `D_c + i D_s = (1/n) Σ exp(2 i α_j)`; `1` for no balls.
pub fn mean_double_angle(angles: &[f64]) -> (f64, f64) {
    if angles.is_empty() {
        return (1.0, 0.0);
    }
    let n = angles.len() as f64;
    let (c, s) = angles.iter().fold((0.0, 0.0), |(c, s), a| (c + (2.0 * a).cos(), s + (2.0 * a).sin()));
    (c / n, s / n)
}

/// Ball angles at balance for `n ≤ 2`, relative to the unbalance: one ball opposite it;
/// two balls at `π ± acos(1/E)` (`α = π` for both when `E < 1`, where they cannot balance).
/// `None` for `n ≥ 3` (a family of positions).
pub fn balancing_angles(set: &BallSet) -> Option<Vec<f64>> {
    match set.n {
        0 => Some(vec![]),
        1 => Some(vec![PI]),
        2 => {
            let beta = if set.capacity.is_finite() { (1.0 / set.capacity).min(1.0).acos() } else { PI / 2.0 };
            Some(vec![PI - beta, PI + beta])
        }
        _ => None,
    }
}

/// Compute the anisotropy both ways for the balls at balance, and choose the one in use.
///
/// For `n ≥ 3` the balancing positions form an `(n − 2)`-parameter family
/// `(1/n) Σ exp(i α_j) = −1/E`; the exact interval is found by a global search over it
/// ([`exact_interval`]).
pub fn anisotropy(set: &BallSet, d_a: Option<f64>, method: AnisotropyMethod) -> Result<Anisotropy> {
    if let Some(d) = d_a {
        if !(0.0..=1.0).contains(&d) || d.is_nan() {
            return Err(Error::invalid("d_a", format!("D_A must lie in [0, 1], got {}", fmt_num(d))));
        }
    }
    let mut warnings = vec![];
    let can_balance = match set.n {
        0 => set.a_m0 == 0.0,
        1 => (set.capacity - 1.0).abs() < 1e-12,
        _ => set.capacity >= 1.0,
    };
    if set.n > 0 && !can_balance {
        warnings.push(format!(
            "balancer capacity E = {:.4} {}: the balls cannot cancel the unbalance; they are taken at their limit position opposite it",
            set.capacity,
            if set.n == 1 { "≠ 1 with one ball" } else { "< 1" }
        ));
    }
    let (paper, paper_interval, exact, ball_angles, d_used) = if set.n <= 2 || !can_balance {
        let angles = if can_balance { balancing_angles(set).unwrap() } else { vec![PI; set.n as usize] };
        // two balls at π ± β, cos β = 1/E: D = cos 2β = 2/E² − 1 exactly (no trigonometric
        // round-off, so 000's base case E = 2 comes out exactly isotropic)
        let (dc, ds) = if set.n == 2 && can_balance && set.capacity.is_finite() {
            (2.0 / (set.capacity * set.capacity) - 1.0, 0.0)
        } else {
            mean_double_angle(&angles)
        };
        let da_natural = dc.hypot(ds);
        if set.n <= 2 {
            if let Some(d) = d_a {
                if (d - da_natural).abs() > 1e-9 && set.n > 0 {
                    return Err(Error::invalid(
                        "d_a",
                        format!(
                            "with n = {} balls the balancing positions are fixed, so D_A = {da_natural:.6}; omit d_a or use that value (d_a = {} given)",
                            set.n,
                            fmt_num(d)
                        ),
                    ));
                }
            }
        }
        let paper = 0.5 * set.a_m0 + 0.5 * set.a_m * da_natural;
        let exact = 0.5 * (set.a_m0 + set.a_m * dc).hypot(set.a_m * ds);
        (paper, [paper; 2], [exact; 2], Some(angles), da_natural)
    } else {
        let d = d_a.unwrap_or(1.0);
        let paper = 0.5 * set.a_m0 + 0.5 * set.a_m * d;
        let interval = exact_interval(set);
        (paper, [0.5 * set.a_m0, 0.5 * (set.a_m0 + set.a_m)], [interval.min, interval.max], Some(interval.argmax), d)
    };
    let (used, used_interval) = match method {
        AnisotropyMethod::Paper => (paper, if d_a.is_some() || set.n <= 2 { [paper; 2] } else { paper_interval }),
        _ => (exact[1], exact),
    };
    let mut a = Anisotropy {
        paper,
        paper_interval,
        exact,
        used,
        used_interval,
        method: if method == AnisotropyMethod::Given { AnisotropyMethod::Exact } else { method },
        d_a: Some(d_used),
        ball_angles,
        can_balance,
        warnings,
    };
    if a.relative_difference() > 0.01 {
        a.warnings.push(format!(
            "the exact inertia tensor gives ΔĀ = {} but paper 000's eq (17) gives {}: they differ by {:.0} % (eq (17) adds the anisotropies of unbalance and balls by magnitude); using the {} value",
            fmt_interval(a.exact),
            fmt_interval(a.paper_interval),
            100.0 * a.relative_difference(),
            if a.method == AnisotropyMethod::Paper { "paper" } else { "exact" }
        ));
    }
    Ok(a)
}

fn fmt_interval(i: [f64; 2]) -> String {
    if (i[0] - i[1]).abs() <= 1e-12 * i[1].abs().max(1.0) {
        format!("{:.6}", i[0])
    } else {
        format!("[{:.6}, {:.6}]", i[0], i[1])
    }
}

/// The range of the exact anisotropy over the balancing family of `n ≥ 3` balls, with the
/// configurations that attain it.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactInterval {
    /// Smallest `ΔĀ` over the family.
    pub min: f64,
    /// Largest `ΔĀ` over the family.
    pub max: f64,
    /// Ball angles attaining the minimum.
    pub argmin: Vec<f64>,
    /// Ball angles attaining the maximum.
    pub argmax: Vec<f64>,
}

/// Close a configuration: given the angles of balls 3..n, place balls 1 and 2 so that
/// `Σ exp(i α_j) = −n/E`. `None` when they cannot reach (the remaining vector exceeds 2).
pub fn complete_configuration(n: u32, capacity: f64, free: &[f64]) -> Option<Vec<f64>> {
    let target = -(n as f64) / capacity;
    let (mut wx, mut wy) = (target, 0.0);
    for a in free {
        wx -= a.cos();
        wy -= a.sin();
    }
    let r = wx.hypot(wy);
    if r > 2.0 {
        return None;
    }
    let phi = wy.atan2(wx);
    let half = (r / 2.0).min(1.0).acos();
    let mut v = vec![phi + half, phi - half];
    v.extend_from_slice(free);
    Some(v)
}

/// Global search of the exact anisotropy over the balancing family (`n ≥ 3`, `E ≥ 1`).
///
/// Parametrised by the angles of balls 3..n (balls 1, 2 close the balance,
/// [`complete_configuration`]); deterministic multistart of Nelder–Mead from structured
/// candidates (groups of balls at 0 and π with a symmetric pair) and quasi-random points.
/// Tests check it against a dense sweep for `n = 3` and against random feasible samples.
pub fn exact_interval(set: &BallSet) -> ExactInterval {
    let n = set.n;
    let k = (n - 2) as usize;
    let e = set.capacity;
    let eval = |free: &[f64]| complete_configuration(n, e, free).map(|c| exact_anisotropy_of(set, &c));
    let mut starts: Vec<Vec<f64>> = vec![];
    // structured: j balls at 0, the rest of the free ones at π
    for j in 0..=k {
        let mut v = vec![PI; k];
        for x in v.iter_mut().take(j) {
            *x = 0.0;
        }
        starts.push(v);
    }
    // quasi-random (additive recurrence on the golden ratio, deterministic)
    let mut seed = 0.5f64;
    let count = 48 * k.max(1);
    for _ in 0..count {
        let v: Vec<f64> = (0..k)
            .map(|_| {
                seed = (seed + 0.618_033_988_749_894_9).fract();
                2.0 * PI * seed
            })
            .collect();
        starts.push(v);
    }
    let mut best_min = (f64::INFINITY, vec![]);
    let mut best_max = (f64::NEG_INFINITY, vec![]);
    for s in &starts {
        if eval(s).is_none() {
            continue;
        }
        let (xmin, fmin) = nelder_mead(|x| eval(x).unwrap_or(f64::INFINITY), s, 0.4, 400);
        if fmin < best_min.0 {
            best_min = (fmin, xmin);
        }
        let (xmax, fmax) = nelder_mead(|x| eval(x).map(|v| -v).unwrap_or(f64::INFINITY), s, 0.4, 400);
        if -fmax > best_max.0 {
            best_max = (-fmax, xmax);
        }
    }
    ExactInterval {
        min: best_min.0,
        max: best_max.0,
        argmin: complete_configuration(n, e, &best_min.1).unwrap_or_default(),
        argmax: complete_configuration(n, e, &best_max.1).unwrap_or_default(),
    }
}

/// Minimal Nelder–Mead simplex search (standard coefficients 1, 2, ½, ½), used only on the
/// few smooth angle variables of [`exact_interval`]; infeasible points return `+∞`.
fn nelder_mead(f: impl Fn(&[f64]) -> f64, x0: &[f64], step: f64, iters: usize) -> (Vec<f64>, f64) {
    let d = x0.len();
    let mut simplex: Vec<(Vec<f64>, f64)> = vec![(x0.to_vec(), f(x0))];
    for i in 0..d {
        let mut x = x0.to_vec();
        x[i] += step;
        let v = f(&x);
        simplex.push((x, v));
    }
    for _ in 0..iters {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        if (simplex[d].1 - simplex[0].1).abs() < 1e-15 && simplex[d].1.is_finite() {
            let spread: f64 = simplex.iter().map(|p| (p.0[0] - simplex[0].0[0]).abs()).sum();
            if spread < 1e-12 {
                break;
            }
        }
        let centroid: Vec<f64> =
            (0..d).map(|j| simplex[..d].iter().map(|p| p.0[j]).sum::<f64>() / d as f64).collect();
        let lerp = |t: f64| -> Vec<f64> { (0..d).map(|j| centroid[j] + t * (simplex[d].0[j] - centroid[j])).collect() };
        let xr = lerp(-1.0);
        let fr = f(&xr);
        if fr < simplex[0].1 {
            let xe = lerp(-2.0);
            let fe = f(&xe);
            simplex[d] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[d - 1].1 {
            simplex[d] = (xr, fr);
        } else {
            let xc = if fr < simplex[d].1 { lerp(-0.5) } else { lerp(0.5) };
            let fc = f(&xc);
            if fc < simplex[d].1.min(fr) {
                simplex[d] = (xc, fc);
            } else {
                let best = simplex[0].0.clone();
                for p in simplex.iter_mut().skip(1) {
                    for j in 0..d {
                        p.0[j] = best[j] + 0.5 * (p.0[j] - best[j]);
                    }
                    p.1 = f(&p.0);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    let (x, v) = simplex.swap_remove(0);
    (x, v)
}

/// Composite mass-inertia properties (000, eqs (4), (5)) relative to `A_Σ`, or in SI when a
/// scale is known: `M_s`, `A_Σ`, `C_Σ`, principal equatorial moments `A_C1,2 = A_Σ ± ΔA`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompositeInertia {
    /// Total mass `M_s` (kg), when dimensional.
    pub total_mass: Option<f64>,
    /// Mean equatorial moment `A_Σ` (kg·m²), when dimensional; 1 in relative units.
    pub a_sigma: f64,
    /// Polar moment `C_Σ`.
    pub c_sigma: f64,
    /// Larger principal equatorial moment `A_C1 = A_Σ + ΔA`.
    pub a_c1: f64,
    /// Smaller principal equatorial moment `A_C2 = A_Σ − ΔA`.
    pub a_c2: f64,
    /// Anisotropy `ΔA` in the same units.
    pub delta_a: f64,
    /// Whether the values are in SI (`true`) or relative to `A_Σ`.
    pub si: bool,
}

/// Composite inertia of a model, from the anisotropy in use.
pub fn composite_inertia(model: &crate::spatial::params::SpatialModel) -> CompositeInertia {
    let (scale_a, total_mass, si) = match model.scale {
        Some(s) => (s.total_mass * s.rho_s * s.rho_s, Some(s.total_mass), true),
        None => (1.0, None, false),
    };
    let d = model.anisotropy.used * scale_a;
    CompositeInertia {
        total_mass,
        a_sigma: scale_a,
        c_sigma: model.c_sigma * scale_a,
        a_c1: scale_a + d,
        a_c2: scale_a - d,
        delta_a: d,
        si,
    }
}

/// Ball-coupling matrix `d_A` of the ball equation (000, eq (6); docs/model.md §1) in the principal
/// frame of the composite rotor, where the inertia reads `I_C = E + ΔĀ E_A` with `ΔĀ ≥ 0`.
///
/// With `D = (1/n) Σ exp(2 i α_j)` (angles from the unbalance) and the complex anisotropy
/// `Z = Ā_m0 + Ā_m D`, the principal frame is turned by `ψ = ½ arg Z`, so `D' = D e^{−2iψ}` and
/// `d_A = [[1 − D'_c, −D'_s], [−D'_s, 1 + D'_c]]` (the sum of the balls' tangent projectors,
/// `(2/n) Σ t_j t_jᵀ`). The paper's form `diag(1 − D_A, 1 + D_A)` is the case `D' = D_A ≥ 0`.
pub fn ball_coupling_exact(set: &BallSet, angles: &[f64]) -> [[f64; 2]; 2] {
    let (dc, ds) = if set.n == 2 && set.capacity.is_finite() && set.capacity >= 1.0 {
        (2.0 / (set.capacity * set.capacity) - 1.0, 0.0)
    } else {
        mean_double_angle(angles)
    };
    let (zr, zi) = (set.a_m0 + set.a_m * dc, set.a_m * ds);
    let two_psi = if zr == 0.0 && zi == 0.0 { 0.0 } else { zi.atan2(zr) };
    let (c, s) = (two_psi.cos(), two_psi.sin());
    // D' = D (cos 2ψ − i sin 2ψ)
    let dpc = dc * c + ds * s;
    let dps = ds * c - dc * s;
    [[1.0 - dpc, -dps], [-dps, 1.0 + dpc]]
}

/// The paper's ball-coupling matrix `d_A = diag(1 − D_A, 1 + D_A)` (000, eq (6)).
pub fn ball_coupling_paper(d_a: f64) -> [[f64; 2]; 2] {
    [[1.0 - d_a, 0.0], [0.0, 1.0 + d_a]]
}
