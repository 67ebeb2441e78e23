//! Stability maps on **every configuration** (issue 18 item 3): the verdict and margin of the
//! stationary state over a grid of two parameter paths, for the planar rotor and for spatial
//! rotors with what paper 000's 12-state model ([`crate::spatial::map`]) does not represent (a
//! second plane, couple unbalance, supports that differ by direction, gravity, a tilted axis).
//!
//! A linear rotor config (`[linear_rotor]`, [`crate::linear_rotor`]) is mapped by
//! [`linear_map_traced`] over its parameter paths ([`crate::linear_rotor::spec`]), its balanced
//! state in axes turning with the rotor ([`Rotor::Linear`],
//! [`crate::linear_rotor::LinearRotorField`]), margins in 1/s.
//!
//! Each axis is a config key (`balancer.ball_mass`, `planar.c_psi`, `supports.stiffness_left`, …),
//! set in the TOML table with [`crate::config::set_number`], the rotor rebuilt by
//! [`crate::config::planar`] or [`crate::config::spatial_simulation`] as the simulation would
//! build it; or the speed: `omega` (the papers' `Ω = ω/ω0` for a spatial config, with the `ω0`
//! of the rotor at that cell as in the 12-state map; rad/s for a planar one), or `speed`
//! (rad/s), `speed_rpm`, `speed_hz` ([`crate::units::SPEED_PATHS`]; not for a dimensionless
//! config).
//!
//! At each cell the stationary state is found as in [`crate::rotor_stability`]: Newton's method
//! on the equations in turning axes ([`crate::analysis::stationary`]: an equilibrium, or the
//! periodic orbit of the revolution by shooting). An equilibrium starts from the closed-form
//! balanced state ([`Rotor::guess`]; it names the branch), where no balanced state exists from
//! the partially balanced state of least growth rate over the speed scan's candidate starts and
//! the cell before it ([`Rotor::partial_states`], as `stability`), and where that fails from the
//! state of the cell before it in the row (continuation). A periodic orbit starts from the neighbouring
//! cell's converged orbit, with that orbit's monodromy matrix as the shooting's starting matrix
//! (one integration of the variational equations per cell instead of two), then from the closed
//! form. A cell left without a state is tried once more from its right-hand neighbour's state, so
//! that a row whose first state lies at larger `x` (the two-plane example at 1200 rpm, below the
//! closed form's reach) continues it back. Its stability ([`crate::analysis::stability()`]) gives the verdict
//! and the margin: the spectral abscissa `α = max Re λ` without the family's structural zeros,
//! or the largest Floquet exponent `max ln|μ| / T`. The margin is written in the time unit of
//! the speed axis `omega`: per unit `τ = ω0 t` for a spatial config (`α / ω0`, as the 12-state
//! map writes it), 1/s for a planar one. A cell without a stationary state has margin NaN and no
//! verdict.
//!
//! # Families
//! With `n ≥ 3` balls in a plane the balanced states form a family of dimension `k`
//! ([`VectorField::structural_zeros`]), and one member's verdict says nothing of the others. At
//! such a cell the margin and verdict stay those of the member Newton reaches (from the closed
//! form: [`GeneralCell::margin`] names it), and the family through it is followed with
//! [`crate::analysis::family`] as the speed scan of [`crate::rotor_stability`] follows it, more
//! coarsely to stay cheap: continuation at steps of [`MAP_FAMILY_STEP`] in scaled arclength for
//! `k = 1`, with the least and the most stable member refined by a parabolic step
//! ([`FamilyOptions::refine_extremes`]), and [`MAP_FAMILY_SAMPLES`] members drawn for `k ≥ 2`
//! with the family's bunched members ([`crate::rotor_stability::bunched_members`]: each plane's
//! balls in two coinciding groups, the corners where its extremes can sit) and the search for
//! the extremes from them.
//! The cell's [`GeneralCell::family`] says whether all, some or none of the members are stable,
//! and [`GeneralCell::family_max_margin`], [`GeneralCell::family_min_margin`] give the margins
//! of the least and the most stable member. "Some members stable" is not "stable": a run can
//! settle on an unstable member and leave it. The traced boundary (`trace`) is that of the
//! member's margin. Cost: a family of `m` members costs about `m` cells (a Newton solve and
//! eigenvalues each): ~40 on the three-ball Jeffcott rotor.
//!
//! Rows (all `x` at one `y`) are computed in parallel (rayon) in blocks and handed to `on_row`
//! in order; the [`Control`] is asked before each row is started (an early stop is
//! [`GeneralMapOutcome::stopped`]) and its progress observer hears `(rows done, rows)`.
//!
//! ```
//! use autobal::rotor_map::{general_map, Verdict};
//! use autobal::spatial::map::Axis;
//! let mut root = autobal::config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
//! autobal::config::set_number(&mut root, "planar.s2", 0.0).unwrap(); // race centred: Jeffcott
//! let wn = autobal::config::planar(&root).unwrap().rotor.natural_frequency();
//! let x = Axis { path: "omega".into(), values: vec![0.5 * wn, 2.0 * wn] };
//! let y = Axis { path: "planar.c_psi".into(), values: vec![0.05, 0.1] };
//! let mut rows = vec![];
//! general_map(&root, &x, &y, None, &autobal::control::Control::none(), &mut |_, r| { rows.push(r.to_vec()); true }).unwrap();
//! // the balanced state is unstable below the critical speed in every row
//! assert!(rows.iter().all(|r| r[0].verdict == Some(Verdict::Unstable)));
//! ```

use crate::analysis::{family, stability, states_switch, stationary_near, FamilyOptions, NewtonOptions, StationaryState, VectorField, FILL_SUBSTEPS};
pub use crate::analysis::{FamilyVerdict, Kind, Verdict};
use crate::config;
use crate::control::{Control, StopReason};
use crate::error::{fmt_num, Error, Result};
use crate::linear_rotor::spec::LinearRotorSpec;
use crate::rotor_stability::{newton_options, Field, Rotor, StateKind};
use crate::spatial::map::Axis;
use crate::units::{speed_path_unit, Speed, SpeedUnit};
use rayon::prelude::*;
use serde::Serialize;
use toml::Table;

/// One cell of a general map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GeneralCell {
    /// Spectral abscissa `max Re λ` (or the largest Floquet exponent `max ln|μ| / T`) without
    /// the structural zeros, per unit `τ` (spatial) or 1/s (planar); NaN without a state. With
    /// a family (`family_dimension > 0`) it is that of **one member**, the one Newton's method
    /// reaches from the closed form ([`Rotor::guess`]: the planar rotor's balls one on the
    /// direction of the unbalance they cancel and the others in mirror pairs about it, the
    /// spatial rotor's balls of each plane in an equally spaced arc), else from the neighbouring
    /// cell's state ([`GeneralCell::continued`]); the family's verdict is [`GeneralCell::family`].
    pub margin: f64,
    /// The verdict of the state whose margin is `margin` (with a family, that one member's);
    /// `None` where no stationary state was found.
    pub verdict: Option<Verdict>,
    /// Equilibrium or periodic orbit; `None` without a state.
    pub kind: Option<Kind>,
    /// Dimension of the family of stationary states ([`VectorField::structural_zeros`]).
    pub family_dimension: usize,
    /// With a family: whether all, some or none of its members are stable (module docs,
    /// "Families"); `None` for an isolated state, without a state, or where the family could
    /// not be followed from the member.
    pub family: Option<FamilyVerdict>,
    /// With a family: the largest margin over its members (the least stable member: all are
    /// stable when it is negative beyond the neutral band), in `margin`'s unit; NaN otherwise.
    pub family_max_margin: f64,
    /// With a family: the smallest margin over its members (the most stable member: some are
    /// stable when it is negative beyond the neutral band); NaN otherwise.
    pub family_min_margin: f64,
    /// What the state is ([`Rotor::classify`], the speed scan's words: balanced,
    /// semi-balanced, partially balanced, not balanced); `None` without a state (and on a
    /// boundary's bisection points, which follow the margin only).
    pub state: Option<StateKind>,
    /// Whether the state was reached from the neighbouring cell rather than the closed form.
    pub continued: bool,
    /// Whether the cell was analysed: `false` where its stationary state is a periodic orbit
    /// and its speed is below the periodic-orbit analysis' floor ([`Rotor::periodic_floor`], the
    /// rule of [`crate::rotor_stability`]): no state was sought there (not "no stationary state
    /// found"; `verdict` `None`, `margin` NaN).
    pub analysed: bool,
}

impl GeneralCell {
    const NONE: GeneralCell = GeneralCell {
        margin: f64::NAN,
        verdict: None,
        kind: None,
        family_dimension: 0,
        family: None,
        family_max_margin: f64::NAN,
        family_min_margin: f64::NAN,
        state: None,
        continued: false,
        analysed: true,
    };
    /// A cell below the periodic-orbit floor ([`GeneralCell::analysed`]).
    const NOT_ANALYSED: GeneralCell = GeneralCell { analysed: false, ..GeneralCell::NONE };
}

/// Step in scaled arclength of a map cell's one-parameter family (0.3; a periodic orbit's
/// 0.5), the least and most stable member then refined by one parabolic step each
/// ([`FamilyOptions::refine_extremes`]): on the three-ball Jeffcott rotor ~40 members instead of
/// the speed scan's 119 at 0.1, and the extremes of the abscissa still found to well within the
/// sampling (tests/family_map.rs).
pub const MAP_FAMILY_STEP: f64 = 0.3;

/// Members drawn on a map cell's family of dimension `k ≥ 2` (40; a periodic orbit's 12): a
/// sample, as the speed scan's 200, so "all stable" there means all members drawn (those Newton
/// corrects onto the family), the bunched members ([`crate::rotor_stability::bunched_members`]:
/// three with four equal balls in a plane) and those the search for the extremes reached
/// ([`FamilyOptions::refine_extremes`]: at most `max(samples / 2, 4k)` more per extreme).
pub const MAP_FAMILY_SAMPLES: usize = 40;

/// The family through `state` (of dimension `k ≥ 1`) at one cell, sampled as
/// [`MAP_FAMILY_STEP`] and [`MAP_FAMILY_SAMPLES`] say: `(verdict, largest abscissa, smallest
/// abscissa)` over its members; `None` where it cannot be followed.
fn cell_family(field: &Field, state: &StationaryState, newton: &NewtonOptions) -> Option<(FamilyVerdict, f64, f64)> {
    let periodic = field.period().is_some();
    let angles = crate::rotor_stability::ball_coordinates(field).collect();
    let opts = FamilyOptions {
        step: if periodic { 0.5 } else { MAP_FAMILY_STEP },
        samples: if periodic { 12 } else { MAP_FAMILY_SAMPLES },
        max_members: if periodic { 200 } else { 1000 },
        angles,
        newton: newton.clone(),
        refine_extremes: true,
        // three equal balls: a third of the family, the rest its relabellings (3x fewer members)
        // (the linear rotor's balls: every member followed)
        relabellings: crate::rotor_stability::ball_rotations(field),
        ..FamilyOptions::default()
    };
    let fam = family(field, state, &crate::rotor_stability::with_bunched(opts, field, state)).ok()?;
    let (hi, lo) = fam.extremes()?;
    Some((fam.verdict(), hi.stability.abscissa, lo.stability.abscissa))
}

