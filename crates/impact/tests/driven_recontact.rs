//! Every contact of the driven CJ with the exact dome geometry against an independent solution
//! of the same equations, written here from the physics (not from the library's code): a
//! light link on a soft torsion spring, its hub turned at a constant speed, strikes a heavier
//! free hand, bounces back, is pulled forward by its spring and strikes again, until the hand
//! moves away beyond the dome's reach.
//!
//! Reference, in the joint angle φ of the link (φ_m = ω t the hub's prescribed angle):
//!   J φ̈ = k_θ (ω t − φ) − f L λ(u),   J = (m_e + m_r/3) L², k_θ = k_δ L²
//!   m_h Ẍ = f
//!   δ = L sin u + d_c (1 − cos u) − X,  λ = cos u + (d_c/L) sin u,  u = φ − φ_c
//!   f = k_c δⁿ (δ > 0)
//! with d_c = R − s the dome's centre behind the link's axis. Fixed-step RK4 at 2e-7 s; the
//! contacts are the stretches with δ > 0, their peaks the largest sampled force refined by a
//! parabola through the three samples around it.

#[path = "support/driven_cj_reference.rs"]
mod driven_cj_reference;

use driven_cj_reference::*;
use flexrig_impact::RunEnd;
use flexrig_impact::drive::Dome;
use flexrig_impact::driven_cj::{CjSettings, run_exact_cj};

#[test]
fn every_contact_of_a_light_link_striking_a_free_hand_matches_the_independent_solution() {
    for omega in [2.0, 3.0] {
        let settings = CjSettings {
            every_contact: true,
            ..CjSettings::DEFAULT
        };
        let out = run_exact_cj(&strike(omega), &settings, &Dome::TEST_BED).unwrap();
        let RunEnd::PartedForGood(parted) = out.ended else {
            panic!(
                "the run should end with the bodies parted for good: {:?}",
                out.ended
            )
        };
        let reference = reference(omega, parted + 0.1);
        assert!(
            out.contacts.len() >= 2,
            "the design should strike again: {} contacts",
            out.contacts.len()
        );
        assert_contacts_match(&format!("ω {omega}"), &out, &reference, 1e-4);
        // the largest contact is not the first one for this light link
        let (governing, _) = out.largest_contact();
        eprintln!(
            "ω {omega}: {} contacts, the largest is contact {governing}",
            out.contacts.len()
        );
    }
}

/// The dome of the light-beam comparison: its centre on the link's axis (s = R), so the tip
/// section's rotation, which differs between a bent beam (3w/2L) and a rigid link turned on a
/// spring (w/L), does not move the contact point.
const CENTRED_DOME: Dome = Dome {
    radius_m: 0.0715,
    standoff_m: 0.0715,
};

/// The exact CL (corotational beam on the driven hub) following every contact, against the
/// independent solution above of its lumped limit: a beam of negligible mass (m_r = 1e-4 kg
/// under a 0.12 kg tip) is a tip mass on the lateral spring k_δ = 3EI/L³, which is the rigid
/// link on the torsion spring k_δ L² up to the link's geometry: the tip's path (a chord's
/// shortening (3/5) w²/L against the arc's w²/2L), the rotation's stiffening of the beam
/// (≈ 0.2 m_e ω²/k_δ ≈ 1e-4) and the beam's mass (0.1 m_r/m_e ≈ 1e-4), all below 1e-3 of the
/// peaks at these tip deflections (w/L ≈ 2 %). Every contact, its number, the largest one
/// and the parting for good are the behaviour under test.
#[test]
fn every_contact_of_the_exact_cl_matches_the_lumped_limit_of_a_light_beam() {
    use flexrig_impact::exact_link::{ExactSettings, run_exact_cl};
    let (m_r, m_e) = (1e-4, 0.12);
    for omega in [2.0, 3.0] {
        let out = run_exact_cl(
            &strike_of(omega, m_r, m_e),
            &ExactSettings {
                dome: CENTRED_DOME,
                every_contact: true,
                ..ExactSettings::DEFAULT
            },
        )
        .unwrap();
        let RunEnd::PartedForGood(parted) = out.ended else {
            panic!(
                "the run should end with the bodies parted for good: {:?}",
                out.ended
            )
        };
        let reference = reference_of(omega, parted + 0.1, m_e + m_r / 3.0, &CENTRED_DOME);
        assert!(
            out.contacts.len() >= 2,
            "the design should strike again: {} contacts",
            out.contacts.len()
        );
        assert_contacts_match(&format!("CL ω {omega}"), &out, &reference, 1e-3);
    }
}

