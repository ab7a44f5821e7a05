//! Reading a URDF document into plain link and joint records with their line numbers; no
//! topology here (that is [`crate::model`]'s). Only the elements that the dynamics needs are read:
//! `<link>` with `<inertial>` (`<origin>`, `<mass>`, `<inertia>`), `<joint>` with `<parent>`,
//! `<child>`, `<origin>`, `<axis>`, `<limit>`; `<visual>`, `<collision>`, `<dynamics>`,
//! `<transmission>`, `<gazebo>` and the rest are ignored. `<mimic>` and the floating and planar
//! joint types are refused.

use nalgebra::{Isometry3, Matrix3, Unit, Vector3};
use roxmltree::{Document, Node, ParsingOptions};

use crate::error::RobotError;
use crate::inertia::pose_from_xyz_rpy;

/// The largest URDF file read, in bytes (16 MiB: real arms take tens of kilobytes).
pub const MAX_URDF_BYTES: u64 = 16 * 1024 * 1024;
/// The most links a URDF may have.
pub const MAX_LINKS: usize = 1024;
/// The most joints a URDF may have.
pub const MAX_JOINTS: usize = 1024;
/// The most XML markup tags (`<`) a URDF may have, checked before parsing (bounded memory).
pub const MAX_XML_TAGS: usize = 1_000_000;
/// The deepest nesting of XML elements read, checked before parsing (the XML parser recurses
/// per level; a URDF nests about 5 deep).
pub const MAX_XML_DEPTH: usize = 256;

/// The kind of a moving joint: one degree of freedom each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about the axis within `[lower, upper]` (rad).
    Revolute,
    /// Rotation about the axis without limits (rad).
    Continuous,
    /// Translation along the axis within `[lower, upper]` (m).
    Prismatic,
}

impl JointKind {
    /// The URDF type name.
    pub fn urdf_name(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
        }
    }
}

/// A joint's type as read: moving, or fixed (merged into its parent).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RawKind {
    Moving(JointKind),
    Fixed,
}

/// `<inertial>` as read: its frame in the link frame, mass (kg), inertia about the centre of
/// mass in the inertial frame (kg·m²).
#[derive(Debug, Clone)]
pub(crate) struct RawInertial {
    pub origin: Isometry3<f64>,
    pub mass: f64,
    pub inertia: Matrix3<f64>,
}

#[derive(Debug, Clone)]
pub(crate) struct RawLink {
    pub name: String,
    pub line: u32,
    pub inertial: Option<RawInertial>,
}

#[derive(Debug, Clone)]
pub(crate) struct RawJoint {
    pub name: String,
    pub line: u32,
    pub kind: RawKind,
    pub parent: String,
    pub child: String,
    /// The child link's frame in the parent link's frame at q = 0.
    pub origin: Isometry3<f64>,
    /// Unit axis in the joint frame.
    pub axis: Unit<Vector3<f64>>,
    pub lower: f64,
    pub upper: f64,
}

#[derive(Debug, Clone)]
pub(crate) struct RawUrdf {
    pub source_name: String,
    pub robot_name: String,
    pub links: Vec<RawLink>,
    pub joints: Vec<RawJoint>,
}

/// Byte offset → 1-based line, by binary search over the line starts.
struct LineIndex {
    starts: Vec<usize>,
}

impl LineIndex {
    fn new(text: &str) -> Self {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|(_, b)| *b == b'\n')
                .map(|(i, _)| i + 1),
        );
        LineIndex { starts }
    }

    fn line(&self, pos: usize) -> u32 {
        self.starts.partition_point(|&s| s <= pos) as u32
    }
}

struct Reader<'a> {
    source_name: &'a str,
    lines: LineIndex,
}

