#!/usr/bin/env python3
"""Independent reference for flexrig-robot: joint-space mass matrices, point Jacobians and
reflected masses m_u = 1 / (uᵀ J M⁻¹ Jᵀ u) computed with Pinocchio (PyPI package `pin`) from the
same URDF files that the Rust crate loads, written to crates/robot/tests/data/pinocchio_reference.json
(the Rust test crates/robot/tests/pinocchio.rs compares against it).

    python3 -m venv /tmp/erd && /tmp/erd/bin/pip install pin==4.1.0 numpy
    /tmp/erd/bin/python scripts/reflected_mass_pinocchio.py

Pinocchio computes M by its own CRBA (upper triangle, symmetrised here), adds `model.armature` to
the diagonal (checked below against M without armature), and the Jacobian of an operational frame
placed at the contact point on the link (LOCAL_WORLD_ALIGNED: the point's linear velocity in the
base frame). Poses, points, directions and armatures are drawn from a seeded generator; continuous
joints are given to Pinocchio as (cos q, sin q). Numbers are written with 17 significant digits.
"""

import json
import pathlib

import numpy as np
import pinocchio as pin

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "crates/robot/tests/data/pinocchio_reference.json"

ROBOTS = [
    ("assets/robots/ur5.urdf",
     ["upper_arm_link", "forearm_link", "wrist_3_link", "ee_link", "tool0"]),
    ("assets/robots/panda.urdf",
     ["panda_link4", "panda_link5", "panda_link7", "panda_hand", "panda_hand_tcp"]),
    ("crates/robot/tests/data/panda_fingers.urdf",
     ["panda_link6", "panda_hand", "panda_leftfinger", "panda_rightfinger"]),
    ("crates/robot/tests/data/tree_rpy.urdf",
     ["l1", "l2", "l2_tool", "l4", "l3", "l3_pad"]),
]
POSES = 6
POINTS_PER_POSE = 4


def config(model, angles):
    """Pinocchio configuration from one number per joint (continuous joints as cos, sin)."""
    q = pin.neutral(model)
    for j, a in zip(model.joints[1:], angles):
        if j.nq == 2:
            q[j.idx_q], q[j.idx_q + 1] = np.cos(a), np.sin(a)
        else:
            q[j.idx_q] = a
    return q


def mass_matrix(model, data, q):
    m = pin.crba(model, data, q)
    return np.triu(m) + np.triu(m, 1).T


def main():
    rng = np.random.default_rng(20261207)
    robots = []
    for path, links in ROBOTS:
        model = pin.buildModelFromUrdf(str(ROOT / path))
        names = list(model.names)[1:]
        assert all(j.nv == 1 for j in model.joints[1:]), "one degree of freedom per joint"
        lower, upper = [], []
        for j in model.joints[1:]:
            if j.nq == 2:
                lower.append(-np.pi)
                upper.append(np.pi)
            else:
                lo, hi = model.lowerPositionLimit[j.idx_q], model.upperPositionLimit[j.idx_q]
                lower.append(max(lo, -np.pi))
                upper.append(min(hi, np.pi))
        frames = {}
        for link in links:
            frames[link] = model.getFrameId(link)
            assert frames[link] < len(model.frames), link
        poses = []
        for p in range(POSES):
            angles = rng.uniform(lower, upper)
            armature = rng.uniform(0.02, 0.5, size=model.nv)
            q = config(model, angles)
            model.armature[:] = 0.0
            data = model.createData()
            m0 = mass_matrix(model, data, q)
            model.armature[:] = armature
            m1 = mass_matrix(model, data, q)
            assert np.allclose(m1 - m0, np.diag(armature), rtol=0, atol=1e-12), "armature"
            model.armature[:] = 0.0
            qdot = rng.normal(size=model.nv)
            cases = []
            for c in range(POINTS_PER_POSE):
                link = links[rng.integers(len(links))]
                point = rng.uniform(-0.1, 0.1, size=3)
                parent = model.frames[frames[link]]
                placement = parent.placement * pin.SE3(np.eye(3), point)
                name = f"contact_{p}_{c}"
                fid = model.addFrame(
                    pin.Frame(name, parent.parentJoint, frames[link], placement,
                              pin.FrameType.OP_FRAME))
                data = model.createData()
                pin.forwardKinematics(model, data, q)
                pin.updateFramePlacements(model, data)
                pin.computeJointJacobians(model, data, q)
                jac = pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)[:3, :]
                position = data.oMf[fid].translation.copy()
                u = rng.normal(size=3)
                u /= np.linalg.norm(u)
                velocity = jac @ qdot
                uv = velocity / np.linalg.norm(velocity)

                def reflected(m, d):
                    g = jac.T @ d
                    return 1.0 / float(g @ np.linalg.solve(m, g))

                cases.append({
                    "link": link,
                    "point": point.tolist(),
                    "position": position.tolist(),
                    "jacobian": jac.tolist(),
                    "direction": u.tolist(),
                    "m_rigid": reflected(m0, u),
                    "m_armature": reflected(m1, u),
                    "velocity": velocity.tolist(),
                    "m_rigid_along_velocity": reflected(m0, uv),
                })
            poses.append({
                "q": angles.tolist(),
                "qdot": qdot.tolist(),
                "armature": armature.tolist(),
                "mass_matrix": m0.tolist(),
                "cases": cases,
            })
        robots.append({"urdf": path, "joint_names": names, "poses": poses})
        print(f"{path}: {model.nv} joints, {POSES} poses x {POINTS_PER_POSE} points")
    doc = {
        "generator": "scripts/reflected_mass_pinocchio.py",
        "pinocchio_version": pin.__version__,
        "numpy_version": np.__version__,
        "units": "q rad or m; point, position m (point in the link frame, position in the base "
                 "frame); jacobian 3 x nv in Pinocchio's joint order (joint_names); masses kg; "
                 "mass_matrix without armature; armature kg m^2 or kg",
        "robots": robots,
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print("wrote", OUT.relative_to(ROOT))


if __name__ == "__main__":
    main()
