//! Families of stationary states (n ≥ 3 balls) and the partially balanced state (capacity
//! short, or paper 004's rotor below the speed where its semi-balanced state exists): each
//! verdict against an independent route (a SymPy/numpy linearisation of Lagrange's equations,
//! the closed form of the balancing condition, a time simulation of the full equations).

mod common;

use autobal::analysis::{
    family, mode, stability, stationary, Family, FamilyOptions, FamilyVerdict, NewtonOptions, Stability, StationaryState, VectorField, Verdict,
};
use autobal::planar::field::PlanarField;
use autobal::planar::{simulate, Drive, Method, PlanarRotor, Settings};
use autobal::rotor_stability::{stability_over_speed, Rotor, StateKind};
use common::{match_distance, planar_case as case_json, python_with, sympy_linearisation};
use num_complex::Complex64;
use std::f64::consts::PI;

/// The Jeffcott rotor (paper 004's with the race centred) with three balls.
fn three_balls() -> PlanarRotor {
    PlanarRotor { n: 3, s2: 0.0, ..PlanarRotor::paper() }
}

fn opts(p: &PlanarRotor) -> FamilyOptions {
    FamilyOptions { angles: (2..2 + p.n).collect(), ..FamilyOptions::default() }
}

/// The family at speed `w` through the member Newton reaches from the closed form.
fn family_at(p: &PlanarRotor, w: f64) -> (PlanarField, Family) {
    let f = PlanarField::new(p, w).unwrap();
    let s = stationary(&f, &f.semi_balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    assert_eq!(s.family_dimension, 1);
    let fam = family(&f, &s, &opts(p)).unwrap();
    (f, fam)
}

/// The abscissa of a spectrum without its eigenvalue nearest 0 (the family's structural zero).
fn abscissa_without_zero(l: &[Complex64]) -> f64 {
    let z = (0..l.len()).min_by(|&a, &b| l[a].norm().total_cmp(&l[b].norm())).unwrap();
    (0..l.len()).filter(|&i| i != z).map(|i| l[i].re).fold(f64::NEG_INFINITY, f64::max)
}

fn all_eigenvalues(st: &Stability) -> Vec<Complex64> {
    st.spectrum.iter().chain(&st.structural).map(|e| e.complex()).collect()
}

#[test]
fn the_three_ball_family_is_swept_all_round_and_is_the_closed_form_balancing_set() {
    // Balanced states of the Jeffcott rotor with n = 3 equal balls: the disk on the axis (u = 0)
    // and m3 r Σ e^{iψ_j} = −m1 s1 (B of planar::stationary with s2 = 0), i.e. Σ e^{iψ_j} = b,
    // |b| = m1 s1/(m3 r) = 5/3. Given ψ_1 the other two exist iff |b − e^{iψ_1}| ≤ 2, so ψ_1
    // spans arg b ± acos((|b|² − 3)/(2|b|)) and the set is one closed curve (|b| > 1). The
    // continuation must return to its start, every member must satisfy the balancing condition
    // (to Newton's tolerance), and ψ_1 must reach both ends of its closed-form span (to the step).
    let p = three_balls();
    let w = 1.06 * p.natural_frequency();
    let (_, fam) = family_at(&p, w);
    assert!(fam.closed, "the continuation did not close after {} members", fam.members.len());
    assert_eq!(fam.dimension, 1);
    let b = -p.m1 * p.s1 / (p.m3 * p.r);
    let half = ((b * b - 3.0) / (2.0 * b.abs())).acos();
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for m in &fam.members {
        let x = &m.state.x;
        assert!(x[0].hypot(x[1]) < 1e-12 * p.s1, "the disk is off the axis: {:?}", &x[..2]);
        let sum = (2..5).fold(Complex64::new(0.0, 0.0), |a, i| a + Complex64::from_polar(1.0, x[i]));
        assert!((sum - b).norm() < 1e-9, "Σ e^(iψ) = {sum} against b = {b} at s = {:?}", m.parameter);
        // ψ_1 relative to arg b = π, in (−π, π]
        let d = (x[2] - PI + PI).rem_euclid(2.0 * PI) - PI;
        lo = lo.min(d);
        hi = hi.max(d);
    }
    // the members are 0.05 apart in the scaled arclength; ψ_1 moves at most that much a step,
    // and near its ends it turns, so it comes within (0.05)²-ish: 0.01 is generous
    assert!((hi - half).abs() < 0.01 && (lo + half).abs() < 0.01, "ψ_1 − arg b spans [{lo}, {hi}], closed form ±{half}");
    // the speed is between the two family boundaries: some members stable, others not
    assert_eq!(fam.verdict(), FamilyVerdict::SomeStable);
    let ranges = fam.stable_ranges();
    // the three balls are equal: their 3! relabellings are members too, so the stable arcs
    // come in a multiple of three (six here: the ball between the other two, and the turn)
    assert_eq!(ranges.len() % 3, 0, "{ranges:?}");
}

#[test]
fn eigenvalues_along_the_family_equal_an_independent_lagrangian_linearisation() {
    // Every 8th member of the family at 1.06 ω_n (where some members are stable and some not)
    // and the extremes: SymPy's Lagrange equations (tests/planar_linearisation.py) give the same
    // eigenvalues, the structural zero included, to 1e-9 ρ (both exact; round-off apart), the
    // member is stationary in their equations too, and their abscissa without the zero has
    // the sign of ours (the verdict of each member).
    let Some(python) = python_with(&["sympy", "numpy"]) else { return };
    let p = three_balls();
    let w = 1.06 * p.natural_frequency();
    let (f, fam) = family_at(&p, w);
    let (hi, lo) = fam.extremes().unwrap();
    let mut chosen: Vec<_> = fam.members.iter().step_by(8).collect();
    chosen.push(hi);
    chosen.push(lo);
    let cases: Vec<_> = chosen.iter().map(|m| case_json(&p, w, &m.state.x)).collect();
    let theirs = sympy_linearisation(&python, &cases);
    let scales = f.scales();
    let (mut stable, mut unstable) = (0, 0);
    for (m, (l, rhs)) in chosen.iter().zip(&theirs) {
        let st = &m.stability;
        let ours = all_eigenvalues(st);
        let d = match_distance(&ours, l);
        assert!(d <= 1e-9 * st.rate, "s = {:?}: eigenvalues differ by {d:e} (ρ = {})", m.parameter, st.rate);
        assert!(rhs.iter().zip(&scales).all(|(v, s)| v.abs() <= 1e-9 * s * st.rate), "s = {:?}: not stationary in their equations: {rhs:?}", m.parameter);
        let a = abscissa_without_zero(l);
        assert!(a.abs() > 1e-6 * st.rate, "s = {:?}: too close to neutral to compare verdicts", m.parameter);
        assert_eq!(a < 0.0, st.verdict == Verdict::Stable, "s = {:?}: their abscissa {a}, ours {}", m.parameter, st.abscissa);
        if a < 0.0 {
            stable += 1;
        } else {
            unstable += 1;
        }
    }
    assert!(stable > 0 && unstable > 0, "{stable} stable and {unstable} unstable members checked");
}

/// Positions `(ξ, η, ψ_j)` in rotor axes of a simulation sample.
fn sample_positions(s: &autobal::planar::Sample) -> Vec<f64> {
    let (sn, cs) = s.theta.sin_cos();
    let mut q = vec![s.x * cs + s.y * sn, -s.x * sn + s.y * cs];
    q.extend(&s.psi);
    q
}

/// Simulate the full planar equations (`planar::simulate`, rotor angle integrated, DOP853) at
/// constant speed from `x0` (reduced state) to `t_end`; the positions `(ξ, η, ψ)` at the end.
fn simulate_from(p: &PlanarRotor, w: f64, x0: &[f64], t_end: f64, rtol: f64) -> Vec<f64> {
    let nr = 2 + p.n;
    let settings = Settings {
        method: Method::Dop853,
        dt: t_end / 8.0,
        rtol,
        atol: 1e-6 * rtol,
        psi0: x0[2..nr].to_vec(),
        psi_rate0: x0[nr + 2..].to_vec(),
        xy0: [x0[0], x0[1]],
        xy_rate0: [x0[nr] - w * x0[1], x0[nr + 1] + w * x0[0]],
        ..Settings::new(p, t_end)
    };
    let mut last = None;
    let summary = simulate(p, &Drive::Speed { omega0: w }, &settings, |s| {
        last = Some(s.clone());
        true
    })
    .unwrap();
    assert!(summary.status.is_completed(), "{:?}", summary.stopped);
    sample_positions(&last.unwrap())
}

/// From `state` moved 1e-7 (of the scales) along its least stable eigenvector, the rate at
/// which a simulation of the full equations grows or decays: `ln(‖δq(t)‖/‖δq(0)‖)/t` on the
/// scaled positions, read after whole periods `2π/|Im λ|` of a complex pair (where the
/// deviation is back in its own direction) with `|α| t ≥ 1`.
fn measured_rate(p: &PlanarRotor, f: &PlanarField, s: &StationaryState, st: &Stability) -> f64 {
    let n = f.dim();
    let nr = n / 2;
    let lambda = st.spectrum[st.least_stable.unwrap()].complex();
    let v = mode(&st.matrix, n, lambda);
    let scales = f.scales();
    let size = v.iter().zip(&scales).map(|(z, s)| z.re.abs() / s).fold(0.0, f64::max);
    let eps = 1e-7 / size;
    let x0: Vec<f64> = s.x.iter().zip(&v).map(|(x, z)| x + eps * z.re).collect();
    let t_end = if lambda.im.abs() > 1e-9 {
        let period = 2.0 * PI / lambda.im.abs();
        period * (1.0 / (lambda.re.abs() * period)).ceil()
    } else {
        1.0 / lambda.re.abs()
    };
    let q = simulate_from(p, f.omega(), &x0, t_end, 1e-12);
    let norm = |d: &mut dyn Iterator<Item = f64>| d.map(|v| v * v).sum::<f64>().sqrt();
    let d0 = norm(&mut (0..nr).map(|i| (x0[i] - s.x[i]) / scales[i]));
    let d1 = norm(&mut (0..nr).map(|i| (q[i] - s.x[i]) / scales[i]));
    (d1 / d0).ln() / t_end
}

#[test]
fn runs_started_near_members_grow_or_decay_at_each_members_rate() {
    // At 1.06 ω_n the least stable member sampled (α > 0) and the most stable (α < 0): a run of
    // the full equations started 1e-7 off each along its least stable eigenvector leaves the
    // first and returns towards the second at the computed rate, to 3 % (the nonlinear terms
    // are 1e-7 of the linear ones; the other modes decay faster, the structural zero is not
    // excited by an eigenvector of another eigenvalue).
    let p = three_balls();
    let w = 1.06 * p.natural_frequency();
    let (f, fam) = family_at(&p, w);
    let (hi, lo) = fam.extremes().unwrap();
    assert!(hi.stability.abscissa > 0.0 && lo.stability.abscissa < 0.0);
    for m in [hi, lo] {
        let l = m.stability.least_stable_exponent().unwrap();
        let rate = measured_rate(&p, &f, &m.state, &m.stability);
        assert!((rate - l.re).abs() <= 0.03 * l.re.abs(), "member ψ = {:?}: measured {rate}, computed {}", &m.state.x[2..5], l.re);
    }
}

#[test]
fn over_speed_the_family_says_where_all_and_where_some_members_are_stable() {
    // n = 3 Jeffcott rotor from 0.9 to 1.4 ω_n: the speed where some member first becomes
    // stable lies below the one where all are; between them every grid point says "some".
    // At each located end the family's extreme member is neutral: its abscissa (without the
    // structural zero) from SymPy's independent linearisation is ~0 (1e-6 ρ; the end is located
    // to 1e-9 in Ω, where α changes by ~0.4 1/s per rad/s).
    let p = three_balls();
    let wn = p.natural_frequency();
    let speeds: Vec<f64> = (0..=25).map(|i| wn * (0.9 + 0.02 * i as f64)).collect();
    let r = stability_over_speed(&Rotor::Planar(p.clone()), &speeds).unwrap();
    assert_eq!(r.family_dimension, 1);
    let fam = r.family.as_ref().unwrap();
    assert!(fam.parameterisation.contains("one-parameter"));
    assert_eq!((fam.all_members_stable.len(), fam.some_members_stable.len()), (1, 1), "{fam:?}");
    let (all, some) = (fam.all_members_stable[0], fam.some_members_stable[0]);
    assert!(all.from_is_boundary && some.from_is_boundary);
    assert!(some.from < all.from && all.from < 1.1 * wn, "some from {} all from {}", some.from, all.from);
    for pt in &r.points {
        let v = pt.family_verdict.unwrap();
        assert_eq!(pt.state, Some(StateKind::Balanced));
        assert_eq!(pt.member_psi.len(), 3);
        if pt.omega > some.from && pt.omega < all.from {
            assert_eq!(v, FamilyVerdict::SomeStable, "at {}", pt.omega);
        } else if pt.omega > all.from {
            assert_eq!(v, FamilyVerdict::AllStable, "at {}", pt.omega);
        } else {
            assert_eq!(v, FamilyVerdict::NoneStable, "at {}", pt.omega);
        }
    }
    let Some(python) = python_with(&["sympy", "numpy"]) else { return };
    let mut cases = vec![];
    let mut rates = vec![];
    for (w, least) in [(all.from, true), (some.from, false)] {
        let (_, fam) = family_at(&p, w);
        let (hi, lo) = fam.extremes().unwrap();
        let m = if least { hi } else { lo };
        assert!(m.stability.abscissa.abs() < 1e-6 * m.stability.rate, "Ω = {w}: α = {}", m.stability.abscissa);
        cases.push(case_json(&p, w, &m.state.x));
        rates.push(m.stability.rate);
    }
    for ((l, _), rho) in sympy_linearisation(&python, &cases).iter().zip(rates) {
        let a = abscissa_without_zero(l);
        assert!(a.abs() < 1e-6 * rho, "their abscissa at the end: {a}");
    }
}

/// Ball angles modulo 2π in (−π, π].
fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(2.0 * PI) - PI
}

