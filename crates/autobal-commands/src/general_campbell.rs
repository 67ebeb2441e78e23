//! `autobal campbell` and `autobal critical` on any configuration autobal can run: the general
//! route ([`autobal::rotor_campbell`], [`autobal::rotor_stability`]) for the planar rotor and for
//! spatial rotors with what paper 000's 12-state model does not have (a second plane, couple
//! unbalance, supports that differ by direction, gravity), or for any config with
//! `--route general`.

use crate::general::GeneralRotor;
use crate::plot::{Plot, Series};
use anyhow::Result;
use autobal::analysis::Kind;
use autobal::control::Control;
use autobal::error::fmt_num;
use autobal::rotor_campbell::{
    campbell_locked, fixed_view, fixed_view_with, locked_critical_speeds, Balls, LockedCriticalSpeeds, RotorCampbell, Whirl, FLOQUET_BRANCH,
};
use autobal::rotor_stability::{speed_grid, stability_over_speed, Rotor, RotorStability, StateKind};
use autobal::spatial::campbell::FixedCampbell;
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

/// The unit of the frequencies (`im`, `fixed_frequency`, `frequency`, `nu`): rad/s on an SI
/// config, multiples of ω0 on a dimensionless one (as the 12-state route's `(ω0)` columns).
fn frequency_unit(g: &GeneralRotor) -> &'static str {
    if g.si {
        "rad/s"
    } else {
        "ω0"
    }
}

/// The unit of the growth rates (`re`): 1/s on an SI config, multiples of ω0 on a dimensionless
/// one.
fn rate_unit(g: &GeneralRotor) -> &'static str {
    if g.si {
        "1/s"
    } else {
        "ω0"
    }
}

/// [`autobal::units::parse_speed`] for a rotor whose speeds are rad/s (a planar or linear
/// rotor): its errors do not offer "a bare number for the dimensionless Ω", which such a rotor
/// does not have (review 32: `campbell --omega-max abc` on a linear rotor); `bare` is what
/// replaces it: `""` where a bare number is refused (a linear rotor), `", or a bare number in
/// rad/s"` where it is read so (a planar rotor).
pub fn parse_speed_rad_s(field: &str, text: &str, bare: &str) -> autobal::Result<autobal::units::Speed> {
    autobal::units::parse_speed(field, text).map_err(|e| match e {
        autobal::Error::InvalidParameter { field, reason } => {
            autobal::Error::InvalidParameter { field, reason: reason.replace(", or a bare number for the dimensionless Ω", bare) }
        }
        e => e,
    })
}

/// The top of the speed axis (model units: rad/s, or Ω of a dimensionless spatial config):
/// `--omega-max` (a speed with its unit on an SI config, a bare number in units of ω0 or, for
/// the planar rotor, rad/s), else 3 ω_n for the planar rotor, else twice the 12-state model's
/// automatic axis (a second plane, supports that differ by direction or gravity move the modes).
pub fn omega_max(root: &Table, g: &GeneralRotor, arg: Option<&str>) -> Result<f64> {
    Ok(match (&g.rotor, arg) {
        (_, Some(t)) => {
            let s = match &g.rotor {
                Rotor::Planar(_) => parse_speed_rad_s("--omega-max", t, ", or a bare number in rad/s")?,
                Rotor::Linear(_) => parse_speed_rad_s("--omega-max", t, "")?,
                Rotor::Spatial(_) => autobal::units::parse_speed("--omega-max", t)?,
            };
            let w = match s.unit.rad_s() {
                Some(k) if g.si => s.value * k,
                Some(_) => s.to_omega("--omega-max", None)?,
                None => {
                    if g.si && matches!(g.rotor, Rotor::Spatial(_)) {
                        // the 12-state route's note (crate::linear::speed_arg), this route's speed
                        crate::linear::bare_speed_note("--omega-max", t, &format!("{} rad/s", fmt_num(s.value * g.omega0)));
                    }
                    s.value * g.omega0
                }
            };
            match &g.rotor {
                // rad/s, a planar or linear rotor's unit (the dimensionless range called 1.0472e6
                // rad/s from `1e7 rpm` "dimensionless")
                Rotor::Planar(_) | Rotor::Linear(_) => crate::command::check_speed_rad_s("--omega-max", t, w)?,
                Rotor::Spatial(_) => crate::command::check_speed_omega("--omega-max", t, w / g.omega0, g.si.then_some(g.omega0))?,
            }
            w
        }
        // the general route's default axis, as `stability`'s
        (_, None) => crate::general::default_omega_max(g, root)?,
    })
}

/// The speeds of a Campbell diagram of `points` speeds: cell middles of `(0, omega_max]`.
pub fn speeds(omega_max: f64, points: usize) -> Vec<f64> {
    let n = points.max(3);
    (0..n).map(|k| omega_max * (k as f64 + 0.5) / n as f64).collect()
}

/// The general route's Campbell diagram with what the 12-state route gives beside it
/// ([`crate::linear::campbell_run`]): the fixed-axes view (one curve per mode, its log
/// decrement) and the crossings with the excitation lines `h×Ω`, for the balls free or locked.
pub struct GeneralCampbell {
    /// The tracked eigenvalues (or Floquet exponents) over speed.
    pub diagram: RotorCampbell,
    /// Free, or locked at the closed-form balanced position.
    pub balls: Balls,
    /// The harmonics `h` of the excitation lines.
    pub harmonics: Vec<u32>,
    /// The fixed-axes view (crossings empty where [`GeneralCampbell::crossings_not_given`]
    /// says why), `None` where it could not be formed.
    pub fixed: Option<FixedCampbell>,
    /// Why the crossings (critical speeds) are not given, where they are not: Floquet
    /// exponents (defined modulo 2π/T: Ω, or 2Ω where T = π/Ω), or a crossing whose stationary state was not found.
    pub crossings_not_given: Option<String>,
    /// Why the diagram is incomplete (Ctrl-C, a budget) and what it kept, `None` when complete:
    /// the speeds analysed before the stop (no crossings), or every speed with the search for
    /// the crossings stopped (the command prints it and exits 2, as the closed-form route).
    pub stopped: Option<String>,
    /// The balls free: `stability`'s analysis at the diagram's first speed with a balanced
    /// (semi-balanced) state, for the family of balanced states and the member the values are
    /// of (review 34's D5: neither named), in `stability`'s words (`general::family_line`);
    /// `None` with the balls locked, a stopped scan, or no such speed.
    pub member: Option<RotorStability>,
}

/// What the mode numbers are where they were ranked at the first speed (no spectrum at the
/// reference speed: a periodic orbit's Floquet exponents).
pub const MODES_AT_FIRST_SPEED: &str = "ranked at the first speed of the grid, not at the reference speed 0.001 ω_n (no spectrum found there: a periodic orbit's Floquet exponents, or no stationary state): they can change with --points and --omega-max";

