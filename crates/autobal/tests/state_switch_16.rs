//! A stable range's end where the speed scan's state switches to another stationary state is
//! not a change of stability (`StableRange::from_is_switch`). Found by an independent check
//! (bench/independent/check_spatial_two_plane.py, session 16): Rodrigues et al.'s two-plane
//! rotor with balls of 0.97 of the existence threshold `m_c = ε/4` has no balanced state, and
//! two partially balanced states coexist near 315 rad/s; the scan's start reaches the unstable
//! one (balls opposite the unbalance) below 315.503 rad/s and the stable one above, and main at
//! bb89c7b reported 315.503 as a located boundary (`from_is_boundary`). Now the range's own
//! state is followed (Newton continuation) to the grid speed below, 315 rad/s, where it is
//! still stable: the range starts there, at a switch of state.
//!
//! Since session 21 the scan also starts Newton from every ball bunched where the race pulls
//! them (the roots on the rotor's linearisation, `linear_rotor::partial::bunched_guesses`) and
//! analyses the state of least growth, so below 315 rad/s it reaches the range's stable state
//! itself: the range runs from the axis's first speed through 315 rad/s with no end there at
//! all (neither boundary nor switch), which the continuation below confirms to 150 rad/s.

use autobal::analysis::{stability, stationary, NewtonOptions, Verdict};
use autobal::rotor_stability::{speed_grid, stability_over_speed, Rotor};

mod common;
use common::RODRIGUES_097;

#[test]
fn a_switch_between_two_partially_balanced_states_is_not_a_boundary() {
    let root = autobal::config::parse(RODRIGUES_097, "rodrigues").unwrap();
    let rotor = Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor);
    let r = stability_over_speed(&rotor, &speed_grid(1500.0, 200).unwrap()).unwrap();
    // the range that holds 315 rad/s, without an end between 150 and 322 rad/s
    let first = r.stable_ranges.iter().find(|s| s.from <= 150.0 && s.to > 315.6).unwrap_or_else(|| panic!("{:?}", r.stable_ranges));
    assert!(!first.from_is_switch, "{first:?}");
    // every other end the checker confirmed as a change of stability stays a located boundary
    let ends: Vec<(f64, bool, bool)> =
        r.stable_ranges.iter().flat_map(|s| [(s.from, s.from_is_boundary, s.from_is_switch), (s.to, s.to_is_boundary, s.to_is_switch)]).collect();
    for w in [322.859, 705.713, 725.665, 912.182] {
        let e = ends.iter().find(|e| (e.0 - w).abs() < 0.01).unwrap_or_else(|| panic!("{w}: {ends:?}"));
        assert!(e.1 && !e.2, "{w}: {e:?}");
    }
    // the second route: the range's state at 318 rad/s (inside it: the scan's own start reaches
    // it there, stable), continued down past the range's start by Newton in steps of 0.25 rad/s
    // (the branch turns fast: its balls move ~0.3 rad per 2 rad/s near 312), stays stable at
    // every step: no change of stability at 315.503, where main put a boundary, nor at 315
    let below: f64 = 315.0 * (1.0 - 1e-3);
    let newton = NewtonOptions::default();
    let at = |w: f64| rotor.field(w).unwrap();
    let f318 = at(318.0);
    let autobal::rotor_stability::Field::Spatial(f) = &f318 else { panic!() };
    let start = Rotor::guess(&f318).or_else(|| Rotor::placed_guess(&f318)).unwrap();
    let mut s = stationary(f, &start, &newton).unwrap();
    assert_eq!(stability(f, &s).unwrap().verdict, Verdict::Stable);
    let mut w = 318.0;
    while w > below {
        w = (w - 0.25).max(below);
        let fw = at(w);
        let autobal::rotor_stability::Field::Spatial(f) = &fw else { panic!() };
        s = autobal::analysis::stationary_near(f, &s.x, None, &newton).unwrap();
        assert_eq!(stability(f, &s).unwrap().verdict, Verdict::Stable, "the range's state at {w} rad/s");
    }
    // further down the same state swings the balls to the heavy side: at 150 rad/s the
    // checker's own model (SciPy) gives a residual of 1.97 of the unbalance, worded "not
    // balanced" since session 29's one rule (`rotor_stability::state_from_residual`: a residual
    // of 1 or more, the larger of the static and couple parts, is not reduced by the balls;
    // it was "partially balanced" before, while `simulate` called such a state not balanced)
    while w > 150.0 {
        w = (w - 0.5).max(150.0);
        let fw = at(w);
        let autobal::rotor_stability::Field::Spatial(f) = &fw else { panic!() };
        s = autobal::analysis::stationary_near(f, &s.x, None, &newton).unwrap();
    }
    let (kind, residual) = Rotor::classify(&at(150.0), &s.x);
    assert!((residual - 1.97).abs() < 0.01, "{residual}");
    assert_eq!(kind, autobal::rotor_stability::StateKind::NotBalanced);
    // and the scan's own state below 315 rad/s is the stable one now, the unstable one (balls
    // opposite the unbalance, the scan's state there until session 21) listed beside it
    let r_below = stability_over_speed(&rotor, &[below]).unwrap();
    assert_eq!(r_below.points[0].verdict, Some(Verdict::Stable));
    assert!(r_below.points[0].other_orbits.iter().any(|o| o.verdict == Verdict::Unstable), "{:?}", r_below.points[0]);
}
