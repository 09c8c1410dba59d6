"""The hostile corpus (issue 31): careless and hostile invocations of ``perturb response``,
``perturb sweep``, scenes with ``[response]``/``[sweep]``, users' problem files, and the driven
problems in ``solve``/``validate``/``families`` — each with the folder it runs in, the files a user
keeps there, the class of outcome it must give and a time bound.

Each :class:`Case` runs in a fresh folder holding the user's files (:data:`USER_FILES`, the
problem files of :mod:`tests.cli.hostile_files`, the case's own). What each class must give:

===========  ======================================================================================
class        must give
===========  ======================================================================================
``usage``    exit 2, one ``perturb: error:`` line on stderr (warnings aside), nothing on stdout
``failed``   exit 1 with the reason on stderr (``perturb: failed: ...`` or ``perturb: NAME: ...``)
``refuse``   ``usage`` or ``failed`` (either is honest: the input or the run is refused with a reason)
``ok``       exit 0; JSON output parses; no NaN/inf where a number is promised
``any``      one of the above
===========  ======================================================================================

and, for every class: no traceback, never ``internal error``, never an exit code other than
0/1/2, never "overflowed" for a user's file, nothing a user wrote removed or changed, no file
written outside the case's outputs, and an end within the case's bound (``seconds``). A case may
also name a pattern its output must show (``says``: a flag such as a point beyond the series'
validity).

:func:`corpus` lists every case; ``benchmarks/hostile_cli.py`` runs them all, each in a fresh
process (the figures in ``benchmarks/hostile_cli.md``); ``tests/cli/test_cli_hostile.py`` runs a
sample in the default suite and the whole corpus under ``-m slow``.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import socket
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from tests.cli.hostile_files import DRIVEN_FILE, GOOD_FILE, PROBLEM_FILES, scene

#: Files every case's folder holds before it runs: a user's own, some with the names a report
#: writes (none of them may be removed or changed by any invocation).
USER_FILES = {
    "notes.txt": "my notes: never to be touched\n",
    "data/solution.csv": "t,x\n0,1\n",
}

#: What each class of invocation must give: the exit codes allowed, and in words (the table of the
#: module docstring). Every class must also keep the promises :func:`judge` checks for all.
CLASSES = {
    "usage": ({2}, "exit 2, one 'perturb: error:' line, nothing on stdout"),
    "failed": ({1}, "exit 1 with the reason on stderr"),
    "refuse": ({1, 2}, "exit 1 with a reason or exit 2 with one line"),
    "ok": ({0}, "exit 0, its output sane"),
    "any": ({0, 1, 2}, "any of the above"),
}

#: Bounds (seconds): a refusal before any work; a small computation; a validated one.
QUICK, SMALL, HEAVY = 60.0, 180.0, 400.0


@dataclass(frozen=True)
class Case:
    """One invocation, the folder it runs in and what it must give."""

    surface: str
    argv: tuple
    expect: str
    files: tuple = ()
    outputs: tuple = ()
    seconds: float = QUICK
    says: str = ""
    never: str = ""
    server: str = ""
    twice: bool = False
    label: str = ""
    group: str = ""
    pre: tuple = ()
    ops: tuple = ()

    @property
    def name(self) -> str:
        words = " ".join(repr(a) if not a or " " in a else a for a in self.argv)
        notes = [n for n in (self.label, self.server and f"{self.server} server",
                             self.twice and "twice", (self.says or self.never) and "flagged")
                 if n]  # fmt: skip
        return f"{self.surface}: perturb {words}" + (f" [{', '.join(notes)}]" if notes else "")


def _case(surface, argv, expect, **kw) -> Case:
    return Case(surface, tuple(str(a) for a in argv), expect, **kw)


# ---------------------------------------------------------------------------------- response
RESPONSE = ["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:5"]

#: --sweep texts and their class.
SWEEPS = {
    "Omega=0.9:1.1:5": "ok",
    "Omega=0.9:1.1:2": "ok",
    "Omega=1.0:1.2:3": "ok",
    "Omega": "usage",
    "Omega=": "usage",
    "=0.9:1.1:5": "usage",
    "Omega=0.9:1.1": "usage",
    "Omega=0.9:1.1:5:7": "usage",
    "Omega=a:b:5": "usage",
    "Omega=0.9:1.1:x": "usage",
    "Omega=0.9:1.1:2.5": "usage",
    "Omega=0.9:1.1:1": "usage",
    "Omega=0.9:1.1:0": "usage",
    "Omega=0.9:1.1:-3": "usage",
    "Omega=1.1:0.9:5": "usage",
    "Omega=1:1:5": "usage",
    "Omega=nan:1:5": "usage",
    "Omega=0.9:inf:5": "usage",
    "Omega=-1:1:5": "usage",
    "Omega=0:1:5": "usage",
    "omega=0.9:1.1:5": "usage",
    "bogus=0.9:1.1:5": "usage",
    "Om ega=0.9:1.1:5": "usage",
    "Omega=0.9:1.1:200000": "usage",
    "Omega=0.9:1.1:10000000": "usage",
    "Omega=0.9:1.1:1e7": "usage",
    "Omega=1e-300:1e-299:3": "any",
    "Omega=1e300:1e301:3": "refuse",
    "eps=0.01:0.1:4": "ok",
    "F=0.5:2:4": "ok",
    "zeta=0:0.2:3": "ok",
    "gamma=-1:1:3": "any",
}

VALIDATE_VALUES = {
    "0": "ok",
    "1": "ok",
    "abc": "usage",
    "-1": "usage",
    "2.5": "usage",
    "": "usage",
    "1e9": "usage",
    "1000000000": "usage",
    "100000": "usage",
}

ORDER_VALUES = {
    "2": "ok",
    "0": "usage",
    "-1": "usage",
    "abc": "usage",
    "": "usage",
    "1.5": "usage",
    "13": "usage",
    "12": "usage",
    "1000": "usage",
}

#: --plot paths (the folder holds notes.txt and data/) and their class.
PLOTS = {
    "r.png": "ok",
    "r.svg": "ok",
    "r.pdf": "ok",
    "data/r.png": "ok",
    "": "usage",
    " ": "usage",
    "/proc/nowhere/r.png": "usage",
    "missing/r.png": "usage",
    "r.xyz": "usage",
    "r": "usage",
    "data": "usage",
    ".": "usage",
    "notes.txt": "usage",
}

RESPONSE_SETS = {
    "eps=10": "any",
    "eps=1e308": "refuse",
    "eps=0": "usage",
    "eps=-1": "usage",
    "eps=nan": "usage",
    "eps=inf": "usage",
    "zeta=0": "any",
    "zeta=-1": "usage",
    "F=0": "usage",
    "F=1e308": "refuse",
    "F=1e-300": "any",
    "gamma=0": "ok",
    "gamma=-1": "ok",
    "gamma=1e308": "refuse",
    "Omega=1": "usage",
    "bogus=1": "usage",
    "=1": "usage",
    "eps": "usage",
}

#: Driven problems and a sweep around their resonance (ok) and one far from it.
DRIVEN = {
    "forced-duffing": ("Omega=0.9:1.1:5", "Omega=2.5:3:3"),
    "parametric-duffing": ("Omega=1.9:2.1:5", "Omega=0.5:0.7:3"),
    "superharmonic-duffing": ("Omega=0.32:0.35:4", "Omega=0.9:1.1:5"),
    "autoparametric-absorber": ("Omega=1.9:2.1:4", "Omega=0.5:0.7:3"),
}


def _response_cases() -> list[Case]:
    cases = []
    base = RESPONSE[:2]
    for text, expect in SWEEPS.items():
        cases.append(_case("response", [*base, "--sweep", text], expect, seconds=SMALL))
    for value, expect in VALIDATE_VALUES.items():
        cases.append(_case("response", [*RESPONSE, "--validate", value], expect, seconds=SMALL))
    for value, expect in ORDER_VALUES.items():
        cases.append(_case("response", [*RESPONSE, "--order", value], expect, seconds=SMALL))
    for path, expect in PLOTS.items():
        outputs = (path,) if expect == "ok" else ()
        cases.append(
            _case("response", [*RESPONSE, "--plot", path], expect, outputs=outputs, seconds=SMALL)
        )
    for item, expect in RESPONSE_SETS.items():
        cases.append(_case("response", [*RESPONSE, "--set", item], expect, seconds=SMALL))
    for fmt in ("table", "csv", "json", "latex", "xml", ""):
        expect = "usage" if fmt in ("xml", "") else "ok"
        cases.append(_case("response", [*RESPONSE, "--format", fmt], expect, seconds=SMALL))
    for output, expect in {
        "out.txt": "ok",
        "notes.txt": "usage",
        ".": "usage",
        "data": "usage",
        "/proc/nowhere/out.txt": "usage",
        "": "usage",
    }.items():
        outputs = (output,) if expect == "ok" else ()
        cases.append(
            _case("response", [*RESPONSE, "--output", output], expect, outputs=outputs,
                  seconds=SMALL)
        )  # fmt: skip
    cases.append(
        _case("response", [*RESPONSE, "--output", "notes.txt", "--force"], "ok",
              outputs=("notes.txt",), seconds=SMALL)
    )  # fmt: skip
    cases.append(
        _case("response", [*RESPONSE, "--output", "again.txt"], "ok", outputs=("again.txt",),
              seconds=SMALL, twice=True)
    )  # fmt: skip
    for problem in ("duffing", "van-der-pol", "nope", "", "resonant-chain-3"):
        cases.append(_case("response", ["response", problem, "--sweep", "Omega=0.9:1.1:5"],
                           "usage", seconds=SMALL))  # fmt: skip
    for problem, (near, far) in DRIVEN.items():
        bound = HEAVY if problem == "autoparametric-absorber" else SMALL  # two modes
        cases.append(_case("response", ["response", problem, "--sweep", near], "ok",
                           seconds=bound))  # fmt: skip
        cases.append(_case("response", ["response", problem, "--sweep", far], "any",
                           seconds=bound))  # fmt: skip
        cases.append(_case("response", ["response", problem, "--sweep", near, "--set", "eps=2"],
                           "any", seconds=bound))  # fmt: skip
    # outside the domain of solve (superharmonic at Omega = 1): never a "stable" branch
    cases.append(
        _case("response", ["response", "superharmonic-duffing", "--sweep", "Omega=0.9:1.1:5"],
              "any", says=r"(?i)outside|domain|beyond|valid", seconds=SMALL)
    )  # fmt: skip
    # eps = 10: the amplitudes are not those of the true motion: flagged
    cases.append(
        _case("response", [*RESPONSE, "--set", "eps=10"], "any",
              says=r"(?i)outside|domain|beyond|valid", seconds=SMALL)
    )  # fmt: skip
    # quasi-static forcing of a damped oscillator: never "unstable"
    cases.append(
        _case("response", ["response", "forced-duffing", "--sweep", "Omega=1e-9:1e-3:3"], "any",
              never=r"\bunstable\b", seconds=SMALL)
    )  # fmt: skip
    return cases


# ---------------------------------------------------------------------------------- sweep
SWEEP = ["sweep", "duffing", "--grid", "eps=0.01:0.1:3", "--format", "csv"]

GRIDS = {
    "eps=0.01:0.1:3": "ok",
    "eps=0.01,0.05": "ok",
    "eps=1e-3:1e-1:3:log": "ok",
    "eps": "usage",
    "eps=": "usage",
    "=0.1:0.2:3": "usage",
    "eps=0.1:0.2": "usage",
    "eps=a:b:3": "usage",
    "eps=0.1:0.2:0": "usage",
    "eps=0.1:0.2:-1": "usage",
    "eps=0.1:0.2:x": "usage",
    "eps=0.1:0.1:3": "usage",
    "eps=nan:1:3": "usage",
    "eps=0:inf:3": "usage",
    "eps=-1:1:3:log": "usage",
    "eps=0.1:0.2:3:cubic": "usage",
    "eps=1,1": "usage",
    "eps=,": "usage",
    "Eps=0.1:0.2:3": "usage",
    "e ps=0.1:0.2:3": "usage",
    "bogus=0.1:0.2:3": "usage",
    "eps=0.01:0.1:20000000": "usage",
    "eps=0.01:0.1:1e7": "usage",
    "eps=1e308:1.7e308:3": "any",
    "amplitude=-1:1:3": "any",
    "amplitude=0.5:2:4": "ok",
}


def _sweep_cases() -> list[Case]:
    cases = []
    for grid, expect in GRIDS.items():
        argv = ["sweep", "duffing", "--grid", grid, "--format", "csv"]
        cases.append(_case("sweep", argv, expect, seconds=SMALL))
    two = ["sweep", "duffing", "--grid", "eps=0.01:0.1:100000", "--grid",
           "amplitude=0.5:2:100000"]  # fmt: skip
    cases += [
        _case("sweep", [*two, "--format", "csv"], "usage"),
        _case("sweep", [*two, "--format", "csv", "--yes"], "usage"),
        _case("sweep", [*two, "--format", "json", "--yes"], "usage"),
        _case(
            "sweep",
            [
                *two[:3],
                "eps=0.01:0.1:5000",
                "--grid",
                "amplitude=0.5:2:5000",
                "--validate",
                "--format",
                "csv",
            ],
            "usage",
        ),  # fmt: skip
        _case("sweep", [*SWEEP, "--grid", "eps=0.2:0.3:3"], "usage"),
        _case("sweep", [*SWEEP, "--set", "eps=0.1"], "usage"),
        _case("sweep", ["sweep", "duffing", "--format", "csv"], "usage"),
        _case("sweep", ["sweep", "duffing", "--grid", "eps=0.01:0.1:3"], "usage"),
    ]
    hostile = {
        "--workers": {"0": "usage", "-1": "usage", "abc": "usage", "1e9": "usage",
                      "1000000": "usage", "": "usage", "1": "ok"},
        "--order": {"0": "usage", "13": "usage", "12": "any", "abc": "usage", "2": "ok"},
        "--periods": {"0": "usage", "nan": "usage", "1e308": "usage", "-1": "usage"},
        "--tol": {"0": "usage", "nan": "usage", "inf": "usage", "abc": "usage"},
        "--times": {"abc": "usage", "0:1:0": "usage", "0,1,2": "ok", "nan": "usage",
                    "0:1:100000000": "usage"},
        "--derive": {"bogus": "usage", "per-point": "ok"},
        "--family": {"bogus": "usage"},
        "--integrator": {"bogus": "usage"},
    }  # fmt: skip
    for option, values in hostile.items():
        for value, expect in values.items():
            argv = [*SWEEP, option, value]
            if option in ("--periods", "--tol", "--integrator"):
                argv.append("--validate")
            cases.append(_case("sweep", argv, expect, seconds=SMALL))
    # scheduler addresses: refused within the (clamped) timeout
    zarr = ["sweep", "duffing", "--grid", "eps=0.01:0.1:3", "--output", "s.zarr"]
    for address in ("nonsense", "tcp://127.0.0.1:1", "tcp://256.0.0.1:1", "http://127.0.0.1:1",
                    "", "tls://127.0.0.1:1", "tcp://127.0.0.1:99999"):  # fmt: skip
        cases.append(_case("sweep", [*zarr, "--scheduler", address], "usage", seconds=QUICK))
    for timeout in ("1e308", "inf", "nan", "0", "-1", "abc", "100000"):
        expect = "usage"
        cases.append(
            _case("sweep", [*zarr, "--scheduler", "tcp://127.0.0.1:1", "--timeout", timeout],
                  expect, seconds=QUICK)
        )  # fmt: skip
    for kind in ("silent", "http400", "garbage"):
        cases.append(
            _case("sweep", [*zarr, "--scheduler", "tcp://127.0.0.1:{port}", "--timeout", "3"],
                  "usage", server=kind, seconds=QUICK)
        )  # fmt: skip
        cases.append(
            _case("sweep", [*zarr, "--scheduler", "tcp://127.0.0.1:{port}", "--timeout", "1e308"],
                  "usage", server=kind, seconds=120)
        )  # fmt: skip
    cases.append(_case("sweep", [*zarr, "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"],
                       "usage"))  # fmt: skip
    # stores and output files
    store = ["sweep", "duffing", "--grid", "eps=0.01:0.1:3", "--workers", "1"]
    cases += [
        _case("sweep", [*store, "--output", "s.zarr"], "ok", outputs=("s.zarr",), seconds=SMALL),
        _case("sweep", [*store, "--output", "notes.txt"], "usage"),
        _case("sweep", [*store, "--output", "data"], "usage"),
        _case("sweep", [*store, "--output", ""], "usage"),
        _case("sweep", [*store, "--output", "/proc/nowhere/s.zarr"], "usage"),
        _case("sweep", [*store, "--output", "new.zarr", "--resume"], "usage"),
        _case("sweep", [*store, "--output", "data", "--resume"], "usage"),
        _case(
            "sweep",
            [*store, "--output", "s.zarr"],
            "usage",
            outputs=("s.zarr",),
            seconds=SMALL,
            twice=True,
        ),
        _case("sweep", [*store, "--output", "notes.txt", "--format", "csv"], "usage"),
        _case(
            "sweep",
            [*store, "--output", "p.csv", "--format", "csv"],
            "ok",
            outputs=("p.csv",),
            seconds=SMALL,
        ),
        _case(
            "sweep",
            [*store, "--output", "notes.txt", "--format", "csv", "--force"],
            "ok",
            outputs=("notes.txt",),
            seconds=SMALL,
        ),
        _case("sweep", [*store, "--format", "csv", "--resume"], "usage"),
    ]
    # a family followed over the excitation frequency
    forced = ["sweep", "forced-duffing", "--grid", "Omega=1.05:1.2:4", "--format", "csv",
              "--workers", "1"]  # fmt: skip
    for family, expect in (("upper", "ok"), ("lower", "ok"), ("middle", "ok"),
                           ("bogus", "usage")):  # fmt: skip
        cases.append(_case("sweep", [*forced, "--family", family], expect, seconds=SMALL))
    cases.append(
        _case("sweep", ["sweep", "superharmonic-duffing", "--grid", "Omega=0.9:1.1:3",
                        "--format", "csv", "--workers", "1"], "any", seconds=SMALL)
    )  # fmt: skip
    for problem in ("nope", "", "forced-duffing"):
        argv = ["sweep", problem, "--grid", "eps=0.01:0.1:3", "--format", "csv", "--workers", "1"]
        cases.append(_case("sweep", argv, "usage" if problem != "forced-duffing" else "ok",
                           seconds=SMALL))  # fmt: skip
    return cases


# ---------------------------------------------------------------------------------- report
def _report(surface_scene: str, expect: str, output="rep", extra=(), **kw) -> Case:
    files = (("scene.toml", surface_scene), *kw.pop("files", ()))
    kw.setdefault("label", "scene " + hashlib.sha256(repr(files).encode()).hexdigest()[:8])
    outputs = kw.pop("outputs", (output,) if expect != "usage" else ())
    return _case("report", ["report", "scene.toml", "--output", output, *extra], expect,
                 files=files, outputs=outputs, seconds=kw.pop("seconds", SMALL), **kw)  # fmt: skip


RESPONSE_SCENE = scene(response='sweep = "Omega=0.95:1.1:5"', outputs="response = true")
TABLE_SCENE = scene(problem="duffing", outputs="table = true")
SWEEP_SCENE = scene(
    problem="duffing", parameters="", sweep='grid = ["eps=0.01:0.1:3"]', outputs="sweep = true"
)


def _report_cases() -> list[Case]:
    cases = [
        _report(TABLE_SCENE, "ok"),
        _report(RESPONSE_SCENE, "ok"),
        _report(SWEEP_SCENE, "ok"),
        _report(TABLE_SCENE, "ok", twice=True),
        _report(SWEEP_SCENE, "ok", twice=True),
        _report(RESPONSE_SCENE, "ok", output="data/rep"),
        # folders holding a user's files with a report's names: nothing removed, a clash is exit 2
        _report(TABLE_SCENE, "usage", output="."),
        _report(TABLE_SCENE, "usage", output="data"),
        _report(TABLE_SCENE, "usage", output="data", extra=("--force",)),
        _report(TABLE_SCENE, "usage", output="mine", files=(("mine/solution.json", "{}"),)),
        _report(
            RESPONSE_SCENE, "usage", output="mine", files=(("mine/response.csv", "mine"),)
        ),  # fmt: skip
        _report(
            scene(
                outputs="response = true",
                response='sweep = "Omega=0.95:1.1:5"',
            ).replace("response = true", "response = true\nvalidation = true"),
            "usage",
            output="mine",
            files=(("mine/validation.json", "mine"),),
        ),  # fmt: skip
        # a user's file named as a report file this scene does not write: left alone, the
        # report written beside it (README: "Files of other names are left alone")
        _report(
            TABLE_SCENE,
            "ok",
            output="mine",
            files=(("mine/time_series.png", "not a png"),),
            outputs=("mine",),
        ),  # fmt: skip
        _report(
            scene(problem="duffing", outputs="table = false"),
            "ok",
            output="mine",
            files=(("mine/solution.csv", "t\n"),),
            outputs=("mine",),
        ),  # fmt: skip
        _report(
            SWEEP_SCENE,
            "usage",
            output="mine",
            files=(
                (
                    "mine/sweep.zarr/zarr.json",
                    '{"zarr_format": 3, "node_type": "group", "attributes": {"perturb_sweep": 1}}',
                ),
            ),
        ),  # fmt: skip
        _report(
            scene(problem="duffing", outputs="table = false"),
            "ok",
            output="mine",
            files=(("mine/other.txt", "mine"),),
            outputs=("mine",),
        ),  # fmt: skip
        _report(TABLE_SCENE, "usage", output="notes.txt"),
        _report(TABLE_SCENE, "usage", output=""),
        _report(TABLE_SCENE, "usage", output="/proc/nowhere/rep"),
        _report(TABLE_SCENE, "usage", output="/proc/rep"),
        # expensive sections: bounded before any work
        _report(
            scene(response='sweep = "Omega=0.9:1.1:10000000"', outputs="response = true"), "usage"
        ),  # fmt: skip
        _report(
            scene(response='sweep = "Omega=0.9:1.1:200000"', outputs="response = true"), "usage"
        ),  # fmt: skip
        _report(
            scene(
                response='sweep = "Omega=0.9:1.1:1000000"\nvalidate = 10', outputs="response = true"
            ),
            "usage",
        ),  # fmt: skip
        _report(
            scene(
                problem="duffing",
                parameters="",
                sweep='grid = ["eps=0.01:0.1:100000", "amplitude=0.5:2:100000"]',
                outputs="sweep = true",
            ),
            "usage",
        ),  # fmt: skip
        _report(
            scene(
                problem="duffing",
                parameters="",
                sweep='grid = ["eps=0.01:0.1:3000", "amplitude=0.5:2:3000"]\nvalidate = true',
                outputs="sweep = true",
            ),
            "usage",
        ),  # fmt: skip
        # the engine's highest order is cheap for one mode (0.4 s for the Duffing): no question
        _report(scene(problem="duffing", order=12, outputs="table = true"), "ok"),
        _report(
            scene(response='sweep = "Omega=0.9:1.1:5"', order=12, outputs="response = true"),
            "usage",
        ),  # fmt: skip
        # sections that do not fit their problem
        _report(
            scene(
                problem="duffing", response='sweep = "Omega=0.9:1.1:5"', outputs="response = true"
            ),
            "usage",
        ),  # fmt: skip
        _report(
            scene(response='sweep = "bogus=0.9:1.1:5"', outputs="response = true"), "usage"
        ),  # fmt: skip
        _report(scene(response='sweep = "Omega=-1:1.1:5"', outputs="response = true"), "usage"),
        _report(
            scene(
                parameters="eps = 0.05\nOmega = 1.0",
                response='sweep = "Omega=0.9:1.1:5"',
                outputs="response = true",
            ),
            "usage",
        ),  # fmt: skip
        _report(
            scene(
                response='sweep = "Omega=0.9:1.1:5"',
                outputs='response = true\nplots = ["frequency_response"]\nformats = ["png", "xyz"]',
            ),
            "usage",
        ),  # fmt: skip
        _report(
            scene(
                problem="superharmonic-duffing",
                response='sweep = "Omega=0.9:1.1:5"',
                outputs="response = true",
            ),
            "any",
            says=r"(?i)outside|domain|beyond|valid",
        ),  # fmt: skip
        _report(
            scene(problem="duffing", sweep='grid = ["bogus=0.1:0.2:3"]', outputs="sweep = true"),
            "usage",
        ),  # fmt: skip
        _report(
            scene(
                problem="duffing",
                parameters="",
                sweep='grid = ["eps=0.1:0.2:3"]\nworkers = 100000',
                outputs="sweep = true",
            ),
            "usage",
        ),  # fmt: skip
        _report(
            scene(
                problem="forced-duffing",
                sweep='grid = ["Omega=1.05:1.2:4"]',
                outputs="sweep = true",
            ).replace('name = "forced-duffing"', 'name = "forced-duffing"\nfamily = "upper"'),
            "ok",
        ),  # fmt: skip
        _report("[problem\nname=", "usage"),
        _report("", "usage"),
        _report(scene(problem="nope", outputs="table = true"), "usage"),
    ]
    return cases


# ---------------------------------------------------------------------------------- problem files
def _file_cases() -> list[Case]:
    cases = []
    files = tuple(PROBLEM_FILES.items())
    texts = tuple((name.split(":")[0], text) for name, (text, _) in files)  # the spec's file
    for name, (_, expect) in files:
        for command in ("solve", "validate", "families"):
            want = expect
            if command != "solve" and expect in ("ok", "failed"):
                want = "any"  # validate/families may judge what solve builds differently
            cases.append(_case("user-file", [command, name], want, files=texts, seconds=SMALL))
        cases.append(
            _case("user-file", ["sweep", name, "--grid", "eps=0.05,0.1", "--format", "csv",
                                "--workers", "1"],
                  "any" if expect in ("ok", "failed") else expect, files=texts, seconds=SMALL)
        )  # fmt: skip
        driven = ("undamped_linear.py:Undamped", "ratio_float.py", "detuning_number.py")
        if expect == "usage" or name == DRIVEN_FILE or name in driven:
            want = expect if expect == "usage" else "any"  # a response away from sigma = 0 exists
            cases.append(
                _case("user-file", ["response", name, "--sweep", "sigma=-1:1:5"], want,
                      files=texts, seconds=SMALL)
            )  # fmt: skip
        cases.append(
            _case("user-file", ["report", "s.toml", "--output", "rep"],
                  "any" if expect in ("ok", "failed") else expect,
                  files=(*texts, ("s.toml", scene(problem=name, parameters="",
                                                  outputs="table = true"))),
                  outputs=("rep",), seconds=SMALL, label=name)
        )  # fmt: skip
    for spec in (f"{GOOD_FILE}:Nope", f"{GOOD_FILE}:HEADER", "nofile.py", "data", "data:Good",
                 f"{GOOD_FILE}:", ":Good", "os:getcwd", "os.path:join"):  # fmt: skip
        cases.append(_case("user-file", ["solve", spec], "usage", files=texts))
    return cases


# ---------------------------------------------------------------------------------- driven
DRIVEN_SETS = {
    "forced-duffing": ("Omega=1", "Omega=1e-9", "Omega=100", "eps=10", "eps=1e308", "zeta=0",
                       "F=1e-300", "gamma=0", "zeta=0 gamma=0", "Omega=1e308"),
    "parametric-duffing": ("Omega=2", "Omega=1", "Omega=1e-9", "eps=10", "h=0", "zeta=0",
                           "h=1e308", "gamma=0"),
    "superharmonic-duffing": ("Omega=1", "Omega=0.3333333333333333", "Omega=1e-9", "eps=10",
                              "F=1e308", "zeta=0", "gamma=0"),
    "autoparametric-absorber": ("Omega=2", "Omega=1", "eps=10", "F=0", "delta=1e308",
                                "zeta1=0 zeta2=0", "alpha1=0"),
}  # fmt: skip


def _driven_cases() -> list[Case]:
    cases = []
    for problem, sets in DRIVEN_SETS.items():
        for item in sets:
            options = [a for s in item.split() for a in ("--set", s)]
            for command in ("solve", "validate", "families"):
                bound = HEAVY if command == "validate" else SMALL
                cases.append(_case("driven", [command, problem, *options], "any", seconds=bound))
        for family in ("upper", "bogus", ""):
            cases.append(
                _case("driven", ["solve", problem, "--family", family],
                      "usage" if family != "upper" else "any", seconds=SMALL)
            )  # fmt: skip
    # validate superharmonic-duffing at Omega = 1: outside the domain, a failed run with a reason
    cases.append(
        _case("driven", ["validate", "superharmonic-duffing", "--set", "Omega=1"], "refuse",
              seconds=HEAVY)
    )  # fmt: skip
    return cases


def corpus() -> list[Case]:
    """Every case, grouped by surface (the classes of :mod:`tests.cli.hostile_classes` after the
    first corpus's)."""
    from tests.cli.hostile_classes import more_cases

    return [*_response_cases(), *_sweep_cases(), *_report_cases(), *_file_cases(),
            *_driven_cases(), *more_cases()]  # fmt: skip


# ---------------------------------------------------------------------------------- running
def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def snapshot(folder: Path) -> dict[str, str]:
    out = {}
    for path in folder.rglob("*"):
        if path.is_file() and not path.is_symlink():
            out[str(path.relative_to(folder))] = _digest(path)
    return out


def prepare(case: Case, folder: Path, env: dict | None = None) -> dict[str, str]:
    """Write the user's files into ``folder``, run the case's earlier commands (``pre``: a
    report or a store made first) and its operations on the folder (``ops``: see
    :func:`tests.cli.hostile_classes.apply`); return the digests of what is there."""
    for name, text in {**USER_FILES, **dict(case.files)}.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text) if isinstance(text, str) else path.write_bytes(text)
    for argv in case.pre:
        subprocess.run(
            [sys.executable, "-m", "perturb", *argv], capture_output=True, cwd=folder,
            env={**os.environ, **(env or {})}, stdin=subprocess.DEVNULL, timeout=HEAVY,
        )  # fmt: skip
    if case.ops:
        from tests.cli.hostile_classes import apply

        apply(case.ops, folder)
    return snapshot(folder)


