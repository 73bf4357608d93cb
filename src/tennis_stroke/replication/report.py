"""The replication report: one self-contained HTML page (figures embedded as PNG data).

Sections: summary of the claims, each reproduced figure beside the paper's statement,
the claims table (failures in red), the assumption ledger (candidates, defaults, the
fits of the identification with their leave-one-out predictions), the
solver settings, run metadata and per-rule timings (Snakemake ``benchmark:`` files).
"""

from __future__ import annotations

import base64
import platform
from collections.abc import Mapping, Sequence
from datetime import UTC, datetime
from pathlib import Path

import jinja2
import pandas as pd
import xarray as xr

from .._version import __version__
from ..failures import failure_counts
from ..io import git_commit
from ..model.params import READINGS
from .claims import load_statements

TEMPLATE = jinja2.Template("""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>tennis-stroke replication report</title>
<style>
body { font-family: sans-serif; max-width: 1100px; margin: auto; padding: 1em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0; }
td, th { border: 1px solid #bbb; padding: 2px 6px; }
tr.fail td { background: #f8c4c4; } tr.known_deviation td { background: #fbe7b5; }
tr.pass td.status { color: #1a6b1a; } .fig { display: flex; gap: 1em; margin: 1em 0; }
.fig img { width: 560px; } .statement { font-style: italic; }
</style></head><body>
<h1>Replication of Youn, "Double pendulum model for tennis stroke including a collision
process"</h1>
<p><b>{{ n_pass }}</b> of {{ n_claims }} claims pass (held out),
<b style="color:#b00">{{ n_fail }}</b> fail, {{ n_known }} are known deviations.
{{ n_ident }} claims (Fig. 4 and Table I's speeds, the fit sets of
config/readings.yaml) were used to fit the readings of the paper; {{ n_fit_ok }} of them
are within tolerance (status <i>used_for_fit</i>): they cannot confirm the readings.</p>

<h2>Claims</h2>
<table><tr><th>id</th><th>source</th><th>quantity</th><th>unit</th><th>paper</th>
<th>reproduced</th><th>tolerance</th><th>status</th><th>note</th></tr>
{% for c in claims %}<tr class="{{ c.status }}"><td>{{ c.id }}</td><td>{{ c.source }}</td>
<td>{{ c.quantity }}</td><td>{{ c.unit }}</td><td>{{ c.paper_value }}</td>
<td>{{ "%.4g"|format(c.reproduced_value) }}</td><td>{{ c.tolerance }}</td>
<td class="status">{{ c.status }}</td>
<td>{% if c.fit_set %}used for fit ({{ c.fit_set }}).{% endif %} {{ c.reason }}</td></tr>
{% endfor %}</table>

<h2>Figures</h2>
{% for f in figures %}<div class="fig">
<img alt="{{ f.name }}" src="data:image/png;base64,{{ f.data }}">
<p class="statement">{{ f.statement }}</p></div>
{% endfor %}

<h2>Assumption ledger</h2>
<p>Every ambiguity of the paper is a named option; config/readings.yaml declares the
candidates, the ranges of the unknowns, the fit sets and the rule that picks the
defaults, before any fit; docs/assumptions.md gives the reasoning.</p>
<table><tr><th>reading</th><th>candidates</th><th>default</th><th>literal</th><th>meaning</th></tr>
{% for r in readings %}<tr><td>{{ r.name }}</td><td>{{ r.choices|join(", ") }}</td>
<td>{{ r.default }}</td><td>{{ r.literal }}</td><td>{{ r.description }}</td></tr>{% endfor %}
</table>
{% for f in fits %}<h3>Fit set {{ f.name }}: the best fits ({{ f.n }} combinations of the
discrete readings, continuous unknowns fitted by bounded least squares)</h3>
<p>Fit claims: {{ f.claims }}. Default by the declared rule: {{ f.default }}.</p>
{{ f.table }}
<p>Leave-one-out: each fit claim predicted by a fit without it.</p>
{{ f.loo }}
{% endfor %}
{% if robustness %}<h2>Robustness across the readings consistent with the paper</h2>
<p>{{ robustness.n_candidates }} Sobol candidates of the continuous unknowns under each of
{{ robustness.n_combinations }} combinations of the model fit's discrete readings
({{ robustness.candidates }} in all) were screened against both fit sets;
{{ robustness.consistent }} are consistent (every fit claim within its tolerance), and
{{ robustness.readings }} of them were kept, each evaluated under
{{ robustness.variants }} combinations of the claim-level readings. Discrete readings
represented: {{ robustness.combos|join("; ") }}.</p>
<p>Held-out claims by robustness class: {% for k, v in robustness.counts.items() %}{{ k }}
{{ v }}{% if not loop.last %}, {% endif %}{% endfor %}.</p>
{{ robustness.table }}
<h3>Evidence for every deviation of the default reading</h3>
<p>best_residual: the smallest |value - paper| / tolerance any consistent reading reaches;
objective_gap: for an argmax claim, how far (km/h) the objective at the paper's argument
lies below its optimum.</p>
{{ robustness.evidence }}
{% endif %}
<h3>All assumptions with their evidence (docs/assumptions.md)</h3>
<pre style="white-space: pre-wrap; font-size: 0.8em">{{ assumptions }}</pre>

<h2>Model ladder and optimum search</h2>
<p>The cheapest model, an instantaneous elastic impact with the racket's effective mass at
phi = 0, differs from the paper's spring contact by up to {{ ladder_error }} km/h on the
sampled strokes: more than the 1 km/h speed tolerance of the claims, so every experiment
keeps the spring contact. The optimum search of Figs. 5-6 (coarse grid, fine grid,
parabola) against a finer reference search:</p>
{% for t in study_tables %}{{ t }}{% endfor %}

<h2>Solver and run</h2>
<table>{% for k, v in meta.items() %}<tr><td>{{ k }}</td><td>{{ v }}</td></tr>{% endfor %}</table>
<h3>Failed strokes per result file</h3>
<p>A stroke that fails is a status in its file, never a crashed job; a map with more
than {{ max_failure_share }} of its strokes failed stops the run (config
<code>max_failure_share</code>).</p>
{{ failure_table }}
<h3>Per-rule wall time (Snakemake benchmark files)</h3>
{{ timing_table }}
</body></html>
""")


