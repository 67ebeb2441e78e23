//! Section "Design maps" of the report about the user's rotor: the exact stability of the
//! balanced state over speed against the three things a designer of a ball balancer chooses,
//! the position of the balancer plane, the mass of a ball and the drag on the balls, each
//! around the config's own value, with the operating speed and the config's value marked.
//!
//! Each map is the library's stability map ([`autobal::spatial::map::stability_map_units`],
//! the one `autobal map` runs) over the config's own parameter path (`balancer.z`,
//! `balancer.ball_mass`, `balancer.drag` of a dimensional config, `dimensionless.z_a`, `.m`,
//! `.h_s` of a dimensionless one) and the speed (`speed_rpm`, or `omega`), so a map's row at the
//! config's value is the stability section's margin line. A dimensional map's growth rate is
//! `max Re λ · ω0` in 1/s, with the `ω0 = sqrt(c_x/M_s)` of each column (a ball's mass moves it).
//!
//! A config that model does not represent (two planes, gravity, supports that differ by
//! direction, a planar rotor) gets the same maps by the general map
//! ([`autobal::rotor_map::general_map`], the one `autobal map` runs for it) on the rotor as
//! given: the stationary state (an equilibrium, or the periodic orbit of the revolution) and its
//! eigenvalues or Floquet multipliers at every cell; the planar rotor over its ball mass and
//! drag (`planar.m3`, `planar.c_psi`).

use super::{rotor::operating_vlines, Ctx, Section};
use crate::map::{MapResult, Quantity};
use crate::num::{fmt, RPM_PER_RAD_S};
use crate::plot::{ColorScale, Series};
use anyhow::Result;
use autobal::paths::Axis;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::map::{MapSettings, ModelFamily};
use autobal::spatial::paths::SpatialSpec;

/// Grid of the maps per axis (the quick report: fewer).
const MAP_N: usize = 121;
const MAP_N_QUICK: usize = 41;

/// One design map: the parameter path, its range, the title and what it shows.
struct Design {
    path: &'static str,
    lo: f64,
    hi: f64,
    title: &'static str,
    what: &'static str,
}

