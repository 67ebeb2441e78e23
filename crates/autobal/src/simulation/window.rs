//! The last revolutions of a run, for its summary: records at a fixed grid of the rotor's
//! angle located on the integrator's dense output ([`super::Hooks::dense_step`]), and their
//! means over a revolution and the drift of those means from one revolution to the next.
//!
//! Every model's summary (the planar, spatial and linear-rotor runs) takes its averages here,
//! each through its own [`Recorder`] (where its rotor's angle is, what a record holds). The
//! means are the trapezoidal rule of a periodic integrand over its period: exact, to the
//! integration's accuracy, for a stationary motion periodic in the rotor's angle with no
//! harmonic of order [`POINTS`] or above, wherever in the revolution the run ends.

use std::collections::VecDeque;
use std::f64::consts::TAU;

/// Records per revolution: at `φ = 2π k / POINTS`, `k` whole. A stationary motion's harmonics
/// in `φ` fall off as powers of what makes it periodic rather than constant in the rotor's
/// axes (supports that differ by direction: `(k_y − k_x)/(k_x + k_y)` per order `2φ`, 0.14
/// for `k_x = 9e4`, `k_y = 1.2e5`; gravity over the unbalance's force): the 32nd, the first
/// the grid aliases onto the mean, is below 1e-13 of the motion there; a steady whirl has none.
pub const POINTS: usize = 32;

/// Revolutions before the run's end, at the speed at a step's end, from which on the window
/// records: two for the means and six to spare for a speed that falls (a run that covers fewer
/// than two revolutions in the time eight would take at its speed of the moment is no
/// stationary motion; its summary then takes the end state). Before that the dense output is
/// not asked for (DOP853's costs 3 right-hand sides a step).
pub const LEAD: f64 = 8.0;

/// How a summary's line says what its residuals are: `"mean over the last revolution"` where
/// they are (`averaged`, a summary's field of that name), else `"at the end: no revolution
/// recorded"` (the run turned less than one, or stopped early before its last revolutions:
/// the end state's values).
pub fn basis_words(averaged: bool) -> &'static str {
    if averaged {
        "mean over the last revolution"
    } else {
        "at the end: no revolution recorded"
    }
}

/// What a model records in a [`RevolutionWindow`].
pub trait Recorder {
    /// The rotor's angle `φ` (rad, continuous through the run: not reduced to one turn) and
    /// its rate `φ̇` in the state `y` at `t`.
    fn spin(&self, t: f64, y: &[f64]) -> (f64, f64);
    /// The record at `(t, y)` into `out` (the window's width): the values whose means the
    /// summary takes.
    fn record(&self, t: f64, y: &[f64], out: &mut [f64]);
}

/// The last two revolutions of a run sampled on its dense output at `φ = 2π k / POINTS` (see
/// the [module](self)): each record is the weight `1/|φ̇|` (the time per unit of angle there)
/// and the [`Recorder`]'s values; the mean by time over a revolution is the weighted mean of
/// its [`POINTS`] records. Recording starts [`LEAD`] revolutions (at the speed of the moment)
/// before `t_end`; older records are dropped, so the memory is that of two revolutions.
#[derive(Debug, Clone)]
pub struct RevolutionWindow {
    width: usize,
    t_end: f64,
    /// Whether the last step ended within [`LEAD`] revolutions of the end.
    on: bool,
    data: VecDeque<f64>,
    /// Each record's grid index `k` (`φ = 2π k / POINTS`): a revolution is [`POINTS`]
    /// consecutive ones, turning one way.
    index: VecDeque<i64>,
    /// The dense output's state at a grid angle.
    buf: Vec<f64>,
    /// A record's values.
    row: Vec<f64>,
}

impl RevolutionWindow {
    /// An empty window for records of `width` values, for a run that ends at `t_end`.
    pub fn new(width: usize, t_end: f64) -> Self {
        RevolutionWindow { width, t_end, on: false, data: VecDeque::new(), index: VecDeque::new(), buf: vec![], row: vec![0.0; width] }
    }

    fn stride(&self) -> usize {
        self.width + 1
    }

    /// Records held (at most `2 POINTS`).
    pub fn len(&self) -> usize {
        self.data.len() / self.stride()
    }

