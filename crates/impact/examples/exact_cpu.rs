//! CPU time of the exact driven CL strike (the thread's own time from
//! /proc/thread-self/schedstat, so a shared machine's load does not count):
//! `cargo run --release -p flexrig-impact --example exact_cpu`.
use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Drive, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl};
use flexrig_impact::{DrivenStrike, LinkParams};

fn cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0)
}

fn main() {
    let l = 0.33802;
    let strike = |ramp_time: f64, settle: f64| DrivenStrike {
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
    };
    for (case, s) in [("0.5 s ramp (bent)", strike(0.5, 0.1)), ("1 s ramp (rings)", strike(1.0, 0.15))] {
        for (name, settings) in [("FAST", ExactSettings::FAST), ("DEFAULT", ExactSettings::DEFAULT)] {
            let repeats = if name == "FAST" { 20 } else { 3 };
            let t0 = cpu_ns();
            let mut steps = 0;
            let mut peak = 0.0;
            for _ in 0..repeats {
                let o = run_exact_cl(&s, &settings).unwrap();
                steps = o.work;
                peak = o.contact.peak_force_n;
            }
            let ms = (cpu_ns() - t0) as f64 / 1e6 / repeats as f64;
            println!("{case}, {name}: {ms:.1} ms CPU per strike, {steps} steps, peak {peak:.4} N");
        }
    }
}
