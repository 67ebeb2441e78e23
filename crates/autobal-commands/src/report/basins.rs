//! Section "The balls' basins": where the balls end when they start from each pair of angles,
//! at the operating speed. The rotor of the config runs at the constant operating speed
//! (`[drive] kind = "speed"`) for [`REVOLUTIONS`] revolutions from each point of an `n × n`
//! grid of the first two balls' initial angles (the others where the config starts them), as
//! `autobal basins` does ([`autobal::spatial::dynamics::basins`]); a run is balanced when the
//! balls cancel the unbalance at its end (the run-up's criterion).

use super::{Ctx, Section};
use crate::num::fmt;
use anyhow::Result;
use autobal::spatial::dynamics::basins::{angle_grid, basins, check_angle_grid};
use toml::Value;

/// Revolutions of each run at the operating speed (enough for the washer's balls to settle:
/// 64 of 64 runs balanced after 200).
const REVOLUTIONS: f64 = 200.0;
/// Grid points per angle (the quick report: fewer).
const N: usize = 12;
const N_QUICK: usize = 6;

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    const TITLE: &str = "The balls' basins at the operating speed";
    let Some(cfg) = &ctx.spatial else {
        return Ok(Some(Section::not_applicable(
            "basins",
            TITLE,
            "the basins of `autobal basins` are of the spatial rotor's balls; this config has only a [planar] rotor",
        )));
    };
    let Some([_, hi]) = cfg.analysis.operating_speed else {
        return Ok(Some(Section::not_applicable(
            "basins",
            TITLE,
            "the basins are computed at the operating speed, and the config gives none ([analysis] operating_speed = \"1400 rpm\"); `autobal basins --config FILE` computes them at its [drive]",
        )));
    };
    if cfg.model.balls.is_none() || cfg.model.masses.is_some_and(|m| m.n < 2) {
        return Ok(Some(Section::not_applicable(
            "basins",
            TITLE,
            "the basins are over the first two balls' initial angles: the config needs at least two balls",
        )));
    }
    // rad/s for a dimensional config, Ω for a dimensionless one (the drive's speed unit)
    let w = hi * cfg.model.scale.map_or(1.0, |s| s.omega0);
    let t_end = REVOLUTIONS * std::f64::consts::TAU / w;
    let mut root = ctx.root.clone();
    let mut d = toml::Table::new();
    d.insert("kind".into(), Value::String("speed".into()));
    d.insert("omega0".into(), Value::Float(w));
    d.insert("t_end".into(), Value::Float(t_end));
    if let Some(p) = root.get("drive").and_then(Value::as_table).and_then(|t| t.get("psi0")) {
        d.insert("psi0".into(), p.clone());
    }
    root.insert("drive".into(), Value::Table(d));
    let ig = root.entry("integration").or_insert_with(|| Value::Table(toml::Table::new()));
    if let Some(t) = ig.as_table_mut() {
        t.entry("dt").or_insert(Value::Float(t_end / 200.0));
    }
    let mut s = Section::new("basins", TITLE);
    let sim = match crate::spatial_sim::build(&root, &ctx.source) {
        Ok(sim) => sim,
        Err(e) => {
            s.p(format!("Not computed: {}.", super::esc(&format!("{e:#}"))));
            return Ok(Some(s));
        }
    };
    let n = if ctx.quick { N_QUICK } else { N };
    check_angle_grid(&sim.rotor, n, "n")?;
    let cases = angle_grid(&sim.initial, &sim.drive, n, n);
    let t0 = std::time::Instant::now();
    let out = basins(&sim.rotor, &cases, &sim.settings, &ctx.control)?;
    let wall = t0.elapsed().as_secs_f64();
    let stopped = out.stopped.is_some();
    // the command's output, and its figure (`crate::basins::Output::plot`, as Python draws it)
    let out = crate::basins::Output {
        angles: cases.iter().map(|c| [c.initial.psi[0], c.initial.psi[1]]).collect(),
        ends: out.value,
        wall,
        written: None,
        svg: None,
        linear: None,
        rtol: Some(sim.settings.rtol),
    };
    let done: Vec<_> = out.ends.iter().flatten().collect();
    s.complete = done.len() == cases.len() && !stopped;
    let balanced = done.iter().filter(|r| r.balanced).count();
    let (lu, ls) = if cfg.dimensional { ("mm", 1e3) } else { ("ρ_s", 1.0) };
    let worst = done.iter().map(|r| r.final_amplitude).fold(0.0, f64::max);
    let speed = if cfg.dimensional { format!("{} rpm", crate::num::grouped(w * crate::num::RPM_PER_RAD_S, 0)) } else { format!("Ω = {}", fmt(w, 4)) };
    s.p(format!(
        "The rotor held at the operating speed {speed} for {} revolutions ({} {}), the first two balls started from each point of a {n} × {n} grid of angles (the others where the config starts them), as <code>autobal basins</code> runs it ({} s here). <b>{balanced} of {} runs end balanced</b>; the largest final whirl at the balancer plane is {} {lu}.",
        REVOLUTIONS,
        fmt(t_end, 3),
        if cfg.dimensional { "s" } else { "τ" },
        fmt(wall, 2),
        done.len(),
        fmt(ls * worst, 3)
    ));
    s.summary.push(format!("At {speed}, {balanced} of {} starts of the balls (a {n} × {n} grid of the first two balls' angles) end balanced.", done.len()));
    let plot = out.plot();
    s.figure(
        "basins",
        plot,
        format!("Each cell one run at {speed}: green where the balls end balancing the rotor, orange where they do not after {REVOLUTIONS} revolutions (slow to settle, or caught elsewhere; grey: not run, interrupted). Angles from the unbalance direction."),
    );
    Ok(Some(s))
}
