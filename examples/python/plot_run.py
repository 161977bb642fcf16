#!/usr/bin/env python3
"""Plans a part program with Kontur's Python module and plots the path speed and the axis
accelerations against the machine's limits (matplotlib; no display needed with --output).

    python3 examples/python/plot_run.py                       # a shared CAM program, XYZ.ini
    python3 examples/python/plot_run.py PROGRAM.ngc --machine MACHINE.ini --output run.png

The package must be importable: after scripts/setup.sh it is installed for python3; from a build
tree, PYTHONPATH=build/python.
"""

import argparse
import pathlib
import sys

import numpy as np

import kontur

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data" / "gcode"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program", nargs="?", default=str(SHARED / "linuxcnc-tp" / "performance" / "3D_Chips.ngc"),
                        help="part program (default: a shared CAM program of short lines, LinuxCNC's performance test)")
    parser.add_argument("--machine", default=str(SHARED / "linuxcnc-tp" / "configs" / "XYZ.ini"),
                        help="machine file, LinuxCNC INI or Kontur TOML (default: the shared XYZ.ini)")
    parser.add_argument("--output", default="plot_run.png", help="the plot's file (PNG, SVG or PDF)")
    args = parser.parse_args()

    import matplotlib

    if args.output:
        matplotlib.use("Agg")  # a file, no window
    import matplotlib.pyplot as plt

    machine = kontur.Machine.load(args.machine)
    run = kontur.run(args.program, machine=machine)
    sp = run.setpoints
    T = machine.servo_period_s
    print(f"{args.program}: {len(sp)} setpoints at {T * 1e3:g} ms, {run.total_time_s:.3f} s, "
          f"{'PASS' if run.passed else 'FAIL'} (largest acceleration {run.summary['max_acceleration_ratio']:.3f} "
          f"of the limit, jerk {run.summary['max_jerk_ratio']:.3f})")

    fig = plt.figure(figsize=(15, 8), constrained_layout=True)
    grid = fig.add_gridspec(2, 2, width_ratios=[1, 1.4])
    ax_path = fig.add_subplot(grid[:, 0])
    ax_speed = fig.add_subplot(grid[0, 1])
    ax_acc = fig.add_subplot(grid[1, 1], sharex=ax_speed)
    points = ax_path.scatter(sp["x"], sp["y"], c=sp["v"], s=1, cmap="viridis")
    fig.colorbar(points, ax=ax_path, label="path speed [mm/s]")
    ax_path.set(xlabel="X [mm]", ylabel="Y [mm]", title=pathlib.Path(args.program).name, aspect="equal")

    ax_speed.plot(sp["t"], sp["v"], lw=0.8)
    ax_speed.set(xlabel="t [s]", ylabel="path speed v [mm/s]", title="planned path speed")

    # Axis accelerations by second differences of the setpoints, as the independent check measures them.
    for axis in machine.axes:
        name = axis["name"].lower()
        if name not in sp.dtype.names:
            continue
        acc = np.diff(sp[name], 2) / T**2
        line, = ax_acc.plot(sp["t"][1:-1], acc, lw=0.6, label=f"{axis['name']}")
        ax_acc.axhline(axis["max_acceleration"], color=line.get_color(), ls="--", lw=0.8)
        ax_acc.axhline(-axis["max_acceleration"], color=line.get_color(), ls="--", lw=0.8)
    ax_acc.set(xlabel="t [s]", ylabel="axis acceleration [mm/s²]", title="axis accelerations (dashed: limits)")
    ax_acc.legend(loc="upper right")

    fig.savefig(args.output, dpi=110)
    print(f"plot written to {args.output}")
    return 0 if run.passed else 4


if __name__ == "__main__":
    sys.exit(main())
