"""flexrig.sweep: the DataFrame equals `flexrig sweep`'s CSV, failed runs are rows, bad input is
refused naming it, the native Sweep pickles."""

import csv
import math
import pickle

import numpy as np
import pandas as pd
import pytest

import flexrig
from conftest import missing, scene_path

#: A quick sweep (from contact to the peak): 3 angles × CJ/CL, and a payload out of range
#: whose runs fail.
GRID = {
    "operator.start.release_angle_deg": "20:40:3",
    "robot.design": ["cj", "cl"],
    "robot.payload_kg": [0.412, -1.0],
    "operator.start.from": "contact",
    "stop": {"at": "peak"},
}
CLI_SETS = [
    "operator.start.release_angle_deg=20:40:3",
    "robot.design=cj,cl",
    "robot.payload_kg=0.412,-1.0",
    "operator.start.from=contact",
    'stop={ at = "peak" }',
]


def read_cli_table(path, like: pd.DataFrame) -> pd.DataFrame:
    """The CLI's CSV with every cell parsed exactly (Python float()), typed like ``like``."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    columns = {}
    for j, name in enumerate(header):
        cells = [r[j] for r in rows]
        if name == "index":
            columns[name] = np.array([int(c) for c in cells], dtype=np.int64)
        elif str(like[name].dtype) == "Int64":
            # the CSV writes counts in the float format (1e0): whole numbers read exactly
            assert all(c == "" or float(c).is_integer() for c in cells), name
            columns[name] = pd.array([int(float(c)) if c != "" else None for c in cells], dtype="Int64")
        elif like[name].dtype == np.float64:
            columns[name] = np.array([float(c) if c != "" else math.nan for c in cells])
        else:
            columns[name] = cells
    return pd.DataFrame(columns)


@pytest.fixture(scope="module")
def table():
    return flexrig.sweep(scene_path("cj_iron"), GRID)


def test_the_dataframe_equals_the_cli_csv(cli, table, tmp_path):
    sets = [w for s in CLI_SETS for w in ("--set", s)]
    result = cli("sweep", scene_path("cj_iron"), "--out", tmp_path, *sets, check=False)
    assert result.returncode == 1, result.stderr  # some runs fail: exit 1, the table is written
    expected = read_cli_table(tmp_path / "sweep.csv", table)
    # the counts are whole numbers in the CSV, not 1e0
    with open(tmp_path / "sweep.csv", newline="") as f:
        rows = list(csv.reader(f))
    for name in flexrig.INTEGER_SUMMARY_COLUMNS:
        j = rows[0].index(name)
        cells = [r[j] for r in rows[1:] if r[j]]
        assert cells and all(c.isdigit() for c in cells), (name, cells)
    assert list(table.columns) == list(expected.columns)
    pd.testing.assert_frame_equal(table, expected, check_dtype=False, check_exact=True)  # bit for bit
    assert table["index"].dtype == np.int64
    for name in flexrig.SUMMARY_COLUMNS:
        if name in flexrig.INTEGER_SUMMARY_COLUMNS:
            assert str(table[name].dtype) == "Int64", name
        else:
            assert table[name].dtype == np.float64, name


def test_rows_are_the_points_in_grid_order(table):
    assert len(table) == 3 * 2 * 2
    assert table["index"].tolist() == list(range(12))
    assert table["operator.start.release_angle_deg"].tolist() == [20.0] * 4 + [30.0] * 4 + [40.0] * 4
    assert table["robot.design"].tolist()[:4] == ["cj", "cj", "cl", "cl"]
    assert table["stop"].tolist() == ['{ at = "peak" }'] * 12


def test_a_failed_run_is_a_row_with_its_error(table):
    failed = table[table["robot.payload_kg"] < 0]
    assert len(failed) == 6
    assert (failed["status"] == "error").all()
    assert failed["error"].str.contains("robot.payload_kg").all()
    assert failed[list(flexrig.SUMMARY_COLUMNS)].isna().all().all()
    ok = table[table["robot.payload_kg"] > 0]
    assert (ok["status"] == "ok").all() and (ok["error"] == "").all()
    assert (ok["peak_force_n"] > 0).all() and ok["separation_velocity_mps"].isna().all()


def test_a_row_equals_its_single_run(table):
    row = table.iloc[2]
    r = flexrig.run("cj_iron", **{"operator.start.release_angle_deg": 20.0, "robot.design": "cl",
                                  "robot.payload_kg": 0.412, "operator.start.from": "contact",
                                  "stop": {"at": "peak"}})
    assert row["peak_force_n"] == r.peak_force_n and row["steps"] == r.steps
    # the link quantities of the row's scene (a CL with the cj_iron link), as the run reports them
    assert list(flexrig.LINK_COLUMNS) == [c for c in flexrig.SUMMARY_COLUMNS if c in flexrig.LINK_COLUMNS]
    for name in flexrig.LINK_COLUMNS:
        assert row[name] == getattr(r, name) == r.summary[name], name


def test_value_forms_give_the_same_sweep():
    base = "cj_iron"
    fixed = {"operator.start.from": "contact", "stop.at": "peak"}
    a = flexrig.sweep(base, {"robot.payload_kg": "0.1,0.2,0.3", **fixed})
    b = flexrig.sweep(base, {"robot.payload_kg": [0.1, 0.2, 0.3], **fixed})
    c = flexrig.sweep(base, {"robot.payload_kg": np.array([0.1, 0.2, 0.3]), **fixed}, threads=1)
    d = flexrig.sweep(base, {"robot.payload_kg": pd.Series([0.1, 0.2, 0.3]), **fixed}, threads=2)
    for other in (b, c, d):
        pd.testing.assert_frame_equal(a, other)
    # zipped lists have one length: fixed values go into the base
    quick = flexrig.scene_text(base, overrides=fixed)
    z = flexrig.sweep(quick, {"robot.payload_kg": [0.1, 0.2], "operator.start.release_angle_deg": [20, 30]},
                      zip=True)
    assert len(z) == 2 and z["operator.start.release_angle_deg"].tolist() == [20, 30]


def test_a_values_file_next_to_the_base(tmp_path):
    base = tmp_path / "base.toml"
    base.write_text(scene_path("cj_iron").read_text())
    (tmp_path / "payloads.txt").write_text("# payloads\n0.1\n0.3\n")
    df = flexrig.sweep(base, {"robot.payload_kg": "@payloads.txt", "operator.start.from": "contact",
                              "stop.at": "peak"})
    assert df["robot.payload_kg"].tolist() == [0.1, 0.3]


@pytest.mark.parametrize(
    "grid, field, words",
    [
        ({}, "grid", "empty"),
        ({"robot.payload_kg": []}, "robot.payload_kg", "no values"),
        ({"robot.payload_kgg": [0.1]}, "robot.payload_kgg", "unknown field"),
        ({"robot.payload_kg": ["heavy"]}, "robot.payload_kg", "invalid type"),
        ({"robot.payload_kg": "1:2:0"}, "robot.payload_kg", "count"),
        ({"robot..payload_kg": [0.1]}, "robot..payload_kg", "scene path"),
        ({"robot.payload_kg": [None]}, "robot.payload_kg", "not a scene value"),
    ],
)
def test_bad_grids_raise_value_errors_naming_them(grid, field, words):
    with pytest.raises(ValueError) as info:
        flexrig.sweep("cj_iron", grid)
    assert field in str(info.value) and words in str(info.value), str(info.value)
    assert info.value.field == field


def test_other_bad_sweeps():
    with pytest.raises(ValueError, match="zip"):
        flexrig.sweep("cj_iron", {"robot.payload_kg": [0.1, 0.2], "robot.design": ["cj"]}, zip=True)
    with pytest.raises(ValueError, match="grid"):
        flexrig.sweep("cj_iron", [("robot.payload_kg", [0.1])])
    with pytest.raises(ValueError, match="threads"):
        flexrig.sweep("cj_iron", {"robot.payload_kg": [0.1]}, threads=0)


@pytest.mark.parametrize(
    "arguments, field",
    [
        # Regression: threads=-1 raised OverflowError, client=object() AttributeError
        ({"threads": -1}, "threads"),
        ({"threads": 2**70}, "threads"),
        ({"threads": 1.5}, "threads"),
        ({"threads": True}, "threads"),
        ({"threads": "4"}, "threads"),
        ({"chunk_size": 0}, "chunk_size"),
        ({"chunk_size": -3}, "chunk_size"),
        ({"client": object()}, "client"),
        ({"client": "tcp://localhost:8786"}, "client"),
    ],
)
def test_bad_sweep_arguments_raise_input_error_naming_them(arguments, field):
    with pytest.raises(flexrig.InputError) as info:
        flexrig.sweep("cj_iron", {"robot.payload_kg": [0.1]}, **arguments)
    assert info.value.field == field
    assert str(info.value).startswith(field), str(info.value)


def test_the_native_sweep_pickles_and_runs_chunks_like_the_whole():
    text, _ = flexrig._flexrig.scene_text("cj_iron")
    grid = [("robot.payload_kg", "0.1:0.5:5"), ("operator.start.from", "contact"), ("stop", {"at": "peak"})]
    s = flexrig.Sweep(text, grid)
    t = pickle.loads(pickle.dumps(s))
    assert len(t) == len(s) == 5 and t.paths == s.paths and t.fingerprint() == s.fingerprint()
    whole = s.run()
    parts = [t.run([0, 3], 1), t.run([4, 1, 2], 1)]
    frame = flexrig._frame(s.paths, [whole])
    pd.testing.assert_frame_equal(frame, flexrig._frame(t.paths, parts))
    assert "5 points" in repr(s)
    with pytest.raises(ValueError, match="indices"):
        s.run([5])


def test_the_table_round_trips_through_parquet(table, tmp_path):
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        missing("pyarrow")
    table.to_parquet(tmp_path / "sweep.parquet")
    back = pd.read_parquet(tmp_path / "sweep.parquet")
    pd.testing.assert_frame_equal(back, table, check_dtype=False)
    assert back["peak_force_n"].dtype == np.float64


def test_a_huge_grid_is_refused_before_anything_is_made():
    # Regression: a large grid aborted the interpreter on memory. The grid is counted from the
    # sizes of its entries (never materialised here) and refused naming the entry.
    big = range(10**9)
    with pytest.raises(flexrig.InputError) as info:
        flexrig.sweep("cj_iron", {"robot.payload_kg": big})
    assert info.value.field == "robot.payload_kg" and "at most" in str(info.value)
    with pytest.raises(flexrig.InputError) as info:
        flexrig.sweep("cj_iron", {"robot.payload_kg": np.zeros(5000), "robot.length_m": np.zeros(5000)})
    assert info.value.field == "robot.length_m"
    with pytest.raises(flexrig.InputError, match="at most"):
        flexrig.sweep("cj_iron", {"robot.payload_kg": "0:1:100000000"})
    # within the grid bound but more than one process runs: refused before running, naming grid
    with pytest.raises(flexrig.InputError) as info:
        flexrig.sweep("cj_iron", {"robot.payload_kg": "0.1:0.2:2000", "robot.length_m": "0.1:0.5:1000"})
    assert info.value.field == "grid" and "shards" in str(info.value)


def test_a_field_varied_twice_is_refused():
    with pytest.raises(flexrig.InputError, match="overlaps"):
        flexrig.sweep(
            "cj_iron",
            {"operator.start": [{"from": "release", "release_angle_deg": 20.0}], "operator.start.release_angle_deg": [10, 20]},
        )
