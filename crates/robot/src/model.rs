//! The validated arm: a tree of rigid bodies connected by one-degree-of-freedom joints, built
//! from the URDF's links and joints. Links on fixed joints are merged into the body they hang
//! from (mass, centre of mass and inertia combined by the parallel-axis theorem), so the bodies
//! are the root (the immobile base) and one body per moving joint.

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Isometry3, Unit, Vector3};

use crate::error::RobotError;
use crate::inertia::RigidInertia;
use crate::urdf::{self, JointKind, MAX_URDF_BYTES, RawKind, RawUrdf};

/// A moving joint: degree of freedom `index` of the arm, which moves body `index + 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    name: String,
    kind: JointKind,
    line: u32,
    parent_body: usize,
    origin: Isometry3<f64>,
    axis: Unit<Vector3<f64>>,
    lower: f64,
    upper: f64,
}

impl Joint {
    /// The URDF name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Revolute, continuous or prismatic.
    pub fn kind(&self) -> JointKind {
        self.kind
    }
    /// The line of the `<joint>` element in the URDF.
    pub fn line(&self) -> u32 {
        self.line
    }
    /// The body this joint hangs from (0 is the immobile base).
    pub fn parent_body(&self) -> usize {
        self.parent_body
    }
    /// The joint frame in the parent body's frame (at q = 0 it is the moved body's frame), m.
    pub fn origin(&self) -> &Isometry3<f64> {
        &self.origin
    }
    /// The unit axis in the joint frame.
    pub fn axis(&self) -> &Unit<Vector3<f64>> {
        &self.axis
    }
    /// The lower position limit, rad (revolute) or m (prismatic); −∞ for continuous joints.
    pub fn lower(&self) -> f64 {
        self.lower
    }
    /// The upper position limit, rad (revolute) or m (prismatic); +∞ for continuous joints.
    pub fn upper(&self) -> f64 {
        self.upper
    }
    /// The unit of the joint's position: `rad` or `m`.
    pub fn unit(&self) -> &'static str {
        match self.kind {
            JointKind::Prismatic => "m",
            _ => "rad",
        }
    }
    /// The joint's displacement at position `q`: a rotation about the axis by q (rad) or a
    /// translation along it by q (m).
    pub fn motion(&self, q: f64) -> Isometry3<f64> {
        match self.kind {
            JointKind::Prismatic => {
                Isometry3::translation(self.axis.x * q, self.axis.y * q, self.axis.z * q)
            }
            _ => Isometry3::from_parts(
                nalgebra::Translation3::identity(),
                nalgebra::UnitQuaternion::from_axis_angle(&self.axis, q),
            ),
        }
    }
}

/// A rigid body of the arm: one moving link with every link fixed to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    link: String,
    inertia: RigidInertia,
}

impl Body {
    /// The link whose frame is the body's frame (the moving joint's child, or the root link).
    pub fn link(&self) -> &str {
        &self.link
    }
    /// Its inertia (merged links included) in the body frame.
    pub fn inertia(&self) -> &RigidInertia {
        &self.inertia
    }
}

/// Where a URDF link sits: on which body, and its frame in the body's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkFrame {
    name: String,
    body: usize,
    pose_in_body: Isometry3<f64>,
}

impl LinkFrame {
    /// The URDF name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The body it is part of (0 is the immobile base).
    pub fn body(&self) -> usize {
        self.body
    }
    /// The link frame in the body frame (identity for a body's own link), m.
    pub fn pose_in_body(&self) -> &Isometry3<f64> {
        &self.pose_in_body
    }
}

/// A fixed-base arm loaded from URDF: the model (immutable once built).
///
/// Degrees of freedom are numbered in depth-first order from the root link, children in the
/// order of their joints in the file; joint `i` moves body `i + 1`, and every body's parent
/// has a smaller number. Positions are rad (revolute, continuous) or m (prismatic).
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    name: String,
    source_name: String,
    joints: Vec<Joint>,
    bodies: Vec<Body>,
    links: Vec<LinkFrame>,
}

impl Robot {
    /// Reads a URDF file (at most [`MAX_URDF_BYTES`]).
    pub fn from_urdf_file(path: impl AsRef<Path>) -> Result<Robot, RobotError> {
        let path = path.as_ref();
        let shown = path.display().to_string();
        let text = read_bounded(path, MAX_URDF_BYTES, "URDF file")?;
        Robot::from_urdf_str(&text, &shown)
    }

    /// Reads a URDF document from text; `source_name` names it in error messages.
    pub fn from_urdf_str(text: &str, source_name: &str) -> Result<Robot, RobotError> {
        let raw = urdf::parse(text, source_name)?;
        build(raw)
    }

