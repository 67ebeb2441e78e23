//! `autobal`: the command-line front end. Parses the arguments and hands each subcommand to
//! `autobal-commands`, which reads the config, runs the library's analyses and writes tables,
//! JSON, figures and the HTML report.

use autobal_commands::command::{Command as _, ConfigSource, Output, Route};
use autobal_commands::{
    basins, campbell, critical, export_model, inertia, linear, map, merge, outfile, parquet, ranges, report, simulate, stability, sweep, term,
};

use anyhow::Result;
use autobal::control::Control;
use autobal_commands::term::Format;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Ctrl-C, installed once per process: the one flag of the [`Control`] every command of this
/// front end runs under.
mod interrupt {
    use autobal::control::Control;
    use std::io::Write;
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
            // SIGHUP or SIGTERM ignored when the process started (`nohup autobal sweep …`
            // ignores SIGHUP) stays ignored: ctrlc's `termination` feature installs the handler
            // for SIGINT, SIGTERM and SIGHUP alike, and `nohup` then no longer protected a run
            // from `kill -HUP` or a closed terminal. SIGINT is handled whatever its disposition
            // (as before the feature).
            let ignored = ignored_at_start();
            let _ = ctrlc::set_handler(move || {
                let polled = POLLED.load(Ordering::Relaxed);
                if !polled || f.swap(true, Ordering::Relaxed) {
                    // at once: no destructor runs, so the files being written are removed here
                    // (the outputs already committed stay); always one line saying so (a
                    // command that does not poll, such as `stability`, ended silently)
                    let removed = autobal_commands::outfile::remove_unfinished() > 0;
                    let what = match (polled, removed) {
                        (_, true) => "; the unfinished output files were removed",
                        (false, false) => " (this command keeps no partial result: its outputs are written when it completes)",
                        (true, false) => "",
                    };
                    // never `eprintln!`: it panics when standard error is a closed pipe, and a
                    // panic here would end this (the handler's) thread before the exit below,
                    // leaving the process running and deaf to any further Ctrl-C
                    let _ = writeln!(std::io::stderr(), "interrupted: stopped at once{what}");
                    std::process::exit(130);
                }
            });
            ignore_again(&ignored);
            flag
        });
        flag.store(false, Ordering::Relaxed);
        POLLED.store(polled, Ordering::Relaxed);
        Control::with_flag(flag.clone())
    }

    /// The signals the `termination` handler takes over (beyond SIGINT) that this process
    /// started with ignored.
    #[cfg(unix)]
    fn ignored_at_start() -> Vec<libc::c_int> {
        [libc::SIGHUP, libc::SIGTERM]
            .into_iter()
            .filter(|&sig| {
                // SAFETY: `sigaction` with a null new action only reads the current one into
                // `old`, a zeroed plain C struct it fills
                unsafe {
                    let mut old: libc::sigaction = std::mem::zeroed();
                    libc::sigaction(sig, std::ptr::null(), &mut old) == 0 && old.sa_sigaction == libc::SIG_IGN
                }
            })
            .collect()
    }

    #[cfg(not(unix))]
    fn ignored_at_start() -> Vec<i32> {
        Vec::new()
    }

    /// `signals` set back to ignored after the handler was installed.
    #[cfg(unix)]
    fn ignore_again(signals: &[libc::c_int]) {
        for &sig in signals {
            // SAFETY: `sigaction` installs SIG_IGN (no handler function) for a valid signal
            // number, with an empty mask
            unsafe {
                let mut act: libc::sigaction = std::mem::zeroed();
                act.sa_sigaction = libc::SIG_IGN;
                libc::sigemptyset(&mut act.sa_mask);
                libc::sigaction(sig, &act, std::ptr::null_mut());
            }
        }
    }

    #[cfg(not(unix))]
    fn ignore_again(_: &[i32]) {}
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
    #[arg(long, value_name = "SPEED")]
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

