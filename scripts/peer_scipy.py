#!/usr/bin/env python3
"""Peer run of the lumped two-mass impact with scipy's solve_ivp (DOP853, Radau, LSODA).

Integrates the same problem as flexrig-lumped (state: contact indentation δ_c and approach speed
v; f = k_c δ_c^n, δ_c' = v / (1 + n k_c δ_c^(n-1) / k_δ), μ v' = -f) from first contact to the peak
(event v = 0), over the same tolerances, and prints one JSON object per line:
{"method", "rtol", "error", "seconds", "nfev"}; the error is that of the peak force against the
exact energy solution computed here independently (brentq on U(f) = μ v0²/2).

Usage: python3 scripts/peer_scipy.py M_H M_EFF K_DELTA K_C N V0 [RTOL ...]
Needs: numpy, scipy.
"""
import json
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


def main():
    m_h, m_eff, k_d, k_c, n, v0 = (float(x) for x in sys.argv[1:7])
    rtols = [float(x) for x in sys.argv[7:]] or [1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
    mu = m_h * m_eff / (m_h + m_eff)
    energy = 0.5 * mu * v0 * v0

    def stored(f):
        return f * f / (2 * k_d) + f * (f / k_c) ** (1 / n) / (n + 1)

    f_hi = min(np.sqrt(2 * energy * k_d), (energy * (n + 1)) ** (n / (n + 1)) * k_c ** (1 / (n + 1)))
    exact = brentq(lambda f: stored(f) - energy, 0.0, f_hi * (1 + 1e-12), xtol=1e-300, rtol=1e-15)

    def rhs(_t, y):
        dc = max(y[0], 0.0)
        f = k_c * dc**n
        k_t = n * k_c * dc ** (n - 1) if dc > 0 else (k_c if n == 1 else 0.0)
        return [y[1] / (1 + k_t / k_d), -f / mu]

    def peak(_t, y):
        return y[1]

    peak.terminal = True
    peak.direction = -1
    dc_scale = (f_hi / k_c) ** (1 / n)
    t_end = 10 * (f_hi / k_d + dc_scale) / v0
    for method in ["DOP853", "Radau", "LSODA"]:
        for rtol in rtols:
            atol = [rtol * dc_scale, rtol * v0]
            runs, times = None, []
            for _ in range(5):
                start = time.perf_counter()
                runs = solve_ivp(rhs, (0, t_end), [0.0, v0], method=method, rtol=rtol, atol=atol,
                                 events=peak)
                times.append(time.perf_counter() - start)
            if runs.status != 1 or not len(runs.y_events[0]):
                continue
            f_peak = k_c * max(runs.y_events[0][0][0], 0.0) ** n
            print(json.dumps({"method": method, "rtol": rtol, "error": abs(f_peak / exact - 1),
                              "seconds": sorted(times)[len(times) // 2], "nfev": int(runs.nfev)}))


if __name__ == "__main__":
    main()
