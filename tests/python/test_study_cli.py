"""`python3 -m bladestab study`: under MPI (mpiexec, mpi4py.futures) the serial answer; stopped by
SIGINT and run again against its store, the same answer with no stored chunk computed again."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import zarr

import bladestab

from study_reference import assert_equals_serial, serial, study_file


def test_mpi_study_equals_serial(tmp_path):
    store = tmp_path / "mpi.zarr"
    done = subprocess.run(["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", "3", sys.executable, "-m",
                           "mpi4py.futures", "-m", "bladestab", "study", str(study_file(tmp_path)), "--mpi",
                           "--store", str(store)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert_equals_serial(bladestab.open_study(str(store)), serial())


def test_sigint_then_restart_resumes_without_recomputing(tmp_path):
    store = tmp_path / "resumed.zarr"
    command = [sys.executable, "-m", "bladestab", "study", str(study_file(tmp_path)), "--store", str(store),
               "--chunk", "1"]
    first = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    while first.poll() is None:  # stop it once some points are stored
        if os.path.exists(store / "computed" / ".zarray") and 3 <= zarr.open_group(str(store))["computed"][...].sum():
            first.send_signal(signal.SIGINT)
            break
        time.sleep(0.01)
    _, err = first.communicate(timeout=60)
    assert first.returncode == 130 and "interrupted" in err, err
    stored = zarr.open_group(str(store))["computed"][...].copy()
    assert 0 < stored.sum() < stored.size  # stopped mid-study

    again = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert again.returncode == 0, again.stderr
    computed = zarr.open_group(str(store))["computed"][...]
    assert (computed == 1).all()  # nothing stored was computed again, nothing is missing
    assert_equals_serial(bladestab.open_study(str(store)), serial())
    assert np.array_equal(computed[stored == 1], stored[stored == 1])
