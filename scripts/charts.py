"""Render bladestab charts with matplotlib.

Usage (the C++ side pipes this file to the interpreter):

    /usr/bin/python3 - <chart-kind> <input.json> <output.png|output.svg>

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
         "family": "bending" | "axial" | "rotation",
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
         "family": "bending" | "axial" | "rotation",
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
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402  (ships with matplotlib)
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from matplotlib.colors import ListedColormap, Normalize  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)
FIGSIZE = (8.0, 5.5)
FIGSIZES = {"transient": (10.0, 7.0), "sweep": (11.0, 5.0)}  # kinds that need another size
DPI = 150
OUTPUT_FORMATS = {".png": "png", ".svg": "svg"}


class InputError(Exception):
    """Raised for malformed chart input; reported as a one-line message."""


# --------------------------------------------------------------------------
# Small validation helpers
# --------------------------------------------------------------------------

def _require(data, key, kind):
    if key not in data:
        raise InputError(f"missing key '{key}'")
    value = data[key]
    if not isinstance(value, kind):
        raise InputError(f"'{key}' has the wrong type")
    return value


def _optional_list(data, key):
    value = data.get(key, [])
    if not isinstance(value, list):
        raise InputError(f"'{key}' is not a list")
    return value


def _number(value, what, allow_null=False):
    if value is None and allow_null:
        return math.nan
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{what} is not a number")
    value = float(value)
    if not allow_null and not math.isfinite(value):
        raise InputError(f"{what} is not finite")
    return value


def _numbers(values, what, allow_null=False):
    if not isinstance(values, list):
        raise InputError(f"{what} is not a list")
    return [_number(v, f"{what}[{i}]", allow_null) for i, v in enumerate(values)]


def _integer(value, what):
    if isinstance(value, bool) or not isinstance(value, int):
        raise InputError(f"{what} is not an integer")
    return value


# --------------------------------------------------------------------------
# Campbell diagram
# --------------------------------------------------------------------------

# family -> (label prefix, colormap, linestyle)
CAMPBELL_FAMILIES = {
    "bending": ("B", "Blues", "-"),
    "axial": ("A", "Reds", "--"),
    "rotation": ("R", "Greens", ":"),
}


def _campbell_curves(data, n_speeds):
    """Validate curves; return them sorted with family labels (B1, A1, ...)."""
    curves = []
    for i, curve in enumerate(_require(data, "curves", list)):
        if not isinstance(curve, dict):
            raise InputError(f"curves[{i}] is not an object")
        family = curve.get("family")
        if family not in CAMPBELL_FAMILIES:
            raise InputError(f"curves[{i}] has unknown family {family!r}")
        mode = _integer(curve.get("mode"), f"curves[{i}].mode")
        freqs = _numbers(curve.get("frequency_hz"),
                         f"curves[{i}].frequency_hz", allow_null=True)
        if len(freqs) != n_speeds:
            raise InputError(f"curves[{i}].frequency_hz has {len(freqs)} values,"
                             f" expected {n_speeds}")
        curves.append({"mode": mode, "family": family, "freqs": freqs})

    return _label_by_family(curves, "mode", darkest=0.9, spread=0.35)


def _label_by_family(items, order_key, darkest, spread):
    """Labels ("B1", "B2", … per family) and colours (shades of the family's
    colour map, from `darkest` down by up to `spread`), in `order_key` order."""
    by_family = {}
    for item in sorted(items, key=lambda c: c[order_key]):
        by_family.setdefault(item["family"], []).append(item)
    for family, members in by_family.items():
        prefix, cmap_name, _ = CAMPBELL_FAMILIES[family]
        cmap = matplotlib.colormaps[cmap_name]
        for n, item in enumerate(members):
            shade = darkest - spread * n / max(len(members) - 1, 1)
            item["label"] = f"{prefix}{n + 1}"
            item["color"] = cmap(shade if len(members) > 1 else 0.75)
    return sorted(items, key=lambda c: c[order_key])


def _campbell_crossings(data):
    crossings = []
    for i, cross in enumerate(_optional_list(data, "crossings")):
        if not isinstance(cross, dict):
            raise InputError(f"crossings[{i}] is not an object")
        order = _integer(cross.get("engine_order"), f"crossings[{i}].engine_order")
        mode = _integer(cross.get("mode"), f"crossings[{i}].mode")
        speed = _number(cross.get("speed_rad_s"), f"crossings[{i}].speed_rad_s")
        freq = _number(cross.get("frequency_hz"), f"crossings[{i}].frequency_hz")
        rpm = cross.get("speed_rpm")
        rpm = speed * RAD_S_TO_RPM if rpm is None else \
            _number(rpm, f"crossings[{i}].speed_rpm")
        crossings.append({"order": order, "mode": mode, "rpm": rpm, "freq": freq})
    return crossings


# (dx, dy, ha, va) offsets in points tried in turn for a point annotation.
LABEL_OFFSETS = [(6, -4, "left", "top"), (-6, 4, "right", "bottom"),
                 (6, 4, "left", "bottom"), (-6, -4, "right", "top"),
                 (6, -22, "left", "top"), (-6, 22, "right", "bottom")]


def _place_label(ax, text, xy):
    """Annotate xy lightly, choosing an offset that stays inside the axes and
    clear of labels already placed (falls back to the first offset)."""
    renderer = ax.figure.canvas.get_renderer()
    inside = ax.get_window_extent(renderer)
    placed = [t.get_window_extent(renderer) for t in ax.texts
              if getattr(t, "_bladestab_label", False)]

    def annotate(dx, dy, ha, va):
        return ax.annotate(text, xy=xy, xytext=(dx, dy),
                           textcoords="offset points", ha=ha, va=va,
                           fontsize=7, color="0.25", zorder=5)

    for offset in LABEL_OFFSETS:
        label = annotate(*offset)
        box = label.get_window_extent(renderer)
        fits = (box.x0 >= inside.x0 and box.x1 <= inside.x1
                and box.y0 >= inside.y0 and box.y1 <= inside.y1)
        if fits and not any(box.overlaps(other) for other in placed):
            break
        label.remove()
    else:
        label = annotate(*LABEL_OFFSETS[0])
    label._bladestab_label = True


def chart_campbell(data, ax):
    """Campbell diagram: modal frequencies and engine orders vs rotor speed."""
    speeds = _numbers(_require(data, "speeds_rad_s", list), "speeds_rad_s")
    if len(speeds) < 2:
        raise InputError("speeds_rad_s needs at least two values")
    if any(b < a for a, b in zip(speeds, speeds[1:])) or speeds[0] < 0:
        raise InputError("speeds_rad_s must be non-negative and ascending")
    orders = [_integer(k, f"engine_orders[{i}]")
              for i, k in enumerate(_optional_list(data, "engine_orders"))]
    curves = _campbell_curves(data, len(speeds))
    crossings = _campbell_crossings(data)

    rpm = [w * RAD_S_TO_RPM for w in speeds]
    rpm_max = rpm[-1]
    if rpm_max <= rpm[0]:
        raise InputError("speeds_rad_s spans no range")

    # Axis limits: a little headroom above the highest EO line / mode curve.
    eo_top = max((k * speeds[-1] / (2.0 * math.pi) for k in orders), default=0.0)
    curve_top = max((f for c in curves for f in c["freqs"] if math.isfinite(f)),
                    default=0.0)
    f_top = max(eo_top, curve_top)
    if f_top <= 0.0:
        f_top = 1.0
    ax.set_xlim(rpm[0], rpm_max)
    ax.set_ylim(0.0, 1.08 * f_top)

    # Engine-order lines f = k * Omega / 2pi, labelled along their right end.
    for k in orders:
        f_end = k * speeds[-1] / (2.0 * math.pi)
        ax.plot([rpm[0], rpm_max], [k * speeds[0] / (2.0 * math.pi), f_end],
                color="0.55", linewidth=0.8, zorder=1)
        x_lab = rpm[0] + 0.97 * (rpm_max - rpm[0])
        y_lab = k * x_lab / RAD_S_TO_RPM / (2.0 * math.pi)
        slope_deg = math.degrees(math.atan2(f_end, rpm_max))
        ax.text(x_lab, y_lab, f"{k}EO", color="0.35", fontsize=8,
                ha="right", va="bottom", rotation=slope_deg,
                rotation_mode="anchor", transform_rotates_text=True, zorder=4,
                bbox=dict(boxstyle="square,pad=0.1", facecolor="white",
                          edgecolor="none", alpha=0.75))
    if orders:
        ax.plot([], [], color="0.55", linewidth=0.8, label="engine orders")

    # Mode curves.
    labels = {}
    for curve in curves:
        _, _, style = CAMPBELL_FAMILIES[curve["family"]]
        ax.plot(rpm, curve["freqs"], linestyle=style, color=curve["color"],
                linewidth=1.8, label=curve["label"], zorder=3)
        # Points with no tracked neighbour would be invisible as a line.
        isolated = [i for i, f in enumerate(curve["freqs"]) if math.isfinite(f)
                    and not any(0 <= j < len(rpm)
                                and math.isfinite(curve["freqs"][j])
                                for j in (i - 1, i + 1))]
        ax.plot([rpm[i] for i in isolated],
                [curve["freqs"][i] for i in isolated],
                linestyle="none", marker=".", color=curve["color"], zorder=3)
        labels[curve["mode"]] = curve["label"]

    # Crossings: markers, annotated when there are few enough to stay legible.
    if crossings:
        ax.plot([c["rpm"] for c in crossings], [c["freq"] for c in crossings],
                linestyle="none", marker="o", markersize=6,
                markerfacecolor="white", markeredgecolor="black",
                markeredgewidth=1.2, label="crossings", zorder=4)

    ax.set_xlabel("Rotor speed [rpm]")
    ax.set_ylabel("Frequency [Hz]")
    ax.set_title(str(data.get("title") or "Campbell diagram"))
    top = ax.secondary_xaxis("top", functions=(lambda x: x / RAD_S_TO_RPM,
                                               lambda w: w * RAD_S_TO_RPM))
    top.set_xlabel("Rotor speed [rad/s]")
    ax.grid(True, which="major", color="0.88", linewidth=0.6)
    ax.set_axisbelow(True)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              fontsize=8, frameon=False)

    # Annotate crossings last, once the layout is final enough to measure.
    if len(crossings) <= 12:
        ax.figure.tight_layout()  # settle the layout before measuring labels
        for c in sorted(crossings, key=lambda c: (c["rpm"], c["freq"])):
            mode_label = labels.get(c["mode"], f"M{c['mode']}")
            _place_label(ax, f"{c['order']}EO×{mode_label}\n{c['rpm']:.0f} rpm",
                         (c["rpm"], c["freq"]))

# --------------------------------------------------------------------------
# Stability map (Ince-Strutt style)
# --------------------------------------------------------------------------

STABLE_LIMIT = 1.0 + 1e-9     # default: max|rho| at or below this counts as stable ("stable_below" overrides)
MAP_SHADE_MIN = 0.05          # smallest upper end of the log10 max|rho| scale
MAP_SHADE_PERCENTILE = 98.0   # upper end: this percentile of unstable cells
# multiplier -> (legend label, colour, linestyle)
MAP_FAMILIES = {
    -1: ("boundary ρ = −1", "#0b2f7a", "-"),
    1: ("boundary ρ = +1", "#0a5c1e", "--"),
}
MAP_NOTE = ("shading: Floquet max|ρ| (shows combination resonances too);"
            " lines: ±1 boundary equations")


def _ascending(values, what):
    if len(values) < 2:
        raise InputError(f"{what} needs at least two values")
    if any(b <= a for a, b in zip(values, values[1:])):
        raise InputError(f"{what} must be strictly ascending")
    return values


def _map_grid(data):
    """Validate the grid; return (x, y, values[ny][nx]) or None if absent."""
    grid = data.get("grid")
    if grid is None:
        return None
    if not isinstance(grid, dict):
        raise InputError("'grid' is not an object")
    for key in ("x", "y", "max_abs_multiplier"):
        if key not in grid:
            raise InputError(f"missing key 'grid.{key}'")
    x = _numbers(grid["x"], "grid.x")
    if not x:
        return None
    x = _ascending(x, "grid.x")
    y = _ascending(_numbers(grid["y"], "grid.y"), "grid.y")
    rows = grid["max_abs_multiplier"]
    if not isinstance(rows, list):
        raise InputError("grid.max_abs_multiplier is not a list")
    if len(rows) != len(y):
        raise InputError(f"grid.max_abs_multiplier has {len(rows)} rows,"
                         f" expected {len(y)} (one per grid.y)")
    values = []
    for j, row in enumerate(rows):
        row = _numbers(row, f"grid.max_abs_multiplier[{j}]", allow_null=True)
        if len(row) != len(x):
            raise InputError(f"grid.max_abs_multiplier[{j}] has {len(row)}"
                             f" values, expected {len(x)} (one per grid.x)")
        for i, v in enumerate(row):
            if v < 0.0:
                raise InputError(f"grid.max_abs_multiplier[{j}][{i}] = {v:g}"
                                 " is negative")
        values.append(row)
    return x, y, values


def _map_curves(data):
    curves = []
    for i, curve in enumerate(_optional_list(data, "curves")):
        if not isinstance(curve, dict):
            raise InputError(f"curves[{i}] is not an object")
        if "multiplier" not in curve:
            raise InputError(f"curves[{i}] is missing key 'multiplier'")
        multiplier = _number(curve["multiplier"], f"curves[{i}].multiplier")
        if multiplier not in (-1.0, 1.0):
            raise InputError(f"curves[{i}].multiplier = {multiplier:g},"
                             " expected -1 or 1")
        for key in ("mode", "order"):
            if curve.get(key) is not None:
                _integer(curve[key], f"curves[{i}].{key}")
        for key in ("x", "y"):
            if key not in curve:
                raise InputError(f"curves[{i}] is missing key '{key}'")
        xs = _numbers(curve["x"], f"curves[{i}].x", allow_null=True)
        ys = _numbers(curve["y"], f"curves[{i}].y", allow_null=True)
        if len(xs) != len(ys):
            raise InputError(f"curves[{i}] has {len(xs)} x values"
                             f" but {len(ys)} y values")
        # A null in either coordinate breaks the line there.
        points = [(a, b) if math.isfinite(a) and math.isfinite(b)
                  else (math.nan, math.nan) for a, b in zip(xs, ys)]
        curves.append({"multiplier": int(multiplier),
                       "mode": int(curve["mode"]) if curve.get("mode") is not None else None,
                       "order": int(curve["order"]) if curve.get("order") is not None else None,
                       "x": [p[0] for p in points], "y": [p[1] for p in points]})
    return curves


SUBSCRIPT_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
MAX_REGION_LABELS = 16


def _region_label(mode, order):
    """The region a boundary curve belongs to, as the resonance that opens it:
    "2ω₁/2" for mode 1, order 2 (θ ≈ 2ω₁/2); "2ω₁" for order 1; "ω₁ buckling"
    for order 0 (the +1 family's static divergence under the mean load)."""
    omega = "ω" + str(mode).translate(SUBSCRIPT_DIGITS)
    if order == 0:
        return f"{omega} buckling"
    return f"2{omega}" if order == 1 else f"2{omega}/{order}"


def _label_regions(ax, curves):
    """One label per (family, mode, order), at the curve's lowest point (a
    region's tip), when there are few enough to stay legible."""
    tips = {}
    for curve in curves:
        if curve["mode"] is None or curve["order"] is None:
            continue
        points = [(y, x) for x, y in zip(curve["x"], curve["y"])
                  if math.isfinite(x) and math.isfinite(y)]
        if not points:
            continue
        key = (curve["multiplier"], curve["mode"], curve["order"])
        tip = min(points)
        if key not in tips or tip < tips[key]:
            tips[key] = tip
    if not tips or len(tips) > MAX_REGION_LABELS:
        return
    x_lo, x_hi = ax.get_xlim()
    y_lo, y_hi = ax.get_ylim()
    for (multiplier, mode, order), (y, x) in sorted(tips.items()):
        if not (x_lo <= x <= x_hi and y_lo <= y <= y_hi):
            continue
        _annotate_point(ax, _region_label(mode, order), x, y, above=True,
                        color=MAP_FAMILIES[multiplier][1])


def _annotate_point(ax, text, x, y, above, **style):
    """A small label on a white box beside (x, y): above or below it, and to
    its left near the plot's right edge so that it stays inside."""
    x_lo, x_hi = ax.get_xlim()
    right = x > x_lo + 0.85 * (x_hi - x_lo)
    ax.annotate(text, xy=(x, y),
                xytext=(-3 if right else 3, 2 if above else -2), textcoords="offset points",
                ha="right" if right else "left", va="bottom" if above else "top",
                fontsize=7, zorder=5,
                bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.75),
                annotation_clip=True, **style)


