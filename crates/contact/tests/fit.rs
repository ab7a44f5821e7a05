//! Hertz fits from compression data: exact recovery, honest standard errors on noisy data, and
//! clear errors for malformed files.

use flexrig_contact::tolerance::assert_close;
use flexrig_contact::{CompressionPoint, ContactError, fit_hertz, parse_compression_csv};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

fn synthetic(k: f64, n: f64, sigma: f64, rng: &mut StdRng) -> Vec<CompressionPoint> {
    let noise = Normal::new(0.0, sigma).unwrap();
    (1..=60)
        .map(|i| {
            let d = 0.2e-3 * i as f64 / 60.0 * 20.0; // up to 4 mm, like Fig. 4
            CompressionPoint {
                indentation_m: d,
                force_n: k * d.powf(n) + if sigma > 0.0 { noise.sample(rng) } else { 0.0 },
            }
        })
        .collect()
}

#[test]
fn noise_free_data_are_recovered_exactly() {
    let mut rng = StdRng::seed_from_u64(1);
    for (k, n) in [
        (7.359e7, 1.961),
        (9.642e7, 2.002),
        (1.311e7, 1.817),
        (2e5, 1.0),
    ] {
        let fit = fit_hertz(&synthetic(k, n, 0.0, &mut rng)).unwrap();
        assert_close("k", fit.k, k, 1e-9);
        assert_close("n", fit.n, n, 1e-10);
        assert!(fit.r2 > 1.0 - 1e-15, "R² = {}", fit.r2);
    }
}

#[test]
fn noisy_fit_is_within_its_reported_uncertainty() {
    // Single draw: within 4 standard errors.
    let (k, n) = (7.359e7, 1.961);
    let mut rng = StdRng::seed_from_u64(7);
    let fit = fit_hertz(&synthetic(k, n, 2.0, &mut rng)).unwrap();
    assert!((fit.k - k).abs() < 4.0 * fit.k_stderr, "{fit:?}");
    assert!((fit.n - n).abs() < 4.0 * fit.n_stderr, "{fit:?}");
    assert!(fit.r2 > 0.99 && fit.r2 < 1.0, "{fit:?}");
    assert!(fit.k_stderr > 0.0 && fit.n_stderr > 0.0);
}

#[test]
fn reported_standard_errors_match_the_monte_carlo_spread() {
    // Over many noise draws the scatter of n̂ and k̂ must equal the reported standard error
    // (within the sampling error of a standard deviation from 300 draws, ≈ 4 %; allow 15 %),
    // and about 95 % of the ±1.96σ intervals must cover the truth.
    let (k, n, sigma) = (9.642e7, 2.002, 3.0);
    let mut rng = StdRng::seed_from_u64(42);
    let draws = 300;
    let fits: Vec<_> = (0..draws)
        .map(|_| fit_hertz(&synthetic(k, n, sigma, &mut rng)).unwrap())
        .collect();
    let spread = |v: Vec<f64>| {
        let m = v.iter().sum::<f64>() / v.len() as f64;
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
    };
    let sd_n = spread(fits.iter().map(|f| f.n).collect());
    let sd_k = spread(fits.iter().map(|f| f.k).collect());
    let se_n = fits.iter().map(|f| f.n_stderr).sum::<f64>() / draws as f64;
    let se_k = fits.iter().map(|f| f.k_stderr).sum::<f64>() / draws as f64;
    assert_close("spread of n̂ vs reported n_stderr", sd_n, se_n, 0.15);
    assert_close("spread of k̂ vs reported k_stderr", sd_k, se_k, 0.15);
    let covered = fits
        .iter()
        .filter(|f| (f.n - n).abs() <= 1.96 * f.n_stderr)
        .count() as f64
        / draws as f64;
    assert!((0.91..=0.99).contains(&covered), "coverage {covered}");
}

#[test]
fn csv_with_header_comments_and_contact_free_points() {
    let text = "# Mark-10 export\nindentation_m,force_n\n-0.0001,0\n0,0\n0.001, 73.59\n\n0.002,287.0\n0.003,638.0\n";
    let points = parse_compression_csv(text).unwrap();
    assert_eq!(points.len(), 5);
    let fit = fit_hertz(&points).unwrap();
    assert_eq!((fit.points, fit.skipped), (3, 2));
}

