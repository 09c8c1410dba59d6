"""The hostile corpus (issue 31): careless and hostile invocations of the newer surfaces, each
judged by the table of :mod:`tests.cli.hostile_corpus` (exit 2 one line, exit 1 with a reason, a
sane exit 0, no user file touched, no file outside the output, an end within the bound).

The default suite runs a fixed sample of the refusals in this process (each is refused before any
work, in a second or two); ``pytest -m slow`` runs every case in a fresh process and folder with
its time bound (``python benchmarks/hostile_cli.py`` prints the table of the whole corpus).
"""

from __future__ import annotations

import os
from collections import Counter
from pathlib import Path

import pytest

from perturb.cli import main
from tests.cli.hostile_corpus import CLASSES, Case, corpus, judge, prepare, run_case, snapshot

CASES = corpus()
#: Every 12th refusal that needs no server and no cluster: about 25 cases of every surface.
SAMPLE = [
    case
    for case in CASES
    if case.expect == "usage" and not case.server and "--scheduler" not in case.argv
][::12]


def test_the_corpus_covers_every_surface_and_class():
    surfaces = Counter(case.surface for case in CASES)
    assert set(surfaces) == {"response", "sweep", "report", "user-file", "driven"}
    assert all(count >= 30 for count in surfaces.values()), surfaces
    assert {case.expect for case in CASES} <= set(CLASSES)
    assert len({case.name for case in CASES}) > 0.95 * len(CASES)  # hardly any repeated
    assert {case.surface for case in SAMPLE} >= {"response", "sweep", "report", "user-file"}


def _in_process(case: Case, folder, monkeypatch, capsys):
    before = prepare(case, folder)
    monkeypatch.chdir(folder)
    code = None
    for _ in range(2 if case.twice else 1):
        try:
            code = main(list(case.argv))
        except SystemExit as exc:  # argparse's own exits (--help) are exit codes too
            code = exc.code if isinstance(exc.code, int) else 2
    out, err = capsys.readouterr()
    return judge(case, code, out, err, before, snapshot(folder))


@pytest.mark.parametrize("case", SAMPLE, ids=[c.name[:90] for c in SAMPLE])
def test_a_sample_keeps_its_promises(tmp_path, monkeypatch, capsys, case):
    assert _in_process(case, tmp_path, monkeypatch, capsys) == []


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES, ids=[c.name[:90] for c in CASES])
def test_every_case_keeps_its_promises(tmp_path, case):
    root = str(Path(__file__).resolve().parents[2])
    env = {"PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))}
    outcome = run_case(case, tmp_path, env)
    assert outcome.broken == [], (outcome.err[-400:], outcome.out[-200:])
