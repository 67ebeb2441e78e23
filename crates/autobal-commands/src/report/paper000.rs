//! Section "Paper 000": every figure of Gorbenko 2016 (critical speeds of a rotor with a ball
//! balancer), with the paper's base case whatever the config, the exact inertia tensor beside
//! the paper's eq (17) where they differ, and the paper's printed numbers drawn as markers so
//! each figure can be checked against the text.

use super::{Ctx, Section};
use crate::figures::{curve_color, linspace, with_layout};
use crate::num::fmt;
use crate::plot::{Plot, Series, PALETTE};
use anyhow::Result;
use autobal::spatial::critical_speeds::{critical_speeds_at, ModeKind};
use autobal::spatial::inertia::{anisotropy, exact_interval, AnisotropyMethod, BallSet};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
use autobal::spatial::sensitivity::sensitivity;

/// 000's base case (the text before its Figs 4-8): C̄Σ = 0.75, ρ̄s = 0.4, l̄_L = 0.8,
/// m̄ = 0.05, R̄ = 2, m̄0 = 0.025, R̄0 = 2, two balls (E = 2, D_A = 0.5), ΔĀ = 0.1 by eq (17).
pub const BASE_MASSES: MassSet = MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 };

/// The base case with the paper's eq (17) in use (ΔĀ = 0.1), exact tensor alongside.
pub fn base_model(l_left: f64) -> SpatialModel {
    papers_base(l_left, AnisotropyInput::Masses { masses: BASE_MASSES, d_a: None }, AnisotropyMethod::Paper)
}

/// The long rotor of both papers' worked examples (C̄Σ = 0.75, ρ̄s = 0.4, z̄_A = 0.8, no
/// damping) at layout `l̄_L` with the given anisotropy.
pub fn papers_base(l_left: f64, anisotropy: AnisotropyInput, method: AnisotropyMethod) -> SpatialModel {
    SpatialModel::from_dimensionless(&DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left,
        z_a: 0.8,
        anisotropy,
        h_x: 0.0,
        h_s: 0.0,
        method,
        direct_balls: None,
    })
    .expect("the papers' base case is valid")
}

/// The worked numbers 000 prints for the base case, per layout: (l̄_L, p̄α, c̄yα, Ω_K1-4).
pub const PRINTED: [(f64, f64, f64, [f64; 4]); 3] =
    [(0.5, 1.25, 0.0, [1.0, 1.0, 2.11, 3.23]), (0.8, 1.46, 0.75, [0.837, 0.849, 2.52, 3.80]), (1.2, 2.15, 1.75, [0.567, 0.575, 3.73, 5.61])];

const KEYS: [(u8, ModeKind); 4] = [(1, ModeKind::Transverse), (1, ModeKind::Angular), (2, ModeKind::Transverse), (2, ModeKind::Angular)];

/// Critical speeds along a sweep, one curve per (branch, kind), in one legend group per branch.
/// NaN where a root does not exist.
fn branch_curves(xs: &[f64], at: &dyn Fn(f64) -> (SpatialModel, f64), names: [&str; 2], colors: [&str; 2], dashed: bool, angular_only: bool) -> Vec<Series> {
    let roots: Vec<Vec<(f64, ModeKind, u8)>> = xs
        .iter()
        .map(|&x| {
            let (m, d) = at(x);
            critical_speeds_at(&m, d)
        })
        .collect();
    let mut out = vec![];
    for (k, &(branch, kind)) in KEYS.iter().enumerate() {
        if angular_only && kind != ModeKind::Angular {
            continue;
        }
        let pts = xs.iter().zip(&roots).map(|(&x, r)| (x, r.iter().find(|q| q.1 == kind && q.2 == branch).map_or(f64::NAN, |q| q.0))).collect();
        let b = (branch - 1) as usize;
        let first_of_branch = !out.iter().any(|s: &Series| s.group.as_deref() == Some(names[b]));
        let _ = k;
        let mut s = Series::new(if first_of_branch { names[b] } else { "" }, pts, colors[b]).group(names[b]);
        s.dashed = dashed;
        out.push(s);
    }
    out
}

/// The paper's printed values as markers.
fn printed_markers(points: Vec<(f64, f64)>) -> Series {
    Series::new("printed in the paper", points, "#000000").markers()
}

