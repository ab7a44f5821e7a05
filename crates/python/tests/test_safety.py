"""flexrig.safety against ``flexrig safety --json``: the same numbers, bit for bit."""

import pytest

import flexrig

CASES = [
    (
        dict(region="chest", area="Sternum", moving_mass=20.0, payload=1.0, area_model="fixed",
             contact_area=1e-4, method="standard,energy", speed=0.3),
        ["--region", "chest", "--area", "Sternum", "--moving-mass", "20", "--payload", "1",
         "--area-model", "fixed", "--contact-area", "1e-4m2", "--method", "standard,energy",
         "--speed", "0.3"],
    ),
    (
        dict(region="hands_and_fingers", area="Back of the hand ND", m_r=0.051, m_e=0.412, gamma=1.0,
             material="skinned_aluminium", k_delta=1e4, method=["standard", "energy", "simulation"],
             speed=1.5),
        ["--region", "hands_and_fingers", "--area", "Back of the hand ND", "--m-r", "0.051",
         "--m-e", "0.412", "--gamma", "1", "--material", "skinned_aluminium", "--k-delta", "1e4",
         "--method", "standard,energy,simulation", "--speed", "1.5"],
    ),
    (
        dict(region="abdomen", contact="quasi_static", m_eff=3.0, k_c=1e6, n=1.5,
             area_model="hertz_sphere", radius=0.05),
        ["--region", "abdomen", "--contact", "quasi-static", "--m-eff", "3", "--k-c", "1e6",
         "--n", "1.5", "--area-model", "hertz-sphere", "--radius", "0.05"],
    ),
    (
        dict(region="chest", m_eff=3.0, contact_area="2cm2", speed=0.5),
        ["--region", "chest", "--m-eff", "3", "--contact-area", "2cm2", "--speed", "0.5"],
    ),
]


@pytest.mark.parametrize("kwargs,flags", CASES)
def test_safety_equals_the_cli_json(cli, kwargs, flags):
    assert flexrig.safety(**kwargs) == cli.json("safety", *flags)


def test_the_overall_verdict_is_the_most_restrictive_method_and_a_free_hub_needs_its_length():
    # the light-payload hand of the re-contact reference (scripts/reference_recontact.py):
    # permissible 1.5825554 m/s by every contact; at 2 m/s the simulation alone fails
    r = flexrig.safety("hands_and_fingers", m_r=0.051, m_e=0.01, k_delta=2e4, k_c=7.359e7,
                       n=2.0, link="cj", speed=2.0)
    assert [m["method"] for m in r["methods"]] == ["standard", "energy", "simulation"]
    o = r["overall"]
    assert o["method"] == "simulation" and o["pass"] is False and o["failed_by"] == ["simulation"]
    assert abs(o["v_max_mps"] / 1.582555402403759 - 1.0) < 1e-4
    with pytest.raises(flexrig.InputError, match="--length"):
        flexrig.safety("chest", m_r=2.0, m_e=1.0, link="cj", joint="free_hub", rotor_inertia=0.1,
                       method="simulation")


def test_transient_head_contact_is_refused_with_the_clause():
    with pytest.raises(flexrig.InputError, match="5.5.5.4"):
        flexrig.safety("face", m_eff=5.0)


def test_bad_arguments_name_the_field():
    with pytest.raises(flexrig.InputError, match="--k-delta"):
        flexrig.safety("chest", m_eff=5.0, k_delta=-1.0)
    with pytest.raises(flexrig.InputError) as e:
        flexrig.safety("chest", m_eff=5.0, area_model="fixed")
    assert e.value.field == "contact_area"


def test_safety_map_equals_the_cli_map(cli, tmp_path):
    import json

    import numpy as np

    cli("safety-map", "--region", "hands_and_fingers", "--material", "skinned_aluminium",
        "--m-r", "0.051", "--x", "m-e=0.01:5:4:log", "--y", "k-delta=10,1e4,1e7",
        "--out", str(tmp_path))
    expected = json.loads((tmp_path / "safety_map.json").read_text())
    got = flexrig.safety_map("hands_and_fingers", material="skinned_aluminium", m_r=0.051,
                             x="m-e=0.01:5:4:log", y=("k_delta", [10.0, 1e4, 1e7]))
    assert got["map"]["cells"][0]["x"] == expected["cells"][0]["x"]
    for a, b in zip(got["map"]["cells"], expected["cells"]):
        assert a["cj"] == b["cj"] and a["cl"] == b["cl"]
    assert got["v_max_cj_mps"].shape == (3, 4)
    assert got["v_max_cl_mps"][2, 3] == expected["cells"][11]["cl"]["v_max_mps"]
    np.testing.assert_array_equal(got["ratio_cl_cj"], got["v_max_cl_mps"] / got["v_max_cj_mps"])