/// Why a periodic orbit's diagram has no crossing speeds.
pub const FLOQUET_CROSSINGS: &str = "not defined for Floquet exponents: their imaginary parts are defined modulo 2π/T (Ω under gravity, 2Ω where only the supports differ by direction), so a curve's crossing of h×Ω is a crossing of other harmonics on other branches; `autobal critical` gives the locked rotor's critical speeds where they are defined";

/// The Campbell diagram of the general route with the balls `balls` (`--balls`), its fixed-axes
/// view and the crossings with `h×Ω` for each of `harmonics` (`--harmonics`, checked by
/// [`crate::linear::check_harmonics`]), its numbers checked finite once.
pub fn campbell_with(g: &GeneralRotor, omega_max: f64, points: usize, balls: Balls, harmonics: &[u32], control: &Control) -> Result<GeneralCampbell> {
    let sp = speeds(omega_max, points);
    // the scan asks the control once per speed; stopped, the speeds analysed are kept and said
    // (session 23; the closed-form route's rule: no crossings over a partial grid)
    let mut stopped = None;
    let c = match balls {
        Balls::Free => {
            let out = autobal::rotor_campbell::campbell_over_speed_with(&g.rotor, &sp, control).map_err(|e| crate::general::floor_in_units(g, e, &sp))?;
            if let Some(why) = out.stopped {
                stopped = Some(format!(
                    "{why}: {} of {} speeds analysed; what was analysed is printed (its curves end where the scan stopped; no critical speeds)",
                    out.value.omega.len(),
                    sp.len()
                ));
            }
            out.value
        }
        Balls::Locked => campbell_locked(&g.rotor, &sp).map_err(|e| crate::general::floor_in_units(g, e, &sp))?,
    };
    autobal::limits::check_finite("campbell", &c)?;
    // stopped: no fixed-axes view either (its mode numbers are tracked to a reference speed
    // without the control: a Ctrl-C would wait for it)
    let (fixed, mut why) = if stopped.is_some() {
        (None, Some("not located: the scan stopped before its last speed (no fixed-axes view)".to_string()))
    } else {
        match fixed_view_with(&g.rotor, balls, &c, harmonics, control) {
            Ok(f) => (Some(f), None),
            // Ctrl-C (or the budget) during the search for the critical speeds: every speed's
            // curves kept, no crossing (exit 2, as a stop during the scan)
            Err(_) if control.should_stop().is_some() => {
                stopped = Some(format!(
                    "interrupted: all {} speeds analysed, the search for critical speeds stopped (none given); what was analysed is printed",
                    sp.len()
                ));
                (None, Some("not located: the search was stopped (no fixed-axes view)".to_string()))
            }
            // a crossing's stationary state not found: the curves without the crossings, and why
            Err(e) => match fixed_view(&g.rotor, balls, &c, &[]) {
                Ok(mut f) => {
                    f.harmonics = harmonics.to_vec();
                    (Some(f), Some(format!("not located: {e}")))
                }
                Err(e) => (None, Some(format!("no fixed-axes view: {e}"))),
            },
        }
    };
    if c.kind == Kind::PeriodicOrbit {
        why = Some(FLOQUET_CROSSINGS.into());
    }
    if let Some(f) = &fixed {
        autobal::limits::check_finite("campbell.critical_speeds", &f.critical_speeds)?;
    }
    let member = if balls == Balls::Free && stopped.is_none() { member_at_first_state(g, &c, control) } else { None };
    Ok(GeneralCampbell { diagram: c, balls, harmonics: harmonics.to_vec(), fixed, crossings_not_given: why, stopped, member })
}

/// `stability` at the diagram's first speed whose state is balanced (semi-balanced), Newton
/// from the closed form as the diagram's: the family's dimension and the member its values
/// are of, named as `stability` names it; `None` without such a speed or where it fails or stops.
fn member_at_first_state(g: &GeneralRotor, c: &RotorCampbell, control: &Control) -> Option<RotorStability> {
    let k = c.states.iter().position(|s| matches!(s, Some(StateKind::Balanced | StateKind::SemiBalanced)))?;
    let out = autobal::rotor_stability::stability_over_speed_with(&g.rotor, &[c.omega[k]], control).ok()?;
    out.stopped.is_none().then_some(out.value)
}

fn what(c: &RotorCampbell) -> &'static str {
    match c.kind {
        Kind::Equilibrium => "eigenvalues λ = σ + iν of the exact (AD) Jacobian at the stationary state, an equilibrium in axes turning with the rotor",
        Kind::PeriodicOrbit => {
            "Floquet exponents ρ = σ + iν of the stationary periodic orbit (supports that differ by direction or gravity: the rotor sags and the balls swing once per revolution), from the monodromy matrix"
        }
    }
}

/// What the state followed is, where the balls' capacity falls short (some speed's state is
/// partially balanced): `None` where every state found is (semi-)balanced.
pub const PARTIAL_STATE: &str = "the balls' capacity falls short of the unbalance, so no balanced state exists: the values are those of the state the balls rest in, bunched at their capacity limit with a residual unbalance (partially balanced; not balanced where the residual is 1 or more, below the critical speed), the state `autobal stability` analyses; `state` says which at each speed";

/// [`PARTIAL_STATE`] where some speed's state is partially balanced.
fn partial_state(c: &RotorCampbell) -> Option<&'static str> {
    c.states.iter().flatten().any(|s| *s == StateKind::PartiallyBalanced).then_some(PARTIAL_STATE)
}

/// A crossing's component share below which unbalance hardly excites it (session 29). The
/// response at a crossing is the force's projection on the mode (the left eigenvector's
/// component, amplitude ~√share) times the mode's component that moves the rotor there
/// (~√share): ~share of a pure whirl's at the same damping. Below 1e-3 that is 60 dB down,
/// under what a run-up or a measured Campbell diagram shows (j.toml: the rotor's forward
/// mode's backward component at −Ω, share 1.83e-6 at 32.56 rad/s).
pub const NEGLIGIBLE_SHARE: f64 = 1e-3;

/// Why a critical speed of the equilibrium route is not excited by unbalance, `None` where
/// it is. Unbalance is a load fixed in the turning axes: constant there, it meets only a
/// mode with `ν̂ = 0` (the forward `1×` crossing, share 1). A backward `1×` crossing
/// (`ν̂ = 2Ω`: the backward component at `−Ω`) answers only to a backward-whirling `1×` force,
/// which supports alike in every direction (the equilibrium route) do not make: on a Jeffcott
/// rotor the backward whirl `−ω_d` meets it at the same speed as the forward one, not excited.
/// A component with share below [`NEGLIGIBLE_SHARE`] is not excited by anything.
pub fn not_excited(k: &autobal::spatial::campbell::CriticalSpeed) -> Option<String> {
    if k.share < NEGLIGIBLE_SHARE {
        return Some(format!("not excited: its component's share is below {NEGLIGIBLE_SHARE} (the response there is ~share of a pure whirl's)"));
    }
    if k.harmonic == 1 && k.whirl == autobal::spatial::stability::Whirl::Backward {
        return Some("not excited by unbalance: a backward whirl at −Ω (unbalance is constant in turning axes and meets only ν = 0, the forward 1×)".into());
    }
    None
}

