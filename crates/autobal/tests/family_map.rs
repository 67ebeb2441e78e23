//! Families in maps (issue 18 item 1): a map cell whose balanced states form a family (n ≥ 3
//! balls) says whether all, some or none of the members are stable, against the speed scan's
//! all/some ranges (a second route through the same machinery, sampled finer) and, near the
//! all/some boundary, against SymPy/NumPy eigenvalues along the closed-form balancing set (an
//! independent parameterisation of the family and an independent linearisation).

mod common;

use autobal::control::Control;
use autobal::rotor_map::{general_map, FamilyVerdict, GeneralCell, Verdict};
use autobal::rotor_stability::{stability_over_speed, Rotor};
use autobal::spatial::map::Axis;
use common::{planar_case, python_with, sympy_linearisation};
use num_complex::Complex64;
use std::f64::consts::PI;
use toml::Table;

/// examples/planar.toml (paper 004's rotor) with the race centred and three balls: the
/// Jeffcott rotor whose family's some/all ranges start at 300.41 and 307.08 rad/s.
fn three_ball_root() -> Table {
    let mut root = autobal::config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
    autobal::config::set_number(&mut root, "planar.s2", 0.0).unwrap();
    autobal::config::set_number(&mut root, "planar.n", 3.0).unwrap();
    root
}

/// The map's cells at the speeds `speeds` (one row, `c_psi` as in the config).
fn map_row(root: &Table, speeds: &[f64]) -> Vec<GeneralCell> {
    let x = Axis { path: "omega".into(), values: speeds.to_vec() };
    let y = Axis { path: "planar.c_psi".into(), values: vec![0.1] };
    let mut rows = vec![];
    let out = general_map(root, &x, &y, None, &Control::none(), &mut |_, r| {
        rows.push(r.to_vec());
        true
    })
    .unwrap();
    assert_eq!(out.families, speeds.len(), "{out:?}");
    rows.remove(0)
}

/// The speed scan's family ranges of the same rotor: (all members stable from, some from).
fn scan_ends(root: &Table) -> (f64, f64) {
    let p = autobal::config::planar(root).unwrap().rotor;
    let wn = p.natural_frequency();
    let speeds: Vec<f64> = (0..=25).map(|i| wn * (0.9 + 0.02 * i as f64)).collect();
    let r = stability_over_speed(&Rotor::Planar(p), &speeds).unwrap();
    let fam = r.family.unwrap();
    assert_eq!((fam.all_members_stable.len(), fam.some_members_stable.len()), (1, 1), "{fam:?}");
    let (all, some) = (fam.all_members_stable[0], fam.some_members_stable[0]);
    assert!(all.from_is_boundary && some.from_is_boundary && all.to > 1.3 * wn && some.to > 1.3 * wn);
    (all.from, some.from)
}

#[test]
fn a_map_cell_says_what_the_speed_scans_family_says_at_the_same_parameters() {
    // The speed scan follows the family at steps of 0.1 (scaled arclength) and locates where
    // its largest and smallest abscissa cross 0: some members stable from 300.41 rad/s, all
    // from 307.08. The map follows it at 0.3 with the extremes refined, so the two locate
    // those ends within ~1e-3 rad/s of each other (the scan's own sampling moves them by
    // ~1e-3: docs/notes/stability.md); every speed here is at least 0.1 rad/s from both ends, so a
    // disagreement is a wrong verdict, not resolution.
    let root = three_ball_root();
    let (all, some) = scan_ends(&root);
    assert!((some - 300.41).abs() < 0.01 && (all - 307.08).abs() < 0.01, "some from {some}, all from {all}");
    let speeds = [250.0, 290.0, 300.0, 300.6, 302.0, 305.0, 306.9, 307.3, 310.0, 330.0, 380.0];
    let cells = map_row(&root, &speeds);
    let mut seen = [0; 3];
    for (w, c) in speeds.iter().zip(&cells) {
        assert!((w - all).abs() >= 0.1 && (w - some).abs() >= 0.1, "{w} is too near an end to test the verdict");
        let expected = if *w > all {
            FamilyVerdict::AllStable
        } else if *w > some {
            FamilyVerdict::SomeStable
        } else {
            FamilyVerdict::NoneStable
        };
        assert_eq!(c.family, Some(expected), "at {w} rad/s: {c:?}");
        assert_eq!(c.family_dimension, 1);
        seen[expected as usize] += 1;
        // the member's own margin lies within the family's range, and its verdict is its sign's
        assert!(c.family_min_margin <= c.margin + 1e-12 && c.margin <= c.family_max_margin + 1e-12, "{c:?}");
        assert_eq!(c.verdict == Some(Verdict::Stable), c.margin < 0.0, "{c:?}");
        // the family's verdict follows the signs of its extremes
        assert_eq!(c.family_max_margin < 0.0, expected == FamilyVerdict::AllStable, "{c:?}");
        assert_eq!(c.family_min_margin < 0.0, expected != FamilyVerdict::NoneStable, "{c:?}");
    }
    assert!(seen.iter().all(|&k| k > 0), "all three verdicts occur: {seen:?}");
}

/// The abscissa of a spectrum without its eigenvalue nearest 0 (the family's structural zero).
fn abscissa_without_zero(l: &[Complex64]) -> f64 {
    let z = (0..l.len()).min_by(|&a, &b| l[a].norm().total_cmp(&l[b].norm())).unwrap();
    (0..l.len()).filter(|&i| i != z).map(|i| l[i].re).fold(f64::NEG_INFINITY, f64::max)
}

