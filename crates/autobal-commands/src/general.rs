//! `autobal stability` on any configuration autobal can run: the general route
//! ([`autobal::rotor_stability`]) for the planar rotor and for spatial rotors with what paper
//! 000's 12-state model does not have (a second plane, couple unbalance, supports that differ by
//! direction, gravity, a tilted principal axis), or for any config with `--route general`.

use crate::plot::{Plot, Series, Shade, PALETTE};
use anyhow::Result;
use autobal::analysis::{Kind, Verdict};
use autobal::control::Control;
use autobal::error::fmt_num;
use autobal::rotor_stability::{speed_grid, Rotor, RotorStability};
use serde_json::{json, Value};
use toml::Table;

/// A rotor built from a config for the general route, with its speed unit.
pub struct GeneralRotor {
    /// The rotor.
    pub rotor: Rotor,
    /// Whether speeds are SI (rad/s; also rpm printed) or the papers' dimensionless Ω.
    pub si: bool,
    /// ω0 of a spatial config (rad/s per unit Ω), 1 otherwise.
    pub omega0: f64,
}

impl GeneralRotor {
    /// A linear rotor (`[linear_rotor]`, SI: speeds in rad/s with rpm), as `stability`,
    /// `campbell` and the report analyse it.
    pub fn linear(rotor: autobal::linear_rotor::LinearRotor) -> Self {
        GeneralRotor { rotor: Rotor::Linear(rotor), si: true, omega0: 1.0 }
    }
}

/// Whether an analysis must take the general route for this config: a planar config, or a
/// spatial one with entries paper 000's 12-state model does not represent.
pub fn needs_general_route(root: &Table) -> bool {
    !autobal::config::is_spatial(root) || !autobal::config::ignored_by_linear_model(root).is_empty()
}

/// Whether a stability verdict (`stability`, `ranges`, `map`, the report's stability and
/// design sections) must take the general route: [`needs_general_route`], or a spatial config
/// whose balanced state the closed form does not give as an isolated state: no unbalance
/// ([`Rotor::has_unbalance`]: the balls' balanced states form a family, whose neutral
/// direction the closed-form route counted as "not stable", so that it read "stable: none"
/// at every speed where the general route finds the family's stable members and a time
/// simulation balances), or a single ball (balanced only at one unbalance: elsewhere the
/// general route's partially balanced state; the closed form said "stable: none" without
/// saying why). Both found by session 19's audit on examples/dimensional.toml. The critical
/// speeds and Campbell diagrams keep the closed form there (paper 000's report, well defined
/// without unbalance). A map decides for all its cells at once: an axis through zero unbalance
/// or one ball takes the whole map onto the general route (`map`'s `axis_value_needs_general`).
pub fn needs_general_verdict(root: &Table) -> bool {
    if needs_general_route(root) {
        return true;
    }
    autobal::config::spatial_simulation(root).is_ok_and(|sim| {
        let single = sim.rotor.planes.iter().any(|p| p.n == 1);
        single || !Rotor::Spatial(sim.rotor).has_unbalance()
    })
}

/// The rotor of a planar (`[planar]`) or spatial config, as the simulation would run it.
pub fn rotor_of(root: &Table) -> Result<GeneralRotor> {
    if autobal::config::is_spatial(root) {
        let sim = autobal::config::spatial_simulation(root)?;
        let omega0 = sim.config.model.scale.map_or(1.0, |s| s.omega0);
        Ok(GeneralRotor { rotor: Rotor::Spatial(sim.rotor), si: sim.config.dimensional, omega0 })
    } else {
        Ok(GeneralRotor { rotor: Rotor::Planar(autobal::config::planar_rotor_for_analysis(root)?), si: true, omega0: 1.0 })
    }
}

fn unit(g: &GeneralRotor) -> &'static str {
    if g.si {
        "rad/s"
    } else {
        "Ω"
    }
}

fn rpm(w: f64) -> f64 {
    w * 30.0 / std::f64::consts::PI
}

pub(crate) fn speed_text(g: &GeneralRotor, w: f64) -> String {
    if g.si {
        format!("{} rad/s ({} rpm)", fmt_num(round(w)), fmt_num(round(rpm(w))))
    } else {
        format!("Ω = {}", fmt_num(round(w)))
    }
}

/// Six significant digits for the table (the JSON keeps every digit).
fn round(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let p = 10f64.powi(5 - x.abs().log10().floor() as i32);
    (x * p).round() / p
}

/// Run the general route over `(0, omega_max]` (model units) with `samples` speeds, under
/// `control`; a stopped scan is an error (`ranges`' use, which prints nothing of a stopped
/// scan: `stability` and the report keep what a stopped scan analysed, [`scan`]).
pub fn analyse(g: &GeneralRotor, omega_max: f64, samples: usize, control: &Control) -> Result<RotorStability> {
    let (out, speeds) = scan(g, omega_max, samples, control)?;
    if let Some(why) = out.stopped {
        anyhow::bail!("{why}: the stability scan stopped after {} of {speeds} speeds; nothing is printed", out.value.points.len());
    }
    Ok(out.value)
}

/// The general route's scan over `(0, omega_max]` with `samples` speeds under `control` (asked
/// once per speed), as it ended: stopped, the speeds analysed until then; and the grid's
/// length.
pub fn scan(g: &GeneralRotor, omega_max: f64, samples: usize, control: &Control) -> Result<(autobal::control::Outcome<RotorStability>, usize)> {
    let speeds = speed_grid(omega_max, samples)?;
    let out = autobal::rotor_stability::stability_over_speed_with(&g.rotor, &speeds, control).map_err(|e| floor_in_units(g, e, &speeds))?;
    Ok((out, speeds.len()))
}

fn what_is_analysed(g: &GeneralRotor, r: &RotorStability) -> String {
    let model = match &g.rotor {
        Rotor::Planar(p) if p.s2 == 0.0 => "the planar rotor with its race centred (a Jeffcott rotor with balls): its balanced state",
        Rotor::Planar(_) => "the planar rotor with an eccentric race (paper 004): its semi-balanced state (race centre on the axis)",
        Rotor::Spatial(s) if s.planes.iter().filter(|p| p.n > 0).count() > 1 => {
            "the spatial rotor with two ball planes: the state where the balls cancel static and couple unbalance"
        }
        Rotor::Spatial(_) => "the spatial rotor: the state where the balls cancel the static unbalance",
        Rotor::Linear(_) => "the linear rotor-bearing model: its balanced state (the balancer's race centre on the axis)",
    };
    let how = match (r.kind, &g.rotor) {
        (Kind::Equilibrium, _) => "an equilibrium in axes turning with the rotor (Newton on the nonlinear equations; eigenvalues of their exact Jacobian by automatic differentiation)",
        // the planar rotor's equations turn with its supports only, through e^{-2iθ}
        (Kind::PeriodicOrbit, Rotor::Planar(p)) if p.s2 == 0.0 => {
            "a state at rest in axes turning with the rotor whose equations vary with half a revolution (supports that differ by direction; no support force acts on the balanced state, so it is stationary at every instant); Floquet multipliers over T = π/Ω from the variational equations"
        }
        (Kind::PeriodicOrbit, Rotor::Planar(_)) => {
            "a periodic orbit of half a revolution (supports that differ by direction: the whirl is elliptic; shooting with the variational equations; Floquet multipliers)"
        }
        // without gravity across the axis the spatial equations repeat after half a revolution
        (Kind::PeriodicOrbit, Rotor::Spatial(s)) if !s.gravity_across() => {
            "a periodic orbit of half a revolution (supports that differ by direction turn against the rotor: the whirl is elliptic; shooting with the variational equations; Floquet multipliers over T = π/Ω)"
        }
        (Kind::PeriodicOrbit, _) => {
            "a periodic orbit of one revolution (supports that differ by direction or gravity turn against the rotor: the rotor sags and the balls swing; shooting with the variational equations; Floquet multipliers)"
        }
    };
    // where no speed has the state named (capacity short, a couple no plane cancels), say
    // what is analysed instead: the state words per speed follow in the table
    let none_balanced = r.points.iter().any(|p| p.state.is_some())
        && r.points
            .iter()
            .filter_map(|p| p.state)
            .all(|k| !matches!(k, autobal::rotor_stability::StateKind::Balanced | autobal::rotor_stability::StateKind::SemiBalanced));
    let instead = if none_balanced { " (at no speed here does that state exist: the states found instead are named below)" } else { "" };
    format!("{model}{instead}, found as {how}")
}

/// The neutral band of the verdict, as the JSON's `neutral_tolerance` states it.
pub fn neutral_tolerance(kind: Kind) -> String {
    match kind {
        Kind::Equilibrium => format!("|max Re λ| ≤ {} · max|λ| is neutral", fmt_num(autobal::analysis::NEUTRAL_TOLERANCE)),
        Kind::PeriodicOrbit => format!("|max|μ| − 1| ≤ {} is neutral", fmt_num(autobal::analysis::FLOQUET_TOLERANCE)),
    }
}

