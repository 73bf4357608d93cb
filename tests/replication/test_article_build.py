"""The article built from small made-up inputs (no workflow run): its sections and
equations, one numbering of figures, units on every value, the provenance of every result
file (a mix stated as one), the claims table `tennis-stroke claims` accepts and no other,
a damaged figure in one line with the previous PDF kept, ReScience C's metadata fields,
and a scenario's long name kept on the page."""

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pypdf
import pytest
import xarray as xr
import yaml
from conftest import ROOT, work_precision_table
from PIL import Image

from tennis_stroke.inference.claims import load_claims
from tennis_stroke.replication.article import build_article
from tennis_stroke.replication.claims import COLUMNS, ClaimsTableError, check, measure_text
from tennis_stroke.replication.formats import ReportInputError
from tennis_stroke.replication.registry import FIGURES

STATEMENTS = str(ROOT / "config" / "claims.yaml")
DECLARED = load_claims(STATEMENTS)
PAPER_FIGURES = sorted(name for name, f in FIGURES.items() if f.of_paper)
COMMIT_A, COMMIT_B = "a" * 40, "b" * 40
#: The side margins of the articles' pages (2.2 cm), in points.
MARGIN = 2.2 / 2.54 * 72
#: A claim the paper's config expects to deviate: the made-up table's deviation.
DEVIATING = next(c for c in DECLARED if c["expectation"] == "known_deviation")


def _claims_table(path, value_of=None):
    """A claims table the claims job could have written: every claim at the paper's
    value (``pass``) but :data:`DEVIATING`, ten tolerances off (``known_deviation``,
    irreducible); ``value_of``: other values by claim id, with the status they claim."""
    rows = []
    for c in DECLARED:
        value, status, evidence = float(c["paper_value"]), "pass", ""
        if c["id"] == DEVIATING["id"]:
            value += 10 * float(c["tolerance"]) + 1
            status, evidence = "known_deviation", "irreducible"
        if value_of and c["id"] in value_of:
            value = value_of[c["id"]]
        rows.append(
            {
                **{k: c.get(k, "") for k in ("id", "source", "quantity", "unit")},
                **{k: c[k] for k in ("paper_value", "tolerance", "expectation")},
                "reproduced_value": value,
                "status": status,
                "reason": c.get("reason", ""),
                "measure": measure_text(c["measure"]),
                "fit_set": "",
                "map_value": value,
                "map_difference": 0.0,
                "map_cause": "agrees",
                "robustness": "robust" if status == "pass" else "not_reproduced",
                "pass_share": 1.0 if status == "pass" else 0.0,
                "deciding": "",
                "evidence": evidence,
            }
        )
    pd.DataFrame(
        rows, columns=[*COLUMNS, "robustness", "pass_share", "deciding", "evidence"]
    ).to_csv(path, index=False, na_rep="nan")  # nan written out, as the table
    return str(path)


def _png(path, shade=0):
    """A small PNG, its colour by ``shade`` (equal images are stored once in a PDF)."""
    Image.new("RGB", (64, 48), (200, 220, shade)).save(path)
    return str(path)


def _result(path, commit):
    ds = xr.Dataset({"x": ("i", np.arange(3.0))})
    ds.attrs.update(
        git_commit=commit,
        environment_lock_sha256_16="0123456789abcdef",
        environment_is_lock="yes",
        python_version="3.11.2",
        tennis_stroke_version="0.1.0",
    )
    ds.to_netcdf(path, engine="netcdf4")
    return str(path)


def _work_precision(path):
    """A made-up work-precision file: on ``contact`` scipy RK45 at 5e-8 is the cheapest
    setting meeting both requirements (DOP853 at 1e-4 misses v_out, RK45 at 1e-4 the
    event times); on ``swing`` no setting meets them."""
    ds = work_precision_table(
        v_out=[[[1e-3, 1e-5], [1e-5, 2e-5]], [[1e-2, 1e-2], [1e-2, 1e-2]]],
        events=[[[1e-7, 1e-9], [1e-5, 1e-8]]] * 2,
        evals=[[[160.0, 283.0], [108.0, 150.0]]] * 2,
        failed=np.zeros((2, 2, 2)),
        scenes=("contact", "swing"),
    )
    ds.to_netcdf(path, engine="netcdf4")
    return str(path)


@pytest.fixture
def inputs(tmp_path):
    """Claims table, the paper's figures and two result files of one commit."""
    folder = tmp_path / "results"
    (folder / "figures").mkdir(parents=True)
    return {
        "claims_csv": _claims_table(folder / "claims.csv"),
        "claims_yaml": STATEMENTS,
        "figures": [
            _png(folder / "figures" / f"{n}.png", 10 * i) for i, n in enumerate(PAPER_FIGURES)
        ],
        "results": [_result(folder / f"r{i}.nc", COMMIT_A) for i in range(2)],
        "work_precision": _work_precision(folder / "work_precision.nc"),
        "output_pdf": str(tmp_path / "report" / "article.pdf"),
        "output_metadata": str(tmp_path / "report" / "metadata.yaml"),
    }


