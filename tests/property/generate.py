#!/usr/bin/env python3
"""Seeded generator of valid part programs and random machines for Kontur's property test.

    generate.py --seed N --out DIR

writes, deterministically from the seed (Python's `random.Random(seed)`, no other source of
randomness):

    DIR/program.ngc             a valid LinuxCNC-dialect program: lines with reversals and zero
                                lengths, dense CAM-like line runs, arcs of 1 um .. 10 m radius in
                                G17/G18/G19 (I J K and R form, full circles, helices, P turns), G5,
                                G5.1, G5.2/G5.3 (L order, P weights 0.01..100, repeated points),
                                G6.2 (P rank, clamped K knots, R weights), CONIC blocks (ellipse,
                                parabola, hyperbola arcs in arbitrary planes), G93 inverse time,
                                G61/G61.1/G64 P Q, G4 dwells, canned cycles G81/G82/G83/G73;
    DIR/machine.toml            Kontur's TOML (80 %), or
    DIR/machine.ini             a LinuxCNC INI (20 %: mm or inch, [AXIS_X] / [AXIS_0] / [JOINT_n],
                                MAX_JERK or [KONTUR] JERK_TIME or LinuxCNC's default),
    DIR/case.json               the machine's limits in mm and s (for the runner's own check of
                                the setpoints) and what the case contains.

Servo periods 125 us .. 4 ms; velocity, acceleration and jerk per axis over a few decades,
sometimes jerk ~ A / T. The program's estimated machining time is kept within a budget so that a
case makes at most ~150,000 setpoints (lengths shrink to fit; feeds stay as drawn).

Python 3 standard library only.
"""
import argparse
import json
import math
import os
import random
import sys

INCH = 25.4


def fmt(v, digits=6):
    """A G-code / INI number: fixed point (no exponent), no trailing zeros, no '-0'."""
    s = f"{v:.{digits}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    if s in ("-0", ""):
        s = "0"
    return s


def rd(v):
    """The value a program line carries for v (what the reader will see)."""
    return float(fmt(v))


def log_uniform(rng, lo, hi):
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


# ---------------------------------------------------------------------------------------- machine

def gen_machine(rng):
    m = {}
    if rng.random() < 0.4:
        m["servo_period_s"] = rng.choice([125e-6, 250e-6, 500e-6, 1e-3, 2e-3, 4e-3])
    else:
        m["servo_period_s"] = round(log_uniform(rng, 125e-6, 4e-3) * 1e6) * 1e-6  # whole us
    T = m["servo_period_s"]
    axes = {}
    base_v = log_uniform(rng, 5, 2000)
    base_a = log_uniform(rng, 10, 50000)
    jerk_mode = rng.choice(["a_over_t", "free", "free", "jerk_time"])
    jerk_time = log_uniform(rng, 0.002, 0.5)
    for ax in "XYZ":
        # axes alike, or each its own over a decade or two
        spread = rng.choice([1, 1, 10, 100])
        v = base_v * log_uniform(rng, 1 / spread, 1) if spread > 1 else base_v
        a = base_a * log_uniform(rng, 1 / spread, 1) if spread > 1 else base_a
        if jerk_mode == "a_over_t":
            j = a / T * rng.uniform(0.9, 1.1)
        elif jerk_mode == "jerk_time":
            j = a / jerk_time
        else:
            j = a * log_uniform(rng, 1, 3000)
        axes[ax] = {"max_velocity": v, "max_acceleration": a, "max_jerk": j}
    m["axes"] = axes
    m["max_feed_mm_min"] = log_uniform(rng, 300, 60000)
    m["rapid_feed_mm_min"] = m["max_feed_mm_min"] * rng.choice([1, 1, 1.5, 3])
    m["chord_tolerance_mm"] = log_uniform(rng, 1e-4, 0.05)
    m["path_tolerance_mm"] = log_uniform(rng, 1e-3, 0.5)
    m["soft_limits"] = rng.random() < 0.2
    m["format"] = "ini" if rng.random() < 0.2 else "toml"
    m["dialect"] = rng.random() < 0.3  # name the dialect in the machine file (else detected)
    return m


def sig(v, n=6):
    """v rounded to n significant digits (machine files carry few)."""
    if v == 0:
        return 0.0
    return float(f"{v:.{n}g}")


