//! Section "Rolling resistance": where rolling-resistant balls stop and the unbalance they leave,
//! against the rolling-resistance coefficient and the speed (planar model, paper 004's rotor or
//! the config's `[planar]` rotor), from runs at constant speed ([`autobal::planar::friction`]).

use super::{Ctx, Section};
use crate::num::fmt;
use crate::plot::{Plot, Series, PALETTE};
use anyhow::Result;
use autobal::planar::friction::{residual, Residual};
use autobal::planar::PlanarRotor;
use rayon::prelude::*;

/// Speeds, as multiples of `sqrt(k/m0)`, of the figure's curves.
const SPEED_RATIOS: [f64; 3] = [1.5, 2.0, 3.0];

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let rotor = ctx.planar.as_ref().map_or_else(|| PlanarRotor::paper_004(0.03), |c| c.rotor.clone());
    if rotor.n < 2 || rotor.m3 <= 0.0 {
        return Ok(None);
    }
    let mus: &[f64] = if ctx.quick { &[0.0, 1e-3, 2e-3, 4e-3] } else { &[0.0, 2.5e-4, 5e-4, 1e-3, 1.5e-3, 2e-3, 3e-3, 4e-3] };
    let wn = rotor.natural_frequency();
    let jobs: Vec<(f64, f64)> = SPEED_RATIOS.iter().flat_map(|k| mus.iter().map(move |mu| (k * wn, *mu))).collect();
    let t_end = 40.0;
    let done: Vec<Result<Residual>> = jobs
        .par_iter()
        .map(
            |(w, mu)| {
                if ctx.control.should_stop().is_some() {
                    Err(anyhow::anyhow!("interrupted"))
                } else {
                    residual(&rotor, *w, *mu, t_end).map_err(Into::into)
                }
            },
        )
        .collect();
    let mut s = Section::new("friction", "Rolling resistance: the unbalance real balls leave");
    let mut rows = vec![];
    let mut series = vec![];
    for (i, k) in SPEED_RATIOS.iter().enumerate() {
        let mut pts = vec![];
        for (job, r) in jobs.iter().zip(&done) {
            if (job.0 - k * wn).abs() > 1e-9 * wn {
                continue;
            }
            match r {
                Ok(r) => {
                    pts.push((r.rolling_resistance, 1e6 * r.eccentricity));
                    rows.push(vec![
                        fmt(*k, 3),
                        fmt(r.omega, 4),
                        fmt(r.rolling_resistance, 3),
                        fmt(1e6 * r.eccentricity, 3),
                        fmt(1e6 * r.unbalance, 3),
                        r.at_rest.to_string(),
                        r.stick_slip_transitions.to_string(),
                    ]);
                }
                Err(_) => s.complete = false,
            }
        }
        series.push(Series::new(format!("ω = {k} sqrt(k/m0)"), pts, PALETTE[i]).markers());
    }
    series.push(Series::new("μ_r r", mus.iter().map(|m| (*m, 1e6 * m * rotor.r)).collect(), PALETTE[7]).dashed());
    // margins, so the markers at μ_r = 0 and at the largest μ_r are not cut by the axes
    let mu_max = mus.iter().copied().fold(0.0, f64::max);
    let y_max = series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).filter(|y| y.is_finite()).fold(0.0, f64::max);
    s.p(format!(
        "Balls that roll with resistance stop as soon as every ball can rest: |P| |sin(ψ_j − arg P)| ≤ μ_r (r + P·e^{{iψ_j}}), P the race centre E's offset from the axis (docs/notes/balls.md). The runs hold the rotor ({} balls of {} g on r = {} mm, sqrt(k/m0) = {} rad/s) at constant speed for {} s from balls spread evenly, the shaft started in its steady whirl; the end states are checked against that condition on the closed-form steady whirl (column 'at rest').",
        rotor.n,
        fmt(1e3 * rotor.m3, 3),
        fmt(1e3 * rotor.r, 3),
        fmt(wn, 4),
        t_end
    ));
    s.figure(
        "balls_residual_vs_friction",
        Plot { title: "Residual eccentricity of the balancer against rolling resistance".into(), x_label: "rolling-resistance coefficient μ_r".into(), y_label: "|P| (µm)".into(), series, x_range: Some((-0.04 * mu_max, 1.04 * mu_max)), y_range: (y_max > 0.0).then_some((-0.04 * y_max, 1.06 * y_max)), ..Default::default() },
        "Eccentricity |P| of the race centre E after the balls stopped, against the rolling-resistance coefficient, at three speeds above resonance; dashed: μ_r r. Without friction E ends on the axis (semi-balanced); with it the residual grows about linearly with μ_r and depends little on the speed (the pull on a ball and the friction that holds it both scale with m3 ω²).",
    );
    s.table(&["ω/sqrt(k/m0)", "ω (rad/s)", "μ_r", "|P| (µm)", "residual unbalance (g·mm)", "at rest", "stick-slip transitions"], &rows);
    Ok(Some(s))
}
