//! Figure builders shared by the commands and the report: speed axes, the papers' layouts,
//! Campbell diagrams and the stability margin along the speed.

use crate::num::RPM_PER_RAD_S;
use crate::plot::{Plot, SecondAxis, Series, Shade, PALETTE};
use autobal::spatial::campbell::{FixedCampbell, FixedPoint};
use autobal::spatial::comparison::Comparison;
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

/// Vertical markers at the operating speed (`analysis.operating_speed`, `Ω`) on an axis that
/// shows `k · Ω`: one line, or one at each end of a range.
pub fn operating_vlines(op: Option<[f64; 2]>, k: f64) -> Vec<(f64, String)> {
    match op {
        Some([lo, hi]) if lo == hi => vec![(k * lo, "operating speed".into())],
        Some([lo, hi]) => vec![(k * lo, "operating from".into()), (k * hi, "operating to".into())],
        None => vec![],
    }
}

/// Test check that figure `id`'s `plot` marks an operating speed of `rpm` once, where that
/// speed lies on its own axis: `rpm` on an rpm axis, `rpm·2π/60` on a rad/s one, read from the
/// axis title (not from the code's factors); to a relative 1e-9 (the config's rpm to Ω and
/// back: a few ulps). Panics otherwise.
#[cfg(test)]
pub(crate) fn assert_marks_operating_rpm(id: &str, plot: &Plot, rpm: f64) {
    let marks: Vec<f64> = plot.vlines.iter().filter(|(_, l)| l == "operating speed").map(|(x, _)| *x).collect();
    let want = if plot.x_label.contains("rpm") {
        rpm
    } else if plot.x_label.contains("rad/s") {
        rpm * std::f64::consts::TAU / 60.0
    } else {
        panic!("{id}: axis {}", plot.x_label)
    };
    assert_eq!(marks.len(), 1, "{id}: {marks:?}");
    assert!((marks[0] - want).abs() <= 1e-9 * want, "{id} ({}): marked at {}, want {want}", plot.x_label, marks[0]);
}

/// Colours for many curves: the palette without black and grey, then more distinct ones, ordered
/// so that the first nine differ in hue (no two greens or two light blues among them).
pub fn curve_color(i: usize) -> &'static str {
    const MORE: [&str; 12] =
        ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#882255", "#332288", "#999933", "#56B4E9", "#AA4499", "#44AA99", "#117733"];
    MORE[i % MORE.len()]
}

pub(crate) fn group_name(g: Group) -> &'static str {
    match g {
        Group::Translation => "translation",
        Group::Tilt => "tilt",
        Group::Balls => "balls",
    }
}

/// Share of a circular component below which it is not drawn in fixed axes.
pub(crate) const COMPONENT_SHARE: f64 = 0.1;

/// The legend name of tracked line `i`: "mode N" by its mode number (`line_modes`), else
/// "line i+1" (no number: no value at its first speed).
pub fn line_name(line_modes: &[Option<usize>], i: usize) -> String {
    line_modes.get(i).copied().flatten().map_or_else(|| format!("line {}", i + 1), |m| format!("mode {m}"))
}

