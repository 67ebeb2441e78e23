//! What a command is: typed arguments with their defaults and checks, run once under the front
//! end's [`Control`], giving a typed output that the front ends print, write or convert.
//!
//! ```text
//!   CLI: clap flags ─┐                                    ┌─> --format json: Output::write_json
//!                    ├─> X::Args ─ run(&args, &control) ─> X::Output ─> table:  Output::table
//!   Python: kwargs ──┘   (defaults: Args::default())      (computed once)  └─> --svg, .plot(): Output::figures
//! ```
//!
//! A command is one module with its `Args` (a struct, `Default` giving the CLI's defaults),
//! `impl` [`Command`] for it, and its `Output` (`impl` [`Output`]): [`inertia`](crate::inertia),
//! [`critical`](crate::critical), [`ranges`](crate::ranges), [`stability`](crate::stability),
//! [`campbell`](crate::campbell), [`basins`](crate::basins), [`simulate`](crate::simulate),
//! [`export_model`](crate::export_model), [`map`](crate::map), [`sweep`](crate::sweep),
//! [`merge`](crate::merge), [`report`](crate::report). The front ends add only what is theirs: the CLI its flags,
//! files and terminal, Python its keyword arguments and NumPy. Options are named as the CLI's
//! flags (`--omega-max`) in errors; Python shows them as its keywords (`omega_max`).

use crate::plot::Plot;
use anyhow::Result;
use autobal::control::Control;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use toml::Table;

/// A command: its arguments (`Self`) run under a [`Control`] to its [`Output`].
pub trait Command {
    /// The command's name, as the CLI's subcommand.
    const NAME: &'static str;
    /// What it computes.
    type Output: Output;
    /// Check the arguments, read the config once, compute once. Long work asks `control`
    /// (Ctrl-C, a budget); an output cut short says so in [`Output::stopped`].
    fn run(&self, control: &Control) -> Result<Self::Output>;
}

/// A command's result: typed data computed once, shown as JSON, a table or figures.
pub trait Output {
    /// The JSON (`autobal X --format json`, Python's `autobal.run("X")`).
    fn json(&self) -> Result<Value>;
    /// The text table (the CLI's default output).
    fn table(&self) -> Result<String>;
    /// Write the JSON, pretty-printed, with a final newline (an output too large to hold in
    /// memory streams it instead).
    fn write_json(&self, out: &mut dyn std::io::Write) -> Result<()> {
        let text = serde_json::to_string_pretty(&self.json()?)?;
        out.write_all(text.as_bytes())?;
        out.write_all(b"\n")?;
        Ok(())
    }
    /// The figures (the descriptions SVG, PNG and Plotly all draw), by id; none by default.
    fn figures(&self) -> Result<Vec<Figure>> {
        Ok(vec![])
    }
    /// Why the output is incomplete (Ctrl-C, a budget), or `None`: a front end shows what was
    /// computed, then reports this as an error.
    fn stopped(&self) -> Option<String> {
        None
    }
}

/// One figure of a command's output: its id (the report's figure id, or the command's) and
/// its description.
pub struct Figure {
    /// The id (`stability_margin`, `campbell_modes`, ...).
    pub id: String,
    /// The description.
    pub plot: Plot,
}

impl Figure {
    /// A figure with its id.
    pub fn new(id: &str, plot: Plot) -> Self {
        Figure { id: id.to_string(), plot }
    }

    /// `{"id", "title", "figure"}`, the figure as Plotly JSON (`{data, layout}`).
    pub fn to_json(&self) -> Value {
        json!({"id": self.id, "title": self.plot.title, "figure": self.plot.to_plotly()})
    }
}

/// Where a command's config comes from.
#[derive(Debug, Clone)]
pub enum ConfigSource {
    /// A TOML file (`None`: the embedded default, examples/default.toml) and `KEY=VALUE`
    /// overrides: the CLI's `--config` and `--set`.
    File {
        /// The file.
        path: Option<PathBuf>,
        /// The overrides, in order.
        sets: Vec<String>,
    },
    /// Tables already read and overridden (Python's text or dict with its keywords); `source`
    /// names them in messages.
    Tables {
        /// The tables.
        root: Table,
        /// Their name.
        source: String,
        /// The folder the config's own files (a linear rotor's matrices) are read relative to.
        dir: PathBuf,
    },
}

impl Default for ConfigSource {
    fn default() -> Self {
        ConfigSource::File { path: None, sets: vec![] }
    }
}

impl ConfigSource {
    /// Tables already read, named `source`: a file's name (its folder is where the config's own
    /// files are read from) or another name (the working folder).
    pub fn tables(root: Table, source: &str) -> Self {
        let p = Path::new(source);
        let dir = if p.is_file() { p.parent().unwrap_or(Path::new(".")).to_path_buf() } else { PathBuf::from(".") };
        ConfigSource::Tables { root, source: source.to_string(), dir }
    }

    /// The CLI's `--config` and `--set`.
    pub fn file(path: Option<&Path>, sets: &[String]) -> Self {
        ConfigSource::File { path: path.map(Path::to_path_buf), sets: sets.to_vec() }
    }

