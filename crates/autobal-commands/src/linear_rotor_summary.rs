//! `inertia`, `critical` and `ranges` on a linear rotor config (`[linear_rotor]`, issue 19):
//! what each can say exactly about a rotor given by its matrices, and where it cannot, one line
//! saying why and which command answers instead.
//!
//! - `inertia`: the structure's mass in a rigid translation `u_xᵀ M u_x`, `u_yᵀ M u_y` (`u_x`:
//!   1 on every `x` DOF, 0 elsewhere; the consistent mass of beam elements and lumped masses
//!   give the structure's mass exactly, a rigid translation having unit translations and zero
//!   tilts at every node), the rotor's polar moment `I_p`
//!   ([`autobal::linear_rotor::LinearRotor::polar_inertia`]), and per balancer plane the balls'
//!   mass `n m_b`, the ring's polar moment `n m_b R²` and the capacity `n m_b R` against the
//!   static unbalance `|Σ m e e^{i phase}|`. Paper 000's composite inertia (a rigid body on two
//!   supports) is not this rotor's.
//! - `critical`: the undamped natural frequencies at rest with the balls as rings
//!   ([`autobal::linear_rotor::LinearRotor::natural_frequencies`], of the model analysed: the
//!   reduced one where the config reduces, as `stability` prints them). The critical speeds at
//!   speed (gyroscopic terms, bearings over speed, balls free) are `autobal campbell`'s.
//! - `ranges`: paper 003's necessary ranges are those of the rigid rotor of papers 000/003, not
//!   defined here; the exact stable ranges over `stability`'s default axis and grid instead.

use crate::linear_rotor::{divergence_json, divergence_text, model, modes_at_rest, reduction_json, reduction_text};
use anyhow::Result;
use autobal::error::fmt_num;
use autobal::linear_rotor::config::LinearRotorConfig;
use autobal::linear_rotor::{Direction, LinearRotor};
use serde_json::{json, Value};
use std::fmt::Write;

/// `u_aᵀ A u_b` for the rigid translations `u_a`, `u_b` (1 on every DOF of direction `a`, `b`).
fn translation_form(rotor: &LinearRotor, a: &[f64], da: Direction, db: Direction) -> f64 {
    let n = rotor.dofs();
    let on = |d: Direction| -> Vec<usize> { (0..n).filter(|&i| rotor.dof_node(i).is_some_and(|(_, di)| di == d)).collect() };
    let (ia, ib) = (on(da), on(db));
    ia.iter().map(|&i| ib.iter().map(|&j| a[i * n + j]).sum::<f64>()).sum()
}

/// `|Σ m e e^{i phase}|`, the static unbalance (kg·m).
pub fn static_unbalance(rotor: &LinearRotor) -> f64 {
    let (x, y) = rotor.unbalances.iter().fold((0.0, 0.0), |(x, y), u| (x + u.me * u.phase.cos(), y + u.me * u.phase.sin()));
    x.hypot(y)
}

/// `autobal inertia` on a linear rotor config (module docs): the JSON and the table.
pub fn inertia(cfg: &LinearRotorConfig) -> (Value, String) {
    let r = &cfg.rotor;
    let mx = translation_form(r, &r.m, Direction::X, Direction::X);
    let my = translation_form(r, &r.m, Direction::Y, Direction::Y);
    let mxy = translation_form(r, &r.m, Direction::X, Direction::Y);
    // the inertia that turns with the rotor: its mean over the rotor's angle
    let mrot = if r.rotor_fixed_mass.is_empty() {
        0.0
    } else {
        0.5 * (translation_form(r, &r.rotor_fixed_mass, Direction::X, Direction::X) + translation_form(r, &r.rotor_fixed_mass, Direction::Y, Direction::Y))
    };
    let balls: Vec<Value> = r
        .balancers
        .iter()
        .map(|b| {
            let n = b.balls as f64;
            json!({
                "node": b.node,
                "balls": b.balls,
                "ball_mass": b.ball_mass,
                "balls_mass": n * b.ball_mass,
                "radius": b.radius,
                "ring_polar_moment": n * b.ball_mass * b.radius * b.radius,
                "capacity": n * b.ball_mass * b.radius,
            })
        })
        .collect();
    let balls_mass: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass).sum();
    let capacity: f64 = r.balancers.iter().map(|b| b.balls as f64 * b.ball_mass * b.radius).sum();
    let s0 = static_unbalance(r);
    let physical = cfg.source == "shaft";
    let basis = "u_x^T M u_x with u_x = 1 on every x DOF (a rigid translation: unit translations, zero tilts): the structure's mass where the DOFs are physical nodes' translations and tilts (not the modal coordinates of a reduced model written by export-model)";
    let v = json!({
        "model": "linear",
        "source": cfg.source,
        "dofs": r.dofs(),
        "structure": {
            "mass_x": mx,
            "mass_y": my,
            "mass_xy": mxy,
            "rotor_fixed_mass_mean": mrot,
            "basis": basis,
            "dofs_are_physical": if physical { Value::Bool(true) } else { Value::Null },
        },
        "polar_inertia": if r.polar_inertia > 0.0 { json!(r.polar_inertia) } else { Value::Null },
        "balancers": balls,
        "balls_mass": balls_mass,
        "total_mass": mx + mrot + balls_mass,
        "static_unbalance": s0,
        "capacity": capacity,
        "paper_000_not_applicable": "a linear rotor (matrices M, C, G, K over nodes): paper 000's composite inertia is that of a rigid rotor on two supports",
    });
    let mut s = String::new();
    let _ = writeln!(s, "Linear rotor: mass properties ({} DOFs, {})", r.dofs(), if physical { "built-in shaft builder" } else { "matrix files" });
    let _ = writeln!(s, "structure, rigid translation: u_x^T M u_x = {} kg, u_y^T M u_y = {} kg (u_x^T M u_y = {})", fmt_num(mx), fmt_num(my), fmt_num(mxy));
    if !physical {
        let _ = writeln!(
            s,
            "  (u_x: 1 on every x DOF: the structure's mass where the DOFs are physical translations and tilts, not a reduced model's modal coordinates)"
        );
    }
    if mrot != 0.0 {
        let _ = writeln!(s, "inertia turning with the rotor (linear_rotor.rotor_fixed_mass), mean over the angle: {} kg", fmt_num(mrot));
    }
    let _ = writeln!(
        s,
        "polar moment I_p (spin axis, balls excluded): {}",
        if r.polar_inertia > 0.0 { format!("{} kg m^2", fmt_num(r.polar_inertia)) } else { "not given (linear_rotor.polar_inertia)".into() }
    );
    for (i, b) in r.balancers.iter().enumerate() {
        let n = b.balls as f64;
        let _ = writeln!(
            s,
            "balancer {i} at node {}: {} balls of {} kg ({} kg), race radius {} m, ring polar moment n m R^2 = {} kg m^2, capacity n m R = {} kg m",
            b.node,
            b.balls,
            fmt_num(b.ball_mass),
            fmt_num(n * b.ball_mass),
            fmt_num(b.radius),
            fmt_num(n * b.ball_mass * b.radius * b.radius),
            fmt_num(n * b.ball_mass * b.radius)
        );
    }
    let _ = writeln!(s, "static unbalance |sum m e e^(i phase)| = {} kg m; balls' capacity in all {} kg m", fmt_num(s0), fmt_num(capacity));
    let _ = writeln!(s, "total mass (structure + balls): {} kg", fmt_num(mx + mrot + balls_mass));
    let _ = writeln!(s, "paper 000's composite inertia: not defined (a rigid rotor on two supports; this is a linear rotor over nodes)");
    (v, s)
}

