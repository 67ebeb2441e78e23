//! `autobal stability` and `autobal campbell`: exact linear stability of the balanced state.

use crate::config::Config;
use anyhow::Result;
use autobal::spatial::campbell::{fixed_axes, fixed_axes_with, FixedCampbell};
use autobal::spatial::comparison::fmt_ranges_in;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::stability::{campbell, campbell_stream, Campbell, Whirl};
use serde_json::Value;
use std::fmt::Write;

pub use autobal::spatial::comparison::{compare, Comparison};

pub fn stability_json(cfg: &Config, c: &Comparison, balls: Balls) -> Value {
    autobal::reports::to_json(&autobal::reports::stability_of(&cfg.config, c, balls))
}

/// A speed `Ω` as the config's user reads it: `Ω = 1.5 (157.1 rad/s, 1500 rpm)` for a
/// dimensional config, `Ω = 1.5` for a dimensionless one.
pub fn speed_text(cfg: &Config, w: f64) -> String {
    match cfg.model.scale {
        Some(sc) => {
            let (rad, rpm, _) = autobal::units::omega_in_si(w, sc.omega0);
            format!("{rpm:.0} rpm ({rad:.1} rad/s, Ω = {})", crate::num::fmt(w, 4))
        }
        None => format!("Ω = {}", crate::num::fmt(w, 4)),
    }
}

/// A speed or range `[lo, hi]` as [`speed_text`] writes one.
fn op_text(cfg: &Config, [lo, hi]: [f64; 2]) -> String {
    if lo == hi {
        return speed_text(cfg, lo);
    }
    match cfg.model.scale {
        Some(sc) => {
            let k = sc.omega0 * 30.0 / std::f64::consts::PI;
            format!("{:.0}-{:.0} rpm (Ω = {}-{})", lo * k, hi * k, crate::num::fmt(lo, 4), crate::num::fmt(hi, 4))
        }
        None => format!("Ω = {}-{}", crate::num::fmt(lo, 4), crate::num::fmt(hi, 4)),
    }
}

/// The verdict at the operating speed in words, one or two lines (the first lines of
/// `critical` and `stability`), or nothing without `analysis.operating_speed`.
pub fn operating_lines(cfg: &Config, v: Option<autobal::Result<autobal::reports::OperatingVerdict>>) -> String {
    let Some(v) = v else { return String::new() };
    let v = match v {
        Ok(v) => v,
        Err(e) => return format!("operating speed: the exact stability could not be computed ({e})\n"),
    };
    let at = op_text(cfg, v.omega);
    let f = |x: f64| crate::num::fmt(x, 4);
    let rate = match v.max_real_part_per_s {
        Some(r) => format!("max Re λ = {} 1/s ({} in units of ω0)", f(r), f(v.max_real_part)),
        None => format!("max Re λ = {}", f(v.max_real_part)),
    };
    let rpm = cfg.model.scale.map(|sc| sc.omega0 * 30.0 / std::f64::consts::PI);
    let range = |r: autobal::spatial::ranges::SpeedRange| match rpm {
        Some(k) => format!("{:.0}-{} rpm", r.lo * k, r.hi.map_or(format!("{:.0}+", v.span * k), |h| format!("{:.0}", h * k))),
        None => format!("Ω = {}-{}", f(r.lo), r.hi.map_or(format!("{}+", f(v.span)), f)),
    };
    let dist = |d: f64| match rpm {
        Some(k) => format!("{:.0} rpm (Ω {})", d * k, f(d)),
        None => format!("Ω {}", f(d)),
    };
    let end = |w: f64| match rpm {
        Some(k) => format!("{:.0} rpm", w * k),
        None => format!("Ω = {}", f(w)),
    };
    if v.stable {
        let r = v.stable_range.expect("a stable verdict has its range");
        let margin = match (v.margin_below, v.margin_above) {
            (Some(b), Some(a)) if a < b => format!("margin {} to its upper end", dist(a)),
            (Some(b), Some(_)) => format!("margin {} to its lower end", dist(b)),
            (Some(b), None) => format!("margin {} to its lower end; no upper end up to {}", dist(b), end(v.span)),
            _ => String::new(),
        };
        format!("operating speed {at}: the balanced state is STABLE (exact, balls {}) in the stable range {}, {margin}; {rate}\n", v.balls, range(r))
    } else {
        let near = v.nearest_stable_range.map_or(format!("no stable range up to {}", end(v.span)), |r| format!("nearest stable range {}", range(r)));
        // a growth rate within the tolerance of zero is no instability (hunt 27: 1 rpm read NOT
        // STABLE at 8.7e-11 1/s; the general route says NEUTRAL there): not stable, and why
        let word = if v.max_real_part.abs() <= autobal::spatial::stability::STABILITY_TOLERANCE {
            format!(
                "NEUTRAL (not stable: its largest growth rate is within the tolerance {} ω0 of zero)",
                crate::num::fmt(autobal::spatial::stability::STABILITY_TOLERANCE, 1)
            )
        } else {
            "NOT STABLE".to_string()
        };
        format!("operating speed {at}: the balanced state is {word} (exact, balls {}); {rate}; {near}\n", v.balls)
    }
}

