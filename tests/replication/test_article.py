"""The replication's article (tennis_stroke.replication.article): written from the
results, every claim's value in its text, rebuilt when a result changes, the figures the
results' PNGs, a missing input one line."""

import shutil

import pandas as pd
import pypdf
import pytest
import yaml
from conftest import ROOT
from rescience_shape import departures

from tennis_stroke.replication.article import build_article
from tennis_stroke.replication.formats import _number
from tennis_stroke.replication.registry import FIGURES
from tennis_stroke.replication.report import ReportInputError
from tennis_stroke.replication.rescience import authors, read_citation

STATEMENTS = str(ROOT / "config" / "claims.yaml")


def _inputs(run):
    figures = sorted(str(p) for p in (run / "results" / "figures").glob("fig*.png"))
    results = [str(run / "results" / "angle_maps" / "fig2.nc")]
    return figures, results


def _text(pdf) -> str:
    reader = pypdf.PdfReader(pdf)
    text = " ".join(page.extract_text() for page in reader.pages)
    return text.replace("\u200b", "")  # a break opportunity, not text


@pytest.mark.workflow
def test_the_article_holds_the_counts_and_every_claim_s_value(tiny_run):
    """`make report` writes it; its text states the claims table's counts and each
    claim's id and value, and its metadata is ReScience C's template's (the title's mark
    by the claims, the authors CITATION.cff's) with the lock's software."""
    pdf = tiny_run / "report" / "article.pdf"
    text = " ".join(_text(pdf).split())
    table = pd.read_csv(tiny_run / "results" / "claims.csv")
    status = table["status"].value_counts()
    reproduce = f"{status.get('pass', 0)} claims reproduce"
    assert f"{len(table)} quantitative and qualitative claims" in text and reproduce in text
    assert f"{status.get('known_deviation', 0)} deviate" in text
    assert "A rule for a new scene: the cheapest method" in text  # the study's rule table
    for claim in table.to_dict("records"):
        assert claim["id"].replace("_", "") in text.replace("_", "").replace(" ", ""), claim["id"]
        assert _number(float(claim["reproduced_value"])) in text, claim["id"]
    meta = yaml.safe_load((tiny_run / "report" / "metadata.yaml").read_text())
    assert departures(meta) == []  # ReScience C's template, key by key
    # the title's mark by the claims table's held-out claims, the authors CITATION.cff's
    held = table[table["fit_set"].fillna("") == ""]
    mark = "[Re]" if (held["status"] == "pass").sum() > len(held) / 2 else "[\u00acRe]"
    assert (
        meta["title"]
        == f"{mark} Double pendulum model for tennis stroke including a collision process"
    )
    assert f"The title carries {mark}" in text
    assert meta["authors"] == authors(read_citation(ROOT / "CITATION.cff"))[0]
    assert {"url": "https://arxiv.org/abs/1505.01916"} in meta["replication"]
    assert any(s.startswith("typst==") for s in meta["software"])


@pytest.mark.workflow
def test_a_changed_result_changes_the_article_and_its_figures_are_the_pngs(tiny_run, tmp_path):
    figures, results = _inputs(tiny_run)
    csv = tmp_path / "claims.csv"
    table = pd.read_csv(tiny_run / "results" / "claims.csv")
    table.loc[0, "reproduced_value"] = 12345.678
    # the status the value gives: the article refuses a table edited by hand
    deviation = table.loc[0, "expectation"] == "known_deviation"
    table.loc[0, "status"] = "known_deviation" if deviation else "fail"
    table.to_csv(csv, index=False)
    out = tmp_path / "article.pdf"
    build_article(str(csv), STATEMENTS, figures, results, str(out), str(tmp_path / "m.yaml"))
    assert "1.235e+04" in _text(out)
    images = [i for page in pypdf.PdfReader(out).pages for i in page.images]
    shown = [f for f in figures if FIGURES[f.split("/")[-1][:-4]].of_paper]
    assert len(images) == len(shown)


def test_a_missing_input_is_one_line(tmp_path):
    missing = tmp_path / "results" / "claims.csv"
    with pytest.raises(ReportInputError) as info:
        build_article(str(missing), STATEMENTS, [], [], str(tmp_path / "a.pdf"), "m.yaml")
    assert str(info.value) == f"the article needs {missing}, which does not exist"
    assert not (tmp_path / "a.pdf").exists()
    shutil.rmtree(tmp_path / "results", ignore_errors=True)


@pytest.mark.workflow
def test_a_scenario_s_article_is_an_exploration_never_a_replication(tiny_scenario, tmp_path):
    """Its changes, the figures it changes against the paper's, and every claim under
    both configurations with the signed change; no verdict, no replication's counts."""
    from tennis_stroke.replication.scenario_article import build_scenario_article

    run, _ = tiny_scenario
    folder = run / "results" / "scenarios" / "strong"
    comparisons = sorted(str(p) for p in (folder / "compare").glob("*.png"))
    out = tmp_path / "article.pdf"
    scenario = {"name": "strong", "changes": [{"text": "torque_delay.base_stroke.C2 = 8 N m"}]}
    build_scenario_article(
        scenario,
        comparisons,
        str(folder / "claims.csv"),
        STATEMENTS,
        str(out),
        str(run / "results" / "claims.csv"),
    )
    text = " ".join(_text(out).split())
    assert "An exploration beside the paper, not a replication" in text
    assert "torque_delay.base_stroke.C2 = 8 N m" in text
    assert "claims reproduce" not in text and "verdict" not in text
    table = pd.read_csv(folder / "claims.csv")
    for claim in table.to_dict("records"):
        assert claim["id"].replace("_", "") in text.replace("_", "").replace(" ", ""), claim["id"]
    images = [i for page in pypdf.PdfReader(out).pages for i in page.images]
    assert len(images) == len(comparisons) > 0
    # each comparison on a landscape page (its three panels were about 2 pt type at
    # portrait width), and every value with its unit
    shown = [page for page in pypdf.PdfReader(out).pages if page.images]
    assert all(float(p.mediabox.width) > float(p.mediabox.height) for p in shown)
    assert "km/h" in text and "((" not in text
    assert "); ours under the scenario" in text  # typst swallowed a ';' after a value
