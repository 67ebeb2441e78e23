//! `autobal map`: the stability margin over two parameters (a speed and/or parameter paths),
//! as one command ([`Args`] -> `run` -> [`Output`]): paper 000's 12-state model where it
//! represents the config ([`autobal::spatial::map`], with 003's necessary ranges and, with
//! `boundary`, the traced Hopf and fold curves), else the general route (the nonlinear
//! equations' stationary state: [`autobal::rotor_map`]). Rows are computed in parallel and
//! handed over in grid order: the CLI streams them to its CSV ([`Rows::Csv`]; an interrupted
//! map keeps its complete rows), Python keeps every cell ([`Rows::Keep`]); the figure is drawn
//! from a decimated copy ([`PLOT_CELLS`] per axis), so memory does not grow with the grid.
//!
//! The axes are the library's [`Axis`] (a parameter path and its values); a map's axes are
//! evenly spaced (the heatmap's cells), at most [`MAX_N`] values each.

use crate::command::{self, check_speed, ConfigSource, Figure, Route};
use crate::config::{self, Config};
use crate::plot::Series;
use anyhow::{anyhow, bail, Result};
use autobal::control::Control;
use autobal::paths::Axis;
use autobal::rotor_map::{Along, BoundaryPoint, FamilyVerdict, GeneralCell, GeneralMapOutcome, Kind, Verdict};
use autobal::rotor_stability::StateKind;
use autobal::spatial::boundary::{Boundary, Codim2Kind, CurveKind, TraceSettings};
use autobal::spatial::linear_model::Balls;
pub use autobal::spatial::map::{Cell, Quantity};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Most values per axis.
pub const MAX_N: usize = 100_000;

/// Most cells a map keeps in memory ([`Rows::Keep`], Python's arrays: about 16 bytes each).
pub const MAX_KEPT_CELLS: usize = 50_000_000;

/// `autobal map`'s arguments (`Default`: the CLI's defaults; the axes have none and are
/// required).
#[derive(Debug, Clone)]
pub struct Args {
    /// The config.
    pub config: ConfigSource,
    /// The horizontal axis: a speed (`omega`: Ω of a spatial config, rad/s of the planar rotor;
    /// `speed_rpm`, `speed`, `speed_hz` of a dimensional one) or a parameter path.
    pub x: Axis,
    /// The vertical axis.
    pub y: Axis,
    /// The speed when neither axis is one: a speed with its unit, or a bare number (Ω).
    pub omega: Option<String>,
    /// Balls free (12 states) or locked (8 states; the closed-form route only).
    pub balls: Balls,
    /// The margin (max Re λ) or the verdict alone (Routh–Hurwitz: faster, no margin).
    pub quantity: Quantity,
    /// Also trace the stability boundary (closed form: Hopf and fold curves; general route:
    /// each row's verdict changes bisected along `x`).
    pub boundary: bool,
    /// The route.
    pub route: Route,
}

impl Default for Args {
    fn default() -> Self {
        Args {
            config: ConfigSource::default(),
            x: Axis::new("", vec![]),
            y: Axis::new("", vec![]),
            omega: None,
            balls: Balls::Free,
            quantity: Quantity::Margin,
            boundary: false,
            route: Route::Auto,
        }
    }
}

/// A map's axis from its text form `KEY=LO:HI:N` (`flag` names it in errors): the library's
/// [`Axis::parse`], evenly spaced, checked as `run` checks it.
pub fn parse_axis(flag: &str, spec: &str) -> Result<Axis> {
    let a = Axis::parse(spec).map_err(|e| anyhow!("{flag} {e}"))?;
    if spec.split_once('=').is_none_or(|(_, r)| r.split(':').count() != 3) {
        bail!("{flag} {spec}: expected KEY=LO:HI:N (a map's axis is evenly spaced), e.g. {flag} omega=0.1:6:400");
    }
    check_axis(flag, spec, &a)?;
    Ok(a)
}

/// The checks of a map's axis (`name`: the spec or the path, in messages): a path, 2 to
/// [`MAX_N`] finite increasing values, a speed `omega` not negative.
fn check_axis(flag: &str, name: &str, a: &Axis) -> Result<()> {
    if a.path.is_empty() {
        return Err(autobal::Error::invalid(flag, format!("required: KEY=LO:HI:N, e.g. {flag} omega=0.1:6:400")).into());
    }
    let n = a.values.len();
    if !(2..=MAX_N).contains(&n) {
        return Err(autobal::Error::invalid(format!("{flag} {name}"), format!("N must lie between 2 and {MAX_N}, got {n}")).into());
    }
    if a.values.iter().any(|v| !v.is_finite()) || a.values.windows(2).any(|w| w[1] <= w[0]) {
        return Err(autobal::Error::invalid(format!("{flag} {name}"), "the values must be finite and increasing").into());
    }
    if a.path == "omega" && a.lo() < 0.0 {
        return Err(autobal::Error::invalid(format!("{flag} {name}"), "the speed Ω must not be negative").into());
    }
    Ok(())
}

/// Whether the axis is a speed: `omega` or, for a dimensional config, `speed_rpm`, `speed`
/// (rad/s), `speed_hz` ([`autobal::units::SPEED_PATHS`]).
fn is_speed(a: &Axis) -> bool {
    autobal::units::speed_path_unit(&a.path).is_some()
}

/// Where a map's rows go as they are computed.
pub enum Rows<'a> {
    /// Written as CSV in grid order (row `j` = every `x` at `y_j`), the header first; only the
    /// figure's decimated copy is kept.
    Csv(&'a mut dyn Write),
    /// Every cell kept in the [`Output`] (at most [`MAX_KEPT_CELLS`]).
    Keep,
    /// Only the figure's decimated copy kept.
    Figure,
}

/// A map whose arguments and config are checked, ready to compute ([`Args::prepare`]): a
/// front end checks its output files between the two.
pub struct Plan {
    args: Args,
    route: PlanRoute,
}

enum PlanRoute {
    /// `omega`: the fixed speed as `Ω` of the config's rotor; `at_si`: the fixed speed in rad/s
    /// where the axes move `ω0`, each cell then at its own `Ω`
    /// ([`autobal::spatial::map::stability_map_at_speed`]).
    Closed {
        cfg: Box<Config>,
        omega: Option<f64>,
        at_si: Option<f64>,
    },
    General {
        root: Box<toml::Table>,
        speed: Option<autobal::units::Speed>,
        planar: bool,
        linear: bool,
    },
}

impl command::Command for Args {
    const NAME: &'static str = "map";
    type Output = Output;

    /// Every cell kept ([`Rows::Keep`]).
    fn run(&self, control: &Control) -> Result<Output> {
        self.prepare()?.run(control, Rows::Keep)
    }
}

impl Args {
    /// Check the axes, read the config once and check the options against it (the speeds'
    /// ranges, the paths), before anything is computed or written.
    pub fn prepare(&self) -> Result<Plan> {
        check_axis("--x", &self.x.path, &self.x)?;
        check_axis("--y", &self.y.path, &self.y)?;
        if self.x.path == self.y.path {
            bail!("--y {}: the same key as --x; give the second axis another field", self.y.path);
        }
        // a fixed speed beside a speed axis would be ignored (hunt 27: exit 0, no word): the
        // library's one check and message (Python's linear rotor map meets it there), the
        // field as the CLI's flag
        if let Some(t) = &self.omega {
            let s = autobal::units::parse_speed("--omega", t)?;
            autobal::rotor_map::check_fixed_speed(&self.x, &self.y, Some(s)).map_err(|e| match e {
                autobal::Error::InvalidParameter { reason, .. } => autobal::Error::invalid("--omega", reason),
                e => e,
            })?;
        }
        // a linear rotor config ([linear_rotor]) takes its own --set and the general route
        let (root, source) = self.config.read_any()?;
        let linear = crate::linear_rotor::is_linear(&root);
        // `omega` of a dimensional spatial config is Ω = ω/ω0, not rad/s (a user writing SI
        // may not mean it; 100 there is ~3000 rad/s on examples/washing_machine.toml)
        if !linear && autobal::config::is_spatial(&root) && config::is_dimensional(&root) {
            for (flag, a) in [("--x", &self.x), ("--y", &self.y)] {
                if a.path == "omega" {
                    crate::term::note(&format!(
                        "note: {flag} omega is the dimensionless Ω = ω/ω0 on this dimensional config; for SI map over speed=LO:HI:N (rad/s), speed_rpm or speed_hz"
                    ));
                }
            }
        }
        if linear || self.route.is_general_verdict(&root) {
            return self.general_plan(root, linear);
        }
        // the speeds need the config's ω0: it is read (and checked) first
        let cfg = config::build(&root, &source)?;
        // an axis through zero unbalance or one ball: the whole map on the general route
        if [&self.x, &self.y].iter().any(|a| !is_speed(a) && a.values.iter().any(|&v| axis_value_needs_general(&cfg.spec, &a.path, v))) {
            return self.general_plan(root, linear);
        }
        config::check_entries(&root, "map", &[config::Model::Linear])?;
        let omega = self.omega.as_deref().map(|t| crate::linear::speed_arg(&cfg, "--omega", t)).transpose()?;
        if let Some(w) = omega {
            check_speed("--omega", w)?;
        }
        let (xa, ya) = (&self.x, &self.y);
        // a speed axis in SI (speed_rpm, speed, speed_hz) is converted to Ω point by point by the
        // library (autobal::spatial::map::stability_map_units); a fixed speed in SI must mean one Ω
        for (flag, a) in [("--x", xa), ("--y", ya)] {
            if is_speed(a) && a.path != "omega" && !cfg.dimensional {
                bail!("{flag} {}: a speed in SI needs a dimensional config (the rotor's ω0); this config is dimensionless: use omega=LO:HI:N (Ω)", a.path);
            }
        }
        // a fixed speed in SI over axes that move ω0 is a different Ω in each cell: each cell
        // at its own (the engineer's question: this machine at 1400 rpm, over its design)
        let fixed_si = self.omega.as_deref().and_then(|t| autobal::units::parse_speed("--omega", t).ok()).filter(|s| s.is_si());
        // ω0 over the map's corners ([`omega0_range`], the table's unit): the axes move it
        // where the corners differ (ω0 is monotone in each entry that moves it)
        let corners =
            omega0_range(self, &cfg.spec, |s: &mut autobal::spatial::paths::SpatialSpec, path, v| s.set(path, v), |s| Ok(s.build()?.scale.map(|k| k.omega0)));
        let at_si = fixed_si
            .filter(|_| !is_speed(xa) && !is_speed(ya))
            .filter(|_| corners.is_some_and(|[lo, hi]| lo != hi))
            .and_then(|s| s.unit.rad_s().map(|k| s.value * k))
            .filter(|&w| w > 0.0);
        if let (Some(w), Some([least, _])) = (at_si, corners) {
            // the largest Ω is the cell's of least ω0, at a corner: within the range of Ω
            // there (rev28: 5e6 rpm on 1 N/m springs was Ω = 1.7e6 in a corner, taken)
            check_speed("--omega", w / least)
                .map_err(|e| anyhow!("{e} (Ω = ω/ω0 at the map's corner of least ω0 = {} rad/s)", autobal::error::fmt_num(least)))?;
        }
        // typed, the options named as both front ends call them (`--route general` and
        // `route="general"`, `--omega` and `omega=`): Python's `analyse("map", boundary=True)`
        // reached this only while drawing, after every cell, with the CLI's flags (session 29)
        if at_si.is_some() && self.boundary {
            return Err(autobal::Error::invalid(
                "--boundary",
                "at a fixed speed in SI over axes that move ω0 (each cell at its own Ω) the boundary is not traced; use route general (its boundary is bisected between cells), or give omega as Ω",
            )
            .into());
        }
        for (flag, a) in [("--x", xa), ("--y", ya)] {
            if a.path == "omega" {
                check_speed(&format!("{flag} omega"), a.hi())?;
            } else if let (Some(k), Some(sc)) = (autobal::units::speed_path_unit(&a.path).and_then(|u| u.rad_s()), cfg.model.scale) {
                // the same range as Ω (at the config's ω0; a mass axis moves it a little)
                check_speed(&format!("{flag} {}", a.path), a.hi() * k / sc.omega0)?;
            }
        }
        for (flag, a) in [("--x", xa), ("--y", ya)] {
            if !is_speed(a) {
                cfg.spec.clone().set(&a.path, a.lo()).map_err(|e| anyhow!("{flag}: {e}"))?;
            }
        }
        config::check_axes(&root, "map", &[config::Model::Linear], &[("--x", xa), ("--y", ya)], &map_unused)?;
        if is_speed(xa) && is_speed(ya) {
            bail!("--x, --y: only one axis can be omega");
        }
        if !is_speed(xa) && !is_speed(ya) && omega.is_none() {
            return Err(autobal::Error::invalid("--omega", "required when neither axis is omega (the speed at which to map)").into());
        }
        Ok(Plan { args: self.clone(), route: PlanRoute::Closed { cfg: Box::new(cfg), omega, at_si } })
    }
}

impl Args {
    /// The plan of a map on the general route (`linear`: a `[linear_rotor]` config).
    fn general_plan(&self, root: toml::Table, linear: bool) -> Result<Plan> {
        if self.balls == Balls::Locked {
            bail!("--balls locked: the general route maps the balls free (use the 12-state route of a one-plane config for the locked rotor)");
        }
        if !linear {
            config::check_entries(&root, "map", &[config::simulation_model(&root)])?;
            config::check_axes(&root, "map", &[config::simulation_model(&root)], &[("--x", &self.x), ("--y", &self.y)], &map_unused)?;
        }
        let speed = self.omega.as_deref().map(|t| autobal::units::parse_speed("--omega", t)).transpose()?;
        // the linear rotor's speed is ω in rad/s, as the planar rotor's
        let planar = linear || !autobal::config::is_spatial(&root);
        self.check_speed_axes(&root, planar)?;
        Ok(Plan { args: self.clone(), route: PlanRoute::General { root: Box::new(root), speed, planar, linear } })
    }
}

