"""Sortable tables whose columns are as wide as their text (the multiverse's, the live
explorer's claims)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from bokeh.models import ColumnDataSource, DataTable

#: Pixels per character of a table's text (12 px sans-serif) and around it: a column is
#: as wide as its title and its longest value (up to :data:`CELL_CHARS` characters); its
#: title was cut ("contact_lead", "k_contact (N/").
HEADER_CHAR_PX, HEADER_PAD_PX, CELL_CHARS = 7.5, 22, 80


def _text_width(col, values) -> int:
    """Characters a table column needs: its title, its values (a number: 10)."""
    cells = [10 if isinstance(v, (int, float, np.number)) else len(str(v)) for v in values[:500]]
    return max(len(col.title), min(max(cells, default=0), CELL_CHARS))


def fit_columns(data: Mapping, columns: Sequence) -> None:
    """Make each table column as wide as its title and its longest value in ``data``
    (up to :data:`CELL_CHARS` characters): no title or value is cut."""
    for col in columns:
        chars = _text_width(col, list(data.get(col.field, [])))
        col.width = int(HEADER_CHAR_PX * chars + HEADER_PAD_PX)


def data_table(source: ColumnDataSource, columns: list, height: int, name: str) -> DataTable:
    """A sortable table whose rows a reader picks (no column dragging: it needs
    jquery-ui, which BokehJS does not ship), each column as wide as its title at least
    (a wide table scrolls sideways)."""
    fit_columns(source.data, columns)
    return DataTable(
        source=source,
        columns=columns,
        sortable=True,
        reorderable=False,
        selectable=True,
        index_position=None,
        autosize_mode="none",
        width=1000,
        height=height,
        name=name,
    )
