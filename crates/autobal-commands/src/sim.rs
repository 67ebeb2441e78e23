//! `autobal simulate` of paper 004's planar rotor (the nonlinear passage through resonance: the
//! run, its rows, its summary and figures; the command itself: [`crate::simulate`]), also used by
//! `autobal sweep` and the report.

use crate::config::PlanarConfig;
use crate::plot::{Plot, Series, PALETTE};
use anyhow::{bail, Result};
use autobal::control::Control;
use autobal::planar::stationary::{aligned_whirls_of, capacity_ratio, locked_amplitude, semi_balanced_exists};
use autobal::planar::{simulate_with, Sample, Summary};
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Samples kept for plotting: per bucket of consecutive samples, the ones with the smallest and
/// largest amplitude (so peaks survive decimation), in their order; a bucket of one or two
/// samples keeps them all. The bucket's extremes are tracked as the samples come (the first
/// smallest and the last largest, as `Iterator::min_by`/`max_by` pick them), copied into two
/// reused samples. The kept samples are stored flat, one row of floats each (`t, ω, θ, X, Y,
/// amplitude, ψ_1 … ψ_n`, [`Envelope::rows`]), in one buffer sized from the expected count once:
/// no allocation per sample (a `Sample` with its own heap `Vec` of ball angles each took 120
/// bytes and a `malloc` a sample for a passage's two balls, 64 bytes flat), no growth while the
/// run goes (a run of up to `target` samples keeps every one of them).
///
/// [`Envelope::for_figures`] keeps only what the figures draw (`t, ω, amplitude, ψ_1 … ψ_n`,
/// [`Envelope::rows`] with [`Envelope::amplitude_at`] and [`Envelope::psi_at`]): `simulate`'s
/// rows, whose every column is in the CSV; 5 floats a two-ball sample instead of 8, and as many
/// fewer pages first touched (~30 of the passage's page faults).
pub struct Envelope {
    bucket: usize,
    /// Samples of the current bucket so far.
    count: usize,
    /// The current bucket's first smallest and last largest sample, with their positions in it.
    lo: (usize, Sample),
    hi: (usize, Sample),
    /// Samples to reserve room for at the first one (when its width is known).
    reserve: usize,
    /// Floats a kept sample: `ROW_PSI` (or `FIG_PSI`) + its ball count (0 before the first
    /// sample).
    width: usize,
    /// Whether the rows are whole samples (`ROW_*`) or what the figures draw (`FIG_*`).
    full: bool,
    /// The kept samples' rows, one after the other.
    data: Vec<f64>,
}

/// A kept sample's row ([`Envelope::rows`]): time (s).
pub const ROW_T: usize = 0;
/// … speed `ω` (rad/s).
pub const ROW_OMEGA: usize = 1;
/// … whirl radius of C (m).
pub const ROW_AMPLITUDE: usize = 5;
/// … the first ball angle (rad); the others follow.
pub const ROW_PSI: usize = 6;
/// A figures' row ([`Envelope::for_figures`]): time, speed as in a whole row, then the whirl
/// radius of C (m) …
const FIG_AMPLITUDE: usize = 2;
/// … and the ball angles (rad).
const FIG_PSI: usize = 3;

/// `dst` becomes a copy of `src`, reusing `dst`'s ball angles' allocation (every field named:
/// a field added to `Sample` fails to compile here rather than be left out).
fn copy_sample(dst: &mut Sample, src: &Sample) {
    let Sample { t, omega, theta, x, y, amplitude, psi } = src;
    (dst.t, dst.omega, dst.theta, dst.x, dst.y, dst.amplitude) = (*t, *omega, *theta, *x, *y, *amplitude);
    dst.psi.clone_from(psi);
}

impl Envelope {
    /// An envelope for a run of about `expected` samples, keeping about `target` of them at most
    /// (two per bucket of `ceil(expected / target)` samples).
    pub fn new(expected: usize, target: usize) -> Self {
        let bucket = expected.div_ceil(target.max(1)).max(1);
        // every sample of a run of one-sample buckets (and the end sample off the grid), else two
        // a bucket; at most the target's worth reserved ahead (a run longer than expected grows)
        let reserve = if bucket == 1 { expected + 2 } else { 2 * expected.div_ceil(bucket) + 2 };
        let blank = || (0, Sample { t: 0.0, omega: 0.0, theta: 0.0, x: 0.0, y: 0.0, amplitude: 0.0, psi: vec![] });
        Envelope { bucket, count: 0, lo: blank(), hi: blank(), reserve: reserve.min(2 * target.max(1) + 2), width: 0, full: true, data: vec![] }
    }

    /// [`Envelope::new`] keeping, of each kept sample, only what the figures draw: `t, ω,
    /// amplitude, ψ_1 … ψ_n` ([`Envelope::kept`] is not for it: θ, X and Y are not kept).
    pub fn for_figures(expected: usize, target: usize) -> Self {
        Envelope { full: false, ..Self::new(expected, target) }
    }

    /// Where a kept row has the whirl radius of C ([`ROW_AMPLITUDE`] for whole samples).
    pub fn amplitude_at(&self) -> usize {
        if self.full {
            ROW_AMPLITUDE
        } else {
            FIG_AMPLITUDE
        }
    }

    /// Where a kept row has its first ball angle ([`ROW_PSI`] for whole samples).
    pub fn psi_at(&self) -> usize {
        if self.full {
            ROW_PSI
        } else {
            FIG_PSI
        }
    }

