//! `autobal inertia`: the whole rotor's mass properties on every spatial config, and paper
//! 000's composite inertia (eqs (4), (5), (17)) where it applies ([`crate::any_config::inertia`]).

use crate::command::{self, ConfigSource};
use anyhow::Result;
use autobal::control::Control;

/// `autobal inertia`'s arguments.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The config.
    pub config: ConfigSource,
}

/// Its result: the JSON and the table, each built once from the config.
pub type Output = crate::output::JsonTable;

impl command::Command for Args {
    const NAME: &'static str = "inertia";
    type Output = Output;

    fn run(&self, _control: &Control) -> Result<Output> {
        // every spatial config: nothing is ignored (supports and gravity are not part of the
        // rotor's mass); a planar config is refused with one line
        let (root, source) = self.config.read()?;
        let (json, table) = crate::any_config::inertia(&root, &source)?;
        Ok(Output { json, table })
    }
}