def _combination_label(region):
    """ "ω₁+ω₂" for a sum combination of order 1, "(ω₁+ω₂)/2" of order 2,
    "ω₂−ω₁" / "(ω₂−ω₁)/3" for a difference combination."""
    i = "ω" + str(region["mode_i"]).translate(SUBSCRIPT_DIGITS)
    j = "ω" + str(region["mode_j"]).translate(SUBSCRIPT_DIGITS)
    pair = f"{i}+{j}" if region["kind"] == "sum" else f"{j}−{i}"
    return pair if region["order"] == 1 else f"({pair})/{region['order']}"


def _label_combinations(ax, data):
    """Each combination region named in the JSON, at its sample of largest
    max|rho|, in italic dark grey."""
    regions = _optional_list(data, "combination_regions")
    for k, region in enumerate(regions):
        if not isinstance(region, dict):
            raise InputError(f"combination_regions[{k}] is not an object")
        for key in ("mode_i", "mode_j", "order"):
            _integer(_require(region, key, int), f"combination_regions[{k}].{key}")
        if region.get("kind") not in ("sum", "difference"):
            raise InputError(f"combination_regions[{k}].kind is not 'sum' or 'difference'")
        _number(region.get("x"), f"combination_regions[{k}].x")
        _number(region.get("y"), f"combination_regions[{k}].y")
    if len(regions) > MAX_REGION_LABELS:
        return
    for region in regions:
        _annotate_point(ax, _combination_label(region), region["x"], region["y"],
                        above=False, color="0.15", style="italic")


