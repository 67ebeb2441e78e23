//! `autobal map`: stability margin over two parameters (Ω and/or parameter paths), computed by
//! the library in parallel ([`autobal::spatial::map`]), with a progress bar, written as CSV in
//! grid order as rows complete (an interrupted run keeps what it has computed), SVG and PNG
//! from a decimated copy.

use crate::config::Config;
use crate::plot::Series;
use anyhow::{anyhow, bail, Result};
use autobal::control::Control;
use autobal::spatial::boundary::{Boundary, Codim2Kind, CurveKind, TraceSettings};
use autobal::spatial::linear_model::Balls;
use rayon::prelude::*;
use std::io::Write;
use std::path::Path;

/// One axis: `key=lo:hi:n`, key `omega` or a config field.
#[derive(Debug, Clone)]
pub struct Axis {
    pub key: String,
    pub lo: f64,
    pub hi: f64,
    pub n: usize,
}

impl Axis {
    pub fn parse(flag: &str, spec: &str) -> Result<Self> {
        let (key, range) = spec.split_once('=').ok_or_else(|| anyhow!("{flag} {spec}: expected KEY=LO:HI:N, e.g. {flag} omega=0.1:6:400"))?;
        let parts: Vec<&str> = range.split(':').collect();
        if parts.len() != 3 {
            bail!("{flag} {spec}: expected KEY=LO:HI:N");
        }
        let num = |s: &str, what: &str| -> Result<f64> {
            let v: f64 = s.trim().parse().map_err(|_| anyhow!("{flag} {spec}: {what} `{s}` is not a number"))?;
            if !v.is_finite() {
                bail!("{flag} {spec}: {what} must be finite");
            }
            Ok(v)
        };
        let (lo, hi) = (num(parts[0], "LO")?, num(parts[1], "HI")?);
        let n: usize = parts[2].trim().parse().map_err(|_| anyhow!("{flag} {spec}: N `{}` is not a whole number", parts[2]))?;
        if !(2..=100_000).contains(&n) {
            bail!("{flag} {spec}: N must lie between 2 and 100000, got {n}");
        }
        if hi <= lo {
            bail!("{flag} {spec}: HI must exceed LO");
        }
        let key = key.trim().to_string();
        if key == "omega" && lo < 0.0 {
            bail!("{flag} {spec}: the speed Ω must not be negative");
        }
        Ok(Axis { key, lo, hi, n })
    }
    /// The `i`-th grid value, rounded to 12 significant digits so that printed values read as
    /// typed (0.4, not 0.39999999999999997); the ends are exact.
    pub fn value(&self, i: usize) -> f64 {
        if i + 1 >= self.n {
            return self.hi;
        }
        let v = self.lo + (self.hi - self.lo) * i as f64 / (self.n - 1) as f64;
        if v == 0.0 {
            return 0.0;
        }
        let mag = 10f64.powi(11 - v.abs().log10().floor() as i32);
        (v * mag).round() / mag
    }
    /// Whether the axis is the speed: `omega` (Ω) or, for a dimensional config, `speed_rpm`,
    /// `speed` (rad/s), `speed_hz` ([`autobal::units::SPEED_PATHS`]).
    fn is_omega(&self) -> bool {
        autobal::units::speed_path_unit(&self.key).is_some()
    }
    /// The library's axis: the path and every value.
    pub fn to_library(&self) -> autobal::spatial::map::Axis {
        autobal::spatial::map::Axis { path: self.key.clone(), values: (0..self.n).map(|i| self.value(i)).collect() }
    }
}

pub use autobal::spatial::map::{Cell, Quantity};

/// The data the figures are drawn from: the whole map, or a decimated copy of a large one
/// (every k-th row and column, at most [`PLOT_CELLS`] per axis).
pub struct MapResult {
    pub x: Axis,
    pub y: Axis,
    /// `rows[j][i]` at `(x_i, y_j)`; `None` for rows not computed (interrupted).
    pub rows: Vec<Option<Vec<Cell>>>,
    pub quantity: Quantity,
}

