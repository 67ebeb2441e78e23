//! The input ranges of docs/reference/robustness.md (`autobal::limits::LIMITS`) are true: every field at
//! each end of its range (the end itself where it is closed, the nearest double inside where it
//! is open) is accepted by the model that reads it, on the example config of that model, and
//! the nearest value outside is refused with that limit's own message (issue 23, "limits stated
//! once and true").

use autobal::config::{self, parse, parse_value, set, Table, Value};
use autobal::limits::{Limit, LIMITS};

const PLANAR: &str = include_str!("../../../examples/planar.toml");
const DIMENSIONAL: &str = include_str!("../../../examples/dimensional.toml");
const DIMENSIONLESS: &str = include_str!("../../../examples/default.toml");
const TWO_PLANE: &str = include_str!("../../../examples/spatial_two_plane.toml");

/// The example config a field belongs to, and the model that reads it.
fn base(field: &str) -> (&'static str, fn(&Table) -> autobal::Result<()>) {
    let linear: fn(&Table) -> autobal::Result<()> = |r| config::spatial(r).map(drop);
    let sim: fn(&Table) -> autobal::Result<()> = |r| config::spatial_simulation(r).map(drop);
    let planar: fn(&Table) -> autobal::Result<()> = |r| config::planar(r).map(drop);
    let table = field.split('.').next().unwrap();
    match table {
        "planar" | "drive" | "integration" => (PLANAR, planar),
        "dimensionless" => (DIMENSIONLESS, linear),
        "analysis" => (DIMENSIONAL, linear),
        "couple" | "balancer2" | "spatial" | "initial" => (TWO_PLANE, sim),
        _ if field.ends_with("_y") || field.contains("axis_tilt") || field == "unbalance.angle" => (TWO_PLANE, sim),
        _ if ["ball_diameter", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate"].iter().any(|k| field.ends_with(k)) => (TWO_PLANE, sim),
        _ => (DIMENSIONAL, linear),
    }
}

/// `field` set to `v` in the form the config takes (an array's first entry for array fields).
fn value(field: &str, v: f64) -> Value {
    let num = |x: f64| if field.ends_with("balls") || field == "dimensionless.n" || field == "planar.n" { Value::Integer(x as i64) } else { Value::Float(x) };
    match field {
        "spatial.gravity" => Value::Array(vec![num(v), num(0.0), num(0.0)]),
        f if f.starts_with("initial.") || f.starts_with("drive.psi") || f.starts_with("drive.xy") => Value::Array(vec![num(v), num(0.0)]),
        "drive.schedule" => Value::Array(vec![Value::Array(vec![num(0.0), num(v)]), Value::Array(vec![num(1.0), num(v)])]),
        _ => num(v),
    }
}

/// The two ends of a limit reached from inside, and just past each.
fn ends(l: &Limit) -> [(f64, f64); 2] {
    let inside_lo = if l.lo_open { l.lo.next_up() } else { l.lo };
    let past_lo = if l.lo_open { l.lo } else { l.lo.next_down() };
    let inside_hi = if l.hi_open { l.hi.next_down() } else { l.hi };
    let past_hi = if l.hi_open { l.hi } else { l.hi.next_up() };
    [(inside_lo, past_lo), (inside_hi, past_hi)]
}

fn with(text: &str, field: &str, v: Value) -> Table {
    let mut root = parse(text, "example").unwrap();
    set(&mut root, field, v).unwrap();
    if field == "drive.schedule" {
        set(&mut root, "drive.kind", parse_value("\"schedule\"")).unwrap();
        set(&mut root, "drive.schedule_of", parse_value("\"torque\"")).unwrap();
    }
    root
}

#[test]
fn every_limit_is_reached_and_one_past_it_is_refused_with_its_message() {
    let mut not_reached = vec![];
    let mut wrong = vec![];
    for l in LIMITS {
        let (text, build) = base(l.field);
        assert!(build(&parse(text, "example").unwrap()).is_ok(), "{}: the example does not build", l.field);
        for (at, past) in ends(l) {
            let is_count = l.field.ends_with("balls") || l.field.ends_with(".n");
            if is_count && at.fract() != 0.0 {
                continue;
            }
            // past the end: refused with this limit's message, naming the field
            let past = if is_count {
                if past < l.lo {
                    continue;
                } else {
                    l.hi + 1.0
                }
            } else {
                past
            };
            let own =
                if is_count { format!("{}: {} exceeds the limit of {}", l.field, past, l.hi) } else { format!("{}: must lie in {}", l.field, l.describe()) };
            match build(&with(text, l.field, value(l.field, past))) {
                Ok(()) => wrong.push(format!("{} = {past:e} accepted", l.field)),
                Err(e) if !e.to_string().starts_with(&own) => wrong.push(format!("{} = {past:e}: `{e}` is not the limit's message `{own}`", l.field)),
                Err(_) => {}
            }
            // at the end: never refused by its own range; accepted unless another stated
            // relation (also at most ..., a derived ratio) is what the end breaks
            if let Err(e) = build(&with(text, l.field, value(l.field, at))) {
                let e = e.to_string();
                // another relation is a derived ratio or a condition, never another plain range
                if e.contains("must lie in") {
                    wrong.push(format!("{} = {at:e} lies in its range but is refused by it: {e}", l.field));
                }
                not_reached.push(format!("{} = {at:e}: {e}", l.field));
            }
        }
    }
    for n in &not_reached {
        eprintln!("{n}");
    }
    eprintln!("{} of {} ends refused by another relation", not_reached.len(), 2 * LIMITS.len());
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
