"""The model's parameters, readings and model options as rows of text, for a person to
read (``tennis-stroke params``): each row read from :data:`~.params.PARAMETERS` or
:data:`~.params.CHOICES`, never a second list.
"""

from __future__ import annotations

from collections.abc import Collection

from .params import CHOICES, PARAMETERS, READINGS, ParamSpec, resolve_params

#: Columns of :func:`parameter_rows`.
PARAMETER_COLUMNS = ("name", "unit", "default", "source", "bounds", "meaning")
#: Where a default comes from, in the words every page and command uses: the paper's
#: value, fitted to the fit sets (``config/readings.yaml``), derived from the others, or
#: a default of ours (a solver setting, an option beyond the paper).
ORIGINS = ("paper", "fitted", "derived", "ours")


def origin(name: str, fitted: Collection[str] = ()) -> str:
    """Where the default of model parameter or reading ``name`` comes from
    (:data:`ORIGINS`); ``fitted``: the names whose default is fitted
    (:meth:`tennis_stroke.inference.reading_space.ReadingSpace.fitted`)."""
    if name in fitted:
        return "fitted"
    if name in PARAMETERS:
        return "derived" if PARAMETERS[name].derived else "paper"
    choice = CHOICES[name]
    return "paper" if choice.default == choice.literal else "ours"


#: Columns of :func:`choice_rows`.
CHOICE_COLUMNS = ("name", "choices; meaning")


def bounds_text(spec: ParamSpec) -> str:
    """The values ``spec`` accepts as an interval: ``(0, 5]`` (an exclusive lower bound
    is a round bracket), ``[0, 10]``, ``(-inf, inf)``."""
    low = "(-inf" if spec.lower is None else ("(" if spec.strict else "[") + f"{spec.lower:g}"
    high = "inf)" if spec.upper is None else f"{spec.upper:g}]"
    return f"{low}, {high}"


def parameter_rows(fitted: Collection[str] = ()) -> list[tuple[str, ...]]:
    """One row per parameter (:data:`PARAMETER_COLUMNS`), in the table's order, with the
    :func:`origin` of its default.  A derived parameter's default is its value under the
    other defaults."""
    resolved = resolve_params()
    return [
        (
            name,
            spec.unit,
            f"{resolved[name]:.4g}",
            origin(name, fitted),
            bounds_text(spec),
            spec.description,
        )
        for name, spec in PARAMETERS.items()
    ]


def choice_rows(fitted: Collection[str] = ()) -> list[tuple[str, ...]]:
    """One row per reading and model option (:data:`CHOICE_COLUMNS`): its choices, the
    default marked ``[default]`` (``[default, fitted]`` where it is fitted) and the one
    that reads the paper word for word ``[paper]`` (a reading's ``literal``; a model
    option's is the paper's model), then its meaning."""
    rows = []
    for name, choice in CHOICES.items():
        marked = []
        default = "default, fitted" if name in fitted else "default"
        for option in choice.choices:
            marks = [
                m for m, c in ((default, choice.default), ("paper", choice.literal)) if c == option
            ]
            marked.append(option + (f" [{', '.join(marks)}]" if marks else ""))
        kind = "" if name in READINGS else "model option: "
        rows.append((name, f"{kind}{', '.join(marked)}; {choice.description}"))
    return rows
