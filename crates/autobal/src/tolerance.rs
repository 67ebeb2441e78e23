//! Whether a run's end state depends on the integration tolerance (issue 18, "verdicts that
//! mean what they say").
//!
//! A run that starts near the boundary of a basin of attraction, or whose transient is chaotic
//! (balls that circulate round the race and are caught by chance), ends in a state that the
//! rounding of each step decides: run it again at a tighter tolerance and it may end
//! elsewhere. Printing one outcome as *the* answer would then be false. The check here is the
//! direct one: the same point run again with `integration.rtol` and `integration.atol` both
//! divided by [`TIGHTENING`] (multiplied where the tolerance is already at the double-precision
//! floor of 1e-14), and the two end states compared by class ([`EndState`]: balanced, partially
//! balanced, not balanced, not settled, stopped). Equal classes say the outcome does not depend
//! on the tolerance *between these two tolerances*, which is evidence, not proof: a test of
//! two samples cannot show that no tolerance would change it. Different classes prove that the
//! outcome at the first tolerance is not the answer.
//!
//! It costs one more run at the tighter tolerance (about 1.5-2x the first run's right-hand
//! sides for an 8th-order method, `10^{1/8}` per step), so the front ends ask for it
//! (`--check-tolerance`) rather than pay it on every run.
//!
//! ```
//! use autobal::control::Control;
//! use autobal::paths::Parameters;
//! use autobal::planar::problem::PlanarProblem;
//! use autobal::sweep::SweepModel;
//! use autobal::tolerance::{check_tolerance, EndState};
//! let mut p = PlanarProblem::default();
//! p.set("drive.t_end", 60.0).unwrap();
//! let first = p.run(&p, &Control::none()).unwrap();
//! let check = check_tolerance(&p, &first, p.settings.rtol, p.settings.atol, &Control::none()).unwrap();
//! assert_eq!(check.first, EndState::of(&first));
//! assert!((check.second_rtol - p.settings.rtol / 10.0).abs() < 1e-20);
//! ```

use crate::control::Control;
use crate::error::Result;
use crate::sweep::SweepModel;
use serde::Serialize;

/// The factor between the two tolerances compared.
pub const TIGHTENING: f64 = 10.0;

/// The smallest relative tolerance the models accept (double precision's floor).
const RTOL_FLOOR: f64 = 1e-14;

/// The class of a run's end state, as its summary reports it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EndState {
    /// Balanced (or paper 004's semi-balanced whirl with an eccentric race): `outcome` balanced.
    Balanced,
    /// The balls' capacity falls short and they rest at its limit (either rotor).
    PartiallyBalanced,
    /// Settled, but neither of the above.
    NotBalanced,
    /// Still moving at the end (balls drifting or circulating).
    NotSettled,
    /// The run stopped before its end (interrupted, budget, too many steps).
    Stopped,
}

impl EndState {
    /// The class of a summary.
    pub fn of<S: Classified>(s: &S) -> EndState {
        s.end_state()
    }
}

/// A summary whose end state has a class.
pub trait Classified {
    /// The class of the end state.
    fn end_state(&self) -> EndState;
}

impl Classified for crate::planar::Summary {
    /// Paper 004's rotor: its [`crate::spatial::dynamics::RunOutcome`] (the spatial run's rule),
    /// as the spatial rotor's.
    fn end_state(&self) -> EndState {
        if self.stopped.is_some() {
            return EndState::Stopped;
        }
        outcome_state(self.outcome)
    }
}

/// The class of a run's [`crate::spatial::dynamics::RunOutcome`].
fn outcome_state(o: crate::spatial::dynamics::RunOutcome) -> EndState {
    use crate::spatial::dynamics::RunOutcome;
    match o {
        RunOutcome::Balanced => EndState::Balanced,
        RunOutcome::PartiallyBalanced => EndState::PartiallyBalanced,
        RunOutcome::NotBalanced => EndState::NotBalanced,
        RunOutcome::NotSettled => EndState::NotSettled,
    }
}

impl Classified for crate::spatial::dynamics::Summary {
    /// The spatial rotor's [`crate::spatial::dynamics::RunOutcome`].
    fn end_state(&self) -> EndState {
        if self.stopped.is_some() {
            return EndState::Stopped;
        }
        outcome_state(self.outcome)
    }
}

/// The result of [`check_tolerance`].
#[derive(Debug, Clone, Serialize)]
pub struct ToleranceCheck<S> {
    /// The first run's tolerances and end state.
    pub first_rtol: f64,
    /// The first run's end state.
    pub first: EndState,
    /// The second run's relative tolerance (`first_rtol / 10`, or `* 10` at the floor).
    pub second_rtol: f64,
    /// The second run's end state.
    pub second: EndState,
    /// `first != second`: the outcome depends on the tolerance, and the first run's is not the
    /// answer.
    pub depends_on_tolerance: bool,
    /// The second run's summary.
    #[serde(skip)]
    pub second_summary: S,
}

