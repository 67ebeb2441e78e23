//! The spatial rotor at a constant speed as an [`analysis::VectorField`](crate::analysis::VectorField):
//! the equations of [`Equations`](super::Equations) with the spin prescribed, `φ = Ω t`,
//! `φ̇ = Ω`, and the coordinates that do not move (`φ`, `φ̇`, and the tilt when locked)
//! removed from the state, so that a stationary motion of the rotor in its turning axes is an
//! equilibrium (isotropic supports, gravity along the axis) or a periodic orbit of the
//! revolution's period `2π/Ω` (gravity across the axis), or of half of it, `π/Ω` (supports that
//! differ by direction, without gravity across the axis: [`SpatialField`]'s `period`).
//!
//! The reduced state is `x = (ξ, η[, δ, θ], ψ_1..N, ξ̇, η̇[, δ̇, θ̇], ψ̇_1..N)` (tilt omitted when
//! locked); its Jacobian is exact, by forward-mode differentiation of the same code that
//! computes the right-hand side ([`Equations::exact_jacobian`](super::Equations::exact_jacobian)).
//!
//! ```
//! use autobal::analysis::VectorField;
//! use autobal::spatial::dynamics::field::SpatialField;
//! use autobal::spatial::dynamics::SpatialRotor;
//! use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, Support};
//! let rotor = SpatialRotor::new(
//!     RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
//!     vec![Support::isotropic(-0.3, 1e5, 20.0), Support::isotropic(0.3, 1e5, 20.0)],
//!     vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.0, z: 0.1 }],
//!     vec![BallPlane::point_masses(0.1, 3, 0.02, 0.1, 0.01)],
//! );
//! let field = SpatialField::new(&rotor, 300.0).unwrap();
//! let x = field.balanced_guess().unwrap(); // balls cancel the unbalance: an equilibrium
//! let mut f = vec![0.0; field.dim()];
//! field.rhs(0.0, &x, &mut f);
//! assert!(f.iter().all(|v| v.abs() < 1e-9));
//! assert_eq!(field.period(), None);
//! assert_eq!(field.structural_zeros(&x), 1); // 3 balls, 2 conditions
//! ```

use super::equations::{real_balls_error, residual_unbalance, Model, Scratch, Spin, PHI, ROTOR_COORDS};
use super::rotor::SpatialRotor;
use crate::analysis::VectorField;
use crate::error::{finite, Result};
use std::cell::RefCell;

/// The spatial rotor at the constant speed `Ω` in its turning axes ([module docs](self)).
#[derive(Debug, Clone)]
pub struct SpatialField {
    rotor: SpatialRotor,
    omega: f64,
    model: Model,
    /// Full-state coordinate of each reduced coordinate (`ξ, η[, δ, θ], ψ_j`).
    coords: Vec<usize>,
    scratch: RefCell<Scratch>,
    /// Full state and its derivative (scratch of the reduced right-hand side).
    full: RefCell<(Vec<f64>, Vec<f64>)>,
}

/// Relative tolerance of [`SpatialField::structural_zeros`]'s tests (rotor at rest on the axis,
/// unbalance cancelled): a stationary state found by Newton's method meets them with room
/// (~1e-12); a state off balance by more than a millionth of its scales is not balanced.
const BALANCE_TOL: f64 = 1e-6;

/// Relative pivot tolerance of the rank of `∂(static, couple)/∂ψ`: entries carry round-off of
/// ~1e-16 of the largest; a pivot below 1e-9 of the largest entry is a configuration within
/// round-off-amplified distance of a degenerate one (balls collinear), counted degenerate.
const RANK_TOL: f64 = 1e-9;

impl SpatialField {
    /// The field of `rotor` at speed `omega` (rad/s; the papers' units for a dimensionless
    /// rotor). Errors: the rotor's own validation ([`SpatialRotor::validate`]), a non-finite
    /// speed (`drive.omega0`), and [`crate::Error::NoLinearisation`] for real balls (contact or
    /// rolling resistance: a friction dead zone or a resting contact has no linearisation).
    pub fn new(rotor: &SpatialRotor, omega: f64) -> Result<Self> {
        rotor.validate()?;
        finite("drive.omega0", omega)?;
        if rotor.planes.iter().any(|p| p.n > 0 && p.physics.is_active()) {
            return Err(real_balls_error());
        }
        let model = Model::new(rotor);
        let nb = rotor.balls();
        let tilt: &[usize] = if rotor.lock_tilt { &[] } else { &[2, 3] };
        let coords: Vec<usize> = [0, 1].iter().chain(tilt).copied().chain(ROTOR_COORDS..ROTOR_COORDS + nb).collect();
        let nc = model.coords();
        Ok(SpatialField {
            rotor: rotor.clone(),
            omega,
            model,
            coords,
            scratch: Scratch::new(nb, false),
            full: RefCell::new((vec![0.0; 2 * nc], vec![0.0; 2 * nc])),
        })
    }

