//! `flexrig safety --trace FILE`: a measured impact's severity and its verdict against a body
//! region's limits, see [`flexrig::safety::measured`].

use std::io::Write;

use flexrig::Error;
use flexrig::safety::measured::{EnergyBasis, MeasuredReport, TraceInput, judge_trace};
use flexrig::safety::{BodyModel, ContactAreaModel, ContactKind};

use crate::print::{line, print_json};

/// Runs `flexrig safety --trace FILE` on the library's `input` (built from the flags by
/// `flexrig safety`): JSON with `json`, else text.
pub fn run(
    input: &TraceInput,
    model: Option<&BodyModel>,
    json: bool,
    out: &mut dyn Write,
) -> Result<(), Error> {
    let report = judge_trace(input, model)?;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    if json {
        let value = serde_json::to_value(&report).expect("the report serialises");
        return print_json(out, &value);
    }
    print_text(out, &report)
}

fn print_text(out: &mut dyn Write, r: &MeasuredReport) -> Result<(), Error> {
    line(
        out,
        format!(
            "measured trace     {}: {} samples over {:.6} s; columns {}",
            r.trace,
            r.samples,
            r.duration_s,
            r.columns
                .iter()
                .map(|c| c.header.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )?;
    line(
        out,
        format!("body region        {} ({})", r.region_name, r.region),
    )?;
    line(out, format!("area               {}", r.area))?;
    line(
        out,
        format!(
            "contact            {}",
            match r.contact {
                ContactKind::Transient => "transient (the body free to recoil)",
                ContactKind::QuasiStatic => "quasi-static (clamped against a support)",
            }
        ),
    )?;
    line(
        out,
        format!(
            "limits             force {} N, pressure {} N/cm²",
            r.force_limit_n,
            r.pressure_limit_pa / 1e4
        ),
    )?;
    let s = &r.severity;
    line(
        out,
        format!(
            "peak force         {:.3} N at {:.6} s",
            s.peak_force_n, s.time_of_peak_force_s
        ),
    )?;
    match (s.pressure.first(), &r.area_model) {
        (Some(p), Some(model)) => line(
            out,
            format!(
                "peak pressure      {:.3} N/cm² mean ({:.3} N/cm² peak of the distribution) at \
                 {:.6} s, {}",
                p.mean_pa / 1e4,
                p.peak_pa / 1e4,
                p.time_s,
                area_words(model)
            ),
        )?,
        _ => line(
            out,
            "peak pressure      not assessed (no contact geometry: give --contact-area, e.g. \
             1cm2, or --radius of the dome with an indentation column)",
        )?,
    }
    line(
        out,
        format!(
            "energy transferred {:.6} J {}; the standard's energy at the force limit, \
             F²/(2K), is {:.6} J",
            s.energy_transferred_j,
            match s.energy_transferred_from {
                EnergyBasis::ForceAndIndentation =>
                    "(∫ f dδ up to the largest indentation)".to_string(),
                EnergyBasis::BodySpringAtPeakForce => format!(
                    "(no indentation in the trace: F²/(2K) of the body spring, K = {} N/mm, \
                     Eq. A.1)",
                    r.body_stiffness_n_per_m / 1e3
                ),
            },
            r.energy_limit_j
        ),
    )?;
    match (&s.hic15, &s.hic36, s.peak_acceleration_g) {
        (Some(h15), Some(h36), Some(g)) => line(
            out,
            format!(
                "acceleration       peak {g:.3} g; HIC15 {:.4} ({:.6}–{:.6} s), HIC36 {:.4}",
                h15.hic, h15.t1_s, h15.t2_s, h36.hic
            ),
        )?,
        _ => line(out, "acceleration       not in the trace (no HIC)")?,
    }
    let v = &r.verdict;
    let pressure = match v.pressure_margin {
        Some(m) => format!(", pressure margin {m:.4}"),
        None => "; pressure not assessed".into(),
    };
    line(
        out,
        format!(
            "verdict            {} (peak force {:.3} N against {} N, force margin {:.4}{pressure})",
            if v.pass { "pass" } else { "FAIL" },
            s.peak_force_n,
            r.force_limit_n,
            v.force_margin
        ),
    )
}

fn area_words(model: &ContactAreaModel) -> String {
    match model {
        ContactAreaModel::HertzSphere { radius_m } => {
            format!("Hertz sphere A = π R δ, R = {} mm", radius_m * 1e3)
        }
        ContactAreaModel::ThinLayer { radius_m } => {
            format!("thin layer A = π(2Rδ − δ²), R = {} mm", radius_m * 1e3)
        }
        ContactAreaModel::Fixed { area_m2 } => format!("fixed area A = {} cm²", area_m2 * 1e4),
    }
}
