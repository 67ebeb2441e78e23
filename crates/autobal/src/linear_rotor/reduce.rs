//! Modal reduction of a [`LinearRotor`] that says its error (Craig–Bampton): the DOFs of the
//! nodes that carry a balancer, an unbalance or a speed-dependent bearing stay physical
//! ("boundary" nodes), the other ("interior") DOFs are represented by the static correction
//! from the boundary (`Ψ = −K_ii⁻¹ K_ib`, exact at zero frequency) plus the lowest undamped
//! modes of the interior with the boundary held (`K_ii φ = ω² M_ii φ`) up to a cut-off:
//!
//! ```text
//! q = B z,   B = [[I, 0], [Ψ, Φ]],   z = (q_b, η),   X_r = Bᵀ X B   for X = M, C, G, K.
//! ```
//!
//! The balls and unbalances act on boundary DOFs, so the reduced rotor is again a
//! [`LinearRotor`]: the boundary nodes first (in increasing order), then the modal coordinates
//! in pairs `(φ, J φ)` (`J` the quarter turn of every `(x, y)` and `(α, β)` pair) packed as
//! pseudo-nodes, so that the reduced coordinates turn with the frame as the full ones do
//! (`J B = B J_r`) and the analysis in turning axes stays exact for the reduced model. The basis
//! is computed from the isotropic symmetric parts of `M` and `K` (`(X + Jᵀ X J)/2`), which keeps
//! `J B = B J_r` for anisotropic structures too (then it is a Ritz basis, not the exact
//! Craig–Bampton one); the speed-dependent bearings sit on boundary nodes, on which the basis
//! does not depend, so one basis serves every speed.
//!
//! The polar moment, spin drag and real balls carry over unchanged, and gravity's weight is projected
//! (`Bᵀ load`, its virtual work on `q = B z`).
//!
//! **Inertia fixed to the rotor** ([`LinearRotor::rotor_fixed_mass`] `M_rot`, kinetic energy
//! `½ q̇ᵀ T(φ) M_rot T(φ)ᵀ q̇`). `T(φ) = cos φ I + sin φ J` pair by pair, so `J B = B J_r` gives
//! `T(φ) B = B T_r(φ)` and the projection `Bᵀ T(φ) M_rot T(φ)ᵀ B = T_r(φ) (Bᵀ M_rot B) T_r(φ)ᵀ`:
//! the reduced rotor's rotor-fixed inertia is `Bᵀ M_rot B`, exact at every angle, because the
//! basis is closed under `J` (boundary nodes whole, `Ψ` from the isotropic `K`, modes in pairs
//! `(φ, J φ)`) whatever the bearings. The modes are those of `M` plus `M_rot`'s mean over a
//! turn (its part that commutes with `J`, `(M_rot + Jᵀ M_rot J)/2`); the part that turns with
//! the rotor is only projected. The stated frequencies and their intervals are those of the
//! rotor fixed in space (`M` alone, as [`LinearRotor::natural_frequencies`]).
//!
//! **The error it states.** For each undamped natural frequency `ω̃_k` of the reduced rotor
//! at rest (symmetric part of `K`, no gyroscopic or damping terms), the Krylov–Weinstein bound:
//! with `x = B z` the mode in full coordinates (`xᵀ M x = 1`) and `r = K x − ω̃² M x`, the full
//! model has an eigenvalue `ω²` with `|ω² − ω̃²| ≤ ‖L⁻¹ r‖` (`M = L Lᵀ`), a guaranteed interval
//! computed from the full matrices without solving the full eigenproblem. The first neglected
//! interior frequency `ω_c` is reported too: a forced response at frequency `ω` misses terms of
//! relative size about `(ω/ω_c)²` (the static correction carries the rest).

use super::{cholesky, Layout, LinearRotor};
use crate::error::{Error, Result};
use crate::ode::lu::Lu;
use serde::Serialize;