/// The JSON of the general route.
pub fn json(g: &GeneralRotor, r: &RotorStability, omega_max: f64) -> Value {
    let ranges: Vec<Value> = r
        .stable_ranges
        .iter()
        .map(|s| {
            let mut v = stable_range_json(s);
            // the states the range covers, as points[].state names them ("not_balanced", ...)
            v["states"] = json!(range_state_keys(r, s));
            if g.si {
                v["from_rpm"] = json!(rpm(s.from));
                v["to_rpm"] = json!(rpm(s.to));
            }
            v
        })
        .collect();
    json!({
        "route": "general",
        "model": r.model,
        "stationary_state": r.kind,
        "what": what_is_analysed(g, r),
        "speed_unit": unit(g),
        "omega_max": omega_max,
        "stable_ranges": ranges,
        "has_unbalance": r.has_unbalance,
        "residual_scale": r.residual_scale,
        "family_dimension": r.family_dimension,
        "member_psi": r.member_psi,
        "family": r.family,
        "neutral_tolerance": neutral_tolerance(r.kind),
        "points": r.points,
    })
}

/// How many members of the family were analysed at each speed, for the family's line:
/// `", 52-135 members analysed per speed (drawn and corrected onto the family, bunched,
/// searched)"` ([`autobal::rotor_stability::FamilyStability::members_analysed`]; a count of
/// members, not of the points drawn); empty where none was followed.
pub(crate) fn members_words(f: &autobal::rotor_stability::FamilyStability) -> String {
    let what = if f.dimension >= 2 { " (drawn and corrected onto the family, bunched, searched)" } else { "" };
    match f.members_analysed {
        Some([a, b]) if a == b => format!(", {a} members analysed at each speed{what}"),
        Some([a, b]) => format!(", {a}-{b} members analysed per speed{what}"),
        None => String::new(),
    }
}

/// The table of the general route.
pub fn table(g: &GeneralRotor, r: &RotorStability, omega_max: f64, op: Option<&Operating>) -> String {
    let mut s = String::new();
    if let Some(op) = op {
        s.push_str(&operating_line(g, r, op));
    }
    s.push_str("Exact linear stability over speed (general route)\n");
    s.push_str(&format!("analysed: {}\n", what_is_analysed(g, r)));
    if !r.has_unbalance {
        s.push_str(NO_UNBALANCE_LINE);
    }
    if r.family_dimension > 0 {
        s.push_str(&family_line(r, |w| speed_text(g, w)));
    }
    if let Rotor::Spatial(sr) = &g.rotor {
        if sr.gravity_across() && sr.planes.iter().any(|p| p.n >= 3) && r.points.iter().any(|p| p.verdict.is_some()) {
            s.push_str("gravity breaks the family of balanced states of 3 or more balls in a plane: the orbits have each such plane's balls in two groups (the member's angles in the JSON's member_psi); at each speed the orbit of least growth rate among those found from every split and its mirror is the one analysed, the others are in the JSON's points[].other_orbits (docs/notes/stability.md)\n");
        }
    }
    if let Rotor::Planar(_) = &g.rotor {
        // audit 25's F3: the eccentric race on supports that differ by direction breaks the
        // family as gravity does; the scan lists the other orbits it found
        let with: Vec<&autobal::rotor_stability::SpeedPoint> = r.points.iter().filter(|p| p.verdict.is_some() && !p.other_orbits.is_empty()).collect();
        if !with.is_empty() {
            let other = with.iter().filter(|p| p.other_orbits.iter().any(|o| Some(o.verdict) != p.verdict)).count();
            s.push_str(&format!(
                "an eccentric race on supports that differ by direction breaks the family of balanced states of 3 or more balls: the orbits have the balls in two groups (the member's angles in the JSON's member_psi); at each speed the orbit of least growth rate among those found from every split and its mirror is the one analysed, the others are in the JSON's points[].other_orbits: found at {} of {} speeds, {} (docs/notes/stability.md)\n",
                with.len(),
                r.points.len(),
                if other > 0 { format!("of another verdict than the one analysed at {other} of them (a run may sit near either; the analysed one is the stable one where one is)") } else { "of the same verdict".to_string() }
            ));
        }
    }
    s.push_str(&family_range_lines(r, |w| speed_text(g, w)));
    let partial: Vec<&autobal::rotor_stability::SpeedPoint> =
        r.points.iter().filter(|p| p.state == Some(autobal::rotor_stability::StateKind::PartiallyBalanced)).collect();
    if let (Some(a), Some(b)) = (partial.first(), partial.last()) {
        // on supports that differ by direction no closed form says where the planar rotor's
        // semi-balanced orbit exists: the balls were found at their capacity limit, no more
        let why = match &g.rotor {
            Rotor::Planar(p) if p.anisotropic() && p.s2 > 0.0 && p.n >= 2 => "the balls together at their capacity limit, the race centre off the axis; on supports that differ by direction no closed form says whether a semi-balanced orbit exists there: none was found from the scan's starts",
            _ => "the balls reduce the unbalance without cancelling it, a residual below 1: no balanced state exists (the balls' capacity falls short, a couple no plane can cancel, or, planar, below the speed where the semi-balanced state exists), or the state found is not the balanced one",
        };
        s.push_str(&format!(
            "partially balanced ({why}; a residual of {}: spatial and linear a fraction of the unbalance, planar the race centre's distance from the axis over its distance without the balls' resultant) at {} of {} speeds, {}: the verdicts there are the partially balanced state's\n",
            residual_range(&partial),
            partial.len(),
            r.points.len(),
            speed_span(|w| speed_text(g, w), a.omega, b.omega)
        ));
    }
    s.push_str(&residual_text(r, |w| speed_text(g, w)));
    s.push_str(&not_balanced_text(r, |w| speed_text(g, w)));
    let missing = r.points.iter().filter(|p| p.verdict.is_none()).count();
    let solved = r.points.len() - missing;
    if let Some(line) = stopped_before_first_speed(r) {
        s.push_str(line);
    } else if r.stable_ranges.is_empty() && solved == 0 {
        let analysed = r.points.iter().filter(|p| p.analysed).count();
        s.push_str(&format!(
            "no verdict: no stationary state was found at any of the {analysed} speeds analysed of {} in (0, {}]\n",
            r.points.len(),
            speed_text(g, analysed_span(r, omega_max))
        ));
    } else if r.stable_ranges.is_empty() {
        s.push_str(&format!(
            "stable: nowhere among the {solved} of {} speeds in (0, {}] where a stationary state was found\n",
            r.points.len(),
            speed_text(g, analysed_span(r, omega_max))
        ));
    } else {
        for st in &r.stable_ranges {
            let from = end_text(r, st, false, |w| speed_text(g, w));
            let to = end_text(r, st, true, |w| speed_text(g, w));
            s.push_str(&format!("{}: {from} to {to}\n", range_label(r, st)));
        }
    }
    let neutral = r.points.iter().filter(|p| p.verdict == Some(Verdict::Neutral)).count();
    if neutral > 0 {
        s.push_str(&format!(
            "neutral (the growth rate within the neutral tolerance of zero: undecided at that tolerance, not a verdict) at {neutral} of {} speeds\n",
            r.points.len()
        ));
    }
    s.push_str(&missing_lines(r, |w| speed_text(g, w)));
    s
}

/// The table's line for a scan stopped before its first speed, `None` otherwise: no range, no
/// "nowhere", no count of speeds without a state (review 23: "no stationary state was found at
/// any of the 0 speeds"). The general and linear routes' one rule.
pub(crate) fn stopped_before_first_speed(r: &RotorStability) -> Option<&'static str> {
    (r.points.is_empty() && r.cut_short()).then_some("no verdict: the scan stopped before its first speed\n")
}

/// The table's lines on the speeds without a verdict: those below the periodic-orbit floor as
/// not analysed ([`autobal::rotor_stability::SpeedPoint::analysed`]), apart from those where
/// no stationary state was found; each with the reason at its first speed, named as the
/// first's (the others' may differ: the JSON's `points[].failure` has each).
pub(crate) fn missing_lines(r: &RotorStability, speed: impl Fn(f64) -> String) -> String {
    let mut s = String::new();
    let n = r.points.len();
    for (analysed, what) in [(false, "not analysed (below the periodic-orbit floor)"), (true, "no stationary state found")] {
        let missing: Vec<_> = r.points.iter().filter(|p| p.verdict.is_none() && p.analysed == analysed).collect();
        if let Some(p) = missing.first() {
            let why = p.failure.clone().unwrap_or_default();
            s.push_str(&format!("{what} at {} of {n} speeds (the first, at {}: {why})\n", missing.len(), speed(p.omega)));
        }
    }
    s
}

/// The table's line for a rotor without unbalance ([`RotorStability::has_unbalance`]).
pub(crate) const NO_UNBALANCE_LINE: &str = "no unbalance to cancel (below 1e-6 of the balls' capacity Σ m R): the balanced state is the one where the balls' resultant vanishes; residuals are that resultant over the capacity\n";

/// The table's line on the family of balanced states (`r.family_dimension > 0`): which member
/// the verdicts are of, named at the first speed whose state has the family (a
/// (semi-)balanced point: a partially balanced point has none), or that no speed has one.
pub(crate) fn family_line(r: &RotorStability, speed: impl Fn(f64) -> String) -> String {
    let head = format!(
        "the balanced states form a family of dimension {} (the balls' positions are not unique); its {} zero eigenvalue(s) are structural and left out of the verdict",
        r.family_dimension, r.family_dimension
    );
    match r.points.iter().find(|p| p.family_dimension > 0) {
        Some(p) => format!(
            "{head}, which at each speed is that of the member reached from the closed form (at {}, the first speed with the family: ball angles {} rad)\n",
            speed(p.omega),
            p.member_psi.iter().map(|a| fmt_num(round(a.rem_euclid(std::f64::consts::TAU)))).collect::<Vec<_>>().join(", ")
        ),
        None => format!("{head}; no speed of the axis has a balanced state, so no member to name\n"),
    }
}

