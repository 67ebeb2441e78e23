//! `autobal critical`: paper 000's critical speeds (eq (16)), sensitivity criterion and
//! autobalancing ranges where its 12-state model represents the config ([`crate::output`]),
//! else the general route ([`crate::general_campbell::critical`]: the verdict at the operating
//! speed first, as on the closed-form route, then the locked critical speeds, with the balls
//! at the partially balanced placement where they cannot balance, and the exact stability
//! ranges of the nonlinear equations' linearisation); on a linear rotor
//! config its natural frequencies at rest with the balls as rings
//! ([`crate::linear_rotor_summary::critical`]).

use crate::command::{self, ConfigSource, Route};
use crate::config::{self, Config};
use crate::general::GeneralRotor;
use crate::general_campbell::{self, GeneralCritical};
use anyhow::{bail, Result};
use autobal::control::Control;
use serde_json::Value;

/// `autobal critical`'s arguments.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// The config.
    pub config: ConfigSource,
    /// The route.
    pub route: Route,
    /// The top of the general route's speed axis (a speed with its unit, or a bare number Ω);
    /// `None`: automatic. The closed forms give every critical speed and take none.
    pub omega_max: Option<String>,
}

/// `critical`'s result, by route.
pub enum Output {
    /// Paper 000's closed forms on the config (the JSON and table evaluate them).
    Closed(Box<Config>),
    /// The general route.
    General(Box<(GeneralRotor, GeneralCritical)>),
    /// A linear rotor config: its natural frequencies at rest with the balls as rings
    /// ([`crate::linear_rotor_summary::critical`]).
    LinearRotor(Box<crate::output::JsonTable>),
}

impl command::Command for Args {
    const NAME: &'static str = "critical";
    type Output = Output;

    fn run(&self, control: &Control) -> Result<Output> {
        let (root, source) = self.config.read_any()?;
        if crate::linear_rotor::is_linear(&root) {
            if self.omega_max.is_some() {
                bail!("--omega-max: a linear rotor's `critical` gives its natural frequencies at rest and takes no speed axis (autobal campbell --omega-max gives the critical speeds over one)");
            }
            let cfg = crate::linear_rotor::from_table(&root, self.config.dir())?;
            let (json, table) = crate::linear_rotor_summary::critical(&cfg)?;
            return Ok(Output::LinearRotor(Box::new(crate::output::JsonTable { json, table })));
        }
        if self.route.is_general(&root) {
            let g = crate::general::rotor_of(&root)?;
            let from_linear = config::FromLinear::SpeedRange { omega_max_given: self.omega_max.is_some(), necessary: true };
            config::check_entries_with(&root, "critical", &[config::simulation_model(&root)], from_linear)?;
            let w = general_campbell::omega_max(&root, &g, self.omega_max.as_deref())?;
            let c = general_campbell::critical(&root, &g, w, control).map_err(|e| match e.downcast::<autobal::Error>() {
                Ok(e) => crate::general::name_omega_max(crate::general::floor_in_units(&g, e, &[w]), self.omega_max.is_some(), "analysis.omega_max", &root, &g),
                Err(e) => e,
            })?;
            return Ok(Output::General(Box::new((g, c))));
        }
        if self.omega_max.is_some() {
            bail!("--omega-max: only the general route (--route general) takes a speed axis; eq (16) gives every critical speed");
        }
        let cfg = config::build(&root, &source)?;
        config::check_entries(&root, "critical", &[config::Model::Linear])?;
        crate::output::check_results(&cfg)?;
        Ok(Output::Closed(Box::new(cfg)))
    }
}

impl command::Output for Output {
    fn json(&self) -> Result<Value> {
        Ok(match self {
            Output::Closed(cfg) => crate::output::critical_json(cfg),
            Output::General(b) => general_campbell::critical_json(&b.0, &b.1),
            Output::LinearRotor(t) => t.json.clone(),
        })
    }
    fn table(&self) -> Result<String> {
        Ok(match self {
            Output::Closed(cfg) => crate::output::critical_table(cfg),
            Output::General(b) => general_campbell::critical_table(&b.0, &b.1),
            Output::LinearRotor(t) => t.table.clone(),
        })
    }
}
