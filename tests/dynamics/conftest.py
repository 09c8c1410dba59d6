"""Shared cases of the dynamics tests: the bistable forced Duffing (three steady states at
Omega = 1.05: lower and upper stable, middle a saddle) and its catalogue."""

from __future__ import annotations

import pytest

from problems import get_problem

#: The bistable case of docs/forced.md.
BISTABLE = {"Omega": 1.05}


@pytest.fixture(scope="session")
def bistable():
    return get_problem("forced-duffing").create(**BISTABLE)


@pytest.fixture(scope="session")
def motion(bistable):
    from perturb.dynamics.motion import motion_of

    return motion_of(bistable)


@pytest.fixture(scope="session")
def chart(bistable, motion):
    from perturb.dynamics.attractors import catalogue

    return catalogue(bistable, 1, 0.0, motion)
