"""Print the identification tables of docs/assumptions.md from the result files.

    .venv/bin/python tools/assumptions_tables.py [results/identification]

The numbers in docs/assumptions.md's identification section are this script's output,
pasted between its BEGIN/END markers, never typed by hand.
"""

import sys
from pathlib import Path

import xarray as xr


def _row(cells) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


def tables(folder: Path, rows: int = 6) -> str:
    out = []
    for fit in ("model", "elbow_force"):
        fits = xr.load_dataset(folder / f"{fit}_fits.nc")
        loo = xr.load_dataset(folder / f"{fit}_loo.nc")
        cols = [v for v in fits.data_vars if fits[v].dims == ("combination",)]
        out.append(
            f"**Fit set `{fit}`** ({fits.sizes['combination']} combinations; "
            f"claims: {fits.attrs['fit_claims']})\n"
        )
        out.append(_row(cols))
        out.append(_row(["--"] * len(cols)))
        for i in range(min(rows, fits.sizes["combination"])):
            out.append(
                _row(
                    f"{fits[c].values[i]:.4g}" if fits[c].dtype.kind == "f" else fits[c].values[i]
                    for c in cols
                )
            )
        default = {
            k.removeprefix("default_"): v for k, v in fits.attrs.items() if k.startswith("default_")
        }
        out.append(
            "\nDefault by the declared rule: "
            + ", ".join(f"`{k} = {v}`" for k, v in default.items())
            + ".\n"
        )
        out.append(
            _row(
                [
                    "claim",
                    "paper",
                    "best fit",
                    "residual",
                    "left-out prediction",
                    "left-out residual",
                ]
            )
        )
        out.append(_row(["--"] * 6))
        for i, claim in enumerate(fits["claim"].values):
            out.append(
                _row(
                    [
                        claim,
                        f"{float(fits.paper_value[i]):g}",
                        f"{float(fits.value[0, i]):.4g}",
                        f"{float(fits.residual[0, i]):+.2f}",
                        f"{float(loo.predicted[i]):.4g}",
                        f"{float(loo.residual[i]):+.2f}",
                    ]
                )
            )
        out.append("")
    return "\n".join(out)


if __name__ == "__main__":
    print(tables(Path(sys.argv[1] if len(sys.argv) > 1 else "results/identification")))
