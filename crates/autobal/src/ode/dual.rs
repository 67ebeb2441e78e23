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
    #[inline]
    fn value(self) -> f64 {
        self
    }
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
