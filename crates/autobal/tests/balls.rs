//! Real balls (finite size, contact, rolling resistance) in the planar model: end states of
//! simulations against static equilibria computed here independently in closed form, an impact
//! against its restitution coefficient and the invariants it must keep, and the regularisation's
//! error vanishing with its parameter.

use autobal::balls::{can_rest, capacity, min_separation, packed_resultant, steel_diameter, BallPhysics};
use autobal::planar::stationary::{capacity_ratio, locked_amplitude};
use autobal::planar::{energy, initial_state, simulate, Drive, PlanarRotor, Sample, Settings, Summary};
use num_complex::Complex64 as C;
use std::f64::consts::PI;

mod common;
use common::planar_as_spatial;

/// The last sample of a run at constant speed `w` from ball angles `psi0`.
fn run_at(p: &PlanarRotor, w: f64, psi0: &[f64], t_end: f64) -> (Summary, Sample) {
    run_from(p, w, psi0, t_end, false)
}

/// [`run_at`], with C started in the steady whirl of the balls held at `psi0` when `steady`
/// (`Z = u` at θ = 0, `Ż = iω Z`), so no transient shakes the balls.
fn run_from(p: &PlanarRotor, w: f64, psi0: &[f64], t_end: f64, steady: bool) -> (Summary, Sample) {
    let mut settings = Settings { psi0: psi0.to_vec(), dt: t_end / 200.0, ..Settings::new(p, t_end) };
    if steady {
        let u = steady_p(p, w, psi0) - C::from_polar(p.s2, p.gamma);
        let v = C::new(0.0, w) * u;
        settings.xy0 = [u.re, u.im];
        settings.xy_rate0 = [v.re, v.im];
    }
    let mut last = None;
    let s = simulate(p, &Drive::Speed { omega0: w }, &settings, |x| {
        last = Some(x.clone());
        true
    })
    .unwrap();
    assert!(s.stopped.is_none(), "{:?}", s.stopped);
    (s, last.unwrap())
}

/// C in rotor axes, `u = (X + iY) e^{−iθ}`.
fn u_of(s: &Sample) -> C {
    C::new(s.x, s.y) * C::from_polar(1.0, -s.theta)
}

/// `H = ω²/(k − m0 ω² + i c ω)`: the steady whirl `u = H U` of a total unbalance `U` (rotor axes).
fn receptance(p: &PlanarRotor, w: f64) -> C {
    C::new(w * w, 0.0) / C::new(p.k - p.total_mass() * w * w, p.c * w)
}

/// The race centre `P = u + s2 e^{iγ}` of the steady whirl with the balls held at `psi`.
fn steady_p(p: &PlanarRotor, w: f64, psi: &[f64]) -> C {
    let e = C::from_polar(p.s2, p.gamma);
    let mut u = C::new(p.m1 * p.s1, 0.0) + e * (p.m2 + p.n as f64 * p.m3);
    for a in psi {
        u += C::from_polar(p.m3 * p.r, *a);
    }
    receptance(p, w) * u + e
}

fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(2.0 * PI) - PI
}

/// Paper 004's rotor with balls of finite size, stiffer than the default (contact frequency
/// 100 sqrt(k/m0)) so that the overlap stays below 1e-5 rad of the closed forms' positions.
fn contact_rotor(m3: f64) -> PlanarRotor {
    PlanarRotor { balls: BallPhysics { contact: true, contact_stiffness: Some(4e6), ..Default::default() }, ..PlanarRotor::paper_004(m3) }
}

/// Two touching balls at rest relative to the rotor at speed `w`: the pair's centre angle `β`
/// and the whirl radius `|u|` of C (see the test below for the derivation).
fn touching_pair(p: &PlanarRotor, w: f64) -> (f64, f64) {
    let sep = min_separation(p.balls.diameter(p.m3), p.r);
    let h = receptance(p, w);
    let e = C::from_polar(p.s2, p.gamma);
    let wv = h * (C::new(p.m1 * p.s1, 0.0) + e * (p.m2 + 2.0 * p.m3)) + e;
    let g = h * 2.0 * p.m3 * p.r * (sep / 2.0).cos();
    let a = (-g.im / wv.norm()).asin();
    let candidates: Vec<f64> =
        [wv.arg() - a, wv.arg() - PI + a].into_iter().filter(|b| ((wv + g * C::from_polar(1.0, *b)) * C::from_polar(1.0, -b)).re > 0.0).collect();
    assert_eq!(candidates.len(), 1, "{candidates:?}");
    let beta = candidates[0];
    (beta, (wv + g * C::from_polar(1.0, beta) - e).norm())
}

