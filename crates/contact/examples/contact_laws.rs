//! flexrig-contact on its own: the paper's skinned-aluminium Hertz law, a damped variant, the
//! series compliance of a soft link, and a fit of (k, n) to compression data.
//!
//! `cargo run -p flexrig-contact --example contact_laws`

use flexrig_contact::{
    CompressionPoint, ContactLaw, DampedHertz, Materials, SeriesCompliance, fit_hertz,
};

fn main() -> Result<(), flexrig_contact::ContactError> {
    let materials = Materials::bundled()?;
    let aluminium = materials.get("skinned_aluminium")?;
    let hertz = aluminium.hertz;
    println!(
        "{}: k = {:e} N/m^n, n = {}",
        aluminium.name,
        hertz.k(),
        hertz.n()
    );
    for delta in [0.5e-3, 1e-3, 2e-3] {
        println!(
            "  δ = {delta:e} m: f = {:.3} N, U = {:.4e} J",
            hertz.force(delta, 0.0),
            hertz.energy(delta)
        );
    }
    let damped = DampedHertz::hunt_crossley(hertz, 0.8, 1.0)?;
    println!(
        "Hunt–Crossley e = 0.8 at 1 m/s: χ = {} s/m, f(1 mm, +0.5 m/s) = {:.3} N",
        damped.chi(),
        damped.force(1e-3, 0.5)
    );
    let series = SeriesCompliance::new(10.8, hertz)?;
    let f = series.force(0.05);
    println!(
        "link 10.8 N/m in series, δ = 5 cm: f = {f:.4} N (indentation {:.3e} m)",
        series.indentation(f)
    );
    let data: Vec<CompressionPoint> = (1..=20)
        .map(|i| {
            let d = 2e-4 * i as f64;
            CompressionPoint {
                indentation_m: d,
                force_n: hertz.force(d, 0.0),
            }
        })
        .collect();
    let fit = fit_hertz(&data)?;
    println!(
        "fit of noise-free data: k = {:e}, n = {:.6}, R² = {}",
        fit.k, fit.n, fit.r2
    );
    Ok(())
}
