//! Gravity across the axis breaks the family of balanced states of `n >= 3` balls: the
//! periodic orbits have the balls in two bunched groups (`SpatialField::split_guesses`).
//! Checked against a time simulation of the same equations (a second route): the
//! horizontal washer (examples/washing_machine.toml with gravity along −y) run up to 1400
//! rpm and held there settles on the orbit `stability_over_speed` reports, two balls together.

use autobal::rotor_stability::{stability_over_speed, Rotor};
use std::f64::consts::PI;

const WASHER: &str = include_str!("../../../examples/washing_machine.toml");
const SPIN: f64 = 1400.0 * PI / 30.0;

fn washer(extra: &str) -> autobal::config::SpatialSimulation {
    let mut root = autobal::config::parse(&format!("{WASHER}\n{extra}"), "washer").unwrap();
    autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, -9.81, 0.0]")).unwrap();
    autobal::config::spatial_simulation(&root).unwrap()
}

/// Angle difference wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(2.0 * PI);
    if r > PI {
        r - 2.0 * PI
    } else {
        r
    }
}

#[test]
fn the_horizontal_washer_settles_on_the_two_group_orbit_the_analysis_reports() {
    let rotor = Rotor::Spatial(washer("").rotor);
    let r = stability_over_speed(&rotor, &[SPIN]).unwrap();
    let p = &r.points[0];
    assert!(p.failure.is_none(), "{:?}", p.failure);
    let psi = p.member_psi.clone();
    assert_eq!(psi.len(), 3);
    // two balls together (to the shooting's tolerance), the third apart
    let mut pairs: Vec<(f64, usize, usize)> = vec![];
    for i in 0..3 {
        for j in i + 1..3 {
            pairs.push((wrap(psi[i] - psi[j]).abs(), i, j));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(pairs[0].0 < 1e-6 && pairs[1].0 > 0.5, "not two groups: {psi:?}");
    assert_eq!(format!("{:?}", p.verdict), "Some(Stable)", "{p:?}");

    // the simulation: run up in 15 s, held at 1400 rpm to 60 s; the balls' angles over the
    // last revolution, averaged (they swing once a revolution by g/(R Ω sqrt(Ω² + β²)) =
    // 1.8e-3 rad about their mean)
    let sim = washer("[drive]\nkind = \"schedule\"\nschedule = [[0.0, 0.0], [15.0, 146.60765716752368], [60.0, 146.60765716752368]]\nt_end = 60.0\n[integration]\ndt = 0.001\n");
    let period = 2.0 * PI / SPIN;
    let mut last: Vec<Vec<f64>> = vec![];
    autobal::spatial::dynamics::simulate::simulate(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, |s| {
        if s.t >= 60.0 - period {
            last.push(s.psi.clone());
        }
        true
    })
    .unwrap();
    assert!(last.len() > 30);
    let mean: Vec<f64> = (0..3)
        .map(|j| {
            let (c, s) = last.iter().fold((0.0, 0.0), |(c, s), v| (c + v[j].cos(), s + v[j].sin()));
            s.atan2(c)
        })
        .collect();
    // the same placement up to the order of the balls: the lone ball's angle and the pair's.
    // Tolerance 5e-3 rad: along the former family the orbit attracts at only |abscissa| =
    // 1.5e-4 1/s (an e-folding of ~2 h), so the 45 s at speed leave the run-up's offset along
    // it in place (measured: 0.9e-3 rad for the lone ball, 1.6e-3 for the pair); the other
    // orbit (the lone ball at -2.003 rad) and the family's arc member (balls 0.93 rad apart)
    // are hundreds of tolerances away
    let lone = |v: &[f64]| {
        let d = |i: usize, j: usize| wrap(v[i] - v[j]).abs();
        if d(1, 2) < 1e-3 {
            0
        } else if d(0, 2) < 1e-3 {
            1
        } else {
            2
        }
    };
    let pair = |v: &[f64], l: usize| v[(l + 1) % 3];
    let (a, b) = (lone(&psi), lone(&mean));
    assert!(wrap(psi[a] - mean[b]).abs() < 5e-3, "lone ball: analysis {psi:?}, simulation {mean:?}");
    assert!(wrap(pair(&psi, a) - pair(&mean, b)).abs() < 5e-3, "pair: analysis {psi:?}, simulation {mean:?}");
}

#[test]
fn the_mirror_orbit_is_unstable_and_the_arc_is_no_orbit() {
    // the two placements of the groups give two orbits; the analysis reports the one of least
    // growth rate (stable), the other is unstable: both are orbits (shooting converges to the
    // tolerance), while the family's arc member is not (shooting stagnates near a multiplier 1)
    use autobal::analysis::{stability, stationary, NewtonOptions, Verdict};
    let rotor = Rotor::Spatial(washer("").rotor);
    let field = rotor.field(SPIN).unwrap();
    let autobal::rotor_stability::Field::Spatial(f) = &field else { panic!() };
    let starts = f.split_guesses();
    assert_eq!(starts.len(), 2, "one split (2 + 1), both mirror placements");
    let newton = NewtonOptions::default();
    let verdicts: Vec<Verdict> = starts.iter().map(|g| stability(f, &stationary(f, g, &newton).unwrap()).unwrap().verdict).collect();
    assert!(verdicts.contains(&Verdict::Stable) && verdicts.contains(&Verdict::Unstable), "{verdicts:?}");
    let arc = Rotor::guess(&field).unwrap();
    let e = stationary(f, &arc, &newton).unwrap_err().to_string();
    assert!(e.contains("Floquet multiplier lies within"), "{e}");
}