/// How far a general map got.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct GeneralMapOutcome {
    /// Rows handed to `on_row`.
    pub rows: usize,
    /// Whether every row was computed (not stopped by the control or by `on_row`); the same as
    /// `stopped.is_none()`.
    pub complete: bool,
    /// Why it stopped before every row was computed (`None`: complete).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<StopReason>,
    /// Cells whose state came from the closed form.
    pub closed_form: usize,
    /// Cells whose state was continued from the neighbour.
    pub continued: usize,
    /// Cells analysed without a stationary state found (not those below the periodic-orbit
    /// floor: [`GeneralMapOutcome::not_analysed`]).
    pub none: usize,
    /// Cells not analysed: a periodic orbit's speed below the periodic-orbit floor
    /// ([`GeneralCell::analysed`]).
    pub not_analysed: usize,
    /// Cells whose stationary state is a periodic orbit.
    pub periodic: usize,
    /// Cells whose state belongs to a family whose members were followed
    /// ([`GeneralCell::family`] set).
    pub families: usize,
    /// Cells whose state is partially balanced ([`GeneralCell::state`]: no balanced state
    /// exists there; the verdict is that state's).
    pub partially_balanced: usize,
    /// Cells whose state is not balanced ([`GeneralCell::state`]: e.g. the balls bunched on
    /// the unbalance's side below the critical speed; the verdict is that state's, not the
    /// balanced state's).
    pub not_balanced: usize,
}

/// The rotor of one cell and the speed unit of its `omega`.
#[derive(Debug, Clone)]
struct CellRotor {
    rotor: Rotor,
    /// Model speed units per unit of `omega`: `ω0` (rad/s) of an SI spatial rotor, else 1.
    scale: f64,
    /// Whether the model's speeds are rad/s (planar, SI spatial) rather than `Ω`.
    si: bool,
}

/// The rotor the config `root` describes, as [`crate::rotor_stability`] takes it.
fn build(root: &Table) -> Result<CellRotor> {
    if config::is_spatial(root) {
        let sim = config::spatial_simulation(root)?;
        let scale = sim.config.model.scale.map_or(1.0, |s| s.omega0);
        Ok(CellRotor { rotor: Rotor::Spatial(sim.rotor), scale, si: sim.config.dimensional })
    } else {
        Ok(CellRotor { rotor: Rotor::Planar(config::planar_rotor_for_analysis(root)?), scale: 1.0, si: true })
    }
}

/// `root` with `path` set to `v` ([`set_path`]); errors name the path and the value.
fn with(root: &Table, path: &str, v: f64) -> Result<Table> {
    let mut t = root.clone();
    set_path(&mut t, path, v).map_err(|e| name_axis(e, path, v))?;
    Ok(t)
}

/// The per-ball lists of `[planar]` that a map's axis sets by element, and the common value
/// each replaces: `planar.ball_masses[j]` (`m3`), `planar.ball_drags[j]` (`c_psi`).
const PLANAR_PER_BALL: [(&str, &str); 2] = [("planar.ball_masses", "m3"), ("planar.ball_drags", "c_psi")];

/// Set a map's axis `path` to `v` in the config `root`: a `table.key`
/// ([`config::set_number`]), or element `j` (1-based) of an array key, `table.key[j]`
/// ([`config::set_element`]; config.md's `planar.ball_masses[j]`, `planar.ball_drags[j]`, as
/// `sweep` takes them). Where the config gives one value for every ball (`planar.m3`,
/// `planar.c_psi`) instead of the list, the list is made of that value for each of the
/// `planar.n` balls, in its place, and then element `j` set: the other balls keep the common
/// value, as `sweep`'s planar paths do ([`crate::planar::problem::PlanarProblem`]). Until session 28 a
/// map handed the indexed path to `set_number`, which refused it as an unknown key while
/// naming `ball_masses` among the known ones.
fn set_path(root: &mut Table, path: &str, v: f64) -> Result<()> {
    let Some((key, j)) = crate::paths::indexed(path) else { return config::set_number(root, path, v) };
    let j = j.map_err(|r| Error::invalid(path, r))?;
    if let Some((_, common)) = PLANAR_PER_BALL.iter().find(|(k, _)| *k == key) {
        let list = key.trim_start_matches("planar.");
        if let Some(p) = root.get_mut("planar").and_then(|t| t.as_table_mut()) {
            if !p.contains_key(list) {
                if let (Some(c), Some(n)) =
                    (p.get(*common).and_then(|c| c.as_float().or(c.as_integer().map(|i| i as f64))), p.get("n").and_then(|n| n.as_integer()))
                {
                    let n = usize::try_from(n).unwrap_or(0).min(crate::planar::MAX_BALLS);
                    p.remove(*common);
                    p.insert(list.into(), toml::Value::Array(vec![toml::Value::Float(c); n]));
                }
            }
        }
    }
    config::set_element(root, path, key, j, v)
}

/// The error of the config at `v` on the axis `a` off its grid values (a boundary's bisection
/// or continuation point), naming the axis, the value and the map's range: `PATH: V, inside the
/// map's range LO to HI (where the boundary is bisected), gives an invalid rotor: REASON` (the
/// reason without the `at PATH = V: ` that [`name_axis`] put in).
fn inside_range(a: &Axis, v: f64, e: Error) -> Error {
    let (lo, hi) = a.values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| (l.min(x), h.max(x)));
    let reason = match &e {
        Error::InvalidParameter { field, reason } if *field == a.path => {
            let at = format!("at {} = {}: ", a.path, fmt_num(v));
            reason.strip_prefix(&at).unwrap_or(reason).to_string()
        }
        e => e.to_string(),
    };
    Error::invalid(
        a.path.clone(),
        format!("{}, inside the map's range {} to {} (where the boundary is bisected), gives an invalid rotor: {reason}", fmt_num(v), fmt_num(lo), fmt_num(hi)),
    )
}

fn name_axis(e: Error, path: &str, v: f64) -> Error {
    if e.field() == Some(path) {
        e
    } else {
        Error::invalid(path, format!("at {path} = {}: {e}", fmt_num(v)))
    }
}

/// A speed in the model's units (rad/s, or `Ω` for a dimensionless spatial rotor): `Ω · ω0`
/// for `omega`, the value times its unit's rad/s otherwise.
fn model_speed(c: &CellRotor, s: Speed, field: &str) -> Result<f64> {
    match s.unit.rad_s() {
        None => Ok(s.value * c.scale),
        Some(k) if c.si => Ok(s.value * k),
        Some(_) => Err(Error::invalid(
            field,
            format!(
                "{} {} needs a dimensional config (the rotor's ω0); this config is dimensionless: use the axis omega (Ω)",
                fmt_num(s.value),
                s.unit.symbol()
            ),
        )),
    }
}

/// The stationary state at model speed `w` from the closed form (with `closed_form`) or the
/// neighbouring cell's state `previous`, and its cell. For a periodic orbit the neighbour's converged orbit is
/// tried first, its monodromy matrix the shooting's starting matrix (as the speed scan
/// continues; one variational integration per cell instead of two), then the closed form
/// (also with that matrix); for an equilibrium the closed form first (it names the branch).
///
/// With `classify`, the state is settled and named as the speed scan does it
/// ([`Rotor::settle_balanced`] where the closed form is tried, else [`Rotor::classify`]); with
/// `family`, a state of a family ([`VectorField::structural_zeros`] `> 0`) gets its family's
/// verdict too ([`cell_family`]). A bisection, which follows the member's margin, goes without
/// both; a continuation's steps to a cell ([`Plane::continue_to`]) without the family.
fn solve(c: &CellRotor, w: f64, previous: Option<&StationaryState>, closed_form: bool, classify: bool, family: bool) -> (GeneralCell, Option<StationaryState>) {
    let Ok(field) = c.rotor.field(w) else { return (GeneralCell::NONE, None) };
    let periodic = field.period().is_some();
    // the periodic-orbit floor (the speed scan's one rule): a revolution spanning more than
    // PERIODS_PER_REVOLUTION of the fastest natural periods is not shot
    if periodic && c.rotor.below_periodic_floor(w).is_some() {
        return (GeneralCell::NOT_ANALYSED, None);
    }
    // no balanced orbit where no two groups of a plane's balls give its share under gravity
    // (Field::gravity_circulation): no start, as the speed scan
    if field.gravity_circulation().is_some() {
        return (GeneralCell::NONE, None);
    }
    let previous = previous.filter(|p| p.x.len() == field.dim());
    let hint = previous.and_then(|p| p.monodromy.as_deref());
    let opts = newton_options(periodic);
    let near = previous.map(|p| p.x.as_slice());
    // the speed scan's start (Rotor::first_start: under gravity with n >= 3 balls in a plane
    // the orbit with the balls in two groups, the closed form, each plane's share, the balls
    // bunched): built only when tried. Where the balls cannot cancel the unbalance, the
    // partially balanced state of least growth rate among the candidate starts and the
    // neighbour's state, as the speed scan analyses (Rotor::partial_states; from one start
    // until session 21 the cell could analyse another state than `stability`)
    // the planar rotor with an eccentric race on supports that differ by direction and n >= 3
    // equal balls: the family breaks into two-group orbits as under gravity, and the speed scan
    // analyses the one of least growth rate (Rotor::planar_split_orbits in its start, session
    // 25): so does the cell (review 25b: with four balls the cells continued onto an unstable
    // 2+2 orbit where the scan analyses a stable 3+1 one)
    let eccentric_split = matches!(&field, Field::Planar(f) if f.rotor().s2 > 0.0 && f.split_guesses().len() > 1);
    let closed = || {
        if !closed_form {
            return None;
        }
        let orbit = Rotor::gravity_orbit_start(&field, &opts)
            .or_else(|| eccentric_split.then(|| Rotor::planar_split_orbits(&field, &opts).into_iter().next().map(|(x, _)| x)).flatten())
            .or_else(|| {
                let carried: Vec<Vec<f64>> = near.map(|x| vec![x.to_vec()]).unwrap_or_default();
                Rotor::partial_states_from(&field, &opts, &carried).into_iter().next().map(|(x, _)| x)
            });
        Rotor::first_start(&field, orbit)
    };
    // Under gravity across the axis with n >= 3 balls in a plane, orbits with the balls in
    // two groups coexist (one per placement, SpatialField::split_guesses): the speed scan takes
    // the one of least growth rate at every speed (Rotor::gravity_orbit_start first, its
    // `prefer_guess`), and so does the cell. Continued from its neighbour, a cell could land on
    // another placement's orbit, and the verdict depended on the grid: the washer of
    // examples/washing_machine.toml under gravity at 1362.5 rpm, balancer.z = 0.2556, read
    // "unstable" (+3.74e-4 1/s, the other orbit) on a 25 x 10 map and "stable" (-1.64e-4 1/s)
    // in `stability` and on a 3 x 2 map (session 19's audit; tests/gravity_family.rs)
    let placements = matches!(&field, Field::Spatial(f) if f.split_guesses().len() > 1) || eccentric_split;
    // the last resort, as the speed scan's, where neither start reaches a state: the planar
    // rotor's orbit with n >= 3 balls in two groups on supports that differ by direction
    // (Rotor::planar_split_orbits, the least growth rate first)
    let last = || if closed_form { Rotor::planar_split_orbits(&field, &opts).into_iter().next().map(|(x, _)| x) } else { None };
    let order = if periodic && !placements { [Start::Continued, Start::Closed, Start::Last] } else { [Start::Closed, Start::Continued, Start::Last] };
    // the closed form's start once built (the scan's first start, shot from with `hint`)
    let mut closed_start: Option<Vec<f64>> = None;
    for how in order {
        let continued = how == Start::Continued;
        let owned;
        let start = match how {
            Start::Continued => near,
            Start::Closed => {
                closed_start = closed();
                closed_start.as_deref()
            }
            Start::Last => {
                owned = last();
                owned.as_deref()
            }
        };
        let Some(start) = start else { continue };
        let Ok(state) = stationary_near(&field, start, hint, &opts) else { continue };
        // a row's cell analyses the state `stability` analyses at its speed: the balanced
        // (semi-balanced) one wherever Newton reaches it (Rotor::settle_balanced, the commands'
        // one rule; a cell continued from a not-balanced neighbour kept that orbit until
        // session 21, audit 21's F4), classified once; a bisection follows its ends' state
        let (state, class) = if classify && closed_form {
            // the closed form was shot from with `hint` where this start is it or came after it
            let tried = if continued { None } else { closed_start.as_deref() };
            let (state, class) = Rotor::settle_balanced(&field, state, hint, tried, &opts);
            (state, Some(class.0))
        } else {
            let class = if classify { Some(Rotor::classify(&field, &state.x).0) } else { None };
            (state, class)
        };
        let Ok(st) = stability(&field, &state) else { continue };
        let mut cell = GeneralCell {
            margin: st.abscissa / c.scale,
            verdict: Some(st.verdict),
            kind: Some(st.kind),
            family_dimension: state.family_dimension,
            continued,
            // what the state is, as the speed scan names it (a row's cell; a bisection follows
            // the margin only)
            state: class,
            ..GeneralCell::NONE
        };
        if family && state.family_dimension > 0 {
            if let Some((v, hi, lo)) = cell_family(&field, &state, &opts) {
                (cell.family, cell.family_max_margin, cell.family_min_margin) = (Some(v), hi / c.scale, lo / c.scale);
            }
        }
        return (cell, Some(state));
    }
    (GeneralCell::NONE, None)
}

