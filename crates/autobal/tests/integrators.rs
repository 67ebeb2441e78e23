//! The integrators of `autobal::ode`: orders measured under step halving (DOP853 8, its dense
//! output 7, RODAS 4, its dense output 3) on problems with known solutions, stiffness, the
//! automatic switching against pure DOP853, events, cancellation, budgets, failures.

use autobal::ode::{Control, DenseJacobian, Direction, Event, Jacobian, Method, Options, Solver, Status, System};

/// A non-stiff test problem with a known solution, nonlinear, coupled and non-autonomous: a
/// limit cycle `x' = −y + x(1 − r²)`, `y' = x + y(1 − r²)` (`r' = r(1 − r²)`, so
/// `r = 1/sqrt(1 + 3e^{−2t})` from `r = 1/2`, angle `t`), and `z' = cos(3t) z + (x² + y² − r(t)²)`
/// (`z = exp(sin(3t)/3)`: the coupling term vanishes on the exact solution but not on the
/// numerical one).
struct Mixed;
fn radius(t: f64) -> f64 {
    1.0 / (1.0 + 3.0 * (-2.0 * t).exp()).sqrt()
}
impl System for Mixed {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let r2 = y[0] * y[0] + y[1] * y[1];
        dy[0] = -y[1] + y[0] * (1.0 - r2);
        dy[1] = y[0] + y[1] * (1.0 - r2);
        dy[2] = (3.0 * t).cos() * y[2] + (r2 - radius(t).powi(2));
    }
    fn jacobian(&self) -> Box<dyn Jacobian + '_> {
        // exact, so that the implicit method's measured order is not limited by difference
        // increments
        Box::new(
            DenseJacobian::analytic(self, |t, y, j| {
                let (x, z) = (y[0], y[1]);
                let r2 = x * x + z * z;
                j.copy_from_slice(&[
                    1.0 - r2 - 2.0 * x * x,
                    -1.0 - 2.0 * x * z,
                    0.0,
                    1.0 - 2.0 * x * z,
                    1.0 - r2 - 2.0 * z * z,
                    0.0,
                    2.0 * x,
                    2.0 * z,
                    (3.0 * t).cos(),
                ]);
            })
            .with_time_derivative(|t, y, out| {
                // d/dt r(t)² = 6 e^{−2t} / (1 + 3 e^{−2t})²
                let e = (-2.0 * t).exp();
                out[0] = 0.0;
                out[1] = 0.0;
                out[2] = -3.0 * (3.0 * t).sin() * y[2] - 6.0 * e / (1.0 + 3.0 * e).powi(2);
            }),
        )
    }
}
fn mixed_exact(t: f64) -> [f64; 3] {
    let r = radius(t);
    [r * t.cos(), r * t.sin(), ((3.0 * t).sin() / 3.0).exp()]
}
fn max_err(y: &[f64], e: &[f64]) -> f64 {
    y.iter().zip(e).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
}

fn fixed(method: Method, h: f64) -> Options {
    let mut o = Options::new(1e-6, 1e-6).method(method);
    o.fixed_step = Some(h);
    o
}

/// Global error at `t_end` with fixed steps `h`.
fn global_error(method: Method, h: f64, t_end: f64) -> f64 {
    let mut s = Solver::new(&Mixed, fixed(method, h)).unwrap();
    let mut y = mixed_exact(0.0);
    let out = s.integrate(0.0, &mut y, t_end, |_| Control::Continue);
    assert!(out.status.is_completed());
    max_err(&y, &mixed_exact(t_end))
}

/// Error after one step of size `h` from the exact state at `t0` (`O(h^{p+1})` for order `p`).
fn local_error(method: Method, t0: f64, h: f64) -> f64 {
    let mut s = Solver::new(&Mixed, fixed(method, h)).unwrap();
    let mut y = mixed_exact(t0);
    s.integrate(t0, &mut y, t0 + h, |_| Control::Continue);
    max_err(&y, &mixed_exact(t0 + h))
}

