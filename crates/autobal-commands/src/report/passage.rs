//! Section "Your rotor's passage": with a `[planar]` table the config's own rotor (paper 004
//! model) is simulated with its own drive, instead of only the paper's rotor.

use super::paper004::{run_all, runs_table, Run};
use super::{Ctx, Section};
use crate::num::fmt;
use anyhow::Result;
use autobal::planar::stationary::capacity_ratio;

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let Some(cfg) = &ctx.planar else {
        return Ok(Some(Section::not_applicable(
            "passage",
            "Your rotor's passage through resonance",
            "the rotor's passage (paper 004's planar model) needs a [planar] config: not applicable to a spatial rotor, whose run-up is the section \"Run-up\"",
        )));
    };
    let runs = vec![Run {
        tag: "config".into(),
        label: format!("{:?} drive", cfg.drive).split(['{', '(']).next().unwrap_or("drive").trim().to_lowercase(),
        sets: vec![],
    }];
    let done = run_all(&runs, Some(&ctx.root), &ctx.control)?;
    let d = &done[0];
    let p = &d.cfg.rotor;
    let mut s = Section::new("passage", "Your rotor's passage through resonance (paper 004 model)");
    s.complete = !d.cut();
    let alpha = capacity_ratio(p);
    s.p(format!(
        "The planar rotor of the config's <code>[planar]</code> table with its <code>[drive]</code>: total mass {} kg, sqrt(k/m0) = {} rad/s ({} rpm), {} balls of {} g on a race of radius {} mm; capacity ratio α∞ = {} ({}).",
        fmt(p.total_mass(), 4),
        fmt(p.natural_frequency(), 4),
        crate::num::grouped(p.natural_frequency() * crate::num::RPM_PER_RAD_S, 0),
        p.n,
        fmt(1e3 * p.m3, 3),
        fmt(1e3 * p.r, 3),
        fmt(alpha, 3),
        if alpha > 1.0 { "the balls can balance at high speed" } else { "too little ball mass to balance" }
    ));
    let (head, rows) = runs_table(&runs, &done);
    s.table(&head, &rows);
    for (suffix, plot) in crate::sim::plots(&d.cfg, &d.env, "Your rotor") {
        let caption = match suffix.as_str() {
            "amplitude_omega" => "Whirl radius of the shaft point C against the speed, with the stationary whirls (balls held; semi-balanced, radius s2; balls free on the far or near side).",
            "amplitude_t" => "Whirl radius of C against time.",
            "psi_t" => "Ball angles relative to CG, wrapped to ±180°.",
            _ => "Speed against time, with sqrt(k/m0).",
        };
        s.figure(format!("passage_{suffix}"), plot, caption);
    }
    Ok(Some(s))
}
