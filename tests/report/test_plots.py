"""perturb.report.plots (issue 13 item 3): every plot on real perturb results.

Each figure is checked for what it promises — its lines hold the data passed in, axes carry labels
with units, legends name every line, log scales where promised — and saved as a non-empty PNG.  Set
``PERTURB_PLOT_REVIEW_DIR`` to keep the PNGs and the GIF there for a look.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot  # noqa: E402  (only to check that no plot registers a figure with it)
from matplotlib.figure import Figure  # noqa: E402

from perturb._defaults import DEFAULT_RTOL  # noqa: E402
from perturb.errors import InvalidParameterError, MissingDependencyError  # noqa: E402
from perturb.oracle import Scipy  # noqa: E402
from perturb.report.plots import (  # noqa: E402
    animate_orientation,
    plot_convergence,
    plot_error,
    plot_euler_angles,
    plot_orientation,
    plot_phase,
    plot_time_series,
    plot_work_precision,
    rotation_matrix,
)
from perturb.validation import original_rhs  # noqa: E402
from perturb.workprecision import work_precision  # noqa: E402
from problems import get_problem  # noqa: E402
from tests.helpers import roundings  # noqa: E402

#: Duffing's small parameter and order: error O(eps^3) ~ 1e-3 relative, visible on the plots.
EPS, ORDER = 0.1, 2
#: Values of eps of the convergence figure: a factor 2 apart, as validation's SLOPE_FACTORS.
CONVERGENCE_EPS = (0.025, 0.05, 0.1, 0.2)
#: A fitted slope may fall this far from order + 1: four points a factor 2 apart leave a few tenths
#: from the next-order terms (perturb.validation.SLOPE_TOLERANCE).
SLOPE_TOLERANCE = 0.5
#: Entries of a rotation from its three angles by two routes: sines and cosines, products of up to
#: three of them and sums of two (and R R^T: three more products and a sum): about 8 operations on
#: numbers of size <= 1.
ROTATION = roundings(8)
#: The disk of the README (fast spin, eps = c/r0 = 0.004).
DISK = {"r0": 0.755155, "R": 0.123299, "gamma3_0": 0.25}


@pytest.fixture(autouse=True)
def no_pyplot_figures():
    """No plot may register a figure with pyplot (it would leak memory in a long session)."""
    yield
    assert matplotlib.pyplot.get_fignums() == []


@pytest.fixture(scope="module")
def out_dir(tmp_path_factory):
    review = os.environ.get("PERTURB_PLOT_REVIEW_DIR")
    if review:
        os.makedirs(review, exist_ok=True)
        return review
    return str(tmp_path_factory.mktemp("plots"))


def save(fig: Figure, out_dir: str, name: str) -> str:
    path = os.path.join(out_dir, name)
    fig.savefig(path)
    assert os.path.getsize(path) > 1000  # a real PNG, not an empty canvas's header
    with open(path, "rb") as handle:
        assert handle.read(8) == b"\x89PNG\r\n\x1a\n"
    return path


def _true_motion(problem, analytic: dict, t: np.ndarray) -> dict:
    """The original equations integrated (DOP853) from the analytic state at t = 0."""
    names = problem.state_names()
    field = original_rhs(problem)
    y0 = np.array([analytic[n][0] for n in names])
    traj = Scipy("DOP853", rtol=DEFAULT_RTOL).integrate(
        lambda y: np.asarray(field(0.0, y), dtype=float), (0.0, float(t[-1])), y0, t_eval=t
    )
    traj.raise_for_status()
    return dict(zip(names, np.asarray(traj.y, dtype=float), strict=True))


@pytest.fixture(scope="module")
def duffing():
    problem = get_problem("duffing").create(eps=EPS)
    solution = problem.solve(ORDER)
    t = np.linspace(0.0, 3 * problem.period(solution), 301)
    analytic = problem.state(solution, t)
    return t, analytic, _true_motion(problem, analytic, t)


@pytest.fixture(scope="module")
def convergence():
    """One-period max relative error of the order-2 Duffing solution at each eps."""
    errors = []
    for eps in CONVERGENCE_EPS:
        problem = get_problem("duffing").create(eps=eps)
        solution = problem.solve(ORDER)
        t = np.linspace(0.0, problem.period(solution), 81)
        analytic = problem.state(solution, t)
        true = _true_motion(problem, analytic, t)
        errors.append(
            max(np.max(np.abs(analytic[n] - true[n])) / np.max(np.abs(true[n])) for n in true)
        )
    return np.array(CONVERGENCE_EPS), np.array(errors)


@pytest.fixture(scope="module")
def disk():
    problem = get_problem("disk").create(**DISK)
    solution = problem.solve(1)
    t = np.linspace(0.0, 2 * problem.period(solution), 241)
    return t, problem.euler_angles(solution, t)


def labels_of(ax) -> list[str]:
    legend = ax.get_legend()
    return [] if legend is None else [text.get_text() for text in legend.get_texts()]


def figure_legend_labels(fig: Figure) -> list[str]:
    return [text.get_text() for legend in fig.legends for text in legend.get_texts()]


# ------------------------------------------------------------------------------ time series
def test_time_series_holds_the_data_with_units(duffing, out_dir):
    t, analytic, true = duffing
    fig = plot_time_series(t, analytic, true, time_unit="", units={"x": "m", "xdot": "m/s"})
    assert isinstance(fig, Figure)
    axes = fig.axes
    assert len(axes) == 2
    for ax, name in zip(axes, ("x", "xdot"), strict=True):
        analytic_line, true_line = ax.get_lines()
        np.testing.assert_array_equal(analytic_line.get_xdata(), t)
        np.testing.assert_array_equal(analytic_line.get_ydata(), analytic[name])
        np.testing.assert_array_equal(true_line.get_ydata(), true[name])
    assert axes[0].get_ylabel() == "$x$ [m]"
    assert axes[1].get_ylabel() == "$\\dot{x}$ [m/s]"
    assert axes[1].get_xlabel() == "$t$ [1]"
    assert labels_of(fig.axes[0]) == ["analytic", "true (integrated)"]
    save(fig, out_dir, "time_series.png")


def test_threads_and_global_rc_params_untouched(duffing):
    """Figures built concurrently in threads all come out whole; the user's rcParams stay."""
    from concurrent.futures import ThreadPoolExecutor

    t, analytic, true = duffing
    before = dict(matplotlib.rcParams)
    with ThreadPoolExecutor(max_workers=4) as pool:
        figures = list(pool.map(lambda _: plot_time_series(t, analytic, true), range(4)))
    for fig in figures:
        assert [len(ax.get_lines()) for ax in fig.axes] == [2, 2]
        assert fig.dpi == 200 and fig.axes[0].spines["top"].get_visible() is False
    assert dict(matplotlib.rcParams) == before


