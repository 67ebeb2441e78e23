//! `autobal campbell` and `autobal critical` on any configuration autobal can run: the general
//! route ([`autobal::rotor_campbell`], [`autobal::rotor_stability`]) for the planar rotor and for
//! spatial rotors with what paper 000's 12-state model does not have (a second plane, couple
//! unbalance, supports that differ by direction, gravity), or for any config with
//! `--route general`.

use crate::general::GeneralRotor;
use crate::plot::{Plot, Series, PALETTE};
use anyhow::Result;
use autobal::analysis::Kind;
use autobal::control::Control;
use autobal::error::fmt_num;
use autobal::rotor_campbell::{campbell_over_speed, locked_critical_speeds, LockedCriticalSpeeds, RotorCampbell, Whirl, FLOQUET_BRANCH};
use autobal::rotor_stability::{speed_grid, stability_over_speed, Rotor, RotorStability};
use serde_json::{json, Value};
use std::fmt::Write as _;
use toml::Table;

fn rpm(w: f64) -> f64 {
    w * 30.0 / std::f64::consts::PI
}

/// Six significant digits for the table (the JSON keeps every digit).
fn round(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let p = 10f64.powi(5 - x.abs().log10().floor() as i32);
    (x * p).round() / p
}

fn speed_text(g: &GeneralRotor, w: f64) -> String {
    if g.si {
        format!("{} rad/s ({} rpm)", fmt_num(round(w)), fmt_num(round(rpm(w))))
    } else {
        format!("Ω = {}", fmt_num(round(w)))
    }
}

fn unit(g: &GeneralRotor) -> &'static str {
    if g.si {
        "rad/s"
    } else {
        "Ω"
    }
}

/// The top of the speed axis (model units: rad/s, or Ω of a dimensionless spatial config):
/// `--omega-max` (a speed with its unit on an SI config, a bare number in units of ω0 or, for
/// the planar rotor, rad/s), else 3 ω_n for the planar rotor, else twice the 12-state model's
/// automatic axis (a second plane, supports that differ by direction or gravity move the modes).
pub fn omega_max(root: &Table, g: &GeneralRotor, arg: Option<&str>) -> Result<f64> {
    Ok(match (&g.rotor, arg) {
        (_, Some(t)) => {
            let s = autobal::units::parse_speed("--omega-max", t)?;
            let w = match s.unit.rad_s() {
                Some(k) if g.si => s.value * k,
                Some(_) => s.to_omega("--omega-max", None)?,
                None => s.value * g.omega0,
            };
            autobal::limits::check_as("--omega-max", "analysis.omega_max", w / g.omega0)?;
            w
        }
        (Rotor::Planar(_), None) => 3.0 * g.rotor.natural_frequency(),
        (Rotor::Spatial(_), None) => {
            let cfg = autobal::config::spatial(root)?;
            cfg.analysis.speed_axis_max(2.0 * autobal::reports::default_omega_max(&cfg.model)) * g.omega0
        }
    })
}

/// The speeds of a Campbell diagram of `points` speeds: cell middles of `(0, omega_max]`.
pub fn speeds(omega_max: f64, points: usize) -> Vec<f64> {
    let n = points.max(3);
    (0..n).map(|k| omega_max * (k as f64 + 0.5) / n as f64).collect()
}

/// The Campbell diagram of the general route, its numbers checked finite once.
pub fn campbell(g: &GeneralRotor, omega_max: f64, points: usize, control: &Control) -> Result<RotorCampbell> {
    // the library's scan takes the control when it is wired (rotor_campbell); until then it
    // is asked before the scan
    if let Some(why) = control.should_stop() {
        anyhow::bail!("{why} before the Campbell scan");
    }
    let c = campbell_over_speed(&g.rotor, &speeds(omega_max, points))?;
    autobal::limits::check_finite("campbell", &c)?;
    Ok(c)
}

fn what(c: &RotorCampbell) -> &'static str {
    match c.kind {
        Kind::Equilibrium => "eigenvalues λ = σ + iν of the exact (AD) Jacobian at the balanced state, an equilibrium in axes turning with the rotor",
        Kind::PeriodicOrbit => {
            "Floquet exponents ρ = σ + iν of the stationary periodic orbit (supports that differ by direction or gravity: the rotor sags and the balls swing once per revolution), from the monodromy matrix"
        }
    }
}

/// Whether a line is the kept one of a conjugate pair (most of its points with `Im ≥ 0`) and a
/// mode (not structural).
fn kept(l: &autobal::rotor_campbell::CampbellLine) -> bool {
    let pts: Vec<_> = l.points.iter().flatten().collect();
    let up = pts.iter().filter(|p| p.im >= 0.0).count();
    !pts.is_empty() && 2 * up >= pts.len() && !pts.iter().all(|p| p.structural)
}