impl Args {
    /// The general route's speed axis within the range `stability` takes for its top speed
    /// (`--omega-max`, the one check and message: [`crate::command::check_speed_rad_s`] in
    /// rad/s for a planar or linear rotor, [`crate::command::check_speed_omega`] in `Ω` for a
    /// spatial one, an SI axis at the config's `ω0`). Walk 32: the map took speeds of 1e308
    /// (exit 0, every cell without a state) where `stability` refuses them.
    fn check_speed_axes(&self, root: &toml::Table, planar: bool) -> Result<()> {
        for (flag, a) in [("--x", &self.x), ("--y", &self.y)] {
            let Some(unit) = autobal::units::speed_path_unit(&a.path) else { continue };
            let flag = format!("{flag} {}", a.path);
            let hi = a.hi();
            let f = autobal::error::fmt_num;
            match unit.rad_s() {
                // rad/s on a planar or linear rotor; a dimensionless spatial rotor's Ω
                None if planar => crate::command::check_speed_rad_s(&flag, &format!("{} rad/s", f(hi)), hi)?,
                None => crate::command::check_speed_omega(&flag, &f(hi), hi, None)?,
                Some(k) if planar => crate::command::check_speed_rad_s(&flag, &format!("{} {}", f(hi), unit.symbol()), hi * k)?,
                Some(k) => {
                    // the config's ω0 (an axis that moves it moves it a little); a config the
                    // rotor cannot be built from is left to the map's own error
                    // (a dimensionless one: the library's refusal of an SI axis)
                    if let Some(g) = crate::general::rotor_of(root).ok().filter(|g| g.si) {
                        crate::command::check_speed_omega(&flag, &format!("{} {}", f(hi), unit.symbol()), hi * k / g.omega0, Some(g.omega0))?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// The keys a map's models read without using them ([`config::check_axes`]): a map computes
/// the stationary states at prescribed speeds, so a run's settings (`[drive]`, `[integration]`,
/// `[initial]`) and the drag on the spin (`spatial.spin_drag`, `planar.c_theta`) change none of
/// its cells.
fn map_unused(_: &toml::Table, path: &str) -> Option<String> {
    let table = path.split('.').next().unwrap_or_default();
    if autobal::config::RUN_TABLES.contains(&table) {
        return Some("a run's setting: `map` computes the stationary states at each speed and runs nothing".into());
    }
    matches!(path, "spatial.spin_drag" | "planar.c_theta").then(|| "acts on the spin only, and `map` prescribes the speed (its speed axis or --omega)".into())
}

/// Whether the map's cell with `path = value` on the closed form's config `spec` needs the
/// general verdict ([`crate::general::needs_general_verdict`]: no unbalance, or one ball): a
/// map is drawn on one route, so an axis through zero unbalance (`unbalance.mass = 0:…`) or one
/// ball takes the whole map onto the general route. Before (session 20's fix), the route was
/// decided from the config as given, and such a map drew its zero row by paper 000's closed
/// form, which counts the balancing family's neutral direction as "not stable": the row read
/// unstable (margin ~1e-27) where `stability` on that cell's config finds the family's stable
/// members (`tests/map_route_20.rs`). The same rule as [`Rotor::has_unbalance`] for the closed
/// form's rotor (one plane, the unbalance in it): `|m0 R0| ≤ NO_UNBALANCE · n m R`, read from
/// the spec's fields (parsing each cell's config for the full rule cost 390 k instructions a
/// value, +68 % on a 400-value axis); a unit test holds it to the full rule. A value the spec
/// refuses is left to the map's own checks.
///
/// [`Rotor::has_unbalance`]: autobal::rotor_stability::Rotor::has_unbalance
fn axis_value_needs_general(spec: &autobal::spatial::paths::SpatialSpec, path: &str, value: f64) -> bool {
    let mut s = spec.clone();
    if s.set(path, value).is_err() {
        return false;
    }
    let g = |p: &str| s.get(p).unwrap_or(f64::NAN);
    // (unbalance, capacity Σ m R, balls)
    let (u, cap, n) = match &s.input {
        autobal::spatial::paths::SpatialInput::Dimensionless(_) => {
            (g("dimensionless.m0") * g("dimensionless.r0"), g("dimensionless.m") * g("dimensionless.r"), g("dimensionless.n"))
        }
        autobal::spatial::paths::SpatialInput::Si { .. } => {
            let n = g("balancer.balls");
            (g("unbalance.mass") * g("unbalance.radius"), n * g("balancer.ball_mass") * g("balancer.race_radius"), n)
        }
    };
    // a config that gives the 12-state model's inputs directly (`delta_a`, `m`, `d_a`: no
    // masses, so no unbalance or capacity to read) has no general route at all (it needs the
    // masses): the closed form's (session 25: such a map over z_a was refused, "the
    // simulation needs the masses", where `critical` and `stability` take the config)
    if !(u.is_finite() && cap.is_finite()) {
        return n == 1.0;
    }
    n == 1.0 || !(u.abs() > autobal::rotor_stability::NO_UNBALANCE * cap)
}

impl Plan {
    /// The plan with its options checked as given, `boundary` included ([`Args::prepare`]),
    /// that computes the cells without tracing the boundary: Python's `analyse("map",
    /// boundary=True)` keeps the cells and traces the boundary only for its figure, so a
    /// boundary that cannot be traced is refused before any cell is computed.
    pub fn untraced(mut self) -> Plan {
        self.args.boundary = false;
        self
    }

    /// Compute the map under `control` (Ctrl-C keeps the complete rows; progress is reported in
    /// rows), its rows going to `rows`.
    pub fn run(&self, control: &Control, rows: Rows<'_>) -> Result<Output> {
        let a = &self.args;
        if matches!(rows, Rows::Keep) {
            let cells = a.x.values.len().saturating_mul(a.y.values.len());
            if cells > MAX_KEPT_CELLS {
                return Err(autobal::Error::TooLarge {
                    what: "x × y".into(),
                    size: cells as u64,
                    limit: MAX_KEPT_CELLS as u64,
                    reason: "cells of the map held in memory".into(),
                }
                .into());
            }
        }
        let t0 = std::time::Instant::now();
        let route = match &self.route {
            PlanRoute::Closed { cfg, omega, at_si } => {
                let traced = match a.boundary {
                    true => {
                        let t = std::time::Instant::now();
                        let b = trace(cfg, &a.x, &a.y, *omega, a.balls, control)?;
                        Some((b, t.elapsed().as_secs_f64()))
                    }
                    false => None,
                };
                if traced.as_ref().is_some_and(|(b, _)| !b.complete) {
                    // nothing of the map is computed after an interrupted trace
                    let (dx, dy) = (decimate(&a.x).1, decimate(&a.y).1);
                    let figure = FigureCells::new(dx, dy, a.quantity);
                    RouteOutput::Closed { figure, cells: None, rows_done: 0, continued: 0, direct: 0, traced, at_si: None }
                } else {
                    let speed = match at_si {
                        Some(w) => FixedSpeed::Si(*w),
                        None => FixedSpeed::Omega(*omega),
                    };
                    let (figure, run, cells) = compute(cfg, &a.x, &a.y, speed, a.balls, a.quantity, rows, control)?;
                    // the speed as given (`1400 rpm`), named in the table and the figure
                    let at_si = at_si.and(a.omega.as_deref()).and_then(|t| autobal::units::parse_speed("--omega", t).ok()).map(|s| s.to_string());
                    RouteOutput::Closed { figure, cells, rows_done: run.rows_done, continued: run.continued, direct: run.direct, traced, at_si }
                }
            }
            PlanRoute::General { root, speed, planar, linear } => general(root, a, *speed, *planar, *linear, rows, control)?,
        };
        let dimensional = match &self.route {
            PlanRoute::Closed { cfg, .. } => cfg.dimensional,
            PlanRoute::General { root, planar, linear, .. } => !planar && !linear && config::is_dimensional(root),
        };
        // the unit of the margins per τ (audit 25's F6: printed nowhere, and on a two-plane
        // rotor not the whole rotor's sqrt(c/M)); its range where an axis moves it (review
        // 25b: one ω0 printed for all cells was 12-15 % off there)
        let omega0 = match &self.route {
            _ if !dimensional => None,
            PlanRoute::Closed { cfg, .. } => {
                omega0_range(a, &cfg.spec, |s: &mut autobal::spatial::paths::SpatialSpec, path, v| s.set(path, v), |s| Ok(s.build()?.scale.map(|k| k.omega0)))
            }
            PlanRoute::General { root, .. } => omega0_range(
                a,
                root.as_ref(),
                |t: &mut toml::Table, path, v| autobal::config::set_number(t, path, v),
                |t| Ok(autobal::config::spatial_simulation(t)?.config.model.scale.map(|k| k.omega0)),
            ),
        };
        Ok(Output {
            x: a.x.clone(),
            y: a.y.clone(),
            balls: a.balls,
            quantity: a.quantity,
            secs: t0.elapsed().as_secs_f64(),
            route,
            written: None,
            margin_column: margin_column(dimensional),
            omega0,
        })
    }
}

/// `map`'s result.
pub struct Output {
    /// The axes, every value.
    pub x: Axis,
    pub y: Axis,
    /// Free or locked.
    pub balls: Balls,
    /// What the cells hold.
    pub quantity: Quantity,
    /// Wall time (s).
    pub secs: f64,
    /// The route's cells and counts.
    pub route: RouteOutput,
    /// The stem the front end wrote the files to (`STEM.csv`, `.svg`, `.png`,
    /// `STEM_boundary.csv`), named in the table and the messages.
    pub written: Option<PathBuf>,
    /// The margin's column name in the CSV and Python's table ([`margin_column`]): per τ on a
    /// dimensional spatial config.
    pub margin_column: &'static str,
    /// On a dimensional spatial config, `ω0 = sqrt(c_x / M_s)` (rad/s) of paper 000's
    /// nondimensionalisation: the margin column is per `τ = ω0 t` ([`OMEGA0_WORDS`]); its
    /// least and largest value over the map (equal unless an axis moves a stiffness or a mass:
    /// then each cell's margin is per τ of its own cell's `ω0`).
    pub omega0: Option<[f64; 2]>,
}

/// `ω0` over the map's four corners (`[min, max]`; equal where no axis moves it): `base` with
/// each config axis at its first or last value (`set`; a speed axis is no config entry) and
/// `ω0` read by `omega0`; `None` where a corner has none. `ω0 = sqrt(c_x / M_s)` is monotone
/// in each entry that moves it (a stiffness, a mass), so the corners hold its extremes.
fn omega0_range<T: Clone>(
    a: &Args,
    base: &T,
    set: impl Fn(&mut T, &str, f64) -> autobal::Result<()>,
    omega0: impl Fn(&T) -> autobal::Result<Option<f64>>,
) -> Option<[f64; 2]> {
    let ends = |ax: &Axis| [ax.values[0], ax.values[ax.values.len() - 1]];
    let put = |t: &mut T, ax: &Axis, v: f64| if is_speed(ax) { Ok(()) } else { set(t, &ax.path, v) };
    let mut range = [f64::INFINITY, f64::NEG_INFINITY];
    for xv in ends(&a.x) {
        for yv in ends(&a.y) {
            let mut t = base.clone();
            put(&mut t, &a.x, xv).ok()?;
            put(&mut t, &a.y, yv).ok()?;
            let w = omega0(&t).ok()??;
            range = [range[0].min(w), range[1].max(w)];
        }
    }
    Some(range)
}

/// What `ω0` is, beside its value in the table: `M_s` is paper 000's one-plane rotor's mass.
pub const OMEGA0_WORDS: &str = "sqrt(c_x / M_s), M_s = the rotor with the unbalance and the first balancer plane's balls, paper 000's (a couple mass and a second plane's balls are not in it)";

/// The cells and counts of each route.
pub enum RouteOutput {
    /// Paper 000's 12-state model.
    Closed {
        /// The figure's decimated copy, compact.
        figure: FigureCells,
        /// Every row ([`Rows::Keep`]): `cells[j][i]` at `(x_i, y_j)`.
        cells: Option<Vec<Vec<Cell>>>,
        /// Rows computed.
        rows_done: usize,
        /// Points from continuation or the characteristic polynomial, and direct solves.
        continued: usize,
        direct: usize,
        /// The traced boundary and its wall time (s), with `boundary`; the map is not computed
        /// when the trace was interrupted.
        traced: Option<(Boundary, f64)>,
        /// The fixed speed in SI over axes that move `ω0` (as given, e.g. `1400 rpm`): each
        /// cell at its own `Ω`.
        at_si: Option<String>,
    },
    /// The general route.
    General {
        /// The figure's decimated axes and rows.
        fx: Axis,
        fy: Axis,
        frows: Vec<Option<Vec<GeneralCell>>>,
        /// Every row ([`Rows::Keep`]).
        cells: Option<Vec<Vec<GeneralCell>>>,
        /// The library's counts.
        outcome: GeneralMapOutcome,
        /// The planar or a linear rotor (ω in rad/s), else the spatial one.
        planar: bool,
        /// A linear rotor (`[linear_rotor]`).
        linear: bool,
        /// The bisected boundary points, with `boundary`.
        traced: Option<Vec<BoundaryPoint>>,
    },
}

/// The bisected boundary points found along `x` (within a row) and along `y` (within a
/// column).
fn along_counts(t: &[BoundaryPoint]) -> (usize, usize) {
    let nx = t.iter().filter(|b| b.along == Along::X).count();
    (nx, t.len() - nx)
}

/// The general route's points where a stationary state appears or is lost (`from` or `to`
/// empty: located to [`autobal::rotor_map::FOLD_RTOL`], not bisected to 1e-9).
fn fold_count(t: &[BoundaryPoint]) -> usize {
    t.iter().filter(|b| b.from.is_none() || b.to.is_none()).count()
}

/// `STEM_boundary.csv`: the traced boundary beside the map.
pub fn boundary_path(stem: &Path) -> PathBuf {
    PathBuf::from(format!("{}_boundary.csv", stem.display()))
}

/// The general route's CSV verdict of a cell below the periodic-orbit floor
/// ([`autobal::rotor_stability::Rotor::periodic_floor`]): not analysed, no state sought.
pub const NOT_ANALYSED: &str = "not_analysed";

fn verdict_name(v: Option<Verdict>) -> &'static str {
    match v {
        None => "",
        Some(Verdict::Stable) => "stable",
        Some(Verdict::Unstable) => "unstable",
        Some(Verdict::Neutral) => "neutral",
    }
}

impl Output {
    /// Rows computed.
    pub fn rows_done(&self) -> usize {
        match &self.route {
            RouteOutput::Closed { rows_done, .. } => *rows_done,
            RouteOutput::General { outcome, .. } => outcome.rows,
        }
    }

    /// Free the closed route's copy of the cells for the figure once
    /// [`command::Output::figures`] has drawn it (the table, JSON and notes do not read it): its
    /// pages are then reused by the figure's rendering (the PNG's 3.8 MB pixmap) instead of new
    /// ones being touched.
    pub fn release_figure_cells(&mut self) {
        if let RouteOutput::Closed { figure, .. } = &mut self.route {
            figure.rows = vec![];
            figure.rows.shrink_to_fit();
        }
    }

    /// Whether the map was computed (not after an interrupted boundary trace).
    pub fn map_computed(&self) -> bool {
        match &self.route {
            RouteOutput::Closed { traced, .. } => traced.as_ref().is_none_or(|(b, _)| b.complete),
            RouteOutput::General { .. } => true,
        }
    }

    /// The traced boundary as CSV (`STEM_boundary.csv`), with `boundary`: the closed form's
    /// curves ([`boundary_csv`]), or the general route's bisected points `x,y,from,to,along`
    /// (where the margin changes sign, bisected to 1e-9 relative, or a stationary state
    /// appears or is lost, to ~1e-4 relative ([`autobal::rotor_map::FOLD_RTOL`]), between two
    /// neighbouring cells, along `x` between two cells of a row or along `y` between two of a
    /// column, as `along` says; `from`, `to` the verdicts on the sides of the smaller and the
    /// larger value of that axis, empty where there is no stationary state).
    pub fn boundary_csv(&self) -> Option<String> {
        match &self.route {
            RouteOutput::Closed { traced, .. } => traced.as_ref().map(|(b, _)| boundary_csv(b, &self.x.path, &self.y.path)),
            RouteOutput::General { traced, .. } => traced.as_ref().map(|pts| {
                use std::fmt::Write as _;
                let mut t = format!("{},{},from,to,along\n", self.x.path, self.y.path);
                for b in pts {
                    let _ = writeln!(t, "{},{},{},{},{}", crate::num::Csv(b.x), crate::num::Csv(b.y), verdict_name(b.from), verdict_name(b.to), b.along.key());
                }
                t
            }),
        }
    }

    /// Lines for standard error: the boundary's counts, the general route's families.
    pub fn notes(&self) -> Vec<String> {
        let wrote = |what: String| self.written.as_ref().map_or(what.clone(), |s| format!("{what}; wrote {}", boundary_path(s).display()));
        let mut out = vec![];
        match &self.route {
            RouteOutput::Closed { traced: Some((b, secs)), .. } => out.push(wrote(format!(
                "boundary: {} curves, {} codimension-two points, {} characteristic polynomials, {secs:.3} s",
                b.curves.len(),
                b.codim2.len(),
                b.evaluations
            ))),
            RouteOutput::General { traced, outcome, .. } => {
                if let Some(t) = traced {
                    let (nx, ny) = along_counts(t);
                    // a state's fold is where continuation stops converging, not bisected to
                    // 1e-9 (walk 32: the note claimed 1e-9 for every point)
                    let folds = fold_count(t);
                    let located = if folds == 0 {
                        "bisected to 1e-9 relative".to_string()
                    } else {
                        format!(
                            "{} where the verdict changes, bisected to 1e-9 relative, {folds} where a stationary state appears or is lost (an empty from or to: a fold, located where continuation stops converging, to ~{} relative)",
                            t.len() - folds,
                            autobal::error::fmt_num(autobal::rotor_map::FOLD_RTOL)
                        )
                    };
                    out.push(wrote(format!(
                        "boundary: {} points between neighbouring cells ({nx} along {} within a row, {ny} along {} within a column): {located}",
                        t.len(),
                        self.x.path,
                        self.y.path
                    )));
                }
                if outcome.families > 0 {
                    out.push(format!(
                        "{} cells have a family of balanced states (n ≥ 3 balls, or no unbalance to cancel): max_real_part and verdict{} are those of one member, the one reached from the closed form (balls in a symmetric arc); the column family says whether all, some or none of the family's members are stable",
                        outcome.families,
                        if traced.is_some() { ", and the boundary points," } else { "" }
                    ));
                }
            }
            _ => {}
        }
        out
    }

    /// The files written, as the table names them.
    fn wrote(&self) -> String {
        match &self.written {
            Some(s) => format!(
                "; wrote {}, {}, {}",
                crate::term::with_suffix(s, "csv").display(),
                crate::term::with_suffix(s, "svg").display(),
                crate::term::with_suffix(s, "png").display()
            ),
            None => String::new(),
        }
    }

    /// The state the general route maps, in words: the kind of the cells' states, or that no
    /// cell has one ([`general_state`]).
    fn state(outcome: &GeneralMapOutcome) -> &'static str {
        match general_state(outcome) {
            None => NO_STATE,
            Some(Kind::Equilibrium) => "equilibrium (eigenvalues)",
            Some(Kind::PeriodicOrbit) => "periodic orbit (Floquet multipliers)",
        }
    }
}

/// The table's words on the cells whose state is not the (semi-)balanced one (none: nothing):
/// their verdicts are those states' (a "stable" not-balanced cell is the balls held on the
/// unbalance's side, not a balancer that works), as `stability`'s table says of its speeds.
fn state_words(o: &GeneralMapOutcome) -> String {
    let mut parts = vec![];
    if o.partially_balanced > 0 {
        parts.push(format!("{} partially balanced (no balanced state exists there)", o.partially_balanced));
    }
    if o.not_balanced > 0 {
        parts.push(format!("{} not balanced", o.not_balanced));
    }
    if parts.is_empty() {
        return String::new();
    }
    format!("; cells whose state is {}: the verdicts there are those states', not a balanced state's (the CSV's state column)", parts.join(", "))
}

/// The kind of stationary state the general route's map found: a periodic orbit where any cell
/// has one, else an equilibrium; `None` where no cell has a stationary state (every cell
/// without one or not analysed: then no kind is claimed, hunt 28: such a map read "stationary
/// state: equilibrium (eigenvalues)" on a config whose state would be a periodic orbit).
fn general_state(o: &GeneralMapOutcome) -> Option<Kind> {
    match (o.closed_form + o.continued, o.periodic) {
        (0, _) => None,
        (_, 0) => Some(Kind::Equilibrium),
        _ => Some(Kind::PeriodicOrbit),
    }
}

/// The table's and the figure's words where no cell of the general route's map has a
/// stationary state.
const NO_STATE: &str = "none found (no cell has a stationary state)";

/// The table's words on the cells below the periodic-orbit floor (none: nothing).
fn not_analysed_words(n: usize) -> String {
    if n == 0 {
        return String::new();
    }
    format!(
        ", {n} not analysed (below the periodic-orbit floor: a revolution longer than {} periods of the fastest natural vibration)",
        autobal::rotor_stability::PERIODS_PER_REVOLUTION
    )
}

/// An axis as the JSON gives it: its path, ends and number of values.
fn axis_json(a: &Axis) -> Value {
    json!({"path": a.path, "lo": a.lo(), "hi": a.hi(), "n": a.values.len()})
}

impl command::Output for Output {
    /// The map's summary (its cells are the CSV's, or Python's arrays): the route, the axes, the
    /// rows computed and how, the boundary's counts, the files written.
    fn json(&self) -> Result<Value> {
        let mut v = json!({
            "x": axis_json(&self.x),
            "y": axis_json(&self.y),
            "balls": if self.balls == Balls::Free { "free" } else { "locked" },
            "quantity": if self.quantity == Quantity::Margin { "margin" } else { "verdict" },
            "rows_computed": self.rows_done(),
            "rows": self.y.values.len(),
            "wall_s": self.secs,
            "stopped": command::Output::stopped(self),
            "margin_column": self.margin_column,
            "omega0_rad_s": self.omega0.filter(|[a, b]| a == b).map(|[a, _]| a),
            "omega0_range_rad_s": self.omega0,
        });
        match &self.route {
            RouteOutput::Closed { continued, direct, traced, at_si, .. } => {
                v["route"] = json!("closed_form");
                v["fixed_speed"] = json!(at_si);
                v["continued"] = json!(continued);
                v["direct"] = json!(direct);
                if let Some((b, _)) = traced {
                    v["boundary"] =
                        json!({"curves": b.curves.len(), "codimension_two_points": b.codim2.len(), "evaluations": b.evaluations, "complete": b.complete});
                }
            }
            RouteOutput::General { outcome, traced, .. } => {
                v["route"] = json!("general");
                // null where no cell has a stationary state (no kind is claimed)
                v["state"] = json!(general_state(outcome).map(|k| if k == Kind::PeriodicOrbit { "periodic_orbit" } else { "equilibrium" }));
                v["closed_form"] = json!(outcome.closed_form);
                v["continued"] = json!(outcome.continued);
                v["without_stationary_state"] = json!(outcome.none);
                v["not_analysed"] = json!(outcome.not_analysed);
                v["families"] = json!(outcome.families);
                v["partially_balanced"] = json!(outcome.partially_balanced);
                v["not_balanced"] = json!(outcome.not_balanced);
                if let Some(t) = traced {
                    let (nx, ny) = along_counts(t);
                    let folds = fold_count(t);
                    // family_member: the points are those of one member's margin where cells
                    // have a family (walk 34: nothing said so of the boundary)
                    v["boundary"] = json!({"bisected_points": t.len(), "along_x": nx, "along_y": ny, "fold_points": folds, "rtol": autobal::rotor_map::BOUNDARY_RTOL, "fold_rtol": autobal::rotor_map::FOLD_RTOL, "family_member": outcome.families > 0});
                }
            }
        }
        if let Some(s) = &self.written {
            v["csv"] = json!(crate::term::with_suffix(s, "csv").display().to_string());
        }
        Ok(v)
    }

    /// One line: rows × points, the time, how the points were answered, the files written
    /// (nothing when the map was not computed).
    fn table(&self) -> Result<String> {
        if !self.map_computed() {
            return Ok(String::new());
        }
        let n = self.x.values.len();
        let done = self.rows_done();
        let per_point = 1e6 * self.secs / (done * n).max(1) as f64;
        let unit = self.omega0.map_or(String::new(), |[a, b]| {
            if a == b {
                format!("{}: margins per τ = ω0 t, ω0 = {} rad/s = {OMEGA0_WORDS} (multiply by ω0 for 1/s)\n", self.margin_column, autobal::error::fmt_num(a))
            } else {
                format!(
                    "{}: margins per τ = ω0 t of each cell's own ω0 = {OMEGA0_WORDS}, which the axes move: {} to {} rad/s over the map (multiply a cell's margin by its own ω0 for 1/s)\n",
                    self.margin_column,
                    autobal::error::fmt_num(a),
                    autobal::error::fmt_num(b)
                )
            }
        });
        Ok(unit + &match &self.route {
            RouteOutput::Closed { continued, direct, at_si, .. } => format!(
                "{}{done} rows × {n} points in {:.2} s ({per_point:.2} µs per point; {continued} by continuation, {direct} direct solves){}\n",
                at_si.as_ref().map_or(String::new(), |w| format!("every cell at {w}: its own Ω = ω/ω0 of that cell's rotor\n")),
                self.secs,
                self.wrote()
            ),
            RouteOutput::General { outcome, .. } => format!(
                "general route: {done} rows × {n} points in {:.2} s ({per_point:.2} µs per point; {} from the closed form, {} continued from a neighbour, {} without a stationary state{}); stationary state: {}{}{}\n",
                self.secs,
                outcome.closed_form,
                outcome.continued,
                outcome.none,
                not_analysed_words(outcome.not_analysed),
                Output::state(outcome),
                state_words(outcome),
                self.wrote()
            ),
        })
    }

    /// `stability_map`: the margin (or verdict) heatmap with the stability boundary; the closed
    /// form adds 003's necessary boundary and, with `boundary`, the traced curves; the general
    /// route the bisected boundary points. None when the map was not computed. An interrupted
    /// map's title begins `INCOMPLETE:` (as `stability`'s and `campbell`'s figures:
    /// `stability::mark_stopped`; its rows not computed are blank).
    fn figures(&self) -> Result<Vec<Figure>> {
        if !self.map_computed() {
            return Ok(vec![]);
        }
        let p = match &self.route {
            RouteOutput::Closed { figure, traced, at_si, .. } => {
                let at = at_si.as_ref().map_or(String::new(), |w| format!(", at {w}"));
                let mut p = plot_cells(figure, &format!("Stability map, balls {}{at}", if self.balls == Balls::Free { "free" } else { "locked" }));
                if let Some((b, _)) = traced {
                    p.series.extend(boundary_series(b));
                }
                p
            }
            RouteOutput::General { fx, fy, frows, outcome, planar, linear, traced, .. } => {
                general_plot(fx, fy, frows, outcome, *planar, *linear, self.quantity, traced.as_deref())
            }
        };
        Ok(vec![Figure::new("stability_map", crate::stability::mark_stopped(p, &command::Output::stopped(self), None))])
    }

    fn stopped(&self) -> Option<String> {
        let kept = |p: PathBuf| format!(" and kept in {}", p.display());
        if let RouteOutput::Closed { traced: Some((b, _)), .. } = &self.route {
            if !b.complete {
                return Some(format!(
                    "interrupted while tracing the boundary: the {} curves traced are kept{}; the map was not computed",
                    b.curves.len(),
                    self.written.as_ref().map_or(String::new(), |s| format!(" in {}", boundary_path(s).display()))
                ));
            }
        }
        let (done, total) = (self.rows_done(), self.y.values.len());
        (done < total).then(|| {
            format!("interrupted: {done} of {total} rows computed{}", self.written.as_ref().map_or(String::new(), |s| kept(crate::term::with_suffix(s, "csv"))))
        })
    }
}

/// The data the figures are drawn from: the whole map, or a decimated copy of a large one
/// (every k-th row and column, at most [`PLOT_CELLS`] per axis).
pub struct MapResult {
    pub x: Axis,
    pub y: Axis,
    /// `rows[j][i]` at `(x_i, y_j)`; `None` for rows not computed (interrupted).
    pub rows: Vec<Option<Vec<Cell>>>,
    pub quantity: Quantity,
}

/// The copy of a closed-route map's cells its figure is drawn from (decimated as
/// [`MapResult`]), compact: each cell's two flags in one byte ([`FigureCells::STABLE`],
/// [`FigureCells::NECESSARY`]) and, for a margin map, its margin: 1 or 9 bytes a cell instead
/// of a [`Cell`]'s 16 (a 400 x 400 verdict map's copy is 160 kB instead of 2.6 MB, which the
/// command touched while the map ran).
pub struct FigureCells {
    pub x: Axis,
    pub y: Axis,
    pub quantity: Quantity,
    /// Per row (`None`: not computed): the flags and, for a margin map, the margins.
    rows: Vec<Option<(Vec<u8>, Vec<f64>)>>,
}

impl FigureCells {
    /// Bit of a stable cell.
    pub const STABLE: u8 = 1;
    /// Bit of a cell inside 003's necessary ranges.
    pub const NECESSARY: u8 = 2;

    /// No row computed yet.
    pub fn new(x: Axis, y: Axis, quantity: Quantity) -> Self {
        let n = y.values.len();
        FigureCells { x, y, quantity, rows: vec![None; n] }
    }

    /// Row `j`: every `k`-th of `cells`, at most `n` (a verdict map keeps no margin).
    fn set_row(&mut self, j: usize, cells: &[Cell], k: usize, n: usize) {
        let flag = |c: &Cell| (c.stable as u8 * Self::STABLE) | (c.necessary as u8 * Self::NECESSARY);
        let (flags, margins): (Vec<u8>, Vec<f64>) = match (k, self.quantity) {
            // undecimated: plain passes over the slice
            (1, Quantity::Verdict) => (cells[..n.min(cells.len())].iter().map(flag).collect(), vec![]),
            (1, Quantity::Margin) => (cells[..n.min(cells.len())].iter().map(flag).collect(), cells[..n.min(cells.len())].iter().map(|c| c.margin).collect()),
            (_, Quantity::Verdict) => (cells.iter().step_by(k).take(n).map(flag).collect(), vec![]),
            (_, Quantity::Margin) => (cells.iter().step_by(k).take(n).map(flag).collect(), cells.iter().step_by(k).take(n).map(|c| c.margin).collect()),
        };
        self.rows[j] = Some((flags, margins));
    }

    /// The copy of a whole [`MapResult`].
    pub fn from_map(r: &MapResult) -> Self {
        let mut f = FigureCells::new(r.x.clone(), r.y.clone(), r.quantity);
        for (j, row) in r.rows.iter().enumerate() {
            if let Some(cells) = row {
                f.set_row(j, cells, 1, cells.len());
            }
        }
        f
    }
}

/// How far a map got.
pub struct MapRun {
    /// Rows computed.
    pub rows_done: usize,
    /// Points from continuation / characteristic polynomial, and direct solves.
    pub continued: usize,
    pub direct: usize,
}

/// Largest number of cells per axis kept for the figures.
pub const PLOT_CELLS: usize = 500;

/// Stride and decimated axis: the values `0, k, 2k, …` of `a`.
fn decimate(a: &Axis) -> (usize, Axis) {
    let k = a.values.len().div_ceil(PLOT_CELLS).max(1);
    if k == 1 {
        return (1, a.clone());
    }
    (k, Axis::new(a.path.clone(), a.values.iter().copied().step_by(k).collect()))
}

/// The closed route's CSV rows, formatted into buffers kept for the whole map (no fresh
/// megabytes per batch, no copy of a row's cells where the library's slice serves). On one
/// thread each row is formatted as it comes, from the library's slice, into one text that is
/// written once it holds [`crate::sim::CSV_CHUNK`] bytes (the staged file's buffer size: a write that large
/// goes to the file without a copy into that buffer). On more threads the rows are formatted in
/// parallel in batches of about 64 k cells (the pool is idle between the library's blocks),
/// the batch's cells and its rows' texts reused from batch to batch. The bytes are the same
/// either way.
struct CsvRows<'a> {
    /// The `x` values' CSV text, once.
    xs: Vec<Piece>,
    y: &'a [f64],
    nx: usize,
    /// `--quantity verdict`: an empty margin field.
    verdict_only: bool,
    /// Rows per batch (1: each row formatted as it comes).
    batch: usize,
    /// The batch's row indices and cells (`nx` a row).
    rows: Vec<usize>,
    cells: Vec<Cell>,
    /// One text per row of a batch; on one thread `texts[0]`, the text being collected.
    texts: Vec<Vec<u8>>,
}

/// A short text (at most [`Piece::N`] bytes) kept in a fixed-size array, so that appending it
/// is one fixed-size copy (no call to a variable-length copy) and a cut back to its length.
#[derive(Clone, Copy)]
struct Piece {
    bytes: [u8; Piece::N],
    len: usize,
}

impl Piece {
    const N: usize = 32;

    /// `text` as a piece; `None` when it is longer than [`Piece::N`].
    fn new(text: &[u8]) -> Option<Piece> {
        let mut bytes = [0u8; Piece::N];
        bytes.get_mut(..text.len())?.copy_from_slice(text);
        Some(Piece { bytes, len: text.len() })
    }

    /// Append the text to `t`: all [`Piece::N`] bytes, then `t` cut back by the padding.
    #[inline]
    fn push(&self, t: &mut Vec<u8>) {
        t.extend_from_slice(&self.bytes);
        t.truncate(t.len() - (Piece::N - self.len));
    }
}

impl<'a> CsvRows<'a> {
    fn new(x: &Axis, y: &'a Axis, verdict_only: bool, threads: usize) -> Self {
        let nx = x.values.len();
        let xs = x
            .values
            .iter()
            .map(|v| {
                let mut t = vec![];
                crate::num::Csv(*v).push_to(&mut t);
                Piece::new(&t).expect("a double's shortest text is at most 24 bytes")
            })
            .collect();
        let batch = if threads > 1 { crate::sim::CSV_CHUNK / nx.max(1) + 1 } else { 1 };
        CsvRows { xs, y: &y.values, nx, verdict_only, batch, rows: vec![], cells: vec![], texts: vec![vec![]] }
    }

    /// Append row `j`'s lines (`x,y,margin,stable,necessary`) to `t`: each line from fixed-size
    /// pieces (the `x` text; `,y,` or, with no margin, `,y,,s,n` whole) copied 32 bytes at a
    /// time and cut back to their length, instead of five variable-length copies a cell.
    fn format(xs: &[Piece], y: f64, verdict_only: bool, cells: &[Cell], t: &mut Vec<u8>) {
        let mut yv = Vec::with_capacity(24);
        crate::num::Csv(y).push_to(&mut yv);
        let flags = |s: bool, n: bool| [b',', b'0' + s as u8, b',', b'0' + n as u8, b'\n'];
        let all = [flags(false, false), flags(false, true), flags(true, false), flags(true, true)];
        let idx = |c: &Cell| 2 * c.stable as usize + c.necessary as usize;
        t.reserve(cells.len() * (xs.iter().map(|p| p.len).max().unwrap_or(0) + yv.len() + 32));
        // `y`'s shortest text is at most 24 bytes: `,y,` (26) and `,y,,s,n` (31) fit a piece
        const FITS: &str = "a double's shortest text is at most 24 bytes";
        if verdict_only {
            // `--quantity verdict` computes no margin: an empty field, never `NaN`
            let ends = all.map(|f| Piece::new(&[&b","[..], &yv, b",", &f].concat()).expect(FITS));
            for (x, c) in xs.iter().zip(cells) {
                x.push(t);
                ends[idx(c)].push(t);
            }
        } else {
            let mid = Piece::new(&[&b","[..], &yv, b","].concat()).expect(FITS);
            for (x, c) in xs.iter().zip(cells) {
                x.push(t);
                mid.push(t);
                crate::num::Csv(c.margin).push_to(t);
                t.extend_from_slice(&all[idx(c)]);
            }
        }
    }

    /// Row `j` computed (`last`: the map's last row): formatted now (one thread) or with its
    /// batch, and written when the text or the batch is full.
    fn row(&mut self, j: usize, cells: &[Cell], last: bool, w: &mut dyn Write) -> std::io::Result<()> {
        if self.batch == 1 {
            let t = &mut self.texts[0];
            Self::format(&self.xs, self.y[j], self.verdict_only, cells, t);
            if t.len() >= crate::sim::CSV_CHUNK || last {
                w.write_all(t)?;
                t.clear();
            }
            return Ok(());
        }
        self.rows.push(j);
        self.cells.extend_from_slice(cells);
        if self.rows.len() >= self.batch || last {
            self.flush(w)?;
        }
        Ok(())
    }

    /// Format the pending batch in parallel and write it.
    fn flush(&mut self, w: &mut dyn Write) -> std::io::Result<()> {
        let n = self.rows.len();
        if n > 0 {
            if self.texts.len() < n {
                self.texts.resize_with(n, Vec::new);
            }
            let (xs, y, verdict_only) = (&self.xs, self.y, self.verdict_only);
            self.texts[..n].par_iter_mut().zip(self.rows.par_iter()).zip(self.cells.par_chunks(self.nx)).for_each(|((t, &j), cells)| {
                t.clear();
                Self::format(xs, y[j], verdict_only, cells, t);
            });
            self.rows.clear();
            self.cells.clear();
            for t in &self.texts[..n] {
                w.write_all(t)?;
            }
        }
        w.flush()
    }

    /// Write what is still pending (an interrupted map's complete rows) and flush the writer.
    fn finish(&mut self, w: &mut dyn Write) -> std::io::Result<()> {
        if self.batch == 1 {
            w.write_all(&self.texts[0])?;
            self.texts[0].clear();
        }
        self.flush(w)
    }
}

/// The CSV's name of the margin column: `max_real_part`, or `max_real_part_per_tau` on a
/// dimensional (SI) spatial config, whose margin is per unit of the dimensionless time
/// `τ = ω0 t` as on every spatial config (the figure's "per unit τ") while `stability` on the
/// same config prints 1/s: multiply by ω0 (rad/s) for 1/s. A dimensionless config's only time
/// is τ, the planar rotor's and a linear rotor's margin is in 1/s: both keep `max_real_part`.
pub fn margin_column(dimensional: bool) -> &'static str {
    if dimensional {
        "max_real_part_per_tau"
    } else {
        "max_real_part"
    }
}

/// A closed-form map's speed when neither axis is one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FixedSpeed {
    /// `Ω` of the config's rotor for every cell (`None`: a speed axis gives it).
    Omega(Option<f64>),
    /// One speed in rad/s over axes that move `ω0`: each cell at its own `Ω = ω/ω0`.
    Si(f64),
}

/// Compute the map with the library ([`autobal::spatial::map::stability_map_units`]), handing
/// the rows to `rows` in grid order and keeping a decimated copy for the figures.
#[allow(clippy::too_many_arguments)]
pub fn compute(
    cfg: &Config,
    x: &Axis,
    y: &Axis,
    speed: FixedSpeed,
    balls: Balls,
    quantity: Quantity,
    rows: Rows<'_>,
    control: &Control,
) -> Result<(FigureCells, MapRun, Option<Vec<Vec<Cell>>>)> {
    let omega = match speed {
        FixedSpeed::Omega(o) => o,
        FixedSpeed::Si(_) => None,
    };
    let settings = autobal::spatial::map::MapSettings { balls, quantity, omega };
    let (kx, dx) = decimate(x);
    let (ky, dy) = decimate(y);
    let ny = y.values.len();
    let nd = dx.values.len();
    let mut kept = FigureCells::new(dx, dy, quantity);
    let keep_all = matches!(rows, Rows::Keep);
    let mut all: Vec<Vec<Cell>> = vec![];
    let mut csv = match rows {
        Rows::Csv(w) => Some(w),
        _ => None,
    };
    if let Some(w) = csv.as_mut() {
        writeln!(w, "{},{},{},stable,necessary", x.path, y.path, margin_column(cfg.dimensional))?;
    }
    let mut out = csv.as_ref().map(|_| CsvRows::new(x, y, quantity == Quantity::Verdict, rayon::current_num_threads()));
    let mut io_error: Option<std::io::Error> = None;
    let mut on_row = |j: usize, cells: &[Cell]| {
        if j.is_multiple_of(ky) && j / ky < kept.rows.len() {
            kept.set_row(j / ky, cells, kx, nd);
        }
        if keep_all {
            all.push(cells.to_vec());
        }
        if let (Some(w), Some(o)) = (csv.as_mut(), out.as_mut()) {
            if let Err(e) = o.row(j, cells, j + 1 == ny, &mut **w) {
                io_error = Some(e);
                return false;
            }
        }
        control.report(j as u64 + 1, ny as u64);
        true
    };
    let outcome = match speed {
        FixedSpeed::Si(w) => autobal::spatial::map::stability_map_at_speed(&cfg.spec, x, y, w, &settings, control, &mut on_row),
        FixedSpeed::Omega(_) => autobal::spatial::map::stability_map_units(&cfg.spec, x, y, &settings, control, &mut on_row),
    };
    if let Some(e) = io_error {
        return Err(e.into());
    }
    let outcome = outcome.map_err(|e| anyhow!("{e}"))?;
    if let (Some(w), Some(o)) = (csv, out.as_mut()) {
        // the rows of an interrupted map still pending, and the staged file's buffer
        o.finish(w)?;
    }
    let run = MapRun { rows_done: outcome.rows, continued: outcome.continued, direct: outcome.direct };
    Ok((kept, run, keep_all.then_some(all)))
}

/// The general route ([`autobal::rotor_map::general_map_traced`]) over the plan's axes: any
/// planar or spatial config; CSV columns: the two axes, `max_real_part`, `verdict`,
/// `family_dimension`, `family`, `state` (empty fields where no stationary state was found).
#[allow(clippy::too_many_arguments)]
fn general(
    root: &toml::Table,
    a: &Args,
    speed: Option<autobal::units::Speed>,
    planar: bool,
    linear: bool,
    rows: Rows<'_>,
    control: &Control,
) -> Result<RouteOutput> {
    use autobal::rotor_map::general_map_traced;
    let (x, y) = (&a.x, &a.y);
    let verdict_only = a.quantity == Quantity::Verdict;
    let keep_all = matches!(rows, Rows::Keep);
    let mut all: Vec<Vec<GeneralCell>> = vec![];
    let mut csv = match rows {
        Rows::Csv(w) => Some(w),
        _ => None,
    };
    if let Some(w) = csv.as_mut() {
        // a spatial config in SI: its margin is per τ all the same (the header says so)
        let dimensional = !planar && !linear && config::is_dimensional(root);
        writeln!(w, "{},{},{},verdict,family_dimension,family,state", x.path, y.path, margin_column(dimensional))?;
    }
    let mut traced: Vec<BoundaryPoint> = vec![];
    let (kx, dx) = decimate(x);
    let (ky, dy) = decimate(y);
    let mut kept: Vec<Option<Vec<GeneralCell>>> = vec![None; dy.values.len()];
    let xs: Vec<String> = x.values.iter().map(|v| crate::num::Csv(*v).to_string()).collect();
    let ny = y.values.len();
    let mut io_error: Option<std::io::Error> = None;
    let mut on_row = |j: usize, cells: &[GeneralCell], points: &[BoundaryPoint]| {
        traced.extend_from_slice(points);
        if j.is_multiple_of(ky) && j / ky < kept.len() {
            kept[j / ky] = Some(cells.iter().step_by(kx).take(dx.values.len()).copied().collect());
        }
        if keep_all {
            all.push(cells.to_vec());
        }
        if let Some(w) = csv.as_mut() {
            use std::fmt::Write as _;
            let yv = crate::num::Csv(y.values[j]).to_string();
            let mut t = String::with_capacity(cells.len() * 48);
            for (xs, c) in xs.iter().zip(cells) {
                // no stationary state: empty fields, never `NaN`
                // below the periodic-orbit floor: `not_analysed` (no state was sought)
                let (margin, verdict, fam) = match c.verdict {
                    None if !c.analysed => (String::new(), NOT_ANALYSED, String::new()),
                    None => (String::new(), "", String::new()),
                    Some(v) => (
                        if verdict_only { String::new() } else { crate::num::Csv(c.margin).to_string() },
                        verdict_name(Some(v)),
                        c.family_dimension.to_string(),
                    ),
                };
                // with a family: all, some or none of its members stable (empty for an isolated state)
                let family = match c.family {
                    None => "",
                    Some(FamilyVerdict::AllStable) => "all_stable",
                    Some(FamilyVerdict::SomeStable) => "some_stable",
                    Some(FamilyVerdict::NoneStable) => "none_stable",
                };
                // what the state is, in the speed scan's words (`stability`'s points[].state)
                let state = c.state.map_or("", StateKind::key);
                let _ = writeln!(t, "{xs},{yv},{margin},{verdict},{fam},{family},{state}");
            }
            if let Err(e) = w.write_all(t.as_bytes()).and_then(|_| w.flush()) {
                io_error = Some(e);
                return false;
            }
        }
        control.report(j as u64 + 1, ny as u64);
        true
    };
    // a linear rotor config ([linear_rotor]): its own paths and rotor (crate::linear_rotor), its
    // matrix files read relative to the config's folder (a file's, or the tables' own `dir`)
    let outcome = if linear {
        crate::linear_rotor::map_traced(root, a.config.dir(), x, y, speed, a.boundary, control, &mut on_row)
    } else {
        general_map_traced(root, x, y, speed, a.boundary, control, &mut on_row)
    };
    if let Some(e) = io_error {
        return Err(e.into());
    }
    let outcome = outcome.map_err(|e| match e.field() {
        Some(f) if f == x.path => anyhow!("--x: {e}"),
        Some(f) if f == y.path => anyhow!("--y: {e}"),
        // the flag names the key once
        Some("omega") => match &e {
            autobal::Error::InvalidParameter { reason, .. } => anyhow!("--omega: {reason}"),
            _ => anyhow!("--omega: {e}"),
        },
        _ => anyhow!("{e}"),
    })?;
    Ok(RouteOutput::General { fx: dx, fy: dy, frows: kept, cells: keep_all.then_some(all), outcome, planar, linear, traced: a.boundary.then_some(traced) })
}

/// The general route's figure: the heatmap of [`plot`] (cells without a stationary state
/// blank, no 003 necessary boundary), the margin named by the state (max Re λ, or the largest
/// Floquet exponent), the bisected boundary points as markers.
#[allow(clippy::too_many_arguments)]
fn general_plot(
    fx: &Axis,
    fy: &Axis,
    frows: &[Option<Vec<GeneralCell>>],
    outcome: &GeneralMapOutcome,
    planar: bool,
    linear: bool,
    quantity: Quantity,
    traced: Option<&[BoundaryPoint]>,
) -> crate::plot::Plot {
    let found = general_state(outcome);
    let mut r = FigureCells::new(fx.clone(), fy.clone(), quantity);
    for (j, row) in frows.iter().enumerate() {
        if let Some(row) = row {
            let cells: Vec<Cell> = row.iter().map(|c| Cell { margin: c.margin, stable: c.verdict == Some(Verdict::Stable), necessary: false }).collect();
            r.set_row(j, &cells, 1, cells.len());
        }
    }
    let state = Output::state(outcome);
    let model = if linear {
        "linear"
    } else if planar {
        "planar"
    } else {
        "spatial"
    };
    // with n >= 3 balls in a plane a cell's state is one member of a family of balanced
    // states: the colour and the bisected points are that member's (walk 34: only a line on
    // standard error said so, for the colour alone)
    let member = if outcome.families > 0 { FAMILY_MEMBER_NOTE } else { "" };
    let title = format!("Stability map of the {model} rotor's stationary state (general route: {state}){member}");
    let mut p = plot_cells(&r, &title);
    // no 003 necessary ranges off the 12-state model
    p.series.retain(|s| s.label != NECESSARY_EDGE_LABEL);
    if planar {
        // the planar model's `omega` is ω itself (no ω0)
        for (key, label) in [(&r.x.path, &mut p.x_label), (&r.y.path, &mut p.y_label)] {
            if key == "omega" {
                *label = "speed ω (rad/s)".into();
            }
        }
    }
    if let Some(h) = p.heatmap.as_mut() {
        // cells without a stationary state stay blank
        for (zr, kr) in h.z.iter_mut().zip(frows) {
            if let Some(kr) = kr {
                for (z, c) in zr.iter_mut().zip(kr) {
                    if c.verdict.is_none() {
                        *z = f64::NAN;
                    }
                }
            }
        }
        if quantity == Quantity::Margin {
            let what = match found {
                None => "margin",
                Some(Kind::PeriodicOrbit) => "largest Floquet exponent",
                Some(Kind::Equilibrium) => "max Re λ",
            };
            h.label = format!("{what} ({}; < 0 stable)", if planar { "1/s" } else { "per unit τ" });
        }
    }
    // cells below the periodic-orbit floor: blank too, marked as not analysed (grey)
    let below: Vec<(f64, f64)> = frows
        .iter()
        .enumerate()
        .filter_map(|(j, r)| r.as_ref().map(|r| (j, r)))
        .flat_map(|(j, r)| r.iter().enumerate().filter(|(_, c)| !c.analysed).map(move |(i, _)| (fx.values[i], fy.values[j])))
        .collect();
    if !below.is_empty() {
        p.series.push(Series::new("not analysed (below the periodic-orbit floor)", below, "#999999").markers());
    }
    if let Some(t) = traced {
        if !t.is_empty() {
            p.series.push(Series::new("bisected boundary points", t.iter().map(|b| (b.x, b.y)).collect(), "#0072B2").markers());
        }
    }
    p
}

/// What the general route's figure title adds where cells have a family of balanced states
/// (`n ≥ 3` balls in a plane): its colour and bisected boundary points are one member's.
pub const FAMILY_MEMBER_NOTE: &str =
    "; where a cell has a family of balanced states (n ≥ 3 balls, or no unbalance to cancel), colour and boundary points are one member's, the one reached from the closed form";

/// The traced curves as figure series: the stability boundary solid (Hopf blue, fold orange),
/// the rest of each curve thin and dashed, codimension-two points as markers.
pub fn boundary_series(b: &Boundary) -> Vec<Series> {
    let mut out = vec![];
    for (kind, color, name) in [(CurveKind::Hopf, "#0072B2", "Hopf"), (CurveKind::Fold, "#E69F00", "fold")] {
        let (mut on, mut off) = (vec![], vec![]);
        for c in b.curves.iter().filter(|c| c.kind == kind) {
            for w in c.points.windows(2) {
                let seg = [(w[0].x, w[0].y), (w[1].x, w[1].y), (f64::NAN, f64::NAN)];
                if w[0].on_boundary && w[1].on_boundary {
                    on.extend(seg);
                } else {
                    off.extend(seg);
                }
            }
        }
        if !on.is_empty() {
            out.push(Series::new(format!("traced boundary ({name})"), on, color).width(2.5));
        }
        if !off.is_empty() {
            out.push(Series::new(format!("{name} curve, not a boundary"), off, color).dashed().width(1.0));
        }
    }
    if !b.codim2.is_empty() {
        out.push(Series::new("codimension-two points", b.codim2.iter().map(|p| (p.x, p.y)).collect(), "#000000").markers());
    }
    out
}

/// The traced curves as CSV rows `curve,kind,x,y,hopf_frequency_squared,on_boundary` (`ω_H²` of
/// the pair `λ = ±iω_H` on a Hopf curve, 0 on a fold curve; not the speed) and the
/// codimension-two points as `-,KIND,x,y,,`.
pub fn boundary_csv(b: &Boundary, x: &str, y: &str) -> String {
    use std::fmt::Write as _;
    let mut s = format!("curve,kind,{x},{y},hopf_frequency_squared,on_boundary\n");
    for (i, c) in b.curves.iter().enumerate() {
        let kind = if c.kind == CurveKind::Hopf { "hopf" } else { "fold" };
        for p in &c.points {
            let _ = writeln!(s, "{i},{kind},{},{},{},{}", crate::num::Csv(p.x), crate::num::Csv(p.y), crate::num::Csv(p.w), p.on_boundary as u8);
        }
    }
    for p in &b.codim2 {
        let kind = match p.kind {
            Codim2Kind::BogdanovTakens => "bogdanov-takens",
            Codim2Kind::DoubleHopf => "double-hopf",
            Codim2Kind::FoldHopf => "fold-hopf",
        };
        let _ = writeln!(s, "-,{kind},{},{},,", crate::num::Csv(p.x), crate::num::Csv(p.y));
    }
    s
}

/// Trace the stability boundary over the map's plane ([`autobal::spatial::boundary`]; the
/// tracer needs the ends of the axes alone); the control (Ctrl-C) stops it with the curves
/// traced so far (`complete` false).
pub fn trace(cfg: &Config, x: &Axis, y: &Axis, omega: Option<f64>, balls: Balls, control: &Control) -> Result<Boundary> {
    let ends = |a: &Axis| Axis::range(a.path.clone(), a.lo(), a.hi());
    let s = TraceSettings { balls, omega, ..Default::default() };
    // a value the config refuses inside the map's range (an integer key such as
    // `balancer.balls` at 2.03125) names the axis, as the general route does (walk 32: it read
    // "--boundary: balancer.balls: ...", as if the option were wrong)
    autobal::spatial::boundary::trace_boundary_units(&cfg.spec, &ends(x), &ends(y), &s, control).map_err(|e| match (&e, e.field()) {
        (autobal::Error::InvalidParameter { reason, .. }, Some(f)) if f == x.path || f == y.path => {
            let (flag, a) = if f == x.path { ("--x", x) } else { ("--y", y) };
            let fm = autobal::error::fmt_num;
            anyhow!(
                "{flag} {f}: a value inside the map's range {} to {} (where the boundary is traced) gives an invalid rotor: {reason}",
                fm(a.lo()),
                fm(a.hi())
            )
        }
        _ => anyhow!("--boundary: {e}"),
    })
}

// The map's figure: Figures of stability maps (`autobal map` and the report): the margin heatmap
// with its colour bar, the stability boundary and 003's necessary boundary along cell edges, axes
// named by the physics (not by config keys). Written as SVG and PNG from one [`Plot`].
use crate::plot::{ColorScale, Heatmap, Plot};

/// Axis title of a map axis: the physical quantity for the keys autobal knows, else the key.
pub fn axis_label(key: &str) -> String {
    let known: &[(&str, &str)] = &[
        ("omega", "Ω = ω/ω0"),
        ("speed_rpm", "speed n (rpm)"),
        ("speed", "speed ω (rad/s)"),
        ("speed_hz", "speed f (Hz)"),
        ("dimensionless.c_sigma", "C̄Σ (polar / mean equatorial moment)"),
        ("dimensionless.rho_s", "ρ̄s (radius of gyration / span)"),
        ("dimensionless.l_left", "l̄_L (C from the left support / span)"),
        ("dimensionless.z_a", "z̄_A (balancer plane from C / ρ_s)"),
        ("dimensionless.delta_a", "ΔĀ = ΔĀ0 (anisotropy)"),
        ("dimensionless.m0", "m̄0 (unbalance mass / M_s)"),
        ("dimensionless.r0", "R̄0 (unbalance radius / ρ_s)"),
        ("dimensionless.m", "m̄ (ball mass / M_s)"),
        ("dimensionless.r", "R̄ (race radius / ρ_s)"),
        ("dimensionless.h_x", "h̄x (support damping)"),
        ("dimensionless.h_s", "h̄s (ball drag)"),
        ("rotor.mass", "rotor mass M_r (kg)"),
        ("rotor.z", "axial position of G (m)"),
        ("balancer.z", "axial position of plane A (m)"),
        ("balancer.ball_mass", "ball mass m (kg)"),
        ("balancer.race_radius", "race radius R (m)"),
        ("balancer.drag", "ball drag h_A (N·s/m)"),
        ("unbalance.mass", "unbalance mass m0 (kg)"),
        ("unbalance.radius", "unbalance radius R0 (m)"),
        ("supports.stiffness_left", "left stiffness c_L (N/m)"),
        ("supports.stiffness_right", "right stiffness c_R (N/m)"),
        ("supports.damping_left", "left damping h_L (N·s/m)"),
        ("supports.damping_right", "right damping h_R (N·s/m)"),
    ];
    known.iter().find(|k| k.0 == key).map_or_else(|| key.to_string(), |k| k.1.to_string())
}

/// The legend of the closed route's boundary drawn along cell edges between cells of different
/// exact verdicts: the exact boundary lies within a cell of it, not on it (a traced or bisected
/// boundary is its own series; walk29 read the staircase labelled "exact stability boundary" as
/// the boundary itself, off the bisected points).
pub const STABLE_EDGE_LABEL: &str = "stability boundary, to a cell";

/// The legend of the cell-edge boundary of 003's necessary condition ([`STABLE_EDGE_LABEL`]).
pub const NECESSARY_EDGE_LABEL: &str = "003 necessary boundary, to a cell";

/// The hash of a rounded point in [`chain`]: each integer multiplied into the state and mixed
/// (Fibonacci hashing; the keys are ours, never an adversary's, so no SipHash is needed).
#[derive(Default)]
struct PointHasher(u64);

impl std::hash::Hasher for PointHasher {
    fn finish(&self) -> u64 {
        self.0 ^ (self.0 >> 29)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// Join cell-edge segments (pairs of points) that share ends into polylines, NaN-separated,
/// so that a dashed line shows its dashes instead of restarting them on every cell edge.
/// A straight piece of a boundary, end to end.
pub type Segment = ((f64, f64), (f64, f64));

pub fn chain(segments: &[Segment]) -> Vec<(f64, f64)> {
    use std::collections::HashMap;
    let key = |p: (f64, f64)| ((p.0 * 1e9).round() as i64, (p.1 * 1e9).round() as i64);
    // the ends are looked up, never iterated: a cheap hash gives the same chains as SipHash
    let mut ends: HashMap<(i64, i64), Vec<usize>, std::hash::BuildHasherDefault<PointHasher>> =
        HashMap::with_capacity_and_hasher(segments.len() + 1, Default::default());
    for (k, (a, b)) in segments.iter().enumerate() {
        ends.entry(key(*a)).or_default().push(k);
        ends.entry(key(*b)).or_default().push(k);
    }
    let mut used = vec![false; segments.len()];
    let mut out = vec![];
    let next = |p: (f64, f64), used: &Vec<bool>| ends.get(&key(p)).and_then(|v| v.iter().copied().find(|&k| !used[k]));
    for start in 0..segments.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b) = segments[start];
        let mut line = std::collections::VecDeque::from([a, b]);
        // grow forwards, then backwards
        for forward in [true, false] {
            loop {
                let end = if forward { *line.back().expect("non-empty") } else { *line.front().expect("non-empty") };
                let Some(k) = next(end, &used) else { break };
                used[k] = true;
                let (p, q) = segments[k];
                let far = if key(p) == key(end) { q } else { p };
                if forward {
                    line.push_back(far);
                } else {
                    line.push_front(far);
                }
            }
        }
        // a point inside a straight horizontal or vertical run (a boundary along a row or a
        // column of cells) adds nothing to the line: left out, the ends and corners kept
        let n = line.len();
        out.extend((0..n).filter(|&k| k == 0 || k + 1 == n || !straight(line[k - 1], line[k], line[k + 1])).map(|k| line[k]));
        out.push((f64::NAN, f64::NAN));
    }
    out
}

/// Whether `b` lies strictly between `a` and `c` on one horizontal or vertical line (exact
/// coordinates: the cell edges of one row or column are computed alike).
fn straight(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> bool {
    (a.0 == b.0 && b.0 == c.0 && (b.1 - a.1) * (c.1 - b.1) > 0.0) || (a.1 == b.1 && b.1 == c.1 && (b.0 - a.0) * (c.0 - b.0) > 0.0)
}

/// Cell-edge segments between cells whose `flag` (a [`FigureCells`] bit) differs (the grid
/// evenly spaced).
fn boundary(r: &FigureCells, flag: u8) -> Vec<(f64, f64)> {
    chain(&boundary_segments(r, flag))
}

/// The cell-edge segments of [`boundary`], row by row, each cell's right edge before its upper
/// one.
fn boundary_segments(r: &FigureCells, flag: u8) -> Vec<Segment> {
    let (xs, ys) = (&r.x.values, &r.y.values);
    let (nx, ny) = (xs.len(), ys.len());
    let dx = (r.x.hi() - r.x.lo()) / (nx - 1) as f64;
    let dy = (r.y.hi() - r.y.lo()) / (ny - 1) as f64;
    // each row's flags once (a cell is compared with its right and upper neighbours)
    let flags: Vec<Option<Vec<bool>>> = r.rows.iter().map(|row| row.as_ref().map(|(f, _)| f.iter().map(|&b| b & flag != 0).collect())).collect();
    let mut segs = vec![];
    // cells in blocks of 16: a block whose flags equal their right and upper neighbours' (two
    // slice comparisons) has no segment and is skipped; the segments keep their order
    const BLOCK: usize = 16;
    for j in 0..ny {
        let Some(row) = &flags[j] else { continue };
        let up = flags.get(j + 1).and_then(Option::as_ref);
        let y = ys[j];
        let mut b = 0;
        while b < nx {
            let e = (b + BLOCK).min(nx);
            let h = e.min(nx - 1);
            let flat = row[b..h] == row[b + 1..h + 1] && up.is_none_or(|u| row[b..e] == u[b..e]);
            if !flat {
                for i in b..e {
                    let x = xs[i];
                    if i + 1 < nx && row[i] != row[i + 1] {
                        segs.push(((x + dx / 2.0, y - dy / 2.0), (x + dx / 2.0, y + dy / 2.0)));
                    }
                    if let Some(up) = up {
                        if row[i] != up[i] {
                            segs.push(((x - dx / 2.0, y + dy / 2.0), (x + dx / 2.0, y + dy / 2.0)));
                        }
                    }
                }
            }
            b = e;
        }
    }
    segs
}

/// The map as a figure: heatmap (margin with a diverging colour bar, or the verdict), the exact
/// boundary (solid black) and 003's necessary boundary (dashed), physics axis titles.
pub fn plot(r: &MapResult, title: &str) -> Plot {
    plot_cells(&FigureCells::from_map(r), title)
}

/// [`plot`] from the compact copy of the cells.
pub fn plot_cells(r: &FigureCells, title: &str) -> Plot {
    // the largest finite margin on each side, one pass (a verdict map keeps none)
    let (mut neg, mut pos) = (1e-12f64, 1e-12f64);
    for &m in r.rows.iter().flatten().flat_map(|(_, m)| m).filter(|m| m.is_finite()) {
        if m < 0.0 {
            neg = neg.max(-m);
        } else {
            pos = pos.max(m);
        }
    }
    let z: Vec<Vec<f64>> = r
        .rows
        .iter()
        .map(|row| match (row, r.quantity) {
            (Some((_, margins)), Quantity::Margin) => margins.clone(),
            (Some((flags, _)), Quantity::Verdict) => flags.iter().map(|&f| if f & FigureCells::STABLE != 0 { -1.0 } else { 1.0 }).collect(),
            (None, _) => vec![f64::NAN; r.x.values.len()],
        })
        .collect();
    let (scale, label) = match r.quantity {
        Quantity::Margin => (ColorScale::Diverging { neg, pos }, "max Re λ (< 0 stable)".to_string()),
        Quantity::Verdict => (ColorScale::Verdict, "verdict".to_string()),
    };
    let dx = (r.x.hi() - r.x.lo()) / (r.x.values.len() - 1) as f64;
    let dy = (r.y.hi() - r.y.lo()) / (r.y.values.len() - 1) as f64;
    Plot {
        title: title.to_string(),
        x_label: axis_label(&r.x.path),
        y_label: axis_label(&r.y.path),
        series: vec![
            Series::new(STABLE_EDGE_LABEL, boundary(r, FigureCells::STABLE), "#000000"),
            Series::new(NECESSARY_EDGE_LABEL, boundary(r, FigureCells::NECESSARY), "#CC79A7").dashed(),
        ],
        x_range: Some((r.x.lo() - dx / 2.0, r.x.hi() + dx / 2.0)),
        y_range: Some((r.y.lo() - dy / 2.0, r.y.hi() + dy / 2.0)),
        heatmap: Some(Heatmap { x: r.x.values.clone(), y: r.y.values.clone(), z, scale, label }),
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The general route's speed axis takes the range `stability --omega-max` takes, with its
    /// message (walk 32: `map` took 1e308 rad/s, exit 0, every cell empty): rad/s on a planar
    /// rotor, `Ω` (at the config's ω0 for an SI axis) on a spatial one; the largest speed
    /// accepted (1e6 rad/s) still maps.
    #[test]
    fn a_speed_axis_past_stabilitys_limit_is_refused() {
        let planar = include_str!("../../../examples/planar.toml");
        let washer = include_str!("../../../examples/washing_machine.toml");
        for (text, x, y, want) in [
            (planar, "omega=100:1e308:3", "planar.c_psi=0.05:0.2:2", "--x omega: 1e308 rad/s outside (0, 1e6] rad/s ("),
            (planar, "planar.c_psi=0.05:0.2:2", "speed_rpm=100:2e7:2", "--y speed_rpm: 2e7 rpm is 2.0944e6 rad/s, outside (0, 1e6] rad/s ("),
            (washer, "speed_rpm=100:1e308:2", "balancer.drag=0.5:3:2", "--x speed_rpm: 1e308 rpm is Ω = ω/ω0 = "),
        ] {
            let args =
                Args { config: tables(text), x: parse_axis("--x", x).unwrap(), y: parse_axis("--y", y).unwrap(), route: Route::General, ..Default::default() };
            let e = args.prepare().err().expect("refused").to_string();
            assert!(e.starts_with(want), "{e}");
            // the message `stability --omega-max` gives for that speed
            let top = if x.starts_with("balancer") || x.starts_with("planar") { y } else { x };
            let (path, hi) = (top.split('=').next().unwrap(), top.rsplit(':').nth(1).unwrap());
            let unit = match path {
                "omega" => "rad/s",
                _ => "rpm",
            };
            let st = crate::stability::Args { config: tables(text), omega_max: Some(format!("{hi} {unit}")), route: Route::General, ..Default::default() };
            let se = command::Command::run(&st, &Control::none()).err().expect("stability refuses it").to_string();
            assert_eq!(e.split_once(": ").unwrap().1, se.split_once(": ").unwrap().1, "map: {e}\nstability: {se}");
        }
        let ok = Args {
            config: tables(planar),
            x: parse_axis("--x", "omega=1e5:1e6:2").unwrap(),
            y: parse_axis("--y", "planar.c_psi=0.05:0.2:2").unwrap(),
            ..Default::default()
        };
        assert!(ok.prepare().is_ok());
    }

    /// A value the config refuses inside the map's range, met where the closed route traces
    /// its boundary (`balancer.balls` is a whole number; the trace's points lie between the
    /// grid's), names the axis and the range, not `--boundary` (walk 32).
    #[test]
    fn an_invalid_rotor_inside_the_range_names_the_axis() {
        let args = Args {
            config: tables(include_str!("../../../examples/dimensional.toml")),
            x: parse_axis("--x", "balancer.balls=2:4:3").unwrap(),
            y: parse_axis("--y", "speed_rpm=3000:6000:2").unwrap(),
            boundary: true,
            ..Default::default()
        };
        let e = args.prepare().and_then(|p| p.run(&Control::none(), Rows::Keep)).err().expect("refused").to_string();
        assert!(
            e.starts_with(
                "--x balancer.balls: a value inside the map's range 2 to 4 (where the boundary is traced) gives an invalid rotor: must be a whole number"
            ),
            "{e}"
        );
    }

    /// `--omega` beside a speed axis was ignored, exit 0 (hunt 27): refused, naming the axis,
    /// on both routes (the planar config's general route, the washer's closed form).
    #[test]
    fn a_fixed_speed_beside_a_speed_axis_is_refused() {
        for (text, x, y) in [
            (include_str!("../../../examples/planar.toml"), "planar.c_psi=0.05:0.2:2", "omega=300:400:2"),
            (include_str!("../../../examples/washing_machine.toml"), "balancer.drag=0.5:3:2", "speed_rpm=300:1500:2"),
        ] {
            let root = crate::config::parse_text(text, "c.toml").unwrap();
            let args = Args {
                config: ConfigSource::tables(root, "c.toml"),
                x: parse_axis("--x", x).unwrap(),
                y: parse_axis("--y", y).unwrap(),
                omega: Some("3000 rpm".into()),
                ..Default::default()
            };
            let e = args.prepare().err().expect("refused").to_string();
            let axis = y.split('=').next().unwrap();
            // the library's words (rotor_map::check_fixed_speed), which Python's linear rotor
            // map gives too, the field as the CLI's flag
            assert_eq!(
                e,
                format!(
                    "--omega: 3000 rpm: the map's y axis {axis} is the speed already; drop the fixed speed, or map over two other parameters at that speed"
                )
            );
        }
    }

    /// `boundary` at a fixed speed in SI over axes that move ω0 (each cell at its own Ω, no
    /// plane to trace): refused by `prepare`, before any cell, as a typed error whose field is
    /// the option (`--boundary`, Python's `boundary`) and whose reason names the other options
    /// as both front ends call them (session 29: Python met the CLI's `--route general`,
    /// `--omega` in its message, and only after every cell, while drawing). The plan without
    /// `boundary` is taken, and [`Plan::untraced`] leaves the check done and the trace off.
    #[test]
    fn a_boundary_at_a_fixed_si_speed_is_refused_before_any_cell() {
        let text = include_str!("../../../examples/dimensional.toml");
        let args = |boundary: bool| Args {
            config: tables(text),
            x: parse_axis("--x", "balancer.ball_mass=0.01:0.05:3").unwrap(),
            y: parse_axis("--y", "supports.stiffness_left=1e6:4e6:2").unwrap(),
            omega: Some("6000rpm".into()),
            boundary,
            ..Default::default()
        };
        let e = args(true).prepare().err().expect("refused");
        match e.downcast_ref::<autobal::Error>() {
            Some(autobal::Error::InvalidParameter { field, reason }) => {
                assert_eq!(field, "--boundary");
                assert!(reason.starts_with("at a fixed speed in SI over axes that move ω0 (each cell at its own Ω) the boundary is not traced"), "{reason}");
                assert!(reason.contains("route general") && reason.contains("omega as Ω") && !reason.contains("--"), "{reason}");
            }
            _ => panic!("not a typed error: {e:#}"),
        }
        assert!(args(false).prepare().is_ok());
        // over axes that keep ω0 the boundary is traced; `untraced` keeps the cells only
        let plain = Args {
            config: tables(text),
            x: parse_axis("--x", "balancer.drag=0.5:3:2").unwrap(),
            y: parse_axis("--y", "balancer.z=0.3:0.45:2").unwrap(),
            omega: Some("6000rpm".into()),
            boundary: true,
            ..Default::default()
        };
        let o = plain.prepare().unwrap().untraced().run(&Control::none(), Rows::Keep).unwrap();
        assert!(matches!(o.route, RouteOutput::Closed { cells: Some(_), traced: None, .. }));
    }

    use crate::command::{Command as _, Output as _};

    fn tables(text: &str) -> ConfigSource {
        ConfigSource::tables(crate::config::parse_text(text, "test").unwrap(), "test")
    }

    /// A config with the 12-state model's inputs given directly (`delta_a`, `m`, `d_a`, no
    /// masses: bench/stability_map.py's rotor) maps over `z_a` on the closed form, as the full
    /// rule says (it has no general route: that needs the masses); it was refused, the axis
    /// rule reading the missing masses as "no unbalance". Its margins are the 12-state model's
    /// own: the map's cell equals `spatial::stability::margin` on the model built from the
    /// same inputs (bit for bit: the same route), and not the model with masses.
    #[test]
    fn a_config_of_direct_inputs_maps_on_the_closed_form() {
        let text = "[dimensionless]\nc_sigma = 0.75\nrho_s = 0.4\nl_left = 0.8\nz_a = 0.0\ndelta_a = 0.1\nm = 0.05\nd_a = 0.5\nh_x = 0.05\nh_s = 0.1\n";
        let root = crate::config::parse_text(text, "test").unwrap();
        let cfg = config::build(&root, "test").unwrap();
        for z in [-2.0, 0.0, 1.5] {
            let mut r = root.clone();
            autobal::config::set_number(&mut r, "dimensionless.z_a", z).unwrap();
            assert!(!crate::general::needs_general_verdict(&r));
            assert!(!axis_value_needs_general(&cfg.spec, "dimensionless.z_a", z), "z_a = {z}");
        }
        let args = Args {
            config: tables(text),
            x: parse_axis("--x", "dimensionless.z_a=-2:2:3").unwrap(),
            y: parse_axis("--y", "omega=0.5:1.5:2").unwrap(),
            quantity: Quantity::Margin,
            ..Default::default()
        };
        let o = args.run(&Control::none()).unwrap();
        let RouteOutput::Closed { cells: Some(cells), rows_done, .. } = &o.route else { panic!("not the closed form's route") };
        assert_eq!(*rows_done, 2);
        use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
        for (j, &w) in o.y.values.iter().enumerate() {
            for (i, &z) in o.x.values.iter().enumerate() {
                let inp = DimensionlessInput {
                    c_sigma: 0.75,
                    rho_s: 0.4,
                    l_left: 0.8,
                    z_a: z,
                    anisotropy: AnisotropyInput::Direct(0.1),
                    h_x: 0.05,
                    h_s: 0.1,
                    method: autobal::spatial::inertia::AnisotropyMethod::Exact,
                    direct_balls: Some((0.05, 0.5)),
                };
                let want = autobal::spatial::stability::margin(&SpatialModel::from_dimensionless(&inp).unwrap(), w, Balls::Free).unwrap();
                // the map certifies its margin to 1e-10 (1 + |λ|) (spatial::map): the same
                // rightmost eigenvalue by another route
                assert!((cells[j][i].margin - want).abs() <= 1e-9, "z_a {z}, Ω {w}: map {} vs {want}", cells[j][i].margin);
            }
        }
    }

    /// Audit 25's F6: on a dimensional spatial config the margins are per τ = ω0 t with
    /// ω0 = sqrt(c_x / M_s) (paper 000's M_s); the map prints and returns that ω0: equal to
    /// sqrt((c_L + c_R) / (M_r + m0 + n m)) from examples/dimensional.toml's own entries to
    /// round-off.
    #[test]
    fn a_dimensional_map_names_its_omega0() {
        let root = crate::config::parse_text(include_str!("../../../examples/dimensional.toml"), "test").unwrap();
        let a = |k: &str| -> f64 {
            let (t, f) = k.split_once('.').unwrap();
            root[t][f].as_float().or_else(|| root[t][f].as_integer().map(|i| i as f64)).unwrap()
        };
        let m_s = a("rotor.mass") + a("unbalance.mass") + a("balancer.balls") * a("balancer.ball_mass");
        let want = (a("supports.stiffness_left") + a("supports.stiffness_right")).sqrt() / m_s.sqrt();
        let args = Args {
            config: ConfigSource::tables(root.clone(), "test"),
            x: parse_axis("--x", "balancer.z=0.3:0.45:2").unwrap(),
            y: parse_axis("--y", "omega=0.5:3:2").unwrap(),
            quantity: Quantity::Margin,
            ..Default::default()
        };
        let o = args.run(&Control::none()).unwrap();
        let [w, w1] = o.omega0.unwrap();
        assert_eq!(w, w1, "no axis moves it");
        assert!((w - want).abs() <= 1e-12 * want, "{w} vs {want}");
        assert_eq!(o.json().unwrap()["omega0_rad_s"].as_f64(), Some(w));
        assert!(o.table().unwrap().starts_with("max_real_part_per_tau: margins per τ = ω0 t, ω0 = "));
        // review 25b: an axis over the left stiffness moves ω0 cell by cell: its range, from
        // each corner's own sqrt(c_x / M_s), and no single value
        let args = Args {
            config: ConfigSource::tables(root.clone(), "test"),
            x: parse_axis("--x", "speed=600:700:2").unwrap(),
            y: parse_axis("--y", "supports.stiffness_left=1e6:4e6:2").unwrap(),
            quantity: Quantity::Margin,
            ..Default::default()
        };
        let o = args.run(&Control::none()).unwrap();
        let [lo, hi] = o.omega0.unwrap();
        let corner = |c_l: f64| ((c_l + a("supports.stiffness_right")) / m_s).sqrt();
        assert!((lo - corner(1e6)).abs() <= 1e-12 * lo && (hi - corner(4e6)).abs() <= 1e-12 * hi, "{lo} {hi}");
        assert!(o.json().unwrap()["omega0_rad_s"].is_null());
        assert!(o.table().unwrap().contains("of each cell's own ω0"));
    }

    /// [`axis_value_needs_general`] against the full rule it stands for
    /// ([`crate::general::needs_general_verdict`] on the config with the value set), on the
    /// dimensionless and the SI example, at values through and near its thresholds.
    #[test]
    fn the_axis_route_rule_is_the_full_verdict_rule() {
        for (file, cases) in [
            (
                include_str!("../../../examples/default.toml"),
                vec![
                    ("dimensionless.m0", vec![0.0, 1e-12, 1e-8, 1e-7, 1e-3, 0.025]),
                    ("dimensionless.r0", vec![0.0, 1e-9, 2.0]),
                    ("dimensionless.n", vec![1.0, 2.0, 3.0]),
                    ("dimensionless.m", vec![1e-3, 0.05, 0.5]),
                    ("dimensionless.z_a", vec![-1.0, 0.0, 0.8]),
                ],
            ),
            (
                include_str!("../../../examples/dimensional.toml"),
                vec![
                    ("unbalance.mass", vec![0.0, 1e-12, 4.7e-8, 4.9e-8, 0.01]),
                    ("unbalance.radius", vec![0.0, 0.1]),
                    ("balancer.balls", vec![1.0, 2.0, 4.0]),
                    ("balancer.ball_mass", vec![1e-3, 0.02, 1e4]),
                    ("balancer.z", vec![0.3, 0.45]),
                ],
            ),
        ] {
            let root = crate::config::parse_text(file, "test").unwrap();
            let cfg = config::build(&root, "test").unwrap();
            let mut flips = 0;
            for (path, values) in cases {
                for v in values {
                    let mut r = root.clone();
                    autobal::config::set_number(&mut r, path, v).unwrap();
                    let full = crate::general::needs_general_verdict(&r);
                    assert_eq!(axis_value_needs_general(&cfg.spec, path, v), full, "{path} = {v}");
                    flips += full as usize;
                }
            }
            // the cases reach both sides of the rule
            assert!(flips >= 4, "{flips}");
        }
    }

    #[test]
    fn axis_values_read_as_typed() {
        let a = parse_axis("--x", "planar.c_psi=0.01:0.4:4").unwrap();
        assert_eq!(a.values, vec![0.01, 0.14, 0.27, 0.4]);
        let a = parse_axis("--x", "omega=0:6:401").unwrap();
        assert_eq!(a.values[0], 0.0);
        assert!((a.values[123] - 6.0 * 123.0 / 400.0).abs() < 1e-11);
    }

    #[test]
    fn bad_axis_specs_are_rejected_with_the_flag() {
        for spec in ["omega", "omega=1:2", "omega=2:1:5", "omega=0:1:1", "omega=a:1:3", "omega=-1:1:3", "x=0:1:9999999", "omega=0.1,0.2", "x=0:1:100001"] {
            let e = parse_axis("--y", spec).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--y {spec}")), "{e}");
        }
        assert!(parse_axis("--x", "x=0:1:100001").unwrap_err().to_string().ends_with("N must lie between 2 and 100000, got 100001"));
        // the same checks on an axis given as values (Python's lists), naming the path
        for (a, why) in [
            (Axis::new("omega", vec![0.1]), "between 2"),
            (Axis::new("omega", vec![0.2, 0.1]), "increasing"),
            (Axis::new("omega", vec![-0.1, 0.1]), "negative"),
        ] {
            let args = Args { x: a, y: Axis::linspace("dimensionless.z_a", 0.0, 1.0, 2), ..Default::default() };
            let e = args.run(&Control::none()).err().expect("refused").to_string();
            assert!(e.starts_with("--x omega: ") && e.contains(why), "{e}");
        }
        let e = Args::default().run(&Control::none()).err().expect("refused").to_string();
        assert!(e.starts_with("--x: required"), "{e}");
    }

    /// A figure's decimated axis is a subset of the computed values (every k-th, the first
    /// included), never values between them: the figure draws cells that were computed.
    #[test]
    fn decimation_keeps_computed_values() {
        let a = Axis::linspace("omega", 0.05, 4.5, 1501);
        let (k, d) = decimate(&a);
        assert_eq!(k, 4);
        assert_eq!(d.values.len(), 376);
        assert!(d.values.iter().enumerate().all(|(i, v)| v.to_bits() == a.values[i * k].to_bits()));
        assert_eq!(decimate(&Axis::linspace("omega", 0.0, 1.0, 500)).0, 1);
    }

    /// The CSV the CLI streams and the cells Python keeps are one computation: the same cells,
    /// bit for bit, and the figure's heatmap is the kept margins (a map small enough not to be
    /// decimated).
    #[test]
    fn csv_kept_cells_and_figure_agree() {
        let args = Args { x: parse_axis("--x", "dimensionless.z_a=-2:2:7").unwrap(), y: parse_axis("--y", "omega=0.05:4.5:5").unwrap(), ..Default::default() };
        let plan = args.prepare().unwrap();
        let mut csv = vec![];
        let streamed = plan.run(&Control::none(), Rows::Csv(&mut csv)).unwrap();
        let kept = args.run(&Control::none()).unwrap();
        let RouteOutput::Closed { cells: Some(cells), .. } = &kept.route else { panic!("closed route, cells kept") };
        let text = String::from_utf8(csv).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("dimensionless.z_a,omega,max_real_part,stable,necessary"));
        let flat: Vec<&Cell> = cells.iter().flatten().collect();
        assert_eq!(flat.len(), 35);
        for (l, c) in lines.zip(&flat) {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f[2].parse::<f64>().unwrap().to_bits(), c.margin.to_bits(), "{l}");
            assert_eq!((f[3] == "1", f[4] == "1"), (c.stable, c.necessary), "{l}");
        }
        assert_eq!(streamed.table().unwrap().split(" in ").next(), kept.table().unwrap().split(" in ").next());
        let figs = kept.figures().unwrap();
        assert_eq!(figs.len(), 1);
        let h = figs[0].plot.heatmap.as_ref().unwrap();
        assert_eq!((h.x.clone(), h.y.clone()), (args.x.values.clone(), args.y.values.clone()));
        assert!(h.z.iter().flatten().zip(&flat).all(|(z, c)| z.to_bits() == c.margin.to_bits()));
        assert_eq!(kept.stopped(), None);
        assert_eq!(kept.json().unwrap()["rows_computed"], json!(5));
    }

    /// A second route to the same verdicts: the map's cells along the speed at the config's own
    /// parameters lie where `stability` (eigenvalues on a grid, range ends bisected to 1e-9)
    /// finds the balanced state stable, and outside where it does not. Cells within 1e-6 of a
    /// range end are skipped (the two computations may round the margin's sign differently
    /// there; the grid's spacing, 4.45/199, keeps such cells rare).
    #[test]
    fn the_maps_verdicts_are_stabilitys_ranges() {
        let source = tables(crate::config::DEFAULT_CONFIG);
        let (root, _) = source.read().unwrap();
        let l = root["dimensionless"]["l_left"].as_float().unwrap();
        let args = Args {
            config: source.clone(),
            x: Axis::linspace("omega", 0.05, 4.5, 200),
            y: Axis::new("dimensionless.l_left", vec![l, l + 0.1]),
            ..Default::default()
        };
        let out = args.run(&Control::none()).unwrap();
        let RouteOutput::Closed { cells: Some(cells), .. } = &out.route else { panic!("closed route, cells kept") };
        let st =
            crate::stability::Args { config: source, omega_max: Some("4.5".into()), samples: Some(2000), ..Default::default() }.run(&Control::none()).unwrap();
        let crate::stability::Output::Closed { c, .. } = st else { panic!("closed route") };
        let ranges = &c.exact.stable_ranges;
        assert!(!ranges.is_empty());
        let mut checked = 0;
        for (w, cell) in args.x.values.iter().zip(&cells[0]) {
            let near_end = ranges.iter().any(|r| (w - r.lo).abs() < 1e-6 || r.hi.is_some_and(|h| (w - h).abs() < 1e-6));
            if near_end {
                continue;
            }
            let inside = ranges.iter().any(|r| *w > r.lo && r.hi.is_none_or(|h| *w < h));
            assert_eq!(cell.stable, inside, "Ω = {w}: the map says stable = {}, stability's ranges {ranges:?}", cell.stable);
            checked += 1;
        }
        assert!(checked > 190, "{checked}");
    }

    /// A map stopped before its first row keeps nothing and says so, naming the CSV once the
    /// front end has written it.
    #[test]
    fn a_stopped_map_says_what_it_kept() {
        let control = Control::new();
        control.cancel();
        let args = Args { x: parse_axis("--x", "dimensionless.z_a=-2:2:3").unwrap(), y: parse_axis("--y", "omega=0.05:4.5:3").unwrap(), ..Default::default() };
        let mut out = args.run(&control).unwrap();
        assert!(out.rows_done() < 3);
        assert_eq!(out.stopped().unwrap(), format!("interrupted: {} of 3 rows computed", out.rows_done()));
        out.written = Some("m".into());
        assert!(out.stopped().unwrap().ends_with(" and kept in m.csv"));
        assert!(out.table().unwrap().ends_with("; wrote m.csv, m.svg, m.png\n"));
        // its figure says so, as stability's and campbell's do (hunt 28: no mark)
        let title = &out.figures().unwrap()[0].plot.title;
        assert!(title.starts_with("INCOMPLETE: Stability map"), "{title}");
        // the general route's too; a complete map's title has no mark
        let general = Args {
            config: tables(crate::config::DEFAULT_PLANAR),
            x: parse_axis("--x", "omega=100:400:3").unwrap(),
            y: parse_axis("--y", "planar.c_psi=0.05:0.2:3").unwrap(),
            ..Default::default()
        };
        let out = general.run(&control).unwrap();
        assert!(out.stopped().is_some());
        let title = &out.figures().unwrap()[0].plot.title;
        assert!(title.starts_with("INCOMPLETE: Stability map of the planar rotor"), "{title}");
        let title = &general.run(&Control::none()).unwrap().figures().unwrap()[0].plot.title;
        assert!(title.starts_with("Stability map of the planar rotor"), "{title}");
    }

    /// A general map none of whose cells has a stationary state claims no kind of state (hunt
    /// 28: the two-plane rotor under gravity at 500-1000 rpm, where the state would be a
    /// periodic orbit, read "stationary state: equilibrium (eigenvalues)" in the table and the
    /// figure's title): the table and the title say none was found, the JSON's `state` is null.
    #[test]
    fn a_map_without_any_state_claims_no_kind_of_state() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/spatial_two_plane.toml");
        let args = Args {
            config: ConfigSource::file(Some(&path), &[]),
            x: parse_axis("--x", "balancer.drag=0.1:1:2").unwrap(),
            y: parse_axis("--y", "speed_rpm=500:1000:2").unwrap(),
            ..Default::default()
        };
        let out = args.run(&Control::none()).unwrap();
        let RouteOutput::General { outcome, .. } = &out.route else { panic!("general route") };
        assert_eq!((outcome.none, outcome.closed_form + outcome.continued), (4, 0));
        let table = out.table().unwrap();
        assert!(table.contains("; stationary state: none found (no cell has a stationary state)"), "{table}");
        assert!(!table.contains("equilibrium") && !table.contains("periodic"), "{table}");
        let title = &out.figures().unwrap()[0].plot.title;
        assert!(title.contains("general route: none found (no cell has a stationary state)") && !title.contains("equilibrium"), "{title}");
        assert_eq!(out.json().unwrap()["state"], Value::Null);
    }

