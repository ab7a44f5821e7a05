//! CPU time of the exact driven CL strike from rest to the separation (the thread's own time
//! from /proc/thread-self/schedstat, so a shared machine's load does not count), at the default
//! and the fast settings: the bundled driven scenes (the Fig. 6 stiff link, a PD loop, a free
//! head and a wall) and the test bed's link bent by a 0.5 s ramp and ringing after a 1 s one.
//! `cargo run --release -p flexrig-impact --example exact_cpu`.
use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl_meshed};
use flexrig_impact::{DrivenStrike, LinkParams};

fn cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0)
}

/// assets/drives/cl_free_head.toml (`support` free) and cl_wall.toml (wall).
fn bundled(support: HeadSupport) -> DrivenStrike {
    DrivenStrike {
        link: LinkParams {
            m_r: 10.0,
            length: 1.0,
            k_delta: 1e8,
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
            support,
            contact: Hertz::new(1e8, 2.0).unwrap(),
            damping: DampingSpec::NONE,
            speed: 0.0,
        },
        placement: Placement::AfterRamp { settle: 0.3 },
        horizon_s: 5.0,
    }
}

/// The test bed's link ramped to 1 m/s at the tip in `ramp_time`, the person `settle` later.
fn test_bed(ramp_time: f64, settle: f64) -> DrivenStrike {
    let l = 0.33802;
    DrivenStrike {
        link: LinkParams {
            m_r: 0.051,
            length: l,
            k_delta: 1.2334 / (l * l),
            m_e: 0.412,
        },
        drive: Drive::trajectory(
            Motor::new(1e-5, 50.0, 0.0).unwrap(),
            Profile::SmoothRamp {
                speed: 1.0 / l,
                ramp_time,
            },
        )
        .unwrap(),
        person: Person {
            m_h: 4.0,
            support: HeadSupport::Free,
            contact: Hertz::new(7.359e7, 1.961).unwrap(),
            damping: DampingSpec::NONE,
            speed: 0.0,
        },
        placement: Placement::AfterRamp { settle },
        horizon_s: 5.0,
    }
}

fn main() {
    let cases = [
        ("cl_free_head (bundled)", bundled(HeadSupport::Free)),
        ("cl_wall (bundled)", bundled(HeadSupport::Wall)),
        ("test bed, 0.5 s ramp (bent)", test_bed(0.5, 0.1)),
        ("test bed, 1 s ramp (rings)", test_bed(1.0, 0.15)),
    ];
    // `exact_cpu free` runs the cases whose name contains "free"
    let only = std::env::args().nth(1).unwrap_or_default();
    for (case, s) in cases.into_iter().filter(|(c, _)| c.contains(only.as_str())) {
        for (name, settings) in [
            ("FAST", ExactSettings::FAST),
            ("DEFAULT", ExactSettings::DEFAULT),
        ] {
            let repeats = if name == "FAST" { 20 } else { 5 };
            let t0 = cpu_ns();
            let mut out = None;
            for _ in 0..repeats {
                out = Some(run_exact_cl_meshed(&s, &settings).unwrap());
            }
            let ms = (cpu_ns() - t0) as f64 / 1e6 / repeats as f64;
            let (o, n) = out.unwrap();
            println!(
                "{case}, {name}: {ms:.1} ms CPU per strike, {n} elements, {} steps, peak {:.4} N",
                o.work, o.contact.peak_force_n
            );
        }
    }
}
