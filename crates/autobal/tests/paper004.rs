//! Paper 004's findings that depend on choices the paper leaves open (the disk inertia and
//! bearing drag of its torque runs) and its trends that the equations do not give as stated:
//! each verdict of docs/notes/paper004.md as a test that fails if the finding changes.

use autobal::planar::paper004::{settling_time, torque_outcomes, torque_rotor, torque_run, SWITCH_OFF, TORQUE_C_THETA, TORQUE_I_G};
use autobal::planar::stationary::{aligned_whirls, capacity_ratio, locked_amplitude};
use autobal::planar::{simulate, Drive, Method, PlanarRotor, Settings, Summary};

fn passage(p: &PlanarRotor, omega0: f64, b: f64, t_end: f64, tweak: impl FnOnce(&mut Settings)) -> (Summary, Vec<(f64, f64)>) {
    let mut st = Settings { dt: t_end / 4000.0, ..Settings::new(p, t_end) };
    tweak(&mut st);
    let mut tr = vec![];
    let s = simulate(p, &Drive::Acceleration { omega0, b }, &st, |x| {
        tr.push((x.t, x.amplitude));
        true
    })
    .unwrap();
    assert!(s.status.is_completed(), "{:?}", s.stopped);
    (s, tr)
}

/// Largest value of `f` over a fine speed grid around resonance.
fn max_over_speed(f: impl Fn(f64) -> f64) -> f64 {
    (0..40_000).map(|i| f(200.0 + 0.005 * i as f64)).fold(0.0, f64::max)
}

#[test]
fn the_chosen_inertia_and_drag_give_every_outcome_of_section_3() {
    let o = torque_outcomes(TORQUE_I_G, TORQUE_C_THETA, &autobal::control::Control::none()).unwrap();
    assert!(o.all(), "{o:?}");
    let rotor = torque_rotor(TORQUE_I_G, TORQUE_C_THETA);
    // Fig. 6b: the larger torque settles semi-balanced sooner
    let t91 = torque_run(&rotor, 91.0, None, 8.0, |_| true).unwrap().t_semi_balanced().unwrap();
    let t165 = torque_run(&rotor, 165.0, None, 8.0, |_| true).unwrap().t_semi_balanced().unwrap();
    assert!(t165 < 0.7 * t91, "91 N·m settles at {t91} s, 165 N·m at {t165} s");
    // Fig. 8: with c_ψ = 0.004 the balls swing round the race after resonance and the whirl
    // oscillates before it breaks down to s2 (measured: 0.73 s after resonance, against 0.97 s
    // with c_ψ = 0.1: under this torque the light drag does not prolong the transient);
    // switched off at 0.6 s the rotor runs back through resonance and the whirl dies out
    let mut light = rotor.clone();
    light.c_psi = 0.004;
    let r = torque_run(&light, 183.0, None, 4.0, |_| true).unwrap();
    assert!(r.summary.balanced, "{:?}", r.summary);
    let settle = r.t_semi_balanced().unwrap() - r.t_resonance().unwrap();
    let normal = torque_run(&rotor, 183.0, None, 4.0, |_| true).unwrap();
    let settle_normal = normal.t_semi_balanced().unwrap() - normal.t_resonance().unwrap();
    assert!(settle > 0.5 && settle < settle_normal, "settling after resonance: c_ψ = 0.004 {settle} s, 0.1 {settle_normal} s");
    let off = torque_run(&light, 183.0, Some(0.6), 6.0, |_| true).unwrap();
    assert!(off.t_back_below_resonance().is_some() && off.summary.final_amplitude < 0.5 * rotor.s2, "{:?}", off.summary);
}