def test_time_series_alone_has_no_legend_and_seconds_by_default(duffing):
    t, analytic, _ = duffing
    fig = plot_time_series(t, analytic, names=["x"], title="Duffing")
    (ax,) = fig.axes
    assert len(ax.get_lines()) == 1 and ax.get_legend() is None
    assert ax.get_ylabel() == "$x$ [1]" and ax.get_xlabel() == "$t$ [s]"
    assert fig.get_suptitle() == "Duffing"


def test_error_is_relative_on_a_log_axis(duffing, out_dir):
    t, analytic, true = duffing
    fig = plot_error(t, analytic, true, time_unit="")
    (ax,) = fig.axes
    assert ax.get_yscale() == "log"
    for line, name in zip(ax.get_lines(), ("x", "xdot"), strict=True):
        expected = np.abs(analytic[name] - true[name]) / np.max(np.abs(true[name]))
        np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-15, atol=0)
    assert "amplitude" in ax.get_ylabel() and "[1]" in ax.get_ylabel()
    assert labels_of(ax) == ["$x$", "$\\dot{x}$"]
    # the error is O(eps^3) relative: it must be drawn well below 1 and above round-off
    assert 1e-6 < np.max(ax.get_lines()[0].get_ydata()) < 10 * EPS**3
    save(fig, out_dir, "error.png")


def test_absolute_error_carries_the_unit(duffing):
    t, analytic, true = duffing
    fig = plot_error(t, analytic, true, names=["x"], relative=False, units={"x": "m"})
    (ax,) = fig.axes
    np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), np.abs(analytic["x"] - true["x"]))
    assert ax.get_ylabel() == "|analytic − true| [m]"


def test_phase_portrait(duffing, out_dir):
    t, analytic, true = duffing
    fig = plot_phase(analytic, true)
    (ax,) = fig.axes
    analytic_line, true_line = ax.get_lines()
    np.testing.assert_array_equal(analytic_line.get_xdata(), analytic["x"])
    np.testing.assert_array_equal(analytic_line.get_ydata(), analytic["xdot"])
    np.testing.assert_array_equal(true_line.get_xdata(), true["x"])
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("$x$ [1]", "$\\dot{x}$ [1]")
    assert labels_of(fig.axes[0]) == ["analytic", "true (integrated)"]
    save(fig, out_dir, "phase.png")


