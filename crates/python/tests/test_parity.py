"""Every command of the `flexrig` CLI has a Python twin (or is CLI-only, with a reason), and each
twin gives the numbers of `flexrig COMMAND --json` bit for bit on the same inputs.

The commands are read from the CLI's own help (`flexrig --help`, then each command's help for
its subcommands), so a command added to the CLI fails here until it has a twin: by default the
twin of `flexrig some-command` is `flexrig.some_command` (of `flexrig group sub`,
`flexrig.group_sub`); list a twin of another name in TWINS, or the command in CLI_ONLY with the
reason.
"""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import flexrig

from conftest import ROOT, scene_path

#: Twins not named after their command.
TWINS = {
    # `flexrig run SCENE` ↔ flexrig.run; the others follow the naming rule
    # `flexrig scenes` lists the bundled scenes (`--write NAME` is flexrig.write_scene)
    "scenes": "scene_descriptions",
}

#: Commands deliberately without a Python twin, and why.
CLI_ONLY = {
    "sweep merge": "joins the shard tables that `flexrig sweep --shard` runs wrote on a cluster; "
    "in Python a sweep is one call (here or on a Dask cluster) and has no shards to join",
}


def _help(cli, *command):
    return cli(*command, "--help").stdout


def _subcommands(text):
    """The subcommand names of a help text (its Commands: section, without `help`)."""
    names = []
    inside = False
    for line in text.splitlines():
        if line.strip() == "Commands:":
            inside = True
            continue
        if inside:
            m = re.match(r"^  ([a-z][a-z0-9-]*)\s", line + " ")
            if not m:
                break
            if m.group(1) != "help":
                names.append(m.group(1))
    return names


def _runnable(text):
    """Whether a command runs by itself (a usage line without <COMMAND>)."""
    usage = text[text.index("Usage:") :].split("\n\n")[0]
    lines = [l.replace("Usage:", "").strip() for l in usage.splitlines()]
    return any(l and not l.endswith("<COMMAND>") for l in lines)


def cli_commands(cli):
    """Every command path of the CLI, e.g. ["run", "beam modal", "sweep merge", ...]."""
    found = []

    def walk(path):
        text = _help(cli, *path)
        subs = _subcommands(text)
        if path and (_runnable(text) or not subs):
            found.append(" ".join(path))
        for sub in subs:
            walk(path + [sub])

    walk([])
    return found


def twin_name(command):
    return TWINS.get(command, command.replace("-", "_").replace(" ", "_"))


def test_every_cli_command_has_a_python_twin_or_a_reason(cli):
    commands = cli_commands(cli)
    assert {"run", "impact", "beam modal", "beam static", "sweep merge"} <= set(commands), commands
    missing = [
        f"`flexrig {c}` (expected flexrig.{twin_name(c)})"
        for c in commands
        if c not in CLI_ONLY
        and not (twin_name(c) in flexrig.__all__ and callable(getattr(flexrig, twin_name(c), None)))
    ]
    assert not missing, (
        "commands without a Python twin: " + ", ".join(missing) + "; add the twin to flexrig "
        "(and __all__), name it in TWINS, or list the command in CLI_ONLY with the reason"
    )


def test_the_cli_only_list_names_real_commands_with_reasons(cli):
    commands = set(cli_commands(cli))
    for command, reason in CLI_ONLY.items():
        assert command in commands, f"CLI_ONLY lists `flexrig {command}`, which the CLI does not have"
        assert len(reason) > 20


def test_every_twin_is_compared_with_its_command(cli):
    """The floor "the same numbers from both fronts" for every command: some test runs the
    command through the CLI fixture (`cli.json("eta", ...)`, `cli("spin-up", ...)`) to compare
    its twin's numbers with it."""
    sources = "\n".join(p.read_text(encoding="utf-8") for p in Path(__file__).parent.glob("test_*.py"))
    uncompared = []
    for command in cli_commands(cli):
        if command in CLI_ONLY:
            continue
        words = ", ".join(f'"{w}"' for w in command.split())
        if not re.search(r"\bcli(\.json)?\(" + re.escape(words) + r"[,)]", sources):
            uncompared.append(command)
    assert not uncompared, f"no test compares these twins with the CLI: {uncompared}"


