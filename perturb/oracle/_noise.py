"""Another machine's last bits, on demand: the test noise ``PERTURB_TEST_NOISE=K``.

A different CPU, BLAS or library build rounds differently: every integration ends a few units in
the last place (ulps) away from this machine's, and so does every linear solve. A test that holds
only for this machine's bits is wrong, and passes here all the same. With the environment
variable ``PERTURB_TEST_NOISE`` set to ``K`` (a number of ulps, read once, at import), the oracle
moves

* every integration's result — each state of :meth:`perturb.oracle.base.IntegratorBase.integrate`
  after the start, whatever the backend — by :func:`integration_noise`, and
* every Newton step of the shootings (:func:`perturb.oracle.newton.newton_step`, which the
  driven shooting :mod:`perturb.oracle.forced` and the rigid body's conditioned shooting use too)
  by :func:`solve_noise`,

each component by up to ``K`` spacings of its own type (float64, long double, real128). The
perturbation is a function of the seed and of the computation's inputs, so the same computation
gives the same result: a machine is deterministic, only different. The seed is
``PERTURB_TEST_NOISE_SEED`` at import (processes a test starts — Dask workers, the CLI — inherit
it), then what :func:`seed` set last; the test suite seeds from each test's node id
(``tests/conftest.py``). Unset or ``0``: both hooks return their argument itself after one
comparison. Nothing outside the tests sets it.

Examples
--------
>>> import numpy as np
>>> from perturb.oracle import _noise
>>> y = np.array([1.0, -3.0])
>>> moved = _noise.perturbed(y, 4.0, b"the inputs")
>>> bool(np.all(np.abs(moved - y) <= 4 * np.spacing(np.abs(y))))
True
>>> np.array_equal(moved, _noise.perturbed(y, 4.0, b"the inputs"))  # the same inputs, the same bits
True
"""

from __future__ import annotations

import hashlib
import math
import os

import numpy as np

from perturb.errors import bad_value

__all__ = ["ULPS", "integration_noise", "perturbed", "seed", "solve_noise"]

#: Relative spacing used for a type numpy has no ``spacing`` for: heyoka's real128 (113-bit
#: significand), whose ulp at ``|x|`` lies in ``[|x| 2**-113, |x| 2**-112)``.
_REAL128_SPACING = 2.0**-113


def _read_ulps() -> float:
    text = os.environ.get("PERTURB_TEST_NOISE", "").strip()
    if not text:
        return 0.0
    try:
        ulps = float(text)
    except ValueError:
        ulps = math.nan
    if not (math.isfinite(ulps) and ulps >= 0):
        raise bad_value(
            "PERTURB_TEST_NOISE", text, "set a number of ulps >= 0 (e.g. 4), or unset it"
        )
    return ulps


#: The noise, in ulps of each component; 0 (the variable unset) turns both hooks off.
ULPS: float = _read_ulps()
_seed: bytes = os.environ.get("PERTURB_TEST_NOISE_SEED", "").encode()


def seed(key: str) -> None:
    """Seed the noise with ``key`` (the test suite: each test's node id), here and, through
    ``PERTURB_TEST_NOISE_SEED``, in the processes started from now on."""
    global _seed
    _seed = key.encode()
    os.environ["PERTURB_TEST_NOISE_SEED"] = key


def _spacing(values: np.ndarray) -> np.ndarray:
    magnitude = np.abs(values)
    try:
        return np.spacing(magnitude)
    except TypeError:  # real128: no numpy ufunc loop; its relative spacing instead
        return magnitude * values.dtype.type(_REAL128_SPACING)


def perturbed(values, ulps: float, *inputs, level: float = 0.0) -> np.ndarray:
    """``values`` plus up to ``level + ulps`` spacings of each component (a new array).

    The draw is seeded by the current seed and the bytes of ``inputs`` (arrays or bytes): the same
    inputs give the same perturbation. ``level`` adds an absolute noise (an integration error,
    ``tests/oracle/noisy.py``).
    """
    values = np.asarray(values)
    digest = hashlib.sha256(_seed)
    for item in inputs:
        digest.update(item if isinstance(item, bytes) else np.ascontiguousarray(item).tobytes())
    rng = np.random.default_rng(int.from_bytes(digest.digest()[:8], "little"))
    draw = rng.uniform(-1.0, 1.0, values.shape).astype(values.dtype)
    size = _spacing(values) * values.dtype.type(ulps) + values.dtype.type(level)
    return values + size * draw


def integration_noise(y: np.ndarray, t, t0: float, y0: np.ndarray, integrator: str) -> np.ndarray:
    """The states ``y`` (n, len(t)) of an integration from ``y0`` at ``t0`` by ``integrator`` (its
    name: two integrators' errors are independent), with the noise on every column after the
    start (the start itself a machine copies exactly)."""
    if not ULPS:
        return y
    later = np.asarray(t, dtype=float) > t0
    if not np.any(later):
        return y
    y = np.array(y)
    y[:, later] = perturbed(y[:, later], ULPS, integrator.encode(), y0, np.asarray(t, float))
    return y


def solve_noise(step: np.ndarray, matrix: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The solution ``step`` of the linear system ``matrix @ step = target``, with the noise."""
    if not ULPS:
        return step
    return perturbed(step, ULPS, matrix, target)
