//! Section "Your rotor": the config's spatial rotor (papers 000/003 model): parameters,
//! composite inertia, critical speeds, sensitivity criterion, autobalancing ranges and the
//! signed response of the balancer plane. With a dimensional config, speeds are given in rad/s
//! and rpm and the response in mm. A config that model does not represent (two planes, gravity,
//! supports that differ by direction, a planar rotor) also gets the critical speeds of the rotor
//! as given, by the general route (`autobal critical`'s locked critical speeds), which the
//! summary quotes; the 000/003 numbers stay, labelled as the one-plane model's.

use super::{Ctx, Section};
use crate::num::{fmt, grouped, speed, RPM_PER_RAD_S};
use crate::plot::{Plot, SecondAxis, Series, Shade, PALETTE};
use anyhow::Result;
use autobal::spatial::critical_speeds::critical_speeds;
use autobal::spatial::params::SpatialModel;
use autobal::spatial::ranges::{autobalancing_ranges, point_a_response, SpeedRange};
use autobal::spatial::sensitivity::sensitivity;

/// Speed ranges as text: dimensionless, and in rpm when the rotor is dimensional.
pub fn ranges_text(r: &[SpeedRange], omega0: Option<f64>) -> String {
    ranges_text_in(r, omega0, None)
}

/// [`ranges_text`] of ranges computed over `(0, span_end]` only: a range without upper end
/// reaches the span's end, `a – W (end of the span)`, rather than `a – ∞`.
pub fn ranges_text_in(r: &[SpeedRange], omega0: Option<f64>, span_end: Option<f64>) -> String {
    if r.is_empty() {
        return "none".into();
    }
    let open = |w: Option<String>| w.map_or("∞".to_string(), |w| format!("{w} (end of the span)"));
    let one = |x: &SpeedRange| match x.hi {
        Some(h) => format!("{} – {}", fmt(x.lo, 4), fmt(h, 4)),
        None => format!("{} – {}", fmt(x.lo, 4), open(span_end.map(|w| fmt(w, 4)))),
    };
    let dimless = r.iter().map(one).collect::<Vec<_>>().join(", ");
    match omega0 {
        Some(w0) => {
            let k = w0 * RPM_PER_RAD_S;
            let rpm = r
                .iter()
                .map(|x| match x.hi {
                    Some(h) => format!("{} – {}", grouped(x.lo * k, 0), grouped(h * k, 0)),
                    None => format!("{} – {}", grouped(x.lo * k, 0), open(span_end.map(|w| grouped(w * k, 0)))),
                })
                .collect::<Vec<_>>()
                .join(", ");
            format!("Ω = {dimless} ({rpm} rpm)")
        }
        None => format!("Ω = {dimless}"),
    }
}

/// The speed axis of a figure of this rotor: ω in rad/s with rpm on top when dimensional,
/// else Ω. Returns (factor from Ω, label, second axis).
pub fn speed_axis(m: &SpatialModel) -> (f64, String, Option<SecondAxis>) {
    match m.scale {
        Some(sc) => (sc.omega0, "ω (rad/s)".into(), Some(SecondAxis { factor: RPM_PER_RAD_S, label: "n (rpm)".into() })),
        None => (1.0, "Ω = ω/ω0".into(), None),
    }
}

pub use crate::figures::operating_vlines;

