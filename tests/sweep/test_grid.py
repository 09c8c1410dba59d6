"""The grid of a sweep: axes as written, checks with one-line errors, chunks that tile the grid."""

from __future__ import annotations

import enum

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from perturb._defaults import SWEEP_CONFIRM_POINTS, SWEEP_MAX_POINTS
from perturb.errors import InvalidParameterError, UnknownNameError
from perturb.sweep.grid import Chunking, Grid, check_names, check_size, parse_axis
from perturb.sweep.status import NOT_COMPUTED, PointStatus, code_of, coding_attrs, member_of
from perturb.validation import Verdict
from tests.helpers import roundings

#: numpy's geomspace: a logarithm of each end, a linear step between them and a power (whose
#: exponent, of size <= 3 here, carries its few ulps into the value times ln 10).
GEOMSPACE = roundings(4)


def test_axis_forms():
    linear = parse_axis("r0=0.5:1:3")
    assert linear.name == "r0" and linear.values == (0.5, 0.75, 1.0)
    log = parse_axis("eps=1e-3:1e-1:3:log")
    assert log.values == pytest.approx((1e-3, 1e-2, 1e-1), rel=GEOMSPACE)
    negative_log = parse_axis("eps=-1e-3:-1e-1:3:log")
    assert negative_log.values == pytest.approx((-1e-3, -1e-2, -1e-1), rel=GEOMSPACE)
    listed = parse_axis("gamma3_0=0.3, 0.1,0.2")
    assert listed.values == (0.3, 0.1, 0.2)  # as given, not sorted
    single = parse_axis("k=2:2:1")
    assert single.values == (2.0,)


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("r0", "NAME=START:STOP:N"),
        ("=1:2:3", "NAME=START:STOP:N"),
        ("r0=1:2", "NAME=START:STOP:N"),
        ("r0=1:2:0", "N = 0"),
        ("r0=1:2:-4", "N = -4"),
        ("r0=1:2:2.5", "whole number"),
        ("r0=a:2:3", "'a' is not a number"),
        ("r0=1:inf:3", "not finite"),
        ("r0=1:nan:3", "not finite"),
        ("r0=1:1:3", "START = STOP"),
        ("r0=-1:1:3:log", "one sign"),
        ("r0=1:2:3:cubic", "spacing"),
        ("r0=1,2,1", "repeat"),
        ("r0=", "NAME=START:STOP:N"),
    ],
)
def test_bad_axes_are_one_line_naming_the_axis(text, words):
    with pytest.raises(InvalidParameterError) as info:
        parse_axis(text)
    message = str(info.value)
    assert "\n" not in message and repr(text) in message and words in message


def test_names_are_checked_against_the_problem():
    axes = [parse_axis("epss=0.1:0.2:2")]
    with pytest.raises(
        UnknownNameError, match=r"'epss' is not a parameter of duffing \(did you mean 'eps'\?\)"
    ):
        check_names(axes, ["eps", "amplitude"], "duffing")
    twice = [parse_axis("eps=0.1:0.2:2"), parse_axis("eps=0.3,0.4")]
    with pytest.raises(InvalidParameterError, match="swept twice"):
        check_names(twice, ["eps"], "duffing")
    with pytest.raises(InvalidParameterError, match="also set with --set"):
        check_names(axes[:0] + [parse_axis("eps=0.1:0.2:2")], ["eps"], "duffing", fixed={"eps"})
    check_names([parse_axis("eps=0.1:0.2:2")], ["eps", "amplitude"], "duffing")


def test_sizes_need_confirmation_and_have_a_ceiling():
    check_size(SWEEP_CONFIRM_POINTS, yes=False)
    with pytest.raises(InvalidParameterError) as info:
        check_size(SWEEP_CONFIRM_POINTS + 1, yes=False)
    assert f"{SWEEP_CONFIRM_POINTS + 1:,} points" in str(info.value) and "--yes" in str(info.value)
    check_size(SWEEP_CONFIRM_POINTS + 1, yes=True)
    with pytest.raises(InvalidParameterError, match="more than"):
        check_size(SWEEP_MAX_POINTS + 1, yes=True)


