//! The margin map alone, for instruction counts: the library's [`stability_map`] of
//! `Quantity::Margin` over the plane of `bench_map` (z̄_A = −2..2 × Ω = 0.05..4.5, 12 states),
//! single-threaded, nothing else in the process (no verdict map, no boundary, no per-point
//! references). `valgrind --tool=callgrind` on it counts the margin map's library work.
//!
//! Usage: `cargo run --release --example bench_map_margin -p autobal -- [NX NY [OUT.bin]]`;
//! prints the cells' routes; OUT.bin (optional) holds the NX·NY margins (f64 LE) then the
//! verdicts (u8), row-major (row = speed), to compare two builds cell by cell.

use autobal::spatial::inertia::AnisotropyMethod;
use autobal::spatial::linear_model::Balls;
use autobal::spatial::map::{stability_map, Axis, MapSettings, Quantity};
use autobal::spatial::params::{AnisotropyInput, DimensionlessInput};
use autobal::spatial::paths::{SpatialInput, SpatialSpec};
use std::io::Write;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let nx: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(400);
    let ny: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(400);
    let input = DimensionlessInput {
        c_sigma: 0.75,
        rho_s: 0.4,
        l_left: 0.8,
        z_a: 0.0,
        anisotropy: AnisotropyInput::Direct(0.1),
        h_x: 0.05,
        h_s: 0.1,
        method: AnisotropyMethod::Exact,
        direct_balls: Some((0.05, 0.5)),
    };
    let spec = SpatialSpec { input: SpatialInput::Dimensionless(input), delta_a_override: None };
    let x = Axis::linspace("dimensionless.z_a", -2.0, 2.0, nx);
    let y = Axis::linspace("omega", 0.05, 4.5, ny);
    let s = MapSettings { balls: Balls::Free, quantity: Quantity::Margin, omega: None };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    let mut cells = Vec::with_capacity(nx * ny);
    let o = pool
        .install(|| {
            stability_map(&spec, &x, &y, &s, &autobal::control::Control::none(), &mut |_, row| {
                cells.extend_from_slice(row);
                true
            })
        })
        .expect("map");
    println!("{} cells: {} continued, {} direct", cells.len(), o.continued, o.direct);
    if let Some(path) = args.get(3) {
        let mut f = std::io::BufWriter::new(std::fs::File::create(path).expect("output file"));
        for c in &cells {
            f.write_all(&c.margin.to_le_bytes()).expect("write");
        }
        for c in &cells {
            f.write_all(&[c.stable as u8 | (c.necessary as u8) << 1]).expect("write");
        }
    }
}
