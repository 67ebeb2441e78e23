//! The stationary state and its exact stability over speed for **every rotor autobal can run**
//! (issue "Analyse every rotor"): the planar rotor (paper 004, and with the race centred the
//! Jeffcott rotor with balls) and the spatial rotor as the simulation runs it (one or two ball
//! planes, static and couple unbalance, supports that differ by direction, gravity, a tilted
//! principal axis), and the linear rotor-bearing model with its balancer planes
//! ([`crate::linear_rotor`], [`Rotor::Linear`]), through the model-agnostic pipeline of
//! [`crate::analysis`]: one [`Rotor`] type for every model, which the maps
//! ([`crate::rotor_map`]) take too.
//!
//! At each speed `Ω` of a grid the model's equations in axes turning with the rotor
//! ([`PlanarField`], [`SpatialField`], [`LinearRotorField`]) are solved for the stationary state — an equilibrium
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

use crate::analysis::{
    family, speed_scan_with_last, stationary, Family, FamilyOptions, FamilyVerdict, Kind, NewtonOptions, ParameterRange, ScanOptions, StableRange,
    StationaryState, VectorField, Verdict,
};
use crate::control::{Control, Outcome, StopReason};
use crate::error::{Error, Result};
use crate::linear_rotor::{Frame, LinearRotor, LinearRotorField};
use crate::planar::field::PlanarField;
use crate::planar::PlanarRotor;
use crate::spatial::dynamics::field::SpatialField;
use crate::spatial::dynamics::RunOutcome;
use crate::spatial::dynamics::SpatialRotor;
use rayon::prelude::*;
use serde::Serialize;

/// A rotor that the stationary analysis can take: any model as the simulation runs it.
#[derive(Debug, Clone, PartialEq)]
pub enum Rotor {
    /// The planar rotor (paper 004; SI: rad/s).
    Planar(PlanarRotor),
    /// The spatial rotor (papers 000/003 and beyond; SI, or the papers' dimensionless units).
    Spatial(SpatialRotor),
    /// The linear rotor-bearing model with its balancer planes ([`crate::linear_rotor`]; SI:
    /// rad/s), in axes turning with the rotor ([`Frame::Rotating`]). The speed scan, the maps
    /// and [`crate::rotor_campbell::stationary_at`] take it; the Campbell diagram with the
    /// balls, the locked critical speeds and the partially balanced states refuse it (with an
    /// [`Error::InvalidParameter`] naming `linear_rotor`).
    Linear(LinearRotor),
}

/// The model's field at one speed ([`VectorField`] by delegation).
// one field per speed, built and dropped in the scan's loop: the variants' sizes do not matter
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
pub enum Field {
    /// [`PlanarField`].
    Planar(PlanarField),
    /// [`SpatialField`].
    Spatial(SpatialField),
    /// [`LinearRotorField`] in axes turning with the rotor.
    Linear(LinearRotorField),
}

macro_rules! delegate {
    ($self:ident, $f:ident => $e:expr) => {
        match $self {
            Field::Planar($f) => $e,
            Field::Spatial($f) => $e,
            Field::Linear($f) => $e,
        }
    };
}