    /// The general route's map (a planar config): its own figure (the general route's title, no
    /// 003 necessary boundary, the bisected boundary points with `boundary`) for the CLI and
    /// Python alike; its CSV columns.
    #[test]
    fn the_general_route_has_its_own_figure() {
        let args = Args {
            config: tables(crate::config::DEFAULT_PLANAR),
            x: parse_axis("--x", "omega=100:400:4").unwrap(),
            y: parse_axis("--y", "planar.c_psi=0.05:0.2:2").unwrap(),
            boundary: true,
            ..Default::default()
        };
        let mut csv = vec![];
        let out = args.prepare().unwrap().run(&Control::none(), Rows::Csv(&mut csv)).unwrap();
        assert!(String::from_utf8(csv).unwrap().starts_with("omega,planar.c_psi,max_real_part,verdict,family_dimension,family,state\n"));
        let p = &out.figures().unwrap()[0].plot;
        assert!(p.title.contains("general route"), "{}", p.title);
        assert_eq!(p.x_label, "speed ω (rad/s)");
        assert!(p.series.iter().all(|s| !s.label.contains("003")), "{:?}", p.series.iter().map(|s| &s.label).collect::<Vec<_>>());
        let RouteOutput::General { traced: Some(t), .. } = &out.route else { panic!("general route, traced") };
        assert_eq!(p.series.iter().any(|s| s.label == "bisected boundary points"), !t.is_empty());
        assert_eq!(out.json().unwrap()["route"], json!("general"));
        // the planar rotor's balanced state is an equilibrium, named so
        assert!(p.title.contains("(general route: equilibrium (eigenvalues))"), "{}", p.title);
        assert_eq!(out.json().unwrap()["state"], json!("equilibrium"));
        assert!(out.boundary_csv().unwrap().starts_with("omega,planar.c_psi,from,to,along\n"));
    }

