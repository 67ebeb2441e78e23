//! Fuzzing harness (issue 12 §5): property tests with random TOML trees, random `--set`
//! overrides, random text and extreme numbers, over the config parser, the validation and the
//! model constructors, and then the analyses the accepted configs feed.
//!
//! Every outcome must be `Ok` with every reported number finite, or an error whose message
//! begins with a real config key (or table, or option) — never a panic, never a hang. The
//! number of cases per property is fixed (so `cargo test` runs them in bounded time, ~10 s);
//! `PROPTEST_CASES=20000 cargo test -p autobal-commands fuzz` runs a longer campaign. Failures are
//! shrunk to a minimal input and printed; a case that fails should become a named regression
//! test in `tests/robustness.rs`.

use crate::config::{self, SCHEMA};
use crate::{linear, output};
use autobal::spatial::linear_model::Balls;
use proptest::prelude::*;
use proptest::test_runner::Config as RunnerConfig;
use toml::{Table, Value};

/// Cases per property: `PROPTEST_CASES`, else `default`.
fn cases(default: u32) -> RunnerConfig {
    let n = std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(default);
    RunnerConfig { cases: n, max_shrink_iters: 2000, failure_persistence: None, ..RunnerConfig::default() }
}

/// Numbers where validation and numerics break: zeros, signs, subnormals, the ends of f64,
/// NaN and infinities, the edges of the ranges, any power of ten, and anything at all.
fn extreme_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => prop::sample::select(vec![
            0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 3.0, 9.0, 10.0, 100.0, 101.0, 1000.0, 1e4, 1e6, 1e9, 1e12, 1e13, 1e-2, 1e-3, 1e-14,
            1e-300, 1e-308, -1e-308, 5e-324, 1e308, -1e308, f64::MAX, f64::MIN, f64::MIN_POSITIVE, f64::EPSILON, 0.999_999_999,
            f64::NAN, f64::INFINITY, f64::NEG_INFINITY,
        ]),
        3 => -10.0f64..10.0,
        3 => (-320i32..=308, any::<bool>(), 1.0f64..10.0).prop_map(|(e, neg, m)| if neg { -m * 10f64.powi(e) } else { m * 10f64.powi(e) }),
        1 => any::<f64>(),
    ]
}

/// A number for `field`: mostly inside its range (`autobal::limits`: the ends, just inside
/// them, uniform, log-uniform over the magnitudes), sometimes any extreme number. The accepted
/// inputs are the ones that reach the analyses, where a range that is too wide would show as a
/// non-finite result.
fn value_for(field: &str) -> BoxedStrategy<f64> {
    let Some(l) = autobal::limits::limit(field) else { return extreme_f64().boxed() };
    let (lo, hi) = (l.lo, l.hi);
    let edges: Vec<f64> = [lo, hi, lo + (hi - lo) * 1e-12, hi - (hi - lo) * 1e-12, 0.0, 1.0, -1.0, 0.5 * (lo + hi), 1e-300, -1e-300]
        .into_iter()
        .filter(|v| l.contains(*v))
        .collect();
    let top = hi.abs().max(lo.abs());
    let magnitude = (-300.0f64..=top.log10(), any::<bool>()).prop_map(move |(e, neg)| {
        let v = 10f64.powf(e);
        let v = if neg { -v } else { v };
        v.clamp(lo, hi)
    });
    let within = (0.0f64..=1.0).prop_map(move |t| lo + t * (hi - lo));
    prop_oneof![
        3 => prop::sample::select(edges),
        3 => within,
        3 => magnitude,
        1 => extreme_f64(),
    ]
    .boxed()
}