    /// The rotor.
    pub fn rotor(&self) -> &SpatialRotor {
        &self.rotor
    }

    /// The speed `Ω`.
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Number of reduced coordinates `m = 2 (or 4 with the tilt free) + N`; the state has `2m`.
    pub fn coords(&self) -> usize {
        self.coords.len()
    }

    /// The full state `y` of [`Equations`](super::Equations) (under `Drive::Speed { omega0: Ω }`)
    /// at time `t` for the reduced state `x`: `φ = Ω t`, `φ̇ = Ω`, the locked tilt and its rate 0.
    pub fn full_state(&self, t: f64, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; 2 * self.model.coords()];
        self.fill_full(t, x, &mut y);
        y
    }

    fn fill_full(&self, t: f64, x: &[f64], y: &mut [f64]) {
        let nc = self.model.coords();
        let m = self.coords.len();
        y.iter_mut().for_each(|v| *v = 0.0);
        for (i, &c) in self.coords.iter().enumerate() {
            y[c] = x[i];
            y[nc + c] = x[m + i];
        }
        y[PHI] = self.omega * t;
        y[nc + PHI] = self.omega;
    }

    /// The reduced state of a full state `y` (drops `φ`, `φ̇` and the locked tilt).
    pub fn reduced_state(&self, y: &[f64]) -> Vec<f64> {
        let nc = self.model.coords();
        self.coords.iter().map(|&c| y[c]).chain(self.coords.iter().map(|&c| y[nc + c])).collect()
    }

    /// A closed-form starting guess for the balanced state, reduced: rotor at rest on the axis,
    /// all rates zero, and the balls placed so that they cancel the unbalance masses' static
    /// unbalance `s0` (one plane) or static and couple unbalance `s0`, `c0` about C (two planes,
    /// as Rodrigues et al. 2008: plane `k` at `ζ_k` takes the share `b_1 = (ζ_2 s0 − c0)/(ζ_1 − ζ_2)`,
    /// `b_2 = −s0 − b_1`, so that `b_1 + b_2 = −s0`, `ζ_1 b_1 + ζ_2 b_2 = −c0`). Each plane's
    /// balls form the arc of [`arc_angles`]. With one plane and a couple unbalance (or a tilted
    /// principal axis) the guess cancels only the static part and is not itself stationary.
    ///
    /// Two planes at the same axial position `ζ` act as one: their balls together must cancel
    /// `s0` (`B = −s0`, `B = Σ m_j R_j e^{iψ_j}` over both), and then their couple about the
    /// reference is `ζ B = −ζ s0`, which cancels `c0` only where `c0 = ζ s0` (no couple about
    /// that plane); the guess places them as one plane of `n_1 + n_2` balls on the arc of `−s0`
    /// (equal balls: [`arc_angles`] of all, the first `n_1` to the first plane; else each plane
    /// its share of `−s0` in proportion to its capacity where each has two balls or more; a plane
    /// with one ball, whose resultant is `m R` exactly, by [`coincident_split`]),
    /// and leaves any couple about the plane uncancelled, as one plane does.
    ///
    /// `None` when a plane's capacity `n m R` is below its share, with no balls or more than
    /// two planes of balls.
    pub fn balanced_guess(&self) -> Option<Vec<f64>> {
        balancing_ball_angles(&self.rotor).map(|psi| self.with_ball_angles(&psi))
    }

    /// Starts for the balanced **periodic orbit under gravity across the axis** when a plane
    /// carries `n ≥ 3` balls: each such plane's balls in **two bunched groups** of `p` and
    /// `n − p` balls (`n/2 ≤ p ≤ n − 1`) at angles `α`, `β` with
    /// `p m R e^{iα} + (n − p) m R e^{iβ} = t` (the plane's share `t` of the unbalance to cancel,
    /// [`SpatialField::balanced_guess`]'s), both mirror placements (`α` on either side of `t`);
    /// the other planes on their arcs. Empty without gravity across the axis or without such a
    /// plane.
    ///
    /// Why: without gravity the balanced states of `n ≥ 3` balls form a family; gravity across
    /// the axis drags every ball behind the rotor with one mean torque `m g² β/(2Ω(Ω² + β²))`
    /// (`β = h_A/m`, independent of where the ball sits, [`crate::rotor_stability`]'s
    /// `gravity_slip`), and the only mean torque that depends on a ball's angle is the whirl's,
    /// `∝ m R Ω² |r| sin(ψ_j − θ)` (`r e^{iθ}` the race centre's mean offset in turning axes).
    /// Every ball's torque balances only where all `sin(ψ_j − θ)` are equal: the balls sit at
    /// two angles `θ + a` and `θ + π − a`. So the family breaks into isolated orbits with the
    /// balls in two groups, and the arc member of [`SpatialField::balanced_guess`] is no
    /// orbit (its balls creep along the former family: shooting from it stagnates with a
    /// Floquet multiplier within 1e-6..1e-2 of 1). On examples/washing_machine.toml with
    /// gravity along −y at 1400 rpm a time simulation ends with two balls together at
    /// 3.6116 rad and the third at 2.0013 rad: the stable one of the two orbits found from
    /// here (`tests/gravity_family.rs`).
    pub fn split_guesses(&self) -> Vec<Vec<f64>> {
        let Some(shares) = self.gravity_shares() else { return vec![] };
        // each plane's options: its arc, or its groups (both mirror placements of each split)
        let mut options: Vec<Vec<Vec<f64>>> = vec![];
        for PlaneShare { n, mr, t, arc } in shares {
            if n < 3 {
                options.push(vec![arc]);
                continue;
            }
            let mine_options = two_groups(n, mr, t);
            if mine_options.is_empty() {
                // no two groups give the share (`gravity_circulation`): no balanced orbit
                return vec![];
            }
            options.push(mine_options);
        }
        // every combination over the planes (at most 2 planes: a handful)
        let mut out: Vec<Vec<f64>> = vec![vec![]];
        for o in &options {
            out = out.iter().flat_map(|head| o.iter().map(move |tail| [head.as_slice(), tail.as_slice()].concat())).collect();
        }
        out.into_iter().map(|angles| self.with_ball_angles(&angles)).collect()
    }

    /// Why no balanced periodic orbit exists under gravity across the axis, where a plane has
    /// an odd number `n ≥ 3` of balls and its share `t` of the unbalance is below `m R`: the
    /// orbits have the plane's balls in two groups ([`SpatialField::split_guesses`]), whose
    /// resultant `|p − q| m R ≤ |t| ≤ n m R` cannot be that small with `p + q` odd. Orbits
    /// that do not balance remain (two groups whose resultant misses the share; continued from
    /// a balanced neighbour on the washer under gravity at 1400 rpm, 0.10-0.13 kg: unstable), and
    /// a run's balls creep along the placements that balance (the washing-machine example with
    /// 0.05 kg of unbalance at 400 rpm: the angles keep turning over 3000 s). `None` otherwise.
    pub fn gravity_circulation(&self) -> Option<String> {
        self.gravity_shares()?.into_iter().find_map(|PlaneShare { n, mr, t, .. }| {
            let need = t[0].hypot(t[1]);
            (n >= 3 && n % 2 == 1 && need < mr * (1.0 - 1e-12)).then(|| {
                format!(
                    "the balls can balance but cannot come to rest balanced: placements of a plane's {n} balls that cancel its share of the unbalance ({} kg m) exist (their capacity is {} kg m), but under gravity across the axis the balls are stationary only in two groups, and no two groups give a share below one ball's m R = {} kg m; so no balanced periodic orbit exists, and a run's balls creep slowly along the placements that balance (balanced on average, not a stationary state): the stability of that creeping motion is not analysed, so no verdict (`simulate` shows whether a run balances)",
                    crate::error::fmt_num(need),
                    crate::error::fmt_num(n as f64 * mr),
                    crate::error::fmt_num(mr)
                )
            })
        })
    }

    /// Each ball plane's share of the unbalance (the resultant `t` of its balls on the arc of
    /// [`SpatialField::balanced_guess`]), its ball count `n`, one ball's `m R` and those arc
    /// angles, in the state's order: for [`SpatialField::split_guesses`] and
    /// [`SpatialField::gravity_circulation`]. `None` without gravity across the axis, without a
    /// plane of 3 or more balls, or without a balanced placement.
    fn gravity_shares(&self) -> Option<Vec<PlaneShare>> {
        if !self.rotor.gravity_across() || self.rotor.planes.iter().all(|p| p.n < 3) {
            return None;
        }
        let arc = self.balanced_guess()?;
        let m = self.coords.len();
        let planes: Vec<_> = self.rotor.planes.iter().filter(|p| p.n > 0).collect();
        let mut first = m - planes.iter().map(|p| p.n).sum::<usize>();
        Some(
            planes
                .into_iter()
                .map(|p| {
                    let arc = arc[first..first + p.n].to_vec();
                    first += p.n;
                    let mr = p.ball_mass * p.race_radius;
                    let t = arc.iter().fold([0.0, 0.0], |s, a| [s[0] + mr * a.cos(), s[1] + mr * a.sin()]);
                    PlaneShare { n: p.n, mr, t, arc }
                })
                .collect(),
        )
    }

    /// The reduced state with the rotor at rest on the axis and the balls at `psi`.
    fn with_ball_angles(&self, psi: &[f64]) -> Vec<f64> {
        // planes without balls contribute none; the balls keep the planes' order
        let m = self.coords.len();
        let first = m - psi.len();
        let mut x = vec![0.0; 2 * m];
        x[first..m].copy_from_slice(psi);
        x
    }

    /// `Σ (n_g − 1)` over the groups of balls at one axial position (a plane, or two planes
    /// at one `ζ`) whose balls are **bunched**: all within [`RANK_TOL`] rad of one angle (the
    /// rank's own tolerance: their columns of `∂(s, c/L)/∂ψ` then count as one). A balanced
    /// group that is bunched is at its **exactly full capacity** (`|share| = Σ m_j R_j`):
    /// `|Σ m_j R_j e^{iψ_j}| = Σ m_j R_j` holds only with every ball at one angle, so the
    /// balanced state is isolated there (dimension 0) although the rank of the Jacobian falls
    /// to 1, leaving `n_g − 1` zeros that are no family (two balls spread by `±δ` lose
    /// `m R δ²` of their resultant: second order, a genuine zero of the linearisation).
    /// How close to full counts as full: the closed form ([`arc_angles`]) bunches the balls
    /// where the capacity is within `1e-12` (relative) of the share, and just above, at
    /// relative excess `ε`, spreads two balls by `2√(2ε)` (3e-8 rad at `ε = 1e-16`), above
    /// this tolerance: full capacity is exact to round-off, and just above it the state is
    /// isolated for two balls, a family of `n − 2` for more.
    fn bunched_surplus(&self, psi: &[f64]) -> usize {
        let balls = &self.model.balls;
        let mut seen = vec![false; balls.len()];
        let mut surplus = 0;
        for i in 0..balls.len() {
            if seen[i] {
                continue;
            }
            let group: Vec<usize> = (i..balls.len()).filter(|&j| balls[j].zeta == balls[i].zeta).collect();
            group.iter().for_each(|&j| seen[j] = true);
            let bunched = group.iter().all(|&j| {
                let w = (psi[j] - psi[i]).rem_euclid(std::f64::consts::TAU);
                w.min(std::f64::consts::TAU - w) <= RANK_TOL
            });
            if bunched {
                surplus += group.len() - 1;
            }
        }
        surplus
    }

    /// The rank of `∂(s, c/L)/∂ψ` at the ball angles `psi` (all planes): the 4×N matrix of
    /// columns `m_j R_j (−sin ψ_j, cos ψ_j, −ζ_j sin ψ_j/L, ζ_j cos ψ_j/L)` (`s`, `c` the residual
    /// static and couple unbalance, `L` the largest `|ζ_j|` so that the rows are commensurate),
    /// by Gaussian elimination with full pivoting, pivots below [`RANK_TOL`] times the largest
    /// entry counted zero. One plane gives couple rows `ζ_p` times the static rows: rank ≤ 2.
    fn unbalance_rank(&self, psi: &[f64]) -> usize {
        let balls = &self.model.balls;
        let l = balls.iter().map(|b| b.zeta.abs()).fold(0.0, f64::max);
        let l = if l > 0.0 { l } else { 1.0 };
        let n = balls.len();
        let mut a = vec![[0.0; 4]; n];
        for (j, b) in balls.iter().enumerate() {
            let (s, c) = psi[j].sin_cos();
            let mr = b.m * b.r;
            a[j] = [-mr * s, mr * c, -mr * b.zeta / l * s, mr * b.zeta / l * c];
        }
        let big = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        if big == 0.0 {
            return 0;
        }
        // eliminate on the transpose (rows = balls, 4 columns)
        let mut rank = 0;
        let mut used_col = [false; 4];
        let mut used_row = vec![false; n];
        loop {
            let mut best = (0.0, 0, 0);
            for (j, row) in a.iter().enumerate() {
                if used_row[j] {
                    continue;
                }
                for k in 0..4 {
                    if !used_col[k] && row[k].abs() > best.0 {
                        best = (row[k].abs(), j, k);
                    }
                }
            }
            if best.0 <= RANK_TOL * big {
                return rank;
            }
            let (_, pj, pk) = best;
            used_row[pj] = true;
            used_col[pk] = true;
            rank += 1;
            let prow = a[pj];
            for (j, row) in a.iter_mut().enumerate() {
                if used_row[j] {
                    continue;
                }
                let f = row[pk] / prow[pk];
                for k in 0..4 {
                    row[k] -= f * prow[k];
                }
            }
        }
    }
}

