//! The one tolerance helper of the beam tests.
#![allow(dead_code)]

/// Asserts |got/want − 1| ≤ rel, naming `what`.
#[track_caller]
pub fn assert_rel(what: &str, got: f64, want: f64, rel: f64) {
    let e = (got / want - 1.0).abs();
    assert!(
        e <= rel,
        "{what}: got {got:.12e}, reference {want:.12e}, relative error {e:.3e} > {rel:.1e}"
    );
}

/// Observed convergence order from errors at h and h/2.
pub fn order(e_coarse: f64, e_fine: f64) -> f64 {
    (e_coarse.abs() / e_fine.abs()).log2()
}
