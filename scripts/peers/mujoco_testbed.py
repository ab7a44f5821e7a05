#!/usr/bin/env python3
"""MuJoCo's two-hinge model of the CJ test bed, release -> separation, side by side with flexrig.

The model (built here from the scene file, with the geometry of crates/rig/src/geometry.rs):
  - the operator pendulum: a hinge about x through the pivot (L, -a - b/2, l), mass M, centre of
    mass l_c below the pivot, the principal inertias of the arm (uniform rod) and the block;
  - the rigid robot link: a hinge about the vertical z axis through the origin, the link (m_r,
    slender rod) and the payload m_e at the tip, on its torsion spring k_theta_r (the joint's
    `stiffness`, a passive force);
  - the dome-block contact f = k delta^n (the block material's Hertz fit) between the dome's
    sphere (radius R, centre (L, -a + R, 0) in the link frame) and the block (a cuboid),
    computed exactly (sphere-box distance) and applied as generalised forces in mjcb_passive,
    so that every stage of MuJoCo's integrator sees it.
Step policy as flexrig's fixed one: dt_swing in the free swing, halving the predicted time to
touch near the onset, the Hertz contact time over CONTACT_STEPS in contact; the peak is the
vertex of the parabola through the three largest step values (as flexrig reports it); the run
stops at separation.

For each integrator (RK4, semi-implicit Euler) and setting the peak-force error is taken against
MuJoCo's own converged run (RK4, dt_swing 1e-4 s, 12 800 contact steps). A setting counts when
it and the next finer one (more contact steps, or the next smaller uniform step) reach the
target — a lucky cancellation of errors at one setting is not a converged result; the same rule
is applied to flexrig. Two MuJoCo step policies are reported: one step for the whole run (the
plain use) and flexrig's onset policy above. The cheapest counted setting is timed in-process (time.perf_counter around the whole run, model
built once; median of --repeat runs). If flexrig's `work_error` example is built, it is run in
the same call at its cheapest setting and the ratio printed (both in-process medians): for each
swing policy with Rapier's contact steps, and with the adaptive contact (solver.contact =
"adaptive", its cheapest tolerance).

Usage (in the project venv: bash scripts/python-env.sh --peers):
  .venv/bin/python scripts/peers/mujoco_testbed.py [--scene assets/scenes/cj_aluminium.toml]
      [--target 1e-3] [--repeat 21] [--flexrig target/release/examples/work_error]
Prints one JSON object per line. Exits 0 with a "skipped" line when mujoco is not installed.

For timing whole processes (start-up included) against `flexrig run`:
  .venv/bin/python scripts/peers/mujoco_testbed.py --once rk4 8e-3 60 [--runs 1]
builds the model and makes --runs runs (0: the start-up alone: Python, MuJoCo's import, the
model) at that integrator, swing step [s] and contact steps, and prints the last peak and its
error against MuJoCo's converged run only with --check (that reference costs ~1 s).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time
import tomllib

try:
    import mujoco
except ImportError:
    print(json.dumps({"skipped": "mujoco is not installed (bash scripts/python-env.sh --peers)"}))
    sys.exit(0)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CONTACT_TIME_FACTOR = 3.0  # as crates/rig/src/run.rs


class TestBed:
    """The scene's geometry, masses and contact law (crates/rig/src/geometry.rs)."""

    def __init__(self, scene_path):
        with open(scene_path, "rb") as f:
            scene = tomllib.load(f)
        with open(os.path.join(ROOT, "assets", "materials.toml"), "rb") as f:
            materials = tomllib.load(f)
        op, rob = scene["operator"], scene["robot"]
        if rob["design"] != "cj":
            raise SystemExit("only the CJ test bed (design = \"cj\") has a two-hinge model")
        material = materials["material"][op["block_material"]]
        self.k = scene["contact"].get("k", material["k"])
        self.n = scene["contact"].get("n", material["n"])
        self.g = scene["gravity_mps2"]
        start = op["start"]
        if start["from"] != "release":
            raise SystemExit("the comparison runs from a release")
        self.theta0 = math.radians(start["release_angle_deg"])
        # robot link
        L, w, t = rob["length_m"], rob["width_m"], rob["thickness_m"]
        m_r = rob["density_kg_m3"] * w * t * L
        m_e = rob["payload_kg"]
        self.L = L
        self.inertia_axis = m_r * L * L / 3 + m_e * L * L
        self.mass_r = m_r + m_e
        self.com_x = (m_r * 0.5 * L + m_e * L) / self.mass_r
        i_z = self.inertia_axis - self.mass_r * self.com_x**2
        i_x = max(m_r * (w * w + t * t) / 12, 1e-12 * i_z)
        self.robot_inertia = (i_x, i_z, i_z)
        self.spring = rob.get("torsion_spring_nm_per_rad") or 3 * rob["youngs_modulus_pa"] * w * t**3 / 12 / L
        a = rob["dome_standoff_m"]
        self.R = rob["dome_radius_m"]
        self.dome_local = (L, -a + self.R, 0.0)
        # operator
        l, m_a = op["arm_length_m"], op["arm_mass_kg"]
        m_b = op.get("block_mass_kg", material["block_mass_kg"])
        sx, sy, sz = op["block_size_m"]
        self.l = l
        self.mass = m_a + m_b
        self.lc = (m_a * 0.5 * l + m_b * l) / self.mass
        self.inertia_pivot = m_a * l * l / 3 + m_b * (l * l + (sy * sy + sz * sz) / 12)
        ix = self.inertia_pivot - self.mass * self.lc**2
        iy = m_a * l * l / 3 + m_b * (l * l + (sx * sx + sz * sz) / 12) - self.mass * self.lc**2
        iz = m_b * (sx * sx + sy * sy) / 12
        self.op_inertia = (ix, iy, iz)
        self.half = (0.5 * sx, 0.5 * sy, 0.5 * sz)
        self.pivot = (L, -a - 0.5 * sy, l)
        # contact time scale (undamped Hertz impact of the two effective masses)
        v = self.l * math.sqrt(2 * self.mass * self.g * self.lc * (1 - math.cos(self.theta0)) / self.inertia_pivot)
        m_op = self.inertia_pivot / l**2
        m_rob = self.inertia_axis / L**2
        mu = m_op * m_rob / (m_op + m_rob)
        delta_max = ((self.n + 1) * mu * v * v / (2 * self.k)) ** (1 / (self.n + 1))
        self.contact_time = CONTACT_TIME_FACTOR * delta_max / v
        self.v_impact = v

    def xml(self):
        px, py, pz = self.pivot
        return f"""
<mujoco model="cj_testbed">
  <option timestep="1e-3" gravity="0 0 {-self.g!r}" integrator="RK4">
    <flag contact="disable" constraint="disable" energy="disable"/>
  </option>
  <worldbody>
    <body name="operator" pos="{px!r} {py!r} {pz!r}">
      <joint name="phi" type="hinge" axis="1 0 0" damping="0" armature="0"/>
      <inertial pos="0 0 {-self.lc!r}" mass="{self.mass!r}"
                diaginertia="{self.op_inertia[0]!r} {self.op_inertia[1]!r} {self.op_inertia[2]!r}"/>
    </body>
    <body name="link" pos="0 0 0">
      <joint name="psi" type="hinge" axis="0 0 1" damping="0" armature="0"
             stiffness="{self.spring!r}" springref="0"/>
      <inertial pos="{self.com_x!r} 0 0" mass="{self.mass_r!r}"
                diaginertia="{self.robot_inertia[0]!r} {self.robot_inertia[1]!r} {self.robot_inertia[2]!r}"/>
    </body>
  </worldbody>
</mujoco>"""

    def contact(self, phi, psi):
        """(gap [m], generalised forces (tau_phi, tau_psi) [N m], force [N]) at the angles."""
        cpsi, spsi = math.cos(psi), math.sin(psi)
        dx, dy, _ = self.dome_local
        cx, cy, cz = dx * cpsi - dy * spsi, dx * spsi + dy * cpsi, 0.0
        px, py, pz = self.pivot
        rx, ry, rz = cx - px, cy - py, cz - pz
        cphi, sphi = math.cos(phi), math.sin(phi)
        # sphere centre in the block frame (origin at the block centre)
        bx = rx
        by = ry * cphi + rz * sphi
        bz = -ry * sphi + rz * cphi + self.l
        hx, hy, hz = self.half
        qx, qy, qz = min(max(bx, -hx), hx), min(max(by, -hy), hy), min(max(bz, -hz), hz)
        ex, ey, ez = bx - qx, by - qy, bz - qz
        dist = math.sqrt(ex * ex + ey * ey + ez * ez)
        gap = dist - self.R
        if gap >= 0.0:
            return gap, 0.0, 0.0, 0.0
        f = self.k * (-gap) ** self.n
        nbx, nby, nbz = ex / dist, ey / dist, ez / dist  # block -> sphere centre, block frame
        # to world
        nx, ny, nz = nbx, nby * cphi - nbz * sphi, nby * sphi + nbz * cphi
        # contact point: midpoint of the box point and the sphere point
        qwx = px + qx
        qwy = py + qy * cphi - (qz - self.l) * sphi
        qwz = pz + qy * sphi + (qz - self.l) * cphi
        swx, swy, swz = cx - self.R * nx, cy - self.R * ny, cz - self.R * nz
        mx, my, mz = 0.5 * (qwx + swx), 0.5 * (qwy + swy), 0.5 * (qwz + swz)
        # force on the block -f n, on the dome +f n
        fbx, fby, fbz = -f * nx, -f * ny, -f * nz
        ay, az = my - py, mz - pz
        tau_phi = ay * fbz - az * fby  # ((point - pivot) x F_block)_x
        tau_psi = mx * (f * ny) - my * (f * nx)  # (point x F_dome)_z
        return gap, tau_phi, tau_psi, f


