"""What every chart shares: the matplotlib setup, sizes, the input checks and the point labels."""

import math
import re

import matplotlib

matplotlib.use("Agg")  # before any module imports pyplot

RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)
FIGSIZE = (8.0, 5.5)
FIGSIZES = {"transient": (10.0, 7.0), "sweep": (11.0, 5.0)}  # kinds that need another size
DPI = 150
OUTPUT_FORMATS = {".png": "png", ".svg": "svg"}


class InputError(Exception):
    """Raised for malformed chart input; reported as a one-line message."""


# Small validation helpers

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


def _objects(values, what):
    """(index, item) of a list whose items must all be objects."""
    for i, item in enumerate(values):
        if not isinstance(item, dict):
            raise InputError(f"{what}[{i}] is not an object")
        yield i, item


def _optional_object(data, key, keys):
    """data[key], an object holding every one of `keys`, or None where it is absent."""
    value = data.get(key)
    if value is None:
        return None
    if not isinstance(value, dict):
        raise InputError(f"'{key}' is not an object")
    for k in keys:
        if k not in value:
            raise InputError(f"missing key '{key}.{k}'")
    return value


def _integer(value, what):
    if isinstance(value, bool) or not isinstance(value, int):
        raise InputError(f"{what} is not an integer")
    return value


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
