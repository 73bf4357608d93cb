"""The ball's and the racket's speed through one stroke, from Python.

Fig. 4's stroke a (theta0 = 120 deg, delta0 = 81.5 deg, the default reading) solved
with the scipy path, its trajectory in the lab frame as an ``xarray.Dataset``
(:func:`tennis_stroke.stroke_dataset`), and the speeds of the racket's hitting point and
of the ball drawn over the whole stroke and over the contact. Every axis is labelled
from the dataset's ``long_name`` and ``units``.

Run it with the environment active::

    python examples/stroke_speeds.py                  # writes stroke_speeds.png
    python examples/stroke_speeds.py OUT.png --theta0 75 --delta0 39 --set M2=0.35

It prints the rebound speed and the racket's speed at the contact start.
"""

from __future__ import annotations

import argparse

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

from tennis_stroke import ParameterError, solve_stroke, stroke_dataset  # noqa: E402

#: Free swing drawn after the ball has left (s).
FOLLOW_THROUGH = 0.05


def label(da) -> str:
    """An axis label from a variable's attributes."""
    return f"{da.attrs['long_name']} ({da.attrs['units']})"


def draw(ds, out: str) -> None:
    """The two panels into ``out``: the whole stroke and the contact (ms around it)."""
    t_c, t_sep = float(ds["t_contact_start"]), float(ds["t_separation"])
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    margin = 2.5 * (t_sep - t_c)
    for ax, span in zip(axes, [(None, None), (t_c - margin, t_sep + margin)], strict=True):
        part = ds.sel(t=slice(*span))
        ax.plot(part["t"], part["speed_hit"], label="racket (hitting point)")
        ax.plot(part["t"], abs(part["vx_ball"]), label="ball")
        ax.axvspan(t_c, t_sep, color="0.85", label="contact")
        ax.set_xlabel(label(ds["t"]))
        ax.set_ylabel(f"speed ({ds['speed_hit'].attrs['units']})")
    axes[0].set_title("the stroke")
    axes[1].set_title("the contact")
    axes[0].legend(loc="upper left")
    fig.suptitle(
        f"theta0 = {ds.attrs['theta0']:g} deg, delta0 = {ds.attrs['delta0']:g} deg: "
        f"{ds['v_out'].long_name} {float(ds['v_out']):.1f} {ds['v_out'].units}"
    )
    fig.savefig(out, dpi=100)
    plt.close(fig)


def setting(text: str) -> tuple[str, float | str]:
    """``NAME=VALUE``: a parameter (a number) or a reading (a word)."""
    name, sep, value = text.partition("=")
    if not sep:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    try:
        return name, float(value)
    except ValueError:
        return name, value


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="stroke_speeds.png", help="PNG to write")
    parser.add_argument("--theta0", type=float, default=120.0, help="theta(0) (degree)")
    parser.add_argument("--delta0", type=float, default=81.5, help="delta(0) (degree)")
    parser.add_argument(
        "--set", type=setting, action="append", default=[], help="NAME=VALUE, a parameter"
    )
    args = parser.parse_args(argv)
    try:
        stroke = solve_stroke(
            args.theta0, args.delta0, dict(args.set), follow_through=FOLLOW_THROUGH
        )
    except ParameterError as err:
        parser.exit(2, f"stroke_speeds: {err}\n")
    if stroke.result["status_name"] != "ok":
        parser.exit(1, f"stroke_speeds: the stroke failed: {stroke.result['status_name']}\n")
    ds = stroke_dataset(stroke)
    ds.attrs.update(theta0=args.theta0, delta0=args.delta0)
    draw(ds, args.out)
    at_start = ds["speed_hit"].sel(t=ds["t_contact_start"])
    print(f"{args.out}: v_out {float(ds['v_out']):.6f} {ds['v_out'].units}")
    print(f"racket speed at the contact start {float(at_start):.6f} {at_start.units}")


if __name__ == "__main__":
    main()
