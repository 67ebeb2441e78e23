//! Stability-map benchmark, autobal side: the 12-state model of 000 eq (6) over a grid
//! z̄_A × Ω (003 Fig. 5a layout), single-threaded, timing only the per-point work.
//! `bench/stability_map.py` runs this, builds the same matrices in NumPy, times
//! `numpy.linalg.eigvals`, and compares verdicts and margins.
//!
//! Usage: `cargo run --release --example bench_map -p autobal -- NX NY OUT.bin`
//! Prints one JSON line of timings; OUT.bin holds NX·NY margins (f64 LE) then NX·NY verdicts (u8).

use autobal::linalg::eigen::{characteristic_polynomial, routh_hurwitz_stable, spectral_abscissa};
use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::{Balls, StateSpace};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput, SpatialModel};
use std::io::Write;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let nx: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(400);
    let ny: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(400);
    let out = args.get(3).cloned().unwrap_or_else(|| "bench_map.bin".into());
    let zs: Vec<f64> = (0..nx).map(|i| -2.0 + 4.0 * i as f64 / (nx - 1) as f64).collect();
    let ws: Vec<f64> = (0..ny).map(|j| 0.05 + 4.45 * j as f64 / (ny - 1) as f64).collect();
    let t0 = Instant::now();
    let spaces: Vec<StateSpace> = zs
        .iter()
        .map(|&z| {
            let m = SpatialModel::from_dimensionless(&DimensionlessInput {
                c_sigma: 0.75,
                rho_s: 0.4,
                l_left: 0.8,
                z_a: z,
                anisotropy: AnisotropyInput::Direct(0.1),
                h_x: 0.05,
                h_s: 0.1,
                method: AnisotropyMethod::Exact,
                direct_balls: Some((0.05, 0.5)),
            })
            .expect("valid parameters");
            StateSpace::new(&m, Balls::Free).expect("balls described")
        })
        .collect();
    let setup = t0.elapsed().as_secs_f64();
    let n = spaces[0].states;
    // verdict: characteristic polynomial + Routh–Hurwitz
    let t1 = Instant::now();
    let mut verdict = vec![0u8; nx * ny];
    for (j, &w) in ws.iter().enumerate() {
        for (i, ss) in spaces.iter().enumerate() {
            let c = characteristic_polynomial(&ss.at(w), n);
            verdict[j * nx + i] = routh_hurwitz_stable(&c[..=n]) as u8;
        }
    }
    let t_verdict = t1.elapsed().as_secs_f64();
    // margin: eigenvalues by balanced Hessenberg QR
    let t2 = Instant::now();
    let mut margin = vec![0f64; nx * ny];
    for (j, &w) in ws.iter().enumerate() {
        for (i, ss) in spaces.iter().enumerate() {
            margin[j * nx + i] = spectral_abscissa(&ss.at(w), n).expect("QR converges");
        }
    }
    let t_margin = t2.elapsed().as_secs_f64();
    let mut f = std::io::BufWriter::new(std::fs::File::create(&out).expect("output file"));
    for m in &margin {
        f.write_all(&m.to_le_bytes()).unwrap();
    }
    f.write_all(&verdict).unwrap();
    let pts = (nx * ny) as f64;
    println!(
        "{{\"points\": {}, \"setup_s\": {setup}, \"verdict_s\": {t_verdict}, \"margin_s\": {t_margin}, \"verdict_us_per_point\": {}, \"margin_us_per_point\": {}}}",
        nx * ny,
        1e6 * t_verdict / pts,
        1e6 * t_margin / pts
    );
}
