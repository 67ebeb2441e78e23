//! `autobal ranges`: the exact stable speed ranges on every config, and paper 003's necessary
//! ranges (eqs (1)-(3)) where they are defined ([`crate::any_config::ranges`]: the general route
//! where the one-plane model does not describe the config, a planar config included; a linear
//! rotor config: [`crate::linear_rotor_summary::ranges`]).

use crate::command::{self, ConfigSource};
use anyhow::Result;
use autobal::control::Control;

/// `autobal ranges`' arguments.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The config.
    pub config: ConfigSource,
}

/// Its result: the JSON and the table, each built once from the config.
pub type Output = crate::output::JsonTable;

impl command::Command for Args {
    const NAME: &'static str = "ranges";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        let (root, source) = self.config.read_any()?;
        if crate::linear_rotor::is_linear(&root) {
            let cfg = crate::linear_rotor::from_table(&root, self.config.dir())?;
            let (json, table) = crate::linear_rotor_summary::ranges(&cfg)?;
            return Ok(Output { json, table });
        }
        for n in crate::config::bare_speed_notes(&root) {
            crate::term::note(&n);
        }
        let (json, table) = crate::any_config::ranges(&root, &source, control)?;
        Ok(Output { json, table })
    }
}
