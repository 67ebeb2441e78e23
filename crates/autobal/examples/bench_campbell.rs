//! Campbell benchmark, autobal side: the diagram of paper 000's base case with masses (the
//! default config), balls free (12 states) and locked (8 states), over SPEEDS speeds up to 5:
//! eigenvalues, eigenvectors, tracking and classification of every mode, single-threaded.
//! `bench/campbell.py` runs it beside ROSS and NumPy. Prints one JSON line (seconds, median of
//! REPEAT runs in this process, and the min-max).
//!
//! Usage: `cargo run --release --example bench_campbell -p autobal -- [SPEEDS] [REPEAT]`

use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::{DimensionlessInput, SpatialModel};
use autobal::spatial::stability::campbell_stream;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let reps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(21);
    let m = SpatialModel::from_dimensionless(&DimensionlessInput::paper_000(0.8)).expect("valid");
    let mut report = vec![];
    for (name, balls) in [("free", Balls::Free), ("locked", Balls::Locked)] {
        let mut times = vec![];
        let mut stats = None;
        for _ in 0..reps {
            let t = Instant::now();
            let mut sink = 0.0;
            let s = campbell_stream(&m, (0..n).map(|k| 5.0 * (k as f64 + 0.5) / n as f64), balls, &mut |_, modes| {
                sink += modes[0].fixed_frequency;
                true
            })
            .expect("campbell");
            times.push(t.elapsed().as_secs_f64());
            std::hint::black_box(sink);
            stats = Some(s);
        }
        times.sort_by(f64::total_cmp);
        let s = stats.expect("ran");
        report.push(format!(
            "\"{name}\": {{\"median_s\": {}, \"min_s\": {}, \"max_s\": {}, \"continued\": {}, \"direct\": {}}}",
            times[times.len() / 2],
            times[0],
            times[times.len() - 1],
            s.continued,
            s.direct
        ));
    }
    println!("{{\"speeds\": {n}, {}}}", report.join(", "));
}
