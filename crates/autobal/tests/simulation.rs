//! Nonlinear simulation of the planar rotor (paper 004): the equations against the paper's
//! fixed-frame eq (1), energy balance, closed-form limits, and the paper's findings.

use autobal::ode::System;
use autobal::planar::stationary::{aligned_whirls, capacity_ratio, locked_amplitude, semi_balanced_exists};
use autobal::planar::{energy, simulate, Drive, Equations, Method, PlanarRotor, Settings, Summary};

mod common;
use common::Rng;

fn settings(p: &PlanarRotor, t_end: f64, dt: f64) -> Settings {
    Settings { dt, ..Settings::new(p, t_end) }
}

fn run(p: &PlanarRotor, d: &Drive, t_end: f64) -> (Summary, Vec<(f64, f64, f64)>) {
    let mut samples = vec![];
    let s = simulate(p, d, &settings(p, t_end, t_end / 4000.0), |x| {
        samples.push((x.t, x.omega, x.amplitude));
        true
    })
    .unwrap();
    assert!(s.stopped.is_none(), "{:?}", s.stopped);
    (s, samples)
}

#[test]
fn equations_satisfy_the_papers_fixed_frame_eq_1() {
    // Random states: our rotor-frame accelerations, mapped to fixed axes, must satisfy 004's
    // eq (1) as docs/notes/model.md §2 states it, with the translation right-hand side −d²/dt²[…]
    // (the paper prints +, which would make an unbalance push the shaft towards the axis below
    // resonance).
    let mut rng = Rng(41);
    for _ in 0..200 {
        let mut p = PlanarRotor::paper();
        p.n = 1 + (rng.next() * 3.0) as usize;
        p.gamma = rng.range(-3.0, 3.0);
        p.c_theta = rng.range(0.0, 0.1);
        let torque = rng.range(-50.0, 50.0);
        let d = Drive::Torque { omega0: 0.0, torque, t_off: None };
        let eq = Equations::new(&p, &d);
        let n = p.n;
        let nc = 3 + n;
        let mut y = vec![0.0; 2 * nc];
        for v in y.iter_mut().take(2 * nc) {
            *v = rng.range(-1.0, 1.0);
        }
        y[0] *= 0.01;
        y[1] *= 0.01;
        y[nc] *= 3.0;
        y[nc + 1] *= 3.0;
        y[nc + 2] = rng.range(-500.0, 500.0);
        let mut dy = vec![0.0; 2 * nc];
        eq.rhs(0.0, &y, &mut dy);
        let (th, thd, thdd) = (y[2], y[nc + 2], dy[nc + 2]);
        let (u, ud, udd) = ((y[0], y[1]), (y[nc], y[nc + 1]), (dy[nc], dy[nc + 1]));
        // fixed frame: z = u e^{iθ}, ż = (u̇ + iθ̇u) e^{iθ}, z̈ = (ü + 2iθ̇u̇ + iθ̈u − θ̇²u) e^{iθ}
        let rot = |a: (f64, f64)| (a.0 * th.cos() - a.1 * th.sin(), a.0 * th.sin() + a.1 * th.cos());
        let z = rot(u);
        let zd = rot((ud.0 - thd * u.1, ud.1 + thd * u.0));
        let zdd = rot((udd.0 - 2.0 * thd * ud.1 - thdd * u.1 - thd * thd * u.0, udd.1 + 2.0 * thd * ud.0 + thdd * u.0 - thd * thd * u.1));
        let m0 = p.total_mass();
        let me = p.m2 + n as f64 * p.m3;
        // −d²/dt² of the first moment of the offsets
        let mut fx = -p.m1 * p.s1 * (-thdd * th.sin() - thd * thd * th.cos()) - me * p.s2 * (-thdd * (th + p.gamma).sin() - thd * thd * (th + p.gamma).cos());
        let mut fy = -p.m1 * p.s1 * (thdd * th.cos() - thd * thd * th.sin()) - me * p.s2 * (thdd * (th + p.gamma).cos() - thd * thd * (th + p.gamma).sin());
        let mut torque_terms = 0.0;
        for j in 0..n {
            let (ps, psd, psdd) = (y[3 + j], y[nc + 3 + j], dy[nc + 3 + j]);
            let (a, ad, add) = (th + ps, thd + psd, thdd + psdd);
            fx -= p.m3 * p.r * (-add * a.sin() - ad * ad * a.cos());
            fy -= p.m3 * p.r * (add * a.cos() - ad * ad * a.sin());
            torque_terms -= p.m3 * p.r * p.s2 * (ad * ad * (p.gamma - ps).sin() + add * (p.gamma - ps).cos());
            // ball equation
            let lhs = p.m3 * p.r * p.r * add + p.c_psi * psd;
            let rhs = p.m3 * p.r * (zdd.0 * a.sin() - zdd.1 * a.cos()) + p.m3 * p.r * p.s2 * (thd * thd * (p.gamma - ps).sin() - thdd * (p.gamma - ps).cos());
            assert!((lhs - rhs).abs() < 1e-9 * (lhs.abs() + rhs.abs() + 1e-6), "ball {j}: {lhs} vs {rhs}");
        }
        let ex = m0 * zdd.0 + p.c * zd.0 + p.k * z.0 - fx;
        let ey = m0 * zdd.1 + p.c * zd.1 + p.k * z.1 - fy;
        let scale = p.k * z.0.hypot(z.1) + m0 * zdd.0.hypot(zdd.1) + fx.hypot(fy);
        assert!(ex.abs() < 1e-9 * scale && ey.abs() < 1e-9 * scale, "translation residual {ex}, {ey} (scale {scale})");
        // rotation: J_C θ̈ + c_θ θ̇ − c_ψ Σψ̇ = M + m1 s1 (Ẍ sinθ − Ÿ cosθ) + (m2 + n m3) s2 (…) − m3 r s2 Σ[…]
        let sum_psd: f64 = (0..n).map(|j| y[nc + 3 + j]).sum();
        let lhs = p.polar_moment() * thdd + p.c_theta * thd - p.c_psi * sum_psd;
        let rhs = torque
            + p.m1 * p.s1 * (zdd.0 * th.sin() - zdd.1 * th.cos())
            + me * p.s2 * (zdd.0 * (th + p.gamma).sin() - zdd.1 * (th + p.gamma).cos())
            + torque_terms;
        assert!((lhs - rhs).abs() < 1e-9 * (lhs.abs() + rhs.abs() + 1e-6), "rotation: {lhs} vs {rhs}");
    }
}