/// The group of the mode a crossing lies on: that of its curve's line at the drawn speed
/// nearest the crossing (`None` where the line has no point).
fn crossing_group(gc: &GeneralCampbell, f: &FixedCampbell, k: &autobal::spatial::campbell::CriticalSpeed) -> Option<autobal::spatial::stability::Group> {
    let line = &gc.diagram.lines.get(f.curves.get(k.curve)?.line)?.points;
    line.iter()
        .zip(&gc.diagram.omega)
        .filter_map(|(p, &w)| p.map(|p| (p, w)))
        .min_by(|a, b| (a.1 - k.omega).abs().total_cmp(&(b.1 - k.omega).abs()))
        .map(|(p, _)| p.group)
}

/// What the crossings of the diagram with the balls free on the equilibrium route leave out:
/// the rotor's own critical speed (session 29, j.toml: 96.76 rad/s was listed as a backward
/// crossing and no forward one, while `critical` gives 96.67 rad/s forward).
pub const FREE_BALLS_CRITICAL: &str = "with the balls free their motion shifts the rotor's forward mode: it need not cross 1× (on a Jeffcott rotor it stays above the line, at ν ≈ 20 in turning axes, and no forward crossing is listed); the rotor's critical speed, its forward whirl meeting 1× with the balls locked, is given by `--balls locked` (ν = 0: the damped natural frequency) or `autobal critical` (undamped)";

/// [`FREE_BALLS_CRITICAL`] for a linear rotor (session 33), whose balls neither `--balls locked`
/// nor `critical` lock: `campbell --balls locked` refuses a linear rotor, and its `critical`
/// gives the natural frequencies at rest (no gyroscopic or bearing terms of the speed). It names
/// what gives its critical speeds: the forward `1×` crossings listed (balls free), and the
/// structure's own diagram without the balls in `autobal report`. Two forward ends close
/// together are a stretch off the axis where the rotor's forward pair and the balls'
/// synchronous pair change places (`autobal::spatial::campbell`, exchanges):
/// examples/linear_rotor_shaft.toml's 373.576 and 374.635 rad/s, about the balls-as-a-ring
/// model's resonance at 374.45 rad/s (review 32).
pub const LINEAR_FREE_BALLS_CRITICAL: &str = "with the balls free their motion shifts the rotor's forward modes; the forward 1× crossings above (ν = 0) are this model's critical speeds, and two close together are the two ends of a stretch off the axis where the rotor's forward whirl passes 1× and changes places with the balls' synchronous pair (examples/linear_rotor_shaft.toml: 373.576 and 374.635 rad/s, its first forward critical speed); a linear rotor's balls cannot be locked (`campbell --balls locked` refuses it), `autobal critical` gives its undamped natural frequencies at rest with the balls as rings (no gyroscopic or bearing terms of the speed), and `autobal report` draws the structure's Campbell diagram without the balls, whose crossings of 1× are its critical speeds";

/// The note under a balls-free diagram's critical speeds: [`LINEAR_FREE_BALLS_CRITICAL`] for a
/// linear rotor, else [`FREE_BALLS_CRITICAL`].
pub fn free_balls_note(g: &GeneralRotor) -> &'static str {
    match g.rotor {
        Rotor::Linear(_) => LINEAR_FREE_BALLS_CRITICAL,
        _ => FREE_BALLS_CRITICAL,
    }
}

/// What a Floquet exponent given as a bound is ([`autobal::rotor_campbell::CampbellPoint::decay_at_least`]).
pub const UNDETERMINED: &str = "a Floquet multiplier below the monodromy's round-off (|μ| < δ = 100 · 1e-10 · ‖S⁻¹ΦS‖∞) gives no exponent, only a bound: re and log_decrement are null and decay_at_least says the mode decays at least that fast, σ ≤ ln(|μ| + δ)/T (its im, the phase of round-off, is not determined either)";

/// Whether a line is the kept one of a conjugate pair (most of its points with `Im ≥ 0`) and a
/// mode (not structural).
fn kept(l: &autobal::rotor_campbell::CampbellLine) -> bool {
    let pts: Vec<_> = l.points.iter().flatten().collect();
    let up = pts.iter().filter(|p| p.im >= 0.0).count();
    !pts.is_empty() && 2 * up >= pts.len() && !pts.iter().all(|p| p.structural)
}

/// The rows of [`campbell_table`] at speed index `k`: every eigenvalue (structural zeros left
/// out) but the `Im λ < 0` one of each conjugate pair, found at that speed among all the
/// lines, not by the lines' tracking. Before session 29 the rows were the points with
/// `Im λ ≥ 0` of the lines [`kept`] over the whole grid: a kept line's point with `Im λ < 0`
/// (the line crossed the real axis) and the real eigenvalues of lines left out were dropped,
/// the largest growth rate among them (j.toml at 25 rad/s: 3 rows of 8 eigenvalues).
fn table_points(c: &RotorCampbell, k: usize) -> Vec<autobal::rotor_campbell::CampbellPoint> {
    let pts: Vec<_> = c.lines.iter().filter_map(|l| l.points[k]).filter(|p| !p.structural).collect();
    // |a − conj(p)|
    let gap = |a: &autobal::rotor_campbell::CampbellPoint, p: &autobal::rotor_campbell::CampbellPoint| (a.re - p.re).hypot(a.im + p.im);
    let mut used = vec![false; pts.len()];
    let mut rows = vec![];
    for (i, p) in pts.iter().enumerate() {
        if p.im >= 0.0 {
            rows.push(*p);
            continue;
        }
        // Im λ < 0: left out where an unused point with Im λ > 0 is its conjugate (a real
        // Jacobian's, or a real monodromy's exponents on their branch), else shown
        let partner = (0..pts.len()).filter(|&j| j != i && !used[j] && pts[j].im > 0.0).min_by(|&a, &b| gap(&pts[a], p).total_cmp(&gap(&pts[b], p)));
        match partner {
            Some(j) if gap(&pts[j], p) <= 1e-6 * (1.0 + p.re.hypot(p.im)) => used[j] = true,
            _ => rows.push(*p),
        }
    }
    rows
}