/// Two coincident planes' resultants `(B_a, B_b)` with `B_a + B_b = t`, where one plane (or
/// both) has a single ball of `m R` = `ma` or `mb`, its resultant of that magnitude exactly; a
/// plane of `n ≥ 2` balls reaches any magnitude in `[0, n m R]`. One single ball: it points
/// along `t` (or against it where `|t| < m R`), the other plane takes the rest, `|B| = ||t| − m
/// R|`, collinear (a member of the family the other plane's freedom leaves). Two single balls:
/// the triangle of sides `|t|, m_a R_a, m_b R_b`. `None` where no such pair exists (the
/// other plane's capacity short of `||t| − m R|`, or the triangle impossible).
pub fn coincident_split(na: usize, ma: f64, nb: usize, mb: f64, t: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    let d = t[0].hypot(t[1]);
    let unit = if d > 0.0 { [t[0] / d, t[1] / d] } else { [1.0, 0.0] };
    let tol = 1e-12 * (d + ma + mb);
    match (na, nb) {
        (1, 1) => {
            if d < (ma - mb).abs() - tol || d > ma + mb + tol {
                return None;
            }
            // B_a at angle α from t: cos α = (d² + ma² − mb²)/(2 d ma)
            let cos = if d > 0.0 { ((d * d + ma * ma - mb * mb) / (2.0 * d * ma)).clamp(-1.0, 1.0) } else { 1.0 };
            let sin = (1.0 - cos * cos).sqrt();
            let ba = [ma * (unit[0] * cos - unit[1] * sin), ma * (unit[0] * sin + unit[1] * cos)];
            let bb = [t[0] - ba[0], t[1] - ba[1]];
            // B_b's magnitude is mb to rounding: set it exactly (arc_angles of one ball wants it)
            let nbb = bb[0].hypot(bb[1]);
            let bb = if nbb > 0.0 { [bb[0] * mb / nbb, bb[1] * mb / nbb] } else { [-ba[0] * mb / ma, -ba[1] * mb / ma] };
            Some((ba, bb))
        }
        (1, n) | (n, 1) if n != 1 => {
            let single_a = na == 1;
            let (m1, cap) = if single_a { (ma, nb as f64 * mb) } else { (mb, na as f64 * ma) };
            let single = [unit[0] * m1, unit[1] * m1];
            let rest = [t[0] - single[0], t[1] - single[1]];
            if rest[0].hypot(rest[1]) > cap * (1.0 + 1e-12) {
                return None;
            }
            Some(if single_a { (single, rest) } else { (rest, single) })
        }
        _ => None,
    }
}

