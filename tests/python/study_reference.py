"""The tests' design study: 6 speeds × 4 rub loads of the shipped blade's stability, and its
answer computed point by point, serially, through the plain API."""

import numpy as np

import bladestab
from conftest import SCENE

GRID = {"operation.speed_rad_s": [150.0, 200.0, 250.0, 300.0, 350.0, 400.0],
        "load.fmax_over_fcr": [1.0, 2.0, 4.0, 6.0]}
FIELDS = ["max_abs_multiplier", "error_estimate", "stable", "reduced_dofs"]


def serial():
    """{field: array over the grid}, one bladestab.stability call per point."""
    shape = tuple(len(v) for v in GRID.values())
    values = {f: np.zeros(shape, dtype=bool if f == "stable" else float) for f in FIELDS}
    for i, speed in enumerate(GRID["operation.speed_rad_s"]):
        for j, fmax in enumerate(GRID["load.fmax_over_fcr"]):
            answer = bladestab.stability(SCENE, **{"operation.speed_rad_s": speed, "load.fmax_over_fcr": fmax})
            for f in FIELDS:
                values[f][i, j] = answer[f]
    return values


def assert_equals_serial(dataset, reference):
    assert list(dataset.dims) == list(GRID)
    for key, values in GRID.items():
        assert dataset[key].values.tolist() == values
    for f in FIELDS:
        assert np.array_equal(dataset[f].values, reference[f]), f
    assert not dataset["failed"].values.any()


def study_file(directory, scene=SCENE):
    """STUDY.toml for `python3 -m bladestab study`."""
    path = directory / "study.toml"
    grid = "\n".join(f'"{k}" = {v}' for k, v in GRID.items())
    path.write_text(f'scene = "{scene}"\nanalysis = "stability"\n[grid]\n{grid}\n')
    return path
