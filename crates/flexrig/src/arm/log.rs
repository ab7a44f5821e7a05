//! The arm along its path as an MCAP log for Foxglove, with its layout: at every sample, on
//! `/scene` (foxglove `SceneUpdate`), the arm as simple shapes — a grey line from each moving
//! joint to the next (the kinematic chain from the base through every joint to each contact
//! point's link), a sphere at each joint — and each contact point as a sphere coloured by its
//! margin 1 − speed/permissible speed (green: far within, yellow: close, red: beyond), its
//! velocity as an arrow and a short tag (P1, P2, …), spelled out with each point's speed and
//! ratio in a caption above the arm; on `/arm/pointK` (K = 0, 1, …, in the order
//! given) the point's speed, permissible speed, ratio and reflected mass; on `/arm/joints` the
//! joint positions. Log time is the trajectory's time (ns from its first sample).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use flexrig_robot::Robot;
use foxglove::Encode;
use foxglove::messages::{
    ArrowPrimitive, Color, JointState, JointStates, LinePrimitive, Point3, Pose, Quaternion,
    SceneEntity, SceneUpdate, SpherePrimitive, TextPrimitive, Timestamp, Vector3,
    line_primitive::Type as LineType,
};
use serde_json::{Value, json};

use crate::Error;
use crate::arm::judge::ArmReport;

/// One contact point at one sample.
#[derive(Debug, Clone, Encode)]
pub struct ArmPointState {
    /// Trajectory time.
    pub timestamp: Timestamp,
    /// Speed \[m/s\].
    pub speed_mps: f64,
    /// Permissible speed \[m/s\] (NaN at rest or unlimited: no point plotted).
    pub v_max_mps: f64,
    /// speed / permissible speed.
    pub ratio: f64,
    /// Reflected mass along the velocity \[kg\] (NaN at rest).
    pub reflected_mass_kg: f64,
}

fn stamp(t: f64) -> Timestamp {
    let ns = (t.max(0.0) * 1e9).round() as u64;
    Timestamp::new((ns / 1_000_000_000) as u32, (ns % 1_000_000_000) as u32)
}

fn p3(v: [f64; 3]) -> Point3 {
    Point3 {
        x: v[0],
        y: v[1],
        z: v[2],
    }
}

fn rgba(r: f64, g: f64, b: f64, a: f64) -> Option<Color> {
    Some(Color { r, g, b, a })
}

/// The colour of a margin m = 1 − ratio: green at m ≥ 0.5, through yellow at 0.25, to red at
/// m ≤ 0 (beyond the limit).
pub fn margin_colour(ratio: f64) -> (f64, f64, f64) {
    let m = (1.0 - ratio).clamp(0.0, 0.5) / 0.5;
    if m >= 0.5 {
        (2.0 * (1.0 - m), 0.75, 0.2)
    } else {
        (0.9, 1.5 * m, 0.15)
    }
}

fn io(path: &Path) -> impl Fn(mcap::McapError) -> Error + '_ {
    move |e| Error::write(path, std::io::Error::other(e.to_string()))
}

/// Writes the log of `report` (of `robot`) to `path` (atomically: a temporary name renamed
/// when finished) and its layout beside it (`path_beside`); returns both paths.
pub fn write_log(robot: &Robot, report: &ArmReport, path: &Path) -> Result<Vec<PathBuf>, Error> {
    let bytes = log_bytes(robot, report).map_err(io(path))?;
    crate::shared::output::write_atomic(path, &bytes)?;
    let layout = crate::log::layout::path_beside(path);
    let text = serde_json::to_string_pretty(&layout_json(report)).expect("a layout serialises");
    crate::shared::output::write_atomic(&layout, text.as_bytes())?;
    Ok(vec![path.to_path_buf(), layout])
}

/// The highest rate \[Hz\] the log writes the arm at: Foxglove advises at most 60 Hz for its 3D
/// scenes.
pub const MAX_LOG_RATE_HZ: f64 = 50.0;

