#!/usr/bin/env python3
"""Exudyn's ANCFCable2D on issue 13's cantilever, for the work-precision comparison in
docs/performance-beam.md.

Cantilever: L 0.3 m, E 1.5 GPa, 25 x 1 mm, rho 900 kg/m^3, clamped (x, y, y' of the root node
held, as in Exudyn's examples; x' free), dead transverse tip load P = alpha EI/L^2.

  static:    alpha in {1, 2, 5, 10}, 10 load steps: tip (u, v, theta)
  transient: step load alpha = 1 from rest, generalized-alpha rho_inf, h, 1000 steps (t = 1 s):
             tip (u, v, theta) at t_end and the wall time of SolveDynamic (best of --repeat)

Prints one JSON object per line. Usage (in a venv with `pip install exudyn numpy`):
  python scripts/peer_exudyn.py transient --elements 32 --h 1e-3 --rho 0.9 --repeat 5
  python scripts/peer_exudyn.py static --elements 32
"""
import argparse
import warnings
import json
import math
import time

warnings.filterwarnings("ignore", category=DeprecationWarning)
import exudyn as exu
from exudyn.itemInterface import (ObjectANCFCable2D, MarkerNodePosition, LoadForceVector,
                                  SensorNode)
from exudyn.beams import GenerateStraightLineANCFCable2D

L, E, W, T, RHO = 0.3, 1.5e9, 0.025, 0.001, 900.0
EA = E * W * T
EI = E * W * T**3 / 12.0
RHOA = RHO * W * T


def build(elements, alpha, reduced, sensor=False):
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    cable = ObjectANCFCable2D(physicsMassPerLength=RHOA, physicsBendingStiffness=EI,
                              physicsAxialStiffness=EA, useReducedOrderIntegration=reduced)
    items = GenerateStraightLineANCFCable2D(mbs, [0, 0, 0], [L, 0, 0], elements, cable,
                                            fixedConstraintsNode0=[1, 1, 0, 1])
    nodes = items[0]
    tip = nodes[-1]
    marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=tip))
    mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[0, alpha * EI / L**2, 0]))
    sens = None
    if sensor:
        sens = mbs.AddSensor(SensorNode(nodeNumber=tip, storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.Displacement))
    mbs.Assemble()
    return sc, mbs, tip, sens


def tip_state(mbs, tip):
    q = mbs.GetNodeOutput(tip, exu.OutputVariableType.Coordinates)  # displacements
    u, v, sx, sy = q[0], q[1], 1.0 + q[2], q[3]
    return u, v, math.atan2(sy, sx)


def settings(sparse=True):
    s = exu.SimulationSettings()
    s.solutionSettings.writeSolutionToFile = False
    s.solutionSettings.sensorsWritePeriod = 1e9
    s.displayComputationTime = False
    s.displayStatistics = False
    s.timeIntegration.verboseMode = 0
    s.staticSolver.verboseMode = 0
    s.linearSolver.solverType = (exu.LinearSolverType.EigenSparse if sparse
                                 else exu.LinearSolverType.EXUdense)
    return s


def static(args):
    for alpha in (1.0, 2.0, 5.0, 10.0):
        best = math.inf
        for _ in range(args.repeat):
            sc, mbs, tip, _ = build(args.elements, alpha, args.reduced)
            s = settings(not args.dense)
            s.staticSolver.numberOfLoadSteps = 10
            s.staticSolver.newton.relativeTolerance = 1e-10
            s.staticSolver.newton.absoluteTolerance = 1e-12
            t0 = time.perf_counter()
            exu.SolveStatic(mbs, s)
            best = min(best, time.perf_counter() - t0)
        u, v, th = tip_state(mbs, tip)
        print(json.dumps({"case": "static", "elements": args.elements, "alpha": alpha,
                          "u": u, "v": v, "theta": th, "seconds": best}))


def transient(args):
    best = math.inf
    trajectory = None
    for rep in range(args.repeat + 1):
        # the first run records the tip trajectory (sensor every step), the others are timed
        record = rep == 0
        sc, mbs, tip, sens = build(args.elements, 1.0, args.reduced, sensor=record)
        s = settings(not args.dense)
        if record:
            s.solutionSettings.sensorsWritePeriod = args.h
        s.timeIntegration.numberOfSteps = args.steps
        s.timeIntegration.endTime = args.steps * args.h
        s.timeIntegration.generalizedAlpha.spectralRadius = args.rho
        s.timeIntegration.newton.relativeTolerance = args.rtol
        t0 = time.perf_counter()
        exu.SolveDynamic(mbs, s)
        if record:
            data = mbs.GetSensorStoredData(sens)  # rows: t, dx, dy, dz
            trajectory = [[float(r[0]), float(r[2])] for r in data]
        else:
            best = min(best, time.perf_counter() - t0)
    u, v, th = tip_state(mbs, tip)
    print(json.dumps({"case": "transient", "elements": args.elements, "h": args.h,
                      "rho": args.rho, "steps": args.steps, "u": u, "v": v, "theta": th,
                      "seconds": best, "rtol": args.rtol, "tip_v": trajectory}))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", choices=["static", "transient"])
    p.add_argument("--elements", type=int, default=32)
    p.add_argument("--h", type=float, default=1e-3)
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--rho", type=float, default=0.9)
    p.add_argument("--rtol", type=float, default=1e-8, help="Exudyn's Newton relative tolerance (its default 1e-8)")
    p.add_argument("--repeat", type=int, default=3, help="timed runs (best taken)")
    p.add_argument("--reduced", type=int, default=0, help="useReducedOrderIntegration (0, 1, 2)")
    p.add_argument("--dense", action="store_true", help="dense LU instead of EigenSparse")
    a = p.parse_args()
    static(a) if a.case == "static" else transient(a)


if __name__ == "__main__":
    main()
