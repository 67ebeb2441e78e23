//! A run's verdicts mean what they say (issue 18 item 4): `balanced` is the balls cancelling
//! the unbalance on average over a revolution, the stationary motion (the sag under gravity) is
//! its own field and the whirl radius is measured about it, a balancer of too little capacity
//! is `partially_balanced` with the closed-form residual.

use autobal::drive::Drive;
use autobal::spatial::dynamics::{simulate, simulate_summary, BallPlane, Initial, PointMass, RigidRotor, RunOutcome, Settings, SpatialRotor, Summary, Support};

const G: f64 = 9.81;

/// examples/washing_machine.toml: drum, tub and counterweights on their suspension, 0.3 kg of
/// laundry at the drum wall, three 120 g balls at 250 mm.
fn washer(ball_mass: f64) -> SpatialRotor {
    SpatialRotor::new(
        RigidRotor::aligned(32.0, 0.9, 0.75, 0.22),
        vec![Support::isotropic(0.0, 1.8e4, 180.0), Support::isotropic(0.45, 1.2e4, 120.0)],
        vec![PointMass { mass: 0.30, radius: 0.22, angle: 0.0, z: 0.26 }],
        vec![BallPlane::point_masses(0.26, 3, ball_mass, 0.25, 1.5)],
    )
}

fn horizontal(mut r: SpatialRotor) -> SpatialRotor {
    r.gravity = [0.0, -G, 0.0];
    r
}

/// 1400 rpm, above the washer's four critical speeds (284, 985, 1060 rpm).
const SPIN: f64 = 1400.0 * std::f64::consts::PI / 30.0;

fn run(r: &SpatialRotor, t_end: f64) -> Summary {
    let drive = Drive::Speed { omega0: SPIN };
    let set = Settings { method: Default::default(), t_end, dt: 1e-3, rtol: 1e-8, atol: 1e-10 };
    simulate_summary(r, &drive, &Initial::at_rest(r), &set, &autobal::control::Control::none()).unwrap()
}

/// The static deflection at `z` of a rigid rotor of weight `w` (centre of mass at `z_g`) on
/// springs `k_i` at `z_i`, the line `d(z) = a + b z` from the balance of forces and moments:
/// `Σ k_i (a + b z_i) = w`, `Σ k_i z_i (a + b z_i) = w z_g`. Gyroscopic and unbalance forces
/// do not enter: the sag is constant in fixed axes (no precession), and the balls' and the
/// unbalance's centrifugal forces cancel when balanced.
fn two_spring_sag(springs: &[(f64, f64)], w: f64, z_g: f64, z: f64) -> f64 {
    let (k0, k1, k2) = springs.iter().fold((0.0, 0.0, 0.0), |(a, b, c), (k, zi)| (a + k, b + k * zi, c + k * zi * zi));
    let det = k0 * k2 - k1 * k1;
    let a = (w * k2 - k1 * w * z_g) / det;
    let b = (k0 * w * z_g - k1 * w) / det;
    a + b * z
}

/// Total mass and centre of mass of rotor, unbalance and balls.
fn mass_and_centre(r: &SpatialRotor) -> (f64, f64) {
    let mut m = r.rotor.mass;
    let mut mz = r.rotor.mass * r.rotor.z;
    for u in &r.unbalances {
        m += u.mass;
        mz += u.mass * u.z;
    }
    for p in &r.planes {
        m += p.n as f64 * p.ball_mass;
        mz += p.n as f64 * p.ball_mass * p.z;
    }
    (m, mz / m)
}

fn springs(r: &SpatialRotor) -> Vec<(f64, f64)> {
    r.supports.iter().map(|s| (s.stiffness[1], s.z)).collect()
}

