//! `autobal stability`: the exact linear stability of the balanced state over speed, by the
//! route the config needs: paper 000's 12-state model (eigenvalues of eq (6), beside 003's
//! necessary ranges: [`crate::linear`]), the general route (the nonlinear equations' exact
//! linearisation: [`crate::general`]), or a linear rotor config ([`crate::linear_rotor`]).

use crate::command::{self, check_count, ConfigSource, Figure, Route};
use crate::config::{self, Config};
use crate::general::{self, GeneralRotor};
use crate::linear::{self, Comparison};
use crate::plot::Plot;
use anyhow::{bail, Result};
use autobal::control::Control;
use autobal::linear_rotor::config::LinearRotorConfig;
use autobal::linear_rotor::reduce::Reduction;
use autobal::rotor_stability::RotorStability;
use autobal::spatial::linear_model::Balls;
use serde_json::Value;

/// The range of `--samples`, on every route.
pub const SAMPLES: std::ops::RangeInclusive<usize> = 10..=1_000_000;

/// `--samples` of the closed-form route when none is given (the general route's:
/// [`general::default_samples`]; a linear rotor's: 200, 50 where it is anisotropic).
pub const DEFAULT_SAMPLES: usize = 2000;

/// `autobal stability`'s arguments.
#[derive(Debug, Clone)]
pub struct Args {
    /// The config.
    pub config: ConfigSource,
    /// The top of the speed axis: a speed with its unit, or a bare number Ω; `None`: the
    /// config's `analysis.omega_max`, else automatic.
    pub omega_max: Option<String>,
    /// Balls free (12 states) or locked at balance (8 states; the closed-form route only).
    pub balls: Balls,
    /// Grid points along the speed before the range ends are refined; `None`: the route's
    /// default ([`DEFAULT_SAMPLES`], [`general::default_samples`]).
    pub samples: Option<usize>,
    /// The route.
    pub route: Route,
}

impl Default for Args {
    fn default() -> Self {
        Args { config: ConfigSource::default(), omega_max: None, balls: Balls::Free, samples: None, route: Route::Auto }
    }
}

/// `stability`'s result, by route.
pub enum Output {
    /// Paper 000's 12-state model.
    Closed {
        /// The config.
        cfg: Box<Config>,
        /// Exact and necessary ranges.
        c: Box<Comparison>,
        /// Free or locked.
        balls: Balls,
        /// Why the scan stopped before its end, and what it kept (`interrupted: K of N speeds analysed; …`): the
        /// speeds analysed until then are in `c` (its ranges, 003's too, end at the last of
        /// them), no operating-speed verdict; `None` when complete.
        stopped: Option<String>,
    },
    /// The general route over `(0, omega_max]`.
    General {
        /// The rotor.
        g: Box<GeneralRotor>,
        /// Its stability.
        r: Box<RotorStability>,
        /// The top of the axis (model units).
        omega_max: f64,
        /// The verdict at the config's operating speed, if it has one.
        op: Option<Box<general::Operating>>,
        /// Why the scan stopped before its end, as [`Output::LinearRotor`]'s.
        stopped: Option<String>,
    },
    /// A linear rotor config.
    LinearRotor {
        /// The config.
        cfg: Box<LinearRotorConfig>,
        /// Its stability.
        r: Box<RotorStability>,
        /// The modal reduction, where the config asks for one.
        red: Box<Option<Reduction>>,
        /// The top of the axis (rad/s).
        omega_max: f64,
        /// The rotor analysed (the reduced one where the config reduces), as the general
        /// route's, and the verdict at `linear_rotor.operating_speed`, if the config gives one.
        op: Option<Box<(GeneralRotor, general::Operating)>>,
        /// Why the scan stopped before its end (Ctrl-C, a budget) and what it kept: the speeds
        /// analysed until then are in `r` (their ranges end at the last of them, not where the
        /// stability does), no operating-speed verdict; `None` when complete.
        stopped: Option<String>,
    },
}

impl command::Command for Args {
    const NAME: &'static str = "stability";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        let (root, source) = self.config.read_any()?;
        if crate::linear_rotor::is_linear(&root) {
            return self.linear_rotor(&root, control);
        }
        if self.route.is_general_verdict(&root) {
            if self.balls == Balls::Locked {
                bail!("--balls locked: the general route analyses the balls free (use the closed-form route of a one-plane config for the locked rotor)");
            }
            let g = general::rotor_of(&root)?;
            let from_linear = config::FromLinear::SpeedRange { omega_max_given: self.omega_max.is_some(), necessary: false };
            config::check_entries_with(&root, "stability", &[config::simulation_model(&root)], from_linear)?;
            // a periodic orbit costs a shooting (the variational equations over a revolution) per speed
            let samples = check_count("--samples", self.samples.unwrap_or(general::default_samples(&g)), SAMPLES)?;
            // rad/s: a speed with its unit on an SI config, a bare number times the unit of its
            // speeds (ω0 of a spatial config, 1 rad/s of a planar one), as campbell and critical
            let omega_max = match self.omega_max.as_deref() {
                Some(t) => crate::general_campbell::omega_max(&root, &g, Some(t))?,
                None => general::default_omega_max(&g, &root)?,
            };
            // under the control, as a linear rotor's: a stopped scan keeps the speeds it analysed
            let (out, speeds) = general::scan(&g, omega_max, samples, control).map_err(|e| self.name_omega_max(e, "analysis.omega_max", &root, &g))?;
            let (r, op, stopped) = kept_scan(out, speeds, control, |r, control| general::operating(&g, &root, r, control))?;
            return Ok(Output::General { g: Box::new(g), r: Box::new(r), omega_max, op: op.map(Box::new), stopped });
        }
        let mut cfg = config::build(&root, &source)?;
        config::check_entries(&root, "stability", &[config::Model::Linear])?;
        let w = linear::omega_max(&cfg, self.omega_max.as_deref())?;
        if let Some(t) = self.omega_max.as_deref() {
            crate::command::check_speed_omega("--omega-max", t, w, linear::omega0_of_unit(&cfg, t))?;
        }
        let samples = check_count("--samples", self.samples.unwrap_or(DEFAULT_SAMPLES), SAMPLES)?;
        let out = autobal::spatial::comparison::compare_with(&cfg.model, w, samples, self.balls, control)?;
        autobal::limits::check_finite("stability", &out.value.exact)?;
        let stopped = out.stopped.map(|why| {
            // no operating-speed verdict from a scan that did not reach its end
            cfg.config.analysis.operating_speed = None;
            let grid = autobal::spatial::stability::stability_grid(&cfg.model, w, samples).len();
            stopped_message(why, out.value.exact.max_real_part.len(), grid, None)
        });
        Ok(Output::Closed { cfg: Box::new(cfg), c: Box::new(out.value), balls: self.balls, stopped })
    }
}

impl Args {
    /// The library's `omega_max` error (a top speed below what the periodic-orbit analysis
    /// resolves, [`autobal::rotor_stability::Rotor::periodic_floor`]) named as the user
    /// gave the speed: `--omega-max`, else the config's key `key` (`analysis.omega_max`,
    /// `linear_rotor.omega_max`).
    fn name_omega_max(&self, e: anyhow::Error, key: &str, root: &toml::Table, g: &GeneralRotor) -> anyhow::Error {
        general::name_omega_max(e, self.omega_max.is_some(), key, root, g)
    }