impl Field {
    /// Why no balanced periodic orbit exists at this field's speed: a spatial rotor under
    /// gravity across the axis whose plane of an odd number of balls has a share below one
    /// ball's `m R` ([`SpatialField::gravity_circulation`]); `None` otherwise. The analyses
    /// take no start there (the family's arc member would creep, and shooting can take its
    /// slow creep for an orbit) and give this as the reason.
    pub fn gravity_circulation(&self) -> Option<String> {
        match self {
            Field::Spatial(f) => f.gravity_circulation(),
            _ => None,
        }
    }
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
    /// The model's name in outputs: `"planar"`, `"spatial"` or `"linear"`.
    pub fn model_name(&self) -> &'static str {
        match self {
            Rotor::Planar(_) => "planar",
            Rotor::Spatial(_) => "spatial",
            Rotor::Linear(_) => "linear",
        }
    }

    /// The field at speed `omega`; [`Error::NoLinearisation`] for real balls. The linear
    /// rotor's is in axes turning with it ([`Frame::Rotating`]: the balanced state is an
    /// equilibrium, or a periodic orbit of half a revolution for direction-dependent supports,
    /// of one under gravity).
    pub fn field(&self, omega: f64) -> Result<Field> {
        Ok(match self {
            Rotor::Planar(p) => Field::Planar(PlanarField::new(p, omega)?),
            Rotor::Spatial(s) => Field::Spatial(SpatialField::new(s, omega)?),
            Rotor::Linear(r) => Field::Linear(LinearRotorField::new(r, omega, Frame::Rotating)?),
        })
    }

    /// The closed-form starting state at the field's speed: the planar rotor's semi-balanced
    /// state ([`PlanarField::semi_balanced_guess`], the balanced state when the race is centred),
    /// the spatial and the linear rotor's balanced state ([`SpatialField::balanced_guess`],
    /// [`LinearRotorField::balanced_guess`]).
    pub fn guess(field: &Field) -> Option<Vec<f64>> {
        match field {
            Field::Planar(f) => f.semi_balanced_guess(),
            Field::Spatial(f) => f.balanced_guess(),
            Field::Linear(f) => f.balanced_guess(),
        }
    }

    /// The start of a spatial rotor's balanced periodic orbit **under gravity across the axis
    /// with `n ≥ 3` balls in a plane**, where the family of balanced states breaks into
    /// isolated orbits with each such plane's balls in two bunched groups
    /// ([`SpatialField::split_guesses`], why there): the orbit is found from every placement
    /// of the groups and the one of least growth rate (its largest Floquet exponent's real part)
    /// is returned: the orbit a run settles on where one of them is stable. `None` where the
    /// rotor is not of that kind or no placement reaches an orbit (then [`Rotor::guess`]).
    ///
    /// ```
    /// use autobal::rotor_stability::Rotor;
    /// use autobal::analysis::NewtonOptions;
    /// let mut root = autobal::config::parse(include_str!("../../../examples/washing_machine.toml"), "washer").unwrap();
    /// autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, -9.81, 0.0]")).unwrap();
    /// let rotor = Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor);
    /// let field = rotor.field(146.61).unwrap(); // 1400 rpm
    /// let x = Rotor::gravity_orbit_start(&field, &NewtonOptions::default()).unwrap();
    /// let n = x.len() / 2;
    /// // two of the three balls together, the third apart
    /// let psi = &x[n - 3..n];
    /// let mut gaps: Vec<f64> = [(0, 1), (0, 2), (1, 2)].iter().map(|&(i, j)| (psi[i] - psi[j]).abs()).collect();
    /// gaps.sort_by(f64::total_cmp);
    /// assert!(gaps[0] < 1e-6 && gaps[1] > 0.5, "{psi:?}");
    /// ```
    pub fn gravity_orbit_start(field: &Field, newton: &NewtonOptions) -> Option<Vec<f64>> {
        Self::gravity_orbits(field, newton).into_iter().next().map(|(x, _)| x)
    }

    /// Every distinct periodic orbit that [`Rotor::gravity_orbit_start`] finds from the groups'
    /// placements, each as its state and [`OtherOrbit`] (ball angles at phase 0, largest
    /// Floquet exponent, verdict), the least growth rate first. Two placements that reach one
    /// orbit (the same ball angles to 1e-2 rad, `SAME_ANGLE`, a plane's balls in any order: they are alike)
    /// count once. Empty where the rotor is not of that kind or no placement reaches an orbit.
    pub fn gravity_orbits(field: &Field, newton: &NewtonOptions) -> Vec<(Vec<f64>, OtherOrbit)> {
        let Field::Spatial(f) = field else { return vec![] };
        shoot_placements(field, f, f.split_guesses(), |a, b| same_placement(f.rotor(), a, b), newton)
    }

    /// The planar rotor's periodic orbits with `n ≥ 3` equal balls in **two groups**, on
    /// supports that differ by direction (a periodic stationary motion): shot from each
    /// placement of [`PlanarField::split_guesses`], each as its state and [`OtherOrbit`], the
    /// least growth rate first; two placements reaching one orbit (the ball angles matched to
    /// 1e-6 rad in any order: the balls are alike) count once. The speed scan's last resort
    /// ([`stability_over_speed`]: only where Newton from [`Rotor::first_start`] and the
    /// neighbour's state finds no state), as [`Rotor::gravity_orbits`] is the spatial rotor's
    /// first start under gravity. Empty for any other rotor, or where no placement reaches an
    /// orbit.
    pub fn planar_split_orbits(field: &Field, newton: &NewtonOptions) -> Vec<(Vec<f64>, OtherOrbit)> {
        let Field::Planar(f) = field else { return vec![] };
        shoot_placements(field, f, f.split_guesses(), same_angles, newton)
    }

    /// The candidate **partially balanced equilibria** of a spatial or linear rotor whose balls
    /// cannot cancel its unbalance (no balanced state: a plane's capacity short, or one plane
    /// against a couple; an equilibrium, not a periodic orbit): Newton from each of
    /// [`Rotor::guess`] (where it has a placement), [`Rotor::placed_guess`] (a short plane
    /// bunched towards its share, the other on its arc), [`Rotor::bunched_guess`] (each plane's
    /// balls bunched against its own share), every ball bunched against the static unbalance,
    /// and every ball bunched where the race pulls them (each root of `d(ψ) × e^{iψ} = 0` on the
    /// rotor's linearisation [`LinearRotor::from_spatial`],
    /// [`crate::linear_rotor::partial::bunched_guesses`]), the rotor on the axis at rest; a
    /// linear rotor from the same placements by its own model
    /// ([`crate::linear_rotor::partial::share_guesses`], the shares from its balancing system,
    /// and [`crate::linear_rotor::partial::bunched_guesses`]), so the two routes shoot from the
    /// same placements (session 21: the linear route took one start and analysed another state
    /// than the spatial scan on rnd/r19_00_sp.toml, unstable at 81-249 rad/s where the spatial
    /// one is stable). Each distinct state found (ball angles matched per plane to 1e-2 rad, `SAME_ANGLE`)
    /// with its stability, the least growth rate first. Which
    /// start Newton took decided the state analysed until session 20 (audit 20's F11: on
    /// rnd/r19_00_sp.toml at 435.1 rad/s each plane's share, opposite each other, gives a state
    /// unstable at +7.88 1/s, every ball against the static unbalance a stable one at −0.75
    /// 1/s that a run settles on). Empty for the planar rotor, a periodic orbit, or where a
    /// balanced state exists.
    pub fn partial_states(field: &Field, newton: &NewtonOptions) -> Vec<(Vec<f64>, OtherOrbit)> {
        Rotor::partial_states_from(field, newton, &[])
    }

    /// [`Rotor::partial_states`] with `carried` starts besides the candidates: the speed scan's
    /// states of the previous speed, so that a state the candidates reach at one speed is
    /// followed to the next where they miss it (rnd/r19_00_sp.toml: the stable state at
    /// 440.9-568.5 rad/s is reached from the candidates at 32 of 38 grid speeds).
    pub(crate) fn partial_states_from(field: &Field, newton: &NewtonOptions, carried: &[Vec<f64>]) -> Vec<(Vec<f64>, OtherOrbit)> {
        if let Field::Linear(f) = field {
            // no balanced state (a plane's capacity short of its share): the same starts from
            // the model's shares (linear_rotor::partial::share_guesses: each plane on its
            // share as far as it reaches, each bunched at it, every ball against the static
            // unbalance), the linear route's own start (the balls bunched where the race
            // pulls them) and the carried states
            if f.period().is_some() || f.balanced_guess().is_some() {
                return vec![];
            }
            let mut starts = crate::linear_rotor::partial::share_guesses(f);
            starts.extend(crate::linear_rotor::partial::bunched_guesses(f));
            starts.extend(carried.iter().filter(|x| x.len() == 2 * f.coords()).cloned());
            let sizes: Vec<usize> = f.rotor().balancers.iter().map(|b| b.balls).collect();
            return shoot_placements(field, f, starts, |a, b| same_in_planes(&sizes, a, b), newton);
        }
        let Field::Spatial(f) = field else { return vec![] };
        if f.period().is_some() || spatial_can_balance(f) {
            return vec![];
        }
        // the closed form's placement too where it has one (one plane against a couple it
        // cannot cancel: the static balance, the scan's start until session 20)
        let mut starts: Vec<Vec<f64>> = [Rotor::guess(field), Rotor::placed_guess(field), Rotor::bunched_guess(field)].into_iter().flatten().collect();
        let r = f.rotor();
        let s0 = r.static_unbalance();
        if s0[0] != 0.0 || s0[1] != 0.0 {
            let m = f.coords();
            let nb = r.balls();
            let mut x = vec![0.0; 2 * m];
            x[m - nb..m].iter_mut().for_each(|v| *v = (-s0[1]).atan2(-s0[0]));
            starts.push(x);
        }
        // every ball bunched where the race pulls them, each root of d(ψ) × e^{iψ} = 0 on the
        // rotor's linearisation (LinearRotor::from_spatial: the linear route's starts,
        // linear_rotor::partial::bunched_guesses), the rotor on the axis at rest
        if let Some(lf) = LinearRotor::from_spatial(r).ok().and_then(|l| LinearRotorField::new(&l, f.omega(), Frame::Rotating).ok()) {
            let n = lf.rotor().dofs();
            for g in crate::linear_rotor::partial::bunched_guesses(&lf) {
                let m = f.coords();
                let mut x = vec![0.0; 2 * m];
                x[m - r.balls()..m].iter_mut().for_each(|v| *v = g[n]);
                starts.push(x);
            }
        }
        starts.extend(carried.iter().filter(|x| x.len() == 2 * f.coords()).cloned());
        shoot_placements(field, f, starts, |a, b| same_placement(r, a, b), newton)
    }

    /// The start of Newton's method at a speed without a neighbour's state, the one order of
    /// the speed scan ([`stability_over_speed`]) and the map ([`crate::rotor_map`]): `orbit`
    /// (under gravity across the axis with `n ≥ 3` balls in a plane, the orbit of least growth
    /// rate among the groups' placements, [`Rotor::gravity_orbits`]), else the closed form of
    /// the (semi-)balanced state ([`Rotor::guess`]), else each plane's balls on its share
    /// ([`Rotor::placed_guess`]), else every plane's balls bunched ([`Rotor::bunched_guess`]:
    /// the partially balanced state where the balls' capacity falls short). (The map tried
    /// only the first two until session 17, and found no state where the scan found the
    /// partially balanced one.)
    pub fn first_start(field: &Field, orbit: Option<Vec<f64>>) -> Option<Vec<f64>> {
        orbit.or_else(|| Rotor::guess(field)).or_else(|| Rotor::placed_guess(field)).or_else(|| Rotor::bunched_guess(field))
    }

    /// The first guess where [`Rotor::guess`] has none, for a spatial rotor with two ball
    /// planes: each plane's balls placed on its share of the unbalance
    /// ([`crate::spatial::dynamics::SpatialRotor::balanced_ball_angles`]: a plane short of its
    /// share bunched towards it, the other on the arc of its share), the rotor at rest on the
    /// axis, a start for Newton. On the rotor of `tests/partial_two_plane.rs` Newton reaches
    /// the stable partially balanced state from here and the unstable one from
    /// [`Rotor::bunched_guess`] (every plane bunched). `None` for the planar rotor and one plane
    /// (where [`Rotor::bunched_guess`] is the same placement).
    pub fn placed_guess(field: &Field) -> Option<Vec<f64>> {
        let Field::Spatial(f) = field else { return None };
        let r = f.rotor();
        if r.planes.iter().filter(|p| p.n > 0).count() != 2 {
            return None;
        }
        let m = f.coords();
        let nb = r.balls();
        let placed = r.balanced_ball_angles();
        if placed.angles.len() != nb {
            return None;
        }
        let mut x = vec![0.0; 2 * m];
        x[m - nb..m].copy_from_slice(&placed.angles);
        Some(x)
    }

    /// The second guess, where [`Rotor::guess`] has none (the balls' capacity falls short of
    /// the unbalance the balanced or semi-balanced state needs): **the balls bunched**, all at
    /// one angle, leaving a residual unbalance (the partially balanced state).
    ///
    /// Planar rotor: the aligned whirl with every ball on the far side of the line through
    /// the axis and the race centre E ([`crate::planar::stationary::aligned_whirls_of`] with
    /// `q = n`, a closed form: `e^{iφ}(ρD − n m3 r Ω²) = Ω² U0 + s2 e^{iγ} D`, `ρ e^{iφ}` the
    /// position of E), of the (at most two) roots the one of least whirl radius: the balls
    /// opposite the unbalance. It joins the semi-balanced state where that ceases to exist
    /// (all its balls bunched, E on the axis), so a speed scan follows one branch across.
    /// Spatial rotor: each plane's balls bunched at the angle of its share of the unbalance
    /// ([`SpatialField::balanced_guess`]'s targets), the rotor on the axis at rest: not itself
    /// stationary (the residual unbalance makes the rotor whirl), a start for Newton. Linear
    /// rotor: every ball opposite the static unbalance, the structure at its stationary
    /// displacement under them ([`crate::linear_rotor::partial::bunched_guess`]).
    pub fn bunched_guess(field: &Field) -> Option<Vec<f64>> {
        match field {
            Field::Linear(f) => crate::linear_rotor::partial::bunched_guess(f),
            Field::Planar(f) => {
                use num_complex::Complex64 as C;
                let p = f.rotor();
                let w = f.omega();
                if p.n == 0 || w == 0.0 {
                    return None;
                }
                // |ρD − qq| = |rhs| for ρ = |E| ≥ 0 (as aligned_whirls_of), then φ from the phase
                let e = C::from_polar(p.s2, p.gamma);
                let d = C::new(p.k - p.total_mass() * w * w, p.c * w);
                let u0 = C::new(p.m1 * p.s1, 0.0) + e * (p.m2 + p.n as f64 * p.m3);
                let rhs = u0 * (w * w) + e * d;
                let qq = p.m3 * p.r * p.n as f64 * w * w;
                let (a, b, c) = (d.norm_sqr(), -2.0 * qq * d.re, qq * qq - rhs.norm_sqr());
                let disc = b * b - 4.0 * a * c;
                if !(disc >= 0.0 && a > 0.0) {
                    return None;
                }
                let u = [-1.0, 1.0]
                    .iter()
                    .map(|sg| (-b + sg * disc.sqrt()) / (2.0 * a))
                    .filter(|rho| *rho > 0.0)
                    .map(|rho| {
                        let phase = rhs.arg() - (d * rho - qq).arg();
                        (C::from_polar(rho, phase) - e, phase)
                    })
                    .min_by(|x, y| x.0.norm().total_cmp(&y.0.norm()))?;
                let nr = 2 + p.n;
                let mut x = vec![0.0; 2 * nr];
                x[0] = u.0.re;
                x[1] = u.0.im;
                x[2..nr].iter_mut().for_each(|v| *v = u.1);
                Some(x)
            }
            Field::Spatial(f) => {
                let r = f.rotor();
                let planes: Vec<_> = r.planes.iter().filter(|p| p.n > 0).collect();
                let s0 = r.static_unbalance();
                let targets: Vec<[f64; 2]> = match planes.len() {
                    1 => vec![[-s0[0], -s0[1]]],
                    2 => {
                        let zr = r.z_reference();
                        let (z1, z2) = (planes[0].z - zr, planes[1].z - zr);
                        if z1 == z2 {
                            return None;
                        }
                        let c0 = r.couple_unbalance();
                        let b1 = [(z2 * s0[0] - c0[0]) / (z1 - z2), (z2 * s0[1] - c0[1]) / (z1 - z2)];
                        vec![b1, [-s0[0] - b1[0], -s0[1] - b1[1]]]
                    }
                    _ => return None,
                };
                let mut psi = vec![];
                for (p, t) in planes.iter().zip(targets) {
                    let a = if t[0] == 0.0 && t[1] == 0.0 { 0.0 } else { t[1].atan2(t[0]) };
                    psi.extend(std::iter::repeat_n(a, p.n));
                }
                let m = f.coords();
                let mut x = vec![0.0; 2 * m];
                x[m - psi.len()..m].copy_from_slice(&psi);
                Some(x)
            }
        }
    }

    /// What the stationary state `x` of `field` is ([`StateKind`]), from its residual
    /// ([`Rotor::residual`]: on a periodic orbit the mean over the revolution, the orbit's 64
    /// samples of [`crate::analysis::orbit_samples`], never its start alone, where the sag and
    /// the swing read as a whirl). Planar: E on the axis (residual at most `1e-6`), balanced
    /// or semi-balanced; else partially balanced with the balls bunched (with the race centred,
    /// only with the residual unbalance below 1: bunched on the unbalance's side, above 1, the
    /// balls add to it: not balanced); else, on a periodic
    /// orbit only, (semi-)balanced to the residual while it is at most 5 % (the simulation's
    /// threshold, `BALANCE_TOLERANCE`); not balanced.
    /// Spatial: residual at most `1e-6`, balanced; else partially balanced where no balanced
    /// state exists (decided in closed form, whatever the balls' bunching: the capacity short
    /// for the static unbalance, or one ball plane against a nonzero couple about it,
    /// `spatial_can_balance`); else, on a periodic orbit, balanced (to the residual, which it
    /// carries) while the residual is at most 5 % of the unbalance (the swing's second
    /// order: on examples/spatial_two_plane.toml 1e-6..1e-3 below ~600 rad/s); else not
    /// balanced (at an equilibrium a balanced state's residual is Newton's: any residual above
    /// `1e-6` there is not balanced). Linear: [`crate::linear_rotor::partial::state_kind`] (the race
    /// centres' mean whirl against their whirl without the balls' resultant).
    pub fn state_kind(field: &Field, x: &[f64]) -> StateKind {
        Rotor::classify(field, x).0
    }

    /// The state a verdict command analyses at a speed, given `found` (the state Newton reached
    /// there from the command's starts: the closed form, the neighbour's state; `hint` the
    /// neighbour's monodromy the shooting started from), with its [`Rotor::classify`]. **The one
    /// rule of `stability`, `map` and `campbell`**: where `found` is not balanced or
    /// semi-balanced but the closed form has such a state ([`Rotor::guess`]), Newton from the
    /// closed form (with `hint`, then, on a periodic orbit, without it: a fresh shooting) and
    /// the first balanced or semi-balanced state it reaches is analysed; else `found`. A
    /// balanced state found pays nothing more than its classification (which the commands
    /// report anyway), so only speeds whose state is of another kind try again. Until session
    /// 21 each command kept the state its first start reached, and which that was depended on
    /// where the continuation came from: a map cell continued the not-balanced orbit of its
    /// neighbour (stable) where `stability` analysed the semi-balanced one (unstable), and
    /// `stability`'s shooting from the closed form with the neighbour's monodromy reached a
    /// not-balanced orbit where `map` and `campbell` analysed the balanced one (audit 21's F4,
    /// F5; tests/balanced_first.rs).
    ///
    /// `tried`: a start the command has already shot from with `hint` (its state is `found`, or
    /// it failed); where it is the closed form that attempt is not repeated (the same Newton,
    /// the same answer).
    pub fn settle_balanced(
        field: &Field,
        found: StationaryState,
        hint: Option<&[f64]>,
        tried: Option<&[f64]>,
        opts: &NewtonOptions,
    ) -> (StationaryState, (StateKind, f64)) {
        let class = Rotor::classify(field, &found.x);
        let wanted = |k: StateKind| matches!(k, StateKind::Balanced | StateKind::SemiBalanced);
        if wanted(class.0) {
            return (found, class);
        }
        let Some(g) = Rotor::guess(field) else { return (found, class) };
        let hints: &[Option<&[f64]>] = if hint.is_some() && field.period().is_some() { &[hint, None] } else { &[hint] };
        let again = tried == Some(g.as_slice());
        for &h in hints.iter().filter(|&&h| !(again && h == hint)) {
            let Ok(s) = crate::analysis::stationary_near(field, &g, h, opts) else { continue };
            let c = Rotor::classify(field, &s.x);
            if wanted(c.0) {
                return (s, c);
            }
        }
        (found, class)
    }

    /// [`Rotor::state_kind`] and [`Rotor::residual`] together, from one integration of the
    /// orbit (each alone integrates it once).
    pub fn classify(field: &Field, x: &[f64]) -> (StateKind, f64) {
        let rows = orbit_rows(field, x);
        let r = Rotor::residual_in(field, x, &rows);
        let kind = match field {
            Field::Linear(f) => crate::linear_rotor::partial::state_kind_in(f, x, &rows),
            Field::Planar(f) => {
                let p = f.rotor();
                // E on the axis (to 1e-6 of its whirl without the balls' resultant):
                // (semi-)balanced; on a periodic orbit E's mean position over the revolution
                // (its once-per-revolution whirl in fixed axes: the orbit's start alone reads
                // the swing as a whirl). Else the balls bunched: partially balanced; else, on a
                // periodic orbit only (an equilibrium has no swing to leave a residual),
                // (semi-)balanced while E is within the allowance (5 % of s2, or of the
                // residual's reference where that is smaller: `balance_allowance`), partially
                // balanced where the balls are together (their mean resultant at least 99 % of
                // the capacity, the run's test: the swing parts balls of different masses or
                // drags, 0.01 rad on audit 23's rotor); not balanced
                let balanced = if p.s2 == 0.0 { StateKind::Balanced } else { StateKind::SemiBalanced };
                let periodic = field.period().is_some();
                let together = || {
                    let b = mean_of(&rows, x.len(), |row| crate::planar::stationary::ball_resultant(p, ball_coordinates(field).map(|i| row[i])).to_vec());
                    crate::spatial::dynamics::simulate::together(b[0].hypot(b[1]), crate::planar::stationary::ball_capacity(p))
                };
                if r <= BALANCED_EXACTLY {
                    balanced
                } else if bunched(&ball_angles(field, x)) && r < 1.0 {
                    // partially: the balls reduce the unbalance; with the race centred the
                    // residual is the residual unbalance itself, and bunched on the unbalance's
                    // side (below the critical speed, residual > 1) they add to it: not
                    // balanced. An eccentric race's residual is E's offset against E's offset
                    // without the balls' resultant: above 1 the balls put E farther from the
                    // axis than no balls would, so not balanced either (paper 004's bunched
                    // state below its semi-balanced speed, 1.91 at 200 rad/s, read partially
                    // balanced until session 16; a review of the planar run's words)
                    // (before the allowance: equal balls bunched on a periodic orbit are at their
                    // capacity limit, whatever E's offset; review 24a: E 2.3 µm off the axis, 2.3 %
                    // of s2, below the speed where the semi-balanced state begins)
                    StateKind::PartiallyBalanced
                } else if periodic && r <= crate::planar::stationary::balance_allowance(p, f.omega()) {
                    balanced
                } else if periodic && together() && r < 1.0 {
                    // (the balls of different masses or drags, parted by the swing, at their
                    // capacity limit: the rule of the bunched ones above)
                    StateKind::PartiallyBalanced
                } else {
                    // the one rule (state_from_residual) for what is left: no balanced state
                    // here, so below 1 the balls reduce the unbalance (partially), else not
                    state_from_residual(r, 0.0, false)
                }
            }
            Field::Spatial(s) => {
                // the residual static and couple unbalance (each ball's e^{iψ} its mean over the
                // revolution on a periodic orbit: balanced means cancelling it on average).
                // Whether the balls can cancel the unbalance at all is decided in closed form
                // (capacity, one plane against a couple about it), whatever their bunching;
                // where they can, a residual above 1e-6 is balanced only on a periodic orbit
                // (the swing's second order, at most BALANCE_TOLERANCE; an equilibrium has no swing).
                // The swing's own estimate Σ m_b R (1 − |⟨e^{iψ}⟩|) / u does not bound it: the
                // residual is 60 to 740 times it on the gravity cases of
                // tests/state_kind_orbits.rs (independent of g: both second order), while the
                // opposite-ball orbit's (~1) is ~1e3 times its own, so no factor separates them
                // (the one rule, state_from_residual: a residual of 1 or more is not balanced
                // whether or not the balls could balance; before session 29 a rotor that
                // cannot balance had every state partially balanced, a lone ball on the heavy
                // side with residual 1.45 too, where `simulate` said not balanced)
                let tolerance = if field.period().is_some() { BALANCE_TOLERANCE } else { BALANCED_EXACTLY };
                state_from_residual(r, tolerance, spatial_can_balance(s))
            }
        };
        (kind, r)
    }

    /// The residual unbalance that the balls of the stationary state `x` leave, as a fraction
    /// of the rotor's unbalance (the balls' positions on a periodic orbit averaged over the
    /// revolution, as [`Rotor::state_kind`] reads them). Spatial: `max(|s|, |c|/ℓ) / max(|s0|,
    /// |c0|/ℓ)`, `s`, `c` the residual static and couple unbalance of the unbalance masses and
    /// the balls (each ball's `e^{iψ}` its mean over the orbit), `s0`, `c0` those of the
    /// unbalance masses alone, `ℓ` the largest distance of a ball plane or unbalance mass
    /// from the reference plane (the balls' capacity `Σ m_b R` in place of the unbalance where
    /// there is none). Linear: the static residual `|s0 + Σ m_b R ⟨e^{iψ}⟩| / |s0|`
    /// ([`crate::linear_rotor::partial::residual_static`]). Planar: the race centre E's
    /// (mean) distance from the axis over its distance without the balls' resultant,
    /// `|Ω² u0 / D + s2 e^{iγ}|`, `u0 = m1 s1 + (m2 + Σ m_j) s2 e^{iγ}`, `D = k̄ − M Ω² + i c̄ Ω`
    /// (the semi-balanced state's E is on the axis; for a centred race, at an equilibrium,
    /// exactly the residual unbalance `|m1 s1 + Σ m_j r e^{iψ_j}| / (m1 s1)`). On an orbit that cannot be integrated again, the
    /// orbit's start.
    ///
    /// At an equilibrium a balanced state's residual is Newton's (~1e-12). On a periodic orbit
    /// (gravity, supports that differ by direction) the balls swing once a revolution by `δψ`
    /// and the mean of `e^{iψ}` differs from `e^{i⟨ψ⟩}` at second order (`−⟨δψ²⟩/2`): the balls
    /// settle where the rotor's mean whirl (its once-per-revolution whirl about the sag) holds
    /// them against that, so a balanced orbit keeps a residual of second order in the swing,
    /// ∝ g² under gravity (examples/spatial_two_plane.toml: 3.0e-3 at 262 rad/s, 1.1e-4 at 437,
    /// below 1e-6 above ~700 rad/s). [`StateKind::Balanced`] carries it (`SpeedPoint::residual`).
    pub fn residual(field: &Field, x: &[f64]) -> f64 {
        Rotor::residual_in(field, x, &orbit_rows(field, x))
    }

    /// [`Rotor::residual`] with the means over `rows` ([`orbit_rows`]).
    fn residual_in(field: &Field, x: &[f64], rows: &[f64]) -> f64 {
        let orbit_mean = |_: &Field, _: &[f64], f: &dyn Fn(&[f64]) -> Vec<f64>| mean_of(rows, x.len(), f);
        match field {
            Field::Spatial(s) => {
                let units = orbit_mean(field, x, &|row| row[ball_coordinates(field)].iter().flat_map(|a| [a.cos(), a.sin()]).collect());
                let units: Vec<[f64; 2]> = units.chunks(2).map(|u| [u[0], u[1]]).collect();
                spatial_residual(s.rotor(), &units)
            }
            Field::Linear(l) => {
                let r = l.rotor();
                let units = orbit_mean(field, x, &|row| row[ball_coordinates(field)].iter().flat_map(|a| [a.cos(), a.sin()]).collect());
                let s0 = crate::linear_rotor::partial::static_unbalance(r);
                let mut s = s0;
                let mut j = 0;
                let mut cap = 0.0;
                for b in &r.balancers {
                    for _ in 0..b.balls {
                        s[0] += b.ball_mass * b.radius * units[2 * j];
                        s[1] += b.ball_mass * b.radius * units[2 * j + 1];
                        cap += b.ball_mass * b.radius;
                        j += 1;
                    }
                }
                s[0].hypot(s[1]) / unbalance_scale(s0[0].hypot(s0[1]), cap)
            }
            Field::Planar(f) => {
                use num_complex::Complex64 as C;
                let p = f.rotor();
                let e = orbit_mean(field, x, &|row| vec![row[0], row[1]]);
                let race = C::from_polar(p.s2, p.gamma);
                let off = (C::new(e[0], e[1]) + race).norm();
                // over E without the balls' resultant (the run's scale too)
                off / crate::planar::stationary::race_offset_scale(p, f.omega())
            }
        }
    }

    /// `sqrt(k/M)`: the rotor's translational natural frequency on its supports (a scale for
    /// default speed axes); the linear rotor's lowest undamped natural frequency with its balls
    /// as rings ([`LinearRotor::natural_frequencies`]), NaN where it has none (`M` not
    /// positive definite: refused by [`Rotor::field`] too).
    pub fn natural_frequency(&self) -> f64 {
        match self {
            Rotor::Planar(p) => p.natural_frequency(),
            Rotor::Spatial(s) => s.natural_frequency(),
            Rotor::Linear(r) => r.natural_frequencies(&[], true).ok().and_then(|w| w.first().copied()).unwrap_or(f64::NAN),
        }
    }

    /// The fastest undamped natural frequency of the rotor at speed `omega` without its
    /// rotation (gyroscopic terms left out), its balls as rings: what sets the step of the
    /// shooting's integration (DOP853's stability and accuracy both follow the fastest
    /// vibration). Planar: `sqrt(max(k_x, k_y)/m0)`; spatial: the larger root of the
    /// translation-tilt pair `M q̈ + K q = 0` in each direction about the centre of mass at
    /// balance (translation alone with the tilt locked); linear: the highest of
    /// [`LinearRotor::natural_frequencies`] with the bearings at `omega`
    /// ([`LinearRotor::at_speed`]). NaN where there is none (`M` not positive definite).
    pub fn fastest_natural_frequency(&self, omega: f64) -> f64 {
        match self {
            Rotor::Planar(p) => {
                let (wx, wy) = p.natural_frequencies_xy();
                wx.max(wy)
            }
            Rotor::Spatial(s) => {
                let m = s.total_mass();
                let zr = s.z_reference();
                let d2 = |z: f64| (z - zr) * (z - zr);
                let tilt = s.rotor.equatorial_moment
                    + s.rotor.mass * d2(s.rotor.z)
                    + s.unbalances.iter().map(|u| u.mass * d2(u.z)).sum::<f64>()
                    + s.planes.iter().map(|p| p.n as f64 * p.ball_mass * (d2(p.z) + 0.5 * p.race_radius * p.race_radius)).sum::<f64>();
                (0..2)
                    .map(|i| {
                        let (k, kd, kdd) = s.supports.iter().fold((0.0, 0.0, 0.0), |(a, b, c), sp| {
                            let d = sp.z - zr;
                            (a + sp.stiffness[i], b + sp.stiffness[i] * d, c + sp.stiffness[i] * d * d)
                        });
                        if s.lock_tilt || !(tilt > 0.0) {
                            return (k / m).sqrt();
                        }
                        // eigenvalues of M⁻¹K, M = diag(m, tilt), K = [[k, kd], [kd, kdd]]
                        let (tr, det) = (k / m + kdd / tilt, (k * kdd - kd * kd) / (m * tilt));
                        (0.5 * (tr + (tr * tr - 4.0 * det).max(0.0).sqrt())).sqrt()
                    })
                    .fold(f64::NAN, f64::max)
            }
            Rotor::Linear(r) => r.at_speed(omega).natural_frequencies(&[], true).ok().and_then(|w| w.last().copied()).unwrap_or(f64::NAN),
        }
    }

    /// The lowest speed near `omega` at which the periodic-orbit analysis runs: the fastest
    /// natural frequency at `omega` ([`Rotor::fastest_natural_frequency`]) over
    /// [`PERIODS_PER_REVOLUTION`], i.e. a revolution spans at most that many of the fastest
    /// natural periods. The shooting integrates a revolution (`2π/Ω`, or half of it) with the
    /// variational equations at steps set by the fastest vibration, so its cost grows as
    /// `ω_fast/Ω` (~5e11 periods at 1e-9 rad/s on examples/spatial_two_plane.toml, which ran
    /// for more than 120 s without an answer). `None` for an equilibrium (no integration), or
    /// for a rotor with no stiffness at all (no vibration: the steps follow the revolution).
    pub fn periodic_floor(&self, omega: f64) -> Option<f64> {
        let wn = self.fastest_natural_frequency(omega);
        (self.is_periodic() && wn.is_finite() && wn > 0.0).then(|| wn / PERIODS_PER_REVOLUTION)
    }

    /// The floor ([`Rotor::periodic_floor`]) where `omega` lies below it (`|omega| <` floor):
    /// a speed the periodic-orbit analysis does not analyse. The one rule that `stability`,
    /// `map` ([`crate::rotor_map`]) and `campbell` ([`crate::rotor_campbell`]) apply.
    pub fn below_periodic_floor(&self, omega: f64) -> Option<f64> {
        self.periodic_floor(omega).filter(|f| omega.abs() < *f)
    }

    /// Whether the rotor has an unbalance for the balls to cancel, static or couple, above
    /// [`NO_UNBALANCE`] of the balls' capacity `Σ m_b R`: spatial the static `|s0|` or the
    /// couple over the largest axial distance (as [`Rotor::residual`]); linear (no axial
    /// positions) `|s0|` or any node's own resultant (unbalances at one node and offset that
    /// cancel are none; opposite ones at two nodes are a couple); planar the unbalance
    /// `|m1 s1 + (m0 − m1) s2 e^{iγ}|` that whirls E. What the residuals are fractions of is
    /// [`Rotor::residual_scale`].
    pub fn has_unbalance(&self) -> bool {
        match self {
            Rotor::Planar(p) => {
                let u0 = num_complex::Complex64::new(p.m1 * p.s1, 0.0) + num_complex::Complex64::from_polar(p.s2, p.gamma) * (p.total_mass() - p.m1);
                u0.norm() > NO_UNBALANCE * p.balls_mass() * p.r
            }
            Rotor::Spatial(r) => {
                let (s0, c0) = (r.static_unbalance(), r.couple_unbalance());
                let zr = r.z_reference();
                let zl = r.planes.iter().filter(|p| p.n > 0).map(|p| (p.z - zr).abs()).chain(r.unbalances.iter().map(|u| (u.z - zr).abs())).fold(0.0, f64::max);
                let zl = if zl > 0.0 { zl } else { 1.0 };
                let cap: f64 = r.planes.iter().map(|p| p.n as f64 * p.ball_mass * p.race_radius).sum();
                s0[0].hypot(s0[1]).max(c0[0].hypot(c0[1]) / zl) > NO_UNBALANCE * cap
            }
            Rotor::Linear(r) => {
                let s0 = crate::linear_rotor::partial::static_unbalance(r);
                let cap: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius).sum();
                let mut worst = s0[0].hypot(s0[1]);
                for u in &r.unbalances {
                    let here = r.unbalances.iter().filter(|v| v.node == u.node && v.offset == u.offset);
                    let s = here.fold([0.0, 0.0], |s, v| [s[0] + v.me * v.phase.cos(), s[1] + v.me * v.phase.sin()]);
                    worst = worst.max(s[0].hypot(s[1]));
                }
                worst > NO_UNBALANCE * cap
            }
        }
    }

    /// What the residuals ([`SpeedPoint::residual`], [`Rotor::residual`]) are fractions of.
    pub fn residual_scale(&self) -> ResidualScale {
        let cap = |s0: [f64; 2], cap: f64| s0[0].hypot(s0[1]) <= NO_UNBALANCE * cap;
        match self {
            Rotor::Planar(_) => ResidualScale::RaceOffset,
            Rotor::Spatial(_) if !self.has_unbalance() => ResidualScale::Capacity,
            Rotor::Spatial(_) => ResidualScale::Unbalance,
            Rotor::Linear(r) => {
                let c: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius).sum();
                if cap(crate::linear_rotor::partial::static_unbalance(r), c) {
                    ResidualScale::Capacity
                } else {
                    ResidualScale::StaticUnbalance
                }
            }
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
    /// Whether the speed was analysed: `false` below the periodic-orbit analysis' floor
    /// ([`Rotor::periodic_floor`]), where `failure` says so and no state was sought (not "no
    /// stationary state found").
    pub analysed: bool,
    /// What the state analysed here is: balanced, semi-balanced, or partially balanced (the
    /// balls' capacity short: balls bunched, a residual unbalance); `None` without a state.
    pub state: Option<StateKind>,
    /// What `state` is decided on ([`StateBasis`]): the residual (spatial, planar), or the
    /// race centres' whirl (linear: a `balanced` state may then carry a static `residual` of
    /// 0.03-0.5, an unbalance away from the balancer planes that they do not see); `None`
    /// without a state.
    pub state_basis: Option<StateBasis>,
    /// The residual unbalance the balls leave in that state, as a fraction of the rotor's
    /// unbalance ([`Rotor::residual`]: on a periodic orbit the balls' positions averaged over
    /// the revolution; planar: the race centre's distance from the axis over the eccentricity
    /// scale; the unbalance as the scale, or the balls' capacity `Σ m_b R` where the unbalance
    /// is below `1e-6` of it ([`Rotor::has_unbalance`]): then the balls' resultant over their
    /// capacity); `None` without a
    /// state. A balanced state carries the residual it is balanced
    /// to: ~1e-10 at an equilibrium, on an orbit the second-order residual of the balls' swing.
    pub residual: Option<f64>,
    /// The balls' angles of the state analysed here (rad, all planes in order): with a family
    /// (`family_dimension > 0`), the member that `verdict` and `abscissa` refer to.
    pub member_psi: Vec<f64>,
    /// With a family: its stability over the members sampled at this speed
    /// ([`FamilyPoint`]: how many stable, the least and most stable member by their ball
    /// angles), at every grid speed where the family could be followed; `None` for an
    /// isolated state.
    pub family: Option<FamilyPoint>,
    /// With a family: which of its members are stable (all, some, none): `family`'s verdict.
    pub family_verdict: Option<FamilyVerdict>,
    /// Under gravity across the axis with `n ≥ 3` balls in a plane, or on the planar rotor with
    /// an eccentric race on supports that differ by direction and `n ≥ 3` equal balls
    /// ([`Rotor::planar_split_orbits`]): the other periodic orbits
    /// found at this speed from the groups' placements ([`OtherOrbit`]); on a spatial or linear
    /// rotor whose balls cannot cancel its unbalance, the other partially balanced equilibria found
    /// from the candidate starts ([`Rotor::partial_states`]: the one of least growth rate is
    /// the one analysed here); the least growth rate first; empty elsewhere.
    pub other_orbits: Vec<OtherOrbit>,
}