def write_toml(m, path):
    L = [f'name = "property case"',
         f"max_feed_mm_min = {fmt(m['max_feed_mm_min'], 3)}",
         f"rapid_feed_mm_min = {fmt(m['rapid_feed_mm_min'], 3)}",
         f"chord_tolerance_mm = {fmt(m['chord_tolerance_mm'], 7)}",
         f"path_tolerance_mm = {fmt(m['path_tolerance_mm'], 6)}",
         f"servo_period_s = {fmt(m['servo_period_s'], 9)}"]
    if m["dialect"]:
        L.append('dialect = "linuxcnc"')
    L.append("")
    for ax, a in m["axes"].items():
        L.append(f"[axes.{ax}]")
        L.append(f"max_velocity = {fmt(a['max_velocity'], 4)}")
        L.append(f"max_acceleration = {fmt(a['max_acceleration'], 3)}")
        L.append(f"max_jerk = {fmt(a['max_jerk'], 1)}")
        if m["soft_limits"]:
            L.append("min_position = -1000000")
            L.append("max_position = 1000000")
        L.append("")
    with open(path, "w") as f:
        f.write("\n".join(L))
    # what Kontur will use, in mm and s, as written
    lim = {"servo_period_s": float(fmt(m["servo_period_s"], 9)),
           "max_feed_mm_s": float(fmt(m["max_feed_mm_min"], 3)) / 60,
           "rapid_feed_mm_s": float(fmt(m["rapid_feed_mm_min"], 3)) / 60,
           "chord_tolerance_mm": float(fmt(m["chord_tolerance_mm"], 7)),
           "axes": {ax: {"max_velocity": float(fmt(a["max_velocity"], 4)),
                         "max_acceleration": float(fmt(a["max_acceleration"], 3)),
                         "max_jerk": float(fmt(a["max_jerk"], 1))} for ax, a in m["axes"].items()}}
    return lim


def write_ini(m, rng, path):
    inch = rng.random() < 0.5
    unit = INCH if inch else 1.0
    style = rng.choice(["AXIS_X", "AXIS_0", "JOINT_n"])
    jerk_src = rng.choice(["MAX_JERK", "JERK_TIME", "default"])
    jerk_time = sig(log_uniform(rng, 0.002, 0.2), 3)
    T_ns = int(round(m["servo_period_s"] * 1e9))
    maxlin = sig(m["max_feed_mm_min"] / 60 / unit, 6)
    L = ["# LinuxCNC configuration generated by Kontur's property test", "[EMC]",
         "VERSION = 1.1", "MACHINE = property-case", "DEBUG = 0", "",
         "[DISPLAY]", "DISPLAY = axis", f"MAX_LINEAR_VELOCITY = {fmt(maxlin, 6)}", "",
         "[TASK]", "TASK = milltask", "CYCLE_TIME = 0.001", "",
         "[RS274NGC]", "PARAMETER_FILE = sim.var", "",
         "[EMCMOT]", "EMCMOT = motmod", "COMM_TIMEOUT = 1.0", f"SERVO_PERIOD = {T_ns}", "",
         "[TRAJ]", "AXES = 3", "COORDINATES = X Y Z", "HOME = 0 0 0",
         f"LINEAR_UNITS = {'inch' if inch else 'mm'}", "ANGULAR_UNITS = degree",
         f"DEFAULT_LINEAR_VELOCITY = {fmt(maxlin / 10, 6)}",
         f"MAX_LINEAR_VELOCITY = {fmt(maxlin, 6)}", ""]
    kontur = ["DIALECT = linuxcnc"] if m["dialect"] else []
    if jerk_src == "JERK_TIME":
        kontur.append(f"JERK_TIME = {fmt(jerk_time, 6)}")
    chord = None
    if rng.random() < 0.5:
        chord = sig(m["chord_tolerance_mm"] / unit, 3)
        kontur.append(f"CHORD_TOLERANCE = {fmt(chord, 9)}")
    if rng.random() < 0.3:
        kontur.append(f"PATH_TOLERANCE = {fmt(sig(m['path_tolerance_mm'] / unit, 3), 9)}")
    if kontur:
        L += ["[KONTUR]"] + kontur + [""]
    lim_axes = {}
    for i, (ax, a) in enumerate(m["axes"].items()):
        sec = {"AXIS_X": f"AXIS_{ax}", "AXIS_0": f"AXIS_{i}", "JOINT_n": f"JOINT_{i}"}[style]
        v = sig(a["max_velocity"] / unit, 5)
        acc = sig(a["max_acceleration"] / unit, 5)
        L += [f"[{sec}]", "TYPE = LINEAR", "HOME = 0.0", f"MAX_VELOCITY = {fmt(v, 9)}",
              f"MAX_ACCELERATION = {fmt(acc, 9)}"]
        if jerk_src == "MAX_JERK":
            jk = sig(a["max_jerk"] / unit, 6)
            L.append(f"MAX_JERK = {fmt(jk, 6)}")
            j_mm = jk * unit
        elif jerk_src == "JERK_TIME":
            j_mm = acc / float(fmt(jerk_time, 6)) * unit
        else:
            j_mm = acc / 0.01 * unit
        lim_axes[ax] = {"max_velocity": v * unit, "max_acceleration": acc * unit, "max_jerk": j_mm}
        if m["soft_limits"]:
            lim = 1e6 / unit * 0.99
            L += [f"MIN_LIMIT = {fmt(-lim, 3)}", f"MAX_LIMIT = {fmt(lim, 3)}"]
        L += ["FERROR = 0.050", "MIN_FERROR = 0.010", "HOME_SEQUENCE = 0", ""]
    L += ["[EMCIO]", "TOOL_TABLE = sim.tbl", ""]
    with open(path, "w") as f:
        f.write("\n".join(L))
    # what Kontur will use, in mm and s (docs/machine.md, "LinuxCNC INI")
    lim = {"servo_period_s": T_ns * 1e-9, "max_feed_mm_s": maxlin * unit, "rapid_feed_mm_s": maxlin * unit,
           "chord_tolerance_mm": chord * unit if chord is not None else 0.001, "axes": lim_axes,
           "ini": {"units": "inch" if inch else "mm", "sections": style, "jerk": jerk_src}}
    return lim


