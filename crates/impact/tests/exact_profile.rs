use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl, run_exact_cl_meshed};
use flexrig_impact::{DrivenOutcome, DrivenStrike, LinkParams};
use std::time::Instant;

fn stiff(support: HeadSupport) -> DrivenStrike {
    DrivenStrike {
        link: LinkParams { m_r: 10.0, length: 1.0, k_delta: 1e8, m_e: 0.1 },
        drive: Drive::controller(
            Motor::new(1e-4, 50.0, 1e-5).unwrap(),
            Profile::SmoothRamp { speed: 2.0, ramp_time: 0.5 },
            Gains::position_pd(500.0, 40.0),
            Some(1.0),
        ).unwrap(),
        person: Person { m_h: 4.0, support, contact: Hertz::new(1e8, 2.0).unwrap(), damping: DampingSpec::NONE, speed: 0.0 },
        placement: Placement::AfterRamp { settle: 0.3 },
        horizon_s: 5.0,
    }
}
fn bed() -> DrivenStrike {
    let l = 0.33802;
    DrivenStrike {
        link: LinkParams { m_r: 0.051, length: l, k_delta: 1.2334 / (l * l), m_e: 0.412 },
        drive: Drive::trajectory(Motor::new(1e-5, 50.0, 0.0).unwrap(), Profile::SmoothRamp { speed: 1.0 / l, ramp_time: 0.5 }).unwrap(),
        person: Person { m_h: 4.0, support: HeadSupport::Free, contact: Hertz::new(7.359e7, 1.961).unwrap(), damping: DampingSpec::NONE, speed: 0.0 },
        placement: Placement::AfterRamp { settle: 0.1 },
        horizon_s: 5.0,
    }
}
fn bedcase(name: &str) -> DrivenStrike {
    let l = 0.33802;
    let motor = || Motor::new(1e-5, 50.0, 0.0).unwrap();
    let omega = 1.0 / l;
    let (drive, placement) = match name {
        "steady" => (Drive::trajectory(motor(), Profile::Steady { speed: omega }).unwrap(), Placement::Angle { angle: 0.05 }),
        "ramp_rings" => (Drive::trajectory(motor(), Profile::SmoothRamp { speed: omega, ramp_time: 1.0 }).unwrap(), Placement::AfterRamp { settle: 0.15 }),
        "bent" => return bed(),
        _ => (Drive::controller(motor(), Profile::SmoothRamp { speed: omega, ramp_time: 1.0 }, Gains::position_pd(5.0, 0.5), None).unwrap(), Placement::AfterRamp { settle: 0.2 }),
    };
    DrivenStrike { drive, placement, horizon_s: 10.0, ..bed() }
}
fn err(a: &DrivenOutcome, b: &DrivenOutcome) -> [f64; 4] {
    let (x, y) = (&a.contact, &b.contact);
    [(x.peak_force_n / y.peak_force_n - 1.0).abs(),
     ((x.time_of_peak_s - x.onset_s) - (y.time_of_peak_s - y.onset_s)).abs() / y.duration_s,
     (x.duration_s / y.duration_s - 1.0).abs(),
     (x.onset_s / y.onset_s - 1.0).abs()]
}
fn run(s: &DrivenStrike, st: &ExactSettings) -> (DrivenOutcome, f64) {
    let t = Instant::now();
    let o = run_exact_cl(s, st).unwrap();
    (o, t.elapsed().as_secs_f64() * 1e3)
}
#[test]
#[ignore]
fn profile() {
    let which = std::env::var("CASES").unwrap_or("bed,free,wall".into());
    let grid: Vec<(usize, usize, usize)> = std::env::var("GRID").unwrap_or("16:1000:400".into())
        .split(',').map(|g| { let v: Vec<usize> = g.split(':').map(|x| x.parse().unwrap()).collect(); (v[0], v[1], v[2]) }).collect();
    let refg: Vec<usize> = std::env::var("REF").unwrap_or("192:16000:4000".into()).split(':').map(|x| x.parse().unwrap()).collect();
    for name in which.split(',') {
        let s = match name { "bed" => bed(), "steady" | "ramp_rings" | "pd" | "bent" => bedcase(name), "free" => stiff(HeadSupport::Free), _ => stiff(HeadSupport::Wall) };
        let rs = ExactSettings { elements: refg[0], approach_steps: refg[1], contact_steps: refg[2], mesh_tolerance: None, ..ExactSettings::DEFAULT };
        let (r, tr) = run(&s, &rs);
        println!("{name} ref {:?} {:.1} ms steps {} peak {:.9} onset {:.9} dur {:.9e}", refg, tr, r.work, r.contact.peak_force_n, r.contact.onset_s, r.contact.duration_s);
        {
            let t = Instant::now();
            let (o, n) = run_exact_cl_meshed(&s, &ExactSettings::DEFAULT).unwrap();
            println!("{name} DEFAULT -> {n} elements {:.1} ms steps {} err {}", t.elapsed().as_secs_f64()*1e3, o.work, err(&o, &r).map(|x| format!("{x:.1e}")).join(" "));
        }
        for &(e, a, c) in &grid {
            let st = ExactSettings { elements: e, approach_steps: a, contact_steps: c, mesh_tolerance: None, ..ExactSettings::DEFAULT };
            let (o, t) = run(&s, &st);
            if std::env::var("NOW").is_ok() { println!("{name} {e}:{a}:{c} {:.1} ms steps {} err {}", t, o.work, err(&o, &r).map(|x| format!("{x:.1e}")).join(" ")); continue; }
            let tr = run_exact_cl(&s, &ExactSettings { trace_every: Some(1e-5), ..st }).unwrap();
            let w = tr.trace.iter().fold(0.0f64, |m, x| m.max(x.tip_deflection_m.abs())) / s.link.length;
            let wc = tr.trace.iter().filter(|x| x.t >= o.contact.onset_s).fold(0.0f64, |m, x| m.max(x.tip_deflection_m.abs())) / s.link.length;
            println!("  max w/L {w:.3e} in contact {wc:.3e}  pred 0.5(w/L)^2/N^2 {:.2e}", 0.5 * w * w / (e * e) as f64);
            let (_, t2) = run(&s, &st);
            println!("{name} {e}:{a}:{c} {:.1} ms steps {} err {}", t.min(t2), o.work, err(&o, &r).map(|x| format!("{x:.1e}")).join(" "));
        }
    }
}