# ---- the same numbers ----------------------------------------------------------------------


def same(python, cli, where="data"):
    """Exact equality of two JSON-like values (floats bit for bit; NaN never appears)."""
    if isinstance(cli, dict):
        assert isinstance(python, dict) and set(python) == set(cli), (where, sorted(python), sorted(cli))
        for k in cli:
            same(python[k], cli[k], f"{where}.{k}")
    elif isinstance(cli, list):
        assert isinstance(python, (list, tuple)) and len(python) == len(cli), where
        for i, (p, c) in enumerate(zip(python, cli)):
            same(p, c, f"{where}[{i}]")
    elif isinstance(cli, float):
        assert isinstance(python, float) and python == cli and math.copysign(1, python) == math.copysign(1, cli), (
            where, python, cli,
        )
    elif isinstance(cli, bool) or cli is None or isinstance(cli, str):
        assert python == cli and type(python) is type(cli), (where, python, cli)
    else:  # int
        assert isinstance(python, int) and not isinstance(python, bool) and python == cli, (where, python, cli)


def same_naming_keywords(python, cli):
    """`same`, but for the `warnings`, which name the keyword arguments (`yield_strength`) where the
    CLI names its flags (`--yield-strength`): the same warnings otherwise, word for word."""
    same(without(python, "warnings"), without(cli, "warnings"))
    as_keywords = lambda text: re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), text)
    expected = [{k: as_keywords(v) for k, v in w.items()} for w in cli.get("warnings", [])]
    same(python.get("warnings", []), expected, "data.warnings")


def without(data, *keys):
    """`data` without the wall-clock `keys` at any depth."""
    if isinstance(data, dict):
        return {k: without(v, *keys) for k, v in data.items() if k not in keys}
    if isinstance(data, list):
        return [without(v, *keys) for v in data]
    return data


@pytest.mark.parametrize(
    "kwargs, flags",
    [
        (dict(gamma=2 / 3, m_r=10.0, m_e=0.1), ["--gamma", repr(2 / 3), "--m-r", "10.0", "--m-e", "0.1"]),
        (dict(m_eff=3.4333, method="analytic"), ["--m-eff", "3.4333", "--method", "analytic"]),
        (dict(m_eff=3.4333, method="ode"), ["--m-eff", "3.4333", "--method", "ode"]),
        (
            dict(gamma=1.0, m_r=10.0, m_e=0.5, method="ode", formulation="displacement", rtol=1e-8),
            ["--gamma", "1.0", "--m-r", "10.0", "--m-e", "0.5", "--method", "ode", "--formulation",
             "displacement", "--rtol", "1e-08"],
        ),
        (dict(m_eff=2.0, method="ode", formulation="indentation"),
         ["--m-eff", "2.0", "--method", "ode", "--formulation", "indentation"]),
        (dict(m_eff=2.0, method="ode", dome_radius=0.05),
         ["--m-eff", "2.0", "--method", "ode", "--dome-radius", "0.05"]),
    ],
)
@pytest.mark.parametrize("n", [1.0, 2.0])
def test_impact_every_input_and_method_equals_the_cli(cli, kwargs, flags, n):
    if kwargs.get("method") == "analytic" and n != 1.0:
        with pytest.raises(ValueError):
            flexrig.impact(4.0, k_delta=1e8, k_c=1e8, n=n, v0=2.0, **kwargs)
        return
    r = flexrig.impact(4.0, k_delta=1e8, k_c=1e8, n=n, v0=2.0, **kwargs)
    expected = cli.json("impact", "--m-h", "4.0", "--k-delta", "1e8", "--k-c", "1e8", "--n", repr(n), "--v0", "2.0", *flags)
    assert isinstance(r, flexrig.ImpactReport)
    for key, value in expected.items():
        same(getattr(r, key), value, key)
    for key in flexrig.IMPACT_FIELDS:
        if key not in expected:
            assert getattr(r, key) is None, key
    if "rhs_evals" in expected:
        assert isinstance(r.rhs_evals, int) and r.rhs_evals > 0


