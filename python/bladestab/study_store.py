"""A study's results in a Zarr group (python3-zarr; on disk, or in memory without a store): one
array per variable over the study's dimensions, chunked as the tasks (study_plan.py), with
xarray's dimension names, so xarray.open_zarr reads it as the Dataset. Only the caller writes it,
a task's chunks at a time as its results arrive; `computed` counts how often each point was
written (1 when the study is complete, 0 where a stopped study has not reached), and a study
resumed against the store runs only the tasks with points at 0. A point that failed has `failed`
set and its one-line reason in `failure`; an answer's field named as a grid key (modes echoes
`model.terms`) is kept as `answer.<key>` beside the coordinate."""

import json
import os

import numpy as np
import xarray as xr
import zarr

from bladestab.errors import InputError

COMPUTED = "computed"
FAILED = "failed"
FAILURE = "failure"
# The store's own variables and dimension, which no grid key may name (study_plan.py).
RESERVED = {COMPUTED, FAILED, FAILURE, "point"}


def _unusable(store, reason):
    return InputError(f"store {os.fspath(store)}: {reason}; give a new path (a directory that does not exist yet, "
                      f"or an empty one) or the store of this study")


def held_study(store):
    """The description of the study a store on disk holds, or None for a path that does not exist
    yet or an empty directory."""
    if store is None or not os.path.exists(os.fspath(store)):
        return None
    path = os.fspath(store)
    if os.path.isdir(path) and not os.listdir(path):
        return None
    try:
        held = zarr.open_group(store, mode="r").attrs.get("bladestab_study")
    except Exception as error:  # zarr's errors for a file, a foreign directory, an unreadable path
        raise _unusable(store, f"not a Zarr group ({type(error).__name__})") from None
    if held is None:
        raise _unusable(store, "a Zarr group that holds no bladestab study")
    return held


def _open_group(store):
    """The group of `store` (in memory for None), created where it does not exist."""
    if store is None:
        return zarr.open_group(zarr.MemoryStore(), mode="a")
    try:
        return zarr.open_group(store, mode="a")
    except Exception as error:  # an unwritable path, a plain file
        raise _unusable(store, f"cannot be written as a Zarr group ({type(error).__name__}: {error})") from None


class StudyStore:
    def __init__(self, store, plan, description):
        self.plan = plan
        self.group = _open_group(store)
        held = self.group.attrs.get("bladestab_study")
        wanted = json.loads(json.dumps(description))
        if held is not None and held != wanted:
            entry = next(k for k in sorted(set(held) | set(wanted)) if held.get(k) != wanted.get(k))
            differs = ("its scene's text is another" if entry == "scene_sha256"
                       else "its section table's contents are others" if entry == "section_tables_sha256"
                       else f"its {entry} is {held.get(entry)!r}, this one's {wanted.get(entry)!r}")
            raise InputError(f"store {store}: holds another study ({differs}); give a new store to start this one")
        if held is None:
            self.group.attrs["bladestab_study"] = description
            for dim, key in zip(plan.dims if plan.dims != ["point"] else [], plan.keys):
                self._array(key, plan.coordinate(key), [dim])
            if plan.dims == ["point"]:
                self._array("point", np.arange(plan.size), ["point"])
                for key in plan.keys:
                    self._array(key, plan.coordinate(key), ["point"])
            self._variable(COMPUTED, np.int8, 0)
            self._variable(FAILED, bool, False)
            self._variable(FAILURE, str, "")

    def _array(self, name, values, dims):
        array = self.group.create_dataset(name, data=values, shape=values.shape, dtype=values.dtype)
        array.attrs["_ARRAY_DIMENSIONS"] = dims

    def _variable(self, name, dtype, fill):
        chunks = (1,) * (len(self.plan.shape) - 1) + (self.plan.chunk,)
        array = self.group.create_dataset(name, shape=self.plan.shape, chunks=chunks, dtype=dtype, fill_value=fill)
        array.attrs["_ARRAY_DIMENSIONS"] = self.plan.dims
        return array

    def pending(self):
        """The tasks with a point not yet written."""
        computed = self.group[COMPUTED][...]
        return [task for task in self.plan.chunks() if (computed[self.plan.region(task)] == 0).any()]

    def write(self, task, answers):
        """A task's answers (study_worker.run_task) into its chunks, then its points' counts."""
        region = self.plan.region(task)
        names = dict.fromkeys(k for a in answers if isinstance(a, dict) for k, v in a.items() if v is not None)
        for name in names:
            values = [a.get(name) if isinstance(a, dict) else None for a in answers]
            is_bool = all(isinstance(v, bool) or v is None for v in values)
            stored = f"answer.{name}" if name in self.plan.keys or name in RESERVED else name
            if stored not in self.group:
                self._variable(stored, bool if is_bool else float, False if is_bool else np.nan)
            array = self.group[stored]
            cells = np.array([False if v is None else v for v in values] if array.dtype == bool
                             else [np.nan if v is None else float(v) for v in values], dtype=array.dtype)
            array[region] = cells
        failed = np.array([not isinstance(a, dict) for a in answers])
        self.group[FAILED][region] = failed
        self.group[FAILURE][region] = np.array(["" if isinstance(a, dict) else a[1] for a in answers], dtype=object)
        self.group[COMPUTED][region] = self.group[COMPUTED][region] + 1

    def dataset(self):
        return open_study(self.group.store, self.plan.keys)


def open_study(store, keys=None):
    """The Dataset a store holds (complete or not), its variables as written: without xarray's
    masking of fill values, which would turn a False or a 0 into NaN."""
    dataset = xr.open_zarr(store, consolidated=False, mask_and_scale=False).load()
    keys = keys if keys is not None else [k for k in dataset.data_vars if dataset[k].dims == ("point",)]
    # Attributes netCDF can hold (Dataset.to_netcdf): the description as JSON text, and no fill
    # values, which mark nothing in the values as read.
    if isinstance(dataset.attrs.get("bladestab_study"), (dict, list)):
        dataset.attrs["bladestab_study"] = json.dumps(dataset.attrs["bladestab_study"])
    for variable in dataset.variables.values():
        variable.attrs.pop("_FillValue", None)
    return dataset.set_coords([k for k in keys if k in dataset.data_vars])
