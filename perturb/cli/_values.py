"""Reading option values: ``--set``, ``--order``, ``--times``, positive numbers."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

from perturb._defaults import MAX_ORDER, MAX_TIMES, TIMES_FILE_MAX_BYTES
from perturb._install import install_hint, installed
from perturb.cli._errors import _UsageError


def _parse_sets(items: Sequence[str]) -> dict[str, float]:
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise _UsageError(f"--set {item!r}: write NAME=VALUE, e.g. --set eps=0.1")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise _UsageError(
                f"--set {item!r}: {value!r} is not a number; write NAME=VALUE with a real VALUE"
            ) from None
    return out


def _parse_order(text: str) -> int:
    try:
        order = int(text)
    except ValueError:
        raise _UsageError(f"--order {text!r} is not an integer: give an integer >= 1") from None
    if not 1 <= order <= MAX_ORDER:  # the engine's own bound, checked before any work
        raise _UsageError(f"--order {order} is invalid: give an integer from 1 to {MAX_ORDER}")
    return order


def _read_times_file(text: str) -> str:
    name = text[1:]
    if not name:
        raise _UsageError("--times '@': name a file after @, e.g. --times @times.txt")
    from perturb._files import UnreadableFile, read_capped

    try:
        content = read_capped(name, TIMES_FILE_MAX_BYTES).decode("utf-8-sig")
    except UnreadableFile as exc:
        raise _UsageError(f"--times {text!r}: cannot read {name!r} ({exc})") from None
    except UnicodeDecodeError:
        raise _UsageError(f"--times {text!r}: {name!r} is not UTF-8 text") from None
    lines = (line.split("#", 1)[0] for line in content.splitlines())
    return ",".join(item for line in lines for item in line.split(","))


def _parse_number(flag: str, text: str, item: str) -> float:
    try:
        value = float(item)
    except ValueError:
        raise _UsageError(
            f"{flag} {text!r}: {item.strip()!r} is not a number; give T1,T2,..., START:STOP:N "
            "or @FILE"
        ) from None
    if not math.isfinite(value):
        raise _UsageError(f"{flag} {text!r}: {item.strip()!r} is not finite; give finite times")
    return value


def _parse_times(text: str | None):
    """``--times``: ``T1,T2,...``, ``START:STOP:N`` or ``@FILE`` (an array, or None)."""
    import numpy as np  # lazily: `--help` and argument errors do not load numpy

    if text is None:
        return None
    spec = _read_times_file(text) if text.startswith("@") else text
    if ":" in spec and not text.startswith("@"):
        parts = spec.split(":")
        if len(parts) != 3:
            raise _UsageError(f"--times {text!r}: write START:STOP:N, e.g. --times 0:10:1001")
        start, stop = (_parse_number("--times", text, p) for p in parts[:2])
        try:
            count = int(parts[2])
        except ValueError:
            raise _UsageError(
                f"--times {text!r}: N = {parts[2].strip()!r} must be a whole number >= 1"
            ) from None
        if not 1 <= count <= MAX_TIMES:
            raise _UsageError(f"--times {text!r}: N must be between 1 and {MAX_TIMES}")
        with np.errstate(all="ignore"):  # an overflowing range is reported just below
            values = np.linspace(start, stop, count)
        if not np.all(np.isfinite(values)):
            raise _UsageError(f"--times {text!r}: the times overflow; give a smaller range")
        return values
    items = [v for v in spec.split(",") if v.strip()]
    if not items:
        raise _UsageError(f"--times {text!r}: give at least one time")
    if len(items) > MAX_TIMES:
        raise _UsageError(f"--times {text!r}: at most {MAX_TIMES} times")
    return np.array([_parse_number("--times", text, v) for v in items], dtype=float)


def _parse_positive(flag: str, text: str, kind=float):
    try:
        value = kind(text)
    except ValueError:
        raise _UsageError(
            f"{flag} {text!r} is not a number: give a positive {kind.__name__}"
        ) from None
    if not value > 0 or value != value or value == float("inf"):
        raise _UsageError(f"{flag} {text!r} is invalid: give a finite value > 0")
    return value


def _parse_output(flag: str, text: str | None) -> Path | None:
    """An output folder: a non-empty path that is not an existing file (created when written)."""
    if text is None:
        return None
    if not text.strip():
        raise _UsageError(f"{flag} {text!r}: name a folder, e.g. {flag} results")
    path = Path(text)
    if path.exists() and not path.is_dir():
        raise _UsageError(f"{flag} {text!r} is an existing file: name a folder")
    return path


def _check_plot(args) -> Path | None:
    """``--plot FILE``, checked before any work: matplotlib installed, the path writable and not
    a file perturb did not write (unless ``--force``), its extension a known format."""
    plot = getattr(args, "plot", None)
    if plot is None:
        return None
    from perturb.report.written import check_file

    target = check_file(plot, "--plot", force=getattr(args, "force", False), plot=True)
    if not installed("matplotlib"):
        raise _UsageError(f"--plot needs matplotlib: {install_hint('plot')}, or drop --plot")
    return target


def _save_plot(figure, target: Path, force: bool = False) -> None:
    """Save ``figure`` into ``target`` (checked by :func:`_check_plot`) in its extension's format;
    looked at again just before (a file the user saved there meanwhile is theirs)."""
    import io

    from perturb.report.written import check_file, write_file

    buffer = io.BytesIO()
    figure.savefig(buffer, format=target.suffix[1:].lower())
    check_file(target, "--plot", force=force, plot=True)
    write_file(target, buffer.getvalue())
