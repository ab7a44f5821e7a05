//! MCAP logs of rig runs that open well in Foxglove (see `docs/foxglove.md`).
//!
//! Written with the raw `mcap::Writer` (every write reports its I/O error at once) fed with the
//! Foxglove SDK's protobuf message types and our own `#[derive(Encode)]` messages. Time is the
//! simulation time from 0, in ns, in `log_time`, `publish_time` and every message's own
//! timestamp. Inside the contact window every step is logged on `/contact`, every sensor sample,
//! and the 3D channels (`/tf`, `/scene`, with `/energy`) at 10 kHz; outside it the scalar channels
//! are decimated to 250 Hz and the 3D channels to 60 Hz ([`LogRates::DECIMATED`]; every step with
//! [`LogRates::EVERY_STEP`]). Chunks are indexed but not compressed:
//! LZ4 took 57 % of the logging instructions (zstd 2.5× more time than LZ4) and protobuf doubles
//! compress poorly; an uncompressed bundled run is 0.23–0.25 MB. The scene file is attached;
//! key parameters, the software version and the git revision are metadata. The file is always
//! finished: [`McapRecorder::finish`] closes it, with an `error` metadata record when the run
//! failed, and [`run_logged`] writes it under a temporary name that is renamed into place only
//! when finished (a full disk leaves no half-written file under the requested name).

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use flexrig_contact::math::{Pose, Vector};
use flexrig_rig::sensors::SensorSample;
use flexrig_rig::{Frame, Recorder, RigError, RunSummary, Scene, SwingSamples};
use foxglove::Encode;
use foxglove::messages::{
    ArrowPrimitive, Color, CubePrimitive, FrameTransform, FrameTransforms, JointState, JointStates,
    KeyValuePair, LinePrimitive, Point3, Quaternion, SceneEntity, SceneUpdate, SpherePrimitive,
    TextPrimitive, Timestamp, Vector3, line_primitive::Type as LineType,
};

pub use crate::log::messages::*;

use crate::shared::cancel::CancelToken;

/// Channel ids of the log.
#[derive(Debug, Clone, Copy)]
struct Channels {
    tf: u16,
    scene: u16,
    force: u16,
    accel_operator: u16,
    accel_load: u16,
    encoders: u16,
    contact: u16,
    energy: u16,
    severity: u16,
    /// The drive on the robot joint (`robot.drive`): `/drive/joint` (the motor side),
    /// `/drive/command`, `/drive/torque`, `/drive/link` (the link after the spring) — the
    /// driven scenes' messages — and `/drive/load` (the link's moment on the hub, its
    /// deflection).
    drive: Option<DriveChannels>,
}

/// Channel ids of a test-bed drive's topics.
#[derive(Debug, Clone, Copy)]
struct DriveChannels {
    joint: u16,
    command: u16,
    torque: u16,
    link: u16,
    load: u16,
}

/// How often the channels are written. Inside the contact window `/contact` and the sensor
/// channels take every step and sample whatever the rates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LogRates {
    /// Period of the 3D channels (`/tf`, `/scene`) and `/energy` outside contact [ns].
    pub scene_period_ns: u64,
    /// Period of the 3D channels and `/energy` inside contact [ns].
    pub scene_period_contact_ns: u64,
    /// Period of the sensor channels outside contact [ns].
    pub scalar_period_ns: u64,
}

impl LogRates {
    /// The default: 3D at 60 Hz outside contact and 10 kHz inside (about 40 frames across a
    /// pulse; the plots read the full-rate scalar channels), sensors at 250 Hz outside contact
    /// (the swing is slow).
    pub const DECIMATED: LogRates = LogRates {
        scene_period_ns: 1_000_000_000 / 60,
        scene_period_contact_ns: 100_000,
        scalar_period_ns: 4_000_000,
    };
    /// Every step and every sensor sample on every channel (`flexrig run --log-every-step`).
    pub const EVERY_STEP: LogRates = LogRates {
        scene_period_ns: 0,
        scene_period_contact_ns: 0,
        scalar_period_ns: 0,
    };
}