    /// Keep `s`: its row appended to `data` (`width` set, and room for `reserve` rows made, at
    /// the first).
    fn keep(data: &mut Vec<f64>, width: &mut usize, reserve: usize, full: bool, s: &Sample) {
        let head = if full { ROW_PSI } else { FIG_PSI };
        if *width == 0 {
            *width = head + s.psi.len();
            data.reserve_exact(reserve * *width);
        }
        debug_assert_eq!(*width, head + s.psi.len(), "one ball count a run");
        let Sample { t, omega, theta, x, y, amplitude, psi } = s;
        if full {
            data.extend_from_slice(&[*t, *omega, *theta, *x, *y, *amplitude]);
        } else {
            data.extend_from_slice(&[*t, *omega, *amplitude]);
        }
        data.extend_from_slice(psi);
    }

    pub fn push(&mut self, s: &Sample) {
        if self.bucket == 1 {
            Self::keep(&mut self.data, &mut self.width, self.reserve, self.full, s);
            return;
        }
        let k = self.count;
        if k == 0 || s.amplitude.total_cmp(&self.lo.1.amplitude).is_lt() {
            self.lo.0 = k;
            copy_sample(&mut self.lo.1, s);
        }
        if k == 0 || !s.amplitude.total_cmp(&self.hi.1.amplitude).is_lt() {
            self.hi.0 = k;
            copy_sample(&mut self.hi.1, s);
        }
        self.count += 1;
        if self.count >= self.bucket {
            self.flush();
        }
    }

    /// Keep the current bucket's extremes (in their order; one sample where they are the same).
    pub fn flush(&mut self) {
        if self.count == 0 {
            return;
        }
        let (a, b) = if self.lo.0 <= self.hi.0 { (&self.lo, &self.hi) } else { (&self.hi, &self.lo) };
        Self::keep(&mut self.data, &mut self.width, self.reserve, self.full, &a.1);
        if b.0 != a.0 {
            Self::keep(&mut self.data, &mut self.width, self.reserve, self.full, &b.1);
        }
        self.count = 0;
    }

    /// The kept samples' rows in their order: `t, ω, θ, X, Y, amplitude, ψ_1 … ψ_n` (the
    /// `ROW_*` indices), or `t, ω, amplitude, ψ_1 … ψ_n` for [`Envelope::for_figures`]
    /// ([`Envelope::amplitude_at`], [`Envelope::psi_at`]).
    pub fn rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.data.chunks_exact(self.width.max(1))
    }

    /// How many samples are kept.
    pub fn len(&self) -> usize {
        self.data.len() / self.width.max(1)
    }

    /// Whether no sample is kept.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// The kept samples as `Sample`s (each with its own ball angles' `Vec`: for the report's
    /// figures, not the run's hot path). Only of an envelope of whole samples
    /// ([`Envelope::new`]).
    pub fn kept(&self) -> Vec<Sample> {
        debug_assert!(self.full, "an envelope for figures keeps no θ, X, Y");
        self.rows().map(|r| Sample { t: r[0], omega: r[1], theta: r[2], x: r[3], y: r[4], amplitude: r[5], psi: r[ROW_PSI..].to_vec() }).collect()
    }
}

/// The columns of a simulation's samples: `t, omega, x, y, amplitude, psi_1 … psi_n`.
pub fn sample_columns(n: usize) -> Vec<String> {
    let mut c: Vec<String> = ["t", "omega", "x", "y", "amplitude"].iter().map(|s| s.to_string()).collect();
    c.extend((1..=n).map(|j| format!("psi_{j}")));
    c
}

/// Floats handed to the writer thread at a time (whole rows of `5 + n` floats; 64 KiB: 1 170
/// rows of a two-ball passage). Each batch wakes the writer (a futex wake, two context switches
/// on a loaded machine): batches of 256 rows made 19 hand-overs of paper 004's 4 801 samples
/// and 45-70 context switches a run (`perf stat`, load ~5); this size makes 5, and 13-36. The batches' buffers go back to the run's
/// thread to be filled again (no allocation, and no fresh pages, per batch).
const BATCH_FLOATS: usize = 1 << 13;

/// The rows of a batch for rows of `width` floats ([`BATCH_FLOATS`], at least one row).
fn batch_rows(width: usize) -> usize {
    (BATCH_FLOATS / width.max(1)).max(1)
}

/// CSV text handed to the writer at a time (bytes, whole rows): the staged file's buffer is as
/// large, so each chunk goes to the file without a second copy ([`std::io::BufWriter`] passes a
/// write of its capacity or more straight through).
pub const CSV_CHUNK: usize = 1 << 16;

/// Room for one CSV value and its separator in the text buffer ([`crate::num::Csv::write_into`]'s
/// window of 40 bytes, of which at most 24 are written).
const VALUE_ROOM: usize = 41;

/// Where a run's rows go, one row (the values of the run's columns) at a time: CSV lines (the
/// floats as their shortest round-trip text, [`crate::num::Csv`], written in place into one
/// reused buffer and handed to the writer in chunks of [`CSV_CHUNK`] bytes, so the file grows as
/// the run goes), Parquet rows, and columns kept in memory (Python's arrays), each where given.
/// [`RowSink::finish`] writes the last chunk and flushes.
pub struct RowSink<'a, W: Write + ?Sized> {
    csv: Option<&'a mut W>,
    parquet: Option<&'a mut crate::parquet::Table>,
    columns: Option<&'a mut Vec<Vec<f64>>>,
    /// The CSV text not yet written: `text[..used]` (whole lines); the rest is room for a row.
    text: Vec<u8>,
    used: usize,
}

impl<'a, W: Write + ?Sized> RowSink<'a, W> {
    /// A sink into any of a CSV writer, a Parquet table and columns (one `Vec` per column,
    /// sized by the caller).
    pub fn new(csv: Option<&'a mut W>, parquet: Option<&'a mut crate::parquet::Table>, columns: Option<&'a mut Vec<Vec<f64>>>) -> Self {
        RowSink { csv, parquet, columns, text: vec![], used: 0 }
    }

