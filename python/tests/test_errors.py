"""Failures raise the classes of mechdiff.errors with the Rust library's message and its
parts: file, line and column for the file's errors, the drive position for the motion's."""

import _thread
import threading
import time

import numpy as np
import pytest

import mechdiff
from mechdiff import errors


def norton_text(norton_path, old, new):
    text = norton_path.read_text()
    assert old in text
    return text.replace(old, new, 1)


def line_of(text, needle):
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def test_a_misspelt_key_is_a_syntax_error_at_its_line(norton_path):
    text = norton_text(norton_path, "speed = 10", "sped = 10")
    with pytest.raises(errors.SceneSyntaxError) as caught:
        mechdiff.parse(text, file="norton.toml")
    e = caught.value
    assert isinstance(e, ValueError) and isinstance(e, errors.MechdiffError)
    assert (e.kind, e.file, e.line) == ("Syntax", "norton.toml", line_of(text, "sped = 10"))
    assert str(e).startswith(f"norton.toml:{e.line}:{e.column}: ")
    assert "sped" in str(e)


def test_an_unknown_point_is_an_invalid_scene_error_naming_the_points(norton_path):
    text = norton_text(norton_path, 'circles = ["A", "O4"]', 'circles = ["A", "O5"]')
    with pytest.raises(errors.InvalidSceneError) as caught:
        mechdiff.parse(text, file="norton.toml")
    e = caught.value
    assert e.kind == "UnknownPoint" and e.line == line_of(text, '"O5"')
    assert "`O5`" in str(e) and "the points are: A, B, O2, O4" in str(e)


def test_a_setting_of_no_parameter_is_a_setting_error(norton_path):
    with pytest.raises(errors.SettingError) as caught:
        mechdiff.load(norton_path, zz=1)
    assert "no parameter `zz`" in str(caught.value) and "a, b, c, d, theta" in str(caught.value)


def test_a_position_past_the_limit_is_a_motion_error_at_a_drive_position_in_degrees(norton_path):
    scene = mechdiff.load(norton_path)
    # The crank rocks within ±116°: the loop stops closing between 100° and 150°.
    with pytest.raises(errors.MotionError) as caught:
        scene.run(positions=[100.0, 150.0])
    e = caught.value
    assert isinstance(e, (errors.BlockedError, errors.UnassemblableError)), type(e)
    assert e.file.endswith("norton_four_bar.toml")
    assert e.position.endswith("deg") and 100 < float(e.position.split()[0]) < 150


def test_a_variant_that_fails_in_a_study_keeps_its_class_and_settings(norton_path):
    text = norton_path.read_text() + '\n[sensitivity]\ncolumns = ["d(psi)/d(b)"]\n'
    # b = 0.2 m cannot reach: the nominal run fails, with the file named.
    with pytest.raises(errors.MechdiffError) as caught:
        mechdiff.parse(text, file="n.toml", b=0.2).sensitivity()
    assert caught.value.file == "n.toml" or "n.toml" in str(caught.value)


def test_bad_positions_and_arguments_are_refused_with_what_to_do(norton_path):
    scene = mechdiff.load(norton_path)
    with pytest.raises(errors.InvalidSceneError) as caught:
        scene.run(positions=[0.0, np.nan])
    assert "drive position 1 (from 0) is NaN" in str(caught.value)
    assert caught.value.line == line_of(norton_path.read_text(), "[drive]")
    with pytest.raises(errors.ArgumentError, match="evaluator"):
        scene.run(evaluator="fast")
    with pytest.raises(errors.ArgumentError, match="no column `nu`"):
        scene.run_variants({"b": [1.85]}, columns=["nu"])
    with pytest.raises(errors.SceneFileError) as caught:
        mechdiff.load(norton_path.parent / "no_such_scene.toml")
    assert isinstance(caught.value, OSError) and "no_such_scene.toml" in str(caught.value)


def test_each_kind_has_its_own_class_under_its_group_with_file_line_and_column(norton_path):
    text = norton_text(norton_path, 'circles = ["A", "O4"]', 'circles = ["A", "O5"]')
    with pytest.raises(errors.UnknownPointError) as caught:
        mechdiff.parse(text, file="norton.toml")
    e = caught.value
    assert isinstance(e, errors.InvalidSceneError) and isinstance(e, ValueError)
    assert (e.kind, e.file, e.line) == ("UnknownPoint", "norton.toml", line_of(text, '"O5"'))
    # The column is that of the name in its line (from 1).
    assert text.splitlines()[e.line - 1][e.column - 1 :].startswith('"O5"')
    assert str(e).startswith(f"norton.toml:{e.line}:{e.column}: ")
    # Every class is a MechdiffError; the package exports them all.
    for name in errors.__all__:
        assert issubclass(getattr(errors, name), errors.MechdiffError), name
        assert getattr(mechdiff, name) is getattr(errors, name)


def test_ctrl_c_interrupts_a_long_run_within_a_chunk_of_positions(norton_path):
    scene = mechdiff.load(norton_path)
    # The cost of a position on this machine (a debug build in CI: some microseconds).
    sample = np.linspace(-100.0, 100.0, 20_000)
    start = time.perf_counter()
    scene.run(positions=sample)
    per_position = (time.perf_counter() - start) / len(sample)
    count = 1_000_000  # the most positions a run takes
    whole = per_position * count
    if whole < 2.0:
        pytest.skip(f"a run of 10⁶ positions takes {whole:.2f} s here: too short to interrupt")
    delay = 0.2
    # As Ctrl-C does: the SIGINT handler's flag set while the main thread is inside Rust.
    timer = threading.Timer(delay, _thread.interrupt_main)
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.run(positions=np.linspace(-100.0, 100.0, count))
    elapsed = time.perf_counter() - start
    timer.join()
    # Ctrl-C is looked for every 1024 positions: it arrives within a chunk of the signal;
    # 1 s more for the run's set-up before its first position and a busy machine, and in
    # any case long before the run would have ended.
    assert elapsed < delay + 1.0 + 1024 * per_position, (elapsed, per_position)
    assert elapsed < 0.5 * whole, (elapsed, whole)