#[test]
fn energy_balance_without_damping_under_constant_torque() {
    // all damping zero, constant torque: T + V changes by the work M Δθ, to the tolerance
    let mut p = PlanarRotor::paper();
    p.c = 0.0;
    p.c_psi = 0.0;
    p.c_theta = 0.0;
    let torque = 5.0;
    let d = Drive::Torque { omega0: 200.0, torque, t_off: None };
    let mut st = settings(&p, 0.4, 0.001);
    st.rtol = 1e-11;
    st.atol = 1e-13;
    st.psi0 = vec![0.3, 2.0];
    st.psi_rate0 = vec![5.0, -3.0];
    let y0 = autobal::planar::initial_state(&p, &d, &st);
    let e0 = energy(&p, &y0);
    let mut worst: f64 = 0.0;
    let mut last = (0.0, 0.0);
    let nc = 3 + p.n;
    let eq = Equations::new(&p, &d);
    let tol = autobal::planar::tolerances(&p, &st).method(Method::Dop853);
    let mut solver = autobal::ode::Solver::new(&eq, tol).unwrap();
    let mut y = y0.clone();
    let out = solver.integrate(0.0, &mut y, 0.4, |s| {
        let work = torque * (s.y_new[2] - y0[2]);
        let e = energy(&p, s.y_new);
        worst = worst.max((e - e0 - work).abs() / e.abs());
        last = (e - e0, work);
        let _ = nc;
        autobal::ode::Control::Continue
    });
    assert!(out.status.is_completed());
    assert!(last.1 > 10.0, "the torque did work: {last:?}");
    assert!(worst < 1e-8, "relative energy error {worst}");
}

#[test]
fn without_balls_the_steady_whirl_is_the_closed_form() {
    let mut p = PlanarRotor::paper();
    p.n = 0;
    for w in [150.0, 260.0, 288.0, 320.0, 600.0] {
        let d = Drive::Speed { omega0: w };
        let (s, _) = run(&p, &d, 1.0); // decay time 2 m0/c ≈ 0.05 s
        let exact = locked_amplitude(&p, w, &[]);
        assert!((s.final_amplitude - exact).abs() < 1e-6 * exact, "ω = {w}: {} vs {exact}", s.final_amplitude);
    }
}

#[test]
fn passage_peak_approaches_the_stationary_peak_as_b_goes_to_zero() {
    // Lewis (1932): without balls, the slower the passage the closer its peak to the stationary one
    let mut p = PlanarRotor::paper();
    p.n = 0;
    let stationary = (200..400).map(|w| locked_amplitude(&p, w as f64, &[])).fold(0.0, f64::max);
    let stationary = (0..200_000).map(|i| locked_amplitude(&p, 200.0 + 0.001 * i as f64, &[])).fold(stationary, f64::max);
    // for moderate b the peak slightly overshoots (it comes later, at a higher speed); the gap
    // |peak/stationary − 1| shrinks monotonically as b → 0
    let mut last_gap = f64::INFINITY;
    for b in [50.0, 12.5, 2.5] {
        let d = Drive::Acceleration { omega0: 100.0, b };
        let (s, _) = run(&p, &d, 300.0 / b);
        let gap = (s.peak_amplitude / stationary - 1.0).abs();
        assert!(gap < last_gap, "b = {b}: gap {gap} (previous {last_gap})");
        last_gap = gap;
    }
    assert!(last_gap < 1e-3, "at b = 2.5 the peak is within 0.1 % of the stationary one: {last_gap}");
}

#[test]
fn paper_004_semi_balanced_with_enough_ball_mass() {
    // m3 = 0.03 kg: after the passage C whirls at radius s2 = 0.5 mm, whatever the speed
    let p = PlanarRotor::paper();
    assert!(capacity_ratio(&p) > 1.0);
    for w in [500.0, 800.0] {
        let d = Drive::Speed { omega0: w };
        let (s, _) = run(&p, &d, 3.0);
        assert!(s.balanced, "ω = {w}: {s:?}");
        assert!((s.final_amplitude - p.s2).abs() < 0.01 * p.s2, "ω = {w}: {}", s.final_amplitude);
        assert!(semi_balanced_exists(&p, w));
    }
}

