"""The report page: escaping of every text from a file, the ledger rendered from markdown,
the page in a real browser (Debian's headless Chromium), and Snakemake's own report."""

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pandas as pd
import pytest
import yaml
from claim_tables import edited_shape, numbers, text_of
from conftest import ROOT, SCENARIO_PAGE, merged, record_configuration, run_snakemake

from tennis_stroke.experiments.specs import INFERENCE_RESULTS, PAPER_RESULTS, STUDY_RESULTS
from tennis_stroke.io.netcdf import load_result
from tennis_stroke.replication.analyses import ladder_summary, studies_section
from tennis_stroke.replication.registry import FIGURES
from tennis_stroke.replication.report import _paper_place, build_report, markdown_html

CLAIM_IDS = [c["id"] for c in yaml.safe_load((ROOT / "config/claims.yaml").read_text())["claims"]]
#: Chromium as Debian installs it (.ci/run); the browser tests skip without it.
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
HOSTILE = '<script>alert("claim")</script> & <b>co</b>'


def _build(work: Path, output: Path, claims_csv: Path, statements: Path) -> str:
    """The report of a workflow run in ``work``, as the report rule builds it (a claims
    table outside the run gets the run's configuration record beside it)."""
    record = claims_csv.with_name("configuration.yaml")
    if not record.exists():
        shutil.copy(work / "results" / "configuration.yaml", record)
    build_report(
        figures=[str(work / f"results/figures/{name}.png") for name in sorted(FIGURES)],
        claims_csv=str(claims_csv),
        inference={k: str(work / v) for k, v in INFERENCE_RESULTS.items()},
        results=[str(work / v) for v in PAPER_RESULTS.values()],
        config=merged(
            yaml.safe_load((ROOT / "config/config.yaml").read_text()),
            yaml.safe_load((work / "config/config.yaml").read_text()),
        ),
        benchmarks_dir=str(work / "logs/benchmarks"),
        output=str(output),
        assumptions_md=str(ROOT / "docs/assumptions.md"),
        studies={k: str(work / v) for k, v in STUDY_RESULTS.items()},
        statements_yaml=str(statements),
    )
    return output.read_text()


def test_the_ladder_sentence_follows_the_numbers():
    """The report said 'more than the 1 km/h tolerance' of a 0.16 km/h error: the
    comparison is now made from the file and the claims."""
    claims = pd.DataFrame({"unit": ["km/h", "km/h", "s"], "tolerance": ["1.0", "2.0", "0.002"]})
    assert ladder_summary(0.16, claims) == {"error": "0.16", "tolerance": "1", "above": False}
    assert ladder_summary(1.58, claims)["above"] is True
    assert ladder_summary(None, claims)["error"] == "n/a"


def test_markdown_renders_tables_and_escapes_raw_html():
    html = str(markdown_html("# T\n\n| a | b |\n|---|---|\n| 1 | <i>x</i> & y |\n<!-- gone -->"))
    assert "<table>" in html and "<td>1</td>" in html
    assert "&lt;i&gt;x&lt;/i&gt; &amp; y" in html and "<i>" not in html
    assert "gone" not in html


@pytest.mark.parametrize(
    ("source", "claim_id", "place"),
    [
        ("Sec. V, Fig. 9", "fig9_v_H", ("V", "fig09")),
        ("Sec. V, Figs. 11-12", "fig12_x", ("V", "fig11")),
        ("Sec. III", "fig4_theta_c_a", ("III", "fig04")),
        ("Sec. III", "sec3_statement", ("III", "")),
        ("Table I", "table1_v_180", ("VI", "Table I")),
        ("Sec. IX", "x", ("IX", "")),
        ("abstract", "x", (None, "")),
    ],
)
def test_each_claim_is_placed_by_its_source(source, claim_id, place):
    sections = {"V": {}, "VI": {"tables": ["Table I"]}}
    assert _paper_place(source, claim_id, sections) == place


#: The page's sections of our own by the registry's section (the template's ids; a
#: section of the paper, ``III``, is ``sec-iii``).
OUR_SECTION_IDS = {"inference": "inference", "ladder": "model-ladder", "study": "studies"}


