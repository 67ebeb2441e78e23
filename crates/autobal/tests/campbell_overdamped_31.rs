//! Session 31: the log decrement where the frequency is resolved, and the overdamped ends on the
//! real axis (`spatial::campbell`, `CriticalSpeed::overdamped`).
//!
//! * The log decrement `−2πσ/|f|` has one rule on every route and view
//!   (`spatial::stability::log_decrement`): given where `|f|` exceeds `√ε` times the largest
//!   `|λ|` of the speed's spectrum (the error of a double eigenvalue), `None` below. Ordinary
//!   modes keep theirs (a damped Jeffcott rotor's, from the closed-form eigenvalue), and so does
//!   a nearly real pair whose `ν` is resolved (two balls' drag modes: `ν` checked against
//!   60-digit eigenvalues of the same matrix).
//! * An end of a stretch on the real axis of the rotating frame (`ν̂ = 0`, forward `1×`) whose
//!   pair never oscillates faster than it decays (`ν̂ > |σ|`) within `Ω/5` of it, on a side
//!   where it is complex, is marked overdamped: no resonance (API 684's amplification factor
//!   below 2.5). For a damped Jeffcott rotor the half-power band is exactly `2ζ` wide about
//!   `ω_d`, so the mark changes at `ζ = ω_d/5`, `ζ* = 1/√26`; the two balls' drag modes of
//!   examples/default.toml (`σ ≈ −0.1`, `|ν| < 1e-4`) are marked on both routes, the real
//!   crossings are not.

use autobal::spatial::campbell::{fixed_axes, CriticalSpeed};
use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::SpatialModel;
use autobal::spatial::stability::{campbell, eigenvalues_at, log_decrement, Whirl, FREQUENCY_RESOLUTION};
use std::f64::consts::PI;

mod common;
use common::{campbell_grid, direct_model};

/// A config of examples/ as the commands read it, with `h_s` set where given.
fn example(text: &str, h_s: Option<f64>) -> SpatialModel {
    let mut root = autobal::config::parse(text, "test").unwrap();
    if let Some(h) = h_s {
        autobal::config::set(&mut root, "dimensionless.h_s", toml::Value::Float(h)).unwrap();
    }
    for t in ["drive", "initial"] {
        root.remove(t);
    }
    autobal::config::spatial_simulation(&root).unwrap().config.model
}

/// A symmetric isotropic rotor with its balls locked, supports damped `h_x = 2ζ`: its
/// translation obeys `z̈ + 2ζ ż + z = 0` in fixed axes (000 eq (6) with `l̄ = ½`: no coupling to
/// the tilt), eigenvalues `−ζ ± i ω_d`, `ω_d = √(1 − ζ²)`.
fn jeffcott(zeta: f64) -> SpatialModel {
    direct_model(0.6, 0.4, 0.5, 0.0, 0.0, 2.0 * zeta, 0.0, None)
}

#[test]
fn the_log_decrement_is_given_where_the_frequency_is_resolved() {
    // the rule itself
    let s = 2.0;
    assert_eq!(log_decrement(-0.1, 0.5 * FREQUENCY_RESOLUTION * s, s), None);
    assert_eq!(log_decrement(-0.1, -0.5 * FREQUENCY_RESOLUTION * s, s), None);
    assert_eq!(log_decrement(-0.1, 0.0, s), None);
    let d = log_decrement(-0.1, -2.0 * FREQUENCY_RESOLUTION * s, s).unwrap();
    assert!((d - 2.0 * PI * 0.1 / (2.0 * FREQUENCY_RESOLUTION * s)).abs() < 1e-12 * d);
    assert_eq!(FREQUENCY_RESOLUTION, f64::EPSILON.sqrt());
}

