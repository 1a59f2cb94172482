"""What the Python tests share: the program, the shipped scene, and running the program to compare."""

import json
import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("BLADESTAB_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(__file__))))
EXE = os.environ.get("BLADESTAB_EXE", os.path.join(SOURCE_DIR, "build", "bladestab"))
SCENE = os.path.join(SOURCE_DIR, "stability_maps", "sinha2005", "blade.toml")


def without_wall_times(document):
    """The document without its wall times ("seconds": each check of `check`, as JUnit reports
    them), which differ from run to run."""
    if isinstance(document, dict):
        return {k: without_wall_times(v) for k, v in document.items() if k != "seconds"}
    if isinstance(document, list):
        return [without_wall_times(v) for v in document]
    return document


def run_program(*args, expect_status=0):
    """The program's JSON answer to `bladestab ARGS --format json`."""
    done = subprocess.run([EXE, *args, "--format", "json"], capture_output=True, text=True, timeout=120)
    assert done.returncode == expect_status, done.stderr
    return json.loads(done.stdout)


@pytest.fixture
def scene():
    return SCENE
