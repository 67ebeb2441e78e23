//! The general route's Campbell diagram and locked critical speeds (`autobal::rotor_campbell`)
//! against independent routes: paper 000's 12-state pencil (eigenvalues) and eq (16) (critical
//! speeds) on one-plane rotors, the Jeffcott rotor's closed form `sqrt(k/m_total)`, and the
//! isotropic eigenvalues on a nearly isotropic rotor analysed as periodic (Floquet exponents).

use autobal::analysis::Kind;
use autobal::planar::PlanarRotor;
use autobal::rotor_campbell::{campbell_over_speed, locked_critical_speeds, Whirl};
use autobal::rotor_stability::Rotor;
use autobal::spatial::critical_speeds::critical_speeds;
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
use autobal::spatial::stability::eigenvalues_at;
use num_complex::Complex64;

mod common;
use common::{Rng, Sys};

/// A random one-plane, two-ball dimensionless rotor (as tests/rotor_stability.rs).
fn random_model(rng: &mut Rng) -> (SpatialModel, SpatialRotor) {
    loop {
        let m0 = rng.range(0.005, 0.04);
        let r0 = rng.range(0.5, 2.5);
        let e = rng.range(1.05, 3.0);
        let r = rng.range(0.5, 2.5);
        let m = e * m0 * r0 / r;
        let inp = DimensionlessInput {
            c_sigma: rng.range(0.3, 1.6),
            rho_s: rng.range(0.25, 0.6),
            l_left: rng.range(0.2, 1.3),
            z_a: rng.range(-1.0, 1.0),
            anisotropy: AnisotropyInput::Masses { masses: MassSet { m0, r0, m, r, n: 2 }, d_a: None },
            h_x: rng.range(0.02, 0.2),
            h_s: rng.range(0.02, 0.5),
            method: AnisotropyMethod::Exact,
            direct_balls: None,
        };
        let Ok(model) = SpatialModel::from_dimensionless(&inp) else { continue };
        if let Ok(rotor) = SpatialRotor::from_dimensionless(&model) {
            return (model, rotor);
        }
    }
}

#[test]
fn the_general_campbell_diagram_has_the_eigenvalues_of_paper_000s_pencil() {
    // One plane, two balls, isotropic supports, no gravity: at every speed each eigenvalue of
    // the general route (exact AD Jacobian of the nonlinear equations at the balanced state
    // found by Newton) has a partner among the 12-state pencil's eigenvalues (000 eq (6)) within
    // 1e-10 (relative to max(1, |λ|)), one to one. Both are balanced QR on 12 x 12 matrices that
    // agree to round-off, and the eigenvalues are simple here (condition numbers ~1-100), so the
    // differences are ~1e-14.
    let mut rng = Rng(5);
    let mut worst = 0.0f64;
    for case in 0..8 {
        let (model, rotor) = random_model(&mut rng);
        let speeds: Vec<f64> = (1..=40).map(|i| 0.1 * i as f64).collect();
        let c = campbell_over_speed(&Rotor::Spatial(rotor), &speeds).unwrap();
        assert_eq!(c.kind, Kind::Equilibrium);
        assert_eq!(c.lines.len(), 12, "case {case}: 12 states");
        for (k, &w) in speeds.iter().enumerate() {
            assert!(c.failures[k].is_none(), "case {case}, Ω = {w}: {:?}", c.failures[k]);
            let (_, theirs) = eigenvalues_at(&model, w, Balls::Free).unwrap();
            let mut used = vec![false; theirs.len()];
            for l in &c.lines {
                let p = l.points[k].unwrap();
                let z = Complex64::new(p.re, p.im);
                let (j, d) = theirs.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, t)| (j, (t - z).norm())).min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
                used[j] = true;
                let rel = d / z.norm().max(1.0);
                worst = worst.max(rel);
                assert!(rel < 1e-10, "case {case}, Ω = {w}: λ = {z} has no 12-state partner (nearest {} off)", d);
            }
        }
    }
    eprintln!("worst relative difference: {worst:e}");
}

