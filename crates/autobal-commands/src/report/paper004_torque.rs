//! Section "Paper 004: constant torque": the paper's section 3 (Figs 6-8) with its own torques
//! (18, 73, 91, 165, 183 N·m) and ball drags, on the disk inertia and bearing drag chosen so
//! that its outcomes hold (`autobal::planar::paper004`), and a sweep over both that shows what
//! the choice decides. Runs in parallel; a run cut short by Ctrl-C is marked as such.

use super::paper004::{ball_angles, curves, mm, om, run_all, runs_table, tt, Run};
use super::{Ctx, Section};
use crate::num::fmt;
use crate::plot::{Plot, Series, PALETTE};
use anyhow::Result;
use autobal::planar::paper004::{torque_outcomes, torque_rotor, TorqueOutcomes, SWITCH_OFF, TORQUE_C_THETA, TORQUE_I_G};
use rayon::prelude::*;

/// The grid of the sweep: disk inertia (kg·m²) and bearing drag (N·m·s).
const SWEEP_I_G: [f64; 5] = [0.01, 0.03, 0.1, 0.3, 1.0];
const SWEEP_C_THETA: [f64; 6] = [0.03, 0.06, 0.1, 0.15, 0.2, 0.3];

/// Switch-off time of the 73 N·m run (s): the paper does not give it; after the rotor has
/// settled semi-balanced (about 4.6 s with the chosen inertia and drag).
const OFF_73: f64 = 5.0;
/// The paper's switch-off time of the run with too little ball drag (Fig. 8d-f, s).
const OFF_8: f64 = 0.6;

fn torque(m: f64, t_off: Option<f64>, t_end: f64, c_psi: f64) -> Vec<String> {
    let mut o = vec![
        format!("planar.i_g={TORQUE_I_G}"),
        format!("planar.c_theta={TORQUE_C_THETA}"),
        format!("planar.c_psi={c_psi}"),
        "drive.kind=\"torque\"".into(),
        format!("drive.torque={m}"),
        "drive.omega0=0".into(),
        format!("drive.t_end={t_end}"),
        format!("integration.dt={}", t_end / 4000.0),
    ];
    if let Some(t) = t_off {
        o.push(format!("drive.t_off={t}"));
    }
    o
}

fn runs() -> Vec<Run> {
    let run = |tag: &str, label: String, sets: Vec<String>| Run { tag: tag.into(), label, sets };
    let mut v = vec![];
    for m in [18.0, 91.0, 165.0] {
        v.push(run("6", format!("M = {m} N·m"), torque(m, None, 8.0, 0.1)));
    }
    v.push(run("7", format!("M = 183 N·m, off at {SWITCH_OFF} s"), torque(183.0, Some(SWITCH_OFF), 8.0, 0.1)));
    v.push(run("7", format!("M = 73 N·m, off at {OFF_73} s"), torque(73.0, Some(OFF_73), 12.0, 0.1)));
    v.push(run("8", "M = 183 N·m, c_ψ = 0.004".into(), torque(183.0, None, 4.0, 0.004)));
    v.push(run("8", format!("M = 183 N·m, c_ψ = 0.004, off at {OFF_8} s"), torque(183.0, Some(OFF_8), 6.0, 0.004)));
    v
}

/// A horizontal line over `[0, t]`.
fn level(label: &str, y: f64, t: f64) -> Series {
    Series::new(label, vec![(0.0, y), (t, y)], PALETTE[7]).dashed()
}

