//! `autobal inertia`: the whole rotor's mass properties on every spatial config, and paper
//! 000's composite inertia (eqs (4), (5), (17)) where it applies ([`crate::any_config::inertia`]);
//! on a linear rotor config the structure's mass, polar moment and balls from its matrices
//! ([`crate::linear_rotor_summary::inertia`]).

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
        // rotor's mass); a planar config is refused with one line; a linear rotor config:
        // crate::linear_rotor_summary::inertia
        let (root, source) = self.config.read_any()?;
        if crate::linear_rotor::is_linear(&root) {
            // a linear rotor: the structure's mass, I_p and the balls from its matrices
            let cfg = crate::linear_rotor::from_table(&root, self.config.dir())?;
            let (json, table) = crate::linear_rotor_summary::inertia(&cfg);
            return Ok(Output { json, table });
        }
        let (json, table) = crate::any_config::inertia(&root, &source)?;
        Ok(Output { json, table })
    }
}
