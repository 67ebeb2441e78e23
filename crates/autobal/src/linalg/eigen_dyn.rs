//! Eigenvalues of a dense real `n × n` matrix of any size (row-major slice, heap-backed):
//! the same three stages as [`super::eigen`] (which is fixed at 12×12 on the stack), for the
//! model-agnostic stability analysis ([`crate::analysis`]), whose state dimension is the
//! model's (`2(2 + n)` for the planar rotor with `n` balls, more for two planes):
//!
//! 1. **balancing**: a diagonal similarity `D⁻¹ A D` by powers of two (exact in floating point)
//!    making each row and column norm comparable (Parlett–Reinsch; LAPACK `dgebal` without the
//!    permutations). State matrices in physical units mix `k/m ~ 1e5` with `c_ψ/(m r²) ~ 1`;
//!    without this step the QR iteration's backward error `ε‖A‖` is an absolute error of `ε‖A‖`
//!    on every eigenvalue, and faer's and nalgebra's unbalanced Schur forms return eigenvalues
//!    wrong by O(1) after a scaling spanning 1e6 (/work/shared/DEPENDENCIES.md; the tests here
//!    repeat that experiment);
//! 2. **Hessenberg reduction** by stabilised elimination (EISPACK `elmhes`);
//! 3. **Francis double-shift QR** (EISPACK `hqr`, eigenvalues only), with exceptional shifts
//!    after 10 and 20 iterations and at most [`MAX_ITERATIONS`] iterations per eigenvalue, after
//!    which it stops with [`NoConvergence`] rather than loop or return a guess.
//!
//! Model-free: imports nothing but `num_complex`.

// Index loops follow the algorithms' formulas (rows, columns, coefficients).
#![allow(clippy::needless_range_loop)]

use num_complex::Complex64;

/// Most QR iterations spent on one eigenvalue (or pair) before [`NoConvergence`] (EISPACK's
/// `hqr` uses 30; we allow more, the exceptional shifts come at 10, 20, 30, ...).
pub const MAX_ITERATIONS: usize = 60;

/// The QR iteration did not converge: [`MAX_ITERATIONS`] iterations did not split off an
/// eigenvalue with `remaining` still in the active block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NoConvergence {
    /// Size of the active (unreduced) block when it stopped.
    pub remaining: usize,
    /// Iterations spent on it.
    pub iterations: usize,
}

impl std::fmt::Display for NoConvergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the QR iteration did not converge ({} iterations with {} eigenvalues left)", self.iterations, self.remaining)
    }
}

impl std::error::Error for NoConvergence {}

/// All `n` eigenvalues of the real `n × n` matrix `a` (row-major, `a[i n + j] = A_ij`), in no
/// particular order, complex pairs adjacent with the negative imaginary part first: balancing,
/// Hessenberg reduction, Francis QR (module docs). Non-finite entries give [`NoConvergence`].
///
/// ```
/// use autobal::linalg::eigen_dyn::eigenvalues;
/// // x'' + 0.2 x' + x = 0 as a first-order system: λ = −0.1 ± i sqrt(0.99)
/// let l = eigenvalues(&[0.0, 1.0, -1.0, -0.2], 2).unwrap();
/// assert!((l[0].re + 0.1).abs() < 1e-15 && (l[1].im - 0.99f64.sqrt()).abs() < 1e-15);
/// ```
pub fn eigenvalues(a: &[f64], n: usize) -> Result<Vec<Complex64>, NoConvergence> {
    // `stop` never says yes: always `Some`
    eigenvalues_or_stop(a, n, || false).map(Option::unwrap_or_default)
}

