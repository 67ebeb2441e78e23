//! Timoshenko shaft elements of the built-in shaft builder ([`autobal::linear_rotor::shaft`]):
//! a simply supported shaft against the Timoshenko frequency equation, convergence with the
//! number of elements, the Euler–Bernoulli element as the shear stiffness grows without bound,
//! and ROSS's `ShaftElement(shear_effects=True)` on the same rotor (where ROSS is installed), with
//! the Campbell diagram of a second ROSS example rotor against its `run_campbell`.

mod ross_common;

use autobal::linear_rotor::shaft::{cowper_kappa, Bearing, Disk, Element, ShaftBuilder};
use autobal::linear_rotor::{Direction, LinearRotor};
use std::f64::consts::PI;

const E: f64 = 2.1e11;
const G: f64 = 8.1e10;
const RHO: f64 = 7800.0;

/// A stubby shaft (`L/d = 5`): shear deformation changes its bending frequencies by percents.
fn stubby(elements: usize, shear_scale: Option<f64>) -> (LinearRotor, f64, f64) {
    let (l, d) = (0.5, 0.1);
    let el = match shear_scale {
        None => Element::circular(l / elements as f64, d, E, RHO),
        Some(s) => {
            let t = Element::timoshenko(l / elements as f64, d, 0.0, E, RHO, G);
            Element { shear: t.shear.map(|v| v * s), ..t }
        }
    };
    let b = ShaftBuilder { elements: vec![el; elements], rotary_inertia: true, gyroscopic: true, ..Default::default() };
    (b.build().unwrap(), l, d)
}

/// The undamped frequencies of the shaft simply supported at its ends (`x`, `y` held).
fn ss_frequencies(r: &LinearRotor) -> Vec<f64> {
    let last = r.nodes - 1;
    let fixed = [r.dof(0, Direction::X).unwrap(), r.dof(0, Direction::Y).unwrap(), r.dof(last, Direction::X).unwrap(), r.dof(last, Direction::Y).unwrap()];
    r.natural_frequencies(&fixed, false).unwrap()
}

/// The lower (bending) root of the Timoshenko frequency equation of a simply supported uniform
/// beam, mode `k` (`w = sin(kπz/L)`, `ψ = cos(kπz/L)`):
/// `(ρ²I/(κG)) ω⁴ − (ρA + ρI q² + EIρ q²/(κG)) ω² + EI q⁴ = 0`, `q = kπ/L` (the determinant
/// of `κGA(q² W − q Ψ) = ρA ω² W`, `κGA(Ψ − q W) + EI q² Ψ = ρI ω² Ψ`). `kappa_g = ∞` gives
/// the Rayleigh beam `ω² = EI q⁴/(ρA + ρI q²)`.
fn timoshenko_ss(k: usize, l: f64, d: f64, kappa_g: f64) -> f64 {
    let (a, i) = (PI * d * d / 4.0, PI * d.powi(4) / 64.0);
    let q = k as f64 * PI / l;
    let qa = RHO * RHO * i / kappa_g;
    let qb = RHO * a + RHO * i * q * q + E * i * RHO * q * q / kappa_g;
    let qc = E * i * q.powi(4);
    // the smaller root without cancellation: 2c / (b + sqrt(b² − 4ac))
    (2.0 * qc / (qb + (qb * qb - 4.0 * qa * qc).sqrt())).sqrt()
}