/// The family's lines of the table (`r.family`: its ranges where all the members sampled and
/// where at least one is stable, each end in the words of [`end_text`]); empty without a
/// family. `stability`'s and `critical`'s one text.
pub(crate) fn family_range_lines(r: &RotorStability, speed: impl Fn(f64) -> String) -> String {
    let Some(f) = &r.family else { return String::new() };
    let list = |v: &[autobal::analysis::StableRange]| {
        if v.is_empty() {
            "nowhere on the axis".to_string()
        } else {
            // each end in the words of the one member's ranges ("(end of the axis)", a grid
            // speed; audit 21's F8: the family's lines dropped them)
            v.iter().map(|st| format!("{} to {}", end_text(r, st, false, &speed), end_text(r, st, true, &speed))).collect::<Vec<_>>().join(", ")
        }
    };
    format!(
        "family ({}{}): all members sampled stable: {}\nfamily: at least one member sampled stable (some members, which is not \"stable\"): {}\n",
        f.parameterisation.split(':').next().unwrap_or(""),
        members_words(f),
        list(&f.all_members_stable),
        list(&f.some_members_stable)
    )
}

/// A stable range's label in the table: the states it covers ([`range_states`]: "not
/// balanced, stable", "partially balanced, stable" never read "stable"), on a family that its
/// verdicts are one member's; `stability`'s and `critical`'s one text.
pub(crate) fn range_label(r: &RotorStability, st: &autobal::analysis::StableRange) -> String {
    let kinds = range_states(r, st);
    if kinds.iter().any(|k| *k != "balanced" && *k != "semi-balanced") {
        format!("{}, stable", kinds.join(" then "))
    } else if r.family.is_some() {
        "stable (the one member per speed reached from the closed form)".to_string()
    } else {
        "stable".to_string()
    }
}

/// The states a stable range covers as the JSON's `points[].state` names them
/// ([`autobal::rotor_stability::StateKind::key`]), in order, each once in a row
/// ([`range_states`]' points).
pub(crate) fn range_state_keys(r: &RotorStability, st: &autobal::analysis::StableRange) -> Vec<&'static str> {
    let mut k: Vec<&str> = range_points(r, st).filter_map(|p| p.state.map(|k| k.key())).collect();
    k.dedup();
    k
}

/// The points of a stable range: stable, within its ends (not a switch end's grid speed, whose
/// state is another).
fn range_points<'a>(r: &'a RotorStability, st: &'a autobal::analysis::StableRange) -> impl Iterator<Item = &'a autobal::rotor_stability::SpeedPoint> {
    r.points.iter().filter(|p| p.omega >= st.from && p.omega <= st.to && p.abscissa.is_some_and(|a| a < 0.0))
}

/// The names of the states a stable range covers, in order, each once in a row: its own
/// points (stable: not a switch end's grid speed, whose state is another).
pub(crate) fn range_states(r: &RotorStability, st: &autobal::analysis::StableRange) -> Vec<&'static str> {
    let mut k: Vec<&str> = range_points(r, st).filter_map(|p| p.state.map(|k| k.name())).collect();
    k.dedup();
    k
}

/// A stable range as JSON: its ends, whether each is a located boundary or a switch of state;
/// each command adds its units (`from_rpm`, `from_si`, ...).
pub(crate) fn stable_range_json(s: &autobal::analysis::StableRange) -> Value {
    json!({ "from": s.from, "to": s.to, "from_is_boundary": s.from_is_boundary, "to_is_boundary": s.to_is_boundary, "from_is_switch": s.from_is_switch, "to_is_switch": s.to_is_switch })
}

/// The end of the span a scan covered: `omega_max`, or where a stopped scan's last point is
/// (review 23: "nowhere in (0, 864 rad/s]" after 179 speeds that reached 0.155 rad/s).
pub(crate) fn analysed_span(r: &RotorStability, omega_max: f64) -> f64 {
    match r.points.last() {
        Some(p) if r.cut_short() => p.omega,
        _ => omega_max,
    }
}

/// A stable range's end in words ([`range_end`]), or, where the scan's state switches there
/// to another stationary state with the other verdict
/// ([`autobal::analysis::StableRange::from_is_switch`]), that it is such a switch and no
/// change of stability.
pub(crate) fn end_text(r: &RotorStability, st: &autobal::analysis::StableRange, upper: bool, speed: impl Fn(f64) -> String) -> String {
    let (w, located, switch) = if upper { (st.to, st.to_is_boundary, st.to_is_switch) } else { (st.from, st.from_is_boundary, st.from_is_switch) };
    if switch {
        return format!(
            "{} (a switch of state, not a change of stability: {} it the scan's start reaches another stationary state, with the other verdict; the state of this range may exist and stay stable {} it)",
            speed(w),
            if upper { "above" } else { "below" },
            if upper { "above" } else { "below" }
        );
    }
    range_end(r, w, located, upper, speed)
}

/// A stable range's end in words: a located boundary as its speed; else a grid speed, the
/// axis' start or end, or one next to a speed where no stationary state was found (the range
/// stops at its last analysed speed: nothing is known beyond it).
pub(crate) fn range_end(r: &RotorStability, w: f64, located: bool, upper: bool, speed: impl Fn(f64) -> String) -> String {
    if located {
        return speed(w);
    }
    let i = r.points.iter().position(|p| p.omega == w);
    let next = i.and_then(|i| if upper { r.points.get(i + 1) } else { i.checked_sub(1).map(|j| &r.points[j]) });
    match next {
        // a stopped scan's last point is where it stopped (review 23: "(end of the axis)")
        None if upper && r.cut_short() => format!("{} (the last speed analysed: the scan stopped there)", speed(w)),
        None => format!("{} ({} of the axis)", speed(w), if upper { "end" } else { "start" }),
        Some(p) if p.verdict.is_none() => {
            let what = if p.analysed { "no stationary state found" } else { "not analysed (below the periodic-orbit floor)" };
            format!("{} (a grid speed: {what} at {} {} it)", speed(w), speed(p.omega), if upper { "above" } else { "below" })
        }
        Some(_) => format!("{} (a grid speed: the end was not located)", speed(w)),
    }
}

/// The margin over speed as a plot: the spectral abscissa (or largest Floquet exponent) of the
/// stationary state, stable ranges shaded.
pub fn margin_plot(g: &GeneralRotor, r: &RotorStability, omega_max: f64) -> Plot {
    let pts: Vec<(f64, f64)> = r.points.iter().filter_map(|p| p.abscissa.map(|a| (p.omega, a))).collect();
    let lo = pts.iter().map(|p| p.1).fold(0.0, f64::min);
    let hi = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    let pad = 0.1 * (hi - lo).max(1e-6);
    let shades = r.stable_ranges.iter().map(|s| Shade { x: (s.from, s.to), y: (None, Some(0.0)), color: "#009E73".into() }).collect();
    let rate = if g.si { "1/s" } else { "per unit τ" };
    Plot {
        title: format!(
            "Stability margin of the {} over speed (general route)",
            if r.kind == Kind::PeriodicOrbit { "stationary orbit" } else { "balanced state" }
        ),
        x_label: if g.si { "speed ω (rad/s)".into() } else { "speed Ω".into() },
        y_label: format!("{} ({rate}; < 0: stable)", if r.kind == Kind::PeriodicOrbit { "largest Floquet exponent" } else { "max Re λ" }),
        series: vec![Series::new("margin", pts, PALETTE[1])],
        shades,
        shade_legend: vec![("#009E73".into(), "exactly stable (shaded below 0)".into())],
        x_range: Some((0.0, omega_max)),
        y_range: Some((lo - pad, hi + pad)),
        ..Default::default()
    }
}

/// The number of speeds of the general route's grid when none is given: 200, or 50 for a
/// periodic orbit (a shooting with the variational equations over a revolution per speed).
pub fn default_samples(g: &GeneralRotor) -> usize {
    if g.rotor.is_periodic() {
        50
    } else {
        200
    }
}

/// The end of the general route's speed axis when none is given, in the rotor's units (rad/s;
/// the papers' units for a dimensionless config): 3 times the
/// planar rotor's natural frequency; for a spatial rotor `analysis.omega_max` if given, else
/// twice paper 000's automatic axis (it covers the 12-state model's critical speeds; a second
/// plane, supports that differ by direction or gravity move the modes), extended to cover the
/// operating speed.
pub fn default_omega_max(g: &GeneralRotor, root: &Table) -> Result<f64> {
    Ok(match &g.rotor {
        Rotor::Planar(_) | Rotor::Linear(_) => 3.0 * g.rotor.natural_frequency(),
        Rotor::Spatial(_) => {
            let cfg = autobal::config::spatial(root)?;
            cfg.analysis.speed_axis_max(2.0 * autobal::reports::default_omega_max(&cfg.model)) * g.omega0
        }
    })
}

