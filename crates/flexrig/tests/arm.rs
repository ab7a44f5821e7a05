//! A real arm along its trajectory, judged by the safety methods (`flexrig::arm`): every sample's
//! permissible speed is `flexrig safety`'s single-link answer for its effective mass bit for bit;
//! a one-link arm reproduces the single-link model it is mapped onto (the reflected mass of a rod
//! with a tip payload, m_e + m_r/3, from its closed form); the standard's formula against its
//! closed form; the speed-scaling factor brings the largest ratio to 1; the mass grid; bad input.

use flexrig::arm::{
    ArmDrive, ArmInput, ArmJoints, ArmPoint, Robot, Trajectory, bundled, effective_mass_node,
    judge, simulation_settings,
};
use flexrig::safety::{
    ContactKind, ContactLaw, FeLink, RobotEffectiveMass, SafetyInput, SafetyMethod, safety,
};

fn input(law: ContactLaw, k_delta: Option<f64>, drive: ArmDrive, step: f64) -> ArmInput {
    ArmInput {
        points: bundled::ur5_points(),
        joints: ArmJoints::Rigid,
        speed_scale: 1.0,
        mass_step: step,
        region: "chest".into(),
        area: None,
        contact: ContactKind::Transient,
        law,
        area_model: None,
        link: FeLink::CompliantJoint,
        k_delta,
        link_mass: None,
        simulation: simulation_settings(drive, 1e-6, 1e-6),
        methods: vec![],
    }
}

/// The UR5's swing, every `every`-th sample (at least 3).
fn ur5_every(every: usize) -> (Robot, Trajectory) {
    let robot = bundled::ur5().unwrap();
    let full = bundled::ur5_swing(&robot).unwrap();
    let idx: Vec<usize> = (0..full.len()).step_by(every).collect();
    let traj = Trajectory::new(
        &robot,
        idx.iter().map(|&i| full.times()[i]).collect(),
        idx.iter().map(|&i| full.positions()[i].clone()).collect(),
    )
    .unwrap();
    (robot, traj)
}

/// The question `flexrig safety` is asked for an effective mass m, written out as the command
/// line would be (`--link cj --m-r m_r --m-e (m − m_r/3) --joint free-hub --rotor-inertia 1e-12
/// --length 1 --k-delta … --material …`), not through the arm's own helper.
fn by_hand(arm: &ArmInput, m_r: f64, m: f64) -> SafetyInput {
    SafetyInput {
        region: arm.region.clone(),
        area: None,
        contact: ContactKind::Transient,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma: 1.0,
            m_r,
            m_e: m - m_r / 3.0,
        }),
        k_delta: arm.k_delta,
        law: arm.law.clone(),
        area_model: None,
        moving_mass: None,
        payload: 0.0,
        speed: None,
        methods: vec![],
        link: Some(FeLink::CompliantJoint),
        simulation: Some(arm.simulation),
        scene: None,
    }
}

#[test]
fn every_sample_is_flexrig_safety_for_its_mass_bit_for_bit() {
    // a compliant joint with the fitted skin, re-contacts included; every mass exact, then on
    // the 1 % grid
    let (robot, traj) = ur5_every(15);
    for step in [0.0, 0.01] {
        let arm = input(
            ContactLaw::Material("skinned_aluminium".into()),
            Some(2e4),
            ArmDrive::Free,
            step,
        );
        let r = judge(&robot, &traj, &arm, None).unwrap();
        let mut checked = 0;
        for s in &r.samples {
            for p in &s.points {
                let (Some(m_u), Some(m)) = (p.reflected_mass_kg, p.effective_mass_kg) else {
                    continue;
                };
                if step == 0.0 {
                    assert_eq!(m.to_bits(), m_u.to_bits());
                } else {
                    assert!(m >= m_u && m / (1.0 + step) < m_u, "{m} vs {m_u}");
                }
                let single = safety(&by_hand(&arm, r.link_mass_kg, m), None).unwrap();
                let v = p.v_max_mps.unwrap();
                assert_eq!(
                    v.value().to_bits(),
                    single.overall.v_max_mps.value().to_bits(),
                    "t = {} s, m = {m} kg",
                    s.time_s
                );
                assert_eq!(p.method, Some(single.overall.method));
                checked += 1;
            }
        }
        assert!(checked >= 30, "{checked}");
    }
}

