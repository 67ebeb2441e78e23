//! Section "Paper 004": the passages through resonance of Bykov and Kovachev 2017, re-run with
//! the paper's rotor. Runs in parallel; a run that Ctrl-C cuts short is marked as such, never
//! reported with numbers it did not reach.

use super::{esc, interrupted, Ctx, Section};
use crate::config::PlanarConfig;
use crate::num::fmt;
use crate::plot::{Plot, Series, PALETTE};
use crate::sim::Envelope;
use anyhow::Result;
use autobal::planar::{simulate, stationary::locked_amplitude, Sample, Summary};
use rayon::prelude::*;

/// Samples kept per run for the figures (min and max of each bucket: peaks survive).
const BUCKETS: usize = 1500;

/// One simulation of the report: a figure tag, a legend label, and `--set` overrides of the
/// embedded paper-004 config (or of the user's config).
#[derive(Clone)]
pub struct Run {
    pub tag: String,
    pub label: String,
    pub sets: Vec<String>,
}

/// A finished (or interrupted) run.
pub struct Done {
    pub cfg: PlanarConfig,
    pub summary: Summary,
    pub env: Envelope,
    pub wall: f64,
}

impl Done {
    /// Whether Ctrl-C cut the run short.
    pub fn cut(&self) -> bool {
        self.summary.stopped.is_some() && interrupted()
    }
}

/// Run every simulation in parallel; identical runs (same overrides) are computed once.
/// `base`: the config table to apply the overrides to (`None`: paper 004's rotor).
pub fn run_all(runs: &[Run], base: Option<&toml::Table>) -> Result<Vec<std::sync::Arc<Done>>> {
    use std::collections::HashMap;
    use std::sync::Arc;
    let mut unique: Vec<&Vec<String>> = vec![];
    for r in runs {
        if !unique.contains(&&r.sets) {
            unique.push(&r.sets);
        }
    }
    let done: Vec<Arc<Done>> = unique
        .par_iter()
        .map(|sets| -> Result<Arc<Done>> {
            let cfg = match base {
                None => crate::config::load_planar(None, sets)?,
                Some(t) => {
                    let mut t = t.clone();
                    for s in sets.iter() {
                        crate::config::apply_set(&mut t, s)?;
                    }
                    crate::config::build_planar(&t, "config")?
                }
            };
            let mut env = Envelope::new((cfg.settings.t_end / cfg.settings.dt) as usize + 1, BUCKETS);
            let t = std::time::Instant::now();
            let summary = simulate(&cfg.rotor, &cfg.drive, &cfg.settings, |x| {
                env.push(x);
                !interrupted()
            })?;
            env.flush();
            Ok(Arc::new(Done { cfg, summary, env, wall: t.elapsed().as_secs_f64() }))
        })
        .collect::<Result<Vec<_>>>()?;
    let by: HashMap<&Vec<String>, Arc<Done>> = unique.into_iter().zip(done).collect();
    Ok(runs.iter().map(|r| by[&r.sets].clone()).collect())
}

/// Table of runs: peak, final state, work; a run cut short says so instead of numbers.
pub fn runs_table(runs: &[Run], done: &[std::sync::Arc<Done>]) -> (Vec<&'static str>, Vec<Vec<String>>) {
    let head = vec!["figure", "run", "m3 (kg)", "c_ψ (N·m·s)", "method", "peak radius of C (mm)", "ω at peak (rad/s)", "final radius (mm)", "final ω (rad/s)", "semi-balanced", "steps", "wall (s)"];
    let rows = runs
        .iter()
        .zip(done)
        .map(|(r, d)| {
            let s = &d.summary;
            let mut row = vec![r.tag.clone(), r.label.clone(), fmt(d.cfg.rotor.m3, 3), fmt(d.cfg.rotor.c_psi, 3), format!("{:?}", d.cfg.settings.method).to_lowercase()];
            if d.cut() {
                row.push(format!("interrupted at t = {} s of {} s", fmt(s.t_end, 3), fmt(d.cfg.settings.t_end, 3)));
                row.extend(std::iter::repeat_n("—".to_string(), 5));
            } else {
                row.extend([fmt(1e3 * s.peak_amplitude, 4), fmt(s.omega_at_peak, 4), fmt(1e3 * s.final_amplitude, 3), fmt(s.final_omega, 4), if s.balanced { "yes".into() } else { "no".into() }]);
            }
            row.push(s.steps.to_string());
            row.push(fmt(d.wall, 2));
            row
        })
        .collect();
    (head, rows)
}

