//! Helpers shared by this crate's unit tests.

/// Asserts `|actual − expected| ≤ tol` (in the quantity's own units), and
/// names the quantity `what` with both values to 17 digits when it fails.
pub(crate) fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
    let err = (actual - expected).abs();
    assert!(
        err <= tol,
        "{what}: got {actual:.17e}, expected {expected:.17e}, |error| {err:.3e} > tol {tol:.3e}"
    );
}
