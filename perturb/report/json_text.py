"""JSON that every reader can parse: a non-finite number (NaN, ±inf) becomes ``null``.

Python's :func:`json.dumps` writes ``NaN`` and ``Infinity`` by default, which are not JSON (a
strict reader, ``jq``, JavaScript's ``JSON.parse`` refuse them). Every ``--format json`` and every
JSON file perturb writes goes through :func:`json_text`: a value that is not finite is written as
``null``, and a mapping at the top gets the key ``non_finite`` naming where (its status: which
numbers could not be computed or overflowed), so that a ``null`` is never silent.
"""

from __future__ import annotations

import json
import math

__all__ = ["NON_FINITE_KEY", "finite", "json_text"]

#: The key, added at the top of a mapping, that lists where non-finite values were written null.
NON_FINITE_KEY = "non_finite"

#: Paths listed under :data:`NON_FINITE_KEY` (the rest counted).
NON_FINITE_LISTED = 20


def finite(data, path: str = "", found: list | None = None):
    """``data`` with every non-finite float (and numpy floating scalar) replaced by None; the
    paths replaced are appended to ``found``."""
    if isinstance(data, float) or type(data).__name__ in ("float64", "float32", "float16"):
        value = float(data)
        if math.isfinite(value):
            return value if not isinstance(data, float) else data
        if found is not None:
            found.append(path or "$")
        return None
    if isinstance(data, dict):
        return {k: finite(v, f"{path}.{k}" if path else str(k), found) for k, v in data.items()}
    if isinstance(data, list | tuple):
        return [finite(v, f"{path}[{i}]", found) for i, v in enumerate(data)]
    return data


def json_text(data, **kwargs) -> str:
    """``json.dumps(data, **kwargs)`` with non-finite numbers as ``null`` (and, for a mapping, the
    key :data:`NON_FINITE_KEY` listing their paths: at most :data:`NON_FINITE_LISTED`, then how
    many more); always valid JSON (``allow_nan=False``).

    Examples
    --------
    >>> json_text({"period": float("inf"), "order": 2})
    '{"period": null, "order": 2, "non_finite": ["period"]}'
    """
    found: list[str] = []
    clean = finite(data, "", found)
    if found and isinstance(clean, dict) and NON_FINITE_KEY not in clean:
        listed = found[:NON_FINITE_LISTED]
        if len(found) > NON_FINITE_LISTED:
            listed.append(f"... and {len(found) - NON_FINITE_LISTED} more")
        clean[NON_FINITE_KEY] = listed
    kwargs["allow_nan"] = False
    return json.dumps(clean, **kwargs)
