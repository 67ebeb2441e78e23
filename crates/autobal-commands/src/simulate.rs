//! `autobal simulate`: a run in time of the config's rotor, by its kind: paper 004's planar rotor
//! (`[planar]`, [`crate::sim`]), the spatial rotor of papers 000/003 (the analytic commands'
//! tables plus `[drive]`, [`crate::spatial_sim`]) or a linear rotor (`[linear_rotor]`,
//! [`crate::linear_rotor`]); with `--check-tolerance`, the run again at a tenth of its
//! tolerances ([`crate::tolerance`]).
//!
//! The samples go, as they come, to the CSV and Parquet files of [`Files`] (the CLI: written
//! under a temporary name and renamed when the run ends, also when it is stopped, with the
//! complete rows; [`crate::outfile`]) and/or into columns in memory (Python's arrays); the
//! figures (the decimated samples) are written beside the CSV. [`Args::plan`] reads the config
//! and checks every option and output before any work (the CLI prints [`Plan::notes`] then),
//! [`Plan::run`] runs.

use crate::command::{self, ConfigSource, Figure};
use crate::config::{self, PlanarConfig};
use crate::linear_rotor::{self, RunOutput, RunSetup};
use crate::outfile;
use crate::sim::{self, Envelope, RowSink};
use crate::spatial_sim::{self, SpatialSim};
use crate::term;
use crate::tolerance::{self, Check};
use anyhow::{bail, Result};
use autobal::control::Control;
use autobal::linear_rotor::config::LinearRotorConfig;
use serde_json::Value;
use std::path::PathBuf;
use toml::Table;

/// The name of the embedded default config (examples/planar.toml), read without `--config`.
pub const DEFAULT_NAME: &str = "embedded default (examples/planar.toml)";

/// `autobal simulate`'s arguments.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The config (`File` without a path: the embedded examples/planar.toml).
    pub config: ConfigSource,
    /// `--dt`: the output interval (s, or τ for a dimensionless config), overriding
    /// `integration.dt`.
    pub dt: Option<f64>,
    /// `--check-tolerance`: run again at a tenth of the tolerances and say whether the end
    /// state depends on them.
    pub check_tolerance: bool,
    /// Where the samples and figures are written (`None`: no file, Python).
    pub files: Option<Files>,
    /// Keep every sample in [`Output::columns`] (Python's arrays).
    pub columns: bool,
}

/// `simulate`'s files: the CSV of the samples, the Parquet file, the figures beside them.
#[derive(Debug, Clone)]
pub struct Files {
    /// `--out`: `file.csv` is written as given; any other name is a stem (as for sweep and
    /// map), `STEM.csv`; a folder (`runs/`) gets `runs/simulation.csv`.
    pub out: PathBuf,
    /// `--parquet`: the samples also as `STEM.parquet`.
    pub parquet: bool,
}

impl Files {
    /// The CSV's path and the stem of the files beside it (`STEM.parquet`, `STEM_*.svg`).
    pub fn csv_and_stem(&self) -> (PathBuf, PathBuf) {
        let stem = term::out_stem(&outfile::resolve(&self.out, "simulation.csv"), &["csv", "parquet", "svg"]);
        (term::with_suffix(&stem, "csv"), stem)
    }
}

/// The model a config runs.
enum Model {
    Planar(Box<PlanarConfig>),
    Spatial(Box<SpatialSim>),
    Linear(Box<LinearRotorConfig>, Box<RunSetup>),
}

/// The checked paths of [`Files`].
struct Paths {
    csv: PathBuf,
    stem: PathBuf,
    parquet: Option<PathBuf>,
    /// The CSV's staged file, created by the check (its folder's probe), taken by the run.
    staged: Option<outfile::Staged>,
}

/// A run ready to start: the config read and converted, `--dt` applied, every output checked.
pub struct Plan {
    model: Model,
    paths: Option<Paths>,
    check_tolerance: bool,
    columns: bool,
    notes: Vec<String>,
}

