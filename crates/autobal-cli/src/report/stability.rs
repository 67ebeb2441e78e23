//! Section "Exact linear stability" of the config's spatial rotor: Campbell diagrams, the
//! margin along the speed against 003's necessary ranges, the papers' three layouts, and
//! stability maps in the layouts of 003's Figs 4, 5a, 5b around this rotor.

use super::{interrupted, rotor::ranges_text_in, Ctx, Section};
use crate::figures::{campbell_plots, margin_plot, omega_limit, with_layout, SpeedUnit};
use crate::linear;
use crate::map::{Axis, MapResult, Quantity};
use crate::num::fmt;
use anyhow::Result;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::map::{stability_map, MapSettings, ModelFamily};
use autobal::spatial::params::SpatialModel;

/// Grid of the report's maps (per axis).
const MAP_N: usize = 121;

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let Some(cfg) = &ctx.spatial else { return Ok(None) };
    let m = &cfg.model;
    let w0 = m.scale.map(|s| s.omega0);
    let mut s = Section::new("stability", "Exact linear stability of the balanced state (your rotor)");
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
    let (rot, fixed) = campbell_plots(m, &c);
    s.figure(
        "campbell_fixed",
        fixed,
        "Campbell diagram in fixed axes: whirl frequency of each tracked eigenvalue (forward above zero, backward below; legend: the motion that dominates the mode and its whirl). A mode whirls in fixed axes at Ω + ν (solid) and Ω − ν (dashed), ν its frequency seen from the rotor; a component is drawn where it carries at least 10 % of the mode's motion, so curves start and stop where a whirl turns circular. Clicking a legend entry hides both components. Also drawn: the synchronous 1× line, and the analytic critical speeds K1-K4 of the locked rotor. Where a mode crosses 1× near a K line the locked rotor is at a critical speed.",
    );
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
            Axis { key: "dimensionless.c_sigma".into(), lo: 0.2, hi: 2.0, n: MAP_N },
            |m, v| m.c_sigma = v,
            "in the layout of 003 Fig. 4: over the rotor type C̄Σ (long &lt; 1 &lt; short) and the speed",
        ),
        (
            "stability_map_z_a",
            "Stability map z̄_A × speed",
            Axis { key: "dimensionless.z_a".into(), lo: -2.0, hi: 2.0, n: MAP_N },
            |m, v| m.z_a = v,
            "in the layout of 003 Fig. 5a: over the position of the balancer plane z̄_A and the speed",
        ),
        (
            "stability_map_delta_a0",
            "Stability map ΔĀ0 × speed",
            Axis { key: "dimensionless.delta_a".into(), lo: 0.0, hi: 0.24, n: MAP_N },
            |m, v| {
                m.anisotropy.used = v;
                m.delta_a0 = v;
            },
            "in the layout of 003 Fig. 5b: over the anisotropy (ΔĀ = ΔĀ0, given directly as in 003's examples) and the speed",
        ),
    ];
    for (stem, title, x, set, what) in maps {
        let y = Axis { key: "omega".into(), lo: 0.02 * w, hi: w, n: MAP_N };
        let r = map(m, x, y, set, balls)?;
        let complete = r.rows.iter().all(|r| r.is_some());
        s.complete &= complete;
        let mut p = crate::mapfig::plot(&r, title);
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
                "Stability map {what}: largest real part of the eigenvalues (colour bar: blue stable, red unstable, white near zero, square-root scale on each side), the exact stability boundary (solid black) and the boundary of 003's necessary condition (dashed). The other parameters are this rotor's.{}",
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
fn map(m: &SpatialModel, x: Axis, y: Axis, set: fn(&mut SpatialModel, f64), balls: Balls) -> Result<MapResult> {
    let family = Varied { model: m, path: &x.key, set, value: None };
    let settings = MapSettings { balls, quantity: Quantity::Margin, omega: None };
    let mut rows = vec![None; y.n];
    stability_map(&family, &x.to_library(), &y.to_library(), &settings, &mut |j, cells| {
        rows[j] = Some(cells.to_vec());
        !interrupted()
    })?;
    Ok(MapResult { x, y, rows, quantity: Quantity::Margin })
}