    /// The `<robot name>`.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The number of degrees of freedom (moving joints).
    pub fn dof(&self) -> usize {
        self.joints.len()
    }
    /// The moving joints in degree-of-freedom order.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }
    /// The bodies: 0 is the immobile base, `i + 1` is moved by joint `i`.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }
    /// Every URDF link, merged or not, in file order.
    pub fn links(&self) -> &[LinkFrame] {
        &self.links
    }
    /// The parent of body `b ≥ 1`.
    pub fn parent_body(&self, b: usize) -> usize {
        self.joints[b - 1].parent_body
    }
    /// A link by name.
    pub fn link(&self, name: &str) -> Result<&LinkFrame, RobotError> {
        Ok(&self.links[self.link_index(name)?])
    }
    /// The index of a link in [`Robot::links`] by name.
    pub fn link_index(&self, name: &str) -> Result<usize, RobotError> {
        self.links
            .iter()
            .position(|l| l.name == name)
            .ok_or_else(|| RobotError::UnknownLink {
                robot: self.name.clone(),
                name: name.to_string(),
                known: self
                    .links
                    .iter()
                    .map(|l| l.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
    /// The degree-of-freedom index of a moving joint by name.
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }
    /// The total moving mass (every body but the base), kg.
    pub fn moving_mass(&self) -> f64 {
        self.bodies[1..].iter().map(|b| b.inertia.mass).sum()
    }
    /// The file name the robot was read from (for messages).
    pub fn source_name(&self) -> &str {
        &self.source_name
    }

    /// Checks a joint-position vector: its length is [`Robot::dof`] and every entry is finite
    /// (limits are not checked here; trajectories check them).
    pub fn check_positions(&self, q: &[f64]) -> Result<(), RobotError> {
        self.check_vector("q", q, "rad or m")
    }

    pub(crate) fn check_vector(&self, what: &str, v: &[f64], unit: &str) -> Result<(), RobotError> {
        if v.len() != self.dof() {
            return Err(RobotError::parameter(
                format!("the length of {what}"),
                v.len(),
                format!(
                    "robot {:?} has {} moving joints ({})",
                    self.name,
                    self.dof(),
                    self.joint_names().join(", ")
                ),
            ));
        }
        for (i, x) in v.iter().enumerate() {
            if !x.is_finite() {
                return Err(RobotError::parameter(
                    format!("{what}[{i}] ({})", self.joints[i].name),
                    x,
                    format!("a finite number, {unit}"),
                ));
            }
        }
        Ok(())
    }

    /// The moving joints' names in degree-of-freedom order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.joints.iter().map(|j| j.name.as_str()).collect()
    }
}

/// Reads at most `max` bytes of a UTF-8 file; larger files are refused before reading.
pub(crate) fn read_bounded(
    path: &Path,
    max: u64,
    what: &'static str,
) -> Result<String, RobotError> {
    use std::io::Read;
    let shown = path.display().to_string();
    let io = |e: std::io::Error| RobotError::Io {
        path: shown.clone(),
        reason: e.to_string(),
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let len = file.metadata().map_err(io)?.len();
    let too_large = |bytes| RobotError::FileTooLarge {
        path: shown.clone(),
        bytes,
        max,
        what,
    };
    if len > max {
        return Err(too_large(len));
    }
    let mut bytes = Vec::new();
    file.take(max + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > max {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| RobotError::Io {
        path: shown.clone(),
        reason: format!("not UTF-8 text ({e})"),
    })
}

fn urdf_err(raw: &RawUrdf, line: u32, element: String, problem: String) -> RobotError {
    RobotError::Urdf {
        source_name: raw.source_name.clone(),
        line,
        element,
        problem,
    }
}

/// Topology checks, fixed-joint merging and body numbering.
fn build(raw: RawUrdf) -> Result<Robot, RobotError> {
    // Unique names.
    let mut link_index: HashMap<&str, usize> = HashMap::new();
    for (i, l) in raw.links.iter().enumerate() {
        if let Some(&first) = link_index.get(l.name.as_str()) {
            return Err(urdf_err(
                &raw,
                l.line,
                format!("link {:?}", l.name),
                format!(
                    "a second link with this name (the first is on line {}); link names must \
                     be unique",
                    raw.links[first].line
                ),
            ));
        }
        link_index.insert(&l.name, i);
    }
    if raw.links.is_empty() {
        return Err(urdf_err(
            &raw,
            1,
            "<robot>".into(),
            "has no <link>; an arm needs at least one".into(),
        ));
    }
    let mut joint_names: HashMap<&str, usize> = HashMap::new();
    let mut parent_joint: Vec<Option<usize>> = vec![None; raw.links.len()];
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); raw.links.len()];
    for (j, joint) in raw.joints.iter().enumerate() {
        let element = format!("joint {:?}", joint.name);
        if let Some(&first) = joint_names.get(joint.name.as_str()) {
            return Err(urdf_err(
                &raw,
                joint.line,
                element,
                format!(
                    "a second joint with this name (the first is on line {}); joint names must \
                     be unique",
                    raw.joints[first].line
                ),
            ));
        }
        joint_names.insert(&joint.name, j);
        let find = |which: &str, name: &str| {
            link_index.get(name).copied().ok_or_else(|| {
                urdf_err(
                    &raw,
                    joint.line,
                    element.clone(),
                    format!("its {which} link {name:?} is not a <link> of this robot"),
                )
            })
        };
        let p = find("parent", &joint.parent)?;
        let c = find("child", &joint.child)?;
        if p == c {
            return Err(urdf_err(
                &raw,
                joint.line,
                element,
                format!(
                    "connects link {:?} to itself (a cycle); a joint connects two links",
                    joint.parent
                ),
            ));
        }
        if let Some(other) = parent_joint[c] {
            return Err(urdf_err(
                &raw,
                joint.line,
                element,
                format!(
                    "link {:?} already has the parent joint {:?} (line {}); a link with two \
                     parents closes a loop, and closed loops are not supported",
                    joint.child, raw.joints[other].name, raw.joints[other].line
                ),
            ));
        }
        parent_joint[c] = Some(j);
        children[p].push(j);
    }
    let roots: Vec<usize> = (0..raw.links.len())
        .filter(|&l| parent_joint[l].is_none())
        .collect();
    if roots.is_empty() {
        let l = &raw.links[0];
        return Err(urdf_err(
            &raw,
            l.line,
            format!("link {:?}", l.name),
            "every link has a parent joint, so the joints form a cycle; an arm is a tree with \
             one root link"
                .into(),
        ));
    }
    if roots.len() > 1 {
        let names: Vec<String> = roots
            .iter()
            .map(|&r| format!("{:?} (line {})", raw.links[r].name, raw.links[r].line))
            .collect();
        let second = &raw.links[roots[1]];
        return Err(urdf_err(
            &raw,
            second.line,
            format!("link {:?}", second.name),
            format!(
                "the robot has {} root links (links without a parent joint): {}; an arm has \
                 exactly one, connect the others with joints",
                roots.len(),
                names.join(", ")
            ),
        ));
    }
    let root = roots[0];

    // Depth-first from the root; a moving joint opens a body, a fixed joint places its child
    // on the parent's body.
    let mut placement: Vec<Option<(usize, Isometry3<f64>)>> = vec![None; raw.links.len()];
    placement[root] = Some((0, Isometry3::identity()));
    let mut bodies = vec![Body {
        link: raw.links[root].name.clone(),
        inertia: RigidInertia::zero(),
    }];
    let mut joints: Vec<Joint> = Vec::new();
    let mut body_joint_line: Vec<(u32, String)> = vec![(0, String::new())];
    let mut stack: Vec<usize> = children[root].iter().rev().copied().collect();
    while let Some(j) = stack.pop() {
        let joint = &raw.joints[j];
        let p = link_index[joint.parent.as_str()];
        let c = link_index[joint.child.as_str()];
        let (pb, p_pose) = placement[p].expect("a parent is placed before its children");
        let origin = p_pose * joint.origin;
        placement[c] = Some(match joint.kind {
            RawKind::Fixed => (pb, origin),
            RawKind::Moving(kind) => {
                joints.push(Joint {
                    name: joint.name.clone(),
                    kind,
                    line: joint.line,
                    parent_body: pb,
                    origin,
                    axis: joint.axis,
                    lower: joint.lower,
                    upper: joint.upper,
                });
                bodies.push(Body {
                    link: joint.child.clone(),
                    inertia: RigidInertia::zero(),
                });
                body_joint_line.push((joint.line, joint.name.clone()));
                (bodies.len() - 1, Isometry3::identity())
            }
        });
        stack.extend(children[c].iter().rev().copied());
    }
    if let Some(l) = (0..raw.links.len()).find(|&l| placement[l].is_none()) {
        let link = &raw.links[l];
        return Err(urdf_err(
            &raw,
            link.line,
            format!("link {:?}", link.name),
            format!(
                "cannot be reached from the root link {:?}: its joints form a cycle; an arm \
                 is a tree",
                raw.links[root].name
            ),
        ));
    }

    // Merge the inertias into the bodies.
    let mut links = Vec::with_capacity(raw.links.len());
    for (l, link) in raw.links.iter().enumerate() {
        let (b, pose) = placement[l].expect("checked above");
        if let Some(inertial) = &link.inertial {
            let in_link = RigidInertia {
                mass: inertial.mass,
                com: Vector3::zeros(),
                inertia: inertial.inertia,
            }
            .transformed(&inertial.origin);
            let in_body = in_link.transformed(&pose);
            bodies[b].inertia = bodies[b].inertia.combined(&in_body);
        }
        links.push(LinkFrame {
            name: link.name.clone(),
            body: b,
            pose_in_body: pose,
        });
    }
    for (b, body) in bodies.iter().enumerate().skip(1) {
        if !(body.inertia.mass > 0.0) {
            let l = link_index[body.link.as_str()];
            let (jline, jname) = &body_joint_line[b];
            let has_inertial = raw.links[l].inertial.is_some();
            return Err(urdf_err(
                &raw,
                raw.links[l].line,
                format!("link {:?}", body.link),
                format!(
                    "moves with joint {jname:?} (line {jline}) but {} and no link fixed to it \
                     has mass; a moving link needs <inertial> with a mass > 0 kg",
                    if has_inertial {
                        "its <inertial> has zero mass"
                    } else {
                        "has no <inertial>"
                    }
                ),
            ));
        }
    }
    Ok(Robot {
        name: raw.robot_name,
        source_name: raw.source_name,
        joints,
        bodies,
        links,
    })
}