/// Curves of the runs with one of `tags`: x and y of each kept sample; reverse runs dashed.
pub fn curves(runs: &[Run], done: &[std::sync::Arc<Done>], tags: &[&str], x: fn(&Sample) -> f64, y: fn(&Sample) -> f64) -> Vec<Series> {
    runs.iter()
        .zip(done)
        .filter(|(r, _)| tags.contains(&r.tag.as_str()))
        .enumerate()
        .map(|(i, (r, d))| {
            let s = Series::new(r.label.clone(), d.env.kept.iter().map(|s| (x(s), y(s))).collect(), crate::figures::curve_color(i));
            if r.label.contains("reverse") {
                s.dashed()
            } else {
                s
            }
        })
        .collect()
}

pub fn mm(s: &Sample) -> f64 {
    1e3 * s.amplitude
}
pub fn om(s: &Sample) -> f64 {
    s.omega
}
pub fn tt(s: &Sample) -> f64 {
    s.t
}

fn acc(m3: f64, b: f64, w0: f64, t_end: f64, method: &str) -> Vec<String> {
    vec![
        format!("planar.m3={m3}"),
        "drive.kind=\"acceleration\"".into(),
        format!("drive.b={b}"),
        format!("drive.omega0={w0}"),
        format!("drive.t_end={t_end}"),
        format!("integration.dt={}", t_end / 4000.0),
        format!("integration.method=\"{method}\""),
    ]
}

fn torque(m: f64, t_off: Option<f64>, t_end: f64, cpsi: f64) -> Vec<String> {
    let mut o = vec![
        "drive.kind=\"torque\"".into(),
        format!("drive.torque={m}"),
        "drive.omega0=0".into(),
        format!("drive.t_end={t_end}"),
        format!("integration.dt={}", t_end / 4000.0),
        format!("planar.c_psi={cpsi}"),
    ];
    if let Some(t) = t_off {
        o.push(format!("drive.t_off={t}"));
    }
    o
}

