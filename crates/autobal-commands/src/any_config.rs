//! `autobal inertia` and `autobal ranges` on every configuration: what each computes where the
//! one-plane model of papers 000/003 does not describe the rotor, and where it does, beside it.
//!
//! - `inertia`: paper 000's composite inertia where it describes the rotor, and always (where the
//!   simulation can build the rotor) the whole rotor's mass properties
//!   ([`autobal::reports::whole_rotor`]). Supports and gravity do not enter: they are not
//!   ignored, they are not part of the rotor's mass. A planar config is refused with one line:
//!   the planar rotor moves in its plane without tilting, so an inertia tensor and principal
//!   axes say nothing about it.
//! - `ranges`: on a one-plane config, 003's necessary ranges labelled as a necessary condition,
//!   beside the exact ranges of the 12-state model (as `stability`); on any other config (a
//!   second plane, couple unbalance, supports that differ by direction, gravity, a planar
//!   config, ...) the exact stable ranges of the general route over `stability`'s axis and grid
//!   ([`general::default_omega_max`], [`general::default_samples`]), and a line saying that
//!   003's ranges are not defined there, naming the entries.

use crate::general;
use crate::output;
use anyhow::{bail, Result};
use autobal::control::Control;
use autobal::spatial::ranges::SpeedRange;
use serde_json::{json, Value};
use std::fmt::Write;
use toml::Table;

/// The one-line refusal of `inertia` on a planar config.
pub const PLANAR_INERTIA: &str = "inertia: this is a planar-rotor config ([planar]): the planar rotor moves in its plane without tilting, so an inertia tensor and principal axes say nothing about it (its masses are the [planar] entries m1, m2, n m3); use a spatial config ([rotor], [supports], ... or [dimensionless])";

/// `autobal inertia` of `root`: the JSON and the table.
pub fn inertia(root: &Table, source: &str) -> Result<(Value, String)> {
    if !autobal::config::is_spatial(root) {
        bail!(PLANAR_INERTIA);
    }
    let r = autobal::reports::inertia_of(root, source)?;
    let mut s = String::new();
    match &r.paper_000_not_applicable {
        None => s.push_str(&output::inertia_table(&crate::config::build(root, source)?)),
        Some(why) => {
            let _ = writeln!(s, "config: {source}");
            let _ = writeln!(s, "{why}: the whole rotor below is the config's");
        }
    }
    match (&r.whole_rotor, &r.whole_rotor_unavailable) {
        (Some(w), _) => s.push_str(&output::whole_rotor_table(w)),
        (None, e) => {
            let _ = writeln!(
                s,
                "
whole rotor as the simulation builds it: not available ({})",
                e.as_deref().unwrap_or_default()
            );
        }
    }
    Ok((autobal::reports::to_json(&r), s))
}

/// `autobal ranges` of `root`: the JSON and the table.
/// The general route's scan runs under `control`.
pub fn ranges(root: &Table, source: &str, control: &Control) -> Result<(Value, String)> {
    if general::needs_general_verdict(root) {
        return ranges_general(root, source, control);
    }
    let cfg = crate::config::build(root, source)?;
    output::check_results(&cfg)?;
    let r = autobal::reports::ranges_with_exact(&cfg.config, source)?;
    let mut s = output::ranges_table(&cfg);
    let (exact, w) =
        r.exact.as_ref().map_or((vec![], f64::NAN), |e| (e.stable_ranges.iter().map(|&(lo, hi)| SpeedRange { lo, hi }).collect::<Vec<_>>(), e.omega_max));
    let _ = writeln!(s, "  exact stable ranges (eigenvalues of 000's 12-state model, balls free, as `autobal stability`), 0 < Ω ≤ {w:.4}:");
    let _ = writeln!(s, "    {}", autobal::spatial::comparison::fmt_ranges_in(&exact, 4, Some(w)));
    if let Some(sc) = cfg.model.scale {
        let k = sc.omega0 * 30.0 / std::f64::consts::PI;
        let _ = writeln!(s, "    {} rpm", autobal::spatial::comparison::fmt_ranges_in(&autobal::reports::scale_ranges(&exact, k), 0, Some(w * k)));
    }
    Ok((autobal::reports::to_json(&r), s))
}

/// The entries for which 003's ranges are not defined, as a phrase.
fn not_defined(root: &Table) -> String {
    if !autobal::config::is_spatial(root) {
        return "the planar rotor ([planar]): 003's conditions are those of the spatial rotor of papers 000/003".into();
    }
    let keys = autobal::config::ignored_by_linear_model(root);
    format!("{} (003's conditions are those of the rotor of papers 000/003: one plane of point-mass balls, static unbalance, supports equal in x and y, no gravity)", keys.join(", "))
}

fn ranges_general(root: &Table, source: &str, control: &Control) -> Result<(Value, String)> {
    let g = general::rotor_of(root)?;
    let omega_max = general::default_omega_max(&g, root)?;
    let r = general::analyse(&g, omega_max, general::default_samples(&g), control)?;
    let op = general::operating(&g, root, &r, control)?;
    if let Some(why) = op.as_ref().and_then(|o| o.stopped) {
        // (`ranges` keeps no part of a stopped run, as of a stopped scan: `general::analyse`)
        bail!("{why}: the verdict at the operating speed stopped; nothing is printed");
    }
    let why = not_defined(root);
    let model = if autobal::config::is_spatial(root) {
        autobal::reports::to_json(&autobal::reports::model_report(&autobal::config::spatial(root)?, source))
    } else {
        Value::Null
    };
    let v = json!({
        "model": model,
        "source": source,
        "autobalancing_ranges": Value::Null,
        "autobalancing_ranges_are": Value::Null,
        "necessary_not_defined": format!("paper 003's necessary ranges are not defined for this config: {why}"),
        "exact": general::json(&g, &r, omega_max),
        "operating": op.as_ref().map_or(Value::Null, general::operating_json),
    });
    let mut s = String::new();
    let _ = writeln!(s, "config: {source}");
    let _ = writeln!(s, "autobalancing ranges (necessary condition, paper 003): not defined for this config: {why}");
    let _ = writeln!(s, "exact stable speed ranges, as `autobal stability`:");
    s.push_str(&general::table(&g, &r, omega_max, op.as_ref()));
    Ok((v, s))
}
