//! The result of each front-end command as one JSON value: what `autobal <command> --format
//! json` prints and what the Python package's `autobal.run(command, ...)` returns, built here
//! once so that the two cannot differ.
//!
//! ```
//! use autobal::{config, reports};
//! let c = config::spatial(&config::parse(config::DEFAULT_SPATIAL, "default").unwrap()).unwrap();
//! let v = reports::critical(&c, "default");
//! assert_eq!(v["rotor_type"], "long");
//! assert_eq!(v["critical_speeds"].as_array().unwrap().len(), 4);
//! ```

use crate::config::SpatialConfig;
use crate::error::Result;
use crate::limits::check_finite;
use crate::planar::problem::PlanarProblem;
use crate::planar::stationary::capacity_ratio;
use crate::planar::Summary;
use crate::spatial::comparison::Comparison;
use crate::spatial::critical_speeds::{critical_speeds, critical_speeds_at};
use crate::spatial::linear_model::Balls;
use crate::spatial::params::SpatialModel;
use crate::spatial::ranges::{antiresonance_speed, autobalancing_ranges, SpeedRange};
use crate::spatial::sensitivity::sensitivity;
use crate::spatial::stability::Campbell;
use serde_json::{json, Value};

/// `[lo, hi]` pairs with `null` for an unbounded end.
pub fn ranges_value(r: &[SpeedRange]) -> Value {
    Value::Array(r.iter().map(|x| json!([x.lo, x.hi])).collect())
}

/// Whether the last of ranges computed over a span reaches the span's end (`hi = None` there).
fn open_at(r: &[SpeedRange]) -> bool {
    r.last().is_some_and(|x| x.hi.is_none())
}

/// Ranges scaled by `k` (e.g. to rpm).
pub fn scale_ranges(r: &[SpeedRange], k: f64) -> Vec<SpeedRange> {
    r.iter().map(|x| SpeedRange { lo: x.lo * k, hi: x.hi.map(|h| h * k) }).collect()
}

/// rad/s and rpm per unit of dimensionless speed Ω (`ω0` and `30 ω0 / π`), for a dimensional
/// config; `None` for a dimensionless one, whose SI keys are then `null`.
fn si_units(m: &SpatialModel) -> Option<(f64, f64)> {
    m.scale.map(|s| (s.omega0, s.omega0 * 30.0 / std::f64::consts::PI))
}

/// A speed (or speeds) Ω in rad/s and rpm: `(rad_s, rpm)`, `null`s without a scale.
fn speed_si(m: &SpatialModel, w: &[f64]) -> (Value, Value) {
    match si_units(m) {
        Some((rad, rpm)) => (json!(w.iter().map(|x| x * rad).collect::<Vec<_>>()), json!(w.iter().map(|x| x * rpm).collect::<Vec<_>>())),
        None => (Value::Null, Value::Null),
    }
}

/// Ranges of Ω in rpm, `null` without a scale.
fn ranges_rpm(m: &SpatialModel, r: &[SpeedRange]) -> Value {
    si_units(m).map_or(Value::Null, |(_, rpm)| ranges_value(&scale_ranges(r, rpm)))
}

/// The upper end of the speed axis when none is given: 1.3 times the highest critical,
/// antiresonance or split-pair speed (at least 1), at most 50.
pub fn default_omega_max(m: &SpatialModel) -> f64 {
    let top = critical_speeds_at(m, m.anisotropy.used)
        .iter()
        .map(|r| r.0)
        .chain(antiresonance_speed(m))
        .chain(autobalancing_ranges(m).critical_speeds)
        .fold(1.0, f64::max);
    (1.3 * top).min(50.0)
}

/// The upper end of the automatic speed axis of a config (`Ω`): `analysis.omega_max` if given,
/// else [`default_omega_max`] extended to cover the operating speed with margin
/// ([`crate::config::Analysis::speed_axis_max`]).
pub fn speed_axis_max(c: &SpatialConfig) -> f64 {
    c.analysis.speed_axis_max(default_omega_max(&c.model))
}

/// Grid speeds of the stability verdict at the operating speed ([`operating_verdict`]).
pub const OPERATING_SAMPLES: usize = 2000;

