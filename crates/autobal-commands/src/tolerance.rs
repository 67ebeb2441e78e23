//! `simulate --check-tolerance`: the run again at a tenth of its tolerances, and whether its end
//! state changes class ([`autobal::tolerance`]): where it does, the first run's outcome is not
//! the answer, and the summary says so.

use crate::config::PlanarConfig;
use crate::spatial_sim::SpatialSim;
use anyhow::Result;
use autobal::control::Control;
use autobal::planar::problem::PlanarProblem;
use autobal::tolerance::{check_tolerance, depends, second_tolerances, Classified, EndState};
use serde_json::{json, Value};

/// The check of a run's outcome against the tolerance: both end states and the verdict.
#[derive(Debug, Clone)]
pub struct Check {
    /// The first run's relative tolerance and end state.
    pub first: (f64, EndState),
    /// The second run's.
    pub second: (f64, EndState),
    /// The classes differ.
    pub depends: bool,
}

impl Check {
    /// Whether the second run stopped before its end (Ctrl-C, a budget): then nothing is
    /// checked (review 25a: a stopped second run read "the same end state", exit 0).
    pub fn stopped(&self) -> bool {
        self.second.1 == EndState::Stopped
    }

    /// The `tolerance_check` object of the summary's JSON (`checked` false where the second
    /// run stopped).
    pub fn json(&self) -> Value {
        json!({
            "checked": !self.stopped(),
            "rtol": self.first.0,
            "end_state": self.first.1,
            "tighter_rtol": self.second.0,
            "tighter_end_state": self.second.1,
            "depends_on_tolerance": self.depends,
            "what": "the run again with integration.rtol and integration.atol divided by 10: different end states prove the first is not the answer; equal ones are evidence, not proof",
        })
    }

    /// The line the table adds.
    pub fn line(&self) -> String {
        let name = |s: EndState| serde_json::to_value(s).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
        if self.stopped() {
            format!(
                "tolerance check: NOT DONE: the run again at rtol {} stopped before its end; the end state above ({} at rtol {}) is not checked",
                autobal::error::fmt_num(self.second.0),
                name(self.first.1),
                autobal::error::fmt_num(self.first.0)
            )
        } else if self.depends {
            format!(
                "tolerance check: the END STATE DEPENDS ON THE TOLERANCE ({} at rtol {}, {} at rtol {}): the outcome above is not the answer",
                name(self.first.1),
                autobal::error::fmt_num(self.first.0),
                name(self.second.1),
                autobal::error::fmt_num(self.second.0)
            )
        } else {
            format!(
                "tolerance check: the same end state ({}) at rtol {} and {}",
                name(self.first.1),
                autobal::error::fmt_num(self.first.0),
                autobal::error::fmt_num(self.second.0)
            )
        }
    }
}

/// What a run not checked says about its tolerance (issue 18 item 4: an end state decided by
/// the tolerance must not read as the answer; the check costs a second run, so it is asked
/// for): the `tolerance_check` object of the JSON, `checked` false, and the table's line.
pub fn unchecked(rtol: f64) -> (Value, String) {
    let what = "the end state at this tolerance, not checked against a tighter one: a start near a basin boundary or a chaotic transient can end elsewhere at another tolerance; --check-tolerance runs it again at a tenth";
    (
        json!({ "checked": false, "rtol": rtol, "depends_on_tolerance": null, "what": what }),
        format!(
            "tolerance: the end state above is that at rtol {}, not checked against a tighter one (a start near a basin boundary can end elsewhere): --check-tolerance runs it again at a tenth",
            autobal::error::fmt_num(rtol)
        ),
    )
}

/// What [`unchecked_runs`] says of a grid of runs (`sweep`'s note; the JSON's `what`).
pub const UNCHECKED_RUNS: &str = "each run's end state is that at its tolerance, none checked against a tighter one: a start near a basin boundary or a chaotic transient can end elsewhere at another tolerance; simulate --check-tolerance checks one run";

/// [`unchecked`] for a grid of runs (`basins`, `sweep`): each run's end (`outcome`, `balanced`)
/// is that at `rtol` (`None`: each run's own, as a sweep's axis may move it; JSON null), none
/// checked against a tighter one (a run near a basin boundary can end elsewhere at another
/// tolerance; `simulate --check-tolerance` checks one run).
pub fn unchecked_runs(rtol: Option<f64>) -> (Value, String) {
    let at = rtol.map_or("its tolerance".to_string(), |r| format!("rtol {}", autobal::error::fmt_num(r)));
    (
        json!({ "checked": false, "rtol": rtol, "depends_on_tolerance": null, "what": UNCHECKED_RUNS }),
        format!("tolerance: each run's end is that at {at}, none checked against a tighter one (near a basin boundary a run can end elsewhere): simulate --check-tolerance checks one"),
    )
}

/// Paper 004's planar rotor: `cfg`'s run at its tolerances ended in `first`.
pub fn planar(cfg: &PlanarConfig, first: &autobal::planar::Summary, control: &Control) -> Result<Check> {
    let p = PlanarProblem { rotor: cfg.rotor.clone(), drive: cfg.drive.clone(), settings: cfg.settings.clone() };
    let c = check_tolerance(&p, first, cfg.settings.rtol, cfg.settings.atol, control)?;
    Ok(Check { first: (c.first_rtol, c.first), second: (c.second_rtol, c.second), depends: c.depends_on_tolerance })
}

/// The spatial rotor: `sim`'s run at its tolerances ended in `first`.
pub fn spatial(sim: &SpatialSim, first: &autobal::spatial::dynamics::Summary, control: &Control) -> Result<Check> {
    let mut s = sim.lib.settings.clone();
    (s.rtol, s.atol) = second_tolerances(s.rtol, s.atol);
    let second = autobal::spatial::dynamics::simulate_with(&sim.lib.rotor, &sim.lib.drive, &sim.lib.initial, &s, control, |_| true)?;
    let (c1, c2) = (first.end_state(), second.end_state());
    Ok(Check { first: (sim.lib.settings.rtol, c1), second: (s.rtol, c2), depends: depends(c1, c2) })
}