impl Args {
    /// The config's tables (without `--config`: the embedded examples/planar.toml) with `--set`
    /// applied, a linear rotor config's own way ([`linear_rotor::apply_set`]).
    fn read(&self) -> Result<(Table, String)> {
        match &self.config {
            ConfigSource::File { path, sets } => {
                config::check_repeated_sets(sets)?;
                let (mut root, source) = config::read_with_default(path.as_deref(), config::DEFAULT_PLANAR, DEFAULT_NAME)?;
                let linear = linear_rotor::is_linear(&root);
                for s in sets {
                    if linear {
                        linear_rotor::apply_set(&mut root, s)?;
                    } else {
                        config::apply_set(&mut root, s)?;
                    }
                }
                Ok((root, source))
            }
            ConfigSource::Tables { .. } => self.config.read(),
        }
    }

    /// Read the config, pick the model, apply `--dt`, check every output file: everything
    /// before the run, whose errors come before any work.
    pub fn plan(&self) -> Result<Plan> {
        let (root, source) = self.read()?;
        let linear = linear_rotor::is_linear(&root);
        if linear && self.check_tolerance {
            bail!("--check-tolerance: not yet for a linear rotor config");
        }
        let dt_error = |e: autobal::Error| autobal::Error::invalid("--dt", e.to_string());
        let mut notes = vec![];
        let model = if linear {
            let cfg = linear_rotor::from_table(&root, self.config.dir())?;
            let omega_max = linear_rotor::default_omega_max(&cfg)?;
            let setup = linear_rotor::setup(&cfg, omega_max, self.dt)?;
            if setup.default_drive {
                notes.push(format!(
                    "note: the config has no [drive]: running up from rest at constant acceleration to {} rad/s in 1000 revolutions; give [drive] to choose the run",
                    autobal::error::fmt_num(omega_max)
                ));
            }
            Model::Linear(Box::new(cfg), Box::new(setup))
        } else if autobal::config::is_spatial(&root) {
            let mut sim = spatial_sim::build(&root, &source)?;
            config::check_entries_with(&root, "simulate", &[config::Model::Spatial], config::FromLinear::RunUp)?;
            if sim.default_drive {
                let (w_end, _) = sim.drive.kinematics(sim.settings.t_end);
                let unit = if sim.config.dimensional { " rad/s" } else { " (Ω)" };
                notes.push(format!(
                    "note: the config has no [drive]: running up from rest at constant acceleration through the critical speeds to {}{unit} in {} revolutions (t_end = {}{}); give [drive] to choose the run",
                    autobal::error::fmt_num(w_end),
                    autobal::config::DEFAULT_RUN_UP_REVOLUTIONS,
                    autobal::error::fmt_num(sim.settings.t_end),
                    if sim.config.dimensional { " s" } else { " τ" }
                ));
            }
            if let Some(d) = self.dt {
                sim.settings.dt = d;
                sim.settings.validate().map_err(dt_error)?;
            }
            Model::Spatial(Box::new(sim))
        } else {
            let mut cfg = config::build_planar(&root, &source)?;
            config::check_entries(&root, "simulate", &[config::Model::Planar])?;
            if let Some(d) = self.dt {
                cfg.settings.dt = d;
                cfg.settings.validate(&cfg.rotor).map_err(dt_error)?;
            }
            Model::Planar(Box::new(cfg))
        };
        let paths = match &self.files {
            None => None,
            Some(f) => {
                let (csv, stem) = f.csv_and_stem();
                let parquet = f.parquet.then(|| term::with_suffix(&stem, "parquet"));
                let mut o = outfile::Outputs::new();
                // the config and the files it names (as overridden: a linear rotor's matrices)
                o.config_inputs(self.config.path(), Some((&root, self.config.dir())))
                    .stem("--out", &outfile::resolve(&f.out, "simulation.csv"), &stem)
                    .output("--out", &csv);
                if let Some(p) = &parquet {
                    o.output("--parquet", p);
                }
                for p in sim::plot_paths(&stem) {
                    o.output("--out", &p);
                }
                // the CSV's staged file, created now, is its folder's probe
                let staged = o.check_and_stage_first()?;
                Some(Paths { csv, stem, parquet, staged: Some(staged) })
            }
        };
        Ok(Plan { model, paths, check_tolerance: self.check_tolerance, columns: self.columns, notes })
    }
}

