#!/usr/bin/python3
"""What a design study costs (issue 27): the in-process cost of a stability point on the shipped
scene, a study's throughput on 1 and 2 local worker processes, and the overhead each executor adds
per task (an empty task: submit, run, result back). Writes bench/python_results.json (merged with
what is there) and prints the figures.

    PYTHONPATH=build/python bench/python_study.py                  # in-process, local processes, Dask
    PYTHONPATH=build/python mpiexec --allow-run-as-root -n 3 python3 -m mpi4py.futures bench/python_study.py --mpi
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import tempfile
import time

import bladestab
from bladestab import _core
from bladestab.arguments import command_line
from bladestab.study_worker import run_task

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "stability_maps", "sinha2005", "blade.toml")
RESULTS = os.path.join(ROOT, "bench", "python_results.json")
GRID = {"operation.speed_rad_s": [150.0 + 25.0 * i for i in range(12)], "load.fmax_over_fcr": [1.0, 2.0, 4.0, 6.0]}


def grid_points():
    return [{"operation.speed_rad_s": s, "load.fmax_over_fcr": f} for s in GRID["operation.speed_rad_s"]
            for f in GRID["load.fmax_over_fcr"]]


def point_cost(threads):
    """Seconds per point of `stability` in this process: the command's run (options, scene text,
    analysis, JSON), without Python's parsing of the answer; the median over the grid's points."""
    with open(SCENE, encoding="utf-8") as fh:
        text = fh.read()
    times = []
    for point in grid_points():
        arguments = command_line("stability", SCENE, {"threads": threads, **point})
        start = time.perf_counter()
        _core.run(arguments, text, None)
        times.append(time.perf_counter() - start)
    return {"median_s": statistics.median(times), "mean_s": statistics.mean(times), "points": len(times)}


def throughput(workers):
    """Points per second of a study on `workers` local processes (threads = 1 per point)."""
    with concurrent.futures.ProcessPoolExecutor(workers) as pool:
        pool.submit(run_task, "stability", SCENE, "", {}, []).result()  # started
        start = time.perf_counter()
        bladestab.study(SCENE, GRID, "stability", executor=pool, options={"threads": 1}, chunk=2)
        seconds = time.perf_counter() - start
    return {"points_per_s": len(grid_points()) / seconds, "seconds": seconds, "points": len(grid_points())}


def task_overhead(executor, tasks):
    """Seconds per empty task: all submitted at once, the wall time to the last result over their number."""
    executor.submit(run_task, "stability", SCENE, "", {}, []).result()
    start = time.perf_counter()
    futures = [executor.submit(run_task, "stability", SCENE, "", {}, []) for _ in range(tasks)]
    for f in futures:
        f.result()
    return (time.perf_counter() - start) / tasks


def local_figures(tasks):
    figures = {"point_cost_threads_1": point_cost(1), "point_cost_threads_2": point_cost(2)}
    figures["throughput_1_worker"] = throughput(1)
    figures["throughput_2_workers"] = throughput(2)
    figures["speedup_2_workers"] = figures["throughput_2_workers"]["points_per_s"] / figures["throughput_1_worker"]["points_per_s"]
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        figures["task_overhead_local_processes_s"] = task_overhead(pool, tasks)
    from dask.distributed import Client, LocalCluster

    with tempfile.TemporaryDirectory() as scratch, \
            LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                         local_directory=scratch) as cluster, \
            Client(cluster) as client:
        figures["task_overhead_dask_s"] = task_overhead(client.get_executor(), tasks)
    return figures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mpi", action="store_true", help="only the MPI executor's overhead (under mpiexec)")
    parser.add_argument("--tasks", type=int, default=400)
    args = parser.parse_args()
    if args.mpi:
        from mpi4py.futures import MPIPoolExecutor

        with MPIPoolExecutor() as pool:
            figures = {"task_overhead_mpi_s": task_overhead(pool, args.tasks)}
    else:
        figures = local_figures(args.tasks)
    figures_time = {"measured": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "load": os.getloadavg()}
    results = {}
    if os.path.exists(RESULTS):
        with open(RESULTS, encoding="utf-8") as fh:
            results = json.load(fh)
    results.update(figures)
    results["mpi_measured" if args.mpi else "local_measured"] = figures_time
    with open(RESULTS, "w", encoding="utf-8") as fh:
        json.dump(results, fh, indent=2)
        fh.write("\n")
    print(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
