//! `autobal simulate` on the spatial rotor of papers 000/003 (the analytic commands' config
//! plus `[drive]`, `[integration]`, optionally `[initial]`, `[spatial]`, `[couple]`,
//! `[balancer2]`) (`autobal basins`: [`crate::basins`]).

use crate::plot::{Plot, Series, PALETTE};
use anyhow::{bail, Result};
use autobal::config::SpatialSimulation;
use autobal::control::Control;
use autobal::spatial::dynamics::stationary::response_curve;
use autobal::spatial::dynamics::{simulate_with, Sample, Summary};
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use toml::Table;

/// A loaded spatial simulation: the library's converted config and where it came from.
pub struct SpatialSim {
    pub lib: SpatialSimulation,
    pub source: String,
}

impl std::ops::Deref for SpatialSim {
    type Target = SpatialSimulation;
    fn deref(&self) -> &SpatialSimulation {
        &self.lib
    }
}

impl std::ops::DerefMut for SpatialSim {
    fn deref_mut(&mut self) -> &mut SpatialSimulation {
        &mut self.lib
    }
}

impl SpatialSim {
    /// Units of lengths and speeds for labels.
    fn units(&self) -> (&'static str, f64, &'static str, &'static str) {
        if self.config.dimensional {
            ("mm", 1e3, "ω (rad/s)", "t (s)")
        } else {
            ("ρ_s", 1.0, "Ω", "τ")
        }
    }
}

/// Build the spatial simulation from a config table (converted by the library,
/// [`autobal::config::spatial_simulation`]).
pub fn build(root: &Table, source: &str) -> Result<SpatialSim> {
    Ok(SpatialSim { lib: autobal::config::spatial_simulation(root)?, source: source.to_string() })
}

/// Samples kept for the plots: per bucket of consecutive samples the smallest and largest
/// whirl radius at the balancer plane (so peaks survive decimation).
struct Envelope {
    bucket: usize,
    current: Vec<Sample>,
    kept: Vec<Sample>,
}

impl Envelope {
    fn push(&mut self, s: &Sample) {
        self.current.push(s.clone());
        if self.current.len() >= self.bucket {
            self.flush();
        }
    }
    fn flush(&mut self) {
        let key = |s: &Sample| s.amplitude_planes.first().copied().unwrap_or(0.0);
        if self.current.len() > 2 {
            let by = |a: &usize, b: &usize| key(&self.current[*a]).total_cmp(&key(&self.current[*b]));
            let imin = (0..self.current.len()).min_by(by).unwrap_or(0);
            let imax = (0..self.current.len()).max_by(by).unwrap_or(0);
            let mut keep = vec![imin.min(imax), imin.max(imax)];
            keep.dedup();
            self.current = keep.into_iter().map(|i| self.current[i].clone()).collect();
        }
        self.kept.append(&mut self.current);
    }
}

/// The columns of the samples: `t, omega, x, y, tilt_x, tilt_y`, the supports' and planes'
/// amplitudes, `psi_1 … psi_n`.
pub fn columns(sim: &SpatialSim) -> Vec<String> {
    let r = &sim.rotor;
    let mut c: Vec<String> = ["t", "omega", "x", "y", "tilt_x", "tilt_y"].iter().map(|s| s.to_string()).collect();
    c.extend(["left", "right"].iter().take(r.supports.len()).map(|s| format!("amplitude_{s}")));
    c.extend((1..=r.planes.len().max(1)).map(|p| format!("amplitude_plane{p}")));
    c.extend((1..=r.balls()).map(|j| format!("psi_{j}")));
    c
}

/// Run, writing every sample to `csv` (flushed as it goes; `progress`: a bar on standard error
/// when it is a terminal).
pub fn run_to_csv(sim: &SpatialSim, csv: &mut dyn Write, progress: bool, control: &Control) -> Result<(Summary, Vec<Sample>, f64)> {
    run_to_files(sim, csv, None, progress, control)
}

