"""Scenes: a TOML file naming a problem, its parameters and the outputs wanted
(``perturb report SCENE.toml --output DIR``).

Modules: :mod:`.spec` (the :class:`Scene` value object and its strict parser), :mod:`.checks`
(a scene's values and names checked, each failure one line), :mod:`.files`
(a scene read from its file, paths in it taken from its folder), :mod:`.run` (the
lazy pipeline: computes only what the outputs need). Writing the folder is the report leaf
:mod:`perturb.report.scene_output`, imported by the CLI only: a scene's results stay data.
"""

from perturb.scene.checks import check_parameter_names, check_sweep_names
from perturb.scene.files import problem_spec, read_scene
from perturb.scene.spec import (
    EULER_PLOTS,
    MAP_PLOTS,
    PLOT_FORMATS,
    PLOT_NAMES,
    TRUTH_PLOTS,
    Outputs,
    ResponseSettings,
    Scene,
    SweepSettings,
    WorkPrecisionSettings,
    parse_scene,
)


def __getattr__(name: str):
    """``run_scene`` and ``SceneResult``: imported on first use (they bring in the oracle)."""
    if name in ("run_scene", "SceneResult"):
        from perturb.scene import run

        return getattr(run, name)
    raise AttributeError(f"module 'perturb.scene' has no attribute {name!r}")


__all__ = [
    "EULER_PLOTS",
    "MAP_PLOTS",
    "PLOT_FORMATS",
    "PLOT_NAMES",
    "TRUTH_PLOTS",
    "Outputs",
    "Scene",
    "SceneResult",
    "ResponseSettings",
    "SweepSettings",
    "WorkPrecisionSettings",
    "check_parameter_names",
    "check_sweep_names",
    "parse_scene",
    "problem_spec",
    "read_scene",
    "run_scene",
]
