//! A map cell's stationary state does not depend on the grid: a cell whose own starts miss
//! the state its neighbour has is reached from the neighbour by continuation in smaller steps
//! (`Plane::continue_to`), along a row and along a column, and a traced boundary never puts a
//! state "appearing" at a grid cell that continuation reaches.
//!
//! The case (walk 29, finding 3): the washer of examples/washing_machine.toml under gravity,
//! balancer.z = 0.22, mapped over 100-600 rpm. On a 6-column grid the cell at 200 rpm held a
//! partially balanced orbit (reached from 300 rpm), on an 11-column grid none (the one step
//! from 250 rpm failed), and the traced boundary then had the orbit "appear" at
//! 200.0000001 rpm, a bisection that only walked back to the grid cell.
//!
//! Second route: the same cell on three grids (6 and 11 speeds along `x`, 11 along `y`): the
//! same orbit, the margins equal to 1e-9 per τ (shooting at rtol 1e-10 from different starts
//! keeps the multipliers near 1 good to ~1e-9 (rotor_stability), and a revolution is 3 to 18 τ
//! here, so the exponents ln|μ|/T agree to better than 1e-9 per τ), and the boundary points
//! where an orbit appears all lie at least 1e-6 of a grid step away from a grid speed.

use autobal::control::Control;
use autobal::rotor_map::{general_map_traced, BoundaryPoint, GeneralCell};
use autobal::spatial::map::Axis;

const WASHER: &str = include_str!("../../../examples/washing_machine.toml");

fn washer() -> toml::Table {
    let mut root = autobal::config::parse(WASHER, "washer").unwrap();
    autobal::config::set(&mut root, "spatial.gravity", autobal::config::parse_value("[0.0, -9.81, 0.0]")).unwrap();
    root
}

fn speeds(n: usize) -> Vec<f64> {
    (0..n).map(|i| 100.0 + 500.0 * i as f64 / (n - 1) as f64).collect()
}

/// The map's cells by (speed, cell) and its boundary points, with the speed along `x` or `y`.
fn map(n: usize, speed_on_x: bool) -> (Vec<(f64, GeneralCell)>, Vec<BoundaryPoint>) {
    let root = washer();
    let s = Axis { path: "speed_rpm".into(), values: speeds(n) };
    let z = Axis { path: "balancer.z".into(), values: vec![0.22] };
    let (x, y) = if speed_on_x { (&s, &z) } else { (&z, &s) };
    let mut cells = vec![];
    let mut points = vec![];
    general_map_traced(&root, x, y, None, true, &Control::none(), &mut |j, row, p| {
        for (i, c) in row.iter().enumerate() {
            let w = if speed_on_x { x.values[i] } else { y.values[j] };
            cells.push((w, *c));
        }
        points.extend_from_slice(p);
        true
    })
    .unwrap();
    (cells, points)
}

fn at(cells: &[(f64, GeneralCell)], w: f64) -> GeneralCell {
    cells.iter().find(|c| (c.0 - w).abs() < 1e-9).unwrap().1
}