/// A [`Recorder`] that writes an MCAP file.
pub struct McapRecorder<W: Write + Seek> {
    writer: mcap::Writer<W>,
    channels: Channels,
    sequence: u32,
    buffer: Vec<u8>,
    last_scene_ns: Option<u64>,
    last_scalar_ns: Option<u64>,
    /// The last sensor sample written or chosen ahead ([`Recorder::wants_swing_sample`]) [ns].
    last_chosen_ns: Option<u64>,
    geometry: flexrig_rig::geometry::RigGeometry,
    messages: u64,
    cancel: Option<CancelToken>,
    rates: LogRates,
    /// Factor on the FE beam's displacements in the 3D view (1: true scale).
    deformation_scale: f64,
    /// The link is the FE beam (CL), whose deflection the 3D view exaggerates.
    flexible_link: bool,
    /// What the simulation clock counts from, for its label ("the release", …).
    clock_origin: &'static str,
}

/// What time 0 of a run starting with `start` is, in words: the release, the first contact
/// (a run started at the contact) or the start of the motion (an operator already moving, or a
/// driven robot's start).
pub fn clock_origin(start: &flexrig_rig::scene::Start) -> &'static str {
    use flexrig_rig::scene::Start;
    match start {
        Start::Release { .. } => "the release",
        Start::Contact { .. } => "the first contact",
        Start::Moving { .. } => "the start",
    }
}

/// The factor on the FE beam's displacements in the 3D view by default: the CL link of the
/// bundled scenes deflects 0.3–0.6 mm at the force peak (invisible on a 338 mm link) and up to
/// 4.3 mm by separation; ×30 draws 9–17 mm at the peak and at most 128 mm (38 % of the link).
pub const DEFAULT_DEFORMATION_SCALE: f64 = 30.0;

impl<W: Write + Seek> std::fmt::Debug for McapRecorder<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapRecorder")
            .field("messages", &self.messages)
            .finish()
    }
}

fn io_error(e: mcap::McapError) -> RigError {
    RigError::Recorder(format!("MCAP write failed: {e}"))
}

fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

fn stamp(t: f64) -> Timestamp {
    let ns = nanos(t);
    Timestamp::new((ns / 1_000_000_000) as u32, (ns % 1_000_000_000) as u32)
}

fn vec3(v: Vector) -> Vector3 {
    Vector3 {
        x: v.x,
        y: v.y,
        z: v.z,
    }
}

fn point(v: Vector) -> Point3 {
    Point3 {
        x: v.x,
        y: v.y,
        z: v.z,
    }
}

fn pose(p: &Pose) -> foxglove::messages::Pose {
    let q = p.rotation;
    foxglove::messages::Pose {
        position: Some(vec3(p.translation)),
        orientation: Some(Quaternion {
            x: q.x,
            y: q.y,
            z: q.z,
            w: q.w,
        }),
    }
}

fn color(r: f64, g: f64, b: f64) -> Option<Color> {
    Some(Color { r, g, b, a: 1.0 })
}

/// A line strip `thickness` pixels wide.
fn line(points: Vec<Point3>, color: Option<Color>, thickness: f64) -> LinePrimitive {
    LinePrimitive {
        r#type: LineType::LineStrip as i32,
        pose: None,
        thickness,
        scale_invariant: true,
        points,
        color,
        colors: vec![],
        indices: vec![],
    }
}

/// The beam's nodes as drawn, reference + `scale` × displacement (the reference is the
/// undeformed axis, node i at (xᵢ, 0, 0)) \[m, world\], and the true transverse deflection
/// of the tip \[m\].
fn drawn_beam(beam: &flexrig_rig::BeamLink, scale: f64) -> (Vec<Point3>, f64) {
    let model = beam.model();
    let nodes = beam.node_positions();
    let tip_m = nodes.last().map_or(0.0, |p| p.y);
    let points = nodes
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let reference = Vector::new(model.node_x(i), 0.0, 0.0);
            point(reference + (*p - reference) * scale)
        })
        .collect();
    (points, tip_m)
}

/// Where the link's label sits \[m, world\]: on the link's line, behind the robot axis, clear
/// of the CJ's drawn spring (30 mm around the axis).
const LABEL_AT: Vector = Vector::new(-0.055, 0.0, 0.0);
/// Where the simulation clock sits \[m, world\]: behind the robot axis, beyond the link's label.
const CLOCK_AT: Vector = Vector::new(-0.1, 0.0, 0.0);
/// The world direction that points down the screen in the layout's 3D view (the links hang
/// from their axes along +x as seen from above).
const VIEW_DOWN: Vector = Vector::new(1.0, 0.0, 0.0);

