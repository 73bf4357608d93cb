"""The model's parameters, readings and model options as rows of text, for a person to
read (``tennis-stroke params``): each row read from :data:`~.params.PARAMETERS` or
:data:`~.params.CHOICES`, never a second list.
"""

from __future__ import annotations

from .params import CHOICES, PARAMETERS, READINGS, ParamSpec, resolve_params

#: Columns of :func:`parameter_rows`.
PARAMETER_COLUMNS = ("name", "unit", "default", "bounds", "meaning")
#: Columns of :func:`choice_rows`.
CHOICE_COLUMNS = ("name", "choices; meaning")


def bounds_text(spec: ParamSpec) -> str:
    """The values ``spec`` accepts as an interval: ``(0, 5]`` (an exclusive lower bound
    is a round bracket), ``[0, 10]``, ``(-inf, inf)``."""
    low = "(-inf" if spec.lower is None else ("(" if spec.strict else "[") + f"{spec.lower:g}"
    high = "inf)" if spec.upper is None else f"{spec.upper:g}]"
    return f"{low}, {high}"


def parameter_rows() -> list[tuple[str, ...]]:
    """One row per parameter (:data:`PARAMETER_COLUMNS`), in the table's order.  A derived
    parameter's default is its value under the other defaults, and its meaning says
    ``derived``."""
    resolved = resolve_params()
    return [
        (
            name,
            spec.unit,
            f"{resolved[name]:.4g}",
            bounds_text(spec),
            f"derived: {spec.description}" if spec.derived else spec.description,
        )
        for name, spec in PARAMETERS.items()
    ]


def choice_rows() -> list[tuple[str, ...]]:
    """One row per reading and model option (:data:`CHOICE_COLUMNS`): its choices, the
    default marked ``[default]`` and the one that reads the paper word for word
    ``[paper]`` (a reading's ``literal``; a model option's is the paper's model), then
    its meaning."""
    rows = []
    for name, choice in CHOICES.items():
        marked = []
        for option in choice.choices:
            marks = [
                m
                for m, c in (("default", choice.default), ("paper", choice.literal))
                if c == option
            ]
            marked.append(option + (f" [{', '.join(marks)}]" if marks else ""))
        kind = "" if name in READINGS else "model option: "
        rows.append((name, f"{kind}{', '.join(marked)}; {choice.description}"))
    return rows
