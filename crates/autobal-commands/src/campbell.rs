//! `autobal campbell`: eigenvalues along the speed, tracked, with whirl direction and dominant
//! motion: paper 000's 12-state model, streamed ([`crate::linear::campbell_run`]), or the
//! general route ([`crate::general_campbell`]: eigenvalues, or Floquet exponents of the
//! periodic orbit, of the nonlinear equations' exact linearisation; on a `[linear_rotor]`
//! config always, the rotor with its balls free).

use crate::command::{self, check_count, ConfigSource, Figure, Route};
use crate::config;
use crate::general::GeneralRotor;
use crate::general_campbell;
use crate::linear::{self, CampbellRun, CampbellView};
use anyhow::Result;
use autobal::control::Control;
use autobal::spatial::linear_model::Balls;
use serde_json::Value;

/// The range of `--points` on the closed-form route (streamed: memory does not grow with it).
pub const POINTS: std::ops::RangeInclusive<usize> = 3..=10_000_000;

/// The range of `--points` on the general route (held in memory).
pub const GENERAL_POINTS: std::ops::RangeInclusive<usize> = 3..=100_000;

/// `--points` when none is given (the general route: 60 where it shoots periodic orbits).
pub const DEFAULT_POINTS: usize = 300;

/// `autobal campbell`'s arguments.
#[derive(Debug, Clone)]
pub struct Args {
    /// The config.
    pub config: ConfigSource,
    /// The top of the speed axis: a speed with its unit, or a bare number Ω; `None`: the
    /// config's `analysis.omega_max`, else automatic.
    pub omega_max: Option<String>,
    /// Balls free (12 states) or locked (8 states; on the general route locked at the closed-form
    /// balanced position).
    pub balls: Balls,
    /// The number of speeds; `None`: [`DEFAULT_POINTS`] (60 where the general route shoots
    /// periodic orbits).
    pub points: Option<usize>,
    /// Excitation harmonics `h` whose lines `h×Ω` are crossed for the critical speeds (where a
    /// mode's circular component whirls at `h×Ω`: [`autobal::spatial::campbell`]).
    pub harmonics: Vec<u32>,
    /// The figure view.
    pub view: CampbellView,
    /// The route.
    pub route: Route,
    /// Whether the JSON is kept (the closed-form route streams it to temporary files; `false`
    /// for the table and figures alone).
    pub json: bool,
}

impl Default for Args {
    fn default() -> Self {
        Args {
            config: ConfigSource::default(),
            omega_max: None,
            balls: Balls::Free,
            points: None,
            harmonics: vec![1],
            view: CampbellView::Fixed,
            route: Route::Auto,
            json: true,
        }
    }
}

/// `campbell`'s result, by route.
pub enum Output {
    /// The 12-state model's diagram, streamed.
    Closed(Box<CampbellRun>),
    /// The general route over `(0, omega_max]`.
    General {
        /// The rotor.
        g: Box<GeneralRotor>,
        /// Its diagram, fixed-axes view and crossings.
        c: Box<general_campbell::GeneralCampbell>,
        /// The top of the axis (model units).
        omega_max: f64,
        /// The figure view (`--view`).
        view: CampbellView,
        /// The operating speed `[lo, hi]` (model units), marked in the figures.
        op: Option<[f64; 2]>,
    },
}

