"""A scene's checks, each failing with one line that names the file, the line where the value
stands, the value and the fix: :class:`Checker` (the type of one section's values, used by the
parser :mod:`perturb.scene.spec`) and the names of a scene against its problem
(:func:`check_parameter_names`, :func:`check_sweep_names`: the caller knows the problem, this
package does not). The scene is a :class:`perturb.scene.spec.Scene`, which imports this module.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterable

from perturb._defaults import SCENE_SUGGESTION_CUTOFF
from perturb.errors import SceneError

__all__ = ["Checker", "check_parameter_names", "check_sweep_names", "close_name", "line_of"]


def close_name(name: str, names: Iterable[str]) -> str:
    """`` (did you mean 'X'?)`` for the known name closest to ``name`` (difflib), or ``""``."""
    close = difflib.get_close_matches(name, list(names), n=1, cutoff=SCENE_SUGGESTION_CUTOFF)
    return f" (did you mean {close[0]!r}?)" if close else ""


class Checker:
    """Type checks of one section's values; each returns the value converted or raises."""

    def __init__(self, source: str, text: str, section: str):
        self.source, self.text, self.section = source, text, section

    def fail(self, key: str | None, value: object, fix: str) -> SceneError:
        line = line_of(self.text, self.section, key)
        where = f"line {line}: " if line else ""
        name = f"[{self.section}] {key}" if key else f"[{self.section}]"
        shown = repr(value)
        if len(shown) > 60:
            shown = shown[:57] + "..."
        return SceneError(f"{self.source}: {where}{name} = {shown} is invalid: {fix}")

    def boolean(self, key: str, value: object) -> bool:
        if not isinstance(value, bool):
            raise self.fail(key, value, "write true or false")
        return value

    def string(self, key: str, value: object) -> str:
        if not isinstance(value, str) or not value.strip():
            raise self.fail(key, value, 'write a non-empty string in quotes, e.g. "disk"')
        return value.strip()

    def integer(self, key: str, value: object, low: int, high: int) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            raise self.fail(key, value, f"write a whole number from {low} to {high}")
        return value

    def positive(self, key: str, value: object, high: float = math.inf) -> float:
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        if not ok or not (math.isfinite(value) and 0 < value <= high):
            limit = f" and at most {high:g}" if math.isfinite(high) else ""
            raise self.fail(key, value, f"write a finite number > 0{limit}")
        return float(value)

    def names(self, key: str, value: object, known: tuple[str, ...]) -> tuple[str, ...]:
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise self.fail(key, value, f"write a list of names in quotes, from {list(known)}")
        for item in value:
            if item not in known:
                raise self.fail(
                    key, item, f"unknown name{close_name(item, known)}; choose from {list(known)}"
                )
        if len(set(value)) != len(value):
            raise self.fail(key, value, "name each entry once")
        return tuple(value)


def line_of(text: str, section: str, key: str | None) -> int | None:
    """The line (1-based) of ``key`` in ``[section]`` (of the header if ``key`` is None), if found."""
    current = None
    header = re.compile(r"^\s*\[\s*([^\[\]]+?)\s*\]")
    for number, line in enumerate(text.splitlines(), start=1):
        match = header.match(line)
        if match:
            current = match.group(1).strip().strip("\"'")
            if key is None and current == section:
                return number
            continue
        if key is not None and current == section:
            if re.match(rf"^\s*[\"']?{re.escape(key)}[\"']?\s*=", line):
                return number
    return None


def check_sweep_names(scene, known: Iterable[str], problem: str) -> None:
    """Raise :class:`SceneError` unless every ``[sweep]`` axis names a parameter once (the closest
    name suggested), none also set in ``[parameters]``."""
    if scene.sweep is None:
        return
    from perturb.errors import InvalidParameterError, UnknownNameError
    from perturb.sweep.grid import check_names, parse_axis

    try:
        axes = [parse_axis(axis) for axis in scene.sweep.grid]
        check_names(axes, list(known), problem, fixed=set(scene.parameters))
    except (UnknownNameError, InvalidParameterError) as exc:
        line = line_of(scene.text, "sweep", "grid")
        where = f"line {line}: " if line else ""
        raise scene.error(f"{where}[sweep] {exc}") from None


def check_parameter_names(scene, known: Iterable[str], problem: str) -> None:
    """Raise :class:`SceneError` unless every ``[parameters]`` key is one of ``known``.

    The caller knows the problem (the CLI loads it); the message suggests the closest name.
    """
    known = list(known)
    for name in scene.parameters:
        if name not in known:
            line = line_of(scene.text, "parameters", name)
            where = f"line {line}: " if line else ""
            raise scene.error(
                f"{where}unknown parameter {name!r} of {problem}{close_name(name, known)}; the "
                f"parameters are {', '.join(known)}"
            )
