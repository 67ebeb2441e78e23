//! The family of stationary states through one member, and its stability member by member
//! (module docs of [`crate::analysis`], "Families").

// Index loops follow the formulas.
#![allow(clippy::needless_range_loop)]

use super::linear::null_space;
use super::stability::{stability, Stability, Verdict};
use super::stationary::{stationary_near, NewtonOptions, StationaryState};
use super::{AnalysisError, Result, VectorField};
use serde::Serialize;

/// Options of [`family`].
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyOptions {
    /// Step along a one-parameter family, in scaled arclength (the state in units of
    /// [`VectorField::scales`]; for ball angles, radians): default `0.05`, so that a family
    /// whose balls turn by `2π` is sampled at ~125 members per ball angle's turn.
    pub step: f64,
    /// Most members sampled (default 2000): a one-parameter family that has not closed by then
    /// is reported as open ([`Family::closed`] false).
    pub max_members: usize,
    /// Members sampled on a family of dimension `k ≥ 2` (default 200).
    pub samples: usize,
    /// Seed of the sampling of a family of dimension `k ≥ 2`.
    pub seed: u64,
    /// The state components that are angles (ball angles): a one-parameter family closes when it
    /// returns to its first member modulo `2π` in these.
    pub angles: Vec<usize>,
    /// Newton's tolerances for each member.
    pub newton: NewtonOptions,
    /// For a one-parameter family: after the continuation, refine the least and the most
    /// stable member sampled by one parabolic step each ([`family`]: the vertex of the parabola
    /// through the abscissae of the extreme member and its two neighbours, corrected onto the
    /// family), so that a coarse step still finds the extremes of the abscissa along the family
    /// to well within the step; for a family of dimension `k ≥ 2`, a compass search from the
    /// least and the most stable member drawn or seeded (steps along the sampling's coefficients halved to
    /// 1/512 of the samples' spacing, at most `max(samples / 2, 4k)` corrections), the members it
    /// reaches added (default `false`).
    pub refine_extremes: bool,
    /// Relabellings of the state that map the family onto itself and fix none of its members
    /// (the cyclic relabellings of three equal balls in a plane: a member fixed by one would
    /// have all three balls at one angle), each a permutation `p` of the state's components,
    /// `y[i] = x[p[i]]`. A one-parameter family's continuation then stops at the first member
    /// within `0.75 step` of the image of the member given under one of them: the arc walked
    /// is a fundamental domain (every member of the family is a relabelling of a member on
    /// it, the same physical state, with the same stability), reported `closed`. Default none.
    pub relabellings: Vec<Vec<usize>>,
    /// For a family of dimension `k ≥ 2`: states at (or near) special members, each corrected
    /// onto the family by the samples' corrector (minimum-norm Newton, from the member given's
    /// monodromy matrix where periodic) and, where it lands on the family (its dimension `k`),
    /// added to the members after the draws: before the verdict and the extremes, and a start
    /// of the compass search ([`FamilyOptions::refine_extremes`]). Why: the extremes of the
    /// abscissa can sit at the family's corners, members where balls coincide, which a uniform
    /// sample rarely comes near (the rotors give their bunched members,
    /// `crate::rotor_stability`'s groupings of each plane's balls in two). Unused for `k ≤ 1`
    /// (the continuation passes within half a step of every member). Default none.
    pub seeds: Vec<Vec<f64>>,
}

impl Default for FamilyOptions {
    fn default() -> Self {
        FamilyOptions {
            step: 0.05,
            max_members: 2000,
            samples: 200,
            seed: 1,
            angles: vec![],
            newton: NewtonOptions::default(),
            refine_extremes: false,
            relabellings: vec![],
            seeds: vec![],
        }
    }
}

