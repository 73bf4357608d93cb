"""The random-stroke ladder study: the impact model against the spring contact.
(Not test_ladder.py: tests/inference has one, and pytest needs unique basenames.)"""

import numpy as np

from tennis_stroke.studies.ladder import ladder
from tennis_stroke.studies.sampling import sample_strokes


def test_impact_model_is_close_to_but_not_the_spring_contact():
    """The random-stroke ladder: the impact rung, timed as the spring contact is."""
    ds = ladder(sample_strokes(6, seed=5), repeats=1)
    err = np.abs(ds["v_out_impact"] - ds["v_out_spring"])
    assert 0.05 < float(err.max()) < 5.0
    assert ds.attrs["max_error_impact_kmh"] == float(err.max())
    assert ds.attrs["us_per_stroke_impact"] > 0  # a timing: measured, never compared here
