//! Forward-mode automatic differentiation: numbers carrying `N` directional derivatives, so a
//! model writes its equations once, generic over [`Real`], and gets exact Jacobian entries
//! (no difference increments) by evaluating them on [`Dual`] numbers.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// What the equations need of a number: `+ − ×`, scaling by and division by constants,
/// adding constants, `sin`/`cos`.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + Add<f64, Output = Self>
{
    /// A constant.
    fn cst(v: f64) -> Self;
    /// `(sin x, cos x)`.
    fn sin_cos(self) -> (Self, Self);
    /// `(sin x, cos x)` where an absolute error of 2 ulp of 1 is enough (angles of bodies whose
    /// sines enter sums of terms of order one): on `f64` a Cody–Waite reduction by π/2 and
    /// fdlibm's kernels, about a quarter of the C library's instructions; by default (and on [`Dual`] numbers) [`Real::sin_cos`].
    #[inline(always)]
    fn sin_cos_fast(self) -> (Self, Self) {
        self.sin_cos()
    }
    /// The value (derivatives dropped).
    fn value(self) -> f64;
}

impl Real for f64 {
    #[inline]
    fn cst(v: f64) -> Self {
        v
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
    #[inline(always)]
    fn sin_cos_fast(self) -> (Self, Self) {
        sin_cos(self)
    }
    #[inline]
    fn value(self) -> f64 {
        self
    }
}

/// `(sin x, cos x)` to within 2 ulp of 1 in absolute error (what the equations need: the
/// sines enter sums of terms of order one), about a quarter of the instructions of the C
/// library's `sincos` (which is 30 % of a right-hand side with many balls): Cody–Waite
/// reduction by π/2 with the constant split in three (33 + 33 + 53 bits, so `k·P1` and `k·P2`
/// are exact for `|k| < 2^20`), then fdlibm's minimax kernels on `[−π/4, π/4]`. Outside
/// `|x| ≤ 2^19 π/2` (and for NaN) the library's `sin_cos`. The constants are fdlibm's bit for
/// bit (shortest decimals that round to them). [`Real::sin_cos_fast`] of `f64`.
#[inline(always)]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    if !(x.abs() <= SIN_COS_LIMIT) {
        return x.sin_cos();
    }
    sin_cos_reduced(x)
}

/// Arguments up to this magnitude take [`sin_cos_reduced`] (`2^19 π/2`).
pub(crate) const SIN_COS_LIMIT: f64 = 823_549.656_552_477_6;

/// [`sin_cos`] without the range check (`|x| ≤ SIN_COS_LIMIT`): no branch, so a loop over the
/// balls vectorises.
#[inline(always)]
pub(crate) fn sin_cos_reduced(x: f64) -> (f64, f64) {
    const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;
    const P1: f64 = 1.570_796_326_734_125_6; // first 33 bits of π/2
    const P2: f64 = 6.077_100_506_303_966e-11; // next 33 bits
    const P3: f64 = 2.022_266_248_795_950_6e-21; // π/2 − P1 − P2
    const ROUND: f64 = 6_755_399_441_055_744.0; // 1.5 · 2^52: adding it rounds to an integer
    const S: [f64; 6] = [
        -0.166_666_666_666_666_32,
        0.008_333_333_333_322_49,
        -1.984_126_982_985_795e-4,
        2.755_731_370_707_006_8e-6,
        -2.505_076_025_340_686_3e-8,
        1.589_690_995_211_55e-10,
    ];
    const C: [f64; 6] = [
        0.041_666_666_666_666_6,
        -0.001_388_888_888_887_411,
        2.480_158_728_947_673e-5,
        -2.755_731_435_139_066_3e-7,
        2.087_572_321_298_175e-9,
        -1.135_964_755_778_819_5e-11,
    ];
    let shifted = x * INV_PIO2 + ROUND;
    let k = shifted - ROUND;
    // the quadrant k mod 4 sits in the low bits of the shifted sum (two's complement)
    let q = shifted.to_bits() & 3;
    let r = ((x - k * P1) - k * P2) - k * P3;
    let z = r * r;
    let sin = r + r * z * (S[0] + z * (S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let cos = w + (((1.0 - w) - hz) + z * z * (C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5]))))));
    // (sin, cos), (cos, −sin), (−sin, −cos), (−cos, sin) for q = 0..3, without branches (a
    // jump per ball mispredicts when the balls lie in different quadrants)
    let swap = 0u64.wrapping_sub(q & 1);
    let (sb, cb) = (sin.to_bits(), cos.to_bits());
    let first = (sb & !swap) | (cb & swap);
    let second = (cb & !swap) | (sb & swap);
    (f64::from_bits(first ^ ((q & 2) << 62)), f64::from_bits(second ^ (((q + 1) & 2) << 62)))
}

/// A value with `N` directional derivatives: `v + Σ d_k ε_k`, `ε_k ε_l = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// Value.
    pub v: f64,
    /// Derivatives along the `N` seeded directions.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// The independent variable seeded in direction `k` (derivative 1 there, 0 elsewhere).
    pub fn var(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        d[k] = 1.0;
        Dual { v, d }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Dual { v: self.v + o.v, d: std::array::from_fn(|k| self.d[k] + o.d[k]) }
    }
}
impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Dual { v: self.v - o.v, d: std::array::from_fn(|k| self.d[k] - o.d[k]) }
    }
}
impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    // the product rule adds
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline]
    fn mul(self, o: Self) -> Self {
        Dual { v: self.v * o.v, d: std::array::from_fn(|k| self.d[k] * o.v + self.v * o.d[k]) }
    }
}
impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Dual { v: -self.v, d: self.d.map(|x| -x) }
    }
}
impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, s: f64) -> Self {
        Dual { v: self.v * s, d: self.d.map(|x| x * s) }
    }
}
impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    /// `(v + d ε)/s = v/s + (d/s) ε` (divided, not multiplied by `1/s`: `f64` rounding kept).
    #[inline]
    fn div(self, s: f64) -> Self {
        Dual { v: self.v / s, d: self.d.map(|x| x / s) }
    }
}
impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(self, s: f64) -> Self {
        Dual { v: self.v + s, d: self.d }
    }
}

impl<const N: usize> Real for Dual<N> {
    fn cst(v: f64) -> Self {
        Dual { v, d: [0.0; N] }
    }
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.v.sin_cos();
        (Dual { v: s, d: self.d.map(|x| x * c) }, Dual { v: c, d: self.d.map(|x| -x * s) })
    }
    fn value(self) -> f64 {
        self.v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_closed_forms() {
        // f(x, y) = x² sin y + 3 x − y cos x at (0.7, −1.3)
        let (x, y) = (0.7, -1.3);
        let f = |x: Dual<2>, y: Dual<2>| {
            let (sy, _) = y.sin_cos();
            let (_, cx) = x.sin_cos();
            x * x * sy + x * 3.0 - y * cx
        };
        let r = f(Dual::var(x, 0), Dual::var(y, 1));
        let q = Dual::<2>::var(x, 0) / 4.0;
        assert_eq!((q.v, q.d), (x / 4.0, [0.25, 0.0]));
        assert!((r.v - (x * x * y.sin() + 3.0 * x - y * x.cos())).abs() < 1e-15);
        assert!((r.d[0] - (2.0 * x * y.sin() + 3.0 + y * x.sin())).abs() < 1e-15);
        assert!((r.d[1] - (x * x * y.cos() - x.cos())).abs() < 1e-15);
    }
}