    /// `stability` on a linear rotor config ([`crate::linear_rotor`]).
    fn linear_rotor(&self, root: &toml::Table, control: &Control) -> Result<Output> {
        if self.balls == Balls::Locked {
            bail!("--balls locked: a linear rotor is analysed with its balls free");
        }
        let cfg = crate::linear_rotor::from_table(root, self.config.dir())?;
        let samples = check_count("--samples", self.samples.unwrap_or(if cfg.rotor.is_isotropic() { 200 } else { 50 }), SAMPLES)?;
        let omega_max = crate::linear_rotor::omega_max(self.omega_max.as_deref(), &cfg)?;
        // under the control: a stopped scan keeps the speeds it analysed and says so
        // ([`Output::LinearRotor`]'s `stopped`: printed, then an error), as `map` and
        // `campbell` do (audit 21's F2: three balls on a 28-DOF rotor ran for minutes, and
        // Ctrl-C then lost everything)
        let speeds = autobal::rotor_stability::speed_grid(omega_max, samples)?;
        let (rotor, red) = crate::linear_rotor::model(&cfg)?;
        // (as the general route: a speed below the periodic floor is said in rad/s and rpm)
        let g = GeneralRotor::linear(rotor);
        let out = autobal::rotor_stability::stability_over_speed_with(&g.rotor, &speeds, control)
            .map_err(|e| self.name_omega_max(general::floor_in_units(&g, e, &speeds), "linear_rotor.omega_max", root, &g))?;
        // the verdict at the operating speed, as the general route's (first line, JSON
        // `operating`)
        let (r, op, stopped) = kept_scan(out, speeds.len(), control, |r, control| {
            cfg.operating_speed.map(|w| general::operating_at(&g, w, "linear_rotor.operating_speed", r, control)).transpose()
        })?;
        let op = op.map(|o| Box::new((g, o)));
        Ok(Output::LinearRotor { cfg: Box::new(cfg), r: Box::new(r), red: Box::new(red), omega_max, op, stopped })
    }
}

/// A general or linear-rotor scan (`out`, over a grid of `speeds`) as `stability` (and the
/// report's general route) gives it, with the verdict at the operating speed (`op`, asked only
/// of a complete scan) and why it stopped (`stopped_message`). Stopped during the scan
/// (Ctrl-C, a budget): the speeds analysed until then, their ranges ending at the last of them,
/// no family ranges (counted over the speeds whose family was followed, scattered since the
/// families run in parallel, they read the others as not stable: review 22's "all members
/// sampled stable: 80-160, 480-560" where the whole run gives 80-800), no operating-speed
/// verdict. Stopped during the verdict: the complete scan (review 22: it was lost) and the
/// verdict's speeds solved until then ([`general::Operating::stopped_message`]: no verdict, or
/// NOT STABLE where one of them is unstable). Audit 21's F2: three balls on a 28-DOF rotor ran
/// for minutes, and Ctrl-C then lost everything.
pub fn kept_scan(
    out: autobal::control::Outcome<RotorStability>,
    speeds: usize,
    control: &Control,
    op: impl FnOnce(&RotorStability, &Control) -> Result<Option<general::Operating>>,
) -> Result<(RotorStability, Option<general::Operating>, Option<String>)> {
    let mut r = out.value;
    if let Some(why) = out.stopped {
        let families = r.points.iter().filter(|p| p.family_dimension > 0).count();
        let followed = r.points.iter().filter(|p| p.family.is_some()).count();
        let family = (r.family_dimension > 0).then_some((followed, families));
        r.family = None;
        let why = stopped_message(why, r.points.len(), speeds, family);
        return Ok((r, None, Some(why)));
    }
    // the verdict's speeds (and their families) counted on after the scan's reports, the grid
    // speeds then the families followed (`stability_over_speed_with`): one count over the run
    let families = r.points.iter().filter(|p| p.family_dimension > 0).count();
    match op(&r, &control.counted_after((speeds + families) as u64)) {
        Ok(o) => {
            let why = o.as_ref().and_then(general::Operating::stopped_message);
            Ok((r, o, why))
        }
        // (a stop that ends the verdict's solve with an error: none known since the verdict
        // keeps its speeds, kept as the rule for any that does)
        Err(e) => match control.should_stop() {
            Some(why) => Ok((r, None, Some(format!("{why}: the scan is complete, the verdict at the operating speed was stopped and is not given")))),
            None => Err(e),
        },
    }
}

/// What a stopped scan kept, on every route: `"interrupted: 37 of 200 speeds analysed; what was
/// analysed is printed (its stable ranges end where the scan stopped, not where the stability
/// does)"`; with a family of balanced states (`family`: the speeds whose family was followed,
/// of those with one) the count of families followed, and that the family's ranges are left
/// out.
fn stopped_message(why: autobal::control::StopReason, done: usize, speeds: usize, family: Option<(usize, usize)>) -> String {
    let (followed, left_out) = match family {
        Some((followed, families)) if families > 0 => (
            format!(", the family of balanced states followed at {followed} of the {families} with one"),
            "; the family's ranges over its members are left out",
        ),
        Some(_) => (String::new(), "; the family's ranges over its members are left out"),
        None => (String::new(), ""),
    };
    format!(
        "{why}: {done} of {speeds} speeds analysed{followed}; what was analysed is printed (its stable ranges end where the scan stopped, not where the stability does{left_out})"
    )
}

/// A stopped scan's JSON: `complete: false` and `stopped` (why, what was kept); a complete
/// run's JSON is as before, without either key.
pub fn mark_json(mut v: Value, stopped: &Option<String>) -> Value {
    if let Some(why) = stopped {
        v["complete"] = false.into();
        v["stopped"] = why.as_str().into();
    }
    v
}

/// The first line of a stopped scan's table: `INCOMPLETE (why)`; empty when complete.
pub(crate) fn incomplete_line(stopped: &Option<String>) -> String {
    stopped.as_ref().map_or(String::new(), |why| format!("INCOMPLETE ({why})\n"))
}

/// A stopped scan's figure said to be incomplete: its title begins `INCOMPLETE:`, and a
/// vertical line at `at` (the last speed analysed, in the figure's unit) says the scan stopped
/// there (the rest of the axis is empty because nothing was analysed, not because nothing is
/// there).
pub(crate) fn mark_stopped(mut p: Plot, stopped: &Option<String>, at: Option<f64>) -> Plot {
    if stopped.is_some() {
        p.title = format!("INCOMPLETE: {}", p.title);
        if let Some(w) = at {
            p.vlines.push((w, "scan stopped".into()));
        }
    }
    p
}

