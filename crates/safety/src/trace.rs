//! Checks shared by the functions over sampled traces: equal lengths, finite samples, strictly
//! increasing times.

use crate::SafetyError;

fn invalid(trace: &str, reason: String) -> SafetyError {
    SafetyError::InvalidTrace {
        trace: trace.to_string(),
        reason,
    }
}

/// `values` must be non-empty and finite.
pub(crate) fn check_values(trace: &str, values: &[f64]) -> Result<(), SafetyError> {
    if values.is_empty() {
        return Err(invalid(
            trace,
            "is empty: at least one sample is needed".into(),
        ));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(invalid(
            trace,
            format!("sample {i} is {}: every sample must be finite", values[i]),
        ));
    }
    Ok(())
}

/// `times` [s] and `values` must have equal lengths ≥ 2, finite samples and strictly increasing
/// times.
pub(crate) fn check_series(trace: &str, times: &[f64], values: &[f64]) -> Result<(), SafetyError> {
    if times.len() != values.len() {
        return Err(invalid(
            trace,
            format!(
                "has {} samples but the time trace has {}: they must have the same length",
                values.len(),
                times.len()
            ),
        ));
    }
    if times.len() < 2 {
        return Err(invalid(
            trace,
            format!("has {} samples: at least two are needed", times.len()),
        ));
    }
    check_values("time", times)?;
    check_values(trace, values)?;
    if let Some(i) = times.windows(2).position(|w| !(w[1] > w[0])) {
        return Err(invalid(
            "time",
            format!(
                "sample {} ({} s) is not after sample {i} ({} s): times must increase strictly",
                i + 1,
                times[i + 1],
                times[i]
            ),
        ));
    }
    Ok(())
}

/// Two traces sampled together must have equal lengths.
pub(crate) fn check_paired(
    a_name: &str,
    a: &[f64],
    b_name: &str,
    b: &[f64],
) -> Result<(), SafetyError> {
    check_values(a_name, a)?;
    check_values(b_name, b)?;
    if a.len() != b.len() {
        return Err(invalid(
            b_name,
            format!(
                "has {} samples but {a_name} has {}: they must have the same length",
                b.len(),
                a.len()
            ),
        ));
    }
    Ok(())
}
