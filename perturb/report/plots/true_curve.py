"""The true curves drawn beside the analytic response (``perturb response --true --plot``): stable
parts solid, unstable dashed, marginal (conservative) dash-dotted; the curves through the analytic
branches and those born at their branch points in black, the doubled orbits (period 2, 4…) in a
colour per period; the special points located on them (fold, branch point, period doubling,
Neimark–Sacker) and where the analytic curve parts from them by more than the tolerance."""

from __future__ import annotations

__all__ = ["draw_true_curves"]

#: Marker, colour and legend label of each kind of special point of a true curve.
MARKERS = {
    "fold": ("v", "k", "true fold"),
    "branch-point": ("*", "C2", "branch point"),
    "period-doubling": ("s", "C1", "period doubling"),
    "neimark-sacker": ("D", "C4", "Neimark–Sacker"),
}
_STYLE = {True: "-", False: "--", None: "-."}
#: The colour of a true curve by its period (in response periods): 1 black, then one a doubling.
_PERIOD_COLOURS = {1: "k", 2: "C5", 4: "C6", 8: "C8", 16: "C9"}


def _segments(points, coordinate, measure):
    """Runs of consecutive points with the same stability: (stable, values, amplitudes). A
    marginal point among others (a fold's, where a multiplier is at 1) joins the run before it;
    only a run of marginal points (a conservative system's) is drawn as marginal."""
    run, key = [], object()
    for p in points:
        amplitude = p.amplitude(coordinate, measure)
        stable = p.stable if p.stable is not None or not run else key
        if stable is not key and run:
            yield key, [q[0] for q in run], [q[1] for q in run]
            run = run[-1:]  # the segments join
        key = stable
        run.append((p.value, amplitude))
    if len(run) > 1:
        yield key, [q[0] for q in run], [q[1] for q in run]


def draw_true_curves(ax, curves, coordinate: str, parameter: str) -> None:
    """Draw ``curves`` (:class:`perturb.response.true_curve.TrueCurves`) on ``ax``.

    The amplitude is ``curves.measure`` of ``coordinate`` (the analytic curve's measure), so that
    the two curves are compared on the same axis.
    """
    if curves is None:
        return
    labelled = set()
    for curve in curves.curves:
        colour = _PERIOD_COLOURS.get(curve.period, "C7")
        for stable, values, amplitudes in _segments(curve.points, coordinate, curves.measure):
            label = {True: "true, stable", False: "true, unstable", None: "true, marginal"}[stable]
            if curve.period > 1:
                label = f"true period {curve.period}, " + label.split(", ")[1]
            ax.plot(values, amplitudes, _STYLE[stable], color=colour, lw=0.9,
                    label=None if label in labelled else label)  # fmt: skip
            labelled.add(label)
    for kind, (marker, colour, label) in MARKERS.items():
        found = [b for b in curves.bifurcations if b.kind == kind]
        if found:
            ax.plot([b.value for b in found],
                    [b.amplitude(coordinate, curves.measure) for b in found],
                    marker, color=colour, ms=6, ls="none", label=label)  # fmt: skip
    if curves.partings:
        ax.plot([p.value for p in curves.partings], [p.analytic for p in curves.partings], "X",
                color="C1", ms=7, ls="none",
                label=f"parts from the truth (> {curves.tolerance:g})")  # fmt: skip
        first = {}
        for p in curves.partings:  # the first parting of each branch named, the others marked
            first.setdefault(p.branch, p)
        for p in first.values():
            ax.annotate(f"{parameter} = {p.value:.4g}", (p.value, p.analytic),
                        textcoords="offset points", xytext=(4, 4), fontsize=7, color="C1")  # fmt: skip
