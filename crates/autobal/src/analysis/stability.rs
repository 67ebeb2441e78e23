//! Linear stability of a stationary state, and its continuation over the rotor speed (module
//! docs of [`crate::analysis`]).

use super::stationary::{stationary_near, NewtonOptions, StationaryState};
use super::{AnalysisError, Result, VectorField};
use crate::control::{Control, Outcome};
use crate::linalg::eigen::complex_solve;
use crate::linalg::eigen_dyn::eigenvalues_or_stop;
use num_complex::Complex64;
use serde::Serialize;

/// Relative tolerance of the equilibrium verdict: `|α| ≤ NEUTRAL_TOLERANCE · ρ` is neutral,
/// `ρ = max |λ|` (module docs of [`crate::analysis`]).
pub const NEUTRAL_TOLERANCE: f64 = 1e-9;

/// Tolerance of the periodic verdict on `max |μ| − 1` (equivalently `|α| ≤ FLOQUET_TOLERANCE / T`
/// on the Floquet exponent; module docs of [`crate::analysis`]).
pub const FLOQUET_TOLERANCE: f64 = 1e-8;

/// A complex eigenvalue (or multiplier) as two numbers, for output.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Eigenvalue {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl From<Complex64> for Eigenvalue {
    fn from(z: Complex64) -> Self {
        Eigenvalue { re: z.re, im: z.im }
    }
}

impl Eigenvalue {
    /// As a complex number.
    pub fn complex(&self) -> Complex64 {
        Complex64::new(self.re, self.im)
    }
}

/// What kind of stationary state was analysed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// An equilibrium of an autonomous field: eigenvalues of the Jacobian.
    Equilibrium,
    /// A periodic orbit: Floquet multipliers, eigenvalues of the monodromy matrix.
    PeriodicOrbit,
}

/// The linear stability verdict (tolerances in the module docs of [`crate::analysis`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Every non-structural exponent has `Re λ < −threshold`: perturbations decay.
    Stable,
    /// Some exponent has `Re λ > threshold`: perturbations along it grow.
    Unstable,
    /// The largest `|Re λ| ≤ threshold`: linearisation alone cannot decide.
    Neutral,
}

impl Verdict {
    /// `"stable"`, `"unstable"`, `"neutral"`: the word a table prints, as the JSON writes it.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Stable => "stable",
            Verdict::Unstable => "unstable",
            Verdict::Neutral => "neutral",
        }
    }
}

/// The stability of one stationary state ([`stability()`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Stability {
    /// Equilibrium or periodic orbit.
    pub kind: Kind,
    /// The orbit's period `T` (s), `None` for an equilibrium.
    pub period: Option<f64>,
    /// The verdict from `abscissa` against `threshold`.
    pub verdict: Verdict,
    /// `α`: the spectral abscissa `max Re λ` of the non-structural eigenvalues, or for an orbit
    /// the largest Floquet exponent `max ln|μ| / T` (1/s).
    pub abscissa: f64,
    /// `|α| ≤ threshold` is neutral (1/s): `NEUTRAL_TOLERANCE · ρ` or `FLOQUET_TOLERANCE / T`.
    pub threshold: f64,
    /// Characteristic rate `ρ = max |λ|` over every exponent, structural ones included (1/s).
    pub rate: f64,
    /// The non-structural eigenvalues `λ` (equilibrium) or multipliers `μ` (orbit).
    pub spectrum: Vec<Eigenvalue>,
    /// The exponents of `spectrum`: `λ` itself, or `ln μ / T` (principal logarithm).
    pub exponents: Vec<Eigenvalue>,
    /// The structural eigenvalues (nearest 0) or multipliers (nearest 1), removed from the
    /// verdict: as many as [`VectorField::structural_zeros`] at the state.
    pub structural: Vec<Eigenvalue>,
    /// Index into `spectrum` of the least stable member (largest real exponent).
    pub least_stable: Option<usize>,
    /// The matrix analysed, row-major: the Jacobian or the monodromy matrix `Φ(T)` (for
    /// [`mode`]).
    #[serde(skip)]
    pub matrix: Vec<f64>,
}

impl Stability {
    /// The least stable exponent, if any.
    pub fn least_stable_exponent(&self) -> Option<Complex64> {
        self.least_stable.map(|i| self.exponents[i].complex())
    }
}

/// The state dimension from which [`stability`]'s eigenvalue solve asks the thread's stop probe
/// ([`crate::control::with_probe`]) as it goes: an `n × n` QR costs ~`10 n³` operations, ~1 ms
/// at 64 and tens of seconds at 1 600 (a linear rotor of 800 DOFs without modal reduction,
/// where Ctrl-C waited ~30 s for the speed's solve before).
pub const STOPPABLE_EIGEN_N: usize = 64;

/// The smallest step, as a fraction of the gap between two neighbouring grid points (speeds
/// of a scan, cells of a map), in which a state found at one is continued to the other where
/// that point's own starts find none (64, six halvings; the bisection of a range end or a map
/// boundary then locates a fold closer than that). Until session 30 a scan never went back,
/// and a map went back one step: the washer under gravity (balancer.z = 0.22) at 200 rpm had
/// its partially balanced orbit on one grid and none on another (tests/map_fill_30.rs).
pub const FILL_SUBSTEPS: f64 = 64.0;

