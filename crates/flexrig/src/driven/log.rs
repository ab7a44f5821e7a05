//! The MCAP log of a driven run (docs/foxglove.md, "Driven runs"), with its Foxglove layout
//! beside it ([`crate::log::layout::driven_for_log`]).
//!
//! Channels (protobuf, simulation time from 0 in ns, as the test bed's logs):
//! `/drive/joint` (actual joint angle and speed), `/drive/command` (commanded joint angle and
//! speed; absent under an open-loop torque), `/drive/torque` (motor torque at the joint and at
//! the motor shaft), `/link` (the spring's or the beam root's moment, the tip deflection) and
//! `/contact` (force, indentation and the head's acceleration), and at the run's end one JSON
//! message on `/severity` (the summary's severity, [`crate::log::mcap::SEVERITY_JSON_SCHEMA`],
//! struck body the head). Inside the contact every trace sample is logged; outside
//! it the channels are decimated to [`LogRates::scalar_period_ns`]. The scene file is attached;
//! `flexrig` (parameters), `view` and `summary` metadata records as in the test bed's logs. The
//! run is computed first and the log written from its trace, under a temporary name moved into
//! place when finished; a failed run leaves a log holding only its metadata and an `error`
//! record.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Seek, Write};

use foxglove::Encode;
use foxglove::messages::Timestamp;

use super::scene::{DrivenRun, DrivenScene, run, summary_json};
use crate::Error;
use crate::log::file::{LogTarget, PendingFile, io_of, refuse_overwrite};
use crate::log::layout as foxglove_layout;
use crate::log::mcap::LogRates;
pub use crate::log::mcap::{JointMotion, MotorTorque};

/// The link's elastic state.
#[derive(Debug, Clone, Encode)]
pub struct LinkState {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// The torsion spring's moment (CJ) or the beam's root moment (CL) [N·m].
    pub moment_nm: f64,
    /// Tip deflection from the hub's line \[m\].
    pub tip_deflection_m: f64,
    /// The same in millimetres (for the plots) \[mm\].
    pub tip_deflection_mm: f64,
}

/// The contact.
#[derive(Debug, Clone, Encode)]
pub struct DrivenContact {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Contact force \[N\].
    pub force_n: f64,
    /// Indentation \[m\] (negative: the gap before the contact).
    pub indentation_m: f64,
    /// The same in millimetres (for the plots) \[mm\].
    pub indentation_mm: f64,
    /// The head's acceleration along the tip's path [m/s²] (positive away from the link; 0
    /// against a wall).
    pub head_acceleration_mps2: f64,
}

/// The topics of a driven log.
pub const TOPICS: [&str; 6] = [
    "/drive/joint",
    "/drive/command",
    "/drive/torque",
    "/link",
    "/contact",
    "/severity",
];

fn stamp(t: f64) -> Timestamp {
    let ns = nanos(t);
    Timestamp::new((ns / 1_000_000_000) as u32, (ns % 1_000_000_000) as u32)
}

fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

struct Writer<W: Write + Seek> {
    mcap: mcap::Writer<W>,
    buffer: Vec<u8>,
    sequence: u32,
}

impl<W: Write + Seek> Writer<W> {
    fn channel<M: Encode>(&mut self, topic: &str) -> Result<u16, mcap::McapError> {
        let schema = M::get_schema().expect("derived messages have schemas");
        let id = self
            .mcap
            .add_schema(&schema.name, &schema.encoding, &schema.data)?;
        self.mcap
            .add_channel(id, topic, &M::get_message_encoding(), &BTreeMap::new())
    }

    fn write<M: Encode>(&mut self, channel: u16, t: f64, msg: &M) -> Result<(), mcap::McapError> {
        self.buffer.clear();
        msg.encode(&mut self.buffer)
            .map_err(|e| std::io::Error::other(format!("encoding a message failed: {e}")))?;
        self.sequence += 1;
        let ns = nanos(t);
        self.mcap.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: channel,
                sequence: self.sequence,
                log_time: ns,
                publish_time: ns,
            },
            &self.buffer,
        )
    }

    /// One JSON message (already serialised) at time `t` \[s\].
    fn write_json(&mut self, channel: u16, t: f64, json: &str) -> Result<(), mcap::McapError> {
        self.sequence += 1;
        let ns = nanos(t);
        self.mcap.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: channel,
                sequence: self.sequence,
                log_time: ns,
                publish_time: ns,
            },
            json.as_bytes(),
        )
    }

    fn metadata(
        &mut self,
        name: &str,
        pairs: BTreeMap<String, String>,
    ) -> Result<(), mcap::McapError> {
        self.mcap.write_metadata(&mcap::records::Metadata {
            name: name.into(),
            metadata: pairs,
        })
    }
}

fn pairs(items: &[(&str, String)]) -> BTreeMap<String, String> {
    items
        .iter()
        .map(|(k, v)| (k.to_string(), v.clone()))
        .collect()
}

