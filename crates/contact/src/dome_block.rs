//! The contact callback the test rig calls each step: a spherical dome (on the robot's payload)
//! against a skinned cuboid block (on the operator's pendulum), with the penetration from
//! parry3d-f64 and the force from any [`ContactLaw`].
//!
//! Conventions: the normal `n` points from the dome into the block; the indentation is
//! δ = −(signed distance) ≥ 0 in contact; its rate is δ̇ = (v_dome − v_block)·n at the contact
//! point. The force on the block is +f n and on the dome −f n, both applied at the contact point
//! (the midpoint of the two surface points). The closest points are computed in closed form in
//! the block's frame (the dome's centre projected on the cuboid: a clamp of each coordinate to
//! the half extents) by the operations of parry's ball–cuboid query, bit for bit, which itself
//! answers the one case the clamp does not cover (the dome's centre inside the block).

use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query;
use parry3d_f64::shape::{Ball, Cuboid};

use crate::{ContactError, ContactLaw, validate};

/// Pose and velocity of a rigid body (or of a beam node's section).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyKinematics {
    /// Pose of the body frame in the world.
    pub pose: Pose,
    /// Point [m, world] whose velocity is `linvel` (e.g. the centre of mass).
    pub reference_point: Vector,
    /// Velocity of `reference_point` [m/s, world].
    pub linvel: Vector,
    /// Angular velocity [rad/s, world].
    pub angvel: Vector,
}

impl BodyKinematics {
    /// Velocity [m/s] of the body point at world position `p`.
    pub fn velocity_at(&self, p: Vector) -> Vector {
        self.linvel + self.angvel.cross(p - self.reference_point)
    }
}

/// One evaluation of the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSample {
    /// Indentation δ ≥ 0 \[m\].
    pub indentation: f64,
    /// Indentation rate δ̇ [m/s] (> 0 while approaching).
    pub rate: f64,
    /// Force magnitude f ≥ 0 \[N\].
    pub force: f64,
    /// Unit normal from the dome into the block (direction of the force on the block).
    pub normal: Vector,
    /// Where the force acts [m, world].
    pub point: Vector,
}

impl ContactSample {
    /// Force on the block [N, world]: +f n.
    pub fn force_on_block(&self) -> Vector {
        self.normal * self.force
    }

    /// Force on the dome [N, world]: −f n.
    pub fn force_on_dome(&self) -> Vector {
        -self.normal * self.force
    }
}

/// A contact model the rig calls each step (no global state; one per simulation).
pub trait ContactCallback: Send + Sync + std::fmt::Debug {
    /// Signed gap between the surfaces \[m\] (negative when penetrating); used to predict onset.
    fn gap(&self, dome: &Pose, block: &Pose) -> f64;

    /// The contact force, or `None` when the surfaces do not touch.
    fn evaluate(&self, dome: &BodyKinematics, block: &BodyKinematics) -> Option<ContactSample>;
}

/// A spherical dome of radius `radius` against a cuboid block, with a contact law.
#[derive(Debug)]
pub struct DomeBlockContact {
    dome: Ball,
    dome_offset: Pose,
    block: Cuboid,
    block_offset: Pose,
    law: Box<dyn ContactLaw>,
}

impl DomeBlockContact {
    /// Dome of radius `dome_radius` \[m\] centred at `dome_offset` in the dome body's frame; block
    /// with half extents `block_half_extents` \[m\] centred at `block_offset` in the block body's
    /// frame.
    pub fn new(
        dome_radius: f64,
        dome_offset: Pose,
        block_half_extents: Vector,
        block_offset: Pose,
        law: Box<dyn ContactLaw>,
    ) -> Result<Self, ContactError> {
        validate::positive("dome_radius", dome_radius)?;
        for (name, v) in [
            ("block_half_extents.x", block_half_extents.x),
            ("block_half_extents.y", block_half_extents.y),
            ("block_half_extents.z", block_half_extents.z),
        ] {
            validate::positive(name, v)?;
        }
        Ok(DomeBlockContact {
            dome: Ball::new(dome_radius),
            dome_offset,
            block: Cuboid::new(block_half_extents),
            block_offset,
            law,
        })
    }

    /// Centre of the dome's sphere [m, world] when the dome body is at `dome`.
    pub fn dome_center(&self, dome: &Pose) -> Vector {
        (*dome * self.dome_offset).translation
    }

    /// The signed gap \[m\] between the surfaces (negative when penetrating) and the approach
    /// rate [m/s] (δ̇ of [`ContactSample`], > 0 when closing) along the normal through the closest
    /// points, touching or not; `None` if the bodies are too far apart for a query.
    pub fn approach(&self, dome: &BodyKinematics, block: &BodyKinematics) -> Option<(f64, f64)> {
        let c = self.closest(&dome.pose, &block.pose)?;
        Some((c.dist, c.closing_rate(dome, block)))
    }

    /// The contact law.
    pub fn law(&self) -> &dyn ContactLaw {
        self.law.as_ref()
    }