#[test]
fn two_touching_balls_rest_where_the_closed_form_puts_them() {
    // Too little ball mass to balance (m3 = 10 g): point masses end on top of each other; real
    // balls end touching, at β ± Δc/2. With d1 + d2 = 2 cos(Δc/2) e^{iβ}, P = W + G e^{iβ}
    // (W = H U0 + s2 e^{iγ}, G = 2 H m3 r cos(Δc/2)); the pair is in equilibrium (the contact is
    // internal) where the pair's torque vanishes, Im(P e^{−iβ}) = 0, i.e.
    // |W| sin(arg W − β) = −Im G, with the pair on P's side (Re(P e^{−iβ}) > 0: the balls
    // move outwards, away from the axis).
    let p = contact_rotor(0.01);
    let w = 400.0;
    let d = steel_diameter(p.m3);
    let sep = min_separation(d, p.r);
    assert!((sep - 0.2247).abs() < 1e-3, "{sep}");
    let (beta, _) = touching_pair(&p, w);
    // start apart on either side of the unbalance's far side, at rest relative to the rotor
    let (s, last) = run_at(&p, w, &[PI - 0.6, PI + 0.5], 20.0);
    assert!(s.settled, "{s:?}");
    assert!(s.contacts >= 1, "{s:?}");
    let mid = 0.5 * (last.psi[0] + last.psi[1]);
    let gap = last.psi[1] - last.psi[0];
    // the overlap under the pair's load F: δ = F/k_c ≈ 1e-7 m, an angle δ/(r cos) ≈ 2e-6
    assert!((gap - sep).abs() < 1e-5, "separation {gap} vs Δc = {sep}");
    assert!(gap < sep, "touching balls press on each other: {gap} vs {sep}");
    assert!(wrap(mid - beta).abs() < 1e-5, "pair centre {mid} vs closed form {beta}");
    // and the rotor whirls as the locked closed form says for that configuration
    let locked = locked_amplitude(&p, w, &last.psi);
    assert!((last.amplitude - locked).abs() < 1e-6 * locked, "{} vs {locked}", last.amplitude);
}

#[test]
fn resting_contact_converges_as_the_stiffness_grows() {
    // the overlap, and with it the error of the positions, scales as 1/k_c
    let sep = min_separation(steel_diameter(0.01), 0.06);
    let err = |k: f64| {
        let mut p = contact_rotor(0.01);
        p.balls.contact_stiffness = Some(k);
        let (_, last) = run_at(&p, 400.0, &[PI - 0.6, PI + 0.5], 20.0);
        sep - (last.psi[1] - last.psi[0])
    };
    let (e1, e2) = (err(1e6), err(1e7));
    assert!(e1 > 0.0 && e2 > 0.0);
    let ratio = e1 / e2;
    assert!((ratio - 10.0).abs() < 0.5, "overlap ratio {ratio} for 10× the stiffness ({e1}, {e2})");
}

