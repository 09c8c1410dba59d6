"""The second hostile corpus's classes (:func:`more_cases`), run with the first by
:mod:`tests.cli.hostile_corpus`: nothing runs that the user did not name, nothing is removed that
perturb did not write, nothing is unbounded.

Each case names its class in ``group``:

=================  ===============================================================================
group              what is tried, and the promise
=================  ===============================================================================
working folder     stdlib (and dependency) names planted in the working folder, each writing a
                   file when imported: never imported by the command or its Dask workers
scene paths        a scene's problem file beside the scene, not in the working folder; a scene
                   with a byte-order mark; a scene that is a FIFO, a device, a folder, too large
report marker      a report folder whose marker was crafted (null, mismatched, "claimed, not yet
                   written" records, a null store token) over a user's file: the file is kept
sizes              grid axes, ``--times`` (counts, ``@/dev/zero``, a FIFO, a folder), ``--repeat``,
                   ``--orders``, scenes: refused before anything is built, within the quick bound
user code          a hook raising SystemExit(0), KeyboardInterrupt, GeneratorExit, BaseException:
                   one line naming file:line, exit 2
overflow, JSON     parameters past the floats, a separatrix, an empty response: a reason, never
                   a normal-looking answer; every ``--format json`` strict JSON (no NaN)
valid input        values starting with '-', a tiny eps swept, a store through a link: accepted
outputs            two outputs naming one file: refused before any work
stores             a store damaged after it was written, resumed; a cluster without workers
=================  ===============================================================================

``ops`` are applied to the folder after the case's ``pre`` commands ran (:func:`apply`): write a
file, plant a module, make a FIFO or a link, craft a report's marker, damage a store.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

from tests.cli.hostile_corpus import HEAVY, QUICK, SMALL, _case
from tests.cli.hostile_files import GOOD_FILE, PROBLEM_FILES, scene

GOOD = PROBLEM_FILES[GOOD_FILE][0]

#: Modules planted in the working folder: the standard library's and perturb's dependencies'.
PLANTED = ("multiprocessing", "struct", "selectors", "socket", "json", "pickle", "typing",
           "threading", "asyncio", "logging", "random", "numpy", "sympy", "dask", "zarr",
           "heyoka", "matplotlib", "cloudpickle")  # fmt: skip


def _planted() -> tuple:
    """A module per name of :data:`PLANTED` that writes ``NAME.ran`` beside itself when imported
    (a file outside every output: the judge reports it)."""
    body = "import os\nopen(os.path.join(os.path.dirname(os.path.abspath(__file__)), {!r}), 'w')\n"
    return tuple((f"{name}.py", body.format(f"{name}.ran")) for name in PLANTED)


def apply(ops, folder: Path) -> None:
    """Apply each ``(op, *args)`` of ``ops`` to ``folder`` (paths relative to it)."""
    for op, *args in ops:
        path = folder / args[0]
        if op == "write":
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(args[1])
        elif op == "bytes":
            path.write_bytes(args[1])
        elif op == "fifo":
            os.mkfifo(path)
        elif op == "sparse":  # a file of this size with nothing written
            with open(path, "wb") as file:
                file.truncate(args[1])
        elif op == "link":
            path.symlink_to(args[1])
        elif op == "remove":
            shutil.rmtree(path) if path.is_dir() else path.unlink()
        elif op == "folder":  # a file replaced by a folder
            path.unlink()
            path.mkdir()
        elif op == "marker":  # the report marker's records set to ``args[1]`` (a dict)
            marker = json.loads(path.read_text())
            for key, changes in args[1].items():
                if isinstance(marker.get(key), dict) and isinstance(changes, dict):
                    marker[key].update(changes)
                else:
                    marker[key] = changes
            path.write_text(json.dumps(marker))
        else:  # pragma: no cover - a mistake in the corpus
            raise ValueError(f"unknown op {op!r}")


def _working_folder() -> list:
    files = _planted()
    sweep = ["sweep", "duffing", "--grid", "eps=0.01:0.2:3", "--workers", "1", "--format", "csv"]
    commands = [
        (sweep, HEAVY),
        (["phase-diagram", "forced-duffing", "--grid", "Omega=0.9:1.1:3", "--grid", "F=0.5:1:3",
          "--workers", "1", "--rows-only"], HEAVY),
        (["solve", "duffing", "--times", "0,1"], SMALL),
        (["validate", "duffing", "--periods", "1"], HEAVY),
        (["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:3", "--order", "1"], SMALL),
        (["families", "resonant-pair"], SMALL),
        (["solve", "good.py", "--times", "0"], SMALL),
        (["sweep", "good.py", "--grid", "eps=0.05,0.1", "--workers", "1", "--format", "csv"],
         HEAVY),
    ]  # fmt: skip
    cases = [
        _case("sweep", argv, "ok", files=(*files, ("good.py", GOOD)), seconds=bound,
              group="working folder")
        for argv, bound in commands
    ]  # fmt: skip
    report = scene(problem="duffing", parameters="", sweep='grid = ["eps=0.05,0.1"]\nworkers = 1',
                   outputs="sweep = true")  # fmt: skip
    cases.append(
        _case("report", ["report", "s.toml", "--output", "rep"], "ok",
              files=(*files, ("s.toml", report)), outputs=("rep",), seconds=HEAVY,
              group="working folder")
    )  # fmt: skip
    return cases


def _scene_paths() -> list:
    table = scene(problem="user.py:Good", parameters="", outputs="table = true")
    beside = (("sub/user.py", GOOD), ("user.py", "raise SystemExit('the wrong user.py ran')\n"),
              ("sub/s.toml", table))  # fmt: skip
    duffing = scene(problem="duffing", parameters="", outputs="table = true")
    group = "scene paths"
    cases = [
        _case("report", ["report", "sub/s.toml", "--output", "rep"], "ok", files=beside,
              outputs=("rep",), seconds=SMALL, group=group),
        _case("report", ["report", "s.toml", "--output", "rep"], "ok",
              ops=(("bytes", "s.toml", b"\xef\xbb\xbf" + duffing.encode()),), outputs=("rep",),
              seconds=SMALL, group=group, label="BOM"),
        _case("report", ["report", "s.toml", "--output", "rep"], "usage",
              ops=(("fifo", "s.toml"),), group=group, label="FIFO"),
        _case("report", ["report", "/dev/zero", "--output", "rep"], "usage", group=group),
        _case("report", ["report", "data", "--output", "rep"], "usage", group=group),
        _case("report", ["report", "s.toml", "--output", "rep"], "usage",
              ops=(("sparse", "s.toml", 2 << 20),), group=group, label="2 MB"),
        _case("report", ["report", "s.toml", "--output", "rep"], "usage",
              files=(("s.toml", duffing.replace("order = 1", "order = 1\nperiods = 1000\n"
                                                "samples = 10000")),), group=group),
    ]  # fmt: skip
    return cases


REPORT = scene(problem="duffing", parameters="", outputs="table = true\nvalidation = true")
SWEEP_REPORT = scene(problem="duffing", parameters="", sweep='grid = ["eps=0.05,0.1"]\nworkers = 1',
                     outputs="sweep = true")  # fmt: skip


def _report_marker() -> list:
    group = "report marker"
    run = ("report", "s.toml", "--output", "rep")
    marker = "rep/.perturb-report.json"
    crafted = {
        "null digest": {"files": {"validation.json": None}},
        "claimed, not yet written": {"files": {"validation.json": None, "solution.csv": None}},
        "digest mismatch": {"files": {"validation.json": "0" * 64}},
        "digest not a string": {"files": {"validation.json": ["x"]}},
        "other scene": {"scene": "/elsewhere/s.toml", "files": {"validation.json": None}},
    }
    cases = []
    for name, change in crafted.items():
        for force in ((), ("--force",)):
            cases.append(
                _case("report", [*run, *force], "usage", files=(("s.toml", REPORT),),
                      pre=(run,), ops=(("marker", marker, change),
                                       ("write", "rep/validation.json", "my own\n")),
                      outputs=(), seconds=HEAVY, group=group, label=name)
            )  # fmt: skip
    store_crafts = {
        "null store token": {"stores": {"sweep.zarr": None}},
        "null store fingerprint": {"store_fingerprints": {"sweep.zarr": None}},
    }
    for name, change in store_crafts.items():
        for force in ((), ("--force",)):
            cases.append(
                _case("report", [*run, *force], "usage", files=(("s.toml", SWEEP_REPORT),),
                      pre=(run,), ops=(("marker", marker, change),), outputs=(),
                      seconds=HEAVY, group=group, label=name)
            )  # fmt: skip
    # a user's own complete store named sweep.zarr under a marker claiming it with a null token
    cases.append(
        _case("report", [*run, "--force"], "usage",
              files=(("s.toml", SWEEP_REPORT), ("rep/notes.txt", "mine\n")),
              pre=(("sweep", "duffing", "--grid", "eps=0.05,0.1", "--workers", "1", "--output",
                    "rep/sweep.zarr"),),
              ops=(("write", marker, json.dumps({
                  "perturb_report": 1, "scene": "s.toml", "files": {},
                  "stores": {"sweep.zarr": None}})),),
              outputs=(), seconds=HEAVY, group=group, label="user's store, null token")
    )  # fmt: skip
    # the same scene again, nothing crafted: replaced (its own files)
    cases.append(
        _case("report", list(run), "ok", files=(("s.toml", SWEEP_REPORT),), pre=(run,),
              outputs=("rep",), seconds=HEAVY, group=group, label="own report again")
    )  # fmt: skip
    return cases


def _sizes() -> list:
    group = "sizes"
    solve = ["solve", "duffing"]
    sweep = ["sweep", "duffing", "--format", "csv", "--workers", "1"]
    cases = [
        _case("sweep", [*sweep, "--grid", "eps=0.01:0.2:1000000000"], "usage"),
        _case("sweep", [*sweep, "--grid", "eps=0.01:0.2:99999999999999999999999"], "usage"),
        _case("sweep", [*sweep, "--grid", "eps=0.01:0.2:1000000000", "--yes"], "usage"),
        _case("sweep", [*sweep, "--grid", "eps=0.01:0.2:100000", "--grid",
                        "amplitude=0.5:2:100000", "--grid", "eps=0.1:0.2:100000"], "usage"),
        _case("sweep", [*sweep, "--grid", "eps=0.01:0.2:1000", "--times", "0:1:1000000"],
              "usage"),
        _case("driven", [*solve, "--times", "0:1e6:10000000"], "usage"),
        _case("driven", [*solve, "--times", "0:1:99999999999999999999"], "usage"),
        _case("driven", [*solve, "--times", "@/dev/zero"], "usage"),
        _case("driven", [*solve, "--times", "@/dev/urandom"], "usage"),
        _case("driven", [*solve, "--times", "@data"], "usage"),
        _case("driven", [*solve, "--times", "@fifo"], "usage", ops=(("fifo", "fifo"),)),
        _case("driven", [*solve, "--times", "@big.txt"], "usage",
              ops=(("sparse", "big.txt", 64 << 20),)),
        _case("driven", [*solve, "--times", "@t.txt"], "ok",
              ops=(("bytes", "t.txt", b"\xef\xbb\xbf0\n0.5 # half\n1\n"),)),
        _case("response", ["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:1000000000"],
              "usage"),
        _case("response", ["response", "forced-duffing", "--sweep",
                           "Omega=0.9:1.1:10000000000000000000000"], "usage"),
        _case("driven", ["work-precision", "duffing", "--repeat", "1000"], "usage"),
        _case("driven", ["work-precision", "duffing", "--repeat", "1000000000"], "usage"),
        _case("driven", ["work-precision", "duffing", "--periods", "100000"], "usage"),
        _case("driven", ["work-precision", "duffing", "--periods", "1000", "--repeat", "50"],
              "usage"),
        _case("driven", ["phase-diagram", "forced-duffing", "--grid", "Omega=0.9:1.1:100000",
                         "--grid", "F=0.5:1:100000"], "usage"),
        _case("driven", ["phase-diagram", "forced-duffing", "--grid",
                         "Omega=0.9:1.1:1000000000", "--grid", "F=0.5:1:3"], "usage"),
    ]  # fmt: skip
    return [_with(case, group) for case in cases]


def _with(case, group):
    from dataclasses import replace

    return replace(case, group=group)


def _hook(raise_: str) -> str:
    return GOOD.replace('return {"amplitudes": {"x": A}}', raise_)


def _user_code() -> list:
    hooks = {
        "exit0_hook.py": "raise SystemExit(0)",
        "exit3_hook.py": "raise SystemExit(3)",
        "exit_text_hook.py": "raise SystemExit('bye')",
        "keyboard_hook.py": "raise KeyboardInterrupt",
        "generator_hook.py": "raise GeneratorExit",
        "base_hook.py": "raise BaseException('bare')",
        "exit_build.py": None,
    }
    files = []
    for name, raise_ in hooks.items():
        if raise_ is None:
            text = GOOD.replace("return QuasilinearSystem(", "raise SystemExit(0)\n        return "
                                "QuasilinearSystem(")  # fmt: skip
        else:
            text = _hook(raise_)
        files.append((name, text))
    cases = []
    for name, _ in files:
        for command in (["solve", name], ["validate", name, "--periods", "1"], ["families", name],
                        ["work-precision", name, "--periods", "1", "--repeat", "1"]):  # fmt: skip
            cases.append(_case("user-file", command, "usage", files=tuple(files), seconds=SMALL,
                               group="user code"))  # fmt: skip
    return cases


def _overflow_json() -> list:
    group = "overflow, JSON"
    cases = [
        (["solve", "disk", "--set", "r0=1e308", "--format", "json"], "refuse"),
        (["solve", "disk", "--set", "r0=1e308"], "refuse"),
        (["families", "resonant-pair", "--set", "kappa=1e308"], "refuse"),
        (["families", "linear-pair", "--set", "kappa=1e308"], "refuse"),
        (["solve", "linear-pair", "--set", "kappa=1e308"], "refuse"),
        (["solve", "resonant-pair", "--set", "kappa=-1e308", "--format", "json"], "refuse"),
        (["validate", "duffing", "--set", "amplitude=1e200", "--format", "json"], "refuse"),
        (["response", "forced-duffing", "--sweep", "F=1e150:1e151:3"], "refuse"),
        (["response", "forced-duffing", "--sweep", "F=1e10:1e11:3", "--order", "1"], "refuse"),
        (["solve", "duffing", "--set", "eps=-1"], "refuse"),
        (["solve", "duffing", "--set", "eps=-4", "--set", "amplitude=0.5"], "refuse"),
        (["validate", "duffing", "--set", "eps=-1"], "refuse"),
        (["work-precision", "disk", "--format", "json"], "refuse"),
        (["validate", "duffing", "--periods", "1", "--format", "json"], "ok"),
        (["validate", "van-der-pol", "--periods", "1", "--format", "json"], "any"),
        (["work-precision", "duffing", "--periods", "1", "--repeat", "1", "--format", "json"],
         "ok"),
        (["sweep", "duffing", "--grid", "eps=-1.5:0.1:3", "--format", "json", "--workers", "1"],
         "ok"),
        (["sweep", "duffing", "--grid", "eps=0.05,0.1", "--validate", "--format", "json",
          "--workers", "1"], "ok"),
        (["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:3", "--format", "json"], "ok"),
        (["phase-diagram", "forced-duffing", "--grid", "Omega=0.9:1.1:3", "--grid", "F=0.5:1:3",
          "--workers", "1", "--rows-only", "--format", "json"], "ok"),
        (["families", "resonant-pair", "--format", "json"], "ok"),
        (["list", "--format", "json"], "ok"),
    ]  # fmt: skip
    return [_case("driven", argv, expect, seconds=HEAVY, group=group) for argv, expect in cases]


def _valid_input() -> list:
    group = "valid input"
    store = ["sweep", "duffing", "--grid", "eps=0.01:0.2:3", "--workers", "1"]
    cases = [
        _case("response", ["response", "forced-duffing", "--sweep", "eps=1e-6:2e-6:3"], "ok",
              seconds=SMALL),
        _case("driven", ["solve", "duffing", "--times", "-1,0,1"], "ok", seconds=SMALL),
        _case("driven", ["solve", "duffing", "--times", "-1:1:5", "--format", "csv"], "ok",
              seconds=SMALL),
        _case("driven", ["solve", "duffing", "--output", "-o.json", "--format", "json"], "ok",
              outputs=("-o.json",), seconds=SMALL),
        _case("driven", ["solve", "duffing", "--set", "eps=-0.5", "--times", "-2,-1"], "ok",
              seconds=SMALL),
        _case("sweep", [*store, "--output", "l.zarr", "--resume"], "ok",
              pre=((*store, "--output", "s.zarr"),), ops=(("link", "l.zarr", "s.zarr"),),
              outputs=("s.zarr", "l.zarr"), seconds=HEAVY),
        _case("driven", ["phase-diagram", "forced-duffing", "--set", "Omega=1", "--grid",
                         "Omega=0.9:1.1:3", "--grid", "F=0.5:1:3"], "usage"),
        _case("driven", ["work-precision", "duffing", "--orders", "13"], "usage"),
        _case("response", ["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:3", "--set",
                           "Omega=1"], "usage"),
    ]  # fmt: skip
    return [_with(case, group) for case in cases]


def _outputs() -> list:
    group = "outputs"
    response = ["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:3"]
    work = ["work-precision", "duffing", "--periods", "1", "--repeat", "1"]
    cases = []
    for base in (response, work):
        for plot, output, ops in (("same.png", "same.png", ()),
                                  ("./same.png", "same.png", ()),
                                  ("data/../same.png", "same.png", ()),
                                  ("link.png", "same.png", (("link", "link.png", "same.png"),)),
                                  ("same.svg", "SAME.svg", ())):  # fmt: skip
            expect = "usage" if plot != "same.svg" else "ok"
            outputs = ("same.svg", "SAME.svg") if expect == "ok" else ()
            cases.append(_case("response", [*base, "--plot", plot, "--output", output], expect,
                               ops=ops, outputs=outputs, seconds=SMALL, group=group))  # fmt: skip
    cases.append(
        _case("driven", ["phase-diagram", "forced-duffing", "--grid", "Omega=0.9:1.1:3", "--grid",
                         "F=0.5:1:3", "--output", "p.zarr", "--plot", "p.zarr"], "usage",
              group=group)
    )  # fmt: skip
    return cases


def _stores() -> list:
    group = "stores"
    store = ["sweep", "duffing", "--grid", "eps=0.01:0.2:3", "--workers", "1", "--output",
             "s.zarr"]  # fmt: skip
    damages = {
        "metadata of an array removed": ((("remove", "s.zarr/period/zarr.json"),), "ok"),
        "an array removed": ((("remove", "s.zarr/period"),), "ok"),
        "a chunk removed": ((("remove", "s.zarr/status/c/0"),), "ok"),
        "a chunk replaced by a folder": ((("folder", "s.zarr/period/c/0"),), "usage"),
        "the group's metadata removed": ((("remove", "s.zarr/zarr.json"),), "usage"),
    }
    cases = []
    for name, (ops, expect) in damages.items():
        cases.append(
            _case("sweep", [*store, "--resume"], expect, pre=(store,), ops=ops,
                  outputs=("s.zarr",) if expect == "ok" else (), seconds=HEAVY, group=group,
                  label=name)
        )  # fmt: skip
    cases.append(
        _case("sweep", ["sweep", "duffing", "--grid", "eps=0.01:0.2:3", "--scheduler",
                        "tcp://127.0.0.1:{port}", "--output", "nw.zarr"], "failed",
              server="dask", outputs=("nw.zarr",), seconds=HEAVY, group=group)
    )  # fmt: skip
    return cases


def more_cases() -> list:
    """Every case of the second corpus's classes (see the module docstring)."""
    return [*_working_folder(), *_scene_paths(), *_report_marker(), *_sizes(), *_user_code(),
            *_overflow_json(), *_valid_input(), *_outputs(), *_stores()]  # fmt: skip


__all__ = ["PLANTED", "QUICK", "apply", "more_cases"]
