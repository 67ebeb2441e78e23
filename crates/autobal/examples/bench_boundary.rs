//! The boundary tracer against the verdict map of the same plane, one at a time, for instruction
//! counts and CPU time (`bench/boundary.py` runs it): the 12-state model of 000 eq (6) over
//! z̄_A ∈ [−2, 2] × Ω ∈ [0.05, 4.5] (003 Fig. 5a's layout, the plane of `bench_map`), on one
//! thread.
//!
//! Usage: `cargo run --release --example bench_boundary -p autobal -- MODE [N] [docs]`, MODE one of
//! - `verdict`: the library's verdict map on an N × N grid (default 400; Routh–Hurwitz on the
//!   characteristic polynomial in Ω, changes confirmed directly);
//! - `margin`: the margin map on the same grid;
//! - `boundary`: the traced stability boundary of the plane (default settings);
//! - `none`: the set-up alone (the process, the thread pool, the spec), to subtract;
//!
//! and `docs` the default rotor (the docs' example) instead of the benchmark's.
//!
//! Prints one JSON line: what was computed and its counts.

use autobal::control::Control;
use autobal::spatial::boundary::{trace_boundary, TraceSettings};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::map::{stability_map, Axis, MapSettings, Quantity};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput};
use autobal::spatial::paths::{SpatialInput, SpatialSpec};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map(String::as_str).unwrap_or("boundary").to_string();
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(400);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    // a third argument `docs`: the default rotor (paper 000's, the plane of the docs' example
    // `autobal map --x dimensionless.z_a=-2:2:100 --y omega=0.05:4.5:100 --boundary`)
    let docs = args.get(3).is_some_and(|a| a == "docs");
    let spec = SpatialSpec {
        input: SpatialInput::Dimensionless(if docs {
            DimensionlessInput::default()
        } else {
            DimensionlessInput {
                c_sigma: 0.75,
                rho_s: 0.4,
                l_left: 0.8,
                z_a: 0.0,
                anisotropy: AnisotropyInput::Direct(0.1),
                h_x: 0.05,
                h_s: 0.1,
                method: AnisotropyMethod::Exact,
                direct_balls: Some((0.05, 0.5)),
            }
        }),
        delta_a_override: None,
    };
    let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, n);
    let y = Axis::linspace("omega", 0.05, 4.5, n);
    let map = |q: Quantity| {
        let s = MapSettings { balls: Balls::Free, quantity: q, omega: None };
        let mut stable = 0usize;
        let o = pool
            .install(|| {
                stability_map(&spec, &x, &y, &s, &Control::none(), &mut |_, row| {
                    stable += row.iter().filter(|c| c.stable).count();
                    true
                })
            })
            .expect("map");
        println!("{{\"mode\": \"{mode}\", \"n\": {n}, \"points\": {}, \"stable\": {stable}, \"continued\": {}, \"direct\": {}}}", n * n, o.continued, o.direct);
    };
    match mode.as_str() {
        "verdict" => map(Quantity::Verdict),
        "margin" => map(Quantity::Margin),
        "boundary" => {
            let b = pool.install(|| trace_boundary(&spec, &x, &y, &TraceSettings::default())).expect("boundary");
            let points: usize = b.curves.iter().map(|c| c.points.len()).sum();
            let on: usize = b.curves.iter().map(|c| c.points.iter().filter(|p| p.on_boundary).count()).sum();
            println!(
                "{{\"mode\": \"boundary\", \"n\": {n}, \"curves\": {}, \"codim2\": {}, \"points\": {points}, \"on_boundary\": {on}, \"evaluations\": {}}}",
                b.curves.len(),
                b.codim2.len(),
                b.evaluations
            );
        }
        "none" => println!("{{\"mode\": \"none\", \"n\": {n}, \"x\": {}, \"y\": {}}}", x.values.len(), y.values.len()),
        m => {
            eprintln!("unknown mode {m}: verdict, margin, boundary or none");
            std::process::exit(2);
        }
    }
}
