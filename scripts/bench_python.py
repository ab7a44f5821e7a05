"""Benchmarks of the Python package (issue 15; figures in docs/performance.md, "Python package").

    bash scripts/python-package.sh            # once: builds the package into .venv
    .venv/bin/python scripts/bench_python.py [--quick]

1. flexrig.impact on 10^6 parameter sets (exact method), from Python, broadcasting included.
2. A sweep of 1 000 CJ runs (from contact to the peak) locally (rayon, every core) and on a Dask
   LocalCluster of 2 worker processes (1 thread each), the cluster already up; the tables are
   checked identical.
Best of several repeats; prints the machine and its load, since other work on it skews the wall clock.
"""

import os
import platform
import sys
import time

import numpy as np
import pandas as pd

import flexrig


def best(f, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        value = f()
        times.append(time.perf_counter() - t)
    return min(times), value


def machine():
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, load {os.getloadavg()}"


def main():
    quick = "--quick" in sys.argv
    print(machine())
    rng = np.random.default_rng(2026)
    size = 10**5 if quick else 10**6
    args = (
        rng.uniform(1.0, 1000.0, size),  # m_h
        rng.uniform(0.1, 10.0, size),  # m_eff
        10 ** rng.uniform(np.log10(200.0), 8.0, size),  # k_delta
        10 ** rng.uniform(7.0, 8.0, size),  # k_c
        rng.uniform(1.0, 2.5, size),  # n
        rng.uniform(0.5, 3.0, size),  # v0
    )
    seconds, peaks = best(lambda: flexrig.impact(*args), 5)
    assert np.all(peaks.f_max_n > 0)
    print(f"impact: {size} parameter sets in {seconds:.3f} s ({1e9 * seconds / size:.0f} ns per set)")

    base = flexrig.scene_text("cj_iron", **{"operator.start.from": "contact", "stop.at": "peak"})
    points = (5, 8) if quick else (25, 40)
    grid = {
        "operator.start.release_angle_deg": f"10:60:{points[0]}",
        "robot.payload_kg": f"0.05:1:{points[1]}",
    }
    runs = points[0] * points[1]
    local_s, local = best(lambda: flexrig.sweep(base, grid), 3)
    print(f"local sweep: {runs} runs in {local_s:.3f} s")

    from dask.distributed import Client, LocalCluster

    start = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            client.wait_for_workers(2)
            up_s = time.perf_counter() - start
            start = time.perf_counter()
            flexrig.sweep(base, {"robot.payload_kg": [0.1, 0.2, 0.3, 0.4]}, client=client)  # warm-up
            warm_s = time.perf_counter() - start
            dask_s, remote = best(lambda: flexrig.sweep(base, grid, client=client), 3)
    print(f"dask cluster up in {up_s:.2f} s; first (4-run) sweep, workers importing flexrig: {warm_s:.2f} s")
    pd.testing.assert_frame_equal(local, remote)
    print(f"dask sweep (LocalCluster, 2 worker processes): {runs} runs in {dask_s:.3f} s, "
          f"{dask_s / local_s:.2f}x the local sweep; tables identical")


if __name__ == "__main__":
    main()