def test_impact_arrays_hold_the_scalar_answers_and_name_the_bad_set():
    v0 = np.array([[0.5, 1.0], [2.0, 3.0]])
    r = flexrig.impact(4.0, gamma=2 / 3, m_r=10.0, m_e=0.1, k_delta=1e8, k_c=1e8, n=1.0, v0=v0, method="ode")
    assert r.f_max_n.shape == (2, 2) and r.steps.dtype == np.int64 and r.formulation.shape == (2, 2)
    for i in range(2):
        for j in range(2):
            one = flexrig.impact(4.0, gamma=2 / 3, m_r=10.0, m_e=0.1, k_delta=1e8, k_c=1e8, n=1.0, v0=v0[i, j], method="ode")
            assert r.f_max_n[i, j] == one.f_max_n and r.steps[i, j] == one.steps
    # the ode peak against the n = 1 closed form f = v0 sqrt(k_o mu) (Eq. 13)
    mu = 4.0 * (0.1 + 10.0 * 2 / 9) / (4.0 + 0.1 + 10.0 * 2 / 9)
    np.testing.assert_allclose(r.f_max_n, v0 * np.sqrt(0.5e8 * mu), rtol=1e-7)
    with pytest.raises(ValueError, match=r"gamma\[1\]") as info:
        flexrig.impact(4.0, gamma=[0.5, 1.5], m_r=10.0, m_e=0.1, k_delta=1e8, k_c=1e8, n=1.0, v0=2.0)
    assert info.value.field == "gamma[1]"
    with pytest.raises(ValueError, match="rtol") as info:
        flexrig.impact(4.0, 3.0, 1e8, 1e8, 1.0, 2.0, method="ode", rtol=1.0)
    assert info.value.field == "rtol"
    with pytest.raises(ValueError, match="method"):
        flexrig.impact(4.0, 3.0, 1e8, 1e8, 1.0, 2.0, method="rk4")
    with pytest.raises(ValueError, match="m_eff"):
        flexrig.impact(4.0, 3.0, 1e8, 1e8, 1.0, 2.0, gamma=0.5, m_r=1.0, m_e=0.1)


