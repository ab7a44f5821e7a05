#!/usr/bin/env python3
"""flexrig's ANCF cable against Exudyn's ANCFCable2D, side by side in one run.

Problem (the Exudyn comparison's cantilever, canonical::polypropylene_cantilever): L 0.3 m, E 1.5 GPa, 25 x 1 mm,
rho 900 kg/m^3 (EI, rho A, EA from these), clamped, dead transverse tip load P = alpha EI/L^2.
  transient: P = EI/L^2 applied at t = 0 to the beam at rest, generalized-alpha rho_inf = 0.9,
             h = 1 ms, 1000 steps; N = 8, 16, 32, 64 elements (both codes the same N, h, rho_inf)
  static:    the elastica alpha = 5, 10 load steps; N = 8, 16, 32 (64 as the reference)
Exudyn: ObjectANCFCable2D, default integration, SolveDynamic / SolveStatic with EigenSparse and its
default Newton (the set-up of scripts/peer_exudyn.py). flexrig: the examples wp_transient and
wp_static (crates/beam/examples; build them with
`cargo build --release -p flexrig-beam --example wp_transient --example wp_static`).

Errors (so that the ratio compares runs of equal error):
  transient: max over t = 1, 2, ..., 1000 ms of |v - v_ref| / max |v_ref| of the tip deflection,
             v_ref from flexrig with 32 ANCF elements at h = 25 us (the time discretisation
             dominates both codes' errors at h = 1 ms: about 3e-3 for either)
  static:    max of |u - u_ref|, |v - v_ref| over L and |theta - theta_ref| at the tip, reference
             flexrig with 64 ANCF elements (7.6e-9 from the extensible elastica)
Times: the runs alternate (flexrig, Exudyn, flexrig, ...) ROUNDS times; each flexrig run is the
best of 3 inside its process, each Exudyn run one SolveDynamic / SolveStatic call; the table
gives the medians over the rounds and the ratio of the medians. The machine may be shared: the
ratio of interleaved runs is the meaningful number, not the absolute times.

Run it with the project's venv, where `bash scripts/python-env.sh --peers` put Exudyn:
  .venv/bin/python scripts/peers/exudyn_ancf_cable.py [--rounds 5] [--bin-dir target/release/examples]
Without Exudyn it prints that it skipped and exits 0.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def flexrig(bin_dir, name, *args):
    exe = os.path.join(bin_dir, name)
    out = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def exudyn_transient(peer, elements, h, steps, rho):
    sc, mbs, tip, sens = peer.build(elements, 1.0, 0, sensor=True)
    s = peer.settings(True)
    s.solutionSettings.sensorsWritePeriod = h
    s.timeIntegration.numberOfSteps = steps
    s.timeIntegration.endTime = steps * h
    s.timeIntegration.generalizedAlpha.spectralRadius = rho
    t0 = time.perf_counter()
    peer.exu.SolveDynamic(mbs, s)
    seconds = time.perf_counter() - t0
    data = mbs.GetSensorStoredData(sens)  # rows: t, dx, dy, dz
    every = max(1, round(1e-3 / h))
    tip_v = [float(r[2]) for r in data[1:]][every - 1::every]
    return seconds, tip_v


def exudyn_static(peer, elements, alpha, load_steps=10):
    sc, mbs, tip, _ = peer.build(elements, alpha, 0)
    s = peer.settings(True)
    s.staticSolver.numberOfLoadSteps = load_steps
    s.staticSolver.newton.relativeTolerance = 1e-10
    s.staticSolver.newton.absoluteTolerance = 1e-12
    t0 = time.perf_counter()
    peer.exu.SolveStatic(mbs, s)
    seconds = time.perf_counter() - t0
    return seconds, peer.tip_state(mbs, tip)


def trajectory_error(tip_v, ref):
    k = min(len(tip_v), len(ref))
    return max(abs(tip_v[i] - ref[i]) for i in range(k)) / max(abs(x) for x in ref)


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin-dir", default=os.path.join(ROOT, "target", "release", "examples"))
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--elements", type=int, nargs="+", default=[8, 16, 32, 64])
    p.add_argument("--no-static", action="store_true")
    p.add_argument("--no-transient", action="store_true")
    p.add_argument("--load-steps", type=int, default=10,
                   help="Exudyn's static load steps (10: the comparison's setting)")
    p.add_argument("--adaptive", action="store_true",
                   help="flexrig's static solve with adaptive load steps from the full load")
    a = p.parse_args()
    try:
        sys.path.insert(0, os.path.dirname(HERE))
        import peer_exudyn as peer  # imports exudyn
    except ImportError as e:
        print(f"skipped: Exudyn is not installed in this interpreter ({sys.executable}: {e}); "
              "`bash scripts/python-env.sh --peers`, then run this script with .venv/bin/python")
        return 0
    print(f"Exudyn {peer.exu.__version__}, flexrig examples from {a.bin_dir}, {a.rounds} rounds")
    h, steps, rho = 1e-3, 1000, 0.9
    if not a.no_transient:
        ref = flexrig(a.bin_dir, "wp_transient", "ancf", rho, 32, 2.5e-5, 1)["tip_v"]
        print("\n| N | flexrig ms | its/step | error | Exudyn ms | error | Exudyn / flexrig |")
        print("|---|---|---|---|---|---|---|")
    for n in ([] if a.no_transient else a.elements):
        fx, ex = [], []
        for _ in range(a.rounds):
            r = flexrig(a.bin_dir, "wp_transient", "ancf", rho, n, h, 3)
            fx.append(r["seconds"])
            t, tip_v = exudyn_transient(peer, n, h, steps, rho)
            ex.append(t)
        f_err = trajectory_error(r["tip_v"], ref)
        e_err = trajectory_error(tip_v, ref)
        fm, em = statistics.median(fx), statistics.median(ex)
        print(f"| {n} | {fm * 1e3:.2f} | {r['iterations_per_step']:.2f} | {f_err:.2e} "
              f"| {em * 1e3:.1f} | {e_err:.2e} | {em / fm:.1f} |", flush=True)
    if a.no_static:
        return 0
    alpha = 5.0
    r64 = flexrig(a.bin_dir, "wp_static", "ancf", 64, alpha, 1)
    ref_tip = (r64["u"], r64["v"], r64["theta"])

    def err(tip):
        return max(abs(tip[0] - ref_tip[0]) / 0.3, abs(tip[1] - ref_tip[1]) / 0.3,
                   abs(tip[2] - ref_tip[2]))

    how = "adaptive load steps" if a.adaptive else "10 load steps"
    print(f"\nstatic elastica alpha = {alpha}, flexrig {how}, Exudyn {a.load_steps} load steps "
          "(reference: flexrig, 64 ANCF elements)")
    print("\n| N | flexrig ms | iterations | error | Exudyn ms | error | Exudyn / flexrig |")
    print("|---|---|---|---|---|---|---|")
    for n in [x for x in a.elements if x < 64]:
        fx, ex = [], []
        for _ in range(a.rounds):
            r = flexrig(a.bin_dir, "wp_static", "ancf", n, alpha, 20,
                        *(["adaptive"] if a.adaptive else []))
            fx.append(r["seconds"])
            t, tip = exudyn_static(peer, n, alpha, a.load_steps)
            ex.append(t)
        fm, em = statistics.median(fx), statistics.median(ex)
        print(f"| {n} | {fm * 1e3:.3f} | {r['iterations']} | {err((r['u'], r['v'], r['theta'])):.1e} "
              f"| {em * 1e3:.2f} | {err(tip):.1e} | {em / fm:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
