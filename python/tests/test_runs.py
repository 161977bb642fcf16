"""Machine, check, run, run_iter and verify against the command on the same inputs: the same JSON
(summary, check), the same setpoints bit for bit (the command's binary file), the same messages."""

import json
import os
import pathlib

import numpy as np
import pytest

import kontur


@pytest.fixture(scope="module")
def full_xy(shared):
    return shared / "data" / "gcode" / "linuxcnc-tp" / "arc-feed" / "full_xy.ngc"


@pytest.fixture(scope="module")
def xyz_ini(shared):
    return shared / "data" / "gcode" / "linuxcnc-tp" / "configs" / "XYZ.ini"


def read_binary_setpoints(path, axes="XYZ"):
    data = pathlib.Path(path).read_bytes()
    header = 24 if axes == "XYZ" else 40
    return np.frombuffer(data[header:], dtype=kontur.setpoint_dtype(axes))


def test_machines(xyz_ini, command):
    d = kontur.Machine.load()
    assert d.source == "embedded default"
    assert [a["name"] for a in d.axes] == ["X", "Y", "Z"]
    assert d.servo_period_s == 0.001
    m = kontur.Machine.load(xyz_ini)
    assert m.source == str(xyz_ini)
    assert m.to_toml() == command("machine", xyz_ini).stdout
    c = m.copy()
    c.set_axis("X", max_acceleration=100.0)
    assert c.axes[0]["max_acceleration"] == 100.0 and m.axes[0]["max_acceleration"] != 100.0
    with pytest.raises(kontur.InputError) as e:
        c.set_axis("X", max_velocity=0.0)
    assert "X" in str(e.value)
    with pytest.raises(kontur.InputError) as e:
        c.set_axis("Q", max_velocity=1.0)
    assert e.value.rule == "axis-name"
    with pytest.raises(kontur.InputError) as e:
        kontur.Machine.load(xyz_ini.parent / "missing.ini")
    assert "missing.ini" in str(e.value)
    with pytest.raises(kontur.InputError):
        c.dialect = "klingon"


def test_check_equals_the_command(full_xy, command):
    assert kontur.check(full_xy) == json.loads(command("check", full_xy, "--json").stdout)
    quiet = kontur.check(full_xy, blocks=False)
    assert quiet["blocks"] == [] and quiet["totals"] == json.loads(command("check", full_xy, "--json").stdout)["totals"]


def test_run_equals_the_command(full_xy, xyz_ini, command, tmp_path):
    out, summary = tmp_path / "sp.bin", tmp_path / "summary.json"
    command("run", full_xy, "--machine", xyz_ini, "-o", out, "--format", "binary", "--summary", summary, "--quiet")
    r = kontur.run(full_xy, machine=xyz_ini)
    assert r.summary == json.loads(summary.read_text())
    expected = read_binary_setpoints(out)
    assert r.setpoints.dtype.names == ("t", "x", "y", "z", "v", "block")
    assert len(r.setpoints) == len(expected) == r.summary["setpoints"]
    assert r.setpoints.tobytes() == expected.tobytes()  # bit for bit
    assert r.passed and r.summary["passed"]
    assert r.total_time_s == r.setpoints["t"][-1]
    # The same with a Machine object, and options as the command's flags.
    m = kontur.Machine.load(xyz_ini)
    command("run", full_xy, "--machine", xyz_ini, "-o", out, "--format", "binary", "--summary", summary, "--quiet",
            "--no-blend", "--time-optimal")
    r2 = kontur.run(str(full_xy), m, blend=False, time_optimal=True)
    assert r2.summary == json.loads(summary.read_text())
    assert r2.setpoints.tobytes() == read_binary_setpoints(out).tobytes()


def test_run_without_check_has_no_summary(root):
    r = kontur.run(root / "examples" / "programs" / "square_arc.ngc", check=False)
    assert r.summary is None and len(r) > 0
    assert np.all(np.isfinite(r.setpoints["x"]))


def test_run_iter_equals_run(full_xy, xyz_ini):
    whole = kontur.run(full_xy, machine=xyz_ini)
    it = kontur.run_iter(full_xy, machine=xyz_ini, chunk=1000)
    chunks = list(it)
    assert all(len(c) == 1000 for c in chunks[:-1]) and 0 < len(chunks[-1]) <= 1000
    assert np.concatenate(chunks).tobytes() == whole.setpoints.tobytes()
    assert it.summary == whole.summary and it.passed and it.total_time_s == whole.total_time_s
    # Stopped early: the run's thread ends, nothing is left behind.
    with kontur.run_iter(full_xy, machine=xyz_ini, chunk=100) as early:
        first = next(early)
        assert len(first) == 100
    assert early.summary is None