#[test]
fn the_horizontal_washer_balances_about_its_sag() {
    // The defect of issue 18: under gravity across the axis the balls swing once per revolution
    // (never at rest) and the shaft sags; the old verdict asked for balls at rest and printed
    // the sag as the whirl radius. Now: balanced on average, the sag its own field, the whirl
    // about it.
    let r = horizontal(washer(0.12));
    let drive = Drive::Speed { omega0: SPIN };
    let set = Settings { method: Default::default(), t_end: 20.0, dt: 1e-3, rtol: 1e-8, atol: 1e-10 };
    let period = 2.0 * std::f64::consts::PI / SPIN;
    let mut last_rev: Vec<f64> = vec![];
    let s = simulate(&r, &drive, &Initial::at_rest(&r), &set, |x| {
        if x.t > 20.0 - period {
            last_rev.push(x.psi[0]);
        }
        true
    })
    .unwrap();
    assert_eq!(s.outcome, RunOutcome::Balanced, "{s:#?}");
    assert!(s.balanced);
    // balanced to 1e-3 of the unbalance (measured 1.7e-5)
    assert!(s.residual_unbalance < 1e-3 && s.residual_couple.unwrap() < 1e-3, "{s:#?}");
    // the balls swing relative to the rotor (not at rest: the old criterion fails) but their
    // mean does not drift
    let swing = last_rev.iter().fold(f64::NEG_INFINITY, |a, b| a.max(*b)) - last_rev.iter().fold(f64::INFINITY, |a, b| a.min(*b));
    assert!(swing > 1e-4, "swing {swing}");
    assert!(s.ball_drift.unwrap() < 1e-2 * swing, "drift {:?} swing {swing}", s.ball_drift);
    // the sag: the two-spring closed form (the supports 1.8e4 and 1.2e4 N/m are not centred on
    // the centre of mass, so the drum tilts: 11.40 mm at the balancer plane, not
    // M g / Σ k = 10.68 mm). Tolerance 1e-3 relative: the tilt (9e-3 rad) enters the
    // nonlinear equations at second order (1e-4) and the defect-corrected mean is exact for a
    // displacement constant in fixed axes (measured 1.4e-5).
    let (m, zg) = mass_and_centre(&r);
    let want = two_spring_sag(&springs(&r), m * G, zg, r.planes[0].z);
    assert!((s.static_sag.unwrap() / want - 1.0).abs() < 1e-3, "sag {} closed form {want}", s.static_sag.unwrap());
    let mean = s.mean_displacement.unwrap();
    assert!(mean[1] < 0.0 && mean[0].abs() < 1e-3 * s.static_sag.unwrap(), "{mean:?}");
    let mgk = m * G / 3.0e4;
    assert!((s.static_sag.unwrap() / mgk - 1.0).abs() < 0.1, "sag {} M g / k {mgk}", s.static_sag.unwrap());
    // the whirl about it is much smaller than the sag (measured 8.7e-7 m against 1.14e-2 m)
    assert!(s.final_amplitude < 1e-3 * s.static_sag.unwrap(), "whirl {} sag {}", s.final_amplitude, s.static_sag.unwrap());
}

#[test]
fn a_balancer_short_of_capacity_is_partially_balanced_with_the_closed_form_residual() {
    // Half the washer's ball mass: capacity 3 · 0.06 · 0.25 = 0.045 kg m against the laundry's
    // 0.3 · 0.22 = 0.066 kg m: no balanced state exists, the least residual is
    // 1 − 0.045/0.066 = 0.318, the balls together against the unbalance.
    let r = horizontal(washer(0.06));
    let drive = Drive::Speed { omega0: SPIN };
    let set = Settings { method: Default::default(), t_end: 20.0, dt: 1e-3, rtol: 1e-8, atol: 1e-10 };
    let mut last = vec![];
    let s = simulate(&r, &drive, &Initial::at_rest(&r), &set, |x| {
        last = x.psi.clone();
        true
    })
    .unwrap();
    assert_eq!(s.outcome, RunOutcome::PartiallyBalanced, "{s:#?}");
    assert!(!s.balanced);
    let c = 3.0 * 0.06 * 0.25 / (0.30 * 0.22);
    let closed = 1.0 - c;
    // never below the closed form (|U + B| ≥ |U| − |B|), above it by the whirl's lag only
    // (measured 0.3258 against 0.3182: the balls sit 5° off exactly against)
    assert!(s.residual_unbalance >= closed - 1e-9 && s.residual_unbalance - closed < 0.01, "{} vs {closed}", s.residual_unbalance);
    // second route: the residual from the balls' angle at the end, |1 + c e^{iψ}| (the balls
    // together; the swing changes it by less than 1e-3)
    assert!(last.iter().all(|p| (p - last[0]).abs() < 1e-6), "{last:?}");
    let from_angle = (1.0 + c * last[0].cos()).hypot(c * last[0].sin());
    assert!((s.residual_unbalance - from_angle).abs() < 1e-3, "{} vs {from_angle}", s.residual_unbalance);
}

