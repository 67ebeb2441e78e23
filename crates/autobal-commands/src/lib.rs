//! autobal's commands: the layer between the physics library (`autobal`, no files, no printing)
//! and the two front ends (the `autobal` binary in `autobal-cli`, the Python module in
//! `autobal-py`).
//!
//! Everything a command needs beyond the physics lives here once, so that the CLI and Python
//! cannot differ: reading a config and `--set` ([`config`]), each command's run, table and JSON
//! ([`linear`] for the analytic commands, [`general`] for the general route, [`sim`] and
//! [`spatial_sim`] for runs in time, [`map`], [`sweep`]), the output files ([`outfile`]: checked
//! before the work, written under a temporary name and renamed when complete; [`num`] for CSV,
//! [`parquet`]), the figure descriptions that SVG, PNG and Plotly all draw ([`plot`],
//! [`figures`], [`map`]; each command's figures for a front end that draws them itself:
//! [`figures_api`]) and the HTML report ([`report`]).
//!
//! The front ends parse arguments and own the terminal: `autobal-cli` maps each subcommand to
//! the functions here; `autobal-py` converts to NumPy and Python exceptions.

pub mod any_config;
pub mod config;
pub mod figures;
pub mod figures_api;
#[cfg(test)]
mod fuzz;
pub mod general;
pub mod general_campbell;
pub mod linear;
pub mod linear_rotor;
pub mod map;
pub mod num;
pub mod outfile;
pub mod output;
pub mod parquet;
pub mod plot;
pub mod report;
pub mod sim;
pub mod spatial_sim;
pub mod sweep;
pub mod term;