/// Run, writing every sample to `csv` (flushed as it goes) and to `parquet` if given
/// ([`run_rows`] into a [`crate::sim::RowSink`]).
pub fn run_to_files(
    sim: &SpatialSim,
    csv: &mut dyn Write,
    parquet: Option<&mut crate::parquet::Table>,
    progress: bool,
    control: &Control,
) -> Result<(Summary, Vec<Sample>, f64)> {
    let (shown, bar) = if progress { crate::term::progress_bar(control) } else { (control.clone(), None) };
    let mut sink = crate::sim::RowSink::new(Some(csv), parquet, None);
    sink.header(&columns(sim))?;
    let out = run_rows(sim, &mut |r| sink.push(r), &shown);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let out = out?;
    sink.finish().map_err(|e| anyhow::anyhow!("--out: cannot write: {e:#}"))?;
    Ok(out)
}

/// Run, handing every sample's row (the values of [`columns`]) to `rows`; an error of `rows`
/// stops the run and is returned as `--out: cannot write: ...`. Returns the summary, the
/// samples kept for the figures (per bucket of consecutive samples the smallest and largest
/// whirl radius at the balancer plane) and the wall time. Progress (per mille of `t_end`) goes
/// to `control`'s observer.
pub fn run_rows(sim: &SpatialSim, rows: &mut dyn FnMut(&[f64]) -> Result<()>, control: &Control) -> Result<(Summary, Vec<Sample>, f64)> {
    let mut row = vec![];
    let expected = (sim.settings.t_end / sim.settings.dt) as usize + 1;
    let mut env = Envelope { bucket: expected.div_ceil(6000).max(1), current: vec![], kept: vec![] };
    let mut io_error = None;
    let mut count = 0u64;
    let t0 = std::time::Instant::now();
    let summary = simulate_with(&sim.rotor, &sim.drive, &sim.initial, &sim.settings, control, |s| {
        row.clear();
        row.extend([s.t, s.omega, s.x, s.y, s.tilt_x, s.tilt_y]);
        row.extend(s.amplitude_supports.iter().chain(&s.amplitude_planes).chain(&s.psi));
        if let Err(e) = rows(&row) {
            io_error = Some(e);
            return false;
        }
        env.push(s);
        count += 1;
        if count.is_multiple_of(1000) {
            control.report((1000.0 * s.t / sim.settings.t_end) as u64, 1000);
        }
        true
    })?;
    let wall = t0.elapsed().as_secs_f64();
    env.flush();
    if let Some(e) = io_error {
        bail!("--out: cannot write: {e:#}");
    }
    Ok((summary, env.kept, wall))
}

/// The summary as `--format json` prints it ([`autobal::reports::spatial_simulation`]), its
/// `warnings` those the table prints ([`warnings`]).
pub fn summary_json(sim: &SpatialSim, s: &Summary, wall: f64) -> Value {
    let mut v = autobal::reports::spatial_simulation(sim, s, wall);
    if let Some(o) = v.as_object_mut() {
        o.insert("warnings".into(), serde_json::json!(warnings(s)));
        // the table's reason for a missing sag under gravity (a run not settled)
        if s.static_sag.is_none() && s.averaged && sim.rotor.gravity_across() {
            o.insert(
                "static_sag_note".into(),
                serde_json::json!("not reported: the run has not settled, the last revolution's mean position is the transient's"),
            );
        }
    }
    v
}