def parabola_vertex(p):
    (t0, f0), (t1, f1), (t2, f2) = p
    d01 = (f1 - f0) / (t1 - t0)
    d12 = (f2 - f1) / (t2 - t1)
    a = (d12 - d01) / (t2 - t0)
    if not a < 0:
        return f1
    b = d01 - a * (t0 + t1)
    t = -b / (2 * a)
    f = f1 + d01 * (t - t1) + a * (t - t0) * (t - t1)
    return f if t0 <= t <= t2 else f1


class Runner:
    def __init__(self, bed, integrator):
        self.bed = bed
        self.model = mujoco.MjModel.from_xml_string(bed.xml())
        self.model.opt.integrator = {
            "rk4": mujoco.mjtIntegrator.mjINT_RK4,
            "euler": mujoco.mjtIntegrator.mjINT_EULER,
        }[integrator]
        self.data = mujoco.MjData(self.model)
        contact = bed.contact

        def passive(m, d):
            _, tp, tr, _ = contact(d.qpos[0], d.qpos[1])
            if tp or tr:
                d.qfrc_passive[0] += tp
                d.qfrc_passive[1] += tr

        self.callback = passive

    def run(self, dt_swing, contact_steps, uniform=False):
        """Release -> separation: (peak force [N], steps). `uniform`: every step dt_swing (no
        step policy; contact_steps is ignored)."""
        bed, m, d = self.bed, self.model, self.data
        mujoco.set_mjcb_passive(self.callback)
        try:
            mujoco.mj_resetData(m, d)
            d.qpos[0] = -bed.theta0
            dt_contact = dt_swing if uniform else bed.contact_time / contact_steps
            opt = m.opt
            step = mujoco.mj_step
            contact = bed.contact
            l = bed.l
            t, steps = 0.0, 0
            history = [(0.0, 0.0)] * 3
            peak, touched = None, False
            while True:
                gap, _, _, f = contact(d.qpos[0], d.qpos[1])
                if uniform:
                    h = dt_swing
                elif gap > 0.0 and not touched:
                    closing = l * math.cos(d.qpos[0]) * d.qvel[0]
                    time_to_touch = gap / closing if closing > 0 else math.inf
                    if time_to_touch >= 2 * dt_swing:
                        h = dt_swing
                    elif time_to_touch < 2 * dt_contact:
                        h = dt_contact
                    else:
                        h = 0.5 * time_to_touch
                else:
                    h = dt_contact
                opt.timestep = h
                step(m, d)
                t += h
                steps += 1
                _, _, _, f = contact(d.qpos[0], d.qpos[1])
                if f > 0.0:
                    touched = True
                    history = [history[1], history[2], (t, f)]
                    if peak is None and history[2][1] < history[1][1] >= history[0][1] and history[0][1] > 0:
                        peak = parabola_vertex(history)
                elif touched:
                    return (peak if peak is not None else max(x[1] for x in history)), steps
                if steps > 10_000_000:
                    raise RuntimeError("no separation")
        finally:
            mujoco.set_mjcb_passive(None)