/// The balanced state at the machine's operating speed (`analysis.operating_speed`): whether
/// it is stable there by the exact linear stability ([`crate::spatial::stability`]), and by how
/// much. Speeds in `Ω`, with rad/s and rpm for a dimensional config.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OperatingVerdict {
    /// The operating speed `[lo, hi]` (`Ω`; `lo = hi` for one speed).
    pub omega: [f64; 2],
    /// The same in rad/s (dimensional configs).
    pub rad_s: Option<[f64; 2]>,
    /// The same in rpm (dimensional configs).
    pub rpm: Option<[f64; 2]>,
    /// `free` or `locked`.
    pub balls: &'static str,
    /// Whether the whole operating speed lies inside one exact stable range.
    pub stable: bool,
    /// That range (`Ω`; `hi = None`: it reaches `span`, the end of the computation).
    pub stable_range: Option<SpeedRange>,
    /// The stable range nearest to the operating speed, when it is not stable.
    pub nearest_stable_range: Option<SpeedRange>,
    /// Distance from the lower end of the stable range down to the operating speed (`Ω`).
    pub margin_below: Option<f64>,
    /// Distance from the operating speed up to the upper end of the stable range (`Ω`); `None`
    /// when the range reaches `span` (then it is at least `span − hi`).
    pub margin_above: Option<f64>,
    /// The smaller of the two: the distance to the nearest end of the stable range (`Ω`).
    pub margin: Option<f64>,
    /// `margin` in rpm (dimensional configs).
    pub margin_rpm: Option<f64>,
    /// `margin_below` in rpm (dimensional configs).
    pub margin_below_rpm: Option<f64>,
    /// `margin_above` in rpm (dimensional configs).
    pub margin_above_rpm: Option<f64>,
    /// `stable_range` in rpm (dimensional configs).
    pub stable_range_rpm: Option<SpeedRange>,
    /// `nearest_stable_range` in rpm (dimensional configs).
    pub nearest_stable_range_rpm: Option<SpeedRange>,
    /// `span` in rpm (dimensional configs).
    pub span_rpm: Option<f64>,
    /// `max Re λ` over the operating speed (largest over 33 speeds of a range), unit `ω0`:
    /// negative where stable.
    pub max_real_part: f64,
    /// `max_real_part` in 1/s (dimensional configs).
    pub max_real_part_per_s: Option<f64>,
    /// The span `(0, span]` the stable ranges were computed over (`Ω`).
    pub span: f64,
    /// Every exact stable range over `(0, span]` (`Ω`; `hi = None`: reaches `span`).
    pub stable_ranges: Vec<SpeedRange>,
    /// The same in rpm (dimensional configs).
    pub stable_ranges_rpm: Option<Vec<SpeedRange>>,
}

/// [`OperatingVerdict`] of `model` at `op = [lo, hi]` (`Ω`) from its exact stable ranges over
/// `(0, span]` (`span ≥ hi`, [`crate::spatial::stability::stability_ranges`]); `max Re λ` from
/// the eigenvalues ([`crate::spatial::stability::margin`]).
///
/// ```
/// use autobal::reports::operating_verdict;
/// use autobal::spatial::linear_model::Balls;
/// use autobal::spatial::params::{DimensionlessInput, SpatialModel};
/// use autobal::spatial::stability::stability_ranges;
/// // paper 000's base case: stable at Ω = 1.6 (the range ~[1.13, 1.70]), not at 1.72
/// let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).unwrap();
/// let s = stability_ranges(&m, 5.0, 2000, Balls::Free, 1e-9).unwrap();
/// let v = operating_verdict(&m, [1.6, 1.6], &s.stable_ranges, 5.0, Balls::Free).unwrap();
/// assert!(v.stable && v.max_real_part < 0.0 && v.margin.unwrap() > 0.0);
/// let r = v.stable_range.unwrap();
/// assert_eq!(v.margin.unwrap(), (1.6 - r.lo).min(r.hi.unwrap() - 1.6));
/// assert!(!operating_verdict(&m, [1.72, 1.72], &s.stable_ranges, 5.0, Balls::Free).unwrap().stable);
/// ```
pub fn operating_verdict(model: &SpatialModel, op: [f64; 2], stable: &[SpeedRange], span: f64, balls: Balls) -> Result<OperatingVerdict> {
    let [lo, hi] = op;
    let inside = stable.iter().find(|r| r.lo <= lo && r.hi.is_none_or(|h| hi <= h) && r.contains(0.5 * (lo + hi)));
    let dist = |r: &SpeedRange| if r.hi.is_some_and(|h| h <= lo) { lo - r.hi.unwrap_or(lo) } else { (r.lo - hi).max(0.0) };
    let nearest = if inside.is_some() { None } else { stable.iter().min_by(|a, b| dist(a).total_cmp(&dist(b))).copied() };
    let n = if hi > lo { 33 } else { 1 };
    let mut worst = f64::NEG_INFINITY;
    for k in 0..n {
        let w = if n == 1 { lo } else { lo + (hi - lo) * k as f64 / (n - 1) as f64 };
        worst = worst.max(crate::spatial::stability::margin(model, w.max(crate::spatial::map::OMEGA_FLOOR), balls)?);
    }
    let (below, above) = match inside {
        Some(r) => (Some(lo - r.lo), r.hi.map(|h| h - hi)),
        None => (None, None),
    };
    let margin = match (below, above) {
        (Some(b), Some(a)) => Some(b.min(a)),
        (Some(b), None) => Some(b),
        _ => None,
    };
    let si = si_units(model);
    Ok(OperatingVerdict {
        omega: op,
        rad_s: si.map(|(k, _)| [lo * k, hi * k]),
        rpm: si.map(|(_, k)| [lo * k, hi * k]),
        balls: balls_name(balls),
        stable: inside.is_some(),
        stable_range: inside.copied(),
        nearest_stable_range: nearest,
        margin_below: below,
        margin_above: above,
        margin,
        margin_rpm: si.and_then(|(_, k)| margin.map(|m| m * k)),
        margin_below_rpm: si.and_then(|(_, k)| below.map(|m| m * k)),
        margin_above_rpm: si.and_then(|(_, k)| above.map(|m| m * k)),
        stable_range_rpm: si.and_then(|(_, k)| inside.map(|r| scale_ranges(&[*r], k)[0])),
        nearest_stable_range_rpm: si.and_then(|(_, k)| nearest.map(|r| scale_ranges(&[r], k)[0])),
        span_rpm: si.map(|(_, k)| span * k),
        max_real_part: worst,
        max_real_part_per_s: si.map(|(k, _)| worst * k),
        span,
        stable_ranges: stable.to_vec(),
        stable_ranges_rpm: si.map(|(_, k)| scale_ranges(stable, k)),
    })
}