/// The JSON of the general Campbell diagram.
pub fn campbell_json(g: &GeneralRotor, c: &RotorCampbell, omega_max: f64) -> Value {
    let mut v = json!({
        "route": "general",
        "model": c.model,
        "stationary_state": c.kind,
        "what": what(c),
        "speed_unit": unit(g),
        "omega_max": omega_max,
        "omega": c.omega,
        "lines": c.lines,
        "failures": c.failures,
        "fixed_axes": "fixed_frequency f = Ω ± ν of the dominant circular component of the rotor's motion (> 0 forward whirl); log_decrement per fixed-axes cycle −2πσ/|f|",
    });
    if c.kind == Kind::PeriodicOrbit {
        v["branch"] = json!(FLOQUET_BRANCH);
    }
    if g.si {
        v["omega_rpm"] = json!(c.omega.iter().map(|&w| rpm(w)).collect::<Vec<_>>());
    }
    v
}

fn whirl_name(w: Whirl) -> &'static str {
    match w {
        Whirl::Forward => "forward",
        Whirl::Backward => "backward",
        Whirl::None => "none",
    }
}

/// The table of the general Campbell diagram: at five speeds, each mode (one of each conjugate
/// pair, structural zeros left out) with its rotating-axes and fixed-axes numbers.
pub fn campbell_table(g: &GeneralRotor, c: &RotorCampbell) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Campbell diagram (general route, {} rotor)", c.model);
    let _ = writeln!(s, "values: {}", what(c));
    if c.kind == Kind::PeriodicOrbit {
        let _ = writeln!(s, "branch: {FLOQUET_BRANCH}");
    }
    let rate = if g.si { "1/s" } else { "ω0" };
    let _ =
        writeln!(s, "ν, σ in {rate} (turning axes); fixed f = Ω ± ν of the dominant whirl component (fixed axes, > 0 forward); log dec per fixed-axes cycle");
    let n = c.omega.len();
    let mut at = vec![0, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)];
    at.dedup();
    for k in at {
        let _ = writeln!(s, "\nspeed {}", speed_text(g, c.omega[k]));
        if let Some(f) = &c.failures[k] {
            let _ = writeln!(s, "  no stationary state: {f}");
            continue;
        }
        let hz = if g.si { format!(" {:>11}", "fixed Hz") } else { String::new() };
        let _ = writeln!(s, "  {:>12} {:>12} {:>10} {:>12}{hz}  {:<9}", "ν", "σ", "log dec", "fixed f", "whirl");
        let mut pts: Vec<_> = c.lines.iter().filter(|l| kept(l)).filter_map(|l| l.points[k]).filter(|p| !p.structural && p.im >= 0.0).collect();
        pts.sort_by(|a, b| a.fixed_frequency.abs().total_cmp(&b.fixed_frequency.abs()));
        for p in pts {
            let hz = if g.si { format!(" {:>11}", fmt_num(round(p.fixed_frequency / (2.0 * std::f64::consts::PI)))) } else { String::new() };
            let _ = writeln!(
                s,
                "  {:>12} {:>12} {:>10} {:>12}{hz}  {:<9}",
                fmt_num(round(p.im)),
                fmt_num(round(p.re)),
                p.log_decrement.map_or("—".into(), |d| format!("{d:.4}")),
                fmt_num(round(p.fixed_frequency)),
                whirl_name(p.whirl)
            );
        }
    }
    let missing = c.failures.iter().filter(|f| f.is_some()).count();
    if missing > 0 {
        let first = c.failures.iter().flatten().next().cloned().unwrap_or_default();
        let _ = writeln!(s, "\nno stationary state at {missing} of {n} speeds (first: {first})");
    }
    s
}

/// The fixed-axes Campbell figure: `|f|` of each mode over speed, forward whirl solid, backward
/// dashed, and the line `1×Ω`.
pub fn campbell_plot(g: &GeneralRotor, c: &RotorCampbell, omega_max: f64) -> Plot {
    let mut series = vec![];
    let mut top = omega_max;
    for (i, l) in c.lines.iter().filter(|l| kept(l)).enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        for (dir, dashed) in [(Whirl::Forward, false), (Whirl::Backward, true)] {
            let pts: Vec<(f64, f64)> = l
                .points
                .iter()
                .zip(&c.omega)
                .map(|(p, &w)| match p {
                    Some(p) if p.whirl == dir && !p.structural => (w, p.fixed_frequency.abs()),
                    _ => (w, f64::NAN),
                })
                .collect();
            if pts.iter().all(|p| p.1.is_nan()) {
                continue;
            }
            top = top.max(pts.iter().map(|p| p.1).filter(|v| v.is_finite() && *v <= 4.0 * omega_max).fold(0.0, f64::max));
            let label = format!("mode {} {}", i + 1, whirl_name(dir));
            let s = Series::new(label, pts, color).group(format!("mode {}", i + 1));
            series.push(if dashed { s.dashed() } else { s });
        }
    }
    series.push(Series::new("1×Ω", vec![(0.0, 0.0), (omega_max, omega_max)], "#888888").dashed());
    let u = if g.si { "rad/s" } else { "ω0" };
    Plot {
        title: format!("Campbell diagram in fixed axes (general route, {})", if c.kind == Kind::PeriodicOrbit { "Floquet exponents" } else { "eigenvalues" }),
        x_label: if g.si { "speed ω (rad/s)".into() } else { "speed Ω".into() },
        y_label: format!("natural frequency |f| ({u}); dashed: backward whirl"),
        series,
        x_range: Some((0.0, omega_max)),
        y_range: Some((0.0, 1.05 * top)),
        ..Default::default()
    }
}

