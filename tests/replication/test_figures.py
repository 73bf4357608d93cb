"""The figure registry drawn: every figure from a tiny run's files, its axes labelled, the
paper's value of each claim it marks drawn and named (the figures job's params)."""

import matplotlib.pyplot as plt
import pytest
from conftest import ROOT

from tennis_stroke.experiments.specs import RESULT_FILES
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.replication.figures import drawn
from tennis_stroke.replication.marks import mark_values
from tennis_stroke.replication.registry import FIGURES

CLAIMS = {c["id"]: c for c in load_claims(ROOT / "config/claims.yaml")}


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_every_figure_is_drawn_labelled_and_marked(tiny_run, name):
    figure = FIGURES[name]
    marks = mark_values(figure, CLAIMS)
    fig = drawn(figure, [tiny_run / RESULT_FILES[k] for k in figure.files], marks=marks)
    try:
        ax = fig.axes[0]
        assert ax.get_title()
        assert ax.get_xlabel() and ax.get_ylabel()  # the first panel's (colour bars aside)
        legend = ax.get_legend()
        named = [t.get_text() for t in legend.get_texts()] if legend else []
        for mark in marks:
            assert any(t.startswith(f"paper: {mark['claim']} ") for t in named), named
            x, y = (mark["paper"], mark["other_paper"])
            if y is not None:  # a point, at the paper's coordinates on the figure's axes
                at = (x, y) if mark["axis"] == figure.axes[0] else (y, x)
                points = [
                    line.get_xydata()[0].tolist()
                    for line in ax.get_lines()
                    if line.get_label().startswith(f"paper: {mark['claim']} ")
                ]
                assert points == [pytest.approx(list(at))]
    finally:
        plt.close(fig)