/// The linear stability of the stationary `state` of `f` (module docs of [`crate::analysis`]):
/// eigenvalues of `J(0, x)` for an equilibrium, Floquet multipliers of `Φ(T)` for a periodic
/// orbit; the `state.family_dimension` eigenvalues nearest 0 (multipliers nearest 1) set apart
/// as structural; the verdict from the rest.
pub fn stability<F: VectorField + ?Sized>(f: &F, state: &StationaryState) -> Result<Stability> {
    let n = f.dim();
    if state.x.len() != n {
        return Err(AnalysisError::InvalidInput { field: "state".into(), reason: format!("has {} components, the field {n}", state.x.len()) });
    }
    let k = state.family_dimension.min(n);
    let (kind, matrix, what) = match (state.period, &state.monodromy) {
        (None, _) => {
            let mut j = vec![0.0; n * n];
            f.jacobian(0.0, &state.x, &mut j);
            (Kind::Equilibrium, j, "Jacobian")
        }
        (Some(_), Some(phi)) => (Kind::PeriodicOrbit, phi.clone(), "monodromy matrix"),
        (Some(_), None) => return Err(AnalysisError::InvalidInput { field: "state".into(), reason: "a periodic orbit without its monodromy matrix".into() }),
    };
    if let Some(i) = matrix.iter().position(|v| !v.is_finite()) {
        return Err(AnalysisError::NonFinite { component: f.component_name(i / n), what: what.into() });
    }
    // a large model's solve (a linear rotor of hundreds of DOFs: tens of seconds) asks the
    // thread's stop probe as it goes; a small one (microseconds) is not worth the asking
    let large = n >= STOPPABLE_EIGEN_N;
    let values = match eigenvalues_or_stop(&matrix, n, || large && crate::control::probe().is_some()) {
        Ok(Some(values)) => values,
        Ok(None) => {
            return Err(AnalysisError::Stopped { what: what.into(), reason: crate::control::probe().unwrap_or(crate::control::StopReason::Interrupted) })
        }
        Err(source) => return Err(AnalysisError::Eigenvalues { what: what.into(), source }),
    };
    let period = state.period;
    let exponent = |z: Complex64| match period {
        None => z,
        Some(t) => Complex64::new(z.norm().max(f64::MIN_POSITIVE).ln(), z.arg()) / t,
    };
    let reference = |z: &Complex64| match period {
        None => z.norm(),
        Some(_) => (z - 1.0).norm(),
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| reference(&values[a]).total_cmp(&reference(&values[b])));
    let structural: Vec<Eigenvalue> = order[..k].iter().map(|&i| values[i].into()).collect();
    let mut rest: Vec<usize> = order[k..].to_vec();
    rest.sort_unstable();
    let spectrum: Vec<Eigenvalue> = rest.iter().map(|&i| values[i].into()).collect();
    let exponents: Vec<Eigenvalue> = rest.iter().map(|&i| exponent(values[i]).into()).collect();
    let rate = values.iter().map(|z| exponent(*z).norm()).fold(0.0, f64::max);
    let threshold = match period {
        None => NEUTRAL_TOLERANCE * rate,
        Some(t) => FLOQUET_TOLERANCE / t,
    };
    let least_stable = (0..exponents.len()).max_by(|&a, &b| exponents[a].re.total_cmp(&exponents[b].re));
    let abscissa = least_stable.map_or(f64::NEG_INFINITY, |i| exponents[i].re);
    let verdict = if abscissa < -threshold {
        Verdict::Stable
    } else if abscissa > threshold {
        Verdict::Unstable
    } else {
        Verdict::Neutral
    };
    Ok(Stability { kind, period, verdict, abscissa, threshold, rate, spectrum, exponents, structural, least_stable, matrix })
}

/// The eigenvector of the `n × n` matrix `a` (row-major) for its eigenvalue `value`, by inverse
/// iteration (three solves with `A − (value + δ) I`, `δ = ε‖A‖`), normalised to largest
/// component 1.
pub fn mode(a: &[f64], n: usize, value: Complex64) -> Vec<Complex64> {
    let norm = a.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    let shift = value + Complex64::new(f64::EPSILON * norm, 0.0);
    let m: Vec<Vec<Complex64>> =
        (0..n).map(|i| (0..n).map(|j| Complex64::new(a[i * n + j], 0.0) - if i == j { shift } else { Complex64::new(0.0, 0.0) }).collect()).collect();
    let mut v: Vec<Complex64> = (0..n).map(|i| Complex64::new(1.0 + 0.1 * i as f64, 0.0)).collect();
    for _ in 0..3 {
        v = complex_solve(&m, &v);
        let big = v.iter().copied().max_by(|p, q| p.norm().total_cmp(&q.norm())).unwrap_or(Complex64::new(1.0, 0.0));
        if big.norm() > 0.0 && big.is_finite() {
            v.iter_mut().for_each(|z| *z /= big);
        }
    }
    v
}

/// Options of [`speed_scan`].
#[derive(Debug, Clone, PartialEq)]
pub struct ScanOptions {
    /// Newton's tolerances.
    pub newton: NewtonOptions,
    /// Relative width in `Ω` to which a stability boundary is bisected (default `1e-9`).
    pub boundary_rtol: f64,
    /// Start Newton from the model's closed-form state before the previous speed's solution
    /// (default `true`): the closed form names the branch (balanced, semi-balanced) whose
    /// stability is asked, and continuation could otherwise switch branches at a bifurcation.
    pub prefer_guess: bool,
}

impl Default for ScanOptions {
    fn default() -> Self {
        ScanOptions { newton: NewtonOptions::default(), boundary_rtol: 1e-9, prefer_guess: true }
    }
}

/// One speed of a [`speed_scan`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScanPoint {
    /// The speed `Ω`.
    pub omega: f64,
    /// The stationary state found there (`None` where none was).
    pub state: Option<StationaryState>,
    /// Its stability.
    pub stability: Option<Stability>,
    /// Why there is no state or no verdict (a one-line message).
    pub failure: Option<String>,
}

impl ScanPoint {
    /// Whether the verdict here is [`Verdict::Stable`].
    pub fn is_stable(&self) -> bool {
        self.stability.as_ref().is_some_and(|s| s.verdict == Verdict::Stable)
    }
}

/// A range of speeds where the stationary state is stable.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StableRange {
    /// Lower end.
    pub from: f64,
    /// Upper end.
    pub to: f64,
    /// Whether `from` is a located boundary (else a grid speed: the grid's first, or one next
    /// to a speed where no stationary state was found, or where a stop cut the location short).
    pub from_is_boundary: bool,
    /// Whether `to` is a located boundary (else a grid speed: the grid's last, or one next to a
    /// speed where no stationary state was found, or where a stop cut the location short).
    pub to_is_boundary: bool,
    /// Whether `from` is where the state analysed **switches** to another stationary state
    /// (with the other verdict), not where one state changes stability: the location's last
    /// bracket holds two states far apart (`analysis::stability::switches`), e.g. two partially balanced states
    /// that coexist, the scan's start landing on one below the speed and on the other above.
    /// `from_is_boundary` is then false.
    pub from_is_switch: bool,
    /// Whether `to` is such a switch (`to_is_boundary` then false).
    pub to_is_switch: bool,
}

