"""Render bladestab charts with matplotlib.

Usage: the program pipes the package, its modules joined into one script (CMakeLists.txt), to the
interpreter, or from the source tree:

    /usr/bin/python3 scripts/charts <chart-kind> <input.json> <output.png|output.svg> [<input.json> <output> ...]

More than one input and output pair draws each chart in turn in the same interpreter (a script
drawing many charts pays for Python and matplotlib once); the first bad input ends the run.

Modules: chart_common (setup, input checks, labels), chart_campbell, chart_map, chart_transient,
chart_sweep, and this one (dispatch). They import each other by plain name, one line each.

The output format follows the output file's extension (.png or .svg).
On bad input the script prints one line to stderr and exits non-zero.

Chart kinds and the JSON each expects
-------------------------------------
campbell
    {
      "title":         str (optional),
      "speeds_rad_s":  [float, ...]           rotor speeds, ascending, >= 2 values,
      "engine_orders": [int, ...]             optional, e.g. [1, 2, 3],
      "curves": [                             one per tracked mode
        {"mode": int,
         "family": "bending" | "flap" | "edge" | "axial" | "rotation",
         "frequency_hz": [float|null, ...]}   same length as speeds_rad_s
      ],
      "crossings": [                          optional
        {"engine_order": int, "mode": int, "speed_rad_s": float,
         "speed_rpm": float, "frequency_hz": float}
      ]
    }

map
    Stability map (Ince-Strutt style): Floquet max|rho| shading plus the
    rho = -1 / rho = +1 boundary curves.
    {
      "title":   str (optional),
      "x_label": str (optional),              e.g. "pulse frequency θ [rad/s]",
      "y_label": str (optional),              e.g. "F̄_max = F_max / F_cr",
      "grid": {                               optional; empty x means no grid
        "x": [float, ...],                    ascending, >= 2 values,
        "y": [float, ...],                    ascending, >= 2 values,
        "max_abs_multiplier": [[float|null, ...], ...]
                                              one row per y, len(x) values each
      },
      "refinement": {                         optional; drawn instead of the grid
        "cells_x": int, "cells_y": int,       the fine lattice's cells
        "x_lo": float, "x_hi": float, "y_lo": float, "y_hi": float,
        "cells": [[i, j, width, height, float|null], ...]
                                              leaves covering the lattice
      },
      "stable_below": float (optional),       max|rho| at or below: stable (white)
      "curves": [                             optional boundary curves
        {"multiplier": -1 | 1, "mode": int (optional), "order": int (optional),
         "x": [float|null, ...], "y": [float|null, ...]}  same length; null = gap
      ],
      "markers": [                            optional
        {"x": float, "y": float, "label": str (optional)}
      ]
    }
    A PNG map records where its markers landed, as the text chunk
    "bladestab:markers_px" = "x,y;x,y;..." (pixels from the image's top left),
    so a test can read the colour under a marker.

sweep
    Natural frequencies against a scene key (bladestab sweep), one line per
    tracked mode: bending solid, rotation and axial dashed (as Sinha's
    Figs. 7-9). Frequency [Hz] on the left; on the right the frequency
    parameter lambda where it is not proportional to the frequency (the key
    changes EI, e.g. the slenderness: the paper's Figs. 7, 8), else each
    frequency relative to its value at the first point (Fig. 9's drop).
    {
      "title":  str (optional),
      "key":    str                          the x axis label,
      "values": [float, ...]                 >= 2 values, strictly monotonic,
      "modes": [                             one per tracked mode
        {"index": int,
         "family": "bending" | "flap" | "edge" | "axial" | "rotation",
         "families": [str, ...]              optional; the family at each
                                             value (sets each piece's style),
         "frequency_hz": [float, ...],       same length as values, >= 0,
         "lambda": [float, ...]}             optional; same length
      ]
    }

transient
    Time response of the blade tip under rub pulses: 2x2 panels with the tip
    lateral and axial deflection vs revolutions (contact windows, where the
    axial force is negative, shaded), the axial phase plane and the spectrum.
    Lengths are in metres and drawn in mm.
    {
      "title":                  str (optional),
      "revolutions":            [float, ...]  time in revolutions, strictly
                                              ascending, >= 2 values,
      "tip_lateral_m":          [float, ...]  same length as revolutions,
      "tip_axial_m":            [float, ...]  same length,
      "tip_axial_velocity_m_s": [float, ...]  same length,
      "axial_force_n":          [float, ...]  same length, <= 0 (may be all 0),
      "spectrum": {                           optional (null or empty = none)
        "frequency_hz": [float, ...],         ascending, >= 2 values,
        "lateral":      [float, ...],         one-sided amplitudes [m], >= 0,
        "axial":        [float, ...]          same length as frequency_hz
      },
      "dominant": {"lateral_hz": float, "axial_hz": float}
                                              optional; peaks marked on the
                                              spectrum (either key optional),
      "modes_hz": [float, ...]                optional; reference lines on the
                                              spectrum
    }
    The spectrum's log axis spans at most SPECTRUM_DECADES below its peak.
"""