/// [`eigenvalues`], asking `stop` once per column of the Hessenberg reduction and once per QR
/// iteration (each `O(n²)` work or less on an `n × n` matrix, so a few milliseconds apart even
/// at `n` in the thousands, where the whole solve takes tens of seconds; a 2 × 2 matrix has
/// neither and is never asked); `Ok(None)` as soon as
/// it says yes (the work so far is dropped). For a caller that must stop within a moment of
/// Ctrl-C on a large model ([`crate::analysis`] on a linear rotor of hundreds of DOFs); with
/// `|| false` it is [`eigenvalues`].
///
/// ```
/// use autobal::linalg::eigen_dyn::eigenvalues_or_stop;
/// // a 3 × 3 matrix is reduced over one column, where a stop that says yes ends it
/// let a = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0];
/// assert!(eigenvalues_or_stop(&a, 3, || true).unwrap().is_none());
/// assert_eq!(eigenvalues_or_stop(&a, 3, || false).unwrap().unwrap().len(), 3);
/// ```
pub fn eigenvalues_or_stop(a: &[f64], n: usize, stop: impl Fn() -> bool) -> Result<Option<Vec<Complex64>>, NoConvergence> {
    assert_eq!(a.len(), n * n, "an n × n matrix");
    if a.iter().any(|x| !x.is_finite()) {
        return Err(NoConvergence { remaining: n, iterations: 0 });
    }
    if n == 0 {
        return Ok(Some(vec![]));
    }
    let mut b = vec![vec![0.0; n + 1]; n + 1];
    for i in 0..n {
        b[i + 1][1..].copy_from_slice(&a[i * n..(i + 1) * n]);
    }
    balance(&mut b, n);
    if hessenberg(&mut b, n, &stop) {
        return Ok(None);
    }
    let mut wr = vec![0.0; n];
    let mut wi = vec![0.0; n];
    if hqr(&mut b, n, &mut wr, &mut wi, &stop)? {
        return Ok(None);
    }
    Ok(Some(wr.iter().zip(&wi).map(|(&r, &i)| Complex64::new(r, i)).collect()))
}

/// Spectral abscissa `max Re λ` of the `n × n` matrix `a` ([`eigenvalues`]).
pub fn spectral_abscissa(a: &[f64], n: usize) -> Result<f64, NoConvergence> {
    Ok(eigenvalues(a, n)?.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max))
}

/// Diagonal similarity `D⁻¹ A D` with powers of two making row and column norms comparable
/// (Parlett–Reinsch; LAPACK `dgebal` without permutations). Exact in floating point.
fn balance(a: &mut [Vec<f64>], n: usize) {
    const RADIX: f64 = 2.0;
    let sqrdx = RADIX * RADIX;
    let mut done = false;
    let mut sweeps = 0;
    while !done && sweeps < 100 {
        done = true;
        sweeps += 1;
        for i in 1..=n {
            let (mut r, mut c) = (0.0, 0.0);
            for j in 1..=n {
                if j != i {
                    c += a[j][i].abs();
                    r += a[i][j].abs();
                }
            }
            if c != 0.0 && r != 0.0 {
                let mut g = r / RADIX;
                let mut f = 1.0;
                let s = c + r;
                while c < g {
                    f *= RADIX;
                    c *= sqrdx;
                }
                g = r * RADIX;
                while c > g {
                    f /= RADIX;
                    c /= sqrdx;
                }
                if (c + r) / f < 0.95 * s {
                    done = false;
                    let g = 1.0 / f;
                    for j in 1..=n {
                        a[i][j] *= g;
                    }
                    for j in 1..=n {
                        a[j][i] *= f;
                    }
                }
            }
        }
    }
}

