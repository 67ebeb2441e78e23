//! The general route's speed scans, for instruction counts (bench/stationary.py's Floquet and
//! equilibrium cases in the library, without the command): run under
//! `valgrind --tool=callgrind target/release/examples/bench_floquet CASE`.
//!
//! Cases: `two-plane` (examples/spatial_two_plane.toml, 10 speeds 250-2500 rad/s: a periodic
//! orbit, Floquet), `two-plane-autonomous` (the same rotor without gravity and with equal
//! supports: an equilibrium), `two-plane-no-gravity` (without gravity, the supports as given:
//! an orbit of half a revolution), `planar-anisotropic` and `planar-isotropic` (paper 004's Jeffcott
//! rotor, race centred, with `k_x, k_y = (1 ∓ 0.15) k` or equal, 200 speeds up to 3 ω_n),
//! `washer` (examples/washing_machine.toml by the general route, 200 speeds: a three-ball
//! family followed over speed).
use autobal::planar::PlanarRotor;
use autobal::rotor_stability::{speed_grid, stability_over_speed, Rotor};

fn two_plane(case: &str) -> Rotor {
    let mut root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    if case != "two-plane" {
        autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, 0.0, 0.0]")).unwrap();
    }
    if case == "two-plane-autonomous" {
        autobal::config::set_number(&mut root, "supports.stiffness_left_y", 2.0e6).unwrap();
        autobal::config::set_number(&mut root, "supports.stiffness_right_y", 3.0e6).unwrap();
    }
    Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor)
}

fn main() {
    let case = std::env::args().nth(1).unwrap_or_else(|| "two-plane".into());
    let (rotor, speeds) = match case.as_str() {
        "two-plane" | "two-plane-autonomous" | "two-plane-no-gravity" => (two_plane(&case), (1..=10).map(|i| 250.0 * i as f64).collect()),
        "planar-anisotropic" | "planar-isotropic" => {
            let mut p = PlanarRotor::paper();
            p.s2 = 0.0;
            if case == "planar-anisotropic" {
                p.k_y = Some(1.15 * p.k);
                p.k *= 0.85;
            }
            let wn = p.natural_frequency();
            (Rotor::Planar(p), speed_grid(3.0 * wn, 200).unwrap())
        }
        "washer" => {
            // the grid of `autobal stability --route general` on it: 200 speeds up to the
            // command's default end of the axis
            let root = autobal::config::parse(include_str!("../../../examples/washing_machine.toml"), "washer").unwrap();
            let sim = autobal::config::spatial_simulation(&root).unwrap();
            let omega0 = sim.config.model.scale.map_or(1.0, |s| s.omega0);
            let cfg = autobal::config::spatial(&root).unwrap();
            let w = cfg.analysis.speed_axis_max(2.0 * autobal::reports::default_omega_max(&cfg.model)) * omega0;
            (Rotor::Spatial(sim.rotor), speed_grid(w, 200).unwrap())
        }
        other => panic!("unknown case {other}"),
    };
    let r = stability_over_speed(&rotor, &speeds).unwrap();
    let ranges: Vec<(f64, f64)> = r.stable_ranges.iter().map(|s| (s.from, s.to)).collect();
    println!("{case}: {} speeds, stable {ranges:?}", speeds.len());
    if let Some(f) = &r.family {
        let all: Vec<(f64, f64)> = f.all_members_stable.iter().map(|s| (s.from, s.to)).collect();
        let some: Vec<(f64, f64)> = f.some_members_stable.iter().map(|s| (s.from, s.to)).collect();
        println!("family: all {all:?} some {some:?}");
        let verdicts: Vec<String> = r.points.iter().map(|p| p.family.as_ref().map_or("-".to_string(), |f| format!("{:?}", f.verdict))).collect();
        println!("per speed: {}", verdicts.join(" "));
    }
}