#[test]
fn the_locked_critical_speeds_are_paper_000s_eq_16() {
    // Balls locked at balance (point masses of the rotor), no damping: the speeds where the
    // turning-axes stiffness block A(Ω) of the exact Jacobian is singular, bisected to 1e-12 on
    // a grid of 2000, against the closed-form roots of Δ1 Δ2 = 0 (eq (16), spatial::critical_speeds)
    // with the exact inertia tensor of the locked composite rotor: equal to 1e-9 relative.
    let mut rng = Rng(23);
    let (mut compared, mut worst) = (0, 0.0f64);
    for case in 0..10 {
        let (model, rotor) = random_model(&mut rng);
        let exact = critical_speeds(&model);
        let omega_max = 4.0;
        let mut theirs: Vec<f64> = exact.speeds.iter().map(|s| s.omega).filter(|w| *w < omega_max).collect();
        theirs.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        let ours = locked_critical_speeds(&Rotor::Spatial(rotor), omega_max, 2000).unwrap();
        let mine: Vec<f64> = ours.speeds.iter().map(|s| s.omega).collect();
        assert_eq!(mine.len(), theirs.len(), "case {case}: ours {mine:?}, eq (16) {theirs:?}");
        for (a, b) in mine.iter().zip(&theirs) {
            assert!((a - b).abs() <= 1e-9 * b, "case {case}: {a} vs eq (16) {b} ({:e})", (a - b) / b);
            worst = worst.max((a - b).abs() / b);
            compared += 1;
        }
    }
    eprintln!("{compared} critical speeds, worst relative difference {worst:e}");
    assert!(compared >= 15, "only {compared} critical speeds compared");
}

#[test]
fn the_jeffcott_rotors_locked_critical_speed_is_sqrt_k_over_m_total() {
    // Paper 004's rotor with its race centred: with the balls locked it is a Jeffcott rotor of
    // mass m1 + m2 + n m3 on stiffness k, whose critical speed is sqrt(k / m_total) (a
    // translation, double: the whirl is circular). With the race eccentric the balls lock where
    // they hold the race centre on the axis; the rotor's translation is still the same mass on
    // the same spring: the same speed.
    for s2 in [0.0, 0.5e-3] {
        let mut p = PlanarRotor::paper();
        p.s2 = s2;
        p.n = 3;
        let wn = (p.k / (p.m1 + p.m2 + p.n as f64 * p.m3)).sqrt();
        let r = locked_critical_speeds(&Rotor::Planar(p), 3.0 * wn, 300).unwrap();
        assert_eq!(r.speeds.len(), 1, "s2 = {s2}: {:?}", r.speeds);
        assert!((r.speeds[0].omega - wn).abs() <= 1e-9 * wn, "s2 = {s2}: {} vs {wn}", r.speeds[0].omega);
        assert_eq!(r.speeds[0].multiplicity, 2);
    }
}

#[test]
fn balls_of_their_own_masses_lock_into_the_rotors_mass() {
    // Audit 25's F1: a planar rotor with a mass and a drag per ball (`ball_masses`,
    // `ball_drags`) and supports that differ by direction. Locked, it is a point mass
    // m1 + m2 + Σ m_j on springs k_x, k_y: critical speeds sqrt(k_x / M) and sqrt(k_y / M), each
    // simple (the whirl is a line, not a circle), to the bisection's 1e-12 (1e-9 allowed).
    // Before the fix the locked rotor kept the per-ball lists with n = 0 and was refused
    // ("needs one mass per ball (planar.n = 0)"), and its mass used n m3.
    let p = PlanarRotor {
        k: 8.0e4,
        k_y: Some(1.3e5),
        c: 30.0,
        c_y: Some(70.0),
        s2: 5e-4,
        gamma: 0.7,
        r: 0.06,
        ball_masses: Some(vec![0.028, 0.034]),
        ball_drags: Some(vec![0.07, 0.13]),
        ..PlanarRotor::paper()
    };
    let m_total = p.m1 + p.m2 + 0.028 + 0.034;
    let want = [(p.k / m_total).sqrt(), (1.3e5 / m_total).sqrt()];
    let r = locked_critical_speeds(&Rotor::Planar(p), 1.5 * want[1], 400).unwrap();
    let got: Vec<f64> = r.speeds.iter().map(|s| s.omega).collect();
    assert_eq!(got.len(), 2, "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= 1e-9 * w, "{g} vs sqrt(k/M) {w}");
    }
}

