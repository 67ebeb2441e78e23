//! Section "Exact linear stability" of the config's spatial rotor: Campbell diagrams, the
//! margin along the speed against 003's necessary ranges, the papers' three layouts, and
//! stability maps in the layouts of 003's Figs 4, 5a, 5b around this rotor ([`build`], the
//! papers' report, on paper 000's base case).
//!
//! [`build_user`], the report about the user's rotor: the same exact stability over speed, as
//! `autobal stability` computes it (same speed axis, same 2000 grid speeds), with the verdict at
//! the operating speed in the summary, and the operating speed marked; a config that paper 000's
//! 12-state model does not represent (two planes, gravity, supports that differ by direction,
//! a planar rotor; [`crate::general::needs_general_route`]) is analysed as given by the general
//! route ([`crate::general::analyse`]), as `autobal stability` does, with its Campbell diagrams
//! by the general route ([`crate::general_campbell`], as `autobal campbell` draws them).

use super::{rotor::ranges_text_in, Ctx, Section};
use crate::figures::{campbell_plots, margin_plot, omega_limit, with_layout, SpeedUnit};
use crate::linear;
use crate::map::{MapResult, Quantity};
use crate::num::fmt;
use anyhow::Result;
use autobal::paths::Axis;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::map::{stability_map, MapSettings, ModelFamily};
use autobal::spatial::params::SpatialModel;

/// Grid of the report's maps (per axis).
const MAP_N: usize = 121;

/// Grid speeds of `autobal stability` (its default `--samples`): the report's verdict is
/// computed on the same grid, so it is the command's.
pub const STABILITY_SAMPLES: usize = 2000;

/// Marker of the verdict at the operating speed in the summary: `data-stable` is `true` or
/// `false` (the tests compare it with `autobal stability --format json`).
fn verdict_html(stable: bool, text: &str) -> String {
    format!("<span id=\"verdict\" data-stable=\"{stable}\"><b>{}</b></span>", super::esc(text))
}

