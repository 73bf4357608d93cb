"""The README and the docs: the numbers they quote from a run are generated from its
result files (tools/readme_results.py; ``make report`` fails when they are stale), and
the README's shell commands run as written, from a fresh shell."""

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from conftest import record_configuration

ROOT = Path(__file__).resolve().parents[1]
TOOL = ROOT / "tools" / "readme_results.py"


def _claims(path: Path, status="pass") -> Path:
    rows = [
        {
            "id": "a",
            "paper_value": 1.0,
            "reproduced_value": 1.1,
            "unit": "km/h",
            "status": status,
            "robustness": "robust",
            "evidence": "",
            "fit_set": "",  # held out, as every claim in no fit set
        },
        {
            "id": "b",
            "paper_value": 76.0,
            "reproduced_value": 232.0,
            "unit": "degree",
            "status": "known_deviation",
            "robustness": "not_reproduced",
            "evidence": "irreducible",
            "fit_set": "",
        },
    ]
    pd.DataFrame(rows).to_csv(path, index=False)
    record_configuration(path.parent)
    return path


def _run(*args):
    return subprocess.run(
        [sys.executable, str(TOOL), *map(str, args)], capture_output=True, text=True, timeout=60
    )


@pytest.mark.process
def test_the_block_is_written_and_then_checks_clean(tmp_path):
    claims = _claims(tmp_path / "claims.csv")
    readme = tmp_path / "README.md"
    readme.write_text("# x\n<!-- results:begin -->\nold\n<!-- results:end -->\nrest\n")
    assert _run("--claims", claims, "--readme", readme, "--check").returncode == 1
    assert _run("--claims", claims, "--readme", readme).returncode == 0
    text = readme.read_text()
    assert "| reproduces | 1 | 1 | 0 | 0 |" in text and "| deviates | 1 | 0 | 0 | 1 |" in text
    assert "| `b` | 76 | 232 | degree | irreducible |" in text
    assert text.startswith("# x\n") and text.endswith("<!-- results:end -->\nrest\n")
    assert _run("--claims", claims, "--readme", readme, "--check").returncode == 0


def test_the_block_speaks_the_reports_words(tmp_path):
    """A row is a verdict under the default reading in the report's words (its
    scoreboard's), a column a robustness class across the readings, and the list of
    deviations says how many deviate and how many fail."""
    sys.path.insert(0, str(TOOL.parent))
    try:
        from readme_results import block
    finally:
        sys.path.remove(str(TOOL.parent))
    from tennis_stroke.replication.claims import STATUS_WORDS

    table = pd.read_csv(_claims(tmp_path / "claims.csv"), keep_default_na=False)
    extra = {**table.iloc[1].to_dict(), "id": "c", "status": "fail", "robustness": "robust"}
    table = pd.concat([table, pd.DataFrame([extra])], ignore_index=True)
    text = block(table)
    rows = [line.split(" | ")[0].lstrip("| ") for line in text.splitlines()[4:7]]
    assert rows == [STATUS_WORDS[s][1] for s in ("pass", "known_deviation", "fail")]
    header = text.splitlines()[2]
    assert header.startswith("| default reading | claims | robust")
    assert header.endswith("| not reproduced under any reading |")
    assert "The 1 claim that deviates and 1 claim that fails under the default reading" in text


