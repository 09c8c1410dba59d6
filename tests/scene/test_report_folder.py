"""A report folder never loses what perturb did not write (issue 31, item 1).

The folder is created fresh, or recognised as an earlier report of the same scene by the marker
perturb writes there; a file the report would write or remove that perturb did not write (or that
changed since) is a clash: one line, exit 2, before any work, the file left as it was. The report
of another scene needs ``--force``, which replaces perturb's own files only.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest

from perturb.cli import main
from perturb.report.written import MARKER

SCENE = """[problem]
name = "duffing"
[parameters]
eps = 0.05
[solve]
periods = 1
samples = 8
[outputs]
{outputs}
"""


def _scene(folder: Path, outputs: str = "table = true", name: str = "scene.toml") -> Path:
    path = folder / name
    path.write_text(SCENE.format(outputs=outputs), encoding="utf-8")
    return path


def _report(capsys, scene: Path, folder, *extra) -> tuple[int, str, str]:
    code = main(["report", str(scene), "--output", str(folder), *extra])
    out, err = capsys.readouterr()
    return code, out, err


def _digests(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def _refused(code: int, out: str, err: str, *words: str) -> None:
    assert code == 2 and out == "", err
    assert err.startswith("perturb: error: --output") and err.count("\n") == 1, err
    for word in words:
        assert word in err, err


@pytest.mark.parametrize(
    "name", ["solution.csv", "solution.json", "summary.md", "scene.toml", "time_series.png"]
)
def test_a_users_file_with_a_report_name_is_a_clash(capsys, tmp_path, name):
    scene = _scene(tmp_path, "table = true\nplots = ['time_series']", name="my-scene.toml")
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / name).write_text("the user's own work\n")
    (folder / "notes.txt").write_text("mine too\n")
    before = _digests(folder)
    code, out, err = _report(capsys, scene, folder)
    _refused(code, out, err, name, "not written by perturb")
    assert _digests(folder) == before  # nothing removed, changed or added
    # --force replaces perturb's own files only: the user's stays, the clash stays
    code, out, err = _report(capsys, scene, folder, "--force")
    _refused(code, out, err, name)
    assert _digests(folder) == before


def test_a_stale_report_name_the_user_wrote_is_not_removed(capsys, tmp_path):
    """A report that does not ask for a table must not remove a user's solution.csv either."""
    scene = _scene(tmp_path, "latex = true", name="my-scene.toml")
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / "solution.csv").write_text("t,x\n0,1\n")
    code, _, err = _report(capsys, scene, folder)
    assert code == 0, err
    assert (folder / "solution.csv").read_text() == "t,x\n0,1\n"
    assert (folder / "solution.tex").exists()
    marker = json.loads((folder / MARKER).read_text())
    assert "solution.csv" not in marker["files"]


def test_the_current_folder_keeps_the_users_files(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene = _scene(tmp_path, "table = true", name="my-scene.toml")
    Path("solution.csv").write_text("mine\n")
    before = _digests(tmp_path)
    code, out, err = _report(capsys, scene, ".")
    _refused(code, out, err, "solution.csv")
    assert _digests(tmp_path) == before


def test_an_earlier_report_of_the_scene_is_replaced(capsys, tmp_path):
    scene = _scene(tmp_path, "table = true\nlatex = true")
    folder = tmp_path / "out"
    assert _report(capsys, scene, folder)[0] == 0
    (folder / "notes.txt").write_text("mine")
    scene.write_text(SCENE.format(outputs="latex = true"), encoding="utf-8")
    code, _, err = _report(capsys, scene, folder)
    assert code == 0, err
    names = sorted(p.name for p in folder.iterdir())
    assert names == [MARKER, "notes.txt", "scene.toml", "solution.tex", "summary.md"]
    assert (folder / "notes.txt").read_text() == "mine"
    marker = json.loads((folder / MARKER).read_text())
    assert marker["scene"] == str(scene.resolve())
    for name, digest in marker["files"].items():
        assert hashlib.sha256((folder / name).read_bytes()).hexdigest() == digest


def test_a_file_of_the_report_changed_by_the_user_is_theirs(capsys, tmp_path):
    scene = _scene(tmp_path)
    folder = tmp_path / "out"
    assert _report(capsys, scene, folder)[0] == 0
    with (folder / "solution.csv").open("a") as fh:
        fh.write("my annotation\n")
    before = _digests(folder)
    for extra in ((), ("--force",)):
        code, out, err = _report(capsys, scene, folder, *extra)
        _refused(code, out, err, "solution.csv", "changed since")
        assert _digests(folder) == before


def test_another_scenes_report_needs_force(capsys, tmp_path):
    first, second = _scene(tmp_path, name="a.toml"), _scene(tmp_path, name="b.toml")
    folder = tmp_path / "out"
    assert _report(capsys, first, folder)[0] == 0
    before = _digests(folder)
    code, out, err = _report(capsys, second, folder)
    _refused(code, out, err, "another scene", "--force", "a.toml")
    assert _digests(folder) == before
    code, _, err = _report(capsys, second, folder, "--force")
    assert code == 0, err
    assert json.loads((folder / MARKER).read_text())["scene"] == str(second.resolve())


def test_another_sweeps_store_named_sweep_zarr_is_kept(capsys, tmp_path):
    zarr = pytest.importorskip("zarr")
    scene = tmp_path / "scene.toml"
    scene.write_text(
        '[problem]\nname = "duffing"\n[sweep]\ngrid = ["eps=0.05,0.1"]\n[outputs]\nsweep = true\n',
        encoding="utf-8",
    )
    folder = tmp_path / "out"
    other = zarr.open_group(str(folder / "sweep.zarr"), mode="w", attributes={"perturb_sweep": 1})
    other.create_array("session", shape=(3,), dtype="int32")[...] = [1, 2, 3]
    before = _digests(folder)
    code, out, err = _report(capsys, scene, folder)
    _refused(code, out, err, "sweep.zarr")
    assert _digests(folder) == before


def test_a_marker_perturb_did_not_write_is_refused(capsys, tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / MARKER).write_text("{not json")
    code, out, err = _report(capsys, _scene(tmp_path), folder)
    _refused(code, out, err, MARKER)
    assert (folder / MARKER).read_text() == "{not json"


@pytest.mark.parametrize("output", ["", "   "])
def test_an_empty_folder_name_is_refused(capsys, tmp_path, monkeypatch, output):
    monkeypatch.chdir(tmp_path)
    code, out, err = _report(capsys, _scene(tmp_path), output)
    _refused(code, out, err, "name a folder")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.toml"]