    /// The signed distance between the surfaces, the normal (dome → block) and the midpoint of
    /// the two closest surface points, all in the world: with c the dome's centre in the block's
    /// frame and q its projection on the cuboid (each coordinate clamped to ±the half extent),
    /// d = |c − q| − R, n = (q − c)/|c − q|, the points q and c + R n. The operations are
    /// parry's ball–cuboid query's, in its order (the same numbers to the last bit), without
    /// its dispatch and feature bookkeeping; when c lies inside the block parry answers.
    fn closest(&self, dome: &Pose, block: &Pose) -> Option<Closest> {
        let dome_pose = *dome * self.dome_offset;
        let block_pose = *block * self.block_offset;
        // the dome's pose in the block's frame, as parry forms it
        let pos21 = dome_pose.inv_mul(&block_pose).inverse();
        let center = pos21.translation;
        let half = self.block.half_extents;
        let shift = (-half - center).max(Vector::ZERO) - (center - half).max(Vector::ZERO);
        if shift != Vector::ZERO {
            let (dir, len) = ((center + shift) - center).normalize_and_length();
            if len >= parry3d_f64::math::DEFAULT_EPSILON {
                let normal_dome = pos21.rotation.inverse() * dir;
                let on_dome = dome_pose * (normal_dome * self.dome.radius);
                let on_block = block_pose * (center + shift);
                return Some(Closest {
                    dist: len - self.dome.radius,
                    normal: dome_pose.rotation * normal_dome,
                    point: (on_dome + on_block) * 0.5,
                });
            }
        }
        // Ball–cuboid is always supported by the default dispatcher.
        let c = query::contact(&dome_pose, &self.dome, &block_pose, &self.block, f64::MAX)
            .ok()
            .flatten()?;
        Some(Closest {
            dist: c.dist,
            normal: c.normal1,
            point: (c.point1 + c.point2) * 0.5,
        })
    }

    /// The closest points as [`Self::closest`] by the shortest sequence of operations: the
    /// dome's centre transformed into the block's frame directly (one rotation less, no pose
    /// products); equal to it to round-off (1e-15 m, tested). For integrators that evaluate the
    /// contact many times a step and owe no bit-for-bit history to parry's order.
    fn closest_direct(&self, dome: &Pose, block: &Pose) -> Option<Closest> {
        let dome_center = dome.transform_point(self.dome_offset.translation);
        let block_pose = *block * self.block_offset;
        let center = block_pose.inverse_transform_point(dome_center);
        let half = self.block.half_extents;
        let q = center.clamp(-half, half);
        let (dir, len) = (q - center).normalize_and_length();
        if q != center && len >= parry3d_f64::math::DEFAULT_EPSILON {
            let normal = block_pose.rotation * dir;
            return Some(Closest {
                dist: len - self.dome.radius,
                normal,
                point: (dome_center + normal * self.dome.radius + block_pose.transform_point(q))
                    * 0.5,
            });
        }
        self.closest(dome, block)
    }

    /// [`ContactCallback::evaluate`] with the closest points of [`Self::closest_direct`].
    pub fn evaluate_direct(
        &self,
        dome: &BodyKinematics,
        block: &BodyKinematics,
    ) -> Option<ContactSample> {
        self.sample(self.closest_direct(&dome.pose, &block.pose)?, dome, block)
    }

    /// [`ContactCallback::gap`] with the closest points of [`Self::closest_direct`].
    pub fn gap_direct(&self, dome: &Pose, block: &Pose) -> f64 {
        self.closest_direct(dome, block)
            .map_or(f64::INFINITY, |c| c.dist)
    }

    /// [`Self::approach`] with the closest points of [`Self::closest_direct`].
    pub fn approach_direct(
        &self,
        dome: &BodyKinematics,
        block: &BodyKinematics,
    ) -> Option<(f64, f64)> {
        let c = self.closest_direct(&dome.pose, &block.pose)?;
        Some((c.dist, c.closing_rate(dome, block)))
    }

    /// The contact sample of the closest points `c`, if the surfaces overlap.
    fn sample(
        &self,
        c: Closest,
        dome: &BodyKinematics,
        block: &BodyKinematics,
    ) -> Option<ContactSample> {
        if !(c.dist < 0.0) {
            return None;
        }
        let indentation = -c.dist;
        let rate = c.closing_rate(dome, block);
        Some(ContactSample {
            indentation,
            rate,
            force: self.law.force(indentation, rate),
            normal: c.normal,
            point: c.point,
        })
    }
}

/// The closest points of the dome and the block.
#[derive(Debug, Clone, Copy)]
struct Closest {
    /// Signed distance \[m\] (negative when penetrating).
    dist: f64,
    /// Unit normal from the dome into the block (world).
    normal: Vector,
    /// Midpoint of the two closest surface points [m, world].
    point: Vector,
}

impl Closest {
    /// The rate of approach δ̇ = (v_dome − v_block)·n at the midpoint [m/s] (> 0 closing).
    fn closing_rate(&self, dome: &BodyKinematics, block: &BodyKinematics) -> f64 {
        (dome.velocity_at(self.point) - block.velocity_at(self.point)).dot(self.normal)
    }
}

impl ContactCallback for DomeBlockContact {
    fn gap(&self, dome: &Pose, block: &Pose) -> f64 {
        match self.closest(dome, block) {
            Some(c) => c.dist,
            None => f64::INFINITY,
        }
    }

    fn evaluate(&self, dome: &BodyKinematics, block: &BodyKinematics) -> Option<ContactSample> {
        self.sample(self.closest(&dome.pose, &block.pose)?, dome, block)
    }
}