/// A periodic orbit found at a speed beside the one analysed there
/// ([`SpeedPoint::other_orbits`]): under gravity across the axis with `n ≥ 3` balls in a plane
/// each placement of the balls in two groups is shot ([`Rotor::gravity_orbits`]) and the
/// orbit of least growth rate analysed; these are the others (e.g. the washer at 1400 rpm: the
/// mirror of the stable orbit, unstable at +3.49e-4 1/s). Where one of them is stable too, a
/// run may settle on either.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OtherOrbit {
    /// The balls' angles at phase 0 (rad, all planes in order), as [`SpeedPoint::member_psi`].
    pub member_psi: Vec<f64>,
    /// Its largest Floquet exponent's real part (1/s, or per unit τ).
    pub abscissa: f64,
    /// Its verdict.
    pub verdict: Verdict,
}

/// The distinct stationary states (periodic orbits or equilibria) Newton reaches from
/// `guesses` on `f` (the model of `field`), each as its state and [`OtherOrbit`]; two starts
/// reaching one state (`same` on their ball angles) count once; the least growth rate first.
/// [`Rotor::gravity_orbits`], [`Rotor::planar_split_orbits`] and
/// [`Rotor::partial_states_from`].
fn shoot_placements<F: VectorField>(
    field: &Field,
    f: &F,
    guesses: Vec<Vec<f64>>,
    same: impl Fn(&[f64], &[f64]) -> bool,
    newton: &NewtonOptions,
) -> Vec<(Vec<f64>, OtherOrbit)> {
    let mut found: Vec<(Vec<f64>, OtherOrbit)> = vec![];
    for g in guesses {
        let Ok(state) = stationary(f, &g, newton) else { continue };
        let Ok(st) = crate::analysis::stability(f, &state) else { continue };
        let member_psi = ball_angles(field, &state.x);
        if !found.iter().any(|(_, o)| same(&o.member_psi, &member_psi)) {
            found.push((state.x, OtherOrbit { member_psi, abscissa: st.abscissa, verdict: st.verdict }));
        }
    }
    found.sort_by(|a, b| a.1.abscissa.total_cmp(&b.1.abscissa));
    found
}

/// Whether two placements of alike balls are one: the angles matched one to one within
/// `1e-6` rad round the circle.
fn same_angles(a: &[f64], b: &[f64]) -> bool {
    matched_within(a, b, 1e-6)
}

/// Whether each angle of `a` matches an unused one of `b` within `tol` rad round the circle
/// (not sorted lists: 1e-9 and 2π − 1e-9 are one angle), the two of one length.
fn matched_within(a: &[f64], b: &[f64], tol: f64) -> bool {
    let near = |x: f64, y: f64| {
        let d = (x - y).rem_euclid(std::f64::consts::TAU);
        d.min(std::f64::consts::TAU - d) <= tol
    };
    let mut used = vec![false; b.len()];
    a.len() == b.len()
        && a.iter().all(|&x| match b.iter().enumerate().position(|(j, &y)| !used[j] && near(x, y)) {
            Some(j) => {
                used[j] = true;
                true
            }
            None => false,
        })
}

/// Whether two placements of a spatial rotor's balls (all planes in order) are one: each
/// plane's angles matched one to one within [`SAME_ANGLE`] round the circle (the balls of a
/// plane are alike, so a placement and its relabelling are the same orbit).
fn same_placement(rotor: &SpatialRotor, a: &[f64], b: &[f64]) -> bool {
    let sizes: Vec<usize> = rotor.planes.iter().map(|p| p.n).collect();
    same_in_planes(&sizes, a, b)
}

/// Ball angles within this of each other (rad) are one placement ([`same_in_planes`]). Newton
/// leaves weakly held balls (a partially balanced state at low speed) where its scaled
/// residual is met, which on those balls is ~1e-3 rad from the state (review 21: one state
/// reached from two starts 1e-3 rad apart on a linear Rodrigues rotor, 2.47e-3 on the spatial
/// rnd/r19_00_sp.toml at 11.6 rad/s); at 1e-6 rad such copies were listed as other states, a
/// stable copy of the analysed state read as "a run may settle on a stable one of these".
/// Distinct states measured are ≥ 0.25 rad apart (the balls on the other side of a whirl's
/// line, or bunched elsewhere), 25 times this.
const SAME_ANGLE: f64 = 1e-2;

/// [`same_placement`] with the planes' ball counts `sizes` (all planes in order).
fn same_in_planes(sizes: &[usize], a: &[f64], b: &[f64]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut start = 0;
    sizes.iter().all(|&n| {
        let range = start..(start + n).min(a.len());
        start = range.end;
        matched_within(&a[range.clone()], &b[range], SAME_ANGLE)
    })
}

/// What [`SpeedPoint::state`] is decided on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StateBasis {
    /// The residual unbalance [`SpeedPoint::residual`] (spatial: with the closed-form test of
    /// whether a balanced state exists; planar: the race centre's offset, with the balls'
    /// bunching): [`Rotor::state_kind`].
    Residual,
    /// The race centres' whirl against their whirl without the balls' resultant (the linear
    /// rotor, [`crate::linear_rotor::partial::state_kind`]); its `residual` is the static one
    /// only, which an unbalance away from the balancer planes leaves whatever the balls do.
    RaceWhirl,
}

/// What the residuals ([`SpeedPoint::residual`]) are fractions of ([`Rotor::residual_scale`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ResidualScale {
    /// The residual static and couple unbalance over the rotor's (spatial).
    Unbalance,
    /// The residual static unbalance over the rotor's static one (linear).
    StaticUnbalance,
    /// The balls' resultant (static only on a linear rotor) over their capacity `Σ m_b R`:
    /// the unbalance it measures is below [`NO_UNBALANCE`] of the capacity (none, or on a
    /// linear rotor a couple only).
    Capacity,
    /// The race centre's distance from the axis over its distance without the balls'
    /// resultant, or over a length scale where that is below 1e-12 of it (planar).
    RaceOffset,
}

impl ResidualScale {
    /// The words for "a residual of 0.1 {words}".
    pub fn words(self) -> &'static str {
        match self {
            ResidualScale::Unbalance => "of the unbalance",
            ResidualScale::StaticUnbalance => "of the static unbalance",
            ResidualScale::Capacity => "of the balls' capacity (no unbalance they measure)",
            ResidualScale::RaceOffset => "of the race centre's offset without the balls",
        }
    }
}

/// What a stationary state is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StateKind {
    /// The balls cancel the unbalance: the rotor turns about its axis. Spatial: the residual
    /// [`Rotor::residual`] at most `1e-6` of the unbalance, or, on a periodic orbit only and
    /// where a balanced state exists, at most 5 % of it (the balls swing and cancel the
    /// unbalance on average but for the swing's second order, ∝ g² under gravity;
    /// [`SpeedPoint::residual`] carries it). Planar: the race centred, `s2 = 0`, E on the axis.
    /// Linear: the race-whirl rule of [`crate::linear_rotor::partial::state_kind`] (no plane's
    /// race whirls at more than 0.05 (`BALANCE_TOLERANCE`) of its whirl without the balls' resultant); its residual
    /// is the static one only (the linear rotor's nodes carry no axial positions).
    Balanced,
    /// Paper 004's eccentric race: the race centre E on the axis, the disk whirling at `s2`
    /// (at an equilibrium to `1e-6` of E's offset without the balls' resultant; on a periodic
    /// orbit, supports that differ by direction, E's mean position within 5 % of `s2`
    /// of the axis, [`crate::planar::stationary::balance_allowance`]).
    SemiBalanced,
    /// Not balanced, but the balls reduce the unbalance: the residual unbalance below 1 (by
    /// more than [`NO_REDUCTION`]; [`state_from_residual`], the one rule `simulate`'s settled
    /// runs use too). Typically the balls cannot cancel the unbalance (capacity short, or
    /// below the speed where paper 004's semi-balanced state exists) and rest bunched at their
    /// limit; the spatial residual is the larger of the static and couple parts (one plane
    /// against a couple about it is never balanced). Planar: the balls bunched (or, on a
    /// periodic orbit, together at their capacity limit) with a residual below 1, else the one
    /// rule. Linear: the race-whirl rule of [`crate::linear_rotor::partial::state_kind`].
    PartiallyBalanced,
    /// The balls do not reduce the unbalance: a residual unbalance of 1 or more
    /// ([`state_from_residual`]; before session 29 the spatial route called such states
    /// partially balanced where the balls could not balance). E.g. the balls on the heavy side
    /// below the critical speed, or two balls opposite each other on the line of the whirl: a
    /// ball is at rest on a whirling race only on that line (its tangential force
    /// `m_b Ω² |d| sin(ψ − arg d)` vanishes), so such states exist at every speed beside the
    /// balanced one and Newton can reach one from a poor start; they are named, never called
    /// balanced ([`state_kind`](Rotor::state_kind)). Linear: the race whirling (mean over an
    /// orbit) at more than 0.05 (`BALANCE_TOLERANCE`) of its whirl without the balls'
    /// resultant ([`crate::linear_rotor::partial::state_kind`]).
    NotBalanced,
}

impl StateKind {
    /// `"balanced"`, `"semi_balanced"`, `"partially_balanced"`, `"not_balanced"`: the JSON's
    /// words (its serde names), for the CSV columns and Python's arrays that name a state.
    pub fn key(self) -> &'static str {
        match self {
            StateKind::Balanced => "balanced",
            StateKind::SemiBalanced => "semi_balanced",
            StateKind::PartiallyBalanced => "partially_balanced",
            StateKind::NotBalanced => "not_balanced",
        }
    }

    /// `"balanced"`, `"semi-balanced"`, `"partially balanced"`, `"not balanced"`.
    pub fn name(self) -> &'static str {
        match self {
            StateKind::Balanced => "balanced",
            StateKind::SemiBalanced => "semi-balanced",
            StateKind::PartiallyBalanced => "partially balanced",
            StateKind::NotBalanced => "not balanced",
        }
    }
}

/// How far below 1 a residual must be for the balls to count as reducing the unbalance
/// ([`state_from_residual`]): 1e-3. Two balls opposite each other on the line of the whirl
/// leave the unbalance whole, a residual of 1 to rounding (the planar Jeffcott rotor's
/// opposite-ball equilibrium, `tests/end_state_18.rs`, read partially balanced with the bare
/// `r < 1`), or to the swing's second order on a periodic orbit.
pub const NO_REDUCTION: f64 = 1e-3;

/// **The one rule** that names a state by its residual unbalance, for `stability`'s states
/// ([`Rotor::classify`]) and `simulate`'s settled runs
/// ([`crate::spatial::dynamics::simulate::RunOutcome`]) alike: `residual` the residual
/// unbalance as a fraction of the rotor's own (the larger of the static and couple parts
/// where both are measured), `tolerance` the residual up to which the state is balanced,
/// `can_balance` whether a balanced state exists at all (the balls' capacity suffices and
/// no couple is left that no plane cancels; where it does not, the state is never balanced,
/// issue 18 item 4). Balanced: `residual ≤ tolerance` where the balls can balance (or
/// `residual ≤ 1e-6` whatever the closed form says). Partially balanced: `residual < 1`
/// (by more than [`NO_REDUCTION`]), the balls reduce the unbalance (the residual printed
/// beside it). Not balanced: `residual ≥ 1` (to [`NO_REDUCTION`]), the balls do not reduce the unbalance or add to it (a ball on the heavy
/// side below the critical speed; two balls opposite each other, residual 1). Before
/// session 29 the spatial route called every state of a rotor that cannot balance
/// "partially balanced" (a lone ball on the heavy side, residual 1.45) and `simulate` called
/// a reducing state "not balanced" unless the balls were together at the capacity limit.
pub fn state_from_residual(residual: f64, tolerance: f64, can_balance: bool) -> StateKind {
    if residual <= BALANCED_EXACTLY || (can_balance && residual <= tolerance) {
        StateKind::Balanced
    } else if residual < 1.0 - NO_REDUCTION {
        StateKind::PartiallyBalanced
    } else {
        StateKind::NotBalanced
    }
}

/// One member of a family, named by its balls' angles.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Member {
    /// Its parameter on the family ([`crate::analysis::FamilyMember::parameter`]: the scaled
    /// arclength `s` from the member Newton reached from the closed form, `s = 0`).
    pub parameter: Vec<f64>,
    /// The balls' angles (rad, all planes in order).
    pub psi: Vec<f64>,
    /// Its spectral abscissa without the structural zeros (1/s, or per unit τ).
    pub abscissa: f64,
    /// Its verdict.
    pub verdict: Verdict,
}