/// How the family was sampled.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "method")]
pub enum Sampling {
    /// No family (an isolated state): the one member.
    Isolated,
    /// A one-parameter family followed by continuation along its tangent (pseudo-arclength
    /// predictor, minimum-norm Newton corrector) at a fixed step in scaled arclength `s`,
    /// from `s = 0` (the member given) in both directions until it closes or ends.
    Continuation {
        /// The step in scaled arclength.
        step: f64,
    },
    /// A family of dimension `k ≥ 2`: members from the member given displaced along the
    /// family's tangent space by `π` times coefficients drawn uniformly in `[−1, 1]^k`
    /// (a fixed-seed generator), each corrected onto the family by minimum-norm Newton.
    Random {
        /// The seed.
        seed: u64,
    },
}

/// One member of a [`Family`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FamilyMember {
    /// Where on the family: for a continuation the scaled arclength `s` from the member given
    /// (one number); for a random sample the `k` coefficients along the tangent basis at the
    /// member given (before Newton's correction); `[]` for an isolated state.
    pub parameter: Vec<f64>,
    /// The member's state.
    pub state: StationaryState,
    /// Its stability (the family's `k` structural exponents left out).
    pub stability: Stability,
}

/// A family of stationary states through one member ([`family`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Family {
    /// Its dimension `k` ([`VectorField::structural_zeros`] at the member given).
    pub dimension: usize,
    /// How it was sampled.
    pub sampling: Sampling,
    /// The members, in order of the parameter for a continuation.
    pub members: Vec<FamilyMember>,
    /// For a continuation: whether it returned to the member given (a closed family, sampled
    /// all round) rather than ending (Newton failing, or `max_members`).
    pub closed: bool,
    /// For a continuation: its length in scaled arclength (all round when `closed`).
    pub length: f64,
    /// For a random sample (`k ≥ 2`): the points drawn (`samples − 1`; those Newton corrects
    /// onto the family are members, the others are dropped); 0 otherwise.
    pub drawn: usize,
    /// For a random sample: the members added from [`FamilyOptions::seeds`] (the seeds that
    /// landed on the family); 0 otherwise.
    pub seeded: usize,
    /// The members the search for the extremes added ([`FamilyOptions::refine_extremes`]: the
    /// compass search's, or the continuation's parabolic steps').
    pub searched: usize,
}

/// A range of the family's parameter where its members are stable.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ParameterRange {
    /// First stable member's parameter `s`.
    pub from: f64,
    /// Last stable member's parameter `s`.
    pub to: f64,
}

/// Which members of a family are stable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FamilyVerdict {
    /// Every member sampled is stable.
    AllStable,
    /// Some members sampled are stable, others not.
    SomeStable,
    /// No member sampled is stable.
    NoneStable,
}

impl Family {
    /// How many members are stable.
    pub fn stable_count(&self) -> usize {
        self.members.iter().filter(|m| m.stability.verdict == Verdict::Stable).count()
    }

    /// Which members are stable.
    pub fn verdict(&self) -> FamilyVerdict {
        match self.stable_count() {
            0 => FamilyVerdict::NoneStable,
            c if c == self.members.len() => FamilyVerdict::AllStable,
            _ => FamilyVerdict::SomeStable,
        }
    }

    /// The member with the largest abscissa (the least stable), and the one with the smallest.
    pub fn extremes(&self) -> Option<(&FamilyMember, &FamilyMember)> {
        let by = |a: &&FamilyMember, b: &&FamilyMember| a.stability.abscissa.total_cmp(&b.stability.abscissa);
        Some((self.members.iter().max_by(by)?, self.members.iter().min_by(by)?))
    }

    /// For a continuation, the ranges of the parameter `s` whose members are stable (ends at
    /// the sampling's resolution: the first and last stable member of each run; a run through
    /// the ends of a closed family is split there).
    pub fn stable_ranges(&self) -> Vec<ParameterRange> {
        if !matches!(self.sampling, Sampling::Continuation { .. }) {
            return vec![];
        }
        let mut out = vec![];
        let mut start: Option<f64> = None;
        let mut last = 0.0;
        for m in &self.members {
            let s = m.parameter[0];
            if m.stability.verdict == Verdict::Stable {
                start.get_or_insert(s);
                last = s;
            } else if let Some(a) = start.take() {
                out.push(ParameterRange { from: a, to: last });
            }
        }
        if let Some(a) = start {
            out.push(ParameterRange { from: a, to: last });
        }
        out
    }
}

