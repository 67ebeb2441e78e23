//! Linear rotors with two balancer planes: the closed-form balanced state
//! ([`LinearRotorField::balanced_guess`] for `P ≥ 2` planes: the race centres held on the axis)
//! against the native spatial model of the same rigid rotor (`LinearRotor::from_spatial`, as
//! `tests/linear_rotor_spatial_preset.rs`), its exactness for a rigid rotor, and a flexible
//! shaft with two planes through the general speed scan and a time simulation.

use autobal::analysis::{stability, stationary, NewtonOptions, VectorField, Verdict};
use autobal::linear_rotor::shaft::{Bearing, Disk, Element, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, Frame, LinearRotor, LinearRotorField, Unbalance};
use autobal::rotor_stability::{stability_over_speed, Rotor, StateKind};
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialField, SpatialRotor, Support};
use std::f64::consts::PI;

/// The two-plane rotor of `tests/linear_rotor_spatial_preset.rs` (equal supports): a rigid
/// rotor (`M_r = 10` kg, `A_r = 0.5`, `C_r = 0.2` kg m²) on supports at `−0.3` and `0.4` m
/// (`k` and `1.2 k`, damping 20 and 25 N s/m), balancer planes at 0.15 and −0.2 m, an unbalance
/// mass in the first plane, a second out of both and the principal axis tilted by 0.002 (a
/// couple unbalance, so both planes carry a share); `da`: two opposite 0.5 kg masses (an
/// inertia anisotropy fixed to the rotor).
fn two_plane(k: f64, da: bool, balls: usize) -> SpatialRotor {
    let ball = |z: f64| BallPlane { z, n: balls, ball_mass: 0.02, race_radius: 0.1, drag: 0.01, physics: Default::default() };
    let mut unbalances = vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.4, z: 0.15 }, PointMass { mass: 0.006, radius: 0.08, angle: 2.2, z: 0.05 }];
    if da {
        unbalances.push(PointMass { mass: 0.5, radius: 0.1, angle: 0.9, z: 0.02 });
        unbalances.push(PointMass { mass: 0.5, radius: 0.1, angle: 0.9 + PI, z: 0.02 });
    }
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.02, axis_tilt: 0.002, axis_tilt_angle: 0.7 },
        supports: vec![Support { z: -0.3, stiffness: [k, k], damping: [20.0, 20.0] }, Support { z: 0.4, stiffness: [1.2 * k, 1.2 * k], damping: [25.0, 25.0] }],
        unbalances,
        planes: vec![ball(0.15), ball(-0.2)],
        gravity: [0.0; 3],
        spin_drag: 0.0,
        lock_tilt: false,
    }
}

