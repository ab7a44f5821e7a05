#!/usr/bin/env python3
"""Makes the arms bundled in assets/robots/ (and the 9-joint Panda test variant) from the URDF
files of the PyPI package `example-robot-data`, and writes one trajectory CSV per arm.

    python3 -m venv /tmp/erd && /tmp/erd/bin/pip install example-robot-data==6.0.0
    /tmp/erd/bin/python scripts/bundle_robots.py

What is changed (everything else, in particular every <inertial>, <origin>, <axis> and <limit>,
is copied as it is in the package's file):
- <visual>, <collision>, <gazebo>, <transmission> and comments are dropped (meshes are not
  shipped; flexrig needs the dynamics only);
- Panda (assets/robots/panda.urdf): the two finger joints, prismatic in the package with a
  <mimic>, become fixed joints at their zero position (fingers closed): mimic joints are not
  supported, and on an impact's time scale the non-backdrivable finger drive holds them;
- Panda test variant (crates/robot/tests/data/panda_fingers.urdf): the fingers stay prismatic,
  only the <mimic> element is dropped (9 independent joints; exercises prismatic joints against
  Pinocchio).
"""

import argparse
import pathlib
import sys
import xml.etree.ElementTree as ET

ROOT = pathlib.Path(__file__).resolve().parent.parent
PACKAGE = "example-robot-data"
VERSION = "6.0.0"


def find_share() -> pathlib.Path:
    for p in map(pathlib.Path, sys.path):
        c = p / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
        if c.is_dir():
            return c
    sys.exit("example-robot-data not found: install it in this interpreter (see the docstring)")


def strip(root: ET.Element) -> None:
    for tag in ("gazebo", "transmission"):
        for e in root.findall(tag):
            root.remove(e)
    for link in root.findall("link"):
        for tag in ("visual", "collision"):
            for e in link.findall(tag):
                link.remove(e)


def write(root: ET.Element, out: pathlib.Path, source: str, changes: str) -> None:
    ET.indent(root, space="  ")
    body = ET.tostring(root, encoding="unicode")
    header = (
        '<?xml version="1.0" encoding="utf-8"?>\n'
        f"<!-- From the PyPI package {PACKAGE} {VERSION}, file {source}.\n"
        f"     Changed by scripts/bundle_robots.py: {changes}\n"
        "     Provenance and licence: assets/robots/README.md. -->\n"
    )
    out.write_text(header + body + "\n")
    print("wrote", out.relative_to(ROOT))


def min_jerk(q0, q1, duration, n):
    rows = []
    for k in range(n):
        t = duration * k / (n - 1)
        s = t / duration
        b = 10 * s**3 - 15 * s**4 + 6 * s**5
        rows.append((t, [a + (c - a) * b for a, c in zip(q0, q1)]))
    return rows


def write_csv(out: pathlib.Path, names, rows, comment: str) -> None:
    lines = [f"# {comment}", "# time in s; joint positions in rad (revolute joints)"]
    lines.append(",".join(["time_s"] + names))
    for t, q in rows:
        lines.append(",".join([f"{t:.6f}"] + [f"{x:.9f}" for x in q]))
    out.write_text("\n".join(lines) + "\n")
    print("wrote", out.relative_to(ROOT))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--share", type=pathlib.Path, help="example-robot-data's robots/ folder")
    args = ap.parse_args()
    share = args.share or find_share()
    assets = ROOT / "assets" / "robots"
    data = ROOT / "crates" / "robot" / "tests" / "data"

    ur_src = "robots/ur_description/urdf/ur5_robot.urdf"
    ur = ET.parse(share / "ur_description/urdf/ur5_robot.urdf").getroot()
    strip(ur)
    write(ur, assets / "ur5.urdf", ur_src, "visual, collision, gazebo and transmission elements dropped.")

    panda_src = "robots/panda_description/urdf/panda.urdf"
    for fixed, out in ((True, assets / "panda.urdf"), (False, data / "panda_fingers.urdf")):
        panda = ET.parse(share / "panda_description/urdf/panda.urdf").getroot()
        strip(panda)
        for j in panda.findall("joint"):
            if j.get("name", "").startswith("panda_finger_joint"):
                for m in j.findall("mimic"):
                    j.remove(m)
                if fixed:
                    j.set("type", "fixed")
                    for tag in ("axis", "limit", "dynamics"):
                        for e in j.findall(tag):
                            j.remove(e)
        changes = "visual and collision elements dropped; " + (
            "the finger joints made fixed at their zero position (fingers closed)."
            if fixed
            else "the <mimic> of panda_finger_joint2 dropped (9 independent joints; a test file)."
        )
        write(panda, out, panda_src, changes)

    (assets / "LICENSE-panda.txt").write_text((share / "panda_description/LICENSE").read_text())
    print("wrote assets/robots/LICENSE-panda.txt")

    ur_names = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
                "wrist_2_joint", "wrist_3_joint"]
    write_csv(
        assets / "ur5_swing.csv",
        ur_names,
        min_jerk([0.0, -1.5708, 1.5708, -1.5708, -1.5708, 0.0],
                 [1.2, -1.0, 1.0, -1.2, -1.5708, 0.5], 1.5, 151),
        "UR5: a minimum-jerk move of 1.5 s, 100 Hz (made by scripts/bundle_robots.py)",
    )
    panda_names = [f"panda_joint{i}" for i in range(1, 8)]
    write_csv(
        assets / "panda_swing.csv",
        panda_names,
        min_jerk([0.0, -0.785398, 0.0, -2.356194, 0.0, 1.570796, 0.785398],
                 [1.0, -0.3, 0.2, -1.8, 0.1, 1.9, 0.5], 1.5, 151),
        "Panda: a minimum-jerk move of 1.5 s from the ready pose, 100 Hz (made by "
        "scripts/bundle_robots.py)",
    )


if __name__ == "__main__":
    main()