/// The section of the user's report ([`Kind::User`](super::Kind::User)).
pub fn build_user(ctx: &Ctx) -> Result<Option<Section>> {
    if crate::general::needs_general_verdict(&ctx.root) {
        return general_route(ctx);
    }
    let Some(cfg) = &ctx.spatial else { return general_route(ctx) };
    let m = &cfg.model;
    let w0 = m.scale.map(|s| s.omega0);
    let mut s = Section::new("stability", "Exact stability of the balanced state over speed");
    if m.balls.is_none() {
        s.p("The config does not describe the balls (give the masses, or <code>m</code> and <code>d_a</code> beside <code>delta_a</code>), so only the locked rotor is analysed here.");
    }
    let balls = if m.balls.is_some() { Balls::Free } else { Balls::Locked };
    let w = linear::omega_max(cfg, None)?;
    let cmp = linear::compare(m, w, STABILITY_SAMPLES, balls)?;
    autobal::limits::check_finite("stability", &cmp.exact)?;
    let table = linear::stability_table(cfg, &cmp, balls);
    let json = linear::stability_json(cfg, &cmp, balls);
    match (json["operating_speed"]["stable"].as_bool(), table.lines().find(|l| l.starts_with("operating speed"))) {
        (Some(stable), Some(line)) => s.summary.push(verdict_html(stable, line)),
        (_, Some(line)) => s.summary.push(format!("<b>{}</b>", super::esc(line))),
        _ => s.summary.push(format!(
            "No operating speed given (<code>[analysis] operating_speed = {}</code> or a range): the balanced state is exactly stable on {}.",
            if w0.is_some() { "\"1400 rpm\"" } else { "1.5</code>, as Ω = ω/ω0,<code>" },
            super::esc(&ranges_text_in(&cmp.exact.stable_ranges, w0, Some(cmp.omega_max)))
        )),
    }
    s.p(format!(
        "Eigenvalues of the linearised equations (000, eq (6)), balls {} ({} states), on {STABILITY_SAMPLES} speeds up to the end of the speed axis, the operating speed and 1.3 times the highest critical speed covered. Stable means every eigenvalue has Re λ {}; range ends located by bisection to 1e-9 in Ω. What <code>autobal stability</code> prints for this config:",
        if balls == Balls::Free { "free" } else { "locked" },
        if balls == Balls::Free { 12 } else { 8 },
        if balls == Balls::Free { "&lt; −1e-11 ω0" } else { "≤ 1e-11 ω0 (neutral allowed)" }
    ));
    s.html(format!("<pre>{}</pre>\n", super::esc(table.lines().skip(1).collect::<Vec<_>>().join("\n").as_str())));
    let u = SpeedUnit::of(m);
    let mut margin = margin_plot(m, &cmp);
    margin.vlines.extend(super::rotor::operating_vlines(cfg.analysis.operating_speed, u.factor));
    s.figure(
        "stability_margin",
        margin,
        format!(
            "Largest real part of the eigenvalues along the speed, the operating speed marked. Exactly stable on {}; 003's necessary condition holds on {}. {}.",
            super::esc(&ranges_text_in(&cmp.exact.stable_ranges, w0, Some(cmp.omega_max))),
            super::esc(&ranges_text_in(&cmp.necessary, w0, Some(cmp.omega_max))),
            super::esc(&cmp.difference())
        ),
    );
    s.h3("campbell", "Campbell diagrams");
    let c = linear::campbell_of(cfg, w, 240, balls)?;
    let fx = autobal::spatial::campbell::fixed_axes(m, &c, balls, &[1])?;
    let (mut rot, mut fixed) = campbell_plots(m, &c, &fx.line_modes);
    let mut modes = crate::figures::campbell_fixed_plot(m, &fx);
    for p in [&mut rot, &mut fixed] {
        p.vlines.extend(super::rotor::operating_vlines(cfg.analysis.operating_speed, u.factor));
    }
    // the engineers' diagram has its own axes (rpm for a dimensional model: walk 27 found the
    // operating speed drawn at its rad/s value on that rpm axis)
    modes.vlines.extend(super::rotor::operating_vlines(cfg.analysis.operating_speed, crate::figures::fixed_axes_of(m).kx));
    s.figure("campbell_modes", modes, "Campbell diagram as engineers read it: one curve per mode of natural frequency in fixed axes (forward whirl solid, backward dashed), coloured by log decrement, the 1x line and the critical speeds (its crossings) marked.");
    s.figure("campbell_fixed", fixed, CAMPBELL_FIXED_CAPTION);
    s.figure("campbell_rotating", rot, "Campbell diagram in rotating axes: Im λ of each tracked eigenvalue (the frequency seen from the rotor).");
    Ok(Some(s))
}

