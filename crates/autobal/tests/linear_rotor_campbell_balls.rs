//! The Campbell diagram of the linear rotor **with its balls** (issue 19, item 4) on the general
//! route (`autobal::rotor_campbell::campbell_over_speed` on `Rotor::Linear`) against second
//! routes: the planar and spatial rotors' own general diagrams on the same rotor (the presets
//! `LinearRotor::from_planar` and `from_spatial`: other equations, other fields, the same
//! linearisation), and, with balls of vanishing mass on a shaft, the structure's diagram
//! without them (`LinearRotor::structure_eigenvalues`, ROSS's `run_campbell`) moved into
//! turning axes.

use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, LinearRotor, Unbalance};
use autobal::planar::PlanarRotor;
use autobal::rotor_campbell::{campbell_over_speed, CampbellPoint, RotorCampbell, Whirl};
use autobal::rotor_stability::Rotor;
use autobal::spatial::dynamics::{BallPlane, PointMass, RigidRotor, SpatialRotor, Support};
use num_complex::Complex64;

fn z(p: &CampbellPoint) -> Complex64 {
    Complex64::new(p.re, p.im)
}

/// The points of the diagram at speed index `k` (every line's).
fn points_at(c: &RotorCampbell, k: usize) -> Vec<CampbellPoint> {
    assert!(c.failures[k].is_none(), "Ω {}: {:?}", c.omega[k], c.failures[k]);
    c.lines.iter().map(|l| l.points[k].expect("a point")).collect()
}

/// Every point of `b` (the linear rotor's) has a partner in `a` (the native model's), one to
/// one, nearest first: the eigenvalue within `1e-9 max(1, |λ|)`, the fixed-axes frequency
/// within `1e-9 max(1, |f|)`, the same whirl label and the same structural flag; the worst
/// relative eigenvalue difference is returned.
fn same_diagram(a: &RotorCampbell, b: &RotorCampbell, what: &str) -> f64 {
    assert_eq!(a.omega, b.omega);
    assert_eq!(a.kind, b.kind, "{what}");
    assert_eq!(a.lines.len(), b.lines.len(), "{what}: the number of states");
    let mut worst = 0.0f64;
    for k in 0..a.omega.len() {
        let (pa, pb) = (points_at(a, k), points_at(b, k));
        let mut used = vec![false; pa.len()];
        for p in &pb {
            let (j, d) = pa.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, q)| (j, (z(q) - z(p)).norm())).min_by(|x, y| x.1.total_cmp(&y.1)).unwrap();
            used[j] = true;
            let q = &pa[j];
            let rel = d / z(p).norm().max(1.0);
            worst = worst.max(rel);
            assert!(rel <= 1e-9, "{what}, Ω {}: λ {} vs {} (relative {rel:e})", p.omega, z(p), z(q));
            let df = (p.fixed_frequency - q.fixed_frequency).abs();
            assert!(df <= 1e-9 * p.fixed_frequency.abs().max(1.0), "{what}, Ω {}: λ {}: f {} vs {}", p.omega, z(p), p.fixed_frequency, q.fixed_frequency);
            assert_eq!(p.whirl, q.whirl, "{what}, Ω {}: λ {} (shares {} and {})", p.omega, z(p), p.forward_share, q.forward_share);
            assert_eq!(p.structural, q.structural, "{what}, Ω {}: λ {}", p.omega, z(p));
        }
    }
    worst
}

