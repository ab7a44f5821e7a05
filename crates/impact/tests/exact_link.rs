//! The geometrically exact driven link (crates/impact/src/exact_link.rs) against the
//! independent bar-chain elastica of scripts/reference_driven_elastica.py (fixture
//! tests/data/driven_elastica.json): the test bed's link (m_r = 51 g, L = 0.33802 m,
//! k_θr = 1.2334 N·m/rad, 412 g payload) with the skinned-aluminium dome into a free 4 kg head.

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl};
use flexrig_impact::{DrivenOutcome, DrivenStrike, LinkParams};

const L: f64 = 0.33802;

fn link() -> LinkParams {
    LinkParams {
        m_r: 0.051,
        length: L,
        k_delta: 1.2334 / (L * L),
        m_e: 0.412,
    }
}

fn person() -> Person {
    Person {
        m_h: 4.0,
        support: HeadSupport::Free,
        contact: Hertz::new(7.359e7, 1.961).unwrap(),
        damping: DampingSpec::NONE,
        speed: 0.0,
    }
}

fn motor() -> Motor {
    Motor::new(1e-5, 50.0, 0.0).unwrap()
}

/// The fixture's cases by name.
fn case(name: &str) -> DrivenStrike {
    let omega = 1.0 / L;
    let (drive, placement) = match name {
        "steady" => (
            Drive::trajectory(motor(), Profile::Steady { speed: omega }).unwrap(),
            Placement::Angle { angle: 0.05 },
        ),
        "ramp_rings" | "short_ramp_bent" | "cj_short_ramp" => {
            let (ramp_time, settle) = match name {
                "ramp_rings" => (1.0, 0.15),
                _ => (0.5, 0.1),
            };
            (
                Drive::trajectory(
                    motor(),
                    Profile::SmoothRamp {
                        speed: omega,
                        ramp_time,
                    },
                )
                .unwrap(),
                Placement::AfterRamp { settle },
            )
        }
        "pd_ramp" => (
            Drive::controller(
                motor(),
                Profile::SmoothRamp {
                    speed: omega,
                    ramp_time: 1.0,
                },
                Gains::position_pd(5.0, 0.5),
                None,
            )
            .unwrap(),
            Placement::AfterRamp { settle: 0.2 },
        ),
        other => panic!("no case {other}"),
    };
    DrivenStrike {
        link: link(),
        drive,
        person: person(),
        placement,
        horizon_s: 10.0,
    }
}

fn show(name: &str, o: &DrivenOutcome) {
    println!(
        "{name}: onset {:.9} peak {:.6} at {:.9} duration {:.9} approach {:.9} sep {:.9} defl {:.6} steps {} energy {:?} notes {:?}",
        o.contact.onset_s,
        o.contact.peak_force_n,
        o.contact.time_of_peak_s,
        o.contact.duration_s,
        o.approach_speed_mps,
        -o.separation_rate_mps,
        o.pre_impact_deflection_m,
        o.work,
        o.energy,
        o.notes.iter().map(|n| n.to_string()).collect::<Vec<_>>()
    );
}

#[test]
fn dev_print() {
    for name in ["steady", "short_ramp_bent"] {
        let o = run_exact_cl(&case(name), &ExactSettings::DEFAULT).unwrap();
        show(name, &o);
    }
}

#[test]
fn dev_convergence() {
    for (el, ap, co, ax) in [(16, 2000, 1000, 2.05e5), (16, 2000, 1000, 2e7), (64, 2000, 1000, 2e7), (128, 2000, 1000, 2.05e5)] {
        let s = ExactSettings {
            axial_slenderness: ax,
            elements: el,
            approach_steps: ap,
            contact_steps: co,
            ..ExactSettings::DEFAULT
        };
        for name in ["steady", "short_ramp_bent"] {
            let o = run_exact_cl(&case(name), &s).unwrap();
            show(&format!("{name} {el} {ap} {co}"), &o);
        }
    }
}
