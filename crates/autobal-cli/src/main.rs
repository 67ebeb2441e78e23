//! `autobal`: command-line front end. Reads a config, runs the library's analyses, writes
//! tables, JSON, SVG figures and an HTML report.

mod config;
mod figures;
mod output;
mod plot;
mod report;

use anyhow::Result;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

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

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Format {
    Table,
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Mass-inertia properties and anisotropy of the composite rotor (000, eqs (4), (5), (17))
    Inertia {
        #[command(flatten)]
        common: Common,
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
    },
    /// Critical speeds (000, eq (16)), sensitivity criterion and autobalancing ranges
    Critical {
        #[command(flatten)]
        common: Common,
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
    },
    /// Speed ranges where autobalancing is possible (003, eqs (1)-(3))
    Ranges {
        #[command(flatten)]
        common: Common,
        #[arg(long, value_enum, default_value = "table")]
        format: Format,
    },
    /// Write an HTML report with SVG figures to a folder
    Report {
        #[command(flatten)]
        common: Common,
        /// Output folder (created if missing)
        #[arg(long, short, default_value = "autobal-report")]
        out: PathBuf,
    },
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Inertia { common, format } => {
            let cfg = config::load(common.config.as_deref(), &common.set)?;
            emit(format, output::inertia_json(&cfg), output::inertia_table(&cfg))
        }
        Command::Critical { common, format } => {
            let cfg = config::load(common.config.as_deref(), &common.set)?;
            emit(format, output::critical_json(&cfg), output::critical_table(&cfg))
        }
        Command::Ranges { common, format } => {
            let cfg = config::load(common.config.as_deref(), &common.set)?;
            emit(format, output::ranges_json(&cfg), output::ranges_table(&cfg))
        }
        Command::Report { common, out } => {
            let cfg = config::load(common.config.as_deref(), &common.set)?;
            let index = report::write(&cfg, &out)?;
            for w in &cfg.model.anisotropy.warnings {
                eprintln!("warning: {w}");
            }
            println!("report written to {}", index.display());
            Ok(())
        }
    }
}

fn emit(format: Format, json: serde_json::Value, table: String) -> Result<()> {
    match format {
        Format::Json => println!("{}", serde_json::to_string_pretty(&json)?),
        Format::Table => print!("{table}"),
    }
    Ok(())
}

fn main() {
    let cli = Cli::parse();
    if let Err(e) = run(cli) {
        eprintln!("error: {}", format!("{e:#}").replace('\n', " "));
        std::process::exit(2);
    }
}