def median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def flexrig_point(binary, scene, target, sample_rate):
    """flexrig's cheapest setting at the target from its work_error example (JSON lines), with
    the sensors sampled at `sample_rate` Hz (None: the scene's)."""
    if not binary or not os.path.exists(binary):
        return None
    env = dict(os.environ)
    if sample_rate:
        env["SAMPLE_RATE"] = repr(float(sample_rate))
    out = subprocess.run([binary, "--json", "--target", repr(target), scene],
                         capture_output=True, text=True, check=True, env=env).stdout
    rows = [json.loads(x) for x in out.splitlines() if x.startswith("{")]
    return [r for r in rows if r.get("cheapest")]


def once(bed, args):
    """--once: the model built and --runs runs at one setting (for whole-process timings)."""
    integrator, dt_swing, contact_steps = args.once[0], float(args.once[1]), int(args.once[2])
    runner = Runner(bed, integrator)
    peak = None
    for _ in range(args.runs):
        peak, steps = runner.run(dt_swing, contact_steps)
    row = {"code": "mujoco", "integrator": integrator, "dt_swing_s": dt_swing,
           "contact_steps": contact_steps, "runs": args.runs, "peak_n": peak}
    if args.check and peak is not None:
        reference, _ = Runner(bed, "rk4").run(1e-4, 12_800)
        row["error"] = abs(peak / reference - 1)
    print(json.dumps(row))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=os.path.join(ROOT, "assets", "scenes", "cj_aluminium.toml"))
    ap.add_argument("--target", type=float, default=1e-3)
    ap.add_argument("--repeat", type=int, default=21)
    ap.add_argument("--flexrig", default=os.path.join(ROOT, "target", "release", "examples", "work_error"))
    ap.add_argument("--once", nargs=3, metavar=("INTEGRATOR", "DT_SWING", "CONTACT_STEPS"))
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    bed = TestBed(args.scene)
    if args.once:
        once(bed, args)
        return
    reference, ref_steps = Runner(bed, "rk4").run(1e-4, 12_800)
    print(json.dumps({"code": "mujoco", "mujoco": mujoco.__version__, "converged_peak_n": reference,
                      "converged_steps": ref_steps, "v_impact_mps": bed.v_impact}))
    # One step for the whole run (the plain use of MuJoCo): the largest that reaches the target.
    for integrator in ("rk4", "euler"):
        runner = Runner(bed, integrator)
        grid = (2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6)
        for dt, finer in zip(grid, grid[1:]):
            peak, steps = runner.run(dt, 0, uniform=True)
            error = abs(peak / reference - 1)
            if error <= args.target and abs(runner.run(finer, 0, uniform=True)[0] / reference - 1) <= args.target:
                seconds = median_time(lambda: runner.run(dt, 0, uniform=True), max(3, args.repeat // 4))
                print(json.dumps({"code": "mujoco", "policy": "uniform", "integrator": integrator,
                                  "dt_s": dt, "steps": steps, "peak_n": peak, "error": error,
                                  "median_s": seconds}))
                break
    # flexrig's step policy (large swing steps, landing on the onset, the contact on its own
    # time scale): the cheapest setting is the yardstick.
    best = None
    for integrator in ("rk4", "euler"):
        runner = Runner(bed, integrator)
        for dt_swing in (1.6e-2, 8e-3, 4e-3, 2e-3, 1e-3, 5e-4):
            grid = (10, 15, 20, 30, 40, 60, 80, 120, 160, 240, 320, 640, 1280)
            for n, finer in zip(grid, grid[1:]):
                peak, steps = runner.run(dt_swing, n)
                error = abs(peak / reference - 1)
                if error <= args.target and abs(runner.run(dt_swing, finer)[0] / reference - 1) <= args.target:
                    seconds = median_time(lambda: runner.run(dt_swing, n), args.repeat)
                    row = {"code": "mujoco", "policy": "onset", "integrator": integrator,
                           "dt_swing_s": dt_swing,
                           "contact_steps": n, "steps": steps, "peak_n": peak, "error": error,
                           "median_s": seconds}
                    print(json.dumps(row))
                    if best is None or seconds < best["median_s"]:
                        best = row
                    break  # more contact steps only cost more at this swing step
    best = dict(best or {}, cheapest=True)
    print(json.dumps(best))
    # flexrig with the scene's sensors (50 kHz in the bundled scenes) and with the sensors at
    # 1 Hz (MuJoCo records nothing here).
    for rate in (None, 1.0):
        for row in flexrig_point(args.flexrig, args.scene, args.target, rate) or []:
            row = dict(row, code="flexrig", sample_rate_hz=rate or "scene")
            print(json.dumps(row))
            print(json.dumps({"ratio_mujoco_over_flexrig": best["median_s"] / row["median_s"],
                              "swing": row["swing"], "contact": row.get("contact", "fixed"),
                              "sample_rate_hz": row["sample_rate_hz"],
                              "target": args.target}))


if __name__ == "__main__":
    main()
