"""bladestab from Python: the program's analyses in this process, and design studies over grids
of scene overrides on local processes, a Dask cluster or MPI (docs/python.md).

    import bladestab
    r = bladestab.stability("blade.toml", tolerance=1e-6, **{"load.fmax_over_fcr": 3.0})
    r.max_abs_multiplier, r.stable, r.to_dict()
"""

from bladestab.analyses import ANALYSES, run
from bladestab.errors import InputError, Note, NumericalError, TimeLimitReached
from bladestab.results import Result

globals().update(ANALYSES)


def study(*args, **kwargs):
    """bladestab.studies.study (imported on first use: it needs xarray and zarr)."""
    from bladestab.studies import study as run_study

    return run_study(*args, **kwargs)


def open_study(store):
    """The Dataset of a study's Zarr store, complete or not (`computed` counts each point's writes)."""
    from bladestab.study_store import open_study as open_store

    return open_store(store)


__all__ = ["InputError", "NumericalError", "TimeLimitReached", "Note", "Result", "run", "study", "open_study", *ANALYSES]
