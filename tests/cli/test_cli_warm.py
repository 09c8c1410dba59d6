"""A warm ``perturb validate disk`` (cache filled) gives the cold run's report, to the bit.

Each run is a fresh process, as a user's would be; the cache folder and signing key are private to
the test. The warm run must read every derivation back (it writes no entry) and report the same
verdict and the same numbers (JSON floats are exact), timings aside.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: What a cold ``validate disk`` keeps on disk (the true-orbit kinds only when it shoots).
KINDS = ("reduction", "solution", "body-potential", "body-rhs", "body-dimensional", "jacobian")
SHOOTING_KINDS = ("true-orbit-rhs", "variational", "forward-map")


def _validate(tmp_path, *extra, returncode: int = 0) -> dict:
    env = {
        **os.environ,
        "PYTHONPATH": str(ROOT),
        "PERTURB_CACHE_DIR": str(tmp_path / "cache"),
        "PERTURB_CACHE_KEY_FILE": str(tmp_path / "key" / "cache.key"),
    }
    out = subprocess.run(
        [sys.executable, "-m", "perturb", "validate", "disk", "--format", "json", *extra],
        capture_output=True, text=True, env=env, cwd=ROOT, timeout=300,
    )  # fmt: skip
    assert out.returncode == returncode, out.stderr
    report = json.loads(out.stdout)
    report.pop("timings")
    return report


def _entries(tmp_path) -> dict[str, int]:
    return {p.name: p.stat().st_mtime_ns for p in (tmp_path / "cache").glob("*.pkl")}


def _warm_equals_cold(tmp_path, extra, kinds, returncode: int = 0):
    cold = _validate(tmp_path, *extra, returncode=returncode)
    written = _entries(tmp_path)
    for kind in kinds:
        assert any(name.startswith(f"{kind}-") for name in written), kind
    warm = _validate(tmp_path, *extra, returncode=returncode)
    assert _entries(tmp_path) == written  # everything read back, nothing recomputed or rewritten
    assert warm == cold
    return warm


def test_warm_validate_disk_reports_what_the_cold_run_did(tmp_path):
    # the paper's eps = 232: the series has broken down, and its initial state (through the
    # order-4 inverse map that order 1 now needs for the P-branch's O(eps^2) term) overflows the
    # integration at t = 0, so the run fails (exit 1) with an INVALID verdict, warm as cold
    report = _warm_equals_cold(tmp_path, (), KINDS, returncode=1)
    assert report["outcome"] == "invalid" and not report["completed"]


def test_warm_validate_disk_with_the_true_orbit_reports_what_the_cold_run_did(tmp_path):
    report = _warm_equals_cold(tmp_path, ("--set", "r0=30.2"), KINDS + SHOOTING_KINDS)
    assert report["outcome"] == "valid"
    assert report["periodic_orbit"]["initial_state"]  # the conditioned shooting ran