def test_each_figure_is_in_the_section_the_registry_declares(tiny_run):
    html = (tiny_run / "report/index.html").read_text()
    shown = {
        alt: section
        for section, body in re.findall(r'<section id="([^"]+)"[^>]*>(.*?)</section>', html, re.S)
        for alt in re.findall(r'<img alt="([^"]+)"', body)
    }
    assert shown == {
        name: OUR_SECTION_IDS.get(f.section, f"sec-{f.section.lower()}")
        for name, f in FIGURES.items()
    }


def test_the_studies_are_read_by_their_keys(tiny_run):
    """The model ladder's error from the ladder study's file, a table of each other study
    the page tabulates, in the page's order; nothing without their files."""
    files = {k: str(tiny_run / v) for k, v in STUDY_RESULTS.items()}
    error, tables = studies_section(files)
    assert error == float(load_result(files["ladder"]).attrs["max_error_impact_kmh"])
    assert [t["title"].split(":")[0] for t in tables] == [
        "A rule for a new scene",
        "The optimum of Figs. 5-6",
        "Stability",
    ]
    assert all("<table" in t["html"] for t in tables)
    assert studies_section({}) == (None, [])
    assert [t["title"][:9] for t in studies_section({"stability": files["stability"]})[1]] == [
        "Stability"
    ]


def test_text_from_files_is_escaped(tiny_run, tmp_path):
    """A '<script>' or '&' in a claim's text, its reason or the paper's statement is shown
    as text, never run as HTML."""
    claims = pd.read_csv(tiny_run / "results/claims.csv", keep_default_na=False, dtype=str)
    claims.loc[0, "quantity"] = HOSTILE
    statements = yaml.safe_load((ROOT / "config/claims.yaml").read_text())
    statements["statements"]["fig04"] = HOSTILE
    statements["claims"][0]["quantity"] = HOSTILE  # the table follows its claims file
    # claim 1 declared a known deviation with a hostile reason, and deviating (a table
    # that does not follow from the declared claims is refused)
    declared = statements["claims"][1]
    declared.update(expectation="known_deviation", reason=HOSTILE)
    far = float(declared["paper_value"]) + 100.0 * float(declared["tolerance"])
    claims.loc[1, ["reason", "expectation", "status"]] = [HOSTILE, *["known_deviation"] * 2]
    claims.loc[1, "reproduced_value"] = str(far)
    claims.to_csv(tmp_path / "claims.csv", index=False)
    (tmp_path / "claims.yaml").write_text(yaml.safe_dump(statements))
    html = _build(
        tiny_run, tmp_path / "index.html", tmp_path / "claims.csv", tmp_path / "claims.yaml"
    )
    # the page's own scripts (BokehJS, the views, the figure overlay) run; the text is text
    assert '<script>alert("claim")' not in html and "<b>co</b>" not in html
    escaped = "&lt;script&gt;alert(&#34;claim&#34;)&lt;/script&gt; &amp; &lt;b&gt;co&lt;/b&gt;"
    assert html.count(escaped) >= 3, html.count(escaped)


def test_the_report_refuses_inputs_it_was_not_given_by_the_workflow(tiny_run, tmp_path):
    """A claims table edited by hand (a deviation marked pass), a figure that does not
    decode and an empty assumption ledger are each one line, and no page is written."""
    from tennis_stroke.replication.report import ReportInputError

    claims = pd.read_csv(tiny_run / "results/claims.csv", keep_default_na=False, dtype=str)
    declared = yaml.safe_load((ROOT / "config/claims.yaml").read_text())["claims"]
    i = next(
        n for n, c in enumerate(declared) if c["expectation"] == "reproduce" and c["tolerance"]
    )
    claims.loc[i, "reproduced_value"] = str(
        declared[i]["paper_value"] + 100 * declared[i]["tolerance"]
    )
    claims.loc[i, "status"] = "pass"
    claims.to_csv(tmp_path / "claims.csv", index=False)
    page = tmp_path / "index.html"
    with pytest.raises(ReportInputError, match="gives 'fail' \\(edited by hand\\?\\)"):
        _build(tiny_run, page, tmp_path / "claims.csv", ROOT / "config/claims.yaml")
    assert not page.exists()
    work = tmp_path / "work"
    shutil.copytree(tiny_run, work, symlinks=True)
    figure = work / "results/figures/fig09_v_tau.png"
    figure.write_bytes(figure.read_bytes()[:200])
    with pytest.raises(ReportInputError, match="fig09_v_tau.png does not decode"):
        _build(work, page, work / "results/claims.csv", ROOT / "config/claims.yaml")
    shutil.copy2(tiny_run / "results/figures/fig09_v_tau.png", figure)
    ledger = tmp_path / "assumptions.md"
    ledger.write_text("  \n")
    with pytest.raises(ReportInputError, match="assumption ledger .* is empty"):
        build_report(
            figures=[],
            claims_csv=str(work / "results/claims.csv"),
            inference={},
            results=[],
            config={},
            benchmarks_dir=str(work),
            output=str(page),
            assumptions_md=str(ledger),
            statements_yaml=str(ROOT / "config/claims.yaml"),
        )
    assert not page.exists()


