use autobal::planar::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let b: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(2.5);
    let m3: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.03);
    let mut p = PlanarRotor::paper();
    p.m3 = m3;
    let drive = Drive::Acceleration { omega0: 0.0, b };
    let t_end = 600.0 / b.abs();
    let st = Settings { method: Method::Dop853, t_end, dt: t_end / 2000.0, rtol: 1e-8, atol: 1e-9, psi0: Settings::default_psi0(2), psi_rate0: vec![0.0; 2] };
    let t0 = std::time::Instant::now();
    let s = simulate(&p, &drive, &st, |_| true).unwrap();
    println!("{:?}\nwall {:.3} s", s, t0.elapsed().as_secs_f64());
}
