"""``perturb report SCENE.toml --output DIR``: a scene's report folder (the scene runner's front end).

The CLI is the one place that knows both ``problems`` (to load the scene's problem) and the report
leaves (to write the folder): it parses the scene (:mod:`perturb.scene.spec`), loads and checks the
problem and its parameters, runs the lazy pipeline (:mod:`perturb.scene.run`) and writes the folder
(:mod:`perturb.report.scene_output`).
"""

from __future__ import annotations

import sys

from perturb._install import install_hint, installed
from perturb.cli._errors import EXIT_FAILED, EXIT_OK, _UsageError
from perturb.errors import InvalidParameterError, ProblemLoadError, UnknownNameError


def _load(scene):
    """The scene's problem, created with its parameters and family (errors name the scene file)."""
    from perturb.scene import check_parameter_names, check_sweep_names, problem_spec
    from problems import load_problem

    try:
        cls = load_problem(problem_spec(scene))
    except (UnknownNameError, ProblemLoadError) as exc:
        raise scene.error(f"[problem] name: {exc}") from None
    check_parameter_names(scene, [s.name for s in cls.parameter_specs], cls.name)
    check_sweep_names(scene, [s.name for s in cls.parameter_specs], cls.name)
    try:
        problem = cls.create(**scene.parameters)
    except (InvalidParameterError, UnknownNameError) as exc:
        raise scene.error(f"[parameters] {exc}") from None
    if scene.family is not None:
        from perturb.scene.run import with_order

        scene = with_order(scene, problem)
        try:
            problem.families(scene.order).get(scene.family)
        except UnknownNameError as exc:
            if scene.sweep is None or not scene.outputs.needs_sweep:
                raise scene.error(f"[problem] family: {exc}") from None
            problem = _family_along_sweep(scene, problem, exc)
        problem = problem.case().with_family(scene.family).model
    return problem


def _family_along_sweep(scene, problem, exc):
    """A family the scene's values do not have, looked for along its ``[sweep]`` grid."""
    from perturb.sweep.grid import Grid, parse_axis
    from perturb.sweep.spec import check_family

    grid = Grid(tuple(parse_axis(axis) for axis in scene.sweep.grid))
    try:
        return check_family(problem, scene.family, grid, scene.order)
    except UnknownNameError:
        raise scene.error(f"[problem] family: {exc} (nor anywhere on the [sweep] grid)") from None


def _cmd_report(args) -> int:
    from perturb.report.scene_output import prepare_folder, write_report
    from perturb.scene import read_scene
    from perturb.scene.run import check_scene, run_scene, with_order

    scene = read_scene(args.scene)
    if scene.sweep is not None and scene.outputs.needs_sweep:
        from perturb.errors import MissingDependencyError
        from perturb.sweep.api import require_extra

        try:
            require_extra()
        except MissingDependencyError as exc:
            raise _UsageError(f"{args.scene}: [sweep] {exc}, or remove the sweep") from None
    if scene.outputs.plots:
        if not installed("matplotlib"):
            raise _UsageError(
                f"{args.scene}: [outputs] plots need matplotlib: {install_hint('plot')}, or "
                "remove the plots"
            )
    problem = _load(scene)
    scene = with_order(scene, problem)  # without [solve] order: the default of its kind
    check_scene(scene, problem, args.yes)
    # the folder is claimed now, before the computation: unwritable, or holding a file perturb
    # did not write where the report writes, it is refused (exit 2) with nothing computed
    folder = prepare_folder(args.output, scene, force=args.force)
    result = run_scene(scene, problem, args.yes)
    _, summary = write_report(result, folder)
    print(summary, end="")
    if not result.success:  # the summary says why; stderr too, in one line
        why = result.failure or (result.validation.message if result.validation else "")
        print(f"perturb: {args.scene}: {' '.join(str(why).split())}", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK
