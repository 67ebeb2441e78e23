//! Sweeps of a linear rotor config (issue 19 item 4): [`LinearRotorSpec`] as a
//! [`autobal::sweep::SweepModel`], against runs set up by hand and the native planar sweep on
//! the Jeffcott preset.

use autobal::config;
use autobal::control::Control;
use autobal::drive::Drive;
use autobal::linear_rotor::config::{export, linear_rotor};
use autobal::linear_rotor::runup::{simulate, RunSettings};
use autobal::linear_rotor::spec::LinearRotorSpec;
use autobal::linear_rotor::LinearRotor;
use autobal::ode::Method;
use autobal::sweep::{linear_summary_values, simulate_grid, summary_values, Axis, Grid, LINEAR_SUMMARY_COLUMNS, SUMMARY_COLUMNS};
use toml::Table;

const T_END: f64 = 2.0;
const DT: f64 = 5e-4;

/// examples/planar.toml with its race centred, run up through the critical speed in 2 s at
/// rtol 1e-10, the balls starting at 0 and π (as the linear rotor's run starts them).
fn planar_root(wn: f64) -> Table {
    let mut root = config::parse(include_str!("../../../examples/planar.toml"), "planar").unwrap();
    for (k, v) in [
        ("planar.s2", 0.0),
        ("drive.omega0", 0.2 * wn),
        ("drive.b", 1.6 * wn / T_END),
        ("drive.t_end", T_END),
        ("integration.rtol", 1e-10),
        ("integration.atol", 1e-12),
        ("integration.dt", DT),
    ] {
        config::set_number(&mut root, k, v).unwrap();
    }
    let pi = toml::Value::Float(std::f64::consts::PI);
    config::set(&mut root, "drive.psi0", toml::Value::Array(vec![toml::Value::Float(0.0), pi])).unwrap();
    root
}

/// The preset written by `export-model`, with the same `[drive]` and `[integration]`.
fn preset(wn: f64) -> (LinearRotorSpec, String, Vec<(String, String)>) {
    let p = config::planar(&planar_root(wn)).unwrap().rotor;
    let (mut text, files) = export(&LinearRotor::from_planar(&p).unwrap(), "jeffcott");
    text.push_str(&format!(
        "\n[drive]\nkind = \"acceleration\"\nomega0 = {:?}\nb = {:?}\nt_end = {T_END:?}\n[integration]\nrtol = 1e-10\natol = 1e-12\ndt = {DT:?}\n",
        0.2 * wn,
        1.6 * wn / T_END
    ));
    let load = |files: &[(String, String)]| {
        let files = files.to_vec();
        move |name: &str| files.iter().find(|f| f.0 == name).map(|f| f.1.clone().into_bytes()).ok_or_else(|| "missing".to_string())
    };
    let spec = LinearRotorSpec::new(text.parse().unwrap(), &mut load(&files)).unwrap();
    (spec, text, files)
}