impl Plan {
    /// What the front end says before the run (the default run-up of a config without
    /// `[drive]`).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The sample columns of the run, in the CSV's order.
    pub fn column_names(&self) -> Vec<String> {
        match &self.model {
            Model::Planar(cfg) => sim::sample_columns(cfg.rotor.n),
            Model::Spatial(s) => spatial_sim::columns(s),
            Model::Linear(_, setup) => setup.columns.clone(),
        }
    }

    /// Run: the samples into the files and columns as they come, then the figures; the run again
    /// at tighter tolerances where asked (and the first ended). A run stopped early (Ctrl-C, a
    /// budget) keeps its complete rows and says so in [`command::Output::stopped`].
    pub fn run(mut self, control: &Control) -> Result<Output> {
        let names = self.column_names();
        let mut staged = match self.paths.as_mut() {
            Some(p) => Some(match p.staged.take() {
                Some(s) => s,
                None => outfile::Staged::create("--out", &p.csv)?,
            }),
            None => None,
        };
        let mut table = match self.paths.as_ref().and_then(|p| p.parquet.as_ref()) {
            Some(p) => Some(crate::parquet::Table::create(p, &names, false)?),
            None => None,
        };
        let mut columns: Option<Vec<Vec<f64>>> = self.columns.then(|| vec![vec![]; names.len()]);
        let mut sink = RowSink::new(staged.as_mut().map(|w| w as &mut (dyn std::io::Write + Send)), table.as_mut(), columns.as_mut());
        sink.header(&names)?;
        let cannot_write = |e: anyhow::Error| anyhow::anyhow!("--out: cannot write: {e:#}");
        let run = match self.model {
            Model::Planar(cfg) => {
                let (summary, env, wall) = sim::run_rows(&cfg, &mut |r| sink.push(r), control)?;
                sink.finish().map_err(cannot_write)?;
                autobal::limits::check_finite("the summary", &summary)?;
                Run::Planar { cfg, summary: Box::new(summary), env: Box::new(env), wall }
            }
            Model::Spatial(s) => {
                let (summary, kept, wall) = spatial_sim::run_rows(&s, &mut |r| sink.push(r), control)?;
                sink.finish().map_err(cannot_write)?;
                Run::Spatial { sim: s, summary: Box::new(summary), kept, wall }
            }
            Model::Linear(cfg, setup) => {
                let run = linear_rotor::run(&setup, control, |r| sink.push(r).map_err(cannot_write))?;
                sink.finish().map_err(cannot_write)?;
                autobal::limits::check_finite("the summary", &run.summary)?;
                Run::Linear { cfg, setup, run: Box::new(run) }
            }
        };
        drop(sink);
        // complete rows (also when stopped early): renamed into place
        let written = match (staged, self.paths) {
            (Some(w), Some(p)) => {
                let csv = w.commit()?;
                let parquet = table.map(|t| t.finish()).transpose()?;
                let plots = match &run {
                    Run::Planar { cfg, env, .. } => sim::write_plots(cfg, env, &p.stem, "Passage")?,
                    Run::Spatial { sim, kept, .. } => spatial_sim::write_plots(sim, kept, &p.stem, "Spatial rotor")?,
                    Run::Linear { setup, run, .. } => linear_rotor::write_plots(setup, &run.kept, &p.stem)?,
                };
                Some(Written { csv, parquet, plots })
            }
            _ => None,
        };
        let tolerance = match &run {
            _ if !self.check_tolerance || run.stopped().is_some() => None,
            Run::Planar { cfg, summary, .. } => Some(tolerance::planar(cfg, summary, control)?),
            Run::Spatial { sim, summary, .. } => Some(tolerance::spatial(sim, summary, control)?),
            Run::Linear { .. } => None,
        };
        Ok(Output { run, tolerance, columns: columns.map(|c| (names, c)), written })
    }
}

