//! Parameter studies of papers 000 (Figs 4-8) and 003 (Figs 3-5), around the configured model.

use crate::plot::{Plot, Series, Shade, PALETTE};
use autobal::spatial::critical_speeds::{critical_speeds_at, ModeKind};
use autobal::spatial::inertia::{anisotropy, AnisotropyMethod, BallSet};
use autobal::spatial::params::{identical_support_coefficients, MassSet, SpatialModel};
use autobal::spatial::ranges::{antiresonance_speed, autobalancing_ranges, point_a_response};

/// A named figure with its caption.
pub struct Figure {
    pub file: String,
    pub caption: String,
    pub plot: Plot,
}

fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| a + (b - a) * i as f64 / (n - 1) as f64).collect()
}

const KEYS: [(u8, ModeKind); 4] =
    [(1, ModeKind::Transverse), (2, ModeKind::Transverse), (1, ModeKind::Angular), (2, ModeKind::Angular)];

/// One series per (branch, kind) of critical speeds along a sweep; NaN where a root is absent.
fn crit_series(
    xs: &[f64],
    model_at: &dyn Fn(f64) -> (SpatialModel, f64),
    label: &str,
    colors: [&str; 2],
    dashed: bool,
    angular_only: bool,
) -> Vec<Series> {
    KEYS.iter()
        .filter(|(_, k)| !angular_only || *k == ModeKind::Angular)
        .enumerate()
        .map(|(i, &(branch, kind))| {
            let pts = xs
                .iter()
                .map(|&x| {
                    let (m, d) = model_at(x);
                    let w = critical_speeds_at(&m, d)
                        .into_iter()
                        .find(|r| r.1 == kind && r.2 == branch)
                        .map_or(f64::NAN, |r| r.0);
                    (x, w)
                })
                .collect();
            let name = if i == 0 { label.to_string() } else { String::new() };
            let mut s = Series::new(name, pts, colors[(branch - 1) as usize]);
            s.dashed = dashed;
            s
        })
        .collect()
}

/// The model moved on its supports to `l̄_L` (identical supports: stiffness and damping
/// coefficients from 000 eq (10)).
pub fn with_layout(base: &SpatialModel, l_left: f64) -> SpatialModel {
    let mut m = base.clone();
    let rho = base.rho_s.unwrap_or(0.4);
    let (p, c) = identical_support_coefficients(l_left, rho);
    m.p_alpha_sq = p;
    m.c_y_alpha = c;
    m.l_left = Some(l_left);
    m.damping.h_alpha = m.damping.h_x * p;
    m.damping.h_y_alpha = m.damping.h_x * c;
    m
}

/// Masses for the mass studies: the config's, else 000's base case.
fn masses_of(m: &SpatialModel) -> MassSet {
    m.masses.filter(|x| x.n > 0 && x.m0 > 0.0).unwrap_or(MassSet { m0: 0.025, r0: 2.0, m: 0.05, r: 2.0, n: 2 })
}

/// Speed axis limit: configured, else 1.3 × the highest critical speed or antiresonance.
pub fn omega_limit(m: &SpatialModel, configured: Option<f64>) -> f64 {
    configured.unwrap_or_else(|| {
        let top = critical_speeds_at(m, m.anisotropy.used)
            .iter()
            .map(|r| r.0)
            .chain(antiresonance_speed(m))
            .chain(autobalancing_ranges(m).critical_speeds)
            .fold(1.0, f64::max);
        (1.3 * top).min(50.0)
    })
}

/// Curves for the paper's ΔĀ (eq (17)), the exact tensor's when different, and the isotropic
/// rotor, along a sweep of one layout parameter.
fn three_way(xs: &[f64], base: &SpatialModel, at: &dyn Fn(f64) -> SpatialModel, angular_only: bool) -> Vec<Series> {
    let a = &base.anisotropy;
    let (paper, exact) = (a.paper, a.exact[1]);
    let mut out = crit_series(xs, &|x| (at(x), paper), &format!("ΔĀ = {paper:.4} (eq (17))"), [PALETTE[0], PALETTE[1]], false, angular_only);
    if (paper - exact).abs() > 1e-9 {
        out.extend(crit_series(xs, &|x| (at(x), exact), &format!("ΔĀ = {exact:.4} (exact tensor)"), [PALETTE[2], PALETTE[3]], false, angular_only));
    }
    out.extend(crit_series(xs, &|x| (at(x), 0.0), "isotropic ΔĀ = 0", [PALETTE[7], PALETTE[7]], true, angular_only));
    out
}