#[test]
fn capacity_of_touching_balls_decides_balancing() {
    // E on the axis (s2 = 0): balancing means u → 0, possible while m1 s1 ≤ the balls' largest
    // resultant. 3 steel balls of 10 g on r = 60 mm: point masses 0.0018 kg·m, packed real balls
    // m3 r (1 + 2 cos Δc) = 0.0017698 kg·m. An unbalance between the two is balanced by point
    // masses and not by real balls, which end packed with the residual unbalance m1 s1 − capacity.
    let mut p = PlanarRotor { n: 3, s2: 0.0, ..PlanarRotor::paper_004(0.01) };
    let cap = capacity(3, p.m3, steel_diameter(p.m3), p.r);
    assert!((cap - p.m3 * p.r * (1.0 + 2.0 * min_separation(steel_diameter(p.m3), p.r).cos())).abs() < 1e-15);
    assert!((cap - 0.001_769_8).abs() < 1e-7, "{cap}");
    p.s1 = 0.5 * (cap + 3.0 * p.m3 * p.r) / p.m1;
    let w = 3.0 * p.natural_frequency();
    let start = [PI - 0.8, PI, PI + 0.9];
    let residual = p.m1 * p.s1 - cap;
    let expected = receptance(&p, w).norm() * residual;
    let (s, last) = run_at(&p, w, &start, 30.0);
    assert!(last.amplitude < 0.05 * expected, "point masses balance: {} m ({s:?})", last.amplitude);
    let sep = min_separation(steel_diameter(p.m3), p.r);
    assert!(last.psi[1] - last.psi[0] < sep, "…on top of each other: {:?}", last.psi);
    p.balls.contact = true;
    let (s, last) = run_at(&p, w, &start, 30.0);
    assert!(s.settled, "{s:?}");
    assert!((last.psi[1] - last.psi[0] - sep).abs() < 1e-5 && (last.psi[2] - last.psi[1] - sep).abs() < 1e-5, "packed: {:?}", last.psi);
    // centred at β, where the packed arc's torque vanishes: P = H (m1 s1 + cap e^{iβ}) ∥ e^{iβ},
    // i.e. m1 s1 sin(φ − β) + cap sin φ = 0 (φ = arg H, the damping's phase lag)
    let phi = receptance(&p, w).arg();
    let beta = phi + (cap * phi.sin() / (p.m1 * p.s1)).asin(); // the root with Re(P e^{−iβ}) > 0
    assert!((receptance(&p, w) * (C::new(p.m1 * p.s1, 0.0) + C::from_polar(cap, beta)) * C::from_polar(1.0, -beta)).re > 0.0);
    assert!(wrap(last.psi[1] - beta).abs() < 1e-5, "centred at {beta}: {:?}", last.psi);
    // residual whirl: the locked closed form with the packed balls, |H| |m1 s1 + cap e^{iβ}|
    let expected = receptance(&p, w).norm() * (C::new(p.m1 * p.s1, 0.0) + C::from_polar(cap, beta)).norm();
    assert!((last.amplitude - expected).abs() < 1e-3 * expected, "{} vs {expected}", last.amplitude);
    // the point-mass capacity condition overstates what real balls do
    assert!(packed_resultant(3, sep) < 3.0);
}

#[test]
fn an_impact_honours_the_restitution_coefficient_and_keeps_momentum() {
    // Two balls on a housing too heavy to move (m1, m2 = 1000 kg, at rest: ω = 0), ball 1
    // rolling into ball 2 at 1 rad/s: afterwards their relative speed is reversed and multiplied
    // by e, the balls' angular momentum m3 r² (ψ̇1 + ψ̇2) is kept (to O(m3/m0)), and with e = 1
    // the energy (contact energy included) is kept.
    for e in [1.0, 0.5, 0.2] {
        let p = PlanarRotor {
            m1: 1000.0,
            m2: 1000.0,
            s1: 0.0,
            s2: 0.0,
            c: 0.0,
            c_psi: 0.0,
            k: 1e7,
            balls: BallPhysics { contact: true, restitution: e, ..Default::default() },
            ..PlanarRotor::paper_004(0.01)
        };
        let d = Drive::Speed { omega0: 0.0 };
        let settings = Settings { psi0: vec![0.0, 1.0], psi_rate0: vec![1.0, 0.0], dt: 0.01, ..Settings::new(&p, 1.2) };
        let y0 = initial_state(&p, &d, &settings);
        let mut last = None;
        let s = simulate(&p, &d, &settings, |x| {
            last = Some(x.clone());
            true
        })
        .unwrap();
        assert_eq!(s.contacts, 1, "one impact: {s:?}");
        // rates from two late samples (the balls move freely after the impact)
        let last = last.unwrap();
        let mut prev = None;
        let settings2 = Settings { t_end: 1.19, ..settings.clone() };
        simulate(&p, &d, &settings2, |x| {
            prev = Some(x.clone());
            true
        })
        .unwrap();
        let prev = prev.unwrap();
        let rate = |j: usize| (last.psi[j] - prev.psi[j]) / (last.t - prev.t);
        let (v1, v2) = (rate(0), rate(1));
        // Errors measured: relative speed 1.6e-5, 2.3e-5, 1.0e-6 (e = 1, 0.5, 0.2), momentum
        // ≤ 7.5e-7, energy (e = 1) 1.6e-5. Their sources: the housing, pushed through the
        // contact, keeps a share of O(m3/m0) = 5e-6 of momentum and energy (its vibration is not
        // counted below), and the contact is the linear spring–damper of exact restitution
        // only to first order in the overlap (chord against angle). Tolerances ≈ 10× measured.
        assert!(((v2 - v1) - e).abs() < 2e-4, "e = {e}: relative speed after {}", v2 - v1);
        assert!((v1 + v2 - 1.0).abs() < 1e-5, "e = {e}: momentum {}", v1 + v2);
        if e == 1.0 {
            let mut y = y0.clone();
            let nc = 5;
            y[3] = last.psi[0];
            y[4] = last.psi[1];
            y[nc + 3] = v1;
            y[nc + 4] = v2;
            let (e0, e1) = (energy(&p, &y0), energy(&p, &y));
            assert!((e1 - e0).abs() < 2e-4 * e0, "energy {e0} → {e1}");
        }
    }
}

