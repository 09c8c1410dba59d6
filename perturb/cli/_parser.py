"""The argument parser: commands, options and their help (never abbreviated)."""

from __future__ import annotations

import argparse

from perturb._defaults import DRIVEN_ORDER, FREE_ORDER
from perturb.cli._errors import _UsageError
from perturb.report.formats import choices as _format_choices

_EPILOG = """examples:
  perturb --version
  perturb list
  perturb solve duffing --set eps=0.05 --set amplitude=1.2 --order 2
  perturb solve van-der-pol --order 3 --times 0,1,2,3 --format json
  perturb solve disk --euler --format json
  perturb solve my_oscillator.py:MyOscillator --set eps=0.05   (your own Problem subclass)
  perturb validate duffing --set eps=0.05
  perturb families resonant-pair --order 2
  perturb response forced-duffing --sweep Omega=0.9:1.3:81 --set F=1 --validate 2
  perturb solve resonant-pair --family anti-phase
  perturb reproduce paper
  perturb work-precision duffing --periods 10 --orders 3 --format csv
  perturb report examples/scenes/disk-fast-spin.toml --output disk-report
  perturb sweep duffing --grid eps=0.01:0.2:20 --grid amplitude=0.5:2:16 --validate --output duffing.zarr
  perturb phase-diagram coupled-parametrons --grid Omega=1.98:2.02:21 --grid h=0.2:3:15 --plot map.png
  perturb basins forced-duffing --set Omega=1.05 --grid x=-3:3:200 --grid xdot=-3:3:200 --plot basins.png
  perturb transient forced-duffing --set Omega=1.05 --from x=0,xdot=0 --periods 300 --plot transient.png
  perturb ramp forced-duffing --set eps=0.02 --set F=0.5 --sweep Omega=0.99:1.06 --rate 5e-6 --both-ways
"""


#: Errors about the user's input (exit 2); every other exception inside a run is a failure (exit 1).


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)  # `--order` must never mean `--orders`
        super().__init__(*args, **kwargs)

    def error(self, message):  # one line, exit 2, no usage dump
        raise _UsageError(message)


def _add_problem_arguments(parser: argparse.ArgumentParser, *, order: bool = True) -> None:
    """PROBLEM, --set (and --order): shared by every command that builds a problem's solution."""
    parser.add_argument(
        "problem",
        help="problem name (see `perturb list`), path/to/file.py:Class or package.module:Class",
    )
    parser.add_argument(
        "--set",
        dest="sets",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="set a parameter (repeatable); unset parameters take their defaults",
    )
    if order:  # the default: perturb.cli._order (one rule for every command)
        parser.add_argument(
            "--order",
            default=None,
            help=f"highest power of the small parameter kept (integer >= 1; default "
            f"{DRIVEN_ORDER} for a driven problem, whose response is continued, {FREE_ORDER} for "
            "a free one)",
        )