def test_run_out_writes_the_log_and_layout_of_the_cli(cli, tmp_path):
    scene = scene_path("cl_aluminium")
    (tmp_path / "py").mkdir()
    (tmp_path / "cli").mkdir()
    r = flexrig.run(scene, out=tmp_path / "py" / "run.mcap", robot__payload_kg=0.3)
    expected = cli.json("run", scene, "--out", tmp_path / "cli" / "run.mcap", "--set", "robot.payload_kg=0.3")
    same(r.summary, expected, "summary")
    for name in ("run.mcap", "run.layout.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    # traces as without the log
    plain = flexrig.run(scene, robot__payload_kg=0.3)
    assert np.array_equal(plain.force_n, r.force_n)
    # not replaced without force, as the CLI
    with pytest.raises(ValueError, match="force") as info:
        flexrig.run(scene, out=tmp_path / "py" / "run.mcap")
    assert info.value.field == "out"
    flexrig.run(scene, out=tmp_path / "py" / "run.mcap", force=True, log_every_step=True, deformation_scale=1.0)
    assert (tmp_path / "py" / "run.mcap").stat().st_size > (tmp_path / "cli" / "run.mcap").stat().st_size
    with pytest.raises(ValueError, match="deformation_scale"):
        flexrig.run(scene, out=tmp_path / "x.mcap", deformation_scale=-1.0)
    with pytest.raises(ValueError, match="log_every_step"):
        flexrig.run(scene, log_every_step=True)


def test_fit_equals_the_cli(cli, tmp_path):
    # f = k δ^n sampled with a deterministic ripple: the fit is not exact, its numbers are the CLI's
    delta = np.linspace(1e-4, 2e-3, 40)
    force = 7.3e7 * delta**1.9 * (1 + 0.01 * np.sin(np.arange(40)))
    path = tmp_path / "compression.csv"
    path.write_text("indentation_m,force_n\n" + "".join(f"{float(d)!r},{float(f)!r}\n" for d, f in zip(delta, force)))
    r = flexrig.fit(path)
    same(r.data, cli.json("fit", path))
    assert abs(r.n - 1.9) < 0.02 and r.points == 40


BEAM = dict(length=0.3, youngs=7e10, density=2700.0, width=0.02, thickness=0.002, elements=4)
BEAM_FLAGS = ["--length", "0.3", "--youngs", "7e10", "--density", "2700", "--width", "0.02", "--thickness", "0.002",
              "--elements", "4"]


def test_beam_modal_and_static_equal_the_cli(cli):
    r = flexrig.beam_modal(**BEAM, tip_mass=0.05, modes=3)
    same(r.data, cli.json("beam", "modal", *BEAM_FLAGS, "--tip-mass", "0.05", "--modes", "3"))
    assert list(r.table["mode"]) == [1, 2, 3] and r.table["mode"].dtype == np.int64
    for model in ("linear", "corotational", "ancf"):
        r = flexrig.beam_static(**BEAM, tip_load=5.0, model=model, root="pinned", k_theta=50.0)
        expected = cli.json("beam", "static", *BEAM_FLAGS, "--tip-load", "5", "--model", model, "--root", "pinned",
                            "--k-theta", "50")
        same_naming_keywords(r.data, expected)
        # adaptive load steps from the whole load: the same numbers as the CLI's
        r = flexrig.beam_static(**BEAM, tip_load=5.0, model=model, load_steps=1, adaptive_steps=True)
        same_naming_keywords(r.data, cli.json("beam", "static", *BEAM_FLAGS, "--tip-load", "5", "--model", model,
                                              "--load-steps", "1", "--adaptive-steps"))
    with pytest.raises(ValueError) as info:
        flexrig.beam_static(**BEAM, tip_load=5.0, model="ancf", adaptive_steps="yes")
    assert info.value.field == "adaptive_steps"
    # the scene's link, a flag overriding it, the yield strength and the warnings
    r = flexrig.beam_static(scene="cl_aluminium", tip_load=2.0, elements=8, yield_strength=1e6)
    expected = cli.json("beam", "static", "--scene", "cl_aluminium", "--tip-load", "2", "--elements", "8",
                        "--yield-strength", "1e6")
    same(without(r.data, "warnings"), without(expected, "warnings"))
    assert r.data["scene"] == "bundled cl_aluminium"
    # the warnings name the keyword arguments where the CLI names its flags
    assert [w["field"] for w in r.data["warnings"]] == ["model", "yield_strength"]
    same_naming_keywords(r.data, expected)
    r = flexrig.beam_modal(scene="cl_aluminium", thickness=0.003, modes=2)
    same_naming_keywords(r.data, cli.json("beam", "modal", "--scene", "cl_aluminium", "--thickness", "0.003",
                                          "--modes", "2"))
    # a static solve needs no density; a modal one does
    nodensity = {k: v for k, v in BEAM.items() if k != "density"}
    r = flexrig.beam_static(**nodensity, tip_load=5.0)
    same_naming_keywords(r.data, cli.json("beam", "static", *BEAM_FLAGS[:4], *BEAM_FLAGS[6:], "--tip-load", "5"))
    with pytest.raises(ValueError) as info:
        flexrig.beam_modal(**nodensity)
    assert info.value.field == "density"
    with pytest.raises(ValueError, match="root") as info:
        flexrig.beam_modal(**BEAM, root="hinged")
    assert info.value.field == "root" and "--" not in str(info.value)
    with pytest.raises(ValueError) as info:
        flexrig.beam_static(**dict(BEAM, length=-1.0), tip_load=1.0)
    assert info.value.field == "length"


def test_prb_equals_the_cli_and_returns_its_figure(cli, tmp_path):
    out = tmp_path / "prb"
    r = flexrig.prb(out=out, elements=4, model="corotational", criterion="length")
    same(r.data, cli.json("prb", "--elements", "4", "--model", "corotational", "--criterion", "length", "--out", out))
    assert r.figures["prb.svg"].startswith("<svg") or "<svg" in r.figures["prb.svg"][:200]
    # without out: the figure as text, nothing left behind
    r2 = flexrig.prb(elements=4, model="corotational", criterion="length")
    assert r2.gamma == r.gamma and r2.files == [] and "prb.svg" in r2.figures
    with pytest.raises(ValueError, match="criterion"):
        flexrig.prb(elements=4, criterion="angle")


def test_eta_equals_the_cli(cli, tmp_path):
    out = tmp_path / "eta"
    r = flexrig.eta(out=out, zone_elements=0.5, tol=0.1)
    same(r.data, cli.json("eta", "--zone-elements", "0.5", "--tol", "0.1", "--out", out))
    assert len(r.table) == len(r.rows) == 16 and {"eta.svg", "eta_fig6.svg"} <= set(r.figures)
    with pytest.raises(ValueError, match="c_max") as info:
        flexrig.eta(damping="hunt-crossley", restitution=0.5, c_max=10.0)
    assert info.value.field == "c_max"
    with pytest.raises(ValueError, match="elements") as info:
        flexrig.eta(elements=8)
    assert info.value.field == "elements" and "only with method alpha" in str(info.value)


def test_eta_map_and_eta_rotor_equal_the_cli(cli, tmp_path):
    out = tmp_path / "map"
    r = flexrig.eta_map(out=out, m_h=4.0, points=2, damping="hunt-crossley", restitution=0.8)
    expected = cli.json("eta-map", "--m-h", "4", "--points", "2", "--damping", "hunt-crossley", "--restitution", "0.8",
                        "--out", out)
    same(without(r.data, "seconds"), without(expected, "seconds"))
    assert r.table["points"].dtype == np.int64
    r = flexrig.eta_map(out=out, m_h=[4.0], points=2, mass_ratio=(1e-2, 1.0), damping="hunt-crossley", restitution=0.8)
    expected = cli.json("eta-map", "--m-h", "4", "--points", "2", "--mass-ratio", "0.01:1.0", "--damping",
                        "hunt-crossley", "--restitution", "0.8", "--out", out)
    same(without(r.data, "seconds"), without(expected, "seconds"))
    out = tmp_path / "rotor"
    r = flexrig.eta_rotor(out=out, points=2, n=2.0)
    same(r.data, cli.json("eta-rotor", "--points", "2", "--n", "2", "--out", out))
    assert "eta_rotor.svg" in r.figures
    with pytest.raises(ValueError, match="points") as info:
        flexrig.eta_rotor(points=1)
    assert info.value.field == "points"


# ---- your own robot: the design and the cases of the Fig. 6 studies -------------------------

#: A design and cases other than the paper's, as keyword arguments and as flags.
DESIGN = dict(m_r=3.0, k_c=5e7, v0=1.5)
DESIGN_FLAGS = ["--m-r", "3", "--k-c", "5e7", "--v0", "1.5"]
CASES = dict(m_h=[4.0, 70.0], k_delta=1e5, m_e=[0.5])
CASES_FLAGS = ["--m-h", "4,70", "--k-delta", "1e5", "--m-e", "0.5"]


def test_fig6_for_another_design_equals_the_cli(cli, tmp_path):
    df = flexrig.fig6(points=11, **DESIGN, **CASES, out=tmp_path / "py")
    expected = cli.json("fig6", "--points", "11", *DESIGN_FLAGS, *CASES_FLAGS, "--out", tmp_path / "cli")
    assert expected["design"] == {"m_r": 3.0, "k_c": 5e7, "v0": 1.5} == df.attrs["design"]
    curves = list(df.groupby(["m_h_kg", "k_delta_n_per_m", "m_e_kg", "n"], sort=False))
    assert len(curves) == len(expected["cases"]) == 2 * 1 * 1 * 2
    for (key, curve), case in zip(curves, expected["cases"]):
        assert key == (case["m_h"], case["k_delta"], case["m_e"], case["n"])
        same(curve["gamma"].tolist(), case["gamma"])
        same(curve["eta"].tolist(), case["eta"])
        assert set(curve["eta_at_2_3"]) == {case["eta_at_2_3"]}
    for name in ("fig6.csv", "fig6.svg"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    # not the paper's numbers: the design changed the curves
    paper = flexrig.fig6(points=11, m_h=[4.0, 70.0], k_delta=1e5, m_e=0.5)
    assert not np.array_equal(paper["eta"].to_numpy(), df["eta"].to_numpy())


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: flexrig.fig6(m_r=-1.0), "m_r"),
        (lambda: flexrig.fig6(k_c=0.0), "k_c"),
        (lambda: flexrig.fig6(v0=float("nan")), "v0"),
        (lambda: flexrig.fig6(k_delta=[1e8, 1e8]), "k_delta"),
        (lambda: flexrig.fig6(m_h=[1.0, 2.0, 3.0, 4.0, 5.0]), "m_h"),
        (lambda: flexrig.fig6(m_e="heavy"), "m_e"),
        (lambda: flexrig.eta(m_r=1e5), "m_r"),
        (lambda: flexrig.eta(m_e=[0.0]), "m_e"),
        (lambda: flexrig.eta_map(v0=1e3, points=2), "v0"),
        (lambda: flexrig.eta_map(length=1e6, points=2), "length"),
        (lambda: flexrig.eta_rotor(k_c=1e14, points=2), "k_c"),
        (lambda: flexrig.eta_rotor(k_delta=[], points=2), "k_delta"),
    ],
)
def test_a_bad_design_or_case_names_the_keyword(call, field):
    with pytest.raises(flexrig.InputError) as info:
        call()
    assert info.value.field == field and field in str(info.value) and "--" not in str(info.value)


