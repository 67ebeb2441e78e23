//! DOP853 over one interval with nothing else: no events, no observer, no dense output, no
//! method switching, no budgets (only the thread's stop probe, [`crate::control::with_probe`],
//! asked every 256 steps). For the many short integrations of a shooting method (the flow
//! over a period, the variational equations `Φ' = J Φ` on `n²` states), where
//! [`Solver::integrate`](super::Solver::integrate)'s generality is not used.
//!
//! The step is DOP853's ([`super::dop853`], Hairer's `dop853.f`), with the same initial step,
//! error norm and step-size control as [`Solver`](super::Solver) under
//! [`Method::Dop853`](super::Method::Dop853), and the same arithmetic in the same order: the
//! stage sums `y + h Σ_j a_sj k_j` are accumulated stage by stage over contiguous vectors
//! (`acc_i += a_sj k_j,i` for `j` increasing, the tableau's zeros skipped, as
//! [`super::dop853`] sums them component by component), so the steps taken and the result are
//! bit for bit those of `Solver` (tested); only the loops are ordered for long states (an axpy
//! per stage instead of a short gather per component).

use super::dop853;
use super::dop853_tableau as tab;
use super::{Outcome, Stats, Status, System};
use crate::control::StopReason;

/// Buffers of [`integrate`] for a state of length `n`; reusable between calls.
pub struct Lean {
    n: usize,
    /// The 13 stage derivatives `k_0 .. k_12` (`k_12 = f(t + h, y_new)`).
    k: Vec<f64>,
    y: Vec<f64>,
    y_new: Vec<f64>,
    ys: Vec<f64>,
    acc: Vec<f64>,
    acc5: Vec<f64>,
    tmp: Vec<f64>,
}

impl Lean {
    /// Buffers for states of length `n`.
    pub fn new(n: usize) -> Self {
        let v = || vec![0.0; n];
        Lean { n, k: vec![0.0; (tab::N_STAGES + 1) * n], y: v(), y_new: v(), ys: v(), acc: v(), acc5: v(), tmp: v() }
    }

    /// `ys = y + h Σ_{j<s} a_sj k_j` (stage row `s`), summed in the order of
    /// [`dop853::stage_state`]: `acc_i = Σ_j a_sj k_j,i` over `j` increasing, non-zero `a_sj`,
    /// then `y_i + h acc_i`.
    fn stage_state(&mut self, s: usize, h: f64) {
        let n = self.n;
        self.acc.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..s {
            let a = tab::A[s][j];
            if a != 0.0 {
                for (o, kj) in self.acc.iter_mut().zip(&self.k[j * n..(j + 1) * n]) {
                    *o += a * kj;
                }
            }
        }
        for ((o, y), a) in self.ys.iter_mut().zip(&self.y).zip(&self.acc) {
            *o = y + h * a;
        }
    }

    /// One attempted step from `(t, y)` with `k_0` in place: as `dop853::Work::attempt`, its
    /// error norm (`≤ 1` to accept) with `y_new`.
    fn attempt<S: System + ?Sized>(&mut self, sys: &S, t: f64, h: f64, atol: &[f64], rtol: f64) -> f64 {
        let n = self.n;
        for s in 1..tab::N_STAGES {
            self.stage_state(s, h);
            sys.rhs(t + tab::C[s] * h, &self.ys, &mut self.k[s * n..(s + 1) * n]);
        }
        // b = Σ B_j k_j and a5 = Σ E5_j k_j per component, j increasing (as
        // dop853::solution_and_error)
        self.acc.iter_mut().for_each(|v| *v = 0.0);
        self.acc5.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..tab::N_STAGES {
            let kj = &self.k[j * n..(j + 1) * n];
            if tab::B[j] != 0.0 {
                for (o, k) in self.acc.iter_mut().zip(kj) {
                    *o += tab::B[j] * k;
                }
            }
            if tab::E5[j] != 0.0 {
                for (o, k) in self.acc5.iter_mut().zip(kj) {
                    *o += tab::E5[j] * k;
                }
            }
        }
        let (k0, k8, k11) = (&self.k[..n], &self.k[8 * n..9 * n], &self.k[11 * n..12 * n]);
        let (mut e5, mut e3) = (0.0, 0.0);
        for i in 0..n {
            let (b, a5) = (self.acc[i], self.acc5[i]);
            let a3 = b - tab::BHH[0] * k0[i] - tab::BHH[1] * k8[i] - tab::BHH[2] * k11[i];
            let v = self.y[i] + h * b;
            self.y_new[i] = v;
            let sk = atol[i] + rtol * self.y[i].abs().max(v.abs());
            e5 += (a5 / sk) * (a5 / sk);
            e3 += (a3 / sk) * (a3 / sk);
        }
        let mut deno = e5 + 0.01 * e3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * e5 * (1.0 / (n as f64 * deno)).sqrt()
    }
}