/// Paper 004's rotor (m3 = 30 g) with rolling resistance `mu` at constant speed.
fn friction_rotor(mu: f64, slip_rate: f64) -> PlanarRotor {
    PlanarRotor { balls: BallPhysics { rolling_resistance: mu, slip_rate, ..Default::default() }, ..PlanarRotor::paper_004(0.03) }
}

#[test]
fn friction_leaves_the_balls_where_the_static_equilibrium_lets_them_rest() {
    // From balls spread across the unbalance, above resonance: without friction E ends on the
    // axis (semi-balanced, |P| → 0); with μ_r the balls stop as soon as every ball can rest,
    // |P| |sin(ψ_j − arg P)| ≤ μ_r (r + P·e^{iψ_j}), checked on the closed-form steady whirl P
    // of the end configuration (independent of the simulated rotor state), which the simulated
    // rotor matches; the residual |P| is of the order μ_r r (1.4 μ_r r from this start).
    let w = 450.0;
    let start = [PI / 2.0, 3.0 * PI / 2.0];
    let (s0, last0) = run_at(&friction_rotor(0.0, 1e-4), w, &start, 40.0);
    assert!(s0.balanced, "{s0:?}");
    assert!(steady_p(&friction_rotor(0.0, 1e-4), w, &last0.psi).norm() < 1e-8);
    for mu in [1e-3, 3e-3] {
        let p = friction_rotor(mu, 1e-5);
        let (s, last) = run_at(&p, w, &start, 40.0);
        assert!(s.stick_slip_transitions >= 2, "{s:?}");
        let pp = steady_p(&p, w, &last.psi);
        let e = C::from_polar(p.s2, p.gamma);
        let sim_p = u_of(&last) + e;
        // measured 3.2e-6 and 1.6e-6 (the balls still creep at the regularisation's v_ε)
        assert!((sim_p - pp).norm() < 3e-5 * pp.norm(), "simulated P {sim_p} vs steady {pp}");
        for &psi in &last.psi {
            let margin = can_rest(mu, p.r, (pp.re, pp.im), psi);
            assert!(margin > -1e-3 * mu * p.r, "μ = {mu}: ball at {psi} cannot rest (margin {margin})");
        }
        let residual = pp.norm();
        // of the order μ_r r: measured 1.42 and 1.39 μ_r r; the band 1.2-1.6 μ_r r is that range
        // (the residual test below sweeps speed, μ_r and ball mass)
        assert!(residual > 1.2 * mu * p.r && residual < 1.6 * mu * p.r, "μ = {mu}: residual |P| = {residual} vs μ r = {}", mu * p.r);
    }
}

