//! A small shaft builder: Euler–Bernoulli or Timoshenko beam elements, rigid disks and linear
//! isotropic bearings assembled into a [`LinearRotor`] with 4 DOFs per node (`x, y, α, β`,
//! ROSS's order).
//!
//! # Element matrices
//! In the `x–z` plane the element's DOFs are `(x1, β1, x2, β2)` with `β` the section's rotation
//! (`β = dx/dz` without shear); in the `y–z` plane `(y1, α1, y2, α2)` with `α` the rotation about
//! `x` (`α = −dy/dz` without shear: a tilt about `x` moves a point at `+z` to `−y`), so the `y–z`
//! matrices are the planar ones with the signs of the `α` rows and columns flipped (`S X S`,
//! `S = diag(1, −1, 1, −1)`). For length `L` and the shear parameter
//! `Φ = 12 E I / (κ G A L²)` (`κ G A` the element's [`Element::shear`] stiffness; `Φ = 0`, the
//! Euler–Bernoulli element with Hermite cubics, when it is `None`), the planar matrices in
//! `(w1, θ1, w2, θ2)` are the Timoshenko element's of Friedman & Kosmatka (1993) (ROSS's
//! `ShaftElement` for a uniform section, its `K`, `M` and `G` with `shear_effects`):
//!
//! ```text
//! K = EI/(L³(1+Φ)) [[12, 6L, −12, 6L], [6L, (4+Φ)L², −6L, (2−Φ)L²], [−12, −6L, 12, −6L], [6L, (2−Φ)L², −6L, (4+Φ)L²]]
//! M = ρAL/(1260(1+Φ)²) [[m1, m2, m3, −m4], [m2, m5, m4, −m7], [m3, m4, m1, −m2], [−m4, −m7, −m2, m5]]
//!     m1 = 468 + 882Φ + 420Φ²,  m2 = (66 + 115.5Φ + 52.5Φ²) L,  m3 = 162 + 378Φ + 210Φ²,
//!     m4 = (39 + 94.5Φ + 52.5Φ²) L,  m5 = (12 + 21Φ + 10.5Φ²) L²,  m7 = (9 + 21Φ + 10.5Φ²) L²
//! M_rot = ρI/(210 L (1+Φ)²) [[252, r1, −252, r1], [r1, r2, −r1, −r3], [−252, −r1, 252, −r1], [r1, −r3, −r1, r2]]
//!     r1 = (21 − 105Φ) L,  r2 = (28 + 35Φ + 70Φ²) L²,  r3 = (7 + 35Φ − 35Φ²) L²
//! ```
//!
//! (at `Φ = 0`: `K = EI/L³ [[12, 6L, …]]`, `M = ρAL/420 [[156, 22L, 54, −13L], …]`,
//! `M_rot = ρI/(30L) [[36, 3L, −36, 3L], …]`, the Euler–Bernoulli consistent matrices; `M_rot`
//! is the optional rotary inertia `ρI ∫ N_θᵀ N_θ dz` of the section rotations). The gyroscopic
//! matrix follows from the spin's kinetic energy `Ω ∫ ρ I_p α̇ β dz` (`I_p = 2I` for a circular
//! section; a rigid disk's `Ω I_p α̇ β` gives `G[α][β] = I_p = −G[β][α]`, ROSS's disk): with
//! `α = −N_θ S q_y`, `β = N_θ q_x`, the term is `Ω q̇ᵀ A q`, `A[y, x] = −2ρI S R`,
//! `R = ∫ N_θᵀ N_θ dz = M_rot / (ρI)`, and Lagrange's equations give `G = A − Aᵀ`:
//! `G[y, x] = −2ρI S R`, `G[x, y] = 2ρI R S`.
//!
//! The shear coefficient of a (hollow) circular section is Cowper's (1966),
//! `κ = 6(1+ν)(1+r²)² / ((7+6ν)(1+r²)² + (20+12ν) r²)`, `r` the ratio of inner to outer
//! diameter and `ν = E/(2G) − 1` ([`cowper_kappa`], ROSS's default `shear_method_calc`).
//!
//! A disk `(m, I_d, I_p)` adds `m` to `x, y`, `I_d` to `α, β` and `I_p` to `G[α][β]`,
//! `−I_p` to `G[β][α]`; a bearing `(k, c)` adds `k` and `c` to `x, y` of its node. The built
//! rotor's polar moment ([`LinearRotor::polar_inertia`], for torque drives) is
//! `Σ ρ (2I) L + Σ I_p` over the elements (circular sections: the polar second moment is `2I`)
//! and the disks.

use super::{Layout, LinearRotor};
use crate::error::{non_negative, positive, Error, Result};

/// A uniform shaft element of the builder: Euler–Bernoulli (`shear: None`) or Timoshenko.
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
    /// Shear stiffness `κ G A` (N) of a Timoshenko element (shear deformation, module docs);
    /// `None`: Euler–Bernoulli (the limit `κ G A → ∞`).
    pub shear: Option<f64>,
}

impl Element {
    /// A solid circular section of outer diameter `d`: `A = π d²/4`, `I = π d⁴/64`.
    pub fn circular(length: f64, d: f64, e: f64, rho: f64) -> Self {
        let pi = std::f64::consts::PI;
        Element { length, e, rho, area: pi * d * d / 4.0, inertia: pi * d.powi(4) / 64.0, shear: None }
    }