#[test]
fn a_jeffcott_rotors_log_decrement_is_the_closed_forms() {
    // δ = −2πσ/|f| = 2πζ/ω_d per fixed-axes cycle on both translation curves at every speed,
    // and −2πσ/|ν| = 2πζ/|±ω_d − Ω| per rotating-axes cycle (ν = ±ω_d − Ω), to 1e-9 relative
    // (eigenvalues of a 8×8 state matrix accurate to ~1e-14; the curves are told apart by
    // |f| = ω_d, the tilt's lying near 1.2 and above)
    for zeta in [0.02, 0.1, 0.3] {
        let m = jeffcott(zeta);
        let wd = (1.0 - zeta * zeta).sqrt();
        let omegas = campbell_grid(2.5, 250);
        let c = campbell(&m, &omegas, Balls::Locked).unwrap();
        let f = fixed_axes(&m, &c, Balls::Locked, &[1]).unwrap();
        let want = 2.0 * PI * zeta / wd;
        let translation: Vec<_> = f.curves.iter().filter(|cv| cv.points.iter().all(|p| (p.frequency - wd).abs() < 1e-9)).collect();
        assert_eq!(translation.len(), 2, "ζ {zeta}: the forward and backward translation curves");
        for cv in translation {
            for p in &cv.points {
                let d = p.log_decrement.unwrap();
                assert!((d - want).abs() < 1e-9 * want, "ζ {zeta}, Ω {}: δ {d}, closed form {want}", p.omega);
            }
        }
        let mut seen = 0;
        for (k, &w) in omegas.iter().enumerate() {
            for line in &c.lines {
                let md = line.modes[k];
                for nu in [wd - w, -wd - w] {
                    if (md.re + zeta).abs() < 1e-9 && (md.im.abs() - nu.abs()).abs() < 1e-9 && nu.abs() > 1e-3 {
                        let want = 2.0 * PI * zeta / nu.abs();
                        let d = md.log_decrement.unwrap();
                        assert!((d - want).abs() < 1e-9 * want, "ζ {zeta}, Ω {w}: rotating δ {d}, closed form {want}");
                        seen += 1;
                    }
                }
            }
        }
        assert!(seen >= 2 * omegas.len(), "ζ {zeta}: {seen} rotating-axes values compared");
    }
}

#[test]
fn a_resolved_nearly_real_pair_keeps_its_large_log_decrement() {
    // examples/spatial.toml with h_s = 0.03 at its table's first speed Ω = 0.00715618: the two
    // balls' drag modes form the pair −0.0300011343 ± 1.20858779e-6 i (60-digit eigenvalues of
    // the same state matrix, mpmath; unchanged to 5 digits with every entry perturbed by an
    // ulp): resolved (√ε × 1.59 = 2.4e-8), so its decrement is given, 2π·0.0300011/1.2086e-6
    // ≈ 1.5597e5 per rotating-axes cycle, and `autobal campbell` prints its ν beside it. QR
    // agrees with the 60 digits to 4e-11 relative in ν; 1e-8 is asked.
    let m = example(include_str!("../../../examples/spatial.toml"), Some(0.03));
    let w = 0.007156181366624035;
    let (_, ev) = eigenvalues_at(&m, w, Balls::Free).unwrap();
    let lam = ev.iter().copied().find(|z| (z.re + 0.03).abs() < 1e-3 && z.im > 0.0).unwrap();
    let (re, nu) = (-0.030001134286419876, 1.208_587_792_200_033e-6);
    assert!((lam.re - re).abs() < 1e-12 && (lam.im - nu).abs() < 1e-8 * nu, "{lam}");
    let c = campbell(&m, &[w], Balls::Free).unwrap();
    let md = c.lines.iter().map(|l| l.modes[0]).find(|md| (md.re + 0.03).abs() < 1e-3 && md.im > 0.0).unwrap();
    let d = md.log_decrement.expect("a resolved ν has a log decrement");
    let want = -2.0 * PI * re / nu;
    assert!((d - want).abs() < 1e-8 * want, "δ {d}, from the 60-digit eigenvalue {want}");
}

/// The forward `1×` crossings (ends on the real axis) of `cs` within 1e-6 of `w` (6 digits).
fn near(cs: &[CriticalSpeed], w: f64) -> Vec<CriticalSpeed> {
    cs.iter().copied().filter(|k| k.harmonic == 1 && k.whirl == Whirl::Forward && (k.omega - w).abs() < 1e-6 * w.max(1.0)).collect()
}

