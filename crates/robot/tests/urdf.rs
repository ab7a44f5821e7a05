//! Loading URDF: what the bundled arms hold, and every refusal — unsupported elements, broken
//! topology, non-physical numbers, hostile files — as an error naming the element and its line,
//! never a panic, in bounded memory.

mod common;

use common::bundled;
use flexrig_robot::{JointKind, MAX_LINKS, MAX_URDF_BYTES, Robot, RobotError};

fn err(text: &str) -> RobotError {
    Robot::from_urdf_str(text, "test.urdf").unwrap_err()
}

/// The error's message, checked to be plain words: no Rust debug text.
fn message(text: &str) -> String {
    let m = err(text).to_string();
    for debug in ["Some(", "None", "Urdf {", "RobotError", "\\\""] {
        assert!(!m.contains(debug), "debug text in {m:?}");
    }
    m
}

const LINK_A: &str = r#"<link name="a"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>"#;

fn robot_with(body: &str) -> String {
    format!("<robot name=\"r\">\n<link name=\"base\"/>\n{body}\n</robot>")
}

#[test]
fn bundled_arms_load_as_published() {
    let ur5 = bundled("ur5");
    assert_eq!(ur5.name(), "ur5");
    assert_eq!(
        ur5.joint_names(),
        [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint"
        ]
    );
    // The base link (4 kg) is immobile; the moving links weigh 3.7 + 8.393 + 2.275 + 3 × 1.219
    // (wrist 1 and 2) + 0.1879 kg.
    let moving = 3.7 + 8.393 + 2.275 + 1.219 + 1.219 + 0.1879;
    assert!((ur5.moving_mass() - moving).abs() < 1e-12);
    assert_eq!(ur5.bodies()[0].link(), "world");
    assert!(ur5.joints().iter().all(|j| j.kind() == JointKind::Revolute));
    // The file gives π to 12 digits.
    assert_eq!(
        ur5.joints()[2].lower(),
        "-3.14159265359".parse::<f64>().unwrap()
    );
    let panda = bundled("panda");
    assert_eq!(panda.dof(), 7);
    // The hand (0.73 kg) and the two fingers (0.015 kg each) are merged into link 7.
    assert!((panda.bodies()[7].inertia().mass - (0.735522 + 0.73 + 0.03)).abs() < 1e-12);
    assert_eq!(panda.link("panda_hand_tcp").unwrap().body(), 7);
    assert_eq!(panda.joints()[3].upper(), -0.0698);
}

#[test]
fn unsupported_joints_are_refused_with_their_line() {
    let m = message(&robot_with(&format!(
        "{LINK_A}\n<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/>\n<limit lower=\"-1\" upper=\"1\"/>\n<mimic joint=\"k\"/></joint>"
    )));
    assert!(
        m.contains("line 7") && m.contains("joint \"j\"") && m.contains("<mimic>"),
        "{m}"
    );
    for kind in ["floating", "planar"] {
        let m = message(&robot_with(&format!(
            "{LINK_A}\n<joint name=\"free\" type=\"{kind}\"><parent link=\"base\"/><child link=\"a\"/></joint>"
        )));
        assert!(
            m.contains("line 5") && m.contains("joint \"free\"") && m.contains(kind),
            "{m}"
        );
        assert!(
            m.contains("revolute, continuous, prismatic and fixed"),
            "{m}"
        );
    }
    let m = message(&robot_with(&format!(
        "{LINK_A}\n<joint name=\"j\" type=\"hinge\"><parent link=\"base\"/><child link=\"a\"/></joint>"
    )));
    assert!(m.contains("unknown type \"hinge\""), "{m}");
    let m = message(&robot_with(&format!(
        "{LINK_A}\n<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/></joint>"
    )));
    assert!(m.contains("needs <limit"), "{m}");
    let m = message(&robot_with(&format!(
        "{LINK_A}\n<joint name=\"j\" type=\"prismatic\"><parent link=\"base\"/><child link=\"a\"/>\n<limit lower=\"1\" upper=\"-1\"/></joint>"
    )));
    assert!(
        m.contains("line 6") && m.contains("lower must be ≤ upper"),
        "{m}"
    );
    let m = message(&robot_with(&format!(
        "{LINK_A}\n<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"a\"/>\n<axis xyz=\"0 0 0\"/></joint>"
    )));
    assert!(m.contains("line 6") && m.contains("non-zero length"), "{m}");
}