/// The three maps around the config's values (a map whose parameter is zero or unknown is left
/// out, with the reason).
fn designs(spec: &SpatialSpec, si: bool) -> (Vec<Design>, Vec<String>) {
    let get = |p: &str| spec.get(p).ok().filter(|v| v.is_finite());
    let (z, m, h) = if si { ("balancer.z", "balancer.ball_mass", "balancer.drag") } else { ("dimensionless.z_a", "dimensionless.m", "dimensionless.h_s") };
    let mut out = vec![];
    let mut skipped = vec![];
    // the balancer plane: between the supports (SI), or over 003 Fig. 5a's −2 … 2 (ρ_s)
    let zv = get(z);
    let (zlo, zhi) = if si {
        match (get("supports.z_left"), get("supports.z_right")) {
            (Some(a), Some(b)) if b > a => (a.min(zv.unwrap_or(a)), b.max(zv.unwrap_or(b))),
            _ => (zv.unwrap_or(0.0) - 0.5, zv.unwrap_or(0.0) + 0.5),
        }
    } else {
        ((-2.0f64).min(zv.unwrap_or(0.0) - 0.5), 2.0f64.max(zv.unwrap_or(0.0) + 0.5))
    };
    out.push(Design {
        path: z,
        lo: zlo,
        hi: zhi,
        title: "Design map: balancer position × speed",
        what: if si {
            "over the axial position of the balancer plane between the supports"
        } else {
            "over the position of the balancer plane z̄_A (from the centre of mass, in ρ_s)"
        },
    });
    match get(m) {
        Some(v) if v > 0.0 => out.push(Design {
            path: m,
            lo: 0.25 * v,
            hi: 3.0 * v,
            title: "Design map: ball mass × speed",
            what: "over the mass of one ball, from a quarter to three times the config's",
        }),
        _ => skipped.push(format!("ball mass: the config gives no ball mass ({m})")),
    }
    match get(h) {
        Some(v) if v > 0.0 => out.push(Design {
            path: h,
            lo: 0.1 * v,
            hi: 5.0 * v,
            title: "Design map: ball drag × speed",
            what: "over the drag on the balls, from a tenth to five times the config's",
        }),
        _ => skipped.push(format!("ball drag: the config's drag is zero or not given ({h}); a map around zero has no scale")),
    }
    (out, skipped)
}

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    if crate::general::needs_general_verdict(&ctx.root) {
        return general(ctx);
    }
    let Some(cfg) = &ctx.spatial else {
        return Ok(Some(Section::not_applicable(
            "design",
            "Design maps",
            "the design maps (balancer position, ball mass, ball drag against speed) use the spatial model of papers 000/003; a [planar] rotor's parameters are swept with `autobal sweep`",
        )));
    };
    let m = &cfg.model;
    let si = cfg.spec.get("balancer.z").is_ok();
    let mut s = Section::new("design", "Design maps: balancer position, ball mass, ball drag");
    let ignored = autobal::config::ignored_by_linear_model(&ctx.root);
    let balls = if m.balls.is_some() { Balls::Free } else { Balls::Locked };
    s.p(format!(
        "The exact stability of the balanced state (the margin of the stability section, balls {}) over the speed and one design parameter at a time, the others the config's. Colour: the largest real part of the eigenvalues (blue stable, red unstable, white near zero, square-root scale on each side); solid black: the stability boundary between cells of different exact verdicts (the boundary lies within a cell of it); dashed: 003's necessary condition; the vertical line is the config's value, the horizontal one the operating speed; grey: no balanced state there (too little ball mass to cancel the unbalance) or a row not computed.{}",
        if balls == Balls::Free { "free" } else { "locked" },
        if ignored.is_empty() {
            String::new()
        } else {
            format!(
                " <b>These maps are of the one-plane rotor of papers 000/003, which leaves out {}</b>: a guide to the trends; the verdict is the stability section's (general route).",
                super::esc(&ignored.join(", "))
            )
        }
    ));
    let w = crate::linear::omega_max(cfg, None)?;
    let w0 = m.scale.map(|sc| sc.omega0);
    let n = if ctx.quick { MAP_N_QUICK } else { MAP_N };
    // the speed axis in rpm for a dimensional config (ω0 per column, as `autobal map`), else Ω
    let (ykey, yk) = match (si, w0) {
        (true, Some(w0)) => ("speed_rpm", w0 * RPM_PER_RAD_S),
        _ => ("omega", 1.0),
    };
    let (list, skipped) = designs(&cfg.spec, si);
    for d in list {
        if stopped_before(ctx, &mut s, d.title) {
            continue;
        }
        let x = Axis::linspace(d.path, d.lo, d.hi, n);
        let y = Axis::linspace(ykey, 0.02 * w * yk, w * yk, n);
        let r = match map(&cfg.spec, x, y, balls, &ctx.control) {
            Ok(r) => r,
            Err(e) => {
                s.p(format!("{}: not computed ({}).", d.title, super::esc(&format!("{e:#}"))));
                continue;
            }
        };
        let complete = r.rows.iter().all(|r| r.is_some());
        s.complete &= complete;
        let mut p = crate::map::plot(&r, d.title);
        if ykey == "speed_rpm" {
            // Re λ in 1/s: units of each column's ω0
            let k: Vec<f64> =
                r.x.values
                    .iter()
                    .map(|&v| cfg.spec.with(d.path, v).and_then(|f| f.model()).map_or(f64::NAN, |m| m.scale.map_or(f64::NAN, |s| s.omega0)))
                    .collect();
            if let Some(h) = p.heatmap.as_mut() {
                for row in h.z.iter_mut() {
                    row.iter_mut().zip(&k).for_each(|(v, k)| *v *= k);
                }
                let neg = h.z.iter().flatten().filter(|v| **v < 0.0).map(|v| -v).fold(1e-12, f64::max);
                let pos = h.z.iter().flatten().filter(|v| **v >= 0.0).copied().fold(1e-12, f64::max);
                h.scale = ColorScale::Diverging { neg, pos };
                h.label = "max Re λ (1/s; < 0 stable)".into();
            }
        }
        if let Ok(v) = cfg.spec.get(d.path) {
            p.vlines.push((v, "this rotor".into()));
        }
        for (y, label) in operating_vlines(cfg.analysis.operating_speed, yk) {
            p.series.push(Series::new(label, vec![(d.lo, y), (d.hi, y)], "#E69F00").width(1.5));
        }
        s.figure(
            format!("design_{}", d.path.replace('.', "_")),
            p,
            format!(
                "Stability map {} and the speed{}.{}",
                d.what,
                if ykey == "speed_rpm" { " (rpm)" } else { " (Ω)" },
                if complete { "" } else { " <b>Interrupted: grey rows were not computed.</b>" }
            ),
        );
    }
    for why in skipped {
        s.p(format!("Not drawn: {}.", super::esc(&why)));
    }
    s.p(format!(
        "Other parameters: <code>autobal map --config FILE --x PATH=LO:HI:N --y {ykey}={}:{}:{n}</code> (docs/notes/stability.md lists the paths).",
        fmt(0.02 * w * yk, 4),
        fmt(w * yk, 4)
    ));
    Ok(Some(s))
}