/// The general route's verdict at the config's operating speed (`analysis.operating_speed`,
/// spatial configs): the stationary state solved at the speed itself (at 9 speeds across an
/// operating range) as the scan solves each grid speed, and the scan's stable range that
/// holds it.
#[derive(Debug, Clone)]
pub struct Operating {
    /// The operating speed `[lo, hi]` in the rotor's units (rad/s, or Ω).
    pub omega: [f64; 2],
    /// The speeds solved there (one, or 9 across a range).
    pub points: Vec<autobal::rotor_stability::SpeedPoint>,
    /// The scan's stable range that holds the whole operating speed, if one does.
    pub range: Option<autobal::analysis::StableRange>,
    /// Why the verdict stopped before its end (Ctrl-C, a budget), `None` where it is complete:
    /// `points` then holds the speeds solved before the stop ([`Operating::stopped_message`]).
    pub stopped: Option<autobal::control::StopReason>,
}

/// The speeds solved across an operating range `[lo, hi]` (one at a single speed).
const OPERATING_RANGE_SPEEDS: usize = 9;

impl Operating {
    /// The speeds the verdict solves: one, or [`OPERATING_RANGE_SPEEDS`] across a range.
    fn planned(&self) -> usize {
        if self.omega[0] == self.omega[1] {
            1
        } else {
            OPERATING_RANGE_SPEEDS
        }
    }

    /// Whether the verdict stopped before it solved every one of its speeds.
    fn cut_short(&self) -> bool {
        self.stopped.is_some() && self.points.len() < self.planned()
    }

    /// The verdict over the speeds solved there: stable where every one is, unstable where one
    /// is, else neutral (stable or neutral everywhere, neutral somewhere); `None` where a speed
    /// has no state. Stopped before its last speed: unstable where a speed solved is (the
    /// others cannot make it stable), else `None`.
    pub fn verdict(&self) -> Option<Verdict> {
        let v: Option<Vec<Verdict>> = self.points.iter().map(|p| p.verdict).collect();
        let v = v?;
        if self.cut_short() {
            return v.contains(&Verdict::Unstable).then_some(Verdict::Unstable);
        }
        Some(if v.iter().all(|x| *x == Verdict::Stable) {
            Verdict::Stable
        } else if v.contains(&Verdict::Unstable) {
            Verdict::Unstable
        } else {
            Verdict::Neutral
        })
    }

    /// The largest growth rate (`abscissa`) over the speeds solved there.
    fn max_growth_rate(&self) -> f64 {
        self.points.iter().filter_map(|p| p.abscissa).fold(f64::NEG_INFINITY, f64::max)
    }
}

/// A spatial config's `analysis.operating_speed` `[lo, hi]` in the rotor's units (rad/s, or Ω),
/// else `None` (a planar config has none).
pub fn operating_speed(g: &GeneralRotor, root: &Table) -> Result<Option<[f64; 2]>> {
    if !autobal::config::is_spatial(root) {
        return Ok(None);
    }
    Ok(autobal::config::spatial(root)?.analysis.operating_speed.map(|[lo, hi]| [lo * g.omega0, hi * g.omega0]))
}

/// [`Operating`] for a config with `analysis.operating_speed`, else `None`.
pub fn operating(g: &GeneralRotor, root: &Table, r: &RotorStability, control: &Control) -> Result<Option<Operating>> {
    let Some(op) = operating_speed(g, root)? else { return Ok(None) };
    operating_at(g, op, "analysis.operating_speed", r, control).map(Some)
}

/// The verdict at the operating speed `omega` (`[lo, hi]`, the rotor's units; a linear rotor's
/// `linear_rotor.operating_speed` in rad/s): the stationary state solved at the speed itself, or
/// at 9 speeds across a range, with the stable range of the scan `r` that holds it. A speed
/// below the periodic-orbit floor is an error naming `key` (the config's key), with the units.
pub fn operating_at(g: &GeneralRotor, omega: [f64; 2], key: &str, r: &RotorStability, control: &Control) -> Result<Operating> {
    let speeds: Vec<f64> = if omega[0] == omega[1] { vec![omega[0]] } else { (0..9).map(|i| omega[0] + (omega[1] - omega[0]) * i as f64 / 8.0).collect() };
    let scan =
        autobal::rotor_stability::stability_over_speed_with(&g.rotor, &speeds, control).map_err(|e| match (&e, g.rotor.below_periodic_floor(omega[1])) {
            // the library names its grid's `omega_max`; here the grid is the operating speed
            (autobal::Error::InvalidParameter { field, .. }, Some(f)) if field == "omega_max" => {
                autobal::Error::invalid(key, autobal::rotor_stability::below_floor_words(&speed_text(g, omega[1]), &speed_text(g, f))).into()
            }
            _ => anyhow::Error::from(e),
        })?;
    // stopped (Ctrl-C, a budget): the speeds solved until then are kept, and said
    // (`stopped_message`; it was an error, "nothing is printed", after a complete scan)
    let range = r.stable_ranges.iter().find(|st| st.from <= omega[0] && omega[1] <= st.to).cloned();
    Ok(Operating { omega, points: scan.value.points, range, stopped: scan.stopped })
}

impl Operating {
    /// Why a stopped verdict is incomplete and what it kept, after a complete scan: `None`
    /// where the verdict is complete. "interrupted: the scan is complete; the verdict at the
    /// operating speed stopped after 3 of 9 speeds solved there (kept: JSON
    /// operating.points): no verdict", or "NOT STABLE" where a speed solved is unstable; all
    /// speeds solved, the stop came after them (locating a boundary between them, or following their family).
    pub fn stopped_message(&self) -> Option<String> {
        let why = self.stopped?;
        let (k, n) = (self.points.len(), self.planned());
        Some(if k < n {
            let decided = if self.verdict().is_some() { "NOT STABLE, a speed solved is unstable" } else { "no verdict" };
            format!("{why}: the scan is complete; the verdict at the operating speed stopped after {k} of {n} speeds solved there (kept: JSON operating.points): {decided}")
        } else {
            format!("{why}: the scan is complete, and the verdict at the operating speed at its {n} speeds; the stop came after them (while a stability boundary between them was located or their family of balanced states followed)")
        })
    }
}

/// [`Operating`] as JSON: `omega` (`[lo, hi]`, the rotor's units), `stable` (every speed
/// solved there stable), `verdict` (`stable`, `unstable` where one speed is, else `neutral`;
/// `null` where a speed has no state), `max_growth_rate` (the largest `abscissa` there; `null` where no
/// state was found), `stable_range` (`{from, to}` of the scan, or `null`), `points` (as the
/// scan's); stopped before its end (Ctrl-C, a budget), also `complete: false` and `stopped`
/// ([`Operating::stopped_message`]), its `points` the speeds solved, `verdict` `unstable` where
/// one of them is, else `null`, and `max_growth_rate` over them.
pub fn operating_json(op: &Operating) -> Value {
    let verdict = op.verdict();
    let v = json!({
        "omega": op.omega,
        "stable": verdict == Some(Verdict::Stable),
        "verdict": verdict.map(Verdict::name),
        "max_growth_rate": if verdict.is_some() { json!(op.max_growth_rate()) } else { Value::Null },
        "stable_range": op.range.as_ref().map_or(Value::Null, |st| json!({"from": st.from, "to": st.to})),
        "points": op.points,
    });
    crate::stability::mark_json(v, &op.stopped_message())
}

/// The first line of the general route's table at the operating speed: STABLE only where
/// every speed solved there is stable (exact: the eigenvalues or Floquet multipliers of the
/// state found), with the scan's stable range that holds it.
pub fn operating_line(g: &GeneralRotor, r: &RotorStability, op: &Operating) -> String {
    let line = operating_verdict_line(g, r, op);
    format!("{line}{}", other_orbits_line(g, op))
}

/// The other periodic orbits found at the operating speed (under gravity across the axis with
/// 3 or more balls in a plane), or the other partially balanced equilibria
/// ([`autobal::rotor_stability::Rotor::partial_states`]),
/// [`autobal::rotor_stability::SpeedPoint::other_orbits`], as one
/// line: each orbit's ball angles and verdict at a single operating speed, or over an operating
/// range how many of its speeds have one and whether any is stable; empty where none was found.
fn other_orbits_line(g: &GeneralRotor, op: &Operating) -> String {
    let with: Vec<&autobal::rotor_stability::SpeedPoint> = op.points.iter().filter(|p| !p.other_orbits.is_empty()).collect();
    let Some(first) = with.first() else { return String::new() };
    let per = if g.si { " 1/s" } else { "" };
    let stable_too = "; a run may settle on a stable one of these instead (its start decides)";
    // under gravity the periodic orbits of the groups' placements; without a periodic motion
    // the partially balanced equilibria of each start (Rotor::partial_states)
    let what = if g.rotor.is_periodic() { "periodic orbits" } else { "partially balanced states" };
    if op.omega[0] == op.omega[1] {
        let list: Vec<String> = first
            .other_orbits
            .iter()
            .map(|o| {
                let psi: Vec<String> = o.member_psi.iter().map(|a| fmt_num(round(a.rem_euclid(std::f64::consts::TAU)))).collect();
                format!("balls at {} rad ({}, growth rate {}{per})", psi.join(", "), o.verdict.name(), fmt_num(o.abscissa))
            })
            .collect();
        let any_stable = first.other_orbits.iter().any(|o| o.verdict == Verdict::Stable);
        format!("  other {what} at this speed (beside the one analysed): {}{}\n", list.join("; "), if any_stable { stable_too } else { "" })
    } else {
        let stable = with.iter().filter(|p| p.other_orbits.iter().any(|o| o.verdict == Verdict::Stable)).count();
        format!(
            "  other {what} found at {} of the {} speeds solved there (JSON operating.points[].other_orbits), {}\n",
            with.len(),
            op.points.len(),
            // (it read "a stable one at 0" where none is)
            if stable > 0 { format!("a stable one at {stable} of them{stable_too}") } else { "none of them stable".to_string() }
        )
    }
}