/// The verdict at the config's operating speed, if it has one: exact stable ranges over
/// `(0, max(span, 1.25 hi)]` with [`OPERATING_SAMPLES`] grid speeds.
pub fn operating_of(c: &SpatialConfig, balls: Balls) -> Option<Result<OperatingVerdict>> {
    let op = c.analysis.operating_speed?;
    let span = speed_axis_max(c).max(crate::config::OPERATING_SPEED_MARGIN * op[1]);
    Some(crate::spatial::stability::stability_ranges(&c.model, span, OPERATING_SAMPLES, balls, crate::spatial::comparison::RANGE_TOLERANCE).and_then(|s| {
        check_finite("stability", &s)?;
        operating_verdict(&c.model, op, &s.stable_ranges, span, balls)
    }))
}

/// The operating verdict as JSON: `null` without an operating speed, `{"error": ...}` where the
/// eigenvalues did not converge.
fn operating_json(v: Option<Result<OperatingVerdict>>) -> Value {
    match v {
        None => Value::Null,
        Some(Ok(v)) => json!(v),
        Some(Err(e)) => json!({ "error": e.to_string() }),
    }
}

/// Warnings about the anisotropy a user can act on: all but the comparison of the exact tensor
/// with paper 000's eq (17) (a property of the paper's formula, reported by `inertia` and the
/// docs only).
pub fn actionable_warnings(a: &crate::spatial::inertia::Anisotropy) -> Vec<String> {
    a.warnings.iter().filter(|w| !is_eq17_comparison(w)).cloned().collect()
}

/// Whether a warning of [`crate::spatial::inertia::Anisotropy`] is its comparison with eq (17).
pub fn is_eq17_comparison(w: &str) -> bool {
    w.contains("paper 000's eq (17) gives")
}

fn model_json(c: &SpatialConfig, source: &str) -> Value {
    let m = &c.model;
    json!({
        "c_sigma": m.c_sigma,
        "rho_s": m.rho_s,
        "l_left": m.l_left,
        "z_a": m.z_a,
        "p_alpha": m.p_alpha_sq.sqrt(),
        "p_alpha_sq": m.p_alpha_sq,
        "c_y_alpha": m.c_y_alpha,
        "delta_a0": m.delta_a0,
        "damping": m.damping,
        "masses": m.masses,
        "scale": m.scale,
        "source": source,
    })
}

/// The anisotropy; `eq17`: with the comparison of the exact tensor and eq (17) among the
/// warnings (`inertia` only, [`actionable_warnings`]).
fn anisotropy_json(m: &SpatialModel, eq17: bool) -> Value {
    let a = &m.anisotropy;
    let warnings = if eq17 { a.warnings.clone() } else { actionable_warnings(a) };
    json!({
        "paper": a.paper,
        "exact": a.exact[1],
        "used": a.used,
        "method": a.method,
        "exact_interval": a.exact,
        "paper_interval": a.paper_interval,
        "used_interval": a.used_interval,
        "d_a": a.d_a,
        "ball_angles_rad": a.ball_angles,
        "can_balance": a.can_balance,
        "warnings": warnings,
    })
}

