"""tennis-stroke: Youn's double-pendulum tennis stroke with a ball collision, fast and verified.

Public API
----------
:func:`strike`, :func:`strike_batch`
    One stroke or many (compiled path, parallel).
:class:`SolverSettings`
    Method and tolerances of the compiled solver.
:func:`resolve_params`, :data:`PARAMETERS`, :data:`READINGS`
    Model parameters with units, and the readings of the paper's ambiguities.
:mod:`tennis_stroke.solver.reference`
    The independent scipy ``solve_ivp`` path on the same equations.
"""

from ._cache import configure_numba_cache
from ._version import __version__

configure_numba_cache()

from .model.params import PARAMETERS, READINGS, ParameterError, resolve_params  # noqa: E402
from .solver.results import STATUS_NAMES  # noqa: E402
from .solver.settings import SolverSettings  # noqa: E402
from .solver.stroke import strike, strike_batch  # noqa: E402

__all__ = [
    "PARAMETERS",
    "READINGS",
    "STATUS_NAMES",
    "ParameterError",
    "SolverSettings",
    "__version__",
    "resolve_params",
    "strike",
    "strike_batch",
]
