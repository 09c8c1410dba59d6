"""``perturb reproduce paper``: the one-screen summary, ``--full``, the JSON contract, the registry.

The summary is checked against the report it summarises (every figure is looked up in the report,
none is copied from a run); the JSON key tree is checked against the tree captured before the
paper's module was split into a package (``paper_report_keys.json``).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import attrs
import pytest

from perturb.cli import main
from perturb.errors import UnknownNameError
from problems import reproductions
from problems.reproductions import (
    Reproduction,
    get_reproduction,
    register_reproduction,
    reproduction_names,
)
from problems.rigid_body.paper import PaperReproduction, reproduce
from problems.rigid_body.paper.data import PAPER_CITATION, PRINTED_CONSTANTS, TABLE1_COLUMNS
from problems.rigid_body.paper.errata import ERRATA_STATUSES
from problems.rigid_body.paper.output import (
    SUMMARY_MAX_LINES,
    SUMMARY_MAX_WIDTH,
    full_text,
    summary_text,
)

pytestmark = pytest.mark.paper

KEYS_FILE = Path(__file__).with_name("paper_report_keys.json")


@pytest.fixture(scope="module")
def report():
    return reproduce("paper")


@pytest.fixture(scope="module")
def summary(report):
    return summary_text(report)


def _key_paths(value, prefix="") -> set[str]:
    """Every dict key of a JSON value as a '/'-separated path; '[]' marks list elements."""
    paths: set[str] = set()
    if isinstance(value, dict):
        for key, item in value.items():
            path = f"{prefix}/{key}"
            paths.add(path)
            paths |= _key_paths(item, path)
    elif isinstance(value, list):
        for item in value:
            paths |= _key_paths(item, prefix + "[]")
    return paths


def _line(summary: str, start: str) -> str:
    (line,) = [s for s in summary.splitlines() if s.startswith(start)]
    return line


# ---------------------------------------------------------------------------- the summary
def test_summary_fits_one_screen(summary):
    lines = summary.splitlines()
    assert len(lines) <= SUMMARY_MAX_LINES
    assert max(len(line) for line in lines) <= SUMMARY_MAX_WIDTH


def test_summary_leads_with_the_verdict(report, summary):
    lines = summary.splitlines()
    assert lines[0].startswith("Reproduction of 'paper'")
    # the first unindented line after the title and the paper's citation block
    verdict = next(line for line in lines[1:] if line.strip() and not line.startswith(" "))
    assert verdict.startswith("VERDICT")
    assert not report.verdict["valid"]
    assert "does NOT hold" in verdict
    assert f"{report.verdict['numbers']['eps_c_over_r0']:.4g}" in verdict
    assert f"{report.verdict['numbers']['r_over_r0_min_0_300s']:.4g}" in summary


def test_summary_names_the_paper_and_how_to_read_it(summary):
    """A newcomer without the paper open: which paper, what (NN) and E# mean, where each is argued."""
    flat = " ".join(line.strip() for line in summary.splitlines()[:8])
    assert f'paper: "{PAPER_CITATION["title"]}"' in flat
    assert "(NN) = the paper's equation NN" in flat
    assert f"argued under its ID in {PAPER_CITATION['errata']}" in flat


def test_every_erratum_on_the_screen_is_argued_in_the_errata_file(report, summary):
    doc = (Path(__file__).resolve().parents[2] / PAPER_CITATION["errata"]).read_text()
    for eid in report.errata:
        assert eid in summary
        assert re.search(rf"(^#+ .*\b{eid}\b|\*\*{eid}\b)", doc, re.M), eid


def test_summary_counts_the_constants_matched(report, summary):
    matched = [name for name in PRINTED_CONSTANTS if report.constants[name]["matches"]]
    missed = [name for name in PRINTED_CONSTANTS if name not in matched]
    line = _line(summary, "constants (32)")
    assert f"{len(matched)}/{len(PRINTED_CONSTANTS)} printed values" in line
    assert missed == ["mu"]  # E1
    assert line.endswith("not: mu")


def test_summary_gives_table1_deviations(report, summary):
    check = report.table1_check
    total = len(report.table1["t"]) * len(TABLE1_COLUMNS)
    outside = sum(len(check[c]["rows_outside"]) for c in TABLE1_COLUMNS)
    assert f"{total - outside}/{total} entries within printed precision" in summary
    for c in TABLE1_COLUMNS:
        assert f"{c} {check[c]['max_deviation']:.2e}" in summary


def test_summary_gives_the_true_motion_discrepancy(report, summary):
    line = _line(summary, "true motion")
    for c, value in report.table2["true_motion"]["max_diff_vs_table1"].items():
        assert f"{c} {value:.3g}" in line
    ours = _line(summary, "corrected solution")
    for c, value in report.table2["corrected"]["max_diff_vs_true_motion"].items():
        assert f"{c} {value:.3g}" in ours