#[test]
fn paper_004_no_balance_with_too_little_ball_mass() {
    // m3 = 0.01 kg: the balls cannot supply the unbalance, the whirl stays unbalanced, at the
    // aligned stationary whirl with both balls on the far side of the axis (opposite the heavy
    // spot, above resonance)
    let mut p = PlanarRotor::paper();
    p.m3 = 0.01;
    assert!(capacity_ratio(&p) < 1.0);
    let w = 600.0;
    assert!(!semi_balanced_exists(&p, w));
    let d = Drive::Speed { omega0: w };
    let (s, _) = run(&p, &d, 3.0);
    assert!(!s.balanced);
    let far = aligned_whirls(&p, w).into_iter().find(|a| a.q == 2).expect("far-side branch exists");
    assert!((s.final_amplitude - far.amplitude).abs() < 1e-4 * far.amplitude, "{} vs {}", s.final_amplitude, far.amplitude);
}

#[test]
fn paper_004_forward_passage_overshoots_and_reverse_is_lower() {
    let p = PlanarRotor::paper();
    let stationary = (200..400).map(|w| locked_amplitude(&p, w as f64, &Settings::default_psi0(2))).fold(0.0, f64::max);
    let (fwd, _) = run(&p, &Drive::Acceleration { omega0: 0.0, b: 2.5 }, 240.0);
    assert!(fwd.peak_amplitude > stationary, "forward {} vs stationary {stationary}", fwd.peak_amplitude);
    assert!(fwd.balanced, "semi-balanced after the forward passage");
    // reverse: the balls sit opposite the heavy spot when resonance is reached, so the peak stays
    // far below the forward one (004: "the influence of the ABB is positive"). How the balls
    // leave the semi-balanced state near resonance is sensitive to perturbations far below any
    // tolerance: moving one ball's initial angle by 1e-10 rad already changes the reverse peak
    // from 17.1 to 20.8 mm, and the looser the tolerance the more often the outcome is the
    // higher one (docs/notes/simulation.md). So the claim is checked over a family of imperceptibly
    // different starts: every reverse peak far below the forward one (measured: 17.1-23.8 mm
    // against 31.7), and none below 0.9 of the stationary peak (the balls cannot keep the rotor
    // out of resonance on the way down either).
    let mut peaks = vec![];
    for dpsi in [0.0, 1e-10, 1e-8, 1e-7, 3e-7, 1e-5, 3e-5, 1e-3, 1e-2] {
        let mut st = settings(&p, 240.0, 0.06);
        st.psi0[0] += dpsi;
        let s = simulate(&p, &Drive::Acceleration { omega0: 600.0, b: -2.5 }, &st, |_| true).unwrap();
        assert!(s.status.is_completed());
        peaks.push(s.peak_amplitude);
    }
    peaks.sort_by(f64::total_cmp);
    assert!(peaks[peaks.len() - 1] < 0.8 * fwd.peak_amplitude, "reverse peaks {peaks:?} vs forward {}", fwd.peak_amplitude);
    assert!(peaks[0] > 0.9 * stationary, "reverse peaks {peaks:?} vs stationary {stationary}");
}

#[test]
fn paper_004_too_little_ball_damping_prolongs_the_oscillations() {
    // 004 Fig. 5 (b = 0.2 1/s²): with c_ψ = 0.01 the whirl keeps oscillating long after
    // resonance before it settles at s2; with 0.1 it settles promptly. Measured: the last time
    // the radius of C is more than 5 % off s2, counted from the moment ω passes ω_n.
    let mut settle = vec![];
    for c_psi in [0.1, 0.01] {
        let mut p = PlanarRotor::paper();
        p.c_psi = c_psi;
        let b = 0.2;
        let t_res = (p.natural_frequency() - 200.0) / b;
        let (s, samples) = run(&p, &Drive::Acceleration { omega0: 200.0, b }, 1100.0);
        assert!(s.balanced, "c_ψ = {c_psi}: {s:?}");
        let last_off = samples.iter().filter(|x| (x.2 - p.s2).abs() > 0.05 * p.s2).map(|x| x.0).fold(0.0, f64::max);
        settle.push(last_off - t_res);
    }
    assert!(settle[1] > 3.0 * settle[0], "settling after resonance: c_ψ = 0.1 → {} s, 0.01 → {} s", settle[0], settle[1]);
}

#[test]
fn paper_004_too_small_a_torque_cannot_pass_resonance() {
    // Sommerfeld effect: below the largest torque the vibration can absorb at resonance
    // (c ω A² ≈ 4.8 N·m here) the rotor sticks below ω_n, where the power balance
    // M = c ω A² holds (c_θ = 0, balls at rest); above it the rotor passes and balances.
    let p = PlanarRotor::paper();
    let wn = p.natural_frequency();
    let (low, _) = run(&p, &Drive::Torque { omega0: 0.0, torque: 3.0, t_off: None }, 10.0);
    assert!(low.final_omega < wn, "3 N·m: stuck below resonance at {} rad/s", low.final_omega);
    let balance = p.c * low.final_omega * low.final_amplitude.powi(2);
    assert!((balance - 3.0).abs() < 1e-3 * 3.0, "power balance c ω A² = {balance}");
    let (high, _) = run(&p, &Drive::Torque { omega0: 0.0, torque: 10.0, t_off: None }, 10.0);
    assert!(high.final_omega > 10.0 * wn && high.balanced, "10 N·m: passes ({} rad/s)", high.final_omega);
}