impl command::Command for Args {
    const NAME: &'static str = "campbell";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        let (root, source) = self.config.read_any()?;
        let harmonics = linear::check_harmonics(&self.harmonics)?;
        if crate::linear_rotor::is_linear(&root) {
            return self.linear_rotor(&root, &harmonics, control);
        }
        if self.route.is_general(&root) {
            let g = crate::general::rotor_of(&root)?;
            let from_linear = config::FromLinear::SpeedRange { omega_max_given: self.omega_max.is_some(), necessary: false };
            config::check_entries_with(&root, "campbell", &[config::simulation_model(&root)], from_linear)?;
            let points = self.points.unwrap_or(if g.rotor.is_periodic() { 60 } else { DEFAULT_POINTS });
            if !GENERAL_POINTS.contains(&points) {
                return Err(autobal::Error::invalid(
                    "--points",
                    format!("must lie between {} and {} on the general route, got {points}", GENERAL_POINTS.start(), GENERAL_POINTS.end()),
                )
                .into());
            }
            let w = general_campbell::omega_max(&root, &g, self.omega_max.as_deref())?;
            let c = general_campbell::campbell_with(&g, w, points, self.balls, &harmonics, control)
                .map_err(|e| crate::general::name_omega_max(e, self.omega_max.is_some(), "analysis.omega_max", &root, &g))?;
            // (only marked in the figures: a config whose operating speed cannot be read marks none)
            let op = crate::general::operating_speed(&g, &root).ok().flatten();
            return Ok(Output::General { g: Box::new(g), c: Box::new(c), omega_max: w, view: self.view, op });
        }
        let cfg = config::build(&root, &source)?;
        config::check_entries(&root, "campbell", &[config::Model::Linear])?;
        let w = linear::omega_max(&cfg, self.omega_max.as_deref())?;
        if let Some(t) = self.omega_max.as_deref() {
            crate::command::check_speed_omega("--omega-max", t, w, linear::omega0_of_unit(&cfg, t))?;
        }
        let points = check_count("--points", self.points.unwrap_or(DEFAULT_POINTS), POINTS)?;
        let run = linear::campbell_run(&cfg, w, points, self.balls, self.json, &harmonics, control)?;
        Ok(Output::Closed(Box::new(run)))
    }
}

impl Args {
    /// `campbell` on a linear rotor config ([`crate::linear_rotor`]): the general route's
    /// diagram of the rotor **with its balls** free (the model analysed: the reduced one where
    /// the config reduces), as `stability` analyses it; the structure's diagram without the
    /// balls (ROSS's `run_campbell`) is the report's.
    fn linear_rotor(&self, root: &toml::Table, harmonics: &[u32], control: &Control) -> Result<Output> {
        if self.balls == Balls::Locked {
            anyhow::bail!("--balls locked: a linear rotor is analysed with its balls free");
        }
        let cfg = crate::linear_rotor::from_table(root, self.config.dir())?;
        let (rotor, _) = crate::linear_rotor::model(&cfg)?;
        let g = GeneralRotor::linear(rotor);
        let points = self.points.unwrap_or(if g.rotor.is_periodic() { 60 } else { DEFAULT_POINTS });
        if !GENERAL_POINTS.contains(&points) {
            return Err(autobal::Error::invalid(
                "--points",
                format!("must lie between {} and {} on the general route, got {points}", GENERAL_POINTS.start(), GENERAL_POINTS.end()),
            )
            .into());
        }
        let w = crate::linear_rotor::omega_max(self.omega_max.as_deref(), &cfg)?;
        let c = general_campbell::campbell_with(&g, w, points, Balls::Free, harmonics, control)
            .map_err(|e| crate::general::name_omega_max(e, self.omega_max.is_some(), "linear_rotor.omega_max", root, &g))?;
        Ok(Output::General { g: Box::new(g), c: Box::new(c), omega_max: w, view: self.view, op: cfg.operating_speed })
    }
}

