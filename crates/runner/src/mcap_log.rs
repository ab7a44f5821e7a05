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
//! compress poorly; an uncompressed bundled run is 0.22–0.24 MB. The scene file is attached;
//! key parameters, the software version and the git revision are metadata. The file is always
//! finished: [`McapRecorder::finish`] closes it, with an `error` metadata record when the run
//! failed, and [`run_logged`] writes it under a temporary name that is renamed into place only
//! when finished (a full disk leaves no half-written file under the requested name).

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_contact::math::{Pose, Vector};
use flexrig_rig::sensors::SensorSample;
use flexrig_rig::{Frame, Recorder, RigError, RunSummary, Scene, Simulation};
use foxglove::Encode;
use foxglove::messages::{
    ArrowPrimitive, Color, CubePrimitive, FrameTransform, FrameTransforms, JointState, JointStates,
    LinePrimitive, Point3, Quaternion, SceneEntity, SceneUpdate, SpherePrimitive, Timestamp,
    Vector3, line_primitive::Type as LineType,
};

use crate::CliError;

/// Contact force sensor between load and dome.
#[derive(Debug, Clone, Encode)]
pub struct ForceSensor {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Force \[N\].
    pub force_n: f64,
}

/// One accelerometer, along the strike direction (world y).
#[derive(Debug, Clone, Encode)]
pub struct Accelerometer {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Acceleration [m/s²].
    pub accel_mps2: f64,
}

/// The contact state at a step end.
#[derive(Debug, Clone, Encode)]
pub struct ContactState {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Indentation δ \[m\].
    pub indentation_m: f64,
    /// Indentation rate δ̇ [m/s].
    pub rate_mps: f64,
    /// Contact force \[N\].
    pub force_n: f64,
}

/// Mechanical energy.
#[derive(Debug, Clone, Encode)]
pub struct EnergyState {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Total mechanical energy \[J\].
    pub total_j: f64,
}

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
    geometry: flexrig_rig::geometry::RigGeometry,
    messages: u64,
    interrupt: Option<Arc<AtomicBool>>,
    rates: LogRates,
}

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

/// Where and how [`run_logged`] writes a run's MCAP log.
#[derive(Debug, Clone)]
pub struct LogTarget<'a> {
    /// The log file the user asked for.
    pub path: &'a Path,
    /// Replace an existing file at `path` (otherwise an existing file is an error).
    pub force: bool,
    /// The scene text as run (attached to the log).
    pub scene_text: &'a str,
    /// Ctrl-C: set, the run stops and its log is finished.
    pub interrupt: Arc<AtomicBool>,
    /// What is logged how often.
    pub rates: LogRates,
}

/// Runs `simulation` of `scene` while logging it to `target.path`.
///
/// The log is written under a temporary name in the same directory and moved into place only
/// when finished, so the requested name never holds an unfinished file. A run that fails (or is
/// stopped by Ctrl-C) still leaves its finished log, with an `error` metadata record, and returns
/// the run's error; a write that fails (e.g. a full disk) leaves nothing and returns the write
/// error, naming the file.
pub fn run_logged(
    simulation: Simulation,
    scene: &Scene,
    target: &LogTarget<'_>,
) -> Result<RunSummary, CliError> {
    let path = target.path;
    if !target.force && path.exists() {
        return Err(refuse_overwrite(path));
    }
    let pending = PendingFile::new(path);
    let file = File::create(&pending.tmp).map_err(|e| CliError::write(path, e))?;
    let write_error = |e: mcap::McapError| CliError::write(path, io_of(e));
    let mut log = McapRecorder::new(BufWriter::new(file), scene, target.scene_text)
        .map_err(write_error)?
        .with_interrupt(target.interrupt.clone())
        .with_rates(target.rates);
    let outcome = simulation.run(&mut log);
    let finished = match &outcome {
        Ok(summary) => log
            .write_summary(summary)
            .and_then(|()| log.finish_into_inner()),
        Err(e) => log.finish_with_error(&e.to_string()),
    };
    let writer = finished.map_err(write_error)?;
    let file = writer
        .into_inner()
        .map_err(|e| CliError::write(path, e.into_error()))?;
    drop(file);
    pending.commit(target.force)?;
    Ok(outcome?)
}

