//! The supports' damping of every rotor is held to the range of the dimensionless damping it
//! implies, as the spatial rotor's `supports.damping_left` always was (`h̄x = (h_L + h_R)/(M_s
//! ω0) ≤ 1000`, limits.rs): session 28's hunt found `supports.damping_left_y = 1e12` taken (the
//! general route then ran for minutes), and the planar rotor's `c`, `c_x`, `c_y` and the linear
//! rotor's bearing `c` without such a bound (`planar.c_y = 1e12`: `stability` ran for minutes).
//!
//! Each case computes the damping at which the ratio reaches 1000 from the config's own
//! numbers by hand (the closed form `Σc = 1000 sqrt(Σk M)`), then checks that 0.1 % below it
//! is read and 0.1 % above it is refused naming the key the config spells. The 0.1 % margin is
//! far above the rounding of the sums (1e-15 relative) and far below any other mass or
//! stiffness the check might wrongly include (the smallest, one ball of 0.02 kg of 20 kg, is
//! 0.1 % of the mass and moves the bound by 0.05 %: see the spatial case, which counts it).

use autobal::config;
use toml::{Table, Value};

const BOUND: f64 = 1000.0; // dimensionless.h_x's upper end

fn with(text: &str, sets: &[(&str, f64)]) -> Table {
    let mut root = config::parse(text, "test").unwrap();
    for (k, v) in sets {
        config::set(&mut root, k, Value::Float(*v)).unwrap();
    }
    root
}

fn expect_refused(r: autobal::Result<()>, key: &str) {
    let e = r.expect_err(key).to_string();
    assert!(e.starts_with(&format!("{key}: ")), "expected an error naming {key}, got: {e}");
    assert!(e.contains("outside [0, 1000]"), "{e}");
    assert!(!e.contains('\n'), "{e}");
}

/// The spatial simulation's y damping: `(h_Ly + h_Ry)/(M_s ω0y)`, `ω0y = sqrt((k_Ly + k_Ry)/M_s)`.
#[test]
fn spatial_y_damping_is_held_to_the_ratio_of_its_x_twin() {
    let text = include_str!("../../../examples/spatial_two_plane.toml");
    // M_s: rotor, unbalance, couple and two planes of two balls (the example's numbers)
    let ms: f64 = 20.0 + 0.010 + 0.010 + 2.0 * 2.0 * 0.020;
    let ky: f64 = 2.6e6 + 3.6e6;
    let other = 300.0; // damping_right_y: as damping_right when not given
    let limit = BOUND * (ky * ms).sqrt() - other;
    let run = |key: &str, v: f64| config::spatial_simulation(&with(text, &[(key, v)])).map(|_| ());
    run("supports.damping_left_y", 0.999 * limit).unwrap();
    expect_refused(run("supports.damping_left_y", 1.001 * limit), "supports.damping_left_y");
    expect_refused(run("supports.damping_right_y", 1.001 * limit), "supports.damping_right_y");
    // the reported case
    expect_refused(run("supports.damping_left_y", 1e12), "supports.damping_left_y");
}

/// The planar rotor: `c_d/(m0 ω_d)`, `ω_d = sqrt(k_d/m0)`, so `c_d ≤ 1000 sqrt(k_d m0)`.
#[test]
fn planar_damping_is_held_to_the_spatial_ratio() {
    let aniso = "[planar]\nm1 = 1.0\nm2 = 0.2\nm3 = 0.03\nn = 2\ns1 = 0.003\ns2 = 0.0005\nr = 0.06\n\
                 k_x = 9.0e4\nk_y = 1.2e5\nc_x = 40.0\nc_y = 60.0\nc_psi = 0.1\ni_g = 0.0025\n";
    let m0: f64 = 1.0 + 0.2 + 2.0 * 0.03;
    let run = |text: &str, key: &str, v: f64| config::planar_rotor(&with(text, &[(key, v)])).map(|_| ());
    for (key, k) in [("planar.c_x", 9.0e4_f64), ("planar.c_y", 1.2e5)] {
        let limit = BOUND * (k * m0).sqrt();
        run(aniso, key, 0.999 * limit).unwrap();
        expect_refused(run(aniso, key, 1.001 * limit), key);
    }
    expect_refused(run(aniso, "planar.c_y", 1e12), "planar.c_y");
    // one c in every direction: held against the smaller stiffness (here k_x)
    let iso_c = aniso.replace("c_x = 40.0\nc_y = 60.0\n", "c = 50.0\n");
    let limit = BOUND * (9.0e4 * m0).sqrt();
    run(&iso_c, "planar.c", 0.999 * limit).unwrap();
    expect_refused(run(&iso_c, "planar.c", 1.001 * limit), "planar.c");
    // the paper's isotropic rotor
    let paper = include_str!("../../../examples/planar.toml");
    let k: f64 = 104509.44;
    let limit = BOUND * (k * m0).sqrt();
    run(paper, "planar.c", 0.999 * limit).unwrap();
    expect_refused(run(paper, "planar.c", 1.001 * limit), "planar.c");
}

