//! The stationary state and its exact stability over speed for **every rotor autobal can run**
//! (issue "Analyse every rotor"): the planar rotor (paper 004, and with the race centred the
//! Jeffcott rotor with balls) and the spatial rotor as the simulation runs it (one or two ball
//! planes, static and couple unbalance, supports that differ by direction, gravity, a tilted
//! principal axis), through the model-agnostic pipeline of [`crate::analysis`].
//!
//! At each speed `Ω` of a grid the model's equations in axes turning with the rotor
//! ([`PlanarField`], [`SpatialField`]) are solved for the stationary state — an equilibrium
//! (Newton with the exact Jacobian by automatic differentiation) when nothing turns against the
//! rotor, else the periodic orbit of the revolution (shooting with the variational equations) —
//! continued from the previous speed and started from the closed-form balanced (or, for the
//! eccentric race of paper 004, semi-balanced) state; its stability is read from the eigenvalues
//! of the Jacobian or the Floquet multipliers of the monodromy matrix, with the family's
//! structural zeros removed ([`crate::analysis::VectorField::structural_zeros`]); the ends of the
//! stable ranges are bisected to `1e-9` relative in `Ω`.
//!
//! For the one-plane rotor of papers 000/003 (isotropic supports, no gravity, point-mass balls)
//! [`crate::spatial::stability::stability_ranges`] computes the same ranges from paper 000's
//! 12-state linear model (eq (6)) and its characteristic polynomial: the fast path, and the
//! cross-check of this general route (tests/rotor_stability.rs: the range ends agree to 1e-9).
//!
//! ```
//! use autobal::planar::PlanarRotor;
//! use autobal::rotor_stability::{stability_over_speed, Rotor};
//! // paper 004's rotor with its race centred: a Jeffcott rotor with two balls
//! let mut p = PlanarRotor::paper();
//! p.s2 = 0.0;
//! let wn = p.natural_frequency();
//! let rotor = Rotor::Planar(p);
//! let speeds: Vec<f64> = (1..=60).map(|i| 0.05 * wn * i as f64).collect();
//! let r = stability_over_speed(&rotor, &speeds).unwrap();
//! // the balanced state is stable only above the critical speed
//! assert!(r.stable_ranges.iter().all(|s| s.from > wn));
//! assert!(!r.stable_ranges.is_empty());
//! ```

use crate::analysis::{speed_scan, Kind, ScanOptions, StableRange, VectorField, Verdict};
use crate::error::{Error, Result};
use crate::planar::field::PlanarField;
use crate::planar::PlanarRotor;
use crate::spatial::dynamics::field::SpatialField;
use crate::spatial::dynamics::SpatialRotor;
use serde::Serialize;

/// A rotor that the stationary analysis can take: either model as the simulation runs it.
#[derive(Debug, Clone, PartialEq)]
pub enum Rotor {
    /// The planar rotor (paper 004; SI: rad/s).
    Planar(PlanarRotor),
    /// The spatial rotor (papers 000/003 and beyond; SI, or the papers' dimensionless units).
    Spatial(SpatialRotor),
}

/// Either model's field at one speed ([`VectorField`] by delegation).
// one field per speed, built and dropped in the scan's loop: the variants' sizes do not matter
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
pub enum Field {
    /// [`PlanarField`].
    Planar(PlanarField),
    /// [`SpatialField`].
    Spatial(SpatialField),
}

macro_rules! delegate {
    ($self:ident, $f:ident => $e:expr) => {
        match $self {
            Field::Planar($f) => $e,
            Field::Spatial($f) => $e,
        }
    };
}

impl VectorField for Field {
    fn dim(&self) -> usize {
        delegate!(self, f => f.dim())
    }
    fn rhs(&self, t: f64, x: &[f64], dx: &mut [f64]) {
        delegate!(self, f => f.rhs(t, x, dx))
    }
    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) {
        delegate!(self, f => f.jacobian(t, x, jac))
    }
    fn period(&self) -> Option<f64> {
        delegate!(self, f => f.period())
    }
    fn structural_zeros(&self, x: &[f64]) -> usize {
        delegate!(self, f => f.structural_zeros(x))
    }
    fn component_name(&self, i: usize) -> String {
        delegate!(self, f => f.component_name(i))
    }
    fn scales(&self) -> Vec<f64> {
        delegate!(self, f => f.scales())
    }
}