/// A TOML value: numbers (extreme floats, any integer), strings (including the names the
/// config knows), booleans, nested arrays and tables.
fn toml_value() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        6 => extreme_f64().prop_map(Value::Float),
        2 => (-3i64..200).prop_map(Value::Integer),
        1 => any::<i64>().prop_map(Value::Integer),
        1 => prop::sample::select(vec!["exact", "paper", "speed", "acceleration", "torque", "motor", "schedule", "dop853", "rosenbrock", "", "x"])
            .prop_map(|s| Value::String(s.to_string())),
        1 => "\\PC{0,12}".prop_map(Value::String),
        1 => any::<bool>().prop_map(Value::Boolean),
    ];
    leaf.prop_recursive(3, 32, 6, |inner| {
        prop_oneof![
            3 => prop::collection::vec(inner.clone(), 0..6).prop_map(Value::Array),
            1 => prop::collection::btree_map("[a-z_]{1,8}", inner, 0..4).prop_map(|m| Value::Table(m.into_iter().collect())),
        ]
    })
}

/// A `table.key` of the schema (mostly) or a made-up one.
fn key() -> impl Strategy<Value = (String, String)> {
    let known: Vec<(String, String)> = SCHEMA.iter().flat_map(|(t, ks)| ks.iter().map(move |k| (t.to_string(), k.to_string()))).collect();
    prop_oneof![
        9 => prop::sample::select(known),
        1 => ("[a-z]{1,10}", "[a-z_]{1,10}"),
    ]
}

/// The three embedded or example configs, or nothing, as the tree the mutations start from.
fn base() -> impl Strategy<Value = Table> {
    prop::sample::select(vec![config::DEFAULT_CONFIG, include_str!("../../../examples/dimensional.toml"), config::DEFAULT_PLANAR, ""])
        .prop_map(|t| t.parse::<Table>().expect("examples parse"))
}

/// A key with a value: mostly a number from [`value_for`] (a whole number for the counts), else
/// any TOML value.
fn assignment() -> impl Strategy<Value = ((String, String), Value)> {
    key().prop_flat_map(|(t, k)| {
        let field = format!("{t}.{k}");
        let number = if ["balancer.balls", "balancer2.balls", "dimensionless.n", "planar.n"].contains(&field.as_str()) {
            prop_oneof![3 => 0i64..12, 1 => 0i64..=110, 1 => any::<i64>()].prop_map(Value::Integer).boxed()
        } else {
            value_for(&field).prop_map(Value::Float).boxed()
        };
        (Just((t, k)), prop_oneof![4 => number, 1 => toml_value()])
    })
}

/// Up to six random assignments on a base config.
fn config_tree() -> impl Strategy<Value = Table> {
    (base(), prop::collection::vec(assignment(), 0..6)).prop_map(|(mut root, sets)| {
        for ((t, k), v) in sets {
            let table = root.entry(t).or_insert_with(|| Value::Table(Table::new()));
            if let Value::Table(tab) = table {
                tab.insert(k, v);
            }
        }
        root
    })
}

/// The error message must begin with a config key, a table, or an option, followed by `:`.
fn assert_names_a_field(msg: &str) {
    let first = msg.split(": ").next().unwrap_or("");
    let keys: Vec<String> = SCHEMA.iter().flat_map(|(t, ks)| ks.iter().map(move |k| format!("{t}.{k}"))).collect();
    let ok = keys.iter().any(|k| k == first)
        || SCHEMA.iter().any(|(t, _)| *t == first)
        || first == "config"
        || first.starts_with("--set ")
        || first.starts_with("--config ")
        || first.starts_with("test: line ")
        // an unknown key or table is named as the user spelt it
        || msg.contains(": unknown key (") || msg.contains(": unknown table (");
    assert!(ok, "error names no field: `{msg}`");
    assert!(!msg.contains('\n'), "multi-line error: `{msg}`");
    let longest = msg.split(|c: char| !c.is_ascii_digit()).map(str::len).max().unwrap_or(0);
    assert!(longest <= 24, "a {longest}-digit number in `{msg}`");
}

