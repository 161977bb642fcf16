#!/usr/bin/env python3
"""Kontur's property test: seeded random valid programs, each on its own random machine.

    run_property.py --first S --count N [--timeout SEC] [--jobs J] [--kontur PATH] [--keep DIR]
    run_property.py --shrink SEED [--timeout SEC] [--kontur PATH] [--keep DIR]

For each seed S .. S+N-1, generate.py writes a case (program.ngc and machine.toml or
machine.ini) into a temporary folder and `kontur run program --machine machine -o out.csv
--summary s.json --quiet` runs on it under a timeout. Each case is one of

    PASS       exit 0, the summary's check passed, no NaN / inf in the setpoints, and the runner's
               own finite differences of the setpoints within the machine's limits;
    REFUSED    exit 1 with a message on stderr (the generator makes valid programs, so each one is
               listed: either the generator or Kontur is wrong);
    VIOLATION  exit 4 (Kontur's own check found a limit exceeded or a setpoint off the path), or
               exit 0 but the summary not passed, or the runner's own check of the setpoints finds
               an axis velocity, acceleration or jerk above the limit (Kontur's check missed it);
    CRASH      a signal, exit 3 (internal error) or any other code, exit 1 without a message, NaN or
               inf in the setpoints, a missing or unreadable summary;
    HANG       still running after --timeout seconds (killed), or a crawl: a passed run whose
               motion takes over 10 times the generator's estimate plus 30 s.

Notes (not failures) are printed too: a program not read as LinuxCNC (dialect detection).

Ends with `property: N cases, P passed, R refused, V violations, C crashes, H hangs` and exits 1
when there is a VIOLATION, CRASH or HANG. Every failure is printed with its seed and the command
that reproduces it. `--shrink SEED` deletes lines of that seed's program while the failure stays
of the same kind and prints the smallest program (and keeps it with --keep).

Python 3 standard library only.
"""
import argparse
import concurrent.futures
import json
import math
import operator
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import generate  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
FAILING = ("VIOLATION", "CRASH", "HANG")
# The runner's own check: a ratio above 1 + this (after the rounding noise of the differences) is a
# violation Kontur's check should have reported.
OWN_CHECK_SLACK = 1e-3
# Above this many setpoints the own check is skipped (pure Python: ~4 us a setpoint), with a note.
OWN_CHECK_MAX_ROWS = 1_500_000


def normalise(msg):
    """A failure's kind: its message without paths, line:column and numbers."""
    msg = re.sub(r"\S*/(program\.ngc|machine\.(toml|ini)|out\.csv|s\.json)", r"\1", msg)
    msg = re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "#", msg)
    return re.sub(r"\s+", " ", msg).strip()


def own_check(csv_path, limits):
    """Backward differences of the setpoints against the axis limits, as docs/setpoints.md defines
    them. Returns (worst ratios per quantity, list of violations, nan_found); a ratio counts as a
    violation above 1 + OWN_CHECK_SLACK after the rounding noise of the differences."""
    T = limits["servo_period_s"]
    axes = limits["axes"]
    with open(csv_path, "rb") as f:
        data = f.read()
    low = data.lower()
    if b"nan" in low or b"inf" in low:
        return None, [], True
    rows = data.split(b"\n")
    header = rows[0].decode().split(",")
    del data, low
    if len(rows) > OWN_CHECK_MAX_ROWS:
        return "skipped", [], False
    cols = [header.index(a) for a in ("x", "y", "z")]
    if cols != [1, 2, 3]:
        raise ValueError(f"unexpected CSV header {header}")
    xyz = ([], [], [])
    ax, ay, az = (c.append for c in xyz)
    for r in rows[1:]:
        if r:
            p = r.split(b",", 4)
            ax(float(p[1]))
            ay(float(p[2]))
            az(float(p[3]))
    del rows
    worst = {"velocity": (0.0, None, None), "acceleration": (0.0, None, None), "jerk": (0.0, None, None)}
    violations = []
    eps = 2.3e-16
    sub = operator.sub
    for name, xs in zip(("X", "Y", "Z"), xyz):
        if len(xs) < 2:
            continue
        xmax = max(map(abs, xs))
        d1 = list(map(sub, xs[1:], xs[:-1]))
        d2 = list(map(sub, d1[1:], d1[:-1]))
        d3 = list(map(sub, d2[1:], d2[:-1]))
        lim = axes[name]
        for q, d, limit, scale, noise in (("velocity", d1, lim["max_velocity"], T, 2),
                                           ("acceleration", d2, lim["max_acceleration"], T * T, 4),
                                           ("jerk", d3, lim["max_jerk"], T * T * T, 8)):
            if not d:
                continue
            m = max(map(abs, d))
            r = m / scale / limit
            k = [abs(x) for x in d].index(m) + {"velocity": 1, "acceleration": 2, "jerk": 3}[q]
            if r > worst[q][0]:
                worst[q] = (r, name, k)
            if m / scale > limit * (1 + OWN_CHECK_SLACK) + noise * eps * xmax / scale:
                violations.append((q, name, k, r))
    return worst, violations, False