def _fit_tables(inference: Mapping[str, str], rows: int = 6) -> list[dict]:
    """The best fits and the leave-one-out table of each fit set (``inference``: the
    registry's keys ``{fit}_fits`` and ``{fit}_loo`` -> paths)."""
    out = []
    for key in sorted(k for k in inference if k.endswith("_fits")):
        fits = xr.load_dataset(inference[key])
        loo = xr.load_dataset(inference[key.removesuffix("_fits") + "_loo"])
        columns = [v for v in fits.data_vars if fits[v].dims == ("combination",)]
        table = fits[columns].to_dataframe().head(rows)
        default = {
            k.removeprefix("default_"): v for k, v in fits.attrs.items() if k.startswith("default_")
        }
        out.append(
            {
                "name": fits.attrs["fit_set"],
                "claims": fits.attrs["fit_claims"],
                "n": fits.sizes["combination"],
                "default": ", ".join(f"{k} = {v}" for k, v in default.items()),
                "table": table.round(4).to_html(index=False),
                "loo": loo.to_dataframe().round(4).to_html(),
            }
        )
    return out


def _robustness(claims: pd.DataFrame, inference: Mapping[str, str]) -> dict:
    """The robustness section: the consistent set, the classes and the evidence."""
    if "robustness" not in inference or "robustness" not in claims:
        return {}
    screen = xr.load_dataset(inference["robustness_screen"])
    kept = xr.load_dataset(inference["robustness"])
    combos = sorted(
        {
            ", ".join(
                f"{k}={kept[k].values[i]}"
                for k in kept.data_vars
                if kept[k].dims == ("reading",) and kept[k].dtype.kind in "OUS"
            )
            for i in range(kept.sizes["reading"])
        }
    )
    held = claims[claims["fit_set"] == ""]
    counts = held["robustness"].value_counts().to_dict()
    deviations = claims[claims["evidence"] != ""]
    return {
        "candidates": screen.sizes["candidate"] * screen.sizes["combination"],
        "n_candidates": screen.sizes["candidate"],
        "n_combinations": screen.sizes["combination"],
        "consistent": int(screen["consistent"].sum()),
        "readings": kept.sizes["reading"],
        "variants": kept.sizes["variant"],
        "combos": combos,
        "counts": counts,
        "table": held[
            [
                "id",
                "paper_value",
                "reproduced_value",
                "robustness",
                "pass_share",
                "deciding",
                "best_value",
            ]
        ].to_html(index=False, float_format=lambda x: f"{x:.4g}"),
        "evidence": deviations[
            [
                "id",
                "paper_value",
                "reproduced_value",
                "evidence",
                "best_value",
                "best_residual",
                "objective_gap",
            ]
        ].to_html(index=False, float_format=lambda x: f"{x:.4g}", na_rep="-"),
    }