#[test]
fn topology_errors_name_the_links_and_lines() {
    let joint = |name: &str, p: &str, c: &str| {
        format!(
            "<joint name=\"{name}\" type=\"fixed\"><parent link=\"{p}\"/><child link=\"{c}\"/></joint>"
        )
    };
    // Two parents: a closed loop.
    let m = message(&robot_with(&format!(
        "{LINK_A}\n<link name=\"b\"/>\n{}\n{}\n{}",
        joint("j1", "base", "a"),
        joint("j2", "base", "b"),
        joint("j3", "b", "a")
    )));
    assert!(m.contains("line 8") && m.contains("joint \"j3\""), "{m}");
    assert!(
        m.contains("already has the parent joint \"j1\" (line 6)") && m.contains("closed loops"),
        "{m}"
    );
    // Unknown names.
    let m = message(&robot_with(&format!(
        "{LINK_A}\n{}",
        joint("j", "base", "hand")
    )));
    assert!(
        m.contains("child link \"hand\" is not a <link>") && m.contains("line 5"),
        "{m}"
    );
    let m = message(&robot_with(&format!(
        "{LINK_A}\n{}",
        joint("j", "bse", "a")
    )));
    assert!(m.contains("parent link \"bse\""), "{m}");
    // Several roots.
    let m = message(&robot_with(&format!("{LINK_A}\n<link name=\"c\"/>")));
    assert!(
        m.contains("3 root links") && m.contains("\"c\" (line 5)"),
        "{m}"
    );
    // Cycles: all links in one, and one beside a proper root, and a self-loop.
    let m = message(&format!(
        "<robot name=\"r\">\n<link name=\"x\"/>\n<link name=\"y\"/>\n{}\n{}\n</robot>",
        joint("xy", "x", "y"),
        joint("yx", "y", "x")
    ));
    assert!(
        m.contains("cycle") && m.contains("link \"x\"") && m.contains("line 2"),
        "{m}"
    );
    let m = message(&robot_with(&format!(
        "<link name=\"x\"/>\n<link name=\"y\"/>\n{}\n{}",
        joint("xy", "x", "y"),
        joint("yx", "y", "x")
    )));
    assert!(
        m.contains("cannot be reached from the root link \"base\"") && m.contains("cycle"),
        "{m}"
    );
    let m = message(&robot_with(&joint("self", "base", "base")));
    assert!(m.contains("to itself"), "{m}");
    // Duplicate names.
    let m = message(&robot_with(&format!("{LINK_A}\n<link name=\"base\"/>")));
    assert!(
        m.contains("second link") && m.contains("line 2") && m.contains("line 5"),
        "{m}"
    );
    // No links; the wrong root element.
    assert!(message("<robot name=\"r\"/>").contains("has no <link>"));
    assert!(message("<sdf/>").contains("root element of a URDF must be <robot>"));
}

