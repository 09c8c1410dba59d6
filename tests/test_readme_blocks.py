"""Every runnable README block says how ``.ci/readme_blocks.py`` checks it (issue 27).

The check itself (each block in a fresh venv) runs in ``.ci/run``; here, fast, only that the
README can be read by it: every ``bash``/``python`` block carries a directive, the install blocks
create their own environment, and the main job's block asks for the paper-geometry true orbit.
"""

import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _runner():
    spec = importlib.util.spec_from_file_location(
        "readme_blocks", ROOT / ".ci" / "readme_blocks.py"
    )
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # the dataclasses of the script look their module up
    spec.loader.exec_module(module)
    return module


def test_every_runnable_block_has_a_directive():
    runner = _runner()
    blocks = runner.parse((ROOT / "README.md").read_text())
    bare = [b.line for b in blocks if b.language in runner.RUNNABLE and not b.options]
    assert not bare, f"README.md blocks at lines {bare} need a <!-- readme-check: ... --> line"


def test_blocks_that_install_run_in_their_own_environment():
    runner = _runner()
    blocks = runner.parse((ROOT / "README.md").read_text())
    installs = [b for b in blocks if "pip install" in b.text and "skip" not in b.options]
    assert installs and all("venv" in b.options for b in installs)
    # one environment per install block: none reuses another's extras by accident
    names = [b.options["venv"] for b in installs]
    assert len(names) == len(set(names)), names


def test_the_main_job_must_show_the_true_orbit():
    runner = _runner()
    (main_job,) = [
        b
        for b in runner.parse((ROOT / "README.md").read_text())
        if "reproduce paper" in b.text and b.language == "bash"
    ]
    assert "pip install -e ." in main_job.text
    assert "true orbit" in main_job.options["expect"] and "not found" in main_job.options["absent"]


def test_the_parser_reads_directives_and_fences(tmp_path):
    runner = _runner()
    text = (
        '<!-- readme-check: venv=a expect="x y" -->\n```bash\necho x y\n```\n\n'
        "prose\n\n```python\nprint(1)\n```\n"
    )
    first, second = runner.parse(text)
    assert first.options == {"venv": "a", "expect": "x y"} and first.text == "echo x y\n"
    assert second.options == {} and second.language == "python"