# ------------------------------------------------------------------------------ convergence
def _line_slope(line) -> float:
    x, y = np.log(line.get_xdata()), np.log(line.get_ydata())
    return float((y[-1] - y[0]) / (x[-1] - x[0]))


def test_convergence_fitted_and_expected_slopes(convergence, out_dir):
    eps, errors = convergence
    fig = plot_convergence(eps, errors, order=ORDER, slope_band=SLOPE_TOLERANCE)
    (ax,) = fig.axes
    assert (ax.get_xscale(), ax.get_yscale()) == ("log", "log")
    points, fitted, reference = ax.get_lines()
    np.testing.assert_array_equal(points.get_xdata(), eps)
    np.testing.assert_array_equal(points.get_ydata(), errors)
    slope = np.polyfit(np.log(eps), np.log(errors), 1)[0]
    assert _line_slope(fitted) == pytest.approx(slope, rel=1e-12)
    assert _line_slope(reference) == pytest.approx(ORDER + 1, rel=1e-12)
    labels = labels_of(ax)
    assert labels[:3] == ["measured", f"fit: slope {slope:.2f}", "expected: slope 3 (order 2 + 1)"]
    assert labels[3] == "consistent: slope 2.5 to 3.5"
    assert ax.get_xlabel() == "$\\varepsilon$ [1]" and "[1]" in ax.get_ylabel()
    # the data are real: order 2 converges like eps^3
    assert abs(slope - (ORDER + 1)) < SLOPE_TOLERANCE
    np.testing.assert_array_equal(ax.get_xticks(), eps)  # ticks at the measured eps, plain
    assert [label.get_text() for label in ax.get_xticklabels()] == [f"{e:g}" for e in eps]
    save(fig, out_dir, "convergence.png")


def test_convergence_given_slope_and_unusable_points(convergence):
    eps, errors = convergence
    errors = errors.copy()
    errors[0] = math.nan  # a failed point: shown nowhere, left out of the fit
    fig = plot_convergence(eps, errors, order=ORDER, slope=2.9)
    (ax,) = fig.axes
    points, fitted, _ = ax.get_lines()
    assert np.isnan(points.get_ydata()[0])
    assert _line_slope(fitted) == pytest.approx(2.9, rel=1e-12)
    np.testing.assert_allclose(fitted.get_xdata(), [eps[1], eps[-1]], rtol=1e-12)
    assert "fit: slope 2.90" in labels_of(ax)


# ------------------------------------------------------------------------------ work-precision
@pytest.fixture(scope="module")
def table():
    return work_precision(
        get_problem("duffing").create(eps=EPS),
        periods=2,
        orders=2,
        rk4_steps=(20, 80),
        scipy_methods=("DOP853",),
        tolerances=(1e-6, 1e-10),
        repeat=1,
    )


def test_work_precision_one_line_per_method(table, out_dir):
    fig = plot_work_precision(table)
    (ax,) = fig.axes
    assert (ax.get_xscale(), ax.get_yscale()) == ("log", "log")
    finite = [p for p in table.points if math.isfinite(p.error)]
    methods = list(dict.fromkeys(p.method for p in finite))
    assert "analytic derivation" not in methods  # its error is NaN: no place on the diagram
    assert labels_of(ax) == methods
    analytic = [p.setting for p in finite if p.method == "analytic"]
    assert [text.get_text() for text in ax.texts] == analytic  # "order 1", "order 2"
    for line, method in zip(ax.get_lines(), methods, strict=True):
        rows = [p for p in finite if p.method == method]
        np.testing.assert_array_equal(line.get_xdata(), [p.seconds for p in rows])
        np.testing.assert_array_equal(line.get_ydata(), [p.error for p in rows])
    assert ax.get_xlabel() == "wall time [s]" and "error" in ax.get_ylabel()
    assert table.problem in ax.get_title() and table.reference in ax.get_title()
    save(fig, out_dir, "work_precision.png")


def test_cli_plot_option(table, tmp_path, capsys, monkeypatch):
    """``perturb work-precision --plot`` draws with plot_work_precision (the run itself is the
    fixture's: the CLI's own sweep is tested in tests/cli)."""
    import perturb.workprecision
    from perturb.cli import main

    monkeypatch.setattr(perturb.workprecision, "work_precision", lambda *a, **k: table)
    path = tmp_path / "wp.png"
    assert main(["work-precision", "duffing", "--repeat", "1", "--plot", str(path)]) == 0
    assert table.reference in capsys.readouterr().out
    assert path.stat().st_size > 1000


