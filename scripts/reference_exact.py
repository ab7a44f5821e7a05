#!/usr/bin/env python3
"""Independent high-precision peak forces of the two-mass impact (paper Eq. 10-12).

Method (deliberately not the code path of flexrig-lumped): with mpmath at 50 digits, the stored
energy is computed by numerical quadrature (tanh-sinh) of the work of the force,
    U(f) = int_0^f phi * d(delta)/d(phi) d(phi),  delta(phi) = phi/k_delta + (phi/k_c)^(1/n),
and the peak force is the root of U(f) = mu v0^2 / 2 found by the secant/Anderson method of
mpmath.findroot. Prints one line per case; the values are embedded in
crates/lumped/tests/exact.rs.

Usage: python3 scripts/reference_exact.py   (needs `pip install mpmath`)
"""
import mpmath as mp

mp.mp.dps = 50

# (m_h, m_eff, k_delta, k_c, n, v0)
CASES = [
    (4, "10/3+0.1", "1e8", "1e8", "2", "2"),
    (4, "10/3+0.1", "1e8", "1e8", "1.5", "2"),
    (4, "20/9+0.1", "2e2", "1e8", "2", "2"),
    (1000, "10/3+0.1", "1e8", "1e8", "2.5", "2"),
    ("0.398", "0.429", "6.0", "7.359e7", "1.961", "0.9"),
    ("4.008", "0.429", "6.0", "9.642e7", "2.002", "0.9"),
    ("0.039", "0.1", "1e2", "1.311e7", "1.817", "1.5"),
    (1, 1, "1e-2", "1e4", "3", "1"),
]


def peak(m_h, m_eff, k_delta, k_c, n, v0):
    m_h, m_eff = mp.mpf(mp.mpmathify(eval_frac(m_h))), mp.mpf(eval_frac(m_eff))
    k_delta, k_c, n, v0 = (mp.mpf(x) for x in (k_delta, k_c, n, v0))
    mu = m_h * m_eff / (m_h + m_eff)
    energy = mu * v0**2 / 2

    def work(f):
        integrand = lambda phi: phi * (1 / k_delta + (phi / k_c) ** (1 / n) / (n * phi))
        return mp.quad(integrand, [0, f])

    # Start from the smaller single-spring solution (an upper bound).
    f_link = mp.sqrt(2 * energy * k_delta)
    f_contact = (energy * (n + 1)) ** (n / (n + 1)) * k_c ** (1 / (n + 1))
    f0 = min(f_link, f_contact)
    return mp.findroot(lambda f: work(f) - energy, (f0 * mp.mpf("0.5"), f0), solver="anderson")


def eval_frac(text):
    text = str(text)
    if "+" in text or "/" in text:
        total = mp.mpf(0)
        for term in text.split("+"):
            if "/" in term:
                a, b = term.split("/")
                total += mp.mpf(a) / mp.mpf(b)
            else:
                total += mp.mpf(term)
        return total
    return mp.mpf(text)


if __name__ == "__main__":
    for case in CASES:
        f = peak(*case)
        print(case, mp.nstr(f, 25))