/// The run's warnings: the summary's, or where the run completed not settled without one that
/// says why, that it is no stationary state (audit 25: the table said so, the JSON's
/// `warnings` was empty).
pub fn warnings(s: &Summary) -> Vec<String> {
    use autobal::spatial::dynamics::RunOutcome;
    // (not where the creep check said why: the balls creep away from an unstable balanced
    // state, which a longer run leaves, and their drift passed the test)
    if s.outcome == RunOutcome::NotSettled && s.stopped.is_none() && s.warnings.is_empty() {
        return vec![format!(
            "the balls have not settled: their mean angles still drift from one revolution to the next{}: a transient (raise drive.t_end) or balls circulating round the race; the residual and radius are no stationary state's, and the static sag is not reported (the last revolution's mean position is the transient's)",
            s.ball_drift.map_or(", or it turned less than two revolutions".to_string(), |d| format!(" by {d:.2e} rad"))
        )];
    }
    s.warnings.clone()
}

pub fn summary_table(sim: &SpatialSim, s: &Summary, wall: f64) -> String {
    use std::fmt::Write as _;
    let (lu, ls, _, _) = sim.units();
    let mut o = String::new();
    let (balls, planes) = (sim.rotor.balls(), sim.rotor.planes.len());
    let _ = writeln!(
        o,
        "config: {} (spatial rotor, {balls} ball{} in {planes} plane{})",
        sim.source,
        if balls == 1 { "" } else { "s" },
        if planes == 1 { "" } else { "s" }
    );
    // speeds and times in the config's units: rad/s (rpm) and s, or the papers' Ω and τ
    let speed = |w: f64| match sim.config.dimensional {
        true => format!("ω = {w:.4} rad/s = {:.1} rpm", w * 30.0 / std::f64::consts::PI),
        false => format!("Ω = {w:.4}"),
    };
    let time = |t: f64| if sim.config.dimensional { format!("t = {t:.4} s") } else { format!("τ = {t:.4}") };
    let _ = writeln!(
        o,
        "peak whirl radius at the balancer plane (distance from the axis, a sag included): {:.6} {lu} at {} ({})",
        ls * s.peak_amplitude,
        speed(s.omega_at_peak),
        time(s.t_at_peak)
    );
    use autobal::spatial::dynamics::RunOutcome;
    let _ = writeln!(
        o,
        "final: {} {:.6} {lu} at {}{}; residual unbalance {:.3e} of the unbalance{} ({}); {}",
        // the RMS whirl about the mean position, or (no revolution recorded) the distance
        // from the axis at the end, a sag included
        if s.averaged { "radius" } else { "distance from the axis" },
        ls * s.final_amplitude,
        speed(s.final_omega),
        // the sag only where the summary has one (gravity across the axis, or settled): else
        // the mean position is a transient's and the radius is still about it
        match s.static_sag {
            Some(sag) =>
                format!("; static sag {:.6} {lu} (last revolution: radius = RMS whirl about the mean position, sag = its distance from the axis)", ls * sag),
            // under gravity a sag is expected: say why there is none (not settled)
            None if s.averaged && sim.rotor.gravity_across() => "; static sag not reported (the run has not settled: the last revolution's mean position is the transient's)".to_string(),
            None => String::new(),
        },
        s.residual_unbalance,
        s.residual_couple.map_or(String::new(), |c| format!(", couple {c:.3e}")),
        autobal::simulation::window::basis_words(s.averaged),
        match s.outcome {
            RunOutcome::Balanced => "balanced",
            RunOutcome::PartiallyBalanced => "partially balanced: the balls reduce the unbalance without cancelling it (a residual below 1: their capacity short, a couple one plane cannot cancel, or the balls settled off the balanced state)",
            RunOutcome::NotBalanced => "not balanced",
            RunOutcome::NotSettled => "not settled",
        }
    );
    for w in &warnings(s) {
        let _ = writeln!(o, "warning: {w}");
    }
    let _ = writeln!(o, "integration: {} steps ({} rejected), {} right-hand sides, {:.3} s", s.steps, s.rejected_steps, s.rhs_evaluations, wall);
    if sim.rotor.planes.iter().any(|p| p.physics.is_active()) {
        let _ = writeln!(o, "real balls: {} contacts, {} stick-slip transitions", s.contacts, s.stick_slip_transitions);
    }
    if let Some(st) = &s.stopped {
        let _ = writeln!(o, "stopped early: {st}");
    }
    o
}

