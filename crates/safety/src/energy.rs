//! Transferred energy and peak force over sampled contacts.
//!
//! The kinetic energy of the relative motion, ½ μ v² (ISO/TS 15066:2016 Eq. A.2; the paper's
//! energy balance behind Eq. 13), is what an undamped contact stores at maximum compression; the
//! work of the contact force over the indentation, ∫ f dδ, is the same energy measured from a
//! force–indentation trace. The standard's energy limit of a body region is F²/(2k) (Eq. A.1).

use crate::SafetyError;
use crate::trace::{check_paired, check_values};

/// Kinetic energy of the relative motion ½ μ v² \[J\]; `reduced_mass` \[kg\] > 0, `speed` [m/s].
pub fn relative_kinetic_energy(reduced_mass: f64, speed: f64) -> Result<f64, SafetyError> {
    let mu = flexrig_contact::validate::positive("reduced_mass", reduced_mass)?;
    let v = flexrig_contact::validate::finite("speed", speed)?;
    Ok(0.5 * mu * v * v)
}

/// The energy a linear body spring k [N/m] stores at force F \[N\]: F²/(2k) \[J\]
/// (ISO/TS 15066:2016 Eq. A.1).
pub fn spring_energy_at_force(force: f64, spring_constant: f64) -> Result<f64, SafetyError> {
    let f = flexrig_contact::validate::non_negative("force", force)?;
    let k = flexrig_contact::validate::positive("spring_constant", spring_constant)?;
    Ok(0.5 * f * f / k)
}

/// Work of the contact force over the indentation up to the largest indentation,
/// W = ∫₀^{δ_max} f dδ \[J\], by the trapezoidal rule over the loading samples: from the start of
/// the contact that reaches the largest indentation (the last sample before it without
/// indentation, δ ≤ 0; the first sample if none) to the first sample of largest indentation.
/// `force` \[N\] and `indentation` \[m\] are sampled together.
pub fn loading_work(force: &[f64], indentation: &[f64]) -> Result<f64, SafetyError> {
    check_paired("force", force, "indentation", indentation)?;
    let peak = indentation.iter().enumerate().fold(
        0,
        |best, (i, &d)| if d > indentation[best] { i } else { best },
    );
    let start = indentation[..=peak]
        .iter()
        .rposition(|&d| d <= 0.0)
        .unwrap_or(0);
    let work = (start + 1..=peak)
        .map(|i| 0.5 * (force[i] + force[i - 1]) * (indentation[i] - indentation[i - 1]))
        .sum();
    Ok(work)
}

/// The largest value of a force trace \[N\] and its sample index.
pub fn peak_force(force: &[f64]) -> Result<(f64, usize), SafetyError> {
    check_values("force", force)?;
    Ok(force.iter().enumerate().fold(
        (force[0], 0),
        |best, (i, &f)| if f > best.0 { (f, i) } else { best },
    ))
}
