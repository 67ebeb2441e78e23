//! DOF layouts node by node (issue 19): a rigid rotor (node 1: `x, y, α, β`) on two bearings
//! whose outer races sit in pedestals, support masses with `x, y` only (nodes 0 and 2, as ROSS's
//! `PointMass` at the far end of an `n_link` bearing). The indexing (`dof`, `dof_name`), the
//! checks of offsets on nodes without tilts, the natural frequencies against the closed form of
//! the two decoupled 2-DOF problems, the balanced state's eigenvalues against the same rotor with
//! every node `x, y, α, β` (the supports given dummy tilts decoupled from the rest), the config's
//! DOF table and export, the modal reduction, and a speed-dependent bearing between two nodes.

mod common;

use autobal::analysis::{stability, stationary, NewtonOptions};
use autobal::linear_rotor::config::{export, layouts_from_dofs, linear_rotor};
use autobal::linear_rotor::reduce::reduce;
use autobal::linear_rotor::{BalancerPlane, Direction, Frame, Layout, LinearRotor, LinearRotorField, Unbalance};
use common::{all_eigenvalues, match_distance};
use num_complex::Complex64;

// rotor mass, diametral and polar moments, support mass, bearing and ground stiffness, the
// bearings' offsets ±A from the rotor's node
const M: f64 = 3.0;
const ID: f64 = 0.02;
const IP: f64 = 0.03;
const MS: f64 = 1.5;
const K1: f64 = 2.0e5;
const K2: f64 = 5.0e5;
const A: f64 = 0.1;
// the dummy tilts of the all-tilt comparison: inertia and natural frequency (far from the rest)
const JD: f64 = 0.7;
const WD: f64 = 1234.0;

/// The pedestal rotor: nodes `[support, rotor, support]`; with `dummy_tilts` every node has
/// `x, y, α, β` (the supports' tilts with inertia `JD`, stiffness `JD WD²`, coupled to nothing).
fn pedestal_rotor(dummy_tilts: bool) -> LinearRotor {
    let support = if dummy_tilts { Layout::TranslationTilt } else { Layout::Translation };
    let mut r = LinearRotor::with_layouts(&[support, Layout::TranslationTilt, support]);
    let n = r.dofs();
    let d = |node: usize, dir: Direction| r.dof(node, dir).unwrap();
    let (x0, y0, x1, y1, a1, b1, x2, y2) = (
        d(0, Direction::X),
        d(0, Direction::Y),
        d(1, Direction::X),
        d(1, Direction::Y),
        d(1, Direction::Alpha),
        d(1, Direction::Beta),
        d(2, Direction::X),
        d(2, Direction::Y),
    );
    let add = |a: &mut Vec<f64>, row: &[(usize, f64)], k: f64| {
        for &(i, ci) in row {
            for &(j, cj) in row {
                a[i * n + j] += k * ci * cj;
            }
        }
    };
    let (mut m, mut k, mut c, mut g) = (vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]);
    for (i, v) in [(x1, M), (y1, M), (a1, ID), (b1, ID), (x0, MS), (y0, MS), (x2, MS), (y2, MS)] {
        m[i * n + i] = v;
    }
    g[a1 * n + b1] = IP;
    g[b1 * n + a1] = -IP;
    // bearing at +A to support 0, at −A to support 2: x + zβ − x_s, y − zα − y_s
    for (z, xs, ys) in [(A, x0, y0), (-A, x2, y2)] {
        add(&mut k, &[(x1, 1.0), (b1, z), (xs, -1.0)], K1);
        add(&mut k, &[(y1, 1.0), (a1, -z), (ys, -1.0)], K1);
        add(&mut c, &[(x1, 1.0), (b1, z), (xs, -1.0)], 40.0);
        add(&mut c, &[(y1, 1.0), (a1, -z), (ys, -1.0)], 40.0);
        add(&mut k, &[(xs, 1.0)], K2);
        add(&mut k, &[(ys, 1.0)], K2);
    }
    if dummy_tilts {
        for node in [0, 2] {
            for dir in [Direction::Alpha, Direction::Beta] {
                let i = d(node, dir);
                m[i * n + i] = JD;
                k[i * n + i] = JD * WD * WD;
            }
        }
    }
    (r.m, r.k, r.c, r.g) = (m, k, c, g);
    r
}

