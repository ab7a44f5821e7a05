//! The role-switch table: the prescribed drive is the test bed's held joint, a linear drive sees
//! the same impact whether it moves the robot or holds it (Galilean invariance), and the stiff
//! loop approaches the held joint while the torque-free rotor gives the free hub.

use flexrig_impact::role_switch::{
    Design, DriveLevel, RoleSettings, fig6_cases, role_switch_table, test_bed_cases,
};

#[test]
fn the_role_switch_table_holds_its_limits() {
    let mut cases = test_bed_cases().unwrap();
    let fig6 = fig6_cases(2.0).unwrap();
    cases.push(fig6[0].clone());
    cases.push(fig6[4].clone());
    let t0 = std::time::Instant::now();
    let rows = role_switch_table(&cases, &RoleSettings::standard()).unwrap();
    eprintln!("{} rows in {:?}", rows.len(), t0.elapsed());
    for r in &rows {
        eprintln!(
            "{:40} {:?} {:?}: test bed {:.6} driven {:.6} ratio {:.4} switched {:.6}",
            r.case,
            r.design,
            r.level,
            r.f_test_bed_n,
            r.f_driven_n,
            r.ratio,
            r.f_switched_same_drive_n
        );
        let galilean = (r.f_switched_same_drive_n - r.f_driven_n).abs() / r.f_driven_n;
        assert!(galilean < 1e-5, "{galilean}");
        if r.level == DriveLevel::Prescribed {
            assert!((r.ratio - 1.0).abs() < 1e-6, "{}", r.ratio);
        }
    }
    assert!(rows.iter().any(|r| r.design == Design::Cl));
}