fn range_shades(xs: &[f64], model_at: &dyn Fn(f64) -> SpatialModel) -> Vec<Shade> {
    let dx = if xs.len() > 1 { xs[1] - xs[0] } else { 1.0 };
    xs.iter()
        .flat_map(|&x| {
            autobalancing_ranges(&model_at(x)).ranges.into_iter().map(move |r| Shade {
                x: (x - dx / 2.0, x + dx / 2.0),
                y: (Some(r.lo), r.hi),
                color: "#009E73".into(),
            })
        })
        .collect()
}

fn boundary_series(xs: &[f64], model_at: &dyn Fn(f64) -> SpatialModel) -> Vec<Series> {
    let anti = xs.iter().map(|&x| (x, antiresonance_speed(&model_at(x)).unwrap_or(f64::NAN))).collect();
    let mut out = vec![Series::new("Ω_a", anti, PALETTE[3])];
    for (i, label) in [(1usize, "Ω_K2"), (3, "Ω_K4")] {
        // upper member of each split pair: roots of Δ2 (ΔĪ02)
        let pts = xs
            .iter()
            .map(|&x| {
                let m = model_at(x);
                let r = critical_speeds_at(&m, m.delta_a0);
                let d2: Vec<f64> = r.iter().filter(|q| q.2 == 2).map(|q| q.0).collect();
                (x, d2.get(i / 2).copied().unwrap_or(f64::NAN))
            })
            .collect();
        out.push(Series::new(label, pts, if i == 1 { PALETTE[0] } else { PALETTE[1] }));
    }
    // isotropic angular critical speed for comparison (003 Fig. 4, dashed)
    let iso = xs
        .iter()
        .map(|&x| {
            let m = model_at(x);
            (x, critical_speeds_at(&m, 0.0).into_iter().find(|q| q.1 == ModeKind::Angular).map_or(f64::NAN, |q| q.0))
        })
        .collect();
    out.push(Series::new("Ω_Kα, ΔĀ0 = 0", iso, PALETTE[7]).dashed());
    out
}