/// Reduce to upper Hessenberg form by Gaussian elimination with pivoting (EISPACK `elmhes`);
/// entries below the subdiagonal are zeroed. `true` when `stop` (asked once per column) said
/// yes: the reduction is then unfinished.
fn hessenberg(a: &mut [Vec<f64>], n: usize, stop: &impl Fn() -> bool) -> bool {
    for m in 2..n {
        if stop() {
            return true;
        }
        let mut x: f64 = 0.0;
        let mut i = m;
        for j in m..=n {
            if a[j][m - 1].abs() > x.abs() {
                x = a[j][m - 1];
                i = j;
            }
        }
        if i != m {
            for j in (m - 1)..=n {
                let t = a[i][j];
                a[i][j] = a[m][j];
                a[m][j] = t;
            }
            for row in a.iter_mut().take(n + 1).skip(1) {
                row.swap(i, m);
            }
        }
        if x != 0.0 {
            for i in (m + 1)..=n {
                let mut y = a[i][m - 1];
                if y != 0.0 {
                    y /= x;
                    a[i][m - 1] = y;
                    for j in m..=n {
                        a[i][j] -= y * a[m][j];
                    }
                    for j in 1..=n {
                        a[j][m] += y * a[j][i];
                    }
                }
            }
        }
    }
    for i in 3..=n {
        for j in 1..i - 1 {
            a[i][j] = 0.0;
        }
    }
    false
}

fn sign(a: f64, b: f64) -> f64 {
    if b >= 0.0 {
        a.abs()
    } else {
        -a.abs()
    }
}

