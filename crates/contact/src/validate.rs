//! Parameter checks shared by every constructor in the flexrig crates that build on contact.
//! Each returns the value when it is allowed, or an error naming the field, the value and the
//! allowed range.

use crate::ContactError;

/// A number as an error message should quote it: plain for ordinary magnitudes, in exponent
/// form for very small or large ones (1e-300 must not print as 300 digits).
pub fn display(value: f64) -> String {
    let a = value.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e6).contains(&a) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

fn invalid(field: &str, value: f64, allowed: &str) -> ContactError {
    ContactError::InvalidParameter {
        field: field.to_string(),
        value: display(value),
        allowed: allowed.to_string(),
    }
}

/// `value` must be finite.
pub fn finite(field: &str, value: f64) -> Result<f64, ContactError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(invalid(field, value, "must be a finite number"))
    }
}

/// `value` must be finite and > 0.
pub fn positive(field: &str, value: f64) -> Result<f64, ContactError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(field, value, "must be a finite number > 0"))
    }
}

/// `value` must be finite and ≥ 0.
pub fn non_negative(field: &str, value: f64) -> Result<f64, ContactError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(invalid(field, value, "must be a finite number >= 0"))
    }
}

/// `value` must lie in the closed interval `[lo, hi]`.
pub fn in_closed(field: &str, value: f64, lo: f64, hi: f64) -> Result<f64, ContactError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(field, value, &format!("must lie in [{lo}, {hi}]")))
    }
}

/// `value` must lie in the half-open interval `(lo, hi]`.
pub fn in_left_open(field: &str, value: f64, lo: f64, hi: f64) -> Result<f64, ContactError> {
    if value.is_finite() && value > lo && value <= hi {
        Ok(value)
    } else {
        Err(invalid(field, value, &format!("must lie in ({lo}, {hi}]")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_field_value_and_range() {
        let e = positive("k_c", -1.0).unwrap_err().to_string();
        assert!(
            e.contains("k_c") && e.contains("-1") && e.contains("> 0"),
            "{e}"
        );
        let e = in_left_open("gamma", 1.5, 0.0, 1.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("gamma") && e.contains("1.5") && e.contains("(0, 1]"),
            "{e}"
        );
        assert!(positive("m", f64::NAN).is_err());
        assert!(non_negative("c", f64::INFINITY).is_err());
        assert!(finite("x", f64::NEG_INFINITY).is_err());
        assert_eq!(in_closed("e", 0.0, 0.0, 1.0), Ok(0.0));
        assert_eq!(non_negative("c", 0.0), Ok(0.0));
    }
}
