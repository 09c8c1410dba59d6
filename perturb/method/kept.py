"""What order N keeps of the series, and the :class:`~perturb.solution.PeriodicSolution` packed from it.

A mixin of the order-by-order template (:mod:`perturb.method.poincare`): the depth rule (order N
keeps coordinate ``i`` through :math:`\\varepsilon^{N+d_i}`, ``d_i`` the order of its first
non-zero term), the unknowns still open in what is kept, and the frozen result. It reads the
template's working state (``x``, ``omega``, ``conv``, ``unknowns``, ``solved``, ``steps``, ...).
"""

from __future__ import annotations

import sympy as sp

from perturb.solution import PeriodicSolution, Status
from perturb.steps import GeneratingSolution

__all__ = ["KeptSeries"]


class KeptSeries:
    """The depth rule and the packing of a run's result (mixin of the order-by-order template)."""

    def _depths(self) -> list[int]:
        """How many orders each coordinate's series keeps: ``order + d_i``.

        ``d_i`` is the order of the coordinate's first non-zero term (0 when all known terms
        vanish). Order N promises each coordinate relative to its own size to
        :math:`O(\\varepsilon^{N+1})`: a coordinate that starts at :math:`\\varepsilon^{d}` (the
        degenerate branch of the disk, whose P-amplitude is O(ε); a non-resonant coordinate
        forced at order 1) needs its terms through :math:`\\varepsilon^{N+d}`, with the amplitude
        and frequency corrections the later conditions fix, as a free amplitude's are.
        """
        depths = []
        for row in self.x:
            lead = next((q for q, term in enumerate(row) if self._known_nonzero(term)), 0)
            depths.append(self.method.order + lead)
        return depths

    def _known_nonzero(self, term) -> bool:
        """Whether a term is non-zero whatever its open unknowns turn out to be: a term made of
        open unknowns alone (a correction not yet fixed, an invariant coordinate's zero) does not
        decide where a coordinate starts."""
        if term.is_zero():
            return False
        open_ = self.conv.poly_symbols(term) & self.unknowns
        if not open_:
            return True
        zero = self.conv.mapping(dict.fromkeys(open_, sp.S.Zero))
        return not term.subs(zero).is_zero()

    def _open_unknowns(self, uniform: bool = False) -> set:
        """The unknowns left in the terms each coordinate keeps and in the frequency to order N
        (``uniform``: in every coordinate's terms to order N, whatever its leading order)."""
        conv, order = self.conv, self.method.order
        syms = set()
        depths = [order] * self.n if uniform else self._depths()
        for row, depth in zip(self.x, depths, strict=True):
            for term in row[: depth + 1]:
                syms |= conv.poly_symbols(term)
        for w in self.omega[: order + 1]:
            syms |= conv.symbols(w)
        return syms & self.unknowns

    def result(
        self, generating: GeneratingSolution, status: Status, message: str
    ) -> PeriodicSolution:
        """The run packed as a :class:`PeriodicSolution` (what order N keeps, the depth rule)."""
        order = self.method.order
        gen = GeneratingSolution(
            coordinates=generating.coordinates,
            harmonics=generating.harmonics,
            cos_amplitudes=tuple(
                sp.sympify(a).xreplace(self.solved) for a in generating.cos_amplitudes
            ),
            sin_amplitudes=tuple(
                sp.sympify(b).xreplace(self.solved) for b in generating.sin_amplitudes
            ),
            phase_coordinate=generating.phase_coordinate,
            reference_frequency=generating.reference_frequency,
        )
        conv = self.conv  # back to sympy: the result holds sympy expressions only
        terms = tuple(
            tuple(conv.trig(t) for t in row[: depth + 1])
            for row, depth in zip(self.x, self._depths(), strict=True)
        )
        omega_all = [conv.to_sympy(w) for w in self.omega]
        # keep every frequency coefficient that is fully determined by the time every coordinate's
        # terms to order N were (the orders run further only for the deeper terms of coordinates
        # that start at a power of eps: they add those terms, never frequency coefficients)
        frequency = []
        top = len(omega_all) if self.frequency_top is None else self.frequency_top + 1
        for w in omega_all[:top]:
            if w.free_symbols & self.unknowns:
                break
            frequency.append(w)
        deviations = {}
        for i, name in enumerate(self.names):
            if self.harmonics[i] is None:
                continue
            values = [t.at_zero() for t in terms[i]]
            deviations[name] = tuple(values[1:])
            slopes = [t.derivative().at_zero() for t in terms[i]]
            omega = omega_all[: len(frequency)]
            velocity = [
                sp.expand(sum(omega[a] * slopes[q - a] for a in range(q + 1) if a < len(omega)))
                for q in range(len(slopes))
            ]
            deviations[self.system.velocities[i].name] = tuple(velocity[1:])
        return PeriodicSolution(
            system=self.system,
            order=order,
            terms=terms,
            frequency=tuple(frequency),
            generating=gen,
            steps=tuple(self.steps),
            deviations=deviations,
            status=status,
            message=message,
            dependent_residuals={
                c.name: sp.expand(c.expression.xreplace(self.solved)) for c in self.dependent
            },
        )