#[test]
fn samples_are_on_the_requested_grid_whatever_the_steps() {
    let p = PlanarRotor::paper();
    let mut ts = vec![];
    let s = simulate(&p, &Drive::Speed { omega0: 400.0 }, &settings(&p, 0.1, 0.0037), |x| {
        ts.push(x.t);
        true
    })
    .unwrap();
    assert_eq!(ts.len(), 29); // 0, 0.0037, …, 0.0999, and the end 0.1
    for (i, t) in ts[..28].iter().enumerate() {
        assert!((t - 0.0037 * i as f64).abs() < 1e-12);
    }
    assert_eq!(ts[28], 0.1);
    assert!(s.steps as usize != ts.len());
}

#[test]
fn rosenbrock_agrees_with_dop853_and_wins_on_light_balls() {
    // light balls (m3 = 2 g): the balls relax in m3 r²/c_ψ ≈ 72 µs; the implicit method must give
    // the same passage as DOP853 in far fewer steps
    let mut p = PlanarRotor::paper();
    p.m3 = 0.002;
    let d = Drive::Acceleration { omega0: 250.0, b: 50.0 };
    let mut res = vec![];
    for method in [Method::Dop853, Method::Rodas] {
        let mut st = settings(&p, 2.0, 0.001);
        st.method = method;
        let mut amps = vec![];
        let s = simulate(&p, &d, &st, |x| {
            amps.push(x.amplitude);
            true
        })
        .unwrap();
        assert!(s.stopped.is_none());
        res.push((s, amps));
    }
    let (e, i) = (&res[0], &res[1]);
    let peak = e.0.peak_amplitude;
    assert!((e.0.peak_amplitude - i.0.peak_amplitude).abs() < 1e-5 * peak, "{} vs {}", e.0.peak_amplitude, i.0.peak_amplitude);
    let worst = e.1.iter().zip(&i.1).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst < 1e-4 * peak, "samples differ by {worst}");
    assert!(i.0.steps < e.0.steps, "steps: DOP853 {}, Rosenbrock {}", e.0.steps, i.0.steps);
    // where it pays: a long steady run, which DOP853 must step at its stability limit
    // (h ≲ 6 m3 r²/c_ψ) while the Rosenbrock method strides
    let d = Drive::Speed { omega0: 600.0 };
    let mut fin = vec![];
    for method in [Method::Dop853, Method::Rodas] {
        let mut st = settings(&p, 20.0, 0.5);
        st.method = method;
        fin.push(simulate(&p, &d, &st, |_| true).unwrap());
    }
    assert!((fin[0].final_amplitude - fin[1].final_amplitude).abs() < 1e-8 * fin[0].final_amplitude);
    assert!(fin[1].steps * 10 < fin[0].steps, "steady run: DOP853 {} steps, Rosenbrock {}", fin[0].steps, fin[1].steps);
}

#[test]
fn drives_follow_their_definitions() {
    let p = PlanarRotor::paper();
    let wn = p.natural_frequency();
    // prescribed speed schedule: ω(t) is the piecewise-linear function, exactly
    let pts = vec![(0.0, 100.0), (1.0, 400.0), (2.0, 400.0), (3.0, 250.0)];
    let d = Drive::SpeedSchedule { points: pts.clone() };
    let mut worst: f64 = 0.0;
    let st = settings(&p, 3.0, 0.01);
    simulate(&p, &d, &st, |s| {
        let expect = if s.t <= 1.0 {
            100.0 + 300.0 * s.t
        } else if s.t <= 2.0 {
            400.0
        } else {
            400.0 - 150.0 * (s.t - 2.0)
        };
        worst = worst.max((s.omega - expect).abs());
        true
    })
    .unwrap();
    assert!(worst < 1e-6, "speed schedule off by {worst}");
    // a run-down at constant deceleration stops at rest and stays there
    let (s, samples) = run(&p, &Drive::Acceleration { omega0: 100.0, b: -50.0 }, 4.0);
    assert!(s.final_omega.abs() < 1e-9 && samples.iter().all(|x| x.1 >= -1e-9), "{}", s.final_omega);
    // a torque switched off at 1 s: the rotor coasts, slowed only by the drag of its semi-balanced
    // whirl (radius s2): J_eff dω/dt = −c ω s2², J_eff = I_G + m1 (s1 − s2)² + n m3 r²
    let (_, samples) = run(&p, &Drive::Torque { omega0: 500.0, torque: 10.0, t_off: Some(1.0) }, 2.0);
    let at = |t: f64| samples.iter().min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs())).unwrap().1;
    assert!(at(1.0) > 500.0 + 0.5 * 10.0 / p.polar_moment(), "accelerated: {}", at(1.0));
    let j_eff = p.i_g + p.m1 * (p.s1 - p.s2).powi(2) + p.n as f64 * p.m3 * p.r * p.r;
    let predicted = -p.c * 0.5 * (at(1.0) + at(2.0)) * p.s2 * p.s2 / j_eff;
    let observed = at(2.0) - at(1.0);
    assert!((observed - predicted).abs() < 0.01 * predicted.abs(), "coasting: Δω = {observed}, power balance {predicted}");
    // a torque schedule equal to a constant torque gives the constant-torque run
    let (a, _) = run(&p, &Drive::Torque { omega0: 0.0, torque: 10.0, t_off: None }, 1.0);
    let (b, _) = run(&p, &Drive::TorqueSchedule { omega0: 0.0, points: vec![(0.0, 10.0), (5.0, 10.0)] }, 1.0);
    assert!((a.final_omega - b.final_omega).abs() < 1e-9 * a.final_omega);
    // the motor: M(ω) = M0 (1 − ω/ω_idle). Far above resonance the balanced rotor settles where
    // the torque meets the drag of its semi-balanced whirl, M0 (1 − ω/ω_idle) = c ω s2², just
    // below ω_idle; a weak motor sticks below resonance (Sommerfeld), where its torque balances
    // the drag of the resonant whirl, c ω A²
    let (m0, w_idle) = (20.0, 3.0 * wn);
    let (strong, _) = run(&p, &Drive::Motor { omega0: 0.0, torque: m0, omega_idle: w_idle, t_off: None }, 30.0);
    let w_star = m0 / (m0 / w_idle + p.c * p.s2 * p.s2);
    assert!((strong.final_omega - w_star).abs() < 1e-6 * w_star && strong.balanced, "{} vs {w_star}: {strong:?}", strong.final_omega);
    let (weak, _) = run(&p, &Drive::Motor { omega0: 0.0, torque: 5.0, omega_idle: 3.0 * wn, t_off: None }, 30.0);
    assert!(weak.final_omega < wn, "weak motor sticks: {}", weak.final_omega);
    let m = 5.0 * (1.0 - weak.final_omega / (3.0 * wn));
    let drag = p.c * weak.final_omega * weak.final_amplitude.powi(2);
    assert!((m - drag).abs() < 1e-3 * m, "power balance at the stuck speed: M = {m}, c ω A² = {drag}");
}

