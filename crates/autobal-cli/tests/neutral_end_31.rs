//! Walk 31, finding 3: a stable range's end where a grid speed lies in the neutral band. On the
//! flexible shaft of examples/linear_rotor_windows.toml with the ball drag a map's column point
//! put at 300 rad/s (`linear_rotor.drag` = 0.035333999230060725), the default grid's speed
//! 300 reads "neutral" (α = −3.4e-11 1/s, inside the stability test's band) and 310 "stable"
//! (α = −0.0038): `α` has no zero between them, and the bisection on its sign walked to the
//! stable end, reporting a located range start at 309.9999998509884 rad/s (a grid speed minus
//! the tolerance, `from_is_boundary` true). Other grids (`--samples 199`, 333), where 300 is
//! not a grid speed, give 300.0000000 ± 1e-7 (the walk's figures): the second route. The
//! start is now the neutral speed itself, where the secant across the bracket puts `α`'s zero
//! within the tolerance.

mod common;
use common::{examples as example, json};

fn start(samples: Option<&str>) -> (f64, bool) {
    let cfg = example("linear_rotor_windows.toml");
    let mut args = vec!["stability", "--config", cfg.as_str(), "--set", "linear_rotor.drag=0.035333999230060725", "--format", "json"];
    if let Some(s) = samples {
        args.extend(["--samples", s]);
    }
    let v = json(&args);
    let ranges = v["stable_ranges"].as_array().unwrap_or_else(|| panic!("{v}"));
    // the first range that starts near 300 rad/s (the window's lower end at this drag)
    let r = ranges.iter().find(|r| (r["from"].as_f64().unwrap() - 305.0).abs() < 20.0).unwrap_or_else(|| panic!("{ranges:?}"));
    (r["from"].as_f64().unwrap(), r["from_is_boundary"].as_bool().unwrap())
}

#[test]
fn a_neutral_grid_speed_ends_the_range_there_not_at_its_stable_neighbour() {
    let (other, located) = start(Some("199"));
    assert!(located && (other - 300.0).abs() < 1e-6, "--samples 199: {other}");
    let (got, located) = start(None);
    assert!(located, "default grid: {got} not located");
    assert!((got - other).abs() <= 1e-8 * other, "default grid {got}, --samples 199 {other}");
}