/// A map row's cells and their states (`None` where a cell has none).
#[derive(Clone)]
struct RawRow {
    cells: Vec<GeneralCell>,
    states: Vec<Option<StationaryState>>,
}

/// Where a cell's Newton starts ([`solve`]): the neighbour's state, the speed scan's first
/// start ([`Rotor::first_start`]), or its last resort ([`Rotor::planar_split_orbits`]).
#[derive(Clone, Copy, PartialEq)]
enum Start {
    Continued,
    Closed,
    Last,
}

/// One end of a bisection: its coordinate along the axis bisected, the verdict, the state, the
/// cell.
type Side = (f64, Option<Verdict>, Option<StationaryState>, GeneralCell);

/// Which side of the stability boundary a cell lies on: 0 without a stationary state, 1 where
/// the margin is negative, 2 where it is not, 3 not analysed (below the periodic-orbit floor:
/// no boundary is traced next to it). The boundary is where the margin crosses 0 (as
/// [`crate::analysis::speed_scan`] bisects it), not the edge of the neutral band around it.
fn side(c: &GeneralCell) -> u8 {
    match c.verdict {
        None if !c.analysed => 3,
        None => 0,
        Some(_) if c.margin < 0.0 => 1,
        Some(_) => 2,
    }
}

/// An axis: the speed in some unit, or a config path.
fn speed_unit(a: &Axis) -> Option<SpeedUnit> {
    speed_path_unit(&a.path)
}

/// The map's plane: the config, the axes, the fixed speed, and the rotors prebuilt along the
/// parameter axis when the other is the speed.
struct Plane<'a> {
    src: Source<'a>,
    x: &'a Axis,
    y: &'a Axis,
    speed: Option<Speed>,
    /// Rotors along the parameter axis (when one axis is the speed).
    line: Option<Vec<CellRotor>>,
}

