//! A family's extremes include its bunched members (session 24). With four equal balls in one
//! plane (paper 000's base case, `m = 0.04`) the balanced states form a two-parameter family
//! whose least stable member at Ω = 2.12 is a corner: three balls bunched (the closed form's
//! member of largest inertia anisotropy, growing at +3.5759e-3 per unit τ), which the 40 members
//! a map cell draws (and the compass search from them) missed, so the cell read `all_stable`.
//! The family's sample is now seeded with every placement of each plane's balls in two
//! coinciding groups that keeps the balancing condition
//! (`autobal::rotor_stability::bunched_members`).

use autobal::analysis::{stationary, FamilyVerdict, NewtonOptions, VectorField};
use autobal::control::Control;
use autobal::rotor_map::general_map;
use autobal::rotor_stability::{bunched_members, stability_over_speed, Rotor};
use autobal::spatial::map::Axis;
use std::f64::consts::TAU;
use toml::Table;

/// Paper 000's base case (the embedded default config) with four balls of `m = 0.04`.
fn root() -> Table {
    let mut root = autobal::config::parse(autobal::config::DEFAULT_SPATIAL, "default").unwrap();
    // the run's tables do not describe the rotor (and `drive.psi0` counts the balls)
    for t in ["drive", "initial"] {
        root.remove(t);
    }
    autobal::config::set_number(&mut root, "dimensionless.n", 4.0).unwrap();
    autobal::config::set_number(&mut root, "dimensionless.m", 0.04).unwrap();
    root
}

/// The closed form's member (`anisotropy.ball_angles`, relative to the unbalance, found by
/// paper 000's exact-interval search, [`autobal::spatial::inertia::exact_interval`]: Nelder–Mead
/// over the balancing configurations) against the bunched members built from the member Newton
/// reaches: one of them is it. The search leaves its three bunched balls spread by 8.6e-9 rad
/// about their common angle (spreading them changes the resultant only to second order, which
/// it cannot see), so each ball is compared to 1e-8 rad, and the sum of the four angles, which
/// the spread leaves (the balls' mean angle and the lone ball: measured 1e-15 from the
/// triangle's), to 1e-12 (round-off of `acos`, `atan2` and the unbalance's angle, ~1e-15 each).
#[test]
fn a_bunched_member_is_the_closed_forms_member() {
    let root = root();
    let sim = autobal::config::spatial_simulation(&root).unwrap();
    let u = sim.rotor.unbalances[0].angle;
    let reference: Vec<f64> = sim.config.model.anisotropy.ball_angles.clone().unwrap().iter().map(|a| a + u).collect();
    // three bunched, one apart (the corner of largest anisotropy)
    assert_eq!(reference.len(), 4);
    let rotor = Rotor::Spatial(sim.rotor);
    let f = rotor.field(2.12).unwrap();
    let member = stationary(&f, &Rotor::guess(&f).unwrap(), &NewtonOptions::default()).unwrap();
    assert_eq!(member.family_dimension, 2);
    let m = f.dim() / 2;
    let psi = |x: &[f64]| -> Vec<f64> {
        let mut v: Vec<f64> = x[m - 4..m].iter().map(|a| a.rem_euclid(TAU)).collect();
        v.sort_by(f64::total_cmp);
        v
    };
    let mut want: Vec<f64> = reference.iter().map(|a| a.rem_euclid(TAU)).collect();
    want.sort_by(f64::total_cmp);
    let seeds = bunched_members(&f, &member.x);
    // four equal balls: groups of 1 + 3 (two mirrors) and 2 + 2 (one: its mirror is a
    // relabelling)
    assert_eq!(seeds.len(), 3, "{seeds:?}");
    let sum = |x: &[f64]| x[m - 4..m].iter().fold((0.0, 0.0), |(c, s), a| (c + a.cos(), s + a.sin()));
    let c0 = sum(&member.x);
    let mut best = (f64::INFINITY, f64::INFINITY);
    for x in &seeds {
        // each keeps the balancing condition (so the rotor's coordinates are the member's)
        let c = sum(x);
        assert!((c.0 - c0.0).hypot(c.1 - c0.1) < 1e-12, "{x:?}");
        assert_eq!(&x[..m - 4], &member.x[..m - 4]);
        // (no angle near 0 or 2π here: sorted in [0, 2π) the balls pair up in order)
        let got = psi(x);
        let d = got.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        if d < best.0 {
            best = (d, (got.iter().sum::<f64>() - want.iter().sum::<f64>()).abs());
        }
    }
    assert!(best.0 < 1e-8 && best.1 < 1e-12, "nearest bunched member {best:?} rad from the closed form's {want:?}");
}