impl Rotor {
    /// The model's name in outputs: `"planar"` or `"spatial"`.
    pub fn model_name(&self) -> &'static str {
        match self {
            Rotor::Planar(_) => "planar",
            Rotor::Spatial(_) => "spatial",
        }
    }

    /// The field at speed `omega`; [`Error::NoLinearisation`] for real balls.
    pub fn field(&self, omega: f64) -> Result<Field> {
        Ok(match self {
            Rotor::Planar(p) => Field::Planar(PlanarField::new(p, omega)?),
            Rotor::Spatial(s) => Field::Spatial(SpatialField::new(s, omega)?),
        })
    }

    /// The closed-form starting state at the field's speed: the planar rotor's semi-balanced
    /// state ([`PlanarField::semi_balanced_guess`], the balanced state when the race is centred),
    /// the spatial rotor's balanced state ([`SpatialField::balanced_guess`]).
    pub fn guess(field: &Field) -> Option<Vec<f64>> {
        match field {
            Field::Planar(f) => f.semi_balanced_guess(),
            Field::Spatial(f) => f.balanced_guess(),
        }
    }

    /// `sqrt(k/M)`: the rotor's translational natural frequency on its supports (a scale for
    /// default speed axes).
    pub fn natural_frequency(&self) -> f64 {
        match self {
            Rotor::Planar(p) => p.natural_frequency(),
            Rotor::Spatial(s) => s.natural_frequency(),
        }
    }

    /// Whether the stationary motion is a periodic orbit of the revolution (supports that differ
    /// by direction, gravity across the spin axis) rather than an equilibrium in turning axes.
    pub fn is_periodic(&self) -> bool {
        self.field(1.0).ok().and_then(|f| f.period()).is_some()
    }
}

/// One speed of [`RotorStability`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedPoint {
    /// The speed (rad/s, or Ω for a dimensionless spatial rotor).
    pub omega: f64,
    /// The verdict there; `None` where no stationary state was found.
    pub verdict: Option<Verdict>,
    /// Spectral abscissa `max Re λ` (or the largest Floquet exponent) without the structural
    /// zeros (1/s, or per unit τ).
    pub abscissa: Option<f64>,
    /// `|abscissa|` below this is neutral ([`crate::analysis::NEUTRAL_TOLERANCE`] times the
    /// largest `|λ|`, or [`crate::analysis::FLOQUET_TOLERANCE`]`/T`).
    pub threshold: Option<f64>,
    /// Dimension of the family of stationary states there (structural zeros removed).
    pub family_dimension: usize,
    /// Whirl radius of the stationary state at the (first) balancer plane in turning axes (m, or
    /// in units of `ρ_s`): 0 when balanced (for a periodic orbit: its value at `t = 0`).
    pub amplitude: Option<f64>,
    /// Why there is no state or verdict (a one-line message).
    pub failure: Option<String>,
}

/// The stationary state's stability over speed ([`stability_over_speed`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RotorStability {
    /// `"planar"` or `"spatial"`.
    pub model: &'static str,
    /// Equilibrium (eigenvalues) or periodic orbit (Floquet multipliers).
    pub kind: Kind,
    /// The speed ranges where the stationary state is stable (ends bisected to 1e-9 relative).
    pub stable_ranges: Vec<StableRange>,
    /// Every speed of the grid.
    pub points: Vec<SpeedPoint>,
    /// The largest family dimension met (0: isolated states; `n − 2` for `n ≥ 3` balls in one
    /// plane at balance): that many eigenvalues 0 (multipliers 1) are structural at each point
    /// and left out of the verdict, which therefore holds for every member of the family that
    /// Newton's method reached from the closed-form guess (one member per speed).
    pub family_dimension: usize,
    /// The balls' angles of the member analysed at the first speed where a state was found
    /// (rad, all planes in order): the member any single number refers to.
    pub member_psi: Vec<f64>,
}