def run_case(seed, kontur, timeout, workdir=None, own=True, program_text=None):
    """Generates (or takes program_text for) the case of `seed` in workdir and classifies it.
    Returns a dict: seed, cls, kind, detail, dir, seconds, notes."""
    d = workdir or tempfile.mkdtemp(prefix=f"kontur_prop_{seed}_")
    program, machine = generate.generate(seed, d)
    if program_text is not None:
        with open(program, "w") as f:
            f.write(program_text)
    with open(os.path.join(d, "case.json")) as f:
        case = json.load(f)
    out = os.path.join(d, "out.csv")
    summ = os.path.join(d, "s.json")
    for p in (out, summ):
        if os.path.exists(p):
            os.remove(p)
    cmd = [kontur, "run", program, "--machine", machine, "-o", out, "--summary", summ, "--quiet"]
    res = {"seed": seed, "dir": d, "cmd": cmd, "notes": [], "elements": case["elements"]}
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
    except subprocess.TimeoutExpired:
        res.update(cls="HANG", kind="HANG", detail=f"still running after {timeout} s", seconds=timeout)
        return res
    res["seconds"] = time.monotonic() - t0
    err = p.stderr.decode(errors="replace").strip()
    errors = [l for l in err.splitlines() if "error" in l]
    rc = p.returncode
    res["rc"] = rc
    if rc < 0:
        res.update(cls="CRASH", kind=f"signal {-rc}", detail=f"killed by signal {-rc}: {err[-300:]}")
        return res
    if rc == 1:
        if errors:
            msg = errors[0]
            res.update(cls="REFUSED", kind=normalise(msg), detail=msg)
        else:
            res.update(cls="CRASH", kind="exit 1 without a message", detail=err[-300:])
        return res
    if rc not in (0, 4):
        res.update(cls="CRASH", kind=f"exit {rc}", detail=err[-500:])
        return res
    try:
        with open(summ) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        res.update(cls="CRASH", kind="no summary", detail=f"exit {rc} but the summary is unreadable: {e}")
        return res
    dia = s.get("dialect", {}).get("name")
    if dia and dia != "linuxcnc":
        res["notes"].append(f"read as {dia}: {s['dialect'].get('reason')}")
    res["summary"] = {k: v for k, v in s.items() if k != "blocks"}
    nan_in_summary = any(isinstance(v, float) and not math.isfinite(v) for v in res["summary"].values())
    if not os.path.exists(out):
        res.update(cls="CRASH", kind="no setpoints", detail=f"exit {rc} but {out} is missing")
        return res
    worst, own_viol, nan = (None, [], False)
    if own:
        worst, own_viol, nan = own_check(out, case["limits"])
    else:
        with open(out, "rb") as f:
            low = f.read().lower()
        nan = b"nan" in low or b"inf" in low
    if nan or nan_in_summary:
        res.update(cls="CRASH", kind="NaN or inf in the output", detail="NaN or inf in the setpoints or summary")
        return res
    if worst == "skipped":
        res["notes"].append(f"own check skipped: {s.get('setpoints')} setpoints")
        worst = None
    res["own"] = worst
    est = case.get("estimated_time_s", 0)
    crawl = None
    if s.get("total_time_s", 0) > 10 * est + 30:
        crawl = (f"crawl: {s.get('total_time_s')} s of motion against ~{est:.1f} s estimated "
                 f"({s.get('setpoints')} setpoints); slowest block {slowest_block(s)}")
    if rc == 4 or not s.get("passed", False):
        fails = s.get("failures", [])
        # the block where the failing quantity is worst, for the kind
        btype = worst_block_type(s, fails)
        kind = "; ".join(normalise(f) for f in fails) + (f" [{btype}]" if btype else "")
        if rc == 0:
            kind = "exit 0 but not passed: " + kind
        if own and worst is not None:
            q = quantity_of(fails)
            if q and worst[q][0] <= 1 + OWN_CHECK_SLACK:
                kind += f" (own check: {q} ratio {worst[q][0]:.4f}: false alarm?)"
        res.update(cls="VIOLATION", kind=kind, detail="; ".join(fails))
        return res
    if own_viol:
        q, ax, k, r = max(own_viol, key=lambda v: v[3])
        res.update(cls="VIOLATION", kind=f"own check: {q} of axis {ax} above the limit (Kontur's check passed)",
                   detail=f"{len(own_viol)} setpoints; worst {q} of axis {ax} at setpoint {k}: {r:.4f} of the limit; "
                          f"Kontur reports {q} ratio {s.get('max_' + q + '_ratio')}")
        return res
    if crawl:
        # a motion that crawls (at 1e-16 mm/s near a cusp, say) is a hang to the user
        res.update(cls="HANG", kind="crawl: motion far longer than the estimate", detail=crawl)
        return res
    res.update(cls="PASS", kind="PASS", detail="")
    return res


