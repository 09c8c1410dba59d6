"""Files of the hostile corpus (``tests/cli/hostile_corpus.py``): users' problem files, careless and
broken, and scenes with ``[response]`` and ``[sweep]`` sections.

Each problem file is a text written into the invocation's own folder before it runs; the corpus
says what each must give (:data:`PROBLEM_FILES`: the class of its outcome under ``solve``).
"""

from __future__ import annotations

HEADER = """
import sympy as sp

from perturb import EPS, Excitation, QuasilinearSystem
from problems.base import ParameterSpec, Problem, positive

X, XDOT, A, K, MU = sp.symbols("x xdot amplitude k mu")
THETA, SIGMA, F, ZETA = sp.symbols("theta sigma F zeta")
"""

_GOOD = """
class Good(Problem):
    name = "good"
    summary = "x'' + x = -eps x^3 from x(0) = amplitude"
    parameter_specs = (
        ParameterSpec("eps", 0.1, "small parameter"),
        ParameterSpec("amplitude", 1.0, "x(0)", positive),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem([X], [XDOT], [1], [-EPS * X**3], parameters=[A])

    def method_options(self):
        return {"amplitudes": {"x": A}}
"""

#: A forced, damped oscillator of the user's own (sigma a parameter, no DrivenProblem base).
_DRIVEN = """
class Driven(Problem):
    name = "my-driven"
    summary = "x'' + x = eps(-2 zeta x' - x^3 + F cos theta), theta = (1 + eps sigma) t"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small parameter", positive),
        ParameterSpec("zeta", 0.1, "damping"),
        ParameterSpec("F", 1.0, "forcing", positive),
        ParameterSpec("sigma", 0.0, "detuning"),
    )

    @classmethod
    def build_system(cls):
        return QuasilinearSystem(
            [X], [XDOT], [1], [EPS * (-2 * ZETA * XDOT - X**3 + F * sp.cos(THETA))],
            parameters=[ZETA, F, SIGMA],
            excitation=Excitation(phase=THETA, ratio=1, detuning=SIGMA),
        )
"""

#: An undamped linear oscillator forced at resonance: no bounded response (no root).
_UNDAMPED_LINEAR = (
    _DRIVEN.replace("- X**3 ", "").replace('"damping"', '"damping", ')
    + """
class Undamped(Driven):
    name = "undamped-linear"
    parameter_specs = (
        ParameterSpec("eps", 0.05, "small parameter", positive),
        ParameterSpec("zeta", 0.0, "damping"),
        ParameterSpec("F", 1.0, "forcing", positive),
        ParameterSpec("sigma", 0.0, "detuning"),
    )
"""
)


def _variant(body: str) -> str:
    return HEADER + body


