//! The whole rotor's mass properties (`SpatialRotor::mass_properties`) against independent
//! results: paper 000's composite inertia (eqs (4)-(5)) on one-plane configs, the tensor about
//! the origin shifted by the parallel-axis theorem, the exact and small-tilt principal-axis tilt
//! of a couple unbalance, and the balanced state of two planes (no residual, no tilt).

use autobal::analysis::VectorField;
use autobal::config;
use autobal::spatial::dynamics::field::SpatialField;
use autobal::spatial::dynamics::{BallPlane, Placement, PointMass, RigidRotor, SpatialRotor, Support};

fn rotor_of(text: &str, sets: &[(&str, &str)]) -> (SpatialRotor, autobal::config::SpatialConfig) {
    let mut root = config::parse(text, "test").unwrap();
    // the run's tables do not describe the rotor (and `drive.psi0` counts the balls)
    for t in ["drive", "initial"] {
        root.remove(t);
    }
    for (k, v) in sets {
        config::set(&mut root, k, config::parse_value(v)).unwrap();
    }
    let sim = config::spatial_simulation(&root).unwrap();
    (sim.rotor, sim.config)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

const DIMENSIONAL: &str = include_str!("../../../examples/dimensional.toml");
const SPATIAL: &str = include_str!("../../../examples/spatial.toml");
const TWO_PLANE: &str = include_str!("../../../examples/spatial_two_plane.toml");

/// One plane, balls at the member paper 000's composite inertia refers to: total mass, polar
/// moment `C_Σ`, equatorial `A_C1 = A_Σ + ΔA`, `A_C2 = A_Σ − ΔA` equal to 1e-12 relative (the
/// two computations differ only in the order of round-off: ~1e-15), and the shaft is a
/// principal axis (one plane balanced: no couple).
#[test]
fn one_plane_equals_paper_000_composite_inertia() {
    let cases: Vec<(&str, Vec<(&str, &str)>)> = vec![
        (DIMENSIONAL, vec![]),
        (DIMENSIONAL, vec![("balancer.balls", "3")]),
        (DIMENSIONAL, vec![("balancer.balls", "5"), ("unbalance.mass", "0.03")]),
        (DIMENSIONAL, vec![("unbalance.angle", "1.1"), ("balancer.balls", "4")]),
        (SPATIAL, vec![]),
        (SPATIAL, vec![("dimensionless.n", "3")]),
    ];
    for (text, sets) in cases {
        let (rotor, cfg) = rotor_of(text, &sets);
        let a = &cfg.model.anisotropy;
        assert_eq!(a.method, autobal::spatial::inertia::AnisotropyMethod::Exact, "{sets:?}");
        let u = rotor.unbalances[0].angle;
        let angles: Vec<f64> = a.ball_angles.as_ref().unwrap().iter().map(|x| x + u).collect();
        let mp = rotor.mass_properties(&angles).unwrap();
        let ci = cfg.model.composite_inertia();
        if let Some(m) = ci.total_mass {
            assert!(rel(mp.total_mass, m) < 1e-12, "{sets:?}: M {} vs {m}", mp.total_mass);
        } else {
            assert!(rel(mp.total_mass, 1.0) < 1e-12, "{sets:?}: dimensionless M_s = 1");
        }
        assert!(rel(mp.polar_moment, ci.c_sigma) < 1e-12, "{sets:?}: C {} vs {}", mp.polar_moment, ci.c_sigma);
        assert!(rel(mp.equatorial_moments[0], ci.a_c1) < 1e-12, "{sets:?}: A_C1 {} vs {}", mp.equatorial_moments[0], ci.a_c1);
        assert!(rel(mp.equatorial_moments[1], ci.a_c2) < 1e-12, "{sets:?}: A_C2 {} vs {}", mp.equatorial_moments[1], ci.a_c2);
        // balanced: centre of mass on the axis, no couple, no tilt
        let scale = rotor.unbalances[0].mass * rotor.unbalances[0].radius;
        assert!(mp.static_unbalance[0].hypot(mp.static_unbalance[1]) < 1e-12 * scale, "{sets:?}");
        assert!(mp.axis_tilt < 1e-12, "{sets:?}: tilt {}", mp.axis_tilt);
    }
}

/// A rotor of hand-chosen numbers, two planes at arbitrary ball angles: the tensor about the
/// centre of mass equals the tensor about the origin (summed directly) minus `M (|c|² 1 − c cᵀ)`
/// (the parallel-axis theorem, a different route from the library's sum about `c`); the
/// principal moments have the tensor's trace and determinant, and the polar axis is an
/// eigenvector.
#[test]
fn two_planes_by_the_parallel_axis_theorem() {
    let (ka, kb) = (0.2f64, 0.7f64);
    let r = SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: 0.5, polar_moment: 0.2, z: 0.03, axis_tilt: ka, axis_tilt_angle: kb },
        supports: vec![Support { z: -0.3, stiffness: [1e5, 2e5], damping: [10.0; 2] }, Support { z: 0.3, stiffness: [1e5; 2], damping: [10.0; 2] }],
        unbalances: vec![PointMass { mass: 0.05, radius: 0.08, angle: 0.4, z: 0.1 }, PointMass { mass: 0.03, radius: 0.06, angle: 2.0, z: -0.2 }],
        planes: vec![
            BallPlane { z: 0.1, n: 2, ball_mass: 0.1, race_radius: 0.05, drag: 0.1, physics: Default::default() },
            BallPlane { z: -0.2, n: 1, ball_mass: 0.2, race_radius: 0.1, drag: 0.1, physics: Default::default() },
        ],
        gravity: [0.0, -9.81, 0.0],
        spin_drag: 0.0,
        lock_tilt: false,
    };
    let psi = [0.0, std::f64::consts::FRAC_PI_2, std::f64::consts::PI];
    let mp = r.mass_properties(&psi).unwrap();
    // point masses written out by hand: (m, x, y, z)
    let pts = [
        (10.0, 0.0, 0.0, 0.03),
        (0.05, 0.08 * 0.4f64.cos(), 0.08 * 0.4f64.sin(), 0.1),
        (0.03, 0.06 * 2.0f64.cos(), 0.06 * 2.0f64.sin(), -0.2),
        (0.1, 0.05, 0.0, 0.1),
        (0.1, 0.0, 0.05, 0.1),
        (0.2, -0.1, 0.0, -0.2),
    ];
    let m: f64 = pts.iter().map(|p| p.0).sum();
    assert!(rel(mp.total_mass, 10.48) < 1e-15 && rel(m, 10.48) < 1e-15);
    let c = [pts.iter().map(|p| p.0 * p.1).sum::<f64>() / m, pts.iter().map(|p| p.0 * p.2).sum::<f64>() / m, pts.iter().map(|p| p.0 * p.3).sum::<f64>() / m];
    for i in 0..3 {
        assert!((mp.centre_of_mass[i] - c[i]).abs() < 1e-15, "c[{i}]");
    }
    // about the origin
    let (s, co) = (ka.sin(), ka.cos());
    let e = [s * kb.cos(), s * kb.sin(), co];
    let mut io = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            io[i][j] = (0.2 - 0.5) * e[i] * e[j];
        }
        io[i][i] += 0.5;
    }
    for &(mk, x, y, z) in &pts {
        io[0][0] += mk * (y * y + z * z);
        io[1][1] += mk * (x * x + z * z);
        io[2][2] += mk * (x * x + y * y);
        for (i, j, v) in [(0, 1, x * y), (0, 2, x * z), (1, 2, y * z)] {
            io[i][j] -= mk * v;
            io[j][i] -= mk * v;
        }
    }
    let c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    for i in 0..3 {
        for j in 0..3 {
            let want = io[i][j] - m * (if i == j { c2 } else { 0.0 } - c[i] * c[j]);
            // round-off of the shift: the origin tensor is ~0.5, the terms ~1e-2
            assert!((mp.inertia[i][j] - want).abs() < 1e-14, "I[{i}][{j}] {} vs {want}", mp.inertia[i][j]);
        }
    }
    let t = &mp.inertia;
    let trace = t[0][0] + t[1][1] + t[2][2];
    let det = t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1]) - t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0])
        + t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0]);
    let p = mp.principal_moments;
    assert!(rel(p[0] + p[1] + p[2], trace) < 1e-14);
    assert!(rel(p[0] * p[1] * p[2], det) < 1e-13);
    assert!(p[0] >= p[1] && p[1] >= p[2]);
    let u = mp.principal_axis;
    for i in 0..3 {
        let tu = t[i][0] * u[0] + t[i][1] * u[1] + t[i][2] * u[2];
        assert!((tu - mp.polar_moment * u[i]).abs() < 1e-14, "eigenvector row {i}");
    }
    assert!((u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - 1.0).abs() < 1e-15);
    assert!(rel(mp.axis_tilt, u[2].acos()) < 1e-12);
    // couple = −(I_xz, I_yz)
    assert_eq!(mp.couple_unbalance, [-t[0][2], -t[1][2]]);
    // the wrong count of angles is an error naming them
    assert!(r.mass_properties(&psi[..2]).unwrap_err().to_string().contains("ball_angles"));
}