#[test]
fn a_ball_inside_the_dead_zone_stays_and_the_regularisation_error_vanishes() {
    // Start both balls at rest where they can rest (a point of the dead zone off the balanced
    // state); the exact (non-smooth) model keeps them there. The regularised model lets them
    // creep by at most v_ε t: the drift over 10 s must shrink with v_ε (here ∝ v_ε).
    let w = 450.0;
    let mu = 2e-3;
    let p = friction_rotor(mu, 1e-4);
    // balanced positions of point masses, then both turned by 0.01 rad: E off the axis
    let (_, bal) = run_at(&friction_rotor(0.0, 1e-4), w, &[PI / 2.0, 3.0 * PI / 2.0], 40.0);
    let psi0: Vec<f64> = bal.psi.iter().map(|a| a + 0.01).collect();
    let pp = steady_p(&p, w, &psi0);
    for &a in &psi0 {
        assert!(can_rest(mu, p.r, (pp.re, pp.im), a) > 0.2 * mu * p.r, "the start must lie inside the dead zone");
    }
    let mut drifts = vec![];
    for v in [1e-3, 1e-4, 1e-5] {
        let (_, last) = run_from(&friction_rotor(mu, v), w, &psi0, 10.0, true);
        let drift = (0..2).map(|j| (last.psi[j] - psi0[j]).abs()).fold(0.0, f64::max);
        eprintln!("v_ε = {v}: drift {drift}");
        assert!(drift < 10.0 * v, "v_ε = {v}: drift {drift} beyond v_ε t");
        drifts.push(drift);
    }
    assert!(drifts[0] / drifts[1] > 5.0 && drifts[1] / drifts[2] > 5.0, "drift does not vanish with v_ε: {drifts:?}");
    // outside the dead zone (turned by 0.5 rad) the balls do move
    let far: Vec<f64> = bal.psi.iter().map(|a| a + 0.5).collect();
    let (_, last) = run_from(&friction_rotor(mu, 1e-5), w, &far, 10.0, true);
    assert!((last.psi[0] - far[0]).abs() > 0.1, "{:?}", last.psi);
}

#[test]
fn switched_off_the_balls_are_the_papers_point_masses() {
    // a diameter alone changes nothing: no contact, no friction → the same run bit for bit
    let p = PlanarRotor::paper_004(0.01);
    let q = PlanarRotor { balls: BallPhysics { diameter: Some(0.02), ..Default::default() }, ..p.clone() };
    let (a, la) = run_at(&p, 300.0, &[1.0, 2.0], 2.0);
    let (b, lb) = run_at(&q, 300.0, &[1.0, 2.0], 2.0);
    assert_eq!(la, lb);
    assert_eq!((a.steps, a.contacts, a.stick_slip_transitions), (b.steps, 0, 0));
}

#[test]
fn the_right_hand_side_solves_every_bodys_equation_with_the_ball_forces() {
    // The structured right-hand side adds Q_j through its ball moments; every body's d'Alembert
    // residual (assembled body by body, with Q_j added to the ball rows) must vanish at its
    // accelerations, for free and prescribed rotation, with balls pressed together and rolling.
    use autobal::ode::System;
    use autobal::planar::Equations;
    let drives = [Drive::Torque { omega0: 0.0, torque: 3.0, t_off: None }, Drive::Acceleration { omega0: 100.0, b: 20.0 }];
    for n in [2, 3, 5] {
        let p = PlanarRotor { n, balls: BallPhysics { contact: true, rolling_resistance: 2e-3, ..Default::default() }, ..PlanarRotor::paper_004(0.01) };
        let sep = min_separation(steel_diameter(p.m3), p.r);
        for d in &drives {
            let eq = Equations::new(&p, d);
            let nc = 3 + n;
            let mut y = vec![0.0; 2 * nc];
            (y[0], y[1], y[nc], y[nc + 1], y[nc + 2]) = (1e-3, -2e-3, 0.3, 0.1, 250.0);
            for j in 0..n {
                y[3 + j] = 1.0 + 0.999 * sep * j as f64; // each pair overlapping slightly
                y[nc + 3 + j] = 0.01 * (j as f64 - 1.0); // one ball near sticking
            }
            let q = eq.ball_torques(0.0, &y);
            assert!(q[0].abs() > 0.05, "the balls press on each other: {q:?}");
            let mut dy = vec![0.0; 2 * nc];
            eq.rhs(0.0, &y, &mut dy);
            let res = eq.residuals(0.0, &y, &dy[nc..]);
            let scale = q.iter().fold(p.k * 1e-3, |a, x| a.max(x.abs()));
            assert!(res.iter().all(|r| r.abs() < 1e-10 * scale), "n = {n}, {d:?}: residuals {res:?}");
        }
    }
}

