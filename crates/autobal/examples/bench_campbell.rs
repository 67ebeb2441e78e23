//! Campbell benchmark, autobal side: the diagram of paper 000's base case with masses (the
//! default config), balls free (12 states) and locked (8 states), over SPEEDS speeds up to 5:
//! eigenvalues, eigenvectors, tracking and classification of every mode, single-threaded.
//! `bench/campbell.py` runs it beside ROSS and NumPy. Prints one JSON line (seconds, median of
//! REPEAT runs in this process, and the min-max).
//!
//! With `command` as the third argument it does instead the library work of `autobal campbell
//! --points SPEEDS --omega-max 5 --format json` (`bench/commands.py` runs the two side by side),
//! with the same library calls in the same order: the default config parsed and built
//! (`autobal::config::spatial`), `campbell_stream` over the same speeds with balls free, each
//! speed's modes checked finite and kept (the command keeps every speed up to 2 000 for its
//! figures and its fixed-axes view), then the fixed axes' curves and crossings with `1 × Ω`
//! (`fixed_axes`), checked finite. What it leaves to the command is the command's own
//! overhead: process start, argument parsing, the JSON text and its temporary files. It prints
//! the crossings' speeds, so that the bench can check it computed the command's diagram.
//!
//! Usage: `cargo run --release --example bench_campbell -p autobal -- [SPEEDS] [REPEAT] [command]`

use autobal::spatial::campbell::fixed_axes;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::params::{DimensionlessInput, SpatialModel};
use autobal::spatial::stability::{campbell_stream, Campbell, CampbellLine};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let reps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(21);
    if args.get(3).map(String::as_str) == Some("command") {
        return command(n, reps);
    }
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

/// The library calls of `autobal campbell --points n --omega-max 5 --format json` (module
/// docs), `reps` times; one JSON line: the median and min-max seconds, the crossings' speeds.
fn command(n: usize, reps: usize) {
    let mut times = vec![];
    let mut crossings = vec![];
    for _ in 0..reps.max(1) {
        let t = Instant::now();
        let root = autobal::config::parse(autobal::config::DEFAULT_SPATIAL, "default").expect("the default config parses");
        let cfg = autobal::config::spatial(&root).expect("the default config builds");
        let n = n.max(3);
        let speed = |k: usize| 5.0 * (k as f64 + 0.5) / n as f64;
        let mut kept = Campbell { omega: Vec::new(), lines: Vec::new() };
        campbell_stream(&cfg.model, (0..n).map(speed), Balls::Free, &mut |k, modes| {
            autobal::limits::check_finite("campbell.speeds", &modes).expect("finite");
            if kept.lines.is_empty() {
                kept.lines = modes.iter().map(|_| CampbellLine { modes: vec![] }).collect();
            }
            kept.omega.push(speed(k));
            for (l, m) in kept.lines.iter_mut().zip(modes) {
                l.modes.push(*m);
            }
            true
        })
        .expect("campbell");
        let fixed = fixed_axes(&cfg.model, &kept, Balls::Free, &[1]).expect("fixed axes");
        autobal::limits::check_finite("campbell.critical_speeds", &fixed.critical_speeds).expect("finite");
        times.push(t.elapsed().as_secs_f64());
        crossings = fixed.critical_speeds.iter().map(|c| c.omega).collect();
        std::hint::black_box(&kept);
    }
    times.sort_by(f64::total_cmp);
    let w: Vec<String> = crossings.iter().map(|w: &f64| format!("{w:?}")).collect();
    println!(
        "{{\"speeds\": {n}, \"command\": {{\"median_s\": {}, \"min_s\": {}, \"max_s\": {}, \"critical_omega\": [{}]}}}}",
        times[times.len() / 2],
        times[0],
        times[times.len() - 1],
        w.join(", ")
    );
}