/// The library's map over `x` and the speed `y` (rows not computed when Ctrl-C came: `None`).
/// Whether the report was stopped before the map `title` started: then it is not computed,
/// said in the section, which is incomplete.
fn stopped_before(ctx: &Ctx, s: &mut Section, title: &str) -> bool {
    if ctx.control.should_stop().is_none() {
        return false;
    }
    s.p(format!("{title}: not computed (the report was stopped before it)."));
    s.complete = false;
    true
}

fn map(spec: &SpatialSpec, x: Axis, y: Axis, balls: Balls, control: &autobal::control::Control) -> Result<MapResult> {
    let settings = MapSettings { balls, quantity: Quantity::Margin, omega: None };
    let mut rows = vec![None; y.values.len()];
    autobal::spatial::map::stability_map_units(spec, &x, &y, &settings, control, &mut |j, cells| {
        rows[j] = Some(cells.to_vec());
        true
    })?;
    Ok(MapResult { x, y, rows, quantity: Quantity::Margin })
}

/// Grid of the general maps per axis: (equilibrium, periodic orbit), full and quick; 0: not
/// drawn. A periodic orbit's cell is a shooting over one revolution with its variational
/// equations (measured on examples/spatial_two_plane.toml: 3 maps of 21 x 21 cost 90 s of CPU
/// in a dev build), so the quick report leaves those maps out and says so.
const GENERAL_N: [(usize, usize); 2] = [(121, 41), (21, 0)];

/// A number of the config by its path (`balancer.z`), if it is one.
fn number(root: &toml::Table, path: &str) -> Option<f64> {
    let (table, key) = path.split_once('.')?;
    match root.get(table)?.get(key)? {
        toml::Value::Float(v) => Some(*v),
        toml::Value::Integer(v) => Some(*v as f64),
        _ => None,
    }
}

