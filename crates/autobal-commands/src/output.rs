//! Tables and JSON for the analytic commands.

use crate::config::Config;
use autobal::spatial::critical_speeds::{critical_speeds, CriticalSpeeds};
use autobal::spatial::ranges::{autobalancing_ranges, AutobalancingRanges};
use autobal::spatial::sensitivity::sensitivity;
use serde_json::Value;
use std::fmt::Write;

pub use autobal::reports::scale_ranges;
pub use autobal::spatial::comparison::fmt_ranges;

/// `autobal critical`'s JSON on the 12-state model ([`autobal::reports::CriticalReport`]).
pub fn critical_json(cfg: &Config) -> Value {
    autobal::reports::to_json(&autobal::reports::critical(&cfg.config, &cfg.source))
}

/// The result of a command whose JSON and table are both built once from the config
/// (`inertia`, `ranges`: [`crate::any_config`]).
pub struct JsonTable {
    /// The JSON.
    pub json: Value,
    /// The text table.
    pub table: String,
}

impl crate::command::Output for JsonTable {
    fn json(&self) -> anyhow::Result<Value> {
        Ok(self.json.clone())
    }
    fn table(&self) -> anyhow::Result<String> {
        Ok(self.table.clone())
    }
}

fn opt(x: Option<f64>, prec: usize) -> String {
    x.map_or("—".into(), |v| format!("{v:.prec$}"))
}

fn header(cfg: &Config, s: &mut String) {
    let m = &cfg.model;
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(
        s,
        "C̄Σ = {:.4}  ρ̄s = {}  l̄_L = {}  z̄_A = {:.4}  p̄α = {:.4}  c̄yα = {:.4}",
        m.c_sigma,
        opt(m.rho_s, 4),
        opt(m.l_left, 4),
        m.z_a,
        m.p_alpha_sq.sqrt(),
        m.c_y_alpha
    );
    if let Some(sc) = m.scale {
        let _ = writeln!(
            s,
            "ω0 = {:.4} rad/s ({:.1} rpm), M_s = {:.4} kg, ρ_s = {:.4} m, span l = {:.4} m",
            sc.omega0,
            sc.omega0 * 30.0 / std::f64::consts::PI,
            sc.total_mass,
            sc.rho_s,
            sc.span
        );
    }
    let a = &m.anisotropy;
    let _ = writeln!(s, "anisotropy ΔĀ: used {:.6} ({:?}); exact tensor {}; paper eq (17) {}", a.used, a.method, fmt_pair(a.exact), fmt_pair(a.paper_interval));
    // the comparison with eq (17) is a property of the paper's formula: `inertia` prints it
    for w in autobal::reports::actionable_warnings(a) {
        let _ = writeln!(s, "warning: {w}");
    }
}

fn fmt_pair(p: [f64; 2]) -> String {
    if (p[0] - p[1]).abs() <= 1e-12 * p[1].abs().max(1.0) {
        format!("{:.6}", p[0])
    } else {
        format!("[{:.6}, {:.6}]", p[0], p[1])
    }
}

pub fn inertia_table(cfg: &Config) -> String {
    let mut s = String::new();
    header(cfg, &mut s);
    for w in cfg.model.anisotropy.warnings.iter().filter(|w| autobal::reports::is_eq17_comparison(w)) {
        let _ = writeln!(s, "note: {w}");
    }
    let ci = cfg.model.composite_inertia();
    let unit = if ci.si { " kg·m²" } else { " ×A_Σ" };
    let _ = writeln!(s, "\ncomposite inertia");
    if let Some(mt) = ci.total_mass {
        let _ = writeln!(s, "  M_s   = {mt:.6} kg");
    }
    for (k, v) in [("A_Σ", ci.a_sigma), ("C_Σ", ci.c_sigma), ("A_C1", ci.a_c1), ("A_C2", ci.a_c2), ("ΔA", ci.delta_a)] {
        let _ = writeln!(s, "  {k:<5} = {v:.6}{unit}");
    }
    if let Some(ang) = &cfg.model.anisotropy.ball_angles {
        let deg: Vec<String> = ang.iter().map(|a| format!("{:.2}°", a.to_degrees())).collect();
        let _ = writeln!(s, "  ball angles at balance (from the unbalance): {}", deg.join(", "));
    }
    s
}