    /// A linear rotor config given as tables (Python's) reads its matrix files relative to the
    /// tables' folder, not the working folder: tables with the folder of the file they came from
    /// map exactly (bit for bit: the same matrices, the same computation) as the file itself,
    /// whatever the working folder (here the crate's, which has no `rotor_*.mtx`); tables whose
    /// folder is the working folder (a dict's, as documented) do not find the files there.
    #[test]
    fn a_linear_configs_matrix_files_are_read_beside_it() {
        let d = std::env::temp_dir().join(format!("autobal-map-linear-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        let preset = crate::linear_rotor::preset().unwrap();
        let drag = preset.balancers[0].drag;
        crate::linear_rotor::export_model(&preset, (None, None), &d, "rotor").unwrap();
        let file = d.join("rotor.toml");
        let (root, _) = crate::linear_rotor::read_set(Some(&file), &[]).unwrap();
        let map = |config: ConfigSource| {
            let args = Args {
                config,
                x: parse_axis("--x", "omega=50:150:3").unwrap(),
                y: parse_axis("--y", &format!("linear_rotor.drag={}:{}:2", 0.5 * drag, 2.0 * drag)).unwrap(),
                boundary: true,
                ..Default::default()
            };
            let mut csv = vec![];
            args.prepare()?.run(&Control::none(), Rows::Csv(&mut csv))?;
            anyhow::Ok(String::from_utf8(csv).unwrap())
        };
        let from_file = map(ConfigSource::file(Some(&file), &[])).unwrap();
        let beside = map(ConfigSource::Tables { root: root.clone(), source: "dict".into(), dir: d.clone() }).unwrap();
        assert_eq!(beside, from_file);
        assert_eq!(from_file.lines().count(), 1 + 3 * 2, "{from_file}");
        let e = map(ConfigSource::Tables { root, source: "dict".into(), dir: ".".into() }).unwrap_err();
        assert!(format!("{e:#}").contains("rotor_M.mtx"), "{e:#}");
        let _ = std::fs::remove_dir_all(&d);
    }

    /// The CSV's rows are the same bytes whether formatted as they come (one thread: pieces
    /// collected into 64 KB texts) or in parallel batches of reused buffers (three batches of
    /// 219 rows here), and each line is the plain `format!` of its values: `x,y,margin,s,n`,
    /// the margin empty for a verdict map. Values of every text length (the longest shortest
    /// forms, 24 bytes, negative zero, NaN and infinities in the margin) and all four flag
    /// pairs.
    #[test]
    fn csv_rows_are_the_same_bytes_on_one_thread_and_in_batches() {
        let (nx, ny) = (300, 500);
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let special = [-1.2345678901234567e-300, 1.7976931348623157e308, -0.0, 0.0, 5e-324, -2.2250738585072014e-308];
        let mut value = |k: usize| match k % 97 {
            i if i < special.len() => special[i],
            _ => f64::from_bits(next() >> 2) * if next() % 2 == 0 { 1.0 } else { -1e-200 },
        };
        let x = Axis::new("x", (0..nx).map(&mut value).collect());
        let y = Axis::new("y", (0..ny).map(|k| value(k + 3)).collect());
        let mut next2 = {
            let mut s = 88_172_645_463_325_252u64;
            move || {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                s
            }
        };
        let margins = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.0, -1.2345678901234567e-300];
        let rows: Vec<Vec<Cell>> = (0..ny)
            .map(|j| {
                (0..nx)
                    .map(|i| {
                        let r = next2();
                        let margin = if (i + j) % 53 < margins.len() { margins[(i + j) % 53] } else { f64::from_bits(r >> 1) };
                        Cell { margin, stable: r & 1 == 1, necessary: r & 2 == 2 }
                    })
                    .collect()
            })
            .collect();
        for verdict_only in [false, true] {
            let mut want = vec![];
            for (j, row) in rows.iter().enumerate() {
                for (xv, c) in x.values.iter().zip(row) {
                    let m = if verdict_only { String::new() } else { crate::num::Csv(c.margin).to_string() };
                    let line = format!("{},{},{m},{},{}\n", crate::num::Csv(*xv), crate::num::Csv(y.values[j]), c.stable as u8, c.necessary as u8);
                    want.extend_from_slice(line.as_bytes());
                }
            }
            for threads in [1, 4] {
                let mut o = CsvRows::new(&x, &y, verdict_only, threads);
                assert_eq!(o.batch, if threads == 1 { 1 } else { 219 });
                let mut got = vec![];
                for (j, row) in rows.iter().enumerate() {
                    o.row(j, row, j + 1 == ny, &mut got).unwrap();
                }
                o.finish(&mut got).unwrap();
                assert!(got == want, "verdict_only {verdict_only}, {threads} threads: the bytes differ");
            }
            // an interrupted map: the rows so far, nothing lost in a pending text or batch
            for threads in [1, 4] {
                let mut o = CsvRows::new(&x, &y, verdict_only, threads);
                let mut got = vec![];
                for (j, row) in rows.iter().take(250).enumerate() {
                    o.row(j, row, false, &mut got).unwrap();
                }
                o.finish(&mut got).unwrap();
                let lines = 250 * nx;
                let end = want.iter().enumerate().filter(|(_, &b)| b == b'\n').nth(lines - 1).unwrap().0 + 1;
                assert!(got == want[..end], "verdict_only {verdict_only}, {threads} threads: the interrupted map's rows differ");
            }
        }
    }

    /// The boundary's segments skip blocks of cells without a change, and are the plain
    /// cell-by-cell scan's segments in its order: on grids of every width around the 16-cell
    /// blocks, with flat regions, scattered single cells and rows not computed.
    #[test]
    fn boundary_segments_are_the_plain_scans() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for nx in [2, 3, 15, 16, 17, 31, 32, 33, 47, 70] {
            for ny in [2, 5, 19] {
                let rows: Vec<Option<Vec<Cell>>> = (0..ny)
                    .map(|j| {
                        (next() % 7 != 0).then(|| {
                            (0..nx)
                                .map(|i| {
                                    let region = (i as f64 - 0.4 * nx as f64) * 0.3 + (j as f64 - 0.5 * ny as f64) > 0.0;
                                    let stray = next() % 23 == 0;
                                    Cell { margin: f64::NAN, stable: region != stray, necessary: i + j > nx }
                                })
                                .collect()
                        })
                    })
                    .collect();
                let r = MapResult { x: Axis::linspace("x", -1.0, 2.0, nx), y: Axis::linspace("y", 0.5, 3.0, ny), rows, quantity: Quantity::Verdict };
                let compact = FigureCells::from_map(&r);
                let (dx, dy) = (3.0 / (nx - 1) as f64, 2.5 / (ny - 1) as f64);
                for (bit, flag) in [(FigureCells::STABLE, (|c: &Cell| c.stable) as fn(&Cell) -> bool), (FigureCells::NECESSARY, |c: &Cell| c.necessary)] {
                    let mut want = vec![];
                    for j in 0..ny {
                        let Some(row) = &r.rows[j] else { continue };
                        let up = r.rows.get(j + 1).and_then(Option::as_ref);
                        let y = r.y.values[j];
                        for i in 0..nx {
                            let x = r.x.values[i];
                            if i + 1 < nx && flag(&row[i]) != flag(&row[i + 1]) {
                                want.push(((x + dx / 2.0, y - dy / 2.0), (x + dx / 2.0, y + dy / 2.0)));
                            }
                            if let Some(up) = up {
                                if flag(&row[i]) != flag(&up[i]) {
                                    want.push(((x - dx / 2.0, y + dy / 2.0), (x + dx / 2.0, y + dy / 2.0)));
                                }
                            }
                        }
                    }
                    let got = boundary_segments(&compact, bit);
                    assert!(
                        got.len() == want.len() && got.iter().zip(&want).all(|(a, b)| a == b),
                        "{nx} x {ny}: {} segments against {}",
                        got.len(),
                        want.len()
                    );
                }
            }
        }
    }

