//! What a stationary state is called where the balls make things worse (session 15, found by
//! an independent check): with the race centred the planar residual is the residual unbalance
//! `|m1 s1 + Σ m r e^{iψ}| / (m1 s1)` itself, and a state whose bunched balls sit on the
//! unbalance's side (below the critical speed) leaves more than the unbalance: "not balanced",
//! never "partially balanced" (main at 07fe55e said "partially balanced, stable" with 1.40).

use autobal::planar::PlanarRotor;
use autobal::rotor_stability::{stability_over_speed, Rotor, StateKind};

#[test]
fn bunched_balls_on_the_unbalances_side_are_not_balanced() {
    let p = PlanarRotor { s2: 0.0, m3: 0.01, ..PlanarRotor::paper() };
    let wn = p.natural_frequency();
    // below the critical speed the bunched balls join the unbalance; above it they oppose it
    let r = stability_over_speed(&Rotor::Planar(p.clone()), &[12.0, 2.0 * wn]).unwrap();
    let (low, high) = (&r.points[0], &r.points[1]);
    // the residual unbalance, recomputed here from the ball angles (two balls of m3 at radius r)
    let resid = |psi: &[f64]| {
        let (mut x, mut y) = (p.m1 * p.s1, 0.0);
        for a in psi {
            x += p.m3 * p.r * a.cos();
            y += p.m3 * p.r * a.sin();
        }
        x.hypot(y) / (p.m1 * p.s1)
    };
    let (rl, rh) = (resid(&low.member_psi), resid(&high.member_psi));
    // the pipeline's residual is that unbalance to round-off (an equilibrium, race centred)
    assert!((low.residual.unwrap() - rl).abs() < 1e-9 && (high.residual.unwrap() - rh).abs() < 1e-9, "{low:?} {high:?}");
    assert!(rl > 1.0, "below the critical speed the balls add to the unbalance: {rl}");
    assert_eq!(low.state, Some(StateKind::NotBalanced), "{low:?}");
    assert!(rh < 1.0, "{rh}");
    assert_eq!(high.state, Some(StateKind::PartiallyBalanced), "{high:?}");
}
