//! Matrix Market's array format with symmetric or skew-symmetric storage (the lower triangle,
//! without the diagonal where skew, column by column: the NIST format's definition), as SciPy's
//! `scipy.io.mmwrite` writes a dense symmetric `M`, `K` or a skew `G` (issue 19: a config naming
//! files a Python user wrote). The texts below are SciPy 1.17's output, byte for byte, of the
//! matrices asserted; the numbers are exact in decimal, so equality is exact.

use autobal::linear_rotor::config::parse_matrix_market;

#[test]
fn scipy_symmetric_array_reads_as_the_full_matrix() {
    let text = "%%MatrixMarket matrix array real symmetric\n%\n3 3\n4\n-1.5\n2.5E-1\n2\n0\n1\n";
    let (r, c, a) = parse_matrix_market(text).unwrap();
    assert_eq!((r, c), (3, 3));
    assert_eq!(a, vec![4.0, -1.5, 0.25, -1.5, 2.0, 0.0, 0.25, 0.0, 1.0]);
}

#[test]
fn scipy_skew_symmetric_array_reads_as_the_full_matrix() {
    let text = "%%MatrixMarket matrix array real skew-symmetric\n%\n3 3\n-5E-1\n0\n-2\n";
    let (_, _, a) = parse_matrix_market(text).unwrap();
    assert_eq!(a, vec![0.0, 0.5, 0.0, -0.5, 0.0, 2.0, 0.0, -2.0, 0.0]);
}

#[test]
fn symmetric_array_counts_and_shape_are_checked() {
    // a full 2 × 2 written under a symmetric header: one entry too many
    let e = parse_matrix_market("%%MatrixMarket matrix array real symmetric\n2 2\n1\n2\n3\n4\n").unwrap_err();
    assert!(e.contains("more entries than the 3 the size line announces"), "{e}");
    let e = parse_matrix_market("%%MatrixMarket matrix array real symmetric\n2 3\n1\n2\n3\n").unwrap_err();
    assert!(e.contains("must be square, got 2 × 3"), "{e}");
    // the general array format is unchanged: column-major, every entry
    let (_, _, a) = parse_matrix_market("%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n").unwrap();
    assert_eq!(a, vec![1.0, 3.0, 2.0, 4.0]);
}