/// (a) Paper 004's rotor with its race centred (two and three balls: an isolated balanced state
/// and a family with its structural zero) as the planar model and as the linear rotor
/// (`from_planar`): the same Jeffcott rotor with balls in other coordinates, so the general
/// Campbell diagrams have the same eigenvalues (QR on two 8 × 8 (10 × 10) Jacobians that agree
/// to round-off, after Newton to ~1e-12: observed differences ~1e-13 relative; bound 1e-9), and
/// one whirl pair `x + iy` in both, so the same forward shares, fixed-axes frequencies and
/// labels (the weight of the pair cancels in the share).
#[test]
fn the_jeffcott_preset_has_the_planar_rotors_diagram() {
    let speeds = [150.0, 220.0, 300.0, 400.0, 600.0];
    for n in [2, 3] {
        let p = PlanarRotor { n, s2: 0.0, ..PlanarRotor::paper() };
        let a = campbell_over_speed(&Rotor::Planar(p.clone()), &speeds).unwrap();
        let b = campbell_over_speed(&Rotor::Linear(LinearRotor::from_planar(&p).unwrap()), &speeds).unwrap();
        assert_eq!(b.model, "linear");
        let worst = same_diagram(&a, &b, &format!("{n} balls"));
        eprintln!("{n} balls: worst relative eigenvalue difference {worst:e}");
        // the rotor's modes whirl: some forward and some backward points
        let pts: Vec<CampbellPoint> = (0..speeds.len()).flat_map(|k| points_at(&b, k)).collect();
        assert!(pts.iter().any(|p| p.whirl == Whirl::Forward) && pts.iter().any(|p| p.whirl == Whirl::Backward));
    }
}

/// A rigid rotor on two equal supports (the spatial preset's tests' rotor, `k_x = k_y`), an
/// unbalance mass in the balancer plane (0.15 m) with `balls` balls (one plane; two planes:
/// tests/linear_rotor_two_planes.rs).
fn spatial(balls: usize) -> SpatialRotor {
    let unbalances = vec![PointMass { mass: 0.01, radius: 0.1, angle: 0.4, z: 0.15 }];
    let p = vec![BallPlane { z: 0.15, n: balls, ball_mass: 0.02, race_radius: 0.1, drag: 0.01, physics: Default::default() }];
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.02, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
        supports: vec![Support { z: -0.3, stiffness: [1e5, 1e5], damping: [20.0, 20.0] }, Support { z: 0.4, stiffness: [1.2e5, 1.2e5], damping: [25.0, 25.0] }],
        unbalances,
        planes: p,
        gravity: [0.0; 3],
        spin_drag: 0.0,
        lock_tilt: false,
    }
}

/// (b) The spatial preset (`from_spatial`, equal supports, two and three balls) has the
/// spatial rotor's general Campbell diagram: the two linearisations are the same matrices
/// (tests/linear_rotor_spatial_preset.rs: Jacobians to 1e-9 of their rows, spectra to 1e-10 of
/// the rate), so the eigenvalues agree to 1e-9 relative; the whirl reads the same translation
/// pair and the tilt pair (`θ − iδ` natively, `α + iβ` here: the same circular components, the
/// native tilt weighted by the radius of gyration, here by the mean tilt inertia about the
/// centre of mass), so the labels and fixed-axes frequencies agree wherever a mode is not split
/// evenly between the directions (every mode here: a rigid rotor on isotropic supports whirls
/// circularly in fixed axes).
#[test]
fn the_spatial_preset_has_the_spatial_rotors_diagram() {
    let speeds = [60.0, 90.0, 140.0, 250.0, 400.0];
    for balls in [2, 3] {
        let s = spatial(balls);
        let a = campbell_over_speed(&Rotor::Spatial(s.clone()), &speeds).unwrap();
        let b = campbell_over_speed(&Rotor::Linear(LinearRotor::from_spatial(&s).unwrap()), &speeds).unwrap();
        let worst = same_diagram(&a, &b, &format!("{balls} balls"));
        eprintln!("{balls} balls: worst relative eigenvalue difference {worst:e}");
        let pts: Vec<CampbellPoint> = (0..speeds.len()).flat_map(|k| points_at(&b, k)).collect();
        assert!(pts.iter().any(|p| p.whirl == Whirl::Forward) && pts.iter().any(|p| p.whirl == Whirl::Backward));
    }
}

