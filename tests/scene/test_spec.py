"""The scene parser (issue 13 item 1): every class of bad input is one clean SceneError line naming
the file (and the line where it can be found), the value and the fix, with the closest known name;
fuzzed with hypothesis, it raises nothing else."""

from __future__ import annotations

import string

import pytest
from hypothesis import given
from hypothesis import strategies as st

from perturb.errors import PerturbError, SceneError
from perturb.scene import PLOT_NAMES, Outputs, check_parameter_names, parse_scene, read_scene

MINIMAL = '[problem]\nname = "duffing"\n'


def _error(text: str) -> str:
    with pytest.raises(SceneError) as info:
        parse_scene(text, "scene.toml")
    message = str(info.value)
    assert "\n" not in message and message.startswith("scene.toml: ")
    return message


def test_scene_error_is_a_value_error_of_perturb():
    assert issubclass(SceneError, PerturbError) and issubclass(SceneError, ValueError)


def test_minimal_scene_asks_for_nothing():
    scene = parse_scene(MINIMAL)
    assert scene.problem == "duffing" and scene.parameters == {}
    assert scene.outputs == Outputs()
    assert not (scene.outputs.needs_validation or scene.outputs.needs_euler)
    assert not (scene.outputs.needs_state or scene.outputs.needs_work_precision)


def test_full_scene_is_read():
    text = (
        MINIMAL + "family = 'main'\n[parameters]\neps = 0.05\namplitude = 2\n"
        "[solve]\norder = 2\nperiods = 4.5\nsamples = 50\nintegrator = 'rk45'\ntol = 0.01\n"
        "[outputs]\ntable = true\neuler = false\nvalidation = true\nwork_precision = true\n"
        "latex = true\nplots = ['phase', 'convergence']\nformats = ['png', 'svg']\n"
        "[work_precision]\nperiods = 2\norders = 3\nrepeat = 2\n"
    )
    scene = parse_scene(text)
    assert (scene.family, scene.order, scene.periods, scene.samples) == ("main", 2, 4.5, 50)
    assert scene.parameters == {"eps": 0.05, "amplitude": 2.0}
    assert (scene.integrator, scene.tol) == ("rk45", 0.01)
    assert scene.outputs.plots == ("phase", "convergence")
    assert scene.outputs.formats == ("png", "svg")
    assert scene.outputs.needs_validation and scene.outputs.needs_truth_trajectory
    assert (scene.work_precision.periods, scene.work_precision.orders) == (2.0, 3)
    assert scene.text == text


@pytest.mark.parametrize(
    "text, fragments",
    [
        ("[problem\nname = 'x'", ["malformed TOML", "line 1"]),
        (MINIMAL + "[outputz]\ntable = true\n", ["line 3", "[outputz]", "did you mean 'outputs'"]),
        (MINIMAL + "[solve]\norderr = 2\n", ["line 4", "'orderr'", "did you mean 'order'"]),
        (MINIMAL + "[outputs]\nplots = ['phaze']\n", ["'phaze'", "did you mean 'phase'"]),
        (MINIMAL + "[outputs]\nformats = ['jpg']\n", ["'jpg'", "png"]),
        (MINIMAL + "[outputs]\nplots = ['phase', 'phase']\n", ["once"]),
        (MINIMAL + "[outputs]\ntable = 'yes'\n", ["line 4", "table", "true or false"]),
        (MINIMAL + "[outputs]\nplots = 'phase'\n", ["list of names"]),
        (MINIMAL + "[solve]\norder = 1.5\n", ["order", "whole number"]),
        (MINIMAL + "[solve]\norder = 0\n", ["order", "from 1"]),
        (MINIMAL + "[solve]\norder = true\n", ["order", "whole number"]),
        (MINIMAL + "[solve]\nperiods = -1\n", ["periods", "> 0"]),
        (MINIMAL + "[solve]\nperiods = inf\n", ["periods", "finite"]),
        (MINIMAL + "[solve]\nperiods = 1e9\n", ["periods", "at most"]),
        (MINIMAL + "[solve]\nintegrator = 3\n", ["integrator", "string"]),
        (MINIMAL + "[parameters]\neps = 'big'\n", ["eps", "real number"]),
        (MINIMAL + "[parameters]\neps = nan\n", ["eps", "real number"]),
        (MINIMAL + "[work_precision]\nrepeat = 0\n", ["repeat", "whole number"]),
        ("[problem]\nfamily = 'x'\n", ["names no problem", "name ="]),
        ("[outputs]\ntable = true\n", ["names no problem", "[problem]"]),
        ('problem = "duffing"\n', ["[problem] must be a table"]),
        ("name = 'duffing'\n", ["unknown section [name]"]),
    ],
)
def test_bad_scenes_are_one_clear_line(text, fragments):
    message = _error(text)
    for fragment in fragments:
        assert fragment in message, (fragment, message)