/// Length of the contact-force arrow per newton \[m/N\]: 0.3 mm/N keeps the bundled scenes'
/// peaks (up to about 280 N) under 85 mm, within the view.
pub const ARROW_M_PER_N: f64 = 3e-4;
/// Its head: length and diameter \[m\], fixed so that it stays visible at any force.
const ARROW_HEAD: (f64, f64) = (0.012, 0.012);

/// The contact-force arrow on the block (Okabe–Ito reddish purple: not the axes' red): along
/// `normal` (the force on the block), [`ARROW_M_PER_N`] long per newton (at least its head),
/// its head's tip at the contact `point` so that it pushes on the block from the dome's side
/// (seen through the translucent dome), and its label (the force in N) below the dome of
/// radius `dome_radius` \[m\] in the view, outside it (inside, the translucent sphere fades it).
fn force_arrow(
    point: Vector,
    normal: Vector,
    force: f64,
    dome_radius: f64,
) -> (Vec<ArrowPrimitive>, Vec<TextPrimitive>) {
    let length = (force * ARROW_M_PER_N).max(ARROW_HEAD.0);
    let rotation = arrow_rotation(normal);
    let purple = color(0.8, 0.475, 0.655);
    let tail = point - normal.normalize() * length;
    let arrow = ArrowPrimitive {
        pose: Some(pose(&Pose::from_parts(tail, rotation))),
        shaft_length: length - ARROW_HEAD.0,
        shaft_diameter: 0.004,
        head_length: ARROW_HEAD.0,
        head_diameter: ARROW_HEAD.1,
        color: purple,
    };
    let text = TextPrimitive {
        color: color(0.5, 0.2, 0.4),
        ..label(
            format!("contact force {force:.0} N"),
            point - normal.normalize() * dome_radius + VIEW_DOWN * (dome_radius + 0.012),
        )
    };
    (vec![arrow], vec![text])
}

/// A label at `at` \[m, world\], facing the camera, 15 px high.
fn label(text: String, at: Vector) -> TextPrimitive {
    TextPrimitive {
        pose: Some(pose(&Pose::from_translation(at))),
        billboard: true,
        font_size: 15.0,
        scale_invariant: true,
        color: color(0.1, 0.2, 0.6),
        text,
    }
}