pub fn stability_table(cfg: &Config, c: &Comparison, balls: Balls) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let op = cfg.analysis.operating_speed.map(|op| {
        if op[1] <= c.omega_max {
            autobal::reports::operating_verdict(&cfg.model, op, &c.exact.stable_ranges, c.omega_max, balls)
        } else {
            autobal::reports::operating_of(&cfg.config, balls).expect("an operating speed")
        }
    });
    if let Some(w) = autobal::reports::no_balanced_state_warning(&cfg.model) {
        let _ = writeln!(s, "{w}");
    }
    s.push_str(&operating_lines(cfg, op));
    let _ = writeln!(
        s,
        "exact linear stability of the balanced state, balls {} ({} states), 0 < Ω ≤ {}{}",
        if balls == Balls::Free { "free" } else { "locked" },
        if balls == Balls::Free { 12 } else { 8 },
        crate::num::fmt(c.omega_max, 7),
        cfg.model.scale.map_or(String::new(), |sc| {
            let (rpm, rad_s) = (c.omega_max * sc.omega0 * 30.0 / std::f64::consts::PI, c.omega_max * sc.omega0);
            // (below 1 rpm in significant digits: `--omega-max "1e-3 rpm"` read "up to 0 rpm")
            if rpm >= 1.0 {
                format!(" (up to {rpm:.0} rpm, {rad_s:.1} rad/s)")
            } else {
                format!(" (up to {} rpm, {} rad/s)", crate::num::fmt(rpm, 6), crate::num::fmt(rad_s, 6))
            }
        })
    );
    // stopped: every range below, 003's too, covers the speeds analysed only (review 23)
    match c.stopped_at {
        Some(at) if at > 0.0 => {
            let _ =
                writeln!(s, "  the scan stopped at Ω = {}: the ranges below, 003's too, cover 0 < Ω ≤ {} only", crate::num::fmt(at, 7), crate::num::fmt(at, 7));
        }
        Some(_) => {
            let _ = writeln!(s, "  the scan stopped before its first speed: no range below is known, 003's neither");
        }
        None => {}
    }
    // computed over (0, Ω_max] only: a range reaching Ω_max ends there as far as is known
    let w = Some(c.omega_max);
    if let Some(m) = autobal::reports::family_member(&cfg.model, balls) {
        let _ = writeln!(s, "  member: {m}");
    }
    let rule = if balls == Balls::Free { "all Re λ < −1e-11" } else { "all Re λ ≤ 1e-11" };
    let _ = writeln!(s, "  stable ({rule}): {}", fmt_ranges_in(&c.exact.stable_ranges, 6, w));
    let _ = writeln!(s, "  necessary (003, eqs (1)-(3)):   {}", fmt_ranges_in(&c.necessary, 6, w));
    let _ = writeln!(s, "  difference: {}", c.difference());
    if let Some(sc) = cfg.model.scale {
        let k = sc.omega0 * 30.0 / std::f64::consts::PI;
        let _ = writeln!(s, "  stable in rpm: {}", fmt_ranges_in(&autobal::reports::scale_ranges(&c.exact.stable_ranges, k), 0, Some(c.omega_max * k)));
        let _ = writeln!(s, "  necessary in rpm: {}", fmt_ranges_in(&autobal::reports::scale_ranges(&c.necessary, k), 0, Some(c.omega_max * k)));
    }
    let worst = c.exact.max_real_part.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
    let best = c.exact.max_real_part.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
    match cfg.model.scale {
        // stopped before the first speed (review 23: "from inf to -inf")
        _ if c.exact.max_real_part.is_empty() => {
            let _ = writeln!(s, "  max Re λ over the grid: none (no speed analysed)");
        }
        Some(sc) => {
            let _ = writeln!(
                s,
                "  max Re λ over the grid: from {:.4e} to {:.4e} 1/s ({best:.4e} to {worst:.4e} in units of ω0)",
                best * sc.omega0,
                worst * sc.omega0
            );
        }
        None => {
            let _ = writeln!(s, "  max Re λ over the grid: from {best:.4e} to {worst:.4e} (in units of ω0)");
        }
    }
    s
}