/// One ball plane's share of the unbalance ([`SpatialField::gravity_shares`]).
struct PlaneShare {
    /// Balls in the plane.
    n: usize,
    /// One ball's first moment `m R` (kg m).
    mr: f64,
    /// The share `Σ m R e^{iψ}` of the arc (kg m).
    t: [f64; 2],
    /// The arc's ball angles (rad).
    arc: Vec<f64>,
}

/// Ball angles (from the body x axis) of `n` equal balls of first moment `mr = m R` each whose
/// sum `Σ m R (cos ψ_j, sin ψ_j)` is `target`: an arc of equally spaced balls centred on the
/// target's direction `β`, `ψ_j = β + a (j − (n − 1)/2)`, its spacing `a ∈ [0, 2π/n]` solving
/// `Σ_j cos(a (j − (n−1)/2)) = sin(n a/2)/sin(a/2) = |target|/(m R)` (decreasing in `a` there:
/// bisection to round-off). Two balls sit at `β ± a/2`, `cos(a/2) = |target|/(2 m R)`; for
/// `n ≥ 3` this is one member of the `(n − 2)`-dimensional family of balancing positions; a
/// zero target gives the balls evenly spread round the race.
///
/// `None` when the capacity `n m R` is below `|target|` (beyond a relative 1e-12), or for one
/// ball unless `|target| = m R` to that tolerance.
pub fn arc_angles(n: usize, mr: f64, target: [f64; 2]) -> Option<Vec<f64>> {
    let need = target[0].hypot(target[1]);
    if n == 0 {
        return (need == 0.0).then(Vec::new);
    }
    if !(mr > 0.0) || !need.is_finite() {
        return None;
    }
    let ratio = need / mr;
    let nf = n as f64;
    if ratio > nf * (1.0 + 1e-12) {
        return None;
    }
    let dir = target[1].atan2(target[0]);
    if n == 1 {
        return ((ratio - 1.0).abs() <= 1e-12).then(|| vec![dir]);
    }
    let centre = 0.5 * (nf - 1.0);
    let sum = |a: f64| (0..n).map(|j| (a * (j as f64 - centre)).cos()).sum::<f64>();
    let (mut lo, mut hi) = (0.0, 2.0 * std::f64::consts::PI / nf);
    if ratio >= nf {
        hi = 0.0;
    }
    while hi - lo > 1e-16 * hi.max(1.0) {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if sum(mid) > ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let a = 0.5 * (lo + hi);
    Some((0..n).map(|j| dir + a * (j as f64 - centre)).collect())
}

impl VectorField for SpatialField {
    fn dim(&self) -> usize {
        2 * self.coords.len()
    }

    fn rhs(&self, t: f64, x: &[f64], dx: &mut [f64]) {
        let mut full = self.full.borrow_mut();
        let (y, dy) = &mut *full;
        self.fill_full(t, x, y);
        self.model.rhs(Spin::Prescribed { rate: self.omega, acc: 0.0 }, y, dy, &[], &self.scratch);
        let nc = self.model.coords();
        let m = self.coords.len();
        for (i, &c) in self.coords.iter().enumerate() {
            dx[i] = dy[c];
            dx[m + i] = dy[nc + c];
        }
    }

    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) {
        let nc = self.model.coords();
        let m = self.coords.len();
        let y = self.full_state(t, x);
        let mut dy = vec![0.0; 2 * nc];
        let spin = Spin::Prescribed { rate: self.omega, acc: 0.0 };
        self.model.rhs(spin, &y, &mut dy, &[], &self.scratch);
        // full-state index of each reduced component
        let full: Vec<usize> = self.coords.iter().copied().chain(self.coords.iter().map(|&c| nc + c)).collect();
        let mut cols = vec![0.0; 2 * nc * 2 * m];
        self.model.jacobian_columns(spin, &y, &dy, &full, &mut cols);
        for (i, &r) in full.iter().enumerate() {
            jac[i * 2 * m..(i + 1) * 2 * m].copy_from_slice(&cols[r * 2 * m..(r + 1) * 2 * m]);
        }
    }

    /// `Some(2π/|Ω|)` when gravity has a component across the spin axis (it turns at `−Ω` in
    /// the rotor's axes: `g(t + π/Ω) = −g(t)`, one revolution to repeat); `Some(π/|Ω|)` when
    /// only a support's stiffness or damping differs between x and y: the support force in
    /// turning axes is `R(φ)ᵀ K R(φ) r` with `R(φ + π) = −R(φ)`, so the equations repeat after
    /// half a revolution (the orbit's multipliers over a revolution are the squares of these);
    /// else `None` (also at `Ω = 0`, where nothing turns).
    fn period(&self) -> Option<f64> {
        let anisotropic = self.rotor.supports.iter().any(|s| s.stiffness[0] != s.stiffness[1] || s.damping[0] != s.damping[1]);
        let across = self.rotor.gravity_across();
        if self.omega == 0.0 {
            return None;
        }
        if across {
            Some(2.0 * std::f64::consts::PI / self.omega.abs())
        } else {
            anisotropic.then(|| std::f64::consts::PI / self.omega.abs())
        }
    }

    /// Typical magnitudes for Newton's scaled residual and the shooting's absolute tolerances:
    /// the length scale ([`SpatialRotor::length_scale`]) for the translations, 1 rad for the
    /// tilts and ball angles, and those times `max(|Ω|, ω0)` for the rates.
    fn scales(&self) -> Vec<f64> {
        let m = self.coords.len();
        let l = self.rotor.length_scale();
        let w = self.omega.abs().max(self.rotor.natural_frequency());
        (0..2 * m).map(|i| if i % m < 2 { l } else { 1.0 } * if i >= m { w } else { 1.0 }).collect()
    }

    /// At a balanced state — rotor at rest on the axis (displacements within 1e-6 of the length
    /// scale, tilts within 1e-6 rad, rates within 1e-6 of those times `max(|Ω|, ω0)`) and the
    /// residual static and couple unbalance within 1e-6 of `Σ m R + |s0|` (times the largest
    /// `|ζ|` for the couple) — the stationary states form a family of dimension
    /// `N − rank ∂(s, c)/∂ψ` (balls of all planes; `n − 2` for `n ≥ 3` balls in one plane):
    /// every ball is in equilibrium wherever it sits, and the rotor only needs the 2 (one plane)
    /// or 4 conditions `s = 0`, `c = 0`. Elsewhere 0.
    fn structural_zeros(&self, x: &[f64]) -> usize {
        let nb = self.model.balls.len();
        if nb == 0 {
            return 0;
        }
        let m = self.coords.len();
        let nr = m - nb;
        let l = self.rotor.length_scale();
        let rate = self.omega.abs().max(self.rotor.natural_frequency());
        let at_rest = (0..nr).all(|i| {
            let s = if i < 2 { l } else { 1.0 };
            x[i].abs() <= BALANCE_TOL * s && x[m + i].abs() <= BALANCE_TOL * s * rate
        }) && (nr..m).all(|i| x[m + i].abs() <= BALANCE_TOL * rate);
        if !at_rest {
            return 0;
        }
        let y = self.full_state(0.0, x);
        let (st, cp) = residual_unbalance(&self.rotor, &self.model, &y);
        let s0 = self.rotor.static_unbalance();
        let scale = self.model.balls.iter().map(|b| b.m * b.r).sum::<f64>() + s0[0].hypot(s0[1]);
        let zl = self.model.balls.iter().map(|b| b.zeta.abs()).fold(l, f64::max);
        if st[0].hypot(st[1]) > BALANCE_TOL * scale || cp[0].hypot(cp[1]) > BALANCE_TOL * scale * zl {
            return 0;
        }
        (nb - self.unbalance_rank(&x[nr..m])).saturating_sub(self.bunched_surplus(&x[nr..m]))
    }

    fn component_name(&self, i: usize) -> String {
        let m = self.coords.len();
        let (rate, k) = if i >= m { (true, i - m) } else { (false, i) };
        let base = match self.coords.get(k) {
            Some(0) => "ξ (x of C in rotor axes)".to_string(),
            Some(1) => "η (y of C in rotor axes)".to_string(),
            Some(2) => "δ (tilt about the rotor x axis)".to_string(),
            Some(3) => "θ (tilt about the rotor y axis)".to_string(),
            Some(&c) => format!("ψ_{} (ball {} angle)", c - ROTOR_COORDS + 1, c - ROTOR_COORDS + 1),
            None => format!("x[{i}]"),
        };
        if rate {
            format!("rate of {base}")
        } else {
            base
        }
    }
}