impl Plane<'_> {
    /// The rotor at coordinate `t` along `along` on row `k` (along `x`) or column `k` (along
    /// `y`), and its speed: [`Plane::cell`] with `idx` the grid index of `t` on that axis
    /// (`None` off the grid: a bisection's midpoint or a continuation's step). Off the grid, a
    /// value the config refuses (an integer key such as `balancer.balls` at 2.5, a hole in a
    /// key's range) is an error naming the axis, the value and the map's range it lies in
    /// ([`inside_range`]; walk 32: the point was named as if the user had given it).
    fn on_line(&self, along: Along, k: usize, idx: Option<usize>, t: f64) -> Result<(std::borrow::Cow<'_, CellRotor>, f64)> {
        let r = match along {
            Along::X => self.cell(idx, Some(k), t, self.y.values[k]),
            Along::Y => self.cell(Some(k), idx, self.x.values[k], t),
        };
        if idx.is_some() {
            return r;
        }
        let axis = if along == Along::X { self.x } else { self.y };
        r.map_err(|e| inside_range(axis, t, e))
    }

    /// The rotor at `(xv, yv)` (grid index `(i, j)` for the prebuilt line) and its speed.
    /// `i` is `None` off the grid's `x` values, `j` off its `y` values (a bisection along that
    /// axis), where the rotor at that value is built.
    fn cell(&self, i: Option<usize>, j: Option<usize>, xv: f64, yv: f64) -> Result<(std::borrow::Cow<'_, CellRotor>, f64)> {
        use std::borrow::Cow;
        match (speed_unit(self.x), speed_unit(self.y)) {
            (Some(u), None) => {
                let c = match (&self.line, j) {
                    (Some(l), Some(j)) => Cow::Borrowed(&l[j]),
                    _ => Cow::Owned(self.build_at(&[(&self.y.path, yv)])?),
                };
                let w = model_speed(&c, Speed { value: xv, unit: u }, &self.x.path)?;
                Ok((c, w))
            }
            (None, Some(u)) => {
                let c = match (&self.line, i) {
                    (Some(l), Some(i)) => Cow::Borrowed(&l[i]),
                    _ => Cow::Owned(self.build_at(&[(&self.x.path, xv)])?),
                };
                let w = model_speed(&c, Speed { value: yv, unit: u }, &self.y.path)?;
                Ok((c, w))
            }
            _ => {
                let c = self.build_at(&[(&self.x.path, xv), (&self.y.path, yv)])?;
                let s = self.speed.ok_or_else(|| Error::invalid("omega", "required when neither axis is the speed (the speed at which to map)"))?;
                let w = model_speed(&c, s, "omega")?;
                Ok((Cow::Owned(c), w))
            }
        }
    }

    fn build_at(&self, set: &[(&str, f64)]) -> Result<CellRotor> {
        let built = match self.src {
            Source::Config(root) => {
                let mut t = root.clone();
                for (p, v) in set {
                    t = with(&t, p, *v)?;
                }
                build(&t)
            }
            Source::Linear(spec) => {
                // errors naming a path (and its value) pass as they are
                match spec.model_at(set) {
                    Err(e) if set.iter().any(|(p, _)| e.field() == Some(*p)) => return Err(e),
                    r => r.map(|r| CellRotor { rotor: Rotor::Linear(r), scale: 1.0, si: true }),
                }
            }
        };
        let v = set.last().map_or(0.0, |s| s.1);
        built.map_err(|e| match set {
            [(p, v)] => name_axis(e, p, *v),
            [(p, pv), (q, qv)] => Error::invalid(*p, format!("at {p} = {}, {q} = {}: {e}", fmt_num(*pv), fmt_num(*qv))),
            _ => name_axis(e, "config", v),
        })
    }

    /// The refusal of a map none of whose cells is analysed: every cell's stationary state a
    /// periodic orbit whose speed is below the periodic-orbit floor ([`Rotor::periodic_floor`],
    /// the speed scan's rule), named by the key that set the speed (the speed axis' path, or
    /// `omega` for a fixed speed) in its unit; `None` as soon as one cell is analysed. The
    /// speed axis is walked from its top, so a map with its top speed above the floor costs one
    /// rotor per line; only a refused map builds every cell's.
    fn all_below_floor(&self) -> Result<Option<Error>> {
        let (sx, sy) = (speed_unit(self.x), speed_unit(self.y));
        let (key, unit) = match (sx, sy, self.speed) {
            (Some(u), _, _) => (self.x.path.as_str(), u),
            (None, Some(u), _) => (self.y.path.as_str(), u),
            (None, None, Some(s)) => ("omega", s.unit),
            (None, None, None) => return Ok(None),
        };
        let descending = |a: &Axis, speed: bool| {
            let mut k: Vec<usize> = (0..a.values.len()).collect();
            if speed {
                k.sort_by(|&i, &j| a.values[j].total_cmp(&a.values[i]));
            }
            k
        };
        let (xs, ys) = (descending(self.x, sx.is_some()), descending(self.y, sy.is_some()));
        // the cell closest to its floor: (speed, floor) in the key's unit, and their ratio
        let mut closest: Option<(f64, f64, f64)> = None;
        for &j in &ys {
            for &i in &xs {
                let (xv, yv) = (self.x.values[i], self.y.values[j]);
                let (c, w) = self.cell(Some(i), Some(j), xv, yv)?;
                // as `solve`: a cell whose state is no periodic orbit (an equilibrium at rest,
                // `w = 0`), or without a field there, is analysed
                let periodic = c.rotor.field(w).is_ok_and(|f| f.period().is_some());
                let Some(f) = c.rotor.below_periodic_floor(w).filter(|_| periodic) else { return Ok(None) };
                // model speed units per unit of the key (Ω0 of an SI spatial rotor's `omega`, …)
                let per = model_speed(&c, Speed { value: 1.0, unit }, key)?;
                let (v, fv) = (w / per, f / per);
                if closest.is_none_or(|(_, _, r)| w / f > r) {
                    closest = Some((v, fv, w / f));
                }
            }
        }
        // both numbers in the key's unit, written
        let text = |v: f64| if unit == SpeedUnit::Omega { format!("Ω = {}", fmt_num(v)) } else { format!("{} {}", fmt_num(v), unit.symbol()) };
        Ok(closest.map(|(v, f, _)| {
            Error::invalid(key, format!("{} (every cell of the map: nothing to analyse)", crate::rotor_stability::below_floor_words(&text(v), &text(f))))
        }))
    }

    /// Row `j`'s cells and states: every `x` at `y_j`, continued along the row; a cell left
    /// without a state next to one with a state is then reached from that neighbour by
    /// continuation in smaller steps ([`Plane::continue_to`]), first from the left, then from
    /// the right (a row that finds its first state only at larger `x` continues it back). Until
    /// session 30 the fill was one step from the right-hand neighbour, and whether a cell had a
    /// state depended on the grid: the washer of examples/washing_machine.toml under gravity at
    /// 200 rpm, balancer.z = 0.22, had a partially balanced orbit on a 6-column map (reached
    /// from 300 rpm) and none on an 11-column one (the step from 250 rpm failed), where a
    /// bisection then reported the state "appearing" at 200.0000001 rpm.
    #[allow(clippy::type_complexity)]
    fn row_cells(&self, j: usize) -> Result<(Vec<GeneralCell>, Vec<Option<StationaryState>>)> {
        let yv = self.y.values[j];
        let mut previous: Option<StationaryState> = None;
        let mut out = Vec::with_capacity(self.x.values.len());
        let mut states: Vec<Option<StationaryState>> = Vec::with_capacity(self.x.values.len());
        for (i, &xv) in self.x.values.iter().enumerate() {
            let (c, w) = self.cell(Some(i), Some(j), xv, yv)?;
            let (mut cell, mut x) = solve(&c, w, previous.as_ref(), true, true, true);
            if cell.verdict.is_none() && cell.analysed && i > 0 {
                if let Some(from) = &states[i - 1] {
                    if let Some((c2, x2)) = self.continue_to(Along::X, j, Some(i), self.x.values[i - 1], from, xv, false)? {
                        (cell, x) = (c2, Some(x2));
                    }
                }
            }
            states.push(x.clone());
            previous = x.or(previous);
            out.push(cell);
        }
        for i in (0..out.len().saturating_sub(1)).rev() {
            if out[i].verdict.is_none() && out[i].analysed {
                if let Some(from) = states[i + 1].clone() {
                    if let Some((cell, x)) = self.continue_to(Along::X, j, Some(i), self.x.values[i + 1], &from, self.x.values[i], true)? {
                        out[i] = cell;
                        states[i] = Some(x);
                    }
                }
            }
        }
        // the states kept (for the fill along `y` and the bisections) without their monodromy
        // matrices, `dim²` numbers each (a 60-state orbit's 29 kB: 0.9 GB for 64 rows of 500
        // cells): a continuation or bisection from them is shot without that hint (one more
        // variational integration)
        for s in states.iter_mut().flatten() {
            s.monodromy = None;
        }
        Ok((out, states))
    }

    /// The cell at grid index `idx` along `along` (column `idx` of row `k` along `x`, row `idx`
    /// of column `k` along `y`; `None`: a bisection's midpoint off the grid, solved as the
    /// bisection solves it, without the state's name and family) reached by continuation from
    /// `from`, the state at coordinate `a`, to the cell's coordinate `b`: natural-parameter steps, halved where Newton fails
    /// and doubled again where it succeeds, from the whole gap (from half of it with `!whole`:
    /// the caller has tried the whole gap in one step) down to `|b − a| / FILL_SUBSTEPS`; `None` where a step that small
    /// fails, or a point on the way is below the periodic-orbit floor. Each point is solved as
    /// a row's cell ([`solve`], the closed form's starts too) with the last state reached
    /// carried (the neighbour's state continued, and the candidate partially balanced starts
    /// from it), as a bisection solves its midpoints: the washer above has, at 250 rpm, an
    /// orbit that folds at 211 rpm beside the one that reaches 200 rpm (and folds at 189 rpm);
    /// following only the cell's state, the 11-column map kept 200 rpm empty. Only the cell
    /// itself gets its family's verdict.
    #[allow(clippy::too_many_arguments)]
    fn continue_to(
        &self,
        along: Along,
        k: usize,
        idx: Option<usize>,
        a: f64,
        from: &StationaryState,
        b: f64,
        whole: bool,
    ) -> Result<Option<(GeneralCell, StationaryState)>> {
        let gap = b - a;
        if gap == 0.0 {
            // two grid values equal: nothing to continue over (the cell was solved with its own
            // starts)
            return Ok(None);
        }
        let least = gap.abs() / FILL_SUBSTEPS;
        let (mut t, mut state, mut h) = (a, from.clone(), if whole { gap } else { 0.5 * gap });
        while h.abs() >= least {
            let reach = (t + h - b) * gap.signum() >= 0.0;
            let next = if reach { b } else { t + h };
            let (c, w) = self.on_line(along, k, idx.filter(|_| reach), next)?;
            let (cell, x) = solve(&c, w, Some(&state), true, idx.is_some(), reach && idx.is_some());
            if side(&cell) == 3 {
                return Ok(None);
            }
            match x {
                Some(x) if reach => return Ok(Some((GeneralCell { continued: true, ..cell }, x))),
                Some(x) => {
                    (t, state) = (next, x);
                    h = (2.0 * h).abs().min((b - t).abs()) * gap.signum();
                }
                None => h *= 0.5,
            }
        }
        Ok(None)
    }

    /// Row `j`'s points where the verdict changes between neighbouring cells (`cells`, their
    /// `states`), bisected along `x`.
    fn row_points(&self, j: usize, cells: &[GeneralCell], states: &[Option<StationaryState>]) -> Result<Vec<BoundaryPoint>> {
        let mut points = vec![];
        for i in 0..cells.len().saturating_sub(1) {
            let end = |k: usize| (self.x.values[k], cells[k].verdict, states[k].clone(), cells[k]);
            if crosses(&cells[i], &cells[i + 1]) {
                points.extend(self.bisect(Along::X, j, end(i), end(i + 1))?);
            } else if differ_in_kind(&cells[i], &cells[i + 1]) {
                points.extend(self.follow_each(Along::X, j, end(i), end(i + 1))?);
            }
        }
        Ok(points)
    }

    /// Column `i`'s cells left without a state in `rows` (consecutive rows, from row `j0`),
    /// each reached by continuation along `y` ([`Plane::continue_to`]) from the state its own
    /// row found in the row below, else in the row above, as [`Plane::row_cells`] left them
    /// (`raw`, the same rows), never from a state this fill reached, so that a cell's state
    /// depends on its neighbours only, not on how the map's rows fall into blocks (which
    /// follows the number of threads). The first of `rows` is not filled from below (it is the
    /// row held back from the last block, filled from below there, or the map's first row).
    /// Returns the cells changed, `(jj, cell, state)`.
    #[allow(clippy::type_complexity)]
    fn fill_column(&self, i: usize, j0: usize, raw: &[RawRow], rows: &[RawRow]) -> Result<Vec<(usize, GeneralCell, StationaryState)>> {
        let n = rows.len();
        let mut changed = vec![];
        for jj in 0..n {
            let cell = &rows[jj].cells[i];
            if cell.verdict.is_some() || !cell.analysed {
                continue;
            }
            let j = j0 + jj;
            let mut got = None;
            if jj > 0 {
                if let Some(from) = &raw[jj - 1].states[i] {
                    got = self.continue_to(Along::Y, i, Some(j), self.y.values[j - 1], from, self.y.values[j], true)?;
                }
            }
            if got.is_none() && jj + 1 < n {
                if let Some(from) = &raw[jj + 1].states[i] {
                    got = self.continue_to(Along::Y, i, Some(j), self.y.values[j + 1], from, self.y.values[j], true)?;
                }
            }
            if let Some((c, x)) = got {
                changed.push((jj, c, x));
            }
        }
        Ok(changed)
    }

    /// The points where the verdict changes between rows `j` and `j + 1` (cells `lo`, `hi`
    /// with their states `lo_states`, `hi_states`), column by column, bisected along `y` as
    /// [`Plane::row`] bisects along `x`; the columns in parallel.
    fn column_points(
        &self,
        j: usize,
        (lo, lo_states): (&[GeneralCell], &[Option<StationaryState>]),
        (hi, hi_states): (&[GeneralCell], &[Option<StationaryState>]),
    ) -> Result<Vec<BoundaryPoint>> {
        let found: Vec<Vec<BoundaryPoint>> = (0..lo.len().min(hi.len()))
            .into_par_iter()
            .map(|i| {
                let state = |s: &[Option<StationaryState>]| s.get(i).cloned().flatten();
                let a = (self.y.values[j], lo[i].verdict, state(lo_states), lo[i]);
                let b = (self.y.values[j + 1], hi[i].verdict, state(hi_states), hi[i]);
                if crosses(&lo[i], &hi[i]) {
                    self.bisect(Along::Y, i, a, b)
                } else if differ_in_kind(&lo[i], &hi[i]) {
                    self.follow_each(Along::Y, i, a, b)
                } else {
                    Ok(vec![])
                }
            })
            .collect::<Result<_>>()?;
        Ok(found.into_iter().flatten().collect())
    }

    /// The point between `lo` and `hi` (coordinate along `along`, verdict, state) on row `k`
    /// (`along` [`Along::X`]) or column `k` (`along` [`Along::Y`]) where the verdict changes, by
    /// bisection to [`BOUNDARY_RTOL`] relative in that coordinate; `None` where a midpoint is not
    /// analysed (below the periodic-orbit floor, side 3): the interval then holds cells on no
    /// side, and taking such a midpoint for the far side would walk towards it and report a
    /// boundary that is only the floor's edge.
    ///
    /// Each midpoint is solved from the closed form, else continued from the nearer side's
    /// state. Where the last bracket holds two different states (the speed scan's test,
    /// [`crate::analysis::states_switch`]: e.g. the partially balanced orbit on one side and the
    /// balanced one on the other), each side's state is followed towards the other side and
    /// its own changes of stability located ([`Plane::follow_each`]); a state lost on the way
    /// gives no point.
    fn bisect(&self, along: Along, k: usize, lo: Side, hi: Side) -> Result<Vec<BoundaryPoint>> {
        self.bisect_with(along, k, lo, hi, None)
    }

    /// [`Plane::bisect`]; with `follow` `Some(true)` (`Some(false)`) each midpoint is continued
    /// from `lo`'s (`hi`'s) side's state only, never from the closed form, and a midpoint
    /// without a state lies on the other side ([`Plane::changes_along`] calls it with that
    /// state at both ends, on two sides: the point is where that state changes stability);
    /// none if the last bracket still holds two states.
    fn bisect_with(&self, along: Along, k: usize, lo: Side, hi: Side, follow: Option<bool>) -> Result<Vec<BoundaryPoint>> {
        let (side_lo, side_hi) = (side(&lo.3), side(&hi.3));
        // one end without a state: the bracket locates where a state appears or is lost
        let appears = follow.is_none() && (side_lo == 0) != (side_hi == 0);
        let (mut a, mut b) = (lo.0, hi.0);
        let (mut xa, mut xb) = (lo.2.clone(), hi.2.clone());
        // the cells at the bracket's ends (a midpoint's once it replaces an end)
        let (mut ca, mut cb) = (lo.3, hi.3);
        let at = |t: f64| match along {
            Along::X => (t, self.y.values[k]),
            Along::Y => (self.x.values[k], t),
        };
        while (b - a).abs() > BOUNDARY_RTOL * a.abs().max(b.abs()) {
            let mid = 0.5 * (a + b);
            if mid == a || mid == b {
                break;
            }
            let (c, w) = self.on_line(along, k, None, mid)?;
            let (mut cell, mut x) = match follow {
                None => solve(&c, w, xa.as_ref().or(xb.as_ref()), true, false, false),
                Some(true) => solve(&c, w, xa.as_ref(), false, false, false),
                Some(false) => solve(&c, w, xb.as_ref(), false, false, false),
            };
            if appears && x.is_none() && side(&cell) != 3 {
                // no state from one Newton jump: continued from the end that has one in
                // halved steps (Plane::continue_to), so that the point is where the state
                // ends, not where one jump across half the bracket failed (walk 31: the
                // washer's orbit "appearing" at 200.0000001 rpm, the first midpoint of
                // 150-250 rpm, where it exists down to its fold at 188.58 rpm)
                let from = if side_lo == 0 { (b, &xb) } else { (a, &xa) };
                if let (t, Some(state)) = from {
                    if let Some((c2, x2)) = self.continue_to(along, k, None, t, state, mid, false)? {
                        (cell, x) = (c2, Some(x2));
                    }
                }
            }
            if side(&cell) == 3 {
                return Ok(vec![]);
            }
            let on_lo = match follow {
                Some(false) => side(&cell) != side_hi,
                _ => side(&cell) == side_lo,
            };
            if on_lo {
                a = mid;
                xa = x.or(xa);
                ca = cell;
            } else {
                b = mid;
                xb = x.or(xb);
                cb = cell;
            }
        }
        // two states in the last bracket (measured against the grid ends' states, the speed
        // scan's test): a switch of state, not one state's change of stability
        let switch = match (&xa, &xb, &lo.2, &hi.2) {
            (Some(p), Some(q), Some(g), Some(h)) => states_switch((&p.x, &q.x, (b - a).abs()), (&g.x, &h.x, (hi.0 - lo.0).abs())),
            _ => false,
        };
        if switch {
            return match follow {
                None => self.follow_each(along, k, lo, hi),
                Some(_) => Ok(vec![]),
            };
        }
        // a state that appears (or disappears) at the very cell without one: the cell's own
        // starts missed a state that continuation reaches (the bisection's midpoints are
        // continued from the side with a state), so no stationary state appears there; not a
        // boundary (the fill in Plane::row_cells and Plane::fill_column reaches most such cells
        // first: this is the case where a fold lies within FILL_SUBSTEPS of the cell)
        let none_end = match (side_lo, side_hi) {
            _ if !appears => None,
            (0, _) if a == lo.0 => Some((a, &xb)),
            (_, 0) if b == hi.0 => Some((b, &xa)),
            _ => None,
        };
        if let Some((t, Some(from))) = none_end {
            let (c, w) = self.on_line(along, k, None, t)?;
            if let (cell, Some(x)) = solve(&c, w, Some(from), false, false, false) {
                // the state's own boundary between that cell and the far end, if its margin
                // changes sign there (the far end's side is a state's)
                let lo_is_none = side_lo == 0;
                let far = if lo_is_none { &hi.3 } else { &lo.3 };
                if side(&cell) == side(far) {
                    return Ok(vec![]);
                }
                let end = (t, cell.verdict, Some(x), cell);
                return if lo_is_none { self.bisect(along, k, end, hi) } else { self.bisect(along, k, lo, end) };
            }
        }
        let (x, y) = at(0.5 * (a + b));
        if !appears {
            return Ok(vec![BoundaryPoint { x, y, from: lo.1, to: hi.1, along, rtol: BOUNDARY_RTOL }]);
        }
        // where a state appears (or is lost): the verdict on its side is that state's at the
        // bracket's end, not the far cell's (walk 31: "stable" from the balanced cell at 350
        // rpm beside a partially balanced orbit, unstable, appearing at its fold), and that
        // state's own change of stability between there and the far cell is bisected as
        // between two cells (walk 31: the balanced orbit's boundary at 303.14 rpm was lost
        // behind the fold at 188.58)
        let lo_is_none = side_lo == 0;
        let (t, state, cell) = if lo_is_none { (b, xb, cb) } else { (a, xa, ca) };
        // where the state is lost (a fold): the bracket's end is where continuation in halved
        // steps stopped converging, not a change of sign bisected, so it is not claimed to
        // BOUNDARY_RTOL (walk 32: one fold 1.4e-5 relative apart on three grids)
        let from = if lo_is_none { None } else { cell.verdict };
        let to = if lo_is_none { cell.verdict } else { None };
        let point = BoundaryPoint { x, y, from, to, along, rtol: FOLD_RTOL };
        let mut points = vec![point];
        let far = if lo_is_none { &hi } else { &lo };
        if state.is_some() && side(&cell) != 0 && side(&cell) != side(&far.3) {
            let end = (t, cell.verdict, state, cell);
            points.extend(if lo_is_none { self.bisect(along, k, end, hi)? } else { self.bisect(along, k, lo, end)? });
        }
        Ok(points)
    }

    /// The points between `lo` and `hi` (their states differ: [`Plane::bisect`] ended on a
    /// switch, or two cells on one side hold states of different kinds, [`differ_in_kind`])
    /// where either end's state changes stability: each end's state is continued towards the
    /// other end ([`Plane::changes_along`]) and each change of its verdict bisected on that
    /// state alone. A state lost on the way (a fold) ends its walk without a point: that is a
    /// switch of state, not a change of stability (walk 32: the planar rotor's not-balanced
    /// state lost at 277.65 rad/s was reported "stable to unstable" there, a point no
    /// `stability` range ends at). Nor does a change of its stability where the map analyses
    /// another state on either side of it ([`Plane::is_maps_state`]; walk 34: the bunched balls
    /// past the ball mass where the balanced state branches off them). So a switch of state
    /// gives a point only where the map's verdict changes there: the state the map analyses on
    /// one side, followed across, changes stability at the switch. Points found by both walks
    /// (one state on both ends after all) are reported once; the points in increasing
    /// coordinate.
    fn follow_each(&self, along: Along, k: usize, lo: Side, hi: Side) -> Result<Vec<BoundaryPoint>> {
        let mut points = self.changes_along(along, k, &lo, hi.0, true)?;
        for p in self.changes_along(along, k, &hi, lo.0, false)? {
            let c = |q: &BoundaryPoint| if along == Along::X { q.x } else { q.y };
            let same = |q: &BoundaryPoint| (c(q) - c(&p)).abs() <= 1e-6 * c(&p).abs().max(f64::MIN_POSITIVE) && (q.from, q.to) == (p.from, p.to);
            if !points.iter().any(same) {
                points.push(p);
            }
        }
        points.sort_by(|p, q| if along == Along::X { p.x.total_cmp(&q.x) } else { p.y.total_cmp(&q.y) });
        Ok(points)
    }

    /// The changes of stability of the state of `from` continued towards `to` in
    /// [`FOLLOW_STEPS`] equal steps (a branch can turn fast over one grid step), each from the
    /// last step's state only (never the closed form), each step's side against the last's; a
    /// change is bisected on that state alone ([`Plane::bisect_with`] following `from`'s side,
    /// `from_lo`: `from` is the bracket's lower end). The walk ends where the state is lost or
    /// a step is below the periodic-orbit floor. Two changes within one step (a window
    /// narrower than a sixteenth of the grid step) are not seen.
    fn changes_along(&self, along: Along, k: usize, from: &Side, to: f64, from_lo: bool) -> Result<Vec<BoundaryPoint>> {
        let Some(mut state) = from.2.clone() else { return Ok(vec![]) };
        if side(&from.3) == 0 || side(&from.3) == 3 {
            return Ok(vec![]);
        }
        let mut last: Side = from.clone();
        let mut points = vec![];
        for s in 1..=FOLLOW_STEPS {
            let t = if s == FOLLOW_STEPS { to } else { from.0 + (to - from.0) * s as f64 / FOLLOW_STEPS as f64 };
            let (c, w) = self.on_line(along, k, None, t)?;
            let (cell, x) = solve(&c, w, Some(&state), false, false, false);
            let Some(x) = x.filter(|_| side(&cell) != 3) else { break };
            let here: Side = (t, cell.verdict, Some(x.clone()), cell);
            // a change of the followed state's stability is a point of the map's boundary
            // only where the map analyses that state on both sides of it (walk 34: the
            // two-plane rotor's bunched balls, followed past the ball mass where the balanced
            // state branches off them, turn unstable there, where the map's state is the
            // balanced one, stable: a "stable to unstable" point between two stable cells);
            // the first step's `last` is the grid cell, whose state is the map's
            if crosses(&last.3, &cell) && (s == 1 || self.is_maps_state(along, k, &last)?) && self.is_maps_state(along, k, &here)? {
                let (a, b) = if from_lo { (last.clone(), here.clone()) } else { (here.clone(), last.clone()) };
                points.extend(self.bisect_with(along, k, a, b, Some(from_lo))?);
            }
            state = x;
            last = here;
        }
        Ok(points)
    }

    /// Whether the state of `at` (a step of [`Plane::changes_along`]: a state continued from
    /// a neighbouring cell's) is the one a map cell there analyses ([`solve`] from the closed
    /// form and that state, settled on the balanced state wherever Newton reaches it, as
    /// `stability`): what it is is the same ([`Rotor::classify`]) and, for an isolated state,
    /// it is the same state ([`states_switch`]'s test of one state found twice; a family's
    /// member reached from the closed form is another member of the same family).
    fn is_maps_state(&self, along: Along, k: usize, at: &Side) -> Result<bool> {
        let Some(followed) = &at.2 else { return Ok(false) };
        let (c, w) = self.on_line(along, k, None, at.0)?;
        let Ok(field) = c.rotor.field(w) else { return Ok(false) };
        let (cell, Some(maps)) = solve(&c, w, Some(followed), true, true, false) else { return Ok(false) };
        if cell.state != Some(Rotor::classify(&field, &followed.x).0) {
            return Ok(false);
        }
        Ok(maps.family_dimension > 0 || !states_switch((&maps.x, &followed.x, 0.0), (&followed.x, &followed.x, 1.0)))
    }
}