/// Eigenvalues of an upper Hessenberg matrix by the Francis double-shift QR iteration
/// (EISPACK `hqr`, eigenvalues only; the matrix is destroyed). `Ok(true)` when `stop` (asked
/// once per iteration) said yes: `wr`, `wi` are then incomplete.
#[allow(unused_assignments)] // the working scalars carry values between the stages, as in EISPACK
fn hqr(a: &mut [Vec<f64>], n: usize, wr: &mut [f64], wi: &mut [f64], stop: &impl Fn() -> bool) -> Result<bool, NoConvergence> {
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in (i.max(2) - 1)..=n {
            anorm += a[i][j].abs();
        }
    }
    let mut nn = n as isize;
    let mut t = 0.0;
    let (mut p, mut q, mut r, mut s, mut w, mut x, mut y, mut z) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    while nn >= 1 {
        let mut its = 0;
        loop {
            let nu = nn as usize;
            let mut l = nu;
            while l >= 2 {
                s = a[l - 1][l - 1].abs() + a[l][l].abs();
                if s == 0.0 {
                    s = anorm;
                }
                if a[l][l - 1].abs() <= f64::EPSILON * s {
                    a[l][l - 1] = 0.0;
                    break;
                }
                l -= 1;
            }
            x = a[nu][nu];
            if l == nu {
                wr[nu - 1] = x + t;
                wi[nu - 1] = 0.0;
                nn -= 1;
            } else {
                y = a[nu - 1][nu - 1];
                w = a[nu][nu - 1] * a[nu - 1][nu];
                if l == nu - 1 {
                    p = 0.5 * (y - x);
                    q = p * p + w;
                    z = q.abs().sqrt();
                    x += t;
                    if q >= 0.0 {
                        z = p + sign(z, p);
                        wr[nu - 2] = x + z;
                        wr[nu - 1] = x + z;
                        if z != 0.0 {
                            wr[nu - 1] = x - w / z;
                        }
                        wi[nu - 2] = 0.0;
                        wi[nu - 1] = 0.0;
                    } else {
                        wr[nu - 2] = x + p;
                        wr[nu - 1] = x + p;
                        wi[nu - 2] = -z;
                        wi[nu - 1] = z;
                    }
                    nn -= 2;
                } else {
                    if its == MAX_ITERATIONS {
                        return Err(NoConvergence { remaining: nu, iterations: its });
                    }
                    if its % 10 == 0 && its > 0 {
                        // exceptional shift
                        t += x;
                        for i in 1..=nu {
                            a[i][i] -= x;
                        }
                        s = a[nu][nu - 1].abs() + a[nu - 1][nu - 2].abs();
                        x = 0.75 * s;
                        y = x;
                        w = -0.4375 * s * s;
                    }
                    if stop() {
                        return Ok(true);
                    }
                    its += 1;
                    let mut m = nu - 2;
                    loop {
                        z = a[m][m];
                        r = x - z;
                        s = y - z;
                        p = (r * s - w) / a[m + 1][m] + a[m][m + 1];
                        q = a[m + 1][m + 1] - z - r - s;
                        r = a[m + 2][m + 1];
                        s = p.abs() + q.abs() + r.abs();
                        p /= s;
                        q /= s;
                        r /= s;
                        if m == l {
                            break;
                        }
                        let u = a[m][m - 1].abs() * (q.abs() + r.abs());
                        let v = p.abs() * (a[m - 1][m - 1].abs() + z.abs() + a[m + 1][m + 1].abs());
                        if u <= f64::EPSILON * v {
                            break;
                        }
                        m -= 1;
                    }
                    for i in (m + 2)..=nu {
                        a[i][i - 2] = 0.0;
                        if i != m + 2 {
                            a[i][i - 3] = 0.0;
                        }
                    }
                    let mut k = m;
                    while k < nu {
                        if k != m {
                            p = a[k][k - 1];
                            q = a[k + 1][k - 1];
                            r = 0.0;
                            if k != nu - 1 {
                                r = a[k + 2][k - 1];
                            }
                            x = p.abs() + q.abs() + r.abs();
                            if x != 0.0 {
                                p /= x;
                                q /= x;
                                r /= x;
                            }
                        }
                        s = sign((p * p + q * q + r * r).sqrt(), p);
                        if s != 0.0 {
                            if k == m {
                                if l != m {
                                    a[k][k - 1] = -a[k][k - 1];
                                }
                            } else {
                                a[k][k - 1] = -s * x;
                            }
                            p += s;
                            x = p / s;
                            y = q / s;
                            z = r / s;
                            q /= p;
                            r /= p;
                            for j in k..=nu {
                                p = a[k][j] + q * a[k + 1][j];
                                if k != nu - 1 {
                                    p += r * a[k + 2][j];
                                    a[k + 2][j] -= p * z;
                                }
                                a[k + 1][j] -= p * y;
                                a[k][j] -= p * x;
                            }
                            let mmin = if nu < k + 3 { nu } else { k + 3 };
                            for i in l..=mmin {
                                p = x * a[i][k] + y * a[i][k + 1];
                                if k != nu - 1 {
                                    p += z * a[i][k + 2];
                                    a[i][k + 2] -= p * r;
                                }
                                a[i][k + 1] -= p * q;
                                a[i][k] -= p;
                            }
                        }
                        k += 1;
                    }
                }
            }
            if nn < 1 || l + 1 >= nn as usize {
                break;
            }
        }
    }
    Ok(false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::eigen::complex_solve;
    use nalgebra::DMatrix;

    /// SplitMix64, so failures reproduce.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn norm_inf(a: &[f64], n: usize) -> f64 {
        (0..n).map(|i| a[i * n..(i + 1) * n].iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max)
    }

    /// `min over v of ‖(A − λI) v‖ / ‖v‖` bounded from above by one step of inverse iteration:
    /// a backward error of λ as an eigenvalue of `A` (zero for an exact eigenvalue, whatever
    /// its condition number).
    fn residual(a: &[f64], n: usize, l: Complex64) -> f64 {
        // shifted by ε‖A‖ (adds at most that to the residual) so that an eigenvalue exact to the
        // last bit does not make the solve divide by zero
        let l = l + Complex64::new(f64::EPSILON * norm_inf(a, n), 0.0);
        let m: Vec<Vec<Complex64>> =
            (0..n).map(|i| (0..n).map(|j| Complex64::new(a[i * n + j], 0.0) - if i == j { l } else { Complex64::new(0.0, 0.0) }).collect()).collect();
        let mut v = vec![Complex64::new(1.0, 0.0); n];
        for _ in 0..2 {
            v = complex_solve(&m, &v);
            let s = v.iter().map(|z| z.norm()).fold(0.0, f64::max);
            v.iter_mut().for_each(|z| *z /= s);
        }
        let r = (0..n).map(|i| (0..n).map(|j| m[i][j] * v[j]).sum::<Complex64>().norm()).fold(0.0, f64::max);
        r / v.iter().map(|z| z.norm()).fold(0.0, f64::max)
    }

    /// nalgebra's eigenvalues (Schur form, no balancing), with its iteration limit.
    fn nalgebra_eigenvalues(a: &[f64], n: usize) -> Vec<Complex64> {
        let m = DMatrix::from_row_slice(n, n, a);
        let s = nalgebra::linalg::Schur::try_new(m, f64::EPSILON, 10_000).expect("nalgebra converges");
        s.complex_eigenvalues().iter().copied().collect()
    }

    /// Greatest distance from a member of `a` to the member of `b` paired with it (greedy
    /// matching, closest first): a multiset distance.
    fn match_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
        let mut used = vec![false; b.len()];
        let mut worst: f64 = 0.0;
        for x in a {
            let (k, d) = b.iter().enumerate().filter(|(k, _)| !used[*k]).map(|(k, y)| (k, (x - y).norm())).min_by(|p, q| p.1.total_cmp(&q.1)).unwrap();
            used[k] = true;
            worst = worst.max(d);
        }
        worst
    }

    #[test]
    fn a_stop_ends_the_solve_at_the_next_column_or_iteration_and_never_changes_an_answer() {
        // 120 x 120 random: the reduction asks once per column (118 times), the QR once per
        // iteration. A stop that says yes on its k-th question gives no eigenvalues, asked
        // exactly k times (it ends at once); one that never says yes gives eigenvalues()'s
        // answer bit for bit, having been asked at least once per column.
        let mut rng = Rng(7);
        let n = 120;
        let a: Vec<f64> = (0..n * n).map(|_| rng.next() * 2.0 - 1.0).collect();
        let plain = eigenvalues(&a, n).unwrap();
        let asked = std::cell::Cell::new(0usize);
        let never = eigenvalues_or_stop(&a, n, || {
            asked.set(asked.get() + 1);
            false
        })
        .unwrap()
        .unwrap();
        assert_eq!(never, plain);
        let total = asked.get();
        assert!(total >= n - 2 + n / 2, "asked {total} times");
        for k in [1, n / 2, n - 2, n - 1, total] {
            let asked = std::cell::Cell::new(0usize);
            let stopped = eigenvalues_or_stop(&a, n, || {
                asked.set(asked.get() + 1);
                asked.get() >= k
            })
            .unwrap();
            assert!(stopped.is_none(), "k = {k}");
            assert_eq!(asked.get(), k);
        }
    }

    #[test]
    fn random_matrices_of_every_size_agree_with_nalgebra_and_have_small_residuals() {
        // Each size 1..=40: a Gaussian-like random matrix A, and D A D⁻¹ with D spanning 1e6
        // (what physical units do). The eigenvalues of both must be eigenvalues of A to a
        // backward error of 20 n ε ‖A‖ (QR's backward error is a modest multiple of n ε ‖A‖; the
        // balancing is what keeps it relative to ‖A‖ rather than ‖D A D⁻¹‖ ~ 1e6 ‖A‖), and match
        // nalgebra's eigenvalues of the well-scaled A to 1e-7 ‖A‖ (a multiset check: eigenvalues
        // of random matrices have condition numbers up to ~1e3 here, the tolerance leaves room).
        let mut rng = Rng(42);
        for n in 1..=40 {
            for scaled in [false, true] {
                let a: Vec<f64> = (0..n * n).map(|_| rng.next() * 2.0 - 1.0).collect();
                let d: Vec<f64> = (0..n).map(|_| 10f64.powf(6.0 * rng.next() - 3.0)).collect();
                let b: Vec<f64> = if scaled { (0..n * n).map(|k| d[k / n] * a[k] / d[k % n]).collect() } else { a.clone() };
                let ours = eigenvalues(&b, n).unwrap();
                assert_eq!(ours.len(), n);
                let na = norm_inf(&a, n);
                for l in &ours {
                    let r = residual(&a, n, *l);
                    assert!(r <= 20.0 * n as f64 * f64::EPSILON * na, "n = {n}, scaled {scaled}: λ = {l}, residual {r:e} against ‖A‖ = {na}");
                }
                let theirs = nalgebra_eigenvalues(&a, n);
                let dist = match_distance(&ours, &theirs).max(match_distance(&theirs, &ours));
                assert!(dist <= 1e-7 * na, "n = {n}, scaled {scaled}: distance to nalgebra {dist:e}");
                // complex pairs are exact conjugates, and the real ones real
                for l in &ours {
                    if l.im != 0.0 {
                        assert!(ours.iter().any(|m| m.re == l.re && m.im == -l.im), "n = {n}: {l} without its conjugate");
                    }
                }
            }
        }
    }

    #[test]
    fn balancing_is_what_makes_badly_scaled_matrices_accurate() {
        // The experiment of DEPENDENCIES.md: nalgebra without balancing on D A D⁻¹ (D spanning
        // 1e6) loses accuracy that our balanced route keeps; a test that the balancing matters
        // here, so that it cannot silently be dropped.
        let mut rng = Rng(3);
        let n = 20;
        let mut worst_theirs: f64 = 0.0;
        let mut worst_ours: f64 = 0.0;
        for _ in 0..5 {
            let a: Vec<f64> = (0..n * n).map(|_| rng.next() * 2.0 - 1.0).collect();
            let d: Vec<f64> = (0..n).map(|i| 10f64.powf(-3.0 + 6.0 * i as f64 / (n - 1) as f64)).collect();
            let b: Vec<f64> = (0..n * n).map(|k| d[k / n] * a[k] / d[k % n]).collect();
            let na = norm_inf(&a, n);
            for l in nalgebra_eigenvalues(&b, n) {
                worst_theirs = worst_theirs.max(residual(&a, n, l) / na);
            }
            for l in eigenvalues(&b, n).unwrap() {
                worst_ours = worst_ours.max(residual(&a, n, l) / na);
            }
        }
        assert!(worst_ours < 1e-13, "ours {worst_ours:e}");
        assert!(worst_theirs > 1e3 * worst_ours, "nalgebra unbalanced {worst_theirs:e}, ours {worst_ours:e}");
    }

    #[test]
    fn known_spectra_and_bad_input() {
        // a companion matrix of (λ − 1)(λ − 2)…(λ − 6): exact integer eigenvalues
        let c = [720.0, -1764.0, 1624.0, -735.0, 175.0, -21.0];
        let n = 6;
        let mut a = vec![0.0; n * n];
        for i in 1..n {
            a[i * n + i - 1] = 1.0;
        }
        for i in 0..n {
            a[i * n + n - 1] = -c[i];
        }
        let mut l: Vec<f64> = eigenvalues(&a, n).unwrap().iter().map(|z| z.re).collect();
        l.sort_by(f64::total_cmp);
        for (k, x) in l.iter().enumerate() {
            assert!((x - (k + 1) as f64).abs() < 1e-9, "{l:?}");
        }
        // a rotation generator: ±i exactly
        let l = eigenvalues(&[0.0, -1.0, 1.0, 0.0], 2).unwrap();
        assert!(l.iter().all(|z| z.re.abs() < 1e-15 && (z.im.abs() - 1.0).abs() < 1e-15), "{l:?}");
        assert_eq!(eigenvalues(&[], 0).unwrap(), vec![]);
        assert_eq!(eigenvalues(&[3.5], 1).unwrap(), vec![Complex64::new(3.5, 0.0)]);
        assert!(eigenvalues(&[f64::NAN, 0.0, 0.0, 1.0], 2).is_err());
        assert_eq!(spectral_abscissa(&[0.0, 1.0, -1.0, -0.2], 2).unwrap(), -0.1);
    }
}
