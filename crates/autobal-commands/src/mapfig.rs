//! Figures of stability maps (`autobal map` and the report): the margin heatmap with its colour
//! bar, the exact stability boundary and 003's necessary boundary as lines, axes named by the
//! physics (not by config keys). Written as SVG and PNG from one [`Plot`].

use crate::map::{Cell, MapResult, Quantity};
use crate::plot::{ColorScale, Heatmap, Plot, Series};
use anyhow::{Context, Result};
use std::path::Path;

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
pub fn write_plots(r: &MapResult, stem: &Path, title: &str) -> Result<()> {
    let p = plot(r, title);
    let svg_path = crate::output::with_suffix(stem, "svg");
    // one SVG (the heatmap's PNG encoded once), rasterised for the PNG
    let svg = p.to_svg();
    std::fs::write(&svg_path, &svg).with_context(|| format!("cannot write {}", svg_path.display()))?;
    let png_path = crate::output::with_suffix(stem, "png");
    std::fs::write(&png_path, crate::plot::svg_to_png(&svg, 1.5)?).with_context(|| format!("cannot write {}", png_path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