/// The indices of the samples at `times` \[s\] (ascending) the log writes: the first, then each
/// one at least 1/`rate` after the last written, and the last (which takes the place of the one
/// written before it when the two would be closer than 1/`rate`, unless that one is the first).
pub fn logged_samples(times: &[f64], rate: f64) -> Vec<usize> {
    let gap = 1.0 / rate;
    // a sample on the rate's grid up to rounding counts as on it
    let slack = 1e-9 * gap;
    let mut kept: Vec<usize> = Vec::new();
    for (i, &t) in times.iter().enumerate() {
        match kept.last() {
            None => kept.push(i),
            Some(&j) if t - times[j] >= gap - slack => kept.push(i),
            _ => {}
        }
    }
    let last = times.len().saturating_sub(1);
    if !times.is_empty() && kept.last() != Some(&last) {
        if kept.len() > 1 && times[last] - times[kept[kept.len() - 1]] < gap - slack {
            kept.pop();
        }
        kept.push(last);
    }
    kept
}

/// The MCAP bytes of the log: the arm at [`MAX_LOG_RATE_HZ`] at most ([`logged_samples`]).
pub fn log_bytes(robot: &Robot, report: &ArmReport) -> Result<Vec<u8>, mcap::McapError> {
    let mut w = mcap::WriteOptions::new()
        .compression(None)
        .profile("")
        .library(format!("flexrig {}", env!("CARGO_PKG_VERSION")))
        .create(std::io::Cursor::new(Vec::new()))?;
    let channel = |w: &mut mcap::Writer<_>,
                   topic: &str,
                   schema: Option<foxglove::Schema>,
                   encoding: String|
     -> Result<u16, mcap::McapError> {
        let schema = schema.expect("foxglove and derived messages have schemas");
        let id = w.add_schema(&schema.name, &schema.encoding, &schema.data)?;
        w.add_channel(id, topic, &encoding, &BTreeMap::new())
    };
    let scene = channel(
        &mut w,
        "/scene",
        SceneUpdate::get_schema(),
        SceneUpdate::get_message_encoding(),
    )?;
    let joints = channel(
        &mut w,
        "/arm/joints",
        JointStates::get_schema(),
        JointStates::get_message_encoding(),
    )?;
    let mut point_channels = Vec::new();
    for k in 0..report.points.len() {
        point_channels.push(channel(
            &mut w,
            &format!("/arm/point{k}"),
            ArmPointState::get_schema(),
            ArmPointState::get_message_encoding(),
        )?);
    }
    let mut ws = robot.workspace();
    let t0 = report.samples.first().map_or(0.0, |s| s.time_s);
    let mut seq = 0u32;
    let mut write = |w: &mut mcap::Writer<_>, ch: u16, t: f64, data: &[u8]| {
        let ns = ((t - t0).max(0.0) * 1e9).round() as u64;
        seq += 1;
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id: ch,
                sequence: seq,
                log_time: ns,
                publish_time: ns,
            },
            data,
        )
    };
    let names: Vec<String> = report.joint_names.clone();
    let times: Vec<f64> = report.samples.iter().map(|s| s.time_s).collect();
    let caption_anchor = caption_anchor(report);
    for s in logged_samples(&times, MAX_LOG_RATE_HZ)
        .into_iter()
        .map(|i| &report.samples[i])
    {
        let ts = stamp(s.time_s - t0);
        robot
            .forward_kinematics(&s.q, &mut ws)
            .map_err(|e| mcap::McapError::Io(std::io::Error::other(e.to_string())))?;
        // the chain: a line from each body's parent joint origin to its own
        let origin = |b: usize| -> [f64; 3] { ws.body_pose(b).translation.vector.into() };
        let mut lines = Vec::new();
        let mut spheres = Vec::new();
        for b in 1..robot.bodies().len() {
            let parent = robot.parent_body(b);
            lines.push(LinePrimitive {
                r#type: LineType::LineStrip as i32,
                pose: None,
                thickness: 0.06,
                scale_invariant: false,
                points: vec![p3(origin(parent)), p3(origin(b))],
                color: rgba(0.55, 0.57, 0.62, 1.0),
                colors: vec![],
                indices: vec![],
            });
            spheres.push(SpherePrimitive {
                pose: Some(pose_at(origin(b))),
                size: Some(Vector3 {
                    x: 0.075,
                    y: 0.075,
                    z: 0.075,
                }),
                color: rgba(0.3, 0.32, 0.38, 0.45),
            });
        }
        let mut point_spheres = Vec::new();
        let mut arrows = Vec::new();
        let mut texts = Vec::new();
        let mut caption = Vec::new();
        for (k, pr) in s.points.iter().enumerate() {
            let (r, g, b) = margin_colour(pr.ratio);
            // a link to the body origin so the point hangs on the arm
            let body = robot
                .link(&report.points[k].link)
                .map(|l| l.body())
                .unwrap_or(0);
            lines.push(LinePrimitive {
                r#type: LineType::LineStrip as i32,
                pose: None,
                thickness: 0.02,
                scale_invariant: false,
                points: vec![p3(origin(body)), p3(pr.position_m)],
                color: rgba(0.55, 0.57, 0.62, 1.0),
                colors: vec![],
                indices: vec![],
            });
            point_spheres.push(SpherePrimitive {
                pose: Some(pose_at(pr.position_m)),
                size: Some(Vector3 {
                    x: 0.09,
                    y: 0.09,
                    z: 0.09,
                }),
                color: rgba(r, g, b, 1.0),
            });
            if let Some(u) = pr.direction {
                arrows.push(arrow(pr.position_m, u, 0.1 + 0.3 * pr.speed_mps.min(2.0)));
            }
            // a short tag over the point, staggered by the point's number so that neighbours'
            // tags stand apart (long labels would overlap); the caption above the arm spells
            // each tag out
            let tag_at = [
                pr.position_m[0],
                pr.position_m[1],
                pr.position_m[2] + tag_height(k + 1),
            ];
            // a leader from the point to its tag
            lines.push(LinePrimitive {
                r#type: LineType::LineStrip as i32,
                pose: None,
                thickness: 1.0,
                scale_invariant: true,
                points: vec![p3(pr.position_m), p3(tag_at)],
                color: rgba(0.1, 0.1, 0.1, 1.0),
                colors: vec![],
                indices: vec![],
            });
            texts.push(TextPrimitive {
                pose: Some(pose_at(tag_at)),
                billboard: true,
                font_size: 14.0,
                scale_invariant: true,
                color: rgba(0.1, 0.1, 0.1, 1.0),
                text: point_tag(k),
            });
            caption.push(format!(
                "{} {}: {:.2} m/s, {:.0} % of its permissible speed",
                point_tag(k),
                report.points[k].label(),
                pr.speed_mps,
                100.0 * pr.ratio
            ));
            let state = ArmPointState {
                timestamp: ts,
                speed_mps: pr.speed_mps,
                // unlimited (or at rest): NaN, no point plotted
                v_max_mps: pr
                    .v_max_mps
                    .map(|v| v.value())
                    .filter(|v| v.is_finite())
                    .unwrap_or(f64::NAN),
                ratio: pr.ratio,
                reflected_mass_kg: pr.reflected_mass_kg.unwrap_or(f64::NAN),
            };
            let mut buf = Vec::new();
            state
                .encode(&mut buf)
                .map_err(|e| mcap::McapError::Io(std::io::Error::other(e.to_string())))?;
            write(&mut w, point_channels[k], s.time_s, &buf)?;
        }
        texts.push(TextPrimitive {
            pose: Some(pose_at(caption_anchor)),
            billboard: true,
            font_size: 12.0,
            scale_invariant: true,
            color: rgba(0.1, 0.1, 0.1, 1.0),
            text: caption.join("\n"),
        });
        let update = SceneUpdate {
            deletions: vec![],
            entities: vec![
                SceneEntity {
                    timestamp: Some(ts),
                    frame_id: "world".into(),
                    id: "arm".into(),
                    lines,
                    spheres,
                    ..Default::default()
                },
                SceneEntity {
                    timestamp: Some(ts),
                    frame_id: "world".into(),
                    id: "contact_points".into(),
                    spheres: point_spheres,
                    arrows,
                    texts,
                    ..Default::default()
                },
            ],
        };
        let mut buf = Vec::new();
        update
            .encode(&mut buf)
            .map_err(|e| mcap::McapError::Io(std::io::Error::other(e.to_string())))?;
        write(&mut w, scene, s.time_s, &buf)?;
        let js = JointStates {
            timestamp: Some(ts),
            joints: names
                .iter()
                .zip(&s.q)
                .map(|(n, q)| JointState {
                    name: n.clone(),
                    position: Some(*q),
                    ..Default::default()
                })
                .collect(),
        };
        let mut buf = Vec::new();
        js.encode(&mut buf)
            .map_err(|e| mcap::McapError::Io(std::io::Error::other(e.to_string())))?;
        write(&mut w, joints, s.time_s, &buf)?;
    }
    let mut meta = BTreeMap::new();
    meta.insert("robot".to_string(), report.robot.clone());
    meta.insert("region".to_string(), report.region.clone());
    meta.insert(
        "speed_scale_factor".to_string(),
        format!("{:?}", report.speed_scale_factor),
    );
    w.write_metadata(&mcap::records::Metadata {
        name: "arm".into(),
        metadata: meta,
    })?;
    w.finish()?;
    Ok(w.into_inner().into_inner())
}