/// The placements of `n` alike balls (each `m R = mr`) in **two groups**, `p` balls at `α` and
/// `n − p` at `β` (`⌈n/2⌉ ≤ p < n`), whose resultant `mr (p e^{iα} + (n − p) e^{iβ})` is `t`
/// (the triangle of sides `p mr`, `(n − p) mr`, `|t|`): both mirror placements of an uneven
/// split, one of an even split (its mirror swaps the groups); each placement as its `n` ball
/// angles. Empty where no split can give `t` (or `t = 0`). The starts of
/// [`SpatialField::split_guesses`] (gravity) and [`crate::planar::field::PlanarField::split_guesses`]
/// (supports that differ by direction).
pub(crate) fn two_groups(n: usize, mr: f64, t: [f64; 2]) -> Vec<Vec<f64>> {
    let need = t[0].hypot(t[1]);
    let mut out = vec![];
    for big in n.div_ceil(2)..n {
        let (a, b) = (big as f64 * mr, (n - big) as f64 * mr);
        if need < (a - b).abs() || need > a + b || need == 0.0 {
            continue;
        }
        // an even split's mirror is the same placement with the groups swapped
        let sides: &[f64] = if 2 * big == n { &[1.0] } else { &[1.0, -1.0] };
        for &side in sides {
            let (alpha, beta) = triangle_angles(a, t, need, b, side);
            out.push((0..n).map(|j| if j < big { alpha } else { beta }).collect());
        }
    }
    out
}

