"""Parameter sweep: natural frequencies against a scene key."""

import math

from matplotlib.lines import Line2D

from chart_campbell import CAMPBELL_FAMILIES, _campbell_family, _label_by_family
from chart_common import InputError, _display_text, _integer, _numbers, _objects, _require

SWEEP_LOG_RATIO = 30.0   # a log frequency axis when the lines span more than this


def _sweep_modes(data, n_values):
    """Validate the tracked modes; return them with labels and colours
    (B1, B2, ..., A1, R1 by family, as in the Campbell diagram)."""
    modes = []
    for i, mode in _objects(_require(data, "modes", list), "modes"):
        family = _campbell_family(mode, f"modes[{i}]")
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
            style = "-" if family in ("bending", "flap", "edge") else "--"
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