/// Every number the analytic commands report is finite (else the error names the quantity);
/// the input ranges ([`crate::limits`]) are chosen so that this holds, this is the last guard.
pub fn check_results(c: &SpatialConfig) -> Result<()> {
    check_finite("the model", &c.model)?;
    check_finite("inertia", &c.model.composite_inertia())?;
    check_finite("critical_speeds", &critical_speeds(&c.model))?;
    check_finite("autobalancing_ranges", &autobalancing_ranges(&c.model))?;
    check_finite("sensitivity", &sensitivity(&c.model, c.analysis.sensitivity_limit))?;
    Ok(())
}

/// `autobal inertia`: composite inertia and anisotropy.
pub fn inertia(c: &SpatialConfig, source: &str) -> Value {
    json!({
        "model": model_json(c, source),
        "inertia": c.model.composite_inertia(),
        "anisotropy": anisotropy_json(&c.model, true),
    })
}

/// The entries of a spatial config that make paper 000's composite inertia (one plane, static
/// unbalance, principal axis along the shaft) not that of the rotor: `[couple]`, `[balancer2]`,
/// `rotor.axis_tilt` (with its angle) where not 0. Supports, gravity and the balls' physics are
/// not among them: they do not change the rotor's mass properties.
pub fn beyond_paper_000_inertia(root: &toml::Table) -> Vec<String> {
    crate::config::ignored_by_linear_model(root)
        .into_iter()
        .filter(|k| matches!(k.as_str(), "[couple]" | "[balancer2]" | "rotor.axis_tilt" | "rotor.axis_tilt_angle"))
        .collect()
}

/// The whole rotor's mass properties ([`crate::spatial::dynamics::mass_properties`]) with its
/// balls placed, as `autobal inertia` reports them.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct WholeRotor {
    /// Where the balls are and what state that is.
    pub placement: crate::spatial::dynamics::BallPlacement,
    /// The mass properties.
    pub properties: crate::spatial::dynamics::MassProperties,
    /// Units: SI, or the papers' (`M_s = 1`, `ρ_s = 1`, so `A_Σ = 1`) for a dimensionless config.
    pub si: bool,
}

/// The rotor the simulation builds from `root` ([`crate::config::spatial_simulation`], its
/// run's tables `[drive]`, `[initial]`, `[integration]` left out: they do not describe the
/// rotor), its balls at the balanced state. On a config paper 000's composite inertia describes
/// ([`beyond_paper_000_inertia`] empty) the balls sit at the position that inertia refers to
/// (for `n ≥ 3` the member of the family with the largest anisotropy); otherwise
/// [`SpatialRotor::balanced_ball_angles`](crate::spatial::dynamics::SpatialRotor::balanced_ball_angles).
pub fn whole_rotor(root: &toml::Table, c: &SpatialConfig) -> Result<WholeRotor> {
    let mut rotor_only = root.clone();
    for t in ["drive", "initial", "integration"] {
        rotor_only.remove(t);
    }
    let rotor = crate::config::spatial_simulation(&rotor_only)?.rotor;
    let one_plane = rotor.planes.iter().filter(|p| p.n > 0).count() == 1;
    let from_000 = match (&c.model.anisotropy.ball_angles, beyond_paper_000_inertia(root).is_empty() && one_plane) {
        (Some(a), true) if a.len() == rotor.balls() && a.len() >= 3 => {
            let u = rotor.unbalances.first().map_or(0.0, |u| u.angle);
            Some(crate::spatial::dynamics::BallPlacement {
                angles: a.iter().map(|x| x + u).collect(),
                placement: crate::spatial::dynamics::Placement::Balanced,
                note: "balanced state: the balls cancel the static unbalance (n ≥ 3: the member of the family with the largest anisotropy, the one paper 000's composite inertia and the 12-state model refer to)".into(),
            })
        }
        _ => None,
    };
    let placement = from_000.unwrap_or_else(|| rotor.balanced_ball_angles());
    let properties = rotor.mass_properties(&placement.angles)?;
    check_finite("inertia.whole_rotor", &properties)?;
    Ok(WholeRotor { placement, properties, si: c.dimensional })
}

/// `autobal inertia` of any spatial config: paper 000's composite inertia and anisotropy where
/// they describe the rotor (`null` and the reason otherwise), and the whole rotor's mass
/// properties as the simulation builds it ([`whole_rotor`]; `null` with the reason where the
/// simulation cannot build it, e.g. a dimensionless config without masses).
pub fn inertia_of(root: &toml::Table, source: &str) -> Result<Value> {
    let c = crate::config::spatial(root)?;
    let beyond = beyond_paper_000_inertia(root);
    let whole = whole_rotor(root, &c);
    if beyond.is_empty() {
        check_results(&c)?;
    } else if let Err(e) = whole {
        return Err(e);
    }
    let mut v = inertia(&c, source);
    if !beyond.is_empty() {
        v["inertia"] = Value::Null;
        v["anisotropy"] = Value::Null;
    }
    v["paper_000_not_applicable"] = if beyond.is_empty() {
        Value::Null
    } else {
        json!(format!("paper 000's composite inertia is that of one balancer plane cancelling a static unbalance; this config has {}", beyond.join(", ")))
    };
    match whole {
        Ok(w) => {
            v["whole_rotor"] = json!(w);
            v["whole_rotor_unavailable"] = Value::Null;
        }
        Err(e) => {
            v["whole_rotor"] = Value::Null;
            v["whole_rotor_unavailable"] = json!(e.to_string());
        }
    }
    Ok(v)
}