fn pose_at(p: [f64; 3]) -> Pose {
    Pose {
        position: Some(Vector3 {
            x: p[0],
            y: p[1],
            z: p[2],
        }),
        orientation: Some(Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        }),
    }
}

/// An arrow from `at` along the unit `u`, `length` m long.
fn arrow(at: [f64; 3], u: [f64; 3], length: f64) -> ArrowPrimitive {
    // the arrow points along its pose's +x: the rotation taking x to u, about x × u
    let (ay, az) = (-u[2], u[1]);
    let s_axis = (ay * ay + az * az).sqrt();
    let angle = u[0].clamp(-1.0, 1.0).acos();
    let (w, qy, qz) = if s_axis > 1e-12 {
        let h = 0.5 * angle;
        (h.cos(), h.sin() * ay / s_axis, h.sin() * az / s_axis)
    } else if u[0] > 0.0 {
        (1.0, 0.0, 0.0)
    } else {
        (0.0, 0.0, 1.0)
    };
    let q = Quaternion {
        x: 0.0,
        y: qy,
        z: qz,
        w,
    };
    ArrowPrimitive {
        pose: Some(Pose {
            position: Some(Vector3 {
                x: at[0],
                y: at[1],
                z: at[2],
            }),
            orientation: Some(q),
        }),
        shaft_length: length * 0.75,
        shaft_diameter: 0.012,
        head_length: length * 0.25,
        head_diameter: 0.03,
        color: rgba(0.15, 0.35, 0.85, 1.0),
    }
}

