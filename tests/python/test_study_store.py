"""What a study keeps and refuses: answers beside grid keys of the same name, the reason a point
failed, a store's scene checked by its text, a resumed store's chunks, bad chunks and grid values,
and Ctrl-C at a terminal (the whole process group) ending a study at once."""

import concurrent.futures
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import zarr

import bladestab
from conftest import SCENE

SERIAL = concurrent.futures.ThreadPoolExecutor(1)


def test_a_grid_key_that_the_answer_also_names_is_kept_apart():
    # `modes` echoes model.terms; it had overwritten the coordinate (IndexError on a 2-d grid).
    grid = {"operation.speed_rad_s": [200.0, 300.0], "model.terms": [8, 12]}
    dataset = bladestab.study(SCENE, grid, "modes", executor=SERIAL)
    assert dataset["model.terms"].values.tolist() == [8, 12]
    assert dataset["answer.model.terms"].values.tolist() == [[8, 12], [8, 12]]
    # The answer itself, one point through the plain API: the study's modes are its modes.
    single = bladestab.modes(SCENE, **{"operation.speed_rad_s": 300.0, "model.terms": 12})
    assert dataset["accuracy.reference_terms"].values[1, 1] == single["accuracy"]["reference_terms"]


def test_a_failed_point_says_why_and_the_others_stand():
    grid = {"operation.tip_compression_over_fcr": [0.0, 5.0, 6.0]}
    dataset = bladestab.study(SCENE, grid, "stability", executor=SERIAL)
    assert dataset["failed"].values.tolist() == [False, True, True]
    failure = dataset["failure"].values.tolist()
    assert failure[0] == ""
    # The blade buckles at 4.954 F_cr at 300 rad/s (the scene file's comment; printed 4.95372).
    assert all("operation.tip_compression_over_fcr" in f and "4.9537" in f for f in failure[1:]), failure
    assert np.isfinite(dataset["max_abs_multiplier"].values[0]) and np.isnan(dataset["max_abs_multiplier"].values[1:]).all()


def test_a_store_refuses_a_scene_whose_text_changed(tmp_path):
    scene = tmp_path / "blade.toml"
    text = open(SCENE, encoding="utf-8").read()
    scene.write_text(text)
    store = str(tmp_path / "s.zarr")
    grid = {"load.fmax_over_fcr": [1.0, 2.0]}
    bladestab.study(str(scene), grid, "stability", executor=SERIAL, store=store)
    scene.write_text(text.replace("speed_rad_s = 300.0", "speed_rad_s = 200.0"))
    with pytest.raises(bladestab.InputError, match="scene's text is another"):
        bladestab.study(str(scene), grid, "stability", executor=SERIAL, store=store)


def test_a_store_resumed_on_other_workers_takes_its_chunks(tmp_path):
    # The default chunk follows the number of workers; a resumed study takes the store's.
    store = str(tmp_path / "s.zarr")
    grid = {"load.fmax_over_fcr": [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]}
    with concurrent.futures.ThreadPoolExecutor(2) as two:
        first = bladestab.study(SCENE, grid, "stability", executor=two, store=store)
    again = bladestab.study(SCENE, grid, "stability", executor=SERIAL, store=store)
    assert (zarr.open_group(store)["computed"][...] == 1).all()  # nothing computed twice
    assert again.equals(first)
    with pytest.raises(bladestab.InputError, match="chunk"):
        bladestab.study(SCENE, grid, "stability", executor=SERIAL, store=store, chunk=5)


def test_a_store_refuses_the_grid_keys_in_another_order(tmp_path):
    # The keys' order is the store's dimensions': the swapped study had written (150, 7)'s answer
    # into (350, 1)'s cell.
    store = str(tmp_path / "s.zarr")
    speeds, loads = [150.0, 350.0], [1.0, 7.0]
    bladestab.study(SCENE, {"operation.speed_rad_s": speeds, "load.fmax_over_fcr": loads}, "stability",
                    executor=SERIAL, store=store)
    with pytest.raises(bladestab.InputError, match="its grid is"):
        bladestab.study(SCENE, {"load.fmax_over_fcr": loads, "operation.speed_rad_s": speeds}, "stability",
                        executor=SERIAL, store=store)