impl command::Command for Args {
    const NAME: &'static str = "simulate";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        self.plan()?.run(control)
    }
}

/// One run, by model: its config, summary, the samples kept for the figures, the wall time (s).
pub enum Run {
    /// Paper 004's planar rotor.
    Planar {
        /// The config.
        cfg: Box<PlanarConfig>,
        /// The run's summary.
        summary: Box<autobal::planar::Summary>,
        /// The samples kept for the figures.
        env: Box<Envelope>,
        /// Wall time of the run (s).
        wall: f64,
    },
    /// The spatial rotor of papers 000/003.
    Spatial {
        /// The config.
        sim: Box<SpatialSim>,
        /// The run's summary.
        summary: Box<autobal::spatial::dynamics::Summary>,
        /// The samples kept for the figures.
        kept: Vec<autobal::spatial::dynamics::Sample>,
        /// Wall time of the run (s).
        wall: f64,
    },
    /// A linear rotor.
    Linear {
        /// The config.
        cfg: Box<LinearRotorConfig>,
        /// The model run, its drive and settings.
        setup: Box<RunSetup>,
        /// The summary, the samples kept for the figures, the wall time.
        run: Box<RunOutput>,
    },
}

impl Run {
    /// Why the run stopped before its end (Ctrl-C, a budget, too many steps), or `None`.
    pub fn stopped(&self) -> Option<&str> {
        match self {
            Run::Planar { summary, .. } => summary.stopped.as_deref(),
            Run::Spatial { summary, .. } => summary.stopped.as_deref(),
            Run::Linear { run, .. } => run.summary.stopped.as_deref(),
        }
    }
}

/// The files a run wrote.
#[derive(Debug, Clone)]
pub struct Written {
    /// The CSV of the samples.
    pub csv: PathBuf,
    /// The Parquet file, where asked.
    pub parquet: Option<PathBuf>,
    /// The figures (`STEM_amplitude_omega.svg`, ...).
    pub plots: Vec<PathBuf>,
}

/// `simulate`'s result: the run, the tolerance check where asked, the samples as columns where
/// asked, the files written.
pub struct Output {
    /// The run.
    pub run: Run,
    /// `--check-tolerance`'s result (a run that stopped early is not checked).
    pub tolerance: Option<Check>,
    /// Every sample, column by column, with the columns' names ([`Args::columns`]).
    pub columns: Option<(Vec<String>, Vec<Vec<f64>>)>,
    /// The files written ([`Args::files`]).
    pub written: Option<Written>,
}

impl Output {
    /// What the front end says after the result: the files written, the run's warnings (which
    /// the table also prints: a front end showing the table leaves them out).
    pub fn notes(&self) -> Vec<String> {
        let mut n = vec![];
        if let Some(w) = &self.written {
            if let Some(p) = &w.parquet {
                n.push(format!("wrote {}", p.display()));
            }
            n.push(format!(
                "wrote {} and {} plots ({})",
                w.csv.display(),
                w.plots.len(),
                w.plots.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
            ));
        }
        match &self.run {
            Run::Planar { summary, .. } => n.extend(summary.warnings.iter().map(|w| format!("warning: {w}"))),
            Run::Spatial { summary, .. } => n.extend(spatial_sim::warnings(summary).iter().map(|w| format!("warning: {w}"))),
            Run::Linear { run, .. } => n.extend(linear_rotor::run_warnings(&run.summary).iter().map(|w| format!("warning: {w}"))),
        }
        n
    }

