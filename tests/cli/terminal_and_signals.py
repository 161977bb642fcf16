#!/usr/bin/env python3
"""`kontur run` as a person meets it (issue 19), with the standard library only:

* on a terminal (a pseudo-terminal): the progress bar is drawn on stderr for a run longer than a
  second, PASS is coloured, NO_COLOR turns the colour off; into a pipe: no bar, no colour;
* Ctrl-C (SIGINT) and SIGTERM stop a run with exit 130 / 143 and one line naming what was not
  written; an earlier output file is left as it was and no temporary file is left behind.

    terminal_and_signals.py KONTUR_BINARY SHARED_DIR
"""

import os
import pty
import select
import signal
import subprocess
import sys
import tempfile
import time

KONTUR, SHARED = sys.argv[1], sys.argv[2]
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHIPS = os.path.join(SHARED, "data", "gcode", "3D_Chips.ngc")
EXAMPLE = os.path.join(ROOT, "examples", "programs", "square_arc.ngc")
failures = []


def check(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def in_terminal(args, env=None, until=None, then_signal=None, timeout=60.0):
    """Runs the command with stdout and stderr on a pseudo-terminal; returns (exit, output). With
    `until`, sends `then_signal` once the output contains it."""
    pid, fd = pty.fork()
    if pid == 0:
        os.execve(KONTUR, [KONTUR, *args], env if env is not None else dict(os.environ))
    out, sent, deadline = b"", False, time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], 0.1)
        if ready:
            try:
                chunk = os.read(fd, 65536)
            except OSError:
                break
            if not chunk:
                break
            out += chunk
        if until and not sent and until in out:
            os.kill(pid, then_signal)
            sent = True
    else:
        os.kill(pid, signal.SIGKILL)
    _, status = os.waitpid(pid, 0)
    os.close(fd)
    return os.waitstatus_to_exitcode(status), out.decode(errors="replace")


with tempfile.TemporaryDirectory() as work:
    slow = os.path.join(work, "slow.toml")  # 3D_Chips at 10 us: seconds of work
    with open(slow, "w") as f:
        f.write("servo_period_s = 0.00001\n")
    env = {k: v for k, v in os.environ.items() if k != "NO_COLOR"}

    # The progress bar on a terminal, then Ctrl-C.
    code, out = in_terminal(["run", CHIPS, "--machine", slow], env=env, until=b"kontur run: running",
                            then_signal=signal.SIGINT)
    check("kontur run: running" in out and "line " in out, "a terminal gets the progress bar")
    check(code == 130, f"SIGINT exits 130 (got {code})")
    check("stopped by SIGINT" in out, "SIGINT says it stopped")

    # Colour on a terminal, none with NO_COLOR or into a pipe.
    code, out = in_terminal(["run", EXAMPLE], env=env)
    check(code == 0 and "\x1b[1;32mPASS\x1b[0m" in out, "PASS is green on a terminal")
    code, out = in_terminal(["run", EXAMPLE], env=dict(env, NO_COLOR="1"))
    check(code == 0 and "PASS" in out and "\x1b[" not in out, "NO_COLOR: no escape sequence")
    p = subprocess.run([KONTUR, "run", EXAMPLE], capture_output=True, text=True, env=env)
    check(p.returncode == 0 and "PASS" in p.stdout and "\x1b[" not in p.stdout + p.stderr,
          "into a pipe: the short summary on stdout, no colour, no bar")
    check("-o FILE" in p.stdout and "t,x,y,z" not in p.stdout, "without -o: no setpoints, says how to write them")

    # SIGTERM while a file is written: the earlier file stays, no temporary file is left.
    target = os.path.join(work, "out.csv")
    with open(target, "w") as f:
        f.write("earlier content\n")
    proc = subprocess.Popen([KONTUR, "run", CHIPS, "--machine", slow, "-o", target, "--summary",
                             os.path.join(work, "out.json")], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    proc.send_signal(signal.SIGTERM)
    stdout, stderr = proc.communicate(timeout=60)
    check(proc.returncode == 143, f"SIGTERM exits 143 (got {proc.returncode})")
    check(f"stopped by SIGTERM: {target}" in stderr and "not written" in stderr, "the line names what was not written")
    with open(target) as f:
        check(f.read() == "earlier content\n", "the earlier output is untouched")
    check(sorted(os.listdir(work)) == ["out.csv", "slow.toml"], f"no temporary file left ({sorted(os.listdir(work))})")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
