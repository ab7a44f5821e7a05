//! Least-squares fit of the Hertz law f = k δ^n to compression-test data (paper §III-B, Fig. 4).
//!
//! The residuals are taken in force, r_i = f_i − k δ_i^n (the load cell's noise is additive in
//! force), and minimised over p = (ln k, n) by Levenberg–Marquardt, started from the straight
//! line through the data in log–log axes. Standard errors come from the covariance
//! σ² (JᵀJ)⁻¹ with σ² = SSR/(m − 2) at the optimum; the error of k is k·σ(ln k) (first order).

use serde::Serialize;

use crate::{ContactError, Hertz};

/// One compression-test sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompressionPoint {
    /// Indentation δ \[m\].
    pub indentation_m: f64,
    /// Force f \[N\].
    pub force_n: f64,
}

/// The expected CSV header.
pub const CSV_HEADER: &str = "indentation_m,force_n";

/// Parses compression data: an optional header `indentation_m,force_n`, then one
/// `indentation_m,force_n` pair of finite numbers per line. Blank lines and lines starting with
/// `#` are skipped. Errors name the 1-based line.
pub fn parse_compression_csv(text: &str) -> Result<Vec<CompressionPoint>, ContactError> {
    // a byte-order mark (spreadsheets write one) is not part of the header
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut points = Vec::new();
    let mut seen_content = false;
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let first_content = !seen_content;
        seen_content = true;
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let csv_error = |reason: String| ContactError::Csv {
            line: line_no,
            content: line.to_string(),
            reason,
        };
        if first_content && fields.iter().any(|f| f.parse::<f64>().is_err()) {
            if fields.join(",") == CSV_HEADER {
                continue;
            }
            return Err(csv_error(format!(
                "expected the header {CSV_HEADER:?} or two numbers"
            )));
        }
        if fields.len() != 2 {
            return Err(csv_error(format!(
                "expected 2 comma-separated numbers ({CSV_HEADER}), found {} fields",
                fields.len()
            )));
        }
        let number = |text: &str, name: &str| -> Result<f64, ContactError> {
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(csv_error(format!("{name} must be a finite number"))),
            }
        };
        let force_n = number(fields[1], "force_n")?;
        if force_n < 0.0 {
            return Err(csv_error(format!(
                "force_n = {} must be >= 0 (a compression force; the contact does not pull)",
                crate::validate::display(force_n)
            )));
        }
        points.push(CompressionPoint {
            indentation_m: number(fields[0], "indentation_m")?,
            force_n,
        });
    }
    Ok(points)
}

/// Result of a Hertz fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HertzFit {
    /// Fitted stiffness k [N/m^n].
    pub k: f64,
    /// Fitted exponent n [-].
    pub n: f64,
    /// Coefficient of determination R² = 1 − SSR/SST.
    pub r2: f64,
    /// Standard error of k [N/m^n].
    pub k_stderr: f64,
    /// Standard error of n [-].
    pub n_stderr: f64,
    /// Root-mean-square residual \[N\].
    pub rms_residual_n: f64,
    /// Points used (indentation > 0).
    pub points: usize,
    /// Points skipped (indentation ≤ 0: not in contact).
    pub skipped: usize,
    /// Levenberg–Marquardt iterations.
    pub iterations: usize,
}

impl HertzFit {
    /// The fitted law.
    pub fn hertz(&self) -> Result<Hertz, ContactError> {
        Hertz::new(self.k, self.n)
    }
}

const MAX_LM_ITERATIONS: usize = 200;