/// Largest error of the dense output inside one step of size `h` taken from the exact state at
/// `t0` (the local error of the interpolant, `O(h^{p+1})` for a dense output of order `p`).
fn dense_local_error(method: Method, h: f64) -> f64 {
    let t0 = 0.4;
    let mut s = Solver::new(&Mixed, fixed(method, h)).unwrap();
    let mut y = mixed_exact(t0);
    let mut worst: f64 = 0.0;
    let mut out = [0.0; 3];
    s.integrate(t0, &mut y, t0 + h, |step| {
        for th in [0.2, 0.45, 0.7, 0.9] {
            let t = step.t_old + th * (step.t_new - step.t_old);
            step.interpolate(t, &mut out);
            worst = worst.max(max_err(&out, &mixed_exact(t)));
        }
        Control::Continue
    });
    worst
}

/// `log2` of successive error ratios under step halving.
fn orders(errs: &[f64]) -> Vec<f64> {
    errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn dop853_is_of_order_8_under_step_halving() {
    // global errors at t = 4 with fixed steps, from ~4e-7 down to ~2e-12 (above rounding).
    // Measured: 2^8.8, 2^8.9. DOP853's eighth-order error constants are small (the method was
    // built that way), so over the step sizes reachable above rounding the error falls slightly
    // faster than h⁸; a wrong coefficient drops the order to 5 or less.
    let errs: Vec<f64> = [0.4, 0.2, 0.1].iter().map(|h| global_error(Method::Dop853, *h, 4.0)).collect();
    let p = orders(&errs);
    for q in &p {
        assert!(*q > 7.7 && *q < 9.3, "observed orders {p:?} (errors {errs:?})");
    }
    // the local error of one step: O(h⁹). Measured from t0 = 1 under two halvings: 2^8.94 and
    // 2^9.07 (errors 5e-9 → 1.9e-14, above rounding); the bracket ±0.3 is the spread of the
    // local slopes over h = 0.3-0.075 (8.9-9.1) with room for the O(h¹⁰) term. (From t0 = 0.4
    // one component's h⁹ coefficient nearly vanishes and the ratios scatter, 2^4.9-2^11.8.)
    let errs: Vec<f64> = [0.3, 0.15, 0.075].iter().map(|h| local_error(Method::Dop853, 1.0, *h)).collect();
    let p = orders(&errs);
    for q in &p {
        assert!((q - 9.0).abs() < 0.3, "observed local orders {p:?} (errors {errs:?})");
    }
}

#[test]
fn dop853_dense_output_is_of_order_7() {
    // largest error of the interpolant inside one step from exact data: O(h^8), measured
    // 2^8.06-2^8.09 per halving
    let errs: Vec<f64> = [0.4, 0.2, 0.1, 0.05].iter().map(|h| dense_local_error(Method::Dop853, *h)).collect();
    let p: Vec<f64> = orders(&errs).iter().map(|q| q - 1.0).collect();
    for q in &p {
        assert!((q - 7.0).abs() < 0.2, "observed dense orders {p:?} (errors {errs:?})");
    }
}

#[test]
fn rodas_is_of_order_4_under_step_halving() {
    // with the exact Jacobian and ∂f/∂t; at larger steps the error falls faster (2^5.1-2^5.3
    // for h = 0.1 … 0.025), then settles to order 4 (measured 2^3.99, 2^3.91) above rounding
    let errs: Vec<f64> = [0.0125, 0.00625, 0.003125].iter().map(|h| global_error(Method::Rodas, *h, 4.0)).collect();
    let p = orders(&errs);
    for q in &p {
        assert!((q - 4.0).abs() < 0.25, "observed orders {p:?} (errors {errs:?})");
    }
}

#[test]
fn rodas_dense_output_is_of_order_3() {
    // largest error of the interpolant inside one step from exact data: O(h⁴), measured
    // 2^4.13-2^4.03 per halving
    let errs: Vec<f64> = [0.1, 0.05, 0.025, 0.0125].iter().map(|h| dense_local_error(Method::Rodas, *h)).collect();
    let p: Vec<f64> = orders(&errs).iter().map(|q| q - 1.0).collect();
    for q in &p {
        assert!((q - 3.0).abs() < 0.2, "observed dense orders {p:?} (errors {errs:?})");
    }
}

#[test]
fn adaptive_dop853_meets_its_tolerance_with_few_steps() {
    let mut s = Solver::new(&Mixed, Options::new(1e-10, 1e-12).method(Method::Dop853)).unwrap();
    let mut y = mixed_exact(0.0);
    let out = s.integrate(0.0, &mut y, 20.0, |_| Control::Continue);
    assert_eq!(out.status, Status::Completed);
    assert_eq!(out.t, 20.0);
    assert!(max_err(&y, &mixed_exact(20.0)) < 1e-8, "{}", max_err(&y, &mixed_exact(20.0)));
    assert!(out.stats.steps > 10 && out.stats.steps < 400, "{:?}", out.stats);
}

/// Prothero–Robinson with a stiffness that changes in time: `y' = −L(t)(y − sin t) + cos t`,
/// solution `y = sin t` whatever `L`; with a non-stiff oscillator beside it.
struct Pr {
    l: fn(f64) -> f64,
}
impl System for Pr {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = -(self.l)(t) * (y[0] - t.sin()) + t.cos();
        dy[1] = y[2];
        dy[2] = -y[1];
    }
}

