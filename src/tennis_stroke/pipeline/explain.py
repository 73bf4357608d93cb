"""What each config key drives: the result files, figures and claims a change of it moves.

Derived from the table of experiments (the config keys each row reads,
:func:`tennis_stroke.pipeline.params.read_keys`), the registry of figures (the files each
is drawn from) and the claims (the files each reads), so it cannot drift from what the
workflow runs; ``tests/workflow/test_workflow_failsafe.py`` checks the rows against what
``snakemake -n`` plans after changing each key.  ``tennis-stroke config explain KEY``
prints one key's entry; ``docs/config_keys.md`` is the whole table
(``tennis-stroke config explain --all``).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass

from ..experiments.specs import EXPERIMENTS, VALIDATION_GROUPS
from ..inference.claims import claim_files
from ..io.config_files import config_keys, did_you_mean
from ..model.params import CHOICES, PARAMETERS
from ..replication.registry import FIGURES
from .params import PAPER_SECTIONS, reads, related

#: The inference jobs and the config keys each reads besides its files (a change of one
#: reruns it): the identification and the robustness screen simulate the fit sets'
#: strokes; the claims and the robustness analysis run the targeted evaluation of the
#: paper's sections; the model ladder also its own section and the figures' curves.
#: (The keys of tennis_stroke.experiments.specs.fit_set_arguments: Fig. 4's strokes, the
#: Table I force and stroke.)
_FIT_SETS = (
    EXPERIMENTS["fig4"].key_of("strokes"),
    *(k for arg in ("force", "stroke") for k in EXPERIMENTS["elbow"].args[arg].values()),
    "model",
    "solver",
)
_PAPER = (*PAPER_SECTIONS, "model", "solver")
INFERENCE_READS = {
    "identification": _FIT_SETS,
    "robustness analysis": (*_FIT_SETS, *_PAPER),
    "claims": _PAPER,
    "model ladder": (*_PAPER, "figure_curves", "model_ladder"),
}


class UnknownKeyError(KeyError):
    """A config key the configuration does not have (one line)."""

    def __str__(self) -> str:
        return str(self.args[0])


@dataclass(frozen=True)
class KeyEffect:
    """What a change of one config key moves."""

    key: str
    rows: tuple[str, ...]
    files: tuple[str, ...]
    figures: tuple[str, ...]
    claims: tuple[str, ...]
    inference: tuple[str, ...]
    note: str = ""
    instead: tuple[str, ...] = ()


def rows_reading(key: str) -> list[str]:
    """The rows of the table of experiments whose jobs a change of ``key`` reruns: those
    that read it (a row reading a mapping reads its keys; every model row reads
    ``model`` and ``solver``) and, for a chunk count, the rows it splits."""
    if key.startswith("chunks."):
        return [k for k, e in EXPERIMENTS.items() if e.chunks == key]
    return [k for k, e in EXPERIMENTS.items() if reads(e, key)]


def effect(key: str, claims: Sequence[Mapping]) -> KeyEffect:
    """What a change of config ``key`` moves (``claims``: the declared claims)."""
    rows = rows_reading(key)
    note = ""
    if key == "max_failure_share":
        note = "checked when a map is gathered: moves no number (reruns the gatherings)"
    elif key.startswith("chunks."):
        note = "splits the map into jobs: moves no number (reruns the map's jobs)"
    elif key == "max_points_per_job":
        note = "a bound checked before any job, and each job's resources: moves no number"
    moving = [] if note else rows
    inference = [
        name for name, keys in INFERENCE_READS.items() if any(related(key, r) for r in keys)
    ]
    searched = key == "search" or key.startswith("search.")
    if key.startswith("model_ladder"):
        files = {"model_ladder"}
    else:
        files = set(moving)
    figures = [n for n, f in FIGURES.items() if files & set(f.files)]
    moved_claims = [
        c["id"]
        for c in claims
        if set(claim_files(c)) & set(moving) or (searched and set(claim_files(c)) & _searched())
    ]
    section, _, name = key.partition(".")
    instead = tuple(
        f"{e.label} (reads {e.reads_instead(name)})"
        for e in EXPERIMENTS.values()
        if section == "model" and name in e.sets
    )
    return KeyEffect(
        key,
        tuple(rows),
        tuple(EXPERIMENTS[k].path for k in moving),
        tuple(figures),
        tuple(moved_claims),
        tuple(inference),
        note,
        instead,
    )


def _searched() -> set[str]:
    return {k for keys in VALIDATION_GROUPS.values() for k in keys}


def leaves(node, parts: tuple = ()) -> Iterator[str]:
    """The keys of a config a user sets, dotted: scalars, lists and ranges
    (``{start, stop, ...}``); other mappings are walked (an empty one is a key)."""
    if isinstance(node, Mapping) and node and not {"start", "stop"} <= set(node):
        for key, value in node.items():
            yield from leaves(value, (*parts, str(key)))
    else:
        yield ".".join(parts)


def explain(key: str, config: Mapping, claims: Sequence[Mapping]) -> KeyEffect:
    """:func:`effect` of a key of ``config`` at any depth (a section, a leaf, a range or
    one of its bounds and step: :func:`~tennis_stroke.io.config_files.config_keys`), or
    of a model parameter, reading or option by its name; raises
    :class:`UnknownKeyError` naming the closest keys otherwise."""
    if key in PARAMETERS or key in CHOICES:  # a model parameter, reading or option by name
        key = f"model.{key}"
    section, _, name = key.partition(".")
    if section == "model" and (name in PARAMETERS or name in CHOICES):
        return effect(key, claims)
    known = list(config_keys(config))
    if key not in known:
        names = (*PARAMETERS, *CHOICES)  # taken by name or as model.NAME
        every = [*known, *names, *(f"model.{p}" for p in names)]
        hint = did_you_mean(key, every)
        raise UnknownKeyError(f"config key {key!r} is not in the configuration{hint}")
    return effect(key, claims)


def _names(items: Sequence[str], limit: int = 0) -> str:
    if not items:
        return "-"
    shown = list(items[:limit] if limit else items)
    more = f" and {len(items) - limit} more" if limit and len(items) > limit else ""
    return ", ".join(shown) + more


def text(e: KeyEffect) -> str:
    """One key's entry for the command line."""
    lines = [f"{e.key}:" + (f" {e.note}" if e.note else "")]
    lines.append(f"  experiments  {_names(e.rows)}")
    lines.append(f"  files        {_names(e.files)}")
    lines.append(f"  figures      {_names(e.figures)}")
    lines.append(f"  claims       {len(e.claims)}: {_names(e.claims)}")
    if e.instead:
        lines.append(f"  not read by  {_names(e.instead)}: each sets it itself")
    lines.append(f"  in the paper's run, also reruns  {_names(e.inference)}")
    return "\n".join(lines)


def markdown(config: Mapping, claims: Sequence[Mapping]) -> str:
    """The whole table, one row per key of ``config`` (``docs/config_keys.md``)."""
    out = [
        "| config key | experiments (jobs rerun) | figures | claims moved | also reruns |",
        "|---|---|---|---:|---|",
    ]
    for key in leaves(config):
        e = effect(key, claims)
        rows = _names(e.rows) + (f" ({e.note})" if e.note else "")
        figures = _names([f.split("_")[0] for f in e.figures])
        out.append(f"| `{key}` | {rows} | {figures} | {len(e.claims)} | {_names(e.inference)} |")
    return "\n".join(out)