#[test]
fn the_jeffcott_campbell_curves_whirl_at_the_natural_frequency() {
    // The planar Jeffcott rotor (race centred) with the balls free: far above the critical
    // speed the rotor's modes are nearly those of the mass on its spring, whose fixed-axes
    // frequency is ±sqrt(k/m_eff) — a forward and a backward whirl. Checked: one forward and
    // one backward curve, and the forward one's frequency within 10 % of sqrt(k/m_total)
    // (the balls' free motion makes the effective mass differ by their few per cent).
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    let wn = p.natural_frequency();
    let c = campbell_over_speed(&Rotor::Planar(p), &[3.0 * wn]).unwrap();
    let pts: Vec<_> = c.lines.iter().filter_map(|l| l.points[0]).filter(|p| p.whirl != Whirl::None && p.im >= 0.0).collect();
    let forward: Vec<f64> = pts.iter().filter(|p| p.whirl == Whirl::Forward && p.fixed_frequency.abs() < 2.0 * wn).map(|p| p.fixed_frequency).collect();
    let backward: Vec<f64> = pts.iter().filter(|p| p.whirl == Whirl::Backward).map(|p| p.fixed_frequency).collect();
    assert!(forward.iter().any(|f| (f - wn).abs() < 0.1 * wn), "forward {forward:?}, ω_n = {wn}");
    assert!(backward.iter().any(|f| (f + wn).abs() < 0.1 * wn), "backward {backward:?}, ω_n = {wn}");
}

fn si_rotor(ratio: f64) -> SpatialRotor {
    let mut r = SpatialRotor::new(
        RigidRotor::aligned(10.0, 0.5, 0.2, 0.0),
        vec![Support::isotropic(-0.3, 1e5, 40.0), Support::isotropic(0.3, 1.5e5, 60.0)],
        vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.0, z: 0.1 }],
        vec![BallPlane::point_masses(0.1, 2, 0.02, 0.08, 0.02)],
    );
    for s in &mut r.supports {
        s.stiffness[0] *= ratio;
    }
    r
}

#[test]
fn floquet_exponents_on_their_branch_continue_the_isotropic_eigenvalues() {
    // Supports that differ by 1e-9: periodic for the pipeline (shooting, monodromy), physically
    // the isotropic rotor. Its Floquet exponents, on the branch of rotor_campbell's rule (the
    // Rayleigh quotient of J(0)), must equal the isotropic rotor's eigenvalues — not merely
    // modulo iΩ: a wrong branch is off by a multiple of Ω (here 100-300 rad/s). Tolerance: the
    // multipliers are good to ~1e-9 (shooting at rtol 1e-10 over one period), i.e. the exponents
    // to ~1e-9 / T; and the anisotropy moves them by ~1e-9 ω: 1e-6 relative to max(|λ|, Ω) is room.
    for omega in [100.0, 180.0, 300.0] {
        let iso = campbell_over_speed(&Rotor::Spatial(si_rotor(1.0)), &[omega]).unwrap();
        let near = campbell_over_speed(&Rotor::Spatial(si_rotor(1.0 + 1e-9)), &[omega]).unwrap();
        assert_eq!(iso.kind, Kind::Equilibrium);
        assert_eq!(near.kind, Kind::PeriodicOrbit);
        let lam: Vec<Complex64> = iso.lines.iter().filter_map(|l| l.points[0]).map(|p| Complex64::new(p.re, p.im)).collect();
        let rho: Vec<Complex64> = near.lines.iter().filter_map(|l| l.points[0]).map(|p| Complex64::new(p.re, p.im)).collect();
        assert_eq!(lam.len(), rho.len());
        for r in &rho {
            let d = lam.iter().map(|l| (l - r).norm()).fold(f64::INFINITY, f64::min);
            let scale = r.norm().max(omega);
            assert!(d < 1e-6 * scale, "Ω = {omega}: ρ = {r} is {d} from every isotropic λ {lam:?}");
        }
    }
}

