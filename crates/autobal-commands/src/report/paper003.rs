//! Section "Paper 003": every figure of Gorbenko, Shmelev, Strautmanis 2019 (necessary
//! conditions of autobalancing with the unbalance mass), with 003's own base case
//! (ΔĀ0 = 0.1, m̄0 = 0.05, R̄0 = 2, z̄_A0 = 0.8), so its printed Ω_K1-4 and Ω_a appear.

use super::{Ctx, Section};
use crate::figures::linspace;
use crate::num::fmt;
use crate::plot::{Plot, Series, Shade, PALETTE};
use anyhow::Result;
use autobal::spatial::critical_speeds::{critical_speeds_at, ModeKind};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::params::{AnisotropyInput, SpatialModel};
use autobal::spatial::ranges::{antiresonance_speed, autobalancing_ranges, point_a_response};
use autobal::spatial::sensitivity::sensitivity;

/// 003's base case: C̄Σ0 = 0.75, ρ̄s = 0.4, ΔĀ0 = 0.1, z̄_A0 = 0.8 (m̄0 = 0.05, R̄0 = 2,
/// Ā_m0 = 0.2), at layout `l̄_L`.
pub fn base_model(l_left: f64) -> SpatialModel {
    super::paper000::papers_base(l_left, AnisotropyInput::Direct(0.1), AnisotropyMethod::Exact)
}

/// 003's printed numbers: (l̄_L, Ω_K1-4, Ω_a).
const PRINTED: [(f64, [f64; 4], f64); 3] =
    [(0.5, [1.0, 1.0, 2.11, 3.23], 1.67), (0.8, [0.837, 0.849, 2.52, 3.80], 2.24), (1.2, [0.567, 0.575, 3.73, 5.61], 3.20)];

const GREEN: &str = "#009E73";

/// The boundaries of 003's Figs 4-5 along a sweep: Ω_K2, Ω_K4 (roots of Δ2 with ΔĪ02), Ω_K3
/// (the angular root of Δ1), Ω_a, and the isotropic Ω_K3,4 (dashed).
fn boundaries(xs: &[f64], at: &dyn Fn(f64) -> SpatialModel) -> Vec<Series> {
    let models: Vec<SpatialModel> = xs.iter().map(|&x| at(x)).collect();
    let root = |m: &SpatialModel, d: f64, branch: u8, kind: ModeKind| {
        critical_speeds_at(m, d).into_iter().find(|q| q.2 == branch && q.1 == kind).map_or(f64::NAN, |q| q.0)
    };
    let curve = |f: &dyn Fn(&SpatialModel) -> f64| xs.iter().zip(&models).map(|(&x, m)| (x, f(m))).collect::<Vec<_>>();
    vec![
        Series::new("Ω_K2 (transverse, Δ2)", curve(&|m| root(m, m.delta_a0, 2, ModeKind::Transverse)), PALETTE[0]),
        Series::new("Ω_K3 (angular, Δ1)", curve(&|m| root(m, m.delta_a0, 1, ModeKind::Angular)), PALETTE[4]),
        Series::new("Ω_K4 (angular, Δ2)", curve(&|m| root(m, m.delta_a0, 2, ModeKind::Angular)), PALETTE[1]),
        Series::new("Ω_a (antiresonance)", curve(&|m| antiresonance_speed(m).unwrap_or(f64::NAN)), PALETTE[3]),
        Series::new("Ω_K3,4 of the isotropic rotor, ΔĀ0 = 0", curve(&|m| root(m, 0.0, 1, ModeKind::Angular)), PALETTE[7]).dashed(),
    ]
}

/// The autobalancing ranges along a sweep as shaded columns.
fn range_shades(xs: &[f64], at: &dyn Fn(f64) -> SpatialModel) -> Vec<Shade> {
    let dx = if xs.len() > 1 { xs[1] - xs[0] } else { 1.0 };
    xs.iter()
        .flat_map(|&x| {
            autobalancing_ranges(&at(x)).ranges.into_iter().map(move |r| Shade { x: (x - dx / 2.0, x + dx / 2.0), y: (Some(r.lo), r.hi), color: GREEN.into() })
        })
        .collect()
}