/// The stability section by the general route, as `autobal stability` runs it for this config
/// (same speed axis and number of speeds).
fn general_route(ctx: &Ctx) -> Result<Option<Section>> {
    use autobal::rotor_stability::Rotor;
    let g = crate::general::rotor_of(&ctx.root)?;
    let samples = if g.rotor.is_periodic() { 50 } else { 200 };
    let (omega_max, op) = match &g.rotor {
        Rotor::Planar(_) | Rotor::Linear(_) => (3.0 * g.rotor.natural_frequency(), None),
        Rotor::Spatial(_) => {
            let cfg = autobal::config::spatial(&ctx.root)?;
            (
                cfg.analysis.speed_axis_max(2.0 * autobal::reports::default_omega_max(&cfg.model)) * g.omega0,
                cfg.analysis.operating_speed.map(|[a, b]| [a * g.omega0, b * g.omega0]),
            )
        }
    };
    // under the report's control, as `stability` runs it: stopped (Ctrl-C, the budget), the
    // speeds analysed are kept and the section is incomplete (it ended the report with an
    // error, "nothing is printed"); the verdict at the operating speed is `stability`'s
    // (`general::operating`: the state solved at the speed itself), not read off the scan's
    // ranges, so that the report and `stability` cannot disagree (review 24: a speed between
    // two grid speeds near a boundary could read STABLE from the ranges)
    let (out, speeds) = crate::general::scan(&g, omega_max, samples, &ctx.control)?;
    let (r, operating, stopped) = crate::stability::kept_scan(out, speeds, &ctx.control, |r, c| crate::general::operating(&g, &ctx.root, r, c))?;
    let mut s = Section::new("stability", "Exact stability of the stationary state over speed (general route)");
    s.complete = stopped.is_none();
    let what: Vec<String> = autobal::config::ignored_by_linear_model(&ctx.root);
    s.p(format!(
        "{} The general route finds the stationary state from the full nonlinear equations at each of {samples} speeds and takes its eigenvalues (or Floquet multipliers), as <code>autobal stability</code> does for this config. What it prints:",
        if matches!(g.rotor, Rotor::Planar(_)) {
            "The config's planar rotor (paper 004 model).".to_string()
        } else {
            format!("The config has what paper 000's 12-state model does not represent ({}), so its rotor is analysed as given.", super::esc(&what.join(", ")))
        }
    ));
    let table = crate::stability::incomplete_line(&stopped) + &crate::general::table(&g, &r, omega_max, operating.as_ref());
    s.html(format!("<pre>{}</pre>\n", super::esc(&table)));
    let speed = |w: f64| if g.si { format!("{} rpm", crate::num::grouped(w * crate::num::RPM_PER_RAD_S, 0)) } else { format!("Ω = {}", fmt(w, 4)) };
    match (&operating, op) {
        // `stability`'s first line, word for word (its other-orbits line after it)
        (Some(o), _) => {
            let text = crate::general::operating_line(&g, &r, o);
            let text: Vec<&str> = text.lines().map(str::trim).collect();
            s.summary.push(verdict_html(o.verdict() == Some(autobal::analysis::Verdict::Stable), &text.join("; ")));
        }
        // a stopped scan's ranges end where it stopped: no verdict from them
        (None, Some([lo, hi])) => {
            let at = if lo == hi { speed(lo) } else { format!("{} – {}", speed(lo), speed(hi)) };
            s.summary.push(format!(
                "<b>{}</b>",
                super::esc(&format!("operating speed {at}: no verdict: the stability scan was stopped ({})", stopped.as_deref().unwrap_or_default()))
            ));
        }
        (None, None) => s.summary.push(format!(
            "No operating speed given{}: see the stable ranges of the stability section.",
            if matches!(g.rotor, Rotor::Planar(_)) { " (a planar config has none)" } else { " (<code>[analysis] operating_speed</code>)" }
        )),
    }
    let mut p = crate::stability::mark_stopped(crate::general::margin_plot(&g, &r, omega_max), &stopped, r.points.last().map(|q| q.omega));
    p.vlines.extend(super::rotor::operating_vlines(op, 1.0));
    if g.si {
        p.x2 = Some(crate::plot::SecondAxis { factor: crate::num::RPM_PER_RAD_S, label: "n (rpm)".into() });
    }
    s.figure("stability_margin", p, "The stationary state's margin over speed by the general route (largest Re λ, or largest Floquet exponent for a periodic orbit), the stable ranges shaded and the operating speed marked.");
    if stopped.is_some() {
        s.h3("campbell", "Campbell diagrams");
        s.p(if operating.is_some() {
            "Not computed: the report was stopped during the verdict at the operating speed above."
        } else {
            "Not computed: the report was stopped during the stability scan above."
        });
    } else {
        general_campbell(ctx, &g, omega_max, op, &mut s)?;
    }
    Ok(Some(s))
}

/// Speeds of the report's general-route Campbell diagram: an equilibrium costs a Newton solve
/// and an eigenvalue problem per speed, a periodic orbit a shooting over a revolution.
fn general_campbell_points(periodic: bool, quick: bool) -> usize {
    match (periodic, quick) {
        (false, false) => 240,
        (false, true) => 120,
        (true, false) => 40,
        (true, true) => 16,
    }
}