/// All figures of the report.
pub fn all(base: &SpatialModel, omega_max: Option<f64>) -> Vec<Figure> {
    let wmax = omega_limit(base, omega_max);
    let n = 241;
    let mut figs = vec![];
    let ms = masses_of(base);

    // 000 Fig. 4: ΔĀ vs m̄ for D_A = 0, 0.5, 1, plus the exact tensor for n = 2 and n = 3
    let mbar = linspace(0.0, 0.1, 101);
    let mut series: Vec<Series> = [0.0, 0.5, 1.0]
        .iter()
        .enumerate()
        .map(|(i, &d)| {
            Series::new(
                format!("eq (17), D_A = {d}"),
                mbar.iter().map(|&m| (m, 0.5 * ms.a_m0() + 0.5 * m * ms.r * ms.r * d)).collect(),
                PALETTE[i],
            )
        })
        .collect();
    let set_at = |m: f64, n: u32| {
        let s = MassSet { m, n, ..ms };
        BallSet { n, ..s.ball_set() }
    };
    series.push(Series::new(
        "exact, 2 balls",
        mbar.iter()
            .map(|&m| (m, if m > 0.0 { anisotropy(&set_at(m, 2), None, AnisotropyMethod::Exact).map_or(f64::NAN, |a| a.exact[0]) } else { 0.5 * ms.a_m0() }))
            .collect(),
        PALETTE[6],
    ));
    let mbar3 = linspace(0.0, 0.1, 41);
    let three: Vec<[f64; 2]> = mbar3
        .iter()
        .map(|&m| if m > 0.0 { anisotropy(&set_at(m, 3), None, AnisotropyMethod::Exact).map_or([f64::NAN; 2], |a| a.exact) } else { [0.5 * ms.a_m0(); 2] })
        .collect();
    series.push(Series::new("exact, 3 balls: min", mbar3.iter().zip(&three).map(|(&m, v)| (m, v[0])).collect(), PALETTE[4]).dashed());
    series.push(Series::new("exact, 3 balls: max", mbar3.iter().zip(&three).map(|(&m, v)| (m, v[1])).collect(), PALETTE[5]).dashed());
    figs.push(Figure {
        file: "fig000_4_anisotropy_vs_ball_mass.svg".into(),
        caption: format!(
            "000 Fig. 4: anisotropy ΔĀ against the balls' mass m̄ (m̄0 = {}, R̄0 = {}, R̄ = {}). Eq (17) for D_A = 0, 0.5, 1 against the exact inertia tensor of the balls at balance: where the capacity E exceeds √2 the balls' anisotropy opposes the unbalance's and eq (17) overestimates it.",
            ms.m0, ms.r0, ms.r
        ),
        plot: Plot { title: "Inertia anisotropy vs ball mass".into(), x_label: "m̄ = n m / M_s".into(), y_label: "ΔĀ".into(), series, ..Default::default() },
    });

    // 000 Fig. 5a/5b: critical speeds vs C̄Σ, symmetric and overhung
    for (tag, l) in [("a", 0.5), ("b", 1.2)] {
        let cs = linspace(0.1, 2.0, n);
        let at = |c: f64| {
            let mut m = with_layout(base, l);
            m.c_sigma = c;
            m
        };
        figs.push(Figure {
            file: format!("fig000_5{tag}_critical_vs_c_sigma.svg"),
            caption: format!("000 Fig. 5{tag}: critical speeds against the rotor type C̄Σ, l̄_L = {l}. Blue/orange: branches 1/2 (ΔĪ = 1 − C̄Σ ± ΔĀ)."),
            plot: Plot {
                title: format!("Critical speeds vs C̄Σ, l̄_L = {l}"),
                x_label: "C̄Σ".into(),
                y_label: "Ω_K".into(),
                series: three_way(&cs, base, &at, false),
                y_range: Some((0.0, wmax)),
                ..Default::default()
            },
        });
    }

    // 000 Fig. 6: vs l̄_L
    let ls = linspace(-0.5, 1.5, n);
    figs.push(Figure {
        file: "fig000_6_critical_vs_l_left.svg".into(),
        caption: "000 Fig. 6: critical speeds against the position of the rotor on its supports l̄_L (0.5 symmetric, > 1 overhung).".into(),
        plot: Plot {
            title: "Critical speeds vs l̄_L".into(),
            x_label: "l̄_L".into(),
            y_label: "Ω_K".into(),
            series: three_way(&ls, base, &|l| with_layout(base, l), false),
            y_range: Some((0.0, wmax)),
            ..Default::default()
        },
    });

    // 000 Fig. 7: vs ΔĀ
    let ds = linspace(0.0, 0.3, n);
    let mut s7 = crit_series(&ds, &|d| (base.clone(), d), "exact roots of eq (16)", [PALETTE[0], PALETTE[1]], false, false);
    s7.extend(crit_series(&ds, &|_| (base.clone(), 0.0), "isotropic", [PALETTE[7], PALETTE[7]], true, false));
    figs.push(Figure {
        file: "fig000_7_critical_vs_anisotropy.svg".into(),
        caption: format!("000 Fig. 7: critical speeds against the anisotropy ΔĀ at l̄_L = {}.", base.l_left.map_or("?".into(), |l| format!("{l}"))),
        plot: Plot { title: "Critical speeds vs ΔĀ".into(), x_label: "ΔĀ".into(), y_label: "Ω_K".into(), series: s7, y_range: Some((0.0, wmax)), ..Default::default() },
    });

    // 000 Fig. 8: angular critical speeds vs m̄ at capacity E = 2
    let mb = linspace(0.0, 0.1, n);
    let mut s8 = vec![];
    for (i, d) in [0.0, 0.5, 1.0].into_iter().enumerate() {
        // E = 2 → m̄0 R̄0 = m̄ R̄ / 2; ΔĀ = ½ m̄0 R̄0² + ½ m̄ R̄² D_A
        let da = |m: f64| 0.5 * (m * ms.r / 2.0) * ms.r0 + 0.5 * m * ms.r * ms.r * d;
        let mut ss = crit_series(&mb, &|m| (base.clone(), da(m)), &format!("eq (17), D_A = {d}"), [PALETTE[i], PALETTE[i]], false, true);
        s8.append(&mut ss);
    }
    let exact2 = |m: f64| {
        let m0 = m * ms.r / (2.0 * ms.r0);
        let set = BallSet { n: 2, a_m0: m0 * ms.r0 * ms.r0, a_m: m * ms.r * ms.r, capacity: 2.0 };
        anisotropy(&set, None, AnisotropyMethod::Exact).map_or(f64::NAN, |a| a.exact[0])
    };
    s8.extend(crit_series(&mb, &|m| (base.clone(), exact2(m)), "exact tensor, 2 balls", [PALETTE[6], PALETTE[6]], true, true));
    figs.push(Figure {
        file: "fig000_8_angular_critical_vs_ball_mass.svg".into(),
        caption: "000 Fig. 8: angular critical speeds against the balls' mass m̄ at capacity E = 2. For two balls at E = 2 the exact tensor is isotropic: the critical speeds do not split at all (black dashed).".into(),
        plot: Plot { title: "Angular critical speeds vs m̄ (E = 2)".into(), x_label: "m̄".into(), y_label: "Ω_Kα".into(), series: s8, ..Default::default() },
    });

    // 003 Fig. 3: signed amplitude of plane A
    let ws = linspace(0.0, wmax, 1201);
    let asym = {
        let di = 1.0 - base.c_sigma - base.delta_a0;
        ((di + base.z_a * base.z_a) / di).abs()
    };
    let ylim = (3.0 * asym).clamp(2.0, 60.0);
    let pts: Vec<(f64, f64)> = ws
        .iter()
        .map(|&w| {
            let v = point_a_response(base, w);
            (w, if v.abs() > 10.0 * ylim { f64::NAN } else { v })
        })
        .collect();
    let ar = autobalancing_ranges(base);
    let mut vlines: Vec<(f64, String)> = ar.critical_speeds.iter().enumerate().map(|(i, &w)| (w, format!("K{}", i + 1))).collect();
    if let Some(wa) = ar.antiresonance_speed {
        vlines.push((wa, "Ω_a".into()));
    }
    figs.push(Figure {
        file: "fig003_3_signed_response.svg".into(),
        caption: "003 Fig. 3: signed amplitude of plane A of the locked rotor per unit unbalance, ξ̄_A/(m̄0 R̄0). Shaded: speeds where A moves against the unbalance and no split pair is unstable, i.e. where autobalancing is possible.".into(),
        plot: Plot {
            title: "Signed response of plane A".into(),
            x_label: "Ω".into(),
            y_label: "ξ̄_A / (m̄0 R̄0)".into(),
            series: vec![Series::new("ξ̄_A", pts, PALETTE[0])],
            shades: ar.ranges.iter().map(|r| Shade { x: (r.lo, r.hi.unwrap_or(wmax)), y: (None, None), color: "#009E73".into() }).collect(),
            shade_label: Some("autobalancing possible".into()),
            vlines,
            x_range: Some((0.0, wmax)),
            y_range: Some((-ylim, ylim)),
            raster: None,
        },
    });

    // 003 Figs 4, 5a, 5b: range boundaries vs C̄Σ0, z̄_A, ΔĀ0
    let studies: [(&str, &str, &str, Vec<f64>, Box<dyn Fn(f64) -> SpatialModel>); 3] = [
        ("fig003_4_ranges_vs_c_sigma.svg", "003 Fig. 4: where autobalancing is possible (shaded) against the rotor type C̄Σ0.", "C̄Σ0", linspace(0.2, 2.0, 181), Box::new(|c| {
            let mut m = base.clone();
            m.c_sigma = c;
            m
        })),
        ("fig003_5a_ranges_vs_z_a.svg", "003 Fig. 5a: where autobalancing is possible against the position of plane A, z̄_A0.", "z̄_A0", linspace(-2.0, 2.0, 161), Box::new(|z| {
            let mut m = base.clone();
            m.z_a = z;
            m
        })),
        ("fig003_5b_ranges_vs_delta_a0.svg", "003 Fig. 5b: where autobalancing is possible against the unbalance mass's anisotropy ΔĀ0.", "ΔĀ0", linspace(0.0, 0.24, 121), Box::new(|d| {
            let mut m = base.clone();
            m.delta_a0 = d;
            m
        })),
    ];
    for (file, caption, xl, xs, at) in studies {
        figs.push(Figure {
            file: file.into(),
            caption: caption.into(),
            plot: Plot {
                title: format!("Autobalancing ranges vs {xl}"),
                x_label: xl.into(),
                y_label: "Ω".into(),
                series: boundary_series(&xs, &*at),
                shades: range_shades(&xs, &*at),
                shade_label: Some("autobalancing possible".into()),
                y_range: Some((0.0, wmax)),
                x_range: Some((xs[0], *xs.last().unwrap())),
                ..Default::default()
            },
        });
    }
    figs
}