def test_eta_for_another_design_equals_the_cli(cli, tmp_path):
    out = tmp_path / "eta"
    r = flexrig.eta(out=out, zone_elements=0.5, tol=0.1, length=0.8, **DESIGN, **CASES)
    expected = cli.json("eta", "--zone-elements", "0.5", "--tol", "0.1", "--length", "0.8", *DESIGN_FLAGS,
                        *CASES_FLAGS, "--out", out)
    same(r.data, expected)
    assert r.settings["design"] == {"m_r": 3.0, "k_c": 5e7, "v0": 1.5} and r.settings["length"] == 0.8
    assert sorted({row["case"]["m_h"] for row in r.rows}) == [4.0, 70.0] and len(r.rows) == 4


def test_eta_map_and_eta_rotor_for_another_design_equal_the_cli(cli, tmp_path):
    out = tmp_path / "map"
    r = flexrig.eta_map(out=out, m_h=70.0, points=2, length=0.8, **DESIGN)
    expected = cli.json("eta-map", "--m-h", "70", "--points", "2", "--length", "0.8", *DESIGN_FLAGS, "--out", out)
    same(without(r.data, "seconds"), without(expected, "seconds"))
    assert r.settings["design"]["m_r"] == 3.0
    out = tmp_path / "rotor"
    r = flexrig.eta_rotor(out=out, points=2, n=2.0, length=0.8, **DESIGN, **CASES)
    expected = cli.json("eta-rotor", "--points", "2", "--n", "2", "--length", "0.8", *DESIGN_FLAGS, *CASES_FLAGS,
                        "--out", out)
    same(r.data, expected)
    assert {p["case"]["m_h"] for p in r.points} == {4.0, 70.0}