/// The angles `(α, β)` of two groups of resultants `a` and `b` with `a e^{iα} + b e^{iβ} = t`
/// (`need = |t|`; the triangle of sides `a`, `b`, `|t|`, whose existence the caller checks):
/// `α = arg t + side · acos((a² + |t|² − b²)/(2 a |t|))`, `side = ±1` the two mirror solutions,
/// `β = arg(t − a e^{iα})`. One home of [`two_groups`]' and the family's bunched members'
/// triangle (`crate::rotor_stability::bunched_members`).
pub(crate) fn triangle_angles(a: f64, t: [f64; 2], need: f64, b: f64, side: f64) -> (f64, f64) {
    let off = ((a * a + need * need - b * b) / (2.0 * a * need)).clamp(-1.0, 1.0).acos();
    let alpha = t[1].atan2(t[0]) + side * off;
    (alpha, (t[1] - a * alpha.sin()).atan2(t[0] - a * alpha.cos()))
}

/// The balls' angles (rad, the planes with balls in order) of [`SpatialField::balanced_guess`]'s
/// closed-form placement, from the rotor alone (no speed, no field: a run with real balls has
/// no field but the same question): each plane's balls on the arc of its share `b_p` of the
/// unbalance (Rodrigues et al. 2008, eq (21): `b_1 + b_2 = −s0`, `ζ_1 b_1 + ζ_2 b_2 = −c0`);
/// `None` where a plane's capacity `n m R` is below its share, with no balls or more than two
/// planes of balls. One plane cancels the static part only.
pub(crate) fn balancing_ball_angles(rotor: &SpatialRotor) -> Option<Vec<f64>> {
    let planes: Vec<_> = rotor.planes.iter().filter(|p| p.n > 0).collect();
    let s0 = rotor.static_unbalance();
    let targets: Vec<[f64; 2]> = match planes.len() {
        1 => vec![[-s0[0], -s0[1]]],
        2 => {
            let zr = rotor.z_reference();
            let (z1, z2) = (planes[0].z - zr, planes[1].z - zr);
            if z1 == z2 {
                let (a, b) = (planes[0], planes[1]);
                let (ma, mb) = (a.ball_mass * a.race_radius, b.ball_mass * b.race_radius);
                let t = [-s0[0], -s0[1]];
                let psi = if ma == mb {
                    arc_angles(a.n + b.n, ma, t)?
                } else if a.n == 1 || b.n == 1 {
                    let (ta, tb) = coincident_split(a.n, ma, b.n, mb, t)?;
                    let mut psi = arc_angles(a.n, ma, ta)?;
                    psi.extend(arc_angles(b.n, mb, tb)?);
                    psi
                } else {
                    let (ca, cb) = (a.n as f64 * ma, b.n as f64 * mb);
                    let share = |c: f64| [t[0] * c / (ca + cb), t[1] * c / (ca + cb)];
                    let mut psi = arc_angles(a.n, ma, share(ca))?;
                    psi.extend(arc_angles(b.n, mb, share(cb))?);
                    psi
                };
                return Some(psi);
            }
            let c0 = rotor.couple_unbalance();
            let b1 = [(z2 * s0[0] - c0[0]) / (z1 - z2), (z2 * s0[1] - c0[1]) / (z1 - z2)];
            vec![b1, [-s0[0] - b1[0], -s0[1] - b1[1]]]
        }
        _ => return None,
    };
    let mut psi = vec![];
    for (p, t) in planes.iter().zip(targets) {
        psi.extend(arc_angles(p.n, p.ball_mass * p.race_radius, t)?);
    }
    Some(psi)
}