/// The state found by `stability_over_speed` at one speed, and a 1e-6 comparison with the end of
/// a constant-speed run from the simulator's default start (balls spread, shaft at rest).
fn bunched_state_against_a_run(p: &PlanarRotor, w: f64, t_end: f64, kind: StateKind) {
    let r = stability_over_speed(&Rotor::Planar(p.clone()), &[w]).unwrap();
    let pt = &r.points[0];
    assert_eq!(pt.state, Some(kind), "{pt:?}");
    assert_eq!(pt.verdict, Some(Verdict::Stable), "{pt:?}");
    let f = PlanarField::new(p, w).unwrap();
    let x = Rotor::bunched_guess(&Rotor::Planar(p.clone()).field(w).unwrap()).unwrap();
    let s = stationary(&f, &x, &NewtonOptions::default()).unwrap();
    let st = stability(&f, &s).unwrap();
    assert!((st.abscissa - pt.abscissa.unwrap()).abs() <= 1e-9 * st.rate);
    // the balls bunched: one angle
    assert!((wrap(s.x[2] - s.x[3])).abs() < 1e-12, "{:?}", &s.x[2..4]);
    let settings = Settings { method: Method::Dop853, dt: t_end / 4.0, rtol: 1e-10, atol: 1e-13, ..Settings::new(p, t_end) };
    let mut last = None;
    simulate(p, &Drive::Speed { omega0: w }, &settings, |x| {
        last = Some(x.clone());
        true
    })
    .unwrap();
    let q = sample_positions(&last.unwrap());
    let scales = f.scales();
    for i in 0..2 {
        assert!((q[i] - s.x[i]).abs() < 1e-6 * scales[i], "{}: run {} pipeline {}", f.component_name(i), q[i], s.x[i]);
    }
    for i in 2..4 {
        assert!(wrap(q[i] - s.x[i]).abs() < 1e-6, "ball angles: run {:?} pipeline {:?}", &q[2..4], &s.x[2..4]);
    }
}