#[test]
fn a_cells_state_is_the_same_on_every_grid_and_no_state_appears_at_a_grid_cell() {
    let (six, p6) = map(6, true);
    let (eleven, p11) = map(11, true);
    let (column, pc) = map(11, false);
    for w in [200.0, 300.0, 400.0, 600.0] {
        let a = at(&six, w);
        for b in [at(&eleven, w), at(&column, w)] {
            assert_eq!((a.verdict, a.state), (b.verdict, b.state), "{w} rpm: {a:?} vs {b:?}");
            assert!(a.verdict.is_some(), "{w} rpm has a state on every grid: {a:?}");
            assert!((a.margin - b.margin).abs() <= 1e-9, "{w} rpm: {} vs {}", a.margin, b.margin);
        }
    }
    // the speed scan of `stability` over the same 11 speeds (it continues back too): the same
    // orbit at 200 rpm, its growth rate in 1/s the map's per-τ margin times ω0 (to the
    // shooting's tolerance, 1e-9 per τ: 3e-8 1/s); before session 30 it had none there
    let sim = autobal::config::spatial_simulation(&{
        let mut r = washer();
        autobal::config::set(&mut r, "balancer.z", autobal::config::parse_value("0.22")).unwrap();
        r
    })
    .unwrap();
    let omega0 = sim.config.model.scale.map_or(1.0, |s| s.omega0);
    let rotor = autobal::rotor_stability::Rotor::Spatial(sim.rotor);
    let ws: Vec<f64> = speeds(11).iter().map(|r| r * std::f64::consts::PI / 30.0).collect();
    let scan = autobal::rotor_stability::stability_over_speed(&rotor, &ws).unwrap();
    for (p, (w, c)) in scan.points.iter().zip(&eleven) {
        assert_eq!((p.verdict, p.state), (c.verdict, c.state), "{w} rpm: scan {p:?}, map {c:?}");
        if let Some(a) = p.abscissa {
            assert!((a - c.margin * omega0).abs() <= 1e-9 * omega0, "{w} rpm: scan {a}, map {}", c.margin * omega0);
        }
    }
    assert!(scan.points[2].abscissa.is_some(), "the scan has the orbit at 200 rpm");
    // the cells with and without a state agree between the 11-speed row and column
    for (r, c) in eleven.iter().zip(&column) {
        assert_eq!((r.1.verdict.is_some(), r.1.state), (c.1.verdict.is_some(), c.1.state), "{} rpm", r.0);
    }
    // where an orbit appears (no state below, a state above) it is not at a grid speed
    for (points, axis) in [(&p6, 'x'), (&p11, 'x'), (&pc, 'y')] {
        for p in points.iter().filter(|p| p.from.is_none() || p.to.is_none()) {
            let w = if axis == 'x' { p.x } else { p.y };
            let step = 50.0;
            let near = speeds(11).iter().chain(&speeds(6)).map(|g| (w - g).abs()).fold(f64::INFINITY, f64::min);
            assert!(near > 1e-6 * step, "an orbit appears at a grid speed, {w} rpm: {p:?}");
        }
    }
}

#[test]
fn the_column_fill_does_not_depend_on_how_rows_fall_into_blocks() {
    // A map hands its rows on in blocks of 4 x threads rows; a cell is filled from the row
    // above it even where that row falls in the next block (the block's last row is held back
    // until then). Speeds 50-550 rpm along y: with one thread the blocks are 50-200 and
    // 250-400 rpm, and the 200 rpm cell (no state of its own) is reached from 250 rpm across the
    // blocks' edge; with two threads both are in one block. Review 30 found the first version
    // of the fill leaving the cell empty with one thread (the block's last row was handed on
    // before the next block was computed).
    let root = washer();
    let z = Axis { path: "balancer.z".into(), values: vec![0.22, 0.26] };
    let s = Axis { path: "speed_rpm".into(), values: (0..11).map(|i| 50.0 + 50.0 * i as f64).collect() };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut cells = vec![];
            general_map_traced(&root, &z, &s, None, true, &Control::none(), &mut |_, row, _| {
                cells.extend_from_slice(row);
                true
            })
            .unwrap();
            cells
        })
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.len(), 22);
    for (k, (a, b)) in one.iter().zip(&two).enumerate() {
        assert_eq!((a.verdict, a.state), (b.verdict, b.state), "cell {k}: {a:?} vs {b:?}");
        if a.verdict.is_some() {
            assert!((a.margin - b.margin).abs() <= 1e-9, "cell {k}: {} vs {}", a.margin, b.margin);
        }
    }
    // the 200 rpm cells (row 3) have the orbit
    assert!(one[6].verdict.is_some() && one[7].verdict.is_some(), "{:?}", &one[6..8]);
}