/// (c) Balls of vanishing mass (`m_b = 1e-9` kg, against a 3 kg disk on a 3.4 kg shaft) on a
/// shaft with a disk on isotropic bearings, gyroscopic: the rotor's branches of the general
/// diagram, moved into fixed axes by their whirl (`λ_fixed = λ_turning + iΩ` where the forward
/// share is at least ½, `− iΩ` else: a circular mode `u e^{λ_f t}` of `x + iy` is
/// `u e^{(λ_f − iΩ) t}` in turning axes), are the structure's eigenvalues without the balls
/// (`structure_eigenvalues`, fixed axes) one to one. The balls (and the unbalance they cancel,
/// `5e-11` kg m) change the structure by `m_b/M ~ 1e-9` relative (the rings' mass `2 m_b` on
/// the disk's node), so the match is to `1e-6 max(1, |λ|)`, a thousand times that and far below
/// the whirl's `2Ω` between the two candidates (a wrong label fails by `2Ω`). The balls' own
/// branches (no drag: `m_b R² ψ̈` against the restoring moment of the rotor's response to the
/// balls' own unbalance, `~ m_b²`) have `|λ|² ~ m_b Ω²·(…)`: below `1e-3` of the lowest
/// structural `|λ|`.
#[test]
fn vanishing_balls_leave_the_structures_diagram_in_turning_axes() {
    let mut b = ShaftBuilder::uniform(3, 0.9, 0.025, 2.1e11, 7800.0);
    b.rotary_inertia = true;
    b.gyroscopic = true;
    b.disks.push(Disk { node: 2, mass: 3.0, id: 0.02, ip: 0.04 });
    b.bearings.push(Bearing { node: 0, k: 1e6, c: 150.0 });
    b.bearings.push(Bearing { node: 3, k: 1e6, c: 150.0 });
    let mut r = b.build().unwrap();
    let mb = 1e-9;
    r.unbalances.push(Unbalance { node: 2, me: 5e-11, phase: 0.3, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.05, balls: 2, ball_mass: mb, drag: 0.0, offset: 0.0 });
    let n = r.dofs();
    let speeds = [50.0, 200.0, 500.0];
    let c = campbell_over_speed(&Rotor::Linear(r.clone()), &speeds).unwrap();
    assert_eq!(c.lines.len(), 2 * (n + 2));
    let mut worst = 0.0f64;
    for (k, &w) in speeds.iter().enumerate() {
        let mut pts = points_at(&c, k);
        pts.sort_by(|a, b| z(a).norm().total_cmp(&z(b).norm()));
        let (balls, rotor) = pts.split_at(4);
        let structure = r.structure_eigenvalues(w).unwrap();
        let lowest = structure.iter().map(|v| v.norm()).fold(f64::INFINITY, f64::min);
        for p in balls {
            assert!(z(p).norm() <= 1e-3 * lowest, "Ω {w}: ball branch λ = {} (lowest structural |λ| {lowest})", z(p));
        }
        let mut used = vec![false; structure.len()];
        for p in rotor {
            let shift = if p.forward_share >= 0.5 { w } else { -w };
            let fixed = z(p) + Complex64::new(0.0, shift);
            // the label reads the dominant component: its frequency is ±Im λ_fixed (the
            // conjugate partner maps to the conjugate structural eigenvalue)
            assert!((p.fixed_frequency.abs() - fixed.im.abs()).abs() <= 1e-9 * w, "Ω {w}: f {} vs λ_fixed {fixed}", p.fixed_frequency);
            let (j, d) =
                structure.iter().enumerate().filter(|(j, _)| !used[*j]).map(|(j, s)| (j, (s - fixed).norm())).min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
            used[j] = true;
            let rel = d / fixed.norm().max(1.0);
            worst = worst.max(rel);
            assert!(rel <= 1e-6, "Ω {w}: λ_turning {} → λ_fixed {fixed}, nearest structural {} (relative {rel:e})", z(p), structure[j]);
            assert_ne!(p.whirl, Whirl::None, "Ω {w}: a structural mode moves the rotor");
        }
    }
    eprintln!("worst relative difference to the structure's eigenvalues: {worst:e}");
}