impl Reader<'_> {
    fn line_of(&self, node: Node) -> u32 {
        self.lines.line(node.range().start)
    }

    fn err(&self, node: Node, element: &str, problem: impl Into<String>) -> RobotError {
        RobotError::Urdf {
            source_name: self.source_name.to_string(),
            line: self.line_of(node),
            element: element.to_string(),
            problem: problem.into(),
        }
    }

    /// The one child element `tag` of `node`, if any; two are refused.
    fn only_child<'a, 'i>(
        &self,
        node: Node<'a, 'i>,
        tag: &str,
        element: &str,
    ) -> Result<Option<Node<'a, 'i>>, RobotError> {
        let mut found = node.children().filter(|c| c.has_tag_name(tag));
        let first = found.next();
        if let Some(second) = found.next() {
            return Err(self.err(
                second,
                element,
                format!("has a second <{tag}> element; one is allowed"),
            ));
        }
        Ok(first)
    }

    fn required_attr<'a>(
        &self,
        node: Node<'a, '_>,
        attr: &str,
        element: &str,
    ) -> Result<&'a str, RobotError> {
        node.attribute(attr).ok_or_else(|| {
            self.err(
                node,
                element,
                format!("<{}> has no {attr} attribute", node.tag_name().name()),
            )
        })
    }

    fn number(&self, node: Node, attr: &str, text: &str, element: &str) -> Result<f64, RobotError> {
        match text.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.err(
                node,
                element,
                format!(
                    "<{} {attr}=\"{text}\">: not a finite number (NaN and infinities are refused)",
                    node.tag_name().name()
                ),
            )),
            Err(_) => Err(self.err(
                node,
                element,
                format!(
                    "<{} {attr}=\"{text}\">: not a number",
                    node.tag_name().name()
                ),
            )),
        }
    }

    /// A required attribute holding one finite number.
    fn scalar(&self, node: Node, attr: &str, element: &str) -> Result<f64, RobotError> {
        let text = self.required_attr(node, attr, element)?;
        self.number(node, attr, text, element)
    }

    /// An optional attribute holding one finite number, `default` when absent.
    fn scalar_or(
        &self,
        node: Node,
        attr: &str,
        default: f64,
        element: &str,
    ) -> Result<f64, RobotError> {
        match node.attribute(attr) {
            None => Ok(default),
            Some(text) => self.number(node, attr, text, element),
        }
    }

    /// An optional attribute holding three finite numbers separated by white space.
    fn triple(
        &self,
        node: Node,
        attr: &str,
        default: [f64; 3],
        element: &str,
    ) -> Result<[f64; 3], RobotError> {
        let Some(text) = node.attribute(attr) else {
            return Ok(default);
        };
        let parts: Vec<&str> = text.split_whitespace().collect();
        if parts.len() != 3 {
            return Err(self.err(
                node,
                element,
                format!(
                    "<{} {attr}=\"{text}\">: three numbers separated by spaces are required, \
                     found {}",
                    node.tag_name().name(),
                    parts.len()
                ),
            ));
        }
        let mut out = [0.0; 3];
        for (o, p) in out.iter_mut().zip(&parts) {
            *o = self.number(node, attr, p, element)?;
        }
        Ok(out)
    }

    /// `<origin xyz rpy>` (both optional, zero by default); identity when the element is absent.
    fn origin(&self, parent: Node, element: &str) -> Result<Isometry3<f64>, RobotError> {
        match self.only_child(parent, "origin", element)? {
            None => Ok(Isometry3::identity()),
            Some(o) => {
                let xyz = self.triple(o, "xyz", [0.0; 3], element)?;
                let rpy = self.triple(o, "rpy", [0.0; 3], element)?;
                Ok(pose_from_xyz_rpy(xyz, rpy))
            }
        }
    }

    fn name(&self, node: Node, what: &str) -> Result<String, RobotError> {
        match node.attribute("name") {
            Some(n) if !n.trim().is_empty() => Ok(n.to_string()),
            _ => Err(self.err(
                node,
                &format!("<{what}>"),
                "has no name attribute (a non-empty name is required)",
            )),
        }
    }

    fn link(&self, node: Node) -> Result<RawLink, RobotError> {
        let name = self.name(node, "link")?;
        let element = format!("link {name:?}");
        let inertial = match self.only_child(node, "inertial", &element)? {
            None => None,
            Some(i) => Some(self.inertial(i, &element)?),
        };
        Ok(RawLink {
            name,
            line: self.line_of(node),
            inertial,
        })
    }

    fn inertial(&self, node: Node, element: &str) -> Result<RawInertial, RobotError> {
        let origin = self.origin(node, element)?;
        let mass_node = self
            .only_child(node, "mass", element)?
            .ok_or_else(|| self.err(node, element, "<inertial> has no <mass value=\"…\"/>"))?;
        let mass = self.scalar(mass_node, "value", element)?;
        if mass < 0.0 {
            return Err(self.err(
                mass_node,
                element,
                format!("<mass value=\"{mass}\">: a mass must be ≥ 0 kg"),
            ));
        }
        let i = self.only_child(node, "inertia", element)?.ok_or_else(|| {
            self.err(
                node,
                element,
                "<inertial> has no <inertia ixx ixy ixz iyy iyz izz/>",
            )
        })?;
        let mut v = [0.0; 6];
        for (k, attr) in ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
            .iter()
            .enumerate()
        {
            v[k] = self.scalar(i, attr, element)?;
        }
        let inertia = Matrix3::new(v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5]);
        if let Some(problem) = crate::inertia::inertia_problem(&inertia) {
            return Err(self.err(i, element, problem));
        }
        Ok(RawInertial {
            origin,
            mass,
            inertia,
        })
    }

    fn joint(&self, node: Node) -> Result<RawJoint, RobotError> {
        let name = self.name(node, "joint")?;
        let element = format!("joint {name:?}");
        let type_name = self.required_attr(node, "type", &element)?;
        let kind = match type_name {
            "revolute" => RawKind::Moving(JointKind::Revolute),
            "continuous" => RawKind::Moving(JointKind::Continuous),
            "prismatic" => RawKind::Moving(JointKind::Prismatic),
            "fixed" => RawKind::Fixed,
            "floating" | "planar" => {
                return Err(self.err(
                    node,
                    &element,
                    format!(
                        "type \"{type_name}\" is not supported (a fixed-base arm has revolute, \
                         continuous, prismatic and fixed joints)"
                    ),
                ));
            }
            other => {
                return Err(self.err(
                    node,
                    &element,
                    format!(
                        "unknown type \"{other}\"; allowed are revolute, continuous, prismatic, \
                         fixed"
                    ),
                ));
            }
        };
        if let Some(m) = node.children().find(|c| c.has_tag_name("mimic")) {
            return Err(self.err(
                m,
                &element,
                "<mimic> joints are not supported (the joint would not be an independent degree \
                 of freedom); make it fixed or remove the <mimic> element",
            ));
        }
        let link_of = |tag: &str| -> Result<String, RobotError> {
            let n = self
                .only_child(node, tag, &element)?
                .ok_or_else(|| self.err(node, &element, format!("has no <{tag} link=\"…\"/>")))?;
            let l = self.required_attr(n, "link", &element)?;
            Ok(l.to_string())
        };
        let parent = link_of("parent")?;
        let child = link_of("child")?;
        let origin = self.origin(node, &element)?;
        let axis = match self.only_child(node, "axis", &element)? {
            None => Vector3::x(),
            Some(a) => {
                let v = Vector3::from(self.triple(a, "xyz", [1.0, 0.0, 0.0], &element)?);
                if v.norm() < 1e-9 {
                    return Err(self.err(
                        a,
                        &element,
                        format!(
                            "<axis xyz=\"{} {} {}\">: the axis must have a non-zero length",
                            v.x, v.y, v.z
                        ),
                    ));
                }
                v
            }
        };
        let axis = Unit::new_normalize(axis);
        let (lower, upper) = match kind {
            RawKind::Moving(JointKind::Revolute) | RawKind::Moving(JointKind::Prismatic) => {
                let l = self.only_child(node, "limit", &element)?.ok_or_else(|| {
                    self.err(
                        node,
                        &element,
                        format!(
                            "a {type_name} joint needs <limit lower=\"…\" upper=\"…\"/> (use \
                             type \"continuous\" for an unlimited revolute joint)"
                        ),
                    )
                })?;
                let lower = self.scalar_or(l, "lower", 0.0, &element)?;
                let upper = self.scalar_or(l, "upper", 0.0, &element)?;
                if lower > upper {
                    return Err(self.err(
                        l,
                        &element,
                        format!(
                            "<limit lower=\"{lower}\" upper=\"{upper}\">: lower must be ≤ upper"
                        ),
                    ));
                }
                (lower, upper)
            }
            _ => (f64::NEG_INFINITY, f64::INFINITY),
        };
        Ok(RawJoint {
            name,
            line: self.line_of(node),
            kind,
            parent,
            child,
            origin,
            axis,
            lower,
            upper,
        })
    }
}

