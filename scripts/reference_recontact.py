#!/usr/bin/env python3
"""Independent reference for the safety verdict with re-contact: every contact of a free body
striking a link on a held joint, until the bodies part for good, and the smallest speed at which
the largest contact force reaches a limit.

Written from the equations, not from flexrig's code:

* the body (mass m_h, speed v0 towards the link at the first onset, free to recoil):
  m_h x_h'' = -f;
* the contact: f = k_c <delta>^n, delta = x_h - w (w the link tip's deflection);
* the CJ: a rigid link on its torsion spring, seen at the tip: (m_e + m_r/3) w'' = -k_delta w + f;
* the CL: the clamped-free Euler-Bernoulli beam (rho A = m_r/L, EI = k_delta L^3/3, L = 1 m; the
  tip response depends on m_r, m_e and k_delta only) with the payload m_e as a point mass at the
  tip, by its analytic modes (frequency equation
  1 + cos l cosh l + (m_e/m_r) l (cos l sinh l - sin l cosh l) = 0), mass-normalised, the first
  N_MODES of them with the static residual of the rest in series with the contact,
  R = 1/k_delta - sum phi_i(L)^2/omega_i^2: q_i'' + omega_i^2 q_i = phi_i(L) f,
  w = sum phi_i(L) q_i + R f.

Integrated by scipy's DOP853 (rtol 1e-10) with event location: each onset and separation
restarts the integration; each contact's peak is the largest force at the zeros of the
indentation rate (and at the ends). The bodies have parted for good when the body moves away
and its distance exceeds the largest reach of the vibrating tip in free flight,
sum |phi_i(L)| A_i (A_i each mode's amplitude).

The permissible speed: a scan upwards by 2 % steps from the speed whose whole kinetic energy
equals the contact energy at the limit (no contact can reach it below), to the first speed at which the
largest contact force reaches the limit, refined by brentq between it and the speed before.

Usage: python3 scripts/reference_recontact.py OUT.json
Writes a fixture with, per case, the design, the permissible speed and the contacts at two
speeds. Needs numpy, scipy (bash scripts/python-env.sh).
"""
import json
import math
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

N_MODES = 6
RTOL = 1e-10


def cl_modes(m_r, m_e, k_delta, length=1.0):
    """(omega_i, phi_i(L)) of the clamped-free beam with a tip mass, mass-normalised."""
    rho_a = m_r / length
    ei = k_delta * length**3 / 3.0
    alpha = m_e / m_r

    def freq(lam):
        # divided by cosh(lam) to stay finite
        c, s = math.cos(lam), math.sin(lam)
        return 1.0 / math.cosh(lam) + c + alpha * lam * (c * math.tanh(lam) - s)

    roots = []
    lam = 0.5
    step = 0.01
    f0 = freq(lam)
    while len(roots) < N_MODES:
        f1 = freq(lam + step)
        if f0 * f1 < 0:
            roots.append(brentq(freq, lam, lam + step, xtol=1e-15, rtol=1e-15))
        lam += step
        f0 = f1
    omegas, gains = [], []
    xs, ws = np.polynomial.legendre.leggauss(400)
    x = 0.5 * length * (xs + 1.0)
    wq = 0.5 * length * ws
    for lam in roots:
        b = lam / length
        sigma = (math.cosh(lam) + math.cos(lam)) / (math.sinh(lam) + math.sin(lam))

        def shape(xx):
            # cosh bx - sigma sinh bx, written without cancellation
            num = np.sinh(lam - b * xx) + math.sin(lam) * np.cosh(b * xx) - math.cos(lam) * np.sinh(b * xx)
            return num / (math.sinh(lam) + math.sin(lam)) - np.cos(b * xx) + sigma * np.sin(b * xx)

        wx = shape(x)
        w_tip = float(shape(np.array([length]))[0])
        modal_mass = rho_a * float(np.sum(wq * wx * wx)) + m_e * w_tip * w_tip
        omegas.append(lam * lam * math.sqrt(ei / (rho_a * length**4)))
        gains.append(w_tip / math.sqrt(modal_mass))
    omegas = np.array(omegas)
    gains = np.array(gains)
    residual = 1.0 / k_delta - float(np.sum(gains**2 / omegas**2))
    return omegas, gains, residual


def cj_modes(m_r, m_e, k_delta):
    m = m_e + m_r / 3.0
    return np.array([math.sqrt(k_delta / m)]), np.array([1.0 / math.sqrt(m)]), 0.0