/// The result of a [`speed_scan`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedScan {
    /// Every speed of the grid, in order.
    pub points: Vec<ScanPoint>,
    /// The stable ranges, ends located to `boundary_rtol`, over the grid and the speeds
    /// `refined` added.
    pub stable_ranges: Vec<StableRange>,
    /// The speeds added between grid speeds of one verdict where α's samples say a zero
    /// crossing may hide there (`refine_speeds`), in the order analysed: ordinary points of
    /// the ranges' location, kept out of `points` (the grid asked for).
    pub refined: Vec<ScanPoint>,
}

/// How near zero the extremum of the parabola through three consecutive samples of `α` may
/// stay, as a fraction of the three samples' spread `max α − min α`, for the speed of that
/// extremum to be analysed (`refine_speeds`).
pub const REFINE_REACH: f64 = 1.0;

/// At most this many rounds of `refine_speeds` (each round's speeds analysed before the next
/// round's parabolas are drawn through them).
pub const REFINE_PASSES: usize = 12;

/// At most this many speeds tried by `refine_speeds` over one scan.
pub const REFINE_MAX_SPEEDS: usize = 32;

/// The speeds where a scan's samples `points` (analysed, ascending or descending) say that `α`
/// may cross zero between two neighbours of one verdict: for each three consecutive points
/// with a finite `α`, the parabola through them; where its vertex `ω*` lies strictly between
/// two neighbours whose verdicts are both stable (both unstable), is a maximum (a minimum) of
/// `α`, and its value there is at least `−REFINE_REACH · spread` (at most `+REFINE_REACH ·
/// spread`), `spread` the three samples' `max α − min α`, the speed `ω*`. A local extremum of
/// `α` toward zero, modelled within the samples' own variation of zero, is the signature of a
/// dip through zero narrower than the grid step (walk 34: `α` = −0.051, −0.114, −2.90 1/s at
/// 286.8, 302.7, 318.6 rad/s, a concave parabola peaking at +0.26 near 294.4, where `α` is
/// positive over 296.65-298.11); a monotone `α`, or an extremum far from zero against its
/// variation, adds nothing. A speed closer than `1 / FILL_SUBSTEPS` of its grid step (`grid`:
/// the grid speeds, ascending) to a sample or to one in `tried` is left out: the search at one
/// extremum converges geometrically onto it (walk 34's two-ball rotor: 20.4, 20.8, 21.0,
/// 21.02, ... at a minimum of α near +1e-4 1/s), and a dip narrower than that is not sought.
fn refine_speeds(points: &[ScanPoint], tried: &[f64], grid: &[f64]) -> Vec<f64> {
    let sample = |p: &ScanPoint| p.stability.as_ref().filter(|s| s.abscissa.is_finite()).map(|s| (p.omega, s.abscissa));
    let definite = |p: &ScanPoint| p.stability.as_ref().map(|s| s.verdict).filter(|v| *v != Verdict::Neutral);
    let mut out: Vec<f64> = vec![];
    for w in points.windows(3) {
        let (Some((x0, y0)), Some((x1, y1)), Some((x2, y2))) = (sample(&w[0]), sample(&w[1]), sample(&w[2])) else { continue };
        // Newton's form p(x) = y0 + d01 (x − x0) + a (x − x0)(x − x1) = y1 + b (x − x1) + a (x − x1)²
        let d01 = (y1 - y0) / (x1 - x0);
        let d12 = (y2 - y1) / (x2 - x1);
        let a = (d12 - d01) / (x2 - x0);
        if !a.is_finite() || a == 0.0 {
            continue;
        }
        let b = d01 + a * (x1 - x0);
        let (xv, yv) = (x1 - b / (2.0 * a), y1 - b * b / (4.0 * a));
        if !(xv > x0.min(x2) && xv < x0.max(x2) && yv.is_finite()) {
            continue;
        }
        let (pa, pb) = if (xv - x1) * (x2 - x1) > 0.0 { (&w[1], &w[2]) } else { (&w[0], &w[1]) };
        let (Some(va), Some(vb)) = (definite(pa), definite(pb)) else { continue };
        if va != vb {
            continue; // the boundary loop locates this interval's end
        }
        let stable = va == Verdict::Stable;
        // an extremum toward zero: a maximum (a < 0) of a stable α, a minimum of an unstable one
        if stable != (a < 0.0) {
            continue;
        }
        let spread = y0.max(y1).max(y2) - y0.min(y1).min(y2);
        let reaches = if stable { yv >= -REFINE_REACH * spread } else { yv <= REFINE_REACH * spread };
        let k = grid.partition_point(|&g| g < xv).clamp(1, grid.len().max(2) - 1);
        let step = grid.get(k).zip(grid.get(k - 1)).map_or((pb.omega - pa.omega).abs(), |(h, l)| h - l);
        let clear = |x: f64| (x - xv).abs() > step / FILL_SUBSTEPS;
        if reaches && clear(pa.omega) && clear(pb.omega) && tried.iter().chain(&out).all(|&t| clear(t)) {
            out.push(xv);
        }
    }
    out
}

/// The stationary state at one speed: Newton from each of `starts` in turn (the first that
/// converges), then its stability; `hint`: a neighbouring orbit's monodromy matrix
/// ([`stationary_near`]). A refusal as beyond single shooting ([`AnalysisError::Unresolvable`]:
/// the flow over a period amplifies a deviation by more than `1/rtol`) is a failure like any
/// other: the shooting refuses before it converges, so the growth is measured off the orbit
/// (at a start, or at an iterate where the matrix is refreshed), and on a nonlinear model a
/// start far off the orbit can grow where the orbit does not; the next start is tried (the
/// shooting's step caps bound what a refused start costs). The message is the last start's.
fn solve_at<F: VectorField>(f: &F, starts: &[Option<&[f64]>], hint: Option<&[f64]>, opts: &NewtonOptions) -> std::result::Result<StationaryState, String> {
    let mut last = String::from("no starting point (no previous solution and no closed-form guess)");
    for start in starts.iter().flatten() {
        match stationary_near(f, start, hint, opts) {
            Ok(state) => return Ok(state),
            Err(e) => last = e.to_string(),
        }
    }
    Err(last)
}

/// A speed tried while locating a range end: its abscissa `α` and state where one was found.
#[derive(Clone)]
struct Trial {
    omega: f64,
    alpha: Option<f64>,
    state: Option<StationaryState>,
}