/// A uniform rod of mass m_r and length L turning about z at one end, with a point payload m_e
/// at its tip (a second link fixed to it): the reflected mass at the tip across the rod is
/// (m_r L²/3 + m_e L²)/L² = m_e + m_r/3.
fn rod(m_r: f64, m_e: f64, l: f64) -> Robot {
    let i = m_r * l * l / 12.0;
    let urdf = format!(
        r#"<robot name="rod">
  <link name="base"/>
  <link name="rod"><inertial><origin xyz="{h} 0 0"/><mass value="{m_r}"/>
    <inertia ixx="1e-6" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/></inertial></link>
  <link name="payload"><inertial><origin xyz="0 0 0"/><mass value="{m_e}"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="hub" type="continuous"><parent link="base"/><child link="rod"/>
    <axis xyz="0 0 1"/></joint>
  <joint name="tip" type="fixed"><parent link="rod"/><child link="payload"/>
    <origin xyz="{l} 0 0"/></joint>
</robot>"#,
        h = l / 2.0
    );
    Robot::from_urdf_str(&urdf, "rod.urdf").unwrap()
}

#[test]
fn a_one_link_arm_is_the_single_link_model_it_maps_onto() {
    let (m_r, m_e, l) = (0.6, 2.0, 0.5);
    let robot = rod(m_r, m_e, l);
    // the hub turns at 1, 2, 3 rad/s: the tip at 0.5, 1, 1.5 m/s
    let times = vec![0.0, 0.1, 0.2, 0.3, 0.4];
    let positions: Vec<Vec<f64>> = times.iter().map(|t| vec![0.5 * 10.0 * t * t]).collect();
    let traj = Trajectory::new(&robot, times, positions).unwrap();
    for (link, drive) in [
        (FeLink::CompliantJoint, ArmDrive::Free),
        (FeLink::CompliantJoint, ArmDrive::Held),
    ] {
        let arm = ArmInput {
            points: vec![ArmPoint {
                link: "payload".into(),
                xyz: [0.0; 3],
            }],
            link_mass: Some(m_r),
            link,
            ..input(
                ContactLaw::Hertz { k_c: 1e8, n: 1.5 },
                Some(5e4),
                drive,
                0.0,
            )
        };
        let r = judge(&robot, &traj, &arm, None).unwrap();
        let single = safety(&by_hand(&arm, m_r, m_e + m_r / 3.0), None).unwrap();
        for s in &r.samples[1..] {
            let p = &s.points[0];
            let m_u = p.reflected_mass_kg.unwrap();
            assert!(
                (m_u - (m_e + m_r / 3.0)).abs() <= 1e-12 * m_u,
                "{m_u} vs {}",
                m_e + m_r / 3.0
            );
            let v = p.v_max_mps.unwrap().value();
            let want = single.overall.v_max_mps.value();
            assert!(
                (v - want).abs() <= 1e-9 * want,
                "{drive:?}: {v} vs the single link's {want}"
            );
        }
    }
}

#[test]
fn the_standards_formula_matches_its_closed_form_at_every_sample() {
    // the body's own spring (n = 1), the standard's method alone: v = F/√(μK), μ = m m_H/(m + m_H)
    let (robot, traj) = ur5_every(5);
    let arm = ArmInput {
        methods: vec![SafetyMethod::Standard],
        ..input(ContactLaw::BodySpring, None, ArmDrive::Free, 0.0)
    };
    let r = judge(&robot, &traj, &arm, None).unwrap();
    let (f, k, m_h) = (r.force_limit_n, r.k_c, r.human_mass_kg.unwrap());
    assert_eq!((f, m_h), (280.0, 40.0));
    for s in &r.samples {
        for p in &s.points {
            let Some(m) = p.effective_mass_kg else {
                continue;
            };
            let mu = m * m_h / (m + m_h);
            let want = f / (mu * k).sqrt();
            let v = p.v_max_mps.unwrap().value();
            assert!((v - want).abs() <= 1e-12 * want, "{v} vs {want}");
            assert!((p.ratio - p.speed_mps / want).abs() <= 1e-12 * p.ratio.max(1e-300));
        }
    }
}