def test_payload_takes_a_scene_file_as_the_cli(cli, tmp_path):
    scene = tmp_path / "my_robot.toml"
    flexrig.write_scene("cl_light_load", scene)
    scene.write_text(scene.read_text().replace("arm_length_m = 0.30", "arm_length_m = 0.32"))
    r = flexrig.payload(out=tmp_path / "py", scene=scene, points=2)
    expected = cli.json("payload", "--scene", scene, "--points", "2", "--out", tmp_path / "cli")
    same(without(r.data, "csv", "logs", "figures"), without(expected, "csv", "logs", "figures"))
    bundled = flexrig.payload(points=2)
    assert r.rows != bundled.rows  # the file's longer arm ran


def test_payload_and_experiment_equal_the_cli(cli, tmp_path):
    out = tmp_path / "payload"
    r = flexrig.payload(out=out, points=2)
    same(r.data, cli.json("payload", "--points", "2", "--out", out))
    assert {"payload_kg", "cj_peak_n", "cl_peak_n", "ratio"} <= set(r.table.columns)
    with pytest.raises(ValueError, match=r"payloads = -1:1") as info:
        flexrig.payload(payloads="-1:1", points=2)
    assert info.value.field == "payloads"
    assert flexrig.payload(out=tmp_path / "p2", payloads="0.01:1:2:log").data["rows"] == r.data["rows"]
    out = tmp_path / "experiment"
    r = flexrig.experiment(out=out, repeats=1, seed=3, **{"operator.start.release_angle_deg": 30.0})
    expected = cli.json("experiment", "--repeats", "1", "--seed", "3", "--set", "operator.start.release_angle_deg=30.0",
                        "--out", out)
    same(r.data, expected)
    assert len(r.table) == len(r.runs) and any(f.endswith(".mcap") for f in r.files)
    with pytest.raises(ValueError, match="repeats") as info:
        flexrig.experiment(repeats=0)
    assert info.value.field == "repeats"