/// The closed-form balancing set of three equal balls, sampled: the disk on the axis and
/// `Σ e^{iψ_j} = b`, `b = −m1 s1/(m3 r)`. Given `ψ_1` the other two are
/// `arg w ± acos(|w|/2)`, `w = b − e^{iψ_1}`, which exists for `ψ_1 ∈ arg b ± acos((|b|² − 3)/(2|b|))`;
/// `ψ_1 = arg b + half · sin t` with `t` uniform puts the samples about evenly along the
/// family near the ends of that span too (where `ψ_2, ψ_3` turn). Swapping `ψ_2` and `ψ_3` is a
/// relabelling of equal balls (the same eigenvalues), so one sign covers the family.
fn closed_form_family(p: &autobal::planar::PlanarRotor, samples: usize) -> Vec<Vec<f64>> {
    let b = Complex64::new(-p.m1 * p.s1 / (p.m3 * p.r), 0.0);
    let half = ((b.norm_sqr() - 3.0) / (2.0 * b.norm())).acos();
    (0..samples)
        .map(|i| {
            let t = -0.5 * PI + PI * i as f64 / (samples - 1) as f64;
            let psi1 = b.arg() + half * t.sin();
            let w = b - Complex64::from_polar(1.0, psi1);
            let a = (0.5 * w.norm()).min(1.0).acos();
            let mut x = vec![0.0; 10];
            x[2..5].copy_from_slice(&[psi1, w.arg() + a, w.arg() - a]);
            x
        })
        .collect()
}

/// SymPy's linearisation (tests/planar_linearisation.py) at each state: the eigenvalues and
/// the right-hand side.
fn sympy(python: &str, p: &autobal::planar::PlanarRotor, omega: f64, xs: &[Vec<f64>]) -> Vec<(Vec<Complex64>, Vec<f64>)> {
    sympy_linearisation(python, &xs.iter().map(|x| planar_case(p, omega, x)).collect::<Vec<_>>())
}

#[test]
fn near_the_all_some_boundary_a_cell_agrees_with_sympy_eigenvalues_along_the_family() {
    // Cells 0.05 rad/s either side of the all-members-stable end (307.08 rad/s): the map says
    // "some" below and "all" above. Independently, the closed-form balancing set sampled at 601
    // members and SymPy's Lagrangian linearisation of each: the largest abscissa over the
    // family (structural zero removed) is > 0 below and < 0 above, and equals the map's
    // family_max_margin. Tolerance 1e-3 1/s: the dense sampling's spacing in ψ_1 is at most
    // 0.009 rad, so its maximum is low by at most α''·(0.0045)²/2 ≈ 1e-4 (|α''| ≲ 10 1/s per
    // rad² along the family); the map's parabolic refinement from a step of 0.3 is off by a
    // like amount; while |α| at the cells is ~0.4 1/s per rad/s · 0.05 = 0.02, 20x the tolerance.
    let Some(python) = python_with(&["sympy", "numpy"]) else { return };
    let root = three_ball_root();
    let p = autobal::config::planar(&root).unwrap().rotor;
    let (all, _) = scan_ends(&root);
    let speeds = [all - 0.05, all + 0.05];
    let cells = map_row(&root, &speeds);
    assert_eq!(cells[0].family, Some(FamilyVerdict::SomeStable), "{:?}", cells[0]);
    assert_eq!(cells[1].family, Some(FamilyVerdict::AllStable), "{:?}", cells[1]);
    let members = closed_form_family(&p, 601);
    for (w, c) in speeds.iter().zip(&cells) {
        let theirs = sympy(&python, &p, *w, &members);
        let s = autobal::analysis::VectorField::scales(&autobal::planar::field::PlanarField::new(&p, *w).unwrap());
        let mut hi = f64::NEG_INFINITY;
        let mut lo = f64::INFINITY;
        for (x, (l, rhs)) in members.iter().zip(&theirs) {
            let rho = l.iter().map(|e| e.norm()).fold(0.0, f64::max);
            // each sample is balanced in their equations too (to round-off of the largest term)
            assert!(rhs.iter().zip(&s).all(|(v, s)| v.abs() <= 1e-9 * s * rho), "ψ = {:?} is not stationary in their equations: {rhs:?}", &x[2..5]);
            let a = abscissa_without_zero(l);
            hi = hi.max(a);
            lo = lo.min(a);
        }
        assert!((hi - c.family_max_margin).abs() <= 1e-3, "at {w}: SymPy's largest abscissa {hi}, the map's {}", c.family_max_margin);
        if c.family == Some(FamilyVerdict::AllStable) {
            assert!(hi < -1e-2, "at {w}: SymPy's largest abscissa {hi}");
        } else {
            assert!(hi > 1e-2 && lo < 0.0, "at {w}: SymPy's abscissae span [{lo}, {hi}]");
        }
    }
}

/// Instruction counts per cell (docs/notes/stability.md, "Families in maps"): `valgrind
/// --tool=callgrind` on this test alone, `--ignored`. 20 cells of the three-ball Jeffcott rotor.
#[test]
#[ignore]
fn cost_of_twenty_three_ball_cells() {
    let root = three_ball_root();
    let speeds: Vec<f64> = (0..20).map(|i| 280.0 + 5.0 * i as f64).collect();
    let cells = map_row(&root, &speeds);
    assert!(cells.iter().all(|c| c.family.is_some()));
}
