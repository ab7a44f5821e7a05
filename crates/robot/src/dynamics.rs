//! The arm's multibody dynamics at a posture: forward kinematics, the joint-space mass matrix by
//! the composite-rigid-body algorithm, point Jacobians, and the Cholesky factorisation of the
//! mass matrix. Everything is computed in the base frame (world coordinates).
//!
//! **Composite-rigid-body algorithm** (Featherstone, *Rigid Body Dynamics Algorithms*, Springer
//! 2008, §6.2), written with spatial vectors in base coordinates about the base origin:
//! - every body's spatial inertia about the origin is (m, h = m c, I_O = I_c + m(|c|²1 − ccᵀ)),
//!   with c the centre of mass and I_c the rotational inertia about it, both in base axes;
//! - the composite inertia of body i is the sum over its subtree (a plain sum, since all are
//!   expressed about the same point and axes), accumulated from the leaves to the root;
//! - the motion subspace of joint i is S_i = (ω; v_O) = (a; p × a) for a revolute joint with
//!   unit axis a through the point p, and (0; a) for a prismatic joint;
//! - F_i = I^c_i S_i is the momentum (angular about O; linear) of the subtree moving with unit
//!   joint rate: H = I_O a_ω + h × v_O, L = m v_O − h × a_ω;
//! - M_ij = M_ji = S_jᵀ F_i for every j on the path from i to the root (zero otherwise).
//!
//! **Point Jacobian**: the linear velocity (m/s, base frame) of a point fixed on body b is
//! v = J q̇ with column i equal to a_i × (x − p_i) for a revolute joint i that supports b, a_i for
//! a prismatic one, and zero for joints that do not support b.

use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Matrix3xX, Point3, Vector3};

use crate::error::RobotError;
use crate::model::Robot;
use crate::urdf::JointKind;

/// A point fixed on a link of the arm: where a contact may happen.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPoint {
    link: String,
    link_index: usize,
    body: usize,
    point_in_link: Vector3<f64>,
    point_in_body: Vector3<f64>,
}

impl ContactPoint {
    /// The point `point` (m, in the frame of link `link`) of `robot`. Any URDF link may be named,
    /// also one merged into its parent by a fixed joint (e.g. a tool frame).
    pub fn new(robot: &Robot, link: &str, point: [f64; 3]) -> Result<ContactPoint, RobotError> {
        let link_index = robot.link_index(link)?;
        let frame = &robot.links()[link_index];
        for (k, x) in point.iter().enumerate() {
            if !x.is_finite() {
                return Err(RobotError::parameter(
                    format!("point[{k}] on link {link:?}"),
                    x,
                    "a finite coordinate in the link frame, m",
                ));
            }
        }
        let p = Vector3::from(point);
        Ok(ContactPoint {
            link: link.to_string(),
            link_index,
            body: frame.body(),
            point_in_link: p,
            point_in_body: (frame.pose_in_body() * Point3::from(p)).coords,
        })
    }
    /// The link the point is given on.
    pub fn link(&self) -> &str {
        &self.link
    }
    /// The body the link is part of (0 is the immobile base).
    pub fn body(&self) -> usize {
        self.body
    }
    /// The point in the link frame, m.
    pub fn point_in_link(&self) -> &Vector3<f64> {
        &self.point_in_link
    }
    /// The point in the body frame, m.
    pub fn point_in_body(&self) -> &Vector3<f64> {
        &self.point_in_body
    }
}

/// Scratch space for one robot's dynamics, reused between postures (no allocation per call).
#[derive(Debug, Clone)]
pub struct Workspace {
    dof: usize,
    /// World pose of every body at the last posture.
    poses: Vec<Isometry3<f64>>,
    /// World unit axis of every joint.
    axes: Vec<Vector3<f64>>,
    /// Composite inertia of every body's subtree about the world origin: mass, first moment,
    /// rotational inertia.
    comp_m: Vec<f64>,
    comp_h: Vec<Vector3<f64>>,
    comp_i: Vec<Matrix3<f64>>,
    pub(crate) mass: DMatrix<f64>,
    /// Lower Cholesky factor of the (armature-augmented) mass matrix (valid while a
    /// [`crate::Posture`] borrows the workspace).
    pub(crate) chol: DMatrix<f64>,
    /// 1 / L_ii (the solves multiply instead of dividing).
    inv_diag: Vec<f64>,
    pub(crate) jac: Matrix3xX<f64>,
    pub(crate) rhs: DVector<f64>,
    pub(crate) sol: DVector<f64>,
}

impl Workspace {
    /// A workspace sized for `robot`.
    pub fn new(robot: &Robot) -> Workspace {
        let n = robot.dof();
        let nb = n + 1;
        Workspace {
            dof: n,
            poses: vec![Isometry3::identity(); nb],
            axes: vec![Vector3::zeros(); n],
            comp_m: vec![0.0; nb],
            comp_h: vec![Vector3::zeros(); nb],
            comp_i: vec![Matrix3::zeros(); nb],
            mass: DMatrix::zeros(n, n),
            chol: DMatrix::zeros(n, n),
            inv_diag: vec![0.0; n],
            jac: Matrix3xX::zeros(n),
            rhs: DVector::zeros(n),
            sol: DVector::zeros(n),
        }
    }