#[test]
fn critical_speeds_on_supports_that_differ_by_direction() {
    // Supports stiffer along x by 1.3: the locked rotor's linearisation turns with the rotor, so
    // the critical speeds come from fixed axes (Q(Ω) = −A_f − iΩB_f − Ω²I singular).
    // (1) The tilt locked: a mass M_total on Σk_x and Σk_y, critical at sqrt(Σk_x/M) and
    //     sqrt(Σk_y/M) (closed form), each simple.
    let mut r = si_rotor(1.3);
    r.lock_tilt = true;
    let m = r.total_mass();
    let kx: f64 = r.supports.iter().map(|s| s.stiffness[0]).sum();
    let ky: f64 = r.supports.iter().map(|s| s.stiffness[1]).sum();
    let want = [(ky / m).sqrt(), (kx / m).sqrt()];
    let got = locked_critical_speeds(&Rotor::Spatial(r), 1.5 * want[1], 600).unwrap();
    let w: Vec<f64> = got.speeds.iter().map(|s| s.omega).collect();
    assert_eq!(w.len(), 2, "{w:?} vs {want:?}");
    for (a, b) in w.iter().zip(want) {
        assert!((a - b).abs() <= 1e-9 * b, "{a} vs sqrt(k/M) = {b}");
    }
    assert!(got.speeds.iter().all(|s| s.multiplicity == 1));
    // (2) The tilt free, supports differing by 1e-7, and a rotor whose inertia is the same in
    //     every direction (no balls, no unbalance: locked balls and unbalance masses make it
    //     differ, and then the linearisation is periodic in both axes): the fixed-axes route
    //     (translation and tilt pairs rotated into fixed axes) against the turning-axes route of
    //     the isotropic rotor. Turning axes count a circular whirl standing still as two real
    //     eigenvalues of A (multiplicity 2); fixed axes as one complex null vector of Q
    //     (multiplicity 1): the same forward critical speeds, moved by ~1e-7 at most.
    let bare = |ratio: f64| {
        let mut r = si_rotor(ratio);
        r.planes.iter_mut().for_each(|p| p.n = 0);
        r.unbalances.iter_mut().for_each(|u| u.mass = 0.0);
        Rotor::Spatial(r)
    };
    let iso = locked_critical_speeds(&bare(1.0), 400.0, 800).unwrap();
    let near = locked_critical_speeds(&bare(1.0 + 1e-7), 400.0, 800).unwrap();
    // (3) Supports and inertia both differing by direction: said, not guessed.
    let e = locked_critical_speeds(&Rotor::Spatial(si_rotor(1.3)), 400.0, 100).unwrap_err();
    assert!(e.to_string().contains("periodic in both"), "{e}");
    // In fixed axes the backward modes whose frequency equals the speed are critical too (an
    // unbalance excites them through the supports' anisotropy); in the isotropic limit they are
    // not excited, and the turning-axes route does not report them: compared are the forward ones.
    assert!(!iso.speeds.is_empty());
    assert!(iso.speeds.iter().all(|s| s.whirl == Whirl::Forward));
    let forward: Vec<_> = near.speeds.iter().filter(|s| s.whirl == Whirl::Forward).collect();
    assert!(near.speeds.iter().any(|s| s.whirl == Whirl::Backward), "{:?}", near.speeds);
    assert_eq!(forward.len(), iso.speeds.len(), "iso {:?}, near {:?}", iso.speeds, near.speeds);
    for (k, s) in iso.speeds.iter().enumerate() {
        assert_eq!(s.multiplicity, 2);
        assert_eq!(forward[k].multiplicity, 1);
        for t in &forward[k..k + 1] {
            assert!((t.omega - s.omega).abs() <= 1e-7 * s.omega, "{} vs isotropic {}: {:?} {:?}", t.omega, s.omega, iso.speeds, near.speeds);
            assert_eq!(t.motion, s.motion);
        }
    }
}

