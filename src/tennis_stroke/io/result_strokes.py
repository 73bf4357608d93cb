"""Which stroke each result field's value comes from, for the labels of
``tennis-stroke strike``.

A stroke is integrated twice over its start (:mod:`tennis_stroke.solver.stroke`): the
swing without the ball runs on to phi = 0 (t0, the paper's procedure, Sec. II), and the
stroke with the ball leaves it at the contact start t_c = t0 - contact_lead.  So a value
at phi = 0 is none of the stroke with the ball's, and may exceed ``omega2_max``, that
stroke's maximum (issue 66, case 24).  Up to t_c the two are one.

Not in :mod:`tennis_stroke.io.units`: that table's long names are written into the result
files, and it is a code input of the jobs that write them, so a label only the command
line prints would rerun them; no job imports this module, and the files' long names stay
as they are.
"""

from __future__ import annotations

from .units import VARIABLES

SWING = "the swing without the ball"
STROKE = "the stroke with the ball"
BOTH = "both strokes"
#: The stroke each result field comes from, by its file name
#: (:data:`tennis_stroke.io.units.RESULT_VARIABLES`).
RESULT_STROKES: dict[str, str] = {
    "status": BOTH,
    "v_out": STROKE,
    "t_phi0": SWING,
    "t_contact_start": f"{BOTH} (they part here)",
    "t_separation": STROKE,
    "theta_deg_at_phi0": SWING,
    "omega1_phi0": SWING,
    "omega2_phi0": SWING,
    "theta_deg_contact": f"{BOTH} (they part here)",
    "omega1_contact": f"{BOTH} (they part here)",
    "omega2_contact": f"{BOTH} (they part here)",
    "omega2_max": STROKE,
    "rhs_evals": f"{BOTH} together",
    "steps": f"{BOTH} together",
}


def result_label(name: str) -> str:
    """The long name of the result field ``name`` (its file name) and, in brackets, the
    stroke its value comes from (:data:`RESULT_STROKES`)."""
    return f"{VARIABLES[name][1]} [{RESULT_STROKES[name]}]"