fn refuse_overwrite(path: &Path) -> CliError {
    CliError::InvalidArgument {
        arg: "--out".into(),
        value: path.display().to_string(),
        allowed: "a file that does not exist yet (or add --force to overwrite)".into(),
    }
}

/// The I/O error inside an MCAP error (kept, so a full disk still reads as one).
fn io_of(e: mcap::McapError) -> std::io::Error {
    match e {
        mcap::McapError::Io(e) => e,
        other => std::io::Error::other(other.to_string()),
    }
}

/// A file written under a temporary sibling name, removed unless committed.
struct PendingFile {
    tmp: PathBuf,
    path: PathBuf,
    committed: bool,
}

impl PendingFile {
    fn new(path: &Path) -> Self {
        PendingFile {
            tmp: crate::output::temporary_sibling(path),
            path: path.to_path_buf(),
            committed: false,
        }
    }

    /// Moves the finished file into place; without `force` an existing file is not replaced.
    fn commit(mut self, force: bool) -> Result<(), CliError> {
        let placed = if force {
            std::fs::rename(&self.tmp, &self.path)
        } else {
            // a hard link fails if the name was taken meanwhile; then the temporary is removed
            std::fs::hard_link(&self.tmp, &self.path)
                .or_else(|e| match e.kind() {
                    std::io::ErrorKind::AlreadyExists => Err(e),
                    // file systems without hard links
                    _ => std::fs::rename(&self.tmp, &self.path),
                })
                .map(|()| {
                    let _ = std::fs::remove_file(&self.tmp);
                })
        };
        placed.map_err(|e| {
            if e.kind() == std::io::ErrorKind::AlreadyExists {
                refuse_overwrite(&self.path)
            } else {
                CliError::write(&self.path, e)
            }
        })?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.tmp);
        }
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
        };
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
            ("scene", f.name.clone()),
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
            geometry: flexrig_rig::geometry::RigGeometry::of(scene),
            messages: 0,
            interrupt: None,
            rates: LogRates::DECIMATED,
        })
    }

    /// Stops the run (with [`RigError::Interrupted`]) at the first frame after `flag` is set,
    /// e.g. by a Ctrl-C handler; the file is then finished with an `error` record as for any
    /// failed run.
    pub fn with_interrupt(mut self, flag: Arc<AtomicBool>) -> Self {
        self.interrupt = Some(flag);
        self
    }

    /// Writes at `rates` instead of [`LogRates::DECIMATED`].
    pub fn with_rates(mut self, rates: LogRates) -> Self {
        self.rates = rates;
        self
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

    fn write_samples(&mut self, samples: &[SensorSample], every: bool) -> Result<(), RigError> {
        for s in samples {
            let ns = nanos(s.t);
            if !every
                && self
                    .last_scalar_ns
                    .is_some_and(|last| ns < last + self.rates.scalar_period_ns)
            {
                continue;
            }
            self.last_scalar_ns = Some(ns);
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
        let robot = &self.geometry.robot;
        let world = |p: &Pose, local: Vector| p.transform_point(local);
        let block_pose = f.operator_pose * Pose::from_translation(op.block_center_local);
        let link_points: Vec<Point3> = match f.beam {
            Some(b) => b.node_positions().into_iter().map(point).collect(),
            None => vec![
                point(world(&f.dome_body_pose, Vector::ZERO)),
                point(world(
                    &f.dome_body_pose,
                    Vector::new(robot.length, 0.0, 0.0),
                )),
            ],
        };
        let (dome_body, dome_local) = match f.beam {
            Some(_) => (
                f.dome_body_pose,
                robot.dome_center_local - Vector::new(robot.length, 0.0, 0.0),
            ),
            None => (f.dome_body_pose, robot.dome_center_local),
        };
        let line = |points: Vec<Point3>, c: Option<Color>| LinePrimitive {
            r#type: LineType::LineStrip as i32,
            pose: None,
            thickness: 4.0,
            scale_invariant: true,
            points,
            color: c,
            colors: vec![],
            indices: vec![],
        };
        let mut entities = vec![
            SceneEntity {
                timestamp: Some(ts),
                frame_id: "world".into(),
                id: "operator".into(),
                lines: vec![line(
                    vec![point(op.pivot), point(block_pose.translation)],
                    color(0.6, 0.6, 0.6),
                )],
                cubes: vec![CubePrimitive {
                    pose: Some(pose(&block_pose)),
                    size: Some(vec3(op.block_half_extents * 2.0)),
                    color: color(0.75, 0.55, 0.3),
                }],
                ..Default::default()
            },
            SceneEntity {
                timestamp: Some(ts),
                frame_id: "world".into(),
                id: "robot".into(),
                lines: vec![line(link_points, color(0.2, 0.4, 0.9))],
                spheres: vec![SpherePrimitive {
                    pose: Some(pose(&(dome_body * Pose::from_translation(dome_local)))),
                    size: Some(vec3(Vector::splat(2.0 * robot.dome_radius))),
                    color: Some(Color {
                        r: 0.8,
                        g: 0.8,
                        b: 0.85,
                        a: 0.5,
                    }),
                }],
                ..Default::default()
            },
        ];
        let arrows = match f.contact {
            Some(c) if c.force > 0.0 => {
                // 1 mm of arrow per N, along the force on the block.
                let length = (c.force * 1e-3).max(1e-3);
                let rotation = arrow_rotation(c.normal);
                vec![ArrowPrimitive {
                    pose: Some(pose(&Pose::from_parts(c.point, rotation))),
                    shaft_length: 0.8 * length,
                    shaft_diameter: 0.004,
                    head_length: 0.2 * length,
                    head_diameter: 0.01,
                    color: color(0.9, 0.1, 0.1),
                }]
            }
            _ => vec![],
        };
        entities.push(SceneEntity {
            timestamp: Some(ts),
            frame_id: "world".into(),
            id: "contact_force".into(),
            arrows,
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

    /// Closes the file; with `error`, an `error` metadata record first. Returns the summary of
    /// the written file.
    pub fn finish(mut self, error: Option<&str>) -> Result<(), mcap::McapError> {
        if let Some(e) = error {
            self.write_error(e)?;
        }
        self.writer.finish()?;
        Ok(())
    }

    /// Finishes the file (as [`McapRecorder::finish`] without an error) and returns the writer.
    pub fn finish_into_inner(mut self) -> Result<W, mcap::McapError> {
        self.writer.finish()?;
        Ok(self.writer.into_inner())
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

/// The rotation taking +x (the Foxglove arrow axis) onto `direction`.
fn arrow_rotation(direction: Vector) -> flexrig_contact::math::Rotation {
    flexrig_contact::math::Rotation::from_rotation_arc(Vector::X, direction.normalize())
}

impl<W: Write + Seek> Recorder for McapRecorder<W> {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        if self
            .interrupt
            .as_ref()
            .is_some_and(|i| i.load(Ordering::Relaxed))
        {
            return Err(RigError::Interrupted { t: f.t });
        }
        let ns = nanos(f.t);
        let in_contact = f.contact.is_some();
        self.write_samples(f.samples, in_contact)?;
        if in_contact || self.last_scalar_ns.is_none_or(|last| ns >= last) {
            let ts = stamp(f.t);
            if let Some(c) = f.contact {
                self.write(
                    self.channels.contact,
                    f.t,
                    &ContactState {
                        timestamp: ts,
                        indentation_m: c.indentation,
                        rate_mps: c.rate,
                        force_n: c.force,
                    },
                )?;
            }
        }
        let period = if in_contact {
            self.rates.scene_period_contact_ns
        } else {
            self.rates.scene_period_ns
        };
        let energy_due = self.last_scene_ns.is_none_or(|last| ns >= last + period);
        if energy_due {
            self.write(
                self.channels.energy,
                f.t,
                &EnergyState {
                    timestamp: stamp(f.t),
                    total_j: f.energy,
                },
            )?;
            self.write_3d(f)?;
            self.last_scene_ns = Some(ns);
        }
        Ok(())
    }
}