#: Run in the page by the browser test: what a reader would see go wrong.
CHECKS = """<script>
window.addEventListener("load", () => {
  const cells = [...document.querySelectorAll("td, th")];
  const result = {
    images: [...document.images].map(i => [i.alt, i.complete && i.naturalWidth > 0]),
    text: document.body.innerText,
    overflowing: cells.filter(c => c.scrollWidth > c.clientWidth + 1)
                      .map(c => c.textContent.trim().slice(0, 60)),
    pageWidth: document.documentElement.scrollWidth,
    viewport: window.innerWidth,
  };
  const out = document.createElement("pre");
  out.id = "browser-check";
  out.textContent = JSON.stringify(result);
  document.body.appendChild(out);
});
</script></body>"""


def _chromium(page: Path, width: int, height: int, *options: str) -> str:
    """Run headless Chromium on ``page`` in a ``width`` x ``height`` window; its stdout."""
    done = subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            # the network off: every request would go to a dead proxy (a page must work
            # from file:// alone)
            "--proxy-server=127.0.0.1:9",
            "--proxy-bypass-list=<-loopback>",
            f"--window-size={width},{height}",
            *options,
            page.as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


def _in_browser(page: Path, width: int) -> dict:
    """The page's checks (:data:`CHECKS`) as Chromium computes them at ``width`` px."""
    checked = page.with_name(f"checked-{width}.html")
    # the page's last </body> (BokehJS inline holds the text "</body>" in its strings)
    head, _, tail = page.read_text().rpartition("</body>")
    checked.write_text(head + CHECKS + tail)
    dom = _chromium(checked, width, 1000, "--virtual-time-budget=10000", "--dump-dom")
    start = dom.index('<pre id="browser-check">') + len('<pre id="browser-check">')
    text = dom[start : dom.index("</pre>", start)]
    for entity, char in (("&lt;", "<"), ("&gt;", ">"), ("&quot;", '"'), ("&amp;", "&")):
        text = text.replace(entity, char)
    return json.loads(text)


@pytest.mark.browser
@pytest.mark.skipif(CHROMIUM is None, reason="no chromium on PATH (.ci/run installs it)")
# 500 px: the narrowest window headless Chromium opens (a narrower --window-size gives 500).
@pytest.mark.parametrize("width", [1280, 500])
def test_the_page_in_a_real_browser(tiny_run, tmp_path, width):
    """At a desktop and a phone width: every figure loads, every claim id is on the page,
    no text overflows its table cell, nothing makes the page wider than the window; and a
    screenshot for a person to look at."""
    page = tmp_path / "index.html"
    shutil.copy(tiny_run / "report/index.html", page)
    seen = _in_browser(page, width)
    assert sorted(alt for alt, _ in seen["images"]) == sorted(FIGURES)
    assert all(loaded for _, loaded in seen["images"]), seen["images"]
    missing = [c for c in CLAIM_IDS if c not in seen["text"]]
    assert not missing, missing
    assert not seen["overflowing"], seen["overflowing"]
    assert seen["pageWidth"] <= seen["viewport"], (seen["pageWidth"], seen["viewport"])
    shots = Path(os.environ.get("REPORT_SCREENSHOTS", tmp_path))
    shots.mkdir(parents=True, exist_ok=True)
    shot = shots / f"report-{width}px.png"
    _chromium(page, width, 2400, f"--screenshot={shot}")
    assert shot.stat().st_size > 0
    print(f"screenshot: {shot}")