def _map_markers(data):
    markers = []
    for i, marker in enumerate(_optional_list(data, "markers")):
        if not isinstance(marker, dict):
            raise InputError(f"markers[{i}] is not an object")
        x = _number(marker.get("x"), f"markers[{i}].x")
        y = _number(marker.get("y"), f"markers[{i}].y")
        label = marker.get("label")
        if label is not None and not isinstance(label, str):
            raise InputError(f"markers[{i}].label is not a string")
        markers.append({"x": x, "y": y, "label": label or ""})
    return markers


def _map_refined(data):
    """The refined shading as cell edges and a raster; None if absent."""
    ref = data.get("refinement")
    if ref is None:
        return None
    if not isinstance(ref, dict):
        raise InputError("'refinement' is not an object")
    nx = _integer(_require(ref, "cells_x", int), "refinement.cells_x")
    ny = _integer(_require(ref, "cells_y", int), "refinement.cells_y")
    if not (1 <= nx <= 20000 and 1 <= ny <= 20000):
        raise InputError(f"refinement: {nx} x {ny} cells is outside 1..20000")
    bounds = [_number(_require(ref, k, (int, float)), f"refinement.{k}")
              for k in ("x_lo", "x_hi", "y_lo", "y_hi")]
    if not (bounds[0] < bounds[1] and bounds[2] < bounds[3]):
        raise InputError("refinement: x_lo < x_hi and y_lo < y_hi are required")
    raster = np.full((ny, nx), np.nan)
    for k, cell in enumerate(_require(ref, "cells", list)):
        if not isinstance(cell, list) or len(cell) != 5:
            raise InputError(f"refinement.cells[{k}] is not [i, j, width, height, value]")
        i, j, w, h = (_integer(v, f"refinement.cells[{k}]") for v in cell[:4])
        v = _number(cell[4], f"refinement.cells[{k}][4]", allow_null=True)
        if i < 0 or j < 0 or w < 1 or h < 1 or i + w > nx or j + h > ny:
            raise InputError(f"refinement.cells[{k}] lies outside the {nx} x {ny} lattice")
        raster[j:j + h, i:i + w] = np.nan if v is None else v
    x = np.linspace(bounds[0], bounds[1], nx + 1)
    y = np.linspace(bounds[2], bounds[3], ny + 1)
    return x, y, raster