fn symmetric_rotor(a: f64, c: f64) -> SpatialRotor {
    SpatialRotor {
        rotor: RigidRotor { mass: 10.0, equatorial_moment: a, polar_moment: c, z: 0.0, axis_tilt: 0.0, axis_tilt_angle: 0.0 },
        supports: vec![Support { z: -0.3, stiffness: [1e5; 2], damping: [10.0; 2] }, Support { z: 0.3, stiffness: [1e5; 2], damping: [10.0; 2] }],
        unbalances: vec![],
        planes: vec![],
        gravity: [0.0; 3],
        spin_drag: 0.0,
        lock_tilt: false,
    }
}

/// A couple unbalance: two equal masses `m` at `(ρ, 0, d)` and `(−ρ, 0, −d)` on an axisymmetric
/// rotor `diag(A, A, C)`. The xz block is `[[A + 2 m d², −2 m ρ d], [−2 m ρ d, C + 2 m ρ²]]`,
/// so the principal axis leans in the xz plane by `θ` with `tan 2θ = 2 J/|C' − A'|`
/// exactly (`J = 2 m ρ d`), and by `J/|C' − A'|` to first order: the relative error of the
/// small-tilt form is `(4/3) θ²` (`½ atan 2x = x − (4/3) x³ + …`), bounded here by `2 θ²`.
#[test]
fn couple_unbalance_tilts_the_principal_axis_by_the_closed_form() {
    // a disk-like rotor (C > A): the polar axis leans away from the masses' line, towards −x;
    // a long one (C < A): towards +x
    for (a, c) in [(0.5, 0.8), (0.8, 0.5)] {
        for (m, rho, d) in [(0.01, 0.1, 0.2), (0.001, 0.05, 0.1), (0.05, 0.1, 0.3)] {
            let mut r = symmetric_rotor(a, c);
            r.unbalances = vec![PointMass { mass: m, radius: rho, angle: 0.0, z: d }, PointMass { mass: m, radius: rho, angle: std::f64::consts::PI, z: -d }];
            let mp = r.mass_properties(&[]).unwrap();
            let (a1, c1, j) = (a + 2.0 * m * d * d, c + 2.0 * m * rho * rho, 2.0 * m * rho * d);
            let exact = 0.5 * (2.0 * j / (c1 - a1).abs()).atan();
            assert!(rel(mp.axis_tilt, exact) < 1e-12, "exact {} vs {exact}", mp.axis_tilt);
            // (−I_xz, −I_yz) = (m ρ d + m ρ d, 0)
            assert!(rel(mp.couple_unbalance[0], j) < 1e-12 && mp.couple_unbalance[1].abs() < 1e-18);
            let towards = if c > a { std::f64::consts::PI } else { 0.0 };
            assert!((mp.axis_tilt_angle.abs() - towards).abs() < 1e-12, "direction {}", mp.axis_tilt_angle);
            let small = j / (c1 - a1).abs();
            assert!(rel(mp.axis_tilt, small) < 2.0 * small * small, "small tilt {} vs {small}", mp.axis_tilt);
            assert!(rel(mp.axis_tilt, small) < 0.05, "a small tilt: {} vs {small}", mp.axis_tilt);
        }
    }
    // a rigid rotor with its principal axis tilted by κ towards β: tilt κ, direction β
    for (k, b) in [(0.01, 0.0), (0.3, 1.2), (0.2, -2.5)] {
        let mut r = symmetric_rotor(0.5, 0.2);
        r.rotor.axis_tilt = k;
        r.rotor.axis_tilt_angle = b;
        let mp = r.mass_properties(&[]).unwrap();
        assert!((mp.axis_tilt - k).abs() < 1e-13 && (mp.axis_tilt_angle - b).abs() < 1e-12, "{k} {b}: {} {}", mp.axis_tilt, mp.axis_tilt_angle);
        assert!(rel(mp.polar_moment, 0.2) < 1e-13 && rel(mp.equatorial_moments[0], 0.5) < 1e-13);
    }
}