#[test]
fn the_speed_scaling_factor_brings_the_largest_ratio_to_one() {
    let (robot, traj) = ur5_every(3);
    let arm = input(
        ContactLaw::Material("skinned_aluminium".into()),
        Some(1e5),
        ArmDrive::Free,
        0.01,
    );
    let r = judge(&robot, &traj, &arm, None).unwrap();
    let factor = r.speed_scale_factor.value();
    assert!(factor.is_finite() && factor > 0.0);
    let g = r.governing.as_ref().unwrap();
    // the governing sample's own question at its speed agrees with the ratio's verdict
    assert_eq!(g.safety.overall.pass, Some(g.ratio <= 1.0));
    let scaled = judge(
        &robot,
        &traj,
        &ArmInput {
            speed_scale: factor,
            ..arm.clone()
        },
        None,
    )
    .unwrap();
    assert!(
        (scaled.max_ratio - 1.0).abs() <= 1e-9,
        "{}",
        scaled.max_ratio
    );
    let gs = scaled.governing.as_ref().unwrap();
    assert_eq!((gs.sample, gs.point), (g.sample, g.point));
    // the masses (postures and directions) do not change with the speed
    assert_eq!(scaled.masses.len(), r.masses.len());
}

#[test]
fn the_mass_grid_rounds_up_to_its_nodes() {
    for step in [0.001, 0.01, 0.05, 0.25] {
        for m in [0.013, 0.5, 1.0, 2.6578746899084074, 14.1, 987.0] {
            let (k, node) = effective_mass_node(m, step);
            assert!(
                node >= m && node / (1.0 + step) < m * (1.0 + 1e-12),
                "{m} {step}"
            );
            assert_eq!(node.to_bits(), (k as f64 * step.ln_1p()).exp().to_bits());
        }
    }
    assert_eq!(effective_mass_node(2.5, 0.0).1, 2.5);
    // a node is a fixed point: the grid is the same for every sample
    let (_, node) = effective_mass_node(3.3, 0.01);
    assert_eq!(effective_mass_node(node, 0.01).1.to_bits(), node.to_bits());
}

fn err(arm: &ArmInput) -> String {
    let (robot, traj) = ur5_every(50);
    judge(&robot, &traj, arm, None).unwrap_err().to_string()
}

#[test]
fn bad_input_names_the_flag_the_value_and_what_is_allowed() {
    let base = input(ContactLaw::BodySpring, None, ArmDrive::Free, 0.01);
    let e = err(&ArmInput {
        points: vec![ArmPoint {
            link: "toool0".into(),
            xyz: [0.0; 3],
        }],
        ..base.clone()
    });
    assert!(
        e.contains("--point") && e.contains("\"toool0\"") && e.contains("tool0"),
        "{e}"
    );
    let e = err(&ArmInput {
        points: vec![],
        ..base.clone()
    });
    assert!(e.contains("--point") && e.contains("1 to 64"), "{e}");
    let e = err(&ArmInput {
        joints: ArmJoints::Armature(vec![0.1; 3]),
        ..base.clone()
    });
    assert!(
        e.contains("--armature") && e.contains("3 values") && e.contains("elbow_joint"),
        "{e}"
    );
    let e = err(&ArmInput {
        joints: ArmJoints::Armature(vec![0.1, 0.1, -1.0, 0.1, 0.1, 0.1]),
        ..base.clone()
    });
    assert!(e.contains("--armature") && e.contains("elbow_joint"), "{e}");
    for bad in [-0.1, 0.3, f64::NAN] {
        let e = err(&ArmInput {
            mass_step: bad,
            ..base.clone()
        });
        assert!(e.contains("--mass-step") && e.contains("[0, 0.25]"), "{e}");
    }
    for bad in [0.0, -1.0, f64::INFINITY] {
        let e = err(&ArmInput {
            speed_scale: bad,
            ..base.clone()
        });
        assert!(
            e.contains("--speed-scale") && e.contains("(0, 1000]"),
            "{e}"
        );
    }
    let e = err(&ArmInput {
        link_mass: Some(30.0),
        ..base.clone()
    });
    assert!(
        e.contains("--link-mass") && e.contains("less than a third"),
        "{e}"
    );
    let e = err(&ArmInput {
        link_mass: Some(-2.0),
        ..base.clone()
    });
    assert!(e.contains("--link-mass") && e.contains("(0, 1e4]"), "{e}");
    let e = err(&ArmInput {
        region: "chestt".into(),
        ..base.clone()
    });
    assert!(e.contains("--region") && e.contains("chest"), "{e}");
    let e = err(&ArmInput {
        k_delta: Some(-5.0),
        ..base.clone()
    });
    assert!(e.contains("--k-delta"), "{e}");
    for text in ["", ":1,2,3", "tool0:1,2", "tool0:a,b,c", "tool0:0,0,1e9"] {
        let e = ArmPoint::parse(text).unwrap_err().to_string();
        assert!(
            e.contains("--point") && e.contains("LINK:x,y,z"),
            "{text}: {e}"
        );
    }
    assert_eq!(
        ArmPoint::parse("tool0:0,0,0.1").unwrap(),
        ArmPoint {
            link: "tool0".into(),
            xyz: [0.0, 0.0, 0.1]
        }
    );
}