/// The Campbell diagrams of the user's rotor as given, by the general route (as `autobal
/// campbell` draws them for this config: the fixed-axes view with its `1×` crossings, and the
/// components view), the operating speed marked.
fn general_campbell(ctx: &Ctx, g: &crate::general::GeneralRotor, omega_max: f64, op: Option<[f64; 2]>, s: &mut Section) -> Result<()> {
    use autobal::analysis::Kind;
    let points = general_campbell_points(g.rotor.is_periodic(), ctx.quick);
    s.h3("campbell", "Campbell diagrams");
    // stopped (Ctrl-C, the budget): the speeds analysed (or every speed, the search for the
    // crossings stopped) kept and drawn, marked, the section incomplete, as `autobal campbell`
    // keeps them (it ended the report with an error)
    let c = crate::general_campbell::campbell_with(g, omega_max, points, Balls::Free, &[1], &ctx.control)?;
    if c.stopped.is_some() {
        s.complete = false;
        s.p(super::esc(crate::stability::incomplete_line(&c.stopped).trim_end()));
    }
    let periodic = c.diagram.kind == Kind::PeriodicOrbit;
    s.p(format!(
        "The {} of the stationary state at {points} speeds, balls free, by the general route (what <code>autobal campbell</code> computes for this config){}.",
        if periodic { "Floquet exponents" } else { "eigenvalues" },
        if periodic {
            format!(
                "; a Floquet exponent's imaginary part is defined modulo the speed Ω, so the curves are drawn on one branch ({}) and <b>no crossing speeds are given</b>: the critical speeds of the locked rotor are in the section above where they are defined",
                super::esc(autobal::rotor_campbell::FLOQUET_BRANCH)
            )
        } else {
            String::new()
        }
    ));
    let kx = if g.si { crate::num::RPM_PER_RAD_S } else { 1.0 };
    if let (Some(f), None) = (&c.fixed, &c.crossings_not_given) {
        let speed = |w: f64| if g.si { format!("{} rpm", crate::num::grouped(w * kx, 0)) } else { format!("Ω = {}", fmt(w, 4)) };
        let list: Vec<String> = f.critical_speeds.iter().filter(|k| k.harmonic == 1).map(|k| speed(k.omega)).collect();
        s.p(format!(
            "Speeds where a mode's natural frequency in fixed axes crosses 1× (bisected on the spectrum; the balls free, damping kept): {}.",
            if list.is_empty() { "none on the axis".to_string() } else { list.join(", ") }
        ));
    }
    let mark = |p| crate::stability::mark_stopped(p, &c.stopped, None);
    let mut modes = mark(crate::general_campbell::campbell_plot(g, &c, omega_max));
    modes.vlines.extend(super::rotor::operating_vlines(op, kx));
    let (rot, fixed) = crate::general_campbell::components_plots(g, &c);
    let (mut rot, mut fixed) = (mark(rot), mark(fixed));
    for p in [&mut rot, &mut fixed] {
        p.vlines.extend(super::rotor::operating_vlines(op, 1.0));
    }
    s.figure(
        "campbell_modes",
        modes,
        "Campbell diagram as engineers read it (general route): one curve per mode of natural frequency in fixed axes (forward whirl solid, backward dashed), coloured by log decrement, the 1x line and its crossings marked (none for Floquet exponents).",
    );
    s.figure("campbell_fixed", fixed, CAMPBELL_FIXED_GENERAL_CAPTION);
    s.figure("campbell_rotating", rot, "Campbell diagram in rotating axes (general route): Im λ of each tracked eigenvalue, or Im ρ of each Floquet exponent on its branch (the frequency seen from the rotor).");
    Ok(())
}

const CAMPBELL_FIXED_GENERAL_CAPTION: &str = "Campbell diagram in fixed axes (general route): a mode whirls in fixed axes at Ω + ν (solid) and Ω − ν (dashed), ν its frequency seen from the rotor; a component is drawn where it carries at least 10 % of the rotor's motion. Legend: the coordinates that carry most of the mode's kinetic energy and its whirl. Also drawn: the synchronous 1× line and its crossings.";

const CAMPBELL_FIXED_CAPTION: &str = "Campbell diagram in fixed axes: whirl frequency of each tracked eigenvalue (forward above zero, backward below; legend: the motion that dominates the mode and its whirl). A mode whirls in fixed axes at Ω + ν (solid) and Ω − ν (dashed), ν its frequency seen from the rotor; a component is drawn where it carries at least 10 % of the mode's motion, so curves start and stop where a whirl turns circular. Clicking a legend entry hides both components. Also drawn: the synchronous 1× line, and the analytic critical speeds K1-K4 of the locked rotor. Where a mode crosses 1× near a K line the locked rotor is at a critical speed.";

