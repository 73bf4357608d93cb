"""The registry of figures, read by the workflow and the report.

The result files are named in the table of experiments
(:data:`tennis_stroke.experiments.specs.RESULT_FILES`, by the key that claims and figures
use).  :data:`FIGURES` gives every figure its
section of the paper, the files it is drawn from, the drawing function (a module of
:mod:`tennis_stroke.replication.drawing`) with its extra arguments, and its title.  What
the paper says about a figure, with its numbers, is in ``config/claims.yaml``
(``statements``), the only home of the paper's numbers.

Pure data: the Snakefile imports it without loading the plotting libraries.
"""

from __future__ import annotations

import json
import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..experiments.specs import EXPERIMENTS, RESULT_FILES
from ..model.params import INITIAL_ANGLES, PARAMETERS


@dataclass(frozen=True)
class Mark:
    """A claim drawn on a figure, at the paper's value and at ours.  Its value lies along
    the coordinate ``axis``; the other coordinate is the argument ``at`` of the claim's
    measure (``theta0`` of ``best_delta0``) or the value of the claim ``other`` (a
    point), or neither (a line across the figure)."""

    claim: str
    axis: str
    at: str | None = None
    other: str | None = None


#: A unit as a title, a line of the command line or the report writes it.
UNIT_SHORT = {"degree": "deg", "1": ""}

#: The report's sections of our own, beside the paper's: the fits and the robustness
#: analysis, the model ladder, the speed-against-accuracy studies.
OUR_SECTIONS = ("inference", "ladder", "study")


@dataclass(frozen=True)
class Figure:
    """One figure: file name (without ``.png``), section (where the report shows it: one
    of the paper's, ``III`` ... ``VI``, or of ours, :data:`OUR_SECTIONS`), result files
    (keys of :data:`RESULT_FILES`), drawing function (a module of
    :mod:`tennis_stroke.replication.drawing`) and its extra arguments, and its title: a
    template filled from the first file's attributes (``{L1}`` is ``param_L1``; ``{fixed}``
    the inputs its strokes share, :meth:`fixed_text`), so a title never states a value
    the file does not hold.  ``marks``: the claims drawn on it;
    ``axes``: the coordinates along its x and y axes (a map's or a curve's, where marks
    and the page's view place values); ``dpi`` of the PNG; ``compare``: the variables of
    its first file a scenario's difference panel shows (scenario minus paper,
    :mod:`tennis_stroke.replication.compare`)."""

    name: str
    section: str
    files: tuple[str, ...]
    draw: str
    title: str
    args: tuple = ()
    marks: tuple[Mark, ...] = ()
    axes: tuple[str, ...] = ()
    dpi: int = 110
    compare: tuple[str, ...] = ("v_out",)

    def __post_init__(self):
        # a job's param gives the entry as plain data (dataclasses.asdict)
        marks = tuple(m if isinstance(m, Mark) else Mark(**m) for m in self.marks)
        object.__setattr__(self, "marks", marks)
        object.__setattr__(self, "files", tuple(self.files))
        object.__setattr__(self, "args", tuple(self.args))
        object.__setattr__(self, "axes", tuple(self.axes))
        object.__setattr__(self, "compare", tuple(self.compare))

    def filled_title(self, attrs: Mapping) -> str:
        """The title filled from a result file's attributes: the resolved parameters
        (``{L1}`` for ``param_L1``), the other scalar global attributes
        (``{theta0_deg}``) and, from the job's record of its arguments, the inputs its
        strokes share (``{fixed}``: :meth:`fixed_text`)."""
        context = {k: v for k, v in attrs.items() if np.ndim(v) == 0}
        context.update({k.removeprefix("param_"): v for k, v in context.items()})
        if "config" in attrs:
            context["fixed"] = self.fixed_text(attrs)
        return self.title.format(**context)

    def fixed_inputs(self, attrs: Mapping) -> dict[str, tuple[float, str]]:
        """The inputs every stroke of its first file shares, by name with value and unit
        (``{"theta0": (90.0, "degree"), "C2": (5.0, "N m")}``), from the attributes of
        that file (``config``: its job's params, with the arguments it ran on): each
        initial angle of the row (``Experiment.angles``) and each model parameter the row
        sets under its own name (``Experiment.sets``) that is one number and not a
        variable of the file.  An axis, a list, a search range, a value of each stroke
        (Table I's F0) and a parameter the row derives from an argument of another name
        (each stroke's tau from tau_L and tau_H) are not shared.  None for a file of no
        row of the table of experiments."""
        row = EXPERIMENTS.get(self.files[0])
        if row is None:
            return {}
        arguments = json.loads(attrs["config"])["args"]
        named = [(a.rpartition(".")[2], a) for a in row.angles]
        named += [(p, a) for p, a in row.sets.items() if a.rpartition(".")[2] == p]
        specs = {**INITIAL_ANGLES, **PARAMETERS}
        out = {}
        for name, argument in named:
            head, _, inner = argument.partition(".")
            value = arguments.get(head)
            if inner:
                value = value.get(inner) if isinstance(value, Mapping) else None
            one = isinstance(value, int | float) and not isinstance(value, bool)
            if one and name in specs and name not in row.variables:
                out[name] = (float(value), specs[name].unit)
        return out

    def fixed_text(self, attrs: Mapping) -> str:
        """:meth:`fixed_inputs` as a title and the command line write them, ``theta0 = 90
        deg, delta0 = 52.5 deg``: a no-break space inside each, so that a title wraps
        between them only."""
        return ", ".join(
            f"{name} = {value:g} {UNIT_SHORT.get(unit, unit)}".strip().replace(" ", "\u00a0")
            for name, (value, unit) in self.fixed_inputs(attrs).items()
        )

    @property
    def key(self) -> str:
        """The paper's figure it is, ``fig09`` (where the report puts its statement and
        claims, :func:`claim_figure`); empty for a figure of ours."""
        return self.name[:5] if self.of_paper else ""

    @property
    def of_paper(self) -> bool:
        """Whether it is one of the paper's figures (its section is the paper's)."""
        return self.section not in OUR_SECTIONS

    @property
    def inputs(self) -> list[str]:
        """The result files it is drawn from (paths relative to the workflow)."""
        return [RESULT_FILES[key] for key in self.files]