/// The roots `ω` of `det(K − ω² diag(m1, m2)) = 0`, `K = [[k11, k12], [k12, k22]]`.
fn two_dof(m1: f64, m2: f64, k11: f64, k12: f64, k22: f64) -> [f64; 2] {
    let (p, q) = (k11 / m1, k22 / m2);
    let s = ((p - q).powi(2) + 4.0 * k12 * k12 / (m1 * m2)).sqrt();
    [(0.5 * (p + q - s)).sqrt(), (0.5 * (p + q + s)).sqrt()]
}

#[test]
fn dofs_are_named_by_node_and_direction() {
    let r = pedestal_rotor(false);
    assert_eq!((r.nodes, r.dofs()), (3, 8));
    assert_eq!(r.node_layouts, vec![Layout::Translation, Layout::TranslationTilt, Layout::Translation]);
    assert_eq!(r.layout, Layout::TranslationTilt);
    assert_eq!(r.node_starts(), vec![0, 2, 6]);
    assert_eq!(r.dof(0, Direction::Y), Some(1));
    assert_eq!(r.dof(0, Direction::Alpha), None);
    assert_eq!(r.dof(1, Direction::X), Some(2));
    assert_eq!(r.dof(1, Direction::Beta), Some(5));
    assert_eq!(r.dof(2, Direction::X), Some(6));
    assert_eq!(r.dof(2, Direction::Beta), None);
    assert_eq!(r.dof(3, Direction::X), None);
    let names: Vec<String> = (0..8).map(|i| r.dof_name(i)).collect();
    assert_eq!(names, ["node 0 x", "node 0 y", "node 1 x", "node 1 y", "node 1 α", "node 1 β", "node 2 x", "node 2 y"]);
    assert_eq!(r.node_dofs(1), (2, 3, Some((4, 5))));
    assert_eq!(r.node_dofs(2), (6, 7, None));
    // all alike: the uniform layout, no per-node table
    let u = LinearRotor::with_layouts(&[Layout::Translation; 3]);
    assert_eq!((u.layout, u.node_layouts.len(), u.dofs()), (Layout::Translation, 0, 6));
    r.validate().unwrap();
}

#[test]
fn offsets_on_nodes_without_tilts_are_refused_by_name() {
    let mut r = pedestal_rotor(false);
    r.balancers.push(BalancerPlane { node: 1, radius: 0.05, balls: 2, ball_mass: 0.01, drag: 1e-3, offset: 0.02 });
    r.unbalances.push(Unbalance { node: 1, me: 1e-4, phase: 0.0, offset: 0.03 });
    r.validate().unwrap();
    let mut b = r.clone();
    b.balancers.push(BalancerPlane { node: 2, offset: 0.01, ..b.balancers[0] });
    let e = b.validate().unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.balancers[1].offset:") && e.contains("node 2 has x, y only"), "{e}");
    // without offset a plane on a support is fine (its race centre is the node)
    b.balancers[1].offset = 0.0;
    b.validate().unwrap();
    let mut u = r.clone();
    u.unbalances.push(Unbalance { node: 0, me: 1e-4, phase: 0.0, offset: -0.01 });
    let e = u.validate().unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.unbalances[1].offset:") && e.contains("node 0 has x, y only"), "{e}");
    let mut w = r.clone();
    w.node_layouts.pop();
    let e = w.validate().unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.node_layouts: has 2 entries, one per node: 3"), "{e}");
}

