"""Hostile arguments of the safety, safety-map and spin-up twins (issue 35, round four): each is
refused with a ValueError (flexrig.InputError) naming the keyword argument, never a JSON parser's
words, an OverflowError, a MemoryError or a silently truncated number."""

import math

import pytest

import flexrig


@pytest.mark.parametrize("name", ["m_eff", "speed", "k_delta", "payload", "length"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_safety_non_finite_numbers_name_the_argument(name, value):
    kwargs = dict(region="chest", m_eff=3.0)
    kwargs[name] = value
    with pytest.raises(ValueError) as e:
        flexrig.safety(**kwargs)
    assert e.value.field == name, str(e.value)
    assert "line 1 column" not in str(e.value)


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(region=math.nan, m_eff=3.0), "region"),
        (dict(region="chest", m_eff=3.0, method=math.nan), "method"),
        (dict(region="chest", m_eff=3.0, method=["standard", math.nan]), "method"),
        (dict(region="chest", m_eff=3.0, method="standard,"), "method"),
    ],
)
def test_safety_words_that_are_not_words_name_the_argument(kwargs, field):
    with pytest.raises(ValueError) as e:
        flexrig.safety(**kwargs)
    assert e.value.field == field, str(e.value)
    assert "line 1 column" not in str(e.value)


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(region="chest", x=("m-e", [0.1, math.nan])), "x"),
        (dict(region="chest", y=("k-delta", [math.inf, 1e4])), "y"),
        (dict(region="chest", m_r=math.nan), "m_r"),
        (dict(region=math.nan), "region"),
        (dict(region="chest", method=math.nan), "method"),
    ],
)
def test_safety_map_non_finite_axes_and_numbers_name_the_argument(kwargs, field):
    with pytest.raises(ValueError) as e:
        flexrig.safety_map(**kwargs)
    assert e.value.field == field, str(e.value)
    assert "line 1 column" not in str(e.value)


def test_a_body_model_read_is_bounded_as_on_the_command_line():
    with pytest.raises(ValueError) as e:
        flexrig.safety("chest", m_eff=3.0, body_model="/dev/zero")
    assert e.value.field == "body_model"
    assert "1048576" in str(e.value)


def test_a_body_model_with_a_repeated_area_names_body_model(tmp_path):
    from pathlib import Path

    bundled = Path(__file__).resolve().parents[3] / "assets" / "safety" / "iso_ts_15066_2016.toml"
    text = bundled.read_text(encoding="utf-8").replace('name = "Pectoral muscle"', 'name = "sternum"')
    path = tmp_path / "dup.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ValueError) as e:
        flexrig.safety("chest", m_eff=3.0, body_model=path)
    assert e.value.field == "body_model"
    assert '"sternum"' in str(e.value) and "line " in str(e.value)


@pytest.mark.parametrize("elements", [1.9, -1, 2**70, "16", True])
def test_spin_up_elements_must_be_a_whole_number(elements):
    with pytest.raises(ValueError) as e:
        flexrig.spin_up(elements=elements)
    assert e.value.field == "elements", str(e.value)


def test_spin_up_at_zero_speed_is_refused():
    with pytest.raises(ValueError) as e:
        flexrig.spin_up(omega_s=0.0)
    assert "omega_s" in str(e.value)
