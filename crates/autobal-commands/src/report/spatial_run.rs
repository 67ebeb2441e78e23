//! Section "Your rotor in time": the config's spatial rotor (papers 000/003 model) simulated
//! with its balls by the nonlinear spatial model (docs/notes/spatial.md): its own `[drive]` when the
//! config has one for this rotor, else a run-up at constant acceleration from rest through its
//! critical speeds. The whirl radius at the balancer plane against speed is drawn beside the
//! stationary curve of the rotor with the balls held where they start; SI (mm, rad/s) for a
//! dimensional config.

use super::{Ctx, Section};
use crate::num::{fmt, grouped, RPM_PER_RAD_S};
use crate::spatial_sim;
use anyhow::Result;
use autobal::spatial::critical_speeds::critical_speeds;
use toml::Value;

/// Revolutions of the default run-up (the quick report: fewer).
const REVOLUTIONS: f64 = autobal::config::DEFAULT_RUN_UP_REVOLUTIONS;
const REVOLUTIONS_QUICK: f64 = 300.0;

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let Some(cfg) = &ctx.spatial else {
        return Ok(Some(Section::not_applicable(
            "spatial-run",
            "Run-up",
            "the run-up of the spatial model needs a spatial rotor; a [planar] rotor's run is the section \"Your rotor's passage\"",
        )));
    };
    let m = &cfg.model;
    let w0 = m.scale.map_or(1.0, |s| s.omega0);
    let mut root = ctx.root.clone();
    // a [drive] beside [planar] is the planar rotor's: this rotor then gets the default run-up
    let own_drive = ctx.planar.is_none() && root.contains_key("drive");
    let crit = critical_speeds(m);
    let revolutions = if ctx.quick { REVOLUTIONS_QUICK } else { REVOLUTIONS };
    if !own_drive {
        // the library's run-up from rest through the critical speeds (the one `simulate` runs
        // for a config without [drive]), in fewer revolutions for the quick report
        let (d, ig) = autobal::config::default_run_up(m, cfg.analysis.run_up_end(), &toml::Table::new(), revolutions);
        root.insert("drive".into(), Value::Table(d));
        root.insert("integration".into(), Value::Table(ig));
    }
    let title = match (ctx.kind, own_drive, cfg.analysis.operating_speed.is_some()) {
        (super::Kind::User, false, true) => "Run-up to the operating speed (nonlinear spatial model)",
        (super::Kind::User, _, _) => "Run-up (nonlinear spatial model)",
        _ => "Your rotor in time (nonlinear spatial model)",
    };
    let mut s = Section::new("spatial-run", title);
    let sim = match spatial_sim::build(&root, &ctx.source) {
        Ok(sim) => sim,
        Err(e) => {
            s.p(format!("Not simulated: {}.", super::esc(&format!("{e:#}"))));
            return Ok(Some(s));
        }
    };
    let (summary, kept, wall) = spatial_sim::run_to_csv(&sim, &mut std::io::sink(), false, &ctx.control)?;
    s.complete = summary.stopped.is_none();
    let (lu, ls, speed_unit) = if cfg.dimensional { ("mm", 1e3, "rad/s") } else { ("ρ_s", 1.0, "(Ω)") };
    let rpm = |w: f64| if cfg.dimensional { format!(" ({} rpm)", grouped(w * RPM_PER_RAD_S, 0)) } else { String::new() };
    let drive_text = if own_drive {
        "with the config's own <code>[drive]</code>".to_string()
    } else {
        format!(
            "run up from rest at constant acceleration through its critical speeds to {} {speed_unit}{} in {} revolutions (the config has no <code>[drive]</code> for it; give one to simulate your own)",
            fmt(sim.drive.kinematics(sim.settings.t_end).0, 4),
            rpm(sim.drive.kinematics(sim.settings.t_end).0),
            revolutions
        )
    };
    let one_plane = crit.speeds.iter().map(|c| format!("{} {speed_unit}{}", fmt(c.omega * w0, 4), rpm(c.omega * w0))).collect::<Vec<_>>().join(", ");
    // the critical speeds of the rotor simulated: paper 000's closed form where it is that
    // rotor, else the rotor as given by the general route (`autobal critical`'s locked speeds)
    let left_out = autobal::config::ignored_by_linear_model(&ctx.root);
    let critical = if left_out.is_empty() {
        format!("The critical speeds of the balanced rotor (linear analysis) are {one_plane}.")
    } else {
        let g = crate::general::rotor_of(&ctx.root)?;
        let omega_max = crate::general::default_omega_max(&g, &ctx.root)?;
        let model = format!("the one-plane isotropic model of papers 000/003, which leaves out {}, has {one_plane}", left_out.join(", "));
        match autobal::rotor_campbell::locked_critical_speeds(&g.rotor, omega_max, 2000) {
            Ok(l) => format!(
                "The critical speeds of the rotor as given, its balls held at balance (general route, as <code>autobal critical</code> and the first section), are {} ({}).",
                if l.speeds.is_empty() {
                    crate::general_campbell::no_critical_speed_words(&l, &format!("{} {speed_unit}{}", fmt(omega_max, 4), rpm(omega_max)))
                } else {
                    l.speeds.iter().map(|k| format!("{} {speed_unit}{}", fmt(k.omega, 4), rpm(k.omega))).collect::<Vec<_>>().join(", ")
                },
                super::esc(&model)
            ),
            Err(autobal::Error::NoLinearisation { .. }) => format!(
                "The rotor as given has no critical speeds defined by one frequency (its linearisation turns in fixed and in rotating axes: the Floquet Campbell diagram of the stability section); {}.",
                super::esc(&model)
            ),
            Err(e) => return Err(e.into()),
        }
    };
    s.p(format!(
        "The rotor of the config simulated in time with its {} balls free on their race (full nonlinear equations: translation, tilt, spin and balls; docs/notes/spatial.md), {drive_text}. The balls start spread evenly across the unbalance unless <code>drive.psi0</code> says otherwise. {critical}",
        sim.rotor.balls(),
    ));
    let t_unit = if cfg.dimensional { "s" } else { "τ" };
    let rows = vec![
        vec![
            "peak whirl radius at the balancer plane".into(),
            format!("{} {lu}", fmt(ls * summary.peak_amplitude, 4)),
            format!("at {} {speed_unit}{}, t = {} {t_unit}", fmt(summary.omega_at_peak, 4), rpm(summary.omega_at_peak), fmt(summary.t_at_peak, 4)),
        ],
        vec![
            "final whirl radius".into(),
            format!("{} {lu}", fmt(ls * summary.final_amplitude, 4)),
            format!("at {} {speed_unit}{}", fmt(summary.final_omega, 4), rpm(summary.final_omega)),
        ],
        vec![
            "residual unbalance (balls + unbalance)".into(),
            fmt(summary.residual_unbalance, 3),
            format!("of the unbalance alone: {}", if summary.balanced { "balanced" } else { "not balanced" }),
        ],
        vec!["integration".into(), format!("{} steps", summary.steps), format!("{} right-hand sides, {} s", summary.rhs_evaluations, fmt(wall, 3))],
    ];
    s.table(&["quantity", "value", "note"], &rows);
    if summary.stopped.is_none() {
        let at = |w: f64| if cfg.dimensional { format!("{} rpm", grouped(w * RPM_PER_RAD_S, 0)) } else { format!("Ω = {}", fmt(w, 4)) };
        s.summary.push(format!(
            "The run-up ({}) peaks at <b>{} {lu} at {}</b>; at its end ({}) the whirl is {} {lu}, {}.",
            if own_drive { "the config's <code>[drive]</code>".to_string() } else { format!("from rest to {}", at(summary.final_omega)) },
            fmt(ls * summary.peak_amplitude, 3),
            at(summary.omega_at_peak),
            at(summary.final_omega),
            fmt(ls * summary.final_amplitude, 3),
            if summary.balanced {
                "the balls balance the rotor".to_string()
            } else {
                // why, as `simulate` says it (walk 27: the report said STABLE in the stability
                // section and "not balanced" here, without the run's own warning); and what the
                // stability verdict does not say
                let why = spatial_sim::warnings(&summary).first().map_or(String::new(), |w| format!(" ({})", super::esc(w)));
                format!("the balls have not balanced the rotor{why}; a STABLE verdict of the balanced state (the stability section) is a linear one: it says the balls stay balanced once near that state, not that a run reaches it")
            }
        ));
        for w in &spatial_sim::warnings(&summary) {
            s.p(format!("Warning: {}.", super::esc(w)));
        }
    } else {
        s.summary.push("The run-up was cut short: no peak to report.".into());
    }
    if let Some(st) = &summary.stopped {
        s.p(format!("The run stopped early: {}.", super::esc(st)));
    }
    for (suffix, mut plot) in spatial_sim::plots(&sim, &kept, "Your rotor in time") {
        if suffix == "amplitude_omega" {
            if cfg.dimensional {
                plot.x2 = super::rotor::speed_axis(m).2;
            }
            plot.vlines.extend(super::rotor::operating_vlines(cfg.analysis.operating_speed, w0));
        }
        let caption = match suffix.as_str() {
            "amplitude_omega" => "Whirl radius of the shaft at the balancer plane against the speed, beside the stationary whirls of the rotor with the balls held where they start (Newton on the nonlinear equations).",
            "amplitude_t" => "Whirl radii at the balancer plane and at the supports against time.",
            "psi_t" => "Ball angles from the unbalance direction, wrapped to ±180°.",
            _ if !own_drive => continue,
            _ => "Speed against time.",
        };
        s.figure(format!("spatial_run_{suffix}"), plot, caption);
    }
    Ok(Some(s))
}