impl Trial {
    fn of(p: &ScanPoint) -> Self {
        Trial { omega: p.omega, alpha: p.stability.as_ref().map(|s| s.abscissa).filter(|v| v.is_finite()), state: p.state.clone() }
    }

    /// The side of the end it lies on: stable where `α < 0` (so the end is where `α` crosses
    /// zero, not the neutral threshold, which would shift it by the tolerance); no state or no
    /// `α` counts as not stable.
    fn stable(&self) -> bool {
        self.alpha.is_some_and(|v| v < 0.0)
    }
}

/// The start predicted for a periodic orbit at `omega` from two neighbouring trials on its
/// branch: the linear interpolation (or extrapolation) of their states, and their spread
/// `|x_p − x_q|` (the state found is taken only within `‖S⁻¹(x_p − x_q)‖∞ + 1e-6` of the
/// prediction, scaled: one farther off than the neighbours are from each other is not on
/// their branch). `None` for equilibria (the closed form is their exact start) or where a
/// neighbour has no state.
fn predict(p: &Trial, q: &Trial, omega: f64) -> Option<(Vec<f64>, Vec<f64>)> {
    let (xp, xq) = (p.state.as_ref()?, q.state.as_ref()?);
    if xp.period.is_none() || xq.period.is_none() || xp.x.len() != xq.x.len() || p.omega == q.omega {
        return None;
    }
    let w = (omega - p.omega) / (q.omega - p.omega);
    let x: Vec<f64> = xp.x.iter().zip(&xq.x).map(|(a, b)| a + w * (b - a)).collect();
    let spread: Vec<f64> = xp.x.iter().zip(&xq.x).map(|(a, b)| (b - a).abs()).collect();
    x.iter().all(|v| v.is_finite()).then_some((x, spread))
}

/// The end of a stable range between the grid speeds `a` and `b` (verdicts differ), located to
/// `rtol · Ω` on the sign of the abscissa `α` by Brent's method (inverse quadratic
/// interpolation and secant steps on `α`, safeguarded by bisection, every step at least half
/// the tolerance: Brent, *Algorithms for Minimization without Derivatives*, 1973, ch. 4,
/// `zeroin`); by bisection on the side where `α` is missing at an end or a trial finds no
/// state. Where `α` has one sign at both ends (the verdicts differ by the neutral band alone:
/// one end neutral, `α` within the stability test's tolerance of zero on the other end's
/// side), there is no zero to bisect: the end is the neutral speed where the secant puts the
/// zero within the tolerance of it, else none (the range ends at its grid speed). Each trial
/// starts from its two nearest solutions ([`predict`]) and the nearest one's monodromy matrix.
/// Returns the middle of the last bracket (`None` if stopped or not located) and why it
/// stopped.
fn locate_end<E>(a: &ScanPoint, b: &ScanPoint, rtol: f64, control: &Control, evaluate: E) -> (Option<f64>, Option<crate::control::StopReason>, bool)
where
    E: Fn(f64, Option<&StationaryState>, Option<(&[f64], &[f64])>) -> std::result::Result<(StationaryState, Stability), String>,
{
    let tolerance = |x: f64, y: f64| (0.5 * rtol * x.abs().max(y.abs())).max(4.0 * f64::EPSILON * x.abs().max(y.abs()));
    // one trial at `omega`, from its nearest neighbours among `near`
    let trial = |omega: f64, near: &[&Trial]| -> Trial {
        let mut by_distance: Vec<&Trial> = near.iter().copied().filter(|t| t.state.is_some()).collect();
        by_distance.sort_by(|p, q| (p.omega - omega).abs().total_cmp(&(q.omega - omega).abs()));
        let nearest = by_distance.first().and_then(|t| t.state.as_ref());
        let predicted = match by_distance.as_slice() {
            [p, q, ..] => predict(p, q, omega),
            _ => None,
        };
        let r = evaluate(omega, nearest, predicted.as_ref().map(|(x, spread)| (x.as_slice(), spread.as_slice())));
        let r = r.or_else(|_| evaluate(omega, near.iter().rev().find_map(|t| t.state.as_ref()), None));
        match r {
            Ok((state, st)) => Trial { omega, alpha: Some(st.abscissa).filter(|v| v.is_finite()), state: Some(state) },
            Err(_) => Trial { omega, alpha: None, state: None },
        }
    };
    let (ta, tb) = (Trial::of(a), Trial::of(b));
    if let (Some(x), Some(y)) = (ta.alpha, tb.alpha) {
        if (x < 0.0) == (y < 0.0) {
            // the verdicts differ by the neutral band alone: one end is neutral (|α| within the
            // stability test's tolerance) on the same side of zero as the other, so `α` has no
            // zero in the bracket to bisect, and a bisection on its sign walked to the far end
            // (walk 31: a linear rotor's range start "located" at 309.9999998 rad/s, a grid
            // speed minus the tolerance, where α = −3.4e-11 at 300 and −0.0038 at 310). The
            // zero lies beyond the neutral end by about |α|/|dα/dω| (the secant's slope
            // across the bracket): the end is the neutral speed where that is within the
            // tolerance, else not located (`None`: the range ends at its grid speed)
            let slope = (y - x) / (tb.omega - ta.omega);
            let near = if x.abs() <= y.abs() { ta.omega } else { tb.omega };
            let offset = x.abs().min(y.abs()) / slope.abs();
            let end = (offset <= tolerance(ta.omega, tb.omega)).then_some(near);
            return (end, None, false);
        }
    }
    // Brent's variables: `b` the best estimate, `c` the other end of the bracket [b, c], `a`
    // the previous `b`
    let (mut pa, mut pb) = (ta.clone(), tb.clone());
    let mut pc = pa.clone();
    let brent = matches!((pa.alpha, pb.alpha), (Some(x), Some(y)) if x * y < 0.0);
    let (mut d, mut e) = (pb.omega - pa.omega, pb.omega - pa.omega);
    if brent {
        loop {
            let (fb, fc) = (pb.alpha.unwrap_or(f64::NAN), pc.alpha.unwrap_or(f64::NAN));
            if fc.abs() < fb.abs() {
                pa = pb.clone();
                pb = pc.clone();
                pc = pa.clone();
            }
            let (fa, fb, fc) = (pa.alpha.unwrap_or(f64::NAN), pb.alpha.unwrap_or(f64::NAN), pc.alpha.unwrap_or(f64::NAN));
            let tol1 = tolerance(pb.omega, pc.omega);
            let xm = 0.5 * (pc.omega - pb.omega);
            if fb == 0.0 {
                return (Some(pb.omega), None, false); // α vanishes here: the end itself
            }
            if xm.abs() <= tol1 {
                return (Some(0.5 * (pb.omega + pc.omega)), None, switches(&pb, &pc, a, b));
            }
            if e.abs() >= tol1 && fa.abs() > fb.abs() {
                let s = fb / fa;
                let (mut p, mut q);
                if pa.omega == pc.omega {
                    // secant
                    p = 2.0 * xm * s;
                    q = 1.0 - s;
                } else {
                    // inverse quadratic interpolation
                    let (qq, r) = (fa / fc, fb / fc);
                    p = s * (2.0 * xm * qq * (qq - r) - (pb.omega - pa.omega) * (r - 1.0));
                    q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
                }
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                    e = d;
                    d = p / q;
                } else {
                    d = xm;
                    e = d;
                }
            } else {
                d = xm;
                e = d;
            }
            let omega = pb.omega + if d.abs() > tol1 { d } else { tol1.copysign(xm) };
            if let Some(why) = control.should_stop() {
                return (None, Some(why), false);
            }
            let t = trial(omega, &[&pb, &pc, &pa]);
            pa = pb.clone();
            if t.alpha.is_none() {
                // no α here: bisection on the verdict from the bracket [b, c]
                let (lo, hi) = if t.stable() == pb.stable() { (t, pc) } else { (t, pb) };
                return bisect(lo, hi, rtol, control, &trial, (a, b));
            }
            pb = t;
            if (pb.alpha.unwrap_or(0.0) > 0.0) == (pc.alpha.unwrap_or(0.0) > 0.0) {
                pc = pa.clone();
                d = pb.omega - pa.omega;
                e = d;
            }
        }
    }
    bisect(ta, tb, rtol, control, &trial, (a, b))
}