/// `autobal ranges` of a config paper 003 describes: its necessary ranges ([`ranges`]) labelled
/// as a necessary condition, beside the exact stable ranges of the 12-state linear model
/// (balls free) over `autobal stability`'s default axis and grid ([`speed_axis_max`], 2000
/// speeds).
pub fn ranges_with_exact(c: &SpatialConfig, source: &str) -> Result<Value> {
    let w = speed_axis_max(c);
    // `autobal stability`'s default `--samples`
    let cmp = crate::spatial::comparison::compare(&c.model, w, 2000, Balls::Free)?;
    check_finite("ranges.exact", &cmp.exact)?;
    let mut v = ranges(c, source);
    let r = &cmp.exact.stable_ranges;
    v["autobalancing_ranges_are"] = json!("necessary condition (paper 003, eqs (1)-(3)): not a verdict");
    v["exact"] = json!({
        "route": "the 12-state linear model of paper 000, balls free (as `autobal stability`)",
        "omega_max": w,
        "omega_max_rpm": si_units(&c.model).map(|(_, rpm)| w * rpm),
        "stable_ranges": ranges_value(r),
        "stable_ranges_rpm": ranges_rpm(&c.model, r),
        "tolerance": cmp.exact.tolerance,
    });
    Ok(v)
}

/// `autobal critical`: critical speeds, sensitivity and autobalancing ranges.
pub fn critical(c: &SpatialConfig, source: &str) -> Value {
    let cs = critical_speeds(&c.model);
    let ar = autobalancing_ranges(&c.model);
    let s = sensitivity(&c.model, c.analysis.sensitivity_limit);
    let (a_rad, a_rpm) = speed_si(&c.model, &ar.antiresonance_speed.into_iter().collect::<Vec<_>>());
    let mut speeds = json!(cs.speeds);
    if let (Some((_, rpm)), Some(list)) = (si_units(&c.model), speeds.as_array_mut()) {
        // every dimensionless speed of an entry beside its rpm (exact value: omega_rad_s, rpm)
        for e in list.iter_mut().filter_map(Value::as_object_mut) {
            for k in ["approx_symmetric", "approx_near_symmetric", "approx_small_anisotropy"] {
                let v = e.get(k).and_then(Value::as_f64).map_or(Value::Null, |w| json!(w * rpm));
                e.insert(format!("{k}_rpm"), v);
            }
            let iv = e
                .get("interval")
                .and_then(Value::as_array)
                .map_or(Value::Null, |iv| json!(iv.iter().filter_map(Value::as_f64).map(|w| w * rpm).collect::<Vec<_>>()));
            e.insert("interval_rpm".into(), iv);
        }
    }
    json!({
        "critical_speeds": speeds,
        "distinct_count": cs.distinct_count,
        "table1_count": cs.table1_count,
        "rotor_type": cs.rotor_class,
        "antiresonance_speed": ar.antiresonance_speed,
        "antiresonance_speed_rad_s": a_rad[0],
        "antiresonance_speed_rpm": a_rpm[0],
        "autobalancing_ranges": ranges_value(&ar.ranges),
        "autobalancing_ranges_rpm": ranges_rpm(&c.model, &ar.ranges),
        "balancing_class": ar.class,
        "operating_speed": operating_json(operating_of(c, Balls::Free)),
        "sensitivity": s,
        "anisotropy": anisotropy_json(&c.model, false),
        "model": model_json(c, source),
    })
}

/// `autobal ranges`: the speed ranges where autobalancing is possible (003).
pub fn ranges(c: &SpatialConfig, source: &str) -> Value {
    let ar = autobalancing_ranges(&c.model);
    let (a_rad, a_rpm) = speed_si(&c.model, &ar.antiresonance_speed.into_iter().collect::<Vec<_>>());
    let (cs_rad, cs_rpm) = speed_si(&c.model, &ar.critical_speeds);
    json!({
        "antiresonance_speed": ar.antiresonance_speed,
        "antiresonance_speed_rad_s": a_rad[0],
        "antiresonance_speed_rpm": a_rpm[0],
        "autobalancing_ranges": ranges_value(&ar.ranges),
        "autobalancing_ranges_rpm": ranges_rpm(&c.model, &ar.ranges),
        "phase_condition_ranges": ranges_value(&ar.phase_condition),
        "phase_condition_ranges_rpm": ranges_rpm(&c.model, &ar.phase_condition),
        "instability_ranges": ranges_value(&ar.instability),
        "instability_ranges_rpm": ranges_rpm(&c.model, &ar.instability),
        "critical_speeds_unbalanced_rotor": ar.critical_speeds,
        "critical_speeds_unbalanced_rotor_rad_s": cs_rad,
        "critical_speeds_unbalanced_rotor_rpm": cs_rpm,
        "balancing_class": ar.class,
        "delta_a0": c.model.delta_a0,
        "model": model_json(c, source),
    })
}