def test_unknown_parameter_suggests_the_closest():
    scene = parse_scene(MINIMAL + "[parameters]\nampltude = 2\n", "s.toml")
    with pytest.raises(SceneError, match=r"s.toml: line 4: .*'ampltude'.*did you mean 'amplitude'"):
        check_parameter_names(scene, ["eps", "amplitude"], "duffing")
    check_parameter_names(parse_scene(MINIMAL + "[parameters]\neps = 0.1\n"), ["eps"], "duffing")


def test_read_scene_names_the_file(tmp_path):
    with pytest.raises(SceneError, match="missing.toml: cannot read"):
        read_scene(tmp_path / "missing.toml")
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b"\xff\xfe[problem]")
    with pytest.raises(SceneError, match="not UTF-8"):
        read_scene(binary)
    good = tmp_path / "good.toml"
    good.write_text(MINIMAL, encoding="utf-8")
    assert read_scene(good).source == str(good)


# ---------------------------------------------------------------------------------- fuzz
_KEYS = ["name", "family", "order", "periods", "samples", "integrator", "tol", "table", "euler",
         "validation", "work_precision", "latex", "plots", "formats", "repeat", "orders", "eps",
         "r0", "x"]  # fmt: skip
_SECTIONS = ["problem", "parameters", "solve", "outputs", "work_precision", "plot", "extra"]
_VALUES = st.one_of(
    st.booleans(),
    st.integers(-(10**20), 10**20),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(string.printable, max_size=8),
    st.lists(st.sampled_from([*PLOT_NAMES, "png", "svg", "pdf", "nope"]), max_size=4),
    st.lists(st.integers(), max_size=3),
)


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if value != value:
            return "nan"
        if value in (float("inf"), float("-inf")):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return "[" + ", ".join(_toml_value(v) for v in value) + "]"


@st.composite
def _scene_texts(draw) -> str:
    """Structurally plausible scenes: known and unknown sections, keys and values of every type."""
    lines = []
    for section in draw(st.lists(st.sampled_from(_SECTIONS), max_size=5, unique=True)):
        lines.append(f"[{section}]")
        for key in draw(st.lists(st.sampled_from(_KEYS), max_size=4, unique=True)):
            lines.append(f"{key} = {_toml_value(draw(_VALUES))}")
    return "\n".join(lines) + "\n"


def _parses_cleanly(text: str) -> None:
    try:
        scene = parse_scene(text, "fuzz.toml")
    except SceneError as exc:
        message = str(exc)
        assert message.startswith("fuzz.toml: ") and "\n" not in message
        return
    assert isinstance(scene.problem, str) and scene.periods > 0
    assert scene.order is None or scene.order >= 1  # None: the default order of its kind


@given(_scene_texts())
def test_fuzz_structured_scenes_give_a_scene_or_a_clean_error(text):
    _parses_cleanly(text)


@given(st.text(max_size=200))
def test_fuzz_arbitrary_text_gives_a_scene_or_a_clean_error(text):
    _parses_cleanly(text)


@given(st.text(alphabet="[]=\"\n .=abc\\#{},'0123456789", max_size=120))
def test_fuzz_toml_punctuation_gives_a_scene_or_a_clean_error(text):
    _parses_cleanly(MINIMAL + text)