/// Steps in which [`Plane::changes_along`] continues an end's state to the other end,
/// as the speed scan does after a switch ([`crate::analysis::speed_scan`]: 16; the two-plane
/// rotor's partially balanced state below 322 rad/s moves its balls 0.6 rad over one grid step).
const FOLLOW_STEPS: usize = 16;

/// Whether the boundary is bisected between two neighbouring cells (along a row or a column):
/// they lie on different sides ([`side`]) and neither below the periodic-orbit floor. Two cells
/// holding states of different kinds are bisected too ([`Plane::bisect`] tells a switch of
/// state from a change of one state's stability: walk 30 found `--boundary` silent between a
/// partially balanced unstable cell and a balanced stable one, where the balanced state's own
/// boundary lies, until session 31 this refused such pairs). Two neutral cells
/// ([`Verdict::Neutral`]: `|α|` within the verdict's threshold, where linearisation cannot
/// decide) are not, whatever the signs of their margins: a margin that touches 0 over a range
/// has a sign of round-off (walk 34: the planar rotor at the ball mass where its balanced
/// state branches off the bunched balls, neutral at every speed, gave a "neutral to neutral"
/// point).
fn crosses(a: &GeneralCell, b: &GeneralCell) -> bool {
    let (sa, sb) = (side(a), side(b));
    let neutral = a.verdict == Some(Verdict::Neutral) && b.verdict == Some(Verdict::Neutral);
    sa != sb && sa != 3 && sb != 3 && !neutral
}