@pytest.mark.browser
@pytest.mark.skipif(CHROMIUM is None, reason="no chromium on PATH (.ci/run installs it)")
def test_a_scenario_page_in_a_real_browser(tiny_scenario, tmp_path):
    """A scenario's page, built by the workflow beside the tiny run, at a phone width:
    its figures load, every claim is on it, nothing overflows, the network off."""
    work, _ = tiny_scenario  # a copy: the shared tiny run keeps no scenario
    target = SCENARIO_PAGE
    page = tmp_path / "index.html"
    shutil.copy(work / target, page)
    seen = _in_browser(page, 500)
    assert len(seen["images"]) >= 6 and all(loaded for _, loaded in seen["images"])
    assert not [c for c in CLAIM_IDS if c not in seen["text"]]
    assert "torque_delay.base_stroke.C2 = 8 N m (paper: 5 N m)" in seen["text"]
    # each claim's value moves, stays or cannot be compared: the parts make every claim
    said = re.search(
        r"Of the (\d+) claims' values, (\d+) move, (\d+) stay the same and (\d+) cannot",
        " ".join(seen["text"].split()),
    )
    assert said and int(said[1]) == len(CLAIM_IDS) == sum(int(said[k]) for k in (2, 3, 4))
    assert not seen["overflowing"], seen["overflowing"]
    assert seen["pageWidth"] <= seen["viewport"], (seen["pageWidth"], seen["viewport"])


def test_snakemake_builds_its_own_report(tiny_run, tmp_path):
    """`snakemake --report` (README): the caption files are found and every figure and the
    claims table are in it."""
    out = tmp_path / "snakemake-report.html"
    done = run_snakemake([], tiny_run, "--report", str(out))
    assert done.returncode == 0, done.stderr[-3000:]
    html = out.read_text(errors="replace")
    assert "claims.csv" in html
    for name in FIGURES:
        assert f"{name}.png" in html, name


def test_a_departing_configuration_opens_the_page(tiny_run, tmp_path):
    """A claims table computed under a configuration other than the paper's (its record
    says where) gives a page that says so first, with each departure."""
    shutil.copy(tiny_run / "results" / "claims.csv", tmp_path / "claims.csv")
    departure = {"key": "elbow_force.F0", "value": 30.0, "paper_value": 20.0, "source": "Sec. VI"}
    record_configuration(tmp_path, departures=[departure])
    html = _build(
        tiny_run, tmp_path / "index.html", tmp_path / "claims.csv", ROOT / "config/claims.yaml"
    )
    head = html.split('id="scoreboard"')[0]
    assert (
        "departs from the paper" in head
        and "elbow_force.F0 = 30 (the paper&#39;s 20: Sec. VI)" in head
    )
    paper = _build(
        tiny_run,
        tmp_path / "paper.html",
        tiny_run / "results/claims.csv",
        ROOT / "config/claims.yaml",
    )
    assert "departs from the paper" not in paper


def _cards(html: str) -> dict[str, str]:
    """The scoreboard's cards by their class, as text."""
    board = html.split('id="scoreboard"')[1].split("<nav")[0]
    return {
        k: text_of(v) for k, v in re.findall(r'<div class="card (\w+)">(.*?)</div>', board, re.S)
    }