    /// A Timoshenko element of a hollow circular section (outer diameter `d`, inner `di`, `0` for
    /// a solid one), shear modulus `g`: `A = π(d² − di²)/4`, `I = π(d⁴ − di⁴)/64`, shear
    /// stiffness `κ G A` with Cowper's `κ` ([`cowper_kappa`], `ν = E/(2G) − 1`), as ROSS's
    /// `ShaftElement(shear_effects=True)`.
    pub fn timoshenko(length: f64, d: f64, di: f64, e: f64, rho: f64, g: f64) -> Self {
        // the outer section less the inner one (as the config's elements with inner_diameter)
        let (o, i) = (Element::circular(length, d, e, rho), Element::circular(length, di, e, rho));
        let (area, inertia) = (o.area - i.area, o.inertia - i.inertia);
        let kappa = cowper_kappa(e / (2.0 * g) - 1.0, di / d);
        Element { length, e, rho, area, inertia, shear: Some(kappa * g * area) }
    }

    /// The shear parameter `Φ = 12 E I / (κ G A L²)` (0 for Euler–Bernoulli).
    pub fn shear_parameter(&self) -> f64 {
        match self.shear {
            Some(s) => 12.0 * self.e * self.inertia / (s * self.length * self.length),
            None => 0.0,
        }
    }
}

/// Cowper's (1966) shear coefficient of a hollow circular section,
/// `κ = 6(1+ν)(1+r²)² / ((7+6ν)(1+r²)² + (20+12ν) r²)` (`r` inner/outer diameter, `ν` Poisson's
/// ratio; `6(1+ν)/(7+6ν)` for a solid section).
pub fn cowper_kappa(nu: f64, r: f64) -> f64 {
    let r2 = r * r;
    let r12 = (1.0 + r2) * (1.0 + r2);
    6.0 * r12 * (1.0 + nu) / (r12 * (7.0 + 6.0 * nu) + r2 * (20.0 + 12.0 * nu))
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

/// The planar stiffness, consistent mass and `∫ N_θᵀ N_θ dz` matrices of an element in
/// `(w1, θ1, w2, θ2)` (module docs; Timoshenko with the element's shear parameter `Φ`).
pub fn planar_matrices(el: &Element) -> ([[f64; 4]; 4], [[f64; 4]; 4], [[f64; 4]; 4]) {
    let l = el.length;
    let p = el.shear_parameter();
    let p2 = p * p;
    let l2 = l * l;
    let ei = el.e * el.inertia / (l * l * l * (1.0 + p));
    let k = [
        [12.0, 6.0 * l, -12.0, 6.0 * l],
        [6.0 * l, (4.0 + p) * l2, -6.0 * l, (2.0 - p) * l2],
        [-12.0, -6.0 * l, 12.0, -6.0 * l],
        [6.0 * l, (2.0 - p) * l2, -6.0 * l, (4.0 + p) * l2],
    ]
    .map(|r| r.map(|v| v * ei));
    let m1 = 468.0 + 882.0 * p + 420.0 * p2;
    let m2 = (66.0 + 115.5 * p + 52.5 * p2) * l;
    let m3 = 162.0 + 378.0 * p + 210.0 * p2;
    let m4 = (39.0 + 94.5 * p + 52.5 * p2) * l;
    let m5 = (12.0 + 21.0 * p + 10.5 * p2) * l2;
    let m7 = (9.0 + 21.0 * p + 10.5 * p2) * l2;
    let ma = el.rho * el.area * l / (1260.0 * (1.0 + p) * (1.0 + p));
    let m = [[m1, m2, m3, -m4], [m2, m5, m4, -m7], [m3, m4, m1, -m2], [-m4, -m7, -m2, m5]].map(|r| r.map(|v| v * ma));
    let r1 = (21.0 - 105.0 * p) * l;
    let r2 = (28.0 + 35.0 * p + 70.0 * p2) * l2;
    let r3 = (7.0 + 35.0 * p - 35.0 * p2) * l2;
    let rr = 1.0 / (210.0 * l * (1.0 + p) * (1.0 + p));
    let r = [[252.0, r1, -252.0, r1], [r1, r2, -r1, -r3], [-252.0, -r1, 252.0, -r1], [r1, -r3, -r1, r2]].map(|row| row.map(|v| v * rr));
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
            if let Some(sh) = el.shear {
                positive(&f("shear"), sh)?;
            }
        }
        let nodes = self.nodes();
        let mut r = LinearRotor::zeros(nodes, Layout::TranslationTilt);
        let n = r.dofs();
        r.polar_inertia = self.elements.iter().map(|el| el.rho * 2.0 * el.inertia * el.length).sum::<f64>() + self.disks.iter().map(|d| d.ip).sum::<f64>();
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
                return Err(Error::invalid(f("node"), format!("{} is not a node (the nodes are 0 to {})", d.node, nodes.saturating_sub(1))));
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
                return Err(Error::invalid(f("node"), format!("{} is not a node (the nodes are 0 to {})", br.node, nodes.saturating_sub(1))));
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