#[test]
fn a_time_simulation_whirls_at_the_fixed_axes_frequency_and_decays_at_sigma() {
    // Independent of the eigen-analysis's bookkeeping (the forward/backward sign convention, the
    // choice of component): paper 004's Jeffcott rotor (race centred) at 2 ω_n, started at its
    // balanced state plus 1e-6 along the real part of one mode's eigenvector, integrated by
    // DOP853 in turning axes; in fixed axes W(t) = (δξ + iδη) e^{iΩt}. W's mean angular rate
    // over 10 cycles is the frequency of its larger circular component (a winding number), the
    // Campbell diagram's signed fixed_frequency; its log-amplitude's slope (least squares) is σ.
    // Measured: f to 2e-6, σ to 6e-5 (the minor component's modulation of |W| and arg W over a
    // window that is not a whole number of beats); held to 1e-4 and 1e-2. A wrong whirl sign is
    // off by 2f, a wrong mode by its frequency or σ.
    use autobal::analysis::{mode, stationary, VectorField};
    use autobal::planar::field::PlanarField;
    let mut p = PlanarRotor::paper();
    p.s2 = 0.0;
    let wn = p.natural_frequency();
    let omega = 2.0 * wn;
    let c = campbell_over_speed(&Rotor::Planar(p.clone()), &[omega]).unwrap();
    let field = PlanarField::new(&p, omega).unwrap();
    let n = field.dim();
    let x0 = stationary(&field, &field.semi_balanced_guess().unwrap(), &Default::default()).unwrap().x;
    let mut jac = vec![0.0; n * n];
    field.jacobian(0.0, &x0, &mut jac);
    for whirl in [Whirl::Forward, Whirl::Backward] {
        let pt = c
            .lines
            .iter()
            .filter_map(|l| l.points[0])
            .filter(|q| q.whirl == whirl && q.im > 0.0 && !q.structural)
            .min_by(|a, b| (a.fixed_frequency.abs() - wn).abs().total_cmp(&(b.fixed_frequency.abs() - wn).abs()))
            .unwrap();
        assert!((pt.fixed_frequency.abs() - wn).abs() < 0.2 * wn, "{pt:?}");
        let v = mode(&jac, n, Complex64::new(pt.re, pt.im));
        let big = v.iter().map(|z| z.re.abs()).fold(0.0, f64::max);
        let len = p.s1.max(p.r);
        let mut y: Vec<f64> = x0.iter().zip(&v).map(|(x, z)| x + 1e-6 * len * z.re / big).collect();
        let sys = Sys(&field);
        let opts = autobal::ode::Options::new(1e-11, 1e-15).method(autobal::ode::Method::Dop853);
        let mut s = autobal::ode::Solver::new(&sys, opts).unwrap();
        let cycles = 10.0;
        let t_end = cycles * 2.0 * std::f64::consts::PI / pt.fixed_frequency.abs();
        let steps = 2000;
        let (mut t, mut phase, mut last) = (0.0, 0.0, None::<f64>);
        let mut fit = vec![];
        for k in 0..=steps {
            let tk = t_end * k as f64 / steps as f64;
            if tk > t {
                let out = s.integrate(t, &mut y, tk, |_| autobal::ode::Control::Continue);
                assert!(out.status.is_completed(), "{out}");
                t = tk;
            }
            let w = Complex64::new(y[0] - x0[0], y[1] - x0[1]) * Complex64::from_polar(1.0, omega * t);
            let a = w.arg();
            if let Some(l) = last {
                let mut d = a - l;
                d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
                phase += d;
            }
            last = Some(a);
            fit.push((t, w.norm().ln()));
        }
        let rate = phase / t_end;
        eprintln!("{whirl:?}: f = {} simulated {rate}", pt.fixed_frequency);
        assert!((rate - pt.fixed_frequency).abs() < 1e-4 * pt.fixed_frequency.abs(), "{whirl:?}: simulated {rate} vs f = {}", pt.fixed_frequency);
        let m = fit.len() as f64;
        let (st, sl) = (fit.iter().map(|p| p.0).sum::<f64>() / m, fit.iter().map(|p| p.1).sum::<f64>() / m);
        let slope = fit.iter().map(|p| (p.0 - st) * (p.1 - sl)).sum::<f64>() / fit.iter().map(|p| (p.0 - st).powi(2)).sum::<f64>();
        eprintln!("{whirl:?}: σ = {} simulated {slope}", pt.re);
        assert!((slope - pt.re).abs() < 1e-2 * pt.re.abs(), "{whirl:?}: simulated decay {slope} vs σ = {}", pt.re);
    }
}