/// The general speed scan ([`stability_over_speed`], what `autobal stability` runs) on the
/// two-plane preset finds the balanced state at every speed above the critical speeds (before
/// this closed form it found none: every speed a failure), and it is the native model's: ball
/// angles to `1e-9` rad, the rotor on the axis, the abscissa to `1e-9` of the fastest rate.
/// Tolerances: both states are Newton's to a scaled residual of ~1e-12 of equations whose
/// linearisations agree to round-off (`tests/linear_rotor_spatial_preset.rs`), so angles agree
/// to ~1e-12; an error in a plane's share moves them by its relative size (>1e-3 for any
/// wrong coefficient). The abscissa: eigenvalues of matrices equal to round-off, well separated.
#[test]
fn speed_scan_finds_the_native_balanced_state_at_every_speed() {
    for (da, balls) in [(false, 2), (true, 2), (true, 3)] {
        let s = two_plane(1e5, da, balls);
        let lin = LinearRotor::from_spatial(&s).unwrap();
        let top = *lin.natural_frequencies(&[], true).unwrap().last().unwrap();
        let speeds: Vec<f64> = [1.3, 1.8, 2.5, 4.0].iter().map(|f| f * top).collect();
        let scan = stability_over_speed(&Rotor::Linear(lin.clone()), &speeds).unwrap();
        for (p, &w) in scan.points.iter().zip(&speeds) {
            assert!(p.failure.is_none() && p.verdict.is_some(), "da {da}, {balls} balls, Ω {w}: {:?}", p.failure);
            assert_eq!(p.state, Some(StateKind::Balanced), "Ω {w}");
            assert!(p.amplitude.unwrap() <= 1e-12, "Ω {w}: amplitude {:?}", p.amplitude);
            let fs = SpatialField::new(&s, w).unwrap();
            let fl = LinearRotorField::new(&lin, w, Frame::Rotating).unwrap();
            let ss = stationary(&fs, &fs.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
            let st = stability(&fs, &ss).unwrap();
            let n = lin.dofs();
            if balls == 2 {
                // isolated state: the same balls, up to their labels within a plane
                let sorted = |v: &[f64]| {
                    let mut v: Vec<f64> = v.iter().map(|a| a.rem_euclid(2.0 * PI)).collect();
                    v.sort_by(f64::total_cmp);
                    v
                };
                for q in 0..2 {
                    let (a, b) = (sorted(&p.member_psi[2 * q..2 * q + 2]), sorted(&ss.x[n + 2 * q..n + 2 * q + 2]));
                    for j in 0..2 {
                        let d = (a[j] - b[j] + PI).rem_euclid(2.0 * PI) - PI;
                        assert!(d.abs() <= 1e-9, "da {da}, Ω {w}: plane {q}: ψ {a:?} vs native {b:?}");
                    }
                }
                assert!((p.abscissa.unwrap() - st.abscissa).abs() <= 1e-9 * st.rate, "Ω {w}: abscissa {:?} vs {}", p.abscissa, st.abscissa);
                assert_eq!(p.verdict, Some(st.verdict), "Ω {w}");
            }
            // the linear field's guess itself: the native balanced state (the rotor on the axis)
            let g = fl.balanced_guess().unwrap();
            let sc = fl.scales();
            for i in 0..n {
                assert!(g[i].abs() <= 1e-12 * sc[i], "Ω {w}: guess {} = {:e}", fl.component_name(i), g[i]);
            }
            eprintln!("da {da}, {balls} balls, Ω {w:.1}: {:?}, abscissa {:.4e} (native {:.4e})", p.verdict, p.abscissa.unwrap(), st.abscissa);
        }
    }
}

/// For a rigid rotor the balanced state has the rotor on the axis (both race centres at rest
/// on it fix the translation and the tilt), so the closed form is exact whatever the damping,
/// gyroscopic or rotor-fixed terms: the field's residual there is round-off, below `1e-9` of
/// `Ω² l` (`l` the displacement scale; the terms are `O(Ω² l)` and summed over a few dozen
/// entries, round-off ~1e-15 of them; a wrong ball share leaves `O(Ω² l)`), and Newton's method
/// takes at most one step. Both frames (fixed axes: the state of the turning one transformed).
#[test]
fn the_guess_is_the_exact_balanced_state_of_a_rigid_two_plane_rotor() {
    for (da, balls, w) in [(false, 2, 90.0), (true, 2, 140.0), (true, 3, 400.0), (false, 4, 700.0)] {
        let lin = LinearRotor::from_spatial(&two_plane(1e5, da, balls)).unwrap();
        for frame in [Frame::Rotating, Frame::Fixed] {
            let f = LinearRotorField::new(&lin, w, frame).unwrap();
            let g = f.balanced_guess().unwrap();
            let dim = f.dim();
            let mut r = vec![0.0; dim];
            f.rhs(0.0, &g, &mut r);
            let big = w * w * f.scales()[0];
            let worst = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(worst <= 1e-9 * big, "Ω {w}, {frame:?}: residual {worst:e} (Ω² l = {big:e})");
            if frame == Frame::Rotating {
                let s = stationary(&f, &g, &NewtonOptions::default()).unwrap();
                assert!(s.iterations <= 1, "Ω {w}: {} Newton iterations", s.iterations);
            }
        }
    }
    // the one-plane result is untouched; a plane with one ball has no guess
    let mut one = LinearRotor::from_spatial(&two_plane(1e5, false, 2)).unwrap();
    one.balancers[1].balls = 1;
    assert!(LinearRotorField::new(&one, 300.0, Frame::Rotating).unwrap().balanced_guess().is_none());
    // balls too light for their share: no balanced state
    let mut light = LinearRotor::from_spatial(&two_plane(1e5, false, 2)).unwrap();
    for b in &mut light.balancers {
        b.ball_mass = 1e-4;
    }
    assert!(LinearRotorField::new(&light, 300.0, Frame::Rotating).unwrap().balanced_guess().is_none());
}

/// A flexible shaft (six Euler–Bernoulli elements with rotary inertia and gyroscopic terms, 0.9
/// m, two disks carrying the balancer planes, bearings at the ends) with unbalances off the
/// planes, so the balanced shaft deflects between them while the race centres rest on the axis.
fn flexible() -> LinearRotor {
    let mut b = ShaftBuilder { rotary_inertia: true, gyroscopic: true, ..Default::default() };
    for _ in 0..6 {
        b.elements.push(Element::circular(0.15, 0.04, 2.1e11, 7800.0));
    }
    b.disks.push(Disk { node: 2, mass: 4.0, id: 0.02, ip: 0.04 });
    b.disks.push(Disk { node: 4, mass: 3.0, id: 0.015, ip: 0.03 });
    b.bearings.push(Bearing { node: 0, k: 5e6, c: 400.0 });
    b.bearings.push(Bearing { node: 6, k: 5e6, c: 400.0 });
    let mut r = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 1, me: 2e-4, phase: 0.3, offset: 0.0 });
    r.unbalances.push(Unbalance { node: 3, me: 1.5e-4, phase: 2.5, offset: 0.0 });
    r.unbalances.push(Unbalance { node: 5, me: 1e-4, phase: -1.0, offset: 0.0 });
    for node in [2, 4] {
        r.balancers.push(BalancerPlane { node, radius: 0.06, balls: 2, ball_mass: 0.01, drag: 0.02, offset: 0.0 });
    }
    r
}

