"""The program's charts from Python: the chart modules of scripts/charts/ (installed as
bladestab/charts/), which the program runs to draw the same charts."""

import importlib.util
import json
import os
import sys
import tempfile

CHARTS_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "charts")


def _charts():
    """The charts package's dispatch module. Its modules import each other by plain name (as the
    program joins them into one script), so their directory is put on the import path."""
    if "bladestab_charts" not in sys.modules:
        if CHARTS_DIR not in sys.path:
            sys.path.append(CHARTS_DIR)
        spec = importlib.util.spec_from_file_location("bladestab_charts", os.path.join(CHARTS_DIR, "__main__.py"))
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        sys.modules["bladestab_charts"] = module
    return sys.modules["bladestab_charts"]


def plot(kind, data, path=None):
    charts = _charts()
    if kind not in charts.CHARTS:
        raise ValueError(f"{kind}: the program draws no chart for it; charts: {', '.join(sorted(charts.CHARTS))}")
    if path is not None:
        with tempfile.TemporaryDirectory() as scratch:
            json_path = os.path.join(scratch, "chart.json")
            with open(json_path, "w", encoding="utf-8") as fh:
                json.dump(data, fh)
            charts.render(kind, json_path, os.fspath(path))
        return None
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=charts.FIGSIZES.get(kind, charts.FIGSIZE))
    charts.CHARTS[kind](data, ax)
    fig.tight_layout()
    return fig
