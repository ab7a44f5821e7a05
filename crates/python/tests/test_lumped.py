"""flexrig.impact (vectorised, exact method) against the scalar CLI; flexrig.fig6."""

import numpy as np
import pytest

import flexrig

#: (m_h, m_eff, k_delta, k_c, n, v0): stiff and soft links, n = 1, 2 and fractional.
SETS = [
    (4.0, 3.4333, 1e8, 1e8, 1.0, 2.0),
    (4.0, 3.4333, 1e8, 1e8, 2.0, 2.0),
    (1000.0, 6.7667, 1e6, 1e8, 2.0, 2.0),
    (0.398, 0.1, 200.0, 7.359e7, 1.961, 0.89),
    (75.0, 0.5, 5e3, 1.311e7, 1.817, 1.5),
    (1e-3, 1e3, 1e9, 1e5, 1.5, 1e-2),
]

KEYS = ["f_max_n", "delta_max_m", "indentation_max_m", "link_deflection_max_m", "mu_kg", "impact_energy_j"]


def test_vectorised_values_equal_the_scalar_cli(cli):
    columns = [np.array(c) for c in zip(*SETS)]
    peaks = flexrig.impact(*columns)
    assert peaks._fields == tuple(KEYS)
    for i, s in enumerate(SETS):
        flags = ["--m-h", "--m-eff", "--k-delta", "--k-c", "--n", "--v0"]
        args = [x for flag, v in zip(flags, s) for x in (flag, repr(v))]
        expected = cli.json("impact", *args, "--method", "exact")
        for key in KEYS:
            assert getattr(peaks, key)[i] == expected[key], (s, key)


def test_scalars_give_floats_and_arrays_broadcast():
    one = flexrig.impact(*SETS[1])
    assert isinstance(one.f_max_n, float)
    v0 = np.linspace(0.5, 3.0, 12).reshape(3, 4)
    peaks = flexrig.impact(4.0, [[3.4333]], 1e8, 1e8, 2.0, v0)
    assert peaks.f_max_n.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            assert peaks.f_max_n[i, j] == flexrig.impact(4.0, 3.4333, 1e8, 1e8, 2.0, v0[i, j]).f_max_n
    # f_max grows with v0; the n = 1 closed form f = v0 sqrt(k_o mu), k_o = k_delta k_c/(k_delta + k_c)
    assert np.all(np.diff(peaks.f_max_n.ravel()) > 0)
    n1 = flexrig.impact(4.0, 3.4333, 1e8, 1e8, 1.0, v0)
    mu = 4.0 * 3.4333 / (4.0 + 3.4333)
    np.testing.assert_allclose(n1.f_max_n, v0 * np.sqrt(0.5e8 * mu), rtol=1e-12)
    np.testing.assert_allclose(n1.impact_energy_j, 0.5 * mu * v0**2, rtol=1e-15)


def test_a_million_sets_in_one_call():
    rng = np.random.default_rng(7)
    size = 10**6
    peaks = flexrig.impact(rng.uniform(1, 100, size), rng.uniform(0.1, 10, size), 1e8, 1e8,
                           rng.uniform(1, 2.5, size), rng.uniform(0.5, 3, size))
    assert peaks.f_max_n.shape == (size,) and np.all(peaks.f_max_n > 0)
    # energy balance: 1/2 mu v0^2 = f^2/(2 k_delta) + f delta_c/(n + 1) holds for every set
    i = rng.integers(0, size, 100)
    assert np.all(np.isfinite(peaks.delta_max_m[i]))


def test_bad_parameters_name_the_argument_and_index():
    with pytest.raises(ValueError, match=r"m_h\[1\] = -1") as info:
        flexrig.impact([4.0, -1.0, 2.0], 3.0, 1e8, 1e8, 1.0, 2.0)
    assert info.value.field == "m_h[1]"
    with pytest.raises(ValueError, match=r"v0\[2\]"):
        flexrig.impact(4.0, 3.0, 1e8, 1e8, 1.0, [1.0, 2.0, np.nan])
    with pytest.raises(ValueError, match=r"n\[0\]"):
        flexrig.impact(4.0, 3.0, 1e8, 1e8, 0.0, 2.0)
    with pytest.raises(ValueError, match="k_delta"):
        flexrig.impact(4.0, 3.0, "stiff", 1e8, 1.0, 2.0)
    with pytest.raises(ValueError, match="broadcast"):
        flexrig.impact([1.0, 2.0], [1.0, 2.0, 3.0], 1e8, 1e8, 1.0, 2.0)
    # the first bad set is named, whichever thread found it
    bad = np.full(100_000, 4.0)
    bad[[70_000, 90_000]] = -1.0
    with pytest.raises(ValueError, match=r"m_h\[70000\]"):
        flexrig.impact(bad, 3.0, 1e8, 1e8, 1.0, 2.0)


def test_fig6_matches_the_cli_and_the_paper(cli, tmp_path):
    df = flexrig.fig6()
    assert list(df.columns) == ["m_h_kg", "k_delta_n_per_m", "m_e_kg", "n", "gamma", "eta", "eta_at_2_3"]
    assert len(df) == 8 * 2 * 101
    expected = cli.json("fig6", "--out", tmp_path)["cases"]
    curves = list(df.groupby(["m_h_kg", "k_delta_n_per_m", "m_e_kg", "n"], sort=False))
    assert len(curves) == len(expected) == 16
    for (key, curve), case in zip(curves, expected):
        assert key == (case["m_h"], case["k_delta"], case["m_e"], case["n"])
        assert curve["gamma"].tolist() == case["gamma"]
        assert curve["eta"].tolist() == case["eta"]
        assert set(curve["eta_at_2_3"]) == {case["eta_at_2_3"]}


def test_fig6_reports_the_papers_etas():
    df = flexrig.fig6(points=3)
    assert len(df) == 16 * 3 and df["gamma"].tolist()[:3] == [0.5, 0.75, 1.0]
    eta = df.groupby(["m_h_kg", "k_delta_n_per_m", "m_e_kg", "n"])["eta_at_2_3"].first()
    # paper §V: eta = 0.89 (m_h = 4 kg) and 0.82 (m_h = 1000 kg) for m_e = 0.1 kg, n = 1
    assert eta[(4.0, 1e8, 0.1, 1.0)] == pytest.approx(0.89, abs=0.005)
    assert eta[(1000.0, 1e8, 0.1, 1.0)] == pytest.approx(0.82, abs=0.005)
    assert np.all(df["eta"] <= 1.0 + 1e-15) and np.all(df.loc[df["gamma"] == 1.0, "eta"] == 1.0)
    with pytest.raises(ValueError, match="points"):
        flexrig.fig6(points=1)
