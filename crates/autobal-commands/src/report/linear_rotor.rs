//! The report's section on the user's linear rotor (`[linear_rotor]`, issue 19 "your own
//! rotor"): the undamped modes at the balancer planes ([`crate::linear_rotor::modes_at_plane`]:
//! where a plane sits at a node of a mode, the balls cannot act on that mode), where the
//! balanced state is stable over speed (`autobal stability`'s computation and figure), the
//! structure's Campbell diagram without the balls (ROSS's `run_campbell`), and the run-up in
//! time (`autobal simulate`'s run and figures).

use super::{Ctx, Section};
use crate::linear_rotor as lr;
use crate::num::fmt;
use crate::plot::{Plot, Series, PALETTE};
use anyhow::Result;
use autobal::rotor_stability::speed_grid;

/// Modes listed per balancer plane.
const MODES: usize = 8;
/// A plane whose translation and tilt in a mode are below this fraction of the mode's largest
/// translation (tilt: times 0.1 m) sits at a node of the mode.
const NODE_OF_MODE: f64 = 0.05;

fn rpm(w: f64) -> f64 {
    w * 30.0 / std::f64::consts::PI
}

fn speed(w: f64) -> String {
    format!("{} rad/s ({} rpm)", fmt(w, 4), fmt(rpm(w), 4))
}

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let Some(cfg) = &ctx.linear else {
        return Ok(Some(Section::not_applicable("linear_rotor", "Your linear rotor", "the config has no [linear_rotor] table")));
    };
    let rotor = &cfg.rotor;
    let mut s = Section::new("linear_rotor", "Your linear rotor");
    let omega_max = lr::default_omega_max(cfg)?;
    let (model, red) = lr::model(cfg)?;
    s.p(format!(
        "A linear rotor–bearing model <code>M q̈ + (C(Ω) + Ω G) q̇ + K(Ω) q = f</code> ({}): {} DOFs on {} nodes, {} balancer plane(s) with {} balls, {} unbalance(s), {} speed-dependent bearing(s). {}",
        if cfg.source == "shaft" { "the built-in shaft builder" } else { "matrix files" },
        rotor.dofs(),
        rotor.nodes,
        rotor.balancers.len(),
        rotor.total_balls(),
        rotor.unbalances.len(),
        rotor.speed_bearings.len(),
        match &red {
            None => "Every analysis below runs on the full model.".to_string(),
            Some(r) => format!(
                "The stability, the Campbell diagram and the run-up run on its reduction to {} DOFs ({} interior mode pairs up to {}; first neglected {}).",
                r.dofs.1,
                r.mode_pairs,
                r.cutoff.map_or("-".into(), speed),
                r.first_neglected.map_or("none".into(), speed)
            ),
        }
    ));

    // a stiffness that is not positive semi-definite: said first, never a "0 rad/s" mode
    let (_, diverging) = lr::modes_at_rest(&model, 0)?;
    if !diverging.is_empty() {
        let line = lr::divergence_text(&diverging);
        s.p(format!("<b>{}</b>", super::html::esc(line.trim_end())));
        // the summary is HTML (its terminal copy strips tags: an unescaped "ω² < 0" cut the line)
        s.summary.push(format!("Linear rotor: {}", super::html::esc(line.trim_end())));
    }

    // the modes at the balancer planes, on the full model (the nodes are physical)
    s.h3("linear_rotor_modes", "Mode shapes at the balancer plane");
    s.p("The undamped modes of the rotor at rest with the balls as rings and the inertia fixed to the rotor at its angle 0 (symmetric part of <code>K</code> at Ω = 0): how far each balancer plane moves in each mode (its race centre: its node's translation plus its <code>offset</code> times the tilt, <code>x + e β</code>, <code>y − e α</code>), as a fraction of the mode's largest translation of any node or plane (1: the plane sits at the mode's antinode; 0: at a node of the mode, where the balls can neither feel nor counter that mode's whirl), and the tilt at the plane's node in that mode (rad per metre of that largest translation). Above a critical speed whose mode barely moves the plane, the balls cannot balance that mode's response.");
    for (i, b) in rotor.balancers.iter().enumerate() {
        let modes = lr::modes_at_plane(rotor, i, MODES)?;
        let rows: Vec<Vec<String>> = modes
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let at_node = m.translation < NODE_OF_MODE && 0.1 * m.tilt < NODE_OF_MODE;
                // a divergent mode has no frequency: its ω² < 0 instead
                let (w, n) = if m.omega_squared < 0.0 && m.omega == 0.0 {
                    (format!("none: ω² = {} (rad/s)², statically unstable", fmt(m.omega_squared, 5)), "-".to_string())
                } else {
                    (fmt(m.omega, 5), fmt(rpm(m.omega), 5))
                };
                vec![format!("{}", k + 1), w, n, fmt(m.translation, 3), fmt(m.tilt, 3), if at_node { "near a node of the mode".into() } else { String::new() }]
            })
            .collect();
        let offset = if b.offset == 0.0 { String::new() } else { format!(", {} m from it along the axis", fmt(b.offset, 4)) };
        s.p(format!("Balancer plane {i} at node {}{offset} (race radius {} m, {} balls):", b.node, fmt(b.radius, 4), b.balls));
        s.table(&["mode", "ω (rad/s)", "ω (rpm)", "translation at the plane (of the largest)", "tilt at the plane (rad/m)", ""], &rows);
        // one curve per distinct frequency (a pair of equal ones has one shape)
        let mut series = vec![];
        let mut last = f64::NAN;
        for m in &modes {
            if (m.omega - last).abs() <= 1e-9 * m.omega.abs().max(1e-300) {
                continue;
            }
            last = m.omega;
            let c = PALETTE[series.len() % 7];
            series.push(Series::new(format!("{} rad/s", fmt(m.omega, 4)), m.shape.iter().enumerate().map(|(k, v)| (k as f64, *v)).collect(), c).markers());
        }
        s.figure(
            format!("linear_rotor_modes_{i}"),
            Plot {
                title: format!("Mode shapes at rest, balancer plane {i} at node {}", b.node),
                x_label: "node".into(),
                y_label: "translation (of the mode's largest)".into(),
                series,
                vlines: vec![(b.node as f64, format!("balancer plane {i}"))],
                ..Default::default()
            },
            "The lowest undamped modes at rest (balls as rings), each as its translation at every node along the direction of its largest one; the balancer plane's node is marked. A pair of equal frequencies (an isotropic rotor's x and y whirl) is drawn once.",
        );
    }

    // stability over speed: `autobal stability`'s computation and figure
    s.h3("linear_rotor_stability", "Where the balanced state is stable");
    let full = if rotor.is_isotropic() { 200 } else { 50 };
    let samples = match (ctx.quick, rotor.is_isotropic()) {
        (false, _) => full,
        (true, true) => 60,
        (true, false) => 20,
    };
    // under the report's control, as `autobal stability` runs it (`general::scan`,
    // `stability::kept_scan`): stopped (Ctrl-C, the budget) during the scan, the speeds
    // analysed kept, no verdict at the operating speed, the section incomplete; stopped
    // during that verdict, the speeds it solved kept (its scan ran without the control: Ctrl-C
    // did not stop it)
    let g = crate::general::GeneralRotor::linear(model.clone());
    let (out, asked) = crate::general::scan(&g, omega_max, samples, &ctx.control)?;
    let (st, op, stopped) = crate::stability::kept_scan(out, asked, &ctx.control, |r, c| {
        cfg.operating_speed.map(|w| crate::general::operating_at(&g, w, "linear_rotor.operating_speed", r, c)).transpose()
    })?;
    if stopped.is_some() {
        s.complete = false;
        s.p(super::html::esc(crate::stability::incomplete_line(&stopped).trim_end()));
    }
    let analysed = crate::general::analysed_span(&st, omega_max);
    // each end as `stability` words it: a located boundary, else the axis' end, a switch of
    // state or a grid speed next to one without a state ([`crate::general::end_text`])
    let ranges: Vec<String> = st
        .stable_ranges
        .iter()
        .map(|r| format!("{} to {}", crate::general::end_text(&st, r, false, speed), crate::general::end_text(&st, r, true, speed)))
        .collect();
    let verdict = if ranges.is_empty() { format!("nowhere in (0, {}]", speed(analysed)) } else { ranges.join("; ") };
    // the verdicts are the grid's: a range's located ends are exact, but an unstable gap
    // between two stable grid speeds narrower than the step is not seen (the quick grid's
    // 60 speeds stepped over 386-411 rad/s on the shaft example with me = 5e-3: review 21)
    let step = omega_max / samples as f64;
    let grid = format!(
        "on a grid of {samples} speeds {} apart: an unstable gap narrower than that between two stable grid speeds can go unseen{}",
        speed(step),
        if ctx.quick {
            format!(" (the quick report's coarse grid; the full report takes {full}, `autobal stability --samples N` any number)")
        } else {
            String::new()
        }
    );
    s.p(format!(
        "The balanced state (the balls where they cancel the unbalance) by its exact linearisation at {samples} speeds up to {} ({}), as <code>autobal stability</code> computes it: stable {verdict}. The ranges are {}.",
        speed(omega_max),
        if rotor.is_isotropic() { "an equilibrium in axes turning with the rotor: eigenvalues" } else { "anisotropic: a periodic orbit, Floquet multipliers" },
        super::html::esc(&grid)
    ));
    // the summary states the ranges alone: the quick one says they are a coarse grid's
    let caveat = if ctx.quick {
        format!(" (quick report: a grid of {samples} speeds {} apart, a narrower unstable gap can go unseen)", speed(step))
    } else {
        String::new()
    };
    // balls too light: the partially balanced state, said so (lr::partial_text)
    let partial = lr::partial_text(cfg, &st);
    if !partial.is_empty() {
        s.p(super::html::esc(partial.trim_end()));
    }
    let what = if partial.is_empty() { "the balanced state" } else { "the stationary state (balanced, else partially balanced)" };
    // the verdict at `linear_rotor.operating_speed` first, as `autobal stability` prints it
    // (none where the scan was stopped; stopped itself, the INCOMPLETE line above says why)
    if let Some(op) = &op {
        let line = crate::general::operating_line(&g, &st, op);
        s.p(format!("<b>{}</b>", super::html::esc(line.trim_end())));
        // the caveat on the verdict's line, before any lines of other states
        let line = line.trim_end();
        let (first, rest) = line.split_once('\n').map_or((line, String::new()), |(a, b)| (a, format!("\n{b}")));
        s.summary.push(format!("{first}{caveat}{rest}"));
    }
    let incomplete = if st.cut_short() { format!(" (INCOMPLETE: the scan stopped at {})", speed(analysed)) } else { String::new() };
    s.summary.push(format!("Linear rotor: {what} is stable {verdict}{caveat}{incomplete}."));
    let margin = lr::margin_plot(&st, omega_max);
    let margin = if st.cut_short() { crate::stability::mark_stopped(margin, &stopped, st.points.last().map(|q| q.omega)) } else { margin };
    s.figure("linear_rotor_stability_margin", margin, "The balanced state's stability margin over speed (largest Re λ, or the largest Floquet exponent of a periodic orbit), the exactly stable ranges shaded: <code>autobal stability --svg</code>'s figure.");

    // the structure's Campbell diagram without the balls
    s.h3("linear_rotor_campbell", "Campbell diagram");
    let points = if ctx.quick { 40 } else { 120 };
    let speeds = speed_grid(omega_max, points)?;
    let mut lines: Vec<Vec<(f64, f64)>> = vec![];
    let mut top = 0.0f64;
    for &w in std::iter::once(&0.0).chain(&speeds) {
        if ctx.control.should_stop().is_some() {
            s.complete = false;
            break;
        }
        let mut f: Vec<f64> = model.structure_eigenvalues(w)?.iter().map(|z| z.im).filter(|v| *v > 1e-9).collect();
        f.sort_by(f64::total_cmp);
        f.truncate(MODES);
        for (i, v) in f.iter().enumerate() {
            if lines.len() <= i {
                lines.push(vec![]);
            }
            lines[i].push((w, *v));
            top = top.max(*v);
        }
    }
    let mut series: Vec<Series> = lines.into_iter().enumerate().map(|(i, p)| Series::new(format!("mode {}", i + 1), p, PALETTE[i % 6])).collect();
    series.push(Series::new("1× (synchronous)", vec![(0.0, 0.0), (omega_max, omega_max)], PALETTE[7]).dashed());
    s.figure(
        "linear_rotor_campbell_diagram",
        Plot {
            title: "Campbell diagram of the structure without its balls".into(),
            x_label: "speed ω (rad/s)".into(),
            y_label: "damped natural frequency (rad/s)".into(),
            series,
            x_range: Some((0.0, omega_max)),
            y_range: Some((0.0, 1.05 * top.max(omega_max))),
            ..Default::default()
        },
        "The damped natural frequencies (imaginary parts of the eigenvalues, ascending, the lowest 8) of the structure without its balls at each speed, with its speed-dependent bearings and gyroscopic terms: ROSS's <code>run_campbell</code>. Where a line crosses the 1× line the rotor passes a critical speed.",
    );

    // the run-up: `autobal simulate`'s run and figures
    s.h3("linear_rotor_runup", "Run-up");
    // the quick report samples the same run more coarsely
    let dt = ctx.quick.then(|| lr::drive_of(cfg, omega_max).1 / 500.0);
    let setup = lr::setup(cfg, omega_max, dt)?;
    let run = lr::run(&setup, &ctx.control, |_| Ok(()))?;
    let sum = &run.summary;
    // a run that ended early: interrupted where Ctrl-C or the wall-time budget stopped it
    // (the section is incomplete), else failed (the integrator's own reason: a step too small,
    // a non-finite state, its step budget spent), which on a K that is not positive
    // semi-definite is what its divergence does to any run
    // (the config's wall-time budget, `integration.max_wall_s`, is the integrator's: its
    // reason says so, review 23)
    let interrupted = sum.stopped.as_deref().is_some_and(|st| ctx.control.should_stop().is_some() || st.starts_with("time budget"));
    let failed = if interrupted { None } else { sum.stopped.as_deref() };
    if interrupted {
        s.complete = false;
    }
    let why = failed.map(|st| {
        let cause = if diverging.is_empty() {
            String::new()
        } else {
            format!(
                " The stiffness K is not positive semi-definite ({} mode(s) diverge at rest, the fastest as exp({} t) with t in s): the motion grows without bound, and no run of this rotor can reach its end.",
                diverging.len(),
                fmt((-diverging[0]).sqrt(), 4)
            )
        };
        format!("The run-up failed at t = {} s: the integrator stopped ({st}).{cause}", fmt(sum.t, 4))
    });
    if let Some(w) = &why {
        s.failed = Some(format!("the run-up failed at t = {} s", fmt(sum.t, 4)));
        s.p(format!("<b>{}</b>", super::html::esc(w)));
        s.summary.push(format!("Linear rotor run-up: {}", super::html::esc(&w.replacen("The run-up failed", "failed", 1))));
    }
    s.p(format!(
        "{}: the peak whirl radius of the first balancer plane's race centre is {} mm at {} (t = {} s), {} mm at the end; the largest radius of any node {} mm at {}.{}",
        if setup.default_drive {
            format!("From rest at constant acceleration to {} in 1000 revolutions (the config has no <code>[drive]</code>)", speed(omega_max))
        } else {
            "The config's <code>[drive]</code>".to_string()
        },
        fmt(1e3 * sum.peak.value, 4),
        speed(sum.peak.with),
        fmt(sum.peak.t, 4),
        fmt(1e3 * sum.final_radius, 4),
        fmt(1e3 * sum.peak_any_node.value, 4),
        speed(sum.peak_any_node.with),
        match (interrupted, &sum.stopped) {
            (true, Some(st)) => format!(" Interrupted: {st}."),
            (false, Some(_)) => " (Up to the failure.)".to_string(),
            _ => String::new(),
        }
    ));
    if sum.stopped.is_none() {
        s.summary.push(format!(
            "Linear rotor run-up: peak whirl radius at the balancer plane {} mm at {}, {} mm at the end.",
            fmt(1e3 * sum.peak.value, 3),
            speed(sum.peak.with),
            fmt(1e3 * sum.final_radius, 3)
        ));
    }
    for (suffix, plot) in lr::plots(&setup, &run.kept) {
        if suffix == "amplitude_omega" || suffix == "psi_t" {
            let caption = if suffix == "psi_t" {
                "The balls' angles relative to the rotor during the run-up."
            } else {
                "The whirl radius of each balancer plane's race centre and the largest of any node against speed during the run-up: <code>autobal simulate</code>'s figure."
            };
            s.figure(format!("linear_rotor_runup_{suffix}"), plot, caption);
        }
    }
    Ok(Some(s))
}