/// The matrix whose null space is the family's tangent space, scaled: `S⁻¹ J S` at an
/// equilibrium, `S⁻¹ (I − Φ(T)) S` at a periodic orbit.
fn scaled_matrix<F: VectorField + ?Sized>(f: &F, state: &StationaryState, s: &[f64]) -> Result<Vec<f64>> {
    let n = f.dim();
    let mut m = vec![0.0; n * n];
    match (&state.period, &state.monodromy) {
        (None, _) => f.jacobian(0.0, &state.x, &mut m),
        (Some(_), Some(phi)) => m.copy_from_slice(phi),
        (Some(_), None) => return Err(AnalysisError::InvalidInput { field: "state".into(), reason: "a periodic orbit without its monodromy matrix".into() }),
    }
    scaled_from(m, state.period.is_some(), s)
}

/// [`scaled_matrix`] from the matrix [`stability`] analysed at the state (its
/// [`Stability::matrix`]: the Jacobian, or the monodromy matrix where `periodic`), which is
/// the same matrix: no Jacobian evaluated again.
fn scaled_from(mut m: Vec<f64>, periodic: bool, s: &[f64]) -> Result<Vec<f64>> {
    let n = s.len();
    if periodic {
        for ab in 0..n * n {
            m[ab] = if ab / n == ab % n { 1.0 } else { 0.0 } - m[ab];
        }
    }
    for a in 0..n {
        for b in 0..n {
            m[a * n + b] *= s[b] / s[a];
        }
    }
    if m.iter().any(|v| !v.is_finite()) {
        return Err(AnalysisError::NonFinite { component: "the family's tangent".into(), what: "Jacobian".into() });
    }
    Ok(m)
}

/// The scaled distance between two states, angles (`angles`) modulo `2π`.
fn distance(a: &[f64], b: &[f64], s: &[f64], angles: &[usize]) -> f64 {
    (0..a.len())
        .map(|i| {
            let mut d = (a[i] - b[i]) / s[i];
            if angles.contains(&i) {
                let tau = std::f64::consts::TAU / s[i];
                d -= tau * (d / tau).round();
            }
            d * d
        })
        .sum::<f64>()
        .sqrt()
}