/// Fits f = k δ^n to `points` (those with δ > 0; at least 3, with at least 2 distinct δ).
pub fn fit_hertz(points: &[CompressionPoint]) -> Result<HertzFit, ContactError> {
    // Fit in units of the largest indentation D and the largest force F, so that data of any
    // magnitude (1e-300 … 1e300) neither under- nor overflows in the sums of squares; then
    // k = k' F / D^n, with the same relative standard error.
    let scale_d = points
        .iter()
        .filter(|p| p.indentation_m > 0.0)
        .fold(0.0f64, |m, p| m.max(p.indentation_m));
    let scale_f = points.iter().fold(0.0f64, |m, p| m.max(p.force_n.abs()));
    if !(scale_d > 0.0 && scale_f > 0.0) {
        return fit_scaled(points);
    }
    let scaled: Vec<CompressionPoint> = points
        .iter()
        .map(|p| CompressionPoint {
            indentation_m: p.indentation_m / scale_d,
            force_n: p.force_n / scale_f,
        })
        .collect();
    let f = fit_scaled(&scaled)?;
    // ln k = ln k' + ln F − n ln D (in logarithms, so that an intermediate D^n does not
    // overflow); its variance takes the covariance of (ln k', n): with L = ln D,
    // var ln k = var ln k' + L² var n − 2 L cov(ln k', n).
    let l = scale_d.ln();
    let ln_k = f.k.ln() + scale_f.ln() - f.n * l;
    let used: Vec<CompressionPoint> = scaled
        .iter()
        .copied()
        .filter(|p| p.indentation_m > 0.0)
        .collect();
    let m = used.len() as f64;
    let (jtj, _) = normal_equations(&used, [f.k.ln(), f.n]);
    let det = jtj[0][0] * jtj[1][1] - jtj[0][1] * jtj[1][0];
    let sigma2 = f.rms_residual_n.powi(2) * m / (m - 2.0);
    let var_ln_k = if m > 2.0 && det > 0.0 {
        let (var_a, var_n, cov) = (
            sigma2 * jtj[1][1] / det,
            sigma2 * jtj[0][0] / det,
            -sigma2 * jtj[0][1] / det,
        );
        (var_a + l * l * var_n - 2.0 * l * cov).max(0.0)
    } else {
        f64::INFINITY
    };
    let k = ln_k.exp();
    let fit = HertzFit {
        k,
        k_stderr: k * var_ln_k.sqrt(),
        rms_residual_n: f.rms_residual_n * scale_f,
        ..f
    };
    if !(fit.k.is_finite() && fit.k > 0.0 && fit.k_stderr.is_finite()) {
        return Err(ContactError::FitDidNotConverge {
            iterations: fit.iterations,
            reason: format!(
                "the fitted k = {} N/mⁿ (n = {}) is not representable in double precision: \
                 give the data in other units (e.g. mm and kN)",
                crate::validate::display(fit.k),
                fit.n
            ),
        });
    }
    if !(fit.n_stderr.is_finite() && fit.rms_residual_n.is_finite()) {
        return Err(ContactError::FitDidNotConverge {
            iterations: fit.iterations,
            reason: "the standard errors are not finite (too few independent points?)".into(),
        });
    }
    Ok(fit)
}

/// The Levenberg–Marquardt fit on data of moderate magnitude.
fn fit_scaled(points: &[CompressionPoint]) -> Result<HertzFit, ContactError> {
    let used: Vec<CompressionPoint> = points
        .iter()
        .copied()
        .filter(|p| p.indentation_m > 0.0)
        .collect();
    let skipped = points.len() - used.len();
    let needed = "at least 3 points with indentation_m > 0 and 2 distinct indentations";
    let distinct = used
        .iter()
        .any(|p| p.indentation_m != used[0].indentation_m);
    if used.len() < 3 || !distinct {
        return Err(ContactError::NotEnoughData {
            found: used.len(),
            needed: needed.into(),
        });
    }
    let mut p = log_log_start(&used).ok_or_else(|| ContactError::NotEnoughData {
        found: used.iter().filter(|p| p.force_n > 0.0).count(),
        needed: "at least 2 points with indentation_m > 0 and force_n > 0, at 2 distinct \
                 indentations, to start the fit"
            .into(),
    })?;
    let mut ssr = sum_sq(&used, p);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    loop {
        iterations += 1;
        if iterations > MAX_LM_ITERATIONS {
            return Err(ContactError::FitDidNotConverge {
                iterations: MAX_LM_ITERATIONS,
                reason: format!("sum of squared residuals still changing at {ssr:e} N²"),
            });
        }
        let (jtj, jtr) = normal_equations(&used, p);
        let mut accepted = false;
        while lambda < 1e16 {
            let a = [
                [jtj[0][0] * (1.0 + lambda), jtj[0][1]],
                [jtj[1][0], jtj[1][1] * (1.0 + lambda)],
            ];
            let Some(step) = solve2(a, [-jtr[0], -jtr[1]]) else {
                lambda *= 10.0;
                continue;
            };
            let trial = [p[0] + step[0], p[1] + step[1]];
            let trial_ssr = sum_sq(&used, trial);
            if trial_ssr.is_finite() && trial_ssr <= ssr {
                let small_step = step[0].abs() < 1e-13 * p[0].abs().max(1.0)
                    && step[1].abs() < 1e-13 * p[1].abs().max(1.0);
                let small_gain = ssr - trial_ssr <= 1e-15 * ssr;
                p = trial;
                ssr = trial_ssr;
                lambda = (lambda / 10.0).max(1e-12);
                accepted = true;
                if small_step || small_gain {
                    return finish(&used, p, ssr, skipped, iterations);
                }
                break;
            }
            lambda *= 10.0;
        }
        if !accepted {
            // No descent direction left at machine precision: p is the minimum.
            return finish(&used, p, ssr, skipped, iterations);
        }
    }
}

