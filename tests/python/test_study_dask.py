"""Studies on a Dask cluster (a LocalCluster of two worker processes): the serial answer, also
when a worker is killed mid-study — no point lost, none written twice into the store."""

import os
import signal

import pytest
import zarr
from dask.distributed import Client, LocalCluster

import bladestab
from conftest import SCENE
from study_reference import GRID, assert_equals_serial, serial


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    # The workers' scratch space under pytest's temporary directory, not /tmp/dask-worker-space.
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                           local_directory=str(tmp_path_factory.mktemp("dask")))
    with Client(cluster) as client:
        yield client
    cluster.close()


@pytest.fixture(scope="module")
def reference():
    return serial()


def test_dask_study_equals_serial(client, reference, tmp_path):
    dataset = bladestab.study(SCENE, GRID, "stability", executor=client, store=str(tmp_path / "s.zarr"))
    assert_equals_serial(dataset, reference)


def test_killed_worker_loses_no_point_and_computes_none_twice(client, reference, tmp_path):
    store = str(tmp_path / "killed.zarr")
    killed = []

    def kill_one_worker(done, total):
        if done == 2 and not killed:
            pid = next(iter(client.run(os.getpid).values()))
            os.kill(pid, signal.SIGKILL)
            killed.append(done < total)

    dataset = bladestab.study(SCENE, GRID, bladestab.stability, executor=client, store=store, chunk=1,
                              progress=kill_one_worker)
    assert killed == [True]
    assert_equals_serial(dataset, reference)
    assert (zarr.open_group(store)["computed"][...] == 1).all()