/// The flexible two-plane shaft: the speed scan finds the balanced state at every speed from
/// above the second critical speed, the guess is within Newton's reach (≤ 6 iterations; on a
/// flexible shaft it is exact only to first order: the balancer nodes tilt at balance, and the
/// tilted ring pushes the balls at second order, below), and where the state is stable a time simulation in fixed axes
/// (RK4, 400 steps a revolution, 20 revolutions) from it stays there: the balls' angles relative
/// to the rotor move by less than `1e-6` rad (RK4's error over the run is ~(Ω h)⁴ ≈ 6e-10 of
/// the motion; the state's residual is Newton's 1e-12).
#[test]
fn a_flexible_shaft_with_two_planes_balances_above_its_second_critical_speed() {
    let r = flexible();
    let crit = r.natural_frequencies(&[], true).unwrap();
    let w2 = crit[2]; // crit[0], crit[1]: the first mode in x and y (isotropic)
    assert!((crit[1] - crit[0]).abs() <= 1e-6 * crit[0] && w2 > 1.5 * crit[1], "{crit:?}");
    let speeds: Vec<f64> = [1.2, 1.5, 2.0].iter().map(|f| f * w2).collect();
    let scan = stability_over_speed(&Rotor::Linear(r.clone()), &speeds).unwrap();
    let n = r.dofs();
    let mut stable = 0;
    for (p, &w) in scan.points.iter().zip(&speeds) {
        assert!(p.failure.is_none() && p.verdict.is_some(), "Ω {w}: {:?}", p.failure);
        assert_eq!(p.state, Some(StateKind::Balanced), "Ω {w}");
        let f = LinearRotorField::new(&r, w, Frame::Rotating).unwrap();
        let s = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
        assert!(s.iterations <= 6, "Ω {w}: {} iterations", s.iterations);
        // the race centres: at rest for the balls to second order in the amplitude. The ball's
        // equation has the tilted ring's term −m_b R² σ_j (ω·e_j) (module docs of
        // `linear_rotor`), with σ_j, ω·e_j ∝ Ω|τ| at rest in turning axes: a tangential push
        // O(m_b R² Ω² τ²) that the race centre's m_b R Ω² e⊥_j·u_p balances, so e⊥_j·u_p =
        // O(R τ²) and the closed form (u_p = 0) is exact to first order (measured ratios 100.1-100.7). (u_p itself is larger:
        // the two balls of a plane are nearly opposite when its share is small, e⊥_1 ≈ −e⊥_2,
        // and u_p along them is O(R τ²) over the gap.) Checked: the largest e⊥_j·u_p shrinks
        // 100-fold (90-110) when every unbalance does 10-fold (τ ∝ ε, the next term O(ε⁴)); a
        // first-order error of the closed form would give 10.
        let push = |eps: f64| -> (f64, usize) {
            let mut re = r.clone();
            re.unbalances.iter_mut().for_each(|u| u.me *= eps);
            let fe = LinearRotorField::new(&re, w, Frame::Rotating).unwrap();
            let se = stationary(&fe, &fe.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
            let mut worst = 0.0f64;
            for (q, node) in [2, 4].into_iter().enumerate() {
                let (ix, iy, _) = re.node_dofs(node);
                for j in 0..2 {
                    let psi = se.x[n + 2 * q + j];
                    worst = worst.max((-psi.sin() * se.x[ix] + psi.cos() * se.x[iy]).abs());
                }
            }
            (worst, se.iterations)
        };
        let ((o1, i1), (o2, i2)) = (push(0.1), push(0.01));
        let ratio = o1 / o2;
        eprintln!("Ω {w:.1}: largest e⊥·u {o1:.3e} m at ε = 0.1, then {o2:.3e} at ε = 0.01 (ratio {ratio:.1}); {i1}, {i2} Newton iterations");
        assert!((90.0..110.0).contains(&ratio), "Ω {w}: ratio {ratio}");
        assert!(i1.max(i2) <= 6, "Ω {w}: {i1}, {i2} Newton iterations");
        // the shaft deflects between the planes (the test is not the trivial p = 0)
        let defl = r.node_dofs(3);
        let mid = s.x[defl.0].hypot(s.x[defl.1]);
        eprintln!(
            "Ω {w:.1} (ω2 {w2:.1}): {:?}, abscissa {:.3e}, {} Newton iterations, mid-span deflection {mid:.3e} m",
            p.verdict,
            p.abscissa.unwrap(),
            s.iterations
        );
        assert!(mid > 1e-9, "Ω {w}: mid-span {mid:e}");
        if p.verdict != Some(Verdict::Stable) {
            continue;
        }
        stable += 1;
        let ff = LinearRotorField::new(&r, w, Frame::Fixed).unwrap();
        let mut x = f.rotating_to_fixed(0.0, &s.x);
        let psi0 = x[n..n + 4].to_vec();
        let dim = ff.dim();
        let h = 2.0 * PI / w / 400.0;
        let (mut k1, mut k2, mut k3, mut k4, mut y) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
        let mut drift = 0.0f64;
        for step in 0..8000 {
            let t = step as f64 * h;
            ff.rhs(t, &x, &mut k1);
            (0..dim).for_each(|i| y[i] = x[i] + 0.5 * h * k1[i]);
            ff.rhs(t + 0.5 * h, &y, &mut k2);
            (0..dim).for_each(|i| y[i] = x[i] + 0.5 * h * k2[i]);
            ff.rhs(t + 0.5 * h, &y, &mut k3);
            (0..dim).for_each(|i| y[i] = x[i] + h * k3[i]);
            ff.rhs(t + h, &y, &mut k4);
            (0..dim).for_each(|i| x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
            drift = drift.max((0..4).map(|j| (x[n + j] - psi0[j]).abs()).fold(0.0, f64::max));
        }
        eprintln!("Ω {w:.1}: balls moved by {drift:.2e} rad over 20 revolutions");
        assert!(drift < 1e-6, "Ω {w}: balls moved by {drift:e} rad");
    }
    eprintln!("{stable} of {} speeds stable", speeds.len());
    // measured: all three stable; the simulation must have run at least once
    assert!(stable >= 1, "no stable speed: the simulation check did not run");
}
