//! Prints the tables of docs/driven.md: the role-switch verdict and the spin-up benchmark.
//! `cargo run --release -p flexrig-impact --example driven_tables` (`-- role`: the role-switch
//! table alone)
use flexrig_impact::role_switch::{
    DriveLevel, RoleSettings, fig6_cases, role_switch_table, test_bed_cases,
};
use flexrig_impact::spin_up::{SpinUp, spin_up_fe, spin_up_linear, spin_up_reference};

fn level(l: &DriveLevel) -> String {
    match l {
        DriveLevel::Prescribed => "prescribed".into(),
        DriveLevel::Pd { kappa } => format!("PD κ={kappa:e}"),
        DriveLevel::TorqueFree => "torque-free".into(),
    }
}

fn main() {
    let mut cases = test_bed_cases().unwrap();
    cases.extend(fig6_cases(1.0).unwrap());
    cases.extend(fig6_cases(2.0).unwrap());
    let settings = RoleSettings::standard();
    let t0 = std::time::Instant::now();
    let rows = role_switch_table(&cases, &settings).unwrap();
    eprintln!("{} rows in {:?}", rows.len(), t0.elapsed());
    let levels: Vec<String> = settings.levels.iter().map(level).collect();
    println!(
        "| case | design | test bed [N] | {} | worst Galilean check |",
        levels.join(" | ")
    );
    println!("|---|---|---|{}---|", "---|".repeat(levels.len()));
    for chunk in rows.chunks(settings.levels.len()) {
        let r0 = &chunk[0];
        let ratios: Vec<String> = chunk.iter().map(|r| format!("{:.4}", r.ratio)).collect();
        let worst = chunk
            .iter()
            .map(|r| (r.f_switched_same_drive_n - r.f_driven_n).abs() / r.f_driven_n)
            .fold(0.0, f64::max);
        println!(
            "| {} | {:?} | {:.1} | {} | {worst:.1e} |",
            r0.case,
            r0.design,
            r0.f_test_bed_n,
            ratios.join(" | ")
        );
    }
    if std::env::args().nth(1).as_deref() == Some("role") {
        return;
    }
    for omega_s in [4.0, 6.0] {
        let spec = SpinUp::simo_vu_quoc(omega_s);
        let t0 = std::time::Instant::now();
        let r7 = spin_up_reference(&spec, 7, 1e-11).unwrap();
        let r6 = spin_up_reference(&spec, 6, 1e-10).unwrap();
        eprintln!("reference in {:?}", t0.elapsed());
        let lin = spin_up_linear(&spec, 6, 1e-10).unwrap();
        let (i_max, d_max) =
            r7.tip_deflection_m
                .iter()
                .enumerate()
                .fold(
                    (0, 0.0_f64),
                    |m, (i, d)| if d.abs() > m.1.abs() { (i, *d) } else { m },
                );
        println!(
            "ω_s = {omega_s}: max deflection {d_max:.6} m at t = {:.1} s; reference 6 vs 7 modes {:.1e}; deflection at 15 s {:.6} m, at 20 s {:.6} m; linear model at 20 s {:.3e} m",
            r7.t[i_max],
            r6.difference(&r7),
            r7.tip_deflection_m[150],
            r7.tip_deflection_m[200],
            lin.tip_deflection_m[200]
        );
        for (el, h) in [(8, 1e-3), (16, 1e-3), (32, 1e-3), (64, 1e-3), (32, 5e-4)] {
            let t0 = std::time::Instant::now();
            let fe = spin_up_fe(&spec, el, h).unwrap();
            let mut stiff = spec;
            stiff.ea *= 1e3;
            let fe_stiff = spin_up_fe(&stiff, el, h).unwrap();
            println!(
                "  FE {el} elements, h {h:e} s: {:.2e} of the max ({:.2e} with EA × 1000) [{:?}]",
                fe.difference(&r7),
                fe_stiff.difference(&r7),
                t0.elapsed() / 2
            );
        }
    }
}
