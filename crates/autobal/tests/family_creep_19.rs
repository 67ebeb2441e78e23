//! A run at constant speed that ends next to a family of balanced states (four balls in a
//! plane) of which every member is unstable creeps away from it: not a settled balanced end.
//! Found by session 19's audit with an independent model: a planar rotor with four balls at
//! 115.8 rad/s, below its critical speed (~214 rad/s), every member of the two-parameter family
//! unstable (the most stable at +0.055 1/s); the balls started on a member, 1e-3 rad apart,
//! read "balanced", settled, no warning at 40 s (residual 0.027), and "not balanced" (residual
//! 3.0, the balls bunched on the heavy side) at 121 s. The creep check covered isolated states
//! only. The second route is the time simulation itself, run on: the end at 40 s is not
//! settled, and the same run continued leaves the family.

use autobal::planar::{simulate, Drive, PlanarRotor, Settings, Summary};
use autobal::rotor_stability::{stability_over_speed, unstable_balanced_state, Rotor, UnstableBalance};
use autobal::spatial::dynamics::RunOutcome;

/// The audit's random rotor (runs/rb3_0_1.toml): race centred, four 22 g balls.
fn rotor() -> PlanarRotor {
    PlanarRotor {
        m1: 1.0920262664902491,
        m2: 0.4105735093428786,
        n: 4,
        s1: 0.002746486108193103,
        s2: 0.0,
        gamma: 2.7200371846850557,
        r: 0.06874307788845005,
        c_theta: 0.0,
        i_g: 0.0025,
        k: 73129.50695201122,
        c: 42.166678097087896,
        m3: 0.02202,
        c_psi: 0.2873,
        ..PlanarRotor::paper()
    }
}

const OMEGA: f64 = 115.78404097663164;
/// The audit's start: a member of the family (two pairs of balls), 1e-3 rad off.
const PSI0: [f64; 4] = [4.195161736179644, 2.0883235709999424, 4.194561736179644, 2.0888235709999425];

fn run(t_end: f64) -> Summary {
    let p = rotor();
    let settings = Settings { psi0: PSI0.to_vec(), dt: 0.08, ..Settings::new(&p, t_end) };
    let s = simulate(&p, &Drive::Speed { omega0: OMEGA }, &settings, |_| true).unwrap();
    assert!(s.status.is_completed(), "{s:?}");
    s
}

#[test]
fn a_run_next_to_a_family_with_no_stable_member_is_not_settled() {
    let p = rotor();
    // the analysis: a family, no member sampled stable, the least growth rate positive
    let r = stability_over_speed(&Rotor::Planar(p.clone()), &[OMEGA]).unwrap();
    let point = &r.points[0];
    assert!(point.family_dimension > 0, "{point:?}");
    let Some(UnstableBalance::Family(rate)) = unstable_balanced_state(&Rotor::Planar(p), OMEGA) else { panic!("{point:?}") };
    // the audit's independent model: the most stable member at +0.0548 1/s; the fitted
    // departure of a run 0.074 1/s on a similar rotor: a rate of that order
    assert!(rate > 0.01 && rate < 0.2, "{rate}");
    // at 40 s the residual is still small, but the end is not settled, with the family's words
    let s = run(40.0);
    assert!(s.residual_unbalance < 0.1, "{s:?}");
    assert_eq!(s.outcome, RunOutcome::NotSettled, "{s:?}");
    assert!(!s.balanced && !s.settled);
    assert!(
        s.warnings.len() == 1 && s.warnings[0].contains("every member of which") && s.warnings[0].contains("unstable at ω = 115.784041 rad/s"),
        "{:?}",
        s.warnings
    );
    // the time simulation run on confirms it: the balls leave the family (a residual of order 1:
    // the audit's 3.0 at 121 s, the balls bunched)
    let long = run(150.0);
    assert!(long.residual_unbalance > 1.0, "{long:?}");
}