def _timings(directory: Path) -> pd.DataFrame:
    """Per-job timings, with the time each was measured: jobs of an earlier run (e.g.
    with other chunk counts) keep their files until ``benchmarks/workflow`` is removed."""
    rows = []
    for path in sorted(directory.glob("*.tsv")):
        table = pd.read_csv(path, sep="\t")
        rows.append(
            {
                "job": path.stem,
                "wall time (s)": round(float(table["s"].iloc[-1]), 2),
                "max RSS (MB)": table.get("max_rss", pd.Series([float("nan")])).iloc[-1],
                "measured (UTC)": datetime.fromtimestamp(path.stat().st_mtime, UTC).isoformat(
                    timespec="seconds"
                ),
            }
        )
    return pd.DataFrame(rows)


def _failures(results: Sequence[str]) -> pd.DataFrame:
    """Strokes, failed strokes and the failing statuses of every result file."""
    rows = []
    for path in results:
        with xr.open_dataset(path) as ds:
            counts = failure_counts(ds)
        if counts:
            rows.append({"file": str(path), **counts})
    return pd.DataFrame(rows).convert_dtypes()


def build_report(
    figures: Sequence[str],
    claims_csv: str,
    inference: Mapping[str, str],
    results: Sequence[str],
    config: Mapping,
    benchmarks_dir: str,
    output: str,
    assumptions_md: str | None = None,
    studies: Sequence[str] = (),
    statements_yaml: str | None = None,
) -> None:
    """Write the report page to ``output`` (``assumptions_md``: the ledger's text;
    ``statements_yaml``: ``config/claims.yaml``, whose ``statements`` quote the paper on
    each figure)."""
    claims = pd.read_csv(claims_csv, keep_default_na=False)
    statements = load_statements(statements_yaml) if statements_yaml else {}
    claims["reproduced_value"] = claims["reproduced_value"].astype(float)
    figs = []
    for path in figures:
        name = Path(path).stem
        figs.append(
            {
                "name": name,
                "statement": statements.get(name[:5], ""),
                "data": base64.b64encode(Path(path).read_bytes()).decode(),
            }
        )
    with xr.open_dataset(results[0]) as ds:
        solver = {k: v for k, v in ds.attrs.items() if k.startswith("solver_")}
    meta = {
        "tennis_stroke version": __version__,
        "git commit": git_commit(),
        "python": platform.python_version(),
        "built": datetime.now(UTC).isoformat(timespec="seconds"),
        **solver,
        "config": dict(config),
    }
    ladder_error, study_tables = "n/a", []
    for path in studies:
        with xr.open_dataset(path) as ds:
            if "max_error_impact_kmh" in ds.attrs:
                ladder_error = f"{float(ds.attrs['max_error_impact_kmh']):.2f}"
            elif "outcome" in ds:
                names = ds["outcome"].attrs["flag_meanings"].split()
                counts = pd.DataFrame(
                    [
                        [int((row == i).sum()) for i in range(len(names))]
                        for row in ds["outcome"].values
                    ],
                    index=[str(c) for c in ds["case"].values],
                    columns=names,
                )
                study_tables.append(
                    "<h3>Stability: outcomes over k = "
                    f"{float(ds.k_contact.min()):g} ... "
                    f"{float(ds.k_contact.max()):g} N/m</h3>" + counts.to_html()
                )
            else:
                study_tables.append(ds.to_dataframe().round(4).to_html())
    html = TEMPLATE.render(
        claims=claims.to_dict("records"),
        n_claims=len(claims),
        n_pass=int((claims.status == "pass").sum()),
        n_fail=int((claims.status == "fail").sum()),
        n_known=int((claims.status == "known_deviation").sum()),
        n_ident=int((claims["fit_set"] != "").sum()),
        n_fit_ok=int((claims.status == "used_for_fit").sum()),
        figures=figs,
        readings=list(READINGS.values()),
        fits=_fit_tables(inference),
        robustness=_robustness(claims, inference),
        meta=meta,
        timing_table=_timings(Path(benchmarks_dir)).to_html(index=False),
        failure_table=_failures(results).to_html(index=False, na_rep="-"),
        max_failure_share=f"{100 * float(config['max_failure_share']):g} %",
        assumptions=Path(assumptions_md).read_text() if assumptions_md else "",
        ladder_error=ladder_error,
        study_tables=study_tables,
    )
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    Path(output).write_text(html)
