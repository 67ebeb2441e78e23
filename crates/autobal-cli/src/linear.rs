//! `autobal stability` and `autobal campbell`: exact linear stability of the balanced state.

use crate::config::Config;
use anyhow::Result;
use autobal::spatial::comparison::fmt_ranges_in;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::stability::{campbell, campbell_stream, Campbell};
use serde_json::Value;
use std::fmt::Write;

pub use autobal::spatial::comparison::{compare, Comparison};

pub fn stability_json(cfg: &Config, c: &Comparison, balls: Balls) -> Value {
    autobal::reports::stability(&cfg.model, c, balls)
}

pub fn stability_table(cfg: &Config, c: &Comparison, balls: Balls) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(
        s,
        "exact linear stability of the balanced state, balls {} ({} states), 0 < Ω ≤ {}",
        if balls == Balls::Free { "free" } else { "locked" },
        if balls == Balls::Free { 12 } else { 8 },
        crate::num::fmt(c.omega_max, 7)
    );
    // computed over (0, Ω_max] only: a range reaching Ω_max ends there as far as is known
    let w = Some(c.omega_max);
    let rule = if balls == Balls::Free { "all Re λ < −1e-11" } else { "all Re λ ≤ 1e-11" };
    let _ = writeln!(s, "  stable ({rule}): {}", fmt_ranges_in(&c.exact.stable_ranges, 6, w));
    let _ = writeln!(s, "  necessary (003, eqs (1)-(3)):   {}", fmt_ranges_in(&c.necessary, 6, w));
    let _ = writeln!(s, "  difference: {}", c.difference());
    if let Some(sc) = cfg.model.scale {
        let k = sc.omega0 * 30.0 / std::f64::consts::PI;
        let _ = writeln!(s, "  stable in rpm: {}", fmt_ranges_in(&crate::output::scale_ranges(&c.exact.stable_ranges, k), 0, Some(c.omega_max * k)));
    }
    let worst = c.exact.max_real_part.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
    let best = c.exact.max_real_part.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
    let _ = writeln!(s, "  max Re λ over the grid: from {best:.4e} to {worst:.4e}");
    s
}

/// The speed axis of the linear commands: `--omega-max`, else the config's, else automatic.
pub fn omega_max(cfg: &Config, arg: Option<f64>) -> Result<f64> {
    let w = arg.or(cfg.analysis.omega_max).unwrap_or_else(|| autobal::reports::default_omega_max(&cfg.model));
    if !(w > 0.0 && w.is_finite()) {
        anyhow::bail!("--omega-max: must be a positive number, got {w}");
    }
    Ok(w)
}

pub fn campbell_grid(w: f64, points: usize) -> Vec<f64> {
    autobal::reports::campbell_speeds(w, points)
}