/// Campbell diagrams (rotating axes, fixed axes) with one colour and legend entry per tracked
/// mode ("mode 3: tilt, forward", from the dominant motion and whirl over the line), the 1×
/// line and the analytic critical speeds as markers whose labels never overlap; speeds in the
/// model's unit ([`SpeedUnit`]). In fixed axes a mode of rotating-frame frequency `ν` whirls
/// at `Ω + ν` and at `Ω − ν` (shares from its eigenvector): each component is its own
/// continuous curve wherever its share is at least 10 %, so no curve jumps between the two
/// where an elliptic mode changes its dominant direction.
///
/// Each line is labelled by its mode number (`line_modes`, per line of `c`:
/// [`autobal::spatial::campbell::FixedCampbell::line_modes`]), as the crossings and the fixed-axes
/// curves are.
pub fn campbell_plots(model: &SpatialModel, c: &Campbell, line_modes: &[Option<usize>]) -> (Plot, Plot) {
    let u = SpeedUnit::of(model);
    let k = u.factor;
    let mut rot = vec![];
    let mut fixed = vec![];
    let mut shown = 0;
    for (i, l) in c.lines.iter().enumerate() {
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
        let name = format!("{}: {}, {whirl}, from {}", line_name(line_modes, i), group_name(g), crate::num::fmt(start(&pts_r).unwrap_or(f64::NAN), 3));
        rot.push(Series::new(name.clone(), pts_r, col));
        // one legend entry per mode, toggling both components: Ω + ν solid, Ω − ν dashed
        let mut labelled = false;
        for sign in [1.0, -1.0] {
            let pts = component(sign);
            if start(&pts).is_some() {
                let label = if labelled { String::new() } else { name.clone() };
                labelled = true;
                let se = Series::new(label, pts, col).group(format!("line {}", i + 1));
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

/// Log-decrement classes of the fixed-axes Campbell diagram: (upper bound, colour, legend).
const LOG_DEC_CLASSES: [(f64, &str, &str); 4] = [
    (0.0, "#D62728", "δ < 0: unstable"),
    (0.1, "#E69F00", "0 ≤ δ < 0.1: lightly damped"),
    (0.5, "#009E73", "0.1 ≤ δ < 0.5"),
    (f64::INFINITY, "#0072B2", "δ ≥ 0.5: well damped"),
];

/// Colour of a log decrement `δ` (`LOG_DEC_CLASSES`; grey where it is undefined, `f = 0`).
pub fn log_dec_color(d: Option<f64>) -> &'static str {
    match d {
        Some(d) => LOG_DEC_CLASSES.iter().find(|c| d < c.0).map_or(LOG_DEC_CLASSES[3].1, |c| c.1),
        None => "#999999",
    }
}

/// The axes of a fixed-axes Campbell diagram: speeds and frequencies as stored times `kx`
/// and `ky` give the axes' units; `si` writes the legend's speeds in rpm and frequencies in Hz.
#[derive(Debug, Clone)]
pub struct FixedAxes {
    /// Multiplier from the stored speed to the axis unit.
    pub kx: f64,
    /// Title of the speed axis.
    pub x_label: String,
    /// Multiplier from the stored frequency to the axis unit.
    pub ky: f64,
    /// Title of the frequency axis.
    pub y_label: String,
    /// Speeds in rpm and frequencies in Hz in the legend (else `Ω = …`, `f = …`).
    pub si: bool,
}

impl FixedAxes {
    /// Speeds in rad/s drawn in rpm and frequencies in rad/s drawn in Hz, given `omega0` (rad/s
    /// per stored unit: `ω0` of a dimensional model, 1 for the general route's SI speeds).
    pub fn si(omega0: f64) -> Self {
        FixedAxes {
            kx: omega0 * 30.0 / std::f64::consts::PI,
            x_label: "rotor speed n (rpm)".into(),
            ky: omega0 / (2.0 * std::f64::consts::PI),
            y_label: "natural frequency (Hz)".into(),
            si: true,
        }
    }
    /// Dimensionless speeds `Ω` and frequencies `f/ω0`.
    pub fn dimensionless() -> Self {
        FixedAxes { kx: 1.0, x_label: "Ω = ω/ω0".into(), ky: 1.0, y_label: "natural frequency / ω0".into(), si: false }
    }
    /// A speed as the legend writes it.
    fn speed(&self, w: f64) -> String {
        if self.si {
            format!("{:.0} rpm", w * self.kx)
        } else {
            format!("Ω = {}", crate::num::fmt(w, 4))
        }
    }
    /// A frequency as the legend writes it.
    fn freq(&self, f: f64) -> String {
        if self.si {
            format!("{} Hz", crate::num::fmt(f * self.ky, 4))
        } else {
            format!("f = {}", crate::num::fmt(f, 4))
        }
    }
}

/// The axes of the fixed-axes Campbell diagram: (speed factor and label, frequency factor and
/// label): rpm and Hz for a dimensional model (`n = Ω ω0 · 30/π`, `f_Hz = f ω0 / 2π`), `Ω` and
/// `f/ω0` otherwise.
pub fn campbell_axes(model: &SpatialModel) -> ((f64, String), (f64, String)) {
    let a = fixed_axes_of(model);
    ((a.kx, a.x_label), (a.ky, a.y_label))
}

/// [`FixedAxes`] of a model of papers 000/003 (rpm and Hz where it is dimensional).
pub fn fixed_axes_of(model: &SpatialModel) -> FixedAxes {
    match model.scale {
        Some(sc) => FixedAxes::si(sc.omega0),
        None => FixedAxes::dimensionless(),
    }
}

/// The Campbell diagram as engineers read it ([`autobal::spatial::campbell`]): one curve per
/// mode of natural frequency `|f|` in fixed axes, forward whirl solid and backward dashed, each
/// segment coloured by its log decrement `δ = −2π σ/|f|` (classes in the legend); the
/// excitation lines `h Ω` dashed grey; the critical speeds (crossings with them) as points,
/// each listed in the legend. Axes in rpm and Hz for a dimensional model ([`campbell_axes`]).
pub fn campbell_fixed_plot(model: &SpatialModel, f: &FixedCampbell) -> Plot {
    campbell_fixed_plot_in(&fixed_axes_of(model), f)
}

/// [`campbell_fixed_plot`] on any axes: the 12-state route's and the general route's
/// ([`autobal::rotor_campbell::fixed_view`]) fixed-axes view, one drawing.
pub fn campbell_fixed_plot_in(axes: &FixedAxes, f: &FixedCampbell) -> Plot {
    let (kx, ky) = (axes.kx, axes.ky);
    let mut series = vec![];
    let w_max = f.omega.last().copied().unwrap_or(1.0);
    let f_max = f.curves.iter().flat_map(|c| c.points.iter().map(|p| p.frequency)).fold(0.0, f64::max);
    for cv in &f.curves {
        let group = format!("mode {}", cv.mode);
        let p0 = &cv.points[0];
        let fwd = cv.points.iter().filter(|p| p.whirl == Whirl::Forward).count();
        let whirl = if 2 * fwd >= cv.points.len() { "forward" } else { "backward" };
        let name = format!("mode {}: {whirl}, {} at {}", cv.mode, axes.freq(p0.frequency), axes.speed(p0.omega));
        // runs of one whirl direction and one colour; each run starts at the previous run's
        // last point so that the curve has no gaps
        let key = |p: &FixedPoint| (p.whirl, log_dec_color(p.log_decrement));
        let mut start = 0;
        let mut labelled = false;
        for k in 1..=cv.points.len() {
            if k < cv.points.len() && key(&cv.points[k]) == key(&cv.points[start]) {
                continue;
            }
            let from = start.saturating_sub(1);
            let pts: Vec<(f64, f64)> = cv.points[from..k].iter().map(|p| (kx * p.omega, ky * p.frequency)).collect();
            let (wh, col) = key(&cv.points[start]);
            let label = if labelled { String::new() } else { name.clone() };
            labelled = true;
            let se = Series::new(label, pts, col).group(group.clone());
            series.push(if wh == Whirl::Backward { se.dashed() } else { se });
            start = k;
        }
    }
    let y_top = f_max.max(w_max) * 1.05;
    for &h in &f.harmonics {
        // the line h Ω up to the top of the frequency axis
        let w_end = w_max.min(y_top / h as f64);
        series.push(Series::new(format!("{h}× (excitation)"), vec![(0.0, 0.0), (kx * w_end, ky * h as f64 * w_end)], "#888888").dashed());
    }
    const LISTED: usize = 12;
    for (j, cs) in f.critical_speeds.iter().enumerate() {
        let whirl = if cs.whirl == Whirl::Backward { "backward" } else { "forward" };
        // a minor circular component (share < ½), or an overdamped crossing (no resonance):
        // said, and marked in grey, so that it does not read as the mode's resonance
        let minor = cs.share < 0.5;
        let label = if j < LISTED {
            let comp = if minor { format!(", minor component, share {}", crate::num::fmt(cs.share, 2)) } else { String::new() };
            let od = if cs.overdamped { ", overdamped: no resonance" } else { "" };
            format!("critical {}: {} (mode {}, {whirl}, {}×{comp}{od})", j + 1, axes.speed(cs.omega), cs.mode, cs.harmonic)
        } else if j == LISTED {
            format!("further critical speeds ({})", f.critical_speeds.len() - LISTED)
        } else {
            String::new()
        };
        let se = Series::new(label, vec![(kx * cs.omega, ky * cs.frequency)], if minor || cs.overdamped { "#999999" } else { "#000000" }).markers();
        series.push(if j >= LISTED { se.group("further critical speeds") } else { se });
    }
    // the colour classes of the log decrement, as legend entries without points
    for (_, col, text) in LOG_DEC_CLASSES {
        if f.curves.iter().any(|c| c.points.iter().any(|p| log_dec_color(p.log_decrement) == col)) {
            series.push(Series::new(format!("log dec {text}"), vec![], col));
        }
    }
    Plot {
        title: "Campbell diagram (fixed axes): natural frequencies, forward solid, backward dashed, coloured by log decrement".into(),
        x_label: axes.x_label.clone(),
        y_label: axes.y_label.clone(),
        series,
        x_range: Some((0.0, kx * w_max)),
        y_range: Some((0.0, ky * y_top)),
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use autobal::spatial::campbell::fixed_axes;
    use autobal::spatial::linear_model::Balls;
    use autobal::spatial::params::DimensionlessInput;
    use autobal::spatial::stability::campbell;

    /// The components view labels each line by its mode number, as the crossings are
    /// (review of session 15: a counter over the lines called examples/dimensional.toml's
    /// lowest rotor mode "mode 6", mode 3 everywhere else; checked failing with the counter:
    /// here the lines come in the order of modes 2, 1, 3, ...).
    #[test]
    fn the_components_view_labels_lines_by_their_mode_numbers() {
        let mut root = autobal::config::parse(include_str!("../../../examples/dimensional.toml"), "test").unwrap();
        for t in ["drive", "initial"] {
            root.remove(t);
        }
        let m = autobal::config::spatial_simulation(&root).unwrap().config.model;
        let omegas = autobal::reports::campbell_speeds(5.0, 240);
        let c = campbell(&m, &omegas, Balls::Free).unwrap();
        let f = fixed_axes(&m, &c, Balls::Free, &[1]).unwrap();
        let (_, fixed) = campbell_plots(&m, &c, &f.line_modes);
        let mut checked = 0;
        for s in fixed.series.iter().filter(|s| !s.label.is_empty() && s.group.is_some()) {
            let line: usize = s.group.as_deref().and_then(|g| g.strip_prefix("line ")).and_then(|g| g.parse().ok()).unwrap();
            let n: usize = s.label.strip_prefix("mode ").and_then(|l| l.split(':').next()).and_then(|n| n.parse().ok()).unwrap();
            assert_eq!(Some(n), f.line_modes[line - 1], "{}", s.label);
            checked += 1;
        }
        assert!(checked >= f.curves.len(), "{checked} legend entries");
    }

    #[test]
    fn fixed_campbell_plot_has_one_legend_entry_per_mode_and_critical_speed() {
        let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
        let omegas = linspace(0.01, 4.0, 200);
        let c = campbell(&m, &omegas, Balls::Locked).unwrap();
        let f = fixed_axes(&m, &c, Balls::Locked, &[1, 2]).unwrap();
        let p = campbell_fixed_plot(&m, &f);
        let labels: Vec<&str> = p.series.iter().map(|s| s.label.as_str()).filter(|l| !l.is_empty()).collect();
        assert_eq!(labels.iter().filter(|l| l.starts_with("mode ")).count(), f.curves.len());
        assert_eq!(labels.iter().filter(|l| l.starts_with("critical ")).count(), f.critical_speeds.len().min(12));
        assert!(labels.contains(&"1× (excitation)") && labels.contains(&"2× (excitation)"));
        // backward stretches are dashed, forward ones solid
        assert!(p.series.iter().any(|s| s.dashed && s.group.is_some()) && p.series.iter().any(|s| !s.dashed && s.group.is_some()));
        let svg = p.to_svg();
        assert!(svg.contains("log dec"));
        let plotly = p.to_plotly();
        assert!(plotly.to_string().contains("mode 1:"));
    }

    /// A minor circular component's crossing (paper 000's rotor with free balls: two backward
    /// components of share ~1e-3 meet 1×) is labelled as such and marked grey; a major one not.
    /// So is an overdamped end on the real axis (session 31: the balls' drag pair at 0.0774 and
    /// 0.1319), no resonance.
    #[test]
    fn a_minor_components_critical_speed_says_so() {
        let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
        let c = campbell(&m, &linspace(0.01, 4.0, 300), Balls::Free).unwrap();
        let f = fixed_axes(&m, &c, Balls::Free, &[1]).unwrap();
        assert!(f.critical_speeds.iter().any(|cs| cs.share < 0.5) && f.critical_speeds.iter().any(|cs| cs.share >= 0.5), "{:?}", f.critical_speeds);
        assert!(
            f.critical_speeds.iter().any(|cs| cs.overdamped) && f.critical_speeds.iter().any(|cs| cs.share >= 0.5 && !cs.overdamped),
            "{:?}",
            f.critical_speeds
        );
        let p = campbell_fixed_plot(&m, &f);
        for (cs, se) in f.critical_speeds.iter().zip(p.series.iter().filter(|s| s.label.starts_with("critical "))) {
            assert_eq!(se.label.contains("minor component"), cs.share < 0.5, "{}", se.label);
            assert_eq!(se.label.contains("overdamped"), cs.overdamped, "{}", se.label);
            assert_eq!(se.color == "#999999", cs.share < 0.5 || cs.overdamped, "{}", se.label);
        }
    }
}