/// The linear models (`link_model = "linear"`: the tip and the hand on one straight path, the
/// link's deflection linear) following every contact, against the independent solution along
/// the same path: the CJ (a rigid link on the torsion spring, the reference's own model) and
/// the CL in its lumped limit (a beam of 0.1 g under a 0.12 kg tip: a tip mass on the lateral
/// spring 3EI/L³ = k_δ, the beam's mass 1e-4 of the tip's). Along a straight path the tip can
/// always come back, so both runs go on to the window; every contact in it is compared.
#[test]
fn every_contact_of_the_linear_models_matches_the_solution_along_their_path() {
    use flexrig_impact::driven_cj::run_driven_cj;
    use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl};
    let horizon = 1.5;
    for omega in [2.0, 3.0] {
        for (model, m_r, m_e, bar) in [("CJ", M_R, M_E, 1e-6), ("CL", 1e-4, 0.12, 3e-4)] {
            let mut strike = strike_of(omega, m_r, m_e);
            strike.horizon_s = horizon;
            let out = if model == "CJ" {
                run_driven_cj(
                    &strike,
                    &CjSettings {
                        every_contact: true,
                        ..CjSettings::DEFAULT
                    },
                )
            } else {
                run_driven_cl(
                    &strike,
                    &ClDriveSettings {
                        every_contact: true,
                        ..ClDriveSettings::DEFAULT
                    },
                )
            }
            .unwrap();
            assert_eq!(
                out.ended,
                RunEnd::Window(horizon),
                "{model}: the run goes on to the window"
            );
            let reference = reference_along(omega, horizon, m_e + m_r / 3.0, None);
            assert!(
                reference.len() >= 2,
                "the design should strike again: {} contacts",
                reference.len()
            );
            assert_contacts_match(&format!("linear {model} ω {omega}"), &out, &reference, bar);
        }
    }
}

/// Every contact of `out` against the reference's (onset, peak, time of peak, duration), printed
/// and held: as many contacts, each peak within `bar`, each onset within 10 `bar` of the
/// contact's duration, each duration within 10 `bar`, and the largest peak within `bar`.
fn assert_contacts_match(
    label: &str,
    out: &flexrig_impact::DrivenOutcome,
    reference: &[(f64, f64, f64, f64)],
    bar: f64,
) {
    for (k, (c, r)) in out.contacts.iter().zip(reference).enumerate() {
        eprintln!(
            "{label} contact {}: peak {:.6} N (reference {:.6}, {:+.2e}), onset {:.6e} s \
             ({:.6e}), duration {:.6e} s ({:.6e})",
            k + 1,
            c.peak_force_n,
            r.1,
            c.peak_force_n / r.1 - 1.0,
            c.onset_s,
            r.0,
            c.duration_s,
            r.3
        );
    }
    assert_eq!(
        out.contacts.len(),
        reference.len(),
        "{label}: the number of contacts"
    );
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    for (k, (c, r)) in out.contacts.iter().zip(reference).enumerate() {
        assert!(rel(c.peak_force_n, r.1) < bar, "peak of contact {}", k + 1);
        assert!(
            (c.onset_s - r.0).abs() < 10.0 * bar * r.3,
            "onset of contact {}",
            k + 1
        );
        assert!(
            rel(c.duration_s, r.3) < 10.0 * bar,
            "duration of contact {}",
            k + 1
        );
    }
    let top = reference.iter().map(|r| r.1).fold(0.0, f64::max);
    assert!((out.largest_contact().1.peak_force_n - top).abs() < bar * top);
}
