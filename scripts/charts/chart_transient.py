"""Transient response: tip histories, phase plane, contact windows and the spectrum."""

import math

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.patches import Patch

from chart_common import DPI, InputError, _display_text, _number, _numbers, _optional_object, _place_label, _require

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
    spectrum = _optional_object(data, "spectrum", ("frequency_hz", "lateral", "axial"))
    if spectrum is None:
        return None
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


def _pixel_columns(ax):
    """Pixel columns a panel of a two-column figure can have at most: half
    the saved figure's width."""
    return max(1, int(ax.figure.get_figwidth() * DPI) // 2)


def _pixel_decimate(x, y, columns):
    """The points of the line through (x, y), x ascending, that draw it the
    same at `columns` pixel columns: in each column's x range the first, the
    last, the lowest and the highest point (M4; Jugel et al., VLDB 2014), so
    every peak stays. Returns the kept indices, ascending."""
    if x.size <= 4 * columns or x[-1] <= x[0]:
        return np.arange(x.size)
    column = np.minimum(((x - x[0]) / (x[-1] - x[0]) * columns).astype(int),
                        columns - 1)
    starts = np.flatnonzero(np.r_[True, column[1:] != column[:-1]])
    ends = np.r_[starts[1:], x.size]
    keep = [starts, ends - 1]
    for pick in (np.argmin, np.argmax):
        keep.append(np.array([a + pick(y[a:b]) for a, b in zip(starts, ends)]))
    return np.unique(np.concatenate(keep))


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
    for amp, color, name in ((lateral, LATERAL_COLOR, "lateral"),
                             (axial, AXIAL_COLOR, "axial")):
        kept = _pixel_decimate(freq, amp, _pixel_columns(ax))
        ax.plot(freq[kept], np.where(amp[kept] > 0.0, amp[kept], np.nan),
                color=color, linewidth=0.8, label=name, zorder=3,
                rasterized=kept.size > RASTERIZE_POINTS)
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
        kept = _pixel_decimate(rev, values, _pixel_columns(panel))
        panel.plot(rev[kept], values[kept], color=color, linewidth=0.7,
                   zorder=3, rasterized=kept.size > RASTERIZE_POINTS)
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