/// At rest the pedestal rotor splits into the symmetric motion (the rotor's translation `m` on
/// `2 k1` to the two supports `2 ms` on `2 k2`) and the antisymmetric one (the tilt `I_d` on
/// `2 k1 A²` to the supports moving oppositely), per direction: closed form. Tolerance 1e-10
/// relative: the Cholesky reduction and the symmetric eigen-solver of an 8 × 8 problem whose
/// entries span 6 decades are good to about 1e-13.
#[test]
fn natural_frequencies_equal_the_closed_form() {
    let r = pedestal_rotor(false);
    let sym = two_dof(M, 2.0 * MS, 2.0 * K1, -2.0 * K1, 2.0 * K1 + 2.0 * K2);
    let anti = two_dof(ID, 2.0 * MS, 2.0 * K1 * A * A, -2.0 * K1 * A, 2.0 * K1 + 2.0 * K2);
    let mut want: Vec<f64> = sym.iter().chain(&anti).flat_map(|w| [*w, *w]).collect();
    want.sort_by(f64::total_cmp);
    let got = r.natural_frequencies(&[], false).unwrap();
    assert_eq!(got.len(), 8);
    for (a, b) in got.iter().zip(&want) {
        assert!((a / b - 1.0).abs() < 1e-10, "{got:?} vs {want:?}");
    }
}