def _add_format(parser: argparse.ArgumentParser, kind: str) -> None:
    """``--format``, its choices the formats that write results of ``kind``
    (:mod:`perturb.report.formats`)."""
    parser.add_argument(
        "--format",
        default="table",
        choices=_format_choices(kind),
        help="output format (default table)",
    )


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="perturb",
        description="Periodic solutions of oscillating systems by Poincaré's method, checked against the true motion.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "--version", action="store_true", help="print perturb's version and exit"
    )  # answered by the entry point (argparse's own version action would exit inside main())
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    listing = sub.add_parser("list", help="list the registered problems and their parameters")
    _add_format(listing, "problems")
    solve = sub.add_parser(
        "solve",
        help="construct a problem's periodic solution and print its state",
        description="Construct PROBLEM's periodic solution by Poincaré's method and print the state "
        "at the requested times (default: one period, 101 samples from t = 0).",
    )
    _add_problem_arguments(solve)
    solve.add_argument(
        "--times",
        default=None,
        metavar="TIMES",
        help="times (physical units): T1,T2,... or START:STOP:N (N evenly spaced, both ends "
        "included) or @FILE (one value a line, or comma-separated; '#' starts a comment)",
    )
    _add_format(solve, "solution")
    solve.add_argument(
        "--euler", action="store_true", help="add the Euler angles (rigid bodies only)"
    )
    solve.add_argument(
        "--latex",
        action="store_true",
        help="also print the symbolic solution (coordinates and period) as LaTeX",
    )
    solve.add_argument(
        "--steps",
        action="store_true",
        help="also print the construction order by order (forcing, quadratures, conditions, solved)",
    )
    validate = sub.add_parser(
        "validate",
        help="check a problem's periodic solution against the true motion and give a verdict",
        description="Integrate the original equations from the analytic initial state, find the true "
        "periodic orbit by shooting, measure the errors and their slope in the expansion parameter, "
        "and say whether the analytic solution is valid.",
    )
    _add_problem_arguments(validate)
    validate.add_argument(
        "--integrator",
        default=None,
        help="rk4, dop853, rk45, radau, lsoda or heyoka (default: heyoka if installed, else dop853)",
    )
    validate.add_argument(
        "--periods",
        default="10",
        help="horizon of the trajectory comparison, in periods (default 10; information only)",
    )
    validate.add_argument(
        "--tol",
        default=None,
        help="accuracy tolerance: largest relative distance of the analytic orbit and period from "
        "the true ones (default 0.1)",
    )
    _add_format(validate, "validation")
    work = sub.add_parser(
        "work-precision",
        help="error against run time: analytic orders 1..N, RK4, scipy and heyoka",
        description="For PROBLEM over a horizon, measure the error against a reference trajectory and "
        "the wall time (best of repeated runs after a warm-up) of the analytic solution at orders 1..N "
        "(derivation and evaluation timed apart), RK4 at several steps, the scipy methods at "
        "several tolerances and heyoka.",
    )
    _add_problem_arguments(work, order=False)
    work.add_argument("--periods", default="10", help="horizon in periods (default 10)")
    work.add_argument("--orders", default="3", help="analytic orders 1..N (default 3)")
    work.add_argument(
        "--repeat",
        default="3",
        help="timed runs per point after one untimed warm-up, best reported (default 3)",
    )
    work.add_argument(
        "--plot",
        default=None,
        metavar="FILE",
        help="also save a work-precision plot (needs matplotlib)",
    )
    work.add_argument(
        "--yes",
        action="store_true",
        help="confirm a run estimated at more than an hour of work (many periods, many runs)",
    )
    _add_format(work, "work-precision")
    reproduce = sub.add_parser(
        "reproduce",
        help="reproduce a published paper's numbers beside the true motion",
        description="Reproduce a paper's printed constants and tables, the corrected solution and the "
        "true motion, and list its errata.",
    )
    reproduce.add_argument("paper", help="paper name (`paper`: the seed paper on the disk)")
    _add_format(reproduce, "reproduction")
    reproduce.add_argument(
        "--full",
        action="store_true",
        help="print the full tables after the summary (json output is always complete)",
    )
    reproduce.add_argument(
        "--output", default=None, metavar="DIR", help="also write the report files into DIR"
    )
    _add_family_arguments(sub, solve, validate)
    _add_response(sub)
    report = sub.add_parser(
        "report",
        help="write a scene's report folder: only the tables, checks and plots it asks for",
        description="Read SCENE (a TOML file: [problem], [parameters], [solve], [outputs], "
        "[work_precision]), compute only what its [outputs] ask for and write it into DIR with a "
        "copy of the scene and summary.md (the verdict), which is also printed.",
    )
    report.add_argument("scene", metavar="SCENE", help="the scene file (TOML)")
    report.add_argument(
        "--output", required=True, metavar="DIR", help="the report folder (created if missing)"
    )
    report.add_argument(
        "--yes",
        action="store_true",
        help="confirm a scene whose [response] or [sweep] is estimated at more than an hour of "
        "work",
    )
    report.add_argument(
        "--force",
        action="store_true",
        help="replace perturb's own files of another scene's report in DIR (a file perturb did "
        "not write is never overwritten)",
    )
    _add_sweep(sub)
    _add_phase(sub)
    from perturb.cli._dynamics import add_dynamics_commands

    add_dynamics_commands(sub, _add_problem_arguments, _add_format)
    for name, command in sub.choices.items():
        if name not in ("reproduce", "report", "sweep", "phase-diagram", "basins"):  # a store
            command.add_argument(
                "--output",
                default=None,
                metavar="PATH",
                help="write the output into the file PATH instead of printing it",
            )
        if name not in ("reproduce", "report"):
            command.add_argument(
                "--force",
                action="store_true",
                help="overwrite an existing --output/--plot file that perturb did not write "
                "(without it such a file is refused: exit 2)",
            )
        command.add_argument(
            "--quiet",
            action="store_true",
            help="no progress on stderr (a bar on a terminal; otherwise a line when a step "
            "has lasted half a second, then every 10 s)",
        )
    return parser


