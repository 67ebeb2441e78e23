//! `autobal`: the command-line front end. Parses the arguments and hands each subcommand to
//! `autobal-commands`, which reads the config, runs the library's analyses and writes tables,
//! JSON, figures and the HTML report.

use autobal_commands::command::{check_speed, Command as _, ConfigSource, Output, Route};
use autobal_commands::{
    basins, campbell, config, critical, inertia, linear, linear_rotor, map, outfile, parquet, ranges, report, sim, spatial_sim, stability, sweep, term,
};

use anyhow::Result;
use autobal::control::Control;
use autobal_commands::term::{emit, Format};
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Ctrl-C, installed once per process: the one flag of the [`Control`] every command of this
/// front end runs under.
mod interrupt {
    use autobal::control::Control;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, OnceLock};

    /// The flag Ctrl-C sets.
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    /// Whether the running command asks the control (else Ctrl-C ends the process at once, as
    /// without a handler).
    static POLLED: AtomicBool = AtomicBool::new(false);

    /// The control of one command line: the process's one flag, cleared, with the handler
    /// installed on first use. `polled`: whether the command's long work asks the control; a
    /// command that does not (a quick analysis) is ended by Ctrl-C at once (exit status 130),
    /// and so is any command on a second Ctrl-C.
    pub fn control(polled: bool) -> Control {
        let flag = FLAG.get_or_init(|| {
            let flag = Arc::new(AtomicBool::new(false));
            let f = flag.clone();
            let _ = ctrlc::set_handler(move || {
                if !POLLED.load(Ordering::Relaxed) || f.swap(true, Ordering::Relaxed) {
                    std::process::exit(130);
                }
            });
            flag
        });
        flag.store(false, Ordering::Relaxed);
        POLLED.store(polled, Ordering::Relaxed);
        Control::with_flag(flag.clone())
    }
}

#[derive(Parser)]
#[command(name = "autobal", version, about = "Rotors with automatic ball balancers: inertia, critical speeds, autobalancing ranges, report")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Args, Clone)]
struct Common {
    /// Config file (TOML); default: the embedded example (examples/default.toml)
    #[arg(long, short, global = true)]
    config: Option<PathBuf>,
    /// Override a config field, e.g. --set dimensionless.l_left=1.2 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE", global = true)]
    set: Vec<String>,
}

impl Common {
    /// The config a command reads (once).
    fn source(&self) -> ConfigSource {
        ConfigSource::file(self.config.as_deref(), &self.set)
    }
}