/// The section of the papers' report ([`Kind::Papers`](super::Kind::Papers)): paper 000's base
/// case (the embedded default) with 003's maps.
pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let Some(cfg) = &ctx.spatial else {
        return Ok(Some(Section::not_applicable("stability", "Exact linear stability", "the exact stability of papers 000/003 needs a spatial rotor")));
    };
    let m = &cfg.model;
    let w0 = m.scale.map(|s| s.omega0);
    let mut s = Section::new("stability", "Exact linear stability of the balanced state (paper 000's base case, the embedded default)");
    if m.balls.is_none() {
        s.p("The config does not describe the balls (give the masses, or <code>m</code> and <code>d_a</code> beside <code>delta_a</code>), so only the locked rotor is analysed here.");
    }
    let balls = if m.balls.is_some() { Balls::Free } else { Balls::Locked };
    let w = linear::omega_max(cfg, None)?;
    s.p(format!(
        "Eigenvalues of the linearised equations (000, eq (6)), balls {} ({} states). Stable means every eigenvalue has Re λ {}; range ends located by bisection to 1e-9 in Ω.",
        if balls == Balls::Free { "free" } else { "locked" },
        if balls == Balls::Free { 12 } else { 8 },
        if balls == Balls::Free { "&lt; −1e-11 ω0" } else { "≤ 1e-11 ω0 (neutral allowed)" }
    ));
    s.h3("campbell", "Campbell diagrams");
    let c = linear::campbell_of(cfg, w, 240, balls)?;
    let fx = autobal::spatial::campbell::fixed_axes(m, &c, balls, &[1])?;
    let (rot, fixed) = campbell_plots(m, &c, &fx.line_modes);
    let modes = crate::figures::campbell_fixed_plot(m, &fx);
    s.figure("campbell_modes", modes, "Campbell diagram as engineers read it: one curve per mode of natural frequency in fixed axes (forward whirl solid, backward dashed), coloured by log decrement, the 1x line and the critical speeds (its crossings) marked.");
    s.figure("campbell_fixed", fixed, CAMPBELL_FIXED_CAPTION);
    s.figure("campbell_rotating", rot, "Campbell diagram in rotating axes: Im λ of each tracked eigenvalue (the frequency seen from the rotor).");

    s.h3("margin", "Stability along the speed");
    let cmp = linear::compare(m, w, 1500, balls)?;
    s.figure(
        "stability_margin",
        margin_plot(m, &cmp),
        format!(
            "Largest real part of the eigenvalues along the speed for this rotor. Exactly stable on {}; 003's necessary condition holds on {}. {}.",
            super::esc(&ranges_text_in(&cmp.exact.stable_ranges, w0, Some(cmp.omega_max))),
            super::esc(&ranges_text_in(&cmp.necessary, w0, Some(cmp.omega_max))),
            super::esc(&cmp.difference())
        ),
    );
    if m.rho_s.is_some() && m.scale.is_none() {
        let mut rows = vec![];
        for l in [0.5, 0.8, 1.2] {
            let ml = with_layout(m, l);
            let cl = linear::compare(&ml, w.max(omega_limit(&ml, None)), 1500, balls)?;
            rows.push(vec![
                fmt(l, 3),
                ranges_text_in(&cl.exact.stable_ranges, None, Some(cl.omega_max)),
                ranges_text_in(&cl.necessary, None, Some(cl.omega_max)),
                cl.difference(),
            ]);
        }
        s.h3("layouts", "Exact ranges against 003's necessary ranges, the papers' three layouts");
        s.p("This rotor moved on identical supports to the three layouts of the papers' worked examples.");
        s.table(&["l̄_L (–)", "exactly stable (Ω)", "003 necessary (Ω)", "difference"], &rows);
    }

    s.h3("maps", "Stability maps");
    let u = SpeedUnit::of(m);
    type Setter = fn(&mut SpatialModel, f64);
    let maps: [(&str, &str, Axis, Setter, &str); 3] = [
        (
            "stability_map_c_sigma",
            "Stability map C̄Σ × speed",
            Axis::linspace("dimensionless.c_sigma", 0.2, 2.0, MAP_N),
            |m, v| m.c_sigma = v,
            "in the layout of 003 Fig. 4: over the rotor type C̄Σ (long &lt; 1 &lt; short) and the speed",
        ),
        (
            "stability_map_z_a",
            "Stability map z̄_A × speed",
            Axis::linspace("dimensionless.z_a", -2.0, 2.0, MAP_N),
            |m, v| m.z_a = v,
            "in the layout of 003 Fig. 5a: over the position of the balancer plane z̄_A and the speed",
        ),
        (
            "stability_map_delta_a0",
            "Stability map ΔĀ0 × speed",
            Axis::linspace("dimensionless.delta_a", 0.0, 0.24, MAP_N),
            |m, v| {
                m.anisotropy.used = v;
                m.delta_a0 = v;
            },
            "in the layout of 003 Fig. 5b: over the anisotropy (ΔĀ = ΔĀ0, given directly as in 003's examples) and the speed",
        ),
    ];
    for (stem, title, x, set, what) in maps {
        let y = Axis::linspace("omega", 0.02 * w, w, MAP_N);
        let r = map(m, x, y, set, balls, &ctx.control)?;
        let complete = r.rows.iter().all(|r| r.is_some());
        s.complete &= complete;
        let mut p = crate::map::plot(&r, title);
        if u.factor != 1.0 {
            // a dimensional rotor: speed in rad/s, growth rate in 1/s
            if let Some(h) = p.heatmap.as_mut() {
                h.y.iter_mut().for_each(|v| *v *= u.factor);
                // Re λ in 1/s (the eigenvalues are in units of ω0)
                h.z.iter_mut().flatten().for_each(|v| *v *= u.factor);
                if let crate::plot::ColorScale::Diverging { neg, pos } = &mut h.scale {
                    *neg *= u.factor;
                    *pos *= u.factor;
                }
                h.label = "max Re λ (1/s; < 0 stable)".into();
            }
            for se in &mut p.series {
                se.points.iter_mut().for_each(|q| q.1 *= u.factor);
            }
            p.y_range = p.y_range.map(|(a, b)| (a * u.factor, b * u.factor));
            p.y_label = u.label.clone();
        }
        s.figure(
            stem,
            p,
            format!(
                "Stability map {what}: largest real part of the eigenvalues (colour bar: blue stable, red unstable, white near zero, square-root scale on each side), the stability boundary between cells of different exact verdicts (solid black; the boundary lies within a cell of it) and the boundary of 003's necessary condition (dashed). The other parameters are this rotor's.{}",
                if complete { "" } else { " <b>Interrupted: grey rows were not computed.</b>" }
            ),
        );
    }
    Ok(Some(s))
}

