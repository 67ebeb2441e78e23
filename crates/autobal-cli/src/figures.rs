//! Figure builders shared by the commands and the report: speed axes, the papers' layouts,
//! Campbell diagrams and the stability margin along the speed.

use crate::linear::Comparison;
use crate::num::RPM_PER_RAD_S;
use crate::plot::{Plot, SecondAxis, Series, Shade, PALETTE};
use autobal::spatial::critical_speeds::critical_speeds;
use autobal::spatial::params::{identical_support_coefficients, SpatialModel};
use autobal::spatial::stability::{Campbell, Group, Whirl};

/// `n` evenly spaced values from `a` to `b`.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| a + (b - a) * i as f64 / (n - 1).max(1) as f64).collect()
}

/// The model moved on its supports to `l̄_L` (identical supports: stiffness and damping
/// coefficients from 000 eq (10)).
pub fn with_layout(base: &SpatialModel, l_left: f64) -> SpatialModel {
    let mut m = base.clone();
    let rho = base.rho_s.unwrap_or(0.4);
    let (p, c) = identical_support_coefficients(l_left, rho);
    m.p_alpha_sq = p;
    m.c_y_alpha = c;
    m.l_left = Some(l_left);
    m.damping.h_alpha = m.damping.h_x * p;
    m.damping.h_y_alpha = m.damping.h_x * c;
    m
}

/// Speed axis limit: configured, else 1.3 × the highest critical speed or antiresonance.
pub fn omega_limit(m: &SpatialModel, configured: Option<f64>) -> f64 {
    configured.unwrap_or_else(|| autobal::reports::default_omega_max(m))
}

/// How speeds of a model are shown: ω in rad/s (rpm on a second axis) for a dimensional
/// model, Ω = ω/ω0 otherwise.
#[derive(Debug, Clone)]
pub struct SpeedUnit {
    /// Multiplier from Ω to the axis unit.
    pub factor: f64,
    /// Axis title of a speed.
    pub label: String,
    /// Axis title of a frequency in the same unit.
    pub freq_label: String,
    pub second: Option<SecondAxis>,
}

impl SpeedUnit {
    pub fn of(m: &SpatialModel) -> Self {
        match m.scale {
            Some(sc) => SpeedUnit {
                factor: sc.omega0,
                label: "ω (rad/s)".into(),
                freq_label: "whirl frequency (rad/s)".into(),
                second: Some(SecondAxis { factor: RPM_PER_RAD_S, label: "n (rpm)".into() }),
            },
            None => SpeedUnit { factor: 1.0, label: "Ω = ω/ω0".into(), freq_label: "whirl frequency / ω0".into(), second: None },
        }
    }
}

/// Colours for many curves: the palette without black and grey, then more distinct ones, ordered
/// so that the first nine differ in hue (no two greens or two light blues among them).
pub fn curve_color(i: usize) -> &'static str {
    const MORE: [&str; 12] =
        ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#882255", "#332288", "#999933", "#56B4E9", "#AA4499", "#44AA99", "#117733"];
    MORE[i % MORE.len()]
}

fn group_name(g: Group) -> &'static str {
    match g {
        Group::Translation => "translation",
        Group::Tilt => "tilt",
        Group::Balls => "balls",
    }
}

/// Share of a circular component below which it is not drawn in fixed axes.
const COMPONENT_SHARE: f64 = 0.1;