/// Each point of a sweep over the balls' drag is the run of the config with that drag written
/// in by hand, set up here from the config's own numbers (not by the sweep's `run_of`): the
/// same summary to the bit. And the rows match the native planar sweep over `planar.c_psi`:
/// the final amplitude (a sample at `t_end` on both) to 1e-7 of the peak (the two models agree
/// sample by sample to 1e-8 of the peak at rtol 1e-10, tests/linear_rotor_config.rs), and the
/// peak, which the planar run follows on its dense output and the linear one at its samples,
/// low by at most the sampling's `(Ω dt)²/8` relative (the radius of a synchronous whirl turns
/// by at most `Ω dt` between samples).
#[test]
fn a_sweep_over_the_drag_is_the_config_run_by_hand_and_the_native_sweep() {
    let wn = autobal::planar::PlanarRotor { s2: 0.0, ..autobal::planar::PlanarRotor::paper() }.natural_frequency();
    let (spec, text, files) = preset(wn);
    let drags = vec![0.05, 0.2];
    let mut rows = vec![];
    let grid = Grid::new(vec![Axis::new("linear_rotor.drag", drags.clone())]).unwrap();
    let out = simulate_grid(
        &spec,
        &grid,
        0..grid.len(),
        &mut |i, v, r| {
            rows.push((i, v.to_vec(), r.summary.clone()));
            true
        },
        &Control::none(),
    )
    .unwrap();
    assert!(out.complete());
    assert_eq!(LINEAR_SUMMARY_COLUMNS.len(), linear_summary_values(&rows[0].2).len());
    let mut native = vec![];
    let base = config::planar(&planar_root(wn)).unwrap();
    let pg = Grid::new(vec![Axis::new("planar.c_psi", drags.clone())]).unwrap();
    simulate_grid(
        &base,
        &pg,
        0..pg.len(),
        &mut |_, _, r| {
            native.push(summary_values(&r.summary));
            true
        },
        &Control::none(),
    )
    .unwrap();
    let col = |c: &str| SUMMARY_COLUMNS.iter().position(|x| *x == c).unwrap();
    let lcol = |c: &str| LINEAR_SUMMARY_COLUMNS.iter().position(|x| *x == c).unwrap();
    for ((i, v, s), n) in rows.iter().zip(&native) {
        // by hand: the drag in the config's text, the run's settings from its tables
        let mut root: Table = text.parse().unwrap();
        let b = root.get_mut("linear_rotor").and_then(|v| v.get_mut("balancer")).and_then(|v| v.as_array_mut()).unwrap()[0].as_table_mut().unwrap();
        b.insert("drag".into(), toml::Value::Float(v[0]));
        let cfg = linear_rotor(&root, &mut |name| files.iter().find(|f| f.0 == name).map(|f| f.1.clone()).ok_or_else(|| "missing".into())).unwrap();
        assert_eq!(cfg.rotor.balancers[0].drag, drags[*i]);
        let drive = Drive::Acceleration { omega0: 0.2 * wn, b: 1.6 * wn / T_END };
        let rs =
            RunSettings { t_end: T_END, dt: DT, rtol: 1e-10, atol: 1e-12, method: Method::Auto, max_steps: 10_000_000, max_wall_s: None, physical_nodes: None };
        let direct = simulate(&cfg.rotor, &drive, &rs, &Control::none(), |_| true).unwrap();
        assert_eq!(*s, direct, "point {i}");
        let l = linear_summary_values(s);
        assert_eq!((l[lcol("completed")], l[lcol("t_reached")]), (1.0, T_END));
        let peak = n[col("peak_amplitude")];
        assert!(
            (l[lcol("final_amplitude")] - n[col("final_amplitude")]).abs() <= 1e-7 * peak,
            "point {i}: {} vs {}",
            l[lcol("final_amplitude")],
            n[col("final_amplitude")]
        );
        let w = n[col("omega_at_peak")];
        let low = (peak - l[lcol("peak_amplitude")]) / peak;
        assert!(low >= -1e-7 && low <= (w * DT).powi(2) / 8.0, "point {i}: peak {} vs native {peak} ({low:e})", l[lcol("peak_amplitude")]);
        // a passage through resonance: the peak near the critical speed
        assert!((0.8 * wn..1.3 * wn).contains(&l[lcol("omega_at_peak")]), "{l:?}");
    }
    // the drag reached the rotor: the runs differ
    assert_ne!(rows[0].2.final_radius, rows[1].2.final_radius);
}

/// Without `[drive]` a point runs `simulate`'s default run-up (from rest to ω_max in 1000
/// revolutions, `dt = t_end/2000`); paths that do not exist, and values the config refuses, are
/// one-line errors naming the path and the point before anything runs.
#[test]
fn default_run_and_errors_name_the_path() {
    let wn = autobal::planar::PlanarRotor { s2: 0.0, ..autobal::planar::PlanarRotor::paper() }.natural_frequency();
    let (spec, _, _) = preset(wn);
    let cfg = spec.config_at(&[("linear_rotor.omega_max", 900.0)]).unwrap();
    let mut no_drive = cfg.clone();
    no_drive.drive = None;
    let run = autobal::linear_rotor::spec::run_of(&no_drive).unwrap();
    let t_end = 2.0 * std::f64::consts::TAU * 1000.0 / 900.0;
    assert!(run.default_drive);
    assert_eq!(run.drive, Drive::Acceleration { omega0: 0.0, b: 900.0 / t_end });
    assert_eq!((run.settings.t_end, run.settings.dt), (t_end, t_end / 2000.0));
    let err = |path: &str, v: f64| autobal::sweep::check_batch(&spec, &[path], &[v]).unwrap_err().to_string();
    let e = err("linear_rotor.nope", 1.0);
    assert!(e.starts_with("linear_rotor.nope: unknown parameter path"), "{e}");
    let e = err("drive.psi0", 1.0);
    assert!(e.starts_with("drive.psi0: unknown parameter path"), "{e}");
    let e = err("linear_rotor.drag", -1.0);
    assert!(e.starts_with("linear_rotor.") && e.contains("drag") && e.ends_with("(at the point linear_rotor.drag = -1)"), "{e}");
    let e = err("linear_rotor.balls", 2.5);
    assert!(e.starts_with("linear_rotor.balls:"), "{e}");
    let e = err("linear_rotor.me", f64::NAN);
    assert!(e.starts_with("linear_rotor.me:"), "{e}");
    assert!(!e.contains('\n'));
}