    /// The tables after the overrides and the source's name, read once
    /// ([`crate::config::read_set`]).
    pub fn read(&self) -> Result<(Table, String)> {
        match self {
            ConfigSource::File { path, sets } => crate::config::read_set(path.as_deref(), sets),
            ConfigSource::Tables { root, source, .. } => Ok((root.clone(), source.clone())),
        }
    }

    /// [`read`](Self::read), where a linear rotor config (`[linear_rotor]`) takes its own
    /// overrides ([`crate::linear_rotor::read_set`]).
    pub fn read_any(&self) -> Result<(Table, String)> {
        match self {
            ConfigSource::File { path, sets } => crate::linear_rotor::read_set(path.as_deref(), sets),
            ConfigSource::Tables { .. } => self.read(),
        }
    }

    /// The config file, if one was read.
    pub fn path(&self) -> Option<&Path> {
        match self {
            ConfigSource::File { path, .. } => path.as_deref(),
            ConfigSource::Tables { .. } => None,
        }
    }

    /// The folder the config's own files (a linear rotor's matrices) are read relative to: the
    /// config file's, else the working folder.
    pub fn dir(&self) -> &Path {
        match self {
            ConfigSource::File { path, .. } => path.as_deref().and_then(Path::parent).unwrap_or(Path::new(".")),
            ConfigSource::Tables { dir, .. } => dir,
        }
    }
}

/// Which route an analysis takes: `auto`, paper 000's 12-state model (closed forms) where it
/// represents the config, else the general route (the nonlinear equations' exact
/// linearisation); `general`, the general route always. (No docs on the variants: clap would
/// switch the whole `--help` to its long layout.)
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Route {
    #[default]
    Auto,
    General,
}

impl Route {
    /// Whether `root` is analysed by the general route.
    pub fn is_general(self, root: &Table) -> bool {
        self == Route::General || crate::general::needs_general_route(root)
    }

    /// Whether `root`'s stability verdict is taken on the general route
    /// ([`crate::general::needs_general_verdict`]).
    pub fn is_general_verdict(self, root: &Table) -> bool {
        self == Route::General || crate::general::needs_general_verdict(root)
    }
}

/// An option's value that must lie in `range` (`flag`: the CLI's name, e.g. `--samples`).
pub fn check_count(flag: &str, n: usize, range: std::ops::RangeInclusive<usize>) -> Result<usize> {
    if !range.contains(&n) {
        return Err(autobal::Error::invalid(flag, format!("must lie between {} and {}, got {n}", range.start(), range.end())).into());
    }
    Ok(n)
}

/// A top speed `w` in rad/s given as `text` by `flag` (`--omega-max 1e7rpm` on a planar or
/// linear rotor, whose speeds are rad/s): positive, at most 1e6 rad/s (the SI speeds' range,
/// as `drive.omega_idle`'s). The error says what was given and its value in rad/s (it called
/// 1.0472e6 rad/s a "dimensionless speed").
pub fn check_speed_rad_s(flag: &str, text: &str, w: f64) -> Result<()> {
    let l = autobal::limits::limit("drive.omega_idle").expect("drive.omega_idle has a limit");
    if !l.contains(w) {
        let f = autobal::error::fmt_num;
        let text = text.trim();
        let is = if text.trim_end_matches("rad/s").trim() == f(w) || text == f(w) { String::new() } else { format!(" is {} rad/s,", f(w)) };
        return Err(autobal::Error::invalid(flag, format!("{text}{is} outside {} ({})", l.describe(), l.why)).into());
    }
    Ok(())
}

/// A top speed `Ω` (dimensionless) given as `text` by `flag`, within the range of
/// `analysis.omega_max`; `omega0` (rad/s per Ω) where the config is SI, so that the error says
/// what `text` is in Ω (`--omega-max: 1e9 rpm is Ω = ω/ω0 = 2.1e5 (ω0 = 500 rad/s), outside …`).
pub fn check_speed_omega(flag: &str, text: &str, omega: f64, omega0: Option<f64>) -> Result<()> {
    let l = autobal::limits::limit("analysis.omega_max").expect("analysis.omega_max has a limit");
    if !l.contains(omega) {
        let f = autobal::error::fmt_num;
        let is = match omega0 {
            Some(w0) => format!("{} is Ω = ω/ω0 = {} (ω0 = {} rad/s),", text.trim(), f(omega), f(w0)),
            None => format!("{} (Ω)", text.trim()),
        };
        return Err(autobal::Error::invalid(flag, format!("{is} outside {} ({})", l.describe(), l.why)).into());
    }
    Ok(())
}

/// A dimensionless speed option (`--omega`, `--omega-max`): finite, ≥ 0 and within the range
/// of `analysis.omega_max` (`--omega` may be 0).
pub fn check_speed(flag: &str, w: f64) -> Result<()> {
    if w == 0.0 && !flag.ends_with("--omega-max") {
        return Ok(());
    }
    autobal::limits::check_as(flag, "analysis.omega_max", w)?;
    Ok(())
}