def test_safety_map_refuses_a_bad_axis_naming_it():
    with pytest.raises(flexrig.InputError, match="x"):
        flexrig.safety_map("chest", m_r=0.05, x="speed=1:2:3")
    with pytest.raises(flexrig.InputError):
        flexrig.safety_map("chest", m_r=0.05, x=("weight", [1, 2]))


def test_safety_of_a_driven_scene_equals_the_cli_json(cli):
    # the bundled driven CJ against a wall: the chest clamped, the drive's speed searched
    got = flexrig.safety("chest", scene="driven_cj_wall")
    assert got == cli.json("safety", "--region", "chest", "--scene", "driven_cj_wall")
    assert got["contact"] == "quasi_static"
    assert [m["method"] for m in got["methods"]] == ["standard", "energy", "simulation"]
    assert got["scene"]["by_force_mps"] == got["methods"][2]["by_force_mps"]


def test_safety_of_a_test_bed_scene_equals_the_cli_json(cli):
    # the bundled CJ test bed: the operator's speed at contact searched through its release angle
    got = flexrig.safety("abdomen", scene="cj_aluminium", method="simulation")
    assert got == cli.json(
        "safety", "--region", "abdomen", "--scene", "cj_aluminium", "--method", "simulation"
    )
    assert got["contact"] == "transient"
    scene = got["scene"]
    assert scene["support"] == "pendulum" and scene["limit_reached"] is True
    assert 0.0 < scene["release_angle_at_root_deg"] <= 170.0
    assert abs(scene["peak_force_at_root_n"] / got["force_limit_n"] - 1.0) < 1e-5
    with pytest.raises(flexrig.InputError, match="5.5.5.4"):
        flexrig.safety("face", scene="cj_aluminium", method="energy")


def test_a_scene_refuses_the_contact_keyword_and_a_transient_head():
    with pytest.raises(flexrig.InputError) as e:
        flexrig.safety("chest", scene="driven_cj_wall", contact="transient")
    assert e.value.field == "contact"
    with pytest.raises(flexrig.InputError, match="5.5.5.4"):
        flexrig.safety("face", scene="driven_cj_free_head", method="energy")


def test_safety_map_over_body_regions_equals_the_cli_map(cli, tmp_path):
    import json

    cli("safety-map", "--m-r", "0.5", "--x", "m-e=0.1,1", "--y", "region=chest,abdomen,face",
        "--out", str(tmp_path))
    expected = json.loads((tmp_path / "safety_map.json").read_text())
    got = flexrig.safety_map(m_r=0.5, x="m-e=0.1,1", y=("region", ["chest", "abdomen", "face"]))
    assert got["y_names"] == ["chest", "abdomen", "face"]
    for a, b in zip(got["map"]["cells"], expected["cells"]):
        assert a.get("cj") == b.get("cj") and a.get("error") == b.get("error")
    assert got["v_max_cj_mps"].shape == (3, 2)
    assert len(got["errors"]) == 2  # the face: transient contact not permitted