/// Whether two neighbouring cells on the same side (both with a negative margin, or both
/// not) hold stationary states of different kinds ([`GeneralCell::state`], or an equilibrium
/// beside a periodic orbit): the state of either may change stability between them before it
/// is lost, so each is followed towards the other ([`Plane::follow_each`]). Walk 32: the
/// planar rotor of examples/planar.toml at `c_psi` 0.15, stable and not balanced at 200
/// rad/s, stable and semi-balanced at 300, the semi-balanced state unstable below 296.2
/// rad/s (`stability`'s range start): until session 32 such a pair was never bisected and
/// the point was missing on a 100 rad/s grid.
fn differ_in_kind(a: &GeneralCell, b: &GeneralCell) -> bool {
    let (sa, sb) = (side(a), side(b));
    sa == sb && (sa == 1 || sa == 2) && (a.state != b.state || a.kind != b.kind)
}

/// Where a map's rotors come from: a planar or spatial config ([`build`]), or a linear rotor's
/// ([`LinearRotorSpec`]).
#[derive(Clone, Copy)]
enum Source<'a> {
    Config(&'a Table),
    Linear(&'a LinearRotorSpec),
}

/// Check an axis: a speed, or a config path that the config takes (at its first value).
fn check_axis(src: Source, a: &Axis) -> Result<()> {
    if a.values.is_empty() {
        return Err(Error::invalid(a.path.clone(), "the axis has no value"));
    }
    if let Some(v) = a.values.iter().find(|v| !v.is_finite()) {
        return Err(Error::invalid(a.path.clone(), format!("{v} is not a finite value")));
    }
    match speed_unit(a) {
        Some(_) if a.values.iter().any(|v| *v < 0.0) => Err(Error::invalid(a.path.clone(), "the speed must not be negative")),
        Some(_) => Ok(()),
        None => match src {
            Source::Config(root) => with(root, &a.path, a.values[0]).map(|_| ()),
            Source::Linear(spec) => crate::linear_rotor::spec::set_path(&mut spec.root().clone(), &a.path, a.values[0]),
        },
    }
}

/// Refuse a fixed speed `speed` given beside a speed axis (`omega`, `speed`, `speed_rpm`,
/// `speed_hz`): the axis sets every cell's speed, so the fixed one would be ignored. The error
/// names `omega`, the key both front ends take (the CLI's `--omega`, Python's `omega`), with
/// the speed as given and the axis: one check and one message for every map, the 12-state
/// route's included (the command layer asks it before choosing a route). Hunt 27 found the
/// CLI ignoring `--omega` there (exit 0), hunt 28 Python's `autobal.map` on a linear rotor
/// config, which reached this module without the CLI's check.
///
/// ```
/// use autobal::rotor_map::check_fixed_speed;
/// use autobal::spatial::map::Axis;
/// use autobal::units::parse_speed;
/// let (x, y) = (Axis::new("planar.c_psi", vec![0.05, 0.1]), Axis::new("speed_rpm", vec![500.0, 900.0]));
/// let e = check_fixed_speed(&x, &y, Some(parse_speed("omega", "3000 rpm").unwrap())).unwrap_err();
/// assert_eq!(e.to_string(), "omega: 3000 rpm: the map's y axis speed_rpm is the speed already; drop the fixed speed, or map over two other parameters at that speed");
/// assert!(check_fixed_speed(&x, &y, None).is_ok());
/// ```
pub fn check_fixed_speed(x: &Axis, y: &Axis, speed: Option<Speed>) -> Result<()> {
    let Some(s) = speed else { return Ok(()) };
    match [("x", x), ("y", y)].into_iter().find(|(_, a)| speed_unit(a).is_some()) {
        Some((which, a)) => Err(Error::invalid(
            "omega",
            format!("{s}: the map's {which} axis {} is the speed already; drop the fixed speed, or map over two other parameters at that speed", a.path),
        )),
        None => Ok(()),
    }
}

/// The stationary state's verdict and margin over the grid `x × y` (module docs): `on_row(j,
/// cells)` gets row `j` (`cells[i]` at `(x_i, y_j)`) in order and returns whether to go on;
/// `speed` is the speed when neither axis is one (a bare number is `omega`'s unit).
pub fn general_map(
    root: &Table,
    x: &Axis,
    y: &Axis,
    speed: Option<Speed>,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[GeneralCell]) -> bool,
) -> Result<GeneralMapOutcome> {
    general_map_traced(root, x, y, speed, false, control, &mut |j, cells, _| on_row(j, cells))
}

/// Where the verdict changes between two neighbouring cells, along a row (`x` located by
/// bisection to [`BOUNDARY_RTOL`] relative, `y` the row's value) or along a column (`y`
/// bisected, `x` the column's value): [`BoundaryPoint::along`] says which.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoundaryPoint {
    /// The boundary's `x` (the column's, along `y`).
    pub x: f64,
    /// The boundary's `y` (the row's, along `x`).
    pub y: f64,
    /// The verdict on the side of the smaller value of the axis bisected (`None`: no stationary
    /// state).
    pub from: Option<Verdict>,
    /// The verdict on the side of its larger value.
    pub to: Option<Verdict>,
    /// The axis along which the point was bisected (`"x"`: between two cells of a row; `"y"`:
    /// of a column).
    pub along: Along,
    /// The relative tolerance in the coordinate bisected to which the point is located:
    /// [`BOUNDARY_RTOL`] where the verdict changes (the margin's sign, bisected), [`FOLD_RTOL`]
    /// where a stationary state appears or is lost (`from` or `to` `None`: where continuation
    /// stops converging).
    pub rtol: f64,
}

/// The axis along which a [`BoundaryPoint`] was bisected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Along {
    /// Along `x`, between two cells of a row.
    X,
    /// Along `y`, between two cells of a column.
    Y,
}

impl Along {
    /// `"x"` or `"y"`, as the JSON and the boundary CSV write it.
    pub fn key(self) -> &'static str {
        match self {
            Along::X => "x",
            Along::Y => "y",
        }
    }
}

/// Relative width in the coordinate bisected (`x` along a row, `y` along a column) to which
/// [`general_map_traced`] bisects a verdict change: `|b − a| ≤ 1e-9 max(|a|, |b|)`, as
/// [`crate::analysis::speed_scan`] bisects the ends of stable ranges.
pub const BOUNDARY_RTOL: f64 = 1e-9;

/// Relative tolerance claimed for a point where a stationary state appears or is lost (a
/// fold, [`BoundaryPoint::from`] or [`BoundaryPoint::to`] `None`): 1e-4 of the coordinate.
/// Such a point is not a change of sign bisected but where Newton's continuation towards the
/// fold, in steps halved down to [`FILL_SUBSTEPS`] of the gap and then by bisection, stops
/// converging; near a fold the branch moves as the square root of the distance and one real
/// exponent tends to 0, so Newton's basin shrinks and where it fails depends on the state it
/// starts from. Seen: the orbit of examples/dimensional.toml under gravity lost near 1130.32
/// rpm at `balancer.drag` 0.5, 1.4e-5 relative apart on grids of 3, 5 and 7 speeds over
/// 300-1500 rpm (tests/map_walk_32.rs); the washer's at 188.58 rpm 3e-9 apart
/// (tests/map_switch_31.rs). Locating the fold itself (the zero of that exponent, or
/// arclength continuation round it) was tried in session 32: the exponent's square
/// extrapolated to zero within ~1e-8 of each grid's own bracket on the dimensional rotor, so
/// its three branches fold 1.4e-5 apart, and no grid-independent fold was found.
pub const FOLD_RTOL: f64 = 1e-4;

/// [`general_map`], and with `trace` the stability boundary: wherever the margin changes sign
/// between neighbouring cells, or a stationary state appears or disappears, the change is
/// located by bisection, along `x` between two cells of a row and along `y` between two cells of
/// a column ([`BoundaryPoint`]; each midpoint solved from the closed form, else continued from
/// the nearer side's state). `on_row(j, cells, points)`: row `j`'s points along `x`, then those
/// along `y` between rows `j - 1` and `j`.
#[allow(clippy::type_complexity)]
pub fn general_map_traced(
    root: &Table,
    x: &Axis,
    y: &Axis,
    speed: Option<Speed>,
    trace: bool,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[GeneralCell], &[BoundaryPoint]) -> bool,
) -> Result<GeneralMapOutcome> {
    map_on(Source::Config(root), x, y, speed, trace, control, on_row)
}

/// [`general_map_traced`] on a linear rotor config ([`crate::linear_rotor`]): the axes are its
/// parameter paths ([`crate::linear_rotor::spec`]: `linear_rotor.ball_mass`,
/// `linear_rotor.support_stiffness_scale`, …) or the speed (`omega` and `speed` in rad/s,
/// `speed_rpm`, `speed_hz`); each cell's rotor is the config with those values set, read
/// again and reduced as `stability` runs it ([`crate::linear_rotor::spec::model`]); its
/// balanced state is an equilibrium in axes turning with the rotor (isotropic structure) or a
/// periodic orbit (half a revolution for direction-dependent supports, one under gravity:
/// [`crate::linear_rotor::LinearRotorField`]), started from
/// [`crate::linear_rotor::LinearRotorField::balanced_guess`]. Margins are in 1/s.
#[allow(clippy::type_complexity)]
pub fn linear_map_traced(
    spec: &LinearRotorSpec,
    x: &Axis,
    y: &Axis,
    speed: Option<Speed>,
    trace: bool,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[GeneralCell], &[BoundaryPoint]) -> bool,
) -> Result<GeneralMapOutcome> {
    map_on(Source::Linear(spec), x, y, speed, trace, control, on_row)
}