# ---------------------------------------------------------------------------------------- program

PLANES = {"G17": (0, 1, 2), "G18": (2, 0, 1), "G19": (1, 2, 0)}  # (a, b, normal), CCW about normal
OFFSET_WORD = {0: "I", 1: "J", 2: "K"}
AXIS_WORD = {0: "X", 1: "Y", 2: "Z"}


class Program:
    def __init__(self, rng, lim):
        self.rng = rng
        self.lim = lim
        self.lines = []
        self.pos = [0.0, 0.0, 0.0]
        self.T = lim["servo_period_s"]
        ax = lim["axes"].values()
        self.vmin = min(min(a["max_velocity"] for a in ax), lim["max_feed_mm_s"])
        self.amin = min(a["max_acceleration"] for a in ax)
        self.jmin = min(a["max_jerk"] for a in ax)
        self.rapid = min(min(a["max_velocity"] for a in ax), lim["rapid_feed_mm_s"])
        # machining-time budget [s]: at most ~150,000 setpoints, at most a minute
        self.budget = min(60.0, 150000 * self.T)
        self.time = 0.0
        self.feed = None  # mm/min in G94
        self.inverse = False
        self.plane = "G17"
        self.kinds = []
        self.far = 0.0

    # ---- helpers
    def emit(self, s):
        self.lines.append(s)

    def stop_time(self, v):
        """Time to start from rest to v and back (an upper estimate)."""
        a, j = self.amin, self.jmin
        return 2 * (v / a + a / j) + 4 * self.T

    def move_time(self, length, v):
        v = max(min(v, self.vmin), 1e-6)
        return length / v + self.stop_time(v)

    def curve_speed(self, v, r):
        """Path speed allowed on a curve of radius r (centripetal, its jerk, chord tolerance)."""
        r = max(r, 1e-9)
        caps = [v, self.vmin, math.sqrt(self.amin * r), (self.jmin * r * r) ** (1 / 3)]
        tol = self.lim["chord_tolerance_mm"]
        caps.append(math.sqrt(8 * r * tol) / self.T)
        return max(min(caps), 1e-6)

    def left(self):
        return self.budget - self.time

    def fit_length(self, want, v, share=0.35):
        """Largest length <= want whose move fits in `share` of the remaining budget."""
        v = max(min(v, self.vmin), 1e-6)
        avail = share * self.left() - self.stop_time(v)
        if avail <= 0:
            return min(want, 1e-3)
        return max(min(want, avail * v), 1e-3 if want >= 1e-3 else want)

    def pick_feed(self):
        return log_uniform(self.rng, 3, 20000)  # mm/min

    def set_feed_words(self, force=False):
        """F word for a G94 feed move (a new feed now and then)."""
        if self.feed is None or force or self.rng.random() < 0.3:
            self.feed = rd(self.pick_feed())
            return f" F{fmt(self.feed)}"
        return ""

    def xyz(self, p, axes=(0, 1, 2), only_changed=False):
        words = []
        for i in axes:
            if only_changed and rd(p[i]) == self.pos[i] and self.rng.random() < 0.7:
                continue
            words.append(f"{AXIS_WORD[i]}{fmt(p[i])}")
        return " ".join(words)

    def set_pos(self, p):
        self.pos = [rd(c) for c in p]

    def random_dir(self, dims=3):
        while True:
            d = [self.rng.gauss(0, 1) for _ in range(3)]
            if dims == 2:
                d[2] = 0.0
            n = math.sqrt(sum(c * c for c in d))
            if n > 1e-6:
                return [c / n for c in d]

    def length_scale(self):
        """1 um .. 10 m, log-uniform, with extra weight at both ends."""
        r = self.rng.random()
        if r < 0.1:
            return log_uniform(self.rng, 1e-3, 1e-2)
        if r < 0.15:
            return log_uniform(self.rng, 1000, 10000)
        return log_uniform(self.rng, 1e-2, 1000)

    def feed_v(self):
        """The path speed [mm/s] of the feed in force (G94)."""
        return (self.feed or 1000) / 60

    # ---- elements
    def header(self):
        self.emit("(Kontur property test case)")
        head = ["G21", "G90", "G94", "G17", "G40", "G49"] + (["G80"] if self.rng.random() < 0.3 else [])
        self.emit(" ".join(head) + (" G64" if self.rng.random() < 0.5 else ""))
        # start near 0 or far away (up to ~1e5 mm)
        if self.rng.random() < 0.4:
            far = log_uniform(self.rng, 100, 1e5)
            p = [self.rng.uniform(-far, far) for _ in range(3)]
            d = math.dist(p, self.pos)
            if self.move_time(d, self.rapid) < 0.3 * self.budget:
                self.emit(f"G0 {self.xyz(p)}")
                self.time += self.move_time(d, self.rapid)
                self.set_pos(p)
                self.far = max(abs(c) for c in p)
        self.emit(f"G1 F{fmt(rd(self.pick_feed()))}".replace("G1 ", ""))
        self.feed = float(self.lines[-1][1:])

    def el_lines(self):
        """Lines: random steps, exact reversals, zero lengths, G0 among them, G91 now and then."""
        self.kinds.append("lines")
        n = self.rng.randint(1, 8)
        for _ in range(n):
            r = self.rng.random()
            rapid = self.rng.random() < 0.15
            fw = "" if rapid else self.set_feed_words()
            back = getattr(self, "prev", None)
            if r < 0.15:
                p = list(self.pos)  # zero length
            elif r < 0.35 and back is not None and \
                    self.move_time(math.dist(back, self.pos), self.rapid if rapid else self.feed_v()) < 0.2 * self.left():
                p = list(back)  # reversal back to where we came from
            else:
                d = self.random_dir(2 if self.rng.random() < 0.3 else 3)
                v = self.rapid if rapid else self.feed_v()
                L = self.fit_length(self.length_scale(), v, 0.2)
                p = [self.pos[i] + L * d[i] for i in range(3)]
            length = math.dist(p, self.pos)
            v = self.rapid if rapid else self.feed_v()
            self.time += self.move_time(length, v)
            if self.rng.random() < 0.1 and not rapid:
                # incremental
                rel = [rd(p[i]) - self.pos[i] for i in range(3)]
                self.emit(f"G91 G1 X{fmt(rel[0])} Y{fmt(rel[1])} Z{fmt(rel[2])}{fw}")
                self.emit("G90")
                p = [self.pos[i] + rd(rel[i]) for i in range(3)]
            else:
                code = "G0" if rapid else "G1"
                words = self.xyz(p, only_changed=True) or f"X{fmt(p[0])}"
                self.emit(f"{code} {words}{fw}")
            self.prev = list(self.pos)
            self.pos = [rd(c) for c in p]

    def el_dense(self):
        """A CAM-like run of short lines along a wavy curve (smoothing within G64 P)."""
        self.kinds.append("dense")
        n = self.rng.randint(8, 50)
        step = log_uniform(self.rng, 0.005, 2.0)
        d = self.random_dir(2 if self.rng.random() < 0.6 else 3)
        e = self.random_dir()
        amp = step * log_uniform(self.rng, 0.1, 20)
        wl = step * self.rng.uniform(5, 40)
        start = list(self.pos)
        feedw = self.set_feed_words()
        v = self.feed_v()
        if self.move_time(n * step * 2, v) + n * self.stop_time(min(v, self.vmin)) * 0.2 > 0.4 * self.left():
            n = 3
        for k in range(1, n + 1):
            s = k * step
            w = amp * (math.sin(2 * math.pi * s / wl) if self.rng.random() < 0.95 else self.rng.uniform(-1, 1))
            p = [start[i] + s * d[i] + w * e[i] for i in range(3)]
            self.emit(f"G1 {self.xyz(p)}{feedw if k == 1 else ''}")
            self.time += self.move_time(math.dist(p, self.pos), v) * 0.3
            self.pos = [rd(c) for c in p]
        self.prev = None

    def el_arc(self, inverse=False):
        """G2/G3 in any plane: I J K or R form, 1 um .. 10 m radius, full circles, helices, P turns."""
        self.kinds.append("arc")
        plane = self.rng.choice(["G17", "G17", "G18", "G19"])
        a, b, nrm = PLANES[plane]
        pre = ""
        if plane != self.plane:
            pre = plane + " "
            self.plane = plane
        r_scale = self.rng.random()
        if r_scale < 0.12:
            r = log_uniform(self.rng, 1e-3, 1e-2)
        elif r_scale < 0.2:
            r = log_uniform(self.rng, 1000, 10000)
        else:
            r = log_uniform(self.rng, 1e-2, 500)
        cw = self.rng.random() < 0.5
        full = self.rng.random() < 0.2
        turns = 0
        if full:
            span = 2 * math.pi
            if self.rng.random() < 0.3:
                turns = self.rng.randint(2, 3)
        else:
            span = self.rng.choice([self.rng.uniform(0.001, 0.5), self.rng.uniform(0.5, 2 * math.pi - 0.01),
                                    math.pi / 2, math.pi])
        fw = "" if inverse else self.set_feed_words()
        helix = 0.0
        if self.rng.random() < 0.3:
            helix = self.rng.choice([-1, 1]) * r * log_uniform(self.rng, 0.01, 3)
        v = self.curve_speed(self.feed_v() if not inverse else 1000, r)
        length = math.hypot(r * (span + 2 * math.pi * max(turns - 1, 0)), helix)
        # shrink the radius until the arc fits the budget
        while self.move_time(length, v) > 0.35 * self.left() and r > 1e-3:
            r = max(r / 4, 1e-3)
            helix /= 4
            v = self.curve_speed(self.feed_v() if not inverse else 1000, r)
            length = math.hypot(r * (span + 2 * math.pi * max(turns - 1, 0)), helix)
        th0 = self.rng.uniform(0, 2 * math.pi)
        c = list(self.pos)
        c[a] = self.pos[a] - r * math.cos(th0)
        c[b] = self.pos[b] - r * math.sin(th0)
        c = [rd(x) for x in c]
        # the radius as the reader sees it: from the rounded centre
        r_eff = math.hypot(self.pos[a] - c[a], self.pos[b] - c[b])
        th1 = th0 + (-span if cw else span)
        end = list(self.pos)
        if full:
            end[a], end[b] = self.pos[a], self.pos[b]
        else:
            end[a] = c[a] + r_eff * math.cos(th1)
            end[b] = c[b] + r_eff * math.sin(th1)
        end[nrm] = self.pos[nrm] + helix
        end = [rd(x) for x in end]
        if math.dist(end, self.pos) < 2e-6 and not full:
            full = True  # a tiny arc whose end rounds onto its start: say so, as a full circle
            end = list(self.pos)
            end[nrm] = rd(self.pos[nrm] + helix)
        code = "G2" if cw else "G3"
        words = [f"{AXIS_WORD[a]}{fmt(end[a])}", f"{AXIS_WORD[b]}{fmt(end[b])}"]
        if helix != 0.0 or self.rng.random() < 0.3:
            words.append(f"{AXIS_WORD[nrm]}{fmt(end[nrm])}")
        use_r = (not full) and self.rng.random() < 0.25 and span < 2 * math.pi - 0.3 and r_eff > 0.01
        if use_r:
            words.append(f"R{fmt(r_eff if span <= math.pi else -r_eff)}")
        else:
            words.append(f"{OFFSET_WORD[a]}{fmt(c[a] - self.pos[a])}")
            words.append(f"{OFFSET_WORD[b]}{fmt(c[b] - self.pos[b])}")
        if turns:
            words.append(f"P{turns}")
        if inverse:
            t = self.move_time(length, v)
            words.append(f"F{fmt(max(60 / t, 0.001), 4)}")
        else:
            words.append(fw.strip())
        self.emit(pre + code + " " + " ".join(w for w in words if w))
        self.time += self.move_time(length, v)
        self.pos = end
        self.prev = None

    def ensure_g17(self):
        if self.plane != "G17":
            self.emit("G17")
            self.plane = "G17"

    def spline_scale(self):
        self.pending_fw = self.set_feed_words()  # the feed first: the length fits the budget at it
        s = self.length_scale()
        v = self.curve_speed(self.feed_v(), s / 4)
        while self.move_time(3 * s, v) > 0.3 * self.left() and s > 2e-3:
            s /= 4
            v = self.curve_speed(self.feed_v(), s / 4)
        self.time += self.move_time(3 * s, v)
        return max(s, 2e-3)

    def el_g5(self):
        """Cubic Bezier chains: repeated control points (I0 J0, P0 Q0), tangent continuation."""
        self.kinds.append("G5")
        self.ensure_g17()
        n = self.rng.randint(1, 4)
        s = self.spline_scale()
        for k in range(n):
            d = self.random_dir(2)
            end = [self.pos[0] + s * d[0], self.pos[1] + s * d[1], self.pos[2]]
            ij = [self.rng.uniform(-s, s), self.rng.uniform(-s, s)]
            pq = [self.rng.uniform(-s, s), self.rng.uniform(-s, s)]
            if self.rng.random() < 0.2:
                ij = [0, 0]
            if self.rng.random() < 0.2:
                pq = [0, 0]
            words = f"X{fmt(end[0])} Y{fmt(end[1])}"
            if k > 0 and self.rng.random() < 0.4:
                w = f"G5 {words} P{fmt(pq[0])} Q{fmt(pq[1])}"  # I J from the previous G5's tangent
            else:
                w = f"G5 {words} I{fmt(ij[0])} J{fmt(ij[1])} P{fmt(pq[0])} Q{fmt(pq[1])}"
            if k > 0 and rd(pq[0]) == 0 and rd(pq[1]) == 0 and "I" not in w:
                w = f"G5 {words} I{fmt(ij[0])} J{fmt(ij[1])} P{fmt(pq[0])} Q{fmt(pq[1])}"
            self.emit(w + (self.pending_fw if k == 0 else ""))
            self.pos = [rd(end[0]), rd(end[1]), self.pos[2]]
        self.prev = None

    def el_g51(self):
        self.kinds.append("G5.1")
        self.ensure_g17()
        s = self.spline_scale()
        d = self.random_dir(2)
        end = [self.pos[0] + s * d[0], self.pos[1] + s * d[1], self.pos[2]]
        while True:
            ij = [rd(self.rng.uniform(-s, s)), rd(self.rng.uniform(-s, s))]
            if ij != [0.0, 0.0]:
                break
        self.emit(f"G5.1 X{fmt(end[0])} Y{fmt(end[1])} I{fmt(ij[0])} J{fmt(ij[1])}{self.pending_fw}")
        self.pos = [rd(end[0]), rd(end[1]), self.pos[2]]
        self.prev = None

    def weight(self):
        r = self.rng.random()
        if r < 0.4:
            return 1.0
        if r < 0.5:
            return self.rng.choice([0.01, 100.0])
        return rd(log_uniform(self.rng, 0.01, 100))

    def control_points(self, n, s, dims):
        pts = []
        p = list(self.pos)
        for _ in range(n):
            if pts and self.rng.random() < 0.15:
                pts.append(list(pts[-1]))  # repeated point
                continue
            d = self.random_dir(dims)
            step = s * self.rng.uniform(0.2, 1.0)
            p = [p[i] + step * d[i] for i in range(3)]
            pts.append([rd(c) for c in p])
        return pts

    def el_g52(self):
        """LinuxCNC NURBS G5.2 L order, X Y P weight, G5.3."""
        self.kinds.append("G5.2")
        self.ensure_g17()
        s = self.spline_scale()
        order = self.rng.choice([2, 3, 3, 3, 4, 4, 5, 6, 10])
        n = self.rng.randint(max(order - 1, 1), max(order - 1, 1) + 6)  # points after the start
        pts = self.control_points(n, s, 2)
        first = f"G5.2 P{fmt(self.weight())}"
        if order != 3 or self.rng.random() < 0.5:
            first += f" L{order}"
        first += self.pending_fw
        self.emit(first)
        for p in pts:
            self.emit(f"    X{fmt(p[0])} Y{fmt(p[1])} P{fmt(self.weight())}")
        self.emit("G5.3")
        self.pos = [pts[-1][0], pts[-1][1], self.pos[2]]
        self.prev = None

    def el_g62(self, inverse=False):
        """G6.2 P rank, K knots (clamped, inner multiplicity < rank), R weights."""
        self.kinds.append("G6.2")
        s = self.spline_scale()
        rank = self.rng.choice([2, 3, 4, 4, 4, 5, 6, 10])
        n = self.rng.randint(rank, rank + 6)  # control points with the start
        pts = [list(self.pos)] + self.control_points(n - 1, s, 3 if self.rng.random() < 0.5 else 2)
        # knots: clamped; inner ones non-decreasing, each repeated at most rank - 1 times
        k0 = self.rng.choice([0.0, 0.0, rd(self.rng.uniform(-10, 10))])
        width = self.rng.choice([1.0, float(n - rank + 1), rd(log_uniform(self.rng, 0.01, 1000))])
        inner_count = n - rank
        inner = []
        while len(inner) < inner_count:
            u = rd(k0 + width * self.rng.uniform(0.02, 0.98))
            if u <= k0 or u >= k0 + width:
                continue
            inner.append(u)
            while len(inner) < inner_count and self.rng.random() < 0.25:
                inner.append(u)
        inner.sort()
        # enforce multiplicity <= rank - 1
        ok = []
        for u in inner:
            if ok.count(u) < rank - 1:
                ok.append(u)
        while len(ok) < inner_count:  # rare: fill with distinct values
            u = rd(k0 + width * self.rng.uniform(0.02, 0.98))
            if k0 < u < k0 + width and ok.count(u) < rank - 1:
                ok.append(u)
                ok.sort()
        kend = rd(k0 + width)
        knots = [k0] * rank + ok + [kend] * rank
        assert len(knots) == n + rank
        code = self.rng.choice(["G6.2", "G06.2"])
        w0 = self.weight()
        p0 = pts[0]
        first = f"{code} P{rank} K{fmt(knots[0])} X{fmt(p0[0])} Y{fmt(p0[1])} Z{fmt(p0[2])}"
        if w0 != 1.0 or self.rng.random() < 0.3:
            first += f" R{fmt(w0)}"
        first += self.pending_fw
        self.emit(first)
        for i in range(1, n):
            w = self.weight()
            line = f"K{fmt(knots[i])} {self.xyz(pts[i])}"
            if w != 1.0:
                line += f" R{fmt(w)}"
            self.emit(line)
        bare = self.rng.random() < 0.6
        for i in range(n, n + rank):
            self.emit(("" if bare else "G6.2 ") + f"K{fmt(knots[i])}")
        self.pos = list(pts[-1])
        self.prev = None

    def el_conic(self):
        """CONIC through five points of an ellipse, parabola or hyperbola arc in a random plane."""
        self.kinds.append("CONIC")
        kind = self.rng.choice(["ellipse", "ellipse", "parabola", "hyperbola"])
        fw = self.set_feed_words()
        s = log_uniform(self.rng, 0.5, 5000)
        v = self.curve_speed(self.feed_v(), s / 10)
        while self.move_time(4 * s, v) > 0.35 * self.left() and s > 0.5:
            s /= 4
            v = self.curve_speed(self.feed_v(), s / 10)
        s = max(s, 0.5)
        self.time += self.move_time(4 * s, v)
        if kind == "ellipse":
            a, b = s, s * self.rng.uniform(0.1, 1.0)
            t0 = self.rng.uniform(0, 2 * math.pi)
            span = self.rng.uniform(0.6, 1.8 * math.pi)
            ts = [t0 + span * k / 4 for k in range(5)]
            pts2 = [(a * math.cos(t), b * math.sin(t)) for t in ts]
        elif kind == "parabola":
            p = s * self.rng.uniform(0.1, 1.0)
            t0 = self.rng.uniform(-2, 1)
            span = self.rng.uniform(1, 3)
            ts = [t0 + span * k / 4 for k in range(5)]
            pts2 = [(p * t * t, 2 * p * t) for t in ts]
        else:
            a, b = s, s * self.rng.uniform(0.2, 2.0)
            t0 = self.rng.uniform(-1.5, 0.5)
            span = self.rng.uniform(0.8, 2.5)
            ts = [t0 + span * k / 4 for k in range(5)]
            pts2 = [(a * math.cosh(t), b * math.sinh(t)) for t in ts]
        # plane: principal or arbitrary
        if self.rng.random() < 0.5:
            ax = self.rng.choice([(0, 1), (1, 2), (2, 0)])
            u = [0.0, 0.0, 0.0]
            w = [0.0, 0.0, 0.0]
            u[ax[0]] = 1.0
            w[ax[1]] = 1.0
            ang = self.rng.uniform(0, 2 * math.pi)
            u, w = ([math.cos(ang) * u[i] + math.sin(ang) * w[i] for i in range(3)],
                    [-math.sin(ang) * u[i] + math.cos(ang) * w[i] for i in range(3)])
        else:
            u = self.random_dir()
            t = self.random_dir()
            d = sum(u[i] * t[i] for i in range(3))
            w = [t[i] - d * u[i] for i in range(3)]
            nw = math.sqrt(sum(c * c for c in w))
            w = [c / nw for c in w]
        x0 = pts2[0]
        P = [[self.pos[i] + (q[0] - x0[0]) * u[i] + (q[1] - x0[1]) * w[i] for i in range(3)] for q in pts2]
        P = [[rd(c) for c in q] for q in P]
        P[0] = list(self.pos)
        words = f"CONIC X{fmt(P[4][0])} Y{fmt(P[4][1])} Z{fmt(P[4][2])}"
        for k in (1, 2, 3):
            q = P[k]
            words += f" I{k}={fmt(q[0])} J{k}={fmt(q[1])} K{k}={fmt(q[2])}"
        self.emit(words + fw)
        self.pos = P[4]
        self.prev = None

    def el_g93(self):
        """Inverse time: lines and arcs, each with its own F; back to G94 with a feed."""
        self.kinds.append("G93")
        self.emit("G93")
        self.inverse = True
        for _ in range(self.rng.randint(1, 5)):
            if self.rng.random() < 0.7:
                d = self.random_dir()
                v = log_uniform(self.rng, 0.1, 300)
                L = self.fit_length(self.length_scale(), v, 0.2)
                p = [self.pos[i] + L * d[i] for i in range(3)]
                p = [rd(c) for c in p]
                L = math.dist(p, self.pos)
                if L == 0:
                    continue
                t = L / v
                self.emit(f"G1 {self.xyz(p)} F{fmt(max(60 / t, 0.001), 4)}")
                self.time += self.move_time(L, v)
                self.pos = p
            else:
                self.el_arc(inverse=True)
        self.emit("G94")
        self.inverse = False
        self.feed = None
        self.prev = None

    def el_dwell(self):
        self.kinds.append("G4")
        p = self.rng.choice([0, rd(log_uniform(self.rng, 0.001, 0.5))])
        p = min(p, max(self.left() * 0.1, 0))
        self.emit(f"G4 P{fmt(p, 3)}")
        self.time += p

    def el_mode(self):
        self.kinds.append("G61/G64")
        r = self.rng.random()
        if r < 0.2:
            self.emit("G61")
        elif r < 0.3:
            self.emit("G61.1")
        elif r < 0.45:
            self.emit("G64")
        elif r < 0.8:
            self.emit(f"G64 P{fmt(log_uniform(self.rng, 1e-4, 1), 4)}")
        else:
            p = log_uniform(self.rng, 1e-4, 1)
            self.emit(f"G64 P{fmt(p, 4)} Q{fmt(p * self.rng.uniform(0.1, 3), 4)}")

    def el_cycle(self):
        """Drilling cycles G81 / G82 / G83 / G73 over a few holes, G98 / G99, then G80."""
        self.kinds.append("cycle")
        self.ensure_g17()
        code = self.rng.choice(["G81", "G83", "G83", "G82", "G73"])
        ret = self.rng.choice(["G98", "G99"])
        depth = log_uniform(self.rng, 0.01, 50)
        clearance = log_uniform(self.rng, 0.001, 10)
        r_plane = self.pos[2] - self.rng.choice([0.0, clearance, -clearance])
        r_plane = rd(r_plane)
        z = rd(r_plane - depth)
        if z >= r_plane:
            z = rd(r_plane - 0.01)
        words = f"{ret} {code}"
        holes = self.rng.randint(1, 4)
        spacing = log_uniform(self.rng, 0.01, 100)
        old_feed = self.feed
        feedw = self.set_feed_words(force=self.rng.random() < 0.5)
        v = self.feed_v()
        peck = ""
        npeck = 1
        if code in ("G83", "G73"):
            q = depth * log_uniform(self.rng, 0.05, 2)
            q = max(rd(q), 0.001)
            npeck = math.ceil(depth / q)
            peck = f" Q{fmt(q)}"
        dwell = ""
        if code == "G82":
            dwell = f" P{fmt(rd(log_uniform(self.rng, 0.001, 0.3)), 3)}"
        per_hole = self.move_time(depth * 2, v) + npeck * 2 * self.stop_time(min(v, self.vmin)) + \
            self.move_time(spacing, self.rapid) + self.move_time(clearance * 2, self.rapid)
        while holes > 1 and per_hole * holes > 0.4 * self.left():
            holes -= 1
        if per_hole > 0.4 * self.left() or npeck > 60:
            self.feed = old_feed  # its F word is not written
            return
        # (the estimate also counts each later peck's feed through the clearance a G83 / G73
        # re-approach leaves above the previous depth, 0.010 in as in LinuxCNC: seed 41406's 14 um
        # hole in 1 um pecks at 3.2 mm/min fed 14 x 0.255 mm per hole, 269 s against 19 s
        # estimated; the choices above keep the estimate without it, so the programs of every
        # seed stay as they were)
        clearance_feed = (npeck - 1) * 0.254 if code in ("G83", "G73") else 0.0
        self.time += (per_hole + self.move_time(clearance_feed, v)) * holes
        x, y = self.pos[0], self.pos[1]
        for k in range(holes):
            d = self.random_dir(2)
            x, y = rd(x + spacing * d[0]), rd(y + spacing * d[1])
            if k == 0:
                self.emit(f"{words} X{fmt(x)} Y{fmt(y)} Z{fmt(z)} R{fmt(r_plane)}{peck}{dwell}{feedw}")
            else:
                self.emit(f"X{fmt(x)} Y{fmt(y)}")
        self.emit("G80")
        # where the cycle leaves the tool
        if ret == "G98":
            endz = max(self.pos[2], r_plane)
        else:
            endz = r_plane
        self.pos = [x, y, endz]
        self.prev = None

    def build(self):
        self.header()
        n = self.rng.randint(3, 14)
        table = [(self.el_lines, 20), (self.el_arc, 16), (self.el_dense, 6), (self.el_g5, 6),
                 (self.el_g51, 4), (self.el_g52, 7), (self.el_g62, 7), (self.el_conic, 6),
                 (self.el_g93, 5), (self.el_dwell, 4), (self.el_mode, 6), (self.el_cycle, 6)]
        total = sum(w for _, w in table)
        for _ in range(n):
            if self.left() < 0.05 * self.budget:
                break
            r = self.rng.uniform(0, total)
            for fn, w in table:
                r -= w
                if r <= 0:
                    fn()
                    break
        if self.rng.random() < 0.5:
            self.emit(f"G0 Z{fmt(self.pos[2] + 1)}")
        self.emit("M2")
        return "\n".join(self.lines) + "\n"


def generate(seed, out):
    rng = random.Random(seed)
    m = gen_machine(rng)
    os.makedirs(out, exist_ok=True)
    for name in ("machine.toml", "machine.ini"):
        try:
            os.remove(os.path.join(out, name))
        except FileNotFoundError:
            pass
    if m["format"] == "ini":
        machine = os.path.join(out, "machine.ini")
        lim = write_ini(m, rng, machine)
    else:
        machine = os.path.join(out, "machine.toml")
        lim = write_toml(m, machine)
    prog = Program(rng, lim)
    text = prog.build()
    program = os.path.join(out, "program.ngc")
    with open(program, "w") as f:
        f.write(text)
    case = {"seed": seed, "machine_file": os.path.basename(machine), "limits": lim,
            "estimated_time_s": prog.time, "budget_s": prog.budget, "elements": prog.kinds}
    with open(os.path.join(out, "case.json"), "w") as f:
        json.dump(case, f, indent=1)
    return program, machine


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--out", required=True, help="folder for program.ngc, machine.toml|machine.ini, case.json")
    a = ap.parse_args(argv)
    program, machine = generate(a.seed, a.out)
    print(program)
    print(machine)
    return 0


if __name__ == "__main__":
    sys.exit(main())