def _pulse(path, f0=250.0):
    """A half-sine pulse of f0 N over 10 ms with its acceleration (g) and indentation (mm)."""
    import math

    lines = ["t [ms], F [N], a [g], delta [mm]"]
    for i in range(401):
        x = math.sin(math.pi * i / 400)
        lines.append(f"{10 * i / 400!r}, {f0 * x!r}, {40 * x!r}, {2 * x!r}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_measured_trace_equals_the_cli_json(cli, tmp_path):
    path = _pulse(tmp_path / "pulse.csv")
    expected = cli.json("safety", "--trace", path, "--region", "chest", "--contact-area", "2cm2")
    assert flexrig.safety("chest", trace=path, contact_area="2cm2") == expected
    assert flexrig.safety("chest", trace=str(path), contact_area=2e-4) == expected
    assert expected["verdict"]["pass"] is True
    assert expected["severity"]["energy_transferred_from"] == "force_and_indentation"
    # without an area: pressure not assessed
    bare = flexrig.safety("chest", trace=path)
    assert bare["verdict"]["pressure_assessed"] is False and "pressure_margin" not in bare["verdict"]


def test_a_measured_trace_refuses_design_keywords_and_bad_lines(tmp_path):
    path = _pulse(tmp_path / "pulse.csv")
    with pytest.raises(flexrig.InputError) as e:
        flexrig.safety("chest", trace=path, m_eff=3.0)
    assert e.value.field == "m_eff"
    bad = tmp_path / "bad.csv"
    bad.write_text("t [s], F [N]\n0, 1\n0.001, oops\n")
    with pytest.raises(flexrig.InputError, match="line 3") as e:
        flexrig.safety("chest", trace=bad)
    assert e.value.field == "trace"


def test_an_area_without_its_unit_is_refused_and_an_implausible_one_warned_about():
    with pytest.raises(flexrig.InputError) as e:
        flexrig.safety("chest", m_eff=3.0, contact_area="1")
    assert e.value.field == "contact_area"
    with pytest.warns(flexrig.PlausibilityWarning, match="contact_area"):
        r = flexrig.safety("chest", m_eff=3.0, contact_area=1.0)
    assert r["warnings"][0]["field"] == "contact_area"


def _without_warnings(report):
    return {k: v for k, v in report.items() if k != "warnings"}


def test_a_unit_slip_is_warned_about_naming_the_keyword_as_the_cli_names_the_flag(cli, tmp_path):
    # 1200 kg typed for 1200 g, 600 m for 600 mm: the command's warnings name --m-r and
    # --length, Python's the keyword arguments, with the same messages and the same report
    with pytest.warns(flexrig.PlausibilityWarning) as caught:
        got = flexrig.safety("chest", m_r=1200.0, m_e=0.412, link="cj", length=600.0,
                             method="standard,energy")
    expected = cli.json("safety", "--region", "chest", "--m-r", "1200", "--m-e", "0.412", "--link",
                        "cj", "--length", "600", "--method", "standard,energy")
    assert [w["field"] for w in expected["warnings"]] == ["--m-r", "--length"]
    assert got["warnings"] == [
        {"field": w["field"][2:].replace("-", "_"), "message": w["message"]} for w in expected["warnings"]
    ]
    assert [str(w.message) for w in caught] == [f"{w['field']}: {w['message']}" for w in got["warnings"]]
    assert _without_warnings(got) == _without_warnings(expected)
    # a measured trace: a column it does not read is named by the keyword trace
    path = _pulse(tmp_path / "pulse.csv")
    lines = path.read_text().splitlines()
    lines = [lines[0] + ", temperature [K]"] + [line + ", 300" for line in lines[1:]]
    path.write_text("\n".join(lines) + "\n")
    with pytest.warns(flexrig.PlausibilityWarning, match=r"^trace: columns not used: temperature \[K\]"):
        got = flexrig.safety("chest", trace=path)
    expected = cli.json("safety", "--trace", path, "--region", "chest")
    assert [w["field"] for w in expected["warnings"]] == ["--trace"]
    assert got["warnings"] == [{"field": "trace", "message": expected["warnings"][0]["message"]}]
    assert _without_warnings(got) == _without_warnings(expected)


def test_the_map_warns_about_a_unit_slip_naming_the_keyword(cli, tmp_path):
    args = dict(m_r=0.051, m_e=250.0, x="k-c=1e7:1e8:2", y="k-delta=10:1e7:2:log", method="energy")
    with pytest.warns(flexrig.PlausibilityWarning, match=r"m_e: 250 kg is heavier"):
        got = flexrig.safety_map("chest", **args)
    expected = cli.json("safety-map", "--region", "chest", "--m-r", "0.051", "--m-e", "250", "--x",
                        "k-c=1e7:1e8:2", "--y", "k-delta=10:1e7:2:log", "--method", "energy",
                        "--out", tmp_path)["warnings"]
    assert [w["field"] for w in expected] == ["--m-e"]
    assert got["warnings"] == [{"field": "m_e", "message": expected[0]["message"]}]
    # the library's whole result too
    assert got["map"]["warnings"] == got["warnings"]
