"""The studies' timing harness: a timed stroke costs what the stroke costs alone."""

import numpy as np
from conftest import FIG4_A, swings_while

from tennis_stroke.studies.timing import compiled_costs


def test_each_timed_copy_of_a_stroke_integrates_its_own_swing():
    """The harness repeats the strokes to fill a batch; were the copies to share one
    swing (as rows that swing alike do by default), the time per stroke would leave the
    swing out and the compiled solver would look cheaper than a stroke is."""
    counted, (us, res) = swings_while(
        lambda: compiled_costs(np.array([FIG4_A[0]]), np.array([FIG4_A[1]]), {}, None, 2, 50)
    )
    assert counted == (100, 100)  # 2 repeats of 50 copies, each copy swung
    assert us.shape == (2,) and np.all(us > 0) and res["status"].tolist() == [0]