/// How far a map got.
pub struct MapRun {
    /// Rows written to the CSV.
    pub rows_done: usize,
    /// Rows of the full grid.
    pub rows_total: usize,
    /// Points per row.
    pub row_len: usize,
    /// Points from continuation / characteristic polynomial, and direct solves.
    pub continued: usize,
    pub direct: usize,
}

/// Largest number of cells per axis kept for the figures.
pub const PLOT_CELLS: usize = 500;

/// Stride and decimated axis: indices `0, k, 2k, …` of `a`.
fn decimate(a: &Axis) -> (usize, Axis) {
    let k = a.n.div_ceil(PLOT_CELLS).max(1);
    if k == 1 {
        return (1, a.clone());
    }
    let m = (a.n - 1) / k;
    (k, Axis { key: a.key.clone(), lo: a.value(0), hi: a.value(m * k), n: m + 1 })
}

/// Compute the map with the library ([`autobal::spatial::map::stability_map`]), writing the
/// CSV in grid order (row `j` = all `x` at `y_j`) as rows complete, and keeping a decimated copy
/// for the figures: memory does not grow with the grid.
#[allow(clippy::too_many_arguments)]
pub fn compute(
    cfg: &Config,
    x: Axis,
    y: Axis,
    omega: Option<f64>,
    balls: Balls,
    quantity: Quantity,
    csv: &mut dyn Write,
    progress: bool,
    control: &Control,
) -> Result<(MapResult, MapRun)> {
    for (flag, a) in [("--x", &x), ("--y", &y)] {
        if !a.is_omega() {
            let mut s = cfg.spec.clone();
            s.set(&a.key, a.lo).map_err(|e| anyhow!("{flag}: {e}"))?;
        }
    }
    if x.is_omega() && y.is_omega() {
        bail!("--x, --y: only one axis can be omega");
    }
    if !x.is_omega() && !y.is_omega() && omega.is_none() {
        bail!("--omega: required when neither axis is omega (the speed at which to map)");
    }
    writeln!(csv, "{},{},max_real_part,stable,necessary", x.key, y.key)?;
    let (lx, ly) = (x.to_library(), y.to_library());
    let settings = autobal::spatial::map::MapSettings { balls, quantity, omega };
    let bar = progress.then(|| {
        let b = indicatif::ProgressBar::new(y.n as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} rows  {elapsed_precise} (eta {eta})")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b
    });
    let (kx, dx) = decimate(&x);
    let (ky, dy) = decimate(&y);
    let mut kept: Vec<Option<Vec<Cell>>> = vec![None; dy.n];
    let xs: Vec<String> = lx.values.iter().map(|v| crate::num::Csv(*v).to_string()).collect();
    let verdict_only = quantity == Quantity::Verdict;
    // rows are formatted in parallel in batches (the pool is idle between the library's blocks)
    let mut pending: Vec<(usize, Vec<Cell>)> = vec![];
    let mut io_error: Option<std::io::Error> = None;
    let flush = |pending: &mut Vec<(usize, Vec<Cell>)>, csv: &mut dyn Write| -> std::io::Result<()> {
        let texts: Vec<String> = pending
            .par_iter()
            .map(|(j, cells)| {
                let yv = crate::num::Csv(ly.values[*j]).to_string();
                let mut t = String::with_capacity(cells.len() * 40);
                for (xs, c) in xs.iter().zip(cells) {
                    use std::fmt::Write as _;
                    // `--quantity verdict` computes no margin: an empty field, never `NaN`
                    let margin = if verdict_only { String::new() } else { crate::num::Csv(c.margin).to_string() };
                    let _ = writeln!(t, "{xs},{yv},{margin},{},{}", c.stable as u8, c.necessary as u8);
                }
                t
            })
            .collect();
        pending.clear();
        for t in texts {
            csv.write_all(t.as_bytes())?;
        }
        csv.flush()
    };
    let batch = (1 << 16) / x.n.max(1) + 1;
    let outcome = autobal::spatial::map::stability_map_units(&cfg.spec, &lx, &ly, &settings, control, &mut |j, cells| {
        if j % ky == 0 && j / ky < dy.n {
            kept[j / ky] = Some(cells.iter().step_by(kx).take(dx.n).copied().collect());
        }
        pending.push((j, cells.to_vec()));
        if pending.len() >= batch || j + 1 == ly.values.len() {
            if let Err(e) = flush(&mut pending, csv) {
                io_error = Some(e);
                return false;
            }
        }
        if let Some(b) = &bar {
            b.set_position(j as u64 + 1);
        }
        true
    });
    if let Some(e) = io_error {
        return Err(e.into());
    }
    let outcome = outcome.map_err(|e| anyhow!("{e}"))?;
    if !pending.is_empty() {
        flush(&mut pending, csv)?;
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let run = MapRun { rows_done: outcome.rows, rows_total: y.n, row_len: x.n, continued: outcome.continued, direct: outcome.direct };
    Ok((MapResult { x: dx, y: dy, rows: kept, quantity }, run))
}

/// Write `<stem>.svg` and `<stem>.png` (drawn by [`plot`]), with the traced boundary when given.
pub fn write_plots(r: &MapResult, stem: &Path, title: &str, traced: Option<&Boundary>) -> Result<()> {
    let Some(b) = traced else { return write_heatmap(r, stem, title) };
    let mut p = plot(r, title);
    p.series.extend(boundary_series(b));
    crate::outfile::write_atomic("--out", &crate::term::with_suffix(stem, "svg"), p.to_svg())?;
    crate::outfile::write_atomic("--out", &crate::term::with_suffix(stem, "png"), p.to_png(1.5)?)
}

/// The traced curves as figure series: the stability boundary solid (Hopf blue, fold orange),
/// the rest of each curve thin and dashed, codimension-two points as markers.
pub fn boundary_series(b: &Boundary) -> Vec<Series> {
    let mut out = vec![];
    for (kind, color, name) in [(CurveKind::Hopf, "#0072B2", "Hopf"), (CurveKind::Fold, "#E69F00", "fold")] {
        let (mut on, mut off) = (vec![], vec![]);
        for c in b.curves.iter().filter(|c| c.kind == kind) {
            for w in c.points.windows(2) {
                let seg = [(w[0].x, w[0].y), (w[1].x, w[1].y), (f64::NAN, f64::NAN)];
                if w[0].on_boundary && w[1].on_boundary {
                    on.extend(seg);
                } else {
                    off.extend(seg);
                }
            }
        }
        if !on.is_empty() {
            out.push(Series::new(format!("traced boundary ({name})"), on, color).width(2.5));
        }
        if !off.is_empty() {
            out.push(Series::new(format!("{name} curve, not a boundary"), off, color).dashed().width(1.0));
        }
    }
    if !b.codim2.is_empty() {
        out.push(Series::new("codimension-two points", b.codim2.iter().map(|p| (p.x, p.y)).collect(), "#000000").markers());
    }
    out
}

/// The traced curves as CSV rows `curve,kind,x,y,hopf_frequency_squared,on_boundary` (`ω_H²` of
/// the pair `λ = ±iω_H` on a Hopf curve, 0 on a fold curve; not the speed) and the
/// codimension-two points as `-,KIND,x,y,,`.
pub fn boundary_csv(b: &Boundary, x: &str, y: &str) -> String {
    use std::fmt::Write as _;
    let mut s = format!("curve,kind,{x},{y},hopf_frequency_squared,on_boundary\n");
    for (i, c) in b.curves.iter().enumerate() {
        let kind = if c.kind == CurveKind::Hopf { "hopf" } else { "fold" };
        for p in &c.points {
            let _ = writeln!(s, "{i},{kind},{},{},{},{}", crate::num::Csv(p.x), crate::num::Csv(p.y), crate::num::Csv(p.w), p.on_boundary as u8);
        }
    }
    for p in &b.codim2 {
        let kind = match p.kind {
            Codim2Kind::BogdanovTakens => "bogdanov-takens",
            Codim2Kind::DoubleHopf => "double-hopf",
            Codim2Kind::FoldHopf => "fold-hopf",
        };
        let _ = writeln!(s, "-,{kind},{},{},,", crate::num::Csv(p.x), crate::num::Csv(p.y));
    }
    s
}

/// Trace the stability boundary over the map's plane ([`autobal::spatial::boundary`]); the
/// control (Ctrl-C) stops it with the curves traced so far (`complete` false).
pub fn trace(cfg: &Config, x: &Axis, y: &Axis, omega: Option<f64>, balls: Balls, control: &Control) -> Result<Boundary> {
    let ax = |a: &Axis| autobal::paths::Axis::range(a.key.clone(), a.lo, a.hi);
    let s = TraceSettings { balls, omega, ..Default::default() };
    autobal::spatial::boundary::trace_boundary_units(&cfg.spec, &ax(x), &ax(y), &s, control).map_err(|e| anyhow!("--boundary: {e}"))
}

/// `autobal map` by the general route ([`autobal::rotor_map`]): any planar or spatial config,
/// written as `STEM.csv` (columns: the two axes, `max_real_part`, `verdict`,
/// `family_dimension`; empty fields where no stationary state was found), `STEM.svg`,
/// `STEM.png`.
#[allow(clippy::too_many_arguments)]
pub fn run_general(
    root: &toml::Table,
    config: Option<&Path>,
    x: &str,
    y: &str,
    omega: Option<&str>,
    verdict_only: bool,
    out: &Path,
    threads: Option<usize>,
    boundary: bool,
    control: &Control,
) -> Result<()> {
    use autobal::rotor_map::{general_map_traced, BoundaryPoint, Kind, Verdict};
    let xa = Axis::parse("--x", x)?;
    let ya = Axis::parse("--y", y)?;
    if xa.key == ya.key {
        bail!("--y {}: the same key as --x; map over two different keys", ya.key);
    }
    let speed = omega.map(|t| autobal::units::parse_speed("--omega", t)).transpose()?;
    if let Some(t) = threads {
        if t == 0 {
            bail!("--threads: must be at least 1");
        }
        rayon::ThreadPoolBuilder::new().num_threads(t).build_global().ok();
    }
    let out = crate::term::out_stem(&crate::outfile::resolve(out, "stability-map"), &["csv", "svg", "png"]);
    let csv_path = crate::term::with_suffix(&out, "csv");
    let mut o = crate::outfile::Outputs::new();
    o.inputs(config);
    for p in crate::outfile::stem_files(&out, &["csv", "svg", "png"]) {
        o.output("--out", &p);
    }
    let boundary_path = std::path::PathBuf::from(format!("{}_boundary.csv", out.display()));
    if boundary {
        o.output("--out", &boundary_path);
    }
    o.check()?;
    let mut w = crate::outfile::Staged::create("--out", &csv_path)?;
    writeln!(w, "{},{},max_real_part,verdict,family_dimension,family", xa.key, ya.key)?;
    let mut traced: Vec<BoundaryPoint> = vec![];
    let verdict_name = |v: Option<Verdict>| match v {
        None => "",
        Some(Verdict::Stable) => "stable",
        Some(Verdict::Unstable) => "unstable",
        Some(Verdict::Neutral) => "neutral",
    };
    let (lx, ly) = (xa.to_library(), ya.to_library());
    let bar = std::io::IsTerminal::is_terminal(&std::io::stderr()).then(|| {
        let b = indicatif::ProgressBar::new(ya.n as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} rows  {elapsed_precise} (eta {eta})")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b
    });
    let (kx, dx) = decimate(&xa);
    let (ky, dy) = decimate(&ya);
    let mut kept: Vec<Option<Vec<autobal::rotor_map::GeneralCell>>> = vec![None; dy.n];
    let xs: Vec<String> = lx.values.iter().map(|v| crate::num::Csv(*v).to_string()).collect();
    let mut io_error: Option<std::io::Error> = None;
    let t0 = std::time::Instant::now();
    let mut on_row = |j: usize, cells: &[autobal::rotor_map::GeneralCell], points: &[BoundaryPoint]| {
        traced.extend_from_slice(points);
        if j.is_multiple_of(ky) && j / ky < dy.n {
            kept[j / ky] = Some(cells.iter().step_by(kx).take(dx.n).copied().collect());
        }
        use std::fmt::Write as _;
        let yv = crate::num::Csv(ly.values[j]).to_string();
        let mut t = String::with_capacity(cells.len() * 48);
        for (xs, c) in xs.iter().zip(cells) {
            // no stationary state: empty fields, never `NaN`
            let (margin, verdict, fam) = match c.verdict {
                None => (String::new(), "", String::new()),
                Some(v) => {
                    (if verdict_only { String::new() } else { crate::num::Csv(c.margin).to_string() }, verdict_name(Some(v)), c.family_dimension.to_string())
                }
            };
            // with a family: all, some or none of its members stable (empty for an isolated state)
            let family = match c.family {
                None => "",
                Some(autobal::rotor_map::FamilyVerdict::AllStable) => "all_stable",
                Some(autobal::rotor_map::FamilyVerdict::SomeStable) => "some_stable",
                Some(autobal::rotor_map::FamilyVerdict::NoneStable) => "none_stable",
            };
            let _ = writeln!(t, "{xs},{yv},{margin},{verdict},{fam},{family}");
        }
        if let Err(e) = w.write_all(t.as_bytes()).and_then(|_| w.flush()) {
            io_error = Some(e);
            return false;
        }
        if let Some(b) = &bar {
            b.set_position(j as u64 + 1);
        }
        true
    };
    // a linear rotor config ([linear_rotor]): its own paths and rotor (crate::linear_rotor)
    let linear = crate::linear_rotor::is_linear(root);
    let outcome = if linear {
        crate::linear_rotor::map_traced(root, config, &lx, &ly, speed, boundary, control, &mut on_row)
    } else {
        general_map_traced(root, &lx, &ly, speed, boundary, control, &mut on_row)
    };
    if let Some(e) = io_error {
        return Err(e.into());
    }
    let outcome = outcome.map_err(|e| match e.field() {
        Some(f) if f == xa.key => anyhow!("--x: {e}"),
        Some(f) if f == ya.key => anyhow!("--y: {e}"),
        Some("omega") => anyhow!("--omega: {e}"),
        _ => anyhow!("{e}"),
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let csv_path = w.commit()?;
    let secs = t0.elapsed().as_secs_f64();
    let planar = !autobal::config::is_spatial(root);
    let periodic = outcome.periodic > 0;
    let kind = if periodic { Kind::PeriodicOrbit } else { Kind::Equilibrium };
    let rows: Vec<Option<Vec<Cell>>> = kept
        .iter()
        .map(|r| r.as_ref().map(|r| r.iter().map(|c| Cell { margin: c.margin, stable: c.verdict == Some(Verdict::Stable), necessary: false }).collect()))
        .collect();
    let q = if verdict_only { Quantity::Verdict } else { Quantity::Margin };
    let r = MapResult { x: dx, y: dy, rows, quantity: q };
    let state = match kind {
        Kind::Equilibrium => "equilibrium (eigenvalues)",
        Kind::PeriodicOrbit => "periodic orbit (Floquet multipliers)",
    };
    let model = if linear {
        "linear"
    } else if planar {
        "planar"
    } else {
        "spatial"
    };
    let title = format!("Stability map of the {model} rotor's stationary state (general route: {state})");
    let mut p = plot(&r, &title);
    // no 003 necessary ranges off the 12-state model
    p.series.retain(|s| s.label != "003 necessary boundary");
    if planar {
        // the planar model's `omega` is ω itself (no ω0)
        for (key, label) in [(&r.x.key, &mut p.x_label), (&r.y.key, &mut p.y_label)] {
            if key == "omega" {
                *label = "speed ω (rad/s)".into();
            }
        }
    }
    if let Some(h) = p.heatmap.as_mut() {
        // cells without a stationary state stay blank
        for (zr, kr) in h.z.iter_mut().zip(&kept) {
            if let Some(kr) = kr {
                for (z, c) in zr.iter_mut().zip(kr) {
                    if c.verdict.is_none() {
                        *z = f64::NAN;
                    }
                }
            }
        }
        if !verdict_only {
            let what = if periodic { "largest Floquet exponent" } else { "max Re λ" };
            h.label = format!("{what} ({}; < 0 stable)", if planar { "1/s" } else { "per unit τ" });
        }
    }
    if boundary {
        // the bisected points: `x` to 1e-9 relative where the margin changes sign (or a
        // stationary state appears), with the verdicts on either side
        let mut t = format!("{},{},from,to\n", xa.key, ya.key);
        for b in &traced {
            use std::fmt::Write as _;
            let _ = writeln!(t, "{},{},{},{}", crate::num::Csv(b.x), crate::num::Csv(b.y), verdict_name(b.from), verdict_name(b.to));
        }
        crate::outfile::write_atomic("--out", &boundary_path, t)?;
        crate::term::note(&format!("boundary: {} points bisected along {} to 1e-9 relative; wrote {}", traced.len(), xa.key, boundary_path.display()));
        if !traced.is_empty() {
            p.series.push(Series::new("bisected boundary points", traced.iter().map(|b| (b.x, b.y)).collect(), "#0072B2").markers());
        }
    }
    crate::outfile::write_atomic("--out", &crate::term::with_suffix(&out, "svg"), p.to_svg())?;
    crate::outfile::write_atomic("--out", &crate::term::with_suffix(&out, "png"), p.to_png(1.5)?)?;
    let points = outcome.rows * xa.n;
    crate::term::print(&format!(
        "general route: {} rows × {} points in {:.2} s ({:.2} µs per point; {} from the closed form, {} continued from a neighbour, {} without a stationary state); stationary state: {state}; wrote {}, {}, {}\n",
        outcome.rows,
        xa.n,
        secs,
        1e6 * secs / points.max(1) as f64,
        outcome.closed_form,
        outcome.continued,
        outcome.none,
        csv_path.display(),
        crate::term::with_suffix(&out, "svg").display(),
        crate::term::with_suffix(&out, "png").display()
    ))?;
    if outcome.families > 0 {
        crate::term::note(&format!(
            "{} cells have a family of balanced states (n ≥ 3 balls): max_real_part and verdict are those of one member, the one reached from the closed form (balls in a symmetric arc); the column family says whether all, some or none of the family's members are stable",
            outcome.families
        ));
    }
    if !outcome.complete {
        bail!("interrupted: {} of {} rows computed and kept in {}", outcome.rows, ya.n, csv_path.display());
    }
    Ok(())
}

// The map's figure: Figures of stability maps (`autobal map` and the report): the margin heatmap
// with its colour bar, the exact stability boundary and 003's necessary boundary as lines, axes
// named by the physics (not by config keys). Written as SVG and PNG from one [`Plot`].
use crate::plot::{ColorScale, Heatmap, Plot};
use anyhow::Context;

/// Axis title of a map axis: the physical quantity for the keys autobal knows, else the key.
pub fn axis_label(key: &str) -> String {
    let known: &[(&str, &str)] = &[
        ("omega", "Ω = ω/ω0"),
        ("speed_rpm", "speed n (rpm)"),
        ("speed", "speed ω (rad/s)"),
        ("speed_hz", "speed f (Hz)"),
        ("dimensionless.c_sigma", "C̄Σ (polar / mean equatorial moment)"),
        ("dimensionless.rho_s", "ρ̄s (radius of gyration / span)"),
        ("dimensionless.l_left", "l̄_L (C from the left support / span)"),
        ("dimensionless.z_a", "z̄_A (balancer plane from C / ρ_s)"),
        ("dimensionless.delta_a", "ΔĀ = ΔĀ0 (anisotropy)"),
        ("dimensionless.m0", "m̄0 (unbalance mass / M_s)"),
        ("dimensionless.r0", "R̄0 (unbalance radius / ρ_s)"),
        ("dimensionless.m", "m̄ (ball mass / M_s)"),
        ("dimensionless.r", "R̄ (race radius / ρ_s)"),
        ("dimensionless.h_x", "h̄x (support damping)"),
        ("dimensionless.h_s", "h̄s (ball drag)"),
        ("rotor.mass", "rotor mass M_r (kg)"),
        ("rotor.z", "axial position of G (m)"),
        ("balancer.z", "axial position of plane A (m)"),
        ("balancer.ball_mass", "ball mass m (kg)"),
        ("balancer.race_radius", "race radius R (m)"),
        ("balancer.drag", "ball drag h_A (N·s/m)"),
        ("unbalance.mass", "unbalance mass m0 (kg)"),
        ("unbalance.radius", "unbalance radius R0 (m)"),
        ("supports.stiffness_left", "left stiffness c_L (N/m)"),
        ("supports.stiffness_right", "right stiffness c_R (N/m)"),
        ("supports.damping_left", "left damping h_L (N·s/m)"),
        ("supports.damping_right", "right damping h_R (N·s/m)"),
    ];
    known.iter().find(|k| k.0 == key).map_or_else(|| key.to_string(), |k| k.1.to_string())
}

/// Join cell-edge segments (pairs of points) that share ends into polylines, NaN-separated,
/// so that a dashed line shows its dashes instead of restarting them on every cell edge.
/// A straight piece of a boundary, end to end.
pub type Segment = ((f64, f64), (f64, f64));

pub fn chain(segments: &[Segment]) -> Vec<(f64, f64)> {
    use std::collections::HashMap;
    let key = |p: (f64, f64)| ((p.0 * 1e9).round() as i64, (p.1 * 1e9).round() as i64);
    let mut ends: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (k, (a, b)) in segments.iter().enumerate() {
        ends.entry(key(*a)).or_default().push(k);
        ends.entry(key(*b)).or_default().push(k);
    }
    let mut used = vec![false; segments.len()];
    let mut out = vec![];
    let next = |p: (f64, f64), used: &Vec<bool>| ends.get(&key(p)).and_then(|v| v.iter().copied().find(|&k| !used[k]));
    for start in 0..segments.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b) = segments[start];
        let mut line = std::collections::VecDeque::from([a, b]);
        // grow forwards, then backwards
        for forward in [true, false] {
            loop {
                let end = if forward { *line.back().expect("non-empty") } else { *line.front().expect("non-empty") };
                let Some(k) = next(end, &used) else { break };
                used[k] = true;
                let (p, q) = segments[k];
                let far = if key(p) == key(end) { q } else { p };
                if forward {
                    line.push_back(far);
                } else {
                    line.push_front(far);
                }
            }
        }
        out.extend(line);
        out.push((f64::NAN, f64::NAN));
    }
    out
}

/// Cell-edge segments between cells whose `flag` differs.
fn boundary(r: &MapResult, flag: impl Fn(&Cell) -> bool) -> Vec<(f64, f64)> {
    let dx = (r.x.hi - r.x.lo) / (r.x.n - 1) as f64;
    let dy = (r.y.hi - r.y.lo) / (r.y.n - 1) as f64;
    // the grid values once (each `value` call rounds through log10: 320 000 calls per figure)
    let xs: Vec<f64> = (0..r.x.n).map(|i| r.x.value(i)).collect();
    let ys: Vec<f64> = (0..r.y.n).map(|j| r.y.value(j)).collect();
    let mut segs = vec![];
    for j in 0..r.y.n {
        let Some(row) = &r.rows[j] else { continue };
        for i in 0..r.x.n {
            let (x, y) = (xs[i], ys[j]);
            if i + 1 < r.x.n && flag(&row[i]) != flag(&row[i + 1]) {
                segs.push(((x + dx / 2.0, y - dy / 2.0), (x + dx / 2.0, y + dy / 2.0)));
            }
            if let Some(Some(up)) = r.rows.get(j + 1) {
                if flag(&row[i]) != flag(&up[i]) {
                    segs.push(((x - dx / 2.0, y + dy / 2.0), (x + dx / 2.0, y + dy / 2.0)));
                }
            }
        }
    }
    chain(&segs)
}

/// The map as a figure: heatmap (margin with a diverging colour bar, or the verdict), the exact
/// boundary (solid black) and 003's necessary boundary (dashed), physics axis titles.
pub fn plot(r: &MapResult, title: &str) -> Plot {
    let cells = || r.rows.iter().flatten().flatten().filter(|c| c.margin.is_finite());
    let neg = cells().filter(|c| c.margin < 0.0).map(|c| -c.margin).fold(1e-12, f64::max);
    let pos = cells().filter(|c| c.margin >= 0.0).map(|c| c.margin).fold(1e-12, f64::max);
    let z: Vec<Vec<f64>> = r
        .rows
        .iter()
        .map(|row| match row {
            Some(cells) => cells
                .iter()
                .map(|c| match r.quantity {
                    Quantity::Margin => c.margin,
                    Quantity::Verdict => {
                        if c.stable {
                            -1.0
                        } else {
                            1.0
                        }
                    }
                })
                .collect(),
            None => vec![f64::NAN; r.x.n],
        })
        .collect();
    let (scale, label) = match r.quantity {
        Quantity::Margin => (ColorScale::Diverging { neg, pos }, "max Re λ (< 0 stable)".to_string()),
        Quantity::Verdict => (ColorScale::Verdict, "verdict".to_string()),
    };
    let dx = (r.x.hi - r.x.lo) / (r.x.n - 1) as f64;
    let dy = (r.y.hi - r.y.lo) / (r.y.n - 1) as f64;
    Plot {
        title: title.to_string(),
        x_label: axis_label(&r.x.key),
        y_label: axis_label(&r.y.key),
        series: vec![
            Series::new("exact stability boundary", boundary(r, |c| c.stable), "#000000"),
            Series::new("003 necessary boundary", boundary(r, |c| c.necessary), "#CC79A7").dashed(),
        ],
        x_range: Some((r.x.lo - dx / 2.0, r.x.hi + dx / 2.0)),
        y_range: Some((r.y.lo - dy / 2.0, r.y.hi + dy / 2.0)),
        heatmap: Some(Heatmap { x: (0..r.x.n).map(|i| r.x.value(i)).collect(), y: (0..r.y.n).map(|j| r.y.value(j)).collect(), z, scale, label }),
        ..Default::default()
    }
}

/// Write `<stem>.svg` and `<stem>.png` (the PNG rasterised from the SVG: legend, colour bar
/// and tick labels included).
fn write_heatmap(r: &MapResult, stem: &Path, title: &str) -> Result<()> {
    let p = plot(r, title);
    let svg_path = crate::term::with_suffix(stem, "svg");
    // one SVG (the heatmap's PNG encoded once), rasterised for the PNG
    let svg = p.to_svg();
    std::fs::write(&svg_path, &svg).with_context(|| format!("cannot write {}", svg_path.display()))?;
    let png_path = crate::term::with_suffix(stem, "png");
    std::fs::write(&png_path, crate::plot::svg_to_png(&svg, 1.5)?).with_context(|| format!("cannot write {}", png_path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_values_read_as_typed() {
        let a = Axis::parse("--x", "planar.c_psi=0.01:0.4:4").unwrap();
        let v: Vec<f64> = (0..4).map(|i| a.value(i)).collect();
        assert_eq!(v, vec![0.01, 0.14, 0.27, 0.4]);
        let a = Axis::parse("--x", "omega=0:6:401").unwrap();
        assert_eq!(a.value(0), 0.0);
        assert!((a.value(123) - 6.0 * 123.0 / 400.0).abs() < 1e-11);
    }

    #[test]
    fn bad_axis_specs_are_rejected_with_the_flag() {
        for spec in ["omega", "omega=1:2", "omega=2:1:5", "omega=0:1:1", "omega=a:1:3", "omega=-1:1:3", "x=0:1:9999999"] {
            let e = Axis::parse("--y", spec).unwrap_err().to_string();
            assert!(e.starts_with("--y"), "{e}");
        }
    }

    #[test]
    fn chained_segments_form_one_polyline() {
        // an L-shaped boundary given as three unit segments in scrambled order
        let segs = [((1.0, 0.0), (1.0, 1.0)), ((0.0, 0.0), (1.0, 0.0)), ((1.0, 1.0), (2.0, 1.0))];
        let pts = chain(&segs);
        assert_eq!(pts.iter().filter(|p| p.0.is_nan()).count(), 1, "one line: {pts:?}");
        assert_eq!(pts.len(), 5);
    }

    #[test]
    fn config_keys_read_as_physics() {
        assert_eq!(axis_label("dimensionless.z_a"), "z̄_A (balancer plane from C / ρ_s)");
        assert_eq!(axis_label("planar.k"), "planar.k");
    }
}
