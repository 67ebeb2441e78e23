//! Optimal assignment (the Hungarian method): shared machinery, no model.

/// Optimal assignment of the `n×n` cost matrix `cost(row, column)` (finite): `out[row]` the
/// column, the assignment minimising the summed cost (the Hungarian method with potentials,
/// O(n³): Kuhn–Munkres with row and column potentials, shortest augmenting paths).
/// The Campbell diagrams' line tracking (`crate::rotor_campbell`, `crate::spatial::stability`).
///
/// ```
/// use autobal::linalg::assignment::assignment;
/// let c = [[4.0, 1.0, 3.0], [2.0, 0.0, 5.0], [3.0, 2.0, 2.0]];
/// assert_eq!(assignment(|r, k| c[r][k], 3), vec![1, 0, 2]); // 1 + 2 + 2
/// ```
pub fn assignment(cost: impl Fn(usize, usize) -> f64, n: usize) -> Vec<usize> {
    let inf = f64::INFINITY;
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; n + 1];
    let mut p = vec![0usize; n + 1]; // p[j]: row matched to column j (1-based, 0 = none)
    let mut way = vec![0usize; n + 1];
    for i in 1..=n {
        p[0] = i;
        let mut j0 = 0;
        let mut minv = vec![inf; n + 1];
        let mut used = vec![false; n + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = inf;
            let mut j1 = 0;
            for j in 1..=n {
                if !used[j] {
                    let cur = cost(i0 - 1, j - 1) - u[i0] - v[j];
                    if cur < minv[j] {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=n {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if p[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut out = vec![0usize; n];
    for j in 1..=n {
        if p[j] > 0 {
            out[p[j] - 1] = j - 1;
        }
    }
    out
}