def test_bench_equals_the_cli_but_for_the_timings(cli, tmp_path):
    """The work–precision rows: the same points and errors bit for bit; the run times (and the
    peer's run-time ratio) are this machine's at that moment, so they are only checked to be
    run times."""
    r = flexrig.bench(quick=True, out=tmp_path / "py")
    expected = cli.json("bench", "--quick", "--out", tmp_path / "cli")
    timings = ("seconds", "scipy_dop853_over_flexrig_at_1e_9", "plots")
    same(without(r.data, *timings), without(expected, *timings))
    assert [row["seconds"] > 0 for row in r.rows] == [True] * len(expected["rows"])
    assert list(r.table.columns[:5]) == ["model", "method", "setting", "error", "seconds"]
    assert r.table["evaluations"].dtype == "Int64"
    assert {"bench_lumped.svg", "bench_beam.svg", "bench_rig.svg"} <= set(r.figures)
    # the errors are against each study's reference: the converged rows are small
    assert (r.table["error"] >= 0).all() and r.table["error"].min() < 1e-6


def test_scenes_and_write_scene_equal_the_cli(cli, tmp_path):
    listed = cli.json("scenes")["scenes"]
    assert [(s["name"], s["summary"]) for s in listed] == [tuple(d) for d in flexrig.scene_descriptions()]
    assert [s["name"] for s in listed] == list(flexrig.bundled_scenes())
    cli("scenes", "--write", "cl_iron", "--out", tmp_path / "cli.toml")
    flexrig.write_scene("cl_iron", tmp_path / "py.toml")
    assert (tmp_path / "py.toml").read_bytes() == (tmp_path / "cli.toml").read_bytes()
    with pytest.raises(flexrig.InputError):
        flexrig.write_scene("cl_iron", tmp_path / "py.toml")


def test_validate_equals_the_cli(cli, tmp_path):
    out = tmp_path / "validate"
    r = flexrig.validate(quick=True, out=out)
    expected = json.loads(cli("validate", "--quick", "--out", out, "--json", check=False).stdout)
    same(r.data, expected)
    assert r.table["pass"].all() and (out / "validation.md").is_file()


def test_every_public_name_is_documented_in_docs_python_md():
    text = (ROOT / "docs" / "python.md").read_text(encoding="utf-8")
    undocumented = [name for name in flexrig.__all__ if f"flexrig.{name}" not in text]
    assert not undocumented, f"docs/python.md does not describe: {', '.join(undocumented)}"
    # and every twin the table names exists
    for name in re.findall(r"`flexrig\.([a-z_]+)\(", text):
        assert name in flexrig.__all__, name


def _documented_signatures(text):
    """{name: (parameter names, whether the entry lists them all)} of each `flexrig.name(...)`
    entry in bold (the reference's entries), parameters split at the top-level commas."""
    entries = {}
    for name, inside in re.findall(r"\*\*`flexrig\.([a-z_0-9]+)\((.*?)\)`", text, re.S):
        items, depth, current = [], 0, ""
        for ch in inside:
            if ch in "([{":
                depth += 1
            elif ch in ")]}":
                depth -= 1
            if ch == "," and depth == 0:
                items.append(current)
                current = ""
            else:
                current += ch
        items.append(current)
        names, complete = [], True
        for item in (i.strip() for i in items):
            if item in ("", "*", "/") or item.startswith("**"):
                continue
            if item.endswith(("...", "…")):
                complete = False
                item = item.rstrip(".…").strip()
                if not item:
                    continue
            names.append(item.split("=")[0].strip())
        entries[name] = (names, complete)
    return entries


