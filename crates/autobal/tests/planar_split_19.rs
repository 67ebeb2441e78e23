//! The planar rotor with three balls, an eccentric race and supports that differ by direction
//! (session 19's audit, its F3): the family of balanced states breaks into isolated periodic
//! orbits with the balls in two groups, which the speed scan reaches from the two-group
//! placements ([`Rotor::planar_split_orbits`]) where its other starts find no state.

use autobal::analysis::{NewtonOptions, Verdict};
use autobal::planar::{simulate, Drive, PlanarRotor, Settings};
use autobal::rotor_stability::{stability_over_speed, Rotor};

/// examples/planar.toml (paper 004's rotor) with `n = 3` and `k_x = 9.0e4`, `k_y = 1.2e5` N/m:
/// the audit's pk.toml.
fn rotor() -> PlanarRotor {
    PlanarRotor { n: 3, k: 9.0e4, k_y: Some(1.2e5), ..PlanarRotor::paper() }
}

/// The audit's stable orbit at 400 rad/s from its own fixed-axes model (/tmp/audit19/py/planar.py,
/// shooting over a whole revolution with DOP853 at rtol 1e-11, residual 2e-11): the ball angles
/// at phase 0 and the largest Floquet exponent (1/s).
const AUDIT_PSI: [f64; 3] = [3.679672, 3.679672, 1.428152];
const AUDIT_EXPONENT: f64 = -3.3232e-5;

fn gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// Whether `psi` matches `want` ball for ball within `tol` rad in some order (the balls are
/// alike).
fn same_up_to_order(psi: &[f64], want: &[f64], tol: f64) -> bool {
    let mut used = vec![false; want.len()];
    psi.len() == want.len()
        && psi.iter().all(|&x| match want.iter().enumerate().position(|(j, &y)| !used[j] && gap(x, y) <= tol) {
            Some(j) => {
                used[j] = true;
                true
            }
            None => false,
        })
}

#[test]
fn the_scan_finds_the_audits_stable_two_group_orbit_at_400_rad_s() {
    let p = rotor();
    let w = 400.0;
    let out = stability_over_speed(&Rotor::Planar(p.clone()), &[w]).unwrap();
    let pt = &out.points[0];
    assert!(pt.failure.is_none(), "{:?}", pt.failure);
    // ball angles within 1e-3 rad of the audit's (its orbit is printed to 1e-6 rad; the two
    // shootings agree far closer than that, so 1e-3 only allows for the balls' order)
    assert!(same_up_to_order(&pt.member_psi, &AUDIT_PSI, 1e-3), "{:?} vs {AUDIT_PSI:?}", pt.member_psi);
    assert_eq!(pt.verdict, Some(Verdict::Stable));
    // the exponent: the audit's multiplier 0.99999948 over its period 2π/400 s comes from a
    // monodromy by central differences (steps 1e-6 of the scales, flows at rtol 1e-11), good to
    // ~1e-8 in μ, i.e. ~1e-6 1/s in the exponent (μ − 1 = −5.2e-7 is itself small); autobal's
    // shooting (rtol 1e-10, multipliers near 1 good to ~1e-9 over π/400 s: ~1e-7 1/s). 1e-6 1/s
    // (3 %) holds both and still tells the orbit from the unstable mirror (+3.6e-5 1/s) and
    // from the next multiplier's −4.08 1/s
    let a = pt.abscissa.unwrap();
    assert!((a - AUDIT_EXPONENT).abs() < 1e-6, "exponent {a:e} vs the audit's {AUDIT_EXPONENT:e}");
}

#[test]
fn the_split_orbits_are_the_stable_one_and_its_unstable_mirror() {
    // every placement: the audit's two orbits, the stable one first
    let p = rotor();
    let f = Rotor::Planar(p).field(400.0).unwrap();
    let orbits = Rotor::planar_split_orbits(&f, &NewtonOptions::default());
    assert!(orbits.len() >= 2, "{} orbits", orbits.len());
    assert!(same_up_to_order(&orbits[0].1.member_psi, &AUDIT_PSI, 1e-3), "{:?}", orbits[0].1.member_psi);
    assert_eq!(orbits[0].1.verdict, Verdict::Stable);
    // the audit's unstable orbit, exponent +3.6e-5 1/s (same tolerance as above)
    let mirror = orbits.iter().find(|(_, o)| same_up_to_order(&o.member_psi, &[2.6483, 2.6483, 4.9002], 1e-3)).expect("the unstable orbit");
    assert_eq!(mirror.1.verdict, Verdict::Unstable);
    assert!((mirror.1.abscissa - 3.6e-5).abs() < 1.5e-6, "{:e}", mirror.1.abscissa);
}