def contacts(m_h, v0, k_c, n, modes):
    """Every contact's peak force [N] (onset, peak, time of peak) until the bodies part."""
    omegas, gains, residual = modes
    k = len(omegas)

    def force_of(dm):
        # f = k_c (dm - R f)^n, dm the indentation without the residual
        if dm <= 0.0:
            return 0.0
        if residual <= 0.0:
            return k_c * dm**n
        if n == 2.0:
            # k_c u^2 = f, u + R k_c u^2 = dm: the root without cancellation
            u = 2.0 * dm / (1.0 + math.sqrt(1.0 + 4.0 * residual * k_c * dm))
            return k_c * u * u
        g = lambda f: f - k_c * max(dm - residual * f, 0.0) ** n
        return brentq(g, 0.0, dm / residual, xtol=1e-14 * k_c * dm**n + 1e-300, rtol=1e-15)

    def dm_of(y):
        return y[0] - float(np.dot(gains, y[2 : 2 + k]))

    def rate_of(y):
        return y[1] - float(np.dot(gains, y[2 + k :]))

    def rhs(_t, y):
        f = force_of(dm_of(y))
        dy = np.empty_like(y)
        dy[0] = y[1]
        dy[1] = -f / m_h
        dy[2 : 2 + k] = y[2 + k :]
        dy[2 + k :] = -omegas**2 * y[2 : 2 + k] + gains * f
        return dy

    y = np.zeros(2 + 2 * k)
    y[1] = v0
    t = 0.0
    t_scale = 1e-3
    events = []
    for _ in range(200):
        # ---- a contact, from the onset at t ----
        sep = lambda _t, yy: dm_of(yy)
        sep.terminal = True
        sep.direction = -1
        peak_ev = lambda _t, yy: rate_of(yy)
        peak_ev.direction = -1
        # step off the onset so the separation event does not fire at once
        onset = t
        best = (0.0, t)
        while True:
            sol = solve_ivp(rhs, (t, t + 10.0), y, method="DOP853", rtol=RTOL,
                            atol=1e-14, events=[sep, peak_ev], dense_output=True,
                            first_step=1e-8)
            for tp, yp in zip(sol.t_events[1], sol.y_events[1]):
                fp = force_of(dm_of(yp))
                if fp > best[0]:
                    best = (fp, tp)
            if sol.status == 1 and len(sol.t_events[0]) > 0:
                t = float(sol.t_events[0][-1])
                y = sol.y_events[0][-1].copy()
                break
            raise RuntimeError("contact did not end")
        events.append({"onset_s": onset, "peak_force_n": best[0], "time_of_peak_s": best[1]})
        # ---- free flight ----
        while True:
            amp = np.sqrt(y[2 : 2 + k] ** 2 + (y[2 + k :] / omegas) ** 2)
            reach = float(np.sum(np.abs(gains) * amp))
            if y[1] < 0.0 and y[0] < -reach:
                return events, t
            on = lambda _t, yy: dm_of(yy)
            on.terminal = True
            on.direction = 1
            horizon = t + 0.05
            sol = solve_ivp(rhs, (t + 1e-12, horizon), y, method="DOP853", rtol=RTOL,
                            atol=1e-14, events=[on])
            if sol.status == 1 and len(sol.t_events[0]) > 0:
                t = float(sol.t_events[0][-1])
                y = sol.y_events[0][-1].copy()
                break
            t = horizon
            y = sol.y[:, -1].copy()
    raise RuntimeError("the bodies never parted")


def largest(m_h, v0, k_c, n, modes):
    ev, _ = contacts(m_h, v0, k_c, n, modes)
    return max(e["peak_force_n"] for e in ev)


def permissible(m_h, k_c, n, modes, limit):
    # below this speed no contact can store the contact energy f delta_c/(n + 1) of the limit
    v = math.sqrt(2.0 * limit * (limit / k_c) ** (1.0 / n) / (n + 1.0) / m_h)
    r = largest(m_h, v, k_c, n, modes) - limit
    assert r < 0, "the scan must start below the limit"
    while True:
        w = v * 1.02
        rw = largest(m_h, w, k_c, n, modes) - limit
        if rw >= 0:
            break
        v = w
    return brentq(lambda s: largest(m_h, s, k_c, n, modes) - limit, v, w, xtol=1e-12, rtol=1e-10)


def main():
    out = sys.argv[1]
    from multiprocessing import Pool

    with Pool(2) as pool:
        cases = pool.map(case, ["cj", "cl"])
    with open(out, "w") as fh:
        json.dump({"source": "scripts/reference_recontact.py", "n_modes": N_MODES,
                   "rtol": RTOL, "cases": cases}, fh, indent=1)


def case(link):
    # the hand (ISO/TS 15066 Table A.2: m_H 0.6 kg, 280 N), a light payload on a soft link
    m_h, limit = 0.6, 280.0
    m_r, m_e, k_delta, k_c, n = 0.051, 0.01, 2e4, 7.359e7, 2.0
    if True:
        modes = cj_modes(m_r, m_e, k_delta) if link == "cj" else cl_modes(m_r, m_e, k_delta)
        v = permissible(m_h, k_c, n, modes, limit)
        at = {}
        for s in (2.0, 3.0):
            ev, parted = contacts(m_h, s, k_c, n, modes)
            at[str(s)] = {"contacts": ev, "parted_s": parted}
        result = {
            "region": "hands_and_fingers", "m_h": m_h, "force_limit_n": limit,
            "m_r": m_r, "m_e": m_e, "k_delta": k_delta, "k_c": k_c, "n": n, "link": link,
            "permissible_speed_mps": v, "at_speed": at,
        }
        print(link, v, {k2: max(e["peak_force_n"] for e in a["contacts"]) for k2, a in at.items()},
              file=sys.stderr)
    return result


if __name__ == "__main__":
    main()
