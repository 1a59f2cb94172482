"""Design studies: one analysis over a grid of scene overrides, on any concurrent.futures executor
(local processes by default, a Dask cluster through its Client, MPI through mpi4py.futures), the
answers gathered into an xarray.Dataset and, with a store, into Zarr as they arrive, so a stopped
study resumes where it stopped."""

import concurrent.futures
import hashlib
import os
import signal

import tomllib

from bladestab.analyses import ANALYSES
from bladestab.arguments import command_options, scene_source
from bladestab.errors import InputError, NumericalError
from bladestab.study_plan import Plan
from bladestab.study_store import COMPUTED, FAILED, StudyStore, held_study
from bladestab.study_worker import run_task


def _command(analysis):
    name = getattr(analysis, "__name__", analysis)
    if name not in command_options():
        raise InputError(f"analysis {name!r}: not one of {', '.join(ANALYSES)}")
    return name


def _scene_text(scene):
    """The scene as (name, text): a file is read once here, so workers need no shared files."""
    name, text = scene_source(scene)
    if not text:
        try:
            with open(name, encoding="utf-8") as fh:
                text = fh.read()
        except OSError as error:
            raise InputError(f"scene {name}: cannot read it: {error.strerror}") from None
    return name, text


def _section_files(name, text, options, plan):
    """The section tables (blade.sections) the study's points read, as the program resolves them
    (beside the scene file): from the scene, its fixed overrides and the grid."""
    try:
        named = [tomllib.loads(text).get("blade", {}).get("sections")]
    except (tomllib.TOMLDecodeError, AttributeError):
        named = []  # the program says what is wrong with the scene
    named += [options.get("blade.sections")] + list(plan.coords.get("blade.sections", []))
    base = os.path.dirname(name) if os.sep in name else ""
    return sorted({os.path.join(base, n) for n in named if isinstance(n, str) and n})


def _files_sha256(paths):
    """{path: SHA-256 of its bytes} of the files that can be read (the program reports the others)."""
    digests = {}
    for path in paths:
        try:
            with open(path, "rb") as fh:
                digests[path] = hashlib.sha256(fh.read()).hexdigest()
        except OSError:
            continue
    return digests


def _ignore_interrupts():
    """A local worker's start: Ctrl-C reaches the whole process group, and the study (the caller)
    answers it by ending its workers; a worker stopped by it half-way through sending a result
    would leave the pool waiting for that result forever."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _executor(executor):
    """(executor, owned): a Dask Client becomes its concurrent.futures executor; none, a pool of
    local processes (one per core) that the study shuts down."""
    if executor is None:
        return concurrent.futures.ProcessPoolExecutor(os.cpu_count(), initializer=_ignore_interrupts), True
    if hasattr(executor, "get_executor"):  # dask.distributed.Client
        return executor.get_executor(), False
    return executor, False


def _workers(executor):
    if executor is None:
        return os.cpu_count() or 1
    if hasattr(executor, "nthreads"):  # dask.distributed.Client
        return max(1, sum(executor.nthreads().values()))
    return getattr(executor, "_max_workers", None) or getattr(executor, "num_workers", None) or 1


def study(scene, grid, analysis, executor=None, store=None, options=None, chunk=None, progress=None):
    """`analysis` (a name or a bladestab function) at every point of `grid` ({key: values}: their
    cartesian product; or a list of {key: value}) over `scene` with `options` (as the analysis
    takes them), on `executor`; the xarray.Dataset of the answers' scalar fields, one dimension
    per grid key. With `store` (a Zarr path) the answers are written there chunk by chunk and a
    study run again against it computes only what it does not hold. `chunk`: points per task;
    `progress(done, total)` after each task. A point refused or failing its checks is `failed`,
    its one-line reason in `failure`, its numeric variables NaN and its boolean ones False; a study
    where every point fails raises the first one's error."""
    command = _command(analysis)
    options = dict(options or {})
    if "--threads" in command_options()[command]:
        options.setdefault("threads", 1)  # a worker per core: each point on its own one (answers do not depend on it)
    name, text = _scene_text(scene)
    held = held_study(store)
    # A study resumed takes the store's chunks unless given others (the default depends on the workers).
    plan = Plan(grid, chunk if chunk is not None or held is None else held.get("chunk"), _workers(executor))
    # What the answers depend on: the grid's keys in their order (the store's dimensions), and the
    # section tables' contents as well as the scene's text.
    description = {"analysis": command, "scene": name, "scene_sha256": hashlib.sha256(text.encode()).hexdigest(),
                   "section_tables_sha256": _files_sha256(_section_files(name, text, options, plan)),
                   "options": {k: repr(v) for k, v in options.items()},
                   "grid": [[k, repr(plan.coords[k])] for k in plan.keys], "chunk": plan.chunk}
    results = StudyStore(store, plan, description)
    tasks = results.pending()
    pool, owned = _executor(executor)
    try:
        futures = {pool.submit(run_task, command, name, text, options, plan.points(t)): t for t in tasks}
        done = len(plan.chunks()) - len(tasks)
        failure = None
        for future in concurrent.futures.as_completed(futures):
            answers = future.result()
            failure = failure or next((a for a in answers if not isinstance(a, dict)), None)
            results.write(futures[future], answers)
            done += 1
            if progress is not None:
                progress(done, len(plan.chunks()))
    except KeyboardInterrupt:
        if owned:  # its workers ignore Ctrl-C (_ignore_interrupts): ended here, their tasks with them
            for process in list((getattr(pool, "_processes", None) or {}).values()):
                process.terminate()
        raise
    finally:
        if owned:
            pool.shutdown(wait=True, cancel_futures=True)
    dataset = results.dataset()
    if failure is not None and bool(dataset[FAILED].all()):  # a bad key or option, not a bad point
        raise (InputError if failure[0] == "input" else NumericalError)(failure[1])
    return dataset.drop_vars(COMPUTED)