#[test]
fn a_balancer_short_of_capacity_is_partially_balanced_where_a_run_settles() {
    // Jeffcott rotor with two 20 g balls: capacity 2 m3 r = 2.4e-3 kg m against m1 s1 = 3e-3
    // (E = 0.8): no balanced state. At 2 ω_n the balls bunch opposite the unbalance (the
    // aligned whirl, all balls on the far side) with a residual of 20 %; the pipeline says
    // "partially balanced, stable" and a 12 s run (α = −2.7 1/s: e^{−32}) ends on it.
    let p = PlanarRotor { s2: 0.0, m3: 0.02, ..PlanarRotor::paper() };
    bunched_state_against_a_run(&p, 2.0 * p.natural_frequency(), 12.0, StateKind::PartiallyBalanced);
}

#[test]
fn below_its_semi_balanced_speed_paper_004s_rotor_is_partially_balanced_where_a_run_settles() {
    // Paper 004's eccentric race has no semi-balanced state below ~215 rad/s (the balls cannot
    // supply B). There the second guess, the balls bunched on the far side, is the state: at
    // 200 rad/s stable (α = −1.94 1/s), and a 16 s run (e^{−31}) ends on it. Its residual is
    // 1.91 (E 1.91 times farther from the axis than without the balls' resultant): "not
    // balanced" since session 16 (was "partially balanced": the balls do not reduce it).
    let p = PlanarRotor::paper();
    assert!(!autobal::planar::stationary::semi_balanced_exists(&p, 200.0));
    bunched_state_against_a_run(&p, 200.0, 16.0, StateKind::NotBalanced);
}

