//! A small shaft builder: Euler–Bernoulli beam elements, rigid disks and linear isotropic
//! bearings assembled into a [`LinearRotor`] with 4 DOFs per node (`x, y, α, β`, ROSS's order).
//!
//! # Element matrices
//! In the `x–z` plane the element's DOFs are `(x1, β1, x2, β2)` with `β = dx/dz`; in the `y–z`
//! plane `(y1, α1, y2, α2)` with `α = −dy/dz` (a tilt about `x` moves a point at `+z` to `−y`), so
//! the `y–z` matrices are the planar ones with the signs of the `α` rows and columns flipped
//! (`S X S`, `S = diag(1, −1, 1, −1)`). For length `L`, Hermite cubic shape functions, the
//! planar matrices in `(w1, θ1, w2, θ2)`, `θ = dw/dz`, are
//!
//! ```text
//! K = EI/L³ [[12, 6L, −12, 6L], [6L, 4L², −6L, 2L²], [−12, −6L, 12, −6L], [6L, 2L², −6L, 4L²]]
//! M = ρAL/420 [[156, 22L, 54, −13L], [22L, 4L², 13L, −3L²], [54, 13L, 156, −22L], [−13L, −3L², −22L, 4L²]]
//! M_rot = ρI/(30L) [[36, 3L, −36, 3L], [3L, 4L², −3L, −L²], [−36, −3L, 36, −3L], [3L, −L², −3L, 4L²]]
//! ```
//!
//! (consistent mass; `M_rot = ρI ∫ N'ᵀ N' dz` the optional rotary inertia). The gyroscopic
//! matrix follows from the spin's kinetic energy `Ω ∫ ρ I_p α̇ β dz` (`I_p = 2I` for a circular
//! section; a rigid disk's `Ω I_p α̇ β` gives `G[α][β] = I_p = −G[β][α]`, ROSS's disk): with
//! `α = −N' S q_y`, `β = N' q_x`, the term is `Ω q̇ᵀ A q`, `A[y, x] = −2ρI S R`,
//! `R = ∫ N'ᵀ N' dz = M_rot / (ρI)`, and Lagrange's equations give `G = A − Aᵀ`:
//! `G[y, x] = −2ρI S R`, `G[x, y] = 2ρI R S`.
//!
//! A disk `(m, I_d, I_p)` adds `m` to `x, y`, `I_d` to `α, β` and `I_p` to `G[α][β]`,
//! `−I_p` to `G[β][α]`; a bearing `(k, c)` adds `k` and `c` to `x, y` of its node.

use super::{Layout, LinearRotor};
use crate::error::{non_negative, positive, Error, Result};

/// A uniform Euler–Bernoulli shaft element of the builder.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    /// Length `L` (m).
    pub length: f64,
    /// Young's modulus `E` (Pa).
    pub e: f64,
    /// Density `ρ` (kg/m³).
    pub rho: f64,
    /// Cross-section area `A` (m²).
    pub area: f64,
    /// Second moment of area `I` (m⁴).
    pub inertia: f64,
}

impl Element {
    /// A solid circular section of outer diameter `d`: `A = π d²/4`, `I = π d⁴/64`.
    pub fn circular(length: f64, d: f64, e: f64, rho: f64) -> Self {
        let pi = std::f64::consts::PI;
        Element { length, e, rho, area: pi * d * d / 4.0, inertia: pi * d.powi(4) / 64.0 }
    }
}

/// A rigid disk at a node: mass `m`, diametral `I_d` and polar `I_p` moments of inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disk {
    /// Node.
    pub node: usize,
    /// Mass (kg).
    pub mass: f64,
    /// Diametral moment `I_d` (kg·m²).
    pub id: f64,
    /// Polar moment `I_p` (kg·m²).
    pub ip: f64,
}

/// A linear isotropic bearing at a node: `k`, `c` on `x` and `y`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bearing {
    /// Node.
    pub node: usize,
    /// Stiffness (N/m).
    pub k: f64,
    /// Damping (N·s/m).
    pub c: f64,
}

/// Shaft elements in a row (element `i` joins nodes `i` and `i + 1`), disks, bearings.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ShaftBuilder {
    /// The elements, left to right.
    pub elements: Vec<Element>,
    /// The disks.
    pub disks: Vec<Disk>,
    /// The bearings.
    pub bearings: Vec<Bearing>,
    /// Include the elements' rotary inertia `M_rot` (and then their gyroscopic matrix).
    pub rotary_inertia: bool,
    /// Include the elements' gyroscopic matrix (needs `rotary_inertia`'s `I`; independent switch).
    pub gyroscopic: bool,
}

