"""python3 -m bladestab study STUDY.toml [--scheduler ADDRESS | --mpi] [--store PATH] [--chunk N]

Runs the design study STUDY.toml describes and prints its Dataset:

    scene = "blade.toml"           # relative to the study file
    analysis = "stability"
    [options]                      # the analysis's options and fixed scene overrides
    tolerance = 1e-6
    [grid]                         # one dimension per key: the cartesian product of the values
    "operation.speed_rad_s" = [100.0, 200.0, 300.0]
    "load.fmax_over_fcr" = [1.0, 2.0, 3.0, 4.0]

on local processes, a Dask cluster (--scheduler tcp://host:8786) or MPI (--mpi, under
`mpiexec -n N python3 -m mpi4py.futures -m bladestab study …`). With --store the answers go to a
Zarr store as they arrive, and the same command again resumes a stopped study. A progress bar is
shown on a terminal. Exit status 2 for bad input, with one line on stderr."""

import argparse
import os
import sys

import tomllib

from bladestab.errors import InputError, NumericalError


def _study_file(path):
    try:
        with open(path, "rb") as fh:
            study = tomllib.load(fh)
    except (OSError, tomllib.TOMLDecodeError) as error:
        raise InputError(f"{path}: cannot read it as a study: {error}") from None
    for key in ("scene", "analysis", "grid"):
        if key not in study:
            raise InputError(f"{path}: {key}: required (scene, analysis, [grid], optional [options])")
    unknown = set(study) - {"scene", "analysis", "grid", "options"}
    if unknown:
        raise InputError(f"{path}: {sorted(unknown)[0]}: unknown; known: scene, analysis, grid, options")
    for key, kinds, what in (("scene", str, "a path"), ("analysis", str, "a name"),
                             ("grid", (dict, list), "a table of value lists or a list of tables"),
                             ("options", dict, "a table")):
        if key in study and not isinstance(study[key], kinds):
            raise InputError(f"{path}: {key} = {study[key]!r}: must be {what}")
    study["scene"] = os.path.join(os.path.dirname(os.path.abspath(path)), study["scene"])
    return study


def _executor(args):
    if args.scheduler:
        from dask.distributed import Client

        try:
            return Client(args.scheduler)
        except OSError as error:
            raise InputError(f"--scheduler {args.scheduler}: cannot reach it ({error})") from None
    if args.mpi:
        from mpi4py.futures import MPIPoolExecutor

        return MPIPoolExecutor()
    return None


def _progress_bar():
    if not sys.stderr.isatty():
        return None, None
    from tqdm import tqdm

    bar = tqdm(desc="study", unit="task", file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.n = done
        bar.refresh()

    return progress, bar


def main(argv):
    parser = argparse.ArgumentParser(prog="python3 -m bladestab", description="bladestab design studies")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("study", help="run a design study (STUDY.toml)")
    run.add_argument("study", help="the study file (TOML)")
    where = run.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="a Dask scheduler's address (tcp://host:8786)")
    where.add_argument("--mpi", action="store_true", help="MPI workers (under mpiexec … -m mpi4py.futures)")
    run.add_argument("--store", help="a Zarr store for the answers; a study run again against it resumes")
    run.add_argument("--chunk", type=int, help="points per task (default: about four tasks per worker)")
    args = parser.parse_args(argv)
    from bladestab.studies import study

    progress, bar = _progress_bar()
    executor = None
    try:
        spec = _study_file(args.study)
        executor = _executor(args)
        dataset = study(spec["scene"], spec["grid"], spec["analysis"], executor=executor, store=args.store,
                        options=spec.get("options"), chunk=args.chunk, progress=progress)
    except InputError as error:
        print(f"bladestab: error: {error}", file=sys.stderr)
        return 2
    except NumericalError as error:
        print(f"bladestab: failed: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        stored = f"; the store {args.store} holds what was computed" if args.store else ""
        print(f"bladestab: stopped: interrupted (SIGINT){stored}", file=sys.stderr)
        return 130
    finally:
        if bar is not None:
            bar.close()
        if executor is not None:
            (executor.close if hasattr(executor, "close") else executor.shutdown)()
    print(dataset)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