def test_points_are_numbered_in_c_order():
    grid = Grid((parse_axis("a=1,2,3"), parse_axis("b=10,20")))
    assert grid.shape == (3, 2) and grid.size == 6
    assert [grid.point(i) for i in range(6)] == [
        {"a": a, "b": b} for a in (1.0, 2.0, 3.0) for b in (10.0, 20.0)
    ]
    with pytest.raises(InvalidParameterError):
        Grid(())


@given(
    shape=st.lists(st.integers(1, 7), min_size=1, max_size=4),
    points=st.integers(1, 60),
    data=st.data(),
)
def test_chunks_tile_the_grid_once(shape, points, data):
    first = data.draw(st.lists(st.sampled_from(range(len(shape))), unique=True))
    chunking = Chunking.of(shape, points, first)
    seen = np.zeros(shape, dtype=int)
    flat = []
    for number in chunking:
        region = chunking.region(number)
        block = seen[region]
        assert 1 <= block.size <= points
        seen[region] += 1
        indices = chunking.indices(number)
        assert indices.size == block.size
        flat += indices.tolist()
        # the flat indices are those of the block, in C order
        expected = np.ravel_multi_index(
            tuple(
                m.ravel()
                for m in np.meshgrid(*[np.arange(s.start, s.stop) for s in region], indexing="ij")
            ),
            tuple(shape),
        )
        assert indices.tolist() == expected.tolist()
    assert np.all(seen == 1)
    assert sorted(flat) == list(range(int(np.prod(shape))))


def test_enums_are_coded_by_position_with_their_meanings():
    for enum_type in (Verdict, PointStatus):
        attrs = coding_attrs(enum_type, "what")
        members = list(enum_type)
        assert attrs["flag_values"] == [NOT_COMPUTED, *range(len(members))]
        for member in members:
            assert member_of(enum_type, code_of(member)) is member
        assert member_of(enum_type, NOT_COMPUTED) is None and code_of(None) == NOT_COMPUTED

    class Grown(enum.Enum):  # a member added later gets the next code, the others keep theirs
        A = "a"
        B = "b"
        C = "c"

    assert [code_of(m) for m in Grown] == [0, 1, 2]
    import json

    assert json.loads(coding_attrs(Grown, "x")["meanings"]) == {
        "-1": "x not computed",
        "0": "a",
        "1": "b",
        "2": "c",
    }


def test_chunks_keep_the_entering_axes_fixed_when_asked():
    chunking = Chunking.of((100, 100), 30, first=(0,))  # fill along axis 0 first
    assert chunking.chunk == (30, 1)
    assert Chunking.of((100, 100), 30).chunk == (1, 30)


@given(
    per=st.floats(1e-8, 100.0),
    size=st.integers(1, 10**8),
    workers=st.integers(1, 64),
)
def test_chunks_hold_enough_work_for_their_overhead(per, size, workers):
    from perturb._defaults import (
        SWEEP_MAX_CHUNK_POINTS,
        SWEEP_OVERHEAD_SHARE,
        SWEEP_TASK_OVERHEAD_SECONDS,
        SWEEP_TASK_SECONDS,
    )
    from perturb.sweep.driver import chunk_points

    points = chunk_points(per, size, workers)
    assert 1 <= points <= min(size, SWEEP_MAX_CHUNK_POINTS)
    if points < min(size, SWEEP_MAX_CHUNK_POINTS):  # not cut by the grid or the ceiling
        assert points * per >= SWEEP_TASK_OVERHEAD_SECONDS / SWEEP_OVERHEAD_SHARE * (1 - 1e-9)
    if per * min(size, SWEEP_MAX_CHUNK_POINTS) > 2 * SWEEP_TASK_SECONDS:  # enough work to cut
        assert points * per <= SWEEP_TASK_SECONDS + per  # about the target, one point over
