//! The figures of each command's result, for a front end that draws them itself (the Python
//! module's `.plot()`, which builds `plotly.graph_objects.Figure`s): the same [`Plot`](crate::plot::Plot)
//! descriptions the CLI writes as SVG/PNG and the report embeds as Plotly JSON, computed as the
//! CLI computes them (same routes, same defaults), returned as [`Plot::to_plotly`](crate::plot::Plot::to_plotly)'s JSON.
//!
//! - `stability`: `stability_margin` (paper 000's 12-state model, the general route where
//!   the CLI takes it: [`crate::general::needs_general_route`], or a linear rotor config's
//!   margin over speed: [`crate::linear_rotor::margin_plot`]);
//! - `campbell`: `campbell_modes` (fixed axes, one curve per mode: what `--svg` draws by
//!   default), `campbell_fixed`, `campbell_rotating` (`--view components`);
//! - `map`: `stability_map` (the command's figure on either route, with the traced boundary
//!   where `boundary` asks for it; `x`, `y` as `KEY=LO:HI:N`);
//! - `simulate`: `simulation_amplitude_omega`, `simulation_amplitude_t`, `simulation_psi_t`,
//!   `simulation_omega_t` (the plots `simulate` writes beside its CSV);
//! - `sweep`: `sweep_peak`, `sweep_final` (each run's peak and final whirl radius against the
//!   first axis, a curve per value of the other axes; `x`, `y`, `axis` as `PATH=LO:HI:N`,
//!   `shard` as `K/N`), on every rotor (planar, spatial, linear);
//! - `basins`: `basins` (the report's figure: where each run of the `n × n` grid ends;
//!   `n` defaults to the CLI's), on a spatial or linear rotor config;
//! - `report`: every figure of the HTML report, by its id ([`report_figures`]).
//!
//! The other commands draw no figure ([`COMMANDS_WITH_FIGURES`]). Every function takes the
//! [`Control`] the long computations run under (the front end's Ctrl-C).

use crate::command::{Command as _, ConfigSource, Output as _};
use crate::config;
use crate::map::Quantity;
use anyhow::{bail, Result};
use autobal::control::Control;
use autobal::spatial::linear_model::Balls;
use serde::Deserialize;
use serde_json::Value;
use toml::Table;

/// The commands whose results have figures, in the CLI's order.
pub const COMMANDS_WITH_FIGURES: &[&str] = &["stability", "campbell", "map", "simulate", "sweep", "basins", "report"];

/// A command's options that change its figures, as the CLI's flags (`None`: the CLI's default).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Options {
    /// `--omega-max` (a speed with its unit, or a bare number Ω).
    pub omega_max: Option<String>,
    /// `stability --samples`.
    pub samples: Option<usize>,
    /// `campbell --points`.
    pub points: Option<usize>,
    /// `--balls`: `free` (default) or `locked`.
    pub balls: Option<String>,
    /// `campbell --harmonics` (default `[1]`).
    pub harmonics: Option<Vec<u32>>,
    /// `map --x`, `--y` (`KEY=LO:HI:N`); `sweep --x`, `--y` (`PATH=LO:HI:N`, `PATH=V1,V2,…`).
    pub x: Option<String>,
    pub y: Option<String>,
    /// `sweep --axis` (more axes after `x` and `y`).
    pub axis: Option<Vec<String>>,
    /// `sweep --shard` (`K/N`).
    pub shard: Option<String>,
    /// `basins --n`.
    pub n: Option<usize>,
    /// `map --omega`.
    pub omega: Option<String>,
    /// `map --quantity`: `margin` (default) or `verdict`.
    pub quantity: Option<String>,
    /// `map --boundary`: also trace the stability boundary.
    pub boundary: Option<bool>,
    /// `simulate --dt`.
    pub dt: Option<f64>,
    /// `report --quick`.
    pub quick: Option<bool>,
    /// `report --papers`.
    pub papers: Option<bool>,
    /// `stability`, `campbell`, `map --route`: `auto` (default) or `general`.
    pub route: Option<String>,
}