/// The second run's `(rtol, atol)`: both divided by [`TIGHTENING`], or multiplied where
/// `rtol / 10` would pass below the double-precision floor of 1e-14.
pub fn second_tolerances(rtol: f64, atol: f64) -> (f64, f64) {
    let factor = if rtol / TIGHTENING >= RTOL_FLOOR { 1.0 / TIGHTENING } else { TIGHTENING };
    (rtol * factor, atol * factor)
}

/// Whether two end states show the outcome depends on the tolerance: different classes, neither
/// run stopped early.
pub fn depends(first: EndState, second: EndState) -> bool {
    first != second && first != EndState::Stopped && second != EndState::Stopped
}

/// Run `model`'s point again with both tolerances divided by [`TIGHTENING`] (multiplied when
/// `rtol / 10` would pass below 1e-14) and compare the end state with `first`, the summary of
/// the run at `rtol`, `atol`. `model` is the run's own description (a [`SweepModel`] is also
/// its own point: [`crate::planar::problem::PlanarProblem`]; for the spatial rotor
/// [`crate::sweep::SpatialSweep`]). A run the control stops is reported as
/// [`EndState::Stopped`].
pub fn check_tolerance<M>(model: &M, first: &M::Summary, rtol: f64, atol: f64, control: &Control) -> Result<ToleranceCheck<M::Summary>>
where
    M: SweepModel,
    M::Summary: Classified + Clone,
{
    let (r2, a2) = second_tolerances(rtol, atol);
    let point = model.at(&["integration.rtol", "integration.atol"], &[r2, a2])?;
    let second = model.run(&point, control)?;
    let (c1, c2) = (first.end_state(), second.end_state());
    Ok(ToleranceCheck { first_rtol: rtol, first: c1, second_rtol: r2, second: c2, depends_on_tolerance: depends(c1, c2), second_summary: second })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planar::problem::PlanarProblem;

    /// A model whose end state is decided by its tolerance, as at a basin boundary: balanced
    /// at `rtol >= 1e-8`, not balanced below. The check must see the dependence, and must not
    /// see it in a model that ignores the tolerance.
    struct Toy {
        rtol: f64,
        decided_by_tolerance: bool,
    }
    #[derive(Clone, serde::Serialize)]
    struct ToySummary(EndState);
    impl Classified for ToySummary {
        fn end_state(&self) -> EndState {
            self.0
        }
    }
    impl crate::sweep::SweepSummary for ToySummary {
        const COLUMNS: &'static [&'static str] = &[];
        fn values(&self) -> Vec<f64> {
            vec![]
        }
        fn stopped(&self) -> Option<&str> {
            None
        }
    }
    impl SweepModel for Toy {
        type Point = f64;
        type Summary = ToySummary;
        fn at(&self, paths: &[&str], values: &[f64]) -> Result<f64> {
            assert_eq!(paths, ["integration.rtol", "integration.atol"]);
            Ok(values[0])
        }
        fn run(&self, rtol: &f64, _: &Control) -> Result<ToySummary> {
            let balanced = !self.decided_by_tolerance || *rtol >= 1e-8 * (1.0 - 1e-12);
            Ok(ToySummary(if balanced { EndState::Balanced } else { EndState::NotBalanced }))
        }
    }

    #[test]
    fn a_tolerance_decided_outcome_is_flagged_and_a_robust_one_is_not() {
        for decided in [true, false] {
            let toy = Toy { rtol: 1e-8, decided_by_tolerance: decided };
            let first = toy.run(&toy.rtol, &Control::none()).unwrap();
            let c = check_tolerance(&toy, &first, toy.rtol, 1e-9, &Control::none()).unwrap();
            assert_eq!(c.second_rtol, 1e-9);
            assert_eq!(c.depends_on_tolerance, decided, "decided_by_tolerance = {decided}");
        }
        // at the floor the second run is looser, not tighter
        let toy = Toy { rtol: 1e-14, decided_by_tolerance: false };
        let first = toy.run(&toy.rtol, &Control::none()).unwrap();
        let c = check_tolerance(&toy, &first, 1e-14, 1e-15, &Control::none()).unwrap();
        assert!((c.second_rtol - 1e-13).abs() < 1e-27);
    }

    /// Paper 004's passage at its defaults ends balanced, and so does the run at rtol 1e-9:
    /// the published outcome does not depend on the tolerance.
    #[test]
    fn paper_004s_passage_is_balanced_at_both_tolerances() {
        let p = PlanarProblem::default();
        let first = p.run(&p, &Control::none()).unwrap();
        let c = check_tolerance(&p, &first, p.settings.rtol, p.settings.atol, &Control::none()).unwrap();
        assert_eq!(c.first, EndState::Balanced);
        assert_eq!(c.second, EndState::Balanced);
        assert!(!c.depends_on_tolerance);
        // the two runs are different runs (not the first one returned twice)
        assert_ne!(c.second_summary.steps, first.steps);
    }
}