#[test]
fn moving_links_without_mass_are_refused() {
    let m = message(&robot_with(
        "<link name=\"a\"/>\n<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"a\"/></joint>",
    ));
    assert!(
        m.contains("link \"a\"") && m.contains("line 3") && m.contains("has no <inertial>"),
        "{m}"
    );
    assert!(m.contains("joint \"j\" (line 4)"), "{m}");
    let m = message(&robot_with(
        "<link name=\"a\"><inertial><mass value=\"0\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link>\n<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"a\"/></joint>",
    ));
    assert!(m.contains("zero mass"), "{m}");
    // A massless moving link carrying a massive fixed child is a body with mass: accepted.
    let ok = robot_with(&format!(
        "<link name=\"carrier\"/>\n{LINK_A}\n<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"carrier\"/></joint>\n<joint name=\"f\" type=\"fixed\"><parent link=\"carrier\"/><child link=\"a\"/></joint>"
    ));
    assert_eq!(
        Robot::from_urdf_str(&ok, "ok.urdf").unwrap().moving_mass(),
        1.0
    );
}

#[test]
fn non_physical_numbers_are_refused() {
    let inertial = |mass: &str, i: [&str; 6], origin: &str| {
        format!(
            "<link name=\"a\">\n<inertial>{origin}<mass value=\"{mass}\"/>\n<inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/></inertial></link>\n<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"a\"/></joint>",
            i[0], i[1], i[2], i[3], i[4], i[5]
        )
    };
    let good = ["0.01", "0", "0", "0.01", "0", "0.01"];
    let m = message(&robot_with(&inertial("-1", good, "")));
    assert!(
        m.contains("line 4") && m.contains("mass value=\"-1\"") && m.contains("≥ 0 kg"),
        "{m}"
    );
    for bad in ["NaN", "inf", "-infinity"] {
        let m = message(&robot_with(&inertial(bad, good, "")));
        assert!(
            m.contains("not a finite number") && m.contains("link \"a\""),
            "{m}"
        );
    }
    let m = message(&robot_with(&inertial(
        "1",
        ["0.01", "0", "0", "0.01", "0", "1e400"],
        "",
    )));
    assert!(
        m.contains("izz=\"1e400\"") && m.contains("not a finite number"),
        "{m}"
    );
    let m = message(&robot_with(&inertial(
        "1",
        ["0.01", "0", "0", "0.01", "0", "abc"],
        "",
    )));
    assert!(m.contains("not a number"), "{m}");
    // Not positive semi-definite (a product of inertia larger than the moments).
    let m = message(&robot_with(&inertial(
        "1",
        ["0.01", "0.05", "0", "0.01", "0", "0.01"],
        "",
    )));
    assert!(
        m.contains("line 5") && m.contains("not positive semi-definite"),
        "{m}"
    );
    // The triangle inequality: 0.01 + 0.01 < 0.05.
    let m = message(&robot_with(&inertial(
        "1",
        ["0.01", "0", "0", "0.01", "0", "0.05"],
        "",
    )));
    assert!(m.contains("triangle inequality"), "{m}");
    // NaN in an origin; two numbers where three are needed.
    let m = message(&robot_with(&inertial(
        "1",
        good,
        "<origin xyz=\"0 nan 0\"/>",
    )));
    assert!(
        m.contains("xyz") && m.contains("not a finite number"),
        "{m}"
    );
    let m = message(&robot_with(&inertial("1", good, "<origin rpy=\"0 0\"/>")));
    assert!(m.contains("three numbers"), "{m}");
    // Missing pieces.
    let m = message(&robot_with(
        "<link name=\"a\"><inertial><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>",
    ));
    assert!(m.contains("no <mass"), "{m}");
    let m = message(&robot_with(&format!("{LINK_A}\n<joint type=\"fixed\"/>")));
    assert!(m.contains("<joint>") && m.contains("no name"), "{m}");
}