fn model(p: [f64; 2], delta: f64) -> f64 {
    (p[0] + p[1] * delta.ln()).exp()
}

fn sum_sq(points: &[CompressionPoint], p: [f64; 2]) -> f64 {
    points
        .iter()
        .map(|q| (q.force_n - model(p, q.indentation_m)).powi(2))
        .sum()
}

/// JᵀJ and Jᵀr for r_i = f_i − k δ_i^n over p = (ln k, n).
fn normal_equations(points: &[CompressionPoint], p: [f64; 2]) -> ([[f64; 2]; 2], [f64; 2]) {
    let mut jtj = [[0.0; 2]; 2];
    let mut jtr = [0.0; 2];
    for q in points {
        let f = model(p, q.indentation_m);
        let j = [-f, -f * q.indentation_m.ln()];
        let r = q.force_n - f;
        for a in 0..2 {
            jtr[a] += j[a] * r;
            for b in 0..2 {
                jtj[a][b] += j[a] * j[b];
            }
        }
    }
    (jtj, jtr)
}

fn solve2(a: [[f64; 2]; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let scale = a[0][0].abs() * a[1][1].abs() + a[0][1].abs() * a[1][0].abs();
    if !(det.abs() > 1e-14 * scale) {
        return None;
    }
    Some([
        (b[0] * a[1][1] - a[0][1] * b[1]) / det,
        (a[0][0] * b[1] - a[1][0] * b[0]) / det,
    ])
}

/// Straight-line fit of ln f against ln δ over the points with f > 0.
fn log_log_start(points: &[CompressionPoint]) -> Option<[f64; 2]> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|q| q.force_n > 0.0)
        .map(|q| (q.indentation_m.ln(), q.force_n.ln()))
        .collect();
    let m = xy.len() as f64;
    if xy.len() < 2 {
        return None;
    }
    let mx = xy.iter().map(|v| v.0).sum::<f64>() / m;
    let my = xy.iter().map(|v| v.1).sum::<f64>() / m;
    let sxx: f64 = xy.iter().map(|v| (v.0 - mx).powi(2)).sum();
    let sxy: f64 = xy.iter().map(|v| (v.0 - mx) * (v.1 - my)).sum();
    if !(sxx > 0.0) {
        return None;
    }
    let n = sxy / sxx;
    Some([my - n * mx, n])
}

fn finish(
    points: &[CompressionPoint],
    p: [f64; 2],
    ssr: f64,
    skipped: usize,
    iterations: usize,
) -> Result<HertzFit, ContactError> {
    let m = points.len();
    let mean = points.iter().map(|q| q.force_n).sum::<f64>() / m as f64;
    let sst: f64 = points.iter().map(|q| (q.force_n - mean).powi(2)).sum();
    let (jtj, _) = normal_equations(points, p);
    let sigma2 = ssr / (m as f64 - 2.0);
    let det = jtj[0][0] * jtj[1][1] - jtj[0][1] * jtj[1][0];
    let (var_lnk, var_n) = if m > 2 && det > 0.0 {
        (sigma2 * jtj[1][1] / det, sigma2 * jtj[0][0] / det)
    } else {
        (f64::INFINITY, f64::INFINITY)
    };
    let k = p[0].exp();
    let fit = HertzFit {
        k,
        n: p[1],
        r2: if sst > 0.0 { 1.0 - ssr / sst } else { 1.0 },
        k_stderr: k * var_lnk.sqrt(),
        n_stderr: var_n.sqrt(),
        rms_residual_n: (ssr / m as f64).sqrt(),
        points: m,
        skipped,
        iterations,
    };
    if !(fit.k.is_finite() && fit.k > 0.0 && fit.n.is_finite() && fit.n > 0.0) {
        return Err(ContactError::FitDidNotConverge {
            iterations,
            reason: format!(
                "the data do not fit f = k δ^n with k > 0, n > 0 (got k = {:e}, n = {})",
                fit.k, fit.n
            ),
        });
    }
    Ok(fit)
}

#[cfg(test)]
mod bom_tests {
    use super::parse_compression_csv;

    #[test]
    fn a_byte_order_mark_before_the_header_is_skipped() {
        // Regression: a spreadsheet's CSV (with a byte-order mark) was refused, quoting
        // "\u{feff}indentation_m,force_n"
        let plain = "indentation_m,force_n\n0.001,10\n0.002,40\n";
        let marked = format!("\u{feff}{plain}");
        assert_eq!(
            parse_compression_csv(&marked).unwrap(),
            parse_compression_csv(plain).unwrap()
        );
    }
}