/// Gaussian elimination with partial pivoting (row-major `n×n`), for the checks below.
fn dense_solve(mut a: Vec<f64>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs())).unwrap();
        for j in 0..n {
            a.swap(k * n + j, p * n + j);
        }
        b.swap(k, p);
        for i in k + 1..n {
            let f = a[i * n + k] / a[k * n + k];
            for j in k..n {
                a[i * n + j] -= f * a[k * n + j];
            }
            b[i] -= f * b[k];
        }
    }
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k * n + j] * b[j]).sum();
        b[k] = (b[k] - s) / a[k * n + k];
    }
    b
}

/// A random state of the planar rotor with `n` balls (displacements ~ 1 cm, speeds ~ 500 rad/s).
fn random_state(rng: &mut Rng, n: usize) -> Vec<f64> {
    let nc = 3 + n;
    let mut y: Vec<f64> = (0..2 * nc).map(|_| rng.range(-1.0, 1.0)).collect();
    y[0] *= 0.01;
    y[1] *= 0.01;
    y[2] *= 3.0;
    for j in 0..n {
        y[3 + j] *= 3.0;
        y[nc + 3 + j] *= 50.0;
    }
    y[nc] *= 3.0;
    y[nc + 1] *= 3.0;
    y[nc + 2] = rng.range(-500.0, 500.0);
    y
}

fn random_drives(rng: &mut Rng) -> Vec<Drive> {
    vec![
        Drive::Torque { omega0: 0.0, torque: rng.range(-20.0, 20.0), t_off: None },
        Drive::Motor { omega0: 0.0, torque: 10.0, omega_idle: 400.0, t_off: None },
        Drive::Acceleration { omega0: rng.range(0.0, 300.0), b: rng.range(-50.0, 50.0) },
    ]
}

#[test]
fn structured_rhs_equals_the_dense_mass_matrix_solve() {
    // the closed-form elimination of the balls (cost linear in n) against the full mass matrix
    // assembled body by body and solved by Gaussian elimination, at random states, for free and
    // prescribed rotation; and every body's d'Alembert residual vanishes at the result
    let mut rng = Rng(7);
    let mut worst: f64 = 0.0;
    for n in [0, 1, 2, 3, 5, 9, 17] {
        for _ in 0..20 {
            let mut p = PlanarRotor::paper();
            p.n = n;
            p.gamma = rng.range(-3.0, 3.0);
            p.m3 = rng.range(1e-4, 0.1);
            p.c_theta = rng.range(0.0, 0.1);
            for d in random_drives(&mut rng) {
                let eq = Equations::new(&p, &d);
                let y = random_state(&mut rng, n);
                let nc = 3 + n;
                let mut dy = vec![0.0; 2 * nc];
                eq.rhs(0.37, &y, &mut dy);
                let (m, f) = eq.mass_matrix(0.37, &y);
                let acc = dense_solve(m, f);
                let scale = acc.iter().fold(1.0f64, |a, x| a.max(x.abs()));
                for i in 0..nc {
                    let e = (dy[nc + i] - acc[i]).abs() / scale;
                    worst = worst.max(e);
                    assert!(e < 1e-11, "n = {n}, {d:?}, component {i}: {} vs {}", dy[nc + i], acc[i]);
                    assert_eq!(dy[i], y[nc + i]);
                }
                let res = eq.residuals(0.37, &y, &dy[nc..]);
                let fscale = res.len() as f64 * p.k * 0.02 + 1.0;
                assert!(res.iter().all(|r| r.abs() < 1e-9 * fscale), "n = {n}: residuals {res:?}");
            }
        }
    }
    eprintln!("largest difference, relative to the largest acceleration: {worst:e}");
}

