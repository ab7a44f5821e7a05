//! Joint trajectories: samples of time and joint positions, their joint velocities by finite
//! differences, and, along them, every candidate contact point's position, velocity, contact
//! direction (its velocity's direction) and reflected mass along it.
//!
//! # CSV format
//!
//! ```text
//! # comment lines start with '#'; blank lines are skipped
//! time_s,shoulder_pan_joint,shoulder_lift_joint,...
//! 0.0,0.0,-1.57,...
//! 0.01,0.001,-1.569,...
//! ```
//!
//! The header's first column is `time_s` (s); the others name every moving joint of the robot
//! exactly once, in any order; positions are rad for revolute and continuous joints, m for
//! prismatic ones. Refused, with the line number: a wrong column count, a value that is not a
//! finite number, time not strictly increasing, an unknown, fixed, duplicated or missing joint,
//! fewer than 3 or more than [`MAX_SAMPLES`] samples, files over [`MAX_CSV_BYTES`], and a
//! position outside the joint's URDF limits (an **error**, not a warning: a trajectory outside
//! the limits is not a motion of the arm the URDF describes).
//!
//! # Joint velocities
//!
//! Second-order finite differences on the (possibly non-uniform) time grid: the three-point
//! central formula at interior samples,
//! q̇ᵢ ≈ −h₂/(h₁(h₁+h₂)) qᵢ₋₁ + (h₂−h₁)/(h₁h₂) qᵢ + h₁/(h₂(h₁+h₂)) qᵢ₊₁ (h₁ = tᵢ − tᵢ₋₁,
//! h₂ = tᵢ₊₁ − tᵢ), and the three-point one-sided formulas at the first and last samples; all
//! exact for quadratic motions, error O(h²).

use std::path::Path;

use crate::dynamics::{ContactPoint, Workspace};
use crate::error::RobotError;
use crate::model::{Robot, read_bounded};
use crate::reflected::{JointModel, PointSample, Posture};

/// The largest trajectory CSV read, in bytes.
pub const MAX_CSV_BYTES: u64 = 16 * 1024 * 1024;
/// The most samples a trajectory may have (bounded memory: 1 000 000 samples of a 7-joint arm
/// hold about 100 MB).
pub const MAX_SAMPLES: usize = 1_000_000;

/// A validated joint trajectory of one robot (degree-of-freedom order).
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    times: Vec<f64>,
    positions: Vec<Vec<f64>>,
}

/// One sample of a trajectory with its contact points.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub time: f64,
    /// Joint positions, rad or m.
    pub q: Vec<f64>,
    /// Joint velocities, rad/s or m/s (second-order finite differences).
    pub qdot: Vec<f64>,
    /// The contact points, in the order given.
    pub points: Vec<PointSample>,
}

impl Trajectory {
    /// Reads a trajectory CSV (format in the module documentation) for `robot`.
    pub fn from_csv_file(robot: &Robot, path: impl AsRef<Path>) -> Result<Trajectory, RobotError> {
        let path = path.as_ref();
        let text = read_bounded(path, MAX_CSV_BYTES, "trajectory CSV")?;
        Trajectory::from_csv_str(robot, &text, &path.display().to_string())
    }