def test_verify_arrays_and_files(full_xy, xyz_ini, command, tmp_path):
    r = kontur.run(full_xy, machine=xyz_ini)
    s = kontur.verify(full_xy, r.setpoints, machine=xyz_ini)
    assert s["passed"]
    assert s["max_path_error_mm"] == r.summary["max_path_error_mm"]
    # Another planner's setpoints: no speed, no block; the checker finds its own way.
    plain = np.zeros(len(r.setpoints), dtype=[("t", "f8"), ("x", "f8"), ("y", "f8"), ("z", "f8")])
    for name in plain.dtype.names:
        plain[name] = r.setpoints[name]
    assert kontur.verify(full_xy, plain, machine=xyz_ini)["passed"]
    # A setpoint pushed 0.05 mm off the path is found.
    bad = r.setpoints.copy()
    bad["z"][len(bad) // 2] += 0.05  # out of the plane the whole path lies in: 0.05 mm from it
    s_bad = kontur.verify(full_xy, bad, machine=xyz_ini)
    assert not s_bad["passed"] and abs(s_bad["max_path_error_mm"] - 0.05) < 1e-9
    # A file: the same summary as `kontur verify`.
    csv, summary = tmp_path / "sp.csv", tmp_path / "verify.json"
    command("run", full_xy, "--machine", xyz_ini, "-o", csv, "--quiet")
    command("verify", full_xy, csv, "--machine", xyz_ini, "--summary", summary, "--quiet")
    assert kontur.verify(full_xy, csv, machine=xyz_ini) == json.loads(summary.read_text())
    with pytest.raises(kontur.InputError):
        kontur.verify(full_xy, np.zeros(3), machine=xyz_ini)


def test_program_errors_are_the_commands(tmp_path, command):
    program = tmp_path / "broken.ngc"
    program.write_text("G21 G90\nG1 X10 F600\nG1 X20 Y\nM2\n")
    expected = command("check", program, check=False)
    assert expected.returncode == 1
    for call in (kontur.check, kontur.run):
        with pytest.raises(kontur.InputError) as e:
            call(program)
        assert str(e.value) in expected.stderr
        assert f"{program}:3" in str(e.value)
    missing = tmp_path / "missing.ngc"
    with pytest.raises(kontur.InputError) as e:
        kontur.run(missing)
    assert str(e.value) in command("run", missing, "-o", tmp_path / "x.csv", check=False).stderr
    # The stream reports the same error when iterated.
    with pytest.raises(kontur.InputError):
        list(kontur.run_iter(program))
    with pytest.raises(kontur.InputError) as e:
        kontur.run(program, dialect="klingon")
    assert e.value.rule == "dialect-name"


def test_bad_arguments_never_crash(root):
    program = root / "examples" / "programs" / "square_arc.ngc"
    with pytest.raises(TypeError):
        kontur.run(program, machine=42)
    with pytest.raises(TypeError):
        kontur.run(program, no_such_option=True)
    with pytest.raises(kontur.InputError):
        kontur.run_iter(program, chunk=0)
    m = kontur.Machine.load()
    m.servo_period_s = 0.0
    with pytest.raises(kontur.InputError) as e:
        kontur.run(program, machine=m)
    assert "servo" in str(e.value).lower() or "period" in str(e.value).lower()


def test_a_signal_stops_a_long_run(shared):
    """Ctrl-C (SIGINT) reaches Python within a run: the run stops and the handler's exception
    propagates (KeyboardInterrupt by default; here a test's own, so that a late signal cannot stop
    pytest itself)."""
    import signal
    import threading
    import time

    class Stopped(Exception):
        pass

    def handler(signum, frame):
        raise Stopped()

    m = kontur.Machine.load(shared / "data" / "gcode" / "linuxcnc-tp" / "configs" / "XYZ.ini")
    m.servo_period_s = 1e-4  # 1.1 million setpoints: seconds of work
    returned = False
    old = signal.signal(signal.SIGINT, handler)
    try:
        timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
        timer.start()
        with pytest.raises(Stopped):
            kontur.run(shared / "data" / "gcode" / "3D_Chips.ngc", machine=m)
            returned = True
            time.sleep(10)  # (the signal would come here)
        timer.join()
    finally:
        signal.signal(signal.SIGINT, old)
    assert not returned