def _map_contour(ax, refined, stable_below, handles):
    """The max|rho| = stable_below contour of the refined shading (its
    lattice's cell centres): the edge of every instability, the combination
    resonances' too, which have no traced +-1 curve."""
    if refined is None:
        return
    x_edges, y_edges, raster = refined
    with np.errstate(divide="ignore", invalid="ignore"):
        level_of = np.log10(raster)
    level = math.log10(stable_below)
    finite = level_of[np.isfinite(level_of)]
    if finite.size == 0 or not (finite.min() <= level < finite.max()):
        return
    xc = 0.5 * (x_edges[:-1] + x_edges[1:])
    yc = 0.5 * (y_edges[:-1] + y_edges[1:])
    ax.contour(xc, yc, level_of, levels=[level], colors="0.15", linewidths=0.6,
               linestyles=":", zorder=2.5)
    handles.append(Line2D([], [], color="0.15", linestyle=":", linewidth=0.8,
                          label=f"max|ρ| = {stable_below:.6g} (combination resonances too)"))


def _map_shading(ax, grid, stable_below=STABLE_LIMIT, edges=False):
    """Shade growth per period, log10 max|rho|, with its lower end at the
    stability threshold: every unstable cell is clearly coloured, stable ones
    are white. `grid` holds cell centres, or cell edges if `edges`."""
    x, y, values = grid
    rho = np.array(values, dtype=float)
    missing = np.isnan(rho)
    unstable = ~missing & (rho > stable_below)
    floor = math.log10(stable_below)
    with np.errstate(divide="ignore", invalid="ignore"):
        level = np.log10(np.where(unstable, rho, 1.0))
    finite = level[unstable & np.isfinite(level)]
    top = floor + MAP_SHADE_MIN
    if finite.size:
        top = max(float(np.percentile(finite, MAP_SHADE_PERCENTILE)), top)
    # Stable cells fall below the scale ("under" = white), divergent ones
    # (inf) above it; missing cells are "bad" (light grey).
    level = np.where(unstable, np.minimum(level, 2.0 * top + 1.0), floor - 1.0)
    level = np.ma.masked_array(level, mask=missing)

    base = matplotlib.colormaps["OrRd"]
    cmap = ListedColormap(base(np.linspace(0.45, 0.97, 256)), name="bladestab_map")
    cmap.set_under("white")
    cmap.set_bad("0.82")
    mesh = ax.pcolormesh(x, y, level, shading="flat" if edges else "nearest",
                         cmap=cmap, norm=Normalize(vmin=floor, vmax=top),
                         rasterized=rho.size > 1000, zorder=0)
    above = bool((level.filled(floor - 1.0) > top).any())
    cbar = ax.figure.colorbar(mesh, ax=ax, extend="max" if above else "neither",
                              pad=0.02, fraction=0.05)
    cbar.set_label(f"log10 max|ρ| (growth per period); white: max|ρ| ≤ {stable_below:.6g}")
    cbar.ax.tick_params(labelsize=8)

    handles = [Patch(facecolor=cmap(0.0), edgecolor="none",
                     label=f"unstable (max|ρ| > {stable_below:.6g})")]
    if missing.any():
        handles.append(Patch(facecolor="0.82", edgecolor="none", label="no data"))
    return handles