#[derive(Args, Clone)]
struct LinearArgs {
    /// Upper end of the speed axis: a speed with its unit (1500rpm, "157 rad/s", 25Hz) for a
    /// dimensional config, or a bare number, the dimensionless Ω; default: [analysis] omega_max,
    /// else automatic (1.3 × the highest critical speed, and 1.25 × the top of
    /// [analysis] operating_speed)
    #[arg(long, allow_negative_numbers = true, value_name = "SPEED")]
    omega_max: Option<String>,
    /// Balls free (12 states) or locked at balance (8 states, the bare anisotropic rotor)
    #[arg(long, value_enum, default_value = "free")]
    balls: BallsArg,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum BallsArg {
    Free,
    Locked,
}

impl From<BallsArg> for autobal::spatial::linear_model::Balls {
    fn from(b: BallsArg) -> Self {
        match b {
            BallsArg::Free => autobal::spatial::linear_model::Balls::Free,
            BallsArg::Locked => autobal::spatial::linear_model::Balls::Locked,
        }
    }
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum QuantityArg {
    Margin,
    Verdict,
}

#[derive(Subcommand)]
enum Command {
    /// Mass properties of the whole rotor with its balls at balance; 000's composite inertia (eqs (4), (5), (17)) where it applies
    Inertia {
        #[command(flatten)]
        common: Common,
        /// Output on standard output: a table to read or JSON
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
    },
    /// Critical speeds (000, eq (16)), sensitivity criterion and autobalancing ranges
    Critical {
        #[command(flatten)]
        common: Common,
        /// Output on standard output: a table to read or JSON
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
        /// `auto`: paper 000's closed forms where they represent the config, else the general
        /// route (locked critical speeds from the nonlinear equations' linearisation, exact
        /// stability ranges); `general`: the general route always
        #[arg(long, value_enum, default_value = "auto")]
        route: Route,
        /// Upper end of the general route's speed axis (a speed with its unit, or a bare Ω)
        #[arg(long, allow_negative_numbers = true, value_name = "SPEED")]
        omega_max: Option<String>,
    },
    /// Exact stable speed ranges, and 003's necessary ranges (eqs (1)-(3)) where they are defined
    Ranges {
        #[command(flatten)]
        common: Common,
        /// Output on standard output: a table to read or JSON
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
    },
    /// Exact linear stability of the balanced state (eigenvalues of 000 eq (6)) vs 003's necessary ranges
    Stability {
        #[command(flatten)]
        common: Common,
        /// Output on standard output: a table to read or JSON
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
        #[command(flatten)]
        lin: LinearArgs,
        /// Grid points along Ω before the range ends are refined by bisection (default 2000 on
        /// the closed-form route, 200 on the general route, 50 where it shoots periodic orbits)
        #[arg(long)]
        samples: Option<usize>,
        /// Also write the margin plot as SVG to this file
        #[arg(long)]
        svg: Option<PathBuf>,
        /// `auto`: paper 000's 12-state model (closed form) where it represents the config, else
        /// the general route (the nonlinear equations: planar rotor, two planes, couple,
        /// direction-dependent supports, gravity); `general`: the general route always
        #[arg(long, value_enum, default_value = "auto")]
        route: Route,
    },
    /// Campbell diagram: eigenvalues along Ω, tracked, with whirl direction and dominant motion
    Campbell {
        #[command(flatten)]
        common: Common,
        /// Output on standard output: a table to read or JSON
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
        #[command(flatten)]
        lin: LinearArgs,
        /// Number of speeds (default 300; 60 where the general route shoots periodic orbits)
        #[arg(long)]
        points: Option<usize>,
        /// Write the figure: PREFIX.svg (`--view fixed`) or PREFIX_rotating.svg and
        /// PREFIX_fixed.svg (`--view components`)
        #[arg(long, value_name = "PREFIX")]
        svg: Option<PathBuf>,
        /// Figure view: `fixed` (one natural-frequency curve per mode in fixed axes, forward
        /// solid, backward dashed, coloured by log decrement, critical speeds marked) or
        /// `components` (rotating axes, and the Ω + ν and Ω − ν components of each mode)
        #[arg(long, value_enum, default_value = "fixed")]
        view: linear::CampbellView,
        /// Excitation harmonics h whose lines h×Ω are drawn and crossed for the critical
        /// speeds, e.g. 1,2
        #[arg(long, value_delimiter = ',', default_value = "1")]
        harmonics: Vec<u32>,
        /// `auto`: paper 000's 12-state model where it represents the config, else the general
        /// route (eigenvalues, or Floquet exponents of the periodic orbit, of the nonlinear
        /// equations' exact linearisation); `general`: the general route always
        #[arg(long, value_enum, default_value = "auto")]
        route: Route,
    },
    /// Stability map over two parameters: margin heatmap with exact and necessary boundaries (SVG, PNG, CSV)
    Map {
        #[command(flatten)]
        common: Common,
        /// Horizontal axis, KEY=LO:HI:N with KEY a speed (`omega`: dimensionless Ω for a spatial
        /// config, rad/s for the planar rotor; for a dimensional config `speed_rpm`, `speed` in
        /// rad/s, `speed_hz`) or a config field (e.g. dimensionless.l_left, balancer.ball_mass)
        #[arg(long, value_name = "KEY=LO:HI:N")]
        x: String,
        /// Vertical axis, KEY=LO:HI:N
        #[arg(long, value_name = "KEY=LO:HI:N")]
        y: String,
        /// The speed when neither axis is a speed: 1400rpm, "147 rad/s", 23Hz, or a bare number Ω
        #[arg(long, allow_negative_numbers = true, value_name = "SPEED")]
        omega: Option<String>,
        /// Balls free (12 states) or locked (8 states)
        #[arg(long, value_enum, default_value = "free")]
        balls: BallsArg,
        /// `margin`: max Re λ from the eigenvalues; `verdict`: Routh–Hurwitz only (faster; the
        /// CSV's max_real_part column is then empty)
        #[arg(long, value_enum, default_value = "margin")]
        quantity: QuantityArg,
        /// Output stem: writes STEM.csv, STEM.svg, STEM.png (a folder, `DIR/`: DIR/stability-map.*)
        #[arg(long, short, default_value = "stability-map")]
        out: PathBuf,
        /// Worker threads (default: all cores)
        #[arg(long)]
        threads: Option<usize>,
        /// Also trace the stability boundary as curves (Hopf and fold continuation), draw it on
        /// the figures and write STEM_boundary.csv
        #[arg(long)]
        boundary: bool,
        /// `auto`: paper 000's 12-state model where it represents the config, else the general
        /// route (the stationary state of the nonlinear equations: planar rotor, two planes,
        /// couple, direction-dependent supports, gravity); `general`: the general route always
        #[arg(long, value_enum, default_value = "auto")]
        route: Route,
    },
    /// Simulate in time: the planar rotor of paper 004 ([planar]) or the spatial rotor of 000/003 (the analytic commands' config plus [drive])
    Simulate {
        /// Config file with [planar] or the spatial rotor's tables, plus [drive], [integration]; default: the embedded examples/planar.toml
        #[arg(long, short)]
        config: Option<PathBuf>,
        /// Override a config field, e.g. --set drive.b=-2.5 (repeatable)
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Output interval (s, or τ for a dimensionless config), read from the dense output; also the automatic method's time resolution (implicit steps ≤ 4 dt); overrides integration.dt
        #[arg(long, allow_negative_numbers = true)]
        dt: Option<f64>,
        /// CSV of samples (t, omega, x, y, amplitude, psi_1 … psi_n): `--out run.csv` writes run.csv; a
        /// name without .csv is a stem, as for sweep and map (`--out runs/m3` writes runs/m3.csv);
        /// plots go beside it as STEM_*.svg; a folder (`runs/`) gets runs/simulation.csv. Written
        /// to a temporary name and renamed when done (or stopped, with the complete rows)
        #[arg(long, short, default_value = "simulation.csv")]
        out: PathBuf,
        /// Also write the samples as Parquet, STEM.parquet beside the CSV
        #[arg(long)]
        parquet: bool,
        /// Summary format on standard output
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
        /// Run again with integration.rtol and atol divided by 10 and say whether the end state
        /// (balanced, not balanced, not settled, ...) depends on the tolerance (a start near a
        /// basin boundary, a chaotic transient); costs a second, tighter run
        #[arg(long)]
        check_tolerance: bool,
    },
    /// Many simulations over a grid of parameter paths, in parallel; summaries as CSV/JSON (--shard K/N for batch systems)
    Sweep(sweep::SweepArgs),
    /// Merge the outputs of `autobal sweep --shard K/N` into the unsharded sweep's STEM.csv/json
    Merge(sweep::MergeArgs),
    /// Write a linear rotor ([linear_rotor]) as a config plus Matrix Market files (M, C, G, K):
    /// the config's rotor (reduced if it sets linear_rotor.modes), or without --config paper
    /// 004's rotor (race centred) as a Jeffcott rotor
    ExportModel {
        #[command(flatten)]
        common: Common,
        /// Folder to write STEM.toml and STEM_{M,C,G,K}.mtx into (created if missing)
        #[arg(long, short, default_value = "model")]
        out: PathBuf,
        /// File name stem
        #[arg(long, default_value = "rotor")]
        stem: String,
    },
    /// Basins of the spatial rotor: where runs end over a grid of the first two balls' initial angles (parallel; CSV)
    Basins {
        /// Config file with the spatial rotor's tables plus [drive] (e.g. examples/spatial.toml);
        /// default: the embedded examples/default.toml, which has no [drive]
        #[arg(long, short)]
        config: Option<PathBuf>,
        /// Override a config field, e.g. --set drive.omega0=1.5 (repeatable)
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Grid points per angle (N × N runs)
        #[arg(long, default_value_t = 24)]
        n: usize,
        /// CSV of the runs' ends (a folder, `DIR/`: DIR/basins.csv); checked before the runs
        #[arg(long, short, default_value = "basins.csv")]
        out: PathBuf,
        /// Output on standard output: a table to read or JSON
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
        /// Worker threads (default: all cores)
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Write an HTML report with SVG figures to a folder: about your rotor (with --config), or
    /// the papers' reproductions (--papers, the default without --config)
    Report {
        #[command(flatten)]
        common: Common,
        /// Output folder (created if missing)
        #[arg(long, short, default_value = "autobal-report")]
        out: PathBuf,
        /// Shorter runs in time (for a quick look; the tests use it)
        #[arg(long)]
        quick: bool,
        /// The papers' reproductions (000, 003, 004) instead of a report about the config's rotor;
        /// the default when no --config is given
        #[arg(long, conflicts_with = "config")]
        papers: bool,
    },
}

impl Command {
    /// Whether the command's long work asks the [`Control`] (so Ctrl-C stops it keeping what
    /// it computed); the others end at once on Ctrl-C.
    fn polls_the_control(&self) -> bool {
        matches!(
            self,
            Command::Campbell { .. }
                | Command::Map { .. }
                | Command::Simulate { .. }
                | Command::Sweep(_)
                | Command::Merge(_)
                | Command::Basins { .. }
                | Command::Report { .. }
        )
    }
}

fn run(cli: Cli, control: &Control) -> Result<()> {
    match cli.command {
        Command::Inertia { common, format } => show(&inertia::Args { config: common.source() }.run(control)?, format),
        Command::Critical { common, format, route, omega_max } => show(&critical::Args { config: common.source(), route, omega_max }.run(control)?, format),
        Command::Ranges { common, format } => show(&ranges::Args { config: common.source() }.run(control)?, format),
        Command::Stability { common, format, lin, samples, svg, route } => {
            // the output is checked before the run
            let svg: Vec<(PathBuf, &str)> = svg.map(|p| (outfile::resolve(&p, "stability.svg"), "stability_margin")).into_iter().collect();
            check_outputs(common.config.as_deref(), "--svg", &svg)?;
            let args = stability::Args { config: common.source(), omega_max: lin.omega_max, balls: lin.balls.into(), samples, route };
            let out = args.run(control)?;
            write_figures(&out, "--svg", &svg, "not drawn for this config")?;
            show(&out, format)
        }
        Command::Campbell { common, format, lin, points, svg, view, harmonics, route } => {
            let svg = svg.map(|p| campbell::svg_files(&outfile::resolve(&p, "campbell"), view)).unwrap_or_default();
            check_outputs(common.config.as_deref(), "--svg", &svg)?;
            let args = campbell::Args {
                config: common.source(),
                omega_max: lin.omega_max,
                balls: lin.balls.into(),
                points,
                harmonics,
                view,
                route,
                json: format == Format::Json,
            };
            let out = args.run(control)?;
            write_figures(&out, "--svg", &svg, "not drawn for this config")?;
            show(&out, format)
        }
        Command::Map { common, x, y, omega, balls, quantity, out, threads, boundary, route } => {
            run_map(common, x, y, omega, balls, quantity, out, threads, boundary, route, control)
        }
        Command::Simulate { config, set, dt, out, parquet, format, check_tolerance } => {
            run_simulate(config, set, dt, out, parquet, format, check_tolerance, control)
        }
        Command::ExportModel { common, out, stem } => {
            let rotor = match common.config.as_deref() {
                // the model the commands run: reduced where the config asks for it
                Some(p) => linear_rotor::model(&linear_rotor::load(p, &common.set)?)?.0,
                None => linear_rotor::preset()?,
            };
            let paths = linear_rotor::export_model(&rotor, &out, &stem)?;
            term::print(&format!("wrote {}\n", paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))
        }
        Command::Sweep(a) => sweep::run(a, control),
        Command::Merge(a) => sweep::merge(a, control),
        Command::Basins { config, set, n, out, format, threads } => {
            set_threads(threads)?;
            // checked before the grid is computed
            let path = outfile::resolve(&out, "basins.csv");
            outfile::Outputs::new().inputs(config.as_deref()).output("--out", &path).check()?;
            let (shown, bar) = term::progress_bar(control);
            let result = basins::Args { config: ConfigSource::file(config.as_deref(), &set), n }.run(&shown);
            if let Some(b) = bar {
                b.finish_and_clear();
            }
            let mut o = result?;
            // whole or not at all (an interrupted grid keeps its complete runs, and says so)
            outfile::write_atomic("--out", &path, o.csv())?;
            o.written = Some(path);
            show(&o, format)
        }
        Command::Report { common, out, quick, papers } => {
            // the folder is created and checked before any section runs
            outfile::Outputs::new().inputs(common.config.as_deref()).output("--out", &out.join("index.html")).check()?;
            let kind = if papers || common.config.is_none() { report::Kind::Papers } else { report::Kind::User };
            let index = report::run(common.config.as_deref(), &common.set, &out, quick, kind, control)?;
            term::print(&format!("report written to {}\n", index.display()))
        }
    }
}

/// Print a command's output on stdout in `format` (the JSON streamed where the output streams
/// it); an output cut short (Ctrl-C) is then an error saying what was kept.
fn show(out: &impl Output, format: Format) -> Result<()> {
    match format {
        Format::Json => {
            use std::io::Write;
            let stdout = std::io::stdout();
            let mut lock = stdout.lock();
            out.write_json(&mut lock)?;
            lock.flush()?;
        }
        Format::Table => term::print(&out.table()?)?,
    }
    match out.stopped() {
        Some(why) => Err(anyhow::anyhow!(why)),
        None => Ok(()),
    }
}

/// Check the files a command will write (`(path, figure id)`), before it runs.
fn check_outputs(config: Option<&std::path::Path>, flag: &str, files: &[(PathBuf, &str)]) -> Result<()> {
    if files.is_empty() {
        return Ok(());
    }
    let mut o = outfile::Outputs::new();
    o.inputs(config);
    for (p, _) in files {
        o.output(flag, p);
    }
    o.check()
}

/// Write the output's figures named in `files` as SVG (`missing`: why a figure the output does
/// not have is not drawn).
fn write_figures(out: &impl Output, flag: &str, files: &[(PathBuf, &str)], missing: &str) -> Result<()> {
    if files.is_empty() {
        return Ok(());
    }
    let figures = out.figures()?;
    for (path, id) in files {
        let f = figures.iter().find(|f| f.id == *id).ok_or_else(|| anyhow::anyhow!("{flag}: {missing}"))?;
        outfile::write_atomic(flag, path, f.plot.to_svg())?;
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn run_map(
    common: Common,
    x: String,
    y: String,
    omega: Option<String>,
    balls: BallsArg,
    quantity: QuantityArg,
    out: PathBuf,
    threads: Option<usize>,
    boundary: bool,
    route: Route,
    control: &Control,
) -> Result<()> {
    // a linear rotor config takes its own --set (linear_rotor::read_set) and the general route
    let (root, source) = linear_rotor::read_set(common.config.as_deref(), &common.set)?;
    let linear = linear_rotor::is_linear(&root);
    if linear || route.is_general(&root) {
        if balls == BallsArg::Locked {
            anyhow::bail!("--balls locked: the general route maps the balls free (use the 12-state route of a one-plane config for the locked rotor)");
        }
        let verdict_only = quantity == QuantityArg::Verdict;
        if !linear {
            config::check_entries(&root, "map", &[config::simulation_model(&root)])?;
        }
        return map::run_general(&root, common.config.as_deref(), &x, &y, omega.as_deref(), verdict_only, &out, threads, boundary, control);
    }
    // the speeds need the config's ω0: it is read (and checked) first
    let cfg = config::build(&root, &source)?;
    config::check_entries(&root, "map", &[config::Model::Linear])?;
    let omega_text = omega;
    let omega = omega_text.as_deref().map(|t| linear::speed_arg(&cfg, "--omega", t)).transpose()?;
    if let Some(w) = omega {
        check_speed("--omega", w)?;
    }
    let xa = map::Axis::parse("--x", &x)?;
    let ya = map::Axis::parse("--y", &y)?;
    distinct_axes(&xa.key, Some(&ya.key))?;
    // a speed axis in SI (speed_rpm, speed, speed_hz) is converted to Ω point by point by the
    // library (autobal::spatial::map::stability_map_units); a fixed speed in SI must mean one Ω
    let is_speed = |a: &map::Axis| autobal::units::speed_path_unit(&a.key).is_some();
    for (flag, a) in [("--x", &xa), ("--y", &ya)] {
        if is_speed(a) && a.key != "omega" && !cfg.dimensional {
            anyhow::bail!("{flag} {}: a speed in SI needs a dimensional config (the rotor's ω0); this config is dimensionless: use omega=LO:HI:N (Ω)", a.key);
        }
    }
    if omega_text.as_deref().is_some_and(|t| autobal::units::parse_speed("--omega", t).is_ok_and(|s| s.is_si())) && !is_speed(&xa) && !is_speed(&ya) {
        linear::check_fixed_speed(&cfg, [(&xa.key, xa.lo, xa.hi), (&ya.key, ya.lo, ya.hi)])?;
    }
    for (flag, a) in [("--x", &xa), ("--y", &ya)] {
        if a.key == "omega" {
            check_speed(&format!("{flag} omega"), a.hi)?;
        } else if let (Some(k), Some(sc)) = (autobal::units::speed_path_unit(&a.key).and_then(|u| u.rad_s()), cfg.model.scale) {
            // the same range as Ω (at the config's ω0; a mass axis moves it a little)
            check_speed(&format!("{flag} {}", a.key), a.hi * k / sc.omega0)?;
        }
    }
    set_threads(threads)?;
    let out = term::out_stem(&outfile::resolve(&out, "stability-map"), &["csv", "svg", "png"]);
    let csv_path = term::with_suffix(&out, "csv");
    let boundary_path = PathBuf::from(format!("{}_boundary.csv", out.display()));
    let mut o = outfile::Outputs::new();
    o.inputs(common.config.as_deref());
    for p in outfile::stem_files(&out, &["csv", "svg", "png"]) {
        o.output("--out", &p);
    }
    if boundary {
        o.output("--out", &boundary_path);
    }
    o.check()?;
    // the rows go to a temporary file, renamed into place when the map ends or is interrupted
    // (complete rows only); an error removes it
    let mut w = outfile::Staged::create("--out", &csv_path)?;
    let q = if quantity == QuantityArg::Margin { map::Quantity::Margin } else { map::Quantity::Verdict };
    let progress = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let traced = if boundary {
        // the checks the map makes, before the tracing (whose messages would not name the flags)
        for (flag, a) in [("--x", &xa), ("--y", &ya)] {
            if !is_speed(a) {
                cfg.spec.clone().set(&a.key, a.lo).map_err(|e| anyhow::anyhow!("{flag}: {e}"))?;
            }
        }
        if !is_speed(&xa) && !is_speed(&ya) && omega.is_none() {
            anyhow::bail!("--omega: required when neither axis is omega (the speed at which to map)");
        }
        let t = std::time::Instant::now();
        let b = map::trace(&cfg, &xa, &ya, omega, balls.into(), control)?;
        let path = boundary_path;
        outfile::write_atomic("--out", &path, map::boundary_csv(&b, &xa.key, &ya.key))?;
        term::note(&format!(
            "boundary: {} curves, {} codimension-two points, {} characteristic polynomials, {:.3} s; wrote {}",
            b.curves.len(),
            b.codim2.len(),
            b.evaluations,
            t.elapsed().as_secs_f64(),
            path.display()
        ));
        if !b.complete {
            // nothing of the map was computed: no empty CSV left behind
            drop(w);
            anyhow::bail!(
                "interrupted while tracing the boundary: the {} curves traced are kept in {}; the map was not computed",
                b.curves.len(),
                path.display()
            );
        }
        Some(b)
    } else {
        None
    };
    let t0 = std::time::Instant::now();
    let (r, run) = map::compute(&cfg, xa, ya, omega, balls.into(), q, &mut w, progress, control)?;
    let csv_path = w.commit()?;
    let secs = t0.elapsed().as_secs_f64();
    let done = run.rows_done;
    map::write_plots(&r, &out, &format!("Stability map, balls {}", if balls == BallsArg::Free { "free" } else { "locked" }), traced.as_ref())?;
    let points = done * run.row_len;
    term::print(&format!(
        "{} rows × {} points in {:.2} s ({:.2} µs per point; {} by continuation, {} direct solves); wrote {}, {}, {}\n",
        done,
        run.row_len,
        secs,
        1e6 * secs / points.max(1) as f64,
        run.continued,
        run.direct,
        csv_path.display(),
        term::with_suffix(&out, "svg").display(),
        term::with_suffix(&out, "png").display()
    ))?;
    if done < run.rows_total {
        anyhow::bail!("interrupted: {done} of {} rows computed and kept in {}", run.rows_total, csv_path.display());
    }
    Ok(())
}

/// `simulate --out`: `file.csv` is written as given; any other name is a stem (as for sweep and
/// map), `STEM.csv`; a folder (`runs/`) gets `runs/simulation.csv`. Returns the CSV's path and
/// the stem of the files beside it.
fn csv_and_stem(out: &std::path::Path) -> (PathBuf, PathBuf) {
    let stem = term::out_stem(&outfile::resolve(out, "simulation.csv"), &["csv", "parquet", "svg"]);
    (term::with_suffix(&stem, "csv"), stem)
}

/// `simulate`'s outputs (the CSV, the Parquet file, the figures), checked before the run.
fn simulation_outputs(config: Option<&std::path::Path>, out: &std::path::Path, parquet: bool) -> Result<(PathBuf, PathBuf)> {
    let (csv, stem) = csv_and_stem(out);
    let mut o = outfile::Outputs::new();
    o.inputs(config).output("--out", &csv);
    if parquet {
        o.output("--parquet", &term::with_suffix(&stem, "parquet"));
    }
    for p in sim::plot_paths(&stem) {
        o.output("--out", &p);
    }
    o.check()?;
    Ok((csv, stem))
}

#[allow(clippy::too_many_arguments)]
fn run_simulate(
    config: Option<PathBuf>,
    set: Vec<String>,
    dt: Option<f64>,
    out: PathBuf,
    parquet: bool,
    format: Format,
    check_tolerance: bool,
    control: &Control,
) -> Result<()> {
    let (mut root, source) = config::read_with_default(config.as_deref(), config::DEFAULT_PLANAR, "embedded default (examples/planar.toml)")?;
    let linear = linear_rotor::is_linear(&root);
    for s in &set {
        if linear {
            linear_rotor::apply_set(&mut root, s)?;
        } else {
            config::apply_set(&mut root, s)?;
        }
    }
    if linear && check_tolerance {
        anyhow::bail!("--check-tolerance: not yet for a linear rotor config");
    }
    if linear {
        return run_linear_rotor_simulate(&root, config.as_deref(), dt, out, parquet, format, control);
    }
    if autobal::config::is_spatial(&root) {
        return run_spatial(&root, &source, config.as_deref(), dt, out, parquet, format, check_tolerance, control);
    }
    let mut cfg = config::build_planar(&root, &source)?;
    config::check_entries(&root, "simulate", &[config::Model::Planar])?;
    if let Some(d) = dt {
        cfg.settings.dt = d;
        cfg.settings.validate(&cfg.rotor).map_err(|e| anyhow::anyhow!("--dt: {e}"))?;
    }
    let (out, stem) = simulation_outputs(config.as_deref(), &out, parquet)?;
    let mut w = outfile::Staged::create("--out", &out)?;
    let mut table = match parquet {
        true => Some(parquet::Table::create(&term::with_suffix(&stem, "parquet"), &sim::sample_columns(cfg.rotor.n), false)?),
        false => None,
    };
    let progress = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let (summary, env, wall) = sim::run_to_csv(&cfg, &mut w, table.as_mut(), progress, control)?;
    autobal::limits::check_finite("the summary", &summary)?;
    // complete rows (also when stopped early): renamed into place
    let out = w.commit()?;
    if let Some(t) = table {
        term::note(&format!("wrote {}", t.finish()?.display()));
    }
    let plots = sim::write_plots(&cfg, &env, &stem, "Passage")?;
    let (mut json, mut table) = (sim::summary_json(&cfg, &summary, wall), sim::summary_table(&cfg, &summary, wall));
    if check_tolerance && summary.stopped.is_none() {
        let c = autobal_commands::tolerance::planar(&cfg, &summary, control)?;
        add_tolerance_check(&mut json, &mut table, &c);
    }
    emit(format, json, table)?;
    term::note(&format!(
        "wrote {} and {} plots ({})",
        out.display(),
        plots.len(),
        plots.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
    ));
    for w in &summary.warnings {
        term::note(&format!("warning: {w}"));
    }
    if let Some(st) = summary.stopped {
        anyhow::bail!("{st}: the samples up to then are kept in {}", out.display());
    }
    Ok(())
}

/// `--check-tolerance`'s result into the summary: `tolerance_check` in the JSON, a line in the
/// table.
fn add_tolerance_check(json: &mut serde_json::Value, table: &mut String, c: &autobal_commands::tolerance::Check) {
    if let Some(o) = json.as_object_mut() {
        o.insert("tolerance_check".into(), c.json());
    }
    if !table.ends_with('\n') {
        table.push('\n');
    }
    table.push_str(&c.line());
    table.push('\n');
}

#[allow(clippy::too_many_arguments)]
fn run_spatial(
    root: &toml::Table,
    source: &str,
    config: Option<&std::path::Path>,
    dt: Option<f64>,
    out: PathBuf,
    parquet: bool,
    format: Format,
    check_tolerance: bool,
    control: &Control,
) -> Result<()> {
    let mut sim = spatial_sim::build(root, source)?;
    config::check_entries(root, "simulate", &[config::Model::Spatial])?;
    if sim.default_drive {
        let (w_end, _) = sim.drive.kinematics(sim.settings.t_end);
        let unit = if sim.config.dimensional { " rad/s" } else { " (Ω)" };
        term::note(&format!(
            "note: the config has no [drive]: running up from rest at constant acceleration through the critical speeds to {}{unit} in {} revolutions (t_end = {}{}); give [drive] to choose the run",
            autobal::error::fmt_num(w_end),
            autobal::config::DEFAULT_RUN_UP_REVOLUTIONS,
            autobal::error::fmt_num(sim.settings.t_end),
            if sim.config.dimensional { " s" } else { " τ" }
        ));
    }
    if let Some(d) = dt {
        sim.settings.dt = d;
        sim.settings.validate().map_err(|e| anyhow::anyhow!("--dt: {e}"))?;
    }
    let (out, stem) = simulation_outputs(config, &out, parquet)?;
    let mut w = outfile::Staged::create("--out", &out)?;
    let mut table = match parquet {
        true => Some(parquet::Table::create(&term::with_suffix(&stem, "parquet"), &spatial_sim::columns(&sim), false)?),
        false => None,
    };
    let progress = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let (summary, kept, wall) = spatial_sim::run_to_files(&sim, &mut w, table.as_mut(), progress, control)?;
    // complete rows (also when stopped early): renamed into place
    let out = w.commit()?;
    if let Some(t) = table {
        term::note(&format!("wrote {}", t.finish()?.display()));
    }
    let plots = spatial_sim::write_plots(&sim, &kept, &stem, "Spatial rotor")?;
    let (mut json, mut table) = (spatial_sim::summary_json(&sim, &summary, wall), spatial_sim::summary_table(&sim, &summary, wall));
    if check_tolerance && summary.stopped.is_none() {
        let c = autobal_commands::tolerance::spatial(&sim, &summary, control)?;
        add_tolerance_check(&mut json, &mut table, &c);
    }
    emit(format, json, table)?;
    eprintln!("wrote {} and {} plots ({})", out.display(), plots.len(), plots.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "));
    if let Some(st) = summary.stopped {
        anyhow::bail!("{st}: the samples up to then are kept in {}", out.display());
    }
    Ok(())
}

/// `simulate` on a linear rotor config ([`linear_rotor`]).
fn run_linear_rotor_simulate(
    root: &toml::Table,
    config: Option<&std::path::Path>,
    dt: Option<f64>,
    out: PathBuf,
    parquet: bool,
    format: Format,
    control: &Control,
) -> Result<()> {
    let dir = config.and_then(|p| p.parent()).unwrap_or(std::path::Path::new("."));
    let cfg = linear_rotor::from_table(root, dir)?;
    let omega_max = linear_rotor::default_omega_max(&cfg)?;
    let setup = linear_rotor::setup(&cfg, omega_max, dt)?;
    // every output checked before the run: the CSV, the Parquet file, the figures
    let (csv, stem) = csv_and_stem(&out);
    let mut o = outfile::Outputs::new();
    o.inputs(config).output("--out", &csv);
    if parquet {
        o.output("--parquet", &term::with_suffix(&stem, "parquet"));
    }
    for p in linear_rotor::plot_paths(&stem) {
        o.output("--out", &p);
    }
    o.check()?;
    if setup.default_drive {
        term::note(&format!(
            "note: the config has no [drive]: running up from rest at constant acceleration to {} rad/s in 1000 revolutions; give [drive] to choose the run",
            autobal::error::fmt_num(omega_max)
        ));
    }
    let mut w = outfile::Staged::create("--out", &csv)?;
    let mut table = match parquet {
        true => Some(parquet::Table::create(&term::with_suffix(&stem, "parquet"), &setup.columns, false)?),
        false => None,
    };
    let run = linear_rotor::run_to_files(&setup, &mut w, table.as_mut(), control)?;
    autobal::limits::check_finite("the summary", &run.summary)?;
    // complete rows (also when stopped early): renamed into place
    let path = w.commit()?;
    if let Some(t) = table {
        term::note(&format!("wrote {}", t.finish()?.display()));
    }
    let plots = linear_rotor::write_plots(&setup, &run.kept, &stem)?;
    emit(
        format,
        linear_rotor::simulate_json(&cfg, &run.summary, &setup.reduction, run.wall),
        linear_rotor::simulate_table(&run.summary, &setup.reduction, run.wall),
    )?;
    term::note(&format!(
        "wrote {} and {} plots ({})",
        path.display(),
        plots.len(),
        plots.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
    ));
    if let Some(st) = run.summary.stopped {
        anyhow::bail!("{st}: the samples up to then are kept in {}", path.display());
    }
    Ok(())
}

/// `--threads`: the global pool's size (at least 1; default all cores).
fn set_threads(threads: Option<usize>) -> Result<()> {
    if let Some(t) = threads {
        if t == 0 {
            anyhow::bail!("--threads: must be at least 1");
        }
        rayon::ThreadPoolBuilder::new().num_threads(t).build_global().ok();
    }
    Ok(())
}

/// The two axes of a map or sweep must set different fields (else one would silently win).
fn distinct_axes(x: &str, y: Option<&str>) -> Result<()> {
    if y == Some(x) {
        anyhow::bail!("--y {x}: the same key as --x; give the second axis another field");
    }
    Ok(())
}

/// The names of the CLI's commands, in `--help`'s order (the Python module lists them from here,
/// so that its tests cover every command without a list kept by hand).
pub fn command_names() -> Vec<String> {
    use clap::CommandFactory;
    Cli::command().get_subcommands().map(|c| c.get_name().to_string()).collect()
}

/// Runs the `autobal` command line on `args` (the program name first, as `std::env::args_os`
/// gives it) and returns the process's exit code: 0 on success, 2 on an error (its one-line
/// message already on stderr), clap's own codes for `--help`, `--version` and usage errors.
/// The binary and the Python wheel's console script both call this.
pub fn main_with_args<I, T>(args: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return e.exit_code();
        }
    };
    let control = interrupt::control(cli.command.polls_the_control());
    if let Err(e) = run(cli, &control) {
        if term::is_broken_pipe(&e) {
            // the reader has what it wanted (`autobal critical | head -1`): end quietly
            return 0;
        }
        term::note(&format!("error: {}", format!("{e:#}").replace('\n', " ")));
        return 2;
    }
    0
}
