"""``--output FILE`` and ``--plot FILE`` (issue 31, items 1 and 3): checked before any work, never
over a file perturb did not write unless ``--force``, written whole or not at all."""

from __future__ import annotations

import json

import pytest

from perturb.cli import main
from perturb.report import written


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _one_error(code, out, err, *words):
    assert code == 2 and out == "", err
    assert err.startswith("perturb: error:") and err.count("\n") == 1, err
    for word in words:
        assert word in err, err


SOLVE = ("solve", "duffing", "--times", "0,1", "--format", "json")


def test_a_users_file_is_refused_then_replaced_with_force(capsys, tmp_path):
    target = tmp_path / "mine.json"
    target.write_text("the user's data\n")
    _one_error(*run(capsys, *SOLVE, "--output", target), "not written by perturb", "--force")
    assert target.read_text() == "the user's data\n"
    code, _, err = run(capsys, *SOLVE, "--output", target, "--force")
    assert code == 0, err
    assert json.loads(target.read_text())["problem"] == "duffing"


def test_perturbs_own_output_is_overwritten_and_a_changed_one_is_not(capsys, tmp_path):
    target = tmp_path / "out.json"
    assert run(capsys, *SOLVE, "--output", target)[0] == 0
    assert written.is_ours(target)
    code, _, err = run(capsys, "solve", "duffing", "--times", "0", "--format", "csv", "--output",
                       target)  # fmt: skip
    assert code == 0, err
    assert target.read_text().startswith("t,x,xdot")
    target.write_text(target.read_text() + "my note\n")  # now the user's
    assert not written.is_ours(target)
    _one_error(*run(capsys, *SOLVE, "--output", target), "changed since")


def test_an_empty_file_holds_nothing_to_lose(capsys, tmp_path):
    target = tmp_path / "empty.json"
    target.touch()
    code, _, err = run(capsys, *SOLVE, "--output", target)
    assert code == 0, err and json.loads(target.read_text())


def test_without_a_record_an_existing_file_needs_force(capsys, tmp_path, monkeypatch):
    monkeypatch.setenv("PERTURB_CACHE_DIR", "off")  # no record of what perturb wrote
    target = tmp_path / "out.json"
    assert run(capsys, *SOLVE, "--output", target)[0] == 0
    _one_error(*run(capsys, *SOLVE, "--output", target), "--force")
    assert run(capsys, *SOLVE, "--output", target, "--force")[0] == 0


@pytest.mark.parametrize(
    ("path", "words"),
    [
        ("", "name a file"),
        ("   ", "name a file"),
        ("{tmp}/missing/out.json", "does not exist"),
        ("{tmp}", "is a folder"),
    ],
)
def test_bad_output_paths_are_one_line(capsys, tmp_path, path, words):
    _one_error(*run(capsys, *SOLVE, "--output", path.format(tmp=tmp_path)), "--output", words)


@pytest.fixture
def no_work(monkeypatch):
    """Fail the test if the response is computed: --plot must be refused before any work."""
    import perturb.response.model

    def computed(*args, **kwargs):
        raise AssertionError("the response was computed before --plot was checked")

    monkeypatch.setattr(perturb.response.model, "problem_response", computed)


@pytest.mark.parametrize(
    ("plot", "words"),
    [
        ("", "name a file"),
        ("/proc/nowhere/r.png", "does not exist"),
        ("{tmp}/r.xyz", "'xyz' is unknown"),
        ("{tmp}/r", "no extension"),
        ("{tmp}", "is a folder"),
        ("{tmp}/mine.png", "not written by perturb"),
    ],
)
def test_plot_paths_are_checked_before_any_work(capsys, tmp_path, no_work, plot, words):
    pytest.importorskip("matplotlib")
    (tmp_path / "mine.png").write_bytes(b"the user's picture")
    argv = ["response", "forced-duffing", "--sweep", "Omega=0.9:1.1:3", "--plot",
            plot.format(tmp=tmp_path)]  # fmt: skip
    _one_error(*run(capsys, *argv), "--plot", words)
    assert (tmp_path / "mine.png").read_bytes() == b"the user's picture"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.png"]


def test_a_plot_is_written_in_its_extensions_format_and_recorded(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    target = tmp_path / "r.svg"
    argv = ["response", "forced-duffing", "--sweep", "Omega=1.0:1.1:3", "--plot", target]
    code, _, err = run(capsys, *argv)
    assert code == 0, err
    assert target.read_text().lstrip().startswith("<?xml") and written.is_ours(target)
    assert run(capsys, *argv)[0] == 0  # perturb's own plot: replaced without --force
