"""A scene file as input: its problem file found beside it (not in the working folder), a
byte-order mark accepted, and what is not a regular file or too large refused in one line before
anything is read (a FIFO with no writer would block the read for ever)."""

from __future__ import annotations

import os

import pytest

from perturb._defaults import MAX_TIMES, SCENE_MAX_BYTES
from perturb.cli import main
from perturb.errors import SceneError
from perturb.scene import problem_spec, read_scene
from tests.cli.hostile_files import GOOD_FILE, PROBLEM_FILES

GOOD = PROBLEM_FILES[GOOD_FILE][0]

SCENE = """[problem]
name = "{name}"
[solve]
order = 1
periods = 1
samples = 8
[outputs]
table = true
"""


def _error(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("perturb: error:"), err
    return err[0]


def test_a_problem_file_is_taken_from_the_scenes_folder(tmp_path, monkeypatch, capsys):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "user.py").write_text(GOOD)
    marker = tmp_path / "ran"
    # a file of the same name in the working folder: never run
    (tmp_path / "user.py").write_text(f"open({str(marker)!r}, 'w').write('ran')\n")
    (tmp_path / "sub" / "scene.toml").write_text(SCENE.format(name="user.py:Good"))
    monkeypatch.chdir(tmp_path)
    assert main(["report", "sub/scene.toml", "--output", "rep"]) == 0, capsys.readouterr().err
    assert not marker.exists()
    assert (tmp_path / "rep" / "solution.csv").is_file()
    # the scene copied into the folder is the scene as written
    assert 'name = "user.py:Good"' in (tmp_path / "rep" / "scene.toml").read_text()


def test_an_absolute_problem_file_and_a_name_are_left_as_written(tmp_path):
    (tmp_path / "scene.toml").write_text(SCENE.format(name="/elsewhere/user.py:Good"))
    assert problem_spec(read_scene(tmp_path / "scene.toml")) == "/elsewhere/user.py:Good"
    (tmp_path / "scene.toml").write_text(SCENE.format(name="duffing"))
    assert problem_spec(read_scene(tmp_path / "scene.toml")) == "duffing"
    (tmp_path / "scene.toml").write_text(SCENE.format(name="lib/user.py"))
    assert problem_spec(read_scene(tmp_path / "scene.toml")) == str(tmp_path / "lib" / "user.py")


def test_a_scene_saved_with_a_byte_order_mark_is_read(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_bytes(b"\xef\xbb\xbf" + SCENE.format(name="duffing").encode())
    scene = read_scene(path)
    assert scene.problem == "duffing" and scene.outputs.table


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs are POSIX")
def test_a_fifo_a_device_and_a_folder_are_refused_before_reading(tmp_path, monkeypatch, capsys):
    os.mkfifo(tmp_path / "scene.toml")  # no writer: an open for reading would block for ever
    monkeypatch.chdir(tmp_path)
    assert main(["report", "scene.toml", "--output", "rep"]) == 2
    assert "FIFO" in _error(capsys)
    for path, word in (("/dev/zero", "device"), (str(tmp_path), "folder")):
        with pytest.raises(SceneError, match=word):
            read_scene(path)
    assert not (tmp_path / "rep").exists()


def test_a_scene_too_large_is_refused_before_it_is_read(tmp_path):
    path = tmp_path / "scene.toml"
    with open(path, "wb") as file:
        file.truncate(SCENE_MAX_BYTES + 1)  # sparse: nothing written, its size past the cap
    with pytest.raises(SceneError, match="more than"):
        read_scene(path)


def test_periods_times_samples_past_the_rows_allowed_is_refused(tmp_path):
    path = tmp_path / "scene.toml"
    text = SCENE.format(name="duffing").replace("periods = 1", "periods = 1000")
    path.write_text(text.replace("samples = 8", "samples = 10000"))
    with pytest.raises(SceneError, match=f"{MAX_TIMES:,}"):
        read_scene(path)