/// `autobal critical` on a linear rotor config (module docs): the JSON and the table.
pub fn critical(cfg: &LinearRotorConfig) -> Result<(Value, String)> {
    let (rotor, red) = model(cfg)?;
    let (w, diverging) = modes_at_rest(&rotor, 8)?;
    let what = "undamped natural frequencies at rest (Omega = 0: no gyroscopic terms, speed-dependent bearings at 0) with the balls as rings and the rotor-fixed inertia at the rotor's angle 0 (LinearRotor::natural_frequencies)";
    let v = json!({
        "model": "linear",
        "source": cfg.source,
        "route": "linear",
        "natural_frequencies": w,
        "static_divergence": divergence_json(&diverging),
        "every_mode_diverges": w.is_empty() && !diverging.is_empty(),
        "natural_frequencies_are": what,
        "reduction": reduction_json(&red),
        "critical_speeds": Value::Null,
        "critical_speeds_are": "not computed here: the critical speeds at speed (gyroscopic terms, bearings over speed, balls free) are autobal campbell's",
    });
    let mut s = divergence_text(&diverging);
    let others = if diverging.is_empty() { "" } else { " (of the modes that do not diverge)" };
    let _ = writeln!(s, "Linear rotor: {what}{others}:");
    if w.is_empty() {
        let _ = writeln!(s, "  {}", crate::linear_rotor::frequencies_text(&w, &diverging));
    }
    for (i, x) in w.iter().enumerate() {
        let _ = writeln!(
            s,
            "  {}. {} rad/s ({} rpm)",
            i + 1,
            fmt_num(crate::num::round_sig(*x, 6).unwrap_or(*x)),
            fmt_num(crate::num::round_sig(x * 30.0 / std::f64::consts::PI, 6).unwrap_or(*x))
        );
    }
    s.push_str(&reduction_text(&red));
    let _ = writeln!(s, "critical speeds at speed (gyroscopic terms, bearings over speed, balls free): autobal campbell --config ...");
    Ok((v, s))
}

/// `autobal ranges` on a linear rotor config (module docs): the exact stable ranges of
/// `stability` over its default axis and grid, and a line saying 003's are not defined.
pub fn ranges(cfg: &LinearRotorConfig) -> Result<(Value, String)> {
    let omega_max = crate::linear_rotor::default_omega_max(cfg)?;
    let samples = if cfg.rotor.is_isotropic() { 200 } else { 50 };
    let (r, red) = crate::linear_rotor::stability(cfg, omega_max, samples)?;
    let why = "paper 003's necessary ranges are not defined for this config: a linear rotor (003's conditions are those of the rigid rotor of papers 000/003)";
    let v = json!({
        "model": "linear",
        "source": cfg.source,
        "autobalancing_ranges": Value::Null,
        "autobalancing_ranges_are": Value::Null,
        "necessary_not_defined": why,
        "exact": crate::linear_rotor::stability_json(cfg, &r, &red, omega_max)?,
    });
    let mut s = String::new();
    let _ = writeln!(s, "config: {}", cfg.source);
    let _ = writeln!(s, "autobalancing ranges (necessary condition, paper 003): not defined for this config: a linear rotor (003's conditions are those of the rigid rotor of papers 000/003)");
    let _ = writeln!(s, "exact stable speed ranges, as `autobal stability`:");
    s.push_str(&crate::linear_rotor::stability_table(cfg, &r, &red, omega_max)?);
    Ok((v, s))
}
