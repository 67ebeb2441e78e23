//! A Campbell diagram's speeds must increase (round 3 session 13): `campbell` on a repeated
//! speed (`[1.0, 1.0]`, `[1.0; 3]`) hung on main (the tracking's speed step 0/0), and
//! `fixed_axes` bisects between neighbouring speeds. Both now refuse such speeds by name.

use autobal::spatial::campbell::fixed_axes;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::{DimensionlessInput, SpatialModel};
use autobal::spatial::stability::{campbell, Campbell};

fn model() -> SpatialModel {
    SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap()
}

#[test]
fn speeds_that_do_not_increase_are_refused() {
    let m = model();
    for speeds in [vec![1.0, 1.0], vec![1.0; 3], vec![0.5, 1.0, 0.9], vec![0.5, f64::NAN]] {
        for balls in [Balls::Free, Balls::Locked] {
            let e = campbell(&m, &speeds, balls).unwrap_err();
            assert_eq!(e.field(), Some("omega"), "{speeds:?}: {e}");
            assert!(e.to_string().contains("must increase"), "{e}");
        }
    }
    // increasing speeds still work; a hand-built diagram with a repeated speed is refused by
    // the crossing search
    let c = campbell(&m, &[0.5, 1.0, 1.5], Balls::Free).unwrap();
    assert_eq!(c.omega.len(), 3);
    let twice = Campbell { omega: vec![0.5, 1.0, 1.0], lines: c.lines.clone() };
    let e = fixed_axes(&m, &twice, Balls::Free, &[1]).unwrap_err();
    assert_eq!(e.field(), Some("omega"), "{e}");
}
