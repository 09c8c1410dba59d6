"""A branch's name follows its orbit from order to order.

Naming the branches at one point by their rank (``lower``, ``middle``, ``upper`` of max ``|x|``,
within each mode shape) at every order on its own lets a name jump to another orbit when two
branches change places between orders (near a fold, where the series barely converges): ``--family
NAME`` would then pick a different orbit when ``--order`` changes. So the ranks are read once, at
order 1 (:data:`RANKED_ORDER`, the lowest order a command takes), and every branch of a higher
order N inherits the name of its partner one order lower, at the same parameters:

1. **Carried.** The order-N root carried continuously to the order-(N−1) equations (Newton, else
   the homotopy in the truncation: :meth:`perturb.steady.evaluate.PointEvaluator.lower_root`)
   lands on an order-(N−1) branch (:func:`orbit_distance` within :data:`~perturb._defaults.ORDER_LINK`): that
   branch is its partner.
2. **Nearest, without doubt.** A branch not carried to one (the homotopy turned back) is paired
   with the nearest order-(N−1) branch left when each is the other's nearest and their distance
   is below half the distance from that order-(N−1) branch to every other one of its order (no
   other branch could be meant) and below :data:`~perturb._defaults.ORDER_NEAREST` of their size.
3. **No partner.** Anything else is named ``beyond-series-k``: one order lower has nothing there,
   so the lower orders do not vouch for it. ``k`` counts on from the ``beyond-series`` names the
   order below already gave, so an orbit that first appears at order N keeps ``beyond-series-k``
   at every order above.

The state at rest is ``trivial`` at every order.
"""

from __future__ import annotations

import numpy as np

from perturb._defaults import ORDER_LINK, ORDER_NEAREST
from perturb.steady.census import orbit_images

__all__ = ["RANKED_ORDER", "inherited_names", "orbit_distance"]

#: The order whose branches are named by rank (:func:`perturb.steady.branches.branch_names`); the
#: orders above inherit their names. The lowest order a command takes (``--order`` and a scene's
#: ``[solve] order`` start at 1), so that every name a user sees is read at one order.
RANKED_ORDER = 1

#: The name given to a branch with no partner one order lower (and its count).
NO_PARTNER = "beyond-series"


def orbit_distance(u, v, harmonics, group: int) -> float:
    """The distance between two responses' amplitudes as motions: the smallest max-norm distance
    between ``v`` and ``u`` or one of ``u``'s images under the forcing's time shifts
    (:func:`perturb.steady.census.orbit_images`), relative to the larger of 1 and their sizes."""
    u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
    size = max(1.0, float(np.max(np.abs(u))), float(np.max(np.abs(v))))
    return min(float(np.max(np.abs(w - v))) for w in [u, *orbit_images(u, harmonics, group)]) / size


def _vector(point) -> np.ndarray:
    return np.array([float(x) for x in point.amplitudes.values()])


def _no_partner_count(names) -> int:
    counts = [0]
    for name in names:
        head, _, tail = name.rpartition("-")
        if head == NO_PARTNER and tail.isdigit():
            counts.append(int(tail))
    return max(counts)


def inherited_names(points, lowers, below, below_names, harmonics, group: int) -> list[str]:
    """The names of the order-N branches ``points`` at one parameter point, inherited from the
    order-(N−1) branches ``below`` (named ``below_names``) at the same point (module notes).

    Parameters
    ----------
    points : sequence of ResponsePoint
        The order-N branches.
    lowers : sequence of array or None
        Each branch's order-(N−1) root reached from it (None: none was).
    below : sequence of ResponsePoint
        The order-(N−1) branches at the same point.
    below_names : sequence of str
        Their names.
    harmonics : tuple of int
        The harmonic each resonant coordinate responds at.
    group : int
        The forcing's time-shift symmetry (:func:`perturb.steady.census.shift_symmetry`).

    Returns
    -------
    list of str
        A name for each of ``points``, in their order; no two alike.
    """
    mine = [_vector(p) for p in points]
    theirs = [_vector(p) for p in below]
    partner: dict[int, int] = {}
    claimed: set[int] = set()
    carried = []
    for i, w in enumerate(lowers):
        if w is None or points[i].trivial or not theirs:
            continue
        gaps = [orbit_distance(w, v, harmonics, group) for v in theirs]
        j = int(np.argmin(gaps))
        if gaps[j] <= ORDER_LINK:
            carried.append((gaps[j], i, j))
    for _, i, j in sorted(carried):  # the closer claims first
        if j not in claimed:
            partner[i] = j
            claimed.add(j)
    _nearest(mine, theirs, points, below, partner, claimed, harmonics, group)
    names = []
    fresh = _no_partner_count(below_names)
    for i, p in enumerate(points):
        if p.trivial:
            names.append("trivial")
        elif i in partner and below_names[partner[i]] != "trivial":
            names.append(below_names[partner[i]])
        else:
            fresh += 1
            names.append(f"{NO_PARTNER}-{fresh}")
    return names


def _nearest(mine, theirs, points, below, partner, claimed, harmonics, group) -> None:
    """Rule 2: pair the branches left with their nearest order-(N−1) branch when there is no
    doubt which one is meant (in place)."""
    left = [i for i in range(len(mine)) if i not in partner and not points[i].trivial]
    free = [j for j in range(len(theirs)) if j not in claimed and not below[j].trivial]
    if not left or not free:
        return
    gap = np.array([[orbit_distance(mine[i], theirs[j], harmonics, group) for j in free]
                    for i in left])  # fmt: skip
    for a, i in enumerate(left):
        b = int(np.argmin(gap[a]))
        if int(np.argmin(gap[:, b])) != a:
            continue
        j = free[b]
        others = [
            orbit_distance(theirs[j], theirs[k], harmonics, group)
            for k in range(len(theirs))
            if k != j
        ]
        if gap[a, b] < min([ORDER_NEAREST, *(0.5 * d for d in others)]):  # one branch below: none
            partner[i] = j
            claimed.add(j)