impl command::Output for Output {
    fn json(&self) -> Result<Value> {
        match self {
            Output::Closed(run) => {
                let mut text = vec![];
                run.write_json(&mut text)?;
                Ok(serde_json::from_slice(&text)?)
            }
            // only where stopped: `complete: false`, `stopped` (a complete run's JSON is as before)
            Output::General { g, c, omega_max, .. } => Ok(crate::stability::mark_json(general_campbell::campbell_json(g, c, *omega_max), &c.stopped)),
        }
    }
    fn write_json(&self, out: &mut dyn std::io::Write) -> Result<()> {
        match self {
            // streamed from the temporary files: the whole JSON is never in memory
            Output::Closed(run) => run.write_json(out),
            Output::General { .. } => {
                let text = serde_json::to_string_pretty(&self.json()?)?;
                writeln!(out, "{text}")?;
                Ok(())
            }
        }
    }
    fn table(&self) -> Result<String> {
        Ok(match self {
            Output::Closed(run) => run.table(),
            Output::General { g, c, .. } => crate::stability::incomplete_line(&c.stopped) + &general_campbell::campbell_table(g, c),
        })
    }
    /// `campbell_modes` (fixed axes, one curve per mode), and on the closed-form route
    /// `campbell_fixed`, `campbell_rotating` (`--view components`).
    fn figures(&self) -> Result<Vec<Figure>> {
        Ok(match self {
            Output::Closed(run) => run.figures(),
            // a stopped diagram's figures say so in their titles (its curves end at the last
            // speed analysed)
            // the operating speed marked, as in the report (walk 27): on the fixed-axes view's
            // rpm axis for an SI rotor, else in the rotor's units
            Output::General { g, c, omega_max, view, op } => {
                let mark = |mut p: crate::plot::Plot, k: f64| {
                    p.vlines.extend(crate::figures::operating_vlines(*op, k));
                    crate::stability::mark_stopped(p, &c.stopped, None)
                };
                match view {
                    CampbellView::Fixed => {
                        let k = if g.si { crate::num::RPM_PER_RAD_S } else { 1.0 };
                        vec![Figure::new("campbell_modes", mark(general_campbell::campbell_plot(g, c, *omega_max), k))]
                    }
                    CampbellView::Components => {
                        let (rotating, fixed) = general_campbell::components_plots(g, c);
                        vec![Figure::new("campbell_rotating", mark(rotating, 1.0)), Figure::new("campbell_fixed", mark(fixed, 1.0))]
                    }
                }
            }
        })
    }
    fn stopped(&self) -> Option<String> {
        match self {
            Output::Closed(run) => run.stopped(),
            Output::General { c, .. } => c.stopped.clone(),
        }
    }
}

/// `serde_json::to_writer(out, r)` of one mode (its exact bytes: compact, fields in the
/// struct's order, the SI ones left out when `None`, a non-finite number `null`), written
/// without serde's per-field calls and key escaping: the keys are constant text, the numbers
/// zmij's shortest round-trip digits as `serde_json` writes them. The closed-form route writes
/// one a mode a speed (2 400 for 200 speeds): serde's path was an eighth of the command's
/// instructions. A test compares the bytes with `serde_json`'s.
pub fn write_mode_json(out: &mut impl std::io::Write, r: &autobal::reports::ModeReport) -> std::io::Result<()> {
    let mut j = Json(Vec::with_capacity(640));
    j.num(b"{\"decay_rate\":", r.decay_rate);
    j.opt(b",\"decay_rate_per_s\":", r.decay_rate_per_s);
    j.num(b",\"fixed_frequency\":", r.fixed_frequency);
    j.opt(b",\"fixed_frequency_hz\":", r.fixed_frequency_hz);
    j.opt(b",\"fixed_frequency_rad_s\":", r.fixed_frequency_rad_s);
    j.opt(b",\"fixed_frequency_rpm\":", r.fixed_frequency_rpm);
    j.num(b",\"forward_share\":", r.forward_share);
    j.put(b",\"group\":");
    j.put(match r.group {
        autobal::spatial::stability::Group::Translation => b"\"translation\"",
        autobal::spatial::stability::Group::Tilt => b"\"tilt\"",
        autobal::spatial::stability::Group::Balls => b"\"balls\"",
    });
    j.num(b",\"im\":", r.im);
    j.opt(b",\"im_hz\":", r.im_hz);
    j.opt(b",\"im_rad_s\":", r.im_rad_s);
    j.nullable(b",\"log_decrement\":", r.log_decrement);
    j.num(b",\"re\":", r.re);
    j.opt(b",\"re_per_s\":", r.re_per_s);
    j.whirl(b",\"whirl\":", r.whirl);
    j.put(b"}");
    out.write_all(&j.0)
}