/// The critical speeds of the rotor as the config gives it, by the general route
/// ([`autobal::rotor_campbell::locked_critical_speeds`], as `autobal critical` computes them for
/// this config): a subsection, and the summary's line when `summary`.
fn general_critical(ctx: &Ctx, s: &mut Section, summary: bool) -> Result<()> {
    let g = crate::general::rotor_of(&ctx.root)?;
    let omega_max = crate::general::default_omega_max(&g, &ctx.root)?;
    let speed = |w: f64| {
        if g.si {
            format!("{} rpm ({} rad/s)", grouped(w * RPM_PER_RAD_S, 0), fmt(w, 5))
        } else {
            format!("Ω = {}", fmt(w, 5))
        }
    };
    s.h3("rotor-critical-general", "Critical speeds of the rotor as given (general route)");
    let what: Vec<String> = autobal::config::ignored_by_linear_model(&ctx.root);
    s.p(format!(
        "The {} rotor as the config gives it{}, its balls locked where they balance it, or where no balanced state exists where they rest bunched against the unbalance (point masses of the rotor), and no damping: the speeds up to {} where a natural frequency in fixed axes equals the speed, from the exact Jacobian of its nonlinear equations (what <code>autobal critical</code> prints for this config).",
        g.rotor.model_name(),
        if what.is_empty() { String::new() } else { format!(" (with {})", super::esc(&what.join(", "))) },
        speed(omega_max)
    ));
    let line = match autobal::rotor_campbell::locked_critical_speeds(&g.rotor, omega_max, 2000) {
        Ok(l) => {
            autobal::limits::check_finite("critical.locked", &l)?;
            let rows: Vec<Vec<String>> = l
                .speeds
                .iter()
                .enumerate()
                .map(|(i, k)| {
                    let mut r = vec![format!("{}", i + 1)];
                    if g.si {
                        r.push(fmt(k.omega, 6));
                        r.push(grouped(k.omega * RPM_PER_RAD_S, 0));
                    } else {
                        r.push(fmt(k.omega, 6));
                    }
                    r.push(name(&k.whirl));
                    r.push(name(&k.motion));
                    r.push(k.multiplicity.to_string());
                    r
                })
                .collect();
            let none = crate::general_campbell::no_critical_speed_words(&l, &speed(omega_max));
            if rows.is_empty() {
                s.p(format!("{}{}.", none[..1].to_uppercase(), &none[1..]));
            } else if g.si {
                s.table(&["", "ω (rad/s)", "n (rpm)", "whirl", "motion", "multiplicity (–)"], &rows);
            } else {
                s.table(&["", "Ω (–)", "whirl", "motion", "multiplicity (–)"], &rows);
            }
            if l.partial > 0 {
                s.p(format!("{}.", super::esc(&autobal::rotor_campbell::partial_words(l.partial, l.samples))));
            }
            if l.unlocked > 0 {
                s.p(format!("{}.", autobal::rotor_campbell::unlocked_words(l.unlocked, l.samples)));
            }
            let list: Vec<String> = l.speeds.iter().map(|k| speed(k.omega).split(" (").next().unwrap_or_default().to_string()).collect();
            format!("Critical speeds of the rotor as given (balls held at balance, general route): {}.", if list.is_empty() { none } else { list.join(", ") })
        }
        Err(e @ autobal::Error::NoLinearisation { .. }) => {
            s.p(format!("Not located: {}.", super::esc(&e.to_string())));
            "Critical speeds of the rotor as given: not defined by one frequency (its linearisation turns in fixed and in rotating axes); see the Floquet Campbell diagram of the stability section.".into()
        }
        Err(e) => return Err(e.into()),
    };
    if summary {
        s.summary.push(line);
    }
    Ok(())
}

/// The name of a value whose JSON is a string (`forward`, `translation`, …).
fn name<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_value(v).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default()
}