/// The family of stationary states at one speed ([`crate::analysis::family`]): which of its
/// sampled members are stable.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FamilyPoint {
    /// Members analysed: the member given, the points drawn that Newton corrected onto the
    /// family (a family of dimension `k ≥ 2`) or the continuation's members (`k = 1`), the
    /// bunched members and those the search for the extremes added.
    pub members: usize,
    /// Points drawn (`k ≥ 2`; only those corrected onto the family are members); 0 for a
    /// continuation.
    pub drawn: usize,
    /// Bunched members analysed (`k ≥ 2`: each plane's balls in two coinciding groups,
    /// [`crate::analysis::FamilyOptions::seeds`]).
    pub bunched: usize,
    /// Members the search for the extremes added ([`crate::analysis::FamilyOptions::refine_extremes`]).
    pub searched: usize,
    /// Of which stable.
    pub stable_members: usize,
    /// All, some, or none of the sampled members stable.
    pub verdict: FamilyVerdict,
    /// For a one-parameter family: whether the continuation closed (the family sampled all
    /// round), and its length in the parameter `s`.
    pub closed: bool,
    /// The family's length in `s` (one-parameter family).
    pub length: f64,
    /// The least stable member sampled (largest abscissa).
    pub least_stable: Member,
    /// The most stable member sampled (smallest abscissa).
    pub most_stable: Member,
    /// The ranges of `s` whose members are stable (one-parameter family; ends at the sampling
    /// step: the first and last stable member of each run).
    pub stable_parameter_ranges: Vec<ParameterRange>,
}

/// The family's stability over speed ([`RotorStability::family`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FamilyStability {
    /// Its dimension `k` (`n − 2` for `n ≥ 3` balls in one plane).
    pub dimension: usize,
    /// How it is parameterised and sampled, in words (with how many members were analysed).
    pub parameterisation: String,
    /// The fewest and the most members analysed at one grid speed ([`FamilyPoint::members`]);
    /// `None` where no family was followed.
    pub members_analysed: Option<[usize; 2]>,
    /// The speed ranges where **every** sampled member is stable (ends located to 1e-9
    /// relative where the largest abscissa over the sampled members crosses 0).
    pub all_members_stable: Vec<StableRange>,
    /// The speed ranges where **at least one** sampled member is stable ("some members
    /// stable", not "stable": other members are not), ends where the smallest abscissa over
    /// the sampled members crosses 0.
    pub some_members_stable: Vec<StableRange>,
}

/// The stationary state's stability over speed ([`stability_over_speed`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RotorStability {
    /// `"planar"`, `"spatial"` or `"linear"` ([`Rotor::model_name`]).
    pub model: &'static str,
    /// Equilibrium (eigenvalues) or periodic orbit (Floquet multipliers).
    pub kind: Kind,
    /// The speed ranges where the stationary state analysed is stable (ends located to 1e-9
    /// relative): with a family, of **one member per speed**, the one Newton's method reaches
    /// from the closed form ([`SpeedPoint::member_psi`]); the family's own ranges are in
    /// [`RotorStability::family`].
    pub stable_ranges: Vec<StableRange>,
    /// Every speed of the grid.
    pub points: Vec<SpeedPoint>,
    /// The largest family dimension met (0: isolated states; `n − 2` for `n ≥ 3` balls in one
    /// plane at balance): that many eigenvalues 0 (multipliers 1) are structural at each point
    /// and left out of the verdict.
    pub family_dimension: usize,
    /// The balls' angles of the member analysed at the first speed with a family of
    /// (semi-)balanced states (`SpeedPoint::family_dimension > 0`; without one anywhere, at the
    /// first speed where a state was found) (rad, all planes in order): the member that
    /// `stable_ranges` follows from there (each point's own member in
    /// [`SpeedPoint::member_psi`]). Never a partially balanced point's bunched balls where a
    /// family exists elsewhere (main at 21dbfc9 named the first speed's, bunched, member).
    pub member_psi: Vec<f64>,
    /// With a family (`family_dimension > 0`): its stability over all the members sampled,
    /// the speed ranges where all and where some members are stable.
    pub family: Option<FamilyStability>,
    /// Whether the rotor has an unbalance for the balls to cancel ([`Rotor::has_unbalance`]);
    /// without one the residuals are the balls' resultant over their capacity `Σ m_b R`.
    pub has_unbalance: bool,
    /// What the residuals are fractions of ([`Rotor::residual_scale`]).
    pub residual_scale: ResidualScale,
    /// How many speeds the scan was asked for: more than [`RotorStability::points`] where it
    /// was stopped (Ctrl-C, a budget), so that its last point is where it stopped, not the end
    /// of the axis (not in the JSON, which says `complete: false` itself).
    #[serde(skip)]
    pub speeds_asked: usize,
    /// The speeds the scan added between grid speeds of one verdict where the samples of `α`
    /// say a zero crossing may hide (`analysis::stability`'s refinement): they take part in
    /// `stable_ranges` only, not in `points` (the grid) nor the family's ranges (not in the JSON).
    #[serde(skip)]
    pub refined_speeds: Vec<f64>,
}

impl RotorStability {
    /// Whether the scan stopped before the last speed it was asked for.
    pub fn cut_short(&self) -> bool {
        self.points.len() < self.speeds_asked
    }
}

/// The stationary state of `rotor` and its stability at each of `speeds` (ascending), with the
/// ends of the stable ranges located (module docs). Runs to the end: [`stability_over_speed_with`]
/// under a [`Control`].
pub fn stability_over_speed(rotor: &Rotor, speeds: &[f64]) -> Result<RotorStability> {
    stability_over_speed_with(rotor, speeds, &Control::none()).map(|o| o.value)
}

/// The growth rate (1/s) of the (semi-)balanced state of `rotor` at `omega` where it is an
/// isolated state (no family) and unstable by its exact linear stability
/// ([`stability_over_speed`]); `None` where it is stable or neutral, belongs to a family, is not
/// the state found, or has no linearisation (real balls). [`unstable_balanced_state`]'s
/// isolated case.
pub fn unstable_isolated_state(rotor: &Rotor, omega: f64) -> Option<f64> {
    match unstable_balanced_state(rotor, omega)? {
        UnstableBalance::Isolated(rate) => Some(rate),
        UnstableBalance::Family(_) => None,
    }
}

/// The (semi-)balanced state a balanced end sits next to, where it moves away
/// ([`unstable_balanced_state`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum UnstableBalance {
    /// An isolated state, unstable by its exact linear stability: its growth rate (1/s, or
    /// per unit `τ`).
    Isolated(f64),
    /// A family of balanced states (`n >= 3` balls in a plane) of which every member sampled
    /// ([`FamilyPoint`], verdict [`FamilyVerdict::NoneStable`]) is unstable: the least growth
    /// rate among them (the most stable member's abscissa, > 0).
    Family(f64),
}

/// Whether the (semi-)balanced state of `rotor` at `omega` is one a run moves away from
/// ([`stability_over_speed`] at that one speed): an isolated state that is unstable
/// ([`UnstableBalance::Isolated`]), or a family whose every sampled member is unstable
/// ([`UnstableBalance::Family`]); `None` where it is stable or neutral, a family with a stable
/// (or neutral) member sampled, not the state found, or without linearisation (real balls).
/// The runs' creep check (`end_checks`): a run at a constant speed that ends balanced next
/// to such a state is creeping away from it, not settled. With a family the run rests on some
/// member, not necessarily the one Newton reached; only where none of them is stable is a
/// creep certain (a sampled verdict: the family is followed at steps of
/// [`crate::analysis::FamilyOptions`]' default, and a stable arc between two samples would
/// be missed; the warning says "every member sampled").
///
/// The last few answers are kept (rotor and speed compared exactly): `basins` and repeated
/// runs end at one speed of one rotor, where each run asked the whole analysis again (a
/// periodic orbit's Floquet analysis under gravity, +63 % on the washer's basins, counted by a
/// review in session 18).
pub fn unstable_balanced_state(rotor: &Rotor, omega: f64) -> Option<UnstableBalance> {
    type Answers = Vec<(Rotor, u64, Option<UnstableBalance>)>;
    static ANSWERS: std::sync::Mutex<Answers> = std::sync::Mutex::new(Vec::new());
    let known = |a: &Answers| a.iter().find(|(r, w, _)| *w == omega.to_bits() && r == rotor).map(|k| k.2);
    if let Some(k) = ANSWERS.lock().ok().and_then(|a| known(&a)) {
        return k;
    }
    let answer = (|| {
        let r = stability_over_speed(rotor, &[omega]).ok()?;
        let p = r.points.first()?;
        if !matches!(p.state, Some(StateKind::Balanced | StateKind::SemiBalanced)) {
            return None;
        }
        if p.family_dimension == 0 {
            return (p.verdict == Some(crate::analysis::Verdict::Unstable)).then_some(UnstableBalance::Isolated(p.abscissa?));
        }
        // a family: a creep only where no member sampled is stable (session 19's audit: paper
        // 004's rotor with four balls at 115.8 rad/s, below its critical speed, every member
        // unstable at +0.055 1/s or more, read "balanced" at 40 s, residual 0.027, and not
        // balanced, residual 3.0, at 121 s: tests/family_creep_19.rs)
        let f = p.family.as_ref()?;
        let rate = f.most_stable.abscissa;
        (f.verdict == FamilyVerdict::NoneStable && f.members > 0 && rate > 0.0).then_some(UnstableBalance::Family(rate))
    })();
    if let Ok(mut a) = ANSWERS.lock() {
        if known(&a).is_none() {
            if a.len() == 4 {
                a.remove(0);
            }
            a.push((rotor.clone(), omega.to_bits(), answer));
        }
    }
    answer
}

/// The runs' warning for the creep check ([`unstable_balanced_state`]): the final speed `omega`
/// and the growth rate (> 0) of the unstable state the run ends next to (of a family, its
/// most stable member sampled), in the model's units: rad/s and 1/s where `si` (the planar and
/// linear rotors), else named as either (the spatial run does not know whether its model is
/// the papers' dimensionless one, `Ω` and `1/τ`). One wording for every route (planar,
/// spatial, linear).
pub(crate) fn creep_warning(omega: f64, state: UnstableBalance, si: bool) -> String {
    let (speed, rate_unit, time_unit, note) = run_units(omega, si);
    match state {
        UnstableBalance::Isolated(rate) => format!(
            "the balls end near the balanced state, which is unstable at ω = {speed} (exact linear stability: growth rate {rate:.4e}{rate_unit}, a deviation grows by e in {:.4e}{time_unit}{note}): they creep away from it, so the end is not settled although the residual is small; a longer run leaves it",
            1.0 / rate,
        ),
        UnstableBalance::Family(rate) => format!(
            "the balls end near the family of balanced states, every member of which that `stability` samples is unstable at ω = {speed} (exact linear stability: the most stable grows at {rate:.4e}{rate_unit}, a deviation by e in {:.4e}{time_unit}{note}): they creep away from it, so the end is not settled although the residual is small; a longer run leaves it",
            1.0 / rate,
        ),
    }
}

/// The runs' warnings' units ([`creep_warning`], [`settled_end_check`]): the speed to six
/// decimals with trailing zeros dropped (1.395, not 1.40; 600, not 600.00) and `rad/s` where
/// `si`, the rate's and the time's units, and where not `si` a note naming both unit systems.
fn run_units(omega: f64, si: bool) -> (String, &'static str, &'static str, &'static str) {
    let w = format!("{omega:.6}");
    let w = if w.contains('.') { w.trim_end_matches('0').trim_end_matches('.') } else { &w };
    if si {
        (format!("{w} rad/s"), " 1/s", " s", "")
    } else {
        (w.to_string(), "", "", "; rad/s, 1/s and s, or a dimensionless model's Ω and τ")
    }
}

/// Balls within this angle (rad) of a stationary state count as next to it for the end-state
/// check ([`settled_end_check`]): Newton from an end on a stable state lands on it to
/// round-off, and a run at a drift below the settling test's rate (`1e-3 Ω` per revolution)
/// that is more than 0.1 rad away from an unstable state is no slow creep away from it.
pub(crate) const NEAR_STATE: f64 = 0.1;

/// Where Newton's method from a run's end lands ([`settled_end_check`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum EndState {
    /// Within [`NEAR_STATE`] of the balls' angles, on an isolated equilibrium that is unstable
    /// by its exact linear stability: its word and growth rate (1/s, or `1/τ`).
    Unstable(StateKind, f64),
    /// Newton lands more than [`NEAR_STATE`] from the balls' angles, or does not converge: the
    /// end is at no stationary state (a run that settled on one starts Newton within its drift
    /// of it).
    Elsewhere,
}

/// The stationary state that a run at a constant speed, ending in `x` (the field's reduced
/// state in its turning axes: each route turns its own end state into it), sits next to, by
/// Newton's method from `x` ([`crate::analysis::stationary`], default options): [`EndState`];
/// `None` where Newton lands on a family (`n >= 3` balls in a plane), on a stable or
/// neutral state, or where the stationary motion is a periodic orbit (gravity across the
/// axis, supports that differ by direction: no Newton from one instant). The three runs'
/// check of an end that reads not balanced or partially balanced and settled.
pub(crate) fn end_state(field: &Field, x: &[f64]) -> Option<EndState> {
    if field.period().is_some() || x.len() != field.dim() {
        return None;
    }
    let balls = ball_coordinates(field);
    if balls.is_empty() {
        return None;
    }
    // A run settled on a stationary state ends within its drift of it, where Newton converges
    // in a few iterations; one that does not converge within the analyses' limit (50) starts
    // at no state either. A review's run-up of examples/linear_rotor_shaft.toml to 600 rad/s
    // (the balls turning together at 0.012 rad/s at 20 s) stalls there at a scaled residual of
    // 3e-9: the balls' common rotation is nearly free (the scaled Jacobian's smallest singular
    // value 7.5e-11 of its largest), the Newton step along it 2 rad long and curved off by the
    // stiff rotor coordinates; 807 iterations reach the state with the balls opposite on the
    // whirl's line, 0.7 rad from theirs (tests/end_state_18.rs). Following such a valley costs
    // ~1e6 instructions an iteration on every such run; not needed for the verdict
    let Ok(st) = stationary(field, x, &NewtonOptions::default()) else {
        return Some(EndState::Elsewhere);
    };
    let tau = std::f64::consts::TAU;
    let near = st.x[balls.clone()].iter().zip(&x[balls]).all(|(a, b)| {
        let d = (a - b).rem_euclid(tau);
        d.min(tau - d) <= NEAR_STATE
    });
    if !near {
        return Some(EndState::Elsewhere);
    }
    if st.family_dimension > 0 {
        return None;
    }
    let lin = crate::analysis::stability(field, &st).ok()?;
    (lin.verdict == Verdict::Unstable && lin.abscissa > 0.0).then(|| EndState::Unstable(Rotor::state_kind(field, &st.x), lin.abscissa))
}

/// The end-state check of a run of `rotor` that ends at the constant speed `omega`, reading
/// not balanced or partially balanced and settled, in the state `x` (the reduced state of
/// `rotor.field(omega)` in turning axes): where Newton from it lands ([`end_state`]) and the
/// run's warning, or `None` (the word stands). The growth rate is `Some` for
/// [`EndState::Unstable`]. Units as [`creep_warning`]'s (`si`: rad/s and 1/s). One check and
/// one wording for the planar, spatial and linear runs.
pub(crate) fn settled_end_check(rotor: &Rotor, x: &[f64], omega: f64, si: bool) -> Option<(Option<f64>, String)> {
    let field = rotor.field(omega).ok()?;
    let (speed, rate_unit, time_unit, note) = run_units(omega, si);
    match end_state(&field, x)? {
        EndState::Unstable(kind, rate) => {
            let state = match stability_over_speed(rotor, &[omega]).ok().and_then(|r| r.points.first().map(|p| (p.state, p.verdict))) {
                Some((Some(k), Some(v))) => format!("; `stability`'s state at this speed is {} and {}", k.name(), v.name()),
                _ => String::new(),
            };
            let kind = match kind {
                StateKind::NotBalanced => "not balanced (the balls' resultant not cancelling the unbalance)",
                k => k.name(),
            };
            Some((
                Some(rate),
                format!(
                    "the run ends near a stationary state that is {kind} and unstable at ω = {speed} (exact linear stability: growth rate {rate:.4e}{rate_unit}, a deviation grows by e in {:.4e}{time_unit}{note}): the motion moves away from it, so the end is not settled{state}; where it goes depends on the start: raise drive.t_end or start elsewhere (drive.psi0)",
                    1.0 / rate
                ),
            ))
        }
        EndState::Elsewhere => Some((
            None,
            format!(
                "the balls are at no stationary state at ω = {speed}: Newton's method from the end reaches none within {NEAR_STATE} rad of their angles, so they still move, though more slowly than the settling test sees; the end is not settled: raise drive.t_end"
            ),
        )),
    }
}

/// What the end checks ([`end_checks`]) leave of a run's verdict.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EndChecks {
    /// The run's outcome, [`RunOutcome::NotSettled`] where a check overrode it.
    pub outcome: RunOutcome,
    /// Whether the run settled: `false` where a check overrode the outcome.
    pub settled: bool,
    /// The growth rate (1/s, or `1/τ`) of the unstable state the run ends next to: the creep
    /// check's, or the end-state check's for [`EndState::Unstable`]; `None` where neither
    /// found one (also for [`EndState::Elsewhere`]).
    pub creep_rate: Option<f64>,
    /// The overriding check's warning ([`creep_warning`] or [`settled_end_check`]'s words):
    /// `Some` exactly where the outcome was overridden.
    pub warning: Option<String>,
}