/// The JSON of the general Campbell diagram: the tracked lines, and the fixed-axes view with
/// the 12-state route's columns ([`autobal::reports::campbell_fixed`]: `harmonics`,
/// `fixed_axes_modes`, `critical_speeds`, in rpm and Hz on an SI config), `critical_speeds`
/// null with `critical_speeds_not_given` saying why where they are not given.
pub fn campbell_json(g: &GeneralRotor, gc: &GeneralCampbell, omega_max: f64) -> Value {
    let mut v = lines_json(g, &gc.diagram, omega_max);
    v["balls"] = json!(match gc.balls {
        Balls::Free => "free",
        Balls::Locked => "locked",
    });
    if gc.balls == Balls::Locked {
        v["locked"] = json!("the balls locked where the closed form puts them at each speed (point masses of the rotor), damping kept");
    }
    v["harmonics"] = json!(gc.harmonics);
    // the family of balanced states and the member whose values these are, as `stability`'s
    // JSON has them (review 34's D5)
    if let Some(m) = &gc.member {
        v["family_dimension"] = json!(m.family_dimension);
        v["member_psi"] = json!(m.member_psi);
    }
    let tau = 2.0 * std::f64::consts::PI;
    match &gc.fixed {
        Some(f) => {
            let modes: Vec<Value> = f
                .curves
                .iter()
                .map(|cv| {
                    let pts: Vec<Value> = cv
                        .points
                        .iter()
                        .map(|p| {
                            let mut e = json!(p);
                            // a bound only: no growth rate
                            let re = p.decay_at_least.is_none().then_some(p.re);
                            e["re"] = json!(re);
                            if let (true, Some(o)) = (g.si, e.as_object_mut()) {
                                o.insert("frequency_hz".into(), json!(p.frequency / tau));
                                o.insert("fixed_frequency_hz".into(), json!(p.fixed_frequency / tau));
                                o.insert("re_per_s".into(), json!(re));
                                o.insert("omega_rpm".into(), json!(rpm(p.omega)));
                            }
                            e
                        })
                        .collect();
                    json!({ "mode": cv.mode, "line": cv.line, "points": pts })
                })
                .collect();
            v["fixed_axes_modes"] = json!(modes);
            if f.modes_at_first_speed {
                v["mode_numbers"] = json!(MODES_AT_FIRST_SPEED);
            }
        }
        None => v["fixed_axes_modes"] = Value::Null,
    }
    match (&gc.fixed, &gc.crossings_not_given) {
        (Some(f), None) => {
            let crit: Vec<Value> = f
                .critical_speeds
                .iter()
                .map(|k| {
                    let mut e =
                        json!({ "omega": k.omega, "mode": k.mode, "whirl": k.whirl, "share": k.share, "harmonic": k.harmonic, "frequency": k.frequency, "overdamped": k.overdamped });
                    if let Some(gr) = crossing_group(gc, f, k) {
                        e["group"] = json!(crate::figures::group_name(gr));
                    }
                    let why = not_excited(k);
                    e["excited"] = json!(why.is_none());
                    if let Some(why) = why {
                        e["not_excited"] = json!(why);
                    }
                    if let (true, Some(o)) = (g.si, e.as_object_mut()) {
                        o.insert("omega_rad_s".into(), json!(k.omega));
                        o.insert("omega_rpm".into(), json!(rpm(k.omega)));
                        o.insert("frequency_hz".into(), json!(k.frequency / tau));
                    }
                    e
                })
                .collect();
            v["critical_speeds"] = json!(crit);
            if gc.balls == Balls::Free {
                v["critical_speeds_note"] = json!(free_balls_note(g));
            }
        }
        (_, why) => {
            v["critical_speeds"] = Value::Null;
            v["critical_speeds_not_given"] = json!(why.clone().unwrap_or_default());
        }
    }
    v
}