fn balls_name(balls: Balls) -> &'static str {
    if balls == Balls::Free {
        "free"
    } else {
        "locked"
    }
}

/// `autobal stability` of a config: [`stability`] with the verdict at the config's operating
/// speed (`operating_speed`, `null` without one; [`OperatingVerdict`]).
pub fn stability_of(cfg: &SpatialConfig, c: &Comparison, balls: Balls) -> Value {
    let mut v = stability(&cfg.model, c, balls);
    let op = cfg.analysis.operating_speed.map(|op| {
        if op[1] <= c.omega_max {
            operating_verdict(&cfg.model, op, &c.exact.stable_ranges, c.omega_max, balls)
        } else {
            // the span given does not reach the operating speed: a span that does
            operating_of(cfg, balls).unwrap_or_else(|| operating_verdict(&cfg.model, op, &c.exact.stable_ranges, c.omega_max, balls))
        }
    });
    v["operating_speed"] = operating_json(op);
    // a balancer that cannot cancel the unbalance has no balanced state: the verdicts above are
    // about the linear model's state, not about balancing (said, not left to be inferred)
    let capacity = cfg.model.masses.as_ref().map(|m| m.capacity());
    v["balancer_capacity"] = json!(capacity);
    v["balanced_state_exists"] = json!(capacity.is_none_or(|e| e >= 1.0));
    v
}

/// The line a report of the exact stability prints when the balancer's capacity `E < 1`: no
/// balanced state exists, so the 12-state verdict is not a verdict on balancing.
pub fn no_balanced_state_warning(model: &SpatialModel) -> Option<String> {
    let e = model.masses.as_ref()?.capacity();
    (e < 1.0).then(|| {
        format!(
            "warning: no balanced state exists: the balancer's capacity E = {} < 1 (the balls cannot cancel the unbalance; at best they rest together opposite it, partially balanced). The verdicts below are those of the linearised equations at the balanced configuration the balls cannot reach: not a verdict on balancing",
            crate::error::fmt_num((e * 1e4).round() / 1e4)
        )
    })
}

/// `autobal stability`: exact stability ranges against 003's necessary ranges; speeds in `Ω`
/// and, for a dimensional config, in rpm (`*_rpm`) and rad/s (`omega_max_rad_s`); the grid's
/// `max Re λ` also as `[rpm, 1/s]` pairs (`max_real_part_si`).
pub fn stability(model: &SpatialModel, c: &Comparison, balls: Balls) -> Value {
    let si = si_units(model);
    json!({
        "balls": balls_name(balls),
        "omega_max": c.omega_max,
        "omega_max_rad_s": si.map(|(k, _)| c.omega_max * k),
        "omega_max_rpm": si.map(|(_, k)| c.omega_max * k),
        "necessary_not_stable_rpm": ranges_rpm(model, &c.necessary_not_stable),
        "stable_not_necessary_rpm": ranges_rpm(model, &c.stable_not_necessary),
        "max_real_part_si": si.map(|(k, rpm)| c.exact.max_real_part.iter().map(|(w, a)| json!([w * rpm, a * k])).collect::<Vec<_>>()),
        "stable_ranges": ranges_value(&c.exact.stable_ranges),
        "necessary_ranges": ranges_value(&c.necessary),
        "stable_ranges_rpm": ranges_rpm(model, &c.exact.stable_ranges),
        "necessary_ranges_rpm": ranges_rpm(model, &c.necessary),
        "necessary_not_stable": ranges_value(&c.necessary_not_stable),
        "stable_not_necessary": ranges_value(&c.stable_not_necessary),
        // the ranges are computed over (0, omega_max] only: a null upper end means "reaches
        // omega_max", not "unbounded"; true for the lists whose last range reaches it
        "open_at_span_end": {
            "stable_ranges": open_at(&c.exact.stable_ranges),
            "necessary_ranges": open_at(&c.necessary),
            "necessary_not_stable": open_at(&c.necessary_not_stable),
            "stable_not_necessary": open_at(&c.stable_not_necessary),
        },
        "difference": c.difference(),
        "max_real_part": c.exact.max_real_part.iter().map(|(w, a)| json!([w, a])).collect::<Vec<_>>(),
        "tolerance": c.exact.tolerance,
        "stability_threshold": crate::spatial::stability::STABILITY_TOLERANCE,
        "anisotropy_used": model.anisotropy.used,
        "ball_coupling": model.balls,
    })
}