/// Run what an accepted spatial config feeds: the analytic outputs (finite, checked by
/// `output::check_results`) and the linear stability on a coarse grid.
fn analyse_spatial(cfg: &config::Config) -> Result<(), String> {
    output::check_results(cfg).map_err(|e| format!("{e:#}"))?;
    let w = linear::omega_max(cfg, None).map_err(|e| format!("{e:#}"))?;
    for balls in [Balls::Locked, Balls::Free] {
        if balls == Balls::Free && cfg.model.balls.is_none() {
            continue;
        }
        match linear::compare(&cfg.model, w, 60, balls) {
            Ok(c) => autobal::limits::check_finite("stability", &c.exact).map_err(|e| e.to_string())?,
            // an eigen-solver failure is a typed error, not a panic; it must be rare
            Err(e) => assert!(format!("{e:#}").contains("did not converge"), "{e:#}"),
        }
    }
    Ok(())
}

/// Validate a tree as the commands do; `Ok` configs are analysed. Returns the outcome message.
fn outcome(root: &Table) -> Result<(), String> {
    let spatial = config::build(root, "test");
    let planar = config::build_planar(root, "test");
    for r in [spatial.as_ref().err(), planar.as_ref().err()].into_iter().flatten() {
        assert_names_a_field(&format!("{r:#}"));
    }
    if let Ok(cfg) = &spatial {
        analyse_spatial(cfg)?;
    }
    if let Ok(p) = &planar {
        autobal::limits::check_finite("planar", &p.rotor).map_err(|e| e.to_string())?;
        autobal::limits::check_finite("settings", &p.settings).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The round-2 configs as bases: the spatial simulation (one plane, and two planes with a couple
/// unbalance, y supports and gravity) and the planar rotor.
fn base_round_two() -> impl Strategy<Value = Table> {
    prop::sample::select(vec![include_str!("../../../examples/spatial.toml"), include_str!("../../../examples/spatial_two_plane.toml"), config::DEFAULT_PLANAR])
        .prop_map(|t| t.parse::<Table>().expect("examples parse"))
}

/// Up to six random assignments on a round-2 base, drawn mostly from the tables round 2 added
/// (`[couple]`, `[balancer2]`, `[spatial]`, `[initial]`, the real-ball keys, `drive.xy0`), so
/// that every optional table meets every model.
fn config_tree_round_two() -> impl Strategy<Value = Table> {
    let round_two = prop::sample::select(
        SCHEMA
            .iter()
            .flat_map(|(t, ks)| ks.iter().map(move |k| (t.to_string(), k.to_string())))
            .filter(|(t, k)| {
                matches!(t.as_str(), "couple" | "balancer2" | "spatial" | "initial" | "planar")
                    || k.ends_with("_y")
                    || [
                        "ball_diameter",
                        "contact",
                        "restitution",
                        "contact_stiffness",
                        "rolling_resistance",
                        "slip_rate",
                        "xy0",
                        "xy_rate0",
                        "axis_tilt",
                        "balls",
                    ]
                    .contains(&k.as_str())
            })
            .collect::<Vec<_>>(),
    );
    let assignment2 = prop_oneof![
        3 => round_two.prop_flat_map(|(t, k)| {
            let field = format!("{t}.{k}");
            let v = match k.as_str() {
                "contact" | "lock_tilt" => any::<bool>().prop_map(Value::Boolean).boxed(),
                "balls" | "n" => prop_oneof![3 => 0i64..6, 1 => 0i64..=110].prop_map(Value::Integer).boxed(),
                _ if ["gravity"].contains(&k.as_str()) => prop::collection::vec(value_for(&field), 3).prop_map(|v| Value::Array(v.into_iter().map(Value::Float).collect())).boxed(),
                _ if ["position", "velocity", "tilt", "tilt_rate", "xy0", "xy_rate0"].contains(&k.as_str()) => {
                    prop::collection::vec(value_for(&field), 2).prop_map(|v| Value::Array(v.into_iter().map(Value::Float).collect())).boxed()
                }
                _ => value_for(&field).prop_map(Value::Float).boxed(),
            };
            (Just((t, k)), v)
        }),
        1 => assignment(),
    ];
    (base_round_two(), prop::collection::vec(assignment2, 0..6)).prop_map(|(mut root, sets)| {
        for ((t, k), v) in sets {
            if let Value::Table(tab) = root.entry(t).or_insert_with(|| Value::Table(Table::new())) {
                tab.insert(k, v);
            }
        }
        root
    })
}

/// Every model on a round-2 tree: each build is accepted or names a real key; on an accepted
/// one, [`autobal::config::entry_use`] sorts every entry into its classes, naming only real keys
/// and tables, and the spatial rotor's state is finite.
fn outcome_round_two(root: &Table) -> Result<(), String> {
    use autobal::config::Model;
    let keys: Vec<String> = SCHEMA.iter().flat_map(|(t, ks)| ks.iter().map(move |k| format!("{t}.{k}"))).collect();
    let real = |k: &str| keys.iter().any(|x| x == k) || SCHEMA.iter().any(|(t, _)| format!("[{t}]") == k);
    let built = [
        (Model::Linear, autobal::config::spatial(root).map(drop)),
        (Model::Spatial, autobal::config::spatial_simulation(root).map(drop)),
        (Model::Planar, autobal::config::planar(root).map(drop)),
    ];
    for (model, b) in built {
        match b {
            Err(e) => assert_names_a_field(&e.to_string()),
            Ok(()) => {
                let u = autobal::config::entry_use(root, &[model]);
                for k in u.foreign.iter().chain(&u.moot).map(|u| u.key.as_str()).chain(u.simulation_only.iter().chain(&u.linear_only).map(String::as_str)) {
                    assert!(real(k), "{model:?}: entry_use names `{k}`, no key of the config");
                    // a reported entry is one the config has
                    let table = k.trim_start_matches('[').trim_end_matches(']').split('.').next().unwrap();
                    assert!(root.contains_key(table), "{model:?}: `{k}` is not in the config");
                }
                if model != Model::Linear {
                    assert!(u.simulation_only.is_empty(), "{model:?}: {:?}", u.simulation_only);
                }
                // the linear model's own inputs are used where it runs
                if model != Model::Spatial {
                    assert!(u.linear_only.is_empty(), "{model:?}: {:?}", u.linear_only);
                }
            }
        }
    }
    if let Ok(sim) = autobal::config::spatial_simulation(root) {
        autobal::limits::check_finite("rotor", &sim.rotor).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The SI parameter paths ([`autobal::spatial::paths::PARAMETER_PATHS`]) but `balancer.balls`.
const SI_FIELDS: [&str; 16] = [
    "rotor.mass",
    "rotor.equatorial_moment",
    "rotor.polar_moment",
    "rotor.z",
    "balancer.z",
    "supports.z_left",
    "supports.z_right",
    "supports.stiffness_left",
    "supports.stiffness_right",
    "supports.damping_left",
    "supports.damping_right",
    "unbalance.mass",
    "unbalance.radius",
    "balancer.ball_mass",
    "balancer.race_radius",
    "balancer.drag",
];

/// The SI example (examples/dimensional.toml) with every field scaled by up to `10^±s` (`s` from
/// 0.3 to 8, positions shifted instead), sometimes one field replaced by any number: rotors that
/// make sense as a whole, out to the edges of the ranges.
fn near_the_example() -> impl Strategy<Value = Vec<f64>> {
    const EXAMPLE: [f64; 16] = [20.0, 0.6, 0.15, 0.25, 0.45, 0.0, 0.5, 2e6, 3e6, 300.0, 300.0, 0.01, 0.1, 0.02, 0.12, 0.5];
    (prop::sample::select(vec![0.3, 1.0, 3.0, 8.0]), prop::collection::vec(-1.0f64..1.0, 16), prop::option::weighted(0.2, (0usize..16, extreme_f64())))
        .prop_map(|(s, u, replace)| {
            let mut v: Vec<f64> = EXAMPLE
                .iter()
                .zip(&u)
                .enumerate()
                .map(|(i, (x, t))| if (3..=6).contains(&i) { x + t * 10f64.powf(s - 1.0) } else { x * 10f64.powf(s * t) })
                .collect();
            if let Some((i, x)) = replace {
                v[i] = x;
            }
            v
        })
}

/// The dimensionless fields of [`autobal::spatial::params::DimensionlessInput`] and the masses.
const DIMENSIONLESS_FIELDS: [&str; 10] = [
    "dimensionless.c_sigma",
    "dimensionless.rho_s",
    "dimensionless.l_left",
    "dimensionless.z_a",
    "dimensionless.h_x",
    "dimensionless.h_s",
    "dimensionless.delta_a",
    "dimensionless.m0",
    "dimensionless.r0",
    "dimensionless.m",
];

proptest! {
    #![proptest_config(cases(1000))]

    /// Random trees on the example configs: validation names a real key, accepted models give
    /// finite results.
    #[test]
    fn random_config_trees(root in config_tree()) {
        let t0 = std::time::Instant::now();
        if let Err(e) = outcome(&root) {
            panic!("accepted, but: {e}\nconfig:\n{}", toml::to_string(&root).unwrap_or_default());
        }
        // a hang guard, not a performance claim: one case is milliseconds
        prop_assert!(t0.elapsed().as_secs() < 60, "case took {:?}", t0.elapsed());
    }

    /// Random `--set` assignments (key and value as typed on the command line).
    /// Round-2 trees (every optional table of the spatial simulation, two planes, real balls,
    /// the planar start) against every model and the entry-use check.
    #[test]
    fn random_round_two_trees(root in config_tree_round_two()) {
        let t0 = std::time::Instant::now();
        if let Err(e) = outcome_round_two(&root) {
            panic!("accepted, but: {e}\nconfig:\n{}", toml::to_string(&root).unwrap_or_default());
        }
        prop_assert!(t0.elapsed().as_secs() < 60, "case took {:?}", t0.elapsed());
    }

    #[test]
    fn random_set_overrides(
        sets in prop::collection::vec(
            (key(), prop_oneof![
                extreme_f64().prop_map(|v| format!("{v}")),
                extreme_f64().prop_map(|v| format!("{v:e}")),
                prop::sample::select(vec!["nan", "inf", "-inf", "+inf", "1e400", "-0", "0x10", "1_000", "[1, 2]", "[[0, 0], [1, 1]]", "{a = 1}", "\"x\"", "true", "", "=", "1e", ".5", "5."]).prop_map(str::to_string),
                "\\PC{0,10}",
            ]),
            1..4,
        ),
        dimensional in any::<bool>(),
    ) {
        let args: Vec<String> = sets.iter().map(|((t, k), v)| format!("{t}.{k}={v}")).collect();
        for planar in [false, true] {
            let r = if planar {
                config::load_planar(None, &args).map(|_| ())
            } else if dimensional {
                let mut root: Table = include_str!("../../../examples/dimensional.toml").parse().unwrap();
                args.iter().try_for_each(|a| config::apply_set(&mut root, a)).and_then(|_| config::build(&root, "test").map(|_| ()))
            } else {
                config::load(None, &args).and_then(|c| output::check_results(&c))
            };
            if let Err(e) = r {
                assert_names_a_field(&format!("{e:#}"));
            }
        }
    }

    /// Arbitrary text as a config file: the parser never panics, errors say where.
    #[test]
    fn random_text(text in prop_oneof![
        "\\PC{0,200}",
        prop::collection::vec(prop::sample::select(vec!["[", "]", "[[", "]]", "{", "}", "=", "\"", "'", ",", ".", "\n", "dimensionless", "planar", "c_sigma", "1e308", "nan", "#", " "]), 0..60).prop_map(|v| v.concat()),
    ]) {
        match config::parse_text(&text, "test") {
            Ok(root) => {
                if let Err(e) = outcome(&root) {
                    panic!("accepted, but: {e}\ntext: {text:?}");
                }
            }
            Err(e) => {
                let msg = format!("{e:#}");
                prop_assert!(msg.starts_with("test: "), "{msg}");
                prop_assert!(!msg.contains('\n'), "{msg}");
            }
        }
    }

    /// The library's constructors directly, with extreme numbers in every field.
    #[test]
    fn si_constructor(
        v in prop_oneof![
            1 => SI_FIELDS.iter().map(|f| value_for(f)).collect::<Vec<_>>(),
            2 => near_the_example(),
        ],
        balls in prop_oneof![4 => 0u32..6, 1 => 0u32..=110],
    ) {
        use autobal::spatial::paths::{SpatialInput, SpatialSpec};
        // the example rotor with every SI field set through its parameter path
        let mut spec = SpatialSpec { input: SpatialInput::Si { rotor: autobal::spatial::dynamics::SpatialRotor::dimensional_example(), method: autobal::spatial::inertia::AnisotropyMethod::Exact }, delta_a_override: None };
        for (path, x) in SI_FIELDS.iter().zip(&v) {
            spec.set(path, *x).unwrap();
        }
        spec.set("balancer.balls", balls as f64).unwrap();
        let SpatialInput::Si { rotor: r, .. } = &spec.input else { unreachable!() };
        for method in [autobal::spatial::inertia::AnisotropyMethod::Exact, autobal::spatial::inertia::AnisotropyMethod::Paper] {
            match r.to_dimensionless(method) {
                Ok(model) => {
                    let spec = SpatialSpec { input: SpatialInput::Si { rotor: r.clone(), method }, delta_a_override: None };
                    let cfg = config::Config { config: autobal::config::SpatialConfig { model, spec, analysis: config::Analysis { sensitivity_limit: 0.15, omega_max: None, operating_speed: None }, dimensional: true }, source: String::new() };
                    if let Err(e) = analyse_spatial(&cfg) {
                        panic!("accepted {r:?}, but: {e}");
                    }
                }
                Err(e) => assert_names_a_field(&e.to_string()),
            }
        }
    }

    /// The dimensionless constructor, with `ΔĀ` given or from masses (`dimensionless.r` and `n`
    /// drawn as well).
    #[test]
    fn dimensionless_constructor(
        v in DIMENSIONLESS_FIELDS.iter().map(|f| value_for(f)).collect::<Vec<_>>(),
        r in value_for("dimensionless.r"),
        n in prop_oneof![4 => 0u32..6, 1 => 0u32..=110],
        direct in any::<bool>(),
        paper in any::<bool>(),
    ) {
        use autobal::spatial::inertia::AnisotropyMethod;
        use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, MassSet, SpatialModel};
        let anisotropy = if direct {
            AnisotropyInput::Direct(v[6])
        } else {
            AnisotropyInput::Masses { masses: MassSet { m0: v[7], r0: v[8], m: v[9], r, n }, d_a: None }
        };
        let inp = DimensionlessInput {
            c_sigma: v[0], rho_s: v[1], l_left: v[2], z_a: v[3], anisotropy, h_x: v[4], h_s: v[5],
            method: if paper { AnisotropyMethod::Paper } else { AnisotropyMethod::Exact },
            direct_balls: None,
        };
        match SpatialModel::from_dimensionless(&inp) {
            Ok(model) => {
                let spec = autobal::spatial::paths::SpatialSpec { input: autobal::spatial::paths::SpatialInput::Dimensionless(inp), delta_a_override: None };
                let cfg = config::Config { config: autobal::config::SpatialConfig { model, spec, analysis: config::Analysis { sensitivity_limit: 0.15, omega_max: None, operating_speed: None }, dimensional: false }, source: String::new() };
                if let Err(e) = analyse_spatial(&cfg) {
                    panic!("accepted {inp:?}, but: {e}");
                }
            }
            Err(e) => assert_names_a_field(&e.to_string()),
        }
    }
}
