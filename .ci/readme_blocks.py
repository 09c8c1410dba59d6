#!/usr/bin/env python3
"""Run every README block on its own, in a fresh virtual environment, as a new user would (issue 27).

Each fenced ``bash`` or ``python`` block of README.md must be preceded by a directive comment (HTML,
so it does not render) saying how it is checked::

    <!-- readme-check: venv=core expect="true orbit at eps" absent="not found" -->

Keys (values without spaces may go unquoted):

``venv=NAME``
    Run in the virtual environment NAME. A block that contains ``pip install`` creates NAME afresh
    (``python -m venv``, no system site packages), so it installs exactly what the block says; a
    block without one runs in the environment an earlier block made.
``session=NAME``
    Python blocks of one session run as one script (a later block uses an earlier one's names).
``file=PATH``
    The block is a file the README asks to save: written to PATH, not run.
``skip=REASON``
    Not run here, for the reason given (e.g. the test command, which ``.ci/run`` itself runs in a
    fresh environment).
``expect=REGEX`` / ``absent=REGEX``
    The block's output (stdout and stderr) must match / must not match.
``creates=PATH``
    The block must leave PATH behind.

Blocks run in order in a scratch copy of the checkout's files (tracked and untracked, not ignored),
so nothing they write lands in the checkout. A runnable block without a directive is an error: a
new block is checked, or its exemption is written down. Prints one row per block (what ran, how
long, the outcome) and exits 1 if any block failed.

Usage: ``python .ci/readme_blocks.py [--only N[,N...]] [--keep]`` from the root of a checkout.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: Longest a block may run (installing the docs extra and building the site is the longest, ~6 min
#: on 2 cores with a cold pip cache).
BLOCK_TIMEOUT = 40 * 60
DIRECTIVE = re.compile(r"<!--\s*readme-check:(.*?)-->", re.S)
FENCE = re.compile(r"^```(\w*)\s*$")
RUNNABLE = {"bash", "sh", "python"}
KEYS = {"venv", "session", "file", "skip", "expect", "absent", "creates"}


@dataclass
class Block:
    """One fenced block of the README and its directive."""

    line: int
    language: str
    text: str
    options: dict = field(default_factory=dict)


def parse(readme: str) -> list[Block]:
    """The fenced blocks of ``readme`` with the directive on the line before each (if any)."""
    blocks, lines = [], readme.splitlines()
    i, pending = 0, None
    while i < len(lines):
        stripped = lines[i].strip()
        found = DIRECTIVE.search(stripped)
        if found:
            pending = _options(found.group(1), i + 1)
        elif (fence := FENCE.match(stripped)) is not None:
            start, body = i, []
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            blocks.append(Block(start + 1, fence.group(1), "\n".join(body) + "\n", pending or {}))
            pending = None
        elif stripped:
            pending = None
        i += 1
    return blocks


def _options(text: str, line: int) -> dict:
    options = {}
    for item in shlex.split(text):
        key, _, value = item.partition("=")
        if key not in KEYS:
            raise SystemExit(f"README.md:{line}: unknown readme-check key {key!r} (known: {KEYS})")
        options[key] = value
    return options


def scratch_copy(target: Path) -> None:
    """The checkout's files (tracked, and untracked but not ignored) copied into ``target``."""
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT,
        capture_output=True,
        check=True,
    ).stdout.split(b"\0")
    for name in filter(None, (n.decode() for n in listed)):
        source = ROOT / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)


def run(blocks: list[Block], work: Path, only: set[int] | None) -> list[tuple]:
    venvs: dict[str, Path] = {}
    sessions: dict[str, str] = {}
    rows = []
    for number, block in enumerate(blocks, 1):
        options = block.options
        if block.language not in RUNNABLE and "file" not in options:
            continue
        label = f"{number:>2} README.md:{block.line}"
        if not options:
            rows.append((label, block.language, "-", "FAILED: no readme-check directive"))
            continue
        if "file" in options:
            (work / options["file"]).write_text(block.text)
            rows.append((label, "file", "-", f"saved as {options['file']}"))
            continue
        if "skip" in options:
            rows.append((label, block.language, "-", f"skipped: {options['skip']}"))
            continue
        if only is not None and number not in only:
            continue
        name = options.get("venv", "core")
        if "pip install" in block.text or name not in venvs:
            venvs[name] = _fresh_venv(work / ".readme-venvs" / name)
        if block.language == "python":
            key = options.get("session", f"block-{number}")
            sessions[key] = sessions.get(key, "") + block.text
            script = work / f".readme-{key}.py"
            script.write_text(sessions[key])
            command = f'python "{script}"'
        else:
            command = block.text
        started = time.perf_counter()
        outcome = _run_block(command, venvs[name], work, options)
        rows.append((label, f"{block.language} ({name})", f"{time.perf_counter() - started:.0f} s",
                     outcome))  # fmt: skip
    return rows


def _fresh_venv(path: Path) -> Path:
    if path.exists():
        shutil.rmtree(path)
    subprocess.run([sys.executable, "-m", "venv", str(path)], check=True)
    return path


def _run_block(command: str, venv: Path, work: Path, options: dict) -> str:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["VIRTUAL_ENV"] = str(venv)
    env.setdefault("MPLBACKEND", "Agg")
    try:
        done = subprocess.run(
            ["bash", "-e", "-o", "pipefail", "-c", command],
            cwd=work,
            env=env,
            capture_output=True,
            text=True,
            timeout=BLOCK_TIMEOUT,
        )
    except subprocess.TimeoutExpired:
        return f"FAILED: still running after {BLOCK_TIMEOUT} s"
    output = done.stdout + done.stderr
    problems = []
    if done.returncode != 0:
        problems.append(f"exit {done.returncode}")
    if "expect" in options and not re.search(options["expect"], output):
        problems.append(f"output lacks /{options['expect']}/")
    if "absent" in options and re.search(options["absent"], output):
        problems.append(f"output has /{options['absent']}/")
    if "creates" in options and not (work / options["creates"]).exists():
        problems.append(f"{options['creates']} was not written")
    if problems:
        tail = "\n".join(output.strip().splitlines()[-25:])
        return f"FAILED: {'; '.join(problems)}\n{tail}"
    return "ok"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", help="run only these block numbers (comma-separated)")
    parser.add_argument("--keep", action="store_true", help="keep the scratch folder")
    args = parser.parse_args(argv)
    only = {int(n) for n in args.only.split(",")} if args.only else None
    blocks = parse((ROOT / "README.md").read_text())
    work = Path(tempfile.mkdtemp(prefix="readme-blocks-"))
    try:
        scratch_copy(work)
        rows = run(blocks, work, only)
    finally:
        if args.keep:
            print(f"scratch folder kept: {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)
    width = max(len(r[0]) for r in rows)
    for label, language, seconds, outcome in rows:
        print(f"{label:<{width}}  {language:<18} {seconds:>6}  {outcome}")
    failed = [r for r in rows if r[3].startswith("FAILED")]
    print(f"{len(rows)} README blocks: {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