    /// Whether no record is held.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// The step from `(t0, y0)` to `(t1, y1)` with its dense output `interpolate` (as
    /// [`super::Hooks::dense_step`] gets them): where it ends within [`LEAD`] revolutions of
    /// `t_end` at its speed there, a record at each grid angle the step passes, in `(φ0, φ1]`
    /// turning forwards or `[φ1, φ0)` backwards (in the order passed; a grid angle within
    /// `1e-12 max(|φ1|, 2π)` beyond `φ1`, round-off of a run that ends on it, counts as passed,
    /// and the next step, which starts there, does not take it again), located by Newton's
    /// method on `φ(t) − φ_k` with the recorder's `φ̇` (exact at once at a constant speed, where
    /// `φ` is linear in `t`); the record is taken at the time of the last interpolated state.
    /// A step that passes more than `2 POINTS` grid angles locates only the last `2 POINTS`
    /// (the window keeps no more). A step that ends further back clears the window (a run that
    /// speeds up leaves the lead again, its records then too old to be the last revolutions).
    pub fn dense_step<R: Recorder + ?Sized>(&mut self, rec: &R, t0: f64, t1: f64, y0: &[f64], y1: &[f64], interpolate: &mut dyn FnMut(f64, &mut [f64])) {
        let (th1, w1) = rec.spin(t1, y1);
        let near = self.t_end - t1 <= LEAD * TAU / w1.abs();
        if !near {
            if self.on {
                self.data.clear();
                self.index.clear();
                self.on = false;
            }
            return;
        }
        self.on = true;
        let (th0, _) = rec.spin(t0, y0);
        if !(th0.is_finite() && th1.is_finite()) || th0 == th1 {
            return;
        }
        let d = TAU / POINTS as f64;
        // the slack at either end: round-off of the angle where a run ends on a grid angle
        let (slack0, slack1) = (1e-12 * th0.abs().max(TAU), 1e-12 * th1.abs().max(TAU));
        // the grid indices passed, first to last: beyond φ0 (strictly) to φ1 (and its slack)
        let (first, last, sense) =
            if th1 > th0 { ((th0 / d).floor() + 1.0, ((th1 + slack1) / d).floor(), 1.0) } else { ((th0 / d).ceil() - 1.0, ((th1 - slack1) / d).ceil(), -1.0) };
        let count = sense * (last - first) + 1.0;
        if !(1.0..1e15).contains(&count) {
            return;
        }
        // the first, where the last step took it within its slack (it ended there): skipped
        let recorded = |k: f64| self.index.back().is_some_and(|&b| b as f64 == k) && (k * d - th0).abs() <= slack0;
        let mut skip = usize::from(recorded(first));
        // only the last 2 POINTS are kept
        skip = skip.max((count as usize).saturating_sub(2 * POINTS));
        let mut buf = std::mem::take(&mut self.buf);
        buf.resize(y0.len(), 0.0);
        let mut row = std::mem::take(&mut self.row);
        for i in skip..count as usize {
            let k = first + sense * i as f64;
            let target = k * d;
            let mut t = (t0 + (target - th0) / (th1 - th0) * (t1 - t0)).clamp(t0.min(t1), t0.max(t1));
            let mut rate = 0.0;
            for iteration in 0..12 {
                interpolate(t, &mut buf);
                let (th, w) = rec.spin(t, &buf);
                rate = w;
                let e = th - target;
                // (the record at the t of `buf`: no update after the last interpolation)
                if e.abs() <= 1e-13 * target.abs().max(TAU) || w == 0.0 || iteration == 11 {
                    break;
                }
                t = (t - e / w).clamp(t0.min(t1), t0.max(t1));
            }
            let weight = 1.0 / rate.abs();
            if !weight.is_finite() {
                continue;
            }
            rec.record(t, &buf, &mut row);
            self.data.push_back(weight);
            self.data.extend(&row);
            self.index.push_back(k as i64);
        }
        self.buf = buf;
        self.row = row;
        while self.len() > 2 * POINTS {
            self.data.drain(..self.stride());
            self.index.pop_front();
        }
    }

    /// The means by time over revolution `back` counted from the last record (0 the last, 1
    /// the one before: its [`POINTS`] records) of each of the record's values; `None` where
    /// the records do not reach back that far.
    pub fn mean(&self, back: usize) -> Option<Vec<f64>> {
        let range = self.revolution(back)?;
        let s = self.stride();
        let mut dur = 0.0;
        let mut sums = vec![0.0; self.width];
        for i in range {
            let w = self.data[i * s];
            dur += w;
            for (k, sum) in sums.iter_mut().enumerate() {
                *sum += w * self.data[i * s + 1 + k];
            }
        }
        (dur > 0.0).then(|| sums.into_iter().map(|v| v / dur).collect())
    }

