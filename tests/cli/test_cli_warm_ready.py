"""A warm ``perturb validate`` reads what it needs ready to use and reports the cold run's answers.

Fresh processes, as a user's: the cold run keeps the generated functions and the compiled
integrators (kinds ``lambdified`` and ``taylor``) beside the derivations; the warm run reads every
entry back (it writes none) and its JSON report is the cold one's, timings aside.  A changed
parameter is another problem: it is derived and compiled again, not read.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from perturb.oracle.heyoka import heyoka_available

ROOT = Path(__file__).resolve().parents[2]


def _validate(tmp_path, *args) -> dict:
    env = {
        **os.environ,
        "PYTHONPATH": str(ROOT),
        "PERTURB_CACHE_DIR": str(tmp_path / "cache"),
        "PERTURB_CACHE_KEY_FILE": str(tmp_path / "key" / "cache.key"),
    }
    out = subprocess.run(
        [sys.executable, "-m", "perturb", "validate", *args, "--format", "json", "--quiet"],
        capture_output=True, text=True, env=env, cwd=ROOT, timeout=600,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    report.pop("timings")
    return report


def _entries(tmp_path) -> dict[str, int]:
    return {p.name: p.stat().st_mtime_ns for p in (tmp_path / "cache").glob("*.pkl")}


@pytest.mark.parametrize(
    ("problem", "changed"),
    [
        pytest.param(("duffing",), ("duffing", "--set", "eps=0.07"), id="duffing"),
        pytest.param(
            ("forced-duffing",),
            ("forced-duffing", "--set", "Omega=1.05"),
            id="forced-duffing",
            marks=pytest.mark.slow,  # ~10 s (tests/cli/test_cli_warm.py has the disk by default)
        ),
        pytest.param(
            ("disk", "--set", "r0=0.755155", "--set", "R=0.123299", "--set", "gamma3_0=0.25"),
            ("disk", "--set", "r0=0.8", "--set", "R=0.123299", "--set", "gamma3_0=0.25"),
            id="disk-fast-spin",
            marks=pytest.mark.slow,
        ),
    ],
)
def test_a_warm_validation_reads_everything_and_answers_alike(tmp_path, problem, changed):
    cold = _validate(tmp_path, *problem)
    written = _entries(tmp_path)
    kinds = {name.rsplit("-", 1)[0] for name in written}
    assert "lambdified" in kinds
    if heyoka_available():
        assert "taylor" in kinds
    warm = _validate(tmp_path, *problem)
    assert _entries(tmp_path) == written  # all read back, nothing rewritten
    assert warm == cold
    other = _validate(tmp_path, *changed)
    assert other["parameters"] != cold["parameters"]
    assert set(_entries(tmp_path)) > set(written)  # another point: derived, compiled, kept
