//! Gravity in the constant-speed analyses of the linear rotor ([`autobal::linear_rotor`]): in axes
//! turning with the rotor gravity turns once per revolution, the balanced state is a periodic
//! orbit (the rotor sags, the balls swing) and its stability comes from Floquet multipliers.
//! Checked against the native spatial model with its tilt locked (the Jeffcott rotor of the
//! papers' kind: the same physics written independently, a rigid body with point masses in
//! turning axes) and with its tilt free (the preset `LinearRotor::from_spatial`), against a time
//! simulation in fixed axes, and through the library's stability over speed.

use autobal::analysis::{stability, stationary, Kind, NewtonOptions, Stability, VectorField, Verdict};
use autobal::linear_rotor::{BalancerPlane, Frame, Layout, LinearRotor, LinearRotorField, Unbalance};
use autobal::ode::{Control, Method, Options, Solver};
use autobal::rotor_stability::Rotor;
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialField, SpatialRotor, Support};
use std::f64::consts::PI;

mod common;
use common::{all_eigenvalues, locked_tilt_jeffcott, match_distance, per_revolution, Sys};

/// The same rotor as a linear rotor (one node, `x, y`): `M = (M_r + m_u) I` (the unbalance mass
/// moves with the node), `K = diag(k_x, k_y)`, `C = c I`, the unbalance `m·e = m_u ρ` at its
/// angle, the balls with the drag torque `h_A R²` per unit `ψ̇`, and the weight `M g`
/// ([`LinearRotor::set_gravity`]; the balls' weight comes with the balancer).
fn linear(s: &SpatialRotor) -> LinearRotor {
    let mut r = LinearRotor::zeros(1, Layout::Translation);
    let m = s.rotor.mass + s.unbalances[0].mass;
    let sup = s.supports[0];
    r.m = vec![m, 0.0, 0.0, m];
    r.k = vec![sup.stiffness[0], 0.0, 0.0, sup.stiffness[1]];
    r.c = vec![sup.damping[0], 0.0, 0.0, sup.damping[1]];
    let u = s.unbalances[0];
    r.unbalances.push(Unbalance { node: 0, me: u.mass * u.radius, phase: u.angle, offset: 0.0 });
    let p = s.planes[0];
    r.balancers.push(BalancerPlane {
        node: 0,
        radius: p.race_radius,
        balls: p.n,
        ball_mass: p.ball_mass,
        drag: p.drag * p.race_radius * p.race_radius,
        offset: 0.0,
    });
    r.set_gravity([s.gravity[0], s.gravity[1]]);
    r
}