class _Server:
    """A TCP server on 127.0.0.1 that is not a Dask scheduler: it says nothing, answers HTTP 400,
    or sends bytes that are no Dask message."""

    def __init__(self, kind: str):
        self.kind = kind
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(16)
        self.port = self.sock.getsockname()[1]
        self.stop = False
        self.held = []
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while not self.stop:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.held.append(conn)
            try:
                if self.kind == "http400":
                    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                elif self.kind == "garbage":
                    conn.sendall(b"\xff" * 64)
            except OSError:
                pass

    def close(self):
        self.stop = True
        for conn in self.held:
            conn.close()
        self.sock.close()


class _DaskScheduler:
    """A real ``dask scheduler`` on 127.0.0.1 with no worker (a cluster left without workers)."""

    def __init__(self):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            self.port = probe.getsockname()[1]
        self.process = subprocess.Popen(
            [sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1", "--port",
             str(self.port), "--no-dashboard"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )  # fmt: skip
        deadline = time.monotonic() + QUICK
        while time.monotonic() < deadline:
            with socket.socket() as probe:
                if probe.connect_ex(("127.0.0.1", self.port)) == 0:
                    return
            time.sleep(0.2)

    def close(self):
        self.process.terminate()
        self.process.wait(QUICK)


@dataclass
class Outcome:
    code: int | None
    out: str
    err: str
    seconds: float
    broken: list = field(default_factory=list)


def run_case(case: Case, folder: Path, env: dict | None = None) -> Outcome:
    """Run ``case`` in ``folder`` (a fresh process, its time bound enforced) and judge it."""
    before = prepare(case, folder, env)
    server = None
    if case.server:
        server = _DaskScheduler() if case.server == "dask" else _Server(case.server)
    argv = [a.replace("{port}", str(server.port)) if server else a for a in case.argv]
    environment = {**os.environ, **(env or {})}
    runs = 2 if case.twice else 1
    code, out, err, clock = None, "", "", time.perf_counter()
    try:
        for _ in range(runs):
            try:
                proc = subprocess.run(
                    [sys.executable, "-m", "perturb", *argv], capture_output=True, text=True,
                    timeout=case.seconds, stdin=subprocess.DEVNULL, cwd=folder, env=environment,
                )  # fmt: skip
                code, out, err = proc.returncode, proc.stdout, proc.stderr
            except subprocess.TimeoutExpired as exc:
                code = None
                out = exc.stdout.decode() if isinstance(exc.stdout, bytes) else (exc.stdout or "")
                err = exc.stderr.decode() if isinstance(exc.stderr, bytes) else (exc.stderr or "")
                break
    finally:
        if server is not None:
            server.close()
    seconds = time.perf_counter() - clock
    outcome = Outcome(code, out, err, seconds)
    outcome.broken = judge(case, code, out, err, before, snapshot(folder))
    return outcome


_NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)


