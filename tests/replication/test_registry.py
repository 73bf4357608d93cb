"""The figure registry as data: each entry names files, a drawing function and a section
that exist, its marks lie along its axes and resolve to the paper's values, it survives
the trip through a job's params, and its title is filled from a file's attributes."""

import json
import re
from dataclasses import asdict

import pytest
import yaml
from conftest import ROOT

from tennis_stroke.experiments.specs import EXPERIMENTS, RESULT_FILES, sorted_data
from tennis_stroke.inference.claims import load_claims
from tennis_stroke.io.config_files import load_yaml
from tennis_stroke.pipeline.params import simulation_params
from tennis_stroke.replication.figures import drawer, drawing_names
from tennis_stroke.replication.marks import mark_values
from tennis_stroke.replication.registry import FIGURES, OUR_SECTIONS, Figure, Mark

CLAIMS = {c["id"]: c for c in load_claims(ROOT / "config/claims.yaml")}
PAPER_SECTIONS = yaml.safe_load((ROOT / "config/claims.yaml").read_text())["sections"]
PAPER = load_yaml(ROOT / "config" / "config.yaml")


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_an_entry_names_what_exists(name):
    """Its files are result files, its drawing function is one of figures.py's, and its
    section is one of the paper's (config/claims.yaml) or of ours; a figure of the paper
    is named by its number (``fig09_...``: the report finds its statement and claims by
    it), no other is."""
    figure = FIGURES[name]
    assert figure.name == name
    assert set(figure.files) <= set(RESULT_FILES)
    assert figure.draw in drawing_names()
    assert figure.section in PAPER_SECTIONS or figure.section in OUR_SECTIONS
    assert figure.of_paper == (figure.section in PAPER_SECTIONS)
    assert figure.of_paper == bool(re.fullmatch(r"fig\d\d_\w+", name))


@pytest.mark.parametrize("name", sorted(n for n, f in FIGURES.items() if f.marks))
def test_marks_lie_along_the_figure_s_axes_at_the_paper_s_values(name):
    """A mark's value lies along one of the two axes the figure declares; the paper's
    value and the other coordinate of a point come from the declared claims."""
    figure = FIGURES[name]
    assert len(figure.axes) == 2
    values = mark_values(figure, CLAIMS, {m.claim: 1.5 for m in figure.marks})
    for mark, value in zip(figure.marks, values, strict=True):
        claim = CLAIMS[mark.claim]
        assert mark.axis in figure.axes
        assert value["paper"] == float(claim["paper_value"]) and value["ours"] == 1.5
        if mark.at:
            assert value["other_paper"] == float(claim["measure"][mark.at])
        elif mark.other:
            assert value["other_paper"] == float(CLAIMS[mark.other]["paper_value"])
        else:
            assert value["other_paper"] is None


def test_a_mark_naming_no_claim_or_argument_is_refused():
    base = FIGURES["fig02_angle_map"]
    for mark, message in (
        (Mark("no_such_claim", "delta0"), "no_such_claim"),
        (Mark("fig2_best_delta0_at_120", "delta0", at="nothing"), "nothing"),
        (Mark("fig9_v_H", "v_out", other="no_such_claim"), "no_such_claim"),
    ):
        figure = Figure(**{**asdict(base), "marks": (mark,)})
        with pytest.raises(KeyError, match=message):
            mark_values(figure, CLAIMS)


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_an_entry_survives_a_job_s_params(name):
    """The figure job gets its entry as plain data (``asdict``, sorted): the same entry
    comes back, its marks Marks again."""
    figure = FIGURES[name]
    assert Figure(**sorted_data(asdict(figure))) == figure


def test_a_title_is_filled_from_a_file_s_attributes():
    """``{L1}`` is the file's ``param_L1``, ``{theta0_deg}`` its own attribute; an
    attribute the file does not hold is an error, never a title with a gap."""
    figure = Figure("x", "III", ("fig2",), "angle_map", "L1 = {L1:g} m at {theta0_deg:g} deg")
    attrs = {"param_L1": 0.35, "theta0_deg": 120.0, "solver_rtol": [1e-9, 1e-10]}
    assert figure.filled_title(attrs) == "L1 = 0.35 m at 120 deg"
    with pytest.raises(KeyError, match="theta0_deg"):
        figure.filled_title({"param_L1": 0.35})


def _job_attrs(key: str) -> dict:
    """What a row's job records of its params in its file (``config``, pipeline.jobs.save),
    under the paper's configuration."""
    return {"config": json.dumps(simulation_params(EXPERIMENTS[key], PAPER), sort_keys=True)}


@pytest.mark.parametrize("name", sorted(n for n, f in FIGURES.items() if f.of_paper))
def test_a_paper_figure_s_title_names_the_inputs_its_strokes_share(name):
    """Issue 66, case 21: Fig. 9's title named neither theta0 = 90 deg nor delta0 = 52.5
    deg, the inputs its gain over no delay was computed at (16.1 % there, 12.4 % with
    delta0 optimised at tau = 0). A paper figure's title names each input every stroke of
    its first file shares, as the file's job recorded it: the row's initial angles and
    the model parameters it sets that are one number."""
    figure = FIGURES[name]
    attrs = _job_attrs(figure.files[0])
    title = figure.filled_title(attrs).replace("\u00a0", " ")
    shared = figure.fixed_text(attrs).replace("\u00a0", " ")
    for text in shared.split(", ") if shared else []:
        assert text in title, (text, title)


def test_the_inputs_a_figure_s_strokes_share_are_the_job_s_single_values():
    """Fig. 9's curve: theta0 and delta0 of the base stroke, L1 and C2 (the delay tau is
    its axis); the Figs. 10-12 strokes share no tau (tau_L and tau_H, each a stroke's);
    the Fig. 2 map shares only L1 (the angles are its axes); Fig. 4's two strokes have
    angles of their own."""
    stroke = PAPER["torque_delay"]
    shared = FIGURES["fig09_v_tau"].fixed_inputs(_job_attrs("fig9"))
    assert shared == {
        "theta0": (stroke["theta0"], "degree"),
        "delta0": (stroke["base_stroke"]["delta0"], "degree"),
        "L1": (stroke["L1"], "m"),
        "C2": (stroke["base_stroke"]["C2"], "N m"),
    }
    assert FIGURES["fig09_v_tau"].fixed_text(_job_attrs("fig9")).replace("\u00a0", " ") == (
        "theta0 = 90 deg, delta0 = 52.5 deg, L1 = 0.4 m, C2 = 5 N m"
    )
    assert set(FIGURES["fig10_omegas_delay"].fixed_inputs(_job_attrs("delay"))) == {
        "theta0",
        "delta0",
        "L1",
        "C2",
    }
    assert FIGURES["fig02_angle_map"].fixed_inputs(_job_attrs("fig2")) == {"L1": (0.3, "m")}
    assert FIGURES["fig04_omegas"].fixed_inputs(_job_attrs("fig4")) == {}


def test_every_drawing_module_is_one_function_of_its_name_and_a_bad_name_is_refused():
    """Each module of the drawing package holds the function of its name (what
    :func:`drawer` loads), every one is drawn by some figure, and an unknown name is a
    one-line error naming the known ones."""
    names = drawing_names()
    assert set(names) == {f.draw for f in FIGURES.values()}
    for name in names:
        assert drawer(name).__name__ == name
    with pytest.raises(KeyError, match="no drawing function 'axes'.*angle_map"):
        drawer("axes")
