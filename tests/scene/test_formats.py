"""Output formats everywhere (issue 13 items 4-5): ``--format latex`` and ``--output PATH`` on every
command, and the notebook display of solutions, validation reports and work-precision results."""

from __future__ import annotations

import json

import pytest

from perturb.cli import main
from problems import get_problem


def run(capsys, *argv) -> tuple[int, str, str]:
    code = main([*argv, "--quiet"])
    out, err = capsys.readouterr()
    return code, out, err


def _balanced(tex: str) -> None:
    """Environments opened are closed, in order; braces balance."""
    opened = []
    for token in tex.replace("\\begin{", "\n\\begin{").replace("\\end{", "\n\\end{").split("\n"):
        if token.startswith("\\begin{"):
            opened.append(token[7 : token.index("}")])
        elif token.startswith("\\end{"):
            assert opened.pop() == token[5 : token.index("}")]
    assert not opened
    assert tex.count("{") - tex.count("\\{") == tex.count("}") - tex.count("\\}")


def test_solve_latex_has_the_formulas_and_the_state_table(capsys):
    code, out, _ = run(capsys, "solve", "duffing", "--set", "eps=0.05", "--order", "2",
                       "--times", "0,1,2", "--format", "latex")  # fmt: skip
    assert code == 0
    _balanced(out)
    assert "\\begin{align*}" in out and "x &= " in out and "T &= " in out
    body = out.split("\\midrule\n")[1].split("\\bottomrule")[0].strip().splitlines()
    assert len(body) == 3 and body[0].startswith("$0$ & $1$")


@pytest.mark.parametrize(
    "argv, fragments",
    [
        (["validate", "duffing", "--set", "eps=0.05", "--periods", "2"],
         ["check & value", "$\\le$", "% verdict: The analytic solution describes"]),
        (["families", "resonant-pair"], ["anti-phase", "$\\Omega$"]),
        (["list"], ["problem & parameter & default & meaning", "duffing"]),
    ],
)  # fmt: skip
def test_latex_format_of_the_other_commands(capsys, argv, fragments):
    code, out, _ = run(capsys, *argv, "--format", "latex")
    assert code == 0
    _balanced(out)
    assert out.count("\\begin{tabular}") == 1
    for fragment in fragments:
        assert fragment in out


def test_list_json_names_every_problem_with_its_parameters(capsys):
    from problems import problem_names

    code, out, _ = run(capsys, "list", "--format", "json")
    data = json.loads(out)
    assert code == 0 and [p["name"] for p in data] == problem_names()
    duffing = next(p for p in data if p["name"] == "duffing")
    assert [p["name"] for p in duffing["parameters"]] == [
        s.name for s in get_problem("duffing").parameter_specs
    ]


def test_list_table_is_unchanged_by_default(capsys):
    _, default, _ = run(capsys, "list")
    _, table, _ = run(capsys, "list", "--format", "table")
    from problems import problem_names

    assert default == table and default.startswith(f"{problem_names()[0]} ")


@pytest.mark.parametrize("fmt", ["json", "csv", "table", "latex"])
def test_output_file_holds_exactly_what_would_be_printed(capsys, tmp_path, fmt):
    argv = ["solve", "duffing", "--set", "eps=0.05", "--times", "0,1", "--format", fmt]
    _, printed, _ = run(capsys, *argv)
    target = tmp_path / f"out.{fmt}"
    code, out, _ = run(capsys, *argv, "--output", str(target))
    assert code == 0 and out == ""
    assert target.read_text(encoding="utf-8") == printed


def test_output_file_of_validate_and_families(capsys, tmp_path):
    target = tmp_path / "families.json"
    code, out, _ = run(capsys, "families", "duffing", "--format", "json", "--output", str(target))
    assert code == 0 and out == "" and json.loads(target.read_text())["problem"] == "duffing"


@pytest.mark.parametrize("where", ["missing/out.json", "."])
def test_unwritable_output_file_exits_2(capsys, tmp_path, where):
    code, out, err = run(capsys, "solve", "duffing", "--output", str(tmp_path / where))
    assert code == 2 and out == "" and err.count("\n") == 1 and "--output" in err


def test_reproduce_keeps_its_output_folder():
    from perturb.cli._parser import _build_parser

    args = _build_parser().parse_args(["reproduce", "paper", "--output", "dir"])
    assert args.output == "dir"  # a folder of report files, as before (not redirected)


# ---------------------------------------------------------------------------------- notebooks
def test_solution_renders_as_aligned_latex():
    solution = get_problem("duffing").create().solve(2)
    tex = solution._repr_latex_()
    assert tex.startswith("$\\displaystyle \\begin{aligned}") and tex.endswith("\\end{aligned}$")
    assert "x &= " in tex and "T &= " in tex
    _balanced(tex)


def test_validation_and_work_precision_render_as_html_once_loaded():
    ipython = pytest.importorskip("IPython")
    from IPython.core.interactiveshell import InteractiveShell

    from perturb.validation import validate
    from perturb.workprecision import WorkPoint, WorkPrecision

    shell = InteractiveShell.instance()
    report = validate(get_problem("duffing").create(eps=0.05), periods=2, slope=False)
    result = WorkPrecision(
        "duffing", 2.0, 12.5, "DOP853", (WorkPoint("rk4", "10 steps", 1e-3, 0.1),)
    )
    html_formatter = shell.display_formatter.formatters["text/html"]
    before = html_formatter(report)
    shell.run_line_magic("load_ext", "perturb.report")
    data, _ = shell.display_formatter.format(report)
    assert before is None and "text/html" in data
    assert report.outcome.name in data["text/html"] and "<table>" in data["text/html"]
    data, _ = shell.display_formatter.format(result)
    assert "<td>rk4</td>" in data["text/html"] and "DOP853" in data["text/html"]
    assert ipython is not None


def test_work_precision_latex_table():
    from perturb.report.latex import work_precision_latex
    from perturb.workprecision import WorkPoint, WorkPrecision

    points = (WorkPoint("rk4", "10 steps/unit", 1.5e-3, 0.25), WorkPoint("heyoka", "tol=eps",
              float("nan"), 0.001))  # fmt: skip
    tex = work_precision_latex(WorkPrecision("duffing", 2.0, 12.5, "DOP853", points))
    _balanced(tex)
    assert "method & setting & error & seconds" in tex
    assert "rk4 & 10 steps/unit & $0.0015$ & $0.25$" in tex
    assert "heyoka & tol=eps & -- & $0.001$" in tex
