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
from perturb.report.folder import MARKER

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


# ---------------------------------------------------------------------------------- crafted markers
# The marker is a claim, not a licence: a file or store is replaced only while its content is what
# perturb recorded; a null, missing or mismatched record, or "claimed, not yet written", protects it.
def _marker(folder: Path) -> dict:
    return json.loads((folder / MARKER).read_text())


def _craft(folder: Path, **changes) -> None:
    marker = _marker(folder)
    for key, value in changes.items():
        marker[key] = value
    (folder / MARKER).write_text(json.dumps(marker))


VALIDATION_SCENE = "table = true\nvalidation = true"


@pytest.mark.parametrize("record", [None, "0" * 64, [], 17, {"sha256": None}, ["x"]])
@pytest.mark.parametrize("force", [False, True])
def test_a_users_file_under_a_null_or_wrong_record_is_kept(capsys, tmp_path, record, force):
    scene = _scene(tmp_path)
    folder = tmp_path / "out"
    assert _report(capsys, scene, folder)[0] == 0
    files = _marker(folder)["files"]
    files["solution.csv"] = record
    _craft(folder, files=files)
    (folder / "solution.csv").write_text("t,x\nmine\n")
    before = _digests(folder)
    code, out, err = _report(capsys, scene, folder, *(("--force",) if force else ()))
    _refused(code, out, err, "solution.csv")
    assert _digests(folder) == before


def test_an_interrupted_report_leaves_the_users_later_file_alone(capsys, tmp_path):
    """A report killed while it wrote leaves names "claimed, not yet written" (null) in its
    marker; the user then saves a file of that name: the same scene run again refuses."""
    scene = _scene(tmp_path, "table = true\nlatex = true")
    folder = tmp_path / "out"
    assert _report(capsys, scene, folder)[0] == 0
    files = _marker(folder)["files"]
    files["solution.tex"] = None  # as a kill between the claim and the write leaves it
    _craft(folder, files=files)
    (folder / "solution.tex").write_text("my own notes\n")
    before = _digests(folder)
    for extra in ((), ("--force",)):
        code, out, err = _report(capsys, scene, folder, *extra)
        _refused(code, out, err, "solution.tex")
        assert _digests(folder) == before
    # a claimed name left over, not asked for this time: a user's file there is not removed
    scene.write_text(SCENE.format(outputs="table = true"), encoding="utf-8")
    code, _, err = _report(capsys, scene, folder)
    assert code == 0, err
    assert (folder / "solution.tex").read_text() == "my own notes\n"


def test_a_crafted_marker_cannot_claim_a_path_outside_the_folder(capsys, tmp_path):
    scene = _scene(tmp_path)
    folder = tmp_path / "out"
    assert _report(capsys, scene, folder)[0] == 0
    outside = tmp_path / "solution.csv"
    outside.write_text("mine\n")
    digest = hashlib.sha256(outside.read_bytes()).hexdigest()
    _craft(folder, files={"../solution.csv": digest, "..": digest, "/etc/passwd": digest})
    before = _digests(tmp_path)
    code, _, err = _report(capsys, scene, folder)
    _refused(code, "", err, "scene.toml")  # the report's own files are no longer known
    assert _digests(tmp_path) == before


def test_a_file_saved_while_the_report_computes_is_kept(capsys, tmp_path, monkeypatch):
    """The folder is claimed before the work; a file the user puts there meanwhile is looked at
    again before it would be replaced: a clash, the file kept."""
    import perturb.scene.run as run

    scene = _scene(tmp_path)
    folder = tmp_path / "out"
    assert _report(capsys, scene, folder)[0] == 0
    real = run.run_scene

    def slow(*args, **kwargs):
        result = real(*args, **kwargs)
        (folder / "solution.csv").write_text("saved meanwhile\n")
        return result

    monkeypatch.setattr(run, "run_scene", slow)
    code = main(["report", str(scene), "--output", str(folder)])
    err = capsys.readouterr().err
    assert code == 2 and "solution.csv" in err and err.count("\n") == 1, err
    assert (folder / "solution.csv").read_text() == "saved meanwhile\n"


SWEEP_SCENE = (
    '[problem]\nname = "duffing"\n[sweep]\ngrid = ["eps=0.05,0.1"]\nworkers = 1\n'
    "[outputs]\nsweep = true\n"
)


@pytest.fixture
def sweep_report(capsys, tmp_path):
    pytest.importorskip("distributed")
    pytest.importorskip("zarr")
    scene = tmp_path / "scene.toml"
    scene.write_text(SWEEP_SCENE, encoding="utf-8")
    folder = tmp_path / "out"
    code, _, err = _report(capsys, scene, folder)
    assert code == 0, err
    return scene, folder


def test_a_sweep_report_is_replaced_by_its_own_scene(capsys, sweep_report):
    scene, folder = sweep_report
    first = _marker(folder)
    assert first["store_fingerprints"]["sweep.zarr"]
    code, _, err = _report(capsys, scene, folder)
    assert code == 0, err
    assert _marker(folder)["stores"]["sweep.zarr"] != first["stores"]["sweep.zarr"]


@pytest.mark.parametrize(
    "craft",
    ["null token", "null fingerprint", "no fingerprint", "wrong fingerprint", "changed store"],
)
@pytest.mark.parametrize("force", [False, True])
def test_a_store_not_known_to_be_ours_is_kept(capsys, sweep_report, craft, force):
    import zarr

    scene, folder = sweep_report
    marker = _marker(folder)
    if craft == "null token":
        marker["stores"]["sweep.zarr"] = None
    elif craft == "null fingerprint":
        marker["store_fingerprints"]["sweep.zarr"] = None
    elif craft == "no fingerprint":
        del marker["store_fingerprints"]
    elif craft == "wrong fingerprint":
        marker["store_fingerprints"]["sweep.zarr"] = "0" * 64
    else:  # the user added an array of their own to the store perturb wrote
        group = zarr.open_group(str(folder / "sweep.zarr"), mode="r+")
        group.create_array("mine", shape=(2,), dtype="int32")[...] = [4, 2]
    (folder / MARKER).write_text(json.dumps(marker))
    before = _digests(folder)
    code, out, err = _report(capsys, scene, folder, *(("--force",) if force else ()))
    _refused(code, out, err, "sweep.zarr")
    assert _digests(folder) == before


def test_a_users_complete_store_under_a_null_token_is_kept(capsys, tmp_path):
    zarr = pytest.importorskip("zarr")
    scene = tmp_path / "scene.toml"
    scene.write_text(SWEEP_SCENE, encoding="utf-8")
    folder = tmp_path / "out"
    mine = zarr.open_group(str(folder / "sweep.zarr"), mode="w", attributes={"perturb_sweep": 1})
    mine.create_array("session", shape=(3,), dtype="int32")[...] = [1, 2, 3]
    (folder / MARKER).write_text(json.dumps({
        "perturb_report": 1, "scene": str(scene.resolve()), "files": {},
        "stores": {"sweep.zarr": None}, "store_fingerprints": {"sweep.zarr": None},
    }))  # fmt: skip
    before = _digests(folder)
    for extra in ((), ("--force",)):
        code, out, err = _report(capsys, scene, folder, *extra)
        _refused(code, out, err, "sweep.zarr")
        assert _digests(folder) == before