#: name -> (file text, class of ``perturb solve FILE`` : "ok", "usage" or "failed").
PROBLEM_FILES: dict[str, tuple[str, str]] = {
    "good.py": (_variant(_GOOD), "ok"),
    "driven.py": (_variant(_DRIVEN), "ok"),
    # a symbolic parameter of the system that no ParameterSpec gives a value
    "symbolic_k.py": (
        _variant(_GOOD.replace("-EPS * X**3", "-EPS * K * X**3 + EPS * MU * XDOT")),
        "usage",
    ),
    # a right-hand side that makes the engine recurse without end
    "recursive.py": (
        _variant(
            "\nclass Deep(sp.Function):\n    def _eval_subs(self, old, new):\n"
            "        return self.subs(old, new)\n\n"
            "    def _eval_expand_basic(self, **hints):\n        return sp.expand(self)\n"
            + _GOOD.replace("-EPS * X**3", "-EPS * Deep(X)")
        ),
        "usage",
    ),
    # an unknown function of the state: not a polynomial nor a known function
    "unknown_function.py": (
        _variant(_GOOD.replace("-EPS * X**3", "-EPS * sp.Function('g')(X)")),
        "usage",
    ),
    # a pole on the generating orbit: 1/x
    "pole.py": (_variant(_GOOD.replace("-EPS * X**3", "-EPS / X")), "usage"),
    # parameters of the system that no ParameterSpec gives a value
    "no_values.py": (
        _variant(
            _GOOD.replace("-EPS * X**3", "-EPS * K * X**3 + EPS * MU * XDOT").replace(
                "parameters=[A]", "parameters=[A, K, MU]"
            )
        ),
        "usage",
    ),
    # a function of the state with no parameter in it: the numeric quadrature expands it
    "sine.py": (
        _variant(
            _GOOD.replace("-EPS * X**3", "-EPS * sp.sin(X)").replace(
                'return {"amplitudes": {"x": A}}', 'return {"amplitudes": {"x": 1}}'
            )
        ),
        "ok",
    ),
    # the rhs is a list in a list
    "nested_rhs.py": (_variant(_GOOD.replace("[-EPS * X**3]", "[[-EPS * X**3]]")), "usage"),
    # the rhs is a string
    "string_rhs.py": (_variant(_GOOD.replace("[-EPS * X**3]", '["-eps*x**3"]')), "any"),
    # a frequency of zero and a negative one
    "zero_frequency.py": (_variant(_GOOD.replace("[X], [XDOT], [1]", "[X], [XDOT], [0]")), "usage"),
    "negative_frequency.py": (
        _variant(_GOOD.replace("[X], [XDOT], [1]", "[X], [XDOT], [-1]")),
        "usage",
    ),
    "symbolic_frequency.py": (
        _variant(_GOOD.replace("[X], [XDOT], [1]", "[X], [XDOT], [K]")),
        "usage",
    ),
    # the import exits: 0, 3, a message
    "exit0.py": ("import sys\nsys.exit(0)\n", "usage"),
    "exit3.py": ("import sys\nsys.exit(3)\n", "usage"),
    "exit_message.py": ("raise SystemExit('bye')\n", "usage"),
    # the import raises: an error, Ctrl-C, a recursion, out of memory
    "raises.py": ("raise RuntimeError('the file is broken')\n", "usage"),
    "keyboard.py": ("raise KeyboardInterrupt\n", "usage"),
    "recursion_at_import.py": ("def f():\n    return f()\n\nf()\n", "usage"),
    "memory.py": ("raise MemoryError\n", "usage"),
    "syntax.py": ("class Broken(:\n", "usage"),
    "empty.py": ("", "usage"),
    "binary.py": ("\x00\x01\x02", "usage"),
    # a class that is broken in use rather than at import
    "build_raises.py": (
        _variant(
            _GOOD.replace(
                "return QuasilinearSystem(",
                "raise ValueError('no system')\n        return QuasilinearSystem(",
            )
        ),
        "usage",
    ),
    "build_returns_none.py": (
        _variant(_GOOD.replace("return QuasilinearSystem(", "return None and QuasilinearSystem(")),
        "usage",
    ),
    "options_list.py": (
        _variant(_GOOD.replace('return {"amplitudes": {"x": A}}', 'return [("amplitudes", A)]')),
        "usage",
    ),
    "options_bad_amplitude.py": (
        _variant(_GOOD.replace('{"x": A}', '{"x": [A, A]}')),
        "usage",
    ),
    "options_unknown_key.py": (
        _variant(_GOOD.replace('"amplitudes"', '"amplitude_of"')),
        "usage",
    ),
    "default_invalid.py": (
        _variant(
            _GOOD.replace('ParameterSpec("amplitude", 1.0', 'ParameterSpec("amplitude", -1.0')
        ),
        "usage",
    ),
    "specs_not_tuple.py": (
        _variant(_GOOD.replace("parameter_specs = (", "parameter_specs = 3\n    _unused = (")),
        "usage",
    ),
    "linear.py": (_variant(_GOOD.replace("-EPS * X**3", "-EPS * X")), "ok"),
    # a user's own driven problem, carelessly excited
    "ratio_list.py": (_variant(_DRIVEN.replace("ratio=1,", "ratio=[1],")), "usage"),
    "ratio_zero.py": (_variant(_DRIVEN.replace("ratio=1,", "ratio=0,")), "usage"),
    "ratio_float.py": (_variant(_DRIVEN.replace("ratio=1,", "ratio=1.5,")), "any"),
    "detuning_number.py": (_variant(_DRIVEN.replace("detuning=SIGMA", "detuning=0")), "any"),
    "phase_is_state.py": (_variant(_DRIVEN.replace("phase=THETA", "phase=X")), "usage"),
    "tan_forcing.py": (_variant(_DRIVEN.replace("sp.cos(THETA)", "sp.tan(THETA)")), "usage"),
    "zero_rhs.py": (_variant(_GOOD.replace("-EPS * X**3", "0 * EPS")), "ok"),
    "undamped_linear.py:Undamped": (_variant(_UNDAMPED_LINEAR), "failed"),
    "two_classes.py": (_variant(_GOOD + _GOOD.replace("class Good", "class Other")), "usage"),
}

#: The good driven file's name (for response/sweep/report cases).
DRIVEN_FILE = "driven.py"
GOOD_FILE = "good.py"


SCENE_HEAD = """[problem]
name = "{problem}"
[parameters]
{parameters}
[solve]
order = {order}
"""


def scene(problem="forced-duffing", parameters="eps = 0.05", order=1, **sections) -> str:
    """A scene's TOML: the head, then each ``section=body`` as ``[section]\\nbody``."""
    text = SCENE_HEAD.format(problem=problem, parameters=parameters, order=order)
    for name, body in sections.items():
        text += f"[{name}]\n{body}\n"
    return text