def slowest_block(s):
    bl = [b for b in s.get("blocks", []) if b.get("t_start_s") is not None]
    if not bl:
        return "?"
    b = max(bl, key=lambda b: b["t_end_s"] - b["t_start_s"])
    return (f"line {b['line']} {b['type']} {b.get('length_mm', 0):.6g} mm at {b.get('feed_mm_s', 0):.6g} mm/s "
            f"in {b['t_end_s'] - b['t_start_s']:.6g} s")


def quantity_of(fails):
    for f in fails:
        for q in ("velocity", "acceleration", "jerk"):
            if f.startswith(q) or f" {q} " in f:
                return q
    return None


def worst_block_type(s, fails):
    blocks = s.get("blocks", [])
    q = quantity_of(fails)
    key = f"max_{q}_ratio" if q else None
    if key is None:
        for f in fails:
            if "chord" in f:
                key = "max_chord_error_mm"
            elif "path" in f or "off" in f:
                key = "max_path_error_mm"
    if key is None or not blocks:
        return None
    b = max(blocks, key=lambda b: b.get(key) or 0)
    return b.get("type")


def repro(res, kontur):
    d = f"/tmp/kontur_case_{res['seed']}"
    m = "machine.ini" if os.path.exists(os.path.join(res["dir"], "machine.ini")) else "machine.toml"
    return (f"/usr/bin/python3 tests/property/generate.py --seed {res['seed']} --out {d} && "
            f"{kontur} run {d}/program.ngc --machine {d}/{m} -o {d}/out.csv --summary {d}/s.json")


