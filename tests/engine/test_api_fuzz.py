"""Hostile calls of the public Python API (issue 10, item 3): refused cleanly, or answered honestly.

The corpus and the rules are in :mod:`tests.engine.api_corpus`; here every case is a test, plus a
sampled part (hypothesis, derandomized ``ci`` profile): junk in each argument of
:class:`perturb.QuasilinearSystem` and as the expansion parameter of ``evaluate``.
``python -m tests.engine.test_api_fuzz`` prints the counts.
"""

from __future__ import annotations

from collections import Counter

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb import PerturbError
from tests.engine import api_corpus
from tests.engine.api_corpus import INF, NAN, Case, _solution, duffing, outcome
from tests.engine.api_corpus_more import CASES_MORE

CASES = api_corpus.CASES + CASES_MORE


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_hostile_call_is_refused_or_answered_honestly(case: Case):
    kind, detail = outcome(case)
    assert kind in ("refused", "answered"), f"{kind}: {detail}"


def test_corpus_size():
    assert len(CASES) >= 145
    assert len({c.name for c in CASES}) == len(CASES)


# ------------------------------------------------------------------------------ sampled part
_junk = st.one_of(
    st.none(),
    st.booleans(),
    st.complex_numbers(allow_nan=True, allow_infinity=True).filter(lambda z: z.imag != 0),
    st.sampled_from([NAN, INF, -INF, sp.nan, sp.oo, sp.zoo, -sp.oo, sp.I]),
    st.dictionaries(st.text(max_size=3), st.integers(), min_size=1, max_size=2),
    st.text(alphabet="()*+-/ ", min_size=1, max_size=4),
)
_FIELDS = ("coordinates", "velocities", "frequencies", "rhs", "parameter", "parameters")


@given(field=st.sampled_from(_FIELDS), junk=_junk, wrap=st.booleans())
def test_system_junk_is_refused(field, junk, wrap):
    """Junk (as the value, or as the only entry of a list) in any argument of QuasilinearSystem is
    refused with a perturb ValueError that names the argument, never another exception."""
    if isinstance(junk, str) and field not in ("frequencies", "rhs"):
        junk = None  # a string is a legitimate symbol name there
    value = [junk] if wrap else junk
    if isinstance(junk, bool) and field not in ("frequencies", "rhs"):
        value = [junk]  # a bare bool is no sequence: wrap it so the case stays a type error
    with pytest.raises(PerturbError) as info:
        duffing(**{field: value})
    assert isinstance(info.value, ValueError)
    message = str(info.value)
    assert "\n" not in message.strip()
    assert "`" in message


@given(junk=_junk)
def test_evaluate_junk_epsilon_is_refused(junk):
    with pytest.raises(PerturbError) as info:
        _solution().evaluate(0.0, junk)
    assert isinstance(info.value, ValueError) and "`epsilon`" in str(info.value)


def summary() -> Counter:
    return Counter(outcome(c)[0] for c in CASES)


if __name__ == "__main__":  # python -m tests.engine.test_api_fuzz: the counts of the report
    failures = []
    for case in CASES:
        kind, detail = outcome(case)
        if kind not in ("refused", "answered"):
            failures.append((case.name, kind, detail))
    counts = Counter(kind for _, kind, _ in failures)
    print(
        f"corpus: {len(CASES)} cases; {len(CASES) - len(failures)} refused or answered;",
        dict(counts),
    )
    for name, kind, detail in failures:
        print(f"  {name}: {kind}: {detail}")