/// The runs of the section. Light balls (m3 = 0.01 kg), heavy ball drag (c_ψ = 0.4) and slow
/// forward passages are stiff for an explicit method (the balls relax in well under a
/// millisecond): RODAS integrates them 2-100× faster than DOP853 at the same accuracy
/// (measured; docs/report.md). Reverse passages, and ball drag as light as c_ψ = 0.01, stay with
/// DOP853 (RODAS leaves the semi-balanced state differently there, or takes more steps).
fn runs(quick: bool) -> Vec<Run> {
    let f = if quick { 10.0 } else { 1.0 };
    let b = |v: f64| v * f;
    let run = |tag: &str, label: String, sets: Vec<String>| Run { tag: tag.into(), label, sets };
    let mut v = vec![];
    // forward passages at b ≤ 0.25 1/s²: RODAS
    let fwd = |bb: f64| if bb <= 0.25 { "rosenbrock" } else { "dop853" };
    for (tag, m3) in [("2", 0.01), ("3", 0.03)] {
        let rev = if m3 < 0.02 { "rosenbrock" } else { "dop853" };
        v.push(run(tag, format!("forward, b = {} 1/s²", b(0.25)), acc(m3, b(0.25), 0.0, 600.0 / b(0.25), fwd(b(0.25)))));
        v.push(run(tag, format!("reverse, b = {} 1/s²", -b(0.25)), acc(m3, -b(0.25), 1000.0, 1000.0 / b(0.25), rev)));
    }
    for bb in [0.25, 2.5, 12.5] {
        v.push(run("4a", format!("forward, b = {} 1/s²", b(bb)), acc(0.03, b(bb), 0.0, 600.0 / b(bb), fwd(b(bb)))));
        v.push(run("4b", format!("reverse, b = {} 1/s²", -b(bb)), acc(0.03, -b(bb), 1000.0, 1000.0 / b(bb), "dop853")));
    }
    let slow: &[f64] = if quick { &[] } else { &[0.04, 0.08, 0.2] };
    for &bb in slow {
        v.push(run("4c", format!("forward, b = {bb} 1/s²"), acc(0.03, bb, 0.0, 600.0 / bb, fwd(bb))));
    }
    for (cp, method) in [(0.01, "dop853"), (0.1, fwd(b(0.2))), (0.4, "rosenbrock")] {
        let mut o = acc(0.03, b(0.2), 0.0, 600.0 / b(0.2), method);
        o.push(format!("planar.c_psi={cp}"));
        v.push(run("5", format!("c_ψ = {cp} N·m·s"), o));
    }
    for m in [3.0, 6.0, 10.0] {
        v.push(run("6", format!("M = {m} N·m"), torque(m, None, 10.0, 0.1)));
    }
    v.push(run("7", "M = 10 N·m, off at 2 s".into(), torque(10.0, Some(2.0), 4.0, 0.1)));
    v.push(run("8", "M = 10 N·m, c_ψ = 0.004 N·m·s".into(), torque(10.0, None, 6.0, 0.004)));
    v
}

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let runs = runs(ctx.quick);
    let done = run_all(&runs, None)?;
    let mut s = Section::new("paper004", "Paper 004: passage through resonance");
    s.complete = !done.iter().any(|d| d.cut());
    s.p(format!(
        "Bykov and Kovachev 2017. The paper's rotor: m1 = 1 kg, m2 = 0.2 kg, two balls, s1 = 3 mm, s2 = 0.5 mm, r = 60 mm, c = 50 kg/s, c_ψ = 0.1 N·m·s, sqrt(k/m0) = 288 rad/s; I_G = 0.0025 kg·m² and c_θ = 0, which the paper does not give. Integrated in rotor axes at rtol 1e-8 (DOP853, or RODAS where the balls' drag makes the equations stiff; column \"method\"). {} runs ({} distinct).{}",
        runs.len(),
        { let mut u: Vec<&Vec<String>> = runs.iter().map(|r| &r.sets).collect(); u.sort(); u.dedup(); u.len() },
        if ctx.quick { " <b>Quick mode: accelerations ten times the paper's, slow passages of Fig. 4c left out.</b>" } else { "" }
    ));
    let (head, rows) = runs_table(&runs, &done);
    s.table(&head, &rows);

    for (tag, m3) in [("2", 0.01), ("3", 0.03)] {
        let mut ser = curves(&runs, &done, &[tag], om, mm);
        if let Some(d) = runs.iter().zip(&done).find(|(r, _)| r.tag == tag).map(|x| x.1) {
            let rotor = &d.cfg.rotor;
            let psi0 = autobal::planar::Settings::default_psi0(rotor.n);
            ser.push(Series::new("stationary, balls held", (0..=500).map(|i| { let w = 2.0 * i as f64; (w, 1e3 * locked_amplitude(rotor, w, &psi0)) }).collect(), PALETTE[7]).dashed());
        }
        s.figure(
            format!("fig004_{tag}_amplitude_omega"),
            Plot { title: format!("004 Fig. {tag}a: radius of C against speed, m3 = {m3} kg"), x_label: "ω (rad/s)".into(), y_label: "radius of C (mm)".into(), series: ser, x_range: Some((0.0, 1000.0)), ..Default::default() },
            format!("004 Fig. {tag}a: whirl radius of the shaft point C against the speed for the forward (solid) and reverse (dashed) passages at |b| = 0.25 1/s² with m3 = {m3} kg, and the stationary curve of the rotor whose balls are held at their initial, evenly spread positions (grey dashed). {}", if tag == "2" { "Too little ball mass: after resonance the rotor keeps an unbalanced whirl (2.05 mm at 600 rad/s), forward and reverse peaks nearly equal." } else { "After the passage the balls hold C at the radius s2 = 0.5 mm (semi-balanced)." }),
        );
        let psi: Vec<Series> = runs
            .iter()
            .zip(&done)
            .filter(|(r, _)| r.tag == tag)
            .enumerate()
            .flat_map(|(k, (r, d))| {
                let dir = if r.label.contains("reverse") { "reverse" } else { "forward" };
                (0..d.cfg.rotor.n).map(move |j| {
                    let s = Series::new(format!("{dir}: ψ{}", j + 1), crate::sim::wrapped_degrees(d.env.kept.iter().map(|s| (s.t, s.psi[j]))), crate::figures::curve_color(2 * k + j));
                    if dir == "reverse" { s.dashed() } else { s }
                })
            })
            .collect();
        s.figure(
            format!("fig004_{tag}_ball_angles"),
            Plot { title: format!("004 Fig. {tag}b,c: ball angles, m3 = {m3} kg"), x_label: "t (s)".into(), y_label: "ψ (degrees from CG)".into(), series: psi, y_range: Some((-180.0, 180.0)), ..Default::default() },
            format!("004 Fig. {tag}b,c: angles of the balls relative to CG, wrapped to ±180° (a ball slipping round the race shows as a line that wraps)."),
        );
    }
    let mut four = vec![("4a", "forward"), ("4b", "reverse")];
    if !ctx.quick {
        four.push(("4c", "slow forward"));
    }
    for (tag, what) in four {
        s.figure(
            format!("fig004_{tag}_acceleration"),
            Plot { title: format!("004 Fig. {tag}: {what} passages at several accelerations"), x_label: "ω (rad/s)".into(), y_label: "radius of C (mm)".into(), series: curves(&runs, &done, &[tag], om, mm), ..Default::default() },
            format!("004 Fig. {tag}: radius of C against the speed for {what} passages at the accelerations listed (m3 = 0.03 kg). The forward peak overshoots the stationary one and hardly changes with b; reverse passages peak lower, the more the faster."),
        );
    }
    s.figure(
        "fig004_5_ball_damping",
        Plot { title: "004 Fig. 5: effect of the ball drag c_ψ".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: curves(&runs, &done, &["5"], tt, mm), ..Default::default() },
        "004 Fig. 5: radius of C against time for three ball drags (b = 0.2 1/s²): too little drag prolongs the oscillation after resonance, too much raises the peak.",
    );
    s.figure(
        "fig004_6_torque_amplitude",
        Plot { title: "004 Fig. 6a,b: constant torque".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: curves(&runs, &done, &["6"], tt, mm), ..Default::default() },
        "004 Fig. 6a,b: radius of C under constant torques (our torques: the paper's 18-183 N·m need a disk inertia or bearing drag it does not give). The smallest cannot pass resonance (Sommerfeld effect; with this rotor's inertia the threshold is about 4.8 N·m, the largest torque the whirl absorbs at resonance, c ω A²).",
    );
    s.figure(
        "fig004_6_torque_speed",
        Plot { title: "004 Fig. 6c: speed under constant torque".into(), x_label: "t (s)".into(), y_label: "ω (rad/s)".into(), series: curves(&runs, &done, &["6"], tt, om), y_range: Some((0.0, 1000.0)), ..Default::default() },
        "004 Fig. 6c: speed against time (axis cut at 1000 rad/s: without bearing drag, c_θ = 0, the larger torques accelerate without limit once past resonance); the rotor driven by 3 N·m sticks below sqrt(k/m0) = 288 rad/s.",
    );
    s.figure(
        "fig004_7_torque_off",
        Plot { title: "004 Figs 7-8: torque switched off; too little ball drag".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: curves(&runs, &done, &["7", "8"], tt, mm), ..Default::default() },
        "004 Figs 7-8: radius of C for a run-up whose torque is switched off at 2 s, and a run-up with too little ball drag (c_ψ = 0.004 N·m·s). Without bearing drag (c_θ = 0, not given in the paper) the rotor coasts at its speed after the switch-off instead of running down: the paper's run-down needs a drag it does not state.",
    );
    let _ = esc;
    Ok(Some(s))
}