#[test]
fn a_family_walked_to_a_relabelling_covers_the_whole_family_by_relabelling() {
    // Three equal balls: the cyclic relabellings ψ_j → ψ_{j+1}, ψ_{j+2} (with their rates) map
    // the balancing set Σ e^{iψ_j} = b onto itself. The continuation stopped at the first image
    // of the member given walks a third of the closed family; every member of the whole family
    // (walked all round without relabellings) is then, relabelled, within one step (0.05 rad)
    // of a member of the third (the continuation's own sampling resolution: a member lies at
    // most half a step from the nearest sampled one, doubled for the two samplings' offsets),
    // at 1.00, 1.06 and 1.2 ω_n (none, some and all members stable); the verdict is the whole
    // family's, and the third's extreme abscissae equal the whole family's to the abscissa's
    // change over one step (1e-2 of its range over the family).
    let p = three_balls();
    let wn = p.natural_frequency();
    let cyc = |shift: usize| -> Vec<usize> {
        let mut q: Vec<usize> = (0..10).collect();
        for j in 0..3 {
            q[2 + j] = 2 + (j + shift) % 3;
            q[7 + j] = 7 + (j + shift) % 3;
        }
        q
    };
    for w in [1.0 * wn, 1.06 * wn, 1.2 * wn] {
        let (f, whole) = family_at(&p, w);
        let s = stationary(&f, &f.semi_balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
        let third = family(&f, &s, &FamilyOptions { relabellings: vec![cyc(1), cyc(2)], ..opts(&p) }).unwrap();
        assert!(whole.closed && third.closed);
        assert!((third.length - whole.length / 3.0).abs() < 2.0 * 0.05, "Ω = {w}: {} against {} / 3", third.length, whole.length);
        let angle_gap = |a: &[f64], b: &[f64]| (2..5).map(|i| ((a[i] - b[i] + PI).rem_euclid(2.0 * PI) - PI).abs()).fold(0.0, f64::max);
        for m in &whole.members {
            let near = third
                .members
                .iter()
                .flat_map(|t| [0, 1, 2].map(|k| if k == 0 { t.state.x.clone() } else { cyc(k).iter().map(|&j| t.state.x[j]).collect::<Vec<f64>>() }))
                .map(|y| angle_gap(&m.state.x, &y))
                .fold(f64::INFINITY, f64::min);
            assert!(near <= 0.05, "Ω = {w}: a member {:?} is {near} rad from every relabelled member of the third", &m.state.x[2..5]);
        }
        assert_eq!(whole.verdict(), third.verdict(), "Ω = {w}");
        let (wh, wl) = whole.extremes().unwrap();
        let (th, tl) = third.extremes().unwrap();
        let range = wh.stability.abscissa - wl.stability.abscissa;
        assert!(
            (wh.stability.abscissa - th.stability.abscissa).abs() <= 1e-2 * range,
            "Ω = {w}: largest {} against {}",
            th.stability.abscissa,
            wh.stability.abscissa
        );
        assert!(
            (wl.stability.abscissa - tl.stability.abscissa).abs() <= 1e-2 * range,
            "Ω = {w}: smallest {} against {}",
            tl.stability.abscissa,
            wl.stability.abscissa
        );
    }
}

/// A rigid rotor on two supports at ±0.3 m with `n` balls of `m R = mr` in the plane of its
/// centre of mass and a static unbalance `u` (kg m) there: `n mr = u` is exactly full capacity.
fn one_plane(n: usize, mr: f64, u: f64) -> autobal::spatial::dynamics::SpatialRotor {
    use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
    let support = |z: f64| Support { z, stiffness: [1e5, 1e5], damping: [40.0, 40.0] };
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.0, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
        supports: vec![support(-0.3), support(0.3)],
        unbalances: vec![PointMass { mass: u / 0.125, radius: 0.125, angle: 0.7, z: 0.0 }],
        planes: vec![BallPlane { z: 0.0, n, ball_mass: mr / 0.125, race_radius: 0.125, drag: 0.05, physics: Default::default() }],
        gravity: [0.0; 3],
        spin_drag: 0.0,
        lock_tilt: false,
    }
}

