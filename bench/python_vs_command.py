#!/usr/bin/env python3
"""The Python module against the command and against a Python loop, in one script (docs/python.md):

* kontur.run on a program (default: the shared 3D_Chips.ngc on XYZ.ini), setpoints in memory as one
  array, against `kontur run` of the same program writing binary and CSV setpoint files
  (wall time, best of --repeat; the ratio is the target: at most 1.10);
* NurbsCurve.evaluate on 10^6 parameters against a Python loop calling it per parameter (the
  loop timed on 10^5 parameters and scaled; target: at least 20 times faster);
* peak memory (VmHWM of a child process) of kontur.run against kontur.run_iter, at a 0.1 ms
  servo period.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_vs_command.py [--program P --machine M]
"""

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

import kontur

ROOT = pathlib.Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "data" / "gcode"


def best(f, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def child_peak_mb(code):
    env = dict(os.environ, PYTHONPATH=str(ROOT / "build" / "python"))
    # VmHWM, the process's own high-water mark (ru_maxrss would carry this process's over the fork).
    probe = "\nprint([l.split()[1] for l in open('/proc/self/status') if l.startswith('VmHWM')][0])"
    out = subprocess.run([sys.executable, "-c", code + probe], capture_output=True, text=True, env=env,
                         check=True).stdout.split()
    return int(out[-1]) / 1024.0


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--program", default=str(SHARED / "3D_Chips.ngc"))
    p.add_argument("--machine", default=str(SHARED / "linuxcnc-tp" / "configs" / "XYZ.ini"))
    p.add_argument("--bin", default=str(ROOT / "build" / "bin" / "kontur"))
    p.add_argument("--repeat", type=int, default=3)
    a = p.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        def command(fmt):
            out = os.path.join(tmp, "sp." + fmt)
            subprocess.run([a.bin, "run", a.program, "--machine", a.machine, "-o", out, "--format",
                            "binary" if fmt == "bin" else "csv", "--summary", os.path.join(tmp, "s.json"), "--quiet"],
                           check=True)

        t_bin = best(lambda: command("bin"), a.repeat)
        t_csv = best(lambda: command("csv"), a.repeat)
    holder = {}
    t_py = best(lambda: holder.__setitem__("r", kontur.run(a.program, machine=a.machine)), a.repeat)
    r = holder["r"]
    print(f"run {pathlib.Path(a.program).name}: {len(r.setpoints)} setpoints ({r.setpoints.nbytes / 1e6:.1f} MB array)")
    print(f"  kontur run -o FILE --format binary  {t_bin:8.3f} s")
    print(f"  kontur run -o FILE (csv)            {t_csv:8.3f} s")
    print(f"  kontur.run (one numpy array)        {t_py:8.3f} s   ratio to binary {t_py / t_bin:.3f}, to csv {t_py / t_csv:.3f}")

    curve = kontur.read_curve(ROOT / "examples" / "curves" / "seed_example1.json")
    u = np.linspace(curve.u_min, curve.u_max, 1_000_000)
    t_vec = best(lambda: curve.evaluate(u), a.repeat)
    few = u[::10]
    t_loop = best(lambda: [curve.evaluate(x) for x in few], 1) * 10
    print(f"evaluate 10^6 parameters: vectorised {t_vec * 1e3:.1f} ms, Python loop {t_loop:.2f} s "
          f"(10^5 timed x 10): {t_loop / t_vec:.0f} times faster")

    # Memory at a 0.1 ms servo period (ten times the setpoints): one array against chunks.
    prog = repr(a.program)
    setup = f"import kontur\nm = kontur.Machine.load({a.machine!r})\nm.servo_period_s = 1e-4\n"
    base = child_peak_mb("import kontur, numpy")
    peak_run = child_peak_mb(setup + f"r = kontur.run({prog}, machine=m)\nprint(len(r.setpoints))")
    peak_iter = child_peak_mb(setup + f"n = 0\nfor c in kontur.run_iter({prog}, machine=m, chunk=10000): n += len(c)")
    print(f"peak memory at 0.1 ms: python with numpy {base:.0f} MB, kontur.run {peak_run:.0f} MB, "
          f"kontur.run_iter(chunk=10000) {peak_iter:.0f} MB")


if __name__ == "__main__":
    main()
