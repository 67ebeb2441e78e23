//! A rotor statically unstable at rest (review 32, walk 32b's kindef.toml): 2 DOFs `x, y`,
//! `M = diag(2, 2)` kg, `C = diag(10, 10)` N s/m, `K = diag(2e4, −2e4)` N/m (a direction of
//! negative stiffness, as on magnetic bearings), one unbalance and a two-ball balancer. The
//! supports differ by direction, so the stationary state is a periodic orbit of half a
//! revolution, shot over `T = π/Ω`; a deviation along `y` grows at the frozen rate
//! `λ₊ = (−c + √(c² + 4 m k))/(2m)` = 97.06 1/s (`m` = 2.02 kg with the balls as rings), i.e.
//! by `e^{λ₊ π/Ω}` over a period: `e^51` at 5.97 rad/s (the first speed of `stability`'s
//! default axis), where on main at 6230ea0 `stability` and `campbell` made no progress in
//! 100 s (the shooting's line searches, each trial a flow whose residual is the integration's
//! error times that growth). The shooting now refuses such a speed at once, naming the growth
//! (`AnalysisError::Unresolvable`: above `1/rtol`), and gives no verdict there; a speed whose
//! growth it resolves keeps its Floquet verdict.

use autobal::analysis::Verdict;
use autobal::control::Control;
use autobal::linear_rotor::config::linear_rotor_bytes;
use autobal::rotor_campbell::campbell_over_speed_with;
use autobal::rotor_stability::{stability_over_speed_with, Rotor};
use std::time::Duration;

/// The review's files, inline (`/tmp/walk32b/mx`: kindef.toml, M.mtx, Kindef.mtx, C.mtx).
fn rotor() -> Rotor {
    let root: toml::Table = "[linear_rotor]\nlayout = \"x,y\"\nm = \"M.mtx\"\nk = \"Kindef.mtx\"\nc = \"C.mtx\"\n\
        [[linear_rotor.unbalance]]\nnode = 0\nme = 1e-4\n\
        [[linear_rotor.balancer]]\nnode = 0\nradius = 0.05\nballs = 2\nball_mass = 0.01\ndrag = 0.05\n"
        .parse()
        .unwrap();
    let mtx = |a: &str, b: &str| format!("%%MatrixMarket matrix array real symmetric\n%\n2 2\n{a}\n0\n{b}\n").into_bytes();
    let cfg = linear_rotor_bytes(&root, &mut |p| match p {
        "M.mtx" => Ok(mtx("2", "2")),
        "Kindef.mtx" => Ok(mtx("2E4", "-2E4")),
        "C.mtx" => Ok(mtx("1E1", "1E1")),
        _ => Err(format!("{p}: no such file here")),
    })
    .unwrap();
    Rotor::Linear(cfg.rotor)
}

/// The frozen divergence rate `λ₊ = (−c + √(c² + 4 m k))/(2m)` of `m ÿ + c ẏ − k y = 0`,
/// `m` the rotor's 2 kg and the balls' 0.02 kg as a ring.
fn frozen_rate() -> f64 {
    let (m, c, k): (f64, f64, f64) = (2.02, 10.0, 2e4);
    (-c + (c * c + 4.0 * m * k).sqrt()) / (2.0 * m)
}

/// The first speed of `stability`'s default axis (50 speeds to `3 ω_n`, `ω_n` = 99.5 rad/s
/// the positive direction's), and 20 rad/s, where the growth over a period is `e^15` = 4e6.
const SPEEDS: [f64; 2] = [298.511 / 50.0, 20.0];