#[test]
fn an_unbalanced_rotor_without_balls_is_not_balanced_and_whirls_about_its_sag() {
    // The washer without balls, its tilt locked: a Jeffcott rotor. Sag M g / k exactly, whirl
    // about it the unbalance response m0 R0 Ω² / |k − M Ω² + i c Ω| (2.13 mm at 1400 rpm; the
    // transient from rest decays as exp(−4.6 t)). Tolerance 1e-7 relative on both (measured
    // 8.5e-9 and 5e-12 at rtol 1e-8, about 10 steps per revolution): a circle's RMS radius is
    // its radius, and the whirl, constant in the rotor frame, and the sag, constant in fixed
    // axes, are both integrated exactly by the summary's averages.
    let mut r = horizontal(washer(0.0));
    r.planes.clear();
    r.lock_tilt = true;
    let s = run(&r, 20.0);
    assert_eq!(s.outcome, RunOutcome::NotBalanced, "{s:#?}");
    assert!(!s.balanced && s.ball_drift.is_none());
    assert!((s.residual_unbalance - 1.0).abs() < 1e-12, "{}", s.residual_unbalance);
    let (m, _) = mass_and_centre(&r);
    let (k, c) = (3.0e4, 300.0);
    let sag = m * G / k;
    let u = r.unbalances[0].mass * r.unbalances[0].radius;
    let whirl = u * SPIN * SPIN / (k - m * SPIN * SPIN).hypot(c * SPIN);
    assert!((s.static_sag.unwrap() / sag - 1.0).abs() < 1e-7, "sag {} closed form {sag}", s.static_sag.unwrap());
    assert!((s.final_amplitude / whirl - 1.0).abs() < 1e-7, "whirl {} closed form {whirl}", s.final_amplitude);
}

#[test]
fn a_balanced_isotropic_run_is_still_balanced_without_sag() {
    // The washer without gravity: the balanced state is an equilibrium in the rotor frame; no
    // sag (below 1e-9 m: only the transient's remains), no whirl, no drift.
    let r = washer(0.12);
    let s = run(&r, 20.0);
    assert_eq!(s.outcome, RunOutcome::Balanced, "{s:#?}");
    assert!(s.balanced && s.residual_unbalance < 1e-3);
    assert!(s.static_sag.unwrap() < 1e-9 && s.final_amplitude < 1e-6, "{s:#?}");
    assert!(s.ball_drift.unwrap() < 1e-6, "{s:#?}");
}

#[test]
fn a_run_shorter_than_two_revolutions_is_not_settled() {
    let r = horizontal(washer(0.12));
    let s = run(&r, 1.5 * 2.0 * std::f64::consts::PI / SPIN);
    assert_eq!(s.outcome, RunOutcome::NotSettled, "{s:#?}");
    assert!(!s.balanced && s.ball_drift.is_none());
}

#[test]
fn the_averages_are_exact_for_whirl_and_sag_whatever_the_steps() {
    // The same Jeffcott washer with a loose tolerance (rtol 1e-5: 4 steps per revolution,
    // 90° each); the averages still find the closed forms to 1e-4, the integration's own
    // error at rtol 1e-5 (measured 3e-6 sag, 6e-7 whirl). Without the defect correction of the
    // mean the chords of 90° steps would put the sag 20 % off.
    let mut r = horizontal(washer(0.0));
    r.planes.clear();
    r.lock_tilt = true;
    let drive = Drive::Speed { omega0: SPIN };
    let set = Settings { method: Default::default(), t_end: 20.0, dt: 1e-3, rtol: 1e-5, atol: 1e-7 };
    let s = simulate_summary(&r, &drive, &Initial::at_rest(&r), &set, &autobal::control::Control::none()).unwrap();
    let (m, _) = mass_and_centre(&r);
    let sag = m * G / 3.0e4;
    let u = r.unbalances[0].mass * r.unbalances[0].radius;
    let whirl = u * SPIN * SPIN / (3.0e4 - m * SPIN * SPIN).hypot(300.0 * SPIN);
    let per_rev = s.steps as f64 / (20.0 * SPIN / (2.0 * std::f64::consts::PI));
    assert!((s.static_sag.unwrap() / sag - 1.0).abs() < 1e-4, "sag {} closed form {sag} ({per_rev} steps per revolution)", s.static_sag.unwrap());
    assert!((s.final_amplitude / whirl - 1.0).abs() < 1e-4, "whirl {} closed form {whirl} ({per_rev} steps per revolution)", s.final_amplitude);
}

/// Paper 004's planar rotor with its race centred (the Jeffcott rotor with two balls) held at
/// 400 rad/s, 1.39 ω_n, where the balanced state is stable (tests/analysis.rs): the balls
/// cancel the unbalance and the whirl radius decays to round-off.
fn planar_balanced_run(t_end: f64) -> autobal::planar::Summary {
    use autobal::planar::{simulate_summary, PlanarRotor, Settings};
    let p = PlanarRotor { s2: 0.0, ..PlanarRotor::paper() };
    simulate_summary(&p, &Drive::Speed { omega0: 400.0 }, &Settings::new(&p, t_end), &autobal::control::Control::none()).unwrap()
}