#[test]
fn rodas_takes_few_steps_on_a_stiff_problem() {
    let sys = Pr { l: |_| 1e6 };
    let mut s = Solver::new(&sys, Options::new(1e-8, 1e-8).method(Method::Rodas)).unwrap();
    let mut y = [0.0, 1.0, 0.0];
    let out = s.integrate(0.0, &mut y, 10.0, |_| Control::Continue);
    assert!(out.status.is_completed());
    assert!((y[0] - 10f64.sin()).abs() < 1e-8, "{}", y[0] - 10f64.sin());
    // an explicit method needs ≥ L·T/6 ≈ 1.7·10⁶ steps for stability alone
    assert!(out.stats.steps < 300, "{:?}", out.stats);
}

#[test]
fn automatic_switching_is_as_accurate_as_dop853_at_a_fraction_of_the_steps() {
    // stiff (L = 1e5) until t ≈ 5, then non-stiff (L → 0.5 by t ≈ 9, smoothly): the switch
    // must go both ways
    let sys = Pr { l: |t| 0.5 + 1e5 / (1.0 + (4.0 * (t - 6.0)).exp()) };
    let run = |m: Method| {
        let mut s = Solver::new(&sys, Options::new(1e-8, 1e-9).method(m)).unwrap();
        let mut y = [0.0, 1.0, 0.0];
        let mut worst: f64 = 0.0;
        let out = s.integrate(0.0, &mut y, 12.0, |st| {
            let t = st.t_new;
            worst = worst.max((st.y_new[0] - t.sin()).abs()).max((st.y_new[1] - t.cos()).abs());
            Control::Continue
        });
        assert!(out.status.is_completed());
        (worst, out.stats)
    };
    let (e_dop, s_dop) = run(Method::Dop853);
    let (e_auto, s_auto) = run(Method::Auto);
    // measured: DOP853 1.6e-8 in 93 960 steps, auto 1.3e-8 in 833 (610 implicit)
    assert!(e_dop < 3e-8 && e_auto < 3e-8, "errors: DOP853 {e_dop:e}, auto {e_auto:e}");
    assert!(s_auto.switches >= 2, "switched to RODAS and back: {s_auto:?}");
    assert!(s_auto.implicit_steps > 0 && s_auto.steps < s_dop.steps / 10, "auto {s_auto:?} vs DOP853 {s_dop:?}");
}

/// `y'' = −y` from `y(0) = 1`: zeros of `y` at `π/2 + kπ`.
struct Osc;
impl System for Osc {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }
}
struct Zero(Direction, bool);
impl Event for Zero {
    fn g(&self, _t: f64, y: &[f64]) -> f64 {
        y[0]
    }
    fn direction(&self) -> Direction {
        self.0
    }
    fn terminal(&self) -> bool {
        self.1
    }
}