/// Two states at (nearly) one speed that differ by at most `SAME_STATE (1 + max|x|)` (max norm)
/// are one state found twice ([`switches`]): Newton meets its scaled residual with weakly held
/// balls (a partially balanced state) up to ~1e-3 rad from the state, so one state reached
/// from two starts on the two sides of a bracket read as "a switch of state" at a plain change
/// of stability (review 21: a linear Rodrigues rotor at 495.145 and 704.791 rad/s, the spatial
/// one at 495.145); it was `1e-8`, the shooting's accuracy alone. Distinct states measured
/// differ by ≥ 0.25 rad in a ball's angle.
const SAME_STATE: f64 = 1e-2;

/// Whether the last bracket `[p, q]` of a range end's location holds two different stationary
/// states rather than one state on both sides of a change of stability: their states differ
/// (max norm) by more than `10³` times what the grid step's change `|x_a − x_b|` would give
/// over the bracket's width `|ω_p − ω_q|`, plus `SAME_STATE (1 + max|x|)` (one state found
/// twice, [`SAME_STATE`]). One state along a branch changes by
/// `|dx/dω| |ω_p − ω_q|`, ~`|x_a − x_b|` times the bracket over the grid step (10³ allows a
/// branch 10³ times steeper there than on average over the step); a switch keeps a jump of
/// the grid step's size (the balls elsewhere by ~1 rad) however narrow the bracket.
fn switches(p: &Trial, q: &Trial, a: &ScanPoint, b: &ScanPoint) -> bool {
    let (Some(xp), Some(xq), Some(xa), Some(xb)) = (p.state.as_ref(), q.state.as_ref(), a.state.as_ref(), b.state.as_ref()) else { return false };
    states_switch((&xp.x, &xq.x, (p.omega - q.omega).abs()), (&xa.x, &xb.x, (a.omega - b.omega).abs()))
}

/// [`switches`]' test on bare states: the last bracket's states `xp`, `xq` a `width` apart
/// (in the parameter bisected) against the grid step's `xa`, `xb` a `step` apart. One rule for
/// the speed scan's range ends and a map's boundary points ([`crate::rotor_map`]). `false`
/// where the states' lengths differ or the step is 0.
pub(crate) fn states_switch((xp, xq, width): (&[f64], &[f64], f64), (xa, xb, step): (&[f64], &[f64], f64)) -> bool {
    if xp.len() != xq.len() || xa.len() != xb.len() || xp.len() != xa.len() || step == 0.0 {
        return false;
    }
    let diff = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let size = xp.iter().chain(xq).map(|v| v.abs()).fold(0.0, f64::max);
    diff(xp, xq) > 1e3 * (width / step) * diff(xa, xb) + SAME_STATE * (1.0 + size)
}

/// Bisection of the bracket `[p, q]` (sides differ) on the verdict, to `rtol · Ω`.
fn bisect(
    mut p: Trial,
    mut q: Trial,
    rtol: f64,
    control: &Control,
    trial: &dyn Fn(f64, &[&Trial]) -> Trial,
    grid: (&ScanPoint, &ScanPoint),
) -> (Option<f64>, Option<crate::control::StopReason>, bool) {
    loop {
        let width = (q.omega - p.omega).abs();
        let mid = 0.5 * (p.omega + q.omega);
        if width <= rtol * p.omega.abs().max(q.omega.abs()) || mid == p.omega || mid == q.omega {
            return (Some(mid), None, switches(&p, &q, grid.0, grid.1));
        }
        if let Some(why) = control.should_stop() {
            return (None, Some(why), false);
        }
        let t = trial(mid, &[&p, &q]);
        if t.stable() == p.stable() {
            p = Trial { state: t.state.or(p.state), ..t };
        } else {
            q = Trial { state: t.state.or(q.state), ..t };
        }
    }
}