def _cell_edges(values):
    """Outer edges of nearest-shaded cells centred on ascending values."""
    return (values[0] - 0.5 * (values[1] - values[0]),
            values[-1] + 0.5 * (values[-1] - values[-2]))


# Combining accents matplotlib cannot stack on the previous glyph itself.
COMBINING_ACCENTS = {"\u0304": "bar", "\u0302": "hat", "\u0307": "dot",
                     "\u0303": "tilde"}
ACCENTED = re.compile("([A-Za-z0-9])([" + "".join(COMBINING_ACCENTS) + "])")


def _display_text(text):
    """Draw e.g. "F̄" (F + combining macron) as upright mathtext; matplotlib's
    plain text layout would drop the accent."""
    if not ACCENTED.search(text):
        return text
    text = text.replace("$", r"\$")
    return ACCENTED.sub(lambda m: f"$\\{COMBINING_ACCENTS[m.group(2)]}"
                        f"{{\\mathrm{{{m.group(1)}}}}}$", text)


def chart_map(data, ax):
    """Stability map: Floquet max|rho| shading with the +-1 boundary curves."""
    grid = _map_grid(data)
    curves = _map_curves(data)
    markers = _map_markers(data)
    for key in ("title", "x_label", "y_label"):
        if data.get(key) is not None and not isinstance(data[key], str):
            raise InputError(f"'{key}' is not a string")

    # Axis extent: the grid's cells, else the curves'; y always from 0.
    if grid is not None:
        x_lo, x_hi = _cell_edges(grid[0])
        if grid[0][0] >= 0.0:
            x_lo = max(x_lo, 0.0)  # speeds and frequencies are not negative
        y_hi = _cell_edges(grid[1])[1]
    else:
        xs = [v for c in curves for v in c["x"] if math.isfinite(v)]
        ys = [v for c in curves for v in c["y"] if math.isfinite(v)]
        xs += [m["x"] for m in markers]
        ys += [m["y"] for m in markers]
        if not xs:
            raise InputError("nothing to draw: no grid, curves or markers")
        x_lo, x_hi = min(xs), max(xs)
        y_hi = 1.05 * max(max(ys), 0.0)
        if x_hi <= x_lo:
            pad = 0.05 * abs(x_lo) or 1.0
            x_lo, x_hi = x_lo - pad, x_hi + pad
        if y_hi <= 0.0:
            y_hi = 1.0
    ax.set_xlim(x_lo, x_hi)
    ax.set_ylim(0.0, y_hi)

    stable_below = _number(data.get("stable_below", STABLE_LIMIT), "stable_below")
    if not stable_below >= 1.0:
        raise InputError(f"stable_below = {stable_below:g}: must be >= 1")
    refined = _map_refined(data)
    if refined is not None:
        handles = _map_shading(ax, refined, stable_below, edges=True)
    elif grid is not None:
        handles = _map_shading(ax, grid, stable_below)
    else:
        handles = []

    _map_contour(ax, refined, stable_below, handles)

    # Boundary curves, one legend entry per multiplier family.
    legend_lines = {}
    for curve in curves:
        label, color, style = MAP_FAMILIES[curve["multiplier"]]
        (line,) = ax.plot(curve["x"], curve["y"], color=color, linestyle=style,
                          linewidth=1.6, zorder=3)
        legend_lines.setdefault(curve["multiplier"], line)
        # Points with no neighbour would be invisible as a line.
        cx, cy = curve["x"], curve["y"]
        isolated = [i for i in range(len(cx)) if math.isfinite(cx[i])
                    and not any(0 <= j < len(cx) and math.isfinite(cx[j])
                                for j in (i - 1, i + 1))]
        ax.plot([cx[i] for i in isolated], [cy[i] for i in isolated],
                linestyle="none", marker=".", color=color, zorder=3)
    _label_regions(ax, curves)
    _label_combinations(ax, data)
    for multiplier in sorted(legend_lines):
        line = legend_lines[multiplier]
        handles.append(Line2D(
            [], [], color=line.get_color(), linestyle=line.get_linestyle(),
            linewidth=line.get_linewidth(), label=MAP_FAMILIES[multiplier][0]))

    ax.bladestab_markers = [(m["x"], m["y"]) for m in markers]
    if markers:
        ax.plot([m["x"] for m in markers], [m["y"] for m in markers],
                linestyle="none", marker="x", markersize=7, color="black",
                markeredgewidth=1.6, zorder=4, clip_on=False)

    ax.set_xlabel(_display_text(data.get("x_label") or "x"))
    ax.set_ylabel(_display_text(data.get("y_label") or "y"))
    ax.set_title(_display_text(data.get("title") or "Stability map"))
    # Grid lines over the shading (zorder 0) and under the curves (zorder 3).
    ax.grid(True, which="major", color="0.88", linewidth=0.6, alpha=0.7)
    ax.set_axisbelow(False)

    anchor = ax.xaxis.label
    if handles:
        anchor = ax.legend(handles=handles, loc="upper center",
                           bbox_to_anchor=(0.5, -0.13), ncol=len(handles) if len(handles) <= 3 else 2,
                           fontsize=8, frameon=False, borderaxespad=0.0)
    ax.annotate(MAP_NOTE, xy=(0.5, 0.0), xycoords=anchor, xytext=(0, -4),
                textcoords="offset points", ha="center", va="top",
                fontsize=7, color="0.45", annotation_clip=False)

    labelled = [m for m in markers if m["label"]]
    if labelled and len(labelled) <= 12:
        ax.figure.tight_layout()  # settle the layout before measuring labels
        for m in labelled:
            _place_label(ax, _display_text(m["label"]), (m["x"], m["y"]))


# --------------------------------------------------------------------------
# Transient response (tip under rub pulses)
# --------------------------------------------------------------------------

TRANSIENT_SERIES = ("tip_lateral_m", "tip_axial_m", "tip_axial_velocity_m_s",
                    "axial_force_n")
