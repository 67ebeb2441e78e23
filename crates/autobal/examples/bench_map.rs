//! Stability-map benchmark, autobal side: the 12-state model of 000 eq (6) over a grid
//! z̄_A × Ω (003 Fig. 5a layout), single-threaded (the maps on `BENCH_THREADS` threads if set). `bench/stability_map.py` runs this, builds the
//! same matrices in NumPy, times NumPy's best ways to the same outputs, and compares.
//!
//! Timed, each from the model parameters to the map (model set-up included):
//! - `margin`: the library's map ([`autobal::spatial::map::stability_map`]): continuation of the
//!   rightmost root of the characteristic polynomial in Ω, certified; where it cannot be, all
//!   roots continued from the last spectrum (Aberth), certified; QR where neither is;
//! - `verdict`: the library's map, Routh–Hurwitz on the polynomial coefficients, changes of
//!   verdict confirmed directly;
//! - `boundary`: the stability boundary of the same plane traced as curves
//!   ([`autobal::spatial::boundary::trace_boundary`], default settings);
//! - `margin_qr`, `verdict_direct`: the per-point paths (QR eigenvalues of each state matrix;
//!   Hessenberg characteristic polynomial + Routh–Hurwitz), for reference.
//!
//! Usage: `[BENCH_THREADS=N] cargo run --release --example bench_map -p autobal -- NX NY OUT.bin [maps]`
//! Prints one JSON line of timings; OUT.bin holds NX·NY margins (f64 LE) then NX·NY verdicts
//! (u8), row-major (row = speed).

use autobal::linalg::eigen::{characteristic_polynomial, routh_hurwitz_stable, spectral_abscissa};
use autobal::spatial::boundary::{trace_boundary, TraceSettings};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, StateSpace};
use autobal::spatial::map::{stability_map, Axis, MapSettings, Quantity};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
use autobal::spatial::paths::{SpatialInput, SpatialSpec};
use std::io::Write;
use std::time::Instant;

fn input(z: f64) -> DimensionlessInput {
    DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left: 0.8,
        z_a: z,
        anisotropy: AnisotropyInput::Direct(0.1),
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: Some((0.05, 0.5)),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let nx: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(400);
    let ny: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(400);
    let out = args.get(3).cloned().unwrap_or_else(|| "bench_map.bin".into());
    // the maps' thread count (default 1; `BENCH_THREADS=2` for the scaling measurement)
    let threads = std::env::var("BENCH_THREADS").ok().and_then(|s| s.parse().ok()).unwrap_or(1);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    let spec = SpatialSpec { input: SpatialInput::Dimensionless(input(0.0)), delta_a_override: None };
    let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, nx);
    let y = Axis::linspace("omega", 0.05, 4.5, ny);
    let run = |q: Quantity| {
        let mut cells = Vec::with_capacity(nx * ny);
        let s = MapSettings { balls: Balls::Free, quantity: q, omega: None };
        let t = Instant::now();
        let o = pool.install(|| {
            stability_map(&spec, &x, &y, &s, &autobal::control::Control::none(), &mut |_, row| {
                cells.extend_from_slice(row);
                true
            })
        });
        let secs = t.elapsed().as_secs_f64();
        let o = o.expect("map");
        (cells, secs, o)
    };
    let (margin, t_margin, om) = run(Quantity::Margin);
    let (verdict, t_verdict, ov) = run(Quantity::Verdict);
    // the stability boundary of the same plane, traced as curves (single-threaded): once to warm
    // up, then the median of 5 (a trace takes ~2 ms: its first call's first touch of pages and
    // caches is a visible part of it, where it is not of the maps' ~100 ms)
    let trace = || {
        trace_boundary(&spec, &Axis::range(x.path.clone(), -2.0, 2.0), &Axis::range(y.path.clone(), 0.05, 4.5), &TraceSettings::default()).expect("boundary")
    };
    let b = trace();
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(trace());
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    let t_boundary = times[2];
    // per-point reference paths (skipped with a fourth argument `maps`, for instruction counts)
    let maps_only = args.get(4).is_some_and(|a| a == "maps");
    let t = Instant::now();
    let spaces: Vec<StateSpace> =
        x.values.iter().map(|&z| StateSpace::new(&SpatialModel::from_dimensionless(&input(z)).expect("valid"), Balls::Free).expect("balls")).collect();
    let mut check = 0.0;
    for &w in y.values.iter().filter(|_| !maps_only) {
        for ss in &spaces {
            check += spectral_abscissa(&ss.at(w), 12).expect("QR converges");
        }
    }
    let t_qr = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut nst = 0;
    for &w in y.values.iter().filter(|_| !maps_only) {
        for ss in &spaces {
            let c = characteristic_polynomial(&ss.at(w), 12);
            nst += routh_hurwitz_stable(&c[..=12]) as usize;
        }
    }
    let t_direct = t.elapsed().as_secs_f64();
    std::hint::black_box((check, nst));
    let mut f = std::io::BufWriter::new(std::fs::File::create(&out).expect("output file"));
    for c in &margin {
        f.write_all(&c.margin.to_le_bytes()).unwrap();
    }
    for c in &verdict {
        f.write_all(&[c.stable as u8]).unwrap();
    }
    let pts = (nx * ny) as f64;
    println!(
        "{{\"points\": {}, \"boundary_s\": {t_boundary}, \"boundary_evaluations\": {}, \"boundary_points\": {}, \"margin_s\": {t_margin}, \"verdict_s\": {t_verdict}, \"margin_qr_s\": {t_qr}, \"verdict_direct_s\": {t_direct}, \"margin_us_per_point\": {}, \"verdict_us_per_point\": {}, \"margin_qr_us_per_point\": {}, \"verdict_direct_us_per_point\": {}, \"margin_continued\": {}, \"margin_direct\": {}, \"verdict_confirmations\": {}}}",
        nx * ny,
        b.evaluations,
        b.curves.iter().map(|c| c.points.len()).sum::<usize>(),
        1e6 * t_margin / pts,
        1e6 * t_verdict / pts,
        1e6 * t_qr / pts,
        1e6 * t_direct / pts,
        om.continued,
        om.direct,
        ov.direct
    );
}
