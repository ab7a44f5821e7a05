//! Parameter checks shared by every constructor in the flexrig crates that build on contact.
//! Each returns the value when it is allowed, or an error naming the field, the value and the
//! allowed range.

use crate::ContactError;

/// A number as an error message should quote it: plain for ordinary magnitudes, in exponent
/// form for very small or large ones (1e-300 must not print as 300 digits).
///
/// This is the one formatter of numbers in messages: the shortest text that reads back to the
/// value when that is short (what a user typed comes back as typed), else rounded to 6
/// significant digits (a derived 22.297073617089197 reads 22.2971).
pub fn display(value: f64) -> String {
    let a = value.abs();
    let exact = if a != 0.0 && a.is_finite() && !(1e-4..1e6).contains(&a) {
        format!("{value:e}")
    } else {
        format!("{value}")
    };
    if exact.len() <= 12 {
        return exact;
    }
    let rounded: f64 = format!("{value:.5e}").parse().unwrap_or(value);
    let a = rounded.abs();
    if a != 0.0 && !(1e-4..1e6).contains(&a) {
        format!("{rounded:e}")
    } else {
        format!("{rounded}")
    }
}

/// A power of ten `v` as `10` with its exponent in superscript digits, e.g. `10⁻⁵`.
pub fn decade_label(v: f64) -> String {
    let exponent = v.log10().round() as i64;
    let digits: String = exponent
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect();
    format!("10{digits}")
}

/// A number `v` as a reader writes it in a label: `10ᵏ` or `m·10ᵏ` (mantissa to 6 significant
/// digits), e.g. `10⁸`, `2·10²`.
pub fn sci_label(v: f64) -> String {
    let decade = 10f64.powf(v.log10().floor());
    let mantissa = v / decade;
    if (mantissa - 1.0).abs() < 1e-9 {
        decade_label(decade)
    } else {
        format!(
            "{}·{}",
            (mantissa * 1e5).round() / 1e5,
            decade_label(decade)
        )
    }
}

/// The unit of a field, read from the suffix of its name (`payload_kg` → "kg",
/// `youngs_modulus_pa` → "Pa"); empty when the name carries none.
pub fn unit_of(field: &str) -> &'static str {
    // longest suffixes first: `_kg_m3` before `_m3`, `_nm_per_rad` before `_rad`
    const UNITS: &[(&str, &str)] = &[
        ("_kg_m3", "kg/m³"),
        ("_nm_per_rad", "N·m/rad"),
        ("_n_per_m", "N/m"),
        ("_rad_s", "rad/s"),
        ("_mps2", "m/s²"),
        ("_mps", "m/s"),
        ("_kg_m2", "kg·m²"),
        ("_kg", "kg"),
        ("_pa", "Pa"),
        ("_deg", "°"),
        ("_hz", "Hz"),
        ("_rad", "rad"),
        ("_s", "s"),
        ("_m", "m"),
        ("_n", "N"),
        ("_j", "J"),
    ];
    let name = field.rsplit('.').next().unwrap_or(field);
    let name = name.split('[').next().unwrap_or(name);
    UNITS
        .iter()
        .find(|(suffix, _)| name.ends_with(suffix))
        .map_or("", |(_, unit)| unit)
}

/// "must lie in [lo, hi] unit" with the bounds as [`display`] writes them (no `0e0`).
pub fn interval(field: &str, lo: f64, hi: f64) -> String {
    interval_in(unit_of(field), lo, hi)
}

/// "must lie in [lo, hi] unit" for a quantity in `unit` ("" for none), the bounds as
/// [`display`] writes them.
pub fn interval_in(unit: &str, lo: f64, hi: f64) -> String {
    let unit = match unit {
        "" => String::new(),
        "°" => " degrees".to_string(),
        u => format!(" {u}"),
    };
    format!("must lie in [{}, {}]{unit}", display(lo), display(hi))
}

/// A hint for a value that looks given in the wrong unit: a length in millimetres where metres
/// are asked for (its thousandth lies in the range), a mass in grams, an angle in degrees
/// where radians are asked for, or the reverse. Empty when none fits.
pub fn unit_hint(field: &str, value: f64, lo: f64, hi: f64) -> String {
    unit_hint_in(unit_of(field), value, lo, hi)
}

/// [`unit_hint`] for a quantity in `unit` (m, kg, Pa; empty for the others).
pub fn unit_hint_in(unit: &str, value: f64, lo: f64, hi: f64) -> String {
    let fits = |x: f64| x.is_finite() && (lo..=hi).contains(&x);
    match unit {
        "m" if fits(value / 1000.0) => format!(
            " (did you give millimetres? {} mm is {} m)",
            display(value),
            display(value / 1000.0)
        ),
        "kg" if fits(value / 1000.0) => format!(
            " (did you give grams? {} g is {} kg)",
            display(value),
            display(value / 1000.0)
        ),
        "Pa" if fits(value * 1e9) => format!(
            " (did you give GPa? {} GPa is {} Pa)",
            display(value),
            display(value * 1e9)
        ),
        "Pa" if fits(value * 1e6) => format!(
            " (did you give MPa? {} MPa is {} Pa)",
            display(value),
            display(value * 1e6)
        ),
        _ => String::new(),
    }
}

/// "must lie in [lo, hi] unit", with a unit hint when the value looks given in another unit.
pub fn interval_with_hint(field: &str, value: f64, lo: f64, hi: f64) -> String {
    format!(
        "{}{}",
        interval(field, lo, hi),
        unit_hint(field, value, lo, hi)
    )
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

    #[test]
    fn intervals_carry_the_unit_and_plain_bounds() {
        assert_eq!(
            interval("robot.payload_kg", 0.0, 1e4),
            "must lie in [0, 10000] kg"
        );
        assert_eq!(
            interval("robot.youngs_modulus_pa", 1e5, 1.2e12),
            "must lie in [100000, 1.2e12] Pa"
        );
        assert_eq!(
            interval("operator.start.release_angle_deg", 0.0, 170.0),
            "must lie in [0, 170] degrees"
        );
        assert_eq!(
            interval("density_kg_m3", 1.0, 1e5),
            "must lie in [1, 100000] kg/m³"
        );
        assert_eq!(interval("gamma", 0.0, 1.0), "must lie in [0, 1]");
        assert_eq!(unit_of("m_h[3]"), "");
        assert_eq!(unit_of("solver.swing_step_s"), "s");
    }

    #[test]
    fn a_length_in_millimetres_gets_a_hint() {
        let hint = interval_with_hint("robot.length_m", 338.0, 0.01, 10.0);
        assert!(
            hint.contains("did you give millimetres? 338 mm is 0.338 m"),
            "{hint}"
        );
        assert!(unit_hint("robot.length_m", 20.0, 0.01, 10.0).contains("millimetres"));
        assert_eq!(unit_hint("robot.length_m", 1e9, 0.01, 10.0), "");
        assert!(unit_hint("robot.youngs_modulus_pa", 1.5, 1e5, 1.2e12).contains("GPa"));
        assert!(unit_hint("robot.payload_kg", 412.0, 0.0, 100.0).contains("grams"));
    }
}