/// `serde_json::to_writer(out, modes)` of the fixed-axes curves (the same bytes; as
/// [`write_mode_json`], one point a curve a speed).
pub fn write_fixed_modes_json(out: &mut impl std::io::Write, modes: &[autobal::reports::FixedModeReport]) -> std::io::Result<()> {
    let mut j = Json(Vec::with_capacity(1 << 16));
    j.put(b"[");
    for (i, m) in modes.iter().enumerate() {
        j.put(if i == 0 { b"{\"line\":" } else { b",{\"line\":" });
        j.int(m.line as u64);
        j.put(b",\"mode\":");
        j.int(m.mode as u64);
        j.put(b",\"points\":[");
        for (k, p) in m.points.iter().enumerate() {
            j.num(if k == 0 { b"{\"fixed_frequency\":" } else { b",{\"fixed_frequency\":" }, p.fixed_frequency);
            j.opt(b",\"fixed_frequency_hz\":", p.fixed_frequency_hz);
            j.num(b",\"frequency\":", p.frequency);
            j.opt(b",\"frequency_hz\":", p.frequency_hz);
            j.nullable(b",\"log_decrement\":", p.log_decrement);
            j.num(b",\"nu\":", p.nu);
            j.num(b",\"omega\":", p.omega);
            j.opt(b",\"omega_rpm\":", p.omega_rpm);
            j.num(b",\"re\":", p.re);
            j.opt(b",\"re_per_s\":", p.re_per_s);
            j.num(b",\"share\":", p.share);
            j.whirl(b",\"whirl\":", p.whirl);
            j.put(b"}");
            if j.0.len() > 1 << 15 {
                out.write_all(&j.0)?;
                j.0.clear();
            }
        }
        j.put(b"]}");
    }
    j.put(b"]");
    out.write_all(&j.0)
}

/// JSON text as `serde_json` writes it, for [`write_mode_json`] and [`write_fixed_modes_json`].
struct Json(Vec<u8>);

impl Json {
    fn put(&mut self, b: &[u8]) {
        self.0.extend_from_slice(b);
    }
    /// `key` (with its separator and colon) and a number (`null` when not finite).
    fn num(&mut self, key: &[u8], v: f64) {
        self.put(key);
        if v.is_finite() {
            self.put(zmij::Buffer::new().format_finite(v).as_bytes());
        } else {
            self.put(b"null");
        }
    }
    /// A field left out when `None` (`skip_serializing_if = "Option::is_none"`).
    fn opt(&mut self, key: &[u8], v: Option<f64>) {
        if let Some(v) = v {
            self.num(key, v);
        }
    }
    /// A field written `null` when `None`.
    fn nullable(&mut self, key: &[u8], v: Option<f64>) {
        match v {
            Some(v) => self.num(key, v),
            None => {
                self.put(key);
                self.put(b"null");
            }
        }
    }
    fn int(&mut self, v: u64) {
        let mut b = [0u8; 20];
        let mut k = b.len();
        let mut v = v;
        loop {
            k -= 1;
            b[k] = b'0' + (v % 10) as u8;
            v /= 10;
            if v == 0 {
                break;
            }
        }
        self.put(&b[k..]);
    }
    fn whirl(&mut self, key: &[u8], w: autobal::spatial::stability::Whirl) {
        use autobal::spatial::stability::Whirl;
        self.put(key);
        self.put(match w {
            Whirl::Forward => b"\"forward\"",
            Whirl::Backward => b"\"backward\"",
            Whirl::None => b"\"none\"",
        });
    }
}