pub fn build(ctx: &Ctx) -> Result<Option<Section>> {
    let Some(cfg) = &ctx.spatial else {
        // a planar rotor: what the general route gives (papers 000/003's analyses need a
        // spatial rotor)
        let mut s = Section::new("rotor", "Your rotor (planar config)");
        s.p("The config's planar rotor (paper 004 model). The parameters, critical speeds, sensitivity criterion and autobalancing ranges of papers 000/003 need a spatial rotor; its balanced state's stability over speed is the next section, its run the section on the rotor's passage.");
        general_critical(ctx, &mut s, ctx.kind == super::Kind::User)?;
        return Ok(Some(s));
    };
    let general = crate::general::needs_general_route(&ctx.root);
    let m = &cfg.model;
    let w0 = m.scale.map(|s| s.omega0);
    let mut s = Section::new("rotor", if cfg.dimensional { "Your rotor (dimensional config)" } else { "Your rotor (dimensionless config)" });
    s.p(format!(
        "The rotor the config describes, analysed by the model of papers 000 and 003 (rigid rotor on two elastic supports, unbalance and {} in plane A).{}",
        m.masses.map_or("balancer".to_string(), |ms| format!("a {}-ball balancer", ms.n)),
        if let Some(sc) = m.scale {
            format!(
                " Speeds are given as Ω = ω/ω0 with ω0 = sqrt(c_x/M_s) = {} rad/s ({} rpm), and in rad/s and rpm.",
                fmt(sc.omega0, 4),
                grouped(sc.omega0 * RPM_PER_RAD_S, 0)
            )
        } else {
            " The config is dimensionless: speeds are Ω = ω/ω0.".to_string()
        }
    ));
    // what that model leaves out (the stderr warning's list): its numbers below are of the
    // simplified rotor; the rotor as given is analysed by the general route
    let left_out = autobal::config::ignored_by_linear_model(&ctx.root);
    if general {
        s.html(format!(
            "<div class=\"warn\">The config has what that one-plane model leaves out: {}. Its parameters, critical speeds (000), sensitivity criterion and 003's ranges below are those of the simplified rotor without them; the rotor as given is analysed by the general route (its critical speeds below, its stability and run-up in their sections).</div>\n",
            super::esc(&left_out.join(", "))
        ));
    }
    for w in &m.anisotropy.warnings {
        s.html(format!("<div class=\"warn\">{}</div>\n", super::esc(w)));
    }

    s.h3("rotor-parameters", "Parameters");
    let opt = |v: Option<f64>| v.map_or("—".to_string(), |x| fmt(x, 5));
    let mut rows = vec![
        vec!["C̄Σ".into(), fmt(m.c_sigma, 5), "–".into(), "polar / mean equatorial moment (rotor type: long < 1 < short)".into()],
        vec!["ρ̄s".into(), opt(m.rho_s), "–".into(), "radius of gyration / support span".into()],
        vec!["l̄_L".into(), opt(m.l_left), "–".into(), "centre of mass C from the left support / span".into()],
        vec!["z̄_A".into(), fmt(m.z_a, 5), "–".into(), "balancer plane A from C / ρ_s".into()],
        vec!["p̄α".into(), fmt(m.p_alpha_sq.sqrt(), 5), "–".into(), "angular support frequency".into()],
        vec!["c̄yα".into(), fmt(m.c_y_alpha, 5), "–".into(), "translation–tilt coupling of the supports".into()],
        vec!["ΔĀ (used)".into(), fmt(m.anisotropy.used, 4), "–".into(), format!("inertia anisotropy, {}", format!("{:?}", m.anisotropy.method).to_lowercase())],
        vec![
            "ΔĀ exact tensor".into(),
            if (m.anisotropy.exact[1] - m.anisotropy.exact[0]).abs() < 1e-12 {
                fmt(m.anisotropy.exact[0], 4)
            } else {
                format!("{} – {}", fmt(m.anisotropy.exact[0], 4), fmt(m.anisotropy.exact[1], 4))
            },
            "–".into(),
            "over the balancing positions of the balls".into(),
        ],
        vec!["ΔĀ eq (17)".into(), fmt(m.anisotropy.paper, 4), "–".into(), format!("paper 000's sum of magnitudes, D_A = {}", opt(m.anisotropy.d_a))],
        vec!["ΔĀ0".into(), fmt(m.delta_a0, 4), "–".into(), "anisotropy of the unbalance mass alone (003)".into()],
        vec![
            "h̄x, h̄α, h̄yα, h̄s".into(),
            format!("{}, {}, {}, {}", fmt(m.damping.h_x, 3), fmt(m.damping.h_alpha, 3), fmt(m.damping.h_y_alpha, 3), fmt(m.damping.h_s, 3)),
            "–".into(),
            "damping of supports and balls".into(),
        ],
    ];
    if let Some(ms) = m.masses {
        rows.push(vec![
            "m̄0, R̄0, m̄, R̄, n".into(),
            format!("{}, {}, {}, {}, {}", fmt(ms.m0, 4), fmt(ms.r0, 4), fmt(ms.m, 4), fmt(ms.r, 4), ms.n),
            "–".into(),
            format!("masses and radii; balancer capacity E = {}", fmt(ms.capacity(), 4)),
        ]);
    }
    if let Some(sc) = m.scale {
        rows.push(vec!["ω0".into(), fmt(sc.omega0, 5), "rad/s".into(), format!("unit of speed = {} rpm", grouped(sc.omega0 * RPM_PER_RAD_S, 0))]);
        rows.push(vec!["M_s".into(), fmt(sc.total_mass, 5), "kg".into(), "total mass".into()]);
        rows.push(vec!["ρ_s".into(), fmt(1e3 * sc.rho_s, 5), "mm".into(), "radius of gyration sqrt(A_Σ/M_s)".into()]);
        rows.push(vec!["l".into(), fmt(1e3 * sc.span, 5), "mm".into(), "support span".into()]);
    }
    s.table(&["symbol", "value", "unit", "meaning"], &rows);
    let ci = m.composite_inertia();
    let unit = if ci.si { "kg·m²" } else { "A_Σ" };
    s.table(
        &[&format!("A_Σ ({unit})"), &format!("C_Σ ({unit})"), &format!("A_C1 ({unit})"), &format!("A_C2 ({unit})"), &format!("ΔA ({unit})")],
        &[vec![fmt(ci.a_sigma, 5), fmt(ci.c_sigma, 5), fmt(ci.a_c1, 5), fmt(ci.a_c2, 5), fmt(ci.delta_a, 4)]],
    );

    if general {
        general_critical(ctx, &mut s, ctx.kind == super::Kind::User)?;
    }
    s.h3("rotor-critical", if general { "Critical speeds of the one-plane model (000)" } else { "Critical speeds" });
    let cs = critical_speeds(m);
    s.p(format!(
        "Exact roots of Δ1Δ2 = 0 (000, eq (16)) beside the approximations (18) symmetric, (19) near-symmetric and (20) small anisotropy.{}",
        if general {
            format!(
                " <b>Of the one-plane rotor of papers 000/003, which leaves out {}</b>: the critical speeds of the rotor as given are above.",
                super::esc(&left_out.join(", "))
            )
        } else {
            String::new()
        }
    ));
    let rows: Vec<Vec<String>> = cs
        .speeds
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let mut r = vec![
                format!("Ω_K{}", i + 1),
                fmt(k.omega, 5),
                format!("{:?}", k.kind).to_lowercase(),
                k.branch.to_string(),
                opt(k.approx_symmetric),
                opt(k.approx_near_symmetric),
                opt(k.approx_small_anisotropy),
            ];
            if let Some(w0) = w0 {
                r.push(grouped(k.omega * w0, 1));
                r.push(grouped(k.omega * w0 * RPM_PER_RAD_S, 0));
            } else {
                r.push(k.interval.filter(|iv| (iv[1] - iv[0]).abs() > 1e-12).map_or("—".into(), |iv| format!("{} – {}", fmt(iv[0], 4), fmt(iv[1], 4))));
            }
            r
        })
        .collect();
    let mut head = vec!["", "Ω (–)", "kind", "branch", "(18) (–)", "(19) (–)", "(20) (–)"];
    if w0.is_some() {
        head.extend(["ω (rad/s)", "n (rpm)"]);
    } else {
        head.push("over the ΔĀ interval (–)");
    }
    s.table(&head, &rows);
    s.p(format!(
        "{} distinct critical speeds; rotor class (Table 1 of 000, its short-rotor boundary corrected to C̄Σ &gt; 1 + ΔĀ): {}, for which Table 1 predicts {}.",
        cs.distinct_count,
        format!("{:?}", cs.rotor_class).to_lowercase(),
        cs.table1_count
    ));

    if ctx.kind == super::Kind::User && !general {
        let list: Vec<String> = cs
            .speeds
            .iter()
            .map(|k| match w0 {
                Some(w0) => format!("{} rpm", grouped(k.omega * w0 * RPM_PER_RAD_S, 0)),
                None => format!("Ω = {}", fmt(k.omega, 4)),
            })
            .collect();
        s.summary.push(format!("Critical speeds (the rotor with its balls held, 000 eq (16)): {}.", list.join(", ")));
    }
    let se = sensitivity(m, cfg.analysis.sensitivity_limit);
    s.h3("rotor-sensitivity", "Sensitivity criterion");
    s.table(
        &["δΩ_Kα1 exact (–)", "δΩ_Kα2 exact (–)", "δΩ_Kα1 (22) (–)", "δΩ_Kα2 (22) (–)", "[δΩ_Kα] (–)", "[ΔĀ0] (–)", "[m̄0] (–)"],
        &[vec![
            opt(se.delta_exact[0]),
            opt(se.delta_exact[1]),
            opt(se.delta_approx[0]),
            opt(se.delta_approx[1]),
            fmt(se.limit, 3),
            fmt(se.delta_a_limit, 4),
            opt(se.m0_limit),
        ]],
    );
    s.p(format!(
        "<b>Verdict{}:</b> {}",
        if general {
            " (003's criterion on the one-plane rotor: whether its inertia anisotropy may be neglected, not whether that rotor stands for the config's)"
        } else {
            ""
        },
        super::esc(&se.reason)
    ));

    s.h3("rotor-ranges", "Autobalancing ranges (003)");
    if general {
        // as `critical` says: 003's condition is of the one-plane rotor it assumes
        s.p(format!(
            "003's necessary condition does not apply to this configuration (it assumes one balancer plane, supports equal in x and y, no gravity; the config has {}), as <code>autobal critical</code> says: where the rotor as given is stable is the exact analysis of the stability section.",
            super::esc(&left_out.join(", "))
        ));
        return Ok(Some(s));
    }
    let ar = autobalancing_ranges(m);
    s.p(format!(
        "Antiresonance Ω_a = {}. Phase condition (1) holds on {}; split-pair instability on {}. <b>Autobalancing possible on {}</b> by 003's necessary condition (necessary, not sufficient: where the balanced state is stable is the exact analysis of the stability section). Class: {}.",
        ar.antiresonance_speed.map_or("—".into(), |w| speed(w, w0)),
        ranges_text(&ar.phase_condition, None),
        ranges_text(&ar.instability, None),
        ranges_text(&ar.ranges, w0),
        format!("{:?}", ar.class).to_lowercase()
    ));
    s.figure(
        "rotor_response",
        response_plot(
            m,
            crate::figures::omega_limit(m, Some(cfg.analysis.speed_axis_max(autobal::reports::default_omega_max(m)))),
            cfg.analysis.operating_speed,
        ),
        response_caption(m),
    );
    Ok(Some(s))
}