/// The linear rotor's constant bearings: `Σc/(M ω0)`, `ω0 = sqrt(Σk/M)`, `M` the shaft's and
/// disk's mass (ρ A L + m_disk: a rigid translation has no rotary inertia's energy).
#[test]
fn linear_bearing_damping_is_held_to_the_spatial_ratio() {
    let text = |c: f64| {
        format!(
            "[linear_rotor]\nmodes = 2\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.025\ne = 2.1e11\nrho = 7850.0\ncount = 6\n\
             [[linear_rotor.disks]]\nnode = 3\nmass = 4.0\nid = 0.01\nip = 0.02\n\
             [[linear_rotor.bearings]]\nnode = 0\nk = 2e6\nc = 300.0\n[[linear_rotor.bearings]]\nnode = 6\nk = 2e6\nc = {c:e}\n"
        )
    };
    let mass = 7850.0 * std::f64::consts::PI * 0.025 * 0.025 / 4.0 * 0.6 + 4.0;
    let limit = BOUND * (4e6 * mass).sqrt() - 300.0;
    let run = |v: f64| {
        let root = with(&text(v), &[]);
        autobal::linear_rotor::config::linear_rotor_bytes(&root, &mut |p| Err(format!("{p}: no files here"))).map(|_| ())
    };
    run(0.999 * limit).unwrap();
    expect_refused(run(1.001 * limit), "linear_rotor.bearings[1].c");
    expect_refused(run(1e12), "linear_rotor.bearings[1].c");
}

/// The linear rotor's tabulated bearings (session 29: `cxx = 1e12` in a table was taken and
/// ran for minutes; only constant bearings' `c` was bounded): each value at its row, `|c|/(M
/// ω0)` with `ω0 = sqrt(K/M)`, `K` the supports' stiffness along the value's direction at the
/// row's speed (the constant bearing's `k` plus the table's `kxx` or `kyy` there). The same
/// shaft as above, its second bearing tabulated: `kxx = [2e6, 3e6]` at `[0, 1000]` rad/s, so
/// row 1 is held against `K = 5e6`, row 0 against `K = 4e6`; `kyy` given lower, `[1e6, 1e6]`,
/// so `cyy` is held against 3e6. The key and row named; `cyy` where given, else `cxx`.
#[test]
fn linear_tabulated_bearing_damping_is_held_at_each_row() {
    let text = |cxx: [f64; 2], cyy: Option<[f64; 2]>, cxy: [f64; 2]| {
        let cyy = cyy.map_or(String::new(), |c| format!("cyy = [{:e}, {:e}]\n", c[0], c[1]));
        format!(
            "[linear_rotor]\nmodes = 2\n[[linear_rotor.elements]]\nlength = 0.1\ndiameter = 0.025\ne = 2.1e11\nrho = 7850.0\ncount = 6\n\
             [[linear_rotor.disks]]\nnode = 3\nmass = 4.0\nid = 0.01\nip = 0.02\n\
             [[linear_rotor.bearings]]\nnode = 0\nk = 2e6\nc = 300.0\n[[linear_rotor.bearings]]\nnode = 6\nspeeds = [0.0, 1000.0]\n\
             kxx = [2e6, 3e6]\nkyy = [1e6, 1e6]\ncxx = [{:e}, {:e}]\ncxy = [{:e}, {:e}]\n{cyy}",
            cxx[0], cxx[1], cxy[0], cxy[1]
        )
    };
    let mass = 7850.0 * std::f64::consts::PI * 0.025 * 0.025 / 4.0 * 0.6 + 4.0;
    let limit = |k: f64| BOUND * (k * mass).sqrt();
    let run = |t: String| autobal::linear_rotor::config::linear_rotor_bytes(&with(&t, &[]), &mut |p| Err(format!("{p}: no files here"))).map(|_| ());
    let small = Some([300.0, 300.0]);
    // row 1 (1000 rad/s): K along x = 2e6 + 3e6
    run(text([300.0, 0.999 * limit(5e6)], small, [0.0; 2])).unwrap();
    expect_refused(run(text([300.0, 1.001 * limit(5e6)], small, [0.0; 2])), "linear_rotor.bearings[1].cxx[1]");
    // row 0 (0 rad/s): K along x = 2e6 + 2e6
    run(text([0.999 * limit(4e6), 300.0], small, [0.0; 2])).unwrap();
    expect_refused(run(text([1.001 * limit(4e6), 300.0], small, [0.0; 2])), "linear_rotor.bearings[1].cxx[0]");
    // along y, K = 2e6 + 1e6 at both rows: cyy named where given, cxx where cyy falls back to it
    run(text([300.0; 2], Some([300.0, 0.999 * limit(3e6)]), [0.0; 2])).unwrap();
    expect_refused(run(text([300.0; 2], Some([300.0, 1.001 * limit(3e6)]), [0.0; 2])), "linear_rotor.bearings[1].cyy[1]");
    expect_refused(run(text([300.0, 1.001 * limit(3e6)], None, [0.0; 2])), "linear_rotor.bearings[1].cxx[1]");
    // a cross-coupled term: its magnitude, either sign
    run(text([300.0; 2], small, [0.0, -0.999 * limit(5e6)])).unwrap();
    expect_refused(run(text([300.0; 2], small, [0.0, -1.001 * limit(5e6)])), "linear_rotor.bearings[1].cxy[1]");
    // the reported case
    expect_refused(run(text([300.0, 1e12], small, [0.0; 2])), "linear_rotor.bearings[1].cxx[1]");
}