/// [`operating_line`]'s verdict.
fn operating_verdict_line(g: &GeneralRotor, r: &RotorStability, op: &Operating) -> String {
    let at = if op.omega[0] == op.omega[1] { speed_text(g, op.omega[0]) } else { format!("{} to {}", speed_text(g, op.omega[0]), speed_text(g, op.omega[1])) };
    let failure = op.points.iter().find_map(|p| p.verdict.is_none().then_some(p.failure.as_deref())).flatten();
    // stopped before its last speed (its words: `stopped_message`, on the INCOMPLETE line)
    let cut = op.cut_short().then(|| format!("stopped after {} of {} speeds solved there", op.points.len(), op.planned()));
    let Some(verdict) = op.verdict() else {
        let why = match (&cut, failure) {
            (Some(cut), None) => cut.clone(),
            (cut, failure) => format!("{}{}", failure.unwrap_or("no stationary state found"), cut.as_ref().map_or(String::new(), |c| format!("; {c}"))),
        };
        return format!("operating speed {at}: no verdict: {why}\n");
    };
    let per = if g.si { " 1/s" } else { " (per unit τ)" };
    let how = if g.rotor.is_periodic() { "Floquet multipliers" } else { "eigenvalues" };
    let mut kinds: Vec<&str> = op.points.iter().filter_map(|p| p.state.map(|k| k.name())).collect();
    kinds.dedup();
    let state = if kinds.is_empty() { "stationary".to_string() } else { kinds.join(" then ") };
    let member = if op.points.iter().any(|p| p.family_dimension > 0) { ", the member reached from the closed form" } else { "" };
    let rate = format!("largest growth rate {}{per}{}", fmt_num(op.max_growth_rate()), e_folding(op.max_growth_rate(), g.si));
    let range = |st: &autobal::analysis::StableRange| {
        let from = end_text(r, st, false, |w| speed_text(g, w));
        let to = end_text(r, st, true, |w| speed_text(g, w));
        format!("{from} to {to}")
    };
    match verdict {
        Verdict::Stable => {
            let range = op.range.as_ref().map_or_else(
                || match (r.points.first(), r.points.last()) {
                    // the operating speed off the scan's axis (an --omega-max below it): no
                    // grid speed there, so no range of the scan can hold it
                    (Some(a), Some(b)) if op.omega[0] > b.omega || op.omega[1] < a.omega => format!(
                        " (outside the scan's speed axis, {} to {}: no stable range of the scan can hold it; an axis that reaches it, e.g. a larger --omega-max, gives its range)",
                        speed_text(g, a.omega),
                        speed_text(g, b.omega)
                    ),
                    // stable at the speed itself, but no grid speed of the scan round it was:
                    // the grid is too coarse for the window the operating speed sits in
                    _ => " (the scan's grid found no stable range round it: a narrower window than its spacing; more --samples resolve it)".to_string(),
                },
                |st| format!(" in the stable range {}", range(st)),
            );
            format!("operating speed {at}: the {state} state is STABLE (exact, {how}{member}){range}; {rate}\n")
        }
        // stable or neutral everywhere, neutral somewhere: the growth rate within the neutral
        // tolerance of zero (a tolerance-dependent outcome, not a verdict)
        Verdict::Neutral => format!(
            "operating speed {at}: the {state} state is NEUTRAL (its growth rate within the neutral tolerance of zero: undecided at that tolerance, not a verdict; {how}{member}); {rate}\n"
        ),
        Verdict::Unstable => {
            // the scan's stable range nearest to the operating speed, as the closed-form route says
            let dist = |st: &&autobal::analysis::StableRange| if st.to < op.omega[0] { op.omega[0] - st.to } else { (st.from - op.omega[1]).max(0.0) };
            let near = r.stable_ranges.iter().min_by(|a, b| dist(a).total_cmp(&dist(b))).map_or_else(|| "no stable range on the axis".to_string(), |st| format!("nearest stable range {}", range(st)));
            // stopped: decided by a speed solved before the stop, its rate a lower bound
            let cut = cut.map_or(String::new(), |c| format!(" ({c}: one of them is unstable, the rate is theirs)"));
            format!("operating speed {at}: the {state} state is NOT STABLE (exact, {how}{member}){cut}; {rate}; {near}\n")
        }
    }
}

/// The time a growth rate `σ` takes to change a disturbance by the factor e, `1/|σ|`, as
/// " (a disturbance decays by e in 1.89 h at the slowest)" or " (grows by e in 0.023 s)": the
/// margin of a verdict read as a time (a stable periodic orbit's slowest exponent under gravity
/// is ~1e-4 1/s, hours). In seconds, minutes, hours or days where `si`, else in units of
/// `τ = ω0 t`; empty for a rate that is zero or not finite.
pub(crate) fn e_folding(rate: f64, si: bool) -> String {
    if !rate.is_finite() || rate == 0.0 {
        return String::new();
    }
    let t = 1.0 / rate.abs();
    let sig = |v: f64| fmt_num(crate::num::round_sig(v, 3).unwrap_or(v));
    let time = if !si {
        format!("{} units of τ", sig(t))
    } else if t < 120.0 {
        format!("{} s", sig(t))
    } else if t < 5400.0 {
        format!("{} min", sig(t / 60.0))
    } else if t < 172_800.0 {
        format!("{} h", sig(t / 3600.0))
    } else {
        format!("{} days", sig(t / 86_400.0))
    };
    if rate < 0.0 {
        format!(" (a disturbance decays by the factor e in {time} at the slowest)")
    } else {
        format!(" (a disturbance grows by the factor e in {time})")
    }
}

/// `a to b`, or `a` where both ends are one speed.
fn speed_span(speed: impl Fn(f64) -> String, a: f64, b: f64) -> String {
    if a == b {
        speed(a)
    } else {
        format!("{} to {}", speed(a), speed(b))
    }
}

/// The range `a to b` (or `a`) of the points' residuals (fraction of the unbalance,
/// [`autobal::rotor_stability::SpeedPoint::residual`]), to 3 significant digits.
pub(crate) fn residual_range(points: &[&autobal::rotor_stability::SpeedPoint]) -> String {
    let (lo, hi) = points.iter().filter_map(|p| p.residual).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !(lo <= hi) {
        return "unknown size".into();
    }
    let f = |v: f64| fmt_num(crate::num::round_sig(v, 3).unwrap_or(v));
    if f(lo) == f(hi) {
        f(lo)
    } else {
        format!("{} to {}", f(lo), f(hi))
    }
}

/// The line of `stability`'s table where balanced states carry a residual above the exact
/// tolerance (1e-6 of the unbalance): on a periodic orbit the balls swing once a revolution and
/// cancel the unbalance on average but for the swing's second order
/// ([`autobal::rotor_stability::Rotor::residual`]), and how many more are balanced to within
/// 1e-6 (the table's lines count every speed); empty where every balanced state is balanced to
/// within 1e-6.
pub(crate) fn residual_text(r: &autobal::rotor_stability::RotorStability, speed: impl Fn(f64) -> String) -> String {
    let with: Vec<_> =
        r.points.iter().filter(|p| p.state == Some(autobal::rotor_stability::StateKind::Balanced) && p.residual.is_some_and(|v| v > 1e-6)).collect();
    let (Some(a), Some(b)) = (with.first(), with.last()) else { return String::new() };
    let why = if r.kind == Kind::PeriodicOrbit {
        "the balls swing once a revolution and cancel the unbalance on average but for the swing's second order; the rotor whirls once a revolution about its sag as that residual makes it"
    } else {
        "the balls do not cancel the unbalance exactly"
    };
    // the other balanced speeds, so that the lines' counts add up to the speeds analysed
    let exact = r.points.iter().filter(|p| p.state == Some(autobal::rotor_stability::StateKind::Balanced) && !p.residual.is_some_and(|v| v > 1e-6)).count();
    let rest = if exact > 0 { format!("; balanced to within 1e-6 at {exact} more") } else { String::new() };
    format!(
        "balanced to a residual of {} {} (above the exact tolerance 1e-6; on a periodic orbit up to 0.05 is balanced, as in `simulate`, at an equilibrium only 1e-6) at {} of {} speeds, {} ({why}){rest}\n",
        residual_range(&with),
        r.residual_scale.words(),
        with.len(),
        r.points.len(),
        speed_span(&speed, a.omega, b.omega)
    )
}