#[test]
fn the_outcomes_change_with_the_inertia_and_the_drag() {
    // how the choice decides the outcomes (the report's sweep): too little bearing drag and
    // 18 N·m passes; too much and 73 N·m sticks; a lighter disk makes 73 N·m the higher peak
    let little_drag = torque_outcomes(TORQUE_I_G, 0.03, &autobal::control::Control::none()).unwrap();
    assert!(!little_drag.sticks_18 && little_drag.passes_73, "{little_drag:?}");
    // at c_θ = 0.3 the bearing alone holds 73 N·m below resonance (T/c_θ = 243 < 288 rad/s)
    let much_drag = torque_outcomes(TORQUE_I_G, 0.3, &autobal::control::Control::none()).unwrap();
    assert!(!much_drag.passes_73, "{much_drag:?}");
    // and 18 N·m at T/c_θ = 60 rad/s: with J_C/c_θ = 1 s the bearing alone gives
    // 60 (1 − e^{−10}) = 59.9973 rad/s at the end of the run (10 s); the whirl's c ω A² takes a
    // little more (measured 59.99698). It never passes and its speed has settled, though at
    // 60 rad/s the balls still creep when the run ends (settled by 30 s): sticking is about the
    // speed (`TorqueRun::speed_settled`), as in the paper's Fig. 6
    assert!(much_drag.omega_18 < 59.9973 && much_drag.omega_18 > 59.99, "{much_drag:?}");
    assert!(much_drag.sticks_18 && !much_drag.passes_73, "{much_drag:?}");
    for i_g in [0.01, 0.1] {
        let light = torque_outcomes(i_g, TORQUE_C_THETA, &autobal::control::Control::none()).unwrap();
        assert!(light.sticks_18 && light.passes_73 && light.balanced_183_before_off, "{light:?}");
        assert!(!light.smaller_torque_lower_peak, "I_G = {i_g}: {light:?}");
    }
    // the switch-off time 1.8 s is in the settled part only for a light enough disk
    let heavy = torque_outcomes(1.0, TORQUE_C_THETA, &autobal::control::Control::none()).unwrap();
    assert!(!heavy.balanced_183_before_off, "{heavy:?}");
    assert_eq!(SWITCH_OFF, 1.8);
}

#[test]
fn forward_peak_does_not_depend_on_the_acceleration_below_12_5() {
    // 004 Fig. 4a says the forward peak first rises with b, then falls. With the paper's
    // parameters it is the same to 0.2 % from 0.2 to 12.5 1/s² (0.04 and 0.08 too: the report),
    // whatever the initial ball angles and the tolerance, and falls only beyond 20 1/s²: the
    // whirl (2 m0/c = 0.05 s) and the balls (m3 r²/c_ψ ≈ 1 ms) follow the speed
    // quasi-statically, and the peak is set where the balls leave their sub-critical
    // equilibrium, at a fixed speed.
    let p = PlanarRotor::paper();
    let peak = |b: f64, tweak: fn(&mut Settings)| passage(&p, 200.0, b, 200.0 / b, tweak).0.peak_amplitude;
    let base = peak(2.5, |_| {});
    for (b, tweak) in [
        (0.2, (|_| {}) as fn(&mut Settings)),
        (12.5, |_| {}),
        (2.5, |s| s.psi0 = vec![0.0, 0.0]),
        (2.5, |s| s.psi0 = vec![3.0, 3.3]),
        (2.5, |s| s.rtol = 1e-10),
    ] {
        let v = peak(b, tweak);
        assert!((v / base - 1.0).abs() < 2e-3, "b = {b}: {v} vs {base}");
    }
    assert!(peak(50.0, |_| {}) < 0.7 * base);
    // the same peak is the passage's, not the stationary curve's (which is far lower)
    let held = max_over_speed(|w| locked_amplitude(&p, w, &Settings::default_psi0(2)));
    assert!(base > 1.6 * held, "{base} vs {held}");
}

#[test]
fn reverse_passage_at_a_quarter_is_lower_but_not_far_lower() {
    // 004 Fig. 3: "the maximum at the reverse passage is substantially lower". At the paper's
    // |b| = 0.25 1/s² the converged reverse peak is 6 % lower: DOP853 gives 0.938-0.940 of the
    // forward peak from 400, 600 or 1000 rad/s, at rtol 1e-8 to 1e-12, with the balls' initial
    // angles moved by 1e-3 rad (docs/notes/paper004.md); the automatic method 0.947 at the default
    // tolerance (it converges to DOP853's as atol falls: tests/simulation.rs). It is far lower
    // only for faster passages (0.54-0.75 at 2.5 1/s², tests/simulation.rs).
    let p = PlanarRotor::paper();
    let fwd = passage(&p, 200.0, 0.25, 800.0, |_| {}).0.peak_amplitude;
    for tweak in [
        (|s| s.method = Method::Dop853) as fn(&mut Settings),
        |s| {
            s.method = Method::Dop853;
            s.psi0[0] += 1e-3;
        },
        |s| s.method = Method::Auto,
    ] {
        let rev = passage(&p, 400.0, -0.25, 1600.0, tweak).0.peak_amplitude;
        let ratio = rev / fwd;
        assert!(ratio > 0.92 && ratio < 0.96, "reverse/forward = {ratio}");
    }
}

