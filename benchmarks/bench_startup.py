"""Benchmark: a warm ``perturb validate disk`` against the bare import of what it imports.

A warm command (its cache filled) should cost little more than importing the libraries it uses.
This script finds those libraries by running the command twice in a child (the first run fills
the cache) and listing the modules the second, warm, run loaded outside ``perturb`` and
``problems`` (the third-party packages and the submodules of scipy and sympy it reached, e.g.
``scipy.integrate``), then times, in alternating pairs of fresh interpreters,

* the bare import of exactly those modules (``python -c "import numpy, scipy.integrate, ..."``),
* the bare import of the declared dependencies the issue names, ``import numpy, scipy, sympy,
  heyoka`` (scipy's top level only: its submodules load when first used; attrs and symengine,
  also declared, are left out),
* the warm command itself (``python -m perturb validate disk ...`` at the README's fast-spin
  point),

so that the three members of a round see the same load.  The measured tree's own modules are
compiled to bytecode first (``compileall``, as ``pip install`` does for an installed perturb):
the third-party modules are read from their bytecode, and a run with ``PYTHONDONTWRITEBYTECODE``
set and no ``__pycache__`` would otherwise compile perturb from source every time (0.16 s of CPU
here), which no installed perturb does. It prints the median CPU seconds (user
+ system, from ``getrusage`` of the children) of each, the command's ratio to each baseline, the
medians of the rounds' ratios, the load average before and after, and the modules of the second list that a bare
``import sympy`` does not load (what the command imports beyond sympy's own: e.g.
``sympy.physics.units``, which sympy's ``simplify`` and ``solve`` load on their first call).
Run from the repository root::

    python benchmarks/bench_startup.py [--pairs 7] [--rev REV]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from _tree import export

ROOT = Path(__file__).resolve().parent.parent
#: The README's fast-spin disk, where validation runs the whole way (shooting and order check).
COMMAND = ["validate", "disk", "--set", "r0=0.755155", "--set", "R=0.123299",
           "--set", "gamma3_0=0.25", "--quiet"]  # fmt: skip
#: Rounds of fresh processes timed by default.
PAIRS = 7
#: The declared dependencies of the second baseline (the issue's "bare import of sympy + scipy +
#: heyoka", with numpy).
DECLARED = ("numpy", "scipy", "sympy", "heyoka")

_LIST_MODULES = """
import json, sys
from perturb.cli import main
main({argv!r})
ours = ("perturb", "problems", "__main__")
names = sorted(n for n in sys.modules if not n.startswith(ours))
sys.stderr.write("MODULES " + json.dumps(names) + "\\n")
"""


def _cpu(argv: list[str], env: dict, codes=(0, 1)) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=env["PYTHONPATH"])
    if out.returncode not in codes:
        raise RuntimeError(f"{argv[:4]}: exit {out.returncode}: {out.stderr[-400:]}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _modules(env: dict) -> list[str]:
    """The modules the warm command loads, outside perturb and problems: listed by its second
    run (the first fills the cache, and a cold run derives, with modules a warm one never
    imports)."""
    for _ in range(2):
        out = subprocess.run(
            [sys.executable, "-c", _LIST_MODULES.format(argv=COMMAND)],
            capture_output=True, text=True, env=env, cwd=env["PYTHONPATH"], check=True,
        )  # fmt: skip
    line = next(x for x in out.stderr.splitlines() if x.startswith("MODULES "))
    return json.loads(line.removeprefix("MODULES "))


def _third_party(modules: list[str]) -> list[str]:
    """Every module the command loaded outside the standard library (and perturb, problems):
    the bare run imports exactly these, each by its own name."""
    stdlib = set(sys.stdlib_module_names)
    return [
        m for m in modules if m.split(".")[0] not in stdlib and m.split(".")[0] != "_distutils_hack"
    ]


#: The bare run: import each module of the list given as JSON (one that cannot be imported by its
#: name alone, a module a package makes on the fly, is skipped: the package that made it is in
#: the list).
_BARE = """
import importlib, json, sys
for name in json.loads(sys.argv[1]):
    try:
        importlib.import_module(name)
    except Exception:
        pass
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=PAIRS)
    parser.add_argument("--rev", default=None, help="measure this git revision's tree instead")
    options = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="perturb-startup-") as scratch:
        tree = ROOT if options.rev is None else export(options.rev, tempfile.mkdtemp(dir=scratch))
        env = {
            **os.environ,
            "PYTHONPATH": str(tree),
            "PERTURB_CACHE_DIR": str(Path(scratch) / "cache"),
            "PERTURB_CACHE_KEY_FILE": str(Path(scratch) / "cache.key"),
        }
        subprocess.run(
            [sys.executable, "-m", "compileall", "-q", str(tree / "perturb"), str(tree / "problems")],
            check=True, capture_output=True,
        )  # fmt: skip
        modules = _modules(env)  # also fills the cache: every timed command is warm
        imports = _third_party(modules)
        bare = [sys.executable, "-c", _BARE, json.dumps(imports)]
        declared = [sys.executable, "-c", "import " + ", ".join(DECLARED)]
        command = [sys.executable, "-m", "perturb", *COMMAND]
        sympy_alone = subprocess.run(
            [sys.executable, "-c", "import sys, sympy; print('\\n'.join(sys.modules))"],
            capture_output=True, text=True, env=env, check=True,
        ).stdout.split()  # fmt: skip
        beyond = sorted({".".join(m.split(".")[:3]) for m in modules
                         if m.startswith("sympy.") and m not in sympy_alone})  # fmt: skip
        load_before = os.getloadavg()
        rounds = [
            (_cpu(bare, env, (0,)), _cpu(declared, env, (0,)), _cpu(command, env))
            for _ in range(options.pairs)
        ]
        load_after = os.getloadavg()
    bare_cpu, declared_cpu, command_cpu = (
        statistics.median(r[i] for r in rounds) for i in range(3)
    )
    tops = sorted({m.split(".")[0] for m in imports if not m.startswith("_")})
    print(f"bare import of the {len(imports)} modules it loads, of {', '.join(tops)}")
    print(f"{'CPU seconds (medians of ' + str(options.pairs) + ' rounds)':56s} {'':>8s}")
    print(f"{'  bare import of the modules the command loads':56s} {bare_cpu:8.2f}")
    print(f"{'  bare import of ' + '+'.join(DECLARED) + ' (declared)':56s} {declared_cpu:8.2f}")
    print(f"{'  warm perturb validate disk (README point)':56s} {command_cpu:8.2f}")
    for label, index, base in (("the modules", 0, bare_cpu), ("the declared", 1, declared_cpu)):
        ratios = [r[2] / r[index] for r in rounds]
        print(f"{'  ratio to ' + label + ': of the medians':56s} {command_cpu / base:8.2f}")
        middle = statistics.median(ratios)
        print(f"{'  ratio to ' + label + ': median of the rounds ratios':56s} {middle:8.2f}")
    print(f"sympy modules beyond a bare `import sympy`: {', '.join(beyond) or 'none'}")
    print(f"({os.cpu_count()} cores; load average {load_before[0]:.1f} before, "
          f"{load_after[0]:.1f} after)")  # fmt: skip


if __name__ == "__main__":
    main()
