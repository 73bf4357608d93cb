"""tennis-stroke: Youn's double-pendulum tennis stroke with a ball collision, fast and verified.

The public API:

* :func:`strike`, :func:`strike_batch`: one stroke or many (the compiled path, parallel),
  their result fields.
* :func:`solve_stroke`, :func:`stroke_dataset`: one stroke over time (the independent
  scipy path, dense output) and its trajectory in the lab frame as an ``xarray.Dataset``
  with units: the angles and rates, the elbow, the racket's hitting point and the ball.
* :class:`SolverSettings`: the method and tolerances of the compiled solver.
* :func:`resolve_params`, :data:`PARAMETERS`, :data:`READINGS`, :data:`MODEL_OPTIONS`:
  the model's parameters with units, the readings of the paper's ambiguities, and the
  model options (the rungs of the model ladder: ``contact_model``).
* :mod:`tennis_stroke.solver.reference`: the independent scipy ``solve_ivp`` path on the
  same equations.

The API reference of these names and of the modules they come from is built by
``make api`` into ``docs/api/`` (``tools/api_reference.py``).
"""

import time
from importlib import import_module

#: When the package's first module started importing (``time.perf_counter``): a job's
#: log splits its start-up from its imports here (:func:`tennis_stroke.pipeline.jobs.logged`).
IMPORT_STARTED = time.perf_counter()

from ._cache import configure_numba_cache  # noqa: E402 (after IMPORT_STARTED)
from ._version import __version__  # noqa: E402

configure_numba_cache()

#: The public API and the module of each name.  Imported on first use (PEP 562), so that
#: a job that only reads result files (a figure, the claims, the report) does not load
#: numba and the compiled solver.
_API = {
    "MODEL_OPTIONS": ".model.params",
    "PARAMETERS": ".model.params",
    "READINGS": ".model.params",
    "ParameterError": ".model.params",
    "resolve_params": ".model.params",
    "STATUS_NAMES": ".solver.results",
    "SolverSettings": ".solver.settings",
    "solve_stroke": ".solver.reference",
    "stroke_dataset": ".io.trajectory",
    "strike": ".solver.stroke",
    "strike_batch": ".solver.stroke",
}


def __getattr__(name: str) -> object:
    if name not in _API:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(_API[name], __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_API])


__all__ = [
    "MODEL_OPTIONS",
    "PARAMETERS",
    "READINGS",
    "STATUS_NAMES",
    "ParameterError",
    "SolverSettings",
    "__version__",
    "resolve_params",
    "solve_stroke",
    "strike",
    "strike_batch",
    "stroke_dataset",
]