# ------------------------------------------------------------------------------ rigid body
def test_rotation_matches_the_problems_derivation():
    """R_Z(psi) R_X(theta) R_Z(phi) here == the product problems.rigid_body derives symbolically."""
    from problems.rigid_body import euler_angles as ea

    symbolic = ea._rotation(2, ea.psi) * ea._rotation(0, ea.theta) * ea._rotation(2, ea.phi)
    numeric = sp.lambdify((ea.psi, ea.theta, ea.phi), symbolic, modules="numpy")
    rng = np.random.default_rng(13)
    angles = rng.uniform(-np.pi, np.pi, size=(20, 3))
    ours = rotation_matrix(angles[:, 0], angles[:, 1], angles[:, 2])
    for (psi, theta, phi), r in zip(angles, ours, strict=True):
        np.testing.assert_allclose(r, numeric(psi, theta, phi), atol=ROTATION)
    # and its third row is the vertical the problems package derives
    vertical = sp.lambdify((ea.theta, ea.phi), ea.euler_kinematics().vertical, modules="numpy")
    for (_, theta, phi), r in zip(angles, ours, strict=True):
        np.testing.assert_allclose(r[2], vertical(theta, phi), atol=ROTATION)
    np.testing.assert_allclose(
        ours @ np.swapaxes(ours, -1, -2), np.broadcast_to(np.eye(3), ours.shape), atol=ROTATION
    )


def test_euler_angles_in_degrees_unwrapped(disk, out_dir):
    t, angles = disk
    fig = plot_euler_angles(t, angles, time_unit="")
    axes = fig.axes
    assert len(axes) == 3
    for ax, name in zip(axes, ("psi", "theta", "phi"), strict=True):
        (line,) = ax.get_lines()
        np.testing.assert_array_equal(line.get_xdata(), t)
        np.testing.assert_allclose(
            line.get_ydata(), np.degrees(np.unwrap(angles[name])), rtol=1e-15
        )
        assert ax.get_ylabel().endswith("[deg]")
    # the proper rotation spins: unwrapped, it draws as a ramp without 360-degree jumps
    assert np.max(np.abs(np.diff(axes[2].get_lines()[0].get_ydata()))) < 180
    save(fig, out_dir, "euler_angles.png")


def test_euler_angles_in_radians_with_true_angles(disk):
    t, angles = disk
    fig = plot_euler_angles(t, angles, angles, degrees=False, unwrap=False)
    for ax, name in zip(fig.axes, ("psi", "theta", "phi"), strict=True):
        analytic_line, true_line = ax.get_lines()
        np.testing.assert_array_equal(analytic_line.get_ydata(), angles[name])
        assert ax.get_ylabel().endswith("[rad]")
    assert labels_of(fig.axes[0]) == ["analytic", "true (integrated)"]


def test_orientation_body_axes_and_spin_trace(disk, out_dir):
    t, angles = disk
    indices = (0, 40, 80)  # a third of a period apart; sample times: exact, no interpolation
    fig = plot_orientation(t, angles, t[list(indices)], time_unit="")
    assert len(fig.axes) == 3
    rotations = rotation_matrix(angles["psi"], angles["theta"], angles["phi"])
    for ax, index in zip(fig.axes, indices, strict=True):
        vertical, *body, trace = ax.get_lines()
        np.testing.assert_array_equal(np.array(vertical.get_data_3d()), [[0, 0], [0, 0], [-1, 1]])
        for k, line in enumerate(body):
            segment = np.array(line.get_data_3d())
            np.testing.assert_array_equal(segment[:, 0], 0.0)
            np.testing.assert_allclose(segment[:, 1], rotations[index][:, k], atol=1e-12)
        trace = np.array(trace.get_data_3d()).T
        np.testing.assert_allclose(trace, rotations[:, :, 2], atol=ROTATION)
        np.testing.assert_allclose(np.linalg.norm(trace, axis=1), 1.0, atol=1e-12)
        assert ax.get_zlabel().startswith("$Z$") and "[1]" in ax.get_xlabel()
        assert ax.get_title() == f"$t$ = {t[index]:.4g}"
    assert figure_legend_labels(fig) == [
        "body $x$ axis",
        "body $y$ axis",
        "body $z$ axis (spin)",
        "spin-axis trace",
    ]
    save(fig, out_dir, "orientation.png")


def test_orientation_with_a_partly_filled_grid_can_be_saved(disk, tmp_path):
    """Four instants on a 2 x 3 grid: the two unused 3-D axes are removed, not hidden (a hidden
    3-D axes made the constrained layout fail on saving; found by the disk scene, issue 13)."""
    t, angles = disk
    fig = plot_orientation(t, angles, t[[0, 20, 40, 60]], time_unit="")
    assert len(fig.axes) == 4
    fig.savefig(tmp_path / "orientation.png")
    assert (tmp_path / "orientation.png").stat().st_size > 0