/// The design maps of the rotor as given, by the general map (module docs).
fn general(ctx: &Ctx) -> Result<Option<Section>> {
    use autobal::rotor_map::{general_map, Verdict};
    let g = crate::general::rotor_of(&ctx.root)?;
    let planar = matches!(g.rotor, autobal::rotor_stability::Rotor::Planar(_));
    let periodic = g.rotor.is_periodic();
    let mut s = Section::new("design", "Design maps: balancer position, ball mass, ball drag");
    let what = autobal::config::ignored_by_linear_model(&ctx.root);
    s.p(format!(
        "The exact stability of the {} over the speed and one design parameter at a time, the others the config's, by the general map on the rotor as given{} (what <code>autobal map</code> computes for this config): at every cell the stationary state from the nonlinear equations and its {}. Colour: the {} (blue stable, red unstable, white near zero, square-root scale on each side), per unit {}; solid black: the stability boundary; the vertical line is the config's value{}; blank: no stationary state found there (too little ball mass to cancel the unbalance) or a row not computed.",
        if periodic { "stationary periodic orbit" } else { "balanced state" },
        if planar { " (the planar rotor)".to_string() } else if what.is_empty() { String::new() } else { format!(" (with {})", super::esc(&what.join(", "))) },
        if periodic { "Floquet multipliers (monodromy matrix over a revolution)" } else { "eigenvalues (exact Jacobian)" },
        if periodic { "largest Floquet exponent ln|μ|/T" } else { "largest real part of the eigenvalues" },
        if planar { "time (1/s)" } else if g.si { "τ = ω0 t (ω0 of the column's rotor)" } else { "τ = ω0 t" },
        if planar { "" } else { ", the horizontal one the operating speed" }
    ));
    let omega_max = crate::general::default_omega_max(&g, &ctx.root)?;
    let n = {
        let (full, quick) = GENERAL_N[usize::from(periodic)];
        if ctx.quick {
            quick
        } else {
            full
        }
    };
    // the speed axis: rpm for an SI spatial config, else `omega` (Ω; rad/s for the planar rotor)
    let (ykey, yk) = if g.si && !planar { ("speed_rpm", RPM_PER_RAD_S) } else { ("omega", 1.0) };
    let mut list = vec![];
    let mut skipped = vec![];
    let get = |p: &str| number(&ctx.root, p).filter(|v| v.is_finite());
    if planar {
        for (path, title, what, lo, hi) in [
            ("planar.m3", "Design map: ball mass × speed", "over the mass of one ball, from a quarter to three times the config's", 0.25, 3.0),
            ("planar.c_psi", "Design map: ball drag × speed", "over the drag on the balls, from a tenth to five times the config's", 0.1, 5.0),
        ] {
            match get(path) {
                Some(v) if v > 0.0 => list.push(Design { path, lo: lo * v, hi: hi * v, title, what }),
                _ => skipped.push(format!("{path}: zero or not given; a map around zero has no scale")),
            }
        }
    } else {
        let spec = ctx.spatial.as_ref().map(|c| &c.spec);
        match spec {
            Some(spec) => {
                let (l, sk) = designs(spec, g.si);
                list = l;
                skipped = sk;
            }
            None => skipped.push("the config's balancer parameters could not be read".into()),
        }
    }
    let op = if planar {
        None
    } else {
        autobal::config::spatial(&ctx.root).ok().and_then(|c| c.analysis.operating_speed).map(|[a, b]| [a * g.omega0, b * g.omega0])
    };
    if n == 0 {
        s.p(format!(
            "Not drawn in the quick report: the stationary state is a periodic orbit, and each cell of a map costs a shooting over one revolution; the full report draws {} × {} cells, <code>autobal map</code> any grid.",
            GENERAL_N[1].0, GENERAL_N[1].0
        ));
        list.clear();
    }
    for d in list {
        // stopped (Ctrl-C) during an earlier map: the later ones are not started (each built
        // its rotors and solved its first cell before it asked the control: ~1 s of the
        // washer's stop, review 24c)
        if stopped_before(ctx, &mut s, d.title) {
            continue;
        }
        let x = Axis::linspace(d.path, d.lo, d.hi, n);
        let y = Axis::linspace(ykey, 0.02 * omega_max * yk, omega_max * yk, n);
        let mut rows: Vec<Option<Vec<autobal::rotor_map::GeneralCell>>> = vec![None; y.values.len()];
        let outcome = general_map(&ctx.root, &x, &y, None, &ctx.control, &mut |j, cells| {
            rows[j] = Some(cells.to_vec());
            true
        });
        if let Err(e) = outcome {
            s.p(format!("{}: not computed ({}).", d.title, super::esc(&e.to_string())));
            continue;
        }
        let complete = rows.iter().all(|r| r.is_some());
        s.complete &= complete;
        let cells: Vec<Option<Vec<crate::map::Cell>>> = rows
            .iter()
            .map(|r| {
                r.as_ref()
                    .map(|r| r.iter().map(|c| crate::map::Cell { margin: c.margin, stable: c.verdict == Some(Verdict::Stable), necessary: false }).collect())
            })
            .collect();
        let r = MapResult { x, y, rows: cells, quantity: Quantity::Margin };
        let mut p = crate::map::plot(&r, d.title);
        // no 003 necessary condition off the 12-state model
        p.series.retain(|se| se.label != crate::map::NECESSARY_EDGE_LABEL);
        if let Some(h) = p.heatmap.as_mut() {
            // cells without a stationary state stay blank
            for (zr, kr) in h.z.iter_mut().zip(&rows) {
                if let Some(kr) = kr {
                    for (z, c) in zr.iter_mut().zip(kr) {
                        if c.verdict.is_none() {
                            *z = f64::NAN;
                        }
                    }
                }
            }
            h.label = format!("{} ({}; < 0 stable)", if periodic { "largest Floquet exponent" } else { "max Re λ" }, if planar { "1/s" } else { "per unit τ" });
        }
        if planar {
            p.y_label = "speed ω (rad/s)".into();
        }
        if let Some(v) = get(d.path) {
            p.vlines.push((v, "this rotor".into()));
        }
        for (yv, label) in operating_vlines(op, yk) {
            p.series.push(Series::new(label, vec![(d.lo, yv), (d.hi, yv)], "#E69F00").width(1.5));
        }
        s.figure(
            format!("design_{}", d.path.replace('.', "_")),
            p,
            format!(
                "Stability map {} and the speed{}, by the general route on the rotor as given.{}",
                d.what,
                if ykey == "speed_rpm" {
                    " (rpm)"
                } else if planar {
                    " (rad/s)"
                } else {
                    " (Ω)"
                },
                if complete { "" } else { " <b>Interrupted: grey rows were not computed.</b>" }
            ),
        );
    }
    for why in skipped {
        s.p(format!("Not drawn: {}.", super::esc(&why)));
    }
    s.p(format!(
        "Other parameters: <code>autobal map --config FILE --x PATH=LO:HI:N --y {ykey}={}:{}:{n}</code> (docs/notes/stability.md lists the paths).",
        fmt(0.02 * omega_max * yk, 4),
        fmt(omega_max * yk, 4)
    ));
    Ok(Some(s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::ConfigSource;
    use autobal::control::Control;

    /// Stopped (Ctrl-C) during its first map, the section does not start the next: paper 004's
    /// planar example in the quick report (two general maps of 41 × 41 cells), a control that
    /// stops once the first map reported 2 of its 41 rows. The second map is said not computed
    /// and has no figure (it built its rotors and solved its first cell before it asked the
    /// control, then drew an all-grey map: review 24c's washer took ~1 s more to stop for
    /// it); the first keeps its rows. Not stopped, both maps are drawn.
    #[test]
    fn a_stop_starts_no_further_map() {
        let root = crate::config::parse_text(include_str!("../../../../examples/planar.toml"), "planar.toml").unwrap();
        let ctx =
            |control: &Control| super::super::context(&ConfigSource::tables(root.clone(), "planar.toml"), true, super::super::Kind::User, control).unwrap();
        let control = Control::new();
        let c = control.clone();
        let control = control.with_progress(move |p| {
            if p.total == 41 && p.done >= 2 {
                c.cancel();
            }
        });
        let s = build(&ctx(&control)).unwrap().unwrap();
        assert!(!s.complete);
        let html: String = s.blocks.iter().filter_map(|b| if let super::super::Block::Html(h) = b { Some(h.as_str()) } else { None }).collect();
        assert!(html.contains("Design map: ball drag × speed: not computed (the report was stopped before it)."), "{html}");
        assert_eq!(s.figures().count(), 1);
        let whole = build(&ctx(&Control::none())).unwrap().unwrap();
        assert!(whole.complete && whole.figures().count() == 2);
    }
}