FIGURES: dict[str, Figure] = {
    f.name: f
    for f in [
        Figure(
            "fig02_angle_map",
            "III",
            ("fig2",),
            "angle_map",
            "Fig. 2: v_out over the initial angles: {fixed}",
            axes=("theta0", "delta0"),
            marks=(Mark("fig2_best_delta0_at_120", "delta0", at="theta0"),),
        ),
        Figure(
            "fig03_angle_map",
            "III",
            ("fig3",),
            "angle_map",
            "Fig. 3: v_out over the initial angles: {fixed}",
            axes=("theta0", "delta0"),
            marks=(
                Mark("fig3_best_delta0_at_120", "delta0", at="theta0"),
                Mark("fig3_best_delta0_at_90", "delta0", at="theta0"),
            ),
        ),
        Figure(
            "fig04_omegas",
            "III",
            ("fig4",),
            "omegas",
            "Fig. 4: angular velocities of two strokes",
            axes=("t", "omega"),
            compare=("omega1", "omega2"),
            marks=(
                Mark("fig4_omega2_a", "omega", other="fig4_t_a"),
                Mark("fig4_omega2_b", "omega", other="fig4_t_b"),
                Mark("fig4_omega1_a", "omega", other="fig4_t_a"),
                Mark("fig4_omega1_b", "omega", other="fig4_t_b"),
            ),
        ),
        Figure(
            "fig05_mass_length_vout",
            "IV",
            ("ml",),
            "mass_length",
            "Fig. 5: fastest v_out over (M2, L1)",
            ("v_out_best",),
            axes=("M2", "L1"),
            compare=("v_out_best",),
        ),
        Figure(
            "fig06_mass_length_theta_c",
            "IV",
            ("ml",),
            "mass_length",
            "Fig. 6: theta_c of the fastest stroke",
            ("theta_c",),
            axes=("M2", "L1"),
            compare=("theta_c",),
        ),
        Figure(
            "fig07_torque_delay",
            "V",
            ("fig7",),
            "delay_map",
            "Fig. 7: v_out over (C2, tau): {fixed}",
            axes=("C2", "tau"),
            marks=(Mark("fig7_threshold", "C2"),),
        ),
        Figure(
            "fig08_delay_delta0",
            "V",
            ("fig8",),
            "delay_map",
            "Fig. 8: v_out over (delta0, tau): {fixed}",
            axes=("delta0", "tau"),
            marks=(Mark("fig8_tau_opt", "tau", other="fig8_delta0_opt"),),
        ),
        Figure(
            "fig09_v_tau",
            "V",
            ("fig9",),
            "v_tau",
            "Fig. 9: v_out over the delay tau: {fixed}",
            axes=("tau", "v_out"),
            marks=(Mark("fig9_v_H", "v_out", other="fig9_tau_H"), Mark("fig9_v_L", "v_out")),
        ),
        Figure(
            "fig10_omegas_delay",
            "V",
            ("delay",),
            "omegas",
            "Fig. 10: angular velocities for tau_L and tau_H: {fixed}",
            axes=("t", "omega"),
            compare=("omega1", "omega2"),
        ),
        Figure(
            "fig11_strobe_tau_H",
            "V",
            ("delay",),
            "strobe",
            "Fig. 11: stroke with tau_H: {fixed}",
            ("tau_H",),
            compare=("theta", "phi"),
        ),
        Figure(
            "fig12_strobe_tau_L",
            "V",
            ("delay",),
            "strobe",
            "Fig. 12: stroke with tau_L: {fixed}",
            ("tau_L",),
            compare=("theta", "phi"),
        ),
        Figure(
            "fig13_elbow_force",
            "VI",
            ("elbow_map",),
            "elbow_force",
            "Fig. 13: v_out over the elbow force direction and delay: {fixed}",
            axes=("psi_F", "tau_F"),
            marks=(Mark("fig13_best_direction", "psi_F"), Mark("fig14_worst_direction", "psi_F")),
        ),
        Figure(
            "fig14_elbow_paths",
            "VI",
            ("elbow",),
            "elbow_paths",
            "Fig. 14: elbow paths until the contact: {fixed}",
            compare=("x_elbow", "y_elbow"),
        ),
        Figure(
            "inference01_score_profiles",
            "inference",
            ("model_profiles", "elbow_force_profiles"),
            "score_profiles",
            "Identification: score along each unknown (the others refitted)",
            dpi=160,
        ),
        Figure(
            "inference02_claims_readings",
            "inference",
            ("robustness",),
            "claims_readings",
            "Robustness: each claim under each consistent reading",
        ),
        Figure(
            "ladder01_claims_by_rung",
            "ladder",
            ("model_ladder",),
            "ladder_claims",
            "Model ladder: every claim under every rung",
            dpi=160,
        ),
        Figure(
            "ladder02_cost_per_scene",
            "ladder",
            ("model_ladder",),
            "ladder_cost",
            "Model ladder: cost against distance from the paper's model, per experiment",
        ),
        Figure(
            "study01_work_precision",
            "study",
            ("work_precision",),
            "work_precision",
            "Work-precision per scene: error against cost per stroke",
        ),
        Figure(
            "study02_stability",
            "study",
            ("stability",),
            "stability",
            "Stability: isolated contact against stiffness",
        ),
        Figure(
            "study03_ladder",
            "study",
            ("ladder",),
            "ladder",
            "Model ladder: instantaneous impact vs spring contact",
        ),
        Figure(
            "study04_convergence",
            "study",
            ("convergence",),
            "convergence",
            "Measured orders: error at fixed steps against the step",
        ),
    ]
}


