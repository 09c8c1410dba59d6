"""Fuzz the CLI in process (issue 10): a derandomized sample of the corpus in ``fuzz_corpus.py``.

Every invocation must end in exit 0, 1 or 2 without a traceback; an exit 2 prints one
``perturb: error:`` line; an exit 0 never prints NaN/inf or a negative period. The whole corpus, each
call in its own process with a time limit (hangs), is ``python benchmarks/fuzz_cli.py``.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from perturb import cli
from tests.cli.fuzz_corpus import corpus, judge

#: Commands whose valid runs take seconds each (integrations, sweeps, the paper): their hostile
#: variants are sampled, their valid ones are left to the benchmark runner.
SLOW = ("work-precision", "reproduce", "response", "sweep")

CASES = [argv for argv in corpus() if not (argv and argv[0] in SLOW)]


@pytest.fixture(autouse=True)
def _in_a_scratch_folder(tmp_path, monkeypatch):
    """``--output -1`` is a valid file name: written in a folder of the test's, not the clone."""
    monkeypatch.chdir(tmp_path)


@settings(
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(argv=st.sampled_from(CASES))
def test_the_cli_keeps_its_promises(capsys, argv):
    try:
        code = cli.main(list(argv))
    except SystemExit as exc:  # --help/--version style exits are argparse's, still an exit code
        code = exc.code if isinstance(exc.code, int) else 2
    out, err = capsys.readouterr()
    assert judge(argv, code, out, err) == [], (argv, code, err[-300:])


@pytest.mark.parametrize(
    "argv",
    [
        ["work-precision", "duffing", "--periods", "1e308"],
        ["work-precision", "duffing", "--repeat", "1e308"],
        ["work-precision", "duffing", "--orders", "nan"],
        ["reproduce", "paper", "--output", ""],
        ["reproduce", "paper", "--format", "xml"],
        ["response", "forced-duffing", "--sweep", "Omega=1.0:1.1:3", "--validate", "1e308"],
        ["response", "forced-duffing", "--sweep", "Omega=1.0:1.1:3", "--plot", ""],
        ["response", "forced-duffing", "--sweep", "Omega=1.0:1.1:3", "--order", "nan"],
        ["sweep", "duffing", "--grid", "eps=0.1,0.2", "--format", "csv", "--workers", "0"],
        ["sweep", "duffing", "--grid", "eps=0.1,0.2", "--format", "csv", "--timeout", "inf"],
        ["sweep", "duffing", "--grid", "eps=0.1,0.2", "--format", "csv", "--times", "nan"],
    ],
)
def test_slow_commands_refuse_hostile_values_at_once(capsys, argv):
    code = cli.main(argv)
    out, err = capsys.readouterr()
    assert code == 2 and judge(argv, code, out, err) == []