/// Parses a URDF document (its text) into link and joint records.
pub(crate) fn parse(text: &str, source_name: &str) -> Result<RawUrdf, RobotError> {
    if text.len() as u64 > MAX_URDF_BYTES {
        return Err(RobotError::FileTooLarge {
            path: source_name.to_string(),
            bytes: text.len() as u64,
            max: MAX_URDF_BYTES,
            what: "URDF file",
        });
    }
    let (depth, at) = nesting_depth(text);
    if depth > MAX_XML_DEPTH {
        return Err(RobotError::Urdf {
            source_name: source_name.to_string(),
            line: LineIndex::new(text).line(at),
            element: "the document".into(),
            problem: format!(
                "nests XML elements more than {MAX_XML_DEPTH} deep; a URDF nests about 5 deep"
            ),
        });
    }
    let tags = text.bytes().filter(|&b| b == b'<').count();
    if tags > MAX_XML_TAGS {
        return Err(RobotError::Urdf {
            source_name: source_name.to_string(),
            line: 1,
            element: "the document".into(),
            problem: format!(
                "has {tags} XML tags; at most {MAX_XML_TAGS} are read (a real arm has a few \
                 thousand)"
            ),
        });
    }
    let options = ParsingOptions {
        allow_dtd: false,
        nodes_limit: (2 * MAX_XML_TAGS) as u32,
    };
    let doc = Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        RobotError::Xml {
            source_name: source_name.to_string(),
            line: pos.row,
            column: pos.col,
            reason: e.to_string(),
        }
    })?;
    let reader = Reader {
        source_name,
        lines: LineIndex::new(text),
    };
    let root = doc.root_element();
    if !root.has_tag_name("robot") {
        return Err(reader.err(
            root,
            &format!("<{}>", root.tag_name().name()),
            "the root element of a URDF must be <robot>",
        ));
    }
    let robot_name = root.attribute("name").unwrap_or("").to_string();
    let mut links = Vec::new();
    let mut joints = Vec::new();
    for child in root.children().filter(Node::is_element) {
        match child.tag_name().name() {
            "link" => {
                if links.len() == MAX_LINKS {
                    return Err(reader.err(
                        child,
                        "<link>",
                        format!("more than {MAX_LINKS} links; at most {MAX_LINKS} are read"),
                    ));
                }
                links.push(reader.link(child)?);
            }
            "joint" => {
                if joints.len() == MAX_JOINTS {
                    return Err(reader.err(
                        child,
                        "<joint>",
                        format!("more than {MAX_JOINTS} joints; at most {MAX_JOINTS} are read"),
                    ));
                }
                joints.push(reader.joint(child)?);
            }
            _ => {}
        }
    }
    Ok(RawUrdf {
        source_name: source_name.to_string(),
        robot_name,
        links,
        joints,
    })
}