fn route(o: &Options) -> Result<crate::command::Route> {
    match o.route.as_deref().unwrap_or("auto") {
        "auto" => Ok(crate::command::Route::Auto),
        "general" => Ok(crate::command::Route::General),
        r => bail!("route: must be \"auto\" or \"general\", got \"{r}\""),
    }
}

pub use crate::command::Figure;

fn balls(o: &Options) -> Result<Balls> {
    match o.balls.as_deref().unwrap_or("free") {
        "free" => Ok(Balls::Free),
        "locked" => Ok(Balls::Locked),
        b => bail!("balls: must be \"free\" or \"locked\", got \"{b}\""),
    }
}

/// The figures of `command` on the config `root` (`source` names it in messages), as a JSON
/// array of [`Figure::to_json`].
pub fn figures_json(command: &str, root: &Table, source: &str, o: &Options, control: &Control) -> Result<Value> {
    Ok(Value::Array(figures(command, root, source, o, control)?.iter().map(Figure::to_json).collect()))
}

/// The figures of `command` on the config `root`, computed as the CLI computes them.
pub fn figures(command: &str, root: &Table, source: &str, o: &Options, control: &Control) -> Result<Vec<Figure>> {
    match command {
        // the commands' own outputs: the figures the CLI writes, by construction
        "stability" => {
            let args = crate::stability::Args {
                config: ConfigSource::tables(root.clone(), source),
                omega_max: o.omega_max.clone(),
                balls: balls(o)?,
                samples: o.samples,
                route: route(o)?,
            };
            // every route draws its `stability_margin`, a linear rotor config's included
            let out = args.run(control)?;
            if let Some(why) = out.stopped() {
                bail!("{why}");
            }
            out.figures()
        }
        "campbell" => {
            let args = crate::campbell::Args {
                config: ConfigSource::tables(root.clone(), source),
                omega_max: o.omega_max.clone(),
                balls: balls(o)?,
                points: o.points,
                harmonics: o.harmonics.clone().unwrap_or_else(|| vec![1]),
                json: false,
                route: route(o)?,
                ..Default::default()
            };
            let out = args.run(control)?;
            if let Some(why) = out.stopped() {
                bail!("{why}");
            }
            out.figures()
        }
        "map" => {
            // the command's own output: the CLI's figure, by construction (either route, the
            // traced boundary with `boundary`)
            let (Some(x), Some(y)) = (&o.x, &o.y) else { bail!("x: required, with y (KEY=LO:HI:N, e.g. x='dimensionless.z_a=-2:2:41')") };
            let quantity = match o.quantity.as_deref().unwrap_or("margin") {
                "margin" => Quantity::Margin,
                "verdict" => Quantity::Verdict,
                q => bail!("quantity: must be \"margin\" or \"verdict\", got \"{q}\""),
            };
            let args = crate::map::Args {
                config: ConfigSource::tables(root.clone(), source),
                x: crate::map::parse_axis("--x", x)?,
                y: crate::map::parse_axis("--y", y)?,
                omega: o.omega.clone(),
                balls: balls(o)?,
                quantity,
                boundary: o.boundary.unwrap_or(false),
                route: route(o)?,
            };
            // the figure's decimated copy alone: no CSV, no cells kept
            let out = args.prepare()?.run(control, crate::map::Rows::Figure)?;
            if let Some(why) = out.stopped() {
                bail!("{why}");
            }
            out.figures()
        }
        "simulate" => {
            // the command's own figures (`simulate::Output::figures`), of a run without files
            let out = crate::simulate::Args { config: ConfigSource::tables(root.clone(), source), dt: o.dt, ..Default::default() }.run(control)?;
            if let Some(why) = out.stopped() {
                bail!("{why}");
            }
            out.figures()
        }
        "sweep" => {
            // the command's own output (its runs kept, no file): `sweep::Output::figures`
            let Some(x) = &o.x else { bail!("x: required (the first axis, e.g. x='drive.b=0.5:12.5:5')") };
            let args = crate::sweep::Args {
                config: ConfigSource::tables(root.clone(), source),
                x: crate::sweep::parse_axis("--x", x)?,
                y: o.y.as_deref().map(|y| crate::sweep::parse_axis("--y", y)).transpose()?,
                more: o.axis.iter().flatten().map(|a| crate::sweep::parse_axis("--axis", a)).collect::<Result<_>>()?,
                shard: o.shard.as_deref().map(crate::sweep::parse_shard).transpose()?,
            };
            let out = args.run(control)?;
            if let Some(why) = out.stopped() {
                bail!("{why}");
            }
            out.figures()
        }
        "basins" => {
            // the command's own output: `basins::Output::plot`, the report's figure
            let args = crate::basins::Args { config: ConfigSource::tables(root.clone(), source), n: o.n.unwrap_or(crate::basins::DEFAULT_N) };
            let out = args.run(control)?;
            if let Some(why) = out.stopped() {
                bail!("{why}");
            }
            out.figures()
        }
        "report" => {
            let kind = if o.papers.unwrap_or(false) { crate::report::Kind::Papers } else { crate::report::Kind::User };
            report_figures(root, source, o.quick.unwrap_or(false), kind, control)
        }
        c if crate_commands().contains(&c) => bail!("command: {c} draws no figure (figures: {})", COMMANDS_WITH_FIGURES.join(", ")),
        c => bail!("command: unknown command \"{c}\""),
    }
}