/// The stationary state and its stability along `speeds` (ascending or descending), and the
/// ends of the stable ranges (module docs of [`crate::analysis`]): `field_at(Ω)` builds the
/// model at speed `Ω`; `guess_at(&field, Ω)` gives its closed-form stationary state where one
/// exists. At each speed Newton starts from the previous speed's solution, else from the
/// guess; between two speeds whose verdicts differ (stable or not), the boundary is bracketed
/// to `boundary_rtol · Ω` on the sign of the abscissa `α` (so an end is where `α` crosses
/// zero) by Brent's method on `α` (inverse quadratic interpolation and secant steps,
/// safeguarded by bisection; bisection on the verdict where `α` is missing), a periodic orbit's
/// trial started from the state interpolated between its two nearest solutions (typically 4-8
/// trials where bisection takes ~28). Runs to the end: [`speed_scan_with`] under a [`Control`].
pub fn speed_scan<F, M, G>(field_at: M, guess_at: G, speeds: &[f64], opts: &ScanOptions) -> Result<SpeedScan>
where
    F: VectorField,
    M: Fn(f64) -> crate::Result<F>,
    G: Fn(&F, f64) -> Option<Vec<f64>>,
{
    speed_scan_with(field_at, guess_at, speeds, opts, &Control::none()).map(|o| o.value)
}

/// [`speed_scan`] under `control`, asked once per speed (each grid speed, each trial speed of
/// a boundary's location); the progress observer is told the grid speeds done. Stopped, the
/// outcome holds the grid speeds done until then, with the stable ranges among them (an end
/// whose location the stop cut short is reported as not located: `from_is_boundary` /
/// `to_is_boundary` false, at the grid speed).
pub fn speed_scan_with<F, M, G>(field_at: M, guess_at: G, speeds: &[f64], opts: &ScanOptions, control: &Control) -> Result<Outcome<SpeedScan>>
where
    F: VectorField,
    M: Fn(f64) -> crate::Result<F>,
    G: Fn(&F, f64) -> Option<Vec<f64>>,
{
    speed_scan_with_last(field_at, guess_at, |_: &F, _| None, |_: &F, state, _, _| state, speeds, opts, control)
}