@pytest.mark.parametrize("shape", ["as run", "edited"])
def test_every_count_line_of_the_page_adds_up(tiny_run, tmp_path, shape):
    """Issue 53: '7 deviate, each with its cause: 1 ill conditioned, 8 reading dependent,
    6 irreducible' (15), and '23 of 35 held-out claims reproduce' beside 7 deviating and
    8 failing (38).  On the page of the tiny run's claims and of an edited
    configuration's (claims held out and used for fit pushed outside their tolerance),
    every count line sums to the set it counts, read from the table."""
    table = pd.read_csv(tiny_run / "results/claims.csv", keep_default_na=False, dtype=str)
    if shape == "edited":
        table = edited_shape(table)
    table.to_csv(tmp_path / "claims.csv", index=False)
    html = _build(
        tiny_run, tmp_path / "index.html", tmp_path / "claims.csv", ROOT / "config/claims.yaml"
    )
    held = int((table["fit_set"] == "").sum())
    outside = table["status"].isin(["known_deviation", "fail"])
    cards = _cards(html)
    first = {k: int(re.match(r"\d+", v)[0]) for k, v in cards.items()}
    assert int(re.search(r"of (\d+) held-out", cards["pass"])[1]) == held
    assert first["pass"] + first["known_deviation"] + first["fail"] == held, cards
    for card in ("known_deviation", "fail"):
        causes = cards[card].partition(": ")[2]
        assert not causes or sum(numbers(causes)) == first[card], cards[card]
    fit = re.match(
        r"(\d+) used for fit: (\d+) within tolerance(?:, (\d+) outside it(?:: (.*?))?)? \(fits\)",
        cards["used_for_fit"],
    )
    assert fit, cards["used_for_fit"]
    assert int(fit[1]) == len(table) - held == int(fit[2]) + int(fit[3] or 0)
    assert not fit[4] or sum(numbers(fit[4])) == int(fit[3])
    # below the board: every claim outside its tolerance, by status, then by cause
    section = html.split('id="deviations"')[1].split("</section>")[0]
    groups = [int(n) for n in re.findall(r'<h3 id="cause-[^"]+">[^<]*\((\d+)\)</h3>', section)]
    assert sum(groups) == int(outside.sum())
    intro = re.search(
        r"(\d+) of the (\d+) claims lie outside their tolerance: (\d+) held-out deviate as "
        r"declared, (\d+) held-out fail unexpectedly and (\d+) used for fit",
        text_of(section),
    )
    if outside.any():
        assert intro, text_of(section)[:300]
        assert int(intro[1]) == int(outside.sum()) == sum(int(intro[k]) for k in (3, 4, 5))
        assert int(intro[2]) == len(table)
        assert (int(intro[3]), int(intro[4])) == (first["known_deviation"], first["fail"])
    robust = re.search(r"the (\d+) held-out claims are (.*?)\.", text_of(html.split("<nav")[0]))
    if robust:
        assert int(robust[1]) == held == sum(numbers(robust[2])), robust[0]


def test_the_ledger_marks_a_fitted_default_as_the_fits_chose_it(tmp_path):
    """One vocabulary: a reading's default is "fitted" where a fit set chose it (the fits
    file's ``default_*``), as `tennis-stroke params` and the explorer say."""
    import xarray as xr

    from tennis_stroke.io.netcdf import write_netcdf
    from tennis_stroke.replication.report import _fitted

    path = tmp_path / "model_fits.nc"
    attrs = {
        "default_inertia": "uniform_rod",
        "default_k_contact": 7800.0,
        "default_fig4_theta": "phi0",
    }
    write_netcdf(xr.Dataset(attrs=attrs), path)
    assert _fitted({"model_fits": str(path), "model_loo": "unused"}) == {"inertia", "k_contact"}


def test_a_count_a_file_does_not_record_is_a_dash_never_na(tmp_path):
    """The failed strokes table showed <NA> in every status column of Figs. 5-6's row (it
    counts failed strokes per point only)."""
    import numpy as np
    import xarray as xr

    from tennis_stroke.io.netcdf import write_netcdf
    from tennis_stroke.replication.formats import _table
    from tennis_stroke.replication.report import _failures

    points = xr.Dataset(
        {
            "failed_strokes": ("M2", np.array([0, 2])),
            "evaluated_strokes": ("M2", np.array([10, 10])),
        }
    )
    strokes = xr.Dataset({"status": ("stroke", np.array([0, 1, 0]))})
    write_netcdf(points, tmp_path / "ml.nc")
    write_netcdf(strokes, tmp_path / "map.nc")
    frame = _failures([str(tmp_path / "ml.nc"), str(tmp_path / "map.nc")])
    assert frame.loc[0, "total"] == 20 and frame.loc[0, "failed"] == 2
    assert frame.loc[0, "no_phi_zero"] == "-" and frame.loc[1, "failed"] == 1
    html = str(_table(frame, index=False))
    assert "NA" not in html and "NaN" not in html
