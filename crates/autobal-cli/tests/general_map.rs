//! `autobal map` on every configuration: the general route (autobal::rotor_map) against the
//! 12-state map, the Jeffcott rotor's critical speed, and a two-plane rotor with gravity.

use std::process::Command;

fn autobal(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_autobal")).args(args).output().expect("binary runs");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("autobal-general-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The CSV's rows as fields (header dropped), and the header.
fn csv(stem: &std::path::Path) -> (String, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(stem.with_extension("csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    (header, lines.map(|l| l.split(',').map(String::from).collect()).collect())
}

fn num(s: &str) -> f64 {
    s.parse().unwrap_or_else(|_| panic!("`{s}` is not a number"))
}

#[test]
fn one_plane_general_map_equals_the_12_state_map_cell_by_cell() {
    let cfg = example("dimensional.toml");
    let (a, g) = (tmp("closed"), tmp("general"));
    let axes = ["--x", "omega=0.2:3:15", "--y", "balancer.ball_mass=0.01:0.05:6"];
    let (code, _, err) = autobal(&[&["map", "-c", &cfg, "-o", a.to_str().unwrap()], &axes[..]].concat());
    assert_eq!(code, 0, "{err}");
    let (code, out, err) = autobal(&[&["map", "-c", &cfg, "--route", "general", "-o", g.to_str().unwrap()], &axes[..]].concat());
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("general route") && out.contains("equilibrium"), "{out}");
    assert!(!err.contains("ignore"), "{err}");
    let (ha, ra) = csv(&a);
    let (hg, rg) = csv(&g);
    assert_eq!(ha, "omega,balancer.ball_mass,max_real_part_per_tau,stable,necessary");
    assert_eq!(hg, "omega,balancer.ball_mass,max_real_part_per_tau,verdict,family_dimension,family,state");
    assert_eq!(ra.len(), 90);
    assert_eq!(ra.len(), rg.len());
    // the same Ω per cell (each route converts with the ω0 of the rotor at that ball mass)
    let scale = ra.iter().map(|r| num(&r[2]).abs()).fold(0.0, f64::max);
    let (mut stable, mut unstable) = (0, 0);
    for (x, y) in ra.iter().zip(&rg) {
        assert_eq!((&x[0], &x[1]), (&y[0], &y[1]));
        // paper 000's eq (6) by its characteristic polynomial vs the nonlinear equations'
        // exact Jacobian at the Newton solution: the same linearisation, so the same spectral
        // abscissa up to the eigenvalue solvers' round-off, ~ε times the largest |λ|. The
        // tolerance, 1e-7 of the map's largest |margin| (itself below every cell's largest
        // |λ|, so stricter than 1e-7 of that), leaves room for conditioning (seen: 2e-14)
        assert!((num(&x[2]) - num(&y[2])).abs() <= 1e-7 * scale, "{x:?} vs {y:?}");
        assert_eq!(x[3] == "1", y[3] == "stable", "{x:?} vs {y:?}");
        assert_eq!(y[4], "0", "two balls: an isolated balanced state");
        if x[3] == "1" {
            stable += 1;
        } else {
            unstable += 1;
        }
    }
    // both verdicts occur, so that the comparison can fail
    assert!(stable > 0 && unstable > 0, "{stable} {unstable}");
}

#[test]
fn planar_jeffcott_map_is_unstable_below_the_critical_speed_in_every_row() {
    let stem = tmp("jeffcott");
    let (code, out, err) = autobal(&[
        "map",
        "-c",
        &example("planar.toml"),
        "--set",
        "planar.s2=0",
        "--x",
        "omega=20:900:45",
        "--y",
        "planar.c_psi=0.02:0.3:8",
        "--boundary",
        "-o",
        stem.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("general route"), "{out}");
    assert!(!err.contains("ignore"), "{err}");
    for ext in ["svg", "png"] {
        assert!(stem.with_extension(ext).exists(), "{ext}");
    }
    // sqrt(k/M) from examples/planar.toml's numbers: k = 104509.44 N/m, M = m1 + m2 + n m3
    let wn = (104509.44f64 / (1.0 + 0.2 + 2.0 * 0.03)).sqrt();
    let (header, rows) = csv(&stem);
    assert_eq!(header, "omega,planar.c_psi,max_real_part,verdict,family_dimension,family,state");
    assert_eq!(rows.len(), 45 * 8);
    for row in rows.chunks(45) {
        for c in row {
            if num(&c[0]) < wn {
                assert_eq!(c[3], "unstable", "{c:?}");
                assert!(num(&c[2]) > 0.0);
            }
        }
        // well above it the balls balance the rotor (paper 004 with the race centred)
        assert_eq!(row[44][3], "stable", "{row:?}");
    }
    // --boundary: per row, the points bisected along x lie between the grid cells whose
    // verdicts differ, and the first one (unstable to stable) above sqrt(k/M)
    let text = std::fs::read_to_string(format!("{}_boundary.csv", stem.display())).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "omega,planar.c_psi,from,to,along");
    let pts: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(pts.iter().all(|p| p.len() == 5 && (p[4] == "x" || p[4] == "y")), "{text}");
    for row in rows.chunks(45) {
        let y = &row[0][1];
        let mine: Vec<&Vec<&str>> = pts.iter().filter(|p| p[1] == y && p[4] == "x").collect();
        let first = mine.first().unwrap_or_else(|| panic!("no boundary point at c_psi {y}"));
        assert_eq!((first[2], first[3]), ("unstable", "stable"));
        let b = num(first[0]);
        assert!(b > wn, "{b} vs {wn}");
        let i = row.iter().position(|c| c[3] == "stable").unwrap();
        assert!(num(&row[i - 1][0]) < b && b < num(&row[i][0]), "{b} not between the cells");
    }
}

#[test]
fn spatial_two_plane_map_runs_on_the_periodic_orbit() {
    let stem = tmp("two_plane");
    // gravity across a horizontal shaft: the stationary motion is a periodic orbit
    let (code, out, err) = autobal(&[
        "map",
        "-c",
        &example("spatial_two_plane.toml"),
        "--x",
        "speed_rpm=12000:24000:2",
        "--y",
        "balancer.drag=0.5:0.6:2",
        "-o",
        stem.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("periodic orbit (Floquet multipliers)"), "{out}");
    assert!(!err.contains("ignore"), "{err}");
    let (_, rows) = csv(&stem);
    assert_eq!(rows.len(), 4);
    assert!(rows.iter().all(|r| !r[3].is_empty() && r[2].parse::<f64>().is_ok()), "{rows:?}");
    // second route: `stability` (the speed scan of rotor_stability) at the same speeds, drag
    // 0.5 (the example's): its exponents are in 1/s, the map's per unit τ, so the ratio of the
    // two speeds' exponents is compared (ω0 cancels). Both shoot the same orbit to a residual
    // of 1e-10 from different starts; the exponents then agree to ~1e-8 relative
    let (code, out, err) = autobal(&["stability", "-c", &example("spatial_two_plane.toml"), "--omega-max", "24000rpm", "--samples", "10", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let at = |i: usize| v["points"][i]["abscissa"].as_f64().unwrap();
    // (12 000 and 24 000 rpm, where the balanced orbit is stable: at 1 200 rpm the map found no
    // orbit from the closed form at drag 0.5 after the shooting's quasi-Newton change, while the
    // speed scan reaches it by continuation; the closing note records it)
    let (s1, s2) = (at(4), at(9));
    let (m1, m2) = (num(&rows[0][2]), num(&rows[1][2]));
    let (a, b) = (s2 / s1, m2 / m1);
    assert!((a - b).abs() <= 1e-6 * a.abs(), "{a} vs {b}");
    assert_eq!(v["points"][9]["verdict"].as_str().unwrap(), rows[1][3]);
}

#[test]
fn general_route_refuses_what_it_cannot_do_with_one_line() {
    let stem = tmp("refused");
    let base = ["map", "-c", &example("planar.toml"), "--x", "omega=100:200:3", "--y", "planar.c_psi=0.1:0.2:2", "-o", stem.to_str().unwrap()];
    let (code, _, err) = autobal(&[&base[..], &["--balls=locked"]].concat());
    assert_ne!(code, 0);
    assert!(err.contains("--balls") && err.lines().count() == 1, "{err}");
    let (code, _, err) = autobal(&["map", "-c", &example("planar.toml"), "--x", "planar.nope=1:2:3", "--y", "omega=100:200:2", "-o", stem.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("--x") && err.contains("planar.nope"), "{err}");
}

#[test]
fn a_three_ball_map_says_which_members_of_the_family_are_stable() {
    // the Jeffcott rotor (race centred) with three balls: some members stable from 300.41 rad/s,
    // all from 307.08 (docs/notes/stability.md, the speed scan's family); 290, 305 and 320 rad/s lie
    // on either side of both by more than the map's sampling can move them (< 0.01 rad/s)
    let stem = tmp("three-balls");
    let (code, out, err) = autobal(&[
        "map",
        "-c",
        &example("planar.toml"),
        "--set",
        "planar.s2=0",
        "--set",
        "planar.n=3",
        "--x",
        "omega=290:320:3",
        "--y",
        "planar.c=50:60:2",
        "-o",
        stem.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("general route"), "{out}");
    assert!(err.contains("family") && err.contains("one member"), "{err}");
    let (header, rows) = csv(&stem);
    assert_eq!(header, "omega,planar.c,max_real_part,verdict,family_dimension,family,state");
    let at = |w: &str| rows.iter().find(|r| r[0] == w && r[1] == "50").unwrap_or_else(|| panic!("{rows:?}"));
    assert_eq!(at("290")[5], "none_stable", "{rows:?}");
    assert_eq!(at("305")[5], "some_stable", "{rows:?}");
    assert_eq!(at("320")[5], "all_stable", "{rows:?}");
    assert!(rows.iter().all(|r| r[4] == "1"), "{rows:?}");
}
