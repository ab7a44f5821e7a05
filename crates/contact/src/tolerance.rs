//! The one tolerance helper used by the tests, benches and verification reports of the flexrig
//! crates: relative errors against a reference, with a floor for references near zero.

/// Relative error |value − reference| / max(|reference|, floor).
pub fn relative_error(value: f64, reference: f64, floor: f64) -> f64 {
    (value - reference).abs() / reference.abs().max(floor)
}

/// Panics with a readable message unless `value` is within `rel_tol` (relative, with a floor of
/// `f64::MIN_POSITIVE` on |reference|) of `reference`. Non-finite values always fail.
#[track_caller]
pub fn assert_close(what: &str, value: f64, reference: f64, rel_tol: f64) {
    let err = relative_error(value, reference, f64::MIN_POSITIVE);
    assert!(
        value.is_finite() && err <= rel_tol,
        "{what}: value {value:.17e}, reference {reference:.17e}, relative error {err:.3e} > \
         tolerance {rel_tol:.1e}"
    );
}

/// Panics unless |value − reference| ≤ abs_tol.
#[track_caller]
pub fn assert_abs(what: &str, value: f64, reference: f64, abs_tol: f64) {
    let err = (value - reference).abs();
    assert!(
        value.is_finite() && err <= abs_tol,
        "{what}: value {value:.17e}, reference {reference:.17e}, absolute error {err:.3e} > \
         tolerance {abs_tol:.1e}"
    );
}

/// Central finite difference of `f` at `x` with relative step `h_rel`.
pub fn central_difference(f: impl Fn(f64) -> f64, x: f64, h_rel: f64) -> f64 {
    let h = h_rel * x.abs().max(f64::MIN_POSITIVE);
    (f(x + h) - f(x - h)) / (2.0 * h)
}
