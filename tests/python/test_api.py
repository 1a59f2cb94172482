"""The Python API against the program: the same answer for the same run (to_dict() equals the
program's JSON), bad input as InputError naming the key, scenes from text and dicts, charts."""

import os
import tomllib

import numpy as np
import pytest

import bladestab
from conftest import SCENE, run_program, without_wall_times


def test_stability_equals_the_program():
    r = bladestab.stability(SCENE, tolerance=1e-6, **{"load.fmax_over_fcr": 3.0})
    assert r.to_dict() == run_program("stability", SCENE, "--tolerance", "1e-06", "--set", "load.fmax_over_fcr=3.0")
    # The fields as NumPy: |ρ| of the multipliers, the largest of which is max|ρ| within its estimate.
    assert isinstance(r.multipliers, np.ndarray) and r.multipliers.dtype == complex
    assert abs(np.abs(r.multipliers).max() - r.max_abs_multiplier) <= r.error_estimate


def test_boundaries_equals_the_program():
    r = bladestab.boundaries(SCENE, at_theta=300, **{"model.terms": 8})
    assert r.to_dict() == run_program("boundaries", SCENE, "--at-theta", "300", "--set", "model.terms=8")


def test_map_equals_the_program(tmp_path):
    grid = dict(plane="theta-fmax", theta="100:1000:3", fmax="0:5:3", trace=5, resolution="4x4")
    r = bladestab.map(SCENE, **grid)
    args = [f"--{k}={v}" for k, v in grid.items()]
    assert r.to_dict() == run_program("map", SCENE, *args, "--out", str(tmp_path), "--chart", "none")
    assert r.document is not None and r.grid["max_abs_multiplier"].shape == (3, 3)


def test_transient_equals_the_program(tmp_path):
    r = bladestab.transient(SCENE, revolutions=0.5)
    assert without_wall_times(r.to_dict()) == without_wall_times(
        run_program("transient", SCENE, "--revolutions", "0.5", "--out", str(tmp_path), "--chart", "none"))
    assert r.tip_lateral_m.shape == r.revolutions.shape  # the history, from the file the chart is drawn from


def test_scene_as_text_and_dict_gives_the_same_answer():
    with open(SCENE, "rb") as fh:
        tables = tomllib.load(fh)
    with open(SCENE, encoding="utf-8") as fh:
        text = fh.read()
    from_file = bladestab.stability(SCENE).to_dict()
    for scene in (text, tables):
        answer = bladestab.stability(scene).to_dict()
        assert answer.pop("scene") in ("<text>", "<dict>")
        assert answer == {k: v for k, v in from_file.items() if k != "scene"}


@pytest.mark.parametrize("options, named", [
    ({"tolerance": 2.0}, "--tolerance"),
    ({"load.fmax_over_fcr": -1.0}, "load.fmax_over_fcr"),
    ({"model.terms": 2.5}, "model.terms"),
    ({"toleranse": 1e-6}, "toleranse"),
    ({"format": "table"}, "format"),
    ({"harmonics": "x"}, "--harmonics"),
    ({"tolerance": False}, "--tolerance"),
    ({"tolerance": True}, "--tolerance"),
])
def test_bad_input_raises_input_error_naming_the_key(options, named):
    with pytest.raises(bladestab.InputError, match=named.replace(".", r"\.")) as error:
        bladestab.stability(SCENE, **options)
    assert isinstance(error.value, ValueError) and "\n" not in str(error.value)


def test_a_flag_takes_a_boolean_and_none_leaves_an_option_default():
    with pytest.raises(bladestab.InputError, match="follower = 1: a flag, True or False"):
        bladestab.transient(SCENE, follower=1)
    assert bladestab.stability(SCENE, tolerance=None).to_dict() == bladestab.stability(SCENE).to_dict()


def test_missing_scene_file_is_input_error():
    with pytest.raises(bladestab.InputError, match="no-such-scene.toml"):
        bladestab.modes("no-such-scene.toml")


def test_progress_callback_sees_the_run_and_can_stop_it():
    seen = []
    bladestab.stability(SCENE, progress=lambda label, done, total: seen.append((label, done, total)))
    assert seen and seen[-1][1] == seen[-1][2] and all(label.startswith("stability") for label, _, _ in seen)

    class Enough(Exception):
        pass

    def stop(label, done, total):
        raise Enough(label)

    with pytest.raises(Enough):
        bladestab.map(SCENE, plane="theta-fmax", theta="100:1000:9", fmax="0:5:9", progress=stop)