import json
import os
import sys

from chart_common import DPI, FIGSIZE, FIGSIZES, OUTPUT_FORMATS, InputError  # first: it chooses the backend
import matplotlib.pyplot as plt  # noqa: E402

from chart_campbell import chart_campbell
from chart_map import chart_map
from chart_sweep import chart_sweep
from chart_transient import chart_transient

CHARTS = {
    "campbell": chart_campbell,
    "map": chart_map,
    "sweep": chart_sweep,
    "transient": chart_transient,
}


def _marker_pixels(fig, ax, points):
    """Data points as PNG pixels at the saved resolution: "x,y;x,y", from the
    image's top left (matplotlib's display coordinates start bottom left)."""
    scale = DPI / fig.dpi
    height = fig.get_figheight() * DPI
    pixels = []
    for x, y in points:
        px, py = ax.transData.transform((x, y))
        pixels.append(f"{px * scale:.1f},{height - py * scale:.1f}")
    return ";".join(pixels)


def render(kind, input_path, output_path):
    if kind not in CHARTS:
        raise InputError(f"unknown chart kind '{kind}'"
                         f" (known: {', '.join(sorted(CHARTS))})")
    fmt = OUTPUT_FORMATS.get(os.path.splitext(output_path)[1].lower())
    if fmt is None:
        raise InputError(f"output '{output_path}' must end in .png or .svg")
    try:
        with open(input_path, encoding="utf-8") as fh:
            data = json.load(fh)
    except OSError as exc:
        raise InputError(f"cannot read '{input_path}': {exc.strerror or exc}") from exc
    except ValueError as exc:
        raise InputError(f"invalid JSON in '{input_path}': {exc}") from exc
    if not isinstance(data, dict):
        raise InputError("top-level JSON value must be an object")

    plt.rcParams["svg.hashsalt"] = "bladestab"  # reproducible SVG ids
    fig, ax = plt.subplots(figsize=FIGSIZES.get(kind, FIGSIZE))
    try:
        CHARTS[kind](data, ax)
        fig.tight_layout()
        metadata = {"Date": None} if fmt == "svg" else {}
        points = getattr(ax, "bladestab_markers", [])
        if fmt == "png" and points:
            metadata["bladestab:markers_px"] = _marker_pixels(fig, ax, points)
        try:
            fig.savefig(output_path, format=fmt, dpi=DPI, metadata=metadata)
        except OSError as exc:
            raise InputError(f"cannot write '{output_path}': {exc.strerror or exc}") from exc
    finally:
        plt.close(fig)


def main(argv):
    if len(argv) < 3 or len(argv) % 2 == 0:
        print("usage: charts <chart-kind> <input.json> <output.png|.svg>"
              " [<input.json> <output> ...]", file=sys.stderr)
        return 2
    try:
        for input_path, output_path in zip(argv[1::2], argv[2::2]):
            render(argv[0], input_path, output_path)
    except InputError as exc:
        print(f"charts: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
