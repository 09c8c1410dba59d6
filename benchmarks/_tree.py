"""What the benchmark scripts share: a git revision as a folder, a timed fresh interpreter on a tree."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def export(rev: str, folder: str) -> Path:
    """The tree of git revision ``rev`` written into ``folder`` (``git archive``: the checkout is
    not touched)."""
    archive = subprocess.run(
        ["git", "-C", str(ROOT), "archive", rev], capture_output=True, check=True
    ).stdout
    subprocess.run(["tar", "-x", "-C", folder], input=archive, check=True)
    return Path(folder)


def run_child(
    tree: Path, args: list[str], env: dict, timeout: float
) -> tuple[float, subprocess.CompletedProcess]:
    """Run ``python *args`` in ``tree`` (on its ``PYTHONPATH``) with ``env`` added.

    Returns the child's process CPU seconds (user + system, its own children included) and the
    completed process (its exit code unchecked).
    """
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [sys.executable, *args],
        capture_output=True,
        text=True,
        cwd=tree,
        env={**os.environ, "PYTHONPATH": str(tree), **env},
        timeout=timeout,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out
