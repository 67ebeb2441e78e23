//! Paper 004's passage through resonance, timed in the library (samples kept in memory, as
//! SciPy's `solve_ivp` keeps its `t_eval` output), for `bench/passage.py`:
//!
//! ```text
//! cargo run --release --example passage -- [key=value ...]
//!   b=2.5 omega0=0 t_end=(600-omega0)/b dt=0.05 m3=0.03 n=2 c_psi=0.1 method=auto|dop853|rodas
//!   rtol=1e-8 atol=1e-9 repeats=1 samples=FILE
//! ```
//!
//! Prints one JSON line: the summary of the last run and the wall time of every run (the
//! integration and the samples, nothing else). With `samples=FILE` the samples of the last run
//! (`t, radius of C`) are written to FILE after the timing.
use autobal::planar::*;
use std::io::Write;

fn main() {
    let mut kv = std::collections::HashMap::new();
    for a in std::env::args().skip(1) {
        let Some((k, v)) = a.split_once('=') else {
            eprintln!("arguments are key=value, got {a:?}");
            std::process::exit(2);
        };
        kv.insert(k.to_string(), v.to_string());
    }
    let num = |k: &str, d: f64| -> f64 {
        kv.get(k)
            .map(|v| {
                v.parse().unwrap_or_else(|_| {
                    eprintln!("{k}: not a number: {v}");
                    std::process::exit(2)
                })
            })
            .unwrap_or(d)
    };
    let b = num("b", 2.5);
    let omega0 = num("omega0", 0.0);
    let mut p = PlanarRotor::paper();
    p.m3 = num("m3", 0.03);
    p.n = num("n", 2.0) as usize;
    p.c_psi = num("c_psi", p.c_psi);
    let method = match kv.get("method").map(String::as_str) {
        Some("dop853") => Method::Dop853,
        Some("rodas") => Method::Rodas,
        _ => Method::Auto,
    };
    let drive = Drive::Acceleration { omega0, b };
    let t_end = num("t_end", (600.0 - omega0) / b.abs());
    let mut st = Settings { method, ..Settings::new(&p, t_end) };
    st.dt = num("dt", 0.05);
    st.rtol = num("rtol", st.rtol);
    st.atol = num("atol", st.atol);
    let repeats = num("repeats", 1.0).max(1.0) as usize;
    let mut walls = vec![];
    let mut last = None;
    for _ in 0..repeats {
        let mut samples: Vec<(f64, f64)> = Vec::with_capacity((t_end / st.dt) as usize + 2);
        let t0 = std::time::Instant::now();
        let s = simulate(&p, &drive, &st, |s| {
            samples.push((s.t, s.amplitude));
            true
        })
        .unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(1)
        });
        walls.push(t0.elapsed().as_secs_f64());
        last = Some((s, samples));
    }
    let (s, samples) = last.expect("at least one run");
    if let Some(path) = kv.get("samples") {
        let mut f = std::io::BufWriter::new(std::fs::File::create(path).expect("samples file"));
        for (t, a) in &samples {
            writeln!(f, "{t:e} {a:e}").expect("write samples");
        }
    }
    println!(
        "{{\"wall_s\": {walls:?}, \"steps\": {}, \"implicit_steps\": {}, \"switches\": {}, \"rejected_steps\": {}, \"rhs_evaluations\": {}, \"peak_amplitude\": {:e}, \"omega_at_peak\": {}, \"t_at_peak\": {}, \"final_amplitude\": {:e}, \"balanced\": {}, \"samples\": {}}}",
        s.steps, s.implicit_steps, s.switches, s.rejected_steps, s.rhs_evaluations, s.peak_amplitude, s.omega_at_peak, s.t_at_peak, s.final_amplitude, s.balanced, samples.len()
    );
}