#[test]
fn reverse_peak_falls_with_the_deceleration_then_stays_flat() {
    // 004 Fig. 4b: the reverse peak "falls, then rises" with |b|. Reverse passages from
    // 1000 rad/s to rest as the report runs them (automatic method to 12.5 1/s², DOP853 beyond):
    // measured 30.22, 19.09, 11.70, 10.735, 10.735 mm at 0.25, 2.5, 12.5, 25, 50 1/s² (0.2 s of
    // CPU for all five). The fall follows, the rise does not.
    let p = PlanarRotor::paper();
    let peaks: Vec<f64> = [(0.25, Method::Auto), (2.5, Method::Auto), (12.5, Method::Auto), (25.0, Method::Dop853), (50.0, Method::Dop853)]
        .iter()
        .map(|&(b, method)| passage(&p, 1000.0, -b, 1000.0 / b, |s| s.method = method).0.peak_amplitude)
        .collect();
    // the fall, each step by a margin the runs' sensitivity cannot bridge. The 2.5 1/s² peak
    // has no converged value: 17.1-22.3 mm here with the method (auto, DOP853), rtol 1e-8 or
    // 1e-10, dt, and a ball started 1e-10 rad away, 17.1-24.6 mm in docs/notes/simulation.md; the
    // others move by less than 1.7 % (0.25: 29.7-30.2 mm; 12.5 and 25: to 0.1 mm). So
    // 0.25 → 2.5: measured 1.58×, at least 29.7/24.6 = 1.21× → asserted 1.15×; 2.5 → 12.5:
    // measured 1.63×, at least 17.1/11.7 = 1.46× → 1.3×; 12.5 → 25: measured 1.09× → 1.05×
    assert!(peaks[0] > 1.15 * peaks[1] && peaks[1] > 1.3 * peaks[2] && peaks[2] > 1.05 * peaks[3], "reverse peaks {peaks:?}");
    // no rise: 50 equals 25 1/s² (measured to 1.3e-5); 1e-3 is flat to the doc's 3 digits
    assert!((peaks[4] / peaks[3] - 1.0).abs() < 1e-3, "reverse peaks {peaks:?}");
}

#[test]
fn heavy_ball_drag_settles_sooner_to_the_eye_and_later_to_s2() {
    // 004 Fig. 5: c_ψ = 0.4 "increases the time to establish the semi-balanced mode". Within
    // 5 % of s2 (what a plot shows) it settles sooner than 0.1, because the balls no longer
    // slip round the race; within 0.1 % later, because the final approach to the balancing
    // positions goes at a rate proportional to 1/c_ψ.
    let b = 0.2;
    let mut times = vec![];
    for c_psi in [0.1, 0.4] {
        let p = PlanarRotor { c_psi, ..PlanarRotor::paper() };
        let (_, tr) = passage(&p, 200.0, b, 1000.0, |s| s.dt = 0.1);
        let t_res = (p.natural_frequency() - 200.0) / b;
        let eye = settling_time(&tr, p.s2, 0.05, t_res).unwrap() - t_res;
        let tight = settling_time(&tr, p.s2, 1e-3, t_res).unwrap() - t_res;
        times.push((eye, tight));
    }
    let ((eye1, tight1), (eye4, tight4)) = (times[0], times[1]);
    assert!(eye4 < 0.8 * eye1, "5 % band: c_ψ = 0.4 {eye4} s, 0.1 {eye1} s");
    assert!(tight4 > 2.0 * tight1, "0.1 % band: c_ψ = 0.4 {tight4} s, 0.1 {tight1} s");
}