#[cfg(test)]
mod tests {
    use crate::command::ConfigSource;
    use autobal::control::Control;

    /// The quick report's linear section on the shaft example with `operating_speed =
    /// "450-500 rad/s"`, stopped (as Ctrl-C) at the first progress report `(done, total)` for
    /// which `stop` says so; and the section's HTML.
    fn stopped_section(stop: impl Fn(u64, u64) -> bool + Send + Sync + 'static) -> (super::super::Section, String) {
        let text = include_str!("../../../../examples/linear_rotor_shaft.toml").replacen(
            "[linear_rotor]\n",
            "[linear_rotor]\noperating_speed = \"450-500 rad/s\"\n",
            1,
        );
        let root = crate::config::parse_text(&text, "shaft.toml").unwrap();
        let control = Control::new();
        let c = control.clone();
        let control = control.with_progress(move |p| {
            if stop(p.done, p.total) {
                c.cancel();
            }
        });
        let ctx = super::super::context(&ConfigSource::tables(root, "shaft.toml"), true, super::super::Kind::User, &control).unwrap();
        let s = super::build(&ctx).unwrap().unwrap();
        let html: String = s.blocks.iter().filter_map(|b| if let super::super::Block::Html(h) = b { Some(h.as_str()) } else { None }).collect();
        (s, html)
    }