/// The two-plane example at its balanced state: the placement is the simulation's balanced
/// guess (same angles), and the whole rotor has its centre of mass on the axis and the shaft as a
/// principal axis, although it has a static unbalance and a couple ([couple]): the balls cancel
/// both. Gravity and y-supports of the example do not change anything (not part of the rotor).
#[test]
fn two_planes_balanced_state_has_no_residual() {
    for sets in [vec![], vec![("rotor.axis_tilt", "0.003"), ("rotor.axis_tilt_angle", "0.8")], vec![("balancer.balls", "4"), ("balancer2.balls", "3")]] {
        let (rotor, _) = rotor_of(TWO_PLANE, &sets);
        let bp = rotor.balanced_ball_angles();
        assert_eq!(bp.placement, Placement::Balanced, "{sets:?}: {}", bp.note);
        let field = SpatialField::new(&rotor, 300.0).unwrap();
        let x = field.balanced_guess().unwrap();
        let m = field.dim() / 2;
        assert_eq!(&x[m - bp.angles.len()..m], &bp.angles[..], "{sets:?}");
        let mp = rotor.mass_properties(&bp.angles).unwrap();
        let s0 = rotor.static_unbalance();
        let c0 = rotor.couple_unbalance();
        assert!(s0[0].hypot(s0[1]) > 1e-4 && c0[0].hypot(c0[1]) > 1e-5, "the example has both unbalances");
        assert!(mp.static_unbalance[0].hypot(mp.static_unbalance[1]) < 1e-12 * s0[0].hypot(s0[1]), "{sets:?}");
        assert!(mp.couple_unbalance[0].hypot(mp.couple_unbalance[1]) < 1e-12 * c0[0].hypot(c0[1]), "{sets:?}");
        assert!(mp.axis_tilt < 1e-10, "{sets:?}: {}", mp.axis_tilt);
        // without the balls placed (all at angle 0 in a heap) the couple and tilt are there
        let heap = rotor.mass_properties(&vec![0.0; rotor.balls()]).unwrap();
        assert!(heap.axis_tilt > 1e-4);
    }
    // gravity and supports do not enter
    let (a, _) = rotor_of(TWO_PLANE, &[]);
    let (b, _) =
        rotor_of(TWO_PLANE, &[("spatial.gravity", "[0.0, 0.0, 0.0]"), ("supports.stiffness_left_y", "2.0e6"), ("supports.stiffness_right_y", "3.0e6")]);
    let psi = a.balanced_ball_angles().angles;
    assert_eq!(a.mass_properties(&psi).unwrap(), b.mass_properties(&psi).unwrap());
}