    /// Reads a trajectory CSV from text; `source_name` names it in error messages.
    pub fn from_csv_str(
        robot: &Robot,
        text: &str,
        source_name: &str,
    ) -> Result<Trajectory, RobotError> {
        let err = |line: usize, problem: String| RobotError::Csv {
            source_name: source_name.to_string(),
            line,
            problem,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (header_line, header) = lines
            .next()
            .ok_or_else(|| err(0, "the file has no header line".into()))?;
        let columns: Vec<&str> = header.split(',').map(str::trim).collect();
        if columns[0] != "time_s" {
            return Err(err(
                header_line,
                format!(
                    "the first column must be \"time_s\" (time in seconds), found {:?}",
                    columns[0]
                ),
            ));
        }
        // Column k + 1 holds joint dof_of_column[k].
        let mut dof_of_column = Vec::with_capacity(columns.len() - 1);
        let mut seen = vec![false; robot.dof()];
        for name in &columns[1..] {
            let Some(i) = robot.joint_index(name) else {
                let fixed = robot.links().iter().any(|l| l.name() == *name);
                return Err(err(
                    header_line,
                    format!(
                        "column {name:?} is not a moving joint of robot {:?}{}; its moving \
                         joints are {}",
                        robot.name(),
                        if fixed { " (it is a link name)" } else { "" },
                        robot.joint_names().join(", ")
                    ),
                ));
            };
            if seen[i] {
                return Err(err(
                    header_line,
                    format!("column {name:?} appears twice; each joint once"),
                ));
            }
            seen[i] = true;
            dof_of_column.push(i);
        }
        let missing: Vec<&str> = robot
            .joints()
            .iter()
            .zip(&seen)
            .filter(|(_, s)| !**s)
            .map(|(j, _)| j.name())
            .collect();
        if !missing.is_empty() {
            return Err(err(
                header_line,
                format!(
                    "the header lacks the joints {}; every moving joint needs a column",
                    missing.join(", ")
                ),
            ));
        }
        let mut times = Vec::new();
        let mut positions = Vec::new();
        let mut lines_of = Vec::new();
        for (line, row) in lines {
            if times.len() == MAX_SAMPLES {
                return Err(err(
                    line,
                    format!("more than {MAX_SAMPLES} samples; at most {MAX_SAMPLES} are read"),
                ));
            }
            let cells: Vec<&str> = row.split(',').map(str::trim).collect();
            if cells.len() != columns.len() {
                return Err(err(
                    line,
                    format!("{} columns, the header has {}", cells.len(), columns.len()),
                ));
            }
            let mut values = Vec::with_capacity(cells.len());
            for (k, cell) in cells.iter().enumerate() {
                match cell.parse::<f64>() {
                    Ok(v) if v.is_finite() => values.push(v),
                    _ => {
                        return Err(err(
                            line,
                            format!("column {:?}: {cell:?} is not a finite number", columns[k]),
                        ));
                    }
                }
            }
            let mut q = vec![0.0; robot.dof()];
            for (k, &i) in dof_of_column.iter().enumerate() {
                q[i] = values[k + 1];
            }
            times.push(values[0]);
            positions.push(q);
            lines_of.push(line);
        }
        Trajectory::validated(robot, times, positions, |s| lines_of[s])
            .map_err(|(s, problem)| err(if s < lines_of.len() { lines_of[s] } else { 0 }, problem))
    }

    /// A trajectory from sampled times (s, strictly increasing, at least 3) and joint positions
    /// (rad or m, degree-of-freedom order, within the limits).
    pub fn new(
        robot: &Robot,
        times: Vec<f64>,
        positions: Vec<Vec<f64>>,
    ) -> Result<Trajectory, RobotError> {
        let t = times.clone();
        Trajectory::validated(robot, times, positions, |s| s).map_err(|(s, problem)| {
            if s < t.len() {
                RobotError::parameter(
                    format!("trajectory sample {s}"),
                    format!("t = {} s", t[s]),
                    problem,
                )
            } else {
                RobotError::parameter("trajectory samples", t.len(), problem)
            }
        })
    }

    /// Checks samples; errors carry the sample index and the problem (`label` names a sample
    /// in the text: its CSV line or its index).
    fn validated(
        robot: &Robot,
        times: Vec<f64>,
        positions: Vec<Vec<f64>>,
        label: impl Fn(usize) -> usize,
    ) -> Result<Trajectory, (usize, String)> {
        if times.len() != positions.len() {
            return Err((
                usize::MAX,
                format!(
                    "{} times but {} position vectors; one of each per sample",
                    times.len(),
                    positions.len()
                ),
            ));
        }
        if times.len() > MAX_SAMPLES {
            return Err((
                usize::MAX,
                format!("{} samples; at most {MAX_SAMPLES} are allowed", times.len()),
            ));
        }
        if times.len() < 3 {
            return Err((
                usize::MAX,
                format!(
                    "{} samples; at least 3 are needed for second-order joint velocities",
                    times.len()
                ),
            ));
        }
        for (s, (t, q)) in times.iter().zip(&positions).enumerate() {
            if !t.is_finite() {
                return Err((s, format!("time {t} s is not a finite number")));
            }
            if s > 0 && !(*t > times[s - 1]) {
                return Err((
                    s,
                    format!(
                        "time {t} s does not increase (the sample before, {}, is at {} s); \
                         times must be strictly increasing",
                        label(s - 1),
                        times[s - 1]
                    ),
                ));
            }
            if q.len() != robot.dof() {
                return Err((
                    s,
                    format!("{} joint positions, the robot has {}", q.len(), robot.dof()),
                ));
            }
            for (x, joint) in q.iter().zip(robot.joints()) {
                if !x.is_finite() {
                    return Err((s, format!("joint {:?}: {x} is not finite", joint.name())));
                }
                if *x < joint.lower() || *x > joint.upper() {
                    return Err((
                        s,
                        format!(
                            "joint {:?} at {x} {} is outside its limits [{}, {}] {} (URDF line \
                             {})",
                            joint.name(),
                            joint.unit(),
                            joint.lower(),
                            joint.upper(),
                            joint.unit(),
                            joint.line()
                        ),
                    ));
                }
            }
        }
        Ok(Trajectory { times, positions })
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }
    /// Never empty (at least 3 samples); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }
    /// Sample times, s.
    pub fn times(&self) -> &[f64] {
        &self.times
    }
    /// Joint positions per sample, rad or m.
    pub fn positions(&self) -> &[Vec<f64>] {
        &self.positions
    }

    /// The same path at `speed_scale` times the speed: times divided by the scale (so joint
    /// velocities are multiplied by it); the scale must be finite and > 0.
    pub fn with_speed_scale(&self, speed_scale: f64) -> Result<Trajectory, RobotError> {
        if !(speed_scale > 0.0 && speed_scale.is_finite()) {
            return Err(RobotError::parameter(
                "speed_scale",
                speed_scale,
                "a finite number > 0 (1 is the trajectory as given, 2 twice as fast)",
            ));
        }
        Ok(Trajectory {
            times: self.times.iter().map(|t| t / speed_scale).collect(),
            positions: self.positions.clone(),
        })
    }

    /// Joint velocities at every sample (rad/s or m/s), by second-order finite differences
    /// (module documentation).
    pub fn velocities(&self) -> Vec<Vec<f64>> {
        let t = &self.times;
        let q = &self.positions;
        let n = t.len();
        let dof = q[0].len();
        let combine = |w: [f64; 3], idx: [usize; 3]| -> Vec<f64> {
            (0..dof)
                .map(|k| w[0] * q[idx[0]][k] + w[1] * q[idx[1]][k] + w[2] * q[idx[2]][k])
                .collect()
        };
        (0..n)
            .map(|i| {
                if i == 0 {
                    let (h1, h2) = (t[1] - t[0], t[2] - t[1]);
                    combine(
                        [
                            -(2.0 * h1 + h2) / (h1 * (h1 + h2)),
                            (h1 + h2) / (h1 * h2),
                            -h1 / (h2 * (h1 + h2)),
                        ],
                        [0, 1, 2],
                    )
                } else if i == n - 1 {
                    let (ha, hb) = (t[n - 1] - t[n - 2], t[n - 2] - t[n - 3]);
                    combine(
                        [
                            (2.0 * ha + hb) / (ha * (ha + hb)),
                            -(ha + hb) / (ha * hb),
                            ha / (hb * (ha + hb)),
                        ],
                        [n - 1, n - 2, n - 3],
                    )
                } else {
                    let (h1, h2) = (t[i] - t[i - 1], t[i + 1] - t[i]);
                    combine(
                        [
                            -h2 / (h1 * (h1 + h2)),
                            (h2 - h1) / (h1 * h2),
                            h1 / (h2 * (h1 + h2)),
                        ],
                        [i - 1, i, i + 1],
                    )
                }
            })
            .collect()
    }

    /// Every sample with, for each contact point, its position, velocity, speed, direction
    /// (the velocity's) and the reflected mass along it under `joint_model`.
    pub fn evaluate(
        &self,
        robot: &Robot,
        points: &[ContactPoint],
        joint_model: JointModel,
    ) -> Result<Vec<Sample>, RobotError> {
        let mut ws = Workspace::new(robot);
        let velocities = self.velocities();
        let mut out = Vec::with_capacity(self.len());
        for ((time, q), qdot) in self.times.iter().zip(&self.positions).zip(velocities) {
            let mut posture = Posture::new(robot, q, joint_model, &mut ws)?;
            let samples = points
                .iter()
                .map(|point| posture.motion(point, &qdot))
                .collect::<Result<Vec<_>, _>>()?;
            out.push(Sample {
                time: *time,
                q: q.clone(),
                qdot,
                points: samples,
            });
        }
        Ok(out)
    }
}