/// A speed option (`--omega-max 1500rpm`, `--omega 2.1`) as `Ω` ([`autobal::units`]): a bare
/// number is `Ω`; a dimensional config notes on standard error which speed that is, a
/// dimensionless one refuses units.
pub fn speed_arg(cfg: &Config, flag: &str, text: &str) -> Result<f64> {
    let s = autobal::units::parse_speed(flag, text)?;
    let w = s.to_omega(flag, cfg.model.scale.map(|sc| sc.omega0))?;
    if !s.is_si() && cfg.dimensional && w.is_finite() {
        bare_speed_note(flag, text, &speed_text(cfg, w));
    }
    Ok(w)
}

/// The note on a bare number given for a speed on an SI config (`--omega-max 2`): it is the
/// dimensionless `Ω`, `converted` the caller's own conversion of it (this route's
/// [`speed_text`]; the general route's rad/s, `crate::general_campbell::omega_max`). The one
/// home of the wording, for both routes.
pub fn bare_speed_note(flag: &str, text: &str, converted: &str) {
    crate::term::note(&format!("note: {flag} {text} is the dimensionless Ω = {text}, i.e. {converted}; give a unit (rpm, rad/s or Hz) for SI"));
}

/// ω0 (rad/s per Ω) where `text`, a speed option's value, has a unit and the config is SI:
/// what converted it to Ω (a bare number is Ω itself); for the errors that say so.
pub fn omega0_of_unit(cfg: &Config, text: &str) -> Option<f64> {
    let with_unit = autobal::units::parse_speed("--omega-max", text).is_ok_and(|s| s.unit.rad_s().is_some());
    cfg.model.scale.map(|s| s.omega0).filter(|_| with_unit)
}

/// The speed axis of the linear commands: `--omega-max` (a speed with its unit, or `Ω`), else
/// the config's `analysis.omega_max`, else automatic: up to 1.3 times the highest critical
/// speed and 1.25 times the top of the operating speed ([`autobal::reports::speed_axis_max`]).
pub fn omega_max(cfg: &Config, arg: Option<&str>) -> Result<f64> {
    let w = match arg {
        Some(t) => speed_arg(cfg, "--omega-max", t)?,
        None => cfg.analysis.speed_axis_max(autobal::reports::default_omega_max(&cfg.model)),
    };
    if !(w > 0.0 && w.is_finite()) {
        anyhow::bail!("--omega-max: must be a positive number, got {w}");
    }
    Ok(w)
}

pub fn campbell_grid(w: f64, points: usize) -> Vec<f64> {
    autobal::reports::campbell_speeds(w, points)
}

/// `ν` as the table prints it: 5 decimals, or 4 significant digits where those would show a
/// resolved `ν` (one with a log decrement) as 0.00000 beside its large log decrement (a nearly
/// real pair, e.g. two balls' drag modes near where they meet).
fn nu_text(nu: f64, resolved: bool) -> String {
    if resolved && nu != 0.0 && nu.abs() < 5e-6 {
        format!("{nu:.3e}")
    } else {
        format!("{nu:.5}")
    }
}