    /// The run's relative tolerance where its end state is a verdict that was not checked
    /// against a tighter one ([`tolerance::unchecked`]): a ball model's complete run without
    /// `--check-tolerance` (a linear rotor's run has no check yet; a stopped run no end state).
    fn unchecked_rtol(&self) -> Option<f64> {
        match &self.run {
            _ if self.tolerance.is_some() || self.run.stopped().is_some() => None,
            Run::Planar { cfg, .. } => Some(cfg.settings.rtol),
            Run::Spatial { sim, .. } => Some(sim.lib.settings.rtol),
            Run::Linear { .. } => None,
        }
    }

    /// Whether the run is of paper 004's planar rotor or the spatial rotor (whose ball angles
    /// Python gathers into one array `psi`), not a linear rotor.
    pub fn is_ball_model(&self) -> bool {
        !matches!(self.run, Run::Linear { .. })
    }
}

impl command::Output for Output {
    /// The summary (the library's `reports`; a linear rotor's from [`linear_rotor::simulate_json`])
    /// with `tolerance_check` where asked.
    fn json(&self) -> Result<Value> {
        let mut v = match &self.run {
            Run::Planar { cfg, summary, wall, .. } => sim::summary_json(cfg, summary, *wall),
            Run::Spatial { sim, summary, wall, .. } => spatial_sim::summary_json(sim, summary, *wall),
            Run::Linear { cfg, setup, run } => linear_rotor::simulate_json(cfg, &run.summary, &setup.reduction, run.wall),
        };
        if let Some(o) = v.as_object_mut() {
            if let Some(c) = &self.tolerance {
                o.insert("tolerance_check".into(), c.json());
            } else if let Some(rtol) = self.unchecked_rtol() {
                o.insert("tolerance_check".into(), tolerance::unchecked(rtol).0);
            }
        }
        Ok(v)
    }

    fn table(&self) -> Result<String> {
        let mut t = match &self.run {
            Run::Planar { cfg, summary, wall, .. } => sim::summary_table(cfg, summary, *wall),
            Run::Spatial { sim, summary, wall, .. } => spatial_sim::summary_table(sim, summary, *wall),
            Run::Linear { setup, run, .. } => linear_rotor::simulate_table(&run.summary, &setup.reduction, run.wall),
        };
        let line = match (&self.tolerance, self.unchecked_rtol()) {
            (Some(c), _) => Some(c.line()),
            (None, Some(rtol)) => Some(tolerance::unchecked(rtol).1),
            (None, None) => None,
        };
        if let Some(line) = line {
            if !t.ends_with('\n') {
                t.push('\n');
            }
            t.push_str(&line);
            t.push('\n');
        }
        Ok(t)
    }

    /// `simulation_amplitude_omega`, `simulation_amplitude_t`, `simulation_psi_t`,
    /// `simulation_omega_t`: the figures written beside the CSV as `STEM_amplitude_omega.svg`, ...
    fn figures(&self) -> Result<Vec<Figure>> {
        let plots = match &self.run {
            Run::Planar { cfg, env, .. } => sim::plots(cfg, env, "Passage"),
            Run::Spatial { sim, kept, .. } => spatial_sim::plots(sim, kept, "Spatial rotor"),
            Run::Linear { setup, run, .. } => linear_rotor::plots(setup, &run.kept),
        };
        Ok(plots.into_iter().map(|(suffix, p)| Figure::new(&format!("simulation_{suffix}"), p)).collect())
    }

