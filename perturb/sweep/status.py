"""What became of each point: :class:`PointStatus`, and enums as coded variables of the store.

A coded variable holds the position of an enum member (``0, 1, ...`` in the enum's order) and
:data:`NOT_COMPUTED` where nothing was computed; its attributes carry the meanings, so a store
stays readable when an enum grows (a new :class:`perturb.validation.Verdict` member gets the next
code, and the attributes of each store say what its codes meant when it was written).
"""

from __future__ import annotations

import enum
import json

__all__ = ["NOT_COMPUTED", "PointStatus", "code_of", "coding_attrs", "member_of"]

#: The code of a point (or a quantity) that was not computed.
NOT_COMPUTED = -1


class PointStatus(enum.Enum):
    """What became of one grid point; the values are the messages shown to users."""

    OK = "computed"
    INVALID_PARAMETERS = "the problem does not accept these parameter values"
    CONSTRUCTION_FAILED = "the analytic construction failed at these parameter values"
    OUTSIDE_DOMAIN = "the series is outside its domain at these parameter values"
    NOT_FINITE = "the solution is not finite at these parameter values"
    FAILED = "the computation at this point failed"

    @property
    def ok(self) -> bool:
        return self is PointStatus.OK


def code_of(member: enum.Enum | None) -> int:
    """The code of ``member`` (its position in its enum), :data:`NOT_COMPUTED` for None."""
    if member is None:
        return NOT_COMPUTED
    return list(type(member)).index(member)


def member_of(enum_type: type[enum.Enum], code: int) -> enum.Enum | None:
    """The member of ``enum_type`` coded ``code`` (None for :data:`NOT_COMPUTED`)."""
    if int(code) == NOT_COMPUTED:
        return None
    return list(enum_type)[int(code)]


def coding_attrs(enum_type: type[enum.Enum], what: str) -> dict:
    """The attributes of a variable coding ``enum_type``: CF ``flag_values``/``flag_meanings``,
    and ``meanings`` (JSON: code -> the member's message), ``labels`` (code -> name)."""
    members = list(enum_type)
    codes = [NOT_COMPUTED, *range(len(members))]
    names = ["not_computed", *(m.name.lower() for m in members)]
    meanings = {str(NOT_COMPUTED): f"{what} not computed"}
    meanings.update({str(i): str(m.value) for i, m in enumerate(members)})
    return {
        "long_name": what,
        "flag_values": codes,
        "flag_meanings": " ".join(names),
        "meanings": json.dumps(meanings),
        "labels": json.dumps(dict(zip(map(str, codes), names, strict=True))),
        "enum": f"{enum_type.__module__}.{enum_type.__qualname__}",
    }