/// The end checks of a time-domain run of `rotor` (the planar, spatial and linear runs'
/// summaries), which turn a settled-looking end into [`RunOutcome::NotSettled`] (`settled`
/// false) with one warning where the balls sit next to a state they move away from:
///
/// - **The gate** `constant`: a prescribed drive whose speed `omega` is constant at the end
///   (each route decides it from its own drive; the planar run requires its run completed
///   too): `stability`'s states are those of a rotor turned at a prescribed constant speed.
/// - **The creep check**: an end that reads [`RunOutcome::Balanced`] next to an isolated
///   (semi-)balanced state that is unstable at `omega` by its exact linear stability
///   ([`unstable_isolated_state`]) is a slow creep away from it, not a settled end: the drift
///   test's floor (`1e-4 ω_n` in the planar run) passes a creep whose growth rate times its
///   distance is below it. Found in session 17: examples/planar.toml centred, 100 rad/s, the
///   balls 0.01 rad off the unstable balanced state read "balanced" at 30 s with a residual of
///   0.022, not balanced at 300 s with a residual of 2.2 (tests/planar_creep_17.rs; the spatial
///   run tests/spatial_creep_18.rs; the linear run tests/linear_creep_18.rs, "balanced" at
///   10 s, the residual growing at the exact rate). With `n >= 3` balls in a plane the run may
///   rest on a stable member of a family whose closed-form member is unstable: a family
///   counts only where every member sampled is unstable ([`unstable_balanced_state`];
///   tests/family_creep_19.rs). Warning: [`creep_warning`].
/// - **The end-state check**, where the creep check found nothing: an end that reads
///   [`RunOutcome::NotBalanced`] or [`RunOutcome::PartiallyBalanced`] and `settled` is
///   checked by Newton's method from its state ([`settled_end_check`], [`end_state`]), the
///   state `reduced` returns (the route's end as the field's reduced state in turning axes;
///   asked only here, `None` skips the check). Two balls spread evenly (opposite each other)
///   start next to the state with the balls opposite on the line of the whirl, which is
///   unstable where the balanced state is stable: examples/linear_rotor_shaft.toml at
///   600 rad/s, growth rate 0.022/s (e in 45 s), the balanced state approached at 0.022/s; a
///   20 s run read "not balanced", settled, where `stability` says balanced and stable
///   (tests/linear_creep_18.rs; the planar and spatial runs tests/end_state_18.rs). Where the
///   balls go from there depends on the start, and the warning says so. Equilibria only: no
///   Newton from one instant of a periodic orbit.
///
/// Units of the warnings as [`creep_warning`]'s (`si`: rad/s and 1/s; the spatial run does
/// not know its model's units). Otherwise `outcome` and `settled` stand, with no rate and no
/// warning.
pub(crate) fn end_checks(
    rotor: &Rotor,
    omega: f64,
    si: bool,
    constant: bool,
    outcome: RunOutcome,
    settled: bool,
    reduced: impl FnOnce() -> Option<Vec<f64>>,
) -> EndChecks {
    let creep = (outcome == RunOutcome::Balanced && constant).then(|| unstable_balanced_state(rotor, omega)).flatten();
    let found = match creep {
        Some(state) => {
            let (UnstableBalance::Isolated(rate) | UnstableBalance::Family(rate)) = state;
            Some((Some(rate), creep_warning(omega, state, si)))
        }
        None => (matches!(outcome, RunOutcome::NotBalanced | RunOutcome::PartiallyBalanced) && settled && constant)
            .then(|| settled_end_check(rotor, &reduced()?, omega, si))
            .flatten(),
    };
    match found {
        Some((creep_rate, warning)) => EndChecks { outcome: RunOutcome::NotSettled, settled: false, creep_rate, warning: Some(warning) },
        None => EndChecks { outcome, settled, creep_rate: None, warning: None },
    }
}

/// [`stability_over_speed`] under `control`, asked once per speed (each grid speed, each trial
/// speed of a range end's location, each speed's family); the progress observer is told the
/// grid speeds done, then (with a family) the families followed, counted on after the grid
/// speeds (`grid + done` of `grid + families`). Stopped, the outcome holds the speeds done until then: their points, the
/// stable ranges among them (an end whose location the stop cut short reported as not located,
/// at the grid speed), the families followed until then.
pub fn stability_over_speed_with(rotor: &Rotor, speeds: &[f64], control: &Control) -> Result<Outcome<RotorStability>> {
    if speeds.is_empty() {
        return Err(Error::invalid("speeds", "no speed to analyse"));
    }
    // the model's own validation first, so its message names the field
    let first = rotor.field(speeds[0])?;
    let kind = if first.period().is_some() { Kind::PeriodicOrbit } else { Kind::Equilibrium };
    // a periodic orbit is shot over a whole revolution: below the floor its integration spans
    // more than PERIODS_PER_REVOLUTION natural periods (a scan to 1e-9 rad/s integrated for
    // hours); a top speed below it is refused, grid speeds below it fail by name
    // (with the bearings at each speed: a linear rotor's speed-dependent bearings)
    let floor = |w: f64| if kind == Kind::PeriodicOrbit { rotor.below_periodic_floor(w) } else { None };
    let top = speeds.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if let Some(f) = floor(top) {
        return Err(Error::invalid("omega_max", below_floor(top, f)));
    }
    let field_at = |w: f64| match floor(w) {
        Some(f) => Err(Error::invalid("omega", below_floor(w, f))),
        None => rotor.field(w),
    };
    // Newton starts from the closed form at every speed (it names the branch: the balanced
    // state, or for a periodic orbit its autonomous neighbour, from which the shooting lands on
    // the orbit of the balanced branch; continuation from the previous orbit switched to orbits
    // with the balls elsewhere at 450-650 rad/s on examples/spatial_two_plane.toml), the
    // shooting's matrix from the previous speed's monodromy (analysis::stationary_near). The
    // shooting integrates at rtol 1e-10 (not the pipeline's default 1e-12): 5.5x faster, and
    // the multipliers near 1 stay good to ~1e-9, inside FLOQUET_TOLERANCE (1e-8)
    let opts = ScanOptions { newton: newton_options(kind == Kind::PeriodicOrbit), ..ScanOptions::default() };
    // where the closed form has no (semi-)balanced state, the partially balanced state: from
    // each plane's balls placed on its share, a short plane's bunched (Rotor::placed_guess),
    // else every plane's balls bunched (Rotor::bunched_guess)
    // under gravity across the axis with n >= 3 balls in a plane, the orbit with the balls in
    // two groups (Rotor::gravity_orbit_start: the family's arc member is no orbit there)
    let newton = opts.newton.clone();
    // the orbits found from the groups' placements at each speed, kept for `other_orbits`
    let orbits_at: std::sync::Mutex<Vec<(f64, Vec<OtherOrbit>)>> = Default::default();
    // the partially balanced states found at each speed solved, those of the nearest speed
    // solved carried as starts to the next solve (the last speed solved until session 31: a
    // range end's location then started from whatever state an earlier, unrelated location's
    // last trial left, and the two-plane rotor's end near 445 rad/s moved by 0.08 rad/s when
    // an earlier location took fewer trials)
    let carried: std::sync::Mutex<Vec<(f64, Vec<Vec<f64>>)>> = Default::default();
    let guess = |f: &Field, omega: f64| {
        // no balanced orbit where no two groups give a plane's share: no start
        if f.gravity_circulation().is_some() {
            return None;
        }
        let mut orbits = Rotor::gravity_orbits(f, &newton);
        if orbits.is_empty() && matches!(rotor, Rotor::Planar(p) if p.s2 > 0.0) {
            // the planar rotor with an eccentric race on supports that differ by direction,
            // n >= 3 equal balls: the family breaks into isolated orbits with the balls in two
            // groups, as under gravity; every placement shot, the least growth rate analysed,
            // the others listed (audit 25's F3: the scan analysed the stable orbit, reached by
            // continuation, and said nothing of its unstable mirror, +9.6e-5 against -9.5e-5
            // 1/s at 332.6 rad/s). Empty for any other planar rotor (split_guesses)
            orbits = Rotor::planar_split_orbits(f, &newton);
        }
        if orbits.is_empty() {
            // a spatial rotor's partially balanced equilibria from each candidate start, the
            // least growth rate analysed, the others listed (Rotor::partial_states)
            let near = carried
                .lock()
                .ok()
                .and_then(|c| c.iter().min_by(|p, q| (p.0 - omega).abs().total_cmp(&(q.0 - omega).abs()).then(p.0.total_cmp(&q.0))).map(|(_, x)| x.clone()))
                .unwrap_or_default();
            orbits = Rotor::partial_states_from(f, &newton, &near);
            let kept: Vec<Vec<f64>> = orbits.iter().map(|(x, _)| x.clone()).collect();
            if let Ok(mut c) = carried.lock() {
                c.push((omega, kept));
            }
        }
        let start = orbits.first().map(|(x, _)| x.clone());
        // every orbit found: the one the scan settles on is told apart by its placement below
        if let Ok(mut kept) = orbits_at.lock() {
            kept.push((omega, orbits.into_iter().map(|(_, o)| o).collect()));
        }
        Rotor::first_start(f, start)
    };
    // the last resort, only where no state is found from those starts and the neighbour's:
    // the planar rotor's orbit with n >= 3 balls in two groups on supports that differ by
    // direction (Rotor::planar_split_orbits: with an eccentric race the family breaks into
    // such orbits, and the closed form's member is none), the least growth rate first
    let last = |f: &Field, _: f64| Rotor::planar_split_orbits(f, &newton).into_iter().next().map(|(x, _)| x);
    // the balanced state wherever Newton reaches one (Rotor::settle_balanced, the commands' one
    // rule), each state's classification kept for its point (one orbit integration, not two)
    let classes: std::sync::Mutex<Vec<(Vec<f64>, (StateKind, f64))>> = Default::default();
    let settle = |f: &Field, found: StationaryState, hint: Option<&[f64]>, tried: Option<&[f64]>| {
        let (state, class) = Rotor::settle_balanced(f, found, hint, tried, &newton);
        if let Ok(mut c) = classes.lock() {
            c.push((state.x.clone(), class));
        }
        state
    };
    let Outcome { value: scan, mut stopped } = speed_scan_with_last(field_at, guess, last, settle, speeds, &opts, control).map_err(|e| match e {
        crate::analysis::AnalysisError::Model(e) => e,
        e => Error::invalid("speeds", e.to_string()),
    })?;
    let orbits_at = orbits_at.into_inner().unwrap_or_default();
    let classes = classes.into_inner().unwrap_or_default();
    let mut member_psi = vec![];
    let mut family_dimension = 0;
    let mut points: Vec<SpeedPoint> = scan
        .points
        .iter()
        .map(|p| {
            let fam = p.state.as_ref().map_or(0, |s| s.family_dimension);
            family_dimension = family_dimension.max(fam);
            let field = p.state.as_ref().and_then(|_| rotor.field(p.omega).ok());
            let (amplitude, state, residual, psi) = match (&field, &p.state) {
                (Some(f), Some(s)) => {
                    let (kind, residual) = classes.iter().rev().find(|(x, _)| *x == s.x).map_or_else(|| Rotor::classify(f, &s.x), |(_, c)| *c);
                    (Some(amplitude(f, &s.x)), Some(kind), Some(residual), ball_angles(f, &s.x))
                }
                _ => (None, None, None, vec![]),
            };
            if member_psi.is_empty() && fam > 0 {
                member_psi = psi.clone();
            }
            SpeedPoint {
                omega: p.omega,
                verdict: p.stability.as_ref().map(|s| s.verdict),
                abscissa: p.stability.as_ref().map(|s| s.abscissa),
                threshold: p.stability.as_ref().map(|s| s.threshold),
                family_dimension: fam,
                amplitude,
                failure: p.failure.as_ref().map(|f| explain_failure(rotor, p.omega, f)),
                analysed: floor(p.omega).is_none(),
                state,
                state_basis: state.map(|_| if matches!(rotor, Rotor::Linear(_)) { StateBasis::RaceWhirl } else { StateBasis::Residual }),
                residual,
                // the placements' other orbits at this grid speed, less the one analysed
                other_orbits: match (rotor, orbits_at.iter().find(|(w, _)| *w == p.omega)) {
                    (Rotor::Spatial(r), Some((_, found))) => found.iter().filter(|o| !same_placement(r, &o.member_psi, &psi)).cloned().collect(),
                    (Rotor::Planar(_), Some((_, found))) => found.iter().filter(|o| !same_angles(&o.member_psi, &psi)).cloned().collect(),
                    (Rotor::Linear(r), Some((_, found))) => {
                        let sizes: Vec<usize> = r.balancers.iter().map(|b| b.balls).collect();
                        found.iter().filter(|o| !same_in_planes(&sizes, &o.member_psi, &psi)).cloned().collect()
                    }
                    _ => vec![],
                },
                member_psi: psi,
                family: None,
                family_verdict: None,
            }
        })
        .collect();
    if member_psi.is_empty() {
        member_psi = points.iter().find(|p| p.state.is_some()).map_or(vec![], |p| p.member_psi.clone());
    }
    let family = if family_dimension > 0 {
        let states: Vec<Option<&StationaryState>> = scan.points.iter().map(|p| p.state.as_ref()).collect();
        let (fam, why) = family_over_speed(rotor, &mut points, &states, family_dimension, &opts.newton, control);
        stopped = stopped.or(why);
        Some(fam)
    } else {
        None
    };
    let value = RotorStability {
        model: rotor.model_name(),
        kind,
        stable_ranges: scan.stable_ranges,
        points,
        family_dimension,
        member_psi,
        family,
        has_unbalance: rotor.has_unbalance(),
        residual_scale: rotor.residual_scale(),
        speeds_asked: speeds.len(),
        refined_speeds: scan.refined.iter().map(|p| p.omega).collect(),
    };
    Ok(Outcome { value, stopped })
}

/// The sampling of a family in [`stability_over_speed`]: continuation at steps of 0.1 rad
/// (scaled arclength) for one parameter, 200 random members for more
/// ([`crate::analysis::FamilyOptions`]); a periodic orbit's family at 0.2 and 40 members (each
/// member is a shooting).
fn family_options(field: &Field, newton: &NewtonOptions) -> FamilyOptions {
    let periodic = field.period().is_some();
    let angles = ball_coordinates(field).collect();
    FamilyOptions {
        step: if periodic { 0.2 } else { 0.1 },
        samples: if periodic { 40 } else { 200 },
        max_members: if periodic { 400 } else { 2000 },
        angles,
        newton: newton.clone(),
        // the least and most stable member searched for beyond the sample (review 22: a member
        // of three bunched balls, unstable where all 200 drawn were stable)
        refine_extremes: true,
        ..FamilyOptions::default()
    }
}

/// Newton's options of the general route at one speed, shared by the speed scan, the
/// Campbell diagram and the map's cells: the defaults, and for a periodic orbit the shooting at
/// rtol 1e-10 (not the default 1e-12: 5.5x faster on the two-plane rotor) with 20 iterations;
/// the multipliers near 1 stay good to ~1e-9, inside `FLOQUET_TOLERANCE` (1e-8).
pub(crate) fn newton_options(periodic: bool) -> NewtonOptions {
    let mut o = NewtonOptions::default();
    if periodic {
        o.max_iterations = 20;
        o.rtol = 1e-10;
    }
    o
}

/// [`family_options`] (or a map cell's) with the bunched members through `state` as seeds
/// ([`bunched_members`]; for a family of dimension `k ≥ 2`, where the sample is random).
pub(crate) fn with_bunched(mut opts: FamilyOptions, field: &Field, state: &StationaryState) -> FamilyOptions {
    if state.family_dimension >= 2 {
        opts.seeds = bunched_members(field, &state.x);
    }
    opts
}

/// The family through the member `state` at speed `omega`, summarised; `None` where it
/// cannot be followed.
fn family_point(rotor: &Rotor, omega: f64, state: &StationaryState, newton: &NewtonOptions) -> Option<FamilyPoint> {
    let f = rotor.field(omega).ok()?;
    let fam: Family = family(&f, state, &with_bunched(family_options(&f, newton), &f, state)).ok()?;
    let (hi, lo) = fam.extremes()?;
    let name = |m: &crate::analysis::FamilyMember| Member {
        parameter: m.parameter.clone(),
        psi: ball_angles(&f, &m.state.x),
        abscissa: m.stability.abscissa,
        verdict: m.stability.verdict,
    };
    Some(FamilyPoint {
        members: fam.members.len(),
        drawn: fam.drawn,
        bunched: fam.seeded,
        searched: fam.searched,
        stable_members: fam.stable_count(),
        verdict: fam.verdict(),
        closed: fam.closed,
        length: fam.length,
        least_stable: name(hi),
        most_stable: name(lo),
        stable_parameter_ranges: fam.stable_ranges(),
    })
}