/// The tracked lines' part of [`campbell_json`].
fn lines_json(g: &GeneralRotor, c: &RotorCampbell, omega_max: f64) -> Value {
    let mut v = json!({
        "route": "general",
        "model": c.model,
        "stationary_state": c.kind,
        "what": what(c),
        "speed_unit": unit(g),
        "frequency_unit": frequency_unit(g),
        "rate_unit": rate_unit(g),
        "omega_max": omega_max,
        "omega": c.omega,
        "lines": c.lines,
        "failures": c.failures,
        "analysed": c.analysed,
        "fixed_axes": "fixed_frequency f = Ω ± ν of the dominant circular component of the rotor's motion (> 0 forward whirl); log_decrement per fixed-axes cycle −2πσ/|f|",
    });
    if c.kind == Kind::PeriodicOrbit {
        v["branch"] = json!(FLOQUET_BRANCH);
    }
    if c.lines.iter().flat_map(|l| l.points.iter().flatten()).any(|p| p.decay_at_least.is_some()) {
        v["undetermined"] = json!(UNDETERMINED);
    }
    v["state"] = json!(c.states.iter().map(|s| s.map(|s| s.key())).collect::<Vec<_>>());
    if let Some(p) = partial_state(c) {
        v["state_followed"] = json!(p);
    }
    if g.si {
        // the SI speeds under the 12-state route's key too (its `omega` is the dimensionless Ω)
        v["omega_rad_s"] = json!(c.omega);
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
pub fn campbell_table(g: &GeneralRotor, gc: &GeneralCampbell) -> String {
    let c = &gc.diagram;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Campbell diagram (general route, {} rotor, balls {})",
        c.model,
        if gc.balls == Balls::Locked { "locked at the closed-form balanced position, damping kept" } else { "free" }
    );
    let _ = writeln!(s, "values: {}", what(c));
    if let Some(p) = partial_state(c) {
        let _ = writeln!(s, "state: {p}");
    }
    if let Some(m) = gc.member.as_ref().filter(|m| m.family_dimension > 0) {
        // the member the values are of, in `stability`'s words (review 34's D5)
        s.push_str(&crate::general::family_line(m, |w| speed_text(g, w)));
    }
    if c.kind == Kind::PeriodicOrbit {
        let _ = writeln!(s, "branch: {FLOQUET_BRANCH}");
    }
    if c.lines.iter().flat_map(|l| l.points.iter().flatten()).any(|p| p.decay_at_least.is_some()) {
        let _ = writeln!(s, "σ < −r: {UNDETERMINED}");
    }
    if gc.fixed.as_ref().is_some_and(|f| f.modes_at_first_speed) {
        let _ = writeln!(s, "mode numbers: {MODES_AT_FIRST_SPEED}");
    }
    let (fu, ru) = (frequency_unit(g), rate_unit(g));
    let _ = writeln!(
        s,
        "ν in {fu}, σ in {ru} (turning axes); fixed f = Ω ± ν of the dominant whirl component in {fu} (fixed axes, > 0 forward); log dec per fixed-axes cycle"
    );
    let n = c.omega.len();
    let mut at = vec![0, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)];
    at.dedup();
    if n == 0 {
        // stopped before its first speed (Ctrl-C during the first speed's shooting)
        let _ = writeln!(s, "\nno speed computed");
        at.clear();
    }
    for k in at {
        let _ = writeln!(s, "\nspeed {}", speed_text(g, c.omega[k]));
        if let Some(f) = &c.failures[k] {
            // below the periodic-orbit floor no state was sought: say only that
            if !c.analysed.get(k).copied().unwrap_or(true) {
                let _ = writeln!(s, "  {}", autobal::rotor_campbell::NOT_ANALYSED);
            } else {
                let _ = writeln!(s, "  no stationary state: {f}");
            }
            continue;
        }
        let hz = if g.si { format!(" {:>11}", "fixed Hz") } else { String::new() };
        let _ = writeln!(
            s,
            "  {:>12} {:>12} {:>10} {:>15}{hz}  {:<12} {:<9}",
            format!("ν ({fu})"),
            format!("σ ({ru})"),
            "log dec",
            format!("fixed f ({fu})"),
            "group",
            "whirl"
        );
        let mut pts = table_points(c, k);
        pts.sort_by(|a, b| a.fixed_frequency.abs().total_cmp(&b.fixed_frequency.abs()));
        for p in pts {
            let hz = if g.si { format!(" {:>11}", fmt_num(round(p.fixed_frequency / (2.0 * std::f64::consts::PI)))) } else { String::new() };
            let _ = writeln!(
                s,
                "  {:>12} {:>12} {:>10} {:>15}{hz}  {:<12} {:<9}",
                fmt_num(round(p.im)),
                match p.decay_at_least {
                    Some(r) => format!("< −{}", fmt_num(round(r))),
                    None => fmt_num(round(p.re)),
                },
                p.log_decrement.filter(|_| p.decay_at_least.is_none()).map_or("—".into(), |d| format!("{d:.4}")),
                fmt_num(round(p.fixed_frequency)),
                crate::figures::group_name(p.group),
                whirl_name(p.whirl)
            );
        }
    }
    // speeds below the periodic-orbit floor are not analysed (no state sought), apart from
    // those analysed without a stationary state found
    let below: Vec<usize> = (0..c.failures.len()).filter(|&k| c.failures[k].is_some() && !c.analysed.get(k).copied().unwrap_or(true)).collect();
    if let (Some(&k), Some(&last)) = (below.first(), below.last()) {
        let at = if k == last { speed_text(g, c.omega[k]) } else { format!("{} to {}", speed_text(g, c.omega[k]), speed_text(g, c.omega[last])) };
        let _ = writeln!(
            s,
            "\nnot analysed (below the periodic-orbit floor) at {} of {n} speeds ({at}: a revolution longer than {} periods of the fastest natural vibration is not shot)",
            below.len(),
            autobal::rotor_stability::PERIODS_PER_REVOLUTION
        );
    }
    let missing: Vec<&String> = c.failures.iter().zip(&c.analysed).filter(|(_, a)| **a).filter_map(|(f, _)| f.as_ref()).collect();
    if let Some(first) = missing.first() {
        let _ = writeln!(s, "\nno stationary state at {} of {n} speeds (first: {first})", missing.len());
    }
    s.push_str(&crossings_table(g, gc));
    s
}

/// The crossings part of [`campbell_table`] (as the 12-state route's
/// [`crate::linear::fixed_table`] lists them).
fn crossings_table(g: &GeneralRotor, gc: &GeneralCampbell) -> String {
    let mut s = String::new();
    let hs: Vec<String> = gc.harmonics.iter().map(|h| format!("{h}×")).collect();
    let _ = writeln!(s, "\ncritical speeds (a mode's natural frequency in fixed axes crosses {}):", hs.join(", "));
    let f = match (&gc.fixed, &gc.crossings_not_given) {
        (Some(f), None) => f,
        (_, why) => {
            let _ = writeln!(s, "  {}", why.as_deref().unwrap_or("not given"));
            return s;
        }
    };
    if f.critical_speeds.is_empty() {
        let _ = writeln!(s, "  none up to {}", speed_text(g, gc.diagram.omega.last().copied().unwrap_or(0.0)));
    }
    for (j, k) in f.critical_speeds.iter().enumerate() {
        let hz = if g.si { format!(" ({} Hz)", fmt_num(round(k.frequency / (2.0 * std::f64::consts::PI)))) } else { String::new() };
        let _ = writeln!(
            s,
            "  {:>2}. {}  mode {}, {}, {}×, frequency {} {}{hz}, {}",
            j + 1,
            speed_text(g, k.omega),
            k.mode,
            match k.whirl {
                autobal::spatial::stability::Whirl::Backward => "backward",
                _ => "forward",
            },
            k.harmonic,
            fmt_num(round(k.frequency)),
            frequency_unit(g),
            crate::linear::component_text(k.share),
        );
        if k.overdamped {
            let _ = writeln!(s, "      {}", crate::linear::OVERDAMPED);
        }
        if let Some(why) = not_excited(k) {
            let _ = writeln!(s, "      {why}");
        } else if crossing_group(gc, f, k) == Some(autobal::spatial::stability::Group::Balls) {
            let _ = writeln!(s, "      a mode of the balls (its group at the nearest drawn speed): it hardly moves the rotor, not the rotor's critical speed");
        }
    }
    if f.critical_speeds.iter().any(|k| k.overdamped) {
        let _ = writeln!(s, "  note: {}", crate::linear::OVERDAMPED_NOTE);
    }
    if gc.balls == Balls::Free {
        let _ = writeln!(s, "  note: {}", free_balls_note(g));
    }
    s
}

/// The axes of the general route's fixed-axes figure: rpm and Hz on an SI config (speeds in
/// rad/s), `Ω` and `f/ω0` on a dimensionless one.
fn fixed_axes_of(g: &GeneralRotor) -> crate::figures::FixedAxes {
    if g.si {
        crate::figures::FixedAxes::si(1.0)
    } else {
        crate::figures::FixedAxes::dimensionless()
    }
}