#[allow(clippy::type_complexity)]
fn map_on(
    src: Source,
    x: &Axis,
    y: &Axis,
    speed: Option<Speed>,
    trace: bool,
    control: &Control,
    on_row: &mut dyn FnMut(usize, &[GeneralCell], &[BoundaryPoint]) -> bool,
) -> Result<GeneralMapOutcome> {
    check_axis(src, x)?;
    check_axis(src, y)?;
    let (sx, sy) = (speed_unit(x), speed_unit(y));
    if sx.is_some() && sy.is_some() {
        return Err(Error::invalid(y.path.clone(), "only one axis can be the speed"));
    }
    if sx.is_none() && sy.is_none() && speed.is_none() {
        return Err(Error::invalid("omega", "required when neither axis is the speed (the speed at which to map)"));
    }
    check_fixed_speed(x, y, speed)?;
    let mut plane = Plane { src, x, y, speed, line: None };
    // the rotors along the parameter axis, once, when the other axis is the speed
    let other = match (sx, sy) {
        (Some(_), None) => Some(y),
        (None, Some(_)) => Some(x),
        _ => None,
    };
    if let Some(a) = other {
        let line: Vec<CellRotor> = a.values.par_iter().map(|&v| plane.build_at(&[(&a.path, v)])).collect::<Result<_>>()?;
        plane.line = Some(line);
    }
    // the model's own refusals (real balls, a bad speed unit) before any row: at the first cell
    let (c, w) = plane.cell(Some(0), Some(0), x.values[0], y.values[0])?;
    c.rotor.field(w.max(f64::MIN_POSITIVE))?;
    drop(c);
    // a map whose every cell is below the periodic-orbit floor is refused, naming the speed
    if let Some(e) = plane.all_below_floor()? {
        return Err(e);
    }
    let mut out = GeneralMapOutcome { complete: true, ..Default::default() };
    let block = (4 * rayon::current_num_threads()).max(1);
    let mut j0 = 0;
    // the last row handed on, final (the bisections along `y` between it and the next row)
    let mut last: Option<(Vec<GeneralCell>, Vec<Option<StationaryState>>)> = None;
    // the block's last row, held back until the next block's first row is computed (its cells
    // are filled from that row's too): as its row left it (`raw`), and filled from below
    let mut held: Option<(RawRow, RawRow)> = None;
    while j0 < y.values.len() {
        let j1 = (j0 + block).min(y.values.len());
        let computed: Vec<Option<RawRow>> = (j0..j1)
            .into_par_iter()
            .map(|j| {
                if control.should_stop().is_some() {
                    return Ok(None);
                }
                // under the stop probe (a stop ends a cell's shooting early): a row with a
                // cell left without a state once the control says stop is dropped, not
                // handed over with a cell that only the stop left without one
                let (cells, states) = crate::control::with_probe(control, || plane.row_cells(j))?;
                let cut = control.should_stop().is_some() && cells.iter().any(|c| c.verdict.is_none() && c.analysed);
                Ok((!cut).then_some(RawRow { cells, states }))
            })
            .collect::<Result<_>>()?;
        let Some(computed) = computed.into_iter().collect::<Option<Vec<RawRow>>>() else {
            // a stop: this block (and the row held back) is not handed on
            out.complete = false;
            out.stopped = Some(control.should_stop().unwrap_or(StopReason::Interrupted));
            return Ok(out);
        };
        // the rows of this round: the one held back (filled from below already), then the block's
        let base = j0 - usize::from(held.is_some());
        let (mut raw, mut rows): (Vec<RawRow>, Vec<RawRow>) = (vec![], vec![]);
        if let Some((r, f)) = held.take() {
            raw.push(r);
            rows.push(f);
        }
        rows.extend(computed.iter().cloned());
        raw.extend(computed);
        let n = raw.len();
        // each column's cells left without a state, reached from their neighbours in the column
        let filled: Vec<Vec<(usize, GeneralCell, StationaryState)>> = (0..x.values.len())
            .into_par_iter()
            .map(|i| crate::control::with_probe(control, || plane.fill_column(i, base, &raw, &rows)))
            .collect::<Result<_>>()?;
        for (i, f) in filled.into_iter().enumerate() {
            for (jj, cell, state) in f {
                rows[jj].cells[i] = cell;
                rows[jj].states[i] = Some(state);
            }
        }
        // the rows final now: all but the last, which is held back for the next block's first
        // row (its fill from above), unless it is the map's last
        let done = if j1 == y.values.len() { n } else { n - 1 };
        if done < n {
            held = Some((raw.pop().expect("a row"), rows.pop().expect("a row")));
        }
        drop(raw);
        // the points along `x` within each final row, and along `y` between each final row and
        // the one before it
        let mut along_x: Vec<Vec<BoundaryPoint>> = vec![vec![]; rows.len()];
        let mut along_y: Vec<Vec<BoundaryPoint>> = vec![vec![]; rows.len()];
        if trace {
            along_x = rows
                .par_iter()
                .enumerate()
                .map(|(jj, r)| crate::control::with_probe(control, || plane.row_points(base + jj, &r.cells, &r.states)))
                .collect::<Result<_>>()?;
        }
        // (a state the fill reached keeps its monodromy matrix only until here)
        for s in rows.iter_mut().flat_map(|r| r.states.iter_mut()).flatten() {
            s.monodromy = None;
        }
        if trace {
            #[allow(clippy::type_complexity)]
            let pairs: Vec<(usize, (&[GeneralCell], &[Option<StationaryState>]), (&[GeneralCell], &[Option<StationaryState>]))> = (0..rows.len())
                .filter_map(|jj| {
                    let hi = &rows[jj];
                    let (lo, ls) = match jj {
                        0 => last.as_ref().map(|(c, s)| (c.as_slice(), s.as_slice()))?,
                        _ => (rows[jj - 1].cells.as_slice(), rows[jj - 1].states.as_slice()),
                    };
                    Some((jj, (lo, ls), (hi.cells.as_slice(), hi.states.as_slice())))
                })
                .collect();
            let found: Vec<(usize, Vec<BoundaryPoint>)> = pairs
                .into_par_iter()
                .map(|(jj, lo, hi)| Ok((jj, crate::control::with_probe(control, || plane.column_points(base + jj - 1, lo, hi))?)))
                .collect::<Result<_>>()?;
            for (jj, p) in found {
                along_y[jj] = p;
            }
        }
        if control.should_stop().is_some() {
            // a stop during the fill or the bisections may have left a cell without the state
            // it would have reached, or a point misplaced: these rows are not handed on
            out.complete = false;
            out.stopped = control.should_stop();
            return Ok(out);
        }
        for (jj, (row, (mut points, more))) in rows.into_iter().zip(along_x.into_iter().zip(along_y)).enumerate() {
            let RawRow { cells: row, states } = row;
            points.extend(more);
            for c in &row {
                match c.verdict {
                    None if !c.analysed => out.not_analysed += 1,
                    None => out.none += 1,
                    Some(_) if c.continued => out.continued += 1,
                    Some(_) => out.closed_form += 1,
                }
                if c.kind == Some(Kind::PeriodicOrbit) {
                    out.periodic += 1;
                }
                if c.family.is_some() {
                    out.families += 1;
                }
                match c.state {
                    Some(StateKind::PartiallyBalanced) => out.partially_balanced += 1,
                    Some(StateKind::NotBalanced) => out.not_balanced += 1,
                    _ => {}
                }
            }
            out.rows += 1;
            let go_on = on_row(base + jj, &row, &points);
            last = Some((row, states));
            control.report(out.rows as u64, y.values.len() as u64);
            if !go_on {
                out.complete = base + jj + 1 == y.values.len();
                out.stopped = (!out.complete).then_some(StopReason::Observer);
                return Ok(out);
            }
        }
        j0 = j1;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn planar_root() -> Table {
        let mut root = config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
        config::set_number(&mut root, "planar.s2", 0.0).unwrap();
        root
    }

    fn collect(root: &Table, x: &Axis, y: &Axis, speed: Option<Speed>) -> Result<Vec<Vec<GeneralCell>>> {
        let mut rows = vec![];
        general_map(root, x, y, speed, &Control::none(), &mut |_, r| {
            rows.push(r.to_vec());
            true
        })?;
        Ok(rows)
    }

    #[test]
    fn each_row_equals_the_speed_scan_of_the_general_route() {
        // a second route to every cell: rotor_stability's speed scan on the rotor rebuilt with
        // the row's c_psi; the same Newton from the same closed form, so the margins agree to
        // round-off (1e-9 relative of the largest one: the solutions differ only by the order
        // in which the grid is walked, which the closed-form start makes irrelevant)
        let root = planar_root();
        let wn = config::planar(&root).unwrap().rotor.natural_frequency();
        let speeds: Vec<f64> = (1..=7).map(|i| 0.4 * wn * i as f64).collect();
        let x = Axis { path: "omega".into(), values: speeds.clone() };
        let y = Axis { path: "planar.c_psi".into(), values: vec![0.02, 0.3] };
        let rows = collect(&root, &x, &y, None).unwrap();
        for (j, &c) in y.values.iter().enumerate() {
            let mut r = root.clone();
            config::set_number(&mut r, "planar.c_psi", c).unwrap();
            let rotor = Rotor::Planar(config::planar(&r).unwrap().rotor);
            let scan = crate::rotor_stability::stability_over_speed(&rotor, &speeds).unwrap();
            for (cell, p) in rows[j].iter().zip(&scan.points) {
                assert_eq!(cell.verdict, p.verdict);
                let a = p.abscissa.unwrap();
                assert!((cell.margin - a).abs() <= 1e-9 * a.abs().max(1.0), "{} vs {a}", cell.margin);
            }
            // Jeffcott with balls: unstable below sqrt(k/M), and stable somewhere above
            assert!(rows[j].iter().zip(&speeds).filter(|(_, w)| **w < wn).all(|(c, _)| c.verdict == Some(Verdict::Unstable)));
        }
        assert!(rows.iter().flatten().any(|c| c.verdict == Some(Verdict::Stable)));
    }

    #[test]
    fn a_fixed_speed_map_over_two_keys_and_errors_naming_the_axis() {
        let root = planar_root();
        let x = Axis { path: "planar.c_psi".into(), values: vec![0.05, 0.1] };
        let y = Axis { path: "planar.m3".into(), values: vec![0.02, 0.03, 0.04] };
        let wn = config::planar(&root).unwrap().rotor.natural_frequency();
        // m3 = 0.02 kg: the balls cannot cancel the unbalance (n m3 r = 0.0024 < m1 s1 = 0.003
        // kg m), so there is no balanced state: the cells hold the balls bunched, below the
        // critical speed on the unbalance's side (not balanced: residual 1.79), as the speed
        // scan's point at that speed (the second route: same start, same Newton, so the same
        // margin to round-off); until session 17 the map tried only the closed form of the
        // balanced state and left these cells without a state; with heavier balls, below the
        // critical speed every cell is unstable
        let slow = collect(&root, &x, &y, Some(Speed::omega(0.5 * wn))).unwrap();
        for (cell, &c) in slow[0].iter().zip(&x.values) {
            let mut r = root.clone();
            config::set_number(&mut r, "planar.c_psi", c).unwrap();
            config::set_number(&mut r, "planar.m3", 0.02).unwrap();
            let rotor = Rotor::Planar(config::planar(&r).unwrap().rotor);
            let p = &crate::rotor_stability::stability_over_speed(&rotor, &[0.5 * wn]).unwrap().points[0];
            assert!(cell.state.is_some() && cell.state == p.state, "{cell:?} {p:?}");
            assert_eq!(cell.verdict, p.verdict);
            let a = p.abscissa.unwrap();
            assert!((cell.margin - a).abs() <= 1e-9 * a.abs().max(1.0), "{} vs {a}", cell.margin);
        }
        assert!(slow[1..].iter().flatten().all(|c| c.verdict == Some(Verdict::Unstable)), "{slow:?}");
        let e = collect(&root, &x, &y, None).unwrap_err().to_string();
        assert!(e.starts_with("omega"), "{e}");
        let bad = Axis { path: "planar.nope".into(), values: vec![1.0, 2.0] };
        let e = collect(&root, &bad, &y, Some(Speed::omega(wn))).unwrap_err().to_string();
        assert!(e.contains("planar.nope"), "{e}");
        let neg = Axis { path: "planar.k".into(), values: vec![1e5, -1.0] };
        let e = collect(&root, &neg, &Axis { path: "omega".into(), values: vec![wn] }, None).unwrap_err().to_string();
        assert!(e.starts_with("planar.k"), "{e}");
        // a speed in SI on a dimensionless spatial config is refused, naming the axis
        let sp = config::parse(include_str!("../../../examples/spatial.toml"), "spatial").unwrap();
        let rpm = Axis { path: "speed_rpm".into(), values: vec![100.0, 200.0] };
        let m = Axis { path: "dimensionless.h_s".into(), values: vec![0.01, 0.02] };
        if !config::spatial(&sp).unwrap().dimensional {
            let e = collect(&sp, &rpm, &m, None).unwrap_err().to_string();
            assert!(e.starts_with("speed_rpm"), "{e}");
        }
    }

    #[test]
    fn the_traced_boundary_is_the_speed_scans_range_end() {
        // second route: rotor_stability's speed scan bisects the start of the stable range to
        // 1e-9 relative in Ω, as the trace bisects along x: the two agree to 2e-9 relative
        let root = planar_root();
        let wn = config::planar(&root).unwrap().rotor.natural_frequency();
        let speeds: Vec<f64> = (1..=6).map(|i| 0.5 * wn * i as f64).collect();
        let x = Axis { path: "omega".into(), values: speeds.clone() };
        let y = Axis { path: "planar.c_psi".into(), values: vec![0.1] };
        let mut pts = vec![];
        general_map_traced(&root, &x, &y, None, true, &Control::none(), &mut |_, _, p| {
            pts.extend_from_slice(p);
            true
        })
        .unwrap();
        let rotor = Rotor::Planar(config::planar(&root).unwrap().rotor);
        let scan = crate::rotor_stability::stability_over_speed(&rotor, &speeds).unwrap();
        let ends: Vec<f64> = scan
            .stable_ranges
            .iter()
            .flat_map(|r| [r.from, r.to].into_iter().zip([r.from_is_boundary, r.to_is_boundary]))
            .filter(|e| e.1)
            .map(|e| e.0)
            .collect();
        assert!(!pts.is_empty());
        assert_eq!(pts.len(), ends.len(), "{pts:?} vs {ends:?}");
        for (p, e) in pts.iter().zip(&ends) {
            assert!((p.x - e).abs() <= 2e-9 * e, "{} vs {e}", p.x);
            assert_eq!((p.from, p.to), (Some(Verdict::Unstable), Some(Verdict::Stable)));
            // above the critical speed (Jeffcott with balls: stable only above sqrt(k/M))
            assert!(p.x > wn);
        }
    }

    /// The boundary along `y` (hunt 28: only the rows were bisected, so a map with the speed
    /// on `y` reported no point although every column changed from unstable to stable along
    /// it): each column's points are the speed scan's range ends at that column's `c_psi`
    /// (second route: `stability_over_speed` bisects them to 1e-9 relative in Ω as the map
    /// bisects along `y`, so they agree to 2e-9 relative, both last intervals), at the column's
    /// exact `x`, `along` `y`, in the order of the columns; the same map transposed finds them
    /// along `x`.
    #[test]
    fn the_boundary_is_bisected_along_y_too() {
        let root = planar_root();
        let wn = config::planar(&root).unwrap().rotor.natural_frequency();
        let speeds: Vec<f64> = (1..=6).map(|i| 0.5 * wn * i as f64).collect();
        let drags = vec![0.1, 0.2];
        let traced = |x: &Axis, y: &Axis| {
            let mut pts = vec![];
            general_map_traced(&root, x, y, None, true, &Control::none(), &mut |_, _, p| {
                pts.extend_from_slice(p);
                true
            })
            .unwrap();
            pts
        };
        let (w, c) = (Axis { path: "omega".into(), values: speeds.clone() }, Axis { path: "planar.c_psi".into(), values: drags.clone() });
        let pts = traced(&c, &w);
        let along_y: Vec<&BoundaryPoint> = pts.iter().filter(|p| p.along == Along::Y).collect();
        let mut n = 0;
        for &d in &drags {
            let mut r = root.clone();
            config::set_number(&mut r, "planar.c_psi", d).unwrap();
            let scan = crate::rotor_stability::stability_over_speed(&Rotor::Planar(config::planar(&r).unwrap().rotor), &speeds).unwrap();
            let ends: Vec<f64> =
                scan.stable_ranges.iter().flat_map(|r| [(r.from, r.from_is_boundary), (r.to, r.to_is_boundary)]).filter(|e| e.1).map(|e| e.0).collect();
            let mine: Vec<&&BoundaryPoint> = along_y.iter().filter(|p| p.x == d).collect();
            assert!(!ends.is_empty());
            assert_eq!(mine.len(), ends.len(), "c_psi {d}: {mine:?} vs {ends:?}");
            for (p, e) in mine.iter().zip(&ends) {
                assert!((p.y - e).abs() <= 2e-9 * e, "{} vs {e}", p.y);
                assert_eq!((p.from, p.to), (Some(Verdict::Unstable), Some(Verdict::Stable)));
            }
            n += ends.len();
        }
        assert_eq!(along_y.len(), n);
        // transposed: the same points, found along x (the same bisection: 2e-9 relative)
        let t = traced(&w, &c);
        let mut along_x: Vec<&BoundaryPoint> = t.iter().filter(|p| p.along == Along::X).collect();
        along_x.sort_by(|a, b| a.y.total_cmp(&b.y));
        assert_eq!(along_x.len(), n);
        let mut along_y = along_y;
        along_y.sort_by(|a, b| a.x.total_cmp(&b.x));
        for (p, q) in along_y.iter().zip(&along_x) {
            assert!(p.x == q.y && (p.y - q.x).abs() <= 2e-9 * p.y, "{p:?} vs {q:?}");
        }
    }

    /// `planar.ball_masses[j]` and `planar.ball_drags[j]` as a map's axes (config.md lists them
    /// "for maps and sweeps"; hunt 28: the map refused them as unknown keys of `[planar]` while
    /// naming `ball_masses` among the known ones). Each cell equals the speed scan of the rotor
    /// with that ball's value set as `sweep` sets it (second route: the planar problem's own
    /// parameter path on the built rotor, not the config's table; the same Newton from the same
    /// closed form, so the margins agree to round-off, 1e-9 relative), on a config with per-ball
    /// lists and on one with the common `m3`, `c_psi` (the list then made of it, the other
    /// balls keeping it, as `sweep` does); the value moves the margins (the axis is not
    /// ignored); a ball past `planar.n` is refused naming the path.
    #[test]
    fn a_balls_own_mass_and_drag_are_map_axes() {
        use crate::paths::Parameters as _;
        let common = config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
        let mut lists = common.clone();
        let p = lists.get_mut("planar").and_then(|t| t.as_table_mut()).unwrap();
        p.remove("m3");
        p.remove("c_psi");
        p.insert("n".into(), toml::Value::Integer(3));
        let floats = |v: &[f64]| toml::Value::Array(v.iter().map(|&x| toml::Value::Float(x)).collect());
        p.insert("ball_masses".into(), floats(&[0.025, 0.035, 0.02]));
        p.insert("ball_drags".into(), floats(&[0.08, 0.12, 0.1]));
        for (root, path, values) in [
            (&lists, "planar.ball_drags[1]", vec![0.05, 0.3]),
            (&lists, "planar.ball_masses[3]", vec![0.02, 0.04]),
            (&common, "planar.ball_masses[2]", vec![0.02, 0.04]),
            (&common, "planar.ball_drags[1]", vec![0.05, 0.3]),
        ] {
            let wn = config::planar(root).unwrap().rotor.natural_frequency();
            let speeds: Vec<f64> = [0.6, 1.4, 2.5, 4.0].iter().map(|k| k * wn).collect();
            let x = Axis { path: path.into(), values: values.clone() };
            let y = Axis { path: "omega".into(), values: speeds.clone() };
            let rows = collect(root, &x, &y, None).unwrap_or_else(|e| panic!("{path}: {e}"));
            for (i, &v) in values.iter().enumerate() {
                let mut problem = config::planar(root).unwrap();
                problem.set(path, v).unwrap();
                let scan = crate::rotor_stability::stability_over_speed(&Rotor::Planar(problem.rotor), &speeds).unwrap();
                for (row, p) in rows.iter().zip(&scan.points) {
                    let (cell, a) = (row[i], p.abscissa.unwrap());
                    assert_eq!(cell.verdict, p.verdict, "{path} = {v}");
                    assert!((cell.margin - a).abs() <= 1e-9 * a.abs().max(1.0), "{path} = {v}: {} vs {a}", cell.margin);
                }
            }
            assert!(rows.iter().any(|r| (r[0].margin - r[1].margin).abs() > 1e-6 * r[0].margin.abs()), "{path}: the value changes nothing");
        }
        let x = Axis { path: "planar.ball_masses[4]".into(), values: vec![0.02, 0.03] };
        let y = Axis { path: "omega".into(), values: vec![100.0, 200.0] };
        let e = collect(&lists, &x, &y, None).unwrap_err().to_string();
        assert!(e.starts_with("planar.ball_masses[4]: ") && e.contains("has 3 elements"), "{e}");
    }

    #[test]
    fn cancelling_stops_before_the_rows() {
        let root = planar_root();
        let x = Axis { path: "omega".into(), values: vec![100.0, 200.0] };
        let y = Axis { path: "planar.c_psi".into(), values: vec![0.05, 0.1, 0.2] };
        let cancelled = Control::new();
        cancelled.cancel();
        let out = general_map(&root, &x, &y, None, &cancelled, &mut |_, _| panic!("no row is computed")).unwrap();
        assert_eq!((out.rows, out.complete, out.stopped), (0, false, Some(StopReason::Interrupted)));
        // a zero budget: stopped before the first row, the budget named
        let none = Control::new().with_budget(std::time::Duration::ZERO);
        let out = general_map(&root, &x, &y, None, &none, &mut |_, _| panic!("no row is computed")).unwrap();
        assert_eq!((out.rows, out.stopped), (0, Some(StopReason::Budget { seconds: 0.0 })));
        // on_row stopping after the first row: the rows so far, stopped by the observer
        let out = general_map(&root, &x, &y, None, &Control::none(), &mut |_, _| false).unwrap();
        assert_eq!((out.rows, out.stopped), (1, Some(StopReason::Observer)));
    }

    /// A boundary's bisection between two analysed cells on different sides whose midpoint is
    /// below the periodic-orbit floor (0.81 rad/s on examples/spatial_two_plane.toml: 0.5 is
    /// below it) reports no point: taking the not-analysed midpoint for the far side walked
    /// down to rest and reported a boundary at 0 rad/s (checked with the stop taken out). The ends are made up (the bisection
    /// reads only their sides and states), as a row from rest to just above the floor has them.
    #[test]
    fn a_bisection_reports_no_point_past_a_midpoint_below_the_floor() {
        let root = config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
        let (x, y) = (Axis { path: "speed".into(), values: vec![0.0, 1.0] }, Axis { path: "balancer.drag".into(), values: vec![0.5] });
        let plane = Plane { src: Source::Config(&root), x: &x, y: &y, speed: None, line: None };
        let (c, w) = plane.cell(None, Some(0), 0.5, 0.5).unwrap();
        assert!(c.rotor.below_periodic_floor(w).is_some() && c.rotor.field(w).unwrap().period().is_some());
        let stable = GeneralCell { margin: -1.0, verdict: Some(Verdict::Stable), ..GeneralCell::NONE };
        let unstable = GeneralCell { margin: 1.0, verdict: Some(Verdict::Unstable), ..GeneralCell::NONE };
        let p = plane.bisect(Along::X, 0, (0.0, stable.verdict, None, stable), (1.0, unstable.verdict, None, unstable)).unwrap();
        assert!(p.is_empty(), "{p:?}");
    }
}