/// The family's stability at each point of the scan, and the speed ranges where all and where
/// some sampled members are stable: the family is followed at every grid speed with one (in
/// parallel), so that every such point says which of its members are stable
/// ([`SpeedPoint::family`]); between two grid speeds whose family verdicts differ, the
/// end is located to `1e-9` relative in `Ω` where the largest (all) or the smallest (some)
/// abscissa over the sampled members crosses 0, by regula falsi (Illinois) safeguarded by
/// bisection, each trial's family followed from the member Newton reaches from the closed form
/// there (else from the neighbour's member).
fn family_over_speed(
    rotor: &Rotor,
    points: &mut [SpeedPoint],
    states: &[Option<&StationaryState>],
    dimension: usize,
    newton: &NewtonOptions,
    control: &Control,
) -> (FamilyStability, Option<StopReason>) {
    // Every grid speed with a family is followed, in parallel (the control asked before each).
    // (Round 3 session 3 followed only every 8th speed and those whose verdict was not already
    // "some" from members known there: on the washer it cost more than following every speed,
    // 3.34 s against 2.79 s, and left points[].family absent in the "some" band.)
    let skipped = std::sync::atomic::AtomicBool::new(false);
    // the progress observer is told the families followed after the grid speeds the scan
    // reported (`grid + done` of `grid + total`): on a modest FE model with three balls in a
    // plane each family costs seconds, and without this the bar stood full for minutes
    // (audit 21's F2)
    let grid = points.len() as u64;
    let total = states.iter().filter(|s| s.is_some_and(|s| s.family_dimension > 0)).count() as u64;
    let done = std::sync::atomic::AtomicU64::new(0);
    let families: Vec<Option<FamilyPoint>> = points
        .par_iter()
        .zip(states.par_iter())
        .map(|(p, st)| {
            let st = st.filter(|s| s.family_dimension > 0)?;
            if control.should_stop().is_some() {
                skipped.store(true, std::sync::atomic::Ordering::Relaxed);
                return None;
            }
            let fp = family_point(rotor, p.omega, st, newton);
            let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            control.report(grid + d, grid + total);
            fp
        })
        .collect();
    for (p, f) in points.iter_mut().zip(families) {
        p.family_verdict = f.as_ref().map(|f| f.verdict);
        p.family = f;
    }
    let mut stopped = skipped.into_inner().then(|| control.should_stop().unwrap_or(StopReason::Interrupted));
    // the family's extreme abscissas at a speed off the grid
    let extremes_at = |omega: f64, near: Option<&[f64]>| -> Option<(f64, f64)> {
        let f = rotor.field(omega).ok()?;
        let starts = [Rotor::guess(&f), near.map(|x| x.to_vec())];
        let state = starts.iter().flatten().find_map(|g| stationary(&f, g, newton).ok().filter(|s| s.family_dimension > 0))?;
        let fp = family_point(rotor, omega, &state, newton)?;
        Some((fp.least_stable.abscissa, fp.most_stable.abscissa))
    };
    // which = 0: all members (largest abscissa < 0); 1: some (smallest < 0)
    let value = |which: usize, p: &SpeedPoint| p.family.as_ref().map(|f| if which == 0 { f.least_stable.abscissa } else { f.most_stable.abscissa });
    let good = |which: usize, p: &SpeedPoint| {
        p.family_verdict.is_some_and(|v| if which == 0 { v == FamilyVerdict::AllStable } else { v != FamilyVerdict::NoneStable })
    };
    // every range end's bracket, (which, i): between two analysed speeds only (as the scan's
    // own ranges); located in parallel, each by its own sequence of families (on two ball
    // planes of three balls each, the all- and the some-members ends took 35 of the 72 s of
    // `stability` one after the other: walk 29)
    let brackets: Vec<(usize, usize)> = if stopped.is_some() {
        vec![]
    } else {
        (0..2)
            .flat_map(|which| (0..points.len().saturating_sub(1)).map(move |i| (which, i)))
            .filter(|&(which, i)| {
                let (a, b) = (&points[i], &points[i + 1]);
                good(which, a) != good(which, b) && a.verdict.is_some() && b.verdict.is_some()
            })
            .collect()
    };
    let located: Vec<((usize, usize), std::result::Result<f64, StopReason>)> = brackets
        .into_par_iter()
        .map(|(which, i)| {
            let (a, b) = (&points[i], &points[i + 1]);
            let near = states[i].or(states[i + 1]).map(|s| s.x.clone());
            let g = |w: f64| extremes_at(w, near.as_deref()).map(|e| if which == 0 { e.0 } else { e.1 });
            ((which, i), locate(a.omega, b.omega, value(which, a), value(which, b), good(which, a), g, control))
        })
        .collect();
    // the ends located (those a stop cut short are not: their ranges end at the grid speed)
    let mut boundaries = [vec![None; points.len()], vec![None; points.len()]];
    for ((which, i), r) in located {
        match r {
            // a family's range ends are where its extreme abscissa crosses 0, never a switch
            // of state
            Ok(w) => boundaries[which][i] = Some((w, false)),
            Err(why) => stopped = stopped.or(Some(why)),
        }
    }
    // the scan's own rule (one function: session 18 found the two copies the same)
    let ranges = [0, 1].map(|which| crate::analysis::assemble_ranges(|i| points[i].omega, |i| good(which, &points[i]), &boundaries[which]));
    let [all, some] = ranges;
    let counts: Vec<usize> = points.iter().filter_map(|p| p.family.as_ref().map(|f| f.members)).collect();
    let members_analysed = counts.iter().min().zip(counts.iter().max()).map(|(a, b)| [*a, *b]);
    let analysed = match members_analysed {
        Some([a, b]) if a == b => format!("{a} members analysed at each grid speed followed (points[].family.members)"),
        Some([a, b]) => format!("{a}-{b} members analysed per grid speed followed (points[].family.members)"),
        None => "no member analysed".to_string(),
    };
    let parameterisation = if dimension == 1 {
        format!(
            "one-parameter family (n − 2 = 1 free parameter): the balls' angles move together keeping Σ m r e^{{iψ}} (the balancing condition) fixed; \
             parameter s = arclength along the family in the balls' angles (rad, the other states scaled by the model's scales), s = 0 at the member Newton reaches from the closed form (member_psi); \
             swept by continuation at steps of 0.1 until it closes (all round) or ends, the least and the most stable member then refined by one parabolic step each, at every grid speed; {analysed}"
        )
    } else {
        let drawn = points.iter().find_map(|p| p.family.as_ref().map(|f| f.drawn)).unwrap_or(0);
        format!(
            "{dimension}-parameter family (Σ (n − 2) over the ball planes = {dimension} free parameters): at every grid speed the member Newton reaches and {drawn} points drawn, each that member displaced along the family's tangent space by π times coefficients uniform in [−1, 1]^{dimension} (fixed seed) and corrected onto the family by minimum-norm Newton (those where it fails or leaves the family dropped: points[].family.drawn), with the bunched members (each plane's balls in two coinciding groups keeping its Σ m r e^{{iψ}}: the family's corners, points[].family.bunched), then the least and the most stable member searched for beyond them (a compass search over those coefficients from the extreme members: points[].family.searched); {analysed}; not a sweep: a stable or unstable island smaller than the sampling can be missed"
        )
    };
    (FamilyStability { dimension, parameterisation, members_analysed, all_members_stable: all, some_members_stable: some }, stopped)
}

/// Where `g` (the family's largest or smallest abscissa) crosses 0 between `lo` and `hi`
/// (`good_lo`: whether `lo` is on the side where it is negative), to `1e-9` relative:
/// regula falsi (Illinois) on `g`, bisection where `g` is missing or the bracket stops halving;
/// `control` asked before each trial (stopped: why, and no end).
fn locate(
    lo: f64,
    hi: f64,
    g_lo: Option<f64>,
    g_hi: Option<f64>,
    good_lo: bool,
    g: impl Fn(f64) -> Option<f64>,
    control: &Control,
) -> std::result::Result<f64, StopReason> {
    let (mut lo, mut hi, mut f_lo, mut f_hi) = (lo, hi, g_lo, g_hi);
    let mut last_side = 0i8;
    let mut slow = 0;
    for _ in 0..100 {
        let width = (hi - lo).abs();
        let tol = 1e-9 * lo.abs().max(hi.abs());
        if width <= tol {
            break;
        }
        let mut mid = 0.5 * (lo + hi);
        if let (Some(fl), Some(fh), true) = (f_lo, f_hi, slow < 2) {
            if fl * fh < 0.0 {
                let secant = lo - fl * (hi - lo) / (fh - fl);
                let (a, b) = (lo.min(hi) + 0.5 * tol, lo.max(hi) - 0.5 * tol);
                if a < b && secant.is_finite() {
                    mid = secant.clamp(a, b);
                }
            }
        }
        if mid == lo || mid == hi {
            break;
        }
        if let Some(why) = control.should_stop() {
            return Err(why);
        }
        let v = g(mid);
        let good = v.is_some_and(|v| v < 0.0);
        if good == good_lo {
            if last_side == -1 {
                f_hi = f_hi.map(|f| 0.5 * f);
            }
            lo = mid;
            f_lo = v;
            last_side = -1;
        } else {
            if last_side == 1 {
                f_lo = f_lo.map(|f| 0.5 * f);
            }
            hi = mid;
            f_hi = v;
            last_side = 1;
        }
        slow = if (hi - lo).abs() > 0.5 * width { slow + 1 } else { 0 };
    }
    Ok(0.5 * (lo + hi))
}

/// A scan's failure in the user's terms: where the closed form gives no state, say which state
/// does not exist and why.
fn explain_failure(rotor: &Rotor, omega: f64, failure: &str) -> String {
    if let Some(why) = rotor.field(omega).ok().and_then(|f| f.gravity_circulation()) {
        return why;
    }
    if let (Rotor::Spatial(s), true) = (rotor, failure.starts_with("no periodic orbit found")) {
        if let Some(why) = gravity_slip(s, omega) {
            return format!("{failure}; {why}");
        }
    }
    if !failure.starts_with("no starting point") {
        return failure.to_string();
    }
    match rotor {
        Rotor::Planar(_) => "no semi-balanced state at this speed: the balls cannot supply the unbalance it needs (|B| > n m3 r, planar::stationary)".into(),
        Rotor::Spatial(_) => "no balanced state: the balls' capacity Σ m R of a plane is below the unbalance it must cancel".into(),
        Rotor::Linear(r) => format!(
            "no balanced state ({}) and no start for the partially balanced one (no balls, no unbalance, or the structure singular at this speed)",
            crate::linear_rotor::partial::why_not_balanced(r)
        ),
    }
}

/// Why a spatial rotor under gravity has no periodic orbit at `omega` (rad/s), where the
/// evidence is clear: gravity across the axis drags each ball, swinging once a revolution
/// (amplitude `g/(R Ω sqrt(Ω² + β²))`, `β = h_A/m`), behind the rotor with a mean torque
/// `m g² β / (2 Ω (Ω² + β²))` (second-order average of the swing against the gravity torque
/// `m g R cos φ`), while the most the rotor's whirl can hold a ball with is of order
/// `m² R² Ω⁴ / |k − M Ω²|` (the ball's own unbalance's response, `k` the supports' softer
/// direction's total). Said only where the drag exceeds that hold 10 times (the hold is an
/// order of magnitude); then the balls slip behind the rotor at `g² / (2 Ω R² (Ω² + β²))`
/// rad/s and no orbit exists: a run at 30 rad/s on the two-plane example with supports of
/// 5e8/6e8 N/m drifts at 0.0733 rad/s, the closed form 0.0730 (docs/notes/stability.md,
/// session 13).
fn gravity_slip(s: &crate::spatial::dynamics::rotor::SpatialRotor, omega: f64) -> Option<String> {
    use crate::error::fmt_num;
    let g2 = s.gravity[0] * s.gravity[0] + s.gravity[1] * s.gravity[1];
    let w = omega.abs();
    if !(g2 > 0.0 && w > 0.0) {
        return None;
    }
    let m_total = s.total_mass();
    let k = (0..2).map(|i| s.supports.iter().map(|sp| sp.stiffness[i]).sum::<f64>()).fold(f64::INFINITY, f64::min);
    let detuned = (k - m_total * w * w).abs();
    s.planes
        .iter()
        .filter(|p| p.n > 0 && p.ball_mass > 0.0 && p.race_radius > 0.0)
        .map(|p| {
            let (m, r, beta) = (p.ball_mass, p.race_radius, p.drag / p.ball_mass);
            let drag = m * g2 * beta / (2.0 * w * (w * w + beta * beta));
            let hold = m * m * r * r * w.powi(4) / detuned;
            let slip = g2 / (2.0 * w * r * r * (w * w + beta * beta));
            (drag, hold, slip)
        })
        .filter(|(drag, hold, _)| *drag > 10.0 * hold)
        .max_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)))
        .map(|(drag, hold, slip)| {
            format!(
                "no periodic orbit exists here: gravity drags each ball behind the rotor (a mean torque m g² β/(2Ω(Ω² + β²)) = {} N m) more than the rotor's whirl can hold it (~m² R² Ω⁴/|k − M Ω²| = {} N m), so the balls slip behind it at ~{} rad per revolution",
                fmt_num(drag),
                fmt_num(hold),
                fmt_num(slip * 2.0 * std::f64::consts::PI / w)
            )
        })
}

/// The cyclic relabellings of a plane of exactly three equal balls, as permutations of the
/// reduced state (angles and their rates; [`crate::analysis::FamilyOptions::relabellings`]):
/// they map the one-parameter family of balanced states onto itself and fix none of its
/// members (a member fixed by one has its three balls at one angle: `|Σ e^{iψ}| = 3`, the
/// capacity limit, not a family). Empty where the balls differ (planar `ball_masses`,
/// `ball_drags`) or no plane has three, and for the linear rotor (every member followed).
pub(crate) fn ball_rotations(f: &Field) -> Vec<Vec<usize>> {
    let (n, m, planes): (usize, usize, Vec<(usize, usize)>) = match f {
        Field::Linear(_) => return vec![],
        Field::Planar(p) => {
            let r = p.rotor();
            let equal = (0..r.n).all(|j| r.ball_mass(j) == r.ball_mass(0) && r.ball_drag(j) == r.ball_drag(0));
            (2 * (2 + r.n), 2 + r.n, if equal { vec![(2, r.n)] } else { vec![] })
        }
        Field::Spatial(s) => {
            let m = s.coords();
            let mut first = m - s.rotor().balls();
            let mut planes = vec![];
            for p in &s.rotor().planes {
                planes.push((first, p.n));
                first += p.n;
            }
            (2 * m, m, planes)
        }
    };
    let mut out = vec![];
    for (first, count) in planes {
        if count != 3 {
            continue;
        }
        for shift in [1, 2] {
            let mut p: Vec<usize> = (0..n).collect();
            for j in 0..3 {
                p[first + j] = first + (j + shift) % 3;
                p[m + first + j] = m + first + (j + shift) % 3;
            }
            out.push(p);
        }
    }
    out
}

/// The indices of the balls' angles in a reduced state (all planes in order): the planar
/// rotor's `2..2 + n`, the spatial and the linear rotor's last `n` coordinates.
pub(crate) fn ball_coordinates(f: &Field) -> std::ops::Range<usize> {
    match f {
        Field::Planar(p) => 2..2 + p.rotor().n,
        Field::Spatial(s) => s.coords() - s.rotor().balls()..s.coords(),
        Field::Linear(l) => l.rotor().dofs()..l.coords(),
    }
}

/// The balls' angles in a reduced state.
pub(crate) fn ball_angles(f: &Field, x: &[f64]) -> Vec<f64> {
    x[ball_coordinates(f)].to_vec()
}

/// Each plane's balls: `(index of its angle in the reduced state, mass, drag)` per ball, planes
/// in order (the planar rotor's one plane with its `ball_masses`, `ball_drags`; a spatial or
/// linear rotor's planes of equal balls).
fn ball_planes(f: &Field) -> Vec<Vec<(usize, f64, f64)>> {
    match f {
        Field::Planar(p) => {
            let r = p.rotor();
            vec![(0..r.n).map(|j| (2 + j, r.ball_mass(j), r.ball_drag(j))).collect()]
        }
        Field::Spatial(s) => {
            let mut first = s.coords() - s.rotor().balls();
            let mut out = vec![];
            for p in &s.rotor().planes {
                out.push((first..first + p.n).map(|i| (i, p.ball_mass, p.drag)).collect());
                first += p.n;
            }
            out
        }
        Field::Linear(l) => {
            let mut first = l.rotor().dofs();
            let mut out = vec![];
            for p in &l.rotor().balancers {
                out.push((first..first + p.balls).map(|i| (i, p.ball_mass, p.drag)).collect());
                first += p.balls;
            }
            out
        }
    }
}

/// The most groupings [`two_group_angles`] keeps for one plane (balls that all differ: a subset).
const MAX_GROUPINGS: usize = 32;

/// The most codes (ways of splitting the kinds of ball) [`two_group_angles`] tries for one plane.
const MAX_GROUPING_CODES: usize = 4096;

/// The ways of putting one plane's balls at two angles, `ψ_j = a` for the balls of the first
/// group and `b` for the others, that keep the plane's resultant `C = Σ m_j e^{iψ_j}` of the
/// angles in `x` (so the rotor's state, which depends on the balls through their resultants
/// alone, stays that of `x`): with group masses `M_1`, `M_2` the triangle
/// `M_1 e^{ia} + M_2 e^{ib} = C`, `a = arg C ± acos((M_1² + |C|² − M_2²)/(2 M_1 |C|))`,
/// `b = arg(C − M_1 e^{ia})` (the two mirror solutions), which exists where
/// `|M_1 − M_2| < |C| < M_1 + M_2` (strictly, by `1e-9` of the plane's ball mass: at either
/// limit every ball is on one line, where the family's dimension changes) and `C ≠ 0`; at most
/// [`MAX_GROUPINGS`] of the first [`MAX_GROUPING_CODES`] splits (balls that all differ have
/// `2^(n−1)` of them). Balls of equal mass and drag are interchangeable
/// (a relabelling is the same physical state, with the same stability): one grouping per choice
/// of how many of each kind go in the first group, a grouping and its complement once, and of a
/// grouping that its complement's relabelling is (equal halves) the one mirror. Each is the
/// angles of the plane's balls (in `plane`'s order), each within `π` of its angle in `x`.
fn two_group_angles(plane: &[(usize, f64, f64)], x: &[f64]) -> Vec<Vec<f64>> {
    // the kinds of ball, each with its balls (positions in `plane`)
    let mut kinds: Vec<(f64, f64, Vec<usize>)> = vec![];
    for (j, &(_, m, c)) in plane.iter().enumerate() {
        match kinds.iter_mut().find(|k| k.0 == m && k.1 == c) {
            Some(k) => k.2.push(j),
            None => kinds.push((m, c, vec![j])),
        }
    }
    let (cx, cy) = plane.iter().fold((0.0, 0.0), |(cx, cy), &(i, m, _)| (cx + m * x[i].cos(), cy + m * x[i].sin()));
    let r = cx.hypot(cy);
    let total: f64 = plane.iter().map(|b| b.1).sum();
    let tau = std::f64::consts::TAU;
    let mut out = vec![];
    // how many of each kind in the first group, counted as a mixed-radix number
    let sizes: Vec<usize> = kinds.iter().map(|k| k.2.len()).collect();
    // at most MAX_GROUPING_CODES codes tried and MAX_GROUPINGS groupings kept: balls that all
    // differ have 2^(n−1) groupings (review 24b: 70 for eight masses, 1006 for twelve; the
    // product overflows from 64 kinds), so the seeds of many different balls are a subset
    let combos: usize = sizes.iter().try_fold(1usize, |p, s| p.checked_mul(s + 1)).unwrap_or(usize::MAX).min(MAX_GROUPING_CODES);
    for code in 1..combos.saturating_sub(1) {
        if out.len() >= MAX_GROUPINGS {
            break;
        }
        let mut rest = code;
        let take: Vec<usize> = sizes
            .iter()
            .map(|s| {
                let t = rest % (s + 1);
                rest /= s + 1;
                t
            })
            .collect();
        let complement: Vec<usize> = sizes.iter().zip(&take).map(|(s, t)| s - t).collect();
        // a grouping and its complement are the same placement with the groups swapped
        if take > complement {
            continue;
        }
        let m1: f64 = kinds.iter().zip(&take).map(|(k, &t)| k.0 * t as f64).sum();
        let m2 = total - m1;
        // strictly inside the triangle's limits: at |M1 − M2| = |C| or M1 + M2 = |C| every ball
        // is on one line and the family's dimension changes there (review 24b: ten balls of
        // 0.030-0.041 kg on examples/planar.toml, 13 splits exactly at the limit, each a
        // "member" with one zero eigenvalue more than the family's)
        let margin = 1e-9 * total;
        if r == 0.0 || !(r < m1 + m2 - margin && r > (m1 - m2).abs() + margin) {
            continue;
        }
        // equal halves: the second mirror is the first with the groups relabelled
        let branches: &[f64] = if take == complement { &[1.0] } else { &[1.0, -1.0] };
        for &branch in branches {
            let (a, b) = crate::spatial::dynamics::field::triangle_angles(m1, [cx, cy], r, m2, branch);
            let mut angles = vec![b; plane.len()];
            for (k, &t) in kinds.iter().zip(&take) {
                for &j in &k.2[..t] {
                    angles[j] = a;
                }
            }
            for (angle, &(i, _, _)) in angles.iter_mut().zip(plane) {
                *angle -= tau * ((*angle - x[i]) / tau).round();
            }
            out.push(angles);
        }
    }
    out
}