    /// Room for `bytes` more after the text in use (the buffer grows to a chunk plus that, and
    /// at least 4 KiB more: the header's first call leaves room for the rows of up to 99
    /// columns, so the buffer is not reallocated, and copied, as the first chunk fills).
    fn room(&mut self, bytes: usize) {
        if self.used + bytes > self.text.len() {
            self.text.resize(CSV_CHUNK.max(self.used) + bytes.max(4096), 0);
        }
    }

    /// Hand the text in use to the writer once it fills a chunk.
    fn spill(&mut self, at_least: usize) -> std::io::Result<()> {
        if let Some(csv) = self.csv.as_deref_mut() {
            if self.used >= at_least && self.used > 0 {
                csv.write_all(&self.text[..self.used])?;
                self.used = 0;
            }
        }
        Ok(())
    }

    /// The CSV's header line (the column names joined by commas).
    pub fn header(&mut self, names: &[String]) -> Result<()> {
        if self.csv.is_some() {
            let line = names.join(",");
            self.room(line.len() + 1);
            self.text[self.used..self.used + line.len()].copy_from_slice(line.as_bytes());
            self.text[self.used + line.len()] = b'\n';
            self.used += line.len() + 1;
            self.spill(CSV_CHUNK)?;
        }
        Ok(())
    }

    /// One row.
    pub fn push(&mut self, row: &[f64]) -> Result<()> {
        if self.csv.is_some() {
            self.room(row.len() * VALUE_ROOM + 1);
            let mut k = self.used;
            for (i, v) in row.iter().enumerate() {
                if i > 0 {
                    self.text[k] = b',';
                    k += 1;
                }
                let window: &mut [u8; 40] = (&mut self.text[k..k + 40]).try_into().expect("room for a value");
                k += crate::num::Csv(*v).write_into(window);
            }
            self.text[k] = b'\n';
            self.used = k + 1;
            self.spill(CSV_CHUNK)?;
        }
        if let Some(t) = self.parquet.as_deref_mut() {
            t.push(row)?;
        }
        if let Some(c) = self.columns.as_deref_mut() {
            for (c, v) in c.iter_mut().zip(row) {
                c.push(*v);
            }
        }
        Ok(())
    }

    /// Write the CSV's last chunk and flush it.
    pub fn finish(&mut self) -> Result<()> {
        self.spill(0)?;
        if let Some(csv) = self.csv.as_deref_mut() {
            csv.flush()?;
        }
        Ok(())
    }
}

/// Run one simulation, writing every sample to `csv` (in whole chunks of [`CSV_CHUNK`] bytes, the last by the sink's `finish`) and to `parquet` if
/// given, and keeping an envelope for the plots ([`run_rows`] into a [`RowSink`]; `progress`:
/// a bar on standard error when it is a terminal). Returns the summary, the envelope and the
/// wall time.
pub fn run_to_csv(
    cfg: &PlanarConfig,
    csv: &mut (dyn Write + Send),
    parquet: Option<&mut crate::parquet::Table>,
    progress: bool,
    control: &Control,
) -> Result<(Summary, Envelope, f64)> {
    let (shown, bar) = if progress { crate::term::progress_bar(control) } else { (control.clone(), None) };
    let mut sink = RowSink::new(Some(csv), parquet, None);
    sink.header(&sample_columns(cfg.rotor.n))?;
    let out = run_rows(cfg, &mut |r| sink.push(r), &shown);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let out = out?;
    sink.finish().map_err(|e| anyhow::anyhow!("--out: cannot write: {e:#}"))?;
    Ok(out)
}

/// Run one simulation, handing every sample's row (`t, omega, x, y, amplitude, psi_1 … psi_n`,
/// [`sample_columns`]) to `rows`, and keeping an envelope for the plots. Returns the summary,
/// the envelope and the wall time. Progress (per mille of `t_end`) goes to `control`'s observer.
///
/// `rows` runs on a second thread while the integration goes on (the samples travel in batches
/// of `BATCH_FLOATS` (8 192) floats, their buffers sent back to be reused): formatting and
/// writing the CSV costs the run's thread nothing but the copy of the floats. When the run
/// stops (Ctrl-C, a budget) every row sampled so far is still handed over before this returns;
/// an error of `rows` stops the run (the next batch finds the writer gone) and is returned as
/// `--out: cannot write: ...`.
pub fn run_rows(cfg: &PlanarConfig, rows: &mut (dyn FnMut(&[f64]) -> Result<()> + Send), control: &Control) -> Result<(Summary, Envelope, f64)> {
    let width = 5 + cfg.rotor.n;
    let expected = (cfg.settings.t_end / cfg.settings.dt) as usize + 1;
    let mut env = Envelope::for_figures(expected, 6000);
    let mut count = 0u64;
    let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<f64>>(16);
    // the emptied batches, back to the run's thread (a send that finds the channel full or the
    // run's end drops the buffer)
    let (back_tx, back_rx) = std::sync::mpsc::sync_channel::<Vec<f64>>(4);
    let cap = batch_rows(width) * width;
    let (summary, wall, written) = std::thread::scope(|scope| {
        let writer = scope.spawn(move || -> Result<()> {
            for mut batch in rx {
                for row in batch.chunks_exact(width) {
                    rows(row)?;
                }
                batch.clear();
                let _ = back_tx.try_send(batch);
            }
            Ok(())
        });
        let mut batch: Vec<f64> = Vec::with_capacity(cap);
        let mut writer_gone = false;
        let t0 = std::time::Instant::now();
        let summary = simulate_with(&cfg.rotor, &cfg.drive, &cfg.settings, control, |s| {
            batch.extend_from_slice(&[s.t, s.omega, s.x, s.y, s.amplitude]);
            batch.extend_from_slice(&s.psi);
            if batch.len() >= cap {
                let next = back_rx.try_recv().unwrap_or_else(|_| Vec::with_capacity(cap));
                let full = std::mem::replace(&mut batch, next);
                if tx.send(full).is_err() {
                    // the writer stopped on an error: it is reported below
                    writer_gone = true;
                    return false;
                }
            }
            env.push(s);
            count += 1;
            if count.is_multiple_of(1000) {
                control.report((1000.0 * s.t / cfg.settings.t_end) as u64, 1000);
            }
            true
        });
        let wall = t0.elapsed().as_secs_f64();
        // the rows of a run that stopped early are kept: send what is left, then wait
        if !writer_gone && !batch.is_empty() {
            let _ = tx.send(batch);
        }
        drop(tx);
        let written = writer.join().unwrap_or_else(|_| Err(anyhow::anyhow!("the CSV writer panicked")));
        (summary, wall, written)
    });
    if let Err(e) = written {
        bail!("--out: cannot write: {e:#}");
    }
    let summary = summary?;
    env.flush();
    Ok((summary, env, wall))
}