/// The family of stationary states of `f` through `member` (a state found by
/// [`super::stationary`]) and the stability of each member sampled (module docs of
/// [`crate::analysis`], "Families"): the member alone when it is isolated; a continuation
/// along a one-parameter family; a random sample of a larger one ([`Sampling`]).
pub fn family<F: VectorField + ?Sized>(f: &F, member: &StationaryState, opts: &FamilyOptions) -> Result<Family> {
    let n = f.dim();
    let k = member.family_dimension;
    let first = FamilyMember { parameter: vec![], stability: stability(f, member)?, state: member.clone() };
    if k == 0 {
        return Ok(Family { dimension: 0, sampling: Sampling::Isolated, members: vec![first], closed: false, length: 0.0, drawn: 0, seeded: 0, searched: 0 });
    }
    if !(opts.step > 0.0 && opts.step.is_finite()) {
        return Err(AnalysisError::InvalidInput { field: "step".into(), reason: "must be positive and finite".into() });
    }
    let s = f.scales();
    // one corrector: minimum-norm Newton from the predicted point (the member of the family
    // nearest it), a periodic orbit's shooting started from the neighbour's monodromy matrix
    let correct = |x: &[f64], near: &StationaryState| -> Option<FamilyMember> {
        let state = stationary_near(f, x, near.monodromy.as_deref(), &opts.newton).ok()?;
        if state.family_dimension != k {
            return None; // left the family (a member where it meets another branch)
        }
        let stability = stability(f, &state).ok()?;
        Some(FamilyMember { parameter: vec![], state, stability })
    };
    if k >= 2 {
        let basis = null_space(&scaled_matrix(f, member, &s)?, n, k);
        let mut seed = opts.seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let mut uniform = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let point =
            |a: &[f64]| -> Vec<f64> { (0..n).map(|i| member.x[i] + std::f64::consts::PI * s[i] * (0..k).map(|j| a[j] * basis[j][i]).sum::<f64>()).collect() };
        let mut members = vec![FamilyMember { parameter: vec![0.0; k], ..first }];
        // each member's offset from the point its parameter names (`x − point(a)`): zero for
        // the members drawn (a member is `point(a)` corrected), the seed's normal part for a
        // seed (its parameter the projection of `x − x_0` on the tangent basis), so that the
        // compass search steps from `point(a + δ d) + offset` and a drawn member's trials are
        // `point(a + δ d)` bit for bit
        let mut offsets: Vec<Option<Vec<f64>>> = vec![None];
        let drawn = opts.samples.max(1) - 1;
        for _ in 0..drawn {
            let a: Vec<f64> = (0..k).map(|_| uniform()).collect();
            if let Some(mut m) = correct(&point(&a), member) {
                m.parameter = a;
                members.push(m);
                offsets.push(None);
            }
        }
        let mut seeded = 0;
        for x in opts.seeds.iter().filter(|x| x.len() == n) {
            let Some(mut m) = correct(x, member) else { continue };
            // the coefficients of `x − x_0` along the (orthonormal) tangent basis, over π
            let d: Vec<f64> = (0..n).map(|i| (m.state.x[i] - member.x[i]) / s[i]).collect();
            let a: Vec<f64> = (0..k).map(|j| (0..n).map(|i| d[i] * basis[j][i]).sum::<f64>() / std::f64::consts::PI).collect();
            let p = point(&a);
            offsets.push(Some((0..n).map(|i| m.state.x[i] - p[i]).collect()));
            m.parameter = a;
            members.push(m);
            seeded += 1;
        }
        let mut searched = 0;
        if opts.refine_extremes {
            let trial = |a: &[f64], offset: Option<&[f64]>, near: &StationaryState| {
                let mut x = point(a);
                if let Some(o) = offset {
                    x.iter_mut().zip(o).for_each(|(x, o)| *x += o);
                }
                correct(&x, near)
            };
            let extra = compass_extremes(&members, &offsets, k, opts.samples, trial);
            searched = extra.len();
            members.extend(extra);
        }
        return Ok(Family { dimension: k, sampling: Sampling::Random { seed: opts.seed }, members, closed: false, length: 0.0, drawn, seeded, searched });
    }
    // k = 1: continuation both ways from the member given, until the family closes (returns
    // to the member given) or ends
    let h = opts.step;
    let tangent_at = |m: &FamilyMember, previous: Option<&[f64]>| -> Result<Vec<f64>> {
        let scaled = if m.stability.matrix.len() == n * n {
            scaled_from(m.stability.matrix.clone(), m.state.period.is_some(), &s)?
        } else {
            scaled_matrix(f, &m.state, &s)?
        };
        let mut t = null_space(&scaled, n, 1).remove(0);
        let sign = match previous {
            Some(p) => p.iter().zip(&t).map(|(a, b)| a * b).sum::<f64>().signum(),
            // the first direction: the largest component positive (a fixed orientation)
            None => t.iter().copied().max_by(|a, b| a.abs().total_cmp(&b.abs())).map_or(1.0, f64::signum),
        };
        if sign < 0.0 {
            t.iter_mut().for_each(|v| *v = -*v);
        }
        Ok(t)
    };
    let t0 = tangent_at(&first, None)?;
    // the member given relabelled ([`FamilyOptions::relabellings`])
    let images: Vec<Vec<f64>> =
        opts.relabellings.iter().filter(|p| p.len() == n && p.iter().all(|&j| j < n)).map(|p| p.iter().map(|&j| member.x[j]).collect()).collect();
    let relabelled = std::cell::Cell::new(false);
    // one direction: the members met, whether it closed, and the arclength walked
    let walk = |dir: f64, budget: usize| -> Result<(Vec<FamilyMember>, bool, f64)> {
        let mut out: Vec<FamilyMember> = vec![];
        let mut current = member.clone();
        let mut t: Vec<f64> = t0.iter().map(|v| dir * v).collect();
        let mut arc = 0.0;
        while out.len() < budget {
            // predictor along the tangent, corrector onto the family; a step whose member lies
            // much farther (or nearer) than the step is halved (down to h / 64)
            let mut step = h;
            let next = loop {
                let x: Vec<f64> = (0..n).map(|i| current.x[i] + step * t[i] * s[i]).collect();
                if let Some(m) = correct(&x, &current) {
                    let d = distance(&m.state.x, &current.x, &s, &[]);
                    if d > 0.25 * step && d < 2.0 * step {
                        break Some((m, d));
                    }
                }
                step *= 0.5;
                if step < h / 64.0 {
                    break None;
                }
            };
            let Some((mut m, d)) = next else { return Ok((out, false, arc)) };
            arc += d;
            m.parameter = vec![dir * arc];
            // closed: back at the member given (modulo 2π in the angles), after leaving it
            if arc > 3.0 * h && distance(&m.state.x, &member.x, &s, &opts.angles) < 0.75 * h {
                return Ok((out, true, arc));
            }
            // or at a relabelling of it: a fundamental domain walked
            if arc > 3.0 * h && images.iter().any(|y| distance(&m.state.x, y, &s, &opts.angles) < 0.75 * h) {
                relabelled.set(true);
                return Ok((out, true, arc));
            }
            t = tangent_at(&m, Some(&t))?;
            current = m.state.clone();
            out.push(m);
        }
        Ok((out, false, arc))
    };
    let budget = opts.max_members.max(2) - 1;
    let (forward, closed, arc) = walk(1.0, budget)?;
    let mut fam = if closed {
        // the whole family, s ∈ [0, length)
        let mut members = vec![FamilyMember { parameter: vec![0.0], ..first }];
        members.extend(forward);
        Family { dimension: 1, sampling: Sampling::Continuation { step: h }, members, closed: true, length: arc, drawn: 0, seeded: 0, searched: 0 }
    } else {
        // open: the other direction too, members ordered by s
        let (mut backward, _, back_arc) = walk(-1.0, budget.saturating_sub(forward.len()))?;
        backward.reverse();
        let mut members = backward;
        members.push(FamilyMember { parameter: vec![0.0], ..first });
        members.extend(forward);
        Family { dimension: 1, sampling: Sampling::Continuation { step: h }, members, closed: false, length: arc + back_arc, drawn: 0, seeded: 0, searched: 0 }
    };
    if opts.refine_extremes {
        // across the ends of an arc closed at a relabelling the neighbours are not the same
        // balls: refined as an open arc
        let closed = fam.closed;
        fam.closed &= !relabelled.get();
        refine_extremes(f, &mut fam, &s, opts);
        fam.closed = closed;
    }
    Ok(fam)
}