/// The fixed-axes Campbell figure (`--view fixed`), drawn as the 12-state route draws it
/// ([`crate::figures::campbell_fixed_plot_in`]): one curve per mode of natural frequency `|f|`,
/// forward solid, backward dashed, coloured by log decrement, the excitation lines and the
/// crossings marked (none for Floquet exponents, the title says so).
pub fn campbell_plot(g: &GeneralRotor, gc: &GeneralCampbell, omega_max: f64) -> Plot {
    let axes = fixed_axes_of(g);
    let empty = FixedCampbell {
        omega: gc.diagram.omega.clone(),
        curves: vec![],
        critical_speeds: vec![],
        harmonics: gc.harmonics.clone(),
        modes_at_first_speed: false,
        line_modes: vec![],
    };
    let mut p = crate::figures::campbell_fixed_plot_in(&axes, gc.fixed.as_ref().unwrap_or(&empty));
    p.x_range = Some((0.0, axes.kx * omega_max));
    p.title = format!(
        "Campbell diagram in fixed axes (general route, {}{}): forward solid, backward dashed, coloured by log decrement",
        match gc.diagram.kind {
            Kind::PeriodicOrbit => "Floquet exponents on their branch, no crossings: defined modulo 2π/T",
            Kind::Equilibrium => "eigenvalues",
        },
        if gc.balls == Balls::Locked { ", balls locked" } else { "" }
    );
    p
}

/// The components view (`--view components`), as the 12-state route's
/// [`crate::figures::campbell_plots`]: in rotating axes `Im λ` of each kept line (one of each
/// conjugate pair); in fixed axes its two circular components `Ω + ν` (solid) and `Ω − ν`
/// (dashed) wherever the component carries at least 10 % of the rotor's motion, one colour and
/// legend entry per mode ("mode 3: tilt, forward, from …"), the `1×` line, and the `1×`
/// crossings as vertical lines. Speeds in rad/s (rpm on top) on an SI config.
pub fn components_plots(g: &GeneralRotor, gc: &GeneralCampbell) -> (Plot, Plot) {
    use autobal::rotor_campbell::Group;
    let c = &gc.diagram;
    let mut rot = vec![];
    let mut fixed = vec![];
    let line_modes = gc.fixed.as_ref().map_or(&[][..], |f| &f.line_modes[..]);
    let mut shown = 0;
    for (i, l) in c.lines.iter().enumerate().filter(|(_, l)| kept(l)) {
        let upper: Vec<_> = l.points.iter().flatten().filter(|p| p.im >= 0.0 && !p.structural).collect();
        if upper.is_empty() {
            continue;
        }
        let count = |gr: Group| upper.iter().filter(|p| p.group == gr).count();
        let gr = [Group::Translation, Group::Tilt, Group::Balls].into_iter().max_by_key(|&gr| count(gr)).unwrap_or(Group::Translation);
        let fwd = upper.iter().filter(|p| p.whirl == Whirl::Forward).count();
        let bwd = upper.iter().filter(|p| p.whirl == Whirl::Backward).count();
        let whirl = if fwd >= bwd { "forward" } else { "backward" };
        let pts_r: Vec<(f64, f64)> =
            l.points.iter().zip(&c.omega).map(|(p, &w)| (w, p.filter(|p| p.im >= 0.0 && !p.structural).map_or(f64::NAN, |p| p.im))).collect();
        let start = |p: &[(f64, f64)]| p.iter().find(|q| q.1.is_finite()).map(|q| q.1);
        let Some(from) = start(&pts_r) else { continue };
        let component = |sign: f64| -> Vec<(f64, f64)> {
            l.points
                .iter()
                .zip(&c.omega)
                .map(|(p, &w)| {
                    let y = p.filter(|p| {
                        let share = if sign > 0.0 { p.forward_share } else { 1.0 - p.forward_share };
                        p.im >= 0.0 && !p.structural && p.whirl != Whirl::None && share >= crate::figures::COMPONENT_SHARE
                    });
                    (w, y.map_or(f64::NAN, |p| w + sign * p.im))
                })
                .collect()
        };
        shown += 1;
        let col = crate::figures::curve_color(shown - 1);
        let name = format!("{}: {}, {whirl}, from {}", crate::figures::line_name(line_modes, i), crate::figures::group_name(gr), crate::num::fmt(from, 3));
        rot.push(Series::new(name.clone(), pts_r, col));
        let mut labelled = false;
        for sign in [1.0, -1.0] {
            let pts = component(sign);
            if start(&pts).is_some() {
                let label = if labelled { String::new() } else { name.clone() };
                labelled = true;
                let se = Series::new(label, pts, col).group(format!("line {}", i + 1));
                fixed.push(if sign < 0.0 { se.dashed() } else { se });
            }
        }
    }
    let w = c.omega.last().copied().unwrap_or(1.0);
    fixed.push(Series::new("1× (synchronous)", vec![(0.0, 0.0), (w, w)], "#000000").dashed());
    let vlines: Vec<(f64, String)> = match (&gc.fixed, &gc.crossings_not_given) {
        (Some(f), None) => f.critical_speeds.iter().filter(|k| k.harmonic == 1).enumerate().map(|(i, k)| (k.omega, format!("1× crossing {}", i + 1))).collect(),
        _ => vec![],
    };
    let (x_label, unit) = if g.si { ("ω (rad/s)", " (rad/s)") } else { ("Ω = ω/ω0", " / ω0") };
    let x2 = g.si.then(|| crate::plot::SecondAxis { factor: crate::num::RPM_PER_RAD_S, label: "n (rpm)".into() });
    let floquet = if c.kind == Kind::PeriodicOrbit { " (Floquet exponents: Im ρ on its branch, defined modulo 2π/T)" } else { "" };
    (
        Plot {
            title: format!("Campbell diagram, rotating axes (general route){floquet}"),
            x_label: x_label.into(),
            y_label: format!("Im λ, rotating axes{unit}"),
            series: rot,
            vlines: vlines.clone(),
            x_range: Some((0.0, w)),
            x2: x2.clone(),
            ..Default::default()
        },
        Plot {
            title: format!("Campbell diagram, fixed axes: Ω + ν (solid) and Ω − ν (dashed) of each mode (general route){floquet}"),
            x_label: x_label.into(),
            y_label: if g.si { "whirl frequency (rad/s)".into() } else { "whirl frequency / ω0".into() },
            series: fixed,
            vlines,
            x_range: Some((0.0, w)),
            x2,
            ..Default::default()
        },
    )
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
    /// The verdict at the config's operating speed (`analysis.operating_speed`), printed first
    /// as `stability` prints it; `None` without one or without a stability scan.
    pub operating: Option<crate::general::Operating>,
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
    let necessary = necessary_ranges(root, g.omega0)?;
    if let Ok(l) = &locked {
        autobal::limits::check_finite("critical.locked", l)?;
    }
    if let Ok(st) = &stability {
        autobal::limits::check_finite("critical.stability", &st.stable_ranges)?;
    }
    // the verdict at the operating speed first, as `stability` and the closed-form route say it
    let operating = match &stability {
        Ok(st) => crate::general::operating(g, root, st, control)?,
        Err(_) => None,
    };
    if let Some(why) = operating.as_ref().and_then(|o| o.stopped) {
        anyhow::bail!("{why}: the verdict at the operating speed stopped; nothing is printed");
    }
    Ok(GeneralCritical { locked, stability, necessary, omega_max, operating })
}

