"""flexrig.arm against ``flexrig arm --json``: the same numbers bit for bit; NumPy arrays in
give the answer of the same trajectory as a CSV; a pandas DataFrame out; bad input named."""

import numpy as np
import pytest

import flexrig

from conftest import ROOT

ROOT_UR5 = "assets/robots/ur5.urdf"


def _without_samples(cli_json):
    cli_json = dict(cli_json)
    cli_json.pop("samples")
    cli_json.pop("urdf")
    cli_json.pop("trajectory")
    return cli_json


def test_the_bundled_arm_equals_the_cli_json(cli):
    got = flexrig.arm(k_delta=2e4, material="skinned_aluminium", mass_step=0.05)
    want = cli.json("arm", "--k-delta", "2e4", "--material", "skinned_aluminium", "--mass-step", "0.05")
    table = got.pop("table")
    assert got == _without_samples(want)
    # the table holds every sample × point of the CLI's samples
    rows = [(s["time_s"], p["speed_mps"], p["ratio"]) for s in want["samples"] for p in s["points"]]
    assert len(table) == len(rows)
    assert list(table.columns) == list(flexrig.ARM_COLUMNS)
    assert np.array_equal(table["speed_mps"].to_numpy(), np.array([r[1] for r in rows]))
    assert np.array_equal(table["ratio"].to_numpy(), np.array([r[2] for r in rows]))
    g = got["governing"]
    worst = table.loc[table["ratio"].idxmax()]
    assert worst["ratio"] == g["ratio"] and worst["time_s"] == g["time_s"]


def test_numpy_arrays_are_the_csv(cli, tmp_path):
    # the bundled swing as arrays: the same answer as the bundled CSV
    lines = [l for l in open(ROOT / "assets/robots/ur5_swing.csv") if not l.startswith("#")]
    data = np.array([[float(x) for x in l.split(",")] for l in lines[1:]])
    got = flexrig.arm(urdf=ROOT / ROOT_UR5, times=data[:, 0], positions=data[:, 1:],
                      points=["tool0:0,0,0.1", "forearm_link"])
    want = flexrig.arm(points=["tool0:0,0,0.1", "forearm_link"])
    assert got["max_ratio"] == want["max_ratio"]
    assert got["table"].equals(want["table"])


def test_bad_input_names_the_argument(cli):
    with pytest.raises(flexrig.InputError) as e:
        flexrig.arm(points=["toool0:0,0,0.1"])
    assert "toool0" in str(e.value) and "tool0" in str(e.value)
    with pytest.raises(flexrig.InputError) as e:
        flexrig.arm(mass_step=0.5)
    assert "mass_step" in str(e.value)
    with pytest.raises(flexrig.InputError) as e:
        flexrig.arm(link="cx")
    assert e.value.field == "link"
    with pytest.raises(flexrig.InputError) as e:
        flexrig.arm(urdf=ROOT / ROOT_UR5, points=["tool0"])
    assert "trajectory" in str(e.value)
    with pytest.raises(flexrig.InputError) as e:
        flexrig.arm(urdf=ROOT / ROOT_UR5, times=[0, 1, 2], positions=np.zeros((3, 5)), points=["tool0"])
    assert "5 joint positions" in str(e.value) and "6" in str(e.value)