LATERAL_COLOR = "#1f4e9c"
AXIAL_COLOR = "#b8322a"
CONTACT_COLOR = "#f0a030"
SPECTRUM_DECADES = 6.0        # log axis floor: this many decades below the peak
RASTERIZE_POINTS = 20000      # longer time series are rasterized (SVG size)
DENSE_CHUNK = 500             # phase-plane orbit drawn in chunks of this many


def _array(values, what):
    """Validate a list of finite numbers quickly; return a float array."""
    if not isinstance(values, list):
        raise InputError(f"{what} is not a list")
    if not all(type(v) is float or type(v) is int for v in values):
        _numbers(values, what)  # raises, naming the offending entry
    try:
        array = np.array(values, dtype=float)
    except OverflowError as exc:
        raise InputError(f"{what} has a value out of range") from exc
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise InputError(f"{what}[{bad[0]}] is not finite")
    return array


def _transient_series(data):
    """Validate the time series; return (revolutions, {key: array})."""
    rev = _array(_require(data, "revolutions", list), "revolutions")
    if rev.size < 2:
        raise InputError("revolutions needs at least two values")
    if np.any(np.diff(rev) <= 0.0):
        raise InputError("revolutions must be strictly ascending")
    series = {}
    for key in TRANSIENT_SERIES:
        values = _array(_require(data, key, list), key)
        if values.size != rev.size:
            raise InputError(f"'{key}' has {values.size} values,"
                             f" expected {rev.size} (one per revolutions value)")
        series[key] = values
    positive = np.flatnonzero(series["axial_force_n"] > 0.0)
    if positive.size:
        i = positive[0]
        raise InputError(f"axial_force_n[{i}] = {series['axial_force_n'][i]:g}"
                         " is positive (the rub force is <= 0)")
    return rev, series


def _transient_spectrum(data):
    """Validate the spectrum; return (freq, lateral, axial) or None."""
    spectrum = data.get("spectrum")
    if spectrum is None:
        return None
    if not isinstance(spectrum, dict):
        raise InputError("'spectrum' is not an object")
    for key in ("frequency_hz", "lateral", "axial"):
        if key not in spectrum:
            raise InputError(f"missing key 'spectrum.{key}'")
    freq = _array(spectrum["frequency_hz"], "spectrum.frequency_hz")
    if freq.size == 0:
        return None
    if freq.size < 2:
        raise InputError("spectrum.frequency_hz needs at least two values")
    if np.any(np.diff(freq) <= 0.0) or freq[0] < 0.0:
        raise InputError("spectrum.frequency_hz must be non-negative"
                         " and strictly ascending")
    amplitudes = []
    for key in ("lateral", "axial"):
        amp = _array(spectrum[key], f"spectrum.{key}")
        if amp.size != freq.size:
            raise InputError(f"spectrum.{key} has {amp.size} values,"
                             f" expected {freq.size} (one per frequency_hz)")
        negative = np.flatnonzero(amp < 0.0)
        if negative.size:
            i = negative[0]
            raise InputError(f"spectrum.{key}[{i}] = {amp[i]:g} is negative")
        amplitudes.append(amp)
    return freq, amplitudes[0], amplitudes[1]


def _transient_references(data):
    """Validate dominant and modes_hz; return ({family: Hz}, [Hz, ...])."""
    dominant = data.get("dominant")
    peaks = {}
    if dominant is not None:
        if not isinstance(dominant, dict):
            raise InputError("'dominant' is not an object")
        for family in ("lateral", "axial"):
            value = dominant.get(f"{family}_hz")
            if value is not None:
                value = _number(value, f"dominant.{family}_hz")
                if value < 0.0:
                    raise InputError(f"dominant.{family}_hz = {value:g}"
                                     " is negative")
                peaks[family] = value
    modes = data.get("modes_hz")
    modes = [] if modes is None else _numbers(modes, "modes_hz")
    return peaks, modes


def _contact_windows(ax, rev, force):
    """Shade where force < 0 as one collection of rectangles spanning the
    axes height. A window runs half a sample beyond its first and last
    contact samples (the pulse edges lie between samples), and an edge line
    keeps windows narrower than a pixel visible. Returns whether any."""
    contact = force < 0.0
    if not contact.any():
        return False
    edges = np.diff(np.concatenate(([0], contact.astype(np.int8), [0])))
    first = np.flatnonzero(edges == 1)
    last = np.flatnonzero(edges == -1) - 1
    mid = 0.5 * (rev[1:] + rev[:-1])
    x0 = np.where(first > 0, mid[np.maximum(first - 1, 0)], rev[0])
    x1 = np.where(last < rev.size - 1, mid[np.minimum(last, mid.size - 1)],
                  rev[-1])
    boxes = np.stack([np.column_stack([x0, np.zeros_like(x0)]),
                      np.column_stack([x0, np.ones_like(x0)]),
                      np.column_stack([x1, np.ones_like(x1)]),
                      np.column_stack([x1, np.zeros_like(x1)])], axis=1)
    ax.add_collection(PolyCollection(
        boxes, transform=ax.get_xaxis_transform(), facecolors=CONTACT_COLOR,
        edgecolors=CONTACT_COLOR, linewidths=0.4, alpha=0.22, zorder=0,
        rasterized=len(boxes) > 2000), autolim=False)
    return True


def _dense_line(ax, x, y, color, linewidth, **kwargs):
    """Plot a long line that path simplification cannot thin (a phase-plane
    orbit) in chunks sharing their end points: Agg fills many short paths far
    faster than one long self-crossing one."""
    if x.size <= DENSE_CHUNK:
        ax.plot(x, y, color=color, linewidth=linewidth, **kwargs)
        return
    points = np.column_stack((x, y))
    chunks = [points[i:i + DENSE_CHUNK + 1]
              for i in range(0, points.shape[0] - 1, DENSE_CHUNK)]
    ax.add_collection(LineCollection(chunks, colors=[color],
                                     linewidths=linewidth, **kwargs))
    ax.autoscale_view()