    /// The linear rotor's section stopped (Ctrl-C) during the verdict at its operating speed,
    /// after 3 of the range's 9 speeds, keeps them and says so before the verdict's line (it
    /// ended the whole report with an error, "nothing is printed"); the section is incomplete.
    /// The shaft example over 450-500 rad/s, stable at each speed: no verdict from 3 of them.
    #[test]
    fn a_stopped_operating_verdict_keeps_the_section() {
        // the verdict's 9 speeds are counted after the quick scan's 60 (`kept_scan`)
        let (s, html) = stopped_section(|done, total| total == 69 && done >= 63);
        assert!(!s.complete);
        let why = "INCOMPLETE (interrupted: the scan is complete; the verdict at the operating speed stopped after 3 of 9 speeds solved there (kept: JSON operating.points): no verdict)";
        assert!(html.contains(why), "{html}");
        assert!(html.contains("no verdict: stopped after 3 of 9 speeds solved there"), "{html}");
    }

    /// The same section stopped during its stability scan (after 5 of the quick grid's 60
    /// speeds) keeps the speeds analysed and says so, gives no verdict at the operating speed,
    /// and its figure's title says INCOMPLETE (the scan ran without the report's control:
    /// Ctrl-C did not stop it).
    #[test]
    fn a_stopped_scan_keeps_the_speeds_analysed() {
        let (s, html) = stopped_section(|done, total| total == 60 && done >= 5);
        assert!(!s.complete);
        assert!(html.contains("INCOMPLETE (interrupted: 5 of 60 speeds analysed"), "{html}");
        assert!(!html.contains("operating speed 450"), "{html}");
        assert!(s.summary.iter().any(|l| l.contains("INCOMPLETE: the scan stopped at")), "{:?}", s.summary);
        let fig = s
            .blocks
            .iter()
            .find_map(|b| if let super::super::Block::Figure(f) = b { (f.id == "linear_rotor_stability_margin").then_some(f) } else { None })
            .unwrap();
        assert!(fig.plot.title.starts_with("INCOMPLETE: "), "{}", fig.plot.title);
    }
}
