//! The dome–block callback against hand-computed geometry.

use flexrig_contact::math::{Pose, Vector};
use flexrig_contact::tolerance::{assert_abs, assert_close};
use flexrig_contact::{BodyKinematics, ContactCallback, ContactLaw, DomeBlockContact, Hertz};

fn still(pose: Pose) -> BodyKinematics {
    BodyKinematics {
        pose,
        reference_point: pose.translation,
        linvel: Vector::ZERO,
        angvel: Vector::ZERO,
    }
}

fn callback() -> DomeBlockContact {
    // Dome of radius 71.5 mm whose centre sits 71.5 mm behind the dome body's origin along +y, so
    // its apex is at the body origin facing −y; a 50 mm cube block.
    DomeBlockContact::new(
        0.0715,
        Pose::from_translation(Vector::new(0.0, 0.0715, 0.0)),
        Vector::splat(0.025),
        Pose::IDENTITY,
        Box::new(Hertz::new(7.359e7, 1.961).unwrap()),
    )
    .unwrap()
}

#[test]
fn indentation_normal_and_force_of_a_face_contact() {
    let c = callback();
    let law = Hertz::new(7.359e7, 1.961).unwrap();
    // Block centred at y = −0.025 + δ: its +y face at y = δ overlaps the apex (y = 0) by δ.
    for delta in [1e-6, 1e-4, 2e-3] {
        let block = still(Pose::from_translation(Vector::new(
            0.0,
            -0.025 + delta,
            0.0,
        )));
        let dome = still(Pose::IDENTITY);
        let s = c.evaluate(&dome, &block).expect("in contact");
        assert_close("δ", s.indentation, delta, 1e-9);
        assert_abs(
            "normal",
            (s.normal - Vector::new(0.0, -1.0, 0.0)).length(),
            0.0,
            1e-12,
        );
        assert_close("f = law(δ)", s.force, law.force(delta, 0.0), 1e-8);
        assert_close("gap", c.gap(&dome.pose, &block.pose), -delta, 1e-9);
        assert_abs(
            "force on block along −y",
            s.force_on_block().y,
            -s.force,
            1e-9,
        );
        assert_abs(
            "equal and opposite",
            (s.force_on_block() + s.force_on_dome()).length(),
            0.0,
            0.0,
        );
    }
    // Separated by 1 mm: no contact, gap +1 mm.
    let block = still(Pose::from_translation(Vector::new(0.0, -0.026, 0.0)));
    assert!(c.evaluate(&still(Pose::IDENTITY), &block).is_none());
    assert_close("gap", c.gap(&Pose::IDENTITY, &block.pose), 1e-3, 1e-9);
}

#[test]
fn rate_is_the_approach_speed_at_the_contact_point() {
    let c = callback();
    let block_pose = Pose::from_translation(Vector::new(0.0, -0.025 + 1e-4, 0.0));
    // Dome moving towards the block (−y) at 0.3 m/s, block moving towards the dome at 0.5 m/s.
    let dome = BodyKinematics {
        linvel: Vector::new(0.0, -0.3, 0.0),
        ..still(Pose::IDENTITY)
    };
    let block = BodyKinematics {
        linvel: Vector::new(0.0, 0.5, 0.0),
        ..still(block_pose)
    };
    let s = c.evaluate(&dome, &block).unwrap();
    assert_close("δ̇", s.rate, 0.8, 1e-12);
    // A rotation of the block about its own centre adds ω × r at the contact point (the block is
    // shifted 10 mm along x so that r is not parallel to the normal).
    let block_pose = Pose::from_translation(Vector::new(0.01, -0.025 + 1e-4, 0.0));
    let block = BodyKinematics {
        angvel: Vector::new(0.0, 0.0, 2.0),
        ..still(block_pose)
    };
    let s = c.evaluate(&still(Pose::IDENTITY), &block).unwrap();
    let r = s.point - block_pose.translation;
    let v = Vector::new(0.0, 0.0, 2.0).cross(r);
    assert_close("δ̇ from rotation", s.rate, -v.dot(s.normal), 1e-12);
    assert_close("δ̇ = −(ω × r)·n = −0.02 m/s", s.rate, -0.02, 1e-6);
}

#[test]
fn invalid_geometry_is_rejected() {
    let law = || Box::new(Hertz::new(1e7, 2.0).unwrap()) as Box<dyn ContactLaw>;
    assert!(
        DomeBlockContact::new(
            0.0,
            Pose::IDENTITY,
            Vector::splat(0.01),
            Pose::IDENTITY,
            law()
        )
        .is_err()
    );
    let e = DomeBlockContact::new(
        0.07,
        Pose::IDENTITY,
        Vector::new(0.01, -1.0, 0.01),
        Pose::IDENTITY,
        law(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("block_half_extents.y"), "{e}");
}