def _add_response(sub) -> None:
    """``perturb response``: a driven problem's frequency response."""
    response = sub.add_parser(
        "response",
        help="a driven problem's frequency response: every branch, its stability, the folds",
        description="Sweep one parameter of a driven (forced, damped, parametrically excited) "
        "PROBLEM: every steady-state branch of its order-N response, continued along the sweep "
        "from the certified first-order census through its folds, each point's stability "
        "(Floquet multipliers of the variational equation along the order-N series), the folds, "
        "branch points and Neimark-Sacker points (inside the sweep and just beside it), the "
        "series' own error estimate and the backbone of the free system; with --validate K, the "
        "true orbit is shot at K points of every branch spread by arclength, and always at its "
        "largest amplitude, both sides of each fold and its ends.",
    )
    _add_problem_arguments(response)
    response.add_argument(
        "--sweep", required=True, metavar="NAME=START:STOP:N",
        help="the parameter swept and its grid (N >= 2 values, START < STOP), e.g. Omega=0.9:1.2:61",
    )  # fmt: skip
    response.add_argument(
        "--validate", default="0", metavar="K",
        help="shoot the true orbit at K points of every branch spread by arclength, besides its "
        "largest amplitude, both sides of each fold and its ends (default 0: none; at most 50)",
    )  # fmt: skip
    response.add_argument(
        "--measure", default="peak", choices=["peak", "first-harmonic", "initial"],
        help="the amplitude drawn and printed: peak = max |x| over a period (default), "
        "first-harmonic, or initial = |(x(0), xdot(0)/(m nu))|",
    )  # fmt: skip
    response.add_argument(
        "--tol", default=None, metavar="TOL",
        help="relative orbit error above which a shot point is marked, and relative amplitude "
        "difference at which the analytic and true curves part (--true) (default 0.1)",
    )  # fmt: skip
    response.add_argument(
        "--true", nargs="?", const="default", default=None, metavar="POINTS", dest="true_curve",
        help="also continue the TRUE periodic orbits from the branches (shooting with the period "
        "fixed, pseudo-arclength, Floquet multipliers) and report their folds, period doublings, "
        "Neimark-Sacker and branch points and where the analytic curve parts from them; at most "
        "POINTS points per curve (default 1000, at most 10000)",
    )  # fmt: skip
    response.add_argument(
        "--max-period", default=None, metavar="K", dest="max_period",
        help="with --true: follow the period doublings of the true curves while the period stays "
        "at most K response periods (default 2: the doubled orbits; 1: none; at most 16); the "
        "branches born at branch points are always followed",
    )  # fmt: skip
    response.add_argument(
        "--plot", default=None, metavar="FILE",
        help="also save the frequency-response plot (needs matplotlib)",
    )  # fmt: skip
    response.add_argument(
        "--yes", action="store_true",
        help="confirm a request estimated at more than an hour of work (many values, a high "
        "order, many shots)",
    )  # fmt: skip
    _add_format(response, "response")


def _add_family_arguments(sub, solve, validate) -> None:
    """``perturb families`` and the ``--family NAME`` option of ``solve`` and ``validate``."""
    families = sub.add_parser(
        "families",
        help="every family of periodic solutions a problem admits, each carried to order N",
        description="List every family of periodic solutions of PROBLEM that the first order "
        "selecting the generating amplitudes admits (isolated roots and continua, with the free "
        "amplitude named), each with its name, the amplitudes that select it, and its status "
        "carried to --order. Select one in `solve`/`validate` with --family NAME.",
    )
    _add_problem_arguments(families)
    _add_format(families, "families")
    for command in (solve, validate):
        command.add_argument(
            "--family",
            default=None,
            metavar="NAME",
            help="follow the family NAME (see `perturb families PROBLEM`) instead of the default",
        )