/// `autobal campbell` of a complete run: the speeds, the tracked lines and `complete: true`
/// (the CLI streams the same JSON, with `complete: false` after Ctrl-C). Dimensionless: for a
/// dimensional model see [`campbell_of`].
pub fn campbell(c: &Campbell) -> Value {
    json!({ "omega": c.omega, "lines": c.lines, "complete": true })
}

/// [`campbell`] in the model's units: for a dimensional model also the speeds in rad/s and rpm
/// (`omega_rad_s`, `omega_rpm`) and every mode with its frequencies in SI ([`mode_json`]).
pub fn campbell_of(model: &SpatialModel, c: &Campbell) -> Value {
    let Some((rad, rpm)) = si_units(model) else { return campbell(c) };
    let lines: Vec<Value> = c.lines.iter().map(|l| json!({ "modes": l.modes.iter().map(|m| mode_json(model, m)).collect::<Vec<_>>() })).collect();
    json!({
        "omega": c.omega,
        "omega_rad_s": c.omega.iter().map(|w| w * rad).collect::<Vec<_>>(),
        "omega_rpm": c.omega.iter().map(|w| w * rpm).collect::<Vec<_>>(),
        "lines": lines,
        "complete": true,
    })
}

/// One mode of a Campbell diagram as JSON: its fields (`Ω`-units, unit `ω0`) and, for a
/// dimensional model, `im_rad_s`, `im_hz` (`ν ω0`, `ν ω0/2π`), `re_per_s` (`σ ω0`, 1/s),
/// `decay_rate_per_s`, `fixed_frequency_rad_s`, `fixed_frequency_hz`, `fixed_frequency_rpm`
/// (whirl in fixed axes, `ω = f ω0`; in rpm, cycles per minute).
pub fn mode_json(model: &SpatialModel, m: &crate::spatial::stability::Mode) -> Value {
    let mut v = json!(m);
    if let (Some((k, _)), Some(o)) = (si_units(model), v.as_object_mut()) {
        let tau = 2.0 * std::f64::consts::PI;
        o.insert("re_per_s".into(), json!(m.re * k));
        o.insert("im_rad_s".into(), json!(m.im * k));
        o.insert("im_hz".into(), json!(m.im * k / tau));
        o.insert("decay_rate_per_s".into(), json!(m.decay_rate * k));
        o.insert("fixed_frequency_rad_s".into(), json!(m.fixed_frequency * k));
        o.insert("fixed_frequency_hz".into(), json!(m.fixed_frequency * k / tau));
        o.insert("fixed_frequency_rpm".into(), json!(m.fixed_frequency * k * 60.0 / tau));
    }
    v
}

/// `autobal simulate`: the run's summary, with the rotor, drive and tolerances it ran with.
pub fn simulation(p: &PlanarProblem, s: &Summary, wall_time_s: f64) -> Value {
    json!({
        "model": "planar",
        "peak_amplitude": s.peak_amplitude,
        "omega_at_peak": s.omega_at_peak,
        "t_at_peak": s.t_at_peak,
        "final_amplitude": s.final_amplitude,
        "final_omega": s.final_omega,
        "balanced": s.balanced,
        "settled": s.settled,
        "steps": s.steps,
        "implicit_steps": s.implicit_steps,
        "switches": s.switches,
        "rejected_steps": s.rejected_steps,
        "rhs_evaluations": s.rhs_evaluations,
        "contacts": s.contacts,
        "stick_slip_transitions": s.stick_slip_transitions,
        "t_end": s.t_end,
        "stopped": s.stopped,
        "warnings": s.warnings,
        "wall_time_s": wall_time_s,
        "natural_frequency": p.rotor.natural_frequency(),
        "capacity_ratio": capacity_ratio(&p.rotor),
        "s2": p.rotor.s2,
        "rotor": p.rotor,
        "drive": p.drive,
        "integration": {
            "method": p.settings.method,
            "rtol": p.settings.rtol,
            "atol": p.settings.atol,
            "dt": p.settings.dt,
            "max_steps": p.settings.max_steps,
            "max_wall_s": p.settings.max_wall_s,
        },
    })
}

