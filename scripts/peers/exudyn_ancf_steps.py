#!/usr/bin/env python3
"""One Exudyn ANCFCable2D transient of the Exudyn comparison's cantilever (the set-up of
scripts/peers/exudyn_ancf_cable.py: N elements, h = 1 ms, rho_inf = 0.9, step tip load EI/L^2
from rest) with a given number of steps, for instruction counts under callgrind, a
load-independent measure on a shared machine:

  valgrind --tool=callgrind .venv/bin/python scripts/peers/exudyn_ancf_steps.py 32 1000
  valgrind --tool=callgrind .venv/bin/python scripts/peers/exudyn_ancf_steps.py 32 0
  valgrind --tool=callgrind .venv/bin/python scripts/peers/exudyn_ancf_steps.py 32 static

(`static`: the elastica PL^2/EI = 5 in 10 load steps, the static comparison's solve; `static K`:
in K load steps, e.g. `32 static 1` for the full load at once.)
The difference of a count and the set-up's is the work alone (the interpreter's start, the import
and the model's set-up cancel). flexrig's side: crates/beam/examples/probe_instructions.rs
(`transient ancf 32`, whose start-up is a few hundred thousand instructions).
Prints the tip deflection at the end so that the run can be checked against flexrig's.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import peer_exudyn as peer  # noqa: E402


def main():
    elements = int(sys.argv[1]) if len(sys.argv) > 1 else 32
    what = sys.argv[2] if len(sys.argv) > 2 else "1000"
    if what == "static":
        sc, mbs, tip, _ = peer.build(elements, 5.0, 0)
        s = peer.settings(True)
        load_steps = int(sys.argv[3]) if len(sys.argv) > 3 else 10
        s.staticSolver.numberOfLoadSteps = load_steps
        s.staticSolver.newton.relativeTolerance = 1e-10
        s.staticSolver.newton.absoluteTolerance = 1e-12
        peer.exu.SolveStatic(mbs, s)
        u, v, theta = peer.tip_state(mbs, tip)
        print(f"tip v {v:.15e} (static, alpha = 5, {load_steps} load steps)")
        return 0
    steps = int(what)
    h, rho = 1e-3, 0.9
    sc, mbs, tip, _ = peer.build(elements, 1.0, 0)
    if steps == 0:
        print("set-up only")
        return 0
    s = peer.settings(True)
    s.timeIntegration.numberOfSteps = steps
    s.timeIntegration.endTime = steps * h
    s.timeIntegration.generalizedAlpha.spectralRadius = rho
    peer.exu.SolveDynamic(mbs, s)
    u, v, theta = peer.tip_state(mbs, tip)
    print(f"tip v {v:.15e} after {steps} steps of {h} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