/// Signed response of plane A along the speed (003 Fig. 3 for this rotor): per unit unbalance,
/// or in mm for a dimensional rotor.
fn response_plot(m: &SpatialModel, wmax: f64, op: Option<[f64; 2]>) -> Plot {
    let (k, xl, x2) = speed_axis(m);
    // dimensional: ξ_A = (m0 R0 / M_s) · ξ̄_A/(m̄0 R̄0)
    let (amp, yl) = match (m.scale, m.masses) {
        (Some(sc), Some(ms)) => (1e3 * ms.m0 * ms.r0 * sc.rho_s, "ξ_A of plane A (mm)".to_string()),
        _ => (1.0, "ξ̄_A / (m̄0 R̄0)".to_string()),
    };
    let ar = autobalancing_ranges(m);
    let di = 1.0 - m.c_sigma - m.delta_a0;
    let asym = ((di + m.z_a * m.z_a) / di).abs();
    let ylim = (3.0 * asym).clamp(2.0, 60.0);
    let pts: Vec<(f64, f64)> = (0..=1200)
        .map(|i| {
            let w = wmax * i as f64 / 1200.0;
            let v = point_a_response(m, w);
            (k * w, if v.abs() > 10.0 * ylim { f64::NAN } else { amp * v })
        })
        .collect();
    let mut vlines: Vec<(f64, String)> = ar.critical_speeds.iter().enumerate().map(|(i, &w)| (k * w, format!("K{}", i + 1))).collect();
    if let Some(wa) = ar.antiresonance_speed {
        vlines.push((k * wa, "Ω_a".into()));
    }
    vlines.extend(operating_vlines(op, k));
    Plot {
        title: "Signed response of the balancer plane A (locked balls)".into(),
        x_label: xl,
        y_label: yl,
        series: vec![Series::new("ξ_A (negative: against the unbalance)", pts, PALETTE[0])],
        shades: ar.ranges.iter().map(|r| Shade { x: (k * r.lo, k * r.hi.unwrap_or(wmax)), y: (None, None), color: "#009E73".into() }).collect(),
        shade_label: Some("autobalancing possible (003)".into()),
        vlines,
        x_range: Some((0.0, k * wmax)),
        y_range: Some((-amp * ylim, amp * ylim)),
        x2,
        ..Default::default()
    }
}

fn response_caption(m: &SpatialModel) -> String {
    let unit = if m.scale.is_some() && m.masses.is_some() { "in mm, for the config's unbalance" } else { "per unit unbalance m̄0 R̄0" };
    format!(
        "Synchronous response of plane A of the locked, undamped rotor ({unit}), with its sign: negative where A moves against the unbalance (003, Fig. 3 for this rotor). Shaded: speeds where this holds and no split pair is unstable, i.e. where autobalancing is possible by 003's necessary condition; K1-K4 are 003's critical speeds of the unbalanced rotor (ΔĀ0 = {}), Ω_a the antiresonance.",
        fmt(m.delta_a0, 4)
    )
}