/// Writes the log of `outcome` (the run, or its error) of `scene` to `w`.
pub fn write<W: Write + Seek>(
    w: W,
    scene: &DrivenScene,
    scene_text: &str,
    outcome: Result<&DrivenRun, &Error>,
    rates: LogRates,
) -> Result<W, mcap::McapError> {
    let mcap = mcap::WriteOptions::new()
        .compression(None)
        .profile("")
        .library(format!("flexrig {}", env!("CARGO_PKG_VERSION")))
        .create(w)?;
    let mut w = Writer {
        mcap,
        buffer: Vec::with_capacity(256),
        sequence: 0,
    };
    let s = &scene.strike;
    let commanded = s.drive.profile().is_some();
    let joint = w.channel::<JointMotion>("/drive/joint")?;
    let command = if commanded {
        Some(w.channel::<JointMotion>("/drive/command")?)
    } else {
        None
    };
    let torque = w.channel::<MotorTorque>("/drive/torque")?;
    let link = w.channel::<LinkState>("/link")?;
    let contact = w.channel::<DrivenContact>("/contact")?;
    let severity_channel = {
        let id = w.mcap.add_schema(
            crate::log::mcap::SEVERITY_SCHEMA_NAME,
            "jsonschema",
            crate::log::mcap::SEVERITY_JSON_SCHEMA.as_bytes(),
        )?;
        w.mcap
            .add_channel(id, "/severity", "json", &BTreeMap::new())?
    };
    w.mcap.attach(&mcap::Attachment {
        log_time: 0,
        create_time: 0,
        name: "scene.toml".into(),
        media_type: "application/toml".into(),
        data: std::borrow::Cow::Borrowed(scene_text.as_bytes()),
    })?;
    let motor = s.drive.motor();
    let design = match s.design {
        super::strike::StrikeDesign::Cj => "cj",
        super::strike::StrikeDesign::Cl => "cl",
    };
    w.metadata(
        "flexrig",
        pairs(&[
            ("software", format!("flexrig {}", env!("CARGO_PKG_VERSION"))),
            (
                "git_revision",
                option_env!("FLEXRIG_GIT_REVISION")
                    .unwrap_or("unknown")
                    .to_string(),
            ),
            ("scene", scene.name.clone()),
            ("kind", "driven".into()),
            ("design", design.into()),
            ("link_mass_kg", s.link.m_r.to_string()),
            ("link_length_m", s.link.length.to_string()),
            ("k_delta_n_per_m", s.link.k_delta.to_string()),
            ("payload_kg", s.link.m_e.to_string()),
            ("rotor_inertia_kg_m2", motor.rotor_inertia.to_string()),
            ("gear_ratio", motor.gear_ratio.to_string()),
            ("head_mass_kg", s.person.m_h.to_string()),
            ("hertz_k", s.person.contact.k().to_string()),
            ("hertz_n", s.person.contact.n().to_string()),
            ("time", "simulation time from the drive's start (ns)".into()),
        ]),
    )?;
    let channels = Channels {
        joint,
        command,
        torque,
        link,
        contact,
    };
    match outcome {
        Ok(run) => {
            let c = run.outcome.contact;
            write_traces(
                &mut w,
                &channels,
                &run.traces,
                (c.onset_s, c.onset_s + c.duration_s),
                rates,
            )?;
            let off = c.onset_s + c.duration_s;
            if let Some(severity) = &run.summary.severity {
                let mut message = serde_json::to_value(severity).unwrap_or_default();
                if let Some(map) = message.as_object_mut() {
                    map.insert("hic_method".into(), flexrig_safety::HIC_METHOD.into());
                    let struck = if run.summary.head == "wall" {
                        "head against a wall (it does not move: no acceleration, no HIC)"
                    } else {
                        "head (its acceleration (f − neck force)/m_h along the tip's path)"
                    };
                    map.insert("struck_body".into(), struck.into());
                }
                w.write_json(severity_channel, off, &message.to_string())?;
            }
            let summary = summary_json(&run.summary);
            let items: BTreeMap<String, String> = summary
                .as_object()
                .map(|o| o.iter().map(|(k, v)| (k.clone(), v.to_string())).collect())
                .unwrap_or_default();
            w.metadata("summary", items)?;
        }
        Err(e) => {
            // what the run computed before it failed or was stopped
            if let Error::Impact(ie) = e
                && !ie.partial_trace().is_empty()
            {
                let traces = super::scene::traces_of(scene, ie.partial_trace());
                write_traces(&mut w, &channels, &traces, (f64::NAN, f64::NAN), rates)?;
            }
            w.metadata("error", pairs(&[("message", e.to_string())]))?
        }
    }
    w.metadata(
        "view",
        pairs(&[
            ("deformation_scale", "1".into()),
            (
                "deformation_applies_to",
                "nothing: a driven log has plots only, no 3D view".into(),
            ),
        ]),
    )?;
    w.mcap.finish()?;
    Ok(w.mcap.into_inner())
}