impl<W: Write + Seek> McapRecorder<W> {
    /// Starts a log on `w`.
    pub fn new(w: W, scene: &Scene, scene_text: &str) -> Result<Self, mcap::McapError> {
        let mut writer = mcap::WriteOptions::new()
            .compression(None)
            .profile("")
            .library(format!("flexrig {}", env!("CARGO_PKG_VERSION")))
            .create(w)?;
        let mut channel = |topic: &str, schema: Option<foxglove::Schema>, encoding: String| {
            let schema = schema.expect("foxglove and derived messages have schemas");
            let id = writer.add_schema(&schema.name, &schema.encoding, &schema.data)?;
            writer.add_channel(id, topic, &encoding, &BTreeMap::new())
        };
        let channels = Channels {
            tf: channel(
                "/tf",
                FrameTransforms::get_schema(),
                FrameTransforms::get_message_encoding(),
            )?,
            scene: channel(
                "/scene",
                SceneUpdate::get_schema(),
                SceneUpdate::get_message_encoding(),
            )?,
            force: channel(
                "/sensors/force",
                ForceSensor::get_schema(),
                ForceSensor::get_message_encoding(),
            )?,
            accel_operator: channel(
                "/sensors/accel/operator",
                Accelerometer::get_schema(),
                Accelerometer::get_message_encoding(),
            )?,
            accel_load: channel(
                "/sensors/accel/load",
                Accelerometer::get_schema(),
                Accelerometer::get_message_encoding(),
            )?,
            encoders: channel(
                "/sensors/encoders",
                JointStates::get_schema(),
                JointStates::get_message_encoding(),
            )?,
            contact: channel(
                "/contact",
                ContactState::get_schema(),
                ContactState::get_message_encoding(),
            )?,
            energy: channel(
                "/energy",
                EnergyState::get_schema(),
                EnergyState::get_message_encoding(),
            )?,
            severity: {
                let id = writer.add_schema(
                    SEVERITY_SCHEMA_NAME,
                    "jsonschema",
                    SEVERITY_JSON_SCHEMA.as_bytes(),
                )?;
                writer.add_channel(id, "/severity", "json", &BTreeMap::new())?
            },
            drive: None,
        };
        let mut channels = channels;
        if scene.drive.is_some() {
            let mut channel = |topic: &str, schema: Option<foxglove::Schema>, encoding: String| {
                let schema = schema.expect("derived messages have schemas");
                let id = writer.add_schema(&schema.name, &schema.encoding, &schema.data)?;
                writer.add_channel(id, topic, &encoding, &BTreeMap::new())
            };
            channels.drive = Some(DriveChannels {
                joint: channel(
                    "/drive/joint",
                    JointMotion::get_schema(),
                    JointMotion::get_message_encoding(),
                )?,
                command: channel(
                    "/drive/command",
                    JointMotion::get_schema(),
                    JointMotion::get_message_encoding(),
                )?,
                torque: channel(
                    "/drive/torque",
                    MotorTorque::get_schema(),
                    MotorTorque::get_message_encoding(),
                )?,
                link: channel(
                    "/drive/link",
                    JointMotion::get_schema(),
                    JointMotion::get_message_encoding(),
                )?,
                load: channel(
                    "/drive/load",
                    LinkLoad::get_schema(),
                    LinkLoad::get_message_encoding(),
                )?,
            });
        }
        writer.attach(&mcap::Attachment {
            log_time: 0,
            create_time: 0,
            name: "scene.toml".into(),
            media_type: "application/toml".into(),
            data: std::borrow::Cow::Borrowed(scene_text.as_bytes()),
        })?;
        let f = &scene.file;
        let metadata: BTreeMap<String, String> = [
            ("software", format!("flexrig {}", env!("CARGO_PKG_VERSION"))),
            (
                "git_revision",
                option_env!("FLEXRIG_GIT_REVISION")
                    .unwrap_or("unknown")
                    .to_string(),
            ),
            ("scene", name_as_run(&f.name, f.robot.design)),
            ("scene_file_name", f.name.clone()),
            ("design", format!("{:?}", f.robot.design).to_lowercase()),
            ("block_material", f.operator.block_material.clone()),
            ("block_mass_kg", scene.block_mass_kg.to_string()),
            ("payload_kg", f.robot.payload_kg.to_string()),
            ("link_mass_kg", scene.link_mass_kg.to_string()),
            (
                "torsion_spring_nm_per_rad",
                scene.torsion_spring.to_string(),
            ),
            ("hertz_k", scene.hertz.k().to_string()),
            ("hertz_n", scene.hertz.n().to_string()),
            ("time", "simulation time from 0 (ns)".to_string()),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        writer.write_metadata(&mcap::records::Metadata {
            name: "flexrig".into(),
            metadata,
        })?;
        Ok(McapRecorder {
            writer,
            channels,
            sequence: 0,
            buffer: Vec::with_capacity(1024),
            last_scene_ns: None,
            last_scalar_ns: None,
            last_chosen_ns: None,
            geometry: flexrig_rig::geometry::RigGeometry::of(scene),
            messages: 0,
            cancel: None,
            rates: LogRates::DECIMATED,
            deformation_scale: DEFAULT_DEFORMATION_SCALE,
            flexible_link: f.robot.design == flexrig_rig::scene::Design::Cl,
            clock_origin: clock_origin(&f.operator.start),
        })
    }

    /// Stops the run (with [`RigError::Interrupted`]) at the first frame after `cancel` is
    /// cancelled, e.g. by a Ctrl-C handler; the file is then finished with an `error` record as
    /// for any failed run.
    pub fn with_cancel(mut self, cancel: CancelToken) -> Self {
        self.cancel = Some(cancel);
        self
    }

    /// Writes at `rates` instead of [`LogRates::DECIMATED`].
    pub fn with_rates(mut self, rates: LogRates) -> Self {
        self.rates = rates;
        self
    }

    /// Draws the FE beam (CL) at its undeformed axis plus `scale` × its displacements in the 3D
    /// view (as FE post-processors exaggerate deformations), labelled in the view; 1 draws it
    /// at true scale. The scale is recorded in the `view` metadata record; the CJ link is rigid
    /// and always drawn at true scale.
    pub fn with_deformation_scale(mut self, scale: f64) -> Self {
        self.deformation_scale = scale;
        self
    }

    /// The drive's channels of frame `f` (a scene with `robot.drive`): the motor side's joint
    /// angle and speed, the command, the joint and motor torques, the link's angle and speed,
    /// its moment on the hub (spring or beam root) and its deflection.
    fn write_drive(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        let (Some(ch), Some(d)) = (self.channels.drive, f.drive) else {
            return Ok(());
        };
        let motion = |angle_rad: f64, speed_rad_s: f64| JointMotion {
            timestamp: stamp(f.t),
            angle_rad,
            speed_rad_s,
        };
        self.write(
            ch.joint,
            f.t,
            &motion(d.motor_angle_rad, d.motor_speed_rad_s),
        )?;
        self.write(
            ch.command,
            f.t,
            &motion(d.commanded_angle_rad, d.commanded_speed_rad_s),
        )?;
        self.write(
            ch.torque,
            f.t,
            &MotorTorque {
                timestamp: stamp(f.t),
                joint_nm: d.joint_torque_nm,
                motor_nm: d.motor_torque_nm,
            },
        )?;
        self.write(ch.link, f.t, &motion(d.link_angle_rad, d.link_speed_rad_s))?;
        self.write(
            ch.load,
            f.t,
            &LinkLoad {
                timestamp: stamp(f.t),
                moment_nm: d.spring_moment_nm,
                deflection_m: d.link_deflection_m,
                deflection_mm: d.link_deflection_m * 1e3,
            },
        )
    }

    /// Messages written so far.
    pub fn messages(&self) -> u64 {
        self.messages
    }

    fn write<M: Encode>(&mut self, channel: u16, t: f64, msg: &M) -> Result<(), RigError> {
        self.buffer.clear();
        msg.encode(&mut self.buffer)
            .map_err(|e| RigError::Recorder(format!("encoding a message failed: {e}")))?;
        self.sequence += 1;
        let ns = nanos(t);
        self.writer
            .write_to_known_channel(
                &mcap::records::MessageHeader {
                    channel_id: channel,
                    sequence: self.sequence,
                    log_time: ns,
                    publish_time: ns,
                },
                &self.buffer,
            )
            .map_err(io_error)?;
        self.messages += 1;
        Ok(())
    }

    fn write_samples(
        &mut self,
        samples: &[SensorSample],
        in_contact: bool,
    ) -> Result<(), RigError> {
        for s in samples {
            let ns = nanos(s.t);
            if !in_contact
                && self
                    .last_scalar_ns
                    .is_some_and(|last| ns < last + self.rates.scalar_period_ns)
            {
                continue;
            }
            self.last_scalar_ns = Some(ns);
            self.last_chosen_ns = Some(ns);
            let ts = stamp(s.t);
            let c = self.channels;
            self.write(
                c.force,
                s.t,
                &ForceSensor {
                    timestamp: ts,
                    force_n: s.force_n,
                },
            )?;
            self.write(
                c.accel_operator,
                s.t,
                &Accelerometer {
                    timestamp: ts,
                    accel_mps2: s.operator_accel_mps2,
                },
            )?;
            self.write(
                c.accel_load,
                s.t,
                &Accelerometer {
                    timestamp: ts,
                    accel_mps2: s.load_accel_mps2,
                },
            )?;
            let joint = |name: &str, position: f64| JointState {
                name: name.into(),
                position: Some(position),
                velocity: None,
                acceleration: None,
                effort: None,
            };
            self.write(
                c.encoders,
                s.t,
                &JointStates {
                    timestamp: Some(ts),
                    joints: vec![
                        joint("operator", s.operator_angle_rad),
                        joint("robot", s.robot_angle_rad),
                    ],
                },
            )?;
        }
        Ok(())
    }

    fn write_3d(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        let ts = stamp(f.t);
        let transform = |child: &str, p: &Pose| FrameTransform {
            timestamp: Some(ts),
            parent_frame_id: "world".into(),
            child_frame_id: child.into(),
            translation: Some(vec3(p.translation)),
            rotation: Some(Quaternion {
                x: p.rotation.x,
                y: p.rotation.y,
                z: p.rotation.z,
                w: p.rotation.w,
            }),
        };
        let tf = FrameTransforms {
            transforms: vec![
                transform("operator", &f.operator_pose),
                transform("robot", &f.dome_body_pose),
            ],
        };
        self.write(self.channels.tf, f.t, &tf)?;

        let op = &self.geometry.operator;
        let block_pose = f.operator_pose * Pose::from_translation(op.block_center_local);
        let mut entities = vec![
            SceneEntity {
                timestamp: Some(ts),
                frame_id: "world".into(),
                id: "operator".into(),
                lines: vec![line(
                    vec![point(op.pivot), point(block_pose.translation)],
                    color(0.6, 0.6, 0.6),
                    4.0,
                )],
                cubes: vec![CubePrimitive {
                    pose: Some(pose(&block_pose)),
                    size: Some(vec3(op.block_half_extents * 2.0)),
                    color: color(0.75, 0.55, 0.3),
                }],
                ..Default::default()
            },
            self.robot_entity(f, ts),
        ];
        let (arrows, texts) = match f.contact {
            Some(c) if c.force > 0.0 => {
                force_arrow(c.point, c.normal, c.force, self.geometry.robot.dome_radius)
            }
            _ => (vec![], vec![]),
        };
        entities.push(SceneEntity {
            timestamp: Some(ts),
            frame_id: "world".into(),
            id: "contact_force".into(),
            arrows,
            texts,
            ..Default::default()
        });
        entities.push(SceneEntity {
            timestamp: Some(ts),
            frame_id: "world".into(),
            id: "clock".into(),
            texts: vec![TextPrimitive {
                color: color(0.15, 0.15, 0.15),
                ..label(
                    format!(
                        "t = {:.2} ms of simulation (from {})",
                        f.t * 1e3,
                        self.clock_origin
                    ),
                    CLOCK_AT,
                )
            }],
            ..Default::default()
        });
        self.write(
            self.channels.scene,
            f.t,
            &SceneUpdate {
                deletions: vec![],
                entities,
            },
        )
    }

    /// The robot: the link (CJ: a rigid line on its axis; CL: the FE beam drawn at its
    /// undeformed axis plus `deformation_scale` × its displacements, with that axis and a label)
    /// and the dome, at true scale.
    fn robot_entity(&self, f: &Frame<'_>, ts: Timestamp) -> SceneEntity {
        let robot = &self.geometry.robot;
        let length = robot.length;
        let dome_local = match f.beam {
            Some(_) => robot.dome_center_local - Vector::new(length, 0.0, 0.0),
            None => robot.dome_center_local,
        };
        let mut entity = SceneEntity {
            timestamp: Some(ts),
            frame_id: "world".into(),
            id: "robot".into(),
            spheres: vec![SpherePrimitive {
                pose: Some(pose(
                    &(f.dome_body_pose * Pose::from_translation(dome_local)),
                )),
                size: Some(vec3(Vector::splat(2.0 * robot.dome_radius))),
                color: Some(Color {
                    r: 0.8,
                    g: 0.8,
                    b: 0.85,
                    a: 0.35,
                }),
            }],
            ..Default::default()
        };
        let blue = color(0.2, 0.4, 0.9);
        match f.beam {
            Some(beam) => {
                let (points, tip_m) = drawn_beam(beam, self.deformation_scale);
                entity.lines = vec![
                    line(points, blue, 4.0),
                    line(
                        vec![point(Vector::ZERO), point(Vector::new(length, 0.0, 0.0))],
                        color(0.55, 0.55, 0.6),
                        1.5,
                    ),
                ];
                entity.texts = vec![label(
                    format!(
                        "CL: beam deflection ×{} (true tip deflection {:.2} mm)",
                        self.deformation_scale,
                        tip_m * 1e3
                    ),
                    LABEL_AT,
                )];
                entity.metadata = vec![KeyValuePair {
                    key: "deformation_scale".into(),
                    value: flexrig_contact::validate::display(self.deformation_scale),
                }];
            }
            None => {
                let p = &f.dome_body_pose;
                entity.lines = vec![
                    line(
                        vec![
                            point(p.transform_point(Vector::ZERO)),
                            point(p.transform_point(Vector::new(length, 0.0, 0.0))),
                        ],
                        blue,
                        4.0,
                    ),
                    line(torsion_spring(p), color(0.1, 0.55, 0.4), 2.5),
                ];
                entity.texts = vec![label(
                    "CJ: rigid link on the torsion spring, true scale".into(),
                    LABEL_AT,
                )];
            }
        }
        entity
    }

    /// Closes the file; with `error`, an `error` metadata record first. Returns the summary of
    /// the written file.
    pub fn finish(mut self, error: Option<&str>) -> Result<(), mcap::McapError> {
        if let Some(e) = error {
            self.write_error(e)?;
        }
        self.close()
    }

    /// Finishes the file (as [`McapRecorder::finish`] without an error) and returns the writer.
    pub fn finish_into_inner(mut self) -> Result<W, mcap::McapError> {
        self.close()?;
        Ok(self.writer.into_inner())
    }

    /// Writes the `view` metadata record and the summary section.
    fn close(&mut self) -> Result<(), mcap::McapError> {
        self.writer.write_metadata(&mcap::records::Metadata {
            name: "view".into(),
            metadata: view_metadata(self.deformation_scale, self.flexible_link),
        })?;
        self.writer.finish()?;
        Ok(())
    }

    /// Finishes the file with an `error` metadata record and returns the writer.
    pub fn finish_with_error(mut self, error: &str) -> Result<W, mcap::McapError> {
        self.write_error(error)?;
        self.finish_into_inner()
    }

    fn write_error(&mut self, error: &str) -> Result<(), mcap::McapError> {
        self.writer.write_metadata(&mcap::records::Metadata {
            name: "error".into(),
            metadata: [("message".to_string(), error.to_string())]
                .into_iter()
                .collect(),
        })
    }

    /// Writes the run's severity ([`RunSummary::severity`]) as one JSON message on `/severity`
    /// at the run's end (after a successful run; nothing when the run has none).
    pub fn write_severity(&mut self, s: &RunSummary) -> Result<(), mcap::McapError> {
        let Some(severity) = &s.severity else {
            return Ok(());
        };
        let mut message = serde_json::to_value(severity).unwrap_or_default();
        if let Some(map) = message.as_object_mut() {
            map.insert("hic_method".into(), flexrig_safety::HIC_METHOD.into());
            map.insert(
                "struck_body".into(),
                "operator block (virtual operator accelerometer)".into(),
            );
        }
        let data = message.to_string();
        self.sequence += 1;
        let ns = nanos(s.duration_s);
        self.writer.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: self.channels.severity,
                sequence: self.sequence,
                log_time: ns,
                publish_time: ns,
            },
            data.as_bytes(),
        )?;
        self.messages += 1;
        Ok(())
    }

    /// Writes the run summary as metadata (after a successful run).
    pub fn write_summary(&mut self, s: &RunSummary) -> Result<(), mcap::McapError> {
        let value = serde_json::to_value(s).unwrap_or_default();
        let metadata = value
            .as_object()
            .map(|o| o.iter().map(|(k, v)| (k.clone(), v.to_string())).collect())
            .unwrap_or_default();
        self.writer.write_metadata(&mcap::records::Metadata {
            name: "summary".into(),
            metadata,
        })
    }
}