def _spectrum_panel(ax, spectrum, peaks, modes):
    ax.set_title("(d) spectrum", fontsize=10)
    ax.set_xlabel("Frequency [Hz]")
    ax.set_ylabel("Amplitude [mm]")
    if spectrum is None:
        ax.text(0.5, 0.5, "no spectrum", transform=ax.transAxes, ha="center",
                va="center", color="0.45")
        ax.set_xticks([])
        ax.set_yticks([])
        return
    freq, lateral, axial = spectrum
    lateral, axial = 1e3 * lateral, 1e3 * axial
    ax.set_xlim(freq[0], freq[-1])
    ax.set_yscale("log", nonpositive="mask")
    top = max(float(lateral.max()), float(axial.max()))
    if top <= 0.0:
        ax.set_ylim(1e-6, 1.0)
        ax.text(0.5, 0.5, "spectrum is zero", transform=ax.transAxes,
                ha="center", va="center", color="0.45")
        return
    positive = np.concatenate((lateral[lateral > 0.0], axial[axial > 0.0]))
    floor = max(float(positive.min()), top * 10.0 ** -SPECTRUM_DECADES)
    ax.set_ylim(floor / 2.0, top * 4.0)

    shown = [f for f in modes if freq[0] <= f <= freq[-1]]
    for f in shown:
        ax.axvline(f, color="0.78", linewidth=0.6, zorder=1)
    big = freq.size > RASTERIZE_POINTS
    for amp, color, name in ((lateral, LATERAL_COLOR, "lateral"),
                             (axial, AXIAL_COLOR, "axial")):
        ax.plot(freq, np.where(amp > 0.0, amp, np.nan), color=color,
                linewidth=0.8, label=name, zorder=3, rasterized=big)
    if shown:
        ax.plot([], [], color="0.78", linewidth=0.6, label="modes")

    marked = []
    for family, amp, color in (("lateral", lateral, LATERAL_COLOR),
                               ("axial", axial, AXIAL_COLOR)):
        f = peaks.get(family)
        if f is None or not freq[0] <= f <= freq[-1]:
            continue
        i = int(np.argmin(np.abs(freq - f)))
        height = float(amp[max(i - 1, 0):i + 2].max())  # the peak's top bin
        if height <= 0.0:
            continue
        ax.plot([f], [height], linestyle="none", marker="v", markersize=6,
                markerfacecolor="white", markeredgecolor=color,
                markeredgewidth=1.3, zorder=4)
        marked.append((f, height))
    ax.grid(True, which="major", color="0.9", linewidth=0.5)
    ax.set_axisbelow(True)
    ax.legend(loc="upper right", fontsize=8, frameon=True, framealpha=0.85,
              edgecolor="none")
    if marked:
        ax.figure.tight_layout()  # settle the layout before measuring labels
        for f, height in marked:
            _place_label(ax, f"{f:.1f} Hz", (f, height))


def chart_transient(data, ax):
    """Tip response under rub pulses: deflections, phase plane, spectrum."""
    if data.get("title") is not None and not isinstance(data["title"], str):
        raise InputError("'title' is not a string")
    rev, series = _transient_series(data)
    spectrum = _transient_spectrum(data)
    peaks, modes = _transient_references(data)

    fig = ax.figure
    ax.remove()
    (ax_lat, ax_ax), (ax_phase, ax_spec) = fig.subplots(2, 2)
    fig.suptitle(_display_text(data.get("title") or "Transient response"))
    lateral = 1e3 * series["tip_lateral_m"]
    axial = 1e3 * series["tip_axial_m"]
    big = rev.size > RASTERIZE_POINTS

    for panel, values, color, title, label in (
            (ax_lat, lateral, LATERAL_COLOR, "(a) tip lateral deflection",
             "Lateral deflection [mm]"),
            (ax_ax, axial, AXIAL_COLOR, "(b) tip axial deflection",
             "Axial deflection [mm]")):
        contact = _contact_windows(panel, rev, series["axial_force_n"])
        panel.plot(rev, values, color=color, linewidth=0.7, zorder=3,
                   rasterized=big)
        panel.set_xlim(rev[0], rev[-1])
        panel.set_title(title, fontsize=10)
        panel.set_xlabel("Revolutions")
        panel.set_ylabel(label)
        panel.grid(True, which="major", color="0.9", linewidth=0.5)
        panel.set_axisbelow(True)
    if contact:
        ax_lat.legend(handles=[Patch(facecolor=CONTACT_COLOR, alpha=0.35,
                                     edgecolor="none",
                                     label="contact (F < 0)")],
                      loc="upper right", fontsize=8, framealpha=0.85,
                      edgecolor="none")

    mean = float(np.mean(axial))
    spread = float(np.ptp(axial))
    decimals = 4 if spread <= 0.0 else \
        min(max(2 - math.floor(math.log10(spread)), 0), 9)
    ax_ax.axhline(mean, color="0.35", linewidth=0.8, linestyle=(0, (4, 3)),
                  alpha=0.6, zorder=4)
    ax_ax.annotate(f"mean {mean:.{decimals}f} mm", xy=(1.0, mean),
                   xycoords=ax_ax.get_yaxis_transform(), xytext=(-4, 3),
                   textcoords="offset points", ha="right", va="bottom",
                   fontsize=7, color="0.25", zorder=5,
                   bbox=dict(boxstyle="square,pad=0.15", facecolor="white",
                             edgecolor="none", alpha=0.75))

    _dense_line(ax_phase, series["tip_axial_velocity_m_s"], axial,
                color=AXIAL_COLOR, linewidth=0.4, zorder=3, rasterized=big)
    if np.ptp(series["tip_axial_velocity_m_s"]) == 0.0 and np.ptp(axial) == 0.0:
        ax_phase.plot(series["tip_axial_velocity_m_s"][:1], axial[:1],
                      linestyle="none", marker=".", color=AXIAL_COLOR)  # at rest
    ax_phase.set_title("(c) axial phase plane", fontsize=10)
    ax_phase.set_xlabel("Axial velocity [m/s]")
    ax_phase.set_ylabel("Axial deflection [mm]")
    ax_phase.grid(True, which="major", color="0.9", linewidth=0.5)
    ax_phase.set_axisbelow(True)

    _spectrum_panel(ax_spec, spectrum, peaks, modes)