#[test]
fn the_figure_log_and_report_are_written() {
    let dir = std::env::temp_dir().join(format!("flexrig_arm_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let (robot, traj) = ur5_every(10);
    let arm = input(ContactLaw::BodySpring, None, ArmDrive::Free, 0.01);
    let r = judge(&robot, &traj, &arm, None).unwrap();
    let outputs = flexrig::arm::report::Outputs {
        figure: Some(dir.join("arm.svg")),
        log: Some(dir.join("arm.mcap")),
        report: Some(dir.join("arm.md")),
        force: false,
    };
    outputs.check().unwrap();
    let sources = flexrig::arm::report::Sources {
        urdf: "ur5.urdf".into(),
        trajectory: "swing.csv".into(),
    };
    let written = outputs.write(&robot, &r, &sources, None).unwrap();
    assert_eq!(written.len(), 5, "{written:?}");
    let svg = std::fs::read_to_string(dir.join("arm.svg")).unwrap();
    assert!(svg.contains("Reflected mass") && svg.contains("tool0:0,0,0.1"));
    let md = std::fs::read_to_string(dir.join("arm.md")).unwrap();
    let g = r.governing.as_ref().unwrap();
    assert!(md.contains("Verdict") && md.contains(&g.label) && md.contains("arm_arm.svg"));
    // the log: one scene, one joint state and one message per point per logged sample (at most
    // 50 a second, the first and the last among them; this 10 Hz move keeps every sample)
    let bytes = std::fs::read(dir.join("arm.mcap")).unwrap();
    let messages: Vec<_> = mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(|m| m.unwrap())
        .collect();
    let times: Vec<f64> = r.samples.iter().map(|s| s.time_s).collect();
    let logged = flexrig::arm::log::logged_samples(&times, 50.0);
    assert_eq!(messages.len(), logged.len() * (2 + r.points.len()));
    let stamps: std::collections::BTreeSet<u64> = messages.iter().map(|m| m.log_time).collect();
    let ns = |t: f64| ((t - times[0]) * 1e9).round() as u64;
    assert_eq!(stamps.len(), logged.len());
    assert!(stamps.contains(&ns(times[0])) && stamps.contains(&ns(*times.last().unwrap())));
    let stamps: Vec<u64> = stamps.into_iter().collect();
    assert!(
        stamps.windows(2).all(|w| w[1] - w[0] >= 19_999_999),
        "{stamps:?}"
    );
    let layout: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("arm.layout.json")).unwrap())
            .unwrap();
    assert!(layout["configById"]["3D!arm"].is_object());
    // nothing is overwritten without force
    let e = outputs.check().unwrap_err().to_string();
    assert!(e.contains("--figure") && e.contains("--force"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