/// Amplitude against speed (with the stationary curve of the rotor with the balls held where
/// they start), amplitudes against time, ball angles, speed.
pub fn plots(sim: &SpatialSim, kept: &[Sample], title: &str) -> Vec<(String, Plot)> {
    let (lu, ls, wl, tl) = sim.units();
    let (wlo, whi) = kept.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| (a.min(s.omega), b.max(s.omega)));
    let (wlo, whi) = if whi > wlo { (wlo.max(0.0), whi) } else { (0.0, 2.0 * sim.rotor.natural_frequency()) };
    let ws: Vec<f64> = (0..=300).map(|i| wlo + (whi - wlo) * i as f64 / 300.0).collect();
    let curve = response_curve(&sim.rotor, &sim.initial.psi, &ws);
    let plane = |s: &Sample| s.amplitude_planes.first().copied().unwrap_or(0.0);
    let peak = kept.iter().map(plane).fold(0.0, f64::max) * ls;
    let series = vec![
        Series::new("transient", kept.iter().map(|s| (s.omega, ls * plane(s))).collect(), PALETTE[0]),
        Series::new(
            "stationary, balls held",
            ws.iter().zip(&curve).map(|(w, c)| (*w, c.as_ref().map_or(f64::NAN, |c| ls * c.amplitude_planes[0]))).collect(),
            PALETTE[6],
        )
        .dashed(),
    ];
    let mut out = vec![(
        "amplitude_omega".to_string(),
        Plot {
            title: format!("{title}: whirl radius at the balancer plane against speed"),
            x_label: wl.into(),
            y_label: format!("radius ({lu})"),
            series,
            y_range: Some((0.0, 1.15 * peak.max(1e-12))),
            ..Default::default()
        },
    )];
    let mut amp = vec![Series::new("balancer plane", kept.iter().map(|s| (s.t, ls * plane(s))).collect(), PALETTE[0])];
    for (i, name) in ["left support", "right support"].iter().enumerate().take(sim.rotor.supports.len()) {
        amp.push(Series::new(*name, kept.iter().map(|s| (s.t, ls * s.amplitude_supports[i])).collect(), PALETTE[i + 1]));
    }
    out.push((
        "amplitude_t".into(),
        Plot { title: format!("{title}: whirl radii"), x_label: tl.into(), y_label: format!("radius ({lu})"), series: amp, ..Default::default() },
    ));
    let psi: Vec<Series> = (0..sim.rotor.balls())
        .map(|j| Series::new(format!("ψ{}", j + 1), crate::sim::wrapped_degrees(kept.iter().map(|s| (s.t, s.psi[j]))), PALETTE[(j + 1) % 7]))
        .collect();
    out.push((
        "psi_t".into(),
        Plot {
            title: format!("{title}: ball angles"),
            x_label: tl.into(),
            y_label: "ψ (degrees from the unbalance)".into(),
            series: psi,
            ..Default::default()
        },
    ));
    out.push((
        "omega_t".into(),
        Plot {
            title: format!("{title}: speed"),
            x_label: tl.into(),
            y_label: wl.into(),
            series: vec![Series::new("speed", kept.iter().map(|s| (s.t, s.omega)).collect(), PALETTE[0])],
            ..Default::default()
        },
    ));
    out
}

pub fn write_plots(sim: &SpatialSim, kept: &[Sample], stem: &Path, title: &str) -> Result<Vec<PathBuf>> {
    let mut files = vec![];
    for (suffix, plot) in plots(sim, kept, title) {
        let path = crate::sim::plot_path(stem, &suffix);
        crate::outfile::write_atomic("--out", &path, plot.to_svg())?;
        files.push(path);
    }
    Ok(files)
}