/// Each subcommand's arguments are built only when it is the one run (`defer`): clap built all
/// fourteen subcommands' argument lists for any command line (`augment_subcommands`, ~15 page
/// faults a run; docs/notes/benchmarks.md, "Round 3, session 15"); `--help` and errors build
/// what they show.
#[derive(Subcommand)]
#[command(defer = true)]
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
        #[arg(long, value_name = "SPEED")]
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
        /// the closed-form route, 200 on the general route, 50 where it shoots periodic orbits;
        /// a linear rotor: 200 where its M, C, G, K are the same in every direction, under
        /// gravity too, else 50)
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
        /// Excitation harmonics h whose lines h×Ω are drawn; a critical speed is where a mode's
        /// circular whirl component (major or minor: its share is given) meets one, e.g. 1,2
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
        #[arg(long, value_name = "SPEED")]
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
    Sweep(SweepFlags),
    /// Merge the outputs of `autobal sweep --shard K/N` into the unsharded sweep's STEM.csv/json
    Merge(MergeFlags),
    /// Write a linear rotor ([linear_rotor]) as a config plus Matrix Market files (M, C, G, K,
    /// M_rot): the config's rotor (reduced if it sets linear_rotor.modes), a spatial config's
    /// rotor as its linear preset, or without --config paper 004's rotor (race centred) as a
    /// Jeffcott rotor
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
        /// CSV of the runs' ends (a folder, `DIR/`: DIR/basins.csv), and beside it the figure,
        /// STEM.svg (each run's end at its two initial angles); checked before the runs
        #[arg(long, short, default_value = "basins.csv")]
        out: PathBuf,
        /// Write no figure (STEM.svg)
        #[arg(long)]
        no_plots: bool,
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

#[derive(Args)]
struct SweepFlags {
    /// Config file: the planar rotor of paper 004 ([planar], [drive], [integration]) or the
    /// spatial rotor of papers 000/003 (the analytic commands' tables plus [drive],
    /// [integration]); default: the embedded examples/planar.toml
    #[arg(long, short)]
    config: Option<PathBuf>,
    /// Override a config field for every run, e.g. --set planar.c_psi=0.1 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// First axis (varies fastest): PATH=LO:HI:N, PATH=V1,V2,… or PATH=V (e.g. drive.b=0.5:12.5:5;
    /// for a spatial config any of its keys, e.g. balancer.ball_mass=0.01:0.05:5, drive.psi0[2]=3:4:3)
    #[arg(long, value_name = "PATH=LO:HI:N")]
    x: String,
    /// Second axis (e.g. planar.c_psi=0.01:0.4:4)
    #[arg(long, value_name = "PATH=LO:HI:N")]
    y: Option<String>,
    /// More axes after x and y (repeatable), e.g. --axis 'drive.psi0[1]=0:3:4'
    #[arg(long = "axis", value_name = "PATH=LO:HI:N")]
    axes: Vec<String>,
    /// Run only shard K of N (1 ≤ K ≤ N): a contiguous part of the grid's points; merge the
    /// shards' outputs with `autobal merge`
    #[arg(long, value_name = "K/N")]
    shard: Option<String>,
    /// Output stem: STEM.csv (one row per run, written as runs finish, to a temporary name
    /// renamed when done or stopped), STEM.json and the figures STEM_peak.svg and
    /// STEM_final.svg (each run's peak and final whirl radius against the first axis, a curve
    /// per value of the other axes); a folder (`DIR/`): DIR/sweep.*
    #[arg(long, short, default_value = "sweep")]
    out: PathBuf,
    /// Write no figures (STEM_peak.svg, STEM_final.svg)
    #[arg(long)]
    no_plots: bool,
    /// Also write the rows as Parquet, STEM.parquet (row groups written as runs finish)
    #[arg(long)]
    parquet: bool,
    /// Output on standard output: a table to read or JSON
    #[arg(long, value_enum, default_value = "table")]
    format: Format,
    /// Worker threads (default: all cores)
    #[arg(long)]
    threads: Option<usize>,
}

#[derive(Args)]
struct MergeFlags {
    /// The shards' CSV files (each with its STEM.json beside it), in any order
    #[arg(required = true, value_name = "SHARD.csv")]
    shards: Vec<PathBuf>,
    /// Output stem: STEM.csv, STEM.json and the figures STEM_peak.svg and STEM_final.svg, as
    /// the unsharded sweep writes them (a folder, `DIR/`: DIR/sweep.*); written only when every
    /// shard checks out
    #[arg(long, short)]
    out: PathBuf,
    /// Also write STEM.parquet, as `autobal sweep --parquet` does
    #[arg(long)]
    parquet: bool,
}