#[test]
fn a_constant_speed_run_started_there_ends_balanced() {
    // second route: the free rotor's simulation at 400 rad/s, the balls started at rest at the
    // orbit's angles (the rotor at rest on the axis, as the audit's `simulate` run), settles
    // balanced within 30 s, the balls within 5e-3 rad of the orbit (the audit saw 5e-4)
    let p = rotor();
    let w = 400.0;
    let out = stability_over_speed(&Rotor::Planar(p.clone()), &[w]).unwrap();
    let psi = out.points[0].member_psi.clone();
    assert_eq!(psi.len(), 3, "{:?}", out.points[0].failure);
    let settings = Settings { psi0: psi.clone(), ..Settings::new(&p, 30.0) };
    let mut last = None;
    let s = simulate(&p, &Drive::Speed { omega0: w }, &settings, |x| {
        last = Some(x.psi.clone());
        true
    })
    .unwrap();
    assert!(s.balanced, "residual {}", s.residual_unbalance);
    let end = last.unwrap();
    assert!(same_up_to_order(&end, &psi, 5e-3), "{end:?} vs {psi:?}");
}

#[test]
fn a_map_row_finds_the_scans_two_group_orbits() {
    // the map's cells take the scan's last resort too: a row over the speed on that rotor has a
    // state in every cell (main at 3c9afab: none in any), the verdict and growth rate of the
    // scan's point at the same speed
    use autobal::paths::Axis;
    use autobal::rotor_map::general_map;
    let text = include_str!("../../../examples/planar.toml").replace("k = 104509.44", "k_x = 9.0e4\nk_y = 1.2e5");
    let mut root = autobal::config::parse(&text, "pk").unwrap();
    autobal::config::set_number(&mut root, "planar.n", 3.0).unwrap();
    let speeds = vec![350.0, 400.0, 500.0, 600.0];
    let x = Axis { path: "omega".into(), values: speeds.clone() };
    let y = Axis { path: "planar.c".into(), values: vec![50.0] };
    let mut cells = vec![];
    general_map(&root, &x, &y, None, &autobal::control::Control::none(), &mut |_, r| {
        cells.extend_from_slice(r);
        true
    })
    .unwrap();
    let scan = stability_over_speed(&Rotor::Planar(rotor()), &speeds).unwrap();
    for (c, p) in cells.iter().zip(&scan.points) {
        assert_eq!(c.verdict, p.verdict, "{} rad/s: map {c:?}, scan {p:?}", p.omega);
        // the same orbit shot with the same options (the planar map's margins are in 1/s):
        // equal to the shooting's accuracy, ~1e-7 1/s on these rates of ~1e-5
        let a = p.abscissa.unwrap();
        assert!((c.margin - a).abs() <= 1e-7, "{} rad/s: map {}, scan {a}", p.omega, c.margin);
    }
}

