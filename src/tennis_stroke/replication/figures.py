"""The paper's figures, drawn from the result files (never re-simulating).

:func:`draw` draws a figure of the registry (:mod:`tennis_stroke.replication.registry`)
with its drawing function (:mod:`tennis_stroke.replication.drawing`); axis labels and
colour-bar labels come from the files' ``long_name`` and ``units`` attributes.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
import textwrap
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import matplotlib.pyplot as plt

from ..io.netcdf import load_result
from .registry import FIGURES, Figure

#: The package of the drawing functions, one module each named after its function.
DRAWING = f"{__package__}.drawing"
#: The drawing package's module of shared helpers (not a drawing function).
HELPERS = "axes"


def drawing_names() -> tuple[str, ...]:
    """The drawing functions (:attr:`~tennis_stroke.replication.registry.Figure.draw`):
    the modules of :data:`DRAWING` but its helpers."""
    folder = Path(__file__).parent / "drawing"
    return tuple(sorted(m.name for m in pkgutil.iter_modules([str(folder)]) if m.name != HELPERS))


def drawer(name: str) -> Callable[..., plt.Figure]:
    """The drawing function ``name``, imported from its own module only: a figure job
    loads (and its code inputs list) the drawing it runs, not the others."""
    if name not in drawing_names():
        raise KeyError(f"no drawing function {name!r} (known: {', '.join(drawing_names())})")
    return getattr(importlib.import_module(f"{DRAWING}.{name}"), name)


def paper_marks(ax, marks: Sequence[Mapping], axes: Sequence[str]) -> None:
    """The paper's value of each mark (:func:`~tennis_stroke.replication.marks.mark_values`)
    in red, labelled with its claim: a ring at a point, a dashed line across the axes."""
    for mark in marks:
        along_x = mark["axis"] == axes[0]
        text = f"paper: {mark['claim']} = {mark['paper']:g}"
        if mark["other_paper"] is None:
            line = ax.axvline if along_x else ax.axhline
            line(mark["paper"], color="r", ls="--", lw=1.2, label=text)
            continue
        x, y = (mark["paper"], mark["other_paper"])[:: 1 if along_x else -1]
        text = f"paper: {mark['claim']} at ({x:g}, {y:g})"
        ax.plot(x, y, "o", ms=10, mfc="none", mec="r", mew=2, label=text)
    if marks:
        ax.legend(fontsize=7, loc="best", framealpha=0.7)


def drawn(
    figure: Figure,
    inputs: Sequence[str | Path],
    note: str = "",
    marks: Sequence[Mapping] = (),
) -> plt.Figure:
    """``figure`` (a registry entry) drawn from its result files: the drawing function's
    figure, the paper's ``marks`` in red, ``note`` (a scenario's changes) as a second
    title line."""
    datasets = [load_result(p) for p in inputs]
    fig = drawer(figure.draw)(datasets, figure.filled_title(datasets[0].attrs), *figure.args)
    paper_marks(fig.axes[0], marks, figure.axes)
    if note:  # below the figure's title (a panel's, or the whole figure's above panels)
        top = fig.get_suptitle()
        if top:
            width = int(fig.get_figwidth() * 11)  # characters of 10 pt across the figure
            fig.suptitle(top + "\n" + wrapped(note, width), fontsize=10)
        else:
            ax = fig.axes[0]
            ax.set_title(ax.get_title() + "\n" + wrapped(note, 48))
    fig.tight_layout()
    # each step draws the canvas only where the one before changed it since its draw
    drawn_as_is = _titles_broken_to_fit(fig)
    drawn_as_is = _room_for_titles(fig, drawn_as_is)
    _legends_clear_of_points(fig, drawn_as_is)
    return fig


def _titles(fig: plt.Figure) -> list:
    """The figure's title texts: its suptitle and each panel's title, where set."""
    return [t for t in (*fig.texts, *(ax.title for ax in fig.axes)) if t.get_text()]


def _titles_broken_to_fit(fig: plt.Figure) -> bool:
    """Break each line of a title wider than the canvas (the inputs Fig. 13's strokes
    share) between words, at as many characters as the canvas holds; a no-break space
    (inside ``theta0 = 90 deg``, inside a note's change) is no place to break.  Returns
    whether the canvas is drawn as the figure now is."""
    fig.canvas.draw()
    broken = False
    for title in _titles(fig):
        box = title.get_window_extent()
        if box.width <= fig.bbox.width:
            continue
        lines = title.get_text().split("\n")
        fit = int(max(map(len, lines)) * fig.bbox.width / box.width * 0.95)
        parts = [textwrap.wrap(line, fit, break_long_words=False) or [""] for line in lines]
        title.set_text("\n".join(p for part in parts for p in part))
        broken = True
    if broken:
        fig.tight_layout()
    return not broken


#: Where a legend that covers a marked point moves inside its axes, in the order tried.
LEGEND_PLACES = (
    "upper right",
    "upper left",
    "lower left",
    "lower right",
    "center right",
    "center left",
    "upper center",
    "lower center",
    "center",
)


def _marked_points(ax, renderer) -> list:
    """The drawn extent (display coordinates, the marker's size included) of each
    single point ``ax`` marks: the paper's rings, Fig. 13's star."""
    return [
        line.get_window_extent(renderer)
        for line in ax.lines
        if len(line.get_xdata()) == 1 and line.get_marker() not in (None, "None", "")
    ]


def _legends_clear_of_points(fig: plt.Figure, drawn_as_is: bool = False) -> None:
    """Move each legend that covers a marked point (:func:`_marked_points`, as drawn:
    ``loc="best"`` counts a point's centre, not its marker, and takes a place over a
    point when every place crosses a line) to the first of :data:`LEGEND_PLACES` that
    covers none; a legend already clear stays where it is.  ``drawn_as_is``: the canvas
    is drawn as the figure is (no draw is needed before the first legend)."""
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None or not any(len(line.get_xdata()) == 1 for line in ax.lines):
            continue
        if not drawn_as_is:
            fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        points = _marked_points(ax, renderer)
        drawn_as_is = True
        for place in (None, *LEGEND_PLACES):
            if place is not None:
                legend.set_loc(place)
                fig.canvas.draw()
            box = legend.get_window_extent(renderer)
            if not any(box.overlaps(p) for p in points):
                break
        else:  # no place is clear: where matplotlib would put it
            legend.set_loc("best")
            drawn_as_is = False


def _room_for_titles(fig: plt.Figure, drawn_as_is: bool = False) -> bool:
    """Fit ``fig``'s titles on its canvas: a title wider than the canvas (a scenario
    note's unbreakable change over a narrow figure) gets a smaller font, down to 6 pt;
    then the figure grows by what the titles reach above it (over axes whose aspect
    tight_layout cannot shrink), and is laid out again.  ``drawn_as_is``: the canvas is
    drawn as the figure is (the first check needs no draw); returns whether it still
    is."""
    titles = _titles(fig)
    for step in range(16):  # the suptitle is one of the figure's texts
        if step or not drawn_as_is:
            fig.canvas.draw()
        wide = [
            t
            for t in titles
            if t.get_fontsize() > 6
            and (t.get_window_extent().x0 < 0 or t.get_window_extent().x1 > fig.bbox.x1)
        ]
        if not wide:
            break
        for title in wide:
            title.set_fontsize(title.get_fontsize() - 0.5)
        fig.tight_layout()
    over = max(t.get_window_extent().y1 for t in titles) - fig.bbox.y1
    if over > 0:
        fig.set_figheight(fig.get_figheight() + (over + 4) / fig.dpi)
        fig.tight_layout()
        return False
    return not wide  # else the last smaller font is laid out, not drawn


def wrapped(note: str, width: int) -> str:
    """``note`` (changes ``key = value (paper: value)`` joined by ``"; "``, the word
    before the old value where it comes from: ``paper``, ``fitted``, ``ours`` ...) on
    lines of at most ``width`` characters, broken between changes or before ``(paper:
    ...)`` only, never inside a value and its unit."""
    before = re.compile(r" \(([a-z]+): ")
    items = []
    for item in note.split("; "):
        head, *found = before.split(item, maxsplit=1)
        keep = head.replace(" ", "\u00a0")
        if found:
            word, old = found
            keep += f" ({word}:\u00a0" + old.replace(" ", "\u00a0")
        items.append(keep)
    return "\n".join(textwrap.wrap("; ".join(items), width, break_long_words=False))


def draw(
    figure: str | Figure,
    inputs: Sequence[str | Path],
    output: str | Path,
    note: str = "",
    marks: Sequence[Mapping] = (),
) -> None:
    """Draw ``figure`` (a registry entry, or its name in :data:`FIGURES`) from its result
    files into ``output`` (PNG, at the entry's dpi): :func:`drawn`."""
    figure = FIGURES[figure] if isinstance(figure, str) else figure
    fig = drawn(figure, inputs, note, marks)
    fig.savefig(output, dpi=figure.dpi)
    plt.close(fig)