#[test]
fn light_balls_peak_on_their_stationary_whirl_not_above_it() {
    // 004 Fig. 2a: with m3 = 0.01 kg the forward peak "exceeds the stationary maximum". At
    // b = 0.25 1/s² the balls follow the stationary whirl with both balls on the far side and
    // the peak is its maximum to 0.2 %, below the curve with the balls held evenly spread; an
    // overshoot above that curve appears only for fast passages (b = 25 1/s²).
    let p = PlanarRotor::paper_004(0.01);
    let far = max_over_speed(|w| aligned_whirls(&p, w).iter().filter(|a| a.q == 2).map(|a| a.amplitude).fold(0.0, f64::max));
    let held = max_over_speed(|w| locked_amplitude(&p, w, &Settings::default_psi0(2)));
    let slow = passage(&p, 200.0, 0.25, 600.0, |_| {}).0.peak_amplitude;
    assert!((slow / far - 1.0).abs() < 2e-3, "peak {slow} vs far-side maximum {far}");
    assert!(slow < held, "peak {slow} vs held-balls maximum {held}");
    let fast = passage(&p, 200.0, 25.0, 16.0, |_| {}).0.peak_amplitude;
    assert!(fast > held, "b = 25: peak {fast} vs held-balls maximum {held}");
}

#[test]
fn capacity_condition_readings() {
    // 004 eq (3) is garbled; the paper quotes α = 1.2 for m3 = 0.03 kg and 0.8 for 0.01 kg.
    // n m3 r / (m1 s1) gives 1.2 and 0.4: the 0.8 needs m3 = 0.02 kg. Our exact high-speed
    // condition gives 1.44 and 0.48, and 0.96 for 0.02 kg: that rotor does not balance either,
    // as the paper's Fig. 2 says of its light balls.
    let simple = |p: &PlanarRotor| p.n as f64 * p.m3 * p.r / (p.m1 * p.s1);
    let (heavy, light, mid) = (PlanarRotor::paper_004(0.03), PlanarRotor::paper_004(0.01), PlanarRotor::paper_004(0.02));
    assert!((simple(&heavy) - 1.2).abs() < 1e-12 && (simple(&light) - 0.4).abs() < 1e-12 && (simple(&mid) - 0.8).abs() < 1e-12);
    assert!((capacity_ratio(&heavy) - 1.44).abs() < 1e-12 && (capacity_ratio(&light) - 0.48).abs() < 1e-12);
    assert!((capacity_ratio(&mid) - 0.96).abs() < 1e-12);
    let s = simulate(&mid, &Drive::Speed { omega0: 600.0 }, &Settings { dt: 0.01, ..Settings::new(&mid, 3.0) }, |_| true).unwrap();
    assert!(!s.balanced && s.final_amplitude > 1.3 * mid.s2, "{s:?}");
}

/// Paper 004's eq (1) in fixed axes as the paper writes it (X, Y of the shaft point C, ball
/// angles ψ_j in the rotor frame, the speed prescribed: θ = ω0 t + b t²/2), two balls, γ = 0,
/// with the right-hand side of the translation equations multiplied by `sign`: +1 is Newton's
/// law (`m0 Ẍ + c Ẋ + k X = −d²/dt² [m1 s1 cos θ + (m2 + n m3) s2 cos θ + m3 r Σ cos(θ + ψ_j)]`),
/// −1 the sign the paper prints. Written independently of `autobal::planar` (which integrates in
/// rotor axes), so that with +1 it is also a second route to the planar model.
struct PrintedSign {
    p: PlanarRotor,
    sign: f64,
    omega0: f64,
    b: f64,
}

