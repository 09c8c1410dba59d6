"""The CLI fuzz corpus (issues 10 and 31): every subcommand x every option x hostile values.

Shared by ``tests/cli/test_cli_fuzz.py`` (a derandomized hypothesis sample, in process) and
``benchmarks/fuzz_cli.py`` (the whole corpus, each invocation in a fresh process with a time limit).
The newer surfaces' own corpus, with the user's files and the folders they run in, is
``tests/cli/hostile_corpus.py``.

Each invocation is judged by :func:`judge`, which returns the list of broken promises:
a traceback, an exit code other than 0/1/2, an exit 2 whose stderr is not one line naming what was
wrong, or an exit 0 whose output prints NaN/inf or a negative period.
"""

from __future__ import annotations

import json
import math
import re

#: Hostile values for any option: non-numbers, non-finite, zero, negatives, extremes, Unicode digits,
#: empty strings and things that look like lists, hex or overflow.
VALUES = (
    "abc",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "0",
    "-1",
    "-0.5",
    "1e308",
    "-1e308",
    "1e-308",
    "1e400",
    "\u0661\u0662",  # Arabic-Indic "12"
    "\uff13",  # full-width "3"
    "",
    " ",
    "1,2",
    "0x10",
    "2.5",
    "3",
)

#: Problem arguments: known, unknown, empty, and paths that do not exist or are not problems.
PROBLEMS = ("duffing", "van-der-pol", "nope", "", "/no/such/file.py:Thing", "os.path:join")

#: Options of each command and the parameter names ``--set`` is tried with.
OPTIONS = {
    "solve": ("--order", "--times", "--format"),
    "validate": ("--order", "--integrator", "--periods", "--format", "--tol"),
    "work-precision": ("--periods", "--orders", "--repeat", "--format", "--plot"),
    "reproduce": ("--format", "--output"),
    "families": ("--order", "--format", "--output"),
    "response": ("--order", "--validate", "--format", "--plot", "--sweep", "--output"),
    "sweep": ("--order", "--workers", "--timeout", "--periods", "--tol", "--times", "--format"),
}
SET_NAMES = ("eps", "amplitude", "mu", "bogus", "", "eps=1")

#: The valid command each hostile option is added to (a later option overrides an earlier one).
#: work-precision runs a short, single-repeat sweep: the corpus tests option handling, and a full
#: default sweep takes about a minute of CPU.
BASES = {
    "reproduce": ["reproduce", "paper"],
    "work-precision": ["work-precision", "duffing", "--periods", "2", "--repeat", "1"],
    "response": ["response", "forced-duffing", "--sweep", "Omega=1.0:1.1:3"],
    "sweep": ["sweep", "duffing", "--grid", "eps=0.1,0.2", "--format", "csv", "--workers", "1"],
}


def corpus() -> list[list[str]]:
    """Every invocation of the corpus, as argv lists (without the program name)."""
    cases: list[list[str]] = [[], ["list"], ["list", "extra"], ["nope"], ["--version"], ["solve"]]
    for command, options in OPTIONS.items():
        base = BASES.get(command, [command, "duffing"])
        if command != "reproduce":
            cases.extend([[command, problem] for problem in PROBLEMS if problem != "duffing"])
            cases.extend(
                [*base, "--set", f"{name}={value}"] for name in SET_NAMES for value in VALUES
            )
        for option in options:
            cases.extend([*base, option, value] for value in VALUES)
            cases.append([*base, option])  # missing value
        cases.append([*base, "--no-such-option"])
    return cases


_NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)


def judge(argv: list[str], code: int | None, out: str, err: str) -> list[str]:
    """The broken promises of one run (empty when it behaved)."""
    broken = []
    if code is None:
        return ["hang"]
    if "Traceback" in err or "Traceback" in out:
        broken.append("traceback")
    if code not in (0, 1, 2):
        broken.append(f"exit {code}")
    if code == 2 and argv:
        lines = [
            line for line in err.strip().splitlines() if not line.startswith("perturb: warning")
        ]
        if len(lines) != 1 or not lines[0].startswith("perturb: error:"):
            broken.append("exit 2 without one error line")
    if code == 0 and argv and argv[0] in ("solve", "validate", "work-precision"):
        broken.extend(_nonsense(argv, out))
    return broken


def _nonsense(argv: list[str], out: str) -> list[str]:
    fmt = argv[argv.index("--format") + 1] if "--format" in argv[:-1] else "table"
    if fmt == "json":
        try:
            payload = json.loads(out)
        except ValueError:
            return ["exit 0 with unreadable JSON"]
        period = payload.get("period")
        if isinstance(period, int | float) and not period > 0:
            return ["exit 0 with a negative period"]
        if argv[0] == "solve" and _has_non_finite(payload):
            return ["exit 0 printing NaN/inf"]
        return []
    if argv[0] == "solve" and _NON_FINITE.search(out):
        return ["exit 0 printing NaN/inf"]
    match = re.search(r"period\s+(-?[\d.e+-]+)", out)
    if argv[0] == "solve" and match and not float(match.group(1)) > 0:
        return ["exit 0 with a negative period"]
    return []


def _has_non_finite(value) -> bool:
    if isinstance(value, dict):
        return any(_has_non_finite(v) for k, v in value.items() if k != "warnings")
    if isinstance(value, list):
        return any(_has_non_finite(v) for v in value)
    return isinstance(value, float) and not math.isfinite(value)