/// `critical` by the general route: the locked critical speeds, the exact stability ranges and,
/// on a config that paper 000's 12-state model represents, 003's necessary condition.
pub struct GeneralCritical {
    /// The critical speeds with the balls locked at balance, or why they were not located.
    pub locked: std::result::Result<LockedCriticalSpeeds, String>,
    /// The exact stability of the stationary state over speed, or why there is none (real
    /// balls: no linearisation).
    pub stability: std::result::Result<RotorStability, String>,
    /// 003's necessary ranges in the speed unit of the route (`(lo, hi)`, `hi = None` for
    /// `+∞`), where they apply (one plane, isotropic, no gravity).
    pub necessary: Option<Vec<(f64, Option<f64>)>>,
    /// The top of the speed axis.
    pub omega_max: f64,
}

/// Run `critical` by the general route over `(0, omega_max]`.
pub fn critical(root: &Table, g: &GeneralRotor, omega_max: f64, control: &Control) -> Result<GeneralCritical> {
    // the library's scans take the control when it is wired (rotor_campbell, rotor_stability);
    // until then it is asked before them
    if let Some(why) = control.should_stop() {
        anyhow::bail!("{why} before the critical speeds");
    }
    let locked = match locked_critical_speeds(&g.rotor, omega_max, 2000) {
        Ok(l) => Ok(l),
        Err(e @ autobal::Error::NoLinearisation { .. }) => Err(e.to_string()),
        Err(e) => return Err(e.into()),
    };
    let samples = if g.rotor.is_periodic() { 50 } else { 200 };
    let stability = match stability_over_speed(&g.rotor, &speed_grid(omega_max, samples)?) {
        Ok(s) => Ok(s),
        Err(e @ autobal::Error::NoLinearisation { .. }) => Err(e.to_string()),
        Err(e) => return Err(e.into()),
    };
    let necessary = if autobal::config::is_spatial(root) && autobal::config::ignored_by_linear_model(root).is_empty() {
        let cfg = autobal::config::spatial(root)?;
        Some(autobal::spatial::ranges::autobalancing_ranges(&cfg.model).ranges.iter().map(|r| (r.lo * g.omega0, r.hi.map(|h| h * g.omega0))).collect())
    } else {
        None
    };
    if let Ok(l) = &locked {
        autobal::limits::check_finite("critical.locked", l)?;
    }
    if let Ok(st) = &stability {
        autobal::limits::check_finite("critical.stability", &st.stable_ranges)?;
    }
    Ok(GeneralCritical { locked, stability, necessary, omega_max })
}

const LOCKED_WHAT: &str = "balls locked at the closed-form balanced position (point masses of the rotor), no damping: speeds where a natural frequency in fixed axes equals the speed (a whirl standing still in turning axes: the stiffness block of the exact Jacobian is singular)";