/// At exactly full capacity (`n m R = |u|`, here in binary-exact numbers: 2 × 0.03125 kg ×
/// 0.125 m = 0.0625 kg × 0.125 m) the balanced state is unique: `|Σ m R e^{iψ_j}| = n m R` holds
/// only with every ball at one angle (the triangle inequality's equality case), so there is no
/// family, dimension 0, although the Jacobian of the balancing condition has rank 1 there (the
/// balls spreading by ±δ lose `m R δ²` of their resultant: second order). Main at 21dbfc9
/// counted `n − rank = 1` for two balls ("family of dimension 1") and 2 for three. Above full
/// capacity the closed form's count holds: two balls isolated (0), three a one-parameter
/// family (`n − 2 = 1`). Same on the planar rotor (three balls at full capacity: 0).
#[test]
fn at_exactly_full_capacity_the_balanced_state_is_isolated() {
    let mr = 0.03125 * 0.125;
    for (n, u, dimension) in [(2, 2.0 * mr, 0), (3, 3.0 * mr, 0), (2, 1.5 * mr, 0), (3, 1.5 * mr, 1)] {
        let f = autobal::spatial::dynamics::field::SpatialField::new(&one_plane(n, mr, u), 300.0).unwrap();
        let s = stationary(&f, &f.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
        let m = f.coords();
        let psi = &s.x[m - n..m];
        // the state is balanced: the balls' resultant cancels u (to Newton's 1e-12)
        let (c, sn) = psi.iter().fold((0.0, 0.0), |(c, sn), a| (c + mr * a.cos(), sn + mr * a.sin()));
        assert!((c + u * 0.7f64.cos()).hypot(sn + u * 0.7f64.sin()) <= 1e-12 * u, "n {n}, u {u}: ψ {psi:?}");
        let full = u == n as f64 * mr;
        if full {
            assert!(psi.iter().all(|a| (a - psi[0]).abs() <= 1e-9), "bunched at full capacity: {psi:?}");
        }
        assert_eq!(s.family_dimension, dimension, "n {n}, u/(n m R) {}: ψ {psi:?}", u / (n as f64 * mr));
    }
    // the planar rotor: three balls of m3 r = 0.25 × 0.125 m against m1 s1 = 0.75 × 0.125
    let p = PlanarRotor { n: 3, s2: 0.0, m3: 0.25, r: 0.125, m1: 0.75, s1: 0.125, ..PlanarRotor::paper() };
    let f = PlanarField::new(&p, 400.0).unwrap();
    let s = stationary(&f, &f.semi_balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    assert!(s.x[2..5].iter().all(|a| (a - s.x[2]).abs() <= 1e-9), "{:?}", &s.x[2..5]);
    assert_eq!(s.family_dimension, 0, "{:?}", &s.x[2..5]);
}