#[test]
fn structured_jacobian_equals_finite_differences() {
    // the arrow linearisation (exact, by forward differentiation of the residuals) against
    // central differences of the right-hand side, and its O(n) solve of (αI − J)x = b against a
    // dense solve with that difference Jacobian
    use autobal::ode::arrow::ArrowJacobian;
    use autobal::ode::Jacobian;
    let mut rng = Rng(11);
    for n in [0, 1, 2, 4, 7] {
        let mut p = PlanarRotor::paper();
        p.n = n;
        p.gamma = 0.7;
        for d in random_drives(&mut rng) {
            let eq = Equations::new(&p, &d);
            let nc = 3 + n;
            let dim = 2 * nc;
            let y = random_state(&mut rng, n);
            let t = 0.2;
            let mut f0 = vec![0.0; dim];
            eq.rhs(t, &y, &mut f0);
            // J by central differences
            let mut jfd = vec![0.0; dim * dim];
            for j in 0..dim {
                let h = 1e-6 * y[j].abs().max(if j % nc < 2 { 1e-3 } else { 1.0 });
                let (mut yp, mut ym) = (y.clone(), y.clone());
                yp[j] += h;
                ym[j] -= h;
                let (mut fp, mut fm) = (vec![0.0; dim], vec![0.0; dim]);
                eq.rhs(t, &yp, &mut fp);
                eq.rhs(t, &ym, &mut fm);
                for i in 0..dim {
                    jfd[i * dim + j] = (fp[i] - fm[i]) / (2.0 * h);
                }
            }
            let mut jac = ArrowJacobian::new(&eq);
            jac.update(t, &y, &f0);
            // J from the linearisation: rows of q̈ are M⁻¹ G_q, M⁻¹ G_v
            let lin = jac.linearization();
            let m = lin.mass.to_dense();
            let (gq, gv) = (lin.g_q.to_dense(), lin.g_v.to_dense());
            for j in 0..nc {
                let col_q = dense_solve(m.clone(), (0..nc).map(|i| gq[i * nc + j]).collect());
                let col_v = dense_solve(m.clone(), (0..nc).map(|i| gv[i * nc + j]).collect());
                for i in 0..nc {
                    for (col, k) in [(&col_q, j), (&col_v, nc + j)] {
                        let (a, b) = (col[i], jfd[(nc + i) * dim + k]);
                        let sc = jfd[(nc + i) * dim..(nc + i + 1) * dim].iter().fold(1.0f64, |s, x| s.max(x.abs()));
                        assert!((a - b).abs() < 1e-6 * sc, "n = {n}, {d:?}: ∂q̈_{i}/∂y_{k}: {a} vs {b}");
                    }
                }
            }
            // the structured solve against a dense one
            let alpha = rng.range(10.0, 1e4);
            assert!(jac.factor(alpha));
            let b: Vec<f64> = (0..dim).map(|_| rng.range(-1.0, 1.0)).collect();
            let mut x = b.clone();
            jac.solve(&mut x);
            let mut a = vec![0.0; dim * dim];
            for i in 0..dim {
                for k in 0..dim {
                    a[i * dim + k] = -jfd[i * dim + k];
                }
                a[i * dim + i] += alpha;
            }
            let xd = dense_solve(a, b);
            let sc = xd.iter().fold(1e-300f64, |s, v| s.max(v.abs()));
            for i in 0..dim {
                assert!((x[i] - xd[i]).abs() < 1e-6 * sc, "n = {n}, α = {alpha}: x[{i}] = {} vs {}", x[i], xd[i]);
            }
        }
    }
}

#[test]
fn initial_conditions_of_the_rotor_give_the_closed_form_free_whirl() {
    // no balls, constant speed, C started off the axis and moving: in fixed axes
    // m0 z̈ + c ż + k z = ω² U e^{iωt}, whose solution is the steady whirl plus the free
    // vibration set by the initial conditions (closed form below)
    use num_complex::Complex64 as C;
    let mut p = PlanarRotor::paper();
    p.n = 0;
    let w = 250.0;
    let d = Drive::Speed { omega0: w };
    let mut st = settings(&p, 0.1, 0.001);
    st.rtol = 1e-11;
    st.atol = 1e-14;
    st.xy0 = [1e-3, -2e-3];
    st.xy_rate0 = [0.3, 0.1];
    let m0 = p.total_mass();
    let u_bal = C::new(p.m1 * p.s1 + p.m2 * p.s2, 0.0);
    let zp = |t: f64| u_bal * w * w * C::new(0.0, w * t).exp() / C::new(p.k - m0 * w * w, p.c * w);
    let disc = C::new(p.c * p.c - 4.0 * m0 * p.k, 0.0).sqrt();
    let (l1, l2) = ((-p.c + disc) / (2.0 * m0), (-p.c - disc) / (2.0 * m0));
    let z0 = C::new(st.xy0[0], st.xy0[1]) - zp(0.0);
    let v0 = C::new(st.xy_rate0[0], st.xy_rate0[1]) - zp(0.0) * C::new(0.0, w);
    // z_h = A e^{l1 t} + B e^{l2 t}: A + B = z0, l1 A + l2 B = v0
    let a = (v0 - l2 * z0) / (l1 - l2);
    let b = z0 - a;
    let exact = |t: f64| zp(t) + a * (l1 * t).exp() + b * (l2 * t).exp();
    let mut worst: f64 = 0.0;
    let s = simulate(&p, &d, &st, |x| {
        let e = exact(x.t);
        worst = worst.max((x.x - e.re).hypot(x.y - e.im));
        true
    })
    .unwrap();
    assert!(s.status.is_completed());
    assert!(worst < 1e-9 * 2e-3, "largest deviation from the closed form {worst:e} m");
}