/// This rotor with one dimensionless coefficient of its derived model set directly (`set`, the
/// only path): a dimensional rotor is varied in the papers' layouts as a dimensionless one is.
#[derive(Clone)]
struct Varied<'a> {
    model: &'a SpatialModel,
    path: &'a str,
    set: fn(&mut SpatialModel, f64),
    value: Option<f64>,
}

impl ModelFamily for Varied<'_> {
    fn with(&self, path: &str, value: f64) -> autobal::error::Result<Self> {
        if path != self.path {
            return Err(autobal::error::Error::invalid(path, format!("this map varies {} only", self.path)));
        }
        Ok(Varied { value: Some(value), ..self.clone() })
    }
    fn model(&self) -> autobal::error::Result<SpatialModel> {
        let mut m = self.model.clone();
        if let Some(v) = self.value {
            (self.set)(&mut m, v);
        }
        Ok(m)
    }
}

/// A stability map over one model parameter (`set`) and the speed, by the library's map
/// ([`autobal::spatial::map::stability_map`]); rows not computed when Ctrl-C came are `None`.
fn map(m: &SpatialModel, x: Axis, y: Axis, set: fn(&mut SpatialModel, f64), balls: Balls, control: &autobal::control::Control) -> Result<MapResult> {
    let family = Varied { model: m, path: &x.path, set, value: None };
    let settings = MapSettings { balls, quantity: Quantity::Margin, omega: None };
    let mut rows = vec![None; y.values.len()];
    stability_map(&family, &x, &y, &settings, control, &mut |j, cells| {
        rows[j] = Some(cells.to_vec());
        true
    })?;
    Ok(MapResult { x, y, rows, quantity: Quantity::Margin })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::ConfigSource;
    use autobal::control::Control;

    /// The user report's context for paper 004's planar example (the general route) under
    /// `control`.
    fn planar_ctx(control: &Control) -> Ctx {
        let root = crate::config::parse_text(include_str!("../../../../examples/planar.toml"), "planar.toml").unwrap();
        super::super::context(&ConfigSource::tables(root, "planar.toml"), false, super::super::Kind::User, control).unwrap()
    }

    /// A control that cancels itself once a computation whose progress counts `total` items
    /// has reported `k` done (a Ctrl-C after `k` speeds of that computation): the scan's 200
    /// speeds, the Campbell diagram's 240.
    fn stop_after(total: u64, k: u64) -> Control {
        let control = Control::new();
        let c = control.clone();
        control.with_progress(move |p| {
            if p.total == total && p.done >= k {
                c.cancel();
            }
        })
    }

    /// The section's HTML as one string.
    fn html(s: &Section) -> String {
        s.blocks.iter().filter_map(|b| if let super::super::Block::Html(h) = b { Some(h.as_str()) } else { None }).collect()
    }

    /// The report's general route stopped during its stability scan (Ctrl-C after 3 of 200
    /// speeds) keeps the speeds analysed, as `stability` does, and marks its section
    /// incomplete (it ended the whole report with an error, "nothing is printed"): the table's
    /// first line INCOMPLETE with the count, the figure's title too, no Campbell diagram (not
    /// computed: said); the same section not stopped is complete, with its diagram.
    #[test]
    fn the_general_route_s_stopped_scan_keeps_the_speeds_analysed() {
        let s = general_route(&planar_ctx(&stop_after(200, 3))).unwrap().unwrap();
        assert!(!s.complete);
        let h = html(&s);
        assert!(h.contains("INCOMPLETE (interrupted: 3 of 200 speeds analysed; what was analysed is printed"), "{h}");
        assert!(h.contains("Not computed: the report was stopped during the stability scan above."), "{h}");
        let figs: Vec<&super::super::Figure> = s.figures().collect();
        assert_eq!(figs.len(), 1);
        assert!(figs[0].plot.title.starts_with("INCOMPLETE: "), "{}", figs[0].plot.title);
        let whole = general_route(&planar_ctx(&Control::none())).unwrap().unwrap();
        assert!(whole.complete && !html(&whole).contains("INCOMPLETE"));
        assert_eq!(whole.figures().count(), 4);
    }

    /// Stopped during its Campbell diagram (after the whole scan, 5 of 240 speeds), the
    /// section keeps the scan and the curves analysed, marks them (the figures' titles), and
    /// is incomplete (it ended the report with an error).
    #[test]
    fn the_general_route_s_stopped_campbell_keeps_its_curves() {
        let s = general_route(&planar_ctx(&stop_after(240, 5))).unwrap().unwrap();
        assert!(!s.complete);
        let h = html(&s);
        assert!(!h.contains("INCOMPLETE (interrupted: 3 of 200"), "the scan is complete: {h}");
        assert!(h.contains("INCOMPLETE (interrupted: ") && h.contains(" of 240 speeds analysed"), "{h}");
        let titles: Vec<&str> = s.figures().map(|f| f.plot.title.as_str()).collect();
        assert_eq!(titles.len(), 4);
        assert!(!titles[0].starts_with("INCOMPLETE") && titles[1..].iter().all(|t| t.starts_with("INCOMPLETE: ")), "{titles:?}");
    }

    /// The summary's verdict at the operating speed on the general route is `stability`'s,
    /// word for word (its first line), by one route (`general::operating`). Review 24: the
    /// report read it off the scan's stable ranges. The two-plane example without gravity is
    /// stable from the boundary located at 1201.07649 rad/s, between its grid speeds 1180.09
    /// (unstable) and 1223.80 (stable); at 1201.0765 rad/s, inside that range by 1e-5 rad/s,
    /// the state solved there has a growth rate of -1.1e-6 1/s, within the neutral tolerance:
    /// `stability` says NEUTRAL (undecided), the ranges read STABLE. Both verdicts checked
    /// (a speed well inside the range: STABLE in both), so the comparison is not of two copies
    /// of one word.
    #[test]
    fn the_general_route_s_verdict_at_the_operating_speed_is_stability_s() {
        use crate::command::{Command as _, Output as _};
        let two = include_str!("../../../../examples/spatial_two_plane.toml");
        let mut words = vec![];
        for at in ["1201.0765 rad/s", "1300 rad/s"] {
            let sets = ["spatial.gravity=[0.0, 0.0, 0.0]".to_string(), format!("analysis.operating_speed=\"{at}\"")];
            let mut root = crate::config::parse_text(two, "two.toml").unwrap();
            for s in &sets {
                crate::config::apply_set(&mut root, s).unwrap();
            }
            let cli = crate::stability::Args { config: ConfigSource::tables(root.clone(), "two.toml"), ..Default::default() }.run(&Control::none()).unwrap();
            let first = cli.table().unwrap().lines().next().unwrap().to_string();
            let stable = cli.json().unwrap()["operating"]["stable"].as_bool().unwrap();
            let ctx = super::super::context(&ConfigSource::tables(root, "two.toml"), false, super::super::Kind::User, &Control::none()).unwrap();
            let s = general_route(&ctx).unwrap().unwrap();
            assert_eq!(s.summary[0], verdict_html(stable, &first), "{at}");
            words.push(first.split(" state is ").nth(1).unwrap().split(' ').next().unwrap().to_string());
        }
        assert_eq!(words, ["NEUTRAL", "STABLE"]);
    }

    /// Every figure of the washer's section marks its operating speed (1400 rpm) where that
    /// speed lies on the figure's own axis: 1400 on an rpm axis, 1400·2π/60 = 146.608 on a
    /// rad/s one (walk 27: the Campbell diagram in rpm drew it at 146.6). The expected values
    /// come from the axis title and the config's "1400 rpm", not from the code's factors.
    #[test]
    fn the_operating_speed_is_marked_in_each_figure_s_own_unit() {
        let root = crate::config::parse_text(include_str!("../../../../examples/washing_machine.toml"), "washer.toml").unwrap();
        assert!(include_str!("../../../../examples/washing_machine.toml").contains("operating_speed = \"1400 rpm\""));
        let ctx = super::super::context(&ConfigSource::tables(root, "washer.toml"), false, super::super::Kind::User, &Control::none()).unwrap();
        let s = build_user(&ctx).unwrap().unwrap();
        let mut seen = vec![];
        for f in s.figures() {
            crate::figures::assert_marks_operating_rpm(&f.id, &f.plot, 1400.0);
            seen.push(f.id.clone());
        }
        assert!(seen.iter().any(|id| id == "campbell_modes") && seen.iter().any(|id| id == "stability_margin"), "{seen:?}");
    }

    /// The whole report stopped in that section is written, its output says it is incomplete
    /// and names the section (the CLI then exits 2 with that line, as other stopped commands);
    /// it was an error, no page.
    #[test]
    fn a_report_stopped_in_the_general_route_is_written_and_says_so() {
        let dir = std::env::temp_dir().join(format!("autobal-report-general-stopped-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let out = super::super::write(&planar_ctx(&stop_after(200, 3)), &dir).unwrap();
        let why = out.incomplete.expect("incomplete");
        assert!(why.starts_with("interrupted: the report in ") && why.contains("Exact stability of the stationary state over speed (general route)"), "{why}");
        // (the sections run in parallel: another's count of 200 may stop it first)
        let page = std::fs::read_to_string(out.index).unwrap();
        assert!(page.contains("INCOMPLETE (interrupted: ") && page.contains(" of 200 speeds analysed"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