pub fn summary_json(cfg: &PlanarConfig, s: &Summary, wall: f64) -> Value {
    let p = autobal::planar::problem::PlanarProblem { rotor: cfg.rotor.clone(), drive: cfg.drive.clone(), settings: cfg.settings.clone() };
    autobal::reports::simulation(&p, s, wall)
}

pub fn summary_table(cfg: &PlanarConfig, s: &Summary, wall: f64) -> String {
    let mut o = String::new();
    use std::fmt::Write as _;
    let _ = writeln!(o, "config: {}", cfg.source);
    let _ = writeln!(
        o,
        "rotor: m0 = {:.4} kg, {}, capacity ratio α∞ = {:.3} ({})",
        cfg.rotor.total_mass(),
        if cfg.rotor.k_y.is_some() {
            let (wx, wy) = cfg.rotor.natural_frequencies_xy();
            format!("sqrt(k_x/m0) = {wx:.2} rad/s, sqrt(k_y/m0) = {wy:.2} rad/s")
        } else {
            format!("sqrt(k/m0) = {:.2} rad/s", cfg.rotor.natural_frequency())
        },
        capacity_ratio(&cfg.rotor),
        if capacity_ratio(&cfg.rotor) > 1.0 { "the balls can balance at high speed" } else { "too little ball mass to balance" }
    );
    let _ = writeln!(o, "peak whirl radius of C: {:.4} mm at ω = {:.2} rad/s (t = {:.3} s)", 1e3 * s.peak_amplitude, s.omega_at_peak, s.t_at_peak);
    let _ = writeln!(o, "final: radius {:.4} mm at ω = {:.2} rad/s; {}", 1e3 * s.final_amplitude, s.final_omega, outcome_words(&cfg.rotor, s));
    let _ = writeln!(
        o,
        "integration ({}): {} steps ({} implicit, {} {}, {} rejected), {} right-hand sides, {:.3} s",
        cfg.settings.method,
        s.steps,
        s.implicit_steps,
        s.switches,
        if s.switches == 1 { "switch" } else { "switches" },
        s.rejected_steps,
        s.rhs_evaluations,
        wall
    );
    if cfg.rotor.balls.is_active() {
        let _ = writeln!(o, "real balls: {} contacts, {} stick-slip transitions", s.contacts, s.stick_slip_transitions);
    }
    if let Some(st) = &s.stopped {
        let _ = writeln!(o, "stopped early: {st}");
    }
    for w in &s.warnings {
        let _ = writeln!(o, "warning: {w}");
    }
    o
}

/// The run's outcome in words with its residual (mean over the last revolution, or the end
/// state's where none was recorded, [`autobal::simulation::window::basis_words`]): the spatial
/// run's words (`balanced`, `partially balanced`, `not balanced`, `not settled`), `balanced`
/// with an eccentric race said as `stability` says it, semi-balanced; the residual a fraction
/// of the unbalance for a centred race, of the race centre's offset without the balls for an
/// eccentric one ([`autobal::planar::Summary::residual_unbalance`]). A run that ends at rest
/// ([`autobal::planar::at_rest`]) has nothing to balance: not balanced, with the race centre's
/// distance from the axis instead of a residual "of the unbalance".
pub fn outcome_words(p: &autobal::planar::PlanarRotor, s: &Summary) -> String {
    use autobal::spatial::dynamics::RunOutcome;
    if autobal::planar::at_rest(p, s.final_omega) {
        // the residual's scale at rest is a length (s2, or s1 + s2 + n m3 r / m0 for a centred
        // race): its product with the residual is E's distance from the axis
        let e = s.residual_unbalance * autobal::planar::stationary::race_offset_scale(p, s.final_omega);
        return format!(
            "not balanced: at rest (|ω| below {} sqrt(k/m0)) nothing turns the balls against the unbalance; the race centre {:.4} mm from the axis",
            autobal::planar::REST_FRACTION,
            1e3 * e
        );
    }
    let what = match s.outcome {
        RunOutcome::Balanced if p.s2 > 0.0 && p.anisotropic() => {
            "semi-balanced (the race centre on the axis and C at s2 on average over a revolution: supports that differ by direction make them swing about it)"
        }
        RunOutcome::Balanced if p.s2 > 0.0 => "semi-balanced (the race centre on the axis, C whirling at s2)",
        RunOutcome::Balanced => "balanced",
        // supports that differ by direction: decided on the end state alone (no closed form)
        RunOutcome::PartiallyBalanced if p.anisotropic() && p.s2 > 0.0 && p.n >= 2 => {
            "partially balanced: the balls rest together at their capacity limit with the race centre off the axis"
        }
        // with enough ball mass for high speeds (α∞ > 1) the capacity is not what falls short
        RunOutcome::PartiallyBalanced if capacity_ratio(p) > 1.0 => {
            "partially balanced: no semi-balanced state at this speed, the balls rest together against the unbalance"
        }
        RunOutcome::PartiallyBalanced => "partially balanced: the balls reduce the unbalance without cancelling it (a residual below 1: their capacity short, a couple one plane cannot cancel, or the balls settled off the balanced state)",
        RunOutcome::NotBalanced => "not balanced",
        RunOutcome::NotSettled => return "not settled".to_string(),
    };
    let of = if p.s2 > 0.0 { "of the race centre's offset without the balls" } else { "of the unbalance" };
    format!("{what}; residual unbalance {:.3e} {of} ({})", s.residual_unbalance, autobal::simulation::window::basis_words(s.averaged))
}