def _add_phase(sub) -> None:
    """``perturb phase-diagram``: the number of stable steady states over two parameters."""
    phase = sub.add_parser(
        "phase-diagram",
        help="a driven problem's number of stable steady states over two parameters, on Dask",
        description="Count PROBLEM's steady states, and its stable ones, at every point of a grid "
        "over two parameters: the order-N response continued along each line of the grid "
        "(stability from the Floquet multipliers), the certified first-order count at every "
        "point, the folds, branch points and Neimark-Sacker points where the lines cross them. "
        "The lines run on a Dask cluster; --output writes a Zarr store, --plot the map with its "
        "boundaries. Needs the extra perturb[sweep].",
    )
    _add_problem_arguments(phase)
    phase.add_argument(
        "--grid",
        dest="grids",
        action="append",
        default=[],
        metavar="NAME=START:STOP:N",
        help="the two parameters, x first (e.g. --grid Omega=0.98:1.1:41 --grid F=0.5:2:21)",
    )
    phase.add_argument(
        "--rows-only",
        action="store_true",
        help="continue along x only (half the work; no second count, no boundary running along x)",
    )
    phase.add_argument("--workers", default=None, help="worker processes of the local Dask cluster")
    phase.add_argument(
        "--scheduler", default=None, metavar="ADDRESS", help="an existing Dask scheduler"
    )
    phase.add_argument(
        "--output", default=None, metavar="STORE", help="write the maps to this Zarr store"
    )
    phase.add_argument(
        "--plot", default=None, metavar="FILE", help="also save the map (needs matplotlib)"
    )
    phase.add_argument(
        "--map",
        default="order-n",
        choices=["order-n", "first-order"],
        help="the map --plot draws: order-n (default: the order-N responses continued along x, "
        "Floquet stability, the special points located on them: right where the amplitude is "
        "large) or first-order (the certified first-order count at every point, slow-flow "
        "stability, the exact first-order boundaries: off by O(eps) at large amplitude)",
    )
    phase.add_argument(
        "--yes",
        action="store_true",
        help=f"confirm a grid of more than {10**7:,} points, or estimated at more than an hour "
        "of work",
    )
    _add_format(phase, "phase")


def _add_sweep(sub) -> None:
    """``perturb sweep``: a problem's solution over a grid of its parameters, on Dask."""
    sweep = sub.add_parser(
        "sweep",
        help="evaluate (and validate) a problem's solution over a grid of parameters, on Dask",
        description="Derive PROBLEM's periodic solution once, then evaluate it at every point of "
        "the grid (period, frequency, amplitudes, the state at --times) and, with --validate, "
        "shoot and judge each point as `perturb validate` does. The points run in chunks on a "
        "Dask cluster (a LocalCluster over this machine's cores, or --scheduler) and are written "
        "to the Zarr store --output as they finish; --resume continues an interrupted sweep. "
        "Needs the extra perturb[sweep].",
    )
    _add_problem_arguments(sweep)
    sweep.add_argument(
        "--grid",
        dest="grids",
        action="append",
        default=[],
        metavar="NAME=START:STOP:N",
        help="a swept parameter (repeatable; one dimension each): N evenly spaced values from "
        "START to STOP, both included; NAME=START:STOP:N:log for evenly spaced logarithms; "
        "NAME=V1,V2,... for listed values",
    )
    sweep.add_argument(
        "--validate",
        action="store_true",
        help="also validate every point against the true motion (verdict, orbit and period "
        "errors, Floquet multipliers, order slope)",
    )
    sweep.add_argument(
        "--times",
        default=None,
        metavar="TIMES",
        help="times at which the state is recorded (physical units; default 0): as for solve",
    )
    sweep.add_argument("--family", default=None, metavar="NAME", help="follow the family NAME")
    sweep.add_argument(
        "--integrator", default=None, help="the validation's integrator (as for validate)"
    )
    sweep.add_argument(
        "--periods", default="10", help="the validation's trajectory horizon (default 10)"
    )
    sweep.add_argument("--tol", default=None, help="the validation's tolerance (default 0.1)")
    sweep.add_argument(
        "--derive",
        default="auto",
        choices=["auto", "per-point"],
        help="auto (default): one derivation, symbolic in the swept parameters where the "
        "problem allows; per-point: each point's own derivation, as `perturb validate` does",
    )
    sweep.add_argument(
        "--workers",
        default=None,
        help="worker processes of the local Dask cluster (default: one per core)",
    )
    sweep.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="run on an existing Dask cluster: its scheduler's address, tcp://HOST:PORT",
    )
    sweep.add_argument(
        "--timeout",
        default=None,
        metavar="SECONDS",
        help="how long to wait for --scheduler to answer (default 10)",
    )
    sweep.add_argument(
        "--output",
        default=None,
        metavar="STORE",
        help="the Zarr store written chunk by chunk (with --format csv|json: the file written "
        "instead of printing)",
    )
    sweep.add_argument(
        "--chunk-points",
        default=None,
        metavar="N",
        help="points per task and per chunk of the store (default: about 2 s of work each, "
        "from a pilot)",
    )
    sweep.add_argument(
        "--resume",
        action="store_true",
        help="continue the sweep in the store --output (the same command): no point twice",
    )
    sweep.add_argument(
        "--format",
        default="zarr",
        choices=_format_choices("sweep"),
        help="zarr (default: the store --output, a summary printed), or csv/json of every point "
        "(small sweeps)",
    )
    sweep.add_argument(
        "--yes",
        action="store_true",
        help=f"confirm a grid of more than {10**7:,} points, or estimated at more than an hour "
        "of work",
    )