def judge(case: Case, code, out: str, err: str, before: dict, after: dict) -> list[str]:
    """The broken promises of one run (empty when it behaved)."""
    if code is None:
        return [f"past its bound of {case.seconds:g} s"]
    broken = []
    text = out + err
    if "Traceback" in text:
        broken.append("traceback")
    if "internal error" in err:
        broken.append("internal error")
    if code not in (0, 1, 2):
        broken.append(f"exit {code}")
    if case.surface == "user-file" and "overflowed" in err:
        broken.append("a user's file reported as an overflow")
    lines = [line for line in err.strip().splitlines() if not line.startswith("perturb: warning")]
    if code == 2 and (len(lines) != 1 or not lines[0].startswith("perturb: error:")):
        broken.append("exit 2 without exactly one error line")
    if code == 1 and not any(line.startswith("perturb: ") for line in lines):
        broken.append("exit 1 without a reason")
    want = case.expect
    allowed = CLASSES[want][0]
    if code in (0, 1, 2) and code not in allowed:
        broken.append(f"exit {code} where {want} was due ({lines[-1][:120] if lines else ''})")
    if code == 0:
        broken += _nonsense(case, out)
        if case.says and not re.search(case.says, text):
            broken.append(f"exit 0 without saying /{case.says}/")
        if case.never and re.search(case.never, out):
            broken.append(f"exit 0 saying /{case.never}/")
    # nothing a user wrote removed or changed; nothing written outside the outputs
    for name, digest in before.items():
        if name not in after:
            broken.append(f"removed the user's {name}")
        elif after[name] != digest and not _inside(name, case.outputs, code, case):
            broken.append(f"changed the user's {name}")
    for name in after:
        if name not in before and not _inside(name, case.outputs, code, case):
            broken.append(f"wrote {name} outside its output")
    return broken


def _inside(name: str, outputs, code, case) -> bool:
    if "--force" in case.argv and code == 0:
        return any(name == o or name.startswith(o.rstrip("/") + "/") for o in outputs)
    return any(name == o or name.startswith(o.rstrip("/") + "/") or o == "." for o in outputs)


def _not_json(word: str):
    raise ValueError(f"{word} is not JSON")


def _nonsense(case: Case, out: str) -> list[str]:
    argv = case.argv
    fmt = argv[argv.index("--format") + 1] if "--format" in argv[:-1] else "table"
    if fmt == "json" and "--output" not in argv:
        try:
            json.loads(out, parse_constant=_not_json)  # NaN, Infinity: not JSON
        except ValueError:
            return ["exit 0 with unreadable JSON"]
    if argv[0] == "solve" and _NON_FINITE.search(out):
        return ["exit 0 printing NaN/inf"]
    return []