/// The whole rotor's mass properties ([`autobal::reports::WholeRotor`]) as a table.
pub fn whole_rotor_table(w: &autobal::reports::WholeRotor) -> String {
    let p = &w.properties;
    let (kg, m, kgm2, kgm) = if w.si { (" kg", " m", " kg·m²", " kg·m") } else { ("", "", "", "") };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nwhole rotor as the simulation builds it (rotor, every unbalance mass, every ball){}",
        if w.si { "" } else { ", in the papers' units M_s = 1, ρ_s = 1" }
    );
    let _ = writeln!(s, "  balls: {}", w.placement.note);
    if !w.placement.angles.is_empty() {
        let deg: Vec<String> = w.placement.angles.iter().map(|a| format!("{:.2}°", ((a.to_degrees() * 100.0).round() / 100.0).rem_euclid(360.0))).collect();
        let _ = writeln!(s, "  ball angles (rotor frame, from its x axis): {}", deg.join(", "));
    }
    let _ = writeln!(s, "  total mass M = {:.6}{kg}", p.total_mass);
    let c = p.centre_of_mass;
    let _ = writeln!(s, "  centre of mass (x, y, z) = ({:.6e}, {:.6e}, {:.6}){m}", c[0], c[1], c[2]);
    let _ = writeln!(s, "  inertia tensor about it (rotor frame x, y, z){}:", if w.si { ", kg·m²" } else { "" });
    for row in &p.inertia {
        let _ = writeln!(s, "    [{:>14.6e} {:>14.6e} {:>14.6e}]", row[0], row[1], row[2]);
    }
    let _ = writeln!(
        s,
        "  principal moments: polar {:.6}{kgm2}; equatorial {:.6}, {:.6}{kgm2} (difference {:.6e})",
        p.polar_moment,
        p.equatorial_moments[0],
        p.equatorial_moments[1],
        p.equatorial_moments[0] - p.equatorial_moments[1]
    );
    if p.axis_tilt < 1e-12 {
        let _ = writeln!(s, "  principal axis nearest the shaft: along the shaft (tilt {:.1e} rad, round-off)", p.axis_tilt);
    } else {
        let _ = writeln!(
            s,
            "  principal axis nearest the shaft: tilted {:.6e} rad ({:.4}°) from it, towards {:.2}° (rotor frame)",
            p.axis_tilt,
            p.axis_tilt.to_degrees(),
            // to the printed digits, without a "-0.00"
            (p.axis_tilt_angle.to_degrees() * 100.0).round() / 100.0 + 0.0
        );
    }
    let _ = writeln!(
        s,
        "  residual static unbalance |M c| = {:.6e}{kgm}; residual couple |(−I_xz, −I_yz)| = {:.6e}{kgm2}",
        p.static_unbalance[0].hypot(p.static_unbalance[1]),
        p.couple_unbalance[0].hypot(p.couple_unbalance[1])
    );
    let _ = writeln!(s, "  (supports and gravity act on the rotor: they are not part of its mass and do not enter)");
    s
}

pub fn critical_rows(cs: &CriticalSpeeds, dimensional: bool) -> Vec<[String; 8]> {
    cs.speeds
        .iter()
        .enumerate()
        .map(|(i, k)| {
            [
                format!("Ω_K{}", i + 1),
                format!("{:.6}", k.omega),
                format!("{:?}", k.kind).to_lowercase(),
                k.branch.to_string(),
                opt(k.approx_symmetric, 4),
                opt(k.approx_near_symmetric, 4),
                opt(k.approx_small_anisotropy, 4),
                if dimensional {
                    format!("{:.2} rad/s = {:.1} rpm", k.omega_rad_s.unwrap_or(f64::NAN), k.rpm.unwrap_or(f64::NAN))
                } else {
                    k.interval.map_or("—".into(), |iv| if (iv[1] - iv[0]).abs() < 1e-12 { "—".into() } else { format!("[{:.4}, {:.4}]", iv[0], iv[1]) })
                },
            ]
        })
        .collect()
}