    /// The world pose of body `b` at the last posture given to
    /// [`Robot::forward_kinematics`].
    pub fn body_pose(&self, b: usize) -> &Isometry3<f64> {
        &self.poses[b]
    }

    pub(crate) fn check(&self, robot: &Robot) -> Result<(), RobotError> {
        if self.dof != robot.dof() {
            return Err(RobotError::parameter(
                "workspace size",
                self.dof,
                format!(
                    "the workspace of a robot with {} moving joints (make it with \
                     Workspace::new(&robot))",
                    robot.dof()
                ),
            ));
        }
        Ok(())
    }
}

impl Robot {
    /// A workspace sized for this robot.
    pub fn workspace(&self) -> Workspace {
        Workspace::new(self)
    }

    /// Forward kinematics at joint positions `q` (rad or m): every body's world pose, into `ws`.
    pub fn forward_kinematics(&self, q: &[f64], ws: &mut Workspace) -> Result<(), RobotError> {
        ws.check(self)?;
        self.check_positions(q)?;
        ws.poses[0] = Isometry3::identity();
        for (i, joint) in self.joints().iter().enumerate() {
            let b = i + 1;
            let pose = ws.poses[joint.parent_body()] * joint.origin() * joint.motion(q[i]);
            ws.axes[i] = pose.rotation * joint.axis().into_inner();
            ws.poses[b] = pose;
        }
        Ok(())
    }

    /// The world pose of link `link` at `q` (rad or m).
    pub fn link_pose(
        &self,
        link: &str,
        q: &[f64],
        ws: &mut Workspace,
    ) -> Result<Isometry3<f64>, RobotError> {
        let frame = self.link(link)?;
        self.forward_kinematics(q, ws)?;
        Ok(ws.poses[frame.body()] * frame.pose_in_body())
    }

    /// The joint-space mass matrix M(q) (kg·m² for revolute pairs, kg·m for mixed, kg for
    /// prismatic pairs), by the composite-rigid-body algorithm; no armature.
    pub fn mass_matrix(&self, q: &[f64], ws: &mut Workspace) -> Result<DMatrix<f64>, RobotError> {
        self.forward_kinematics(q, ws)?;
        self.fill_mass_matrix(ws);
        Ok(ws.mass.clone())
    }

    /// The world position (m) of a contact point at `q`.
    pub fn point_position(
        &self,
        q: &[f64],
        point: &ContactPoint,
        ws: &mut Workspace,
    ) -> Result<Vector3<f64>, RobotError> {
        self.forward_kinematics(q, ws)?;
        Ok(point_world(ws, point))
    }

    /// The point Jacobian J(q) (3 × dof; m/rad for revolute columns, dimensionless for
    /// prismatic ones): the point's linear velocity in the base frame is J q̇.
    pub fn point_jacobian(
        &self,
        q: &[f64],
        point: &ContactPoint,
        ws: &mut Workspace,
    ) -> Result<Matrix3xX<f64>, RobotError> {
        self.check_point(point)?;
        self.forward_kinematics(q, ws)?;
        self.fill_point_jacobian(point, ws);
        Ok(ws.jac.clone())
    }

    pub(crate) fn check_point(&self, point: &ContactPoint) -> Result<(), RobotError> {
        let ok = self
            .links()
            .get(point.link_index)
            .is_some_and(|l| l.body() == point.body() && l.name() == point.link());
        if !ok {
            return Err(RobotError::parameter(
                format!("contact point on link {:?}", point.link()),
                format!("body {}", point.body()),
                format!(
                    "a point made with ContactPoint::new for robot {:?}",
                    self.name()
                ),
            ));
        }
        Ok(())
    }

    /// The composite-rigid-body algorithm at the posture of the last forward kinematics.
    pub(crate) fn fill_mass_matrix(&self, ws: &mut Workspace) {
        let n = self.dof();
        // Each body's inertia about the world origin, in world axes.
        for b in 1..=n {
            let inertia = self.bodies()[b].inertia();
            let pose = &ws.poses[b];
            let r = pose.rotation.to_rotation_matrix().into_inner();
            let c = pose * Point3::from(inertia.com);
            let m = inertia.mass;
            ws.comp_m[b] = m;
            ws.comp_h[b] = m * c.coords;
            ws.comp_i[b] =
                r * inertia.inertia * r.transpose() + crate::inertia::parallel_axis(m, &c.coords);
        }
        // Composite inertias, from the leaves to the root (parents have smaller numbers).
        for b in (2..=n).rev() {
            let p = self.parent_body(b);
            if p > 0 {
                ws.comp_m[p] += ws.comp_m[b];
                let h = ws.comp_h[b];
                ws.comp_h[p] += h;
                let i = ws.comp_i[b];
                ws.comp_i[p] += i;
            }
        }
        // Joints on different branches do not couple: only ancestor pairs are filled.
        ws.mass.fill(0.0);
        for i in 0..n {
            let b = i + 1;
            let (w, v) = self.motion_subspace(ws, i);
            let (m, h, io) = (ws.comp_m[b], ws.comp_h[b], ws.comp_i[b]);
            let ang = io * w + h.cross(&v);
            let lin = m * v - h.cross(&w);
            let mut j = b;
            loop {
                let k = j - 1;
                let (wk, vk) = self.motion_subspace(ws, k);
                let value = wk.dot(&ang) + vk.dot(&lin);
                ws.mass[(i, k)] = value;
                ws.mass[(k, i)] = value;
                j = self.parent_body(j);
                if j == 0 {
                    break;
                }
            }
        }
    }