/// A simply supported solid shaft, `L/d = 5`, with shear and rotary inertia: the first three
/// bending frequencies (each twice, one per plane) against the closed form with Cowper's `κ`.
/// The element's shear strain is constant within it (its shape functions solve the static
/// equations: exact at the nodes in statics), so the shear energy is approximated to first
/// order in the element length `h` and the frequencies converge as `h²` from above (Rayleigh–Ritz;
/// observed: order 2.08, 2.02, 2.006 from 5 to 40 elements, first-mode errors 1.16e-3 to 1.67e-5).
/// The check: errors positive and of order 2 within 0.1, and the `h²` Richardson extrapolation
/// of 20 and 40 elements equal to the closed form to `1e-6` (mode 1; observed 9e-8) and `1e-5`
/// (modes 2, 3; observed 9e-7, 2.8e-6): the limit is the Timoshenko beam's, not a neighbour.
#[test]
fn simply_supported_timoshenko_shaft_against_the_frequency_equation() {
    let (_, l, d) = stubby(1, Some(1.0));
    let kappa = cowper_kappa(E / (2.0 * G) - 1.0, 0.0);
    // Cowper's solid-section value for ν = 0.296: 6(1+ν)/(7+6ν)
    let nu = E / (2.0 * G) - 1.0;
    assert!((kappa - 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)).abs() < 1e-15);
    let exact: Vec<f64> = (1..=3).map(|k| timoshenko_ss(k, l, d, kappa * G)).collect();
    // the check discriminates: shear lowers the Rayleigh beam's frequencies by percents here
    for (k, w) in exact.iter().enumerate() {
        let rayleigh = timoshenko_ss(k + 1, l, d, f64::INFINITY);
        assert!(rayleigh / w - 1.0 > 0.01 * (k + 1) as f64, "mode {}: shear effect {}", k + 1, rayleigh / w - 1.0);
    }
    let mut errs: Vec<Vec<f64>> = vec![];
    for ne in [5, 10, 20, 40] {
        let (r, _, _) = stubby(ne, Some(1.0));
        let w = ss_frequencies(&r);
        let mut e = vec![];
        for k in 0..3 {
            // two planes, equal frequencies
            assert!((w[2 * k] - w[2 * k + 1]).abs() <= 1e-9 * w[2 * k], "{ne} elements, mode {}: {} vs {}", k + 1, w[2 * k], w[2 * k + 1]);
            e.push(w[2 * k] / exact[k] - 1.0);
        }
        eprintln!("{ne} elements: relative errors {e:?}");
        errs.push(e);
    }
    for e in errs.iter().flatten() {
        assert!(*e > 0.0, "a frequency below the exact one: {errs:?}");
    }
    for j in 0..3 {
        let order = (errs[j][0] / errs[j + 1][0]).log2();
        assert!((order - 2.0).abs() < 0.1, "observed order {order}, errors {errs:?}");
    }
    for k in 0..3 {
        let extrapolated = (4.0 * errs[3][k] - errs[2][k]) / 3.0;
        let bound = if k == 0 { 1e-6 } else { 1e-5 };
        assert!(extrapolated.abs() < bound, "mode {}: extrapolated error {extrapolated:e}", k + 1);
    }
}

/// The Euler–Bernoulli element is the limit of the Timoshenko element as `κGA → ∞`: the
/// frequency difference falls as `1/(κGA)` (`Φ ∝ 1/(κGA)` enters the matrices smoothly), a
/// thousandfold for a thousandfold stiffer shear to 1 % (from `10⁴ κGA`, where the element's
/// `Φ ≈ 9e-4` and the terms in `Φ²` are 0.1 % of the linear ones), and is below `1e-6` of the
/// frequency at `10⁷ κGA`. With `Φ = 0` the matrices are the Euler–Bernoulli consistent ones.
#[test]
fn euler_bernoulli_is_recovered_as_the_shear_stiffness_grows() {
    let (eb, _, _) = stubby(10, None);
    let web = ss_frequencies(&eb);
    let diff = |s: f64| -> f64 {
        let (t, _, _) = stubby(10, Some(s));
        let w = ss_frequencies(&t);
        (0..6).map(|k| (web[k] - w[k]).abs() / web[k]).fold(0.0, f64::max)
    };
    let (d4, d7) = (diff(1e4), diff(1e7));
    eprintln!("relative differences to Euler–Bernoulli: {d4:e} (κGA × 1e4), {d7:e} (× 1e7)");
    assert!(d7 < 1e-6, "{d7:e}");
    assert!((d4 / d7 / 1e3 - 1.0).abs() < 0.01, "ratio {}", d4 / d7);
    // the Φ = 0 matrices are the Euler–Bernoulli consistent ones
    let el = Element::circular(0.1, 0.02, E, RHO);
    let (k, m, r) = autobal::linear_rotor::shaft::planar_matrices(&el);
    let (l, ei, ma) = (0.1, E * el.inertia / 1e-3, RHO * el.area * 0.1 / 420.0);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs().max(1e-300);
    assert!(close(k[1][1], 4.0 * l * l * ei) && close(k[1][3], 2.0 * l * l * ei) && close(k[0][0], 12.0 * ei));
    assert!(close(m[0][0], 156.0 * ma) && close(m[0][3], -13.0 * l * ma) && close(m[1][3], -3.0 * l * l * ma));
    assert!(close(r[0][0], 36.0 / (30.0 * l)) && close(r[1][3], -l * l / (30.0 * l)));
}