fn mark(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "no"
    }
}

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let runs = runs();
    let done = run_all(&runs, None, &ctx.control)?;
    // quick mode: a 2 × 2 corner of the sweep around the chosen pair
    let (igs, cts): (&[f64], &[f64]) = if ctx.quick { (&[0.1, 0.3], &[0.03, 0.1]) } else { (&SWEEP_I_G, &SWEEP_C_THETA) };
    let grid: Vec<(f64, f64)> = igs.iter().flat_map(|&i| cts.iter().map(move |&c| (i, c))).collect();
    let sweep: Vec<TorqueOutcomes> = match grid.par_iter().map(|&(i, c)| torque_outcomes(i, c, &ctx.control)).collect::<autobal::Result<_>>() {
        Ok(v) => v,
        // cut short (Ctrl-C): no row is read from a partial run; the section says it is incomplete
        Err(autobal::Error::Interrupted { .. }) => Vec::new(),
        Err(e) => return Err(e.into()),
    };
    let mut s = Section::new("paper004torque", "Paper 004: passage under a constant torque");
    s.complete = !done.iter().any(|d| d.cut()) && ctx.control.should_stop().is_none();
    let rotor = torque_rotor(TORQUE_I_G, TORQUE_C_THETA);
    let wn = rotor.natural_frequency();
    s.p(format!(
        "The paper's section 3: the rotor of Figs 2-5 (m3 = 0.03 kg) driven from rest by a constant torque M, with the paper's torques. The paper gives neither the disk's moment of inertia I_G nor the bearing drag c_θ, and a 1 kg disk could not take 18-183 N·m the way its figures show; <b>I_G = {} kg·m² and c_θ = {} N·m·s are chosen here</b> (J_C = {} kg·m²) so that every outcome the paper reports holds: 18 N·m sticks below resonance, 73, 91, 165 and 183 N·m pass and settle semi-balanced, the larger torque sooner, the smaller torque with the lower peak, and 183 N·m switched off at {SWITCH_OFF} s lets the rotor run down through resonance, where the whirl grows again. The sweep at the end shows which outcomes other values give.",
        fmt(TORQUE_I_G, 3),
        fmt(TORQUE_C_THETA, 3),
        fmt(rotor.polar_moment(), 4),
    ));
    let (head, rows) = runs_table(&runs, &done);
    s.table(&head, &rows);
    let t_end = |tag: &str| runs.iter().zip(&done).filter(|(r, _)| r.tag == tag).map(|(_, d)| d.cfg.settings.t_end).fold(0.0, f64::max);

    let mut amp6 = curves(&runs, &done, &["6"], tt, mm);
    amp6.push(level("s2 = 0.5 mm", 1e3 * rotor.s2, t_end("6")));
    s.figure(
        "fig004_6ab_torque_amplitude",
        Plot { title: "004 Fig. 6a,b: constant torque, radius of C".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: amp6, ..Default::default() },
        "004 Fig. 6a,b: radius of C under the paper's constant torques. 18 N·m cannot pass resonance (Sommerfeld effect: the bearing drag takes c_θ ω and the whirl c ω A², together more than 18 N·m below sqrt(k/m0)); 91 and 165 N·m pass and settle at the semi-balanced radius s2 (grey dashed), the larger torque sooner.",
    );
    let mut sp6 = curves(&runs, &done, &["6"], tt, om);
    sp6.push(level("sqrt(k/m0) = 288 rad/s", wn, t_end("6")));
    s.figure(
        "fig004_6c_torque_speed",
        Plot { title: "004 Fig. 6c: speed under constant torque".into(), x_label: "t (s)".into(), y_label: "ω (rad/s)".into(), series: sp6, ..Default::default() },
        format!("004 Fig. 6c: speed against time; the grey dashed line is sqrt(k/m0). 18 N·m settles at {} rad/s, below resonance; the bearing drag limits the larger torques to M/c_θ.", fmt(done[0].summary.final_omega, 4)),
    );
    for (tag, what, extra) in [
        ("7", "run-up and run-down", format!("The 183 N·m torque is switched off at {SWITCH_OFF} s (the paper's t1) and the 73 N·m torque at {OFF_73} s (the paper does not say when; after it has settled)")),
        ("8", "too little ball drag (c_ψ = 0.004 N·m·s)", format!("183 N·m with c_ψ = 0.004 N·m·s, kept on, and switched off at {OFF_8} s (the paper's t1)")),
    ] {
        let mut a = curves(&runs, &done, &[tag], tt, mm);
        a.push(level("s2 = 0.5 mm", 1e3 * rotor.s2, t_end(tag)));
        let caption = if tag == "7" {
            "the whirl passes its peak, settles semi-balanced at s2, and grows again when the rotor, no longer driven, runs down through resonance; the smaller torque passes more slowly and with the lower peak"
        } else {
            "with too little ball drag the balls swing round the race after resonance and the whirl oscillates before it breaks down to the semi-balanced radius; switched off just after resonance, the rotor runs back down and the whirl dies out as the speed falls"
        };
        s.figure(
            format!("fig004_{tag}_amplitude"),
            Plot { title: format!("004 Fig. {tag}a: {what}, radius of C"), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: a, ..Default::default() },
            format!("004 Fig. {tag}: radius of C against time. {extra}: {caption}."),
        );
        s.figure(
            format!("fig004_{tag}_ball_angles"),
            Plot { title: format!("004 Fig. {tag}b: {what}, ball angles"), x_label: "t (s)".into(), y_label: "ψ (degrees from CG)".into(), series: ball_angles(&runs, &done, &[tag]), y_range: Some((-180.0, 180.0)), ..Default::default() },
            format!("004 Fig. {tag}: angles of the two balls relative to CG (ball 1 solid, ball 2 dashed), wrapped to ±180°: a line that wraps is a ball slipping round the race."),
        );
        let mut w = curves(&runs, &done, &[tag], tt, om);
        w.push(level("sqrt(k/m0) = 288 rad/s", wn, t_end(tag)));
        s.figure(
            format!("fig004_{tag}_speed"),
            Plot { title: format!("004 Fig. {tag}c: {what}, speed"), x_label: "t (s)".into(), y_label: "ω (rad/s)".into(), series: w, ..Default::default() },
            format!("004 Fig. {tag}: speed against time; after the switch-off only the bearing drag c_θ and the whirl slow the rotor down (time constant J_C/c_θ = {} s).", fmt(rotor.polar_moment() / TORQUE_C_THETA, 3)),
        );
    }
    let torque_curves: Vec<Series> = runs
        .iter()
        .zip(&done)
        .filter(|(r, _)| r.tag == "7" || r.tag == "8")
        .enumerate()
        .map(|(i, (r, d))| {
            Series::new(r.label.clone(), d.env.kept().iter().map(|x| (x.t, d.cfg.drive.torque(x.t, x.omega))).collect(), crate::figures::curve_color(i))
        })
        .collect();
    s.figure(
        "fig004_7_8_torque",
        Plot { title: "004 Figs 7-8: applied torque".into(), x_label: "t (s)".into(), y_label: "M (N·m)".into(), series: torque_curves, ..Default::default() },
        "004 Figs 7-8: the applied torque of each run against time (constant until its switch-off).",
    );

    s.h3("paper004torque_sweep", "What the chosen I_G and c_θ decide");
    s.p(format!(
        "Each row: paper 004's rotor with that disk inertia and bearing drag, three runs from rest (18 N·m; 73 N·m for 12 s; 183 N·m switched off at {SWITCH_OFF} s, for 12 s). \"Sticks\": the speed never reaches sqrt(k/m0) = 288 rad/s; \"balanced by {SWITCH_OFF} s\": the radius of C within 5 % of s2 for good before the switch-off; \"re-excited\": after it the speed falls below 288 rad/s again and the radius of C exceeds 4 s2 = 2 mm. Only c_θ between about 0.06 and 0.2 N·m·s makes 18 N·m stick while 73 N·m passes; only I_G of about 0.3 kg·m² (the moment of a 1 kg disk of radius 0.77 m) makes the smaller torque the gentler one and still settles 183 N·m before {SWITCH_OFF} s. The chosen pair is marked."
    ));
    let head = [
        "I_G (kg·m²)",
        "c_θ (N·m·s)",
        "18 N·m sticks",
        "ω at 18 N·m (rad/s)",
        "73 N·m passes",
        "183 N·m balanced by 1.8 s",
        "peak at 73 N·m (mm)",
        "peak at 183 N·m (mm)",
        "73 N·m lower peak",
        "re-excited after switch-off",
        "all of the paper's outcomes",
    ];
    let rows: Vec<Vec<String>> = sweep
        .iter()
        .map(|o| {
            let chosen = o.i_g == TORQUE_I_G && o.c_theta == TORQUE_C_THETA;
            vec![
                format!("{}{}", fmt(o.i_g, 3), if chosen { " (chosen)" } else { "" }),
                fmt(o.c_theta, 3),
                mark(o.sticks_18).into(),
                fmt(o.omega_18, 4),
                mark(o.passes_73).into(),
                mark(o.balanced_183_before_off).into(),
                fmt(1e3 * o.peaks.0, 3),
                fmt(1e3 * o.peaks.1, 3),
                mark(o.smaller_torque_lower_peak).into(),
                mark(o.re_excited).into(),
                mark(o.all()).into(),
            ]
        })
        .collect();
    if rows.is_empty() {
        s.p("Interrupted: the sweep was cut short, so its rows are left out.");
    } else {
        s.table(&head, &rows);
    }
    Ok(Some(s))
}