def _text(pdf) -> str:
    """The PDF's text, words joined by single spaces (break opportunities dropped)."""
    pages = pypdf.PdfReader(pdf).pages
    return " ".join(" ".join(p.extract_text() for p in pages).replace("\u200b", "").split())


def test_the_article_has_equations_a_discussion_and_a_conclusion(inputs):
    build_article(**inputs)
    text = _text(inputs["output_pdf"])
    for heading in ("Methods", "Results", "Discussion", "Conclusion", "Reproducibility"):
        assert re.search(rf"\d+ {heading}", text), heading
    assert "The equations as the code computes them" in text
    assert "(1)" in text and "(12)" in text  # the rendered equations, numbered
    assert "What does not reproduce, and why" in text and "Irreducible (1)" in text
    assert DEVIATING["id"] in text.replace(" ", "")
    held = sum(1 for c in DECLARED)  # no fit set in the made-up table
    assert f"reproduces {held - 1} of its {held} held-out claims" in text


def test_the_article_shows_the_rule_table_of_the_integrator_s_settings(inputs):
    """The report's rule table (its caption and each scene's cheapest setting, cost and
    errors, the default's cost) from the work-precision file, not typed into the text."""
    build_article(**inputs)
    text = _text(inputs["output_pdf"]).replace("\u2019", "'")
    assert "The integrator's settings" in text
    assert "A rule for a new scene: the cheapest method and tolerance" in text
    assert "whose worst of 3 strokes per scene meets 0.0001 km/h in v_out" in text
    cells = text.replace(" ", "")
    assert "contactscipy.RK45@5e-08" + "1502e-051e-08meetsit,283" in cells
    assert "swingnone---missesit,283" in cells


def test_figures_carry_the_paper_s_numbers_only(inputs):
    """One numbering: each caption starts with the paper's figure number, never a second
    count of Typst's ("Figure 12: Fig. 13")."""
    build_article(**inputs)
    text = _text(inputs["output_pdf"])
    assert not re.search(r"Figure \d+", text)
    captions = re.findall(r"Fig\. (\d+)\b(?:(?!Fig\. ).)*?\(this replication\)", text)
    assert sorted(map(int, captions)) == sorted(int(n[3:5]) for n in PAPER_FIGURES)
    images = [i for page in pypdf.PdfReader(inputs["output_pdf"]).pages for i in page.images]
    assert len(images) == len(PAPER_FIGURES)


def test_every_value_carries_its_unit_and_no_text_is_below_8_pt(inputs):
    build_article(**inputs)
    reader = pypdf.PdfReader(inputs["output_pdf"])
    sizes = []

    def visit(text, cm, tm, font, size):
        math = font is not None and "Math" in str(font.get("/BaseFont", ""))
        if text.strip() and not math:  # an equation's indices are smaller by design
            sizes.append(abs(size * tm[3] * cm[3]) if tm[3] and cm[3] else abs(size))

    for page in reader.pages:
        page.extract_text(visitor_text=visit)
    assert sizes and min(sizes) >= 8 - 1e-6, min(sizes)
    text = _text(inputs["output_pdf"])
    units = {c["unit"] for c in DECLARED} - {"1", "degree"}
    for unit in units:  # the unit after a value with a space, in each value column
        assert not re.search(rf"\d{re.escape(unit)}(?![\w/])", text), unit
    seconds = next(c for c in DECLARED if c["unit"] == "s")
    paper = f"{float(seconds['paper_value']):.6g} s"
    assert text.count(paper) >= 2, paper  # the paper's value and ours (equal here)
    assert f"±{float(seconds['tolerance']):.4g} s" in text


def _citation(path):
    """A citation file naming the code's repository (its ``repository-code``)."""
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    cff["repository-code"] = "https://github.com/example/tennis-stroke"
    path.write_text(yaml.safe_dump(cff))
    return str(path)


def _entries(meta, key):
    """A key of the metadata as one map (the template's list of one-key maps)."""
    return {k: v for entry in meta[key] for k, v in entry.items()}