#[test]
fn events_are_located_on_the_dense_output() {
    use std::f64::consts::PI;
    for method in [Method::Dop853, Method::Rodas] {
        // non-terminal, both directions: every zero in [0, 10]
        let mut s = Solver::new(&Osc, Options::new(1e-12, 1e-12).method(method)).unwrap();
        s.add_event(Zero(Direction::Either, false));
        let mut y = [1.0, 0.0];
        let mut found = vec![];
        let out = s.integrate(0.0, &mut y, 10.0, |st| {
            found.extend(st.events.iter().map(|e| e.1));
            Control::Continue
        });
        assert!(out.status.is_completed());
        assert_eq!(found.len(), 3, "{method}: {found:?}");
        for (k, t) in found.iter().enumerate() {
            assert!((t - (PI / 2.0 + k as f64 * PI)).abs() < 1e-9, "{method}: zero {k} at {t}");
        }
        // terminal, falling only: stops at π/2 with the state there; going on finds 5π/2
        let mut s = Solver::new(&Osc, Options::new(1e-12, 1e-12).method(method)).unwrap();
        s.add_event(Zero(Direction::Falling, true));
        let mut y = [1.0, 0.0];
        let out = s.integrate(0.0, &mut y, 10.0, |_| Control::Continue);
        assert_eq!(out.status, Status::Event(0));
        assert!((out.t - PI / 2.0).abs() < 1e-9 && y[0].abs() < 1e-9 && (y[1] + 1.0).abs() < 1e-9, "{method}: {} {y:?}", out.t);
        let out = s.integrate(out.t, &mut y, 10.0, |_| Control::Continue);
        assert_eq!(out.status, Status::Event(0), "the zero it stopped at is not found again");
        assert!((out.t - 2.5 * PI).abs() < 1e-9, "{method}: {}", out.t);
    }
}

#[test]
fn cancellation_and_budgets_end_a_run_with_an_explicit_status() {
    use autobal::control::{Control as RunControl, StopReason};
    let run = RunControl::new();
    let sys = Pr { l: |_| 1e5 };
    let mut s = Solver::new(&sys, Options::new(1e-8, 1e-8).method(Method::Dop853)).unwrap();
    s.control(&run);
    let mut y = [0.0, 1.0, 0.0];
    let mut n = 0;
    let out = s.integrate(0.0, &mut y, 100.0, |_| {
        n += 1;
        if n == 50 {
            run.cancel(); // e.g. Ctrl-C from another thread
        }
        Control::Continue
    });
    assert_eq!(out.status, Status::Stopped(StopReason::Interrupted));
    assert_eq!(out.stats.steps, 50, "stopped at the next step");
    assert!(out.t > 0.0 && out.t < 100.0 && (y[0] - out.t.sin()).abs() < 1e-6, "the state is the one at t = {}", out.t);
    assert!(format!("{out}").starts_with("interrupted at t = "));
    // step budget
    let mut o = Options::new(1e-8, 1e-8).method(Method::Dop853);
    o.max_steps = 1000;
    let mut s = Solver::new(&sys, o).unwrap();
    let mut y = [0.0, 1.0, 0.0];
    let out = s.integrate(0.0, &mut y, 100.0, |_| Control::Continue);
    assert_eq!(out.status, Status::Stopped(StopReason::TooManySteps { max_steps: 1000 }));
    assert!(format!("{out}").contains("step budget of 1000 steps"));
    // the observer stops
    let mut s = Solver::new(&Osc, Options::new(1e-8, 1e-8)).unwrap();
    let out = s.integrate(0.0, &mut [1.0, 0.0], 10.0, |st| if st.t_new > 1.0 { Control::Stop } else { Control::Continue });
    assert_eq!(out.status, Status::Stopped(StopReason::Observer));
    // a zero wall-time budget of the control: stopped before the first step, the state untouched
    let spent = RunControl::new().with_budget(std::time::Duration::ZERO);
    let mut s = Solver::new(&Osc, Options::new(1e-8, 1e-8)).unwrap();
    s.control(&spent);
    let mut y = [1.0, 0.0];
    let out = s.integrate(0.0, &mut y, 10.0, |_| Control::Continue);
    assert_eq!((out.status, out.t, out.stats.steps, y), (Status::Stopped(StopReason::Budget { seconds: 0.0 }), 0.0, 0, [1.0, 0.0]));
}