/// Too little capacity: one plane's balls bunched opposite the unbalance, the residual static
/// unbalance `|s0| − n m R` (the partially balanced state); a two-plane rotor whose plane falls
/// short of its share is said to be bunched, not balanced.
#[test]
fn too_little_capacity_is_said() {
    let (r, _) = rotor_of(DIMENSIONAL, &[("balancer.ball_mass", "0.002")]);
    let bp = r.balanced_ball_angles();
    assert_eq!(bp.placement, Placement::PartiallyBalanced, "{}", bp.note);
    assert!(bp.note.contains("no balanced state"));
    let mp = r.mass_properties(&bp.angles).unwrap();
    let want = 0.010 * 0.10 - 2.0 * 0.002 * 0.12;
    assert!(rel(mp.static_unbalance[0].hypot(mp.static_unbalance[1]), want) < 1e-12);
    let (r2, _) = rotor_of(TWO_PLANE, &[("balancer2.ball_mass", "0.0001")]);
    let bp2 = r2.balanced_ball_angles();
    assert_eq!(bp2.placement, Placement::Bunched, "{}", bp2.note);
    assert!(bp2.note.contains("plane 2"), "{}", bp2.note);
    assert!(SpatialField::new(&r2, 300.0).unwrap().balanced_guess().is_none());
}