impl autobal::ode::System for PrintedSign {
    fn dim(&self) -> usize {
        8
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let (p, s) = (&self.p, self.sign);
        let (m3r, mr2) = (p.m3 * p.r, p.m3 * p.r * p.r);
        let m0 = p.m1 + p.m2 + 2.0 * p.m3;
        let (th, thd, thdd) = (self.omega0 * t + 0.5 * self.b * t * t, self.omega0 + self.b * t, self.b);
        let (st, ct) = th.sin_cos();
        let u = p.m1 * p.s1 + (p.m2 + 2.0 * p.m3) * p.s2;
        let (mut fx, mut fy) = (u * (thd * thd * ct + thdd * st), u * (thd * thd * st - thdd * ct));
        // rows: X, Y, ψ1, ψ2; the ψ̈ terms of the translation rows carry its sign too
        let mut a = [[m0, 0.0, 0.0, 0.0], [0.0, m0, 0.0, 0.0], [0.0; 4], [0.0; 4]];
        let mut f = [0.0; 4];
        for j in 0..2 {
            let (sa, ca) = (th + y[2 + j]).sin_cos();
            let ad = thd + y[6 + j];
            fx += m3r * (ad * ad * ca + thdd * sa);
            fy += m3r * (ad * ad * sa - thdd * ca);
            a[0][2 + j] = -s * m3r * sa;
            a[1][2 + j] = s * m3r * ca;
            a[2 + j] = [-m3r * sa, m3r * ca, 0.0, 0.0];
            a[2 + j][2 + j] = mr2;
            let psi = y[2 + j];
            f[2 + j] = -p.c_psi * y[6 + j] - mr2 * thdd - m3r * p.s2 * (thd * thd * psi.sin() + thdd * psi.cos());
        }
        f[0] = -p.c * y[4] - p.k * y[0] + s * fx;
        f[1] = -p.c * y[5] - p.k * y[1] + s * fy;
        // Gaussian elimination with partial pivoting
        for c in 0..4 {
            let piv = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs())).unwrap_or(c);
            a.swap(c, piv);
            f.swap(c, piv);
            for r in c + 1..4 {
                let q = a[r][c] / a[c][c];
                let row = a[c];
                a[r].iter_mut().zip(row).for_each(|(x, v)| *x -= q * v);
                f[r] -= q * f[c];
            }
        }
        let mut acc = [0.0; 4];
        for r in (0..4).rev() {
            acc[r] = (f[r] - (r + 1..4).map(|k| a[r][k] * acc[k]).sum::<f64>()) / a[r][r];
        }
        dy[..4].copy_from_slice(&y[4..]);
        dy[4..].copy_from_slice(&acc);
    }
}

/// A forward passage of [`PrintedSign`] from rest to 600 rad/s by DOP853: `(peak radius of C,
/// final radius, final ball angles from the unbalance in degrees)`.
fn printed_sign_passage(p: &PlanarRotor, sign: f64, b: f64) -> (f64, f64, [f64; 2]) {
    use autobal::ode::{Control, Options, Solver};
    let sys = PrintedSign { p: p.clone(), sign, omega0: 0.0, b };
    let psi0 = Settings::default_psi0(2);
    let mut y = [0.0, 0.0, psi0[0], psi0[1], 0.0, 0.0, 0.0, 0.0];
    let mut solver = Solver::new(&sys, Options::new(1e-8, 1e-9).method(Method::Dop853)).unwrap();
    let mut peak = 0.0f64;
    let out = solver.integrate(0.0, &mut y, 600.0 / b, |st| {
        peak = peak.max(st.y_new[0].hypot(st.y_new[1]));
        Control::Continue
    });
    assert!(out.status.is_completed(), "{:?}", out.status);
    let deg = |x: f64| (x.to_degrees() + 180.0).rem_euclid(360.0) - 180.0;
    (peak, y[0].hypot(y[1]), [deg(y[2]), deg(y[3])])
}

#[test]
fn the_printed_sign_of_the_translation_equation_gives_no_semi_balancing() {
    // 004 prints eq (1)'s translation equations with `+` where Newton's law gives `−`. Could the
    // trends the correct sign does not give come from the printed one? No: with the printed sign
    // the balls balance the rotor below resonance and gather near the unbalance above it, so
    // the rotor never settles semi-balanced at s2 after the passage, which the paper's Figs 3-8
    // all show. (docs/notes/paper004.md: its peaks also fall with b from 0.25 1/s², with no rise.)
    let p = PlanarRotor::paper();
    let b = 12.5;
    // Newton's sign in fixed axes: the planar model's passage (a second route), semi-balanced
    let (peak, fin, _) = printed_sign_passage(&p, 1.0, b);
    let (model, _) = passage(&p, 0.0, b, 600.0 / b, |_| {});
    assert!((peak / model.peak_amplitude - 1.0).abs() < 2e-3, "peak {peak} vs planar model {}", model.peak_amplitude);
    assert!((fin / model.final_amplitude - 1.0).abs() < 1e-2, "final {fin} vs planar model {}", model.final_amplitude);
    assert!(fin < 1.1 * p.s2, "Newton's sign: semi-balanced, {fin} m");
    // the printed sign: far from s2 above resonance, both balls within 30° of the unbalance
    let (_, fin, psi) = printed_sign_passage(&p, -1.0, b);
    assert!(fin > 10.0 * p.s2, "printed sign: final radius {fin} m");
    assert!(psi.iter().all(|a| a.abs() < 30.0), "printed sign: balls at {psi:?}° from the unbalance");
}