/// The stationary state of `rotor` and its stability at each of `speeds` (ascending), with the
/// ends of the stable ranges located (module docs).
pub fn stability_over_speed(rotor: &Rotor, speeds: &[f64]) -> Result<RotorStability> {
    if speeds.is_empty() {
        return Err(Error::invalid("speeds", "no speed to analyse"));
    }
    // the model's own validation first, so its message names the field
    let first = rotor.field(speeds[0])?;
    let kind = if first.period().is_some() { Kind::PeriodicOrbit } else { Kind::Equilibrium };
    // Newton starts from the closed form at every speed (it names the branch: the balanced
    // state, or for a periodic orbit its autonomous neighbour, from which the shooting lands on
    // the orbit of the balanced branch; continuation from the previous orbit switched to orbits
    // with the balls elsewhere at 450-650 rad/s on examples/spatial_two_plane.toml), the
    // shooting's matrix from the previous speed's monodromy (analysis::stationary_near). The
    // shooting integrates at rtol 1e-10 (not the pipeline's default 1e-12): 5.5x faster, and
    // the multipliers near 1 stay good to ~1e-9, inside FLOQUET_TOLERANCE (1e-8)
    let mut opts = ScanOptions::default();
    if kind == Kind::PeriodicOrbit {
        opts.newton.max_iterations = 20;
        opts.newton.rtol = 1e-10;
    }
    let scan = speed_scan(|w| rotor.field(w), |f: &Field, _| Rotor::guess(f), speeds, &opts).map_err(|e| match e {
        crate::analysis::AnalysisError::Model(e) => e,
        e => Error::invalid("speeds", e.to_string()),
    })?;
    let mut member_psi = vec![];
    let mut family_dimension = 0;
    let points = scan
        .points
        .iter()
        .map(|p| {
            let fam = p.state.as_ref().map_or(0, |s| s.family_dimension);
            family_dimension = family_dimension.max(fam);
            let amplitude = p.state.as_ref().and_then(|s| {
                let f = rotor.field(p.omega).ok()?;
                if member_psi.is_empty() {
                    member_psi = ball_angles(&f, &s.x);
                }
                Some(amplitude(&f, &s.x))
            });
            SpeedPoint {
                omega: p.omega,
                verdict: p.stability.as_ref().map(|s| s.verdict),
                abscissa: p.stability.as_ref().map(|s| s.abscissa),
                threshold: p.stability.as_ref().map(|s| s.threshold),
                family_dimension: fam,
                amplitude,
                failure: p.failure.as_ref().map(|f| explain_failure(rotor, f)),
            }
        })
        .collect();
    Ok(RotorStability { model: rotor.model_name(), kind, stable_ranges: scan.stable_ranges, points, family_dimension, member_psi })
}

/// A scan's failure in the user's terms: where the closed form gives no state, say which state
/// does not exist and why.
fn explain_failure(rotor: &Rotor, failure: &str) -> String {
    if !failure.starts_with("no starting point") {
        return failure.to_string();
    }
    match rotor {
        Rotor::Planar(_) => "no semi-balanced state at this speed: the balls cannot supply the unbalance it needs (|B| > n m3 r, planar::stationary)".into(),
        Rotor::Spatial(_) => "no balanced state: the balls' capacity Σ m R of a plane is below the unbalance it must cancel".into(),
    }
}

/// The balls' angles in a reduced state.
fn ball_angles(f: &Field, x: &[f64]) -> Vec<f64> {
    match f {
        Field::Planar(p) => {
            let n = p.rotor().n;
            x[2..2 + n].to_vec()
        }
        Field::Spatial(s) => {
            let nb = s.rotor().balls();
            let m = s.coords();
            x[m - nb..m].to_vec()
        }
    }
}

/// Whirl radius at the first balancer plane in turning axes: `|u|` of the planar rotor's C, the
/// spatial shaft's displacement at the first ball plane (or the first unbalance's plane).
fn amplitude(f: &Field, x: &[f64]) -> f64 {
    match f {
        Field::Planar(_) => x[0].hypot(x[1]),
        Field::Spatial(s) => {
            let r = s.rotor();
            let y = s.full_state(0.0, x);
            let drive = crate::drive::Drive::Speed { omega0: s.omega() };
            let eq = crate::spatial::dynamics::Equations::new(r, &drive);
            let z = r.planes.iter().find(|p| p.n > 0).map(|p| p.z).or_else(|| r.unbalances.first().map(|u| u.z)).unwrap_or(r.z_reference());
            let d = eq.displacement_at(&y, z);
            d[0].hypot(d[1])
        }
    }
}

/// A speed grid of `samples` points from `omega_max / samples` to `omega_max` (the stationary
/// state at `Ω = 0` is degenerate: every ball position is an equilibrium).
pub fn speed_grid(omega_max: f64, samples: usize) -> Result<Vec<f64>> {
    if !(omega_max > 0.0 && omega_max.is_finite()) {
        return Err(Error::invalid("omega_max", format!("must be a positive speed, got {}", crate::error::fmt_num(omega_max))));
    }
    let n = samples.max(2);
    Ok((1..=n).map(|i| omega_max * i as f64 / n as f64).collect())
}