/// The run's outcome in a few words for a table cell ([`outcome_words`]): `semi-balanced`
/// (an eccentric race's balanced state), `balanced`, `partially balanced (residual R)`, `not
/// balanced`, `not settled`.
pub fn outcome_short(p: &autobal::planar::PlanarRotor, s: &Summary) -> String {
    use autobal::spatial::dynamics::RunOutcome;
    match s.outcome {
        RunOutcome::Balanced if p.s2 > 0.0 => "semi-balanced".into(),
        RunOutcome::PartiallyBalanced => format!("partially balanced (residual {:.3})", s.residual_unbalance),
        o => o.name().into(),
    }
}

/// Ball angles in degrees wrapped to (−180°, 180°], the line broken where it wraps (a ball
/// slipping round the race would otherwise run off to thousands of degrees).
pub fn wrapped_degrees(points: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let mut out = vec![];
    wrapped_degrees_into(&mut out, points);
    out
}

/// [`wrapped_degrees`] into `out` (cleared first): one buffer for every ball of a figure, so
/// the second ball's points reuse the pages the first one touched.
fn wrapped_degrees_into(out: &mut Vec<(f64, f64)>, points: impl Iterator<Item = (f64, f64)>) {
    // room for every point and a break before each (a ball slipping round the race breaks its
    // line hundreds of times): one allocation, never grown and copied; the pages of the room
    // not used are never touched
    out.clear();
    out.reserve(2 * points.size_hint().0 + 16);
    for (t, a) in points {
        let d = wrap_360(a.to_degrees() + 180.0) - 180.0;
        if let Some(&(_, prev)) = out.last() {
            if prev.is_finite() && (d - prev).abs() > 180.0 {
                out.push((t, f64::NAN));
            }
        }
        out.push((t, d));
    }
}

/// `v.rem_euclid(360.0)`, bit for bit, without the `fmod` call where `|v| < 2^52` (the ball
/// angles of a run that slips round the race are mostly outside one turn). On [0, 360) it is
/// `v`; on (−360, 0) fmod returns `v` and `rem_euclid` adds 360: the same addition. Otherwise
/// `v − 360 q` with `q = ⌊v / 360⌋` is exact: `v` and `360 q` (an integer below 2^53) are
/// multiples of `ulp(v)` (at most 1 below 2^52) and the difference, below 720 in magnitude
/// (`q` may be one off where `v / 360` rounds onto an integer), is representable; one exact
/// correction by ±360 brings it into [0, 360). That is fmod's exact remainder, plus 360 where it
/// is negative, and `rem_euclid`'s rounded sum of the two is exact as well (a multiple of
/// `ulp(v)` below 360). The one difference, `-0` for `rem_euclid` where `v` is a negative
/// multiple of 360 and `+0` here, is gone after the caller's `- 180`.
fn wrap_360(v: f64) -> f64 {
    if (0.0..360.0).contains(&v) {
        v
    } else if v > -360.0 && v < 0.0 {
        v + 360.0
    } else if v.abs() < 4_503_599_627_370_496.0 {
        let q = v / 360.0;
        let q = {
            let i = q as i64;
            if (i as f64) > q {
                i - 1
            } else {
                i
            }
        };
        let r = v - 360.0 * q as f64;
        if r < 0.0 {
            r + 360.0
        } else if r >= 360.0 {
            r - 360.0
        } else {
            r
        }
    } else {
        v.rem_euclid(360.0)
    }
}

/// Most ball-angle curves drawn in one figure.
pub const PSI_CURVES: usize = 24;

/// The four figures of 004's kind: amplitude vs ω with stationary curves, amplitude vs t,
/// ball angles vs t, ω vs t.
pub fn plots(cfg: &PlanarConfig, env: &Envelope, title: &str) -> Vec<(String, Plot)> {
    plots_with(cfg, env, title, false)
}