impl Command {
    /// Whether the command's long work asks the [`Control`] (so Ctrl-C stops it keeping what
    /// it computed); the others end at once on Ctrl-C. `stability` is among them on every
    /// route (session 23: the closed-form and general routes printed nothing when stopped, and
    /// ended at once).
    fn polls_the_control(&self) -> bool {
        matches!(
            self,
            Command::Stability { .. }
                | Command::Campbell { .. }
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
            svg.iter().try_for_each(|(p, _)| outfile::check_svg_name("--svg", p, false))?;
            check_outputs(&common.source(), "--svg", &svg)?;
            let args = stability::Args { config: common.source(), omega_max: lin.omega_max, balls: lin.balls.into(), samples, route };
            // every route's scan asks the control and keeps what it analysed (audit 21's F2:
            // three balls on a 28-DOF rotor took minutes with no sign of life): Ctrl-C stops it
            // there, and the speeds (then the family's speeds) done are shown on standard error
            // when it is a terminal
            let (shown, bar) = term::progress_bar(control);
            let result = args.run(&shown);
            if let Some(b) = bar {
                b.finish_and_clear();
            }
            let out = result?;
            write_figures(&out, "--svg", &svg, "not drawn for this config")?;
            show(&out, format)
        }
        Command::Campbell { common, format, lin, points, svg, view, harmonics, route } => {
            if let Some(p) = &svg {
                outfile::check_svg_name("--svg", &outfile::resolve(p, "campbell"), true)?;
            }
            let svg = svg.map(|p| campbell::svg_files(&outfile::resolve(&p, "campbell"), view)).unwrap_or_default();
            check_outputs(&common.source(), "--svg", &svg)?;
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
            let args = map::Args {
                config: common.source(),
                x: map::parse_axis("--x", &x)?,
                y: map::parse_axis("--y", &y)?,
                omega,
                balls: balls.into(),
                quantity: match quantity {
                    QuantityArg::Margin => map::Quantity::Margin,
                    QuantityArg::Verdict => map::Quantity::Verdict,
                },
                boundary,
                route,
            };
            run_map(&args, &out, threads, control)
        }
        Command::Simulate { config, set, dt, out, parquet, format, check_tolerance } => {
            let files = Some(simulate::Files { out, parquet });
            run_simulate(&simulate::Args { config: ConfigSource::file(config.as_deref(), &set), dt, check_tolerance, files, columns: false }, format, control)
        }
        Command::ExportModel { common, out, stem } => show(&export_model::Args { config: common.source(), out, stem }.run(control)?, Format::Table),
        Command::Sweep(a) => run_sweep(a, control),
        Command::Merge(a) => {
            let out = merge::Args { shards: a.shards, out: a.out, parquet: a.parquet }.run(control)?;
            if let Some(p) = &out.parquet {
                term::note(&format!("wrote {}", p.display()));
            }
            show(&out, Format::Table)
        }
        Command::Basins { config, set, n, out, format, threads, no_plots } => {
            set_threads(threads)?;
            // checked before the grid is computed
            let path = outfile::resolve(&out, "basins.csv");
            let svg = (!no_plots).then(|| basins::figure_path(&path));
            let mut files = outfile::Outputs::new();
            files.source_inputs(&ConfigSource::file(config.as_deref(), &set)).output("--out", &path);
            if let Some(p) = &svg {
                files.output("--out", p);
            }
            files.check()?;
            let (shown, bar) = term::progress_bar(control);
            let result = basins::Args { config: ConfigSource::file(config.as_deref(), &set), n }.run(&shown);
            if let Some(b) = bar {
                b.finish_and_clear();
            }
            let mut o = result?;
            // whole or not at all (an interrupted grid keeps its complete runs, and says so; its
            // figure draws the runs not done grey)
            outfile::write_atomic("--out", &path, o.csv())?;
            o.written = Some(path);
            if let Some(p) = svg {
                outfile::write_atomic("--out", &p, o.plot().to_svg())?;
                o.svg = Some(p);
            }
            show(&o, format)
        }
        Command::Report { common, out, quick, papers } => {
            // the folder is created and checked before any section runs (report::Args::run);
            // an interrupted report is still written, and says so
            show(&report::Args { config: common.source(), out, quick, papers }.run(control)?, Format::Table)
        }
    }
}

/// Print a command's output on stdout in `format` (the JSON streamed where the output streams
/// it); an output cut short (Ctrl-C) is then an error saying what was kept.
fn show(out: &impl Output, format: Format) -> Result<()> {
    let printed = match format {
        Format::Json => (|| {
            use std::io::Write;
            let stdout = std::io::stdout();
            let mut lock = stdout.lock();
            out.write_json(&mut lock)?;
            lock.flush()?;
            Ok(())
        })(),
        Format::Table => out.table().and_then(|t| term::print(&t)),
    };
    stopped_after(printed, out.stopped())
}

