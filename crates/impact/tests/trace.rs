//! The sampled motion of a driven strike: ordered in time, from the start through the onset to
//! the separation, consistent with the events it samples.

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::driven_cj::{CjSettings, run_driven_cj};
use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl};
use flexrig_impact::{DrivenOutcome, DrivenStrike, LinkParams};

fn strike() -> DrivenStrike {
    DrivenStrike {
        link: LinkParams {
            m_r: 10.0,
            length: 1.0,
            k_delta: 2e2,
            m_e: 0.1,
        },
        drive: Drive::controller(
            Motor::new(1e-4, 50.0, 1e-5).unwrap(),
            Profile::SmoothRamp {
                speed: 2.0,
                ramp_time: 0.5,
            },
            Gains::position_pd(500.0, 40.0),
            Some(1.0),
        )
        .unwrap(),
        person: Person {
            m_h: 4.0,
            support: HeadSupport::Free,
            contact: Hertz::new(1e8, 2.0).unwrap(),
            damping: DampingSpec::NONE,
            speed: 0.0,
        },
        placement: Placement::AfterRamp { settle: 0.3 },
        horizon_s: 5.0,
    }
}

fn check(out: &DrivenOutcome, every: f64) {
    let tr = &out.trace;
    assert!(tr.len() > 20, "{}", tr.len());
    assert_eq!(tr[0].t, 0.0);
    assert!(tr.windows(2).all(|w| w[1].t > w[0].t));
    let c = out.contact;
    let onset = tr
        .iter()
        .find(|s| s.t == c.onset_s)
        .expect("the onset is sampled");
    assert!(onset.indentation_m.abs() < 1e-12);
    assert!((onset.tip_deflection_m - out.pre_impact_deflection_m).abs() < 1e-12);
    let last = tr.last().unwrap();
    assert!((last.t - (c.onset_s + c.duration_s)).abs() < 1e-12);
    let f_max = tr.iter().fold(0.0_f64, |m, s| m.max(s.force_n));
    assert!(f_max <= c.peak_force_n * (1.0 + 1e-9) && f_max > 0.5 * c.peak_force_n);
    // before the onset, no force and at most one sample per interval
    let before: Vec<_> = tr.iter().filter(|s| s.t < c.onset_s).collect();
    assert!(
        before
            .iter()
            .all(|s| s.force_n == 0.0 && s.indentation_m < 0.0)
    );
    assert!(
        before
            .windows(2)
            .all(|w| w[1].t - w[0].t >= every * (1.0 - 1e-12))
    );
}

#[test]
fn the_trace_samples_the_driven_cj_and_cl() {
    let every = 2e-3;
    let cj = run_driven_cj(
        &strike(),
        &CjSettings {
            trace_every: Some(every),
            ..CjSettings::DEFAULT
        },
    )
    .unwrap();
    check(&cj, every);
    let cl = run_driven_cl(
        &strike(),
        &ClDriveSettings {
            trace_every: Some(every),
            ..ClDriveSettings::DEFAULT
        },
    )
    .unwrap();
    check(&cl, every);
    // without tracing nothing is kept
    assert!(
        run_driven_cj(&strike(), &CjSettings::DEFAULT)
            .unwrap()
            .trace
            .is_empty()
    );
    let bad = CjSettings {
        trace_every: Some(0.0),
        ..CjSettings::DEFAULT
    };
    assert!(
        run_driven_cj(&strike(), &bad)
            .unwrap_err()
            .to_string()
            .contains("trace_every")
    );
}