/// [`speed_scan_with`] with a **last resort**: where Newton reaches no state from the guess
/// and the neighbour's state, from `last_at`'s start (asked only then, so every speed where
/// those find a state keeps its answer and its cost); and `settle(field, state, hint, tried)`,
/// the state analysed at a speed given the state Newton reached there from those starts (`hint`
/// the neighbour's monodromy the shooting started from, `tried` the guess where it was shot
/// from first): the rotor's rule that the verdict is
/// the balanced state's wherever Newton reaches one ([`crate::rotor_stability::Rotor::settle_balanced`]). Not
/// asked at a range end's trial speed predicted from its neighbours on one branch.
pub(crate) fn speed_scan_with_last<F, M, G, L, S>(
    field_at: M,
    guess_at: G,
    last_at: L,
    settle: S,
    speeds: &[f64],
    opts: &ScanOptions,
    control: &Control,
) -> Result<Outcome<SpeedScan>>
where
    F: VectorField,
    M: Fn(f64) -> crate::Result<F>,
    G: Fn(&F, f64) -> Option<Vec<f64>>,
    L: Fn(&F, f64) -> Option<Vec<f64>>,
    S: Fn(&F, StationaryState, Option<&[f64]>, Option<&[f64]>) -> StationaryState,
{
    if speeds.is_empty() {
        return Err(AnalysisError::InvalidInput { field: "speeds".into(), reason: "no speed to scan".into() });
    }
    if let Some(w) = speeds.iter().find(|w| !w.is_finite()) {
        return Err(AnalysisError::InvalidInput { field: "speeds".into(), reason: format!("{w} is not a finite speed") });
    }
    // `predicted`: a start from the neighbours of a range end's trial speed, and their spread
    // `|x_p − x_q|` (how far from it the state found may lie: below)
    let evaluate =
        |omega: f64, previous: Option<&StationaryState>, predicted: Option<(&[f64], &[f64])>| -> std::result::Result<(StationaryState, Stability), String> {
            let f = field_at(omega).map_err(|e| e.to_string())?;
            let hint = previous.and_then(|p| p.monodromy.as_deref());
            // a trial speed of a periodic orbit's range end: from the state interpolated between its
            // two nearest solutions on the branch, a far better start than the closed form (which
            // is the autonomous neighbour, not the orbit: 4-6 shooting flows and a steering
            // monodromy against 1-2 flows), taken only if the state found stays within the
            // neighbours' spread of the prediction (else the closed form, as at a grid speed)
            if let Some((x_pred, spread)) = predicted {
                if let Ok(state) = stationary_near(&f, x_pred, hint, &opts.newton) {
                    let sc = f.scales();
                    let scaled = |v: &mut dyn Iterator<Item = f64>| v.zip(&sc).map(|(d, s)| (d / s).abs()).fold(0.0, f64::max);
                    let off = scaled(&mut state.x.iter().zip(x_pred).map(|(a, b)| a - b));
                    if off <= scaled(&mut spread.iter().copied()) + 1e-6 {
                        return stability(&f, &state).map(|st| (state, st)).map_err(|e| e.to_string());
                    }
                }
            }
            let guess = guess_at(&f, omega);
            // the closed-form state first where the model has one: near a bifurcation (a real
            // eigenvalue crossing zero, where another branch of stationary states crosses the
            // balanced one) Newton from a neighbour's solution can land on the other branch, whose
            // stability is the opposite; the closed form pins the branch the user asked about
            let near = previous.map(|p| p.x.as_slice());
            let starts = if opts.prefer_guess { [guess.as_deref(), near] } else { [near, guess.as_deref()] };
            // a periodic orbit's shooting starts from the neighbour's monodromy matrix (no
            // variational integration until the orbit is found)
            let state = solve_at(&f, &starts, hint, &opts.newton).or_else(|e| match last_at(&f, omega) {
                Some(last) => solve_at(&f, &[Some(last.as_slice())], hint, &opts.newton).map_err(|_| e),
                None => Err(e),
            })?;
            // the guess, first, was shot from with `hint` whatever came of it
            let tried = if opts.prefer_guess { guess.as_deref() } else { None };
            let state = settle(&f, state, hint, tried);
            stability(&f, &state).map(|st| (state, st)).map_err(|e| e.to_string())
        };
    // a speed left without a state next to one with a state (`from` at speed `a`), reached from
    // it ([`FILL_SUBSTEPS`]): steps from the whole gap (half of it where the whole was tried)
    // halved where no state is found and doubled again where one is, each speed solved as a
    // grid speed is with the last state carried
    let fill = |a: f64, from: &StationaryState, b: f64, whole: bool| -> Option<(StationaryState, Stability)> {
        let gap = b - a;
        let least = gap.abs() / FILL_SUBSTEPS;
        let (mut t, mut state, mut h) = (a, from.clone(), if whole { gap } else { 0.5 * gap });
        // (a zero gap, a speed given twice: nothing to continue over)
        while gap != 0.0 && h.abs() >= least && control.should_stop().is_none() {
            let reach = (t + h - b) * gap.signum() >= 0.0;
            let next = if reach { b } else { t + h };
            match evaluate(next, Some(&state), None) {
                Ok(found) if reach => return Some(found),
                Ok((x, _)) => {
                    (t, state) = (next, x);
                    h = (2.0 * h).abs().min((b - t).abs()) * gap.signum();
                }
                Err(_) => h *= 0.5,
            }
        }
        None
    };
    let mut points: Vec<ScanPoint> = Vec::with_capacity(speeds.len());
    let mut previous: Option<StationaryState> = None;
    let mut stopped = None;
    for &omega in speeds {
        if let Some(why) = control.should_stop() {
            stopped = Some(why);
            break;
        }
        // under the control's stop probe: a stop ends this speed's integrations early, and a
        // speed that failed then is dropped, not reported as a speed without a state
        let found = crate::control::with_probe(control, || {
            evaluate(omega, previous.as_ref(), None).or_else(|e| match (&previous, points.last()) {
                (Some(from), Some(p)) => fill(p.omega, from, omega, false).ok_or(e),
                _ => Err(e),
            })
        });
        match found {
            Ok((state, st)) => {
                previous = Some(state.clone());
                points.push(ScanPoint { omega, state: Some(state), stability: Some(st), failure: None });
            }
            Err(_) if control.should_stop().is_some() => {
                stopped = control.should_stop();
                break;
            }
            Err(e) => {
                previous = None;
                points.push(ScanPoint { omega, state: None, stability: None, failure: Some(e) });
            }
        }
        control.report(points.len() as u64, speeds.len() as u64);
    }
    // a speed left without a state below one with a state, reached from above (a scan that
    // finds its first state only at a higher speed continues it back), as a map's row does
    if stopped.is_none() {
        for i in (0..points.len().saturating_sub(1)).rev() {
            let Some(from) = points[i + 1].state.clone().filter(|_| points[i].state.is_none()) else { continue };
            let (a, b) = (points[i + 1].omega, points[i].omega);
            match crate::control::with_probe(control, || fill(a, &from, b, true)) {
                Some((state, st)) => points[i] = ScanPoint { omega: b, state: Some(state), stability: Some(st), failure: None },
                None if control.should_stop().is_some() => {
                    stopped = control.should_stop();
                    break;
                }
                None => {}
            }
        }
    }
    // the grid's verdicts alone miss a dip of α through zero narrower than the grid step
    // (walk 34: a stable range's 1.5 rad/s unstable gap, and a 9.3 rad/s stable range between
    // two unstable grid speeds): refine where α's samples say one may hide ([`refine_speeds`]),
    // the speeds added taking part in the ranges below but not in `points` (the grid asked for)
    let mut all = points.clone();
    let mut refined: Vec<ScanPoint> = vec![];
    if stopped.is_none() {
        let ascending = speeds.first() <= speeds.last();
        let mut tried: Vec<f64> = vec![];
        let mut grid: Vec<f64> = speeds.to_vec();
        grid.sort_by(f64::total_cmp);
        'passes: for _ in 0..REFINE_PASSES {
            let candidates = refine_speeds(&all, &tried, &grid);
            if candidates.is_empty() {
                break;
            }
            for omega in candidates {
                if tried.len() >= REFINE_MAX_SPEEDS {
                    break 'passes;
                }
                if let Some(why) = control.should_stop() {
                    stopped = Some(why);
                    break 'passes;
                }
                tried.push(omega);
                // from the nearest analysed speed's state (and, for an orbit, the prediction
                // from the two nearest), as a range end's trial speed is solved
                let mut near: Vec<&ScanPoint> = all.iter().filter(|p| p.state.is_some()).collect();
                near.sort_by(|p, q| (p.omega - omega).abs().total_cmp(&(q.omega - omega).abs()));
                let nearest = near.first().and_then(|p| p.state.as_ref());
                let predicted = match near.as_slice() {
                    [p, q, ..] => predict(&Trial::of(p), &Trial::of(q), omega),
                    _ => None,
                };
                let found = crate::control::with_probe(control, || {
                    evaluate(omega, nearest, predicted.as_ref().map(|(x, s)| (x.as_slice(), s.as_slice()))).or_else(|_| evaluate(omega, nearest, None))
                });
                match found {
                    Ok((state, st)) => {
                        let p = ScanPoint { omega, state: Some(state), stability: Some(st), failure: None };
                        refined.push(p.clone());
                        let at = all.partition_point(|q| if ascending { q.omega < omega } else { q.omega > omega });
                        all.insert(at, p);
                    }
                    // a speed where no state is found adds nothing (it would break a range
                    // where nothing is known), and is not tried again
                    Err(_) if control.should_stop().is_some() => {
                        stopped = control.should_stop();
                        break 'passes;
                    }
                    Err(_) => {}
                }
            }
        }
    }
    // boundaries between neighbours whose verdicts differ, both analysed: next to a speed
    // where no state was found (Newton failed there) the range ends at its last analysed grid
    // speed, not located (`*_is_boundary` false): a located end between a failed and a stable
    // point would claim stability up to a speed about which nothing is known
    let mut boundary = vec![None; all.len()];
    for i in 0..all.len().saturating_sub(1) {
        let (a, b) = (&all[i], &all[i + 1]);
        if a.is_stable() == b.is_stable() || a.stability.is_none() || b.stability.is_none() || stopped.is_some() {
            continue;
        }
        let (mut end, mut why, mut switch) = crate::control::with_probe(control, || locate_end(a, b, opts.boundary_rtol, control, evaluate));
        if switch && why.is_none() {
            // the last bracket holds two states (the grid speeds' starts, or the trials', reach
            // different ones): locate again following only the stable side's state, each trial
            // by Newton from its nearest solution on that side, so the end found is where that
            // state changes stability, or where it is lost (a switch still). E.g. the washer with
            // gravity: the scan reached the mirror orbit below ~31.5 rad/s and the two-group
            // orbit above, and the first location ended 0.25 % off that orbit's own boundary.
            let (kept, other) = if a.is_stable() { (a, b) } else { (b, a) };
            let follow =
                |omega: f64, previous: Option<&StationaryState>, _: Option<(&[f64], &[f64])>| -> std::result::Result<(StationaryState, Stability), String> {
                    let previous = previous.ok_or_else(|| "no state to follow".to_string())?;
                    let f = field_at(omega).map_err(|e| e.to_string())?;
                    let state = stationary_near(&f, &previous.x, previous.monodromy.as_deref(), &opts.newton).map_err(|e| e.to_string())?;
                    stability(&f, &state).map(|st| (state, st)).map_err(|e| e.to_string())
                };
            // the other grid speed's point by the same continuation in 16 steps (a branch can
            // turn fast: the two-plane rotor's partially balanced state below 322 rad/s moves
            // its balls 0.6 rad over one grid step, and one Newton jump lands on the other
            // state), none where it is lost
            let steps = 16;
            let mut walked: std::result::Result<(StationaryState, Stability), String> = Err("no state to follow".into());
            let mut at = kept.state.clone();
            for k in 1..=steps {
                let omega = kept.omega + (other.omega - kept.omega) * k as f64 / steps as f64;
                walked = follow(omega, at.as_ref(), None);
                match &walked {
                    Ok((state, _)) => at = Some(state.clone()),
                    Err(_) => break,
                }
            }
            let followed = match walked {
                Ok((state, st)) => ScanPoint { omega: other.omega, state: Some(state), stability: Some(st), failure: None },
                Err(e) => ScanPoint { omega: other.omega, state: None, stability: None, failure: Some(e) },
            };
            if followed.is_stable() != kept.is_stable() {
                let (p, q) = if a.is_stable() { (kept, &followed) } else { (&followed, kept) };
                (end, why, switch) = crate::control::with_probe(control, || locate_end(p, q, opts.boundary_rtol, control, follow));
            } else {
                // the followed state is stable at the other grid speed too: the range's state
                // goes on, and the verdict there is another state's: the switch is the grid speed
                end = Some(other.omega);
            }
        }
        match why {
            Some(why) => stopped = Some(why),
            None => boundary[i] = end.map(|w| (w, switch)),
        }
    }
    let stable_ranges = assemble_ranges(|i| all[i].omega, |i| all[i].is_stable(), &boundary);
    Ok(Outcome { value: SpeedScan { points, stable_ranges, refined }, stopped })
}