pub fn campbell_table(cfg: &Config, c: &Campbell) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(
        s,
        "Campbell diagram: eigenvalues λ = σ + iν in rotating axes (Im ≥ 0 shown; log dec = −2πσ/|ν| per rotating-axes cycle), fixed-axes whirl frequency"
    );
    let n = c.omega.len();
    let mut at = vec![0, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)];
    at.dedup();
    let w0 = cfg.model.scale.map(|sc| sc.omega0);
    if let Some(w0) = w0 {
        let _ = writeln!(s, "frequencies in Hz and rpm (cycles per minute) with ω0 = {w0:.4} rad/s; ν, σ and fixed freq also in units of ω0");
    }
    for k in at.into_iter().filter(|&k| k < n) {
        match w0 {
            Some(_) => {
                let _ = writeln!(s, "\nspeed {}", speed_text(cfg, c.omega[k]));
                let _ = writeln!(
                    s,
                    "  {:>10} {:>10} {:>10} {:>12} {:>11} {:>11}  {:<12} {:<9}",
                    "ν (ω0)", "σ (ω0)", "log dec", "fixed (ω0)", "fixed Hz", "fixed rpm", "group", "whirl"
                );
            }
            None => {
                let _ = writeln!(s, "\nΩ = {:.4}", c.omega[k]);
                let _ = writeln!(s, "  {:>10} {:>10} {:>10} {:>12}  {:<12} {:<9}", "ν", "σ", "log dec", "fixed freq", "group", "whirl");
            }
        }
        let mut modes: Vec<_> = c.lines.iter().map(|l| l.modes[k]).filter(|m| m.im >= 0.0).collect();
        modes.sort_by(|a, b| a.im.total_cmp(&b.im));
        for m in modes {
            let si = w0.map_or(String::new(), |w0| {
                let hz = m.fixed_frequency * w0 / (2.0 * std::f64::consts::PI);
                format!(" {:>11.3} {:>11.1}", hz, 60.0 * hz)
            });
            let _ = writeln!(
                s,
                "  {:>10} {:>10.5} {:>10} {:>12.5}{si}  {:<12} {:<9}",
                nu_text(m.im, m.log_decrement.is_some()),
                m.re,
                m.log_decrement.map_or("—".into(), |d| format!("{d:.4}")),
                m.fixed_frequency,
                format!("{:?}", m.group).to_lowercase(),
                format!("{:?}", m.whirl).to_lowercase()
            );
        }
    }
    s
}

/// Which figure `autobal campbell --svg PREFIX` draws: `Fixed`, one natural-frequency curve per
/// mode in fixed axes (PREFIX.svg); `Components`, rotating axes and the two whirl components of
/// each mode (PREFIX_rotating.svg and PREFIX_fixed.svg). (No docs on the variants: clap would
/// switch the whole `--help` to its long layout.)
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CampbellView {
    Fixed,
    Components,
}

/// The files `--svg PREFIX` writes for a view (a PREFIX ending in `.svg` is the fixed view's file).
pub fn campbell_svg_paths(prefix: &std::path::Path, view: CampbellView) -> Vec<std::path::PathBuf> {
    let p = prefix.display().to_string();
    match view {
        CampbellView::Fixed if p.to_ascii_lowercase().ends_with(".svg") => vec![prefix.to_path_buf()],
        CampbellView::Fixed => vec![format!("{p}.svg").into()],
        CampbellView::Components => ["rotating", "fixed"].iter().map(|s| format!("{p}_{s}.svg").into()).collect(),
    }
}

/// `--harmonics`: each between 1 and 20, sorted, without repeats.
pub fn check_harmonics(h: &[u32]) -> Result<Vec<u32>> {
    if h.is_empty() {
        anyhow::bail!("--harmonics: give at least one harmonic, e.g. 1 or 1,2");
    }
    if let Some(bad) = h.iter().find(|&&x| !(1..=20).contains(&x)) {
        anyhow::bail!("--harmonics: each must lie between 1 and 20, got {bad}");
    }
    let mut v = h.to_vec();
    v.sort_unstable();
    v.dedup();
    Ok(v)
}

fn whirl_name(w: Whirl) -> &'static str {
    match w {
        Whirl::Forward => "forward",
        Whirl::Backward => "backward",
        Whirl::None => "none",
    }
}

/// The mark of an overdamped crossing of `ν = 0` ([`autobal::spatial::campbell::CriticalSpeed::overdamped`]),
/// under its entry in the tables of both routes.
pub const OVERDAMPED: &str = "overdamped, no resonance (see the note)";

/// What an overdamped crossing is, once under the tables' list of crossings where one is.
pub const OVERDAMPED_NOTE: &str = "overdamped, no resonance: ν = 0 is reached, but the response to unbalance (each mode's part ∝ 1/|λ|) has a half-power band certainly wider than Ω_c/2.5 about the pair's stretch on the axis (|λ| below √2 times its smallest value there, over the stretch and beyond it), so the single-mode estimate of API 684's amplification factor is below 2.5: a critically damped mode, e.g. two balls' drag modes. An end whose band is not established (cut by the axis's end, or |λ| smaller beside it) is not marked";