#[test]
fn malformed_csv_names_the_line() {
    let cases = [
        ("indentation_m,force_n\n0.001,1\n0.002,abc\n", 3, "force_n"),
        ("0.001,1\n0.002\n", 2, "2 comma-separated"),
        ("depth,load\n0.001,1\n", 1, "header"),
        ("0.001,1\n0.002,inf\n", 2, "finite"),
        ("0.001,1,3\n", 1, "3 fields"),
    ];
    for (text, line, words) in cases {
        match parse_compression_csv(text) {
            Err(ContactError::Csv { line: l, .. }) if l == line => {
                let msg = parse_compression_csv(text).unwrap_err().to_string();
                assert!(msg.contains(words), "{msg}");
            }
            other => panic!("{text:?}: expected an error on line {line}, got {other:?}"),
        }
    }
}

#[test]
fn too_little_data_is_an_error() {
    assert!(matches!(
        fit_hertz(&parse_compression_csv("").unwrap()),
        Err(ContactError::NotEnoughData { found: 0, .. })
    ));
    let same_depth = parse_compression_csv("0.001,1\n0.001,1.1\n0.001,0.9\n").unwrap();
    assert!(matches!(
        fit_hertz(&same_depth),
        Err(ContactError::NotEnoughData { .. })
    ));
    let all_zero = parse_compression_csv("0.001,0\n0.002,0\n0.003,0\n").unwrap();
    let e = fit_hertz(&all_zero).unwrap_err();
    assert!(e.to_string().contains("force_n > 0"), "{e}");
    // Regression (issue 11): negative forces were accepted; a compression force is >= 0.
    let e = parse_compression_csv("0.001,1\n0.002,-2\n").unwrap_err();
    assert!(matches!(e, ContactError::Csv { line: 2, .. }), "{e}");
    assert!(e.to_string().contains("force_n"), "{e}");
}

#[test]
fn data_of_any_magnitude_fit_with_finite_errors_or_say_why() {
    // Regression (issue 11): values of 1e300 or 1e-300 gave null standard errors. The fit
    // runs in units of the largest indentation and force; the law and its relative errors do
    // not depend on the units.
    let law = |d: f64| 3.0 * d.powf(1.9);
    let base: Vec<(f64, f64)> = (1..=20)
        .map(|i| {
            let d = i as f64 * 0.05;
            (
                d,
                law(d) * (1.0 + 0.01 * ((i * 7919) % 13) as f64 / 13.0 - 0.005),
            )
        })
        .collect();
    let reference = fit_hertz(
        &base
            .iter()
            .map(|&(d, f)| CompressionPoint {
                indentation_m: d,
                force_n: f,
            })
            .collect::<Vec<_>>(),
    )
    .unwrap();
    for (sd, sf) in [
        (1e-150, 1e150),
        (1e100, 1e-100),
        (1e-300, 1.0),
        (1.0, 1e-300),
    ] {
        let points: Vec<CompressionPoint> = base
            .iter()
            .map(|&(d, f)| CompressionPoint {
                indentation_m: d * sd,
                force_n: f * sf,
            })
            .collect();
        match fit_hertz(&points) {
            Ok(fit) => {
                assert!((fit.n - reference.n).abs() < 1e-9, "{sd:e} {sf:e}: {fit:?}");
                assert!(
                    (fit.n_stderr / reference.n_stderr - 1.0).abs() < 1e-6,
                    "{sd:e} {sf:e}: {fit:?}"
                );
                // k's relative error depends on the units (ln k = ln k' + ln F − n ln D
                // carries n's uncertainty), but it is finite
                assert!(fit.k.is_finite() && fit.k_stderr.is_finite(), "{fit:?}");
                let k_expected = reference.k * sf / sd.powf(reference.n);
                if k_expected.is_normal() {
                    assert!(
                        (fit.k / k_expected - 1.0).abs() < 1e-6,
                        "{fit:?} vs {k_expected:e}"
                    );
                }
            }
            Err(e) => {
                // k = k' F/D^n may leave double precision: then say so
                assert!(
                    e.to_string().contains("not representable"),
                    "{sd:e} {sf:e}: {e}"
                );
            }
        }
    }
}