/// Campbell diagrams (rotating axes, fixed axes) with one colour and legend entry per tracked
/// mode ("mode 3: tilt, forward", from the dominant motion and whirl over the line), the 1×
/// line and the analytic critical speeds as markers whose labels never overlap; speeds in the
/// model's unit ([`SpeedUnit`]). In fixed axes a mode of rotating-frame frequency `ν` whirls
/// at `Ω + ν` and at `Ω − ν` (shares from its eigenvector): each component is its own
/// continuous curve wherever its share is at least 10 %, so no curve jumps between the two
/// where an elliptic mode changes its dominant direction.
pub fn campbell_plots(model: &SpatialModel, c: &Campbell) -> (Plot, Plot) {
    let u = SpeedUnit::of(model);
    let k = u.factor;
    let mut rot = vec![];
    let mut fixed = vec![];
    let mut shown = 0;
    for l in &c.lines {
        let upper: Vec<_> = l.modes.iter().filter(|m| m.im >= 0.0).collect();
        if upper.is_empty() {
            continue; // the conjugate of a line shown
        }
        let count = |g: Group| upper.iter().filter(|m| m.group == g).count();
        let g = [Group::Translation, Group::Tilt, Group::Balls].into_iter().max_by_key(|&g| count(g)).unwrap_or(Group::Translation);
        let fwd = upper.iter().filter(|m| m.whirl == Whirl::Forward).count();
        let bwd = upper.iter().filter(|m| m.whirl == Whirl::Backward).count();
        let whirl = if fwd >= bwd { "forward" } else { "backward" };
        let pts_r: Vec<(f64, f64)> = c.omega.iter().zip(&l.modes).map(|(&w, m)| (k * w, if m.im >= 0.0 { k * m.im } else { f64::NAN })).collect();
        let start = |p: &[(f64, f64)]| p.iter().find(|q| q.1.is_finite()).map(|q| q.1);
        if start(&pts_r).is_none() {
            continue;
        }
        // the fixed-axes components Ω + ν (share s) and Ω − ν (share 1 − s)
        let component = |sign: f64| -> Vec<(f64, f64)> {
            c.omega
                .iter()
                .zip(&l.modes)
                .map(|(&w, m)| {
                    let share = if sign > 0.0 { m.forward_share } else { 1.0 - m.forward_share };
                    let drawn = m.im >= 0.0 && m.whirl != Whirl::None && share >= COMPONENT_SHARE;
                    (k * w, if drawn { k * (w + sign * m.im) } else { f64::NAN })
                })
                .collect()
        };
        shown += 1;
        let col = curve_color(shown - 1);
        let name = format!("mode {shown}: {}, {whirl}, from {}", group_name(g), crate::num::fmt(start(&pts_r).unwrap_or(f64::NAN), 3));
        rot.push(Series::new(name.clone(), pts_r, col));
        // one legend entry per mode, toggling both components: Ω + ν solid, Ω − ν dashed
        let mut labelled = false;
        for sign in [1.0, -1.0] {
            let pts = component(sign);
            if start(&pts).is_some() {
                let label = if labelled { String::new() } else { name.clone() };
                labelled = true;
                let se = Series::new(label, pts, col).group(format!("mode {shown}"));
                fixed.push(if sign < 0.0 { se.dashed() } else { se });
            }
        }
    }
    let w = *c.omega.last().unwrap_or(&1.0);
    fixed.push(Series::new("1× (synchronous)", vec![(0.0, 0.0), (k * w, k * w)], "#000000").dashed());
    let vlines: Vec<(f64, String)> = critical_speeds(model).speeds.iter().enumerate().map(|(i, s)| (k * s.omega, format!("K{}", i + 1))).collect();
    (
        Plot {
            title: "Campbell diagram, rotating axes".into(),
            x_label: u.label.clone(),
            y_label: format!("Im λ, rotating axes{}", if model.scale.is_some() { " (rad/s)" } else { " / ω0" }),
            series: rot,
            vlines: vlines.clone(),
            x_range: Some((0.0, k * w)),
            x2: u.second.clone(),
            ..Default::default()
        },
        Plot {
            title: "Campbell diagram, fixed axes: Ω + ν (solid) and Ω − ν (dashed) of each mode".into(),
            x_label: u.label.clone(),
            y_label: u.freq_label.clone(),
            series: fixed,
            vlines,
            x_range: Some((0.0, k * w)),
            x2: u.second,
            ..Default::default()
        },
    )
}

/// Largest real part along the speed with the exactly stable ranges (green, below zero) and
/// 003's necessary ranges (blue, above zero) shaded.
pub fn margin_plot(model: &SpatialModel, c: &Comparison) -> Plot {
    let u = SpeedUnit::of(model);
    let k = u.factor;
    // with a dimensional rotor Re λ in 1/s (the eigenvalues are in units of ω0)
    let pts: Vec<(f64, f64)> = c.exact.max_real_part.iter().map(|&(w, a)| (k * w, k * a)).collect();
    let mut shades: Vec<Shade> =
        c.exact.stable_ranges.iter().map(|r| Shade { x: (k * r.lo, k * r.hi.unwrap_or(c.omega_max)), y: (None, Some(0.0)), color: "#009E73".into() }).collect();
    let nec: Vec<Shade> =
        c.necessary.iter().map(|r| Shade { x: (k * r.lo, k * r.hi.unwrap_or(c.omega_max)), y: (Some(0.0), None), color: "#56B4E9".into() }).collect();
    let lo = pts.iter().map(|p| p.1).fold(0.0, f64::min);
    let hi = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    let pad = 0.1 * (hi - lo).max(1e-6);
    let series = vec![Series::new("max Re λ", pts, PALETTE[1])];
    shades.extend(nec);
    Plot {
        title: "Stability margin of the balanced state along the speed".into(),
        x_label: u.label,
        y_label: if model.scale.is_some() { "max Re λ (1/s; < 0: stable)".into() } else { "max Re λ / ω0 (< 0: stable)".into() },
        series,
        shades,
        shade_legend: vec![
            ("#009E73".into(), "exactly stable (shaded below 0)".into()),
            ("#56B4E9".into(), "003 necessary condition holds (shaded above 0)".into()),
        ],
        x_range: Some((0.0, k * c.omega_max)),
        y_range: Some((lo - pad, hi + pad)),
        x2: u.second,
        ..Default::default()
    }
}