#[test]
fn the_residual_eccentricity_is_about_mu_r_r_whatever_the_speed_and_ball_mass() {
    // The pull on a resting ball (m3 r ω² |P| |sin|) and the friction that holds it
    // (μ_r r m3 ω² (r + …)) both scale with m3 ω²: balls that approach the balanced state slowly
    // (paper 004's 30 g balls) stop at the edge of the dead zone, |P| ≈ μ_r r whatever the speed.
    // Heavier balls (60 g) overshoot, stick and slip again, and stop deeper inside: the
    // residual is then smaller, never larger. Every end state satisfies the static resting
    // condition (`at_rest`: `can_rest` on the closed-form whirl of the end configuration).
    use autobal::planar::friction::residual;
    let (speeds, mus) = ([1.5, 3.0], [5e-4, 2e-3]);
    // ratio[m3][speed][μ_r] = |P| / (μ_r r)
    let mut ratio = [[[0.0; 2]; 2]; 2];
    for (i, m3) in [0.03, 0.06].into_iter().enumerate() {
        let p = PlanarRotor::paper_004(m3);
        let wn = p.natural_frequency();
        for (j, k) in speeds.into_iter().enumerate() {
            for (l, mu) in mus.into_iter().enumerate() {
                let r = residual(&p, k * wn, mu, 40.0).unwrap();
                assert!(r.completed && r.settled && r.at_rest, "{r:?}");
                ratio[i][j][l] = r.eccentricity / (mu * p.r);
            }
        }
    }
    let light = ratio[0];
    // 30 g: |P| = 0.94-1.23 μ_r r (measured); the band 0.9-1.3 is that range, so a residual
    // that stops scaling with μ_r r, or stops at the axis, fails
    assert!(light.iter().flatten().all(|q| (0.9..1.3).contains(q)), "30 g: |P|/(μ_r r) = {light:?}");
    // almost independent of the speed: 3 against 1.5 ω_n within 10 % (measured 2.4 % at
    // μ_r = 5e-4, 7.2 % at 2e-3)
    for l in 0..2 {
        assert!((light[1][l] / light[0][l] - 1.0).abs() < 0.1, "30 g, μ_r = {}: {light:?}", mus[l]);
    }
    // a little faster than linear in μ_r: 4× μ_r gives 1.22-1.28× the ratio (|P| 4.9-5.1×)
    for j in 0..2 {
        let g = light[j][1] / light[j][0];
        assert!(g > 1.1 && g < 1.4, "30 g at {} ω_n: ratio grows {g}× for 4× μ_r", speeds[j]);
    }
    // 60 g: never more than 30 g at the same speed and μ_r (measured 0.12-0.74 against
    // 0.94-1.23), and not at the axis
    for j in 0..2 {
        for l in 0..2 {
            assert!(
                ratio[1][j][l] > 0.0 && ratio[1][j][l] <= light[j][l],
                "{} ω_n, μ_r = {}: 60 g {} vs 30 g {}",
                speeds[j],
                mus[l],
                ratio[1][j][l],
                light[j][l]
            );
        }
    }
}

#[test]
fn the_spatial_model_has_the_same_real_balls() {
    // The same ball physics in both models: the spatial rotor with its tilt locked on one
    // support is paper 004's planar rotor (balancer centred, s2 = 0; the disk's eccentricity as
    // an unbalance mass with the same first and polar moments). With contact and rolling
    // resistance on, both must run into the same end state: balls touching or stuck at the same
    // angles, the same whirl, the same counts of contacts.
    use autobal::spatial::dynamics::{simulate as spatial_simulate, Initial, Settings as SpatialSettings};
    let physics = BallPhysics { contact: true, contact_stiffness: Some(1e6), rolling_resistance: 1e-3, ..Default::default() };
    for m3 in [0.01, 0.03] {
        let mut p = PlanarRotor { balls: physics, ..PlanarRotor::paper_004(m3) };
        p.s2 = 0.0;
        p.m2 = 0.0;
        let rotor = planar_as_spatial(&p, physics);
        let drive = Drive::Speed { omega0: 2.0 * p.natural_frequency() };
        let (t_end, dt) = (10.0, 0.5);
        let init = Initial { psi: vec![PI - 0.6, PI + 0.5], ..Initial::at_rest(&rotor) };
        let mut ours = None;
        let s = spatial_simulate(&rotor, &drive, &init, &SpatialSettings { method: Default::default(), t_end, dt, rtol: 1e-10, atol: 1e-12 }, |x| {
            ours = Some((x.x, x.y, x.psi.clone()));
            true
        })
        .unwrap();
        let ours = ours.unwrap();
        let ps = Settings { t_end, dt, rtol: 1e-10, atol: 1e-12, psi0: init.psi.clone(), ..Settings::new(&p, t_end) };
        let mut theirs = None;
        let t = simulate(&p, &drive, &ps, |x| {
            theirs = Some((x.x, x.y, x.psi.clone()));
            true
        })
        .unwrap();
        let theirs = theirs.unwrap();
        assert!(t.contacts >= 1 || m3 == 0.03, "{t:?}");
        // both count the same events (from the states at their own step ends): contacts where
        // the planar run had them, stick-slip transitions as the balls stop
        assert_eq!(s.contacts > 0, t.contacts > 0, "m3 = {m3}: spatial {s:?} vs planar {t:?}");
        assert!(s.stick_slip_transitions >= 1 && t.stick_slip_transitions >= 1, "m3 = {m3}: spatial {s:?} vs planar {t:?}");
        for j in 0..2 {
            assert!((ours.2[j] - theirs.2[j]).abs() < 1e-6, "m3 = {m3}: ψ {:?} vs {:?} ({s:?})", ours.2, theirs.2);
        }
        let amp = theirs.0.hypot(theirs.1);
        assert!((ours.0 - theirs.0).abs() < 1e-5 * amp && (ours.1 - theirs.1).abs() < 1e-5 * amp, "m3 = {m3}: C {ours:?} vs {theirs:?}");
    }
}