/// Every command of the CLI (those without figures included), for the messages.
fn crate_commands() -> &'static [&'static str] {
    &["inertia", "critical", "ranges", "stability", "campbell", "map", "simulate", "sweep", "merge", "basins", "report"]
}

/// Every figure of the HTML report on the config `root` (its sections built as `autobal
/// report` builds them, no file written), in page order.
pub fn report_figures(root: &Table, source: &str, quick: bool, kind: crate::report::Kind, control: &Control) -> Result<Vec<Figure>> {
    let spatial = if autobal::config::is_spatial(root) { Some(config::build(root, source)?) } else { None };
    let planar = if root.contains_key("planar") { Some(config::build_planar(root, source)?) } else { None };
    if spatial.is_none() && planar.is_none() {
        bail!("config: describes no rotor: give [dimensionless] or [rotor], [supports], [unbalance], [balancer] (papers 000/003), or [planar] (paper 004)");
    }
    let text = toml::to_string(root).unwrap_or_default();
    let ctx = crate::report::Ctx { kind, spatial, planar, linear: None, quick, source: source.to_string(), text, root: root.clone(), control: control.clone() };
    let list = if kind == crate::report::Kind::User { crate::report::USER_SECTIONS } else { crate::report::PAPER_SECTIONS };
    let mut out = vec![];
    for (name, build) in list {
        let Some(s) = build(&ctx).map_err(|e| e.context(format!("report section {name}")))? else { continue };
        if !s.complete {
            bail!("interrupted: report section {name} was cut short");
        }
        for f in s.figures() {
            out.push(Figure { id: f.id.clone(), plot: f.plot.clone() });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn default_root() -> Table {
        config::parse_text(config::DEFAULT_CONFIG, "default").unwrap()
    }

    #[test]
    fn stability_figure_is_the_clis_margin_plot() {
        let root = default_root();
        let f = figures("stability", &root, "default", &Options { samples: Some(100), ..Default::default() }, &Control::none()).unwrap();
        assert_eq!(f.len(), 1);
        assert_eq!(f[0].id, "stability_margin");
        // the figure of a comparison computed here, not through the command
        let cfg = config::build(&root, "default").unwrap();
        let w = crate::linear::omega_max(&cfg, None).unwrap();
        let c = crate::linear::compare(&cfg.model, w, 100, Balls::Free).unwrap();
        assert_eq!(f[0].plot.to_plotly(), crate::figures::margin_plot(&cfg.model, &c).to_plotly());
    }

    /// The map's figure from Python is the CLI's: the same description (the run that streams
    /// the CSV and the one that keeps the figure's copy alone), the traced boundary included.
    #[test]
    fn map_figure_is_the_clis() {
        let root = default_root();
        let o = Options { x: Some("dimensionless.z_a=-2:2:9".into()), y: Some("omega=0.05:4.5:7".into()), boundary: Some(true), ..Default::default() };
        let f = figures("map", &root, "default", &o, &Control::none()).unwrap();
        assert_eq!(f.len(), 1);
        assert_eq!(f[0].id, "stability_map");
        let args = crate::map::Args {
            config: ConfigSource::tables(root, "default"),
            x: crate::map::parse_axis("--x", "dimensionless.z_a=-2:2:9").unwrap(),
            y: crate::map::parse_axis("--y", "omega=0.05:4.5:7").unwrap(),
            boundary: true,
            ..Default::default()
        };
        let cli = args.prepare().unwrap().run(&Control::none(), crate::map::Rows::Csv(&mut std::io::sink())).unwrap().figures().unwrap();
        assert_eq!(f[0].plot.to_plotly(), cli[0].plot.to_plotly());
        assert!(f[0].plot.series.iter().any(|s| s.label.starts_with("traced boundary")), "the traced curves are drawn");
    }

    /// examples/spatial.toml with a short run (`t_end` τ): the tiny grids' runs.
    fn spatial_root(t_end: f64) -> Table {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/spatial.toml");
        let mut root = config::parse_text(&std::fs::read_to_string(path).unwrap(), "spatial.toml").unwrap();
        root["drive"].as_table_mut().unwrap().insert("t_end".into(), toml::Value::Float(t_end));
        root
    }

    /// The basins' figure from Python is the report's: the description the report's section
    /// draws from its runs (`basins::Output::plot`) of the same config and grid, and each
    /// cell the end of the run started at its angles (placed here independently: with n = 2
    /// the angles are 0 and π, cells 0 and 1).
    #[test]
    fn basins_figure_is_the_reports() {
        let root = spatial_root(20.0);
        let f = figures("basins", &root, "spatial.toml", &Options { n: Some(2), ..Default::default() }, &Control::none()).unwrap();
        assert_eq!(f.len(), 1);
        assert_eq!(f[0].id, "basins");
        // the report's route: the library's runs over the grid, the section's figure
        let sim = crate::spatial_sim::build(&root, "spatial.toml").unwrap();
        let cases = autobal::spatial::dynamics::basins::angle_grid(&sim.initial, &sim.drive, 2, 2);
        let ends = autobal::spatial::dynamics::basins::basins(&sim.rotor, &cases, &sim.settings, &Control::none()).unwrap().value;
        let angles: Vec<[f64; 2]> = cases.iter().map(|c| [c.initial.psi[0], c.initial.psi[1]]).collect();
        let report = crate::basins::Output { angles: angles.clone(), ends: ends.clone(), wall: 0.0, written: None, svg: None, linear: None, rtol: None }.plot();
        assert_eq!(f[0].plot.to_plotly()["data"], report.to_plotly()["data"]);
        assert_eq!(f[0].plot.title, report.title);
        let z = &f[0].plot.heatmap.as_ref().unwrap().z;
        for (a, e) in angles.iter().zip(&ends) {
            let cell = |psi: f64| usize::from(psi > 1.0);
            let want = if e.as_ref().unwrap().balanced { -1.0 } else { 1.0 };
            assert_eq!(z[cell(a[1])][cell(a[0])], want, "run at {a:?}");
        }
    }

    /// The sweep's figures from Python: a curve per value of the second axis, each point a run
    /// (the first axis' value, its summary's peak and final whirl radius, ρ_s: the factor is 1
    /// in the dimensionless example), as the sweep's JSON gives them.
    #[test]
    fn sweep_figures_points_are_the_runs() {
        let root = spatial_root(10.0);
        let o = Options { x: Some("drive.omega0=1.5,1.6".into()), y: Some("drive.t_end=5,10".into()), ..Default::default() };
        let f = figures("sweep", &root, "spatial.toml", &o, &Control::none()).unwrap();
        assert_eq!(f.iter().map(|f| f.id.as_str()).collect::<Vec<_>>(), ["sweep_peak", "sweep_final"]);
        let args = crate::sweep::Args {
            config: ConfigSource::tables(root, "spatial.toml"),
            x: crate::sweep::parse_axis("--x", "drive.omega0=1.5,1.6").unwrap(),
            y: Some(crate::sweep::parse_axis("--y", "drive.t_end=5,10").unwrap()),
            ..Default::default()
        };
        let runs = args.run(&Control::none()).unwrap().json().unwrap()["runs"].as_array().unwrap().clone();
        assert_eq!(runs.len(), 4);
        for (fig, key) in [(&f[0].plot, "peak_amplitude"), (&f[1].plot, "final_amplitude")] {
            assert_eq!(fig.series.len(), 2, "a curve per value of drive.t_end");
            assert!(fig.y_label.ends_with("(ρ_s)"), "{}", fig.y_label);
            for (k, s) in fig.series.iter().enumerate() {
                assert_eq!(s.label, format!("drive.t_end = {}", [5, 10][k]));
                let want: Vec<(f64, f64)> =
                    runs[2 * k..2 * k + 2].iter().map(|r| (r["values"][0].as_f64().unwrap(), r["summary"][key].as_f64().unwrap())).collect();
                assert_eq!(s.points, want);
            }
        }
    }

    /// A linear rotor config's `stability` figure from Python is the CLI's (`autobal stability
    /// --config FILE --svg`): the same description as the command run on the file, and as the
    /// margin plot of the linear rotor's stability computed here from the config (the same
    /// functions, so equal to the last bit). The config's matrix files lie beside it, in another
    /// folder than the working one: the tables are read with the file's folder.
    #[test]
    fn linear_rotor_stability_figure_is_the_clis() {
        let d = std::env::temp_dir().join(format!("autobal-figures-linear-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        crate::linear_rotor::export_model(&crate::linear_rotor::preset().unwrap(), (None, None), &d, "rotor").unwrap();
        let file = d.join("rotor.toml");
        let (root, _) = crate::linear_rotor::read_set(Some(&file), &[]).unwrap();
        let o = Options { samples: Some(40), ..Default::default() };
        let f = figures("stability", &root, &file.display().to_string(), &o, &Control::none()).unwrap();
        assert_eq!(f.len(), 1);
        assert_eq!(f[0].id, "stability_margin");
        let args = crate::stability::Args { config: ConfigSource::file(Some(&file), &[]), samples: Some(40), ..Default::default() };
        let cli = args.run(&Control::none()).unwrap().figures().unwrap();
        assert_eq!(f[0].plot.to_plotly(), cli[0].plot.to_plotly());
        let cfg = crate::linear_rotor::load(&file, &[]).unwrap();
        let w = crate::linear_rotor::default_omega_max(&cfg).unwrap();
        let (r, _) = crate::linear_rotor::stability(&cfg, w, 40).unwrap();
        assert_eq!(f[0].plot.to_plotly(), crate::linear_rotor::margin_plot(&r, w).to_plotly());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn commands_without_figures_say_so() {
        let e = figures("critical", &default_root(), "default", &Options::default(), &Control::none()).err().unwrap().to_string();
        assert!(e.contains("draws no figure"), "{e}");
        let e = figures("nope", &default_root(), "default", &Options::default(), &Control::none()).err().unwrap().to_string();
        assert!(e.contains("unknown command"), "{e}");
        let e = serde_json::from_str::<Options>(r#"{"sample": 3}"#).err().unwrap().to_string();
        assert!(e.contains("unknown field"), "{e}");
    }
}