#[test]
fn a_jeffcott_critical_speed_is_overdamped_where_its_amplification_factor_is_below_2_5() {
    // The forward pair λ = −ζ + i(ω_d − Ω) in turning axes reaches the axis at Ω_c = ω_d and
    // has ν̂ = |σ| at Ω_c ± ζ: half-power band 2ζ, AF = ω_d/(2ζ) ≥ 2.5 exactly where ζ ≤ ω_d/5,
    // ζ ≤ 1/√26 = 0.196116. Either side of it, on two grids.
    let star = 1.0 / 26f64.sqrt();
    for zeta in [0.05, 0.15, 0.19, 0.2, 0.25, 0.4] {
        for n in [120, 401] {
            let m = jeffcott(zeta);
            let wd = (1.0 - zeta * zeta).sqrt();
            let c = campbell(&m, &campbell_grid(2.5, n), Balls::Locked).unwrap();
            let f = fixed_axes(&m, &c, Balls::Locked, &[1]).unwrap();
            let at = near(&f.critical_speeds, wd);
            assert_eq!(at.len(), 1, "ζ {zeta}, {n} speeds: {:?}", f.critical_speeds);
            assert_eq!(at[0].overdamped, zeta > star, "ζ {zeta}, {n} speeds: {:?}", at[0]);
        }
    }
}

#[test]
fn the_drag_modes_of_two_balls_are_overdamped_ends_on_both_routes() {
    // examples/default.toml (paper 000's base rotor, two balls of equal drag h_s = 0.1): the
    // balls' drag pair (σ ≈ −0.1) lies on the real axis from 0.0773556 to 0.131932 and within
    // 1e-4 of it next to there: both ends are overdamped, on the 12-state route and on the
    // general route (the same rotor's nonlinear equations). The ball pair meeting the axis at
    // 2.101767 oscillates faster than it decays 0.12 below it (within 2.1/5): a resonance.
    let m = example(include_str!("../../../examples/default.toml"), None);
    let omegas = campbell_grid(4.3, 300);
    let c = campbell(&m, &omegas, Balls::Free).unwrap();
    let twelve = fixed_axes(&m, &c, Balls::Free, &[1]).unwrap().critical_speeds;
    let rotor = autobal::rotor_stability::Rotor::Spatial(autobal::spatial::dynamics::SpatialRotor::from_dimensionless(&m).unwrap());
    let g = autobal::rotor_campbell::campbell_over_speed(&rotor, &campbell_grid(4.3, 150)).unwrap();
    let general = autobal::rotor_campbell::fixed_view(&rotor, Balls::Free, &g, &[1]).unwrap().critical_speeds;
    for (route, cs) in [("12-state", &twelve), ("general", &general)] {
        for (w, overdamped) in [(0.0773556, true), (0.131932, true), (2.101767, false)] {
            let at = near(cs, w);
            assert_eq!(at.len(), 1, "{route}: {w} in {cs:?}");
            assert_eq!(at[0].overdamped, overdamped, "{route}: {:?}", at[0]);
        }
        // only ends on the real axis are ever marked
        assert!(cs.iter().all(|k| !k.overdamped || (k.harmonic == 1 && k.whirl == Whirl::Forward && k.share == 1.0)), "{route}: {cs:?}");
    }
    // independently of the search: every eigenvalue within 0.02 of the drag pair's σ decays
    // faster than it oscillates at 400 speeds within Ω_c/5 of either end (the spectrum at each
    // speed, no tracking)
    for wc in [0.0773556, 0.131932] {
        for i in 0..=400 {
            let w = wc * (0.8 + 0.4 * i as f64 / 400.0);
            let (_, ev) = eigenvalues_at(&m, w, Balls::Free).unwrap();
            for z in ev.iter().filter(|z| (z.re + 0.1).abs() < 0.02) {
                assert!(z.im.abs() < z.re.abs(), "Ω {w}: {z}");
            }
        }
    }
}