/// Paper 003's necessary ranges (eqs (1)-(3)) that the general `critical` prints beside the
/// exact ones, in the rotor's units (`omega0`: rad/s per Ω): those of the 12-state linear model,
/// defined where that model describes the config (a spatial config with no entry it leaves
/// out), else `None`.
pub fn necessary_ranges(root: &Table, omega0: f64) -> Result<Option<Vec<(f64, Option<f64>)>>> {
    Ok(if autobal::config::is_spatial(root) && autobal::config::ignored_by_linear_model(root).is_empty() {
        let cfg = autobal::config::spatial(root)?;
        Some(autobal::spatial::ranges::autobalancing_ranges(&cfg.model).ranges.iter().map(|r| (r.lo * omega0, r.hi.map(|h| h * omega0))).collect())
    } else {
        None
    })
}

const LOCKED_WHAT: &str = "balls locked at the closed-form balanced position (where none exists, at the partially balanced placement), as point masses of the rotor, no damping: speeds where a natural frequency in fixed axes equals the speed (a whirl standing still in turning axes: the stiffness block of the exact Jacobian is singular)";

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
                    let mut e = json!({ "omega": s.omega, "multiplicity": s.multiplicity, "motion": s.motion, "whirl": s.whirl, "split": s.split, "balls_partially_balanced": s.partial });
                    if g.si { e["rpm"] = json!(rpm(s.omega)); }
                    e
                }).collect::<Vec<_>>(),
                "grid": l.samples,
                "ball_angles": l.ball_angles,
                "same_speed_tolerance": autobal::rotor_campbell::SAME_SPEED,
                "speeds_without_balanced_state": l.partial + l.unlocked,
                "speeds_locked_partially_balanced": l.partial,
                "speeds_not_searched": l.unlocked,
                "not_computed": (l.samples > 0 && l.unlocked == l.samples).then(|| autobal::rotor_campbell::unlocked_words(l.unlocked, l.samples)),
            }),
            Err(e) => json!({ "what": LOCKED_WHAT, "speeds": Value::Null, "not_located": e }),
        },
    });
    match &c.stability {
        Ok(st) => {
            v["exact_stable_ranges"] = json!(st
                .stable_ranges
                .iter()
                .map(|s| {
                    let mut r = crate::general::stable_range_json(s);
                    // the states the range covers, as `stability`'s JSON names them (review 34's D3)
                    r["states"] = json!(crate::general::range_state_keys(st, s));
                    r["from_si"] = to_si(s.from);
                    r["to_si"] = to_si(s.to);
                    r
                })
                .collect::<Vec<_>>());
            let missing: Vec<_> = st.points.iter().filter(|p| p.verdict.is_none()).collect();
            v["speeds_without_stationary_state"] = json!(missing.len());
            v["no_stationary_state_first_reason"] = json!(missing.first().and_then(|p| p.failure.clone()));
            v["stationary_state"] = json!(st.kind);
            v["family_dimension"] = json!(st.family_dimension);
            v["member_psi"] = json!(st.member_psi);
            // the family's ranges (all members sampled stable, some), as `stability`'s JSON has them
            v["family"] = json!(st.family);
        }
        Err(e) => {
            v["exact_stable_ranges"] = Value::Null;
            v["stability_not_analysed"] = json!(e);
        }
    }
    v["operating"] = c.operating.as_ref().map_or(Value::Null, crate::general::operating_json);
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

/// What `critical` and the report say where the locked rotor has no critical speed on the
/// axis up to `top` (its text): "none" only where every speed of the axis was searched
/// (review 29: "none up to" where no speed had a placement to lock the balls at and none was
/// searched), "not computed" where none was, else how many were.
pub fn no_critical_speed_words(l: &autobal::rotor_campbell::LockedCriticalSpeeds, top: &str) -> String {
    if l.unlocked == 0 {
        format!("none up to {top}")
    } else if l.unlocked >= l.samples {
        "not computed: no speed of the axis has a placement to lock the balls at".to_string()
    } else {
        format!("none at the {} of {} speeds searched up to {top} (the others not searched)", l.samples - l.unlocked, l.samples)
    }
}

/// What the balls' locked placement is: with gravity across the axis the balanced family of
/// 3 or more balls breaks into orbits with two groups of balls (`stability`'s `member_psi`), so
/// the closed-form placement the speeds are located at is not where the balls settle (gravity
/// itself does not enter the locked rotor's stiffness; the placement moves the speeds only
/// through the balls' point masses). The family's words only where a plane has 3 or more balls
/// (review 29: printed for 2 balls); `partial`: no balanced state, the partially balanced
/// placement ([`autobal::rotor_campbell::partial_words`]) at `angles` (rad): spatial and linear
/// against the unbalance; planar on the line of the whirl, which side of the unbalance read
/// from the angles (review 34's D6: "against the unbalance" of balls at 0°, on it: the planar
/// ψ is measured from the unbalance).
fn locked_placement_note(g: &GeneralRotor, partial: bool, angles: &[f64]) -> String {
    if partial {
        let side = match &g.rotor {
            Rotor::Planar(p) if !angles.is_empty() => {
                // the planar rotor's unbalance at ψ = 0 (m1 s1), with an eccentric race's (m2 + n m3) s2 at γ
                let e = (p.m2 + p.n as f64 * p.m3) * p.s2;
                let u = (e * p.gamma.sin()).atan2(p.m1 * p.s1 + e * p.gamma.cos());
                let along = angles.iter().map(|a| (a - u).cos()).sum::<f64>();
                if along > 0.0 {
                    "on the line of the whirl on the unbalance's side (0° is the direction of the disk's mass centre, m1 s1), adding to it, as below the critical speed"
                } else {
                    "on the line of the whirl against the unbalance (0° is the direction of the disk's mass centre, m1 s1), as above the critical speed"
                }
            }
            Rotor::Planar(_) => "on the line of the whirl",
            _ => "against the unbalance (each plane's against its share)",
        };
        return format!("no balanced state: the partially balanced placement, the balls bunched {side}");
    }
    match &g.rotor {
        Rotor::Spatial(s) if s.gravity_across() && s.planes.iter().any(|p| p.n >= 3) => {
            "the closed-form placement without gravity; under gravity the balls settle in two groups per plane, at angles that move with the speed (`stability`'s member_psi): the speeds above are the named placement's"
        }
        Rotor::Spatial(s) if s.planes.iter().any(|p| p.n >= 3) => "with 3 or more balls in a plane the balanced states form a family: these speeds are the named member's",
        // an eccentric race on supports that differ by direction breaks the family, as gravity does
        Rotor::Planar(p) if p.n >= 3 && !(p.anisotropic() && p.s2 != 0.0) => "with 3 or more balls the balanced states form a family: these speeds are the named member's",
        Rotor::Planar(p) if p.n >= 3 => "the closed-form placement; on supports that differ by direction the eccentric race's balls settle in two groups (`stability`'s member_psi): the speeds above are the named placement's",
        _ => "the closed-form balanced placement",
    }
    .to_string()
}

