//! A general-route map whose cells hold a family of balanced states (n ≥ 3 balls in a plane):
//! its colour and its bisected boundary are one member's (walk 34, finding D8b). The figure's
//! title said "Stability map of the planar rotor's stationary state" and nothing said it of the
//! boundary; only a line on standard error said so, for the colour. Now the title says it, the
//! JSON summary's `boundary.family_member` does, and so does the line on standard error. A
//! rotor of two balls (no family) says none of it.

mod common;
use autobal::spatial::map::Axis;
use autobal_commands::command::{ConfigSource, Output as _};
use autobal_commands::map::{Args, FAMILY_MEMBER_NOTE};
use common::{run_in, scratch_in};
use std::time::Duration;

/// Paper 004's Jeffcott rotor, race centred, with `n` balls.
fn jeffcott(n: usize) -> String {
    format!(
        "[planar]\nm1 = 1.0\nm2 = 0.2\nm3 = 0.03\nn = {n}\ns1 = 0.003\ns2 = 0.0\ngamma = 0.0\nr = 0.06\nk = 104509.44\nc = 50.0\nc_psi = 0.1\nc_theta = 0.0\ni_g = 0.0025\n\n[drive]\nkind = \"speed\"\nomega0 = 400.0\nt_end = 20.0\n\n[integration]\nrtol = 1e-9\natol = 1e-11\ndt = 0.01\n"
    )
}

/// The map of `n` balls over 280-320 rad/s and `c_psi` 0.1-0.2 with its boundary: the JSON
/// summary, the figure's title, standard error.
fn map(n: usize) -> (serde_json::Value, String, String) {
    let d = scratch_in("m34", &format!("family{n}"));
    let cfg = d.join("j.toml");
    std::fs::write(&cfg, jeffcott(n)).unwrap();
    let args = Args {
        config: ConfigSource::file(Some(&cfg), &[]),
        x: Axis::new("omega", vec![280.0, 320.0]),
        y: Axis::new("planar.c_psi", vec![0.1, 0.2]),
        boundary: true,
        ..Args::default()
    };
    let out = autobal_commands::command::Command::run(&args, &autobal::control::Control::none()).unwrap();
    let title = out.figures().unwrap().remove(0).plot.title;
    let (code, _, err) = run_in(
        &d,
        Duration::from_secs(300),
        &["map", "--config", cfg.to_str().unwrap(), "--x", "omega=280:320:2", "--y", "planar.c_psi=0.1:0.2:2", "--boundary", "--out", "m"],
    );
    assert_eq!(code, 0, "{err}");
    (out.json().unwrap(), title, err)
}

#[test]
fn a_family_maps_title_and_summary_say_the_boundary_is_one_members() {
    let (v, title, err) = map(3);
    assert!(v["families"].as_u64().unwrap() > 0, "{v}");
    assert_eq!(v["boundary"]["family_member"], serde_json::json!(true), "{v}");
    assert!(title.ends_with(FAMILY_MEMBER_NOTE), "{title}");
    assert!(FAMILY_MEMBER_NOTE.contains("colour and boundary points are one member's"));
    assert!(err.contains("max_real_part and verdict, and the boundary points, are those of one member"), "{err}");

    let (v, title, err) = map(2);
    assert_eq!(v["families"].as_u64(), Some(0), "{v}");
    assert_eq!(v["boundary"]["family_member"], serde_json::json!(false), "{v}");
    assert!(!title.contains("member"), "{title}");
    assert!(!err.contains("one member"), "{err}");
}