    /// Chained boundaries leave out the points inside straight runs and draw the same line:
    /// a straight run of five cell edges is one piece; on random maps the pieces' total length
    /// is the segments', every segment lies on a piece, and no piece has a point inside a
    /// horizontal or vertical run.
    #[test]
    fn chained_boundaries_draw_the_same_line_with_fewer_points() {
        let run: Vec<Segment> = (0..5).map(|k| ((k as f64, 1.0), (k as f64 + 1.0, 1.0))).collect();
        let c = chain(&run);
        assert_eq!(c.len(), 3);
        assert_eq!((c[0], c[1]), ((0.0, 1.0), (5.0, 1.0)));
        assert!(c[2].0.is_nan() && c[2].1.is_nan());
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for (nx, ny) in [(30, 20), (64, 48)] {
            let rows: Vec<Option<Vec<Cell>>> = (0..ny)
                .map(|j| {
                    Some(
                        (0..nx)
                            .map(|i| {
                                let (u, v) = (i as f64 / nx as f64 - 0.5, j as f64 / ny as f64 - 0.4);
                                Cell { margin: f64::NAN, stable: u * u + 2.0 * v * v < 0.1 || next() % 41 == 0, necessary: false }
                            })
                            .collect(),
                    )
                })
                .collect();
            let r = MapResult { x: Axis::linspace("x", -2.0, 2.0, nx), y: Axis::linspace("y", 0.05, 4.5, ny), rows, quantity: Quantity::Verdict };
            let segs = boundary_segments(&FigureCells::from_map(&r), FigureCells::STABLE);
            let line = chain(&segs);
            let pieces: Vec<((f64, f64), (f64, f64))> = line.windows(2).filter(|w| !w[0].0.is_nan() && !w[1].0.is_nan()).map(|w| (w[0], w[1])).collect();
            let len = |(a, b): ((f64, f64), (f64, f64))| ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            let (total, drawn): (f64, f64) = (segs.iter().map(|&s| len(s)).sum(), pieces.iter().map(|&p| len(p)).sum());
            // the lengths are sums of a few hundred cell edges of ~0.1: rounding ~1e-13
            assert!((total - drawn).abs() < 1e-9 * total, "{total} against {drawn}");
            assert!(pieces.len() < segs.len(), "{} pieces for {} segments", pieces.len(), segs.len());
            for &(a, b) in &segs {
                let m = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
                // on a piece: the distances to its ends add up to its length (1e-9 of a cell edge)
                let on = pieces.iter().any(|&(p, q)| (len((p, m)) + len((m, q)) - len((p, q))).abs() < 1e-10);
                assert!(on, "segment {a:?}-{b:?} is on no piece");
            }
            for w in line.windows(3) {
                assert!(w.iter().any(|p| p.0.is_nan()) || !straight(w[0], w[1], w[2]), "{w:?}");
            }
        }
    }