/// [`plots`], the run's curves built from what their SVG draws ([`crate::plot::line_columns`],
/// the same SVG) where `columns`: `simulate`'s figure files; the report and Python's figures
/// keep every sample (Plotly's zoom and hover show them).
fn plots_with(cfg: &PlanarConfig, env: &Envelope, title: &str, columns: bool) -> Vec<(String, Plot)> {
    fn line<I: Iterator<Item = (f64, f64)> + Clone>(points: I, columns: bool) -> Vec<(f64, f64)> {
        if columns {
            crate::plot::line_columns(points)
        } else {
            points.collect()
        }
    }
    let k = || env.rows();
    let (ia, ip) = (env.amplitude_at(), env.psi_at());
    let (t, om, amp) = (|r: &[f64]| r[ROW_T], |r: &[f64]| r[ROW_OMEGA], move |r: &[f64]| r[ia]);
    let t_last = env.rows().last().map_or(1.0, t);
    let p = &cfg.rotor;
    let mm = 1e3;
    let (wlo, whi) = k().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), r| (a.min(om(r)), b.max(om(r))));
    let (wlo, whi) = if whi > wlo { (wlo.max(0.0), whi) } else { (0.0, 2.0 * p.natural_frequency()) };
    let ws: Vec<f64> = (0..=600).map(|i| wlo + (whi - wlo) * i as f64 / 600.0).collect();
    let mut s1 = vec![Series::new("transient", line(k().map(|r| (om(r), mm * amp(r))), columns), PALETTE[0])];
    s1.push(Series::new("stationary (balls held)", ws.iter().map(|&w| (w, mm * locked_amplitude(p, w, &cfg.settings.psi0))).collect(), PALETTE[6]).dashed());
    // the semi-balanced amplitude where that state exists on the run's speeds (nowhere: no
    // curve, and no legend entry naming one)
    if p.n >= 2 && ws.iter().any(|&w| semi_balanced_exists(p, w)) {
        s1.push(
            Series::new("semi-balanced (= s2)", ws.iter().map(|&w| (w, if semi_balanced_exists(p, w) { mm * p.s2 } else { f64::NAN })).collect(), PALETTE[2])
                .dashed(),
        );
    }
    if p.n >= 1 {
        let q = p.n as i32;
        for (label, qq, col) in [("balls free, far side", q, PALETTE[1]), ("balls free, near side", -q, PALETTE[3])] {
            let mut a = vec![];
            let pts = ws
                .iter()
                .map(|&w| {
                    // only the branch with every ball on one side: O(1) per speed, whatever n
                    a.clear();
                    aligned_whirls_of(p, w, qq, &mut a);
                    (w, a.iter().map(|a| mm * a.amplitude).fold(f64::NAN, f64::min))
                })
                .collect();
            s1.push(Series::new(label, pts, col).dashed());
        }
    }
    let peak = k().map(amp).fold(0.0, f64::max) * mm;
    let mut out = vec![(
        "amplitude_omega".to_string(),
        Plot {
            title: format!("{title}: whirl radius of C against speed"),
            x_label: "ω (rad/s)".into(),
            y_label: "radius of C (mm)".into(),
            series: s1,
            y_range: Some((0.0, 1.15 * peak.max(1e-6))),
            ..Default::default()
        },
    )];
    out.push((
        "amplitude_t".into(),
        Plot {
            title: format!("{title}: whirl radius of C against time"),
            x_label: "t (s)".into(),
            y_label: "radius of C (mm)".into(),
            series: vec![
                Series::new("radius of C", line(k().map(|r| (t(r), mm * amp(r))), columns), PALETTE[0]),
                Series::new("s2", vec![(0.0, mm * p.s2), (t_last, mm * p.s2)], PALETTE[7]).dashed(),
            ],
            ..Default::default()
        },
    ));
    // at most PSI_CURVES balls drawn (a figure of 1e5 curves is tens of MB and unreadable);
    // the CSV has every ball
    let drawn = p.n.min(PSI_CURVES);
    // the wrapped angles of one ball at a time, in one buffer (its columns are what is kept)
    let mut wrapped: Vec<(f64, f64)> = vec![];
    let psi: Vec<Series> = (0..drawn)
        .map(|j| {
            Series::new(
                format!("ψ{}", j + 1),
                {
                    let angles = k().map(|r| (t(r), r[ip + j]));
                    if columns {
                        wrapped_degrees_into(&mut wrapped, angles);
                        crate::plot::line_columns(wrapped.iter().copied())
                    } else {
                        wrapped_degrees(angles)
                    }
                },
                PALETTE[(j + 1) % 7],
            )
        })
        .collect();
    let psi_title = if drawn < p.n { format!("{title}: ball angles (balls 1-{drawn} of {})", p.n) } else { format!("{title}: ball angles") };
    out.push(("psi_t".into(), Plot { title: psi_title, x_label: "t (s)".into(), y_label: "ψ (degrees from CG)".into(), series: psi, ..Default::default() }));
    out.push((
        "omega_t".into(),
        Plot {
            title: format!("{title}: speed"),
            x_label: "t (s)".into(),
            y_label: "ω (rad/s)".into(),
            series: vec![
                Series::new("ω", line(k().map(|r| (t(r), om(r))), columns), PALETTE[0]),
                Series::new("sqrt(k/m0)", vec![(0.0, p.natural_frequency()), (t_last, p.natural_frequency())], PALETTE[7]).dashed(),
            ],
            ..Default::default()
        },
    ));
    out
}

/// The figures' names beside the CSV: `STEM_amplitude_omega.svg`, `STEM_amplitude_t.svg`,
/// `STEM_psi_t.svg`, `STEM_omega_t.svg` (the planar and the spatial simulation draw the same
/// four), known before the run so that `--out` is checked before any work.
pub const PLOTS: [&str; 4] = ["amplitude_omega", "amplitude_t", "psi_t", "omega_t"];

/// `STEM_suffix.svg`.
pub fn plot_path(stem: &Path, suffix: &str) -> PathBuf {
    let name = format!("{}_{suffix}.svg", stem.file_name().and_then(|s| s.to_str()).unwrap_or("simulation"));
    stem.with_file_name(name)
}

/// Every figure's path ([`PLOTS`]).
pub fn plot_paths(stem: &Path) -> Vec<PathBuf> {
    PLOTS.iter().map(|s| plot_path(stem, s)).collect()
}