/// Runs `scene` and logs it to `target.path` with its layout beside it (as
/// [`crate::log::file::run_logged`] does for the test bed: never a half-written file under the
/// requested name; a failed run leaves its finished log with an `error` record and returns the
/// run's error).
pub fn run_logged(scene: &DrivenScene, target: &LogTarget<'_>) -> Result<DrivenRun, Error> {
    let path = target.path;
    let layout = foxglove_layout::path_beside(path);
    crate::shared::output::check_output_target(path)?;
    crate::shared::output::check_output_target(&layout)?;
    if !target.force {
        for existing in [path, layout.as_path()] {
            if existing.exists() {
                return Err(refuse_overwrite(existing));
            }
        }
    }
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        crate::shared::output::ensure_dir(parent)?;
    }
    let outcome = run(scene, &target.cancel);
    let pending = PendingFile::new(path);
    let file = File::create(&pending.tmp).map_err(|e| Error::write(path, e))?;
    let written = write(
        BufWriter::new(file),
        scene,
        target.scene_text,
        outcome.as_ref(),
        target.rates,
    )
    .map_err(|e| Error::write(path, io_of(e)))?;
    let file = written
        .into_inner()
        .map_err(|e| Error::write(path, e.into_error()))?;
    drop(file);
    pending.commit(target.force)?;
    let window = outcome.as_ref().ok().map(|r| {
        let c = r.outcome.contact;
        foxglove_layout::window_around(c.onset_s, c.onset_s + c.duration_s)
    });
    // the contact plots' value axes leave room for their legends above the curves
    let axes = match (&outcome, window) {
        (Ok(r), Some(w)) => {
            let t = &r.traces;
            foxglove_layout::driven_axes(
                &t.time_s,
                &t.force_n,
                &t.indentation_m,
                &t.tip_deflection_m,
                w,
            )
        }
        _ => foxglove_layout::DrivenAxes::default(),
    };
    foxglove_layout::write_driven_beside(
        path,
        window,
        scene.strike.drive.profile().is_some(),
        axes,
    )?;
    outcome
}

/// The channels of a driven log's motion.
#[derive(Clone, Copy)]
struct Channels {
    joint: u16,
    command: Option<u16>,
    torque: u16,
    link: u16,
    contact: u16,
}

/// The motion's messages: every sample inside the contact window `(on, off)` \[s\] (none with
/// NaN), the first and the last, and elsewhere at most one per `rates.scalar_period_ns`.
fn write_traces<W: Write + Seek>(
    w: &mut Writer<W>,
    ch: &Channels,
    tr: &super::scene::DrivenTraces,
    (on, off): (f64, f64),
    rates: LogRates,
) -> Result<(), mcap::McapError> {
    let Channels {
        joint,
        command,
        torque,
        link,
        contact,
    } = *ch;
    let mut last: Option<u64> = None;
    for i in 0..tr.time_s.len() {
        let t = tr.time_s[i];
        let ns = nanos(t);
        let inside = t >= on && t <= off;
        let first_or_last = i == 0 || i + 1 == tr.time_s.len();
        if !inside && !first_or_last && last.is_some_and(|l| ns < l + rates.scalar_period_ns) {
            continue;
        }
        last = Some(ns);
        let ts = stamp(t);
        w.write(
            joint,
            t,
            &JointMotion {
                timestamp: ts,
                angle_rad: tr.joint_angle_rad[i],
                speed_rad_s: tr.joint_speed_rad_s[i],
            },
        )?;
        if let Some(command) = command {
            w.write(
                command,
                t,
                &JointMotion {
                    timestamp: ts,
                    angle_rad: tr.commanded_angle_rad[i],
                    speed_rad_s: tr.commanded_speed_rad_s[i],
                },
            )?;
        }
        w.write(
            torque,
            t,
            &MotorTorque {
                timestamp: ts,
                joint_nm: tr.joint_torque_nm[i],
                motor_nm: tr.motor_torque_nm[i],
            },
        )?;
        w.write(
            link,
            t,
            &LinkState {
                timestamp: ts,
                moment_nm: tr.link_moment_nm[i],
                tip_deflection_m: tr.tip_deflection_m[i],
                tip_deflection_mm: 1e3 * tr.tip_deflection_m[i],
            },
        )?;
        w.write(
            contact,
            t,
            &DrivenContact {
                timestamp: ts,
                force_n: tr.force_n[i],
                indentation_m: tr.indentation_m[i],
                indentation_mm: 1e3 * tr.indentation_m[i],
                head_acceleration_mps2: tr.head_acceleration_mps2[i],
            },
        )?;
    }
    Ok(())
}