pub fn campbell_table(cfg: &Config, c: &Campbell) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(s, "Campbell diagram: eigenvalues λ = σ + iν in rotating axes (Im ≥ 0 shown), fixed-axes whirl frequency");
    let n = c.omega.len();
    let mut at = vec![0, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)];
    at.dedup();
    for k in at.into_iter().filter(|&k| k < n) {
        let _ = writeln!(s, "\nΩ = {:.4}", c.omega[k]);
        let _ = writeln!(s, "  {:>10} {:>10} {:>10} {:>12}  {:<12} {:<9}", "ν", "σ", "log dec", "fixed freq", "group", "whirl");
        let mut modes: Vec<_> = c.lines.iter().map(|l| l.modes[k]).filter(|m| m.im >= 0.0).collect();
        modes.sort_by(|a, b| a.im.total_cmp(&b.im));
        for m in modes {
            let _ = writeln!(
                s,
                "  {:>10.5} {:>10.5} {:>10} {:>12.5}  {:<12} {:<9}",
                m.im,
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

pub fn campbell_of(cfg: &Config, w: f64, points: usize, balls: Balls) -> Result<Campbell> {
    Ok(campbell(&cfg.model, &campbell_grid(w, points), balls)?)
}

/// Largest number of speeds kept for the figures of `autobal campbell`.
pub const PLOT_SPEEDS: usize = 2000;

/// `autobal campbell`, streamed: JSON lines go to one temporary file per tracked line as the
/// speeds are computed and are joined on standard output at the end; the table keeps its five
/// speeds and the figures a decimated copy (at most [`PLOT_SPEEDS`] speeds). Memory does not
/// grow with `points`.
pub fn run_campbell(cfg: &Config, w: f64, points: usize, balls: Balls, json: bool, svg: Option<&std::path::Path>) -> Result<()> {
    use anyhow::Context;
    use std::io::Write as _;
    let n = points.max(3);
    let speed = |k: usize| w * (k as f64 + 0.5) / n as f64;
    let stride = n.div_ceil(PLOT_SPEEDS);
    let table_at = [0, n / 4, n / 2, 3 * n / 4, n - 1];
    let mut plot = Campbell { omega: vec![], lines: vec![] };
    let mut table = Campbell { omega: vec![], lines: vec![] };
    let dir = std::env::temp_dir().join(format!(
        "autobal-campbell-{}-{}",
        std::process::id(),
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
    ));
    let mut files: Vec<std::io::BufWriter<std::fs::File>> = vec![];
    if json {
        std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
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
        let stop = crate::map::INTERRUPTED.load(std::sync::atomic::Ordering::Relaxed);
        // every reported number finite (as for the other commands), checked as it streams
        if let Err(e) = autobal::limits::check_finite(&format!("campbell.speeds[{k}]"), &modes) {
            io_err = Some(e.into());
            return false;
        }
        if json {
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
                let text = serde_json::to_string(m).unwrap_or_default();
                if let Err(e) = write!(f, "{}{text}", if k == 0 { "" } else { ",\n" }) {
                    io_err = Some(e.into());
                    return false;
                }
            }
        }
        if k % stride == 0 || k + 1 == n || stop {
            keep(&mut plot, speed(k), modes);
        }
        if (table_at.contains(&k) || stop) && table.omega.last() != Some(&speed(k)) {
            keep(&mut table, speed(k), modes);
        }
        !stop
    });
    let finish = || -> Result<()> {
        if let Some(e) = io_err {
            return Err(e);
        }
        // an interrupted run writes what it computed: the speeds done, the figures and the
        // table up to the last of them
        let stats = result?;
        let done = stats.speeds;
        if let Some(prefix) = svg {
            let (rot, fixed) = crate::figures::campbell_plots(&cfg.model, &plot);
            for (suffix, p) in [("rotating", rot), ("fixed", fixed)] {
                let path = std::path::PathBuf::from(format!("{}_{suffix}.svg", prefix.display()));
                crate::outfile::write_atomic("--svg", &path, p.to_svg())?;
            }
        }
        let stdout = std::io::stdout();
        let mut out = std::io::BufWriter::new(stdout.lock());
        if json {
            write!(out, "{{\n\"omega\": [")?;
            for k in 0..done {
                write!(out, "{}{}", if k == 0 { "" } else { ", " }, serde_json::to_string(&speed(k))?)?;
            }
            write!(out, "],\n\"lines\": [\n")?;
            for (i, f) in files.into_iter().enumerate() {
                let f = f.into_inner().map_err(|e| e.into_error())?;
                drop(f);
                writeln!(out, "{}{{\"modes\": [", if i == 0 { "" } else { ",\n" })?;
                let mut r = std::fs::File::open(dir.join(format!("{i}.json")))?;
                std::io::copy(&mut r, &mut out)?;
                write!(out, "\n]}}")?;
            }
            writeln!(out, "\n],\n\"complete\": {}\n}}", stats.complete)?;
        } else if done > 0 {
            write!(out, "{}", campbell_table(cfg, &table))?;
        }
        out.flush()?;
        if !stats.complete {
            anyhow::bail!(
                "interrupted: {done} of {n} speeds computed (up to Ω = {}); what was computed is written",
                crate::num::fmt(speed(done.saturating_sub(1)), 4)
            );
        }
        Ok(())
    };
    let r = finish();
    if json {
        let _ = std::fs::remove_dir_all(&dir);
    }
    r
}