pub fn build(_ctx: &Ctx) -> Result<Option<Section>> {
    let mut s = Section::new("paper000", "Paper 000: critical speeds of a rotor with a ball balancer");
    s.p("Gorbenko 2016. Base case of the paper (text before Figs 4-8): C̄Σ = 0.75, ρ̄s = 0.4, l̄_L = 0.8, m̄ = 0.05, R̄ = 2, m̄0 = 0.025, R̄0 = 2, two balls, capacity E = 2, D_A = 0.5, so Ā_m = 0.2, Ā_m0 = 0.1 and ΔĀ = 0.1 by the paper's eq (17). The exact inertia tensor of the balls at balance gives ΔĀ = 0 for this case (for E &gt; √2 the balls' anisotropy opposes the unbalance's: docs/notes/papers.md), so where the paper's curves assume ΔĀ = 0.1 the exact curve is the isotropic one. Black dots: numbers printed in the paper.");
    let base = base_model(0.8);

    // printed vs computed
    let mut rows = vec![];
    for (l, p, c, k) in PRINTED {
        let m = base_model(l);
        let cs: Vec<String> = critical_speeds_at(&m, 0.1).iter().map(|r| fmt(r.0, 4)).collect();
        rows.push(vec![
            fmt(l, 2),
            format!("{} / {}", fmt(p, 3), fmt(m.p_alpha_sq.sqrt(), 4)),
            format!("{} / {}", fmt(c, 3), fmt(m.c_y_alpha, 4)),
            format!("{} / {}", k.map(|v| fmt(v, 3)).join(", "), cs.join(", ")),
        ]);
    }
    s.table(&["l̄_L (–)", "p̄α printed / computed (–)", "c̄yα printed / computed (–)", "Ω_K1-4 printed / computed, ΔĀ = 0.1 (–)"], &rows);

    // Fig. 3: the spectrum of critical speeds
    {
        let m = &base;
        let row = |y: f64, speeds: &[f64]| speeds.iter().map(|&w| (w, y)).collect::<Vec<_>>();
        let iso: Vec<f64> = critical_speeds_at(m, 0.0).iter().map(|r| r.0).collect();
        let two: Vec<f64> = critical_speeds_at(m, 0.1).iter().map(|r| r.0).collect();
        // n ≥ 3, eq (17): ΔĀ = ½ Ā_m0 + ½ Ā_m D_A over D_A ∈ [0, 1]
        let sweep = |lo: f64, hi: f64| -> Vec<(f64, f64)> {
            let ds = linspace(lo, hi, 101);
            let mut out = vec![];
            for &(branch, kind) in &KEYS {
                let v: Vec<f64> = ds.iter().filter_map(|&d| critical_speeds_at(m, d).into_iter().find(|q| q.1 == kind && q.2 == branch).map(|q| q.0)).collect();
                if let (Some(a), Some(b)) = (v.iter().copied().reduce(f64::min), v.iter().copied().reduce(f64::max)) {
                    out.push((a, b));
                }
            }
            out
        };
        let eq17 = sweep(0.05, 0.15);
        // exact tensor, three balls of the same total mass: interval over the balancing family
        let set3 = BallSet { n: 3, ..BASE_MASSES.ball_set() };
        let ex3 = exact_interval(&set3);
        let exact3 = sweep(ex3.min, ex3.max);
        let bars = |y: f64, iv: &[(f64, f64)], label: &str, col: &str| -> Series {
            let mut pts = vec![];
            for &(a, b) in iv {
                pts.extend([(a, y), (b, y), (f64::NAN, f64::NAN)]);
            }
            Series::new(label, pts, col).width(9.0)
        };
        let series = vec![
            Series::new("a: isotropic rotor, no balancer (ΔĀ = 0)", row(5.0, &iso), PALETTE[6]).markers(),
            Series::new("b: two balls, eq (17): ΔĀ = 0.1", row(4.0, &two), PALETTE[0]).markers(),
            bars(3.0, &eq17, "c: n ≥ 3 balls, eq (17): ΔĀ ∈ [0.05, 0.15] (D_A ∈ [0, 1])", PALETTE[1]),
            Series::new("b, exact tensor: two balls at E = 2 are isotropic", row(2.0, &iso), PALETTE[2]).markers(),
            bars(1.0, &exact3, &format!("c, exact tensor, three balls: ΔĀ ∈ [{}, {}]", fmt(ex3.min, 3), fmt(ex3.max, 3)), PALETTE[3]),
            printed_markers(row(4.0, &PRINTED[1].3)),
        ];
        s.figure(
            "fig000_3_spectrum",
            Plot {
                title: "000 Fig. 3: the spectrum of critical speeds split by the balancer".into(),
                x_label: "Ω_K".into(),
                y_label: "".into(),
                series,
                y_range: Some((0.4, 5.6)),
                x_range: Some((0.0, 4.5)),
                y_ticks: Some(vec![(5.0, "a".into()), (4.0, "b".into()), (3.0, "c".into()), (2.0, "b exact".into()), (1.0, "c exact".into())]),
                ..Default::default()
            },
            "000 Fig. 3 (qualitative in the paper), computed for the base case l̄_L = 0.8: (a) the isotropic rotor has two critical speeds; (b) a two-ball balancer splits each into two, 0.837, 0.849, 2.52, 3.80 as the paper prints (black dots); (c) with three or more balls D_A is not fixed by balance and the critical speeds become intervals (bars). By the exact tensor the two-ball case does not split at all, and three balls of the same total mass give the narrower intervals of the last row.",
        );
    }

    // Fig. 4: ΔĀ against the balls' mass
    {
        let ms = BASE_MASSES;
        let mbar = linspace(0.0, 0.1, 101);
        let mut series: Vec<Series> = [0.0, 0.5, 1.0]
            .iter()
            .enumerate()
            .map(|(i, &d)| {
                Series::new(
                    format!("{}: eq (17), D_A = {d}", i + 1),
                    mbar.iter().map(|&m| (m, 0.5 * ms.a_m0() + 0.5 * m * ms.r * ms.r * d)).collect(),
                    PALETTE[i],
                )
            })
            .collect();
        let set_at = |m: f64, n: u32| BallSet { n, ..MassSet { m, n, ..ms }.ball_set() };
        series.push(Series::new(
            "exact tensor, 2 balls",
            mbar.iter()
                .map(|&m| {
                    (m, if m > 0.0 { anisotropy(&set_at(m, 2), None, AnisotropyMethod::Exact).map_or(f64::NAN, |a| a.exact[0]) } else { 0.5 * ms.a_m0() })
                })
                .collect(),
            PALETTE[6],
        ));
        let mbar3 = linspace(0.0, 0.1, 41);
        let three: Vec<[f64; 2]> = mbar3
            .iter()
            .map(|&m| if m > 0.0 { anisotropy(&set_at(m, 3), None, AnisotropyMethod::Exact).map_or([f64::NAN; 2], |a| a.exact) } else { [0.5 * ms.a_m0(); 2] })
            .collect();
        series.push(Series::new("exact tensor, 3 balls: least", mbar3.iter().zip(&three).map(|(&m, v)| (m, v[0])).collect(), PALETTE[4]).dashed());
        series.push(Series::new("exact tensor, 3 balls: largest", mbar3.iter().zip(&three).map(|(&m, v)| (m, v[1])).collect(), PALETTE[5]).dashed());
        series.push(printed_markers(vec![(0.05, 0.1)]));
        s.figure(
            "fig000_4_anisotropy_vs_ball_mass",
            Plot { title: "000 Fig. 4: inertia anisotropy against the balls' mass".into(), x_label: "m̄ = n m / M_s".into(), y_label: "ΔĀ".into(), series, x_range: Some((0.0, 0.1)), ..Default::default() },
            "000 Fig. 4: ΔĀ against m̄ (m̄0 = 0.025, R̄0 = 2, R̄ = 2). Curves 1-3 are the paper's eq (17) for D_A = 0, 0.5, 1; the base case (m̄ = 0.05, D_A = 0.5) gives the paper's ΔĀ = 0.1 (dot). The exact tensor of the balls at balance: once the capacity E = 20 m̄ exceeds √2 (m̄ &gt; 0.071) the two balls' anisotropy opposes the unbalance's; between E = 1 and √2 eq (17) with D_A = |cos 2β| agrees. Three balls span the interval between the dashed curves.",
        );
    }

    // Figs 5a, 5b: against C̄Σ
    let names = ["branch 1: Δ1 = 0 (ΔĪ1 = 1 − C̄Σ + ΔĀ)", "branch 2: Δ2 = 0 (ΔĪ2 = 1 − C̄Σ − ΔĀ)"];
    let iso_names = ["isotropic ΔĀ = 0 (= exact tensor here)", "isotropic ΔĀ = 0 (= exact tensor here)"];
    for (tag, l) in [("a", 0.5), ("b", 1.2)] {
        let cs = linspace(0.1, 2.0, 381);
        let at = |c: f64| {
            let mut m = with_layout(&base, l);
            m.c_sigma = c;
            m
        };
        let mut series = branch_curves(&cs, &|c| (at(c), 0.1), names, [PALETTE[0], PALETTE[1]], false, false);
        series.extend(branch_curves(&cs, &|c| (at(c), 0.0), iso_names, [PALETTE[7], PALETTE[7]], true, false));
        let pr = PRINTED.iter().find(|p| p.0 == l).expect("printed layout");
        series.push(printed_markers(pr.3.iter().map(|&w| (0.75, w)).collect()));
        s.figure(
            format!("fig000_5{tag}_critical_vs_c_sigma"),
            Plot {
                title: format!("000 Fig. 5{tag}: critical speeds against the rotor type, l̄_L = {l}"),
                x_label: "C̄Σ (long < 1 < short)".into(),
                y_label: "Ω_K".into(),
                series,
                y_range: Some((0.0, 6.0)),
                x_range: Some((0.1, 2.0)),
                vlines: vec![(0.9, "1 − ΔĀ".into()), (1.1, "1 + ΔĀ".into())],
                ..Default::default()
            },
            format!(
                "000 Fig. 5{tag}: critical speeds against C̄Σ, {} rotor (l̄_L = {l}), ΔĀ = 0.1 (solid; blue the roots of Δ1, orange of Δ2, each a transverse and an angular speed) and the isotropic rotor (grey dashed), which is also what the exact tensor gives for the base case. Between C̄Σ = 1 − ΔĀ and 1 + ΔĀ (near-spherical) only branch 1 has an angular critical speed; above, the rotor is short and its angular speeds vanish. Dots: the paper's worked numbers at C̄Σ = 0.75 ({}), reproduced.{}",
                if l == 0.5 { "symmetric" } else { "overhung" },
                pr.3.map(|v| fmt(v, 3)).join(", "),
                if l == 0.5 { " With c̄yα = 0 the transverse speeds of both branches and of the isotropic rotor coincide at Ω = 1." } else { "" }
            ),
        );
    }

    // Fig. 6: against l̄_L
    {
        let ls = linspace(0.0, 1.6, 321);
        let mut series = branch_curves(&ls, &|l| (with_layout(&base, l), 0.1), names, [PALETTE[0], PALETTE[1]], false, false);
        series.extend(branch_curves(&ls, &|l| (with_layout(&base, l), 0.0), iso_names, [PALETTE[7], PALETTE[7]], true, false));
        series.push(printed_markers(PRINTED.iter().flat_map(|p| p.3.iter().map(move |&w| (p.0, w))).collect()));
        s.figure(
            "fig000_6_critical_vs_l_left",
            Plot {
                title: "000 Fig. 6: critical speeds against the position on the supports".into(),
                x_label: "l̄_L (0.5 symmetric, > 1 overhung)".into(),
                y_label: "Ω_K".into(),
                series,
                y_range: Some((0.0, 6.0)),
                x_range: Some((0.0, 1.6)),
                ..Default::default()
            },
            "000 Fig. 6: critical speeds of the long rotor (C̄Σ = 0.75) against l̄_L, ΔĀ = 0.1 (solid, by branch) and isotropic (grey dashed, = exact tensor here). The paper's worked numbers at l̄_L = 0.5, 0.8 and 1.2 (dots) lie on the curves. The relative split of the angular speeds hardly changes with l̄_L, which is why 000 takes eq (22) from the symmetric case.",
        );
    }

    // Fig. 7: against ΔĀ
    {
        let ds = linspace(0.0, 0.3, 301);
        let mut series = branch_curves(&ds, &|d| (base.clone(), d), names, [PALETTE[0], PALETTE[1]], false, false);
        series.extend(branch_curves(&ds, &|_| (base.clone(), 0.0), iso_names, [PALETTE[7], PALETTE[7]], true, false));
        series.push(printed_markers(PRINTED[1].3.iter().map(|&w| (0.1, w)).collect()));
        s.figure(
            "fig000_7_critical_vs_anisotropy",
            Plot {
                title: "000 Fig. 7: critical speeds against the anisotropy, l̄_L = 0.8".into(),
                x_label: "ΔĀ".into(),
                y_label: "Ω_K".into(),
                series,
                y_range: Some((0.0, 7.0)),
                x_range: Some((0.0, 0.3)),
                vlines: vec![(0.1, "eq (17)".into()), (0.0, "exact".into())],
                ..Default::default()
            },
            "000 Fig. 7: critical speeds of the long asymmetric rotor (l̄_L = 0.8) against ΔĀ: the angular speed splits strongly (branch 2 grows without bound as ΔĪ2 = 0.25 − ΔĀ → 0), the transverse one hardly. Dots: the printed 0.837, 0.849, 2.52, 3.80 at the paper's ΔĀ = 0.1; the exact tensor puts the base case at ΔĀ = 0.",
        );
    }

    // Fig. 8: angular critical speeds against m̄ at capacity E = 2
    {
        let ms = BASE_MASSES;
        let mb = linspace(0.0, 0.1, 401);
        let mut series = vec![];
        for (i, d) in [0.0, 0.5, 1.0].into_iter().enumerate() {
            // E = 2 → m̄0 R̄0 = m̄ R̄ / 2; ΔĀ = ½ m̄0 R̄0² + ½ m̄ R̄² D_A
            let da = move |m: f64| 0.5 * (m * ms.r / 2.0) * ms.r0 + 0.5 * m * ms.r * ms.r * d;
            let label = format!("{}: eq (17), D_A = {d}", i + 1);
            series.extend(branch_curves(&mb, &|m| (base.clone(), da(m)), [&label, &label], [curve_color(i), curve_color(i)], false, true));
        }
        let exact2 = |m: f64| {
            let m0 = m * ms.r / (2.0 * ms.r0);
            let set = BallSet { n: 2, a_m0: m0 * ms.r0 * ms.r0, a_m: m * ms.r * ms.r, capacity: 2.0 };
            anisotropy(&set, None, AnisotropyMethod::Exact).map_or(f64::NAN, |a| a.exact[0])
        };
        let ex = "exact tensor, 2 balls (isotropic)";
        series.extend(branch_curves(&mb, &|m| (base.clone(), exact2(m)), [ex, ex], [PALETTE[6], PALETTE[6]], true, true));
        series.push(printed_markers(vec![(0.05, 2.52), (0.05, 3.80)]));
        s.figure(
            "fig000_8_angular_critical_vs_ball_mass",
            Plot {
                title: "000 Fig. 8: angular critical speeds against the balls' mass, E = 2".into(),
                x_label: "m̄ = n m / M_s".into(),
                y_label: "Ω_Kα".into(),
                series,
                y_range: Some((1.5, 6.0)),
                x_range: Some((0.0, 0.1)),
                ..Default::default()
            },
            "000 Fig. 8: the two angular critical speeds of the long asymmetric rotor (l̄_L = 0.8) against m̄ with the unbalance growing with it at capacity E = 2 (m̄0 = m̄/2), by eq (17) for D_A = 0, 0.5, 1 (ΔĀ = m̄ (1 + 2 D_A)): the lower of each pair falls, the upper rises and leaves the plot where ΔĪ2 → 0 (for D_A = 1 at m̄ = 0.083). Dots: 2.52 and 3.80 printed for m̄ = 0.05, D_A = 0.5. By the exact tensor two balls at E = 2 leave the rotor isotropic at every m̄ (black dashed: no split).",
        );
    }

    // Fig. 9: the sensitivity δΩ_Kα1,2 against ΔĀ and against m̄
    {
        let delta_of = |d: f64| {
            let se = sensitivity(&base.with_anisotropy(d), 0.15);
            (se.delta_exact, se.delta_approx)
        };
        let curves = |xs: &[f64], da: &dyn Fn(f64) -> f64| -> Vec<Series> {
            let v: Vec<_> = xs.iter().map(|&x| (x, delta_of(da(x)))).collect();
            let mut out = vec![];
            for (k, name) in [(0usize, "δΩ_Kα1"), (1, "δΩ_Kα2")] {
                out.push(Series::new(format!("{name}, exact (16)"), v.iter().map(|(x, d)| (*x, d.0[k].unwrap_or(f64::NAN))).collect(), PALETTE[k]));
                out.push(Series::new(format!("{name}, eq (22)"), v.iter().map(|(x, d)| (*x, d.1[k].unwrap_or(f64::NAN))).collect(), PALETTE[k]).dashed());
            }
            let x1 = *xs.last().unwrap_or(&1.0);
            out.push(Series::new("±[δΩ_Kα] = ±0.15", vec![(0.0, 0.15), (x1, 0.15), (f64::NAN, f64::NAN), (0.0, -0.15), (x1, -0.15)], PALETTE[7]).dashed());
            out
        };
        let ds = linspace(0.0, 0.2, 201);
        let ex = delta_of(0.1).0;
        let se_base = sensitivity(&base, 0.15);
        s.figure(
            "fig000_9a_sensitivity_vs_anisotropy",
            Plot {
                title: "000 Fig. 9a: relative change of the angular critical speeds against ΔĀ".into(),
                x_label: "ΔĀ".into(),
                y_label: "δΩ_Kα1,2".into(),
                series: curves(&ds, &|d| d),
                x_range: Some((0.0, 0.2)),
                y_range: Some((-0.4, 0.6)),
                vlines: vec![(0.1, "base case".into()), (0.095, "000: 0.095".into()), (se_base.delta_a_limit, format!("[ΔĀ0] = {}", fmt(se_base.delta_a_limit, 3)))],
                ..Default::default()
            },
            format!(
                "000 Fig. 9a: δΩ_Kα1,2 = (Ω_Kα1,2 − Ω_Kα0)/Ω_Kα1,2 for l̄_L = 0.8 by the exact roots of eq (16) (solid) and by eq (22) (dashed). At the base case ΔĀ = 0.1 the exact values are {} and {}: the change reaches {} %, where the paper says \"up to 16 %\"; eq (22) is within {} of the exact values here (the paper: \"not more than 6 %\"). The criterion |δΩ_Kα| &gt; 0.15 is met from ΔĀ = {} by eq (22) (the paper prints 0.095; 003's [ΔĀ0] = 0.069 is the same formula).",
                fmt(ex[0].unwrap_or(f64::NAN), 3),
                fmt(ex[1].unwrap_or(f64::NAN), 3),
                fmt(100.0 * se_base.coefficient.unwrap_or(f64::NAN), 3),
                fmt(ds.iter().map(|&d| { let (e, a) = delta_of(d); (0..2).map(|k| (e[k].unwrap_or(0.0) - a[k].unwrap_or(0.0)).abs()).fold(0.0, f64::max) }).fold(0.0, f64::max), 2),
                fmt(se_base.delta_a_limit, 3)
            ),
        );
        let mb = linspace(0.0, 0.1, 201);
        // base values except m̄: ΔĀ = ½ Ā_m0 + ½ m̄ R̄² D_A = 0.05 + m̄
        let da = |m: f64| 0.5 * BASE_MASSES.a_m0() + 0.5 * m * BASE_MASSES.r * BASE_MASSES.r * 0.5;
        // where the criterion |δΩ_Kα| > 0.15 is first met along m̄, exactly and by eq (22)
        let first = |exact: bool| {
            mb.iter().copied().find(|&m| {
                let (e, a) = delta_of(da(m));
                let v = if exact { e } else { a };
                v.iter().flatten().any(|x| x.abs() > 0.15)
            })
        };
        let (me, ma) = (first(true), first(false));
        s.figure(
            "fig000_9b_sensitivity_vs_ball_mass",
            Plot {
                title: "000 Fig. 9b: relative change of the angular critical speeds against m̄".into(),
                x_label: "m̄ = n m / M_s".into(),
                y_label: "δΩ_Kα1,2".into(),
                series: curves(&mb, &da),
                x_range: Some((0.0, 0.1)),
                y_range: Some((-0.4, 0.6)),
                vlines: vec![(0.05, "base case".into()), (0.036, "000: 0.036".into())],
                ..Default::default()
            },
            format!(
                "000 Fig. 9b: the same against the balls' mass m̄, the other base values kept (m̄0 = 0.025, R̄0 = R̄ = 2, D_A = 0.5, so ΔĀ = 0.05 + m̄ by eq (17); the paper does not say which values it kept). The criterion |δΩ_Kα| &gt; 0.15 is met from m̄ = {} (exact) or {} (eq (22)), not from the paper's m̄ = 0.036. By the exact tensor the base case is isotropic and δΩ_Kα = 0.",
                me.map_or("—".into(), |m| fmt(m, 2)),
                ma.map_or("—".into(), |m| fmt(m, 2))
            ),
        );
    }
    Ok(Some(s))
}