/// The table of the general `critical`.
pub fn critical_table(g: &GeneralRotor, c: &GeneralCritical) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Critical speeds and exact stability (general route, {} rotor)", g.rotor.model_name());
    let _ = writeln!(s, "critical speeds: {LOCKED_WHAT}");
    if let (Some(op), Ok(st)) = (&c.operating, &c.stability) {
        // the verdict first, as `stability` and the closed-form route open (review 29)
        s.insert_str(0, &crate::general::operating_line(g, st, op));
    }
    match &c.locked {
        Ok(l) if l.speeds.is_empty() => {
            let _ = writeln!(s, "  {}", no_critical_speed_words(l, &speed_text(g, c.omega_max)));
        }
        Ok(l) => {
            for (i, k) in l.speeds.iter().enumerate() {
                let motion = serde_json::to_string(&k.motion).unwrap_or_default();
                let merged = match k.split {
                    Some([a, b]) => {
                        format!("; {} speeds {:.1e} apart, relative, merged (below {:.0e})", k.multiplicity, (b - a) / b, autobal::rotor_campbell::SAME_SPEED)
                    }
                    None => String::new(),
                };
                let _ = writeln!(
                    s,
                    "  {:>2}. {}  {} whirl, {} (multiplicity {}{merged})",
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
            let partial_only = l.partial > 0 && l.partial + l.unlocked == l.samples;
            let _ = writeln!(s, "  balls locked at {} ({})", deg.join(", "), locked_placement_note(g, partial_only, &l.ball_angles));
        }
        if l.partial > 0 {
            let _ = writeln!(s, "  ({})", autobal::rotor_campbell::partial_words(l.partial, l.samples));
        }
        if l.unlocked > 0 {
            let _ = writeln!(s, "  ({})", autobal::rotor_campbell::unlocked_words(l.unlocked, l.samples));
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
            // (review 29: "the balanced state" where no speed has one)
            _ if !st.points.iter().any(|p| matches!(p.state, Some(StateKind::Balanced | StateKind::SemiBalanced))) => "stationary state",
            (Rotor::Planar(p), _) if p.s2 != 0.0 => "semi-balanced state (race centre on the axis)",
            _ => "balanced state",
        },
        if st.kind == Kind::PeriodicOrbit { "Floquet multipliers" } else { "eigenvalues of the exact Jacobian" }
    );
    // as `stability` words it (review 29: "stable: nowhere" where no speed had a state)
    let solved = st.points.iter().filter(|p| p.verdict.is_some()).count();
    if st.stable_ranges.is_empty() && solved == 0 {
        let analysed = st.points.iter().filter(|p| p.analysed).count();
        let _ = writeln!(
            s,
            "  no verdict: no stationary state was found at any of the {analysed} speeds analysed of {} in (0, {}]",
            st.points.len(),
            speed_text(g, c.omega_max)
        );
    } else if st.stable_ranges.is_empty() {
        let _ = writeln!(
            s,
            "  stable: nowhere among the {solved} of {} speeds in (0, {}] where a stationary state was found",
            st.points.len(),
            speed_text(g, c.omega_max)
        );
    }
    // as `stability` words them (review 34's D3: a bare "stable" for states that add to the
    // unbalance, one member's range as "the balanced state"): the family's member named, its
    // ranges over the members, each range with the states it covers
    let indent = |text: String| text.lines().map(|l| format!("  {l}\n")).collect::<String>();
    if st.family_dimension > 0 {
        s.push_str(&indent(crate::general::family_line(st, |w| speed_text(g, w))));
    }
    s.push_str(&indent(crate::general::family_range_lines(st, |w| speed_text(g, w))));
    for r in &st.stable_ranges {
        // a grid speed next to one without a state is not the axis' end
        let end = |upper: bool| crate::general::end_text(st, r, upper, |w| speed_text(g, w));
        let _ = writeln!(s, "  {}: {} to {}", crate::general::range_label(st, r), end(false), end(true));
    }
    s.push_str(&indent(crate::general::not_balanced_text(st, |w| speed_text(g, w))));
    for line in crate::general::missing_lines(st, |w| speed_text(g, w)).lines() {
        let _ = writeln!(s, "  {line}");
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

#[cfg(test)]
mod tests {
    use super::*;

    /// "none" only where every speed was searched; where none was, "not computed"; else how
    /// many (review 29: "none up to" where no speed had been searched). `critical` and the
    /// report both say it through this function.
    #[test]
    fn no_critical_speed_says_none_only_where_every_speed_was_searched() {
        let l = |unlocked: usize| autobal::rotor_campbell::LockedCriticalSpeeds {
            speeds: vec![],
            omega_max: 300.0,
            samples: 50,
            unlocked,
            partial: 0,
            ball_angles: vec![],
        };
        assert_eq!(no_critical_speed_words(&l(0), "300 rad/s"), "none up to 300 rad/s");
        assert_eq!(no_critical_speed_words(&l(50), "300 rad/s"), "not computed: no speed of the axis has a placement to lock the balls at");
        assert_eq!(no_critical_speed_words(&l(20), "300 rad/s"), "none at the 30 of 50 speeds searched up to 300 rad/s (the others not searched)");
    }

    /// `critical`'s locked placement note: the washer (three balls in a plane) names the family's
    /// member without gravity, and says under gravity that the balls settle elsewhere, in two
    /// groups (main at bb89c7b called the placement the family's member under gravity too,
    /// where no family exists).
    #[test]
    fn the_locked_placement_note_follows_gravity() {
        let text = include_str!("../../../examples/washing_machine.toml");
        let plain = crate::general::rotor_of(&crate::config::parse_text(text, "w").unwrap()).unwrap();
        assert!(locked_placement_note(&plain, false, &[]).contains("form a family"));
        let heavy = format!("{text}\n[spatial]\ngravity = [0.0, -9.81, 0.0]\n");
        let heavy = crate::general::rotor_of(&crate::config::parse_text(&heavy, "w").unwrap()).unwrap();
        let note = locked_placement_note(&heavy, false, &[]);
        assert!(note.contains("two groups") && !note.contains("form a family"), "{note}");
        // gravity along the axis (a vertical machine) keeps the family
        let vertical = format!("{text}\n[spatial]\ngravity = [0.0, 0.0, -9.81]\n");
        let vertical = crate::general::rotor_of(&crate::config::parse_text(&vertical, "w").unwrap()).unwrap();
        assert!(locked_placement_note(&vertical, false, &[]).contains("form a family"));
    }
}