/// The ranges over a grid of `boundary.len()` speeds (`omega(i)`, ascending) where `good(i)`
/// holds: each run of good points from its first to its last, each end at the located end
/// `boundary[i]` between points `i` and `i + 1` where there is one (`(speed, switch)`: a
/// switch of state, `*_is_switch`, else a boundary, `*_is_boundary`), else at the grid speed
/// (neither). One rule for [`speed_scan_with`]'s ranges and a family's
/// (`rotor_stability`'s all and some members stable, whose ends are never switches).
pub(crate) fn assemble_ranges(omega: impl Fn(usize) -> f64, good: impl Fn(usize) -> bool, boundary: &[Option<(f64, bool)>]) -> Vec<StableRange> {
    let n = boundary.len();
    let mut ranges = vec![];
    let mut i = 0;
    while i < n {
        if !good(i) {
            i += 1;
            continue;
        }
        // (speed, located as a boundary, a switch of state)
        let start = if i > 0 { boundary[i - 1].map(|(w, sw)| (w, !sw, sw)) } else { None }.unwrap_or((omega(i), false, false));
        let mut j = i;
        while j + 1 < n && good(j + 1) {
            j += 1;
        }
        let end = boundary[j].map(|(w, sw)| (w, !sw, sw)).unwrap_or((omega(j), false, false));
        let (lo, hi) = if start.0 <= end.0 { (start, end) } else { (end, start) };
        ranges.push(StableRange { from: lo.0, to: hi.0, from_is_boundary: lo.1, to_is_boundary: hi.1, from_is_switch: lo.2, to_is_switch: hi.2 });
        i = j + 1;
    }
    ranges
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x' = (p − 3) x`, `y' = −y`: the equilibrium 0 has `λ = p − 3` and `−1`, stable below
    /// `p = 3`.
    struct Crossing(f64);

    impl VectorField for Crossing {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, x: &[f64], dx: &mut [f64]) {
            dx[0] = (self.0 - 3.0) * x[0];
            dx[1] = -x[1];
        }
        fn jacobian(&self, _t: f64, _x: &[f64], j: &mut [f64]) {
            j.copy_from_slice(&[self.0 - 3.0, 0.0, 0.0, -1.0]);
        }
        fn period(&self) -> Option<f64> {
            None
        }
    }

    /// A stable range ends between two analysed speeds only: with the state not found at the grid
    /// speed 2 (the model fails there, not at the speeds around it), the ranges are [1, 1] and
    /// [2.5, 3], the end 3 located (λ = p − 3 vanishes there, to 1e-9 relative), the ends next to
    /// the failed speed grid speeds, not located. Main at 21dbfc9 located ends between the failed
    /// speed and its stable neighbours (trial speeds there succeed): [1, ~2] and [~2, 3], a
    /// stable range starting and ending where nothing was analysed.
    #[test]
    fn a_failed_speed_breaks_a_stable_range() {
        let grid = [1.0, 2.0, 2.5, 3.5];
        let scan = speed_scan(
            |p| if p == 2.0 { Err(crate::Error::invalid("p", "no state here")) } else { Ok(Crossing(p)) },
            |_, _| Some(vec![1e-3, 1e-3]),
            &grid,
            &ScanOptions::default(),
        )
        .unwrap();
        assert!(scan.points[1].stability.is_none() && !scan.points[1].is_stable());
        let r = &scan.stable_ranges;
        assert_eq!(r.len(), 2, "{r:?}");
        assert_eq!((r[0].from, r[0].to, r[0].from_is_boundary, r[0].to_is_boundary), (1.0, 1.0, false, false), "{r:?}");
        assert_eq!((r[1].from, r[1].from_is_boundary, r[1].to_is_boundary), (2.5, false, true), "{r:?}");
        assert!((r[1].to - 3.0).abs() <= 1e-9 * 3.0, "{r:?}");
    }
}