def test_orientation_without_trace_and_bad_instants(disk):
    t, angles = disk
    fig = plot_orientation(t, angles, [t[5]], spin_trace=False)
    assert len(fig.axes[0].get_lines()) == 4  # the vertical and the three body axes
    for instants in ([t[-1] + 1.0], list(t[:7]), []):
        with pytest.raises(InvalidParameterError, match="`instants`"):
            plot_orientation(t, angles, instants)


def test_gif_has_the_requested_frames(disk, out_dir):
    from PIL import Image

    t, angles = disk
    path = os.path.join(out_dir, "orientation.gif")
    fig = animate_orientation(t, angles, path, fps=10, frames=6)
    assert isinstance(fig, Figure)
    with Image.open(path) as gif:
        assert gif.format == "GIF"
        assert gif.n_frames == 6
        assert gif.info["duration"] == 100  # ms per frame at 10 fps
        first = np.asarray(gif.convert("RGB"))
        gif.seek(3)
        assert np.any(np.asarray(gif.convert("RGB")) != first)  # the body turns between frames


def test_gif_bad_path(disk, tmp_path):
    t, angles = disk
    with pytest.raises(InvalidParameterError, match="`path`"):
        animate_orientation(t, angles, tmp_path / "orientation.png")
    with pytest.raises(InvalidParameterError, match="`path`"):
        animate_orientation(t, angles, tmp_path / "missing" / "orientation.gif")
    with pytest.raises(InvalidParameterError, match="`frames`"):
        animate_orientation(t, angles, tmp_path / "o.gif", frames=0)


@pytest.mark.parametrize(
    "name, shown",
    [
        ("x", "$x$"),
        ("xdot", "$\\dot{x}$"),
        ("x2dot", "$\\dot{x}_{2}$"),
        ("gamma1", "$\\gamma_{1}$"),
        ("theta", "$\\theta$"),
        ("eps", "$\\varepsilon$"),
        ("amplitude", "amplitude"),
        ("beta_1", "beta_1"),
    ],
)
def test_display_names(name, shown):
    from perturb.report.plots.style import display_name

    assert display_name(name) == shown


# ------------------------------------------------------------------------------ bad input
@pytest.mark.parametrize(
    "call, name",
    [
        (lambda t, a, tr: plot_time_series(t[::-1], a), "t"),
        (lambda t, a, tr: plot_time_series(t, a, names=["y"]), "analytic"),
        (
            lambda t, a, tr: plot_time_series(t, a, {"x": tr["x"][:-1], "xdot": tr["xdot"]}),
            "true['x']",
        ),
        (lambda t, a, tr: plot_error(t, a, None), "true"),
        (lambda t, a, tr: plot_phase(a, pairs=[("x",)]), "pairs"),
        (lambda t, a, tr: plot_time_series(t, a, units={"x": 1}), "units"),
        (lambda t, a, tr: plot_convergence([0.1, -0.2], [1e-3, 1e-2], order=1), "epsilons"),
        (lambda t, a, tr: plot_convergence([0.1, 0.2], [1e-3], order=1), "errors"),
        (lambda t, a, tr: plot_convergence([0.1, 0.2], [1e-3, 1e-2], order=-1), "order"),
        (
            lambda t, a, tr: plot_convergence([0.1, 0.2], [1e-3, 1e-2], order=1, slope_band=-1),
            "slope_band",
        ),
        (lambda t, a, tr: plot_work_precision(object()), "result"),
        (lambda t, a, tr: plot_euler_angles(t, a), "angles"),
    ],
)
def test_bad_input_names_the_argument(duffing, call, name):
    t, analytic, true = duffing
    with pytest.raises(InvalidParameterError) as info:
        call(t, analytic, true)
    message = str(info.value)
    assert message.startswith(f"`{name}`") and "\n" not in message


def test_missing_matplotlib_is_one_clear_import_error(duffing, monkeypatch):
    t, analytic, _ = duffing
    for module in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.setitem(sys.modules, module, None)
    with pytest.raises(
        ImportError, match=r"^plots need matplotlib: pip install 'perturb-poincare\[plot\]'"
    ) as info:
        plot_time_series(t, analytic)
    assert isinstance(info.value, MissingDependencyError)


def test_importing_the_plots_does_not_import_matplotlib():
    code = (
        "import sys, perturb.report.plots, perturb.workprecision, perturb.cli; "
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('matplotlib', 'PIL')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[]"
