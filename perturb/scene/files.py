"""A scene read from its file: only a regular file under a size cap (a FIFO, a device, a folder
refused in one line before anything is read), UTF-8 with or without a byte-order mark; relative
paths inside it (a problem file) are taken from the scene file's folder, not the working folder.
"""

from __future__ import annotations

import os

from perturb._defaults import SCENE_MAX_BYTES
from perturb.errors import SceneError
from perturb.scene.spec import Scene, parse_scene

__all__ = ["problem_spec", "read_scene"]

#: The suffix that marks a problem named by its file (as ``perturb solve FILE.py:Class`` does).
_PY_SUFFIX = ".py"


def read_scene(path) -> Scene:
    """The :class:`~perturb.scene.spec.Scene` in the file ``path`` (UTF-8 TOML, a byte-order mark
    allowed); see :func:`~perturb.scene.spec.parse_scene`. Its :attr:`folder` is the scene
    file's: :func:`problem_spec` takes a relative problem file from there.

    Raises
    ------
    perturb.errors.SceneError
        The file cannot be read (missing, a folder, a FIFO or a device, larger than
        :data:`~perturb._defaults.SCENE_MAX_BYTES`) or decoded, or its content is not a valid
        scene.
    """
    from perturb._files import UnreadableFile, read_capped

    try:
        text = read_capped(path, SCENE_MAX_BYTES).decode("utf-8-sig")  # a byte-order mark read
    except UnreadableFile as exc:
        raise SceneError(f"{path}: cannot read the scene file ({exc}); check the path") from None
    except UnicodeDecodeError:
        raise SceneError(f"{path}: the scene file is not UTF-8 text; save it as UTF-8") from None
    folder = os.path.dirname(os.path.abspath(os.fspath(path)))
    return parse_scene(text, str(path), folder)


def problem_spec(scene: Scene) -> str:
    """The scene's problem as :func:`problems.load_problem` takes it: a relative problem file
    (``file.py`` or ``file.py:Class``) joined to the scene's folder; a name, a module or an
    absolute path as written.

    Examples
    --------
    >>> from perturb.scene import parse_scene
    >>> scene = parse_scene('[problem]\\nname = "user.py:Mine"', folder="/data/scenes")
    >>> problem_spec(scene)
    '/data/scenes/user.py:Mine'
    """
    spec, folder = scene.problem, scene.folder
    if not folder:
        return spec
    if spec.endswith(_PY_SUFFIX):
        target, tail = spec, ""
    else:
        target, sep, name = spec.rpartition(":")
        if not sep or not target.endswith(_PY_SUFFIX):
            return spec
        tail = f":{name}"
    path = os.path.expanduser(target)
    if os.path.isabs(path):
        return spec
    return os.path.join(folder, path) + tail
