"""Plain-text tables of the command line's output (``params``, ``claims``)."""

from __future__ import annotations

from collections.abc import Sequence


def text_table(
    columns: Sequence[str],
    rows: Sequence[Sequence[str]],
    width: int = 0,
    right: Sequence[int] = (),
) -> str:
    """``rows`` under ``columns`` as aligned plain text, two spaces between columns, the
    columns numbered in ``right`` aligned right; with ``width``, the last column wraps to
    fit it (its further lines indented under it)."""
    import textwrap

    widths = [max(len(str(r[i])) for r in [columns, *rows]) for i in range(len(columns) - 1)]
    indent = sum(widths) + 2 * len(widths)
    fill = max(width - indent, 30) if width else 0
    lines = []
    for row in [columns, *rows]:
        head = "".join(
            f"{str(cell):{'>' if i in right else '<'}{w}s}  "
            for i, (cell, w) in enumerate(zip(row, widths, strict=False))
        )
        last = textwrap.wrap(str(row[-1]), fill) if fill else [str(row[-1])]
        lines.append(head + (last[0] if last else ""))
        lines.extend(" " * indent + more for more in last[1:])
    return "\n".join(line.rstrip() for line in lines)