/// The line of `stability`'s table where the state analysed is not balanced
/// ([`autobal::rotor_stability::StateKind::NotBalanced`]: a balanced state exists, but the balls
/// of this one leave more than the tolerance of the unbalance (at an equilibrium 1e-6, there
/// they rest on the line of a whirl; on a periodic orbit 0.05, `simulate`'s)), with its speeds and residuals;
/// empty where there is none.
pub(crate) fn not_balanced_text(r: &autobal::rotor_stability::RotorStability, speed: impl Fn(f64) -> String) -> String {
    let nb: Vec<_> = r.points.iter().filter(|p| p.state == Some(autobal::rotor_stability::StateKind::NotBalanced)).collect();
    let (Some(a), Some(b)) = (nb.first(), nb.last()) else { return String::new() };
    format!(
        "not balanced (the balls leave a residual of {}{}{}) at {} of {} speeds, {}: the verdicts there are that state's, not the balanced state's\n",
        residual_range(&nb),
        match r.residual_scale {
            autobal::rotor_stability::ResidualScale::Capacity if r.has_unbalance => " of their capacity (the unbalance a couple they cannot measure)",
            autobal::rotor_stability::ResidualScale::Capacity => " of their capacity, with no unbalance to cancel",
            autobal::rotor_stability::ResidualScale::Unbalance => " of the unbalance",
            autobal::rotor_stability::ResidualScale::StaticUnbalance => " of the static unbalance",
            autobal::rotor_stability::ResidualScale::RaceOffset => " of the race centre's offset without the balls",
        },
        if r.kind == Kind::PeriodicOrbit { "" } else { ": at rest on the line of the whirl" },
        nb.len(),
        r.points.len(),
        speed_span(&speed, a.omega, b.omega)
    )
}

/// The library's `omega_max` refusal of a grid below the periodic-orbit floor, its numbers
/// written with their unit (`speed_text`: rad/s and rpm, or `Ω`): the grid's top speed
/// (where the floor is taken) and the floor there; other errors as they are.
pub fn floor_in_units(g: &GeneralRotor, e: autobal::Error, speeds: &[f64]) -> anyhow::Error {
    let top = speeds.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    match (&e, g.rotor.below_periodic_floor(top)) {
        (autobal::Error::InvalidParameter { field, .. }, Some(f)) if field == "omega_max" => {
            let words = autobal::rotor_stability::below_floor_words(&format!("{}, the grid's top speed,", speed_text(g, top)), &speed_text(g, f));
            autobal::Error::invalid("omega_max", words).into()
        }
        _ => e.into(),
    }
}

/// The library's `omega_max` error (a top speed below what the periodic-orbit analysis
/// resolves, [`autobal::rotor_stability::Rotor::periodic_floor`]) named as the user gave the
/// speed: `--omega-max` where `flag_set`, else the config's key `key` (`analysis.omega_max`,
/// `linear_rotor.omega_max`) where `root` has it; where neither gave it, the axis's top is the
/// default ([`default_omega_max`]) and the message names what raised the floor above it, the
/// key of the stiffest support where one key sets the fastest natural frequency (a planar
/// rotor's `planar.k_y = 1e13` was reported as `analysis.omega_max`, a key a planar config may
/// not hold), else `--omega-max`; `stability`, `campbell` and `critical` alike.
pub fn name_omega_max(e: anyhow::Error, flag_set: bool, key: &str, root: &Table, g: &GeneralRotor) -> anyhow::Error {
    match e.downcast_ref::<autobal::Error>() {
        Some(autobal::Error::InvalidParameter { field, reason }) if field == "omega_max" => {
            let (table, k) = key.split_once('.').unwrap_or(("", key));
            let key_given = root.get(table).and_then(|t| t.get(k)).is_some();
            if flag_set {
                autobal::Error::invalid("--omega-max", reason.clone()).into()
            } else if key_given {
                autobal::Error::invalid(key, reason.clone()).into()
            } else {
                default_below_floor(g, root)
                    .unwrap_or_else(|| match floor_cause(g, root) {
                        // a linear rotor's default axis is its own: the key that raised the floor
                        // named before the library's words
                        (field, Some(cause)) => {
                            autobal::Error::invalid(field, format!("{cause} raises the floor: the default speed axis's {reason}; give --omega-max above it"))
                        }
                        (_, None) => autobal::Error::invalid("--omega-max", format!("not given: the default speed axis's {reason}")),
                    })
                    .into()
            }
        }
        _ => e,
    }
}

/// The error of a default speed axis ([`default_omega_max`]: no `--omega-max`, no config key)
/// whose top lies below the periodic-orbit floor: naming what raised the floor where one key
/// did ([`floor_cause`]), both speeds with their unit. `None` where there is no such floor.
fn default_below_floor(g: &GeneralRotor, root: &Table) -> Option<autobal::Error> {
    // (a linear rotor's default axis is its own, `crate::linear_rotor::default_omega_max`)
    if matches!(g.rotor, Rotor::Linear(_)) {
        return None;
    }
    let top = default_omega_max(g, root).ok()?;
    let floor = g.rotor.periodic_floor(top)?;
    let wn = g.rotor.fastest_natural_frequency(top);
    let (field, cause) = floor_cause(g, root);
    let cause = cause.unwrap_or_else(|| format!("not given: the fastest natural frequency, {},", speed_text(g, wn)));
    Some(autobal::Error::invalid(
        field,
        format!(
            "{cause} puts the slowest speed the periodic-orbit analysis resolves at {} (a revolution spans at most {} of its periods), above the speed axis's default top {} ({}): give --omega-max above it",
            speed_text(g, floor),
            fmt_num(autobal::rotor_stability::PERIODS_PER_REVOLUTION),
            speed_text(g, top),
            default_top_words(g)
        ),
    ))
}

/// How [`default_omega_max`] sets the axis's top, for messages.
fn default_top_words(g: &GeneralRotor) -> String {
    match &g.rotor {
        Rotor::Planar(_) | Rotor::Linear(_) => "3 times the slowest natural frequency".into(),
        Rotor::Spatial(_) => "twice the linear model's automatic axis".into(),
    }
}

