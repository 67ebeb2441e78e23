//! Paper 004's passage through resonance from rest, timed in the library (no CSV):
//! `cargo run --release --example passage -- [b] [m3] [n] [method] [repeats]`
//! (defaults 2.5 1/s², 0.03 kg, 2 balls, auto, 1). Prints the summary and the median wall time.
use autobal::planar::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize| args.get(i).cloned();
    let b: f64 = arg(1).and_then(|s| s.parse().ok()).unwrap_or(2.5);
    let m3: f64 = arg(2).and_then(|s| s.parse().ok()).unwrap_or(0.03);
    let n: usize = arg(3).and_then(|s| s.parse().ok()).unwrap_or(2);
    let method = match arg(4).as_deref() {
        Some("dop853") => Method::Dop853,
        Some("rodas") => Method::Rodas,
        _ => Method::Auto,
    };
    let repeats: usize = arg(5).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut p = PlanarRotor::paper();
    p.m3 = m3;
    p.n = n;
    let drive = Drive::Acceleration { omega0: 0.0, b };
    let t_end = 600.0 / b.abs();
    let st = Settings { method, ..Settings::new(&p, t_end) };
    let mut walls = vec![];
    let mut s = None;
    for _ in 0..repeats {
        let t0 = std::time::Instant::now();
        s = Some(simulate(&p, &drive, &st, |_| true).unwrap());
        walls.push(t0.elapsed().as_secs_f64());
    }
    walls.sort_by(f64::total_cmp);
    println!("{:?}\nwall median {:.4} s (min {:.4}, max {:.4}, {} runs)", s.unwrap(), walls[walls.len() / 2], walls[0], walls[walls.len() - 1], walls.len());
}
