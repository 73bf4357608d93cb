"""Every figure of the registry drawn from a finished run's result files, plain and with
a long scenario note (the title breaking and fitting a scenario's page needs), into one
folder: the drawing's time in one process, and PNGs to compare byte for byte with
another commit's (``cmp``).

Run from the checkout after ``make report``::

    .venv/bin/python benchmarks/draw_figures.py OUT

Prints the seconds the drawing took (imports excluded).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from tennis_stroke.inference.claims import load_claims
from tennis_stroke.replication.figures import draw
from tennis_stroke.replication.marks import mark_values
from tennis_stroke.replication.registry import FIGURES

#: A scenario's note of seven changes, two of them with no-break spaces inside.
NOTE = (
    "scenario x: "
    + "; ".join(f"model.M2 = 0.{i}5 kg (paper: 0.3 kg)" for i in range(1, 7))
    + "; torque_delay.base_stroke.C2 = 8 N\u00a0m (paper: 5 N\u00a0m)"
)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path, help="folder for the PNGs (made if missing)")
    out = parser.parse_args().out
    out.mkdir(parents=True, exist_ok=True)
    claims = {c["id"]: c for c in load_claims("config/claims.yaml")}
    start = time.perf_counter()
    for name, figure in sorted(FIGURES.items()):
        marks = mark_values(figure, claims)
        draw(figure, figure.inputs, out / f"{name}.png", "", marks)
        draw(figure, figure.inputs, out / f"{name}_note.png", NOTE, marks)
    print(f"{2 * len(FIGURES)} figures drawn in {time.perf_counter() - start:.1f} s")


if __name__ == "__main__":
    main()