/// The family's bunched members through the member `x` ([`crate::analysis::FamilyOptions::seeds`]):
/// the states with the balls of each plane of three or more in two coinciding groups, the
/// plane's resultant `C = Σ m_j e^{iψ_j}` kept (`M_1 e^{ia} + M_2 e^{ib} = C`: a triangle, two
/// mirror solutions; one grouping per choice of how many balls of each kind, mass and drag, go
/// in the first group, a grouping and its complement once; at most `MAX_GROUPINGS` over the planes). Those are the family's corners,
/// finitely many, where its extremes can sit: three or more groups leave a family of dimension
/// `groups − 2 ≥ 1`, one group is the capacity's limit. The other coordinates are those of `x`
/// (the rotor's state depends on the balls through the resultants alone); every combination
/// over the planes (a plane of fewer than three balls, or without a grouping, as in `x`). The
/// balls are point masses here (the fields refuse real balls), so coinciding balls are the
/// model's own states, not an overlap.
pub fn bunched_members(f: &Field, x: &[f64]) -> Vec<Vec<f64>> {
    let mut out: Vec<Vec<f64>> = vec![x.to_vec()];
    for plane in ball_planes(f).iter().filter(|p| p.len() >= 3) {
        let groupings = two_group_angles(plane, x);
        if groupings.is_empty() {
            continue;
        }
        let mut next = vec![];
        for y in &out {
            next.push(y.clone());
            // (at most MAX_GROUPINGS seeds over the planes together)
            for g in groupings.iter().take(MAX_GROUPINGS.saturating_sub(next.len() - 1)) {
                let mut z = y.clone();
                for (&(i, _, _), &a) in plane.iter().zip(g) {
                    z[i] = a;
                }
                next.push(z);
            }
        }
        out = next;
    }
    out.remove(0); // x itself
    out
}

/// The angle (rad, in `[0, π/2]`) between a ball at `psi` and the line through the axis at
/// angle `along`, either side of it.
pub(crate) fn off_line(psi: f64, along: f64) -> f64 {
    let w = (psi - along).rem_euclid(std::f64::consts::PI);
    w.min(std::f64::consts::PI - w)
}

/// The most periods of the fastest natural vibration (`2π/ω_fast`) that one revolution of a
/// periodic orbit may span ([`Rotor::periodic_floor`]). Measured (docs/notes/stability.md): a
/// speed just above the floor costs ~1 s a speed, one below more, growing as `1/Ω`; at 100
/// the floor refused speeds with an answer costing seconds (stiff supports under gravity:
/// 70.5 rad/s, though the balls hold from ~9 rad/s).
pub const PERIODS_PER_REVOLUTION: f64 = 1000.0;

/// The message of a speed below [`Rotor::periodic_floor`] (both in the rotor's speed unit).
pub(crate) fn below_floor(w: f64, floor: f64) -> String {
    use crate::error::fmt_num;
    below_floor_words(&fmt_num(w), &fmt_num(floor))
}

/// The message of a speed below [`Rotor::periodic_floor`], the speed and the floor as written
/// (with their unit, where the caller knows it): "`w` is below `floor`, the slowest speed …".
pub fn below_floor_words(w: &str, floor: &str) -> String {
    use crate::error::fmt_num;
    format!(
        "{w} is below {floor}, the slowest speed the periodic-orbit analysis resolves: the fastest natural frequency over {} (a revolution longer than {} of its periods is not integrated)",
        fmt_num(PERIODS_PER_REVOLUTION),
        fmt_num(PERIODS_PER_REVOLUTION)
    )
}

/// The residual (fraction of the unbalance: [`Rotor::residual`]) at or below which a state is
/// balanced whatever its balls' placement: Newton's and the shooting's residuals (1e-12,
/// 1e-10) leave ~1e-10 of the unbalance, the old classifier's tolerance was this.
const BALANCED_EXACTLY: f64 = 1e-6;

/// A state on a periodic orbit whose balls are not bunched is balanced (to the residual it
/// carries) while the residual is at most this fraction of the unbalance, and not balanced
/// above it where the balls' capacity could cancel it: the simulation's own threshold
/// ([`crate::spatial::dynamics::simulate::BALANCE_TOLERANCE`], 5 %), so that `stability` and
/// `simulate` call one state by one word (session 15: the analysis allowed a tenth, the run 5 %;
/// an orbit with a residual of 0.09 read "balanced" in one and not in the other). Two balls
/// opposite each other leave the whole unbalance (1); a balanced orbit's swing leaves its second
/// order (<= 1e-4 on examples/spatial_two_plane.toml, <= 0.022 on the washing-machine example
/// under gravity down to 276 rpm).
const BALANCE_TOLERANCE: f64 = crate::spatial::dynamics::simulate::BALANCE_TOLERANCE;

/// The states over which a state's means are taken ([`Rotor::residual`], the linear rotor's
/// race centres), row-major (the trapezoidal rule over them is exact for the orbit's harmonics
/// below the 64th): the periodic orbit's 64 samples
/// ([`crate::analysis::orbit_samples`] at rtol 1e-10, the shooting's), or `x` alone at an
/// equilibrium or where the orbit cannot be integrated again.
pub(crate) fn orbit_rows<F: VectorField + ?Sized>(field: &F, x: &[f64]) -> Vec<f64> {
    field.period().and_then(|period| crate::analysis::orbit_samples(field, x, period, 1e-10).ok()).unwrap_or_else(|| x.to_vec())
}

/// The mean of `f(row)` over the rows of length `n` of `rows`.
pub(crate) fn mean_of(rows: &[f64], n: usize, f: impl Fn(&[f64]) -> Vec<f64>) -> Vec<f64> {
    let m = (rows.len() / n) as f64;
    let mut mean: Vec<f64> = vec![];
    for row in rows.chunks(n) {
        let v = f(row);
        if mean.is_empty() {
            mean = vec![0.0; v.len()];
        }
        for (a, v) in mean.iter_mut().zip(v) {
            *a += v / m;
        }
    }
    mean
}

/// [`Rotor::residual`] of the spatial rotor with ball `j`'s `e^{iψ_j}` at `units[j]`.
fn spatial_residual(r: &SpatialRotor, units: &[[f64; 2]]) -> f64 {
    let (s0, c0) = (r.static_unbalance(), r.couple_unbalance());
    let zr = r.z_reference();
    let zl = r.planes.iter().filter(|p| p.n > 0).map(|p| (p.z - zr).abs()).chain(r.unbalances.iter().map(|u| (u.z - zr).abs())).fold(0.0, f64::max);
    let zl = if zl > 0.0 { zl } else { 1.0 };
    let (mut rs, mut rc, mut cap) = (s0, c0, 0.0);
    let mut j = 0;
    for p in r.planes.iter().filter(|p| p.n > 0) {
        let mr = p.ball_mass * p.race_radius;
        let z = p.z - zr;
        for _ in 0..p.n {
            let [cs, sn] = units[j];
            rs[0] += mr * cs;
            rs[1] += mr * sn;
            rc[0] += z * mr * cs;
            rc[1] += z * mr * sn;
            cap += mr;
            j += 1;
        }
    }
    rs[0].hypot(rs[1]).max(rc[0].hypot(rc[1]) / zl) / unbalance_scale(s0[0].hypot(s0[1]).max(c0[0].hypot(c0[1]) / zl), cap)
}

/// The denominator of a residual: the unbalance `u` (kg m); where there is none to speak of
/// (`u ≤ 1e-6 cap`, [`NO_UNBALANCE`]), the balls' capacity `cap = Σ m_b R` itself, so that
/// the residual is the balls' own resultant over what they could produce. (Main at 21dbfc9
/// divided by `1e-6 cap` there: the balls' swing on an orbit under gravity, ~4e-7 of their
/// capacity on examples/spatial_two_plane.toml without unbalance at 350-440 rad/s, read as
/// 0.44 "of the unbalance", "not balanced", on a rotor with nothing to balance. Newton leaves
/// the resultant to ~1e-14 of `cap`, measured on a linear shaft with a pure couple at 1001
/// rad/s.) The scale steps at `u = 1e-6 cap` from `cap` to `1e-6 cap`: below it a residual
/// of the balls is measured against their capacity, above against the unbalance. The one rule
/// for the time-domain runs' residuals as well (spatial `summarise`, linear `ending`), so that
/// a run and `stability` agree on what "no unbalance" means.
pub(crate) fn unbalance_scale(u: f64, cap: f64) -> f64 {
    if u <= NO_UNBALANCE * cap {
        cap.max(f64::MIN_POSITIVE)
    } else {
        u
    }
}

/// An unbalance (kg m) at or below this fraction of the balls' capacity `Σ m_b R` is none to
/// speak of ([`Rotor::has_unbalance`]; the residuals' scale, [`Rotor::residual`]).
pub const NO_UNBALANCE: f64 = 1e-6;

/// Whether the spatial rotor's balls can cancel its unbalance (a balanced state exists): the
/// closed-form placement ([`SpatialField::balanced_guess`]: each plane's balls on the arc of
/// its share) exists (the capacity suffices) and leaves at most [`BALANCED_EXACTLY`] of it (one
/// plane cancels the static unbalance only: a nonzero couple about it stays).
fn spatial_can_balance(s: &SpatialField) -> bool {
    spatial_balance_exists(s.rotor())
}

/// [`spatial_can_balance`] from the rotor alone (no field, no speed): the one test of whether
/// a balanced state exists for `stability` and for a run's verdict (the spatial
/// `simulate`'s summary, which before session 34 compared the total capacity with the static
/// unbalance only and called runs "balanced" where a plane fell short of its share or one
/// plane faced a couple: walk 34, a residual couple of 1.6 % read "balanced").
pub(crate) fn spatial_balance_exists(r: &SpatialRotor) -> bool {
    let Some(psi) = crate::spatial::dynamics::field::balancing_ball_angles(r) else { return false };
    let units: Vec<[f64; 2]> = psi.iter().map(|a| [a.cos(), a.sin()]).collect();
    spatial_residual(r, &units) <= BALANCED_EXACTLY
}

/// Whether the balls at `psi` (rad, one plane) are bunched: every angle within `1e-6` rad of the
/// first, modulo `2π` (a plane at its capacity limit, [`StateKind::PartiallyBalanced`]); true
/// for one ball or none.
pub(crate) fn bunched(psi: &[f64]) -> bool {
    psi.iter().all(|a| {
        let w = (a - psi[0]).rem_euclid(std::f64::consts::TAU);
        w.min(std::f64::consts::TAU - w) <= 1e-6
    })
}