def test_the_reference_lists_each_functions_real_arguments():
    """docs/python.md is kept in step with the package: every argument an entry names is an
    argument of the function, and an entry without "…" names all of them."""
    import inspect

    text = (ROOT / "docs" / "python.md").read_text(encoding="utf-8")
    entries = _documented_signatures(text)
    assert {"impact", "eta", "bench", "run", "strike"} <= set(entries), sorted(entries)
    for name, (documented, complete) in entries.items():
        params = [
            p.name for p in inspect.signature(getattr(flexrig, name)).parameters.values()
            if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL)
        ]
        stale = [d for d in documented if d not in params]
        assert not stale, f"docs/python.md: flexrig.{name} has no argument {stale}"
        if complete:
            missing = [p for p in params if p not in documented]
            assert not missing, f"docs/python.md: flexrig.{name}(...) does not list {missing}"


def test_the_fig6_walk_through_runs_in_both_fronts(cli, tmp_path, monkeypatch):
    """docs/cli.md, "Fig. 6 for your robot": each command and its Python twin run as written
    (each in its own directory) and give the same numbers; the quoted link numbers are the
    scene's."""
    import subprocess

    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    section = text[text.index("## Fig. 6 for your robot") :]
    section = section[: section.index("\n## ", 1)]
    blocks = re.findall(r"```(sh|python)\n(.*?)```", section, re.S)
    commands = [b for kind, b in blocks if kind == "sh"]
    codes = [b for kind, b in blocks if kind == "python"]
    assert len(commands) == len(codes) == 3, blocks
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    monkeypatch.chdir(tmp_path / "py")
    namespace: dict = {}
    results = []
    for command, code in zip(commands, codes):
        words = command.split("#")[0].split()
        assert words[0] == "flexrig"
        args = words[1:] + ([] if "--json" in words else ["--json"])
        done = subprocess.run([str(cli.path), *args], capture_output=True, text=True, cwd=tmp_path / "cli")
        assert done.returncode == 0, done.stderr
        exec(code, namespace)
        results.append((json.loads(done.stdout), dict(namespace)))
    # 1. the run and its link numbers as the text quotes them
    expected, ns = results[0]
    run = ns["r"]
    same(run.summary, expected)
    assert f"m_r = {run.m_r_kg:.3f} kg" in section
    assert f"k_δ = 3EI/L³ = {run.k_delta_n_per_m:.1f} N/m" in section
    assert f"m_e = {run.m_e_over_m_r * run.m_r_kg:.3f} kg" in section
    assert f"v0 = {run.impact_velocity_mps:.2f} m/s" in section
    # 2. Fig. 6: the same curves and files
    expected, ns = results[1]
    df = ns["df"]
    curves = list(df.groupby(["m_h_kg", "k_delta_n_per_m", "m_e_kg", "n"], sort=False))
    assert len(curves) == len(expected["cases"]) == 16
    for (key, curve), case in zip(curves, expected["cases"]):
        assert key == (case["m_h"], case["k_delta"], case["m_e"], case["n"])
        same(curve["eta"].tolist(), case["eta"])
    for name in ("fig6.csv", "fig6.svg"):
        assert (tmp_path / "py" / "my_fig6" / name).read_bytes() == (tmp_path / "cli" / "my_fig6" / name).read_bytes()
    # 3. η at FE fidelity: the same report (paths aside) and table
    expected, ns = results[2]
    report = ns["r"]
    same(without(report.data, "csv", "svg", "fig6_svg"), without(expected, "csv", "svg", "fig6_svg"))
    assert (tmp_path / "py" / "my_eta" / "eta.csv").read_bytes() == (tmp_path / "cli" / "my_eta" / "eta.csv").read_bytes()