pub fn critical_table(cfg: &Config) -> String {
    let mut s = String::new();
    header(cfg, &mut s);
    let op = autobal::reports::operating_of(&cfg.config, autobal::spatial::linear_model::Balls::Free);
    let exact = op.as_ref().and_then(|v| v.as_ref().ok()).map(|v| (v.stable_ranges.clone(), v.span));
    s.push_str(&crate::linear::operating_lines(cfg, op));
    let cs = critical_speeds(&cfg.model);
    let last = if cfg.dimensional { "SI" } else { "over ΔĀ interval" };
    let _ = writeln!(s, "\ncritical speeds (exact roots of eq (16)); approximations (18) symmetric, (19) near-symmetric, (20) small ΔĀ");
    let _ = writeln!(s, "  {:<6} {:>10}  {:<10} {:>2}  {:>7} {:>7} {:>7}  {}", "", "Ω", "kind", "br", "(18)", "(19)", "(20)", last);
    for r in critical_rows(&cs, cfg.dimensional) {
        let _ = writeln!(s, "  {:<6} {:>10}  {:<10} {:>2}  {:>7} {:>7} {:>7}  {}", r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7]);
    }
    let _ =
        writeln!(s, "  {} distinct; inertia class (000 Table 1): {}, which Table 1 says has {}", cs.distinct_count, cs.rotor_class.label(), cs.table1_count);
    let se = sensitivity(&cfg.model, cfg.analysis.sensitivity_limit);
    let _ = writeln!(s, "\nsensitivity criterion (000 eqs (21)-(22), 003 eqs (4)-(5))");
    let _ = writeln!(
        s,
        "  δΩ_Kα1,2 exact: {}, {}   eq (22): {}, {}",
        opt(se.delta_exact[0], 4),
        opt(se.delta_exact[1], 4),
        opt(se.delta_approx[0], 4),
        opt(se.delta_approx[1], 4)
    );
    let _ =
        writeln!(s, "  [ΔĀ0] = {:.4} for [δΩ_Kα] = {}{}", se.delta_a_limit, se.limit, se.m0_limit.map_or(String::new(), |m| format!(", i.e. [m̄0] = {m:.4}")));
    let _ = writeln!(s, "  verdict: {}", se.reason);
    s.push_str(&ranges_block(cfg, &autobalancing_ranges(&cfg.model)));
    if let Some((r, span)) = exact {
        let _ = writeln!(
            s,
            "  exact stable ranges (eigenvalues, balls free), 0 < Ω ≤ {}: {}",
            crate::num::fmt(span, 4),
            autobal::spatial::comparison::fmt_ranges_in(&r, 4, Some(span))
        );
        if let Some(sc) = cfg.model.scale {
            let k = sc.omega0 * 30.0 / std::f64::consts::PI;
            let _ = writeln!(s, "                            {} rpm", autobal::spatial::comparison::fmt_ranges_in(&scale_ranges(&r, k), 0, Some(span * k)));
        }
    } else {
        let _ = writeln!(s, "  (necessary only: `autobal stability` computes the exact stable ranges)");
    }
    s
}

fn ranges_block(cfg: &Config, ar: &AutobalancingRanges) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "\nautobalancing (003 eqs (1)-(3), anisotropy of the unbalance alone ΔĀ0 = {:.4})", cfg.model.delta_a0);
    let si =
        |w: f64| cfg.model.scale.map_or(String::new(), |sc| format!(" ({:.1} rad/s, {:.0} rpm)", w * sc.omega0, w * sc.omega0 * 30.0 / std::f64::consts::PI));
    let _ = writeln!(s, "  antiresonance Ω_a = {}{}", opt(ar.antiresonance_speed, 4), ar.antiresonance_speed.map_or(String::new(), si));
    let _ = writeln!(
        s,
        "  critical speeds of the unbalanced rotor: {}",
        ar.critical_speeds.iter().map(|&w| format!("{w:.4}{}", si(w))).collect::<Vec<_>>().join(", ")
    );
    let _ = writeln!(s, "  phase condition (1) holds: {}", fmt_ranges(&ar.phase_condition, 4));
    let _ = writeln!(s, "  split-pair instability:   {}", fmt_ranges(&ar.instability, 4));
    let _ = writeln!(s, "  necessary condition for autobalancing (003): {}", fmt_ranges(&ar.ranges, 4));
    if let Some(sc) = cfg.model.scale {
        let k = sc.omega0 * 30.0 / std::f64::consts::PI;
        let _ = writeln!(s, "                                               {} rpm", fmt_ranges(&scale_ranges(&ar.ranges, k), 0));
    }
    let _ = writeln!(s, "  autobalancing class (003): {}", ar.class.label());
    s
}

pub fn ranges_table(cfg: &Config) -> String {
    let mut s = String::new();
    header(cfg, &mut s);
    s.push_str(&ranges_block(cfg, &autobalancing_ranges(&cfg.model)));
    s
}

/// Every number the analytic commands report is finite (else the error names the quantity).
pub fn check_results(cfg: &Config) -> anyhow::Result<()> {
    Ok(autobal::reports::check_results(&cfg.config)?)
}