/// The balanced state of the rotor with a two-ball plane at an offset and an unbalance at
/// another, in axes turning with the rotor: the same state and the same eigenvalues as the model
/// with every node `x, y, α, β`, less the dummy tilts' own `±i(WD ± Ω)` (a decoupled block
/// `J p̈ + 2Ω J J ṗ + (k − Ω² J) p = 0` in turning axes). The two models hold the same numbers
/// in other places, so the states agree to 1e-12 of the largest displacement (measured: bit
/// for bit) and the eigenvalues to 1e-11 of the largest (measured 1.8e-15: the eigen-solver's
/// round-off on a 20 × 20 and a 28 × 28 matrix).
#[test]
fn balanced_state_equals_the_all_tilt_model() {
    let omega = 300.0;
    let setup = |mut r: LinearRotor| {
        r.balancers.push(BalancerPlane { node: 1, radius: 0.06, balls: 2, ball_mass: 0.02, drag: 5e-3, offset: 0.02 });
        r.unbalances.push(Unbalance { node: 1, me: 1.2e-3, phase: 0.4, offset: -0.01 });
        r
    };
    let (mixed, full) = (setup(pedestal_rotor(false)), setup(pedestal_rotor(true)));
    let (fm, ff) = (LinearRotorField::new(&mixed, omega, Frame::Rotating).unwrap(), LinearRotorField::new(&full, omega, Frame::Rotating).unwrap());
    let sm = stationary(&fm, &fm.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    let sf = stationary(&ff, &ff.balanced_guess().unwrap(), &NewtonOptions::default()).unwrap();
    // the same state: the mixed model's DOFs are the full model's less the dummy tilts
    let (nm, nf) = (mixed.dofs(), full.dofs());
    let map: Vec<usize> = (0..nm)
        .map(|i| {
            let (node, dir) = mixed.dof_node(i).unwrap();
            full.dof(node, dir).unwrap()
        })
        .collect();
    let scale = sm.x[..nm].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for i in 0..nm {
        assert!((sm.x[i] - sf.x[map[i]]).abs() <= 1e-12 * scale, "{}: {} vs {}", mixed.dof_name(i), sm.x[i], sf.x[map[i]]);
    }
    // the balls' angles (after the structure's DOFs)
    for j in 0..2 {
        assert!((sm.x[nm + j] - sf.x[nf + j]).abs() <= 1e-12, "ψ_{j}");
    }
    let (em, ef) = (all_eigenvalues(&stability(&fm, &sm).unwrap()), all_eigenvalues(&stability(&ff, &sf).unwrap()));
    assert_eq!(ef.len(), em.len() + 8);
    // the dummy block's eigenvalues, each twice (two support nodes)
    let mut rest = ef.clone();
    for w in [WD - omega, WD + omega, -(WD - omega), -(WD + omega)] {
        for _ in 0..2 {
            let (k, d) = rest.iter().enumerate().map(|(k, z)| (k, (z - Complex64::new(0.0, w)).norm())).min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
            assert!(d <= 1e-6 * WD, "dummy eigenvalue {w}i: nearest at distance {d}");
            rest.remove(k);
        }
    }
    let big = em.iter().fold(0.0f64, |a, z| a.max(z.norm()));
    let dist = match_distance(&em, &rest);
    assert!(dist <= 1e-11 * big, "eigenvalues differ by {dist:e} (largest {big})");
}

/// The config's DOF table says each node's DOFs; export writes it (and no `layout`), reading it
/// back gives the same rotor; a table out of ROSS's order is refused naming the entry.
#[test]
fn dof_table_carries_the_layout_through_export() {
    let mut r = pedestal_rotor(false);
    r.balancers.push(BalancerPlane { node: 1, radius: 0.06, balls: 2, ball_mass: 0.02, drag: 5e-3, offset: 0.02 });
    let (text, files) = export(&r, "ped");
    assert!(!text.contains("layout ="), "{text}");
    assert!(text.contains(r#"dofs = ["x0", "y0", "x1", "y1", "alpha1", "beta1", "x2", "y2"]"#), "{text}");
    let root: toml::Table = text.parse().unwrap();
    let mut load = |p: &str| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or_else(|| format!("{p}: missing"));
    let back = linear_rotor(&root, &mut load).unwrap();
    assert_eq!(back.rotor, r);
    // the same files with a layout key that says otherwise
    let with = |extra: &str| -> String {
        let t = text.replace("[linear_rotor]\n", &format!("[linear_rotor]\n{extra}\n"));
        let root: toml::Table = t.parse().unwrap();
        let mut load = |p: &str| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or_else(|| format!("{p}: missing"));
        linear_rotor(&root, &mut load).unwrap_err().to_string()
    };
    let e = with("layout = \"x,y,alpha,beta\"");
    assert!(e.starts_with("linear_rotor.dofs[2]: is \"x1\", ROSS's order has \"alpha0\" there"), "{e}");
    // the parser alone
    let names = |s: &[&str]| -> Vec<toml::Value> { s.iter().map(|v| toml::Value::String(v.to_string())).collect() };
    assert_eq!(layouts_from_dofs(&names(&["x0", "y0", "alpha0", "beta0", "x1", "y1"])).unwrap(), [Layout::TranslationTilt, Layout::Translation]);
    let e = layouts_from_dofs(&names(&["x0", "y0", "beta0"])).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.dofs[2]: is \"beta0\", ROSS's order has \"alpha0\" or \"x1\" there"), "{e}");
    let e = layouts_from_dofs(&names(&["x0", "y0", "alpha0"])).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.dofs: ends inside node 0"), "{e}");
    let e = layouts_from_dofs(&names(&["x0", "y0", "x2", "y2"])).unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.dofs[2]: is \"x2\""), "{e}");
}

/// Reduction with the rotor's node as boundary and the supports' four DOFs interior: both
/// interior pairs kept (pseudo-nodes `x, y`), the basis spans everything, so the reduced
/// natural frequencies equal the full ones (1e-9 relative: the static correction and the modes
/// are computed, not exact).
#[test]
fn reduction_keeps_each_nodes_layout() {
    let mut r = pedestal_rotor(false);
    r.balancers.push(BalancerPlane { node: 1, radius: 0.06, balls: 2, ball_mass: 0.02, drag: 5e-3, offset: 0.02 });
    let red = reduce(&r, 2, &[]).unwrap();
    assert_eq!(red.rotor.node_layouts, vec![Layout::TranslationTilt, Layout::Translation, Layout::Translation]);
    assert_eq!(red.rotor.balancers[0].node, 0);
    let (a, b) = (r.natural_frequencies(&[], false).unwrap(), red.rotor.natural_frequencies(&[], false).unwrap());
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x / y - 1.0).abs() < 1e-9, "{a:?} vs {b:?}");
    }
}