#[test]
fn hostile_files_fail_cleanly_in_bounded_memory() {
    // Not XML, and an entity bomb (DTDs are refused).
    assert!(matches!(
        err("<robot><link name=\"a\"></robot>"),
        RobotError::Xml { line: 1, .. }
    ));
    let bomb = "<?xml version=\"1.0\"?><!DOCTYPE lolz [<!ENTITY lol \"lol\"><!ENTITY lol2 \"&lol;&lol;&lol;&lol;\">]><robot name=\"&lol2;\"/>";
    assert!(matches!(err(bomb), RobotError::Xml { .. }));
    // Deep nesting: a hundred thousand nested elements inside a link.
    let depth = 100_000;
    let deep = format!(
        "<robot name=\"r\"><link name=\"base\">{}{}</link></robot>",
        "<x>".repeat(depth),
        "</x>".repeat(depth)
    );
    let m = message(&deep);
    assert!(
        m.contains("more than 256 deep") && m.contains("line 1"),
        "{m}"
    );
    // Nesting up to the limit parses.
    let ok = format!(
        "<robot name=\"r\"><link name=\"base\">{}{}</link></robot>",
        "<x>".repeat(250),
        "</x>".repeat(250)
    );
    assert_eq!(Robot::from_urdf_str(&ok, "ok.urdf").unwrap().dof(), 0);
    // Too many links.
    let many: String = (0..=MAX_LINKS)
        .map(|i| format!("<link name=\"l{i}\"/>\n"))
        .collect();
    let m = message(&format!("<robot name=\"r\">\n{many}</robot>"));
    assert!(
        m.contains(&format!("more than {MAX_LINKS} links"))
            && m.contains(&format!("line {}", MAX_LINKS + 2)),
        "{m}"
    );
    // Too many XML tags.
    let tags = "<a/>".repeat(1_000_001);
    let m = message(&format!("<robot name=\"r\">{tags}</robot>"));
    assert!(m.contains("XML tags"), "{m}");
    // A 10 MB file (a long comment) loads; a file over the cap is refused before reading.
    let dir = std::env::temp_dir().join(format!("flexrig-robot-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ten = dir.join("ten_mb.urdf");
    let comment = "x".repeat(10 * 1024 * 1024);
    std::fs::write(
        &ten,
        format!("<robot name=\"r\"><!-- {comment} --><link name=\"base\"/></robot>"),
    )
    .unwrap();
    assert_eq!(Robot::from_urdf_file(&ten).unwrap().dof(), 0);
    let big = dir.join("big.urdf");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(MAX_URDF_BYTES + 1).unwrap();
    let e = Robot::from_urdf_file(&big).unwrap_err();
    assert!(matches!(e, RobotError::FileTooLarge { .. }), "{e}");
    assert!(
        e.to_string()
            .contains(&format!("at most {MAX_URDF_BYTES} bytes"))
    );
    let e = Robot::from_urdf_file(dir.join("missing.urdf")).unwrap_err();
    assert!(
        matches!(e, RobotError::Io { .. }) && e.to_string().contains("missing.urdf"),
        "{e}"
    );
    std::fs::write(&ten, [0xff, 0xfe, 0x00]).unwrap();
    assert!(
        Robot::from_urdf_file(&ten)
            .unwrap_err()
            .to_string()
            .contains("UTF-8")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn arbitrary_text_never_panics() {
    use proptest::prelude::*;
    let valid = std::fs::read_to_string(common::root().join("assets/robots/panda.urdf")).unwrap();
    let mut runner = proptest::test_runner::TestRunner::new(proptest::test_runner::Config {
        cases: 300,
        ..Default::default()
    });
    // Random cuts and byte substitutions of a real URDF, and random text.
    runner
        .run(
            &(0..valid.len(), 0..valid.len(), any::<u8>(), ".{0,200}"),
            |(a, b, byte, junk)| {
                let (lo, hi) = (a.min(b), a.max(b));
                let cut = format!("{}{}", &valid[..lo], &valid[hi..]);
                let _ = Robot::from_urdf_str(&cut, "cut.urdf");
                let mut bytes = valid.clone().into_bytes();
                bytes[lo] = byte;
                if let Ok(text) = String::from_utf8(bytes) {
                    let _ = Robot::from_urdf_str(&text, "byte.urdf");
                }
                let _ = Robot::from_urdf_str(&junk, "junk.urdf");
                Ok(())
            },
        )
        .unwrap();
}