/// A reduced rotor and what the reduction neglects.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reduction {
    /// The reduced rotor (boundary nodes first, then the modal pseudo-nodes).
    pub rotor: LinearRotor,
    /// Reduced node `k < boundary.len()` is the full rotor's node `boundary[k]`.
    pub boundary: Vec<usize>,
    /// Number of interior mode pairs kept.
    pub mode_pairs: usize,
    /// The highest kept interior frequency (rad/s; `None` without interior modes).
    pub cutoff: Option<f64>,
    /// The lowest neglected interior frequency `ω_c` (rad/s; `None` when every mode is kept).
    pub first_neglected: Option<f64>,
    /// The reduced rotor's undamped natural frequencies at rest (rad/s, ascending, symmetric
    /// part of `K`, without the balls) with the Krylov–Weinstein bound of each: the full model
    /// has a frequency in `[low, high]`.
    pub frequencies: Vec<BoundedFrequency>,
    /// DOFs of the full and the reduced rotor.
    pub dofs: (usize, usize),
    /// The basis `B`, row-major `N × r` (`q = B z`).
    #[serde(skip)]
    pub basis: Vec<f64>,
}

/// A reduced natural frequency with the interval that holds a full-model frequency.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoundedFrequency {
    /// The reduced model's frequency (rad/s); 0 for a mode that diverges at rest
    /// (`divergent`: its `omega_squared < 0` has no frequency).
    pub omega: f64,
    /// The reduced model's `ω²` ((rad/s)²) with its sign: negative where `K` is not positive
    /// semi-definite.
    pub omega_squared: f64,
    /// Whether the mode diverges at rest: `ω²` below −[`super::divergence_threshold`] of the
    /// reduced model's `ω²` (the rule of [`super::static_divergence`]).
    pub divergent: bool,
    /// Lower end of the guaranteed interval (rad/s).
    pub low: f64,
    /// Upper end (rad/s).
    pub high: f64,
    /// The estimated error (rad/s): the difference to the same frequency with twice the mode
    /// pairs (`None` where the interior has no more modes, and for a divergent mode, which has
    /// no frequency).
    pub estimate: Option<f64>,
}

/// The partner of DOF `i` under the quarter turn `J` (`J e_i = s e_p`).
fn partner(i: usize) -> (usize, f64) {
    if i.is_multiple_of(2) {
        (i + 1, 1.0)
    } else {
        (i - 1, -1.0)
    }
}

/// `J v` (`J (a, b) = (−b, a)` per pair) of a vector indexed by DOFs `dofs` (whole pairs).
fn turn(v: &[f64]) -> Vec<f64> {
    let mut w = vec![0.0; v.len()];
    for m in 0..v.len() / 2 {
        w[2 * m] = -v[2 * m + 1];
        w[2 * m + 1] = v[2 * m];
    }
    w
}

/// The isotropic symmetric part `sym((X + Jᵀ X J)/2)`.
fn iso_sym(a: &[f64], n: usize) -> Vec<f64> {
    let mut b = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            let (pi, si) = partner(i);
            let (pj, sj) = partner(j);
            b[i * n + j] = 0.5 * (a[i * n + j] + si * sj * a[pi * n + pj]);
        }
    }
    for i in 0..n {
        for j in 0..i {
            let s = 0.5 * (b[i * n + j] + b[j * n + i]);
            b[i * n + j] = s;
            b[j * n + i] = s;
        }
    }
    b
}

/// Eigenvalues and eigenvectors (columns of `v`, row-major) of a symmetric `n × n` matrix by
/// cyclic Jacobi rotations, ascending.
fn sym_eigen(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut a = a.to_vec();
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    let norm: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    for _sweep in 0..100 {
        let off: f64 = (0..n).flat_map(|i| (0..n).filter(move |j| *j != i).map(move |j| (i, j))).map(|(i, j)| a[i * n + j].powi(2)).sum::<f64>().sqrt();
        if off <= 1e-15 * norm {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq.abs() <= 1e-300 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k * n + p], a[k * n + q]);
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p * n + k], a[q * n + k]);
                    a[p * n + k] = c * apk - s * aqk;
                    a[q * n + k] = s * apk + c * aqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                    v[k * n + p] = c * vkp - s * vkq;
                    v[k * n + q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut idx: Vec<usize> = (0..n).collect();
    idx.sort_by(|x, y| a[x * n + x].total_cmp(&a[y * n + y]));
    let w = idx.iter().map(|&i| a[i * n + i]).collect();
    let vs = (0..n).flat_map(|r| idx.iter().map(move |&c| (r, c))).map(|(r, c)| v[r * n + c]).collect();
    (w, vs)
}

