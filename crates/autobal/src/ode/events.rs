//! Event location: the times where a function `g(t, y(t))` changes sign, found on the dense
//! output of each accepted step by a bracketing root finder (Brent's method), so no event is
//! missed between step ends when `g` changes sign there, and none is located to worse than a few
//! units of rounding in `t`.

/// Which sign changes of `g` count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// From negative to zero or positive.
    Rising,
    /// From positive to zero or negative.
    Falling,
    /// Either.
    Either,
}

/// An event function `g(t, y)`: an event happens where it changes sign (e.g. a ball touching its
/// neighbour, a relative speed reaching zero at the onset of sticking).
pub trait Event {
    /// The function whose zeros are the events.
    fn g(&self, t: f64, y: &[f64]) -> f64;
    /// Which crossings count (default: both).
    fn direction(&self) -> Direction {
        Direction::Either
    }
    /// Whether the integration stops at the event (default), with the state at the event, so the
    /// caller can change the equations and go on from there.
    fn terminal(&self) -> bool {
        true
    }
}

/// Whether going from `g0` to `g1` over a step is a crossing in `dir`. A step starting exactly
/// on a zero (`g0 == 0`, e.g. right after a terminal event) does not count.
pub(crate) fn crosses(dir: Direction, g0: f64, g1: f64) -> bool {
    let rising = g0 < 0.0 && g1 >= 0.0;
    let falling = g0 > 0.0 && g1 <= 0.0;
    match dir {
        Direction::Rising => rising,
        Direction::Falling => falling,
        Direction::Either => rising || falling,
    }
}

/// A zero of `g` in `[a, b]` with `g(a) = ga`, `g(b) = gb` of opposite signs (or `gb = 0`),
/// by Brent's method (zeroin). Returns the end of the final bracket on `b`'s side of the zero
/// (where `g` already has its new sign, or is zero), so that integration restarted there does
/// not see the same crossing again.
pub(crate) fn locate(mut g: impl FnMut(f64) -> f64, a: f64, ga: f64, b: f64, gb: f64) -> f64 {
    if gb == 0.0 {
        return b;
    }
    // Brent's method on the bracket; `b` is the best estimate, `a` the contrapoint, and we track
    // which side carries the sign of the original `gb` ("after" the crossing)
    let after_sign = gb.signum();
    let (mut a, mut fa, mut b, mut fb) = (a, ga, b, gb);
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() && fb != 0.0 {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 1e-300;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            break;
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = g(b);
    }
    // b and c bracket the zero; return the one with the "after" sign
    if fb == 0.0 || fb.signum() == after_sign {
        b
    } else {
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_roots_to_rounding_and_returns_the_far_side() {
        // cos t − t = 0 at 0.7390851332151607
        let root = 0.739_085_133_215_160_7;
        let g = |t: f64| t.cos() - t;
        let t = locate(g, 0.0, g(0.0), 1.0, g(1.0));
        assert!((t - root).abs() < 4.0 * f64::EPSILON, "{t}");
        assert!(g(t) <= 0.0, "returned on the side where g has its new sign");
        // a steep function and a flat one
        let h = |t: f64| (t - 0.3).powi(3);
        let t = locate(h, 0.0, h(0.0), 1.0, h(1.0));
        assert!((t - 0.3).abs() < 1e-5 && h(t) >= 0.0, "{t}"); // |t−0.3|³ below rounding of h
        assert!(crosses(Direction::Rising, -1.0, 0.0) && !crosses(Direction::Rising, 0.0, 1.0) && !crosses(Direction::Falling, -1.0, 1.0));
    }
}