/// A crossing's component in words: `whole motion` on the real axis (share 1: both components
/// at `Ω`), else the major (share ≥ ½) or minor component with its share.
pub fn component_text(share: f64) -> String {
    if share >= 1.0 {
        "whole motion".into()
    } else {
        format!("{} component (share {})", if share >= 0.5 { "major" } else { "minor" }, crate::num::fmt(share, 3))
    }
}

/// The fixed-axes view as text: the critical speeds (crossings with `h×Ω`) and, at the table's
/// speeds, each mode's natural frequency, whirl and log decrement (`δ = −2π σ/|f|` per
/// fixed-axes cycle).
pub fn fixed_table(cfg: &Config, f: &FixedCampbell, at: &[f64]) -> String {
    let mut s = String::new();
    let w0 = cfg.model.scale.map(|sc| sc.omega0);
    let hz = |x: f64| w0.map_or(String::new(), |w0| format!(" ({} Hz)", crate::num::fmt(x * w0 / (2.0 * std::f64::consts::PI), 5)));
    let hs: Vec<String> = f.harmonics.iter().map(|h| format!("{h}×")).collect();
    if f.harmonics.is_empty() {
        // Ctrl-C during the search (campbell_run)
        let _ = writeln!(s, "\ncritical speeds: not given (the search was interrupted)");
    } else {
        let _ = writeln!(s, "\ncritical speeds (a mode's natural frequency in fixed axes crosses {}):", hs.join(", "));
    }
    if f.critical_speeds.is_empty() && !f.harmonics.is_empty() {
        let _ = writeln!(s, "  none up to {}", speed_text(cfg, f.omega.last().copied().unwrap_or(0.0)));
    }
    for (j, k) in f.critical_speeds.iter().enumerate() {
        let _ = writeln!(
            s,
            "  {:>2}. {}  mode {}, {}, {}×, frequency {}{}, {}",
            j + 1,
            speed_text(cfg, k.omega),
            k.mode,
            whirl_name(k.whirl),
            k.harmonic,
            crate::num::fmt(k.frequency, 6),
            hz(k.frequency),
            component_text(k.share)
        );
        if k.overdamped {
            let _ = writeln!(s, "      {OVERDAMPED}");
        }
    }
    if f.critical_speeds.iter().any(|k| k.overdamped) {
        let _ = writeln!(s, "  note: {OVERDAMPED_NOTE}");
    }
    let _ = writeln!(s, "\nmodes in fixed axes (one continuous curve per mode; log dec per fixed-axes cycle):");
    for &w in at {
        let Some(k) = f.omega.iter().position(|&x| x == w) else { continue };
        let _ = writeln!(s, "speed {}", speed_text(cfg, w));
        for cv in &f.curves {
            let p = &cv.points[k];
            let _ = writeln!(
                s,
                "  mode {:>2}: frequency {:>10}{}  {:<8}  log dec {}",
                cv.mode,
                crate::num::fmt(p.frequency, 6),
                hz(p.frequency),
                whirl_name(p.whirl),
                p.log_decrement.map_or("—".into(), |d| format!("{d:.4}"))
            );
        }
    }
    s
}

/// The fixed-axes view as its JSON's type ([`autobal::reports::campbell_fixed`], shared with Python).
pub fn fixed_json(cfg: &Config, f: &FixedCampbell) -> autobal::reports::FixedReport {
    autobal::reports::campbell_fixed(&cfg.model, f)
}

pub fn campbell_of(cfg: &Config, w: f64, points: usize, balls: Balls) -> Result<Campbell> {
    Ok(campbell(&cfg.model, &campbell_grid(w, points), balls)?)
}

/// Largest number of speeds kept for the figures of `autobal campbell`.
pub const PLOT_SPEEDS: usize = 2000;

/// `autobal campbell` on the 12-state model, streamed: the table keeps its five speeds and
/// the figures a decimated copy (at most [`PLOT_SPEEDS`] speeds). With `json` and more speeds
/// than the figures keep, JSON lines go to one temporary file per tracked line as the speeds
/// are computed (joined by [`CampbellRun::write_json`]); up to [`PLOT_SPEEDS`] speeds the
/// figures' copy holds every speed and the JSON is written from it (no temporary files: the
/// same bytes). Memory does not grow with `points`. Ctrl-C (or a budget) on `control` ends it
/// at the last speed computed, which is kept.
pub fn campbell_run(
    cfg: &Config,
    w: f64,
    points: usize,
    balls: Balls,
    json: bool,
    harmonics: &[u32],
    control: &autobal::control::Control,
) -> Result<CampbellRun> {
    campbell_run_with(cfg, w, points, balls, json, harmonics, control, PLOT_SPEEDS)
}