    #[test]
    fn chained_segments_form_one_polyline() {
        // an L-shaped boundary given as three unit segments in scrambled order
        let segs = [((1.0, 0.0), (1.0, 1.0)), ((0.0, 0.0), (1.0, 0.0)), ((1.0, 1.0), (2.0, 1.0))];
        let pts = chain(&segs);
        assert_eq!(pts.iter().filter(|p| p.0.is_nan()).count(), 1, "one line: {pts:?}");
        assert_eq!(pts.len(), 5);
    }

    #[test]
    fn config_keys_read_as_physics() {
        assert_eq!(axis_label("dimensionless.z_a"), "z̄_A (balancer plane from C / ρ_s)");
        assert_eq!(axis_label("planar.k"), "planar.k");
    }

    /// A periodic configuration's map (the two-plane example: gravity, supports stiffer in y)
    /// with a speed below the periodic-orbit floor (0.81 rad/s): the CSV's verdict there is
    /// `not_analysed`, the JSON and the table count it; every speed below is refused in one
    /// line naming the axis. Main at e3f0650 shot each such cell (more than 60 s at 1e-6 rad/s).
    #[test]
    fn a_maps_speeds_below_the_periodic_floor_are_not_analysed_or_refused() {
        let two = include_str!("../../../examples/spatial_two_plane.toml");
        let args = Args {
            config: tables(two),
            x: parse_axis("--x", "speed=1e-6:1e-5:3").unwrap(),
            y: parse_axis("--y", "balancer.drag=0.4:0.5:2").unwrap(),
            ..Default::default()
        };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("--x: speed: 1e-5 rad/s is below 0.809787 rad/s,") && !e.contains('\n'), "{e}");
        // at one speed in rpm: the key named once, both numbers in rpm
        let args = Args {
            config: tables(two),
            x: parse_axis("--x", "balancer2.drag=0.4:0.5:2").unwrap(),
            y: parse_axis("--y", "balancer.drag=0.4:0.5:2").unwrap(),
            omega: Some("5rpm".into()),
            ..Default::default()
        };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("--omega: 5 rpm is below 7.73289 rpm,") && !e.contains('\n'), "{e}");
        let args = Args {
            config: tables(two),
            x: parse_axis("--x", "speed=0.5:450.5:2").unwrap(),
            y: parse_axis("--y", "balancer.drag=0.4:0.5:2").unwrap(),
            ..Default::default()
        };
        let mut csv = vec![];
        let out = args.prepare().unwrap().run(&Control::none(), Rows::Csv(&mut csv)).unwrap();
        let text = String::from_utf8(csv).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        for (row, y) in [(1, "0.4"), (3, "0.5")] {
            assert_eq!(lines[row], format!("0.5,{y},,not_analysed,,,"), "{text}");
            assert!(lines[row + 1].starts_with(&format!("450.5,{y},")) && !lines[row + 1].contains("not_analysed"), "{text}");
        }
        assert_eq!(out.json().unwrap()["not_analysed"], 2);
        let t = out.table().unwrap();
        assert!(t.contains(", 2 not analysed (below the periodic-orbit floor"), "{t}");
    }
}
