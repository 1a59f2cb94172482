"""Campbell diagram: modal frequencies and engine-order lines against rotor speed."""

import math

import matplotlib

from chart_common import InputError, RAD_S_TO_RPM, _integer, _number, _numbers, _objects, _optional_list, _place_label, _require

# family -> (label prefix, colormap, linestyle)
CAMPBELL_FAMILIES = {
    "bending": ("B", "Blues", "-"),
    "flap": ("F", "Blues", "-"),
    "edge": ("E", "Purples", "-."),
    "axial": ("A", "Reds", "--"),
    "rotation": ("R", "Greens", ":"),
}


def _campbell_family(item, what):
    """item's "family", one of CAMPBELL_FAMILIES."""
    family = item.get("family")
    if family not in CAMPBELL_FAMILIES:
        raise InputError(f"{what} has unknown family {family!r}")
    return family


def _campbell_curves(data, n_speeds):
    """Validate curves; return them sorted with family labels (B1, A1, ...)."""
    curves = []
    for i, curve in _objects(_require(data, "curves", list), "curves"):
        family = _campbell_family(curve, f"curves[{i}]")
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
    for i, cross in _objects(_optional_list(data, "crossings"), "crossings"):
        order = _integer(cross.get("engine_order"), f"crossings[{i}].engine_order")
        mode = _integer(cross.get("mode"), f"crossings[{i}].mode")
        speed = _number(cross.get("speed_rad_s"), f"crossings[{i}].speed_rad_s")
        freq = _number(cross.get("frequency_hz"), f"crossings[{i}].frequency_hz")
        rpm = cross.get("speed_rpm")
        rpm = speed * RAD_S_TO_RPM if rpm is None else \
            _number(rpm, f"crossings[{i}].speed_rpm")
        crossings.append({"order": order, "mode": mode, "rpm": rpm, "freq": freq})
    return crossings


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
