"""A study's points and how they are cut into tasks. A grid {key: values} is their cartesian
product, one dimension per key, in the order given; a list of {key: value} is explicit points
along one dimension "point". Tasks are blocks of up to `chunk` points along the last dimension
(the store's chunks, study_store.py), so each task fills whole chunks and no two tasks share one."""

import itertools
import math
import numbers

import numpy as np

from bladestab.errors import InputError
from bladestab.study_store import RESERVED


def _values(key, values):
    values = values.tolist() if hasattr(values, "tolist") else values
    if isinstance(values, (str, bytes, dict)) or not hasattr(values, "__iter__"):
        raise InputError(f"grid {key}: {values!r}: a list of values (one value is a list of one)")
    values = list(values)
    if not values:
        raise InputError(f"grid {key}: no values")
    for value in values:
        _check_value(key, value)
    return values


def _check_value(key, value):
    """A grid value is what a scene key or an option takes: a number, a bool or a string."""
    if not isinstance(value, (numbers.Real, str)):
        raise InputError(f"grid {key}: {value!r}: each value a number, a bool or a string")


def _check_keys(keys):
    for key in keys:
        if not isinstance(key, str) or key in RESERVED:
            raise InputError(f"grid {key!r}: a scene key (section.key) or an option, not one of the study's own "
                             f"variables {', '.join(sorted(RESERVED))}")


def _chunk(chunk):
    if chunk is None:
        return None
    if isinstance(chunk, bool) or not isinstance(chunk, numbers.Integral) or chunk < 1:
        raise InputError(f"chunk {chunk!r}: the points per task, a whole number of at least 1")
    return int(chunk)


class Plan:
    def __init__(self, grid, chunk=None, workers=1):
        if isinstance(grid, dict):
            if not grid:
                raise InputError("grid: no keys")
            _check_keys(grid)
            self.keys = list(grid)
            self.dims = list(grid)
            self.coords = {key: _values(key, values) for key, values in grid.items()}
            self.shape = tuple(len(v) for v in self.coords.values())
        else:
            points = list(grid)
            if not points or not all(isinstance(p, dict) for p in points):
                raise InputError("grid: a dict of value lists or a non-empty list of dicts of overrides")
            self.keys = list(dict.fromkeys(k for p in points for k in p))
            _check_keys(self.keys)
            for point in points:
                for key, value in point.items():
                    _check_value(key, value)
            missing = [k for k in self.keys if any(k not in p for p in points)]
            if missing:
                raise InputError(f"grid {missing[0]}: not given at every point")
            self.dims = ["point"]
            self.coords = {key: [p[key] for p in points] for key in self.keys}
            self.shape = (len(points),)
        self.size = math.prod(self.shape)
        last = self.shape[-1]
        # By default about four tasks per worker, cut evenly along the last dimension.
        per_task = _chunk(chunk) or max(1, math.ceil(self.size / (4 * max(1, workers))))
        self.blocks = math.ceil(last / min(last, per_task))
        self.chunk = math.ceil(last / self.blocks)
        self.blocks = math.ceil(last / self.chunk)

    def chunks(self):
        """Every task: (index of its leading dimensions, block along the last)."""
        return [(lead, b) for lead in itertools.product(*(range(n) for n in self.shape[:-1])) for b in range(self.blocks)]

    def region(self, task):
        lead, block = task
        stop = min(self.shape[-1], (block + 1) * self.chunk)
        return tuple(lead) + (slice(block * self.chunk, stop),)

    def points(self, task):
        """The overrides of the task's points, in order."""
        lead, block = task
        region = self.region(task)
        points = []
        for i in range(region[-1].start, region[-1].stop):
            index = tuple(lead) + (i,)
            if self.dims == ["point"]:
                points.append({key: self.coords[key][i] for key in self.keys})
            else:
                points.append({key: self.coords[key][j] for key, j in zip(self.keys, index)})
        return points

    def coordinate(self, key):
        values = self.coords[key]
        return np.array(values, dtype=str if any(isinstance(v, str) for v in values) else None)