/// Write the four figures ([`plots`], each curve built from its pixel columns,
/// [`crate::plot::line_columns`]), one after the other: drawn from a few hundred points a
/// curve they cost less than a thread's start, stack and malloc arena.
pub fn write_plots(cfg: &PlanarConfig, env: &Envelope, stem: &Path, title: &str) -> Result<Vec<PathBuf>> {
    let figures: Vec<(PathBuf, Plot)> = plots_with(cfg, env, title, true).into_iter().map(|(suffix, plot)| (plot_path(stem, &suffix), plot)).collect();
    for (path, plot) in &figures {
        crate::outfile::write_atomic("--out", path, plot.to_svg())?;
    }
    Ok(figures.into_iter().map(|(path, _)| path).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t: f64, amplitude: f64) -> Sample {
        Sample { t, omega: 2.0 * t, theta: 0.5 * t, x: amplitude, y: -amplitude, amplitude, psi: vec![t, -t] }
    }

    /// The envelope as it was written first (every sample of a bucket cloned, the extremes picked
    /// by `min_by`/`max_by` when the bucket is full): the reference the streaming one must equal.
    fn reference(samples: &[Sample], expected: usize, target: usize) -> Vec<Sample> {
        let bucket = expected.div_ceil(target.max(1)).max(1);
        let mut kept = vec![];
        for chunk in samples.chunks(bucket) {
            if chunk.len() <= 2 {
                kept.extend_from_slice(chunk);
                continue;
            }
            let imin = (0..chunk.len()).min_by(|&a, &b| chunk[a].amplitude.total_cmp(&chunk[b].amplitude)).unwrap();
            let imax = (0..chunk.len()).max_by(|&a, &b| chunk[a].amplitude.total_cmp(&chunk[b].amplitude)).unwrap();
            let (a, b) = (imin.min(imax), imin.max(imax));
            kept.push(chunk[a].clone());
            if b != a {
                kept.push(chunk[b].clone());
            }
        }
        kept
    }

    /// The streaming envelope keeps exactly the samples of the reference, in order, for buckets
    /// of 1 to 7 samples, runs shorter and longer than expected, a partial last bucket, ties
    /// (amplitudes drawn from 5 values, so buckets hold equal minima and maxima: the first
    /// smallest and the last largest are kept) and NaN amplitudes (ordered by `total_cmp`).
    #[test]
    fn the_streaming_envelope_keeps_what_the_buffered_one_kept() {
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        for case in 0..400 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let expected = 1 + (x % 60) as usize;
            let target = 1 + (x >> 8) as usize % 12;
            let count = (x >> 16) as usize % 80;
            let samples: Vec<Sample> = (0..count)
                .map(|k| {
                    let v = (x.rotate_left(k as u32 * 7) >> 3) % 6;
                    sample(k as f64, if v == 5 && case % 3 == 0 { f64::NAN } else { v as f64 })
                })
                .collect();
            let mut env = Envelope::new(expected, target);
            samples.iter().for_each(|s| env.push(s));
            env.flush();
            // the figures' envelope keeps the same samples, their t, ω, amplitude and ψ bit for bit
            let mut fig = Envelope::for_figures(expected, target);
            samples.iter().for_each(|s| fig.push(s));
            fig.flush();
            assert_eq!(fig.len(), env.len(), "case {case}");
            for (k, (f, w)) in fig.rows().zip(env.rows()).enumerate() {
                let whole: Vec<u64> = [w[ROW_T], w[ROW_OMEGA], w[ROW_AMPLITUDE]].iter().chain(&w[ROW_PSI..]).map(|v| v.to_bits()).collect();
                let narrow: Vec<u64> = [f[ROW_T], f[ROW_OMEGA], f[fig.amplitude_at()]].iter().chain(&f[fig.psi_at()..]).map(|v| v.to_bits()).collect();
                assert_eq!(narrow, whole, "case {case}, kept {k}");
                assert_eq!(f.len(), w.len() - 3, "case {case}: θ, X, Y not kept");
            }
            let want = reference(&samples, expected, target);
            let kept = env.kept();
            assert_eq!(kept.len(), want.len(), "case {case}: expected {expected}, target {target}, {count} samples");
            assert_eq!(env.len(), want.len());
            for (k, (a, b)) in kept.iter().zip(&want).enumerate() {
                // compared as bits: NaN amplitudes are kept too
                assert!(
                    a.t == b.t
                        && a.amplitude.to_bits() == b.amplitude.to_bits()
                        && a.psi == b.psi
                        && a.omega == b.omega
                        && [a.theta, a.x, a.y].map(f64::to_bits) == [b.theta, b.x, b.y].map(f64::to_bits),
                    "case {case}, kept {k}"
                );
            }
        }
    }

    /// `run_rows` hands over every sample's row once, in order, bit for bit the library's
    /// samples, over several batches (the default passage's 4 801 rows are 5 batches, the
    /// buffers sent back and refilled): a buffer refilled without being emptied, a row lost at
    /// a batch's end or the last partial batch not sent would change the rows.
    #[test]
    fn run_rows_hands_over_every_sample_once_in_order() {
        let cfg = crate::config::load_planar(None, &[]).unwrap();
        let width = 5 + cfg.rotor.n;
        let mut got: Vec<Vec<f64>> = vec![];
        let (_, env, _) = run_rows(
            &cfg,
            &mut |r| {
                got.push(r.to_vec());
                Ok(())
            },
            &Control::new(),
        )
        .unwrap();
        let mut want: Vec<Vec<f64>> = vec![];
        simulate_with(&cfg.rotor, &cfg.drive, &cfg.settings, &Control::new(), |s| {
            let mut r = vec![s.t, s.omega, s.x, s.y, s.amplitude];
            r.extend_from_slice(&s.psi);
            want.push(r);
            true
        })
        .unwrap();
        assert!(want.len() > 3 * batch_rows(width) + 1, "{} rows: not several batches", want.len());
        assert_eq!(got.len(), want.len());
        for (k, (a, b)) in got.iter().zip(&want).enumerate() {
            assert!(a.iter().map(|v| v.to_bits()).eq(b.iter().map(|v| v.to_bits())), "row {k}");
        }
        assert_eq!(env.len(), want.len(), "a run shorter than the envelope's target keeps every sample");
    }

    /// The four figures of a passage are the same SVG text from the figures' envelope (what
    /// `run_rows` keeps) as from an envelope of whole samples, both as `simulate` draws them
    /// (from pixel columns) and as the report and Python do (every sample): the figures read the
    /// amplitude and the ball angles where each envelope keeps them. The passage is cut to 60 s
    /// (1 201 samples: the balls slip and wrap, the whirl grows) to keep the test short.
    #[test]
    fn the_figures_envelope_draws_what_the_whole_one_draws() {
        let cfg = crate::config::load_planar(None, &["drive.t_end=60".to_string()]).unwrap();
        let expected = (cfg.settings.t_end / cfg.settings.dt) as usize + 1;
        let (mut whole, mut fig) = (Envelope::new(expected, 6000), Envelope::for_figures(expected, 6000));
        simulate_with(&cfg.rotor, &cfg.drive, &cfg.settings, &Control::new(), |s| {
            whole.push(s);
            fig.push(s);
            true
        })
        .unwrap();
        whole.flush();
        fig.flush();
        assert!(fig.len() > 1000, "{} samples", fig.len());
        for columns in [true, false] {
            let a = plots_with(&cfg, &whole, "Passage", columns);
            let b = plots_with(&cfg, &fig, "Passage", columns);
            assert_eq!(a.len(), 4);
            for ((na, pa), (nb, pb)) in a.iter().zip(&b) {
                assert_eq!(na, nb);
                assert!(pa.to_svg() == pb.to_svg(), "{na} (columns: {columns})");
            }
        }
    }

    /// The CSV text of a sink is the rows' values as `Csv`'s `Display` text, comma-joined, a line
    /// each, after the header, whatever the row width (0 to 40 values: rows of up to 1 600
    /// bytes) and wherever the chunks end; every chunk but the last reaches the writer whole, at
    /// least `CSV_CHUNK` bytes (the staged file's buffer passes it through without a copy).
    #[test]
    fn a_sinks_csv_is_every_row_as_text_in_whole_chunks() {
        struct Chunks(Vec<Vec<u8>>, bool);
        impl Write for Chunks {
            fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
                self.0.push(b.to_vec());
                Ok(b.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                self.1 = true;
                Ok(())
            }
        }
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        for width in [0usize, 1, 7, 40] {
            let mut out = Chunks(vec![], false);
            let mut want = String::new();
            {
                let mut sink = RowSink::new(Some(&mut out), None, None);
                let names: Vec<String> = (0..width).map(|j| format!("c{j}")).collect();
                sink.header(&names).unwrap();
                want.push_str(&names.join(","));
                want.push('\n');
                for _ in 0..3000 {
                    let row: Vec<f64> = (0..width)
                        .map(|_| {
                            x ^= x << 13;
                            x ^= x >> 7;
                            x ^= x << 17;
                            match x % 17 {
                                0 => 0.0,
                                1 => f64::NAN,
                                2 => -f64::INFINITY,
                                3 => (x >> 20) as f64,
                                _ => f64::from_bits(x >> 2) * if x & 2 == 0 { 1.0 } else { -1.0 },
                            }
                        })
                        .collect();
                    sink.push(&row).unwrap();
                    want.push_str(&row.iter().map(|v| crate::num::Csv(*v).to_string()).collect::<Vec<_>>().join(","));
                    want.push('\n');
                }
                sink.finish().unwrap();
            }
            assert!(out.1, "finish flushes");
            let n = out.0.len();
            assert!(out.0[..n - 1].iter().all(|c| c.len() >= CSV_CHUNK), "width {width}: a chunk short of CSV_CHUNK before the last");
            assert!(out.0.iter().all(|c| c.ends_with(b"\n")), "width {width}: whole lines a chunk");
            assert_eq!(String::from_utf8(out.0.concat()).unwrap(), want, "width {width}");
        }
    }

    /// Wrapping ball angles: the fast path (already in [−180°, 180°)) is `rem_euclid`'s value,
    /// and a ball that slips round the race has its line broken where it wraps.
    #[test]
    fn wrapped_degrees_match_rem_euclid_and_break_at_the_wrap() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut angles: Vec<f64> = (-4000..4000).map(|k| k as f64 * 0.0123).collect();
        // far-slipping balls (up to 1e12 rad), the multiples of a turn and their neighbours,
        // the ends of the exact range
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let u = (x >> 11) as f64 / (1u64 << 53) as f64;
            angles.push((u - 0.5) * 10f64.powf(-2.0 + 14.0 * ((x & 0xff) as f64 / 255.0)));
        }
        for k in -3000..3000 {
            let v = k as f64 * 360.0 - 180.0;
            for w in [v, v.next_up(), v.next_down()] {
                angles.push((w - 180.0).to_radians());
                assert_eq!((wrap_360(w) - 180.0).to_bits(), (w.rem_euclid(360.0) - 180.0).to_bits(), "{w}");
            }
        }
        for w in [4.5e15, -4.5e15, 4_503_599_627_370_495.0, -4_503_599_627_370_495.0, 1e300, -1e300, f64::INFINITY, f64::NAN, -0.0, 0.0, -360.0, 360.0] {
            assert_eq!((wrap_360(w) - 180.0).to_bits(), (w.rem_euclid(360.0) - 180.0).to_bits(), "{w}");
        }
        for a in angles {
            let got = wrapped_degrees([(0.0, a)].into_iter())[0].1;
            let want = (a.to_degrees() + 180.0).rem_euclid(360.0) - 180.0;
            assert_eq!(got.to_bits(), want.to_bits(), "{a}");
        }
        let w = wrapped_degrees([(0.0, 3.0), (1.0, 3.3), (2.0, 3.6)].into_iter());
        assert_eq!(w.len(), 4);
        assert!(w[1].1.is_nan() && w[2].1 < -170.0 && w[3].1 < -150.0);
    }
}