/// The short tag of contact point `k` in the 3D view and the plots' legends: P1, P2, …
fn point_tag(k: usize) -> String {
    format!("P{}", k + 1)
}

/// Where the 3D view's caption stands \[m\]: over the base, 0.25 m above the highest tag along
/// the path (fixed for the whole log, so it does not jump).
fn caption_anchor(report: &ArmReport) -> [f64; 3] {
    let top = report
        .samples
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.position_m[2]))
        .filter(|z| z.is_finite())
        .fold(0.0_f64, f64::max);
    [0.0, 0.0, top + tag_height(report.points.len()) + 0.25]
}

/// How high the tag of the `k`-th point (from 1) stands above it \[m\]: staggered, 4 cm a point.
fn tag_height(k: usize) -> f64 {
    0.04 + 0.04 * k as f64
}

const COLOURS: [&str; 8] = [
    "#1d3557", "#e76f51", "#2a9d8f", "#8338ec", "#f4a261", "#457b9d", "#d62828", "#6a994e",
];

/// A plot of `field` over the path, one line per point, its legend on the left naming each by
/// its tag (the 3D view's caption spells the tags out: a point's full name would be cut there).
fn plot(title: &str, field: &str, unit: &str, report: &ArmReport) -> Value {
    let paths: Vec<Value> = report
        .points
        .iter()
        .enumerate()
        .map(|(k, _)| {
            json!({
                "value": format!("/arm/point{k}.{field}"),
                "enabled": true,
                "timestampMethod": "receiveTime",
                "label": format!("{} [{unit}]", point_tag(k)),
                "color": COLOURS[k % COLOURS.len()],
                "lineSize": 1.5,
                "showLine": true,
            })
        })
        .collect();
    json!({
        "paths": paths,
        "showXAxisLabels": true,
        "showYAxisLabels": true,
        "showLegend": true,
        "legendDisplay": "left",
        "showPlotValuesInLegend": false,
        "isSynced": true,
        "xAxisVal": "timestamp",
        "sidebarDimension": 200,
        "foxglovePanelTitle": title,
        "lichtblickPanelTitle": title,
    })
}