/// [`campbell_run`], the JSON streamed to temporary files from `spill_above` speeds on (a test
/// sets it low to compare both ways).
#[allow(clippy::too_many_arguments)]
fn campbell_run_with(
    cfg: &Config,
    w: f64,
    points: usize,
    balls: Balls,
    json: bool,
    harmonics: &[u32],
    control: &autobal::control::Control,
    spill_above: usize,
) -> Result<CampbellRun> {
    use anyhow::Context;
    use std::io::Write as _;
    let n = points.max(3);
    let speed = |k: usize| w * (k as f64 + 0.5) / n as f64;
    let stride = n.div_ceil(PLOT_SPEEDS);
    let table_at = [0, n / 4, n / 2, 3 * n / 4, n - 1];
    let mut plot = Campbell { omega: vec![], lines: vec![] };
    let mut table = Campbell { omega: vec![], lines: vec![] };
    // every speed is in the figures' copy (stride 1): the JSON is written from it at the end
    let from_plot = json && stride == 1 && n <= spill_above;
    let dir = (json && !from_plot).then(|| {
        std::env::temp_dir().join(format!(
            "autobal-campbell-{}-{}",
            std::process::id(),
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
        ))
    });
    if let Some(dir) = &dir {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    // from here the folder is removed when the run is dropped, whatever happens
    let mut run = CampbellRun {
        cfg: cfg.clone(),
        omega_max: w,
        n,
        done: 0,
        complete: false,
        balls,
        plot: Campbell { omega: vec![], lines: vec![] },
        table: Campbell { omega: vec![], lines: vec![] },
        fixed: None,
        dir,
        from_plot,
        lines: 0,
        search_stopped: false,
    };
    let mut files: Vec<std::io::BufWriter<std::fs::File>> = vec![];
    let mut io_err: Option<anyhow::Error> = None;
    let keep = |c: &mut Campbell, wk: f64, modes: &[autobal::spatial::stability::Mode]| {
        if c.lines.is_empty() {
            c.lines = modes.iter().map(|_| autobal::spatial::stability::CampbellLine { modes: vec![] }).collect();
        }
        c.omega.push(wk);
        for (l, m) in c.lines.iter_mut().zip(modes) {
            l.modes.push(*m);
        }
    };
    let result = campbell_stream(&cfg.model, (0..n).map(speed), balls, &mut |k, modes| {
        // Ctrl-C: this speed is the last one computed and kept (figures and table end there)
        let stop = control.should_stop().is_some();
        // every reported number finite (as for the other commands), checked as it streams
        if let Err(e) = autobal::limits::check_finite(&format!("campbell.speeds[{k}]"), &modes) {
            io_err = Some(e.into());
            return false;
        }
        if let Some(dir) = &run.dir {
            if files.is_empty() {
                for i in 0..modes.len() {
                    match std::fs::File::create(dir.join(format!("{i}.json"))) {
                        Ok(f) => files.push(std::io::BufWriter::new(f)),
                        Err(e) => {
                            io_err = Some(e.into());
                            return false;
                        }
                    }
                }
            }
            for (f, m) in files.iter_mut().zip(modes) {
                // the typed mode written straight to the file (no JSON value tree per mode)
                let sep: &[u8] = if k == 0 { b"" } else { b",\n" };
                let mut write = || -> Result<()> {
                    f.write_all(sep)?;
                    crate::campbell::write_mode_json(&mut *f, &autobal::reports::mode_report(&cfg.model, m))?;
                    Ok(())
                };
                if let Err(e) = write() {
                    io_err = Some(e);
                    return false;
                }
            }
        }
        // the figures' speeds include the table's (the fixed-axes table reads the curves there)
        if k % stride == 0 || k + 1 == n || stop || table_at.contains(&k) {
            keep(&mut plot, speed(k), modes);
        }
        if (table_at.contains(&k) || stop) && table.omega.last() != Some(&speed(k)) {
            keep(&mut table, speed(k), modes);
        }
        !stop
    });
    if let Some(e) = io_err {
        return Err(e);
    }
    // an interrupted run keeps what it computed: the speeds done, the figures and the table up
    // to the last of them
    let stats = result?;
    run.lines = if from_plot { plot.lines.len() } else { files.len() };
    for f in files {
        f.into_inner().map_err(|e| e.into_error())?;
    }
    // the fixed-axes curves and the critical speeds, on the figures' speeds
    // Ctrl-C (or the budget) during the search: the curves kept without the critical speeds,
    // and the run marked stopped (exit 2, as a stop during the scan)
    let fixed = match fixed_axes_with(&cfg.model, &plot, balls, harmonics, control) {
        Ok(f) => f,
        Err(_) if control.should_stop().is_some() => {
            run.search_stopped = true;
            // no harmonics: the table says the search was stopped
            fixed_axes(&cfg.model, &plot, balls, &[])?
        }
        Err(e) => return Err(e.into()),
    };
    autobal::limits::check_finite("campbell.critical_speeds", &fixed.critical_speeds)?;
    run.done = stats.speeds;
    run.complete = stats.complete && !run.search_stopped;
    run.plot = plot;
    run.table = table;
    run.fixed = Some(fixed);
    Ok(run)
}

/// A Campbell diagram of the 12-state model computed by [`campbell_run`]: the speeds done, the
/// figures' and the table's speeds, the fixed-axes curves, and the JSON lines in a temporary
/// folder (removed when the run is dropped).
pub struct CampbellRun {
    cfg: Config,
    omega_max: f64,
    n: usize,
    done: usize,
    complete: bool,
    balls: Balls,
    plot: Campbell,
    table: Campbell,
    fixed: Option<FixedCampbell>,
    dir: Option<std::path::PathBuf>,
    /// The JSON's lines are written from `plot` (which holds every speed computed).
    from_plot: bool,
    lines: usize,
    /// Stopped during the search for the critical speeds (none given).
    search_stopped: bool,
}

impl Drop for CampbellRun {
    fn drop(&mut self) {
        if let Some(dir) = &self.dir {
            let _ = std::fs::remove_dir_all(dir);
        }
    }
}

impl CampbellRun {
    fn speed(&self, k: usize) -> f64 {
        self.omega_max * (k as f64 + 0.5) / self.n as f64
    }

    fn fixed(&self) -> &FixedCampbell {
        self.fixed.as_ref().expect("a finished run has its fixed-axes curves")
    }

    /// The JSON (as `autobal::reports::campbell_of` and `campbell_fixed` write it), streamed
    /// from the temporary files: `omega` (and in SI), `lines`, the fixed-axes keys, `complete`.
    pub fn write_json(&self, out: &mut dyn std::io::Write) -> Result<()> {
        use std::io::Write as _;
        if self.dir.is_none() && !self.from_plot {
            anyhow::bail!("campbell: run without its JSON (json = false)");
        }
        let mut out = std::io::BufWriter::new(out);
        let done = self.done;
        write!(out, "{{\n\"omega\": [")?;
        for k in 0..done {
            write!(out, "{}{}", if k == 0 { "" } else { ", " }, serde_json::to_string(&self.speed(k))?)?;
        }
        write!(out, "]")?;
        if let Some(sc) = self.cfg.model.scale {
            // the speeds in SI, as autobal::reports::campbell_of writes them
            for (key, k) in [("omega_rad_s", sc.omega0), ("omega_rpm", sc.omega0 * 30.0 / std::f64::consts::PI)] {
                write!(out, ",\n\"{key}\": [")?;
                for j in 0..done {
                    write!(out, "{}{}", if j == 0 { "" } else { ", " }, serde_json::to_string(&(self.speed(j) * k))?)?;
                }
                write!(out, "]")?;
            }
        }
        write!(out, ",\n\"lines\": [\n")?;
        for i in 0..self.lines {
            writeln!(out, "{}{{\"modes\": [", if i == 0 { "" } else { ",\n" })?;
            match &self.dir {
                Some(dir) => {
                    let mut r = std::fs::File::open(dir.join(format!("{i}.json")))?;
                    std::io::copy(&mut r, &mut out)?;
                }
                // as the streamed files hold them: one mode a speed, ",\n" between
                None => {
                    for (k, m) in self.plot.lines[i].modes.iter().enumerate() {
                        out.write_all(if k == 0 { b"" } else { b",\n" })?;
                        crate::campbell::write_mode_json(&mut out, &autobal::reports::mode_report(&self.cfg.model, m))?;
                    }
                }
            }
            write!(out, "\n]}}")?;
        }
        write!(out, "\n]")?;
        // the fixed-axes view's fields, in the order of FixedReport (that of their names)
        let f = fixed_json(&self.cfg, self.fixed());
        write!(out, ",\n\"critical_speeds\": ")?;
        serde_json::to_writer(&mut out, &f.critical_speeds)?;
        write!(out, ",\n\"fixed_axes_modes\": ")?;
        crate::campbell::write_fixed_modes_json(&mut out, &f.fixed_axes_modes)?;
        write!(out, ",\n\"harmonics\": ")?;
        serde_json::to_writer(&mut out, &f.harmonics)?;
        writeln!(out, ",\n\"complete\": {}\n}}", self.complete)?;
        out.flush()?;
        Ok(())
    }

    /// The table: at five speeds, each mode in rotating and fixed axes, then the fixed-axes
    /// view (empty when no speed was computed).
    pub fn table(&self) -> String {
        if self.done == 0 {
            return String::new();
        }
        campbell_table(&self.cfg, &self.table) + &fixed_table(&self.cfg, self.fixed(), &self.table.omega)
    }

    /// The figures: `campbell_modes` (fixed axes, one curve per mode: `--view fixed`),
    /// `campbell_fixed` and `campbell_rotating` (`--view components`).
    pub fn figures(&self) -> Vec<crate::command::Figure> {
        use crate::command::Figure;
        let (mut rot, mut fx) = crate::figures::campbell_plots(&self.cfg.model, &self.plot, &self.fixed().line_modes);
        let mut modes = crate::figures::campbell_fixed_plot(&self.cfg.model, self.fixed());
        // the operating speed marked on each figure's own axis, as in the report (walk 27)
        let op = self.cfg.analysis.operating_speed;
        for p in [&mut rot, &mut fx] {
            p.vlines.extend(crate::figures::operating_vlines(op, crate::figures::SpeedUnit::of(&self.cfg.model).factor));
        }
        modes.vlines.extend(crate::figures::operating_vlines(op, crate::figures::fixed_axes_of(&self.cfg.model).kx));
        vec![Figure::new("campbell_modes", modes), Figure::new("campbell_fixed", fx), Figure::new("campbell_rotating", rot)]
    }

    /// Why the run is incomplete, or `None`.
    pub fn stopped(&self) -> Option<String> {
        (!self.complete).then(|| {
            if self.search_stopped && self.done == self.n {
                return format!(
                    "interrupted: all {} speeds computed, the search for critical speeds stopped (none given); what was computed is written",
                    self.n
                );
            }
            format!(
                "interrupted: {} of {} speeds computed (up to Ω = {}); what was computed is written",
                self.done,
                self.n,
                crate::num::fmt(self.speed(self.done.saturating_sub(1)), 4)
            )
        })
    }

    /// Balls free or locked.
    pub fn balls(&self) -> Balls {
        self.balls
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The JSON written from the figures' copy of the speeds (up to [`PLOT_SPEEDS`] speeds, no
    /// temporary files) is byte for byte the JSON streamed through the temporary files, for a
    /// complete run and for one stopped at its first speed; a run without JSON has none.
    #[test]
    fn the_json_from_the_kept_speeds_equals_the_streamed_json() {
        let cfg = crate::config::build(&crate::config::parse_text(crate::config::DEFAULT_CONFIG, "d").unwrap(), "d").unwrap();
        let stopped = autobal::control::Control::new();
        stopped.cancel();
        for (control, points) in [(autobal::control::Control::none(), 40), (stopped, 30)] {
            let json = |spill_above: usize| {
                let run = campbell_run_with(&cfg, 3.0, points, Balls::Free, true, &[1, 2], &control, spill_above).unwrap();
                assert_eq!(run.dir.is_some(), spill_above < points, "temporary files only when spilled");
                let mut text = vec![];
                run.write_json(&mut text).unwrap();
                String::from_utf8(text).unwrap()
            };
            let (kept, streamed) = (json(PLOT_SPEEDS), json(0));
            assert_eq!(kept, streamed);
            let v: serde_json::Value = serde_json::from_str(&kept).unwrap();
            let done = v["omega"].as_array().unwrap().len();
            assert_eq!(done, if points == 40 { 40 } else { 1 });
            assert_eq!(v["lines"].as_array().unwrap().len(), 12);
            assert!(v["lines"].as_array().unwrap().iter().all(|l| l["modes"].as_array().unwrap().len() == done));
        }
        let none = campbell_run(&cfg, 3.0, 40, Balls::Free, false, &[1], &autobal::control::Control::none()).unwrap();
        assert!(none.write_json(&mut vec![]).is_err());
    }
}