    /// S_i = (ω; v_O) of joint i at the last posture.
    fn motion_subspace(&self, ws: &Workspace, i: usize) -> (Vector3<f64>, Vector3<f64>) {
        let a = ws.axes[i];
        match self.joints()[i].kind() {
            JointKind::Prismatic => (Vector3::zeros(), a),
            _ => {
                let p = ws.poses[i + 1].translation.vector;
                (a, p.cross(&a))
            }
        }
    }

    /// The point Jacobian into `ws.jac` at the posture of the last forward kinematics.
    pub(crate) fn fill_point_jacobian(&self, point: &ContactPoint, ws: &mut Workspace) {
        ws.jac.fill(0.0);
        let x = point_world(ws, point);
        let mut b = point.body();
        while b > 0 {
            let i = b - 1;
            let a = ws.axes[i];
            let col = match self.joints()[i].kind() {
                JointKind::Prismatic => a,
                _ => a.cross(&(x - ws.poses[b].translation.vector)),
            };
            ws.jac.set_column(i, &col);
            b = self.parent_body(b);
        }
    }

    /// Factors M + diag(armature) (kg·m² or kg) into `ws.chol` (lower, M = L Lᵀ) at the
    /// posture of the last [`Robot::fill_mass_matrix`]. A pivot ≤ 1e-13 × the largest diagonal
    /// entry is refused with the joint's name.
    pub(crate) fn factor_mass_matrix(
        &self,
        armature: Option<&[f64]>,
        ws: &mut Workspace,
    ) -> Result<(), RobotError> {
        let n = self.dof();
        ws.chol.copy_from(&ws.mass);
        if let Some(a) = armature {
            for i in 0..n {
                ws.chol[(i, i)] += a[i];
            }
        }
        let scale = (0..n).map(|i| ws.chol[(i, i)]).fold(0.0, f64::max);
        for j in 0..n {
            let mut d = ws.chol[(j, j)];
            for k in 0..j {
                d -= ws.chol[(j, k)] * ws.chol[(j, k)];
            }
            if !(d > 1e-13 * scale) {
                return Err(RobotError::NotPositiveDefinite {
                    joint: self.joints()[j].name().to_string(),
                    pivot: d,
                });
            }
            let l = d.sqrt();
            ws.chol[(j, j)] = l;
            ws.inv_diag[j] = 1.0 / l;
            for i in (j + 1)..n {
                let mut s = ws.chol[(i, j)];
                for k in 0..j {
                    s -= ws.chol[(i, k)] * ws.chol[(j, k)];
                }
                ws.chol[(i, j)] = s / l;
            }
            for i in 0..j {
                ws.chol[(i, j)] = 0.0;
            }
        }
        Ok(())
    }
}

/// Solves L Lᵀ x = rhs with the factor in `ws.chol`, from `ws.rhs` into `ws.sol`; both
/// triangular solves walk the columns of L (contiguous in memory).
pub(crate) fn cholesky_solve(ws: &mut Workspace) {
    let n = ws.dof;
    let l = ws.chol.as_slice();
    let x = ws.sol.as_mut_slice();
    x.copy_from_slice(ws.rhs.as_slice());
    // L y = rhs, column by column.
    for k in 0..n {
        let col = &l[k * n..(k + 1) * n];
        let xk = x[k] * ws.inv_diag[k];
        x[k] = xk;
        for (xi, lik) in x[k + 1..].iter_mut().zip(&col[k + 1..]) {
            *xi -= lik * xk;
        }
    }
    // Lᵀ x = y: row i of Lᵀ is column i of L.
    for i in (0..n).rev() {
        let col = &l[i * n..(i + 1) * n];
        let s: f64 = x[i + 1..]
            .iter()
            .zip(&col[i + 1..])
            .map(|(xk, lki)| lki * xk)
            .sum();
        x[i] = (x[i] - s) * ws.inv_diag[i];
    }
}

/// The world position (m) of a contact point at the posture of the last forward kinematics.
pub(crate) fn point_world(ws: &Workspace, point: &ContactPoint) -> Vector3<f64> {
    (ws.poses[point.body()] * Point3::from(point.point_in_body)).coords
}