    /// The mean by time over revolution `back` (as [`RevolutionWindow::mean`]) of `f` of each
    /// record's values (e.g. a squared distance from a mean found first: a spread without the
    /// cancellation of a mean of squares less a squared mean).
    pub fn mean_of(&self, back: usize, f: impl Fn(&[f64]) -> f64) -> Option<f64> {
        let range = self.revolution(back)?;
        let s = self.stride();
        let (mut dur, mut sum) = (0.0, 0.0);
        let mut row = Vec::with_capacity(self.width);
        for i in range {
            let w = self.data[i * s];
            row.clear();
            row.extend((0..self.width).map(|k| self.data[i * s + 1 + k]));
            dur += w;
            sum += w * f(&row);
        }
        (dur > 0.0).then_some(sum / dur)
    }

    /// The largest change of the means of the values `columns` from the revolution before the
    /// last to the last, `max_k |m̄_k(last) − m̄_k(before)|` (the balls' drift: 0 for a
    /// stationary motion periodic in the angle); `None` where the records do not cover two
    /// revolutions.
    pub fn drift(&self, columns: std::ops::Range<usize>) -> Option<f64> {
        let (a, b) = (self.mean(0)?, self.mean(1)?);
        Some(columns.map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max))
    }

    /// The records of revolution `back` from the end: `None` unless they are [`POINTS`]
    /// consecutive grid angles turning one way (a rotor that turned back within them did not
    /// turn a revolution).
    fn revolution(&self, back: usize) -> Option<std::ops::Range<usize>> {
        let n = self.len();
        let range = (n >= (back + 1) * POINTS).then(|| n - (back + 1) * POINTS..n - back * POINTS)?;
        let step = self.index[range.start + 1] - self.index[range.start];
        let one_way = step.abs() == 1 && (range.start + 1..range.end).all(|i| self.index[i] - self.index[i - 1] == step);
        one_way.then_some(range)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A motion given in closed form: `φ(t)` and `φ̇(t)` as the state's first two entries, a
    /// record of `cos φ`, `cos² φ`, `sin φ` and the state's third entry.
    struct Closed;

    impl Recorder for Closed {
        fn spin(&self, _t: f64, y: &[f64]) -> (f64, f64) {
            (y[0], y[1])
        }
        fn record(&self, _t: f64, y: &[f64], out: &mut [f64]) {
            out[0] = y[0].cos();
            out[1] = y[0].cos().powi(2);
            out[2] = y[0].sin();
            out[3] = y[2];
        }
    }

    /// Feed `window` steps of `h` from `t0` to `t_end` of the motion `state(t)`, its exact
    /// values as the dense output.
    fn feed(window: &mut RevolutionWindow, state: impl Fn(f64) -> [f64; 3], t0: f64, t_end: f64, h: f64) {
        let mut t = t0;
        while t < t_end {
            let t1 = (t + h).min(t_end);
            let (y0, y1) = (state(t), state(t1));
            window.dense_step(&Closed, t, t1, &y0, &y1, &mut |s, out| out.copy_from_slice(&state(s)));
            t = t1;
        }
    }

    #[test]
    fn means_at_a_constant_speed_are_exact_wherever_the_run_ends() {
        // φ = ω t: over a revolution ⟨cos φ⟩ = ⟨sin φ⟩ = 0 and ⟨cos² φ⟩ = 1/2 exactly (the
        // grid's trapezoidal rule integrates harmonics below 32 exactly), for any end of the
        // run and any step (0.37 rad a step, incommensurate with the grid's 0.196); 1e-14:
        // the round-off of 32 terms of size 1 (at a constant speed Newton's first guess, the
        // chord of φ, is exact to round-off: the 1e-13 of its stopping test is not used up)
        let w = 3.0;
        for k in 0..10 {
            let t_end = 20.0 + k as f64 * TAU / w / 10.0;
            let mut win = RevolutionWindow::new(4, t_end);
            feed(&mut win, |t| [w * t, w, 0.5], 0.0, t_end, 0.37 / w);
            assert_eq!(win.len(), 2 * POINTS);
            let m = win.mean(0).unwrap();
            assert!(m[0].abs() < 1e-14 && (m[1] - 0.5).abs() < 1e-14 && m[2].abs() < 1e-14 && (m[3] - 0.5).abs() < 1e-15, "{m:?}");
            assert!(win.drift(0..4).unwrap() < 1e-14);
            let spread = win.mean_of(0, |r| (r[0] - m[0]).powi(2)).unwrap();
            assert!((spread - 0.5).abs() < 1e-14, "{spread}");
        }
    }

    #[test]
    fn the_mean_is_by_time_where_the_speed_swings() {
        // φ̇ = ω (1 + ε cos φ): the time per angle is 1/φ̇, so the mean of cos φ by time is
        // ∮ cos φ dφ/(1 + ε cos φ) / ∮ dφ/(1 + ε cos φ) = (s − 1)/ε, s = sqrt(1 − ε²) (the
        // mean by angle is 0). The motion in closed form: tan(φ/2) = sqrt((1+ε)/(1−ε))
        // tan(ν/2), ν = s ω t.
        let (w, e) = (2.0f64, 0.3f64);
        let s = (1.0 - e * e).sqrt();
        let phi = move |t: f64| {
            // unwrapped: whole turns of ν plus the principal branch of the half-angle
            let nu = w * s * t;
            let turns = (nu / TAU).round();
            let r = nu - turns * TAU; // in [−π, π]
            turns * TAU + 2.0 * (((1.0 + e) / (1.0 - e)).sqrt() * (r / 2.0).tan()).atan()
        };
        let state = move |t: f64| {
            let p = phi(t);
            [p, w * (1.0 + e * p.cos()), 0.0]
        };
        let t_end = 30.0;
        let mut win = RevolutionWindow::new(4, t_end);
        feed(&mut win, state, 0.0, t_end, 0.05);
        // ∮ dφ/(1 + ε cos φ) = 2π/s, ∮ cos φ dφ/(1 + ε cos φ) = (2π/ε)(1 − 1/s)
        let want = (s - 1.0) / e;
        let m = win.mean(0).unwrap();
        // the grid's trapezoidal rule on 1/(1 + ε cos φ): its error is the 32nd Fourier
        // coefficient, ~ ((1 − s)/ε)^32 = 0.15^32 ~ 1e-26; 1e-12: Newton stops within
        // 1e-13 max(|φ|, 2π) ≈ 1e-11 rad of the grid angle here (φ ≈ 55), moving the mean by
        // about that times its rate, |d cos φ/dφ| ≤ 1, over 32 records of alternating sign
        // (in practice Newton converges quadratically far below its stopping test)
        assert!((m[0] - want).abs() < 1e-12, "{} vs {want}", m[0]);
        // not the mean by angle (0)
        assert!(want.abs() > 0.1);
    }

    #[test]
    fn records_start_within_the_lead_and_restart_when_the_run_speeds_up() {
        // at ω = 1 the lead is 8 revolutions, 50 s: a run of 1000 s records only the last
        // two revolutions' 64 points
        let mut win = RevolutionWindow::new(4, 1000.0);
        let mut asked = 0usize;
        let state = |t: f64| [t, 1.0, 0.0];
        let mut t = 0.0;
        while t < 1000.0 {
            let t1 = (t + 0.5f64).min(1000.0);
            win.dense_step(&Closed, t, t1, &state(t), &state(t1), &mut |s, out| {
                asked += 1;
                out.copy_from_slice(&state(s))
            });
            t = t1;
        }
        assert_eq!(win.len(), 2 * POINTS);
        // 8 revolutions of 32 records, each located in one or two evaluations (Newton
        // converges at once at a constant speed): nothing asked before the lead
        assert!(asked <= 2 * 8 * POINTS + 2 * POINTS, "{asked}");
        // a step outside the lead (the speed risen to 1000: 8 revolutions take 0.05 s, less
        // than the 989 s left) empties it, without asking the dense output
        win.dense_step(&Closed, 10.0, 11.0, &[10.0, 1e3, 0.0], &[11.0, 1e3, 0.0], &mut |_, _| unreachable!());
        assert!(win.is_empty() && win.mean(0).is_none() && win.drift(0..1).is_none());
    }

    #[test]
    fn a_run_of_exactly_one_or_two_revolutions_keeps_its_last_grid_angle() {
        // φ = ω t up to t_end = n 2π/ω, n = 1, 2: φ(t_end) lands on the grid angle 2π n up to
        // round-off (either side); the window holds 32 n records, each grid angle once, and
        // the means of a whole revolution (without the slack of 1e-12 it kept 31 or 63)
        for w in [1400.0, 3.0, 146.61, 0.7] {
            for n in [1usize, 2] {
                let t_end = n as f64 * TAU / w;
                for h in [0.37 / w, TAU / w / 32.0, TAU / w / 7.0] {
                    let mut win = RevolutionWindow::new(4, t_end);
                    feed(&mut win, |t| [w * t, w, 0.0], 0.0, t_end, h);
                    assert_eq!(win.len(), n * POINTS, "ω {w}, {n} revolutions, step {h}");
                    let k: Vec<i64> = win.index.iter().copied().collect();
                    assert_eq!(k, (1..=(n * POINTS) as i64).collect::<Vec<_>>(), "ω {w}, step {h}");
                    let m = win.mean(0).unwrap();
                    assert!(m[0].abs() < 1e-13 && (m[1] - 0.5).abs() < 1e-13, "{m:?}");
                    assert_eq!(win.drift(0..4).is_some(), n == 2);
                }
            }
        }
    }

    #[test]
    fn a_rotor_turning_backwards_gives_the_same_means() {
        // φ = −3 t + 0.1: the grid angles passed backwards, each once, in the order passed;
        // the means those of any whole revolution (⟨cos φ⟩ = 0, ⟨cos² φ⟩ = 1/2) to the
        // round-off of 32 terms, the weights 1/|φ̇| positive
        let w = -3.0;
        let t_end = 20.0;
        let mut win = RevolutionWindow::new(4, t_end);
        feed(&mut win, |t| [w * t + 0.1, w, 0.5], 0.0, t_end, 0.37 / 3.0);
        assert_eq!(win.len(), 2 * POINTS);
        assert!(win.index.iter().zip(win.index.iter().skip(1)).all(|(a, b)| b - a == -1), "{:?}", win.index);
        let m = win.mean(0).unwrap();
        assert!(m[0].abs() < 1e-14 && (m[1] - 0.5).abs() < 1e-14 && m[2].abs() < 1e-14 && (m[3] - 0.5).abs() < 1e-15, "{m:?}");
        assert!(win.drift(0..4).unwrap() < 1e-14);
    }

    #[test]
    fn a_rotor_that_turns_back_turned_no_revolution() {
        // φ = 2 sin 2t swings through ±2 rad (10 grid angles either side, 21 in a swing: less
        // than the 32 of a revolution) and back: 64 records are soon held, none of them a
        // revolution (the grid angles go back and forth), so no means and no drift
        let t_end = 30.0;
        let mut win = RevolutionWindow::new(4, t_end);
        // (|φ̇| ≤ 4: the lead, 8 revolutions at the speed at a step's end, at least 12.6 s,
        // holds the whole 6 s fed: two periods, some 80 grid angles passed)
        feed(&mut win, |t| [2.0 * (2.0 * t).sin(), 4.0 * (2.0 * t).cos(), 0.0], t_end - 6.0, t_end, 0.01);
        assert_eq!(win.len(), 2 * POINTS);
        assert!(win.mean(0).is_none() && win.mean(1).is_none() && win.drift(0..4).is_none());
    }

    /// A recorder whose `φ̇` is twice the motion's (Newton on it converges only linearly: the
    /// error halves each iteration and does not meet the test in 12), recording the time it is
    /// given and the time the state was interpolated at (the state's third entry).
    struct Slow;

    impl Recorder for Slow {
        fn spin(&self, _t: f64, y: &[f64]) -> (f64, f64) {
            (y[0], 2.0 * y[1])
        }
        fn record(&self, t: f64, y: &[f64], out: &mut [f64]) {
            out[0] = t;
            out[1] = y[2];
        }
    }

    #[test]
    fn a_record_is_taken_at_the_time_of_its_state() {
        // φ = t + 0.3 sin t, steps of 0.5 (a grid angle every 0.2 s or so): the chord, Newton's
        // first guess, is off by up to ~1e-2 and the error halves each iteration, to ~1e-6
        // after 12, not converged; the record's t is the one its state was interpolated at
        let state = |t: f64| [t + 0.3 * t.sin(), 1.0 + 0.3 * t.cos(), t];
        let mut win = RevolutionWindow::new(2, 20.0);
        let mut t = 0.0;
        while t < 20.0 {
            let t1 = (t + 0.5f64).min(20.0);
            win.dense_step(&Slow, t, t1, &state(t), &state(t1), &mut |s, out| out.copy_from_slice(&state(s)));
            t = t1;
        }
        assert_eq!(win.len(), 2 * POINTS);
        let s = win.stride();
        for i in 0..win.len() {
            let (tr, ts) = (win.data[i * s + 1], win.data[i * s + 2]);
            assert_eq!(tr, ts, "record {i}");
        }
    }
}