#[test]
fn the_scan_lists_the_unstable_mirror_beside_the_stable_orbit() {
    // audit 25's F3: the scan analysed the stable two-group orbit and said nothing of its
    // unstable mirror. Now every placement is shot at each speed, the least growth rate
    // analysed and the others listed in `other_orbits`. References from the auditors' own
    // fixed-axes models, not autobal: audit 19's rotor at 400 rad/s (stable −3.3232e-5, mirror
    // +3.6e-5 1/s: its central-difference monodromy is good to ~1e-6 1/s) and audit 25's A3
    // (eccentric race at γ = 0.7, supports 8e4/1.3e5 N/m with damping 30/70 N s/m, three
    // 20 g balls, c_ψ = 0.1) at 332.609 rad/s (its complex-step monodromy at rtol 1e-12: good
    // to ~2e-9 1/s): −9.480489e-5 and its mirror +9.565373e-5. autobal's shooting (rtol 1e-10
    // over half a revolution) is good to ~1e-7 1/s; the two orbits differ by 7e-5 (400 rad/s)
    // and 1.9e-4 1/s (332.6 rad/s), so these tolerances tell them apart.
    let a3 = PlanarRotor {
        n: 3,
        m3: 0.02,
        c_psi: 0.1,
        s2: 5e-4,
        gamma: 0.7,
        r: 0.06,
        k: 8.0e4,
        k_y: Some(1.3e5),
        c: 30.0,
        c_y: Some(70.0),
        c_theta: 0.0,
        i_g: 0.0025,
        ..PlanarRotor::paper()
    };
    for (p, w, stable, mirror, tol) in [(rotor(), 400.0, AUDIT_EXPONENT, 3.6e-5, 1.5e-6), (a3, 332.609, -9.480489e-5, 9.565373e-5, 1e-7)] {
        let out = stability_over_speed(&Rotor::Planar(p), &[w]).unwrap();
        let pt = &out.points[0];
        assert_eq!(pt.verdict, Some(Verdict::Stable), "{w} rad/s: {pt:?}");
        assert!((pt.abscissa.unwrap() - stable).abs() < tol, "{w} rad/s: analysed {:e} vs {stable:e}", pt.abscissa.unwrap());
        assert_eq!(pt.other_orbits.len(), 1, "{w} rad/s: {:?}", pt.other_orbits);
        let o = &pt.other_orbits[0];
        assert_eq!(o.verdict, Verdict::Unstable);
        assert!((o.abscissa - mirror).abs() < tol, "{w} rad/s: mirror {:e} vs {mirror:e}", o.abscissa);
    }
}

#[test]
fn four_balls_map_cells_and_the_campbell_diagram_take_the_scans_orbit() {
    // review 25b: with four balls (audit 25's A3 with n = 4, m3 = 15 g) the scan analyses the
    // stable 3+1 orbit (−6.777178e-5 1/s at 332.609 rad/s by the auditor's own monodromy, the
    // 2+2 orbit +5.353e-5 and the other 3+1 +6.827e-5), while the map's cells and the
    // Campbell diagram continued onto the unstable 2+2 orbit. Now all three take the orbit of
    // least growth rate: the same verdicts, margins equal to the shooting's ~1e-7 1/s, and the
    // diagram's largest non-structural real part the scan's abscissa to that accuracy.
    use autobal::paths::Axis;
    use autobal::rotor_map::general_map;
    let text = "[planar]\nm1 = 1.0\nm2 = 0.2\nn = 4\nm3 = 0.015\nc_psi = 0.1\ns1 = 0.003\ns2 = 0.0005\ngamma = 0.7\nr = 0.06\nk_x = 8.0e4\nk_y = 1.3e5\nc_x = 30.0\nc_y = 70.0\nc_theta = 0.0\ni_g = 0.0025\n";
    let root = autobal::config::parse(text, "a4b").unwrap();
    let p = autobal::config::planar_rotor_for_analysis(&root).unwrap();
    let speeds = vec![332.609, 400.0, 600.0];
    let scan = stability_over_speed(&Rotor::Planar(p.clone()), &speeds).unwrap();
    assert!((scan.points[0].abscissa.unwrap() + 6.777178e-5).abs() < 1e-7, "{:?}", scan.points[0].abscissa);
    let x = Axis { path: "omega".into(), values: speeds.clone() };
    let y = Axis { path: "planar.c_psi".into(), values: vec![0.1] };
    let mut cells = vec![];
    general_map(&root, &x, &y, None, &autobal::control::Control::none(), &mut |_, r| {
        cells.extend_from_slice(r);
        true
    })
    .unwrap();
    for (c, q) in cells.iter().zip(&scan.points) {
        assert_eq!(c.verdict, q.verdict, "{} rad/s: map {c:?}, scan {q:?}", q.omega);
        assert!((c.margin - q.abscissa.unwrap()).abs() <= 1e-7, "{} rad/s: map {}, scan {:?}", q.omega, c.margin, q.abscissa);
    }
    let camp = autobal::rotor_campbell::campbell_over_speed(&Rotor::Planar(p), &speeds).unwrap();
    for (i, q) in scan.points.iter().enumerate() {
        let top = camp.lines.iter().filter_map(|l| l.points[i].as_ref()).filter(|e| !e.structural).map(|e| e.re).fold(f64::NEG_INFINITY, f64::max);
        assert!((top - q.abscissa.unwrap()).abs() <= 1e-7, "{} rad/s: campbell {top}, scan {:?}", q.omega, q.abscissa);
    }
}