#[test]
fn a_blow_up_is_reported_not_passed_on() {
    // y' = y² from y(0) = 1: y = 1/(1 − t) blows up at t = 1
    struct Blow;
    impl System for Blow {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[0] * y[0];
        }
        fn component_name(&self, _i: usize) -> String {
            "the blowing-up one".into()
        }
    }
    for m in [Method::Dop853, Method::Rodas, Method::Auto] {
        let mut s = Solver::new(&Blow, Options::new(1e-8, 1e-8).method(m)).unwrap();
        let mut y = [1.0];
        let out = s.integrate(0.0, &mut y, 2.0, |_| Control::Continue);
        assert!(!out.status.is_completed(), "{m}: {out:?}");
        assert!(out.t > 0.99 && out.t < 1.01, "{m}: stopped at {}", out.t);
        assert!(y[0].is_finite(), "the state returned is the last finite one");
        match &out.status {
            Status::StepTooSmall { .. } => {}
            Status::NotFinite { name, .. } => assert_eq!(name, "the blowing-up one"),
            s => panic!("{m}: {s:?}"),
        }
    }
    // NaN from the start names the component
    let mut s = Solver::new(&Osc, Options::new(1e-8, 1e-8)).unwrap();
    let out = s.integrate(0.0, &mut [1.0, f64::NAN], 1.0, |_| Control::Continue);
    assert_eq!(out.status, Status::NotFinite { component: 1, name: "y[1]".into() });
}

#[test]
fn options_are_checked_and_name_the_field() {
    let e = |o: Options| Solver::new(&Osc, o).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e(Options::new(0.0, 1e-8)).starts_with("integration.rtol"));
    assert!(e(Options::new(1.0, 1e-8)).starts_with("integration.rtol"));
    assert!(e(Options::new(1e-20, 1e-8)).starts_with("integration.rtol"));
    assert!(e(Options::new(1e-8, -1.0)).starts_with("integration.atol"));
    assert!(e(Options::new(1e-8, 1e-8).atol_per_component(vec![1e-8; 3])).starts_with("integration.atol"));
}

#[test]
fn dense_difference_jacobian_matches_the_closed_form() {
    struct Nl;
    impl System for Nl {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1] * y[2] + t;
            dy[1] = y[0].sin() - 2.0 * y[1];
            dy[2] = y[0] * y[0] * y[2];
        }
    }
    let (t, y) = (0.3, [0.7f64, -1.2, 2.5]);
    let exact = [0.0, y[2], y[1], y[0].cos(), -2.0, 0.0, 2.0 * y[0] * y[2], 0.0, y[0] * y[0]];
    let mut f0 = [0.0; 3];
    Nl.rhs(t, &y, &mut f0);
    let b = [1.0, -2.0, 0.5];
    let solve = |j: &mut dyn Jacobian| {
        j.update(t, &y, &f0);
        assert!(j.factor(3.0));
        let mut x = b;
        j.solve(&mut x);
        x
    };
    let x_fd = solve(&mut DenseJacobian::differences(&Nl));
    let x_an = solve(&mut DenseJacobian::analytic(&Nl, move |_, _, jac| jac.copy_from_slice(&exact)));
    // (3 I − J) x = b
    for i in 0..3 {
        let r: f64 = 3.0 * x_an[i] - (0..3).map(|k| exact[3 * i + k] * x_an[k]).sum::<f64>();
        assert!((r - b[i]).abs() < 1e-13, "closed-form solve residual {}", r - b[i]);
        assert!((x_fd[i] - x_an[i]).abs() < 1e-7, "difference Jacobian: {x_fd:?} vs {x_an:?}");
    }
}