/// A map cell at Ω = 2.12 (the general route) is no longer `all_stable`: its least stable
/// member is the bunched one, `+3.5759e-3` by the closed form (paper 000's 12-state model at
/// that member: `autobal stability --set dimensionless.n=4 --set dimensionless.m=0.04`, the
/// last point of `--omega-max 2.12`; tests/family_extremes_23.rs of the CLI reads it so),
/// to 1e-7 (the printed reference's rounding, 5e-8, and the general route's eigenvalues of its
/// own linearisation at the same state, ~1e-10). On the code before,
/// 40 draws and the compass search from them reached −1.18e-2 ... all members stable.
#[test]
fn a_map_cell_at_2_12_finds_its_bunched_member_growing() {
    let x = Axis { path: "omega".into(), values: vec![2.12] };
    let y = Axis { path: "dimensionless.m".into(), values: vec![0.04] };
    let mut rows = vec![];
    general_map(&root(), &x, &y, None, &Control::none(), &mut |_, r| {
        rows.push(r.to_vec());
        true
    })
    .unwrap();
    let cell = rows[0][0];
    assert_eq!(cell.family_dimension, 2, "{cell:?}");
    assert_eq!(cell.family, Some(FamilyVerdict::SomeStable), "{cell:?}");
    let reference = 3.5759e-3;
    assert!((cell.family_max_margin - reference).abs() < 1e-7, "{cell:?}");
}

/// The speed scan's "all members stable" range starts where the bunched member's own range
/// starts, 2.143786 (the closed form's member: `autobal stability --set dimensionless.n=4 --set
/// dimensionless.m=0.04`, its range 2.143786-2.176456), to 1e-4 in Ω: the end is located to
/// 1e-9 relative where the family's largest abscissa crosses 0, and that is the bunched
/// member's (the code before: 2.13934 on the default grid, 2.14359 on session 23's). Two grid
/// speeds bracket it (2.13: the bunched member grows; 2.16: every member decays).
#[test]
fn the_scans_all_members_range_starts_at_the_bunched_members_end() {
    let sim = autobal::config::spatial_simulation(&root()).unwrap();
    let r = stability_over_speed(&Rotor::Spatial(sim.rotor), &[2.13, 2.16]).unwrap();
    let fam = r.family.expect("a family");
    assert_eq!(fam.dimension, 2);
    assert_eq!(fam.all_members_stable.len(), 1, "{fam:?}");
    let all = fam.all_members_stable[0];
    assert!(all.from_is_boundary, "{all:?}");
    assert!((all.from - 2.143786).abs() < 1e-4, "all members stable from {} against the bunched member's 2.143786", all.from);
    // every point says how many members it analysed: the member given, the draws Newton kept,
    // the bunched members (3) and the search's
    for p in &r.points {
        let f = p.family.as_ref().unwrap();
        assert_eq!(f.drawn, 199);
        assert_eq!(f.bunched, 3);
        assert!(f.members <= 1 + f.drawn + f.bunched + f.searched, "{f:?}");
    }
    let [lo, hi] = fam.members_analysed.unwrap();
    let words = if lo == hi { format!("{lo} members analysed") } else { format!("{lo}-{hi} members analysed") };
    assert!(lo <= hi && fam.parameterisation.contains(&words), "{}", fam.parameterisation);
}
