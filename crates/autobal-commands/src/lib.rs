//! autobal's commands: the layer between the physics library (`autobal`, no files, no printing)
//! and the two front ends (the `autobal` binary in `autobal-cli`, the Python module in
//! `autobal-py`).
//!
//! Everything a command needs beyond the physics lives here once, so that the CLI and Python
//! cannot differ. A command is one module: `Args` (its options with their defaults and checks)
//! `-> run(&Args, &Control) -> Output` (typed, computed once; its JSON, table and figures), the
//! pattern of [`command`]: [`inertia`], [`critical`], [`ranges`], [`stability`], [`campbell`],
//! [`basins`], [`map`], [`sweep`], [`merge`], [`report`], [`simulate`], [`export_model`].
//! Beside them: reading a config and `--set` ([`config`]), the computations and tables the
//! commands share ([`linear`] for paper 000's model, [`general`] for the general route, [`sim`]
//! and [`spatial_sim`] for runs in time, [`map`], [`sweep`]), the output files ([`outfile`]: checked
//! before the work, written under a temporary name and renamed when complete; [`num`] for CSV,
//! [`parquet`]), the figure descriptions that SVG, PNG and Plotly all draw ([`plot`],
//! [`figures`], [`map`]; each command's figures for a front end that draws them itself:
//! [`figures_api`]) and the HTML report ([`report`]).
//!
//! The front ends parse arguments and own the terminal: `autobal-cli` maps each subcommand's
//! flags to its `Args`, runs it and prints or writes the `Output`; `autobal-py` maps keyword
//! arguments to the same `Args` and converts the `Output` to Python objects and exceptions.

pub mod any_config;
pub mod basins;
pub mod campbell;
pub mod command;
pub mod config;
pub mod critical;
pub mod export_model;
pub mod figures;
pub mod figures_api;
#[cfg(test)]
mod fuzz;
pub mod general;
pub mod general_campbell;
pub mod inertia;
pub mod linear;
pub mod linear_rotor;
pub mod linear_rotor_summary;
pub mod map;
pub mod merge;
pub mod num;
pub mod outfile;
pub mod output;
pub mod parquet;
pub mod plot;
pub mod ranges;
pub mod report;
pub mod sim;
pub mod simulate;
pub mod spatial_sim;
pub mod stability;
pub mod sweep;
pub mod term;
pub mod tolerance;