/// The JSON of the general `critical`.
pub fn critical_json(g: &GeneralRotor, c: &GeneralCritical) -> Value {
    let to_si = |w: f64| if g.si { json!({ "rad_s": w, "rpm": rpm(w) }) } else { Value::Null };
    let mut v = json!({
        "route": "general",
        "model": g.rotor.model_name(),
        "speed_unit": unit(g),
        "omega_max": c.omega_max,
        "locked_critical_speeds": match &c.locked {
            Ok(l) => json!({
                "what": LOCKED_WHAT,
                "speeds": l.speeds.iter().map(|s| {
                    let mut e = json!({ "omega": s.omega, "multiplicity": s.multiplicity, "motion": s.motion, "whirl": s.whirl });
                    if g.si { e["rpm"] = json!(rpm(s.omega)); }
                    e
                }).collect::<Vec<_>>(),
                "grid": l.samples,
                "ball_angles": l.ball_angles,
                "speeds_without_balanced_state": l.unlocked,
            }),
            Err(e) => json!({ "what": LOCKED_WHAT, "speeds": Value::Null, "not_located": e }),
        },
    });
    match &c.stability {
        Ok(st) => {
            v["exact_stable_ranges"] = json!(st.stable_ranges.iter().map(|s| {
                json!({ "from": s.from, "to": s.to, "from_is_boundary": s.from_is_boundary, "to_is_boundary": s.to_is_boundary, "from_si": to_si(s.from), "to_si": to_si(s.to) })
            }).collect::<Vec<_>>());
            v["stationary_state"] = json!(st.kind);
            v["family_dimension"] = json!(st.family_dimension);
            v["member_psi"] = json!(st.member_psi);
        }
        Err(e) => {
            v["exact_stable_ranges"] = Value::Null;
            v["stability_not_analysed"] = json!(e);
        }
    }
    v["necessary_condition_003"] = match &c.necessary {
        Some(r) => json!({
            "what": "necessary condition for autobalancing (003 eqs (1)-(3)), not sufficient: the exact ranges above decide",
            "ranges": r.iter().map(|(lo, hi)| json!({ "from": lo, "to": hi })).collect::<Vec<_>>(),
        }),
        None => {
            json!({ "what": "003's necessary condition does not apply to this configuration (it assumes one balancer plane, supports equal in x and y, no gravity)", "ranges": Value::Null })
        }
    };
    v
}

/// The table of the general `critical`.
pub fn critical_table(g: &GeneralRotor, c: &GeneralCritical) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Critical speeds and exact stability (general route, {} rotor)", g.rotor.model_name());
    let _ = writeln!(s, "critical speeds: {LOCKED_WHAT}");
    match &c.locked {
        Ok(l) if l.speeds.is_empty() => {
            let _ = writeln!(s, "  none up to {}", speed_text(g, c.omega_max));
        }
        Ok(l) => {
            for (i, k) in l.speeds.iter().enumerate() {
                let motion = serde_json::to_string(&k.motion).unwrap_or_default();
                let _ = writeln!(
                    s,
                    "  {:>2}. {}  {} whirl, {} (multiplicity {})",
                    i + 1,
                    speed_text(g, k.omega),
                    whirl_name(k.whirl),
                    motion.trim_matches('"'),
                    k.multiplicity
                );
            }
        }
        Err(e) => {
            let _ = writeln!(s, "  not located: {e}");
        }
    }
    if let Ok(l) = &c.locked {
        if !l.ball_angles.is_empty() {
            let deg: Vec<String> = l.ball_angles.iter().map(|p| format!("{:.2}°", p.to_degrees().rem_euclid(360.0))).collect();
            let _ = writeln!(
                s,
                "  balls locked at {} (with 3 or more balls in a plane the balanced states form a family: these speeds are the named member's)",
                deg.join(", ")
            );
        }
        if l.unlocked > 0 {
            let _ = writeln!(s, "  ({} of {} speeds have no balanced state to lock the balls in and were not searched)", l.unlocked, l.samples);
        }
    }
    let st = match &c.stability {
        Ok(st) => st,
        Err(e) => {
            let _ = writeln!(s, "\nexact stability: not analysed: {e}");
            return s;
        }
    };
    let _ = writeln!(
        s,
        "\nexact stability of the {} (balls free; {}):",
        match (&g.rotor, st.kind) {
            (_, Kind::PeriodicOrbit) => "stationary periodic orbit",
            (Rotor::Planar(p), _) if p.s2 != 0.0 => "semi-balanced state (race centre on the axis)",
            _ => "balanced state",
        },
        if st.kind == Kind::PeriodicOrbit { "Floquet multipliers" } else { "eigenvalues of the exact Jacobian" }
    );
    if st.stable_ranges.is_empty() {
        let _ = writeln!(s, "  stable: nowhere in (0, {}]", speed_text(g, c.omega_max));
    }
    for r in &st.stable_ranges {
        let end = |w: f64, b: bool, edge: &str| if b { speed_text(g, w) } else { format!("{} ({edge} of the axis)", speed_text(g, w)) };
        let _ = writeln!(s, "  stable: {} to {}", end(r.from, r.from_is_boundary, "start"), end(r.to, r.to_is_boundary, "end"));
    }
    match &c.necessary {
        Some(r) => {
            let txt: Vec<String> = r.iter().map(|(lo, hi)| format!("{} to {}", speed_text(g, *lo), hi.map_or("∞".into(), |h| speed_text(g, h)))).collect();
            let _ = writeln!(
                s,
                "\nnecessary condition for autobalancing (003; necessary, not sufficient: the exact ranges above decide): {}",
                if txt.is_empty() { "none".into() } else { txt.join(", ") }
            );
        }
        None => {
            let _ = writeln!(s, "\n003's necessary condition does not apply (it assumes one balancer plane, supports equal in x and y, no gravity)");
        }
    }
    s
}
