//! The HTML report: parameters, tables, and the figures, written into one folder.
//! Figures are written one by one before the index, so an interrupted run keeps them.

use crate::config::Config;
use crate::figures;
use crate::output::{critical_rows, fmt_ranges, scale_ranges};
use anyhow::{Context, Result};
use autobal::spatial::critical_speeds::critical_speeds;
use autobal::spatial::inertia::{composite_inertia, AnisotropyMethod};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
use autobal::spatial::ranges::{antiresonance_speed, autobalancing_ranges};
use autobal::spatial::sensitivity::sensitivity;
use std::fmt::Write;
use std::path::{Path, PathBuf};

fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

fn table(head: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = String::from("<table><tr>");
    for h in head {
        let _ = write!(s, "<th>{}</th>", esc(h));
    }
    s.push_str("</tr>\n");
    for r in rows {
        s.push_str("<tr>");
        for c in r {
            let _ = write!(s, "<td>{}</td>", esc(c));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</table>\n");
    s
}

fn paper_examples() -> String {
    let printed: [(f64, f64, f64, [f64; 4], f64); 3] = [
        (0.5, 1.25, 0.0, [1.0, 1.0, 2.11, 3.23], 1.67),
        (0.8, 1.46, 0.75, [0.837, 0.849, 2.52, 3.80], 2.24),
        (1.2, 2.15, 1.75, [0.567, 0.575, 3.73, 5.61], 3.20),
    ];
    let mut rows = vec![];
    for (l, p, c, k, wa) in printed {
        let m = SpatialModel::from_dimensionless(&DimensionlessInput {
            c_sigma: 0.75,
            rho_s: 0.4,
            l_left: l,
            z_a: 0.8,
            anisotropy: AnisotropyInput::Direct(0.1),
            h_x: 0.0,
            h_s: 0.0,
            method: AnisotropyMethod::Exact,
            direct_balls: None,
        })
        .expect("paper base case is valid");
        let cs: Vec<String> = critical_speeds(&m).speeds.iter().map(|s| format!("{:.4}", s.omega)).collect();
        rows.push(vec![
            format!("{l}"),
            format!("{p} / {:.4}", m.p_alpha_sq.sqrt()),
            format!("{c} / {:.4}", m.c_y_alpha),
            format!("{:?} / {}", k, cs.join(", ")),
            format!("{wa} / {:.4}", antiresonance_speed(&m).unwrap_or(f64::NAN)),
            fmt_ranges(&autobalancing_ranges(&m).ranges, 3),
        ]);
    }
    table(&["l̄_L", "p̄α printed / computed", "c̄yα", "Ω_K1-4 printed / computed", "Ω_a", "autobalancing ranges"], &rows)
}

/// Write the report into `dir`; returns the path of `index.html`. `quick` runs the passage
/// simulations of paper 004 ten times faster (and skips the slowest), for tests.
pub fn write(cfg: &Config, dir: &Path, quick: bool) -> Result<PathBuf> {
    std::fs::create_dir_all(dir).with_context(|| format!("--out {}: cannot create the folder", dir.display()))?;
    let m = &cfg.model;
    let figs = figures::all(m, cfg.analysis.omega_max);
    for f in &figs {
        let p = dir.join(&f.file);
        std::fs::write(&p, f.plot.to_svg()).with_context(|| format!("--out: cannot write {}", p.display()))?;
    }
    let mut h = String::new();
    h.push_str(
        r#"<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>autobal report</title>
<style>
body{font-family:system-ui,-apple-system,"DejaVu Sans",sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}
table{border-collapse:collapse;margin:.6em 0 1.2em}th,td{border:1px solid #ccc;padding:3px 8px;text-align:left;font-variant-numeric:tabular-nums}
th{background:#f3f3f3}pre{background:#f7f7f7;padding:.8em;overflow:auto;font-size:90%}
.warn{background:#fff4e0;border-left:4px solid #e69f00;padding:.4em .8em;margin:.5em 0}
figure{margin:1.5em 0}figcaption{font-size:92%;color:#444;max-width:720px}
</style></head><body>
<h1>autobal report</h1>
"#,
    );
    let _ = writeln!(h, "<p>Config: <code>{}</code>. Version {}.</p>", esc(&cfg.source), env!("CARGO_PKG_VERSION"));
    for w in &m.anisotropy.warnings {
        let _ = writeln!(h, "<div class=\"warn\">{}</div>", esc(w));
    }

    h.push_str("<h2>Parameters</h2>\n");
    let mut rows = vec![
        vec!["C̄Σ".into(), format!("{:.6}", m.c_sigma), "polar / mean equatorial moment".into()],
        vec!["ρ̄s".into(), m.rho_s.map_or("—".into(), |v| format!("{v:.6}")), "radius of gyration / support span".into()],
        vec!["l̄_L".into(), m.l_left.map_or("—".into(), |v| format!("{v:.6}")), "C from the left support / span".into()],
        vec!["z̄_A".into(), format!("{:.6}", m.z_a), "balancer plane from C / ρ_s".into()],
        vec!["p̄α".into(), format!("{:.6}", m.p_alpha_sq.sqrt()), "angular support frequency".into()],
        vec!["c̄yα".into(), format!("{:.6}", m.c_y_alpha), "translation–tilt coupling".into()],
        vec!["ΔĀ (used)".into(), format!("{:.6}", m.anisotropy.used), format!("{:?}", m.anisotropy.method).to_lowercase()],
        vec!["ΔĀ exact tensor".into(), format!("{:.6} – {:.6}", m.anisotropy.exact[0], m.anisotropy.exact[1]), "over the balancing positions".into()],
        vec!["ΔĀ eq (17)".into(), format!("{:.6}", m.anisotropy.paper), format!("D_A = {}", m.anisotropy.d_a.map_or("—".into(), |d| format!("{d:.4}")))],
        vec!["ΔĀ0".into(), format!("{:.6}", m.delta_a0), "unbalance mass alone (003)".into()],
        vec!["h̄x, h̄α, h̄yα, h̄s".into(), format!("{:.4}, {:.4}, {:.4}, {:.4}", m.damping.h_x, m.damping.h_alpha, m.damping.h_y_alpha, m.damping.h_s), "damping".into()],
    ];
    if let Some(ms) = m.masses {
        rows.push(vec!["m̄0, R̄0, m̄, R̄, n".into(), format!("{}, {}, {}, {}, {}", ms.m0, ms.r0, ms.m, ms.r, ms.n), format!("capacity E = {:.4}", ms.capacity())]);
    }
    if let Some(sc) = m.scale {
        rows.push(vec!["ω0".into(), format!("{:.4} rad/s = {:.1} rpm", sc.omega0, sc.omega0 * 30.0 / std::f64::consts::PI), "unit of speed".into()]);
    }
    h.push_str(&table(&["symbol", "value", "meaning"], &rows));
    let ci = composite_inertia(m);
    let unit = if ci.si { "kg·m²" } else { "A_Σ" };
    h.push_str(&table(
        &["A_Σ", "C_Σ", "A_C1", "A_C2", "ΔA", "unit"],
        &[vec![format!("{:.6}", ci.a_sigma), format!("{:.6}", ci.c_sigma), format!("{:.6}", ci.a_c1), format!("{:.6}", ci.a_c2), format!("{:.6}", ci.delta_a), unit.into()]],
    ));

    h.push_str("<h2>Critical speeds</h2>\n<p>Exact roots of Δ1Δ2 = 0 (000, eq (16)) with the approximations (18) symmetric, (19) near-symmetric, (20) small anisotropy.</p>\n");
    let cs = critical_speeds(m);
    let rows: Vec<Vec<String>> = critical_rows(&cs, cfg.dimensional).into_iter().map(|r| r.to_vec()).collect();
    h.push_str(&table(&["", "Ω", "kind", "branch", "(18)", "(19)", "(20)", if cfg.dimensional { "SI" } else { "over ΔĀ interval" }], &rows));
    let _ = writeln!(h, "<p>{} distinct critical speeds; rotor class (Table 1, short-rotor boundary corrected to C̄Σ &gt; 1 + ΔĀ): {:?}, for which Table 1 predicts {}.</p>", cs.distinct_count, cs.rotor_class, cs.table1_count);

    let se = sensitivity(m, cfg.analysis.sensitivity_limit);
    h.push_str("<h2>Sensitivity criterion</h2>\n");
    let f = |x: Option<f64>| x.map_or("—".into(), |v| format!("{v:.4}"));
    h.push_str(&table(
        &["δΩ_Kα1 exact", "δΩ_Kα2 exact", "δΩ_Kα1 (22)", "δΩ_Kα2 (22)", "[δΩ_Kα]", "[ΔĀ0]", "[m̄0]"],
        &[vec![f(se.delta_exact[0]), f(se.delta_exact[1]), f(se.delta_approx[0]), f(se.delta_approx[1]), format!("{}", se.limit), format!("{:.4}", se.delta_a_limit), f(se.m0_limit)]],
    ));
    let _ = writeln!(h, "<p><b>Verdict:</b> {}</p>", esc(&se.reason));

    let ar = autobalancing_ranges(m);
    h.push_str("<h2>Autobalancing ranges (003)</h2>\n");
    let _ = writeln!(
        h,
        "<p>Antiresonance Ω_a = {}. Phase condition (1) holds on {}; split-pair instability on {}. <b>Autobalancing possible on {}</b>{}. Class: {:?}.</p>",
        f(ar.antiresonance_speed),
        fmt_ranges(&ar.phase_condition, 4),
        fmt_ranges(&ar.instability, 4),
        fmt_ranges(&ar.ranges, 4),
        m.scale.map_or(String::new(), |sc| format!(" ({} rpm)", fmt_ranges(&scale_ranges(&ar.ranges, sc.omega0 * 30.0 / std::f64::consts::PI), 0))),
        ar.class
    );

    h.push_str("<h2>Worked examples of papers 000 and 003</h2>\n<p>C̄Σ = 0.75, ρ̄s = 0.4, ΔĀ = 0.1, z̄_A = 0.8, as printed / as computed.</p>\n");
    h.push_str(&paper_examples());

    h.push_str(&linear_section(cfg, dir)?);
    h.push_str(&simulation_section(dir, quick)?);

    h.push_str("<h2>Figures of papers 000 and 003</h2>\n");
    for fg in &figs {
        let _ = writeln!(h, "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>", fg.file, esc(&fg.plot.title), esc(&fg.caption));
    }
    let _ = writeln!(h, "<h2>Config as used</h2>\n<pre>{}</pre>\n</body></html>", esc(&cfg.text));
    let index = dir.join("index.html");
    std::fs::write(&index, h).with_context(|| format!("--out: cannot write {}", index.display()))?;
    Ok(index)
}

/// Section of issue 3: Campbell diagram, exact vs necessary ranges for the three layouts of
/// the papers, and one stability map (003 Fig. 5a layout).
fn linear_section(cfg: &Config, dir: &Path) -> Result<String> {
    use crate::linear;
    use crate::map::{write_plots, Axis, Cell, MapResult, Quantity};
    use autobal::spatial::linear_model::{Balls, StateSpace};
    use autobal::spatial::stability::{counts_as_stable, margin_at};
    let m = &cfg.model;
    let mut h = String::from("<h2>Exact linear stability of the balanced state</h2>\n");
    if m.balls.is_none() {
        h.push_str("<p>The config does not describe the balls (give the masses, or <code>m</code> and <code>d_a</code> beside <code>delta_a</code>), so only the locked rotor is analysed here.</p>\n");
    }
    let balls = if m.balls.is_some() { Balls::Free } else { Balls::Locked };
    let w = linear::omega_max(cfg, None)?;
    let _ = writeln!(
        h,
        "<p>Eigenvalues of the linearised equations (000, eq (6)), balls {} ({} states). Stable means every eigenvalue has Re λ {}; range ends located by bisection to 1e-9.</p>",
        if balls == Balls::Free { "free" } else { "locked" },
        if balls == Balls::Free { 12 } else { 8 },
        if balls == Balls::Free { "&lt; −1e-11" } else { "≤ 1e-11 (neutral allowed)" }
    );
    let c = linear::campbell_of(cfg, w, 240, balls)?;
    let (rot, fixed) = linear::campbell_plots(m, &c);
    for (file, p, cap) in [
        ("campbell_fixed.svg", fixed, "Campbell diagram in fixed axes: whirl frequency of each tracked mode (forward above zero, backward below), the 1× line, and the analytic critical speeds K1-K4."),
        ("campbell_rotating.svg", rot, "Campbell diagram in rotating axes: Im λ of each tracked eigenvalue."),
    ] {
        std::fs::write(dir.join(file), p.to_svg()).with_context(|| format!("--out: cannot write {file}"))?;
        let _ = writeln!(h, "<figure><img src=\"{file}\" alt=\"{file}\"><figcaption>{}</figcaption></figure>", esc(cap));
    }
    let cmp = linear::compare(m, w, 1500, balls)?;
    std::fs::write(dir.join("stability_margin.svg"), linear::margin_plot(&cmp).to_svg()).context("--out: cannot write stability_margin.svg")?;
    let _ = writeln!(h, "<figure><img src=\"stability_margin.svg\" alt=\"margin\"><figcaption>{}</figcaption></figure>", esc(&format!("Largest real part along Ω for this config. {}.", linear::difference_sentence(&cmp))));
    if m.rho_s.is_some() {
        let mut rows = vec![];
        for l in [0.5, 0.8, 1.2] {
            let ml = crate::figures::with_layout(m, l);
            let cl = linear::compare(&ml, w.max(crate::figures::omega_limit(&ml, None)), 1500, balls)?;
            rows.push(vec![
                format!("{l}"),
                fmt_ranges(&cl.exact.stable_ranges, 4),
                fmt_ranges(&cl.necessary, 4),
                linear::difference_sentence(&cl),
            ]);
        }
        h.push_str("<h3>Exact ranges against 003's necessary ranges, the papers' three layouts</h3>\n");
        h.push_str(&table(&["l̄_L", "exactly stable", "003 necessary", "difference"], &rows));
    }
    // stability maps in the layouts of 003 Figs 4 and 5a: C̄Σ × Ω and z̄_A × Ω
    let maps: [(&str, &str, Axis, fn(&mut autobal::spatial::params::SpatialModel, f64), &str); 3] = [
        (
            "stability_map_c_sigma",
            "Stability map C̄Σ × Ω",
            Axis { key: "dimensionless.c_sigma".into(), lo: 0.2, hi: 2.0, n: 121 },
            |m, v| m.c_sigma = v,
            "Stability map in the layout of 003 Fig. 4: largest real part over the rotor type C̄Σ and the speed Ω (blue stable, red unstable), with the exact stability boundary (black) and the boundary of 003's necessary condition (dashed). Also as stability_map_c_sigma.png.",
        ),
        (
            "stability_map_z_a",
            "Stability map z̄_A × Ω",
            Axis { key: "dimensionless.z_a".into(), lo: -2.0, hi: 2.0, n: 121 },
            |m, v| m.z_a = v,
            "Stability map in the layout of 003 Fig. 5a: largest real part over the position of the balancer plane z̄_A and the speed Ω, with the exact stability boundary (black) and the boundary of 003's necessary condition (dashed). Also as stability_map_z_a.png.",
        ),
        (
            "stability_map_delta_a0",
            "Stability map ΔĀ0 × Ω",
            Axis { key: "dimensionless.delta_a".into(), lo: 0.0, hi: 0.24, n: 121 },
            |m, v| {
                m.anisotropy.used = v;
                m.delta_a0 = v;
            },
            "Stability map in the layout of 003 Fig. 5b: largest real part over the anisotropy (ΔĀ = ΔĀ0, given directly as in 003's examples) and the speed Ω, with the exact boundary (black) and 003's (dashed). Also as stability_map_delta_a0.png.",
        ),
    ];
    for (stem, title, x, set, caption) in maps {
        let y = Axis { key: "omega".into(), lo: 0.02 * w, hi: w, n: 121 };
        let cols: Vec<(StateSpace, Vec<autobal::spatial::ranges::SpeedRange>)> = (0..x.n)
            .map(|i| {
                let mut mz = m.clone();
                set(&mut mz, x.value(i));
                Ok((StateSpace::new(&mz, balls)?, autobal::spatial::ranges::autobalancing_ranges(&mz).ranges))
            })
            .collect::<Result<_>>()?;
        let mut rows: Vec<Option<Vec<Cell>>> = vec![];
        for j in 0..y.n {
            let om = y.value(j);
            let mut row = vec![];
            for (ss, nec) in &cols {
                let a = margin_at(ss, om)?;
                row.push(Cell { margin: a, stable: counts_as_stable(a, balls), necessary: nec.iter().any(|r| r.contains(om)) });
            }
            rows.push(Some(row));
        }
        let r = MapResult { x, y, rows, quantity: Quantity::Margin };
        write_plots(&r, &dir.join(stem), title)?;
        let _ = writeln!(h, "<figure><img src=\"{stem}.svg\" alt=\"{title}\"><figcaption>{}</figcaption></figure>", esc(caption));
    }
    Ok(h)
}

/// Section of issue 4: paper 004's passages through resonance, re-run with autobal.
fn simulation_section(dir: &Path, quick: bool) -> Result<String> {
    use crate::plot::{Plot, Series, PALETTE};
    use crate::sim::{Envelope, INTERRUPTED};
    use autobal::planar::{simulate, stationary::locked_amplitude, Summary};
    use rayon::prelude::*;
    let f = if quick { 10.0 } else { 1.0 }; // quick: ten times faster sweeps
    let b = |v: f64| v * f;
    // (id, label, overrides)
    let mut runs: Vec<(&str, String, Vec<String>)> = vec![];
    let acc = |m3: f64, bb: f64, w0: f64, t_end: f64| -> Vec<String> {
        vec![
            format!("planar.m3={m3}"),
            "drive.kind=\"acceleration\"".into(),
            format!("drive.b={bb}"),
            format!("drive.omega0={w0}"),
            format!("drive.t_end={t_end}"),
            format!("integration.dt={}", t_end / 4000.0),
        ]
    };
    for (id, m3) in [("2", 0.01), ("3", 0.03)] {
        runs.push((id, format!("forward b = {}", b(0.25)), acc(m3, b(0.25), 0.0, 600.0 / b(0.25))));
        runs.push((id, format!("reverse b = {}", -b(0.25)), acc(m3, -b(0.25), 1000.0, 1000.0 / b(0.25))));
    }
    for bb in [0.25, 2.5, 12.5] {
        runs.push(("4a", format!("forward b = {}", b(bb)), acc(0.03, b(bb), 0.0, 600.0 / b(bb))));
        runs.push(("4b", format!("reverse b = {}", -b(bb)), acc(0.03, -b(bb), 1000.0, 1000.0 / b(bb))));
    }
    if !quick {
        for bb in [0.04, 0.08, 0.2] {
            runs.push(("4c", format!("forward b = {bb}"), acc(0.03, bb, 0.0, 600.0 / bb)));
        }
    }
    for cp in [0.01, 0.1, 0.4] {
        let mut o = acc(0.03, b(0.2), 0.0, 600.0 / b(0.2));
        o.push(format!("planar.c_psi={cp}"));
        runs.push(("5", format!("c_ψ = {cp}"), o));
    }
    let torque = |m: f64, t_off: Option<f64>, t_end: f64, cpsi: f64| -> Vec<String> {
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
    };
    for m in [3.0, 6.0, 10.0] {
        runs.push(("6", format!("M = {m} N·m"), torque(m, None, 10.0, 0.1)));
    }
    runs.push(("7", "M = 10 N·m, off at 2 s".into(), torque(10.0, Some(2.0), 4.0, 0.1)));
    runs.push(("8", "M = 10 N·m, c_ψ = 0.004".into(), torque(10.0, None, 6.0, 0.004)));
    eprintln!("simulating paper 004's passages through resonance ({} runs{})…", runs.len(), if quick { ", quick" } else { "" });
    let t0 = std::time::Instant::now();
    let results: Vec<Result<(crate::config::PlanarConfig, Summary, Envelope, f64)>> = runs
        .par_iter()
        .map(|(_, _, sets)| {
            let cfg = crate::config::load_planar(None, sets)?;
            let mut env = Envelope::new((cfg.settings.t_end / cfg.settings.dt) as usize + 1, 4000);
            let t = std::time::Instant::now();
            let s = simulate(&cfg.rotor, &cfg.drive, &cfg.settings, |x| {
                env.push(x);
                !INTERRUPTED.load(std::sync::atomic::Ordering::Relaxed)
            })?;
            env.flush();
            Ok((cfg, s, env, t.elapsed().as_secs_f64()))
        })
        .collect();
    let results = results.into_iter().collect::<Result<Vec<_>>>()?;
    let total = t0.elapsed().as_secs_f64();
    let mut h = String::from("<h2>Passage through resonance (paper 004)</h2>\n");
    let _ = writeln!(
        h,
        "<p>Paper 004's rotor (m1 = 1 kg, m2 = 0.2 kg, two balls, s1 = 3 mm, s2 = 0.5 mm, r = 60 mm, c = 50 kg/s, c_ψ = 0.1 N·m·s, sqrt(k/m0) = 288 1/s; I_G = 0.0025 kg·m² and c_θ = 0, which the paper does not give), integrated in rotor axes by DOP853 at rtol 1e-8.{} {} runs in {:.1} s.</p>",
        if quick { " <b>Quick mode: accelerations ten times the paper's.</b>" } else { "" },
        results.len(),
        total
    );
    let mut rows = vec![];
    for ((id, label, _), (cfg, s, _, wall)) in runs.iter().zip(&results) {
        rows.push(vec![
            format!("Fig. {id}"),
            label.clone(),
            format!("{}", cfg.rotor.m3),
            format!("{}", cfg.rotor.c_psi),
            format!("{:.3}", 1e3 * s.peak_amplitude),
            format!("{:.1}", s.omega_at_peak),
            format!("{:.4}", 1e3 * s.final_amplitude),
            format!("{:.1}", s.final_omega),
            if s.balanced { "yes".into() } else { "no".into() },
            s.steps.to_string(),
            format!("{wall:.3}"),
        ]);
    }
    h.push_str(&table(&["figure", "run", "m3 (kg)", "c_ψ", "peak (mm)", "ω at peak", "final (mm)", "final ω", "semi-balanced", "steps", "wall (s)"], &rows));
    let series_of = |ids: &[&str], x: &dyn Fn(&autobal::planar::Sample) -> f64, y: &dyn Fn(&autobal::planar::Sample) -> f64| -> Vec<Series> {
        runs.iter()
            .zip(&results)
            .filter(|((id, _, _), _)| ids.contains(id))
            .enumerate()
            .map(|(i, ((_, label, _), (_, _, env, _)))| Series::new(label.clone(), env.kept.iter().map(|s| (x(s), y(s))).collect(), PALETTE[i % 7]))
            .collect()
    };
    let mm = |s: &autobal::planar::Sample| 1e3 * s.amplitude;
    let om = |s: &autobal::planar::Sample| s.omega;
    let tt = |s: &autobal::planar::Sample| s.t;
    let mut figs: Vec<(String, Plot, String)> = vec![];
    for (id, m3) in [("2", 0.01), ("3", 0.03)] {
        let mut ser = series_of(&[id], &om, &mm);
        let rotor = results.iter().zip(&runs).find(|(_, r)| r.0 == id).map(|(x, _)| x.0.rotor.clone()).expect("run present");
        let psi0 = autobal::planar::Settings::default_psi0(rotor.n);
        ser.push(Series::new("stationary (balls held)", (0..=500).map(|i| { let w = 2.0 * i as f64; (w, 1e3 * locked_amplitude(&rotor, w, &psi0)) }).collect(), PALETTE[7]).dashed());
        figs.push((
            format!("fig004_{id}_amplitude_omega.svg"),
            Plot { title: format!("004 Fig. {id}: m3 = {m3} kg, forward and reverse"), x_label: "ω (rad/s)".into(), y_label: "radius of C (mm)".into(), series: ser, ..Default::default() },
            format!("004 Fig. {id}a: radius of C against speed for forward and reverse passage, with the stationary curve of the rotor whose balls are held at their initial, evenly spread positions (dashed)."),
        ));
        let psi: Vec<Series> = runs
            .iter()
            .zip(&results)
            .filter(|((i, _, _), _)| *i == id)
            .flat_map(|((_, label, _), (cfg, _, env, _))| {
                let dir = if label.contains("reverse") { "rev." } else { "fwd." };
                (0..cfg.rotor.n).map(move |j| Series::new(format!("{dir} ψ{}", j + 1), crate::sim::wrapped_degrees(env.kept.iter().map(|s| (s.t, s.psi[j]))), PALETTE[(j + 2 * usize::from(dir == "rev.")) % 7]))
            })
            .collect();
        figs.push((
            format!("fig004_{id}_ball_angles.svg"),
            Plot { title: format!("004 Fig. {id}b,c: ball angles, m3 = {m3} kg"), x_label: "t (s)".into(), y_label: "ψ (degrees)".into(), series: psi, ..Default::default() },
            format!("004 Fig. {id}b,c: ball angles relative to CG during the forward and reverse passages."),
        ));
    }
    let mut four = vec![("4a", "forward"), ("4b", "reverse")];
    if !quick {
        four.push(("4c", "slow forward"));
    }
    for (id, what) in four {
        figs.push((
            format!("fig004_{id}_acceleration.svg"),
            Plot { title: format!("004 Fig. {id}: {what} passage at several accelerations"), x_label: "ω (rad/s)".into(), y_label: "radius of C (mm)".into(), series: series_of(&[id], &om, &mm), ..Default::default() },
            format!("004 Fig. {id}: radius of C against speed for {what} passages at the accelerations listed."),
        ));
    }
    figs.push((
        "fig004_5_ball_damping.svg".into(),
        Plot { title: "004 Fig. 5: effect of the ball drag c_ψ".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: series_of(&["5"], &tt, &mm), ..Default::default() },
        "004 Fig. 5: radius of C against time for three ball drags: too little drag prolongs the oscillation after resonance, too much raises the peak.".into(),
    ));
    figs.push((
        "fig004_6_torque_amplitude.svg".into(),
        Plot { title: "004 Fig. 6a,b: constant torque".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: series_of(&["6"], &tt, &mm), ..Default::default() },
        "004 Fig. 6a,b: radius of C under constant torques; the smallest cannot pass resonance (Sommerfeld effect; with this rotor's inertia the threshold is about 4.8 N·m, the largest torque the whirl can absorb at resonance, c ω A²).".into(),
    ));
    figs.push((
        "fig004_6_torque_speed.svg".into(),
        Plot { title: "004 Fig. 6c: speed under constant torque".into(), x_label: "t (s)".into(), y_label: "ω (rad/s)".into(), series: series_of(&["6"], &tt, &om), ..Default::default() },
        "004 Fig. 6c: speed against time; the rotor driven by the smallest torque sticks below sqrt(k/m0) = 288 1/s.".into(),
    ));
    figs.push((
        "fig004_7_run_down.svg".into(),
        Plot { title: "004 Fig. 7: run-up, torque off, run-down".into(), x_label: "t (s)".into(), y_label: "radius of C (mm)".into(), series: series_of(&["7", "8"], &tt, &mm), ..Default::default() },
        "004 Figs 7-8: radius of C for a run-up with the torque switched off at 2 s, and a run-up with too little ball drag (c_ψ = 0.004).".into(),
    ));
    for (file, plot, caption) in figs {
        std::fs::write(dir.join(&file), plot.to_svg()).with_context(|| format!("--out: cannot write {file}"))?;
        let _ = writeln!(h, "<figure><img src=\"{file}\" alt=\"{}\"><figcaption>{}</figcaption></figure>", esc(&plot.title), esc(&caption));
    }
    Ok(h)
}