/// [`FamilyOptions::refine_extremes`] on a family of dimension `k ≥ 2` (a random sample): from
/// the sampled member of largest abscissa (then of smallest), a compass search over the
/// sampling's coefficients `a` (the point `x + π S Σ a_j b_j` corrected onto the family, as the
/// samples): steps `±δ` along each coefficient, a step taken where it moves the abscissa the
/// wanted way, `δ` halved where none does, from `δ_0 = ½ (2^k / samples)^{1/k}` (half the
/// samples' mean spacing in `[−1, 1]^k`) down to `δ_0 / 512`, at most `max(samples / 2, 4k)`
/// corrections per extreme; from the drawn members only, never from a seed
/// ([`FamilyOptions::seeds`]: a corner, where states Newton accepts beside it are not members). The member reached is added (where it moved): every corrected point
/// is a member, so the extremes can only grow towards the true ones. Why: the extremes of
/// the abscissa can sit at special members a uniform sample rarely comes near (review 22: four
/// balls, `m = 0.04`, paper 000's base case: the member with three balls bunched grows at
/// `Ω = 2.14` where all 200 members drawn decay, so "all members sampled stable" began at
/// 2.138 where that member's own range begins at 2.1438).
fn compass_extremes(
    members: &[FamilyMember],
    offsets: &[Option<Vec<f64>>],
    k: usize,
    samples: usize,
    correct: impl Fn(&[f64], Option<&[f64]>, &StationaryState) -> Option<FamilyMember>,
) -> Vec<FamilyMember> {
    let budget = (samples / 2).max(4 * k);
    let delta0 = 0.5 * (2f64.powi(k as i32) / samples.max(1) as f64).powf(1.0 / k as f64);
    // the directions: every nonzero vector of {−1, 0, 1}^k up to k = 3 (diagonals too: a
    // maximum on a narrow diagonal ridge, balls coming together, stalls a search along the
    // axes), the axes alone above
    let dirs: Vec<Vec<f64>> = if k <= 3 {
        (0..3usize.pow(k as u32))
            .map(|c| (0..k).map(|j| ((c / 3usize.pow(j as u32)) % 3) as f64 - 1.0).collect::<Vec<f64>>())
            .filter(|d| d.iter().any(|&v| v != 0.0))
            .collect()
    } else {
        (0..2 * k)
            .map(|c| {
                (0..k)
                    .map(|j| {
                        if j == c / 2 {
                            if c % 2 == 0 {
                                1.0
                            } else {
                                -1.0
                            }
                        } else {
                            0.0
                        }
                    })
                    .collect()
            })
            .collect()
    };
    let mut extra = vec![];
    for sign in [1.0, -1.0] {
        let by = |m: &&FamilyMember| sign * m.stability.abscissa;
        // from the drawn members only: stepped off a seeded corner (balls coinciding, where
        // the family's dimension changes) Newton accepts states ~1e-7 off the family (the
        // balance's 1e-6), whose abscissa is not a member's (review 24b: +7.5e-7 beside the
        // corner's −3.9e-8, so the every-member range began 7e-7 late)
        let Some((start, offset)) =
            members.iter().zip(offsets).filter(|(m, o)| m.parameter.len() == k && o.is_none()).max_by(|a, b| by(&a.0).total_cmp(&by(&b.0)))
        else {
            continue;
        };
        let mut best = start.clone();
        let (mut delta, mut used, mut moved, mut last) = (delta0, 0, false, 0);
        while delta >= delta0 / 512.0 && used < budget {
            let mut step = None;
            // the direction that last moved it first (a ridge is followed at one correction a
            // step)
            for t in 0..dirs.len() {
                if used >= budget {
                    break;
                }
                used += 1;
                let i = (last + t) % dirs.len();
                let a: Vec<f64> = best.parameter.iter().zip(&dirs[i]).map(|(a, d)| a + delta * d).collect();
                if let Some(mut m) = correct(&a, offset.as_deref(), &best.state) {
                    if sign * m.stability.abscissa > sign * best.stability.abscissa {
                        m.parameter = a;
                        step = Some((m, i));
                        break;
                    }
                }
            }
            match step {
                Some((m, i)) => (best, moved, last) = (m, true, i),
                None => delta *= 0.5,
            }
        }
        if moved {
            extra.push(best);
        }
    }
    extra
}