/// Paper 004's passage (b = 2.5 1/s², forward from rest or reverse from 600 rad/s, 240 s) at
/// relative tolerance `rtol`: summary and last sample.
fn passage(p: &PlanarRotor, forward: bool, rtol: f64) -> (Summary, Sample) {
    let drive = if forward { Drive::Acceleration { omega0: 0.0, b: 2.5 } } else { Drive::Acceleration { omega0: 600.0, b: -2.5 } };
    let settings = Settings { rtol, ..Settings::new(p, 240.0) };
    let mut last = None;
    let s = simulate(p, &drive, &settings, |x| {
        last = Some(x.clone());
        true
    })
    .unwrap();
    assert!(s.stopped.is_none(), "{:?}", s.stopped);
    (s, last.unwrap())
}

#[test]
fn paper_004s_findings_with_real_balls() {
    // Paper 004's passages re-run with steel balls of the default diameter and the default
    // contact stiffness (docs/notes/balls.md, "Paper 004's cases with real balls").
    let real = |m3: f64| PlanarRotor { balls: BallPhysics { contact: true, ..Default::default() }, ..PlanarRotor::paper_004(m3) };
    // The capacity condition with the packed capacity: two touching balls resultant
    // 2 cos(Δc/2) instead of 2, so α∞ shrinks by cos(Δc/2) = sqrt(1 − (d/2r)²)
    for m3 in [0.01, 0.03] {
        let (pm, rb) = (PlanarRotor::paper_004(m3), real(m3));
        let shrink = (1.0 - (steel_diameter(m3) / (2.0 * pm.r)).powi(2)).sqrt();
        assert!((capacity_ratio(&rb) - capacity_ratio(&pm) * shrink).abs() < 1e-12, "m3 = {m3}");
    }
    assert!(capacity_ratio(&real(0.03)) > 1.0 && capacity_ratio(&real(0.01)) < 1.0);

    // 30 g: the semi-balanced radius s2 survives finite size; the forward peak is lower (point
    // masses pass through each other and gather as one mass, real balls collide: 26.2 against
    // 31.7 mm)
    let p = real(0.03);
    let sep = min_separation(steel_diameter(p.m3), p.r);
    let (pm, _) = passage(&PlanarRotor::paper_004(0.03), true, 1e-8);
    let (rb, last) = passage(&p, true, 1e-8);
    assert!(rb.balanced && pm.balanced, "{rb:?}");
    assert!((rb.final_amplitude - p.s2).abs() < 1e-3 * p.s2, "C ends at {} instead of s2 = {}", rb.final_amplitude, p.s2);
    assert!(rb.contacts >= 1, "{rb:?}");
    assert!(wrap(last.psi[1] - last.psi[0]).abs() > sep, "the balanced balls do not touch: {:?}", last.psi);
    assert!(rb.peak_amplitude < 0.9 * pm.peak_amplitude, "forward peak {} with real balls vs {} with point masses", rb.peak_amplitude, pm.peak_amplitude);

    // The reverse-passage peak: ill-conditioned with point masses and with real balls alike
    // (17.1 or 21.9/22.3 mm depending on rtol), but below the forward peak in every run: the
    // finding "the reverse passage at 2.5 1/s² peaks lower" survives
    for rtol in [1e-8, 1e-10] {
        let (rev_pm, _) = passage(&PlanarRotor::paper_004(0.03), false, rtol);
        let (rev_rb, _) = passage(&p, false, rtol);
        assert!(rev_pm.peak_amplitude < 0.75 * pm.peak_amplitude, "rtol {rtol}: point masses' reverse peak {}", rev_pm.peak_amplitude);
        assert!(
            rev_rb.peak_amplitude < 0.9 * rb.peak_amplitude,
            "rtol {rtol}: real balls' reverse peak {} vs forward {}",
            rev_rb.peak_amplitude,
            rb.peak_amplitude
        );
        assert!(rev_rb.contacts > 100, "balls touch and separate as the speed falls: {rev_rb:?}");
    }

    // 10 g: cannot balance either way; point masses end on top of each other, real balls end
    // touching, where the closed form of a touching pair puts them at the final 600 rad/s
    // (quasi-static: the speed changes by 0.4 % per second), C whirling at its radius
    let p = real(0.01);
    let sep = min_separation(steel_diameter(p.m3), p.r);
    let (pm, lp) = passage(&PlanarRotor::paper_004(0.01), true, 1e-8);
    let (rb, last) = passage(&p, true, 1e-8);
    assert!(!pm.balanced && !rb.balanced);
    assert!(wrap(lp.psi[1] - lp.psi[0]).abs() < 0.1 * sep, "point masses overlap: {:?}", lp.psi);
    let gap = wrap(last.psi[1] - last.psi[0]).abs();
    // the default stiffness lets the pair overlap under its load (~1 N at 600 rad/s) by
    // δ ≈ F/k_c ≈ 6e-6 m, an angle δ/(r cos) ≈ 1e-4 rad (measured 6e-5); the closed form is for
    // rigid balls
    assert!((gap - sep).abs() < 3e-4, "touching: {gap} vs Δc = {sep}");
    let (beta, radius) = touching_pair(&p, rb.final_omega);
    let mid = last.psi[0] + 0.5 * wrap(last.psi[1] - last.psi[0]);
    assert!(wrap(mid - beta).abs() < 5e-4, "pair centre {mid} vs closed form {beta}");
    assert!((rb.final_amplitude - radius).abs() < 5e-5 * radius, "C whirls at {} vs closed form {radius}", rb.final_amplitude);
    assert!(rb.final_amplitude > pm.final_amplitude, "real balls leave more: {} vs {}", rb.final_amplitude, pm.final_amplitude);
}