/// The layout: the 3D view of the arm beside three plots per point over the path — the ratio of
/// speed to permissible speed, the speed, and the reflected mass.
pub fn layout_json(report: &ArmReport) -> Value {
    json!({
        "configById": {
            "3D!arm": {
                "cameraState": {
                    "distance": 1.9,
                    "perspective": true,
                    "phi": 55,
                    "thetaOffset": 35,
                    "targetOffset": [0.0, 0.0, 0.35],
                    "target": [0, 0, 0],
                    "targetOrientation": [0, 0, 0, 1],
                    "fovy": 45,
                    "near": 0.01,
                    "far": 100
                },
                "followMode": "follow-none",
                "scene": { "enableStats": false, "labelScaleFactor": 1, "transforms": { "showLabel": false, "axisScale": 0.3 } },
                "transforms": {},
                "topics": { "/scene": { "visible": true } },
                "layers": {
                    "grid": { "visible": true, "layerId": "foxglove.Grid", "size": 4, "divisions": 20, "position": [0, 0, 0], "rotation": [0, 0, 0], "order": 1 }
                },
                "publish": { "type": "point", "poseTopic": "/move_base_simple/goal", "pointTopic": "/clicked_point", "poseEstimateTopic": "/initialpose", "poseEstimateXDeviation": 0.5, "poseEstimateYDeviation": 0.5, "poseEstimateThetaDeviation": 0.26179939 },
                "imageMode": {}
            },
            "Plot!ratio": plot("Speed / permissible speed (1: the limit)", "ratio", "–", report),
            "Plot!speed": plot("Point speed", "speed_mps", "m/s", report),
            "Plot!mass": plot("Reflected mass along the velocity", "reflected_mass_kg", "kg", report),
        },
        "globalVariables": {},
        "userNodes": {},
        "playbackConfig": { "speed": 0.5 },
        "layout": {
            "first": "3D!arm",
            "second": {
                "first": "Plot!ratio",
                "second": { "first": "Plot!speed", "second": "Plot!mass", "direction": "column" },
                "direction": "column",
                "splitPercentage": 34
            },
            "direction": "row",
            "splitPercentage": 55
        }
    })
}

#[cfg(test)]
mod tests {
    use super::logged_samples;

    /// The bundled swing's 100 Hz samples are logged at 50 Hz: every other one, the first and the
    /// last kept; an uneven series keeps its gaps at 1/50 s at least and its ends.
    #[test]
    fn the_log_keeps_the_ends_and_at_most_fifty_samples_a_second() {
        let even: Vec<f64> = (0..151).map(|i| i as f64 * 0.01).collect();
        assert_eq!(
            logged_samples(&even, 50.0),
            (0..151).step_by(2).collect::<Vec<_>>()
        );
        let odd: Vec<f64> = (0..150).map(|i| i as f64 * 0.01).collect();
        let kept = logged_samples(&odd, 50.0);
        assert_eq!((kept[0], *kept.last().unwrap()), (0, 149));
        let gaps: Vec<f64> = kept.windows(2).map(|w| odd[w[1]] - odd[w[0]]).collect();
        assert!(
            gaps.iter()
                .all(|g| *g >= 0.02 - 1e-12 && *g <= 0.04 + 1e-12),
            "{gaps:?}"
        );
        assert_eq!(logged_samples(&[0.0], 50.0), vec![0]);
        assert!(logged_samples(&[], 50.0).is_empty());
        // slower than the rate: every sample
        let slow = [0.0, 0.1, 0.25, 0.3];
        assert_eq!(logged_samples(&slow, 50.0), vec![0, 1, 2, 3]);
    }
}