/// The balanced state (equilibrium or periodic orbit) of `f` from `guess`, and its stability.
fn analyse<F: VectorField>(f: &F, guess: &[f64]) -> (Vec<f64>, Stability) {
    let s = stationary(f, guess, &NewtonOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let st = stability(f, &s).unwrap();
    (s.x, st)
}

/// Gravity across the axis, on equal and on unequal supports, at a speed below and above the
/// critical speed (`ω_n ≈ 99.7` rad/s): in turning axes both models have the period `2π/Ω`, the
/// balanced state is a periodic orbit, and the linear rotor's orbit and Floquet multipliers equal
/// the spatial model's. Without gravity (equilibria) the eigenvalues agree first, to `1e-10`
/// relative: the two codes share no equations, and round-off is their only difference there
/// (as `tests/linear_rotor.rs` for the planar preset). With gravity each orbit is found by
/// shooting to a scaled residual of `1e-10` and each monodromy matrix integrated at `rtol =
/// 1e-12`, so the multipliers (of modulus ≤ 1.3 here) carry an error of ~1e-10 each
/// (`analysis` module docs; `FLOQUET_TOLERANCE = 1e-8` covers it): `1e-8` absolute on the
/// multipliers, and `1e-8` of the scales on the orbit's state (the shooting's `1e-10` times the
/// conditioning of `I − Φ`). The test can fail: gravity moves the multipliers by far more than
/// that (checked below, > 1e-6: 100 times the tolerance), so gravity turned the wrong way, applied in the wrong axes or
/// its weight on the balls dropped would show.
#[test]
fn gravity_orbit_and_multipliers_equal_the_spatial_models() {
    for (k, g, w) in
        [([1e5, 1e5], [0.0, -9.81], 150.0), ([1e5, 1e5], [3.0, -9.0], 80.0), ([1e5, 1.3e5], [0.0, -9.81], 180.0), ([1e5, 1.3e5], [-2.0, -9.81], 70.0)]
    {
        let sp = locked_tilt_jeffcott(k, g);
        let lin = linear(&sp);
        let fs = SpatialField::new(&sp, w).unwrap();
        let fl = LinearRotorField::new(&lin, w, Frame::Rotating).unwrap();
        assert_eq!(fl.period(), Some(2.0 * PI / w));
        assert_eq!(fs.period(), fl.period());
        // without gravity first: equilibria (isotropic) or orbits of π/Ω, one model
        let (sp0, lin0) = (locked_tilt_jeffcott(k, [0.0, 0.0]), linear(&locked_tilt_jeffcott(k, [0.0, 0.0])));
        let fs0 = SpatialField::new(&sp0, w).unwrap();
        let fl0 = LinearRotorField::new(&lin0, w, Frame::Rotating).unwrap();
        let (_, ss0) = analyse(&fs0, &fs0.balanced_guess().unwrap());
        let (_, sl0) = analyse(&fl0, &fl0.balanced_guess().unwrap());
        let t = 2.0 * PI / w;
        let (d0, tol0) = if ss0.kind == Kind::Equilibrium {
            (match_distance(&all_eigenvalues(&ss0), &all_eigenvalues(&sl0)), 1e-10 * sl0.rate)
        } else {
            (match_distance(&per_revolution(&ss0, t), &per_revolution(&sl0, t)), 1e-8)
        };
        assert!(d0 <= tol0, "k {k:?} Ω {w}, no gravity: spectra differ by {d0:e}");
        // with gravity: periodic orbits of one revolution; the spatial model's shooting starts
        // on the linear rotor's orbit (the two closed-form guesses number the two balls the
        // other way round), so its state is a check that this is an orbit of the spatial model
        let (xl, sl) = analyse(&fl, &fl.balanced_guess().unwrap());
        let (xs, ss) = analyse(&fs, &xl);
        assert_eq!(ss.kind, Kind::PeriodicOrbit);
        assert_eq!(sl.kind, Kind::PeriodicOrbit);
        let sc = fl.scales();
        for i in 0..xl.len() {
            assert!((xs[i] - xl[i]).abs() <= 1e-8 * sc[i], "k {k:?} Ω {w}: {} {} (spatial) vs {} (linear)", fl.component_name(i), xs[i], xl[i]);
        }
        let d = match_distance(&all_eigenvalues(&ss), &all_eigenvalues(&sl));
        eprintln!(
            "k {k:?} g {g:?} Ω {w}: multipliers agree to {d:.2e}; verdicts {:?} {:?}, abscissae {:.6e} {:.6e}",
            ss.verdict, sl.verdict, ss.abscissa, sl.abscissa
        );
        assert!(d <= 1e-8, "k {k:?} Ω {w}: multipliers differ by {d:e}");
        assert_eq!(ss.verdict, sl.verdict);
        // gravity matters at this tolerance: the multipliers without it (over the same period:
        // exp(λ T), or the π/Ω orbit's squared) are far from those with it
        let moved = match_distance(&per_revolution(&sl0, t), &all_eigenvalues(&sl));
        eprintln!("  gravity moves the multipliers by {moved:.2e}");
        assert!(moved > 1e-6, "k {k:?} Ω {w}: gravity moved the multipliers by only {moved:e}");
    }
}

/// A time simulation in fixed axes (the fixed-axes form, where gravity is a constant load: a
/// different route from the turning axes' rotated load) started on the orbit found in turning
/// axes stays on it: at every whole revolution it is back at the start, to the integration
/// tolerance (rtol 1e-11 over 20 revolutions of a stable orbit: `1e-7` of the scales); started
/// off the orbit by `1e-3` of the scales it returns to it at the rate of the largest Floquet
/// multiplier (the distance after 300 revolutions within 10× `|μ|^300` of the start's, the 10
/// for the mode shapes' non-orthogonality, and below a tenth of it: the orbit attracts; after
/// 40 revolutions it was still 1.1 times the start's, a transient of the non-normal modes).
#[test]
fn time_run_at_a_stable_speed_stays_on_the_orbit() {
    let lin = linear(&locked_tilt_jeffcott([1e5, 1.3e5], [1.0, -9.81]));
    let w = 180.0;
    let rot = LinearRotorField::new(&lin, w, Frame::Rotating).unwrap();
    let fix = LinearRotorField::new(&lin, w, Frame::Fixed).unwrap();
    let (x0, st) = analyse(&rot, &rot.balanced_guess().unwrap());
    assert_eq!(st.verdict, Verdict::Stable, "abscissa {}", st.abscissa);
    let mu = st.spectrum.iter().map(|e| e.complex().norm()).fold(0.0, f64::max);
    let t = 2.0 * PI / w;
    let y0 = rot.rotating_to_fixed(0.0, &x0);
    let s = fix.scales();
    let run = |y: &mut Vec<f64>, revolutions: usize, each: &mut dyn FnMut(usize, &[f64])| {
        let sys = Sys(&fix);
        for k in 1..=revolutions {
            let mut solver = Solver::new(&sys, Options::new(1e-11, 1e-13).method(Method::Dop853)).unwrap();
            assert!(solver.integrate((k - 1) as f64 * t, y, k as f64 * t, |_| Control::Continue).status.is_completed());
            each(k, y);
        }
    };
    let dist = |y: &[f64]| (0..y.len()).map(|i| ((y[i] - y0[i]) / s[i]).abs()).fold(0.0, f64::max);
    let mut y = y0.clone();
    run(&mut y, 20, &mut |k, y| assert!(dist(y) <= 1e-7, "revolution {k}: off the orbit by {:e} of the scales", dist(y)));
    let mut y: Vec<f64> = y0.iter().zip(&s).enumerate().map(|(i, (v, sc))| v + 1e-3 * sc * if i % 2 == 0 { 1.0 } else { -0.5 }).collect();
    let d0 = dist(&y);
    let revs = 300;
    run(&mut y, revs, &mut |_, _| {});
    let dn = dist(&y);
    let decay = mu.powi(revs as i32);
    eprintln!("max |μ| = {mu:.6}: distance {d0:.3e} -> {dn:.3e} after {revs} revolutions (|μ|^{revs} = {decay:.3e})");
    assert!(dn <= 10.0 * decay * d0 && dn < 0.1 * d0, "distance {d0:e} -> {dn:e}, |μ|^{revs} = {decay:e}");
}

/// The library's stability over speed of a linear rotor with gravity gives Floquet verdicts
/// (a periodic orbit at every speed) and the stable range of the spatial model with gravity:
/// the same verdict at each speed, and the located ends within `1e-6` relative (both bisected
/// to `1e-9` in `Ω` on abscissae that carry the multipliers' ~1e-10 error, divided by the
/// abscissa's slope in `Ω`).
#[test]
fn stability_over_speed_with_gravity_is_the_spatial_models() {
    let sp = locked_tilt_jeffcott([1e5, 1e5], [0.0, -9.81]);
    let lin = linear(&sp);
    let speeds: Vec<f64> = (0..8).map(|i| 75.0 + 20.0 * i as f64).collect();
    let l = autobal::linear_rotor::stability::stability_over_speed(&lin, &speeds).unwrap();
    let s = autobal::rotor_stability::stability_over_speed(&Rotor::Spatial(sp), &speeds).unwrap();
    assert_eq!(l.kind, Kind::PeriodicOrbit);
    assert_eq!(s.kind, Kind::PeriodicOrbit);
    for (a, b) in l.points.iter().zip(&s.points) {
        assert!(a.verdict.is_some(), "Ω {}: {:?}", a.omega, a.failure);
        assert_eq!(a.verdict, b.verdict, "Ω {}", a.omega);
    }
    eprintln!("linear {:?}\nspatial {:?}", l.stable_ranges, s.stable_ranges);
    assert!(!l.stable_ranges.is_empty());
    assert_eq!(l.stable_ranges.len(), s.stable_ranges.len());
    for (a, b) in l.stable_ranges.iter().zip(&s.stable_ranges) {
        assert!((a.from - b.from).abs() <= 1e-6 * b.from && (a.to - b.to).abs() <= 1e-6 * b.to, "{a:?} vs {b:?}");
    }
}

/// `export-model` of a reduced rotor with gravity keeps the weight: a reduced rotor's load is
/// the projection `Bᵀ load` of the full one, which is not the `M_r r_g` that reading
/// `gravity = [g_x, g_y]` alone would recompute (the modal pseudo-nodes are no translations),
/// so the export writes `gravity_load` and reading it back gives the same rotor, bit for bit
/// (numbers written in Rust's shortest round-trip form). A full shaft's weight is `M r_g` and
/// needs no key.
#[test]
fn export_of_a_reduced_rotor_keeps_its_weight() {
    use autobal::linear_rotor::config::{export, linear_rotor};
    use autobal::linear_rotor::reduce::reduce;
    use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
    let mut b = ShaftBuilder::uniform(12, 1.0, 0.03, 2.1e11, 7850.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.bearings.push(Bearing { node: 0, k: 1e7, c: 200.0 });
    b.bearings.push(Bearing { node: 12, k: 1e7, c: 200.0 });
    b.disks.push(Disk { node: 4, mass: 3.0, id: 0.01, ip: 0.02 });
    let mut full = b.build().unwrap();
    full.balancers.push(BalancerPlane { node: 4, radius: 0.06, balls: 2, ball_mass: 0.02, drag: 1e-3, offset: 0.0 });
    full.unbalances.push(Unbalance { node: 4, me: 1e-4, phase: 0.0, offset: 0.0 });
    full.set_gravity([0.0, -9.81]);
    let read = |r: &LinearRotor| {
        let (text, files) = export(r, "m");
        let root: toml::Table = text.parse().unwrap();
        let back = linear_rotor(&root, &mut |p| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or("missing".into())).unwrap();
        (text, back.rotor)
    };
    let (text, back) = read(&full);
    assert!(!text.contains("gravity_load"));
    assert_eq!(back, full);
    let red = reduce(&full, 2, &[]).unwrap().rotor;
    let mut recomputed = red.clone();
    recomputed.set_gravity([0.0, -9.81]);
    let (gr, gc) = (&red.gravity.as_ref().unwrap().load, &recomputed.gravity.as_ref().unwrap().load);
    let differ = gr.iter().zip(gc).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(differ > 1e-3 * gr.iter().fold(0.0f64, |m, v| m.max(v.abs())), "the projected weight equals M_r r_g here: the test would not see a dropped load");
    let (text, back) = read(&red);
    assert!(text.contains("gravity_load"));
    assert_eq!(back, red);
}

/// The tilting spatial rotor under gravity (two supports, the tilt free: the preset
/// [`LinearRotor::from_spatial`], its rotor-fixed inertia `ΔA = 0.01` kg m² included) against the
/// native model: the balanced periodic orbit and its Floquet multipliers, equal and unequal
/// supports, below and above the critical speeds. The supports' stiffness centre is put at the
/// centre of mass C, so that the sag translates without tilting (the native model is exact, and
/// linear, in the translation; a tilted sag would bring in its nonlinear tilt terms, measured
/// 1.9e-7 on the multipliers with the supports as in `tests/linear_rotor_spatial_preset.rs`).
/// What remains is the weight's potential at second order in the tilt, which the preset leaves
/// out (the weight of the unbalance mass and of the balls on a tilted rotor,
/// `δκ = g (m e + n m_b R) ≈ 0.05` N m/rad, 2.5e-6 of the tilt stiffness) and the shooting's
/// `1e-8`: measured 1.6e-9 to 2.5e-8 on the multipliers, 4e-10 to 2e-9 of the scales on the
/// orbit. Bounds `1e-7` and `1e-8` (four and five times the largest measured, below the
/// estimate `δκ/κ` of the omitted term), while gravity moves the multipliers by 2.2e-6 to
/// 1.1e-4, more than 20 times the bound (asserted), so a weight dropped, turned or put in the
/// wrong axes fails.
#[test]
fn tilting_preset_under_gravity_against_the_spatial_model() {
    for (k, g, w) in [([1e5, 1e5], [0.0, -9.81], 250.0), ([1e5, 1e5], [1.0, -9.81], 110.0), ([1e5, 1.3e5], [0.0, -9.81], 130.0)] {
        let mut sp = SpatialRotor {
            rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.02, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
            supports: vec![
                Support { z: -0.3, stiffness: k, damping: [20.0, 20.0] },
                Support { z: 0.4, stiffness: [k[0] * 1.2, k[1] * 1.2], damping: [25.0, 25.0] },
            ],
            unbalances: vec![
                PointMass { mass: 0.01, radius: 0.1, angle: 0.4, z: 0.15 },
                PointMass { mass: 0.5, radius: 0.1, angle: 0.9, z: 0.02 },
                PointMass { mass: 0.5, radius: 0.1, angle: 0.9 + PI, z: 0.02 },
            ],
            planes: vec![BallPlane { z: 0.15, n: 2, ball_mass: 0.02, race_radius: 0.1, drag: 0.01, physics: Default::default() }],
            gravity: [g[0], g[1], 0.0],
            spin_drag: 0.0,
            lock_tilt: false,
        };
        // the stiffness centre at C (Σ k ζ = 0): the sag translates without tilting
        let zc = sp.z_reference();
        let ratio = (zc - sp.supports[0].z) / (sp.supports[1].z - zc);
        sp.supports[1].stiffness = [k[0] * ratio, k[1] * ratio];
        let lin = LinearRotor::from_spatial(&sp).unwrap();
        let fs = SpatialField::new(&sp, w).unwrap();
        let fl = LinearRotorField::new(&lin, w, Frame::Rotating).unwrap();
        let (xl, sl) = analyse(&fl, &fl.balanced_guess().unwrap());
        let (xs, ss) = analyse(&fs, &xl);
        let sc = fl.scales();
        let dx = (0..xl.len()).map(|i| (xs[i] - xl[i]).abs() / sc[i]).fold(0.0, f64::max);
        let d = match_distance(&all_eigenvalues(&ss), &all_eigenvalues(&sl));
        let mut nograv = sp.clone();
        nograv.gravity = [0.0; 3];
        let fl0 = LinearRotorField::new(&LinearRotor::from_spatial(&nograv).unwrap(), w, Frame::Rotating).unwrap();
        let (_, sl0) = analyse(&fl0, &fl0.balanced_guess().unwrap());
        let moved = match_distance(&per_revolution(&sl0, 2.0 * PI / w), &all_eigenvalues(&sl));
        let sag = fl.sag().unwrap();
        eprintln!("k {k:?} Ω {w}: orbit differs by {dx:.2e} of the scales, multipliers by {d:.2e}; gravity moves them by {moved:.2e}; sag {sag:?}");
        assert_eq!(ss.kind, Kind::PeriodicOrbit);
        assert!(sag[2].abs() + sag[3].abs() <= 1e-12, "the sag tilts: {sag:?}");
        assert!(dx <= 1e-8, "k {k:?} Ω {w}: orbits differ by {dx:e} of the scales");
        assert!(d <= 1e-7, "k {k:?} Ω {w}: multipliers differ by {d:e}");
        assert!(moved >= 20.0 * 1e-7, "k {k:?} Ω {w}: gravity moves the multipliers by {moved:e} only");
        assert_eq!(ss.verdict, sl.verdict);
    }
}

/// The preset of the tilt-locked spatial rotor ([`LinearRotor::from_spatial`] with
/// `lock_tilt`) is the rotor written by hand above (`linear`): one node `x, y`, the same
/// matrices, unbalance, balls and weight, bit for bit; its polar moment is the carrier's
/// (`C_r + m_u ρ²`), which the hand-written one leaves at 0.
#[test]
fn tilt_locked_preset_is_the_hand_written_rotor() {
    for (k, g) in [([1e5, 1e5], [0.0, -9.81]), ([1e5, 1.3e5], [-2.0, -9.81])] {
        let s = locked_tilt_jeffcott(k, g);
        let p = LinearRotor::from_spatial(&s).unwrap();
        let mut h = linear(&s);
        h.polar_inertia = s.rotor.polar_moment + s.unbalances[0].mass * s.unbalances[0].radius.powi(2);
        assert_eq!(p, h);
    }
}
