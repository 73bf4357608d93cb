"""The studies' timing harness: a timed stroke costs what the stroke costs alone."""

import numpy as np
from conftest import FIG4_A

from tennis_stroke.solver.stroke import strike, swings_integrated
from tennis_stroke.studies.timing import compiled_costs


def test_each_timed_copy_of_a_stroke_integrates_its_own_swing():
    """The harness repeats the strokes to fill a batch; were the copies to share one
    swing (as rows that swing alike do by default), the time per stroke would leave the
    swing out and the compiled solver would look cheaper than a stroke is."""
    strike(*FIG4_A)  # the compiled code loaded (its first load runs strokes of its own)
    before = swings_integrated()
    us, res = compiled_costs(np.array([FIG4_A[0]]), np.array([FIG4_A[1]]), {}, None, 2, 50)
    after = swings_integrated()
    assert after[0] - before[0] == 100  # 2 repeats of 50 copies
    assert after[1] - before[1] == 100  # each copy swung
    assert us.shape == (2,) and np.all(us > 0) and res["status"].tolist() == [0]