#[test]
fn rolling_resistance_stops_the_balls_short_of_s2_after_a_passage() {
    // docs/notes/balls.md, "Which of 004's findings survive": with μ_r = 1e-3 (point masses otherwise)
    // the 30 g balls stop before E reaches the axis during the forward passage, and C ends at
    // 0.820 s2 (0.410 mm) instead of s2, E 90 µm = 1.50 μ_r r off the axis. Measured
    // 0.819874-0.819878 s2 and 1.5010-1.5011 μ_r r at rtol 1e-6 to 1e-10; the tolerances are
    // ten times that spread.
    let mu = 1e-3;
    let p = PlanarRotor { balls: BallPhysics { rolling_resistance: mu, ..Default::default() }, ..PlanarRotor::paper_004(0.03) };
    let (s, last) = passage(&p, true, 1e-8);
    assert!(s.settled && s.stick_slip_transitions >= 2, "{s:?}");
    assert!((s.final_amplitude / p.s2 - 0.81988).abs() < 5e-5, "C ends at {} s2", s.final_amplitude / p.s2);
    let pe = u_of(&last) + C::from_polar(p.s2, p.gamma);
    assert!((pe.norm() / (mu * p.r) - 1.5011).abs() < 2e-3, "|P| = {} μ_r r", pe.norm() / (mu * p.r));
    // every ball where the static resting condition lets it rest (closed-form whirl at 600 rad/s)
    let pp = steady_p(&p, s.final_omega, &last.psi);
    for &psi in &last.psi {
        let margin = can_rest(mu, p.r, (pp.re, pp.im), psi);
        assert!(margin > -1e-3 * mu * p.r, "ball at {psi} cannot rest (margin {margin})");
    }
}