def shrink(seed, kontur, timeout, keep):
    d = tempfile.mkdtemp(prefix=f"kontur_shrink_{seed}_")
    first = run_case(seed, kontur, timeout, d)
    print(f"seed {seed}: {first['cls']}: {first['kind']}")
    if first["cls"] == "PASS":
        print("nothing to shrink")
        return 0
    target = (first["cls"], first["kind"])
    with open(os.path.join(d, "program.ngc")) as f:
        lines = f.read().splitlines()
    tries = 0

    def same(cand):
        nonlocal tries
        tries += 1
        r = run_case(seed, kontur, timeout, d, program_text="\n".join(cand) + "\n")
        return (r["cls"], r["kind"]) == target

    n = 2
    while len(lines) >= 2:
        chunk = max(1, len(lines) // n)
        removed = False
        i = 0
        while i < len(lines):
            cand = lines[:i] + lines[i + chunk:]
            if cand and same(cand):
                lines = cand
                removed = True
                print(f"  {len(lines)} lines ({tries} runs)", file=sys.stderr)
            else:
                i += chunk
        if not removed:
            if chunk == 1:
                break
            n = min(n * 2, len(lines))
        else:
            n = max(n - 1, 2)
    text = "\n".join(lines) + "\n"
    final = run_case(seed, kontur, timeout, d, program_text=text)
    print(f"shrunk to {len(lines)} lines in {tries} runs: {final['cls']}: {final['kind']}")
    print(f"  {final['detail']}")
    print("--- program.ngc")
    print(text, end="")
    mname = "machine.ini" if os.path.exists(os.path.join(d, "machine.ini")) else "machine.toml"
    print(f"--- {mname}")
    with open(os.path.join(d, mname)) as f:
        print(f.read())
    if keep:
        dst = os.path.join(keep, f"shrunk_{seed}")
        shutil.rmtree(dst, ignore_errors=True)
        shutil.copytree(d, dst)
        print(f"kept in {dst}")
    shutil.rmtree(d, ignore_errors=True)
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--first", type=int, default=1)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per case before it is a HANG")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--kontur", default=os.path.join(ROOT, "build", "bin", "kontur"))
    ap.add_argument("--keep", help="copy the folders of failing and refused cases here")
    ap.add_argument("--no-own-check", action="store_true", help="skip the runner's own check of the setpoints")
    ap.add_argument("--shrink", type=int, metavar="SEED", help="shrink the program of this seed by deleting lines")
    ap.add_argument("--json", help="write every case's result here")
    ap.add_argument("--quiet", action="store_true", help="only failures and the summary line")
    a = ap.parse_args(argv)
    kontur = os.path.abspath(a.kontur)
    if not os.access(kontur, os.X_OK):
        print(f"property: {kontur} is not an executable", file=sys.stderr)
        return 2
    if a.shrink is not None:
        return shrink(a.shrink, kontur, a.timeout, a.keep)

    seeds = range(a.first, a.first + a.count)
    results = []
    t0 = time.monotonic()

    def one(seed):
        r = run_case(seed, kontur, a.timeout, own=not a.no_own_check)
        if a.keep and r["cls"] != "PASS":
            dst = os.path.join(a.keep, f"seed_{seed}")
            shutil.rmtree(dst, ignore_errors=True)
            shutil.copytree(r["dir"], dst, ignore=shutil.ignore_patterns("out.csv"))
        shutil.rmtree(r["dir"], ignore_errors=True)
        return r

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        for r in ex.map(one, seeds):
            results.append(r)
            if r["cls"] != "PASS":
                print(f"seed {r['seed']}: {r['cls']}: {r['detail']}")
                print(f"  kind: {r['kind']}")
                print(f"  elements: {' '.join(r['elements'])}")
                print(f"  reproduce: {repro(r, kontur)}")
            elif not a.quiet:
                print(f"seed {r['seed']}: PASS ({r['seconds']:.2f} s)")
            for note in r["notes"]:
                print(f"seed {r['seed']}: note: {note}")
            sys.stdout.flush()
    counts = {c: sum(1 for r in results if r["cls"] == c) for c in ("PASS", "REFUSED", "VIOLATION", "CRASH", "HANG")}
    kinds = {}
    for r in results:
        if r["cls"] != "PASS":
            kinds.setdefault((r["cls"], r["kind"]), []).append(r["seed"])
    if kinds:
        print("kinds:")
        for (cls, kind), ss in sorted(kinds.items(), key=lambda kv: (kv[0][0], -len(kv[1]))):
            print(f"  {cls:9} {len(ss):4}  {kind}  (seeds {' '.join(map(str, ss[:8]))}{' ...' if len(ss) > 8 else ''})")
    notes = sum(1 for r in results if r["notes"])
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{k: v for k, v in r.items() if k not in ("dir",)} for r in results], f, indent=1)
    slow = max((r.get("seconds", 0) for r in results), default=0)
    print(f"property: {len(results)} cases, {counts['PASS']} passed, {counts['REFUSED']} refused, "
          f"{counts['VIOLATION']} violations, {counts['CRASH']} crashes, {counts['HANG']} hangs"
          f" ({notes} notes; {time.monotonic() - t0:.1f} s, slowest case {slow:.2f} s)")
    return 1 if any(counts[c] for c in FAILING) else 0


if __name__ == "__main__":
    sys.exit(main())