/// The scene's name as run: a name that begins with the other design's prefix (`cj_`, `cl_`:
/// the design was overridden) gets the design that ran, with the file's name after it, e.g.
/// `cl_aluminium (scene cj_aluminium, design set to CL)`.
pub fn name_as_run(name: &str, design: flexrig_rig::scene::Design) -> String {
    let ran = match design {
        flexrig_rig::scene::Design::Cj => "cj",
        flexrig_rig::scene::Design::Cl => "cl",
    };
    match name.split_once('_') {
        Some((prefix, rest)) if (prefix == "cj" || prefix == "cl") && prefix != ran => format!(
            "{ran}_{rest} (scene {name}, design set to {})",
            ran.to_uppercase()
        ),
        _ => name.to_string(),
    }
}

/// The `view` metadata record: how the 3D view draws the rig (`deformation_scale`).
fn view_metadata(scale: f64, flexible_link: bool) -> BTreeMap<String, String> {
    let (scale, applies) = if flexible_link {
        (
            scale.to_string(),
            "the FE beam (/scene entity robot, line 0): drawn node = reference + \
             deformation_scale × (true node − reference), the reference being the undeformed \
             axis, node i at (x_i, 0, 0) m (line 1); true node = reference + (drawn node − \
             reference) / deformation_scale. The dome, the block, the force arrow and /tf are \
             at true scale.",
        )
    } else {
        (
            "1".to_string(),
            "nothing: the CJ link is rigid; the whole view is at true scale.",
        )
    };
    [
        ("deformation_scale", scale),
        ("deformation_applies_to", applies.to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

/// The CJ's torsion spring drawn as a flat spiral of three turns around the robot axis, 8 to
/// 30 mm from it, just above the link, its outer end on the link (it turns with `link`) \[m,
/// world\].
fn torsion_spring(link: &Pose) -> Vec<Point3> {
    let axis = link.transform_point(Vector::ZERO);
    let along = link.rotation * Vector::X;
    let start = along.y.atan2(along.x);
    let n = 120;
    (0..=n)
        .map(|i| {
            let t = f64::from(i) / f64::from(n);
            let r = 0.008 + 0.022 * t;
            let phi = start - 2.0 * std::f64::consts::PI * 3.0 * (1.0 - t);
            point(axis + Vector::new(r * phi.cos(), r * phi.sin(), 0.012))
        })
        .collect()
}

/// The rotation taking +x (the Foxglove arrow axis) onto `direction`.
fn arrow_rotation(direction: Vector) -> flexrig_contact::math::Rotation {
    flexrig_contact::math::Rotation::from_rotation_arc(Vector::X, direction.normalize())
}

impl<W: Write + Seek> Recorder for McapRecorder<W> {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        if self.cancel.as_ref().is_some_and(CancelToken::is_cancelled) {
            return Err(RigError::Interrupted { t: f.t });
        }
        let in_contact = f.contact.is_some();
        self.write_samples(f.samples, in_contact)?;
        if let Some(c) = f.contact {
            self.write(
                self.channels.contact,
                f.t,
                &ContactState {
                    timestamp: stamp(f.t),
                    indentation_m: c.indentation,
                    rate_mps: c.rate,
                    force_n: c.force,
                    indentation_mm: c.indentation * 1e3,
                },
            )?;
        }
        let period = if in_contact {
            self.rates.scene_period_contact_ns
        } else {
            self.rates.scene_period_ns
        };
        self.write_scene_if_due(f, period)
    }

    /// The 3D view's rate outside contact: the free swing, whose integrator steps are long, is
    /// drawn at that rate from its dense output (none when every step is logged).
    fn pose_period(&self) -> Option<f64> {
        (self.rates.scene_period_ns > 0).then_some(self.rates.scene_period_ns as f64 * 1e-9)
    }

    fn between(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        if self.cancel.as_ref().is_some_and(CancelToken::is_cancelled) {
            return Err(RigError::Interrupted { t: f.t });
        }
        self.write_scene_if_due(f, self.rates.scene_period_ns)
    }

    /// Outside contact the sensor channels are decimated: a lean run computes only the swing
    /// samples the decimation writes (every sample when every one is logged).
    fn swing_samples(&self) -> SwingSamples {
        if self.rates.scalar_period_ns == 0 {
            SwingSamples::Every
        } else {
            SwingSamples::Chosen
        }
    }

    /// The decimation of [`McapRecorder::write_samples`] ahead of the frame: the sample is
    /// wanted when it is due after the last one written or chosen (the frame then writes
    /// exactly the chosen ones, as it would pick them out of every sample).
    fn wants_swing_sample(&mut self, t: f64) -> bool {
        let ns = nanos(t);
        if self
            .last_chosen_ns
            .is_some_and(|last| ns < last + self.rates.scalar_period_ns)
        {
            return false;
        }
        self.last_chosen_ns = Some(ns);
        true
    }
}

impl<W: Write + Seek> McapRecorder<W> {
    /// `/energy` and the 3D channels of `f`, if `period` \[ns\] has passed since the last.
    fn write_scene_if_due(&mut self, f: &Frame<'_>, period: u64) -> Result<(), RigError> {
        let ns = nanos(f.t);
        let due = self.last_scene_ns.is_none_or(|last| ns >= last + period);
        if due {
            self.write(
                self.channels.energy,
                f.t,
                &EnergyState {
                    timestamp: stamp(f.t),
                    total_j: f.energy,
                },
            )?;
            self.write_drive(f)?;
            self.write_3d(f)?;
            self.last_scene_ns = Some(ns);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