/// The vertex `σ*` of the parabola through `(σ_j, a_j)`, `σ_0 < σ_1 < σ_2`, where it is an
/// extreme of the kind wanted (`sign` `+1`: a maximum, `−1`: a minimum) strictly inside
/// `(σ_0, σ_2)`: with `d_1`, `d_2` the slopes of the two chords and `c = (d_2 − d_1)/(σ_2 − σ_0)`
/// (half the second derivative), `σ* = (σ_0 + σ_1 − d_1/c)/2`.
fn vertex(sig: [f64; 3], a: [f64; 3], sign: f64) -> Option<f64> {
    let d1 = (a[1] - a[0]) / (sig[1] - sig[0]);
    let d2 = (a[2] - a[1]) / (sig[2] - sig[1]);
    let c = (d2 - d1) / (sig[2] - sig[0]);
    if !(sign * c < 0.0) {
        return None;
    }
    let v = 0.5 * (sig[0] + sig[1] - d1 / c);
    (v.is_finite() && v > sig[0] && v < sig[2]).then_some(v)
}

/// [`FamilyOptions::refine_extremes`]: for the member of largest abscissa (then of smallest)
/// with a neighbour on either side (across the ends of a closed family), the parabola through
/// the three abscissae against the local arclength `σ` (the scaled distances to the neighbours,
/// angles modulo `2π`) gives `σ*`; the three states interpolated quadratically at `σ*` (the
/// neighbours' angles moved by whole turns next to the middle one's) are corrected onto the
/// family by minimum-norm Newton and the member added, at `s + σ*`. The abscissa along the
/// family is smooth where one eigenvalue leads, so the vertex is off the true extreme by
/// `O(h³)` and its abscissa by less; where the lead changes (a kink) the extra member is still
/// a member: the extremes can only grow towards the true ones.
fn refine_extremes<F: VectorField + ?Sized>(f: &F, fam: &mut Family, sc: &[f64], opts: &FamilyOptions) {
    let n = fam.members.len();
    if fam.dimension != 1 || n < 3 {
        return;
    }
    let tau = std::f64::consts::TAU;
    let mut extra: Vec<FamilyMember> = vec![];
    for sign in [1.0, -1.0] {
        let Some(i) = (0..n).max_by(|&a, &b| (sign * fam.members[a].stability.abscissa).total_cmp(&(sign * fam.members[b].stability.abscissa))) else {
            continue;
        };
        let (prev, next) = match (i, fam.closed) {
            (0, true) => (n - 1, 1),
            (i, true) if i == n - 1 => (i - 1, 0),
            (0, false) => continue,
            (i, false) if i == n - 1 => continue,
            (i, _) => (i - 1, i + 1),
        };
        let mid = &fam.members[i];
        let xm = &mid.state.x;
        // a neighbour's state with its angles moved by whole turns next to the middle one's
        let unwrap = |x: &[f64]| -> Vec<f64> {
            let mut y = x.to_vec();
            for &a in &opts.angles {
                y[a] -= tau * ((y[a] - xm[a]) / tau).round();
            }
            y
        };
        let (xp, xn) = (unwrap(&fam.members[prev].state.x), unwrap(&fam.members[next].state.x));
        let sig = [-distance(&xp, xm, sc, &[]), 0.0, distance(xm, &xn, sc, &[])];
        let a = [fam.members[prev].stability.abscissa, mid.stability.abscissa, fam.members[next].stability.abscissa];
        let Some(v) = vertex(sig, a, sign) else { continue };
        // Lagrange's quadratic through the three states at σ*
        let l = [
            (v - sig[1]) * (v - sig[2]) / ((sig[0] - sig[1]) * (sig[0] - sig[2])),
            (v - sig[0]) * (v - sig[2]) / ((sig[1] - sig[0]) * (sig[1] - sig[2])),
            (v - sig[0]) * (v - sig[1]) / ((sig[2] - sig[0]) * (sig[2] - sig[1])),
        ];
        let x: Vec<f64> = (0..xm.len()).map(|j| l[0] * xp[j] + l[1] * xm[j] + l[2] * xn[j]).collect();
        let Ok(state) = stationary_near(f, &x, mid.state.monodromy.as_deref(), &opts.newton) else { continue };
        if state.family_dimension != 1 || distance(&state.x, xm, sc, &opts.angles) > 2.0 * sig[2].max(-sig[0]) {
            continue; // left the family, or landed elsewhere on it
        }
        let Ok(stability) = stability(f, &state) else { continue };
        let mut s = mid.parameter[0] + v;
        if fam.closed {
            s = s.rem_euclid(fam.length);
        }
        extra.push(FamilyMember { parameter: vec![s], state, stability });
    }
    fam.searched = extra.len();
    fam.members.extend(extra);
    fam.members.sort_by(|a, b| a.parameter[0].total_cmp(&b.parameter[0]));
}