def test_summary_gives_the_rk4_outcome(report, summary):
    runs = report.experiment["runs"]
    blown = [run for run in runs.values() if "h_reached" in run]
    assert summary.count("blows up at h =") == len(blown) == 2  # E10: mu^2 and eps^2
    completed = runs["mu_minus_2"]
    assert f"max |RK4 - Table 1| {max(completed['max_diff_vs_table1'].values()):.2g}" in summary
    assert f"max |RK4 - true| {max(completed['max_diff_vs_true_motion'].values()):.3g}" in summary


def test_summary_gives_the_euler_angle_finding(report, summary):
    w = report.errata["E12"]["witness"]
    paper_row = _line(summary, "  paper - true")
    ours_row = _line(summary, "  ours - true")
    for angle in ("theta", "psi", "phi"):
        assert f"{angle} {w['true_vs_paper'][angle]:.2e}" in paper_row
        assert f"{angle} {w['true_vs_ours'][angle]:.2e}" in ours_row
    assert f"{w['slopes']['true_vs_paper']['psi']:.2f}" in paper_row


def test_summary_counts_the_errata_by_status(report, summary):
    line = _line(summary, "errata")
    for status in ERRATA_STATUSES:
        ids = [eid for eid, e in report.errata.items() if e["status"] == status]
        assert f"{len(ids)} {status}" in line
        assert _line(summary, f"  {status} ").split()[1:] == ids
    assert "docs/paper-errata.md" in line


def test_summary_leaves_the_tables_to_full(report, summary):
    assert "## " not in summary
    assert "--full" in summary
    # no column of Table 1 is listed: at most a couple of its printed values may appear by chance
    printed = {str(v) for column in TABLE1_COLUMNS for v in report.table1_printed[column]}
    assert sum(v in summary for v in printed if len(v) > 4) <= 2


def test_summary_without_the_corrected_solution(report):
    table2 = {**report.table2, "corrected": {"description": "-", "p2a": None, "unavailable": "x"}}
    text = summary_text(attrs.evolve(report, table2=table2))
    assert _line(text, "corrected solution").endswith("not available: x")


def test_summary_of_a_valid_verdict(report):
    text = summary_text(attrs.evolve(report, verdict={**report.verdict, "valid": True}))
    assert "holds for its own data" in text and "NOT" not in text


# ---------------------------------------------------------------------------- the CLI
@pytest.fixture
def cli_report(report, monkeypatch):
    """The CLI runs the registered reproduction; reuse the module's report instead of redoing it."""
    monkeypatch.setattr(PaperReproduction, "run", lambda self, output=None: report)
    return report


def test_cli_prints_the_summary_only(cli_report, capsys):
    assert main(["reproduce", "paper"]) == 0
    out = capsys.readouterr().out
    assert out.rstrip("\n") == summary_text(cli_report)


def test_cli_full_prints_the_summary_then_the_tables(cli_report, capsys):
    assert main(["reproduce", "paper", "--full"]) == 0
    out = capsys.readouterr().out
    summary, full = summary_text(cli_report), full_text(cli_report)
    assert out.startswith(summary)
    assert out.rstrip("\n").endswith(full.rstrip("\n"))
    for section in ("## Derived constants (32)", "## Table 1", "## Our Table 2", "## Errata"):
        assert section in out
    assert full == cli_report.as_table()


def test_cli_json_keeps_the_key_tree(capsys):
    """The JSON keys are a contract for users' scripts: every key of before the split is kept;
    the only additions are the extensions named here (issue 21: the paper geometry's true orbit;
    issue 27: the paper's citation)."""
    assert main(["reproduce", "paper", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    expected = set(json.loads(KEYS_FILE.read_text())["paths"])
    paths = _key_paths(data)
    assert expected <= paths
    assert {p.split("/")[1] for p in paths - expected} == {"true_orbit", "citation"}


# ---------------------------------------------------------------------------- the registry
def test_registry_knows_the_paper():
    assert "paper" in reproduction_names()
    assert isinstance(get_reproduction("paper"), PaperReproduction)


def test_registry_refuses_an_unknown_name():
    with pytest.raises(UnknownNameError, match=r"`paper` = 'nope' is unknown: choose from \["):
        get_reproduction("nope")


def test_registry_needs_a_reproduction_class():
    with pytest.raises(TypeError, match="Reproduction subclass"):
        register_reproduction("bad")(dict)


def test_cli_finds_reproductions_through_the_registry(monkeypatch, capsys):
    monkeypatch.setattr(reproductions, "_REGISTRY", dict(reproductions._REGISTRY))

    @register_reproduction("toy")
    class Toy(Reproduction):
        def run(self, output=None):
            return {"answer": 42}

        def as_dict(self, report):
            return report

        def summary(self, report):
            return "toy summary"

        def full(self, report):
            return "toy tables"

    assert main(["reproduce", "toy", "--full"]) == 0
    assert capsys.readouterr().out == "toy summary\n\ntoy tables\n"
    assert main(["reproduce", "toy", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out) == {"answer": 42}
    assert main(["reproduce", "nope"]) == 2
    assert "['paper', 'toy']" in capsys.readouterr().err