/// A speed-dependent bearing between the rotor's node and a support (ROSS's `n_link`): its
/// table `B(Ω)` acts on the difference of the two nodes' `x, y`, the blocks `[[B, −B], [−B, B]]`.
/// At a speed between the table's the structure's eigenvalues equal those of the same rotor with
/// the interpolated coefficients written into `K`, `C` by hand (1e-12 of the largest: the same
/// numbers in the same places, the eigen-solver's round-off); export and reading back keep the
/// link; the reduction keeps the link's node physical (one interior pair left, kept: exact, 1e-9
/// relative as above).
#[test]
fn bearing_between_two_nodes_acts_on_their_difference() {
    use autobal::linear_rotor::SpeedBearing;
    let mut r = pedestal_rotor(false);
    r.balancers.push(BalancerPlane { node: 1, radius: 0.06, balls: 2, ball_mass: 0.02, drag: 5e-3, offset: 0.02 });
    let (kt, ct) = ([[1e5, 2e3, -1e3, 1.2e5], [3e5, 4e3, -3e3, 2.8e5]], [[50.0, 1.0, -2.0, 60.0], [20.0, 0.5, -1.0, 30.0]]);
    r.speed_bearings.push(SpeedBearing { node: 1, link: Some(0), speeds: vec![0.0, 1000.0], k: kt.to_vec(), c: ct.to_vec() });
    r.validate().unwrap();
    let omega = 250.0;
    let f = omega / 1000.0;
    let mut hand = r.clone();
    hand.speed_bearings.clear();
    let n = hand.dofs();
    let (x1, x0) = (hand.dof(1, Direction::X).unwrap(), hand.dof(0, Direction::X).unwrap());
    for (j, (a, b)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
        let (k, c) = (kt[0][j] + f * (kt[1][j] - kt[0][j]), ct[0][j] + f * (ct[1][j] - ct[0][j]));
        for (r0, c0, s) in [(x1, x1, 1.0), (x0, x0, 1.0), (x1, x0, -1.0), (x0, x1, -1.0)] {
            hand.k[(r0 + a) * n + c0 + b] += s * k;
            hand.c[(r0 + a) * n + c0 + b] += s * c;
        }
    }
    let (ea, eb) = (r.structure_eigenvalues(omega).unwrap(), hand.structure_eigenvalues(omega).unwrap());
    let big = eb.iter().fold(0.0f64, |a, z| a.max(z.norm()));
    assert!(match_distance(&ea, &eb) <= 1e-12 * big, "{ea:?} vs {eb:?}");
    // a link to itself or to no node is refused by name
    let mut bad = r.clone();
    bad.speed_bearings[0].link = Some(1);
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.starts_with("linear_rotor.bearings[0].link: 1 is not a node other than the bearing's 1"), "{e}");
    // export and back
    let (text, files) = export(&r, "ped");
    assert!(text.contains("node = 1\nlink = 0\nspeeds"), "{text}");
    let root: toml::Table = text.parse().unwrap();
    let mut load = |p: &str| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or_else(|| format!("{p}: missing"));
    assert_eq!(linear_rotor(&root, &mut load).unwrap().rotor, r);
    // reduction: nodes 1 (balancer, bearing) and 0 (the link) stay, node 2's pair is kept
    let red = reduce(&r, 1, &[]).unwrap();
    assert_eq!(red.boundary, vec![0, 1]);
    assert_eq!(red.rotor.speed_bearings[0].link, Some(0));
    assert_eq!(red.rotor.speed_bearings[0].node, 1);
    let (a, b) = (r.at_speed(omega).natural_frequencies(&[], false).unwrap(), red.rotor.at_speed(omega).natural_frequencies(&[], false).unwrap());
    for (x, y) in a.iter().zip(&b) {
        assert!((x / y - 1.0).abs() < 1e-9, "{a:?} vs {b:?}");
    }
}