#[test]
fn automatic_switching_gives_the_dop853_passage() {
    // paper 004's forward passage: the default method (DOP853 switching to RODAS where the
    // balls' drag pins its step) against DOP853 alone, at the default tolerance; samples before
    // the peak (the forced response) and the peak itself
    let p = PlanarRotor::paper();
    let d = Drive::Acceleration { omega0: 0.0, b: 2.5 };
    let mut res = vec![];
    for method in [Method::Dop853, Method::Auto] {
        let mut st = settings(&p, 240.0, 0.05);
        st.method = method;
        let mut amps = vec![];
        let s = simulate(&p, &d, &st, |x| {
            amps.push((x.t, x.amplitude));
            true
        })
        .unwrap();
        assert!(s.status.is_completed() && s.warnings.is_empty(), "{s:?}");
        res.push((s, amps));
    }
    let ((dop, a_dop), (auto, a_auto)) = (&res[0], &res[1]);
    let peak = dop.peak_amplitude;
    // both are within ~5e-8 of the peak of a reference at rtol 1e-12 (docs/notes/simulation.md)
    assert!((auto.peak_amplitude - peak).abs() < 1e-7 * peak, "peaks {} vs {}", auto.peak_amplitude, peak);
    let worst = a_dop.iter().zip(a_auto).filter(|(a, _)| a.0 <= dop.t_at_peak).map(|(a, b)| (a.1 - b.1).abs()).fold(0.0, f64::max);
    assert!(worst < 1e-7 * peak, "samples before the peak differ by {worst:e} m");
    assert!(auto.balanced && (auto.final_amplitude - dop.final_amplitude).abs() < 1e-6 * p.s2);
    assert!(
        auto.switches >= 2 && auto.implicit_steps > 0 && auto.steps * 5 < dop.steps,
        "auto {} steps ({} implicit), DOP853 {}",
        auto.steps,
        auto.implicit_steps,
        dop.steps
    );
}

#[test]
fn implicit_steps_do_not_hold_back_a_slow_instability() {
    // paper 004's reverse passage at b = −0.25 1/s²: near 301 rad/s the semi-balanced state
    // loses stability through a slow oscillation (eigenvalues ≈ 0.3 ± 13i 1/s, growing at
    // ~0.07 1/s²). RODAS steps of 1.6 s (|hλ| ≈ 21) damped it, so the balls left late and the
    // peak was 0.76 of the forward one instead of 0.94. The reference is DOP853 at tight
    // tolerances (its step, pinned by the balls' drag, resolves the oscillation; 0.938-0.940 at
    // any tolerance). When the departure sets in depends on the perturbation present there
    // (bifurcation delay, logarithmically): RODAS leaves perturbations of the order of atol,
    // so the automatic method converges as atol does (docs/notes/simulation.md).
    let p = PlanarRotor::paper();
    let d = Drive::Acceleration { omega0: 400.0, b: -0.25 };
    let peak = |method: Method, rtol: f64, atol: f64| {
        let st = Settings { method, rtol, atol, ..settings(&p, 1600.0, 0.4) };
        let s = simulate(&p, &d, &st, |_| true).unwrap();
        assert!(s.status.is_completed(), "{s:?}");
        s.peak_amplitude
    };
    let reference = peak(Method::Dop853, 1e-10, 1e-13);
    let default = peak(Method::Auto, 1e-8, 1e-9);
    assert!((default / reference - 1.0).abs() < 0.015, "auto at the default tolerance: {default} vs {reference}");
    let mut errors = vec![];
    for atol in [1e-11, 1e-13] {
        let tight = peak(Method::Auto, 1e-10, atol);
        errors.push((tight / reference - 1.0).abs());
    }
    assert!(errors.iter().all(|e| *e < 4e-3), "auto at rtol 1e-10, atol 1e-11 and 1e-13: relative errors {errors:?}");
    assert!(errors[1] < (default / reference - 1.0).abs(), "no convergence: {errors:?}, default {default} vs {reference}");
}

#[test]
fn many_balls_and_very_light_balls_run_promptly() {
    // 64 balls sharing the paper's ball mass: the cost of a step is linear in n; the passage
    // balances as with two balls
    // (more slowly: they must first gather, so the speed is held at 600 rad/s after the run-up)
    let mut p = PlanarRotor::paper();
    p.n = 64;
    p.m3 = 0.06 / 64.0;
    let (s, _) = run(&p, &Drive::SpeedSchedule { points: vec![(0.0, 200.0), (16.0, 600.0), (120.0, 600.0)] }, 120.0);
    assert!(s.balanced && s.warnings.is_empty(), "{s:?}");
    // m3 = 1e-9 kg: the balls relax in m3 r²/c_ψ ≈ 4e-14 s; explicit steps would be of that
    // size (issue 12: 12+ minutes). The switch to the implicit method keeps it to a few thousand.
    let mut p = PlanarRotor::paper();
    p.m3 = 1e-9;
    let (s, _) = run(&p, &Drive::Acceleration { omega0: 0.0, b: 2.5 }, 240.0);
    assert!(s.steps < 20_000 && s.implicit_steps > s.steps / 2, "{s:?}");
    assert!(!s.balanced, "1e-9 kg balls cannot balance");
}