/// The same rotor (Timoshenko shaft, solid and hollow elements, two disks, two bearings) built
/// by ROSS (`ShaftElement(shear_effects=True, rotary_inertia=True, gyroscopic=True)`, its default
/// Cowper shear coefficient) and by the builder: the lateral `M`, `K`, `G` agree to `1e-12` of
/// each matrix's largest entry (the same formulas; round-off of the assembly). Skipped without
/// ROSS unless `AUTOBAL_REQUIRE_ROSS` is set.
#[test]
fn builder_timoshenko_equals_ross() {
    let script = r#"
import json, numpy as np, ross as rs
steel = rs.Material(name="steel_tim", rho=7810, E=211e9, G_s=81.2e9)
ids = [0.0, 0.0, 0.02, 0.02, 0.0, 0.0]
sh = [rs.ShaftElement(L=0.25, idl=i, odl=0.05, material=steel, shear_effects=True, rotary_inertia=True, gyroscopic=True) for i in ids]
disks = [rs.DiskElement(n=2, m=32.6, Id=0.17, Ip=0.33), rs.DiskElement(n=4, m=32.6, Id=0.17, Ip=0.33)]
brg = [rs.BearingElement(n=0, kxx=1e6, cxx=0.0), rs.BearingElement(n=6, kxx=1e6, cxx=0.0)]
rotor = rs.Rotor(sh, disks, brg)
per = rotor.number_dof
lat = [0, 1, 3, 4] if per == 6 else [0, 1, 2, 3]
idx = [k * per + j for k in range(7) for j in lat]
sel = np.ix_(idx, idx)
print(json.dumps({n: np.asarray(a)[sel].tolist() for n, a in [("M", rotor.M()), ("K", rotor.K(0)), ("G", rotor.G())]}))
"#;
    let Some(out) = ross_common::run_ross(script) else { return };
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let mut b = ShaftBuilder { rotary_inertia: true, gyroscopic: true, ..Default::default() };
    for di in [0.0, 0.0, 0.02, 0.02, 0.0, 0.0] {
        b.elements.push(Element::timoshenko(0.25, 0.05, di, 211e9, 7810.0, 81.2e9));
    }
    for n in [2, 4] {
        b.disks.push(Disk { node: n, mass: 32.6, id: 0.17, ip: 0.33 });
    }
    for n in [0, 6] {
        b.bearings.push(Bearing { node: n, k: 1e6, c: 0.0 });
    }
    let r = b.build().unwrap();
    let n = r.dofs();
    for (name, ours) in [("M", &r.m), ("K", &r.k), ("G", &r.g)] {
        let theirs: Vec<f64> = v[name].as_array().unwrap().iter().flat_map(|row| row.as_array().unwrap().iter().map(|x| x.as_f64().unwrap())).collect();
        assert_eq!(theirs.len(), n * n, "{name}");
        let scale = theirs.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let worst = ours.iter().zip(&theirs).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        eprintln!("{name}: largest difference {:e} of the largest entry", worst / scale);
        assert!(worst <= 1e-12 * scale, "{name}: {:e}", worst / scale);
    }
}

