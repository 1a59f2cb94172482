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
"""

import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)

RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)
FIGSIZE = (8.0, 5.5)
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

    by_family = {}
    for curve in sorted(curves, key=lambda c: c["mode"]):
        by_family.setdefault(curve["family"], []).append(curve)
    for family, members in by_family.items():
        prefix, cmap_name, _ = CAMPBELL_FAMILIES[family]
        cmap = matplotlib.colormaps[cmap_name]
        for n, curve in enumerate(members):
            shade = 0.9 - 0.35 * n / max(len(members) - 1, 1)
            curve["label"] = f"{prefix}{n + 1}"
            curve["color"] = cmap(shade if len(members) > 1 else 0.75)
    return sorted(curves, key=lambda c: c["mode"])


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
# Dispatch
# --------------------------------------------------------------------------

CHARTS = {
    "campbell": chart_campbell,
}


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
    fig, ax = plt.subplots(figsize=FIGSIZE)
    try:
        CHARTS[kind](data, ax)
        fig.tight_layout()
        metadata = {"Date": None} if fmt == "svg" else {}
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