# --------------------------------------------------------------------------
# Sweep: natural frequencies against a scene key
# --------------------------------------------------------------------------

SWEEP_LOG_RATIO = 30.0   # a log frequency axis when the lines span more than this


def _sweep_modes(data, n_values):
    """Validate the tracked modes; return them with labels and colours
    (B1, B2, ..., A1, R1 by family, as in the Campbell diagram)."""
    modes = []
    for i, mode in enumerate(_require(data, "modes", list)):
        if not isinstance(mode, dict):
            raise InputError(f"modes[{i}] is not an object")
        family = mode.get("family")
        if family not in CAMPBELL_FAMILIES:
            raise InputError(f"modes[{i}] has unknown family {family!r}")
        index = _integer(mode.get("index"), f"modes[{i}].index")
        freqs = _numbers(mode.get("frequency_hz"), f"modes[{i}].frequency_hz")
        families = mode.get("families") or [family] * n_values
        if not isinstance(families, list) or len(families) != n_values or \
                any(f not in CAMPBELL_FAMILIES for f in families):
            raise InputError(f"modes[{i}].families must list {n_values} families")
        lam = _numbers(mode.get("lambda"), f"modes[{i}].lambda") \
            if mode.get("lambda") is not None else None
        for name, series in (("frequency_hz", freqs), ("lambda", lam)):
            if series is not None and len(series) != n_values:
                raise InputError(f"modes[{i}].{name} has {len(series)} values,"
                                 f" expected {n_values}")
            if series is not None and any(v < 0 for v in series):
                raise InputError(f"modes[{i}].{name} has a negative value")
        modes.append({"index": index, "family": family, "freqs": freqs,
                      "lambda": lam, "families": families})
    if not modes:
        raise InputError("modes is empty")
    return _label_by_family(modes, "index", darkest=0.95, spread=0.5)


def _family_runs(families):
    """Index ranges [a, b] (inclusive) of equal family; consecutive runs share
    their boundary point, so the pieces join."""
    runs, start = [], 0
    for i in range(1, len(families) + 1):
        if i == len(families) or families[i] != families[start]:
            runs.append((start, min(i, len(families) - 1), families[start]))
            start = i
    return runs


def _sweep_panel(ax, values, modes, series, ylabel):
    positive = [v for m in modes for v in m[series] if v > 0]
    for mode in modes:
        # A tracked mode can change family where it veers (e.g. bending to
        # rotation as the blade gets stubby): each piece in its own style.
        for n, (a, b, family) in enumerate(_family_runs(mode["families"])):
            style = "-" if family == "bending" else "--"
            ax.plot(values[a:b + 1], mode[series][a:b + 1], linestyle=style,
                    color=mode["color"], linewidth=1.6, zorder=3,
                    label=mode["label"] if n == 0 else None)
    if positive and max(positive) > SWEEP_LOG_RATIO * min(positive):
        ax.set_yscale("log")
    ax.set_xlim(min(values), max(values))
    ax.set_ylabel(ylabel)
    ax.grid(True, which="major", color="0.88", linewidth=0.6)
    ax.set_axisbelow(True)


def chart_sweep(data, ax):
    """Natural frequencies against a scene key: one line per tracked mode."""
    values = _numbers(_require(data, "values", list), "values")
    if len(values) < 2:
        raise InputError("values needs at least two entries")
    steps = [b - a for a, b in zip(values, values[1:])]
    if not (all(d > 0 for d in steps) or all(d < 0 for d in steps)):
        raise InputError("values must be strictly monotonic")
    key = _require(data, "key", str)
    modes = _sweep_modes(data, len(values))
    # Lambda = omega L^2 sqrt(rho A / EI) is worth its own panel only where it
    # is not the frequency times one constant (the key changes EI, L, rho or
    # A); otherwise the second panel shows each frequency relative to its
    # value at the first point, the drop (or rise) of every mode alike.
    with_lambda = all(m["lambda"] is not None for m in modes) and any(
        not math.isclose(lam * m["freqs"][0], m["lambda"][0] * f, rel_tol=1e-9)
        for m in modes for f, lam in zip(m["freqs"], m["lambda"]))
    for mode in modes:
        first = mode["freqs"][0]
        mode["relative"] = [f / first if first > 0 else math.nan
                            for f in mode["freqs"]]

    fig = ax.figure
    ax.remove()
    ax, ax_second = fig.subplots(1, 2)
    _sweep_panel(ax, values, modes, "freqs", "Frequency [Hz]")
    if with_lambda:
        _sweep_panel(ax_second, values, modes, "lambda",
                     "Frequency parameter Λ = ωL²√(ρA/EI)")
        ax_second.set_title("(b) frequency parameter (the paper's form)",
                            fontsize=10)
    else:
        _sweep_panel(ax_second, values, modes, "relative",
                     "Frequency / frequency at the first value")
        ax_second.set_yscale("linear")
        ax_second.set_ylim(bottom=0)
        ax_second.set_title("(b) relative to the first value", fontsize=10)
    ax.set_title("(a) frequency", fontsize=10)
    for panel in (ax, ax_second):
        panel.set_xlabel(key)
    fig.suptitle(_display_text(data.get("title") or "Frequencies"))
    handles, labels = ax_second.get_legend_handles_labels()
    handles += [Line2D([], [], color="0.3", linestyle="-"),
                Line2D([], [], color="0.3", linestyle="--")]
    labels += ["bending", "rotation / axial"]
    ax_second.legend(handles, labels, loc="upper left",
                     bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                     fontsize=8, frameon=False)


# --------------------------------------------------------------------------
# Dispatch
# --------------------------------------------------------------------------

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
    if len(argv) != 3:
        print("usage: charts.py <chart-kind> <input.json> <output.png|.svg>",
              file=sys.stderr)
        return 2
    try:
        render(*argv)
    except InputError as exc:
        print(f"charts.py: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