/// Under a 30 s budget as a watchdog (the old code spent it at the first speed and stopped
/// there): the first speed has no state and no verdict, its failure naming the growth over the
/// period (the monodromy matrix at the closed-form start); 20 rad/s is unstable by its Floquet exponent, which at a speed
/// this far below the divergence rate (Ω/λ₊ = 0.2) lies within 1e-3 of the frozen rate
/// (measured 97.0696 against 97.0593: 1.1e-4).
#[test]
fn a_speed_whose_growth_is_beyond_the_shooting_is_refused_at_once_by_name() {
    let out = stability_over_speed_with(&rotor(), &SPEEDS, &Control::new().with_budget(Duration::from_secs(30))).unwrap();
    assert!(out.stopped.is_none(), "the scan must end by itself: {:?}", out.stopped);
    let r = out.value;
    let low = &r.points[0];
    assert!(low.verdict.is_none() && low.abscissa.is_none() && low.state.is_none(), "{low:?}");
    let why = low.failure.as_deref().unwrap_or_default();
    assert!(why.contains("single shooting cannot resolve it here") && why.contains("its stability is not determined here"), "{why}");
    // the rate printed, ln(growth)/t, is the diverging mode's, within 10 % (the monodromy's
    // scaled norm over the period: 101.3 1/s, its eigenvector's scaling included)
    let rate: f64 = why.split("a growth rate of about ln(that)/t = ").nth(1).and_then(|s| s.split_whitespace().next()).and_then(|s| s.parse().ok()).expect(why);
    assert!((rate - frozen_rate()).abs() <= 0.1 * frozen_rate(), "rate {rate} against {}", frozen_rate());
    let high = &r.points[1];
    assert_eq!(high.verdict, Some(Verdict::Unstable), "{high:?}");
    let a = high.abscissa.unwrap();
    assert!((a - frozen_rate()).abs() <= 1e-3 * frozen_rate(), "Floquet exponent {a} against the frozen rate {}", frozen_rate());
    assert!(r.stable_ranges.is_empty(), "{:?}", r.stable_ranges);
    // the scan then reaches back from 20 rad/s to the first speed (its fill), whose line
    // searches at 5.97, 9.5 and 13 rad/s flow from points off the orbit: each such trial is
    // capped at 20x the current point's steps, and the refusal follows from the refreshed
    // matrix (checked by hand: 5 capped trials at 8740 steps at 5.97 rad/s, 10 at 9.5 rad/s, 2
    // at 13 rad/s), where one uncapped trial took 1.18 million steps (20 s in debug), so the
    // watchdog above stops the scan without the cap; at 5.97 rad/s the closed-form start, tried
    // after the carried one, runs past the first flow's cap and is refused at 7/16 of the period
}

/// The Campbell diagram meets the same shooting: the first speed fails by name, promptly.
#[test]
fn the_campbell_diagram_refuses_that_speed_by_name() {
    let out = campbell_over_speed_with(&rotor(), &SPEEDS, &Control::new().with_budget(Duration::from_secs(30))).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let c = out.value;
    assert!(c.failures[0].as_deref().is_some_and(|f| f.contains("single shooting cannot resolve it here")), "{:?}", c.failures[0]);
    assert!(c.failures[1].is_none(), "{:?}", c.failures[1]);
    assert!(c.lines.iter().all(|l| l.points[0].is_none()));
}

/// The Campbell diagram's first default speed on this rotor, 2.49 rad/s (`T = π/Ω` = 1.26 s,
/// growth `e^{λ₊ T}` ≈ e^122 over the period): the first flow from the closed-form start runs
/// past its 20 000 steps (it crawled there before the shooting's caps), so the shooting asks one
/// deviation's growth over sixteenths of the period and refuses at the first sixteenth where it
/// passes `1/rtol`, before `T` (checked by hand: the first flow's cap and that refusal,
/// not the monodromy matrix's). The rate printed, `ln(growth)/t`, is the diverging mode's
/// within 20 % (one deviation's growth over a part of the period, its start transient
/// included).
#[test]
fn a_first_flow_past_its_step_cap_is_refused_within_part_of_the_period() {
    let omega = 2.49;
    let out = campbell_over_speed_with(&rotor(), &[omega], &Control::new().with_budget(Duration::from_secs(30))).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let why = out.value.failures[0].clone().expect("no failure at 2.49 rad/s");
    assert!(why.contains("single shooting cannot resolve it here"), "{why}");
    let number = |after: &str| -> f64 { why.split(after).nth(1).and_then(|s| s.split_whitespace().next()).and_then(|s| s.parse().ok()).expect(&why) };
    let (within, period, rate) = (number("within t = "), number("of its period T = "), number("a growth rate of about ln(that)/t = "));
    // (the message's numbers carry 6 significant digits)
    assert!((period - std::f64::consts::PI / omega).abs() <= 1e-5 * period, "{why}");
    // at the end of a sixteenth of the period short of the period: 3/16 measured
    let sixteenths = within / (period / 16.0);
    assert!((sixteenths - sixteenths.round()).abs() <= 1e-4 && sixteenths.round() < 16.0, "refused at t = {within} s, the period {period} s: {why}");
    assert!((rate - frozen_rate()).abs() <= 0.2 * frozen_rate(), "rate {rate} against {}", frozen_rate());
}