impl command::Output for Output {
    fn json(&self) -> Result<Value> {
        match self {
            Output::Closed { cfg, c, balls, stopped } => {
                let mut v = linear::stability_json(cfg, c, *balls);
                // the unit of the ranges' speeds, as on the general route: this route's are in
                // Ω (units of ω0) for an SI config too (their rpm in the `_rpm` keys)
                v["speed_unit"] = "Ω".into();
                Ok(mark_json(v, stopped))
            }
            Output::General { g, r, omega_max, op, stopped } => {
                let mut v = general::json(g, r, *omega_max);
                v["operating"] = op.as_deref().map_or(Value::Null, general::operating_json);
                Ok(mark_json(v, stopped))
            }
            Output::LinearRotor { cfg, r, red, omega_max, op, stopped } => {
                let mut v = crate::linear_rotor::stability_json(cfg, r, red, *omega_max)?;
                v["operating"] = op.as_deref().map_or(Value::Null, |(_, o)| general::operating_json(o));
                Ok(mark_json(v, stopped))
            }
        }
    }
    fn table(&self) -> Result<String> {
        match self {
            Output::Closed { cfg, c, balls, stopped } => Ok(incomplete_line(stopped) + &linear::stability_table(cfg, c, *balls)),
            Output::General { g, r, omega_max, op, stopped } => Ok(incomplete_line(stopped) + &general::table(g, r, *omega_max, op.as_deref())),
            Output::LinearRotor { cfg, r, red, omega_max, op, stopped } => {
                let mut first = incomplete_line(stopped);
                first += &op.as_deref().map_or(String::new(), |(g, o)| general::operating_line(g, r, o));
                Ok(first + &crate::linear_rotor::stability_table(cfg, r, red, *omega_max)?)
            }
        }
    }
    /// `stability_margin`: the margin over speed with the stable ranges shaded and the
    /// operating speed marked (a linear rotor config's: [`crate::linear_rotor::margin_plot`]);
    /// a stopped scan's marked incomplete
    /// (its title begins `INCOMPLETE:`, a line marks where the scan stopped).
    fn figures(&self) -> Result<Vec<Figure>> {
        let p = match self {
            Output::Closed { cfg, c, stopped, .. } => {
                let mut p = crate::figures::margin_plot(&cfg.model, c);
                // the operating speed marked, as in the report (walk 27: the command's figure had none)
                p.vlines.extend(crate::figures::operating_vlines(cfg.analysis.operating_speed, crate::figures::SpeedUnit::of(&cfg.model).factor));
                // the series is every grid speed analysed, in the figure's unit
                let at = p.series.first().and_then(|s| s.points.last()).map(|q| q.0);
                mark_stopped(p, stopped, at)
            }
            Output::General { g, r, omega_max, op, stopped } => {
                let mut p = general::margin_plot(g, r, *omega_max);
                p.vlines.extend(crate::figures::operating_vlines(op.as_ref().map(|o| o.omega), 1.0));
                mark_stopped(p, stopped, r.points.last().map(|q| q.omega))
            }
            Output::LinearRotor { r, omega_max, stopped, .. } => {
                mark_stopped(crate::linear_rotor::margin_plot(r, *omega_max), stopped, r.points.last().map(|q| q.omega))
            }
        };
        Ok(vec![Figure::new("stability_margin", p)])
    }
    fn stopped(&self) -> Option<String> {
        match self {
            Output::Closed { stopped, .. } | Output::General { stopped, .. } | Output::LinearRotor { stopped, .. } => stopped.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `critical` and `stability` give the washer's verdict at 1400 rpm over one span: the
    /// config's `analysis.omega_max = "1500 rpm"` (between the operating speed and 1.25 times it,
    /// 1750 rpm, where `critical` used to read), as the same stable range (walk 27).
    #[test]
    fn critical_and_stability_scan_one_span_at_the_operating_speed() {
        let text = include_str!("../../../examples/washing_machine.toml");
        let mut root = crate::config::parse_text(text, "w.toml").unwrap();
        crate::config::apply_set(&mut root, "analysis.omega_max=\"1500 rpm\"").unwrap();
        let st = Args { config: ConfigSource::tables(root.clone(), "w.toml"), ..Default::default() }.run(&Control::none()).unwrap().json().unwrap();
        let cr = crate::critical::Args { config: ConfigSource::tables(root, "w.toml"), ..Default::default() }.run(&Control::none()).unwrap().json().unwrap();
        let (a, b) = (&st["operating_speed"], &cr["operating_speed"]);
        // 1500 rpm in rpm, to the conversion's rounding
        assert!((a["span_rpm"].as_f64().unwrap() - 1500.0).abs() < 1e-9, "{a}");
        assert_eq!(a["span"], b["span"], "{a} {b}");
        assert_eq!(a["stable_range"], b["stable_range"]);
        assert_eq!(a["stable"], true);
    }

    /// At 1 rpm the washer's balanced state has a growth rate of ~1e-10 1/s (ω0 30.3 rad/s:
    /// ~3e-12 ω0, inside the 1e-11 tolerance): the one-plane route said NOT STABLE, the
    /// general route NEUTRAL (hunt 27); now both say NEUTRAL, and the JSON stays not stable.
    /// At 200 rpm (below the lowest critical speed, 284 rpm: unstable) it still says NOT STABLE.
    #[test]
    fn a_growth_rate_within_the_tolerance_reads_neutral_not_unstable() {
        let text = include_str!("../../../examples/washing_machine.toml");
        let at = |speed: &str| {
            let mut root = crate::config::parse_text(text, "w.toml").unwrap();
            crate::config::apply_set(&mut root, &format!("analysis.operating_speed=\"{speed}\"")).unwrap();
            Args { config: ConfigSource::tables(root, "w.toml"), ..Default::default() }.run(&Control::none()).unwrap()
        };
        let out = at("1 rpm");
        let first = out.table().unwrap().lines().nth(1).unwrap().to_string();
        assert!(first.contains("the balanced state is NEUTRAL (not stable: its largest growth rate is within the tolerance 1e-11 ω0 of zero)"), "{first}");
        assert_eq!(out.json().unwrap()["operating_speed"]["stable"], false);
        let out = at("200 rpm");
        assert!(out.table().unwrap().lines().nth(1).unwrap().contains("the balanced state is NOT STABLE (exact"), "{}", out.table().unwrap());
    }
    use crate::command::{Command as _, Output as _};
    use autobal::control::Control;

    fn tables(text: &str, sets: &[&str]) -> ConfigSource {
        let mut root = crate::config::parse_text(text, "test").unwrap();
        for s in sets {
            crate::config::apply_set(&mut root, s).unwrap();
        }
        ConfigSource::tables(root, "test")
    }

    /// `--samples` is checked in one place for every route, with the CLI's one-line message
    /// (Python shows the flag as its keyword); a count in range passes on each.
    #[test]
    fn samples_are_checked_once_for_every_route() {
        let planar = include_str!("../../../examples/planar.toml");
        for (config, route) in [(tables(crate::config::DEFAULT_CONFIG, &[]), Route::Auto), (tables(planar, &[]), Route::Auto)] {
            for bad in [0, 9, 1_000_001] {
                let args = Args { config: config.clone(), samples: Some(bad), route, ..Default::default() };
                let e = format!("{:#}", args.run(&Control::none()).err().expect("out of range"));
                assert_eq!(e, format!("--samples: must lie between 10 and 1000000, got {bad}"));
            }
        }
    }

    /// A linear rotor's operating speed (`linear_rotor.operating_speed`, audit 20's N3: a
    /// linear rotor had none): the verdict there first, as the general route's, in the unit
    /// given (rpm read as `π/30` rad/s), agreeing with the scan's verdicts at the grid speeds
    /// round it; NOT STABLE where the scan is unstable; the default axis reaching 1.25 times
    /// its top; the JSON's `neutral_tolerance` as the general route's; a bad value named.
    #[test]
    fn a_linear_rotor_gives_the_verdict_at_its_operating_speed() {
        use crate::command::Output as _;
        use autobal::analysis::Verdict;
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml");
        // a linear rotor config reads its `--set`s its own way: the key written into the text
        let run = |sets: &[&str]| {
            let text = sets
                .iter()
                .fold(shaft.to_string(), |t, s| t.replacen("[linear_rotor]\n", &format!("[linear_rotor]\n{}\n", s.trim_start_matches("linear_rotor.")), 1));
            Args { config: tables(&text, &[]), samples: Some(30), ..Default::default() }.run(&Control::none())
        };
        let Output::LinearRotor { r, op: None, .. } = run(&[]).unwrap() else { panic!("the linear route without an operating speed") };
        // a grid speed inside a stable range with stable neighbours, and an unstable one
        let pts = &r.points;
        let k = (1..pts.len() - 1).find(|&k| (k - 1..=k + 1).all(|j| pts[j].verdict == Some(Verdict::Stable))).expect("a stable stretch");
        let unstable = pts.iter().find(|p| p.verdict == Some(Verdict::Unstable)).expect("an unstable speed").omega;
        // halfway between two stable grid speeds, given in rpm
        let w = 0.5 * (pts[k].omega + pts[k + 1].omega);
        let rpm = w * 30.0 / std::f64::consts::PI;
        let out = run(&[&format!("linear_rotor.operating_speed=\"{rpm} rpm\"")]).unwrap();
        let v = out.json().unwrap();
        let got = v["operating"]["omega"][0].as_f64().unwrap();
        assert!((got - w).abs() <= 1e-12 * w, "{got} vs {w}");
        assert_eq!(v["operating"]["verdict"], "stable", "{}", v["operating"]);
        assert_eq!(v["neutral_tolerance"], general::neutral_tolerance(autobal::analysis::Kind::Equilibrium));
        let range = &v["operating"]["stable_range"];
        assert!(range["from"].as_f64().unwrap() <= w && w <= range["to"].as_f64().unwrap(), "{range}");
        let first = out.table().unwrap().lines().next().unwrap().to_string();
        assert!(first.starts_with("operating speed ") && first.contains("STABLE (exact, eigenvalues) in the stable range "), "{first}");
        // an unstable grid speed, as a number (rad/s)
        let out = run(&[&format!("linear_rotor.operating_speed={unstable}")]).unwrap();
        assert_eq!(out.json().unwrap()["operating"]["verdict"], "unstable");
        assert!(out.table().unwrap().lines().next().unwrap().contains("NOT STABLE"), "{}", out.table().unwrap());
        // far above the default axis: the axis reaches 1.25 times it
        let top = 3.0 * pts.last().unwrap().omega;
        let Output::LinearRotor { omega_max, .. } = run(&[&format!("linear_rotor.operating_speed={top}")]).unwrap() else { panic!() };
        assert!((omega_max - 1.25 * top).abs() <= 1e-12 * top, "{omega_max} vs {top}");
        for (bad, why) in [("\"-100 rpm\"", "linear_rotor.operating_speed"), ("\"fast\"", "linear_rotor.operating_speed")] {
            let e = format!("{:#}", run(&[&format!("linear_rotor.operating_speed={bad}")]).err().expect("refused"));
            assert!(e.starts_with(why) && !e.contains('\n'), "{e}");
        }
    }

    /// The general route says its verdict at the operating speed first, as the closed-form
    /// route does (main at 07fe55e printed none there; under gravity the washer had no orbit at
    /// 1400 rpm at all: `tests/gravity_family.rs`): STABLE with the scan's range holding it,
    /// NOT STABLE with the nearest stable range, each from the state solved at that speed.
    #[test]
    fn the_general_route_gives_the_verdict_at_the_operating_speed() {
        use crate::command::Output as _;
        let washer = include_str!("../../../examples/washing_machine.toml");
        let args = Args { config: tables(washer, &["spatial.gravity=[0.0, -9.81, 0.0]"]), samples: Some(10), ..Default::default() };
        let out = args.run(&Control::none()).unwrap();
        let t = out.table().unwrap();
        let first = t.lines().next().unwrap();
        assert!(
            first.starts_with("operating speed 146.608 rad/s (1400 rpm): the balanced state is STABLE (exact, Floquet multipliers) in the stable range ")
                && first.contains("(end of the axis); largest growth rate -0.00014"),
            "{first}"
        );
        let v = out.json().unwrap();
        assert_eq!(v["operating"]["stable"], true, "{}", v["operating"]);
        // the two-plane example is unstable up to 1201 rad/s (docs/notes/stability.md)
        let two = include_str!("../../../examples/spatial_two_plane.toml");
        let args = Args { config: tables(two, &["analysis.operating_speed=\"1000 rad/s\""]), samples: Some(10), ..Default::default() };
        let out = args.run(&Control::none()).unwrap();
        let t = out.table().unwrap();
        let first = t.lines().next().unwrap();
        assert!(
            first.starts_with(
                "operating speed 1000 rad/s (9549.3 rpm): the balanced state is NOT STABLE (exact, Floquet multipliers); largest growth rate 43.59"
            ),
            "{first}"
        );
        assert!(first.contains("; nearest stable range "), "{first}");
        assert_eq!(out.json().unwrap()["operating"]["stable"], false);
        assert_eq!(out.json().unwrap()["operating"]["verdict"], "unstable");
        // a neutral speed is said to be undecided, never NOT STABLE (the review's 3 + 3 ball
        // two-plane rotor at 1300 rad/s read "NOT STABLE" with a growth rate of -2.1e-7 1/s);
        // the verdict turned neutral by hand on the washer's
        let Output::General { g, r, op: Some(op), .. } =
            Args { config: tables(washer, &["spatial.gravity=[0.0, -9.81, 0.0]"]), samples: Some(10), ..Default::default() }.run(&Control::none()).unwrap()
        else {
            panic!("the washer's general route")
        };
        let mut neutral = (*op).clone();
        neutral.points[0].verdict = Some(autobal::analysis::Verdict::Neutral);
        let line = general::operating_line(&g, &r, &neutral);
        assert!(line.contains("the balanced state is NEUTRAL (its growth rate within the neutral tolerance of zero"), "{line}");
        assert_eq!(general::operating_json(&neutral)["verdict"], "neutral");
        // stable at the speed, but no range of the scan holds it: said, not left blank
        let mut alone = (*op).clone();
        alone.range = None;
        let line = general::operating_line(&g, &r, &alone);
        assert!(line.contains("STABLE (exact, Floquet multipliers) (the scan's grid found no stable range round it"), "{line}");
    }

    /// A periodic orbit's top speed below ω_n/100 (the spatial two-plane example, gravity) is
    /// refused in one line naming where the speed came from: `--omega-max`, or the config's
    /// `analysis.omega_max`. Main at 21dbfc9 integrated revolutions of ~6e9 s for hours.
    #[test]
    fn a_speed_below_the_periodic_floor_is_refused_by_name() {
        let two = include_str!("../../../examples/spatial_two_plane.toml");
        let args = Args { config: tables(two, &[]), omega_max: Some("1e-9 rad/s".into()), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        // both numbers with their unit, the key named once
        assert!(
            e.starts_with("--omega-max: 1e-9 rad/s (") && e.contains("the grid's top speed, is below 0.809787 rad/s (7.73289 rpm),") && !e.contains('\n'),
            "{e}"
        );
        let args = Args { config: tables(two, &["analysis.omega_max=\"0.001 rad/s\""]), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("analysis.omega_max: 0.001 rad/s ("), "{e}");
    }

    /// A default speed axis (no `--omega-max`, no config key) below the periodic-orbit floor:
    /// the planar rotor's `k_y = 1e13` raises the fastest natural frequency to
    /// sqrt(1e13/1.26) = 2.81718e6 rad/s, the floor to 1/1000 of it, above the default top
    /// 3 sqrt(9e4/1.26) = 801.784 rad/s. `stability` named `analysis.omega_max` (a key a planar
    /// config may not hold) and `critical` a bare `omega_max` with unitless numbers; both now
    /// name `planar.k_y`, with the speeds in rad/s. And a top speed out of range on a planar
    /// rotor is said in rad/s, not as a "dimensionless speed" (session 28's hunt).
    #[test]
    fn a_default_axis_below_the_floor_names_the_key_that_raised_it() {
        let aniso = "[planar]\nm1 = 1.0\nm2 = 0.2\nm3 = 0.03\nn = 2\ns1 = 0.003\ns2 = 0.0005\nr = 0.06\n\
                     k_x = 9.0e4\nk_y = 1e13\nc_x = 40.0\nc_y = 60.0\nc_psi = 0.1\ni_g = 0.0025\n";
        let want = "planar.k_y: 1e13 N/m, through the fastest natural frequency sqrt(k_y/m0) = 2.81718e6 rad/s (2.69021e7 rpm), puts the slowest \
                    speed the periodic-orbit analysis resolves at 2817.18 rad/s (26902.1 rpm) (a revolution spans at most 1000 of its periods), above \
                    the speed axis's default top 801.784 rad/s (7656.47 rpm) (3 times the slowest natural frequency): give --omega-max above it";
        let e = format!("{:#}", Args { config: tables(aniso, &[]), ..Default::default() }.run(&Control::none()).err().expect("refused"));
        assert_eq!(e, want);
        let critical = crate::critical::Args { config: tables(aniso, &[]), route: Route::Auto, omega_max: None };
        let e = format!("{:#}", critical.run(&Control::none()).err().expect("refused"));
        assert_eq!(e, want);
        let campbell = crate::campbell::Args { config: tables(aniso, &[]), points: Some(10), ..Default::default() };
        let e = format!("{:#}", campbell.run(&Control::none()).err().expect("refused"));
        assert_eq!(e, want);
        // given, the flag is named (as before)
        let args = Args { config: tables(aniso, &[]), omega_max: Some("800 rad/s".into()), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("--omega-max: 800 rad/s (7639.44 rpm), the grid's top speed, is below 2817.18 rad/s"), "{e}");
        // rad/s, the planar rotor's unit: 1e7 rpm = 1.0472e6 rad/s
        let planar = include_str!("../../../examples/planar.toml");
        let args = Args { config: tables(planar, &[]), omega_max: Some("1e7 rpm".into()), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("--omega-max: 1e7 rpm is 1.0472e6 rad/s, outside (0, 1e6] rad/s (") && !e.contains("dimensionless"), "{e}");
        // Ω, a spatial rotor's: its ω0 said
        let dimensional = include_str!("../../../examples/dimensional.toml");
        let args = Args { config: tables(dimensional, &[]), omega_max: Some("1e12 rpm".into()), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(
            e.starts_with("--omega-max: 1e12 rpm is Ω = ω/ω0 = ") && e.contains("(ω0 = ") && e.contains(" rad/s), outside (0, 1e6] (dimensionless speed"),
            "{e}"
        );
    }

    /// A linear rotor under gravity whose bearings change with speed (the shaft example, one
    /// bearing tabulated): without its bearings folded in (`at_speed`) the shaft sat on one
    /// pin, its lowest frequency 0, no floor, and a scan to 1 rad/s ran for more than 100 s.
    /// Refused at once, naming the key the user set (`linear_rotor.omega_max`, not
    /// `analysis.omega_max`) or the flag.
    #[test]
    fn a_linear_rotor_with_speed_bearings_has_a_floor_named_by_its_key() {
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml");
        let grav = shaft.replacen("[linear_rotor]\n", "[linear_rotor]\ngravity = [0.0, -9.81]\nomega_max = 2.0\n", 1);
        assert_ne!(grav, shaft);
        let args = Args { config: tables(&grav, &[]), omega_max: Some("1 rad/s".into()), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(
            e.starts_with("--omega-max: 1 rad/s (9.5493 rpm), the grid's top speed, is below ") && e.contains(" rpm), the slowest") && !e.contains('\n'),
            "{e}"
        );
        let args = Args { config: tables(&grav, &[]), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("linear_rotor.omega_max: 2 rad/s (19.0986 rpm), the grid's top speed, is below "), "{e}");
    }

    /// A linear rotor with a couple unbalance only (the shaft example, a second unbalance at
    /// node 1 opposite the disk's): it has an unbalance (main at 41cc036 said "no unbalance to
    /// cancel", testing the static part only, and its JSON had no `has_unbalance`), and its
    /// residuals, the static resultant, are over the balls' capacity (`residual_scale`).
    #[test]
    fn a_couple_only_linear_rotor_has_an_unbalance() {
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml");
        let couple = format!("{shaft}\n[[linear_rotor.unbalance]]\nnode = 1\nme = 2e-4\nphase = 3.141592653589793\n");
        let out = Args { config: tables(&couple, &[]), samples: Some(10), ..Default::default() }.run(&Control::none()).unwrap();
        let j = out.json().unwrap();
        assert_eq!(j["has_unbalance"], serde_json::json!(true), "{}", j["has_unbalance"]);
        assert_eq!(j["residual_scale"], serde_json::json!("capacity"));
        let t = out.table().unwrap();
        assert!(!t.contains("no unbalance to cancel") && !t.contains("of the unbalance"), "{t}");
        // the example itself: a static unbalance, residuals over it
        let j = Args { config: tables(shaft, &[]), samples: Some(10), ..Default::default() }.run(&Control::none()).unwrap().json().unwrap();
        assert_eq!((j["has_unbalance"].clone(), j["residual_scale"].clone()), (serde_json::json!(true), serde_json::json!("static_unbalance")));
    }

    /// The same config read from a file (the CLI) or handed over as tables (Python) gives the
    /// same JSON: one read, one `run`.
    #[test]
    fn a_file_and_its_tables_give_the_same_json() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/dimensional.toml");
        let file = ConfigSource::file(Some(&path), &["analysis.omega_max=\"2000 rpm\"".to_string()]);
        let (root, source) = file.read().unwrap();
        let from_tables = ConfigSource::tables(root, &source);
        assert_eq!(from_tables.dir(), file.dir());
        let run = |config: ConfigSource| Args { config, samples: Some(100), ..Default::default() }.run(&Control::none()).unwrap().json().unwrap();
        let (a, b) = (run(file), run(from_tables));
        assert_eq!(a, b);
        // and it is the dimensional config's: speeds in rpm up to the axis set above
        assert!(a["omega_max_rpm"].as_f64().is_some_and(|w| (w - 2000.0).abs() < 1e-9), "{}", a["omega_max_rpm"]);
    }

    /// The figure is the margin of the comparison the JSON reports: its series is the
    /// `max_real_part` grid of the JSON, point for point.
    #[test]
    fn the_figure_draws_the_json_s_margin() {
        let out = Args { samples: Some(50), ..Default::default() }.run(&Control::none()).unwrap();
        let v = out.json().unwrap();
        let figs = out.figures().unwrap();
        assert_eq!(figs.len(), 1);
        assert_eq!(figs[0].id, "stability_margin");
        let grid: Vec<(f64, f64)> = v["max_real_part"].as_array().unwrap().iter().map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap())).collect();
        // the 50 grid speeds and the points where the range ends were refined
        assert!(grid.len() >= 50, "{}", grid.len());
        let drawn = &figs[0].plot.series.iter().find(|s| s.points.len() == grid.len()).expect("the margin series").points;
        assert_eq!(drawn, &grid);
    }

    /// Review 22: a scan stopped while the families of balanced states are followed (three
    /// balls: they run after the grid speeds, in parallel) gives no family ranges: counted over
    /// the speeds whose family was followed they read the others as not stable. A two-element
    /// shaft on stiff bearings with three balls at mid-span; the observer cancels at the family
    /// phase's first report (`done` past the grid).
    #[test]
    fn a_scan_stopped_among_the_families_gives_no_family_ranges() {
        use crate::command::Output as _;
        let text = "[linear_rotor]\nrotary_inertia = false\ngyroscopic = false\n[[linear_rotor.elements]]\nlength = 0.25\ndiameter = 0.04\ne = 2.1e11\nrho = 7850.0\ncount = 2\n\
                    [[linear_rotor.bearings]]\nnode = 0\nk = 1e7\nc = 200.0\n[[linear_rotor.bearings]]\nnode = 2\nk = 1e7\nc = 200.0\n\
                    [[linear_rotor.unbalance]]\nnode = 1\nme = 1e-4\n\
                    [[linear_rotor.balancer]]\nnode = 1\nradius = 0.05\nballs = 3\nball_mass = 0.01\ndrag = 0.05\n";
        let args = Args { config: tables(text, &[]), samples: Some(12), ..Default::default() };
        let control = Control::new();
        let c = control.clone();
        let control = control.with_progress(move |p| {
            if p.done > 12 {
                c.cancel();
            }
        });
        let out = args.run(&control).unwrap();
        let why = out.stopped().expect("stopped among the families");
        assert!(why.contains("the family's ranges over its members are left out"), "{why}");
        let v = out.json().unwrap();
        // a family at the speeds (its dimension), but no ranges over its members
        assert_eq!(v["family_dimension"], 1);
        assert!(v["family"].is_null() && v["complete"] == false, "{}", v["family"]);
        assert_eq!(v["points"].as_array().unwrap().len(), 12);
        assert!(!out.table().unwrap().contains("all members sampled stable"));
    }

    /// A linear rotor's scan stopped (Ctrl-C) keeps the speeds it analysed and says so (audit
    /// 21's F2: it printed nothing, after minutes of a 3-ball family): the output's `stopped`
    /// names the count, the JSON has `complete: false` and the points analysed (the first three
    /// of the grid here, the observer cancelling at the third), the table's first line says
    /// INCOMPLETE, no operating-speed verdict is given; the same run not stopped has neither key.
    #[test]
    fn a_stopped_linear_rotor_scan_keeps_what_it_analysed() {
        use crate::command::Output as _;
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml").replacen("[linear_rotor]\n", "[linear_rotor]\noperating_speed = 300.0\n", 1);
        let args = Args { config: tables(&shaft, &[]), samples: Some(30), ..Default::default() };
        let control = Control::new();
        let c = control.clone();
        let control = control.with_progress(move |p| {
            if p.done >= 3 {
                c.cancel();
            }
        });
        let out = args.run(&control).unwrap();
        let why = out.stopped().expect("stopped");
        assert!(why.starts_with("interrupted: 3 of 30 speeds analysed; what was analysed is printed"), "{why}");
        let v = out.json().unwrap();
        assert_eq!(v["complete"], false);
        assert_eq!(v["stopped"], why.as_str());
        assert_eq!(v["points"].as_array().unwrap().len(), 3);
        assert!(v["operating"].is_null());
        assert!(out.table().unwrap().starts_with(&format!("INCOMPLETE ({why})\n")));
        // complete: no such keys, and the operating speed's verdict
        let out = args.run(&Control::none()).unwrap();
        assert!(out.stopped().is_none());
        let v = out.json().unwrap();
        assert!(v.get("complete").is_none() && v.get("stopped").is_none() && !v["operating"].is_null());
        assert_eq!(v["points"].as_array().unwrap().len(), 30);
    }

    /// A control that cancels itself at the `k`-th progress report (a Ctrl-C after `k` speeds).
    fn stop_after(k: u64) -> Control {
        let control = Control::new();
        let c = control.clone();
        control.with_progress(move |p| {
            if p.done >= k {
                c.cancel();
            }
        })
    }

    /// Session 23: the general route stopped (Ctrl-C) keeps the speeds it analysed, as the
    /// linear route does (it printed nothing: "the stability scan stopped after 3 of 30 speeds;
    /// nothing is printed"): `stopped` names the count, the JSON has `complete: false` and the
    /// three points, which are the complete run's first three bit for bit (the same scan, cut);
    /// the table's first line says INCOMPLETE, the figure's title too, with a line at the last
    /// speed analysed; the same run not stopped has neither key. Paper 004's planar example.
    #[test]
    fn a_stopped_general_scan_keeps_what_it_analysed() {
        use crate::command::Output as _;
        let planar = include_str!("../../../examples/planar.toml");
        let args = Args { config: tables(planar, &[]), samples: Some(30), ..Default::default() };
        let out = args.run(&stop_after(3)).unwrap();
        let why = out.stopped().expect("stopped");
        assert!(why.starts_with("interrupted: 3 of 30 speeds analysed; what was analysed is printed (its stable ranges end where the scan stopped"), "{why}");
        let v = out.json().unwrap();
        assert_eq!((v["complete"].clone(), v["stopped"].clone()), (serde_json::json!(false), serde_json::json!(why)));
        let kept = v["points"].as_array().unwrap().clone();
        assert_eq!(kept.len(), 3);
        assert!(out.table().unwrap().starts_with(&format!("INCOMPLETE ({why})\nExact linear stability over speed (general route)\n")));
        let fig = &out.figures().unwrap()[0].plot;
        assert!(fig.title.starts_with("INCOMPLETE: "), "{}", fig.title);
        let Output::General { r, .. } = &out else { panic!("the general route") };
        assert_eq!(fig.vlines, vec![(r.points[2].omega, "scan stopped".to_string())]);
        let whole = args.run(&Control::none()).unwrap();
        assert!(whole.stopped().is_none() && whole.figures().unwrap()[0].plot.vlines.is_empty());
        let v = whole.json().unwrap();
        assert!(v.get("complete").is_none() && v.get("stopped").is_none());
        assert_eq!(v["points"].as_array().unwrap()[..3], kept[..]);
    }

    /// Session 23: the closed-form route stopped keeps the grid speeds it analysed (it printed
    /// nothing and ended at once): `stopped` names the count of the grid's speeds (the split
    /// pairs seeded in included, `stability_grid`), the JSON has `complete: false`, the
    /// margins analysed (the complete run's first 40), no verdict at the operating speed, and
    /// no range, exact or 003's, reaching past the last speed analysed (`hi` a number there, not
    /// `null`: open to the span's end); the figure is marked. The dimensional example with an
    /// operating speed, whose complete run gives its verdict.
    #[test]
    fn a_stopped_closed_form_scan_keeps_what_it_analysed() {
        use crate::command::Output as _;
        let dim = include_str!("../../../examples/dimensional.toml");
        let args = Args { config: tables(dim, &["analysis.operating_speed=\"1400 rpm\""]), samples: Some(400), ..Default::default() };
        let out = args.run(&stop_after(40)).unwrap();
        let Output::Closed { cfg, c, .. } = &out else { panic!("the closed-form route") };
        let grid = autobal::spatial::stability::stability_grid(&cfg.model, c.omega_max, 400).len();
        assert!(grid >= 400);
        let why = out.stopped().expect("stopped");
        assert_eq!(
            why,
            format!("interrupted: 40 of {grid} speeds analysed; what was analysed is printed (its stable ranges end where the scan stopped, not where the stability does)")
        );
        let v = out.json().unwrap();
        assert_eq!((v["complete"].clone(), v["stopped"].clone()), (serde_json::json!(false), serde_json::json!(why)));
        assert!(v["operating_speed"].is_null(), "{}", v["operating_speed"]);
        let margins = v["max_real_part"].as_array().unwrap().clone();
        assert_eq!(margins.len(), 40);
        let last = margins[39][0].as_f64().unwrap();
        for key in ["stable_ranges", "necessary_ranges", "necessary_not_stable", "stable_not_necessary"] {
            for r in v[key].as_array().unwrap() {
                assert!(r[1].as_f64().is_some_and(|hi| hi <= last), "{key}: {r} past {last}");
            }
        }
        assert!(out.table().unwrap().starts_with(&format!("INCOMPLETE ({why})\nconfig: ")));
        let fig = &out.figures().unwrap()[0].plot;
        assert!(fig.title.starts_with("INCOMPLETE: ") && fig.vlines.len() == 1, "{}", fig.title);
        let whole = args.run(&Control::none()).unwrap();
        assert!(whole.stopped().is_none());
        let v = whole.json().unwrap();
        assert!(v.get("complete").is_none() && !v["operating_speed"].is_null());
        assert_eq!(v["max_real_part"].as_array().unwrap()[..40], margins[..]);
    }

    /// Review 23: a stopped scan's words cover the speeds analysed only. The general route's
    /// range that reaches the stop ends "where the scan stopped", not "(end of the axis)", and
    /// "nowhere" spans (0, the last speed analysed]; stopped before its first speed it says
    /// so (it read "no stationary state was found at any of the 0 speeds"); the closed form's
    /// 003 sentence says it covers the speeds analysed ("coincide" after none), and its margin
    /// line has no "inf"; the linear rotor's "nowhere" spans what was analysed.
    #[test]
    fn a_stopped_scan_s_words_cover_only_the_speeds_analysed() {
        use crate::command::Output as _;
        let none = || Control::new().with_budget(std::time::Duration::ZERO);
        let planar = include_str!("../../../examples/planar.toml");
        let args = Args { config: tables(planar, &[]), samples: Some(30), ..Default::default() };
        // paper 004's rotor is stable from ~301 rad/s: 15 of 30 speeds on (0, 864] reach 432
        let out = args.run(&stop_after(15)).unwrap();
        let t = out.table().unwrap();
        let Output::General { r, .. } = &out else { panic!("the general route") };
        let last = r.points.last().unwrap().omega;
        assert!(r.stable_ranges.last().is_some_and(|s| s.to == last), "{t}");
        assert!(!t.contains("end of the axis") && t.contains("(the last speed analysed: the scan stopped there)"), "{t}");
        let t = args.run(&none()).unwrap().table().unwrap();
        assert!(t.contains("no verdict: the scan stopped before its first speed\n") && !t.contains("no stationary state was found"), "{t}");
        // paper 000's rotor by the general route: unstable below Ω ≈ 1.3
        let default = include_str!("../../../examples/default.toml");
        let general = Args { config: tables(default, &[]), samples: Some(30), route: crate::command::Route::General, ..Default::default() };
        let out = general.run(&stop_after(3)).unwrap();
        let Output::General { g, r, .. } = &out else { panic!("the general route") };
        let t = out.table().unwrap();
        let want = format!("stable: nowhere among the 3 of 3 speeds in (0, {}]", crate::general::speed_text(g, r.points[2].omega));
        assert!(t.contains(&want), "{t}");
        // the closed form
        let dim = include_str!("../../../examples/dimensional.toml");
        let args = Args { config: tables(dim, &[]), samples: Some(400), ..Default::default() };
        let t = args.run(&stop_after(40)).unwrap().table().unwrap();
        assert!(t.contains("difference: over the speeds analysed only, 0 < Ω ≤ "), "{t}");
        assert!(t.contains("the scan stopped at Ω = ") && t.contains(", 003's too, cover 0 < Ω ≤ "), "{t}");
        let whole = args.run(&Control::none()).unwrap().table().unwrap();
        assert!(!whole.contains("over the speeds analysed only"));
        let t = args.run(&none()).unwrap().table().unwrap();
        assert!(t.contains("difference: not compared: the scan stopped before its first speed") && !t.contains("inf"), "{t}");
        assert!(t.contains("max Re λ over the grid: none (no speed analysed)"), "{t}");
        // the linear rotor, stopped below its first stable speed
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml");
        let args = Args { config: tables(shaft, &[]), samples: Some(30), ..Default::default() };
        let out = args.run(&stop_after(1)).unwrap();
        let Output::LinearRotor { r, .. } = &out else { panic!("the linear route") };
        let t = out.table().unwrap();
        if r.stable_ranges.is_empty() {
            let w = r.points[0].omega;
            assert!(t.contains("stable: nowhere in (0, ") && !t.contains("2543"), "{w}: {t}");
        }
    }

    /// The one rule of the general and linear routes ([`kept_scan`]): a stop during the verdict
    /// at the operating speed keeps the complete scan and says the verdict is not given; an
    /// error there that is no stop is the error; a scan stopped gives no verdict (not asked)
    /// and no family ranges. Paper 004's Jeffcott rotor, 10 speeds.
    #[test]
    fn the_operating_speed_s_stop_keeps_the_scan() {
        use autobal::planar::PlanarRotor;
        use autobal::rotor_stability::Rotor;
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let (out, speeds) = general::scan(&g, 600.0, 10, &Control::none()).unwrap();
        let control = Control::new();
        let (r, op, why) = kept_scan(out.clone(), speeds, &control, |_, _| {
            control.cancel();
            anyhow::bail!("interrupted")
        })
        .unwrap();
        assert_eq!(
            (r.points.len(), op.is_none(), why.as_deref()),
            (10, true, Some("interrupted: the scan is complete, the verdict at the operating speed was stopped and is not given"))
        );
        let e = kept_scan(out.clone(), speeds, &Control::none(), |_, _| anyhow::bail!("analysis.operating_speed: bad")).err().unwrap();
        assert_eq!(e.to_string(), "analysis.operating_speed: bad");
        // the verdict stopped at its first speed (the control cancelled before it): kept, said
        let stopped = Control::new();
        stopped.cancel();
        let (r, op, why) =
            kept_scan(out.clone(), speeds, &Control::none(), |r, _| general::operating_at(&g, [450.0, 500.0], "key", r, &stopped).map(Some)).unwrap();
        let op = op.expect("the verdict kept");
        assert_eq!((r.points.len(), op.points.len(), op.verdict()), (10, 0, None));
        assert_eq!(why, op.stopped_message());
        let mut cut = out;
        cut.stopped = Some(autobal::control::StopReason::Interrupted);
        let (_, op, why) = kept_scan(cut, speeds, &Control::none(), |_, _| panic!("no verdict asked of a stopped scan")).unwrap();
        assert!(op.is_none() && why.unwrap().starts_with("interrupted: 10 of 10 speeds analysed"));
    }

    /// The verdict at the operating speed stopped (Ctrl-C after the scan and 3 of its 9
    /// speeds) keeps what it solved and says so (`stability` dropped it: "the verdict at the
    /// operating speed was stopped and is not given"; the report ended with an error, "nothing
    /// is printed"): `stopped` names the count, the JSON has the whole scan and `operating` with
    /// `complete: false` and the 3 speeds solved, bit for bit the complete run's first 3; the
    /// table's first line says INCOMPLETE and the verdict's line that it stopped. A range
    /// whose lower end is unstable is NOT STABLE from the first speed solved (the others cannot
    /// make it stable); one stable at the speeds solved has no verdict. The shaft example (2
    /// balls: no family, so the scan reports one item per speed, then the verdict one per speed).
    #[test]
    fn a_stopped_operating_speed_verdict_keeps_the_speeds_solved() {
        use crate::command::Output as _;
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml");
        let with = |range: &str| {
            let text = shaft.replacen("[linear_rotor]\n", &format!("[linear_rotor]\noperating_speed = \"{range}\"\n"), 1);
            Args { config: tables(&text, &[]), samples: Some(12), ..Default::default() }
        };
        // 450-500 rad/s: stable at each of its 9 speeds (the balanced state is stable from
        // ~420 rad/s), so no verdict from 3 of them
        let whole = with("450-500 rad/s").run(&Control::none()).unwrap().json().unwrap();
        assert_eq!(whole["operating"]["verdict"], "stable");
        let solved = whole["operating"]["points"].as_array().unwrap().clone();
        assert_eq!(solved.len(), 9);
        let out = with("450-500 rad/s").run(&stop_after(12 + 3)).unwrap();
        let why = out.stopped().expect("stopped");
        assert_eq!(why, "interrupted: the scan is complete; the verdict at the operating speed stopped after 3 of 9 speeds solved there (kept: JSON operating.points): no verdict");
        let v = out.json().unwrap();
        assert_eq!((v["complete"].clone(), v["points"].as_array().unwrap().len()), (serde_json::json!(false), 12));
        let op = &v["operating"];
        assert_eq!(
            (op["complete"].clone(), op["stopped"].clone(), op["verdict"].clone()),
            (serde_json::json!(false), serde_json::json!(why), serde_json::Value::Null)
        );
        assert_eq!(op["points"].as_array().unwrap()[..], solved[..3]);
        let t = out.table().unwrap();
        assert!(t.starts_with(&format!("INCOMPLETE ({why})\noperating speed 450 rad/s")), "{t}");
        assert!(t.lines().nth(1).unwrap().ends_with(": no verdict: stopped after 3 of 9 speeds solved there"), "{t}");
        // 300-500 rad/s: unstable at its first speed, so NOT STABLE from that one alone
        let whole = with("300-500 rad/s").run(&Control::none()).unwrap().json().unwrap();
        assert_eq!(
            (whole["operating"]["verdict"].clone(), whole["operating"]["points"][0]["verdict"].clone()),
            (serde_json::json!("unstable"), serde_json::json!("unstable"))
        );
        let out = with("300-500 rad/s").run(&stop_after(12 + 1)).unwrap();
        let why = out.stopped().unwrap();
        assert!(why.ends_with("after 1 of 9 speeds solved there (kept: JSON operating.points): NOT STABLE, a speed solved is unstable"), "{why}");
        let v = out.json().unwrap();
        assert_eq!((v["operating"]["verdict"].clone(), v["operating"]["stable"].clone()), (serde_json::json!("unstable"), serde_json::json!(false)));
        assert_eq!(v["operating"]["points"].as_array().unwrap()[..], whole["operating"]["points"].as_array().unwrap()[..1]);
        let t = out.table().unwrap();
        assert!(t.contains("is NOT STABLE (exact, eigenvalues) (stopped after 1 of 9 speeds solved there: one of them is unstable, the rate is theirs); largest growth rate"), "{t}");
    }

    /// One count over the whole run (review 22: "the progress bar restarts its count"): the
    /// grid speeds, then the families followed, then the operating speed's verdict each report
    /// one more item done of a total that never shrinks, the last report all done. Main at
    /// 32c0d61 counted 1..24 of 24 over the scan and its families on this three-ball shaft (12
    /// speeds), then restarted at 1 of 1 and 2 of 2 for the verdict at the operating speed (its
    /// state, then its family: seconds each on a real FE model), so the bar fell back to empty.
    #[test]
    fn one_progress_count_over_the_whole_run() {
        let text = "[linear_rotor]\nrotary_inertia = false\ngyroscopic = false\noperating_speed = 300.0\n[[linear_rotor.elements]]\nlength = 0.25\ndiameter = 0.04\ne = 2.1e11\nrho = 7850.0\ncount = 2\n\
                    [[linear_rotor.bearings]]\nnode = 0\nk = 1e7\nc = 200.0\n[[linear_rotor.bearings]]\nnode = 2\nk = 1e7\nc = 200.0\n\
                    [[linear_rotor.unbalance]]\nnode = 1\nme = 1e-4\n\
                    [[linear_rotor.balancer]]\nnode = 1\nradius = 0.05\nballs = 3\nball_mass = 0.01\ndrag = 0.05\n";
        let args = Args { config: tables(text, &[]), samples: Some(12), ..Default::default() };
        let seen = std::sync::Arc::new(std::sync::Mutex::new(vec![]));
        let s = seen.clone();
        let control = Control::new().with_progress(move |p| s.lock().unwrap().push((p.done, p.total)));
        let out = args.run(&control).unwrap();
        assert!(out.json().unwrap()["operating"]["verdict"].is_string());
        let seen = seen.lock().unwrap().clone();
        // 12 speeds, 12 families, the operating speed and its family (the families run in
        // parallel: their reports may arrive out of order, each `done` once)
        let mut done: Vec<u64> = seen.iter().map(|p| p.0).collect();
        done.sort_unstable();
        assert_eq!(done, (1..=26).collect::<Vec<u64>>(), "{seen:?}");
        assert!(seen.windows(2).all(|w| w[1].1 >= w[0].1), "a total shrank: {seen:?}");
        assert_eq!(seen.last(), Some(&(26, 26)), "{seen:?}");
    }
}