/// The deepest element nesting of an XML text (comments, CDATA, processing instructions,
/// declarations and quoted attribute values skipped), stopping at the first element deeper than
/// [`MAX_XML_DEPTH`]; with the byte offset where it was reached. A scan without recursion.
fn nesting_depth(text: &str) -> (usize, usize) {
    let b = text.as_bytes();
    let find = |from: usize, pat: &[u8]| -> usize {
        b[from..]
            .windows(pat.len())
            .position(|w| w == pat)
            .map_or(b.len(), |p| from + p + pat.len())
    };
    let (mut i, mut depth, mut max, mut at) = (0, 0usize, 0usize, 0usize);
    while i < b.len() {
        if b[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &b[i..];
        if rest.starts_with(b"<!--") {
            i = find(i + 4, b"-->");
        } else if rest.starts_with(b"<![CDATA[") {
            i = find(i + 9, b"]]>");
        } else if rest.starts_with(b"<?") {
            i = find(i + 2, b"?>");
        } else if rest.starts_with(b"<!") {
            i = find(i + 2, b">");
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            i = find(i + 2, b">");
        } else {
            let start = i;
            let mut quote = None;
            let mut j = i + 1;
            while j < b.len() {
                match (quote, b[j]) {
                    (None, b'"' | b'\'') => quote = Some(b[j]),
                    (Some(q), c) if c == q => quote = None,
                    (None, b'>') => break,
                    _ => {}
                }
                j += 1;
            }
            if j < b.len() && b[j - 1] != b'/' {
                depth += 1;
                if depth > max {
                    max = depth;
                    at = start;
                }
                if depth > MAX_XML_DEPTH {
                    return (depth, start);
                }
            }
            i = j + 1;
        }
    }
    (max, at)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_index_counts_from_one() {
        let idx = LineIndex::new("a\nbc\n\nd");
        assert_eq!(idx.line(0), 1);
        assert_eq!(idx.line(1), 1);
        assert_eq!(idx.line(2), 2);
        assert_eq!(idx.line(5), 3);
        assert_eq!(idx.line(6), 4);
    }

    #[test]
    fn nesting_depth_skips_comments_and_quotes() {
        assert_eq!(nesting_depth("<a><b/><c x=\"/>\"><d></d></c></a>").0, 3);
        assert_eq!(
            nesting_depth("<a><!-- <b><c> --><![CDATA[<e><f>]]><?p <g>?></a>").0,
            1
        );
        let deep = format!("{}{}", "<x>".repeat(300), "</x>".repeat(300));
        assert_eq!(nesting_depth(&deep), (MAX_XML_DEPTH + 1, 3 * MAX_XML_DEPTH));
    }
}