/// Whirl radius at the first balancer plane in turning axes: `|u|` of the planar rotor's C, the
/// spatial shaft's displacement at the first ball plane (or the first unbalance's plane), the
/// linear rotor's race centre of its first balancer plane
/// ([`crate::linear_rotor::runup::plane_positions`]; 0 without one).
pub(crate) fn amplitude(f: &Field, x: &[f64]) -> f64 {
    match f {
        Field::Planar(_) => x[0].hypot(x[1]),
        Field::Linear(l) => crate::linear_rotor::runup::plane_positions(l.rotor(), x).first().map_or(0.0, |c| c.0.hypot(c.1)),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `StateKind::key` is the JSON's word for each state (its serde name), which the map's CSV
    /// and Python's arrays print beside `stability`'s JSON.
    #[test]
    fn state_keys_are_the_json_names() {
        for k in [StateKind::Balanced, StateKind::SemiBalanced, StateKind::PartiallyBalanced, StateKind::NotBalanced] {
            assert_eq!(serde_json::to_value(k).unwrap(), serde_json::json!(k.key()));
        }
    }

    /// Paper 004's rotor with its race centred and `n` balls, as the planar model and as the
    /// linear rotor-bearing model ([`LinearRotor::from_planar`]: the same Jeffcott rotor with
    /// balls, a second route through other equations and another field).
    fn jeffcott(n: usize) -> (Rotor, Rotor) {
        let p = PlanarRotor { n, s2: 0.0, ..PlanarRotor::paper() };
        (Rotor::Planar(p.clone()), Rotor::Linear(LinearRotor::from_planar(&p).unwrap()))
    }

    #[test]
    fn the_linear_rotor_is_one_rotor_of_the_general_route() {
        let (planar, linear) = jeffcott(2);
        assert_eq!(linear.model_name(), "linear");
        // the same M = m1 + m2 + n m3 and k: sqrt(k/M) to round-off
        let (wp, wl) = (planar.natural_frequency(), linear.natural_frequency());
        assert!((wp - wl).abs() <= 1e-12 * wp, "{wp} vs {wl}");
        assert!(!linear.is_periodic());
        // the balanced state from each model's closed form: the balls at the same angles (Newton
        // to ~1e-12 on both: 1e-9 rad), the race centre on the axis (amplitude 0 to 1e-12 of the
        // unbalance's eccentricity s1 = m1 s1 / m1)
        for w in [150.0, 400.0] {
            let (fp, sp) = crate::rotor_campbell::stationary_at(&planar, w).unwrap();
            let (fl, sl) = crate::rotor_campbell::stationary_at(&linear, w).unwrap();
            let (ap, al) = (ball_angles(&fp, &sp.x), ball_angles(&fl, &sl.x));
            assert_eq!(ap.len(), 2);
            for (a, b) in ap.iter().zip(&al) {
                assert!((a - b).abs() <= 1e-9, "Ω {w}: ψ {ap:?} vs {al:?}");
            }
            let Rotor::Planar(p) = &planar else { unreachable!() };
            assert!(amplitude(&fl, &sl.x) <= 1e-12 * p.s1, "Ω {w}: {}", amplitude(&fl, &sl.x));
            assert_eq!(Rotor::state_kind(&fl, &sl.x), StateKind::Balanced);
        }
    }

    /// The other equilibrium of two balls on a whirling race: one ball on each side of the line
    /// of the whirl (planar `aligned_whirls_of` with `q = n_far − n_near = 0`: the balls'
    /// resultant is zero, so C whirls at the rotor's own unbalance response
    /// `u = m1 s1 Ω² / (k − M Ω² + i c Ω)`, `M = m1 + m2 + 2 m3`, a closed form independent of
    /// the field). Newton from it stays there on both the planar field and the linear rotor's
    /// field (so it is an equilibrium of both), and neither may call it balanced nor partially
    /// balanced (main at b7bef73 said "partially balanced" for the planar field, "balanced" for
    /// the linear one). Tolerances: Newton to ~1e-12 relative, so 1e-9 of the whirl radius.
    #[test]
    fn an_equilibrium_with_the_balls_opposite_is_not_balanced() {
        use num_complex::Complex64 as C;
        let (planar, linear) = jeffcott(2);
        let Rotor::Planar(p) = &planar else { unreachable!() };
        for w in [150.0, 400.0] {
            let d = C::new(p.k - p.total_mass() * w * w, p.c * w);
            let u = C::new(p.m1 * p.s1 * w * w, 0.0) / d;
            let phi = u.arg();
            let mut x = vec![0.0; 8];
            (x[0], x[1], x[2], x[3]) = (u.re, u.im, phi, phi + std::f64::consts::PI);
            for rotor in [&planar, &linear] {
                let f = rotor.field(w).unwrap();
                assert_eq!(f.dim(), 8, "{}", rotor.model_name());
                let s = stationary(&f, &x, &NewtonOptions::default()).unwrap();
                let a = amplitude(&f, &s.x);
                assert!((a - u.norm()).abs() <= 1e-9 * u.norm(), "{} Ω {w}: whirl {a} vs closed form {}", rotor.model_name(), u.norm());
                let psi = ball_angles(&f, &s.x);
                let gap = (psi[1] - psi[0]).rem_euclid(std::f64::consts::TAU);
                assert!((gap - std::f64::consts::PI).abs() <= 1e-9, "{} Ω {w}: ψ {psi:?}", rotor.model_name());
                assert_eq!(Rotor::state_kind(&f, &s.x), StateKind::NotBalanced, "{} Ω {w}", rotor.model_name());
            }
            // the balanced state at the same speed is still called balanced
            for rotor in [&planar, &linear] {
                let (f, s) = crate::rotor_campbell::stationary_at(rotor, w).unwrap();
                assert_eq!(Rotor::state_kind(&f, &s.x), StateKind::Balanced, "{} Ω {w}", rotor.model_name());
            }
        }
    }

    /// The spatial classifier on equilibria (Newton's fixed points, residual ~1e-12):
    /// examples/spatial_two_plane.toml without gravity, supports equal by direction. Its
    /// balanced state is balanced; Newton from each plane's two balls opposite each other (the
    /// structure at rest) reaches a state whose races whirl with the balls near the line of the
    /// whirl, both sides (their resultant ~0: the rotor's own unbalance response): not
    /// balanced (its residual is the whole unbalance, no plane bunched). A rotor with one
    /// plane at its centre of mass against a pure couple unbalance cannot be balanced: its
    /// stationary states are partially balanced (the plane at rest while the rotor rocks about
    /// it, its balls opposite: main at 85e6257 called them not balanced, the docs said
    /// partially balanced; no placement of one plane's balls cancels a couple about it).
    /// One placement of the balls is one orbit whatever the balls' labels within a plane and
    /// whole turns; planes are told apart (examples/spatial_two_plane.toml: two balls a plane).
    #[test]
    fn same_placement_is_per_plane_up_to_labels_and_turns() {
        let root = crate::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        let r = crate::config::spatial_simulation(&root).unwrap().rotor;
        assert_eq!(r.planes.iter().map(|p| p.n).collect::<Vec<_>>(), [2, 2]);
        let tau = std::f64::consts::TAU;
        let a = [0.1, 2.0, 3.0, -1.0];
        assert!(same_placement(&r, &a, &[2.0, 0.1 + tau, -1.0 + 1e-7, 3.0 - tau]));
        // the first plane's ball swapped with the second plane's: another placement
        assert!(!same_placement(&r, &a, &[3.0, 2.0, 0.1, -1.0]));
        assert!(same_placement(&r, &a, &[0.1, 2.0, 3.0, -1.0 + 0.5 * SAME_ANGLE]));
        assert!(!same_placement(&r, &a, &[0.1, 2.0, 3.0, -1.0 + 2.0 * SAME_ANGLE]));
        assert!(!same_placement(&r, &a, &a[..3]));
        // across the cut at 0 = 2π
        assert!(same_placement(&r, &[1e-9, 3.0, 1.0, 2.0], &[tau - 1e-9, 3.0, 2.0, 1.0]));
        // two balls together against two apart: not one placement though each ball has a match
        assert!(!same_placement(&r, &[1.0, 1.0, 0.0, 0.0], &[1.0, 2.0, 0.0, 0.0]));
    }

    #[test]
    fn the_spatial_classifier_on_equilibria_opposite_and_couple() {
        use crate::spatial::dynamics::{BallPlane, PointMass, RigidRotor, Support};
        let mut root = crate::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        crate::config::set(&mut root, "spatial.gravity", crate::config::parse_value("[0.0, 0.0, 0.0]")).unwrap();
        crate::config::set_number(&mut root, "supports.stiffness_left_y", 2.0e6).unwrap();
        crate::config::set_number(&mut root, "supports.stiffness_right_y", 3.0e6).unwrap();
        let rotor = Rotor::Spatial(crate::config::spatial_simulation(&root).unwrap().rotor);
        let (f, s) = crate::rotor_campbell::stationary_at(&rotor, 1000.0).unwrap();
        assert_eq!(Rotor::state_kind(&f, &s.x), StateKind::Balanced);
        let balls = ball_coordinates(&f);
        assert_eq!(balls.len(), 4, "two planes of two balls");
        let mut x = vec![0.0; f.dim()];
        x[balls.clone()].copy_from_slice(&[0.3, 0.3 + std::f64::consts::PI, 1.1, 1.1 + std::f64::consts::PI]);
        let o = stationary(&f, &x, &NewtonOptions::default()).unwrap();
        let psi = ball_angles(&f, &o.x);
        // opposite to within the tilted ring's push (2-3e-4 rad here)
        for pair in psi.chunks(2) {
            let gap = (pair[1] - pair[0]).rem_euclid(std::f64::consts::TAU);
            assert!((gap - std::f64::consts::PI).abs() <= 1e-2, "ψ {psi:?}");
        }
        assert!(amplitude(&f, &o.x) > 1e3 * amplitude(&f, &s.x), "{} vs {}", amplitude(&f, &o.x), amplitude(&f, &s.x));
        // each plane's two balls nearly opposite: their resultant ~0 (to the 1e-2 rad above:
        // 1e-2 of a ball's m R), so the residual is the unbalance itself (1 to 1e-2); not
        // bunched, and the capacity could cancel it: not balanced (main before 2026-11-29 said
        // partially balanced: "the balls cannot cancel the unbalance", false)
        let res = Rotor::residual(&f, &o.x);
        assert!((res - 1.0).abs() <= 2e-2, "residual {res}");
        assert_eq!(Rotor::state_kind(&f, &o.x), StateKind::NotBalanced, "ψ {psi:?}");
        // one plane at the centre of mass against a pure couple
        let couple = SpatialRotor::new(
            RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
            vec![Support::isotropic(-0.3, 1e5, 20.0), Support::isotropic(0.3, 1e5, 20.0)],
            vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.0, z: 0.2 }, PointMass { mass: 0.01, radius: 0.1, angle: std::f64::consts::PI, z: -0.2 }],
            vec![BallPlane::point_masses(0.0, 2, 0.02, 0.1, 0.01)],
        );
        let rotor = Rotor::Spatial(couple);
        for w in [50.0, 300.0] {
            let states = crate::rotor_partial::partially_balanced(&rotor, w).unwrap();
            assert!(!states.is_empty());
            // no balanced state: partially balanced below 1, else not balanced (the two balls
            // opposite, residual 1 of the couple: the one state at 50 rad/s), session 29's rule
            let f = rotor.field(w).unwrap();
            for st in &states {
                let r = Rotor::residual(&f, &st.x);
                assert_eq!(st.kind, state_from_residual(r, BALANCE_TOLERANCE, false), "Ω {w}: {:?}, residual {r}", st.psi);
            }
        }
    }

    /// examples/spatial_two_plane.toml as given (a horizontal machine: gravity, its supports):
    /// the balanced state is a periodic orbit on which the balls swing once a revolution. At
    /// 1500 rad/s the residual static and couple unbalance of the balls' positions at the
    /// orbit's start is above the 1e-6 tolerance (the swing), its mean over the revolution far
    /// below it: balanced (main before 2026-11-29 said "partially balanced" at 48 of 50 speeds).
    #[test]
    fn a_balanced_orbit_under_gravity_is_balanced_on_average() {
        let root = crate::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        let rotor = Rotor::Spatial(crate::config::spatial_simulation(&root).unwrap().rotor);
        let (f, s) = crate::rotor_campbell::stationary_at(&rotor, 1500.0).unwrap();
        assert!(f.period().is_some(), "a periodic orbit");
        assert_eq!(Rotor::state_kind(&f, &s.x), StateKind::Balanced);
        // the same classifier on the start alone (an equilibrium's rule) would not say so
        let Field::Spatial(sf) = &f else { unreachable!() };
        let r = sf.rotor();
        let (mut rs, mut scale) = (r.static_unbalance(), 0.0);
        scale += rs[0].hypot(rs[1]);
        for (p, a) in r.planes.iter().filter(|p| p.n > 0).flat_map(|p| std::iter::repeat_n(p, p.n)).zip(ball_angles(&f, &s.x)) {
            rs[0] += p.ball_mass * p.race_radius * a.cos();
            rs[1] += p.ball_mass * p.race_radius * a.sin();
            scale += p.ball_mass * p.race_radius;
        }
        assert!(rs[0].hypot(rs[1]) > 1e-6 * scale, "the start's static residual {} of {scale}", rs[0].hypot(rs[1]));
    }

    /// A periodic orbit's scan at a speed far below the rotor's natural frequencies: a
    /// revolution spans ω_fast/Ω of the fastest natural periods to integrate (at 1e-9 rad/s
    /// main at 21dbfc9 ran for hours). A top speed below ω_fast/1000 is refused, naming
    /// `omega_max`, in one line; grid speeds below it fail by name, at no cost, and the speeds
    /// above are analysed.
    #[test]
    fn a_periodic_scan_below_its_slowest_speed_is_refused_by_name() {
        let root = crate::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        let rotor = Rotor::Spatial(crate::config::spatial_simulation(&root).unwrap().rotor);
        let floor = rotor.periodic_floor(0.0).expect("a periodic orbit");
        // the fastest frequency is a root of det(K − ω² M) for the translation-tilt pair in
        // one direction (x: 2e6 + 3e6 N/m; y: the config's own), about the centre of mass
        let wf = rotor.fastest_natural_frequency(0.0);
        let Rotor::Spatial(s) = &rotor else { unreachable!() };
        let zr = s.z_reference();
        let d2 = |z: f64| (z - zr) * (z - zr);
        // the tilt inertia written out here, not taken from the code under test, so that a wrong
        // term there changes `wf` but not this determinant
        let tilt = s.rotor.equatorial_moment
            + s.rotor.mass * d2(s.rotor.z)
            + s.unbalances.iter().map(|u| u.mass * d2(u.z)).sum::<f64>()
            + s.planes.iter().map(|p| p.n as f64 * p.ball_mass * (d2(p.z) + 0.5 * p.race_radius * p.race_radius)).sum::<f64>();
        let det = |i: usize| {
            let l = wf * wf;
            let (mut a, mut b, mut c) = (-l * s.total_mass(), 0.0, -l * tilt);
            for sp in &s.supports {
                a += sp.stiffness[i];
                b += sp.stiffness[i] * (sp.z - zr);
                c += sp.stiffness[i] * d2(sp.z);
            }
            // relative to the product of the diagonal's scales (cancellation ~1e-12)
            (a * c - b * b) / (l * l * s.total_mass() * tilt)
        };
        assert!(det(0).abs().min(det(1).abs()) < 1e-9, "{} {}", det(0), det(1));
        // ω_fast at least the translational ω_n (Rayleigh: the larger root bounds every quotient)
        assert!(wf >= rotor.natural_frequency() && (floor - wf / 1000.0).abs() <= 1e-12 * floor, "{floor} {wf}");
        for top in [1e-9, 0.5 * floor] {
            let e = stability_over_speed(&rotor, &[0.5 * top, top]).unwrap_err();
            assert_eq!(e.field(), Some("omega_max"), "{e}");
            assert!(!e.to_string().contains('\n') && e.to_string().contains("periodic-orbit analysis"), "{e}");
        }
        // an equilibrium has no floor
        let mut flat = root.clone();
        crate::config::set(&mut flat, "spatial.gravity", crate::config::parse_value("[0.0, 0.0, 0.0]")).unwrap();
        crate::config::set_number(&mut flat, "supports.stiffness_left_y", 2.0e6).unwrap();
        crate::config::set_number(&mut flat, "supports.stiffness_right_y", 3.0e6).unwrap();
        let flat = Rotor::Spatial(crate::config::spatial_simulation(&flat).unwrap().rotor);
        assert_eq!(flat.periodic_floor(0.0), None);
        // a grid across it: the points below fail by name, the one above is analysed
        let r = stability_over_speed(&rotor, &[1e-9, 0.5 * floor, 1.2 * floor]).unwrap();
        for p in &r.points[..2] {
            assert!(p.verdict.is_none() && !p.analysed && p.failure.as_deref().is_some_and(|f| f.contains("periodic-orbit analysis")), "{p:?}");
        }
        assert!(r.points[2].analysed, "{:?}", r.points[2]);
        assert!(r.points[2].failure.as_deref().is_none_or(|f| !f.contains("periodic-orbit analysis")), "{:?}", r.points[2]);
    }

    /// A planar rotor's unbalance is "none" below 1e-6 of the balls' capacity, as the other
    /// models' (main at 41cc036: an exact-zero test, s1 = 1e-12 m counted), and its residuals
    /// are the race centre's offset (`RaceOffset`), never "over the capacity".
    #[test]
    fn a_planar_unbalance_below_a_millionth_of_capacity_is_none() {
        let tiny = Rotor::Planar(PlanarRotor { s1: 1e-12, s2: 0.0, ..PlanarRotor::paper() });
        assert!(!tiny.has_unbalance());
        let real = Rotor::Planar(PlanarRotor { s2: 0.0, ..PlanarRotor::paper() });
        assert!(real.has_unbalance());
        assert_eq!(tiny.residual_scale(), ResidualScale::RaceOffset);
    }

    /// Two coincident planes with unequal balls, one plane a single ball (the two-plane example
    /// without gravity, isotropic, both planes and the couple at z = 0.45, plane 2 one ball of
    /// 0.03 kg): capacity 0.0084 against |s0| 0.00063, a balanced state exists (the lone
    /// ball's `m R` along `−s0`, plane 1 the rest). The split in proportion to capacity, which
    /// a lone ball cannot meet, found no state at 140 of 200 speeds and "partially balanced"
    /// (residual 12) at 60 (main at 41cc036). The residual (static and couple from the balls'
    /// own angles) is the independent check; 1e-6 is the exact tolerance.
    #[test]
    fn coincident_planes_with_a_single_ball_balance() {
        let mut root = crate::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        crate::config::set(&mut root, "spatial.gravity", crate::config::parse_value("[0.0, 0.0, 0.0]")).unwrap();
        for (k, v) in [
            ("supports.stiffness_left_y", 2.0e6),
            ("supports.stiffness_right_y", 3.0e6),
            ("balancer2.z", 0.45),
            ("couple.z", 0.45),
            ("balancer2.ball_mass", 0.03),
            ("balancer2.balls", 1.0),
        ] {
            crate::config::set_number(&mut root, k, v).unwrap();
        }
        let rotor = Rotor::Spatial(crate::config::spatial_simulation(&root).unwrap().rotor);
        let r = stability_over_speed(&rotor, &[200.0, 600.0, 1500.0]).unwrap();
        for p in &r.points {
            assert!(p.state == Some(StateKind::Balanced) && p.residual.is_some_and(|v| v <= 1e-6), "{p:?}");
        }
        // the split itself: B_a + B_b = t, the lone ball's |B| = m R; two lone balls a triangle
        let t = [3e-4, -5e-4];
        for (na, nb) in [(2, 1), (1, 3), (1, 1)] {
            let (ma, mb) = (4e-4, 5e-4);
            let (a, b) = crate::spatial::dynamics::field::coincident_split(na, ma, nb, mb, t).expect("a split");
            assert!((a[0] + b[0] - t[0]).abs() + (a[1] + b[1] - t[1]).abs() <= 1e-15, "{a:?} {b:?}");
            for (n, m, v) in [(na, ma, a), (nb, mb, b)] {
                let r = v[0].hypot(v[1]);
                assert!(if n == 1 { (r - m).abs() <= 1e-15 } else { r <= n as f64 * m }, "{n} {m} {r}");
            }
        }
        // two lone balls too small for the target: none
        assert!(crate::spatial::dynamics::field::coincident_split(1, 1e-4, 1, 1e-4, t).is_none());
    }

    /// Each point says what its class is decided on: the same Jeffcott rotor as the planar
    /// model (the residual: E's offset) and as the linear rotor (the race whirl, whose
    /// `residual` is the static one only), in the JSON's `points[].state_basis`; none where no
    /// state was found.
    #[test]
    fn each_point_says_what_its_class_is_decided_on() {
        let (planar, linear) = jeffcott(2);
        let speeds = [150.0, 400.0];
        for (rotor, basis) in [(&planar, StateBasis::Residual), (&linear, StateBasis::RaceWhirl)] {
            let r = stability_over_speed(rotor, &speeds).unwrap();
            for p in &r.points {
                assert!(p.state.is_some(), "{p:?}");
                assert_eq!(p.state_basis, Some(basis), "{} Ω {}", rotor.model_name(), p.omega);
            }
            let v = serde_json::to_value(&r.points[0]).unwrap();
            let want = if basis == StateBasis::Residual { "residual" } else { "race_whirl" };
            assert_eq!(v["state_basis"], want);
        }
    }

    #[test]
    fn analyses_that_do_not_take_the_linear_rotor_refuse_it_by_name() {
        let (_, linear) = jeffcott(2);
        let w = 400.0;
        let errors = [
            crate::rotor_campbell::campbell_locked(&linear, &[w]).unwrap_err(),
            crate::rotor_campbell::locked_critical_speeds(&linear, w, 10).unwrap_err(),
            crate::rotor_campbell::locked_rotor(&linear, w, true).unwrap_err(),
        ];
        for e in errors {
            assert_eq!(e.field(), Some("linear_rotor"), "{e}");
            assert!(!e.to_string().contains('\n'), "{e}");
        }
    }

    #[test]
    fn the_linear_rotors_family_is_the_planar_rotors() {
        // the three-ball Jeffcott rotor on both models over the "none", "some" and "all" bands
        // of its family (as below): the same equations in other coordinates, so at each speed
        // the member Newton reaches from the closed form has the same verdict and abscissa, and
        // the family, followed at the same steps (0.1 in scaled arclength, the angles' scale 1
        // rad in both), the same members, verdict and extreme abscissas: to 1e-9 1/s (round-off
        // of eigenvalues of size |λ| ~ 300 1/s after Newton to ~1e-12: observed 5e-12). The
        // band ends are each bisected to 1e-9 relative in Ω: they agree to 2e-9 relative
        // (observed 4e-14)
        let (planar, linear) = jeffcott(3);
        let speeds: Vec<f64> = (0..=14).map(|i| 296.0 + i as f64).collect();
        let a = stability_over_speed(&planar, &speeds).unwrap();
        let b = stability_over_speed(&linear, &speeds).unwrap();
        assert_eq!((b.model, b.family_dimension), ("linear", 1));
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-9;
        for (x, y) in a.points.iter().zip(&b.points) {
            assert_eq!(x.verdict, y.verdict, "Ω {}", x.omega);
            let (ax, ay) = (x.abscissa.unwrap(), y.abscissa.unwrap());
            assert!(close(ax, ay), "Ω {}: {ax} vs {ay}", x.omega);
            assert_eq!(x.family_verdict, y.family_verdict, "Ω {}", x.omega);
            let (fx, fy) = (x.family.as_ref().unwrap(), y.family.as_ref().unwrap());
            assert_eq!((fx.members, fx.stable_members), (fy.members, fy.stable_members), "Ω {}", x.omega);
            assert!(close(fx.least_stable.abscissa, fy.least_stable.abscissa), "Ω {}: {fx:?} vs {fy:?}", x.omega);
            assert!(close(fx.most_stable.abscissa, fy.most_stable.abscissa), "Ω {}: {fx:?} vs {fy:?}", x.omega);
        }
        let (fa, fb) = (a.family.unwrap(), b.family.unwrap());
        for (ra, rb) in [(&fa.all_members_stable, &fb.all_members_stable), (&fa.some_members_stable, &fb.some_members_stable)] {
            assert_eq!(ra.len(), 1, "{ra:?}");
            assert_eq!(ra.len(), rb.len(), "{ra:?} vs {rb:?}");
            for (p, q) in ra.iter().zip(rb.iter()) {
                assert!((p.from - q.from).abs() <= 2e-9 * p.from && (p.to - q.to).abs() <= 2e-9 * p.to, "{p:?} vs {q:?}");
                assert_eq!((p.from_is_boundary, p.to_is_boundary), (q.from_is_boundary, q.to_is_boundary));
            }
        }
    }

    #[test]
    fn every_point_with_a_family_says_which_members_are_stable_in_every_band() {
        // The Jeffcott rotor (paper 004, race centred) with three balls on a grid of 1 rad/s
        // from below the "some members stable" band (~300.4 rad/s) to above the "all" band's
        // start (~307.1): every grid speed has its family (points[].family), the bands "none",
        // "some" and "all" all occur, each point's family_verdict is its family's, and that
        // family is the one followed at that speed on its own (family_point from the member
        // Newton reaches from the closed form), member counts and extremes included
        let p = PlanarRotor { n: 3, s2: 0.0, ..PlanarRotor::paper() };
        let rotor = Rotor::Planar(p);
        let speeds: Vec<f64> = (0..=14).map(|i| 296.0 + i as f64).collect();
        let r = stability_over_speed(&rotor, &speeds).unwrap();
        let newton = NewtonOptions::default();
        let mut seen = std::collections::HashSet::new();
        for pt in &r.points {
            assert!(pt.family_dimension > 0, "at {} rad/s", pt.omega);
            let fam = pt.family.as_ref().unwrap_or_else(|| panic!("no family at {} rad/s", pt.omega));
            assert_eq!(pt.family_verdict, Some(fam.verdict), "at {} rad/s", pt.omega);
            let f = rotor.field(pt.omega).unwrap();
            let state = stationary(&f, &Rotor::guess(&f).unwrap(), &newton).unwrap();
            let alone = family_point(&rotor, pt.omega, &state, &newton).unwrap();
            assert_eq!((fam.verdict, fam.members, fam.stable_members), (alone.verdict, alone.members, alone.stable_members), "at {} rad/s", pt.omega);
            seen.insert(format!("{:?}", fam.verdict));
        }
        assert_eq!(seen.len(), 3, "bands met: {seen:?}");
        let fam = r.family.as_ref().unwrap();
        assert_eq!((fam.all_members_stable.len(), fam.some_members_stable.len()), (1, 1), "{fam:?}");
    }
}