/// What a command that printed its output (`printed`) ends with: a run cut short (`stopped`,
/// Ctrl-C) is an error saying what was kept even when standard output was closed (`autobal
/// sweep … | head -c0`: the broken pipe ended it quietly with status 0, the partial result
/// passed on as complete); otherwise the printing's own outcome (a broken pipe: `main` ends
/// quietly).
fn stopped_after(printed: Result<()>, stopped: Option<String>) -> Result<()> {
    match (printed, stopped) {
        (Err(e), _) if !term::is_broken_pipe(&e) => Err(e),
        (_, Some(why)) => Err(anyhow::anyhow!(why)),
        (printed, None) => printed,
    }
}

/// Check the files a command will write (`(path, figure id)`), before it runs.
fn check_outputs(config: &ConfigSource, flag: &str, files: &[(PathBuf, &str)]) -> Result<()> {
    if files.is_empty() {
        return Ok(());
    }
    let mut o = outfile::Outputs::new();
    o.source_inputs(config);
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

/// `sweep`: the arguments, config and grid checked, then the outputs (`STEM.csv`, `STEM.json`,
/// `STEM.parquet`, the figures `STEM_peak.svg` and `STEM_final.svg` unless `--no-plots`), then
/// the runs streamed to the CSV (renamed into place when the sweep ends or is interrupted:
/// complete rows, with its JSON; an error removes it) and each run's JSON to a scratch file
/// ([`sweep::Spill`]), the figures of the runs finished written, the JSON streamed from the
/// scratch file to `STEM.json`, the table (its first rows) or the JSON (streamed from
/// `STEM.json`) printed: memory flat in the points (the figures keep at most
/// [`sweep::FIGURE_POINTS`] runs' points).
fn run_sweep(a: SweepFlags, control: &Control) -> Result<()> {
    let args = sweep::Args {
        config: ConfigSource::file(a.config.as_deref(), &a.set),
        x: sweep::parse_axis("--x", &a.x)?,
        y: a.y.as_deref().map(|y| sweep::parse_axis("--y", y)).transpose()?,
        more: a.axes.iter().map(|s| sweep::parse_axis("--axis", s)).collect::<Result<_>>()?,
        shard: a.shard.as_deref().map(sweep::parse_shard).transpose()?,
    };
    let plan = if a.no_plots { args.prepare()?.without_figures() } else { args.prepare()? };
    set_threads(a.threads)?;
    let given = outfile::resolve(&a.out, "sweep");
    let stem = term::out_stem(&given, &["csv", "json", "parquet"]);
    let (csv_path, json_path, pq_path) = (term::with_suffix(&stem, "csv"), term::with_suffix(&stem, "json"), term::with_suffix(&stem, "parquet"));
    let svg = if a.no_plots { vec![] } else { sweep::figure_paths(&stem) };
    let mut o = outfile::Outputs::new();
    o.source_inputs(&args.config).stem("--out", &given, &stem).output("--out", &csv_path).output("--out", &json_path);
    if a.parquet {
        o.output("--parquet", &pq_path);
    }
    for (p, _) in &svg {
        o.output("--out", p);
    }
    o.check()?;
    let mut csv = outfile::Staged::create("--out", &csv_path)?;
    let mut pq = match a.parquet {
        true => Some(parquet::Table::create(&pq_path, &plan.columns(), true)?),
        false => None,
    };
    let mut spill = sweep::Spill::create(&json_path)?;
    let (shown, bar) = term::progress_bar(control);
    let result = plan.run(&shown, sweep::Rows::Files { csv: &mut csv, parquet: pq.as_mut(), runs: Some(&mut spill) });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let mut out = result?;
    out.written = Some(stem);
    for n in out.notes() {
        term::note(&n);
    }
    csv.commit()?;
    if let Some(t) = pq {
        term::note(&format!("wrote {}", t.finish()?.display()));
    }
    // the figures of the runs finished (none without runs, or past sweep::FIGURE_POINTS)
    let figures = out.figures()?;
    let mut drawn = vec![];
    for (path, id) in &svg {
        if let Some(f) = figures.iter().find(|f| f.id == *id) {
            outfile::write_atomic("--out", path, f.plot.to_svg())?;
            drawn.push(path.display().to_string());
        }
    }
    if !drawn.is_empty() {
        term::note(&format!("wrote {}", drawn.join(" and ")));
    }
    let mut json = outfile::Staged::create("--out", &json_path)?;
    out.write_report(&mut json, Some(&mut spill.reader()?)).map_err(|e| anyhow::anyhow!("--out: cannot write {}: {e:#}", json_path.display()))?;
    json.commit()?;
    drop(spill);
    if let Format::Json = a.format {
        let printed = (|| {
            use std::io::Write;
            let stdout = std::io::stdout();
            let mut lock = stdout.lock();
            std::io::copy(&mut std::fs::File::open(&json_path)?, &mut lock)?;
            lock.flush()?;
            Ok(())
        })();
        return stopped_after(printed, out.stopped());
    }
    show(&out, a.format)
}

/// `map`: the arguments and config checked, then the outputs (`STEM.csv`, `.svg`, `.png`,
/// `STEM_boundary.csv`), then the rows streamed to the CSV (renamed into place when the map
/// ends or is interrupted: complete rows only; an error removes it), the figure and the
/// boundary written, the summary line printed.
fn run_map(args: &map::Args, out: &std::path::Path, threads: Option<usize>, control: &Control) -> Result<()> {
    let plan = args.prepare()?;
    let own = OWN_PROCESS.load(std::sync::atomic::Ordering::Relaxed);
    if own {
        keep_freed_memory();
    }
    if threads == Some(1) && own {
        // one thread: this one. A pool of one worker would run all the map's work on a second
        // thread (its own stack and malloc arena: a quarter of the command's page faults) while
        // this one waits; registered as the pool's only worker, this thread runs the parallel
        // loops itself. Only in the binary's own process: a host calling `main_with_args` (the
        // Python extension) may use the global pool from other threads later, whose jobs no
        // worker would then take.
        rayon::ThreadPoolBuilder::new().num_threads(1).use_current_thread().build_global().ok();
    }
    set_threads(threads)?;
    let given = outfile::resolve(out, "stability-map");
    let stem = term::out_stem(&given, &["csv", "svg", "png"]);
    let mut o = outfile::Outputs::new();
    o.source_inputs(&args.config).stem("--out", &given, &stem);
    for p in outfile::stem_files(&stem, &["csv", "svg", "png"]) {
        o.output("--out", &p);
    }
    if args.boundary {
        o.output("--out", &map::boundary_path(&stem));
    }
    o.check()?;
    let csv = term::with_suffix(&stem, "csv");
    let mut w = outfile::Staged::create("--out", &csv)?;
    let (shown, bar) = term::progress_bar(control);
    // a write of the rows that failed (a full disk) said only "No space left on device"
    let result = plan.run(&shown, map::Rows::Csv(&mut w)).map_err(|e| match e.downcast::<std::io::Error>() {
        Ok(io) => anyhow::anyhow!("--out: cannot write {}: {io}", csv.display()),
        Err(e) => e,
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let mut out = result?;
    out.written = Some(stem.clone());
    if let Some(text) = out.boundary_csv() {
        outfile::write_atomic("--out", &map::boundary_path(&stem), text)?;
    }
    if out.map_computed() {
        w.commit()?;
        let figures = out.figures()?;
        out.release_figure_cells();
        for f in figures {
            // the heatmap's cell colours computed once for both files
            let (svg, png) = f.plot.to_svg_and_png(1.5);
            outfile::write_atomic("--out", &term::with_suffix(&stem, "png"), png?)?;
            outfile::write_atomic("--out", &term::with_suffix(&stem, "svg"), svg)?;
        }
    } else {
        // nothing of the map was computed: no empty CSV left behind
        drop(w);
    }
    for n in out.notes() {
        term::note(&n);
    }
    show(&out, Format::Table)
}

/// glibc's allocator told to keep what the map frees for its next allocations: blocks up to
/// 32 MiB from the heap (not each its own fresh mapping) and the heap's free top not returned to
/// the system. A map frees the library's blocks of lines and its CSV texts before it allocates
/// the figure's 3.8 MB pixmap and the PNG's buffers, which then reuse pages already touched
/// instead of faulting in new ones: -25 % page faults for a 400 x 400 verdict map, the same
/// instructions (docs/notes/benchmarks.md). Only in the binary's own process (a host's
/// allocator is its own business) and only for `map` (`simulate` sets the trim threshold alone,
/// [`keep_heap_top`]).
fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` sets two of glibc's tuning parameters (32 MiB is its largest mmap
    // threshold), with no pointer arguments; glibc takes its arena lock in `mallopt`, so other
    // threads (the Ctrl-C watcher) may run meanwhile. Called before the map's work.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 256 << 20);
    }
}

/// glibc's allocator told not to give the heap's free top back to the system (only that: the
/// mmap threshold stays glibc's own). `simulate` frees its config, its plan and the run's
/// batches before it draws the figures; with the default 128 kB trim threshold glibc returned
/// that top to the system and the figures' buffers faulted fresh pages in again: 392 -> 345
/// page faults for paper 004's passage, the same instructions (docs/notes/benchmarks.md, "Round
/// 3, session 15"). Only in the binary's own process, as [`keep_freed_memory`].
fn keep_heap_top() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` sets one of glibc's tuning parameters, with no pointer arguments;
    // glibc takes its arena lock in `mallopt`. Called before the run's work.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, 256 << 20);
    }
}

/// `simulate`: the run planned (the config read, every option and output checked), its notes,
/// the run under a progress bar, the result, the files written; a run stopped early (Ctrl-C)
/// keeps its rows and is then an error naming the CSV.
fn run_simulate(args: &simulate::Args, format: Format, control: &Control) -> Result<()> {
    if OWN_PROCESS.load(std::sync::atomic::Ordering::Relaxed) {
        keep_heap_top();
    }
    let plan = args.plan()?;
    for n in plan.notes() {
        term::note(n);
    }
    let (shown, bar) = term::progress_bar(control);
    let out = plan.run(&shown);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let out = out?;
    let shown = show(&out, format);
    // the table prints the run's warnings itself: on stderr only beside JSON
    for n in out.notes().iter().filter(|n| format != Format::Table || !n.starts_with("warning: ")) {
        term::note(n);
    }
    shown
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

/// The names of the CLI's commands, in `--help`'s order (the Python module lists them from here,
/// so that its tests cover every command without a list kept by hand).
pub fn command_names() -> Vec<String> {
    use clap::CommandFactory;
    Cli::command().get_subcommands().map(|c| c.get_name().to_string()).collect()
}

/// Whether this process is the `autobal` binary ([`main_process`]), not a host running the
/// command line in its own process (the Python extension's `cli_main`).
static OWN_PROCESS: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// [`main_with_args`] as the `autobal` binary's `main` runs it: the process is the command's
/// own, so `map --threads 1` may make the main thread the global pool's only worker.
pub fn main_process<I, T>(args: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    OWN_PROCESS.store(true, std::sync::atomic::Ordering::Relaxed);
    main_with_args(args)
}

/// The speed flags whose value may be negative (refused as a speed, with its reason).
const SPEED_FLAGS: &[&str] = &["--omega-max", "--omega"];

/// `args` with a speed flag followed by a negative speed (`--omega-max "-5 rpm"`, `--omega
/// -.5`: `-` then a digit or `.`) joined into one `--omega-max=-5 rpm`, so that clap takes it
/// as the value; any other word after the flag is left to clap (`--omega-max --samples 10`:
/// "a value is required", where accepting every hyphen value took `--samples` as the speed and
/// then refused `10` as an unexpected argument).
fn negative_speeds_joined<I, T>(args: I) -> Vec<std::ffi::OsString>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut out: Vec<std::ffi::OsString> = Vec::new();
    let mut it = args.into_iter().map(Into::into).peekable();
    while let Some(a) = it.next() {
        if a == "--" {
            out.push(a);
            out.extend(it);
            break;
        }
        let negative = |v: &std::ffi::OsString| {
            let b = v.as_encoded_bytes();
            b.len() >= 2 && b[0] == b'-' && (b[1].is_ascii_digit() || b[1] == b'.')
        };
        match (a.to_str(), it.peek()) {
            (Some(flag), Some(v)) if SPEED_FLAGS.contains(&flag) && negative(v) => {
                let mut joined = a.clone();
                joined.push("=");
                joined.push(it.next().unwrap());
                out.push(joined);
            }
            _ => out.push(a),
        }
    }
    out
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
    let cli = match Cli::try_parse_from(negative_speeds_joined(args)) {
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
