"""Stability map (Ince–Strutt style): Floquet max|ρ| shading with the ±1 boundary curves."""

import math

import matplotlib
import numpy as np
from matplotlib.colors import ListedColormap, Normalize
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from chart_common import InputError, _display_text, _integer, _number, _numbers, _objects, _optional_list, _optional_object, _place_label, _require  # noqa: E501 (one line: CMakeLists.txt drops it)

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
    grid = _optional_object(data, "grid", ("x", "y", "max_abs_multiplier"))
    if grid is None:
        return None
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
    for i, curve in _objects(_optional_list(data, "curves"), "curves"):
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
    for k, region in _objects(regions, "combination_regions"):
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
    for i, marker in _objects(_optional_list(data, "markers"), "markers"):
        x = _number(marker.get("x"), f"markers[{i}].x")
        y = _number(marker.get("y"), f"markers[{i}].y")
        label = marker.get("label")
        if label is not None and not isinstance(label, str):
            raise InputError(f"markers[{i}].label is not a string")
        markers.append({"x": x, "y": y, "label": label or ""})
    return markers


def _map_refined(data):
    """The refined shading as cell edges and a raster; None if absent."""
    ref = _optional_object(data, "refinement", ())
    if ref is None:
        return None
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