#[test]
fn a_balanced_planar_run_at_constant_speed_is_settled_and_does_not_warn() {
    // issue 18 item 4: "a balanced constant-speed run does not warn 'not settled'". The radius
    // ends near 1e-18 m, changing at round-off rates: relative to its own radius that read as a
    // fast change; the settled test measures it against the balance tolerance there.
    let s = planar_balanced_run(20.0);
    assert!(s.final_amplitude < 1e-12, "{}", s.final_amplitude);
    assert!(s.balanced && s.settled, "{s:?}");
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    // the same run stopped during its transient (balls still moving) is not settled, and says so
    let s = planar_balanced_run(0.3);
    assert!(!s.settled, "{s:?}");
    assert!(s.warnings.iter().any(|w| w.contains("before the motion settled")), "{:?}", s.warnings);
}

/// A rotor with no unbalance (examples/spatial_two_plane.toml with both unbalance masses 0,
/// gravity on): nothing for the balls to cancel, so the balanced state is the one where their
/// resultant vanishes, and the residual is that resultant over their capacity `Σ m R` (the only
/// scale left). Checked against the orbit's 64 samples directly: each ball's mean `e^{iψ}`,
/// the static resultant `Σ m R ⟨e^{iψ}⟩` and the couple `Σ (z − z_ref) m R ⟨e^{iψ}⟩` over the
/// largest ball-plane distance, over `Σ m R` (to 1e-6 relative: the same sums in another
/// order, at a residual of ~3e-7). At 393.6 rad/s (a grid speed of the example's axis) the
/// balls' swing leaves 3e-7 of their capacity: balanced. Main at 21dbfc9 divided by 1e-6 of the
/// capacity and said 0.32 "of an unbalance their capacity could cancel": not balanced.
#[test]
fn without_unbalance_the_residual_is_the_balls_resultant_over_their_capacity() {
    use autobal::rotor_stability::{Rotor, StateKind};
    let mut root = autobal::config::parse(include_str!("../../../examples/spatial_two_plane.toml"), "two-plane").unwrap();
    assert!(Rotor::Spatial(autobal::config::spatial_simulation(&root).unwrap().rotor).has_unbalance());
    autobal::config::set_number(&mut root, "unbalance.mass", 0.0).unwrap();
    autobal::config::set_number(&mut root, "couple.mass", 0.0).unwrap();
    let r = autobal::config::spatial_simulation(&root).unwrap().rotor;
    let rotor = Rotor::Spatial(r.clone());
    assert!(!rotor.has_unbalance());
    // no orbit here: the balls creep (the shooting stalls at a residual of 5.44e-8 at rtol
    // 1e-8, 1e-10 and 1e-12 alike, which the solver now refuses, session 16); classify's sums
    // hold for any state, so the state where it stalls, taken at a tolerance above that drift
    let f = rotor.field(393.6).unwrap();
    let guess = Rotor::guess(&f).unwrap();
    let opts = autobal::analysis::NewtonOptions { periodic_tolerance: 1e-7, max_iterations: 20, rtol: 1e-10, ..Default::default() };
    let s = autobal::analysis::stationary(&f, &guess, &opts).unwrap();
    let period = autobal::analysis::VectorField::period(&f)
        .expect("the spatial rotor's field is periodic under gravity (the state is a creep's stall, sampled over one period)");
    let (kind, residual) = Rotor::classify(&f, &s.x);
    // independently: the means over one period's samples from that state
    let n = s.x.len();
    let rows = autobal::analysis::orbit_samples(&f, &s.x, period, 1e-10).unwrap();
    let m = n / 2;
    let balls: Vec<_> = r.planes.iter().filter(|p| p.n > 0).flat_map(|p| std::iter::repeat_n(p, p.n)).collect();
    let nb = balls.len();
    let zr = r.z_reference();
    let zl = r.planes.iter().filter(|p| p.n > 0).map(|p| (p.z - zr).abs()).fold(0.0, f64::max);
    let (mut st, mut cp, mut cap) = ([0.0; 2], [0.0; 2], 0.0);
    for (j, p) in balls.iter().enumerate() {
        let k = rows.len() / n;
        let (c, sn) = (0..k).map(|i| rows[i * n + m - nb + j]).fold((0.0, 0.0), |(c, sn), a| (c + a.cos() / k as f64, sn + a.sin() / k as f64));
        let mr = p.ball_mass * p.race_radius;
        st = [st[0] + mr * c, st[1] + mr * sn];
        cp = [cp[0] + (p.z - zr) * mr * c, cp[1] + (p.z - zr) * mr * sn];
        cap += mr;
    }
    let want = st[0].hypot(st[1]).max(cp[0].hypot(cp[1]) / zl) / cap;
    assert!((residual - want).abs() <= 1e-6 * want, "residual {residual} against {want}");
    assert!(residual < 1e-6, "{residual}");
    assert_eq!(kind, StateKind::Balanced);
}