def test_check_answer_is_a_result_not_an_error():
    ci = os.path.join(os.path.dirname(os.path.dirname(SCENE)), "ci")
    assert bladestab.check(os.path.join(ci, "passes.toml")).passed
    failing = bladestab.check(os.path.join(ci, "fails.toml"))
    assert not failing.passed
    assert without_wall_times(failing.to_dict()) == without_wall_times(
        run_program("check", os.path.join(ci, "fails.toml"), expect_status=1))


def test_a_crosscheck_that_disagrees_is_a_negative_result():
    # 30 Hz pulses at 47.7 revolutions a second: no revolution repeats the last, so the transient's
    # growth is not resolved and the point cannot agree (exit status 1 on the command line).
    args = {"points": 1, "revolutions": 6, "model.terms": 4, "load.pulse_frequency_hz": 30,
            "load.profile": "rectangular", "load.contact_time_rev": 0.05}
    r = bladestab.crosscheck(SCENE, **args)
    assert not r.passed and "1 of 1 points disagree" in r.failure
    assert r.to_dict() == run_program("crosscheck", SCENE, "--points", "1", "--revolutions", "6", "--set", "model.terms=4",
                                      "--set", "load.pulse_frequency_hz=30", "--set", "load.profile=rectangular",
                                      "--set", "load.contact_time_rev=0.05", expect_status=1)


def test_plot_draws_the_programs_chart(tmp_path):
    grid = ["--plane", "theta-fmax", "--theta", "100:1000:3", "--fmax", "0:5:3", "--trace", "5", "--resolution", "4x4"]
    r = bladestab.map(SCENE, plane="theta-fmax", theta="100:1000:3", fmax="0:5:3", trace=5, resolution="4x4")
    r.plot(tmp_path / "python.png")
    run_program("map", SCENE, *grid, "--out", str(tmp_path), "--chart", "png")
    with open(tmp_path / "python.png", "rb") as a, open(tmp_path / "map_theta_fmax.png", "rb") as b:
        assert a.read() == b.read()


def test_a_flag_on_by_default_is_turned_off_by_false_and_out_none_writes_nowhere(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = bladestab.transient(SCENE, revolutions=1, threads=1, error_estimate=False, out=None)
    program = run_program("transient", SCENE, "--revolutions", "1", "--threads", "1", "--no-error-estimate", "--chart",
                          "none", "--out", str(tmp_path / "program"))
    assert "error_estimate" not in r.to_dict() and "error_estimate" not in program
    assert r.to_dict()["peak_tip_lateral_m"] == program["peak_tip_lateral_m"]
    assert sorted(os.listdir(tmp_path)) == ["program"] and r.files == []


def test_numpy_arrays_are_lists_and_a_missing_path_with_an_equals_sign_is_a_path():
    assert bladestab.stability(SCENE, **{"load.fmax_over_fcr": np.float64(3.0)}).to_dict() == \
        bladestab.stability(SCENE, **{"load.fmax_over_fcr": 3.0}).to_dict()
    with pytest.raises(bladestab.InputError, match="load.fmax_over_fcr"):
        bladestab.stability(SCENE, **{"load.fmax_over_fcr": np.array([1.0, 2.0])})
    with pytest.raises(bladestab.InputError, match="fmax=3/blade.toml"):
        bladestab.stability("no-such-study/fmax=3/blade.toml")
    with pytest.raises(bladestab.InputError, match="progress: must be callable"):
        bladestab.stability(SCENE, progress=5)
    with pytest.raises(bladestab.InputError, match="load.bogus = None"):
        bladestab.stability({"load": {"bogus": None}})


def test_a_result_is_a_read_only_mapping_of_its_fields():
    r = bladestab.stability(SCENE)
    assert "stable" in r and "no-such-field" not in r and r.get("no-such-field") is None
    assert list(r) == list(r.keys()) and len(r) == len(r.to_dict()) and r.get("stable") == r.stable
    assert all(field == "…" or "=" in field for field in repr(r).rstrip(">").split(": ", 1)[1].split(", "))


def test_a_scene_path_that_starts_with_a_dash_is_the_scene(tmp_path, monkeypatch):
    # It was read as an option: "-blade.toml" gave "scene is required", "-h" the parser's own text.
    monkeypatch.chdir(tmp_path)
    with open(SCENE, encoding="utf-8") as fh:
        (tmp_path / "-blade.toml").write_text(fh.read())
    assert bladestab.stability("-blade.toml").to_dict() == bladestab.stability(SCENE).to_dict() | {"scene": "-blade.toml"}
    with pytest.raises(bladestab.InputError, match="-h: cannot read the scene file"):
        bladestab.stability("-h")