def test_the_metadata_holds_rescience_c_s_fields(inputs, tmp_path):
    build_article(
        **inputs,
        lock=ROOT / "requirements.lock",
        pyproject=ROOT / "pyproject.toml",
        citation=_citation(tmp_path / "CITATION.cff"),
    )
    meta = yaml.safe_load(Path(inputs["output_metadata"]).read_text())
    replication, code = _entries(meta, "replication"), _entries(meta, "code")
    assert re.fullmatch(r"[A-Za-z][\w:-]*", replication["bib"])  # a key, no DOI
    assert replication["doi"] == "10.48550/arXiv.1505.01916"
    urls = [code["url"], _entries(meta, "data")["url"], replication["url"]]
    assert all(u is None or re.match(r"https://\S+$", u) for u in urls), urls
    assert code["url"] == f"https://github.com/example/tennis-stroke/tree/{COMMIT_A}"
    names = {s.split("==")[0].lower() for s in meta["software"]}
    assert {"numpy", "scipy", "numba", "xarray", "snakemake", "typst"} <= names
    assert not names & {"black", "ruff", "selenium", "trio", "pytest", "sympy", "uv"}
    assert all(re.fullmatch(r"[\w.\-]+==[\w.\-+]+", s) for s in meta["software"])
    # one author, from CITATION.cff, in the article's byline as in the metadata
    (author,) = meta["authors"]
    assert author["name"] == "The tennis-stroke developers" and author["affiliations"] == "1,*"
    text = _text(inputs["output_pdf"]).replace("\u2019", "'")
    assert "Authors: to fill" not in text and "Contact: The tennis-stroke developers" in text
    # the mark, and why: every held-out claim of the made-up table but one reproduces
    held = len(DECLARED)
    assert meta["title"].startswith("[Re] Double pendulum model")
    assert (
        f"The title carries [Re], ReScience C's mark of a successful replication: {held - 1} "
        f"of the {held} held-out claims ({100 * (held - 1) / held:.0f} %) reproduce" in text
    )
    assert " ".join(meta["abstract"].split()) in text  # the article's abstract


def test_a_mix_of_commits_is_stated_as_a_mix(inputs, tmp_path, capsys):
    """One result file of another commit: the article names both, with the files of
    each, and says the files do not share one; the metadata claims no commit."""
    inputs["results"].append(_result(tmp_path / "results" / "odd.nc", COMMIT_B))
    build_article(**inputs, citation=_citation(tmp_path / "CITATION.cff"))
    text = _text(inputs["output_pdf"])
    assert f"commit: a mix of 2: {COMMIT_A} (2 files); {COMMIT_B} (1 file: odd.nc)" in text
    assert "The result files do not share one commit" in text
    assert "lock (SHA-256 of requirements.lock, first 16 digits): 0123456789abcdef (all 3" in text
    meta = yaml.safe_load(Path(inputs["output_metadata"]).read_text())
    assert _entries(meta, "code")["url"] == "https://github.com/example/tennis-stroke"
    assert "more than one commit" in capsys.readouterr().err


@pytest.mark.parametrize("value", [float("nan"), float("inf"), 1e308])
def test_the_article_refuses_the_table_claims_refuses(inputs, value):
    """A passing row holding nan, inf or 1e308: `tennis-stroke claims` refuses the table,
    and the article refuses it in the same words, keeping the previous PDF."""
    claim = next(c for c in DECLARED if c["id"] != DEVIATING["id"])
    _claims_table(inputs["claims_csv"], {claim["id"]: value})
    with pytest.raises(ClaimsTableError) as refused:
        check(inputs["claims_csv"], [c["id"] for c in DECLARED], DECLARED)
    out, previous = Path(inputs["output_pdf"]), b"%PDF- the previous article"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(previous)
    with pytest.raises(ReportInputError) as info:
        build_article(**inputs)
    assert str(info.value) == str(refused.value)
    assert out.read_bytes() == previous


def test_a_damaged_figure_is_named_in_one_line_and_the_previous_pdf_kept(inputs):
    build_article(**inputs)
    previous = Path(inputs["output_pdf"]).read_bytes()
    damaged = next(p for p in inputs["figures"] if p.endswith("fig02_angle_map.png"))
    Path(damaged).write_text("not a PNG")
    with pytest.raises(ReportInputError) as info:
        build_article(**inputs)
    message = str(info.value)
    assert "\n" not in message and damaged in message, message
    assert Path(inputs["output_pdf"]).read_bytes() == previous


def _text_positions(pdf):
    """Each text chunk of each page with its horizontal start (pt) and the page's width."""
    out = []
    for page in pypdf.PdfReader(pdf).pages:
        width = float(page.mediabox.width)

        def visit(text, cm, tm, font, size, width=width):
            if text.strip():
                out.append((text, cm[0] * tm[4] + cm[2] * tm[5] + cm[4], width))

        page.extract_text(visitor_text=visit)
    return out


def test_a_scenario_s_longest_name_stays_on_the_page(tmp_path):
    """A valid 64-character scenario name (no space to break at) in the title of its
    article: every line of it starts inside the margins (it ran past both, centred),
    and the whole name is there."""
    from tennis_stroke.replication.scenario_article import build_scenario_article

    name = "w" + "ide_wrist_torque_and_a_longer_arm" * 2
    name = name[:64]
    assert len(name) == 64
    csv = _claims_table(tmp_path / "claims.csv")
    figure = _png(tmp_path / "fig09_v_tau.png")
    out = tmp_path / "article.pdf"
    scenario = {"name": name, "changes": [{"text": "torque_delay.base_stroke.C2 = 8 N m"}]}
    build_scenario_article(scenario, [figure], csv, STATEMENTS, str(out), csv)
    chunks = _text_positions(out)
    assert chunks
    for text, x, width in chunks:
        assert MARGIN - 0.5 <= x < width - MARGIN, (text, x)
    assert name in _text(out).replace(" ", "")