/// The planar stiffness, consistent mass and `∫ N'ᵀ N' dz` matrices of an element (module docs).
pub fn planar_matrices(el: &Element) -> ([[f64; 4]; 4], [[f64; 4]; 4], [[f64; 4]; 4]) {
    let l = el.length;
    let (l2, ei, ma) = (l * l, el.e * el.inertia / (l * l * l), el.rho * el.area * l / 420.0);
    let k =
        [[12.0, 6.0 * l, -12.0, 6.0 * l], [6.0 * l, 4.0 * l2, -6.0 * l, 2.0 * l2], [-12.0, -6.0 * l, 12.0, -6.0 * l], [6.0 * l, 2.0 * l2, -6.0 * l, 4.0 * l2]]
            .map(|r| r.map(|v| v * ei));
    let m = [
        [156.0, 22.0 * l, 54.0, -13.0 * l],
        [22.0 * l, 4.0 * l2, 13.0 * l, -3.0 * l2],
        [54.0, 13.0 * l, 156.0, -22.0 * l],
        [-13.0 * l, -3.0 * l2, -22.0 * l, 4.0 * l2],
    ]
    .map(|r| r.map(|v| v * ma));
    let rr = 1.0 / (30.0 * l);
    let r = [[36.0, 3.0 * l, -36.0, 3.0 * l], [3.0 * l, 4.0 * l2, -3.0 * l, -l2], [-36.0, -3.0 * l, 36.0, -3.0 * l], [3.0 * l, -l2, -3.0 * l, 4.0 * l2]]
        .map(|row| row.map(|v| v * rr));
    (k, m, r)
}

impl ShaftBuilder {
    /// `n` equal elements over `length` (uniform shaft).
    pub fn uniform(n: usize, length: f64, d: f64, e: f64, rho: f64) -> Self {
        ShaftBuilder { elements: vec![Element::circular(length / n as f64, d, e, rho); n], ..Default::default() }
    }

    /// Number of nodes: elements + 1.
    pub fn nodes(&self) -> usize {
        self.elements.len() + 1
    }

    /// Assemble the [`LinearRotor`] (no unbalance, no balancer: add them to the result).
    /// Errors name the field (`shaft.elements[2].e`, `shaft.disks[0].node`, …).
    pub fn build(&self) -> Result<LinearRotor> {
        if self.elements.is_empty() {
            return Err(Error::invalid("shaft.elements", "needs at least one element"));
        }
        for (i, el) in self.elements.iter().enumerate() {
            let f = |s: &str| format!("shaft.elements[{i}].{s}");
            positive(&f("length"), el.length)?;
            positive(&f("e"), el.e)?;
            positive(&f("rho"), el.rho)?;
            positive(&f("area"), el.area)?;
            positive(&f("inertia"), el.inertia)?;
        }
        let nodes = self.nodes();
        let mut r = LinearRotor::zeros(nodes, Layout::TranslationTilt);
        let n = r.dofs();
        for (i, el) in self.elements.iter().enumerate() {
            let (k, m, rr) = planar_matrices(el);
            let s = [1.0, -1.0, 1.0, -1.0];
            let xd = [4 * i, 4 * i + 3, 4 * i + 4, 4 * i + 7];
            let yd = [4 * i + 1, 4 * i + 2, 4 * i + 5, 4 * i + 6];
            let ri = el.rho * el.inertia;
            for a in 0..4 {
                for b in 0..4 {
                    let mut mab = m[a][b];
                    if self.rotary_inertia {
                        mab += ri * rr[a][b];
                    }
                    r.k[xd[a] * n + xd[b]] += k[a][b];
                    r.m[xd[a] * n + xd[b]] += mab;
                    r.k[yd[a] * n + yd[b]] += s[a] * s[b] * k[a][b];
                    r.m[yd[a] * n + yd[b]] += s[a] * s[b] * mab;
                    if self.gyroscopic {
                        r.g[yd[a] * n + xd[b]] += -2.0 * ri * s[a] * rr[a][b];
                        r.g[xd[a] * n + yd[b]] += 2.0 * ri * rr[a][b] * s[b];
                    }
                }
            }
        }
        for (i, d) in self.disks.iter().enumerate() {
            let f = |s: &str| format!("shaft.disks[{i}].{s}");
            if d.node >= nodes {
                return Err(Error::invalid(f("node"), format!("{} is not a node (0..{nodes})", d.node)));
            }
            non_negative(&f("mass"), d.mass)?;
            non_negative(&f("id"), d.id)?;
            non_negative(&f("ip"), d.ip)?;
            let b = 4 * d.node;
            r.m[b * n + b] += d.mass;
            r.m[(b + 1) * n + b + 1] += d.mass;
            r.m[(b + 2) * n + b + 2] += d.id;
            r.m[(b + 3) * n + b + 3] += d.id;
            r.g[(b + 2) * n + b + 3] += d.ip;
            r.g[(b + 3) * n + b + 2] -= d.ip;
        }
        for (i, br) in self.bearings.iter().enumerate() {
            let f = |s: &str| format!("shaft.bearings[{i}].{s}");
            if br.node >= nodes {
                return Err(Error::invalid(f("node"), format!("{} is not a node (0..{nodes})", br.node)));
            }
            non_negative(&f("k"), br.k)?;
            non_negative(&f("c"), br.c)?;
            let b = 4 * br.node;
            for d in [b, b + 1] {
                r.k[d * n + d] += br.k;
                r.c[d * n + d] += br.c;
            }
        }
        Ok(r)
    }
}