#[test]
fn runs_that_miss_their_purpose_say_so() {
    // issue 12: a passage at b = 0.04 1/s² with the default 240 s ends at 9.6 rad/s
    let p = PlanarRotor::paper();
    let mut st = settings(&p, 240.0, 1.0);
    st.max_steps = 1_000_000;
    let s = simulate(&p, &Drive::Acceleration { omega0: 0.0, b: 0.04 }, &st, |_| true).unwrap();
    assert!(s.status.is_completed());
    assert!(s.warnings.iter().any(|w| w.contains("resonance was never reached")), "{:?}", s.warnings);
    // a run-up that ends just after resonance, the balls still slipping
    let s = simulate(&p, &Drive::Acceleration { omega0: 0.0, b: 2.5 }, &settings(&p, 125.0, 0.5), |_| true).unwrap();
    assert!(s.warnings.iter().any(|w| w.contains("before the motion settled")), "{:?}", s.warnings);
    // a complete passage has none
    let (s, _) = run(&p, &Drive::Acceleration { omega0: 200.0, b: 25.0 }, 16.0);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    // a step budget ends the run with a message, not a silent success
    let mut st = settings(&p, 240.0, 0.5);
    st.max_steps = 500;
    let s = simulate(&p, &Drive::Acceleration { omega0: 0.0, b: 2.5 }, &st, |_| true).unwrap();
    assert!(!s.status.is_completed() && s.t_end < 240.0);
    assert!(s.stopped.as_deref().is_some_and(|m| m.contains("step budget of 500 steps")), "{:?}", s.stopped);
}

#[test]
fn a_sweep_point_and_a_basin_run_are_the_simulation_of_the_same_config() {
    // Sweeps, Python's simulate_batch and basins keep only the summary, but must integrate with
    // the settings `simulate` uses: dt is also the automatic method's time resolution (implicit
    // steps of at most 4 dt; oscillations that do not decay within 4 dt are resolved). Sweeps
    // used to set dt = t_end for their one sample; in the reverse passage at b = −2.5 1/s² from
    // 600 rad/s, whose peak depends on any perturbation (docs/notes/simulation.md), a sweep then gave
    // 24.83 mm where `simulate` gave 19.81 mm. Equal here means bit for bit: the same steps from
    // the same settings, the samples only read the dense output.
    use autobal::paths::Parameters;
    use autobal::planar::problem::PlanarProblem;
    use autobal::sweep::simulate_batch;
    let root = autobal::config::parse(include_str!("../../../examples/planar.toml"), "planar.toml").unwrap();
    let mut base: PlanarProblem = autobal::config::planar(&root).unwrap();
    base.set("drive.omega0", 600.0).unwrap();
    for b in [-2.5, 2.5] {
        let mut p = base.clone();
        p.set("drive.b", b).unwrap();
        let full = simulate(&p.rotor, &p.drive, &p.settings, |_| true).unwrap();
        let mut got = None;
        simulate_batch(
            &base,
            &["drive.b"],
            &[b],
            &mut |_, _, r| {
                got = Some(r.summary.clone());
                true
            },
            &autobal::control::Control::none(),
        )
        .unwrap();
        let swept = got.unwrap();
        assert_eq!((swept.steps, swept.rejected_steps, swept.balanced), (full.steps, full.rejected_steps, full.balanced), "b = {b}");
        assert_eq!(swept.final_amplitude.to_bits(), full.final_amplitude.to_bits(), "b = {b}");
        assert_eq!(swept.peak_amplitude.to_bits(), full.peak_amplitude.to_bits(), "b = {b}: {} vs {}", swept.peak_amplitude, full.peak_amplitude);
    }

    // the spatial rotor: a basin run equals `simulate` on the same case
    use autobal::spatial::dynamics::basins::{basins, Case};
    use autobal::spatial::dynamics::simulate as spatial_simulate;
    let sim = autobal::config::spatial_simulation(&autobal::config::parse(include_str!("../../../examples/spatial.toml"), "spatial.toml").unwrap()).unwrap();
    let full = spatial_simulate(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, |_| true).unwrap();
    let case = Case { drive: sim.drive.clone(), initial: sim.initial.clone() };
    let basin = basins(&sim.rotor, &[case], &sim.settings, &autobal::control::Control::none()).unwrap().value.remove(0).unwrap();
    assert_eq!((basin.steps, basin.balanced), (full.steps, full.balanced));
    assert_eq!(basin.final_amplitude.to_bits(), full.final_amplitude.to_bits());
    assert_eq!(basin.peak_amplitude.to_bits(), full.peak_amplitude.to_bits());
}

#[test]
fn the_last_sample_is_the_end_of_the_run() {
    // Samples at k dt and at t_end where t_end is no multiple of dt (a CSV used to end at the
    // last multiple, without the state the summary describes; with dt > t_end it held only t = 0).
    let p = PlanarRotor::default();
    let d = Drive::Acceleration { omega0: 0.0, b: 25.0 };
    for (t_end, dt, times) in [(1.0, 0.3, vec![0.0, 0.3, 0.6, 0.9, 1.0]), (1.0, 0.25, vec![0.0, 0.25, 0.5, 0.75, 1.0]), (0.5, 2.0, vec![0.0, 0.5])] {
        let mut got = vec![];
        let mut last = 0.0;
        let s = simulate(&p, &d, &settings(&p, t_end, dt), |x| {
            got.push(x.t);
            last = x.amplitude;
            true
        })
        .unwrap();
        assert_eq!(got.len(), times.len(), "{got:?}");
        for (a, b) in got.iter().zip(&times) {
            assert!((a - b).abs() < 1e-12, "{got:?}");
        }
        assert_eq!(last.to_bits(), s.final_amplitude.to_bits(), "the last sample is the final state");
    }
}
