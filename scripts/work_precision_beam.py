#!/usr/bin/env python3
"""Work-precision table of issue 13's beam transient (docs/performance-beam.md).

Cantilever L 0.3 m, E 1.5 GPa, 25 x 1 mm, rho 900 kg/m^3, clamped, step tip load P = EI/L^2 from
rest, t = 1 s. Each flexrig row runs `wp_transient` (crates/beam/examples), each Exudyn row
scripts/peer_exudyn.py (in the Exudyn venv). Errors of the tip deflection v against a converged
reference (64 ANCF elements, energy-conserving step, h = 1e-5 s, Newton tolerance 1e-10 L):
  traj = max_k |v(t_k) - v_ref(t_k)| / max |v_ref|  over t_k = 1, 2, ..., 1000 ms
  end  = |v(1 s) / v_ref(1 s) - 1|
Times: best of REPEATS runs (flexrig: the whole 1000-step loop; Exudyn: SolveDynamic).

  python3 scripts/work_precision_beam.py --bin target/release/examples/wp_transient \
      --exudyn-python /work/venv-exudyn/bin/python --reference ref.json
"""
import argparse
import json
import subprocess
import sys

FLEXRIG = [
    # (kinematics, integrator, elements, h)
    *[("ancf", "0.9", n, h) for n in (4, 8, 16, 32) for h in (2e-3, 1e-3, 5e-4)],
    *[("ancf", "ec", n, h) for n in (4, 8, 16, 32) for h in (1e-3, 5e-4)],
    *[("corotational", "0.9", n, h) for n in (4, 8, 16, 32) for h in (2e-3, 1e-3, 5e-4)],
]
EXUDYN = [(n, h) for n in (4, 8, 16, 32) for h in (2e-3, 1e-3, 5e-4)]


def errors(tip_v, ref, h=1e-3):
    # ref sampled every 1 ms from t = 1 ms; tip_v every max(h, 1 ms) from t = max(h, 1 ms)
    m = max(abs(x) for x in ref)
    s = max(1, round(h / 1e-3))
    ref = ref[s - 1::s]
    k = min(len(tip_v), len(ref))
    traj = max(abs(tip_v[i] - ref[i]) for i in range(k)) / m
    return traj, abs(tip_v[k - 1] / ref[k - 1] - 1.0)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin", required=True)
    p.add_argument("--exudyn-python")
    p.add_argument("--reference", required=True, help="JSON line of the reference run")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--out", help="write all rows as JSON lines here")
    a = p.parse_args()
    ref = json.loads(open(a.reference).read())["tip_v"]
    rows = []
    for kin, integ, n, h in FLEXRIG:
        out = subprocess.run([a.bin, kin, integ, str(n), repr(h), str(a.repeats)],
                             capture_output=True, text=True)
        if out.returncode != 0:
            rows.append({"who": "flexrig", "model": kin, "integrator": integ, "elements": n,
                         "h": h, "failed": out.stderr.strip().splitlines()[-1:]})
            continue
        r = json.loads(out.stdout)
        traj, end = errors(r["tip_v"], ref, h)
        rows.append({"who": "flexrig", "model": kin, "integrator": integ, "elements": n, "h": h,
                     "seconds": r["seconds"], "its": r["iterations_per_step"],
                     "traj": traj, "end": end})
        print(rows[-1], file=sys.stderr)
    if a.exudyn_python:
        for n, h in EXUDYN:
            steps = round(1.0 / h)
            out = subprocess.run([a.exudyn_python, "scripts/peer_exudyn.py", "transient",
                                  "--elements", str(n), "--h", repr(h), "--steps", str(steps),
                                  "--repeat", str(a.repeats)], capture_output=True, text=True)
            r = json.loads(out.stdout.strip().splitlines()[-1])
            # the sensor rows: t = 0, h, 2h, ...: take every 1 ms from t = 1 ms
            every = max(1, round(1e-3 / h))
            tv = [row[1] for row in r["tip_v"]][every::every]
            traj, end = errors(tv, ref, h)
            rows.append({"who": "exudyn", "model": "ANCFCable2D", "integrator": "0.9",
                         "elements": n, "h": h, "seconds": r["seconds"], "its": None,
                         "traj": traj, "end": end})
            print(rows[-1], file=sys.stderr)
    if a.out:
        with open(a.out, "w") as f:
            for r in rows:
                f.write(json.dumps(r) + "\n")
    print("| code | element | integrator | elements | h [s] | error traj | error end | time [ms] | Newton its/step |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if "failed" in r:
            print(f"| {r['who']} | {r['model']} | {r['integrator']} | {r['elements']} | {r['h']:g} | failed | | | |")
            continue
        integ = "energy-conserving" if r["integrator"] == "ec" else f"gen-α ρ∞ {r['integrator']}"
        its = f"{r['its']:.2f}" if r["its"] is not None else "—"
        print(f"| {r['who']} | {r['model']} | {integ} | {r['elements']} | {r['h']:g} | "
              f"{r['traj']:.2e} | {r['end']:.2e} | {r['seconds'] * 1e3:.2f} | {its} |")


if __name__ == "__main__":
    main()
