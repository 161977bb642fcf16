"""The example script runs (without a display) and writes its plot."""

import os
import subprocess
import sys

import kontur


def test_plot_run_example(root, shared, tmp_path):
    out = tmp_path / "plot.png"
    package_root = os.path.dirname(os.path.dirname(os.path.abspath(kontur.__file__)))
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=package_root)
    p = subprocess.run(
        [sys.executable, str(root / "examples" / "python" / "plot_run.py"), "--output", str(out)],
        capture_output=True, text=True, env=env, cwd=tmp_path,
    )
    assert p.returncode == 0, p.stderr
    assert out.stat().st_size > 10_000
    assert "setpoints" in p.stdout