/// The figures `--svg PREFIX` writes for `view`: `(path, figure id)` ([`linear::campbell_svg_paths`]).
pub fn svg_files(prefix: &std::path::Path, view: CampbellView) -> Vec<(std::path::PathBuf, &'static str)> {
    let ids: &[&'static str] = match view {
        CampbellView::Fixed => &["campbell_modes"],
        CampbellView::Components => &["campbell_rotating", "campbell_fixed"],
    };
    linear::campbell_svg_paths(prefix, view).into_iter().zip(ids.iter().copied()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::{Command as _, Output as _};
    use autobal::spatial::campbell::fixed_axes;

    /// The streamed JSON of the closed-form route equals the library's JSON of the same
    /// diagram computed in memory in one call (`reports::campbell_of` and `campbell_fixed`, the
    /// route Python took before it ran the command), and the figure `campbell_modes` is the
    /// fixed-axes plot of that in-memory diagram: streaming and decimation (none below
    /// `PLOT_SPEEDS` speeds) lose nothing.
    #[test]
    fn the_streamed_json_and_figure_equal_the_in_memory_diagram() {
        let points = 40;
        let out = Args { points: Some(points), omega_max: Some("3".into()), ..Default::default() }.run(&Control::none()).unwrap();
        assert!(out.stopped().is_none());
        let got = out.json().unwrap();
        let cfg = crate::config::build(&crate::config::parse_text(crate::config::DEFAULT_CONFIG, "d").unwrap(), "d").unwrap();
        let c = autobal::spatial::stability::campbell(&cfg.model, &crate::linear::campbell_grid(3.0, points), Balls::Free).unwrap();
        let fixed = fixed_axes(&cfg.model, &c, Balls::Free, &[1]).unwrap();
        let mut want = serde_json::to_value(autobal::reports::campbell_of(&cfg.model, &c)).unwrap();
        if let (Some(o), Value::Object(extra)) = (want.as_object_mut(), serde_json::to_value(autobal::reports::campbell_fixed(&cfg.model, &fixed)).unwrap()) {
            o.extend(extra);
        }
        assert_eq!(got, want);
        let figs = out.figures().unwrap();
        let ids: Vec<&str> = figs.iter().map(|f| f.id.as_str()).collect();
        assert_eq!(ids, ["campbell_modes", "campbell_fixed", "campbell_rotating"]);
        assert_eq!(figs[0].plot.to_plotly(), crate::figures::campbell_fixed_plot(&cfg.model, &fixed).to_plotly());
        // the table's format: streamed or not, the same text
        let table_only = Args { points: Some(points), omega_max: Some("3".into()), json: false, ..Default::default() }.run(&Control::none()).unwrap();
        assert_eq!(table_only.table().unwrap(), out.table().unwrap());
        assert!(table_only.json().is_err(), "no JSON was kept");
    }

    /// `campbell`'s and `stability`'s figures mark the washer's operating speed (1400 rpm)
    /// where it lies on each figure's own axis, on the closed-form route and the general one
    /// (walk 27: the commands' figures had no mark, the report's Campbell diagram had it at the
    /// rad/s value on its rpm axis): 1400 on an rpm axis, 1400·2π/60 = 146.608 on a rad/s one,
    /// read from the axis title, not from the code's factors.
    #[test]
    fn the_commands_figures_mark_the_operating_speed_in_their_own_unit() {
        let text = include_str!("../../../examples/washing_machine.toml");
        assert!(text.contains("operating_speed = \"1400 rpm\""));
        let config = || ConfigSource::tables(crate::config::parse_text(text, "washer.toml").unwrap(), "washer.toml");
        let check = |figs: Vec<Figure>| {
            for f in &figs {
                crate::figures::assert_marks_operating_rpm(&f.id, &f.plot, 1400.0);
            }
            figs.len()
        };
        for route in [Route::Auto, Route::General] {
            for view in [CampbellView::Fixed, CampbellView::Components] {
                let args = Args { config: config(), points: Some(if route == Route::General { 8 } else { 40 }), route, view, ..Default::default() };
                let n = check(args.run(&Control::none()).unwrap().figures().unwrap());
                assert!(n >= 1, "{route:?} {view:?}");
            }
            let args = crate::stability::Args { config: config(), route, samples: Some(if route == Route::General { 10 } else { 200 }), ..Default::default() };
            assert_eq!(check(args.run(&Control::none()).unwrap().figures().unwrap()), 1);
        }
    }

    /// Stopped at once (the control already cancelled, as by a Ctrl-C during the first speed),
    /// the run keeps the speed it computed and says it is incomplete: the JSON has as many
    /// speeds as each line has modes, `complete: false`, and `stopped` names the count.
    #[test]
    fn a_stopped_run_keeps_what_it_computed_and_says_so() {
        let control = Control::new();
        control.cancel();
        let out = Args { points: Some(30), omega_max: Some("3".into()), ..Default::default() }.run(&control).unwrap();
        let why = out.stopped().expect("incomplete");
        assert!(why.starts_with("interrupted: 1 of 30 speeds computed"), "{why}");
        let v = out.json().unwrap();
        assert_eq!(v["complete"], Value::Bool(false));
        let n = v["omega"].as_array().unwrap().len();
        assert_eq!(n, 1);
        for l in v["lines"].as_array().unwrap() {
            assert_eq!(l["modes"].as_array().unwrap().len(), n);
        }
    }

    /// `campbell` on a linear rotor config with balls (examples/linear_rotor_shaft.toml, reduced
    /// as the config says) is the general route's diagram of that rotor with its balls free: the
    /// library's `campbell_over_speed` on the same model and speeds, line for line (the same
    /// computation: equal to the bit), with `2 (N + Σn)` lines; `--balls locked` is refused.
    #[test]
    fn a_linear_rotor_config_gives_the_general_diagram_with_its_balls() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/linear_rotor_shaft.toml");
        let config = ConfigSource::file(Some(&path), &[]);
        let args = Args { config: config.clone(), points: Some(4), omega_max: Some("400 rad/s".into()), ..Default::default() };
        let out = args.run(&Control::none()).unwrap();
        let v = out.json().unwrap();
        assert_eq!(v["model"], "linear");
        assert_eq!(v["balls"], "free");
        let cfg = crate::linear_rotor::load(&path, &[]).unwrap();
        let (rotor, _) = crate::linear_rotor::model(&cfg).unwrap();
        let states = 2 * (rotor.dofs() + rotor.total_balls());
        let want = autobal::rotor_campbell::campbell_over_speed(&autobal::rotor_stability::Rotor::Linear(rotor), &general_campbell::speeds(400.0, 4)).unwrap();
        assert_eq!(want.lines.len(), states);
        assert_eq!(v["lines"], serde_json::to_value(&want.lines).unwrap());
        assert!(!out.table().unwrap().is_empty());
        let locked = Args { config, balls: Balls::Locked, points: Some(4), ..Default::default() }.run(&Control::none()).err().expect("refused");
        assert!(format!("{locked:#}").starts_with("--balls locked"), "{locked:#}");
    }

    /// A stop (Ctrl-C, a cancelled control) during the general route's search for critical
    /// speeds, after the scan has computed every speed, keeps every speed's curves without
    /// crossings and says so (`stopped`, exit 2 from the CLI), as the 12-state route keeps what
    /// it computed (it ended with one line and printed nothing until session 23): here the
    /// control is cancelled when the scan reports its last speed, so that only the search sees
    /// the stop.
    #[test]
    fn a_stop_during_the_general_routes_search_keeps_the_curves() {
        use crate::command::Output as _;
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/linear_rotor_windows.toml");
        let flag = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let f = flag.clone();
        let control = Control::with_flag(flag).with_progress(move |p| {
            if p.done == p.total {
                f.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        });
        let args = Args { config: ConfigSource::file(Some(&path), &[]), points: Some(20), ..Default::default() };
        let out = args.run(&control).unwrap();
        let why = out.stopped().expect("stopped");
        assert!(why.starts_with("interrupted: all 20 speeds analysed, the search for critical speeds stopped (none given)"), "{why}");
        assert!(!why.contains('\n'), "one line: {why}");
        let v = out.json().unwrap();
        assert_eq!((v["complete"].clone(), v["stopped"].clone()), (serde_json::json!(false), serde_json::json!(why)));
        assert!(v["critical_speeds"].is_null() || v["critical_speeds"].as_array().is_some_and(|a| a.is_empty()), "{}", v["critical_speeds"]);
        assert!(out.table().unwrap().starts_with(&format!("INCOMPLETE ({why})\n")));
        // the same run not stopped: critical speeds, the same curves
        let whole = Args { config: ConfigSource::file(Some(&path), &[]), points: Some(20), ..Default::default() }.run(&Control::none()).unwrap();
        assert!(whole.stopped().is_none());
        let w = whole.json().unwrap();
        assert!(w.get("complete").is_none() && w["critical_speeds"].as_array().is_some_and(|a| !a.is_empty()));
        assert_eq!(v["lines"], w["lines"]);
    }

    /// A stop during the general route's scan keeps the speeds analysed (session 23: it printed
    /// nothing): their curves equal the complete run's at those speeds, `complete: false`, no
    /// crossings. Paper 004's planar rotor, stopped after 5 of 30 speeds.
    #[test]
    fn a_stop_during_the_general_routes_scan_keeps_the_speeds_analysed() {
        use crate::command::Output as _;
        let control = Control::new();
        let c = control.clone();
        let control = control.with_progress(move |p| {
            if p.done >= 5 {
                c.cancel();
            }
        });
        let planar = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar.toml");
        let args = Args { config: ConfigSource::file(Some(&planar), &[]), points: Some(30), ..Default::default() };
        let out = args.run(&control).unwrap();
        let why = out.stopped().expect("stopped");
        assert!(why.starts_with("interrupted: 5 of 30 speeds analysed; what was analysed is printed"), "{why}");
        let Output::General { c, .. } = &out else { panic!("the general route") };
        assert_eq!(c.diagram.omega.len(), 5);
        let whole = args.run(&Control::none()).unwrap();
        let Output::General { c: w, .. } = &whole else { panic!("the general route") };
        assert_eq!(c.diagram.omega[..], w.diagram.omega[..5]);
        assert!(out.json().unwrap()["complete"] == false && whole.json().unwrap().get("complete").is_none());
        assert!(out.figures().unwrap()[0].plot.title.starts_with("INCOMPLETE: ") && !whole.figures().unwrap()[0].plot.title.starts_with("INCOMPLETE"));
    }

    /// [`write_mode_json`] writes `serde_json`'s bytes: 20 000 random modes (numbers of random
    /// bits: NaN, infinities, subnormals, negative zero, integers; every group and whirl; the
    /// SI fields and the log decrement present or not), and the default diagram's modes.
    #[test]
    fn the_mode_json_is_serde_json_s() {
        use autobal::reports::{FixedModeReport, FixedPointReport, ModeReport};
        use autobal::spatial::stability::{Group, Whirl};
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut num = |k: u64| match k % 8 {
            0 => f64::from_bits(next()),
            1 => [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.0, 0.0, 5e-324, 1e300, 3.0][(next() % 8) as usize],
            2 => (next() % 2001) as f64 - 1000.0,
            _ => (f64::from_bits(next() >> 12 | 0x3ff0_0000_0000_0000) - 1.5) * 10f64.powi((next() % 40) as i32 - 20),
        };
        let check = |r: &ModeReport| {
            let mut got = vec![];
            write_mode_json(&mut got, r).unwrap();
            assert_eq!(String::from_utf8(got).unwrap(), serde_json::to_string(r).unwrap());
        };
        for i in 0..20_000u64 {
            let v: Vec<f64> = (0..14).map(|j| num(i + j)).collect();
            let si = |x: f64| (i % 3 != 0).then_some(x);
            let r = ModeReport {
                decay_rate: v[0],
                decay_rate_per_s: si(v[1]),
                fixed_frequency: v[2],
                fixed_frequency_hz: si(v[3]),
                fixed_frequency_rad_s: si(v[4]),
                fixed_frequency_rpm: si(v[5]),
                forward_share: v[6],
                group: [Group::Translation, Group::Tilt, Group::Balls][(i % 3) as usize],
                im: v[7],
                im_hz: si(v[8]),
                im_rad_s: si(v[9]),
                log_decrement: (i % 5 != 0).then_some(v[10]),
                re: v[11],
                re_per_s: si(v[12]),
                whirl: [Whirl::Forward, Whirl::Backward, Whirl::None][(i / 3 % 3) as usize],
            };
            check(&r);
        }
        // the fixed-axes curves: random points (as above), line and mode numbers up to 2^64 - 1
        let mut fixed = vec![];
        for i in 0..200u64 {
            let points = (0..i % 7)
                .map(|k| {
                    let v: Vec<f64> = (0..12).map(|j| num(i + k + j)).collect();
                    let si = |x: f64| ((i + k) % 3 != 0).then_some(x);
                    FixedPointReport {
                        fixed_frequency: v[0],
                        fixed_frequency_hz: si(v[1]),
                        frequency: v[2],
                        frequency_hz: si(v[3]),
                        log_decrement: ((i + k) % 5 != 0).then_some(v[4]),
                        nu: v[5],
                        omega: v[6],
                        omega_rpm: si(v[7]),
                        re: v[8],
                        re_per_s: si(v[9]),
                        share: v[10],
                        whirl: [Whirl::Forward, Whirl::Backward, Whirl::None][((i + k) % 3) as usize],
                    }
                })
                .collect();
            let big = [0, 9, 10, 12_345, u64::MAX][(i % 5) as usize];
            fixed.push(FixedModeReport { line: (big ^ (i % 2)) as usize, mode: i as usize, points });
        }
        for k in [0, 1, 5, fixed.len()] {
            let mut got = vec![];
            write_fixed_modes_json(&mut got, &fixed[..k]).unwrap();
            assert_eq!(String::from_utf8(got).unwrap(), serde_json::to_string(&fixed[..k]).unwrap());
        }
        // and the default diagram's, dimensionless and in SI
        for text in [crate::config::DEFAULT_CONFIG, include_str!("../../../examples/dimensional.toml")] {
            let cfg = crate::config::build(&crate::config::parse_text(text, "d").unwrap(), "d").unwrap();
            let c = autobal::spatial::stability::campbell(&cfg.model, &crate::linear::campbell_grid(3.0, 20), Balls::Free).unwrap();
            for m in c.lines.iter().flat_map(|l| &l.modes) {
                check(&autobal::reports::mode_report(&cfg.model, m));
            }
            let f = crate::linear::fixed_json(&cfg, &fixed_axes(&cfg.model, &c, Balls::Free, &[1]).unwrap());
            let mut got = vec![];
            write_fixed_modes_json(&mut got, &f.fixed_axes_modes).unwrap();
            assert_eq!(String::from_utf8(got).unwrap(), serde_json::to_string(&f.fixed_axes_modes).unwrap());
        }
    }

    /// `--points` is checked with the route's own range.
    #[test]
    fn points_are_checked_with_the_route_s_range() {
        let e = |args: Args| format!("{:#}", args.run(&Control::none()).err().expect("out of range"));
        assert_eq!(e(Args { points: Some(2), ..Default::default() }), "--points: must lie between 3 and 10000000, got 2");
        let planar = crate::config::parse_text(include_str!("../../../examples/planar.toml"), "p").unwrap();
        let general = Args { config: ConfigSource::tables(planar, "p"), points: Some(100_001), ..Default::default() };
        assert_eq!(e(general), "--points: must lie between 3 and 100000 on the general route, got 100001");
    }

    /// A periodic orbit's diagram whose every speed is below the periodic-orbit floor (the
    /// two-plane example: 0.81 rad/s) is refused in one line naming where its top speed came
    /// from (`--omega-max`, or the config's `analysis.omega_max`), as `stability` refuses it; a
    /// diagram reaching above it reads "not analysed" at the slow speeds (table and JSON).
    /// Main at e3f0650 shot a revolution at every speed (more than 60 s).
    #[test]
    fn speeds_below_the_periodic_floor_are_refused_or_not_analysed() {
        let two = include_str!("../../../examples/spatial_two_plane.toml");
        let src = |set: &[&str]| {
            let mut t = crate::config::parse_text(two, "test").unwrap();
            for s in set {
                crate::config::apply_set(&mut t, s).unwrap();
            }
            ConfigSource::tables(t, "test")
        };
        let args = Args { config: src(&[]), omega_max: Some("1e-4 rad/s".into()), points: Some(5), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(
            e.starts_with("--omega-max: 9e-5 rad/s (") && e.contains("the grid's top speed, is below 0.809787 rad/s (7.73289 rpm),") && !e.contains('\n'),
            "{e}"
        );
        let args = Args { config: src(&["analysis.omega_max=\"0.001 rad/s\""]), points: Some(5), ..Default::default() };
        let e = format!("{:#}", args.run(&Control::none()).err().expect("refused"));
        assert!(e.starts_with("analysis.omega_max: 0.0009 rad/s ("), "{e}");
        // 10 speeds to 10 rad/s (cell middles 0.5, 1.5, …): the first is below the floor
        let args = Args { config: src(&[]), omega_max: Some("10 rad/s".into()), points: Some(10), ..Default::default() };
        let out = args.run(&Control::none()).unwrap();
        let v = out.json().unwrap();
        assert_eq!((&v["analysed"][0], &v["analysed"][1]), (&serde_json::json!(false), &serde_json::json!(true)), "{}", v["analysed"]);
        let t = out.table().unwrap();
        // one speed below: named once (not "X to X"); its block says only "not analysed"
        assert!(t.contains("not analysed (below the periodic-orbit floor) at 1 of 10 speeds (0.5 rad/s (4.77465 rpm): a revolution"), "{t}");
        assert!(
            t.contains("speed 0.5 rad/s (4.77465 rpm)\n  not analysed (below the periodic-orbit floor)\n") && !t.contains("no stationary state: not analysed"),
            "{t}"
        );
    }
}