/// The config key that sets the fastest natural frequency (and so the periodic-orbit floor,
/// [`autobal::rotor_stability::Rotor::periodic_floor`]), and words saying how, where one key
/// does; else `--omega-max` and `None`. One rule for every rotor, the messages of a default
/// speed axis below the floor ([`default_below_floor`], [`name_omega_max`]):
/// - planar: the stiffer direction's key, `sqrt(k/m0)` (`planar.k_y`; `planar.k` where one
///   stiffness holds for both);
/// - spatial, one plane or two (a dimensional config's `[supports]`): the stiffest support in
///   the stiffer direction, `supports.stiffness_right_y` (the x key where its `_y` twin is not
///   given, as it then sets both directions);
/// - linear: the bearing without which the fastest natural frequency (at rest) falls to half
///   or less, the one it falls most without (`linear_rotor.bearings[0].k`; a table's `kxx` or
///   `kyy`, the stiffer at rest): that key holds the floor up. Its own `sqrt(k/M_dd)` over
///   its node's mass would not tell: the consistent mass lets the neighbours swing against
///   the node, so the bearing's mode is faster than that, by ~2 on the shaft example's end
///   node at 1e13 N/m, and half of the fastest frequency missed it. Only on the full model: a
///   reduction (`linear_rotor.modes`) renumbers the nodes and makes the interior modal, so a
///   bearing's node may have no DOF of its own there.
///
/// Gravity or supports that differ by direction make the stationary state a periodic orbit,
/// and so make the floor apply; its height is the stiffness's.
fn floor_cause(g: &GeneralRotor, root: &Table) -> (String, Option<String>) {
    let none = || ("--omega-max".to_string(), None);
    let wn = g.rotor.fastest_natural_frequency(0.0);
    match &g.rotor {
        Rotor::Planar(p) => {
            let (kx, ky) = p.stiffness_xy();
            let (key, k) = match p.k_y {
                None => ("k", kx),
                Some(_) if ky >= kx => ("k_y", ky),
                Some(_) => ("k_x", kx),
            };
            let wn = (k / p.total_mass()).sqrt();
            (format!("planar.{key}"), Some(format!("{} N/m, through the fastest natural frequency sqrt({key}/m0) = {},", fmt_num(k), speed_text(g, wn))))
        }
        Rotor::Spatial(s) if g.si && s.supports.len() == 2 && root.contains_key("supports") => {
            // the stiffest (support, direction); x first, so an isotropic support names its x key
            let Some((side, dir, k)) = s
                .supports
                .iter()
                .zip(["left", "right"])
                .flat_map(|(sp, side)| [(side, 0, sp.stiffness[0]), (side, 1, sp.stiffness[1])])
                .reduce(|a, b| if b.2 > a.2 { b } else { a })
            else {
                return none();
            };
            let y_key = format!("stiffness_{side}_y");
            let key = if dir == 1 && root.get("supports").and_then(|t| t.get(&y_key)).is_some() { y_key } else { format!("stiffness_{side}") };
            let along = ["x", "y"][dir];
            (
                format!("supports.{key}"),
                Some(format!("{} N/m, the stiffest support (along {along}), through the fastest natural frequency {},", fmt_num(k), speed_text(g, wn))),
            )
        }
        Rotor::Linear(r) if root.get("linear_rotor").and_then(|t| t.get("modes")).and_then(|v| v.as_integer()).is_none_or(|m| m <= 0) => {
            let Some(bearings) = root.get("linear_rotor").and_then(|t| t.get("bearings")).and_then(|v| v.as_array()) else { return none() };
            let n = r.dofs();
            let num = |v: Option<&toml::Value>| v.and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)));
            let node_of = |v: Option<&toml::Value>| v.and_then(|v| v.as_integer()).and_then(|v| usize::try_from(v).ok()).filter(|&v| v < r.nodes);
            // the fastest natural frequency without each bearing: (key, node, stiffness, it);
            // the tables in the config's order are the rotor's `speed_bearings`
            let mut without: Vec<(String, usize, f64, f64)> = vec![];
            let mut t = 0;
            for (i, b) in bearings.iter().enumerate() {
                let Some(node) = node_of(b.get("node")) else { continue };
                let mut rest = r.clone();
                let (key, k) = if b.get("speeds").is_some() {
                    if t >= rest.speed_bearings.len() {
                        continue;
                    }
                    let (k, _) = rest.speed_bearings.remove(t).at(0.0);
                    t += 1;
                    let y = if b.get("kyy").is_some() { "kyy" } else { "kxx" };
                    if k[3] > k[0] {
                        (format!("linear_rotor.bearings[{i}].{y}"), k[3])
                    } else {
                        (format!("linear_rotor.bearings[{i}].kxx"), k[0])
                    }
                } else if let Some(k) = num(b.get("k")) {
                    // K less the bearing's block, along x and y, to ground or to its link
                    let (x, y, _) = rest.node_dofs(node);
                    let link = node_of(b.get("link")).map(|l| rest.node_dofs(l));
                    for (d, i) in [x, y].into_iter().enumerate() {
                        rest.k[i * n + i] -= k;
                        if let Some((lx, ly, _)) = link {
                            let j = [lx, ly][d];
                            rest.k[j * n + j] -= k;
                            rest.k[i * n + j] += k;
                            rest.k[j * n + i] += k;
                        }
                    }
                    (format!("linear_rotor.bearings[{i}].k"), k)
                } else {
                    continue;
                };
                without.push((key, node, k, Rotor::Linear(rest).fastest_natural_frequency(0.0)));
            }
            // the bearing without which the fastest natural frequency falls most, named where
            // it falls to half or less
            match without.into_iter().filter(|b| b.3.is_finite()).reduce(|a, b| if b.3 < a.3 { b } else { a }) {
                Some((key, node, k, w)) if w <= 0.5 * wn => (
                    key,
                    Some(format!(
                        "{} N/m at node {node}, through the fastest natural frequency {} ({} without this bearing),",
                        fmt_num(k),
                        speed_text(g, wn),
                        speed_text(g, w)
                    )),
                ),
                _ => none(),
            }
        }
        _ => none(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The error of `stability`, `critical` and `campbell` on `root` without `--omega-max`.
    fn default_axis_errors(root: &Table) -> [String; 3] {
        use crate::command::Command;
        let src = || crate::command::ConfigSource::tables(root.clone(), "test");
        let e = |r: Result<()>| r.err().map_or("not refused".to_string(), |e| format!("{e:#}"));
        [
            e(crate::stability::Args { config: src(), samples: Some(10), ..Default::default() }.run(&Control::none()).map(|_| ())),
            e(crate::critical::Args { config: src(), route: crate::command::Route::Auto, omega_max: None }.run(&Control::none()).map(|_| ())),
            e(crate::campbell::Args { config: src(), points: Some(10), ..Default::default() }.run(&Control::none()).map(|_| ())),
        ]
    }

    /// `text` with `sets` (`table.key`, value).
    fn with(text: &str, sets: &[(&str, f64)]) -> Table {
        let mut root = crate::config::parse_text(text, "test").unwrap();
        for (k, v) in sets {
            autobal::config::set_number(&mut root, k, *v).unwrap();
        }
        root
    }

    /// A default speed axis below the periodic-orbit floor names the key that raised the floor
    /// on every rotor, by [`floor_cause`] (the planar rotor's rule since session 28:
    /// `stability::tests::a_default_axis_below_the_floor_names_the_key_that_raised_it`). The
    /// spatial rotor, one plane and two, with supports of 1e3 N/m along x and 1e13 N/m at the
    /// right along y: the fastest natural frequency 1.2e6 rad/s puts the floor at ~1238 rad/s,
    /// above the default top 43.3 rad/s; it said "--omega-max: not given: the fastest natural
    /// frequency, …". Now `supports.stiffness_right_y`, the key the user set.
    #[test]
    fn a_spatial_default_axis_below_the_floor_names_the_stiffest_support() {
        let sets = [("supports.stiffness_left", 1e3), ("supports.stiffness_right", 1e3), ("supports.stiffness_right_y", 1e13)];
        // one plane, anisotropic by the `_y` key (a periodic orbit); two planes under gravity
        for (text, name) in
            [(include_str!("../../../examples/dimensional.toml"), "one plane"), (include_str!("../../../examples/spatial_two_plane.toml"), "two planes")]
        {
            for e in default_axis_errors(&with(text, &sets)) {
                assert!(
                    e.starts_with("supports.stiffness_right_y: 1e13 N/m, the stiffest support (along y), through the fastest natural frequency 1.237")
                        && e.contains("puts the slowest speed the periodic-orbit analysis resolves at 123")
                        && e.contains("above the speed axis's default top")
                        && e.ends_with("give --omega-max above it")
                        && !e.contains('\n'),
                    "{name}: {e}"
                );
            }
        }
    }

    /// The linear rotor: the shaft example's full model (no `modes`) under gravity, its first
    /// bearing at `k = 1e13`: the fastest natural frequency 1.7e7 rad/s (at least that bearing's
    /// own sqrt(k/m) over its node's mass), the floor ~16900 rad/s above the default top
    /// ~2900 rad/s. It said "--omega-max: not given: the default speed axis's …"; now the
    /// bearing's key. The example as it is (`modes = 4`) has no such floor, and a reduction
    /// names no bearing.
    #[test]
    fn a_linear_default_axis_below_the_floor_names_the_stiff_bearing() {
        let shaft = include_str!("../../../examples/linear_rotor_shaft.toml");
        let text = shaft.replacen("[linear_rotor]\n", "[linear_rotor]\ngravity = [0.0, -9.81]\n", 1).replacen("\nmodes = 4 ", "\n# modes = 4 ", 1).replacen(
            "node = 0\nk = 2e6\n",
            "node = 0\nk = 1e13\n",
            1,
        );
        assert!(text.contains("# modes = 4") && text.contains("k = 1e13"));
        let [stability, _, campbell] = default_axis_errors(&crate::config::parse_text(&text, "test").unwrap());
        for e in [stability, campbell] {
            assert!(
                e.starts_with("linear_rotor.bearings[0].k: 1e13 N/m at node 0, through the fastest natural frequency ")
                    && e.contains("raises the floor: the default speed axis's ")
                    && e.ends_with("give --omega-max above it")
                    && !e.contains('\n'),
                "{e}"
            );
        }
    }
    use autobal::planar::PlanarRotor;
    use autobal::rotor_stability::StateKind;

    /// The e-folding time is `1/|σ|` in the unit that keeps it readable: the washer's slowest
    /// exponent under gravity, -1.4659e-4 1/s, is 6822 s = 1.89 h; each unit's boundary; the
    /// sign chooses decay or growth; no time for a zero or non-finite rate.
    #[test]
    fn e_folding_reads_the_rate_as_a_time() {
        assert_eq!(e_folding(-1.4659e-4, true), " (a disturbance decays by the factor e in 1.89 h at the slowest)");
        assert_eq!(e_folding(43.59, true), " (a disturbance grows by the factor e in 0.0229 s)");
        assert_eq!(e_folding(-1.0 / 600.0, true), " (a disturbance decays by the factor e in 10 min at the slowest)");
        assert_eq!(e_folding(-1.0 / (3.0 * 86_400.0), true), " (a disturbance decays by the factor e in 3 days at the slowest)");
        assert_eq!(e_folding(-0.5, false), " (a disturbance decays by the factor e in 2 units of τ at the slowest)");
        assert_eq!(e_folding(0.0, true), "");
        assert_eq!(e_folding(f64::NAN, true), "");
        assert_eq!(speed_span(|w| format!("{w}"), 2.0, 2.0), "2");
        assert_eq!(speed_span(|w| format!("{w}"), 1.0, 2.0), "1 to 2");
    }

    /// The family line names a balanced point's member: paper 004's rotor (eccentric race) with
    /// three balls, partially balanced (balls bunched) below ~134 rad/s, a one-parameter
    /// family of semi-balanced states above. The member named is that of the first point with
    /// the family, its balls not bunched (they spread on an arc to cancel the unbalance: at
    /// least 1e-3 rad apart), its state semi-balanced. Main at 21dbfc9 named the first speed's
    /// member, three balls at one angle (6.28318 ×3 on examples/planar.toml with n = 3).
    #[test]
    fn the_family_line_names_a_balanced_points_member() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 3, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let r = analyse(&g, 600.0, 30, &Control::default()).unwrap();
        assert_eq!(r.family_dimension, 1);
        // the balls bunched below the semi-balanced state's speed: partially balanced until
        // session 16, now not balanced where they leave E farther out than no balls (1.04 at
        // 20 rad/s); either way no family
        assert!(
            matches!(r.points[0].state, Some(StateKind::NotBalanced | StateKind::PartiallyBalanced)) && r.points[0].family_dimension == 0,
            "{:?}",
            r.points[0]
        );
        let p = r.points.iter().find(|p| p.family_dimension > 0).unwrap();
        assert_eq!(p.state, Some(StateKind::SemiBalanced));
        assert_eq!(r.member_psi, p.member_psi);
        let psi = &r.member_psi;
        let gap = |a: f64, b: f64| (a - b).rem_euclid(std::f64::consts::TAU).min((b - a).rem_euclid(std::f64::consts::TAU));
        assert!(gap(psi[0], psi[1]) > 1e-3 && gap(psi[1], psi[2]) > 1e-3, "{psi:?}");
        let t = table(&g, &r, 600.0, None);
        let line = t.lines().find(|l| l.starts_with("the balanced states form a family")).unwrap();
        assert!(line.contains(&format!("at {}", speed_text(&g, p.omega))), "{line}");
        let named = psi.iter().map(|a| fmt_num(round(a.rem_euclid(std::f64::consts::TAU)))).collect::<Vec<_>>().join(", ");
        assert!(line.contains(&named), "{line}");
    }

    /// A range end next to a speed where no state was found says so, and is not "the start
    /// of the axis" (main at 21dbfc9 said so of every end that was not located): paper 004's
    /// Jeffcott rotor, its scan with the point before the stable range's first marked failed.
    #[test]
    fn a_range_end_next_to_a_failed_speed_says_so() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let mut r = analyse(&g, 600.0, 30, &Control::default()).unwrap();
        let st = r.stable_ranges[0];
        let i = r.points.iter().position(|p| p.omega > st.from).unwrap();
        assert!(i > 1);
        r.points[i - 1].verdict = None;
        r.stable_ranges[0] = autobal::analysis::StableRange { from: r.points[i].omega, from_is_boundary: false, ..st };
        let t = table(&g, &r, 600.0, None);
        let want = format!(
            "stable: {} (a grid speed: no stationary state found at {} below it)",
            speed_text(&g, r.points[i].omega),
            speed_text(&g, r.points[i - 1].omega)
        );
        assert!(t.contains(&want), "{t}");
        assert!(!t.contains("(start of the axis)"), "{t}");
    }

    /// Speeds below the periodic-orbit floor read "not analysed", never "no stationary state
    /// found", in the summary and at a range end next to them; a grid mixing both says each
    /// with its own first reason (main at 41cc036 called all of them "no stationary state
    /// found" with the first one's reason). The paper's Jeffcott rotor, two points marked.
    #[test]
    fn speeds_below_the_floor_read_not_analysed() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let mut r = analyse(&g, 600.0, 30, &Control::default()).unwrap();
        let st = r.stable_ranges[0];
        let i = r.points.iter().position(|p| p.omega > st.from).unwrap();
        assert!(i > 1);
        for (j, analysed, why) in [(i - 1, false, "omega: below the floor"), (0, true, "no periodic orbit found")] {
            r.points[j].verdict = None;
            r.points[j].analysed = analysed;
            r.points[j].failure = Some(why.into());
        }
        r.stable_ranges[0] = autobal::analysis::StableRange { from: r.points[i].omega, from_is_boundary: false, ..st };
        let t = table(&g, &r, 600.0, None);
        let end = format!(
            "stable: {} (a grid speed: not analysed (below the periodic-orbit floor) at {} below it)",
            speed_text(&g, r.points[i].omega),
            speed_text(&g, r.points[i - 1].omega)
        );
        assert!(t.contains(&end), "{t}");
        let below = format!(
            "not analysed (below the periodic-orbit floor) at 1 of 30 speeds (the first, at {}: omega: below the floor)",
            speed_text(&g, r.points[i - 1].omega)
        );
        let none = format!("no stationary state found at 1 of 30 speeds (the first, at {}: no periodic orbit found)", speed_text(&g, r.points[0].omega));
        assert!(t.contains(&below) && t.contains(&none), "{t}");
    }

    /// The residual line counts the balanced speeds above 1e-6 and says how many more are
    /// balanced to within it, so that the table's lines add up to the speeds analysed (the
    /// washer under gravity: 39 speeds above 1e-6, 7 within it, and the line said only "39 of
    /// 50", leaving 7 speeds unaccounted for, until session 17). Paper 004's Jeffcott rotor
    /// (an equilibrium: every balanced residual Newton's ~1e-12), three of its balanced points
    /// given residuals above 1e-6.
    #[test]
    fn the_residual_line_counts_the_exactly_balanced_speeds_too() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let mut r = analyse(&g, 600.0, 30, &Control::default()).unwrap();
        let balanced: Vec<usize> = (0..r.points.len()).filter(|&i| r.points[i].state == Some(StateKind::Balanced)).collect();
        assert!(balanced.len() > 3, "{:?}", r.points);
        assert!(residual_text(&r, |w| speed_text(&g, w)).is_empty());
        for &i in &balanced[..3] {
            r.points[i].residual = Some(1e-3);
        }
        let line = residual_text(&r, |w| speed_text(&g, w));
        assert!(line.contains("at 3 of 30 speeds"), "{line}");
        assert!(line.trim_end().ends_with(&format!("; balanced to within 1e-6 at {} more", balanced.len() - 3)), "{line}");
        for &i in &balanced {
            r.points[i].residual = Some(1e-3);
        }
        assert!(!residual_text(&r, |w| speed_text(&g, w)).contains("more"));
    }

    /// An operating speed above the scan's axis (an `--omega-max` below it) is stable at the
    /// speed itself but no range of the scan holds it: the line says it is off the axis, not
    /// that the grid is too coarse (main at 51426c6 said "a narrower window than its spacing;
    /// more --samples resolve it", which no number of samples does). Paper 004's Jeffcott
    /// rotor, stable at 500 rad/s, scanned to 200 rad/s.
    #[test]
    fn an_operating_speed_off_the_axis_says_so() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let r = analyse(&g, 200.0, 10, &Control::default()).unwrap();
        let at = autobal::rotor_stability::stability_over_speed_with(&g.rotor, &[500.0], &Control::default()).unwrap().value;
        // as `operating` builds it: no range of the scan holds 500 rad/s
        let range = r.stable_ranges.iter().find(|st| st.from <= 500.0 && 500.0 <= st.to).cloned();
        assert!(range.is_none(), "{:?}", r.stable_ranges);
        let op = Operating { omega: [500.0, 500.0], points: at.points, range, stopped: None };
        assert_eq!(op.verdict(), Some(Verdict::Stable));
        let line = operating_verdict_line(&g, &r, &op);
        assert!(line.contains("outside the scan's speed axis") && !line.contains("more --samples"), "{line}");
    }

    /// The verdict over an operating range stopped before its last speed (Ctrl-C): none from
    /// stable speeds (those not solved may be unstable), NOT STABLE from an unstable one (the
    /// others cannot make the range stable), the usual verdict where every speed was solved
    /// (the stop came in the family phase). Paper 004's Jeffcott rotor, stable over 450-500
    /// rad/s; one point relabelled unstable for the second case.
    #[test]
    fn a_stopped_operating_verdict_decides_only_what_its_speeds_decide() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let r = analyse(&g, 600.0, 30, &Control::default()).unwrap();
        let whole = operating_at(&g, [450.0, 500.0], "key", &r, &Control::default()).unwrap();
        assert_eq!((whole.points.len(), whole.verdict(), whole.stopped_message()), (9, Some(Verdict::Stable), None));
        let stopped = Some(autobal::control::StopReason::Interrupted);
        let cut = Operating { points: whole.points[..2].to_vec(), stopped, ..whole.clone() };
        assert_eq!(cut.verdict(), None);
        let why = cut.stopped_message().unwrap();
        assert!(why.ends_with("stopped after 2 of 9 speeds solved there (kept: JSON operating.points): no verdict"), "{why}");
        assert!(operating_verdict_line(&g, &r, &cut).ends_with(": no verdict: stopped after 2 of 9 speeds solved there\n"));
        let mut unstable = cut.clone();
        unstable.points[1].verdict = Some(Verdict::Unstable);
        assert_eq!(unstable.verdict(), Some(Verdict::Unstable));
        assert!(unstable.stopped_message().unwrap().ends_with(": NOT STABLE, a speed solved is unstable"));
        let all = Operating { stopped, ..whole.clone() };
        assert_eq!(all.verdict(), Some(Verdict::Stable));
        assert!(all.stopped_message().unwrap().contains("the verdict at the operating speed at its 9 speeds"));
        let json = operating_json(&cut);
        assert_eq!((json["complete"].clone(), json["points"].as_array().unwrap().len()), (json!(false), 2));
        assert!(operating_json(&whole).get("complete").is_none());
    }

    /// A stable range over states that are not balanced never reads plain "stable": the label
    /// names the states, and a line names the speeds (paper 004's Jeffcott rotor, race centred,
    /// whose balanced state is stable above its critical speed; the points of the stable range
    /// relabelled as the opposite-ball state, since a scan reaches that state only from a poor
    /// start). Failed on b7bef73, whose label tested for "partially balanced" alone.
    #[test]
    fn a_stable_range_of_not_balanced_states_says_so() {
        let g = GeneralRotor { rotor: Rotor::Planar(PlanarRotor { n: 2, s2: 0.0, ..PlanarRotor::paper() }), si: true, omega0: 1.0 };
        let mut r = analyse(&g, 600.0, 30, &Control::default()).unwrap();
        let st = r.stable_ranges.first().cloned().expect("a stable range above the critical speed");
        assert!(table(&g, &r, 600.0, None).contains("\nstable: "), "{}", table(&g, &r, 600.0, None));
        for p in r.points.iter_mut().filter(|p| p.omega >= st.from && p.omega <= st.to) {
            p.state = Some(StateKind::NotBalanced);
        }
        let t = table(&g, &r, 600.0, None);
        assert!(!t.contains("\nstable: "), "{t}");
        assert!(t.contains("\nnot balanced, stable: "), "{t}");
        assert!(t.contains("\nnot balanced (the balls leave a residual of "), "{t}");
    }
}