def test_a_store_refuses_a_section_table_whose_contents_changed(tmp_path):
    fan = os.path.join(os.path.dirname(os.path.dirname(SCENE)), "fan_blade")
    scene, table = tmp_path / "blade.toml", tmp_path / "sections.csv"
    scene.write_text(open(os.path.join(fan, "blade.toml"), encoding="utf-8").read())
    text = open(os.path.join(fan, "sections.csv"), encoding="utf-8").read()
    table.write_text(text)
    store = str(tmp_path / "s.zarr")
    grid = {"model.terms": [8]}
    bladestab.study(str(scene), grid, "modes", executor=SERIAL, store=store)
    table.write_text(text.replace("0.2,0.0020462", "0.2,0.0030462"))
    with pytest.raises(bladestab.InputError, match="section table's contents are others"):
        bladestab.study(str(scene), grid, "modes", executor=SERIAL, store=store)


@pytest.mark.parametrize("grid", [{"load.fmax_over_fcr": [1.0, None]}, {"load.fmax_over_fcr": [[1.0, 2.0]]},
                                  {"point": [1.0]}, {"failed": [1.0]}])
def test_a_grid_value_or_key_a_store_cannot_hold_is_refused_before_anything_is_written(tmp_path, grid):
    store = tmp_path / "s.zarr"
    with pytest.raises(bladestab.InputError, match="grid"):
        bladestab.study(SCENE, grid, "stability", executor=SERIAL, store=str(store))
    assert not store.exists()


def test_a_store_path_that_holds_something_else_is_refused(tmp_path):
    (tmp_path / "file").write_text("x")
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "notes.txt").write_text("x")
    for store in ("file", "other"):
        with pytest.raises(bladestab.InputError, match=f"store .*{store}: not a Zarr group"):
            bladestab.study(SCENE, {"load.fmax_over_fcr": [1.0]}, "stability", executor=SERIAL,
                            store=str(tmp_path / store))
    (tmp_path / "empty").mkdir()  # an empty directory is a new store
    dataset = bladestab.study(SCENE, {"load.fmax_over_fcr": [1.0]}, "stability", executor=SERIAL,
                              store=str(tmp_path / "empty"))
    dataset.to_netcdf(tmp_path / "study.nc")  # its attributes are netCDF's kinds
    assert json.loads(dataset.attrs["bladestab_study"])["analysis"] == "stability"


def test_a_negative_answer_is_passed_false():
    # fails.toml fails its requirements (exit 1 from the program); passes.toml meets them.
    examples = os.path.join(os.path.dirname(os.path.dirname(SCENE)), "ci")
    for name, passed in (("fails", False), ("passes", True)):
        dataset = bladestab.study(os.path.join(examples, f"{name}.toml"), {"requirements.frequency_margin": [0.1]},
                                  "check", executor=SERIAL)
        assert dataset["passed"].values.tolist() == [passed]


@pytest.mark.parametrize("chunk", [0, -1, 2.5, True, "2"])
def test_a_chunk_is_a_whole_number_of_points(chunk):
    with pytest.raises(bladestab.InputError, match="chunk"):
        bladestab.study(SCENE, {"load.fmax_over_fcr": [1.0, 2.0]}, "stability", executor=SERIAL, chunk=chunk)


@pytest.mark.parametrize("values", ["sine", 3.0, {"a": 1}])
def test_grid_values_are_a_list(values):
    # A string was split into its letters ("s", "i", …), a number raised TypeError.
    with pytest.raises(bladestab.InputError, match="grid model.basis: .*a list of values"):
        bladestab.study(SCENE, {"model.basis": values}, "stability", executor=SERIAL)


def test_ctrl_c_at_a_terminal_ends_a_study_at_once(tmp_path):
    # A terminal's Ctrl-C reaches every process of the group, the workers too; one stopped while
    # sending its result had left the study waiting for it forever.
    study = tmp_path / "study.toml"
    speeds = ", ".join(str(150.0 + 5 * i) for i in range(60))
    study.write_text(f'scene = "{SCENE}"\nanalysis = "stability"\n[grid]\n"operation.speed_rad_s" = [{speeds}]\n'
                     '"load.fmax_over_fcr" = [1.0, 2.0, 4.0, 6.0]\n')
    store = tmp_path / "s.zarr"
    command = [sys.executable, "-m", "bladestab", "study", str(study), "--store", str(store), "--chunk", "2"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    while process.poll() is None:
        if os.path.exists(store / "computed" / ".zarray") and zarr.open_group(str(store))["computed"][...].sum() >= 4:
            os.killpg(process.pid, signal.SIGINT)
            break
        time.sleep(0.01)
    start = time.monotonic()
    _, err = process.communicate(timeout=30)
    assert process.returncode == 130 and "interrupted" in err, err
    assert time.monotonic() - start < 10
