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
    /// anisotropy (which `exact[1]` and the linear model refer to: not in general the family's
    /// least stable member, review 22), exactly on the unbalance's line where the balance
    /// allows every ball there.
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
        let (dc, ds) =
            if set.n == 2 && can_balance && set.capacity.is_finite() { (2.0 / (set.capacity * set.capacity) - 1.0, 0.0) } else { mean_double_angle(&angles) };
        let da_natural = dc.hypot(ds);
        if set.n <= 2 {
            if let Some(d) = d_a {
                if (d - da_natural).abs() > 1e-9 && set.n > 0 {
                    return Err(Error::invalid(
                        "d_a",
                        format!(
                            "with n = {} balls the balancing positions are fixed, so D_A = {}; omit d_a or use that value (d_a = {} given)",
                            set.n,
                            fmt_num(da_natural),
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
    /// Evaluations of the anisotropy the search made: its cost, `O(n)` (tests bound it).
    pub evaluations: u64,
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
    let (b1, b2) = close_with_pair(wx, wy)?;
    let mut v = vec![b1, b2];
    v.extend_from_slice(free);
    Some(v)
}

/// Two unit vectors summing to `(wx, wy)`: angles `φ ± acos(r/2)`; `None` when `r > 2`.
fn close_with_pair(wx: f64, wy: f64) -> Option<(f64, f64)> {
    let r = wx.hypot(wy);
    if r > 2.0 {
        return None;
    }
    let phi = wy.atan2(wx);
    let half = (r / 2.0).min(1.0).acos();
    Some((phi + half, phi - half))
}

/// Up to this many balls the interval is searched over all balancing configurations; above it
/// over the families of [`exact_interval`].
pub const FULL_SEARCH_MAX_BALLS: u32 = 6;

/// A family of balancing configurations: `n1` balls at one angle, `n2` at another, and
/// `singles` balls each at its own angle; the free parameters `x` and how the balance
/// `Σ exp(i α_j) = −n/E` is closed:
/// - `n1 ≥ 1, n2 ≥ 1` (`branch` ±1): `x = (σ, δ, b_3 … b_s)`, singles at `σ ± δ` and `b_k`, the two
///   groups close the balance (a triangle with sides `n1`, `n2`, `|R|`; `branch` picks the mirror);
/// - otherwise: `x = (group angle if n2 ≥ 1, b_3 … b_s)`, singles 1 and 2 close it.
#[derive(Debug, Clone, Copy)]
struct Family {
    n: u32,
    n1: u32,
    n2: u32,
    singles: usize,
    branch: f64,
}

/// At most two groups and six singles: the largest family used (`n ≤ 6` searched in full).
const MAX_PARTS: usize = 8;

impl Family {
    fn dim(&self) -> usize {
        if self.n1 >= 1 {
            self.singles
        } else {
            self.singles - 2 + usize::from(self.n2 >= 1)
        }
    }

    /// `(count, angle)` of each part, or `None` when `x` cannot close the balance.
    fn parts(&self, capacity: f64, x: &[f64]) -> Option<[(f64, f64); MAX_PARTS]> {
        let target = -(self.n as f64) / capacity;
        let mut p = [(0.0, 0.0); MAX_PARTS];
        if self.n1 >= 1 {
            let (sigma, delta) = (x[0], x[1]);
            p[2] = (1.0, sigma + delta);
            p[3] = (1.0, sigma - delta);
            for (k, b) in x[2..].iter().enumerate() {
                p[4 + k] = (1.0, *b);
            }
            let (mut rx, mut ry) = (target, 0.0);
            for q in &p[2..2 + self.singles] {
                rx -= q.1.cos();
                ry -= q.1.sin();
            }
            let (n1, n2, r) = (self.n1 as f64, self.n2 as f64, rx.hypot(ry));
            if r > n1 + n2 || r < (n1 - n2).abs() || r == 0.0 {
                return None;
            }
            let cos1 = ((n1 * n1 + r * r - n2 * n2) / (2.0 * n1 * r)).clamp(-1.0, 1.0);
            let a1 = ry.atan2(rx) + self.branch * cos1.acos();
            let a2 = (ry - n1 * a1.sin()).atan2(rx - n1 * a1.cos());
            p[0] = (n1, a1);
            p[1] = (n2, a2);
        } else {
            let (mut wx, mut wy) = (target, 0.0);
            let mut rest = x;
            if self.n2 >= 1 {
                p[1] = (self.n2 as f64, x[0]);
                wx -= self.n2 as f64 * x[0].cos();
                wy -= self.n2 as f64 * x[0].sin();
                rest = &x[1..];
            }
            for (k, b) in rest.iter().enumerate() {
                p[4 + k] = (1.0, *b);
                wx -= b.cos();
                wy -= b.sin();
            }
            let (b1, b2) = close_with_pair(wx, wy)?;
            p[2] = (1.0, b1);
            p[3] = (1.0, b2);
        }
        Some(p)
    }

    /// The exact anisotropy of the configuration `x`, `½ |Ā_m0 + Ā_m D|`.
    fn anisotropy(&self, set: &BallSet, x: &[f64]) -> Option<f64> {
        let p = self.parts(set.capacity, x)?;
        let (mut c, mut s) = (0.0, 0.0);
        for (count, a) in p.into_iter().filter(|q| q.0 > 0.0) {
            let (sin, cos) = (2.0 * a).sin_cos();
            c += count * cos;
            s += count * sin;
        }
        let n = self.n as f64;
        Some(0.5 * (set.a_m0 + set.a_m * c / n).hypot(set.a_m * s / n))
    }

    /// All `n` ball angles of the configuration `x`.
    fn angles(&self, capacity: f64, x: &[f64]) -> Vec<f64> {
        let Some(p) = self.parts(capacity, x) else { return vec![] };
        p.iter().flat_map(|&(count, a)| std::iter::repeat_n(a, count as usize)).collect()
    }
}

/// The range of the exact anisotropy over the balancing family (`n ≥ 3`, `E ≥ 1`).
///
/// For `n ≤` [`FULL_SEARCH_MAX_BALLS`] a global search over all configurations, parametrised
/// by the angles of balls 3..n (balls 1, 2 close the balance, [`complete_configuration`]).
///
/// For more balls the search runs over small families that contain every extremal
/// configuration, so that the cost is `O(n)` instead of a search in `n − 2` dimensions. Why:
/// the extreme values of `|Ā_m0 + Ā_m D|` are attained where a linear functional
/// `Σ_j cos(2α_j − θ)` is stationary on the balance constraint (two equations), i.e. every
/// ball sits at a critical point of `G(α) = cos(2α − θ) − λ cos α − μ sin α`, a trigonometric
/// polynomial of degree 2 with at most two local maxima and two local minima. The second-order
/// condition on the `(n − 2)`-dimensional tangent space allows at most two balls with the
/// wrong curvature (maximum), four for the minimum of the modulus (whose Hessian adds a rank-2
/// term). So a maximiser has two groups of balls (`n1 + n2 = n − 2`, each at one angle) and two
/// single balls, a minimiser two groups and four singles: 2 and 4 free parameters, for each of
/// the `O(n)` splits `n1 + n2`. Tests check it against the full search for `n = 7 … 9` and
/// against random configurations for `n` up to 1000.
///
/// Each search is a deterministic multistart of Nelder–Mead from quasi-random points.
pub fn exact_interval(set: &BallSet) -> ExactInterval {
    let n = set.n;
    if n <= FULL_SEARCH_MAX_BALLS {
        let all = Family { n, n1: 0, n2: 0, singles: n as usize, branch: 1.0 };
        return search(set, &[all], &[all]);
    }
    exact_interval_families(set)
}

/// The search over the families of extremal configurations alone ([`exact_interval`] uses it
/// for `n >` [`FULL_SEARCH_MAX_BALLS`]); defined for `n ≥ 5`, so that tests can compare it with
/// the full search where both apply.
pub fn exact_interval_families(set: &BallSet) -> ExactInterval {
    let n = set.n;
    assert!(n >= 5, "the families need n ≥ 5 balls");
    let splits = |singles: u32| -> Vec<Family> {
        let rest = n - singles;
        // one group (n1 = 0) closed by two singles, and every split into two groups
        let mut v = vec![Family { n, n1: 0, n2: rest, singles: singles as usize, branch: 1.0 }];
        for n1 in 1..=rest / 2 {
            for branch in [1.0, -1.0] {
                v.push(Family { n, n1, n2: rest - n1, singles: singles as usize, branch });
            }
        }
        v
    };
    search(set, &splits(4), &splits(2))
}

/// Minimum over `min_families`, maximum over `max_families`.
fn search(set: &BallSet, min_families: &[Family], max_families: &[Family]) -> ExactInterval {
    let evaluations = std::cell::Cell::new(0u64);
    let eval = |f: &Family, x: &[f64]| {
        evaluations.set(evaluations.get() + 1);
        f.anisotropy(set, x)
    };
    let mut best_min = (f64::INFINITY, vec![]);
    let mut best_max = (f64::NEG_INFINITY, vec![]);
    for (families, maximise) in [(min_families, false), (max_families, true)] {
        for f in families {
            // the target balance cannot be closed by any member of this split
            if f.n1 >= 1 && (f.n2 - f.n1) as f64 > f.n as f64 / set.capacity + f.singles as f64 {
                continue;
            }
            // zero is the least anisotropy there is (to round-off)
            if !maximise && best_min.0 <= 1e-15 * (set.a_m0 + set.a_m) {
                break;
            }
            let sign = if maximise { -1.0 } else { 1.0 };
            let objective = |x: &[f64]| eval(f, x).map(|v| sign * v).unwrap_or(f64::INFINITY);
            let feasible = |x: &[f64]| f.parts(set.capacity, x).is_some();
            for start in starts(f.dim(), f.n1 == 0 && f.n2 == 0, feasible) {
                let (x, v) = nelder_mead(objective, &start, 0.4, 400);
                let v = sign * v;
                if maximise && v > best_max.0 {
                    best_max = (v, f.angles(set.capacity, &x));
                } else if !maximise && v < best_min.0 {
                    best_min = (v, f.angles(set.capacity, &x));
                }
            }
        }
    }
    // the maximum is the placement with every ball on the unbalance's line where the balance
    // allows one (all `e^{2iα}` equal: `|D| = 1`); Nelder–Mead leaves it ~1e-8 rad off, which
    // tilts `d_A` by as much (off-diagonal ~1e-8) and turns the member's exact eigenvalue 0
    // into ~±1e-9, so the 12-state model read "stable" on slivers of speed (review 22: n = 6,
    // m̄ = 0.075: 6.510878-6.516325); snapped onto the line it is exact
    if let Some(line) = on_the_line(set, &best_max.1) {
        let v = exact_anisotropy_of(set, &line);
        if v >= best_max.0 - 1e-12 * (set.a_m0 + set.a_m) {
            best_max = (v, line);
        }
    }
    ExactInterval { min: best_min.0, max: best_max.0, argmin: best_min.1, argmax: best_max.1, evaluations: evaluations.get() }
}

/// `angles` moved exactly onto the unbalance's line (each to `0` or `π`) where every one lies
/// within `1e-6` rad of it and the placement so moved still cancels the unbalance
/// (`Σ cos α_j = −n/E` to `1e-9 n`: the counts on the two sides fix it); else `None`.
fn on_the_line(set: &BallSet, angles: &[f64]) -> Option<Vec<f64>> {
    use std::f64::consts::{PI, TAU};
    const NEAR: f64 = 1e-6;
    let line: Vec<f64> = angles
        .iter()
        .map(|&a| {
            let r = a.rem_euclid(TAU);
            if r.min(TAU - r) <= NEAR {
                Some(0.0)
            } else if (r - PI).abs() <= NEAR {
                Some(PI)
            } else {
                None
            }
        })
        .collect::<Option<Vec<f64>>>()?;
    let n = set.n as f64;
    let sum: f64 = line.iter().map(|a| a.cos()).sum();
    ((sum + n / set.capacity).abs() <= 1e-9 * n).then_some(line)
}

/// Deterministic starting points in `[0, 2π)^k` that close the balance (`feasible`): for the
/// full search (`structured`) groups of balls at 0 and π, then quasi-random points (Roberts'
/// `R_k` sequence), `6 k` of them (`48 k` for the full search), from at most
/// 50 times as many candidates.
fn starts(k: usize, structured: bool, feasible: impl Fn(&[f64]) -> bool) -> Vec<Vec<f64>> {
    let mut v: Vec<Vec<f64>> = vec![];
    if structured {
        for j in 0..=k {
            let mut s = vec![PI; k];
            for x in s.iter_mut().take(j) {
                *x = 0.0;
            }
            if feasible(&s) {
                v.push(s);
            }
        }
    }
    // Roberts' R_k sequence: x_i = frac(½ + i α_j), α_j = φ_k^−(j+1), φ_k the positive root of
    // x^(k+1) = x + 1 (φ_1 is the golden ratio); fills the k-torus evenly in every dimension
    let mut phi = 2.0f64;
    for _ in 0..60 {
        phi = (1.0 + phi).powf(1.0 / (k as f64 + 1.0));
    }
    let alpha: Vec<f64> = (1..=k).map(|j| phi.powi(-(j as i32))).collect();
    let count = if structured { 48 * k.max(1) } else { 6 * k.max(1) };
    let mut found = 0;
    for i in 0..50 * count {
        let s: Vec<f64> = alpha.iter().map(|a| 2.0 * PI * (0.5 + i as f64 * a).fract()).collect();
        if feasible(&s) {
            v.push(s);
            found += 1;
            if found == count {
                break;
            }
        }
    }
    v
}

/// Most free parameters of a search: `n − 2 = 4` for the full search, 4 for the families.
const MAX_DIM: usize = 4;

/// Minimal Nelder–Mead simplex search (standard coefficients 1, 2, ½, ½) on stack arrays, used
/// only on the few smooth angle variables of [`exact_interval`]; infeasible points return `+∞`.
fn nelder_mead(f: impl Fn(&[f64]) -> f64, x0: &[f64], step: f64, iters: usize) -> (Vec<f64>, f64) {
    let d = x0.len();
    debug_assert!((1..=MAX_DIM).contains(&d));
    type P = ([f64; MAX_DIM], f64);
    let point = |x: &[f64]| -> [f64; MAX_DIM] {
        let mut p = [0.0; MAX_DIM];
        p[..d].copy_from_slice(&x[..d]);
        p
    };
    let mut simplex: [P; MAX_DIM + 1] = [([0.0; MAX_DIM], 0.0); MAX_DIM + 1];
    simplex[0] = (point(x0), f(x0));
    for i in 0..d {
        let mut x = point(x0);
        x[i] += step;
        simplex[i + 1] = (x, f(&x[..d]));
    }
    let sort = |s: &mut [P; MAX_DIM + 1]| s[..=d].sort_by(|a, b| a.1.total_cmp(&b.1));
    for _ in 0..iters {
        sort(&mut simplex);
        if (simplex[d].1 - simplex[0].1).abs() < 1e-15 && simplex[d].1.is_finite() {
            let spread: f64 = simplex[..=d].iter().map(|p| (p.0[0] - simplex[0].0[0]).abs()).sum();
            if spread < 1e-12 {
                break;
            }
        }
        let mut centroid = [0.0; MAX_DIM];
        for p in &simplex[..d] {
            for j in 0..d {
                centroid[j] += p.0[j] / d as f64;
            }
        }
        let worst = simplex[d].0;
        let lerp = |t: f64| -> [f64; MAX_DIM] {
            let mut x = [0.0; MAX_DIM];
            for j in 0..d {
                x[j] = centroid[j] + t * (worst[j] - centroid[j]);
            }
            x
        };
        let xr = lerp(-1.0);
        let fr = f(&xr[..d]);
        if fr < simplex[0].1 {
            let xe = lerp(-2.0);
            let fe = f(&xe[..d]);
            simplex[d] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[d - 1].1 {
            simplex[d] = (xr, fr);
        } else {
            let xc = if fr < simplex[d].1 { lerp(-0.5) } else { lerp(0.5) };
            let fc = f(&xc[..d]);
            if fc < simplex[d].1.min(fr) {
                simplex[d] = (xc, fc);
            } else {
                let best = simplex[0].0;
                for p in simplex[1..=d].iter_mut() {
                    for j in 0..d {
                        p.0[j] = best[j] + 0.5 * (p.0[j] - best[j]);
                    }
                    p.1 = f(&p.0[..d]);
                }
            }
        }
    }
    sort(&mut simplex);
    (simplex[0].0[..d].to_vec(), simplex[0].1)
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

/// Ball-coupling matrix `d_A` of the ball equation (000, eq (6); docs/notes/model.md §1) in the principal
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
