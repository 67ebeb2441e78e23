//! `autobal stability` and `autobal campbell`: exact linear stability of the balanced state.

use crate::config::Config;
use crate::figures::omega_limit;
use crate::output::{fmt_ranges, ranges_value};
use crate::plot::{Plot, Series, PALETTE};
use anyhow::Result;
use autobal::spatial::critical_speeds::critical_speeds;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::SpatialModel;
use autobal::spatial::ranges::{autobalancing_ranges, SpeedRange};
use autobal::spatial::stability::{campbell, stability_ranges, Campbell, StabilityRanges, Whirl};
use serde_json::{json, Value};
use std::fmt::Write;

/// Clip ranges to `[0, w]` as closed pairs.
fn clip(r: &[SpeedRange], w: f64) -> Vec<(f64, f64)> {
    r.iter().filter(|x| x.lo < w).map(|x| (x.lo, x.hi.map_or(w, |h| h.min(w)))).collect()
}

/// `a \ b` for sorted disjoint interval lists.
fn minus(a: &[(f64, f64)], b: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out = vec![];
    for &(lo, hi) in a {
        let mut cur = lo;
        for &(blo, bhi) in b {
            if bhi <= cur || blo >= hi {
                continue;
            }
            if blo > cur {
                out.push((cur, blo));
            }
            cur = cur.max(bhi);
        }
        if cur < hi {
            out.push((cur, hi));
        }
    }
    out.into_iter().filter(|(l, h)| h - l > 1e-9).collect()
}

fn to_ranges(v: &[(f64, f64)], w: f64) -> Vec<SpeedRange> {
    v.iter().map(|&(lo, hi)| SpeedRange { lo, hi: if hi >= w { None } else { Some(hi) } }).collect()
}

/// Exact stability against 003's necessary conditions over `(0, w]`.
pub struct Comparison {
    pub exact: StabilityRanges,
    pub necessary: Vec<SpeedRange>,
    /// Where 003's condition holds but the balanced state is unstable.
    pub necessary_not_stable: Vec<SpeedRange>,
    /// Where the balanced state is stable but 003's condition fails.
    pub stable_not_necessary: Vec<SpeedRange>,
    pub omega_max: f64,
}

pub fn compare(model: &SpatialModel, omega_max: f64, samples: usize, balls: Balls) -> Result<Comparison> {
    let exact = stability_ranges(model, omega_max, samples, balls, 1e-9)?;
    let nec = autobalancing_ranges(model).ranges;
    let (e, n) = (clip(&exact.stable_ranges, omega_max), clip(&nec, omega_max));
    Ok(Comparison {
        necessary: to_ranges(&n, omega_max),
        necessary_not_stable: to_ranges(&minus(&n, &e), omega_max),
        stable_not_necessary: to_ranges(&minus(&e, &n), omega_max),
        exact,
        omega_max,
    })
}

fn total(r: &[SpeedRange], w: f64) -> f64 {
    r.iter().map(|x| x.hi.unwrap_or(w) - x.lo).sum::<f64>() + 0.0 // + 0.0: an empty sum is −0
}

pub fn difference_sentence(c: &Comparison) -> String {
    let w = c.omega_max;
    match (c.necessary_not_stable.is_empty(), c.stable_not_necessary.is_empty()) {
        (true, true) => "the exact stability ranges coincide with 003's necessary ranges".into(),
        _ => format!(
            "003's condition holds but the balanced state is unstable on {} (total {:.4}); the balanced state is stable where 003's condition fails on {} (total {:.4})",
            fmt_ranges(&c.necessary_not_stable, 4),
            total(&c.necessary_not_stable, w),
            fmt_ranges(&c.stable_not_necessary, 4),
            total(&c.stable_not_necessary, w)
        ),
    }
}

pub fn stability_json(cfg: &Config, c: &Comparison, balls: Balls) -> Value {
    json!({
        "balls": if balls == Balls::Free { "free" } else { "locked" },
        "omega_max": c.omega_max,
        "stable_ranges": ranges_value(&c.exact.stable_ranges),
        "necessary_ranges": ranges_value(&c.necessary),
        "necessary_not_stable": ranges_value(&c.necessary_not_stable),
        "stable_not_necessary": ranges_value(&c.stable_not_necessary),
        "difference": difference_sentence(c),
        "max_real_part": c.exact.max_real_part.iter().map(|(w, a)| json!([w, a])).collect::<Vec<_>>(),
        "tolerance": c.exact.tolerance,
        "stability_threshold": autobal::spatial::stability::STABILITY_TOLERANCE,
        "anisotropy_used": cfg.model.anisotropy.used,
        "ball_coupling": cfg.model.balls,
    })
}