@pytest.mark.process
def test_a_changed_result_makes_the_readme_stale(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("<!-- results:begin -->\n<!-- results:end -->\n")
    _run("--claims", _claims(tmp_path / "one.csv"), "--readme", readme)
    done = _run("--claims", _claims(tmp_path / "two.csv", "fail"), "--readme", readme, "--check")
    assert done.returncode == 1 and "stale" in done.stderr


@pytest.mark.process
def test_a_readme_without_markers_is_refused_in_one_line(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("no markers\n")
    done = _run("--claims", _claims(tmp_path / "c.csv"), "--readme", readme)
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1


def _held_out_run(folder: Path, fail: bool = False) -> Path:
    """A claims table with fit sets and the robustness file's sizes, in ``folder``."""
    import xarray as xr

    rows = [
        ("f", "used_for_fit", "used_for_fit", "model"),
        ("a", "pass", "robust", ""),
        ("b", "fail" if fail else "pass", "reading_dependent", ""),
        ("c", "known_deviation", "not_reproduced", ""),
    ]
    table = pd.DataFrame(rows, columns=["id", "status", "robustness", "fit_set"])
    table.to_csv(folder / "claims.csv", index=False)
    record_configuration(folder)
    (folder / "robustness").mkdir(exist_ok=True)
    xr.Dataset(coords={"reading": range(3), "variant": range(2)}).to_netcdf(
        folder / "robustness" / "claims.nc"
    )
    return folder / "claims.csv"


@pytest.mark.process
def test_a_docs_block_is_written_and_then_checks_clean(tmp_path):
    """A docs page's block (docs/inference.md's held-out claims) by the README's
    mechanism: stale before, written between its markers only, clean after; a changed
    result makes it stale again."""
    claims = _held_out_run(tmp_path)
    page = tmp_path / "inference.md"
    page.write_text("# x\n<!-- held-out:begin -->\n26 pass\n<!-- held-out:end -->\nrest\n")
    assert _run("--claims", claims, "--readme", page, "--check").returncode == 1
    assert _run("--claims", claims, "--readme", page).returncode == 0
    text = page.read_text()
    assert "4 claims: 1 chose the readings (`used_for_fit`), 3 are held out: 2 `pass`" in text
    assert "Across the 3 kept readings consistent with the paper, each under 2" in text
    assert "| pass | reading_dependent (1) | `b` |" in text and "26 pass" not in text
    assert text.startswith("# x\n") and text.endswith("<!-- held-out:end -->\nrest\n")
    assert _run("--claims", claims, "--readme", page, "--check").returncode == 0
    done = _run("--claims", _held_out_run(tmp_path, fail=True), "--readme", page, "--check")
    assert done.returncode == 1 and f"{page}'s results are stale" in done.stderr


@pytest.mark.process
def test_a_broken_block_is_refused_naming_its_page(tmp_path):
    page = tmp_path / "inference.md"
    page.write_text("<!-- held-out:begin -->\nno end\n")
    done = _run("--claims", _held_out_run(tmp_path), "--readme", page)
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1
    assert f"{page}: the block 'held-out' needs" in done.stderr


def _tool():
    """tools/readme_results.py as a module."""
    sys.path.insert(0, str(TOOL.parent))
    try:
        import readme_results
    finally:
        sys.path.remove(str(TOOL.parent))
    return readme_results


def test_every_page_with_a_generated_block_is_checked():
    """``make report``'s check covers every page that holds a generated block."""
    tool = _tool()
    begins = [tool.markers(name)[0] for name in tool.BLOCKS]
    pages = [ROOT / "README.md", *sorted(ROOT.glob("docs/*.md"))]
    marked = [p for p in pages if any(b in p.read_text() for b in begins)]
    assert [str(p.relative_to(ROOT)) for p in marked] == sorted(tool.PAGES)


def test_the_shipped_pages_are_generated_from_a_run(tiny_run, tmp_path):
    """Every block of the shipped pages is written from a run's result files (the tiny
    run's numbers differ from the committed ones, so each page is stale against them),
    and only the blocks change."""
    readme_results = _tool()
    pages = []
    for name in readme_results.PAGES:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text((ROOT / name).read_text())
        pages.append(tmp_path / name)
    claims = tiny_run / "results" / "claims.csv"
    done = _run("--claims", claims, "--readme", *pages, "--check")
    assert done.returncode == 1 and done.stderr.count("stale") == len(pages), done.stderr
    assert _run("--claims", claims, "--readme", *pages).returncode == 0
    assert _run("--claims", claims, "--readme", *pages, "--check").returncode == 0
    for page, name in zip(pages, readme_results.PAGES, strict=True):
        old, new = (ROOT / name).read_text(), page.read_text()
        for block in readme_results.BLOCKS:
            begin, end = readme_results.markers(block)
            if begin in old:
                old = old.split(begin)[0] + old.split(end)[1]
                new = new.split(begin)[0] + new.split(end)[1]
        assert old == new, name


#: A count that planning decides: so many jobs or rules (also across a line break), or
#: a table's column of them.
_PLANNED_COUNT = re.compile(r"\b\d[\d,]*\s+(?:jobs?|rules?)\b|\|\s*jobs\s*\|")


def test_no_page_gives_a_count_of_jobs_or_rules_by_hand():
    """Issue 66, case 26: docs/scenarios.md said a change of a paper input plans 30 jobs;
    it planned 34. A count of jobs or rules follows every rule added, so the pages say
    how to get it (``snakemake -n``, ``tennis-stroke config explain KEY``), not a number
    written by hand; the dated log (docs/changes.md) keeps the history, and a generated
    block is written from a run."""
    tool = _tool()
    found = []
    for page in [ROOT / "README.md", *sorted(ROOT.glob("docs/*.md"))]:
        if page.name == "changes.md":
            continue
        text = page.read_text()
        for name in tool.BLOCKS:
            begin, end = tool.markers(name)
            if begin in text:
                text = text.split(begin)[0] + text.split(end)[1]
        found += [f"{page.name}: {m.group(0)!r}" for m in _PLANNED_COUNT.finditer(text)]
    assert not found, found


@pytest.mark.parametrize("xdg", [False, True])
def test_the_readme_says_where_the_compile_cache_lives_and_how_to_remove_it(xdg, monkeypatch):
    """Issue 66, case 25: the compiled solver's cache (35 MB under ~/.cache/tennis-stroke)
    is outside the checkout, and the README did not name it: it names the folder the
    package picks (``HOME``'s ``.cache``, or ``XDG_CACHE_HOME``) and its removal."""
    from tennis_stroke._cache import configure_numba_cache

    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("HOME", "/home/someone")
    base, shown = Path("/home/someone/.cache"), "~/.cache"
    if xdg:
        base, shown = Path("/elsewhere/cache"), "$XDG_CACHE_HOME"
        monkeypatch.setenv("XDG_CACHE_HOME", str(base))
    else:
        monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    configure_numba_cache()
    top = Path(os.environ["NUMBA_CACHE_DIR"]).relative_to(base).parts[0]
    readme = " ".join((ROOT / "README.md").read_text().split())
    assert f"`{shown}/{top}/`" in readme
    assert f"rm -rf ~/.cache/{top}" in readme


def _what_if_section() -> str:
    text = (ROOT / "README.md").read_text()
    return text.split("## What if: scenarios beside the paper")[1].split("\n## ")[0]


def test_the_readme_scenario_is_the_declared_one_and_valid():
    """The README's worked scenario is config/scenarios.yaml's, word for word, and passes
    the checks a run makes before any job."""
    import yaml

    from tennis_stroke.io.config_files import load_yaml
    from tennis_stroke.pipeline.scenarios import load_scenarios, scenario_config

    block = _what_if_section().split("```yaml\n")[1].split("```")[0]
    assert block in (ROOT / "config" / "scenarios.yaml").read_text()
    (name, overrides), *_ = yaml.safe_load(block).items()
    assert load_scenarios(ROOT / "config" / "scenarios.yaml")[name] == overrides
    paper = load_yaml(ROOT / "config" / "config.yaml")
    schema = ROOT / "workflow" / "schemas" / "config.schema.yaml"
    assert scenario_config(paper, name, overrides, schema)["torque_delay"]["base_stroke"]["C2"] == 8


@pytest.mark.workflow
def _rules(stats: str) -> set[str]:
    """The rules a dry run's "Job stats" table plans."""
    return set(re.findall(r"^(\w+)\s+\d+\s*$", stats, re.M)) - {"total"}


@pytest.mark.workflow  # three dry runs of the workflow
def test_the_readme_scenario_commands_plan_what_they_say(tmp_path):
    """Each command of the README's scenario block, the `whatif` ones as dry runs in a
    fresh working folder with the project's config and workflow (the checkout's own
    results may hold them already): the page plans the scenario's Fig. 9 and its page,
    the figure its map and figure, the ad hoc one three jobs; each logs as `make report`
    does (no job's input list); `config explain` names the base stroke's files."""
    import re
    import shutil

    blocks = re.findall(r"```(\w*)\n(.*?)```", _what_if_section(), flags=re.S)
    lines = next(text for lang, text in blocks if lang == "sh").splitlines()
    commands = [line.split("#")[0].split() for line in lines if line.strip()]
    assert commands[-1][:2] == ["snakemake", "--profile"]  # the SLURM run, not a scenario's
    commands = commands[:-1]
    assert [c[:2] for c in commands] == [["tennis-stroke", "whatif"]] * 3 + [
        ["tennis-stroke", "config"]
    ]
    work = tmp_path / "work"
    shutil.copytree(ROOT / "config", work / "config")
    for linked in ("workflow", "src"):
        (work / linked).symlink_to(ROOT / linked)
    bin_ = ROOT / ".venv" / "bin"
    planned = []
    for command in commands[:3]:
        done = subprocess.run(
            [str(bin_ / command[0]), *command[1:], "-n"], cwd=work, capture_output=True, text=True
        )
        assert done.returncode == 0, done.stderr[-2000:]
        assert "    input: " not in done.stdout + done.stderr  # the quiet log
        planned.append(done.stdout.split("Job stats:")[1].split("Reasons:")[0])
    # the page asks for the map of Fig. 9 and the strokes of Figs. 10-12; one figure, its map
    assert {"simulate_chunk", "simulate", "scenario_report"} <= _rules(planned[0]), planned[0]
    assert "simulate_chunk" in _rules(planned[1]), planned[1]
    assert not {"simulate", "scenario_report"} & _rules(planned[1]), planned[1]
    assert "simulate_chunk" in _rules(planned[2]), planned[2]
    assert re.search(r"^total\s+3\s*$", planned[2], re.M), planned[2]
    explain = subprocess.run(
        [str(bin_ / commands[3][0]), *commands[3][1:]], cwd=ROOT, capture_output=True, text=True
    )
    assert explain.returncode == 0 and "results/torque_delay/fig9.nc" in explain.stdout


# --- the README's commands, run as written --------------------------------------------

#: README commands this test does not run, each with why; every other command of a
#: ``sh`` or ``console`` block runs below, so a command added to the README is run or
#: declared here.
NOT_RUN = {
    "make test": "the whole test suite, of which this test is a part",
    "make report": "the whole replication (minutes)",
    "source .venv/bin/activate": "how the others run: each one runs after it",
    "snakemake --profile profiles/slurm report": "needs a SLURM cluster (docs/slurm.md)",
    "tennis-stroke whatif strong_wrist": "a workflow run; planned by "
    "test_the_readme_scenario_commands_plan_what_they_say",
    "tennis-stroke whatif strong_wrist --figure fig9": "a workflow run; planned there too",
    "tennis-stroke whatif heavy --set M2=0.35 --figure fig2": "a workflow run; planned there too",
}
#: Top-level entries of the checkout the commands do not see: their results.
NOT_LINKED = {"results", "report", "logs", ".snakemake", ".git"}
_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")
_WALL_TIME = re.compile(r" in \d+(?:\.\d+)? s$")


def readme_commands() -> list[tuple[str, list[str]]]:
    """Every command of the README's ``sh`` and ``console`` blocks, in order, with the
    output lines the README shows after it (``$ command`` then output, in a console
    block); comments dropped."""
    text = (ROOT / "README.md").read_text()
    out: list[tuple[str, list[str]]] = []
    for lang, block in re.findall(r"^```(\w*)\n(.*?)^```", text, flags=re.S | re.M):
        for line in block.splitlines():
            if lang == "sh" and line.strip():
                out.append((line.split(" #")[0].strip(), []))
            elif lang == "console" and line.startswith("$ "):
                out.append((line[2:].strip(), []))
            elif lang == "console" and out:
                out[-1][1].append(line)
    return out


def _fresh_shell(command: str, cwd: Path) -> subprocess.CompletedProcess:
    """``command`` as a user types it in a new shell after ``source .venv/bin/activate``:
    a clean environment (the system's PATH, HOME and a UTF-8 locale; the compiled
    solver's cache location, if set, so the solver is not compiled anew)."""
    env = {"PATH": "/usr/local/bin:/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": str(Path.home())}
    env.update((k, os.environ[k]) for k in ("XDG_CACHE_HOME", "NUMBA_CACHE_DIR") if k in os.environ)
    return subprocess.run(
        ["bash", "-c", f"source .venv/bin/activate && {command}"],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )


def _same_line(shown: str, actual: str) -> bool:
    """An output line as the README shows it: the same words (spacing folded) and
    numbers within 1e-6 relative (solver changes move them by about 1e-5 km/h); a wall
    time (``in 0.41 s`` at the end) may differ."""
    shown, actual = (_WALL_TIME.sub(" in T s", " ".join(x.split())) for x in (shown, actual))
    if _NUMBER.sub("#", shown) != _NUMBER.sub("#", actual):
        return False
    pairs = zip(_NUMBER.findall(shown), _NUMBER.findall(actual), strict=True)
    return all(math.isclose(float(a), float(b), rel_tol=1e-6, abs_tol=1e-12) for a, b in pairs)


def _check_json(shown: list[str], actual: str) -> None:
    """Each ``"key": value`` the README shows in a section of a JSON output is that
    section's value (numbers within 1e-6 relative)."""
    payload = json.loads(actual)
    for line in shown:
        section = re.match(r'\s*"(\w+)": \{(.*)\}', line)
        if not section:
            continue
        for key, value in re.findall(r'"(\w+)": ("[^"]*"|[-+.\deE]+)', section.group(2)):
            got = payload[section.group(1)][key]
            expected = json.loads(value)
            if isinstance(expected, str):
                assert got == expected, (section.group(1), key, got)
            else:
                assert math.isclose(got, expected, rel_tol=1e-6, abs_tol=1e-12), (key, got)


def test_the_readme_declares_every_command_it_does_not_run():
    commands = [c for c, _ in readme_commands()]
    assert set(NOT_RUN) <= set(commands), set(NOT_RUN) - set(commands)
    assert any(c.startswith("tennis-stroke strike") for c in commands)
    assert any(c.startswith("tennis-stroke params") for c in commands)


@pytest.mark.process
def test_the_readme_commands_run_as_written_from_a_fresh_shell(tmp_path):
    """Each quick command of the README, word for word, in a new shell with a clean
    environment, in a folder that holds the checkout's files (links, so a written file
    such as the sweep's stays out of the checkout, and no earlier result is seen): exit
    status 0 and every output line the README shows (``...`` lines stand for others)."""
    clone = tmp_path / "clone"
    clone.mkdir()
    for entry in ROOT.iterdir():
        if entry.name not in NOT_LINKED:
            (clone / entry.name).symlink_to(entry)
    ran = []
    for command, shown in readme_commands():
        if command in NOT_RUN:
            continue
        done = _fresh_shell(command, clone)
        assert done.returncode == 0, (command, done.stderr[-2000:])
        assert "Traceback" not in done.stderr, (command, done.stderr[-2000:])
        expected = [line for line in shown if line.strip() and "..." not in line]
        if done.stdout.lstrip().startswith("{"):
            _check_json(shown, done.stdout)
        else:
            lines = done.stdout.splitlines()
            for line in expected:
                assert any(_same_line(line, got) for got in lines), (command, line, lines)
        ran.append(command)
    assert (clone / "fig3.nc").is_file()
    assert len(ran) >= 6, ran


@pytest.mark.parametrize(
    "shown, actual, same",
    [
        (
            "fig3.nc: 43621 strokes (43621 ok) in 0.41 s",
            "fig3.nc: 43621 strokes (43621 ok) in 2.5 s",
            True,
        ),
        (
            "fig3.nc: 43621 strokes (43621 ok) in 0.41 s",
            "fig3.nc: 43620 strokes (43620 ok) in 0.41 s",
            False,
        ),
        ("  v_out_kmh   155.677711 km/h  x", "v_out_kmh 155.6777111 km/h x", True),
        ("  v_out_kmh   155.677711 km/h  x", "v_out_kmh 155.68 km/h x", False),
        ("a 1 b", "a 1 c", False),
    ],
)
def test_an_output_line_matches_as_shown_or_not(shown, actual, same):
    assert _same_line(shown, actual) is same