pub fn build(_ctx: &Ctx) -> Result<Option<Section>> {
    let mut s = Section::new("paper003", "Paper 003: where autobalancing is possible, with the unbalance mass");
    s.p("Gorbenko, Shmelev, Strautmanis 2019. Base case of the paper (text before Figs 3-5): C̄Σ0 = 0.75, ρ̄s = 0.4, ΔĀ0 = 0.1, z̄_A0 = 0.8, m̄0 = 0.05, R̄0 = 2 (Ā_m0 = 0.2), long rotor at l̄_L = 0.8 unless stated. Ranges from the necessary conditions (1)-(3) of 003; black dots are the numbers printed in the paper. The exact linear stability of the balanced state, which these conditions only bound, is in the stability section and in docs/notes/stability.md.");
    let base = base_model(0.8);

    let mut rows = vec![];
    for (l, k, wa) in PRINTED {
        let m = base_model(l);
        let cs: Vec<String> = critical_speeds_at(&m, 0.1).iter().map(|r| fmt(r.0, 4)).collect();
        rows.push(vec![
            fmt(l, 2),
            format!("{} / {}", k.map(|v| fmt(v, 3)).join(", "), cs.join(", ")),
            format!("{} / {}", fmt(wa, 3), antiresonance_speed(&m).map_or("—".into(), |w| fmt(w, 4))),
            super::rotor::ranges_text(&autobalancing_ranges(&m).ranges, None),
        ]);
    }
    s.table(&["l̄_L (–)", "Ω_K1-4 printed / computed (–)", "Ω_a printed / computed (–)", "autobalancing possible (eq (3))"], &rows);
    let se = sensitivity(&base, 0.15);
    s.p(format!(
        "Sensitivity threshold (003, eq (5)): [ΔĀ0] = {} for [δΩ_Kα] = 0.15 (003 prints 0.069); the unbalance mass it corresponds to is [m̄0] = 2 [ΔĀ0]/R̄0² = {} (003 prints 0.017, half of it).",
        fmt(se.delta_a_limit, 4),
        fmt(2.0 * se.delta_a_limit / 4.0, 3)
    ));

    // Fig. 2: the areas along Ω for the three layouts
    {
        let mut shades = vec![];
        let mut series = vec![];
        let mut ticks = vec![];
        let wmax = 6.5;
        for (row, (l, k, wa)) in PRINTED.iter().enumerate() {
            let y = 3.0 - row as f64;
            let ar = autobalancing_ranges(&base_model(*l));
            let band =
                |lo: f64, hi: Option<f64>, dy: (f64, f64), c: &str| Shade { x: (lo, hi.unwrap_or(wmax)), y: (Some(y + dy.0), Some(y + dy.1)), color: c.into() };
            for r in &ar.phase_condition {
                shades.push(band(r.lo, r.hi, (0.16, 0.4), "#56B4E9"));
            }
            for r in &ar.ranges {
                shades.push(band(r.lo, r.hi, (-0.12, 0.12), GREEN));
            }
            for r in &ar.instability {
                shades.push(band(r.lo, r.hi, (-0.4, -0.16), "#D55E00"));
            }
            series.push(
                Series::new(if row == 0 { "printed Ω_K1-4 and Ω_a" } else { "" }, k.iter().chain([wa]).map(|&w| (w, y)).collect(), "#000000")
                    .markers()
                    .group("printed"),
            );
            ticks.push((y, format!("l̄_L = {l}")));
        }
        s.figure(
            "fig003_2_areas",
            Plot {
                title: "003 Fig. 2: speed ranges where autobalancing is possible".into(),
                x_label: "Ω".into(),
                y_label: "".into(),
                series,
                shades,
                shade_legend: vec![
                    ("#56B4E9".into(), "A moves against the unbalance (upper band)".into()),
                    (GREEN.into(), "autobalancing possible (middle band)".into()),
                    ("#D55E00".into(), "split-pair instability (lower band)".into()),
                ],
                x_range: Some((0.0, wmax)),
                y_range: Some((0.4, 3.6)),
                y_ticks: Some(ticks),
                ..Default::default()
            },
            "003 Fig. 2 (a scheme in the paper), computed for the three layouts: upper band (blue) where plane A moves against the unbalance (phase condition (1)), lower band (red) where a split pair of critical speeds makes the rotor unstable, middle band (green) where the first holds and the second does not: autobalancing is possible (eq (3)): Ω1 &lt; Ω &lt; Ω2 and Ω &gt; Ω3. Dots: the printed Ω_K1-4 and Ω_a, which bound the bands.",
        );
    }

    // Fig. 3: the signed response of point A
    {
        let m = &base;
        let wmax = 5.0;
        let ylim = 12.0;
        let pts: Vec<(f64, f64)> = linspace(0.0, wmax, 2001)
            .into_iter()
            .map(|w| {
                let v = point_a_response(m, w);
                (w, if v.abs() > 10.0 * ylim { f64::NAN } else { v })
            })
            .collect();
        let ar = autobalancing_ranges(m);
        let mut vlines: Vec<(f64, String)> = ar.critical_speeds.iter().enumerate().map(|(i, &w)| (w, format!("K{} = {}", i + 1, fmt(w, 3)))).collect();
        if let Some(wa) = ar.antiresonance_speed {
            vlines.push((wa, format!("Ω_a = {}", fmt(wa, 3))));
        }
        s.figure(
            "fig003_3_signed_response",
            Plot {
                title: "003 Fig. 3: signed amplitude of point A, l̄_L = 0.8".into(),
                x_label: "Ω".into(),
                y_label: "ξ̄_A / (m̄0 R̄0)".into(),
                series: vec![Series::new("ξ̄_A (locked balls)", pts, PALETTE[0])],
                shades: ar.ranges.iter().map(|r| Shade { x: (r.lo, r.hi.unwrap_or(wmax)), y: (None, None), color: GREEN.into() }).collect(),
                shade_label: Some("autobalancing possible (A against the unbalance, no split-pair instability)".into()),
                vlines,
                x_range: Some((0.0, wmax)),
                y_range: Some((-ylim, ylim)),
                ..Default::default()
            },
            format!(
                "003 Fig. 3: amplitude-frequency characteristic of point A of the unbalanced rotor with its sign, per unit unbalance, base case at l̄_L = 0.8 with 003's ΔĀ0 = 0.1. The markers show the computed critical speeds and antiresonance: the paper prints Ω_K1-4 = 0.837, 0.849, 2.52, 3.80 and Ω_a = 2.24 (computed: {}; {}). Negative amplitude (A moves against the unbalance): autobalancing possible where no split pair is unstable (shaded): {}.",
                ar.critical_speeds.iter().map(|w| fmt(*w, 4)).collect::<Vec<_>>().join(", "),
                ar.antiresonance_speed.map_or("—".into(), |w| fmt(w, 4)),
                super::esc(&super::rotor::ranges_text(&ar.ranges, None))
            ),
        );
    }

    // Figs 4, 5a, 5b: the boundaries against C̄Σ0, z̄_A0, ΔĀ0
    type At<'a> = Box<dyn Fn(f64) -> SpatialModel + 'a>;
    type Study<'a> = (&'a str, &'a str, &'a str, &'a str, Vec<f64>, At<'a>, f64, String);
    let studies: [Study; 3] = [
        (
            "fig003_4_ranges_vs_c_sigma",
            "003 Fig. 4: autobalancing boundaries against the rotor type",
            "C̄Σ0 (long < 1 < short)",
            "003 Fig. 4: the boundaries Ω1,2,3 of possible autobalancing (shaded) against C̄Σ0",
            linspace(0.2, 2.0, 181),
            Box::new(|c| {
                let mut m = base.clone();
                m.c_sigma = c;
                m
            }),
            0.75,
            "a long rotor (C̄Σ0 &lt; 1 − ΔĀ0 = 0.9) can be autobalanced in two ranges, Ω1 &lt; Ω &lt; Ω2 and Ω &gt; Ω3; a near-spherical one (0.9 &lt; C̄Σ0 &lt; 1 − ΔĀ0 + z̄² = 1.54) in one bounded range; a short one above Ω1, as the paper states".into(),
        ),
        (
            "fig003_5a_ranges_vs_z_a",
            "003 Fig. 5a: autobalancing boundaries against the position of plane A",
            "z̄_A0 (plane A from C / ρ_s)",
            "003 Fig. 5a: the boundaries against the position z̄_A0 of the unbalance and balancer plane",
            linspace(-2.0, 2.0, 161),
            Box::new(|z| {
                let mut m = base.clone();
                m.z_a = z;
                m
            }),
            0.8,
            "the ranges are widest with plane A through the centre of mass (z̄_A0 = 0) and narrow as |z̄_A0| grows, as the paper states".into(),
        ),
        (
            "fig003_5b_ranges_vs_delta_a0",
            "003 Fig. 5b: autobalancing boundaries against the unbalance's anisotropy",
            "ΔĀ0",
            "003 Fig. 5b: the boundaries against the anisotropy ΔĀ0 caused by the unbalance mass",
            linspace(0.0, 0.24, 121),
            Box::new(|d| {
                let mut m = base.clone();
                m.delta_a0 = d;
                m.anisotropy.used = d;
                m
            }),
            0.1,
            "growing ΔĀ0 widens the lower range slightly (Ω_K2 falls) and narrows the upper one (Ω_K4 rises), as the paper states; the dashed vertical line is the sensitivity threshold [ΔĀ0]".into(),
        ),
    ];
    for (id, title, xl, what, xs, at, x_base, finding) in studies {
        let mut series = boundaries(&xs, &*at);
        let (k, wa) = (PRINTED[1].1, PRINTED[1].2);
        series.push(Series::new("printed in the paper (base case)", vec![(x_base, k[1]), (x_base, k[2]), (x_base, k[3]), (x_base, wa)], "#000000").markers());
        let mut vlines = vec![];
        if id.ends_with("delta_a0") {
            vlines.push((se.delta_a_limit, format!("[ΔĀ0] = {}", fmt(se.delta_a_limit, 3))));
        }
        s.figure(
            id,
            Plot {
                title: title.into(),
                x_label: xl.into(),
                y_label: "Ω".into(),
                series,
                shades: range_shades(&xs, &*at),
                shade_label: Some("autobalancing possible (eq (3))".into()),
                y_range: Some((0.0, 6.0)),
                x_range: Some((xs[0], *xs.last().unwrap_or(&1.0))),
                vlines,
                ..Default::default()
            },
            format!(
                "{what} (l̄_L = 0.8, other values of the base case). The boundaries are made of Ω_K2, Ω_K3, Ω_K4 and Ω_a (003, eq (2)); grey dashed: the angular critical speed of the isotropic rotor. Compared with the paper's text: {finding}. Dots: the printed Ω_K2, K3, K4 and Ω_a at the base value."
            ),
        );
    }
    Ok(Some(s))
}