    /// The run's stop, naming the CSV that keeps the samples up to then.
    fn stopped(&self) -> Option<String> {
        if let Some(st) = self.run.stopped() {
            return Some(match &self.written {
                Some(w) => format!("{st}: the samples up to then are kept in {}", w.csv.display()),
                None => st.to_string(),
            });
        }
        // the run complete, its check against the tolerance stopped (review 25a: this read as
        // a passed check, exit 0)
        self.tolerance.as_ref().filter(|c| c.stopped()).map(|_| match &self.written {
            Some(w) => format!(
                "the tolerance check stopped before its second run ended: the run itself is complete (its samples in {}), its end state not checked",
                w.csv.display()
            ),
            None => "the tolerance check stopped before its second run ended: the run itself is complete, its end state not checked".to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::{Command as _, Output as _};

    fn planar(sets: &[&str]) -> ConfigSource {
        ConfigSource::File { path: None, sets: sets.iter().map(|s| s.to_string()).collect() }
    }

    /// A short passage of paper 004's rotor: 0.5 s from 250 rad/s, samples every 0.01 s.
    const SHORT: [&str; 4] = ["drive.t_end=0.5", "drive.omega0=250", "drive.b=100", "integration.dt=0.01"];

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("autobal-simulate-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// The CSV the command writes and the columns it keeps are the same samples: the columns
    /// read back from the CSV's text equal the in-memory ones bit for bit (the CSV's floats are
    /// the shortest round-trip text), the header is the columns' names, and the JSON is the
    /// summary of exactly those samples (its time reached is the last row's).
    #[test]
    fn the_csv_and_the_columns_are_the_same_samples() {
        let d = scratch("same");
        let args = Args { config: planar(&SHORT), files: Some(Files { out: d.join("s.csv"), parquet: false }), columns: true, ..Default::default() };
        let o = args.run(&Control::none()).unwrap();
        let (names, cols) = o.columns.as_ref().unwrap();
        let text = std::fs::read_to_string(d.join("s.csv")).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next().unwrap(), names.join(","));
        let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
        // 0.5 s at 0.01 s: 51 samples
        assert_eq!(rows.len(), 51);
        for (i, r) in rows.iter().enumerate() {
            for (j, v) in r.iter().enumerate() {
                assert_eq!(v.to_bits(), cols[j][i].to_bits(), "row {i} column {}", names[j]);
            }
        }
        let w = o.written.as_ref().unwrap();
        assert_eq!(w.plots, sim::plot_paths(&d.join("s")));
        assert!(w.plots.iter().all(|p| p.is_file()));
        assert_eq!(o.figures().unwrap().iter().map(|f| f.id.clone()).collect::<Vec<_>>(), sim::PLOTS.map(|s| format!("simulation_{s}")).to_vec());
        assert!(o.stopped().is_none());
        // the same run without files (Python) gives the same summary but the wall time
        let bare = Args { config: planar(&SHORT), ..Default::default() }.run(&Control::none()).unwrap();
        let strip = |mut v: Value| {
            v.as_object_mut().unwrap().retain(|k, _| !k.contains("wall"));
            v
        };
        assert_eq!(strip(bare.json().unwrap()), strip(o.json().unwrap()));
        assert!(bare.written.is_none() && bare.columns.is_none());
        let _ = std::fs::remove_dir_all(&d);
    }

    /// A run stopped before its start (the control cancelled) keeps what it sampled (the
    /// initial sample at most), renames the CSV into place, and says so naming the file.
    #[test]
    fn a_stopped_run_keeps_its_rows_and_says_where() {
        let d = scratch("stopped");
        let control = Control::new();
        control.cancel();
        let args = Args { config: planar(&SHORT), files: Some(Files { out: d.join("run"), parquet: false }), ..Default::default() };
        let o = args.run(&control).unwrap();
        let why = o.stopped().expect("stopped");
        assert!(why.ends_with(&format!(": the samples up to then are kept in {}", d.join("run.csv").display())), "{why}");
        let text = std::fs::read_to_string(d.join("run.csv")).unwrap();
        assert!(text.starts_with("t,omega,x,y,amplitude,psi_1,psi_2\n"), "{text}");
        assert!(text.lines().count() < 51);
        // a stopped run is not checked against the tolerance
        let o = Args { config: planar(&SHORT), check_tolerance: true, ..Default::default() }.run(&control).unwrap();
        assert!(o.tolerance.is_none() && o.json().unwrap().get("tolerance_check").is_none());
        let _ = std::fs::remove_dir_all(&d);
    }

    /// Options are checked before any file is made: a bad `--dt` names the flag (Python shows
    /// it as `dt`), and `--check-tolerance` on a linear rotor config says it is not supported.
    #[test]
    fn options_are_checked_first() {
        let d = scratch("checks");
        let out = Some(Files { out: d.join("x.csv"), parquet: false });
        let e = Args { config: planar(&SHORT), dt: Some(-1.0), files: out.clone(), ..Default::default() }.run(&Control::none()).err().unwrap();
        let msg = format!("{e:#}");
        assert!(msg.starts_with("--dt: "), "{msg}");
        assert!(matches!(e.downcast_ref::<autobal::Error>(), Some(autobal::Error::InvalidParameter { field, .. }) if field == "--dt"));
        let shaft = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/linear_rotor_shaft.toml");
        let e = Args { config: ConfigSource::file(Some(&shaft), &[]), check_tolerance: true, files: out, ..Default::default() }
            .run(&Control::none())
            .err()
            .unwrap();
        assert!(format!("{e:#}").starts_with("--check-tolerance: not yet"), "{e:#}");
        assert!(std::fs::read_dir(&d).unwrap().next().is_none(), "no file made");
        let _ = std::fs::remove_dir_all(&d);
    }

    /// Issue 18 item 4 (audit 25's F5): a run not checked against the tolerance says so, in
    /// the table and in the JSON (`tolerance_check.checked` false), where `--check-tolerance`
    /// gives the check itself; and a spatial run that ends not settled carries its warning in
    /// the JSON's `warnings` as in the table (it was the table's only).
    #[test]
    fn an_unchecked_end_state_says_it_is_unchecked() {
        let o = Args { config: planar(&SHORT), ..Default::default() }.run(&Control::none()).unwrap();
        let j = o.json().unwrap();
        assert_eq!(j["tolerance_check"]["checked"], false, "{j}");
        assert_eq!(j["tolerance_check"]["rtol"].as_f64(), Some(1e-8));
        assert!(o.table().unwrap().contains("not checked against a tighter one"));
        let c = Args { config: planar(&SHORT), check_tolerance: true, ..Default::default() }.run(&Control::none()).unwrap();
        assert_eq!(c.json().unwrap()["tolerance_check"]["checked"], true);
        assert!(!c.table().unwrap().contains("not checked"));
        let spatial = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/spatial.toml");
        let s = Args { config: ConfigSource::file(Some(std::path::Path::new(spatial)), &["drive.t_end=20".to_string()]), ..Default::default() }
            .run(&Control::none())
            .unwrap();
        let j = s.json().unwrap();
        assert_eq!(j["outcome"], "not_settled", "{j}");
        let w = j["warnings"].as_array().unwrap();
        assert!(w.len() == 1 && w[0].as_str().unwrap().starts_with("the balls have not settled"), "{w:?}");
        assert!(s.table().unwrap().contains("warning: the balls have not settled"));
    }

    /// Review 25a: a check whose second run stopped (Ctrl-C during `--check-tolerance`) read
    /// "the same end state", `checked: true`, exit 0. Now it says the check was not done, its
    /// JSON `checked` is false and the command's stop names it (the front ends exit as for a
    /// stopped run).
    #[test]
    fn a_stopped_tolerance_check_is_no_check() {
        use autobal::tolerance::EndState;
        let mut o = Args { config: planar(&SHORT), ..Default::default() }.run(&Control::none()).unwrap();
        assert!(o.stopped().is_none());
        o.tolerance = Some(Check { first: (1e-8, EndState::Balanced), second: (1e-9, EndState::Stopped), depends: false });
        let why = o.stopped().expect("the check's stop");
        assert!(why.starts_with("the tolerance check stopped before its second run ended"), "{why}");
        assert_eq!(o.json().unwrap()["tolerance_check"]["checked"], false);
        let t = o.table().unwrap();
        assert!(t.contains("tolerance check: NOT DONE") && !t.contains("the same end state"), "{t}");
    }
}