/// The Campbell diagram without balls of a second ROSS example rotor, `compressor_example()`
/// (91 Timoshenko elements, 7 disks, 14 bearings and seals with speed-dependent, cross-coupled
/// coefficients): ROSS's lateral `M(Ω)`, `K(Ω)`, `C(Ω)`, `G` at each speed in a
/// [`LinearRotor`], whose [`LinearRotor::structure_eigenvalues`] contain each damped natural
/// frequency `run_campbell` reports (`wd`, 6 modes tracked over speed by ROSS's MAC criterion,
/// hence not always the lowest) whose mode is lateral (at least 99 % of its displacement norm on
/// the lateral DOFs; ROSS's model has the axial and torsional ones too, ours not), to `1e-8`
/// relative (ROSS's sparse eigen-solver's tolerance; the first example, `rotor_example()`, agrees
/// to 1.2e-10 in the Python tests), at least 4 modes per speed. Skipped without ROSS unless
/// `AUTOBAL_REQUIRE_ROSS` is set.
#[test]
fn compressor_example_campbell_equals_ross() {
    let script = r#"
import json, numpy as np, ross as rs
rotor = rs.compressor_example()
speeds = [0.0, 500.0, 1000.0]
per = rotor.number_dof
lat = [0, 1, 3, 4] if per == 6 else [0, 1, 2, 3]
nodes = np.asarray(rotor.M(0.0)).shape[0] // per
idx = [k * per + j for k in range(nodes) for j in lat]
sel = np.ix_(idx, idx)
def sparse(a):
    a = np.asarray(a)[sel]
    i, j = np.nonzero(a)
    return [[int(p), int(q), float(a[p, q])] for p, q in zip(i, j)]
sp = np.array(speeds)
camp = rotor.run_campbell(sp, frequencies=6)
# the share of each tracked mode's displacement on the lateral DOFs (ROSS's DOFs include the
# axial and torsional ones; our model has the lateral ones only)
lateral = []
for w in sp:
    ev = np.asarray(camp.modal_results[w].evectors)
    nd = np.asarray(rotor.M(w)).shape[0]
    disp = ev[:nd, :6] if ev.shape[0] == 2 * nd else ev[:, :6]
    lateral.append([float(np.linalg.norm(disp[idx, c]) ** 2 / np.linalg.norm(disp[:, c]) ** 2) for c in range(6)])
out = {"n": len(idx), "speeds": speeds, "G": sparse(rotor.G()), "wd": np.asarray(camp.wd).tolist(), "lateral": lateral,
       "M": [sparse(rotor.M(w)) for w in speeds], "K": [sparse(rotor.K(w)) for w in speeds], "C": [sparse(rotor.C(w)) for w in speeds]}
print(json.dumps(out))
"#;
    let Some(out) = ross_common::run_ross(script) else { return };
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let n = v["n"].as_u64().unwrap() as usize;
    let dense = |s: &serde_json::Value| -> Vec<f64> {
        let mut a = vec![0.0; n * n];
        for e in s.as_array().unwrap() {
            let e = e.as_array().unwrap();
            a[e[0].as_u64().unwrap() as usize * n + e[1].as_u64().unwrap() as usize] = e[2].as_f64().unwrap();
        }
        a
    };
    let g = dense(&v["G"]);
    let mut worst: f64 = 0.0;
    for (i, w) in v["speeds"].as_array().unwrap().iter().enumerate() {
        let w = w.as_f64().unwrap();
        let mut r = LinearRotor::zeros(n / 4, autobal::linear_rotor::Layout::TranslationTilt);
        r.m = dense(&v["M"][i]);
        r.k = dense(&v["K"][i]);
        r.c = dense(&v["C"][i]);
        r.g = g.clone();
        let ev = r.structure_eigenvalues(w).unwrap();
        let ours: Vec<f64> = ev.iter().map(|z| z.im).filter(|im| *im > 1e-6).collect();
        let theirs: Vec<f64> = v["wd"][i].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let lateral: Vec<f64> = v["lateral"][i].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        // each of ROSS's tracked lateral modes is one of ours (nearest damped frequency)
        let mut matched = 0;
        for (f, share) in theirs.iter().zip(&lateral) {
            if *share < 0.99 {
                eprintln!("Ω = {w}: ROSS's mode at {f} is not lateral (lateral share {share:.3}): skipped");
                continue;
            }
            let near = ours.iter().map(|o| (o - f).abs() / f).fold(f64::INFINITY, f64::min);
            worst = worst.max(near);
            matched += 1;
        }
        eprintln!("Ω = {w}: ROSS {theirs:?}, lateral shares {lateral:?}");
        assert!(matched >= 4, "Ω = {w}: only {matched} lateral modes among ROSS's {theirs:?}");
    }
    eprintln!("largest relative difference {worst:e}");
    assert!(worst < 1e-8, "{worst:e}");
}