pub fn stability_table(cfg: &Config, c: &Comparison, balls: Balls) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(
        s,
        "exact linear stability of the balanced state, balls {} ({} states), 0 < Ω ≤ {}",
        if balls == Balls::Free { "free" } else { "locked" },
        if balls == Balls::Free { 12 } else { 8 },
        c.omega_max
    );
    let rule = if balls == Balls::Free { "all Re λ < −1e-11" } else { "all Re λ ≤ 1e-11" };
    let _ = writeln!(s, "  stable ({rule}): {}", fmt_ranges(&c.exact.stable_ranges, 6));
    let _ = writeln!(s, "  necessary (003, eqs (1)-(3)):   {}", fmt_ranges(&c.necessary, 6));
    let _ = writeln!(s, "  difference: {}", difference_sentence(c));
    if let Some(sc) = cfg.model.scale {
        let k = sc.omega0 * 30.0 / std::f64::consts::PI;
        let _ = writeln!(s, "  stable in rpm: {}", fmt_ranges(&crate::output::scale_ranges(&c.exact.stable_ranges, k), 0));
    }
    let worst = c.exact.max_real_part.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
    let best = c.exact.max_real_part.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
    let _ = writeln!(s, "  max Re λ over the grid: from {best:.4e} to {worst:.4e}");
    s
}

/// The speed axis of the linear commands: `--omega-max`, else the config's, else automatic.
pub fn omega_max(cfg: &Config, arg: Option<f64>) -> Result<f64> {
    let w = arg.or(cfg.analysis.omega_max).unwrap_or_else(|| omega_limit(&cfg.model, None));
    if !(w > 0.0 && w.is_finite()) {
        anyhow::bail!("--omega-max: must be a positive number, got {w}");
    }
    Ok(w)
}

pub fn campbell_grid(w: f64, points: usize) -> Vec<f64> {
    let n = points.max(3);
    (0..n).map(|i| w * (i as f64 + 0.5) / n as f64).collect()
}

pub fn campbell_json(c: &Campbell) -> Value {
    json!({ "omega": c.omega, "lines": c.lines })
}

pub fn campbell_table(cfg: &Config, c: &Campbell) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(s, "Campbell diagram: eigenvalues λ = σ + iν in rotating axes (Im ≥ 0 shown), fixed-axes whirl frequency");
    let n = c.omega.len();
    for &k in &[0, n / 4, n / 2, 3 * n / 4, n - 1] {
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

/// Campbell plots: rotating-frame frequencies and fixed-frame whirl frequencies with the 1×
/// line and the analytic critical speeds.
pub fn campbell_plots(model: &SpatialModel, c: &Campbell) -> (Plot, Plot) {
    let mut rot = vec![];
    let mut fixed = vec![];
    for (i, l) in c.lines.iter().enumerate() {
        let col = PALETTE[i % 7];
        let pts_r: Vec<(f64, f64)> = c.omega.iter().zip(&l.modes).map(|(&w, m)| (w, if m.im >= 0.0 { m.im } else { f64::NAN })).collect();
        let pts_f: Vec<(f64, f64)> =
            c.omega.iter().zip(&l.modes).map(|(&w, m)| (w, if m.im >= 0.0 && m.whirl != Whirl::None { m.fixed_frequency } else { f64::NAN })).collect();
        rot.push(Series::new("", pts_r, col));
        fixed.push(Series::new("", pts_f, col));
    }
    let w = *c.omega.last().unwrap_or(&1.0);
    fixed.push(Series::new("1× (synchronous)", vec![(0.0, 0.0), (w, w)], "#000000").dashed());
    let vlines: Vec<(f64, String)> =
        critical_speeds(model).speeds.iter().enumerate().map(|(i, k)| (k.omega, format!("K{}", i + 1))).collect();
    (
        Plot {
            title: "Campbell diagram, rotating axes".into(),
            x_label: "Ω".into(),
            y_label: "Im λ (rotating frame)".into(),
            series: rot,
            vlines: vlines.clone(),
            x_range: Some((0.0, w)),
            ..Default::default()
        },
        Plot {
            title: "Campbell diagram, fixed axes (forward > 0 > backward)".into(),
            x_label: "Ω".into(),
            y_label: "whirl frequency / ω0".into(),
            series: fixed,
            vlines,
            x_range: Some((0.0, w)),
            ..Default::default()
        },
    )
}

/// Margin plot along Ω with the exact and necessary ranges shaded.
pub fn margin_plot(c: &Comparison) -> Plot {
    use crate::plot::Shade;
    let pts = c.exact.max_real_part.clone();
    let mut shades: Vec<Shade> = c
        .exact
        .stable_ranges
        .iter()
        .map(|r| Shade { x: (r.lo, r.hi.unwrap_or(c.omega_max)), y: (None, Some(0.0)), color: "#009E73".into() })
        .collect();
    shades.extend(c.necessary.iter().map(|r| Shade { x: (r.lo, r.hi.unwrap_or(c.omega_max)), y: (Some(0.0), None), color: "#56B4E9".into() }));
    let lo = pts.iter().map(|p| p.1).fold(0.0, f64::min);
    let hi = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    let pad = 0.1 * (hi - lo).max(1e-6);
    Plot {
        title: "max Re λ: green = exactly stable, blue = 003 necessary".into(),
        x_label: "Ω".into(),
        y_label: "max Re λ".into(),
        series: vec![Series::new("max Re λ", pts, PALETTE[1])],
        shades,
        x_range: Some((0.0, c.omega_max)),
        y_range: Some((lo - pad, hi + pad)),
        ..Default::default()
    }
}

pub fn campbell_of(cfg: &Config, w: f64, points: usize, balls: Balls) -> Result<Campbell> {
    Ok(campbell(&cfg.model, &campbell_grid(w, points), balls)?)
}
