//! flexrig-lumped on its own: the peak force of the paper's Fig. 6 compliant-joint impact by the
//! exact energy balance and by time integration, and η(2/3) of Eq. 15.
//!
//! `cargo run -p flexrig-lumped --example impact_peak`

use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::ode::{OdeOptions, integrate};
use flexrig_lumped::prb::PrbLink;
use flexrig_lumped::{ImpactModel, fig6, peak_exact};

fn main() -> Result<(), flexrig_lumped::LumpedError> {
    let spring = SeriesCompliance::new(1e8, Hertz::new(1e8, 2.0)?)?;
    let model = ImpactModel::with_prb_link(4.0, PrbLink::new(1.0, 10.0, 0.1)?, spring, 2.0)?;
    let exact = peak_exact(&model);
    let ode = integrate(&model, &OdeOptions::new(1e-10)?)?;
    println!(
        "exact: f_max = {:.6} N, δ_max = {:.4e} m",
        exact.f_max, exact.delta_max
    );
    println!(
        "ode:   f_max = {:.6} N at {:.4e} s, contact {:.4e} s, {} evaluations",
        ode.peak.f_max,
        ode.t_peak,
        ode.contact_duration.unwrap_or(f64::NAN),
        ode.rhs_evals
    );
    for case in fig6::cases() {
        println!(
            "{}: η(2/3) = {:.4} (n = 1), {:.4} (n = 2)",
            case.label(),
            case.eta(1.0, 2.0 / 3.0)?,
            case.eta(2.0, 2.0 / 3.0)?
        );
    }
    Ok(())
}