/// `autobal simulate` on the spatial rotor (papers 000/003): the run's summary, with the rotor,
/// drive, initial state and tolerances it ran with; lengths and speeds in SI for an SI config,
/// in `ρ_s` and `ω0` for a dimensionless one (`units` says which).
pub fn spatial_simulation(sim: &crate::config::SpatialSimulation, s: &crate::spatial::dynamics::Summary, wall_time_s: f64) -> Value {
    json!({
        "model": "spatial",
        "units": if sim.config.dimensional { "SI" } else { "dimensionless (M_s = ω0 = ρ_s = 1)" },
        "outcome": s.outcome,
        "balanced": s.balanced,
        "residual_unbalance": s.residual_unbalance,
        "residual_couple": s.residual_couple,
        "balance_tolerance": crate::spatial::dynamics::simulate::BALANCE_TOLERANCE,
        "ball_drift": s.ball_drift,
        "peak_amplitude": s.peak_amplitude,
        "omega_at_peak": s.omega_at_peak,
        "t_at_peak": s.t_at_peak,
        "final_amplitude": s.final_amplitude,
        "static_sag": s.static_sag,
        "mean_displacement": s.mean_displacement,
        "final_omega": s.final_omega,
        "steps": s.steps,
        "rejected_steps": s.rejected_steps,
        "rhs_evaluations": s.rhs_evaluations,
        "contacts": s.contacts,
        "stick_slip_transitions": s.stick_slip_transitions,
        "wall_time_s": wall_time_s,
        "t_end": s.t_end,
        "stopped": s.stopped,
        "natural_frequency": sim.rotor.natural_frequency(),
        "rotor": sim.rotor,
        "drive": sim.drive,
        "drive_is_default": sim.default_drive,
        "initial": sim.initial,
        "integration": sim.settings,
    })
}

/// `autobal basins`: how many of the runs over the first two balls' initial angles completed
/// and ended balanced.
pub fn basins(results: &[Option<crate::spatial::dynamics::Summary>], wall_time_s: f64) -> Value {
    let done = results.iter().flatten().count();
    let balanced = results.iter().flatten().filter(|s| s.balanced).count();
    json!({
        "runs": results.len(),
        "completed": done,
        "balanced": balanced,
        "fraction_balanced": balanced as f64 / done.max(1) as f64,
        "wall_time_s": wall_time_s,
    })
}

/// The speeds of `autobal campbell`: `points` cell centres over `(0, omega_max)`.
pub fn campbell_speeds(omega_max: f64, points: usize) -> Vec<f64> {
    let n = points.max(3);
    (0..n).map(|i| omega_max * (i as f64 + 0.5) / n as f64).collect()
}

/// The fixed-axes Campbell view ([`crate::spatial::campbell::fixed_axes`]) as JSON, as `autobal campbell --format json` prints it beside the tracked lines: `fixed_axes_modes` (per mode: its number, tracked line and per
/// speed `omega`, `frequency`, `fixed_frequency`, `whirl`, `log_decrement`, ...; for a
/// dimensional config `frequency_hz`, `fixed_frequency_hz`, `re_per_s`, `omega_rpm`) and `critical_speeds` (speed, mode
/// number, whirl, harmonic; in rpm and Hz for a dimensional config).
pub fn campbell_fixed(model: &SpatialModel, f: &crate::spatial::campbell::FixedCampbell) -> Value {
    let w0 = model.scale.map(|sc| sc.omega0);
    let tau = 2.0 * std::f64::consts::PI;
    let modes: Vec<Value> = f
        .curves
        .iter()
        .enumerate()
        .map(|(i, cv)| {
            let pts: Vec<Value> = cv
                .points
                .iter()
                .map(|p| {
                    let mut v = json!(p);
                    if let (Some(w0), Some(o)) = (w0, v.as_object_mut()) {
                        o.insert("frequency_hz".into(), json!(p.frequency * w0 / tau));
                        o.insert("fixed_frequency_hz".into(), json!(p.fixed_frequency * w0 / tau));
                        o.insert("re_per_s".into(), json!(p.re * w0));
                        o.insert("omega_rpm".into(), json!(p.omega * w0 * 60.0 / tau));
                    }
                    v
                })
                .collect();
            json!({"mode": i + 1, "line": cv.line, "points": pts})
        })
        .collect();
    let crit: Vec<Value> = f
        .critical_speeds
        .iter()
        .map(|k| {
            let mut v = json!({"omega": k.omega, "mode": k.curve + 1, "whirl": k.whirl, "harmonic": k.harmonic, "frequency": k.frequency});
            if let (Some(w0), Some(o)) = (w0, v.as_object_mut()) {
                o.insert("omega_rad_s".into(), json!(k.omega * w0));
                o.insert("omega_rpm".into(), json!(k.omega * w0 * 60.0 / tau));
                o.insert("frequency_hz".into(), json!(k.frequency * w0 / tau));
            }
            v
        })
        .collect();
    json!({"harmonics": f.harmonics, "fixed_axes_modes": modes, "critical_speeds": crit})
}