#: The figures the live explorer recomputes (``tennis-stroke explore --figure``, by the
#: name it takes): the report says how to open each live.
LIVE = {"fig02_angle_map": "fig2", "fig03_angle_map": "fig3", "fig09_v_tau": "fig9"}


def claim_figure(claim: Mapping) -> str:
    """The paper's figure a claim is about, ``fig09``: the figure its ``source`` names
    (``"Sec. V, Fig. 9"``; the first of ``"Figs. 11-12"``), else the one its id starts with
    (``fig4_...``); empty for none (a table's claim).  The report shows it under that
    figure, and ``tennis-stroke whatif --figure`` prints it with the figure."""
    found = re.search(r"Figs?\.\s*(\d+)", claim["source"]) or re.match(r"fig(\d+)_", claim["id"])
    return f"fig{int(found.group(1)):02d}" if found else ""


def paper_figure(name: str) -> str:
    """The registry name of one of the paper's figures from what a user types: its name
    (``fig09_v_tau``) or number (``fig9``, ``fig09``); raises KeyError naming them."""
    if name in FIGURES and FIGURES[name].of_paper:
        return name
    digits = name.removeprefix("fig")
    if digits.isdigit():
        matches = [n for n in FIGURES if n.startswith(f"fig{int(digits):02d}_")]
        if matches:
            return matches[0]
    shown = ", ".join(n for n, f in FIGURES.items() if f.of_paper)
    raise KeyError(f"no figure {name!r} of the paper (its figures: {shown})")