/// `Lᵀ x = b` for lower-triangular `L`.
fn upper_t_solve(l: &[f64], b: &mut [f64], n: usize) {
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// `L x = b` for lower-triangular `L`.
fn lower_solve(l: &[f64], b: &mut [f64], n: usize) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// `Bᵀ X B` for `X` `n × n`, `B` `n × r` (row-major).
fn project(x: &[f64], b: &[f64], n: usize, r: usize) -> Vec<f64> {
    let mut xb = vec![0.0; n * r];
    for i in 0..n {
        for k in 0..n {
            let v = x[i * n + k];
            if v != 0.0 {
                for j in 0..r {
                    xb[i * r + j] += v * b[k * r + j];
                }
            }
        }
    }
    let mut out = vec![0.0; r * r];
    for k in 0..n {
        for i in 0..r {
            let bki = b[k * r + i];
            if bki != 0.0 {
                for j in 0..r {
                    out[i * r + j] += bki * xb[k * r + j];
                }
            }
        }
    }
    out
}

/// Reduce `rotor` keeping `mode_pairs` pairs of interior modes (rounded up to an even number
/// with tilt DOFs, so that they fill whole pseudo-nodes; at most the interior's size); the
/// nodes in `extra_boundary` stay physical beside those with a balancer, an unbalance or a
/// speed-dependent bearing.
pub fn reduce(rotor: &LinearRotor, mode_pairs: usize, extra_boundary: &[usize]) -> Result<Reduction> {
    rotor.validate()?;
    let n = rotor.dofs();
    // DOFs per modal pseudo-node: as every node's where all are alike, else one pair (x, y)
    let per = pseudo_layout(rotor).per_node();
    let mut boundary: Vec<usize> = rotor
        .balancers
        .iter()
        .map(|b| b.node)
        .chain(rotor.unbalances.iter().map(|u| u.node))
        .chain(rotor.speed_bearings.iter().flat_map(|b| std::iter::once(b.node).chain(b.link)))
        .chain(extra_boundary.iter().copied())
        .collect();
    boundary.sort_unstable();
    boundary.dedup();
    if let Some(&k) = boundary.iter().find(|k| **k >= rotor.nodes) {
        return Err(Error::invalid("linear_rotor.reduce.boundary", format!("{k} is not a node (the nodes are 0 to {})", rotor.nodes.saturating_sub(1))));
    }
    let bd: Vec<usize> = boundary
        .iter()
        .flat_map(|&k| {
            let s = rotor.node_start(k);
            s..s + rotor.node_layout(k).per_node()
        })
        .collect();
    let id: Vec<usize> = (0..n).filter(|i| !bd.contains(i)).collect();
    let (nb, ni) = (bd.len(), id.len());
    // the modes' mass: M plus the rotor-fixed inertia's mean over a turn (its part that
    // commutes with J; the rest turns with the rotor and is only projected)
    let ms = if rotor.rotor_fixed_mass.is_empty() {
        iso_sym(&rotor.m, n)
    } else {
        let sum: Vec<f64> = rotor.m.iter().zip(&rotor.rotor_fixed_mass).map(|(a, b)| a + b).collect();
        iso_sym(&sum, n)
    };
    let ks = iso_sym(&rotor.k, n);
    let sub = |a: &[f64], r: &[usize], c: &[usize]| -> Vec<f64> { r.iter().flat_map(|&i| c.iter().map(move |&j| a[i * n + j])).collect() };
    // static correction Ψ = −K_ii⁻¹ K_ib (ni × nb)
    let mut psi = vec![0.0; ni * nb];
    let mut phis: Vec<Vec<f64>> = vec![];
    let mut freqs: Vec<f64> = vec![];
    let mut first_neglected = None;
    let mut want_pairs = 0;
    if ni > 0 {
        let kii = sub(&ks, &id, &id);
        let kib = sub(&ks, &id, &bd);
        let lu = Lu::factored(kii.clone(), ni).ok_or_else(|| {
            Error::invalid("linear_rotor.reduce", "the interior stiffness K_ii is singular (a part of the shaft without bearings or boundary nodes?)")
        })?;
        for j in 0..nb {
            let mut col: Vec<f64> = (0..ni).map(|i| -kib[i * nb + j]).collect();
            lu.solve(&mut col);
            for i in 0..ni {
                psi[i * nb + j] = col[i];
            }
        }
        // interior modes with the boundary held: K_ii φ = ω² M_ii φ
        let mii = sub(&ms, &id, &id);
        let l = cholesky(&mii, ni).map_err(|i| Error::invalid("linear_rotor.m", format!("is not positive definite on the interior DOFs (pivot {i})")))?;
        let mut s = vec![0.0; ni * ni];
        // S = L⁻¹ K L⁻ᵀ
        let mut x = kii.clone();
        for c in 0..ni {
            let mut col: Vec<f64> = (0..ni).map(|r| x[r * ni + c]).collect();
            lower_solve(&l, &mut col, ni);
            for r in 0..ni {
                x[r * ni + c] = col[r];
            }
        }
        for r in 0..ni {
            let mut row: Vec<f64> = x[r * ni..(r + 1) * ni].to_vec();
            lower_solve(&l, &mut row, ni);
            for c in 0..ni {
                s[r * ni + c] = row[c];
            }
        }
        for i in 0..ni {
            for j in 0..i {
                let v = 0.5 * (s[i * ni + j] + s[j * ni + i]);
                s[i * ni + j] = v;
                s[j * ni + i] = v;
            }
        }
        let (w2, y) = sym_eigen(&s, ni);
        let want = if per == 4 { mode_pairs.div_ceil(2) * 2 } else { mode_pairs };
        let want = want.min(ni / 2 - (ni / 2) % (per / 2));
        // twice as many pairs are collected: the reference for the error estimate
        let cap = (2 * want).min(ni / 2 - (ni / 2) % (per / 2));
        want_pairs = want;
        let mdot = |a: &[f64], b: &[f64]| -> f64 {
            let mut t = 0.0;
            for i in 0..ni {
                let mut r = 0.0;
                for j in 0..ni {
                    r += mii[i * ni + j] * b[j];
                }
                t += a[i] * r;
            }
            t
        };
        for k in 0..ni {
            let mut phi: Vec<f64> = (0..ni).map(|r| y[r * ni + k]).collect();
            upper_t_solve(&l, &mut phi, ni);
            if phis.len() == 2 * cap {
                // the next mode not in the span of the kept pairs
                let mut p = phi.clone();
                for q in &phis {
                    let c = mdot(q, &p);
                    p.iter_mut().zip(q).for_each(|(a, b)| *a -= c * b);
                }
                if mdot(&p, &p) > 1e-6 {
                    first_neglected = Some(w2[k].max(0.0).sqrt());
                    break;
                }
                continue;
            }
            for q in &phis {
                let c = mdot(q, &phi);
                phi.iter_mut().zip(q).for_each(|(a, b)| *a -= c * b);
            }
            let nn = mdot(&phi, &phi);
            if nn <= 1e-6 {
                continue; // the partner of a kept mode
            }
            phi.iter_mut().for_each(|v| *v /= nn.sqrt());
            let mut jphi = turn(&phi);
            for q in &phis {
                let c = mdot(q, &jphi);
                jphi.iter_mut().zip(q).for_each(|(a, b)| *a -= c * b);
            }
            let c = mdot(&phi, &jphi);
            jphi.iter_mut().zip(&phi).for_each(|(a, b)| *a -= c * b);
            let nj = mdot(&jphi, &jphi);
            jphi.iter_mut().for_each(|v| *v /= nj.sqrt());
            phis.push(phi);
            phis.push(jphi);
            freqs.push(w2[k].max(0.0).sqrt());
        }
    }
    if per == 4 && (phis.len() / 2) % 2 == 1 {
        // whole pseudo-nodes only: the last pair is left out
        phis.truncate(phis.len() - 2);
        first_neglected = freqs.pop();
    }
    let kept = want_pairs.min(phis.len() / 2);
    if kept < freqs.len() {
        first_neglected = Some(freqs[kept]);
    }
    let (red, b, r) = assemble(rotor, &boundary, &bd, &id, &psi, &phis[..2 * kept]);
    let mut frequencies = bounds(rotor, &red, &b, r)?;
    // the error estimate: the same frequencies with twice the pairs (Craig–Bampton converges
    // fast in the pairs, so the difference is nearly all of the coarse reduction's error)
    if phis.len() > 2 * kept {
        let (reference, _, _) = assemble(rotor, &boundary, &bd, &id, &psi, &phis);
        let wr = reference.at_speed(0.0).natural_frequencies(&[], false)?;
        let wk = red.at_speed(0.0).natural_frequencies(&[], false)?;
        for (f, (a, b)) in frequencies.iter_mut().zip(wk.iter().zip(&wr)) {
            f.estimate = (!f.divergent).then(|| (a - b).abs());
        }
    }
    let pairs = kept;
    let cutoff = if kept > 0 { Some(freqs[kept - 1]) } else { None };
    Ok(Reduction { rotor: red, boundary, mode_pairs: pairs, cutoff, first_neglected, frequencies, dofs: (n, r), basis: b })
}

/// The reduced rotor and its basis for the boundary DOFs `bd`, interior DOFs `id`, static
/// correction `psi` and the interior modes `phis` (module docs).
fn assemble(rotor: &LinearRotor, boundary: &[usize], bd: &[usize], id: &[usize], psi: &[f64], phis: &[Vec<f64>]) -> (LinearRotor, Vec<f64>, usize) {
    let n = rotor.dofs();
    let pseudo = pseudo_layout(rotor);
    let nb = bd.len();
    let r = nb + phis.len();
    let mut b = vec![0.0; n * r];
    for (j, &d) in bd.iter().enumerate() {
        b[d * r + j] = 1.0;
    }
    for (ii, &d) in id.iter().enumerate() {
        for j in 0..nb {
            b[d * r + j] = psi[ii * nb + j];
        }
        for (m, phi) in phis.iter().enumerate() {
            b[d * r + nb + m] = phi[ii];
        }
    }
    // the boundary nodes with their DOFs, then the modal pseudo-nodes
    let layouts: Vec<Layout> = boundary.iter().map(|&k| rotor.node_layout(k)).chain(std::iter::repeat_n(pseudo, phis.len() / pseudo.per_node())).collect();
    let mut red = LinearRotor::with_layouts(&layouts);
    red.m = project(&rotor.m, &b, n, r);
    red.c = project(&rotor.c, &b, n, r);
    red.g = project(&rotor.g, &b, n, r);
    red.k = project(&rotor.k, &b, n, r);
    if !rotor.rotor_fixed_mass.is_empty() {
        // J B = B J_r, so Bᵀ T(φ) M_rot T(φ)ᵀ B = T_r(φ) (Bᵀ M_rot B) T_r(φ)ᵀ (module docs)
        red.rotor_fixed_mass = project(&rotor.rotor_fixed_mass, &b, n, r);
    }
    if !rotor.spin_chart.is_empty() {
        // the chart's s = ½ q_rᵀ Σ q_r in the rotor's axes: with J B = B J_r, q_r = B z_r, so
        // s = ½ z_rᵀ (Bᵀ Σ B) z_r exactly (LinearRotor::spin_chart)
        red.spin_chart = project(&rotor.spin_chart, &b, n, r);
    }
    if !rotor.spin_stiffness.is_empty() {
        // Bᵀ K_st B: the kinetic energy's ½ φ̇ q̇ᵀ G' q on q = B z (LinearRotor::spin_stiffness)
        red.spin_stiffness = project(&rotor.spin_stiffness, &b, n, r);
    }
    // exact symmetry of the projected M and skew-symmetry of G (round-off of the sums)
    for i in 0..r {
        for j in 0..i {
            let v = 0.5 * (red.m[i * r + j] + red.m[j * r + i]);
            red.m[i * r + j] = v;
            red.m[j * r + i] = v;
            if !red.rotor_fixed_mass.is_empty() {
                let v = 0.5 * (red.rotor_fixed_mass[i * r + j] + red.rotor_fixed_mass[j * r + i]);
                red.rotor_fixed_mass[i * r + j] = v;
                red.rotor_fixed_mass[j * r + i] = v;
            }
            if !red.spin_chart.is_empty() {
                let v = 0.5 * (red.spin_chart[i * r + j] + red.spin_chart[j * r + i]);
                red.spin_chart[i * r + j] = v;
                red.spin_chart[j * r + i] = v;
            }
            let g = 0.5 * (red.g[i * r + j] - red.g[j * r + i]);
            red.g[i * r + j] = g;
            red.g[j * r + i] = -g;
        }
        red.g[i * r + i] = 0.0;
    }
    let node_of = |k: usize| boundary.iter().position(|b| *b == k).expect("boundary node");
    red.unbalances = rotor.unbalances.iter().map(|u| super::Unbalance { node: node_of(u.node), ..*u }).collect();
    red.balancers = rotor.balancers.iter().map(|p| super::BalancerPlane { node: node_of(p.node), ..*p }).collect();
    red.speed_bearings = rotor.speed_bearings.iter().map(|s| super::SpeedBearing { node: node_of(s.node), link: s.link.map(node_of), ..s.clone() }).collect();
    red.polar_inertia = rotor.polar_inertia;
    red.spin_damping = rotor.spin_damping;
    red.ball_physics = rotor.ball_physics.clone();
    // the weight's virtual work on q = B z: Bᵀ load
    red.gravity = rotor.gravity.as_ref().map(|g| super::Gravity { g: g.g, load: (0..r).map(|j| (0..n).map(|i| b[i * r + j] * g.load[i]).sum()).collect() });
    (red, b, r)
}

/// The layout of the modal pseudo-nodes: every node's where all are alike, else `x, y` (one
/// pair of modal coordinates each).
fn pseudo_layout(rotor: &LinearRotor) -> Layout {
    if rotor.node_layouts.is_empty() {
        rotor.layout
    } else {
        Layout::Translation
    }
}

/// The reduced natural frequencies at rest with their Krylov–Weinstein intervals (module docs).
fn bounds(full: &LinearRotor, red: &LinearRotor, b: &[f64], r: usize) -> Result<Vec<BoundedFrequency>> {
    let n = full.dofs();
    let sym = |a: &[f64], n: usize| -> Vec<f64> { (0..n * n).map(|ij| 0.5 * (a[ij] + a[(ij % n) * n + ij / n])).collect() };
    let (c0, k0) = full.damping_stiffness_at(0.0);
    let _ = c0;
    let kf = sym(&k0, n);
    let (_, kr0) = red.damping_stiffness_at(0.0);
    let kr = sym(&kr0, r);
    let lr = cholesky(&red.m, r).map_err(|i| Error::invalid("linear_rotor.m", format!("the reduced mass matrix is not positive definite (pivot {i})")))?;
    let lf = cholesky(&full.m, n).map_err(|i| Error::invalid("linear_rotor.m", format!("is not positive definite (pivot {i})")))?;
    // reduced S = L⁻¹ K L⁻ᵀ
    let mut x = kr.clone();
    for c in 0..r {
        let mut col: Vec<f64> = (0..r).map(|i| x[i * r + c]).collect();
        lower_solve(&lr, &mut col, r);
        for i in 0..r {
            x[i * r + c] = col[i];
        }
    }
    let mut s = vec![0.0; r * r];
    for i in 0..r {
        let mut row = x[i * r..(i + 1) * r].to_vec();
        lower_solve(&lr, &mut row, r);
        s[i * r..(i + 1) * r].copy_from_slice(&row);
    }
    let s = sym(&s, r);
    let (theta, y) = sym_eigen(&s, r);
    let threshold = super::divergence_threshold(&theta);
    let mut out = vec![];
    for k in 0..r {
        let mut z: Vec<f64> = (0..r).map(|i| y[i * r + k]).collect();
        upper_t_solve(&lr, &mut z, r);
        let xf: Vec<f64> = (0..n).map(|i| (0..r).map(|j| b[i * r + j] * z[j]).sum()).collect();
        let mut res: Vec<f64> = (0..n).map(|i| (0..n).map(|j| (kf[i * n + j] - theta[k] * full.m[i * n + j]) * xf[j]).sum()).collect();
        lower_solve(&lf, &mut res, n);
        let bound = res.iter().map(|v| v * v).sum::<f64>().sqrt();
        let th = theta[k].max(0.0);
        out.push(BoundedFrequency {
            omega: th.sqrt(),
            omega_squared: theta[k],
            divergent: theta[k] < -threshold,
            low: (th - bound).max(0.0).sqrt(),
            high: (th + bound).sqrt(),
            estimate: None,
        });
    }
    Ok(out)
}

impl Reduction {
    /// Full-coordinate state `(q, ψ, q̇, ψ̇)` of a reduced state `(z, ψ, ż, ψ̇)`.
    pub fn expand(&self, x: &[f64]) -> Vec<f64> {
        let (n, r) = self.dofs;
        let nb = (x.len() / 2) - r;
        let nc_r = r + nb;
        let mut y = vec![0.0; 2 * (n + nb)];
        for half in 0..2 {
            let (src, dst) = (half * nc_r, half * (n + nb));
            for i in 0..n {
                y[dst + i] = (0..r).map(|j| self.basis[i * r + j] * x[src + j]).sum();
            }
            y[dst + n..dst + n + nb].copy_from_slice(&x[src + r..src + r + nb]);
        }
        y
    }
}
