"""flexrig.spin_up, flexrig.strike and flexrig.role_switch against the CLI: the same numbers, bit
for bit, from the command's CSV and JSON."""

import csv
import json
from pathlib import Path

import numpy as np
import pytest

import flexrig

DRIVES = Path(__file__).resolve().parents[3] / "assets" / "drives"
#: the spin-up result's file paths (each front its own directory)
PATHS = ("csv", "json", "svg", "figures")


def test_spin_up_equals_the_cli_csv_bit_for_bit(cli, tmp_path):
    args = ["--omega-s", "4", "--duration", "8", "--elements", "8", "--modes", "4"]
    cli("spin-up", "--out", tmp_path, *args)
    with open(tmp_path / "spin_up.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    df = flexrig.spin_up(omega_s=4.0, duration=8.0, elements=8, modes=4)
    assert list(df.columns) == ["t", "fe", "reference", "linear"]
    assert len(df) == len(rows) == 81
    for column in df.columns:
        expected = np.array([float(r[column]) for r in rows])
        assert np.array_equal(df[column].to_numpy(), expected), column
    # the FE beam follows the independent elastica: within 1 % of the max at every time
    assert np.max(np.abs(df.fe - df.reference)) <= 0.01 * np.max(np.abs(df.reference))


def test_spin_up_of_kanes_beam_equals_the_cli_json_bit_for_bit(cli, tmp_path):
    # the case's own numbers (its 8 m beam, 4 rad/s): no beam keyword given
    expected = cli.json("spin-up", "--case", "kane", "--out", tmp_path / "cli")
    df = flexrig.spin_up(case="kane", out=tmp_path / "py")
    for column in ("t", "fe", "reference", "linear"):
        assert np.array_equal(df[column].to_numpy(), np.array(expected[column], dtype=np.float64)), column
    assert df.attrs["options"] == expected["options"]
    assert df.attrs["options"]["length"] == 8.0 and df.attrs["options"]["omega_s"] == 4.0
    for key in ("fe_error_of_max", "reference_max_m"):
        assert df.attrs[key] == expected[key], key
    # the JSON file each wrote holds the same numbers, the paths aside
    on_disk = json.loads(Path(df.attrs["json"]).read_text())
    assert {k: v for k, v in on_disk.items() if k not in PATHS} == {
        k: v for k, v in expected.items() if k not in PATHS
    }


def test_spin_up_keywords_override_the_cases_numbers(cli, tmp_path):
    args = ["--case", "kane", "--density", "2700", "--duration", "6", "--elements", "6", "--modes", "3"]
    expected = cli.json("spin-up", *args, "--out", tmp_path)
    df = flexrig.spin_up(case="kane", density=2700.0, duration=6.0, elements=6, modes=3)
    assert df.attrs["options"] == expected["options"]
    assert expected["options"]["density"] == 2700.0 and expected["options"]["length"] == 8.0
    assert np.array_equal(df["fe"].to_numpy(), np.array(expected["fe"], dtype=np.float64))


@pytest.mark.parametrize("case", ["kane-ryan", "Kane", "simo_vu_quoc", ""])
def test_spin_up_refuses_an_unknown_case_naming_the_keyword(case):
    with pytest.raises(flexrig.InputError) as e:
        flexrig.spin_up(case=case)
    assert e.value.field == "case"
    assert str(e.value) == f"invalid argument case = {case}: one of simo-vu-quoc, kane"
    with pytest.raises(flexrig.InputError) as e:
        flexrig.spin_up(case=1)
    assert e.value.field == "case"


@pytest.mark.parametrize("name", ["cj_free_head.toml", "cl_wall.toml"])
def test_strike_equals_the_cli_json_bit_for_bit(cli, name):
    expected = cli.json("strike", DRIVES / name)["outcome"]
    got = flexrig.strike(DRIVES / name)
    for key in ("contact", "energy"):
        assert got[key] == expected[key], key
    for key in ("impact_velocity_mps", "pre_impact_deflection_m", "joint_torque_at_onset_nm",
                "peak_joint_torque_nm", "separation_velocity_mps", "steps"):
        assert got[key] == expected[key], key
    assert got["energy"]["residual_j"] <= 1e-6 * got["energy"]["impact_energy_j"]


def test_strike_keywords_are_the_flags(cli):
    expected = cli.json("strike", "--design", "cj", "--m-h", "6", "--speed", "1.5")["outcome"]
    got = flexrig.strike(design="cj", m_h=6.0, speed=1.5)
    assert got["contact"] == expected["contact"]


def test_strike_trace(tmp_path):
    got = flexrig.strike(DRIVES / "cj_free_head.toml", trace_every=1e-6, out=tmp_path)
    trace = got["trace"]
    assert tuple(trace.columns) == flexrig.STRIKE_TRACE_COLUMNS
    on_disk = np.loadtxt(tmp_path / "strike_trace.csv", delimiter=",", skiprows=1)
    assert np.array_equal(trace.to_numpy(), on_disk)
    peak = got["contact"]["peak_force_n"]
    assert abs(trace.force_n.max() - peak) <= 1e-3 * peak


def test_strike_bad_field_names_it(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((DRIVES / "cl_free_head.toml").read_text().replace("gear_ratio = 50.0", "gear_ratio = 0"))
    with pytest.raises(flexrig.InputError, match="drive.motor.gear_ratio"):
        flexrig.strike(bad)
    with pytest.raises(flexrig.InputError, match="gear_ratio"):
        flexrig.strike(gear_ratio=0.0)


def test_role_switch_equals_the_cli_csv_bit_for_bit(cli, tmp_path):
    cli("role-switch", "--no-fig6", "--kappa", "1,0.01", "--out", tmp_path)
    with open(tmp_path / "role_switch.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    df = flexrig.role_switch(no_fig6=True, kappa=[1.0, 0.01])
    assert list(df.columns) == list(rows[0].keys())
    assert len(df) == len(rows) == 2 * 2 * 4
    for column in df.columns:
        if column in ("case", "design", "drive"):
            assert list(df[column]) == [r[column] for r in rows], column
        else:
            assert np.array_equal(df[column].to_numpy(), np.array([float(r[column]) for r in rows])), column
    # the test bed's link by the exact link: the drive does not matter (docs/driven.md: every
    # drive's ratio the prescribed one's), the driven link turning through the contact within
    # 4e-3 of the rig's struck link (CL 0.9965-0.9971)
    assert np.all(np.abs(df.ratio - 1.0) <= 4e-3)
    for (_, _), group in df.groupby(["case", "design"], sort=False):
        prescribed = group.ratio[group.drive == "prescribed"].iloc[0]
        assert np.all(np.abs(group.ratio / prescribed - 1.0) <= 1e-6)


@pytest.mark.parametrize(
    "twin, defaults",
    [(flexrig.strike, flexrig._flexrig.strike_defaults), (flexrig.spin_up, flexrig._flexrig.spin_up_defaults)],
)
def test_keyword_defaults_are_the_librarys(twin, defaults):
    """The twin's defaults are the library's (the same the CLI's flags take), so a call without
    arguments is the command without flags."""
    import inspect

    library = defaults()
    signature = inspect.signature(twin).parameters
    assert library and set(library) <= set(signature), sorted(set(library) - set(signature))
    for name, value in library.items():
        assert signature[name].default == value and type(signature[name].default) is type(value), name


def test_spin_up_and_role_switch_take_the_figure_flags(cli, tmp_path):
    # the same figure as the CLI's at one column, in SVG and PNG
    args = ["--omega-s", "4", "--duration", "4", "--elements", "4", "--modes", "3"]
    cli("spin-up", "--out", tmp_path / "cli", *args, "--size", "1", "--format", "svg,png")
    df = flexrig.spin_up(
        omega_s=4.0, duration=4.0, elements=4, modes=3, out=tmp_path / "py", size=1, format=["svg", "png"]
    )
    assert sorted(Path(f).name for f in df.attrs["figures"]) == ["spin_up.png", "spin_up.svg"]
    svg = (tmp_path / "py" / "spin_up.svg").read_text()
    assert svg == (tmp_path / "cli" / "spin_up.svg").read_text()
    assert 'width="3.5in"' in svg
    cli("role-switch", "--no-fig6", "--kappa", "1", "--out", tmp_path / "cli", "--format", "pdf")
    df = flexrig.role_switch(no_fig6=True, kappa=[1.0], out=tmp_path / "py", format="pdf")
    assert [Path(f).name for f in df.attrs["figures"]] == ["role_switch.pdf"]
    assert (tmp_path / "py" / "role_switch.pdf").stat().st_size > 0
    with pytest.raises(flexrig.InputError, match="size"):
        flexrig.spin_up(size="9 feet")


def test_a_unit_slip_is_warned_about_naming_the_keyword_or_the_field(cli, tmp_path):
    # the shared rule (flexrig run, strike, safety, safety-map): 250 kg typed for 250 g
    with pytest.warns(flexrig.PlausibilityWarning, match=r"m_e: 250 kg is heavier"):
        r = flexrig.strike(m_e=250.0)
    assert r["warnings"] == [{"field": "m_e", "message": cli.json("strike", "--m-e", "250")["warnings"][0]["message"]}]
    text = (DRIVES / "cj_wall.toml").read_text().replace("m_e = 0.1 ", "m_e = 250.0 ")
    path = tmp_path / "heavy.toml"
    path.write_text(text)
    with pytest.warns(flexrig.PlausibilityWarning, match=r"link.m_e: 250 kg"):
        r = flexrig.strike(path)
    assert [w["field"] for w in r["warnings"]] == ["link.m_e"]
    assert flexrig.strike(DRIVES / "cj_wall.toml")["warnings"] == []