/// Integrate `y' = f(t, y)` from `(t0, y)` to `t_end` by DOP853 at `rtol` and per-component
/// `atol` (`y` advanced in place), with the initial step, step-size control (factor
/// `0.9 err^{−1/8}` within `[1/3, 6]`, not above 1 after a rejection; a non-finite step cut
/// fivefold) and end handling of [`Solver`](super::Solver) under `Method::Dop853` with default
/// options: the same steps and, bit for bit, the same result ([module docs](self)). The
/// [`Outcome`] says how it ended (`Completed`, `StepTooSmall`, `NotFinite`, or `Stopped` when
/// this thread's stop probe says so, [`crate::control::with_probe`]).
pub fn integrate<S: System + ?Sized>(sys: &S, work: &mut Lean, t0: f64, y: &mut [f64], t_end: f64, rtol: f64, atol: &[f64]) -> Outcome {
    integrate_capped(sys, work, t0, y, t_end, rtol, atol, u64::MAX)
}

/// [`integrate`] with at most `max_steps` attempted steps (accepted and rejected): past them
/// it stops with `Stopped(TooManySteps)`, the state at the last accepted step.
#[allow(clippy::too_many_arguments)]
pub fn integrate_capped<S: System + ?Sized>(sys: &S, work: &mut Lean, t0: f64, y: &mut [f64], t_end: f64, rtol: f64, atol: &[f64], max_steps: u64) -> Outcome {
    let n = work.n;
    assert!(y.len() == n && atol.len() == n && sys.dim() == n, "state, atol and system of length n");
    let mut stats = Stats::default();
    let not_finite = |v: &[f64]| v.iter().position(|x| !x.is_finite()).map(|i| Status::NotFinite { component: i, name: sys.component_name(i) });
    let mut t = t0;
    if let Some(s) = not_finite(y) {
        return Outcome { status: s, t, stats };
    }
    if !(t_end > t0) {
        return Outcome { status: Status::Completed, t, stats };
    }
    work.y.copy_from_slice(y);
    sys.rhs(t, y, &mut work.k[..n]);
    stats.rhs_evaluations += 1;
    if let Some(s) = not_finite(&work.k[..n]) {
        return Outcome { status: s, t, stats };
    }
    let mut h = {
        for i in 0..n {
            work.tmp[i] = atol[i] + rtol * work.y[i].abs();
        }
        let (f0, rest) = work.k.split_at_mut(n);
        stats.rhs_evaluations += 1;
        dop853::initial_step(sys, t, &work.y, f0, f64::INFINITY, dop853::ORDER, &work.tmp, &mut work.y_new, &mut rest[..n])
    };
    let q = dop853::ORDER as f64;
    let mut rejected_last = false;
    let mut attempts = 0u32;
    loop {
        // this thread's stop probe, every 256 attempted steps (crate::control::with_probe)
        attempts = attempts.wrapping_add(1);
        if attempts.is_multiple_of(256) {
            if let Some(why) = crate::control::probe() {
                y.copy_from_slice(&work.y);
                return Outcome { status: Status::Stopped(why), t, stats };
            }
        }
        if t >= t_end {
            y.copy_from_slice(&work.y);
            return Outcome { status: Status::Completed, t, stats };
        }
        if stats.steps + stats.rejected >= max_steps {
            y.copy_from_slice(&work.y);
            return Outcome { status: Status::Stopped(StopReason::TooManySteps { max_steps }), t, stats };
        }
        let last = t + 1.01 * h >= t_end;
        if last {
            h = t_end - t;
        }
        let min_step = 16.0 * f64::EPSILON * t.abs().max(t_end.abs() * 1e-3).max(f64::MIN_POSITIVE);
        if h < min_step {
            y.copy_from_slice(&work.y);
            return Outcome { status: Status::StepTooSmall { h }, t, stats };
        }
        let err = work.attempt(sys, t, h, atol, rtol);
        stats.rhs_evaluations += 11;
        if !err.is_finite() || work.y_new.iter().any(|v| !v.is_finite()) {
            stats.rejected += 1;
            rejected_last = true;
            h *= 0.2;
            if h < min_step {
                y.copy_from_slice(&work.y);
                let s = not_finite(&work.y_new).unwrap_or(Status::StepTooSmall { h });
                return Outcome { status: s, t, stats };
            }
            continue;
        }
        if !(err <= 1.0) {
            stats.rejected += 1;
            rejected_last = true;
            h *= (0.9 * err.powf(-1.0 / q)).clamp(1.0 / 3.0, 1.0);
            continue;
        }
        let t_new = if last { t_end } else { t + h };
        {
            let (k, k12) = work.k.split_at_mut(tab::N_STAGES * n);
            sys.rhs(t_new, &work.y_new, k12);
            // k_12 is the next step's k_0
            k[..n].copy_from_slice(k12);
        }
        stats.rhs_evaluations += 1;
        stats.steps += 1;
        std::mem::swap(&mut work.y, &mut work.y_new);
        t = t_new;
        if let Some(s) = not_finite(&work.k[..n]) {
            y.copy_from_slice(&work.y);
            return Outcome { status: s, t, stats };
        }
        let fac = if err == 0.0 { 6.0 } else { (0.9 * err.powf(-1.0 / q)).clamp(1.0 / 3.0, 6.0) };
        h *= if rejected_last { fac.min(1.0) } else { fac };
        rejected_last = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::{Control, Method, Options, Solver};

    /// A damped, forced, parametrically excited oscillator pair with an exponential: a
    /// non-autonomous, non-linear system of 5 states.
    struct Test;
    impl System for Test {
        fn dim(&self) -> usize {
            5
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -(1.0 + 0.3 * (2.0 * t).cos()) * y[0] - 0.05 * y[1] + 0.2 * y[2].sin();
            dy[2] = y[3];
            dy[3] = -9.0 * y[2] - 0.1 * y[3] * y[0] + (0.7 * t).sin();
            dy[4] = -0.3 * y[4] + y[0] * y[0];
        }
    }

    #[test]
    fn a_stop_probe_ends_an_integration_within_256_steps() {
        // hunts 27-28: one speed's shooting on a stiff rotor took minutes and did not ask the
        // control; the thread's stop probe (crate::control::with_probe) is asked every 256
        // attempted steps. A cancelled control installed as the probe stops the integration at
        // the first ask (at most 256 steps of 12 evaluations and the start's 2); the same
        // integration with the control not installed runs to its end (thousands of steps: an
        // oscillator of period 0.63 over 300 periods)
        struct Osc;
        impl System for Osc {
            fn dim(&self) -> usize {
                2
            }
            fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
                dy[0] = y[1];
                dy[1] = -100.0 * y[0];
            }
        }
        let (rtol, atol, t_end) = (1e-10, vec![1e-10; 2], 190.0);
        let control = crate::control::Control::new();
        control.cancel();
        let mut a = vec![1.0, 0.0];
        let stopped = crate::control::with_probe(&control, || integrate(&Osc, &mut Lean::new(2), 0.0, &mut a, t_end, rtol, &atol));
        assert!(matches!(stopped.status, Status::Stopped(crate::control::StopReason::Interrupted)), "{:?}", stopped.status);
        assert!(stopped.stats.rhs_evaluations <= 256 * 12 + 2 && stopped.t < t_end, "{:?} at t = {}", stopped.stats, stopped.t);
        let mut b = vec![1.0, 0.0];
        let done = integrate(&Osc, &mut Lean::new(2), 0.0, &mut b, t_end, rtol, &atol);
        assert!(done.status.is_completed() && done.stats.rhs_evaluations > 4 * 256 * 12, "{:?}", done.stats);
        // the probe is this thread's only while installed
        assert!(crate::control::probe().is_none());
    }

    #[test]
    fn a_step_cap_stops_after_that_many_attempts_and_a_loose_one_changes_nothing() {
        // integrate_capped (the shooting's trial flows, analysis::stationary): `max_steps`
        // attempted steps (accepted and rejected) and no more, the state at the last accepted
        // one; a cap above what the integration needs gives integrate's steps and bits
        let (rtol, atol) = (1e-10, vec![1e-10; 5]);
        let y0 = [0.3, -0.1, 0.5, 0.2, 0.1];
        let mut free = y0.to_vec();
        let done = integrate(&Test, &mut Lean::new(5), 0.0, &mut free, 20.0, rtol, &atol);
        let used = done.stats.steps + done.stats.rejected;
        assert!(done.status.is_completed() && used > 100, "{:?}", done.stats);
        let mut capped = y0.to_vec();
        let stopped = integrate_capped(&Test, &mut Lean::new(5), 0.0, &mut capped, 20.0, rtol, &atol, 50);
        assert_eq!(stopped.status, Status::Stopped(StopReason::TooManySteps { max_steps: 50 }));
        assert_eq!(stopped.stats.steps + stopped.stats.rejected, 50, "{:?}", stopped.stats);
        assert!(stopped.t > 0.0 && stopped.t < 20.0 && capped != free, "t = {}", stopped.t);
        let mut loose = y0.to_vec();
        let same = integrate_capped(&Test, &mut Lean::new(5), 0.0, &mut loose, 20.0, rtol, &atol, used);
        assert!(same.status.is_completed() && same.stats == done.stats && loose == free, "{:?}", same.stats);
    }

    #[test]
    fn the_same_steps_and_the_same_bits_as_the_solver() {
        // bit for bit: the same arithmetic in the same order (module docs), at tolerances from
        // loose (rejections happen) to tight
        for rtol in [1e-4, 1e-8, 1e-12] {
            let atol = vec![rtol * 0.5; 5];
            let y0 = [1.0, 0.0, 0.3, -0.2, 0.1];
            let mut a = y0.to_vec();
            let mut work = Lean::new(5);
            let out = integrate(&Test, &mut work, 0.0, &mut a, 17.3, rtol, &atol);
            assert!(out.status.is_completed());
            let mut b = y0.to_vec();
            let mut s = Solver::new(&Test, Options::new(rtol, rtol).method(Method::Dop853).atol_per_component(atol.clone())).unwrap();
            let ref_out = s.integrate(0.0, &mut b, 17.3, |_| Control::Continue);
            assert_eq!(a, b, "rtol {rtol}");
            assert_eq!((out.stats.steps, out.stats.rejected), (ref_out.stats.steps, ref_out.stats.rejected), "rtol {rtol}");
            assert!(out.stats.rejected > 0 || rtol < 1e-6, "rtol {rtol}: the loose run exercises rejections");
            // the buffers are reusable: a second run gives the same bits
            let mut c = y0.to_vec();
            integrate(&Test, &mut work, 0.0, &mut c, 17.3, rtol, &atol);
            assert_eq!(a, c);
        }
    }

    #[test]
    fn a_non_finite_state_is_reported() {
        let mut y = [1.0, f64::NAN, 0.0, 0.0, 0.0];
        let out = integrate(&Test, &mut Lean::new(5), 0.0, &mut y, 1.0, 1e-8, &[1e-8; 5]);
        assert!(matches!(out.status, Status::NotFinite { component: 1, .. }), "{:?}", out.status);
    }
}
