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

#[test]
fn closed_form_closest_points_agree_with_parrys_ball_cuboid_query() {
    use parry3d_f64::query;
    use parry3d_f64::shape::{Ball, Cuboid};
    use rand::{Rng, SeedableRng};
    // The callback's closed form (projection of the dome's centre on the block) against parry's
    // general query, bit for bit, for the dome's centre in front of faces, edges and corners of a
    // rotated, offset block, apart and overlapping (also inside the block, where parry answers).
    let radius = 0.0715;
    let half = Vector::new(0.02, 0.025, 0.03);
    let dome_offset = Pose::from_translation(Vector::new(0.01, 0.0715, -0.005));
    let block_offset = Pose::new(Vector::new(0.0, 0.0, -0.3), Vector::new(0.1, -0.2, 0.05));
    let c = DomeBlockContact::new(
        radius,
        dome_offset,
        half,
        block_offset,
        Box::new(Hertz::new(7.359e7, 1.5).unwrap()),
    )
    .unwrap();
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let mut touching = 0;
    for _ in 0..2000 {
        let block = Pose::new(
            Vector::new(
                rng.random_range(-0.1..0.1),
                rng.random_range(-0.1..0.1),
                rng.random_range(0.2..0.4),
            ),
            Vector::new(
                rng.random_range(-0.5..0.5),
                rng.random_range(-0.5..0.5),
                rng.random_range(-0.5..0.5),
            ),
        );
        let dome = Pose::new(
            Vector::ZERO,
            Vector::new(0.0, 0.0, rng.random_range(-0.5..0.5)),
        );
        let reference = query::contact(
            &(dome * dome_offset),
            &Ball::new(radius),
            &(block * block_offset),
            &Cuboid::new(half),
            f64::MAX,
        )
        .unwrap()
        .unwrap();
        assert_eq!(c.gap(&dome, &block), reference.dist, "gap: bit for bit");
        let (dome_k, block_k) = (
            BodyKinematics {
                angvel: Vector::new(0.0, 0.0, 1.3),
                ..still(dome)
            },
            BodyKinematics {
                linvel: Vector::new(0.2, -0.4, 0.1),
                angvel: Vector::new(0.7, 0.0, 0.0),
                ..still(block)
            },
        );
        let point = (reference.point1 + reference.point2) * 0.5;
        let rate = (dome_k.velocity_at(point) - block_k.velocity_at(point)).dot(reference.normal1);
        let (gap, approach) = c.approach(&dome_k, &block_k).unwrap();
        assert_eq!(gap, reference.dist, "approach gap");
        assert_eq!(approach, rate, "approach rate");
        match c.evaluate(&dome_k, &block_k) {
            Some(s) => {
                touching += 1;
                assert!(reference.dist < 0.0);
                assert_eq!(s.indentation, -reference.dist, "δ");
                assert_eq!(s.normal, reference.normal1, "normal");
                assert_eq!(s.point, point, "point");
                assert_eq!(s.rate, rate, "δ̇");
            }
            None => assert!(reference.dist >= 0.0),
        }
        // the direct sequence of operations: the same to round-off
        assert_abs(
            "direct gap",
            c.gap_direct(&dome, &block),
            reference.dist,
            1e-15,
        );
        let (gap, approach) = c.approach_direct(&dome_k, &block_k).unwrap();
        assert_abs("direct approach gap", gap, reference.dist, 1e-15);
        assert_abs("direct approach rate", approach, rate, 1e-13);
        match c.evaluate_direct(&dome_k, &block_k) {
            Some(s) => {
                assert!(reference.dist < 0.0);
                assert_abs("direct δ", s.indentation, -reference.dist, 1e-15);
                assert_abs(
                    "direct normal",
                    (s.normal - reference.normal1).length(),
                    0.0,
                    1e-13,
                );
                assert_abs("direct point", (s.point - point).length(), 0.0, 1e-15);
                assert_abs("direct δ̇", s.rate, rate, 1e-13);
            }
            None => assert!(reference.dist >= 0.0),
        }
    }
    assert!(touching > 100, "only {touching} of the poses overlap");
}
